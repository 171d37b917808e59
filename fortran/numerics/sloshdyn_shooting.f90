!> Periodic orbits of a periodically forced system y' = f(t, y; lambda) by single shooting: orbits
!> of period k T (T = forcing period), their Floquet multipliers and stability, and their
!> continuation in the parameter lambda with the detection of folds, symmetry-breaking branch
!> points, period doublings and Neimark-Sacker points, and branch switching at branch points and
!> period doublings. Generic: the system comes through the
!> periodic_problem interface.
!>
!> Floquet theory: linearised about a T-periodic orbit, perturbations obey v' = J(t) v; over one
!> orbit period they are mapped by the monodromy matrix M = Phi(k T), Phi' = J Phi, Phi(0) = I.
!> Its eigenvalues (the multipliers) decide stability: all |mu| < 1 is asymptotically stable.
!> M is integrated with the orbit (variational equations), by the same method, never by finite
!> differences, so Newton's Jacobian M - I is as accurate as the orbit itself.
!>
!> Every shot is a function of its inputs only (the problem, the start, lambda, the integrator
!> settings): nothing is cached between calls.
!>
!> Layouts of the results of periodic_branch (n = size(y0)):
!>   points(:, j)      = [lambda, y0(1:n), max|y1| over the orbit, stable (1/0)]   (n + 3 rows)
!>   multipliers(:, j) = [Re mu(1:n), Im mu(1:n)]                                   (2 n rows)
!>   special(:, j)     = [kind (SPECIAL_*), lambda, y0(1:n), max|y1|]               (n + 3 rows)
!> max|y1| is the maximum of the integrated orbit, located on the dense output between steps
!> (sloshdyn_ode's peak_tracker).
module sloshdyn_shooting
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_value, ieee_quiet_nan
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, SD_NOT_CONVERGED, SD_SINGULAR, SD_NON_FINITE, &
                             SD_CAPACITY, check_real
  use sloshdyn_text, only: num2str
  use sloshdyn_lapack, only: eigenvalues, solve_linear
  use sloshdyn_ode, only: ode_system, ode_options, rk_integrator, linear_observation, peak_tracker
  use sloshdyn_integrator, only: new_integrator
  use sloshdyn_continuation, only: parametrised_system, branch_test, continuation_options, &
                                   continue_branch, locate_fold, locate_zero_on_branch, &
                                   correct_at, stop_reason_name, STOP_LAMBDA_MIN, STOP_LAMBDA_MAX, &
                                   STOP_CLOSED, STOP_MAX_POINTS, STOP_X_MAX
  use sloshdyn_bifurcation, only: inverse_iteration
  use sloshdyn_tables, only: SPECIAL_FOLD, SPECIAL_BRANCH_POINT, SPECIAL_PERIOD_DOUBLING, &
                             SPECIAL_NEIMARK_SACKER, special_kind_name
  implicit none
  private
  public :: periodic_problem, periodic_jacobian, periodic_scalar, periodic_parameter_derivative, &
            periodic_set_parameter, variational_system, shooting_setup, make_setup
  public :: monodromy_matrix, shooting_newton, floquet_kind, fold_test, period_doubling_test, &
            neimark_sacker_test, complex_pair_count, periodic_branch, check_setup, kind_test, &
            branch_point_data, branch_data, locate_special_points, switch_branch, &
            volume_preserving, kind_test_value
  public :: FLOQUET_STABLE, FLOQUET_NEUTRAL, FLOQUET_UNSTABLE
  public :: samples_per_period

  !> Floquet kinds: all |mu| < 1 - tol; max |mu| within tol of 1; some |mu| > 1 + tol.
  integer, parameter :: FLOQUET_STABLE = 1, FLOQUET_NEUTRAL = 2, FLOQUET_UNSTABLE = 3
  !> max|y1| over an orbit is located on the dense output (sloshdyn_ode's peak_tracker), whose
  !> scan probes at least this many points per forcing period.
  integer, parameter :: samples_per_period = 64
  !> Newton's convergence scale is tol*(max|y0| + scale_floor), so that the rest state converges.
  real(wp), parameter :: scale_floor = 1.0e-12_wp
  !> |mu| tolerance of the stable flag along a branch: stable = FLOQUET_STABLE at this tol.
  real(wp), parameter :: stability_tol = 1.0e-9_wp
  !> |det M| within this of 1: a volume-preserving (conservative) flow (volume_preserving)
  real(wp), parameter :: volume_tol = 1.0e-7_wp
  !> Secant iterations at most when a branch point is located by the secant method.
  integer, parameter :: max_secant_iterations = 20
  real(wp), parameter :: secant_newton_tol = 1.0e-8_wp

  !> A T-periodic system y' = f(t, y; lambda) (rhs, from ode_system) with its analytic Jacobian
  !> and the derivatives in the parameter lambda that continuation needs.
  type, abstract, extends(ode_system) :: periodic_problem
  contains
    procedure(periodic_jacobian), deferred :: jacobian            !< df/dy (n x n)
    procedure(periodic_scalar), deferred :: period                !< forcing period T
    procedure(periodic_parameter_derivative), deferred :: parameter_derivative  !< df/dlambda
    procedure(periodic_set_parameter), deferred :: set_parameter  !< lambda := value
    procedure(periodic_scalar), deferred :: parameter             !< current lambda
    procedure(periodic_scalar), deferred :: period_derivative     !< dT/dlambda
    procedure :: state_size => unknown_state_size                 !< n, or 0 = not checked
  end type periodic_problem

  abstract interface
    subroutine periodic_jacobian(self, t, y, jac)
      import :: wp, periodic_problem
      class(periodic_problem), intent(in) :: self
      real(wp), intent(in) :: t, y(:)
      real(wp), intent(out) :: jac(:, :)
    end subroutine periodic_jacobian

    function periodic_scalar(self) result(value)
      import :: wp, periodic_problem
      class(periodic_problem), intent(in) :: self
      real(wp) :: value
    end function periodic_scalar

    !> df = d f(t, y; lambda)/d lambda at fixed t and y
    subroutine periodic_parameter_derivative(self, t, y, df)
      import :: wp, periodic_problem
      class(periodic_problem), intent(in) :: self
      real(wp), intent(in) :: t, y(:)
      real(wp), intent(out) :: df(:)
    end subroutine periodic_parameter_derivative

    subroutine periodic_set_parameter(self, lambda)
      import :: wp, periodic_problem
      class(periodic_problem), intent(inout) :: self
      real(wp), intent(in) :: lambda
    end subroutine periodic_set_parameter
  end interface

  !> y' = f, then `columns` tangent columns V' = J V (V = Phi when columns = n), then, with
  !> sensitivity, s' = J s + df/dlambda. State layout [y, V(:, 1), .., V(:, columns), s].
  type, extends(ode_system) :: variational_system
    class(periodic_problem), allocatable :: problem
    integer :: n = 0, columns = 0
    logical :: sensitivity = .false.
  contains
    procedure :: rhs => variational_rhs
  end type variational_system

  !> Everything one shot needs: the variational system (with its private copy of the problem),
  !> the number k of forcing periods, and the integrator method and settings widened to the
  !> augmented state.
  type :: shooting_setup
    type(variational_system) :: sys
    integer :: k = 1
    integer :: method = 0
    type(ode_options) :: options
  end type shooting_setup

  !> The results of one shot.
  type :: shot
    real(wp), allocatable :: y_end(:), monodromy(:, :), dlambda(:)
    real(wp) :: max_y1 = 0
  end type shot

  !> F(y0, lambda) = y(k T; y0, lambda) - y0 for sloshdyn_continuation.
  type, extends(parametrised_system) :: shooting_system
    type(shooting_setup) :: setup
  contains
    procedure :: evaluate => shooting_evaluate
  end type shooting_system

  !> A test function along a branch for the special-point kind (SPECIAL_*) that
  !> locate_special_points sets before each location.
  type, abstract, extends(branch_test) :: kind_test
    integer :: kind = SPECIAL_PERIOD_DOUBLING
  end type kind_test

  !> The stored row [lambda, y0(1:n), a measure, stable] and multipliers [re; im] at a point
  !> z = (x, lambda) of a branch (for locate_special_points).
  abstract interface
    subroutine branch_point_data(zj, row, mult, status, message)
      import :: wp, message_len
      real(wp), intent(in) :: zj(:)
      real(wp), intent(out) :: row(:), mult(:)
      integer, intent(out) :: status
      character(len=message_len), intent(out) :: message
    end subroutine branch_point_data
  end interface

  !> Multiplier test functions along the branch (det(M - I), det(M + I), Neimark-Sacker).
  type, extends(kind_test) :: multiplier_test
    type(shooting_setup) :: setup
  contains
    procedure :: value => multiplier_test_value
  end type multiplier_test

contains

  integer function unknown_state_size(self)
    class(periodic_problem), intent(in) :: self
    unknown_state_size = 0
  end function unknown_state_size

  ! ---- public analyses ------------------------------------------------------------------------

  !> One shot from y0 at t = 0 over k forcing periods: y_end = y(k T), the monodromy matrix
  !> M = Phi(k T) of the variational equations, optionally parameter_column = dF/dlambda of
  !> F = y(k T) - y0 (sensitivity s(k T) plus f(k T) k dT/dlambda) and max_abs_y1 = max|y1|
  !> over the orbit (sampled, see the module header).
  subroutine monodromy_matrix(problem, y0, k, options, method, y_end, monodromy, status, &
                              message, parameter_column, max_abs_y1)
    class(periodic_problem), intent(in) :: problem
    real(wp), intent(in) :: y0(:)
    integer, intent(in) :: k, method
    type(ode_options), intent(in) :: options
    real(wp), intent(out) :: y_end(:), monodromy(:, :)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), intent(out), optional :: parameter_column(:), max_abs_y1
    type(shooting_setup) :: setup
    type(shot) :: result
    integer :: n

    n = size(y0)
    y_end = ieee_value(1.0_wp, ieee_quiet_nan)
    monodromy = ieee_value(1.0_wp, ieee_quiet_nan)
    if (present(parameter_column)) parameter_column = ieee_value(1.0_wp, ieee_quiet_nan)
    if (present(max_abs_y1)) max_abs_y1 = ieee_value(1.0_wp, ieee_quiet_nan)
    call check_setup(problem, y0, k, status, message)
    if (status == SD_OK .and. (size(y_end) /= n .or. any(shape(monodromy) /= [n, n]))) then
      status = SD_BAD_INPUT
      message = 'y_end must have size n and monodromy shape (n, n), n = size(y0) = '//num2str(n)
    end if
    if (status == SD_OK .and. present(parameter_column)) then
      if (size(parameter_column) /= n) then
        status = SD_BAD_INPUT
        message = 'parameter_column has size '//num2str(size(parameter_column))// &
                  '; it must match size(y0) = '//num2str(n)
      end if
    end if
    if (status /= SD_OK) return
    call make_setup(setup, problem, n, k, n, present(parameter_column), options, method)
    call shoot(setup, y0, problem%parameter(), result, status, message)
    if (status /= SD_OK) return
    y_end = result%y_end
    monodromy = result%monodromy
    if (present(parameter_column)) parameter_column = result%dlambda
    if (present(max_abs_y1)) max_abs_y1 = result%max_y1
  end subroutine monodromy_matrix

  !> Shooting: Newton on G(y0) = y(k T; y0) - y0 = 0 with the exact Jacobian M - I (dgesv),
  !> from the guess y0. Converged when max|G| and max|step| are <= newton_tol (max|y| + 1e-12);
  !> y_orbit is then the last iterate plus its step, monodromy and the multipliers (dgeev) those
  !> of the last shot (they differ by O(newton_tol)). iterations = shots done.
  !> Fails with SD_SINGULAR when M - I is singular (a multiplier at +1: a fold or branch point,
  !> or an autonomous system), SD_NOT_CONVERGED after max_iter shots, or the integrator's status.
  subroutine shooting_newton(problem, y0, k, options, method, newton_tol, max_iter, y_orbit, &
                             monodromy, multipliers_re, multipliers_im, iterations, status, &
                             message, max_abs_y1)
    class(periodic_problem), intent(in) :: problem
    real(wp), intent(in) :: y0(:)
    integer, intent(in) :: k, method
    type(ode_options), intent(in) :: options
    real(wp), intent(in) :: newton_tol
    integer, intent(in) :: max_iter
    real(wp), intent(out) :: y_orbit(:), monodromy(:, :), multipliers_re(:), multipliers_im(:)
    integer, intent(out) :: iterations, status
    character(len=message_len), intent(out) :: message
    real(wp), intent(out), optional :: max_abs_y1
    type(shooting_setup) :: setup
    type(shot) :: result
    real(wp), allocatable :: y(:), y_before(:), g(:), jac(:, :)
    real(wp) :: g_norm, step_norm, scale
    integer :: n, i

    n = size(y0)
    iterations = 0
    y_orbit = y0
    monodromy = ieee_value(1.0_wp, ieee_quiet_nan)
    multipliers_re = ieee_value(1.0_wp, ieee_quiet_nan)
    multipliers_im = ieee_value(1.0_wp, ieee_quiet_nan)
    if (present(max_abs_y1)) max_abs_y1 = ieee_value(1.0_wp, ieee_quiet_nan)
    call check_setup(problem, y0, k, status, message)
    call check_real('newton_tol', newton_tol, 0.0_wp, 1.0_wp, .true., .false., &
                    'newton_tol must lie in (0, 1]', status, message)
    if (status == SD_OK .and. max_iter < 1) then
      status = SD_BAD_INPUT
      message = 'max_iter = '//num2str(max_iter)//' is out of range: it must be >= 1'
    end if
    if (status == SD_OK .and. (size(y_orbit) /= n .or. any(shape(monodromy) /= [n, n]) .or. &
                               size(multipliers_re) /= n .or. size(multipliers_im) /= n)) then
      status = SD_BAD_INPUT
      message = 'y_orbit, multipliers_re, multipliers_im must have size n and monodromy '// &
                'shape (n, n), n = size(y0) = '//num2str(n)
    end if
    if (status /= SD_OK) return

    call make_setup(setup, problem, n, k, n, .false., options, method)
    allocate (y(n), y_before(n), g(n), jac(n, n))
    y = y0
    g_norm = 0
    step_norm = 0
    do iterations = 1, max_iter
      call shoot(setup, y, problem%parameter(), result, status, message)
      if (status /= SD_OK) then
        message = 'shooting (Newton iteration '//num2str(iterations)//'): '//trim(message)
        return
      end if
      g = result%y_end - y
      g_norm = maxval(abs(g))
      jac = result%monodromy
      do i = 1, n
        jac(i, i) = jac(i, i) - 1
      end do
      g = -g
      call solve_linear(jac, g, status, message)
      if (status /= SD_OK) then
        if (status == SD_SINGULAR) message = 'M - I is singular at Newton iteration '// &
          num2str(iterations)//' (a Floquet multiplier at +1: fold or branch point of the '// &
          'orbit, or an autonomous system), max|y0| = '//num2str(maxval(abs(y)))// &
          ' ('//trim(message)//')'
        return
      end if
      if (.not. all(ieee_is_finite(g))) then
        status = SD_NON_FINITE
        message = 'the Newton step is NaN or infinite at shooting iteration '// &
                  num2str(iterations)//' (M - I nearly singular)'
        return
      end if
      step_norm = maxval(abs(g))
      y_before = y
      y = y + g
      scale = newton_tol*(maxval(abs(y)) + scale_floor)
      if (g_norm <= scale .and. step_norm <= scale) then
        y_orbit = y
        monodromy = result%monodromy
        if (present(max_abs_y1)) max_abs_y1 = result%max_y1
        call eigenvalues(monodromy, multipliers_re, multipliers_im, status, message)
        if (status /= SD_OK) message = 'Floquet multipliers: '//trim(message)
        return
      end if
      ! a step below the rounding of y (an M - I of huge norm, e.g. along an irregular motion)
      ! leaves y as it was: every further iteration would repeat this one to the bit, and end
      ! as the loop does
      if (all(y == y_before)) exit
    end do
    iterations = max_iter
    y_orbit = y
    status = SD_NOT_CONVERGED
    message = 'shooting did not converge in '//num2str(max_iter)//' Newton iterations: last '// &
              'max|y(kT) - y0| = '//num2str(g_norm)//', last max|step| = '// &
              num2str(step_norm)//', max|y0| = '//num2str(maxval(abs(y)))
  end subroutine shooting_newton

  !> Floquet stability from the multipliers: FLOQUET_STABLE if all |mu| < 1 - tol,
  !> FLOQUET_UNSTABLE if some |mu| > 1 + tol, else FLOQUET_NEUTRAL (a multiplier on the unit
  !> circle within tol: a bifurcation, or a conservative system).
  pure integer function floquet_kind(re, im, tol) result(kind)
    real(wp), intent(in) :: re(:), im(:), tol
    real(wp) :: largest
    largest = maxval(hypot(re, im))
    if (largest > 1 + tol) then
      kind = FLOQUET_UNSTABLE
    else if (largest < 1 - tol) then
      kind = FLOQUET_STABLE
    else
      kind = FLOQUET_NEUTRAL
    end if
  end function floquet_kind

  !> det(M - I) = prod(mu_i - 1): changes sign where a real multiplier crosses +1 (fold or
  !> branch point); complex pairs contribute |mu - 1|^2 > 0.
  pure real(wp) function fold_test(re, im) result(g)
    real(wp), intent(in) :: re(:), im(:)
    g = shifted_product(re, im, -1.0_wp)
  end function fold_test

  !> det(M + I) = prod(mu_i + 1): changes sign where a real multiplier crosses -1.
  pure real(wp) function period_doubling_test(re, im) result(g)
    real(wp), intent(in) :: re(:), im(:)
    g = shifted_product(re, im, 1.0_wp)
  end function period_doubling_test

  !> Product over the complex pairs (Im mu > 0) of |mu|^2 - 1: changes sign where a pair crosses
  !> the unit circle; 1 when there is no pair. Compare only points with the same
  !> complex_pair_count (a pair turning real is no Neimark-Sacker point).
  pure real(wp) function neimark_sacker_test(re, im) result(g)
    real(wp), intent(in) :: re(:), im(:)
    integer :: i
    g = 1
    do i = 1, size(re)
      if (im(i) > 0) g = g*(re(i)**2 + im(i)**2 - 1)
    end do
  end function neimark_sacker_test

  !> |det M| = prod |mu_i| within volume_tol of 1: the flow preserves volume (no damping), its
  !> monodromy is symplectic and its stable multipliers sit on the unit circle, where
  !> neimark_sacker_test vanishes identically (its sign is rounding noise).
  pure logical function volume_preserving(re, im)
    real(wp), intent(in) :: re(:), im(:)
    volume_preserving = abs(product(hypot(re, im)) - 1) <= volume_tol
  end function volume_preserving

  pure integer function complex_pair_count(re, im) result(pairs)
    real(wp), intent(in) :: re(:), im(:)
    pairs = count(im > 0)
  end function complex_pair_count

  !> Follow periodic orbits (period k T, k = periods, default 1) from the guess y0 at the
  !> problem's current parameter, in [lambda_min, lambda_max], by sloshdyn_continuation's
  !> pseudo-arclength continuation on F(y0, lambda) = y(k T(lambda); y0, lambda) - y0, with
  !> dF/dy0 = M - I and dF/dlambda = s(k T) + f(k T, y(k T)) k dT/dlambda from the variational
  !> and sensitivity equations. options gives steps, max_points, direction, x_scale and Newton
  !> tolerances (its lambda bounds are replaced by lambda_min, lambda_max).
  !> Results in the layouts of the module header: points(n + 3, >= max_points), multipliers
  !> (2 n, >= max_points), special(n + 3, :). Special points are located between consecutive
  !> points where a test changes sign: folds (the tangent's lambda component, locate_fold),
  !> branch points (det(M - I) without a turn), period doubling (det(M + I)) and Neimark-Sacker
  !> (complex pair modulus), the latter three with locate_zero_on_branch.
  !> complete = .true. when the branch reached lambda_min or lambda_max or closed, and every
  !> special point was located and stored. Otherwise the points computed so far are returned,
  !> with a message; status /= SD_OK for failures (SD_CAPACITY when max_points or the columns of
  !> special ran out), SD_OK when the branch stopped on options%x_max.
  subroutine periodic_branch(problem, y0, lambda_min, lambda_max, options, ode_settings, method, &
                             points, multipliers, n_points, special, n_special, complete, &
                             status, message, periods, tangent0)
    class(periodic_problem), intent(in) :: problem
    real(wp), intent(in) :: y0(:), lambda_min, lambda_max
    type(continuation_options), intent(in) :: options
    type(ode_options), intent(in) :: ode_settings
    integer, intent(in) :: method
    real(wp), intent(out) :: points(:, :), multipliers(:, :), special(:, :)
    integer, intent(out) :: n_points, n_special, status
    logical, intent(out) :: complete
    character(len=message_len), intent(out) :: message
    integer, intent(in), optional :: periods
    real(wp), intent(in), optional :: tangent0(:)
    type(shooting_system) :: sys
    type(multiplier_test) :: test
    type(continuation_options) :: opt
    real(wp), allocatable :: z(:, :), tangents(:, :), arclength(:), re(:), im(:)
    real(wp) :: lambda0
    integer :: n, m, k, stop_reason

    n = size(y0)
    m = n + 1
    n_points = 0
    n_special = 0
    complete = .false.
    points = ieee_value(1.0_wp, ieee_quiet_nan)
    multipliers = ieee_value(1.0_wp, ieee_quiet_nan)
    special = ieee_value(1.0_wp, ieee_quiet_nan)
    k = 1
    if (present(periods)) k = periods
    call check_setup(problem, y0, k, status, message)
    if (status == SD_OK .and. options%max_points >= 1 .and. &
        (size(points, 1) /= n + 3 .or. size(points, 2) < options%max_points .or. &
         size(multipliers, 1) /= 2*n .or. size(multipliers, 2) < options%max_points .or. &
         size(special, 1) /= n + 3)) then
      status = SD_BAD_INPUT
      message = 'points must be (n + 3) x max_points, multipliers 2 n x max_points and special '// &
                '(n + 3) x any, n = size(y0) = '//num2str(n)//', max_points = '// &
                num2str(options%max_points)
    end if
    if (status /= SD_OK) return
    lambda0 = problem%parameter()
    opt = options
    opt%lambda_min = lambda_min
    opt%lambda_max = lambda_max

    call make_setup(sys%setup, problem, n, k, n, .true., ode_settings, method)
    test%setup = sys%setup
    allocate (z(m, max(options%max_points, 1)), tangents(m, max(options%max_points, 1)), &
              arclength(max(options%max_points, 1)), re(n), im(n))
    call continue_branch(sys, y0, lambda0, opt, z, tangents, arclength, n_points, stop_reason, &
                         status, message, tangent0)
    if (status /= SD_OK) call integration_failure()
    if (status /= SD_OK .and. n_points == 0) return

    ! multipliers and max|y1| at every point
    call branch_data(z, point_data, points, multipliers, n_points, status, message)
    call locate_special_points(sys, z, tangents, arclength, multipliers, n_points, .true., &
                               test, opt, point_data, special, n_special, status, message)

    if (status == SD_OK) then
      select case (stop_reason)
      case (STOP_LAMBDA_MIN, STOP_LAMBDA_MAX, STOP_CLOSED)
        complete = .true.
      case (STOP_MAX_POINTS)
        status = SD_CAPACITY
        message = 'the branch reached max_points = '//num2str(options%max_points)// &
                  ' at lambda = '//num2str(z(m, n_points))//' before lambda_min or lambda_max'
      case (STOP_X_MAX)
        message = 'the branch stopped at lambda = '//num2str(z(m, n_points))//': '// &
                  stop_reason_name(stop_reason)
      case default
        message = 'the branch stopped: '//stop_reason_name(stop_reason)
      end select
    end if

  contains

    !> The continuation sees a failed shot only as NaN: shoot again at its last point (the start
    !> when it has none) to add the integrator's words to the message.
    subroutine integration_failure()
      type(shot) :: result
      integer :: st
      character(len=message_len) :: msg
      if (n_points > 0) then
        call shoot(sys%setup, z(1:n, n_points), z(m, n_points), result, st, msg)
      else
        call shoot(sys%setup, y0, lambda0, result, st, msg)
      end if
      if (st /= SD_OK) message = trim(message)//'; '//trim(msg)
    end subroutine integration_failure

    !> The stored row [lambda, y0, max|y1|, stable] and multipliers of branch point zj; re, im
    !> keep the multipliers.
    subroutine point_data(zj, row, mult, st, msg)
      real(wp), intent(in) :: zj(:)
      real(wp), intent(out) :: row(:), mult(:)
      integer, intent(out) :: st
      character(len=message_len), intent(out) :: msg
      type(shot) :: result
      call shoot(sys%setup, zj(1:n), zj(m), result, st, msg)
      if (st == SD_OK) call eigenvalues(result%monodromy, re, im, st, msg)
      if (st /= SD_OK) return
      row(1) = zj(m)
      row(2:n + 1) = zj(1:n)
      row(n + 2) = result%max_y1
      row(n + 3) = merge(1.0_wp, 0.0_wp, floquet_kind(re, im, stability_tol) == FLOQUET_STABLE)
      mult(1:n) = re
      mult(n + 1:2*n) = im
    end subroutine point_data
  end subroutine periodic_branch

  !> Branch switching at a special point (y_special at the problem's current parameter
  !> lambda_s) of a branch of orbits of period k T: at a branch point (SPECIAL_BRANCH_POINT) the
  !> other branch of period k T, at a period doubling (SPECIAL_PERIOD_DOUBLING) the branch of
  !> doubled orbits, of period 2 k T. The other branch leaves along (v, 0), v the critical
  !> Floquet eigenvector (multiplier +1 or -1, by inverse iteration on M - I or M + I):
  !> a null vector of the extended Jacobian [dF/dy0, dF/dlambda] of the orbits of period
  !> k_new T (for the doubling F = y(2 k T) - y0, whose M^2 - I is singular), the one without a
  !> lambda-component. It is exact for a period doubling and for the symmetry-breaking pitchfork
  !> of a Z2-symmetric orbit, whose new branch has dlambda/ds = 0 there (Kuznetsov, Elements of
  !> Applied Bifurcation Theory, 3rd ed., sections 4.4 and 7.4); a transcritical branch point
  !> (not generic here) may need the other null vector. The first point of the new branch is
  !> corrected on the hyperplane <(v, 0), z - z_s - ds (v, 0)> = 0 (options%ds, weighted norm),
  !> checked to lie off the old branch (for the doubling: y(k T) /= y0, since the doubled orbit
  !> satisfies y(k T) - y0 ~ -2 ds v), and continued by periodic_branch away from the special
  !> point (tangent0 = (v, 0)), with its own special points (results as periodic_branch's,
  !> periods = k_new).
  subroutine switch_branch(problem, kind, y_special, k, lambda_min, lambda_max, options, &
                           ode_settings, method, points, multipliers, n_points, special, &
                           n_special, complete, k_new, status, message)
    class(periodic_problem), intent(in) :: problem
    integer, intent(in) :: kind, k, method
    real(wp), intent(in) :: y_special(:), lambda_min, lambda_max
    type(continuation_options), intent(in) :: options
    type(ode_options), intent(in) :: ode_settings
    real(wp), intent(out) :: points(:, :), multipliers(:, :), special(:, :)
    integer, intent(out) :: n_points, n_special, k_new, status
    logical, intent(out) :: complete
    character(len=message_len), intent(out) :: message
    type(shooting_system) :: sys
    type(continuation_options) :: opt
    real(wp), allocatable :: y_end(:), monodromy(:, :), v(:), t(:), z_s(:), z_1(:)
    real(wp) :: shift
    integer :: n, m, i

    n = size(y_special)
    m = n + 1
    n_points = 0
    n_special = 0
    complete = .false.
    k_new = k
    points = ieee_value(1.0_wp, ieee_quiet_nan)
    multipliers = ieee_value(1.0_wp, ieee_quiet_nan)
    special = ieee_value(1.0_wp, ieee_quiet_nan)
    call check_setup(problem, y_special, k, status, message)
    if (status == SD_OK .and. kind /= SPECIAL_BRANCH_POINT .and. &
        kind /= SPECIAL_PERIOD_DOUBLING) then
      status = SD_BAD_INPUT
      message = 'kind = '//num2str(kind)//': branches can be switched at a branch point ('// &
                num2str(SPECIAL_BRANCH_POINT)//') or a period doubling ('// &
                num2str(SPECIAL_PERIOD_DOUBLING)//')'
    end if
    if (status /= SD_OK) return
    if (kind == SPECIAL_PERIOD_DOUBLING) k_new = 2*k
    shift = merge(1.0_wp, -1.0_wp, kind == SPECIAL_PERIOD_DOUBLING)

    ! the critical Floquet eigenvector v of M (period k T) at the special point
    allocate (y_end(n), monodromy(n, n), v(n), t(m), z_s(m), z_1(m))
    call monodromy_matrix(problem, y_special, k, ode_settings, method, y_end, monodromy, &
                          status, message)
    if (status == SD_OK) then
      do i = 1, n
        monodromy(i, i) = monodromy(i, i) + shift
      end do
      call inverse_iteration(monodromy, max(maxval(abs(monodromy)), tiny(1.0_wp)), v, status, &
                             message)
    end if
    if (status /= SD_OK) then
      message = 'the Floquet eigenvector of the multiplier '// &
                trim(merge('-1', '+1', kind == SPECIAL_PERIOD_DOUBLING))//': '//trim(message)
      return
    end if

    ! the first point of the new branch, off the special point along (v, 0)
    opt = options
    opt%lambda_min = lambda_min
    opt%lambda_max = lambda_max
    call make_setup(sys%setup, problem, n, k_new, n, .true., ode_settings, method)
    z_s(1:n) = y_special
    z_s(m) = problem%parameter()
    t(1:n) = v
    t(m) = 0
    call correct_at(sys, z_s, t, options%ds, z_1, status, message, opt)
    if (status == SD_OK .and. kind == SPECIAL_PERIOD_DOUBLING) then
      call monodromy_matrix(problem_at(z_1(m)), z_1(1:n), k, ode_settings, method, y_end, &
                            monodromy, status, message)
      if (status == SD_OK .and. maxval(abs(y_end - z_1(1:n))) < &
          0.1_wp*options%ds/options%x_scale) then
        status = SD_NOT_CONVERGED
        message = 'the corrector went back to the orbits of period '//num2str(k)// &
                  ' T (max|y(kT) - y0| = '//num2str(maxval(abs(y_end - z_1(1:n))))// &
                  '); try another ds'
      end if
    end if
    if (status /= SD_OK) then
      message = 'the first point of the new branch (ds = '//num2str(options%ds)//' from the '// &
                special_kind_name(kind)//' at lambda = '//num2str(z_s(m))//'): '//trim(message)
      return
    end if
    ! continued away from the special point (the start corrected across (v, 0), not at fixed
    ! lambda: near the special point M - I is nearly singular)
    call periodic_branch(problem_at(z_1(m)), z_1(1:n), lambda_min, lambda_max, opt, &
                         ode_settings, method, points, multipliers, n_points, special, &
                         n_special, complete, status, message, k_new, t)

  contains

    !> The problem at parameter lambda.
    function problem_at(lambda) result(p)
      real(wp), intent(in) :: lambda
      class(periodic_problem), allocatable :: p
      allocate (p, source=problem)
      call p%set_parameter(lambda)
    end function problem_at
  end subroutine switch_branch

  !> The data of every point of a branch (point_data: its row and Floquet multipliers); a point
  !> whose data fail ends the branch before it (n_points = its index - 1), with that failure's
  !> message unless the branch already had one.
  subroutine branch_data(z, point_data, points, multipliers, n_points, status, message)
    real(wp), intent(in) :: z(:, :)
    procedure(branch_point_data) :: point_data
    real(wp), intent(inout) :: points(:, :), multipliers(:, :)
    integer, intent(inout) :: n_points, status
    character(len=message_len), intent(inout) :: message
    integer :: j, point_status
    character(len=message_len) :: point_message

    do j = 1, n_points
      call point_data(z(:, j), points(:, j), multipliers(:, j), point_status, point_message)
      if (point_status /= SD_OK) then
        if (status == SD_OK) then
          status = point_status
          message = 'branch point '//num2str(j)//': '//trim(point_message)
        end if
        n_points = j - 1
        exit
      end if
    end do
  end subroutine branch_data

  !> Special points between consecutive points 1..n_points of a branch (z = (x, lambda) with
  !> its tangents and arclength; multipliers(:, j) = [re; im] at point j): folds where the
  !> tangent's lambda component changes sign (locate_fold), else, with branch_points, branch
  !> points where det(M - I) does; period doublings (det(M + I)) and Neimark-Sacker points
  !> (complex pair moduli, at equal complex_pair_count; not between two volume-preserving
  !> points, where that test is rounding noise), located by locate_zero_on_branch with
  !> test (its kind set to each). Each is stored as special(:, n_special) = [kind,
  !> row(1:n + 2)], row from point_data. The first failure sets status and message if they are
  !> still SD_OK (SD_CAPACITY when special has no more columns); the others are skipped.
  subroutine locate_special_points(sys, z, tangents, arclength, multipliers, n_points, &
                                   branch_points, test, opt, point_data, special, n_special, &
                                   status, message)
    class(parametrised_system), intent(in) :: sys
    real(wp), intent(in) :: z(:, :), tangents(:, :), arclength(:), multipliers(:, :)
    integer, intent(in) :: n_points
    logical, intent(in) :: branch_points
    class(kind_test), intent(inout) :: test
    type(continuation_options), intent(in) :: opt
    procedure(branch_point_data) :: point_data
    real(wp), intent(inout) :: special(:, :)
    integer, intent(inout) :: n_special, status
    character(len=message_len), intent(inout) :: message
    real(wp) :: z_special(size(z, 1))
    real(wp), allocatable :: det_minus(:), det_plus(:), ns(:)
    integer, allocatable :: pairs(:)
    logical, allocatable :: conservative(:)
    integer :: n, m, j, locate_status
    character(len=message_len) :: locate_message

    m = size(z, 1)
    n = size(multipliers, 1)/2
    allocate (det_minus(n_points), det_plus(n_points), ns(n_points), pairs(n_points), &
              conservative(n_points))
    do j = 1, n_points
      associate (re => multipliers(1:n, j), im => multipliers(n + 1:2*n, j))
        det_minus(j) = fold_test(re, im)
        det_plus(j) = period_doubling_test(re, im)
        ns(j) = neimark_sacker_test(re, im)
        pairs(j) = complex_pair_count(re, im)
        conservative(j) = volume_preserving(re, im)
      end associate
    end do
    do j = 1, n_points - 1
      if (tangents(m, j)*tangents(m, j + 1) < 0) then
        call locate_fold(sys, z(:, j), tangents(:, j), z(:, j + 1), tangents(:, j + 1), &
                         z_special, locate_status, locate_message, opt)
        call add_special(SPECIAL_FOLD)
      else if (branch_points .and. det_minus(j)*det_minus(j + 1) < 0) then
        call locate_with(SPECIAL_BRANCH_POINT)
      end if
      if (det_plus(j)*det_plus(j + 1) < 0) call locate_with(SPECIAL_PERIOD_DOUBLING)
      if (pairs(j) == pairs(j + 1) .and. ns(j)*ns(j + 1) < 0 .and. &
          .not. (conservative(j) .and. conservative(j + 1))) &
        call locate_with(SPECIAL_NEIMARK_SACKER)
    end do

  contains

    !> Locate a zero of the test of kind what between points j and j + 1 and store it. At a
    !> branch point the corrector is singular, so Brent's iterates close to it may fail; then
    !> the point is found by the secant method on det(M - I) in the arclength from point j,
    !> each iterate corrected onto the branch with Newton tolerances of at least
    !> secant_newton_tol (next to a branch point the corrector's matrix is nearly singular and
    !> amplifies the integration error: the residual stalls near 1e-11; an iterate where the
    !> corrector fails is moved half-way back to the last one, up to max_secant_iterations
    !> times), until the step is below 1e-9 of the interval (the last converged iterate is
    !> kept).
    subroutine locate_with(what)
      integer, intent(in) :: what
      real(wp) :: s(2), g(2), s_new, z_new(size(z, 1))
      integer :: iteration, halvings, st
      character(len=message_len) :: msg
      type(continuation_options) :: slow
      slow = opt
      slow%newton%x_tol = max(opt%newton%x_tol, secant_newton_tol)
      slow%newton%f_tol = max(opt%newton%f_tol, secant_newton_tol)
      test%kind = what
      call locate_zero_on_branch(sys, z(:, j), tangents(:, j), arclength(j + 1) - arclength(j), &
                                 test, z_special, locate_status, locate_message, opt)
      if (locate_status /= SD_OK .and. what == SPECIAL_BRANCH_POINT) then
        s = [0.0_wp, arclength(j + 1) - arclength(j)]
        g = det_minus(j:j + 1)
        halvings = 0
        do iteration = 1, max_secant_iterations
          s_new = s(2) - g(2)*(s(2) - s(1))/(g(2) - g(1))
          call correct_at(sys, z(:, j), tangents(:, j), s_new, z_new, st, msg, slow)
          ! too close to the branch point for the corrector: half-way to the last iterate
          do while (st /= SD_OK .and. halvings < max_secant_iterations)
            halvings = halvings + 1
            s_new = (s_new + s(2))/2
            call correct_at(sys, z(:, j), tangents(:, j), s_new, z_new, st, msg, slow)
          end do
          if (st /= SD_OK) exit
          z_special = z_new
          locate_status = SD_OK
          if (abs(s_new - s(2)) <= 1.0e-9_wp*abs(arclength(j + 1) - arclength(j))) exit
          s = [s(2), s_new]
          g = [g(2), test%value(z_new, tangents(:, j))]
          if (.not. ieee_is_finite(g(2)) .or. g(2) == g(1)) exit
        end do
      end if
      call add_special(what)
    end subroutine locate_with

    !> Store the special point z_special (or record why it could not be located).
    subroutine add_special(what)
      integer, intent(in) :: what
      real(wp) :: row(n + 3), mult(2*n)
      if (locate_status == SD_OK) then
        call point_data(z_special, row, mult, locate_status, locate_message)
      end if
      if (locate_status /= SD_OK) then
        if (status == SD_OK) then
          status = locate_status
          message = 'locating the '//special_kind_name(what)//' between lambda = '// &
                    num2str(z(m, j))//' and '//num2str(z(m, j + 1))//' failed: '// &
                    trim(locate_message)
        end if
        return
      end if
      if (n_special >= size(special, 2)) then
        if (status == SD_OK) then
          status = SD_CAPACITY
          message = 'special has '//num2str(size(special, 2))//' columns; more special '// &
                    'points were found (the next: '//special_kind_name(what)//' at lambda = '// &
                    num2str(row(1))//')'
        end if
        return
      end if
      n_special = n_special + 1
      special(1, n_special) = what
      special(2:n + 3, n_special) = row(1:n + 2)
    end subroutine add_special
  end subroutine locate_special_points

  !> Inputs every public routine checks: y0 finite and of the problem's size, k >= 1, T > 0.
  subroutine check_setup(problem, y0, k, status, message)
    class(periodic_problem), intent(in) :: problem
    real(wp), intent(in) :: y0(:)
    integer, intent(in) :: k
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    integer :: i

    status = SD_OK
    message = ''
    if (size(y0) == 0 .or. (problem%state_size() > 0 .and. size(y0) /= problem%state_size())) then
      status = SD_BAD_INPUT
      message = 'y0 has size '//num2str(size(y0))//'; the problem has '// &
                num2str(problem%state_size())//' state components'
      return
    end if
    do i = 1, size(y0)
      call check_real('y0('//num2str(i)//')', y0(i), -huge(1.0_wp), huge(1.0_wp), .false., &
                      .false., 'the initial state must be finite', status, message)
    end do
    if (status == SD_OK .and. k < 1) then
      status = SD_BAD_INPUT
      message = 'k = '//num2str(k)//' is out of range: the orbit period k T needs k >= 1'
    end if
    call check_real('T', problem%period(), 0.0_wp, huge(1.0_wp), .true., .true., &
                    'the forcing period must be finite and > 0 (e.g. rho > 0)', status, message)
  end subroutine check_setup

  ! ---- private --------------------------------------------------------------------------------

  !> Variational equations (Floquet): y' = f, V' = J V, s' = J s + df/dlambda.
  subroutine variational_rhs(self, t, y, dydt)
    class(variational_system), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: dydt(:)
    real(wp) :: jac(self%n, self%n), df(self%n)
    integer :: n, i, j, offset

    n = self%n
    call self%problem%rhs(t, y(1:n), dydt(1:n))
    call self%problem%jacobian(t, y(1:n), jac)
    do j = 1, self%columns
      offset = n*j
      do i = 1, n
        dydt(offset + i) = dot_product(jac(i, :), y(offset + 1:offset + n))
      end do
    end do
    if (self%sensitivity) then
      offset = n*(self%columns + 1)
      call self%problem%parameter_derivative(t, y(1:n), df)
      do i = 1, n
        dydt(offset + i) = dot_product(jac(i, :), y(offset + 1:offset + n)) + df(i)
      end do
    end if
  end subroutine variational_rhs

  !> The setup of a shot: a private copy of the problem (shots change its parameter), the
  !> augmented system, and the integrator options widened to the augmented state (a
  !> per-component atol_vector for y; atol for the variational part).
  subroutine make_setup(setup, problem, n, k, columns, sensitivity, options, method)
    type(shooting_setup), intent(out) :: setup
    class(periodic_problem), intent(in) :: problem
    integer, intent(in) :: n, k, columns, method
    logical, intent(in) :: sensitivity
    type(ode_options), intent(in) :: options
    integer :: size_z

    setup%k = k
    setup%method = method
    allocate (setup%sys%problem, source=problem)
    setup%sys%n = n
    setup%sys%columns = columns
    setup%sys%sensitivity = sensitivity
    size_z = n*(1 + columns + merge(1, 0, sensitivity))
    setup%options = options
    if (allocated(options%atol_vector)) then
      if (size(options%atol_vector) == n) then
        deallocate (setup%options%atol_vector)
        allocate (setup%options%atol_vector(size_z))
        setup%options%atol_vector = options%atol
        setup%options%atol_vector(1:n) = options%atol_vector
      end if
    end if
  end subroutine make_setup

  !> Integrate y, Phi (Phi(0) = I) and, if set up, s (s(0) = 0) from t = 0 to k T at parameter
  !> lambda; fill the shot's y_end, monodromy, max_y1 and dlambda. Failures carry the
  !> integrator's message and where.
  subroutine shoot(setup, x, lambda, result, status, message)
    type(shooting_setup), intent(in) :: setup
    real(wp), intent(in) :: x(:), lambda
    type(shot), intent(out) :: result
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(variational_system) :: sys
    class(rk_integrator), allocatable, target :: integ
    real(wp), allocatable :: z0(:), f_end(:)
    real(wp) :: period, t_end
    integer :: n, j, size_z
    type(linear_observation) :: first
    type(peak_tracker) :: tracker

    n = setup%sys%n
    sys = setup%sys
    call sys%problem%set_parameter(lambda)
    period = sys%problem%period()
    t_end = setup%k*period
    status = SD_OK
    message = ''
    call check_real('T', period, 0.0_wp, huge(1.0_wp), .true., .true., &
                    'the forcing period must be finite and > 0 (e.g. rho > 0)', status, message)
    if (status /= SD_OK) return
    size_z = n*(1 + sys%columns + merge(1, 0, sys%sensitivity))
    allocate (z0(size_z), f_end(n), result%y_end(n), result%monodromy(n, n), &
              result%dlambda(n))
    z0 = 0
    z0(1:n) = x
    do j = 1, n
      z0(n*j + j) = 1
    end do
    call new_integrator(setup%method, setup%options%rtol, integ, status, message)
    if (status /= SD_OK) return
    call integ%init(sys, 0.0_wp, z0, t_end, setup%options, status, message)
    ! the largest |y1| of the orbit, on the continuous extension between the steps
    allocate (first%c(1, size_z))
    first%c = 0
    first%c(1, 1) = 1
    tracker%spacing = period/samples_per_period
    call tracker%start(first, 0.0_wp, z0)
    do while (status == SD_OK .and. integ%t < t_end)
      call integ%step(sys, status, message)
      if (status == SD_OK) call tracker%watch(integ, first, 0.0_wp, t_end, status, message)
    end do
    result%max_y1 = tracker%peak(1)
    if (status /= SD_OK) then
      message = 'integrating the variational equations from tau = 0 to k T = '// &
                num2str(t_end)//' (lambda = '//num2str(lambda)// &
                ', max|y0| = '//num2str(maxval(abs(x)))//'): '//trim(message)
      return
    end if
    result%y_end = integ%y(1:n)
    do j = 1, n
      result%monodromy(:, j) = integ%y(n*j + 1:n*j + n)
    end do
    result%dlambda = 0
    if (sys%sensitivity) then
      ! F = y(k T(lambda); lambda) - y0: the end time moves with lambda too
      call sys%problem%rhs(t_end, result%y_end, f_end)
      result%dlambda = integ%y(n*(n + 1) + 1:n*(n + 2)) + &
                       f_end*setup%k*sys%problem%period_derivative()
    end if
  end subroutine shoot

  !> F = y(k T) - y0, dF/dy0 = M - I, dF/dlambda; NaN when the integration fails (the
  !> continuation then shortens its step).
  subroutine shooting_evaluate(self, x, lambda, f, fx, flambda)
    class(shooting_system), intent(in) :: self
    real(wp), intent(in) :: x(:), lambda
    real(wp), intent(out) :: f(:), fx(:, :), flambda(:)
    type(shot) :: result
    integer :: status, i
    character(len=message_len) :: message
    call shoot(self%setup, x, lambda, result, status, message)
    if (status /= SD_OK) then
      f = ieee_value(1.0_wp, ieee_quiet_nan)
      fx = ieee_value(1.0_wp, ieee_quiet_nan)
      flambda = ieee_value(1.0_wp, ieee_quiet_nan)
      return
    end if
    f = result%y_end - x
    fx = result%monodromy
    do i = 1, size(x)
      fx(i, i) = fx(i, i) - 1
    end do
    flambda = result%dlambda
  end subroutine shooting_evaluate

  !> Test value at branch point z (the tangent is not needed); NaN if the shot fails, which
  !> stops the zero finder.
  function multiplier_test_value(self, z, t) result(g)
    class(multiplier_test), intent(in) :: self
    real(wp), intent(in) :: z(:), t(:)
    real(wp) :: g
    type(shot) :: result
    real(wp) :: re(self%setup%sys%n), im(self%setup%sys%n)
    integer :: n, status
    character(len=message_len) :: message

    n = self%setup%sys%n
    g = ieee_value(1.0_wp, ieee_quiet_nan)
    call shoot(self%setup, z(1:n), z(n + 1), result, status, message)
    if (status == SD_OK) call eigenvalues(result%monodromy, re, im, status, message)
    if (status /= SD_OK) return
    g = kind_test_value(self%kind, re, im)
  end function multiplier_test_value

  !> The multiplier test of special-point kind `kind` (SPECIAL_*): det(M - I) for folds and
  !> branch points, det(M + I) for period doublings, else the complex pairs' moduli.
  pure real(wp) function kind_test_value(kind, re, im) result(g)
    integer, intent(in) :: kind
    real(wp), intent(in) :: re(:), im(:)
    select case (kind)
    case (SPECIAL_FOLD, SPECIAL_BRANCH_POINT)
      g = fold_test(re, im)
    case (SPECIAL_PERIOD_DOUBLING)
      g = period_doubling_test(re, im)
    case default
      g = neimark_sacker_test(re, im)
    end select
  end function kind_test_value

  !> prod(mu_i + shift), real for conjugate pairs.
  pure real(wp) function shifted_product(re, im, shift) result(g)
    real(wp), intent(in) :: re(:), im(:), shift
    complex(wp) :: p
    integer :: i
    p = (1.0_wp, 0.0_wp)
    do i = 1, size(re)
      p = p*cmplx(re(i) + shift, im(i), wp)
    end do
    g = real(p, wp)
  end function shifted_product
end module sloshdyn_shooting
