!> The LAPACK calls of sloshdyn: dgeev for the eigenvalues of every stability Jacobian, dgesv for
!> Newton steps (up to 8 unknowns, the same unblocked LU written out, see solve_linear). Inputs are copied, so callers keep their matrices. A matrix with NaN or
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
  public :: dgeev, dgesv   ! LAPACK's own interfaces, for tests that call LAPACK directly

  !> Systems up to this size are solved without dgesv (see solve_linear).
  integer, parameter :: small_system = 8

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

  !> Solve a x = b; x overwrites b. Systems up to small_system unknowns (Newton steps of the
  !> slow flows, 4 or 5 unknowns, tens of thousands per frequency response) are solved here by
  !> dgesv's operations written out (small_lu_solve), which for such sizes costs a fraction of
  !> the calls through the recursive dgetrf2 and the BLAS; larger systems go to dgesv.
  subroutine solve_linear(a, b, status, message)
    real(wp), intent(in) :: a(:, :)
    real(wp), intent(inout) :: b(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: small(small_system, small_system)   ! fixed size: no allocation per call
    real(wp), allocatable :: work_matrix(:, :)
    integer, allocatable :: pivots(:)
    integer :: n, info

    n = size(a, 1)
    call check_finite('solve_linear: the matrix', a, status, message)
    if (status == SD_OK .and. .not. all(ieee_is_finite(b))) then
      status = SD_NON_FINITE
      message = 'solve_linear: the right-hand side has NaN or infinite entries'
    end if
    if (status /= SD_OK) return
    if (n <= small_system) then
      small(1:n, 1:n) = a
      call small_lu_solve(small(1:n, 1:n), b, info)
    else
      work_matrix = a
      allocate (pivots(n))
      call dgesv(n, 1, work_matrix, n, pivots, b, n, info)
    end if
    if (info > 0) then
      status = SD_SINGULAR
      message = 'singular matrix in dgesv (zero pivot '//num2str(info)//')'
    else if (info < 0) then
      status = SD_LAPACK_FAILED
      message = 'dgesv failed with info = '//num2str(info)
    end if
  end subroutine solve_linear

  !> LU with partial pivoting of a (overwritten) and the solution of a x = b in b, with the
  !> operations of LAPACK's dgetrf2 + dgetrs in their order (first largest |pivot|, scaling by
  !> the pivot's reciprocal, back substitution by columns from the last), so the results are
  !> dgesv's to the bit: callers such as inverse iteration on nearly singular matrices depend on
  !> them. info = k > 0 when the k-th pivot is exactly zero (b is then left unfinished, as
  !> dgesv leaves it undefined).
  pure subroutine small_lu_solve(a, b, info)
    real(wp), intent(inout) :: a(:, :), b(:)
    integer, intent(out) :: info
    real(wp) :: swap, reciprocal
    integer :: n, i, j, k, p

    n = size(a, 1)
    info = 0
    do k = 1, n
      p = k
      do i = k + 1, n
        if (abs(a(i, k)) > abs(a(p, k))) p = i
      end do
      if (a(p, k) == 0) then
        info = k
        return
      end if
      if (p /= k) then
        do j = 1, n
          swap = a(k, j)
          a(k, j) = a(p, j)
          a(p, j) = swap
        end do
        swap = b(k)
        b(k) = b(p)
        b(p) = swap
      end if
      if (abs(a(k, k)) >= tiny(1.0_wp)) then
        reciprocal = 1/a(k, k)
        a(k + 1:n, k) = a(k + 1:n, k)*reciprocal
      else
        a(k + 1:n, k) = a(k + 1:n, k)/a(k, k)
      end if
      do i = k + 1, n
        b(i) = b(i) - b(k)*a(i, k)
      end do
      do j = k + 1, n
        do i = k + 1, n
          a(i, j) = a(i, j) - a(i, k)*a(k, j)
        end do
      end do
    end do
    do k = n, 1, -1
      if (b(k) == 0) cycle
      b(k) = b(k)/a(k, k)
      do i = 1, k - 1
        b(i) = b(i) - b(k)*a(i, k)
      end do
    end do
  end subroutine small_lu_solve

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
