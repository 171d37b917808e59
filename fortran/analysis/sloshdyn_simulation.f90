!> Direct simulation of the full equations of motion (eq 15 with 29-31) by the integrator family:
!> time histories, stroboscopic Poincare sections, steady states with their amplitudes and the
!> kind of motion, and sweeps in rho or A that carry the state from point to point (sec 4.2).
module sloshdyn_simulation
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, check_real
  use sloshdyn_text, only: num2str
  use sloshdyn_model, only: model_t
  use sloshdyn_excitation, only: excitation_t, forcing_period, breakpoint_step, record_end, &
                                 set_excitation_parameter
  use sloshdyn_linear, only: modal_matrix
  use sloshdyn_system, only: tank_system, tank_ensemble
  use sloshdyn_ensemble, only: advance_members, member_watch
  use sloshdyn_spatial, only: spatial_model_t, pendulum_tilt
  use sloshdyn_spatial_system, only: spatial_tank_system
  use sloshdyn_ode, only: ode_options, ode_stats, rk_integrator, observed_quantities, &
                          linear_observation, peak_tracker
  use sloshdyn_integrator, only: new_integrator, integrate
  use sloshdyn_tables, only: HISTORY_ROWS, SPATIAL_HISTORY_ROWS, SUMMARY_SIZE, MOTION_PERIODIC, MOTION_QUASI_PERIODIC, &
                             MOTION_IRREGULAR, MOTION_SETTLING
  use sloshdyn_sort, only: sort_index
  use sloshdyn_shooting, only: shooting_newton, floquet_kind, FLOQUET_STABLE
  implicit none
  private
  public :: time_history, spatial_time_history, steady_options, steady_state, steady_state_block, &
            check_steady, check_block, parameter_sweep, independent_sweep, steady_state_points, &
            steady_orbit, max_period, max_tau_span, max_state, amplitudes
  public :: check_history, with_breakpoints, derive_history

  !> Longest span of one time history in tau = omega1 t: 1e7, about 1.6 million natural
  !> periods and an hour or more of work at the integrators' usual steps (a few per period up
  !> to hundreds near impacts); a longer span is a mistake, not a study.
  real(wp), parameter :: max_tau_span = 1.0e7_wp
  !> Most output times of one time history (&simulation n_out).
  integer, parameter, public :: max_simulation_outputs = 10000000
  !> Largest |component| of an initial state: x1 = theta/theta0 is 1 at the walls and x2 =
  !> phi/theta0 is of the same order, so a state 1e3 times that lies outside every motion the
  !> model describes (the impact moment beta x1^(2n-1) of eq (4) would exceed any load, and
  !> the integration would crawl through steps too small to finish).
  real(wp), parameter :: max_state = 1.0e3_wp

  !> Longest period (in forcing periods) the classification of steady motions looks for.
  integer, parameter :: max_period = 8
  real(wp), parameter :: max_samples = 1.0e8_wp   !< window_periods*samples_per_period, at most

  !> How a steady state is reached and measured. Times in forcing periods T = 2 pi/rho.
  type :: steady_options
    !> transient integrated before measuring; with settle_tol > 0 it is the minimum
    real(wp) :: transient_periods = 1000
    !> > 0: extend the transient until successive Poincare points differ by less than
    !> settle_tol (relative to the state's size), up to max_transient_periods
    real(wp) :: settle_tol = 1.0e-7_wp
    real(wp) :: max_transient_periods = 20000
    integer :: window_periods = 200          !< periods over which amplitudes are measured
    !> probes per period at least of the scan that brackets the maxima (which are then located
    !> exactly on the dense output, sloshdyn_ode's peak_tracker)
    integer :: samples_per_period = 128
    !> Poincare points closer than this (relative) count as the same point
    real(wp) :: periodic_tol = 1.0e-4_wp
    !> with settle_tol > 0: once the Poincare map contracts, jump to the periodic orbit by
    !> Newton shooting, kept only if it is stable and the attractor being approached
    logical :: shooting = .true.
  end type steady_options

  !> The periodic orbit a steady state jumped to by shooting (found = .false. when the
  !> steady state was reached by integration alone).
  type :: steady_orbit
    logical :: found = .false.
    integer :: periods = 0                  !< k: the orbit's period is k T
    real(wp) :: y(4) = 0                    !< its state at forcing phase 0 (near the approach)
    real(wp) :: multipliers_re(4) = 0, multipliers_im(4) = 0   !< Floquet multipliers
    integer :: attempts = 0                 !< shooting attempts made
  end type steady_orbit

  !> Shooting inside steady_state: a first try once successive Poincare points (or points k
  !> periods apart) differ by less than shoot_trigger relative to the state's size and the
  !> difference is shrinking; at most shoot_attempts tries, the next one only after the
  !> difference has fallen by another factor shoot_retry_factor or the transient has doubled.
  real(wp), parameter :: shoot_trigger = 0.25_wp, shoot_retry_factor = 0.1_wp
  integer, parameter :: shoot_attempts = 8
  !> Newton's settings of the shots, and the acceptance rules: the largest multiplier below
  !> 1 - stable_margin, and the last steps of the integration P_j -> P_{j+k} predicted by the
  !> orbit's linearisation, (P_{j+k} - y*) = M (P_j - y*), within linear_tol of |P_j - y*|.
  real(wp), parameter :: shoot_newton_tol = 1.0e-10_wp, stable_margin = 1.0e-6_wp, &
                         linear_tol = 0.1_wp
  integer, parameter :: shoot_max_iter = 10
  !> independent_sweep's points a block at most, by default (benchmarks/README.md, "Steady
  !> states in blocks": 1.14x a 64-point sweep's CPU time at 16, 1.17x at 64)
  integer, parameter, public :: default_sweep_block = 16

  !> The phases of a steady_run: the transient (whole forcing periods, the settling test and
  !> the shooting attempts at each Poincare point), the window (its Poincare points and
  !> maxima), done (finished or failed).
  integer, parameter :: PHASE_DONE = 0, PHASE_TRANSIENT = 1, PHASE_WINDOW = 2

  !> One steady state (steady_state) as a state machine, so that many of them can share one
  !> ensemble: in each phase it asks for its integrator to be advanced to tau (steps while
  !> integ%t < tau, as integ%step would take them), and steady_reached then reads the state at
  !> tau and decides the next request. steady_state drives one run with its own integrator,
  !> steady_state_block K runs through advance_members: the same requests, the same steps.
  type :: steady_run
    integer :: phase = PHASE_DONE
    real(wp) :: tau = 0                     !< the time the run asks to be advanced to
    integer :: status = SD_OK
    character(len=message_len) :: message = ''
    logical :: initialised = .false.        !< steady_init set up its integrator
    type(tank_system) :: system
    type(ode_options) :: options
    integer :: method = 0
    type(steady_options) :: steady
    real(wp) :: y0(4) = 0, y(4) = 0, previous(4) = 0
    real(wp) :: period = 0, p_inv(2, 2) = 0, maxima(4) = 0
    real(wp) :: tau_window = 0, tau_end = 0, transient = 0
    integer :: k = 0                        !< Poincare points of the transient so far
    integer :: sample = 0                   !< the window's next sample (in 1/samples_per_period)
    logical :: settled = .false., use_shooting = .false., watching = .false.
    type(linear_observation) :: observed
    type(peak_tracker) :: tracker
    real(wp), allocatable :: poincare(:, :)
    ! shooting: the last 2 max_period + 1 Poincare points (ring), the orbit found
    real(wp) :: recent(4, 0:2*max_period) = 0, last_failed_gap = huge(1.0_wp)
    integer :: last_failed_k = 0
    type(steady_orbit) :: jump
  end type steady_run

  !> steady_state_block's runs, watched by advance_members after each accepted step.
  type, extends(member_watch) :: steady_block_watch
    type(steady_run), allocatable :: runs(:)
  contains
    procedure :: accepted => block_accepted
  end type steady_block_watch
  !> A shot's step budget per forcing period: shoot_step_factor times the steps per period the
  !> integration has taken so far, at least shoot_min_steps. A shot near the attractor follows
  !> the integration's path (1.5 changed no result of benchmarks/same_bits.py, the Fig 15-17
  !> amplitude sweep or the Fig 17 basin); where the motion is irregular most attempts fail,
  !> many by this budget (3 instead of 10: the Fig 17 basin 1.4x cheaper, benchmarks/README.md).
  real(wp), parameter :: shoot_step_factor = 3, shoot_min_steps = 1000

contains

  !> y, u, impact force, theta and phi (the rows of the 'history' table after tau) at the times
  !> tau_out (ascending, >= tau0) from y0 at tau0. On failure the columns reached are filled and
  !> the rest are NaN; stats%t_reached says where. With observed and tracker: the peaks of the
  !> observed quantities over [tau0, tau_out(n)], located between the steps (peak_tracker).
  subroutine time_history(model, tau0, y0, tau_out, options, method, history, stats, status, &
                          message, observed, tracker)
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: tau0, y0(4), tau_out(:)
    type(ode_options), intent(in) :: options
    integer, intent(in) :: method           !< METHOD_* of sloshdyn_integrator
    real(wp), intent(out) :: history(HISTORY_ROWS, size(tau_out))
    type(ode_stats), intent(out) :: stats
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    class(observed_quantities), intent(in), optional :: observed
    type(peak_tracker), intent(inout), optional :: tracker
    type(tank_system) :: system

    history = 0
    call check_history(tau0, y0, tau_out, status, message)
    if (status /= SD_OK) return
    system%model = model
    call integrate(method, system, tau0, y0, tau_out, history(1:4, :), &
                   with_breakpoints(options, model%excitation), stats, status, message, &
                   observed, tracker)
    call derive_history(model, history)
  end subroutine time_history

  !> The rows after the state of a time history (u1, u2, the impact force, theta, phi) from
  !> its states, history(1:4, :).
  pure subroutine derive_history(model, history)
    type(model_t), intent(in) :: model
    real(wp), intent(inout) :: history(:, :)
    real(wp) :: p_inv(2, 2)
    integer :: i
    call inverse_modal_matrix(model, p_inv)
    do i = 1, size(history, 2)
      history(5:9, i) = derived_quantities(model, p_inv, history(1:4, i))
    end do
  end subroutine derive_history

  !> The time history of the spatial model (sloshdyn_spatial; issue 26), as time_history's of
  !> the planar one: the 8 states, the pendulum's tilt from the vertical over theta0 and its
  !> azimuth [rad] (sloshdyn_spatial's pendulum_tilt) at tau_out, the rows of the
  !> 'spatial_history' table after tau.
  subroutine spatial_time_history(model, tau0, y0, tau_out, options, method, history, stats, &
                                  status, message)
    type(spatial_model_t), intent(in) :: model
    real(wp), intent(in) :: tau0, y0(8), tau_out(:)
    type(ode_options), intent(in) :: options
    integer, intent(in) :: method
    real(wp), intent(out) :: history(SPATIAL_HISTORY_ROWS, size(tau_out))
    type(ode_stats), intent(out) :: stats
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(spatial_tank_system) :: system
    type(ode_options) :: settings
    integer :: i

    history = 0
    call check_history(tau0, y0, tau_out, status, message)
    if (status /= SD_OK) return
    system%model = model
    settings = with_breakpoints(options, model%planar%excitation)
    ! a second record on the same time grid keeps its kinks to its own end
    if (allocated(model%record_y%samples)) &
      settings%breakpoint_end = max(settings%breakpoint_end, record_end(model%record_y))
    call integrate(method, system, tau0, y0, tau_out, history(1:8, :), settings, stats, status, &
                   message)
    do i = 1, size(tau_out)
      history(9:10, i) = pendulum_tilt(model, history(1:8, i))
    end do
  end subroutine spatial_time_history

  !> The inputs of a time history: y0 (check_initial_state) and the span tau_out(n) - tau0.
  pure subroutine check_history(tau0, y0, tau_out, status, message)
    real(wp), intent(in) :: tau0, y0(:), tau_out(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: span
    status = SD_OK
    message = ''
    call check_initial_state(y0, status, message)
    if (status == SD_OK .and. size(tau_out) > 0) then
      span = tau_out(size(tau_out)) - tau0    ! non-finite or descending: integrate's checks
      if (abs(span) > max_tau_span .and. abs(span) <= huge(span)) then
        status = SD_BAD_INPUT
        message = 'the span tau_out('//num2str(size(tau_out))//') - tau0 = '//num2str(span)// &
                  ' is out of range: one time history spans at most '//num2str(max_tau_span)// &
                  ' in tau (about 1.6 million natural periods, hours of work; in a namelist '// &
                  'it is &simulation t_end)'
      end if
    end if
  end subroutine check_history

  !> options with a record's samples (of excitation) as breakpoints: they are kinks of the
  !> right-hand side, and no step crosses one.
  pure function with_breakpoints(options, excitation) result(settings)
    type(ode_options), intent(in) :: options
    type(excitation_t), intent(in) :: excitation
    type(ode_options) :: settings
    settings = options
    settings%breakpoint_step = breakpoint_step(excitation)
    settings%breakpoint_end = record_end(excitation)
  end function with_breakpoints

  !> Every component of y0 within +-max_state (NaN and infinity are left to the integrator's
  !> own check, which names them the same way); y0 of the planar (4) or the spatial model (8).
  pure subroutine check_initial_state(y0, status, message)
    real(wp), intent(in) :: y0(:)
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    character(len=*), parameter :: names(2) = [character(len=36) :: 'x1, x1'', x2, x2''', &
                                               'x1, x1'', x2, x2'', y1, y1'', y2, y2''']
    integer :: i
    do i = 1, size(y0)
      if (abs(y0(i)) <= max_state .or. .not. abs(y0(i)) <= huge(y0(i))) cycle
      call check_real('y0('//num2str(i)//')', y0(i), -max_state, max_state, .false., .false., &
                      'every component of the initial state ('// &
                      trim(names(merge(2, 1, size(y0) == 8)))//') must lie in [-1e3, 1e3]: '// &
                      'x1 = theta/theta0 is 1 at the walls', status, message)
      return
    end do
  end subroutine check_initial_state

  !> P^-1 of eq (34), or NaN where kappa <= s1 has no modes.
  pure subroutine inverse_modal_matrix(model, p_inv)
    type(model_t), intent(in) :: model
    real(wp), intent(out) :: p_inv(2, 2)
    real(wp) :: p(2, 2)
    integer :: status
    character(len=message_len) :: message
    call modal_matrix(model, p, p_inv, status, message)
    if (status /= SD_OK) p_inv = ieee_value(1.0_wp, ieee_quiet_nan)
  end subroutine inverse_modal_matrix

  !> |x1|, |x2|, |u1|, |u2| (eq 34) of a state y as C y: the steady-state amplitudes.
  pure function amplitudes(p_inv) result(observation)
    real(wp), intent(in) :: p_inv(2, 2)
    type(linear_observation) :: observation
    allocate (observation%c(4, 4))
    observation%c = 0
    observation%c(1, 1) = 1
    observation%c(2, 3) = 1
    observation%c(3:4, 1) = p_inv(:, 1)
    observation%c(3:4, 3) = p_inv(:, 2)
  end function amplitudes

  !> u1, u2 (eq 34), impact force beta x1^(2n-1) (eq 4), theta, phi from y.
  pure function derived_quantities(model, p_inv, y) result(d)
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: p_inv(2, 2), y(4)
    real(wp) :: d(5)
    d(1:2) = matmul(p_inv, [y(1), y(3)])
    d(3) = model%beta*y(1)**(2*model%n - 1)
    d(4:5) = model%theta0*[y(1), y(3)]
  end function derived_quantities

  !> Integrate from y0 at tau = 0 through a transient, then measure over a window: the maxima of
  !> |x1|, |x2|, |u1|, |u2| (located on the dense output between the steps, sloshdyn_ode's
  !> peak_tracker, whose scan probes samples_per_period points per period), the Poincare points at
  !> tau = k T (forcing phase 0), and the kind of motion. y_end is the state at the end of the
  !> window, again at forcing phase 0, so the next point of a sweep can start from it at tau = 0.
  !>
  !> With settle_tol > 0 and steady%shooting, once the Poincare map contracts (points one or k
  !> forcing periods apart close in, k <= max_period) the transient is cut short: Newton
  !> shooting from the current Poincare point finds the orbit of period k T, which is accepted
  !> only if it is stable (every Floquet multiplier inside 1 - stable_margin) and is the
  !> attractor the integration was approaching (its linearisation predicts the integration's
  !> last steps). The window is then measured on that orbit (one orbit period, sampled at the
  !> same phases; its Poincare points repeat). Otherwise (quasi-periodic, irregular, slow or
  !> no contraction, Newton failing) the integration goes on exactly as without shooting.
  !> orbit (optional) tells whether and where the jump was made.
  subroutine steady_state(model, y0, options, method, steady, summary, poincare, y_end, stats, &
                          status, message, orbit)
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: y0(4)
    type(ode_options), intent(in) :: options
    integer, intent(in) :: method
    type(steady_options), intent(in) :: steady
    real(wp), intent(out) :: summary(SUMMARY_SIZE), poincare(:, :)
    real(wp), intent(out) :: y_end(4)
    type(ode_stats), intent(out) :: stats
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(steady_orbit), intent(out), optional :: orbit
    type(steady_run) :: run
    class(rk_integrator), allocatable :: integ

    summary = 0
    poincare = 0
    y_end = y0
    call steady_begin(run, model, y0, options, method, steady)
    status = run%status
    message = run%message
    if (status == SD_OK .and. (size(poincare, 1) /= 4 .or. size(poincare, 2) < steady%window_periods)) then
      status = SD_BAD_INPUT
      message = 'the Poincare array must be 4 x window_periods = 4 x '//num2str(steady%window_periods)
    end if
    if (status /= SD_OK) return
    call new_integrator(method, options%rtol, integ, status, message)
    if (status /= SD_OK) return
    call steady_init(run, integ)
    status = run%status
    message = run%message
    if (status /= SD_OK) return
    do while (run%phase /= PHASE_DONE)
      do while (integ%t < run%tau)
        call integ%step(run%system, run%status, run%message)
        if (run%status == SD_OK) call steady_watch(run, integ, run%status, run%message)
        if (run%status /= SD_OK) exit
      end do
      call steady_reached(run, integ)
    end do
    call steady_finish(run, integ, summary, poincare, y_end, stats, status, message, orbit)
  end subroutine steady_state

  !> steady_state at K points at once: point i from y0(:, i) with models(i) (or models(1) for
  !> all), its results in summaries(:, i), poincare(:, :, i), y_end(:, i), stats(i),
  !> status(i), message(i), orbits(i). The points' integrations advance together through
  !> advance_members (sloshdyn_ensemble) with their right-hand sides evaluated as one
  !> tank_ensemble block; every point is steady_state's alone, bit for bit: each is the same
  !> steady_run, asking for the same stretches, whose integrator steps as integ%step does
  !> (the shots and the orbit's window run one point at a time, as in steady_state). A point
  !> that fails does not stop the others.
  subroutine steady_state_block(models, y0, options, method, steady, summaries, poincare, &
                                y_end, stats, status, message, orbits)
    type(model_t), intent(in) :: models(:)
    real(wp), intent(in) :: y0(:, :)
    type(ode_options), intent(in) :: options
    integer, intent(in) :: method
    type(steady_options), intent(in) :: steady
    real(wp), intent(out) :: summaries(:, :), poincare(:, :, :), y_end(:, :)
    type(ode_stats), intent(out) :: stats(:)
    integer, intent(out) :: status(:)
    character(len=message_len), intent(out) :: message(:)
    type(steady_orbit), intent(out) :: orbits(:)
    type(steady_block_watch) :: block
    type(tank_ensemble) :: esys
    class(rk_integrator), allocatable :: proto, integ(:)
    integer, allocatable :: active(:), advance_status(:)
    character(len=message_len), allocatable :: advance_message(:)
    integer :: n, i, c, m, st
    character(len=message_len) :: msg

    n = size(y0, 2)
    summaries = 0
    poincare = 0
    y_end = 0
    if (size(y0, 1) /= 4 .or. size(summaries, 1) /= SUMMARY_SIZE .or. size(summaries, 2) /= n &
        .or. size(poincare, 1) /= 4 .or. size(poincare, 2) < steady%window_periods .or. &
        size(poincare, 3) /= n .or. any(shape(y_end) /= [4, n]) .or. size(stats) /= n .or. &
        size(status) /= n .or. size(message) /= n .or. size(orbits) /= n .or. &
        (size(models) /= 1 .and. size(models) /= n)) then
      status = SD_BAD_INPUT
      message = 'steady_state_block of '//num2str(n)//' points (size(y0, 2)): the arrays '// &
                'must be y0(4, n), summaries('//num2str(SUMMARY_SIZE)//', n), poincare(4, '// &
                'window_periods, n), y_end(4, n), stats, status, message and orbits(n), '// &
                'models(1) or models(n)'
      return
    end if
    y_end = y0
    allocate (block%runs(n), esys%models(n), active(n), advance_status(n), advance_message(n))
    do i = 1, n
      call steady_begin(block%runs(i), models(min(i, size(models))), y0(:, i), options, method, &
                        steady)
      esys%models(i) = block%runs(i)%system%model
    end do
    st = SD_OK
    msg = ''
    if (any(block%runs%status == SD_OK)) call new_integrator(method, options%rtol, proto, st, msg)
    if (st == SD_OK .and. n > 0 .and. any(block%runs%status == SD_OK)) then
      allocate (integ(n), mold=proto)
      do i = 1, n
        if (block%runs(i)%status == SD_OK) call steady_init(block%runs(i), integ(i))
      end do
      ! every round takes each point still running to the time it asks for, then lets it go on
      do
        m = 0
        do i = 1, n
          if (block%runs(i)%phase == PHASE_DONE) cycle
          m = m + 1
          active(m) = i
        end do
        if (m == 0) exit
        call advance_members(esys, integ, active(1:m), block%runs(active(1:m))%tau, &
                             advance_status(1:m), advance_message(1:m), block)
        do c = 1, m
          associate (run => block%runs(active(c)))
            run%status = advance_status(c)
            run%message = advance_message(c)
            call steady_reached(run, integ(active(c)))
          end associate
        end do
      end do
    end if
    do i = 1, n
      associate (run => block%runs(i))
        if (run%status == SD_OK .and. st /= SD_OK) then
          status(i) = st
          message(i) = msg
        else if (run%status == SD_OK .or. run%initialised) then
          call steady_finish(run, integ(i), summaries(:, i), poincare(:, :, i), y_end(:, i), &
                             stats(i), status(i), message(i), orbits(i))
        else
          status(i) = run%status
          message(i) = run%message
        end if
      end associate
    end do
  end subroutine steady_state_block

  !> steady_state's inputs checked and its quantities set up (run%status, run%message).
  subroutine steady_begin(run, model, y0, options, method, steady)
    type(steady_run), intent(out) :: run
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: y0(4)
    type(ode_options), intent(in) :: options
    integer, intent(in) :: method
    type(steady_options), intent(in) :: steady
    call check_steady(model, steady, run%status, run%message)
    call check_initial_state(y0, run%status, run%message)
    run%system%model = model
    run%y0 = y0
    run%options = options
    run%method = method
    run%steady = steady
    if (run%status /= SD_OK) return
    run%period = forcing_period(model%excitation)
    call inverse_modal_matrix(model, run%p_inv)
    run%observed = amplitudes(run%p_inv)
    run%tracker%spacing = run%period/steady%samples_per_period
    allocate (run%poincare(4, steady%window_periods))
    run%poincare = 0
  end subroutine steady_begin

  !> The integrator set up at tau = 0 and the transient's first request (one forcing period).
  subroutine steady_init(run, integ)
    type(steady_run), intent(inout) :: run
    class(rk_integrator), intent(inout) :: integ
    ! one spare period: sample times computed in steps must not round past t_bound
    call integ%init(run%system, 0.0_wp, run%y0, (max(run%steady%transient_periods, &
                    run%steady%max_transient_periods) + run%steady%window_periods + 1)*run%period, &
                    run%options, run%status, run%message)
    run%initialised = run%status == SD_OK
    if (run%status /= SD_OK) return
    run%k = 1
    run%tau = run%k*run%period
    run%previous = run%y0
    run%settled = run%steady%settle_tol <= 0
    run%use_shooting = run%steady%shooting .and. run%steady%settle_tol > 0
    run%recent(:, 0) = run%y0
    run%phase = PHASE_TRANSIENT
  end subroutine steady_init

  !> After each accepted step of the run's integrator: in the window, the maxima between the
  !> steps (peak_tracker).
  subroutine steady_watch(run, integ, status, message)
    type(steady_run), intent(inout) :: run
    class(rk_integrator), intent(in) :: integ
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    status = SD_OK
    message = ''
    if (run%watching) call run%tracker%watch(integ, run%observed, run%tau_window, &
                                             run%tau_end, status, message)
  end subroutine steady_watch

  !> steady_block_watch's accepted: steady_watch of run j.
  subroutine block_accepted(self, j, integ, status, message)
    class(steady_block_watch), intent(inout) :: self
    integer, intent(in) :: j
    class(rk_integrator), intent(in) :: integ
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    call steady_watch(self%runs(j), integ, status, message)
  end subroutine block_accepted

  !> The run's integrator has passed run%tau (or failed, run%status): read the state at tau
  !> by dense output and take the next phase's step of steady_state -- the transient's
  !> settling test and shooting attempt, the window's Poincare point -- asking for the next
  !> time, or PHASE_DONE.
  subroutine steady_reached(run, integ)
    type(steady_run), intent(inout) :: run
    class(rk_integrator), intent(inout) :: integ
    real(wp) :: y(4)
    integer :: spp
    if (run%status /= SD_OK) then
      run%phase = PHASE_DONE
      return
    end if
    call integ%dense(run%tau, y)
    run%y = y
    spp = run%steady%samples_per_period
    select case (run%phase)
    case (PHASE_TRANSIENT)
      ! transient: whole periods, then (optionally) until the Poincare map settles
      if (run%steady%settle_tol > 0) &
        run%settled = norm2(y - run%previous) <= run%steady%settle_tol*max(norm2(y), tiny(1.0_wp))
      run%previous = y
      if (run%use_shooting) then
        run%recent(:, mod(run%k, 2*max_period + 1)) = y
        if (run%k >= 2*max_period .and. run%jump%attempts < shoot_attempts) &
          call try_orbit(run, integ)
        if (run%jump%found) then
          run%transient = run%k
          call measure_orbit(run)
          run%phase = PHASE_DONE
          return
        end if
      end if
      if (run%k >= run%steady%transient_periods .and. &
          (run%settled .or. run%k >= run%steady%max_transient_periods)) then
        ! window: maxima between the steps, Poincare points at its period boundaries
        run%transient = run%k
        run%tau_window = run%k*run%period
        run%tau_end = run%tau_window + run%steady%window_periods*run%period
        call run%tracker%start(run%observed, run%tau_window, y)
        call run%tracker%watch(integ, run%observed, run%tau_window, run%tau_end, run%status, &
                               run%message)
        run%watching = .true.
        run%sample = spp
        run%phase = PHASE_WINDOW
        if (run%status /= SD_OK) run%phase = PHASE_DONE
      else
        run%k = run%k + 1
        run%tau = run%k*run%period
        return
      end if
    case (PHASE_WINDOW)
      run%poincare(:, run%sample/spp) = y
      run%sample = run%sample + spp
    end select
    if (run%phase /= PHASE_WINDOW) return
    if (run%sample > run%steady%window_periods*spp) then
      run%maxima = run%tracker%peak
      run%phase = PHASE_DONE
    else
      run%tau = run%tau_window + run%sample*run%period/spp
    end if
  end subroutine steady_reached

  !> steady_state's results from a finished run.
  subroutine steady_finish(run, integ, summary, poincare, y_end, stats, status, message, orbit)
    type(steady_run), intent(inout) :: run
    class(rk_integrator), intent(in) :: integ
    real(wp), intent(out) :: summary(SUMMARY_SIZE), poincare(:, :), y_end(4)
    type(ode_stats), intent(out) :: stats
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(steady_orbit), intent(out), optional :: orbit
    real(wp) :: spread, scale
    integer :: motion, repeat
    logical :: settled
    associate (model => run%system%model, steady => run%steady)
      summary = 0
      poincare = 0
      poincare(:, 1:steady%window_periods) = run%poincare
      y_end = run%y0
      status = run%status
      message = run%message
      stats = integ%statistics()
      if (present(orbit)) orbit = run%jump
      if (status /= SD_OK) then
        message = trim(message)//' (steady state at rho = '//num2str(model%excitation%rho)// &
                  ', A = '//num2str(model%excitation%A)//')'
        return
      end if
      settled = run%settled
      if (run%jump%found) then
        y_end = run%poincare(:, steady%window_periods)
        settled = .true.
      else
        y_end = run%y
      end if
      call classify(run%poincare, steady%periodic_tol, motion, repeat, spread, scale)
      summary = [model%excitation%rho, model%excitation%A, run%maxima, real(motion, wp), &
                 real(repeat, wp), run%transient, spread, merge(1.0_wp, 0.0_wp, settled)]
    end associate
  end subroutine steady_finish

  !> Poincare point j (j >= k - 2 max_period) from the run's ring.
  function recent_point(run, j) result(point)
    type(steady_run), intent(in) :: run
    integer, intent(in) :: j
    real(wp) :: point(4)
    point = run%recent(:, mod(j, 2*max_period + 1))
  end function recent_point

  !> A shooting attempt at period k (the current Poincare point y = P_k), when the map
  !> contracts: the smallest p <= max_period with |P_k - P_(k-p)| <= shoot_trigger |P| and
  !> shrinking (below |P_(k-p) - P_(k-2p)|). Accepted orbits end the transient (jump%found).
  subroutine try_orbit(run, integ)
    type(steady_run), intent(inout) :: run
    class(rk_integrator), intent(in) :: integ
    real(wp) :: size_, gap, gap_before, y_orbit(4), monodromy(4, 4), re(4), im(4)
    real(wp) :: from(4), to(4), error
    integer :: p, j, iterations, shot_status, k
    character(len=message_len) :: shot_message
    type(ode_options) :: shot_options
    type(ode_stats) :: stats
    k = run%k
    associate (y => run%y, jump => run%jump, options => run%options)
      size_ = max(norm2(y), tiny(1.0_wp))
      do p = 1, max_period
        gap = norm2(y - recent_point(run, k - p))
        gap_before = norm2(recent_point(run, k - p) - recent_point(run, k - 2*p))
        if (gap <= shoot_trigger*size_ .and. (gap < gap_before .or. gap <= 1.0e-12_wp*size_)) exit
      end do
      if (p > max_period) return
      ! after a failed attempt: wait until the gap has shrunk a lot or the transient doubled
      if (run%last_failed_k > 0 .and. .not. (gap <= shoot_retry_factor*run%last_failed_gap .or. &
                                             k >= 2*run%last_failed_k)) return
      jump%attempts = jump%attempts + 1
      ! a shot may take shoot_step_factor times the steps the integration has needed per
      ! period so far (Newton iterates that wander into the stiff impact regime fail fast)
      shot_options = options
      stats = integ%statistics()
      shot_options%max_steps = int(min(real(options%max_steps, wp), real(p, wp)* &
                                   max(shoot_min_steps, shoot_step_factor* &
                                   real(stats%n_accepted + stats%n_rejected, wp)/k)))
      call shooting_newton(run%system, y, p, shot_options, run%method, shoot_newton_tol, &
                           shoot_max_iter, y_orbit, monodromy, re, im, iterations, shot_status, &
                           shot_message)
      if (shot_status == SD_OK) then
        if (floquet_kind(re, im, stable_margin) == FLOQUET_STABLE) then
          ! the orbit's linearisation must describe the integration's last two steps
          shot_status = SD_OK
          do j = 0, 1
            from = recent_point(run, k - (j + 1)*p) - y_orbit
            to = recent_point(run, k - j*p) - y_orbit
            error = norm2(to - matmul(monodromy, from))
            if (error > linear_tol*norm2(from) + 1.0e2_wp*shoot_newton_tol*size_) &
              shot_status = SD_BAD_INPUT
          end do
          if (shot_status == SD_OK) then
            jump%found = .true.
            jump%periods = p
            jump%y = y_orbit
            jump%multipliers_re = re
            jump%multipliers_im = im
            return
          end if
        end if
      end if
      run%last_failed_k = k
      run%last_failed_gap = gap
    end associate
  end subroutine try_orbit

  !> The window on the orbit found: one orbit period (jump%periods forcing periods) from its
  !> state at phase 0, sampled at the window's phases for the maxima; its Poincare points
  !> repeated over the window (one point at a time, as it is short).
  subroutine measure_orbit(run)
    type(steady_run), intent(inout), target :: run
    class(rk_integrator), allocatable, target :: orbit_integ
    real(wp) :: z(4), points(4, max_period), t_sample
    integer :: p, i
    associate (jump => run%jump, steady => run%steady, period => run%period, &
               status => run%status, message => run%message)
      p = jump%periods
      call new_integrator(run%method, run%options%rtol, orbit_integ, status, message)
      if (status == SD_OK) call orbit_integ%init(run%system, 0.0_wp, jump%y, (p + 1)*period, &
                                                 run%options, status, message)
      if (status /= SD_OK) return
      call run%tracker%start(run%observed, 0.0_wp, jump%y)
      do i = 1, p
        t_sample = (i*steady%samples_per_period)*period/steady%samples_per_period
        do while (orbit_integ%t < t_sample)
          call orbit_integ%step(run%system, status, message)
          if (status == SD_OK) call run%tracker%watch(orbit_integ, run%observed, 0.0_wp, &
                                                      p*period, status, message)
          if (status /= SD_OK) return
        end do
        call orbit_integ%dense(t_sample, z)
        points(:, i) = z
      end do
      run%maxima = run%tracker%peak
      do i = 1, steady%window_periods
        run%poincare(:, i) = points(:, mod(i - 1, p) + 1)
      end do
    end associate
  end subroutine measure_orbit

  !> A block size of the studies: >= 1 points handed to steady_state_block together.
  pure subroutine check_block(block, status, message)
    integer, intent(in) :: block
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    status = SD_OK
    message = ''
    if (block < 1) then
      status = SD_BAD_INPUT
      message = 'block = '//num2str(block)//' is out of range: the points go to the '// &
                'ensemble block points at a time, block >= 1'
    end if
  end subroutine check_block

  !> The steady-state settings and a forcing frequency: the rules every reader applies.
  pure subroutine check_steady(model, steady, status, message)
    type(model_t), intent(in) :: model
    type(steady_options), intent(in) :: steady
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    status = SD_OK
    message = ''
    call check_real('rho', model%excitation%rho, 0.0_wp, huge(1.0_wp), .true., .true., &
                    'a steady state needs a forcing frequency rho > 0', status, message)
    call check_real('transient_periods', steady%transient_periods, 0.0_wp, 1.0e9_wp, .false., &
                    .false., 'transient_periods must lie in [0, 1e9]', status, message)
    call check_real('settle_tol', steady%settle_tol, 0.0_wp, 1.0_wp, .false., .false., &
                    'settle_tol must lie in [0, 1] (0 = fixed transient)', status, message)
    call check_real('max_transient_periods', steady%max_transient_periods, 0.0_wp, 1.0e9_wp, &
                    .false., .false., 'max_transient_periods must lie in [0, 1e9]', status, message)
    call check_real('periodic_tol', steady%periodic_tol, 0.0_wp, 1.0_wp, .true., .false., &
                    'periodic_tol must lie in (0, 1]', status, message)
    if (status /= SD_OK) return
    if (steady%window_periods < 2*max_period .or. steady%window_periods > 1000000) then
      status = SD_BAD_INPUT
      message = 'window_periods = '//num2str(steady%window_periods)//' is out of range: it must '// &
                'lie in ['//num2str(2*max_period)//', 1000000]'
    else if (steady%samples_per_period < 4 .or. &
             real(steady%samples_per_period, wp)*steady%window_periods > max_samples) then
      ! window_periods*samples_per_period dense-output samples: at most 10**8 (some seconds),
      ! and a product that would wrap around the integers is refused, not used
      status = SD_BAD_INPUT
      message = 'samples_per_period = '//num2str(steady%samples_per_period)// &
                ' is out of range: it must be >= 4 and at most 1e8/window_periods = '// &
                num2str(int(max_samples)/steady%window_periods)
    end if
  end subroutine check_steady

  !> Kind of motion from the Poincare points (columns, in time order):
  !> periodic with period k <= 8 forcing periods if every point recurs after k points within
  !> tol (relative to the largest point); otherwise quasi-periodic if the points lie on one smooth
  !> closed curve (sorted by angle about their centroid in the (x1, x1') plane the radius varies
  !> smoothly), else irregular; settling if the points still close in on one point (their mean
  !> distance to the last point halves from the first to the third quarter of the window).
  !> A heuristic: a curve that winds twice around its centroid can be judged irregular. scatter = largest distance of a point from the first, relative.
  pure subroutine classify(points, tol, motion, period, scatter, scale)
    real(wp), intent(in) :: points(:, :), tol
    integer, intent(out) :: motion, period
    real(wp), intent(out) :: scatter, scale
    real(wp) :: centre(2), angle(size(points, 2)), radius(size(points, 2)), jumps(size(points, 2))
    integer :: n, k, i, order(size(points, 2)), quarter
    real(wp) :: early, late

    n = size(points, 2)
    scale = max(maxval(norm2(points, dim=1)), tiny(1.0_wp))
    scatter = maxval(norm2(points - spread(points(:, 1), 2, n), dim=1))/scale
    motion = MOTION_IRREGULAR
    period = 0
    do k = 1, max_period
      if (all(norm2(points(:, 1 + k:n) - points(:, 1:n - k), dim=1) <= tol*scale)) then
        motion = MOTION_PERIODIC
        period = k
        return
      end if
    end do
    ! a transient spiralling into a fixed point: distances to the last point keep shrinking
    quarter = n/4
    early = sum(norm2(points(:, 1:quarter) - spread(points(:, n), 2, quarter), dim=1))/quarter
    late = sum(norm2(points(:, 2*quarter + 1:3*quarter) - spread(points(:, n), 2, quarter), &
                     dim=1))/quarter
    if (late < 0.5_wp*early) then
      motion = MOTION_SETTLING
      return
    end if
    centre = sum(points([1, 2], :), dim=2)/n
    do i = 1, n
      angle(i) = atan2(points(2, i) - centre(2), points(1, i) - centre(1))
      radius(i) = norm2(points([1, 2], i) - centre)
    end do
    call sort_index(angle, order)
    do i = 1, n
      jumps(i) = abs(radius(order(mod(i, n) + 1)) - radius(order(i)))
    end do
    ! a smooth curve sampled at n points: neighbouring radii differ by a small part of the range
    ! (judged on the 90th percentile, so a few points near the centroid do not decide)
    call sort_index(jumps, order)
    if (jumps(order(max(1, (9*n)/10))) <= &
        0.25_wp*max(maxval(radius) - minval(radius), 0.05_wp*maxval(radius))) &
      motion = MOTION_QUASI_PERIODIC
  end subroutine classify

  !> Steady states along values of rho, A or rho at constant acceleration (which, see
  !> set_excitation_parameter), each point starting
  !> from the previous point's final state (so hysteresis and jumps show), as the paper's
  !> numerical continuation (sec 4.2). Only summaries are kept: summaries(:, i) for values(i);
  !> y_final is the state after the last point done (n_done of them).
  subroutine parameter_sweep(model, which, values, y0, options, method, steady, summaries, &
                             y_final, n_done, status, message)
    type(model_t), intent(in) :: model
    integer, intent(in) :: which, method
    real(wp), intent(in) :: values(:), y0(4)
    type(ode_options), intent(in) :: options
    type(steady_options), intent(in) :: steady
    real(wp), intent(out) :: summaries(SUMMARY_SIZE, size(values)), y_final(4)
    integer, intent(out) :: n_done, status
    character(len=message_len), intent(out) :: message
    type(model_t) :: point
    real(wp) :: poincare(4, steady%window_periods), y_start(4)
    type(ode_stats) :: stats
    integer :: i

    summaries = 0
    n_done = 0
    y_final = y0
    status = SD_OK
    message = ''
    point = model
    y_start = y0
    do i = 1, size(values)
      point%excitation = model%excitation   ! each point from the model's (no drift in A)
      call set_excitation_parameter(point%excitation, which, values(i), status, message)
      if (status /= SD_OK) return
      call steady_state(point, y_start, options, method, steady, summaries(:, i), poincare, &
                        y_final, stats, status, message)
      if (status /= SD_OK) return
      n_done = i
      y_start = y_final
    end do
  end subroutine parameter_sweep

  !> Steady states at values of the parameter `which` (as parameter_sweep), each from the
  !> same initial state y0: the points are independent, so they go to steady_state_block
  !> at most `block` at a time (absent or 0: default_sweep_block; fewer where the n_threads
  !> threads would not get a block each) and the threads (OpenMP) share out the blocks; each
  !> point is computed exactly as by steady_state alone -- the results depend neither on
  !> n_threads nor on block, bit for bit. n_done counts the points completed; status and
  !> message are those of the first failing point (in the order of values).
  subroutine independent_sweep(model, which, values, y0, options, method, steady, n_threads, &
                               summaries, n_done, status, message, block)
    type(model_t), intent(in) :: model
    integer, intent(in) :: which, method, n_threads
    real(wp), intent(in) :: values(:), y0(4)
    type(ode_options), intent(in) :: options
    type(steady_options), intent(in) :: steady
    real(wp), intent(out) :: summaries(SUMMARY_SIZE, size(values))
    integer, intent(out) :: n_done, status
    character(len=message_len), intent(out) :: message
    integer, intent(in), optional :: block
    integer :: i, b, points, first, last, point_status(size(values)), point_done(size(values))
    character(len=message_len) :: point_message(size(values))

    summaries = 0
    n_done = 0
    status = SD_OK
    message = ''
    points = default_sweep_block
    if (present(block)) then
      if (block /= 0) points = block
    end if
    if (n_threads < 1) then
      status = SD_BAD_INPUT
      message = 'threads = '//num2str(n_threads)//' is out of range: it must be >= 1'
      return
    end if
    call check_block(points, status, message)
    if (status /= SD_OK) then
      message = trim(message)//', or 0 for the default, '//num2str(default_sweep_block)
      return
    end if
    ! fewer points a block where the threads would otherwise not get one each
    points = max(1, min(points, (size(values) + n_threads - 1)/n_threads))
    point_status = SD_OK
    point_message = ''
    point_done = 0
    !$omp parallel do num_threads(n_threads) schedule(dynamic, 1) private(first, last)
    do b = 1, (size(values) + points - 1)/points
      first = (b - 1)*points + 1
      last = min(size(values), b*points)
      call sweep_block(model, which, values(first:last), y0, options, method, steady, &
                       summaries(:, first:last), point_done(first:last), &
                       point_status(first:last), point_message(first:last))
    end do
    !$omp end parallel do
    n_done = sum(point_done)
    do i = 1, size(values)
      if (point_status(i) /= SD_OK) then
        status = point_status(i)
        message = point_message(i)
        exit
      end if
    end do
  end subroutine independent_sweep

  !> independent_sweep's points values(:) as one steady_state_block (those whose value
  !> set_excitation_parameter accepts): done(i) = 1 for a point completed, its status and
  !> message.
  subroutine sweep_block(model, which, values, y0, options, method, steady, summaries, done, &
                         status, message)
    type(model_t), intent(in) :: model
    integer, intent(in) :: which, method
    real(wp), intent(in) :: values(:), y0(4)
    type(ode_options), intent(in) :: options
    type(steady_options), intent(in) :: steady
    real(wp), intent(inout) :: summaries(:, :)
    integer, intent(out) :: done(:), status(:)
    character(len=message_len), intent(out) :: message(:)
    type(model_t) :: models(size(values))
    real(wp) :: y_end(4, size(values))
    type(steady_orbit) :: orbits(size(values))
    integer :: i

    do i = 1, size(values)
      models(i) = model
      call set_excitation_parameter(models(i)%excitation, which, values(i), status(i), &
                                    message(i))
    end do
    call steady_state_points(models, spread(y0, 2, size(values)), options, method, steady, &
                             size(values), summaries, y_end, orbits, status, message)
    done = merge(1, 0, status == SD_OK)
  end subroutine sweep_block

  !> Steady states of the points i whose models(i) are built (status(i) = SD_OK on entry; the
  !> others, whose model could not be made, keep their status and message), each from
  !> y0(:, i), handed to steady_state_block `block` (>= 1) at a time in the order of the
  !> points, each equal to its steady_state alone: summaries(:, i), y_end(:, i), orbits(i),
  !> status(i) and message(i) of those points, the others' left as they were. The blocks'
  !> results are kept in locals until each block ends, so that threads working on
  !> neighbouring points (independent_sweep) do not pass cache lines to and fro.
  subroutine steady_state_points(models, y0, options, method, steady, block, summaries, y_end, &
                                 orbits, status, message)
    type(model_t), intent(in) :: models(:)
    real(wp), intent(in) :: y0(:, :)
    type(ode_options), intent(in) :: options
    integer, intent(in) :: method, block
    type(steady_options), intent(in) :: steady
    real(wp), intent(inout) :: summaries(:, :), y_end(:, :)
    type(steady_orbit), intent(inout) :: orbits(:)
    integer, intent(inout) :: status(:)
    character(len=message_len), intent(inout) :: message(:)
    integer, allocatable :: members(:)
    integer :: block_status(min(block, size(models))), i, c, first, nb
    character(len=message_len) :: block_message(min(block, size(models)))
    real(wp) :: block_summaries(SUMMARY_SIZE, min(block, size(models))), &
                block_y_end(4, min(block, size(models))), &
                poincare(4, max(steady%window_periods, 1), min(block, size(models)))
    type(ode_stats) :: stats(min(block, size(models)))
    type(steady_orbit) :: block_orbits(min(block, size(models)))

    members = pack([(i, i = 1, size(models))], status == SD_OK)
    do first = 1, size(members), block
      nb = min(block, size(members) - first + 1)
      associate (points => members(first:first + nb - 1))
        call steady_state_block(models(points), y0(:, points), options, method, steady, &
                                block_summaries(:, 1:nb), poincare(:, :, 1:nb), &
                                block_y_end(:, 1:nb), stats(1:nb), block_status(1:nb), &
                                block_message(1:nb), block_orbits(1:nb))
        do c = 1, nb
          i = points(c)
          summaries(:, i) = block_summaries(:, c)
          y_end(:, i) = block_y_end(:, c)
          orbits(i) = block_orbits(c)
          status(i) = block_status(c)
          message(i) = block_message(c)
        end do
      end associate
    end do
  end subroutine steady_state_points
end module sloshdyn_simulation
