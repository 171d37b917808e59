!> Convective (sloshing) and impulsive parameters of a rigid vertical cylindrical tank of radius R
!> and liquid depth H (and of a rigid rectangular tank of length L by ACI 350.3) by three design
!> codes, so that the program can print them beside its own
!> model: ACI 350.3-06 (Housner's model), API 650 Annex E, and Eurocode 8 Part 4 (EN 1998-4:2006)
!> Annex A. Each formula carries the clause of its code; the constants are the codes' own
!> (3.68 or 3.67 for 2 x 1.841, 0.230, 0.866, 2.01 or 1.937 for 2, ...), so the results differ
!> from potential-flow theory and from each other by those roundings (tests/fortran/
!> test_design_codes.f90 measures by how much).
!>
!> Units: SI throughout (m, s, rad/s); masses are ratios to the liquid mass (W/W_L = m/m_L);
!> heights are measured from the tank base. D = 2 R is the diameter. EBP: heights of the wall
!> pressure resultants, excluding the base pressure (for the wall moment); IBP: including it
!> (for the moment on the foundation).
!>
!> The clause and equation numbers below are those of the published codes as cited in design
!> guides and worked examples; the paid texts themselves (ACI 350.3-06, API 650 12th ed.
!> Annex E, EN 1998-4:2006) were not at hand to check them against. The constants were checked
!> against theory and against independent worked examples (see the test).
module sloshdyn_design_codes
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, check_real
  implicit none
  private
  public :: aci350_parameters, api650_parameters, ec8_parameters
  public :: aci350_circular, aci350_rectangular, aci350_wave_height, api650_circular, api650_wave_height, &
            ec8_circular, ec8_wave_height, ec8_table_a2, table_a2_range, TABLE_A2_COLUMNS

  !> ACI 350.3-06, sec 9.2.2 and 9.2.4 (circular tanks), with H = H_L; the same fields for
  !> rectangular tanks, sec 9.2.1 and 9.2.3 (eq 9-1 to 9-11, L in place of D).
  type :: aci350_parameters
    real(wp) :: lambda = 0                 !< eq 9-29: sqrt(3.68 g tanh(3.68 H/D)) [m^0.5/s]
    real(wp) :: convective_frequency = 0   !< omega_c, eq 9-30: lambda/sqrt(D) [rad/s]
    real(wp) :: convective_period = 0      !< T_c, eq 9-31: 2 pi/omega_c [s]
    real(wp) :: impulsive_ratio = 0        !< W_i/W_L, eq 9-15
    real(wp) :: convective_ratio = 0       !< W_c/W_L, eq 9-16
    real(wp) :: impulsive_height = 0       !< h_i (EBP), eq 9-17/9-18 [m]
    real(wp) :: convective_height = 0      !< h_c (EBP), eq 9-19 [m]
    real(wp) :: impulsive_height_ibp = 0   !< h_i' (IBP), eq 9-20/9-21 [m]
    real(wp) :: convective_height_ibp = 0  !< h_c' (IBP), eq 9-22 [m]
  end type aci350_parameters

  !> API 650 Annex E (12th ed.), SI form.
  type :: api650_parameters
    real(wp) :: ks = 0                     !< sloshing period coefficient K_s, eq E.4.5.2-c
    real(wp) :: convective_period = 0      !< T_c = 1.8 K_s sqrt(D), eq E.4.5.2-a [s]
    real(wp) :: impulsive_ratio = 0        !< W_i/W_p, eq E.6.1.1-1/-2
    real(wp) :: convective_ratio = 0       !< W_c/W_p, eq E.6.1.1-3
    real(wp) :: impulsive_height = 0       !< X_i (ringwall moment), eq E.6.1.2.1-1/-2 [m]
    real(wp) :: convective_height = 0      !< X_c (ringwall moment), eq E.6.1.2.1-3 [m]
    real(wp) :: impulsive_height_slab = 0  !< X_is (slab moment), eq E.6.1.2.2-1/-2 [m]
    real(wp) :: convective_height_slab = 0 !< X_cs (slab moment), eq E.6.1.2.2-3 [m]
  end type api650_parameters

  !> EN 1998-4:2006 Annex A.2.1 (rigid circular tanks), first convective (sloshing) mode, with
  !> gamma = H/R and lambda_1 = 1.841 (first root of J1').
  type :: ec8_parameters
    real(wp) :: convective_frequency = 0   !< omega_c1 = sqrt(g lambda_1/R tanh(lambda_1 gamma)) [rad/s]
    real(wp) :: convective_period = 0      !< T_c1 = 2 pi/omega_c1 [s]
    real(wp) :: convective_ratio = 0       !< m_c1/m = 2 tanh(lambda_1 gamma)/(gamma lambda_1 (lambda_1^2 - 1))
    real(wp) :: convective_height = 0      !< h_c1 (EBP) [m]
    real(wp) :: convective_height_ibp = 0  !< h_c1' (IBP) [m]
    real(wp) :: impulsive_ratio = 0        !< m_i/m, A.2.1 (series, ec8_impulsive)
    real(wp) :: impulsive_height = 0       !< h_i (EBP) [m]
    real(wp) :: impulsive_height_ibp = 0   !< h_i' (IBP) [m]
  end type ec8_parameters

  !> EN 1998-4 Annex A.2.1: the first root of J1' as the code rounds it.
  real(wp), parameter :: ec8_lambda_1 = 1.841_wp
  !> Terms of EN 1998-4 Annex A.2.1's impulsive series (their tail is below 1e-9 relative).
  integer, parameter :: ec8_terms = 20000
  !> EN 1998-4:2006 Annex A, Table A.2 (Malhotra, Wenk and Wieland 2000, Table 1): the
  !> simplified procedure's coefficients of a flexible (steel or concrete) circular tank on a
  !> rigid foundation, by gamma = H/R: C_i, C_c [s/m^0.5], m_i/m, m_c/m, h_i/H, h_c/H, h_i'/H,
  !> h_c'/H (columns 2..9; column 1 is H/R). The values as design guides quote them (the
  !> paid text was not at hand).
  integer, parameter :: TABLE_A2_COLUMNS = 8
  real(wp), parameter :: table_a2(9, 8) = reshape([ &
    0.3_wp, 9.28_wp, 2.09_wp, 0.176_wp, 0.824_wp, 0.400_wp, 0.521_wp, 2.640_wp, 3.414_wp, &
    0.5_wp, 7.74_wp, 1.74_wp, 0.300_wp, 0.700_wp, 0.400_wp, 0.543_wp, 1.460_wp, 1.517_wp, &
    0.7_wp, 6.97_wp, 1.60_wp, 0.414_wp, 0.586_wp, 0.401_wp, 0.571_wp, 1.009_wp, 1.011_wp, &
    1.0_wp, 6.36_wp, 1.52_wp, 0.548_wp, 0.452_wp, 0.419_wp, 0.616_wp, 0.721_wp, 0.785_wp, &
    1.5_wp, 6.06_wp, 1.48_wp, 0.686_wp, 0.314_wp, 0.439_wp, 0.690_wp, 0.555_wp, 0.734_wp, &
    2.0_wp, 6.21_wp, 1.48_wp, 0.763_wp, 0.237_wp, 0.448_wp, 0.751_wp, 0.500_wp, 0.764_wp, &
    2.5_wp, 6.56_wp, 1.48_wp, 0.810_wp, 0.190_wp, 0.452_wp, 0.794_wp, 0.480_wp, 0.796_wp, &
    3.0_wp, 7.03_wp, 1.48_wp, 0.842_wp, 0.158_wp, 0.453_wp, 0.825_wp, 0.472_wp, 0.825_wp], &
    [9, 8])
  !> The range of H/R that Table A.2 covers.
  real(wp), parameter :: table_a2_range(2) = [0.3_wp, 3.0_wp]
  !> Branch points of the ACI and API height and mass formulas (D/H).
  real(wp), parameter :: squat_from = 1.333_wp, aci_tall_ibp_below = 0.75_wp

contains

  !> ACI 350.3-06 (Housner's model) for a circular tank of radius R [m], liquid depth H [m]
  !> under gravity g [m/s^2].
  pure subroutine aci350_circular(radius, depth, gravity, aci, status, message)
    real(wp), intent(in) :: radius, depth, gravity
    type(aci350_parameters), intent(out) :: aci
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    call check_tank(radius, depth, gravity, status, message)
    if (status /= SD_OK) return
    call aci350_housner(2*radius, depth, gravity, 3.68_wp, 0.230_wp, aci)
  end subroutine aci350_circular

  !> ACI 350.3-06 sec 9.2.1 and 9.2.3 (Housner's model) for a rectangular tank of inside length
  !> L [m] in the direction of the motion, liquid depth H_L [m], gravity g [m/s^2]. The
  !> equations as cited in design guides (the paid text was not at hand): 3.16 is sqrt(10),
  !> Housner's rounding of pi.
  pure subroutine aci350_rectangular(length, depth, gravity, aci, status, message)
    real(wp), intent(in) :: length, depth, gravity
    type(aci350_parameters), intent(out) :: aci
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message

    call check_tank(length/2, depth, gravity, status, message)
    if (status /= SD_OK) return
    call aci350_housner(length, depth, gravity, 3.16_wp, 0.264_wp, aci)
  end subroutine aci350_rectangular

  !> ACI 350.3-06's equations, which have one form for both shapes: plan size s = D (circular,
  !> eq 9-15 to 9-31) or L (rectangular, eq 9-1 to 9-11), wave constant c = 3.68 or 3.16 and
  !> convective mass constant c_m = 0.230 or 0.264. Equation numbers: circular / rectangular.
  pure subroutine aci350_housner(plan_size, depth, gravity, c, c_m, aci)
    real(wp), intent(in) :: plan_size, depth, gravity, c, c_m
    type(aci350_parameters), intent(out) :: aci
    real(wp) :: ratio, x, y
    ratio = plan_size/depth                           ! D/H_L or L/H_L
    x = c*depth/plan_size
    y = 0.866_wp*ratio
    aci%lambda = sqrt(c*gravity*tanh(x))              ! eq 9-29 / 9-9
    aci%convective_frequency = aci%lambda/sqrt(plan_size)  ! eq 9-30 / 9-10
    aci%convective_period = 2*pi/aci%convective_frequency  ! eq 9-31 / 9-11
    aci%impulsive_ratio = tanh(y)/y                   ! eq 9-15 / 9-1
    aci%convective_ratio = c_m*ratio*tanh(x)          ! eq 9-16 / 9-2
    if (ratio < squat_from) then
      aci%impulsive_height = (0.5_wp - 0.09375_wp*ratio)*depth      ! eq 9-17 / 9-3
    else
      aci%impulsive_height = 0.375_wp*depth                        ! eq 9-18 / 9-4
    end if
    aci%convective_height = depth*(1 - cosh_ratio(x, 1.0_wp))      ! eq 9-19 / 9-5
    if (ratio < aci_tall_ibp_below) then
      aci%impulsive_height_ibp = 0.45_wp*depth                     ! eq 9-20 / 9-6
    else
      aci%impulsive_height_ibp = (y/(2*tanh(y)) - 0.125_wp)*depth  ! eq 9-21 / 9-7
    end if
    aci%convective_height_ibp = depth*(1 - cosh_ratio(x, 2.01_wp)) ! eq 9-22 / 9-8
  end subroutine aci350_housner

  !> ACI 350.3-06 sec 7.1, eq 7-1 (rectangular) and 7-2 (circular): maximum vertical
  !> displacement of the sloshing wave, d_max = (L/2) C_c I or (D/2) C_c I, with the convective
  !> seismic coefficient C_c taken as the spectral acceleration of the 0.5 %-damped spectrum at
  !> T_c in units of g:
  !>     d_max = half_size I Sa(T_c)/g,   half_size = R = D/2 or L/2.
  !> sa_convective = Sa(T_c) [m/s^2] (for the code's own spectrum, sec 9.4.2, Sa = C_c g with
  !> C_c = 1.5 S_D1/T_c <= 1.5 S_DS or 2.4 S_DS/T_c^2), importance = I, gravity = g [m/s^2].
  pure subroutine aci350_wave_height(half_size, sa_convective, gravity, importance, d_max, &
                                     status, message)
    real(wp), intent(in) :: half_size, sa_convective, gravity, importance
    real(wp), intent(out) :: d_max
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message

    call check_wave(half_size, sa_convective, 'Sa', '[m/s^2]', gravity, d_max, status, message)
    call check_real('I', importance, 0.0_wp, huge(1.0_wp), .true., .true., &
                    'the importance factor must be > 0', status, message)
    if (status /= SD_OK) return
    d_max = half_size*importance*sa_convective/gravity   ! eq 7-1, 7-2
  end subroutine aci350_wave_height

  !> API 650 Annex E for a tank of radius R [m] and design liquid level H [m] (SI forms: the
  !> period formula has g built in, D in m gives T_c in s).
  pure subroutine api650_circular(radius, depth, api, status, message)
    real(wp), intent(in) :: radius, depth
    type(api650_parameters), intent(out) :: api
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: diameter, ratio, x, y

    call check_tank(radius, depth, 1.0_wp, status, message)
    if (status /= SD_OK) return
    diameter = 2*radius
    ratio = diameter/depth                                        ! D/H
    x = 3.67_wp*depth/diameter
    y = 0.866_wp*ratio
    api%ks = 0.578_wp/sqrt(tanh(3.68_wp*depth/diameter))          ! eq E.4.5.2-c
    api%convective_period = 1.8_wp*api%ks*sqrt(diameter)          ! eq E.4.5.2-a (SI)
    api%convective_ratio = 0.230_wp*ratio*tanh(x)                 ! eq E.6.1.1-3
    api%convective_height = depth*(1 - cosh_ratio(x, 1.0_wp))     ! eq E.6.1.2.1-3
    api%convective_height_slab = depth*(1 - cosh_ratio(x, 1.937_wp))   ! eq E.6.1.2.2-3
    if (ratio >= squat_from) then
      api%impulsive_ratio = tanh(y)/y                             ! eq E.6.1.1-1
      api%impulsive_height = 0.375_wp*depth                       ! eq E.6.1.2.1-1
      api%impulsive_height_slab = 0.375_wp*(1 + 1.333_wp*(y/tanh(y) - 1))*depth  ! E.6.1.2.2-1
    else
      api%impulsive_ratio = 1 - 0.218_wp*ratio                    ! eq E.6.1.1-2
      api%impulsive_height = (0.5_wp - 0.094_wp*ratio)*depth      ! eq E.6.1.2.1-2
      api%impulsive_height_slab = (0.5_wp + 0.06_wp*ratio)*depth  ! eq E.6.1.2.2-2
    end if
  end subroutine api650_circular

  !> API 650 E.7.2, eq E.7.2-1: sloshing wave height delta_s = 0.42 D A_f [m], with A_f the
  !> acceleration coefficient for the sloshing wave height (in g; eq E.7.2-2 to -5 give it from
  !> the site spectrum, the importance and T_c).
  pure subroutine api650_wave_height(radius, af, delta_s, status, message)
    real(wp), intent(in) :: radius, af
    real(wp), intent(out) :: delta_s
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message

    call check_wave(radius, af, 'Af', '[g]', 1.0_wp, delta_s, status, message)
    if (status /= SD_OK) return
    delta_s = 0.42_wp*(2*radius)*af                   ! eq E.7.2-1
  end subroutine api650_wave_height

  !> EN 1998-4:2006 Annex A.2.1 (rigid circular tank, convective component, first mode).
  !> Frequency and mass as the code gives them; the heights are the resultants of the code's
  !> first-mode convective pressure (wall pressure ~ cosh(lambda_1 z/R), base pressure
  !> ~ J1(lambda_1 r/R)), which integrate to
  !>     h_c1  = H [1 - (cosh(lambda_1 gamma) - 1)/(lambda_1 gamma sinh(lambda_1 gamma))],
  !>     h_c1' = H [1 - (cosh(lambda_1 gamma) - 2)/(lambda_1 gamma sinh(lambda_1 gamma))].
  pure subroutine ec8_circular(radius, depth, gravity, ec8, status, message)
    real(wp), intent(in) :: radius, depth, gravity
    type(ec8_parameters), intent(out) :: ec8
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: gamma, x

    call check_tank(radius, depth, gravity, status, message)
    if (status /= SD_OK) return
    gamma = depth/radius
    x = ec8_lambda_1*gamma
    ec8%convective_frequency = sqrt(gravity*ec8_lambda_1/radius*tanh(x))
    ec8%convective_period = 2*pi/ec8%convective_frequency
    ec8%convective_ratio = 2*tanh(x)/(gamma*ec8_lambda_1*(ec8_lambda_1**2 - 1))
    ec8%convective_height = depth*(1 - cosh_ratio(x, 1.0_wp))
    ec8%convective_height_ibp = depth*(1 - cosh_ratio(x, 2.0_wp))
    call ec8_impulsive(gamma, radius, depth, ec8)
  end subroutine ec8_circular

  !> EN 1998-4:2006 Annex A.2.1 (rigid circular tank), impulsive component: with
  !> nu_n = (2n + 1) pi/2 and gamma = H/R, the wall pressure
  !> p_i = 2 rho H cos(theta) A_g sum (-1)^n cos(nu_n z/H) I1(nu_n r/(R gamma))/(nu_n^2 I1'(nu_n/gamma))
  !> integrates to the impulsive mass
  !>     m_i/m = 2 gamma sum a_n,   a_n = I1(nu_n/gamma)/(nu_n^3 I1'(nu_n/gamma))
  !> and to the heights of its resultant, excluding the base pressure (wall moment)
  !>     h_i/H = sum a_n (1 - (-1)^n/nu_n) / sum a_n
  !> and including it (the base pressure's moment, with int_0^1 x^2 I1(k x) dx = I2(k)/k)
  !>     h_i' = h_i + R sum (-1)^n I2(nu_n/gamma)/(nu_n^3 I1'(nu_n/gamma)) / sum a_n.
  !> I1' = I0 - I1/x; the Bessel functions scaled by e^-x (their ratios only).
  pure subroutine ec8_impulsive(gamma, radius, depth, ec8)
    real(wp), intent(in) :: gamma, radius, depth
    type(ec8_parameters), intent(inout) :: ec8
    real(wp) :: nu, x, i1, d1, a, total, moment, base
    integer :: n
    total = 0
    moment = 0
    base = 0
    do n = ec8_terms - 1, 0, -1            ! smallest terms first
      nu = (2*n + 1)*pi/2
      x = nu/gamma
      i1 = scaled_bessel_i(1, x)
      d1 = scaled_bessel_i(0, x) - i1/x    ! I1'(x) e^-x
      a = i1/(nu**3*d1)
      total = total + a
      moment = moment + a*(1 - (-1)**n/nu)
      base = base + (-1)**n*scaled_bessel_i(2, x)/(nu**3*d1)
    end do
    ec8%impulsive_ratio = 2*gamma*total
    ec8%impulsive_height = depth*moment/total
    ec8%impulsive_height_ibp = ec8%impulsive_height + radius*base/total
  end subroutine ec8_impulsive

  !> e^-x I_nu(x), nu = 0, 1, 2, x > 0 (Abramowitz and Stegun 9.6.10 power series for x <= 20,
  !> 9.7.1 asymptotic expansion beyond, both to round-off there).
  elemental real(wp) function scaled_bessel_i(nu, x) result(value)
    integer, intent(in) :: nu
    real(wp), intent(in) :: x
    real(wp) :: term, total
    integer :: k
    if (x <= 20) then
      term = (x/2)**nu/gamma(real(nu + 1, wp))
      total = term
      do k = 1, 200
        term = term*(x/2)**2/(k*(k + nu))
        total = total + term
        if (term <= epsilon(1.0_wp)*total) exit
      end do
      value = total*exp(-x)
    else
      term = 1
      total = 1
      do k = 1, 40
        term = -term*(4*nu**2 - (2*k - 1)**2)/(8*k*x)
        total = total + term
        if (abs(term) <= epsilon(1.0_wp)*abs(total)) exit
      end do
      value = total/sqrt(2*pi*x)
    end if
  end function scaled_bessel_i

  !> EN 1998-4:2006 Annex A (A.2.1.4 as cited): maximum vertical displacement of the liquid
  !> surface at the wall, d_max = 0.84 R Se(T_c1)/g, with Se(T_c1) [m/s^2] the elastic spectral
  !> acceleration at the first sloshing period (for the damping the code prescribes for the
  !> convective response). 0.84 is 2/(lambda_1^2 - 1) = 0.837 rounded.
  pure subroutine ec8_wave_height(radius, se_convective, gravity, d_max, status, message)
    real(wp), intent(in) :: radius, se_convective, gravity
    real(wp), intent(out) :: d_max
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message

    call check_wave(radius, se_convective, 'Se', '[m/s^2]', gravity, d_max, status, message)
    if (status /= SD_OK) return
    d_max = 0.84_wp*radius*se_convective/gravity
  end subroutine ec8_wave_height

  !> EN 1998-4 Table A.2's coefficients at gamma = H/R (C_i, C_c, m_i/m, m_c/m, h_i/H, h_c/H,
  !> h_i'/H, h_c'/H), linear between its rows, the end row outside its range (the caller says
  !> so: table_a2_range).
  pure function ec8_table_a2(gamma) result(row)
    real(wp), intent(in) :: gamma
    real(wp) :: row(TABLE_A2_COLUMNS), w
    integer :: i
    if (gamma <= table_a2(1, 1)) then
      row = table_a2(2:9, 1)
    else if (gamma >= table_a2(1, 8)) then
      row = table_a2(2:9, 8)
    else
      i = 1
      do while (table_a2(1, i + 1) < gamma)
        i = i + 1
      end do
      w = (gamma - table_a2(1, i))/(table_a2(1, i + 1) - table_a2(1, i))
      row = (1 - w)*table_a2(2:9, i) + w*table_a2(2:9, i + 1)
    end if
  end function ec8_table_a2

  !> (cosh x - c)/(x sinh x), x > 0, without overflow for deep tanks:
  !> cosh x - 1 = 2 sinh^2(x/2) and sinh x = 2 sinh(x/2) cosh(x/2) give
  !> (cosh x - c)/(x sinh x) = tanh(x/2)/x + (1 - c)/(x sinh x), and 1/sinh x = 2 e^{-x} to
  !> round-off for x > 20.
  elemental real(wp) function cosh_ratio(x, c) result(ratio)
    real(wp), intent(in) :: x, c
    real(wp) :: csch
    if (x > 20) then
      csch = 2*exp(-x)
    else
      csch = 1/sinh(x)
    end if
    ratio = tanh(x/2)/x + (1 - c)*csch/x
  end function cosh_ratio

  !> R (or L/2) > 0, H > 0 and g > 0 (API 650's formulas have g built in: 1 passes).
  pure subroutine check_tank(half_size, depth, gravity, status, message)
    real(wp), intent(in) :: half_size, depth, gravity
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    status = SD_OK
    message = ''
    call check_real('R', half_size, 0.0_wp, huge(1.0_wp), .true., .true., &
                    'the tank radius (or half length) must be > 0 [m]', status, message)
    call check_real('H', depth, 0.0_wp, huge(1.0_wp), .true., .true., &
                    'the liquid depth must be > 0 [m]', status, message)
    call check_real('g', gravity, 0.0_wp, huge(1.0_wp), .true., .true., &
                    'the gravitational acceleration must be > 0 [m/s^2]', status, message)
  end subroutine check_tank

  !> The inputs of a wave height: R (or L/2) > 0, the spectral acceleration `name` >= 0 in
  !> `units`, g > 0; the height set to 0 until computed.
  pure subroutine check_wave(half_size, acceleration, name, units, gravity, height, status, &
                             message)
    real(wp), intent(in) :: half_size, acceleration, gravity
    character(len=*), intent(in) :: name, units
    real(wp), intent(out) :: height
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    height = 0
    call check_tank(half_size, 1.0_wp, gravity, status, message)
    call check_real(name, acceleration, 0.0_wp, huge(1.0_wp), .false., .true., &
                    'the convective spectral acceleration must be >= 0 '//units, status, message)
  end subroutine check_wave
end module sloshdyn_design_codes
