!> The input file: Fortran namelist groups, read and validated in full before anything is
!> computed. The only reader: the executable uses it directly and Python through the bridge, so
!> both front doors apply the same rules, defaults and messages. The groups and variables are
!> documented in README.md ("Namelist reference").
!>
!> The file is first split into groups by a scanner of its own (any line length, several groups
!> on a line, comments, quotes), which also rejects unknown, repeated or unclosed groups and text
!> outside groups. Each group then has its own reader with its own local variables, whose
!> defaults come from the option types of the analyses; it parses its group's text with a
!> namelist read and, if that fails, parses each assignment alone to name the culprit.
module sloshdyn_namelist
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, SD_IO_ERROR, check_real
  use sloshdyn_text, only: num2str
  use sloshdyn_model, only: model_t, model_from_arrays, model_from_physical, require_stable_trivial
  use sloshdyn_excitation, only: PARAMETER_RHO, PARAMETER_A, PARAMETER_FREQUENCY, &
                                 set_excitation_parameter
  use sloshdyn_vessel, only: tank_t, tank_properties, tank_model
  use sloshdyn_ground, only: ground_motion_t, harmonic_ground, record_ground, ground_excitation, &
                             scale_ground, GROUND_RECORD
  use sloshdyn_records, only: load_record, units_code, units_factor
  use sloshdyn_seismic, only: max_seismic_outputs
  use sloshdyn_stability_chart, only: chart_settings, check_chart_settings
  use sloshdyn_slowflow_chart, only: chart_parameter_name, CHART_RHO, CHART_KAPPA
  use sloshdyn_ode, only: ode_options, check_options
  use sloshdyn_integrator, only: METHOD_AUTO, method_names
  use sloshdyn_simulation, only: steady_options, check_steady
  use sloshdyn_response, only: response_options, check_response_options
  use sloshdyn_periodic_response, only: lyapunov_options, check_lyapunov
  implicit none
  private
  public :: run_config, simulation_settings, sweep_settings, &
            response_settings, study_settings, study_kinds, worker_kinds, continuation_names, &
            read_input, namelist_defaults, known_analyses, path_len, &
            check_threads
  public :: ANALYSIS_LINEAR, ANALYSIS_SIMULATE, ANALYSIS_STEADY_STATE, ANALYSIS_SWEEP, &
            ANALYSIS_FREQUENCY_RESPONSE, ANALYSIS_PERIODIC_RESPONSE, ANALYSIS_LYAPUNOV, &
            ANALYSIS_SEISMIC, ANALYSIS_STABILITY_CHART
  public :: chart_models
  public :: DIRECTION_UP, DIRECTION_DOWN, DIRECTION_BOTH, direction_names

  character(len=*), parameter :: known_groups(15) = &
    [character(len=13) :: 'model', 'tank', 'ground_motion', 'excitation', 'analysis', 'output', &
     'integration', 'simulation', 'steady', 'sweep', 'response', 'lyapunov', 'seismic', 'chart', &
     'study']
  integer, parameter :: G_MODEL = 1, G_TANK = 2, G_GROUND_MOTION = 3, G_EXCITATION = 4, &
                        G_ANALYSIS = 5, G_OUTPUT = 6, G_INTEGRATION = 7, G_SIMULATION = 8, &
                        G_STEADY = 9, G_SWEEP = 10, G_RESPONSE = 11, G_LYAPUNOV = 12, &
                        G_SEISMIC = 13, G_CHART = 14, G_STUDY = 15
  !> &study: the kinds of study (run by Python, `sloshdyn-py study`), the embedded cluster's
  !> worker kinds and the continuations of a response map, by code (index).
  character(len=*), parameter :: study_kinds(3) = &
    [character(len=12) :: 'response_map', 'basins', 'fragility']
  character(len=*), parameter :: worker_kinds(2) = [character(len=9) :: 'processes', 'threads']
  character(len=*), parameter :: continuation_names(4) = &
    [character(len=4) :: 'none', 'up', 'down', 'both']
  !> The analyses, by code (index).
  character(len=*), parameter :: known_analyses(9) = &
    [character(len=18) :: 'linear', 'simulate', 'steady_state', 'sweep', 'frequency_response', &
     'periodic_response', 'lyapunov', 'seismic', 'stability_chart']
  integer, parameter :: ANALYSIS_LINEAR = 1, ANALYSIS_SIMULATE = 2, ANALYSIS_STEADY_STATE = 3, &
                        ANALYSIS_SWEEP = 4, ANALYSIS_FREQUENCY_RESPONSE = 5, &
                        ANALYSIS_PERIODIC_RESPONSE = 6, ANALYSIS_LYAPUNOV = 7, &
                        ANALYSIS_SEISMIC = 8, ANALYSIS_STABILITY_CHART = 9
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

  !> &simulation: the time history from y0 (also the start of steady states and sweeps).
  type :: simulation_settings
    real(wp) :: t_end = 0       !< required for 'simulate'
    integer :: n_out = 2001
    real(wp) :: y0(4) = 0
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
  end type response_settings

  !> &study: a parameter study run by Python on Dask (sloshdyn-py study); read and checked
  !> here like every group, so both front doors know it (the executable refuses to run it).
  type :: study_settings
    logical :: given = .false.
    integer :: kind = 1                                !< index into study_kinds
    character(len=path_len) :: store = '', figure = '', scheduler = ''
    integer :: workers = 0                             !< embedded cluster: 0 = one per core
    integer :: worker_kind = 1                         !< index into worker_kinds
    integer :: points_per_task = 0                     !< 0 = the engine's choice
    real(wp) :: frequency_start = 0, frequency_stop = 0, amplitude_start = 0, amplitude_stop = 0
    integer :: n_frequencies = 1, n_amplitudes = 1
    integer :: continuation = 1                        !< index into continuation_names
    real(wp) :: x1_start = 0, x1_stop = 0, dx1_start = 0, dx1_stop = 0
    integer :: n_grid = 50
    real(wp) :: tol = 1.0e-3_wp
    !> fragility: the record files (a glob pattern, expanded by Python) and the intensities,
    !> Sa at the sloshing period [g] for spectral_damping
    character(len=path_len) :: records = ''
    real(wp) :: intensity_start = 0, intensity_stop = 0, spectral_damping = 0.005_wp
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
    real(wp) :: seismic_t_end = 0        !< &seismic [s]; 0 = default
    integer :: seismic_n_out = 0
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
  end type run_config

  !> The text of one group: its body between the name and the closing '/' (comments removed,
  !> lines joined), the line it starts on, and the names of the variables it assigns.
  type :: group_text
    logical :: given = .false.
    character(len=:), allocatable :: body, assigned
    integer :: line = 0
  end type group_text

  type :: input_file
    character(len=:), allocatable :: path
    type(group_text) :: groups(size(known_groups))
    !> describe instead of read: every group is written with its defaults into description
    logical :: describing = .false.
    character(len=:), allocatable :: description
  end type input_file

  !> Reading one group. The reader loop of every group is
  !>   call reader%start(file, G_X, status)
  !>   do while (reader%next())
  !>     if (reader%describing) then
  !>       write (reader%written, nml=x, iostat=reader%ios)
  !>     else
  !>       read (reader%text, nml=x, iostat=reader%ios, iomsg=reader%iomsg)
  !>     end if
  !>     call reader%check(file, status, message)
  !>   end do
  !> The whole group is parsed first; if it fails, each assignment alone, to name the culprit.
  !> Describing, the group is written with its values instead (namelist_defaults).
  type :: group_reader
    integer :: group = 0, step = 0, line = 0, next_start = 0, ios = 0
    logical :: describing = .false., done = .true.
    character(len=:), allocatable :: name, body, path, text, assignment
    character(len=message_len) :: iomsg = ''
    character(len=2*path_len) :: written = ''
  contains
    procedure :: start => start_group
    procedure :: next => next_text
    procedure :: check => check_text
  end type group_reader

