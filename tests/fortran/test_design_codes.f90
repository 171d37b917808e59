!> Design-code tank parameters (ACI 350.3-06, API 650 Annex E, EN 1998-4 Annex A) against
!> potential-flow theory of the rigid cylindrical tank, against each other where they must agree
!> (to the codes' rounding of their constants), against hand-worked numbers for one squat and one
!> tall tank, against a published third-party API 650 freeboard calculation, in the shallow and
!> deep limits, and for bad inputs.
!>
!> Theory (first antisymmetric sloshing mode of a rigid upright cylinder, e.g. Abramson, NASA
!> SP-106, ch. 2; Veletsos & Yang 1977): xi = first root of J1' = 1.841184;
!>   omega^2 = (g xi/R) tanh(xi H/R),  m_c/m = 2 R tanh(xi H/R)/(xi (xi^2 - 1) H);
!> the pressure of the mode is ~ J1(xi r/R) cosh(xi z/R) cos(theta), so the heights of its
!> resultants follow by integrating it over the wall (EBP) and over wall and base (IBP); this test
!> does those integrals numerically (Simpson, intrinsic bessel_j1), not by the closed forms.
program test_design_codes
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT
  use sloshdyn_design_codes, only: aci350_parameters, api650_parameters, ec8_parameters, &
                                   aci350_circular, aci350_wave_height, api650_circular, &
                                   api650_wave_height, ec8_circular, ec8_wave_height
  use sloshdyn_design_spectra, only: design_spectrum_t, spectrum_sa, ec8_design_sa, &
                                     ec8_ground_parameters, SPECTRUM_ASCE7, SPECTRUM_ACI350, &
                                     SPECTRUM_EC8
  use sloshdyn_text, only: num2str
  use checks, only: check_close, check_true, finish
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_positive_inf
  implicit none
  real(wp), parameter :: g = 9.80665_wp
  type(aci350_parameters) :: aci
  type(api650_parameters) :: api
  type(ec8_parameters) :: ec8
  integer :: status
  character(len=message_len) :: message
  real(wp) :: xi

  xi = first_root_of_j1_derivative()
  call check_close('theory: first root of J1'' = 1.8411838 (tables)', xi, 1.8411838_wp, 1.0e-7_wp)

  call test_hand_worked_squat()
  call test_hand_worked_tall()
  call test_published_api_example()
  call test_against_theory()
  call test_codes_against_each_other()
  call test_limits()
  call test_wave_heights()
  call test_bad_input()
  call test_ec8_impulsive()
  call test_spectra_continuous()
  call finish()

contains

  !> D = 10 m (R = 5), H = 6 m, g = 9.80665 (pocket-calculator arithmetic):
  !> ACI: H/D = 0.6, x = 3.68*0.6 = 2.208, tanh x = 0.9761236, cosh x = 4.603712,
  !>   sinh x = 4.493791, x sinh x = 9.922290;
  !>   lambda = sqrt(3.68*9.80665*0.9761236) = sqrt(35.22698) = 5.935218,
  !>   omega_c = 5.935218/sqrt(10) = 1.876881 rad/s, T_c = 2 pi/1.876881 = 3.347675 s;
  !>   D/H = 1.666667, y = 0.866*1.666667 = 1.443333, tanh y = 0.8943667,
  !>   W_i/W_L = 0.8943667/1.443333 = 0.6196536; W_c/W_L = 0.230*1.666667*0.9761236 = 0.3741807;
  !>   D/H >= 1.333: h_i = 0.375*6 = 2.25 m; h_c = 6 (1 - 3.603712/9.922290) = 6 (1 - 0.3631935)
  !>   = 3.820839 m; D/H >= 0.75: h_i' = 6 (1.443333/(2*0.8943667) - 0.125) = 6 (0.8069024 -
  !>   0.125) = 4.091414 m; h_c' = 6 (1 - (4.603712 - 2.01)/9.922290) = 6 (1 - 0.2614025)
  !>   = 4.431585 m.
  !> API: K_s = 0.578/sqrt(0.9761236) = 0.578/0.9879897 = 0.5850264, T_c = 1.8*0.5850264*3.162278
  !>   = 3.330028 s; x' = 3.67*0.6 = 2.202, tanh x' = 0.9758388, cosh x' = 4.576832,
  !>   sinh x' = 4.466250, x' sinh x' = 9.834682; W_c/W_p = 0.230*1.666667*0.9758388 = 0.3740715;
  !>   W_i/W_p = 0.6196536 (as ACI, D/H >= 1.333); X_i = 2.25 m;
  !>   X_c = 6 (1 - 3.576832/9.834682) = 6 (1 - 0.3636957) = 3.817826 m;
  !>   X_is = 0.375 (1 + 1.333 (1.443333/0.8943667 - 1)) 6 = 0.375 (1 + 1.333*0.6138048) 6
  !>   = 4.090954 m; X_cs = 6 (1 - (4.576832 - 1.937)/9.834682) = 6 (1 - 0.2684206) = 4.389476 m.
  !> EC8: gamma = 1.2, x = 1.841*1.2 = 2.2092, tanh x = 0.9761801, cosh x = 4.609108,
  !>   sinh x = 4.499319, x sinh x = 9.939895; omega^2 = 9.80665*1.841/5*0.9761801 = 3.524799,
  !>   omega = 1.877445 rad/s, T = 3.346668 s; m_c/m = 2*0.9761801/(1.2*1.841*2.389281)
  !>   = 1.952360/5.278400 = 0.3698773; h_c = 6 (1 - 3.609108/9.939895) = 3.821441 m;
  !>   h_c' = 6 (1 - 2.609108/9.939895) = 4.425069 m.
  subroutine test_hand_worked_squat()
    call aci350_circular(5.0_wp, 6.0_wp, g, aci, status, message)
    call check_true('ACI D=10 H=6: status', status == SD_OK)
    call check_close('ACI D=10 H=6: lambda', aci%lambda, 5.935218_wp, 2.0e-7_wp)
    call check_close('ACI D=10 H=6: omega_c', aci%convective_frequency, 1.876881_wp, 3.0e-7_wp)
    call check_close('ACI D=10 H=6: T_c', aci%convective_period, 3.347675_wp, 2.0e-7_wp)
    call check_close('ACI D=10 H=6: W_i/W_L', aci%impulsive_ratio, 0.6196536_wp, 2.0e-7_wp)
    call check_close('ACI D=10 H=6: W_c/W_L', aci%convective_ratio, 0.3741807_wp, 2.0e-7_wp)
    call check_close('ACI D=10 H=6: h_i', aci%impulsive_height, 2.25_wp, 1.0e-15_wp)
    call check_close('ACI D=10 H=6: h_c', aci%convective_height, 3.820839_wp, 2.0e-7_wp)
    call check_close('ACI D=10 H=6: h_i''', aci%impulsive_height_ibp, 4.091414_wp, 2.0e-7_wp)
    call check_close('ACI D=10 H=6: h_c''', aci%convective_height_ibp, 4.431585_wp, 2.0e-7_wp)

    call api650_circular(5.0_wp, 6.0_wp, api, status, message)
    call check_true('API D=10 H=6: status', status == SD_OK)
    call check_close('API D=10 H=6: K_s', api%ks, 0.5850264_wp, 2.0e-7_wp)
    call check_close('API D=10 H=6: T_c', api%convective_period, 3.330028_wp, 2.0e-7_wp)
    call check_close('API D=10 H=6: W_i/W_p', api%impulsive_ratio, 0.6196536_wp, 2.0e-7_wp)
    call check_close('API D=10 H=6: W_c/W_p', api%convective_ratio, 0.3740715_wp, 2.0e-7_wp)
    call check_close('API D=10 H=6: X_i', api%impulsive_height, 2.25_wp, 1.0e-15_wp)
    call check_close('API D=10 H=6: X_c', api%convective_height, 3.817826_wp, 2.0e-7_wp)
    call check_close('API D=10 H=6: X_is', api%impulsive_height_slab, 4.090954_wp, 2.0e-7_wp)
    call check_close('API D=10 H=6: X_cs', api%convective_height_slab, 4.389476_wp, 2.0e-7_wp)

    call ec8_circular(5.0_wp, 6.0_wp, g, ec8, status, message)
    call check_true('EC8 D=10 H=6: status', status == SD_OK)
    call check_close('EC8 D=10 H=6: omega_c1', ec8%convective_frequency, 1.877445_wp, 3.0e-7_wp)
    call check_close('EC8 D=10 H=6: T_c1', ec8%convective_period, 3.346668_wp, 2.0e-7_wp)
    call check_close('EC8 D=10 H=6: m_c1/m', ec8%convective_ratio, 0.3698773_wp, 2.0e-7_wp)
    call check_close('EC8 D=10 H=6: h_c1', ec8%convective_height, 3.821441_wp, 2.0e-7_wp)
    call check_close('EC8 D=10 H=6: h_c1''', ec8%convective_height_ibp, 4.425069_wp, 2.0e-7_wp)
  end subroutine test_hand_worked_squat

  !> D = 6 m, H = 9 m (D/H = 2/3, the tall branches): ACI h_i = (0.5 - 0.09375*2/3) 9
  !> = (0.5 - 0.0625) 9 = 3.9375 m; D/H < 0.75: h_i' = 0.45*9 = 4.05 m;
  !> y = 0.866*2/3 = 0.5773333, tanh y = 0.5207245, W_i/W_L = 0.9019478 (single ACI formula);
  !> API W_i/W_p = 1 - 0.218*2/3 = 0.8546667; X_i = (0.5 - 0.094*2/3) 9 = 3.936 m;
  !> X_is = (0.5 + 0.06*2/3) 9 = 0.54*9 = 4.86 m.
  subroutine test_hand_worked_tall()
    call aci350_circular(3.0_wp, 9.0_wp, g, aci, status, message)
    call check_close('ACI D=6 H=9: h_i (D/H < 1.333)', aci%impulsive_height, 3.9375_wp, 1.0e-14_wp)
    call check_close('ACI D=6 H=9: h_i'' (D/H < 0.75)', aci%impulsive_height_ibp, 4.05_wp, &
                     1.0e-14_wp)
    call check_close('ACI D=6 H=9: W_i/W_L', aci%impulsive_ratio, 0.9019478_wp, 2.0e-7_wp)
    call api650_circular(3.0_wp, 9.0_wp, api, status, message)
    call check_close('API D=6 H=9: W_i/W_p (D/H < 1.333)', api%impulsive_ratio, &
                     1 - 0.218_wp*2/3, 1.0e-14_wp)
    call check_close('API D=6 H=9: X_i (D/H < 1.333)', api%impulsive_height, 3.936_wp, 1.0e-14_wp)
    call check_close('API D=6 H=9: X_is (D/H < 1.333)', api%impulsive_height_slab, 4.86_wp, &
                     1.0e-14_wp)
  end subroutine test_hand_worked_tall

  !> A third-party freeboard calculation to API 650 12th ed. (spreadsheet "Freeboard calculation
  !> for storage tanks as per API-650 12th edition", published as a PDF) for D = 4.5 m,
  !> H = 3.14 m prints K_s = 0.581411, T_c = 2.220045 s and, for A_f = 0.524483 (in g),
  !> delta_s = 0.991272 m (values to 6 decimals). K_s = 0.581411 also fixes the constant inside
  !> K_s as 3.68 (3.67 would give 0.581459).
  subroutine test_published_api_example()
    real(wp) :: delta_s
    call api650_circular(2.25_wp, 3.14_wp, api, status, message)
    call check_close('API published example: K_s = 0.581411', api%ks, 0.581411_wp, 1.0e-6_wp)
    call check_close('API published example: T_c = 2.220045 s', api%convective_period, &
                     2.220045_wp, 3.0e-7_wp)
    call api650_wave_height(2.25_wp, 0.524483_wp, delta_s, status, message)
    call check_close('API published example: delta_s = 0.991272 m', delta_s, 0.991272_wp, &
                     1.0e-6_wp)
  end subroutine test_published_api_example

  !> Against potential-flow theory with the exact xi, for slender to squat tanks. The codes
  !> round 2 xi = 3.68237 to 3.68 (ACI) or 3.67 (API masses and heights) and xi to 1.841 (EC8):
  !> - EC8 (|d xi/xi| = 1.0e-4): omega moves by < 1.0e-4 relative (omega^2 ~ xi tanh(xi gamma),
  !>   d ln omega/d ln xi = (1 + 2x/sinh 2x)/2 <= 1), m_c by < 4e-4 (|d ln m_c/d xi|
  !>   <= 1/xi + 2 xi/(xi^2-1) = 2.08, the tanh term having the other sign), h_c and h_c' by
  !>   < 3e-4 relative (|d ln h_c/d ln x| <= 0.3, |d ln h_c'/d ln x| <= 2, x = xi H/R);
  !> - ACI T_c (|d xi/xi| = 6.4e-4): < 6.4e-4 relative;
  !> - ACI W_c/W_L = theory x 0.230 xi (xi^2 - 1) (= 1.0121: Housner's 0.230 for
  !>   1/(xi (xi^2-1)) = 0.2273) x tanh(3.68 H/D)/tanh(2 xi H/D) (within 6.4e-4 of 1);
  !> - ACI h_c vs the wall integral: < 0.3*6.4e-4 = 2e-4 relative (the 3.68 rounding);
  !> - ACI h_c' uses 2.01 (Housner) for the theory's 2: h_c'/H differs by 0.01/(x sinh x)
  !>   (x = 3.68 H/D) besides the 3.68 rounding (< 2*6.4e-4 = 1.3e-3 relative).
  subroutine test_against_theory()
    real(wp), parameter :: gammas(4) = [0.4_wp, 1.0_wp, 2.2_wp, 5.0_wp]
    real(wp) :: gamma, radius, depth, omega_theory, mass_theory, hc_theory, hc_ibp_theory, &
                x, housner_factor, tanh_factor
    integer :: i
    character(len=16) :: label

    radius = 4.0_wp
    housner_factor = 0.230_wp*xi*(xi**2 - 1)
    call check_close('theory: 0.230 xi (xi^2 - 1) = 1.0121 (Housner''s rounding)', &
                     housner_factor, 1.0121_wp, 1.0e-4_wp)
    do i = 1, size(gammas)
      gamma = gammas(i)
      depth = gamma*radius
      write (label, '(a, f3.1)') 'H/R = ', gamma
      omega_theory = sqrt(g*xi/radius*tanh(xi*gamma))
      mass_theory = 2*radius*tanh(xi*gamma)/(xi*(xi**2 - 1)*depth)
      call resultant_heights(radius, depth, hc_theory, hc_ibp_theory)
      call ec8_circular(radius, depth, g, ec8, status, message)
      call aci350_circular(radius, depth, g, aci, status, message)
      call check_close('EC8 vs theory, '//trim(label)//': omega', ec8%convective_frequency, &
                       omega_theory, 1.0e-4_wp)
      call check_close('EC8 vs theory, '//trim(label)//': m_c/m', ec8%convective_ratio, &
                       mass_theory, 4.0e-4_wp)
      call check_close('EC8 vs theory (wall integral), '//trim(label)//': h_c', &
                       ec8%convective_height, hc_theory, 3.0e-4_wp)
      call check_close('EC8 vs theory (wall + base integral), '//trim(label)//': h_c''', &
                       ec8%convective_height_ibp, hc_ibp_theory, 3.0e-4_wp)
      call check_close('ACI vs theory, '//trim(label)//': T_c', aci%convective_period, &
                       2*pi/omega_theory, 6.4e-4_wp)
      tanh_factor = tanh(3.68_wp*depth/(2*radius))/tanh(xi*gamma)
      call check_close('ACI vs theory, '//trim(label)//': W_c/W_L = theory x 1.0121 x tanh ratio', &
                       aci%convective_ratio, mass_theory*housner_factor*tanh_factor, 1.0e-14_wp)
      call check_close('ACI vs theory, '//trim(label)//': tanh ratio within 6.4e-4 of 1', &
                       tanh_factor, 1.0_wp, 6.4e-4_wp)
      call check_close('ACI vs theory, '//trim(label)//': h_c', aci%convective_height, hc_theory, &
                       2.0e-4_wp)
      x = 3.68_wp*depth/(2*radius)
      call check_close('ACI vs theory, '//trim(label)//': h_c'' = theory + 0.01 H/(x sinh x)', &
                       aci%convective_height_ibp, hc_ibp_theory + 0.01_wp*depth/(x*sinh(x)), &
                       1.3e-3_wp)
      print '(a, 4es11.3)', '    measured '//trim(label)//' EC8/theory - 1 (omega, m_c, h_c, h_c''): ', &
        ec8%convective_frequency/omega_theory - 1, ec8%convective_ratio/mass_theory - 1, &
        ec8%convective_height/hc_theory - 1, ec8%convective_height_ibp/hc_ibp_theory - 1
      print '(a, 3es11.3)', '    measured '//trim(label)//' ACI/theory - 1 (T_c, W_c, h_c): ', &
        aci%convective_period*omega_theory/(2*pi) - 1, aci%convective_ratio/mass_theory - 1, &
        aci%convective_height/hc_theory - 1
    end do
  end subroutine test_against_theory

  !> The codes against each other:
  !> - API T_c = 1.8 K_s sqrt(D) with K_s = 0.578/sqrt(tanh(3.68 H/D)), ACI T_c = 2 pi
  !>   sqrt(D/(3.68 g tanh(3.68 H/D))): same tanh, so API/ACI = 1.8*0.578 sqrt(3.68 g)/(2 pi)
  !>   = 0.99473 for every tank (g = 9.80665; API's 1.8 is sqrt(3.28084 ft/m) = 1.8113 rounded,
  !>   0.578 is 2 pi/sqrt(3.68*32.174 ft/s^2) = 0.57744 rounded up);
  !> - W_i: the same formula in ACI and API for D/H >= 1.333;
  !> - W_c and h_c: 3.67 (API) against 3.68 (ACI) in tanh, cosh, sinh: within 0.3 %;
  !> - h_i: 0.375 H in both for D/H >= 1.333; 0.094 (API) against 0.09375 (ACI) below.
  subroutine test_codes_against_each_other()
    real(wp), parameter :: ratios(5) = [0.5_wp, 1.0_wp, 1.5_wp, 3.0_wp, 8.0_wp]   ! D/H
    real(wp) :: depth, radius, expected_ratio
    integer :: i
    character(len=16) :: label

    expected_ratio = 1.8_wp*0.578_wp*sqrt(3.68_wp*g)/(2*pi)
    call check_close('API/ACI period ratio constant = 0.99473', expected_ratio, 0.99473_wp, 1.0e-5_wp)
    radius = 6.0_wp
    do i = 1, size(ratios)
      depth = 2*radius/ratios(i)
      write (label, '(a, f3.1)') 'D/H = ', ratios(i)
      call aci350_circular(radius, depth, g, aci, status, message)
      call api650_circular(radius, depth, api, status, message)
      call check_close('API vs ACI, '//trim(label)//': T_c ratio', &
                       api%convective_period/aci%convective_period, expected_ratio, 1.0e-13_wp)
      call check_close('API vs ACI, '//trim(label)//': W_c (3.67 vs 3.68)', api%convective_ratio, &
                       aci%convective_ratio, 3.0e-3_wp)
      call check_close('API vs ACI, '//trim(label)//': h_c (3.67 vs 3.68)', &
                       api%convective_height, aci%convective_height, 3.0e-3_wp)
      if (ratios(i) >= 1.333_wp) then
        call check_close('API vs ACI, '//trim(label)//': W_i identical', api%impulsive_ratio, &
                         aci%impulsive_ratio, 1.0e-15_wp)
        call check_close('API vs ACI, '//trim(label)//': h_i identical', api%impulsive_height, &
                         aci%impulsive_height, 1.0e-15_wp)
      else
        call check_close('API vs ACI, '//trim(label)//': h_i (0.094 vs 0.09375)', &
                         api%impulsive_height - aci%impulsive_height, &
                         -0.00025_wp*ratios(i)*depth, 1.0e-12_wp)
      end if
    end do
  end subroutine test_codes_against_each_other

  !> Limits. Deep (H/D = 25): tanh -> 1, so T_c -> 2 pi sqrt(D/(3.68 g)) and the convective mass
  !> sits D/3.68 below the surface (h_c/H = 1 - tanh(x/2)/x -> 1 - 1/x); W_i/W_L ->
  !> tanh(y)/y -> 1 - y^2/3 (y = 0.866 D/H = 0.03464: 0.99960); EC8 m_c/m -> 2/(gamma lambda
  !> (lambda^2 - 1)). Shallow (H/D = 0.005): shallow-water waves, omega = (3.68/D) sqrt(g H)
  !> (tanh x -> x, relative error x^2/6 = 5.6e-5); W_c/W_L -> 0.230*3.68 = 0.8464 (relative
  !> error x^2/3, x the tanh argument, < x^2/2 here), EC8 and theory m_c/m -> 2/(lambda^2 - 1)
  !> = 0.837; h_c -> H/2 (uniform pressure, 1 - tanh(x/2)/x = 1/2 + x^2/24, so a relative
  !> x^2/12, allowed x^2/6); W_i/W_L -> 1/y (tanh y = 1 to 1e-300).
  subroutine test_limits()
    real(wp) :: radius, depth, x
    radius = 1.0_wp
    depth = 50.0_wp                         ! H/D = 25
    call aci350_circular(radius, depth, g, aci, status, message)
    call ec8_circular(radius, depth, g, ec8, status, message)
    call check_close('deep: ACI T_c = 2 pi sqrt(D/(3.68 g))', aci%convective_period, &
                     2*pi*sqrt(2/(3.68_wp*g)), 1.0e-14_wp)
    call check_close('deep: ACI h_c = H - D/3.68', aci%convective_height, depth - 2/3.68_wp, &
                     1.0e-14_wp)
    call check_close('deep: EC8 h_c1 = H - R/1.841', ec8%convective_height, depth - 1/1.841_wp, &
                     1.0e-14_wp)
    call check_close('deep: EC8 h_c1'' = H - R/1.841 (base moment vanishes)', &
                     ec8%convective_height_ibp, depth - 1/1.841_wp, 1.0e-14_wp)
    call check_close('deep: ACI W_i/W_L -> 1 - y^2/3', aci%impulsive_ratio, &
                     1 - (0.866_wp*0.04_wp)**2/3, 1.0e-6_wp)
    call check_close('deep: EC8 m_c/m = 2/(gamma lambda (lambda^2 - 1))', ec8%convective_ratio, &
                     2/(50*1.841_wp*(1.841_wp**2 - 1)), 1.0e-14_wp)
    depth = 0.01_wp                         ! H/D = 0.005
    x = 3.68_wp*depth/(2*radius)
    call aci350_circular(radius, depth, g, aci, status, message)
    call ec8_circular(radius, depth, g, ec8, status, message)
    call check_close('shallow: ACI omega_c = (3.68/D) sqrt(g H) (shallow-water waves)', &
                     aci%convective_frequency, 3.68_wp/2*sqrt(g*depth), x**2/6)
    call check_close('shallow: ACI W_c/W_L -> 0.230*3.68', aci%convective_ratio, 0.230_wp*3.68_wp, &
                     x**2/2)
    call check_close('shallow: EC8 m_c/m -> 2/(lambda^2 - 1)', ec8%convective_ratio, &
                     2/(1.841_wp**2 - 1), x**2/2)
    call check_close('shallow: theory m_c/m -> 2/(xi^2 - 1) = 0.837', 2/(xi**2 - 1), 0.8369_wp, &
                     1.0e-4_wp)
    call check_close('shallow: ACI h_c -> H/2', aci%convective_height, depth/2, x**2/6)
    call check_close('shallow: ACI W_i/W_L -> 1/(0.866 D/H)', aci%impulsive_ratio, &
                     depth/(0.866_wp*2*radius), 1.0e-15_wp)
    call check_true('shallow: ACI h_c'' > H (base pressure moment dominates)', &
                    aci%convective_height_ibp > depth)
  end subroutine test_limits

  !> Wave heights: potential theory gives the first-mode wall elevation
  !> d = 2/(xi^2 - 1) R Sa/g = 0.8369 R Sa/g (Veletsos; Malhotra et al. 2000 quote 0.84):
  !> EC8's 0.84 R and API's 0.42 D are that factor rounded (+0.4 %), so they agree exactly with
  !> each other for Af = Se/g; ACI's (D/2) C_c I = R I Sa/g has no such factor (1/0.84 = 1.19
  !> times higher). Hand numbers: R = 5 m, Sa = 0.15 g: EC8 0.84*5*0.15 = 0.63 m, API
  !> 0.42*10*0.15 = 0.63 m, ACI with I = 1.25: 5*1.25*0.15 = 0.9375 m.
  subroutine test_wave_heights()
    real(wp) :: d_ec8, d_api, d_aci
    call ec8_wave_height(5.0_wp, 0.15_wp*g, g, d_ec8, status, message)
    call api650_wave_height(5.0_wp, 0.15_wp, d_api, status, message)
    call aci350_wave_height(5.0_wp, 0.15_wp*g, g, 1.25_wp, d_aci, status, message)
    call check_close('wave: EC8 d_max = 0.84*5*0.15 = 0.63 m', d_ec8, 0.63_wp, 1.0e-15_wp)
    call check_close('wave: API delta_s = 0.42*10*0.15 = 0.63 m', d_api, 0.63_wp, 1.0e-15_wp)
    call check_close('wave: ACI d_max = (D/2) I Sa/g = 0.9375 m', d_aci, 0.9375_wp, 1.0e-15_wp)
    call check_close('wave: EC8 = API for Af = Se/g', d_ec8, d_api, 1.0e-15_wp)
    call check_close('wave: EC8 factor 0.84 vs theory 2/(xi^2 - 1)', d_ec8/(5*0.15_wp), &
                     2/(xi**2 - 1), 4.0e-3_wp)
  end subroutine test_wave_heights

  subroutine test_bad_input()
    real(wp) :: nan, infinity, d
    nan = ieee_value(nan, ieee_quiet_nan)
    infinity = ieee_value(infinity, ieee_positive_inf)
    call aci350_circular(-1.0_wp, 6.0_wp, g, aci, status, message)
    call check_true('ACI: R < 0 refused, message names R', &
                    status == SD_BAD_INPUT .and. index(message, 'R = -1') == 1)
    call aci350_circular(5.0_wp, 6.0_wp, 0.0_wp, aci, status, message)
    call check_true('ACI: g = 0 refused, message names g', &
                    status == SD_BAD_INPUT .and. index(message, 'g = 0') == 1)
    call api650_circular(5.0_wp, nan, api, status, message)
    call check_true('API: H = NaN refused, message names H', &
                    status == SD_BAD_INPUT .and. index(message, 'H = NaN') == 1)
    call ec8_circular(5.0_wp, 0.0_wp, g, ec8, status, message)
    call check_true('EC8: H = 0 refused, message names H', &
                    status == SD_BAD_INPUT .and. index(message, 'H = 0') == 1)
    call ec8_circular(infinity, 1.0_wp, g, ec8, status, message)
    call check_true('EC8: R = Inf refused, message names R', &
                    status == SD_BAD_INPUT .and. index(message, 'R = +Inf') == 1)
    call api650_wave_height(5.0_wp, -0.1_wp, d, status, message)
    call check_true('API wave: Af < 0 refused, message names Af', &
                    status == SD_BAD_INPUT .and. index(message, 'Af = -0.1') == 1)
    call ec8_wave_height(5.0_wp, nan, g, d, status, message)
    call check_true('EC8 wave: Se = NaN refused, message names Se', &
                    status == SD_BAD_INPUT .and. index(message, 'Se = NaN') == 1)
    call aci350_wave_height(5.0_wp, 1.0_wp, g, 0.0_wp, d, status, message)
    call check_true('ACI wave: I = 0 refused, message names I', &
                    status == SD_BAD_INPUT .and. index(message, 'I = 0') == 1)
    print '(a)', '    last message: '//trim(message)
  end subroutine test_bad_input

  !> First root of J1'(x) = J0(x) - J1(x)/x by bisection on [1.5, 2.2] (intrinsic Bessel functions).
  real(wp) function first_root_of_j1_derivative() result(root)
    real(wp) :: low, high
    integer :: i
    low = 1.5_wp
    high = 2.2_wp
    do i = 1, 200
      root = (low + high)/2
      if (j1_derivative(root) > 0) then
        low = root
      else
        high = root
      end if
      if (high - low < 4*epsilon(1.0_wp)) exit
    end do
  end function first_root_of_j1_derivative

  real(wp) function j1_derivative(x)
    real(wp), intent(in) :: x
    j1_derivative = bessel_j0(x) - bessel_j1(x)/x
  end function j1_derivative

  !> EN 1998-4 A.2.1's impulsive mass: 289 t for R = 5 m, H = 6 m of water (issue 25), and
  !> potential flow's mass balance m_i + sum_n m_cn = m, with the convective masses
  !> 2 tanh(l_n gamma)/(gamma l_n (l_n^2 - 1)) over the first 3000 roots l_n of J1' (Newton from
  !> McMahon's l_n ~ (n - 1/4) pi - 7/(8 (n - 1/4) pi), intrinsic bessel_j0, bessel_j1; the tail
  !> beyond is below 1e-8); h_i between 3H/8 and H/2 (Housner's shallow and deep limits).
  subroutine test_ec8_impulsive()
    real(wp) :: geometries(2, 3), convective, root, step, gamma
    integer :: k, n, iteration
    geometries = reshape([5.0_wp, 6.0_wp, 3.0_wp, 12.0_wp, 20.0_wp, 4.0_wp], [2, 3])
    call ec8_circular(5.0_wp, 6.0_wp, g, ec8, status, message)
    call check_close('EC8 R=5 H=6: m_i = 289 t (issue 25), 0.1 %', &
                     ec8%impulsive_ratio*pi*25*6*1000, 289.0e3_wp, 1.0e-3_wp)
    do k = 1, 3
      associate (R => geometries(1, k), H => geometries(2, k))
        call ec8_circular(R, H, g, ec8, status, message)
        gamma = H/R
        convective = 0
        do n = 3000, 1, -1
          root = (n - 0.25_wp)*pi - 7/(8*(n - 0.25_wp)*pi)
          if (n == 1) root = xi
          do iteration = 1, 20
            ! J1' = J0 - J1/x, J1'' = -J1'/x - (1 - 1/x^2) J1 (Bessel's equation)
            step = (bessel_j0(root) - bessel_j1(root)/root)/ &
                   (-(bessel_j0(root) - bessel_j1(root)/root)/root - &
                    (1 - 1/root**2)*bessel_j1(root))
            root = root - step
            if (abs(step) < 1.0e-14_wp*root) exit
          end do
          convective = convective + 2*tanh(root*gamma)/(gamma*root*(root**2 - 1))
        end do
        call check_close('EC8: m_i + sum m_cn = m, H/R = '//num2str(gamma), &
                         ec8%impulsive_ratio + convective, 1.0_wp, 1.0e-7_wp)
        call check_true('EC8: 3H/8 < h_i < H/2', ec8%impulsive_height > 0.375_wp*H .and. &
                        ec8%impulsive_height < 0.5_wp*H)
        call check_true('EC8: h_i'' > h_i', ec8%impulsive_height_ibp > ec8%impulsive_height)
      end associate
    end do
  end subroutine test_ec8_impulsive

  !> Each design spectrum is continuous at its corner periods (its branches meet: ASCE 7 at T_0,
  !> T_S, T_L; ACI 350.3 C_i at T_S and C_c at 1.6/T_S; EN 1998-1 Se and Sd at T_B, T_C, T_D, Se
  !> at 4 s and T_F (Annex A),
  !> for every ground type and both types), and has its plateau value there.
  subroutine test_spectra_continuous()
    type(design_spectrum_t) :: spec
    real(wp) :: p(4)
    integer :: ground, kind
    spec = design_spectrum_t(SPECTRUM_ASCE7, s_ds=1.0_wp, s_d1=0.6_wp, t_l=8.0_wp)
    call continuous('ASCE 7 5 %', spec, [0.12_wp, 0.6_wp, 8.0_wp], 0.05_wp, .false.)
    call continuous('ASCE 7 0.5 %', spec, [0.12_wp, 0.6_wp, 8.0_wp], 0.005_wp, .false.)
    spec%kind = SPECTRUM_ACI350
    call continuous('ACI 350.3 C_i', spec, [0.6_wp], 0.05_wp, .false.)
    call continuous('ACI 350.3 C_c', spec, [1.6_wp/0.6_wp], 0.005_wp, .false.)
    do kind = 1, 2
      do ground = 1, 5
        spec = design_spectrum_t(SPECTRUM_EC8, a_gr=0.3_wp, ground_type=ground, ec8_type=kind, &
                                 q=1.5_wp)
        p = ec8_ground_parameters(spec)
        ! EN 1998-1 eq 3.2-3.5 at T_B, T_C, T_D; at 4 s eq 3.5 goes on as Annex A's eq A.1;
        ! eq A.2 meets A.3 at T_F = 10 s (at T_E it starts 1.3 % lower: 0.025 for 1/(4 pi^2))
        call continuous('EC8 Se', spec, [p(2:4), 4.0_wp, 10.0_wp], 0.02_wp, .false.)
        call continuous('EC8 Sd', spec, p(2:4), 5.0_wp, .true.)
      end do
    end do
  end subroutine test_spectra_continuous

  subroutine continuous(label, spec, corners, damping, design)
    character(len=*), intent(in) :: label
    type(design_spectrum_t), intent(in) :: spec
    real(wp), intent(in) :: corners(:), damping
    logical, intent(in) :: design
    real(wp) :: below, above
    integer :: i
    do i = 1, size(corners)
      if (design) then
        call ec8_design_sa(spec, corners(i)*(1 - 1.0e-12_wp), below, status, message)
        call ec8_design_sa(spec, corners(i)*(1 + 1.0e-12_wp), above, status, message)
      else
        call spectrum_sa(spec, corners(i)*(1 - 1.0e-12_wp), damping, below, status, message)
        call spectrum_sa(spec, corners(i)*(1 + 1.0e-12_wp), damping, above, status, message)
      end if
      call check_true(label//': status', status == SD_OK)
      call check_close(label//': continuous at T = '//num2str(corners(i)), above, &
                       below, 1.0e-9_wp)
    end do
  end subroutine continuous

  !> Heights of the resultants of the first-mode pressure p ~ J1(xi r/R) cosh(xi z/R) cos(theta)
  !> (potential theory, rigid tank): the wall force F = pi R J1(xi) int_0^H cosh(xi z/R) dz, its
  !> moment about the base M_w = pi R J1(xi) int_0^H z cosh(xi z/R) dz, and the moment of the base
  !> pressure M_b = pi int_0^R J1(xi r/R) r^2 dr; h_c = M_w/F, h_c' = (M_w + M_b)/F. Composite
  !> Simpson with 4000 intervals (error ~1e-14 relative here).
  subroutine resultant_heights(radius, depth, hc, hc_ibp)
    real(wp), intent(in) :: radius, depth
    real(wp), intent(out) :: hc, hc_ibp
    integer, parameter :: n = 4000
    real(wp) :: force, wall_moment, base_moment, z, r, w, step
    integer :: i
    force = 0
    wall_moment = 0
    base_moment = 0
    do i = 0, n
      w = merge(1.0_wp, merge(4.0_wp, 2.0_wp, mod(i, 2) == 1), i == 0 .or. i == n)
      step = depth/n
      z = i*step
      force = force + w*step/3*pi*radius*bessel_j1(xi)*cosh(xi*z/radius)
      wall_moment = wall_moment + w*step/3*pi*radius*bessel_j1(xi)*z*cosh(xi*z/radius)
      step = radius/n
      r = i*step
      base_moment = base_moment + w*step/3*pi*bessel_j1(xi*r/radius)*r**2
    end do
    hc = wall_moment/force
    hc_ibp = (wall_moment + base_moment)/force
  end subroutine resultant_heights
end program test_design_codes
