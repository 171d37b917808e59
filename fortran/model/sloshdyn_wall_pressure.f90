!> The hydrodynamic pressure on the wall and on the base of a rigid vertical circular cylindrical
!> tank under a horizontal acceleration, by linear potential flow (Jacobsen 1949; Veletsos &
!> Yang 1977; EN 1998-4:2006 Annex A.2.1.2 (impulsive) and A.2.1.3 (convective)), and the
!> resultants of each component (mass, heights of the resultant
!> excluding and including the base pressure). docs/model.md ("Hydrodynamic wall and base pressure") derives every formula.
!>
!> Coordinates: R the radius, H the liquid depth, gamma = H/R, xi = r/R, zeta = z/H (z from the
!> bottom), theta the angle around the axis from the direction of the acceleration's inertia
!> force (the pressure is largest at theta = 0 for a positive acceleration, and its resultant
!> on the wall and base is the base shear: positive along the acceleration).
!>   impulsive (A_g: the tank's acceleration):
!>     p_i = C_i(xi, zeta) rho H A_g cos(theta),
!>     C_i = 2 sum_{n>=0} (-1)^n cos(nu_n zeta) I1(nu_n xi/gamma)/(I1'(nu_n/gamma) nu_n^2),
!>     nu_n = (2n+1) pi/2;
!>   convective mode n (A_n: the absolute acceleration of the mode's oscillator):
!>     p_cn = rho psi_n cosh(lambda_n gamma zeta) J1(lambda_n xi) cos(theta) A_n,
!>     psi_n = 2 R/((lambda_n^2 - 1) J1(lambda_n) cosh(lambda_n gamma)),
!>     lambda_n the roots of J1' (sloshdyn_tank's modal_wave_number, the same as the modes').
!> The wall series of C_i converges like 1/n (terms ~ 1/nu_n^2 without alternation near the
!> free surface): it is summed with its two leading asymptotic terms taken out in closed form
!> (Kummer's transformation; impulsive_wall), so the remainder falls like n^-4 and the number of
!> terms is set for a stated absolute accuracy of C_i (series_tolerance).
!> Rectangular tanks are refused (their closed forms, Graham & Rodriguez 1952, are not coded).
module sloshdyn_wall_pressure
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, check_real
  use sloshdyn_text, only: num2str
  use sloshdyn_tank, only: modal_wave_number, max_modes, SHAPE_CIRCULAR
  use sloshdyn_vessel, only: tank_t, tank_properties, tank_model
  use sloshdyn_model, only: model_t
  use sloshdyn_tables, only: WALL_PRESSURE_ROWS, BASE_PRESSURE_ROWS, PRESSURE_RESULTANT_ROWS
  implicit none
  private
  public :: impulsive_series, new_impulsive_series, impulsive_wall, impulsive_base, &
            impulsive_resultants, convective_coefficient, convective_resultants, &
            scaled_bessel_i, pressure_tables, check_pressure_input, instant_pressure_tables
  public :: COMBINE_SRSS, COMBINE_SUM, combination_names, max_aspect_ratio, series_tolerance

  !> How the table combines components whose peaks need not be simultaneous: SRSS (the
  !> convective modes' pressures as the square root of the sum of their squares, then the total
  !> as the SRSS of impulsive and convective, API 650 Annex E's rule for the hoop forces), or
  !> SUM (algebraic sums: the pressures of one instant, or with positive spectral accelerations
  !> the absolute sum, the upper bound).
  integer, parameter :: COMBINE_SRSS = 1, COMBINE_SUM = 2
  character(len=*), parameter :: combination_names(2) = [character(len=4) :: 'srss', 'sum']
  !> H/R above this needs more than ~4e4 terms of the impulsive series (beyond H/R = 1 they grow
  !> as H/R); no tank is that slender.
  real(wp), parameter :: max_aspect_ratio = 100
  !> Absolute accuracy of C_i on the wall (C_i is of order 1 for H/R <= 1 and ~ R/H beyond: the
  !> tolerance is scaled with min(1, R/H)) and of the base series' terms.
  real(wp), parameter :: series_tolerance = 1.0e-10_wp
  !> Least number of terms: the alternating series (h_i, the base moment) then err by less
  !> than 1/nu_N^3 < 4e-12.
  integer, parameter :: min_terms = 2000
  !> Apery's constant zeta(3): sum 1/nu_n^3 = 7 zeta(3)/pi^3.
  real(wp), parameter :: apery = 1.2020569031595942854_wp

  !> The impulsive series of one aspect ratio gamma = H/R: nu_n, I1(nu_n/gamma)/I1'(nu_n/gamma)
  !> and I2(nu_n/gamma)/I1'(nu_n/gamma) for n = 0..N-1.
  type :: impulsive_series
    real(wp) :: gamma = 0
    real(wp), allocatable :: nu(:), ratio(:), base_ratio(:)
  end type impulsive_series

contains

  !> The terms of the impulsive series of gamma = H/R (0 < gamma <= max_aspect_ratio, checked
  !> by the caller). N: the Kummer remainder of the wall series (impulsive_wall) has terms of at
  !> most 1.56 gamma^2/nu_n^4 (|I1/I1'(x) - 1 - 1/(2x)| <= 0.78/x^2 for all x > 0), so its tail
  !> beyond N is below 0.0427 gamma^2/(2N - 1)^3; N makes that series_tolerance min(1, 1/gamma).
  pure function new_impulsive_series(gamma) result(series)
    real(wp), intent(in) :: gamma
    type(impulsive_series) :: series
    real(wp) :: tolerance, x, i1p
    integer :: n, terms
    tolerance = series_tolerance*min(1.0_wp, 1/gamma)
    terms = max(min_terms, ceiling(((0.05_wp*gamma**2/tolerance)**(1.0_wp/3) + 1)/2))
    series%gamma = gamma
    allocate (series%nu(0:terms - 1), series%ratio(0:terms - 1), series%base_ratio(0:terms - 1))
    do n = 0, terms - 1
      series%nu(n) = (2*n + 1)*pi/2
      x = series%nu(n)/gamma
      i1p = scaled_bessel_i1_prime(x)
      series%ratio(n) = scaled_bessel_i(1, x)/i1p
      series%base_ratio(n) = scaled_bessel_i(2, x)/i1p
    end do
  end function new_impulsive_series

  !> C_i(1, zeta) on the wall, 0 <= zeta <= 1. With s = 1 - zeta, (-1)^n cos(nu_n zeta) =
  !> sin(nu_n s) and I1/I1'(x) = 1 + 1/(2x) + O(x^-2) (x = nu_n/gamma), so
  !>   C_i = S(s) + gamma (1 - zeta^2)/4 + 2 sum sin(nu_n s) (r_n - 1 - gamma/(2 nu_n))/nu_n^2,
  !> with the closed forms 2 sum (-1)^n cos(nu_n zeta)/nu_n^3 = (1 - zeta^2)/2 (the cosine series
  !> of (1 - zeta^2)/2) and S(s) = 2 sum sin(nu_n s)/nu_n^2 = (8/pi^2) chi(pi s/2), chi(x) =
  !> sum sin((2n+1)x)/(2n+1)^2 = -(1/2) int_0^x log tan(t/2) dt (clausen_odd).
  pure real(wp) function impulsive_wall(series, zeta) result(c)
    type(impulsive_series), intent(in) :: series
    real(wp), intent(in) :: zeta
    real(wp) :: s
    s = 1 - zeta
    associate (nu => series%nu, g => series%gamma)
      c = 8/pi**2*clausen_odd(pi*s/2) + g*(1 - zeta**2)/4 + &
          2*sum(sin(nu*s)*(series%ratio - 1 - g/(2*nu))/nu**2)
    end associate
  end function impulsive_wall

  !> C_i(xi, 0) on the base, 0 <= xi <= 1: an alternating series (cos(0) = 1) of falling terms
  !> b_n = 2 I1(nu_n xi/gamma)/(I1'(nu_n/gamma) nu_n^2), summed until b_n < series_tolerance
  !> min(1, 1/gamma), which bounds the error; xi = 1 (the corner) is the wall's zeta = 0.
  pure real(wp) function impulsive_base(series, xi) result(c)
    type(impulsive_series), intent(in) :: series
    real(wp), intent(in) :: xi
    real(wp) :: tolerance, nu, term, x
    integer :: n
    if (xi >= 1) then
      c = impulsive_wall(series, 0.0_wp)
      return
    end if
    tolerance = series_tolerance*min(1.0_wp, 1/series%gamma)
    c = 0
    n = 0
    do
      nu = (2*n + 1)*pi/2
      x = nu/series%gamma
      ! I1(x xi)/I1'(x) from the scaled functions: the factor exp(x xi - x) <= 1 never overflows
      term = 2*scaled_bessel_i(1, x*xi)/scaled_bessel_i1_prime(x)*exp(x*(xi - 1))/nu**2
      c = c + merge(term, -term, mod(n, 2) == 0)
      if (term < tolerance) exit
      n = n + 1
    end do
  end function impulsive_base

  !> The impulsive mass over the liquid mass, m_i/m_F, and the heights of the impulsive
  !> resultant over H excluding (h_i/H, wall only) and including (h_i'/H) the base pressure
  !> (EN 1998-4 A.2.1.2 defines m_i, h_i, h_i' as these resultants). Integrating p_i:
  !>   m_i/m_F = 2 gamma S3, S3 = sum r_n/nu_n^3 (= 7 zeta(3)/pi^3 + gamma/12
  !>             + sum (r_n - 1 - gamma/(2 nu_n))/nu_n^3, with sum 1/nu_n^4 = 1/6)
  !>   h_i/H   = 1 - S4/S3, S4 = sum (-1)^n r_n/nu_n^4   (int_0^1 zeta cos(nu zeta) dzeta
  !>             = (-1)^n/nu - 1/nu^2)
  !>   h_i'/H  = (2 gamma (S3 - S4) + 2 sum (-1)^n q_n/nu_n^3)/(2 gamma S3), the base's moment
  !>             from int_0^1 I1(k xi) xi^2 dxi = I2(k)/k,
  !> with r_n = I1/I1'(nu_n/gamma), q_n = I2/I1'(nu_n/gamma).
  pure subroutine impulsive_resultants(series, mass_ratio, height_ratio, height_ratio_ibp)
    type(impulsive_series), intent(in) :: series
    real(wp), intent(out) :: mass_ratio, height_ratio, height_ratio_ibp
    real(wp) :: s3, s4, base
    associate (nu => series%nu, g => series%gamma, sign => alternating(size(series%nu)))
      s3 = 7*apery/pi**3 + g/12 + sum((series%ratio - 1 - g/(2*nu))/nu**3)
      s4 = sum(sign*series%ratio/nu**4)
      base = 2*sum(sign*series%base_ratio/nu**3)
      mass_ratio = 2*g*s3
      height_ratio = 1 - s4/s3
      height_ratio_ibp = (2*g*(s3 - s4) + base)/mass_ratio
    end associate
  end subroutine impulsive_resultants

  !> (-1)^n for n = 0..count-1.
  pure function alternating(count) result(sign)
    integer, intent(in) :: count
    real(wp) :: sign(count)
    integer :: n
    sign = [(merge(1.0_wp, -1.0_wp, mod(n, 2) == 0), n = 0, count - 1)]
  end function alternating

  !> p_cn/(rho R A_n) of mode n at (xi, zeta) for gamma = H/R: psi_n cosh(lambda_n gamma zeta)
  !> J1(lambda_n xi)/R = 2 J1(lambda_n xi) cosh(x zeta)/((lambda_n^2 - 1) J1(lambda_n) cosh x),
  !> x = lambda_n gamma, the ratio of cosh in exponentials that do not overflow; on the wall
  !> (xi = 1) and on the base (zeta = 0).
  elemental real(wp) function convective_coefficient(n, gamma, xi, zeta) result(c)
    integer, intent(in) :: n
    real(wp), intent(in) :: gamma, xi, zeta
    real(wp) :: lambda, x
    lambda = modal_wave_number(SHAPE_CIRCULAR, 1.0_wp, n)
    x = lambda*gamma
    c = 2/(lambda**2 - 1)*bessel_j1(lambda*xi)/bessel_j1(lambda)*exp(x*(zeta - 1))* &
        (1 + exp(-2*x*zeta))/(1 + exp(-2*x))
  end function convective_coefficient

  !> Mode n's convective mass over m_F and the heights of its resultant over H excluding and
  !> including the base pressure (EN 1998-4 A.2.1.3), x = lambda_n gamma:
  !>   m_cn/m_F = 2 tanh(x)/(x (lambda_n^2 - 1)),
  !>   h_cn/H = 1 + (1 - cosh x)/(x sinh x) = 1 - tanh(x/2)/x,
  !>   h_cn'/H = 1 + (2 - cosh x)/(x sinh x) = 1 - tanh(x/2)/x + 1/(x sinh x)
  !> (the base's moment from int_0^1 J1(lambda xi) xi^2 dxi = J2(lambda)/lambda = J1(lambda)/
  !> lambda^2 at a root of J1').
  elemental subroutine convective_resultants(n, gamma, mass_ratio, height_ratio, &
                                             height_ratio_ibp)
    integer, intent(in) :: n
    real(wp), intent(in) :: gamma
    real(wp), intent(out) :: mass_ratio, height_ratio, height_ratio_ibp
    real(wp) :: lambda, x
    lambda = modal_wave_number(SHAPE_CIRCULAR, 1.0_wp, n)
    x = lambda*gamma
    mass_ratio = 2*tanh(x)/(x*(lambda**2 - 1))
    height_ratio = 1 - tanh(x/2)/x
    height_ratio_ibp = height_ratio + 2*exp(-x)/(x*(1 - exp(-2*x)))
  end subroutine convective_resultants

  !> chi(x) = sum_{n>=0} sin((2n+1) x)/(2n+1)^2 for 0 <= x <= pi/2 (Legendre's chi-type
  !> Clausen function; chi(pi/2) = Catalan's constant): its derivative is
  !> sum cos((2n+1)x)/(2n+1) = -(1/2) log tan(x/2), so chi(x) = -(1/2) [x log(x/2) - x +
  !> int_0^x log(tan(t/2)/(t/2)) dt], the last integrand smooth (analytic for |t| < pi) and
  !> integrated by 20-point Gauss-Legendre to rounding.
  pure real(wp) function clausen_odd(x) result(chi)
    real(wp), intent(in) :: x
    integer, parameter :: points = 20
    real(wp) :: nodes(points), weights(points), t(points)
    if (x <= 0) then
      chi = 0
      return
    end if
    call gauss_legendre(nodes, weights)
    t = x*(nodes + 1)/4     ! t/2 at the nodes mapped to [0, x]
    chi = -(x*log(x/2) - x + x/2*sum(weights*log(tan(t)/t)))/2
  end function clausen_odd

  !> Gauss-Legendre nodes and weights on [-1, 1], by Newton's method on P_n from the
  !> Chebyshev guesses cos(pi (i - 1/4)/(n + 1/2)) (Numerical Recipes' gauleg).
  pure subroutine gauss_legendre(nodes, weights)
    real(wp), intent(out) :: nodes(:), weights(size(nodes))
    real(wp) :: z, p0, p1, p2, dp
    integer :: i, k, iteration, n
    n = size(nodes)
    do i = 1, n
      z = cos(pi*(i - 0.25_wp)/(n + 0.5_wp))
      do iteration = 1, 100
        p1 = 1
        p0 = 0
        do k = 1, n
          p2 = p0
          p0 = p1
          p1 = ((2*k - 1)*z*p0 - (k - 1)*p2)/k
        end do
        dp = n*(z*p1 - p0)/(z**2 - 1)
        z = z - p1/dp
        if (abs(p1/dp) < 1.0e-15_wp) exit
      end do
      nodes(i) = z
      weights(i) = 2/((1 - z**2)*dp**2)
    end do
  end subroutine gauss_legendre

  !> exp(-x) I_order(x), order 0, 1 or 2, x >= 0: the ascending series for x <= 25 (positive
  !> terms, no cancellation), else Hankel's asymptotic expansion (Abramowitz & Stegun 9.7.1),
  !> cut at its smallest term (below 1e-20 for x > 25).
  elemental real(wp) function scaled_bessel_i(order, x) result(value)
    integer, intent(in) :: order
    real(wp), intent(in) :: x
    real(wp) :: term, mu
    integer :: k
    if (x <= 25) then
      ! (x/2)^order sum (x^2/4)^k/(k! (k + order)!)
      term = (x/2)**order/product([(real(k, wp), k = 1, order)])
      value = term
      k = 0
      do while (term > epsilon(1.0_wp)*value/4)
        k = k + 1
        term = term*(x/2)**2/(k*(k + order))
        value = value + term
      end do
      value = value*exp(-x)
    else
      ! (2 pi x)^(-1/2) sum (-1)^k a_k(order)/x^k, a_k = prod_{j<=k} (4 order^2 - (2j - 1)^2)/(8^k k!)
      mu = 4*real(order, wp)**2
      term = 1
      value = 1
      do k = 1, 60
        if (abs(term*(mu - (2*k - 1)**2)/(8*k*x)) >= abs(term)) exit
        term = -term*(mu - (2*k - 1)**2)/(8*k*x)
        value = value + term
        if (abs(term) < epsilon(1.0_wp)*abs(value)/4) exit
      end do
      value = value/sqrt(2*pi*x)
    end if
  end function scaled_bessel_i

  !> exp(-x) I1'(x) = exp(-x) (I0(x) - I1(x)/x); 1/2 at x = 0.
  elemental real(wp) function scaled_bessel_i1_prime(x) result(value)
    real(wp), intent(in) :: x
    if (x > 0) then
      value = scaled_bessel_i(0, x) - scaled_bessel_i(1, x)/x
    else
      value = 0.5_wp
    end if
  end function scaled_bessel_i1_prime

  !> The rules of the pressure tables' inputs (beyond the tank's own, checked by tank_model):
  !> a circular tank with H/R <= max_aspect_ratio, finite accelerations, at most max_modes
  !> convective ones, a known combination, heights in [0, H] and radii in [0, R].
  pure subroutine check_pressure_input(tank, impulsive_acceleration, convective_accelerations, &
                                       angle, combination, heights, radii, status, message)
    type(tank_t), intent(in) :: tank
    real(wp), intent(in) :: impulsive_acceleration, convective_accelerations(:), angle, &
                            heights(:), radii(:)
    integer, intent(in) :: combination
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    real(wp), parameter :: big = huge(1.0_wp)
    integer :: i
    if (status /= SD_OK) return
    if (tank%shape /= SHAPE_CIRCULAR) then
      status = SD_BAD_INPUT
      message = 'shape = rectangular: the wall pressure is coded for circular tanks only '// &
                '(EN 1998-4 A.2.1); a rectangular tank''s closed forms (Graham & Rodriguez '// &
                '1952) are not'
      return
    end if
    call check_real('liquid_depth/radius', tank%liquid_depth/tank%radius, 0.0_wp, &
                    max_aspect_ratio, .true., .false., 'the aspect ratio H/R of the wall '// &
                    'pressure must lie in (0, '//num2str(max_aspect_ratio)//']: the impulsive '// &
                    'series needs ~ 400 H/R terms', status, message)
    call check_real('impulsive_acceleration', impulsive_acceleration, -big, big, .false., &
                    .false., 'the impulsive acceleration [m/s^2] must be finite', status, message)
    call check_real('angle', angle, -big, big, .false., .false., &
                    'the angle [rad] must be finite', status, message)
    if (status /= SD_OK) return
    if (size(convective_accelerations) > max_modes) then
      status = SD_BAD_INPUT
      message = 'convective_accelerations: '//num2str(size(convective_accelerations))// &
                ' given, at most '//num2str(max_modes)//' (one per sloshing mode 1..'// &
                num2str(max_modes)//')'
      return
    end if
    if (combination /= COMBINE_SRSS .and. combination /= COMBINE_SUM) then
      status = SD_BAD_INPUT
      message = 'combination = '//num2str(combination)//' is not known; allowed: '// &
                'srss (1), sum (2)'
      return
    end if
    do i = 1, size(convective_accelerations)
      call check_real('convective_accelerations('//num2str(i)//')', &
                      convective_accelerations(i), -big, big, .false., .false., &
                      'the convective accelerations [m/s^2] must be finite', status, message)
    end do
    do i = 1, size(heights)
      call check_real('heights('//num2str(i)//')', heights(i), 0.0_wp, tank%liquid_depth, &
                      .false., .false., 'the heights on the wall [m] must lie in [0, '// &
                      'liquid_depth = '//num2str(tank%liquid_depth)//']', status, message)
    end do
    do i = 1, size(radii)
      call check_real('radii('//num2str(i)//')', radii(i), 0.0_wp, tank%radius, .false., &
                      .false., 'the radii on the base [m] must lie in [0, radius = '// &
                      num2str(tank%radius)//']', status, message)
    end do
  end subroutine check_pressure_input

  !> The tank's properties (sloshdyn_vessel's tank_model, which checks the tank), the checks of
  !> check_pressure_input, gamma = H/R and the liquid density rho [kg/m^3].
  pure subroutine prepare(tank, acceleration, mode_accelerations, angle, combination, heights, &
                          radii, props, gamma, rho, status, message)
    type(tank_t), intent(in) :: tank
    real(wp), intent(in) :: acceleration, mode_accelerations(:), angle, heights(:), radii(:)
    integer, intent(in) :: combination
    type(tank_properties), intent(out) :: props
    real(wp), intent(out) :: gamma, rho
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(model_t) :: model
    gamma = 0
    rho = 0
    call tank_model(tank, model, props, status, message)
    call check_pressure_input(tank, acceleration, mode_accelerations, angle, combination, &
                              heights, radii, status, message)
    if (status /= SD_OK) return
    gamma = tank%liquid_depth/tank%radius
    rho = props%liquid_mass/(pi*tank%radius**2*tank%liquid_depth)
  end subroutine prepare

  !> The tables 'wall_pressure' (one column per height z: z [m], impulsive, convective and
  !> total pressure [Pa], hoop force [N/m] = total pressure x R), 'base_pressure' (one column
  !> per radius r: r [m], impulsive, convective, total [Pa]) and 'pressure_resultants' (one
  !> column per component: 0 impulsive, n convective mode n; its mass [kg], the heights of its
  !> resultant excluding and including the base pressure [m], its base shear [N] and
  !> overturning moments excluding and including the base pressure [N m] under the given
  !> acceleration) of a tank (sloshdyn_vessel; circular) under the impulsive acceleration A_g
  !> [m/s^2] and the convective ones A_1..A_N [m/s^2] (N = size, the modes' pseudo-spectral
  !> accelerations or the oscillators' absolute accelerations), at the angle theta [rad],
  !> the modes combined by combination (COMBINE_SRSS, COMBINE_SUM): every pressure is its
  !> value at theta = 0 (combined there) times cos(theta). Nothing is filled on failure (0).
  pure subroutine pressure_tables(tank, impulsive_acceleration, convective_accelerations, &
                                  angle, combination, heights, radii, wall, base, resultants, &
                                  status, message)
    type(tank_t), intent(in) :: tank
    real(wp), intent(in) :: impulsive_acceleration, convective_accelerations(:), angle, &
                            heights(:), radii(:)
    integer, intent(in) :: combination
    real(wp), intent(out) :: wall(WALL_PRESSURE_ROWS, size(heights)), &
                             base(BASE_PRESSURE_ROWS, size(radii)), &
                             resultants(PRESSURE_RESULTANT_ROWS, size(convective_accelerations) + 1)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(tank_properties) :: props
    type(impulsive_series) :: series
    real(wp) :: gamma, rho, modal(size(convective_accelerations)), mass, h, h_ibp
    integer :: i, n, modes

    wall = 0
    base = 0
    resultants = 0
    call prepare(tank, impulsive_acceleration, convective_accelerations, angle, combination, &
                 heights, radii, props, gamma, rho, status, message)
    if (status /= SD_OK) return
    modes = size(convective_accelerations)
    associate (big_r => tank%radius, big_h => tank%liquid_depth, a_g => impulsive_acceleration, &
               a_n => convective_accelerations, cos_theta => cos(angle))
      series = new_impulsive_series(gamma)
      do i = 1, size(heights)
        modal = [(convective_coefficient(n, gamma, 1.0_wp, heights(i)/big_h)*rho*big_r*a_n(n), &
                   n = 1, modes)]
        wall(1:4, i) = [heights(i), combined(impulsive_wall(series, heights(i)/big_h)*rho* &
                                             big_h*a_g, modal)*cos_theta]
        wall(5, i) = wall(4, i)*big_r
      end do
      do i = 1, size(radii)
        modal = [(convective_coefficient(n, gamma, radii(i)/big_r, 0.0_wp)*rho*big_r*a_n(n), &
                   n = 1, modes)]
        base(:, i) = [radii(i), combined(impulsive_base(series, radii(i)/big_r)*rho*big_h*a_g, &
                                         modal)*cos_theta]
      end do
      call impulsive_resultants(series, mass, h, h_ibp)
      resultants(:, 1) = resultant_row(0, mass, h, h_ibp, a_g)
      do n = 1, modes
        call convective_resultants(n, gamma, mass, h, h_ibp)
        resultants(:, n + 1) = resultant_row(n, mass, h, h_ibp, a_n(n))
      end do
    end associate

  contains

    !> impulsive, convective (the modes combined) and total pressure at theta = 0.
    pure function combined(impulsive, modal) result(values)
      real(wp), intent(in) :: impulsive, modal(:)
      real(wp) :: values(3)
      if (combination == COMBINE_SRSS) then
        values(2) = sqrt(sum(modal**2))
        values(3) = sqrt(impulsive**2 + values(2)**2)
      else
        values(2) = sum(modal)
        values(3) = impulsive + values(2)
      end if
      values(1) = impulsive
    end function combined

    !> One column of 'pressure_resultants' from the mass ratio and height ratios.
    pure function resultant_row(component, mass_ratio, height_ratio, height_ratio_ibp, &
                                acceleration) result(row)
      integer, intent(in) :: component
      real(wp), intent(in) :: mass_ratio, height_ratio, height_ratio_ibp, acceleration
      real(wp) :: row(PRESSURE_RESULTANT_ROWS)
      associate (m => mass_ratio*props%liquid_mass, big_h => tank%liquid_depth)
        row = [real(component, wp), m, height_ratio*big_h, height_ratio_ibp*big_h, &
               m*acceleration, m*height_ratio*big_h*acceleration, &
               m*height_ratio_ibp*big_h*acceleration]
      end associate
    end function resultant_row
  end subroutine pressure_tables

  !> The tables 'wall_pressure' and 'base_pressure' of one instant of a time history with N
  !> sloshing modes (N = size(mode_accelerations)), from the tank's absolute acceleration a_t
  !> and the modes' a_1..a_N [m/s^2] (docs/model.md, "Accelerations to use"): the liquid
  !> moves as a rigid body with the tank but for the N modes' motion relative to it, so
  !>   p = rho r cos(theta) a_t + sum_{n<=N} p_cn (a_n - a_t),
  !> reported as the part moving with the tank (impulsive_pressure: rho r cos(theta) a_t minus
  !> the N modes' pressures at a_t, that is p_i a_t plus the unmodelled modes' p_cn a_t), the
  !> modes' part (convective_pressure: sum p_cn a_n) and their sum; at angle theta [rad].
  pure subroutine instant_pressure_tables(tank, tank_acceleration, mode_accelerations, angle, &
                                          heights, radii, wall, base, status, message)
    type(tank_t), intent(in) :: tank
    real(wp), intent(in) :: tank_acceleration, mode_accelerations(:), angle, heights(:), radii(:)
    real(wp), intent(out) :: wall(WALL_PRESSURE_ROWS, size(heights)), &
                             base(BASE_PRESSURE_ROWS, size(radii))
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(tank_properties) :: props
    real(wp) :: gamma, rho, coefficients(size(mode_accelerations))
    integer :: i, n, modes

    wall = 0
    base = 0
    call prepare(tank, tank_acceleration, mode_accelerations, angle, COMBINE_SUM, heights, &
                 radii, props, gamma, rho, status, message)
    if (status /= SD_OK) return
    modes = size(mode_accelerations)
    associate (big_r => tank%radius, big_h => tank%liquid_depth, cos_theta => cos(angle))
      do i = 1, size(heights)
        coefficients = [(convective_coefficient(n, gamma, 1.0_wp, heights(i)/big_h), n = 1, modes)]
        wall(1:4, i) = [heights(i), instant(big_r, coefficients)*cos_theta]
        wall(5, i) = wall(4, i)*big_r
      end do
      do i = 1, size(radii)
        coefficients = [(convective_coefficient(n, gamma, radii(i)/big_r, 0.0_wp), n = 1, modes)]
        base(:, i) = [radii(i), instant(radii(i), coefficients)*cos_theta]
      end do
    end associate

  contains

    !> The part moving with the tank, the modes' part and the total at radius r (theta = 0)
    !> from the modes' coefficients p_cn/(rho R A_n) there.
    pure function instant(r, coefficients) result(values)
      real(wp), intent(in) :: r, coefficients(:)
      real(wp) :: values(3)
      values(1) = rho*(r - tank%radius*sum(coefficients))*tank_acceleration
      values(2) = rho*tank%radius*sum(coefficients*mode_accelerations)
      values(3) = values(1) + values(2)
    end function instant
  end subroutine instant_pressure_tables
end module sloshdyn_wall_pressure
