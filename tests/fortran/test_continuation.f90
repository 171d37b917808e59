!> Test systems with closed-form solution sets, the independent source of every expected value.
module continuation_test_systems
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use sloshdyn_kinds, only: wp
  use sloshdyn_continuation, only: separable_system, branch_test
  implicit none
  private
  public :: circle_and_line, circle, averaged_duffing, walled_line, sine_graph, pitchfork, &
            amplitude_level
  public :: amplitude_error, s_upper, fold_function, bisect_fold

  !> F = (x1^2 + x2^2 - lambda, x1 - slope x2); for lambda = 4, slope = 1 the roots are
  !> +-(sqrt 2, sqrt 2), and dF/dx = [2 x1, 2 x2; 1, -slope] is singular at x = 0.
  type, extends(separable_system) :: circle_and_line
    real(wp) :: slope = 1
  contains
    procedure :: residual => circle_and_line_residual
    procedure :: jacobian => circle_and_line_jacobian
  end type circle_and_line

  !> x^2 + lambda^2 = radius^2 (n = 1): a closed branch with folds at (0, +-radius).
  type, extends(separable_system) :: circle
    real(wp) :: radius = 1
  contains
    procedure :: residual => circle_residual
    procedure :: jacobian => circle_jacobian
  end type circle

  !> Steady states of the averaged Duffing oscillator, lambda = detuning s:
  !>   p' = -(g/2) p - (s - k (p^2 + q^2)) q
  !>   q' = -(g/2) q + (s - k (p^2 + q^2)) p + forcing
  !> At equilibrium, with a^2 = p^2 + q^2 and sigma = s - k a^2, (g/2 + i sigma)(p + i q) =
  !> i forcing, so a^2 ((g/2)^2 + sigma^2) = forcing^2: the classic frequency response.
  type, extends(separable_system) :: averaged_duffing
    real(wp) :: g = 0.02_wp, k = 1, forcing = 0.01_wp
  contains
    procedure :: residual => duffing_residual
    procedure :: jacobian => duffing_jacobian
  end type averaged_duffing

  !> x = slope lambda (n = 1), with F = NaN for lambda > wall: a branch that ends.
  type, extends(separable_system) :: walled_line
    real(wp) :: slope = 1, wall = huge(1.0_wp)
  contains
    procedure :: residual => walled_line_residual
    procedure :: jacobian => walled_line_jacobian
  end type walled_line

  !> x = amplitude sin(lambda) (n = 1): an open branch that passes behind its start point
  !> (0, 0), i.e. crosses the line through it normal to its tangent, far from it.
  type, extends(separable_system) :: sine_graph
    real(wp) :: amplitude = 3
  contains
    procedure :: residual => sine_graph_residual
    procedure :: jacobian => sine_graph_jacobian
  end type sine_graph

  !> x (lambda - c x^2) = 0 (n = 1): the trivial branch x = 0 meets x^2 = lambda/c at the
  !> pitchfork (0, 0), a simple branch point.
  type, extends(separable_system) :: pitchfork
    real(wp) :: c = 1
  contains
    procedure :: residual => pitchfork_residual
    procedure :: jacobian => pitchfork_jacobian
  end type pitchfork

  !> Test function p^2 + q^2 - level (a given amplitude on the Duffing branch).
  type, extends(branch_test) :: amplitude_level
    real(wp) :: level = 0.25_wp
  contains
    procedure :: value => amplitude_level_value
  end type amplitude_level

