!> The groups of a tank in SI units and of its design check (&tank, &ground_motion, &seismic,
!> &design, &tank_structure): a submodule of sloshdyn_namelist_groups, which declares their
!> interfaces and holds the reader type and the group codes. docs/namelist.md documents them.
submodule (sloshdyn_namelist_groups) sloshdyn_namelist_tank
  ! the modules the parent does not use, by use (meson rebuilds a submodule when a module it
  ! uses changes); the rest (kinds, status, scanner, the types) from the parent
  use sloshdyn_vessel, only: convective_damping, roof_contact_names
  use sloshdyn_tank, only: shape_names, SHAPE_RECTANGULAR
  use sloshdyn_ground, only: harmonic_ground, record_ground, scale_ground, on_time_grid
  use sloshdyn_records, only: load_record, units_code, units_factor
  use sloshdyn_seismic, only: max_seismic_outputs
  use sloshdyn_design_spectra, only: ground_types, SPECTRUM_ASCE7, SPECTRUM_ACI350, SPECTRUM_EC8
  use sloshdyn_design_loads, only: check_factors, wall_pressure_names
  use sloshdyn_tank_structure, only: material_names, anchorage_names, max_courses
  use sloshdyn_layouts, only: design_spectra, DESIGN_FROM_GROUND
  implicit none

contains

  !> &tank: a cylindrical or rectangular tank on supports in SI units (sloshdyn_vessel), defaults
  !> from tank_t; radius for shape = 'circular', length and width for 'rectangular'; planar
  !> (.false.: the spatial model of issue 26, sloshdyn_spatial).
  module subroutine read_tank(file, vessel, planar, status, message)
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

  !> &seismic (see seismic_settings).
  module subroutine read_seismic(file, settings, status, message)
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
  module subroutine read_design(file, spec, factors, from_ground, status, message)
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
  module subroutine read_tank_structure(file, st, status, message)
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
  !> A path relative to the folder of the input file (absolute paths as they are; the
  !> parent's read_output uses it too: declared there, as a private procedure of the parent
  !> may not be emitted when only a submodule calls it by host association).
  module pure function beside(input_path, path) result(full)
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
end submodule sloshdyn_namelist_tank
