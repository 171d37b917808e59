!> The named layouts of the flat arrays that cross the f2py bridge, both ways: each layout is a
!> list of field names (layout_fields, here) in the order of the array, and its size is the
!> list's length; result tables have theirs in sloshdyn_tables, the model's rpar, ipar in
!> sloshdyn_model (real_param_names; 'model_integers' = [n, p]). Python asks the bridge for the
!> names (names('layout:NAME')) and builds and decodes every array by name, so a new field is a
!> change here (its name, its place in the to_*/from_* conversion) and in the Python class that
!> carries it. The to_*/from_* functions below list the fields in the same order.
!> Integer entries are converted by to_int, which keeps out-of-range and NaN values out of range
!> (so the core's range checks report them) instead of letting them wrap or become 0.
module sloshdyn_layouts
  use sloshdyn_kinds, only: wp
  use sloshdyn_namelist_scanner, only: join
  use sloshdyn_model, only: real_param_names
  use sloshdyn_tables, only: count_items
  use sloshdyn_ode, only: ode_options, ode_stats
  use sloshdyn_continuation, only: continuation_options
  use sloshdyn_simulation, only: steady_options
  use sloshdyn_response, only: response_options
  use sloshdyn_periodic_response, only: lyapunov_options
  use sloshdyn_vessel, only: tank_t
  use sloshdyn_ground, only: ground_motion_t, harmonic_ground, record_ground, GROUND_RECORD
  use sloshdyn_stability_chart, only: chart_settings
  use sloshdyn_slowflow_chart, only: chart_parameter_name, CHART_RHO, CHART_KAPPA
  implicit none
  private
  public :: INTEGRATION_SIZE, STEADY_SIZE, RESPONSE_SIZE, LYAPUNOV_SIZE, TANK_SIZE, GROUND_SIZE, &
            CHART_SETTINGS_SIZE, STUDY_SIZE, SWEEP_SIZE, SIMULATION_SIZE, RESPONSE_RANGE_SIZE, &
            SEISMIC_SIZE, ANALYSIS_SIZE, CONTINUATION_SIZE, CYCLE_CONTINUATION_SIZE, &
            SHOOTING_SIZE, PENDULUM_SIZE, &
            PHYSICAL_SIZE, GROUPS_SIZE, ROUTH_TRIVIAL_SIZE, ORBIT_INFO_SIZE
  public :: chart_axes, CHART_RHO
  public :: layout_fields, layout_size, join, excitation_parameters, ground_kinds, resonances
  public :: to_ode_options, to_method, to_steady, to_response, to_lyapunov
  public :: from_ode_options, from_steady, from_response, from_lyapunov, to_int, counts_array
  public :: to_continuation, to_cycle_continuation
  public :: to_tank, from_tank, to_ground, from_ground, to_chart, from_chart

  integer, parameter :: field_len = 32
  !> &integration (sloshdyn_ode's ode_options and the method code of sloshdyn_integrator)
  character(len=*), parameter :: integration_fields(*) = [character(len=field_len) :: &
    'rtol', 'atol', 'h_initial', 'h_max', 'h_min', 'max_steps', 'method']
  !> &steady (sloshdyn_simulation's steady_options; shooting 1/0)
  character(len=*), parameter :: steady_fields(*) = [character(len=field_len) :: &
    'transient_periods', 'settle_tol', 'max_transient_periods', 'window_periods', &
    'samples_per_period', 'periodic_tol', 'shooting']
  !> &response's numbers (sloshdyn_response's response_options with its continuation)
  character(len=*), parameter :: response_fields(*) = [character(len=field_len) :: &
    'n_scan', 'n_amplitudes', 'n_phases', 'amplitude_min', 'amplitude_max', 'ds', 'ds_min', &
    'ds_max', 'x_scale', 'max_points']
  !> &response's choices: resonance (code of resonances), parameter (of excitation_parameters),
  !> and the special point where periodic_response switches branches (0: none)
  character(len=*), parameter :: response_range_fields(*) = [character(len=field_len) :: &
    'resonance', 'parameter', 'start', 'stop', 'switch_at']
  !> &lyapunov (sloshdyn_periodic_response's lyapunov_options)
  character(len=*), parameter :: lyapunov_fields(*) = [character(len=field_len) :: &
    'transient_periods', 'n_periods', 'renormalise_every', 'spectrum']
  !> &tank: tank_t's components in order (sloshdyn_vessel; n and p as reals)
  character(len=*), parameter :: tank_fields(*) = [character(len=field_len) :: &
    'radius', 'liquid_depth', 'freeboard', 'liquid_density', 'liquid_mass', 'tank_mass', &
    'support_frequency', 'support_damping', 'support_stiffness', 'support_damping_coefficient', &
    'support_height', 'sloshing_damping', 'impact_stiffness', 'impact_damping', 'n', 'p', &
    'gravity']
  !> A ground motion (sloshdyn_ground): kind (ground_kinds), peak_acceleration [m/s^2],
  !> frequency [Hz], dt [s]; a record's samples [m/s^2] travel in their own array.
  character(len=*), parameter :: ground_fields(*) = [character(len=field_len) :: &
    'kind', 'peak_acceleration', 'frequency', 'dt']
  !> &chart (sloshdyn_stability_chart's chart_settings; model a code of 'chart_models', x and y
  !> of 'chart_axes')
  character(len=*), parameter :: chart_fields(*) = [character(len=field_len) :: &
    'model', 'x', 'y', 'x_min', 'x_max', 'y_min', 'y_max', 'n_x', 'n_y', 'n_scan', &
    'max_points', 'max_curves', 'brute_force_starts', 'threads']
  !> &study (given 1/0; kind, worker_kind and continuation codes of 'study_kinds',
  !> 'worker_kinds' and 'continuations'); its strings travel as text
  character(len=*), parameter :: study_fields(*) = [character(len=field_len) :: &
    'given', 'kind', 'workers', 'worker_kind', 'points_per_task', 'frequency_start', &
    'frequency_stop', 'n_frequencies', 'amplitude_start', 'amplitude_stop', 'n_amplitudes', &
    'continuation', 'x1_start', 'x1_stop', 'dx1_start', 'dx1_stop', 'n_grid', 'tol', &
    'intensity_start', 'intensity_stop', 'n_intensities', 'spectral_damping']
  !> &sweep (parameter of excitation_parameters, direction of 'directions', carry_state 1/0)
  character(len=*), parameter :: sweep_fields(*) = [character(len=field_len) :: &
    'parameter', 'start', 'stop', 'n_points', 'direction', 'carry_state', 'threads']
  !> &simulation: t_end, n_out and the initial state y0 = (x1, x1', x2, x2')
  character(len=*), parameter :: simulation_fields(*) = [character(len=field_len) :: &
    't_end', 'n_out', 'y0_1', 'y0_2', 'y0_3', 'y0_4']
  !> &seismic
  character(len=*), parameter :: seismic_fields(*) = [character(len=field_len) :: &
    't_end', 'n_out']
  !> &analysis's numbers (the 3:1 tuning search)
  character(len=*), parameter :: analysis_fields(*) = [character(len=field_len) :: &
    'sigma1', 'kappa_min', 'kappa_max']
  !> The continuation of periodic orbits (direction +1 from the low end, -1 from the high end)
  character(len=*), parameter :: continuation_fields(*) = [character(len=field_len) :: &
    'ds', 'ds_min', 'ds_max', 'x_scale', 'direction']
  !> The continuation of limit cycles of the slow flow (sloshdyn_slowflow_cycles): the
  !> continuation's steps and direction and Newton's tolerances (sloshdyn_continuation's
  !> newton_options)
  character(len=*), parameter :: cycle_continuation_fields(*) = [character(len=field_len) :: &
    continuation_fields, 'x_tol', 'f_tol', 'max_iter']
  !> Newton shooting of periodic orbits
  character(len=*), parameter :: shooting_fields(*) = [character(len=field_len) :: &
    'newton_tol', 'max_iter']
  !> Small results: the equivalent pendulum of a tank (eq 2-3) [m, kg, m, kg, m, kg]; the SI
  !> values of eq (9) and their dimensionless groups; Routh-Hurwitz of eq (20) at the trivial
  !> equilibrium (routh_stable 1/0); a periodic orbit's Newton iterations and max|x1|.
  character(len=*), parameter :: pendulum_fields(*) = [character(len=field_len) :: &
    'pendulum_length', 'sloshing_mass', 'd1', 'rigid_mass', 'd0', 'liquid_mass']
  character(len=*), parameter :: physical_fields(*) = [character(len=field_len) :: &
    'M', 'L', 'k', 'c', 'b', 'd', 'g', 'theta0', 'l', 'm']
  character(len=*), parameter :: groups_fields(*) = [character(len=field_len) :: &
    's1', 'mu1', 'kappa', 'beta', 'gamma', 'delta']
  character(len=*), parameter :: routh_fields(*) = [character(len=field_len) :: &
    'c1', 'c2', 'c3', 'c4', 'delta2', 'delta3', 'routh_stable']
  character(len=*), parameter :: orbit_info_fields(*) = [character(len=field_len) :: &
    'iterations', 'max_x1']
  !> The codes of enumerated options that have no name list elsewhere: the parameter of a sweep
  !> or response (from PARAMETER_RHO of sloshdyn_excitation), the ground kinds (from
  !> GROUND_HARMONIC), the resonance of a frequency response (from 0).
  character(len=*), parameter :: excitation_parameters(*) = [character(len=field_len) :: &
    'rho', 'A', 'frequency']
  character(len=*), parameter :: ground_kinds(*) = [character(len=field_len) :: &
    'harmonic', 'record']
  character(len=*), parameter :: resonances(*) = [character(len=field_len) :: 'none', '3:1']

  integer, parameter :: INTEGRATION_SIZE = size(integration_fields), &
                        STEADY_SIZE = size(steady_fields), RESPONSE_SIZE = size(response_fields), &
                        LYAPUNOV_SIZE = size(lyapunov_fields), TANK_SIZE = size(tank_fields), &
                        GROUND_SIZE = size(ground_fields), &
                        CHART_SETTINGS_SIZE = size(chart_fields), &
                        STUDY_SIZE = size(study_fields), &
                        SWEEP_SIZE = size(sweep_fields), &
                        SIMULATION_SIZE = size(simulation_fields), &
                        RESPONSE_RANGE_SIZE = size(response_range_fields), &
                        SEISMIC_SIZE = size(seismic_fields), &
                        ANALYSIS_SIZE = size(analysis_fields), &
                        CONTINUATION_SIZE = size(continuation_fields), &
                        CYCLE_CONTINUATION_SIZE = size(cycle_continuation_fields), &
                        SHOOTING_SIZE = size(shooting_fields), &
                        PENDULUM_SIZE = size(pendulum_fields), &
                        PHYSICAL_SIZE = size(physical_fields), GROUPS_SIZE = size(groups_fields), &
                        ROUTH_TRIVIAL_SIZE = size(routh_fields), &
                        ORBIT_INFO_SIZE = size(orbit_info_fields)

contains

  !> The comma-separated field names of a named layout (a settings or model array), '' for an
  !> unknown name.
  pure function layout_fields(name) result(fields)
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: fields
    select case (name)
    case ('model');          fields = join(real_param_names, ',')
    case ('model_integers'); fields = 'n,p'
    case ('integration');    fields = join(integration_fields, ',')
    case ('steady');         fields = join(steady_fields, ',')
    case ('response');       fields = join(response_fields, ',')
    case ('response_range'); fields = join(response_range_fields, ',')
    case ('lyapunov');       fields = join(lyapunov_fields, ',')
    case ('tank');           fields = join(tank_fields, ',')
    case ('ground');         fields = join(ground_fields, ',')
    case ('chart');          fields = join(chart_fields, ',')
    case ('study');          fields = join(study_fields, ',')
    case ('sweep');          fields = join(sweep_fields, ',')
    case ('simulation');     fields = join(simulation_fields, ',')
    case ('seismic');        fields = join(seismic_fields, ',')
    case ('analysis');       fields = join(analysis_fields, ',')
    case ('continuation');   fields = join(continuation_fields, ',')
    case ('cycle_continuation'); fields = join(cycle_continuation_fields, ',')
    case ('shooting');       fields = join(shooting_fields, ',')
    case ('pendulum');       fields = join(pendulum_fields, ',')
    case ('physical');       fields = join(physical_fields, ',')
    case ('groups');         fields = join(groups_fields, ',')
    case ('routh');          fields = join(routh_fields, ',')
    case ('orbit_info');     fields = join(orbit_info_fields, ',')
    case default;            fields = ''
    end select
  end function layout_fields

  !> The number of fields of a named layout (0 for an unknown name).
  pure integer function layout_size(name) result(n)
    character(len=*), intent(in) :: name
    n = count_items(layout_fields(name))
  end function layout_size

  !> The parameters of a stability chart (its axes), comma-separated in code order from
  !> CHART_RHO.
  pure function chart_axes() result(names)
    character(len=:), allocatable :: names
    integer :: k
    names = chart_parameter_name(CHART_RHO)
    do k = CHART_RHO + 1, CHART_KAPPA
      names = names//','//chart_parameter_name(k)
    end do
  end function chart_axes

  !> x as an integer; NaN and values beyond the integer range become -huge (out of every range).
  elemental integer function to_int(x)
    real(wp), intent(in) :: x
    if (x == x .and. abs(x) < real(huge(1), wp)) then
      to_int = nint(x)
    else
      to_int = -huge(1)
    end if
  end function to_int

  pure function to_ode_options(a) result(options)
    real(wp), intent(in) :: a(INTEGRATION_SIZE)
    type(ode_options) :: options
    options%rtol = a(1)
    options%atol = a(2)
    options%h_initial = a(3)
    options%h_max = a(4)
    options%h_min = a(5)
    options%max_steps = to_int(a(6))
  end function to_ode_options

  pure integer function to_method(a) result(method)
    real(wp), intent(in) :: a(INTEGRATION_SIZE)
    method = to_int(a(7))
  end function to_method

  pure function from_ode_options(options, method) result(a)
    type(ode_options), intent(in) :: options
    integer, intent(in) :: method
    real(wp) :: a(INTEGRATION_SIZE)
    a = [options%rtol, options%atol, options%h_initial, options%h_max, options%h_min, &
         real(options%max_steps, wp), real(method, wp)]
  end function from_ode_options

  pure function to_steady(a) result(options)
    real(wp), intent(in) :: a(STEADY_SIZE)
    type(steady_options) :: options
    options = steady_options(a(1), a(2), a(3), to_int(a(4)), to_int(a(5)), a(6), a(7) /= 0)
  end function to_steady

  pure function from_steady(options) result(a)
    type(steady_options), intent(in) :: options
    real(wp) :: a(STEADY_SIZE)
    a = [options%transient_periods, options%settle_tol, options%max_transient_periods, &
         real(options%window_periods, wp), real(options%samples_per_period, wp), &
         options%periodic_tol, merge(1.0_wp, 0.0_wp, options%shooting)]
  end function from_steady

  pure function to_response(a) result(options)
    real(wp), intent(in) :: a(RESPONSE_SIZE)
    type(response_options) :: options
    options%n_scan = to_int(a(1))
    options%n_amplitudes = to_int(a(2))
    options%n_phases = to_int(a(3))
    options%amplitude_min = a(4)
    options%amplitude_max = a(5)
    options%continuation%ds = a(6)
    options%continuation%ds_min = a(7)
    options%continuation%ds_max = a(8)
    options%continuation%x_scale = a(9)
    options%continuation%max_points = to_int(a(10))
  end function to_response

  pure function from_response(options) result(a)
    type(response_options), intent(in) :: options
    real(wp) :: a(RESPONSE_SIZE)
    associate (c => options%continuation)
      a = [real(options%n_scan, wp), real(options%n_amplitudes, wp), &
           real(options%n_phases, wp), options%amplitude_min, options%amplitude_max, c%ds, &
           c%ds_min, c%ds_max, c%x_scale, real(c%max_points, wp)]
    end associate
  end function from_response

  pure function to_lyapunov(a) result(options)
    real(wp), intent(in) :: a(LYAPUNOV_SIZE)
    type(lyapunov_options) :: options
    options = lyapunov_options(to_int(a(1)), to_int(a(2)), to_int(a(3)), a(4) /= 0)
  end function to_lyapunov

  pure function from_lyapunov(options) result(a)
    type(lyapunov_options), intent(in) :: options
    real(wp) :: a(LYAPUNOV_SIZE)
    a = real([options%transient_periods, options%n_periods, options%renormalise_every, &
              merge(1, 0, options%spectrum)], wp)
  end function from_lyapunov

  !> The continuation of periodic orbits (its max_points set apart).
  pure function to_continuation(a) result(options)
    real(wp), intent(in) :: a(CONTINUATION_SIZE)
    type(continuation_options) :: options
    options = continuation_options(ds=a(1), ds_min=a(2), ds_max=a(3), x_scale=a(4), &
                                   direction=to_int(a(5)))
  end function to_continuation

  !> The continuation of slow-flow cycles with Newton's tolerances (its max_points set apart).
  pure function to_cycle_continuation(a) result(options)
    real(wp), intent(in) :: a(CYCLE_CONTINUATION_SIZE)
    type(continuation_options) :: options
    options = to_continuation(a(:CONTINUATION_SIZE))
    options%newton%x_tol = a(CONTINUATION_SIZE + 1)
    options%newton%f_tol = a(CONTINUATION_SIZE + 2)
    options%newton%max_iter = to_int(a(CONTINUATION_SIZE + 3))
  end function to_cycle_continuation

  !> tank(TANK_SIZE) in the order of tank_t's components (n and p as reals).
  pure function to_tank(a) result(tank)
    real(wp), intent(in) :: a(TANK_SIZE)
    type(tank_t) :: tank
    tank = tank_t(a(1), a(2), a(3), a(4), a(5), a(6), a(7), a(8), a(9), a(10), a(11), a(12), &
                  a(13), a(14), to_int(a(15)), to_int(a(16)), a(17))
  end function to_tank

  pure function from_tank(tank) result(a)
    type(tank_t), intent(in) :: tank
    real(wp) :: a(TANK_SIZE)
    a = [tank%radius, tank%liquid_depth, tank%freeboard, tank%liquid_density, tank%liquid_mass, &
         tank%tank_mass, tank%support_frequency, tank%support_damping, tank%support_stiffness, &
         tank%support_damping_coefficient, tank%support_height, tank%sloshing_damping, &
         tank%impact_stiffness, tank%impact_damping, real(tank%n, wp), real(tank%p, wp), &
         tank%gravity]
  end function from_tank

  !> ground(GROUND_SIZE) = [kind (GROUND_HARMONIC, GROUND_RECORD), peak_acceleration [m/s^2],
  !> frequency [Hz], dt [s]] and, for a record, its samples [m/s^2].
  pure function to_ground(a, samples) result(ground)
    real(wp), intent(in) :: a(GROUND_SIZE), samples(:)
    type(ground_motion_t) :: ground
    if (to_int(a(1)) == GROUND_RECORD) then
      ground = record_ground(a(4), samples)
    else
      ground = harmonic_ground(a(2), a(3))
    end if
  end function to_ground

  pure function from_ground(ground) result(a)
    type(ground_motion_t), intent(in) :: ground
    real(wp) :: a(GROUND_SIZE)
    a = [real(ground%kind, wp), ground%peak_acceleration, ground%frequency, ground%dt]
  end function from_ground

  !> chart(CHART_SETTINGS_SIZE) = [model, x, y, x_min, x_max, y_min, y_max, n_x, n_y, n_scan,
  !> max_points, max_curves, brute_force_starts, threads] (the &chart variables; x, y and model
  !> as codes).
  pure function to_chart(a) result(settings)
    real(wp), intent(in) :: a(CHART_SETTINGS_SIZE)
    type(chart_settings) :: settings
    settings%model = to_int(a(1))
    settings%parameters = to_int(a(2:3))
    settings%p_min = a([4, 6])
    settings%p_max = a([5, 7])
    settings%n_columns = to_int(a(8))
    settings%n_levels = to_int(a(9))
    settings%response%n_scan = to_int(a(10))
    settings%max_points = to_int(a(11))
    settings%max_curves = to_int(a(12))
    settings%brute_force_starts = to_int(a(13))
    settings%threads = to_int(a(14))
  end function to_chart

  pure function from_chart(settings) result(a)
    type(chart_settings), intent(in) :: settings
    real(wp) :: a(CHART_SETTINGS_SIZE)
    a = [real(settings%model, wp), real(settings%parameters, wp), settings%p_min(1), &
         settings%p_max(1), settings%p_min(2), settings%p_max(2), &
         real([settings%n_columns, settings%n_levels, settings%response%n_scan, &
               settings%max_points, settings%max_curves, settings%brute_force_starts, &
               settings%threads], wp)]
  end function from_chart

  !> counts(4) = [rhs evaluations, accepted steps, rejected steps, tau reached].
  pure function counts_array(stats) result(counts)
    type(ode_stats), intent(in) :: stats
    real(wp) :: counts(4)
    counts = [real(stats%n_rhs, wp), real(stats%n_accepted, wp), real(stats%n_rejected, wp), &
              stats%t_reached]
  end function counts_array
end module sloshdyn_layouts
