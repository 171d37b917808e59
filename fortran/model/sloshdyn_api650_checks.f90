!> API 650 13th ed. Annex E for a circular steel tank (docs/design.md, "API 650"): the
!> convective period, masses and heights (E.4.5.2, E.6.1.1, E.6.1.2), the impulsive period from
!> the shell (E.4.5.1), the design accelerations A_i with its minimum, A_c and A_v (E.4.6.1,
!> E.6.1.3), the freeboard (E.7.2, Table E-7) and, where the sloshing wave delta_s exceeds the
!> freeboard, the roof's loads and the confined mass by the restricted-sloshing method (ASCE 7-16
!> 15.7.6.1.2 as this project reads it; docs/model.md, "Roof loads"), the base shear and
!> overturning moments with W_s, W_r, W_f each at its own height (E.6.1, E.6.1.5), and, with
!> the tank's structure, the hoop forces and stress of each course (E.6.1.4), the anchorage
!> ratio J and its verdict or the anchors' load (E.6.2.1), the shell compression against F_c
!> (E.6.2.2) and the sliding resistance (E.7.6). Every formula is recorded with its clause in
!> the design report (sloshdyn_design_report) where it is computed.
!>
!> Units as the code's SI edition: weights W [N], moments [N m], lengths [m], thicknesses
!> [mm], stresses [MPa], membrane forces N [N/mm], loads per unit of circumference w [N/m],
!> accelerations in g. The clause numbers are those design guides cite (the paid text was not
!> at hand; docs/design.md lists what could not be verified).
module sloshdyn_api650_checks
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK
  use sloshdyn_text, only: num2str
  use sloshdyn_vessel, only: tank_t
  use sloshdyn_design_codes, only: api650_parameters, api650_circular, ec8_table_a2, &
                                   table_a2_range
  use sloshdyn_design_spectra, only: SPECTRUM_ASCE7, IMPULSIVE_RATIO, CONVECTIVE_RATIO
  use sloshdyn_design_source, only: design_source_t, source_sa, source_impulsive_sa, record_sds
  use sloshdyn_design_loads, only: design_factors_t, api650_af, api650_required_freeboard
  use sloshdyn_design_report, only: design_report_t, pick
  use sloshdyn_tank_structure, only: tank_structure_t, shell_t, shell_of, ANCHORAGE_MECHANICAL
  use sloshdyn_restricted_sloshing, only: restricted_sloshing
  use sloshdyn_tables, only: DESIGN_LOADS_COLUMNS, FREEBOARD_COLUMNS
  implicit none
  private
  public :: api650_design

  character(len=*), parameter :: code = 'API 650', ed = 'API 650 13th ed. '
  !> E.4.6.1-2: the smallest impulsive acceleration coefficient [g].
  real(wp), parameter :: min_impulsive = 0.007_wp
  !> Table E-6: J up to which the tank does not uplift, and up to which it is stable.
  real(wp), parameter :: no_uplift = 0.785_wp, stable = 1.54_wp

