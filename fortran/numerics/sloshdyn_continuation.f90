!> Newton's method and Keller's pseudo-arclength continuation for F(x, lambda) = 0, x in R^n
!> (n small), lambda a scalar parameter (H. B. Keller, Numerical solution of bifurcation and
!> nonlinear eigenvalue problems, 1977; E. L. Allgower & K. Georg, Introduction to Numerical
!> Continuation Methods, 2003, ch. 2 and 9). Serves the steady states of the slow flow and
!> periodic orbits by shooting.
!>
!> Points on a branch are z = (x, lambda), of size n + 1. Arclength is measured in the weighted
!> norm ||dz||^2 = x_scale^2 |dx|^2 + dlambda^2, so that small amplitudes and O(1) parameters
!> both move; tangents are unit vectors in that norm.
!>
!> A step: predictor z + ds t, corrector Newton on the bordered system
!>   F(z) = 0,  <t, z - z_pred> = 0           ((n+1) x (n+1), LAPACK dgesv)
!> then the new tangent v from [J; (W t_prev)^T] v = e_(n+1), J = [dF/dx, dF/dlambda] at the
!> new point, W = diag(x_scale^2, .., 1). By Cramer's rule v = c/det [J; (W t_prev)^T] with c
!> the cofactor vector of J (c spans the null space of J), so det [J; v^T] = |c|^2/det [J;
!> (W t_prev)^T]: the new tangent keeps the sign of the bordered determinant with t_prev, and
!> <t_prev, v> = 1 > 0. This orientation passes folds, where the lambda-component of t changes
!> sign, and goes straight through simple branch points, where sign det [J; t^T] along the
!> branch flips (the Allgower-Georg rule, which keeps that sign, would turn back there).
module sloshdyn_continuation
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_value, ieee_quiet_nan
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, SD_NOT_CONVERGED, SD_SINGULAR, &
                             SD_NON_FINITE, check_real
  use sloshdyn_text, only: num2str
  use sloshdyn_cancel, only: check_cancel
  use sloshdyn_lapack, only: solve_linear
  use sloshdyn_roots, only: bracketed_function, brent_zero
  implicit none
  private
  public :: parametrised_system, system_evaluate, separable_system, system_residual, &
            system_jacobian, branch_test, branch_test_value
  public :: newton_options, continuation_options
  public :: newton_solve, continue_branch, correct_at, branch_tangent, locate_fold, &
            locate_zero_on_branch, continuation_check_options, stop_reason_name
  public :: STOP_NONE, STOP_LAMBDA_MIN, STOP_LAMBDA_MAX, STOP_MAX_POINTS, STOP_CLOSED, &
            STOP_X_MAX, STOP_FAILED

  !> A system F(x, lambda) = 0 with its Jacobian; extend it with the parameters F depends on.
  !> n = size(x); f, flambda have size n and fx shape (n, n). F and its Jacobian come from one
  !> evaluation, so a system whose evaluation is costly (shooting) needs no cache.
  !> residual_only (F alone, for the quasi-Newton iterations of newton_options%reuse_jacobian)
  !> defaults to evaluate without its Jacobian; override it where F alone costs less.
  type, abstract :: parametrised_system
  contains
    procedure(system_evaluate), deferred :: evaluate
    procedure :: residual_only => evaluate_residual_only
  end type parametrised_system

  abstract interface
    !> f = F(x, lambda), fx = dF/dx (n x n), flambda = dF/dlambda (n)
    subroutine system_evaluate(self, x, lambda, f, fx, flambda)
      import :: wp, parametrised_system
      class(parametrised_system), intent(in) :: self
      real(wp), intent(in) :: x(:), lambda
      real(wp), intent(out) :: f(:), fx(:, :), flambda(:)
    end subroutine system_evaluate
  end interface

  !> A system that computes F and its Jacobian separately: evaluate calls both.
  type, abstract, extends(parametrised_system) :: separable_system
  contains
    procedure(system_residual), deferred :: residual
    procedure(system_jacobian), deferred :: jacobian
    procedure :: evaluate => separable_evaluate
  end type separable_system

  abstract interface
    !> f = F(x, lambda)
    subroutine system_residual(self, x, lambda, f)
      import :: wp, separable_system
      class(separable_system), intent(in) :: self
      real(wp), intent(in) :: x(:), lambda
      real(wp), intent(out) :: f(:)
    end subroutine system_residual

    !> fx = dF/dx (n x n), flambda = dF/dlambda (n)
    subroutine system_jacobian(self, x, lambda, fx, flambda)
      import :: wp, separable_system
      class(separable_system), intent(in) :: self
      real(wp), intent(in) :: x(:), lambda
      real(wp), intent(out) :: fx(:, :), flambda(:)
    end subroutine system_jacobian
  end interface

  !> A scalar test function along a branch (a fold: the lambda-component of t; a Hopf point:
  !> the caller's Delta_3), whose zeros locate_zero_on_branch finds.
  type, abstract :: branch_test
    !> locate_zero_on_branch also stops when |value| <= value_tol (0 = only the arclength
    !> criterion)
    real(wp) :: value_tol = 0
  contains
    procedure(branch_test_value), deferred :: value
  end type branch_test

  abstract interface
    !> Test value at the branch point z = (x, lambda) with unit tangent t.
    function branch_test_value(self, z, t) result(g)
      import :: wp, branch_test
      class(branch_test), intent(in) :: self
      real(wp), intent(in) :: z(:), t(:)
      real(wp) :: g
    end function branch_test_value
  end interface

  !> Newton settings. Converged when max|step| <= x_tol*(1 + max|x|) and max|F| <= f_tol
  !> (F at the start of the last iteration, so the returned x is one step better still).
  type :: newton_options
    real(wp) :: x_tol = 1.0e-11_wp  !< relative step tolerance, > 0
    real(wp) :: f_tol = 1.0e-11_wp  !< absolute residual tolerance, > 0
    integer :: max_iter = 20        !< iterations (Jacobian solves), >= 1
    !> quasi-Newton iterations: the Jacobian of the first iteration, or the last one evaluated
    !> (a tangent's, in continue_branch and along a branch: the point's before), updated after
    !> every step by Broyden's rank-one secant formula (Dennis & Schnabel, Numerical Methods
    !> for Unconstrained Optimization and Nonlinear Equations, 1983, section 8.1), and F
    !> alone evaluated (sys%residual_only): for systems whose Jacobian costs several F
    !> (finite differences). Converges superlinearly, not quadratically.
    logical :: reuse_jacobian = .false.
  end type newton_options

  !> Continuation settings. Steps are pseudo-arclength in the weighted norm (see the header).
  type :: continuation_options
    real(wp) :: ds = 0.01_wp       !< first step, > 0 (direction gives the sense)
    real(wp) :: ds_min = 1.0e-8_wp !< smallest step, in (0, ds]; failing at it ends the branch
    real(wp) :: ds_max = 0.1_wp    !< largest step, >= ds
    integer :: max_points = 1000   !< points to compute at most (the start included), >= 2
    real(wp) :: lambda_min = -huge(1.0_wp)  !< the branch ends on lambda_min ...
    real(wp) :: lambda_max = huge(1.0_wp)   !< ... or lambda_max (> lambda_min)
    integer :: direction = 1       !< +1 / -1: the first step increases / decreases lambda
    real(wp) :: x_max = huge(1.0_wp)  !< stop after the first point with max|x| > x_max (> 0)
    real(wp) :: x_scale = 1        !< weight of the x-components in the arclength norm, > 0
    type(newton_options) :: newton !< for the start point, the corrector and the end point
  end type continuation_options

  !> Why continue_branch stopped (stop_reason_name gives the words).
  integer, parameter :: STOP_NONE = 0        !< no branch computed (bad input, failed start)
  integer, parameter :: STOP_LAMBDA_MIN = 1  !< left the interval: last point at lambda_min
  integer, parameter :: STOP_LAMBDA_MAX = 2  !< left the interval: last point at lambda_max
  integer, parameter :: max_points_limit = 10000000
  integer, parameter :: STOP_MAX_POINTS = 3  !< max_points computed
  integer, parameter :: STOP_CLOSED = 4      !< closed loop (isola): last point = first point
  integer, parameter :: STOP_X_MAX = 5       !< the last point has max|x| > x_max
  integer, parameter :: STOP_FAILED = 6      !< no step >= ds_min converged (SD_NOT_CONVERGED)

  !> Step control. A step is accepted only if the tangent turned by less than acos(min_turn_cos)
  !> (~26 deg) and the corrector moved the point by less than max_correction*ds off the
  !> predictor: larger moves mean the step cut a corner or jumped to another part of the branch.
  real(wp), parameter :: min_turn_cos = 0.9_wp
  real(wp), parameter :: max_correction = 0.5_wp
  !> ds doubles after a step whose corrector needed at most fast_iterations iterations and whose
  !> tangent turned by less than acos(grow_turn_cos) (~8 deg).
  integer, parameter :: fast_iterations = 3
  !> ... or reuse_fast_iterations for a quasi-Newton corrector (newton_options%reuse_jacobian),
  !> which converges more slowly than Newton's
  integer, parameter :: reuse_fast_iterations = 5
  real(wp), parameter :: grow_turn_cos = 0.99_wp
  !> locate_fold: |lambda-component of the unit tangent| at which the fold counts as found.
  real(wp), parameter :: fold_tol = 1.0e-10_wp
  !> locate_zero_on_branch: arclength interval (relative to |ds_total|).
  real(wp), parameter :: arclength_rtol = 1.0e-12_wp

  !> Work arrays, allocated once per public call (never inside a loop).
  type :: workspace
    real(wp), allocatable :: f(:)          !< F (n)
    real(wp), allocatable :: fx(:, :)      !< dF/dx (n, n)
    real(wp), allocatable :: flambda(:)    !< dF/dlambda (n)
    real(wp), allocatable :: a(:, :)       !< bordered matrix (n+1, n+1)
    real(wp), allocatable :: r(:)          !< right-hand side, then solution (n+1)
    real(wp), allocatable :: f_old(:)      !< F of the iteration before (quasi-Newton, n)
    logical :: jacobian_ready = .false.    !< fx, flambda hold a branch point's (tangent_core)
  end type workspace

  !> A branch_test as a function of the pseudo-arclength s from a point (for brent_zero).
  type, extends(bracketed_function) :: arclength_test
    class(parametrised_system), allocatable :: sys
    class(branch_test), allocatable :: test
    real(wp), allocatable :: z_a(:), t_unit(:), w(:), c(:), z(:), t(:)
    type(newton_options) :: newton
    type(workspace) :: ws
    real(wp) :: s_last = 0
  contains
    procedure :: value => arclength_test_value
  end type arclength_test

  !> Fold test: one component of the tangent; index 0 = the last one, lambda.
  type, extends(branch_test) :: tangent_component_test
    integer :: index = 0
  contains
    procedure :: value => tangent_component_value
  end type tangent_component_test

