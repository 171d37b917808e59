!> ACI 350.3-06 for a circular or rectangular (concrete) tank (docs/design.md, "ACI 350.3"):
!> the dynamic properties (9.2, 9.3: Housner's model, the impulsive period from the wall,
!> 9.2.4 rectangular and 9.3.4 circular), the seismic coefficients C_i, C_c (9.4.1, 9.4.2) and
!> the vertical acceleration (4.1.4, 9.4.3), the wall-mass factor epsilon (9.5), the dynamic
!> forces and moments (4.1.1-4.1.3, eq 4-1 to 4-13), the sloshing wave's d_max (7.1) with the
!> roof's loads by the restricted-sloshing method where it exceeds the freeboard, and the
!> distribution of the hydrodynamic pressures along the wall (chapter 5) combined with the
!> wall's inertia and the vertical acceleration (eq 4-16).
!>
!> Units: weights and forces [N], moments [N m], pressures [Pa], lengths [m], the wall's
!> thickness t_w [mm], E_c [MPa]; coefficients in g. One form for both shapes: plan size D
!> (circular) or L (rectangular, along the motion; B across it). The equation numbers are those
!> design guides cite (the paid text was not at hand; docs/design.md lists what could not be
!> verified).
module sloshdyn_aci350_checks
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK
  use sloshdyn_text, only: num2str
  use sloshdyn_vessel, only: tank_t
  use sloshdyn_tank, only: SHAPE_CIRCULAR
  use sloshdyn_design_codes, only: aci350_parameters, aci350_circular, aci350_rectangular
  use sloshdyn_design_spectra, only: SPECTRUM_ACI350, CONVECTIVE_RATIO
  use sloshdyn_design_source, only: design_source_t, source_sa, source_impulsive_sa, record_sds
  use sloshdyn_design_loads, only: design_factors_t
  use sloshdyn_design_report, only: design_report_t, pick
  use sloshdyn_tank_structure, only: tank_structure_t, shell_t, shell_of, MATERIAL_CONCRETE
  use sloshdyn_restricted_sloshing, only: restricted_sloshing
  use sloshdyn_tables, only: DESIGN_LOADS_COLUMNS, FREEBOARD_COLUMNS
  implicit none
  private
  public :: aci350_design

  character(len=*), parameter :: code = 'ACI 350.3', ed = 'ACI 350.3-06 '
  !> 4.1.4: the ratio b of the vertical to the horizontal design acceleration, unless given.
  real(wp), parameter :: vertical_ratio = 2.0_wp/3

