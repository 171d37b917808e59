!> The base excitation X(tau) = u(t)/L of the tank, in the model's dimensionless time tau = omega t:
!> what every analysis that integrates takes from it is the base acceleration X'' (eq 10, 14),
!> and, for periodic analyses, the forcing period and the derivatives of X'' in the excitation's
!> parameters. A new kind of excitation is added here only.
!>
!> Kinds: harmonic, X = A sin(rho tau) (eq 29-31).
module sloshdyn_excitation
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_positive_inf
  use sloshdyn_kinds, only: wp, pi
  implicit none
  private
  public :: excitation_t, base_acceleration, forcing_period, acceleration_sensitivity, &
            EXCITATION_HARMONIC, PARAMETER_RHO, PARAMETER_A

  integer, parameter :: EXCITATION_HARMONIC = 1
  !> The excitation parameters a continuation or sweep can vary.
  integer, parameter :: PARAMETER_RHO = 1, PARAMETER_A = 2

  type :: excitation_t
    integer :: kind = EXCITATION_HARMONIC
    real(wp) :: A = 0       !< harmonic amplitude, A = u0/L
    real(wp) :: rho = 0     !< harmonic frequency Omega/omega
  end type excitation_t

contains

  !> X''(tau); for X = A sin(rho tau), X'' = -A rho^2 sin(rho tau) (eq 31).
  elemental real(wp) function base_acceleration(excitation, tau) result(xdd)
    type(excitation_t), intent(in) :: excitation
    real(wp), intent(in) :: tau
    xdd = -excitation%A*excitation%rho**2*sin(excitation%rho*tau)
  end function base_acceleration

  !> The forcing period T = 2 pi/rho; +Infinity without a frequency.
  elemental real(wp) function forcing_period(excitation) result(period)
    type(excitation_t), intent(in) :: excitation
    if (excitation%rho > 0) then
      period = 2*pi/excitation%rho
    else
      period = ieee_value(1.0_wp, ieee_positive_inf)
    end if
  end function forcing_period

  !> dX''/dlambda at tau for lambda = rho (PARAMETER_RHO) or A (PARAMETER_A), at fixed tau.
  elemental real(wp) function acceleration_sensitivity(excitation, parameter, tau) result(dxdd)
    type(excitation_t), intent(in) :: excitation
    integer, intent(in) :: parameter
    real(wp), intent(in) :: tau
    associate (a => excitation%A, rho => excitation%rho)
      if (parameter == PARAMETER_A) then
        dxdd = -rho**2*sin(rho*tau)
      else
        dxdd = -a*(2*rho*sin(rho*tau) + rho**2*tau*cos(rho*tau))
      end if
    end associate
  end function acceleration_sensitivity
end module sloshdyn_excitation
