!> Normal forms with closed-form bifurcation sets, the independent source of every expected value.
!> Each field gives its derivatives exactly (they are polynomials), except fd_cm_example, which
!> leaves the higher derivatives to the finite-difference defaults.
module bifurcation_test_fields
  use sloshdyn_kinds, only: wp
  use sloshdyn_bifurcation, only: two_parameter_field
  implicit none
  private
  public :: hopf_normal_form, bt_normal_form, cusp_normal_form, bautin_normal_form, &
            fold_hopf_normal_form, cm_example, fd_cm_example, circle_hopf, walled_bt

  !> x' = b x - omega y + l x r^2, y' = omega x + b y + l y r^2, p = (b, l). In z = x + i y:
  !> z' = (b + i omega) z + l z |z|^2.
  type, extends(two_parameter_field) :: hopf_normal_form
    real(wp) :: omega = 1
  contains
    procedure :: evaluate => hopf_evaluate
    procedure :: jacobian_derivative => hopf_jd
    procedure :: third_derivative => hopf_c
  end type hopf_normal_form

  !> Bogdanov-Takens: x' = y, y' = b1 + b2 x + x^2 + s x y, p = (b1, b2).
  type, extends(two_parameter_field) :: bt_normal_form
    real(wp) :: s = -1
  contains
    procedure :: evaluate => bt_evaluate
    procedure :: jacobian_derivative => bt_jd
    procedure :: third_derivative => bt_c
  end type bt_normal_form

  !> The BT normal form, undefined (NaN) beyond b2 = wall: a curve that cannot be finished.
  type, extends(bt_normal_form) :: walled_bt
    real(wp) :: wall = 0.7_wp
  contains
    procedure :: evaluate => walled_evaluate
  end type walled_bt

  !> Cusp: x' = b1 + b2 x - x^3, p = (b1, b2).
  type, extends(two_parameter_field) :: cusp_normal_form
  contains
    procedure :: evaluate => cusp_evaluate
    procedure :: jacobian_derivative => cusp_jd
    procedure :: third_derivative => cusp_c
  end type cusp_normal_form

  !> Bautin (truncated at third order; the fifth-order term changes neither the Hopf curve nor
  !> l1): z' = (mu + i omega) z + L z |z|^2 with mu = p1 - p2^2, omega = 1 + p2/2,
  !> L = p2 - l_zero: Hopf curve p1 = p2^2, l1 = 2 L/omega, generalised Hopf at p2 = l_zero.
  type, extends(two_parameter_field) :: bautin_normal_form
    real(wp) :: l_zero = 0.3_wp
  contains
    procedure :: evaluate => bautin_evaluate
    procedure :: jacobian_derivative => bautin_jd
    procedure :: third_derivative => bautin_c
  end type bautin_normal_form

  !> Fold-Hopf (zero-Hopf): u' = b1 + u^2 + s (y^2 + z^2), zeta' = (b2 - c + i omega) zeta
  !> + (theta + i vartheta) u zeta, zeta = y + i z, p = (b1, b2). Fold curve b1 = 0 (zero-Hopf
  !> at b2 = c); Hopf curve u = -(b2 - c)/theta, b1 = -u^2.
  type, extends(two_parameter_field) :: fold_hopf_normal_form
    real(wp) :: s = -1, c = 0.2_wp, omega = 1, theta = 2, vartheta = 0.3_wp
  contains
    procedure :: evaluate => fh_evaluate
    procedure :: jacobian_derivative => fh_jd
    procedure :: third_derivative => fh_c
  end type fold_hopf_normal_form

  !> A 3-D field whose Hopf point needs the centre-manifold reduction:
  !> x' = p1 x - omega y + p2 x z, y' = omega x, z' = -mu z + 2 (1 - cos x) + y^2.
  !> On the centre manifold z = (x^2 + y^2)/mu + O(3) (2 (1 - cos x) = x^2 + O(4)), so at p1 = 0
  !> x' = -omega y + (p2/mu) x r^2, y' = omega x: Guckenheimer-Holmes' planar formula gives
  !> a = p2/(2 mu), and l1 = 2 a/omega = p2/(mu omega) for unit q (the module's normalisation).
  !> fd_cm_example is the same field with the finite-difference higher derivatives.
  type, extends(two_parameter_field) :: fd_cm_example
    real(wp) :: omega = 1.3_wp, mu = 0.7_wp
  contains
    procedure :: evaluate => cm_evaluate
  end type fd_cm_example

  !> z' = (mu + i omega) z - z|z|^2, mu = 1/4 - p1^2 - p2^2: a closed Hopf curve, l1 = -2/omega.
  type, extends(two_parameter_field) :: circle_hopf
    real(wp) :: omega = 1.5_wp
  contains
    procedure :: evaluate => circle_evaluate
    procedure :: jacobian_derivative => circle_jd
    procedure :: third_derivative => circle_c
  end type circle_hopf

  type, extends(fd_cm_example) :: cm_example
  contains
    procedure :: jacobian_derivative => cm_jd
    procedure :: third_derivative => cm_c
  end type cm_example

contains

  ! ---- Hopf normal form ----

  subroutine hopf_evaluate(self, x, p, f, fx, fp)
    class(hopf_normal_form), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2)
    real(wp), intent(out) :: f(:), fx(:, :), fp(:, :)
    real(wp) :: r2
    r2 = x(1)**2 + x(2)**2
    f(1) = p(1)*x(1) - self%omega*x(2) + p(2)*x(1)*r2
    f(2) = self%omega*x(1) + p(1)*x(2) + p(2)*x(2)*r2
    fx(1, :) = [p(1) + p(2)*(3*x(1)**2 + x(2)**2), -self%omega + 2*p(2)*x(1)*x(2)]
    fx(2, :) = [self%omega + 2*p(2)*x(1)*x(2), p(1) + p(2)*(x(1)**2 + 3*x(2)**2)]
    fp(:, 1) = x
    fp(:, 2) = x*r2
  end subroutine hopf_evaluate

  !> The cubic T(x) = |x|^2 x: DT[u] = 2 (x.u) x + |x|^2 u, D^2T[u, v] = 2 ((u.v) x + (x.u) v
  !> + (x.v) u), D^3T[u, v, w] = 2 ((u.v) w + (u.w) v + (v.w) u).
  pure function cubic_hx(x, u) result(hx)
    real(wp), intent(in) :: x(:), u(:)
    real(wp) :: hx(size(x), size(x))
    integer :: i
    hx = 2*(spread(x, 2, size(x))*spread(u, 1, size(x)) + spread(u, 2, size(x))* &
            spread(x, 1, size(x)))
    do i = 1, size(x)
      hx(i, i) = hx(i, i) + 2*sum(x*u)
    end do
  end function cubic_hx

  pure function cubic_c(u, v, w) result(c)
    real(wp), intent(in) :: u(:), v(:), w(:)
    real(wp) :: c(size(u))
    c = 2*(sum(u*v)*w + sum(u*w)*v + sum(v*w)*u)
  end function cubic_c

  subroutine hopf_jd(self, x, p, u, hx, hp)
    class(hopf_normal_form), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2), u(:)
    real(wp), intent(out) :: hx(:, :), hp(:, :)
    hx = p(2)*cubic_hx(x, u)
    hp(:, 1) = u
    hp(:, 2) = 2*sum(x*u)*x + sum(x*x)*u + 0*self%omega
  end subroutine hopf_jd

  subroutine hopf_c(self, x, p, u, v, w, c)
    class(hopf_normal_form), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2), u(:), v(:), w(:)
    real(wp), intent(out) :: c(:)
    c = p(2)*cubic_c(u, v, w) + 0*self%omega*x(1)
  end subroutine hopf_c

  ! ---- Bogdanov-Takens ----

  subroutine bt_evaluate(self, x, p, f, fx, fp)
    class(bt_normal_form), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2)
    real(wp), intent(out) :: f(:), fx(:, :), fp(:, :)
    f = [x(2), p(1) + p(2)*x(1) + x(1)**2 + self%s*x(1)*x(2)]
    fx(1, :) = [0.0_wp, 1.0_wp]
    fx(2, :) = [p(2) + 2*x(1) + self%s*x(2), self%s*x(1)]
    fp(1, :) = 0
    fp(2, :) = [1.0_wp, x(1)]
  end subroutine bt_evaluate

  subroutine walled_evaluate(self, x, p, f, fx, fp)
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    class(walled_bt), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2)
    real(wp), intent(out) :: f(:), fx(:, :), fp(:, :)
    call self%bt_normal_form%evaluate(x, p, f, fx, fp)
    if (p(2) > self%wall) f = ieee_value(1.0_wp, ieee_quiet_nan)
  end subroutine walled_evaluate

  subroutine bt_jd(self, x, p, u, hx, hp)
    class(bt_normal_form), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2), u(:)
    real(wp), intent(out) :: hx(:, :), hp(:, :)
    hx = 0
    hx(2, :) = [2*u(1) + self%s*u(2), self%s*u(1)] + 0*x(1)*p(1)
    hp = 0
    hp(2, 2) = u(1)
  end subroutine bt_jd

  subroutine bt_c(self, x, p, u, v, w, c)
    class(bt_normal_form), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2), u(:), v(:), w(:)
    real(wp), intent(out) :: c(:)
    c = 0*(x(1) + p(1) + u(1) + v(1) + w(1) + self%s)
  end subroutine bt_c

  subroutine fh_c(self, x, p, u, v, w, c)
    class(fold_hopf_normal_form), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2), u(:), v(:), w(:)
    real(wp), intent(out) :: c(:)
    c = 0*(x(1) + p(1) + u(1) + v(1) + w(1) + self%s)
  end subroutine fh_c

  ! ---- cusp ----

  subroutine cusp_evaluate(self, x, p, f, fx, fp)
    class(cusp_normal_form), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2)
    real(wp), intent(out) :: f(:), fx(:, :), fp(:, :)
    f(1) = p(1) + p(2)*x(1) - x(1)**3
    fx(1, 1) = p(2) - 3*x(1)**2
    fp(1, :) = [1.0_wp, x(1)]
  end subroutine cusp_evaluate

  subroutine cusp_jd(self, x, p, u, hx, hp)
    class(cusp_normal_form), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2), u(:)
    real(wp), intent(out) :: hx(:, :), hp(:, :)
    hx(1, 1) = -6*x(1)*u(1) + 0*p(1)
    hp(1, :) = [0.0_wp, u(1)]
  end subroutine cusp_jd

  subroutine cusp_c(self, x, p, u, v, w, c)
    class(cusp_normal_form), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2), u(:), v(:), w(:)
    real(wp), intent(out) :: c(:)
    c(1) = -6*u(1)*v(1)*w(1) + 0*(x(1) + p(1))
  end subroutine cusp_c

  ! ---- Bautin ----

  subroutine bautin_evaluate(self, x, p, f, fx, fp)
    class(bautin_normal_form), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2)
    real(wp), intent(out) :: f(:), fx(:, :), fp(:, :)
    real(wp) :: mu, omega, l, r2
    integer :: i
    mu = p(1) - p(2)**2
    omega = 1 + p(2)/2
    l = p(2) - self%l_zero
    r2 = sum(x**2)
    f = mu*x + omega*[-x(2), x(1)] + l*r2*x
    fx = l*(2*spread(x, 2, 2)*spread(x, 1, 2))
    do i = 1, 2
      fx(i, i) = fx(i, i) + mu + l*r2
    end do
    fx(1, 2) = fx(1, 2) - omega
    fx(2, 1) = fx(2, 1) + omega
    fp(:, 1) = x
    fp(:, 2) = -2*p(2)*x + [-x(2), x(1)]/2 + r2*x
  end subroutine bautin_evaluate

  subroutine bautin_jd(self, x, p, u, hx, hp)
    class(bautin_normal_form), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2), u(:)
    real(wp), intent(out) :: hx(:, :), hp(:, :)
    hx = (p(2) - self%l_zero)*cubic_hx(x, u)
    hp(:, 1) = u
    hp(:, 2) = -2*p(2)*u + [-u(2), u(1)]/2 + 2*sum(x*u)*x + sum(x*x)*u
  end subroutine bautin_jd

  subroutine bautin_c(self, x, p, u, v, w, c)
    class(bautin_normal_form), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2), u(:), v(:), w(:)
    real(wp), intent(out) :: c(:)
    c = (p(2) - self%l_zero)*cubic_c(u, v, w) + 0*x(1)
  end subroutine bautin_c

  ! ---- fold-Hopf ----

  subroutine fh_evaluate(self, x, p, f, fx, fp)
    class(fold_hopf_normal_form), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2)
    real(wp), intent(out) :: f(:), fx(:, :), fp(:, :)
    real(wp) :: a, w
    associate (u => x(1), y => x(2), z => x(3))
      a = p(2) - self%c + self%theta*u
      w = self%omega + self%vartheta*u
      f = [p(1) + u**2 + self%s*(y**2 + z**2), a*y - w*z, w*y + a*z]
      fx(1, :) = [2*u, 2*self%s*y, 2*self%s*z]
      fx(2, :) = [self%theta*y - self%vartheta*z, a, -w]
      fx(3, :) = [self%vartheta*y + self%theta*z, w, a]
      fp(:, 1) = [1.0_wp, 0.0_wp, 0.0_wp]
      fp(:, 2) = [0.0_wp, y, z]
    end associate
  end subroutine fh_evaluate

  subroutine fh_jd(self, x, p, u, hx, hp)
    class(fold_hopf_normal_form), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2), u(:)
    real(wp), intent(out) :: hx(:, :), hp(:, :)
    ! rows: (H_i u)^T with the constant Hessians H_i of f_i
    hx(1, :) = [2*u(1), 2*self%s*u(2), 2*self%s*u(3)]
    hx(2, :) = [self%theta*u(2) - self%vartheta*u(3), self%theta*u(1), -self%vartheta*u(1)]
    hx(3, :) = [self%vartheta*u(2) + self%theta*u(3), self%vartheta*u(1), self%theta*u(1)]
    hx = hx + 0*x(1)*p(1)
    hp(:, 1) = 0
    hp(:, 2) = [0.0_wp, u(2), u(3)]
  end subroutine fh_jd

  ! ---- circle Hopf ----

  subroutine circle_evaluate(self, x, p, f, fx, fp)
    class(circle_hopf), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2)
    real(wp), intent(out) :: f(:), fx(:, :), fp(:, :)
    real(wp) :: mu, r2
    integer :: i
    mu = 0.25_wp - p(1)**2 - p(2)**2
    r2 = sum(x**2)
    f = mu*x + self%omega*[-x(2), x(1)] - r2*x
    fx = -2*spread(x, 2, 2)*spread(x, 1, 2)
    do i = 1, 2
      fx(i, i) = fx(i, i) + mu - r2
    end do
    fx(1, 2) = fx(1, 2) - self%omega
    fx(2, 1) = fx(2, 1) + self%omega
    fp(:, 1) = -2*p(1)*x
    fp(:, 2) = -2*p(2)*x
  end subroutine circle_evaluate

  subroutine circle_jd(self, x, p, u, hx, hp)
    class(circle_hopf), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2), u(:)
    real(wp), intent(out) :: hx(:, :), hp(:, :)
    hx = -cubic_hx(x, u) + 0*self%omega
    hp(:, 1) = -2*p(1)*u
    hp(:, 2) = -2*p(2)*u
  end subroutine circle_jd

  subroutine circle_c(self, x, p, u, v, w, c)
    class(circle_hopf), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2), u(:), v(:), w(:)
    real(wp), intent(out) :: c(:)
    c = -cubic_c(u, v, w) + 0*(self%omega + x(1) + p(1))
  end subroutine circle_c

  ! ---- centre-manifold example ----

  subroutine cm_evaluate(self, x, p, f, fx, fp)
    class(fd_cm_example), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2)
    real(wp), intent(out) :: f(:), fx(:, :), fp(:, :)
    f = [p(1)*x(1) - self%omega*x(2) + p(2)*x(1)*x(3), self%omega*x(1), &
         -self%mu*x(3) + 2*(1 - cos(x(1))) + x(2)**2]
    fx(1, :) = [p(1) + p(2)*x(3), -self%omega, p(2)*x(1)]
    fx(2, :) = [self%omega, 0.0_wp, 0.0_wp]
    fx(3, :) = [2*sin(x(1)), 2*x(2), -self%mu]
    fp(:, 1) = [x(1), 0.0_wp, 0.0_wp]
    fp(:, 2) = [x(1)*x(3), 0.0_wp, 0.0_wp]
  end subroutine cm_evaluate

  subroutine cm_jd(self, x, p, u, hx, hp)
    class(cm_example), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2), u(:)
    real(wp), intent(out) :: hx(:, :), hp(:, :)
    hx(1, :) = [p(2)*u(3), 0.0_wp, p(2)*u(1)]
    hx(2, :) = 0
    hx(3, :) = [2*cos(x(1))*u(1), 2*u(2), 0.0_wp] + 0*self%mu
    hp(:, 1) = [u(1), 0.0_wp, 0.0_wp]
    hp(:, 2) = [x(3)*u(1) + x(1)*u(3), 0.0_wp, 0.0_wp]
  end subroutine cm_jd

  subroutine cm_c(self, x, p, u, v, w, c)
    class(cm_example), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2), u(:), v(:), w(:)
    real(wp), intent(out) :: c(:)
    c = [0.0_wp, 0.0_wp, -2*sin(x(1))*u(1)*v(1)*w(1)] + 0*(p(1) + self%mu)
  end subroutine cm_c
