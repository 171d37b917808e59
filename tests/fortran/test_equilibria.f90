!> Equilibria (sec 3.1): the bifurcation of eq (17) near beta^ = 0.012 for n = 2 (Fig 4), the
!> pitchfork of eq (18) at kappa^ = 1 (Fig 5-6), Routh-Hurwitz (eq 20) against the eigenvalues,
!> and the Jacobian at a tilted equilibrium against eq (22) as corrected in docs/errata.md.
program test_equilibria
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_model, only: model_t, model_from_arrays
  use sloshdyn_motion, only: motion_jacobian
  use sloshdyn_equilibria, only: theta_roots, phi_roots, equilibria, trivial_routh_hurwitz
  use sloshdyn_tables, only: VERDICT_STABLE, VERDICT_UNSTABLE, VERDICT_MARGINAL
  use checks, only: check_close, check_true, finish
  implicit none
  type(model_t) :: model
  integer :: status, n, i, j, n_eq, verdict(64)
  character(len=message_len) :: message
  logical :: truncated, routh_stable, physical(64), agree
  real(wp) :: roots(64), theta(64), phi(64), re(4, 64), im(4, 64), coefficients(4), hurwitz(4)
  real(wp) :: low, high, mid, theta_star, beta_tangent, beta_count, x3, c, s, den, jac(4, 4)
  real(wp), parameter :: theta0 = pi/4

  ! Fig 4, n = 2: five roots for beta^ = 0.005, one for beta^ = 0.08
  call with_beta_hat(0.005_wp)
  call theta_roots(model, roots, n, truncated, status, message)
  call check_true('Fig 4: beta^ = 0.005 gives five equilibria', n == 5)
  do i = 1, n
    call check_close('eq 17 residual at a root', sin(roots(i)) + 0.005_wp*roots(i)**3, 0.0_wp, &
                     0.0_wp, 1.0e-12_wp)
  end do
  call with_beta_hat(0.08_wp)
  call theta_roots(model, roots, n, truncated, status, message)
  call check_true('Fig 4: beta^ = 0.08 gives the trivial equilibrium only', n == 1 .and. roots(1) == 0)
  ! bisection on the number of roots: the paper's beta^_b = 0.012
  low = 0.005_wp
  high = 0.08_wp
  do i = 1, 50
    mid = (low + high)/2
    call with_beta_hat(mid)
    call theta_roots(model, roots, n, truncated, status, message)
    if (n > 1) then
      low = mid
    else
      high = mid
    end if
  end do
  call check_close('Fig 4: bifurcation at beta^_b = 0.012', low, 0.012_wp, 0.0_wp, 5.0e-4_wp)
  beta_count = low
  ! closed form: tangency sin t = -b t^3, cos t = -3 b t^2, i.e. tan t = t/3 on (pi, 3 pi/2)
  low = pi + 0.1_wp
  high = 1.5_wp*pi - 0.01_wp
  do i = 1, 60
    mid = (low + high)/2
    if (tan(mid) - mid/3 < 0) then
      low = mid
    else
      high = mid
    end if
  end do
  theta_star = mid
  beta_tangent = -sin(theta_star)/theta_star**3
  call check_close('beta^_b: root count = tangency closed form', beta_count, beta_tangent, 1.0e-6_wp)
  call with_beta_hat(beta_tangent)
  call theta_roots(model, roots, n, truncated, status, message)
  call check_true('at beta^_b: three distinct equilibria (paper sec 3.1)', n == 3)

  ! Fig 5-6: pitchfork at kappa^ = 1; trivial stable iff kappa^ > 1, tilted pair stable below
  call with_kappa_hat(1.3_wp, 0.01_wp)
  call equilibria(model, theta, phi, physical, re, im, verdict, n_eq, truncated, status, message)
  call check_true('Fig 5: kappa^ = 1.3: one equilibrium, stable', n_eq == 1 .and. verdict(1) == VERDICT_STABLE)
  call with_kappa_hat(0.9_wp, 0.01_wp)
  call phi_roots(model, roots, n, truncated, status, message)
  call check_true('Fig 5: kappa^ = 0.9: three phi roots', n == 3)
  call check_close('eq 18 residual', sin(roots(3)) - 0.9_wp*roots(3), 0.0_wp, 0.0_wp, 1.0e-13_wp)
  call equilibria(model, theta, phi, physical, re, im, verdict, n_eq, truncated, status, message)
  call check_true('Fig 6: kappa^ = 0.9: trivial unstable, tilted pair stable', n_eq == 3 .and. &
                  verdict(1) == VERDICT_STABLE .and. verdict(2) == VERDICT_UNSTABLE .and. verdict(3) == VERDICT_STABLE)

  ! Routh-Hurwitz on eq (20) agrees with dgeev at the trivial equilibrium over a scan
  agree = .true.
  do i = 1, 9
    do j = 0, 2
      call with_kappa_hat(0.6_wp + 0.1_wp*i, 0.005_wp*j)
      call equilibria(model, theta, phi, physical, re, im, verdict, n_eq, truncated, status, message)
      call trivial_routh_hurwitz(model, coefficients, hurwitz, routh_stable)
      n = minloc(abs(phi(1:n_eq)), dim=1)
      agree = agree .and. (routh_stable .eqv. verdict(n) == VERDICT_STABLE)
      if (j == 0 .and. i > 4) agree = agree .and. verdict(n) == VERDICT_MARGINAL
    end do
  end do
  call check_true('eq 20: Routh-Hurwitz verdict = eigenvalue verdict (kappa^ 0.7..1.5, gamma 0..0.01)', agree)

  ! eq (22) as corrected in docs/errata.md, at the tilted equilibrium of kappa^ = 0.9 (x1 = 0, x3 = x2)
  call with_kappa_hat(0.9_wp, 0.01_wp)
  call phi_roots(model, roots, n, truncated, status, message)
  x3 = roots(3)/theta0
  call motion_jacobian(model, 0.0_wp, [0.0_wp, 0.0_wp, x3, 0.0_wp], jac)
  associate (s1 => model%s1, mu1 => model%mu1, kappa => model%kappa, gamma => model%gamma)
    c = cos(theta0*x3)
    s = sin(theta0*x3)
    den = mu1*c**2 - 1
    call check_close('eq 22 (corrected): J21', jac(2, 1), &
      (s1*theta0 + s*theta0**2*kappa*x3 - s**2*theta0*s1)/(s1*theta0*den) &
      + 2*mu1*c*s*(s1*c*s - kappa*theta0*x3*c)/(s1*den**2), 1.0e-12_wp)
    call check_close('eq 22: J23', jac(2, 3), &
      (s*theta0**2*kappa*x3 - theta0*kappa*c - s**2*theta0*s1 + s1*theta0*c**2)/(s1*theta0*den) &
      + 2*mu1*c*s*(s1*c*s - kappa*theta0*x3*c)/(s1*den**2), 1.0e-12_wp)
    call check_close('eq 22: J41', jac(4, 1), &
      -mu1*s1*c/den + 2*mu1*c*s*(kappa*theta0*x3 - s1*s)/den**2, 1.0e-12_wp)
    call check_close('eq 22: J43', jac(4, 3), &
      (kappa*theta0 - s1*theta0*c)/(den*theta0) + 2*mu1*c*s*(kappa*theta0*x3 - s1*s)/den**2, 1.0e-12_wp)
    call check_close('eq 22 (corrected, no 1/theta0): J24', jac(2, 4), -gamma*c/(s1*den), 1.0e-12_wp)
    call check_close('eq 22: J44', jac(4, 4), gamma/den, 1.0e-12_wp)
  end associate
  call finish()

contains

  !> theta0 = pi/4, n = 2, beta = beta^ theta0^3
  subroutine with_beta_hat(beta_hat)
    real(wp), intent(in) :: beta_hat
    call model_from_arrays([1.5_wp, 0.5_wp, 1.8_wp, theta0, beta_hat*theta0**3, 0.0_wp, 0.0_wp, &
                            0.0_wp, 0.0_wp, 0.0_wp], [2, 2], model, status, message)
  end subroutine with_beta_hat

  !> s1 = 1.5, kappa = kappa^ s1; beta large enough for theta = 0 only
  subroutine with_kappa_hat(kappa_hat, gamma)
    real(wp), intent(in) :: kappa_hat, gamma
    call model_from_arrays([1.5_wp, 0.5_wp, kappa_hat*1.5_wp, theta0, 1.0_wp, gamma, 0.0_wp, &
                            0.0_wp, 0.0_wp, 0.0_wp], [6, 2], model, status, message)
  end subroutine with_kappa_hat
end program test_equilibria
