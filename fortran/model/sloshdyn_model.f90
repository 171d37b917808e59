!> The validated dimensionless model: the groups of eq (9), the coefficients of eq (11), and
!> the base excitation (sloshdyn_excitation; harmonic X = A sin(rho tau) of eq (29)-(31)).
!>
!> Flat layout used across the f2py bridge (one place defines it, Python mirrors it):
!>   real    parameters  rpar = [s1, mu1, kappa, theta0, beta, gamma, delta, A, rho, zeta]
!>   integer parameters  ipar = [n, p]
module sloshdyn_model
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, check_real
  use sloshdyn_text, only: num2str
  use sloshdyn_excitation, only: excitation_t
  implicit none
  private
  public :: model_t, model_from_arrays, model_to_arrays, model_from_physical, set_coefficients
  public :: require_stable_trivial, n_real_params, n_int_params, real_param_names

  integer, parameter :: n_real_params = 10, n_int_params = 2
  !> Largest allowed groups: beyond them the equations are stiffer than an explicit integrator can
  !> follow, or their eigenvalue problems lose all precision (a damping of 1e300 rounds the slow
  !> eigenvalues to 0); real tanks have groups of order 1.
  real(wp), parameter :: max_s1 = 1.0e3_wp, max_kappa = 1.0e6_wp, max_beta = 1.0e9_wp, &
                         max_damping = 1.0e3_wp, max_excitation = 1.0e3_wp
  integer, parameter :: max_exponent = 50
  character(len=6), parameter :: real_param_names(n_real_params) = &
    [character(len=6) :: 's1', 'mu1', 'kappa', 'theta0', 'beta', 'gamma', 'delta', 'A', 'rho', &
     'zeta']

  type :: model_t
    real(wp) :: s1 = 0      !< l/L, pendulum to rod length ratio
    real(wp) :: mu1 = 0     !< m/M, sloshing to total mass ratio
    real(wp) :: kappa = 0   !< k/(omega^2 L^2 M), rod stiffness
    real(wp) :: theta0 = 0  !< wall angle [rad]
    !> impact coefficient b/(omega^2 m l^2); the paper gives none: 10 makes the wall stiff but
    !> absent from small sloshing (docs/namelist.md, "Impact and dissipation defaults")
    real(wp) :: beta = 10
    real(wp) :: gamma = 0   !< rod damping c/(omega L^2 M)
    !> sloshing dissipation d/(omega m l^2); the paper gives none: 0.1 is about 5 % of critical
    !> at the wall and nothing at small amplitude (docs/namelist.md)
    real(wp) :: delta = 0.1_wp
    !> linear sloshing damping, as a ratio of critical for the pendulum alone: the term
    !> 2 zeta x1' in the pendulum's equation (0 in the paper; the design codes take 0.005)
    real(wp) :: zeta = 0
    integer :: n = 6        !< impact exponent, eq (4)
    integer :: p = 2        !< dissipation exponent, eq (5)
    type(excitation_t) :: excitation   !< base motion X(tau)
    real(wp) :: a_coef(6) = 0  !< a1..a6 of eq (11)
    real(wp) :: b_coef(6) = 0  !< b1..b6 of eq (11)
  end type model_t

