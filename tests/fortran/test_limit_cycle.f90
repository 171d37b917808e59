!> Limit cycles of an autonomous system (sloshdyn_limit_cycle) against the Hopf normal form in
!> Cartesian coordinates, whose cycle is known in closed form:
!>   x' = mu x - w y - (x^2 + y^2)(x + b y),  y' = w x + mu y - (x^2 + y^2)(y - b x)
!> has the circle r = sqrt(mu), turned at the angular speed w + b mu: period 2 pi/(w + b mu),
!> multipliers 1 and exp(-2 mu T) (the radial decay r' = r (mu - r^2) linearised at r^2 = mu).
module normal_form_system
  use sloshdyn_kinds, only: wp
  use sloshdyn_limit_cycle, only: autonomous_system
  implicit none
  private
  public :: normal_form

  type, extends(autonomous_system) :: normal_form
    real(wp) :: mu = 0.25_wp, w = 1, b = 0.8_wp
  contains
    procedure :: rhs => normal_form_rhs
    procedure :: jacobian => normal_form_jacobian
  end type normal_form

contains

  subroutine normal_form_rhs(self, t, y, dydt)
    class(normal_form), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: dydt(:)
    real(wp) :: r2
    r2 = y(1)**2 + y(2)**2
    dydt(1) = self%mu*y(1) - self%w*y(2) - r2*(y(1) + self%b*y(2))
    dydt(2) = self%w*y(1) + self%mu*y(2) - r2*(y(2) - self%b*y(1))
    if (t < 0) dydt = 0      ! autonomous: t unused
  end subroutine normal_form_rhs

  subroutine normal_form_jacobian(self, y, jac)
    class(normal_form), intent(in) :: self
    real(wp), intent(in) :: y(:)
    real(wp), intent(out) :: jac(:, :)
    real(wp) :: r2, x, z
    x = y(1)
    z = y(2)
    r2 = x**2 + z**2
    jac(1, 1) = self%mu - r2 - 2*x*(x + self%b*z)
    jac(1, 2) = -self%w - r2*self%b - 2*z*(x + self%b*z)
    jac(2, 1) = self%w + r2*self%b - 2*x*(z - self%b*x)
    jac(2, 2) = self%mu - r2 - 2*z*(z - self%b*x)
  end subroutine normal_form_jacobian
end module normal_form_system

program test_limit_cycle
  use sloshdyn_kinds, only: wp, message_len, pi
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, SD_NOT_CONVERGED
  use sloshdyn_ode, only: ode_options
  use sloshdyn_integrator, only: METHOD_DOPRI5, METHOD_DOP853
  use sloshdyn_limit_cycle, only: return_time, cycle_newton
  use normal_form_system, only: normal_form
  use checks, only: check_close, check_true, finish
  implicit none
  type(normal_form) :: system
  type(ode_options) :: options
  real(wp) :: period, guess, y(2), re(2), im(2), exact, radius
  integer :: iterations, status, method
  character(len=message_len) :: message

  options%rtol = 1.0e-11_wp
  options%atol = 1.0e-13_wp
  exact = 2*pi/(system%w + system%b*system%mu)
  do method = METHOD_DOPRI5, METHOD_DOP853
    ! from a point off the cycle: the first return is near the period, Newton lands on it
    call return_time(system, [0.3_wp, 0.1_wp], 3*exact, 3000, options, method, guess, status, &
                     message)
    call check_true('return time found: '//trim(message), status == SD_OK)
    call check_close('first return near the period', guess, exact, 0.2_wp)
    call cycle_newton(system, [0.3_wp, 0.1_wp], guess, options, method, 1.0e-10_wp, 30, y, &
                      period, re, im, iterations, status, message)
    call check_true('Newton converges: '//trim(message), status == SD_OK)
    call check_close('period 2 pi/(w + b mu)', period, exact, 1.0e-9_wp)
    radius = hypot(y(1), y(2))
    call check_close('on the circle r = sqrt(mu)', radius, sqrt(system%mu), 1.0e-9_wp)
    call check_close('phase condition: on the section through the start', &
                     (y(1) - 0.3_wp)*(system%mu*0.3_wp - system%w*0.1_wp - 0.1_wp*(0.3_wp + &
                     system%b*0.1_wp)) + (y(2) - 0.1_wp)*(system%w*0.3_wp + system%mu*0.1_wp - &
                     0.1_wp*(0.1_wp - system%b*0.3_wp)), 0.0_wp, 0.0_wp, 1.0e-10_wp)
    call check_close('multiplier 1 (along the flow)', maxval(re), 1.0_wp, 1.0e-8_wp)
    call check_close('multiplier exp(-2 mu T) (radial)', minval(re), exp(-2*system%mu*exact), &
                     1.0e-7_wp)
    call check_true('multipliers real', maxval(abs(im)) == 0)
  end do
  ! a trajectory that never returns, and bad input, are reported
  system%mu = -0.25_wp          ! with w = b = 0 a radial flow into the origin: never returns
  system%w = 0
  system%b = 0
  call return_time(system, [0.3_wp, 0.1_wp], 10.0_wp, 100, options, METHOD_DOP853, guess, &
                   status, message)
  call check_true('no return: SD_NOT_CONVERGED: '//trim(message), status == SD_NOT_CONVERGED)
  call return_time(system, [0.3_wp, 0.1_wp], -1.0_wp, 100, options, METHOD_DOP853, guess, &
                   status, message)
  call check_true('t_max < 0 named: '//trim(message), status == SD_BAD_INPUT .and. &
                  index(message, 't_max') > 0)
  call cycle_newton(system, [0.3_wp, 0.1_wp], 0.0_wp, options, METHOD_DOP853, 1.0e-10_wp, 30, &
                    y, period, re, im, iterations, status, message)
  call check_true('period_guess = 0 named: '//trim(message), status == SD_BAD_INPUT .and. &
                  index(message, 'period_guess') > 0)
  call finish()
end program test_limit_cycle