contains

  !> API 650 Annex E for the tank (liquid mass m_L [kg]), its structure (st%given) or its lumped
  !> mass m_t at h_t, the codes' factors and the source of the accelerations: the report's steps
  !> and checks, and the rows of 'design_loads' and 'freeboard_check' (without the source).
  subroutine api650_design(tank, liquid_mass, m_t, h_t, st, factors, source, report, loads, &
                           freeboard, status, message)
    type(tank_t), intent(in) :: tank
    real(wp), intent(in) :: liquid_mass, m_t, h_t
    type(tank_structure_t), intent(in) :: st
    type(design_factors_t), intent(in) :: factors
    type(design_source_t), intent(in) :: source
    type(design_report_t), intent(inout) :: report
    real(wp), intent(out) :: loads(DESIGN_LOADS_COLUMNS), freeboard(FREEBOARD_COLUMNS)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(api650_parameters) :: api
    type(shell_t) :: shell
    real(wp) :: D, H, G, g_n, W_p, W_i, W_c, W_s, W_r, W_f, X_s, X_r, r_wi, s_ds, sa_i, a_i, &
                a_c, a_v, a_f, delta_s, required, W_conf, confined, V_i, V_c, V, &
                M_rw, M_s, ratio
    logical :: squat

    report%code = code           ! the steps of report%add and report%put are this code's
    loads = 0
    freeboard = 0
    call api650_circular(tank%radius, tank%liquid_depth, api, status, message)
    if (status /= SD_OK) return
    g_n = tank%gravity
    H = tank%liquid_depth
    D = report%add('tank diameter', 'D', 'D = 2 R', '2 × @', [tank%radius], 2*tank%radius, 'm', &
            ed//'E.2.2 (D)')
    call report%note(code, 'design liquid height', 'H', 'H (&tank liquid_depth)', H, 'm', &
                     ed//'E.2.2 (H)')
    G = report%add('design specific gravity', 'G', 'G = ρ/(1000 kg/m³), ρ = m_L/(π D²/4 H)', &
            '@/(1000 × π × @²/4 × @)', [liquid_mass, D, H], liquid_mass/(1000*pi*D**2/4*H), '', &
            ed//'E.2.2 (G)')
    W_p = report%add('total weight of the contents', 'W_p', 'W_p = m_L g', '@ × @', [liquid_mass, g_n], &
              liquid_mass*g_n, 'N', ed//'E.2.2 (W_p)')
    ratio = D/H
    squat = ratio >= 1.333_wp

    ! --- convective period, masses and heights (E.4.5.2, E.6.1.1, E.6.1.2)
    call report%put('sloshing period coefficient', 'K_s', 'K_s = 0.578/√(tanh(3.68 H/D))', &
                   '0.578/√(tanh(3.68 × @/@))', [H, D], api%ks, '', ed//'E.4.5.2-c')
    call report%put('convective (sloshing) period', 'T_c', 'T_c = 1.8 K_s √D', '1.8 × @ × √@', &
                   [api%ks, D], api%convective_period, 's', ed//'E.4.5.2-a')
    if (squat) then
      W_i = report%add('effective impulsive weight (D/H ≥ 1.333)', 'W_i', &
                'W_i = tanh(0.866 D/H)/(0.866 D/H) W_p', 'tanh(0.866 × @/@)/(0.866 × @/@) × @', &
                [D, H, D, H, W_p], api%impulsive_ratio*W_p, 'N', ed//'E.6.1.1-1')
      call report%put('impulsive height, ringwall moment (D/H ≥ 1.333)', 'X_i', 'X_i = 0.375 H', &
                     '0.375 × @', [H], api%impulsive_height, 'm', ed//'E.6.1.2.1-1')
      call report%put('impulsive height, slab moment (D/H ≥ 1.333)', 'X_is', &
                     'X_is = 0.375 [1.0 + 1.333 ((0.866 D/H)/tanh(0.866 D/H) − 1.0)] H', &
                     '0.375 × (1 + 1.333 × ((0.866 × @/@)/tanh(0.866 × @/@) − 1)) × @', &
                     [D, H, D, H, H], api%impulsive_height_slab, 'm', ed//'E.6.1.2.2-1')
    else
      W_i = report%add('effective impulsive weight (D/H < 1.333)', 'W_i', &
                'W_i = (1.0 − 0.218 D/H) W_p', '(1 − 0.218 × @/@) × @', [D, H, W_p], &
                api%impulsive_ratio*W_p, 'N', ed//'E.6.1.1-2')
      call report%put('impulsive height, ringwall moment (D/H < 1.333)', 'X_i', &
                     'X_i = (0.5 − 0.094 D/H) H', '(0.5 − 0.094 × @/@) × @', [D, H, H], &
                     api%impulsive_height, 'm', ed//'E.6.1.2.1-2')
      call report%put('impulsive height, slab moment (D/H < 1.333)', 'X_is', &
                     'X_is = (0.500 + 0.060 D/H) H', '(0.5 + 0.06 × @/@) × @', [D, H, H], &
                     api%impulsive_height_slab, 'm', ed//'E.6.1.2.2-2')
    end if
    W_c = report%add('effective convective weight', 'W_c', 'W_c = 0.230 (D/H) tanh(3.67 H/D) W_p', &
              '0.23 × @/@ × tanh(3.67 × @/@) × @', [D, H, H, D, W_p], api%convective_ratio*W_p, &
              'N', ed//'E.6.1.1-3')
    call report%put('convective height, ringwall moment', 'X_c', &
                   'X_c = [1.0 − (cosh(3.67 H/D) − 1)/((3.67 H/D) sinh(3.67 H/D))] H', &
                   '(1 − (cosh(3.67 × @/@) − 1)/(3.67 × @/@ × sinh(3.67 × @/@))) × @', &
                   [H, D, H, D, H, D, H], api%convective_height, 'm', ed//'E.6.1.2.1-3')
    call report%put('convective height, slab moment', 'X_cs', &
                   'X_cs = [1.0 − (cosh(3.67 H/D) − 1.937)/((3.67 H/D) sinh(3.67 H/D))] H', &
                   '(1 − (cosh(3.67 × @/@) − 1.937)/(3.67 × @/@ × sinh(3.67 × @/@))) × @', &
                   [H, D, H, D, H, D, H], api%convective_height_slab, 'm', ed//'E.6.1.2.2-3')

    ! --- the structure's weights and heights, or the lumped mass
    if (st%given) then
      shell = shell_of(tank, st)
      W_s = report%add('shell weight', 'W_s', 'W_s = g Σ ρ_s π t_j (D + t_j) h_j (the courses)', &
                '@ × @', [g_n, shell%shell_mass], g_n*shell%shell_mass, 'N', ed//'E.2.2 (W_s)')
      X_s = report%add('height of the shell''s centre of gravity', 'X_s', &
                'X_s = Σ m_j (z_j + h_j/2)/Σ m_j', '@', [shell%shell_height], shell%shell_height, &
                'm', ed//'E.2.2 (X_s)')
      W_r = report%add('roof weight', 'W_r', 'W_r = m_r g', '@ × @', [st%roof_mass, g_n], &
                st%roof_mass*g_n, 'N', ed//'E.2.2 (W_r)')
      X_r = report%add('height of the roof''s centre of gravity', 'X_r', &
                'X_r (&tank_structure roof_mass_height; 0: the shell''s top)', '@', &
                [shell%roof_height], shell%roof_height, 'm', ed//'E.2.2 (X_r)')
      W_f = report%add('bottom weight', 'W_f', 'W_f = ρ_s π D²/4 t_b g', '@ × π × @²/4 × @/1000 × @', &
                [shell%density, D, st%bottom_thickness, g_n], shell%bottom_mass*g_n, 'N', &
                ed//'E.2.2 (W_f)')
      call impulsive_period()
    else
      W_s = report%add('shell and roof weight, lumped (no &tank_structure)', 'W_s + W_r', &
                'W_s + W_r = m_t g', '@ × @', [m_t, g_n], m_t*g_n, 'N', ed//'E.6.1 (W_s, W_r)')
      X_s = report%add('height of the lumped shell and roof', 'X_s', 'X_s = h_t', '@', [h_t], h_t, &
                'm', ed//'E.6.1.5 (X_s, X_r)')
      W_r = 0
      X_r = 0
      W_f = 0
      call report%note(code, 'bottom weight (no &tank_structure)', 'W_f', &
                       'not given: W_f = 0 (&tank_structure bottom_thickness gives it)', 0.0_wp, &
                       'N', ed//'E.6.1-2')
    end if

    ! --- design accelerations (E.4.6.1, E.6.1.3)
    call design_accelerations()
    if (status /= SD_OK) return

    ! --- freeboard (E.7.2, Table E-7) and the roof where the wave reaches it
    call sloshing_wave()
    if (status /= SD_OK) return

    ! --- base shear and overturning moments (E.6.1, E.6.1.5), the confined weight impulsive
    V_i = report%add('impulsive base shear', 'V_i', 'V_i = A_i (W_s + W_r + W_f + W_i + W_conf)', &
              '@ × (@ + @ + @ + @ + @)', [a_i, W_s, W_r, W_f, W_i, W_conf], &
              a_i*(W_s + W_r + W_f + W_i + W_conf), 'N', ed//'E.6.1-2')
    V_c = report%add('convective base shear', 'V_c', 'V_c = A_c (W_c − W_conf)', '@ × (@ − @)', &
              [a_c, W_c, W_conf], a_c*(W_c - W_conf), 'N', ed//'E.6.1-3')
    V = report%add('design base shear', 'V', 'V = √(V_i² + V_c²)', '√(@² + @²)', [V_i, V_c], &
            sqrt(V_i**2 + V_c**2), 'N', ed//'E.6.1-1')
    M_rw = report%add('ringwall moment', 'M_rw', 'M_rw = √([A_i (W_i X_i + W_conf X_c + W_s X_s + '// &
               'W_r X_r)]² + [A_c (W_c − W_conf) X_c]²)', &
               '√((@ × (@ × @ + @ × @ + @ × @ + @ × @))² + (@ × (@ − @) × @)²)', &
               [a_i, W_i, api%impulsive_height, W_conf, api%convective_height, W_s, X_s, W_r, &
                X_r, a_c, W_c, W_conf, api%convective_height], &
               sqrt((a_i*(W_i*api%impulsive_height + W_conf*api%convective_height + W_s*X_s + &
                          W_r*X_r))**2 + (a_c*(W_c - W_conf)*api%convective_height)**2), 'N m', &
               ed//'E.6.1.5-1')
    M_s = report%add('slab moment', 'M_s', 'M_s = √([A_i (W_i X_is + W_conf X_cs + W_s X_s + '// &
              'W_r X_r)]² + [A_c (W_c − W_conf) X_cs]²)', &
              '√((@ × (@ × @ + @ × @ + @ × @ + @ × @))² + (@ × (@ − @) × @)²)', &
              [a_i, W_i, api%impulsive_height_slab, W_conf, api%convective_height_slab, W_s, &
               X_s, W_r, X_r, a_c, W_c, W_conf, api%convective_height_slab], &
              sqrt((a_i*(W_i*api%impulsive_height_slab + W_conf*api%convective_height_slab + &
                         W_s*X_s + W_r*X_r))**2 + &
                   (a_c*(W_c - W_conf)*api%convective_height_slab)**2), 'N m', ed//'E.6.1.5-2')
    call report%info(code, 'design base shear V', ed//'E.6.1-1', V, 'N')
    call report%info(code, 'ringwall moment M_rw', ed//'E.6.1.5-1', M_rw, 'N m')
    call report%info(code, 'slab moment M_s', ed//'E.6.1.5-2', M_s, 'N m')
    call fill_loads_row()

    ! --- the structure's checks (E.6.1.4, E.6.2.1, E.6.2.2) and sliding (E.7.6)
    if (st%given) then
      call hoop_stresses()
      call anchorage_and_compression()
    end if
    call sliding()

  contains

    !> E.4.5.1: T_i from the shell, with C_i of Figure E-1 read as EN 1998-4 Table A.2's C_i
    !> at H/R = 2 H/D (the same coefficient: Malhotra's) and t_u the courses' thickness
    !> averaged over the wetted height. The design methods of Annex E do not depend on it
    !> (A_i from S_DS): it is reported (INFO).
    subroutine impulsive_period()
      real(wp) :: c_i, t_u, t_i, row(8)
      row = ec8_table_a2(2*H/D)
      c_i = report%add('impulsive period coefficient (Figure E-1, as EN 1998-4 Table A.2''s C_i at '// &
                'H/R = 2 H/D'//trim(pick(', the table''s end row', repeat(' ', 22), &
                2*H/D < table_a2_range(1) .or. 2*H/D > table_a2_range(2)))//')', 'C_i', &
                'C_i(H/D), linear between the table''s rows', '@', [row(1)], row(1), '', &
                ed//'Figure E-1')
      t_u = report%add('equivalent uniform thickness of the shell', 't_u', &
                't_u = Σ t_j (wetted height of course j)/H', '@', [shell%uniform_thickness], &
                shell%uniform_thickness, 'mm', ed//'E.4.5.1 (t_u)')
      t_i = report%add('impulsive natural period', 'T_i', 'T_i = (1/√2000) (C_i H/√(t_u/D)) (√ρ/√E)', &
                '(1/√2000) × (@ × @/√(@/@)) × (√@/√@)', [c_i, H, t_u, D, 1000*G, shell%modulus], &
                1/sqrt(2000.0_wp)*(c_i*H/sqrt(t_u/D))*(sqrt(1000*G)/sqrt(shell%modulus)), 's', &
                ed//'E.4.5.1-1')
      call report%info(code, 'impulsive period T_i (the design does not use it)', &
                       ed//'E.4.5.1-1', t_i, 's')
    end subroutine impulsive_period

    !> A_i (E.4.6.1-1, with its minimum E.4.6.1-2), A_c (E.4.6.1-4/-5, at most A_i) and A_v
    !> (E.6.1.3); from a ground motion its 5 % (impulsive, the rigid tank: PGA) and 0.5 %
    !> (convective) spectra in place of the ASCE 7 spectrum.
    subroutine design_accelerations()
      real(wp) :: sa_c, a_i0
      r_wi = factors%r_wi
      if (r_wi == 0) r_wi = merge(4.0_wp, 3.5_wp, st%given .and. st%anchorage == &
                                  ANCHORAGE_MECHANICAL)
      call report%note(code, 'importance factor (seismic use group '// &
                       trim(pick('I  ', 'II ', factors%use_group == 1))// &
                       trim(pick('I', ' ', factors%use_group == 3))//')', 'I', &
                       'I (&design importance, at least Table E-5''s for the SUG)', &
                       factors%importance, '', ed//'Table E-5')
      call report%note(code, 'impulsive response modification factor ('// &
                       trim(pick('mechanically anchored', 'self-anchored        ', &
                                  st%given .and. st%anchorage == ANCHORAGE_MECHANICAL))//')', &
                       'R_wi', 'R_wi (&design r_wi; 0: by the anchorage)', r_wi, '', &
                       ed//'Table E-4')
      call report%note(code, 'convective response modification factor', 'R_wc', &
                       'R_wc (&design r_wc)', factors%r_wc, '', ed//'Table E-4')
      call source_impulsive_sa(source, SPECTRUM_ASCE7, factors%impulsive_period, &
                               factors%impulsive_damping_ratio, .false., sa_i, status, message)
      if (status /= SD_OK) return
      call record_sds(source, s_ds, status, message)
      if (status /= SD_OK) return
      if (source%from_ground .and. factors%impulsive_period == 0) then
        a_i0 = report%add('impulsive spectral acceleration coefficient (the ground motion''s peak: '// &
                   'the rigid tank)', 'A_i', 'A_i = PGA/g (I/R_wi)', '@ × (@/@)', &
                   [sa_i, factors%importance, r_wi], sa_i*factors%importance/r_wi, 'g', &
                   ed//'E.4.6.1-1')
      else if (source%from_ground .or. factors%impulsive_period > 0) then
        a_i0 = report%add('impulsive spectral acceleration coefficient at T_i = '// &
                   num2str(factors%impulsive_period)//' s', 'A_i', 'A_i = Sa(T_i, 5 %) (I/R_wi)', &
                   '@ × (@/@)', [sa_i, factors%importance, r_wi], &
                   sa_i*factors%importance/r_wi, 'g', ed//'E.4.6.1-1')
      else
        a_i0 = report%add('impulsive spectral acceleration coefficient', 'A_i', 'A_i = S_DS (I/R_wi)', &
                   '@ × (@/@)', [sa_i, factors%importance, r_wi], sa_i*factors%importance/r_wi, &
                   'g', ed//'E.4.6.1-1')
      end if
      a_i = report%add('impulsive coefficient with its minimum', 'A_i', 'A_i ≥ 0.007', 'max(@, 0.007)', &
                [a_i0], max(a_i0, min_impulsive), 'g', ed//'E.4.6.1-2')
      if (source%from_ground) then
        call source_sa(source, SPECTRUM_ASCE7, api%convective_period, CONVECTIVE_RATIO, sa_c, &
                       status, message)
        if (status /= SD_OK) return
        a_c = report%add('convective spectral acceleration coefficient (the ground motion''s 0.5 % '// &
                  'spectrum)', 'A_c', 'A_c = Sa(T_c, 0.5 %) (I/R_wc) ≤ A_i', 'min(@ × (@/@), @)', &
                  [sa_c, factors%importance, factors%r_wc, a_i], &
                  min(sa_c*factors%importance/factors%r_wc, a_i), 'g', ed//'E.4.6.1-4')
      else if (api%convective_period <= source%spec%t_l) then
        a_c = report%add('convective spectral acceleration coefficient (T_c ≤ T_L)', 'A_c', &
                  'A_c = K S_D1 (1/T_c) (I/R_wc) ≤ A_i', 'min(@ × @ × (1/@) × (@/@), @)', &
                  [source%spec%k, source%spec%s_d1, api%convective_period, factors%importance, &
                   factors%r_wc, a_i], min(source%spec%k*source%spec%s_d1/api%convective_period* &
                                           factors%importance/factors%r_wc, a_i), 'g', &
                  ed//'E.4.6.1-4')
      else
        a_c = report%add('convective spectral acceleration coefficient (T_c > T_L)', 'A_c', &
                  'A_c = K S_D1 (T_L/T_c²) (I/R_wc) ≤ A_i', 'min(@ × @ × (@/@²) × (@/@), @)', &
                  [source%spec%k, source%spec%s_d1, source%spec%t_l, api%convective_period, &
                   factors%importance, factors%r_wc, a_i], &
                  min(source%spec%k*source%spec%s_d1*source%spec%t_l/api%convective_period**2* &
                      factors%importance/factors%r_wc, a_i), 'g', ed//'E.4.6.1-5')
      end if
      if (.not. factors%vertical) then
        a_v = report%add('vertical acceleration coefficient (&design vertical = .false.)', 'A_v', &
                  'A_v = 0 (not specified)', '0', [real(wp) ::], 0.0_wp, 'g', ed//'E.6.1.3')
      else if (factors%vertical_acceleration > 0) then
        a_v = report%add('vertical acceleration coefficient (the purchaser''s)', 'A_v', &
                  'A_v (&design vertical_acceleration)', '@', [factors%vertical_acceleration], &
                  factors%vertical_acceleration, 'g', ed//'E.6.1.3')
      else
        a_v = report%add('vertical acceleration coefficient'//trim(merge( &
                  ' (S_DS of the ground motion: ASCE 7-16 21.4)', repeat(' ', 44), &
                  source%from_ground)), 'A_v', 'A_v = 0.14 S_DS', '0.14 × @', [s_ds], &
                  0.14_wp*s_ds, 'g', ed//'E.6.1.3')
      end if
    end subroutine design_accelerations

    !> E.7.2: A_f by seismic use group, delta_s = 0.42 D A_f and Table E-7's required
    !> freeboard; where delta_s exceeds the freeboard, the roof's head, uplift and the confined
    !> weight (sloshdyn_roof; moved from convective to impulsive).
    subroutine sloshing_wave()
      real(wp) :: sa_c, t_limit
      character(len=16) :: branch
      if (source%from_ground) then
        call source_sa(source, SPECTRUM_ASCE7, api%convective_period, CONVECTIVE_RATIO, sa_c, &
                       status, message)
        if (status /= SD_OK) return
        a_f = report%add('sloshing wave acceleration coefficient (the ground motion''s 0.5 % '// &
                  'spectrum)', 'A_f', 'A_f = Sa(T_c, 0.5 %) I', '@ × @', &
                  [sa_c, factors%importance], sa_c*factors%importance, 'g', ed//'E.7.2')
      else
        t_limit = merge(source%spec%t_l, 4.0_wp, factors%use_group >= 3)
        if (factors%use_group >= 3) then
          branch = pick('E.7.2-4', 'E.7.2-5', api%convective_period <= t_limit)
        else
          branch = pick('E.7.2-2', 'E.7.2-3', api%convective_period <= t_limit)
        end if
        if (api%convective_period <= t_limit) then
          a_f = report%add('sloshing wave acceleration coefficient (T_c ≤ '// &
                    trim(pick('T_L', '4 s', factors%use_group >= 3))//')', 'A_f', &
                    'A_f = K S_D1 I (1/T_c)', '@ × @ × @ × (1/@)', [source%spec%k, &
                    source%spec%s_d1, factors%importance, api%convective_period], &
                    api650_af(source%spec%s_d1, source%spec%t_l, source%spec%k, &
                              factors%importance, factors%use_group, api%convective_period), &
                    'g', ed//trim(branch))
        else
          a_f = report%add('sloshing wave acceleration coefficient (T_c > '// &
                    trim(pick('T_L', '4 s', factors%use_group >= 3))//')', 'A_f', &
                    'A_f = K S_D1 I ('//trim(pick('T_L', '4  ', factors%use_group >= 3))// &
                    '/T_c²)', '@ × @ × @ × (@/@²)', [source%spec%k, source%spec%s_d1, &
                    factors%importance, t_limit, api%convective_period], &
                    api650_af(source%spec%s_d1, source%spec%t_l, source%spec%k, &
                              factors%importance, factors%use_group, api%convective_period), &
                    'g', ed//trim(branch))
        end if
      end if
      delta_s = report%add('sloshing wave height', 'δ_s', 'δ_s = 0.42 D A_f', '0.42 × @ × @', [D, a_f], &
                    0.42_wp*D*a_f, 'm', ed//'E.7.2-1')
      required = api650_required_freeboard(delta_s, s_ds, factors%use_group)
      select case (factors%use_group)
      case (3)
        call report%put('required freeboard (SUG III)', 'f_req', 'f_req = δ_s', '@', [delta_s], &
                       required, 'm', ed//'Table E-7')
      case (2)
        call report%put('required freeboard (SUG II: 0.7 δ_s where S_DS ≥ 0.33 g)', 'f_req', &
                       'f_req = 0.7 δ_s if S_DS ≥ 0.33 g, else 0', &
                       trim(pick('0.7 × @         ', '0 (S_DS = @ g)', s_ds >= 0.33_wp)), &
                       [merge(delta_s, s_ds, s_ds >= 0.33_wp)], required, 'm', ed//'Table E-7')
      case default
        call report%put('required freeboard (SUG I: none; 0.7 δ_s recommended)', 'f_req', &
                       'f_req = 0', '0', [real(wp) ::], required, 'm', ed//'Table E-7')
      end select
      call report%check(code, 'freeboard: required ≤ available', ed//'E.7.2, Table E-7', &
                        required, tank%freeboard, 'm')
      freeboard = [api%convective_period, a_f, delta_s, required, tank%freeboard, &
                   tank%freeboard - required, &
                   merge(1.0_wp, 0.0_wp, required <= tank%freeboard*(1 + 1.0e-9_wp))]
      call restricted_sloshing(report, code, 'δ_s, '//ed//'E.7.2-1', tank, delta_s, 1000*G, &
                               W_c/g_n, confined, status, message)
      W_conf = 0
      if (confined > 0) W_conf = report%add('confined weight, moved from the convective to the '// &
                                     'impulsive weight', 'W_conf', 'W_conf = m_conf g', '@ × @', &
                                     [confined, g_n], confined*g_n, 'N', &
                                     'ASCE 7-16 15.7.6.1.2 (as read here)')
    end subroutine sloshing_wave

    !> The row of 'design_loads': the weights as masses, the structure's lumped at the height of
    !> its moment (W_s X_s + W_r X_r)/(W_s + W_r + W_f), the confined mass in the impulsive at
    !> the convective heights.
    subroutine fill_loads_row()
      real(wp) :: m_i, m_c, m_conf, m_struct, h_struct, h_i, h_is
      m_i = W_i/g_n
      m_c = W_c/g_n
      m_conf = W_conf/g_n
      m_struct = (W_s + W_r + W_f)/g_n
      h_struct = 0
      if (m_struct > 0) h_struct = (W_s*X_s + W_r*X_r)/(W_s + W_r + W_f)
      h_i = (m_i*api%impulsive_height + m_conf*api%convective_height)/(m_i + m_conf)
      h_is = (m_i*api%impulsive_height_slab + m_conf*api%convective_height_slab)/(m_i + m_conf)
      loads = [factors%impulsive_period, api%convective_period, a_i, a_c, m_i + m_conf, &
               m_c - m_conf, m_struct, h_i, api%convective_height, h_is, &
               api%convective_height_slab, h_struct, V_i, V_c, V, M_rw, M_s]
    end subroutine fill_loads_row

    !> E.6.1.4: the hydrodynamic hoop forces N_i, N_c, the hydrostatic N_h and the hoop stress
    !> with the vertical acceleration, at the bottom of each wetted course (Y below the liquid
    !> surface), against the lesser of 1.333 S_d and 0.9 F_y E.
    subroutine hoop_stresses()
      real(wp) :: y, n_i, n_c, n_h, t, sigma, s_d, allowable
      integer :: k
      character(len=:), allocatable :: which
      do k = 1, shell%courses
        y = H - shell%bottom(k)
        if (y <= 0) exit
        which = ' of course '//num2str(k)//' (its bottom, Y = '//num2str(y, 5)//' m)'
        call report%note(code, 'depth below the liquid surface'//which, 'Y', 'Y = H − z_j', y, &
                         'm', ed//'E.6.1.4 (Y)')
        if (squat) then
          n_i = report%add('impulsive hoop membrane force'//which, 'N_i', &
                    'N_i = 8.48 A_i G D H [Y/H − 0.5 (Y/H)²] tanh(0.866 D/H)', &
                    '8.48 × @ × @ × @ × @ × (@/@ − 0.5 × (@/@)²) × tanh(0.866 × @/@)', &
                    [a_i, G, D, H, y, H, y, H, D, H], &
                    8.48_wp*a_i*G*D*H*(y/H - 0.5_wp*(y/H)**2)*tanh(0.866_wp*D/H), 'N/mm', &
                    ed//'E.6.1.4-1a')
        else if (y < 0.75_wp*D) then
          n_i = report%add('impulsive hoop membrane force'//which, 'N_i', &
                    'N_i = 5.22 A_i G D² [Y/(0.75 D) − 0.5 (Y/(0.75 D))²]', &
                    '5.22 × @ × @ × @² × (@/(0.75 × @) − 0.5 × (@/(0.75 × @))²)', &
                    [a_i, G, D, y, D, y, D], &
                    5.22_wp*a_i*G*D**2*(y/(0.75_wp*D) - 0.5_wp*(y/(0.75_wp*D))**2), 'N/mm', &
                    ed//'E.6.1.4-2a')
        else
          n_i = report%add('impulsive hoop membrane force'//which, 'N_i', 'N_i = 2.6 A_i G D²', &
                    '2.6 × @ × @ × @²', [a_i, G, D], 2.6_wp*a_i*G*D**2, 'N/mm', ed//'E.6.1.4-3a')
        end if
        n_c = report%add('convective hoop membrane force'//which, 'N_c', &
                  'N_c = 1.85 A_c G D² cosh[3.68 (H − Y)/D]/cosh[3.68 H/D]', &
                  '1.85 × @ × @ × @² × cosh(3.68 × (@ − @)/@)/cosh(3.68 × @/@)', &
                  [a_c, G, D, H, y, D, H, D], &
                  1.85_wp*a_c*G*D**2*cosh(3.68_wp*(H - y)/D)/cosh(3.68_wp*H/D), 'N/mm', &
                  ed//'E.6.1.4-4a')
        n_h = report%add('hydrostatic hoop membrane force'//which, 'N_h', &
                  'N_h = ρ g Y D/2 (in N/mm: /1000)', '1000 × @ × @ × @ × @/2/1000', &
                  [G, g_n, y, D], 1000*G*g_n*y*D/2/1000, 'N/mm', ed//'E.6.1.4 (N_h)')
        t = report%add('corroded thickness'//which, 't', 't = t_j − CA', '@ − @', &
                [st%course_thickness(k), st%corrosion_allowance], shell%corroded(k), 'mm', &
                ed//'E.6.1.4 (t)')
        sigma = report%add('total hoop stress'//which, 'σ_T', &
                    'σ_T = (N_h + √(N_i² + N_c² + (A_v N_h)²))/t', &
                    '(@ + √(@² + @² + (@ × @)²))/@', [n_h, n_i, n_c, a_v, n_h, t], &
                    (n_h + sqrt(n_i**2 + n_c**2 + (a_v*n_h)**2))/t, 'MPa', ed//'E.6.1.4-6')
        s_d = report%add('product design stress'//which, 'S_d', 'S_d = min(2/3 F_y, 2/5 F_t)', &
                  'min(2/3 × @, 2/5 × @)', [shell%yield(k), shell%tensile(k)], &
                  min(2*shell%yield(k)/3, 2*shell%tensile(k)/5), 'MPa', ed//'5.6.2.1 (Table 5-2)')
        allowable = report%add('allowable hoop stress'//which, 'σ_allow', &
                        'σ_allow = min(1.333 S_d, 0.9 F_y E)', 'min(1.333 × @, 0.9 × @ × @)', &
                        [s_d, shell%yield(k), st%joint_efficiency], &
                        min(1.333_wp*s_d, 0.9_wp*shell%yield(k)*st%joint_efficiency), 'MPa', &
                        ed//'E.6.1.4')
        call report%check(code, 'hoop stress, course '//num2str(k), ed//'E.6.1.4-6', sigma, &
                          allowable, 'MPa')
      end do
    end subroutine hoop_stresses

    !> E.6.2.1: the resisting weight of the shell and roof w_t and of the annulus w_a, the
    !> anchorage ratio J (Table E-6) or, mechanically anchored, the anchors' load; E.6.2.2:
    !> the shell compression sigma_c against F_c.
    subroutine anchorage_and_compression()
      real(wp) :: w_rs, w_t, G_e, t_a, f_y_a, w_a, J, L, t_s, sigma_c, F_c, w_ab, p_ab, j_max, &
                  ghd
      logical :: anchored
      anchored = st%anchorage == ANCHORAGE_MECHANICAL
      w_rs = report%add('roof load on the shell', 'w_rs', 'w_rs = W_r/(π D)', '@/(π × @)', [W_r, D], &
                 W_r/(pi*D), 'N/m', ed//'E.6.2.1.1 (w_rs)')
      w_t = report%add('shell and roof weight acting at the base of the shell', 'w_t', &
                'w_t = W_s/(π D) + w_rs', '@/(π × @) + @', [W_s, D, w_rs], W_s/(pi*D) + w_rs, &
                'N/m', ed//'E.6.2.1.1-2')
      G_e = report%add('effective specific gravity', 'G_e', 'G_e = G (1 − 0.4 A_v)', '@ × (1 − 0.4 × @)', &
                [G, a_v], G*(1 - 0.4_wp*a_v), '', ed//'E.6.2.1.1')
      t_s = report%add('bottom shell course''s thickness less corrosion allowance', 't_s', &
                't_s = t_1 − CA', '@ − @', [st%course_thickness(1), st%corrosion_allowance], &
                shell%corroded(1), 'mm', ed//'E.6.2.2 (t_s)')
      t_a = report%add('the annulus'' thickness less corrosion allowance, at most t_s', 't_a', &
                't_a = min(t_annulus − CA_b, t_s)', 'min(@ − @, @)', &
                [merge(st%annular_thickness, st%bottom_thickness, st%annular_thickness > 0), &
                 st%bottom_corrosion_allowance, t_s], &
                min(merge(st%annular_thickness, st%bottom_thickness, st%annular_thickness > 0) - &
                    st%bottom_corrosion_allowance, t_s), 'mm', ed//'E.6.2.1.1.1')
      f_y_a = st%annular_yield_strength
      if (f_y_a == 0) f_y_a = shell%yield(1)
      call report%note(code, 'yield strength of the annulus', 'F_y', &
                       'F_y (&tank_structure annular_yield_strength; 0: the bottom course''s)', &
                       f_y_a, 'MPa', ed//'E.6.2.1.1.1 (F_y)')
      w_a = report%add('resisting force of the annulus', 'w_a', &
                'w_a = 99 t_a √(F_y H G_e) ≤ 201.1 H D G_e', 'min(99 × @ × √(@ × @ × @), '// &
                '201.1 × @ × @ × @)', [t_a, f_y_a, H, G_e, H, D, G_e], &
                min(99*t_a*sqrt(f_y_a*H*G_e), 201.1_wp*H*D*G_e), 'N/m', ed//'E.6.2.1.1.1-1')
      J = report%add('anchorage ratio (w_int = 0: no internal pressure)', 'J', &
              'J = M_rw/(D² [w_t (1 − 0.4 A_v) + w_a − 0.4 w_int])', &
              '@/(@² × (@ × (1 − 0.4 × @) + @ − 0))', [M_rw, D, w_t, a_v, w_a], &
              M_rw/(D**2*(w_t*(1 - 0.4_wp*a_v) + w_a)), '', ed//'E.6.2.1.1-1')
      call report%note(code, 'Table E-6: '//trim(pick('J ≤ 0.785: no calculated uplift    ', &
                       'J > 0.785: the tank uplifts        ', J <= no_uplift))//'; '// &
                       trim(pick('J ≤ 1.54: stable if the shell compression is satisfied', &
                                  'J > 1.54: not stable self-anchored                    ', &
                                  J <= stable)), 'J', 'Table E-6', J, '', ed//'Table E-6')
      L = report%add('required width of the annulus inside the shell', 'L', &
              'L = 0.01723 t_a √(F_y/(H G_e)) ≤ 0.035 D', 'min(0.01723 × @ × √(@/(@ × @)), '// &
              '0.035 × @)', [t_a, f_y_a, H, G_e, D], &
              min(0.01723_wp*t_a*sqrt(f_y_a/(H*G_e)), 0.035_wp*D), 'm', ed//'E.6.2.1.1.2-1')
      call report%info(code, 'required annulus width L inside the shell', ed//'E.6.2.1.1.2-1', &
                       L, 'm')
      if (anchored) then
        call report%info(code, 'anchorage ratio J (mechanically anchored)', ed//'E.6.2.1.1-1', &
                         J, '')
        w_ab = report%add('design uplift load on the anchors per unit circumference', 'w_AB', &
                   'w_AB = 1.273 M_rw/D² − w_t (1 − 0.4 A_v) + w_int', &
                   '1.273 × @/@² − @ × (1 − 0.4 × @) + 0', [M_rw, D, w_t, a_v], &
                   1.273_wp*M_rw/D**2 - w_t*(1 - 0.4_wp*a_v), 'N/m', ed//'E.6.2.1.2-1')
        p_ab = report%add('anchor seismic design load', 'P_AB', 'P_AB = w_AB (π D/n_A)', &
                   '@ × (π × @/@)', [w_ab, D, real(st%anchor_count, wp)], &
                   w_ab*pi*D/st%anchor_count, 'N', ed//'E.6.2.1.2-2')
        call report%check(code, 'anchor load P_AB against its allowable', ed//'E.6.2.1.2-2', &
                          max(p_ab, 0.0_wp), st%anchor_capacity, 'N')
        sigma_c = report%add('longitudinal shell membrane compression (mechanically anchored)', 'σ_c', &
                      'σ_c = (w_t (1 + 0.4 A_v) + 1.273 M_rw/D²) (1/(1000 t_s))', &
                      '(@ × (1 + 0.4 × @) + 1.273 × @/@²) × (1/(1000 × @))', &
                      [w_t, a_v, M_rw, D, t_s], &
                      (w_t*(1 + 0.4_wp*a_v) + 1.273_wp*M_rw/D**2)/(1000*t_s), 'MPa', &
                      ed//'E.6.2.2.2-1')
      else
        call report%check(code, 'anchorage ratio J (self-anchored, Table E-6)', &
                          ed//'E.6.2.1.1-1, Table E-6', J, stable, '')
        j_max = (0.607_wp/0.18667_wp)**(1/2.3_wp)
        if (J <= no_uplift) then
          sigma_c = report%add('longitudinal shell membrane compression (J ≤ 0.785)', 'σ_c', &
                        'σ_c = (w_t (1 + 0.4 A_v) + 1.273 M_rw/D²) (1/(1000 t_s))', &
                        '(@ × (1 + 0.4 × @) + 1.273 × @/@²) × (1/(1000 × @))', &
                        [w_t, a_v, M_rw, D, t_s], &
                        (w_t*(1 + 0.4_wp*a_v) + 1.273_wp*M_rw/D**2)/(1000*t_s), 'MPa', &
                        ed//'E.6.2.2.1-1a')
        else if (J < j_max) then
          sigma_c = report%add('longitudinal shell membrane compression (J > 0.785)', 'σ_c', &
                        'σ_c = ((w_t (1 + 0.4 A_v) + w_a)/(0.607 − 0.18667 J^2.3) − w_a) '// &
                        '(1/(1000 t_s))', '((@ × (1 + 0.4 × @) + @)/(0.607 − 0.18667 × @^2.3) '// &
                        '− @) × (1/(1000 × @))', [w_t, a_v, w_a, J, w_a, t_s], &
                        ((w_t*(1 + 0.4_wp*a_v) + w_a)/(0.607_wp - 0.18667_wp*J**2.3_wp) - w_a)/ &
                        (1000*t_s), 'MPa', ed//'E.6.2.2.1-1b')
        else
          call report%note(code, 'shell compression: eq E.6.2.2.1-1b has no value for J ≥ '// &
                           '(0.607/0.18667)^(1/2.3) (its denominator ≤ 0): the tank is not '// &
                           'stable self-anchored', 'J_max', 'J_max = (0.607/0.18667)^(1/2.3)', &
                           j_max, '', ed//'E.6.2.2.1-1b')
          call report%check(code, 'shell compression: J below the limit of eq E.6.2.2.1-1b', &
                            ed//'E.6.2.2.1-1b', J, j_max, '')
          return
        end if
      end if
      ghd = report%add('the shell''s compression parameter', 'G H D²/t_s²', 'G H D²/t_s²', &
                '@ × @ × @²/@²', [G, H, D, t_s], G*H*D**2/t_s**2, '', ed//'E.6.2.2.3')
      if (ghd >= 44) then
        F_c = report%add('allowable longitudinal membrane compression (G H D²/t_s² ≥ 44)', 'F_c', &
                  'F_c = 83 t_s/D ≤ 0.5 F_ty', 'min(83 × @/@, 0.5 × @)', [t_s, D, shell%yield(1)], &
                  min(83*t_s/D, 0.5_wp*shell%yield(1)), 'MPa', ed//'E.6.2.2.3-1a')
      else
        F_c = report%add('allowable longitudinal membrane compression (G H D²/t_s² < 44)', 'F_c', &
                  'F_c = 83 t_s/(2.5 D) + 7.5 √(G H) ≤ 0.5 F_ty', &
                  'min(83 × @/(2.5 × @) + 7.5 × √(@ × @), 0.5 × @)', &
                  [t_s, D, G, H, shell%yield(1)], &
                  min(83*t_s/(2.5_wp*D) + 7.5_wp*sqrt(G*H), 0.5_wp*shell%yield(1)), 'MPa', &
                  ed//'E.6.2.2.3-1b')
      end if
      call report%check(code, 'shell compression σ_c against F_c', ed//'E.6.2.2', sigma_c, F_c, &
                        'MPa')
    end subroutine anchorage_and_compression

    !> E.7.6: the friction resistance against the base shear.
    subroutine sliding()
      real(wp) :: mu, V_s
      mu = st%friction
      call report%note(code, 'friction coefficient, bottom on foundation', 'μ', &
                       'μ (&tank_structure friction; 0.4 by default)', mu, '', ed//'E.7.6')
      V_s = report%add('sliding resistance', 'V_s', 'V_s = μ (W_s + W_r + W_f + W_p)(1.0 − 0.4 A_v)', &
                '@ × (@ + @ + @ + @) × (1 − 0.4 × @)', [mu, W_s, W_r, W_f, W_p, a_v], &
                mu*(W_s + W_r + W_f + W_p)*(1 - 0.4_wp*a_v), 'N', ed//'E.7.6-1')
      call report%check(code, 'sliding: base shear V against the resistance V_s', ed//'E.7.6', &
                        V, V_s, 'N')
    end subroutine sliding
  end subroutine api650_design
end module sloshdyn_api650_checks