contains

  !> Read and validate the whole input file. On failure nothing is returned but a status and a
  !> message naming the group, the variable, its value and the allowed range.
  subroutine read_input(path, config, status, message)
    character(len=*), intent(in) :: path
    type(run_config), intent(out) :: config
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(input_file) :: file
    real(wp) :: groups(8), A, rho
    integer :: exponents(2)

    call scan_file(path, file, status, message)
    if (status /= SD_OK) return

    ! which description of the system: dimensionless (&model) or a tank in SI (&tank)
    associate (g => file%groups)
      if (g(G_MODEL)%given .and. g(G_TANK)%given) then
        call fail(status, message, 'give either &model (dimensionless) or &tank (a tank in '// &
                  'SI units), not both')
      else if (.not. (g(G_MODEL)%given .or. g(G_TANK)%given)) then
        call fail(status, message, 'missing group &model (or &tank): the system is not described')
      else if (g(G_MODEL)%given .and. g(G_GROUND_MOTION)%given) then
        call fail(status, message, '&ground_motion goes with &tank (SI units); with &model, '// &
                  'give the dimensionless excitation in &excitation')
      else if (g(G_TANK)%given .and. g(G_EXCITATION)%given) then
        call fail(status, message, '&excitation goes with &model (dimensionless); with &tank, '// &
                  'give the ground motion in &ground_motion (SI units)')
      end if
      if (status /= SD_OK) return
      config%dimensional = g(G_TANK)%given
      config%has_ground = g(G_GROUND_MOTION)%given
    end associate

    if (config%dimensional) then
      call read_tank(file, config%tank, status, message)
      if (status /= SD_OK) return
      call tank_model(config%tank, config%model, config%tank_props, status, message)
      if (status /= SD_OK) then
        message = '&tank: '//trim(message)
        return
      end if
      call read_ground_motion(file, config%tank_props, frequency_of_sweep(file), config%ground, &
                              status, message)
      if (status /= SD_OK) return
      if (config%has_ground) then
        call ground_excitation(config%ground, config%tank_props%omega, &
                               config%tank_props%rod_length, config%model%excitation, status, &
                               message)
        if (status /= SD_OK) then
          message = '&ground_motion: '//trim(message)
          return
        end if
      end if
    else
      call read_excitation(file, A, rho, status, message)
      if (status /= SD_OK) return
      call read_model(file, groups, exponents, status, message)
      if (status /= SD_OK) return
      call model_from_arrays([groups(1:7), A, rho, groups(8)], exponents, config%model, status, &
                             message)
      if (status /= SD_OK) then
        ! the model's rules name the variable first: A and rho belong to &excitation
        if (index(message, 'A = ') == 1 .or. index(message, 'rho = ') == 1) then
          message = '&excitation: '//trim(message)
        else
          message = '&model: '//trim(message)
        end if
        return
      end if
    end if

    call read_analysis(file, config, status, message)
    if (status == SD_OK) call read_output(file, config%directory, status, message)
    if (status == SD_OK) call read_integration(file, config%integration, config%method, &
                                               status, message)
    if (status == SD_OK) call read_simulation(file, config%analysis == ANALYSIS_SIMULATE, &
                                              config%simulation, status, message)
    if (status == SD_OK) call read_steady(file, config%steady, status, message)
    if (status == SD_OK) call read_sweep(file, config%analysis == ANALYSIS_SWEEP, config%sweep, &
                                         status, message)
    if (status == SD_OK) call read_response(file, config%analysis == ANALYSIS_FREQUENCY_RESPONSE &
                                            .or. config%analysis == ANALYSIS_PERIODIC_RESPONSE, &
                                            config%response, status, message)
    if (status == SD_OK) call read_lyapunov(file, config%lyapunov, status, message)
    if (status == SD_OK) call read_seismic(file, config%seismic_t_end, config%seismic_n_out, &
                                           status, message)
    if (status == SD_OK) call read_chart(file, config%analysis == ANALYSIS_STABILITY_CHART, &
                                         config%chart, status, message)
    if (status == SD_OK) call read_study(file, config, status, message)
    ! a study file describes no analysis of the executable: the default one is not checked
    if (status == SD_OK .and. .not. (config%study%given .and. .not. file%groups(G_ANALYSIS)%given)) &
      call check_analysis(config, status, message)
  end subroutine read_input

  !> Every group with its variables and their defaults, as the namelist write statement gives
  !> them (the source for the documentation's namelist reference and its test). Required
  !> variables show their placeholder (0).
  subroutine namelist_defaults(text)
    character(len=:), allocatable, intent(out) :: text
    type(input_file) :: file
    type(run_config) :: config
    type(tank_t) :: tank
    type(tank_properties) :: props
    type(ground_motion_t) :: ground
    type(ode_options) :: integration
    type(simulation_settings) :: simulation
    type(steady_options) :: steady
    type(sweep_settings) :: sweep
    type(response_settings) :: response
    type(lyapunov_options) :: lyapunov
    type(chart_settings) :: chart
    character(len=path_len) :: directory
    type(run_config) :: study_config
    real(wp) :: groups(8), A, rho, t_end
    integer :: exponents(2), method, status, n_out
    character(len=message_len) :: message

    file%describing = .true.
    file%description = ''
    t_end = 0
    n_out = 0
    call read_model(file, groups, exponents, status, message)
    call read_tank(file, tank, status, message)
    call read_ground_motion(file, props, -1.0_wp, ground, status, message)
    call read_excitation(file, A, rho, status, message)
    call read_analysis(file, config, status, message)
    call read_output(file, directory, status, message)
    call read_integration(file, integration, method, status, message)
    call read_simulation(file, .false., simulation, status, message)
    call read_steady(file, steady, status, message)
    call read_sweep(file, .false., sweep, status, message)
    call read_response(file, .false., response, status, message)
    call read_lyapunov(file, lyapunov, status, message)
    call read_seismic(file, t_end, n_out, status, message)
    call read_chart(file, .false., chart, status, message)
    call read_study(file, study_config, status, message)
    text = file%description
  end subroutine namelist_defaults

  ! ---- the groups ------------------------------------------------------------------------------

  !> &model: groups = [s1, mu1, kappa, theta0, beta, gamma, delta, zeta], exponents = [n, p].
  subroutine read_model(file, groups, exponents, status, message)
    type(input_file), intent(inout) :: file
    real(wp), intent(out) :: groups(8)
    integer, intent(out) :: exponents(2), status
    character(len=message_len), intent(out) :: message
    type(model_t) :: defaults
    real(wp) :: s1, mu1, kappa, theta0, beta, gamma, delta, zeta
    integer :: n, p
    type(group_reader) :: reader
    namelist /model/ s1, mu1, kappa, theta0, beta, gamma, delta, zeta, n, p

    s1 = 0; mu1 = 0; kappa = 0; theta0 = 0
    beta = defaults%beta; gamma = defaults%gamma; delta = defaults%delta; zeta = defaults%zeta
    n = defaults%n; p = defaults%p
    status = SD_OK
    message = ''
    call reader%start(file, G_MODEL, status)
    do while (reader%next())
      if (reader%describing) then
        write (reader%written, nml=model, iostat=reader%ios)
      else
        read (reader%text, nml=model, iostat=reader%ios, iomsg=reader%iomsg)
      end if
      call reader%check(file, status, message)
    end do
    call require(file, G_MODEL, 's1', status, message)
    call require(file, G_MODEL, 'mu1', status, message)
    call require(file, G_MODEL, 'kappa', status, message)
    call require(file, G_MODEL, 'theta0', status, message)
    groups = [s1, mu1, kappa, theta0, beta, gamma, delta, zeta]
    exponents = [n, p]
  end subroutine read_model

  !> &tank: a cylindrical tank on supports in SI units (sloshdyn_vessel), defaults from tank_t.
  subroutine read_tank(file, vessel, status, message)
    type(input_file), intent(inout) :: file
    type(tank_t), intent(out) :: vessel
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: radius, liquid_depth, freeboard, liquid_density, liquid_mass, tank_mass, &
                support_frequency, support_damping, support_stiffness, &
                support_damping_coefficient, support_height, sloshing_damping, &
                impact_stiffness, impact_damping, gravity
    integer :: n, p
    type(group_reader) :: reader
    namelist /tank/ radius, liquid_depth, freeboard, liquid_density, liquid_mass, tank_mass, &
                    support_frequency, support_damping, support_stiffness, &
                    support_damping_coefficient, support_height, sloshing_damping, &
                    impact_stiffness, impact_damping, n, p, gravity

    radius = vessel%radius; liquid_depth = vessel%liquid_depth; freeboard = vessel%freeboard
    liquid_density = vessel%liquid_density; liquid_mass = vessel%liquid_mass
    tank_mass = vessel%tank_mass; support_frequency = vessel%support_frequency
    support_damping = vessel%support_damping; support_stiffness = vessel%support_stiffness
    support_damping_coefficient = vessel%support_damping_coefficient
    support_height = vessel%support_height; sloshing_damping = vessel%sloshing_damping
    impact_stiffness = vessel%impact_stiffness; impact_damping = vessel%impact_damping
    n = vessel%n; p = vessel%p; gravity = vessel%gravity
    status = SD_OK
    message = ''
    call reader%start(file, G_TANK, status)
    do while (reader%next())
      if (reader%describing) then
        write (reader%written, nml=tank, iostat=reader%ios)
      else
        read (reader%text, nml=tank, iostat=reader%ios, iomsg=reader%iomsg)
      end if
      call reader%check(file, status, message)
    end do
    call require(file, G_TANK, 'radius', status, message)
    call require(file, G_TANK, 'liquid_depth', status, message)
    call require(file, G_TANK, 'freeboard', status, message)
    call require(file, G_TANK, 'tank_mass', status, message)
    vessel = tank_t(radius, liquid_depth, freeboard, liquid_density, liquid_mass, tank_mass, &
                    support_frequency, support_damping, support_stiffness, &
                    support_damping_coefficient, support_height, sloshing_damping, &
                    impact_stiffness, impact_damping, n, p, gravity)
  end subroutine read_tank

  !> &ground_motion: a record file (PEER NGA .AT2, or two columns time, acceleration) or harmonic
  !> motion (peak_acceleration, frequency), scaled by a factor, to a peak ground acceleration,
  !> or to a pseudo-spectral acceleration at target_period (default: the tank's sloshing period)
  !> for target_damping; accelerations in `units` ('g', 'm/s^2', 'cm/s^2'). A sweep in
  !> frequency gives the frequency (sweep_frequency >= 0, its first [Hz]; < 0: no such sweep)
  !> when none is given.
  subroutine read_ground_motion(file, props, sweep_frequency, ground, status, message)
    type(input_file), intent(inout) :: file
    type(tank_properties), intent(in) :: props
    real(wp), intent(in) :: sweep_frequency
    type(ground_motion_t), intent(out) :: ground
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    character(len=path_len) :: record
    character(len=word_len) :: format, units
    real(wp) :: peak_acceleration, frequency, scale_factor, target_pga, target_sa, &
                target_period, target_damping, to_si, dt
    real(wp), allocatable :: acceleration(:)
    integer :: unit_code
    type(group_reader) :: reader
    namelist /ground_motion/ record, format, units, peak_acceleration, frequency, scale_factor, &
                             target_pga, target_sa, target_period, target_damping

    record = ''; format = 'auto'; units = 'g'
    peak_acceleration = 0; frequency = 0; scale_factor = 1; target_pga = 0; target_sa = 0
    target_period = 0; target_damping = 0.05_wp
    status = SD_OK
    message = ''
    call reader%start(file, G_GROUND_MOTION, status)
    do while (reader%next())
      if (reader%describing) then
        write (reader%written, nml=ground_motion, iostat=reader%ios)
      else
        read (reader%text, nml=ground_motion, iostat=reader%ios, iomsg=reader%iomsg)
      end if
      call reader%check(file, status, message)
    end do
    if (status /= SD_OK .or. file%describing .or. .not. file%groups(G_GROUND_MOTION)%given) return

    call units_code(units, unit_code, status, message)
    if (status == SD_OK) call units_factor(unit_code, to_si, status, message)
    ! the signs in the user's units, so that messages show the values as written
    call check_real('peak_acceleration', peak_acceleration, 0.0_wp, huge(1.0_wp), .false., &
                    .true., 'the peak ground acceleration must be >= 0 ['//trim(units)//']', &
                    status, message)
    call check_real('target_pga', target_pga, 0.0_wp, huge(1.0_wp), .false., .true., &
                    'target_pga must be >= 0 ['//trim(units)//'] (0: not scaled to a PGA)', &
                    status, message)
    call check_real('target_sa', target_sa, 0.0_wp, huge(1.0_wp), .false., .true., &
                    'target_sa must be >= 0 ['//trim(units)//'] (0: not scaled to a spectral '// &
                    'acceleration)', status, message)
    if (status == SD_OK) then
      if (len_trim(record) > 0) then
        call load_record(beside(file%path, trim(record)), format, units, dt, acceleration, &
                         status, message)
        if (status == SD_OK) ground = record_ground(dt, acceleration)
      else
        call require(file, G_GROUND_MOTION, 'peak_acceleration', status, message)
        ! a sweep in frequency sets it (a start <= 0 is &sweep's error, reported there)
        if (sweep_frequency >= 0 .and. .not. given(file, G_GROUND_MOTION, 'frequency')) &
          frequency = merge(sweep_frequency, 1.0_wp, sweep_frequency > 0)
        if (sweep_frequency < 0) call require(file, G_GROUND_MOTION, 'frequency', status, &
                                              message)
        if (status == SD_OK) ground = harmonic_ground(peak_acceleration*to_si, frequency)
      end if
    end if
    if (status == SD_OK) then
      if (target_period <= 0) target_period = props%sloshing_period
      call scale_ground(ground, scale_factor, target_pga*to_si, target_sa*to_si, target_period, &
                        target_damping, status, message)
    end if
    if (status /= SD_OK .and. index(message, '&ground_motion') /= 1) &
      message = '&ground_motion: '//trim(message)
  end subroutine read_ground_motion

  !> A path relative to the folder of the input file (absolute paths as they are).
  pure function beside(input_path, path) result(full)
    character(len=*), intent(in) :: input_path, path
    character(len=:), allocatable :: full
    integer :: slash
    slash = index(input_path, '/', back=.true.)
    if (path(1:1) == '/' .or. slash == 0) then
      full = path
    else
      full = input_path(1:slash)//path
    end if
  end function beside

  !> &seismic: the duration [s] and number of outputs of a seismic response (0: the defaults of
  !> sloshdyn_seismic).
  subroutine read_seismic(file, t_end, n_out, status, message)
    type(input_file), intent(inout) :: file
    real(wp), intent(inout) :: t_end
    integer, intent(inout) :: n_out
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(group_reader) :: reader
    namelist /seismic/ t_end, n_out
    status = SD_OK
    message = ''
    call reader%start(file, G_SEISMIC, status)
    do while (reader%next())
      if (reader%describing) then
        write (reader%written, nml=seismic, iostat=reader%ios)
      else
        read (reader%text, nml=seismic, iostat=reader%ios, iomsg=reader%iomsg)
      end if
      call reader%check(file, status, message)
    end do
    call check_real('t_end', t_end, 0.0_wp, huge(1.0_wp), .false., .true., &
                    't_end must be >= 0 [s] (0: the record plus 5 sloshing periods)', status, &
                    message)
    if (status == SD_OK .and. (n_out < 0 .or. n_out > max_seismic_outputs)) then
      status = SD_BAD_INPUT
      message = 'n_out = '//num2str(n_out)//' is out of range: it must lie in [2, '// &
                num2str(max_seismic_outputs)//'] (0: the default)'
    end if
    if (status == SD_OK .and. n_out == 1) then
      status = SD_BAD_INPUT
      message = 'n_out = 1 is out of range: it must lie in [2, '//num2str(max_seismic_outputs)// &
                '] (0: the default)'
    end if
    if (status /= SD_OK) message = '&seismic: '//trim(message)
  end subroutine read_seismic

  subroutine read_excitation(file, amplitude, frequency, status, message)
    type(input_file), intent(inout) :: file
    real(wp), intent(out) :: amplitude, frequency
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(model_t) :: defaults
    real(wp) :: A, rho
    type(group_reader) :: reader
    namelist /excitation/ A, rho
    A = defaults%excitation%A
    rho = defaults%excitation%rho
    status = SD_OK
    message = ''
    call reader%start(file, G_EXCITATION, status)
    do while (reader%next())
      if (reader%describing) then
        write (reader%written, nml=excitation, iostat=reader%ios)
      else
        read (reader%text, nml=excitation, iostat=reader%ios, iomsg=reader%iomsg)
      end if
      call reader%check(file, status, message)
    end do
    amplitude = A
    frequency = rho
  end subroutine read_excitation

  subroutine read_analysis(file, config, status, message)
    type(input_file), intent(inout) :: file
    type(run_config), intent(inout) :: config
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    character(len=word_len) :: kind
    real(wp) :: sigma1, kappa_min, kappa_max
    integer :: i
    type(group_reader) :: reader
    namelist /analysis/ kind, sigma1, kappa_min, kappa_max

    kind = known_analyses(ANALYSIS_LINEAR)
    sigma1 = 0
    kappa_min = 0
    kappa_max = config%model%s1 + 1000
    status = SD_OK
    message = ''
    call reader%start(file, G_ANALYSIS, status)
    do while (reader%next())
      if (reader%describing) then
        write (reader%written, nml=analysis, iostat=reader%ios)
      else
        read (reader%text, nml=analysis, iostat=reader%ios, iomsg=reader%iomsg)
      end if
      call reader%check(file, status, message)
    end do
    if (status /= SD_OK) return
    config%analysis = 0
    do i = 1, size(known_analyses)
      if (known_analyses(i) == adjustl(kind)) config%analysis = i
    end do
    if (config%analysis == 0) then
      call fail(status, message, '&analysis: kind = '''//trim(adjustl(kind))//''' is not '// &
                'known; allowed: '//join(known_analyses))
      return
    end if
    call check_real('sigma1', sigma1, -huge(1.0_wp), huge(1.0_wp), .false., .false., &
                    'sigma1 must be finite', status, message)
    call check_real('kappa_max', kappa_max, config%model%s1, huge(1.0_wp), .true., .true., &
                    'kappa_max must be > s1 = '//num2str(config%model%s1), status, message)
    call check_real('kappa_min', kappa_min, -huge(1.0_wp), kappa_max, .false., .true., &
                    'kappa_min must be < kappa_max = '//num2str(kappa_max), status, message)
    if (status /= SD_OK) then
      message = '&analysis: '//trim(message)
      return
    end if
    config%sigma1 = sigma1
    config%kappa_min = kappa_min
    config%kappa_max = kappa_max
  end subroutine read_analysis

  subroutine read_output(file, path, status, message)
    type(input_file), intent(inout) :: file
    character(len=path_len), intent(out) :: path
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    character(len=path_len + 1) :: directory
    type(run_config) :: defaults
    type(group_reader) :: reader
    namelist /output/ directory
    directory = defaults%directory
    path = ''
    status = SD_OK
    message = ''
    call reader%start(file, G_OUTPUT, status)
    do while (reader%next())
      if (reader%describing) then
        write (reader%written, nml=output, iostat=reader%ios)
      else
        read (reader%text, nml=output, iostat=reader%ios, iomsg=reader%iomsg)
      end if
      call reader%check(file, status, message)
    end do
    if (status /= SD_OK) return
    if (len_trim(directory) == 0) then
      call fail(status, message, '&output: directory = '''' is empty: give a directory name')
    else if (len_trim(directory) > path_len) then
      call fail(status, message, '&output: directory is too long: it must have at most '// &
                num2str(path_len)//' characters')
    else
      path = directory(1:path_len)
    end if
  end subroutine read_output

  subroutine read_integration(file, options, method_code, status, message)
    type(input_file), intent(inout) :: file
    type(ode_options), intent(out) :: options
    integer, intent(out) :: method_code, status
    character(len=message_len), intent(out) :: message
    real(wp) :: rtol, atol, h_initial, h_max, h_min
    integer :: max_steps, i
    character(len=word_len) :: method
    type(group_reader) :: reader
    namelist /integration/ rtol, atol, h_initial, h_max, h_min, max_steps, method

    rtol = options%rtol; atol = options%atol; h_initial = options%h_initial
    h_max = options%h_max; h_min = options%h_min; max_steps = options%max_steps
    method = method_names(METHOD_AUTO)
    method_code = METHOD_AUTO
    status = SD_OK
    message = ''
    call reader%start(file, G_INTEGRATION, status)
    do while (reader%next())
      if (reader%describing) then
        write (reader%written, nml=integration, iostat=reader%ios)
      else
        read (reader%text, nml=integration, iostat=reader%ios, iomsg=reader%iomsg)
      end if
      call reader%check(file, status, message)
    end do
    if (status /= SD_OK) return
    method_code = -1
    do i = lbound(method_names, 1), ubound(method_names, 1)
      if (method_names(i) == adjustl(method)) method_code = i
    end do
    if (method_code < 0) then
      call fail(status, message, '&integration: method = '''//trim(adjustl(method))//''' is '// &
                'not known; allowed: '//join(method_names))
      return
    end if
    options%rtol = rtol; options%atol = atol; options%h_initial = h_initial
    options%h_max = h_max; options%h_min = h_min; options%max_steps = max_steps
    call check_options(options, [1.0_wp, 1.0_wp, 1.0_wp, 1.0_wp], status, message)
    if (status /= SD_OK) message = '&integration: '//trim(message)
  end subroutine read_integration

  subroutine read_simulation(file, needed, settings, status, message)
    type(input_file), intent(inout) :: file
    logical, intent(in) :: needed
    type(simulation_settings), intent(out) :: settings
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: t_end, y0(4)
    integer :: n_out, i
    type(group_reader) :: reader
    namelist /simulation/ t_end, n_out, y0

    t_end = settings%t_end; n_out = settings%n_out; y0 = settings%y0
    status = SD_OK
    message = ''
    call reader%start(file, G_SIMULATION, status)
    do while (reader%next())
      if (reader%describing) then
        write (reader%written, nml=simulation, iostat=reader%ios)
      else
        read (reader%text, nml=simulation, iostat=reader%ios, iomsg=reader%iomsg)
      end if
      call reader%check(file, status, message)
    end do
    if (status /= SD_OK) return
    do i = 1, 4
      call check_real('y0('//num2str(i)//')', y0(i), -huge(1.0_wp), huge(1.0_wp), .false., &
                      .false., 'the initial state (x1, x1'', x2, x2'') must be finite', status, &
                      message)
    end do
    if (needed) then
      call require(file, G_SIMULATION, 't_end', status, message)
      if (status /= SD_OK) return
      call check_real('t_end', t_end, 0.0_wp, huge(1.0_wp), .true., .true., &
                      't_end must be > 0 (the simulation starts at tau = 0)', status, message)
      if (status == SD_OK .and. (n_out < 2 .or. n_out > 10000000)) then
        status = SD_BAD_INPUT
        message = 'n_out = '//num2str(n_out)//' is out of range: it must lie in [2, 10000000]'
      end if
    end if
    if (status /= SD_OK) then
      message = '&simulation: '//trim(message)
      return
    end if
    settings = simulation_settings(t_end, n_out, y0)
  end subroutine read_simulation

  !> &steady; its rules with the forcing frequency are applied by check_analysis.
  subroutine read_steady(file, options, status, message)
    type(input_file), intent(inout) :: file
    type(steady_options), intent(out) :: options
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: transient_periods, settle_tol, max_transient_periods, periodic_tol
    integer :: window_periods, samples_per_period
    logical :: shooting
    type(group_reader) :: reader
    namelist /steady/ transient_periods, settle_tol, max_transient_periods, window_periods, &
                      samples_per_period, periodic_tol, shooting

    transient_periods = options%transient_periods; settle_tol = options%settle_tol
    max_transient_periods = options%max_transient_periods
    window_periods = options%window_periods; samples_per_period = options%samples_per_period
    periodic_tol = options%periodic_tol; shooting = options%shooting
    status = SD_OK
    message = ''
    call reader%start(file, G_STEADY, status)
    do while (reader%next())
      if (reader%describing) then
        write (reader%written, nml=steady, iostat=reader%ios)
      else
        read (reader%text, nml=steady, iostat=reader%ios, iomsg=reader%iomsg)
      end if
      call reader%check(file, status, message)
    end do
    options = steady_options(transient_periods, settle_tol, max_transient_periods, &
                             window_periods, samples_per_period, periodic_tol, shooting)
  end subroutine read_steady

  subroutine read_sweep(file, needed, settings, status, message)
    type(input_file), intent(inout) :: file
    logical, intent(in) :: needed
    type(sweep_settings), intent(out) :: settings
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    character(len=word_len) :: parameter, direction, start_from
    real(wp) :: start, stop
    integer :: n_points, threads, i
    type(group_reader) :: reader
    namelist /sweep/ parameter, start, stop, n_points, direction, start_from, threads

    parameter = 'rho'; direction = direction_names(settings%direction)
    start = settings%start; stop = settings%stop; n_points = settings%n_points
    start_from = 'previous'; threads = settings%threads
    status = SD_OK
    message = ''
    call reader%start(file, G_SWEEP, status)
    do while (reader%next())
      if (reader%describing) then
        write (reader%written, nml=sweep, iostat=reader%ios)
      else
        read (reader%text, nml=sweep, iostat=reader%ios, iomsg=reader%iomsg)
      end if
      call reader%check(file, status, message)
    end do
    if (status /= SD_OK) return
    ! what was given is kept; the rules apply when the analysis is a sweep
    settings%start = start
    settings%stop = stop
    settings%n_points = n_points
    settings%threads = threads
    call excitation_parameter('sweep', parameter, settings%parameter, status, message)
    if (status /= SD_OK) return
    select case (adjustl(start_from))
    case ('previous')
      settings%carry_state = .true.
    case ('y0')
      settings%carry_state = .false.
    case default
      call fail(status, message, "&sweep: start_from = '"//trim(adjustl(start_from))// &
                "' is not known; allowed: previous, y0")
      return
    end select
    settings%direction = 0
    do i = 1, size(direction_names)
      if (direction_names(i) == adjustl(direction)) settings%direction = i
    end do
    if (settings%direction == 0) then
      call fail(status, message, '&sweep: direction = '''//trim(adjustl(direction))//''' is '// &
                'not known; allowed: '//join(direction_names))
      return
    end if
    if (.not. needed) return
    call require(file, G_SWEEP, 'start', status, message)
    call require(file, G_SWEEP, 'stop', status, message)
    call require(file, G_SWEEP, 'n_points', status, message)
    if (status /= SD_OK) return
    if (settings%parameter == PARAMETER_RHO) then
      call check_real('start', start, 0.0_wp, huge(1.0_wp), .true., .true., &
                      'sweep values of rho must be > 0', status, message)
      call check_real('stop', stop, 0.0_wp, huge(1.0_wp), .true., .true., &
                      'sweep values of rho must be > 0', status, message)
    else if (settings%parameter == PARAMETER_FREQUENCY) then
      call check_real('start', start, 0.0_wp, huge(1.0_wp), .true., .true., &
                      'sweep frequencies must be > 0 [Hz]', status, message)
      call check_real('stop', stop, 0.0_wp, huge(1.0_wp), .true., .true., &
                      'sweep frequencies must be > 0 [Hz]', status, message)
    else
      call check_real('start', start, 0.0_wp, huge(1.0_wp), .false., .true., &
                      'sweep values of A must be >= 0', status, message)
      call check_real('stop', stop, 0.0_wp, huge(1.0_wp), .false., .true., &
                      'sweep values of A must be >= 0', status, message)
    end if
    if (status == SD_OK .and. (n_points < 1 .or. n_points > 100000)) then
      status = SD_BAD_INPUT
      message = 'n_points = '//num2str(n_points)//' is out of range: it must lie in [1, 100000]'
    end if
    call check_threads(threads, settings%carry_state, status, message)
    if (status /= SD_OK) message = '&sweep: '//trim(message)
  end subroutine read_sweep

  !> &study (see study_settings). The rules of the kind of study chosen apply.
  subroutine read_study(file, config, status, message)
    type(input_file), intent(inout) :: file
    type(run_config), intent(inout) :: config
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(study_settings) :: defaults
    character(len=word_len) :: kind, worker_kind, continuation
    character(len=study_text_len + 1) :: store, figure, scheduler, records
    real(wp) :: frequency_start, frequency_stop, amplitude_start, amplitude_stop, x1_start, &
                x1_stop, dx1_start, dx1_stop, tol, intensity_start, intensity_stop, &
                spectral_damping
    integer :: workers, points_per_task, n_frequencies, n_amplitudes, n_grid, n_intensities
    type(model_t) :: first
    type(group_reader) :: reader
    namelist /study/ kind, store, figure, scheduler, workers, worker_kind, points_per_task, &
                     frequency_start, frequency_stop, n_frequencies, amplitude_start, &
                     amplitude_stop, n_amplitudes, continuation, x1_start, x1_stop, dx1_start, &
                     dx1_stop, n_grid, tol, records, intensity_start, intensity_stop, &
                     n_intensities, spectral_damping

    kind = study_kinds(defaults%kind); store = ''; figure = ''; scheduler = ''
    workers = defaults%workers; worker_kind = worker_kinds(defaults%worker_kind)
    points_per_task = defaults%points_per_task
    frequency_start = defaults%frequency_start; frequency_stop = defaults%frequency_stop
    n_frequencies = defaults%n_frequencies; amplitude_start = defaults%amplitude_start
    amplitude_stop = defaults%amplitude_stop; n_amplitudes = defaults%n_amplitudes
    continuation = continuation_names(defaults%continuation)
    x1_start = defaults%x1_start; x1_stop = defaults%x1_stop
    dx1_start = defaults%dx1_start; dx1_stop = defaults%dx1_stop
    n_grid = defaults%n_grid; tol = defaults%tol
    records = ''; intensity_start = defaults%intensity_start
    intensity_stop = defaults%intensity_stop; n_intensities = defaults%n_intensities
    spectral_damping = defaults%spectral_damping
    status = SD_OK
    message = ''
    call reader%start(file, G_STUDY, status)
    do while (reader%next())
      if (reader%describing) then
        write (reader%written, nml=study, iostat=reader%ios)
      else
        read (reader%text, nml=study, iostat=reader%ios, iomsg=reader%iomsg)
      end if
      call reader%check(file, status, message)
    end do
    if (status /= SD_OK .or. file%describing) return
    if (.not. file%groups(G_STUDY)%given) return
    associate (st => config%study)
      st%given = .true.
      call pick('kind', kind, study_kinds, st%kind)
      call pick('worker_kind', worker_kind, worker_kinds, st%worker_kind)
      call pick('continuation', continuation, continuation_names, st%continuation)
      call require(file, G_STUDY, 'store', status, message)
      if (status /= SD_OK) return
      if (len_trim(store) == 0) call fail(status, message, &
        '&study: store = '''' is empty: give the path of the Zarr store')
      if (len_trim(store) > study_text_len .or. len_trim(figure) > study_text_len .or. &
          len_trim(scheduler) > study_text_len) call fail(status, message, '&study: store, '// &
        'figure and scheduler must have at most '//num2str(study_text_len)//' characters')
      if (status /= SD_OK) return
      st%store = store(1:study_text_len)
      st%figure = figure(1:study_text_len)
      st%scheduler = scheduler(1:study_text_len)
      call check_count('workers', workers, 0, 1024)
      call check_count('points_per_task', points_per_task, 0, 1000000)
      st%workers = workers
      st%points_per_task = points_per_task
      if (status /= SD_OK) return
      first = config%model
      select case (st%kind)
      case (1)     ! response_map
        call require(file, G_STUDY, 'frequency_start', status, message)
        call require(file, G_STUDY, 'frequency_stop', status, message)
        call require(file, G_STUDY, 'amplitude_start', status, message)
        call require(file, G_STUDY, 'amplitude_stop', status, message)
        if (status /= SD_OK) return
        call check_real('frequency_start', frequency_start, 0.0_wp, huge(1.0_wp), .true., &
                        .true., 'frequencies (rho) must be > 0', status, message)
        call check_real('frequency_stop', frequency_stop, 0.0_wp, huge(1.0_wp), .true., &
                        .true., 'frequencies (rho) must be > 0', status, message)
        call check_real('amplitude_start', amplitude_start, 0.0_wp, huge(1.0_wp), .false., &
                        .true., 'amplitudes (A) must be >= 0', status, message)
        call check_real('amplitude_stop', amplitude_stop, 0.0_wp, huge(1.0_wp), .false., &
                        .true., 'amplitudes (A) must be >= 0', status, message)
        if (status /= SD_OK) then
          message = '&study: '//trim(message)
          return
        end if
        call check_count('n_frequencies', n_frequencies, 1, 100000)
        call check_count('n_amplitudes', n_amplitudes, 1, 100000)
        if (status == SD_OK .and. n_frequencies > 1 .and. frequency_start == frequency_stop) &
          call fail(status, message, '&study: frequency_start = frequency_stop with '// &
                    'n_frequencies > 1 repeats one frequency')
        if (status == SD_OK .and. n_amplitudes > 1 .and. amplitude_start == amplitude_stop) &
          call fail(status, message, '&study: amplitude_start = amplitude_stop with '// &
                    'n_amplitudes > 1 repeats one amplitude')
        if (status /= SD_OK) return
        st%frequency_start = frequency_start; st%frequency_stop = frequency_stop
        st%amplitude_start = amplitude_start; st%amplitude_stop = amplitude_stop
        st%n_frequencies = n_frequencies; st%n_amplitudes = n_amplitudes
        first%excitation%rho = min(frequency_start, frequency_stop)
      case (2)     ! basins
        call require(file, G_STUDY, 'x1_start', status, message)
        call require(file, G_STUDY, 'x1_stop', status, message)
        call require(file, G_STUDY, 'dx1_start', status, message)
        call require(file, G_STUDY, 'dx1_stop', status, message)
        if (status /= SD_OK) return
        call check_real('x1_stop', x1_stop, x1_start, huge(1.0_wp), .true., .true., &
                        'x1_stop must be > x1_start = '//num2str(x1_start), status, message)
        call check_real('dx1_stop', dx1_stop, dx1_start, huge(1.0_wp), .true., .true., &
                        'dx1_stop must be > dx1_start = '//num2str(dx1_start), status, message)
        call check_real('x1_start', x1_start, -huge(1.0_wp), huge(1.0_wp), .false., .false., &
                        'x1_start must be finite', status, message)
        call check_real('dx1_start', dx1_start, -huge(1.0_wp), huge(1.0_wp), .false., .false., &
                        'dx1_start must be finite', status, message)
        call check_real('tol', tol, 0.0_wp, 1.0_wp, .true., .true., 'tol must lie in (0, 1)', &
                        status, message)
        if (status /= SD_OK) then
          message = '&study: '//trim(message)
          return
        end if
        call check_count('n_grid', n_grid, 2, 10000)
        if (status /= SD_OK) return
        st%x1_start = x1_start; st%x1_stop = x1_stop
        st%dx1_start = dx1_start; st%dx1_stop = dx1_stop
        st%n_grid = n_grid; st%tol = tol
      case (3)     ! fragility
        if (.not. file%groups(G_TANK)%given) then
          call fail(status, message, '&study: a fragility study needs the tank: group &tank '// &
                    'is missing')
          return
        end if
        call require(file, G_STUDY, 'records', status, message)
        call require(file, G_STUDY, 'intensity_start', status, message)
        call require(file, G_STUDY, 'intensity_stop', status, message)
        if (status /= SD_OK) return
        if (len_trim(records) == 0 .or. len_trim(records) > study_text_len) &
          call fail(status, message, '&study: records must name the record files (a pattern '// &
                    'such as ''records/*.AT2''), at most '//num2str(study_text_len)// &
                    ' characters')
        call check_real('intensity_start', intensity_start, 0.0_wp, huge(1.0_wp), .true., &
                        .true., 'intensities (Sa [g]) must be > 0', status, message)
        call check_real('intensity_stop', intensity_stop, intensity_start, huge(1.0_wp), &
                        .false., .true., 'intensity_stop must be >= intensity_start = '// &
                        num2str(intensity_start), status, message)
        call check_real('spectral_damping', spectral_damping, 0.0_wp, 1.0_wp, .false., .true., &
                        'spectral_damping must lie in [0, 1)', status, message)
        if (status /= SD_OK) then
          if (index(message, '&study') /= 1) message = '&study: '//trim(message)
          return
        end if
        call check_count('n_intensities', n_intensities, 1, 100000)
        if (status == SD_OK .and. n_intensities > 1 .and. intensity_start == intensity_stop) &
          call fail(status, message, '&study: intensity_start = intensity_stop with '// &
                    'n_intensities > 1 repeats one intensity')
        if (status /= SD_OK) return
        st%records = records(1:study_text_len)
        st%intensity_start = intensity_start; st%intensity_stop = intensity_stop
        st%n_intensities = n_intensities; st%spectral_damping = spectral_damping
      end select
      if (file%groups(G_ANALYSIS)%given) then
        call fail(status, message, 'give &analysis (a run of the executable) or &study (a '// &
                  'study, sloshdyn-py study), not both')
        return
      end if
      if (st%kind == 3) return
      call check_steady(first, config%steady, status, message)
      if (status /= SD_OK) message = trim(merge('&excitation', '&steady    ', &
                                                index(message, 'rho') == 1))//': '//trim(message)
    end associate

  contains

    subroutine pick(name, value, names, code)
      character(len=*), intent(in) :: name, value, names(:)
      integer, intent(inout) :: code
      integer :: i
      if (status /= SD_OK) return
      code = 0
      do i = 1, size(names)
        if (names(i) == adjustl(value)) code = i
      end do
      if (code == 0) call fail(status, message, '&study: '//name//' = '''// &
                               trim(adjustl(value))//''' is not known; allowed: '//join(names))
    end subroutine pick

    subroutine check_count(name, value, lower, upper)
      character(len=*), intent(in) :: name
      integer, intent(in) :: value, lower, upper
      if (status /= SD_OK) return
      if (value < lower .or. value > upper) call fail(status, message, '&study: '//name// &
        ' = '//num2str(value)//' is out of range: it must lie in ['//num2str(lower)//', '// &
        num2str(upper)//']')
    end subroutine check_count
  end subroutine read_study

  !> &response; the interval is stored lower end first.
  subroutine read_response(file, needed, settings, status, message)
    type(input_file), intent(inout) :: file
    logical, intent(in) :: needed
    type(response_settings), intent(out) :: settings
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    character(len=word_len) :: resonance, parameter
    real(wp) :: start, stop, amplitude_min, amplitude_max, ds, ds_min, ds_max, x_scale
    integer :: n_scan, n_amplitudes, n_phases, max_points
    type(group_reader) :: reader
    namelist /response/ resonance, parameter, start, stop, n_scan, n_amplitudes, n_phases, &
                        amplitude_min, amplitude_max, ds, ds_min, ds_max, x_scale, max_points

    resonance = '3:1'; parameter = 'rho'; start = 0; stop = 0
    associate (o => settings%options, c => settings%options%continuation)
      n_scan = o%n_scan; n_amplitudes = o%n_amplitudes; n_phases = o%n_phases
      amplitude_min = o%amplitude_min; amplitude_max = o%amplitude_max
      ds = c%ds; ds_min = c%ds_min; ds_max = c%ds_max; x_scale = c%x_scale
      max_points = c%max_points
    end associate
    status = SD_OK
    message = ''
    call reader%start(file, G_RESPONSE, status)
    do while (reader%next())
      if (reader%describing) then
        write (reader%written, nml=response, iostat=reader%ios)
      else
        read (reader%text, nml=response, iostat=reader%ios, iomsg=reader%iomsg)
      end if
      call reader%check(file, status, message)
    end do
    if (status /= SD_OK) return
    if (adjustl(resonance) /= '3:1' .and. adjustl(resonance) /= 'none') then
      call fail(status, message, "&response: resonance = '"//trim(adjustl(resonance))// &
                "' is not known; allowed: 3:1, none")
      return
    end if
    call excitation_parameter('response', parameter, settings%parameter, status, message)
    if (status /= SD_OK) return
    ! what was given is kept; the rules apply when the analysis uses &response
    settings%internal_resonance = adjustl(resonance) == '3:1'
    settings%start = min(start, stop)
    settings%stop = max(start, stop)
    associate (o => settings%options, c => settings%options%continuation)
      o%n_scan = n_scan; o%n_amplitudes = n_amplitudes; o%n_phases = n_phases
      o%amplitude_min = amplitude_min; o%amplitude_max = amplitude_max
      c%ds = ds; c%ds_min = ds_min; c%ds_max = ds_max; c%x_scale = x_scale
      c%max_points = max_points
    end associate
    if (.not. needed) return
    call require(file, G_RESPONSE, 'start', status, message)
    call require(file, G_RESPONSE, 'stop', status, message)
    if (status /= SD_OK) return
    if (start == stop) then
      status = SD_BAD_INPUT
      message = '&response: start = stop = '//num2str(start)//': the interval is empty'
      return
    end if
    call check_response_options(settings%options, settings%parameter, settings%start, &
                                settings%stop, status, message)
    if (status /= SD_OK) message = '&response: '//trim(message)
  end subroutine read_response

  subroutine read_lyapunov(file, options, status, message)
    type(input_file), intent(inout) :: file
    type(lyapunov_options), intent(out) :: options
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: transient_periods
    integer :: n_periods, renormalise_every
    logical :: spectrum
    type(group_reader) :: reader
    namelist /lyapunov/ transient_periods, n_periods, renormalise_every, spectrum
    spectrum = options%spectrum
    transient_periods = options%transient_periods
    n_periods = options%n_periods
    renormalise_every = options%renormalise_every
    status = SD_OK
    message = ''
    call reader%start(file, G_LYAPUNOV, status)
    do while (reader%next())
      if (reader%describing) then
        write (reader%written, nml=lyapunov, iostat=reader%ios)
      else
        read (reader%text, nml=lyapunov, iostat=reader%ios, iomsg=reader%iomsg)
      end if
      call reader%check(file, status, message)
    end do
    call check_real('transient_periods', transient_periods, 0.0_wp, 1.0e9_wp, .false., .false., &
                    'transient_periods must lie in [0, 1e9]', status, message)
    if (status /= SD_OK) then
      message = '&lyapunov: '//trim(message)
      return
    end if
    options = lyapunov_options(nint(transient_periods), n_periods, renormalise_every, spectrum)
  end subroutine read_lyapunov

  !> &chart: a stability chart of the slow flow (sloshdyn_stability_chart): the model, the
  !> parameters on the axes and their box, the grid, the settings of the runs and curves.
  subroutine read_chart(file, needed, settings, status, message)
    type(input_file), intent(inout) :: file
    logical, intent(in) :: needed
    type(chart_settings), intent(out) :: settings
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    character(len=word_len) :: model, x, y
    real(wp) :: x_min, x_max, y_min, y_max
    integer :: n_x, n_y, n_scan, max_points, max_curves, brute_force_starts, threads
    type(group_reader) :: reader
    namelist /chart/ model, x, y, x_min, x_max, y_min, y_max, n_x, n_y, n_scan, max_points, &
                     max_curves, brute_force_starts, threads

    model = chart_models(settings%model); x = 'rho'; y = 'A'
    x_min = 0; x_max = 0; y_min = 0; y_max = 0
    n_x = settings%n_columns; n_y = settings%n_levels; n_scan = settings%response%n_scan
    max_points = settings%max_points; max_curves = settings%max_curves
    brute_force_starts = settings%brute_force_starts
    threads = settings%threads
    status = SD_OK
    message = ''
    call reader%start(file, G_CHART, status)
    do while (reader%next())
      if (reader%describing) then
        write (reader%written, nml=chart, iostat=reader%ios)
      else
        read (reader%text, nml=chart, iostat=reader%ios, iomsg=reader%iomsg)
      end if
      call reader%check(file, status, message)
    end do
    if (status /= SD_OK .or. .not. needed) return
    call require(file, G_CHART, 'x_min', status, message)
    call require(file, G_CHART, 'x_max', status, message)
    call require(file, G_CHART, 'y_min', status, message)
    call require(file, G_CHART, 'y_max', status, message)
    if (status /= SD_OK) return
    settings%model = findloc_word(chart_models, model)
    if (settings%model == 0) call fail(status, message, "&chart: model = '"// &
                                       trim(adjustl(model))//"' is not known; allowed: "// &
                                       join(chart_models))
    settings%parameters = [axis_code(x), axis_code(y)]
    if (status == SD_OK .and. any(settings%parameters == 0)) &
      call fail(status, message, "&chart: x = '"//trim(adjustl(x))//"', y = '"// &
                trim(adjustl(y))//"': the axes are two of rho, A, gamma, kappa (x: rho or A)")
    if (status /= SD_OK) return
    settings%p_min = [x_min, y_min]
    settings%p_max = [x_max, y_max]
    settings%n_columns = n_x
    settings%n_levels = n_y
    settings%response%n_scan = n_scan
    settings%max_points = max_points
    settings%max_curves = max_curves
    settings%brute_force_starts = brute_force_starts
    settings%threads = threads
    call check_chart_settings(settings, status, message)
    if (status /= SD_OK) message = '&chart: '//trim(message)
  end subroutine read_chart

  !> The chart parameter code (CHART_*) of an axis name, 0 if there is none.
  pure integer function axis_code(word) result(code)
    character(len=*), intent(in) :: word
    integer :: k
    code = 0
    do k = CHART_RHO, CHART_KAPPA
      if (chart_parameter_name(k) == trim(adjustl(word))) code = k
    end do
  end function axis_code

  !> The index of a word in a list (blanks and case of the word ignored), 0 if absent.
  pure integer function findloc_word(list, word) result(k)
    character(len=*), intent(in) :: list(:), word
    integer :: i
    k = 0
    do i = 1, size(list)
      if (lower(trim(list(i))) == lower(trim(adjustl(word)))) k = i
    end do
  end function findloc_word

  !> The rules that tie the groups to the analysis asked for.
  subroutine check_analysis(config, status, message)
    type(run_config), intent(inout) :: config
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    type(model_t) :: first

    if (config%analysis == ANALYSIS_SEISMIC .and. .not. (config%dimensional .and. &
                                                         config%has_ground)) then
      call fail(status, message, "&analysis: kind = 'seismic' needs a tank (&tank) and its "// &
                'ground motion (&ground_motion)')
      return
    end if
    if (config%has_ground .and. config%ground%kind == GROUND_RECORD .and. .not. any( &
        config%analysis == [ANALYSIS_SEISMIC, ANALYSIS_SIMULATE, ANALYSIS_LINEAR])) then
      call fail(status, message, "&analysis: kind = '"//trim(known_analyses(config%analysis))// &
                "' needs harmonic ground motion (peak_acceleration, frequency), not a record")
      return
    end if

    select case (config%analysis)
    case (ANALYSIS_LINEAR)
      call require_stable_trivial(config%model, status, message)
    case (ANALYSIS_STEADY_STATE, ANALYSIS_SWEEP)
      first = config%model
      if (config%analysis == ANALYSIS_SWEEP .and. config%sweep%parameter == PARAMETER_RHO) &
        first%excitation%rho = min(config%sweep%start, config%sweep%stop)
      if (config%analysis == ANALYSIS_SWEEP .and. &
          config%sweep%parameter == PARAMETER_FREQUENCY) then
        if (.not. (config%dimensional .and. config%has_ground)) then
          call fail(status, message, "&sweep: parameter = 'frequency' sweeps a tank's harmonic "// &
                    'ground motion: it needs &tank and &ground_motion')
          return
        end if
        call set_excitation_parameter(first%excitation, PARAMETER_FREQUENCY, &
                                      2*pi*min(config%sweep%start, config%sweep%stop)/ &
                                      config%tank_props%omega, status, message)
      end if
      call check_steady(first, config%steady, status, message)
      if (status /= SD_OK) message = trim(merge('&excitation', '&steady    ', &
                                                index(message, 'rho') == 1))//': '//trim(message)
    case (ANALYSIS_FREQUENCY_RESPONSE, ANALYSIS_STABILITY_CHART)
      call require_stable_trivial(config%model, status, message)
    case (ANALYSIS_PERIODIC_RESPONSE)
      call require_stable_trivial(config%model, status, message)
      if (status /= SD_OK) return
      first = config%model
      if (config%response%parameter == PARAMETER_RHO) first%excitation%rho = config%response%start
      call check_steady(first, config%steady, status, message)
      if (status /= SD_OK) message = '&steady/&excitation: '//trim(message)
    case (ANALYSIS_LYAPUNOV)
      call check_real('rho', config%model%excitation%rho, 0.0_wp, huge(1.0_wp), .true., .true., &
                      'the Lyapunov exponent needs a forcing frequency rho > 0', status, message)
      if (status /= SD_OK) then
        message = '&excitation: '//trim(message)
        return
      end if
      call check_lyapunov(config%lyapunov, status, message)
      if (status /= SD_OK) message = '&lyapunov: '//trim(message)
    end select
  end subroutine check_analysis

  ! ---- reading groups --------------------------------------------------------------------------

  !> Start reading group `group` of the file (nothing to read after an earlier failure).
  subroutine start_group(reader, file, group, status)
    class(group_reader), intent(out) :: reader
    type(input_file), intent(in) :: file
    integer, intent(in) :: group, status
    reader%group = group
    reader%name = trim(known_groups(group))
    reader%describing = file%describing
    reader%done = status /= SD_OK .or. .not. (file%describing .or. file%groups(group)%given)
    if (.not. file%describing .and. .not. reader%done) then
      reader%body = file%groups(group)%body
      reader%line = file%groups(group)%line
      reader%path = file%path
      reader%next_start = next_assignment(reader%body, 1)
    end if
  end subroutine start_group

  !> Whether there is a text to parse (or, describing, the group to write): the whole group
  !> first; if that fails, each assignment alone, to name the one at fault.
  logical function next_text(reader)
    class(group_reader), intent(inout) :: reader
    integer :: start, next
    next_text = .false.
    if (reader%done) return
    next_text = .true.
    reader%step = reader%step + 1
    if (reader%describing) then
      reader%text = ''
    else if (reader%step == 1) then
      reader%text = '&'//reader%name//' '//reader%body//' /'
    else
      start = reader%next_start
      next = next_assignment(reader%body, start + 1)
      if (next > 0) then
        reader%assignment = trim(reader%body(start:next - 1))
      else
        reader%assignment = trim(reader%body(start:))
      end if
      ! the separator before the next assignment is not part of this one
      if (reader%assignment(len(reader%assignment):) == ',') &
        reader%assignment = trim(reader%assignment(:len(reader%assignment) - 1))
      reader%text = '&'//reader%name//' '//reader%assignment//' /'
      reader%next_start = next
    end if
  end function next_text

  !> The outcome of parsing the current text (reader%ios, reader%iomsg of the namelist read), or,
  !> describing, the group written with its values (reader%written).
  subroutine check_text(reader, file, status, message)
    class(group_reader), intent(inout) :: reader
    type(input_file), intent(inout) :: file
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    character(len=:), allocatable :: prefix, token
    integer :: equals

    if (reader%describing) then
      file%description = file%description//trim(reader%written)//new_line('a')
      reader%done = .true.
      return
    end if
    if (reader%step == 1) then
      reader%done = reader%ios == 0
      if (reader%done) return
      ! text before the first assignment is at fault, or else one of the assignments
      prefix = reader%body(1:merge(reader%next_start - 1, len(reader%body), &
                                   reader%next_start > 0))
      if (len_trim(prefix) > 0) then
        call fail(status, message, '&'//reader%name//" in '"//reader%path//"' (line "// &
                  num2str(reader%line)//"): unexpected text '"//trim(adjustl(prefix))// &
                  "' before the first assignment")
        reader%done = .true.
      end if
    else
      equals = index(reader%assignment, '=')
      token = bad_value(reader%assignment(equals + 1:))
      if (len(token) > 0) then
        call fail(status, message, '&'//reader%name//" in '"//reader%path//"': "// &
                  trim(adjustl(reader%assignment(1:equals - 1)))//' ='// &
                  trim(reader%assignment(equals + 1:))//": '"//token//"' is not a value "// &
                  "(a number or a quoted string; a variable needs 'name = value')")
        reader%done = .true.
      else if (reader%ios /= 0) then
        call fail(status, message, '&'//reader%name//" in '"//reader%path//"': "// &
                  trim(adjustl(reader%assignment(1:equals - 1)))//' ='// &
                  trim(reader%assignment(equals + 1:))//' is not valid: '// &
                  expected_type(variable_name(reader%assignment(1:equals - 1))))
        reader%done = .true.
      end if
    end if
    if (.not. reader%done .and. reader%next_start == 0) then
      ! every assignment parses alone, the group does not
      call fail(status, message, '&'//reader%name//" in '"//reader%path//"' cannot be read: "// &
                trim(reader%iomsg))
      reader%done = .true.
    end if
  end subroutine check_text

  !> The first token of an assignment's value text that is no value: values are numbers (with an
  !> optional repeat count r*), quoted strings or logicals, separated by commas or blanks. A bare
  !> name there is a variable without '='. '' if every token is a value.
  pure function bad_value(values) result(token)
    character(len=*), intent(in) :: values
    character(len=:), allocatable :: token
    integer :: i, start, star
    character :: quote

    token = ''
    i = 1
    do while (i <= len(values))
      if (values(i:i) == ' ' .or. values(i:i) == ',') then
        i = i + 1
        cycle
      end if
      start = i
      if (values(i:i) == '''' .or. values(i:i) == '"') then
        ! a quoted string, doubled quotes inside
        quote = values(i:i)
        i = i + 1
        do while (i <= len(values))
          if (values(i:i) == quote) then
            if (i < len(values)) then
              if (values(i + 1:i + 1) == quote) then
                i = i + 2
                cycle
              end if
            end if
            exit
          end if
          i = i + 1
        end do
        i = i + 1
        cycle
      end if
      do while (i <= len(values))
        if (values(i:i) == ' ' .or. values(i:i) == ',') exit
        i = i + 1
      end do
      token = values(start:i - 1)
      star = index(token, '*')
      if (star > 0) then
        if (verify(token(1:star - 1), '0123456789') == 0 .and. star > 1) token = token(star + 1:)
      end if
      if (len(token) == 0 .or. is_number(lower(token)) .or. is_logical(lower(token))) then
        token = ''
      else
        token = values(start:i - 1)
        return
      end if
    end do
  end function bad_value

  !> A Fortran real or integer literal, or NaN/Infinity as list-directed input reads them.
  pure logical function is_number(text)
    character(len=*), intent(in) :: text
    integer :: i, digits
    logical :: exponent
    is_number = .false.
    if (text == 'nan' .or. text == 'inf' .or. text == 'infinity' .or. text == '+inf' .or. &
        text == '-inf' .or. text == '+infinity' .or. text == '-infinity') then
      is_number = .true.
      return
    end if
    i = 1
    if (scan(text(1:1), '+-') == 1) i = 2
    digits = 0
    do while (i <= len(text))
      if (index('0123456789', text(i:i)) == 0) exit
      digits = digits + 1
      i = i + 1
    end do
    if (i <= len(text)) then
      if (text(i:i) == '.') then
        i = i + 1
        do while (i <= len(text))
          if (index('0123456789', text(i:i)) == 0) exit
          digits = digits + 1
          i = i + 1
        end do
      end if
    end if
    if (digits == 0) return
    exponent = .false.
    if (i <= len(text)) then
      if (scan(text(i:i), 'ed') == 1) then
        exponent = .true.
        i = i + 1
        if (i <= len(text)) then
          if (scan(text(i:i), '+-') == 1) i = i + 1
        end if
        digits = 0
        do while (i <= len(text))
          if (index('0123456789', text(i:i)) == 0) exit
          digits = digits + 1
          i = i + 1
        end do
        if (digits == 0) return
      end if
    end if
    is_number = i > len(text)
  end function is_number

  pure logical function is_logical(text)
    character(len=*), intent(in) :: text
    is_logical = text == 't' .or. text == 'f' .or. text == '.t.' .or. text == '.f.' .or. &
                 text == '.true.' .or. text == '.false.'
  end function is_logical

  !> A required variable must be assigned in its group (an explicit NaN is assigned, and fails
  !> its range check instead).
  subroutine require(file, group, name, status, message)
    type(input_file), intent(in) :: file
    integer, intent(in) :: group
    character(len=*), intent(in) :: name
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    character(len=:), allocatable :: display
    if (status /= SD_OK .or. file%describing) return
    if (given(file, group, name)) return
    display = name
    call fail(status, message, '&'//trim(known_groups(group))//': required variable '// &
              display//' is missing')
  end subroutine require

  !> Whether the file assigns the variable in the group.
  pure logical function given(file, group, name)
    type(input_file), intent(in) :: file
    integer, intent(in) :: group
    character(len=*), intent(in) :: name
    given = .false.
    if (file%groups(group)%given) given = index(file%groups(group)%assigned, ','//name//',') > 0
  end function given

  !> The first frequency [Hz] of a sweep in frequency (parameter = 'frequency'); -1 if there is
  !> none or &sweep cannot be read (its own reading reports why).
  function frequency_of_sweep(file) result(frequency)
    type(input_file), intent(inout) :: file
    real(wp) :: frequency
    type(sweep_settings) :: sweep
    integer :: status
    character(len=message_len) :: message
    frequency = -1
    if (.not. file%groups(G_SWEEP)%given) return
    call read_sweep(file, .false., sweep, status, message)
    if (status == SD_OK .and. sweep%parameter == PARAMETER_FREQUENCY) &
      frequency = max(min(sweep%start, sweep%stop), 0.0_wp)
  end function frequency_of_sweep

  !> Threads for a sweep: any number in [1, 1024] for independent points; one for a sweep that
  !> carries the state, whose points depend on each other (more would change the answer).
  pure subroutine check_threads(threads, carry_state, status, message)
    integer, intent(in) :: threads
    logical, intent(in) :: carry_state
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    if (status /= SD_OK) return
    if (threads < 1 .or. threads > 1024) then
      status = SD_BAD_INPUT
      message = 'threads = '//num2str(threads)//' is out of range: it must lie in [1, 1024]'
    else if (carry_state .and. threads > 1) then
      status = SD_BAD_INPUT
      message = 'threads = '//num2str(threads)//": a sweep that carries the state "// &
                "(start_from = 'previous') runs on one thread, each point starting from the "// &
                "one before; use start_from = 'y0' for independent points, or threads = 1"
    end if
  end subroutine check_threads

  !> 'rho' or 'A' for the group's parameter; &sweep also 'frequency' (a tank's harmonic ground
  !> motion at constant peak acceleration, in Hz).
  subroutine excitation_parameter(group, text, parameter, status, message)
    character(len=*), intent(in) :: group, text
    integer, intent(out) :: parameter
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    parameter = PARAMETER_RHO
    select case (adjustl(text))
    case ('rho')
      parameter = PARAMETER_RHO
    case ('A', 'a')
      parameter = PARAMETER_A
    case ('frequency')
      if (group == 'sweep') then
        parameter = PARAMETER_FREQUENCY
      else
        call fail(status, message, '&'//group//": parameter = 'frequency' is for &sweep only; "// &
                  'allowed here: rho, A')
      end if
    case default
      call fail(status, message, '&'//group//': parameter = '''//trim(adjustl(text))// &
                ''' is not known; allowed: rho, A'//trim(merge(', frequency', '           ', &
                                                              group == 'sweep')))
    end select
  end subroutine excitation_parameter

  pure subroutine fail(status, message, text)
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    character(len=*), intent(in) :: text
    if (status /= SD_OK) return
    status = SD_BAD_INPUT
    message = text
  end subroutine fail

  !> What a variable must be, for messages.
  pure function expected_type(name) result(text)
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: text
    select case (name)
    case ('n', 'p', 'max_steps', 'n_out', 'window_periods', 'samples_per_period', 'n_points', &
          'n_scan', 'n_amplitudes', 'n_phases', 'n_periods', 'renormalise_every', 'max_points', &
          'threads', 'workers', 'points_per_task', 'n_frequencies', 'n_grid', 'n_intensities')
      text = name//' must be an integer'
    case ('kind', 'directory', 'parameter', 'direction', 'resonance', 'method', 'start_from', &
          'record', 'format', 'units', 'store', 'figure', 'scheduler', 'worker_kind', &
          'continuation', 'records')
      text = name//' must be a quoted string'
    case ('shooting')
      text = name//' must be .true. or .false.'
    case ('y0')
      text = 'y0 must be four real numbers (x1, x1'', x2, x2''), or y0(i) = one of them, i = 1..4'
    case ('s1', 'mu1', 'kappa', 'theta0', 'beta', 'gamma', 'delta', 'zeta', 'a', 'rho', &
          'sigma1', 'kappa_min', &
          'kappa_max', 'rtol', 'atol', 'h_initial', 'h_max', 'h_min', 't_end', 'settle_tol', &
          'radius', 'liquid_depth', 'freeboard', 'liquid_density', 'liquid_mass', 'tank_mass', &
          'support_frequency', 'support_damping', 'support_stiffness', &
          'support_damping_coefficient', 'support_height', 'sloshing_damping', &
          'impact_stiffness', 'impact_damping', 'gravity', 'peak_acceleration', 'frequency', &
          'scale_factor', 'target_pga', 'target_sa', 'target_period', 'target_damping', &
          'transient_periods', &
          'max_transient_periods', 'periodic_tol', 'start', 'stop', 'amplitude_min', &
          'amplitude_max', 'ds', 'ds_min', 'ds_max', 'x_scale', 'frequency_start', &
          'frequency_stop', 'amplitude_start', 'amplitude_stop', 'x1_start', 'x1_stop', &
          'dx1_start', 'dx1_stop', 'tol', 'intensity_start', 'intensity_stop', &
          'spectral_damping')
      text = name//' must be a real number'
    case default
      text = 'unknown variable '''//name//''' (see the namelist reference in README.md)'
    end select
  end function expected_type

  ! ---- scanning the file -----------------------------------------------------------------------

  !> Split the file into its groups. Errors: a missing or unreadable file, text outside groups,
  !> unknown, repeated or unclosed groups, no group at all.
  subroutine scan_file(path, file, status, message)
    character(len=*), intent(in) :: path
    type(input_file), intent(out) :: file
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    character(len=:), allocatable :: text, name, body
    integer :: i, k, n, line, group, start_line
    logical :: inside_quotes
    character :: quote

    file%path = path
    call read_text(path, text, status, message)
    if (status /= SD_OK) return
    n = len(text)
    i = 1
    line = 1
    do while (i <= n)
      select case (text(i:i))
      case (' ', char(9), char(13))
        i = i + 1
      case (char(10))
        line = line + 1
        i = i + 1
      case ('!')
        call skip_comment()
      case ('&', '$')
        ! a group: its name, then its body up to '/' (or &end) outside quotes
        start_line = line
        i = i + 1
        name = ''
        do while (i <= n)
          if (.not. is_name_char(text(i:i))) exit
          name = name//lower(text(i:i))
          i = i + 1
        end do
        group = 0
        do k = 1, size(known_groups)
          if (known_groups(k) == name) group = k
        end do
        if (len(name) == 0 .or. name == 'end') then
          call fail(status, message, 'a group name must follow & in '''//path//''' (line '// &
                    num2str(start_line)//')')
        else if (group == 0 .and. name == 'structure') then
          call fail(status, message, 'namelist group &structure in '''//path//''' (line '// &
                    num2str(start_line)//') is no longer read: &tank describes the whole '// &
                    'tank in SI units, its supports by support_frequency and '// &
                    'support_damping (or support_stiffness, support_damping_coefficient, '// &
                    'support_height); README.md, "Namelist reference"')
        else if (group == 0) then
          call fail(status, message, 'unknown namelist group &'//name//' in '''//path// &
                    ''' (line '//num2str(start_line)//'); known groups: &'// &
                    join(known_groups, ', &'))
        else if (file%groups(group)%given) then
          call fail(status, message, 'namelist group &'//name//' appears twice in '''//path// &
                    ''' (lines '//num2str(file%groups(group)%line)//' and '// &
                    num2str(start_line)//')')
        end if
        if (status /= SD_OK) return
        body = ''
        inside_quotes = .false.
        quote = ' '
        do
          if (i > n) then
            call fail(status, message, 'namelist group &'//name//' in '''//path//''' (line '// &
                      num2str(start_line)//') is not closed: end it with /')
            return
          end if
          if (inside_quotes) then
            if (text(i:i) == quote) inside_quotes = .false.
          else if (text(i:i) == '"' .or. text(i:i) == '''') then
            inside_quotes = .true.
            quote = text(i:i)
          else if (text(i:i) == '!') then
            call skip_comment()
            body = body//' '
            cycle
          else if (text(i:i) == '/') then
            i = i + 1
            exit
          else if (text(i:i) == '&' .or. text(i:i) == '$') then
            ! &end (or $end, $) closes the group
            i = i + 1
            do while (i <= n)
              if (.not. is_name_char(text(i:i))) exit
              i = i + 1
            end do
            exit
          end if
          if (text(i:i) == char(10)) then
            line = line + 1
            body = body//' '
          else if (text(i:i) == char(9) .or. text(i:i) == char(13)) then
            body = body//' '
          else
            body = body//text(i:i)
          end if
          i = i + 1
        end do
        file%groups(group)%given = .true.
        file%groups(group)%line = start_line
        file%groups(group)%body = body
        file%groups(group)%assigned = assignment_names(body)
      case default
        call fail(status, message, 'unexpected text '''//trim(next_word())//''' outside a '// &
                  'namelist group in '''//path//''' (line '//num2str(line)//'): groups start '// &
                  'with &name and end with /')
        return
      end select
    end do
    if (.not. any(file%groups%given)) &
      call fail(status, message, 'no namelist group found in '''//path//''' (expected &model '// &
                '... /)')

  contains

    subroutine skip_comment()
      do while (i <= n)
        if (text(i:i) == char(10)) exit
        i = i + 1
      end do
    end subroutine skip_comment

    function next_word() result(word)
      character(len=:), allocatable :: word
      integer :: j
      j = i
      do while (j <= n .and. j < i + 40)
        if (text(j:j) == ' ' .or. text(j:j) == char(10) .or. text(j:j) == char(13)) exit
        j = j + 1
      end do
      word = text(i:j - 1)
    end function next_word
  end subroutine scan_file

  !> The whole file as one string.
  subroutine read_text(path, text, status, message)
    character(len=*), intent(in) :: path
    character(len=:), allocatable, intent(out) :: text   !< unallocated on failure
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    character(len=message_len) :: iomsg
    integer :: unit, ios, file_size
    logical :: exists

    status = SD_OK
    message = ''
    inquire (file=path, exist=exists)
    if (exists) inquire (file=trim(path)//'/.', exist=exists)
    if (exists) then
      status = SD_IO_ERROR
      message = 'cannot read input file '''//path//''': it is a directory'
      return
    end if
    open (newunit=unit, file=path, status='old', action='read', access='stream', &
          form='unformatted', iostat=ios, iomsg=iomsg)
    if (ios /= 0) then
      status = SD_IO_ERROR
      message = 'cannot open input file '''//path//''': '//trim(iomsg)
      return
    end if
    inquire (unit=unit, size=file_size)
    allocate (character(len=max(file_size, 0)) :: text)
    if (file_size > 0) then
      read (unit, iostat=ios, iomsg=iomsg) text
      if (ios /= 0) then
        status = SD_IO_ERROR
        message = 'cannot read input file '''//path//''': '//trim(iomsg)
      end if
    end if
    close (unit)
  end subroutine read_text

  !> ',name1,name2,...,' of the variables assigned in a group body (lower case, indices dropped).
  pure function assignment_names(body) result(names)
    character(len=*), intent(in) :: body
    character(len=:), allocatable :: names
    integer :: start, equals
    names = ','
    start = next_assignment(body, 1)
    do while (start > 0)
      equals = start + index(body(start:), '=') - 1
      names = names//variable_name(body(start:equals - 1))//','
      start = next_assignment(body, start + 1)
    end do
  end function assignment_names

  !> The variable of the left side of an assignment: 'y0(2) ' -> 'y0', lower case.
  pure function variable_name(left) result(name)
    character(len=*), intent(in) :: left
    character(len=:), allocatable :: name
    integer :: paren
    name = trim(adjustl(left))
    paren = index(name, '(')
    if (paren > 0) name = trim(name(1:paren - 1))
    name = lower(name)
  end function variable_name

  !> Position of the next `name =` or `name(index) =` at or after `from` outside quotes, 0 if
  !> none.
  pure integer function next_assignment(text, from) result(position)
    character(len=*), intent(in) :: text
    integer, intent(in) :: from
    integer :: i, j, k
    logical :: quoted
    character :: quote

    position = 0
    quoted = .false.
    quote = ' '
    do i = 1, len(text)
      if (quoted) then
        if (text(i:i) == quote) quoted = .false.
        cycle
      end if
      if (text(i:i) == '"' .or. text(i:i) == '''') then
        quoted = .true.
        quote = text(i:i)
        cycle
      end if
      if (i < from) cycle
      if (.not. is_name_start(text(i:i))) cycle
      if (i > 1) then
        if (is_name_char(text(i - 1:i - 1))) cycle
      end if
      j = i
      do while (j <= len(text))
        if (.not. is_name_char(text(j:j))) exit
        j = j + 1
      end do
      j = skip_blanks(text, j)
      if (j <= len(text)) then
        if (text(j:j) == '(') then
          ! an array index: up to the closing parenthesis
          k = index(text(j:), ')')
          if (k == 0) cycle
          j = skip_blanks(text, j + k)
        end if
      end if
      if (j <= len(text)) then
        if (text(j:j) == '=') then
          position = i
          return
        end if
      end if
    end do
  end function next_assignment

  pure integer function skip_blanks(text, from) result(j)
    character(len=*), intent(in) :: text
    integer, intent(in) :: from
    j = from
    do while (j <= len(text))
      if (text(j:j) /= ' ') exit
      j = j + 1
    end do
  end function skip_blanks

  pure logical function is_name_start(ch)
    character, intent(in) :: ch
    is_name_start = index('abcdefghijklmnopqrstuvwxyz', lower(ch)) > 0
  end function is_name_start

  pure logical function is_name_char(ch)
    character, intent(in) :: ch
    is_name_char = index('abcdefghijklmnopqrstuvwxyz0123456789_', lower(ch)) > 0
  end function is_name_char

  pure function lower(text) result(low)
    character(len=*), intent(in) :: text
    character(len=len(text)) :: low
    integer :: i
    low = text
    do i = 1, len(text)
      if (text(i:i) >= 'A' .and. text(i:i) <= 'Z') low(i:i) = achar(iachar(text(i:i)) + 32)
    end do
  end function lower

  pure function join(items, separator) result(text)
    character(len=*), intent(in) :: items(:)
    character(len=*), intent(in), optional :: separator
    character(len=:), allocatable :: text
    integer :: i
    text = trim(items(1))
    do i = 2, size(items)
      if (present(separator)) then
        text = text//separator//trim(items(i))
      else
        text = text//', '//trim(items(i))
      end if
    end do
  end function join
end module sloshdyn_namelist
