!> Loads of a sloshing wave on a flat roof when the freeboard is insufficient (the free wave's
!> height d at the wall exceeds the freeboard f), from the free (unconstrained) wave:
!>
!> - the equivalent hydrostatic head at the wall, d - f, which the code provision for
!>   restricted sloshing asks the roof to be designed for (ASCE 7-10 15.7.6.1.2 c, to which
!>   API 650 E.7.2 and ACI 350.3 defer; this program's reading, see docs/model.md);
!> - the upward force on a flat roof: the hydrostatic pressure rho g (eta - f) of the part of
!>   the free first-mode wave eta(r, theta) = d J1(xi r/R)/J1(xi) cos(theta) that would rise
!>   above the roof, integrated over the roof (in theta in closed form, in r by Gauss-Legendre);
!> - the confined part of the convective mass, m_c (1 - f/d): the roof caps the wave, hence the
!>   sloshing displacement, at f/d of the free one; the rest of the convective mass moves with
!>   the tank and is added to the impulsive mass (the same provision).
!>
!> Not implemented: Malhotra's method (Earthquake Spectra 21(4), 2005, and the companion paper
!> for cone and dome roofs); only flat roofs.
module sloshdyn_roof
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, check_real
  implicit none
  private
  public :: roof_loads

  !> the first root of J1' (the wave's shape; the paper's 1.84 rounds it)
  real(wp), parameter :: xi_exact = 1.8411837813406593_wp
  !> Gauss-Legendre nodes and weights on [-1, 1] (8 points), and the panels in r
  real(wp), parameter :: gauss_x(4) = [0.1834346424956498_wp, 0.5255324099163290_wp, &
                                       0.7966664774136267_wp, 0.9602898564975363_wp]
  real(wp), parameter :: gauss_w(4) = [0.3626837833783620_wp, 0.3137066458778873_wp, &
                                       0.2223810344533745_wp, 0.1012285362903763_wp]
  integer, parameter :: panels = 64

contains

  !> head = max(d - f, 0) [m], uplift [N] and the confined convective mass [kg] (0 when d <= f)
  !> of a flat roof of radius R at the freeboard f above the still liquid (density rho,
  !> gravity g, convective mass m_c) under a free wave of height d at the wall.
  pure subroutine roof_loads(radius, freeboard, wave_height, density, gravity, &
                             convective_mass, head, uplift, confined_mass, status, message)
    real(wp), intent(in) :: radius, freeboard, wave_height, density, gravity, convective_mass
    real(wp), intent(out) :: head, uplift, confined_mass
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), parameter :: big = huge(1.0_wp)
    real(wp) :: s0, width, centre, s, total
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
    if (status /= SD_OK .or. wave_height <= freeboard) return
    head = wave_height - freeboard
    confined_mass = convective_mass*(1 - freeboard/wave_height)
    ! eta > f where J1(xi s) > (f/d) J1(xi), s = r/R: J1 rises on [0, xi], so for s in (s0, 1]
    s0 = inverse_shape(freeboard/wave_height)
    width = (1 - s0)/panels
    total = 0
    do panel = 1, panels
      centre = s0 + (panel - 0.5_wp)*width
      do k = 1, size(gauss_x)
        do side = -1, 1, 2
          s = centre + side*gauss_x(k)*width/2
          total = total + gauss_w(k)*width/2*ring(s)
        end do
      end do
    end do
    uplift = density*gravity*radius**2*total

  contains

    !> The integral over theta of (eta - f)+ at s = r/R, times s: with a = eta's amplitude there,
    !> 2 (a sin(alpha) - f alpha), alpha = acos(f/a), for a > f.
    pure real(wp) function ring(s_point)
      real(wp), intent(in) :: s_point
      real(wp) :: a, alpha
      a = wave_height*bessel_j1(xi_exact*s_point)/bessel_j1(xi_exact)
      ring = 0
      if (a <= freeboard) return
      alpha = acos(freeboard/a)
      ring = 2*(a*sin(alpha) - freeboard*alpha)*s_point
    end function ring
  end subroutine roof_loads

  !> The s in [0, 1] with J1(xi s)/J1(xi) = q (0 <= q <= 1), by bisection (J1 rises there).
  pure real(wp) function inverse_shape(q) result(s)
    real(wp), intent(in) :: q
    real(wp) :: lo, hi
    integer :: i
    lo = 0
    hi = 1
    do i = 1, 60
      s = (lo + hi)/2
      if (bessel_j1(xi_exact*s) < q*bessel_j1(xi_exact)) then
        lo = s
      else
        hi = s
      end if
    end do
    s = (lo + hi)/2
  end function inverse_shape
end module sloshdyn_roof