contains

  !> Newton's method for F(x, lambda) = 0 at fixed lambda; x is updated in place (on failure it
  !> holds the last iterate). iterations = Jacobian solves done. Undamped. explain = .false.
  !> gives failure messages without the iterate's numbers: formatting them costs more than a
  !> failed run, and scans of Newton starts (frequency_response) make thousands that fail.
  subroutine newton_solve(sys, x, lambda, options, iterations, status, message, explain)
    class(parametrised_system), intent(in) :: sys
    real(wp), intent(inout) :: x(:)
    real(wp), intent(in) :: lambda
    type(newton_options), intent(in) :: options
    integer, intent(out) :: iterations, status
    character(len=message_len), intent(out) :: message
    logical, intent(in), optional :: explain
    type(workspace) :: ws

    status = SD_OK
    message = ''
    iterations = 0
    call check_newton_options(options, '', status, message)
    call check_vector('x', x, 1, status, message)
    call check_real('lambda', lambda, -huge(lambda), huge(lambda), .false., .false., &
                    'lambda must be finite', status, message)
    if (status /= SD_OK) return
    call setup_workspace(ws, size(x))
    call newton_core(sys, x, lambda, options, ws, iterations, status, message, explain)
  end subroutine newton_solve

  !> Follow the branch through (x0, lambda0) by pseudo-arclength continuation. x0 is first
  !> corrected by Newton at lambda0. Results: points(:, k) = (x, lambda) and tangents(:, k)
  !> (unit in the weighted norm) for k = 1..n_points, arclength(k) = pseudo-arclength from the
  !> start (sum of <t_(k-1), z_k - z_(k-1)>); columns beyond n_points are NaN.
  !> points and tangents need n + 1 rows and at least max_points columns.
  !> stop_reason is one of STOP_*. If no step >= ds_min converges, status = SD_NOT_CONVERGED,
  !> stop_reason = STOP_FAILED and the points so far are kept (the branch is incomplete).
  !> With tangent0 (a direction in z, e.g. off a branch point onto another branch), the start
  !> is corrected on the hyperplane through (x0, lambda0) normal to tangent0 instead of at fixed
  !> lambda, and the first tangent is oriented along tangent0 (<tangent0, t> > 0), not by
  !> options%direction.
  subroutine continue_branch(sys, x0, lambda0, options, points, tangents, arclength, n_points, &
                             stop_reason, status, message, tangent0)
    class(parametrised_system), intent(in) :: sys
    real(wp), intent(in) :: x0(:), lambda0
    type(continuation_options), intent(in) :: options
    real(wp), intent(out) :: points(:, :), tangents(:, :), arclength(:)
    integer, intent(out) :: n_points, stop_reason, status
    character(len=message_len), intent(out) :: message
    real(wp), intent(in), optional :: tangent0(:)
    type(workspace) :: ws
    real(wp), allocatable :: w(:), c(:), z(:), t(:), z_new(:), t_new(:), z_pred(:)
    real(wp) :: ds, cos_turn, g_prev, g_new, theta, bound, step_length
    integer :: n, m, iterations, step_status
    character(len=message_len) :: step_message
    logical :: accepted

    status = SD_OK
    message = ''
    n_points = 0
    stop_reason = STOP_NONE
    points = ieee_value(1.0_wp, ieee_quiet_nan)
    tangents = ieee_value(1.0_wp, ieee_quiet_nan)
    arclength = ieee_value(1.0_wp, ieee_quiet_nan)
    n = size(x0)
    m = n + 1
    call continuation_check_options(options, status, message)
    call check_vector('x0', x0, 1, status, message)
    call check_real('lambda0', lambda0, options%lambda_min, options%lambda_max, .false., &
                    .false., 'lambda0 must lie in [lambda_min, lambda_max] = ['// &
                    num2str(options%lambda_min)//', '//num2str(options%lambda_max)//']', &
                    status, message)
    call check_shape('points', points, m, options%max_points, status, message)
    call check_shape('tangents', tangents, m, options%max_points, status, message)
    if (status == SD_OK .and. size(arclength) < options%max_points) then
      status = SD_BAD_INPUT
      message = 'arclength has size '//num2str(size(arclength))//'; it needs at least '// &
                'max_points = '//num2str(options%max_points)
    end if
    if (status /= SD_OK) return

    call setup_workspace(ws, n)
    allocate (w(m), c(m), z(m), t(m), z_new(m), t_new(m), z_pred(m))
    w(1:n) = options%x_scale**2
    w(m) = 1

    z(1:n) = x0
    z(m) = lambda0
    if (present(tangent0)) then
      call check_vector('tangent0', tangent0, m, status, message)
      if (status == SD_OK .and. all(tangent0 == 0)) then
        status = SD_BAD_INPUT
        message = 'tangent0 is zero: it must give the start direction'
      end if
      if (status /= SD_OK) return
      c = w*tangent0/wnorm(tangent0, w)
      call bordered_newton(sys, z, c, sum(c*z), options%newton, ws, iterations, status, message)
    else
      call newton_core(sys, z(1:n), lambda0, options%newton, ws, iterations, status, message)
    end if
    if (status /= SD_OK) then
      message = 'the start point is not near a solution: '//trim(message)
      return
    end if
    if (present(tangent0)) then
      call tangent_core(sys, z, c, w, ws, t, status, message)
    else
      call initial_tangent(sys, z, w, options%direction, ws, c, t, status, message)
    end if
    if (status /= SD_OK) return
    n_points = 1
    points(:, 1) = z
    tangents(:, 1) = t
    arclength(1) = 0
    if (maxval(abs(z(1:n))) > options%x_max) then
      stop_reason = STOP_X_MAX
      return
    end if

    ds = options%ds
    do
      call check_cancel(status, message)
      if (status /= SD_OK) return
      if (n_points >= options%max_points) then
        stop_reason = STOP_MAX_POINTS
        exit
      end if

      ! predictor and bordered corrector
      c = w*t
      z_pred = z + ds*t
      z_new = z_pred
      call bordered_newton(sys, z_new, c, sum(c*z_pred), options%newton, ws, iterations, &
                           step_status, step_message)
      accepted = step_status == SD_OK
      cos_turn = 1
      if (accepted) then
        call tangent_core(sys, z_new, c, w, ws, t_new, step_status, step_message)
        accepted = step_status == SD_OK
      end if
      if (accepted) then
        cos_turn = sum(w*t*t_new)
        if (cos_turn < min_turn_cos) then
          accepted = .false.
          step_message = 'the tangent turned by '// &
                         num2str(acos(max(-1.0_wp, cos_turn))*180/pi)// &
                         ' degrees in one step'
        else if (distance(z_new, z_pred, w) > max_correction*ds) then
          accepted = .false.
          step_message = 'the corrector moved '//num2str(distance(z_new, z_pred, w))// &
                         ' off the predicted point'
        end if
      end if

      ! left [lambda_min, lambda_max]: end exactly on the bound, from the interpolated point
      if (accepted .and. (z_new(m) > options%lambda_max .or. z_new(m) < options%lambda_min)) then
        bound = merge(options%lambda_max, options%lambda_min, z_new(m) > options%lambda_max)
        theta = (bound - z(m))/(z_new(m) - z(m))
        step_length = distance(z_new, z, w)
        z_pred = z + theta*(z_new - z)
        z_pred(m) = bound
        z_new = z_pred
        call newton_core(sys, z_new(1:n), bound, options%newton, ws, iterations, step_status, &
                         step_message)
        accepted = step_status == SD_OK
        if (accepted) then
          if (distance(z_new, z_pred, w) > step_length) then
            accepted = .false.
            step_message = 'Newton at lambda = '//num2str(bound)//' went '// &
                           num2str(distance(z_new, z_pred, w))//' away from the branch'
          end if
        end if
        if (accepted) then
          call tangent_core(sys, z_new, c, w, ws, t_new, step_status, step_message)
          accepted = step_status == SD_OK
        end if
        if (accepted) then
          n_points = n_points + 1
          call store(z_new, t_new)
          stop_reason = merge(STOP_LAMBDA_MAX, STOP_LAMBDA_MIN, bound == options%lambda_max)
          exit
        end if
      end if

      if (.not. accepted) then
        if (ds <= options%ds_min) then
          status = SD_NOT_CONVERGED
          stop_reason = STOP_FAILED
          message = 'continuation stopped after '//num2str(n_points)//' points: no step >= '// &
                    'ds_min = '//num2str(options%ds_min)//' converged from lambda = '// &
                    num2str(z(m))//', max|x| = '//num2str(maxval(abs(z(1:n))))// &
                    '; last attempt: '//trim(step_message)
          exit
        end if
        ds = max(ds/2, options%ds_min)
        cycle
      end if

      ! closed loop: the step crosses the hyperplane through the start, normal to the first
      ! tangent, from behind, within one step length of the start
      g_prev = sum(w*tangents(:, 1)*(z - points(:, 1)))
      g_new = sum(w*tangents(:, 1)*(z_new - points(:, 1)))
      if (g_prev < 0 .and. g_new >= 0) then
        theta = g_prev/(g_prev - g_new)
        z_pred = z + theta*(z_new - z)
        if (distance(z_pred, points(:, 1), w) <= distance(z_new, z, w)) then
          z_new = points(:, 1)
          t_new = tangents(:, 1)
          n_points = n_points + 1
          call store(z_new, t_new)
          stop_reason = STOP_CLOSED
          exit
        end if
      end if

      n_points = n_points + 1
      call store(z_new, t_new)
      if (maxval(abs(z(1:n))) > options%x_max) then
        stop_reason = STOP_X_MAX
        exit
      end if
      if (iterations <= merge(reuse_fast_iterations, fast_iterations, &
                            options%newton%reuse_jacobian) &
          .and. cos_turn >= grow_turn_cos) &
        ds = min(2*ds, options%ds_max)
    end do

  contains

    !> Append point n_points with its tangent and make it the current point.
    subroutine store(z_k, t_k)
      real(wp), intent(in) :: z_k(:), t_k(:)
      points(:, n_points) = z_k
      tangents(:, n_points) = t_k
      arclength(n_points) = arclength(n_points - 1) + sum(w*t*(z_k - z))
      z = z_k
      t = t_k
    end subroutine store
  end subroutine continue_branch

  !> The branch point z at pseudo-arclength ds from z_a along t_a: predictor z_a + ds t_a,
  !> corrector Newton on F(z) = 0, <t_a, z - z_pred> = 0. t_a is first normalised in the
  !> weighted norm. options (optional) gives x_scale and the Newton tolerances (defaults:
  !> x_scale = 1, newton_options()).
  subroutine correct_at(sys, z_a, t_a, ds, z, status, message, options)
    class(parametrised_system), intent(in) :: sys
    real(wp), intent(in) :: z_a(:), t_a(:), ds
    real(wp), intent(out) :: z(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(continuation_options), intent(in), optional :: options
    type(workspace) :: ws
    type(newton_options) :: newton
    real(wp) :: w(size(z_a)), c(size(z_a)), t_unit(size(z_a))
    integer :: iterations

    z = z_a
    call prepare(z_a, t_a, 'correct_at', options, w, newton, t_unit, status, message)
    call check_real('ds', ds, -huge(ds), huge(ds), .false., .false., 'ds must be finite', &
                    status, message)
    if (status == SD_OK .and. size(z) /= size(z_a)) &
      call size_error('z', size(z), 'z_a', size(z_a), status, message)
    if (status /= SD_OK) return
    call setup_workspace(ws, size(z_a) - 1)
    call correct_core(sys, z_a, t_unit, ds, w, newton, ws, c, z, iterations, status, message)
  end subroutine correct_at

  !> The unit tangent t at the branch point z (weighted norm), oriented like t_prev:
  !> sign det [dF/dx, dF/dlambda; t^T] = sign det [dF/dx, dF/dlambda; t_prev^T], i.e.
  !> <t, t_prev> > 0. options (optional) gives x_scale.
  subroutine branch_tangent(sys, z, t_prev, t, status, message, options)
    class(parametrised_system), intent(in) :: sys
    real(wp), intent(in) :: z(:), t_prev(:)
    real(wp), intent(out) :: t(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(continuation_options), intent(in), optional :: options
    type(workspace) :: ws
    type(newton_options) :: newton
    real(wp) :: w(size(z)), t_unit(size(z)), c(size(z))

    t = 0
    call prepare(z, t_prev, 'branch_tangent', options, w, newton, t_unit, status, message)
    if (status == SD_OK .and. size(t) /= size(z)) &
      call size_error('t', size(t), 'z', size(z), status, message)
    if (status /= SD_OK) return
    call setup_workspace(ws, size(z) - 1)
    c = w*t_unit
    call tangent_core(sys, z, c, w, ws, t, status, message)
  end subroutine branch_tangent

  !> The fold (limit point in lambda) between consecutive branch points z_a, z_b whose tangents
  !> t_a, t_b have lambda-components of opposite sign: where the lambda-component of the unit
  !> tangent vanishes, to |t_lambda| <= 1e-10 or an arclength interval <= 1e-12 relative.
  !> z_b must lie ahead of z_a along t_a. options (optional) as for correct_at: pass those of
  !> the branch when its x_scale is not 1.
  subroutine locate_fold(sys, z_a, t_a, z_b, t_b, z_fold, status, message, options)
    class(parametrised_system), intent(in) :: sys
    real(wp), intent(in) :: z_a(:), t_a(:), z_b(:), t_b(:)
    real(wp), intent(out) :: z_fold(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(continuation_options), intent(in), optional :: options
    type(tangent_component_test) :: fold
    type(newton_options) :: newton
    real(wp) :: w(size(z_a)), t_unit(size(z_a)), ds_total
    integer :: m

    m = size(z_a)
    z_fold = z_a
    call prepare(z_a, t_a, 'locate_fold', options, w, newton, t_unit, status, message)
    if (status == SD_OK .and. size(z_b) /= m) &
      call size_error('z_b', size(z_b), 'z_a', m, status, message)
    if (status == SD_OK .and. size(t_b) /= m) &
      call size_error('t_b', size(t_b), 'z_a', m, status, message)
    if (status == SD_OK .and. size(z_fold) /= m) &
      call size_error('z_fold', size(z_fold), 'z_a', m, status, message)
    call check_vector('z_b', z_b, 2, status, message)
    call check_vector('t_b', t_b, 2, status, message)
    if (status /= SD_OK) return
    if (t_a(m) == 0) return
    if (t_b(m) == 0) then
      z_fold = z_b
      return
    end if
    if (t_a(m)*t_b(m) > 0) then
      status = SD_BAD_INPUT
      message = 'no fold between z_a and z_b: the lambda-components of t_a and t_b ('// &
                num2str(t_a(m))//', '//num2str(t_b(m))//') have the same sign'
      return
    end if
    ds_total = sum(w*t_unit*(z_b - z_a))
    if (.not. ds_total > 0) then
      status = SD_BAD_INPUT
      message = 'z_b does not lie ahead of z_a along t_a (pseudo-arclength '// &
                num2str(ds_total)//')'
      return
    end if
    fold%value_tol = fold_tol
    call locate_zero_on_branch(sys, z_a, t_a, ds_total, fold, z_fold, status, message, options)
    if (status /= SD_OK) message = 'locate_fold: '//trim(message)
  end subroutine locate_fold

  !> A zero of test%value(z(s), t(s)) for s between 0 and ds_total, where z(s) = correct_at(z_a,
  !> t_a, s) and t(s) its tangent oriented like t_a: Brent's method (bisection safeguarding
  !> secant and inverse quadratic steps) to an arclength interval <= 1e-12 |ds_total| or
  !> |value| <= test%value_tol. The values at s = 0 and ds_total must differ in sign. Between
  !> two stored points k, k+1 of a branch, ds_total = arclength(k+1) - arclength(k).
  subroutine locate_zero_on_branch(sys, z_a, t_a, ds_total, test, z_zero, status, message, &
                                   options)
    class(parametrised_system), intent(in) :: sys
    real(wp), intent(in) :: z_a(:), t_a(:), ds_total
    class(branch_test), intent(in) :: test
    real(wp), intent(out) :: z_zero(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(continuation_options), intent(in), optional :: options
    type(arclength_test) :: along
    integer :: m
    real(wp) :: g_a, g_b, s, g

    z_zero = z_a
    m = size(z_a)
    allocate (along%w(m), along%t_unit(m), along%c(m), along%z(m), along%t(m))
    call prepare(z_a, t_a, 'locate_zero_on_branch', options, along%w, along%newton, &
                 along%t_unit, status, message)
    call check_real('ds_total', ds_total, -huge(ds_total), huge(ds_total), .false., .false., &
                    'ds_total must be finite', status, message)
    if (status == SD_OK .and. ds_total == 0) then
      status = SD_BAD_INPUT
      message = 'ds_total = 0 is out of range: the search interval is empty'
    end if
    if (status == SD_OK .and. size(z_zero) /= m) &
      call size_error('z_zero', size(z_zero), 'z_a', m, status, message)
    if (status /= SD_OK) return
    allocate (along%sys, source=sys)
    allocate (along%test, source=test)
    along%z_a = z_a
    call setup_workspace(along%ws, m - 1)

    g_a = test%value(z_a, along%t_unit)
    if (abs(g_a) <= test%value_tol) return
    call along%value(ds_total, g_b, status, message)
    if (status /= SD_OK) return
    z_zero = along%z
    if (abs(g_b) <= test%value_tol) return
    if (g_a*g_b > 0) then
      status = SD_BAD_INPUT
      message = 'the test function has the same sign at both ends (s = 0: '//num2str(g_a)// &
                ', s = '//num2str(ds_total)//': '//num2str(g_b)//'): no zero is bracketed'
      z_zero = z_a
      return
    end if
    call brent_zero(along, 0.0_wp, ds_total, g_a, g_b, arclength_rtol*abs(ds_total), &
                    test%value_tol, s, g, status, message)
    ! the point of the last evaluation may be the other end of the bracket
    if (status == SD_OK .and. s /= along%s_last) call along%value(s, g, status, message)
    z_zero = along%z
    if (status /= SD_OK) message = 'locating the zero of the test function along the branch '// &
                                   '(lambda = '//num2str(along%z(m))//'): '//trim(message)
  end subroutine locate_zero_on_branch

  !> The branch point at arclength s from z_a (predictor z_a + s t_a, bordered corrector) and
  !> the test value there; z and t keep that point and its tangent.
  subroutine arclength_test_value(self, x, fx, status, message)
    class(arclength_test), intent(inout) :: self
    real(wp), intent(in) :: x
    real(wp), intent(out) :: fx
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    integer :: iterations
    fx = 0
    status = SD_OK
    message = ''
    self%s_last = x
    if (x == 0) then
      self%z = self%z_a
      fx = self%test%value(self%z_a, self%t_unit)
      return
    end if
    call correct_core(self%sys, self%z_a, self%t_unit, x, self%w, self%newton, self%ws, self%c, &
                      self%z, iterations, status, message)
    if (status == SD_OK) call tangent_core(self%sys, self%z, self%c, self%w, self%ws, self%t, &
                                           status, message)
    if (status /= SD_OK) then
      message = 'at arclength '//num2str(x)//' from z_a: '//trim(message)
      return
    end if
    fx = self%test%value(self%z, self%t)
  end subroutine arclength_test_value

  !> Checks of continuation_options shared by continue_branch and input readers.
  pure subroutine continuation_check_options(options, status, message)
    type(continuation_options), intent(in) :: options
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    real(wp), parameter :: big = huge(1.0_wp)

    call check_real('ds', options%ds, 0.0_wp, big, .true., .false., &
                    'ds must be > 0 (direction gives the sense)', status, message)
    call check_real('ds_min', options%ds_min, 0.0_wp, options%ds, .true., .false., &
                    'ds_min must lie in (0, ds = '//num2str(options%ds)//']', status, message)
    call check_real('ds_max', options%ds_max, options%ds, big, .false., .false., &
                    'ds_max must be >= ds = '//num2str(options%ds), status, message)
    ! at most 10**7 points: the tables are allocated up front (about 1 GB for the largest)
    if (status == SD_OK .and. (options%max_points < 2 .or. options%max_points > max_points_limit)) then
      status = SD_BAD_INPUT
      message = 'max_points = '//num2str(options%max_points)//' is out of range: it must lie '// &
                'in [2, '//num2str(max_points_limit)//']'
    end if
    call check_real('lambda_min', options%lambda_min, -big, big, .false., .false., &
                    'lambda_min must be finite', status, message)
    call check_real('lambda_max', options%lambda_max, options%lambda_min, big, .true., .false., &
                    'lambda_max must be > lambda_min = '//num2str(options%lambda_min), status, &
                    message)
    if (status == SD_OK .and. abs(options%direction) /= 1) then
      status = SD_BAD_INPUT
      message = 'direction = '//num2str(options%direction)//' is out of range: it must be +1 '// &
                '(increasing lambda) or -1'
    end if
    call check_real('x_max', options%x_max, 0.0_wp, big, .true., .false., 'x_max must be > 0', &
                    status, message)
    call check_real('x_scale', options%x_scale, 0.0_wp, big, .true., .false., &
                    'x_scale must be > 0', status, message)
    call check_newton_options(options%newton, 'newton%', status, message)
  end subroutine continuation_check_options

  !> Words for a STOP_* code.
  pure function stop_reason_name(code) result(name)
    integer, intent(in) :: code
    character(len=len_trim(stop_reason_text(code))) :: name
    name = stop_reason_text(code)
  end function stop_reason_name

  !> stop_reason_name's words, fixed length: a deferred-length result would keep its length in
  !> a static variable shared by threads (see sloshdyn_text).
  pure function stop_reason_text(code) result(name)
    integer, intent(in) :: code
    character(len=32) :: name
    select case (code)
    case (STOP_NONE);       name = 'not started'
    case (STOP_LAMBDA_MIN); name = 'reached lambda_min'
    case (STOP_LAMBDA_MAX); name = 'reached lambda_max'
    case (STOP_MAX_POINTS); name = 'max_points computed'
    case (STOP_CLOSED);     name = 'closed loop (isola)'
    case (STOP_X_MAX);      name = 'max|x| exceeded x_max'
    case (STOP_FAILED);     name = 'step fell below ds_min'
    case default;           name = 'unknown stop reason'
    end select
  end function stop_reason_text

  ! ---- private ----------------------------------------------------------------------------

  subroutine separable_evaluate(self, x, lambda, f, fx, flambda)
    class(separable_system), intent(in) :: self
    real(wp), intent(in) :: x(:), lambda
    real(wp), intent(out) :: f(:), fx(:, :), flambda(:)
    call self%residual(x, lambda, f)
    call self%jacobian(x, lambda, fx, flambda)
  end subroutine separable_evaluate

  function tangent_component_value(self, z, t) result(g)
    class(tangent_component_test), intent(in) :: self
    real(wp), intent(in) :: z(:), t(:)
    real(wp) :: g
    g = t(merge(size(z), self%index, self%index == 0))
  end function tangent_component_value

  !> Newton at fixed lambda, work arrays from ws (explain: as in newton_solve).
  subroutine newton_core(sys, x, lambda, options, ws, iterations, status, message, explain)
    class(parametrised_system), intent(in) :: sys
    real(wp), intent(inout) :: x(:)
    real(wp), intent(in) :: lambda
    type(newton_options), intent(in) :: options
    type(workspace), intent(inout) :: ws
    integer, intent(out) :: iterations, status
    character(len=message_len), intent(out) :: message
    logical, intent(in), optional :: explain
    real(wp) :: f_norm
    integer :: n
    logical :: numbers

    numbers = .true.
    if (present(explain)) numbers = explain
    n = size(x)
    status = SD_OK
    message = ''
    f_norm = 0
    do iterations = 1, options%max_iter
      call evaluate_for_newton(sys, x, lambda, options, iterations, ws)
      f_norm = maxval(abs(ws%f))
      if (.not. all(ieee_is_finite(ws%f))) then
        status = SD_NON_FINITE
        message = 'F is NaN or infinite'
        if (numbers) message = 'F is NaN or infinite at Newton iteration '//num2str(iterations)// &
                               ', lambda = '//num2str(lambda)//', max|x| = '//num2str(maxval(abs(x)))
        return
      end if
      if (options%reuse_jacobian .and. iterations > 1) call broyden_update(ws, ws%r(1:n), .false.)
      ws%r(1:n) = -ws%f
      call solve_linear(ws%fx, ws%r(1:n), status, message)
      if (status /= SD_OK .and. .not. numbers) return
      if (status /= SD_OK) then
        message = 'dF/dx is singular at Newton iteration '//num2str(iterations)//', lambda = '// &
                  num2str(lambda)//', max|x| = '//num2str(maxval(abs(x)))//', max|F| = '// &
                  num2str(f_norm)//' ('//trim(message)//')'
        return
      end if
      if (.not. all(ieee_is_finite(ws%r(1:n)))) then
        status = SD_NON_FINITE
        message = 'the Newton step is NaN or infinite'
        if (numbers) message = 'the Newton step is NaN or infinite at iteration '// &
                               num2str(iterations)//', lambda = '//num2str(lambda)// &
                               ', max|x| = '//num2str(maxval(abs(x)))
        return
      end if
      x = x + ws%r(1:n)
      if (maxval(abs(ws%r(1:n))) <= options%x_tol*(1 + maxval(abs(x))) .and. &
          f_norm <= options%f_tol) return
    end do
    iterations = options%max_iter
    status = SD_NOT_CONVERGED
    message = 'Newton did not converge'
    if (.not. numbers) return
    message = 'Newton did not converge in '//num2str(options%max_iter)//' iterations at '// &
              'lambda = '//num2str(lambda)//': max|x| = '//num2str(maxval(abs(x)))// &
              ', last max|F| = '//num2str(f_norm)
  end subroutine newton_core

  !> Newton on the bordered system F(z) = 0, c.z = target, z = (x, lambda) updated in place.
  subroutine bordered_newton(sys, z, c, target, options, ws, iterations, status, message)
    class(parametrised_system), intent(in) :: sys
    real(wp), intent(inout) :: z(:)
    real(wp), intent(in) :: c(:), target
    type(newton_options), intent(in) :: options
    type(workspace), intent(inout) :: ws
    integer, intent(out) :: iterations, status
    character(len=message_len), intent(out) :: message
    real(wp) :: f_norm
    integer :: n, m

    m = size(z)
    n = m - 1
    status = SD_OK
    message = ''
    f_norm = 0
    do iterations = 1, options%max_iter
      call evaluate_for_newton(sys, z(1:n), z(m), options, iterations, ws)
      f_norm = maxval(abs(ws%f))
      if (.not. all(ieee_is_finite(ws%f))) then
        status = SD_NON_FINITE
        message = 'F is NaN or infinite in the corrector at lambda = '//num2str(z(m))// &
                  ', max|x| = '//num2str(maxval(abs(z(1:n))))
        return
      end if
      if (options%reuse_jacobian .and. iterations > 1) call broyden_update(ws, ws%r, .true.)
      ws%a(1:n, 1:n) = ws%fx
      ws%a(1:n, m) = ws%flambda
      ws%a(m, :) = c
      ws%r(1:n) = -ws%f
      ws%r(m) = target - sum(c*z)
      call solve_linear(ws%a, ws%r, status, message)
      if (status /= SD_OK) then
        message = 'the bordered Jacobian is singular in the corrector at lambda = '// &
                  num2str(z(m))//', max|x| = '//num2str(maxval(abs(z(1:n))))//', max|F| = '// &
                  num2str(f_norm)
        return
      end if
      if (.not. all(ieee_is_finite(ws%r))) then
        status = SD_NON_FINITE
        message = 'the corrector step is NaN or infinite at lambda = '//num2str(z(m))// &
                  ', max|x| = '//num2str(maxval(abs(z(1:n))))
        return
      end if
      z = z + ws%r
      if (maxval(abs(ws%r)) <= options%x_tol*(1 + maxval(abs(z))) .and. &
          f_norm <= options%f_tol) return
    end do
    iterations = options%max_iter
    status = SD_NOT_CONVERGED
    message = 'the corrector did not converge in '//num2str(options%max_iter)// &
              ' iterations at lambda = '//num2str(z(m))//': max|x| = '// &
              num2str(maxval(abs(z(1:n))))//', last max|F| = '//num2str(f_norm)
  end subroutine bordered_newton

  !> Predictor z_a + ds t_unit, then the bordered corrector; c returns the border row W t_unit.
  subroutine correct_core(sys, z_a, t_unit, ds, w, newton, ws, c, z, iterations, status, message)
    class(parametrised_system), intent(in) :: sys
    real(wp), intent(in) :: z_a(:), t_unit(:), ds, w(:)
    type(newton_options), intent(in) :: newton
    type(workspace), intent(inout) :: ws
    real(wp), intent(out) :: c(:), z(:)
    integer, intent(out) :: iterations, status
    character(len=message_len), intent(out) :: message

    c = w*t_unit
    z = z_a + ds*t_unit
    call bordered_newton(sys, z, c, sum(c*z), newton, ws, iterations, status, message)
  end subroutine correct_core

  !> Unit tangent (weighted norm) at z from [dF/dx, dF/dlambda; c^T] v = e_(n+1): for
  !> c = W t_prev, <t_prev, t> > 0 (see the module header).
  subroutine tangent_core(sys, z, c, w, ws, t, status, message)
    class(parametrised_system), intent(in) :: sys
    real(wp), intent(in) :: z(:), c(:), w(:)
    type(workspace), intent(inout) :: ws
    real(wp), intent(out) :: t(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    integer :: n, m

    m = size(z)
    n = m - 1
    t = 0
    call sys%evaluate(z(1:n), z(m), ws%f, ws%fx, ws%flambda)
    ws%a(1:n, 1:n) = ws%fx
    ws%a(1:n, m) = ws%flambda
    ws%a(m, :) = c
    ws%r = 0
    ws%r(m) = 1
    call solve_linear(ws%a, ws%r, status, message)
    if (status == SD_OK .and. .not. all(ieee_is_finite(ws%r))) status = SD_NON_FINITE
    if (status /= SD_OK) then
      message = 'no tangent: the bordered Jacobian is singular or not finite at lambda = '// &
                num2str(z(m))//', max|x| = '//num2str(maxval(abs(z(1:n))))// &
                ' (a branch point, or a step too large)'
      return
    end if
    t = ws%r/wnorm(ws%r, w)
    ws%jacobian_ready = .true.
  end subroutine tangent_core

  !> F (ws%f) at iteration `iteration` of a Newton method, and its Jacobian (ws%fx,
  !> ws%flambda) unless a quasi-Newton iteration keeps the one there
  !> (newton_options%reuse_jacobian).
  subroutine evaluate_for_newton(sys, x, lambda, options, iteration, ws)
    class(parametrised_system), intent(in) :: sys
    real(wp), intent(in) :: x(:), lambda
    type(newton_options), intent(in) :: options
    integer, intent(in) :: iteration
    type(workspace), intent(inout) :: ws
    ws%f_old = ws%f
    if (options%reuse_jacobian .and. (iteration > 1 .or. ws%jacobian_ready)) then
      call sys%residual_only(x, lambda, ws%f)
    else
      call sys%evaluate(x, lambda, ws%f, ws%fx, ws%flambda)
    end if
  end subroutine evaluate_for_newton

  !> Broyden's update of the Jacobian (ws%fx, and ws%flambda with_lambda) after the step
  !> `step` (in x, or in (x, lambda)) took F from ws%f_old to ws%f: J + (dF - J s) s^T/(s^T s).
  pure subroutine broyden_update(ws, step, with_lambda)
    type(workspace), intent(inout) :: ws
    real(wp), intent(in) :: step(:)
    logical, intent(in) :: with_lambda
    real(wp) :: miss(size(ws%f)), length2
    integer :: n, j
    n = size(ws%f)
    length2 = sum(step**2)
    if (.not. length2 > 0) return
    miss = ws%f - ws%f_old - matmul(ws%fx, step(1:n))
    if (with_lambda) miss = miss - ws%flambda*step(n + 1)
    do j = 1, n
      ws%fx(:, j) = ws%fx(:, j) + miss*step(j)/length2
    end do
    if (with_lambda) ws%flambda = ws%flambda + miss*step(n + 1)/length2
  end subroutine broyden_update

  !> F alone: evaluate, the Jacobian dropped.
  subroutine evaluate_residual_only(self, x, lambda, f)
    class(parametrised_system), intent(in) :: self
    real(wp), intent(in) :: x(:), lambda
    real(wp), intent(out) :: f(:)
    real(wp) :: fx(size(x), size(x)), flambda(size(x))
    call self%evaluate(x, lambda, f, fx, flambda)
  end subroutine evaluate_residual_only

  !> Tangent at the start: the null vector of [dF/dx, dF/dlambda], found with a unit border row
  !> (lambda first, then each x-component, until the bordered matrix is regular), refined with
  !> itself as border, and oriented so that its lambda-component has the sign of direction.
  subroutine initial_tangent(sys, z, w, direction, ws, c, t, status, message)
    class(parametrised_system), intent(in) :: sys
    real(wp), intent(in) :: z(:), w(:)
    integer, intent(in) :: direction
    type(workspace), intent(inout) :: ws
    real(wp), intent(out) :: c(:), t(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    integer :: trial, m

    m = size(z)
    status = SD_SINGULAR
    do trial = 0, m - 1
      c = 0
      c(merge(m, trial, trial == 0)) = 1
      call tangent_core(sys, z, c, w, ws, t, status, message)
      if (status == SD_OK) exit
    end do
    if (status == SD_OK) then
      c = w*t
      call tangent_core(sys, z, c, w, ws, t, status, message)
    end if
    if (status /= SD_OK) then
      status = SD_SINGULAR
      message = 'the Jacobian [dF/dx, dF/dlambda] has rank < n at the start point (lambda = '// &
                num2str(z(m))//', max|x| = '//num2str(maxval(abs(z(1:m-1))))// &
                '): the branch has no unique tangent there'
      return
    end if
    if (abs(t(m)) <= sqrt(epsilon(1.0_wp))) then
      status = SD_BAD_INPUT
      message = 'the start point (lambda = '//num2str(z(m))//') is a fold: the tangent has no '// &
                'lambda-component, so direction cannot orient it; start away from the fold'
      return
    end if
    if (t(m)*direction < 0) t = -t
  end subroutine initial_tangent

  !> Common checks of (z, t) for correct_at, branch_tangent and the locators; weights, Newton
  !> settings and the unit tangent.
  subroutine prepare(z, t, caller, options, w, newton, t_unit, status, message)
    real(wp), intent(in) :: z(:), t(:)
    character(len=*), intent(in) :: caller
    type(continuation_options), intent(in), optional :: options
    real(wp), intent(out) :: w(:), t_unit(:)
    type(newton_options), intent(out) :: newton
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    integer :: m

    status = SD_OK
    message = ''
    m = size(z)
    w = 1
    t_unit = 0
    if (present(options)) then
      call check_real('x_scale', options%x_scale, 0.0_wp, huge(1.0_wp), .true., .false., &
                      'x_scale must be > 0', status, message)
      call check_newton_options(options%newton, 'newton%', status, message)
      if (status /= SD_OK) return
      w(1:m-1) = options%x_scale**2
      newton = options%newton
    end if
    call check_vector('z', z, 2, status, message)
    if (status == SD_OK .and. size(t) /= m) call size_error('t', size(t), 'z', m, status, message)
    call check_vector('t', t, 2, status, message)
    if (status == SD_OK .and. all(t == 0)) then
      status = SD_BAD_INPUT
      message = 't is zero: '//caller//' needs a tangent direction'
    end if
    if (status /= SD_OK) return
    t_unit = t/wnorm(t, w)
  end subroutine prepare

  pure subroutine check_newton_options(options, prefix, status, message)
    type(newton_options), intent(in) :: options
    character(len=*), intent(in) :: prefix
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message

    call check_real(prefix//'x_tol', options%x_tol, 0.0_wp, huge(1.0_wp), .true., .false., &
                    prefix//'x_tol must be > 0', status, message)
    call check_real(prefix//'f_tol', options%f_tol, 0.0_wp, huge(1.0_wp), .true., .false., &
                    prefix//'f_tol must be > 0', status, message)
    if (status == SD_OK .and. options%max_iter < 1) then
      status = SD_BAD_INPUT
      message = prefix//'max_iter = '//num2str(options%max_iter)// &
                ' is out of range: it must be >= 1'
    end if
  end subroutine check_newton_options

  !> A vector of at least min_size finite entries.
  pure subroutine check_vector(name, v, min_size, status, message)
    character(len=*), intent(in) :: name
    real(wp), intent(in) :: v(:)
    integer, intent(in) :: min_size
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    integer :: i

    if (status /= SD_OK) return
    if (size(v) < min_size) then
      status = SD_BAD_INPUT
      message = name//' has size '//num2str(size(v))//'; it needs at least '//num2str(min_size)
      return
    end if
    do i = 1, size(v)
      if (abs(v(i)) <= huge(1.0_wp)) cycle
      call check_real(name//'('//num2str(i)//')', v(i), -huge(1.0_wp), huge(1.0_wp), .false., &
                      .false., 'must be finite', status, message)
      return
    end do
  end subroutine check_vector

  pure subroutine check_shape(name, a, rows, min_columns, status, message)
    character(len=*), intent(in) :: name
    real(wp), intent(in) :: a(:, :)
    integer, intent(in) :: rows, min_columns
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message

    if (status /= SD_OK) return
    if (size(a, 1) /= rows .or. size(a, 2) < min_columns) then
      status = SD_BAD_INPUT
      message = name//' has shape ('//num2str(size(a, 1))//', '//num2str(size(a, 2))// &
                '); it needs n + 1 = '//num2str(rows)//' rows and at least max_points = '// &
                num2str(min_columns)//' columns'
    end if
  end subroutine check_shape

  pure subroutine size_error(name, actual, reference, expected, status, message)
    character(len=*), intent(in) :: name, reference
    integer, intent(in) :: actual, expected
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    status = SD_BAD_INPUT
    message = name//' has size '//num2str(actual)//'; it must match size('//reference//') = '// &
              num2str(expected)
  end subroutine size_error

  pure subroutine setup_workspace(ws, n)
    type(workspace), intent(out) :: ws
    integer, intent(in) :: n
    allocate (ws%f(n), ws%fx(n, n), ws%flambda(n), ws%a(n + 1, n + 1), ws%r(n + 1), ws%f_old(n))
  end subroutine setup_workspace

  !> Weighted norm sqrt(sum(w v^2)).
  pure real(wp) function wnorm(v, w)
    real(wp), intent(in) :: v(:), w(:)
    wnorm = sqrt(sum(w*v**2))
  end function wnorm

  !> Weighted distance wnorm(a - b, w), without a temporary array.
  pure real(wp) function distance(a, b, w)
    real(wp), intent(in) :: a(:), b(:), w(:)
    distance = sqrt(sum(w*(a - b)**2))
  end function distance
end module sloshdyn_continuation
