!> The f2py bridge of seismic.py: a tank in SI units under ground motion; tank(TANK_SIZE) and
!> ground(GROUND_SIZE) in the layouts of sloshdyn_layouts, samples(n) the record's accelerations
!> [m/s^2] (n = 0 for harmonic motion).
!> The bridge's contract (c_double/c_int arrays in named layouts, status and message,
!> threads and the GIL) is written once, in sloshdyn_bridge_model.f90.
module sloshdyn_bridge_seismic
  use, intrinsic :: iso_c_binding, only: c_double, c_int
  implicit none

contains

  !> The tank's properties (the 'tank_si' table's row), its sloshing modes (the 'tank_modes'
  !> table, columns 1..the tank's modes; the rest 0) and its dimensionless model.
  subroutine tank_properties(tank, row, modes, rpar, ipar, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_to_arrays
    use sloshdyn_tables, only: TANK_SI_SIZE, TANK_MODES_ROWS
    use sloshdyn_tank, only: MAX_TANK_MODES => max_modes
    use sloshdyn_layouts, only: TANK_SIZE, to_tank
    use sloshdyn_vessel, only: tank_properties_t => tank_properties, tank_model
    use sloshdyn_seismic, only: tank_summary, tank_modes
    real(c_double), intent(in) :: tank(TANK_SIZE)
    real(c_double), intent(out) :: row(TANK_SI_SIZE), modes(TANK_MODES_ROWS, MAX_TANK_MODES), &
                                   rpar(n_real_params)
    integer(c_int), intent(out) :: ipar(n_int_params), status
    character(len=512), intent(out) :: message
    type(model_t) :: model
    type(tank_properties_t) :: props
    integer :: info, ints(n_int_params)
    row = 0; modes = 0; rpar = 0; ipar = 0
    call tank_model(to_tank(tank), model, props, info, message)
    if (info == 0) then
      call tank_summary(to_tank(tank), props, model, row)
      call tank_modes(props, modes(:, 1:props%modes))
      call model_to_arrays(model, rpar, ints)
      ipar = ints
    end if
    status = info
  end subroutine tank_properties

  !> A and rho of a tank's model under harmonic ground motion (sloshdyn_ground's
  !> ground_excitation, as the namelist reader sets them for &tank with &ground_motion).
  subroutine tank_excitation(tank, ground, A, rho, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: model_t
    use sloshdyn_layouts, only: TANK_SIZE, GROUND_SIZE, to_tank, to_ground
    use sloshdyn_vessel, only: tank_properties_t => tank_properties, tank_model
    use sloshdyn_ground, only: ground_motion_t, ground_excitation, GROUND_HARMONIC
    use sloshdyn_excitation, only: excitation_t
    use sloshdyn_status, only: SD_BAD_INPUT
    real(c_double), intent(in) :: tank(TANK_SIZE), ground(GROUND_SIZE)
    real(c_double), intent(out) :: A, rho
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
    type(model_t) :: model
    type(tank_properties_t) :: props
    type(excitation_t) :: excitation
    type(ground_motion_t) :: motion
    real(c_double) :: no_samples(0)
    integer :: info
    A = 0; rho = 0
    motion = to_ground(ground, no_samples)
    call tank_model(to_tank(tank), model, props, info, message)
    if (info == 0 .and. motion%kind /= GROUND_HARMONIC) then
      info = SD_BAD_INPUT
      message = 'a record has no A and rho: they are those of harmonic ground motion'
    end if
    if (info == 0) call ground_excitation(motion, props%omega, props%rod_length, excitation, &
                                          info, message)
    if (info == 0) then
      A = excitation%A
      rho = excitation%rho
    end if
    status = info
  end subroutine tank_excitation

  !> The rules of a ground motion (sloshdyn_ground's check_ground).
  subroutine check_ground(ground, n, samples, status, message)
    !f2py threadsafe
    use sloshdyn_layouts, only: GROUND_SIZE, to_ground
    use sloshdyn_ground, only: core => check_ground
    integer(c_int), intent(in) :: n
    real(c_double), intent(in) :: ground(GROUND_SIZE), samples(n)
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
    integer :: info
    call core(to_ground(ground, samples), info, message)
    status = info
  end subroutine check_ground

  !> The factor that turns an acceleration in the named units (g, m/s^2, cm/s^2) into m/s^2.
  subroutine acceleration_units(name, factor, status, message)
    use sloshdyn_records, only: units_code, units_factor
    character(len=*), intent(in) :: name
    real(c_double), intent(out) :: factor
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
    integer :: code, info
    call units_code(name, code, info, message)
    factor = 0
    if (info == 0) call units_factor(code, factor, info, message)
    status = info
  end subroutine acceleration_units

  !> A record file (sloshdyn_records' load_record): dt [s] and the first n of samples [m/s^2].
  !> n_max must be at least the number of samples (the file's count of numbers is enough).
  subroutine read_record(path, format, units, n_max, dt, samples, n, status, message)
    use sloshdyn_kinds, only: wp
    use sloshdyn_status, only: SD_BAD_INPUT
    use sloshdyn_records, only: load_record
    use sloshdyn_text, only: num2str
    character(len=*), intent(in) :: path, format, units
    integer(c_int), intent(in) :: n_max
    real(c_double), intent(out) :: dt, samples(n_max)
    integer(c_int), intent(out) :: n, status
    character(len=512), intent(out) :: message
    real(wp), allocatable :: accel(:)
    integer :: info
    samples = 0; n = 0
    call load_record(path, format, units, dt, accel, info, message)
    if (info == 0) then
      if (size(accel) > n_max) then
        info = SD_BAD_INPUT
        message = path//' has '//num2str(size(accel))//' samples, more than n_max = '// &
                  num2str(int(n_max))
      else
        n = size(accel)
        samples(1:n) = accel
      end if
    end if
    status = info
  end subroutine read_record

  !> The ground motion scaled (sloshdyn_ground's scale_ground; SI units).
  subroutine scale_ground(ground, n, samples, scale_factor, target_pga, target_sa, &
                          target_period, target_damping, scaled, scaled_samples, status, message)
    !f2py threadsafe
    use sloshdyn_layouts, only: GROUND_SIZE, to_ground, from_ground
    use sloshdyn_ground, only: ground_motion_t, core => scale_ground
    integer(c_int), intent(in) :: n
    real(c_double), intent(in) :: ground(GROUND_SIZE), samples(n), scale_factor, target_pga, &
                                  target_sa, &
                                  target_period, target_damping
    real(c_double), intent(out) :: scaled(GROUND_SIZE), scaled_samples(n)
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
    type(ground_motion_t) :: motion
    integer :: info
    motion = to_ground(ground, samples)
    call core(motion, scale_factor, target_pga, target_sa, target_period, target_damping, info, &
              message)
    scaled = from_ground(motion)
    scaled_samples = samples
    if (info == 0 .and. n > 0) scaled_samples = motion%acceleration
    status = info
  end subroutine scale_ground

  !> Response spectrum of the ground motion (sloshdyn_ground's ground_spectrum).
  subroutine ground_spectrum(ground, n, samples, m, periods, damping, tail_duration, duration, &
                             sd, sv, psa, status, message)
    !f2py threadsafe
    use sloshdyn_layouts, only: GROUND_SIZE, to_ground
    use sloshdyn_ground, only: core => ground_spectrum
    integer(c_int), intent(in) :: n, m
    real(c_double), intent(in) :: ground(GROUND_SIZE), samples(n), periods(m), damping, &
                                  tail_duration, &
                                  duration
    real(c_double), intent(out) :: sd(m), sv(m), psa(m)
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
    integer :: info
    call core(to_ground(ground, samples), periods, damping, tail_duration, duration, sd, sv, &
              psa, info, message)
    status = info
  end subroutine ground_spectrum

  !> t_end [s] and n_out of a seismic response, the defaults (sloshdyn_seismic) where the given
  !> ones are <= 0: chosen = [t_end, n_out]; with has_y, the second component ground_y
  !> (samples_y) counts too (the longer record's end).
  subroutine seismic_defaults(tank, ground, n, samples, has_y, ground_y, n_y, samples_y, t_end, &
                              n_out, chosen, status, message)
    !f2py threadsafe
    use sloshdyn_layouts, only: TANK_SIZE, GROUND_SIZE, SEISMIC_SIZE, to_tank, to_ground
    use sloshdyn_model, only: model_t
    use sloshdyn_vessel, only: tank_properties_t => tank_properties, tank_model
    use sloshdyn_ground, only: check_ground
    use sloshdyn_seismic, only: core => seismic_defaults
    integer(c_int), intent(in) :: n, n_out, has_y, n_y
    real(c_double), intent(in) :: tank(TANK_SIZE), ground(GROUND_SIZE), samples(n), t_end, &
                                  ground_y(GROUND_SIZE), samples_y(n_y)
    real(c_double), intent(out) :: chosen(SEISMIC_SIZE)
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
    type(model_t) :: model
    type(tank_properties_t) :: props
    real(c_double) :: duration
    integer :: info, count
    chosen = 0
    call tank_model(to_tank(tank), model, props, info, message)
    if (info == 0) call check_ground(to_ground(ground, samples), info, message)
    if (info == 0) then
      duration = t_end
      count = n_out
      if (has_y /= 0) then
        call core(props, to_ground(ground, samples), duration, count, &
                  to_ground(ground_y, samples_y))
      else
        call core(props, to_ground(ground, samples), duration, count)
      end if
      chosen = [duration, real(count, c_double)]
    end if
    status = info
  end subroutine seismic_defaults

  !> The tank's response from rest (sloshdyn_seismic): table(SEISMIC_ROWS, n_out) in the
  !> 'seismic_impact' layout, peaks(PEAKS_SIZE) in the 'seismic_peaks_impact' layout (the
  !> impact model's entries NaN without roof_contact = 'impact'; the layouts without them are
  !> their first rows) and the accelerations at the load peaks ('seismic_peak_instants').
  subroutine seismic_response(tank, ground, n, samples, t_end, n_out, integration, table, &
                              peaks, instants, status, message)
    !f2py threadsafe
    use sloshdyn_tables, only: SEISMIC_ROWS, PEAKS_SIZE, PEAK_INSTANT_ROWS, PEAK_INSTANTS
    use sloshdyn_layouts, only: INTEGRATION_SIZE, TANK_SIZE, GROUND_SIZE, to_tank, to_ground, &
                                to_ode_options, to_method
    use sloshdyn_seismic, only: core => seismic_response
    integer(c_int), intent(in) :: n, n_out
    real(c_double), intent(in) :: tank(TANK_SIZE), ground(GROUND_SIZE), samples(n), t_end, &
                                  integration(INTEGRATION_SIZE)
    real(c_double), intent(out) :: table(SEISMIC_ROWS, n_out), peaks(PEAKS_SIZE), &
                                   instants(PEAK_INSTANT_ROWS, PEAK_INSTANTS)
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
    integer :: info
    call core(to_tank(tank), to_ground(ground, samples), t_end, int(n_out), &
              to_ode_options(integration), to_method(integration), table, peaks, instants, info, &
              message)
    status = info
  end subroutine seismic_response

  !> The peaks of seismic_response for k ground motions of one time grid (every record of n
  !> samples; sloshdyn_seismic's seismic_responses, the runs integrated together by the ensemble
  !> integrator; issue 43): member i is grounds(:, i), samples(:, i); peaks(:, i) and status(i)
  !> are seismic_response's for it alone, bit for bit, and messages(i) its message ('' where it
  !> succeeded). No table is returned, so a tank of one mode runs with its start and end as
  !> the only outputs (seismic_responses' ends_only).
  subroutine seismic_peaks(tank, k, grounds, n, samples, t_end, n_out, integration, peaks, &
                           status, messages)
    !f2py threadsafe
    use sloshdyn_tables, only: PEAKS_SIZE, PEAK_INSTANT_ROWS, PEAK_INSTANTS
    use sloshdyn_layouts, only: INTEGRATION_SIZE, TANK_SIZE, GROUND_SIZE, to_tank, to_ground, &
                                to_ode_options, to_method
    use sloshdyn_ground, only: ground_motion_t
    use sloshdyn_seismic, only: seismic_responses
    integer(c_int), intent(in) :: k, n, n_out
    real(c_double), intent(in) :: tank(TANK_SIZE), grounds(GROUND_SIZE, k), samples(n, k), &
                                  t_end, integration(INTEGRATION_SIZE)
    real(c_double), intent(out) :: peaks(PEAKS_SIZE, k)
    integer(c_int), intent(out) :: status(k)
    character(len=512), intent(out) :: messages(k)
    type(ground_motion_t) :: motions(k)
    real(c_double), allocatable :: table(:, :, :)
    real(c_double) :: instants(PEAK_INSTANT_ROWS, PEAK_INSTANTS, k)
    integer :: info(k), i
    do i = 1, k
      motions(i) = to_ground(grounds(:, i), samples(:, i))
    end do
    call seismic_responses(to_tank(tank), motions, t_end, int(n_out), &
                           to_ode_options(integration), to_method(integration), table, peaks, &
                           instants, info, messages, ends_only=.true.)
    status = info
  end subroutine seismic_peaks

  !> Steady states of the tank under harmonic ground motion of the ground's peak acceleration
  !> at each frequency [Hz] (sloshdyn_seismic's harmonic_sweep): summaries(SUMMARY_SIZE, n) in the
  !> 'summary' layout and table(HARMONIC_SWEEP_ROWS,
  !> n) in the 'harmonic_sweep' layout; carry = 1: each point
  !> from the previous one's final state (threads = 1; y_final the last one's), else each from
  !> y0.
  subroutine harmonic_sweep(tank, ground, n, frequencies, y0, integration, steady, carry, &
                            threads, summaries, table, y_final, n_done, status, message)
    !f2py threadsafe
    use sloshdyn_tables, only: SUMMARY_SIZE, HARMONIC_SWEEP_ROWS
    use sloshdyn_layouts, only: INTEGRATION_SIZE, STEADY_SIZE, TANK_SIZE, GROUND_SIZE, to_tank, &
                                to_ode_options, to_method, to_steady, to_ground
    use sloshdyn_seismic, only: core => harmonic_sweep
    integer(c_int), intent(in) :: n, carry, threads
    real(c_double), intent(in) :: tank(TANK_SIZE), ground(GROUND_SIZE), frequencies(n), y0(4), &
                                  integration(INTEGRATION_SIZE), &
                                  steady(STEADY_SIZE)
    real(c_double), intent(out) :: summaries(SUMMARY_SIZE, n), table(HARMONIC_SWEEP_ROWS, n), &
                                   y_final(4)
    integer(c_int), intent(out) :: n_done, status
    character(len=512), intent(out) :: message
    real(c_double) :: no_samples(0)
    integer :: info, done
    call core(to_tank(tank), to_ground(ground, no_samples), frequencies, y0, &
              to_ode_options(integration), to_method(integration), to_steady(steady), carry /= 0, &
              int(threads), summaries, table, y_final, done, info, message)
    n_done = done
    status = info
  end subroutine harmonic_sweep

  !> The tank's sloshing parameters by sloshdyn and by the design codes, codes(CODES_COLUMNS,
  !> CODES_ROWS) in the
  !> 'design_codes' layout; wave heights need the ground motion (has_ground = 1).
  subroutine design_codes(tank, has_ground, ground, n, samples, codes, status, message)
    use sloshdyn_tables, only: CODES_COLUMNS, CODES_ROWS
    use sloshdyn_layouts, only: TANK_SIZE, GROUND_SIZE, to_tank, to_ground
    use sloshdyn_seismic, only: design_code_checks
    integer(c_int), intent(in) :: has_ground, n
    real(c_double), intent(in) :: tank(TANK_SIZE), ground(GROUND_SIZE), samples(n)
    real(c_double), intent(out) :: codes(CODES_COLUMNS, CODES_ROWS)
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
    integer :: info
    call design_code_checks(to_tank(tank), to_ground(ground, samples), has_ground /= 0, codes, &
                            info, message)
    status = info
  end subroutine design_codes

  !> design_codes with the wave heights from a code design spectrum (&design's layout).
  subroutine design_codes_spectrum(tank, design, codes, status, message)
    use sloshdyn_tables, only: CODES_COLUMNS, CODES_ROWS
    use sloshdyn_layouts, only: TANK_SIZE, DESIGN_SIZE, to_tank, to_design
    use sloshdyn_seismic, only: design_code_checks
    use sloshdyn_ground, only: ground_motion_t
    use sloshdyn_design_spectra, only: design_spectrum_t
    use sloshdyn_design_loads, only: design_factors_t
    real(c_double), intent(in) :: tank(TANK_SIZE), design(DESIGN_SIZE)
    real(c_double), intent(out) :: codes(CODES_COLUMNS, CODES_ROWS)
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
    type(design_spectrum_t) :: spec
    type(design_factors_t) :: factors
    type(ground_motion_t) :: no_ground
    logical :: from_ground
    integer :: info
    call to_design(design, spec, factors, from_ground)
    call design_code_checks(to_tank(tank), no_ground, .false., codes, info, message, spec)
    status = info
  end subroutine design_codes_spectrum

  !> The design-code table as the executable prints it (sloshdyn_driver's design_codes_table).
  subroutine design_codes_text(codes, text)
    use sloshdyn_tables, only: CODES_COLUMNS, CODES_ROWS
    use sloshdyn_driver, only: design_codes_table
    real(c_double), intent(in) :: codes(CODES_COLUMNS, CODES_ROWS)
    character(len=2048), intent(out) :: text
    text = design_codes_table(codes)
  end subroutine design_codes_text

  !> A design spectrum's Sa [g] at n periods [s] and one damping ratio (&design's layout
  !> 'design'; sloshdyn_design_spectra's spectrum_sa); the first failure stops.
  subroutine design_spectrum_sa(design, n, periods, damping_ratio, sa, status, message)
    !f2py threadsafe
    use sloshdyn_kinds, only: wp
    use sloshdyn_layouts, only: DESIGN_SIZE, to_design
    use sloshdyn_design_spectra, only: design_spectrum_t, spectrum_sa
    use sloshdyn_design_loads, only: design_factors_t
    integer(c_int), intent(in) :: n
    real(c_double), intent(in) :: design(DESIGN_SIZE), periods(n), damping_ratio
    real(c_double), intent(out) :: sa(n)
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
    type(design_spectrum_t) :: spec
    type(design_factors_t) :: factors
    logical :: from_ground
    real(wp) :: value
    integer :: i, info
    sa = 0
    status = 0
    message = ''
    call to_design(design, spec, factors, from_ground)
    if (from_ground) then
      status = 1
      message = "spectrum = 'ground_motion': the ground motion's spectrum is GroundMotion's"
      return
    end if
    do i = 1, n
      call spectrum_sa(spec, periods(i), damping_ratio, value, info, message)
      status = info
      if (info /= 0) return
      sa(i) = value
    end do
  end subroutine design_spectrum_sa

  !> The design check of a tank (sloshdyn_design_check): loads in the 'design_loads' layout
  !> and freeboard in 'freeboard_check' (without the source column, NaN rows where a source
  !> gives none), from &design's spectrum or the ground motion's (its samples, n of them), with
  !> the structure ('tank_structure': &tank_structure, given = 0 for none); with has_peaks = 1
  !> the 'seismic_peaks' of a nonlinear run give the row 'sloshdyn nonlinear'. checks and calc:
  !> the tables 'design_checks' and 'design_calc' as the executable writes them (CSV text,
  !> lines ending in a newline; sloshdyn_design_report).
  subroutine design_check(tank, design, ground, n, samples, tank_structure, has_peaks, peaks, &
                          loads, freeboard, checks, calc, status, message)
    !f2py threadsafe
    use sloshdyn_layouts, only: TANK_SIZE, GROUND_SIZE, DESIGN_SIZE, TANK_STRUCTURE_SIZE, &
                                to_tank, to_ground, to_design, to_tank_structure
    use sloshdyn_tables, only: PEAKS_SIZE, DESIGN_ROWS, DESIGN_LOADS_COLUMNS, FREEBOARD_COLUMNS
    use sloshdyn_design_spectra, only: design_spectrum_t
    use sloshdyn_design_loads, only: design_factors_t
    use sloshdyn_design_report, only: design_report_t, report_text, REPORT_TEXT_LEN
    use sloshdyn_design_check, only: core => design_check
    integer(c_int), intent(in) :: n, has_peaks
    real(c_double), intent(in) :: tank(TANK_SIZE), design(DESIGN_SIZE), ground(GROUND_SIZE), &
                                  samples(n), tank_structure(TANK_STRUCTURE_SIZE), &
                                  peaks(PEAKS_SIZE)
    real(c_double), intent(out) :: loads(DESIGN_LOADS_COLUMNS, DESIGN_ROWS), &
                                   freeboard(FREEBOARD_COLUMNS, DESIGN_ROWS)
    character(len=524288), intent(out) :: checks, calc
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
    type(design_spectrum_t) :: spec
    type(design_factors_t) :: factors
    type(design_report_t) :: report
    logical :: from_ground, overflow(2)
    integer :: info
    checks = ''
    calc = ''
    call to_design(design, spec, factors, from_ground)
    if (has_peaks /= 0) then
      call core(to_tank(tank), spec, factors, from_ground, to_ground(ground, samples), &
                to_tank_structure(tank_structure), loads, freeboard, report, info, message, peaks)
    else
      call core(to_tank(tank), spec, factors, from_ground, to_ground(ground, samples), &
                to_tank_structure(tank_structure), loads, freeboard, report, info, message)
    end if
    status = info
    if (info /= 0) return
    call report_text(report, 'design_checks', checks, overflow(1))
    call report_text(report, 'design_calc', calc, overflow(2))
    if (any(overflow)) then
      status = 1
      message = 'the design check''s tables are longer than the bridge''s text ('// &
                'REPORT_TEXT_LEN characters)'
    end if
  end subroutine design_check
end module sloshdyn_bridge_seismic
