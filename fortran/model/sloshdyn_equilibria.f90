!> Equilibria of the unforced system (sec 3.1, eq 16-18) and their stability: eigenvalues of the
!> 4x4 Jacobian (dgeev) at every equilibrium, and Routh-Hurwitz on eq (20) at the trivial one.
module sloshdyn_equilibria
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, SD_CAPACITY
  use sloshdyn_text, only: num2str
  use sloshdyn_model, only: model_t
  use sloshdyn_excitation, only: excitation_t
  use sloshdyn_motion, only: motion_jacobian
  use sloshdyn_lapack, only: eigenvalues
  use sloshdyn_roots, only: scalar_function, find_all_roots
  use sloshdyn_tables, only: VERDICT_STABLE, VERDICT_MARGINAL, VERDICT_UNSTABLE
  implicit none
  private
  public :: theta_roots, phi_roots, equilibria, trivial_routh_hurwitz, stability_verdict
  public :: search_limit
  !> Roots beyond |angle| = search_limit are not searched (they exist only for tiny beta^ or
  !> kappa^ and are far outside the physical range |angle| < pi/2).
  real(wp), parameter :: search_limit = 32*pi
  !> Grid cell for root bracketing [rad]: much finer than the pi scale of sin.
  real(wp), parameter :: cell_width = 0.02_wp

  !> eq (17): sin(theta) + beta^ theta^(2n-1) = 0.
  type, extends(scalar_function) :: theta_equation
    real(wp) :: beta_hat
    integer :: n
  contains
    procedure :: value => theta_value
    procedure :: derivative => theta_derivative
  end type theta_equation

  !> eq (18): sin(phi) - kappa^ phi = 0.
  type, extends(scalar_function) :: phi_equation
    real(wp) :: kappa_hat
  contains
    procedure :: value => phi_value
    procedure :: derivative => phi_derivative
  end type phi_equation

