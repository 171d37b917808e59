!> A cancellation request (sloshdyn_cancel) stops an integration within N = 1 step of its
!> integrator (docs/studies.md, "Stopping a study"; the poll is in sloshdyn_ode's rk_step): the
!> request is made by the right-hand side itself once t passes t_flag -- at an arbitrary moment
!> of a long integration, as a signal handler or another thread would make it -- and the
!> integration returns SD_CANCELLED with t_reached at most one step (the step under way) past
!> the time of the request, for every method, with fixed and adaptive steps; once the flag is
!> cleared the same integration runs to its end.
module cancelling_decay
  use sloshdyn_kinds, only: wp
  use sloshdyn_ode, only: ode_system
  use sloshdyn_cancel, only: request_cancel, cancel_signal
  implicit none
  private
  public :: decay, t_requested

  !> the time at which the request was made (the stage time of the evaluation that made it)
  real(wp) :: t_requested = -1

  !> y' = -y, which requests cancellation at its first evaluation at t >= t_flag
  type, extends(ode_system) :: decay
    real(wp) :: t_flag = huge(1.0_wp)
  contains
    procedure :: rhs => decay_rhs
  end type decay

contains

  subroutine decay_rhs(self, t, y, dydt)
    class(decay), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: dydt(:)
    dydt = -y
    if (t >= self%t_flag .and. cancel_signal() == 0) then
      t_requested = t
      call request_cancel(-1)
    end if
  end subroutine decay_rhs
end module cancelling_decay

program test_cancel
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_CANCELLED
  use sloshdyn_cancel, only: clear_cancel
  use sloshdyn_ode, only: ode_options, ode_stats
  use sloshdyn_integrator, only: integrate, method_name, METHOD_DOPRI5, METHOD_DOP853, &
                                 METHOD_VERN9
  use cancelling_decay, only: decay, t_requested
  use checks, only: check_true, finish
  implicit none
  !> the steps within which the integration stops after the request (documented N): the step
  !> under way ends, the next one polls the flag
  integer, parameter :: n_poll = 1
  real(wp), parameter :: h = 0.01_wp, t_end = 50.0_wp
  integer, parameter :: methods(3) = [METHOD_DOPRI5, METHOD_DOP853, METHOD_VERN9]
  integer :: k

  do k = 1, size(methods)
    call check_stop(methods(k), .true.)
    call check_stop(methods(k), .false.)
  end do
  call finish()

contains

  !> Integrate y' = -y over [0, t_end] (h fixed, or adaptive with steps of at most h) with a
  !> request at t = 5: cancelled within n_poll steps of the request; then, the flag cleared,
  !> to t_end.
  subroutine check_stop(method, fixed)
    integer, intent(in) :: method
    logical, intent(in) :: fixed
    type(decay) :: system
    type(ode_options) :: options
    type(ode_stats) :: stats
    real(wp) :: y_out(1, 1)
    integer :: status
    character(len=message_len) :: message
    character(len=:), allocatable :: name

    name = trim(method_name(method))//merge(' fixed h   ', ' adaptive h', fixed)
    if (fixed) then
      options%fixed_step = h
    else
      options%h_max = h
    end if
    system%t_flag = 5
    t_requested = -1
    call integrate(method, system, 0.0_wp, [1.0_wp], [t_end], y_out, options, stats, status, &
                   message)
    call check_true(name//': the request stops the integration: '//trim(message), &
                    status == SD_CANCELLED .and. t_requested >= 5)
    call check_true(name//': within one step of its integrator after the request', &
                    stats%t_reached > 0 .and. &
                    stats%t_reached <= t_requested + n_poll*h*(1 + 1.0e-12_wp))
    call clear_cancel()
    system%t_flag = huge(1.0_wp)
    call integrate(method, system, 0.0_wp, [1.0_wp], [t_end], y_out, options, stats, status, &
                   message)
    call check_true(name//': with the flag cleared it runs to its end '//trim(message), &
                    status == SD_OK .and. stats%t_reached == t_end)
  end subroutine check_stop
end program test_cancel
