!> The design check of a tank (issue 25; docs/design.md): each code's seismic loads in its own
!> format ('design_loads') and its freeboard check ('freeboard_check'), from a code design
!> spectrum (sloshdyn_design_spectra) or from a ground motion's pseudo-spectral acceleration at
!> the code's periods and dampings; beside them sloshdyn's own: linear (the response-spectrum
!> method on its model: first sloshing mode and the rigid mass, elastic, SRSS) and, given the
!> peaks of a time-history run (sloshdyn_seismic), nonlinear.
!>
!> Which codes a source feeds: an ASCE 7 (or ACI 350.3) spectrum API 650 (its ASCE 7 form,
!> E.4.6.1) and ACI 350.3 (its sec 9.4 form, from the same S_DS and S_D1); an EN 1998-1
!> spectrum EN 1998-4; a ground motion all three. API 650 and EN 1998-4's Annex A are for
!> circular tanks: their rows are NaN for a rectangular one. A row a source does not feed is NaN.
module sloshdyn_design_check
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, check_real
  use sloshdyn_model, only: model_t
  use sloshdyn_vessel, only: tank_t, tank_properties, tank_model
  use sloshdyn_tank, only: SHAPE_CIRCULAR
  use sloshdyn_ground, only: ground_motion_t, ground_spectrum, peak_ground_acceleration
  use sloshdyn_design_codes, only: aci350_parameters, api650_parameters, ec8_parameters, &
                                   aci350_circular, aci350_rectangular, aci350_wave_height, &
                                   api650_circular, api650_wave_height, ec8_circular, &
                                   ec8_wave_height
  use sloshdyn_design_spectra, only: design_spectrum_t, check_spectrum, spectrum_sa, plateau_sa, &
                                     ec8_design_sa, SPECTRUM_ASCE7, SPECTRUM_ACI350, SPECTRUM_EC8
  use sloshdyn_design_loads, only: design_factors_t, check_factors, code_loads, api650_af, &
                                   api650_required_freeboard
  use sloshdyn_tables, only: DESIGN_ROWS, DESIGN_API650, DESIGN_EC8, DESIGN_ACI350, &
                             DESIGN_LINEAR, DESIGN_NONLINEAR, DESIGN_LOADS_COLUMNS, &
                             FREEBOARD_COLUMNS, PEAKS_SIZE, PEAKS_FREE_WAVE, PEAKS_ROOF_REACHED, &
                             PEAKS_BASE_SHEAR, PEAKS_OVERTURNING_MOMENT, &
                             PEAKS_OVERTURNING_MOMENT_IBP, &
                             LOADS_CONVECTIVE_PERIOD, LOADS_BASE_SHEAR, LOADS_MOMENT_EBP, &
                             LOADS_MOMENT_IBP, &
                            FREEBOARD_SUFFICIENT
  implicit none
  private
  public :: design_check

  !> The codes' convective damping [%] (API 650 E.4.6.1, ACI 350.3 9.4.2, EN 1998-4 A.3.2).
  real(wp), parameter :: code_convective_damping = 0.5_wp
  !> ASCE 7-16 21.4: S_DS of a site-specific spectrum is 90 % of its largest Sa (5 %) between
  !> 0.2 and 5 s; sampled at this many log-spaced periods (for API 650's Table E-7 with a
  !> record).
  integer, parameter :: sds_periods = 100