contains

  pure real(wp) function theta_value(self, x) result(f)
    class(theta_equation), intent(in) :: self
    real(wp), intent(in) :: x
    f = sin(x) + self%beta_hat*x**(2*self%n - 1)
  end function theta_value

  pure real(wp) function theta_derivative(self, x) result(df)
    class(theta_equation), intent(in) :: self
    real(wp), intent(in) :: x
    df = cos(x) + self%beta_hat*(2*self%n - 1)*x**(2*self%n - 2)
  end function theta_derivative

  pure real(wp) function phi_value(self, x) result(f)
    class(phi_equation), intent(in) :: self
    real(wp), intent(in) :: x
    f = sin(x) - self%kappa_hat*x
  end function phi_value

  pure real(wp) function phi_derivative(self, x) result(df)
    class(phi_equation), intent(in) :: self
    real(wp), intent(in) :: x
    df = cos(x) - self%kappa_hat
  end function phi_derivative

  !> All real roots of an odd function f with |root| <= bound: 0, the positive roots and their
  !> mirror images, ascending. truncated = the bound exceeded search_limit.
  subroutine odd_function_roots(f, bound, roots, n_roots, truncated, status, message)
    class(scalar_function), intent(in) :: f
    real(wp), intent(in) :: bound
    real(wp), intent(out) :: roots(:)
    integer, intent(out) :: n_roots, status
    logical, intent(out) :: truncated
    character(len=message_len), intent(out) :: message
    real(wp) :: positive(size(roots)), upper, start
    integer :: n_positive, n_cells

    truncated = bound > search_limit
    upper = min(bound, search_limit)
    n_roots = 0
    roots = 0
    n_cells = max(16, ceiling(upper/cell_width))
    ! start just above 0 so that the trivial root is not found again
    start = upper/(64.0_wp*n_cells)
    call find_all_roots(f, start, upper, n_cells, 1.0e-12_wp, positive, n_positive, status, message)
    if (status == SD_OK .and. 2*n_positive + 1 > size(roots)) then
      status = SD_CAPACITY
      message = num2str(2*n_positive + 1)//' roots found, room for '//num2str(size(roots))
    end if
    if (status /= SD_OK) return
    n_roots = 2*n_positive + 1
    roots(1:n_positive) = -positive(n_positive:1:-1)
    roots(n_positive + 1) = 0
    roots(n_positive + 2:n_roots) = positive(1:n_positive)
  end subroutine odd_function_roots

  !> Real roots theta of eq (17), beta^ = beta/theta0^(2n-1); all lie in |theta| <= beta^^(-1/(2n-1)).
  subroutine theta_roots(model, roots, n_roots, truncated, status, message)
    type(model_t), intent(in) :: model
    real(wp), intent(out) :: roots(:)
    integer, intent(out) :: n_roots, status
    logical, intent(out) :: truncated
    character(len=message_len), intent(out) :: message
    type(theta_equation) :: f
    real(wp) :: bound

    f = theta_equation(beta_hat=model%beta/model%theta0**(2*model%n - 1), n=model%n)
    bound = huge(1.0_wp)
    if (f%beta_hat > 0) bound = (1/f%beta_hat)**(1.0_wp/(2*model%n - 1))
    call odd_function_roots(f, bound, roots, n_roots, truncated, status, message)
    if (status /= SD_OK) message = 'eq (17) for theta: '//trim(message)
  end subroutine theta_roots

  !> Real roots phi of eq (18), kappa^ = kappa/s1; all lie in |phi| <= 1/kappa^.
  subroutine phi_roots(model, roots, n_roots, truncated, status, message)
    type(model_t), intent(in) :: model
    real(wp), intent(out) :: roots(:)
    integer, intent(out) :: n_roots, status
    logical, intent(out) :: truncated
    character(len=message_len), intent(out) :: message
    type(phi_equation) :: f

    f = phi_equation(kappa_hat=model%kappa/model%s1)
    call odd_function_roots(f, 1/f%kappa_hat, roots, n_roots, truncated, status, message)
    if (status /= SD_OK) message = 'eq (18) for phi: '//trim(message)
  end subroutine phi_roots

  !> Stable if every eigenvalue has a negative real part, unstable if one is positive, marginal
  !> (e.g. undamped centres) within a relative tolerance of the imaginary axis.
  pure integer function stability_verdict(wr, wi) result(verdict)
    real(wp), intent(in) :: wr(:), wi(:)
    real(wp) :: tol
    tol = 1.0e-9_wp*max(1.0_wp, maxval(abs(wr)), maxval(abs(wi)))
    if (maxval(wr) < -tol) then
      verdict = VERDICT_STABLE
    else if (maxval(wr) > tol) then
      verdict = VERDICT_UNSTABLE
    else
      verdict = VERDICT_MARGINAL
    end if
  end function stability_verdict

  !> Every equilibrium (theta, phi) = (root of eq 17, root of eq 18) of the unforced system, with
  !> the eigenvalues of its Jacobian and a verdict. Results in columns 1..n_eq. physical: both
  !> angles inside (-pi/2, pi/2), the range the paper calls physical (sec 3.1).
  subroutine equilibria(model, theta, phi, physical, eig_re, eig_im, verdict, n_eq, truncated, &
                        status, message)
    type(model_t), intent(in) :: model
    real(wp), intent(out) :: theta(:), phi(:), eig_re(:, :), eig_im(:, :)
    logical, intent(out) :: physical(:), truncated
    integer, intent(out) :: verdict(:), n_eq, status
    character(len=message_len), intent(out) :: message
    type(model_t) :: unforced
    real(wp) :: thetas(size(theta)), phis(size(theta)), jac(4, 4)
    integer :: n_theta, n_phi, i, j
    logical :: truncated_theta, truncated_phi

    n_eq = 0
    theta = 0; phi = 0; eig_re = 0; eig_im = 0; verdict = 0; physical = .false.
    call theta_roots(model, thetas, n_theta, truncated_theta, status, message)
    if (status /= SD_OK) return
    call phi_roots(model, phis, n_phi, truncated_phi, status, message)
    if (status /= SD_OK) return
    truncated = truncated_theta .or. truncated_phi
    if (n_theta*n_phi > size(theta)) then
      status = SD_CAPACITY
      message = num2str(n_theta*n_phi)//' equilibria found, room for '//num2str(size(theta))
      return
    end if
    unforced = model
    unforced%excitation = excitation_t()   ! no forcing, of any kind
    do i = 1, n_theta
      do j = 1, n_phi
        n_eq = n_eq + 1
        theta(n_eq) = thetas(i)
        phi(n_eq) = phis(j)
        physical(n_eq) = abs(thetas(i)) < pi/2 .and. abs(phis(j)) < pi/2
        call motion_jacobian(unforced, 0.0_wp, &
                             [thetas(i)/model%theta0, 0.0_wp, phis(j)/model%theta0, 0.0_wp], jac)
        call eigenvalues(jac, eig_re(:, n_eq), eig_im(:, n_eq), status, message)
        if (status /= SD_OK) return
        verdict(n_eq) = stability_verdict(eig_re(:, n_eq), eig_im(:, n_eq))
      end do
    end do
  end subroutine equilibria

  !> Characteristic polynomial lambda^4 + c1 lambda^3 + c2 lambda^2 + c3 lambda + c4 of the trivial
  !> equilibrium, eq (20), and its Hurwitz determinants [c1, Delta2, Delta3, Delta4].
  !> Eq (20) assumes p >= 1 and no linear sloshing damping; the linear damping of the pendulum is
  !> delta' = 2 zeta, plus delta when p = 0 (then delta x1' is linear):
  !> det(M0 l^2 + C l + K0) = (l^2 + delta' l + 1)(l^2 + gamma l + kappa - s1) - mu1 l^4.
  pure subroutine trivial_routh_hurwitz(model, coefficients, hurwitz, routh_stable)
    type(model_t), intent(in) :: model
    real(wp), intent(out) :: coefficients(4), hurwitz(4)
    logical, intent(out) :: routh_stable
    real(wp) :: linear_delta
    linear_delta = 2*model%zeta + merge(model%delta, 0.0_wp, model%p == 0)
    associate (g => model%gamma, d => linear_delta, mu1 => model%mu1, &
               sigma_t => model%kappa - model%s1)
      coefficients = [g + d, sigma_t + 1 + d*g, g + d*sigma_t, sigma_t]/(1 - mu1)
    end associate
    associate (c => coefficients)
      hurwitz(1) = c(1)
      hurwitz(2) = c(1)*c(2) - c(3)
      hurwitz(3) = c(3)*hurwitz(2) - c(1)**2*c(4)
      hurwitz(4) = c(4)*hurwitz(3)
      routh_stable = all(c > 0) .and. hurwitz(2) > 0 .and. hurwitz(3) > 0
    end associate
  end subroutine trivial_routh_hurwitz
end module sloshdyn_equilibria
