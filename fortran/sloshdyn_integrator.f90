!> The choice of integration method: Dormand-Prince 5(4) (sloshdyn_rk45, the default) or 8(5,3)
!> (sloshdyn_dop853, fewer steps at tight tolerances), behind one step-wise interface.
module sloshdyn_integrator
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT
  use sloshdyn_text, only: num2str
  use sloshdyn_rk45, only: ode_system, rk45_options, rk45_stats, rk45_integrator, rk45_init, &
                           rk45_step, rk45_dense, rk45_statistics, rk45_integrate
  use sloshdyn_dop853, only: dop853_integrator, dop853_init, dop853_step, dop853_dense, &
                             dop853_statistics, dop853_integrate
  implicit none
  private
  public :: stepper, stepper_init, stepper_step, stepper_dense, stepper_time, stepper_statistics, &
            integrate, check_method, METHOD_RK45, METHOD_DOP853

  integer, parameter :: METHOD_RK45 = 0, METHOD_DOP853 = 1

  !> One integration by either method (only the chosen component is used).
  type :: stepper
    integer :: method = METHOD_RK45
    type(rk45_integrator) :: rk45
    type(dop853_integrator) :: dop853
  end type stepper

contains

  pure subroutine check_method(method, status, message)
    integer, intent(in) :: method
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    if (status /= SD_OK) return
    if (method /= METHOD_RK45 .and. method /= METHOD_DOP853) then
      status = SD_BAD_INPUT
      message = 'method = '//num2str(method)//' is not known: 0 = rk45 (Dormand-Prince 5(4)), '// &
                '1 = dop853 (Dormand-Prince 8(5,3))'
    end if
  end subroutine check_method

  subroutine stepper_init(s, method, sys, t0, y0, t_bound, options, status, message)
    type(stepper), intent(out) :: s
    integer, intent(in) :: method
    class(ode_system), intent(in) :: sys
    real(wp), intent(in) :: t0, y0(:), t_bound
    type(rk45_options), intent(in) :: options
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    status = SD_OK
    message = ''
    call check_method(method, status, message)
    if (status /= SD_OK) return
    s%method = method
    if (method == METHOD_DOP853) then
      call dop853_init(s%dop853, sys, t0, y0, t_bound, options, status, message)
    else
      call rk45_init(s%rk45, sys, t0, y0, t_bound, options, status, message)
    end if
  end subroutine stepper_init

  subroutine stepper_step(s, sys, status, message)
    type(stepper), intent(inout) :: s
    class(ode_system), intent(in) :: sys
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    if (s%method == METHOD_DOP853) then
      call dop853_step(s%dop853, sys, status, message)
    else
      call rk45_step(s%rk45, sys, status, message)
    end if
  end subroutine stepper_step

  pure subroutine stepper_dense(s, t, y)
    type(stepper), intent(in) :: s
    real(wp), intent(in) :: t
    real(wp), intent(out) :: y(:)
    if (s%method == METHOD_DOP853) then
      call dop853_dense(s%dop853, t, y)
    else
      call rk45_dense(s%rk45, t, y)
    end if
  end subroutine stepper_dense

  !> The time reached (end of the last accepted step).
  pure real(wp) function stepper_time(s) result(t)
    type(stepper), intent(in) :: s
    t = merge(s%dop853%t, s%rk45%t, s%method == METHOD_DOP853)
  end function stepper_time

  pure function stepper_statistics(s) result(stats)
    type(stepper), intent(in) :: s
    type(rk45_stats) :: stats
    if (s%method == METHOD_DOP853) then
      stats = dop853_statistics(s%dop853)
    else
      stats = rk45_statistics(s%rk45)
    end if
  end function stepper_statistics

  !> y at every t_out by the chosen method (see rk45_integrate for failures).
  subroutine integrate(method, sys, t0, y0, t_out, y_out, options, stats, status, message)
    integer, intent(in) :: method
    class(ode_system), intent(in) :: sys
    real(wp), intent(in) :: t0, y0(:), t_out(:)
    real(wp), intent(out) :: y_out(:, :)
    type(rk45_options), intent(in) :: options
    type(rk45_stats), intent(out) :: stats
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    status = SD_OK
    message = ''
    call check_method(method, status, message)
    if (status /= SD_OK) then
      y_out = 0
      return
    end if
    if (method == METHOD_DOP853) then
      call dop853_integrate(sys, t0, y0, t_out, y_out, options, stats, status, message)
    else
      call rk45_integrate(sys, t0, y0, t_out, y_out, options, stats, status, message)
    end if
  end subroutine integrate
end module sloshdyn_integrator
