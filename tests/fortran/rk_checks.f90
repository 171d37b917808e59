!> What the tests of the explicit Runge-Kutta methods share (test_rk45, test_dop853): test
!> systems with closed-form solutions (the independent source of the expected values; Van der
!> Pol has none and is checked method against method), the observed order of a sequence of
!> errors, and the checks every method must pass (stepwise use, failures, bad input), each
!> run with the method's code and a new integrator of that method.
module rk_checks
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_is_nan
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, SD_STEP_TOO_SMALL, SD_TOO_MANY_STEPS, &
                             SD_NON_FINITE
  use sloshdyn_text, only: num2str
  use sloshdyn_ode, only: ode_system, ode_options, ode_stats, rk_integrator, linear_observation, &
                         observed_quantities, peak_tracker
  use sloshdyn_integrator, only: integrate, new_integrator, method_name
  use checks, only: check_close, check_true
  implicit none
  private
  public :: riccati, oscillator, van_der_pol, nan_beyond
  public :: check_orders, fixed_step_errors, dense_output_errors, check_stepwise_api, &
            check_failures, check_bad_input, check_without_dense_output, check_replay

  !> y' = -a t y**2, y(0) = 1: y = 1/(1 + a t**2/2) (nonautonomous, nonlinear)
  type, extends(ode_system) :: riccati
    real(wp) :: a = 2
  contains
    procedure :: rhs => riccati_rhs
    procedure :: exact => riccati_exact
  end type riccati

  !> Forced linear oscillator y1' = y2, y2' = -omega**2 y1 + force cos(drive t), y(0) = (1, 0):
  !> y1 = cos(omega t) + force/(omega**2 - drive**2) (cos(drive t) - cos(omega t)), y2 = y1'
  type, extends(ode_system) :: oscillator
    real(wp) :: omega = 1, force = 0.5_wp, drive = 2
  contains
    procedure :: rhs => oscillator_rhs
    procedure :: exact => oscillator_exact
  end type oscillator

  !> g = (y1, y2) before t_switch, (2 y1, y2) from it on: quantities that equal (y1, y2) until
  !> a time (as a seismic run's loads with the confined mass equal the free ones until the
  !> first contact)
  type, extends(observed_quantities) :: switched_observation
    real(wp) :: t_switch = huge(1.0_wp)
  contains
    procedure :: values => switched_values
    procedure :: count => switched_count
  end type switched_observation

  !> Van der Pol y1' = y2, y2' = mu (1 - y1**2) y2 - y1 (no closed form)
  type, extends(ode_system) :: van_der_pol
    real(wp) :: mu = 2
  contains
    procedure :: rhs => van_der_pol_rhs
  end type van_der_pol

  !> y' = -y up to t = t_edge, NaN beyond: a right-hand side that leaves its domain
  type, extends(ode_system) :: nan_beyond
    real(wp) :: t_edge = 1
  contains
    procedure :: rhs => nan_beyond_rhs
  end type nan_beyond

