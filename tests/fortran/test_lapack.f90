!> The LAPACK wrappers never let a bad value end the process: NaN or infinite matrices are
!> refused with a status, results that are not finite are an error, and the project's XERBLA
!> returns (LAPACK's reference XERBLA would stop the program: this test would not finish).
program test_lapack
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_positive_inf
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_NON_FINITE
  use sloshdyn_lapack, only: eigenvalues, solve_linear, dgeev, dgesv
  use checks, only: check_true, check_close, finish
  implicit none

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
  call test_small_systems_as_dgesv()
  call finish()

contains

  !> solve_linear solves systems of up to 8 unknowns without calling dgesv, by dgesv's own
  !> operations in its order: its answers must be dgesv's to the bit (random systems, and
  !> columns of equal entries, where the pivot choice breaks ties), and a zero pivot is
  !> refused as dgesv's info > 0 is.
  subroutine test_small_systems_as_dgesv()
    real(wp) :: m(8, 8), rhs(8), x(8), lu(8, 8), worst
    integer :: n, trial, pivots(8), info_lapack, status_ours
    character(len=message_len) :: msg
    logical :: same_status

    worst = 0
    same_status = .true.
    do trial = 1, 300
      do n = 1, 8
        call random_number(m(1:n, 1:n))
        m(1:n, 1:n) = m(1:n, 1:n) - 0.5_wp
        if (mod(trial, 3) == 0) m(1:n, 1) = 0.5_wp
        call random_number(rhs(1:n))
        x(1:n) = rhs(1:n)
        call solve_linear(m(1:n, 1:n), x(1:n), status_ours, msg)
        lu(1:n, 1:n) = m(1:n, 1:n)
        call dgesv(n, 1, lu, 8, pivots, rhs, 8, info_lapack)
        same_status = same_status .and. ((status_ours == SD_OK) .eqv. (info_lapack == 0))
        if (status_ours == SD_OK) worst = max(worst, maxval(abs(x(1:n) - rhs(1:n))))
      end do
    end do
    call check_true('systems of 1..8 unknowns: solve_linear = dgesv to the bit', worst == 0)
    call check_true('... and the same verdict on singularity', same_status)
    m(1:3, 1:3) = reshape([1.0_wp, 2.0_wp, 3.0_wp, 2.0_wp, 4.0_wp, 6.0_wp, 0.0_wp, 1.0_wp, &
                           1.0_wp], [3, 3])
    x(1:3) = 1
    call solve_linear(m(1:3, 1:3), x(1:3), status_ours, msg)
    call check_true('a singular 3x3 system is refused: '//trim(msg), status_ours /= SD_OK)
  end subroutine test_small_systems_as_dgesv
end program test_lapack
