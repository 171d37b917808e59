!> The f2py bridge of parameters.py (read_namelist) and cli.py: the namelist reader and runs of an
!> input file as the executable runs it, cancellation and exit codes.
!> The bridge's contract (c_double/c_int arrays in named layouts, status and message,
!> threads and the GIL) is written once, in sloshdyn_bridge_model.f90.
module sloshdyn_bridge_input
  use, intrinsic :: iso_c_binding, only: c_double, c_int
  implicit none

contains

  !> Read and validate a namelist input file (the executable's reader) and return it flattened,
  !> every array in its named layout (sloshdyn_layouts): the model (rpar, ipar); the analysis
  !> code (1-based index into the 'analyses' names) with analysis_values ('analysis'); the
  !> output directory; tank and ground with has_tank, has_ground (1/0) and n_samples (the
  !> record's length, for input_record); seismic, integration, steady, response, lyapunov,
  !> simulation, sweep, response_range, chart, chart_range and study; study_store, study_figure,
  !> study_scheduler, study_records the &study strings; planar (1/0), spatial ('spatial': azimuth,
  !> ellipticity), has_ground_y, ground_y and n_samples_y the spatial model's second component
  !> (issue 26); has_design (1/0) and design ('design': &design, issue 25); tank_structure
  !> ('tank_structure': &tank_structure, issue 38; given = 0 without it). It releases the GIL (Python calls it one
  !> at a time, _cancel.app_call), so that Ctrl-C and SIGTERM cancel a long scaling.
  subroutine read_input(path, rpar, ipar, analysis, analysis_values, directory, has_tank, tank, &
                        has_ground, ground, n_samples, seismic, integration, steady, response, &
                        lyapunov, simulation, sweep, response_range, chart, chart_range, study, &
                        study_store, study_figure, study_scheduler, study_records, planar, &
                        spatial, has_ground_y, ground_y, n_samples_y, has_design, design, &
                        tank_structure, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_to_arrays
    use sloshdyn_layouts, only: INTEGRATION_SIZE, STEADY_SIZE, RESPONSE_SIZE, LYAPUNOV_SIZE, &
                                TANK_SIZE, GROUND_SIZE, CHART_SIZE, CHART_RANGE_SIZE, STUDY_SIZE, &
                                SWEEP_SIZE, SIMULATION_SIZE, RESPONSE_RANGE_SIZE, SEISMIC_SIZE, &
                                ANALYSIS_SIZE, from_ode_options, from_steady, from_response, &
                                from_lyapunov, from_tank, from_ground, from_chart, &
                                from_chart_range, from_analysis, from_simulation, from_sweep, &
                                from_response_range, from_seismic, from_study, SPATIAL_SIZE, &
                                DESIGN_SIZE, from_design, TANK_STRUCTURE_SIZE, &
                                from_tank_structure
    use sloshdyn_namelist, only: run_config, core => read_input
    character(len=*), intent(in) :: path
    real(c_double), intent(out) :: rpar(n_real_params), analysis_values(ANALYSIS_SIZE), &
                                   tank(TANK_SIZE), ground(GROUND_SIZE), &
                                   seismic(SEISMIC_SIZE), integration(INTEGRATION_SIZE), &
                                   steady(STEADY_SIZE), response(RESPONSE_SIZE), &
                                   lyapunov(LYAPUNOV_SIZE), simulation(SIMULATION_SIZE), &
                                   sweep(SWEEP_SIZE), response_range(RESPONSE_RANGE_SIZE), &
                                   chart(CHART_SIZE), chart_range(CHART_RANGE_SIZE), &
                                   study(STUDY_SIZE), spatial(SPATIAL_SIZE), &
                                   ground_y(GROUND_SIZE), design(DESIGN_SIZE), &
                                   tank_structure(TANK_STRUCTURE_SIZE)
    integer(c_int), intent(out) :: ipar(n_int_params), analysis, has_tank, has_ground, &
                                   n_samples, planar, has_ground_y, n_samples_y, has_design, &
                                   status
    character(len=4096), intent(out) :: directory, study_store, study_figure, study_scheduler, &
                                        study_records
    character(len=512), intent(out) :: message
    type(run_config) :: config
    integer :: info, ints(n_int_params)
    rpar = 0; ipar = 0; analysis = 0; analysis_values = 0; tank = 0; integration = 0
    steady = 0; response = 0; lyapunov = 0; simulation = 0; sweep = 0; response_range = 0
    has_tank = 0; has_ground = 0; ground = 0; n_samples = 0; seismic = 0; chart = 0
    chart_range = 0
    directory = ''; study = 0; study_store = ''; study_figure = ''; study_scheduler = ''
    study_records = ''; planar = 1; spatial = 0; has_ground_y = 0; ground_y = 0; n_samples_y = 0
    has_design = 0; design = 0; tank_structure = 0
    call core(path, config, info, message)
    status = info
    if (info /= 0) return
    call model_to_arrays(config%model, rpar, ints)
    ipar = ints
    analysis = config%analysis
    analysis_values = from_analysis(config)
    directory = config%directory
    has_tank = merge(1, 0, config%dimensional)
    if (config%dimensional) tank = from_tank(config%tank)
    has_ground = merge(1, 0, config%has_ground)
    if (config%has_ground) then
      ground = from_ground(config%ground)
      if (allocated(config%ground%acceleration)) n_samples = size(config%ground%acceleration)
    end if
    seismic = from_seismic(config%seismic)
    chart = from_chart(config%chart)
    chart_range = from_chart_range(config%chart)
    integration = from_ode_options(config%integration, config%method)
    steady = from_steady(config%steady)
    response = from_response(config%response%options)
    lyapunov = from_lyapunov(config%lyapunov)
    simulation = from_simulation(config%simulation)
    sweep = from_sweep(config%sweep)
    response_range = from_response_range(config%response)
    study = from_study(config%study)
    study_store = config%study%store
    study_records = config%study%records
    study_figure = config%study%figure
    study_scheduler = config%study%scheduler
    planar = merge(1, 0, config%planar)
    spatial = [config%azimuth, config%ellipticity]
    has_ground_y = merge(1, 0, config%has_ground_y)
    if (config%has_ground_y) then
      ground_y = from_ground(config%ground_y)
      n_samples_y = size(config%ground_y%acceleration)
    end if
    has_design = merge(1, 0, config%has_design)
    design = from_design(config%design_spectrum, config%design_factors, &
                         config%design_from_ground)
    tank_structure = from_tank_structure(config%structure)
  end subroutine read_input

  !> The samples of the ground-motion record of a namelist file (as read_input reads it, scaled):
  !> component 1 (record) or 2 (record_y).
  subroutine input_record(path, component, n, samples, status, message)
    !f2py threadsafe
    use sloshdyn_status, only: SD_BAD_INPUT
    use sloshdyn_namelist, only: run_config, core => read_input
    use sloshdyn_ground, only: ground_motion_t, GROUND_RECORD
    character(len=*), intent(in) :: path
    integer(c_int), intent(in) :: component, n
    real(c_double), intent(out) :: samples(n)
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
    type(run_config) :: config
    type(ground_motion_t) :: ground
    integer :: info
    samples = 0
    call core(path, config, info, message)
    ground = config%ground
    if (component == 2) ground = config%ground_y
    if (info == 0 .and. config%has_ground .and. ground%kind == GROUND_RECORD) then
      if (size(ground%acceleration) /= n) then
        info = SD_BAD_INPUT
        message = path//' changed while it was read: its record has a different length now'
      else
        samples = ground%acceleration
      end if
    end if
    status = info
  end subroutine input_record

  !> Read a namelist input file and run it exactly as the executable does (summary on standard
  !> output, CSV files), its files written into `staging`, a new directory that the caller made
  !> and swaps into place (sloshdyn._files.run_directory; blank: as the executable, by the
  !> core's run-directory rule); `directory`, unless blank, is the output directory named in
  !> the summary and messages instead of the file's (the calc sheet's, sloshdyn.design_report);
  !> status 1 for bad input. It releases the GIL so that a cancellation request reaches it, but
  !> its app layer has static string lengths: never two calls at once (sloshdyn.cli holds a
  !> lock around it).
  subroutine run_input(path, directory, staging, status, message)
    !f2py threadsafe
    use sloshdyn_namelist, only: run_config, read_input_file => read_input, path_len
    use sloshdyn_driver, only: run_analysis
    use sloshdyn_status, only: SD_BAD_INPUT
    use sloshdyn_text, only: num2str
    character(len=*), intent(in) :: path, directory, staging
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
    type(run_config) :: config
    integer :: info
    call read_input_file(path, config, info, message)
    if (info == 0 .and. len_trim(directory) > path_len) then
      info = SD_BAD_INPUT
      message = 'the output directory is too long: it must have at most '//num2str(path_len)// &
                ' characters'
    else if (info == 0 .and. len_trim(directory) > 0) then
      config%directory = directory
    end if
    if (info == 0) call run_analysis(config, info, message, staging)
    status = info
  end subroutine run_input

  !> Ask every computation running in this process to stop: they return status 10 (cancelled)
  !> within one integrator or continuation step. Called from Python's main thread on Ctrl-C.
  subroutine request_cancel()
    !f2py threadsafe
    use sloshdyn_cancel, only: core => request_cancel
    call core(-1_c_int)
  end subroutine request_cancel

  !> Forget a cancellation request, once every cancelled call has returned.
  subroutine clear_cancel()
    !f2py threadsafe
    use sloshdyn_cancel, only: core => clear_cancel
    call core()
  end subroutine clear_cancel

  !> The exit code of both front doors for a status, from reading the input (reading = 1) or
  !> from the run (reading = 0).
  subroutine exit_code(status, reading, code)
    !f2py threadsafe
    use sloshdyn_status, only: core => exit_code
    integer(c_int), intent(in) :: status, reading
    integer(c_int), intent(out) :: code
    code = core(int(status), reading /= 0)
  end subroutine exit_code

  !> Every namelist group with its variables and defaults, as written by a namelist write.
  subroutine namelist_defaults(text)
    use sloshdyn_namelist, only: core => namelist_defaults
    character(len=32768), intent(out) :: text
    character(len=:), allocatable :: written
    call core(written)
    text = written
  end subroutine namelist_defaults
end module sloshdyn_bridge_input
