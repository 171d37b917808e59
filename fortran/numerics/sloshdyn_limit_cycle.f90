!> Limit cycles of an autonomous system y' = f(y): the period is an unknown. Generic: the system
!> comes through the autonomous_system interface (f and its Jacobian).
!>
!> return_time: a first guess by integration -- from y_s, the first time the trajectory crosses
!> the hyperplane through y_s normal to f(y_s) in the flow's direction again, interpolated
!> linearly between output samples.
!> cycle_newton: single shooting with the period unknown (Keller's bordered system), Newton on
!>   G(y0, T) = [y(T; y0) - y0 ; f(y_s).(y0 - y_s)] = 0
!> with the exact Jacobian [[M - I, f(y(T))], [f(y_s)^T, 0]], M = dy(T)/dy0 the monodromy
!> matrix integrated with the orbit (variational equations, the same integrator). The phase
!> condition keeps y0 on the hyperplane through y_s, so the orbit is isolated and the bordered
!> matrix regular while the cycle is hyperbolic. The multipliers are the eigenvalues of M
!> (dgeev); one of them is +1 (the flow direction), to the accuracy of the orbit.
module sloshdyn_limit_cycle
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, SD_NOT_CONVERGED
  use sloshdyn_text, only: num2str
  use sloshdyn_lapack, only: eigenvalues, solve_linear
  use sloshdyn_ode, only: ode_system, ode_options, ode_stats
  use sloshdyn_integrator, only: integrate
  implicit none
  private
  public :: autonomous_system, autonomous_jacobian, return_time, cycle_newton

  !> An autonomous system y' = f(y) (rhs, t unused) with its Jacobian df/dy.
  type, abstract, extends(ode_system) :: autonomous_system
  contains
    procedure(autonomous_jacobian), deferred :: jacobian
  end type autonomous_system

  abstract interface
    subroutine autonomous_jacobian(self, y, jac)
      import :: wp, autonomous_system
      class(autonomous_system), intent(in) :: self
      real(wp), intent(in) :: y(:)
      real(wp), intent(out) :: jac(:, :)
    end subroutine autonomous_jacobian
  end interface

  !> The system with its variational equations: z = [y, vec(Phi)], Phi' = J(y) Phi.
  type, extends(ode_system) :: variational
    class(autonomous_system), allocatable :: system
    integer :: n = 0
  contains
    procedure :: rhs => variational_rhs
  end type variational

contains

  !> The first return time of the trajectory from y_s to the hyperplane through y_s normal to
  !> f(y_s), crossed in the flow's direction, searched up to t_max on n_samples equal steps
  !> (the crossing interpolated linearly between samples). A crossing counts only after the
  !> trajectory has left the hyperplane's side it started on (distance from y_s first grows).
  !> SD_NOT_CONVERGED if none is found by t_max.
  subroutine return_time(system, y_s, t_max, n_samples, options, method, period, status, message)
    class(autonomous_system), intent(in) :: system
    real(wp), intent(in) :: y_s(:), t_max
    integer, intent(in) :: n_samples, method
    type(ode_options), intent(in) :: options
    real(wp), intent(out) :: period
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: normal(size(y_s)), t_out(n_samples), y_out(size(y_s), n_samples), s(0:n_samples)
    type(ode_stats) :: stats
    integer :: k

    period = ieee_value(1.0_wp, ieee_quiet_nan)
    if (.not. (t_max > 0) .or. n_samples < 2) then
      status = SD_BAD_INPUT
      message = 'return_time: t_max = '//num2str(t_max)//' must be > 0 and n_samples = '// &
                num2str(n_samples)//' >= 2'
      return
    end if
    call system%rhs(0.0_wp, y_s, normal)
    t_out = [(t_max*k/n_samples, k = 1, n_samples)]
    call integrate(method, system, 0.0_wp, y_s, t_out, y_out, options, stats, status, message)
    if (status /= SD_OK) return
    s(0) = 0
    s(1:) = matmul(normal, y_out - spread(y_s, 2, n_samples))
    ! leave the start (s > 0 first: the flow points along normal), then cross from s < 0 to >= 0
    do k = 2, n_samples
      if (s(k - 1) < 0 .and. s(k) >= 0 .and. any(s(1:k - 1) > 0)) then
        period = t_out(k - 1) + (t_out(k) - t_out(k - 1))*(-s(k - 1))/(s(k) - s(k - 1))
        return
      end if
    end do
    status = SD_NOT_CONVERGED
    message = 'return_time: the trajectory did not return to its start section within t = '// &
              num2str(t_max)
  end subroutine return_time

  !> Newton on the bordered shooting system of the module header, from the guess (y0, period)
  !> with the phase condition's section through y0. Converged when the step in y0 is <=
  !> tol (max|y0| + 1e-12) and the step in T <= tol T. On return y_cycle, period are the last
  !> iterate plus its step, multipliers_re/_im those of the last shot (sorted as dgeev gives
  !> them), iterations the shots done. SD_NOT_CONVERGED after max_iter shots.
  subroutine cycle_newton(system, y0, period_guess, options, method, tol, max_iter, y_cycle, &
                          period, multipliers_re, multipliers_im, iterations, status, message)
    class(autonomous_system), intent(in) :: system
    real(wp), intent(in) :: y0(:), period_guess, tol
    integer, intent(in) :: method, max_iter
    type(ode_options), intent(in) :: options
    real(wp), intent(out) :: y_cycle(:), period, multipliers_re(:), multipliers_im(:)
    integer, intent(out) :: iterations, status
    character(len=message_len), intent(out) :: message
    type(variational) :: var
    type(ode_stats) :: stats
    real(wp) :: normal(size(y0)), z(size(y0)*(size(y0) + 1)), z_end(size(z), 1), &
                bordered(size(y0) + 1, size(y0) + 1), step(size(y0) + 1), f_end(size(y0)), &
                y(size(y0)), monodromy(size(y0), size(y0)), t
    integer :: n

    n = size(y0)
    y_cycle = ieee_value(1.0_wp, ieee_quiet_nan)
    period = ieee_value(1.0_wp, ieee_quiet_nan)
    multipliers_re = ieee_value(1.0_wp, ieee_quiet_nan)
    multipliers_im = ieee_value(1.0_wp, ieee_quiet_nan)
    iterations = 0
    if (size(y_cycle) /= n .or. size(multipliers_re) /= n .or. size(multipliers_im) /= n .or. &
        .not. (period_guess > 0) .or. .not. (tol > 0) .or. max_iter < 1) then
      status = SD_BAD_INPUT
      message = 'cycle_newton: y_cycle and the multipliers need size(y0) = '//num2str(n)// &
                ' values; period_guess = '//num2str(period_guess)//' and tol = '// &
                num2str(tol)//' must be > 0, max_iter = '//num2str(max_iter)//' >= 1'
      return
    end if
    allocate (var%system, source=system)
    var%n = n
    call system%rhs(0.0_wp, y0, normal)
    y = y0
    t = period_guess
    do iterations = 1, max_iter
      z(1:n) = y
      z(n + 1:) = reshape(identity(n), [n*n])
      call integrate(method, var, 0.0_wp, z, [t], z_end, options, stats, status, message)
      if (status /= SD_OK) return
      monodromy = reshape(z_end(n + 1:, 1), [n, n])
      call system%rhs(0.0_wp, z_end(1:n, 1), f_end)
      bordered = 0
      bordered(1:n, 1:n) = monodromy - identity(n)
      bordered(1:n, n + 1) = f_end
      bordered(n + 1, 1:n) = normal
      step(1:n) = -(z_end(1:n, 1) - y)
      step(n + 1) = -dot_product(normal, y - y0)
      call solve_linear(bordered, step, status, message)
      if (status /= SD_OK) return
      y = y + step(1:n)
      t = t + step(n + 1)
      if (maxval(abs(step(1:n))) <= tol*(maxval(abs(y)) + 1.0e-12_wp) .and. &
          abs(step(n + 1)) <= tol*abs(t)) then
        y_cycle = y
        period = t
        call eigenvalues(monodromy, multipliers_re, multipliers_im, status, message)
        return
      end if
    end do
    iterations = max_iter
    status = SD_NOT_CONVERGED
    message = 'cycle_newton: no convergence in '//num2str(max_iter)//' shots (last period '// &
              num2str(t)//')'
    y_cycle = y       ! the last iterate, for a caller that wants to look
    period = t
  end subroutine cycle_newton

  pure function identity(n) result(a)
    integer, intent(in) :: n
    real(wp) :: a(n, n)
    integer :: i
    a = 0
    do i = 1, n
      a(i, i) = 1
    end do
  end function identity

  subroutine variational_rhs(self, t, y, dydt)
    class(variational), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: dydt(:)
    real(wp) :: jac(self%n, self%n)
    integer :: n
    n = self%n
    call self%system%rhs(t, y(1:n), dydt(1:n))
    call self%system%jacobian(y(1:n), jac)
    dydt(n + 1:) = reshape(matmul(jac, reshape(y(n + 1:), [n, n])), [n*n])
  end subroutine variational_rhs
end module sloshdyn_limit_cycle