end module bifurcation_test_fields

program test_bifurcation
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, SD_CAPACITY
  use sloshdyn_bifurcation, only: two_parameter_field, curve_options, bifurcation_curve, &
                                  fold_curve, hopf_curve, first_lyapunov_coefficient, &
                                  codim2_name, curve_end_name, CODIM2_BT, CODIM2_CUSP, &
                                  CODIM2_ZH, CODIM2_GH, END_BOX, END_BT, END_MAX_POINTS, &
                                  END_CLOSED, END_START, END_X_MAX, END_FAILED
  use bifurcation_test_fields
  use curve_checks, only: box, report, find_codim2
  use checks, only: check_close, check_true, finish
  implicit none
  !> the continuation steps of the curves traced in a box
  real(wp), parameter :: ds = 0.02_wp, ds_max = 0.05_wp

  call test_hopf_normal_form()
  call test_centre_manifold()
  call test_finite_differences()
  call test_bogdanov_takens(-1.0_wp)
  call test_bogdanov_takens(1.0_wp)
  call test_cusp()
  call test_bautin()
  call test_fold_hopf()
  call test_incomplete()
  call test_curve_ends()
  call test_closed_hopf()
  call test_bad_input()
  call finish()

contains

  !> l1 of z' = (b + i omega) z + l z|z|^2 at b = 0: 2 l/omega (unit eigenvector).
  subroutine test_hopf_normal_form()
    type(hopf_normal_form) :: field
    real(wp) :: l1, omega
    integer :: status, i
    character(len=message_len) :: message
    real(wp), parameter :: omegas(3) = [1.0_wp, 2.5_wp, 0.4_wp], ls(3) = [-1.0_wp, 0.7_wp, 3.0_wp]
    do i = 1, 3
      field%omega = omegas(i)
      call first_lyapunov_coefficient(field, [0.0_wp, 0.0_wp], [0.0_wp, ls(i)], l1, omega, &
                                      status, message)
      call check_true('Hopf normal form: l1 computed ('//trim(message)//')', status == SD_OK)
      call check_close('Hopf normal form: omega', omega, omegas(i), 1.0e-14_wp)
      call check_close('Hopf normal form: l1 = 2 l/omega', l1, 2*ls(i)/omegas(i), 1.0e-8_wp)
    end do
  end subroutine test_hopf_normal_form

  !> l1 = p2/(mu omega) at p1 = 0, through the quadratic terms (centre-manifold reduction).
  subroutine test_centre_manifold()
    type(cm_example) :: field
    real(wp) :: l1, omega
    integer :: status
    character(len=message_len) :: message
    call first_lyapunov_coefficient(field, [0.0_wp, 0.0_wp, 0.0_wp], [0.0_wp, 0.8_wp], l1, omega, &
                                    status, message)
    call check_true('centre manifold: l1 computed', status == SD_OK)
    call check_close('centre manifold: l1 = p2/(mu omega)', l1, 0.8_wp/(field%mu*field%omega), &
                     1.0e-8_wp)
  end subroutine test_centre_manifold

  !> The finite-difference defaults against exact derivatives (at a point off the equilibrium,
  !> where the cosine's higher derivatives make truncation errors visible), and l1 from them.
  subroutine test_finite_differences()
    type(cm_example) :: exact
    type(fd_cm_example) :: fd
    real(wp) :: x(3), p(2), u(3), v(3), w(3), hx_e(3, 3), hp_e(3, 2), hx_f(3, 3), hp_f(3, 2), &
                c_e(3), c_f(3), b_e(3), b_f(3), l1_e, l1_f, omega
    integer :: status
    character(len=message_len) :: message
    x = [0.4_wp, -0.3_wp, 0.2_wp]
    p = [0.1_wp, 0.8_wp]
    u = [0.3_wp, 1.0_wp, -0.5_wp]
    v = [-0.7_wp, 0.2_wp, 0.9_wp]
    w = [1.0_wp, 0.4_wp, 0.3_wp]
    call exact%jacobian_derivative(x, p, u, hx_e, hp_e)
    call fd%jacobian_derivative(x, p, u, hx_f, hp_f)
    print '(a, 2es10.2)', '  finite differences: max error of d(Ju)/dx, d(Ju)/dp: ', &
      maxval(abs(hx_f - hx_e)), maxval(abs(hp_f - hp_e))
    call check_true('finite-difference d(Ju)/dx within 1e-9', maxval(abs(hx_f - hx_e)) < 1.0e-9_wp)
    call check_true('finite-difference d(Ju)/dp within 1e-9', maxval(abs(hp_f - hp_e)) < 1.0e-9_wp)
    call exact%second_derivative(x, p, u, v, b_e)
    call fd%second_derivative(x, p, u, v, b_f)
    call check_true('finite-difference B within 1e-9', maxval(abs(b_f - b_e)) < 1.0e-9_wp)
    call exact%third_derivative(x, p, u, v, w, c_e)
    call fd%third_derivative(x, p, u, v, w, c_f)
    print '(a, es10.2, a, es10.2)', '  finite differences: max error of C: ', &
      maxval(abs(c_f - c_e)), ' (|C| = ', maxval(abs(c_e))
    call check_true('finite-difference C within 1e-6', maxval(abs(c_f - c_e)) < 1.0e-6_wp)
    call first_lyapunov_coefficient(exact, [0.0_wp, 0.0_wp, 0.0_wp], [0.0_wp, 0.8_wp], l1_e, &
                                    omega, status, message)
    call first_lyapunov_coefficient(fd, [0.0_wp, 0.0_wp, 0.0_wp], [0.0_wp, 0.8_wp], l1_f, &
                                    omega, status, message)
    print '(a, es10.2)', '  finite differences: relative error of l1: ', abs(l1_f/l1_e - 1)
    call check_close('finite-difference l1 within 1e-6', l1_f, l1_e, 1.0e-6_wp)
  end subroutine test_finite_differences

  !> Fold curve b1 = b2^2/4, Hopf curve b1 = 0 (b2 < 0), both through the BT point (0, 0);
  !> along the Hopf curve l1 = s/(2 omega^3 (1 + omega^2)), omega^2 = -b2 (Guckenheimer-Holmes'
  !> planar formula in coordinates (x, -y/omega), where it gives a = s/(8 omega^2), and the
  !> change to the unit eigenvector q ~ (1, i omega) of the (x, y) coordinates).
  subroutine test_bogdanov_takens(s)
    real(wp), intent(in) :: s
    type(bt_normal_form) :: field
    type(bifurcation_curve) :: fold, hopf
    type(curve_options) :: opt
    integer :: status, j, column, count_bt
    character(len=message_len) :: message
    character(len=8) :: tag
    real(wp) :: worst, worst_l1, omega

    write (tag, '(a, f4.1, a)') '(s=', s, ')'
    field%s = s
    opt = box(-1.0_wp, 1.0_wp, -1.0_wp, 1.0_wp, ds, ds_max)
    call fold_curve(field, [-0.25_wp, 0.0_wp], [0.0625_wp, 0.5_wp], opt, fold, status, message)
    call report('BT fold curve '//tag, fold)
    call check_true('BT fold curve '//tag//': complete ('//trim(message)//')', &
                    status == SD_OK .and. fold%complete)
    call check_true('BT fold curve '//tag//': both ends on the box', &
                    all(fold%end_reason == END_BOX))
    worst = 0
    do j = 1, fold%n_points
      worst = max(worst, abs(fold%p(1, j) - fold%p(2, j)**2/4), &
                  abs(fold%x(1, j) + fold%p(2, j)/2), abs(fold%x(2, j)))
    end do
    print '(a, es10.2)', '    max |b1 - b2^2/4|, |x + b2/2|, |y| on the fold curve: ', worst
    call check_true('BT fold curve '//tag//': every point on b1 = b2^2/4, x = -b2/2 (1e-10)', &
                    worst < 1.0e-10_wp)
    call check_true('BT fold curve '//tag//': spans b2 in [-1, 1]', &
                    minval(fold%p(2, 1:fold%n_points)) < -0.999_wp .and. &
                    maxval(fold%p(2, 1:fold%n_points)) > 0.999_wp)
    count_bt = find_codim2(fold, CODIM2_BT, column)
    call check_true('BT fold curve '//tag//': one Bogdanov-Takens point', count_bt == 1 .and. &
                    fold%n_codim2 == 1)
    if (column > 0) then
      call check_close('BT fold curve '//tag//': BT at b1 = 0', fold%p(1, column), 0.0_wp, &
                       0.0_wp, 1.0e-8_wp)
      call check_close('BT fold curve '//tag//': BT at b2 = 0', fold%p(2, column), 0.0_wp, &
                       0.0_wp, 1.0e-8_wp)
    end if

    call hopf_curve(field, [0.0_wp, 0.0_wp], [0.0_wp, -0.5_wp], opt, hopf, status, message)
    call report('BT Hopf curve '//tag, hopf)
    call check_true('BT Hopf curve '//tag//': complete ('//trim(message)//')', &
                    status == SD_OK .and. hopf%complete)
    call check_true('BT Hopf curve '//tag//': ends on the box and at the BT point', &
                    any(hopf%end_reason == END_BOX) .and. any(hopf%end_reason == END_BT))
    worst = 0
    worst_l1 = 0
    do j = 1, hopf%n_points
      worst = max(worst, abs(hopf%p(1, j)), maxval(abs(hopf%x(:, j))))
      omega = sqrt(-hopf%p(2, j))
      if (hopf%p(2, j) < -1.0e-3_wp) worst_l1 = max(worst_l1, &
        abs(hopf%l1(j)/(s/(2*omega**3*(1 + omega**2))) - 1))
    end do
    print '(a, es10.2, a, es10.2)', '    max |b1|, |x| on the Hopf curve: ', worst, &
      ', max relative error of l1: ', worst_l1
    call check_true('BT Hopf curve '//tag//': every point on b1 = 0, x = 0 (1e-10)', &
                    worst < 1.0e-10_wp)
    call check_true('BT Hopf curve '//tag//': b2 < 0 and b2 reaches -1', &
                    maxval(hopf%p(2, 1:hopf%n_points)) < 1.0e-8_wp .and. &
                    minval(hopf%p(2, 1:hopf%n_points)) < -0.999_wp)
    call check_true('BT Hopf curve '//tag//': l1 = s/(2 omega^3 (1 + omega^2)) (1e-8)', &
                    worst_l1 < 1.0e-8_wp)
    call check_true('BT Hopf curve '//tag//': sign of l1 = s (super/subcritical)', &
                    all(sign(1.0_wp, hopf%l1(1:hopf%n_points - 1)) == s .or. &
                        .not. ieee_is_finite(hopf%l1(1:hopf%n_points - 1))))
    count_bt = find_codim2(hopf, CODIM2_BT, column)
    call check_true('BT Hopf curve '//tag//': one Bogdanov-Takens point', count_bt == 1)
    if (column > 0) then
      call check_close('BT Hopf curve '//tag//': BT at b1 = 0', hopf%p(1, column), 0.0_wp, &
                       0.0_wp, 1.0e-8_wp)
      call check_close('BT Hopf curve '//tag//': BT at b2 = 0', hopf%p(2, column), 0.0_wp, &
                       0.0_wp, 1.0e-8_wp)
      call check_close('BT Hopf curve '//tag//': omega = 0 at BT', hopf%omega(column), 0.0_wp, &
                       0.0_wp, 1.0e-6_wp)
    end if
  end subroutine test_bogdanov_takens

  !> Fold curve b2 = 3 x^2, b1 = -2 x^3 (so 4 b2^3 = 27 b1^2), cusp at the origin.
  subroutine test_cusp()
    type(cusp_normal_form) :: field
    type(bifurcation_curve) :: fold
    type(curve_options) :: opt
    integer :: status, j, column, count_cp
    character(len=message_len) :: message
    real(wp) :: worst, worst_eq, x0

    opt = box(-1.0_wp, 1.0_wp, -1.0_wp, 1.0_wp, ds, ds_max)
    x0 = sqrt(0.8_wp/3)
    call fold_curve(field, [x0], [-2*x0**3, 0.8_wp], opt, fold, status, message)
    call report('cusp fold curve', fold)
    call check_true('cusp fold curve: complete ('//trim(message)//')', &
                    status == SD_OK .and. fold%complete .and. all(fold%end_reason == END_BOX))
    worst = 0
    worst_eq = 0
    do j = 1, fold%n_points
      worst = max(worst, abs(fold%p(2, j) - 3*fold%x(1, j)**2), &
                  abs(fold%p(1, j) + 2*fold%x(1, j)**3))
      worst_eq = max(worst_eq, abs(4*fold%p(2, j)**3 - 27*fold%p(1, j)**2))
    end do
    print '(a, es10.2, a, es10.2)', '    max |b2 - 3x^2|, |b1 + 2x^3|: ', worst, &
      ', max |4 b2^3 - 27 b1^2|: ', worst_eq
    call check_true('cusp fold curve: every point on b2 = 3x^2, b1 = -2x^3 (1e-10)', &
                    worst < 1.0e-10_wp)
    call check_true('cusp fold curve: every point on 4 b2^3 = 27 b1^2 (1e-10)', &
                    worst_eq < 1.0e-10_wp)
    call check_true('cusp fold curve: both branches (x > 0 and x < 0) to b2 = 1', &
                    minval(fold%x(1, 1:fold%n_points)) < -0.57_wp .and. &
                    maxval(fold%x(1, 1:fold%n_points)) > 0.57_wp)
    count_cp = find_codim2(fold, CODIM2_CUSP, column)
    call check_true('cusp fold curve: one cusp, nothing else', count_cp == 1 .and. &
                    fold%n_codim2 == 1)
    if (column > 0) then
      call check_close('cusp at b1 = 0', fold%p(1, column), 0.0_wp, 0.0_wp, 1.0e-8_wp)
      call check_close('cusp at b2 = 0', fold%p(2, column), 0.0_wp, 0.0_wp, 1.0e-8_wp)
      call check_close('cusp at x = 0', fold%x(1, column), 0.0_wp, 0.0_wp, 1.0e-8_wp)
    end if
  end subroutine test_cusp

  !> Hopf curve p1 = p2^2 with l1 = 2 (p2 - 0.3)/(1 + p2/2), generalised Hopf at (0.09, 0.3).
  subroutine test_bautin()
    type(bautin_normal_form) :: field
    type(bifurcation_curve) :: hopf
    type(curve_options) :: opt
    integer :: status, j, column, count_gh
    character(len=message_len) :: message
    real(wp) :: worst, worst_l1

    opt = box(-1.0_wp, 1.0_wp, -0.9_wp, 0.9_wp, ds, ds_max)
    call hopf_curve(field, [0.0_wp, 0.0_wp], [0.25_wp, -0.5_wp], opt, hopf, status, message)
    call report('Bautin Hopf curve', hopf)
    call check_true('Bautin Hopf curve: complete ('//trim(message)//')', &
                    status == SD_OK .and. hopf%complete .and. all(hopf%end_reason == END_BOX))
    worst = 0
    worst_l1 = 0
    do j = 1, hopf%n_points
      worst = max(worst, abs(hopf%p(1, j) - hopf%p(2, j)**2), maxval(abs(hopf%x(:, j))))
      worst_l1 = max(worst_l1, abs(hopf%l1(j) - 2*(hopf%p(2, j) - 0.3_wp)/(1 + hopf%p(2, j)/2)))
      worst = max(worst, abs(hopf%omega(j) - (1 + hopf%p(2, j)/2)))
    end do
    print '(a, es10.2, a, es10.2)', '    max |p1 - p2^2|, |x|, |omega - 1 - p2/2|: ', worst, &
      ', max |l1 - 2 (p2 - 0.3)/omega|: ', worst_l1
    call check_true('Bautin Hopf curve: every point on p1 = p2^2 (1e-10)', worst < 1.0e-10_wp)
    call check_true('Bautin Hopf curve: l1 = 2 (p2 - 0.3)/omega (1e-8)', worst_l1 < 1.0e-8_wp)
    count_gh = find_codim2(hopf, CODIM2_GH, column)
    call check_true('Bautin Hopf curve: one generalised Hopf point, nothing else', &
                    count_gh == 1 .and. hopf%n_codim2 == 1)
    if (column > 0) then
      call check_close('generalised Hopf at p2 = 0.3', hopf%p(2, column), 0.3_wp, 0.0_wp, 1.0e-8_wp)
      call check_close('generalised Hopf at p1 = 0.09', hopf%p(1, column), 0.09_wp, 0.0_wp, &
                       1.0e-8_wp)
      call check_close('generalised Hopf: omega = 1.15', hopf%codim2(1)%omega, 1.15_wp, 1.0e-10_wp)
    end if
  end subroutine test_bautin

  !> Fold curve b1 = 0 with a zero-Hopf point at b2 = c; Hopf curve b1 = -((b2 - c)/theta)^2
  !> through the same point (there x = 0, det J = 0).
  subroutine test_fold_hopf()
    type(fold_hopf_normal_form) :: field
    type(bifurcation_curve) :: fold, hopf
    type(curve_options) :: opt
    integer :: status, j, column, count_zh
    character(len=message_len) :: message
    real(wp) :: worst, u

    opt = box(-1.0_wp, 1.0_wp, -1.0_wp, 1.0_wp, ds, ds_max)
    call fold_curve(field, [0.0_wp, 0.0_wp, 0.0_wp], [0.0_wp, 0.6_wp], opt, fold, status, message)
    call report('fold-Hopf fold curve', fold)
    call check_true('fold-Hopf fold curve: complete ('//trim(message)//')', &
                    status == SD_OK .and. fold%complete)
    worst = 0
    do j = 1, fold%n_points
      worst = max(worst, abs(fold%p(1, j)), maxval(abs(fold%x(:, j))))
    end do
    call check_true('fold-Hopf fold curve: every point on b1 = 0, x = 0 (1e-10)', &
                    worst < 1.0e-10_wp)
    count_zh = find_codim2(fold, CODIM2_ZH, column)
    call check_true('fold-Hopf fold curve: one zero-Hopf point, nothing else', &
                    count_zh == 1 .and. fold%n_codim2 == 1)
    if (column > 0) then
      call check_close('fold curve: zero-Hopf at b2 = c', fold%p(2, column), field%c, 0.0_wp, &
                       1.0e-8_wp)
      call check_close('fold curve: zero-Hopf at b1 = 0', fold%p(1, column), 0.0_wp, 0.0_wp, &
                       1.0e-8_wp)
      call check_close('fold curve: zero-Hopf frequency omega', fold%codim2(1)%omega, &
                       field%omega, 1.0e-8_wp)
    end if

    u = -(0.7_wp - field%c)/field%theta
    call hopf_curve(field, [u, 0.0_wp, 0.0_wp], [-u**2, 0.7_wp], opt, hopf, status, message)
    call report('fold-Hopf Hopf curve', hopf)
    call check_true('fold-Hopf Hopf curve: complete ('//trim(message)//')', &
                    status == SD_OK .and. hopf%complete)
    worst = 0
    do j = 1, hopf%n_points
      u = -(hopf%p(2, j) - field%c)/field%theta
      worst = max(worst, abs(hopf%p(1, j) + u**2), abs(hopf%x(1, j) - u), &
                  abs(hopf%omega(j) - (field%omega + field%vartheta*u)))
    end do
    print '(a, es10.2)', '    max |b1 + u^2|, |x - u|, |omega - omega(u)| on the Hopf curve: ', &
      worst
    call check_true('fold-Hopf Hopf curve: every point on b1 = -((b2 - c)/theta)^2 (1e-10)', &
                    worst < 1.0e-10_wp)
    count_zh = find_codim2(hopf, CODIM2_ZH, column)
    call check_true('fold-Hopf Hopf curve: one zero-Hopf point', count_zh == 1)
    if (column > 0) then
      call check_close('Hopf curve: zero-Hopf at b2 = c', hopf%p(2, column), field%c, 0.0_wp, &
                       1.0e-8_wp)
      call check_close('Hopf curve: zero-Hopf at b1 = 0', hopf%p(1, column), 0.0_wp, 0.0_wp, &
                       1.0e-8_wp)
    end if
  end subroutine test_fold_hopf

  !> A curve cut by max_points: complete = .false., status SD_CAPACITY and a message, the points
  !> so far kept.
  subroutine test_incomplete()
    type(bt_normal_form) :: bt
    type(bifurcation_curve) :: curve
    type(curve_options) :: opt
    integer :: status
    character(len=message_len) :: message
    opt = box(-1.0_wp, 1.0_wp, -1.0_wp, 1.0_wp, ds, ds_max)
    opt%max_points = 12
    call fold_curve(bt, [-0.25_wp, 0.0_wp], [0.0625_wp, 0.5_wp], opt, curve, status, message)
    call check_true('max_points: status SD_CAPACITY ('//trim(message)//')', status == SD_CAPACITY)
    print '(a, i0, 2(1x, a))', '    max_points: ', curve%n_points, &
      curve_end_name(curve%end_reason(1)), curve_end_name(curve%end_reason(2))
    call check_true('max_points: not complete, end reason given, points kept', &
                    .not. curve%complete .and. any(curve%end_reason == END_MAX_POINTS) .and. &
                    curve%n_points == 12)
  end subroutine test_incomplete

  !> One way only; through a BT point into the neutral-saddle curve; x_max; a field that fails.
  subroutine test_curve_ends()
    type(bt_normal_form) :: bt
    type(walled_bt) :: walled
    type(cusp_normal_form) :: cusp
    type(bifurcation_curve) :: curve
    type(curve_options) :: opt
    integer :: status, j, column
    character(len=message_len) :: message
    real(wp) :: worst, x0

    opt = box(-1.0_wp, 1.0_wp, -1.0_wp, 1.0_wp, ds, ds_max)
    opt%direction = 1
    call fold_curve(bt, [-0.25_wp, 0.0_wp], [0.0625_wp, 0.5_wp], opt, curve, status, message)
    call check_true('direction = +1: one way, p2 increasing, to the box', status == SD_OK .and. &
                    curve%complete .and. curve%start_index == 1 .and. &
                    all(curve%end_reason == [END_START, END_BOX]) .and. &
                    curve%p(2, 2) > curve%p(2, 1) .and. &
                    abs(curve%p(2, curve%n_points) - 1) < 1.0e-12_wp)
    opt%direction = -1
    call fold_curve(bt, [-0.25_wp, 0.0_wp], [0.0625_wp, 0.5_wp], opt, curve, status, message)
    call check_true('direction = -1: one way, p2 decreasing, through BT to the box', &
                    status == SD_OK .and. curve%complete .and. curve%p(2, 2) < curve%p(2, 1) .and. &
                    abs(curve%p(2, curve%n_points) + 1) < 1.0e-12_wp .and. curve%n_codim2 == 1)

    opt = box(-1.0_wp, 1.0_wp, -1.0_wp, 1.0_wp, ds, ds_max)
    opt%neutral_saddles = .true.
    call hopf_curve(bt, [0.0_wp, 0.0_wp], [0.0_wp, -0.5_wp], opt, curve, status, message)
    call report('BT Hopf curve with neutral saddles', curve)
    worst = 0
    do j = 1, curve%n_points
      worst = max(worst, abs(curve%p(1, j)), maxval(abs(curve%x(:, j))), &
                  abs(sign(curve%omega(j)**2, curve%omega(j)) + curve%p(2, j)))
    end do
    j = find_codim2(curve, CODIM2_BT, column)
    call check_true('neutral_saddles: through the BT point to b2 = 1, both ends on the box', &
                    status == SD_OK .and. curve%complete .and. &
                    all(curve%end_reason == END_BOX) .and. &
                    maxval(curve%p(2, 1:curve%n_points)) > 0.999_wp .and. j == 1)
    call check_true('neutral_saddles: b1 = 0, x = 0, kappa = sign(omega) omega^2 = -b2 (1e-10)', &
                    worst < 1.0e-10_wp)

    opt = box(-1.0_wp, 1.0_wp, -1.0_wp, 1.0_wp, ds, ds_max)
    opt%x_max = 0.3_wp
    x0 = sqrt(0.08_wp/3)
    call fold_curve(cusp, [x0], [-2*x0**3, 0.08_wp], opt, curve, status, message)
    call check_true('x_max: both ends just beyond |x| = 0.3, complete', status == SD_OK .and. &
                    curve%complete .and. all(curve%end_reason == END_X_MAX) .and. &
                    abs(curve%x(1, 1)) > 0.3_wp .and. &
                    abs(curve%x(1, curve%n_points)) > 0.3_wp .and. &
                    maxval(abs(curve%x(1, 2:curve%n_points - 1))) <= 0.3_wp)

    opt = box(-1.0_wp, 1.0_wp, -1.0_wp, 1.0_wp, ds, ds_max)
    call fold_curve(walled, [-0.25_wp, 0.0_wp], [0.0625_wp, 0.5_wp], opt, curve, status, message)
    print '(a)', '    walled field: '//trim(message)
    call check_true('a failing field: not complete, a status and a message, the points kept', &
                    status /= SD_OK .and. len_trim(message) > 0 .and. .not. curve%complete .and. &
                    curve%status == status .and. curve%message == message .and. &
                    any(curve%end_reason == END_FAILED) .and. &
                    maxval(curve%p(2, 1:curve%n_points)) <= 0.7_wp .and. &
                    maxval(curve%p(2, 1:curve%n_points)) > 0.69_wp .and. &
                    minval(curve%p(2, 1:curve%n_points)) < -0.999_wp)
  end subroutine test_curve_ends

  !> A closed Hopf curve p1^2 + p2^2 = 1/4 (no box): it ends where it started.
  subroutine test_closed_hopf()
    type(circle_hopf) :: field
    type(bifurcation_curve) :: curve
    type(curve_options) :: opt
    integer :: status, j
    character(len=message_len) :: message
    real(wp) :: worst
    opt%continuation%ds = 0.02_wp
    opt%continuation%ds_max = 0.05_wp
    call hopf_curve(field, [0.0_wp, 0.0_wp], [0.5_wp, 0.0_wp], opt, curve, status, message)
    call report('circle Hopf curve', curve)
    call check_true('closed Hopf curve: complete, closed ('//trim(message)//')', &
                    status == SD_OK .and. curve%complete .and. any(curve%end_reason == END_CLOSED))
    worst = 0
    do j = 1, curve%n_points
      worst = max(worst, abs(curve%p(1, j)**2 + curve%p(2, j)**2 - 0.25_wp), &
                  abs(curve%l1(j) + 2/field%omega))
    end do
    call check_true('closed Hopf curve: every point on p1^2 + p2^2 = 1/4, l1 = -2/omega (1e-10)', &
                    worst < 1.0e-10_wp)
    call check_close('closed Hopf curve: last point = first point', &
                     norm2(curve%p(:, curve%n_points) - curve%p(:, 1)), 0.0_wp, 0.0_wp, 1.0e-12_wp)
    call check_true('closed Hopf curve: it goes round (p1 reaches -1/2)', &
                    minval(curve%p(1, 1:curve%n_points)) < -0.499_wp)
  end subroutine test_closed_hopf

  !> Bad input names the variable; a start far from a fold is refused with a reason.
  subroutine test_bad_input()
    type(bt_normal_form) :: field
    type(bifurcation_curve) :: curve
    type(curve_options) :: opt
    integer :: status
    character(len=message_len) :: message
    opt = box(-1.0_wp, 1.0_wp, -1.0_wp, 1.0_wp, ds, ds_max)
    opt%p_scale(2) = 0
    call fold_curve(field, [-0.25_wp, 0.0_wp], [0.0625_wp, 0.5_wp], opt, curve, status, message)
    call check_true('bad p2_scale: SD_BAD_INPUT naming p2_scale ('//trim(message)//')', &
                    status == SD_BAD_INPUT .and. index(message, 'p2_scale') > 0)
    opt = box(-1.0_wp, 1.0_wp, -1.0_wp, 1.0_wp, ds, ds_max)
    call fold_curve(field, [-0.25_wp, 0.0_wp], [0.0625_wp, 1.5_wp], opt, curve, status, message)
    call check_true('start outside the box: SD_BAD_INPUT naming p0(2) ('//trim(message)//')', &
                    status == SD_BAD_INPUT .and. index(message, 'p0(2)') > 0)
    opt%max_points = 2
    call fold_curve(field, [-0.25_wp, 0.0_wp], [0.0625_wp, 0.5_wp], opt, curve, status, message)
    call check_true('max_points = 2: SD_BAD_INPUT naming max_points', &
                    status == SD_BAD_INPUT .and. index(message, 'max_points') > 0)
    opt = box(-1.0_wp, 1.0_wp, -1.0_wp, 1.0_wp, ds, ds_max)
    call hopf_curve(field, [0.0_wp, 0.0_wp], [0.0_wp, 0.5_wp], opt, curve, status, message)
    call check_true('Hopf start at a saddle: refused, no complex pair ('//trim(message)//')', &
                    status == SD_BAD_INPUT .and. index(message, 'complex') > 0 .and. &
                    .not. curve%complete)
    ! at (x, y) = (-1/2, 0), b = (0, 1/2) J has eigenvalues 1/4 +- 0.66 i; the nearest solution
    ! of the Hopf system is the neutral saddle x = 0 (eigenvalues +-sqrt(1/2))
    call hopf_curve(field, [-0.5_wp, 0.0_wp], [0.0_wp, 0.5_wp], opt, curve, status, message)
    call check_true('Hopf start near a neutral saddle: refused ('//trim(message)//')', &
                    status /= SD_OK .and. len_trim(message) > 0 .and. .not. curve%complete)
  end subroutine test_bad_input
end program test_bifurcation
