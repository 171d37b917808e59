!> The base excitation X(tau) = u(t)/L of the tank, in the model's dimensionless time tau = omega t:
!> what every analysis that integrates takes from it is the base acceleration X'' (eq 10, 14),
!> and, for periodic analyses, the forcing period and the derivatives of X'' in the excitation's
!> parameters. A new kind of excitation is added here only.
!>
!> Kinds:
!> - harmonic, X = A sin(rho tau) (eq 29-31);
!> - record: X'' sampled at tau = (i - 1) step, i = 1..size(samples), piecewise linear between
!>   samples, and 0 after the last one (the ground is at rest once the record ends). Its kinks
!>   at the samples are breakpoints: integrations end a step on each (breakpoint_step).
module sloshdyn_excitation
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_positive_inf
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, check_real
  use sloshdyn_text, only: num2str
  use sloshdyn_samples, only: check_samples, sampled_value
  implicit none
  private
  public :: excitation_t, base_acceleration, forcing_period, acceleration_sensitivity, &
            record_excitation, breakpoint_step, record_end, set_excitation_parameter, &
            EXCITATION_HARMONIC, EXCITATION_RECORD, PARAMETER_RHO, PARAMETER_A, &
            PARAMETER_FREQUENCY

  integer, parameter :: EXCITATION_HARMONIC = 1, EXCITATION_RECORD = 2
  !> The excitation parameters a continuation or sweep can vary (sweeps also rho at constant
  !> acceleration amplitude A rho^2, PARAMETER_FREQUENCY).
  integer, parameter :: PARAMETER_RHO = 1, PARAMETER_A = 2, PARAMETER_FREQUENCY = 3

  type :: excitation_t
    integer :: kind = EXCITATION_HARMONIC
    real(wp) :: A = 0       !< harmonic amplitude, A = u0/L
    real(wp) :: rho = 0     !< harmonic frequency Omega/omega
    real(wp) :: step = 0                 !< record: sample spacing in tau
    real(wp), allocatable :: samples(:)  !< record: X'' at the samples
  end type excitation_t

contains

  !> A record excitation from X'' samples spaced step apart in tau (at least 2, finite).
  pure subroutine record_excitation(samples, step, excitation, status, message)
    real(wp), intent(in) :: samples(:), step
    type(excitation_t), intent(out) :: excitation
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    call check_samples('the record', samples, step, status, message)
    if (status /= SD_OK) return
    excitation%kind = EXCITATION_RECORD
    excitation%step = step
    excitation%samples = samples
  end subroutine record_excitation

  !> X''(tau); for X = A sin(rho tau), X'' = -A rho^2 sin(rho tau) (eq 31); for a record, linear
  !> between samples and 0 before tau = 0 and after the last sample.
  elemental real(wp) function base_acceleration(excitation, tau) result(xdd)
    type(excitation_t), intent(in) :: excitation
    real(wp), intent(in) :: tau
    if (excitation%kind == EXCITATION_RECORD) then
      xdd = sampled_value(excitation%samples, excitation%step, tau)
    else
      xdd = -excitation%A*excitation%rho**2*sin(excitation%rho*tau)
    end if
  end function base_acceleration

  !> The forcing period T = 2 pi/rho; +Infinity without a frequency or for a record.
  elemental real(wp) function forcing_period(excitation) result(period)
    type(excitation_t), intent(in) :: excitation
    if (excitation%kind == EXCITATION_HARMONIC .and. excitation%rho > 0) then
      period = 2*pi/excitation%rho
    else
      period = ieee_value(1.0_wp, ieee_positive_inf)
    end if
  end function forcing_period

  !> dX''/dlambda at tau for lambda = rho (PARAMETER_RHO) or A (PARAMETER_A), at fixed tau
  !> (harmonic excitation; a record has no such parameter: 0).
  elemental real(wp) function acceleration_sensitivity(excitation, parameter, tau) result(dxdd)
    type(excitation_t), intent(in) :: excitation
    integer, intent(in) :: parameter
    real(wp), intent(in) :: tau
    dxdd = 0
    if (excitation%kind /= EXCITATION_HARMONIC) return
    associate (a => excitation%A, rho => excitation%rho)
      if (parameter == PARAMETER_A) then
        dxdd = -rho**2*sin(rho*tau)
      else
        dxdd = -a*(2*rho*sin(rho*tau) + rho**2*tau*cos(rho*tau))
      end if
    end associate
  end function acceleration_sensitivity

  !> Spacing of the breakpoints an integration must not step over (0: none).
  elemental real(wp) function breakpoint_step(excitation)
    type(excitation_t), intent(in) :: excitation
    breakpoint_step = 0
    if (excitation%kind == EXCITATION_RECORD) breakpoint_step = excitation%step
  end function breakpoint_step

  !> tau of the last sample of a record (0 for a harmonic excitation).
  elemental real(wp) function record_end(excitation)
    type(excitation_t), intent(in) :: excitation
    record_end = 0
    if (excitation%kind == EXCITATION_RECORD) &
      record_end = excitation%step*(size(excitation%samples) - 1)
  end function record_end
  !> The harmonic excitation with one parameter set to value: rho (PARAMETER_RHO), A
  !> (PARAMETER_A), or rho at the same acceleration amplitude A rho^2 (PARAMETER_FREQUENCY: a
  !> sweep in frequency at constant peak ground acceleration). Checks the value's range.
  pure subroutine set_excitation_parameter(excitation, which, value, status, message)
    type(excitation_t), intent(inout) :: excitation
    integer, intent(in) :: which
    real(wp), intent(in) :: value
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    status = SD_OK
    message = ''
    select case (which)
    case (PARAMETER_RHO)
      call check_real('rho', value, 0.0_wp, huge(1.0_wp), .true., .true., &
                      'values of rho must be > 0', status, message)
      if (status == SD_OK) excitation%rho = value
    case (PARAMETER_A)
      call check_real('A', value, 0.0_wp, huge(1.0_wp), .false., .true., &
                      'values of A must be >= 0', status, message)
      if (status == SD_OK) excitation%A = value
    case (PARAMETER_FREQUENCY)
      call check_real('rho', value, 0.0_wp, huge(1.0_wp), .true., .true., &
                      'values of rho must be > 0', status, message)
      call check_real('rho', excitation%rho, 0.0_wp, huge(1.0_wp), .true., .true., &
                      'a sweep at constant acceleration starts from rho > 0', status, message)
      if (status /= SD_OK) return
      excitation%A = excitation%A*(excitation%rho/value)**2
      excitation%rho = value
    case default
      status = SD_BAD_INPUT
      message = 'parameter '//num2str(which)//' is not known: 1 = rho, 2 = A, 3 = rho at '// &
                'constant acceleration'
    end select
  end subroutine set_excitation_parameter
end module sloshdyn_excitation
