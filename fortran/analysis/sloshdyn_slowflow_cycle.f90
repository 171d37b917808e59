!> The beat of the full motion beyond a Hopf point of the 3:1 slow flow (sec 4.2, Fig 13-14):
!> the slow flow's limit cycle and its period. Near the Hopf points the slow amplitudes B1, B2
!> (eq 42, 45) oscillate with that period, and u1 ~ Re(B1 exp(i rho tau)) beats with it.
!> The cycle is reached by integrating the slow flow from rest (B = 0) for settle_time, its
!> period guessed by the first return to the section through the state reached, and both
!> refined by Newton shooting with the period unknown (sloshdyn_limit_cycle). Times in tau.
!> Outside the Hopf interval there is no cycle: the slow flow settles to an equilibrium, and
!> slow_flow_cycle says so (SD_NOT_CONVERGED, "no limit cycle at rho = ..., A = ...").
module sloshdyn_slowflow_cycle
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, SD_NOT_CONVERGED, check_real
  use sloshdyn_text, only: num2str
  use sloshdyn_model, only: model_t
  use sloshdyn_ode, only: ode_options, ode_stats
  use sloshdyn_integrator, only: integrate
  use sloshdyn_limit_cycle, only: autonomous_system, return_time, cycle_newton
  use sloshdyn_slowflow_chart, only: slow_flow_field, make_slow_flow_field, CHART_RHO, CHART_A
  implicit none
  private
  public :: slow_flow_cycle, frozen_slow_flow

  !> Newton's tolerance (relative, on the state and the period) and its shots at most.
  real(wp), parameter :: cycle_tol = 1.0e-10_wp
  integer, parameter :: cycle_max_iter = 30
  !> The settled state is an equilibrium when the flow's rate there is below this fraction of
  !> its rate at rest (B = 0, where only the forcing drives it).
  real(wp), parameter :: equilibrium_tol = 1.0e-8_wp

  !> A slow flow at fixed parameters p (those of its field, e.g. rho and A), as an autonomous
  !> system (also the stability chart's brute-force integrations).
  type, extends(autonomous_system) :: frozen_slow_flow
    type(slow_flow_field) :: field
    real(wp) :: p(2) = 0
  contains
    procedure :: rhs => frozen_rhs
    procedure :: jacobian => frozen_jacobian
  end type frozen_slow_flow

contains

  !> The limit cycle of the 3:1 slow flow at the model's rho and A: x_cycle = (Re B1, Im B1,
  !> Re B2, Im B2) on it, its period [tau], the Floquet multipliers of the cycle (one is 1)
  !> and the Newton shots. settle_time: the integration from rest before the cycle is sought;
  !> max_period: the longest period searched for, on n_samples output samples.
  subroutine slow_flow_cycle(model, settle_time, max_period, n_samples, options, method, &
                             x_cycle, period, multipliers_re, multipliers_im, iterations, &
                             status, message)
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: settle_time, max_period
    integer, intent(in) :: n_samples, method
    type(ode_options), intent(in) :: options
    real(wp), intent(out) :: x_cycle(4), period, multipliers_re(4), multipliers_im(4)
    integer, intent(out) :: iterations, status
    character(len=message_len), intent(out) :: message
    type(frozen_slow_flow) :: flow
    type(ode_stats) :: stats
    real(wp) :: settled(4, 1), guess, rate(4), rate_at_rest(4)

    x_cycle = ieee_value(1.0_wp, ieee_quiet_nan)
    period = ieee_value(1.0_wp, ieee_quiet_nan)
    multipliers_re = ieee_value(1.0_wp, ieee_quiet_nan)
    multipliers_im = ieee_value(1.0_wp, ieee_quiet_nan)
    iterations = 0
    status = SD_OK
    message = ''
    call check_real('settle_time', settle_time, 0.0_wp, huge(1.0_wp), .false., .true., &
                    'the integration before the cycle is sought, in tau', status, message)
    call check_real('max_period', max_period, 0.0_wp, huge(1.0_wp), .true., .true., &
                    'the longest period searched for, in tau', status, message)
    call check_real('rho', model%excitation%rho, 0.0_wp, huge(1.0_wp), .true., .true., &
                    'the slow flow needs a forcing frequency rho > 0', status, message)
    if (status /= SD_OK) return
    call make_slow_flow_field(model, .true., [CHART_RHO, CHART_A], flow%field, status, message)
    if (status /= SD_OK) return
    flow%p = [model%excitation%rho, model%excitation%A]
    settled(:, 1) = 0
    if (settle_time > 0) then
      call integrate(method, flow, 0.0_wp, [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], [settle_time], &
                     settled, options, stats, status, message)
      if (status /= SD_OK) return
    end if
    ! a slow flow that settles to an equilibrium has no cycle here (outside the Hopf interval)
    call flow%rhs(0.0_wp, [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], rate_at_rest)
    call flow%rhs(0.0_wp, settled(:, 1), rate)
    if (norm2(rate) <= equilibrium_tol*norm2(rate_at_rest)) then
      status = SD_NOT_CONVERGED
      message = 'no limit cycle at '//at_point()//': the slow flow settles to an equilibrium '// &
                '(|B1| = '//num2str(norm2(settled(1:2, 1)))//', |B2| = '// &
                num2str(norm2(settled(3:4, 1)))//' after tau = '//num2str(settle_time)// &
                '); a cycle exists only between the Hopf points'
      return
    end if
    call return_time(flow, settled(:, 1), max_period, n_samples, options, method, guess, &
                     status, message)
    if (status == SD_OK) call cycle_newton(flow, settled(:, 1), guess, options, method, &
                                           cycle_tol, cycle_max_iter, x_cycle, period, &
                                           multipliers_re, multipliers_im, iterations, status, &
                                           message)
    if (status == SD_OK .and. .not. period > 0) status = SD_NOT_CONVERGED
    ! the shooting failed or its period left (0, infinity): say so, not its internal values
    if (status == SD_NOT_CONVERGED .or. status == SD_BAD_INPUT) then
      status = SD_NOT_CONVERGED
      message = 'no limit cycle found at '//at_point()//': the shooting from the state reached '// &
                'after tau = '//num2str(settle_time)//' did not converge to a closed orbit '// &
                'of period <= max_period = '//num2str(max_period)//' (outside the Hopf '// &
                'interval the slow flow settles to an equilibrium)'
    end if

  contains

    pure function at_point() result(text)
      character(len=:), allocatable :: text
      text = 'rho = '//num2str(model%excitation%rho)//', A = '//num2str(model%excitation%A)
    end function at_point
  end subroutine slow_flow_cycle

  subroutine frozen_rhs(self, t, y, dydt)
    class(frozen_slow_flow), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: dydt(:)
    real(wp) :: fx(size(y), size(y)), fp(size(y), 2)
    call self%field%evaluate(y, self%p, dydt, fx, fp)
    if (t < 0) dydt = 0      ! autonomous: t unused
  end subroutine frozen_rhs

  subroutine frozen_jacobian(self, y, jac)
    class(frozen_slow_flow), intent(in) :: self
    real(wp), intent(in) :: y(:)
    real(wp), intent(out) :: jac(:, :)
    real(wp) :: f(size(y)), fp(size(y), 2)
    call self%field%evaluate(y, self%p, f, jac, fp)
  end subroutine frozen_jacobian
end module sloshdyn_slowflow_cycle
