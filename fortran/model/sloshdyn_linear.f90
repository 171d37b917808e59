!> Linear analysis about the trivial equilibrium (sec 3.2): stiffness matrix K (eq 26, Appendix),
!> natural frequencies (eq 28), the modal matrix P (eq 34), and the rod stiffness kappa that
!> tunes the 3:1 internal resonance omega2 = 3 omega1 + sigma1 (eq 51).
module sloshdyn_linear
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, check_real
  use sloshdyn_text, only: num2str
  use sloshdyn_model, only: model_t, require_stable_trivial
  use sloshdyn_excitation, only: excitation_t
  use sloshdyn_motion, only: motion_jacobian
  use sloshdyn_lapack, only: eigenvalues
  use sloshdyn_roots, only: scalar_function, find_all_roots
  implicit none
  private
  public :: stiffness_matrix, natural_frequencies, natural_frequencies_eig, modal_matrix
  public :: frequencies_from_groups, frequency_ratio, kappa_for_detuning

  !> omega2 - 3 omega1 - sigma1 as a function of t = log(kappa - s1).
  type, extends(scalar_function) :: detuning_function
    real(wp) :: s1, mu1, sigma1
  contains
    procedure :: value => detuning_value
    procedure :: derivative => detuning_derivative
  end type detuning_function

