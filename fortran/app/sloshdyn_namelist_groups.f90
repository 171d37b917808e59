!> The groups of the input file and their readers: each group has its own reader with its own
!> local variables, whose defaults come from the settings types of the analyses, and applies the
!> group's own rules (the rules that tie groups together are read_input's, sloshdyn_namelist).
!> The groups and variables are documented in docs/namelist.md.
module sloshdyn_namelist_groups
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, check_real, check_output_count
  use sloshdyn_text, only: num2str
  use sloshdyn_namelist_scanner, only: input_file, group_reader, scan_file, start_description, &
                                       require, given, list_length, fail, lower, join
  use sloshdyn_run_config, only: run_config, simulation_settings, sweep_settings, &
                                 response_settings, seismic_settings, known_analyses, path_len, &
                                 word_len, chart_models, direction_names, DIRECTION_UP, &
                                 ANALYSIS_LINEAR
  use sloshdyn_model, only: model_t, model_to_arrays, model_from_arrays, n_real_params, &
                            n_int_params
  use sloshdyn_excitation, only: PARAMETER_RHO, PARAMETER_A, PARAMETER_FREQUENCY
  use sloshdyn_spatial, only: spatial_model_t
  use sloshdyn_vessel, only: tank_t, tank_properties
  use sloshdyn_ground, only: ground_motion_t
  use sloshdyn_design_spectra, only: design_spectrum_t
  use sloshdyn_design_loads, only: design_factors_t
  use sloshdyn_tank_structure, only: tank_structure_t
  use sloshdyn_stability_chart, only: chart_settings, check_chart_settings
  use sloshdyn_slowflow_chart, only: chart_parameter_name, CHART_RHO, CHART_A, CHART_GAMMA, &
                                     CHART_KAPPA
  use sloshdyn_ode, only: ode_options, check_options
  use sloshdyn_integrator, only: METHOD_AUTO, method_names
  use sloshdyn_simulation, only: steady_options, max_simulation_outputs
  use sloshdyn_response, only: response_options, check_response_options
  use sloshdyn_periodic_response, only: lyapunov_options
  use sloshdyn_lyapunov, only: average_names
  implicit none
  private
  public :: known_groups, namelist_reader, open_input, describe_groups, check_threads
  public :: G_MODEL, G_TANK, G_GROUND_MOTION, G_EXCITATION, G_ANALYSIS, G_OUTPUT, &
            G_INTEGRATION, G_SIMULATION, G_STEADY, G_SWEEP, G_RESPONSE, G_LYAPUNOV, G_SEISMIC, &
            G_CHART, G_STUDY
  public :: read_model, read_tank, read_ground_motion, read_excitation, read_analysis, &
            read_output, read_integration, read_simulation, read_steady, read_sweep, &
            read_response, read_lyapunov, read_seismic, read_chart, frequency_of_sweep, &
            read_design
  public :: G_DESIGN, G_TANK_STRUCTURE, read_tank_structure

  character(len=*), parameter :: known_groups(17) = &
    [character(len=14) :: 'model', 'tank', 'ground_motion', 'excitation', 'analysis', 'output', &
     'integration', 'simulation', 'steady', 'sweep', 'response', 'lyapunov', 'seismic', 'chart', &
     'study', 'design', 'tank_structure']
  integer, parameter :: G_MODEL = 1, G_TANK = 2, G_GROUND_MOTION = 3, G_EXCITATION = 4, &
                        G_ANALYSIS = 5, G_OUTPUT = 6, G_INTEGRATION = 7, G_SIMULATION = 8, &
                        G_STEADY = 9, G_SWEEP = 10, G_RESPONSE = 11, G_LYAPUNOV = 12, &
                        G_SEISMIC = 13, G_CHART = 14, G_STUDY = 15, G_DESIGN = 16, &
                        G_TANK_STRUCTURE = 17

  !> The reader of a group of these: its messages say what each variable must be.
  type, extends(group_reader) :: namelist_reader
  contains
    procedure, nopass :: hint => expected_type
  end type namelist_reader

  ! the groups of a tank in SI units and its design check: submodule sloshdyn_namelist_tank
  interface
    !> &tank: a cylindrical or rectangular tank on supports in SI units (sloshdyn_vessel).
    module subroutine read_tank(file, vessel, planar, status, message)
      type(input_file), intent(inout) :: file
      type(tank_t), intent(out) :: vessel
      logical, intent(out) :: planar
      integer, intent(out) :: status
      character(len=message_len), intent(out) :: message
    end subroutine read_tank
    !> &ground_motion: a record or harmonic motion, scaled; its second horizontal component.
    module subroutine read_ground_motion(file, props, sweep_frequency, ground, ground_y, has_y, &
                                         azimuth, ellipticity, status, message)
      type(input_file), intent(inout) :: file
      type(tank_properties), intent(in) :: props
      real(wp), intent(in) :: sweep_frequency
      type(ground_motion_t), intent(out) :: ground, ground_y
      logical, intent(out) :: has_y
      real(wp), intent(out) :: azimuth, ellipticity
      integer, intent(out) :: status
      character(len=message_len), intent(out) :: message
    end subroutine read_ground_motion
    !> &seismic (see seismic_settings).
    module subroutine read_seismic(file, settings, status, message)
      type(input_file), intent(inout) :: file
      type(seismic_settings), intent(out) :: settings
      integer, intent(out) :: status
      character(len=message_len), intent(out) :: message
    end subroutine read_seismic
    !> &design: the spectrum of the design check and the codes' factors.
    module subroutine read_design(file, spec, factors, from_ground, status, message)
      type(input_file), intent(inout) :: file
      type(design_spectrum_t), intent(out) :: spec
      type(design_factors_t), intent(out) :: factors
      logical, intent(out) :: from_ground
      integer, intent(out) :: status
      character(len=message_len), intent(out) :: message
    end subroutine read_design
    !> &tank_structure: the tank's structure for the design check's structural checks.
    module subroutine read_tank_structure(file, st, status, message)
      type(input_file), intent(inout) :: file
      type(tank_structure_t), intent(out) :: st
      integer, intent(out) :: status
      character(len=message_len), intent(out) :: message
    end subroutine read_tank_structure
    !> A path relative to the folder of the input file (absolute paths as they are).
    module pure function beside(input_path, path) result(full)
      character(len=*), intent(in) :: input_path, path
      character(len=:), allocatable :: full
    end function beside
  end interface

