!> The design check of a tank (issues 25 and 38; docs/design.md): each code's seismic loads in
!> its own format ('design_loads'), its freeboard check ('freeboard_check'), and, for a
!> checker, every check with its verdict ('design_checks') and the hand calculation
!> ('design_calc'), from a code design spectrum (sloshdyn_design_spectra) or from a ground
!> motion's pseudo-spectral acceleration at the code's periods and dampings
!> (sloshdyn_design_source); with the tank's structure (&tank_structure) the codes' structural
!> checks. The codes are their modules: sloshdyn_api650_checks, sloshdyn_aci350_checks,
!> sloshdyn_ec8_checks. Beside them sloshdyn's own: linear (the response-spectrum method on its
!> model: first sloshing mode and the rigid mass, elastic, SRSS) and, given the peaks of a
!> time-history run (sloshdyn_seismic), nonlinear.
!>
!> Which codes a source feeds: an ASCE 7 (or ACI 350.3) spectrum API 650 (its ASCE 7 form,
!> E.4.6.1) and ACI 350.3 (its sec 9.4 form, from the same S_DS and S_D1); an EN 1998-1
!> spectrum EN 1998-4; a ground motion all three. API 650 and EN 1998-4's Annex A are for
!> circular tanks: their rows are NaN for a rectangular one. A row a source does not feed is NaN.
!> Every number of the results is finite, or the check fails with SD_NON_FINITE naming it.
module sloshdyn_design_check
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_is_finite
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, SD_NON_FINITE, check_real
  use sloshdyn_text, only: num2str
  use sloshdyn_model, only: model_t
  use sloshdyn_vessel, only: tank_t, tank_properties, tank_model
  use sloshdyn_tank, only: SHAPE_CIRCULAR
  use sloshdyn_ground, only: ground_motion_t
  use sloshdyn_design_spectra, only: design_spectrum_t, check_spectrum, SPECTRUM_ASCE7, &
                                     SPECTRUM_ACI350, SPECTRUM_EC8, IMPULSIVE_RATIO, &
                                     is_tabulated
  use sloshdyn_design_loads, only: design_factors_t, check_factors, code_loads, &
                                   WALL_PRESSURE_ELASTIC
  use sloshdyn_design_source, only: design_source_t, source_sa, source_impulsive_sa
  use sloshdyn_design_report, only: design_report_t, pick
  use sloshdyn_tank_structure, only: tank_structure_t, check_structure, tank_top_height
  use sloshdyn_api650_checks, only: api650_design
  use sloshdyn_aci350_checks, only: aci350_design
  use sloshdyn_ec8_checks, only: ec8_design
  use sloshdyn_tables, only: DESIGN_ROWS, DESIGN_API650, DESIGN_EC8, DESIGN_ACI350, &
                             DESIGN_LINEAR, DESIGN_NONLINEAR, DESIGN_LOADS_COLUMNS, &
                             FREEBOARD_COLUMNS, PEAKS_SIZE, PEAKS_FREE_WAVE, PEAKS_ROOF_REACHED, &
                             PEAKS_BASE_SHEAR, PEAKS_OVERTURNING_MOMENT, &
                             PEAKS_OVERTURNING_MOMENT_IBP, LOADS_MOMENT_IBP, &
                             LOADS_CONVECTIVE_PERIOD, LOADS_BASE_SHEAR, LOADS_MOMENT_EBP, &
                             FREEBOARD_SUFFICIENT, LOADS_IMPULSIVE_ACCELERATION, &
                             LOADS_CONVECTIVE_ACCELERATION, table_header, code_name
  implicit none
  private
  public :: design_check, check_design_input, wall_pressure_row

