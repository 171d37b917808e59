!> Continuation of the limit cycles of an autonomous system y' = f(y; lambda) in lambda, with
!> their Floquet multipliers and bifurcations: folds of cycles, period doublings and
!> Neimark-Sacker points. Generic: the system comes as an autonomous_family, a periodic_problem
!> whose "forcing period" is the cycle's period, an unknown here, so that the shooting of
!> sloshdyn_shooting (monodromy matrix and parameter sensitivity by the variational equations)
!> and the pseudo-arclength continuation of sloshdyn_continuation serve it unchanged.
!>
!> Unknowns x = (y0(1:n), T/t_ref), t_ref the start's period (so that all unknowns are O(1) in
!> the arclength norm); equations
!>   F(x, lambda) = [y(T; y0, lambda) - y0 ; f_p(y0; lambda)] = 0,
!> the phase condition f_p(y0) = 0 (p = phase_index) putting y0 where y_p is extremal on the
!> cycle: intrinsic (no reference cycle), so the system is fixed along the branch. Jacobian
!>   [[M - I, f(y(T)) t_ref], [J(y0)(p, :), 0]],  dF/dlambda = [s(T) ; df_p/dlambda (y0)],
!> M the monodromy matrix, s the parameter sensitivity. One multiplier is +1 (the flow
!> direction), so det(M - I) tells nothing; folds of cycles are where the tangent's lambda
!> component changes sign, period doublings where det(M + I) does, Neimark-Sacker points where a
!> complex pair crosses the unit circle (sloshdyn_shooting's tests).
!>
!> Layouts of the results of cycle_branch (n = size(y0)):
!>   points(:, j)      = [lambda, y0(1:n), T, stable (1/0)]        (n + 3 rows)
!>   multipliers(:, j) = [Re mu(1:n), Im mu(1:n)]                   (2 n rows)
!>   special(:, j)     = [kind (SPECIAL_*), lambda, y0(1:n), T]     (n + 3 rows)
!> stable: every multiplier but the trivial one (the nearest to +1) inside the unit circle.
module sloshdyn_cycle_branch
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, SD_CAPACITY
  use sloshdyn_text, only: num2str
  use sloshdyn_lapack, only: eigenvalues
  use sloshdyn_ode, only: ode_options
  use sloshdyn_continuation, only: parametrised_system, continuation_options, &
                                   continue_branch, stop_reason_name, STOP_LAMBDA_MIN, &
                                   STOP_LAMBDA_MAX, STOP_CLOSED, STOP_MAX_POINTS
  use sloshdyn_shooting, only: periodic_problem, monodromy_matrix, period_doubling_test, &
                               neimark_sacker_test, kind_test, locate_special_points, &
                               branch_data
  use sloshdyn_tables, only: SPECIAL_PERIOD_DOUBLING
  implicit none
  private
  public :: autonomous_family, cycle_branch, cycle_point, stable_cycle

  !> An autonomous system y' = f(y; lambda) as a periodic_problem of period cycle_period:
  !> rhs, jacobian, parameter_derivative, set_parameter and parameter come from the extension
  !> (t unused); the period is a component, its lambda-derivative 0.
  type, abstract, extends(periodic_problem) :: autonomous_family
    real(wp) :: cycle_period = 1
  contains
    procedure :: period => family_period
    procedure :: period_derivative => family_period_derivative
  end type autonomous_family

  !> F(x, lambda) of the module header.
  type, extends(parametrised_system) :: cycle_system
    class(autonomous_family), allocatable :: family
    type(ode_options) :: options
    integer :: method = 0
    integer :: phase_index = 1
    real(wp) :: t_ref = 1
  contains
    procedure :: evaluate => cycle_evaluate
  end type cycle_system

  !> det(M + I) or the Neimark-Sacker product at a branch point, for locate_zero_on_branch.
  type, extends(kind_test) :: cycle_test
    type(cycle_system) :: sys
  contains
    procedure :: value => cycle_test_value
  end type cycle_test

contains

  function family_period(self) result(v)
    class(autonomous_family), intent(in) :: self
    real(wp) :: v
    v = self%cycle_period
  end function family_period

  function family_period_derivative(self) result(v)
    class(autonomous_family), intent(in) :: self
    real(wp) :: v
    v = 0
  end function family_period_derivative

  !> Follow the cycle through (y0, period) at the family's current lambda over [lambda_min,
  !> lambda_max] (options: steps, max_points, direction, x_scale, Newton tolerances; its lambda
  !> bounds are replaced). y0 must satisfy the phase condition f_p(y0) = 0 closely enough for
  !> Newton (phase_index = p). Results in the layouts of the module header; special points
  !> between consecutive points where a test changes sign. stop_reason: sloshdyn_continuation's
  !> STOP_*; status /= SD_OK on a failure (the points so far are kept), SD_CAPACITY when
  !> max_points or the columns of special ran out.
  subroutine cycle_branch(family, y0, period, phase_index, lambda_min, lambda_max, options, &
                          ode_settings, method, points, multipliers, n_points, special, &
                          n_special, stop_reason, status, message)
    class(autonomous_family), intent(in) :: family
    real(wp), intent(in) :: y0(:), period, lambda_min, lambda_max
    integer, intent(in) :: phase_index, method
    type(continuation_options), intent(in) :: options
    type(ode_options), intent(in) :: ode_settings
    real(wp), intent(out) :: points(:, :), multipliers(:, :), special(:, :)
    integer, intent(out) :: n_points, n_special, stop_reason, status
    character(len=message_len), intent(out) :: message
    type(cycle_system) :: sys
    type(cycle_test) :: test
    type(continuation_options) :: opt
    real(wp), allocatable :: z(:, :), tangents(:, :), arclength(:)
    integer :: n, m

    n = size(y0)
    m = n + 2
    n_points = 0
    n_special = 0
    stop_reason = 0
    points = ieee_value(1.0_wp, ieee_quiet_nan)
    multipliers = ieee_value(1.0_wp, ieee_quiet_nan)
    special = ieee_value(1.0_wp, ieee_quiet_nan)
    status = SD_OK
    message = ''
    if (.not. (period > 0) .or. phase_index < 1 .or. phase_index > n) then
      status = SD_BAD_INPUT
      message = 'cycle_branch: period = '//num2str(period)//' must be > 0 and phase_index = '// &
                num2str(phase_index)//' in [1, '//num2str(n)//']'
    else if (size(points, 1) /= n + 3 .or. size(points, 2) < options%max_points .or. &
             size(multipliers, 1) /= 2*n .or. size(multipliers, 2) < options%max_points .or. &
             size(special, 1) /= n + 3) then
      status = SD_BAD_INPUT
      message = 'points must be (n + 3) x max_points, multipliers 2 n x max_points and special'// &
                ' (n + 3) x any, n = size(y0) = '//num2str(n)
    end if
    if (status /= SD_OK) return

    allocate (sys%family, source=family)
    sys%options = ode_settings
    sys%method = method
    sys%phase_index = phase_index
    sys%t_ref = period
    opt = options
    opt%lambda_min = lambda_min
    opt%lambda_max = lambda_max
    allocate (z(m, max(options%max_points, 1)), tangents(m, max(options%max_points, 1)), &
              arclength(max(options%max_points, 1)))
    call continue_branch(sys, [y0, 1.0_wp], family%parameter(), opt, z, tangents, arclength, &
                         n_points, stop_reason, status, message)
    if (status /= SD_OK .and. n_points == 0) return

    call branch_data(z, point_data, points, multipliers, n_points, status, message)
    test%sys = sys
    call locate_special_points(sys, z, tangents, arclength, multipliers, n_points, .false., &
                               test, opt, point_data, special, n_special, status, message)

    if (status == SD_OK .and. stop_reason == STOP_MAX_POINTS) then
      status = SD_CAPACITY
      message = 'the cycle branch reached max_points = '//num2str(options%max_points)// &
                ' at lambda = '//num2str(z(m, n_points))//' before lambda_min or lambda_max'
    else if (status == SD_OK .and. all(stop_reason /= [STOP_LAMBDA_MIN, STOP_LAMBDA_MAX, &
                                                        STOP_CLOSED])) then
      message = 'the cycle branch stopped: '//stop_reason_name(stop_reason)
    end if

  contains

    subroutine point_data(zj, row, mult, st, msg)
      real(wp), intent(in) :: zj(:)
      real(wp), intent(out) :: row(:), mult(:)
      integer, intent(out) :: st
      character(len=message_len), intent(out) :: msg
      call cycle_point(sys, zj, row, mult, st, msg)
    end subroutine point_data
  end subroutine cycle_branch

  !> The stored row [lambda, y0, T, stable] and the multipliers [re, im] of the branch point
  !> z = (y0, T/t_ref, lambda).
  subroutine cycle_point(sys, z, row, mult, status, message)
    type(cycle_system), intent(in) :: sys
    real(wp), intent(in) :: z(:)
    real(wp), intent(out) :: row(:), mult(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: y_end(size(z) - 2), monodromy(size(z) - 2, size(z) - 2)
    integer :: n
    n = size(z) - 2
    call shoot_cycle(sys, z(1:n), z(n + 1), z(n + 2), y_end, monodromy, status, message)
    if (status == SD_OK) call eigenvalues(monodromy, mult(1:n), mult(n + 1:2*n), status, &
                                          message)
    if (status /= SD_OK) return
    row(1) = z(n + 2)
    row(2:n + 1) = z(1:n)
    row(n + 2) = z(n + 1)*sys%t_ref
    row(n + 3) = merge(1.0_wp, 0.0_wp, stable_cycle(mult(1:n), mult(n + 1:2*n)))
  end subroutine cycle_point

  !> Every multiplier but the one nearest to +1 (the flow direction) inside the unit circle.
  pure logical function stable_cycle(re, im) result(stable)
    real(wp), intent(in) :: re(:), im(:)
    real(wp) :: modulus(size(re))
    modulus = hypot(re, im)
    modulus(minloc(hypot(re - 1, im), 1)) = 0
    stable = all(modulus < 1)
  end function stable_cycle

  !> One shot of the family at lambda over T = t_scaled t_ref: y(T), M and (optionally) s(T).
  subroutine shoot_cycle(sys, y0, t_scaled, lambda, y_end, monodromy, status, message, &
                         sensitivity)
    type(cycle_system), intent(in) :: sys
    real(wp), intent(in) :: y0(:), t_scaled, lambda
    real(wp), intent(out) :: y_end(:), monodromy(:, :)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), intent(out), optional :: sensitivity(:)
    class(autonomous_family), allocatable :: family
    allocate (family, source=sys%family)
    call family%set_parameter(lambda)
    family%cycle_period = t_scaled*sys%t_ref
    if (.not. (family%cycle_period > 0)) then
      status = SD_BAD_INPUT
      message = 'the cycle period T = '//num2str(family%cycle_period)//' must be > 0'
      return
    end if
    call monodromy_matrix(family, y0, 1, sys%options, sys%method, y_end, monodromy, status, &
                          message, sensitivity)
  end subroutine shoot_cycle

  subroutine cycle_evaluate(self, x, lambda, f, fx, flambda)
    class(cycle_system), intent(in) :: self
    real(wp), intent(in) :: x(:), lambda
    real(wp), intent(out) :: f(:), fx(:, :), flambda(:)
    class(autonomous_family), allocatable :: family
    real(wp) :: y_end(size(x) - 1), monodromy(size(x) - 1, size(x) - 1), s(size(x) - 1), &
                jac(size(x) - 1, size(x) - 1), f_end(size(x) - 1), f0(size(x) - 1), &
                df(size(x) - 1)
    integer :: n, i, status, p
    character(len=message_len) :: message

    n = size(x) - 1
    p = self%phase_index
    call shoot_cycle(self, x(1:n), x(n + 1), lambda, y_end, monodromy, status, message, s)
    if (status /= SD_OK) then
      f = ieee_value(1.0_wp, ieee_quiet_nan)
      fx = ieee_value(1.0_wp, ieee_quiet_nan)
      flambda = ieee_value(1.0_wp, ieee_quiet_nan)
      return
    end if
    allocate (family, source=self%family)
    call family%set_parameter(lambda)
    call family%rhs(0.0_wp, y_end, f_end)
    call family%rhs(0.0_wp, x(1:n), f0)
    call family%jacobian(0.0_wp, x(1:n), jac)
    call family%parameter_derivative(0.0_wp, x(1:n), df)
    f(1:n) = y_end - x(1:n)
    f(n + 1) = f0(p)
    fx = 0
    fx(1:n, 1:n) = monodromy
    do i = 1, n
      fx(i, i) = fx(i, i) - 1
    end do
    fx(1:n, n + 1) = f_end*self%t_ref
    fx(n + 1, 1:n) = jac(p, :)
    flambda(1:n) = s
    flambda(n + 1) = df(p)
  end subroutine cycle_evaluate

  function cycle_test_value(self, z, t) result(g)
    class(cycle_test), intent(in) :: self
    real(wp), intent(in) :: z(:), t(:)
    real(wp) :: g
    real(wp) :: row(size(z) + 1), mult(2*(size(z) - 2))
    integer :: n, status
    character(len=message_len) :: message
    n = size(z) - 2
    g = ieee_value(1.0_wp, ieee_quiet_nan)
    call cycle_point(self%sys, z, row, mult, status, message)
    if (status /= SD_OK) return
    if (self%kind == SPECIAL_PERIOD_DOUBLING) then
      g = period_doubling_test(mult(1:n), mult(n + 1:))
    else
      g = neimark_sacker_test(mult(1:n), mult(n + 1:))
    end if
  end function cycle_test_value
end module sloshdyn_cycle_branch
