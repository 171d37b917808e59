!> Status codes returned by every routine that can fail (0 = success), their names, and the
!> range check that every input validation uses.
!> Library code never stops: it returns one of these codes and a message naming the cause.
module sloshdyn_status
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_text, only: num2str
  implicit none
  private
  public :: status_name, check_real, check_output_count, exit_code
  public :: EXIT_SUCCESS, EXIT_OUT_OF_TOLERANCE, EXIT_USAGE, EXIT_INPUT, EXIT_FAILURE, EXIT_IO, &
            EXIT_INTERRUPTED, EXIT_TERMINATED
  public :: SD_OK, SD_BAD_INPUT, SD_NOT_CONVERGED, SD_SINGULAR, SD_LAPACK_FAILED, &
            SD_STEP_TOO_SMALL, SD_TOO_MANY_STEPS, SD_NON_FINITE, SD_IO_ERROR, SD_CAPACITY, &
            SD_CANCELLED

  integer, parameter :: SD_OK = 0               !< success
  integer, parameter :: SD_BAD_INPUT = 1        !< an input value is missing, malformed or out of range
  integer, parameter :: SD_NOT_CONVERGED = 2    !< an iterative solver did not converge
  integer, parameter :: SD_SINGULAR = 3         !< a linear system or Jacobian is singular
  integer, parameter :: SD_LAPACK_FAILED = 4    !< LAPACK returned a nonzero info
  integer, parameter :: SD_STEP_TOO_SMALL = 5   !< the integrator step fell below its minimum
  integer, parameter :: SD_TOO_MANY_STEPS = 6   !< the integrator hit its step limit
  integer, parameter :: SD_NON_FINITE = 7       !< the state became NaN or infinite
  integer, parameter :: SD_IO_ERROR = 8         !< a file could not be read or written
  integer, parameter :: SD_CAPACITY = 9         !< a result does not fit the space the caller gave
  integer, parameter :: SD_CANCELLED = 10       !< the run was cancelled (Ctrl-C, SIGTERM, request_cancel)

  !> The exit codes of both front doors (the executable and sloshdyn-py), one table
  !> (docs/architecture.md, "Exit codes"): 0 success; 1 `check` found results out of tolerance;
  !> 2 usage; 3 the input (its file, a value, a rule); 4 the computation failed; 5 the results
  !> could not be written (nothing of the run is left under a final name); 130 interrupted
  !> (SIGINT, Ctrl-C) and 143 terminated (SIGTERM), 128 + the signal as shells report them.
  integer, parameter :: EXIT_SUCCESS = 0, EXIT_OUT_OF_TOLERANCE = 1, EXIT_USAGE = 2, &
                        EXIT_INPUT = 3, EXIT_FAILURE = 4, EXIT_IO = 5, EXIT_INTERRUPTED = 130, &
                        EXIT_TERMINATED = 143

contains

  !> The exit code of a status, from reading the input (reading = .true.) or from the run.
  pure integer function exit_code(code, reading)
    integer, intent(in) :: code
    logical, intent(in) :: reading
    if (code == SD_OK) then
      exit_code = EXIT_SUCCESS
    else if (code == SD_CANCELLED) then
      exit_code = EXIT_INTERRUPTED
    else if (reading .or. code == SD_BAD_INPUT) then
      exit_code = EXIT_INPUT
    else if (code == SD_IO_ERROR) then
      exit_code = EXIT_IO
    else
      exit_code = EXIT_FAILURE
    end if
  end function exit_code

  !> Short name of a status code, used as the prefix of messages and by the Python exceptions.
  pure function status_name(code) result(name)
    integer, intent(in) :: code
    character(len=:), allocatable :: name
    select case (code)
    case (SD_OK);             name = 'ok'
    case (SD_BAD_INPUT);      name = 'bad input'
    case (SD_NOT_CONVERGED);  name = 'not converged'
    case (SD_SINGULAR);       name = 'singular matrix'
    case (SD_LAPACK_FAILED);  name = 'LAPACK failure'
    case (SD_STEP_TOO_SMALL); name = 'step size too small'
    case (SD_TOO_MANY_STEPS); name = 'too many steps'
    case (SD_NON_FINITE);     name = 'non-finite state'
    case (SD_IO_ERROR);       name = 'input/output error'
    case (SD_CAPACITY);       name = 'output capacity exceeded'
    case (SD_CANCELLED);      name = 'cancelled'
    case default;             name = 'unknown status'
    end select
  end function status_name

  !> If no earlier check failed, check lower <(=) value <(=) upper and finiteness; on failure set
  !> a message naming the variable, its value and the rule.
  pure subroutine check_real(name, value, lower, upper, lower_open, upper_open, rule, &
                             status, message)
    character(len=*), intent(in) :: name, rule
    real(wp), intent(in) :: value, lower, upper
    logical, intent(in) :: lower_open, upper_open
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    logical :: ok

    if (status /= SD_OK) return
    ok = value == value .and. abs(value) <= huge(value)
    if (ok) then
      if (lower_open) then
        ok = value > lower
      else
        ok = value >= lower
      end if
    end if
    if (ok) then
      if (upper_open) then
        ok = value < upper
      else
        ok = value <= upper
      end if
    end if
    if (.not. ok) then
      status = SD_BAD_INPUT
      message = name//' = '//num2str(value)//' is out of range: '//rule
    end if
  end subroutine check_real

  !> If no earlier check failed, check that a count of outputs lies in [2, n_max] (or is 0, the
  !> default, where default_allowed); on failure a message naming the variable and the range.
  pure subroutine check_output_count(name, n, n_max, default_allowed, status, message)
    character(len=*), intent(in) :: name
    integer, intent(in) :: n, n_max
    logical, intent(in) :: default_allowed
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message

    if (status /= SD_OK .or. (default_allowed .and. n == 0)) return
    if (n < 2 .or. n > n_max) then
      status = SD_BAD_INPUT
      message = name//' = '//num2str(n)//' is out of range: it must lie in [2, '// &
                num2str(n_max)//']'//trim(merge(' (0: the default)', '                 ', &
                                                 default_allowed))
    end if
  end subroutine check_output_count
end module sloshdyn_status
