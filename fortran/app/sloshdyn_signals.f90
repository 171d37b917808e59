!> The executable's SIGINT (Ctrl-C) and SIGTERM handlers, through libc's signal(): the first
!> signal requests cancellation (sloshdyn_cancel), which the running analysis honours within one
!> integrator or continuation step; the run then discards its temporary files and the
!> executable exits with 128 + the signal. The handler restores the default action, so a second
!> signal ends the process at once.
!> SIGXFSZ (a file grew past the size limit, ulimit -f) is ignored, so the write fails like a
!> write to a full disk and the run ends with its files removed and exit code 5, instead of
!> dying (gfortran's runtime would print a backtrace and leave the temporaries).
module sloshdyn_signals
  use, intrinsic :: iso_c_binding, only: c_int, c_intptr_t, c_funptr, c_funloc, c_null_funptr
  use sloshdyn_cancel, only: request_cancel
  implicit none
  private
  public :: install_signal_handlers, SIGINT, SIGTERM

  integer(c_int), parameter :: SIGINT = 2, SIGTERM = 15   ! POSIX numbers (Linux, macOS)
  integer(c_int), parameter :: SIGXFSZ = 25                ! Linux (x86, ARM)
  integer(c_intptr_t), parameter :: SIG_IGN = 1

  interface
    type(c_funptr) function c_signal(signum, handler) bind(c, name='signal')
      import :: c_int, c_funptr
      integer(c_int), value :: signum
      type(c_funptr), value :: handler
    end function c_signal
  end interface

contains

  subroutine install_signal_handlers()
    type(c_funptr) :: previous
    previous = c_signal(SIGINT, c_funloc(on_signal))
    previous = c_signal(SIGTERM, c_funloc(on_signal))
    previous = c_signal(SIGXFSZ, transfer(SIG_IGN, previous))
  end subroutine install_signal_handlers

  !> Async-signal-safe: stores an integer and calls signal().
  subroutine on_signal(signum) bind(c)
    integer(c_int), value :: signum
    type(c_funptr) :: previous
    call request_cancel(signum)
    previous = c_signal(signum, c_null_funptr)   ! SIG_DFL
  end subroutine on_signal
end module sloshdyn_signals
