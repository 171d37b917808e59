!> The fold and Hopf defining systems of equilibria of a two_parameter_field (the header of
!> sloshdyn_bifurcation gives the systems and their test functions): the minimally augmented
!> fold system on J + shift I (also a map's period doubling, sloshdyn_map_bifurcation) and the
!> standard Hopf system in kappa = omega^2, each with its border / reference refresh, test
!> functions and codimension-2 bookkeeping.
module sloshdyn_fold_hopf
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_value, ieee_quiet_nan
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_SINGULAR
  use sloshdyn_text, only: num2str
  use sloshdyn_lapack, only: eigenvalues, solve_linear
  use sloshdyn_bifurcation, only: curve_system, max_curve_tests, split_x_p, point_x_p, &
                                  nearest_pair, CODIM2_ZH, CODIM2_GH
  use sloshdyn_lyapunov_coefficient, only: lyapunov_core
  implicit none
  private
  public :: fold_system, hopf_system, bordered_vectors

  !> The minimally augmented fold system (module header) on the matrix J + shift I (shift = 0:
  !> folds; a map's period doubling is a fold system on M + I = (M - I) + 2 I).
  type, extends(curve_system) :: fold_system
    real(wp), allocatable :: b(:), c(:)   !< border vectors
    real(wp) :: shift = 0
  contains
    procedure :: evaluate => fold_evaluate
    procedure :: refresh => fold_refresh
    procedure :: diagnose => fold_diagnose
    procedure :: alignment => fold_alignment
    !> the unit null vectors v, w of the bordered matrix at J (for the tests)
    procedure :: null_vectors => fold_null_vectors
    procedure :: confirm_codim2 => fold_confirm
    procedure :: codim2_frequency => fold_codim2_frequency
  end type fold_system

  type, extends(curve_system) :: hopf_system
    real(wp), allocatable :: v_ref(:), u_ref(:)   !< orthonormal basis of the eigenplane
    real(wp) :: kappa_scale = 1
  contains
    procedure :: evaluate => hopf_evaluate
    procedure :: refresh => hopf_refresh
    procedure :: diagnose => hopf_diagnose
    procedure :: alignment => hopf_alignment
    procedure :: confirm_codim2 => hopf_confirm
    procedure :: codim2_frequency => hopf_codim2_frequency
    procedure :: neutral_saddle => hopf_neutral_saddle
    procedure :: frequency_of => hopf_frequency_of
  end type hopf_system

  !> Relative size (to max|eigenvalue|) below which a real part counts as zero, and above which
  !> an imaginary part counts as nonzero, when a zero-Hopf point is confirmed.
  real(wp), parameter :: axis_tol = 1.0e-6_wp

contains

  ! ---- the fold system ----------------------------------------------------------------------

  !> F = (f, g) with the bordered g; see the module header.
  subroutine fold_evaluate(self, x, lambda, f, fx, flambda)
    class(fold_system), intent(in) :: self
    real(wp), intent(in) :: x(:), lambda
    real(wp), intent(out) :: f(:), fx(:, :), flambda(:)
    real(wp) :: xx(self%n), p(2), ff(self%n), jj(self%n, self%n), fp(self%n, 2), v(self%n), &
                w(self%n), g, hx(self%n, self%n), hp(self%n, 2)
    integer :: n, info, o, l

    n = self%n
    o = self%other
    l = self%lam
    call split_x_p(self, x, lambda, xx, p)
    call self%field%evaluate(xx, p, ff, jj, fp)
    call bordered_vectors(jj, self%b, self%c, v, w, g, info, self%shift)
    if (info /= SD_OK) then
      f = ieee_value(1.0_wp, ieee_quiet_nan)
      fx = 0
      flambda = 0
      return
    end if
    call self%field%jacobian_derivative(xx, p, v, hx, hp)
    f(1:n) = ff
    f(n + 1) = g
    fx(1:n, 1:n) = jj*self%x_scale
    fx(1:n, n + 1) = fp(:, o)*self%p_scale(o)
    ! d(J + shift I)v/dx = d(J v)/dx
    fx(n + 1, 1:n) = -matmul(w, hx)*self%x_scale
    fx(n + 1, n + 1) = -sum(w*hp(:, o))*self%p_scale(o)
    flambda(1:n) = fp(:, l)*self%p_scale(l)
    flambda(n + 1) = -sum(w*hp(:, l))*self%p_scale(l)
  end subroutine fold_evaluate

  !> New borders: the current null vectors v, w (unit), so <c, v> = 1 and <b, w> = 1 keep the
  !> orientation of v and w from one segment to the next.
  subroutine fold_refresh(self, s, status, message)
    class(fold_system), intent(inout) :: self
    real(wp), intent(inout) :: s(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: ff(self%n), jj(self%n, self%n), fp(self%n, 2), v(self%n), w(self%n), g
    integer :: n
    n = self%n
    call self%field%evaluate(s(1:n), s(n + 1:n + 2), ff, jj, fp)
    call bordered_vectors(jj, self%b, self%c, v, w, g, status, self%shift)
    message = ''
    if (status /= SD_OK) then
      message = 'the bordered Jacobian is singular at p = ('//num2str(s(n + 1))//', '// &
                num2str(s(n + 2))//'): the null space of df/dx + shift I has dimension > 1 '// &
                '(shift = '//num2str(self%shift)//')'
      return
    end if
    self%c = v/norm2(v)
    self%b = w/norm2(w)
  end subroutine fold_refresh

  !> Tests (BT, cusp, ZH); see the module header.
  subroutine fold_diagnose(self, z, re, im, tests, omega, l1, status, message)
    class(fold_system), intent(in) :: self
    real(wp), intent(in) :: z(:)
    real(wp), intent(out) :: re(:), im(:), tests(max_curve_tests), omega, l1
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: xx(self%n), p(2), ff(self%n), jj(self%n, self%n), fp(self%n, 2), v(self%n), &
                w(self%n), bvv(self%n)

    tests = ieee_value(1.0_wp, ieee_quiet_nan)
    omega = 0
    l1 = ieee_value(1.0_wp, ieee_quiet_nan)
    call point_x_p(self, z, xx, p)
    call self%field%evaluate(xx, p, ff, jj, fp)
    call eigenvalues(jj, re, im, status, message)
    if (status /= SD_OK) return
    call self%null_vectors(jj, v, w, status, message)
    if (status /= SD_OK) return
    call self%field%second_derivative(xx, p, v, v, bvv)
    tests(1) = sum(w*v)
    tests(2) = sum(w*bvv)
    tests(3) = pair_sum_product(re, im)
  end subroutine fold_diagnose

  !> max(|v|, |w|) with <c, v> = <b, w> = 1 and unit borders.
  function fold_alignment(self, z) result(growth)
    class(fold_system), intent(in) :: self
    real(wp), intent(in) :: z(:)
    real(wp) :: growth
    real(wp) :: xx(self%n), p(2), ff(self%n), jj(self%n, self%n), fp(self%n, 2), v(self%n), &
                w(self%n), g
    integer :: info
    call point_x_p(self, z, xx, p)
    call self%field%evaluate(xx, p, ff, jj, fp)
    call bordered_vectors(jj, self%b, self%c, v, w, g, info, self%shift)
    growth = huge(1.0_wp)
    if (info == SD_OK) growth = max(norm2(v), norm2(w))
  end function fold_alignment

  subroutine fold_null_vectors(self, jj, v, w, status, message)
    class(fold_system), intent(in) :: self
    real(wp), intent(in) :: jj(:, :)
    real(wp), intent(out) :: v(:), w(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: g
    message = ''
    call bordered_vectors(jj, self%b, self%c, v, w, g, status, self%shift)
    if (status /= SD_OK) then
      message = 'the bordered matrix is singular'
      return
    end if
    v = v/norm2(v)
    w = w/norm2(w)
  end subroutine fold_null_vectors

  !> v, w and g of the bordered systems [J b; c^T 0] (v; g) = e and its transpose (J + shift I
  !> in place of J with shift).
  subroutine bordered_vectors(jj, b, c, v, w, g, status, shift)
    real(wp), intent(in) :: jj(:, :), b(:), c(:)
    real(wp), intent(out) :: v(:), w(:), g
    integer, intent(out) :: status
    real(wp), intent(in), optional :: shift
    real(wp) :: a(size(b) + 1, size(b) + 1), r(size(b) + 1)
    integer :: n, i
    character(len=message_len) :: message
    n = size(b)
    a(1:n, 1:n) = jj
    if (present(shift)) then
      do i = 1, n
        a(i, i) = a(i, i) + shift
      end do
    end if
    a(1:n, n + 1) = b
    a(n + 1, 1:n) = c
    a(n + 1, n + 1) = 0
    r = 0
    r(n + 1) = 1
    call solve_linear(a, r, status, message)
    v = r(1:n)
    g = r(n + 1)
    if (status /= SD_OK) return
    r = 0
    r(n + 1) = 1
    call solve_linear(transpose(a), r, status, message)
    w = r(1:n)
    if (status == SD_OK .and. .not. (all(ieee_is_finite(v)) .and. all(ieee_is_finite(w)))) &
      status = SD_SINGULAR
  end subroutine bordered_vectors

  !> prod_{i<j} (mu_i + mu_j) over the eigenvalues mu but the one of smallest modulus (real).
  pure real(wp) function pair_sum_product(re, im) result(product_value)
    real(wp), intent(in) :: re(:), im(:)
    complex(wp) :: mu(size(re)), prod
    integer :: i, j, skip
    mu = cmplx(re, im, wp)
    skip = minloc(abs(mu), 1)
    prod = 1
    do i = 1, size(mu)
      if (i == skip) cycle
      do j = i + 1, size(mu)
        if (j == skip) cycle
        prod = prod*(mu(i) + mu(j))
      end do
    end do
    product_value = real(prod)
  end function pair_sum_product

  ! ---- the Hopf system ----------------------------------------------------------------------

  !> F = (f, (J^2 + kappa I) v/kappa_scale, <v_ref, v> - 1, <u_ref, v>); z = (x/x_scale, v,
  !> kappa/kappa_scale, q_other).
  subroutine hopf_evaluate(self, x, lambda, f, fx, flambda)
    class(hopf_system), intent(in) :: self
    real(wp), intent(in) :: x(:), lambda
    real(wp), intent(out) :: f(:), fx(:, :), flambda(:)
    real(wp) :: xx(self%n), p(2), ff(self%n), jj(self%n, self%n), fp(self%n, 2), v(self%n), &
                jv(self%n), kappa, ks, hxv(self%n, self%n), hpv(self%n, 2), &
                hxjv(self%n, self%n), hpjv(self%n, 2)
    integer :: n, o, l, i

    n = self%n
    o = self%other
    l = self%lam
    ks = self%kappa_scale
    call split_x_p(self, x, lambda, xx, p)
    v = x(n + 1:2*n)
    kappa = ks*x(2*n + 1)
    call self%field%evaluate(xx, p, ff, jj, fp)
    jv = matmul(jj, v)
    call self%field%jacobian_derivative(xx, p, v, hxv, hpv)
    call self%field%jacobian_derivative(xx, p, jv, hxjv, hpjv)
    f(1:n) = ff
    f(n + 1:2*n) = (matmul(jj, jv) + kappa*v)/ks
    f(2*n + 1) = sum(self%v_ref*v) - 1
    f(2*n + 2) = sum(self%u_ref*v)
    fx = 0
    fx(1:n, 1:n) = jj*self%x_scale
    fx(1:n, 2*n + 2) = fp(:, o)*self%p_scale(o)
    fx(n + 1:2*n, 1:n) = (hxjv + matmul(jj, hxv))*(self%x_scale/ks)
    fx(n + 1:2*n, n + 1:2*n) = matmul(jj, jj)/ks
    do i = 1, n
      fx(n + i, n + i) = fx(n + i, n + i) + kappa/ks
    end do
    fx(n + 1:2*n, 2*n + 1) = v
    fx(n + 1:2*n, 2*n + 2) = (hpjv(:, o) + matmul(jj, hpv(:, o)))*(self%p_scale(o)/ks)
    fx(2*n + 1, n + 1:2*n) = self%v_ref
    fx(2*n + 2, n + 1:2*n) = self%u_ref
    flambda = 0
    flambda(1:n) = fp(:, l)*self%p_scale(l)
    flambda(n + 1:2*n) = (hpjv(:, l) + matmul(jj, hpv(:, l)))*(self%p_scale(l)/ks)
  end subroutine hopf_evaluate

  !> New reference vectors: v_ref = v/|v|, u_ref = the unit part of J v orthogonal to v_ref; v
  !> in the state becomes v_ref (so <v_ref, v> = 1, <u_ref, v> = 0 hold).
  subroutine hopf_refresh(self, s, status, message)
    class(hopf_system), intent(inout) :: self
    real(wp), intent(inout) :: s(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: ff(self%n), jj(self%n, self%n), fp(self%n, 2), v(self%n), u(self%n)
    integer :: n
    n = self%n
    status = SD_OK
    message = ''
    call self%field%evaluate(s(1:n), s(2*n + 2:2*n + 3), ff, jj, fp)
    v = s(n + 1:2*n)
    if (.not. norm2(v) > 0) then
      status = SD_SINGULAR
      message = 'the eigenvector of the Hopf system vanished'
      return
    end if
    v = v/norm2(v)
    u = matmul(jj, v)
    u = u - sum(u*v)*v
    if (.not. norm2(u) > 0) then
      status = SD_SINGULAR
      message = 'J v is parallel to v at p = ('//num2str(s(2*n + 2))//', '// &
                num2str(s(2*n + 3))//'): no eigenplane of a complex pair (or kappa = 0 exactly)'
      return
    end if
    self%v_ref = v
    self%u_ref = u/norm2(u)
    s(n + 1:2*n) = v
  end subroutine hopf_refresh

  !> |v| with <v_ref, v> = 1.
  function hopf_alignment(self, z) result(growth)
    class(hopf_system), intent(in) :: self
    real(wp), intent(in) :: z(:)
    real(wp) :: growth
    growth = norm2(z(self%n + 1:2*self%n))
  end function hopf_alignment

  !> Tests (BT = kappa, ZH = det J, GH = l1); omega = sign(kappa) sqrt|kappa|.
  subroutine hopf_diagnose(self, z, re, im, tests, omega, l1, status, message)
    class(hopf_system), intent(in) :: self
    real(wp), intent(in) :: z(:)
    real(wp), intent(out) :: re(:), im(:), tests(max_curve_tests), omega, l1
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: xx(self%n), p(2), ff(self%n), jj(self%n, self%n), fp(self%n, 2), kappa
    complex(wp) :: det
    integer :: n, i

    n = self%n
    tests = ieee_value(1.0_wp, ieee_quiet_nan)
    l1 = ieee_value(1.0_wp, ieee_quiet_nan)
    call point_x_p(self, z, xx, p)
    kappa = self%kappa_scale*z(2*n + 1)
    omega = sign(sqrt(abs(kappa)), kappa)
    call self%field%evaluate(xx, p, ff, jj, fp)
    call eigenvalues(jj, re, im, status, message)
    if (status /= SD_OK) return
    det = 1
    do i = 1, n
      det = det*cmplx(re(i), im(i), wp)
    end do
    tests(1) = kappa
    tests(2) = real(det)
    if (kappa > 0) then
      call lyapunov_core(self%field, xx, p, jj, z(n + 1:2*n), omega, l1, status, message)
      if (status /= SD_OK) then
        status = SD_OK   ! a point where l1 fails (J singular: zero-Hopf) keeps l1 = NaN
        message = ''
        l1 = ieee_value(1.0_wp, ieee_quiet_nan)
      end if
      tests(3) = l1
    end if
  end subroutine hopf_diagnose



  !> Zero-Hopf on a fold curve needs a pair on the imaginary axis (not a real pair +-mu).
  logical function fold_confirm(self, kind, re, im, tests) result(confirmed)
    class(fold_system), intent(in) :: self
    integer, intent(in) :: kind
    real(wp), intent(in) :: re(:), im(:), tests(:)
    real(wp) :: scale
    integer :: i
    confirmed = .true.
    if (kind /= CODIM2_ZH) return
    scale = max(maxval(abs(cmplx(re, im, wp))), tiny(1.0_wp))
    confirmed = .false.
    do i = 1, size(re)
      if (abs(re(i)) <= axis_tol*scale .and. abs(im(i)) > axis_tol*scale) confirmed = .true.
    end do
  end function fold_confirm

  !> The imaginary eigenvalue of a zero-Hopf point on a fold curve.
  real(wp) function fold_codim2_frequency(self, kind, re, im, omega) result(frequency)
    class(fold_system), intent(in) :: self
    integer, intent(in) :: kind
    real(wp), intent(in) :: re(:), im(:), omega
    integer :: best
    frequency = 0
    if (kind /= CODIM2_ZH) return
    best = nearest_pair(im, abs(re), 0.0_wp, huge(1.0_wp))
    if (best > 0) frequency = im(best)
  end function fold_codim2_frequency


  !> Zero-Hopf and generalised Hopf need kappa > 0 (det J also vanishes at the
  !> Bogdanov-Takens point).
  logical function hopf_confirm(self, kind, re, im, tests) result(confirmed)
    class(hopf_system), intent(in) :: self
    integer, intent(in) :: kind
    real(wp), intent(in) :: re(:), im(:), tests(:)
    real(wp) :: scale
    confirmed = .true.
    if (kind /= CODIM2_ZH .and. kind /= CODIM2_GH) return
    scale = max(maxval(abs(cmplx(re, im, wp))), tiny(1.0_wp))
    confirmed = tests(1) > axis_tol*scale**2
  end function hopf_confirm

  real(wp) function hopf_codim2_frequency(self, kind, re, im, omega) result(frequency)
    class(hopf_system), intent(in) :: self
    integer, intent(in) :: kind
    real(wp), intent(in) :: re(:), im(:), omega
    frequency = 0
    if (kind == CODIM2_GH .or. kind == CODIM2_ZH) frequency = omega
  end function hopf_codim2_frequency

  !> A Hopf point has kappa > 0; else it is a neutral saddle.
  function hopf_neutral_saddle(self, s) result(saddle)
    class(hopf_system), intent(in) :: self
    real(wp), intent(in) :: s(:)
    character(len=:), allocatable :: saddle
    saddle = ''
    if (.not. s(2*self%n + 1) > 0) saddle = 'a neutral saddle (real eigenvalues +-mu, kappa = '// &
      num2str(s(2*self%n + 1)*self%kappa_scale)//' < 0)'
  end function hopf_neutral_saddle

  real(wp) function hopf_frequency_of(self, s) result(frequency)
    class(hopf_system), intent(in) :: self
    real(wp), intent(in) :: s(:)
    frequency = sqrt(max(s(2*self%n + 1)*self%kappa_scale, 0.0_wp))
  end function hopf_frequency_of
end module sloshdyn_fold_hopf
