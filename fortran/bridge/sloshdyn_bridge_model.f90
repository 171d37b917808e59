!> The f2py bridge of model.py and parameters.py: the model, its linear analysis and equilibria.
!>
!> The f2py bridge, the only Fortran that Python sees: the modules sloshdyn_bridge_*, one per
!> module of the Python package, all in the one extension sloshdyn._core. Scalars and
!> explicit-shape arrays of c_double/c_int cross the boundary; every routine returns status
!> (0 = success) and a fixed-length message.
!> Every flat array has a named layout: the field names of the settings and small results in
!> sloshdyn_layouts, the model's rpar = real_param_names and ipar = [n, p] of sloshdyn_model, the
!> columns of result tables in sloshdyn_tables; Python asks for them (names) and builds and
!> decodes the arrays by name. Array sizes are the layouts' named constants: f2py copies their
!> names into its C wrapper, where the build defines them from the core (sloshdyn_bridge_sizes).
!> Threads: the routines that compute (every one but the namelist reader and the name lists of
!> the app layer) carry `!f2py threadsafe`, so f2py releases the GIL
!> while the Fortran runs and Python threads (e.g. Dask's threaded workers) run them at once.
!> That is safe because the core keeps no state between calls: no module variables, no `save`,
!> and no deferred-length function results in the layers below the app (gfortran keeps their
!> lengths in static variables; see sloshdyn_text). The one exception is the cancellation flag
!> (sloshdyn_cancel): request_cancel, called from another Python thread, makes every running
!> computation return status 10 (cancelled) within one step (python/sloshdyn/_cancel.py). The
!> app layer (reader, driver, writers) has such statics, so its routines keep the GIL and run one
!> at a time; run_input releases it so that Ctrl-C can cancel a run, and Python runs it one at a
!> time (a lock in sloshdyn.cli).
module sloshdyn_bridge_model
  use, intrinsic :: iso_c_binding, only: c_double, c_int
  implicit none

contains

  !> Equivalent pendulum of a cylindrical tank, eq (2)-(3): pendulum in the 'pendulum' layout
  !> (l, m, d1, m0, d0, m_F), filled by the layout's field names.
  subroutine tank_pendulum(radius, depth, density, liquid_mass, pendulum, status, message)
    !f2py threadsafe
    use sloshdyn_layouts, only: PENDULUM_SIZE, field_index
    use sloshdyn_tank, only: core => tank_pendulum
    real(c_double), intent(in) :: radius, depth, density, liquid_mass
    real(c_double), intent(out) :: pendulum(PENDULUM_SIZE)
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
    integer :: info
    call core(radius, depth, density, liquid_mass, &
              l=pendulum(field_index('pendulum', 'pendulum_length')), &
              m=pendulum(field_index('pendulum', 'sloshing_mass')), &
              d1=pendulum(field_index('pendulum', 'd1')), &
              m0=pendulum(field_index('pendulum', 'rigid_mass')), &
              d0=pendulum(field_index('pendulum', 'd0')), &
              mf=pendulum(field_index('pendulum', 'liquid_mass')), status=info, message=message)
    status = info
  end subroutine tank_pendulum

  !> Dimensionless groups of eq (9): physical in the 'physical' layout (M, L, k, c, b, d, g,
  !> theta0, l, m), groups in the 'groups' layout (s1, mu1, kappa, beta, gamma, delta), both
  !> read and filled by the layouts' field names.
  subroutine dimensionless_groups(physical, groups, status, message)
    !f2py threadsafe
    use sloshdyn_layouts, only: PHYSICAL_SIZE, GROUPS_SIZE, field_index
    use sloshdyn_model, only: model_from_physical
    real(c_double), intent(in) :: physical(PHYSICAL_SIZE)
    real(c_double), intent(out) :: groups(GROUPS_SIZE)
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
    integer :: info
    call model_from_physical(total_mass=physical(field_index('physical', 'M')), &
                             rod_length=physical(field_index('physical', 'L')), &
                             stiffness=physical(field_index('physical', 'k')), &
                             rod_damping=physical(field_index('physical', 'c')), &
                             impact_coef=physical(field_index('physical', 'b')), &
                             dissipation_coef=physical(field_index('physical', 'd')), &
                             gravity=physical(field_index('physical', 'g')), &
                             theta0=physical(field_index('physical', 'theta0')), &
                             pendulum_length=physical(field_index('physical', 'l')), &
                             sloshing_mass=physical(field_index('physical', 'm')), &
                             s1=groups(field_index('groups', 's1')), &
                             mu1=groups(field_index('groups', 'mu1')), &
                             kappa=groups(field_index('groups', 'kappa')), &
                             beta=groups(field_index('groups', 'beta')), &
                             gamma=groups(field_index('groups', 'gamma')), &
                             delta=groups(field_index('groups', 'delta')), &
                             status=info, message=message)
    status = info
  end subroutine dimensionless_groups

  !> Validate the parameters; coefficients a1..a6, b1..b6 of eq (11).
  subroutine model_coefficients(rpar, ipar, a, b, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    real(c_double), intent(in) :: rpar(n_real_params)
    integer(c_int), intent(in) :: ipar(n_int_params)
    real(c_double), intent(out) :: a(6), b(6)
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
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
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_status, only: SD_NON_FINITE
    use sloshdyn_text, only: num2str
    use sloshdyn_motion, only: inertia_matrix, forcing_vector, core_eom => equations_of_motion, &
                               motion_jacobian
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    real(c_double), intent(in) :: rpar(n_real_params), tau, y(4)
    integer(c_int), intent(in) :: ipar(n_int_params)
    real(c_double), intent(out) :: mass(2, 2), force(2), dydt(4), jacobian(4, 4)
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
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

  !> Natural frequencies: omegas in the 'natural_frequencies' layout (eq 28, then dgeev);
  !> stiffness K (eq 26), modal matrix P and its inverse (eq 34).
  subroutine natural_frequencies(rpar, ipar, omegas, stiffness, modal, modal_inverse, status, &
                                 message)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_layouts, only: NATURAL_FREQUENCIES_SIZE, field_index
    use sloshdyn_linear, only: stiffness_matrix, core => natural_frequencies, &
                               natural_frequencies_eig, modal_matrix
    real(c_double), intent(in) :: rpar(n_real_params)
    integer(c_int), intent(in) :: ipar(n_int_params)
    real(c_double), intent(out) :: omegas(NATURAL_FREQUENCIES_SIZE), stiffness(2, 2), modal(2, 2), modal_inverse(2, 2)
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
    type(model_t) :: model
    integer :: info
    omegas = 0; stiffness = 0; modal = 0; modal_inverse = 0
    call model_from_arrays(rpar, int(ipar), model, info, message)
    if (info == 0) call core(model, omegas(field_index('natural_frequencies', 'omega1')), &
                             omegas(field_index('natural_frequencies', 'omega2')), info, message)
    if (info == 0) call natural_frequencies_eig(model, &
                          omegas(field_index('natural_frequencies', 'omega1_dgeev')), &
                          omegas(field_index('natural_frequencies', 'omega2_dgeev')), info, &
                          message)
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
    character(len=512), intent(out) :: message
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
    character(len=512), intent(out) :: message
    integer :: info, found
    call core(s1, mu1, sigma1, kappa_min, kappa_max, roots, found, info, message)
    n_roots = found
    status = info
  end subroutine kappa_for_detuning

  !> Real roots of eq (17) (which = 1, theta) or eq (18) (which = 2, phi), ascending.
  subroutine equilibrium_angles(rpar, ipar, which, max_roots, roots, n_roots, truncated, &
                                status, message)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_equilibria, only: theta_roots, phi_roots
    real(c_double), intent(in) :: rpar(n_real_params)
    integer(c_int), intent(in) :: ipar(n_int_params), which, max_roots
    real(c_double), intent(out) :: roots(max_roots)
    integer(c_int), intent(out) :: n_roots, truncated, status
    character(len=512), intent(out) :: message
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
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_layouts, only: ROUTH_TRIVIAL_SIZE
    use sloshdyn_equilibria, only: core => equilibria, trivial_routh_hurwitz
    real(c_double), intent(in) :: rpar(n_real_params)
    integer(c_int), intent(in) :: ipar(n_int_params), max_eq
    real(c_double), intent(out) :: theta(max_eq), phi(max_eq), eig_re(4, max_eq), &
                                   eig_im(4, max_eq), routh(ROUTH_TRIVIAL_SIZE)
    integer(c_int), intent(out) :: physical(max_eq), verdict(max_eq), n_eq, truncated, status
    character(len=512), intent(out) :: message
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
end module sloshdyn_bridge_model
