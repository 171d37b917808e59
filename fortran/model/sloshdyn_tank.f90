!> Equivalent pendulum of the first sloshing mode of a cylindrical tank (Abramson), eq (2)-(3).
module sloshdyn_tank
  use sloshdyn_kinds, only: wp, pi, message_len
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, SD_NON_FINITE, check_real
  implicit none
  private
  public :: tank_pendulum, min_tank_size, max_tank_size, max_liquid_density

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
end module sloshdyn_tank
