!> Hopf points of equilibria of a two_parameter_field and their first Lyapunov coefficient l1
!> (Kuznetsov's formula, in the header of sloshdyn_bifurcation): the complex pair of J closest to
!> the imaginary axis with a real vector of its eigenplane (the start of a Hopf curve), and l1
!> from J, that vector and the field's second and third derivatives.
module sloshdyn_lyapunov_coefficient
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_value, ieee_quiet_nan
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, SD_SINGULAR
  use sloshdyn_text, only: num2str
  use sloshdyn_lapack, only: eigenvalues, solve_linear
  use sloshdyn_bifurcation, only: two_parameter_field, inverse_iteration, nearest_pair
  implicit none
  private
  public :: hopf_start, lyapunov_core

contains


  !> J at (x, p), omega of the complex pair closest to the imaginary axis, and a real vector v
  !> of its eigenplane (inverse iteration on J^2 + omega^2 I).
  subroutine hopf_start(field, x, p, jj, omega, v, status, message)
    class(two_parameter_field), intent(in) :: field
    real(wp), intent(in) :: x(:), p(2)
    real(wp), intent(out) :: jj(:, :), omega, v(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: f(size(x)), fp(size(x), 2), re(size(x)), im(size(x)), a(size(x), size(x))
    integer :: i, best

    omega = 0
    v = 0
    call field%evaluate(x, p, f, jj, fp)
    call eigenvalues(jj, re, im, status, message)
    if (status /= SD_OK) return
    best = nearest_pair(im, abs(re), 0.0_wp, huge(1.0_wp))
    if (best == 0) then
      status = SD_BAD_INPUT
      message = 'df/dx has no complex eigenvalue pair at p = ('//num2str(p(1))//', '// &
                num2str(p(2))//'): not near a Hopf point'
      return
    end if
    omega = im(best)
    a = matmul(jj, jj)
    do i = 1, size(x)
      a(i, i) = a(i, i) + omega**2
    end do
    call inverse_iteration(a, max(maxval(abs(jj))**2, omega**2), v, status, message)
  end subroutine hopf_start

  !> A unit vector near the null space of the nearly singular a: inverse iteration with a tiny

  !> l1 at a Hopf point with J = df/dx, omega > 0 and v in the real eigenplane (module header).
  subroutine lyapunov_core(field, x, p, jj, v, omega, l1, status, message)
    class(two_parameter_field), intent(in) :: field
    real(wp), intent(in) :: x(:), p(2), jj(:, :), v(:), omega
    real(wp), intent(out) :: l1
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: qr(size(x)), qi(size(x)), pr(size(x)), pi_(size(x)), ar(size(x) + 1, size(x) + 1), &
                ai(size(x) + 1, size(x) + 1), br(size(x) + 1), bi(size(x) + 1), &
                b1(size(x)), b2(size(x)), b3(size(x)), h11(size(x)), h20r(size(x)), &
                h20i(size(x)), tr(size(x)), ti(size(x)), c1(size(x)), c2(size(x)), &
                a2r(size(x), size(x)), a2i(size(x), size(x)), scale
    integer :: n, i

    n = size(x)
    l1 = ieee_value(1.0_wp, ieee_quiet_nan)
    ! q = v - i J v/omega, |q| = 1: J q = i omega q
    qr = v
    qi = -matmul(jj, v)/omega
    scale = sqrt(sum(qr**2) + sum(qi**2))
    qr = qr/scale
    qi = qi/scale
    ! p: [J^T + i omega I, q; q^H, 0] (p; s) = (0; 1), so q^H p = 1 = <p, q>
    ar = 0
    ai = 0
    ar(1:n, 1:n) = transpose(jj)
    do i = 1, n
      ai(i, i) = omega
    end do
    ar(1:n, n + 1) = qr
    ai(1:n, n + 1) = qi
    ar(n + 1, 1:n) = qr
    ai(n + 1, 1:n) = -qi
    br = 0
    br(n + 1) = 1
    bi = 0
    call solve_complex(ar, ai, br, bi, status, message)
    if (status /= SD_OK) return
    pr = br(1:n)
    pi_ = bi(1:n)
    ! h11 = J^-1 B(q, conj q), B(q, conj q) = B(qr, qr) + B(qi, qi)
    call field%second_derivative(x, p, qr, qr, b1)
    call field%second_derivative(x, p, qi, qi, b2)
    h11 = b1 + b2
    call solve_linear(jj, h11, status, message)
    if (status /= SD_OK) then
      message = 'J is singular at the Hopf point (a zero-Hopf point): '//trim(message)
      return
    end if
    ! h20 = (2 i omega I - J)^-1 B(q, q), B(q, q) = B(qr, qr) - B(qi, qi) + 2 i B(qr, qi)
    call field%second_derivative(x, p, qr, qi, b3)
    h20r = b1 - b2
    h20i = 2*b3
    a2r = -jj
    a2i = 0
    do i = 1, n
      a2i(i, i) = 2*omega
    end do
    call solve_complex(a2r, a2i, h20r, h20i, status, message)
    if (status /= SD_OK) return
    ! C(q, q, conj q) = C(qr, qr, qr) + C(qr, qi, qi) + i (C(qr, qr, qi) + C(qi, qi, qi))
    call field%third_derivative(x, p, qr, qr, qr, c1)
    call field%third_derivative(x, p, qr, qi, qi, c2)
    tr = c1 + c2
    call field%third_derivative(x, p, qr, qr, qi, c1)
    call field%third_derivative(x, p, qi, qi, qi, c2)
    ti = c1 + c2
    ! - 2 B(q, h11) = -2 (B(qr, h11) + i B(qi, h11))
    call field%second_derivative(x, p, qr, h11, b1)
    call field%second_derivative(x, p, qi, h11, b2)
    tr = tr - 2*b1
    ti = ti - 2*b2
    ! + B(conj q, h20) = B(qr, h20r) + B(qi, h20i) + i (B(qr, h20i) - B(qi, h20r))
    call field%second_derivative(x, p, qr, h20r, b1)
    call field%second_derivative(x, p, qi, h20i, b2)
    tr = tr + b1 + b2
    call field%second_derivative(x, p, qr, h20i, b1)
    call field%second_derivative(x, p, qi, h20r, b2)
    ti = ti + b1 - b2
    ! Re <p, t> = Re conj(p)^T t
    l1 = (sum(pr*tr) + sum(pi_*ti))/(2*omega)
    if (.not. ieee_is_finite(l1)) then
      status = SD_SINGULAR
      message = 'l1 is not finite'
    end if
  end subroutine lyapunov_core

  !> Solve (ar + i ai)(xr + i xi) = br + i bi in real arithmetic; x overwrites b.
  subroutine solve_complex(ar, ai, br, bi, status, message)
    real(wp), intent(in) :: ar(:, :), ai(:, :)
    real(wp), intent(inout) :: br(:), bi(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: a(2*size(br), 2*size(br)), r(2*size(br))
    integer :: n
    n = size(br)
    a(1:n, 1:n) = ar
    a(1:n, n + 1:2*n) = -ai
    a(n + 1:2*n, 1:n) = ai
    a(n + 1:2*n, n + 1:2*n) = ar
    r = [br, bi]
    call solve_linear(a, r, status, message)
    if (status /= SD_OK) return
    br = r(1:n)
    bi = r(n + 1:2*n)
  end subroutine solve_complex
end module sloshdyn_lyapunov_coefficient