contains

  !> The input file at path, split into these groups (sloshdyn_namelist_scanner).
  subroutine open_input(path, file, status, message)
    character(len=*), intent(in) :: path
    type(input_file), intent(out) :: file
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    call scan_file(path, known_groups, file, status, message, retired=['structure'], &
                   retired_hint=['&tank describes the tank in SI units, its supports by '// &
                                 'support_frequency and support_damping (docs/namelist.md)'])
  end subroutine open_input

  !> A file that describes these groups with their defaults instead of reading them.
  subroutine describe_groups(file)
    type(input_file), intent(out) :: file
    call start_description(known_groups, file)
  end subroutine describe_groups

  !> &model: groups = [s1, mu1, kappa, theta0, beta, gamma, delta, zeta], exponents = [n, p],
  !> planar (.false.: the spatial model of issue 26, sloshdyn_spatial).
  subroutine read_model(file, groups, exponents, planar, status, message)
    type(input_file), intent(inout) :: file
    real(wp), intent(out) :: groups(8)
    integer, intent(out) :: exponents(2), status
    logical, intent(out) :: planar
    character(len=message_len), intent(out) :: message
    type(model_t) :: defaults
    real(wp) :: s1, mu1, kappa, theta0, beta, gamma, delta, zeta
    integer :: n, p
    type(namelist_reader) :: reader
    namelist /model/ s1, mu1, kappa, theta0, beta, gamma, delta, zeta, n, p, planar

    s1 = 0; mu1 = 0; kappa = 0; theta0 = 0
    beta = defaults%beta; gamma = defaults%gamma; delta = defaults%delta; zeta = defaults%zeta
    n = defaults%n; p = defaults%p
    planar = .true.
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

  !> &excitation: A, rho and, for the spatial model (planar = .false.), the direction of the
  !> harmonic motion azimuth [rad from x] and its ellipticity (sloshdyn_spatial's
  !> spatial_model_t).
  subroutine read_excitation(file, amplitude, frequency, azimuth, ellipticity, status, message)
    type(input_file), intent(inout) :: file
    real(wp), intent(out) :: amplitude, frequency, azimuth, ellipticity
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(model_t) :: defaults
    type(spatial_model_t) :: spatial_defaults
    real(wp) :: A, rho
    type(namelist_reader) :: reader
    namelist /excitation/ A, rho, azimuth, ellipticity
    A = defaults%excitation%A
    rho = defaults%excitation%rho
    azimuth = spatial_defaults%azimuth
    ellipticity = spatial_defaults%ellipticity
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
    call check_real('azimuth', azimuth, -2*pi, 2*pi, .false., .false., &
                    'azimuth must lie in [-2 pi, 2 pi] rad (from the x axis)', status, message)
    call check_real('ellipticity', ellipticity, 0.0_wp, 1.0_wp, .false., .false., &
                    'ellipticity (minor over major axis of the base motion''s ellipse) must '// &
                    'lie in [0, 1]', status, message)
    if (status /= SD_OK .and. index(message, '&excitation') /= 1) &
      message = '&excitation: '//trim(message)
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
    type(namelist_reader) :: reader
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
    character(len=:), allocatable :: full
    type(run_config) :: defaults
    type(namelist_reader) :: reader
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
    ! relative to the input file's folder, as every path of an input file (docs/namelist.md)
    full = trim(directory)
    if (len(full) > 0 .and. .not. file%describing) full = beside(file%path, full)
    if (len(full) == 0) then
      call fail(status, message, '&output: directory = '''' is empty: give a directory name')
    else if (len(full) > path_len) then
      call fail(status, message, '&output: directory is too long: it must have at most '// &
                num2str(path_len)//' characters, with the input file''s folder')
    else
      path = full
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
    type(namelist_reader) :: reader
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
    real(wp) :: t_end, y0(8)
    integer :: n_out, i
    type(namelist_reader) :: reader
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
    do i = 1, size(y0)
      call check_real('y0('//num2str(i)//')', y0(i), -huge(1.0_wp), huge(1.0_wp), .false., &
                      .false., 'the initial state (x1, x1'', x2, x2'' and, for the spatial '// &
                      'model, y1, y1'', y2, y2'') must be finite', status, message)
    end do
    if (needed) then
      call require(file, G_SIMULATION, 't_end', status, message)
      if (status /= SD_OK) return
      call check_real('t_end', t_end, 0.0_wp, huge(1.0_wp), .true., .true., &
                      't_end must be > 0 (the simulation starts at tau = 0)', status, message)
      call check_output_count('n_out', n_out, max_simulation_outputs, .false., status, message)
    end if
    if (status /= SD_OK) then
      message = '&simulation: '//trim(message)
      return
    end if
    settings = simulation_settings(t_end, n_out, y0, list_length(file, G_SIMULATION, 'y0'))
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
    type(namelist_reader) :: reader
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
    type(namelist_reader) :: reader
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

  !> &response; the interval is stored lower end first.
  subroutine read_response(file, needed, settings, status, message)
    type(input_file), intent(inout) :: file
    logical, intent(in) :: needed
    type(response_settings), intent(out) :: settings
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    character(len=word_len) :: resonance, parameter
    real(wp) :: start, stop, amplitude_min, amplitude_max, ds, ds_min, ds_max, x_scale, x_tol, &
                f_tol, curve_start, curve_stop
    integer :: n_scan, n_amplitudes, n_phases, max_points, max_iter, switch_at, curve_at
    type(namelist_reader) :: reader
    namelist /response/ resonance, parameter, start, stop, n_scan, n_amplitudes, n_phases, &
                        amplitude_min, amplitude_max, ds, ds_min, ds_max, x_scale, max_points, &
                        x_tol, f_tol, max_iter, switch_at, curve_at, curve_start, curve_stop

    resonance = '3:1'; parameter = 'rho'; start = 0; stop = 0; switch_at = settings%switch_at
    curve_at = settings%curve_at; curve_start = settings%curve_start
    curve_stop = settings%curve_stop
    associate (o => settings%options, c => settings%options%continuation)
      n_scan = o%n_scan; n_amplitudes = o%n_amplitudes; n_phases = o%n_phases
      amplitude_min = o%amplitude_min; amplitude_max = o%amplitude_max
      ds = c%ds; ds_min = c%ds_min; ds_max = c%ds_max; x_scale = c%x_scale
      max_points = c%max_points
      x_tol = c%newton%x_tol; f_tol = c%newton%f_tol; max_iter = c%newton%max_iter
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
    settings%switch_at = switch_at
    if (switch_at < 0) then
      call fail(status, message, '&response: switch_at = '//num2str(switch_at)// &
                ' is out of range: it must be >= 0 (0: no branch switching)')
      return
    end if
    call read_curve_range(file, settings, curve_at, curve_start, curve_stop, status, message)
    if (status /= SD_OK) return
    associate (o => settings%options, c => settings%options%continuation)
      o%n_scan = n_scan; o%n_amplitudes = n_amplitudes; o%n_phases = n_phases
      o%amplitude_min = amplitude_min; o%amplitude_max = amplitude_max
      c%ds = ds; c%ds_min = ds_min; c%ds_max = ds_max; c%x_scale = x_scale
      c%max_points = max_points
      c%newton%x_tol = x_tol; c%newton%f_tol = f_tol; c%newton%max_iter = max_iter
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

  !> &response's curve through a special point (periodic_response): curve_at >= 0 (0: none)
  !> and, with it, the other parameter's range curve_start, curve_stop (A >= 0, rho > 0; stored
  !> lower end first).
  subroutine read_curve_range(file, settings, curve_at, curve_start, curve_stop, status, message)
    type(input_file), intent(inout) :: file
    type(response_settings), intent(inout) :: settings
    integer, intent(in) :: curve_at
    real(wp), intent(in) :: curve_start, curve_stop
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    logical :: rho
    character(len=:), allocatable :: other, rule
    settings%curve_at = curve_at
    settings%curve_start = min(curve_start, curve_stop)
    settings%curve_stop = max(curve_start, curve_stop)
    if (curve_at < 0) then
      call fail(status, message, '&response: curve_at = '//num2str(curve_at)// &
                ' is out of range: it must be >= 0 (0: no curve)')
      return
    end if
    if (curve_at == 0) return
    call require(file, G_RESPONSE, 'curve_start', status, message)
    call require(file, G_RESPONSE, 'curve_stop', status, message)
    if (status /= SD_OK) return
    rho = settings%parameter /= PARAMETER_RHO    ! the curve's other parameter is rho
    other = trim(merge('rho', 'A  ', rho))
    rule = ' (the curve''s range of '//other//') must be '//trim(merge('> 0 ', '>= 0', rho))
    call check_real('curve_start', curve_start, 0.0_wp, huge(1.0_wp), rho, .true., &
                    'curve_start'//rule, status, message)
    call check_real('curve_stop', curve_stop, 0.0_wp, huge(1.0_wp), rho, .true., &
                    'curve_stop'//rule, status, message)
    if (status == SD_OK .and. curve_start == curve_stop) &
      call fail(status, message, 'curve_start = curve_stop = '//num2str(curve_start)// &
                ': the curve''s range is empty')
    if (status /= SD_OK .and. index(message, '&response') /= 1) &
      message = '&response: '//trim(message)
  end subroutine read_curve_range

  subroutine read_lyapunov(file, options, status, message)
    type(input_file), intent(inout) :: file
    type(lyapunov_options), intent(out) :: options
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: transient_periods
    integer :: n_periods, renormalise_every, average_code
    logical :: spectrum
    character(len=16) :: average
    type(namelist_reader) :: reader
    namelist /lyapunov/ transient_periods, n_periods, renormalise_every, spectrum, average
    spectrum = options%spectrum
    average = average_names(options%average)
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
    average_code = findloc_word(average_names, average)
    if (average_code == 0) then
      call fail(status, message, '&lyapunov: average = '''//trim(adjustl(average))//''' is '// &
                'not known; allowed: '//join(average_names))
      return
    end if
    options = lyapunov_options(nint(transient_periods), n_periods, renormalise_every, spectrum, &
                               average_code)
  end subroutine read_lyapunov

  !> &chart: a stability chart of the slow flow (sloshdyn_stability_chart): the model, the
  !> parameters on the axes and their box, the grid, the settings of the runs and curves.
  !> The box must lie where the model's rules allow its parameters (check_chart_box).
  subroutine read_chart(file, needed, system, runs, settings, status, message)
    type(input_file), intent(inout) :: file
    logical, intent(in) :: needed
    type(model_t), intent(in) :: system   !< the model of &model or &tank
    !> the settings of the one-parameter runs: &response's numbers (n_scan is &chart's)
    type(response_options), intent(in) :: runs
    type(chart_settings), intent(out) :: settings
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    character(len=word_len) :: model, x, y
    real(wp) :: x_min, x_max, y_min, y_max
    integer :: n_x, n_y, n_scan, max_points, max_curves, brute_force_starts, threads
    type(namelist_reader) :: reader
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
    settings%response = runs
    settings%response%n_scan = n_scan
    settings%max_points = max_points
    settings%max_curves = max_curves
    settings%brute_force_starts = brute_force_starts
    settings%threads = threads
    call check_chart_settings(settings, status, message)
    call check_chart_box(system, settings, status, message)
    if (status /= SD_OK .and. index(message, '&chart') /= 1) message = '&chart: '//trim(message)
  end subroutine read_chart

  !> Every corner of a chart's box is a model the rules of &model and &excitation allow
  !> (model_from_arrays, the one check of both groups): e.g. y = A needs y_max <= the largest A.
  pure subroutine check_chart_box(model, settings, status, message)
    type(model_t), intent(in) :: model
    type(chart_settings), intent(in) :: settings
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    character(len=*), parameter :: bound_names(2, 2) = &
      reshape([character(len=5) :: 'x_min', 'y_min', 'x_max', 'y_max'], [2, 2])
    type(model_t) :: corner
    real(wp) :: rpar(n_real_params), bounds(2, 2)
    integer :: ipar(n_int_params), k, b, model_status
    character(len=message_len) :: model_message

    if (status /= SD_OK) return
    ! a model that breaks the rules itself is not the box's fault (its reader reports it)
    call model_to_arrays(model, rpar, ipar)
    call model_from_arrays(rpar, ipar, corner, model_status, model_message)
    if (model_status /= SD_OK) return
    bounds(:, 1) = settings%p_min
    bounds(:, 2) = settings%p_max
    do b = 1, 2
      do k = 1, 2
        corner = model
        select case (settings%parameters(k))
        case (CHART_RHO);   corner%excitation%rho = bounds(k, b)
        case (CHART_A);     corner%excitation%A = bounds(k, b)
        case (CHART_GAMMA); corner%gamma = bounds(k, b)
        case (CHART_KAPPA); corner%kappa = bounds(k, b)
        end select
        call model_to_arrays(corner, rpar, ipar)
        call model_from_arrays(rpar, ipar, corner, status, message)
        if (status /= SD_OK) then
          message = '&chart: '//bound_names(k, b)//' = '//num2str(bounds(k, b))//' ('// &
                    chart_parameter_name(settings%parameters(k))//'): '//trim(message)
          return
        end if
      end do
    end do
  end subroutine check_chart_box

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

  !> What a variable must be, for messages, where its type alone does not say it (the
  !> scanner tells the type of every other variable: check_probe); '' for the others.
  pure function expected_type(name) result(text)
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: text
    text = ''
    if (name == 'y0') text = 'y0 must be four real numbers (x1, x1'', x2, x2''), eight for '// &
                             'the spatial model (then y1, y1'', y2, y2''), or y0(i) = one of '// &
                             'them, i = 1..8'
  end function expected_type
end module sloshdyn_namelist_groups
