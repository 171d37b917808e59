!> The LAPACK wrappers never let a bad value end the process: NaN or infinite matrices are
!> refused with a status, results that are not finite are an error, and the project's XERBLA
!> returns (LAPACK's reference XERBLA would stop the program: this test would not finish).
program test_lapack
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_positive_inf
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_NON_FINITE
  use sloshdyn_lapack, only: eigenvalues, solve_linear
  use checks, only: check_true, check_close, finish
  implicit none

  interface
    subroutine dgeev(jobvl, jobvr, n, a, lda, wr, wi, vl, ldvl, vr, ldvr, work, lwork, info)
      import :: wp
      character, intent(in) :: jobvl, jobvr
      integer, intent(in) :: n, lda, ldvl, ldvr, lwork
      real(wp), intent(inout) :: a(lda, *)
      real(wp), intent(out) :: wr(*), wi(*), vl(ldvl, *), vr(ldvr, *), work(*)
      integer, intent(out) :: info
    end subroutine dgeev
  end interface

  real(wp) :: a(2, 2), wr(2), wi(2), b(2), work(16), no(1, 1)
  integer :: status, info
  character(len=message_len) :: message

  ! the rotation generator [[0, -1], [1, 0]] has eigenvalues +-i
  a = reshape([0.0_wp, 1.0_wp, -1.0_wp, 0.0_wp], [2, 2])
  call eigenvalues(a, wr, wi, status, message)
  call check_true('eigenvalues of a rotation generator: status OK', status == SD_OK)
  call check_close('... imaginary parts +-1', maxval(abs(wi)), 1.0_wp, 1.0e-15_wp)
  a(1, 2) = ieee_value(1.0_wp, ieee_quiet_nan)
  call eigenvalues(a, wr, wi, status, message)
  call check_true('NaN entry refused: '//trim(message), status == SD_NON_FINITE)
  a(1, 2) = ieee_value(1.0_wp, ieee_positive_inf)
  b = 1
  call solve_linear(a, b, status, message)
  call check_true('infinite entry refused by solve_linear: '//trim(message), &
                  status == SD_NON_FINITE)
  a = reshape([1.0e300_wp, 1.0e300_wp, -1.0e300_wp, 1.0e300_wp], [2, 2])
  call eigenvalues(a, wr, wi, status, message)
  call check_true('huge entries: finite eigenvalues or an error, never NaN: '//trim(message), &
                  status /= SD_OK .or. (all(abs(wr) <= huge(1.0_wp)) .and. all(abs(wi) <= huge(1.0_wp))))
  ! an illegal argument (lda < n): LAPACK calls XERBLA; ours returns, so dgeev returns info < 0
  a = 1
  call dgeev('N', 'N', 2, a, 1, wr, wi, no, 1, no, 1, work, size(work), info)
  call check_true('an illegal argument gives info < 0 and the program goes on', info < 0)
  call finish()
end program test_lapack
