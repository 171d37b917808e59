!> Elastic design spectra of the codes, as pure functions of the period T [s] and the damping
!> ratio zeta (a ratio of critical: 0.05 for 5 %, the one convention of every damping in
!> sloshdyn), returning the spectral acceleration Sa in units of g (docs/design.md):
!>
!> - ASCE 7-16 sec 11.4.6 (the spectrum API 650 Annex E uses, E.4.6.1), from the design values
!>   S_DS [g], S_D1 [g] and the long-period transition T_L [s] (given, not mapped): 5 % damping;
!>   0.5 % damping (the convective response) by API 650's factor K (1.5 unless told, E.4.6.1).
!> - ACI 350.3-06 sec 9.4 (the same S_DS, S_D1): C_i (impulsive, 5 %, eq 9-32/9-33) and C_c
!>   (convective, 0.5 %, eq 9-34/9-35).
!> - EN 1998-1:2004 sec 3.2.2.2, type 1 or 2, ground types A-E (Tables 3.2, 3.3), elastic
!>   (eq 3.2-3.5) with the damping correction eta = sqrt(10/(5 + xi)) >= 0.55, xi = 100 zeta
!>   in % (eq 3.6), to 4 s (3.2.2.1(2)) and beyond 4 s by the informative Annex A (the elastic
!>   displacement spectrum S_De of eq A.1-A.3 with Table A.1's T_E, T_F, and Se = S_De
!>   (2 pi/T)^2, eq 3.7); a_g = gamma_I a_gR (3.2.1(3)); and the design spectrum with the
!>   behaviour factor q (sec 3.2.2.5, eq 3.13-3.16, lower bound beta a_g, beta = 0.2).
!>
!> A damping a code does not tabulate, a period outside a spectrum's range or a parameter out of
!> range is refused with its clause (status SD_BAD_INPUT), never extrapolated.
module sloshdyn_design_spectra
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, check_real
  use sloshdyn_text, only: num2str
  implicit none
  private
  public :: design_spectrum_t, check_spectrum, spectrum_sa, plateau_sa, ec8_design_sa, &
            spectrum_kinds, ground_types, SPECTRUM_ASCE7, SPECTRUM_ACI350, SPECTRUM_EC8, &
            ec8_ground_parameters, ec8_long_periods, ec8_annex_a_periods, is_tabulated, &
            IMPULSIVE_RATIO, &
            CONVECTIVE_RATIO

  !> The kinds of spectrum, by code (index): ASCE 7 (API 650), ACI 350.3, EN 1998-1.
  integer, parameter :: SPECTRUM_ASCE7 = 1, SPECTRUM_ACI350 = 2, SPECTRUM_EC8 = 3
  character(len=*), parameter :: spectrum_kinds(3) = [character(len=6) :: 'asce7', 'aci350', &
                                                      'ec8']
  !> EN 1998-1 ground types, by code (index).
  character(len=*), parameter :: ground_types(5) = [character(len=1) :: 'A', 'B', 'C', 'D', 'E']
  !> The damping ratios the ASCE 7 / API 650 and ACI 350.3 spectra tabulate: 5 % (impulsive)
  !> and 0.5 % (convective).
  real(wp), parameter :: IMPULSIVE_RATIO = 0.05_wp, CONVECTIVE_RATIO = 0.005_wp
  !> EN 1998-1 3.2.2.1(2): the elastic spectrum's formulas are given up to 4 s; beyond, the
  !> informative Annex A's displacement spectrum (ec8_long_periods).
  real(wp), parameter :: ec8_t_max = 4
  !> EN 1998-1 Annex A, Table A.1: the corner periods T_E, T_F [s] of the displacement spectrum
  !> for ground types A..E (given for the type 1 spectrum; used for type 2 as well, see
  !> docs/design.md).
  real(wp), parameter :: ec8_annex_a(2, 5) = reshape([4.5_wp, 10.0_wp, 5.0_wp, 10.0_wp, &
    6.0_wp, 10.0_wp, 6.0_wp, 10.0_wp, 6.0_wp, 10.0_wp], [2, 5])
  !> EN 1998-1 Table 3.2 (type 1) and Table 3.3 (type 2): S, T_B, T_C, T_D [s] for A..E.
  real(wp), parameter :: ec8_type1(4, 5) = reshape([ &
    1.0_wp, 0.15_wp, 0.4_wp, 2.0_wp, 1.2_wp, 0.15_wp, 0.5_wp, 2.0_wp, &
    1.15_wp, 0.20_wp, 0.6_wp, 2.0_wp, 1.35_wp, 0.20_wp, 0.8_wp, 2.0_wp, &
    1.4_wp, 0.15_wp, 0.5_wp, 2.0_wp], [4, 5])
  real(wp), parameter :: ec8_type2(4, 5) = reshape([ &
    1.0_wp, 0.05_wp, 0.25_wp, 1.2_wp, 1.35_wp, 0.05_wp, 0.25_wp, 1.2_wp, &
    1.5_wp, 0.10_wp, 0.25_wp, 1.2_wp, 1.8_wp, 0.10_wp, 0.30_wp, 1.2_wp, &
    1.6_wp, 0.05_wp, 0.25_wp, 1.2_wp], [4, 5])

  !> A code's design spectrum. ASCE 7 and ACI 350.3: s_ds, s_d1 [g], t_l [s] (ASCE 7 only) and
  !> k (API 650's 5 % -> 0.5 % factor). EN 1998-1: a_gr [g] (reference peak ground
  !> acceleration on type A ground), gamma_i (importance factor gamma_I), ground_type (1..5: A..E), ec8_type
  !> (1 or 2), q (behaviour factor of the design spectrum, impulsive part) and beta (its lower
  !> bound factor).
  type :: design_spectrum_t
    integer :: kind = SPECTRUM_ASCE7
    real(wp) :: s_ds = 0, s_d1 = 0, t_l = 0, k = 1.5_wp
    real(wp) :: a_gr = 0, gamma_i = 1
    integer :: ground_type = 1, ec8_type = 1
    real(wp) :: q = 1, beta = 0.2_wp
  end type design_spectrum_t

