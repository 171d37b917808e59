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
  !> simulation, sweep, response_range, chart and study; study_store, study_figure,
  !> study_scheduler, study_records the &study strings. It releases the GIL (Python calls it one
  !> at a time, _cancel.app_call), so that Ctrl-C and SIGTERM cancel a long scaling.
  subroutine read_input(path, rpar, ipar, analysis, analysis_values, directory, has_tank, tank, &
                        has_ground, ground, n_samples, seismic, integration, steady, response, &
                        lyapunov, simulation, sweep, response_range, chart, study, study_store, &
                        study_figure, study_scheduler, study_records, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_to_arrays
    use sloshdyn_layouts, only: INTEGRATION_SIZE, STEADY_SIZE, RESPONSE_SIZE, LYAPUNOV_SIZE, &
                                TANK_SIZE, GROUND_SIZE, CHART_SETTINGS_SIZE, STUDY_SIZE, &
                                SWEEP_SIZE, SIMULATION_SIZE, RESPONSE_RANGE_SIZE, SEISMIC_SIZE, &
                                ANALYSIS_SIZE, from_ode_options, from_steady, from_response, &
                                from_lyapunov, from_tank, from_ground, from_chart
    use sloshdyn_namelist, only: run_config, core => read_input
    character(len=*), intent(in) :: path
    real(c_double), intent(out) :: rpar(n_real_params), analysis_values(ANALYSIS_SIZE), &
                                   tank(TANK_SIZE), ground(GROUND_SIZE), &
                                   seismic(SEISMIC_SIZE), integration(INTEGRATION_SIZE), &
                                     steady(STEADY_SIZE), response(RESPONSE_SIZE), &
                                   lyapunov(LYAPUNOV_SIZE), simulation(SIMULATION_SIZE), &
                                     sweep(SWEEP_SIZE), response_range(RESPONSE_RANGE_SIZE), &
                                   chart(CHART_SETTINGS_SIZE), study(STUDY_SIZE)
    integer(c_int), intent(out) :: ipar(n_int_params), analysis, has_tank, has_ground, &
                                   n_samples, status
    character(len=4096), intent(out) :: directory, study_store, study_figure, study_scheduler, &
                                        study_records
    character(len=256), intent(out) :: message
    type(run_config) :: config
    integer :: info, ints(n_int_params)
    rpar = 0; ipar = 0; analysis = 0; analysis_values = 0; tank = 0; integration = 0
    steady = 0; response = 0; lyapunov = 0; simulation = 0; sweep = 0; response_range = 0
    has_tank = 0; has_ground = 0; ground = 0; n_samples = 0; seismic = 0; chart = 0
    directory = ''; study = 0; study_store = ''; study_figure = ''; study_scheduler = ''
    study_records = ''
    call core(path, config, info, message)
    status = info
    if (info /= 0) return
    call model_to_arrays(config%model, rpar, ints)
    ipar = ints
    analysis = config%analysis
    analysis_values = [config%sigma1, config%kappa_min, config%kappa_max]
    directory = config%directory
    has_tank = merge(1, 0, config%dimensional)
    if (config%dimensional) tank = from_tank(config%tank)
    has_ground = merge(1, 0, config%has_ground)
    if (config%has_ground) then
      ground = from_ground(config%ground)
      if (allocated(config%ground%acceleration)) n_samples = size(config%ground%acceleration)
    end if
    seismic = [config%seismic%t_end, real(config%seismic%n_out, c_double)]
    chart = from_chart(config%chart)
    integration = from_ode_options(config%integration, config%method)
    steady = from_steady(config%steady)
    response = from_response(config%response%options)
    lyapunov = from_lyapunov(config%lyapunov)
    simulation = [config%simulation%t_end, real(config%simulation%n_out, c_double), &
                  config%simulation%y0]
    sweep = [real(config%sweep%parameter, c_double), config%sweep%start, config%sweep%stop, &
             real(config%sweep%n_points, c_double), real(config%sweep%direction, c_double), &
             merge(1.0_c_double, 0.0_c_double, config%sweep%carry_state), &
             real(config%sweep%threads, c_double)]
    response_range = [merge(1.0_c_double, 0.0_c_double, config%response%internal_resonance), &
                      real(config%response%parameter, c_double), config%response%start, &
                      config%response%stop, real(config%response%switch_at, c_double)]
    associate (st => config%study)
      study = [merge(1.0_c_double, 0.0_c_double, st%given), real(st%kind, c_double), &
               real(st%workers, c_double), real(st%worker_kind, c_double), &
               real(st%points_per_task, c_double), st%frequency_start, st%frequency_stop, &
               real(st%n_frequencies, c_double), st%amplitude_start, st%amplitude_stop, &
               real(st%n_amplitudes, c_double), real(st%continuation, c_double), st%x1_start, &
               st%x1_stop, st%dx1_start, st%dx1_stop, real(st%n_grid, c_double), st%tol, &
               st%intensity_start, st%intensity_stop, real(st%n_intensities, c_double), &
               st%spectral_damping]
      study_store = st%store
      study_records = st%records
      study_figure = st%figure
      study_scheduler = st%scheduler
    end associate
  end subroutine read_input

  !> The samples of the ground-motion record of a namelist file (as read_input reads it, scaled).
  subroutine input_record(path, n, samples, status, message)
    !f2py threadsafe
    use sloshdyn_status, only: SD_BAD_INPUT
    use sloshdyn_namelist, only: run_config, core => read_input
    use sloshdyn_ground, only: GROUND_RECORD
    character(len=*), intent(in) :: path
    integer(c_int), intent(in) :: n
    real(c_double), intent(out) :: samples(n)
    integer(c_int), intent(out) :: status
    character(len=256), intent(out) :: message
    type(run_config) :: config
    integer :: info
    samples = 0
    call core(path, config, info, message)
    if (info == 0 .and. config%has_ground .and. config%ground%kind == GROUND_RECORD) then
      if (size(config%ground%acceleration) /= n) then
        info = SD_BAD_INPUT
        message = path//' changed while it was read: its record has a different length now'
      else
        samples = config%ground%acceleration
      end if
    end if
    status = info
  end subroutine input_record

  !> Read a namelist input file and run it exactly as the executable does (summary on standard
  !> output, CSV files in its output directory); status 1 for bad input. It releases the GIL so
  !> that a cancellation request reaches it, but its app layer has static string lengths: never
  !> two calls at once (sloshdyn.cli holds a lock around it).
  subroutine run_input(path, status, message)
    !f2py threadsafe
    use sloshdyn_namelist, only: run_config, read_input_file => read_input
    use sloshdyn_driver, only: run_analysis
    character(len=*), intent(in) :: path
    integer(c_int), intent(out) :: status
    character(len=256), intent(out) :: message
    type(run_config) :: config
    integer :: info
    call read_input_file(path, config, info, message)
    if (info == 0) call run_analysis(config, info, message)
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