contains

  subroutine circle_and_line_residual(self, x, lambda, f)
    class(circle_and_line), intent(in) :: self
    real(wp), intent(in) :: x(:), lambda
    real(wp), intent(out) :: f(:)
    f = [x(1)**2 + x(2)**2 - lambda, x(1) - self%slope*x(2)]
  end subroutine circle_and_line_residual

  subroutine circle_and_line_jacobian(self, x, lambda, fx, flambda)
    class(circle_and_line), intent(in) :: self
    real(wp), intent(in) :: x(:), lambda
    real(wp), intent(out) :: fx(:, :), flambda(:)
    fx = reshape([2*x(1), 1.0_wp, 2*x(2), -self%slope], [2, 2])
    flambda = [-1.0_wp, 0*lambda]
  end subroutine circle_and_line_jacobian

  subroutine circle_residual(self, x, lambda, f)
    class(circle), intent(in) :: self
    real(wp), intent(in) :: x(:), lambda
    real(wp), intent(out) :: f(:)
    f(1) = x(1)**2 + lambda**2 - self%radius**2
  end subroutine circle_residual

  subroutine circle_jacobian(self, x, lambda, fx, flambda)
    class(circle), intent(in) :: self
    real(wp), intent(in) :: x(:), lambda
    real(wp), intent(out) :: fx(:, :), flambda(:)
    fx(1, 1) = 2*x(1)
    flambda(1) = 2*lambda + 0*self%radius
  end subroutine circle_jacobian

  subroutine duffing_residual(self, x, lambda, f)
    class(averaged_duffing), intent(in) :: self
    real(wp), intent(in) :: x(:), lambda
    real(wp), intent(out) :: f(:)
    real(wp) :: sigma
    sigma = lambda - self%k*(x(1)**2 + x(2)**2)
    f(1) = -self%g/2*x(1) - sigma*x(2)
    f(2) = -self%g/2*x(2) + sigma*x(1) + self%forcing
  end subroutine duffing_residual

  subroutine duffing_jacobian(self, x, lambda, fx, flambda)
    class(averaged_duffing), intent(in) :: self
    real(wp), intent(in) :: x(:), lambda
    real(wp), intent(out) :: fx(:, :), flambda(:)
    real(wp) :: sigma, p, q
    p = x(1)
    q = x(2)
    sigma = lambda - self%k*(p**2 + q**2)
    fx(1, 1) = -self%g/2 + 2*self%k*p*q
    fx(1, 2) = -sigma + 2*self%k*q**2
    fx(2, 1) = sigma - 2*self%k*p**2
    fx(2, 2) = -self%g/2 - 2*self%k*p*q
    flambda = [-q, p]
  end subroutine duffing_jacobian

  subroutine walled_line_residual(self, x, lambda, f)
    class(walled_line), intent(in) :: self
    real(wp), intent(in) :: x(:), lambda
    real(wp), intent(out) :: f(:)
    if (lambda > self%wall) then
      f = ieee_value(1.0_wp, ieee_quiet_nan)
    else
      f(1) = x(1) - self%slope*lambda
    end if
  end subroutine walled_line_residual

  subroutine walled_line_jacobian(self, x, lambda, fx, flambda)
    class(walled_line), intent(in) :: self
    real(wp), intent(in) :: x(:), lambda
    real(wp), intent(out) :: fx(:, :), flambda(:)
    fx(1, 1) = 1 + 0*x(1)*lambda
    flambda(1) = -self%slope
  end subroutine walled_line_jacobian

  subroutine sine_graph_residual(self, x, lambda, f)
    class(sine_graph), intent(in) :: self
    real(wp), intent(in) :: x(:), lambda
    real(wp), intent(out) :: f(:)
    f(1) = x(1) - self%amplitude*sin(lambda)
  end subroutine sine_graph_residual

  subroutine sine_graph_jacobian(self, x, lambda, fx, flambda)
    class(sine_graph), intent(in) :: self
    real(wp), intent(in) :: x(:), lambda
    real(wp), intent(out) :: fx(:, :), flambda(:)
    fx(1, 1) = 1 + 0*x(1)
    flambda(1) = -self%amplitude*cos(lambda)
  end subroutine sine_graph_jacobian

  subroutine pitchfork_residual(self, x, lambda, f)
    class(pitchfork), intent(in) :: self
    real(wp), intent(in) :: x(:), lambda
    real(wp), intent(out) :: f(:)
    f(1) = x(1)*(lambda - self%c*x(1)**2)
  end subroutine pitchfork_residual

  subroutine pitchfork_jacobian(self, x, lambda, fx, flambda)
    class(pitchfork), intent(in) :: self
    real(wp), intent(in) :: x(:), lambda
    real(wp), intent(out) :: fx(:, :), flambda(:)
    fx(1, 1) = lambda - 3*self%c*x(1)**2
    flambda(1) = x(1)
  end subroutine pitchfork_jacobian

  function amplitude_level_value(self, z, t) result(g)
    class(amplitude_level), intent(in) :: self
    real(wp), intent(in) :: z(:), t(:)
    real(wp) :: g
    g = z(1)**2 + z(2)**2 - self%level + 0*t(1)
  end function amplitude_level_value

  !> |a^2 ((g/2)^2 + (s - k a^2)^2) - forcing^2| at z = (p, q, s): the amplitude equation.
  pure real(wp) function amplitude_error(sys, z) result(err)
    type(averaged_duffing), intent(in) :: sys
    real(wp), intent(in) :: z(:)
    real(wp) :: a2
    a2 = z(1)**2 + z(2)**2
    err = abs(a2*((sys%g/2)**2 + (z(3) - sys%k*a2)**2) - sys%forcing**2)
  end function amplitude_error

  !> The upper sheet s = k u + sqrt(forcing^2/u - g^2/4) of the response, u = a^2.
  pure real(wp) function s_upper(sys, u)
    type(averaged_duffing), intent(in) :: sys
    real(wp), intent(in) :: u
    s_upper = sys%k*u + sqrt(sys%forcing**2/u - sys%g**2/4)
  end function s_upper

  !> ds/du = 0 on the upper sheet <=> h(u) = 2 k u^2 sqrt(forcing^2/u - g^2/4) - forcing^2 = 0.
  pure real(wp) function fold_function(sys, u) result(h)
    type(averaged_duffing), intent(in) :: sys
    real(wp), intent(in) :: u
    h = 2*sys%k*u**2*sqrt(max(0.0_wp, sys%forcing**2/u - sys%g**2/4)) - sys%forcing**2
  end function fold_function

  !> Root of fold_function in [lo, hi] (a sign change) by bisection, to the last bit.
  pure real(wp) function bisect_fold(sys, lo, hi) result(mid)
    type(averaged_duffing), intent(in) :: sys
    real(wp), intent(in) :: lo, hi
    real(wp) :: a, b
    integer :: i
    a = lo
    b = hi
    mid = (a + b)/2
    do i = 1, 200
      mid = (a + b)/2
      if (mid <= a .or. mid >= b) exit
      if ((fold_function(sys, mid) > 0) .eqv. (fold_function(sys, a) > 0)) then
        a = mid
      else
        b = mid
      end if
    end do
  end function bisect_fold
end module continuation_test_systems

