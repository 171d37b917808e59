!> The LAPACK calls of sloshdyn: dgeev for the eigenvalues of every stability Jacobian, dgesv for
!> Newton steps. Inputs are copied, so callers keep their matrices. A matrix with NaN or
!> infinite entries is refused before LAPACK sees it, and results that are not finite are an
!> error, never a result.
!>
!> LAPACK reports invalid arguments through XERBLA, whose reference version prints a line and
!> STOPS the process -- inside Python it would end the interpreter. This file also defines the
!> project's XERBLA (after the module): it returns, so the LAPACK routine returns with info < 0,
!> which becomes a status here. Linked into the executable and the extension module, it takes
!> precedence over the library's.
module sloshdyn_lapack
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_LAPACK_FAILED, SD_SINGULAR, SD_NON_FINITE
  use sloshdyn_text, only: num2str
  implicit none
  private
  public :: eigenvalues, solve_linear

  interface
    subroutine dgeev(jobvl, jobvr, n, a, lda, wr, wi, vl, ldvl, vr, ldvr, work, lwork, info)
      import :: wp
      character, intent(in) :: jobvl, jobvr
      integer, intent(in) :: n, lda, ldvl, ldvr, lwork
      real(wp), intent(inout) :: a(lda, *)
      real(wp), intent(out) :: wr(*), wi(*), vl(ldvl, *), vr(ldvr, *), work(*)
      integer, intent(out) :: info
    end subroutine dgeev
    subroutine dgesv(n, nrhs, a, lda, ipiv, b, ldb, info)
      import :: wp
      integer, intent(in) :: n, nrhs, lda, ldb
      real(wp), intent(inout) :: a(lda, *), b(ldb, *)
      integer, intent(out) :: ipiv(*), info
    end subroutine dgesv
  end interface

contains

  !> Eigenvalues wr + i wi of the square matrix a (LAPACK dgeev, no eigenvectors).
  subroutine eigenvalues(a, wr, wi, status, message)
    real(wp), intent(in) :: a(:, :)
    real(wp), intent(out) :: wr(size(a, 1)), wi(size(a, 1))
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: work_matrix(size(a, 1), size(a, 1)), work(8*size(a, 1)), no_left(1, 1), no_right(1, 1)
    integer :: n, info

    n = size(a, 1)
    wr = 0
    wi = 0
    call check_finite('eigenvalues: the matrix', a, status, message)
    if (status /= SD_OK) return
    work_matrix = a
    call dgeev('N', 'N', n, work_matrix, n, wr, wi, no_left, 1, no_right, 1, work, size(work), info)
    if (info /= 0) then
      status = SD_LAPACK_FAILED
      message = 'dgeev failed with info = '//num2str(info)
    else if (.not. (all(ieee_is_finite(wr)) .and. all(ieee_is_finite(wi)))) then
      status = SD_NON_FINITE
      message = 'dgeev gave eigenvalues that are not finite (the matrix is too large in '// &
                'magnitude: largest entry '//num2str(maxval(abs(a)))//')'
    end if
  end subroutine eigenvalues

  !> Solve a x = b (LAPACK dgesv); x overwrites b.
  subroutine solve_linear(a, b, status, message)
    real(wp), intent(in) :: a(:, :)
    real(wp), intent(inout) :: b(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: work_matrix(size(a, 1), size(a, 1))
    integer :: n, info, pivots(size(a, 1))

    n = size(a, 1)
    call check_finite('solve_linear: the matrix', a, status, message)
    if (status == SD_OK) call check_finite('solve_linear: the right-hand side', &
                                           reshape(b, [size(b), 1]), status, message)
    if (status /= SD_OK) return
    work_matrix = a
    call dgesv(n, 1, work_matrix, n, pivots, b, n, info)
    if (info > 0) then
      status = SD_SINGULAR
      message = 'singular matrix in dgesv (zero pivot '//num2str(info)//')'
    else if (info < 0) then
      status = SD_LAPACK_FAILED
      message = 'dgesv failed with info = '//num2str(info)
    end if
  end subroutine solve_linear

  pure subroutine check_finite(what, a, status, message)
    character(len=*), intent(in) :: what
    real(wp), intent(in) :: a(:, :)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    status = SD_OK
    message = ''
    if (all(ieee_is_finite(a))) return
    status = SD_NON_FINITE
    message = what//' has NaN or infinite entries'
  end subroutine check_finite
end module sloshdyn_lapack

!> XERBLA for LAPACK (see the module header): return instead of stopping; the calling routine
!> then returns info = -(the argument's position), which the wrappers turn into a status.
subroutine xerbla(srname, info)
  implicit none
  character(len=*), intent(in) :: srname
  integer, intent(in) :: info
end subroutine xerbla
