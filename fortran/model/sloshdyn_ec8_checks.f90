!> EN 1998-4:2006 Annex A for a circular tank (docs/design.md, "EN 1998-4"): the rigid tank's
!> masses and heights (A.2.1: the first sloshing mode and the impulsive series) or, with the
!> tank's structure, the simplified procedure for flexible tanks (A.3.2.2, Table A.2: the
!> impulsive period T_imp from the wall, T_con, the masses and heights), the impulsive
!> acceleration from the design spectrum with q (EN 1998-1:2004 3.2.2.5) and the convective
!> one from the 0.5 % elastic spectrum (beyond 4 s by EN 1998-1's informative Annex A), the
!> base shear and moments by the absolute sum (A.3.2.2), the sloshing wave d_max with the roof's
!> loads by the restricted-sloshing method where it exceeds the freeboard, and the pressure of
!> the vertical component on a rigid tank (A.3.3, with EN 1998-1 3.2.2.3's a_vg).
!>
!> Units: masses [kg], forces [N], moments [N m], pressures [Pa], lengths [m], accelerations in
!> g. The clause numbers are those design guides cite (the paid text was not at hand;
!> docs/design.md lists what could not be verified).
module sloshdyn_ec8_checks
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK
  use sloshdyn_vessel, only: tank_t
  use sloshdyn_design_codes, only: ec8_parameters, ec8_circular, ec8_table_a2, table_a2_range
  use sloshdyn_design_spectra, only: SPECTRUM_EC8, CONVECTIVE_RATIO, ec8_ground_parameters, &
                                     ec8_annex_a_periods
  use sloshdyn_text, only: num2str
  use sloshdyn_design_source, only: design_source_t, source_sa, source_impulsive_sa
  use sloshdyn_design_loads, only: design_factors_t
  use sloshdyn_design_report, only: design_report_t, pick
  use sloshdyn_tank_structure, only: tank_structure_t, shell_t, shell_of
  use sloshdyn_restricted_sloshing, only: restricted_sloshing
  use sloshdyn_tables, only: DESIGN_LOADS_COLUMNS, FREEBOARD_COLUMNS
  implicit none
  private
  public :: ec8_design

  character(len=*), parameter :: code = 'EC8-4', ed = 'EN 1998-4:2006 ', ec1 = 'EN 1998-1:2004 '
  !> EN 1998-1 Table 3.4: a_vg/a_g of the type 1 and type 2 vertical spectra.
  real(wp), parameter :: vertical_ratio(2) = [0.90_wp, 0.45_wp]

contains

  !> EN 1998-4 Annex A for the tank (liquid mass m [kg]), its structure or its lumped mass m_t
  !> at h_t, the factors and the source: the report's steps and checks and the rows of
  !> 'design_loads' and 'freeboard_check'.
  subroutine ec8_design(tank, liquid_mass, m_t, h_t, st, factors, source, report, loads, &
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
    type(ec8_parameters) :: ec8
    type(shell_t) :: shell
    real(wp) :: R, H, g_n, rho, gamma, m_i, m_c, h_i, h_c, hp_i, hp_c, t_imp, t_con, m_w, h_w, &
                m_r, h_r, a_i, a_c, d_max, m_conf, Q, M, Mp, row(8)
    logical :: simplified

    report%code = code           ! the steps of report%add and report%put are this code's
    loads = 0
    freeboard = 0
    call ec8_circular(tank%radius, tank%liquid_depth, tank%gravity, ec8, status, message)
    if (status /= SD_OK) return
    R = tank%radius
    H = tank%liquid_depth
    g_n = tank%gravity
    rho = liquid_mass/(pi*R**2*H)
    gamma = report%add('slenderness', 'γ', 'γ = H/R', '@/@', [H, R], H/R, '', ed//'A.2.1 (γ)')
    call report%note(code, 'mass of the liquid', 'm', 'm = ρ π R² H', liquid_mass, 'kg', &
                     ed//'A.2.1 (m)')
    simplified = st%given .and. gamma >= table_a2_range(1) .and. gamma <= table_a2_range(2)
    if (st%given) shell = shell_of(tank, st)
    if (st%given) row = ec8_table_a2(gamma)

    if (simplified) then
      ! --- the simplified procedure for flexible tanks (A.3.2.2, Table A.2)
      call report%note(code, 'the simplified procedure for a flexible tank (Table A.2, '// &
                       'linear between its rows in H/R)', 'H/R', 'Table A.2', gamma, '', &
                       ed//'A.3.2.2, Table A.2')
      m_i = report%add('impulsive mass', 'm_i', 'm_i = (m_i/m) m', '@ × @', [row(3), liquid_mass], &
                row(3)*liquid_mass, 'kg', ed//'Table A.2')
      m_c = report%add('convective mass', 'm_c', 'm_c = (m_c/m) m', '@ × @', [row(4), liquid_mass], &
                row(4)*liquid_mass, 'kg', ed//'Table A.2')
      h_i = report%add('impulsive height, EBP', 'h_i', 'h_i = (h_i/H) H', '@ × @', [row(5), H], row(5)*H, &
                'm', ed//'Table A.2')
      h_c = report%add('convective height, EBP', 'h_c', 'h_c = (h_c/H) H', '@ × @', [row(6), H], &
                row(6)*H, 'm', ed//'Table A.2')
      hp_i = report%add('impulsive height, IBP', 'h_i''', 'h_i'' = (h_i''/H) H', '@ × @', [row(7), H], &
                 row(7)*H, 'm', ed//'Table A.2')
      hp_c = report%add('convective height, IBP', 'h_c''', 'h_c'' = (h_c''/H) H', '@ × @', [row(8), H], &
                 row(8)*H, 'm', ed//'Table A.2')
      t_con = report%add('convective period', 'T_con', 'T_con = C_c √R', '@ × √@', [row(2), R], &
                  row(2)*sqrt(R), 's', ed//'A.3.2.2 (T_con)')
    else
      ! --- the rigid tank (A.2.1): the first sloshing mode and the impulsive series
      if (st%given) call report%note(code, 'H/R outside Table A.2''s 0.3 to 3: the rigid '// &
                                     'tank''s masses and heights of A.2.1', 'H/R', 'A.2.1', &
                                     gamma, '', ed//'A.3.2.2')
      m_i = report%add('impulsive mass (the series of the impulsive pressure''s resultant)', 'm_i', &
                'm_i = 2 γ m Σ I₁(ν_n/γ)/(ν_n³ I₁''(ν_n/γ)), ν_n = (2n + 1)π/2', '2 × @ × @ × Σ', &
                [gamma, liquid_mass], ec8%impulsive_ratio*liquid_mass, 'kg', ed//'A.2.1')
      m_c = report%add('convective mass of the first mode', 'm_c', &
                'm_c = 2 tanh(λ₁ γ)/(γ λ₁ (λ₁² − 1)) m, λ₁ = 1.841', &
                '2 × tanh(1.841 × @)/(@ × 1.841 × (1.841² − 1)) × @', [gamma, gamma, liquid_mass], &
                ec8%convective_ratio*liquid_mass, 'kg', ed//'A.2.1')
      h_i = report%add('impulsive height, EBP (the wall pressure''s resultant)', 'h_i', &
                'h_i = H Σ a_n (1 − (−1)ⁿ/ν_n)/Σ a_n', '@ × Σ', [H], ec8%impulsive_height, 'm', &
                ed//'A.2.1')
      h_c = report%add('convective height, EBP', 'h_c', &
                'h_c = H [1 − (cosh(λ₁ γ) − 1)/(λ₁ γ sinh(λ₁ γ))]', &
                '@ × (1 − (cosh(1.841 × @) − 1)/(1.841 × @ × sinh(1.841 × @)))', &
                [H, gamma, gamma, gamma], ec8%convective_height, 'm', ed//'A.2.1')
      hp_i = report%add('impulsive height, IBP (with the base pressure)', 'h_i''', &
                 'h_i'' = h_i + R Σ (−1)ⁿ I₂(ν_n/γ)/(ν_n³ I₁''(ν_n/γ))/Σ a_n', '@ + @ × Σ', &
                 [ec8%impulsive_height, R], ec8%impulsive_height_ibp, 'm', ed//'A.2.1')
      hp_c = report%add('convective height, IBP', 'h_c''', &
                 'h_c'' = H [1 − (cosh(λ₁ γ) − 2)/(λ₁ γ sinh(λ₁ γ))]', &
                 '@ × (1 − (cosh(1.841 × @) − 2)/(1.841 × @ × sinh(1.841 × @)))', &
                 [H, gamma, gamma, gamma], ec8%convective_height_ibp, 'm', ed//'A.2.1')
      t_con = report%add('period of the first sloshing mode', 'T_c1', &
                  'T_c1 = 2π/√(g λ₁/R tanh(λ₁ γ))', '2π/√(@ × 1.841/@ × tanh(1.841 × @))', &
                  [g_n, R, gamma], ec8%convective_period, 's', ed//'A.2.1')
    end if

    ! --- the wall and roof, or the lumped mass
    t_imp = factors%impulsive_period
    if (st%given) then
      m_w = report%add('mass of the tank wall', 'm_w', 'm_w = Σ m_j (the courses)', '@', &
                [shell%shell_mass], shell%shell_mass, 'kg', ed//'A.3.2.2 (m_w)')
      h_w = report%add('height of the wall''s centre of gravity', 'h_w', 'h_w = Σ m_j (z_j + h_j/2)/Σ m_j', &
                '@', [shell%shell_height], shell%shell_height, 'm', ed//'A.3.2.2 (h_w)')
      m_r = report%add('mass of the roof', 'm_r', 'm_r (&tank_structure roof_mass)', '@', [st%roof_mass], &
                st%roof_mass, 'kg', ed//'A.3.2.2 (m_r)')
      h_r = report%add('height of the roof''s centre of gravity', 'h_r', 'h_r (&tank_structure '// &
                'roof_mass_height; 0: the shell''s top)', '@', [shell%roof_height], &
                shell%roof_height, 'm', ed//'A.3.2.2 (h_r)')
      if (t_imp == 0) call impulsive_period()
    else
      m_w = report%add('mass of the wall and roof, lumped (no &tank_structure)', 'm_w', 'm_w = m_t', '@', &
                [m_t], m_t, 'kg', ed//'A.3.2.2 (m_w, m_r)')
      h_w = report%add('height of the lumped wall and roof', 'h_w', 'h_w = h_t', '@', [h_t], h_t, 'm', &
                ed//'A.3.2.2 (h_w)')
      m_r = 0
      h_r = 0
    end if

    ! --- accelerations: impulsive with q (EN 1998-1 3.2.2.5), convective elastic at 0.5 %
    call accelerations()
    if (status /= SD_OK) return

    ! --- the sloshing wave (A.2.1) and the roof where it reaches it
    d_max = report%add('maximum vertical displacement of the liquid surface at the wall', 'd_max', &
                'd_max = 0.84 R Se(T_c)/g', '0.84 × @ × @', [R, a_c], 0.84_wp*R*a_c, 'm', &
                ed//'A.2.1')
    call report%check(code, 'freeboard: d_max ≤ available', ed//'A.2.1', d_max, &
                      tank%freeboard, 'm')
    freeboard = [t_con, a_c, d_max, d_max, tank%freeboard, tank%freeboard - d_max, &
                 merge(1.0_wp, 0.0_wp, d_max <= tank%freeboard*(1 + 1.0e-9_wp))]
    call restricted_sloshing(report, code, 'd_max, '//ed//'A.2.1', tank, d_max, rho, m_c, &
                             m_conf, status, message)
    if (status /= SD_OK) return

    ! --- base shear and moments, absolute sum (A.3.2.2)
    Q = report%add('base shear (the confined mass impulsive)', 'Q', &
            'Q = (m_i + m_conf + m_w + m_r) Se(T_imp) g + (m_c − m_conf) Se(T_con) g', &
            '(@ + @ + @ + @) × @ × @ + (@ − @) × @ × @', &
            [m_i, m_conf, m_w, m_r, a_i, g_n, m_c, m_conf, a_c, g_n], &
            (m_i + m_conf + m_w + m_r)*a_i*g_n + (m_c - m_conf)*a_c*g_n, 'N', ed//'A.3.2.2')
    M = report%add('overturning moment above the base plate (EBP)', 'M', &
            'M = (m_i h_i + m_conf h_c + m_w h_w + m_r h_r) Se(T_imp) g + (m_c − m_conf) h_c '// &
            'Se(T_con) g', '(@ × @ + @ × @ + @ × @ + @ × @) × @ × @ + (@ − @) × @ × @ × @', &
            [m_i, h_i, m_conf, h_c, m_w, h_w, m_r, h_r, a_i, g_n, m_c, m_conf, h_c, a_c, g_n], &
            (m_i*h_i + m_conf*h_c + m_w*h_w + m_r*h_r)*a_i*g_n + (m_c - m_conf)*h_c*a_c*g_n, &
            'N m', ed//'A.3.2.2')
    Mp = report%add('overturning moment below the base plate (IBP)', 'M''', &
             'M'' = (m_i h_i'' + m_conf h_c'' + m_w h_w + m_r h_r) Se(T_imp) g + (m_c − m_conf) '// &
             'h_c'' Se(T_con) g', '(@ × @ + @ × @ + @ × @ + @ × @) × @ × @ + (@ − @) × @ × @ × @', &
             [m_i, hp_i, m_conf, hp_c, m_w, h_w, m_r, h_r, a_i, g_n, m_c, m_conf, hp_c, a_c, g_n], &
             (m_i*hp_i + m_conf*hp_c + m_w*h_w + m_r*h_r)*a_i*g_n + &
             (m_c - m_conf)*hp_c*a_c*g_n, 'N m', ed//'A.3.2.2')
    call report%info(code, 'base shear Q', ed//'A.3.2.2', Q, 'N')
    call report%info(code, 'overturning moment M (EBP)', ed//'A.3.2.2', M, 'N m')
    call report%info(code, 'overturning moment M'' (IBP)', ed//'A.3.2.2', Mp, 'N m')
    loads = [t_imp, t_con, a_i, a_c, m_i + m_conf, m_c - m_conf, m_w + m_r, &
             (m_i*h_i + m_conf*h_c)/(m_i + m_conf), h_c, (m_i*hp_i + m_conf*hp_c)/(m_i + m_conf), &
             hp_c, merge((m_w*h_w + m_r*h_r)/(m_w + m_r), 0.0_wp, m_w + m_r > 0), &
             (m_i + m_conf + m_w + m_r)*a_i*g_n, (m_c - m_conf)*a_c*g_n, Q, M, Mp]

    call vertical_pressure()

  contains

    !> A.3.2.2: T_imp = C_i sqrt(rho) H/(sqrt(s/R) sqrt(E)), s the wall's thickness averaged
    !> over the wetted height, C_i of Table A.2 (its end row outside 0.3 <= H/R <= 3).
    subroutine impulsive_period()
      real(wp) :: s
      call report%note(code, 'impulsive period coefficient (Table A.2'// &
                       trim(pick('               ', ', the end row', simplified))//')', 'C_i', &
                       'C_i(H/R)', row(1), '', ed//'Table A.2')
      s = report%add('equivalent uniform thickness of the wall', 's', &
              's = Σ t_j (wetted height of course j)/H', '@/1000', [shell%uniform_thickness], &
              shell%uniform_thickness/1000, 'm', ed//'A.3.2.2 (s)')
      t_imp = report%add('impulsive period', 'T_imp', 'T_imp = C_i √ρ H/(√(s/R) √E)', &
                  '@ × √@ × @/(√(@/@) × √(@ × 10⁶))', [row(1), rho, H, s, R, shell%modulus], &
                  row(1)*sqrt(rho)*H/(sqrt(s/R)*sqrt(shell%modulus*1.0e6_wp)), 's', &
                  ed//'A.3.2.2 (T_imp)')
      call report%info(code, 'impulsive period T_imp', ed//'A.3.2.2', t_imp, 's')
    end subroutine impulsive_period

    !> Se(T_imp) from the design spectrum with q (EN 1998-1 3.2.2.5; on the plateau without a
    !> period; a ground motion: its peak or Sa(T_imp), divided by q) and Se(T_con) elastic at
    !> 0.5 % (EN 1998-1 3.2.2.2, beyond 4 s its Annex A).
    subroutine accelerations()
      call source_impulsive_sa(source, SPECTRUM_EC8, t_imp, factors%impulsive_damping_ratio, &
                               .true., a_i, status, message)
      if (status /= SD_OK) return
      call source_sa(source, SPECTRUM_EC8, t_con, CONVECTIVE_RATIO, a_c, status, message)
      if (status /= SD_OK) return
      if (source%from_ground) then
        call report%note(code, 'impulsive spectral acceleration (the ground motion''s '// &
                         trim(pick('peak: the rigid tank', 'Sa(T_imp, 5 %)    ', t_imp == 0))// &
                         ', divided by q = '//trim(adjustl(fixed(source%spec%q)))//')', &
                         'Se(T_imp)', 'Sa/q', a_i, 'g', ec1//'3.2.2.5')
        call report%note(code, 'convective spectral acceleration (the ground motion''s 0.5 % '// &
                         'spectrum)', 'Se(T_con)', 'Sa(T_con, 0.5 %)', a_c, 'g', ed//'A.3.2.2')
      else
        call spectrum_steps(t_imp, .true., a_i)
        call spectrum_steps(t_con, .false., a_c)
      end if
    end subroutine accelerations

    !> The steps of EN 1998-1's spectrum at period T: the ground's S, T_B, T_C, T_D (Table
    !> 3.2/3.3), the design spectrum with q (impulsive: eq 3.13-3.16; on the plateau without a
    !> period) or the elastic one at 0.5 % (eta of eq 3.6; eq 3.2-3.5, beyond 4 s Annex A's
    !> eq A.1-A.3 with Table A.1 and eq 3.7); value: the source's Sa [g] (sloshdyn_design_spectra).
    subroutine spectrum_steps(period, design, value)
      real(wp), intent(in) :: period, value
      logical, intent(in) :: design
      real(wp) :: p(4), a_g, eta, t_e, t_f, t, x
      character(len=:), allocatable :: what, table
      p = ec8_ground_parameters(source%spec)
      a_g = source%spec%gamma_i*source%spec%a_gr
      t = period
      if (design .and. t == 0) t = p(3)
      table = trim(pick('Table 3.2', 'Table 3.3', source%spec%ec8_type == 1))
      if (design) then
        what = 'impulsive spectral acceleration, the design spectrum with q = '// &
               trim(adjustl(fixed(source%spec%q)))//trim(pick(' (on its plateau: T = T_C)', &
                                                              '', period == 0))
        call report%note(code, 'design ground acceleration', 'a_g', 'a_g = γ_I a_gR', a_g, 'g', &
                         ec1//'3.2.1(3)')
        call report%note(code, 'soil factor S and corner periods T_B, T_C, T_D = '// &
                         num2str(p(2))//', '//num2str(p(3))//', '//num2str(p(4))//' s', 'S', &
                         'ground type, spectrum type', p(1), '', ec1//table)
        if (t <= p(2)) then
          x = report%add(what, 'Sd(T_imp)', 'Sd = a_g S [2/3 + T/T_B (2.5/q − 2/3)]', &
                  '@ × @ × (2/3 + @/@ × (2.5/@ − 2/3))', [a_g, p(1), t, p(2), source%spec%q], &
                  value, 'g', ec1//'3.2.2.5, eq 3.13')
        else if (t <= p(3)) then
          x = report%add(what, 'Sd(T_imp)', 'Sd = a_g S 2.5/q', '@ × @ × 2.5/@', &
                  [a_g, p(1), source%spec%q], value, 'g', ec1//'3.2.2.5, eq 3.14')
        else if (t <= p(4)) then
          x = report%add(what, 'Sd(T_imp)', 'Sd = a_g S 2.5/q T_C/T ≥ β a_g', &
                  'max(@ × @ × 2.5/@ × @/@, @ × @)', [a_g, p(1), source%spec%q, p(3), t, &
                  source%spec%beta, a_g], value, 'g', ec1//'3.2.2.5, eq 3.15')
        else
          x = report%add(what, 'Sd(T_imp)', 'Sd = a_g S 2.5/q T_C T_D/T² ≥ β a_g', &
                  'max(@ × @ × 2.5/@ × @ × @/@², @ × @)', [a_g, p(1), source%spec%q, p(3), &
                  p(4), t, source%spec%beta, a_g], value, 'g', ec1//'3.2.2.5, eq 3.16')
        end if
        return
      end if
      what = 'convective spectral acceleration, the elastic spectrum at 0.5 %'
      eta = report%add('damping correction factor at 0.5 %', 'η', 'η = √(10/(5 + ξ)) ≥ 0.55, ξ = 0.5', &
                'max(√(10/(5 + 0.5)), 0.55)', [real(wp) ::], max(sqrt(10/5.5_wp), 0.55_wp), '', &
                ec1//'3.2.2.2, eq 3.6')
      if (t <= p(2)) then
        x = report%add(what, 'Se(T_con)', 'Se = a_g S [1 + T/T_B (2.5 η − 1)]', &
                '@ × @ × (1 + @/@ × (2.5 × @ − 1))', [a_g, p(1), t, p(2), eta], value, 'g', &
                ec1//'3.2.2.2, eq 3.2')
      else if (t <= p(3)) then
        x = report%add(what, 'Se(T_con)', 'Se = a_g S η 2.5', '@ × @ × @ × 2.5', [a_g, p(1), eta], &
                value, 'g', ec1//'3.2.2.2, eq 3.3')
      else if (t <= p(4)) then
        x = report%add(what, 'Se(T_con)', 'Se = a_g S η 2.5 T_C/T', '@ × @ × @ × 2.5 × @/@', &
                [a_g, p(1), eta, p(3), t], value, 'g', ec1//'3.2.2.2, eq 3.4')
      else if (t <= 4) then
        x = report%add(what, 'Se(T_con)', 'Se = a_g S η 2.5 T_C T_D/T²', '@ × @ × @ × 2.5 × @ × @/@²', &
                [a_g, p(1), eta, p(3), p(4), t], value, 'g', ec1//'3.2.2.2, eq 3.5')
      else
        t_e = ec8_annex_a_periods(source%spec%ground_type, 1)
        t_f = ec8_annex_a_periods(source%spec%ground_type, 2)
        call report%note(code, 'T > 4 s: the informative Annex A''s displacement spectrum '// &
                         'S_De, corner periods T_E = '//num2str(t_e)//' s, T_F = '// &
                         num2str(t_f)//' s (Table A.1, given for type 1; used for both)', &
                         'T_E', 'Table A.1', t_e, 's', ec1//'Annex A, Table A.1')
        if (t <= t_e) then
          x = report%add(what//' (T ≤ T_E)', 'Se(T_con)', 'S_De = Se (T/2π)², Se = a_g S η 2.5 T_C '// &
                  'T_D/T²', '@ × @ × @ × 2.5 × @ × @/@²', [a_g, p(1), eta, p(3), p(4), t], &
                  value, 'g', ec1//'Annex A, eq A.1')
        else if (t <= t_f) then
          x = report%add(what//' (T_E < T ≤ T_F)', 'Se(T_con)', 'Se = S_De (2π/T)², S_De = 0.025 '// &
                  'a_g S T_C T_D [2.5 η + (T − T_E)/(T_F − T_E) (1 − 2.5 η)]', &
                  '0.025 × @ × @ × @ × @ × (2.5 × @ + (@ − @)/(@ − @) × (1 − 2.5 × @)) × '// &
                  '(2π/@)²', [a_g, p(1), p(3), p(4), eta, t, t_e, t_f, t_e, eta, t], value, &
                  'g', ec1//'Annex A, eq A.2, eq 3.7')
        else
          x = report%add(what//' (T > T_F)', 'Se(T_con)', 'Se = d_g (2π/T)², d_g = 0.025 a_g S '// &
                  'T_C T_D', '0.025 × @ × @ × @ × @ × (2π/@)²', [a_g, p(1), p(3), p(4), t], &
                  value, 'g', ec1//'Annex A, eq A.3, eq 3.12, eq 3.7')
        end if
      end if
    end subroutine spectrum_steps

    !> A.3.3: a rigid tank under the vertical ground acceleration a_v (EN 1998-1 3.2.2.3:
    !> a_vg = 0.90 a_g type 1, 0.45 a_g type 2; the purchaser's; none from a ground motion,
    !> which has no vertical component here): p_v = rho H (1 - z/H) a_v g, largest at the base.
    subroutine vertical_pressure()
      real(wp) :: a_v, p_v, p(4)
      if (.not. factors%vertical) then
        call report%note(code, 'vertical component (&design vertical = .false.): not '// &
                         'considered', 'a_v', 'a_v = 0', 0.0_wp, 'g', ed//'A.3.3')
        return
      end if
      if (factors%vertical_acceleration > 0) then
        a_v = report%add('vertical design acceleration (the purchaser''s)', 'a_v', &
                  'a_v (&design vertical_acceleration)', '@', [factors%vertical_acceleration], &
                  factors%vertical_acceleration, 'g', ed//'A.3.3')
      else if (source%from_ground) then
        call report%note(code, 'vertical component: the ground motion is horizontal only '// &
                         '(&design vertical_acceleration gives one)', 'a_v', 'a_v = 0', 0.0_wp, &
                         'g', ed//'A.3.3')
        return
      else
        p = ec8_ground_parameters(source%spec)
        a_v = report%add('design vertical ground acceleration (rigid tank: the vertical spectrum at T = 0)', &
                  'a_vg', 'a_vg = '//trim(pick('0.90', '0.45', source%spec%ec8_type == 1))// &
                  ' a_g', trim(pick('0.90', '0.45', source%spec%ec8_type == 1))//' × @', &
                  [source%spec%gamma_i*source%spec%a_gr], &
                  vertical_ratio(source%spec%ec8_type)*source%spec%gamma_i*source%spec%a_gr, &
                  'g', ec1//'3.2.2.3, Table 3.4')
      end if
      p_v = report%add('pressure of the vertical component at the base (rigid tank)', 'p_v', &
                'p_v = ρ H a_v g (1 − z/H), z = 0', '@ × @ × @ × @', [rho, H, a_v, g_n], &
                rho*H*a_v*g_n, 'Pa', ed//'A.3.3')
      call report%info(code, 'pressure of the vertical component at the base', ed//'A.3.3', &
                       p_v, 'Pa')
    end subroutine vertical_pressure
  end subroutine ec8_design

  !> A short fixed-point text (the behaviour factor in a sentence).
  pure function fixed(x) result(text)
    real(wp), intent(in) :: x
    character(len=16) :: text
    write (text, '(f0.2)') x
  end function fixed
end module sloshdyn_ec8_checks
