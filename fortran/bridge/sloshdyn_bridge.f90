!> The f2py bridge: the only Fortran that Python sees. Scalars and explicit-shape arrays of
!> c_double/c_int cross the boundary; every routine returns status (0 = success) and a fixed-length
!> message. Parameter layout (see sloshdyn_model):
!>   rpar(10) = [s1, mu1, kappa, theta0, beta, gamma, delta, A, rho, zeta], ipar(2) = [n, p]
!> Settings arrays (integration, steady, response, lyapunov): the layouts of sloshdyn_layouts;
!> array sizes are literals here (f2py cannot use another module's constants): the compiler checks
!> them against the layouts' named sizes where the arrays are converted.
!> Threads: the routines that compute (every one but the namelist reader and the name lists of
!> the app layer) carry `!f2py threadsafe`, so f2py releases the GIL
!> while the Fortran runs and Python threads (e.g. Dask's threaded workers) run them at once.
!> That is safe because the core keeps no state between calls: no module variables, no `save`,
!> and no deferred-length function results in the layers below the app (gfortran keeps their
!> lengths in static variables; see sloshdyn_text). The one exception is the cancellation flag
!> (sloshdyn_cancel): request_cancel, called from another Python thread, makes every running
!> computation return status 10 (cancelled) within one step (python/sloshdyn/_cancel.py). The app layer (reader, driver, writers) has
!> such statics, so its routines keep the GIL and run one at a time; run_input releases it so
!> that Ctrl-C can cancel a run, and Python runs it one at a time (a lock in sloshdyn.cli).
!> Result tables: the layouts of sloshdyn_tables (names gives the column names); work counts:
!> counts(4) = [rhs evaluations, accepted steps, rejected steps, tau reached].
module sloshdyn_bridge
  use, intrinsic :: iso_c_binding, only: c_double, c_int
  implicit none

contains

  !> Equivalent pendulum of a cylindrical tank, eq (2)-(3):
  !> pendulum = [l, m, d1, m0, d0, m_F].
  subroutine tank_pendulum(radius, depth, density, liquid_mass, pendulum, status, message)
    !f2py threadsafe
    use sloshdyn_tank, only: core => tank_pendulum
    real(c_double), intent(in) :: radius, depth, density, liquid_mass
    real(c_double), intent(out) :: pendulum(6)
    integer(c_int), intent(out) :: status
    character(len=256), intent(out) :: message
    integer :: info
    call core(radius, depth, density, liquid_mass, pendulum(1), pendulum(2), pendulum(3), &
              pendulum(4), pendulum(5), pendulum(6), info, message)
    status = info
  end subroutine tank_pendulum

  !> Dimensionless groups of eq (9): physical = [M, L, k, c, b, d, g, theta0, l, m],
  !> groups = [s1, mu1, kappa, beta, gamma, delta].
  subroutine dimensionless_groups(physical, groups, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: model_from_physical
    real(c_double), intent(in) :: physical(10)
    real(c_double), intent(out) :: groups(6)
    integer(c_int), intent(out) :: status
    character(len=256), intent(out) :: message
    integer :: info
    call model_from_physical(physical(1), physical(2), physical(3), physical(4), physical(5), &
                             physical(6), physical(7), physical(8), physical(9), physical(10), &
                             groups(1), groups(2), groups(3), groups(4), groups(5), groups(6), &
                             info, message)
    status = info
  end subroutine dimensionless_groups

  !> Validate the parameters; coefficients a1..a6, b1..b6 of eq (11).
  subroutine model_coefficients(rpar, ipar, a, b, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: model_t, model_from_arrays
    real(c_double), intent(in) :: rpar(10)
    integer(c_int), intent(in) :: ipar(2)
    real(c_double), intent(out) :: a(6), b(6)
    integer(c_int), intent(out) :: status
    character(len=256), intent(out) :: message
    type(model_t) :: model
    integer :: info
    call model_from_arrays(rpar, int(ipar), model, info, message)
    status = info
    a = model%a_coef
    b = model%b_coef
  end subroutine model_coefficients

  !> Inertia matrix (eq 13), forcing vector (eq 14/31), y' (eq 15) and the Jacobian dy'/dy.
  subroutine equations_of_motion(rpar, ipar, tau, y, mass, force, dydt, jacobian, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: model_t, model_from_arrays
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use sloshdyn_status, only: SD_NON_FINITE
    use sloshdyn_text, only: num2str
    use sloshdyn_motion, only: inertia_matrix, forcing_vector, core_eom => equations_of_motion, &
                               motion_jacobian
    real(c_double), intent(in) :: rpar(10), tau, y(4)
    integer(c_int), intent(in) :: ipar(2)
    real(c_double), intent(out) :: mass(2, 2), force(2), dydt(4), jacobian(4, 4)
    integer(c_int), intent(out) :: status
    character(len=256), intent(out) :: message
    type(model_t) :: model
    integer :: info
    mass = 0; force = 0; dydt = 0; jacobian = 0
    call model_from_arrays(rpar, int(ipar), model, info, message)
    status = info
    if (info /= 0) return
    call inertia_matrix(model, y, mass)
    call forcing_vector(model, tau, y, force)
    call core_eom(model, tau, y, dydt)
    call motion_jacobian(model, tau, y, jacobian)
    if (.not. (all(ieee_is_finite(mass)) .and. all(ieee_is_finite(force)) .and. &
               all(ieee_is_finite(dydt)) .and. all(ieee_is_finite(jacobian)))) then
      status = SD_NON_FINITE      ! a non-finite result is an error, never a result
      message = 'the equations of motion (12)-(15) overflow at this state: y = ['// &
                num2str(y(1))//', '//num2str(y(2))//', '//num2str(y(3))//', '//num2str(y(4))//']'
      mass = 0; force = 0; dydt = 0; jacobian = 0
    end if
  end subroutine equations_of_motion

  !> Natural frequencies: omegas = [omega1, omega2 (eq 28), omega1, omega2 (dgeev)];
  !> stiffness K (eq 26), modal matrix P and its inverse (eq 34).
  subroutine natural_frequencies(rpar, ipar, omegas, stiffness, modal, modal_inverse, status, &
                                 message)
    !f2py threadsafe
    use sloshdyn_model, only: model_t, model_from_arrays
    use sloshdyn_linear, only: stiffness_matrix, core => natural_frequencies, &
                               natural_frequencies_eig, modal_matrix
    real(c_double), intent(in) :: rpar(10)
    integer(c_int), intent(in) :: ipar(2)
    real(c_double), intent(out) :: omegas(4), stiffness(2, 2), modal(2, 2), modal_inverse(2, 2)
    integer(c_int), intent(out) :: status
    character(len=256), intent(out) :: message
    type(model_t) :: model
    integer :: info
    omegas = 0; stiffness = 0; modal = 0; modal_inverse = 0
    call model_from_arrays(rpar, int(ipar), model, info, message)
    if (info == 0) call core(model, omegas(1), omegas(2), info, message)
    if (info == 0) call natural_frequencies_eig(model, omegas(3), omegas(4), info, message)
    if (info == 0) call modal_matrix(model, modal, modal_inverse, info, message)
    if (info == 0) stiffness = stiffness_matrix(model)
    status = info
  end subroutine natural_frequencies

  !> omega2/omega1 at each (sigma~ = kappa - s1 > 0, mu~ = 1 - mu1 in (0, 1]) (Fig 7, 8).
  subroutine frequency_ratios(n, sigma_t, mu_t, ratio, status, message)
    !f2py threadsafe
    use sloshdyn_linear, only: frequency_ratio
    use sloshdyn_text, only: num2str
    integer(c_int), intent(in) :: n
    real(c_double), intent(in) :: sigma_t(n), mu_t(n)
    real(c_double), intent(out) :: ratio(n)
    integer(c_int), intent(out) :: status
    character(len=256), intent(out) :: message
    integer :: i
    status = 0
    message = ''
    ratio = 0
    do i = 1, n
      if (.not. (sigma_t(i) > 0 .and. sigma_t(i) <= huge(1.0_c_double))) then
        status = 1
        message = 'sigma_tilde = '//num2str(sigma_t(i))//' is out of range: '// &
                  'sigma_tilde = kappa - s1 must be > 0'
      else if (.not. (mu_t(i) > 0 .and. mu_t(i) <= 1)) then
        status = 1
        message = 'mu_tilde = '//num2str(mu_t(i))//' is out of range: '// &
                  'mu_tilde = 1 - mu1 must lie in (0, 1]'
      end if
      if (status /= 0) return
    end do
    ratio = frequency_ratio(sigma_t, mu_t)
  end subroutine frequency_ratios

  !> All kappa in (max(kappa_min, s1), kappa_max] with omega2 - 3 omega1 = sigma1 (eq 51).
  subroutine kappa_for_detuning(s1, mu1, sigma1, kappa_min, kappa_max, max_roots, roots, &
                                n_roots, status, message)
    !f2py threadsafe
    use sloshdyn_linear, only: core => kappa_for_detuning
    real(c_double), intent(in) :: s1, mu1, sigma1, kappa_min, kappa_max
    integer(c_int), intent(in) :: max_roots
    real(c_double), intent(out) :: roots(max_roots)
    integer(c_int), intent(out) :: n_roots, status
    character(len=256), intent(out) :: message
    integer :: info, found
    call core(s1, mu1, sigma1, kappa_min, kappa_max, roots, found, info, message)
    n_roots = found
    status = info
  end subroutine kappa_for_detuning

  !> Real roots of eq (17) (which = 1, theta) or eq (18) (which = 2, phi), ascending.
  subroutine equilibrium_angles(rpar, ipar, which, max_roots, roots, n_roots, truncated, &
                                status, message)
    !f2py threadsafe
    use sloshdyn_model, only: model_t, model_from_arrays
    use sloshdyn_equilibria, only: theta_roots, phi_roots
    real(c_double), intent(in) :: rpar(10)
    integer(c_int), intent(in) :: ipar(2), which, max_roots
    real(c_double), intent(out) :: roots(max_roots)
    integer(c_int), intent(out) :: n_roots, truncated, status
    character(len=256), intent(out) :: message
    type(model_t) :: model
    integer :: info, found
    logical :: cut
    roots = 0; found = 0; cut = .false.
    call model_from_arrays(rpar, int(ipar), model, info, message)
    if (info == 0) then
      if (which == 1) then
        call theta_roots(model, roots, found, cut, info, message)
      else
        call phi_roots(model, roots, found, cut, info, message)
      end if
    end if
    n_roots = found
    truncated = merge(1, 0, cut)
    status = info
  end subroutine equilibrium_angles

  !> Every equilibrium with the eigenvalues of its Jacobian (dgeev) and a verdict
  !> (1 stable, 0 marginal, -1 unstable); Routh-Hurwitz of eq (20) at the trivial one:
  !> routh = [c1, c2, c3, c4, Delta2, Delta3, stable (1/0)].
  subroutine equilibria(rpar, ipar, max_eq, theta, phi, physical, eig_re, eig_im, verdict, &
                        n_eq, truncated, routh, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: model_t, model_from_arrays
    use sloshdyn_equilibria, only: core => equilibria, trivial_routh_hurwitz
    real(c_double), intent(in) :: rpar(10)
    integer(c_int), intent(in) :: ipar(2), max_eq
    real(c_double), intent(out) :: theta(max_eq), phi(max_eq), eig_re(4, max_eq), &
                                   eig_im(4, max_eq), routh(7)
    integer(c_int), intent(out) :: physical(max_eq), verdict(max_eq), n_eq, truncated, status
    character(len=256), intent(out) :: message
    type(model_t) :: model
    integer :: info, found, verdicts(max_eq)
    logical :: is_physical(max_eq), cut, routh_stable
    real(c_double) :: coefficients(4), hurwitz(4)
    theta = 0; phi = 0; eig_re = 0; eig_im = 0; routh = 0; found = 0; cut = .false.
    verdicts = 0; is_physical = .false.
    call model_from_arrays(rpar, int(ipar), model, info, message)
    if (info == 0) call core(model, theta, phi, is_physical, eig_re, eig_im, verdicts, found, &
                             cut, info, message)
    if (info == 0) then
      call trivial_routh_hurwitz(model, coefficients, hurwitz, routh_stable)
      routh = [coefficients, hurwitz(2:3), merge(1.0_c_double, 0.0_c_double, routh_stable)]
    end if
    physical = merge(1, 0, is_physical)
    verdict = verdicts
    n_eq = found
    truncated = merge(1, 0, cut)
    status = info
  end subroutine equilibria

  !> Cubic expansion (eq 32-33) and modal form (eq 35-36). Polynomials are given by their
  !> coefficients on the 34 monomials of degree 1..3 whose exponents are exponents(:, k), in the
  !> variables (x1, x2, x1', x2') for g and (u1, u2, u1', u2') for h; the forcing polynomials
  !> (factor of rho^2 A sin(rho tau)) add a constant term: *_forcing(:, 0).
  !> scalars = [omega1, omega2, gamma11, gamma22, F11]; c = c11..c23.
  subroutine modal_expansion(rpar, ipar, scalars, c, exponents, g, g_forcing, h, h_forcing, &
                             status, message)
    !f2py threadsafe
    use sloshdyn_model, only: model_t, model_from_arrays
    use sloshdyn_modal, only: modal_coefficients, expand_model
    use sloshdyn_polynomial, only: monomial_exponents, poly
    real(c_double), intent(in) :: rpar(10)
    integer(c_int), intent(in) :: ipar(2)
    real(c_double), intent(out) :: scalars(5), c(2, 3), g(2, 34), g_forcing(2, 0:34), h(2, 34), &
                                   h_forcing(2, 0:34)
    integer(c_int), intent(out) :: exponents(4, 34), status
    character(len=256), intent(out) :: message
    type(model_t) :: model
    type(modal_coefficients) :: mc
    integer :: info, r, k, e(4, 34)
    scalars = 0; c = 0; g = 0; g_forcing = 0; h = 0; h_forcing = 0
    e = monomial_exponents()
    exponents = e
    call model_from_arrays(rpar, int(ipar), model, info, message)
    if (info == 0) call expand_model(model, mc, info, message)
    status = info
    if (info /= 0) return
    scalars = [mc%omega1, mc%omega2, mc%gamma11, mc%gamma22, mc%F11]
    c = mc%c
    do r = 1, 2
      g_forcing(r, 0) = mc%g_forcing(r)%c(0, 0, 0, 0)
      h_forcing(r, 0) = mc%h_forcing(r)%c(0, 0, 0, 0)
      do k = 1, 34
        g(r, k) = coefficient(mc%g(r), e(:, k))
        h(r, k) = coefficient(mc%h(r), e(:, k))
        g_forcing(r, k) = coefficient(mc%g_forcing(r), e(:, k))
        h_forcing(r, k) = coefficient(mc%h_forcing(r), e(:, k))
      end do
    end do
  contains
    pure real(c_double) function coefficient(p, ex)
      type(poly), intent(in) :: p
      integer, intent(in) :: ex(4)
      coefficient = p%c(ex(1), ex(2), ex(3), ex(4))
    end function coefficient
  end subroutine modal_expansion

  !> Every real solution |u1| of eq (49) at each rho (A from rpar): amplitudes(1:counts(i), i).
  subroutine nonresonant_amplitudes(rpar, ipar, n, rho, amplitudes, counts, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: model_t, model_from_arrays
    use sloshdyn_modal, only: modal_coefficients, expand_model
    use sloshdyn_slowflow, only: core => nonresonant_amplitudes
    use sloshdyn_text, only: num2str
    real(c_double), intent(in) :: rpar(10), rho(n)
    integer(c_int), intent(in) :: ipar(2), n
    real(c_double), intent(out) :: amplitudes(3, n)
    integer(c_int), intent(out) :: counts(n), status
    character(len=256), intent(out) :: message
    type(model_t) :: model
    type(modal_coefficients) :: mc
    integer :: info, i, found
    amplitudes = 0; counts = 0
    call model_from_arrays(rpar, int(ipar), model, info, message)
    if (info == 0) call expand_model(model, mc, info, message)
    do i = 1, n
      if (info /= 0) exit
      call core(mc, rho(i), model%excitation%A, amplitudes(:, i), found, info, message)
      if (info /= 0) message = 'rho('//num2str(i)//'): '//trim(message)
      counts(i) = found
    end do
    status = info
  end subroutine nonresonant_amplitudes

  !> Time history at tau_out (ascending, >= tau0): history(9, n_out) in the rows of
  !> the 'history' table after tau. On failure the columns not reached are NaN.
  subroutine simulate(rpar, ipar, tau0, y0, n_out, tau_out, integration, history, counts, status, &
                      message)
    !f2py threadsafe
    use sloshdyn_model, only: model_t, model_from_arrays
    use sloshdyn_ode, only: ode_stats
    use sloshdyn_simulation, only: time_history
    use sloshdyn_tables, only: HISTORY_ROWS
    use sloshdyn_layouts, only: to_ode_options, to_method, counts_array
    real(c_double), intent(in) :: rpar(10), tau0, y0(4), tau_out(n_out), &
                                  integration(7)
    integer(c_int), intent(in) :: ipar(2), n_out
    real(c_double), intent(out) :: history(9, n_out), counts(4)
    integer(c_int), intent(out) :: status
    character(len=256), intent(out) :: message
    type(model_t) :: model
    type(ode_stats) :: stats
    integer :: info
    history = 0
    counts = 0
    call model_from_arrays(rpar, int(ipar), model, info, message)
    if (info == 0) then
      call time_history(model, tau0, y0, tau_out, to_ode_options(integration), &
                        to_method(integration), history, stats, info, message)
      counts = counts_array(stats)
    end if
    status = info
  end subroutine simulate

  !> Steady state from y0 at tau = 0: summary in the 'summary' layout, the window's Poincare
  !> points and the final state (at forcing phase 0).
  subroutine steady_state(rpar, ipar, y0, integration, steady, window, summary, poincare, y_end, &
                          counts, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: model_t, model_from_arrays
    use sloshdyn_ode, only: ode_stats
    use sloshdyn_simulation, only: core => steady_state
    use sloshdyn_tables, only: SUMMARY_SIZE
    use sloshdyn_layouts, only: to_ode_options, to_method, &
                                to_steady, counts_array
    real(c_double), intent(in) :: rpar(10), y0(4), integration(7), &
                                  steady(7)
    integer(c_int), intent(in) :: ipar(2), window
    real(c_double), intent(out) :: summary(11), poincare(4, window), y_end(4), &
                                   counts(4)
    integer(c_int), intent(out) :: status
    character(len=256), intent(out) :: message
    type(model_t) :: model
    type(ode_stats) :: stats
    integer :: info
    summary = 0; poincare = 0; y_end = 0; counts = 0
    call model_from_arrays(rpar, int(ipar), model, info, message)
    if (info == 0) then
      call core(model, y0, to_ode_options(integration), to_method(integration), &
                to_steady(steady), summary, poincare, y_end, stats, info, message)
      counts = counts_array(stats)
    end if
    status = info
  end subroutine steady_state

  !> Steady states along values of rho (which = 1) or A (which = 2), each from the previous
  !> final state; summaries(11, n) as for steady_state, n_done points completed.
  subroutine parameter_sweep(rpar, ipar, which, n, values, y0, integration, steady, summaries, &
                             y_final, n_done, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: model_t, model_from_arrays
    use sloshdyn_simulation, only: core => parameter_sweep
    use sloshdyn_tables, only: SUMMARY_SIZE
    use sloshdyn_layouts, only: to_ode_options, to_method, &
                                to_steady
    real(c_double), intent(in) :: rpar(10), values(n), y0(4), integration(7), &
                                  steady(7)
    integer(c_int), intent(in) :: ipar(2), which, n
    real(c_double), intent(out) :: summaries(11, n), y_final(4)
    integer(c_int), intent(out) :: n_done, status
    character(len=256), intent(out) :: message
    type(model_t) :: model
    integer :: info, done
    summaries = 0; y_final = y0; done = 0
    call model_from_arrays(rpar, int(ipar), model, info, message)
    if (info == 0) call core(model, int(which), values, y0, to_ode_options(integration), &
                             to_method(integration), to_steady(steady), summaries, y_final, &
                             done, info, message)
    n_done = done
    status = info
  end subroutine parameter_sweep

  !> Steady states at values of rho (which = 1) or A (which = 2), each from y0 (independent
  !> points), shared out to n_threads threads; the results do not depend on n_threads.
  subroutine independent_sweep(rpar, ipar, which, n, values, y0, integration, steady, n_threads, &
                            summaries, n_done, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: model_t, model_from_arrays
    use sloshdyn_simulation, only: core => independent_sweep
    use sloshdyn_tables, only: SUMMARY_SIZE
    use sloshdyn_layouts, only: to_ode_options, to_method, &
                                to_steady
    real(c_double), intent(in) :: rpar(10), values(n), y0(4), integration(7), &
                                  steady(7)
    integer(c_int), intent(in) :: ipar(2), which, n, n_threads
    real(c_double), intent(out) :: summaries(11, n)
    integer(c_int), intent(out) :: n_done, status
    character(len=256), intent(out) :: message
    type(model_t) :: model
    integer :: info, done
    summaries = 0; done = 0
    call model_from_arrays(rpar, int(ipar), model, info, message)
    if (info == 0) call core(model, int(which), values, y0, to_ode_options(integration), &
                             to_method(integration), to_steady(steady), int(n_threads), &
                             summaries, done, info, message)
    n_done = done
    status = info
  end subroutine independent_sweep

  !> Steady states at the points (rho(i), A(i)) of a study task: each from y0(:, i) (carry = 0)
  !> or, carry = 1, the first from y0(:, 1) and each next from the previous final state.
  !> summaries(11, n) in the 'summary' layout, y_end(4, n), orbit(16, n) in the layout of
  !> sloshdyn_studies, impact(n) = 1 where max|x1| >= 1 (the wall is reached), point_status(n);
  !> status and message of the first failing point.
  subroutine steady_path(rpar, ipar, n, rho, A, y0, carry, integration, steady, summaries, &
                         y_end, orbit, impact, point_status, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: model_t, model_from_arrays
    use sloshdyn_studies, only: core => steady_path, roof_impact
    use sloshdyn_layouts, only: to_ode_options, to_method, to_steady
    real(c_double), intent(in) :: rpar(10), rho(n), A(n), y0(4, n), integration(7), steady(7)
    integer(c_int), intent(in) :: ipar(2), n, carry
    real(c_double), intent(out) :: summaries(11, n), y_end(4, n), orbit(16, n)
    integer(c_int), intent(out) :: impact(n), point_status(n), status
    character(len=256), intent(out) :: message
    type(model_t) :: model
    integer :: info, statuses(n)
    summaries = 0; y_end = 0; orbit = 0; impact = 0; statuses = 0
    call model_from_arrays(rpar, int(ipar), model, info, message)
    if (info == 0) then
      call core(model, rho, A, y0, carry /= 0, to_ode_options(integration), &
                to_method(integration), to_steady(steady), summaries, y_end, orbit, statuses, &
                info, message)
    else
      statuses = info
    end if
    impact = merge(1, 0, roof_impact(summaries(3, :)))
    point_status = statuses
    status = info
  end subroutine steady_path

  !> Steady states from the initial states y0(:, i) at the excitation of rpar, with the orbit
  !> each periodic one settled on (sloshdyn_studies: orbit(16, n), orbit_points(4, 8, n)).
  subroutine attractor_points(rpar, ipar, n, y0, integration, steady, summaries, y_end, orbit, &
                              orbit_points, point_status, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: model_t, model_from_arrays
    use sloshdyn_studies, only: core => attractor_points
    use sloshdyn_layouts, only: to_ode_options, to_method, to_steady
    real(c_double), intent(in) :: rpar(10), y0(4, n), integration(7), steady(7)
    integer(c_int), intent(in) :: ipar(2), n
    real(c_double), intent(out) :: summaries(11, n), y_end(4, n), orbit(16, n), &
                                   orbit_points(4, 8, n)
    integer(c_int), intent(out) :: point_status(n), status
    character(len=256), intent(out) :: message
    type(model_t) :: model
    integer :: info, statuses(n)
    summaries = 0; y_end = 0; orbit = 0; orbit_points = 0; statuses = 0
    call model_from_arrays(rpar, int(ipar), model, info, message)
    if (info == 0) then
      call core(model, y0, to_ode_options(integration), to_method(integration), &
                to_steady(steady), summaries, y_end, orbit, orbit_points, statuses, info, message)
    else
      statuses = info
    end if
    point_status = statuses
    status = info
  end subroutine attractor_points

  !> Attractors of a set of runs (sloshdyn_studies%label_attractors): label(n) from 1, 0 for
  !> failed runs; representative(1:n_attractors) the first run of each.
  subroutine label_attractors(n, motions, periods, orbit_points, tol, label, n_attractors, &
                              representative)
    !f2py threadsafe
    use sloshdyn_studies, only: core => label_attractors
    integer(c_int), intent(in) :: n
    real(c_double), intent(in) :: motions(n), periods(n), orbit_points(4, 8, n), tol
    integer(c_int), intent(out) :: label(n), n_attractors, representative(n)
    integer :: labels(n), found, first(n)
    call core(motions, periods, orbit_points, tol, labels, found, first)
    label = labels
    n_attractors = found
    representative = first
  end subroutine label_attractors

  !> Slow-flow frequency response (sloshdyn_response): branches in lambda = rho (which = 1) or
  !> A (which = 2) over [lambda_min, lambda_max], 3:1 internal resonance or none. table in the
  !> 'response' layout (room for max_points points), special in the 'special' layout;
  !> complete = 0 if a branch could not be finished (status says where).
  subroutine frequency_response(rpar, ipar, resonance, which, lambda_min, lambda_max, settings, &
                                max_points, max_special, table, n_points, special, n_special, &
                                complete, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: model_t, model_from_arrays
    use sloshdyn_response, only: core => frequency_response
    use sloshdyn_tables, only: SPECIAL_ROWS
    use sloshdyn_layouts, only: to_response
    real(c_double), intent(in) :: rpar(10), lambda_min, lambda_max, settings(10)
    integer(c_int), intent(in) :: ipar(2), resonance, which, max_points, max_special
    real(c_double), intent(out) :: table(28, max_points), &
                                   special(9, max_special)
    integer(c_int), intent(out) :: n_points, n_special, complete, status
    character(len=256), intent(out) :: message
    type(model_t) :: model
    integer :: info, points, specials
    logical :: done
    table = 0; special = 0; points = 0; specials = 0; done = .false.
    call model_from_arrays(rpar, int(ipar), model, info, message)
    if (info == 0) call core(model, resonance == 1, int(which), lambda_min, lambda_max, &
                             to_response(settings), table, points, special, specials, done, &
                             info, message)
    n_points = points
    n_special = specials
    complete = merge(1, 0, done)
    status = info
  end subroutine frequency_response

  !> A periodic orbit of period k T by shooting from the guess y0 (full equations):
  !> y_orbit(4), monodromy(4, 4), multipliers(2, 4) = (Re, Im), info(2) = [iterations, max|x1|].
  subroutine periodic_orbit(rpar, ipar, y0, k, integration, newton_tol, max_iter, y_orbit, &
                            monodromy, multipliers, info, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: model_t, model_from_arrays
    use sloshdyn_periodic_response, only: core => periodic_orbit
    use sloshdyn_layouts, only: to_ode_options, to_method
    real(c_double), intent(in) :: rpar(10), y0(4), integration(7), newton_tol
    integer(c_int), intent(in) :: ipar(2), k, max_iter
    real(c_double), intent(out) :: y_orbit(4), monodromy(4, 4), multipliers(2, 4), info(2)
    integer(c_int), intent(out) :: status
    character(len=256), intent(out) :: message
    type(model_t) :: model
    integer :: code, iterations
    real(c_double) :: re(4), im(4), peak
    y_orbit = 0; monodromy = 0; multipliers = 0; info = 0; iterations = 0; peak = 0
    call model_from_arrays(rpar, int(ipar), model, code, message)
    if (code == 0) call core(model, y0, int(k), to_ode_options(integration), &
                             to_method(integration), newton_tol, int(max_iter), y_orbit, &
                             monodromy, re, im, iterations, peak, code, message)
    if (code == 0) multipliers = transpose(reshape([re, im], [4, 2]))
    info = [real(iterations, c_double), peak]
    status = code
  end subroutine periodic_orbit

  !> Continuation of periodic orbits (period k T) in rho (which = 1) or A (which = 2) from the
  !> orbit through y0 at the parameters of rpar; settings = [ds, ds_min, ds_max, x_scale,
  !> direction]; points(7, :) = [lambda, y0(4), max|x1|, stable], multipliers(8, :) =
  !> [Re(4), Im(4)], special(7, :) = [kind, lambda, y0(4), max|x1|] (kinds of sloshdyn_tables);
  !> complete = 0 if the branch stopped early.
  subroutine periodic_branch(rpar, ipar, which, y0, k, lambda_min, lambda_max, settings, &
                             integration, max_points, max_special, points, multipliers, n_points, &
                             special, n_special, complete, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: model_t, model_from_arrays
    use sloshdyn_continuation, only: continuation_options
    use sloshdyn_periodic_response, only: periodic_response
    use sloshdyn_layouts, only: to_ode_options, to_method, to_int
    real(c_double), intent(in) :: rpar(10), y0(4), lambda_min, lambda_max, settings(5), &
                                  integration(7)
    integer(c_int), intent(in) :: ipar(2), which, k, max_points, max_special
    real(c_double), intent(out) :: points(7, max_points), multipliers(8, max_points), &
                                   special(7, max_special)
    integer(c_int), intent(out) :: n_points, n_special, complete, status
    character(len=256), intent(out) :: message
    type(model_t) :: model
    type(continuation_options) :: options
    integer :: code, found, found_special
    logical :: done
    points = 0; multipliers = 0; special = 0; found = 0; found_special = 0; done = .false.
    options%ds = settings(1)
    options%ds_min = settings(2)
    options%ds_max = settings(3)
    options%x_scale = settings(4)
    options%direction = to_int(settings(5))
    options%max_points = max_points
    call model_from_arrays(rpar, int(ipar), model, code, message)
    if (code == 0) call periodic_response(model, int(which), y0, int(k), lambda_min, &
                                          lambda_max, options, to_ode_options(integration), &
                                          to_method(integration), points, multipliers, found, &
                                          special, found_special, done, code, message)
    n_points = found
    n_special = found_special
    complete = merge(1, 0, done)
    status = code
  end subroutine periodic_branch

  !> Largest Lyapunov exponent (per unit tau) from y0, with its running estimates history(n_hist);
  !> settings in the lyapunov layout.
  subroutine lyapunov_exponent(rpar, ipar, y0, settings, integration, n_hist, exponent, history, &
                               status, message)
    !f2py threadsafe
    use sloshdyn_model, only: model_t, model_from_arrays
    use sloshdyn_periodic_response, only: core => lyapunov_exponent, lyapunov_options, &
                                          check_lyapunov
    use sloshdyn_layouts, only: to_ode_options, to_method, &
                                to_lyapunov
    real(c_double), intent(in) :: rpar(10), y0(4), settings(3), &
                                  integration(7)
    integer(c_int), intent(in) :: ipar(2), n_hist
    real(c_double), intent(out) :: exponent, history(n_hist)
    integer(c_int), intent(out) :: status
    character(len=256), intent(out) :: message
    type(model_t) :: model
    type(lyapunov_options) :: options
    integer :: code
    exponent = 0; history = 0
    options = to_lyapunov(settings)
    call model_from_arrays(rpar, int(ipar), model, code, message)
    call check_lyapunov(options, code, message)
    if (code == 0) call core(model, y0, options%transient_periods, options%n_periods, &
                             options%renormalise_every, to_ode_options(integration), &
                             to_method(integration), exponent, history, code, message)
    status = code
  end subroutine lyapunov_exponent

  !> The slow flow (3:1 internal resonance: resonance = 1, n = 4; none: 0, n = 2) at the model's
  !> rho and A: f(x) and its Jacobian (sloshdyn_slowflow_chart; x = Re B1, Im B1, Re B2, Im B2).
  subroutine slow_flow_field(rpar, ipar, resonance, n, x, f, jacobian, status, message)
    use sloshdyn_model, only: model_t, model_from_arrays
    use sloshdyn_slowflow_chart, only: field_t => slow_flow_field, make_slow_flow_field, &
                                       CHART_RHO, CHART_A
    use sloshdyn_status, only: SD_BAD_INPUT
    use sloshdyn_text, only: num2str
    real(c_double), intent(in) :: rpar(10), x(n)
    integer(c_int), intent(in) :: ipar(2), resonance, n
    real(c_double), intent(out) :: f(n), jacobian(n, n)
    integer(c_int), intent(out) :: status
    character(len=256), intent(out) :: message
    type(model_t) :: model
    type(field_t) :: field
    real(c_double) :: fp(n, 2)
    integer :: info
    f = 0
    jacobian = 0
    call model_from_arrays(rpar, int(ipar), model, info, message)
    if (info == 0) call make_slow_flow_field(model, resonance /= 0, [CHART_RHO, CHART_A], field, &
                                             info, message)
    if (info == 0 .and. n /= field%dimension()) then
      info = SD_BAD_INPUT
      message = 'x has '//num2str(int(n))//' components: the slow flow has '// &
                num2str(field%dimension())
    end if
    if (info == 0) call field%evaluate(x, [model%excitation%rho, model%excitation%A], f, &
                                       jacobian, fp)
    status = info
  end subroutine slow_flow_field

  !> The limit cycle of the 3:1 slow flow at the model's rho and A (sloshdyn_slowflow_cycle):
  !> x_cycle = (Re B1, Im B1, Re B2, Im B2) on it, its period [tau], multipliers(2, 4) =
  !> (Re, Im) and the Newton shots; times settle_time, max_period in tau.
  subroutine slow_flow_cycle(rpar, ipar, settle_time, max_period, n_samples, integration, &
                             x_cycle, period, multipliers, iterations, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: model_t, model_from_arrays
    use sloshdyn_slowflow_cycle, only: core => slow_flow_cycle
    use sloshdyn_layouts, only: to_ode_options, to_method
    real(c_double), intent(in) :: rpar(10), settle_time, max_period, integration(7)
    integer(c_int), intent(in) :: ipar(2), n_samples
    real(c_double), intent(out) :: x_cycle(4), period, multipliers(2, 4)
    integer(c_int), intent(out) :: iterations, status
    character(len=256), intent(out) :: message
    type(model_t) :: model
    integer :: code, shots
    real(c_double) :: re(4), im(4)
    x_cycle = 0; period = 0; multipliers = 0; shots = 0
    call model_from_arrays(rpar, int(ipar), model, code, message)
    if (code == 0) call core(model, settle_time, max_period, int(n_samples), &
                             to_ode_options(integration), to_method(integration), x_cycle, &
                             period, re, im, shots, code, message)
    if (code == 0) multipliers = transpose(reshape([re, im], [4, 2]))
    iterations = shots
    status = code
  end subroutine slow_flow_cycle

  ! ---- stability charts -----------------------------------------------------------------------

  !> The &chart defaults (layouts' chart array).
  subroutine chart_defaults(chart)
    use sloshdyn_stability_chart, only: chart_settings
    use sloshdyn_layouts, only: from_chart
    real(c_double), intent(out) :: chart(14)
    type(chart_settings) :: defaults
    chart = from_chart(defaults)
  end subroutine chart_defaults

  !> A stability chart of the model's slow flow (sloshdyn_stability_chart) as its four tables,
  !> each with room for max_* columns; sizes = the columns used [curve points, codimension-2
  !> points, curves, cells] (if a table is too small: status SD_CAPACITY, sizes = those
  !> needed). complete = 0 if a curve stopped early; notes = a line per such curve.
  subroutine stability_chart(rpar, ipar, settings, max_points, max_codim2, max_curves, n_cells, &
                             curves, codim2, ends, grid, sizes, complete, notes, status, message)
    use sloshdyn_model, only: model_t, model_from_arrays
    use sloshdyn_status, only: SD_CAPACITY
    use sloshdyn_text, only: num2str
    use sloshdyn_stability_chart, only: chart_result, core => stability_chart, chart_tables, &
                                        chart_table_sizes
    use sloshdyn_layouts, only: to_chart
    real(c_double), intent(in) :: rpar(10), settings(14)
    integer(c_int), intent(in) :: ipar(2), max_points, max_codim2, max_curves, n_cells
    real(c_double), intent(out) :: curves(13, max_points), codim2(7, max_codim2), &
                                   ends(7, max_curves), grid(8, n_cells)
    integer(c_int), intent(out) :: sizes(4), complete, status
    character(len=4096), intent(out) :: notes
    character(len=256), intent(out) :: message
    type(model_t) :: model
    type(chart_result) :: chart
    integer :: info, used(4), c
    curves = 0; codim2 = 0; ends = 0; grid = 0; sizes = 0; complete = 0
    notes = ''
    call model_from_arrays(rpar, int(ipar), model, info, message)
    if (info == 0) call core(model, to_chart(settings), chart, info, message)
    if (info == 0) then
      call chart_table_sizes(chart, used(1), used(2), used(3), used(4))
      sizes = used
      if (any(used > [int(max_points), int(max_codim2), int(max_curves), int(n_cells)])) then
        info = SD_CAPACITY
        message = 'the chart needs tables of '//num2str(used(1))//' curve points, '// &
                  num2str(used(2))//' codimension-2 points, '//num2str(used(3))//' curves, '// &
                  num2str(used(4))//' cells'
      else
        call chart_tables(chart, curves(:, 1:used(1)), codim2(:, 1:used(2)), &
                          ends(:, 1:used(3)), grid(:, 1:used(4)))
        complete = merge(1, 0, chart%complete)
        do c = 1, chart%n_curves
          if (.not. chart%curves(c)%complete) notes = trim(notes)//'curve '//num2str(c)//': '// &
                                                      trim(chart%curves(c)%message)//new_line('a')
        end do
      end if
    end if
    status = info
  end subroutine stability_chart

  ! ---- a tank in SI units under ground motion (layouts tank(17), ground(4) of sloshdyn_layouts;
  ! ---- samples(n) the record's accelerations [m/s^2], n = 0 for harmonic motion) -------------

  !> The tank's defaults (tank_t).
  subroutine tank_defaults(tank)
    use sloshdyn_vessel, only: tank_t
    use sloshdyn_layouts, only: from_tank
    real(c_double), intent(out) :: tank(17)
    type(tank_t) :: defaults
    tank = from_tank(defaults)
  end subroutine tank_defaults

  !> The tank's properties (the 'tank_si' table's row) and its dimensionless model.
  subroutine tank_properties(tank, row, rpar, ipar, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: model_t, model_to_arrays
    use sloshdyn_vessel, only: tank_properties_t => tank_properties, tank_model
    use sloshdyn_seismic, only: tank_summary
    use sloshdyn_layouts, only: to_tank
    real(c_double), intent(in) :: tank(17)
    real(c_double), intent(out) :: row(28), rpar(10)
    integer(c_int), intent(out) :: ipar(2), status
    character(len=256), intent(out) :: message
    type(model_t) :: model
    type(tank_properties_t) :: props
    integer :: info, ints(2)
    row = 0; rpar = 0; ipar = 0
    call tank_model(to_tank(tank), model, props, info, message)
    if (info == 0) then
      call tank_summary(to_tank(tank), props, model, row)
      call model_to_arrays(model, rpar, ints)
      ipar = ints
    end if
    status = info
  end subroutine tank_properties

  !> A and rho of a tank's model under harmonic ground motion (sloshdyn_ground's
  !> ground_excitation, as the namelist reader sets them for &tank with &ground_motion).
  subroutine tank_excitation(tank, ground, A, rho, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: model_t
    use sloshdyn_vessel, only: tank_properties_t => tank_properties, tank_model
    use sloshdyn_ground, only: ground_excitation, GROUND_HARMONIC
    use sloshdyn_excitation, only: excitation_t
    use sloshdyn_status, only: SD_BAD_INPUT
    use sloshdyn_layouts, only: to_tank, to_ground
    real(c_double), intent(in) :: tank(17), ground(4)
    real(c_double), intent(out) :: A, rho
    integer(c_int), intent(out) :: status
    character(len=256), intent(out) :: message
    type(model_t) :: model
    type(tank_properties_t) :: props
    type(excitation_t) :: excitation
    real(c_double) :: no_samples(0)
    integer :: info
    A = 0; rho = 0
    call tank_model(to_tank(tank), model, props, info, message)
    if (info == 0 .and. nint(ground(1)) /= GROUND_HARMONIC) then
      info = SD_BAD_INPUT
      message = 'a record has no A and rho: they are those of harmonic ground motion'
    end if
    if (info == 0) call ground_excitation(to_ground(ground, no_samples), props%omega, &
                                          props%rod_length, excitation, info, message)
    if (info == 0) then
      A = excitation%A
      rho = excitation%rho
    end if
    status = info
  end subroutine tank_excitation

  !> The rules of a ground motion (sloshdyn_ground's check_ground).
  subroutine check_ground(ground, n, samples, status, message)
    !f2py threadsafe
    use sloshdyn_ground, only: core => check_ground
    use sloshdyn_layouts, only: to_ground
    integer(c_int), intent(in) :: n
    real(c_double), intent(in) :: ground(4), samples(n)
    integer(c_int), intent(out) :: status
    character(len=256), intent(out) :: message
    integer :: info
    call core(to_ground(ground, samples), info, message)
    status = info
  end subroutine check_ground

  !> The factor that turns an acceleration in the named units (g, m/s^2, cm/s^2) into m/s^2.
  subroutine acceleration_units(name, factor, status, message)
    use sloshdyn_records, only: units_code, units_factor
    character(len=*), intent(in) :: name
    real(c_double), intent(out) :: factor
    integer(c_int), intent(out) :: status
    character(len=256), intent(out) :: message
    integer :: code, info
    call units_code(name, code, info, message)
    factor = 0
    if (info == 0) call units_factor(code, factor, info, message)
    status = info
  end subroutine acceleration_units

  !> A record file (sloshdyn_records' load_record): dt [s] and the first n of samples [m/s^2].
  !> n_max must be at least the number of samples (the file's count of numbers is enough).
  subroutine read_record(path, format, units, n_max, dt, samples, n, status, message)
    use sloshdyn_kinds, only: wp
    use sloshdyn_status, only: SD_BAD_INPUT
    use sloshdyn_records, only: load_record
    use sloshdyn_text, only: num2str
    character(len=*), intent(in) :: path, format, units
    integer(c_int), intent(in) :: n_max
    real(c_double), intent(out) :: dt, samples(n_max)
    integer(c_int), intent(out) :: n, status
    character(len=256), intent(out) :: message
    real(wp), allocatable :: accel(:)
    integer :: info
    samples = 0; n = 0
    call load_record(path, format, units, dt, accel, info, message)
    if (info == 0) then
      if (size(accel) > n_max) then
        info = SD_BAD_INPUT
        message = path//' has '//num2str(size(accel))//' samples, more than n_max = '// &
                  num2str(int(n_max))
      else
        n = size(accel)
        samples(1:n) = accel
      end if
    end if
    status = info
  end subroutine read_record

  !> The ground motion scaled (sloshdyn_ground's scale_ground; SI units).
  subroutine scale_ground(ground, n, samples, scale_factor, target_pga, target_sa, &
                          target_period, target_damping, scaled, scaled_samples, status, message)
    !f2py threadsafe
    use sloshdyn_ground, only: ground_motion_t, core => scale_ground
    use sloshdyn_layouts, only: to_ground, from_ground
    integer(c_int), intent(in) :: n
    real(c_double), intent(in) :: ground(4), samples(n), scale_factor, target_pga, target_sa, &
                                  target_period, target_damping
    real(c_double), intent(out) :: scaled(4), scaled_samples(n)
    integer(c_int), intent(out) :: status
    character(len=256), intent(out) :: message
    type(ground_motion_t) :: motion
    integer :: info
    motion = to_ground(ground, samples)
    call core(motion, scale_factor, target_pga, target_sa, target_period, target_damping, info, &
              message)
    scaled = from_ground(motion)
    scaled_samples = samples
    if (info == 0 .and. n > 0) scaled_samples = motion%acceleration
    status = info
  end subroutine scale_ground

  !> Response spectrum of the ground motion (sloshdyn_ground's ground_spectrum).
  subroutine ground_spectrum(ground, n, samples, m, periods, damping, tail_duration, duration, &
                             sd, sv, psa, status, message)
    !f2py threadsafe
    use sloshdyn_ground, only: core => ground_spectrum
    use sloshdyn_layouts, only: to_ground
    integer(c_int), intent(in) :: n, m
    real(c_double), intent(in) :: ground(4), samples(n), periods(m), damping, tail_duration, &
                                  duration
    real(c_double), intent(out) :: sd(m), sv(m), psa(m)
    integer(c_int), intent(out) :: status
    character(len=256), intent(out) :: message
    integer :: info
    call core(to_ground(ground, samples), periods, damping, tail_duration, duration, sd, sv, &
              psa, info, message)
    status = info
  end subroutine ground_spectrum

  !> t_end [s] and n_out of a seismic response, the defaults (sloshdyn_seismic) where the given
  !> ones are <= 0: chosen = [t_end, n_out].
  subroutine seismic_defaults(tank, ground, n, samples, t_end, n_out, chosen, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: model_t
    use sloshdyn_vessel, only: tank_properties_t => tank_properties, tank_model
    use sloshdyn_ground, only: check_ground
    use sloshdyn_seismic, only: core => seismic_defaults
    use sloshdyn_layouts, only: to_tank, to_ground
    integer(c_int), intent(in) :: n, n_out
    real(c_double), intent(in) :: tank(17), ground(4), samples(n), t_end
    real(c_double), intent(out) :: chosen(2)
    integer(c_int), intent(out) :: status
    character(len=256), intent(out) :: message
    type(model_t) :: model
    type(tank_properties_t) :: props
    real(c_double) :: duration
    integer :: info, count
    chosen = 0
    call tank_model(to_tank(tank), model, props, info, message)
    if (info == 0) call check_ground(to_ground(ground, samples), info, message)
    if (info == 0) then
      duration = t_end
      count = n_out
      call core(props, to_ground(ground, samples), duration, count)
      chosen = [duration, real(count, c_double)]
    end if
    status = info
  end subroutine seismic_defaults

  !> The tank's response from rest (sloshdyn_seismic): table(11, n_out) in the 'seismic' layout
  !> and peaks(19) in the 'seismic_peaks' layout.
  subroutine seismic_response(tank, ground, n, samples, t_end, n_out, integration, table, &
                              peaks, status, message)
    !f2py threadsafe
    use sloshdyn_seismic, only: core => seismic_response
    use sloshdyn_layouts, only: to_tank, to_ground, to_ode_options, to_method
    integer(c_int), intent(in) :: n, n_out
    real(c_double), intent(in) :: tank(17), ground(4), samples(n), t_end, integration(7)
    real(c_double), intent(out) :: table(11, n_out), peaks(19)
    integer(c_int), intent(out) :: status
    character(len=256), intent(out) :: message
    integer :: info
    call core(to_tank(tank), to_ground(ground, samples), t_end, int(n_out), &
              to_ode_options(integration), to_method(integration), table, peaks, info, message)
    status = info
  end subroutine seismic_response

  !> Steady states of the tank under harmonic ground motion of the ground's peak acceleration
  !> at each frequency [Hz] (sloshdyn_seismic's harmonic_sweep): summaries(11, n) in the
  !> 'summary' layout and table(9, n) in the 'harmonic_sweep' layout; carry = 1: each point
  !> from the previous one's final state (threads = 1; y_final the last one's), else each from
  !> y0.
  subroutine harmonic_sweep(tank, ground, n, frequencies, y0, integration, steady, carry, &
                            threads, summaries, table, y_final, n_done, status, message)
    !f2py threadsafe
    use sloshdyn_ground, only: harmonic_ground
    use sloshdyn_seismic, only: core => harmonic_sweep
    use sloshdyn_layouts, only: to_tank, to_ode_options, to_method, to_steady
    integer(c_int), intent(in) :: n, carry, threads
    real(c_double), intent(in) :: tank(17), ground(4), frequencies(n), y0(4), integration(7), &
                                  steady(7)
    real(c_double), intent(out) :: summaries(11, n), table(9, n), y_final(4)
    integer(c_int), intent(out) :: n_done, status
    character(len=256), intent(out) :: message
    integer :: info, done
    call core(to_tank(tank), harmonic_ground(ground(2), ground(3)), frequencies, y0, &
              to_ode_options(integration), to_method(integration), to_steady(steady), carry /= 0, &
              int(threads), summaries, table, y_final, done, info, message)
    n_done = done
    status = info
  end subroutine harmonic_sweep

  !> The tank's sloshing parameters by sloshdyn and by the design codes, codes(6, 4) in the
  !> 'design_codes' layout; wave heights need the ground motion (has_ground = 1).
  subroutine design_codes_text(codes, text)
    use sloshdyn_driver, only: design_codes_table
    real(c_double), intent(in) :: codes(6, 4)
    character(len=2048), intent(out) :: text
    text = design_codes_table(codes)
  end subroutine design_codes_text

  subroutine design_codes(tank, has_ground, ground, n, samples, codes, status, message)
    use sloshdyn_seismic, only: design_code_checks
    use sloshdyn_layouts, only: to_tank, to_ground
    integer(c_int), intent(in) :: has_ground, n
    real(c_double), intent(in) :: tank(17), ground(4), samples(n)
    real(c_double), intent(out) :: codes(6, 4)
    integer(c_int), intent(out) :: status
    character(len=256), intent(out) :: message
    integer :: info
    call design_code_checks(to_tank(tank), to_ground(ground, samples), has_ground /= 0, codes, &
                            info, message)
    status = info
  end subroutine design_codes

  !> The samples of the ground-motion record of a namelist file (as read_input reads it, scaled).
  subroutine input_record(path, n, samples, status, message)
    use sloshdyn_status, only: SD_BAD_INPUT
    use sloshdyn_namelist, only: run_config, core => read_input
    use sloshdyn_ground, only: GROUND_RECORD
    character(len=*), intent(in) :: path
    integer(c_int), intent(in) :: n
    real(c_double), intent(out) :: samples(n)
    integer(c_int), intent(out) :: status
    character(len=256), intent(out) :: message
    type(run_config) :: config
    integer :: info
    samples = 0
    call core(path, config, info, message)
    if (info == 0 .and. config%has_ground .and. config%ground%kind == GROUND_RECORD) then
      if (size(config%ground%acceleration) /= n) then
        info = SD_BAD_INPUT
        message = path//' changed while it was read: its record has a different length now'
      else
        samples = config%ground%acceleration
      end if
    end if
    status = info
  end subroutine input_record

  !> Read and validate a namelist input file (the executable's reader) and return it flattened:
  !> the model (rpar, ipar); the analysis code (1-based index into the 'analyses' names) with
  !> analysis_values = [sigma1, kappa_min, kappa_max]; the output directory; tank(17) and
  !> ground(4) in their layouts with has_tank, has_ground (1/0) and n_samples (the record's
  !> length, for input_record); seismic = [t_end, n_out]; integration, steady, response and
  !> lyapunov in their layouts; simulation = [t_end, n_out, y0(4)]; sweep = [parameter (1 rho,
  !> 2 A, 3 frequency [Hz]), start, stop, n_points, direction (1 up, 2 down, 3 both),
  !> carry_state (1/0), threads]; response_range = [resonance (1 3:1, 0 none), parameter, start,
  !> stop]; chart in its layout.
  !> study = [given (1/0), kind (1 response_map, 2 basins), workers, worker_kind (1 processes,
  !> 2 threads), points_per_task, frequency_start, frequency_stop, n_frequencies,
  !> amplitude_start, amplitude_stop, n_amplitudes, continuation (1 none, 2 up, 3 down, 4 both),
  !> x1_start, x1_stop, dx1_start, dx1_stop, n_grid, tol, intensity_start, intensity_stop,
  !> n_intensities, spectral_damping] (kind 3: fragility); study_store, study_figure,
  !> study_scheduler, study_records the &study strings.
  subroutine read_input(path, rpar, ipar, analysis, analysis_values, directory, has_tank, tank, &
                        has_ground, ground, n_samples, seismic, integration, steady, response, &
                        lyapunov, simulation, sweep, response_range, chart, study, study_store, &
                        study_figure, study_scheduler, study_records, status, message)
    use sloshdyn_model, only: model_to_arrays
    use sloshdyn_namelist, only: run_config, core => read_input
    use sloshdyn_layouts, only: from_ode_options, from_steady, from_response, from_lyapunov, &
                                from_tank, from_ground, from_chart
    character(len=*), intent(in) :: path
    real(c_double), intent(out) :: rpar(10), analysis_values(3), tank(17), ground(4), &
                                   seismic(2), integration(7), steady(7), response(10), &
                                   lyapunov(3), simulation(6), sweep(7), response_range(4), &
                                   chart(14), study(22)
    integer(c_int), intent(out) :: ipar(2), analysis, has_tank, has_ground, n_samples, status
    character(len=4096), intent(out) :: directory, study_store, study_figure, study_scheduler, &
                                        study_records
    character(len=256), intent(out) :: message
    type(run_config) :: config
    integer :: info, ints(2)
    rpar = 0; ipar = 0; analysis = 0; analysis_values = 0; tank = 0; integration = 0
    steady = 0; response = 0; lyapunov = 0; simulation = 0; sweep = 0; response_range = 0
    has_tank = 0; has_ground = 0; ground = 0; n_samples = 0; seismic = 0; chart = 0
    directory = ''; study = 0; study_store = ''; study_figure = ''; study_scheduler = ''
    study_records = ''
    call core(path, config, info, message)
    status = info
    if (info /= 0) return
    call model_to_arrays(config%model, rpar, ints)
    ipar = ints
    analysis = config%analysis
    analysis_values = [config%sigma1, config%kappa_min, config%kappa_max]
    directory = config%directory
    has_tank = merge(1, 0, config%dimensional)
    if (config%dimensional) tank = from_tank(config%tank)
    has_ground = merge(1, 0, config%has_ground)
    if (config%has_ground) then
      ground = from_ground(config%ground)
      if (allocated(config%ground%acceleration)) n_samples = size(config%ground%acceleration)
    end if
    seismic = [config%seismic%t_end, real(config%seismic%n_out, c_double)]
    chart = from_chart(config%chart)
    integration = from_ode_options(config%integration, config%method)
    steady = from_steady(config%steady)
    response = from_response(config%response%options)
    lyapunov = from_lyapunov(config%lyapunov)
    simulation = [config%simulation%t_end, real(config%simulation%n_out, c_double), &
                  config%simulation%y0]
    sweep = [real(config%sweep%parameter, c_double), config%sweep%start, config%sweep%stop, &
             real(config%sweep%n_points, c_double), real(config%sweep%direction, c_double), &
             merge(1.0_c_double, 0.0_c_double, config%sweep%carry_state), &
             real(config%sweep%threads, c_double)]
    response_range = [merge(1.0_c_double, 0.0_c_double, config%response%internal_resonance), &
                      real(config%response%parameter, c_double), config%response%start, &
                      config%response%stop]
    associate (st => config%study)
      study = [merge(1.0_c_double, 0.0_c_double, st%given), real(st%kind, c_double), &
               real(st%workers, c_double), real(st%worker_kind, c_double), &
               real(st%points_per_task, c_double), st%frequency_start, st%frequency_stop, &
               real(st%n_frequencies, c_double), st%amplitude_start, st%amplitude_stop, &
               real(st%n_amplitudes, c_double), real(st%continuation, c_double), st%x1_start, &
               st%x1_stop, st%dx1_start, st%dx1_stop, real(st%n_grid, c_double), st%tol, &
               st%intensity_start, st%intensity_stop, real(st%n_intensities, c_double), &
               st%spectral_damping]
      study_store = st%store
      study_records = st%records
      study_figure = st%figure
      study_scheduler = st%scheduler
    end associate
  end subroutine read_input

  !> Read a namelist input file and run it exactly as the executable does (summary on standard
  !> output, CSV files in its output directory); status 1 for bad input. It releases the GIL so
  !> that a cancellation request reaches it, but its app layer has static string lengths: never
  !> two calls at once (sloshdyn.cli holds a lock around it).
  subroutine run_input(path, status, message)
    !f2py threadsafe
    use sloshdyn_namelist, only: run_config, read_input_file => read_input
    use sloshdyn_driver, only: run_analysis
    character(len=*), intent(in) :: path
    integer(c_int), intent(out) :: status
    character(len=256), intent(out) :: message
    type(run_config) :: config
    integer :: info
    call read_input_file(path, config, info, message)
    if (info == 0) call run_analysis(config, info, message)
    status = info
  end subroutine run_input

  !> The rule for the threads of a sweep (carry = 1: the state is carried from point to point).
  subroutine sweep_threads(threads, carry, status, message)
    use sloshdyn_namelist, only: check_threads
    integer(c_int), intent(in) :: threads, carry
    integer(c_int), intent(out) :: status
    character(len=256), intent(out) :: message
    integer :: info
    info = 0
    message = ''
    call check_threads(int(threads), carry /= 0, info, message)
    status = info
  end subroutine sweep_threads

  !> Ask every computation running in this process to stop: they return status 10 (cancelled)
  !> within one integrator or continuation step. Called from Python's main thread on Ctrl-C.
  subroutine request_cancel()
    !f2py threadsafe
    use sloshdyn_cancel, only: core => request_cancel
    call core(-1_c_int)
  end subroutine request_cancel

  !> Forget a cancellation request, once every cancelled call has returned.
  subroutine clear_cancel()
    !f2py threadsafe
    use sloshdyn_cancel, only: core => clear_cancel
    call core()
  end subroutine clear_cancel

  !> The exit code of both front doors for a status, from reading the input (reading = 1) or
  !> from the run (reading = 0).
  subroutine exit_code(status, reading, code)
    !f2py threadsafe
    use sloshdyn_status, only: core => exit_code
    integer(c_int), intent(in) :: status, reading
    integer(c_int), intent(out) :: code
    code = core(int(status), reading /= 0)
  end subroutine exit_code

  !> Every namelist group with its variables and defaults, as written by a namelist write.
  subroutine namelist_defaults(text)
    use sloshdyn_namelist, only: core => namelist_defaults
    character(len=32768), intent(out) :: text
    character(len=:), allocatable :: written
    call core(written)
    text = written
  end subroutine namelist_defaults

  !> Names: a result table's comma-separated column names (list = 'table:NAME'), the analyses
  !> (list = 'analyses'), the integration methods ('methods', from code 0), or the kinds of a
  !> kind list ('special', 'motion', 'verdict'); first = the code of the first name.
  subroutine names(list, text, first, status, message)
    use sloshdyn_tables, only: table_header, table_formats, kind_names
    use sloshdyn_namelist, only: known_analyses, chart_models
    use sloshdyn_integrator, only: method_names
    character(len=*), intent(in) :: list
    character(len=1024), intent(out) :: text
    integer(c_int), intent(out) :: first, status
    character(len=256), intent(out) :: message
    character(len=:), allocatable :: joined
    integer :: code
    status = 0
    message = ''
    code = 1
    if (index(list, 'table:') == 1) then
      joined = table_header(list(7:))
    else if (index(list, 'formats:') == 1) then
      joined = table_formats(list(9:))
    else if (list == 'analyses') then
      joined = join(known_analyses)
    else if (list == 'methods') then
      joined = join(method_names)
      code = lbound(method_names, 1)
    else if (list == 'chart_models') then
      joined = join(chart_models)
    else
      call kind_names(list, joined, code)
    end if
    first = code
    text = joined
    if (len(joined) == 0) then
      status = 1
      message = "no names for '"//list//"'"
    end if
  contains
    pure function join(items) result(joined_items)
      character(len=*), intent(in) :: items(:)
      character(len=:), allocatable :: joined_items
      integer :: i
      joined_items = trim(items(1))
      do i = 2, size(items)
        joined_items = joined_items//','//trim(items(i))
      end do
    end function join
  end subroutine names

  !> The defaults of the option types: model = [beta, gamma, delta, n, p, zeta]; integration, steady,
  !> response and lyapunov in their layouts; shooting = [newton_tol, max_iter].
  !> The method code that runs for the settings integration (layout of sloshdyn_layouts):
  !> the method itself, or for 'auto' the pair chosen for its rtol.
  subroutine method_used(integration, code)
    !f2py threadsafe
    use sloshdyn_integrator, only: chosen_method
    use sloshdyn_layouts, only: to_method
    real(c_double), intent(in) :: integration(7)
    integer(c_int), intent(out) :: code
    code = int(chosen_method(to_method(integration), integration(1)), c_int)
  end subroutine method_used

  subroutine defaults(model, integration, steady, response, lyapunov, shooting)
    !f2py threadsafe
    use sloshdyn_model, only: model_t
    use sloshdyn_ode, only: ode_options
    use sloshdyn_simulation, only: steady_options
    use sloshdyn_response, only: response_options
    use sloshdyn_periodic_response, only: lyapunov_options, newton_tol_default, max_iter_default
    use sloshdyn_integrator, only: METHOD_AUTO
    use sloshdyn_layouts, only: &
                                from_ode_options, from_steady, from_response, from_lyapunov
    real(c_double), intent(out) :: model(6), integration(7), steady(7), &
                                   response(10), lyapunov(3), shooting(2)
    type(model_t) :: m
    model = [m%beta, m%gamma, m%delta, real(m%n, c_double), real(m%p, c_double), m%zeta]
    integration = from_ode_options(ode_options(), METHOD_AUTO)
    steady = from_steady(steady_options())
    response = from_response(response_options())
    lyapunov = from_lyapunov(lyapunov_options())
    shooting = [newton_tol_default, real(max_iter_default, c_double)]
  end subroutine defaults

  ! ==== research toolkit (issue 27): Lyapunov spectrum, slow-flow cycles, branch switching ====
  ! Added at the end in one block for the lead to move into the reorganised bridge.

  !> All four Lyapunov exponents per unit tau from y0 (QR method), their running estimates
  !> history(4, n_hist) after each renormalisation block and the Kaplan-Yorke dimension;
  !> settings in the lyapunov layout.
  subroutine lyapunov_spectrum(rpar, ipar, y0, settings, integration, n_hist, exponents, &
                               history, dimension_ky, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: model_t, model_from_arrays
    use sloshdyn_tank_lyapunov, only: tank_lyapunov_spectrum
    use sloshdyn_layouts, only: to_ode_options, to_method, to_lyapunov
    real(c_double), intent(in) :: rpar(10), y0(4), settings(3), integration(7)
    integer(c_int), intent(in) :: ipar(2), n_hist
    real(c_double), intent(out) :: exponents(4), history(4, n_hist), dimension_ky
    integer(c_int), intent(out) :: status
    character(len=256), intent(out) :: message
    type(model_t) :: model
    integer :: code
    exponents = 0; history = 0; dimension_ky = 0
    call model_from_arrays(rpar, int(ipar), model, code, message)
    if (code == 0) call tank_lyapunov_spectrum(model, y0, to_lyapunov(settings), &
                                               to_ode_options(integration), &
                                               to_method(integration), exponents, history, &
                                               dimension_ky, code, message)
    status = code
  end subroutine lyapunov_spectrum
  !> The branch of slow-flow limit cycles (the beats) through the cycle (x_cycle, period [tau])
  !> at the model's rho and A, in rho (which = 1) or A (2) over [lambda_min, lambda_max];
  !> settings = [ds, ds_min, ds_max, x_scale, direction, x_tol, f_tol, max_iter] (the last three:
  !> Newton's, sloshdyn_continuation's newton_options). points(7, :) = [lambda, x(4), T,
  !> stable], multipliers(8, :) = [re(4), im(4)], amplitudes(4, :) = [min|B1|, max|B1|, min|B2|,
  !> max|B2|], special(7, :) = [kind, lambda, x(4), T]; stop_reason: sloshdyn_continuation's.
  subroutine slow_flow_cycle_branch(rpar, ipar, which, x_cycle, period, lambda_min, lambda_max, &
                                    settings, integration, max_points, max_special, points, &
                                    multipliers, amplitudes, n_points, special, n_special, &
                                    stop_reason, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: model_t, model_from_arrays
    use sloshdyn_continuation, only: continuation_options
    use sloshdyn_slowflow_cycles, only: core => slow_flow_cycle_branch
    use sloshdyn_layouts, only: to_ode_options, to_method, to_int
    real(c_double), intent(in) :: rpar(10), x_cycle(4), period, lambda_min, lambda_max, &
                                  settings(8), integration(7)
    integer(c_int), intent(in) :: ipar(2), which, max_points, max_special
    real(c_double), intent(out) :: points(7, max_points), multipliers(8, max_points), &
                                   amplitudes(4, max_points), special(7, max_special)
    integer(c_int), intent(out) :: n_points, n_special, stop_reason, status
    character(len=256), intent(out) :: message
    type(model_t) :: model
    type(continuation_options) :: options
    integer :: code, found, found_special, reason
    points = 0; multipliers = 0; amplitudes = 0; special = 0
    found = 0; found_special = 0; reason = 0
    options%ds = settings(1)
    options%ds_min = settings(2)
    options%ds_max = settings(3)
    options%x_scale = settings(4)
    options%direction = to_int(settings(5))
    options%newton%x_tol = settings(6)
    options%newton%f_tol = settings(7)
    options%newton%max_iter = to_int(settings(8))
    options%max_points = max_points
    call model_from_arrays(rpar, int(ipar), model, code, message)
    if (code == 0) call core(model, int(which), x_cycle, period, lambda_min, lambda_max, &
                             options, to_ode_options(integration), to_method(integration), &
                             points, multipliers, amplitudes, found, special, found_special, &
                             reason, code, message)
    n_points = found
    n_special = found_special
    stop_reason = reason
    status = code
  end subroutine slow_flow_cycle_branch
  ! ==== end of the research toolkit block ====
end module sloshdyn_bridge