contains

  !> The spectrum's parameters in their ranges (the message names the variable and the clause).
  pure subroutine check_spectrum(spec, status, message)
    type(design_spectrum_t), intent(in) :: spec
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    status = SD_OK
    message = ''
    select case (spec%kind)
    case (SPECTRUM_ASCE7, SPECTRUM_ACI350)
      call check_real('s_ds', spec%s_ds, 0.0_wp, 10.0_wp, .true., .false., 'S_DS must be in '// &
                      '(0, 10] [g] (ASCE 7-16 11.4.5)', status, message)
      call check_real('s_d1', spec%s_d1, 0.0_wp, 10.0_wp, .true., .false., 'S_D1 must be in '// &
                      '(0, 10] [g] (ASCE 7-16 11.4.5)', status, message)
      if (spec%kind == SPECTRUM_ASCE7) then
        call check_real('t_l', spec%t_l, spec%s_d1/max(spec%s_ds, tiny(1.0_wp)), 100.0_wp, &
                        .true., .false., 'T_L must be > T_S = S_D1/S_DS = '// &
                        num2str(spec%s_d1/max(spec%s_ds, tiny(1.0_wp)))//' and <= 100 [s] '// &
                        '(ASCE 7-16 11.4.6, Figure 22-14 to 22-17)', status, message)
        call check_real('k', spec%k, 1.0_wp, 3.0_wp, .false., .false., 'K (API 650 E.4.6.1, '// &
                        '5 % -> 0.5 % damping) must be in [1, 3] (1.5 unless told)', status, &
                        message)
      end if
    case (SPECTRUM_EC8)
      call check_real('a_gr', spec%a_gr, 0.0_wp, 2.0_wp, .true., .false., 'a_gR must be in '// &
                      '(0, 2] [g] (EN 1998-1 3.2.1)', status, message)
      call check_real('gamma_i', spec%gamma_i, 0.0_wp, 3.0_wp, .true., .false., &
                      'gamma_I must be in (0, 3] (EN 1998-1 4.2.5, EN 1998-4 2.1.4)', status, &
                      message)
      call check_real('q', spec%q, 1.0_wp, 8.0_wp, .false., .false., 'q must be in [1, 8] '// &
                      '(EN 1998-1 3.2.2.5; EN 1998-4 2.3.3.3)', status, message)
      call check_real('beta', spec%beta, 0.0_wp, 1.0_wp, .false., .false., 'beta must be in '// &
                      '[0, 1] (EN 1998-1 3.2.2.5(4), recommended 0.2)', status, message)
      if (status == SD_OK .and. (spec%ground_type < 1 .or. spec%ground_type > 5)) then
        status = SD_BAD_INPUT
        message = 'ground_type = '//num2str(spec%ground_type)//' is out of range: one of '// &
                  'A, B, C, D, E (EN 1998-1 Table 3.1)'
      end if
      if (status == SD_OK .and. (spec%ec8_type < 1 .or. spec%ec8_type > 2)) then
        status = SD_BAD_INPUT
        message = 'spectrum_type = '//num2str(spec%ec8_type)//' is out of range: 1 or 2 '// &
                  '(EN 1998-1 3.2.2.2(2))'
      end if
    case default
      status = SD_BAD_INPUT
      message = 'spectrum kind = '//num2str(spec%kind)//' is out of range: asce7, aci350 or ec8'
    end select
  end subroutine check_spectrum

  !> S, T_B, T_C, T_D [s] of EN 1998-1 Table 3.2 (type 1) or 3.3 (type 2).
  pure function ec8_ground_parameters(spec) result(p)
    type(design_spectrum_t), intent(in) :: spec
    real(wp) :: p(4)
    if (spec%ec8_type == 1) then
      p = ec8_type1(:, spec%ground_type)
    else
      p = ec8_type2(:, spec%ground_type)
    end if
  end function ec8_ground_parameters

  !> The spectral acceleration Sa [g] at period T [s] and damping ratio zeta (elastic; for
  !> ASCE 7 and ACI 350.3 only the dampings they tabulate: 0.05 and 0.005).
  pure subroutine spectrum_sa(spec, period, damping, sa, status, message)
    type(design_spectrum_t), intent(in) :: spec
    real(wp), intent(in) :: period, damping
    real(wp), intent(out) :: sa
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: p(4), eta, t_s
    sa = 0
    call check_spectrum(spec, status, message)
    call check_real('period', period, 0.0_wp, 1000.0_wp, .false., .false., &
                    'the period must be in [0, 1000] [s]', status, message)
    call check_real('damping_ratio', damping, 0.0_wp, 1.0_wp, .true., .true., &
                    'the damping ratio must be in (0, 1) (a ratio of critical: 0.05 for 5 %)', &
                    status, message)
    if (status /= SD_OK) return
    select case (spec%kind)
    case (SPECTRUM_ASCE7)
      call tabulated(damping, 'ASCE 7-16 11.4.6 (5 %) and API 650 E.4.6.1 (0.5 % by K)', &
                     status, message)
      if (status /= SD_OK) return
      t_s = spec%s_d1/spec%s_ds
      if (period < 0.2_wp*t_s) then
        sa = spec%s_ds*(0.4_wp + 0.6_wp*period/(0.2_wp*t_s))   ! eq 11.4-5, T_0 = 0.2 T_S
      else if (period <= t_s) then
        sa = spec%s_ds                                         ! 11.4.6 item 2
      else if (period <= spec%t_l) then
        sa = spec%s_d1/period                                  ! eq 11.4-6
      else
        sa = spec%s_d1*spec%t_l/period**2                      ! eq 11.4-7
      end if
      if (is_tabulated(damping, CONVECTIVE_RATIO)) sa = spec%k*sa   ! API 650 E.4.6.1 (K)
    case (SPECTRUM_ACI350)
      call tabulated(damping, 'ACI 350.3-06 9.4.1 (impulsive, 5 %) and 9.4.2 (convective, '// &
                     '0.5 %)', status, message)
      if (status /= SD_OK) return
      t_s = spec%s_d1/spec%s_ds
      if (is_tabulated(damping, IMPULSIVE_RATIO)) then
        if (period <= t_s) then
          sa = spec%s_ds                                       ! eq 9-32
        else
          sa = min(spec%s_d1/period, spec%s_ds)                ! eq 9-33
        end if
      else if (period <= 1.6_wp/t_s) then
        sa = min(1.5_wp*spec%s_d1/period, 1.5_wp*spec%s_ds)    ! eq 9-34
      else
        sa = 2.4_wp*spec%s_ds/period**2                        ! eq 9-35
      end if
    case (SPECTRUM_EC8)
      p = ec8_ground_parameters(spec)
      eta = max(sqrt(10/(5 + 100*damping)), 0.55_wp)           ! eq 3.6, xi in %
      associate (ag => spec%gamma_i*spec%a_gr, s => p(1), tb => p(2), tc => p(3), td => p(4))
        if (period > ec8_t_max) then
          sa = ec8_long_periods(spec, period, eta)             ! Annex A, eq 3.7
        else if (period <= tb) then
          sa = ag*s*(1 + period/tb*(2.5_wp*eta - 1))           ! eq 3.2
        else if (period <= tc) then
          sa = ag*s*eta*2.5_wp                                 ! eq 3.3
        else if (period <= td) then
          sa = ag*s*eta*2.5_wp*tc/period                       ! eq 3.4
        else
          sa = ag*s*eta*2.5_wp*tc*td/period**2                 ! eq 3.5
        end if
      end associate
    end select
  end subroutine spectrum_sa

  !> EN 1998-1 sec 3.2.2.5: the design spectrum Sd [g] with the behaviour factor q at period
  !> T [s] (eq 3.13-3.16, with the lower bound beta a_g); the impulsive part of a tank
  !> (EN 1998-4 2.3.3.3: q for the impulsive response, convective response elastic).
  pure subroutine ec8_design_sa(spec, period, sd, status, message)
    type(design_spectrum_t), intent(in) :: spec
    real(wp), intent(in) :: period
    real(wp), intent(out) :: sd
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: p(4)
    sd = 0
    call check_spectrum(spec, status, message)
    if (status == SD_OK .and. spec%kind /= SPECTRUM_EC8) then
      status = SD_BAD_INPUT
      message = 'the design spectrum with q (EN 1998-1 3.2.2.5) needs an EC8 spectrum '// &
                '(kind = ''ec8'')'
    end if
    call check_real('period', period, 0.0_wp, ec8_t_max, .false., .false., 'the design '// &
                    'spectrum of EN 1998-1 3.2.2.5 is given for T <= 4 s', status, message)
    if (status /= SD_OK) return
    p = ec8_ground_parameters(spec)
    associate (ag => spec%gamma_i*spec%a_gr, s => p(1), tb => p(2), tc => p(3), td => p(4), &
               q => spec%q)
      if (period <= tb) then
        sd = ag*s*(2.0_wp/3 + period/tb*(2.5_wp/q - 2.0_wp/3))   ! eq 3.13
      else if (period <= tc) then
        sd = ag*s*2.5_wp/q                                      ! eq 3.14
      else if (period <= td) then
        sd = max(ag*s*2.5_wp/q*tc/period, spec%beta*ag)          ! eq 3.15
      else
        sd = max(ag*s*2.5_wp/q*tc*td/period**2, spec%beta*ag)    ! eq 3.16
      end if
    end associate
  end subroutine ec8_design_sa

  !> The plateau of a spectrum [g] at damping ratio zeta: where the codes put a tank's impulsive
  !> mode when its period is not given (API 650 E.4.6.1-1: A_i from S_DS; ACI 350.3 eq 9-32;
  !> EN 1998-1 eq 3.3 elastic, or eq 3.14 with q when design).
  pure subroutine plateau_sa(spec, damping, design, sa, status, message)
    type(design_spectrum_t), intent(in) :: spec
    real(wp), intent(in) :: damping
    logical, intent(in) :: design
    real(wp), intent(out) :: sa
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: p(4)
    call check_spectrum(spec, status, message)
    sa = 0
    if (status /= SD_OK) return
    if (spec%kind == SPECTRUM_EC8) then
      p = ec8_ground_parameters(spec)
      if (design) then
        call ec8_design_sa(spec, p(3), sa, status, message)
      else
        call spectrum_sa(spec, p(3), damping, sa, status, message)
      end if
    else
      call spectrum_sa(spec, spec%s_d1/spec%s_ds, damping, sa, status, message)
    end if
  end subroutine plateau_sa

  !> EN 1998-1:2004 informative Annex A beyond 4 s: the elastic displacement spectrum
  !> S_De(T) = Se(T) (T/2 pi)^2 to T_E (eq A.1, Se by eq 3.5), 0.025 a_g S T_C T_D [2.5 eta +
  !> (T - T_E)/(T_F - T_E) (1 - 2.5 eta)] to T_F (eq A.2), d_g = 0.025 a_g S T_C T_D beyond
  !> (eq A.3, eq 3.12); returned as the acceleration Se = S_De (2 pi/T)^2 [g] (eq 3.7).
  pure real(wp) function ec8_long_periods(spec, period, eta) result(se)
    type(design_spectrum_t), intent(in) :: spec
    real(wp), intent(in) :: period, eta
    real(wp) :: p(4), t_e, t_f, d_g
    p = ec8_ground_parameters(spec)
    t_e = ec8_annex_a(1, spec%ground_type)
    t_f = ec8_annex_a(2, spec%ground_type)
    associate (ag => spec%gamma_i*spec%a_gr, s => p(1), tc => p(3), td => p(4))
      d_g = 0.025_wp*ag*s*tc*td                                ! eq 3.12 [g s^2]
      if (period <= t_e) then
        se = ag*s*eta*2.5_wp*tc*td/period**2                   ! eq A.1 with eq 3.5
      else if (period <= t_f) then
        se = d_g*(2.5_wp*eta + (period - t_e)/(t_f - t_e)*(1 - 2.5_wp*eta))* &
             (2*pi/period)**2                                  ! eq A.2, eq 3.7
      else
        se = d_g*(2*pi/period)**2                              ! eq A.3, eq 3.7
      end if
    end associate
  end function ec8_long_periods

  !> EN 1998-1 Annex A, Table A.1: T_E (which = 1) or T_F (2) [s] of a ground type (1..5).
  pure real(wp) function ec8_annex_a_periods(ground_type, which) result(t)
    integer, intent(in) :: ground_type, which
    t = ec8_annex_a(which, ground_type)
  end function ec8_annex_a_periods

  !> ASCE 7 / API 650 and ACI 350.3 tabulate 5 % and 0.5 % only.
  pure subroutine tabulated(damping, clause, status, message)
    real(wp), intent(in) :: damping
    character(len=*), intent(in) :: clause
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    status = SD_OK
    message = ''
    if (.not. (is_tabulated(damping, CONVECTIVE_RATIO) .or. &
               is_tabulated(damping, IMPULSIVE_RATIO))) then
      status = SD_BAD_INPUT
      message = 'damping_ratio = '//num2str(damping)//' is not tabulated: 0.05 or 0.005 (5 or '// &
                '0.5 %; '//clause//')'
    end if
  end subroutine tabulated

  !> The damping ratio is the tabulated one (to round-off).
  elemental logical function is_tabulated(damping, ratio)
    real(wp), intent(in) :: damping, ratio
    is_tabulated = abs(damping - ratio) <= 1.0e-9_wp*ratio
  end function is_tabulated
end module sloshdyn_design_spectra
