!> Equivalent pendulum of the first sloshing mode of a cylindrical tank (Abramson), eq (2)-(3),
!> and the sloshing modes 1..N of a rigid circular or rectangular tank by linear potential flow
!> (Abramson, NASA SP-106, ch 2 and 6; Graham & Rodriguez 1952 for the rectangular tank).
module sloshdyn_tank
  use sloshdyn_kinds, only: wp, pi, message_len
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, SD_NON_FINITE, check_real
  implicit none
  private
  public :: tank_pendulum, min_tank_size, max_tank_size, max_liquid_density
  public :: sloshing_modes, modal_wave_number, shape_names, max_modes
  public :: SHAPE_CIRCULAR, SHAPE_RECTANGULAR

  !> The plan of a tank: a vertical circular cylinder (radius R) or a rectangular basin (length
  !> L in the direction of the motion, width W across it); shape_names in the order of the codes.
  integer, parameter :: SHAPE_CIRCULAR = 1, SHAPE_RECTANGULAR = 2
  character(len=*), parameter :: shape_names(*) = [character(len=11) :: 'circular', &
                                                   'rectangular']
  !> The most sloshing modes a tank takes (&tank modes, Tank(modes=)).
  integer, parameter :: max_modes = 10
  !> The first max_modes roots xi_n of J1' (the antisymmetric sloshing modes of a cylinder),
  !> to 16 digits (Abramson SP-106 table 2.1 gives 1.841, 5.331, 8.536, ...).
  real(wp), parameter :: j1_prime_roots(max_modes) = [1.8411837813406593_wp, &
    5.3314427735250325_wp, 8.536316366346286_wp, 11.706004902592063_wp, 14.863588633909034_wp, &
    18.015527862681804_wp, 21.164369859188792_wp, 24.311326857210776_wp, &
    27.457050571059245_wp, 30.601922972669094_wp]

  !> R and h [m]: from a millimetre (below it surface tension, not gravity, restores the liquid
  !> and Abramson's pendulum does not apply) to a kilometre (no tank is larger); within these
  !> R^2 h, h/R and the hyperbolic functions of eq (2) stay far from overflow and underflow.
  real(wp), parameter :: min_tank_size = 1.0e-3_wp, max_tank_size = 1.0e3_wp
  !> rho_liquid [kg/m^3]: every liquid is lighter than 1e5 (mercury 13 534, molten osmium
  !> about 20 000).
  real(wp), parameter :: max_liquid_density = 1.0e5_wp

contains

  !> From radius R, liquid depth h and either the liquid density (liquid_mass <= 0) or the liquid
  !> mass m_F (density <= 0): pendulum length l, sloshing mass m, its distance d1, the rigid mass
  !> m0 and its distance d0. Exactly one of density and liquid_mass must be positive.
  pure subroutine tank_pendulum(radius, depth, density, liquid_mass, l, m, d1, m0, d0, mf, &
                                status, message)
    real(wp), intent(in) :: radius, depth, density, liquid_mass
    real(wp), intent(out) :: l, m, d1, m0, d0, mf
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), parameter :: big = huge(1.0_wp)
    real(wp) :: x

    status = SD_OK
    message = ''
    l = 0; m = 0; d1 = 0; m0 = 0; d0 = 0; mf = 0
    call check_real('radius', radius, min_tank_size, max_tank_size, .false., .false., &
                    'the tank radius R [m] must lie in [1e-3, 1e3]: Abramson''s pendulum '// &
                    'holds for tanks from a millimetre to a kilometre', status, message)
    call check_real('liquid_depth', depth, min_tank_size, max_tank_size, .false., .false., &
                    'the liquid depth h [m] must lie in [1e-3, 1e3]: Abramson''s pendulum '// &
                    'holds for tanks from a millimetre to a kilometre', status, message)
    if (status /= SD_OK) return
    if ((density > 0) .eqv. (liquid_mass > 0)) then
      status = SD_BAD_INPUT
      message = 'liquid_density and liquid_mass: give exactly one of them, > 0 (the liquid density '// &
                '[kg/m^3] or the liquid mass [kg])'
      return
    end if
    call check_real('liquid_density', max(density, 0.0_wp), 0.0_wp, max_liquid_density, .false., &
                    .false., 'the liquid density [kg/m^3] must lie in [0, 1e5]: every '// &
                    'liquid is lighter', status, message)
    call check_real('liquid_mass', max(liquid_mass, 0.0_wp), 0.0_wp, big, .false., .true., &
                    'the liquid mass must be finite', status, message)
    if (status /= SD_OK) return

    mf = merge(pi*density*radius**2*depth, liquid_mass, density > 0)
    x = 1.84_wp*depth/radius
    l = radius/1.84_wp/tanh(x)                          ! eq (2): coth
    m = mf*radius/(2.2_wp*depth)*tanh(x)                ! eq (2)
    d1 = radius/3.68_wp/sinh(2*x)                       ! eq (2): csch (printed "csc h")
    m0 = mf - m                                         ! eq (3)
    d0 = mf/m0*(depth/2 - radius**2/(2*depth)) - (d1 + l)*m/m0   ! eq (3)
    if (.not. all(ieee_is_finite([l, m, d1, m0, d0, mf]))) then  ! e.g. a liquid mass near huge
      status = SD_NON_FINITE
      message = 'the tank pendulum of eq (2)-(3) is not finite for these R, h and liquid: '// &
                'overflow'
      l = 0; m = 0; d1 = 0; m0 = 0; d0 = 0; mf = 0
    end if
  end subroutine tank_pendulum

  !> k_n [1/m], the horizontal wave number of sloshing mode n: xi_n/R in a cylinder of radius
  !> R = plan_size (xi_n the n-th root of J1'), (2n - 1) pi/L in a rectangular tank of length
  !> L = plan_size (the antisymmetric modes, the ones a horizontal motion along L excites).
  elemental real(wp) function modal_wave_number(shape, plan_size, n) result(k)
    integer, intent(in) :: shape, n
    real(wp), intent(in) :: plan_size
    if (shape == SHAPE_CIRCULAR) then
      k = j1_prime_roots(n)/plan_size
    else
      k = (2*n - 1)*pi/plan_size
    end if
  end function modal_wave_number

  !> The sloshing modes n = 1..size(lengths) of a rigid tank (shape, plan_size R or L, liquid
  !> depth h, liquid mass m_F) by linear potential flow, each as an equivalent pendulum, with
  !> x = k_n h (Abramson SP-106 ch 2 and 6; Housner 1957; EN 1998-4 Annex A.2.1):
  !>   omega_n^2 = g k_n tanh(x), so the pendulum length l_n = g/omega_n^2 = 1/(k_n tanh x);
  !>   m_n/m_F = 2 tanh(x)/(x (xi_n^2 - 1))              (circular)
  !>   m_n/m_F = 8 tanh(x)/((2n - 1)^2 pi^2 x)            (rectangular)
  !>   h_n = h - tanh(x/2)/k_n, the height above the bottom of the resultant of the mode's wall
  !>   pressure (~ cosh(k_n z)), the bottom's excluded;
  !>   eta_n = wave_n sin(theta_n), the wave at the wall when the pendulum swings by theta_n
  !>   (the liquid's horizontal momentum equal to the pendulum's): wave_n = 2 R/(xi_n^2 - 1)
  !>   (circular), 4 L/((2n - 1)^2 pi^2) (rectangular).
  !> The modal masses of all n sum to m_F minus the impulsive mass; as h/R or h/L -> 0 they sum
  !> to m_F (sum 2/(xi_n^2 - 1) = sum 8/((2n-1)^2 pi^2) = 1).
  pure subroutine sloshing_modes(shape, plan_size, depth, liquid_mass, lengths, masses, heights, &
                                 waves)
    integer, intent(in) :: shape
    real(wp), intent(in) :: plan_size, depth, liquid_mass
    real(wp), intent(out) :: lengths(:), masses(size(lengths)), heights(size(lengths)), &
                             waves(size(lengths))
    real(wp) :: k, x
    integer :: n
    do n = 1, size(lengths)
      k = modal_wave_number(shape, plan_size, n)
      x = k*depth
      lengths(n) = 1/(k*tanh(x))
      heights(n) = depth - tanh(x/2)/k
      if (shape == SHAPE_CIRCULAR) then
        masses(n) = liquid_mass*2*tanh(x)/(x*(j1_prime_roots(n)**2 - 1))
        waves(n) = 2*plan_size/(j1_prime_roots(n)**2 - 1)
      else
        masses(n) = liquid_mass*8*tanh(x)/((2*n - 1)**2*pi**2*x)
        waves(n) = 4*plan_size/((2*n - 1)**2*pi**2)
      end if
    end do
  end subroutine sloshing_modes
end module sloshdyn_tank