program test_continuation
  use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, SD_NOT_CONVERGED, SD_SINGULAR
  use sloshdyn_text, only: num2str
  use sloshdyn_continuation, only: newton_options, continuation_options, newton_solve, &
                                   continue_branch, correct_at, branch_tangent, locate_fold, &
                                   locate_zero_on_branch, stop_reason_name, STOP_NONE, &
                                   STOP_LAMBDA_MIN, STOP_LAMBDA_MAX, STOP_MAX_POINTS, &
                                   STOP_CLOSED, STOP_X_MAX, STOP_FAILED, separable_system
  use continuation_test_systems, only: circle_and_line, circle, averaged_duffing, walled_line, &
                                       sine_graph, pitchfork, &
                                       amplitude_level, amplitude_error, s_upper, &
                                       fold_function, bisect_fold
  use checks, only: check_close, check_true, finish
  implicit none

  integer, parameter :: capacity = 5000

  call test_newton()
  call test_circle()
  call test_reuse_jacobian()
  call test_duffing()
  call test_stopping()
  call test_bad_input()
  call finish()

contains

  !> The folds of a branch (points, tangents): where lambda's component of the tangent (the
  !> last) changes sign, located by locate_fold. Each must be located and there must be two,
  !> returned in the order the branch meets them.
  subroutine two_folds(label, sys, points, tangents, folds)
    character(len=*), intent(in) :: label
    class(separable_system), intent(in) :: sys
    real(wp), intent(in) :: points(:, :), tangents(:, :)
    real(wp), intent(out) :: folds(:, :)
    real(wp) :: z(size(points, 1))
    integer :: k, n_folds, status
    character(len=message_len) :: message

    n_folds = 0
    do k = 1, size(points, 2) - 1
      if (first_fold(tangents(:, k:k + 1)) /= 1) cycle
      n_folds = n_folds + 1
      call locate_fold(sys, points(:, k), tangents(:, k), points(:, k + 1), tangents(:, k + 1), &
                       z, status, message)
      call check_true(label//': fold '//num2str(n_folds)//' located: '//trim(message), &
                      status == SD_OK)
      if (n_folds <= 2) folds(:, n_folds) = z
    end do
    call check_true(label//': two folds ('//num2str(n_folds)//')', n_folds == 2)
  end subroutine two_folds

  !> The first k where lambda's component of the tangent (the last) changes sign between
  !> tangents k and k + 1 (size(tangents, 2) if none).
  pure integer function first_fold(tangents) result(k)
    real(wp), intent(in) :: tangents(:, :)
    integer :: m
    m = size(tangents, 1)
    do k = 1, size(tangents, 2) - 1
      if (tangents(m, k)*tangents(m, k + 1) < 0) exit
    end do
  end function first_fold

  !> Quasi-Newton iterations (newton_options%reuse_jacobian: the first or last Jacobian,
  !> updated by Broyden's formula): Newton's root of x1^2 + x2^2 = 4, x1 = x2 (sqrt 2, sqrt 2),
  !> and the circle x^2 + lambda^2 = 1 continued round to its start, every point on it.
  subroutine test_reuse_jacobian()
    type(circle_and_line) :: pair
    type(circle) :: sys
    type(newton_options) :: newton
    type(continuation_options) :: opt
    real(wp), allocatable :: points(:, :), tangents(:, :), arclength(:)
    real(wp) :: x(2)
    integer :: n_points, stop_reason, status, iterations
    character(len=message_len) :: message

    newton%reuse_jacobian = .true.
    x = [1.0_wp, 0.5_wp]
    call newton_solve(pair, x, 4.0_wp, newton, iterations, status, message)
    call check_true('quasi-Newton converges: '//trim(message), status == SD_OK)
    call check_close('quasi-Newton root x1 = sqrt(2)', x(1), sqrt(2.0_wp), 0.0_wp, 1.0e-11_wp)
    call check_close('quasi-Newton root x2 = sqrt(2)', x(2), sqrt(2.0_wp), 0.0_wp, 1.0e-11_wp)

    allocate (points(2, capacity), tangents(2, capacity), arclength(capacity))
    opt%ds = 0.05_wp
    opt%ds_max = 0.2_wp
    opt%lambda_min = -2
    opt%lambda_max = 2
    opt%newton%reuse_jacobian = .true.
    call continue_branch(sys, [1.0_wp], 0.0_wp, opt, points, tangents, arclength, n_points, &
                         stop_reason, status, message)
    print '(a)', '  circle, quasi-Newton corrector: '//num2str(n_points)//' points, '// &
                 stop_reason_name(stop_reason)
    call check_true('circle, quasi-Newton: continuation succeeds: '//trim(message), &
                    status == SD_OK .and. stop_reason == STOP_CLOSED)
    call check_close('circle, quasi-Newton: every point has x^2 + lambda^2 = 1', &
                     maxval(abs(points(1, :n_points)**2 + points(2, :n_points)**2 - 1)), &
                     0.0_wp, 0.0_wp, 1.0e-10_wp)
    call check_true('circle, quasi-Newton: it visits x < 0 and lambda < 0', &
                    minval(points(1, :n_points)) < -0.99_wp .and. &
                    minval(points(2, :n_points)) < -0.99_wp)
  end subroutine test_reuse_jacobian

  !> Newton on x1^2 + x2^2 = 4, x1 = x2 from (1, 0.5): the root (sqrt 2, sqrt 2), errors that
  !> square from one iteration to the next (quadratic convergence), and the failures.
  subroutine test_newton()
    type(circle_and_line) :: sys
    type(newton_options) :: opt
    real(wp), parameter :: root = sqrt(2.0_wp)
    real(wp) :: x(2), x_quiet(2), errors(0:8)
    integer :: k, iterations, status, iterations_quiet, status_quiet
    character(len=message_len) :: message

    errors(0) = maxval(abs([1.0_wp, 0.5_wp] - root))
    do k = 1, 8
      x = [1.0_wp, 0.5_wp]
      opt%max_iter = k
      call newton_solve(sys, x, 4.0_wp, opt, iterations, status, message)
      errors(k) = maxval(abs(x - root))
    end do
    print '(a, *(es10.2))', 'Newton errors after k iterations:', errors
    ! e_(k+1) <= C e_k^2 with C = 1 (the constant of this system is about 0.35), while the
    ! error is above rounding
    do k = 1, 7
      if (errors(k) < 1.0e-7_wp) exit
      call check_true('quadratic convergence, iteration '//num2str(k + 1)//': error '// &
                      num2str(errors(k + 1))//' <= (error '//num2str(errors(k))//')^2', &
                      errors(k + 1) <= errors(k)**2)
    end do

    x = [1.0_wp, 0.5_wp]
    call newton_solve(sys, x, 4.0_wp, newton_options(), iterations, status, message)
    call check_true('Newton converges: '//trim(message), status == SD_OK)
    call check_true('Newton needs few iterations ('//num2str(iterations)//' <= 7)', &
                    iterations <= 7)
    call check_close('Newton root x1 = sqrt(2)', x(1), root, 0.0_wp, 1.0e-12_wp)
    call check_close('Newton root x2 = sqrt(2)', x(2), root, 0.0_wp, 1.0e-12_wp)

    ! dF/dx = [0, 0; 1, -1] at the origin
    x = 0
    call newton_solve(sys, x, 4.0_wp, newton_options(), iterations, status, message)
    print '(a)', '  message: '//trim(message)
    call check_true('Newton from a singular Jacobian returns SD_SINGULAR', status == SD_SINGULAR)
    call check_true('  and the message says where', index(message, 'lambda = 4') > 0 .and. &
                    index(message, 'max|x| = 0') > 0 .and. index(message, 'max|F| = 4') > 0)

    ! x1^2 + x2^2 = -1 has no real root
    x = [1.0_wp, 0.5_wp]
    call newton_solve(sys, x, -1.0_wp, newton_options(), iterations, status, message)
    print '(a)', '  message: '//trim(message)
    call check_true('Newton without a root returns SD_NOT_CONVERGED after max_iter', &
                    status == SD_NOT_CONVERGED .and. iterations == 20)
    call check_true('  and the message says where', index(message, 'lambda = -1') > 0 .and. &
                    index(message, 'max|F|') > 0)

    ! explain = .false. (the seed scans) changes the message only: same iterate, same status
    x_quiet = [1.0_wp, 0.5_wp]
    call newton_solve(sys, x_quiet, -1.0_wp, newton_options(), iterations_quiet, status_quiet, &
                      message, explain=.false.)
    call check_true('explain = .false.: the same status, iterations and last iterate', &
                    status_quiet == status .and. iterations_quiet == iterations .and. &
                    all(x_quiet == x))
    call check_true('  and a message without the numbers: '//trim(message), &
                    trim(message) == 'Newton did not converge')
    x = 0
    x_quiet = 0
    call newton_solve(sys, x, 4.0_wp, newton_options(), iterations, status, message)
    call newton_solve(sys, x_quiet, 4.0_wp, newton_options(), iterations_quiet, status_quiet, &
                      message, explain=.false.)
    call check_true('explain = .false. from a singular Jacobian: the same status and iterate', &
                    status_quiet == status .and. status == SD_SINGULAR .and. all(x_quiet == x))
  end subroutine test_newton

  !> x^2 + lambda^2 = 1 from (1, 0) upward: over the fold (0, 1), down the x < 0 half, over the
  !> fold (0, -1) and back to the start, an isola.
  subroutine test_circle()
    type(circle) :: sys
    type(continuation_options) :: opt
    real(wp), allocatable :: points(:, :), tangents(:, :), arclength(:)
    real(wp) :: z_fold(2), z(2), t(2), folds(2, 2), worst
    integer :: n_points, stop_reason, status, k
    character(len=message_len) :: message

    allocate (points(2, capacity), tangents(2, capacity), arclength(capacity))
    opt%ds = 0.05_wp
    opt%ds_max = 0.2_wp
    opt%lambda_min = -2
    opt%lambda_max = 2
    call continue_branch(sys, [1.0_wp], 0.0_wp, opt, points, tangents, arclength, n_points, &
                         stop_reason, status, message)
    print '(a)', '  circle: '//num2str(n_points)//' points, '//stop_reason_name(stop_reason)
    call check_true('circle: continuation succeeds: '//trim(message), status == SD_OK)
    call check_true('circle: the branch closes as an isola', stop_reason == STOP_CLOSED)
    call check_true('circle: the last point is the first', n_points > 10 .and. &
                    all(points(:, n_points) == points(:, 1)))
    call check_close('circle: first tangent, x-component', tangents(1, 1), 0.0_wp, 0.0_wp, &
                     1.0e-14_wp)
    call check_close('circle: first tangent goes up in lambda', tangents(2, 1), 1.0_wp, 0.0_wp, &
                     1.0e-14_wp)
    worst = maxval(abs(points(1, :n_points)**2 + points(2, :n_points)**2 - 1))
    call check_close('circle: every point has x^2 + lambda^2 = 1', worst, 0.0_wp, 0.0_wp, &
                     1.0e-12_wp)
    ! pseudo-arclength sums chords projected on tangents: a little below 2 pi
    call check_true('circle: pseudo-arclength of the loop '//num2str(arclength(n_points))// &
                    ' within 2 % below 2 pi', arclength(n_points) <= 2*pi .and. &
                    arclength(n_points) >= 0.98_wp*2*pi)
    call check_true('circle: it visits x < 0 and lambda < 0', &
                    minval(points(1, :n_points)) < -0.99_wp .and. &
                    minval(points(2, :n_points)) < -0.99_wp)

    call two_folds('circle', sys, points(:, :n_points), tangents(:, :n_points), folds)
    call check_close('circle: first fold at lambda = 1', folds(2, 1), 1.0_wp, 0.0_wp, 1.0e-10_wp)
    call check_close('circle: first fold at x = 0', folds(1, 1), 0.0_wp, 0.0_wp, 1.0e-10_wp)
    call check_close('circle: second fold at lambda = -1', folds(2, 2), -1.0_wp, 0.0_wp, &
                     1.0e-10_wp)
    call check_close('circle: second fold at x = 0', folds(1, 2), 0.0_wp, 0.0_wp, 1.0e-10_wp)

    ! correct_at from (1, 0) along (0, 1): the hyperplane lambda = ds
    call correct_at(sys, [1.0_wp, 0.0_wp], [0.0_wp, 1.0_wp], 0.5_wp, z, status, message)
    call check_true('circle: correct_at succeeds: '//trim(message), status == SD_OK)
    call check_close('circle: correct_at x = sqrt(0.75)', z(1), sqrt(0.75_wp), 0.0_wp, &
                     1.0e-13_wp)
    call check_close('circle: correct_at lambda = ds', z(2), 0.5_wp, 0.0_wp, 1.0e-15_wp)

    ! branch_tangent at (cos 1, sin 1): +-(-sin 1, cos 1), the sign given by t_prev
    call branch_tangent(sys, [cos(1.0_wp), sin(1.0_wp)], [0.0_wp, 1.0_wp], t, status, message)
    call check_close('circle: tangent oriented upward, x', t(1), -sin(1.0_wp), 0.0_wp, 1.0e-14_wp)
    call check_close('circle: tangent oriented upward, lambda', t(2), cos(1.0_wp), 0.0_wp, &
                     1.0e-14_wp)
    call branch_tangent(sys, [cos(1.0_wp), sin(1.0_wp)], [0.0_wp, -1.0_wp], t, status, message)
    call check_close('circle: tangent oriented downward, x', t(1), sin(1.0_wp), 0.0_wp, &
                     1.0e-14_wp)

    ! the other direction: first fold at lambda = -1
    opt%direction = -1
    call continue_branch(sys, [1.0_wp], 0.0_wp, opt, points, tangents, arclength, n_points, &
                         stop_reason, status, message)
    call check_true('circle, direction -1: closes', status == SD_OK .and. &
                    stop_reason == STOP_CLOSED)
    call check_close('circle, direction -1: first tangent goes down', tangents(2, 1), -1.0_wp, &
                     0.0_wp, 1.0e-14_wp)
    k = first_fold(tangents(:, :n_points))
    call locate_fold(sys, points(:, k), tangents(:, k), points(:, k + 1), tangents(:, k + 1), &
                     z_fold, status, message)
    call check_close('circle, direction -1: first fold at lambda = -1', z_fold(2), -1.0_wp, &
                     0.0_wp, 1.0e-10_wp)

    ! a weighted norm changes the steps, not the branch
    opt%direction = 1
    opt%x_scale = 10
    call continue_branch(sys, [1.0_wp], 0.0_wp, opt, points, tangents, arclength, n_points, &
                         stop_reason, status, message)
    call check_true('circle, x_scale = 10: closes', status == SD_OK .and. &
                    stop_reason == STOP_CLOSED)
    call check_close('circle, x_scale = 10: tangents are unit in the weighted norm', &
                     maxval(abs(100*tangents(1, :n_points)**2 + tangents(2, :n_points)**2 - 1)), &
                     0.0_wp, 0.0_wp, 1.0e-14_wp)
    call check_close('circle, x_scale = 10: points on the circle', &
                     maxval(abs(points(1, :n_points)**2 + points(2, :n_points)**2 - 1)), &
                     0.0_wp, 0.0_wp, 1.0e-12_wp)
    k = first_fold(tangents(:, :n_points))
    call locate_fold(sys, points(:, k), tangents(:, k), points(:, k + 1), tangents(:, k + 1), &
                     z_fold, status, message, opt)
    call check_true('circle, x_scale = 10: fold located with the same options: '// &
                    trim(message), status == SD_OK)
    call check_close('circle, x_scale = 10: fold at lambda = 1', z_fold(2), 1.0_wp, 0.0_wp, &
                     1.0e-10_wp)
    call check_close('circle, x_scale = 10: fold at x = 0', z_fold(1), 0.0_wp, 0.0_wp, &
                     1.0e-10_wp)
  end subroutine test_circle

  !> The Duffing frequency response from s = -0.5 to 1.5 (g = 0.02, k = 1, forcing = 0.01):
  !> every point satisfies the amplitude equation, and the two folds agree with the closed form
  !> s = k u + sqrt(forcing^2/u - g^2/4), u = a^2, whose folds solve ds/du = 0, i.e.
  !> h(u) = 2 k u^2 sqrt(forcing^2/u - g^2/4) - forcing^2 = 0 (found here by bisection).
  subroutine test_duffing()
    type(averaged_duffing) :: sys
    type(continuation_options) :: opt
    type(amplitude_level) :: level
    real(wp), allocatable :: points(:, :), tangents(:, :), arclength(:)
    real(wp) :: z(3), u, s, worst, u_lower, u_upper, s_expected, u_peak, cos_turn
    real(wp) :: folds(3, 2)
    integer :: n_points, stop_reason, status, k, n_folds, n_levels
    character(len=message_len) :: message

    allocate (points(3, capacity), tangents(3, capacity), arclength(capacity))
    opt%ds = 0.01_wp
    opt%ds_max = 0.05_wp
    opt%lambda_min = -0.5_wp
    opt%lambda_max = 1.5_wp
    opt%max_points = capacity
    call continue_branch(sys, [0.0_wp, 0.0_wp], -0.5_wp, opt, points, tangents, arclength, &
                         n_points, stop_reason, status, message)
    print '(a)', '  Duffing: '//num2str(n_points)//' points, '//stop_reason_name(stop_reason)
    call check_true('Duffing: continuation succeeds: '//trim(message), status == SD_OK)
    call check_true('Duffing: ends on lambda_max', stop_reason == STOP_LAMBDA_MAX .and. &
                    points(3, n_points) == 1.5_wp)
    worst = 0
    do k = 1, n_points
      worst = max(worst, amplitude_error(sys, points(:, k))/sys%forcing**2)
    end do
    call check_close('Duffing: every point satisfies a^2((g/2)^2 + (s - k a^2)^2) = F^2 '// &
                     '(relative)', worst, 0.0_wp, 0.0_wp, 1.0e-10_wp)
    ! a^2 <= (2 forcing/g)^2 = 1, reached at s = k: the branch passes over the peak
    u = maxval(points(1, :n_points)**2 + points(2, :n_points)**2)
    call check_true('Duffing: the largest a^2 on the branch, '//num2str(u)//', is just '// &
                    'below the peak 1', u <= 1 + 1.0e-12_wp .and. u > 0.999_wp)

    ! closed-form folds: h < 0 at u -> 0 and at the peak u_peak = (2 forcing/g)^2, > 0 between
    u_peak = (2*sys%forcing/sys%g)**2
    call check_true('Duffing: h(u) brackets two folds', fold_function(sys, 1.0e-6_wp) < 0 .and. &
                    fold_function(sys, 0.5_wp*u_peak) > 0 .and. fold_function(sys, u_peak) < 0)
    u_lower = bisect_fold(sys, 1.0e-6_wp, 0.5_wp*u_peak)
    u_upper = bisect_fold(sys, 0.5_wp*u_peak, u_peak)
    print '(a, 4es24.16)', '  closed-form folds (u, s): ', u_lower, s_upper(sys, u_lower), &
      u_upper, s_upper(sys, u_upper)

    call two_folds('Duffing', sys, points(:, :n_points), tangents(:, :n_points), folds)
    ! the branch meets the upper fold (jump down) first, then the lower one (jump up)
    print '(a, 4es24.16)', '  located folds (u, s):     ', sum(folds(1:2, 2)**2), folds(3, 2), &
      sum(folds(1:2, 1)**2), folds(3, 1)
    call check_close('Duffing: upper fold s', folds(3, 1), s_upper(sys, u_upper), 0.0_wp, &
                     1.0e-8_wp)
    call check_close('Duffing: upper fold a^2', sum(folds(1:2, 1)**2), u_upper, 0.0_wp, &
                     1.0e-8_wp)
    call check_close('Duffing: lower fold s', folds(3, 2), s_upper(sys, u_lower), 0.0_wp, &
                     1.0e-8_wp)
    call check_close('Duffing: lower fold a^2', sum(folds(1:2, 2)**2), u_lower, 0.0_wp, &
                     1.0e-8_wp)

    ! a generic test function: where a^2 = 0.25, s = k u -+ sqrt(forcing^2/u - g^2/4)
    n_levels = 0
    do k = 1, n_points - 1
      if (level%value(points(:, k), tangents(:, k))* &
          level%value(points(:, k + 1), tangents(:, k + 1)) >= 0) cycle
      n_levels = n_levels + 1
      call locate_zero_on_branch(sys, points(:, k), tangents(:, k), &
                                 arclength(k + 1) - arclength(k), level, z, status, message)
      call check_true('Duffing: a^2 = 0.25 located: '//trim(message), status == SD_OK)
      u = z(1)**2 + z(2)**2
      call check_close('Duffing: located a^2 = 0.25', u, 0.25_wp, 0.0_wp, 1.0e-12_wp)
      s = s_upper(sys, 0.25_wp)
      s_expected = merge(s, 2*sys%k*0.25_wp - s, n_levels == 2)
      call check_close('Duffing: s at a^2 = 0.25, crossing '//num2str(n_levels), z(3), &
                       s_expected, 0.0_wp, 1.0e-10_wp)
    end do
    call check_true('Duffing: a^2 = 0.25 crossed twice ('//num2str(n_levels)//')', n_levels == 2)

    ! steps limited by the turning of the tangent, not by ds_max: with ds_max = 3 the branch
    ! keeps both folds, every point solves the system, and no step turns by more than
    ! acos(0.9) (the module's safeguard)
    opt%ds_max = 3
    call continue_branch(sys, [0.0_wp, 0.0_wp], -0.5_wp, opt, points, tangents, arclength, &
                         n_points, stop_reason, status, message)
    call check_true('Duffing, ds_max = 3: ends on lambda_max', status == SD_OK .and. &
                    stop_reason == STOP_LAMBDA_MAX)
    n_folds = count(tangents(3, :n_points - 1)*tangents(3, 2:n_points) < 0)
    call check_true('Duffing, ds_max = 3: two folds ('//num2str(n_folds)//')', n_folds == 2)
    worst = 0
    cos_turn = 1
    do k = 1, n_points
      worst = max(worst, amplitude_error(sys, points(:, k))/sys%forcing**2)
      if (k > 1) cos_turn = min(cos_turn, sum(tangents(:, k - 1)*tangents(:, k)))
    end do
    call check_close('Duffing, ds_max = 3: points on the amplitude curve', worst, 0.0_wp, &
                     0.0_wp, 1.0e-10_wp)
    call check_true('Duffing, ds_max = 3: consecutive tangents within acos(0.9), min cos = '// &
                    num2str(cos_turn), cos_turn >= 0.9_wp)

    call check_close('Duffing: the folds lie on the amplitude curve', &
                     max(amplitude_error(sys, folds(:, 1)), amplitude_error(sys, folds(:, 2)))/ &
                     sys%forcing**2, 0.0_wp, 0.0_wp, 1.0e-10_wp)

  end subroutine test_duffing

  !> The ways a branch ends.
  subroutine test_stopping()
    type(circle) :: sys
    type(walled_line) :: line
    type(sine_graph) :: wave
    type(pitchfork) :: fork
    type(continuation_options) :: opt
    real(wp), allocatable :: points(:, :), tangents(:, :), arclength(:)
    real(wp) :: z(2)
    integer :: n_points, stop_reason, status
    character(len=message_len) :: message

    allocate (points(2, capacity), tangents(2, capacity), arclength(capacity))
    ! leaving [lambda_min, lambda_max]: the last point lies on the bound
    opt%ds = 0.07_wp
    opt%ds_max = 0.2_wp
    opt%lambda_min = -0.3_wp
    opt%lambda_max = 0.5_wp
    call continue_branch(sys, [1.0_wp], 0.0_wp, opt, points, tangents, arclength, n_points, &
                         stop_reason, status, message)
    call check_true('circle to lambda_max = 0.5: stops there', status == SD_OK .and. &
                    stop_reason == STOP_LAMBDA_MAX)
    call check_true('  the last lambda is exactly 0.5', points(2, n_points) == 0.5_wp)
    call check_close('  the last x is sqrt(0.75)', points(1, n_points), sqrt(0.75_wp), 0.0_wp, &
                     1.0e-12_wp)
    call check_true('  the earlier points lie below', all(points(2, :n_points - 1) < 0.5_wp))
    call check_true('  columns after n_points are NaN', ieee_is_nan(points(1, n_points + 1)))
    opt%direction = -1
    call continue_branch(sys, [1.0_wp], 0.0_wp, opt, points, tangents, arclength, n_points, &
                         stop_reason, status, message)
    call check_true('circle to lambda_min = -0.3: the last lambda is exactly -0.3', &
                    status == SD_OK .and. stop_reason == STOP_LAMBDA_MIN .and. &
                    points(2, n_points) == -0.3_wp)
    call check_close('  the last x is sqrt(0.91)', points(1, n_points), sqrt(0.91_wp), 0.0_wp, &
                     1.0e-12_wp)

    ! x = 3 sin(lambda) crosses the line 3 x + lambda = 0 through its start (0, 0), normal to
    ! the first tangent, from behind at lambda ~ 5.6, x ~ -1.9: far from the start, no isola
    opt = continuation_options()
    opt%ds = 0.1_wp
    opt%lambda_max = 8
    call continue_branch(wave, [0.0_wp], 0.0_wp, opt, points, tangents, arclength, n_points, &
                         stop_reason, status, message)
    call check_true('x = 3 sin(lambda) passing behind its start: no isola, ends on lambda_max', &
                    status == SD_OK .and. stop_reason == STOP_LAMBDA_MAX .and. &
                    points(2, n_points) == 8)

    ! along x = 0 through the pitchfork at lambda = 0: straight on to lambda_max, not back
    opt = continuation_options()
    opt%ds = 0.1_wp
    opt%ds_max = 0.2_wp
    opt%lambda_min = -2
    opt%lambda_max = 1
    call continue_branch(fork, [0.0_wp], -1.037_wp, opt, points, tangents, arclength, n_points, &
                         stop_reason, status, message)
    call check_true('x = 0 through the pitchfork at lambda = 0: on to lambda_max = 1', &
                    status == SD_OK .and. stop_reason == STOP_LAMBDA_MAX .and. &
                    points(2, n_points) == 1 .and. all(points(1, :n_points) == 0) .and. &
                    all(tangents(2, :n_points) > 0))

    ! max_points
    opt = continuation_options()
    opt%max_points = 5
    call continue_branch(sys, [1.0_wp], 0.0_wp, opt, points, tangents, arclength, n_points, &
                         stop_reason, status, message)
    call check_true('circle with max_points = 5: 5 points', status == SD_OK .and. &
                    stop_reason == STOP_MAX_POINTS .and. n_points == 5)

    ! F is NaN beyond lambda = 0.5: steps shrink to ds_min, the points so far are kept
    line%wall = 0.5_wp
    opt = continuation_options()
    opt%ds = 0.1_wp
    opt%ds_max = 0.1_wp
    opt%ds_min = 1.0e-6_wp
    opt%lambda_max = 2
    call continue_branch(line, [0.0_wp], 0.0_wp, opt, points, tangents, arclength, n_points, &
                         stop_reason, status, message)
    print '(a)', '  message: '//trim(message)
    call check_true('branch ending at a wall: SD_NOT_CONVERGED, STOP_FAILED', &
                    status == SD_NOT_CONVERGED .and. stop_reason == STOP_FAILED)
    call check_true('  the partial branch is kept, up to the wall', n_points > 1 .and. &
                    points(2, n_points) <= 0.5_wp .and. points(2, n_points) > 0.5_wp - 1.0e-5_wp)
    call check_true('  the message names ds_min and where', index(message, 'ds_min') > 0 .and. &
                    index(message, 'lambda = 0.4999') > 0)

    ! x_max
    line = walled_line(slope=10)
    opt = continuation_options()
    opt%ds = 0.1_wp
    opt%x_max = 1
    call continue_branch(line, [0.0_wp], 0.0_wp, opt, points, tangents, arclength, n_points, &
                         stop_reason, status, message)
    call check_true('x = 10 lambda with x_max = 1: stops after the first point beyond', &
                    status == SD_OK .and. stop_reason == STOP_X_MAX .and. &
                    abs(points(1, n_points)) > 1 .and. abs(points(1, n_points - 1)) <= 1)

    ! a start that is no solution: x^2 = 1 - 1.5^2 < 0
    opt = continuation_options()
    call continue_branch(sys, [1.0_wp], 1.5_wp, opt, points, tangents, arclength, n_points, &
                         stop_reason, status, message)
    print '(a)', '  message: '//trim(message)
    call check_true('start off the branch: SD_NOT_CONVERGED, no points', &
                    status == SD_NOT_CONVERGED .and. n_points == 0 .and. &
                    stop_reason == STOP_NONE)

    ! locate_fold between points without a fold
    call locate_fold(sys, [1.0_wp, 0.0_wp], [0.0_wp, 1.0_wp], [sqrt(0.75_wp), 0.5_wp], &
                     [-0.5_wp, sqrt(0.75_wp)], z, status, message)
    call check_true('locate_fold without a sign change: SD_BAD_INPUT', status == SD_BAD_INPUT)
  end subroutine test_stopping

  !> Each option rule: SD_BAD_INPUT with a message that starts with the option's name.
  subroutine test_bad_input()
    type(circle) :: sys
    type(continuation_options) :: opt
    type(newton_options) :: nopt
    real(wp) :: x(1)
    integer :: status, iterations
    character(len=message_len) :: message

    opt = continuation_options()
    opt%ds = 0
    call expect_bad(opt, 'ds = 0', 'ds = ')
    opt%ds = -0.1_wp
    call expect_bad(opt, 'ds < 0', 'ds = ')
    opt = continuation_options()
    opt%lambda_min = 1
    opt%lambda_max = 0
    call expect_bad(opt, 'lambda_min >= lambda_max', 'lambda_max = ')
    opt = continuation_options()
    opt%direction = 0
    call expect_bad(opt, 'direction = 0', 'direction = ')
    opt%direction = 2
    call expect_bad(opt, 'direction = 2', 'direction = ')
    opt = continuation_options()
    opt%max_points = 1
    call expect_bad(opt, 'max_points = 1', 'max_points = ')
    opt = continuation_options()
    opt%ds_min = 1
    call expect_bad(opt, 'ds_min > ds', 'ds_min = ')
    opt = continuation_options()
    opt%newton%f_tol = 0
    call expect_bad(opt, 'newton%f_tol = 0', 'newton%f_tol = ')
    opt = continuation_options()
    opt%max_points = 20
    call expect_bad(opt, 'points with fewer than max_points columns', 'points has shape')

    nopt%x_tol = -1
    x = 1
    call newton_solve(sys, x, 0.0_wp, nopt, iterations, status, message)
    call check_true('newton_solve with x_tol < 0: SD_BAD_INPUT naming x_tol', &
                    status == SD_BAD_INPUT .and. index(message, 'x_tol = ') == 1)

  end subroutine test_bad_input

  subroutine expect_bad(opt, label, prefix)
    type(continuation_options), intent(in) :: opt
    character(len=*), intent(in) :: label, prefix
    type(circle) :: sys
    real(wp) :: points(2, 10), tangents(2, 10), arclength(10)
    integer :: n_points, stop_reason, status
    character(len=message_len) :: message
    call continue_branch(sys, [1.0_wp], 0.0_wp, opt, points, tangents, arclength, n_points, &
                         stop_reason, status, message)
    print '(a)', '  message: '//trim(message)
    call check_true('bad option '//label//': SD_BAD_INPUT naming it', &
                    status == SD_BAD_INPUT .and. index(message, prefix) == 1 .and. &
                    n_points == 0)
  end subroutine expect_bad
end program test_continuation
