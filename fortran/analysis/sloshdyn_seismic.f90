!> A real tank under ground motion, in SI units: the time histories of the sloshing
!> displacement, the wave height at the wall, the pendulum angle, the tank drift, the tank's
!> and the convective mass's accelerations, the base shear and the overturning moments
!> (sloshdyn_vessel's loads) of the tank without contact below its roof and by the
!> restricted-sloshing method above it, their peaks (located between the integrator's steps,
!> not read at the output times), and whether and when the free wave reaches the roof; and the
!> cross-check of the tank's sloshing parameters against the design codes (API 650 Annex E,
!> Eurocode 8-4 Annex A, ACI 350.3).
!>
!> Table layouts (sloshdyn_tables): 'seismic' (one column per output time), 'seismic_peaks' (one
!> row) and 'design_codes' (one row per source: sloshdyn, API 650, EC8-4, ACI 350.3; with
!> modes > 1 also sloshdyn's modal sums, SRSS and ABS).
module sloshdyn_seismic
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, SD_CANCELLED, check_real, check_output_count
  use sloshdyn_cancel, only: check_cancel
  use sloshdyn_text, only: num2str
  use sloshdyn_model, only: model_t, set_coefficients
  use sloshdyn_motion, only: equations_of_motion
  use sloshdyn_vessel, only: tank_t, tank_properties, tank_model, tank_loads, LOAD_ROWS, &
                            convective_damping, ROOF_CONTACT_IMPACT
  use sloshdyn_tank, only: SHAPE_CIRCULAR, max_modes
  use sloshdyn_sdof, only: sdof_response
  use sloshdyn_ground, only: ground_motion_t, ground_excitation, ground_duration, ground_spectrum, &
                             GROUND_RECORD, GROUND_HARMONIC, harmonic_periods, &
                             spectral_acceleration
  use sloshdyn_excitation, only: PARAMETER_FREQUENCY
  use sloshdyn_design_codes, only: aci350_parameters, api650_parameters, ec8_parameters, &
                                   aci350_circular, aci350_rectangular, aci350_wave_height, &
                                   api650_circular, &
                                   api650_wave_height, ec8_circular, ec8_wave_height
  use sloshdyn_roof, only: roof_loads, rectangular_roof_loads
  use sloshdyn_design_spectra, only: design_spectrum_t, spectrum_sa
  use sloshdyn_ode, only: ode_options, ode_stats, observed_quantities, peak_tracker
  use sloshdyn_simulation, only: steady_options, parameter_sweep, independent_sweep
  use sloshdyn_ensemble_history, only: tank_histories
  use sloshdyn_tables, only: HISTORY_ROWS, SEISMIC_ROWS, PEAKS_SIZE, PEAKS_ROOF_REACHED, &
                             SEISMIC_WAVE_HEIGHT, SEISMIC_BASE_SHEAR, SEISMIC_OVERTURNING_MOMENT, &
                             SEISMIC_OVERTURNING_MOMENT_IBP, SEISMIC_TANK_ACCELERATION, &
                             SEISMIC_CONVECTIVE_ACCELERATION, SEISMIC_X1, SEISMIC_X2, &
                             SEISMIC_FREE_WAVE, SEISMIC_IMPACT_FORCE, PEAK_INSTANT_ROWS, &
                             PEAK_INSTANTS, PEAKS_WAVE_HEIGHT, PEAKS_FIRST_ROOF_TIME, &
                             PEAKS_ROOF_EXCESS, &
                             PEAKS_FREE_WAVE, PEAKS_ROOF_HEAD, PEAKS_ROOF_UPLIFT, &
                             PEAKS_CONFINED_MASS, PEAKS_IMPACT_FORCE, PEAKS_SCALE_FACTOR, &
                             PEAKS_SA, PEAKS_BETA_SENSITIVE, CODES_COLUMNS, CODES_ROWS, &
                             CODES_SOURCES, HARMONIC_SWEEP_ROWS, TANK_MODES_ROWS, SUMMARY_SIZE, &
                             SUMMARY_RHO, SUMMARY_A, &
                             SUMMARY_MAX_X1, SUMMARY_MAX_X2, SUMMARY_MOTION, SUMMARY_PERIOD
  implicit none
  private
  public :: seismic_response, seismic_responses, seismic_setup, seismic_defaults, design_code_checks, tank_summary
  public :: harmonic_sweep, harmonic_sweep_row, free_periods, max_seismic_outputs, tank_modes
  public :: contact_free, confined_convective_mass, modal_responses, beta_sensitive_force

  !> After a record ends the liquid goes on sloshing: t_end defaults to the record plus this
  !> many sloshing periods; harmonic motion runs this many forcing periods.
  integer, parameter :: free_periods = 5
  !> Outputs per sloshing period and per period of the tank on its supports at least, and at
  !> most this many outputs in all.
  integer, parameter :: outputs_per_period = 50, outputs_per_support_period = 20, &
                        max_seismic_outputs = 10000000
  !> Outputs between two polls of the cancellation flag (sloshdyn_cancel) in the loads loop.
  integer, parameter :: outputs_per_poll = 4096
  !> The model's loads are sensitive to beta and delta when its wall force (impact force) peaks
  !> at this share of the sloshing weight m g or more (docs/model.md, "Choice of beta and delta":
  !> data/studies/beta_sensitivity.csv)
  real(wp), parameter :: beta_sensitive_force = 1.0e-3_wp

  !> The loads of sloshdyn_vessel (rows 2..LOAD_ROWS: ground acceleration to the overturning
  !> moment including the base pressure), then x1, as quantities observed along the
  !> integration, for their peaks and x1's entries into |x1| >= 1 between the steps; from
  !> tau_contact on, the share `share` of the convective mass moves with the tank.
  type, extends(observed_quantities) :: tank_load_observation
    type(tank_t) :: tank
    type(tank_properties) :: props
    type(model_t) :: model
    real(wp) :: share = 0, tau_contact = huge(1.0_wp)
  contains
    procedure :: values => load_values
    procedure :: count => load_count
  end type tank_load_observation

  !> The impact force of the paper's wall, coefficient x1^power [N] (eq 4 over the arm l).
  type, extends(observed_quantities) :: impact_observation
    real(wp) :: coefficient = 0
    integer :: power = 11
  contains
    procedure :: values => impact_values
    procedure :: count => impact_count
  end type impact_observation

contains

  !> t_end [s] and n_out when not given (<= 0): the record plus free_periods sloshing periods
  !> (harmonic: harmonic_periods forcing periods), sampled at the finest of the record's step,
  !> 50 points per sloshing (or forcing) period and 20 per period of the tank on its supports.
  !> With a second component (ground_y, a record across the first), the longer record's end.
  pure subroutine seismic_defaults(props, ground, t_end, n_out, ground_y)
    type(tank_properties), intent(in) :: props
    type(ground_motion_t), intent(in) :: ground
    real(wp), intent(inout) :: t_end
    integer, intent(inout) :: n_out
    type(ground_motion_t), intent(in), optional :: ground_y
    real(wp) :: dt_out, support_frequency, duration
    dt_out = props%sloshing_period/outputs_per_period
    ! the tank on its supports: k/(M L^2) - g/L = (2 pi f_s)^2
    support_frequency = sqrt(max(props%stiffness/(props%total_mass*props%rod_length**2) - &
                                 props%omega**2*props%pendulum_length/props%rod_length, &
                                 0.0_wp))/(2*pi)
    if (support_frequency > 0) dt_out = min(dt_out, 1/(outputs_per_support_period* &
                                                       support_frequency))
    if (ground%kind == GROUND_RECORD) then
      ! the record's own step if it is fine enough, so that outputs fall on its samples
      if (ground%dt <= dt_out) dt_out = ground%dt
      duration = ground_duration(ground)
      if (present(ground_y)) then
        if (ground_y%kind == GROUND_RECORD) duration = max(duration, ground_duration(ground_y))
      end if
      ! a whole number of output steps (a real ceiling: the count may exceed any integer)
      if (t_end <= 0) t_end = dt_out*real_ceiling((duration + free_periods* &
                                                   props%sloshing_period)/dt_out)
    else
      dt_out = min(dt_out, 1/(outputs_per_period*ground%frequency))
      if (t_end <= 0) t_end = harmonic_periods/ground%frequency
    end if
    if (n_out <= 0) n_out = nint(min(t_end/dt_out, real(max_seismic_outputs - 1, wp))) + 1
  end subroutine seismic_defaults

  !> The least whole number >= x (x >= 0), as a real.
  elemental real(wp) function real_ceiling(x)
    real(wp), intent(in) :: x
    real_ceiling = aint(x)
    if (real_ceiling < x) real_ceiling = real_ceiling + 1
  end function real_ceiling

  !> The response of the tank, at rest at t = 0, to the ground motion, at n_out times evenly
  !> spaced over [0, t_end] [s]: table(SEISMIC_ROWS, n_out), the peaks, and at the peaks of the
  !> base shear and of the overturning moments (excluding and including the base pressure) the
  !> accelerations the pressure needs (instants, 'seismic_peak_instants'). On failure the times
  !> reached are filled, the rest NaN. A cancellation request stops it within one integrator
  !> step or outputs_per_poll outputs (SD_CANCELLED).
  !>
  !> The loads are the tank's without contact (beta = delta = 0) until its free wave reaches
  !> the roof, and from the first contact on the restricted-sloshing method's: the confined
  !> convective mass of the run's largest free wave (sloshdyn_roof) moves with the tank
  !> (tank_loads' confined_share); the motion is not integrated again with the new masses. So
  !> no load depends on impact_stiffness or impact_damping. With roof_contact = 'impact' the
  !> paper's model (eq 4-5, the tank's beta and delta) is integrated too, for its impact force
  !> and the beta-sensitivity flag only (docs/model.md, "Loads").
  subroutine seismic_response(tank, ground, t_end, n_out, options, method, table, peaks, &
                              instants, status, message)
    type(tank_t), intent(in) :: tank
    type(ground_motion_t), intent(in) :: ground
    real(wp), intent(in) :: t_end
    integer, intent(in) :: n_out, method
    type(ode_options), intent(in) :: options
    real(wp), intent(out) :: table(SEISMIC_ROWS, n_out), peaks(PEAKS_SIZE), &
                             instants(PEAK_INSTANT_ROWS, PEAK_INSTANTS)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), allocatable :: tables(:, :, :)
    real(wp) :: member_peaks(PEAKS_SIZE, 1), member_instants(PEAK_INSTANT_ROWS, PEAK_INSTANTS, 1)
    integer :: member_status(1)
    character(len=message_len) :: member_message(1)
    call seismic_responses(tank, [ground], t_end, n_out, options, method, tables, member_peaks, &
                           member_instants, member_status, member_message)
    table = tables(:, :, 1)
    peaks = member_peaks(:, 1)
    instants = member_instants(:, :, 1)
    status = member_status(1)
    message = member_message(1)
  end subroutine seismic_response

  !> seismic_response of the tank for every ground motion grounds(i) (one t_end and n_out for
  !> all; issue 43): table(:, :, i), peaks(:, i), instants(:, :, i), status(i) and message(i),
  !> bit for bit those of seismic_response(grounds(i)) alone. The runs are made phase by phase
  !> for all members together -- the free runs, through the ensemble integrator together
  !> (tank_histories); then the loads with the confined mass of the members whose wave reached
  !> the roof, along the free runs' recorded steps (confined_runs: the motion is the same);
  !> then (roof_contact = 'impact') the paper's model, through the ensemble integrator again --
  !> and a member that fails leaves, the others go on. One member runs by the single path.
  !> With ends_only (for callers that want the peaks alone) a tank of one mode is run with
  !> outputs at the start and the end alone, table(:, 1:2, i): its peaks and instants are the
  !> same bit for bit (the trackers' depend on the steps, which the outputs never change, and
  !> on the run's end, the last output kept), without the loads at every output.
  subroutine seismic_responses(tank, grounds, t_end, n_out, options, method, table, peaks, &
                               instants, status, message, ends_only)
    type(tank_t), intent(in) :: tank
    type(ground_motion_t), intent(in) :: grounds(:)
    real(wp), intent(in) :: t_end
    integer, intent(in) :: n_out, method
    type(ode_options), intent(in) :: options
    real(wp), allocatable, intent(out) :: table(:, :, :)
    real(wp), intent(out) :: peaks(:, :), instants(:, :, :)
    integer, intent(out) :: status(:)
    character(len=message_len), intent(out) :: message(:)
    logical, intent(in), optional :: ends_only
    type(model_t) :: models(size(grounds)), free(size(grounds))
    type(tank_properties) :: props, member_props
    real(wp), allocatable :: tau(:), member_tau(:), modal(:, :, :), history(:, :, :)
    real(wp) :: share(size(grounds)), contact(size(grounds))
    type(peak_tracker), allocatable :: tracker(:)
    type(ode_stats), allocatable :: stats(:)
    integer :: i, j, members(size(grounds))
    integer, allocatable :: run(:)
    logical :: keep_ends

    keep_ends = .false.
    if (present(ends_only)) keep_ends = ends_only .and. tank%modes == 1 .and. n_out > 2
    allocate (table(SEISMIC_ROWS, merge(2, max(n_out, 0), keep_ends), size(grounds)))
    table = ieee_value(1.0_wp, ieee_quiet_nan)
    peaks = ieee_value(1.0_wp, ieee_quiet_nan)
    instants = 0
    members = [(i, i = 1, size(grounds))]
    ! the tank's properties and the output times are the same for every member
    do i = 1, size(grounds)
      call seismic_setup(tank, grounds(i), t_end, n_out, models(i), member_props, member_tau, &
                         status(i), message(i))
      if (status(i) /= SD_OK) cycle
      free(i) = contact_free(models(i))
      props = member_props
      tau = member_tau
    end do
    if (all(status /= SD_OK)) return
    if (keep_ends) tau = [tau(1), tau(size(tau))]
    allocate (modal(size(tau), props%modes, size(grounds)))
    share = 0
    contact = huge(1.0_wp)
    run = pack(members, status == SD_OK)
    allocate (history(HISTORY_ROWS, size(tau), size(run)), tracker(size(run)), stats(size(run)))
    call free_runs(tank, props, free, tau, options, method, run, history, tracker, stats, table, &
                   peaks, instants, modal, status, message)
    ! the roof: where the free wave reaches it, the confined mass of its largest height
    do i = 1, size(grounds)
      if (status(i) /= SD_OK) cycle
      if (peaks(PEAKS_ROOF_REACHED, i) > 0) then
        call confined_convective_mass(tank, props, peaks(PEAKS_FREE_WAVE, i), &
                                      peaks(PEAKS_ROOF_HEAD, i), peaks(PEAKS_ROOF_UPLIFT, i), &
                                      peaks(PEAKS_CONFINED_MASS, i), status(i), message(i))
        if (status(i) /= SD_OK) cycle
        share(i) = peaks(PEAKS_CONFINED_MASS, i)/props%sloshing_mass
        contact(i) = props%omega*peaks(PEAKS_FIRST_ROOF_TIME, i)
      else
        peaks(PEAKS_ROOF_HEAD:PEAKS_CONFINED_MASS, i) = 0
      end if
    end do
    call confined_runs(tank, props, free, tau, share, contact, &
                       pack(members, status == SD_OK .and. share > 0), run, history, tracker, &
                       stats, table, peaks, instants, modal, status, message)
    do i = 1, size(grounds)
      if (status(i) /= SD_OK) cycle
      ! the wave with the roof: the free wave, capped at the freeboard
      do j = 1, size(tau)
        table(SEISMIC_WAVE_HEIGHT, j, i) = sign(min(abs(table(SEISMIC_FREE_WAVE, j, i)), &
                                                    tank%freeboard), table(SEISMIC_FREE_WAVE, j, i))
      end do
      peaks(PEAKS_WAVE_HEIGHT, i) = min(peaks(PEAKS_FREE_WAVE, i), tank%freeboard)
      if (peaks(PEAKS_ROOF_REACHED, i) > 0) &
        peaks(PEAKS_WAVE_HEIGHT + 1, i) = peaks(PEAKS_FIRST_ROOF_TIME, i)
      peaks(PEAKS_SCALE_FACTOR, i) = grounds(i)%scale_factor
      call spectral_acceleration(grounds(i), props%sloshing_period, convective_damping, &
                                 peaks(PEAKS_SA, i), status(i), message(i))
    end do
    if (tank%roof_contact == ROOF_CONTACT_IMPACT) &
      call impact_runs(tank, props, models, tau, options, method, pack(members, status == SD_OK), &
                       table, peaks, status, message)
  end subroutine seismic_responses

  !> The model of the tank without a roof: no wall (beta = delta = 0), the same supports and
  !> damping.
  pure function contact_free(model) result(free)
    type(model_t), intent(in) :: model
    type(model_t) :: free
    free = model
    free%beta = 0
    free%delta = 0
    call set_coefficients(free)
  end function contact_free

  !> The free tanks' runs (models free(j)) over the output times tau of the members j =
  !> run(c), together (tank_histories), their time histories into history(:, :, c) and their
  !> trackers, with the steps they took in, into tracker(c) (for confined_runs); for each,
  !> free_results into table(:, :, j), peaks(:, j), instants(:, :, j), modal(:, :, j). With one
  !> mode the peaks and the first contact are located between the integrator's steps
  !> (peak_tracker) of the loads and of x1 reaching 1 (the free wave at the freeboard; none
  !> where theta0 is capped: the linear wave cannot reach a freeboard above 2 R/(xi^2 - 1)).
  subroutine free_runs(tank, props, free, tau, options, method, run, history, tracker, stats, &
                       table, peaks, instants, modal, status, message)
    type(tank_t), intent(in) :: tank
    type(tank_properties), intent(in) :: props
    type(model_t), intent(in) :: free(:)
    real(wp), intent(in) :: tau(:)
    type(ode_options), intent(in) :: options
    integer, intent(in) :: method, run(:)
    real(wp), intent(out) :: history(:, :, :)
    type(peak_tracker), intent(out) :: tracker(:)
    type(ode_stats), intent(out) :: stats(:)
    real(wp), intent(inout) :: table(:, :, :), peaks(:, :), instants(:, :, :), modal(:, :, :)
    integer, intent(inout) :: status(:)
    character(len=message_len), intent(inout) :: message(:)
    type(tank_load_observation) :: loads(size(run))
    integer :: c, run_status(size(run))
    character(len=message_len) :: run_message(size(run))

    if (size(run) == 0) return
    do c = 1, size(run)
      loads(c) = tank_load_observation(tank, props, free(run(c)), 0.0_wp, huge(1.0_wp))
      call prepare_tracker(props, tracker(c))
      ! for confined_runs, where the roof can be reached (one mode: the tracker's level of x1,
      ! whose first entry is the contact: before it the confined run's loads are these)
      tracker(c)%record_steps = props%roof_reachable .or. props%modes > 1
      if (props%roof_reachable .and. props%modes == 1) tracker(c)%rewind_quantity = LOAD_ROWS
    end do
    call tank_histories(free(run), spread(0.0_wp, 1, size(run)), &
                        spread([0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], 2, size(run)), &
                        spread(tau, 2, size(run)), options, method, history, stats, run_status, &
                        run_message, loads, tracker)
    do c = 1, size(run)
      associate (j => run(c))
        call free_results(tank, props, free(j), tau, loads(c), tracker(c), stats(c), &
                          history(:, :, c), run_status(c), run_message(c), table(:, :, j), &
                          peaks(:, j), instants(:, :, j), modal(:, :, j), status(j), message(j))
      end associate
    end do
  end subroutine free_runs

  !> The free runs of the members j = run(:) again with the share share(j) of the convective
  !> mass moving with the tank from tau_contact(j) on (tank_loads' confined_share): the
  !> tank's motion is the free run's, only the loads change, so the steps that free_runs'
  !> tracker took in (tracker(c) of member free_run(c) = j) are observed again with these loads
  !> (peak_tracker's replay), bit for bit as integrating again, and free_results takes the
  !> free run's history and statistics (up to the step a failed replay reached).
  subroutine confined_runs(tank, props, free, tau, share, tau_contact, run, free_run, history, &
                           tracker, stats, table, peaks, instants, modal, status, message)
    type(tank_t), intent(in) :: tank
    type(tank_properties), intent(in) :: props
    type(model_t), intent(in) :: free(:)
    real(wp), intent(in) :: tau(:), share(:), tau_contact(:), history(:, :, :)
    integer, intent(in) :: run(:), free_run(:)
    type(peak_tracker), intent(in) :: tracker(:)
    type(ode_stats), intent(in) :: stats(:)
    real(wp), intent(inout) :: table(:, :, :), peaks(:, :), instants(:, :, :), modal(:, :, :)
    integer, intent(inout) :: status(:)
    character(len=message_len), intent(inout) :: message(:)
    type(tank_load_observation) :: loads
    type(peak_tracker) :: confined
    type(ode_stats) :: reached
    integer :: c, i, replay_status
    character(len=message_len) :: replay_message

    do i = 1, size(run)
      associate (j => run(i))
        c = findloc(free_run, j, dim=1)
        loads = tank_load_observation(tank, props, free(j), share(j), tau_contact(j))
        call prepare_tracker(props, confined)
        reached = stats(c)
        ! from rest at tau = 0 over [0, tau(end)], as free_runs' tank_histories
        call confined%replay(tracker(c)%steps, loads, 0.0_wp, [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], &
                             0.0_wp, tau(size(tau)), replay_status, replay_message, &
                             reached%t_reached, before=tau_contact(j))
        call free_results(tank, props, free(j), tau, loads, confined, reached, &
                          history(:, :, c), replay_status, replay_message, table(:, :, j), &
                          peaks(:, j), instants(:, :, j), modal(:, :, j), status(j), message(j))
      end associate
    end do
  end subroutine confined_runs

  !> A tracker of a free run's loads (tank_load_observation), with the state at each peak and
  !> the level 1 of x1 (the wave at the freeboard) where the roof can be reached.
  subroutine prepare_tracker(props, tracker)
    type(tank_properties), intent(in) :: props
    type(peak_tracker), intent(out) :: tracker
    allocate (tracker%level(LOAD_ROWS))
    tracker%level = 0
    if (props%roof_reachable) tracker%level(LOAD_ROWS) = 1
    tracker%keep_states = .true.
  end subroutine prepare_tracker

  !> A free run's results from its time history (its status run_status, run_message): the
  !> 'seismic' table's rows 1..SEISMIC_FREE_WAVE, the loads' peaks, the roof verdict of the
  !> free wave (the first time its height at the wall reaches the freeboard, its entries and
  !> its largest height) and the accelerations at the load peaks; modal(:, n) the absolute
  !> accelerations of the modes at the outputs. With one mode the peaks are the tracker's; with
  !> N > 1 modes the free wave at the wall is mode 1's plus the linear waves of modes 2..N
  !> driven by the free tank's acceleration (modal_responses), known at the output times: the
  !> peaks and the verdict are then read there (sampled_roof).
  subroutine free_results(tank, props, free, tau, loads, tracker, stats, history, run_status, &
                          run_message, table, peaks, instants, modal, status, message)
    type(tank_t), intent(in) :: tank
    type(tank_properties), intent(in) :: props
    type(model_t), intent(in) :: free
    real(wp), intent(in) :: tau(:), history(:, :)
    type(tank_load_observation), intent(in) :: loads
    type(peak_tracker), intent(in) :: tracker
    type(ode_stats), intent(in) :: stats
    integer, intent(in) :: run_status
    character(len=message_len), intent(in) :: run_message
    real(wp), intent(inout) :: table(:, :), peaks(:), instants(:, :), modal(:, :)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: freeboard
    integer :: i, k
    integer, parameter :: peak_rows(PEAK_INSTANTS) = [SEISMIC_BASE_SHEAR, &
      SEISMIC_OVERTURNING_MOMENT, SEISMIC_OVERTURNING_MOMENT_IBP]

    status = run_status
    message = run_message
    do i = 1, size(tau)
      if (tau(i) > stats%t_reached) exit
      if (mod(i, outputs_per_poll) == 0) call check_cancel(status, message)
      if (status == SD_CANCELLED) exit
      call loads%values(tau(i), history(1:4, i), table(2:LOAD_ROWS + 1, i))
      table(1, i) = tau(i)/props%omega
      table(SEISMIC_X1:SEISMIC_X2, i) = history([1, 3], i)
      modal(i, 1) = table(SEISMIC_CONVECTIVE_ACCELERATION, i)
    end do
    if (status /= SD_OK) return
    freeboard = tank%freeboard
    do i = 1, LOAD_ROWS - 1
      peaks(2*i - 1:2*i) = [tracker%peak(i), tracker%time(i)/props%omega]
    end do
    if (props%modes == 1) then
      peaks(PEAKS_ROOF_REACHED:PEAKS_FREE_WAVE) = [merge(1.0_wp, 0.0_wp, &
        tracker%crossings(LOAD_ROWS) > 0), tracker%first_crossing(LOAD_ROWS)/props%omega, &
        real(tracker%crossings(LOAD_ROWS), wp), &
        props%wave_factor*sin(min(free%theta0*tracker%peak(LOAD_ROWS), pi/2))]
      ! the accelerations at the load peaks, from the state there
      do k = 1, PEAK_INSTANTS
        associate (y => tracker%state(:, peak_rows(k) - 1), t => tracker%time(peak_rows(k) - 1))
          instants(1:3, k) = [t/props%omega, loads_at(t, y, SEISMIC_TANK_ACCELERATION), &
                              loads_at(t, y, SEISMIC_CONVECTIVE_ACCELERATION)]
        end associate
      end do
      table(SEISMIC_FREE_WAVE, :) = table(SEISMIC_WAVE_HEIGHT, :)
    else
      call add_higher_modes(props, tank%sloshing_damping, table, peaks, modal, status, message)
      if (status /= SD_OK) return
      table(SEISMIC_FREE_WAVE, :) = table(SEISMIC_WAVE_HEIGHT, :)
      peaks(PEAKS_ROOF_REACHED:PEAKS_FREE_WAVE) = sampled_roof(table(SEISMIC_FREE_WAVE, :), &
                                                               table(1, :), freeboard)
      do k = 1, PEAK_INSTANTS
        i = maxloc(abs(table(peak_rows(k), :)), dim=1)
        instants(1:2, k) = table([1, SEISMIC_TANK_ACCELERATION], i)
        instants(3:2 + props%modes, k) = modal(i, :)
      end do
    end if
    peaks(PEAKS_ROOF_EXCESS) = peaks(PEAKS_FREE_WAVE) - freeboard

  contains

    !> Row `row` of the 'seismic' table of the state y at tau.
    real(wp) function loads_at(t, y, row)
      real(wp), intent(in) :: t, y(:)
      integer, intent(in) :: row
      real(wp) :: values(LOAD_ROWS)
      call loads%values(t, y, values)
      loads_at = values(row - 1)
    end function loads_at
  end subroutine free_results

  !> The restricted-sloshing method's roof loads of the largest free wave d at the wall
  !> (sloshdyn_roof): the head d - f, the uplift on the roof and the confined convective mass
  !> (circular tanks: flat, cone and dome roofs; rectangular tanks: a flat roof).
  subroutine confined_convective_mass(tank, props, wave, head, uplift, confined, status, &
                                      message)
    type(tank_t), intent(in) :: tank
    type(tank_properties), intent(in) :: props
    real(wp), intent(in) :: wave
    real(wp), intent(out) :: head, uplift, confined
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    if (tank%shape == SHAPE_CIRCULAR) then
      call roof_loads(tank%radius, tank%freeboard, tank%roof_slope, tank%roof_radius, wave, &
                      props%liquid_mass/(pi*tank%radius**2*tank%liquid_depth), tank%gravity, &
                      props%sloshing_mass, head, uplift, confined, status, message)
    else
      call rectangular_roof_loads(tank%length, tank%width, tank%freeboard, wave, &
                                  props%liquid_mass/(tank%length*tank%width*tank%liquid_depth), &
                                  tank%gravity, props%sloshing_mass, head, uplift, confined, &
                                  status, message)
    end if
  end subroutine confined_convective_mass

  !> The paper's impact model (roof_contact = 'impact': the tank's beta and delta, eq 4-5) of
  !> the members j = run(:) over the output times, together (tank_histories): its impact force
  !> b x1^(2n-1)/l [N] at the outputs (table's row SEISMIC_IMPACT_FORCE), its peak, and whether
  !> the model's own loads would be sensitive to beta and delta (its wall force reaches
  !> beta_sensitive_force m g; docs/model.md, "Choice of beta and delta"). Labelled as the
  !> paper's model; it feeds no load, design row or calc sheet.
  subroutine impact_runs(tank, props, models, tau, options, method, run, table, peaks, status, &
                         message)
    type(tank_t), intent(in) :: tank
    type(tank_properties), intent(in) :: props
    type(model_t), intent(in) :: models(:)
    real(wp), intent(in) :: tau(:)
    type(ode_options), intent(in) :: options
    integer, intent(in) :: method, run(:)
    real(wp), intent(inout) :: table(:, :, :), peaks(:, :)
    integer, intent(inout) :: status(:)
    character(len=message_len), intent(inout) :: message(:)
    type(impact_observation) :: impact(size(run))
    type(peak_tracker) :: tracker(size(run))
    type(ode_stats) :: stats(size(run))
    real(wp), allocatable :: history(:, :, :)
    real(wp) :: value(1)
    integer :: c, i, run_status(size(run))
    character(len=message_len) :: run_message(size(run))
    if (size(run) == 0) return
    allocate (history(HISTORY_ROWS, size(tau), size(run)))
    do c = 1, size(run)
      impact(c) = impact_observation(props%impact_coefficient/props%pendulum_length, &
                                     2*models(run(c))%n - 1)
    end do
    call tank_histories(models(run), spread(0.0_wp, 1, size(run)), &
                        spread([0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], 2, size(run)), &
                        spread(tau, 2, size(run)), options, method, history, stats, &
                        run_status, run_message, impact, tracker)
    do c = 1, size(run)
      associate (j => run(c))
        status(j) = run_status(c)
        if (status(j) /= SD_OK) then
          message(j) = 'the paper''s impact model (roof_contact = ''impact''): '// &
                       trim(run_message(c))
          cycle
        end if
        do i = 1, size(tau)
          call impact(c)%values(tau(i), history(1:4, i, c), value)
          table(SEISMIC_IMPACT_FORCE, i, j) = value(1)
        end do
        peaks(PEAKS_IMPACT_FORCE:PEAKS_IMPACT_FORCE + 1, j) = [tracker(c)%peak(1), &
                                                               tracker(c)%time(1)/props%omega]
        peaks(PEAKS_BETA_SENSITIVE, j) = merge(1.0_wp, 0.0_wp, tracker(c)%peak(1) >= &
                                               beta_sensitive_force*props%sloshing_mass* &
                                               tank%gravity)
      end associate
    end do
  end subroutine impact_runs

  !> What every seismic response sets up first (seismic_response, and sloshdyn_seismic_spatial's
  !> seismic_response_spatial): the tank's model driven by the ground motion, t_end > 0 [s],
  !> n_out in [2, max_seismic_outputs], and the output times tau (the model's time, tau =
  !> omega t) evenly spaced over [0, t_end].
  subroutine seismic_setup(tank, ground, t_end, n_out, model, props, tau, status, message)
    type(tank_t), intent(in) :: tank
    type(ground_motion_t), intent(in) :: ground
    real(wp), intent(in) :: t_end
    integer, intent(in) :: n_out
    type(model_t), intent(out) :: model
    type(tank_properties), intent(out) :: props
    real(wp), allocatable, intent(out) :: tau(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    integer :: i
    call tank_model(tank, model, props, status, message)
    if (status == SD_OK) call ground_excitation(ground, props%omega, props%rod_length, &
                                                model%excitation, status, message)
    call check_real('t_end', t_end, 0.0_wp, huge(1.0_wp), .true., .true., &
                    't_end must be > 0 [s]', status, message)
    call check_output_count('n_out', n_out, max_seismic_outputs, .false., status, message)
    if (status /= SD_OK) return
    tau = [(props%omega*t_end*(i - 1)/(n_out - 1), i = 1, n_out)]
  end subroutine seismic_setup

  !> Modes 2..N of the tank (props%modes = N > 1) in the time histories: modal_responses on
  !> the model's run, added to the wave height, base shear and overturning moment rows of the
  !> table, whose peaks are then the largest at the output times; modal(:, 2:N) the modes'
  !> absolute accelerations at the outputs [m/s^2].
  subroutine add_higher_modes(props, damping, table, peaks, modal, status, message)
    type(tank_properties), intent(in) :: props
    real(wp), intent(in) :: damping
    real(wp), intent(inout) :: table(:, :), peaks(:), modal(:, :)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    integer, parameter :: summed(4) = [SEISMIC_WAVE_HEIGHT, SEISMIC_BASE_SHEAR, &
                                       SEISMIC_OVERTURNING_MOMENT, &
                                       SEISMIC_OVERTURNING_MOMENT_IBP]
    integer :: i, n, row
    call modal_responses(props, damping, table(1, :), table(SEISMIC_TANK_ACCELERATION, :), &
                         table(SEISMIC_WAVE_HEIGHT, :), status, message, &
                         table(SEISMIC_BASE_SHEAR, :), table(SEISMIC_OVERTURNING_MOMENT, :), &
                         table(SEISMIC_OVERTURNING_MOMENT_IBP, :), modal)
    if (status /= SD_OK) return
    do n = 1, size(summed)
      row = summed(n)
      i = maxloc(abs(table(row, :)), dim=1)
      peaks(2*row - 3:2*row - 2) = [abs(table(row, i)), table(1, i)]
    end do
  end subroutine add_higher_modes

  !> Modes 2..N of the tank (props%modes = N > 1) along a run of the model (the tank's
  !> acceleration accel [m/s^2] at the evenly spaced times t [s]): each a linear oscillator
  !> x_n'' + 2 zeta omega_n x_n' + omega_n^2 x_n = -a_t(t) on the tank's acceleration a_t (of
  !> the model, which counts m_2..m_N as rigid: their reaction on the tank is left
  !> out), a_t linear between the output times and each x_n exact for that (Nigam & Jennings,
  !> sloshdyn_sdof). Added to the wave height at the wall (wave_n x_n/l_n, the linear wave of
  !> sloshdyn_tank) and, when given, the base shear (m_n x_n''), the overturning moment
  !> (m_n h_n (a_t + x_n''), the model's rigid mass at its height having left them out) and the
  !> moment with the base pressure (m_n (h_n' - h_n) x_n'' more); modal(:, n) = a_t + x_n''.
  subroutine modal_responses(props, damping, t, accel, wave, status, message, shear, moment, &
                             moment_ibp, modal)
    type(tank_properties), intent(in) :: props
    real(wp), intent(in) :: damping, t(:), accel(size(t))
    real(wp), intent(inout) :: wave(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), intent(inout), optional :: shear(:), moment(:), moment_ibp(:), modal(:, :)
    real(wp) :: x(size(t)), v(size(t)), a_abs(size(t))
    integer :: n
    status = SD_OK
    message = ''
    if (size(t) < 2) return
    do n = 2, props%modes
      call sdof_response(t(2) - t(1), accel, 2*pi/props%modal_period(n), damping, &
                         0.0_wp, 0.0_wp, x, v, a_abs, status, message)
      if (status /= SD_OK) return
      wave = wave + props%modal_wave(n)*x/props%modal_length(n)
      if (present(shear)) shear = shear + props%modal_mass(n)*(a_abs - accel)
      if (present(moment)) moment = moment + props%modal_mass(n)*props%modal_height(n)*a_abs
      if (present(moment_ibp)) moment_ibp = moment_ibp + props%modal_mass(n)* &
        (props%modal_height(n)*a_abs + (props%modal_height_ibp(n) - props%modal_height(n))* &
         (a_abs - accel))
      if (present(modal)) modal(:, n) = a_abs
    end do
  end subroutine modal_responses

  !> The loads (rows 2..LOAD_ROWS of tank_loads) and x1 of the state y at tau.
  pure subroutine load_values(self, t, y, g)
    class(tank_load_observation), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: g(:)
    real(wp) :: dydt(4), angles(4), xdd, row(LOAD_ROWS)
    call equations_of_motion(self%model, t, y(1:4), dydt, angles, xdd)
    row = tank_loads(self%tank, self%props, self%model, t, y(1:4), dydt, angles, &
                     self%props%rod_length*self%props%omega**2*xdd, &
                     merge(self%share, 0.0_wp, t >= self%tau_contact))
    g(1:LOAD_ROWS - 1) = row(2:LOAD_ROWS)
    g(LOAD_ROWS) = y(1)
  end subroutine load_values

  pure integer function load_count(self)
    class(tank_load_observation), intent(in) :: self
    load_count = LOAD_ROWS
  end function load_count

  pure subroutine impact_values(self, t, y, g)
    class(impact_observation), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: g(:)
    g(1) = self%coefficient*y(1)**self%power
  end subroutine impact_values

  pure integer function impact_count(self)
    class(impact_observation), intent(in) :: self
    impact_count = 1
  end function impact_count

  !> The roof verdict of a wave eta at the wall sampled at the times t [s], against the
  !> freeboard f: [reached (1/0), the first time |eta| reaches f (linear between the samples;
  !> NaN: never), the entries of |eta| into [f, inf) (a first sample there counts, as
  !> peak_tracker's), the largest |eta| [m]].
  pure function sampled_roof(eta, t, freeboard) result(roof)
    real(wp), intent(in) :: eta(:), t(:), freeboard
    real(wp) :: roof(4)
    logical :: above(size(eta))
    integer :: i
    above = abs(eta) >= freeboard
    i = findloc(above, .true., dim=1)
    roof = [merge(1.0_wp, 0.0_wp, i > 0), ieee_value(1.0_wp, ieee_quiet_nan), &
            real(count(above(2:) .and. .not. above(:size(eta) - 1)) + merge(1, 0, above(1)), wp), &
            maxval(abs(eta))]
    if (i == 1) then
      roof(2) = t(1)
    else if (i > 1) then
      roof(2) = t(i - 1) + (t(i) - t(i - 1))*(freeboard - abs(eta(i - 1)))/ &
                (abs(eta(i)) - abs(eta(i - 1)))
    end if
  end function sampled_roof

  !> The tank's sloshing parameters by sloshdyn's model and by the design codes, one row per
  !> source (sloshdyn, API 650, EC8-4, ACI 350.3) in the 'design_codes' layout: convective
  !> period [s], convective and impulsive liquid masses [kg], their heights above the bottom
  !> (EBP) [m], and the wave height [m] from the ground motion's pseudo-spectral acceleration
  !> (or, given, a code design spectrum's spectral acceleration) at
  !> each source's convective period, at the tank's sloshing damping ratio (NaN where a code
  !> gives no value; EC8-4's impulsive mass and height: Annex A.2.1's series, ec8_impulsive).
  !> sloshdyn's wave height is the linear one of its model: 2 R/(xi^2 - 1) Sa/g (4 L/pi^2 Sa/g
  !> for a rectangular tank). A rectangular tank: API 650 (cylinders only) gives NaN; ACI 350.3
  !> its rectangular equations (9-1 to 9-11, 7-1); for EN 1998-4 the rectangular clause's
  !> formulas were not at hand, so its row is the first mode of linear potential flow
  !> (sloshdyn_tank's sloshing_modes: the same as sloshdyn's row; no IBP height), not the code.
  subroutine design_code_checks(tank, ground, has_ground, codes, status, message, spectrum)
    type(tank_t), intent(in) :: tank
    type(ground_motion_t), intent(in) :: ground
    logical, intent(in) :: has_ground
    real(wp), intent(out) :: codes(CODES_COLUMNS, CODES_ROWS)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    !> a code design spectrum in place of the ground motion's (sloshdyn_design_spectra)
    type(design_spectrum_t), intent(in), optional :: spectrum
    type(model_t) :: model
    type(tank_properties) :: props
    type(api650_parameters) :: api
    type(ec8_parameters) :: ec8
    type(aci350_parameters) :: aci
    real(wp) :: periods(CODES_SOURCES), wave(CODES_SOURCES), modal_waves(max_modes), nan

    nan = ieee_value(1.0_wp, ieee_quiet_nan)
    codes = nan
    call tank_model(tank, model, props, status, message)
    if (status /= SD_OK) return
    if (tank%shape == SHAPE_CIRCULAR) then
      call api650_circular(tank%radius, tank%liquid_depth, api, status, message)
      if (status == SD_OK) call ec8_circular(tank%radius, tank%liquid_depth, tank%gravity, ec8, &
                                             status, message)
      if (status == SD_OK) call aci350_circular(tank%radius, tank%liquid_depth, tank%gravity, &
                                                aci, status, message)
    else
      api = api650_parameters(nan, nan, nan, nan, nan, nan, nan, nan)
      ec8 = ec8_parameters(props%omega, props%sloshing_period, &
                           props%sloshing_mass/props%liquid_mass, props%convective_height, nan, &
                           nan, nan, nan)
      call aci350_rectangular(tank%length, tank%liquid_depth, tank%gravity, aci, status, message)
    end if
    if (status /= SD_OK) return
    periods = [props%sloshing_period, api%convective_period, ec8%convective_period, &
               aci%convective_period]
    wave = nan
    modal_waves = nan
    if (has_ground .or. present(spectrum)) call code_wave_heights()
    if (status /= SD_OK) return
    if (props%modes > 1) codes(:, CODES_SOURCES + 1:) = modal_sums(props, &
                                                                   modal_waves(1:props%modes))
    associate (mf => props%liquid_mass)
      codes(:, 1) = [periods(1), props%sloshing_mass, props%rigid_mass, &
                     props%convective_height, props%impulsive_height, wave(1)]
      codes(:, 2) = [periods(2), api%convective_ratio*mf, api%impulsive_ratio*mf, &
                     api%convective_height, api%impulsive_height, wave(2)]
      codes(:, 3) = [periods(3), ec8%convective_ratio*mf, ec8%impulsive_ratio*mf, &
                     ec8%convective_height, ec8%impulsive_height, wave(3)]
      codes(:, 4) = [periods(4), aci%convective_ratio*mf, aci%impulsive_ratio*mf, &
                     aci%convective_height, aci%impulsive_height, wave(4)]
    end associate

  contains

    !> Each source's wave height from the pseudo-spectral acceleration at its period.
    subroutine code_wave_heights()
      real(wp), dimension(CODES_SOURCES + max_modes - 1) :: spectrum_periods, sd, sv, psa
      integer :: n, i
      ! a source without a period (API 650 for a rectangular tank) asks for sloshdyn's; then
      ! the periods of modes 2..N
      n = CODES_SOURCES + props%modes - 1
      spectrum_periods(1:CODES_SOURCES) = merge(periods, periods(1), periods == periods)
      spectrum_periods(CODES_SOURCES + 1:n) = props%modal_period(2:props%modes)
      if (present(spectrum)) then
        do i = 1, n
          call spectrum_sa(spectrum, spectrum_periods(i), tank%sloshing_damping, psa(i), &
                           status, message)
          if (status /= SD_OK) exit
        end do
        psa(1:n) = psa(1:n)*tank%gravity
      else
        call ground_spectrum(ground, spectrum_periods(1:n), tank%sloshing_damping, &
                             free_periods*maxval(spectrum_periods(1:CODES_SOURCES)), 0.0_wp, &
                             sd(1:n), sv(1:n), psa(1:n), status, message)
      end if
      if (status /= SD_OK) then
        message = 'the spectrum for the design codes: '//trim(message)
        return
      end if
      wave(1) = props%wave_factor*psa(1)/tank%gravity
      modal_waves(1) = wave(1)
      modal_waves(2:props%modes) = props%modal_wave(2:props%modes)*psa(CODES_SOURCES + 1:n)/ &
                                   tank%gravity
      if (tank%shape == SHAPE_CIRCULAR) then
        call api650_wave_height(tank%radius, psa(2)/tank%gravity, wave(2), status, message)
        if (status == SD_OK) call ec8_wave_height(tank%radius, psa(3), tank%gravity, wave(3), &
                                                  status, message)
        if (status == SD_OK) call aci350_wave_height(tank%radius, psa(4), tank%gravity, 1.0_wp, &
                                                     wave(4), status, message)
      else
        wave(3) = props%wave_factor*psa(3)/tank%gravity
        call aci350_wave_height(tank%length/2, psa(4), tank%gravity, 1.0_wp, wave(4), status, &
                                message)
      end if
    end subroutine code_wave_heights
  end subroutine design_code_checks

  !> sloshdyn's sums over the sloshing modes 1..N, the rows 'modes SRSS' and 'modes ABS' of
  !> 'design_codes': no one period (NaN); the convective mass sum(m_n) at its resultant height
  !> sum(m_n h_n)/sum(m_n); the rigid mass m0 and its height h0 (the tank's, m_F minus the N
  !> modal masses); the wave height at the wall, waves(n) = w_n Sa(T_n)/g of each mode (NaN
  !> without ground motion), combined by the square root of the sum of squares (the usual
  !> combination of modal peaks of well separated modes) and by the sum of absolute values (an
  !> upper bound).
  pure function modal_sums(props, waves) result(rows)
    type(tank_properties), intent(in) :: props
    real(wp), intent(in) :: waves(:)
    real(wp) :: rows(CODES_COLUMNS, 2)
    real(wp) :: mass, height
    associate (n => props%modes)
      mass = sum(props%modal_mass(1:n))
      height = dot_product(props%modal_mass(1:n), props%modal_height(1:n))/mass
    end associate
    rows(:, 1) = [ieee_value(1.0_wp, ieee_quiet_nan), mass, props%rigid_mass, height, &
                  props%impulsive_height, sqrt(sum(waves**2))]
    rows(:, 2) = [rows(1:5, 1), sum(abs(waves))]
  end function modal_sums

  !> Steady states of the tank under harmonic ground motion at each of the frequencies [Hz], at
  !> the ground motion's peak acceleration (a sweep in rho at constant A rho^2 through
  !> sloshdyn_simulation: from the previous point's final state when carry_state, else each
  !> from y0 on `threads` threads, identical for any number). summaries: the dimensionless
  !> 'summary' layout; table: the same in SI ('harmonic_sweep' layout); y_final: the state after
  !> the last point (carried sweeps continue from it).
  subroutine harmonic_sweep(tank, ground, frequencies, y0, options, method, steady, &
                            carry_state, threads, summaries, table, y_final, n_done, status, &
                            message)
    type(tank_t), intent(in) :: tank
    type(ground_motion_t), intent(in) :: ground
    real(wp), intent(in) :: frequencies(:), y0(4)
    type(ode_options), intent(in) :: options
    integer, intent(in) :: method, threads
    type(steady_options), intent(in) :: steady
    logical, intent(in) :: carry_state
    real(wp), intent(out) :: summaries(SUMMARY_SIZE, size(frequencies)), &
                             table(HARMONIC_SWEEP_ROWS, size(frequencies)), y_final(4)
    integer, intent(out) :: n_done, status
    character(len=message_len), intent(out) :: message
    type(model_t) :: model
    type(tank_properties) :: props
    real(wp) :: rho(size(frequencies)), free_max_x1(size(frequencies))
    integer :: i

    summaries = 0
    table = 0
    y_final = y0
    n_done = 0
    call tank_model(tank, model, props, status, message)
    if (status == SD_OK .and. ground%kind /= GROUND_HARMONIC) then
      status = SD_BAD_INPUT
      message = 'a sweep in frequency needs harmonic ground motion (peak_acceleration), not a '// &
                'record'
    end if
    if (status == SD_OK) call ground_excitation(ground, props%omega, props%rod_length, &
                                                model%excitation, status, message)
    if (status /= SD_OK) return
    rho = 2*pi*frequencies/props%omega
    if (carry_state) then
      call parameter_sweep(model, PARAMETER_FREQUENCY, rho, y0, options, method, steady, &
                           summaries, y_final, n_done, status, message)
    else
      call independent_sweep(model, PARAMETER_FREQUENCY, rho, y0, options, method, steady, &
                             threads, summaries, n_done, status, message)
    end if
    ! the free wave's verdict for the points done (NaN where the sweep failed before it): the
    ! sweep's own steady states, the tank's model being free; with the paper's impact model
    ! (roof_contact = 'impact') those of the tank without a roof, from rest
    free_max_x1 = ieee_value(1.0_wp, ieee_quiet_nan)
    free_max_x1(1:n_done) = summaries(SUMMARY_MAX_X1, 1:n_done)
    if (status == SD_OK .and. n_done > 0 .and. tank%roof_contact == ROOF_CONTACT_IMPACT) then
      call free_steady_waves(model, rho(1:n_done), options, method, steady, threads, &
                             free_max_x1(1:n_done), status, message)
      if (status /= SD_OK) n_done = 0
    end if
    do i = 1, n_done
      table(:, i) = harmonic_sweep_row(props, model%theta0, frequencies(i), summaries(:, i), &
                                       free_max_x1(i), tank%roof_contact /= ROOF_CONTACT_IMPACT)
    end do
  end subroutine harmonic_sweep

  !> The roof verdict of a sweep on the free wave, as seismic_response's roof_contact: max|x1|
  !> of the steady state of the tank without a roof (beta = delta = 0, the same supports and
  !> damping) at each rho, each from rest, so that the verdict does not depend on the contact
  !> model.
  subroutine free_steady_waves(model, rho, options, method, steady, threads, free_max_x1, &
                               status, message)
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: rho(:)
    type(ode_options), intent(in) :: options
    integer, intent(in) :: method, threads
    type(steady_options), intent(in) :: steady
    real(wp), intent(out) :: free_max_x1(size(rho))
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(model_t) :: free
    real(wp) :: summaries(SUMMARY_SIZE, size(rho))
    integer :: n_done
    free = model
    free%beta = 0
    free%delta = 0
    call set_coefficients(free)
    call independent_sweep(free, PARAMETER_FREQUENCY, rho, [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], &
                           options, method, steady, threads, summaries, n_done, status, message)
    if (status /= SD_OK) message = 'the free wave (no roof, for the roof verdict): '// &
                                   trim(message)
    free_max_x1 = summaries(SUMMARY_MAX_X1, :)
  end subroutine free_steady_waves

  !> A steady-state summary in SI ('harmonic_sweep' layout): the largest wave height (capped at
  !> the roof when `capped`: the free tank's wave), sloshing displacement and pendulum angle
  !> from max|x1|, the tank drift from max|x2|, whether the wave reaches the roof (the free
  !> wave's max|x1| >= 1), the kind of motion, its period and the free wave's largest height at
  !> the wall.
  pure function harmonic_sweep_row(props, theta0, frequency, summary, free_max_x1, capped) &
    result(row)
    type(tank_properties), intent(in) :: props
    real(wp), intent(in) :: theta0, frequency, summary(SUMMARY_SIZE), free_max_x1
    logical, intent(in) :: capped
    real(wp) :: row(HARMONIC_SWEEP_ROWS)
    real(wp) :: theta
    theta = theta0*summary(SUMMARY_MAX_X1)
    row = [frequency, summary(SUMMARY_A)*summary(SUMMARY_RHO)**2*props%rod_length*props%omega**2, &
           props%wave_factor*sin(merge(min(theta, theta0), theta, capped)), &
           props%pendulum_length*sin(theta), theta, &
           props%rod_length*sin(theta0*summary(SUMMARY_MAX_X2)), &
           merge(1.0_wp, 0.0_wp, free_max_x1 >= 1), summary(SUMMARY_MOTION), &
           summary(SUMMARY_PERIOD), props%wave_factor*sin(min(theta0*free_max_x1, pi/2))]
  end function harmonic_sweep_row

  !> The tank's sloshing modes 1..props%modes, one column each of the 'tank_modes' table.
  pure subroutine tank_modes(props, table)
    type(tank_properties), intent(in) :: props
    real(wp), intent(out) :: table(:, :)
    integer :: n
    do n = 1, props%modes
      table(:, n) = [real(n, wp), props%modal_period(n), props%modal_mass(n), &
                     props%modal_height(n), props%modal_length(n), props%modal_wave(n)]
    end do
  end subroutine tank_modes

  !> The tank's properties as one row of the 'tank_si' table.
  pure subroutine tank_summary(tank, props, model, row)
    type(tank_t), intent(in) :: tank
    type(tank_properties), intent(in) :: props
    type(model_t), intent(in) :: model
    real(wp), intent(out) :: row(:)
    row = [tank%radius, tank%liquid_depth, tank%freeboard, props%liquid_mass, tank%tank_mass, &
           props%total_mass, props%pendulum_length, props%sloshing_mass, props%d1, &
           props%rigid_mass, props%d0, props%convective_height, props%impulsive_height, &
           props%sloshing_period, props%omega, props%rod_length, props%stiffness, &
           props%damping, props%theta0, props%wave_factor, props%impact_coefficient, &
           model%s1, model%mu1, model%kappa, model%beta, model%gamma, model%delta, model%zeta]
  end subroutine tank_summary
end module sloshdyn_seismic
