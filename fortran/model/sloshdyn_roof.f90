!> Loads of a sloshing wave on the roof of a cylindrical tank whose freeboard is insufficient
!> (the free, unconstrained wave's height d at the wall exceeds the freeboard f at the wall), for
!> flat, cone and dome roofs. Malhotra (Earthquake Spectra 21(4), 2005; Structural Engineering
!> International 16(3), 2006, for cone and dome roofs) names the two effects, an upward load on
!> the roof and an increase of the impulsive mass by the roof's constraint; his formulas were not
!> available to this project, so both are derived here from the free first-mode wave
!> eta(r, a) = d J1(xi r/R)/J1(xi) cos(a) (docs/model.md, "Roof loads"):
!>
!> - roof_head = d - f: the equivalent hydrostatic head at the wall;
!> - the uplift: the hydrostatic pressure rho g (eta - z_roof(r)) of the part of the free wave
!>   that would rise above the roof, integrated over the roof's horizontal projection (the
!>   vertical component of a pressure on any roof surface): in a in closed form, in r by
!>   Gauss-Legendre;
!> - the confined convective mass, phi m_c: the horizontal sloshing displacement of the liquid
!>   is the first moment of the surface elevation (integral of x eta dA; the pendulum's
!>   m l sin(theta), docs/model.md), so the roof, which cuts the wave at z_roof, takes away the
!>   share phi = integral of x (eta - z_roof)+ dA over the crest's integral of x eta dA
!>   = pi d R^3/(2 xi^2) of the convective mass's momentum relative to the tank: that share
!>   moves with the tank, i.e. is impulsive (the code provision restricted sloshing asks for:
!>   the constrained convective mass as additional impulsive mass).
!>
!> A rectangular tank (length L along the motion, width W) has a flat roof and the first mode's
!> free wave eta(x) = d sin(pi x/L), x from the centre: the same two loads in closed form
!> (rectangular_roof_loads).
!>
!> The roof at s = r/R above the still liquid, z_roof: flat f; cone f + R (1 - s) tan(alpha),
!> alpha the roof slope; dome (sphere of radius R_d) f + sqrt(R_d^2 - s^2 R^2) - sqrt(R_d^2 - R^2).
!> Geometries accepted (check_roof): the self-supporting roofs of API 650, cone slope up to 37
!> degrees (5.10.5), dome radius 0.8 D to 1.2 D (5.10.6).
module sloshdyn_roof
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, check_real
  use sloshdyn_text, only: num2str
  implicit none
  private
  public :: roof_loads, rectangular_roof_loads, check_roof

  !> the first root of J1' (the wave's shape; the paper's 1.84 rounds it)
  real(wp), parameter :: xi_exact = 1.8411837813406593_wp
  !> Gauss-Legendre nodes and weights on [-1, 1] (8 points), and the panels in r
  real(wp), parameter :: gauss_x(4) = [0.1834346424956498_wp, 0.5255324099163290_wp, &
                                       0.7966664774136267_wp, 0.9602898564975363_wp]
  real(wp), parameter :: gauss_w(4) = [0.3626837833783620_wp, 0.3137066458778873_wp, &
                                       0.2223810344533745_wp, 0.1012285362903763_wp]
  integer, parameter :: panels = 64
  !> API 650's self-supporting roofs: cone slope <= 37 degrees (5.10.5), dome radius in
  !> [0.8 D, 1.2 D] (5.10.6)
  real(wp), parameter :: max_cone_slope = 37, min_dome_radius = 0.8_wp, &
                         max_dome_radius = 1.2_wp
  !> A dome radius of exactly 0.8 D or 1.2 D is allowed: the bounds 0.8 (2 R) and 1.2 (2 R)
  !> carry the round-off of their product (0.8 x 30 = 24.000000000000004)
  real(wp), parameter :: bound_round_off = 1.0e-12_wp