contains

  !> ACI 350.3-06 for the tank (liquid mass m_L [kg]), its structure or its lumped mass m_t at
  !> h_t, the factors and the source: the report's steps and checks and the rows of
  !> 'design_loads' and 'freeboard_check'.
  subroutine aci350_design(tank, liquid_mass, m_t, h_t, st, factors, source, report, loads, &
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
    type(aci350_parameters) :: aci
    type(shell_t) :: shell
    real(wp) :: s, H, g_n, rho, c, W_L, W_i, W_c, W_w, h_w, W_r, h_r, eps, t_i, c_i, c_c, s_ds, &
                u_v, d_max, m_conf, W_conf, P_w, P_r, P_i, P_c, V, M_b, M_o, ratio
    logical :: circular, concrete
    character(len=1) :: d_or_l

    report%code = code           ! the steps of report%add and report%put are this code's
    loads = 0
    freeboard = 0
    circular = tank%shape == SHAPE_CIRCULAR
    if (circular) then
      call aci350_circular(tank%radius, tank%liquid_depth, tank%gravity, aci, status, message)
    else
      call aci350_rectangular(tank%length, tank%liquid_depth, tank%gravity, aci, status, message)
    end if
    if (status /= SD_OK) return
    concrete = st%given .and. st%material == MATERIAL_CONCRETE
    if (st%given) shell = shell_of(tank, st)
    g_n = tank%gravity
    H = tank%liquid_depth
    d_or_l = pick('D', 'L', circular)
    c = merge(3.68_wp, 3.16_wp, circular)
    if (circular) then
      s = report%add('inside diameter', 'D', 'D = 2 R', '2 × @', [tank%radius], 2*tank%radius, 'm', &
              ed//'9.3 (D)')
      rho = liquid_mass/(pi*s**2/4*H)
    else
      s = report%add('inside length along the motion', 'L', 'L (&tank length)', '@', [tank%length], &
              tank%length, 'm', ed//'9.2 (L)')
      call report%note(code, 'inside width across the motion', 'B', 'B (&tank width)', &
                       tank%width, 'm', ed//'9.2 (B)')
      rho = liquid_mass/(tank%length*tank%width*H)
    end if
    call report%note(code, 'design depth of the stored liquid', 'H_L', 'H_L (&tank liquid_depth)', &
                     H, 'm', ed//'9.2 (H_L)')
    W_L = report%add('weight of the stored liquid', 'W_L', 'W_L = m_L g', '@ × @', [liquid_mass, g_n], &
              liquid_mass*g_n, 'N', ed//'9.2 (W_L)')
    ratio = s/H

    ! --- Housner's model (9.2.1-9.2.3 rectangular, 9.3.1-9.3.3 circular)
    W_i = report%add('effective impulsive weight', 'W_i', 'W_i = tanh(0.866 '//d_or_l//'/H_L)/(0.866 '// &
              d_or_l//'/H_L) W_L', 'tanh(0.866 × @/@)/(0.866 × @/@) × @', [s, H, s, H, W_L], &
              aci%impulsive_ratio*W_L, 'N', ed//trim(eq('15', '1')))
    W_c = report%add('effective convective weight', 'W_c', 'W_c = '// &
              trim(pick('0.230', '0.264', circular))//' ('//d_or_l//'/H_L) tanh('// &
              trim(pick('3.68', '3.16', circular))//' H_L/'//d_or_l//') W_L', &
              trim(pick('0.23 ', '0.264', circular))//' × @/@ × tanh(@ × @/@) × @', &
              [s, H, c, H, s, W_L], aci%convective_ratio*W_L, 'N', ed//trim(eq('16', '2')))
    if (ratio < 1.333_wp) then
      call report%put('height of the impulsive force, EBP ('//d_or_l//'/H_L < 1.333)', 'h_i', &
                     'h_i = (0.5 − 0.09375 '//d_or_l//'/H_L) H_L', '(0.5 − 0.09375 × @/@) × @', &
                     [s, H, H], aci%impulsive_height, 'm', ed//trim(eq('17', '3')))
    else
      call report%put('height of the impulsive force, EBP ('//d_or_l//'/H_L ≥ 1.333)', 'h_i', &
                     'h_i = 0.375 H_L', '0.375 × @', [H], aci%impulsive_height, 'm', &
                     ed//trim(eq('18', '4')))
    end if
    call report%put('height of the convective force, EBP', 'h_c', 'h_c = [1 − (cosh(c H_L/'// &
                   d_or_l//') − 1)/((c H_L/'//d_or_l//') sinh(c H_L/'//d_or_l//'))] H_L, c = '// &
                   trim(pick('3.68', '3.16', circular)), &
                   '(1 − (cosh(@ × @/@) − 1)/(@ × @/@ × sinh(@ × @/@))) × @', &
                   [c, H, s, c, H, s, c, H, s, H], aci%convective_height, 'm', ed//trim(eq('19', '5')))
    if (ratio < 0.75_wp) then
      call report%put('height of the impulsive force, IBP ('//d_or_l//'/H_L < 0.75)', 'h_i''', &
                     'h_i'' = 0.45 H_L', '0.45 × @', [H], aci%impulsive_height_ibp, 'm', &
                     ed//trim(eq('20', '6')))
    else
      call report%put('height of the impulsive force, IBP ('//d_or_l//'/H_L ≥ 0.75)', 'h_i''', &
                     'h_i'' = [0.866 ('//d_or_l//'/H_L)/(2 tanh(0.866 '//d_or_l// &
                     '/H_L)) − 1/8] H_L', '(0.866 × @/@/(2 × tanh(0.866 × @/@)) − 1/8) × @', &
                     [s, H, s, H, H], aci%impulsive_height_ibp, 'm', ed//trim(eq('21', '7')))
    end if
    call report%put('height of the convective force, IBP', 'h_c''', 'h_c'' = [1 − (cosh(c H_L/'// &
                   d_or_l//') − 2.01)/((c H_L/'//d_or_l//') sinh(c H_L/'//d_or_l//'))] H_L', &
                   '(1 − (cosh(@ × @/@) − 2.01)/(@ × @/@ × sinh(@ × @/@))) × @', &
                   [c, H, s, c, H, s, c, H, s, H], aci%convective_height_ibp, 'm', &
                   ed//trim(eq('22', '8')))
    call report%put('convective coefficient', 'λ', 'λ = √(c g tanh(c H_L/'//d_or_l//'))', &
                   '√(@ × @ × tanh(@ × @/@))', [c, g_n, c, H, s], aci%lambda, 'm^0.5/s', &
                   ed//trim(eq('29', '9')))
    call report%put('circular frequency of the convective mode', 'ω_c', 'ω_c = λ/√'//d_or_l, &
                   '@/√@', [aci%lambda, s], aci%convective_frequency, 'rad/s', ed//trim(eq('30', '10')))
    call report%put('convective period', 'T_c', 'T_c = 2π/ω_c', '2π/@', [aci%convective_frequency], &
                   aci%convective_period, 's', ed//trim(eq('31', '11')))

    ! --- the wall and roof (9.5's epsilon on the wall), or the lumped mass
    if (st%given) then
      W_w = report%add('weight of the tank wall', 'W_w', 'W_w = g Σ m_j (the wall''s lifts)', '@ × @', &
                [g_n, shell%shell_mass], g_n*shell%shell_mass, 'N', ed//'4.1.1 (W_w)')
      h_w = report%add('height of the wall''s centre of gravity', 'h_w', 'h_w = Σ m_j (z_j + h_j/2)/Σ m_j', &
                '@', [shell%shell_height], shell%shell_height, 'm', ed//'4.1.3 (h_w)')
      W_r = report%add('weight of the roof', 'W_r', 'W_r = m_r g', '@ × @', [st%roof_mass, g_n], &
                st%roof_mass*g_n, 'N', ed//'4.1.1 (W_r)')
      h_r = report%add('height of the roof''s centre of gravity', 'h_r', &
                'h_r (&tank_structure roof_mass_height; 0: the wall''s top)', '@', &
                [shell%roof_height], shell%roof_height, 'm', ed//'4.1.3 (h_r)')
      eps = report%add('effective mass coefficient', 'ε', 'ε = [0.0151 ('//d_or_l//'/H_L)² − 0.1908 ('// &
                d_or_l//'/H_L) + 1.021] ≤ 1.0', 'min(0.0151 × (@/@)² − 0.1908 × @/@ + 1.021, 1)', &
                [s, H, s, H], min(0.0151_wp*ratio**2 - 0.1908_wp*ratio + 1.021_wp, 1.0_wp), '', &
                ed//trim(pick('9.5, eq 9-45', '9.5, eq 9-44', circular)))
    else
      W_w = report%add('weight of the wall and roof, lumped (no &tank_structure)', 'W_w', 'W_w = m_t g', &
                '@ × @', [m_t, g_n], m_t*g_n, 'N', ed//'4.1.1 (W_w, W_r)')
      h_w = report%add('height of the lumped wall and roof', 'h_w', 'h_w = h_t', '@', [h_t], h_t, 'm', &
                ed//'4.1.3 (h_w)')
      W_r = 0
      h_r = 0
      eps = report%add('effective mass coefficient (lumped wall and roof: ε = 1, conservative)', 'ε', &
                'ε = 1', '1', [real(wp) ::], 1.0_wp, '', ed//'9.5')
    end if

    ! --- seismic coefficients (9.4) and the vertical acceleration (4.1.4)
    call coefficients()
    if (status /= SD_OK) return

    ! --- the sloshing wave (7.1) and the roof where it reaches it
    d_max = report%add('maximum vertical displacement of the sloshing wave', 'd_max', &
                'd_max = ('//d_or_l//'/2) C_c I', '(@/2) × @ × @', [s, c_c, factors%importance], &
                s/2*c_c*factors%importance, 'm', ed//trim(pick('7.1, eq 7-2', '7.1, eq 7-1', &
                                                                circular)))
    call report%check(code, 'freeboard: d_max ≤ available', ed//'7.1', d_max, tank%freeboard, 'm')
    freeboard = [aci%convective_period, c_c*factors%importance, d_max, d_max, tank%freeboard, &
                 tank%freeboard - d_max, &
                 merge(1.0_wp, 0.0_wp, d_max <= tank%freeboard*(1 + 1.0e-9_wp))]
    call restricted_sloshing(report, code, 'd_max, '//ed//'7.1', tank, d_max, rho, W_c/g_n, &
                             m_conf, status, message)
    if (status /= SD_OK) return
    W_conf = 0
    if (m_conf > 0) W_conf = report%add('confined weight, moved from the convective to the impulsive '// &
                                 'weight', 'W_conf', 'W_conf = m_conf g', '@ × @', [m_conf, g_n], &
                                 m_conf*g_n, 'N', 'ASCE 7-16 15.7.6.1.2 (as read here)')

    ! --- dynamic forces and moments (4.1)
    P_w = report%add('inertia force of the wall', 'P_w', 'P_w = C_i I (ε W_w/R_i)', '@ × @ × (@ × @/@)', &
              [c_i, factors%importance, eps, W_w, factors%r_i], &
              c_i*factors%importance*eps*W_w/factors%r_i, 'N', ed//'4.1.1, eq 4-1')
    P_r = report%add('inertia force of the roof', 'P_r', 'P_r = C_i I (W_r/R_i)', '@ × @ × (@/@)', &
              [c_i, factors%importance, W_r, factors%r_i], c_i*factors%importance*W_r/factors%r_i, &
              'N', ed//'4.1.1, eq 4-2')
    P_i = report%add('impulsive force (with the confined weight)', 'P_i', &
              'P_i = C_i I ((W_i + W_conf)/R_i)', '@ × @ × ((@ + @)/@)', &
              [c_i, factors%importance, W_i, W_conf, factors%r_i], &
              c_i*factors%importance*(W_i + W_conf)/factors%r_i, 'N', ed//'4.1.1, eq 4-3')
    P_c = report%add('convective force', 'P_c', 'P_c = C_c I ((W_c − W_conf)/R_c)', '@ × @ × ((@ − @)/@)', &
              [c_c, factors%importance, W_c, W_conf, factors%r_c], &
              c_c*factors%importance*(W_c - W_conf)/factors%r_c, 'N', ed//'4.1.1, eq 4-4')
    V = report%add('total base shear', 'V', 'V = √((P_i + P_w + P_r)² + P_c²)', '√((@ + @ + @)² + @²)', &
            [P_i, P_w, P_r, P_c], sqrt((P_i + P_w + P_r)**2 + P_c**2), 'N', ed//'4.1.2, eq 4-5')
    M_b = report%add('bending moment on the wall at its base (EBP)', 'M_b', &
              'M_b = √((M_i + M_w + M_r)² + M_c²), M_i = P_i h_i* , M_w = P_w h_w, M_r = P_r h_r,'// &
              ' M_c = P_c h_c', '√((@ × @ + @ × @ + @ × @)² + (@ × @)²)', &
              [P_i, h_ebp(aci%impulsive_height, aci%convective_height), P_w, h_w, P_r, h_r, P_c, &
               aci%convective_height], &
              sqrt((P_i*h_ebp(aci%impulsive_height, aci%convective_height) + P_w*h_w + &
                    P_r*h_r)**2 + (P_c*aci%convective_height)**2), 'N m', &
              ed//'4.1.3, eq 4-6 to 4-10')
    M_o = report%add('overturning moment at the base (IBP)', 'M_o', &
              'M_o = √((M_i'' + M_w + M_r)² + M_c''²), M_i'' = P_i h_i''*, M_c'' = P_c h_c''', &
              '√((@ × @ + @ × @ + @ × @)² + (@ × @)²)', &
              [P_i, h_ebp(aci%impulsive_height_ibp, aci%convective_height_ibp), P_w, h_w, P_r, &
               h_r, P_c, aci%convective_height_ibp], &
              sqrt((P_i*h_ebp(aci%impulsive_height_ibp, aci%convective_height_ibp) + P_w*h_w + &
                    P_r*h_r)**2 + (P_c*aci%convective_height_ibp)**2), 'N m', &
              ed//'4.1.3, eq 4-11 to 4-13')
    if (W_conf > 0) call report%note(code, 'h_i* (h_i''*): the height of W_i and W_conf '// &
                                     'together, W_conf at h_c (h_c'')', 'h_i*', &
                                     'h_i* = (W_i h_i + W_conf h_c)/(W_i + W_conf)', &
                                     h_ebp(aci%impulsive_height, aci%convective_height), 'm', &
                                     'ASCE 7-16 15.7.6.1.2 (as read here)')
    call report%info(code, 'total base shear V', ed//'eq 4-5', V, 'N')
    call report%info(code, 'bending moment M_b (EBP)', ed//'eq 4-10', M_b, 'N m')
    call report%info(code, 'overturning moment M_o (IBP)', ed//'eq 4-13', M_o, 'N m')
    loads = [t_i, aci%convective_period, c_i*factors%importance/factors%r_i, &
             c_c*factors%importance/factors%r_c, (W_i + W_conf)/g_n, (W_c - W_conf)/g_n, &
             (eps*W_w + W_r)/g_n, h_ebp(aci%impulsive_height, aci%convective_height), &
             aci%convective_height, h_ebp(aci%impulsive_height_ibp, aci%convective_height_ibp), &
             aci%convective_height_ibp, merge((eps*W_w*h_w + W_r*h_r)/(eps*W_w + W_r), 0.0_wp, &
                                              eps*W_w + W_r > 0), &
             P_i + P_w + P_r, P_c, V, M_b, M_o]

    ! --- the pressures along the wall (chapter 5, eq 4-16)
    call wall_pressures()

  contains

    !> 'eq 9-NN' of the circular or rectangular form.
    pure function eq(circular_number, rectangular_number) result(text)
      character(len=*), intent(in) :: circular_number, rectangular_number
      character(len=8) :: text
      if (circular) then
        text = 'eq 9-'//circular_number
      else
        text = 'eq 9-'//rectangular_number
      end if
    end function eq

    !> The height of the impulsive weight with the confined weight at the convective height.
    pure real(wp) function h_ebp(h_imp, h_con)
      real(wp), intent(in) :: h_imp, h_con
      h_ebp = (W_i*h_imp + W_conf*h_con)/(W_i + W_conf)
    end function h_ebp

    !> C_i at T_i (9.2.4 rectangular, 9.3.4 circular concrete walls; given; or the plateau), C_c
    !> (9.4.2), and the vertical acceleration u_v = C_t I b/R_i (4.1.4, C_t = 0.4 S_DS, 9.4.3).
    subroutine coefficients()
      real(wp) :: sa_c, period
      t_i = factors%impulsive_period
      if (concrete .and. t_i == 0) call impulsive_period()
      call report%note(code, 'importance factor', 'I', 'I (&design importance)', &
                       factors%importance, '', ed//'Table 4.1.1(a)')
      call report%note(code, 'response modification factors', 'R_i', 'R_i (&design r_i)', &
                       factors%r_i, '', ed//'Table 4.1.1(b)')
      call report%note(code, 'response modification factors', 'R_c', 'R_c (&design r_c)', &
                       factors%r_c, '', ed//'Table 4.1.1(b)')
      period = t_i
      call source_impulsive_sa(source, SPECTRUM_ACI350, period, factors%impulsive_damping_ratio, &
                               .false., c_i, status, message)
      if (status /= SD_OK) return
      call source_sa(source, SPECTRUM_ACI350, aci%convective_period, CONVECTIVE_RATIO, sa_c, &
                     status, message)
      if (status /= SD_OK) return
      call record_sds(source, s_ds, status, message)
      if (status /= SD_OK) return
      if (source%from_ground) then
        c_i = report%add('impulsive seismic coefficient (the ground motion'// &
                  trim(pick('''s peak: the rigid tank)', '''s 5 % spectrum)   ', period == 0)), &
                  'C_i', trim(pick('C_i = PGA/g       ', 'C_i = Sa(T_i, 5 %)', period == 0)), &
                  '@', [c_i], c_i, 'g', ed//'9.4.1')
        c_c = report%add('convective seismic coefficient (the ground motion''s 0.5 % spectrum)', 'C_c', &
                  'C_c = Sa(T_c, 0.5 %)', '@', [sa_c], sa_c, 'g', ed//'9.4.2')
      else
        if (period == 0) then
          c_i = report%add('impulsive seismic coefficient (on the plateau: T_i ≤ T_s)', 'C_i', &
                    'C_i = S_DS', '@', [c_i], c_i, 'g', ed//'9.4.1, eq 9-32')
        else if (period <= source%spec%s_d1/source%spec%s_ds) then
          c_i = report%add('impulsive seismic coefficient (T_i ≤ T_s = S_D1/S_DS)', 'C_i', 'C_i = S_DS', &
                    '@', [c_i], c_i, 'g', ed//'9.4.1, eq 9-32')
        else
          c_i = report%add('impulsive seismic coefficient (T_i > T_s)', 'C_i', 'C_i = S_D1/T_i ≤ S_DS', &
                    'min(@/@, @)', [source%spec%s_d1, period, source%spec%s_ds], c_i, 'g', &
                    ed//'9.4.1, eq 9-33')
        end if
        if (aci%convective_period <= 1.6_wp/(source%spec%s_d1/source%spec%s_ds)) then
          c_c = report%add('convective seismic coefficient (T_c ≤ 1.6/T_s)', 'C_c', &
                    'C_c = 1.5 S_D1/T_c ≤ 1.5 S_DS', 'min(1.5 × @/@, 1.5 × @)', &
                    [source%spec%s_d1, aci%convective_period, source%spec%s_ds], sa_c, 'g', &
                    ed//'9.4.2, eq 9-34')
        else
          c_c = report%add('convective seismic coefficient (T_c > 1.6/T_s)', 'C_c', 'C_c = 2.4 S_DS/T_c²', &
                    '2.4 × @/@²', [source%spec%s_ds, aci%convective_period], sa_c, 'g', &
                    ed//'9.4.2, eq 9-35')
        end if
      end if
      if (.not. factors%vertical) then
        u_v = report%add('effective vertical acceleration (&design vertical = .false.)', 'ü_v', &
                  'ü_v = 0', '0', [real(wp) ::], 0.0_wp, 'g', ed//'4.1.4')
      else if (factors%vertical_acceleration > 0) then
        u_v = report%add('effective vertical acceleration (the purchaser''s)', 'ü_v', &
                  'ü_v (&design vertical_acceleration)', '@', [factors%vertical_acceleration], &
                  factors%vertical_acceleration, 'g', ed//'4.1.4')
      else
        u_v = report%add('effective vertical acceleration (C_t = 0.4 S_DS, b = 2/3)', 'ü_v', &
                  'ü_v = C_t I b/R_i, C_t = 0.4 S_DS', '0.4 × @ × @ × (2/3)/@', &
                  [s_ds, factors%importance, factors%r_i], &
                  0.4_wp*s_ds*factors%importance*vertical_ratio/factors%r_i, 'g', &
                  ed//'4.1.4, eq 4-15; 9.4.3')
      end if
    end subroutine coefficients

    !> The impulsive period of the concrete wall: rectangular, the cantilever wall strip with
    !> its share of the impulsive liquid (9.2.4); circular, 9.3.4's C_w polynomial in H_L/D,
    !> written here in consistent SI units: omega_i = 10 C_w sqrt(t_w/R) sqrt(E_c/rho_c)/H_L.
    subroutine impulsive_period()
      real(wp) :: t_w, m_w, m_i, h_cg, k, c_w, omega
      t_w = report%add('wall thickness (the bottom lift)', 't_w', 't_w (&tank_structure '// &
                'course_thickness(1))', '@', [st%course_thickness(1)], st%course_thickness(1), &
                'mm', ed//trim(pick('9.3.4', '9.2.4', circular)))
      if (.not. circular) then
        m_w = report%add('mass of the wall per unit width', 'm_w', 'm_w = H_w t_w ρ_c', &
                  '@ × @/1000 × @', [sum(st%course_height), t_w, shell%density], &
                  sum(st%course_height)*t_w/1000*shell%density, 'kg/m', ed//'9.2.4')
        m_i = report%add('impulsive mass of the liquid per unit width of one wall', 'm_i', &
                  'm_i = (W_i/W_L) (L/2) H_L ρ_L', '@ × (@/2) × @ × @', &
                  [aci%impulsive_ratio, s, H, rho], aci%impulsive_ratio*s/2*H*rho, 'kg/m', &
                  ed//'9.2.4')
        h_cg = report%add('height of the centre of gravity of wall and impulsive liquid', 'h', &
                'h = (h_w m_w + h_i m_i)/(m_w + m_i), h_w = H_w/2', '(@ × @ + @ × @)/(@ + @)', &
                [sum(st%course_height)/2, m_w, aci%impulsive_height, m_i, m_w, m_i], &
                (sum(st%course_height)/2*m_w + aci%impulsive_height*m_i)/(m_w + m_i), 'm', &
                ed//'9.2.4')
        k = report%add('flexural stiffness of a unit width of wall', 'k', 'k = E_c/(4 × 10³) (t_w/h)³', &
                '@/4000 × (@/@)³', [shell%modulus, t_w, h_cg], shell%modulus/4000*(t_w/h_cg)**3, &
                'N/m²', ed//'9.2.4')
        omega = report%add('circular frequency of the impulsive mode', 'ω_i', 'ω_i = √(k/m), m = m_w + m_i', &
                    '√(@/(@ + @))', [k, m_w, m_i], sqrt(k/(m_w + m_i)), 'rad/s', ed//'9.2.4')
      else
        c_w = report%add('coefficient of the impulsive frequency', 'C_w', 'C_w = 9.375e-2 + 0.2039 '// &
                  '(H_L/D) − 0.1034 (H_L/D)² − 0.1253 (H_L/D)³ + 0.1267 (H_L/D)⁴ − 3.186e-2 '// &
                  '(H_L/D)⁵', '0.09375 + 0.2039 × @ − 0.1034 × @² − 0.1253 × @³ + 0.1267 × @⁴ − '// &
                  '0.03186 × @⁵', [H/s, H/s, H/s, H/s, H/s], &
                  0.09375_wp + 0.2039_wp*(H/s) - 0.1034_wp*(H/s)**2 - 0.1253_wp*(H/s)**3 + &
                  0.1267_wp*(H/s)**4 - 0.03186_wp*(H/s)**5, '', ed//'9.3.4')
        omega = report%add('circular frequency of the impulsive mode', 'ω_i', &
                    'ω_i = 10 C_w √(t_w/R) √(E_c/ρ_c)/H_L (consistent SI units)', &
                    '10 × @ × √(@/1000/@) × √(@ × 10⁶/@)/@', &
                    [c_w, t_w, tank%radius, shell%modulus, shell%density, H], &
                    10*c_w*sqrt(t_w/1000/tank%radius)*sqrt(shell%modulus*1.0e6_wp/ &
                                                          shell%density)/H, 'rad/s', ed//'9.3.4')
      end if
      t_i = report%add('impulsive period', 'T_i', 'T_i = 2π/ω_i', '2π/@', [omega], 2*pi/omega, 's', &
                ed//trim(pick('9.3.4', '9.2.4', circular)))
      call report%info(code, 'impulsive period T_i', ed//trim(pick('9.3.4', '9.2.4', circular)), &
                       t_i, 's')
    end subroutine impulsive_period

    !> Chapter 5: the impulsive and convective forces per unit height P_iy, P_cy (linear in y),
    !> their pressures (circular: at theta = 0, 2 P_iy/(pi R) and 16 P_cy/(9 pi R); rectangular:
    !> P_y/(2 B) on each wall across the motion), the wall's inertia p_wy and the vertical
    !> p_vy = u_v q_hy, combined by eq 4-16; at the base and at the bottom of each wetted
    !> course; a circular wall's hoop force p_y R (INFO).
    subroutine wall_pressures()
      real(wp) :: y, p_iy, p_cy, p_wy, p_vy, p_y, t_w, force_i, force_c, hoop
      integer :: k, n
      character(len=:), allocatable :: at
      n = 1
      if (st%given) n = shell%courses
      do k = 1, n
        y = 0
        if (st%given) y = shell%bottom(k)
        if (y >= H) exit
        at = ' at y = '//num2str(y, 5)//' m'
        force_i = report%add('impulsive force per unit height'//at, 'P_iy', 'P_iy = (P_i/2) [4 H_L − '// &
                      '6 h_i − (6 H_L − 12 h_i)(y/H_L)]/H_L²', '(@/2) × (4 × @ − 6 × @ − (6 × @ '// &
                      '− 12 × @) × (@/@))/@²', [P_i, H, aci%impulsive_height, H, &
                      aci%impulsive_height, y, H, H], P_i/2*(4*H - 6*aci%impulsive_height - &
                      (6*H - 12*aci%impulsive_height)*(y/H))/H**2, 'N/m', &
                      ed//trim(pick('5.3.2', '5.3.1', circular)))
        force_c = report%add('convective force per unit height'//at, 'P_cy', 'P_cy = (P_c/2) [4 H_L − '// &
                      '6 h_c − (6 H_L − 12 h_c)(y/H_L)]/H_L²', '(@/2) × (4 × @ − 6 × @ − (6 × @ '// &
                      '− 12 × @) × (@/@))/@²', [P_c, H, aci%convective_height, H, &
                      aci%convective_height, y, H, H], P_c/2*(4*H - 6*aci%convective_height - &
                      (6*H - 12*aci%convective_height)*(y/H))/H**2, 'N/m', &
                      ed//trim(pick('5.3.2', '5.3.1', circular)))
        if (circular) then
          p_iy = report%add('impulsive pressure'//at//', θ = 0', 'p_iy', 'p_iy = 2 P_iy/(π R) cos θ', &
                     '2 × @/(π × @)', [force_i, tank%radius], 2*force_i/(pi*tank%radius), 'Pa', &
                     ed//'5.3.2')
          p_cy = report%add('convective pressure'//at//', θ = 0', 'p_cy', 'p_cy = 16 P_cy/(9 π R) cos θ', &
                     '16 × @/(9 × π × @)', [force_c, tank%radius], &
                     16*force_c/(9*pi*tank%radius), 'Pa', ed//'5.3.2')
        else
          p_iy = report%add('impulsive pressure on a wall across the motion'//at, 'p_iy', &
                     'p_iy = P_iy/(2 B)', '@/(2 × @)', [force_i, tank%width], &
                     force_i/(2*tank%width), 'Pa', ed//'5.3.1')
          p_cy = report%add('convective pressure on a wall across the motion'//at, 'p_cy', &
                     'p_cy = P_cy/(2 B)', '@/(2 × @)', [force_c, tank%width], &
                     force_c/(2*tank%width), 'Pa', ed//'5.3.1')
        end if
        if (st%given) then
          t_w = st%course_thickness(k)
          p_wy = report%add('the wall''s own inertia'//at, 'p_wy', 'p_wy = ε C_i I ρ_c g t_w/R_i', &
                     '@ × @ × @ × @ × @ × @/1000/@', [eps, c_i, factors%importance, &
                     shell%density, g_n, t_w, factors%r_i], eps*c_i*factors%importance* &
                     shell%density*g_n*t_w/1000/factors%r_i, 'Pa', ed//'5.3 (p_wy)')
        else
          p_wy = 0
          call report%note(code, 'the wall''s own inertia'//at//' (no &tank_structure: not '// &
                           'computed)', 'p_wy', 'p_wy = 0', 0.0_wp, 'Pa', ed//'5.3 (p_wy)')
        end if
        p_vy = report%add('hydrodynamic pressure of the vertical acceleration'//at, 'p_vy', &
                   'p_vy = ü_v q_hy, q_hy = ρ_L g (H_L − y)', '@ × @ × @ × (@ − @)', &
                   [u_v, rho, g_n, H, y], u_v*rho*g_n*(H - y), 'Pa', ed//'4.1.4, eq 4-14')
        p_y = report%add('total hydrodynamic pressure'//at, 'p_y', 'p_y = √((p_iy + p_wy)² + p_cy² + '// &
                  'p_vy²)', '√((@ + @)² + @² + @²)', [p_iy, p_wy, p_cy, p_vy], &
                  sqrt((p_iy + p_wy)**2 + p_cy**2 + p_vy**2), 'Pa', ed//'4.1.4, eq 4-16')
        call report%info(code, 'hydrodynamic pressure p_y'//at, ed//'eq 4-16', p_y, 'Pa')
        if (circular) then
          hoop = report%add('hydrodynamic hoop force per unit height'//at, 'N_y', 'N_y = p_y R', &
                     '@ × @', [p_y, tank%radius], p_y*tank%radius, 'N/m', ed//'5.3.2')
          call report%info(code, 'hydrodynamic hoop force p_y R'//at, ed//'5.3.2', hoop, 'N/m')
        end if
      end do
    end subroutine wall_pressures
  end subroutine aci350_design
end module sloshdyn_aci350_checks