contains

  !> The design check of the tank: loads(DESIGN_LOADS_COLUMNS, DESIGN_ROWS) and
  !> freeboard(FREEBOARD_COLUMNS, DESIGN_ROWS) in the 'design_loads' and 'freeboard_check'
  !> layouts (without their source column; NaN rows where a source gives none). from_ground:
  !> the accelerations from the ground motion's spectrum (spec then supplies only K and q),
  !> else from spec. peaks: the 'seismic_peaks' of a nonlinear run of the same tank and motion
  !> (the row 'sloshdyn nonlinear').
  subroutine design_check(tank, spec, factors, from_ground, ground, loads, freeboard, status, &
                          message, peaks)
    type(tank_t), intent(in) :: tank
    type(design_spectrum_t), intent(in) :: spec
    type(design_factors_t), intent(in) :: factors
    logical, intent(in) :: from_ground
    type(ground_motion_t), intent(in) :: ground
    real(wp), intent(out) :: loads(DESIGN_LOADS_COLUMNS, DESIGN_ROWS), &
                             freeboard(FREEBOARD_COLUMNS, DESIGN_ROWS)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), intent(in), optional :: peaks(PEAKS_SIZE)
    type(model_t) :: model
    type(tank_properties) :: props
    type(api650_parameters) :: api
    type(ec8_parameters) :: ec8
    type(aci350_parameters) :: aci
    type(design_spectrum_t) :: asce7, aci350
    real(wp) :: nan, h_t, m_t, sa_i, sa_c, a_i, a_c, wave, s_ds
    logical :: circular, us_codes, ec8_code

    nan = ieee_value(1.0_wp, ieee_quiet_nan)
    loads = nan
    freeboard = nan
    call check_factors(factors, status, message)
    if (from_ground) then
      call check_real('q', spec%q, 1.0_wp, 8.0_wp, .false., .false., 'q must be in [1, 8] '// &
                      '(EN 1998-1 3.2.2.5; EN 1998-4 2.3.3.3)', status, message)
    else if (status == SD_OK) then
      call check_spectrum(spec, status, message)
    end if
    if (status == SD_OK) call tank_model(tank, model, props, status, message)
    if (status /= SD_OK) return
    circular = tank%shape == SHAPE_CIRCULAR
    us_codes = from_ground .or. spec%kind /= SPECTRUM_EC8
    ec8_code = from_ground .or. spec%kind == SPECTRUM_EC8
    asce7 = spec
    asce7%kind = SPECTRUM_ASCE7
    aci350 = spec
    aci350%kind = SPECTRUM_ACI350
    m_t = tank%tank_mass
    h_t = factors%tank_mass_height
    if (h_t == 0) h_t = (tank%liquid_depth + tank%freeboard)/2

    ! API 650 Annex E: A_i = Sa_i I/R_wi (E.4.6.1-1), A_c = K Sa(T_c) I/R_wc <= A_i (E.4.6.1-4/-5)
    ! (an ACI 350.3 spectrum feeds API 650's rows when it has ASCE 7's T_L)
    if (circular .and. us_codes .and. (from_ground .or. spec%kind == SPECTRUM_ASCE7 .or. &
                                        spec%t_l > 0)) then
      call api650_circular(tank%radius, tank%liquid_depth, api, status, message)
      if (status == SD_OK) call impulsive_sa(asce7, .false., sa_i)
      if (status == SD_OK) call sa(asce7, api%convective_period, code_convective_damping, sa_c)
      if (status /= SD_OK) return
      a_i = sa_i*factors%importance/factors%r_wi
      a_c = min(sa_c*factors%importance/factors%r_wc, a_i)
      call set_loads(DESIGN_API650, api%convective_period, a_i, a_c, api%impulsive_ratio, &
                     api%convective_ratio, [api%impulsive_height, api%convective_height, &
                     api%impulsive_height_slab, api%convective_height_slab], .true.)
      ! E.7.2: A_f by seismic use group (eq E.7.2-2 to -5; a record: its 0.5 % spectrum, I)
      if (from_ground) then
        a_c = sa_c*factors%importance
        call record_sds(s_ds)
      else
        a_c = api650_af(spec%s_d1, spec%t_l, spec%k, factors%importance, factors%use_group, &
                        api%convective_period)
        s_ds = spec%s_ds
      end if
      if (status == SD_OK) call api650_wave_height(tank%radius, a_c, wave, status, message)
      if (status /= SD_OK) return
      call set_freeboard(DESIGN_API650, api%convective_period, a_c, wave, &
                         api650_required_freeboard(wave, s_ds, factors%use_group))
    end if

    ! ACI 350.3-06: P_i = C_i I W_i/R_i, P_c = C_c I W_c/R_c (eq 4-3, 4-4); d_max (eq 7-1/7-2)
    if (us_codes) then
      if (circular) then
        call aci350_circular(tank%radius, tank%liquid_depth, tank%gravity, aci, status, message)
      else
        call aci350_rectangular(tank%length, tank%liquid_depth, tank%gravity, aci, status, &
                                message)
      end if
      if (status == SD_OK) call impulsive_sa(aci350, .false., sa_i)
      if (status == SD_OK) call sa(aci350, aci%convective_period, code_convective_damping, sa_c)
      if (status /= SD_OK) return
      a_i = sa_i*factors%importance/factors%r_i
      a_c = sa_c*factors%importance/factors%r_c
      call set_loads(DESIGN_ACI350, aci%convective_period, a_i, a_c, aci%impulsive_ratio, &
                     aci%convective_ratio, [aci%impulsive_height, aci%convective_height, &
                     aci%impulsive_height_ibp, aci%convective_height_ibp], .true.)
      call aci350_wave_height(merge(tank%radius, tank%length/2, circular), sa_c*tank%gravity, &
                              tank%gravity, factors%importance, wave, status, message)
      if (status /= SD_OK) return
      call set_freeboard(DESIGN_ACI350, aci%convective_period, sa_c*factors%importance, wave, &
                         wave)
    end if

    ! EN 1998-4 Annex A: impulsive from the design spectrum with q (EN 1998-1 3.2.2.5),
    ! convective elastic at 0.5 %; absolute sum (A.3.2.2); d_max = 0.84 R Se(T_c1)/g
    if (circular .and. ec8_code) then
      call ec8_circular(tank%radius, tank%liquid_depth, tank%gravity, ec8, status, message)
      if (status == SD_OK) call impulsive_sa(spec, .true., a_i)
      if (status == SD_OK) call sa(spec, ec8%convective_period, code_convective_damping, a_c)
      if (status /= SD_OK) return
      call set_loads(DESIGN_EC8, ec8%convective_period, a_i, a_c, ec8%impulsive_ratio, &
                     ec8%convective_ratio, [ec8%impulsive_height, ec8%convective_height, &
                     ec8%impulsive_height_ibp, ec8%convective_height_ibp], .false.)
      call ec8_wave_height(tank%radius, a_c*tank%gravity, tank%gravity, wave, status, message)
      if (status /= SD_OK) return
      call set_freeboard(DESIGN_EC8, ec8%convective_period, a_c, wave, wave)
    end if

    ! sloshdyn, linear: its first mode at its own damping and its rigid mass, elastic, SRSS
    call impulsive_sa(spec, .false., a_i)
    if (status == SD_OK) call sa(spec, props%sloshing_period, 100*tank%sloshing_damping, a_c)
    if (status /= SD_OK) return
    call set_loads(DESIGN_LINEAR, props%sloshing_period, a_i, a_c, &
                   props%rigid_mass/props%liquid_mass, props%sloshing_mass/props%liquid_mass, &
                   [props%impulsive_height, props%convective_height, nan, nan], .true.)
    call set_freeboard(DESIGN_LINEAR, props%sloshing_period, a_c, props%wave_factor*a_c, &
                       props%wave_factor*a_c)

    ! sloshdyn, nonlinear: the time history's peaks (the tank without contact below its roof,
    ! restricted sloshing above it) and the free wave's roof verdict
    if (present(peaks)) then
      loads([LOADS_CONVECTIVE_PERIOD, LOADS_BASE_SHEAR, LOADS_MOMENT_EBP, LOADS_MOMENT_IBP], &
            DESIGN_NONLINEAR) = [props%sloshing_period, peaks(PEAKS_BASE_SHEAR), &
                                 peaks(PEAKS_OVERTURNING_MOMENT), &
                                 peaks(PEAKS_OVERTURNING_MOMENT_IBP)]
      call set_freeboard(DESIGN_NONLINEAR, props%sloshing_period, nan, peaks(PEAKS_FREE_WAVE), &
                         peaks(PEAKS_FREE_WAVE))
      freeboard(FREEBOARD_SUFFICIENT, DESIGN_NONLINEAR) = 1 - peaks(PEAKS_ROOF_REACHED)
    end if

  contains

    !> The elastic (EC8 with design: the design, with q) spectral acceleration [g] of the
    !> impulsive mode: at factors%impulsive_period, or where it is 0 on the spectrum's plateau
    !> (a ground motion: the rigid tank, its peak acceleration).
    subroutine impulsive_sa(source, design, value)
      type(design_spectrum_t), intent(in) :: source
      logical, intent(in) :: design
      real(wp), intent(out) :: value
      if (from_ground .and. factors%impulsive_period == 0) then
        value = peak_ground_acceleration(ground)/tank%gravity
      else if (from_ground) then
        call sa(source, factors%impulsive_period, factors%impulsive_damping, value)
      else if (factors%impulsive_period == 0) then
        call plateau_sa(source, factors%impulsive_damping, design, value, status, message)
      else if (design) then
        call ec8_design_sa(source, factors%impulsive_period, value, status, message)
      else
        call sa(source, factors%impulsive_period, factors%impulsive_damping, value)
      end if
      if (from_ground .and. design) value = value/source%q
    end subroutine impulsive_sa

    !> The spectral acceleration [g] at period [s] and damping [%]: the ground motion's
    !> pseudo-spectral acceleration, or the code spectrum's.
    subroutine sa(source, period, damping, value)
      type(design_spectrum_t), intent(in) :: source
      real(wp), intent(in) :: period, damping
      real(wp), intent(out) :: value
      real(wp) :: sd(1), sv(1), psa(1)
      if (from_ground) then
        call ground_spectrum(ground, [period], damping/100, 5*period, 0.0_wp, sd, sv, psa, &
                             status, message)
        value = psa(1)/tank%gravity
        if (status /= SD_OK) message = 'the ground motion''s spectrum for the design check: '// &
                                       trim(message)
      else
        call spectrum_sa(source, period, damping, value, status, message)
        if (status /= SD_OK) message = 'the design spectrum for the design check: '//trim(message)
      end if
    end subroutine sa

    !> ASCE 7-16 21.4: S_DS [g] of the ground motion's spectrum, 90 % of its largest Sa (5 %)
    !> between 0.2 and 5 s.
    subroutine record_sds(value)
      real(wp), intent(out) :: value
      real(wp), dimension(sds_periods) :: periods, sd, sv, psa
      integer :: i
      periods = [(0.2_wp*25.0_wp**(real(i - 1, wp)/(sds_periods - 1)), i = 1, sds_periods)]
      call ground_spectrum(ground, periods, 0.05_wp, 5*periods(sds_periods), 0.0_wp, sd, sv, psa, &
                           status, message)
      value = 0.9_wp*maxval(psa)/tank%gravity
    end subroutine record_sds

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
  end subroutine design_check
end module sloshdyn_design_check
