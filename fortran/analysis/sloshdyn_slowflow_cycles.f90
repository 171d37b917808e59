!> The beats continued: the limit cycles of the 3:1 slow flow (eq 53 in Cartesian form, x =
!> (Re B1, Im B1, Re B2, Im B2)) followed in rho or A from a cycle found at one point
!> (sloshdyn_slowflow_cycle), with their period, Floquet multipliers, folds of cycles, period
!> doublings and Neimark-Sacker points (a torus of the slow flow: a 3-frequency motion of the
!> full model), by the generic cycle continuation of sloshdyn_cycle_branch. Times in tau.
module sloshdyn_slowflow_cycles
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT
  use sloshdyn_text, only: num2str
  use sloshdyn_model, only: model_t
  use sloshdyn_ode, only: ode_options, ode_stats
  use sloshdyn_integrator, only: integrate
  use sloshdyn_continuation, only: continuation_options
  use sloshdyn_cycle_branch, only: autonomous_family, cycle_branch
  use sloshdyn_slowflow_chart, only: slow_flow_field, make_slow_flow_field, CHART_RHO, CHART_A
  use sloshdyn_excitation, only: PARAMETER_RHO, PARAMETER_A
  implicit none
  private
  public :: slow_flow_cycle_branch, cycle_amplitudes

  !> Samples per cycle for the phase of the start and the amplitude ranges.
  integer, parameter :: cycle_samples = 512

  !> The slow flow at (rho, A) = p, lambda = p(varied), as an autonomous family.
  type, extends(autonomous_family) :: slow_flow_family
    type(slow_flow_field) :: field
    real(wp) :: p(2) = 0
    integer :: varied = 1        !< 1: rho, 2: A (the field's parameter order)
  contains
    procedure :: rhs => family_rhs
    procedure :: jacobian => family_jacobian
    procedure :: parameter_derivative => family_parameter_derivative
    procedure :: set_parameter => family_set_parameter
    procedure :: parameter => family_parameter
    procedure :: state_size => family_state_size
  end type slow_flow_family

contains

  !> The branch of slow-flow cycles through the cycle (x_cycle, period) at the model's rho and A,
  !> in rho or A (parameter = PARAMETER_RHO, PARAMETER_A) over [lambda_min, lambda_max] in the
  !> direction of continuation%direction: the start is first moved along the cycle to the
  !> maximum of Re B1 (the phase condition). Layouts of sloshdyn_cycle_branch (n = 4);
  !> amplitudes(:, j) = those of cycle_amplitudes at point j.
  subroutine slow_flow_cycle_branch(model, parameter, x_cycle, period, lambda_min, lambda_max, &
                                    continuation, options, method, points, multipliers, &
                                    amplitudes, n_points, special, n_special, stop_reason, &
                                    status, message)
    type(model_t), intent(in) :: model
    integer, intent(in) :: parameter, method
    real(wp), intent(in) :: x_cycle(4), period, lambda_min, lambda_max
    type(continuation_options), intent(in) :: continuation
    type(ode_options), intent(in) :: options
    real(wp), intent(out) :: points(:, :), multipliers(:, :), amplitudes(:, :), special(:, :)
    integer, intent(out) :: n_points, n_special, stop_reason, status
    character(len=message_len), intent(out) :: message
    type(slow_flow_family) :: family
    type(model_t) :: at_point
    real(wp) :: samples(4, cycle_samples)
    integer :: j, point_status
    character(len=message_len) :: point_message

    n_points = 0
    n_special = 0
    stop_reason = 0
    call make_family(model, parameter, family, status, message)
    if (status /= SD_OK) return
    call sample_cycle(family, x_cycle, period, options, method, samples, status, message)
    if (status /= SD_OK) return
    call cycle_branch(family, samples(:, maxloc(samples(1, :), 1)), period, 1, lambda_min, &
                      lambda_max, continuation, options, method, points, multipliers, n_points, &
                      special, n_special, stop_reason, status, message)
    amplitudes = 0
    at_point = model
    do j = 1, n_points
      if (parameter == PARAMETER_RHO) then
        at_point%excitation%rho = points(1, j)
      else
        at_point%excitation%A = points(1, j)
      end if
      call cycle_amplitudes(at_point, points(2:5, j), points(6, j), options, method, &
                            amplitudes(:, j), point_status, point_message)
      if (point_status /= SD_OK .and. status == SD_OK) then
        status = point_status
        message = 'amplitudes of branch point '//num2str(j)//': '//trim(point_message)
      end if
    end do
  end subroutine slow_flow_cycle_branch

  !> min and max of |B1| and |B2| over the cycle through x at the model's (rho, A):
  !> amplitudes = [min|B1|, max|B1|, min|B2|, max|B2|] (the beat's envelope), sampled.
  subroutine cycle_amplitudes(model, x, period, options, method, amplitudes, status, message)
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: x(4), period
    type(ode_options), intent(in) :: options
    integer, intent(in) :: method
    real(wp), intent(out) :: amplitudes(4)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(slow_flow_family) :: family
    real(wp) :: samples(4, cycle_samples), b1(cycle_samples), b2(cycle_samples)
    amplitudes = 0
    call make_family(model, PARAMETER_RHO, family, status, message)
    if (status == SD_OK) call sample_cycle(family, x, period, options, method, samples, status, &
                                           message)
    if (status /= SD_OK) return
    b1 = hypot(samples(1, :), samples(2, :))
    b2 = hypot(samples(3, :), samples(4, :))
    amplitudes = [minval(b1), maxval(b1), minval(b2), maxval(b2)]
  end subroutine cycle_amplitudes

  subroutine make_family(model, parameter, family, status, message)
    type(model_t), intent(in) :: model
    integer, intent(in) :: parameter
    type(slow_flow_family), intent(out) :: family
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    status = SD_OK
    message = ''
    if (parameter /= PARAMETER_RHO .and. parameter /= PARAMETER_A) then
      status = SD_BAD_INPUT
      message = 'parameter = '//num2str(parameter)//' is out of range: it must be rho ('// &
                num2str(PARAMETER_RHO)//') or A ('//num2str(PARAMETER_A)//')'
      return
    end if
    call make_slow_flow_field(model, .true., [CHART_RHO, CHART_A], family%field, status, message)
    family%p = [model%excitation%rho, model%excitation%A]
    family%varied = merge(1, 2, parameter == PARAMETER_RHO)
  end subroutine make_family

  !> The cycle through x sampled at t = j period/cycle_samples, j = 0 .. cycle_samples - 1.
  subroutine sample_cycle(family, x, period, options, method, samples, status, message)
    type(slow_flow_family), intent(in) :: family
    real(wp), intent(in) :: x(4), period
    type(ode_options), intent(in) :: options
    integer, intent(in) :: method
    real(wp), intent(out) :: samples(:, :)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(ode_stats) :: stats
    integer :: j
    status = SD_OK
    message = ''
    if (.not. (period > 0 .and. period < huge(period))) then
      status = SD_BAD_INPUT
      message = 'the cycle period = '//num2str(period)//' is out of range: it must be finite '// &
                'and > 0'
      return
    end if
    samples(:, 1) = x
    call integrate(method, family, 0.0_wp, x, [(j*period/cycle_samples, j = 1, &
                   cycle_samples - 1)], samples(:, 2:), options, stats, status, message)
  end subroutine sample_cycle

  subroutine family_rhs(self, t, y, dydt)
    class(slow_flow_family), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: dydt(:)
    real(wp) :: fx(4, 4), fp(4, 2)
    call self%field%evaluate(y, self%p, dydt, fx, fp)
  end subroutine family_rhs

  subroutine family_jacobian(self, t, y, jac)
    class(slow_flow_family), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: jac(:, :)
    real(wp) :: f(4), fp(4, 2)
    call self%field%evaluate(y, self%p, f, jac, fp)
  end subroutine family_jacobian

  subroutine family_parameter_derivative(self, t, y, df)
    class(slow_flow_family), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: df(:)
    real(wp) :: f(4), fx(4, 4), fp(4, 2)
    call self%field%evaluate(y, self%p, f, fx, fp)
    df = fp(:, self%varied)
  end subroutine family_parameter_derivative

  subroutine family_set_parameter(self, lambda)
    class(slow_flow_family), intent(inout) :: self
    real(wp), intent(in) :: lambda
    self%p(self%varied) = lambda
  end subroutine family_set_parameter

  function family_parameter(self) result(v)
    class(slow_flow_family), intent(in) :: self
    real(wp) :: v
    v = self%p(self%varied)
  end function family_parameter

  integer function family_state_size(self)
    class(slow_flow_family), intent(in) :: self
    family_state_size = 4
  end function family_state_size
end module sloshdyn_slowflow_cycles
