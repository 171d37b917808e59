!> Cancellation of a long computation: one flag, set from outside the computation (the
!> executable's SIGINT/SIGTERM handler, Python's request_cancel from another thread while a
!> bridge call runs without the GIL) and polled by the long loops -- every integrator step,
!> every continuation step, every start of a scan -- which then return SD_CANCELLED.
!>
!> This flag is the one piece of global mutable state of the core, a deliberate exception
!> (docs/architecture.md, "Cancellation"): a signal handler cannot reach the arguments of a
!> running call. It is volatile, so a loop rereads it; a request cancels every call running in
!> the process.
module sloshdyn_cancel
  use, intrinsic :: iso_c_binding, only: c_int
  use sloshdyn_kinds, only: message_len
  use sloshdyn_status, only: SD_OK, SD_CANCELLED
  implicit none
  private
  public :: request_cancel, clear_cancel, cancel_signal, check_cancel

  !> 0: go on; otherwise the request (the signal number, or -1 for a request from Python)
  integer(c_int), volatile :: requested = 0

contains

  !> Ask every running computation to stop (signal = the signal number, or -1). Safe in a
  !> signal handler: it only stores an integer.
  subroutine request_cancel(signal)
    integer(c_int), intent(in) :: signal
    requested = signal
  end subroutine request_cancel

  subroutine clear_cancel()
    requested = 0
  end subroutine clear_cancel

  !> The pending request: 0 for none, the signal number, or -1.
  integer(c_int) function cancel_signal()
    cancel_signal = requested
  end function cancel_signal

  !> If a cancellation was requested and no earlier failure is pending, status = SD_CANCELLED.
  subroutine check_cancel(status, message)
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    if (status /= SD_OK .or. requested == 0) return
    status = SD_CANCELLED
    message = 'stopped on request (Ctrl-C, SIGTERM or request_cancel)'
  end subroutine check_cancel
end module sloshdyn_cancel