contains

  !> K of eq (25)-(26) with k11..k22 of Appendix A: x'' + K x = 0.
  pure function stiffness_matrix(model) result(k)
    type(model_t), intent(in) :: model
    real(wp) :: k(2, 2)
    associate (s1 => model%s1, mu1 => model%mu1, kappa => model%kappa)
      k(1, 1) = 1/(1 - mu1)
      k(1, 2) = -(kappa - s1)/((1 - mu1)*s1)
      k(2, 1) = -mu1*s1/(1 - mu1)
      k(2, 2) = (kappa - s1)/(1 - mu1)
    end associate
  end function stiffness_matrix

  !> omega1 <= omega2 of eq (28) in terms of sigma~ = kappa - s1 and mu~ = 1 - mu1, with
  !> alpha^ = (1 + sigma~)/(2 mu~), beta^ = sigma~/mu~. omega1^2 is written as
  !> beta^/(alpha^ + sqrt(alpha^2 - beta^)), the same number without the cancellation, and the
  !> root as alpha^ sqrt(1 - beta^/alpha^2), which does not overflow for large sigma~.
  elemental subroutine frequencies_from_groups(sigma_t, mu_t, omega1, omega2)
    real(wp), intent(in) :: sigma_t, mu_t
    real(wp), intent(out) :: omega1, omega2
    real(wp) :: alpha_hat, beta_hat, root
    alpha_hat = (1 + sigma_t)/(2*mu_t)
    beta_hat = sigma_t/mu_t
    root = alpha_hat*sqrt(max(1 - (beta_hat/alpha_hat)/alpha_hat, 0.0_wp))
    omega1 = sqrt(beta_hat/(alpha_hat + root))
    omega2 = sqrt(alpha_hat + root)
  end subroutine frequencies_from_groups

  !> omega2/omega1 (Fig 7 and 8) as a function of sigma~ = kappa - s1 > 0 and mu~ = 1 - mu1 > 0.
  elemental real(wp) function frequency_ratio(sigma_t, mu_t) result(ratio)
    real(wp), intent(in) :: sigma_t, mu_t
    real(wp) :: omega1, omega2
    call frequencies_from_groups(sigma_t, mu_t, omega1, omega2)
    ratio = omega2/omega1
  end function frequency_ratio

  !> Natural frequencies omega1 < omega2 of eq (28); needs kappa > s1.
  pure subroutine natural_frequencies(model, omega1, omega2, status, message)
    type(model_t), intent(in) :: model
    real(wp), intent(out) :: omega1, omega2
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    omega1 = 0
    omega2 = 0
    call require_stable_trivial(model, status, message)
    if (status /= SD_OK) return
    call frequencies_from_groups(model%kappa - model%s1, 1 - model%mu1, omega1, omega2)
  end subroutine natural_frequencies

  !> The same frequencies, independently: eigenvalues (dgeev) of the Jacobian of the full
  !> equations of motion at rest, without damping and forcing, are +-i omega1, +-i omega2.
  subroutine natural_frequencies_eig(model, omega1, omega2, status, message)
    type(model_t), intent(in) :: model
    real(wp), intent(out) :: omega1, omega2
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(model_t) :: undamped
    real(wp) :: jac(4, 4), wr(4), wi(4)

    omega1 = 0
    omega2 = 0
    call require_stable_trivial(model, status, message)
    if (status /= SD_OK) return
    undamped = model
    undamped%gamma = 0
    undamped%delta = 0
    undamped%zeta = 0
    undamped%excitation = excitation_t()   ! no forcing, of any kind
    undamped%b_coef(5) = 0
    undamped%a_coef(5) = 0
    call motion_jacobian(undamped, 0.0_wp, [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], jac)
    call eigenvalues(jac, wr, wi, status, message)
    if (status /= SD_OK) return
    omega1 = minval(abs(wi))
    omega2 = maxval(abs(wi))
  end subroutine natural_frequencies_eig

  !> Modal matrix P of eq (34), x = P u, and its inverse.
  pure subroutine modal_matrix(model, p, p_inv, status, message)
    type(model_t), intent(in) :: model
    real(wp), intent(out) :: p(2, 2), p_inv(2, 2)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: k(2, 2), k11, k12, omega1, omega2

    p = 0
    p_inv = 0
    call natural_frequencies(model, omega1, omega2, status, message)
    if (status /= SD_OK) return
    k = stiffness_matrix(model)
    k11 = k(1, 1)
    k12 = -k(1, 2)   ! K = [[k11, -k12], [-k21, k22]]
    p = reshape([-k12, omega1**2 - k11, -k12, omega2**2 - k11], [2, 2])
    p_inv = reshape([-(omega2**2 - k11)/k12, (omega1**2 - k11)/k12, -1.0_wp, 1.0_wp], [2, 2]) &
            /(omega2**2 - omega1**2)
  end subroutine modal_matrix

  pure real(wp) function detuning_value(self, x) result(f)
    class(detuning_function), intent(in) :: self
    real(wp), intent(in) :: x
    real(wp) :: omega1, omega2
    call frequencies_from_groups(exp(x), 1 - self%mu1, omega1, omega2)
    f = omega2 - 3*omega1 - self%sigma1
  end function detuning_value

  !> d/dt of detuning_value, t = log(kappa - s1): d/dsigma~ of eq (28) times sigma~.
  pure real(wp) function detuning_derivative(self, x) result(df)
    class(detuning_function), intent(in) :: self
    real(wp), intent(in) :: x
    real(wp) :: sigma_t, mu_t, alpha_hat, beta_hat, root, droot, omega1, omega2
    sigma_t = exp(x)
    mu_t = 1 - self%mu1
    alpha_hat = (1 + sigma_t)/(2*mu_t)
    beta_hat = sigma_t/mu_t
    root = sqrt(max(alpha_hat**2 - beta_hat, tiny(1.0_wp)))
    droot = (alpha_hat/mu_t - 1/mu_t)/(2*root)          ! d sqrt(alpha^2 - beta^)/d sigma~
    call frequencies_from_groups(sigma_t, mu_t, omega1, omega2)
    df = ((1/(2*mu_t) + droot)/(2*omega2) - 3*(1/(2*mu_t) - droot)/(2*omega1))*sigma_t
  end function detuning_derivative

  !> All kappa in (max(kappa_min, s1), kappa_max] with omega2 - 3 omega1 = sigma1, ascending.
  subroutine kappa_for_detuning(s1, mu1, sigma1, kappa_min, kappa_max, roots, n_roots, &
                                     status, message)
    real(wp), intent(in) :: s1, mu1, sigma1, kappa_min, kappa_max
    real(wp), intent(out) :: roots(:)
    integer, intent(out) :: n_roots, status
    character(len=message_len), intent(out) :: message
    type(detuning_function) :: f
    real(wp) :: t_lower, t_upper, big

    n_roots = 0
    roots = 0
    status = SD_OK
    message = ''
    big = huge(1.0_wp)
    call check_real('s1', s1, 0.0_wp, big, .true., .true., 's1 = l/L must be > 0', status, message)
    call check_real('mu1', mu1, 0.0_wp, 1.0_wp, .true., .true., 'mu1 = m/M must lie in (0, 1)', &
                    status, message)
    call check_real('sigma1', sigma1, -big, big, .false., .false., 'sigma1 must be finite', &
                    status, message)
    call check_real('kappa_max', kappa_max, s1, 1.0e6_wp*max(s1, 1.0_wp), .true., .false., &
                    'kappa_max must lie in (s1, 1e6 max(s1, 1)] = ('//num2str(s1)//', '// &
                    num2str(1.0e6_wp*max(s1, 1.0_wp))//']', status, message)
    call check_real('kappa_min', kappa_min, -big, kappa_max, .false., .true., &
                    'kappa_min must be < kappa_max = '//num2str(kappa_max), status, message)
    if (status /= SD_OK) return
    f = detuning_function(s1=s1, mu1=mu1, sigma1=sigma1)
    t_lower = log(max(kappa_min - s1, 1.0e-10_wp*s1))
    t_upper = log(kappa_max - s1)
    call find_all_roots(f, t_lower, t_upper, 4000, 1.0e-13_wp, roots, n_roots, status, message)
    roots(1:n_roots) = s1 + exp(roots(1:n_roots))
  end subroutine kappa_for_detuning
end module sloshdyn_linear
