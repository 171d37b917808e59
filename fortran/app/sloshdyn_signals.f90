!> The executable's SIGINT (Ctrl-C) and SIGTERM handlers, through libc's signal(). While the
!> input is read nothing has been written, so a signal ends the process at once with exit code
!> 128 + the signal (install_exit_handlers): also when it waits in a system call that gfortran
!> restarts (opening a FIFO with no writer) or reads and scales a long record. Then, while the
!> analysis runs (install_signal_handlers), the first signal requests cancellation
!> (sloshdyn_cancel), which the running analysis honours within one integrator or continuation
!> step or one block of an output, spectrum or grid loop; the run then discards its temporary
!> files and the executable exits with 128 + the signal. The handler restores the default
!> action, so a second signal ends the process at once.
!> SIGXFSZ (a file grew past the size limit, ulimit -f) is ignored, so the write fails like a
!> write to a full disk and the run ends with its files removed and exit code 5, instead of
!> dying (gfortran's runtime would print a backtrace and leave the temporaries).
module sloshdyn_signals
  use, intrinsic :: iso_c_binding, only: c_int, c_intptr_t, c_funptr, c_funloc, c_null_funptr
  use sloshdyn_cancel, only: request_cancel
  implicit none
  private
  public :: install_exit_handlers, install_signal_handlers, SIGINT, SIGTERM

  integer(c_int), parameter :: SIGINT = 2, SIGTERM = 15   ! POSIX numbers (Linux, macOS)
  integer(c_int), parameter :: SIGXFSZ = 25                ! Linux (x86, ARM)
  integer(c_intptr_t), parameter :: SIG_IGN = 1

  interface
    type(c_funptr) function c_signal(signum, handler) bind(c, name='signal')
      import :: c_int, c_funptr
      integer(c_int), value :: signum
      type(c_funptr), value :: handler
    end function c_signal
    subroutine c_exit(status) bind(c, name='_exit')
      import :: c_int
      integer(c_int), value :: status
    end subroutine c_exit
  end interface

contains

  !> SIGINT and SIGTERM end the process at once with exit code 128 + the signal.
  subroutine install_exit_handlers()
    type(c_funptr) :: previous
    previous = c_signal(SIGINT, c_funloc(exit_on_signal))
    previous = c_signal(SIGTERM, c_funloc(exit_on_signal))
  end subroutine install_exit_handlers

  !> Async-signal-safe: _exit(2).
  subroutine exit_on_signal(signum) bind(c)
    integer(c_int), value :: signum
    call c_exit(128 + signum)
  end subroutine exit_on_signal

  !> SIGINT and SIGTERM cancel the running analysis (a second one ends the process); SIGXFSZ is
  !> ignored.
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