contains

  subroutine riccati_rhs(self, t, y, dydt)
    class(riccati), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: dydt(:)
    dydt(1) = -self%a*t*y(1)**2
  end subroutine riccati_rhs

  pure real(wp) function riccati_exact(self, t) result(y)
    class(riccati), intent(in) :: self
    real(wp), intent(in) :: t
    y = 1/(1 + self%a*t**2/2)
  end function riccati_exact

  pure subroutine switched_values(self, t, y, g)
    class(switched_observation), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: g(:)
    g(1) = merge(2.0_wp, 1.0_wp, t >= self%t_switch)*y(1)
    g(2) = y(2)
  end subroutine switched_values

  pure integer function switched_count(self)
    class(switched_observation), intent(in) :: self
    switched_count = 2
  end function switched_count

  subroutine oscillator_rhs(self, t, y, dydt)
    class(oscillator), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: dydt(:)
    dydt(1) = y(2)
    dydt(2) = -self%omega**2*y(1) + self%force*cos(self%drive*t)
  end subroutine oscillator_rhs

  pure function oscillator_exact(self, t) result(y)
    class(oscillator), intent(in) :: self
    real(wp), intent(in) :: t
    real(wp) :: y(2)
    real(wp) :: c
    c = self%force/(self%omega**2 - self%drive**2)
    y(1) = cos(self%omega*t) + c*(cos(self%drive*t) - cos(self%omega*t))
    y(2) = -self%omega*sin(self%omega*t) + c*(-self%drive*sin(self%drive*t) + &
                                              self%omega*sin(self%omega*t))
  end function oscillator_exact

  subroutine van_der_pol_rhs(self, t, y, dydt)
    class(van_der_pol), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: dydt(:)
    dydt(1) = y(2)
    dydt(2) = self%mu*(1 - y(1)**2)*y(2) - y(1)
  end subroutine van_der_pol_rhs

  subroutine nan_beyond_rhs(self, t, y, dydt)
    class(nan_beyond), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: dydt(:)
    if (t <= self%t_edge) then
      dydt = -y
    else
      dydt = ieee_value(1.0_wp, ieee_quiet_nan)
    end if
  end subroutine nan_beyond_rhs

  !> Observed orders log2(e(h)/e(h/2)) of errors at h, h/2, h/4, ... must all be expected +- tol.
  subroutine check_orders(label, errors, expected, tol)
    character(len=*), intent(in) :: label
    real(wp), intent(in) :: errors(:), expected, tol
    real(wp) :: orders(size(errors) - 1)
    integer :: i

    orders = log(errors(:size(errors) - 1)/errors(2:))/log(2.0_wp)
    print '(2a, *(es10.2))', label, ': errors', errors
    print '(2a, *(f7.3))', label, ': orders', orders
    do i = 1, size(orders)
      call check_close(label//', halving '//num2str(i), orders(i), expected, 0.0_wp, tol)
    end do
  end subroutine check_orders

  !> Errors at the end of fixed-step runs of n, 2n, 4n, ... steps (n = ric_steps, osc_steps): the
  !> riccati problem to t = 1 and the forced oscillator to t = 10. One output at the end only,
  !> so no dense stages: stages evaluations per step + f(t0), and no step rejected.
  subroutine fixed_step_errors(method, name, ric_steps, osc_steps, stages, err_ric, err_osc)
    integer, intent(in) :: method, ric_steps, osc_steps, stages
    character(len=*), intent(in) :: name
    real(wp), intent(out) :: err_ric(0:), err_osc(0:)
    type(riccati) :: ric
    type(oscillator) :: osc
    type(ode_options) :: opt
    type(ode_stats) :: stats
    real(wp) :: y1(1, 1), y2(2, 1)
    integer :: i, status, n_steps
    character(len=message_len) :: message

    do i = 0, ubound(err_ric, 1)
      n_steps = ric_steps*2**i
      opt%fixed_step = 1.0_wp/n_steps
      call integrate(method, ric, 0.0_wp, [1.0_wp], [1.0_wp], y1, opt, stats, status, message)
      call check_true(name//', fixed steps on riccati: '//num2str(n_steps)//' steps, none '// &
                      'rejected', status == SD_OK .and. stats%n_accepted == n_steps .and. &
                      stats%n_rejected == 0)
      err_ric(i) = abs(y1(1, 1) - ric%exact(1.0_wp))

      n_steps = osc_steps*2**i
      opt%fixed_step = 10.0_wp/n_steps
      call integrate(method, osc, 0.0_wp, osc%exact(0.0_wp), [10.0_wp], y2, opt, stats, &
                     status, message)
      call check_true(name//', fixed steps on the oscillator: '//num2str(n_steps)//' steps', &
                      status == SD_OK .and. stats%n_accepted == n_steps)
      call check_true(name//' without dense output: n_rhs = '//num2str(stages)// &
                      ' per step + 1', stats%n_rhs == stages*n_steps + 1)
      err_osc(i) = maxval(abs(y2(:, 1) - osc%exact(10.0_wp)))
    end do
  end subroutine fixed_step_errors

  !> Errors of the dense output on the riccati problem with fixed steps h = h0/2**i, i = 0, 1,
  !> ...: err_local(i) at mid-step of one step from the exact y(t0), err_global(i) the largest
  !> at the mid-steps of a run over [0, t_end]. The interpolant must pass through both ends of
  !> the step, and a step with dense output costs stages new evaluations.
  subroutine dense_output_errors(method, t0, h0, t_end, stages, err_local, err_global)
    integer, intent(in) :: method, stages
    real(wp), intent(in) :: t0, h0, t_end
    real(wp), intent(out) :: err_local(0:), err_global(0:)
    class(rk_integrator), allocatable :: integ
    type(riccati) :: ric
    type(ode_options) :: opt
    real(wp) :: h, t_mid, y(1)
    integer :: i, status
    character(len=message_len) :: message

    call new_integrator(method, 0.0_wp, integ, status, message)
    do i = 0, ubound(err_local, 1)
      h = h0/2**i
      opt%fixed_step = h
      call integ%init(ric, t0, [ric%exact(t0)], t0 + h, opt, status, message)
      call integ%step(ric, status, message)
      call check_true('one fixed step, h = '//num2str(h), status == SD_OK .and. integ%t == t0 + h)
      call integ%dense(t0 + h/2, y)
      err_local(i) = abs(y(1) - ric%exact(t0 + h/2))
      ! the interpolant passes through both ends of the step
      call integ%dense(t0, y)
      call check_close('dense output at the step start, h = '//num2str(h), y(1), ric%exact(t0), &
                       0.0_wp, 1.0e-15_wp)
      call integ%dense(t0 + h, y)
      call check_close('dense output at the step end, h = '//num2str(h), y(1), integ%y(1), &
                       0.0_wp, 1.0e-15_wp)

      call integ%init(ric, 0.0_wp, [1.0_wp], t_end, opt, status, message)
      err_global(i) = 0
      do while (status == SD_OK .and. integ%t < integ%t_bound)
        call integ%step(ric, status, message)
        t_mid = (integ%t_old + integ%t)/2
        call integ%dense(t_mid, y)
        err_global(i) = max(err_global(i), abs(y(1) - ric%exact(t_mid)))
      end do
      call check_true('fixed steps over [0, '//num2str(t_end)//'] with dense output, h = '// &
                      num2str(h), status == SD_OK)
      call check_true(num2str(stages)//' new evaluations per step with dense output, h = '// &
                      num2str(h), integ%n_rhs == stages*integ%n_accepted + 1)
    end do
  end subroutine dense_output_errors

  !> Driving a new integrator of the method step by step, reading dense output and replacing
  !> the state; integrate with outputs at t0 and a repeated time.
  subroutine check_stepwise_api(method)
    integer, intent(in) :: method
    class(rk_integrator), allocatable :: integ
    character(len=:), allocatable :: name
    type(oscillator) :: osc
    type(ode_options) :: opt
    type(ode_stats) :: stats
    real(wp) :: y(2), t_mid, y_out(2, 4)
    integer :: status
    logical :: scaled
    character(len=message_len) :: message

    name = method_name(method)
    call new_integrator(method, 0.0_wp, integ, status, message)
    opt%rtol = 1.0e-10_wp
    opt%atol = 1.0e-12_wp
    ! unforced, so after doubling the state the exact solution is twice the old one
    osc%force = 0
    call integ%init(osc, 0.0_wp, osc%exact(0.0_wp), 3.0_wp, opt, status, message)
    call check_true(name//'_init succeeds', status == SD_OK)
    call integ%dense(0.5_wp, y)
    call check_close('dense output before any step returns y0', maxval(abs(y - [1, 0])), &
                     0.0_wp, 0.0_wp, 0.0_wp)
    scaled = .false.
    do while (status == SD_OK .and. integ%t < integ%t_bound)
      call integ%step(osc, status, message)
      if (.not. scaled .and. integ%t > 1) then
        t_mid = (integ%t_old + integ%t)/2
        call integ%dense(t_mid, y)
        call check_close('dense output inside a step', maxval(abs(y - osc%exact(t_mid))), &
                         0.0_wp, 0.0_wp, 1.0e-9_wp)
        call integ%set_state(osc, 2*integ%y, status, message)
        scaled = .true.
      end if
    end do
    call check_true('stepping reaches t_bound exactly', status == SD_OK .and. integ%t == 3.0_wp)
    call check_close(name//'_set_state: the state follows the doubled solution', &
                     maxval(abs(integ%y - 2*osc%exact(3.0_wp))), 0.0_wp, 0.0_wp, 1.0e-8_wp)
    stats = integ%statistics()
    call check_true(name//'_statistics copies the counters', stats%n_rhs == integ%n_rhs .and. &
                    stats%n_accepted == integ%n_accepted .and. &
                    stats%n_rejected == integ%n_rejected .and. stats%t_reached == 3.0_wp)
    call integ%step(osc, status, message)
    call check_true('a step past t_bound is refused: '//trim(message), status == SD_BAD_INPUT)
    call integ%set_state(osc, [1.0_wp], status, message)
    call check_true(name//'_set_state with the wrong size is refused: '//trim(message), &
                    status == SD_BAD_INPUT)

    call integrate(method, osc, 0.0_wp, osc%exact(0.0_wp), [0.0_wp, 0.5_wp, 0.5_wp, 2.0_wp], &
                   y_out, opt, stats, status, message)
    call check_true(name//'_integrate with outputs at t0 and a repeated time', status == SD_OK)
    call check_close('output at t0 is y0', maxval(abs(y_out(:, 1) - osc%exact(0.0_wp))), &
                     0.0_wp, 0.0_wp, 0.0_wp)
    call check_close('a repeated output time gives the same y', &
                     maxval(abs(y_out(:, 2) - y_out(:, 3))), 0.0_wp, 0.0_wp, 0.0_wp)
    call check_close('output at 0.5', maxval(abs(y_out(:, 3) - osc%exact(0.5_wp))), &
                     0.0_wp, 0.0_wp, 1.0e-9_wp)
    call check_close('output at 2', maxval(abs(y_out(:, 4) - osc%exact(2.0_wp))), &
                     0.0_wp, 0.0_wp, 1.0e-9_wp)
  end subroutine check_stepwise_api

  !> Without dense output (init's dense_output = .false.) only the step end is available: y
  !> there, NaN inside the step, the same for every method (sloshdyn_ode's rk_init).
  subroutine check_without_dense_output(method)
    integer, intent(in) :: method
    class(rk_integrator), allocatable :: integ
    character(len=:), allocatable :: name
    type(oscillator) :: osc
    type(ode_options) :: opt
    real(wp) :: y(2)
    integer :: status
    character(len=message_len) :: message

    name = method_name(method)
    call new_integrator(method, 0.0_wp, integ, status, message)
    opt%rtol = 1.0e-10_wp
    opt%atol = 1.0e-12_wp
    osc%force = 0
    call integ%init(osc, 0.0_wp, osc%exact(0.0_wp), 3.0_wp, opt, status, message, &
                    dense_output=.false.)
    call integ%step(osc, status, message)
    call integ%dense(integ%t, y)
    call check_true(name//', dense_output = .false.: y at the step end', all(y == integ%y))
    call integ%dense((integ%t_old + integ%t)/2, y)
    call check_true(name//', dense_output = .false.: NaN inside the step', all(ieee_is_nan(y)))
  end subroutine check_without_dense_output

  !> A run observed again from its recorded steps (peak_tracker's record_steps and replay)
  !> equals tracking the other quantities while integrating it again, bit for bit: the forced
  !> oscillator over [0, 20] (several dozen steps) recorded while tracking y1, then y2 and
  !> y1 + y2 with crossing levels, replayed against integrated again (peaks, their times and
  !> states, the crossings and the first of each); and the record holds every accepted step.
  subroutine check_replay(method)
    integer, intent(in) :: method
    type(oscillator) :: osc
    type(ode_options) :: opt
    type(ode_stats) :: stats
    type(linear_observation) :: first, other
    type(peak_tracker) :: recording, again, replayed
    character(len=:), allocatable :: name
    real(wp) :: y(2, 3), t_reached
    integer :: status, replay_status
    character(len=message_len) :: message, replay_message

    name = method_name(method)
    opt%rtol = 1.0e-9_wp
    opt%atol = 1.0e-11_wp
    first = linear_observation(reshape([1.0_wp, 0.0_wp], [1, 2]))
    other = linear_observation(reshape([0.0_wp, 1.0_wp, 1.0_wp, 1.0_wp], [2, 2]))
    recording%record_steps = .true.
    call integrate(method, osc, 0.0_wp, osc%exact(0.0_wp), [5.0_wp, 12.0_wp, 20.0_wp], y, opt, &
                   stats, status, message, first, recording)
    call check_true(name//', replay: the recorded run runs: '//trim(message), status == SD_OK)
    call check_true(name//', replay: '//num2str(recording%steps%n)//' steps recorded, one per '// &
                    'accepted step ('//num2str(stats%n_accepted)//')', &
                    recording%steps%n == stats%n_accepted .and. stats%n_accepted > 20)
    again%level = [0.5_wp, 1.2_wp]
    again%keep_states = .true.
    replayed%level = again%level
    replayed%keep_states = .true.
    call integrate(method, osc, 0.0_wp, osc%exact(0.0_wp), [5.0_wp, 12.0_wp, 20.0_wp], y, opt, &
                   stats, status, message, other, again)
    call replayed%replay(recording%steps, other, 0.0_wp, osc%exact(0.0_wp), 0.0_wp, 20.0_wp, &
                         replay_status, replay_message, t_reached)
    call check_true(name//', replay: runs to the run''s end, 20: '//trim(replay_message), &
                    replay_status == SD_OK .and. t_reached == 20)
    call check_true(name//', replay: the peaks, their times and states as integrating again', &
                    all(replayed%peak == again%peak) .and. all(replayed%time == again%time) &
                    .and. all(replayed%state == again%state))
    call check_true(name//', replay: the crossings ('//num2str(again%crossings(1))//', '// &
                    num2str(again%crossings(2))//') and the first of each as integrating again', &
                    all(replayed%crossings == again%crossings) .and. &
                    all(replayed%first_crossing == again%first_crossing) .and. &
                    all(again%crossings > 1))
    call replayed%replay(recording%steps, other, 0.0_wp, [1.0_wp], 0.0_wp, 20.0_wp, &
                         replay_status, replay_message)
    call check_true(name//', replay: a y0 of another size is refused: '//trim(replay_message), &
                    replay_status == SD_BAD_INPUT .and. index(replay_message, 'y0') > 0)
    call check_rewind(name, method, osc, opt)
  end subroutine check_replay

  !> A record that rewinds to checkpoints until |y1| first reaches 1.3 (near t = pi; |y1| <=
  !> 4/3), a checkpoint every 4 steps: replayed with quantities that equal (y1, y2) until that
  !> first crossing (switched_observation) from the latest checkpoint before it, the peaks,
  !> their times and states and the crossings are those of integrating again with these
  !> quantities -- |y2| first reaches 1 near t = 1.4, before the checkpoints of rk45 and
  !> dop853, whose state alone then carries it.
  subroutine check_rewind(name, method, osc, opt)
    character(len=*), intent(in) :: name
    integer, intent(in) :: method
    type(oscillator), intent(in) :: osc
    type(ode_options), intent(in) :: opt
    type(ode_stats) :: stats
    type(switched_observation) :: first, switched
    type(peak_tracker) :: recording, again, replayed
    real(wp) :: y(2, 1), t_reached
    integer :: status, replay_status
    character(len=message_len) :: message, replay_message

    recording%record_steps = .true.
    recording%rewind_quantity = 1
    recording%checkpoint_interval = 4
    recording%level = [1.3_wp, 1.0_wp]
    recording%keep_states = .true.
    call integrate(method, osc, 0.0_wp, osc%exact(0.0_wp), [20.0_wp], y, opt, stats, status, &
                   message, first, recording)
    call check_true(name//', rewind: the run runs and |y1| reaches 1.3 first at '// &
                    num2str(recording%first_crossing(1))//' (near pi)', status == SD_OK .and. &
                    abs(recording%first_crossing(1) - acos(-1.0_wp)) < 0.5_wp)
    call check_true(name//', rewind: '//num2str(recording%steps%dropped)//' steps dropped '// &
                    'before the older checkpoint, at '//num2str(recording%steps%checkpoint(1)%t)// &
                    '; the others kept ('//num2str(stats%n_accepted)//' in all)', &
                    recording%steps%dropped > 0 .and. &
                    recording%steps%checkpoint(1)%t < recording%first_crossing(1) .and. &
                    recording%steps%n + recording%steps%dropped == stats%n_accepted)
    switched%t_switch = recording%first_crossing(1)
    again%level = recording%level
    again%keep_states = .true.
    call integrate(method, osc, 0.0_wp, osc%exact(0.0_wp), [20.0_wp], y, opt, stats, status, &
                   message, switched, again)
    replayed%level = recording%level
    replayed%keep_states = .true.
    call replayed%replay(recording%steps, switched, 0.0_wp, osc%exact(0.0_wp), 0.0_wp, 20.0_wp, &
                         replay_status, replay_message, t_reached, before=switched%t_switch)
    call check_true(name//', rewind: the replay from a checkpoint runs to 20: '// &
                    trim(replay_message), replay_status == SD_OK .and. t_reached == 20)
    call check_true(name//', rewind: its peak ('//num2str(replayed%peak(1))//' at '// &
                    num2str(replayed%time(1))//', after the switch), state, crossings and '// &
                    'first crossing as integrating again', &
                    all(replayed%peak == again%peak) .and. all(replayed%time == again%time) .and. &
                    all(replayed%state == again%state) .and. &
                    all(replayed%crossings == again%crossings) .and. &
                    all(replayed%first_crossing == again%first_crossing) .and. &
                    again%time(1) > switched%t_switch .and. again%crossings(2) > 1)
    ! quantities that change at the newer checkpoint itself: the older one must be taken
    switched%t_switch = recording%steps%checkpoint(2)%t
    call integrate(method, osc, 0.0_wp, osc%exact(0.0_wp), [20.0_wp], y, opt, stats, status, &
                   message, switched, again)
    call replayed%replay(recording%steps, switched, 0.0_wp, osc%exact(0.0_wp), 0.0_wp, 20.0_wp, &
                         replay_status, replay_message, before=switched%t_switch)
    call check_true(name//', rewind: quantities changing at the newer checkpoint ('// &
                    num2str(switched%t_switch)//'): replayed from the older one as '// &
                    'integrating again', replay_status == SD_OK .and. &
                    all(replayed%peak == again%peak) .and. all(replayed%time == again%time) .and. &
                    all(replayed%state == again%state) .and. &
                    all(replayed%crossings == again%crossings) .and. &
                    all(replayed%first_crossing == again%first_crossing))
    call replayed%replay(recording%steps, switched, 0.0_wp, osc%exact(0.0_wp), 0.0_wp, 20.0_wp, &
                         replay_status, replay_message, before=0.0_wp)
    call check_true(name//', rewind: from the start, whose steps are dropped, refused: '// &
                    trim(replay_message), replay_status == SD_BAD_INPUT .and. &
                    index(replay_message, 'dropped') > 0)
    replayed%keep_states = .false.
    call replayed%replay(recording%steps, switched, 0.0_wp, osc%exact(0.0_wp), 0.0_wp, 20.0_wp, &
                         replay_status, replay_message, before=20.0_wp)
    call check_true(name//', rewind: a tracker without the states of the record''s '// &
                    'checkpoints refused: '//trim(replay_message), &
                    replay_status == SD_BAD_INPUT .and. index(replay_message, 'keep_states') > 0)
  end subroutine check_rewind

  !> Failures during the integration: partial output, NaN after, the time reached.
  subroutine check_failures(method)
    integer, intent(in) :: method
    type(oscillator) :: osc
    type(nan_beyond) :: nb
    type(riccati) :: ric
    type(ode_options) :: opt
    type(ode_stats) :: stats
    real(wp) :: t_out(1000), y_out(2, 1000), y_nb(1, 2)
    integer :: j, status
    logical :: partition_ok
    character(len=message_len) :: message

    ! outputs every 0.1 up to 100: ten steps end after a few of them
    t_out = [(0.1_wp*j, j = 1, size(t_out))]
    opt%max_steps = 10
    call integrate(method, osc, 0.0_wp, osc%exact(0.0_wp), t_out, y_out, opt, stats, status, &
                   message)
    print '(a)', '    message: '//trim(message)
    call check_true('max_steps = 10 gives SD_TOO_MANY_STEPS', status == SD_TOO_MANY_STEPS)
    call check_true('message names max_steps and tau', &
                    index(message, 'max_steps') > 0 .and. index(message, 'tau') > 0)
    call check_true('10 steps attempted', stats%n_accepted + stats%n_rejected == 10)
    call check_true('time reached '//num2str(stats%t_reached)//' lies past the first output', &
                    stats%t_reached > t_out(1) .and. stats%t_reached < t_out(size(t_out)))
    call check_close('first output before the failure', &
                     maxval(abs(y_out(:, 1) - osc%exact(t_out(1)))), 0.0_wp, 0.0_wp, 1.0e-8_wp)
    partition_ok = .true.
    do j = 1, size(t_out)
      if (t_out(j) <= stats%t_reached) then
        partition_ok = partition_ok .and. .not. any(ieee_is_nan(y_out(:, j)))
      else
        partition_ok = partition_ok .and. all(ieee_is_nan(y_out(:, j)))
      end if
    end do
    call check_true('outputs filled up to t_reached, NaN after', partition_ok)

    opt = ode_options()
    call integrate(method, nb, 0.0_wp, [1.0_wp], [0.5_wp, 2.0_wp], y_nb, opt, stats, status, &
                   message)
    print '(a)', '    message: '//trim(message)
    call check_true('NaN right-hand side gives SD_NON_FINITE', status == SD_NON_FINITE)
    call check_true('message names tau', index(message, 'tau') > 0)
    call check_close('output before the NaN region', y_nb(1, 1), exp(-0.5_wp), 1.0e-7_wp)
    call check_true('output in the NaN region is NaN', ieee_is_nan(y_nb(1, 2)))
    call check_close('integration stops at the edge t = 1', stats%t_reached, 1.0_wp, 0.0_wp, &
                     1.0e-6_wp)

    opt%fixed_step = 0.3_wp
    call integrate(method, nb, 0.0_wp, [1.0_wp], [0.5_wp, 2.0_wp], y_nb, opt, stats, status, &
                   message)
    call check_true('NaN in fixed-step mode gives SD_NON_FINITE', status == SD_NON_FINITE)
    call check_close('fixed steps stop at the last step before the edge', stats%t_reached, &
                     0.9_wp, 1.0e-14_wp)

    opt = ode_options(rtol=1.0e-10_wp, h_min=0.5_wp)
    call integrate(method, ric, 0.0_wp, [1.0_wp], [10.0_wp], y_nb(:, 1:1), opt, stats, status, &
                   message)
    print '(a)', '    message: '//trim(message)
    call check_true('h_min = 0.5 gives SD_STEP_TOO_SMALL', status == SD_STEP_TOO_SMALL)
    call check_true('message names h_min and tau', &
                    index(message, 'h_min') > 0 .and. index(message, 'tau') > 0)
  end subroutine check_failures

  !> Each rule on the inputs is reported with the name of the offending input.
  subroutine check_bad_input(method)
    integer, intent(in) :: method
    class(rk_integrator), allocatable :: integ
    character(len=:), allocatable :: name
    type(ode_options) :: opt
    type(riccati) :: ric
    integer :: status
    character(len=message_len) :: message

    name = method_name(method)
    call new_integrator(method, 0.0_wp, integ, status, message)
    opt%rtol = -1
    call expect_bad(method, opt, [0.5_wp, 1.0_wp], 'rtol')
    opt = ode_options(rtol=1.0e-17_wp)
    call expect_bad(method, opt, [0.5_wp, 1.0_wp], 'rtol')
    opt = ode_options(atol=-1.0e-3_wp)
    call expect_bad(method, opt, [0.5_wp, 1.0_wp], 'atol')
    opt = ode_options(atol_vector=[1.0e-8_wp, 1.0e-8_wp])
    call expect_bad(method, opt, [0.5_wp, 1.0_wp], 'atol_vector')
    opt = ode_options(fac1=-0.1_wp)
    call expect_bad(method, opt, [0.5_wp, 1.0_wp], 'fac1')
    opt = ode_options(beta=0.5_wp)
    call expect_bad(method, opt, [0.5_wp, 1.0_wp], 'beta')
    opt = ode_options(max_steps=0)
    call expect_bad(method, opt, [0.5_wp, 1.0_wp], 'max_steps')
    opt = ode_options(fixed_step=-0.1_wp)
    call expect_bad(method, opt, [0.5_wp, 1.0_wp], 'fixed_step')
    opt = ode_options()
    call expect_bad(method, opt, [1.0_wp, 0.5_wp], 't_out(2)')
    call expect_bad(method, opt, [-1.0_wp, 0.5_wp], 't_out(1)')

    call integ%init(ric, 1.0_wp, [1.0_wp], 1.0_wp, opt, status, message)
    call check_true('t_bound = t0 gives SD_BAD_INPUT: '//trim(message), &
                    status == SD_BAD_INPUT .and. index(message, 't_bound') == 1)
    call integ%step(ric, status, message)
    call check_true(name//'_step after a failed '//name//'_init is refused: '//trim(message), &
                    status == SD_BAD_INPUT)
    opt%atol = 0
    call integ%init(ric, 0.0_wp, [0.0_wp], 1.0_wp, opt, status, message)
    call check_true('atol = 0 with a zero component of y0 gives SD_BAD_INPUT: '//trim(message), &
                    status == SD_BAD_INPUT .and. index(message, 'atol') == 1)
  end subroutine check_bad_input

  !> integrate by the method on the riccati problem must return SD_BAD_INPUT with a message
  !> that starts with the name of the input, and only NaN outputs.
  subroutine expect_bad(method, opt, t_out, name)
    integer, intent(in) :: method
    type(ode_options), intent(in) :: opt
    real(wp), intent(in) :: t_out(:)
    character(len=*), intent(in) :: name
    type(riccati) :: ric
    type(ode_stats) :: stats
    real(wp) :: y_out(1, size(t_out))
    integer :: status
    character(len=message_len) :: message

    call integrate(method, ric, 0.0_wp, [1.0_wp], t_out, y_out, opt, stats, status, message)
    call check_true('bad '//name//' gives SD_BAD_INPUT: '//trim(message), &
                    status == SD_BAD_INPUT .and. index(message, name) == 1)
    call check_true('bad '//name//': all outputs NaN', all(ieee_is_nan(y_out)))
  end subroutine expect_bad
end module rk_checks
