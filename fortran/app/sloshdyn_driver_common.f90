!> What the run driver (sloshdyn_driver) and its submodules share: the beginning of the result
!> files (the output directory, the parameters and, for a tank, its properties, the design-code
!> cross-check and, with &design, the design check), the context of a failed step, the name of the
!> method that runs, and the summaries' number texts. A module of its own, so that the driver
!> exports none of them (gfortran does not export a module's private procedures to its
!> submodules' object files).
module sloshdyn_driver_common
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, status_name
  use sloshdyn_text, only: num2str
  use sloshdyn_tables, only: table_size, code_name, CODES_COLUMNS, CODES_ROWS, CODES_SOURCES, &
                             TANK_SI_SIZE, TANK_MODES_ROWS, PEAKS_SIZE, DESIGN_ROWS, &
                             DESIGN_LOADS_COLUMNS, FREEBOARD_COLUMNS, DESIGN_API650, DESIGN_EC8, &
                             DESIGN_ACI350, LOADS_BASE_SHEAR, LOADS_MOMENT_EBP, LOADS_MOMENT_IBP, &
                             FREEBOARD_WAVE_HEIGHT, FREEBOARD_REQUIRED, FREEBOARD_AVAILABLE, &
                             FREEBOARD_SUFFICIENT, DESIGN_LINEAR, LOADS_IMPULSIVE_ACCELERATION, &
                             LOADS_CONVECTIVE_ACCELERATION, WALL_PRESSURE_ROWS, BASE_PRESSURE_ROWS, &
                             PRESSURE_RESULTANT_ROWS, WALL_HEIGHT, WALL_TOTAL_PRESSURE, &
                             WALL_HOOP_FORCE, PRESSURE_INSTANT_ROWS, PRESSURE_INSTANT_TIME, &
                             PEAK_INSTANT_ROWS, PEAK_INSTANTS
  use sloshdyn_design_check, only: design_check, wall_pressure_row
  use sloshdyn_design_report, only: design_report_t, report_lines, VERDICT_NOT_OK, &
                                    VERDICT_INFO, verdict_names
  use sloshdyn_design_spectra, only: spectrum_sa
  use sloshdyn_wall_pressure, only: pressure_tables, combination_names, COMBINE_SRSS, COMBINE_SUM
  use sloshdyn_seismic_pressure, only: instant_pressures
  use sloshdyn_vessel, only: tank_t
  use sloshdyn_integrator, only: method_name, chosen_method, METHOD_AUTO
  use sloshdyn_seismic, only: design_code_checks, tank_summary, tank_modes
  use sloshdyn_tank, only: max_modes, SHAPE_CIRCULAR
  use sloshdyn_namelist, only: run_config
  use sloshdyn_results, only: result_files
  implicit none
  private
  public :: begin_files, in_context, used_method, value_text, difference, pad, &
            write_peak_pressures

  !> The pressure files' grids: heights on the wall and radii on the base, evenly spaced
  integer, parameter :: pressure_heights = 21, pressure_radii = 11

contains

  !> A failed step: keep the status, put the context (and the kind of failure) in the message.
  pure subroutine in_context(context, status, message)
    character(len=*), intent(in) :: context
    integer, intent(in) :: status
    character(len=message_len), intent(inout) :: message
    if (status == SD_OK) return
    if (status == SD_BAD_INPUT) then
      message = context//': '//trim(message)
    else
      message = context//': '//status_name(status)//': '//trim(message)
    end if
  end subroutine in_context

  !> Create the output directory (only once the analysis succeeded) and write the parameters
  !> (and, for a tank, its properties and the design-code cross-check; with &design the design
  !> check, with the nonlinear run's peaks when given).
  subroutine begin_files(config, files, status, message, peaks)
    type(run_config), intent(in) :: config
    type(result_files), intent(inout) :: files
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), intent(in), optional :: peaks(PEAKS_SIZE)
    real(wp) :: row(TANK_SI_SIZE), codes(CODES_COLUMNS, CODES_ROWS), &
                modes(TANK_MODES_ROWS, max_modes)
    integer :: i, n_codes
    call files%create(config%directory, status, message)
    if (status /= SD_OK) return
    associate (m => config%model)
      call files%write_table('parameters.csv', 'parameters', reshape([m%s1, m%mu1, m%kappa, &
                             m%theta0, m%beta, m%gamma, m%delta, m%zeta, real(m%n, wp), &
                             real(m%p, wp), m%excitation%A, m%excitation%rho, m%a_coef, &
                             m%b_coef], [table_size('parameters'), 1]), status, message)
    end associate
    if (status /= SD_OK .or. .not. config%dimensional) return
    call tank_summary(config%tank, config%tank_props, config%model, row)
    call files%write_table('tank.csv', 'tank_si', reshape(row, [TANK_SI_SIZE, 1]), status, &
                           message)
    if (status == SD_OK .and. config%tank_props%modes > 1) then
      call tank_modes(config%tank_props, modes(:, 1:config%tank_props%modes))
      call files%write_table('tank_modes.csv', 'tank_modes', &
                             modes(:, 1:config%tank_props%modes), status, message)
    end if
    if (status == SD_OK) call design_code_checks(config%tank, config%ground, config%has_ground, &
                                                 codes, status, message)
    ! the modal sums only with modes > 1
    n_codes = merge(CODES_ROWS, CODES_SOURCES, config%tank_props%modes > 1)
    if (status == SD_OK) call files%write_table('design_codes.csv', 'design_codes', &
                                                reshape([(real(i, wp), codes(:, i), &
                                                i = 1, n_codes)], &
                                                [CODES_COLUMNS + 1, n_codes]), status, message)
    if (status == SD_OK .and. config%has_design) call write_design_check(config, files, status, &
                                                                         message, peaks)
  end subroutine begin_files

  !> The design check (&design; sloshdyn_design_check): each code's loads and freeboard check
  !> printed and written to design_loads.csv and freeboard_check.csv (the rows its source
  !> gives), with the nonlinear run's peaks when given.
  subroutine write_design_check(config, files, status, message, peaks)
    type(run_config), intent(in) :: config
    type(result_files), intent(inout) :: files
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), intent(in), optional :: peaks(PEAKS_SIZE)
    real(wp) :: loads(DESIGN_LOADS_COLUMNS, DESIGN_ROWS), freeboard(FREEBOARD_COLUMNS, DESIGN_ROWS)
    logical :: load_rows(DESIGN_ROWS), freeboard_rows(DESIGN_ROWS)
    type(design_report_t) :: report
    integer :: i

    call design_check(config%tank, config%design_spectrum, config%design_factors, &
                      config%design_from_ground, config%ground, config%structure, loads, &
                      freeboard, report, status, message, peaks)
    call in_context('design check', status, message)
    if (status /= SD_OK) return
    load_rows = loads(LOADS_BASE_SHEAR, :) == loads(LOADS_BASE_SHEAR, :)
    freeboard_rows = freeboard(FREEBOARD_WAVE_HEIGHT, :) == freeboard(FREEBOARD_WAVE_HEIGHT, :)
    print '(/a)', 'Design check (&design; docs/design.md): base shear V [MN], overturning moment '// &
                  'excluding / including the base pressure [MN m]; freeboard [m]'
    do i = 1, DESIGN_ROWS
      if (.not. load_rows(i)) cycle
      print '(a)', '  '//pad(trim(code_name('o', i)), 20)//'V '// &
                   pad(num2str(loads(LOADS_BASE_SHEAR, i)/1.0e6_wp, significant=5), 10)//'M '// &
                   pad(num2str(loads(LOADS_MOMENT_EBP, i)/1.0e6_wp, significant=5), 10)//'M'' '// &
                   value_text(loads(LOADS_MOMENT_IBP, i)/1.0e6_wp, significant=5)
    end do
    do i = 1, DESIGN_ROWS
      if (.not. freeboard_rows(i)) cycle
      print '(a)', '  '//pad(trim(code_name('o', i)), 20)//'wave '// &
                   pad(num2str(freeboard(FREEBOARD_WAVE_HEIGHT, i), significant=5), 10)//'required '// &
                   pad(num2str(freeboard(FREEBOARD_REQUIRED, i), significant=5), 10)//'available '// &
                   pad(num2str(freeboard(FREEBOARD_AVAILABLE, i), significant=5), 8)// &
                   trim(merge('sufficient  ', 'insufficient', freeboard(FREEBOARD_SUFFICIENT, i) > 0))
    end do
    ! what the provisions then require (docs/design.md, "Freeboard")
    if (freeboard(FREEBOARD_SUFFICIENT, DESIGN_API650) == 0) &
      print '(a)', '  API 650 Table E-7 (notes b, c): with less freeboard than required, '// &
                   'secondary containment, or a roof and shell designed for the sloshing liquid'
    if (any(freeboard(FREEBOARD_SUFFICIENT, [DESIGN_EC8, DESIGN_ACI350]) == 0)) &
      print '(a)', '  ACI 350.3 / EN 1998-4 freeboard check NOT OK (the code''s wave height '// &
                   'exceeds the freeboard): design the roof for the sloshing wave''s pressure '// &
                   '(roof loads: docs/model.md)'
    call print_checks(report)
    call files%write_table('design_loads.csv', 'design_loads', &
                           with_sources(loads, load_rows), status, message)
    if (status == SD_OK) call files%write_text('design_checks.csv', &
                                               report_lines(report, 'design_checks'), status, &
                                               message)
    if (status == SD_OK) call files%write_text('design_calc.csv', &
                                               report_lines(report, 'design_calc'), status, &
                                               message)
    if (status == SD_OK) call files%write_table('freeboard_check.csv', 'freeboard_check', &
                                                with_sources(freeboard, freeboard_rows), status, &
                                                message)
    if (status == SD_OK .and. .not. config%design_from_ground) &
      call write_design_spectrum(config, files, status, message)
    if (status == SD_OK) call write_wall_pressure(config, files, loads, status, message)
  end subroutine write_design_check

  !> The checks that are not INFO, each with its verdict, ratio and clause; the NOT OK ones
  !> counted (design_checks.csv holds them all).
  subroutine print_checks(report)
    type(design_report_t), intent(in) :: report
    integer :: i, n_bad
    n_bad = 0
    print '(a)', '  checks (design_checks.csv, the hand calculation in design_calc.csv): '// &
                 'demand / capacity'
    do i = 1, report%n_checks
      associate (r => report%checks(i))
        if (r%verdict == VERDICT_NOT_OK) n_bad = n_bad + 1
        if (r%verdict == VERDICT_INFO .or. r%capacity <= 0) cycle
        print '(a)', '  '//pad(trim(r%code), 20)//pad(trim(verdict_names(r%verdict)), 8)// &
                     pad(num2str(r%demand/r%capacity, significant=3), 8)//trim(r%check)// &
                     ' ('//trim(r%clause)//')'
      end associate
    end do
    print '(a)', '  '//num2str(n_bad)//' check(s) NOT OK'
  end subroutine print_checks

  !> design_spectrum.csv: the check's elastic design spectrum at 5 % and 0.5 % damping [g]
  !> over 100 log-spaced periods from 0.02 s to 10 s (EN 1998-1: beyond 4 s its Annex A).
  subroutine write_design_spectrum(config, files, status, message)
    type(run_config), intent(in) :: config
    type(result_files), intent(inout) :: files
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    integer, parameter :: n_periods = 100
    real(wp), parameter :: t_min = 0.02_wp
    real(wp) :: table(3, n_periods), t_max
    integer :: i, j
    t_max = 10
    do i = 1, n_periods
      table(1, i) = t_min*(t_max/t_min)**(real(i - 1, wp)/(n_periods - 1))
      do j = 2, 3
        call spectrum_sa(config%design_spectrum, table(1, i), merge(0.05_wp, 0.005_wp, j == 2), &
                         table(j, i), status, message)
        if (status /= SD_OK) then
          call in_context('design spectrum', status, message)
          return
        end if
      end do
    end do
    call files%write_table('design_spectrum.csv', 'design_spectrum', table, status, message)
  end subroutine write_design_spectrum

  !> The hydrodynamic pressure of the design check (sloshdyn_wall_pressure; docs/model.md,
  !> "Hydrodynamic wall and base pressure") on the wall (21 heights) and base (11 radii) at
  !> theta = 0, and its resultants: from EN 1998-4's design accelerations (its pressure formulas,
  !> Annex A.2.1) combined by their absolute sum as its loads are, or, without an EC8-4 row,
  !> from sloshdyn's linear row (the elastic spectrum at the model's periods) combined by SRSS.
  !> A rectangular tank has no wall pressure (its closed forms are not coded).
  subroutine write_wall_pressure(config, files, loads, status, message)
    type(run_config), intent(in) :: config
    type(result_files), intent(inout) :: files
    real(wp), intent(in) :: loads(DESIGN_LOADS_COLUMNS, DESIGN_ROWS)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: heights(pressure_heights), radii(pressure_radii), &
                wall(WALL_PRESSURE_ROWS, pressure_heights), &
                base(BASE_PRESSURE_ROWS, pressure_radii), resultants(PRESSURE_RESULTANT_ROWS, 2)
    integer :: row, combination, top
    status = SD_OK
    message = ''
    if (config%tank%shape /= SHAPE_CIRCULAR) return
    row = wall_pressure_row(loads, config%design_factors)
    combination = merge(COMBINE_SUM, COMBINE_SRSS, row == DESIGN_EC8)
    call pressure_grid(config%tank, heights, radii)
    associate (tank => config%tank, a => loads(:, row)*config%tank%gravity)
      call pressure_tables(tank, a(LOADS_IMPULSIVE_ACCELERATION), &
                           [a(LOADS_CONVECTIVE_ACCELERATION)], 0.0_wp, combination, heights, &
                           radii, wall, base, resultants, status, message)
    end associate
    call in_context('wall pressure', status, message)
    if (status /= SD_OK) return
    top = maxloc(wall(WALL_TOTAL_PRESSURE, :), 1)
    print '(a)', '  wall pressure ('//trim(code_name('o', row))//'''s '// &
                 trim(merge('ELASTIC accelerations', 'design accelerations ', row == DESIGN_LINEAR))// &
                 ' a_i = '//num2str(loads(LOADS_IMPULSIVE_ACCELERATION, row), significant=5)// &
                 ' g, a_c = '//num2str(loads(LOADS_CONVECTIVE_ACCELERATION, row), significant=5)// &
                 ' g, '//trim(combination_names(combination))//'): largest '// &
                 num2str(wall(WALL_TOTAL_PRESSURE, top)/1.0e3_wp, significant=5)//' kPa at z = '// &
                 num2str(wall(WALL_HEIGHT, top), significant=5)//' m, hoop force '// &
                 num2str(wall(WALL_HOOP_FORCE, top)/1.0e3_wp, significant=5)//' kN/m (wall_pressure.csv)'
    call files%write_table('wall_pressure.csv', 'wall_pressure', wall, status, message)
    if (status == SD_OK) call files%write_table('base_pressure.csv', 'base_pressure', base, &
                                                status, message)
    if (status == SD_OK) call files%write_table('pressure_resultants.csv', &
                                                'pressure_resultants', resultants, status, message)
  end subroutine write_wall_pressure

  !> The hydrodynamic pressure at the base shear and overturning moments' peaks of the seismic
  !> run (sloshdyn_seismic_pressure, theta = 0, from the accelerations the run kept at its peaks,
  !> `instants`): pressure_at_peaks.csv ('pressure_instants', a column per peak) and the wall and
  !> base profiles at each. A rectangular tank has none, as in write_wall_pressure.
  subroutine write_peak_pressures(config, files, instants, status, message)
    type(run_config), intent(in) :: config
    type(result_files), intent(inout) :: files
    real(wp), intent(in) :: instants(PEAK_INSTANT_ROWS, PEAK_INSTANTS)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    character(len=*), parameter :: names(PEAK_INSTANTS) = [character(len=10) :: 'shear', &
      'moment', 'moment_ibp'], loads(PEAK_INSTANTS) = [character(len=42) :: 'base shear', &
      'overturning moment', 'overturning moment including base pressure']
    real(wp) :: heights(pressure_heights), radii(pressure_radii), &
                at_peaks(PRESSURE_INSTANT_ROWS, PEAK_INSTANTS), &
                wall(WALL_PRESSURE_ROWS, pressure_heights, PEAK_INSTANTS), &
                base(BASE_PRESSURE_ROWS, pressure_radii, PEAK_INSTANTS)
    integer :: k, top
    status = SD_OK
    message = ''
    if (config%tank%shape /= SHAPE_CIRCULAR) return
    call pressure_grid(config%tank, heights, radii)
    call instant_pressures(config%tank, instants, heights, radii, 0.0_wp, at_peaks, wall, base, &
                           status, message)
    call in_context('pressure at the peaks', status, message)
    if (status /= SD_OK) return
    do k = 1, PEAK_INSTANTS
      top = maxloc(abs(wall(WALL_TOTAL_PRESSURE, :, k)), 1)
      print '(a)', '  wall pressure at the '//trim(loads(k))//' peak (t = '// &
                   num2str(at_peaks(PRESSURE_INSTANT_TIME, k), significant=5)//' s): largest '// &
                   num2str(wall(WALL_TOTAL_PRESSURE, top, k)/1.0e3_wp, significant=5)// &
                   ' kPa at z = '//num2str(wall(WALL_HEIGHT, top, k), significant=5)// &
                   ' m (wall_pressure_at_'//trim(names(k))//'_peak.csv)'
    end do
    call files%write_table('pressure_at_peaks.csv', 'pressure_instants', at_peaks, status, &
                           message)
    do k = 1, PEAK_INSTANTS
      if (status == SD_OK) call files%write_table('wall_pressure_at_'//trim(names(k))// &
                                                  '_peak.csv', 'wall_pressure', wall(:, :, k), &
                                                  status, message)
      if (status == SD_OK) call files%write_table('base_pressure_at_'//trim(names(k))// &
                                                  '_peak.csv', 'base_pressure', base(:, :, k), &
                                                  status, message)
    end do
  end subroutine write_peak_pressures

  !> The heights [m] on the wall (0 to the liquid depth) and radii [m] on the base (0 to the
  !> radius) of the pressure files.
  pure subroutine pressure_grid(tank, heights, radii)
    type(tank_t), intent(in) :: tank
    real(wp), intent(out) :: heights(pressure_heights), radii(pressure_radii)
    integer :: i
    heights = [(tank%liquid_depth*(i - 1)/(pressure_heights - 1), i = 1, pressure_heights)]
    radii = [(tank%radius*(i - 1)/(pressure_radii - 1), i = 1, pressure_radii)]
  end subroutine pressure_grid

  !> The rows of a design-check table that are present, each with its source code first.
  pure function with_sources(table, present_rows) result(rows)
    real(wp), intent(in) :: table(:, :)
    logical, intent(in) :: present_rows(:)
    real(wp), allocatable :: rows(:, :)
    integer :: i
    rows = reshape([(real(i, wp), table(:, i), i = 1, size(present_rows))], &
                   [size(table, 1) + 1, size(present_rows)])
    rows = rows(:, pack([(i, i = 1, size(present_rows))], present_rows))
  end function with_sources

  !> x with `significant` digits (default 6), or '-' for NaN (a value a code does not give).
  pure function value_text(x, significant) result(text)
    real(wp), intent(in) :: x
    integer, intent(in), optional :: significant
    character(len=:), allocatable :: text
    integer :: digits
    digits = 6
    if (present(significant)) digits = significant
    if (x /= x) then
      text = '-'
    else
      text = num2str(x, significant=digits)
    end if
  end function value_text

  pure function difference(x, reference) result(text)
    real(wp), intent(in) :: x, reference
    character(len=:), allocatable :: text
    text = ''
    if (x == x .and. reference == reference .and. reference /= 0) &
      text = ' ('//trim(percent(100*(x - reference)/reference))//')'
  end function difference

  pure function percent(x) result(text)
    real(wp), intent(in) :: x
    character(len=:), allocatable :: text
    character(len=16) :: buffer
    write (buffer, '(sp, f16.1)') x
    text = trim(adjustl(buffer))//'%'
  end function percent

  pure function pad(text, width) result(padded)
    character(len=*), intent(in) :: text
    integer, intent(in) :: width
    character(len=max(width, len(text) + 1)) :: padded
    padded = text
  end function pad

  !> The name of the integration method that runs, as the summaries print it: the method, or
  !> for 'auto' the one chosen for rtol, e.g. 'dop853 by auto'.
  function used_method(config) result(name)
    type(run_config), intent(in) :: config
    character(len=:), allocatable :: name
    name = method_name(chosen_method(config%method, config%integration%rtol))
    if (config%method == METHOD_AUTO) name = name//' by auto'
  end function used_method
end module sloshdyn_driver_common
