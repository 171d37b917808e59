!> Two-parameter continuation of codimension-1 bifurcation curves of fixed points of a map
!> x -> P(x; p1, p2), x in R^n (n small), with M = dP/dx (for a periodically forced system, P is
!> the stroboscopic (Poincare) map over k forcing periods and M the monodromy matrix, its
!> eigenvalues mu the Floquet multipliers). The curves are traced by sloshdyn_bifurcation (its
!> segments, border refreshes, box, closure, end reasons and codimension-2 location); this module
!> supplies the defining systems and test functions of maps (Kuznetsov, Elements of Applied
!> Bifurcation Theory, 3rd ed. 2004, ch. 4, 9 and 10.3; Govaerts, SIAM 2000, ch. 8; the fixed-point
!> curves of MatContM, Govaerts, Kuznetsov, Khoshsiar Ghaziani & Meijer 2008).
!>
!> A fixed point is an equilibrium of the field f(x, p) = P(x, p) - x (f_x = M - I): a map is a
!> two_parameter_field whose evaluate gives that f, so fold_curve, correct_to_curve and
!> curve_crossings work on maps unchanged; the map chooses its defining systems:
!>
!> Fold (a multiplier +1):  P(x, p) - x = 0,  g(x, p) = 0, the minimally augmented system of
!>   sloshdyn_bifurcation on M - I (n + 1 unknowns x and one parameter besides lambda).   (M1)
!> Period doubling (a multiplier -1): the same on M + I = (M - I) + 2 I (fold_system with
!>   shift 2): [M + I  b; c^T 0] (v; g) = (0; 1), g_z = -w^T d(M v)/dz.                      (M2)
!>   Both are regular at their codimension-2 points (1:1 and 1:2 resonances, cusp, fold-flip),
!>   need one directional derivative of M per evaluation, and their border vectors are the
!>   null vectors of the last segment start (as for flows).
!> Neimark-Sacker (a pair e^{+-i theta}): the map analogue of the standard Hopf system,
!>   P(x, p) - x = 0,  (M^2 - kappa M + I) v = 0,  <v_ref, v> = 1,  <u_ref, v> = 0,         (M3)
!>   kappa = 2 cos(theta) in (-2, 2) (Kuznetsov sec 10.3.2), 2n + 2 unknowns (x, v, kappa, the
!>   other parameter). Chosen over a bordered minimally augmented variant because it is regular
!>   exactly where the one-parameter code and the chart need it: at the 1:1 (kappa = 2, M^2 -
!>   2M + I = (M - I)^2) and 1:2 resonances (kappa = -2, (M + I)^2), where the pair becomes a
!>   double real multiplier, so the curve reaches them (and can go on as a "neutral saddle"
!>   curve of real multipliers mu, 1/mu with mu + 1/mu = kappa, |kappa| > 2); it is real,
!>   theta comes free, v spans the invariant real plane of the pair, and for n = 4 the extra
!>   unknowns cost nothing next to the shots (a bordered variant of the bialternate product
!>   would need matrices of order n(n - 1)/2 and their derivatives). Its Jacobian needs
!>   d(M u)/dx and d(M u)/dp for u = v and u = M v:
!>   d[(M^2 - kappa M + I) v] = D(M (M v)) - kappa D(M v) = H(M v) + (M - kappa I) H(v),
!>   H(u) = d(M u)/d(x, p).
!>
!> Derivatives of M: by central finite differences of M (M itself always comes from the
!> variational equations, so the residual of every defining system, and with it every point of a
!> curve and its multipliers, is as accurate as the shots; the differences only enter Newton's
!> Jacobian, the tangent and the cusp test <w, B(v, v)>). Steps: x_step/max|u| along u and
!> p_step(k) in p_k (two_parameter_map; 0 = eps^(1/3) (1 + |.|), right for exact maps). For
!> shots the step should balance the truncation error (h/L)^2 against the integration error
!> ~rtol L/h that a change of the step sequence between the two shots can bring (L the scale on
!> which M varies, e.g. the curve's x_scale and p_scale): h = rtol^(1/3) L, both ~rtol^(2/3)
!> (the tank's map, sloshdyn_orbit_chart, sets its steps so). Measured in
!> tests/fortran/test_orbit_chart.f90 at rtol = 1e-12: d^2 P/dz^2 of a rotating-frame flow
!> against its closed form, 1.7e-7 relative at h = 1e-4 (truncation; 2e-11 at h = 1e-6); the
!> tank's B(v, v) changes by 9e-9 relative from h to h/10. Second-order variational equations
!> would give the derivatives to the integration tolerance, but the periodic problems provide
!> no second derivatives of their right-hand side, and the accuracy above is far more than
!> Newton's convergence needs.
!>
!> Test functions and codimension-2 points (zeros between consecutive points, located by
!> sloshdyn_bifurcation; v, w unit null vectors of the bordered matrix):
!>   fold curve (4 tests)   1:1 resonance R1   <w, v> (a Jordan block at +1)
!>                          cusp CP            <w, B(v, v)>, B(u, v) = D^2_x P[u, v]
!>                          fold-flip          det(M + I)
!>                          fold-NS            prod_{i<j} (mu_i mu_j - 1) over the multipliers but
!>                                             the one nearest +1; confirmed by a pair on the
!>                                             unit circle (not a real pair mu, 1/mu)
!>   PD curve (4 tests)     1:2 resonance R2   <w, v> (a Jordan block at -1)
!>                          fold-flip          det(M - I)
!>                          flip-NS            as fold-NS, without the multiplier nearest -1
!>                          generalised flip   the flip coefficient c (sloshdyn_map_normal_form)
!>                                             over the size of its terms; confirmed where it
!>                                             is below 1e-3 (the terms cancel; not rounding)
!>   NS curve (7 tests)     R1: kappa - 2, R2: kappa + 2, R3 (theta = 2 pi/3): kappa + 1,
!>                          R4 (theta = pi/2): kappa, fold-NS: prod (mu_j - 1), flip-NS:
!>                          prod (mu_j + 1) over the multipliers but the pair, Chenciner: the
!>                          Neimark-Sacker coefficient d (sloshdyn_map_normal_form; |kappa| < 2)
!>                          over the size of its terms, confirmed as the generalised flip
!> The normal-form coefficients (Kuznetsov 2004, secs 4.7, 5.4 and 8.7.2; the generalised flip
!> and Chenciner points, their zeros, ch. 9) are those of the one-parameter criticality, from
!> the same routines; they exist for stroboscopic maps only (NaN, no test, for other maps) and
!> cost 4 (c) and 8 (d) more monodromy matrices per point: they take the tests' M. That M comes
!> without dP/dp (fixed_point_monodromy; for a stroboscopic map one shot without the sensitivity
!> columns, whose steps the coefficients' differences need), so the tests' multipliers differ
!> from those of the corrector's M (with dP/dp) by the integration error.
!> A Neimark-Sacker curve ends at R1 and R2 (END_RESONANCE) unless curve_options%neutral_saddles.
!> Not detected: double NS. curve%omega holds theta on NS curves (-acosh(|kappa|/2) = -ln|mu|
!> on neutral-saddle parts), codim2_point%omega the angle of the point (R1 0, R2 and the
!> generalised flip pi, R3 2 pi/3, R4 pi/2, fold-NS, flip-NS and Chenciner theta),
!> curve%eig_re/eig_im the multipliers, curve%l1 NaN.
!>
!> Public: two_parameter_map (map: P, M and dP/dp; its evaluate is f = P - x), map_evaluate,
!> stroboscopic_map (P by shooting a periodic_problem of sloshdyn_shooting over k forcing
!> periods; the extension supplies the problem at p), map_fold_curve, period_doubling_curve,
!> neimark_sacker_curve. correct_to_curve and curve_crossings of sloshdyn_bifurcation take maps
!> and the kinds CURVE_FOLD, CURVE_PERIOD_DOUBLING, CURVE_NEIMARK_SACKER.
module sloshdyn_map_bifurcation
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT
  use sloshdyn_text, only: num2str
  use sloshdyn_lapack, only: eigenvalues
  use sloshdyn_ode, only: ode_options
  use sloshdyn_shooting, only: periodic_problem, monodromy_matrix, fold_test, &
                               period_doubling_test
  use sloshdyn_bifurcation, only: two_parameter_field, curve_options, bifurcation_curve, &
                                  curve_system, max_curve_tests, setup_system, split_x_p, &
                                  point_x_p, inverse_iteration, null_vectors, nearest_pair, &
                                  curve_of_kind, &
                                  curve_kind_name, &
                                  CURVE_FOLD, CURVE_HOPF, CURVE_PERIOD_DOUBLING, &
                                  CURVE_NEIMARK_SACKER, CODIM2_R1, CODIM2_R2, CODIM2_R3, &
                                  CODIM2_R4, CODIM2_CUSP, CODIM2_FOLD_FLIP, CODIM2_FOLD_NS, &
                                  CODIM2_FLIP_NS, CODIM2_GF, CODIM2_CH, END_RESONANCE
  use sloshdyn_fold_hopf, only: fold_system, hopf_system
  use sloshdyn_map_normal_form, only: cubic_coefficient, neimark_sacker_coefficient
  implicit none
  private
  public :: two_parameter_map, map_evaluate, stroboscopic_map, map_problem
  public :: map_fold_curve, period_doubling_curve, neimark_sacker_curve

  !> A map x -> P(x; p1, p2) with M = dP/dx. As a two_parameter_field it is f = P - x.
  type, abstract, extends(two_parameter_field) :: two_parameter_map
    !> finite-difference steps for the derivatives of M (module header): along a direction u,
    !> x_step/max|u|; in p_k, p_step(k). 0: eps^(1/3) (1 + max|x|), eps^(1/3) (1 + |p_k|).
    real(wp) :: x_step = 0
    real(wp) :: p_step(2) = 0
  contains
    procedure(map_evaluate), deferred :: map
    procedure :: evaluate => map_as_field
    procedure :: jacobian_derivative => map_jacobian_derivative
    procedure :: second_derivative => map_second_derivative
    procedure :: defining_system => map_defining_system
  end type two_parameter_map

  abstract interface
    !> px = P(x, p), mx = M = dP/dx (n x n) and, if present, mp = dP/dp (n x 2). A failure
    !> (status /= 0, message) leaves the outputs undefined.
    subroutine map_evaluate(self, x, p, px, mx, status, message, mp)
      import :: wp, message_len, two_parameter_map
      class(two_parameter_map), intent(in) :: self
      real(wp), intent(in) :: x(:), p(2)
      real(wp), intent(out) :: px(:), mx(:, :)
      integer, intent(out) :: status
      character(len=message_len), intent(out) :: message
      real(wp), intent(out), optional :: mp(:, :)
    end subroutine map_evaluate
  end interface

  !> The stroboscopic map of a T-periodic system over `periods` forcing periods, by shooting
  !> (sloshdyn_shooting's monodromy_matrix: P, M and each dP/dp_k from the variational
  !> equations, the change of T with p_k included). The extension supplies the problem at p
  !> with lambda = p(varied).
  type, abstract, extends(two_parameter_map) :: stroboscopic_map
    integer :: periods = 1
    integer :: method = 0
    type(ode_options) :: integration
  contains
    procedure(map_problem), deferred :: problem
    procedure :: map => stroboscopic_evaluate
  end type stroboscopic_map

  abstract interface
    !> The periodic problem at parameters p, its continuation parameter lambda being
    !> p(varied) (varied = 1 or 2).
    subroutine map_problem(self, p, varied, problem)
      import :: wp, stroboscopic_map, periodic_problem
      class(stroboscopic_map), intent(in) :: self
      real(wp), intent(in) :: p(2)
      integer, intent(in) :: varied
      class(periodic_problem), allocatable, intent(out) :: problem
    end subroutine map_problem
  end interface

  !> (M1) with shift = 0 and (M2) with shift = 2; the test functions of the module header.
  type, extends(fold_system) :: map_fold_system
  contains
    procedure :: diagnose => map_fold_diagnose
    procedure :: confirm_codim2 => map_fold_confirm
    procedure :: codim2_frequency => map_fold_codim2_frequency
  end type map_fold_system

  !> (M3); the layout of hopf_system (z = (x/x_scale, v, kappa, q_other)) with kappa_scale = 1,
  !> its reference vectors (v and the part of M v orthogonal to v span the pair's plane).
  type, extends(hopf_system) :: neimark_sacker_system
  contains
    procedure :: evaluate => ns_evaluate
    procedure :: diagnose => ns_diagnose
    procedure :: confirm_codim2 => ns_confirm
    procedure :: codim2_frequency => ns_codim2_frequency
    procedure :: neutral_saddle => ns_neutral_saddle
    procedure :: frequency_of => ns_frequency_of
  end type neimark_sacker_system

  !> |mu| - 1 within this (relative to max|mu|) counts as on the unit circle, an imaginary part
  !> above it as nonzero, when a fold-NS or flip-NS point is confirmed.
  real(wp), parameter :: circle_tol = 1.0e-6_wp
  !> A zero of a normal-form coefficient (over the size of its terms) is a generalised flip or
  !> Chenciner point if it is this small there: the terms cancel. A coefficient whose terms
  !> are all rounding noise (a linear map's, identically 0) changes sign at random, its
  !> located zeros as large as its values.
  real(wp), parameter :: cancellation_tol = 1.0e-3_wp

contains

  ! ---- public routines ----------------------------------------------------------------------

  !> The fold curve of fixed points through (x0, p0), a fixed point with a multiplier near +1
  !> (corrected first with p2 fixed, or p1); as fold_curve(map, ...).
  subroutine map_fold_curve(map, x0, p0, options, curve, status, message)
    class(two_parameter_map), intent(in) :: map
    real(wp), intent(in) :: x0(:), p0(2)
    type(curve_options), intent(in) :: options
    type(bifurcation_curve), intent(out) :: curve
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    call curve_of_kind(map, CURVE_FOLD, 'map_fold_curve', x0, p0, options, curve, status, &
                       message)
  end subroutine map_fold_curve

  !> The period-doubling curve through (x0, p0), a fixed point with a multiplier near -1.
  subroutine period_doubling_curve(map, x0, p0, options, curve, status, message)
    class(two_parameter_map), intent(in) :: map
    real(wp), intent(in) :: x0(:), p0(2)
    type(curve_options), intent(in) :: options
    type(bifurcation_curve), intent(out) :: curve
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    call curve_of_kind(map, CURVE_PERIOD_DOUBLING, 'period_doubling_curve', x0, p0, options, &
                       curve, status, message)
  end subroutine period_doubling_curve

  !> The Neimark-Sacker curve through (x0, p0), a fixed point with a complex multiplier pair
  !> near the unit circle (the pair nearest to it).
  subroutine neimark_sacker_curve(map, x0, p0, options, curve, status, message)
    class(two_parameter_map), intent(in) :: map
    real(wp), intent(in) :: x0(:), p0(2)
    type(curve_options), intent(in) :: options
    type(bifurcation_curve), intent(out) :: curve
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    call curve_of_kind(map, CURVE_NEIMARK_SACKER, 'neimark_sacker_curve', x0, p0, options, &
                       curve, status, message)
  end subroutine neimark_sacker_curve

  ! ---- the map as a field, and the derivatives of M ---------------------------------------

  !> f = P - x, fx = M - I, fp = dP/dp; NaN where the map fails (continuation then shortens
  !> its step; the curve routines report where it stopped).
  subroutine map_as_field(self, x, p, f, fx, fp)
    class(two_parameter_map), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2)
    real(wp), intent(out) :: f(:), fx(:, :), fp(:, :)
    integer :: status, i
    character(len=message_len) :: message
    call self%map(x, p, f, fx, status, message, fp)
    if (status /= SD_OK) then
      f = ieee_value(1.0_wp, ieee_quiet_nan)
      fx = f(1)
      fp = f(1)
      return
    end if
    f = f - x
    do i = 1, size(x)
      fx(i, i) = fx(i, i) - 1
    end do
  end subroutine map_as_field

  !> M at (x, p), NaN on failure.
  subroutine monodromy_at(map, x, p, mx)
    class(two_parameter_map), intent(in) :: map
    real(wp), intent(in) :: x(:), p(2)
    real(wp), intent(out) :: mx(:, :)
    real(wp) :: px(size(x))
    integer :: status
    character(len=message_len) :: message
    call map%map(x, p, px, mx, status, message)
    if (status /= SD_OK) mx = ieee_value(1.0_wp, ieee_quiet_nan)
  end subroutine monodromy_at

  !> M (mx) and J = M - I (jx) of a map's fixed point x at p for the tests along a curve:
  !> without dP/dp, which they do not need (for a stroboscopic map one shot, without the
  !> sensitivity columns, and the M its normal-form coefficient takes: sloshdyn_map_normal_form);
  !> NaN where the map fails.
  subroutine fixed_point_monodromy(field, x, p, mx, jx)
    class(two_parameter_field), intent(in) :: field
    real(wp), intent(in) :: x(:), p(2)
    real(wp), intent(out) :: mx(:, :), jx(:, :)
    integer :: i
    mx = ieee_value(1.0_wp, ieee_quiet_nan)
    select type (field)
    class is (two_parameter_map)
      call monodromy_at(field, x, p, mx)
    end select
    jx = mx
    do i = 1, size(x)
      jx(i, i) = jx(i, i) - 1
    end do
  end subroutine fixed_point_monodromy

  !> hx = d(M u)/dx = (M(x + h u) - M(x - h u))/(2h), h = x_step/max|u|.
  subroutine monodromy_x_derivative(map, x, p, u, hx)
    class(two_parameter_map), intent(in) :: map
    real(wp), intent(in) :: x(:), p(2), u(:)
    real(wp), intent(out) :: hx(:, :)
    real(wp) :: mp(size(x), size(x)), mm(size(x), size(x)), h, u_norm
    hx = 0
    u_norm = maxval(abs(u))
    if (.not. u_norm > 0) return
    h = x_step_of(map, x)/u_norm
    call monodromy_at(map, x + h*u, p, mp)
    call monodromy_at(map, x - h*u, p, mm)
    hx = (mp - mm)/(2*h)
  end subroutine monodromy_x_derivative

  !> dm(:, :, k) = dM/dp_k by central differences with steps p_step.
  subroutine monodromy_p_derivative(map, x, p, dm)
    class(two_parameter_map), intent(in) :: map
    real(wp), intent(in) :: x(:), p(2)
    real(wp), intent(out) :: dm(:, :, :)
    real(wp) :: mp(size(x), size(x)), mm(size(x), size(x)), dp(2)
    integer :: k
    do k = 1, 2
      dp = 0
      dp(k) = p_step_of(map, p, k)
      call monodromy_at(map, x, p + dp, mp)
      call monodromy_at(map, x, p - dp, mm)
      dm(:, :, k) = (mp - mm)/(2*dp(k))
    end do
  end subroutine monodromy_p_derivative

  real(wp) function x_step_of(map, x) result(h)
    class(two_parameter_map), intent(in) :: map
    real(wp), intent(in) :: x(:)
    h = map%x_step
    if (.not. h > 0) h = epsilon(1.0_wp)**(1.0_wp/3)*(1 + maxval(abs(x)))
  end function x_step_of

  real(wp) function p_step_of(map, p, k) result(h)
    class(two_parameter_map), intent(in) :: map
    real(wp), intent(in) :: p(2)
    integer, intent(in) :: k
    h = map%p_step(k)
    if (.not. h > 0) h = epsilon(1.0_wp)**(1.0_wp/3)*(1 + abs(p(k)))
  end function p_step_of

  !> hx = d(M u)/dx, hp = d(M u)/dp (d(J u) of the field J = M - I).
  subroutine map_jacobian_derivative(self, x, p, u, hx, hp)
    class(two_parameter_map), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2), u(:)
    real(wp), intent(out) :: hx(:, :), hp(:, :)
    real(wp) :: dm(size(x), size(x), 2)
    call monodromy_x_derivative(self, x, p, u, hx)
    call monodromy_p_derivative(self, x, p, dm)
    hp(:, 1) = matmul(dm(:, :, 1), u)
    hp(:, 2) = matmul(dm(:, :, 2), u)
  end subroutine map_jacobian_derivative

  !> B(u, v) = D^2_x P[u, v] = d(M u)/dx v (two maps, no parameter derivative).
  subroutine map_second_derivative(self, x, p, u, v, b)
    class(two_parameter_map), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2), u(:), v(:)
    real(wp), intent(out) :: b(:)
    real(wp) :: hx(size(x), size(x))
    call monodromy_x_derivative(self, x, p, u, hx)
    b = matmul(hx, v)
  end subroutine map_second_derivative

  ! ---- the stroboscopic map -----------------------------------------------------------------

  !> P, M (and dP/dp: one shot per parameter, each with its sensitivity) by shooting.
  subroutine stroboscopic_evaluate(self, x, p, px, mx, status, message, mp)
    class(stroboscopic_map), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2)
    real(wp), intent(out) :: px(:), mx(:, :)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), intent(out), optional :: mp(:, :)
    class(periodic_problem), allocatable :: problem
    real(wp) :: py(size(x)), my(size(x), size(x))
    integer :: k

    if (.not. present(mp)) then
      call self%problem(p, 1, problem)
      call monodromy_matrix(problem, x, self%periods, self%integration, self%method, px, mx, &
                            status, message)
      return
    end if
    do k = 1, 2
      call self%problem(p, k, problem)
      if (k == 1) then
        call monodromy_matrix(problem, x, self%periods, self%integration, self%method, px, mx, &
                              status, message, parameter_column=mp(:, 1))
      else
        call monodromy_matrix(problem, x, self%periods, self%integration, self%method, py, my, &
                              status, message, parameter_column=mp(:, 2))
      end if
      if (status /= SD_OK) return
    end do
  end subroutine stroboscopic_evaluate

  ! ---- the defining systems -----------------------------------------------------------------

  !> Fold, period-doubling or Neimark-Sacker system of the map with its first borders /
  !> reference vectors, and the start state s0.
  subroutine map_defining_system(field, kind, x0, p0, options, proto, s0, status, message)
    class(two_parameter_map), intent(in) :: field
    integer, intent(in) :: kind
    real(wp), intent(in) :: x0(:), p0(2)
    type(curve_options), intent(in) :: options
    class(curve_system), allocatable, intent(out) :: proto
    real(wp), allocatable, intent(out) :: s0(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: px(size(x0)), mx(size(x0), size(x0)), a(size(x0), size(x0)), v(size(x0)), &
                w(size(x0)), re(size(x0)), im(size(x0)), shift, radius
    integer :: n, i, best

    n = size(x0)
    call field%map(x0, p0, px, mx, status, message)
    if (status /= SD_OK) then
      message = 'the map at the start point: '//trim(message)
      return
    end if
    select case (kind)
    case (CURVE_FOLD, CURVE_PERIOD_DOUBLING)
      ! null vectors of M - I or M + I
      shift = merge(-1.0_wp, 1.0_wp, kind == CURVE_FOLD)
      a = mx
      do i = 1, n
        a(i, i) = a(i, i) + shift
      end do
      call null_vectors(a, v, w, status, message)
      if (status /= SD_OK) then
        message = 'no null vector of M '//merge('- I', '+ I', kind == CURVE_FOLD)// &
                  ' at the start point: '//trim(message)
        return
      end if
      allocate (map_fold_system :: proto)
      select type (proto)
      type is (map_fold_system)
        proto%c = v
        proto%b = w
        proto%shift = shift + 1   ! on f_x = M - I
      end select
      if (kind == CURVE_FOLD) then
        call setup_system(proto, field, kind, n, 0, p0, options, &
                          [CODIM2_R1, CODIM2_CUSP, CODIM2_FOLD_FLIP, CODIM2_FOLD_NS])
      else
        call setup_system(proto, field, kind, n, 0, p0, options, &
                          [CODIM2_R2, CODIM2_FOLD_FLIP, CODIM2_FLIP_NS, CODIM2_GF])
      end if
      s0 = [x0, p0]
    case (CURVE_NEIMARK_SACKER)
      if (n < 2) then
        status = SD_BAD_INPUT
        message = 'x0 has size 1; a Neimark-Sacker point needs n >= 2'
        return
      end if
      call eigenvalues(mx, re, im, status, message)
      if (status /= SD_OK) return
      best = nearest_pair(im, abs(hypot(re, im) - 1), 0.0_wp, huge(1.0_wp))
      if (best == 0) then
        status = SD_BAD_INPUT
        message = 'M has no complex multiplier pair at p = ('//num2str(p0(1))//', '// &
                  num2str(p0(2))//'): not near a Neimark-Sacker point'
        return
      end if
      ! v in the real plane of the pair: the null space of (M - mu)(M - conj mu)
      radius = hypot(re(best), im(best))
      a = matmul(mx, mx) - 2*re(best)*mx
      do i = 1, n
        a(i, i) = a(i, i) + radius**2
      end do
      call inverse_iteration(a, max(maxval(abs(mx))**2, 1.0_wp), v, status, message)
      if (status /= SD_OK) return
      allocate (neimark_sacker_system :: proto)
      select type (proto)
      type is (neimark_sacker_system)
        proto%kappa_scale = 1
        allocate (proto%v_ref(n), proto%u_ref(n))
      end select
      ! the 1:1 and 1:2 resonances end the curve (the pair leaves the unit circle)
      call setup_system(proto, field, kind, n, n + 1, p0, options, [CODIM2_R1, CODIM2_R2, &
                        CODIM2_R3, CODIM2_R4, CODIM2_FOLD_NS, CODIM2_FLIP_NS, CODIM2_CH], &
                        ends=[END_RESONANCE, END_RESONANCE])
      s0 = [x0, v, 2*re(best)/radius, p0]
    case default
      status = SD_BAD_INPUT
      message = 'a '//curve_kind_name(kind)//' curve is not a curve of fixed points of a '// &
                'map (fold, period-doubling or Neimark-Sacker)'
    end select
  end subroutine map_defining_system

  ! ---- fold and period-doubling curves ------------------------------------------------------

  !> Multipliers and the tests of the module header.
  subroutine map_fold_diagnose(self, z, re, im, tests, omega, l1, status, message)
    class(map_fold_system), intent(in) :: self
    real(wp), intent(in) :: z(:)
    real(wp), intent(out) :: re(:), im(:), tests(max_curve_tests), omega, l1
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: xx(self%n), p(2), jj(self%n, self%n), mm(self%n, self%n), v(self%n), &
                w(self%n), bvv(self%n)
    logical :: is_fold

    tests = ieee_value(1.0_wp, ieee_quiet_nan)
    omega = 0
    l1 = ieee_value(1.0_wp, ieee_quiet_nan)
    is_fold = self%kind == CURVE_FOLD
    call point_x_p(self, z, xx, p)
    call fixed_point_monodromy(self%field, xx, p, mm, jj)
    call eigenvalues(mm, re, im, status, message)
    if (status /= SD_OK) return
    call self%null_vectors(jj, v, w, status, message)
    if (status /= SD_OK) return
    tests(1) = sum(w*v)
    if (is_fold) then
      call self%field%second_derivative(xx, p, v, v, bvv)
      tests(2) = sum(w*bvv)
      tests(3) = period_doubling_test(re, im)
      tests(4) = pair_product_without(re, im, 1.0_wp)
    else
      tests(2) = fold_test(re, im)
      tests(3) = pair_product_without(re, im, -1.0_wp)
      tests(4) = normal_form_coefficient(self%field, CURVE_PERIOD_DOUBLING, xx, p, mm)
    end if
  end subroutine map_fold_diagnose

  !> Fold-NS and flip-NS need a complex pair on the unit circle (not a real pair mu, 1/mu).
  logical function map_fold_confirm(self, kind, re, im, tests) result(confirmed)
    class(map_fold_system), intent(in) :: self
    integer, intent(in) :: kind
    real(wp), intent(in) :: re(:), im(:), tests(:)
    confirmed = .true.
    if (kind == CODIM2_FOLD_NS .or. kind == CODIM2_FLIP_NS) confirmed = circle_pair(re, im) > 0
    if (kind == CODIM2_GF) confirmed = abs(tests(4)) <= cancellation_tol
  end function map_fold_confirm

  real(wp) function map_fold_codim2_frequency(self, kind, re, im, omega) result(angle)
    class(map_fold_system), intent(in) :: self
    integer, intent(in) :: kind
    real(wp), intent(in) :: re(:), im(:), omega
    integer :: i
    angle = 0
    select case (kind)
    case (CODIM2_R2, CODIM2_GF)
      angle = pi
    case (CODIM2_FOLD_NS, CODIM2_FLIP_NS)
      i = circle_pair(re, im)
      if (i > 0) angle = atan2(im(i), re(i))
    end select
  end function map_fold_codim2_frequency

  !> The multiplier with im > 0 nearest the unit circle if it is on it (circle_tol), else 0.
  pure integer function circle_pair(re, im) result(best)
    real(wp), intent(in) :: re(:), im(:)
    real(wp) :: scale
    scale = max(maxval(hypot(re, im)), 1.0_wp)
    best = nearest_pair(im, abs(hypot(re, im) - 1), circle_tol*scale, circle_tol*scale)
  end function circle_pair

  !> prod_{i<j} (mu_i mu_j - 1) over the multipliers but the one nearest `skip` (real): zero
  !> where two of the others have mu_i mu_j = 1 (a pair on the unit circle, or a real pair
  !> mu, 1/mu).
  pure real(wp) function pair_product_without(re, im, skip) result(product_value)
    real(wp), intent(in) :: re(:), im(:), skip
    complex(wp) :: mu(size(re)), prod
    integer :: i, j, nearest
    mu = cmplx(re, im, wp)
    nearest = minloc(abs(mu - skip), 1)
    prod = 1
    do i = 1, size(mu)
      if (i == nearest) cycle
      do j = i + 1, size(mu)
        if (j == nearest) cycle
        prod = prod*(mu(i)*mu(j) - 1)
      end do
    end do
    product_value = real(prod)
  end function pair_product_without

  !> The normal-form coefficient of the fixed point x at p, shared with the one-parameter
  !> criticality (sloshdyn_map_normal_form), over the size of its terms: the flip coefficient
  !> c (kind CURVE_PERIOD_DOUBLING) or the Neimark-Sacker coefficient d, relative; NaN (no
  !> test) for a map that is not a stroboscopic map, or where the coefficient fails. mx: M at
  !> (x, p) from fixed_point_monodromy, the one the coefficient would compute.
  function normal_form_coefficient(field, kind, x, p, mx) result(coefficient)
    class(two_parameter_field), intent(in) :: field
    integer, intent(in) :: kind
    real(wp), intent(in) :: x(:), p(2), mx(:, :)
    real(wp) :: coefficient
    class(periodic_problem), allocatable :: problem
    real(wp) :: q(size(x)), mu, terms
    complex(wp) :: q_complex(size(x)), mu_complex
    integer :: status
    character(len=message_len) :: message

    coefficient = ieee_value(1.0_wp, ieee_quiet_nan)
    select type (field)
    class is (stroboscopic_map)
      call field%problem(p, 1, problem)
      if (kind == CURVE_PERIOD_DOUBLING) then
        call cubic_coefficient(problem, x, field%periods, field%integration, field%method, &
                               -1, coefficient, q, mu, status, message, terms, mx)
      else
        call neimark_sacker_coefficient(problem, x, field%periods, field%integration, &
                                        field%method, coefficient, q_complex, mu_complex, &
                                        status, message, terms, mx)
      end if
      if (status /= SD_OK .or. .not. terms > 0) then
        coefficient = ieee_value(1.0_wp, ieee_quiet_nan)
      else
        coefficient = coefficient/terms
      end if
    end select
  end function normal_form_coefficient

  ! ---- Neimark-Sacker curves ----------------------------------------------------------------

  !> F = (P - x, (M^2 - kappa M + I) v, <v_ref, v> - 1, <u_ref, v>) (M3); z = (x/x_scale, v,
  !> kappa, q_other). Ten shots for a stroboscopic map: P, M, dP/dp (2), d(M u)/dx for u = v
  !> and M v (4), dM/dp (4).
  subroutine ns_evaluate(self, x, lambda, f, fx, flambda)
    class(neimark_sacker_system), intent(in) :: self
    real(wp), intent(in) :: x(:), lambda
    real(wp), intent(out) :: f(:), fx(:, :), flambda(:)
    real(wp) :: xx(self%n), p(2), px(self%n), mm(self%n, self%n), mp(self%n, 2), v(self%n), &
                mv(self%n), kappa, hv(self%n, self%n), hmv(self%n, self%n), &
                dm(self%n, self%n, 2), a(self%n, self%n), dp(self%n, 2)
    integer :: n, o, l, i, k, status
    character(len=message_len) :: message

    n = self%n
    o = self%other
    l = self%lam
    call split_x_p(self, x, lambda, xx, p)
    v = x(n + 1:2*n)
    kappa = x(2*n + 1)
    f = ieee_value(1.0_wp, ieee_quiet_nan)
    fx = 0
    flambda = 0
    select type (map => self%field)
    class is (two_parameter_map)
      call map%map(xx, p, px, mm, status, message, mp)
      if (status /= SD_OK) return
      mv = matmul(mm, v)
      call monodromy_x_derivative(map, xx, p, v, hv)
      call monodromy_x_derivative(map, xx, p, mv, hmv)
      call monodromy_p_derivative(map, xx, p, dm)
    class default
      return
    end select
    a = mm
    do i = 1, n
      a(i, i) = a(i, i) - kappa
    end do
    ! d[(M^2 - kappa M + I) v]/dp_k = dM_k (M v) + (M - kappa I) dM_k v
    do k = 1, 2
      dp(:, k) = matmul(dm(:, :, k), mv) + matmul(a, matmul(dm(:, :, k), v))
    end do
    f(1:n) = px - xx
    f(n + 1:2*n) = matmul(mm, mv) - kappa*mv + v
    f(2*n + 1) = sum(self%v_ref*v) - 1
    f(2*n + 2) = sum(self%u_ref*v)
    fx(1:n, 1:n) = mm*self%x_scale
    do i = 1, n
      fx(i, i) = fx(i, i) - self%x_scale
    end do
    fx(1:n, 2*n + 2) = mp(:, o)*self%p_scale(o)
    fx(n + 1:2*n, 1:n) = (hmv + matmul(a, hv))*self%x_scale
    fx(n + 1:2*n, n + 1:2*n) = matmul(a, mm)
    do i = 1, n
      fx(n + i, n + i) = fx(n + i, n + i) + 1
    end do
    fx(n + 1:2*n, 2*n + 1) = -mv
    fx(n + 1:2*n, 2*n + 2) = dp(:, o)*self%p_scale(o)
    fx(2*n + 1, n + 1:2*n) = self%v_ref
    fx(2*n + 2, n + 1:2*n) = self%u_ref
    flambda(1:n) = mp(:, l)*self%p_scale(l)
    flambda(n + 1:2*n) = dp(:, l)*self%p_scale(l)
  end subroutine ns_evaluate

  !> Multipliers; tests (R1, R2, R3, R4, fold-NS, flip-NS, Chenciner) of the module header;
  !> omega = theta.
  subroutine ns_diagnose(self, z, re, im, tests, omega, l1, status, message)
    class(neimark_sacker_system), intent(in) :: self
    real(wp), intent(in) :: z(:)
    real(wp), intent(out) :: re(:), im(:), tests(max_curve_tests), omega, l1
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: xx(self%n), p(2), jj(self%n, self%n), mm(self%n, self%n), kappa
    complex(wp) :: mu(self%n), root, minus, plus
    integer :: n, i, first, second

    n = self%n
    tests = ieee_value(1.0_wp, ieee_quiet_nan)
    l1 = ieee_value(1.0_wp, ieee_quiet_nan)
    call point_x_p(self, z, xx, p)
    kappa = z(2*n + 1)
    omega = kappa_angle(kappa)
    call fixed_point_monodromy(self%field, xx, p, mm, jj)
    call eigenvalues(mm, re, im, status, message)
    if (status /= SD_OK) return
    tests(1) = kappa - 2
    tests(2) = kappa + 2
    tests(3) = kappa + 1
    tests(4) = kappa
    ! the other multipliers: all but the two nearest the roots of mu^2 - kappa mu + 1
    mu = cmplx(re, im, wp)
    root = sqrt(cmplx(kappa**2/4 - 1, 0.0_wp, wp))
    first = minloc(abs(mu - (kappa/2 + root)), 1)
    second = minloc(abs(mu - (kappa/2 - root)), 1, mask=[(i /= first, i = 1, n)])
    minus = 1
    plus = 1
    do i = 1, n
      if (i == first .or. i == second) cycle
      minus = minus*(mu(i) - 1)
      plus = plus*(mu(i) + 1)
    end do
    tests(5) = real(minus)
    tests(6) = real(plus)
    if (abs(kappa) < 2) tests(7) = normal_form_coefficient(self%field, CURVE_NEIMARK_SACKER, &
                                                           xx, p, mm)
  end subroutine ns_diagnose

  !> theta = acos(kappa/2) for |kappa| <= 2; -acosh(|kappa|/2) = -ln|mu| beyond.
  pure real(wp) function kappa_angle(kappa) result(angle)
    real(wp), intent(in) :: kappa
    if (abs(kappa) <= 2) then
      angle = acos(kappa/2)
    else
      angle = -acosh(abs(kappa)/2)
    end if
  end function kappa_angle

  !> R3, R4, fold-NS and flip-NS need the pair on the unit circle (|kappa| < 2).
  logical function ns_confirm(self, kind, re, im, tests) result(confirmed)
    class(neimark_sacker_system), intent(in) :: self
    integer, intent(in) :: kind
    real(wp), intent(in) :: re(:), im(:), tests(:)
    confirmed = .true.
    if (kind /= CODIM2_R1 .and. kind /= CODIM2_R2) confirmed = tests(1) < 0 .and. tests(2) > 0
    if (kind == CODIM2_CH) confirmed = confirmed .and. abs(tests(7)) <= cancellation_tol
  end function ns_confirm

  real(wp) function ns_codim2_frequency(self, kind, re, im, omega) result(angle)
    class(neimark_sacker_system), intent(in) :: self
    integer, intent(in) :: kind
    real(wp), intent(in) :: re(:), im(:), omega
    select case (kind)
    case (CODIM2_R1)
      angle = 0
    case (CODIM2_R2)
      angle = pi
    case default
      angle = omega
    end select
  end function ns_codim2_frequency

  !> A Neimark-Sacker point has |kappa| < 2; else it is a neutral saddle of the map.
  function ns_neutral_saddle(self, s) result(saddle)
    class(neimark_sacker_system), intent(in) :: self
    real(wp), intent(in) :: s(:)
    character(len=:), allocatable :: saddle
    saddle = ''
    if (.not. abs(s(2*self%n + 1)) < 2) saddle = 'a neutral saddle of the map (real '// &
      'multipliers mu, 1/mu, mu + 1/mu = kappa = '//num2str(s(2*self%n + 1))//')'
  end function ns_neutral_saddle

  real(wp) function ns_frequency_of(self, s) result(angle)
    class(neimark_sacker_system), intent(in) :: self
    real(wp), intent(in) :: s(:)
    angle = kappa_angle(s(2*self%n + 1))
  end function ns_frequency_of
end module sloshdyn_map_bifurcation