contains

  !> The roof's geometry: roof_slope [degrees] of a cone (0: not a cone) and roof_radius [m] of a
  !> dome (0: not a dome), at most one given; neither: a flat roof.
  pure subroutine check_roof(radius, roof_slope, roof_radius, status, message)
    real(wp), intent(in) :: radius, roof_slope, roof_radius
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    call check_real('roof_slope', roof_slope, 0.0_wp, max_cone_slope, .false., .false., &
                    'a cone roof''s slope must lie in (0, 37] degrees (API 650 5.10.5; 0: no '// &
                    'cone)', status, message)
    if (roof_radius /= 0) &
      call check_real('roof_radius', roof_radius, min_dome_radius*2*radius*(1 - bound_round_off), &
                      max_dome_radius*2*radius*(1 + bound_round_off), .false., .false., &
                      'a dome roof''s radius must lie in [0.8 D, 1.2 D] = ['// &
                      num2str(min_dome_radius*2*radius)//', '// &
                      num2str(max_dome_radius*2*radius)//'] m (API 650 5.10.6; 0: no dome)', &
                      status, message)
    if (status == SD_OK .and. roof_slope > 0 .and. roof_radius > 0) then
      status = SD_BAD_INPUT
      message = 'roof_slope = '//num2str(roof_slope)//' and roof_radius = '// &
                num2str(roof_radius)//': give at most one (a cone roof by its slope [degrees] '// &
                'or a dome roof by its radius [m]; neither: a flat roof)'
    end if
  end subroutine check_roof

  !> head = max(d - f, 0) [m], uplift [N] and the confined convective mass [kg] (0 when d <= f)
  !> of the roof (check_roof's roof_slope, roof_radius) of a tank of radius R whose roof meets
  !> the wall at the freeboard f above the still liquid (density rho, gravity g, convective
  !> mass m_c) under a free wave of height d at the wall.
  pure subroutine roof_loads(radius, freeboard, roof_slope, roof_radius, wave_height, density, &
                             gravity, convective_mass, head, uplift, confined_mass, status, &
                             message)
    real(wp), intent(in) :: radius, freeboard, roof_slope, roof_radius, wave_height, density, &
                            gravity, convective_mass
    real(wp), intent(out) :: head, uplift, confined_mass
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), parameter :: big = huge(1.0_wp)
    real(wp) :: s0, width, centre, s, weight, force, moment, ring_force, ring_moment
    integer :: panel, k, side

    status = SD_OK
    message = ''
    head = 0
    uplift = 0
    confined_mass = 0
    call check_real('radius', radius, 0.0_wp, big, .true., .true., &
                    'the roof method needs a tank radius > 0 [m]', status, message)
    call check_real('freeboard', freeboard, 0.0_wp, big, .true., .true., &
                    'the roof method needs a freeboard > 0 [m]', status, message)
    call check_real('wave_height', wave_height, 0.0_wp, big, .false., .true., &
                    'the free wave height must be finite and >= 0 [m]', status, message)
    call check_roof(radius, roof_slope, roof_radius, status, message)
    if (status /= SD_OK .or. wave_height <= freeboard) return
    head = wave_height - freeboard
    ! eta > z_roof for s in (s0, 1]: the wave's amplitude rises and the roof falls toward the wall
    s0 = wave_meets_roof()
    width = (1 - s0)/panels
    force = 0
    moment = 0
    do panel = 1, panels
      centre = s0 + (panel - 0.5_wp)*width
      do k = 1, size(gauss_x)
        do side = -1, 1, 2
          s = centre + side*gauss_x(k)*width/2
          weight = gauss_w(k)*width/2
          call ring(s, ring_force, ring_moment)
          force = force + weight*ring_force
          moment = moment + weight*ring_moment
        end do
      end do
    end do
    uplift = density*gravity*radius**2*force
    ! the crest's first moment, integral of x eta over eta > 0: pi d R^3/(2 xi^2) (J2(xi) = J1(xi)/xi)
    confined_mass = convective_mass*moment/(pi*wave_height/(2*xi_exact**2))

  contains

    !> The wave's amplitude at s = r/R.
    pure real(wp) function amplitude(s_point)
      real(wp), intent(in) :: s_point
      amplitude = wave_height*bessel_j1(xi_exact*s_point)/bessel_j1(xi_exact)
    end function amplitude

    !> The roof's height above the still liquid at s = r/R.
    pure real(wp) function roof_height(s_point)
      real(wp), intent(in) :: s_point
      if (roof_slope > 0) then
        roof_height = freeboard + radius*(1 - s_point)*tan(roof_slope*pi/180)
      else if (roof_radius > 0) then
        roof_height = freeboard + sqrt(roof_radius**2 - (s_point*radius)**2) - &
                      sqrt(roof_radius**2 - radius**2)
      else
        roof_height = freeboard
      end if
    end function roof_height

    !> At s, with A = eta's amplitude there, z the roof's height and alpha = acos(z/A) (A > z):
    !> the integral over a of (eta - z)+, times s, 2 (A sin(alpha) - z alpha) (the uplift), and
    !> of cos(a) (eta - z)+, times s^2, A (alpha + sin(alpha) cos(alpha)) - 2 z sin(alpha) (the
    !> first moment in x = r cos(a), over R^3); both 0 where A <= z.
    pure subroutine ring(s_point, ring_force, ring_moment)
      real(wp), intent(in) :: s_point
      real(wp), intent(out) :: ring_force, ring_moment
      real(wp) :: a, z, alpha
      a = amplitude(s_point)
      z = roof_height(s_point)
      ring_force = 0
      ring_moment = 0
      if (a <= z) return
      alpha = acos(z/a)
      ring_force = 2*(a*sin(alpha) - z*alpha)*s_point
      ring_moment = (a*(alpha + sin(alpha)*cos(alpha)) - 2*z*sin(alpha))*s_point**2
    end subroutine ring

    !> The s in [0, 1] where the amplitude meets the roof, by bisection (amplitude - roof rises
    !> from -z(0) < 0 to d - f > 0).
    pure real(wp) function wave_meets_roof() result(s_meet)
      real(wp) :: lo, hi
      integer :: i
      lo = 0
      hi = 1
      do i = 1, 60
        s_meet = (lo + hi)/2
        if (amplitude(s_meet) < roof_height(s_meet)) then
          lo = s_meet
        else
          hi = s_meet
        end if
      end do
      s_meet = (lo + hi)/2
    end function wave_meets_roof
  end subroutine roof_loads

  !> The same loads for a rectangular tank of length L (along the motion) and width W under a
  !> flat roof at the freeboard f, with the first mode's free wave eta(x) = d sin(k x), k = pi/L,
  !> x from the centre: where eta > f, x in (x0, L/2] with sin(k x0) = f/d,
  !>   uplift   = rho g W [d cos(k x0)/k - f (L/2 - x0)]
  !>   confined = m_c k^2/d [d (1 - sin(k x0))/k^2 + d x0 cos(k x0)/k - f (L^2/8 - x0^2/2)]
  !> (the crest's first moment, integral of x eta over 0 < x < L/2, is d/k^2).
  pure subroutine rectangular_roof_loads(length, width, freeboard, wave_height, density, &
                                         gravity, convective_mass, head, uplift, confined_mass, &
                                         status, message)
    real(wp), intent(in) :: length, width, freeboard, wave_height, density, gravity, &
                            convective_mass
    real(wp), intent(out) :: head, uplift, confined_mass
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: k, x0, d, f
    status = SD_OK
    message = ''
    head = 0
    uplift = 0
    confined_mass = 0
    call check_real('freeboard', freeboard, 0.0_wp, huge(1.0_wp), .true., .true., &
                    'the roof method needs a freeboard > 0 [m]', status, message)
    call check_real('wave_height', wave_height, 0.0_wp, huge(1.0_wp), .false., .true., &
                    'the free wave height must be finite and >= 0 [m]', status, message)
    if (status /= SD_OK .or. wave_height <= freeboard) return
    d = wave_height
    f = freeboard
    head = d - f
    k = pi/length
    x0 = asin(f/d)/k
    uplift = density*gravity*width*(d*cos(k*x0)/k - f*(length/2 - x0))
    confined_mass = convective_mass*k**2/d*(d*(1 - sin(k*x0))/k**2 + d*x0*cos(k*x0)/k - &
                                            f*(length**2/8 - x0**2/2))
  end subroutine rectangular_roof_loads
end module sloshdyn_roof
