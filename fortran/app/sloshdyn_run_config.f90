!> The configuration of one run: everything the input file says, validated, with the code lists
!> of its enumerated settings (the analyses, the kinds of study, chart models, sweep directions).
!> Filled by the namelist reader (sloshdyn_namelist), run by the driver (sloshdyn_driver) and
!> flattened for Python by the bridge.
module sloshdyn_run_config
  use sloshdyn_kinds, only: wp
  use sloshdyn_model, only: model_t
  use sloshdyn_excitation, only: PARAMETER_RHO
  use sloshdyn_vessel, only: tank_t, tank_properties, convective_damping
  use sloshdyn_ground, only: ground_motion_t
  use sloshdyn_stability_chart, only: chart_settings
  use sloshdyn_ode, only: ode_options
  use sloshdyn_integrator, only: METHOD_AUTO
  use sloshdyn_simulation, only: steady_options
  use sloshdyn_response, only: response_options
  use sloshdyn_periodic_response, only: lyapunov_options
  use sloshdyn_design_spectra, only: design_spectrum_t
  use sloshdyn_design_loads, only: design_factors_t
  use sloshdyn_tank_structure, only: tank_structure_t
  implicit none
  private
  public :: run_config, simulation_settings, sweep_settings, response_settings, &
            seismic_settings, study_settings, study_kinds, worker_kinds, continuation_names, &
            known_analyses, path_len, study_text_len, word_len
  public :: ANALYSIS_LINEAR, ANALYSIS_SIMULATE, ANALYSIS_STEADY_STATE, ANALYSIS_SWEEP, &
            ANALYSIS_FREQUENCY_RESPONSE, ANALYSIS_PERIODIC_RESPONSE, ANALYSIS_LYAPUNOV, &
            ANALYSIS_SEISMIC, ANALYSIS_STABILITY_CHART, ANALYSIS_SWIRL
  public :: chart_models
  public :: DIRECTION_UP, DIRECTION_DOWN, DIRECTION_BOTH, direction_names

  !> &study: the kinds of study (run by Python, `sloshdyn-py study`), the embedded cluster's
  !> worker kinds and the continuations of a response map, by code (index).
  character(len=*), parameter :: study_kinds(3) = &
    [character(len=12) :: 'response_map', 'basins', 'fragility']
  character(len=*), parameter :: worker_kinds(2) = [character(len=9) :: 'processes', 'threads']
  integer, parameter :: WORKER_THREADS = 2        !< the code of 'threads'
  character(len=*), parameter :: continuation_names(4) = &
    [character(len=4) :: 'none', 'up', 'down', 'both']
  !> The analyses, by code (index).
  character(len=*), parameter :: known_analyses(10) = &
    [character(len=18) :: 'linear', 'simulate', 'steady_state', 'sweep', 'frequency_response', &
     'periodic_response', 'lyapunov', 'seismic', 'stability_chart', 'swirl']
  integer, parameter :: ANALYSIS_LINEAR = 1, ANALYSIS_SIMULATE = 2, ANALYSIS_STEADY_STATE = 3, &
                        ANALYSIS_SWEEP = 4, ANALYSIS_FREQUENCY_RESPONSE = 5, &
                        ANALYSIS_PERIODIC_RESPONSE = 6, ANALYSIS_LYAPUNOV = 7, &
                        ANALYSIS_SEISMIC = 8, ANALYSIS_STABILITY_CHART = 9, &
                        ANALYSIS_SWIRL = 10
  !> &chart: the models, by CHART_SLOW_FLOW_31, CHART_SLOW_FLOW_NONRESONANT, CHART_FULL code.
  character(len=*), parameter :: chart_models(3) = [character(len=21) :: 'slow_flow_3:1', &
                                                    'slow_flow_nonresonant', 'full']
  character(len=*), parameter :: direction_names(3) = [character(len=4) :: 'up', 'down', 'both']
  integer, parameter :: DIRECTION_UP = 1, DIRECTION_DOWN = 2, DIRECTION_BOTH = 3
  !> Longest output directory name; longer ones are refused, never cut.
  integer, parameter :: path_len = 4096
  !> Longest store, figure and scheduler of &study; longer ones are refused, never cut.
  integer, parameter :: study_text_len = 1024
  !> Length of the string variables read (longer values are refused as unknown).
  integer, parameter :: word_len = 64

  !> &simulation: the time history from y0 (also the start of steady states and sweeps): x1,
  !> x1', x2, x2' and, for the spatial model only, y1, y1', y2, y2'.
  type :: simulation_settings
    real(wp) :: t_end = 0       !< required for 'simulate'
    integer :: n_out = 2001
    real(wp) :: y0(8) = 0
    !> how many values the file's `y0 = ...` gave (-1: none, or only y0(i) = ...): one per
    !> state of the model, as Python's y0 (check_spatial)
    integer :: y0_values = -1
  end type simulation_settings

  !> &sweep.
  type :: sweep_settings
    integer :: parameter = PARAMETER_RHO
    real(wp) :: start = 0, stop = 0   !< required
    integer :: n_points = 0           !< required
    integer :: direction = DIRECTION_UP
    !> each point from the previous one's final state (so jumps and hysteresis show), or each
    !> from y0 (independent points, which may share threads)
    logical :: carry_state = .true.
    integer :: threads = 1
  end type sweep_settings

  !> &response (frequency_response and periodic_response).
  type :: response_settings
    logical :: internal_resonance = .true.
    integer :: parameter = PARAMETER_RHO
    real(wp) :: start = 0, stop = 0   !< required; start <= stop after reading
    type(response_options) :: options
    !> periodic_response: also follow the branch born at this special point of the branch (its
    !> number in periodic_special_points.csv: a branch point or a period doubling); 0: none
    integer :: switch_at = 0
    !> periodic_response: also the two-parameter curve in (rho, A) through this special point (a
    !> fold, period doubling or Neimark-Sacker point; 0: none), the other parameter (A when the
    !> branch is continued in rho) over [curve_start, curve_stop]
    integer :: curve_at = 0
    real(wp) :: curve_start = 0, curve_stop = 0
  end type response_settings

  !> &seismic: the duration [s] and number of outputs of a seismic response (0: the defaults of
  !> sloshdyn_seismic).
  type :: seismic_settings
    real(wp) :: t_end = 0
    integer :: n_out = 0
  end type seismic_settings

  !> &study: a parameter study run by Python on Dask (sloshdyn-py study); read and checked
  !> here like every group, so both front doors know it (the executable refuses to run it).
  type :: study_settings
    logical :: given = .false.
    integer :: kind = 1                                !< index into study_kinds
    character(len=path_len) :: store = '', figure = '', scheduler = ''
    integer :: workers = 0                             !< embedded cluster: 0 = one per core
    !> index into worker_kinds: 'threads', faster than processes on one machine (measured:
    !> docs/studies.md, "Worker kind and task size")
    integer :: worker_kind = WORKER_THREADS
    integer :: points_per_task = 0                     !< 0 = the engine's choice
    !> workers a study waits for at its start (with scheduler or a cluster of its own)
    integer :: min_workers = 1
    !> seconds a study waits for min_workers at its start, and for a worker able to run it
    !> whenever none is alive, before it fails (of the order of a minute: a batch system's
    !> workers take that long to start)
    real(wp) :: grace_time = 60
    real(wp) :: frequency_start = 0, frequency_stop = 0, amplitude_start = 0, amplitude_stop = 0
    integer :: n_frequencies = 1, n_amplitudes = 1
    integer :: continuation = 1                        !< index into continuation_names
    real(wp) :: x1_start = 0, x1_stop = 0, dx1_start = 0, dx1_stop = 0
    integer :: n_grid = 50
    real(wp) :: tol = 1.0e-3_wp
    !> fragility: the record files (a glob pattern, expanded by Python) and the intensities,
    !> Sa at the sloshing period [g] for spectral_damping
    character(len=path_len) :: records = ''
    real(wp) :: intensity_start = 0, intensity_stop = 0, spectral_damping = convective_damping
    integer :: n_intensities = 1
  end type study_settings

  !> Everything one run needs, validated.
  type :: run_config
    type(model_t) :: model
    logical :: dimensional = .false.     !< model built from &tank (SI)
    type(tank_t) :: tank
    type(tank_properties) :: tank_props
    logical :: has_ground = .false.      !< &ground_motion given (with &tank)
    type(ground_motion_t) :: ground
    !> the spatial model (issue 26; &model or &tank planar = .false.): the second horizontal
    !> component, a record across the first (has_ground_y) or harmonic motion along azimuth
    !> [rad] with ellipticity (sloshdyn_seismic_spatial; with &model: &excitation's azimuth and
    !> ellipticity of the harmonic base motion)
    logical :: planar = .true.
    logical :: has_ground_y = .false.
    type(ground_motion_t) :: ground_y
    real(wp) :: azimuth = 0, ellipticity = 0
    type(seismic_settings) :: seismic
    type(chart_settings) :: chart
    integer :: analysis = ANALYSIS_LINEAR
    real(wp) :: sigma1 = 0, kappa_min = 0, kappa_max = 0   !< 3:1 tuning search
    character(len=path_len) :: directory = 'sloshdyn_output'
    type(ode_options) :: integration
    integer :: method = METHOD_AUTO
    type(simulation_settings) :: simulation
    type(steady_options) :: steady
    type(sweep_settings) :: sweep
    type(response_settings) :: response
    type(lyapunov_options) :: lyapunov
    type(study_settings) :: study
    !> &design (with &tank): the design check's spectrum (or the ground motion's:
    !> design_from_ground) and the codes' factors (sloshdyn_design_check)
    logical :: has_design = .false., design_from_ground = .false.
    type(design_spectrum_t) :: design_spectrum
    type(design_factors_t) :: design_factors
    !> &tank_structure (with &design): the structure of the codes' structural checks
    type(tank_structure_t) :: structure
  end type run_config
end module sloshdyn_run_config
