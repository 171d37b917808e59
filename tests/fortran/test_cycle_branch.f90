!> Continuation of limit cycles (sloshdyn_cycle_branch) against normal forms whose cycles are
!> known in closed form: in polar coordinates r' = r (mu + a r^2 - c r^4), theta' = w + b r^2
!> (here in Cartesian x, y), a cycle of radius r with g(r) = mu + a r^2 - c r^4 = 0, period
!> 2 pi/(w + b r^2) and non-trivial multiplier exp(T r g'(r)) = exp(T (2 a r^2 - 4 c r^4)).
!>   a = -1, c = 0: the supercritical Hopf normal form, r^2 = mu;
!>   a = 2, c = 1: two cycles r^2 = 1 +- sqrt(1 + mu) meeting in a fold of cycles at mu = -1.
module polar_family_system
  use sloshdyn_kinds, only: wp
  use sloshdyn_cycle_branch, only: autonomous_family
  implicit none
  private
  public :: polar_family

  type, extends(autonomous_family) :: polar_family
    real(wp) :: mu = 0.25_wp, a = -1, c = 0, w = 1, b = 0.8_wp
  contains
    procedure :: rhs => polar_rhs
    procedure :: jacobian => polar_jacobian
    procedure :: parameter_derivative => polar_parameter_derivative
    procedure :: set_parameter => polar_set_parameter
    procedure :: parameter => polar_parameter
  end type polar_family

contains

  subroutine polar_rhs(self, t, y, dydt)
    class(polar_family), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: dydt(:)
    real(wp) :: r2, g, h
    r2 = y(1)**2 + y(2)**2
    g = self%mu + self%a*r2 - self%c*r2**2
    h = self%w + self%b*r2
    dydt(1) = g*y(1) - h*y(2)
    dydt(2) = h*y(1) + g*y(2)
  end subroutine polar_rhs

  subroutine polar_jacobian(self, t, y, jac)
    class(polar_family), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: jac(:, :)
    real(wp) :: r2, g, h, dg(2), dh(2)
    r2 = y(1)**2 + y(2)**2
    g = self%mu + self%a*r2 - self%c*r2**2
    h = self%w + self%b*r2
    dg = (2*self%a - 4*self%c*r2)*y(1:2)
    dh = 2*self%b*y(1:2)
    jac(1, :) = y(1)*dg - y(2)*dh
    jac(2, :) = y(1)*dh + y(2)*dg
    jac(1, 1) = jac(1, 1) + g
    jac(1, 2) = jac(1, 2) - h
    jac(2, 1) = jac(2, 1) + h
    jac(2, 2) = jac(2, 2) + g
  end subroutine polar_jacobian

  subroutine polar_parameter_derivative(self, t, y, df)
    class(polar_family), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: df(:)
    df = y(1:2)
  end subroutine polar_parameter_derivative

  subroutine polar_set_parameter(self, lambda)
    class(polar_family), intent(inout) :: self
    real(wp), intent(in) :: lambda
    self%mu = lambda
  end subroutine polar_set_parameter

  function polar_parameter(self) result(v)
    class(polar_family), intent(in) :: self
    real(wp) :: v
    v = self%mu
  end function polar_parameter
end module polar_family_system

program test_cycle_branch
  use sloshdyn_kinds, only: wp, message_len, pi
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT
  use sloshdyn_ode, only: ode_options
  use sloshdyn_integrator, only: METHOD_DOP853
  use sloshdyn_continuation, only: continuation_options, STOP_LAMBDA_MIN, STOP_LAMBDA_MAX
  use sloshdyn_cycle_branch, only: cycle_branch
  use sloshdyn_tables, only: SPECIAL_FOLD
  use polar_family_system, only: polar_family
  use checks, only: check_close, check_true, finish
  implicit none
  type(polar_family) :: family
  type(ode_options) :: ode
  type(continuation_options) :: options
  real(wp) :: points(5, 400), multipliers(4, 400), special(5, 10), r2, period, mu, worst(3)
  integer :: n_points, n_special, stop_reason, status, j, k
  character(len=message_len) :: message

  ode%rtol = 1.0e-12_wp
  ode%atol = 1.0e-14_wp
  options%ds = 0.02_wp
  options%ds_max = 0.05_wp
  options%max_points = 400

  ! supercritical Hopf: from mu = 0.25 down to 0.01, then up to 1
  do k = -1, 1, 2
    family = polar_family()
    options%direction = k
    call cycle_branch(family, [0.5_wp, 0.0_wp], 2*pi/(1 + 0.8_wp*0.25_wp), 1, 0.01_wp, 1.0_wp, &
                      options, ode, METHOD_DOP853, points, multipliers, n_points, special, &
                      n_special, stop_reason, status, message)
    call check_true('Hopf branch: status 0 ('//trim(message)//')', status == SD_OK)
    call check_true('Hopf branch ends on its bound', stop_reason == merge(STOP_LAMBDA_MIN, &
                    STOP_LAMBDA_MAX, k < 0))
    call check_true('Hopf branch: no special point', n_special == 0 .and. n_points > 5)
    worst = 0
    do j = 1, n_points
      mu = points(1, j)
      period = 2*pi/(1 + 0.8_wp*mu)
      worst(1) = max(worst(1), abs(hypot(points(2, j), points(3, j)) - sqrt(mu)))
      worst(2) = max(worst(2), abs(points(4, j)/period - 1))
      worst(3) = max(worst(3), abs(minval(hypot(multipliers(1:2, j), multipliers(3:4, j))) - &
                                   exp(-2*mu*period)))
      call check_true('Hopf branch: stable', points(5, j) == 1)
    end do
    call check_close('Hopf branch: radius sqrt(mu)', worst(1), 0.0_wp, 0.0_wp, 1.0e-9_wp)
    call check_close('Hopf branch: period 2 pi/(w + b mu)', worst(2), 0.0_wp, 0.0_wp, 1.0e-9_wp)
    call check_close('Hopf branch: multiplier exp(-2 mu T)', worst(3), 0.0_wp, 0.0_wp, 1.0e-8_wp)
    call check_close('Hopf branch: last mu', points(1, n_points), merge(0.01_wp, 1.0_wp, k < 0), &
                     1.0e-12_wp)
  end do

  ! fold of cycles at mu = -1, r^2 = 1: from the outer (stable) cycle at mu = -0.5 downwards,
  ! round the fold onto the inner (unstable) cycle, up to mu = -0.2
  family = polar_family(mu=-0.5_wp, a=2, c=1)
  r2 = 1 + sqrt(0.5_wp)
  options%direction = -1
  call cycle_branch(family, [sqrt(r2), 0.0_wp], 2*pi/(1 + 0.8_wp*r2), 1, -2.0_wp, -0.2_wp, &
                    options, ode, METHOD_DOP853, points, multipliers, n_points, special, &
                    n_special, stop_reason, status, message)
  call check_true('fold branch: status 0 ('//trim(message)//')', status == SD_OK)
  call check_true('fold branch: one fold found', n_special == 1)
  if (n_special == 1) then
    call check_true('fold branch: kind fold', nint(special(1, 1)) == SPECIAL_FOLD)
    call check_close('fold branch: fold at mu = -1', special(2, 1), -1.0_wp, 0.0_wp, 1.0e-8_wp)
    call check_close('fold branch: fold radius 1', hypot(special(3, 1), special(4, 1)), 1.0_wp, &
                     1.0e-7_wp)
    call check_close('fold branch: fold period 2 pi/(w + b)', special(5, 1), 2*pi/1.8_wp, &
                     1.0e-7_wp)
  end if
  call check_true('fold branch: ends at mu = -0.2 on the inner cycle', &
                  stop_reason == STOP_LAMBDA_MAX .and. &
                  abs(hypot(points(2, n_points), points(3, n_points))**2 - &
                      (1 - sqrt(0.8_wp))) < 1.0e-9_wp)
  call check_true('fold branch: outer stable, inner unstable', points(5, 1) == 1 .and. &
                  points(5, n_points) == 0)

  ! bad input
  call cycle_branch(family, [1.0_wp, 0.0_wp], -1.0_wp, 1, -2.0_wp, -0.2_wp, options, ode, &
                    METHOD_DOP853, points, multipliers, n_points, special, n_special, &
                    stop_reason, status, message)
  call check_true('a negative period is refused, named', status == SD_BAD_INPUT .and. &
                  index(message, 'period') > 0)
  call finish()
end program test_cycle_branch
