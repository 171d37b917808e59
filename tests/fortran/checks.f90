!> Tiny check module for the Fortran unit tests: each check prints a line and counts failures;
!> a test program ends with `call finish()`, which exits non-zero if any check failed.
module checks
  use sloshdyn_kinds, only: wp
  implicit none
  private
  public :: check_close, check_true, finish

  integer :: n_checks = 0, n_failed = 0

contains

  !> |actual - expected| <= abs_tol + rel_tol |expected|
  subroutine check_close(label, actual, expected, rel_tol, abs_tol)
    character(len=*), intent(in) :: label
    real(wp), intent(in) :: actual, expected, rel_tol
    real(wp), intent(in), optional :: abs_tol
    real(wp) :: allowed
    allowed = rel_tol*abs(expected)
    if (present(abs_tol)) allowed = allowed + abs_tol
    call record(label, abs(actual - expected) <= allowed)
    if (.not. abs(actual - expected) <= allowed) &
      print '(a, es24.16, a, es24.16, a, es10.2)', '    actual ', actual, ' expected ', expected, &
            ' allowed ', allowed
  end subroutine check_close

  subroutine check_true(label, condition)
    character(len=*), intent(in) :: label
    logical, intent(in) :: condition
    call record(label, condition)
  end subroutine check_true

  subroutine record(label, passed)
    character(len=*), intent(in) :: label
    logical, intent(in) :: passed
    n_checks = n_checks + 1
    if (passed) then
      print '(a)', 'PASS '//label
    else
      n_failed = n_failed + 1
      print '(a)', 'FAIL '//label
    end if
  end subroutine record

  subroutine finish()
    print '(i0, a, i0, a)', n_checks - n_failed, ' passed, ', n_failed, ' failed'
    if (n_failed > 0) error stop 1
  end subroutine finish
end module checks
