!> Equivalent pendulum of the first sloshing mode of a cylindrical tank (Abramson), eq (2)-(3).
module sloshdyn_tank
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, check_real
  implicit none
  private
  public :: tank_pendulum

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
    call check_real('R', radius, 0.0_wp, big, .true., .true., &
                    'the tank radius R must be > 0 [m]', status, message)
    call check_real('h', depth, 0.0_wp, big, .true., .true., &
                    'the liquid depth h must be > 0 [m]', status, message)
    if (status /= SD_OK) return
    if ((density > 0) .eqv. (liquid_mass > 0)) then
      status = SD_BAD_INPUT
      message = 'rho_liquid and m_liquid: give exactly one of them, > 0 (the liquid density '// &
                '[kg/m^3] or the liquid mass [kg])'
      return
    end if
    call check_real('rho_liquid', max(density, 0.0_wp), 0.0_wp, big, .false., .true., &
                    'the liquid density must be finite', status, message)
    call check_real('m_liquid', max(liquid_mass, 0.0_wp), 0.0_wp, big, .false., .true., &
                    'the liquid mass must be finite', status, message)
    if (status /= SD_OK) return

    mf = merge(pi*density*radius**2*depth, liquid_mass, density > 0)
    x = 1.84_wp*depth/radius
    l = radius/1.84_wp/tanh(x)                          ! eq (2): coth
    m = mf*radius/(2.2_wp*depth)*tanh(x)                ! eq (2)
    d1 = radius/3.68_wp/sinh(2*x)                       ! eq (2): csch (printed "csc h")
    m0 = mf - m                                         ! eq (3)
    d0 = mf/m0*(depth/2 - radius**2/(2*depth)) - (d1 + l)*m/m0   ! eq (3)
  end subroutine tank_pendulum
end module sloshdyn_tank
