!> Seismic loads and freeboard of a tank in the format of the design codes (docs/design.md):
!> impulsive and convective base shears, their combination, and the overturning moments
!> excluding (EBP: the wall's, API 650's ringwall moment M_rw, ACI 350.3's M_b) and including
!> the base pressure (IBP: API 650's slab moment M_s, ACI 350.3's M_o), from each code's
!> design coefficients (accelerations in g, factors already applied); and API 650's sloshing
!> wave acceleration A_f and required freeboard (E.7.2, Table E-7).
!>
!> The codes' load formulas share one form (API 650 E.6.1, ACI 350.3-06 sec 4, EN 1998-4 A.3.2):
!>     P_i = a_i g (m_i + m_t),  P_c = a_c g m_c,
!>     M   = combine(a_i g (m_i h_i + m_t h_t), a_c g m_c h_c)   (h' in place of h for IBP),
!> with the tank's own mass m_t (shell and roof) at height h_t, combined by the square root of
!> the sum of squares (API 650 eq E.6.1-1, E.6.1.5-1/-2; ACI 350.3 eq 4-5, 4-10, 4-13) or by
!> the absolute sum (EN 1998-4 A.3.2.2, the simplified procedure's rule).
module sloshdyn_design_loads
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, check_real
  use sloshdyn_text, only: num2str
  implicit none
  private
  public :: design_factors_t, check_factors, code_loads, api650_af, api650_required_freeboard, &
            LOADS_SIZE, table_e5_importance, wall_pressure_names, WALL_PRESSURE_CODE, &
            WALL_PRESSURE_ELASTIC

  !> The loads of code_loads: [P_i, P_c, V, M (EBP), M' (IBP)] [N, N, N, N m, N m].
  integer, parameter :: LOADS_SIZE = 5

  !> The accelerations of the design check's wall pressure: each code's design accelerations,
  !> or the elastic spectrum's at sloshdyn's periods (labelled elastic).
  integer, parameter :: WALL_PRESSURE_CODE = 1, WALL_PRESSURE_ELASTIC = 2
  character(len=*), parameter :: wall_pressure_names(2) = [character(len=8) :: 'code', &
                                                           'elastic']
  !> API 650 Table E-5: the importance factor I of seismic use groups I, II, III.
  real(wp), parameter :: table_e5_importance(3) = [1.0_wp, 1.25_wp, 1.5_wp]

  !> The factors of the codes (&design): importance I (API 650 Table E-5, ACI 350.3 Table
  !> 4.1.1(a)), API 650's seismic use group (E.3.1: 1..3) and response modification factors
  !> R_wi, R_wc (Table E-4: 3.5 and 2 for a self-anchored tank; 4 and 2 mechanically
  !> anchored; r_wi = 0: by the structure's anchorage), ACI 350.3's R_i, R_c (Table 4.1.1(b):
  !> 2.0 fixed or hinged base, R_c = 1.0); the impulsive period [s] (0: from the structure where
  !> the code uses it, else on the plateau of the spectrum, as the codes assume for a tank
  !> without a computed one; with a record: the rigid tank, Sa = PGA) and damping ratio; the
  !> height of the tank's own mass [m] (0: half the shell, (H + freeboard)/2); whether the
  !> codes' vertical accelerations count, and the purchaser's vertical acceleration [g] (0: each
  !> code's own); the accelerations of the wall pressure (WALL_PRESSURE_*).
  type :: design_factors_t
    real(wp) :: importance = 1
    integer :: use_group = 1
    real(wp) :: r_wi = 0, r_wc = 2, r_i = 2, r_c = 1
    real(wp) :: impulsive_period = 0, impulsive_damping_ratio = 0.05_wp
    real(wp) :: tank_mass_height = 0
    logical :: vertical = .true.
    real(wp) :: vertical_acceleration = 0
    integer :: wall_pressure = WALL_PRESSURE_CODE
  end type design_factors_t

contains

  !> The factors in their ranges (the message names the variable, its value and the clause).
  pure subroutine check_factors(f, status, message)
    type(design_factors_t), intent(in) :: f
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    status = SD_OK
    message = ''
    if (f%use_group < 1 .or. f%use_group > 3) then
      status = SD_BAD_INPUT
      message = 'use_group = '//num2str(f%use_group)//' is out of range: 1, 2 or 3 (API 650 '// &
                'E.3.1, seismic use group I, II, III)'
      return
    end if
    call check_real('importance', f%importance, table_e5_importance(f%use_group), 3.0_wp, &
                    .false., .false., 'I must be in ['// &
                    num2str(table_e5_importance(f%use_group))//', 3] for use_group = '// &
                    num2str(f%use_group)//' (API 650 13th ed. Table E-5: 1.0, 1.25, 1.5 for '// &
                    'SUG I, II, III; a higher I is the purchaser''s choice)', status, message)
    if (f%r_wi /= 0) call check_real('r_wi', f%r_wi, 1.0_wp, 10.0_wp, .false., .false., &
                                     'R_wi must be 0 (by the anchorage) or in [1, 10] (API '// &
                                     '650 Table E-4: 3.5 self-anchored, 4 mechanically '// &
                                     'anchored)', status, message)
    call check_real('r_wc', f%r_wc, 1.0_wp, 10.0_wp, .false., .false., 'R_wc must be in '// &
                    '[1, 10] (API 650 Table E-4: 2)', status, message)
    call check_real('r_i', f%r_i, 1.0_wp, 10.0_wp, .false., .false., 'R_i must be in [1, 10] '// &
                    '(ACI 350.3 Table 4.1.1(b))', status, message)
    call check_real('r_c', f%r_c, 1.0_wp, 10.0_wp, .false., .false., 'R_c must be in [1, 10] '// &
                    '(ACI 350.3 Table 4.1.1(b): 1.0)', status, message)
    call check_real('impulsive_period', f%impulsive_period, 0.0_wp, 4.0_wp, .false., .false., &
                    'the impulsive period must be in [0, 4] [s] (0: from the structure, or '// &
                    'the plateau)', status, message)
    call check_real('impulsive_damping_ratio', f%impulsive_damping_ratio, 0.0_wp, 0.3_wp, &
                    .true., .false., 'the impulsive damping ratio must be in (0, 0.3] (a '// &
                    'ratio of critical: 0.05 for 5 %)', status, message)
    call check_real('tank_mass_height', f%tank_mass_height, 0.0_wp, 1.0e4_wp, .false., &
                    .false., 'the height of the tank''s mass must be in [0, 1e4] [m] (0: half '// &
                    'the shell; at most the tank''s height, checked with the tank)', status, &
                    message)
    call check_real('vertical_acceleration', f%vertical_acceleration, 0.0_wp, 3.0_wp, .false., &
                    .false., 'the vertical design acceleration must be in [0, 3] [g] (0: each '// &
                    'code''s own)', status, message)
    if (status == SD_OK .and. (f%wall_pressure < WALL_PRESSURE_CODE .or. &
                               f%wall_pressure > WALL_PRESSURE_ELASTIC)) then
      status = SD_BAD_INPUT
      message = 'wall_pressure = '//num2str(f%wall_pressure)//' is out of range: code or elastic'
    end if
  end subroutine check_factors

  !> The codes' loads [P_i, P_c, V, M, M'] from the design coefficients a_i, a_c [g], the
  !> masses m_i, m_c, m_t [kg], the heights h_i, h_c (EBP), hp_i, hp_c (IBP), h_t [m] and g
  !> [m/s^2]; srss: combine by the square root of the sum of squares, else the absolute sum.
  pure function code_loads(a_i, a_c, m_i, m_c, m_t, h_i, h_c, hp_i, hp_c, h_t, gravity, srss) &
    result(loads)
    real(wp), intent(in) :: a_i, a_c, m_i, m_c, m_t, h_i, h_c, hp_i, hp_c, h_t, gravity
    logical, intent(in) :: srss
    real(wp) :: loads(LOADS_SIZE)
    loads = [a_i*gravity*(m_i + m_t), a_c*gravity*m_c, &
             combine(a_i*gravity*(m_i + m_t), a_c*gravity*m_c), &
             combine(a_i*gravity*(m_i*h_i + m_t*h_t), a_c*gravity*m_c*h_c), &
             combine(a_i*gravity*(m_i*hp_i + m_t*h_t), a_c*gravity*m_c*hp_c)]
  contains
    pure real(wp) function combine(impulsive, convective)
      real(wp), intent(in) :: impulsive, convective
      if (srss) then
        combine = sqrt(impulsive**2 + convective**2)
      else
        combine = abs(impulsive) + abs(convective)
      end if
    end function combine
  end function code_loads

  !> API 650 E.7.2: the acceleration coefficient of the sloshing wave A_f [g] from the ASCE 7
  !> values S_D1 [g] and T_L [s], K, I and the convective period T_c [s]: seismic use group I
  !> and II: eq E.7.2-2 (T_c <= 4 s) and E.7.2-3 (T_c > 4 s); III: eq E.7.2-4 (T_c <= T_L)
  !> and E.7.2-5 (T_c > T_L).
  elemental real(wp) function api650_af(s_d1, t_l, k, importance, use_group, t_c) result(af)
    real(wp), intent(in) :: s_d1, t_l, k, importance, t_c
    integer, intent(in) :: use_group
    real(wp) :: t_limit
    t_limit = merge(t_l, 4.0_wp, use_group >= 3)
    if (t_c <= t_limit) then
      af = k*s_d1*importance/t_c
    else
      af = k*s_d1*importance*t_limit/t_c**2
    end if
  end function api650_af

  !> API 650 Table E-7: the freeboard required [m] for the sloshing wave height delta_s [m]
  !> (eq E.7.2-1) by seismic use group and S_DS [g]: SUG I none (0.7 delta_s recommended,
  !> note a); SUG II 0.7 delta_s when S_DS >= 0.33 g (note b), none below; SUG III delta_s
  !> (note c). Where it is not provided, the notes require secondary containment or a roof and
  !> shell designed for the sloshing liquid.
  elemental real(wp) function api650_required_freeboard(delta_s, s_ds, use_group) result(f)
    real(wp), intent(in) :: delta_s, s_ds
    integer, intent(in) :: use_group
    select case (use_group)
    case (3)
      f = delta_s
    case (2)
      f = merge(0.7_wp*delta_s, 0.0_wp, s_ds >= 0.33_wp)
    case default
      f = 0
    end select
  end function api650_required_freeboard
end module sloshdyn_design_loads