contains

  !> Validate the flat parameter arrays and build the model with its coefficients.
  pure subroutine model_from_arrays(rpar, ipar, model, status, message)
    real(wp), intent(in) :: rpar(n_real_params)
    integer, intent(in) :: ipar(n_int_params)
    type(model_t), intent(out) :: model
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message

    status = SD_OK
    message = ''
    model%s1 = rpar(1); model%mu1 = rpar(2); model%kappa = rpar(3); model%theta0 = rpar(4)
    model%beta = rpar(5); model%gamma = rpar(6); model%delta = rpar(7)
    model%excitation%A = rpar(8); model%excitation%rho = rpar(9); model%zeta = rpar(10)
    model%n = ipar(1); model%p = ipar(2)

    call check_real('s1', model%s1, 0.0_wp, max_s1, .true., .false., &
                    's1 = l/L must be > 0 and at most '//num2str(max_s1), status, message)
    call check_real('mu1', model%mu1, 0.0_wp, 1.0_wp, .true., .true., &
                    'mu1 = m/M must lie in (0, 1)', status, message)
    call check_real('kappa', model%kappa, 0.0_wp, max_kappa, .true., .false., &
                    'kappa must be > 0 and at most '//num2str(max_kappa), status, message)
    call check_real('theta0', model%theta0, 0.0_wp, pi/2, .true., .true., &
                    'theta0 must lie in (0, pi/2) rad', status, message)
    call check_real('beta', model%beta, 0.0_wp, max_beta, .false., .false., &
                    'beta (impact coefficient) must be >= 0 and at most '//num2str(max_beta), &
                    status, message)
    call check_real('gamma', model%gamma, 0.0_wp, max_damping, .false., .false., &
                    'gamma (rod damping) must be >= 0 and at most '//num2str(max_damping), &
                    status, message)
    call check_real('delta', model%delta, 0.0_wp, max_damping, .false., .false., &
                    'delta (sloshing dissipation) must be >= 0 and at most '// &
                    num2str(max_damping), status, message)
    call check_real('zeta', model%zeta, 0.0_wp, 1.0_wp, .false., .true., &
                    'zeta (sloshing damping ratio) must lie in [0, 1)', status, message)
    call check_real('A', model%excitation%A, 0.0_wp, max_excitation, .false., .false., &
                    'A (excitation amplitude) must be >= 0 and at most '//num2str(max_excitation), &
                    status, message)
    call check_real('rho', model%excitation%rho, 0.0_wp, max_excitation, .false., .false., &
                    'rho (excitation frequency) must be >= 0 and at most '// &
                    num2str(max_excitation), status, message)
    if (status == SD_OK .and. (model%n < 1 .or. model%n > max_exponent)) then
      status = SD_BAD_INPUT
      message = 'n = '//num2str(model%n)//' is out of range: the impact exponent n must be '// &
                '>= 1 and at most '//num2str(max_exponent)
    end if
    if (status == SD_OK .and. (model%p < 0 .or. model%p > max_exponent)) then
      status = SD_BAD_INPUT
      message = 'p = '//num2str(model%p)//' is out of range: the dissipation exponent p must '// &
                'be >= 0 and at most '//num2str(max_exponent)
    end if
    if (status == SD_OK) call set_coefficients(model)
  end subroutine model_from_arrays

  pure subroutine model_to_arrays(model, rpar, ipar)
    type(model_t), intent(in) :: model
    real(wp), intent(out) :: rpar(n_real_params)
    integer, intent(out) :: ipar(n_int_params)
    rpar = [model%s1, model%mu1, model%kappa, model%theta0, model%beta, model%gamma, &
            model%delta, model%excitation%A, model%excitation%rho, model%zeta]
    ipar = [model%n, model%p]
  end subroutine model_to_arrays

  !> Coefficients of eq (11).
  pure subroutine set_coefficients(model)
    type(model_t), intent(inout) :: model
    associate (s1 => model%s1, t0 => model%theta0, mu1 => model%mu1)
      model%a_coef = [1/s1, t0/s1, 1/t0, model%beta/t0, model%delta, 1/(t0*s1)]
      model%b_coef = [mu1*s1, mu1*s1*t0, model%kappa, s1/t0, model%gamma, 1/t0]
    end associate
  end subroutine set_coefficients

  !> Dimensionless groups of eq (9) from the dimensional system. l and m are the pendulum length
  !> and sloshing mass (e.g. from the tank, eq 2); omega^2 = g/l.
  pure subroutine model_from_physical(total_mass, rod_length, stiffness, rod_damping, &
                                      impact_coef, dissipation_coef, gravity, theta0, &
                                      pendulum_length, sloshing_mass, s1, mu1, kappa, beta, &
                                      gamma, delta, status, message)
    real(wp), intent(in) :: total_mass, rod_length, stiffness, rod_damping, impact_coef, &
                            dissipation_coef, gravity, theta0, pendulum_length, sloshing_mass
    real(wp), intent(out) :: s1, mu1, kappa, beta, gamma, delta
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: omega
    real(wp), parameter :: big = huge(1.0_wp)

    status = SD_OK
    message = ''
    s1 = 0; mu1 = 0; kappa = 0; beta = 0; gamma = 0; delta = 0
    call check_real('M', total_mass, 0.0_wp, big, .true., .true., &
                    'the total mass M must be > 0 [kg]', status, message)
    call check_real('L', rod_length, 0.0_wp, big, .true., .true., &
                    'the rod length L must be > 0 [m]', status, message)
    call check_real('k', stiffness, 0.0_wp, big, .true., .true., &
                    'the torsional stiffness k must be > 0 [N m/rad]', status, message)
    call check_real('c', rod_damping, 0.0_wp, big, .false., .true., &
                    'the rod damping c must be >= 0 [N m s/rad]', status, message)
    call check_real('b', impact_coef, 0.0_wp, big, .false., .true., &
                    'the impact coefficient b must be >= 0 [N m]', status, message)
    call check_real('d', dissipation_coef, 0.0_wp, big, .false., .true., &
                    'the dissipation coefficient d must be >= 0 [N m s]', status, message)
    call check_real('g', gravity, 0.0_wp, big, .true., .true., &
                    'the gravity g must be > 0 [m/s^2]', status, message)
    call check_real('theta0', theta0, 0.0_wp, pi/2, .true., .true., &
                    'theta0 must lie in (0, pi/2) rad', status, message)
    call check_real('l', pendulum_length, 0.0_wp, big, .true., .true., &
                    'the pendulum length l must be > 0 [m]', status, message)
    call check_real('m', sloshing_mass, 0.0_wp, big, .true., .true., &
                    'the sloshing mass m must be > 0 [kg]', status, message)
    if (status /= SD_OK) return
    if (sloshing_mass >= total_mass) then
      status = SD_BAD_INPUT
      message = 'M = '//num2str(total_mass)//' is out of range: the total mass M must exceed '// &
                'the sloshing mass m = '//num2str(sloshing_mass)//' (mu1 = m/M < 1)'
      return
    end if
    omega = sqrt(gravity/pendulum_length)
    s1 = pendulum_length/rod_length
    mu1 = sloshing_mass/total_mass
    kappa = stiffness/(omega**2*rod_length**2*total_mass)
    beta = impact_coef/(omega**2*sloshing_mass*pendulum_length**2)
    gamma = rod_damping/(omega*rod_length**2*total_mass)
    delta = dissipation_coef/(omega*sloshing_mass*pendulum_length**2)
    ! the groups' ranges (model_from_arrays), told in the dimensional inputs
    call check_group('s1 = l/L', s1, max_s1, 'l/L with l = '//num2str(pendulum_length)// &
                     ' m, L = '//num2str(rod_length)//' m', status, message)
    call check_group('kappa = k/(omega^2 L^2 M)', kappa, max_kappa, 'k = '//num2str(stiffness)// &
                     ' N m/rad', status, message)
    call check_group('beta = b/(omega^2 m l^2)', beta, max_beta, 'b = '//num2str(impact_coef)// &
                     ' N m', status, message)
    call check_group('gamma = c/(omega L^2 M)', gamma, max_damping, 'c = '// &
                     num2str(rod_damping)//' N m s/rad', status, message)
    call check_group('delta = d/(omega m l^2)', delta, max_damping, 'd = '// &
                     num2str(dissipation_coef)//' N m s', status, message)
    if (status /= SD_OK) then
      s1 = 0; mu1 = 0; kappa = 0; beta = 0; gamma = 0; delta = 0
    end if

  contains

    pure subroutine check_group(group, value, upper, source, status, message)
      character(len=*), intent(in) :: group, source
      real(wp), intent(in) :: value, upper
      integer, intent(inout) :: status
      character(len=message_len), intent(inout) :: message
      if (status /= SD_OK .or. (value > 0 .and. value <= upper) .or. value == 0) return
      status = SD_BAD_INPUT
      message = source//' gives '//group//' = '//num2str(value)//', out of range: it must '// &
                'be > 0 and at most '//num2str(upper)
    end subroutine check_group
  end subroutine model_from_physical

  !> Analyses that linearise about the upright tank need the trivial equilibrium stable (sec 3.1.1):
  !> kappa_hat = kappa/s1 > 1.
  pure subroutine require_stable_trivial(model, status, message)
    type(model_t), intent(in) :: model
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    status = SD_OK
    message = ''
    if (model%kappa <= model%s1) then
      status = SD_BAD_INPUT
      message = 'kappa = '//num2str(model%kappa)//' is out of range: this analysis needs '// &
                'kappa_hat = kappa/s1 > 1 (stable upright tank), i.e. kappa > s1 = '// &
                num2str(model%s1)//' (kappa_hat = '//num2str(model%kappa/model%s1)//')'
    end if
  end subroutine require_stable_trivial

end module sloshdyn_model