contains

  !> The inputs of a design check in their ranges and consistent with each other and with the
  !> tank (the same rule for both front doors): the factors, the spectrum (or only q for a
  !> ground motion; every real finite), the structure, the tank's mass height within the tank.
  pure subroutine check_design_input(tank, spec, factors, from_ground, structure, status, &
                                     message)
    type(tank_t), intent(in) :: tank
    type(design_spectrum_t), intent(in) :: spec
    type(design_factors_t), intent(in) :: factors
    logical, intent(in) :: from_ground
    type(tank_structure_t), intent(in) :: structure
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(design_spectrum_t) :: asce7
    call check_factors(factors, status, message)
    if (from_ground) then
      call check_real('q', spec%q, 1.0_wp, 8.0_wp, .false., .false., 'q must be in [1, 8] '// &
                      '(EN 1998-1 3.2.2.5; EN 1998-4 2.3.3.3)', status, message)
      call check_unused(spec, status, message)
    else if (status == SD_OK) then
      call check_spectrum(spec, status, message)
      ! an ACI 350.3 spectrum's T_L (for API 650's rows) is 0 or ASCE 7's
      if (status == SD_OK .and. spec%kind == SPECTRUM_ACI350 .and. spec%t_l /= 0) then
        asce7 = spec
        asce7%kind = SPECTRUM_ASCE7
        call check_spectrum(asce7, status, message)
      end if
      if (status == SD_OK .and. spec%kind /= SPECTRUM_EC8 .and. &
          .not. is_tabulated(factors%impulsive_damping_ratio, IMPULSIVE_RATIO)) then
        status = SD_BAD_INPUT
        message = 'impulsive_damping_ratio = '//num2str(factors%impulsive_damping_ratio)// &
                  ' is out of range: ASCE 7-16 11.4.6 and ACI 350.3-06 9.4.1 tabulate the '// &
                  'impulsive response at 0.05 (5 %) only'
      end if
    end if
    if (status == SD_OK .and. factors%tank_mass_height > tank_top_height(tank)) then
      status = SD_BAD_INPUT
      message = 'tank_mass_height = '//num2str(factors%tank_mass_height)//' is out of range: '// &
                'the tank''s mass lies within the tank, [0, '// &
                num2str(tank_top_height(tank))//'] m (0: (liquid_depth + freeboard)/2)'
    end if
    if (status == SD_OK .and. structure%given .and. factors%tank_mass_height > 0) then
      status = SD_BAD_INPUT
      message = 'tank_mass_height = '//num2str(factors%tank_mass_height)//' is out of range: '// &
                'with &tank_structure each mass has its own height (roof_mass_height; the '// &
                'courses''), give 0'
    end if
    call check_structure(tank, structure, status, message)
  end subroutine check_design_input

  !> A ground motion's check reads only K and q of the spectrum: the others must be finite.
  pure subroutine check_unused(spec, status, message)
    type(design_spectrum_t), intent(in) :: spec
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    character(len=*), parameter :: rule = 'every variable of &design must be finite'
    call check_real('s_ds', spec%s_ds, -huge(1.0_wp), huge(1.0_wp), .false., .false., rule, &
                    status, message)
    call check_real('s_d1', spec%s_d1, -huge(1.0_wp), huge(1.0_wp), .false., .false., rule, &
                    status, message)
    call check_real('t_l', spec%t_l, -huge(1.0_wp), huge(1.0_wp), .false., .false., rule, &
                    status, message)
    call check_real('k', spec%k, -huge(1.0_wp), huge(1.0_wp), .false., .false., rule, status, &
                    message)
    call check_real('a_gr', spec%a_gr, -huge(1.0_wp), huge(1.0_wp), .false., .false., rule, &
                    status, message)
    call check_real('gamma_i', spec%gamma_i, -huge(1.0_wp), huge(1.0_wp), .false., .false., &
                    rule, status, message)
    call check_real('beta', spec%beta, -huge(1.0_wp), huge(1.0_wp), .false., .false., rule, &
                    status, message)
  end subroutine check_unused

  !> The design check of the tank: loads(DESIGN_LOADS_COLUMNS, DESIGN_ROWS) and
  !> freeboard(FREEBOARD_COLUMNS, DESIGN_ROWS) in the 'design_loads' and 'freeboard_check'
  !> layouts (without their source column; NaN rows where a source gives none) and the report
  !> (checks and hand calculation). from_ground: the accelerations from the ground motion's
  !> spectrum (spec then supplies only K and q), else from spec. structure: &tank_structure
  !> (structure%given). peaks: the 'seismic_peaks' of a nonlinear run of the same tank and
  !> motion (the row 'sloshdyn nonlinear').
  subroutine design_check(tank, spec, factors, from_ground, ground, structure, loads, freeboard, &
                          report, status, message, peaks)
    type(tank_t), intent(in) :: tank
    type(design_spectrum_t), intent(in) :: spec
    type(design_factors_t), intent(in) :: factors
    logical, intent(in) :: from_ground
    type(ground_motion_t), intent(in) :: ground
    type(tank_structure_t), intent(in) :: structure
    real(wp), intent(out) :: loads(DESIGN_LOADS_COLUMNS, DESIGN_ROWS), &
                             freeboard(FREEBOARD_COLUMNS, DESIGN_ROWS)
    type(design_report_t), intent(out) :: report
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), intent(in), optional :: peaks(PEAKS_SIZE)
    type(model_t) :: model
    type(tank_properties) :: props
    type(design_source_t) :: source
    type(tank_structure_t) :: st
    real(wp) :: nan, h_t, m_t
    logical :: circular, us_codes, ec8_code

    nan = ieee_value(1.0_wp, ieee_quiet_nan)
    loads = nan
    freeboard = nan
    call check_design_input(tank, spec, factors, from_ground, structure, status, message)
    if (status == SD_OK) call tank_model(tank, model, props, status, message)
    if (status /= SD_OK) return
    source = design_source_t(spec, from_ground, ground, tank%gravity)
    ! without the structure its defaults (E.7.6's friction) and given = .false.
    st = tank_structure_t()
    if (structure%given) st = structure
    circular = tank%shape == SHAPE_CIRCULAR
    us_codes = from_ground .or. spec%kind /= SPECTRUM_EC8
    ec8_code = from_ground .or. spec%kind == SPECTRUM_EC8
    m_t = tank%tank_mass
    h_t = factors%tank_mass_height
    if (h_t == 0) h_t = (tank%liquid_depth + tank%freeboard)/2

    ! API 650 Annex E (an ACI 350.3 spectrum feeds API 650's rows when it has ASCE 7's T_L)
    if (circular .and. us_codes .and. (from_ground .or. spec%kind == SPECTRUM_ASCE7 .or. &
                                        spec%t_l > 0)) then
      call api650_design(tank, props%liquid_mass, m_t, h_t, st, factors, source, report, &
                         loads(:, DESIGN_API650), freeboard(:, DESIGN_API650), status, message)
      if (status /= SD_OK) return
    end if
    ! ACI 350.3-06
    if (us_codes) then
      call aci350_design(tank, props%liquid_mass, m_t, h_t, st, factors, source, report, &
                         loads(:, DESIGN_ACI350), freeboard(:, DESIGN_ACI350), status, message)
      if (status /= SD_OK) return
    end if
    ! EN 1998-4 Annex A
    if (circular .and. ec8_code) then
      call ec8_design(tank, props%liquid_mass, m_t, h_t, st, factors, source, report, &
                      loads(:, DESIGN_EC8), freeboard(:, DESIGN_EC8), status, message)
      if (status /= SD_OK) return
    end if
    call sloshdyn_rows()
    if (status == SD_OK .and. circular) call wall_pressure_basis()
    if (status == SD_OK .and. .not. props%roof_reachable) &
      call report%note('tank', 'the freeboard exceeds what the linear sloshing wave reaches '// &
                       '(2R/(ξ² − 1) at the wall): the linear wave cannot reach the roof; the '// &
                       'model''s θ0 is capped below π/2, and the roof verdicts take the free '// &
                       'wave against the freeboard', 'f', 'f > 2R/(ξ² − 1) = '// &
                       num2str(props%wave_factor, 5)//' m', tank%freeboard, 'm', &
                       'docs/model.md, Derived quantities')
    if (status == SD_OK) call check_finite()

  contains

    !> sloshdyn's linear row (its first mode at its own damping and its rigid mass, elastic,
    !> SRSS; the spectrum's own kind, or the ground motion) and the nonlinear run's peaks.
    subroutine sloshdyn_rows()
      character(len=*), parameter :: src = 'sloshdyn linear', model_doc = 'docs/model.md'
      real(wp) :: a_i, a_c, x
      integer :: kind
      kind = merge(SPECTRUM_ASCE7, spec%kind, from_ground)
      call source_impulsive_sa(source, kind, factors%impulsive_period, &
                               factors%impulsive_damping_ratio, .false., a_i, status, message)
      if (status == SD_OK) call source_sa(source, kind, props%sloshing_period, &
                                          tank%sloshing_damping, a_c, status, message)
      if (status /= SD_OK) return
      call set_loads(DESIGN_LINEAR, props%sloshing_period, a_i, a_c, &
                     props%rigid_mass/props%liquid_mass, props%sloshing_mass/props%liquid_mass, &
                     [props%impulsive_height, props%convective_height, nan, nan], .true.)
      call set_freeboard(DESIGN_LINEAR, props%sloshing_period, a_c, props%wave_factor*a_c, &
                         props%wave_factor*a_c)
      call report%note(src, 'the response-spectrum method on sloshdyn''s model, ELASTIC (no '// &
                       'importance or response modification factor): beside the codes, not '// &
                       'a design value', 'T_1', 'T_1 = 2π √(l/g) (the pendulum of eq 2)', &
                       props%sloshing_period, 's', model_doc)
      x = report%step(src, 'elastic impulsive spectral acceleration', 'Sa_i', &
                      'Sa(T_i, ζ_i) (the plateau where T_i = 0)', '@', [a_i], a_i, 'g', &
                      trim(pick('the ground motion''s spectrum ', 'the spectrum of &design     ', &
                                 from_ground)))
      x = report%step(src, 'elastic convective spectral acceleration at the tank''s sloshing '// &
                      'damping ζ = '//num2str(tank%sloshing_damping), 'Sa_c', 'Sa(T_1, ζ)', '@', &
                      [a_c], a_c, 'g', trim(pick('the ground motion''s spectrum ', &
                                                  'the spectrum of &design     ', from_ground)))
      x = report%step(src, 'base shear (elastic)', 'V', 'V = √((Sa_i g (m_0 + m_t))² + '// &
                      '(Sa_c g m)²)', '√((@ × @ × (@ + @))² + (@ × @ × @)²)', &
                      [a_i, tank%gravity, props%rigid_mass, m_t, a_c, tank%gravity, &
                       props%sloshing_mass], loads(LOADS_BASE_SHEAR, DESIGN_LINEAR), 'N', &
                      model_doc//', Loads')
      x = report%step(src, 'overturning moment (elastic, EBP)', 'M', 'M = √((Sa_i g (m_0 h_0 + '// &
                      'm_t h_t))² + (Sa_c g m h_c)²)', '√((@ × @ × (@ × @ + @ × @))² + (@ × @ '// &
                      '× @ × @)²)', [a_i, tank%gravity, props%rigid_mass, props%impulsive_height, &
                      m_t, h_t, a_c, tank%gravity, props%sloshing_mass, props%convective_height], &
                      loads(LOADS_MOMENT_EBP, DESIGN_LINEAR), 'N m', model_doc//', Loads')
      x = report%step(src, 'linear wave height at the wall (elastic)', 'η', &
                      'η = w Sa_c, w = '//trim(pick('2R/(ξ² − 1)', '4L/π²', circular)), &
                      '@ × @', [props%wave_factor, a_c], &
                      props%wave_factor*a_c, 'm', model_doc)
      call report%info(src, 'base shear V (elastic, not a design value)', model_doc, &
                       loads(LOADS_BASE_SHEAR, DESIGN_LINEAR), 'N')
      call report%check(src, 'linear wave below the roof (elastic)', model_doc, &
                        props%wave_factor*a_c, tank%freeboard, 'm')
      ! the time history's peaks: the tank without contact below its roof, restricted sloshing
      ! above it (sloshdyn_seismic)
      if (present(peaks)) then
        loads([LOADS_CONVECTIVE_PERIOD, LOADS_BASE_SHEAR, LOADS_MOMENT_EBP, LOADS_MOMENT_IBP], &
              DESIGN_NONLINEAR) = [props%sloshing_period, peaks(PEAKS_BASE_SHEAR), &
                                   peaks(PEAKS_OVERTURNING_MOMENT), &
                                   peaks(PEAKS_OVERTURNING_MOMENT_IBP)]
        call set_freeboard(DESIGN_NONLINEAR, props%sloshing_period, nan, peaks(PEAKS_FREE_WAVE), &
                           peaks(PEAKS_FREE_WAVE))
        freeboard(FREEBOARD_SUFFICIENT, DESIGN_NONLINEAR) = 1 - peaks(PEAKS_ROOF_REACHED)
        call report%info('sloshdyn nonlinear', 'peak base shear of the time history', &
                         model_doc//', Loads', peaks(PEAKS_BASE_SHEAR), 'N')
        call report%info('sloshdyn nonlinear', 'peak overturning moment of the time history', &
                         model_doc//', Loads', peaks(PEAKS_OVERTURNING_MOMENT), 'N m')
        call report%info('sloshdyn nonlinear', 'peak overturning moment with the base '// &
                         'pressure', model_doc//', Loads', peaks(PEAKS_OVERTURNING_MOMENT_IBP), &
                         'N m')
        call report%check('sloshdyn nonlinear', 'free wave below the roof', &
                          model_doc//', Roof loads', peaks(PEAKS_FREE_WAVE), tank%freeboard, 'm')
      end if
    end subroutine sloshdyn_rows

    !> The accelerations of the check's wall pressure (wall_pressure.csv), stated with their
    !> source and combination.
    subroutine wall_pressure_basis()
      integer :: row
      character(len=:), allocatable :: source_name, words
      row = wall_pressure_row(loads, factors)
      source_name = trim(code_name('o', row))
      if (row == DESIGN_LINEAR) then
        words = ' ELASTIC accelerations (the spectrum at sloshdyn''s periods, no I or R: not '// &
                'a design value), SRSS'
      else if (row == DESIGN_EC8) then
        words = ' design accelerations (Se(T_imp) with q, Se(T_con) at 0.5 %), absolute sum'
      else if (row == DESIGN_API650) then
        words = ' design accelerations (A_i, A_c with I and R_wi, R_wc), SRSS'
      else
        words = ' design accelerations (C_i I/R_i, C_c I/R_c), SRSS'
      end if
      call report%note(source_name, 'wall_pressure.csv (potential flow, EN 1998-4 A.2.1''s '// &
                       'closed forms): the impulsive acceleration of '//source_name//'''s'// &
                       words, 'a_i', 'a_i (its row of design_loads.csv)', &
                       loads(LOADS_IMPULSIVE_ACCELERATION, row), 'g', 'docs/design.md, Wall pressure')
      call report%note(source_name, 'wall_pressure.csv: the convective acceleration of '// &
                       source_name//'''s'//words, 'a_c', 'a_c (its row of design_loads.csv)', &
                       loads(LOADS_CONVECTIVE_ACCELERATION, row), 'g', &
                       'docs/design.md, Wall pressure')
    end subroutine wall_pressure_basis

    !> A row of 'design_loads' from the design coefficients a_i, a_c [g], the mass ratios
    !> m_i/m, m_c/m and heights [h_i, h_c, h_i', h_c'] [m] (srss, or the absolute sum).
    subroutine set_loads(row, period, a_i, a_c, ratio_i, ratio_c, heights, srss)
      integer, intent(in) :: row
      real(wp), intent(in) :: period, a_i, a_c, ratio_i, ratio_c, heights(4)
      logical, intent(in) :: srss
      associate (m_i => ratio_i*props%liquid_mass, m_c => ratio_c*props%liquid_mass)
        loads(:, row) = [factors%impulsive_period, period, a_i, a_c, m_i, m_c, m_t, heights, &
                         h_t, code_loads(a_i, a_c, m_i, m_c, m_t, heights(1), heights(2), &
                                         heights(3), heights(4), h_t, tank%gravity, srss)]
      end associate
    end subroutine set_loads

    !> A row of 'freeboard_check': required and available freeboard, margin, sufficient 1/0
    !> (a required freeboard equal to the available one within round-off, 1e-9 of it, is
    !> sufficient: e.g. ACI 350.3's d_max = R I Sa/g of a record scaled to that Sa).
    subroutine set_freeboard(row, period, acceleration, wave_height, required)
      integer, intent(in) :: row
      real(wp), intent(in) :: period, acceleration, wave_height, required
      freeboard(:, row) = [period, acceleration, wave_height, required, tank%freeboard, &
                           tank%freeboard - required, &
                           merge(1.0_wp, 0.0_wp, required <= tank%freeboard*(1 + 1.0e-9_wp))]
    end subroutine set_freeboard

    !> Every number of a row that a source gives, and of the report, is finite (a record scaled
    !> by 1e250, or a mass at 1e300 m, must not end in Infinity with success): SD_NON_FINITE
    !> naming the quantity otherwise.
    subroutine check_finite()
      integer :: i, j
      character(len=:), allocatable :: names
      do j = 1, DESIGN_ROWS
        if (loads(LOADS_BASE_SHEAR, j) /= loads(LOADS_BASE_SHEAR, j) .and. &
            freeboard(3, j) /= freeboard(3, j)) cycle
        do i = 1, DESIGN_LOADS_COLUMNS
          if (loads(i, j) == loads(i, j) .and. .not. ieee_is_finite(loads(i, j))) then
            names = table_header('design_loads')
            call fail(trim(code_name('o', j))//' '//column(names, i + 1), loads(i, j))
            return
          end if
        end do
        do i = 1, FREEBOARD_COLUMNS
          if (freeboard(i, j) == freeboard(i, j) .and. .not. ieee_is_finite(freeboard(i, j))) then
            names = table_header('freeboard_check')
            call fail(trim(code_name('o', j))//' '//column(names, i + 1), freeboard(i, j))
            return
          end if
        end do
      end do
      do i = 1, report%n_calc
        if (.not. ieee_is_finite(report%calc(i)%value)) then
          call fail(trim(report%calc(i)%code)//' '//trim(report%calc(i)%symbol)//' ('// &
                    trim(report%calc(i)%quantity)//')', report%calc(i)%value)
          return
        end if
      end do
      do i = 1, report%n_checks
        if (.not. (ieee_is_finite(report%checks(i)%demand) .and. &
                   ieee_is_finite(report%checks(i)%capacity))) then
          call fail(trim(report%checks(i)%code)//' '//trim(report%checks(i)%check), &
                    report%checks(i)%demand)
          return
        end if
      end do
    end subroutine check_finite

    subroutine fail(what, value)
      character(len=*), intent(in) :: what
      real(wp), intent(in) :: value
      status = SD_NON_FINITE
      message = 'the design check gives '//what//' = '//num2str(value)//': the inputs are '// &
                'beyond what the codes'' formulas hold in double precision (check the tank, '// &
                'the ground motion''s scale and &design)'
    end subroutine fail
  end subroutine design_check

  !> The row of 'design_loads' whose accelerations the wall pressure takes: EN 1998-4's where
  !> the source feeds it, else API 650's, else ACI 350.3's (each code's design accelerations);
  !> sloshdyn linear's (elastic) where asked (wall_pressure = 'elastic').
  pure integer function wall_pressure_row(loads, factors) result(row)
    real(wp), intent(in) :: loads(DESIGN_LOADS_COLUMNS, DESIGN_ROWS)
    type(design_factors_t), intent(in) :: factors
    integer :: i
    integer, parameter :: order(3) = [DESIGN_EC8, DESIGN_API650, DESIGN_ACI350]
    row = DESIGN_LINEAR
    if (factors%wall_pressure == WALL_PRESSURE_ELASTIC) return
    do i = 1, size(order)
      if (loads(LOADS_BASE_SHEAR, order(i)) == loads(LOADS_BASE_SHEAR, order(i))) then
        row = order(i)
        return
      end if
    end do
  end function wall_pressure_row

  !> The i-th name of a comma-separated header.
  pure function column(header, i) result(name)
    character(len=*), intent(in) :: header
    integer, intent(in) :: i
    character(len=64) :: name
    integer :: k, start, stop_at
    start = 1
    do k = 1, i - 1
      start = start + index(header(start:), ',')
    end do
    stop_at = index(header(start:), ',')
    if (stop_at == 0) then
      name = header(start:)
    else
      name = header(start:start + stop_at - 2)
    end if
  end function column
end module sloshdyn_design_check
