!> The executable's runs of a tank in SI units (a submodule of sloshdyn_driver, which declares
!> their interfaces): the seismic response in one or two horizontal components, the summary of
!> the tank and the design-code table.
submodule (sloshdyn_driver) sloshdyn_driver_tank
  ! by use, not only from the parent: meson rebuilds a submodule when a module it uses changes,
  ! not when one its parent uses does (a stale object then calls the old interfaces)
  use sloshdyn_driver_common, only: begin_files, in_context, used_method, value_text, &
                                    difference, pad, write_peak_pressures
  use sloshdyn_vessel, only: ROOF_CONTACT_IMPACT, roof_contact_names
  use sloshdyn_seismic, only: seismic_response, seismic_defaults
  use sloshdyn_tables, only: SEISMIC_LOADS, SEISMIC_ROWS, SEISMIC_FREE_ROWS, PEAKS_SIZE, &
                             PEAKS_FREE_SIZE, PEAK_INSTANT_ROWS, PEAK_INSTANTS
  implicit none

contains

  !> A tank under ground motion in two components (sloshdyn_seismic_spatial): SI time
  !> histories, peaks over the wall and the codes' combinations of the two planar runs.
  module subroutine run_seismic_spatial(config, files, status, message)
    type(run_config), intent(in) :: config
    type(result_files), intent(inout) :: files
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), allocatable :: table(:, :)
    real(wp) :: peaks(SEISMIC_SPATIAL_PEAKS), t_end
    integer :: n_out

    t_end = config%seismic%t_end
    n_out = config%seismic%n_out
    if (config%has_ground_y) then
      call seismic_defaults(config%tank_props, config%ground, t_end, n_out, config%ground_y)
    else
      call seismic_defaults(config%tank_props, config%ground, t_end, n_out)
    end if
    allocate (table(SEISMIC_SPATIAL_ROWS, n_out))
    call seismic_response_spatial(config%tank, config%ground, config%ground_y, config%azimuth, &
                                  config%ellipticity, t_end, n_out, config%integration, &
                                  config%method, table, peaks, status, message)
    call in_context('seismic response in two components', status, message)
    if (status /= SD_OK) return
    print '(/a)', 'Seismic response in two components (spatial model; '//used_method(config)// &
                  ') from rest, t = 0 to '//num2str(t_end)//' s, '//num2str(n_out)// &
                  ' outputs; peaks:'
    print '(a)', '  '//pad('wave height', 24)//pad(num2str(peaks(1), significant=5)//' m', 18)// &
                 'at t = '//num2str(peaks(3), significant=5)//' s, azimuth '// &
                 num2str(peaks(2), significant=5)//' rad'
    print '(a)', '  '//pad('base shear', 24)// &
                 pad(num2str(peaks(4)/1.0e6_wp, significant=5)//' MN', 18)//'at t = '// &
                 num2str(peaks(5), significant=5)//' s'
    print '(a)', '  '//pad('overturning moment', 24)// &
                 pad(num2str(peaks(6)/1.0e6_wp, significant=5)//' MN m', 18)//'at t = '// &
                 num2str(peaks(7), significant=5)//' s'
    print '(a)', '  codes'' combinations of the two planar runs '// &
      '(SRSS, 100/30): wave height '//num2str(peaks(10), significant=5)//', '// &
      num2str(peaks(11), significant=5)//' m; base shear '// &
      num2str(peaks(14)/1.0e6_wp, significant=5)//', '// &
      num2str(peaks(15)/1.0e6_wp, significant=5)//' MN'
    ! the roof, judged on the free wave around the whole wall (sloshdyn_seismic_spatial)
    if (peaks(20) > 0) then
      print '(a)', '  the free wave reaches the roof: first at t = '// &
                   num2str(peaks(21), significant=5)//' s at azimuth '// &
                   num2str(peaks(22), significant=5)//' rad, '//num2str(nint(peaks(23)))// &
                   ' time(s); it rises to '//num2str(peaks(24), significant=5)//' m at the wall'
      print '(a)', '  '//roof_name(config%tank)//', restricted sloshing: head '// &
                   num2str(peaks(26), significant=5)//' m, uplift '// &
                   num2str(peaks(27)/1.0e6_wp, significant=5)//' MN, confined convective mass '// &
                   num2str(peaks(28), significant=5)//' kg, moving with the tank from the '// &
                   'first contact on'
    else
      print '(a)', '  the free wave does not reach the roof: its peak around the wall is '// &
                   num2str(100*peaks(24)/config%tank%freeboard, significant=3)// &
                   ' % of the freeboard ('//num2str(config%tank%freeboard)//' m)'
    end if
    call begin_files(config, files, status, message)
    if (status == SD_OK) call files%write_table('seismic_spatial.csv', 'seismic_spatial', table, &
                                                status, message)
    if (status == SD_OK) call files%write_table('seismic_spatial_peaks.csv', &
                                                'seismic_spatial_peaks', &
                                                reshape(peaks, [SEISMIC_SPATIAL_PEAKS, 1]), &
                                                status, message)
  end subroutine run_seismic_spatial

  !> A tank under its ground motion (sloshdyn_seismic): SI time histories and their peaks, the
  !> roof's verdict and loads (the restricted-sloshing method), and with roof_contact =
  !> 'impact' the paper's impact model's force, labelled as such.
  module subroutine run_seismic(config, files, status, message)
    type(run_config), intent(in) :: config
    type(result_files), intent(inout) :: files
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), allocatable :: table(:, :)
    real(wp) :: peaks(PEAKS_SIZE), instants(PEAK_INSTANT_ROWS, PEAK_INSTANTS), t_end
    integer :: n_out, i, columns, peak_columns
    character(len=2*message_len) :: info(2)
    character(len=:), allocatable :: suffix
    character(len=*), parameter :: loads(SEISMIC_LOADS - 1) = [character(len=24) :: &
      'ground acceleration', 'sloshing displacement', 'wave height', 'pendulum angle', &
      'tank drift', 'tank acceleration', 'convective acceleration', 'base shear', &
      'overturning moment', 'moment with base press.']
    ! engineering precision: 5 significant digits, forces in MN and moments in MN m
    character(len=*), parameter :: units(SEISMIC_LOADS - 1) = [character(len=6) :: &
      'm/s^2', 'm', 'm', 'rad', 'm', 'm/s^2', 'm/s^2', 'MN', 'MN m', 'MN m']
    real(wp), parameter :: unit_exponents(SEISMIC_LOADS - 1) = [0, 0, 0, 0, 0, 0, 0, 6, 6, 6]
    logical :: impact

    t_end = config%seismic%t_end
    n_out = config%seismic%n_out
    call seismic_defaults(config%tank_props, config%ground, t_end, n_out)
    allocate (table(SEISMIC_ROWS, n_out))
    call seismic_response(config%tank, config%ground, t_end, n_out, config%integration, &
                          config%method, table, peaks, instants, status, message)
    call in_context('seismic response', status, message)
    if (status /= SD_OK) return
    impact = config%tank%roof_contact == ROOF_CONTACT_IMPACT
    print '(/a)', 'Seismic response ('//used_method(config)//') from rest, t = 0 to '// &
                  num2str(t_end)//' s, '//num2str(n_out)//' outputs: the tank without contact '// &
                  'below its roof, restricted sloshing above it; peaks:'
    do i = 1, SEISMIC_LOADS - 1
      print '(a)', '  '//pad(trim(loads(i)), 24)// &
                   pad(num2str(peaks(2*i - 1)/10.0_wp**unit_exponents(i), significant=5)//' '// &
                   trim(units(i)), 18)//'at t = '//num2str(peaks(2*i), significant=5)//' s'
    end do
    ! the roof's verdict and loads, of the free wave (sloshdyn_seismic)
    associate (free_wave => peaks(PEAKS_FREE_WAVE))
      if (peaks(PEAKS_ROOF_REACHED) > 0) then
        print '(a)', '  the free wave reaches the roof: first at t = '// &
                     num2str(peaks(PEAKS_FIRST_ROOF_TIME), significant=5)//' s, '// &
                     num2str(nint(peaks(PEAKS_ROOF_IMPACTS)))//' time(s); it rises to '// &
                     num2str(free_wave, significant=5)//' m at the wall (the wave height '// &
                     'above is capped at the roof)'
        print '(a)', '  '//roof_name(config%tank)//', restricted sloshing: head '// &
                     num2str(peaks(PEAKS_ROOF_HEAD), significant=5)//' m, uplift '// &
                     num2str(peaks(PEAKS_ROOF_UPLIFT)/1.0e6_wp, significant=5)// &
                     ' MN, confined convective mass '// &
                     num2str(peaks(PEAKS_CONFINED_MASS), significant=5)//' kg, moving with '// &
                     'the tank from the first contact on (the motion is not integrated again)'
      else
        print '(a)', '  the free wave does not reach the roof: its peak is '// &
                     num2str(100*free_wave/config%tank%freeboard, significant=3)// &
                     ' % of the freeboard ('//eng(config%tank%freeboard)//' m)'
      end if
    end associate
    print '(a)', '  ground motion '//ground_name(config%ground)//': scale factor '// &
                 num2str(peaks(PEAKS_SCALE_FACTOR), significant=5)//', PGA '// &
                 num2str(peaks(1)/config%tank%gravity, significant=5)//' g, Sa('// &
                 num2str(config%tank_props%sloshing_period, significant=4)//' s, 0.5 %) '// &
                 num2str(peaks(PEAKS_SA)/config%tank%gravity, significant=5)//' g'
    if (impact) then
      ! the paper's smooth wall (eq 4-5), opt-in: its force, labelled, feeding no load
      print '(a)', '  the paper''s impact model (roof_contact = ''impact'', beta = '// &
                   num2str(config%tank%impact_stiffness)//', delta = '// &
                   num2str(config%tank%impact_damping)//'; not in any load above): its '// &
                   'impact force peaks at '// &
                   num2str(peaks(PEAKS_IMPACT_FORCE)/1.0e6_wp, significant=5)//' MN = '// &
                   num2str(peaks(PEAKS_IMPACT_FORCE)/ &
                           (config%tank_props%sloshing_mass*config%tank%gravity), &
                           significant=3)//' times the sloshing weight m g'
      if (peaks(PEAKS_BETA_SENSITIVE) > 0) &
        print '(a)', '  warning: the paper''s impact model is sensitive to impact_stiffness '// &
                     '(beta) and impact_damping (delta) here: its wall acts (impact force '// &
                     '>= 0.001 m g; docs/model.md, "Choice of beta and delta")'
    end if
    columns = merge(SEISMIC_ROWS, SEISMIC_FREE_ROWS, impact)
    peak_columns = merge(PEAKS_SIZE, PEAKS_FREE_SIZE, impact)
    suffix = trim(merge('_impact', '       ', impact))
    call begin_files(config, files, status, message, peaks)
    if (status == SD_OK) call files%write_table('seismic.csv', 'seismic'//suffix, &
                                                table(1:columns, :), status, message)
    if (status == SD_OK) call files%write_table('seismic_peaks.csv', 'seismic_peaks'//suffix, &
                                                reshape(peaks(1:peak_columns), &
                                                        [peak_columns, 1]), status, message)
    ! what the run rests on, beside its numbers (the same row as Python's SeismicResponse)
    info(1) = table_header('seismic_run'//suffix)
    info(2) = csv_text(config%ground%name)
    info(2) = trim(info(2))//','//csv_text(config%ground%scaling)
    info(2) = trim(info(2))//','//num2str(peaks(PEAKS_SCALE_FACTOR))//','// &
              num2str(peaks(1))//','//num2str(peaks(PEAKS_SA))//','// &
              num2str(config%tank_props%sloshing_period)//','// &
              trim(roof_contact_names(config%tank%roof_contact))
    if (impact) info(2) = trim(info(2))//','//num2str(config%tank%impact_stiffness)//','// &
                          num2str(config%tank%impact_damping)//','// &
                          num2str(nint(peaks(PEAKS_BETA_SENSITIVE)))
    if (status == SD_OK) call files%write_text('run_info.csv', info, status, message)
    if (status == SD_OK) call write_peak_pressures(config, files, instants, status, message)
  end subroutine run_seismic

  !> A text field of a CSV row: in double quotes, its quotes doubled (RFC 4180).
  pure function csv_text(text) result(field)
    character(len=*), intent(in) :: text
    character(len=:), allocatable :: field
    integer :: i
    field = '"'
    do i = 1, len_trim(text)
      field = field//text(i:i)
      if (text(i:i) == '"') field = field//'"'
    end do
    field = field//'"'
  end function csv_text

  !> A ground motion's name in a summary: the record file's, quoted, or 'harmonic'.
  pure function ground_name(ground) result(name)
    type(ground_motion_t), intent(in) :: ground
    character(len=:), allocatable :: name
    if (ground%kind == GROUND_RECORD) then
      name = ''''//trim(ground%name)//''''
    else
      name = 'harmonic'
    end if
  end function ground_name

  !> The tank's roof in words (sloshdyn_roof's shapes).
  pure function roof_name(tank) result(name)
    type(tank_t), intent(in) :: tank
    character(len=:), allocatable :: name
    if (tank%roof_slope > 0) then
      name = 'cone roof ('//eng(tank%roof_slope)//' degrees)'
    else if (tank%roof_radius > 0) then
      name = 'dome roof (radius '//eng(tank%roof_radius)//' m)'
    else
      name = 'flat roof'
    end if
  end function roof_name

  !> The tank in SI, its ground motion, and its sloshing parameters beside the design codes'.
  module subroutine print_tank(config)
    type(run_config), intent(in) :: config
    real(wp) :: codes(CODES_COLUMNS, CODES_ROWS)
    integer :: status, i
    character(len=message_len) :: message

    associate (t => config%tank, p => config%tank_props)
      if (t%shape == SHAPE_CIRCULAR) then
        print '(/a)', 'Tank (SI): radius R = '//eng(t%radius)//' m, liquid depth h = '// &
                      eng(t%liquid_depth)//' m, freeboard = '//eng(t%freeboard)//' m'
      else
        print '(/a)', 'Tank (SI): rectangular, length L = '//eng(t%length)// &
                      ' m (along the motion), width '//eng(t%width)//' m, liquid depth h = '// &
                      eng(t%liquid_depth)//' m, freeboard = '//eng(t%freeboard)//' m'
      end if
      print '(a)', '  liquid '//eng(p%liquid_mass)//' kg, tank (shell, roof) '// &
                   eng(t%tank_mass)//' kg, total M = '//eng(p%total_mass)//' kg'
      print '(a)', '  sloshing ('//trim(merge('eq 2-3                ', &
                   'potential flow, mode 1', t%shape == SHAPE_CIRCULAR))// &
                   '): pendulum l = '//eng(p%pendulum_length)// &
                   ' m, convective mass m = '//eng(p%sloshing_mass)//' kg at '// &
                   eng(p%convective_height)//' m, impulsive m0 = '// &
                   eng(p%rigid_mass)//' kg at '//eng(p%impulsive_height)// &
                   ' m above the bottom; sloshing period '//eng(p%sloshing_period)//' s'
      print '(a)', '  supports: L = '//eng(p%rod_length)//' m, k = '// &
                   eng(p%stiffness)//' N m/rad, c = '//eng(p%damping)// &
                   ' N m s/rad; sloshing damping '//eng(100*t%sloshing_damping)// &
                   ' % of critical'
      if (p%roof_reachable) then
        print '(a)', '  roof: the wave at the wall, '//trim(merge('2 R sin(theta)/(xi^2 - 1)', &
                     '4 L sin(theta)/pi^2      ', t%shape == SHAPE_CIRCULAR))//' = '// &
                     eng(p%wave_factor)//' m sin(theta), reaches the freeboard at theta0 = '// &
                     eng(p%theta0)//' rad'
      else
        ! issue 38: a freeboard beyond the linear wave is checked, not refused
        print '(a)', '  roof: the linear wave at the wall reaches at most '// &
                     eng(p%wave_factor)//' m < the freeboard: it cannot reach the roof '// &
                     '(theta0 capped at '//eng(p%theta0)//' rad for the model; the roof '// &
                     'verdicts take the free wave against the freeboard)'
      end if
      do i = 2, p%modes
        print '(a)', '  sloshing mode '//num2str(i)//' (linear): period '// &
                     eng(p%modal_period(i))//' s, mass '//eng(p%modal_mass(i))// &
                     ' kg at '//eng(p%modal_height(i))//' m, wave at the wall '// &
                     eng(p%modal_wave(i))//' m sin(theta_'//num2str(i)//')'
      end do
    end associate
    if (config%has_ground) then
      associate (g => config%ground)
        if (g%kind == GROUND_RECORD) then
          print '(a)', 'Ground motion: the record '''//trim(g%name)//''' of '// &
                       num2str(size(g%acceleration))// &
                       ' samples every '//eng(g%dt)//' s ('//eng(ground_duration(g))// &
                       ' s), peak '//eng(maxval(abs(g%acceleration)))//' m/s^2 = '// &
                       eng(maxval(abs(g%acceleration))/config%tank%gravity)//' g'
        else
          print '(a)', 'Ground motion: harmonic, peak '//eng(g%peak_acceleration)// &
                       ' m/s^2 = '//eng(g%peak_acceleration/config%tank%gravity)//' g at '// &
                       eng(g%frequency)//' Hz'
        end if
        if (len_trim(g%scaling) > 0) print '(a)', '  scaled ('//trim(g%scaling)// &
                                                   '): factor '//eng(g%scale_factor)
      end associate
      if (config%has_ground_y) then
        print '(a)', '  along azimuth '//eng(config%azimuth)//' rad; across it record_y, '// &
                     num2str(size(config%ground_y%acceleration))//' samples, peak '// &
                     eng(maxval(abs(config%ground_y%acceleration)))// &
                     ' m/s^2 (scaled by the same factor)'
      else if (.not. config%planar) then
        print '(a)', '  along azimuth '//eng(config%azimuth)//' rad, ellipticity '// &
                     eng(config%ellipticity)
      end if
    end if
    call design_code_checks(config%tank, config%ground, config%has_ground, codes, status, &
                            message)
    if (status /= SD_OK) then
      print '(a)', '  (design-code cross-check not available: '//trim(message)//')'
      return
    end if
    if (config%has_ground) then
      print '(/a)', 'Design-code cross-check (difference from sloshdyn in %; wave heights from '// &
                    'the ground motion''s spectrum at '// &
                    num2str(100*config%tank%sloshing_damping)//' % damping)'
    else
      print '(/a)', 'Design-code cross-check (difference from sloshdyn in %; no ground motion, '// &
                    'so no wave heights)'
    end if
    print '(a)', design_codes_table(codes)
  end subroutine print_tank

  !> The design-code cross-check as the executable prints it (and Python's str(DesignCodes)):
  !> a header, then a line per quantity: sloshdyn's value and each code's, with its difference
  !> from sloshdyn in %, then the modal sums if any is given (a tank with modes > 1); lines end
  !> with new_line('a'), the last one not.
  pure module function design_codes_table(codes) result(text)
    real(wp), intent(in) :: codes(CODES_COLUMNS, CODES_ROWS)
    character(len=:), allocatable :: text
    character(len=*), parameter :: quantities(CODES_COLUMNS) = [character(len=24) :: &
      'convective period [s]', 'convective mass [kg]', 'impulsive mass [kg]', &
      'convective height [m]', 'impulsive height [m]', 'wave height [m]']
    character(len=:), allocatable :: line
    integer :: i, j, n
    n = merge(CODES_ROWS, CODES_SOURCES, any(codes(:, CODES_SOURCES + 1:) == &
                                            codes(:, CODES_SOURCES + 1:)))
    text = '  '//pad('', 24)//pad('sloshdyn', 14)//pad('API 650', 22)//pad('EC8-4', 22)// &
           'ACI 350.3'
    if (n > CODES_SOURCES) text = text//repeat(' ', 13)//pad('modes SRSS', 22)//'modes ABS'
    do i = 1, CODES_COLUMNS
      line = '  '//pad(trim(quantities(i)), 24)//pad(value_text(codes(i, 1), 5), 14)
      do j = 2, n
        line = line//pad(value_text(codes(i, j), 5)//difference(codes(i, j), codes(i, 1)), 22)
      end do
      text = text//new_line('a')//trim(line)
    end do
  end function design_codes_table

  !> A number of the tank's SI summary: engineering precision, 5 significant digits (the CSV
  !> files keep full precision).
  pure function eng(x) result(text)
    real(wp), intent(in) :: x
    character(len=:), allocatable :: text
    text = num2str(x, significant=5)
  end function eng

end submodule sloshdyn_driver_tank
