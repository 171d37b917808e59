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
  use sloshdyn_vessel, only: tank_t, tank_properties, convective_damping, roof_contact_names
  use sloshdyn_tank, only: shape_names, SHAPE_RECTANGULAR
  use sloshdyn_ground, only: ground_motion_t, harmonic_ground, record_ground, scale_ground, &
                             on_time_grid
  use sloshdyn_records, only: load_record, units_code, units_factor
  use sloshdyn_seismic, only: max_seismic_outputs
  use sloshdyn_design_spectra, only: design_spectrum_t, check_spectrum, ground_types, &
                                     SPECTRUM_ASCE7, SPECTRUM_ACI350, SPECTRUM_EC8
  use sloshdyn_design_loads, only: design_factors_t, check_factors, wall_pressure_names
  use sloshdyn_tank_structure, only: tank_structure_t, material_names, anchorage_names, &
                                     max_courses
  use sloshdyn_layouts, only: design_spectra, DESIGN_FROM_GROUND
  use sloshdyn_stability_chart, only: chart_settings, check_chart_settings
  use sloshdyn_slowflow_chart, only: chart_parameter_name, CHART_RHO, CHART_A, CHART_GAMMA, &
                                     CHART_KAPPA
  use sloshdyn_ode, only: ode_options, check_options
  use sloshdyn_integrator, only: METHOD_AUTO, method_names
  use sloshdyn_simulation, only: steady_options, max_simulation_outputs
  use sloshdyn_response, only: response_options, check_response_options
  use sloshdyn_periodic_response, only: lyapunov_options
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

  !> &tank: a cylindrical or rectangular tank on supports in SI units (sloshdyn_vessel), defaults
  !> from tank_t; radius for shape = 'circular', length and width for 'rectangular'; planar
  !> (.false.: the spatial model of issue 26, sloshdyn_spatial).
  subroutine read_tank(file, vessel, planar, status, message)
    type(input_file), intent(inout) :: file
    type(tank_t), intent(out) :: vessel
    logical, intent(out) :: planar
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: radius, liquid_depth, freeboard, liquid_density, liquid_mass, tank_mass, &
                support_frequency, support_damping, support_stiffness, &
                support_damping_coefficient, support_height, sloshing_damping, &
                impact_stiffness, impact_damping, gravity, roof_slope, roof_radius, length, width
    integer :: n, p, modes, code, contact
    character(len=word_len) :: shape, roof_contact
    type(namelist_reader) :: reader
    namelist /tank/ radius, liquid_depth, freeboard, liquid_density, liquid_mass, tank_mass, &
                    support_frequency, support_damping, support_stiffness, &
                    support_damping_coefficient, support_height, sloshing_damping, &
                    impact_stiffness, impact_damping, n, p, gravity, roof_slope, roof_radius, &
                    shape, length, width, modes, planar, roof_contact

    radius = vessel%radius; liquid_depth = vessel%liquid_depth; freeboard = vessel%freeboard
    liquid_density = vessel%liquid_density; liquid_mass = vessel%liquid_mass
    tank_mass = vessel%tank_mass; support_frequency = vessel%support_frequency
    support_damping = vessel%support_damping; support_stiffness = vessel%support_stiffness
    support_damping_coefficient = vessel%support_damping_coefficient
    support_height = vessel%support_height; sloshing_damping = vessel%sloshing_damping
    impact_stiffness = vessel%impact_stiffness; impact_damping = vessel%impact_damping
    n = vessel%n; p = vessel%p; gravity = vessel%gravity
    roof_slope = vessel%roof_slope; roof_radius = vessel%roof_radius
    shape = shape_names(vessel%shape); length = vessel%length; width = vessel%width
    modes = vessel%modes
    roof_contact = roof_contact_names(vessel%roof_contact)
    planar = .true.
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
    code = findloc(shape_names, lower(trim(adjustl(shape))), dim=1)
    if (code == 0) call fail(status, message, "&tank: shape = '"//trim(adjustl(shape))// &
                             "' is not known; allowed: "//join(shape_names, ', '))
    contact = findloc(roof_contact_names, lower(trim(adjustl(roof_contact))), dim=1)
    if (contact == 0) call fail(status, message, "&tank: roof_contact = '"// &
                                trim(adjustl(roof_contact))//"' is not known; allowed: "// &
                                join(roof_contact_names, ', '))
    if (code == SHAPE_RECTANGULAR) then
      call require(file, G_TANK, 'length', status, message)
      call require(file, G_TANK, 'width', status, message)
    else
      call require(file, G_TANK, 'radius', status, message)
    end if
    call require(file, G_TANK, 'liquid_depth', status, message)
    call require(file, G_TANK, 'freeboard', status, message)
    call require(file, G_TANK, 'tank_mass', status, message)
    vessel = tank_t(radius, liquid_depth, freeboard, liquid_density, liquid_mass, tank_mass, &
                    support_frequency, support_damping, support_stiffness, &
                    support_damping_coefficient, support_height, sloshing_damping, &
                    impact_stiffness, impact_damping, n, p, gravity, roof_slope, roof_radius, &
                    max(code, 1), length, width, modes, max(contact, 1))
  end subroutine read_tank

  !> &ground_motion: a record file (PEER NGA .AT2, or two columns time, acceleration) or harmonic
  !> motion (peak_acceleration, frequency), scaled by a factor, to a peak ground acceleration,
  !> or to a pseudo-spectral acceleration at target_period (default: the tank's sloshing period)
  !> for target_damping (default: the convective 0.5 %); accelerations in `units` ('g',
  !> 'm/s^2', 'cm/s^2'). A sweep in frequency gives the frequency (sweep_frequency >= 0, its
  !> first [Hz]; < 0: no such sweep) when none is given.
  !> The second horizontal component (the spatial model, issue 26; sloshdyn_seismic_spatial):
  !> record_y, a record across the first (same format and units, resampled onto its time grid by
  !> sloshdyn_ground's on_time_grid; scaled by the first one's factor, one factor for both as
  !> FEMA P695 scales a pair; has_y), or for harmonic motion its
  !> azimuth [rad from x] and ellipticity (minor over major axis).
  subroutine read_ground_motion(file, props, sweep_frequency, ground, ground_y, has_y, &
                                azimuth, ellipticity, status, message)
    type(input_file), intent(inout) :: file
    type(tank_properties), intent(in) :: props
    real(wp), intent(in) :: sweep_frequency
    type(ground_motion_t), intent(out) :: ground, ground_y
    logical, intent(out) :: has_y
    real(wp), intent(out) :: azimuth, ellipticity
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    character(len=path_len) :: record, record_y
    character(len=word_len) :: format, units
    real(wp) :: peak_acceleration, frequency, scale_factor, target_pga, target_sa, &
                target_period, target_damping, to_si, dt, dt_y
    real(wp), allocatable :: acceleration(:)
    character(len=:), allocatable :: harmonic
    integer :: unit_code
    type(namelist_reader) :: reader
    namelist /ground_motion/ record, format, units, peak_acceleration, frequency, scale_factor, &
                             target_pga, target_sa, target_period, target_damping, record_y, &
                             azimuth, ellipticity

    record = ''; record_y = ''; format = 'auto'; units = 'g'; azimuth = 0; ellipticity = 0
    has_y = .false.
    peak_acceleration = 0; frequency = 0; scale_factor = 1; target_pga = 0; target_sa = 0
    target_period = 0; target_damping = convective_damping
    harmonic = ''
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
    call check_real('azimuth', azimuth, -2*pi, 2*pi, .false., .false., &
                    'azimuth must lie in [-2 pi, 2 pi] rad (from the x axis)', status, message)
    call check_real('ellipticity', ellipticity, 0.0_wp, 1.0_wp, .false., .false., &
                    'ellipticity (minor over major axis of the ground''s ellipse) must lie in '// &
                    '[0, 1]', status, message)
    if (len_trim(record_y) > 0 .and. len_trim(record) == 0) &
      call fail(status, message, "&ground_motion: record_y = '"//trim(record_y)//"' is the "// &
                'second component of a record: give the first one in record')
    if (len_trim(record) > 0 .and. given(file, G_GROUND_MOTION, 'ellipticity')) &
      call fail(status, message, '&ground_motion: ellipticity = '//num2str(ellipticity)// &
                ' shapes harmonic motion; the second component of a record is record_y')
    ! a record or harmonic motion, not both (Python's GroundMotion applies the same rule)
    if (given(file, G_GROUND_MOTION, 'peak_acceleration')) harmonic = ', peak_acceleration'
    if (given(file, G_GROUND_MOTION, 'frequency')) harmonic = harmonic//', frequency'
    if (len_trim(record) > 0 .and. len(harmonic) > 0) &
      call fail(status, message, "&ground_motion: record = '"//trim(record)//"' and "// &
                harmonic(3:)//' are both given: the ground motion is a record or harmonic '// &
                '(peak_acceleration, frequency), not both')
    if (status == SD_OK) then
      if (len_trim(record) > 0) then
        call load_record(beside(file%path, trim(record)), format, units, dt, acceleration, &
                         status, message)
        if (status == SD_OK) ground = record_ground(dt, acceleration)
        if (status == SD_OK .and. len_trim(record_y) > 0) then
          call load_record(beside(file%path, trim(record_y)), format, units, dt_y, acceleration, &
                           status, message)
          if (status /= SD_OK) then
            message = "record_y = '"//trim(record_y)//"': "//trim(message)
          else
            ! on the first record's time grid (sloshdyn_ground's on_time_grid)
            ground_y = on_time_grid(record_ground(dt_y, acceleration), dt)
            has_y = .true.
          end if
        end if
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
      ground%name = record(index(record, '/', back=.true.) + 1:)
      ! one factor for both components, the first one's (FEMA P695 scales a pair as one)
      if (status == SD_OK .and. has_y) then
        ground_y%acceleration = ground%scale_factor*ground_y%acceleration
        ground_y%scale_factor = ground%scale_factor
        ground_y%scaling = ground%scaling
      end if
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

  !> &seismic (see seismic_settings).
  subroutine read_seismic(file, settings, status, message)
    type(input_file), intent(inout) :: file
    type(seismic_settings), intent(out) :: settings
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: t_end
    integer :: n_out
    type(namelist_reader) :: reader
    namelist /seismic/ t_end, n_out
    t_end = settings%t_end
    n_out = settings%n_out
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
    call check_output_count('n_out', n_out, max_seismic_outputs, .true., status, message)
    if (status /= SD_OK) then
      message = '&seismic: '//trim(message)
      return
    end if
    settings = seismic_settings(t_end, n_out)
  end subroutine read_seismic

  !> &design (issue 25; docs/design.md): the spectrum of the design check and the codes'
  !> factors, defaults from design_spectrum_t and design_factors_t. spectrum = 'asce7' needs
  !> s_ds, s_d1 and t_l; 'aci350' s_ds and s_d1 (and t_l for API 650's rows); 'ec8' a_gr;
  !> 'ground_motion' the &ground_motion (read_input's rule).
  subroutine read_design(file, spec, factors, from_ground, status, message)
    type(input_file), intent(inout) :: file
    type(design_spectrum_t), intent(out) :: spec
    type(design_factors_t), intent(out) :: factors
    logical, intent(out) :: from_ground
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    character(len=word_len) :: spectrum, ground_type, wall_pressure
    real(wp) :: s_ds, s_d1, t_l, k, a_gr, gamma_i, q, beta, importance, r_wi, r_wc, r_i, r_c, &
                impulsive_period, impulsive_damping_ratio, tank_mass_height, &
                vertical_acceleration
    integer :: spectrum_type, use_group, code, ground_code, wall_code
    logical :: vertical
    type(namelist_reader) :: reader
    namelist /design/ spectrum, s_ds, s_d1, t_l, k, a_gr, gamma_i, ground_type, spectrum_type, &
                      q, beta, importance, use_group, r_wi, r_wc, r_i, r_c, impulsive_period, &
                      impulsive_damping_ratio, tank_mass_height, vertical, &
                      vertical_acceleration, wall_pressure

    spectrum = design_spectra(spec%kind); s_ds = spec%s_ds; s_d1 = spec%s_d1; t_l = spec%t_l
    k = spec%k; a_gr = spec%a_gr; gamma_i = spec%gamma_i
    ground_type = ground_types(spec%ground_type); spectrum_type = spec%ec8_type
    q = spec%q; beta = spec%beta
    importance = factors%importance; use_group = factors%use_group; r_wi = factors%r_wi
    r_wc = factors%r_wc; r_i = factors%r_i; r_c = factors%r_c
    impulsive_period = factors%impulsive_period
    impulsive_damping_ratio = factors%impulsive_damping_ratio
    tank_mass_height = factors%tank_mass_height; vertical = factors%vertical
    vertical_acceleration = factors%vertical_acceleration
    wall_pressure = wall_pressure_names(factors%wall_pressure)
    from_ground = .false.
    status = SD_OK
    message = ''
    call reader%start(file, G_DESIGN, status)
    do while (reader%next())
      if (reader%describing) then
        write (reader%written, nml=design, iostat=reader%ios)
      else
        read (reader%text, nml=design, iostat=reader%ios, iomsg=reader%iomsg)
      end if
      call reader%check(file, status, message)
    end do
    if (status /= SD_OK .or. .not. file%groups(G_DESIGN)%given) return
    code = findloc(design_spectra, lower(trim(adjustl(spectrum))), dim=1)
    if (code == 0) call fail(status, message, "&design: spectrum = '"// &
                             trim(adjustl(spectrum))//"' is not known; allowed: "// &
                             join(design_spectra, ', '))
    wall_code = findloc(wall_pressure_names, lower(trim(adjustl(wall_pressure))), dim=1)
    if (wall_code == 0) call fail(status, message, "&design: wall_pressure = '"// &
                                  trim(adjustl(wall_pressure))//"' is not known; allowed: "// &
                                  join(wall_pressure_names, ', '))
    ground_code = findloc(ground_types, trim(adjustl(ground_type)), dim=1)
    if (ground_code == 0) call fail(status, message, "&design: ground_type = '"// &
                                    trim(adjustl(ground_type))//"' is not known; allowed: "// &
                                    join(ground_types, ', ')//' (EN 1998-1 Table 3.1)')
    if (status /= SD_OK) return
    select case (code)
    case (SPECTRUM_ASCE7, SPECTRUM_ACI350)
      call require(file, G_DESIGN, 's_ds', status, message)
      call require(file, G_DESIGN, 's_d1', status, message)
      if (code == SPECTRUM_ASCE7) call require(file, G_DESIGN, 't_l', status, message)
    case (SPECTRUM_EC8)
      call require(file, G_DESIGN, 'a_gr', status, message)
    end select
    if (status /= SD_OK) return
    from_ground = code == DESIGN_FROM_GROUND
    spec = design_spectrum_t(merge(SPECTRUM_ASCE7, code, from_ground), s_ds, s_d1, t_l, k, &
                             a_gr, gamma_i, ground_code, spectrum_type, q, beta)
    factors = design_factors_t(importance, use_group, r_wi, r_wc, r_i, r_c, impulsive_period, &
                               impulsive_damping_ratio, tank_mass_height, vertical, &
                               vertical_acceleration, wall_code)
    ! the rules that need the tank (sloshdyn_design_check's check_design_input) are read_input's
    call check_factors(factors, status, message)
    if (status /= SD_OK) message = '&design: '//trim(message)
  end subroutine read_design

  !> &tank_structure (issue 38; docs/namelist.md): the tank's structure for the design check's
  !> structural checks, defaults from tank_structure_t; course_height (the bottom course's) is
  !> required. Its rules with the tank are sloshdyn_tank_structure's check_structure (read_input).
  subroutine read_tank_structure(file, st, status, message)
    type(input_file), intent(inout) :: file
    type(tank_structure_t), intent(out) :: st
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    character(len=word_len) :: material, anchorage
    real(wp), dimension(max_courses) :: course_height, course_thickness, course_yield_strength, &
                                        course_tensile_strength
    real(wp) :: corrosion_allowance, joint_efficiency, elastic_modulus, density, &
                bottom_thickness, annular_thickness, bottom_corrosion_allowance, &
                annular_yield_strength, roof_mass, roof_mass_height, anchor_capacity, friction
    integer :: anchor_count, material_code, anchorage_code
    type(namelist_reader) :: reader
    namelist /tank_structure/ material, course_height, course_thickness, &
                              course_yield_strength, course_tensile_strength, &
                              corrosion_allowance, joint_efficiency, elastic_modulus, density, &
                              bottom_thickness, annular_thickness, bottom_corrosion_allowance, &
                              annular_yield_strength, roof_mass, roof_mass_height, anchorage, &
                              anchor_count, anchor_capacity, friction

    material = material_names(st%material); course_height = st%course_height
    course_thickness = st%course_thickness; course_yield_strength = st%course_yield_strength
    course_tensile_strength = st%course_tensile_strength
    corrosion_allowance = st%corrosion_allowance; joint_efficiency = st%joint_efficiency
    elastic_modulus = st%elastic_modulus; density = st%density
    bottom_thickness = st%bottom_thickness; annular_thickness = st%annular_thickness
    bottom_corrosion_allowance = st%bottom_corrosion_allowance
    annular_yield_strength = st%annular_yield_strength; roof_mass = st%roof_mass
    roof_mass_height = st%roof_mass_height; anchorage = anchorage_names(st%anchorage)
    anchor_count = st%anchor_count; anchor_capacity = st%anchor_capacity; friction = st%friction
    status = SD_OK
    message = ''
    call reader%start(file, G_TANK_STRUCTURE, status)
    do while (reader%next())
      if (reader%describing) then
        write (reader%written, nml=tank_structure, iostat=reader%ios)
      else
        read (reader%text, nml=tank_structure, iostat=reader%ios, iomsg=reader%iomsg)
      end if
      call reader%check(file, status, message)
    end do
    if (status /= SD_OK .or. .not. file%groups(G_TANK_STRUCTURE)%given) return
    call require(file, G_TANK_STRUCTURE, 'course_height', status, message)
    call require(file, G_TANK_STRUCTURE, 'course_thickness', status, message)
    material_code = findloc(material_names, lower(trim(adjustl(material))), dim=1)
    if (status == SD_OK .and. material_code == 0) &
      call fail(status, message, "&tank_structure: material = '"//trim(adjustl(material))// &
                "' is not known; allowed: "//join(material_names, ', '))
    anchorage_code = findloc(anchorage_names, lower(trim(adjustl(anchorage))), dim=1)
    if (status == SD_OK .and. anchorage_code == 0) &
      call fail(status, message, "&tank_structure: anchorage = '"//trim(adjustl(anchorage))// &
                "' is not known; allowed: "//join(anchorage_names, ', '))
    if (status /= SD_OK) return
    st = tank_structure_t(.true., material_code, course_height, course_thickness, &
                          course_yield_strength, course_tensile_strength, corrosion_allowance, &
                          joint_efficiency, elastic_modulus, density, bottom_thickness, &
                          annular_thickness, bottom_corrosion_allowance, annular_yield_strength, &
                          roof_mass, roof_mass_height, anchorage_code, anchor_count, &
                          anchor_capacity, friction)
  end subroutine read_tank_structure

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
                f_tol
    integer :: n_scan, n_amplitudes, n_phases, max_points, max_iter, switch_at
    type(namelist_reader) :: reader
    namelist /response/ resonance, parameter, start, stop, n_scan, n_amplitudes, n_phases, &
                        amplitude_min, amplitude_max, ds, ds_min, ds_max, x_scale, max_points, &
                        x_tol, f_tol, max_iter, switch_at

    resonance = '3:1'; parameter = 'rho'; start = 0; stop = 0; switch_at = settings%switch_at
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

  subroutine read_lyapunov(file, options, status, message)
    type(input_file), intent(inout) :: file
    type(lyapunov_options), intent(out) :: options
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: transient_periods
    integer :: n_periods, renormalise_every
    logical :: spectrum
    type(namelist_reader) :: reader
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
