!> The f2py bridge of spatial.py: the spatial model of issue 26 (sloshdyn_spatial) and its swirl
!> analysis. The model crosses as the planar rpar, ipar (sloshdyn_model) plus spatial(2) =
!> [azimuth, ellipticity] (layout 'spatial' of sloshdyn_layouts). See sloshdyn_bridge_model for
!> the bridge's conventions.
module sloshdyn_bridge_spatial
  use, intrinsic :: iso_c_binding, only: c_double, c_int
  implicit none

contains

  !> The spatial equations at one state y = (x1, x1', x2, x2', y1, y1', y2, y2'): the inertia
  !> matrix (eq S7), y', the analytic Jacobian dy'/dy, and [energy, angular momentum about the
  !> vertical] (eq S2-S3).
  subroutine spatial_equations(rpar, ipar, spatial, tau, y, mass, dydt, jacobian, invariants, &
                               status, message)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_layouts, only: SPATIAL_SIZE
    use sloshdyn_status, only: SD_NON_FINITE
    use sloshdyn_spatial, only: spatial_model_t, spatial_model, spatial_mass_matrix, &
                                core_equations => spatial_equations, spatial_jacobian, &
                                spatial_invariants
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    real(c_double), intent(in) :: rpar(n_real_params), spatial(SPATIAL_SIZE), tau, y(8)
    integer(c_int), intent(in) :: ipar(n_int_params)
    real(c_double), intent(out) :: mass(4, 4), dydt(8), jacobian(8, 8), invariants(2)
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
    type(model_t) :: planar
    type(spatial_model_t) :: model
    integer :: info
    mass = 0; dydt = 0; jacobian = 0; invariants = 0
    call model_from_arrays(rpar, int(ipar), planar, info, message)
    if (info == 0) call spatial_model(planar, spatial(1), spatial(2), model, info, message)
    status = info
    if (info /= 0) return
    call spatial_mass_matrix(model, y, mass)
    call core_equations(model, tau, y, dydt)
    call spatial_jacobian(model, tau, y, jacobian)
    call spatial_invariants(model, y, invariants(1), invariants(2))
    if (.not. (all(ieee_is_finite(mass)) .and. all(ieee_is_finite(dydt)) .and. &
               all(ieee_is_finite(jacobian)) .and. all(ieee_is_finite(invariants)))) then
      status = SD_NON_FINITE
      message = 'the spatial equations of motion overflow at this state'
      mass = 0; dydt = 0; jacobian = 0; invariants = 0
    end if
  end subroutine spatial_equations

  !> The time history of the spatial model from y0 (8 states) at tau0 at tau_out (ascending,
  !> >= tau0; sloshdyn_simulation's spatial_time_history): history(SPATIAL_HISTORY_ROWS, n_out)
  !> in the rows of the 'spatial_history' table after tau, counts as simulate's. On failure the
  !> columns not reached are NaN.
  subroutine simulate(rpar, ipar, spatial, tau0, y0, n_out, tau_out, integration, history, &
                      counts, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_tables, only: SPATIAL_HISTORY_ROWS, COUNTS_SIZE
    use sloshdyn_layouts, only: INTEGRATION_SIZE, SPATIAL_SIZE, to_ode_options, to_method, &
                                counts_array
    use sloshdyn_ode, only: ode_stats
    use sloshdyn_spatial, only: spatial_model_t, spatial_model
    use sloshdyn_simulation, only: spatial_time_history
    real(c_double), intent(in) :: rpar(n_real_params), spatial(SPATIAL_SIZE), tau0, y0(8), &
                                  tau_out(n_out), integration(INTEGRATION_SIZE)
    integer(c_int), intent(in) :: ipar(n_int_params), n_out
    real(c_double), intent(out) :: history(SPATIAL_HISTORY_ROWS, n_out), counts(COUNTS_SIZE)
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
    type(model_t) :: planar
    type(spatial_model_t) :: model
    type(ode_stats) :: stats
    integer :: info
    history = 0
    counts = 0
    call model_from_arrays(rpar, int(ipar), planar, info, message)
    if (info == 0) call spatial_model(planar, spatial(1), spatial(2), model, info, message)
    if (info == 0) then
      call spatial_time_history(model, tau0, y0, tau_out, to_ode_options(integration), &
                                to_method(integration), history, stats, info, message)
      counts = counts_array(stats)
    end if
    status = info
  end subroutine simulate

  !> The out-of-plane Floquet multipliers nu(2, 4) = (Re, Im) of the planar orbit of period k T
  !> through y_orbit (sloshdyn_swirl).
  subroutine out_of_plane_multipliers(rpar, ipar, y_orbit, k, integration, nu, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_layouts, only: INTEGRATION_SIZE, to_ode_options, to_method
    use sloshdyn_swirl, only: core => out_of_plane_multipliers
    real(c_double), intent(in) :: rpar(n_real_params), y_orbit(4), integration(INTEGRATION_SIZE)
    integer(c_int), intent(in) :: ipar(n_int_params), k
    real(c_double), intent(out) :: nu(2, 4)
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
    type(model_t) :: model
    real(c_double) :: re(4), im(4)
    integer :: code
    nu = 0
    call model_from_arrays(rpar, int(ipar), model, code, message)
    if (code == 0) call core(model, y_orbit, int(k), to_ode_options(integration), &
                             to_method(integration), re, im, code, message)
    if (code == 0) nu = transpose(reshape([re, im], [4, 2]))
    status = code
  end subroutine out_of_plane_multipliers

  !> The criticality c of the swirl edge of kind `kind` (a SPECIAL_* code) through the planar
  !> orbit y_orbit (period k T) of the model at the edge (sloshdyn_swirl's edge_criticality),
  !> with the critical multiplier nu, the size of c's terms and the critical eigenvector q.
  subroutine swirl_edge_criticality(rpar, ipar, kind, y_orbit, k, integration, c, nu, &
                                    size_of_terms, q, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_layouts, only: INTEGRATION_SIZE, to_ode_options, to_method
    use sloshdyn_swirl, only: edge_criticality
    real(c_double), intent(in) :: rpar(n_real_params), y_orbit(4), integration(INTEGRATION_SIZE)
    integer(c_int), intent(in) :: ipar(n_int_params), kind, k
    real(c_double), intent(out) :: c, nu, size_of_terms, q(8)
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
    type(model_t) :: model
    integer :: code
    c = 0; nu = 0; size_of_terms = 0; q = 0
    call model_from_arrays(rpar, int(ipar), model, code, message)
    if (code == 0) call edge_criticality(model, int(kind), y_orbit, int(k), &
                                         to_ode_options(integration), to_method(integration), &
                                         c, nu, size_of_terms, code, message, q)
    status = code
  end subroutine swirl_edge_criticality

  !> The swirl band along the branch of planar orbits (period k T) through y0, continued in rho
  !> (which = 1) or A (which = 2) over [lambda_min, lambda_max] with settings = [ds, ds_min,
  !> ds_max, x_scale, direction] (sloshdyn_swirl's swirl_branch): points(SWIRL_BRANCH_ROWS, :)
  !> and edges(SWIRL_EDGE_ROWS, :) in the tables 'swirl_branch' and 'swirl_edges'; complete = 0
  !> if the branch stopped early; conservative = 1 if the Neimark-Sacker tests were skipped
  !> (volume-preserving monodromy: no damping).
  subroutine swirl_branch(rpar, ipar, which, y0, k, lambda_min, lambda_max, settings, &
                          integration, max_points, max_edges, points, n_points, edges, n_edges, &
                          complete, conservative, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_tables, only: SWIRL_BRANCH_ROWS, SWIRL_EDGE_ROWS
    use sloshdyn_layouts, only: INTEGRATION_SIZE, CONTINUATION_SIZE, to_ode_options, to_method, &
                                to_continuation
    use sloshdyn_continuation, only: continuation_options
    use sloshdyn_swirl, only: core => swirl_branch
    real(c_double), intent(in) :: rpar(n_real_params), y0(4), lambda_min, lambda_max, &
                                  settings(CONTINUATION_SIZE), integration(INTEGRATION_SIZE)
    integer(c_int), intent(in) :: ipar(n_int_params), which, k, max_points, max_edges
    real(c_double), intent(out) :: points(SWIRL_BRANCH_ROWS, max_points), &
                                   edges(SWIRL_EDGE_ROWS, max_edges)
    integer(c_int), intent(out) :: n_points, n_edges, complete, conservative, status
    character(len=512), intent(out) :: message
    type(model_t) :: model
    type(continuation_options) :: options
    integer :: code, found, found_edges
    logical :: done, no_damping
    points = 0; edges = 0; found = 0; found_edges = 0; done = .false.; no_damping = .false.
    options = to_continuation(settings)
    options%max_points = max_points
    call model_from_arrays(rpar, int(ipar), model, code, message)
    if (code == 0) call core(model, int(which), y0, int(k), lambda_min, lambda_max, options, &
                             to_ode_options(integration), to_method(integration), points, found, &
                             edges, found_edges, done, no_damping, code, message)
    n_points = found
    n_edges = found_edges
    complete = merge(1, 0, done)
    conservative = merge(1, 0, no_damping)
    status = code
  end subroutine swirl_branch

  !> The swirling orbits (period k T) born at the swirl edge through the planar orbit y_edge of
  !> the model (its parameter which = 1 rho, 2 A at the edge), continued over [lambda_min,
  !> lambda_max] with settings = [ds, ds_min, ds_max, x_scale, direction]
  !> (sloshdyn_swirling_branch): points and special in the tables 'swirling_branch' and
  !> 'swirling_special_points'; complete = 0 if the branch stopped early.
  subroutine swirling_branch(rpar, ipar, which, y_edge, k, lambda_min, lambda_max, settings, &
                             integration, max_points, max_special, points, n_points, special, &
                             n_special, complete, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_tables, only: SWIRLING_BRANCH_ROWS, SWIRLING_SPECIAL_ROWS
    use sloshdyn_layouts, only: INTEGRATION_SIZE, CONTINUATION_SIZE, to_ode_options, to_method, &
                                to_continuation
    use sloshdyn_continuation, only: continuation_options
    use sloshdyn_swirling_branch, only: core => swirling_branch
    real(c_double), intent(in) :: rpar(n_real_params), y_edge(4), lambda_min, lambda_max, &
                                  settings(CONTINUATION_SIZE), integration(INTEGRATION_SIZE)
    integer(c_int), intent(in) :: ipar(n_int_params), which, k, max_points, max_special
    real(c_double), intent(out) :: points(SWIRLING_BRANCH_ROWS, max_points), &
                                   special(SWIRLING_SPECIAL_ROWS, max_special)
    integer(c_int), intent(out) :: n_points, n_special, complete, status
    character(len=512), intent(out) :: message
    type(model_t) :: model
    type(continuation_options) :: options
    integer :: code, found, found_special
    logical :: done
    points = 0; special = 0; found = 0; found_special = 0; done = .false.
    options = to_continuation(settings)
    options%max_points = max_points
    call model_from_arrays(rpar, int(ipar), model, code, message)
    if (code == 0) call core(model, int(which), y_edge, int(k), lambda_min, lambda_max, options, &
                             to_ode_options(integration), to_method(integration), points, found, &
                             special, found_special, done, code, message)
    n_points = found
    n_special = found_special
    complete = merge(1, 0, done)
    status = code
  end subroutine swirling_branch

  !> The swirl edge of kind `kind` (a SPECIAL_* code) at rho_edge through the planar orbit y_edge
  !> of the model (at the edge's A) continued as a curve in rho_range x A_range
  !> (sloshdyn_swirl_curve): points(SWIRL_CURVE_ROWS, capacity >= 2 max_points - 1) and at (its
  !> points at the A of A_values) in the table 'swirl_boundary_curve', folds in
  !> 'swirl_curve_folds', its degenerate pitchforks (or flips) in 'swirl_curve_degenerate';
  !> complete = 0 if the curve stopped early (status then says why).
  subroutine swirl_boundary_curve(rpar, ipar, kind, rho_edge, y_edge, k, rho_range, A_range, &
                                  n_A, A_values, ds, max_points, tol, newton_tol, max_iter, &
                                  integration, capacity, max_at, max_folds, points, n_points, &
                                  at, n_at, folds, n_folds, degenerate, n_degenerate, complete, &
                                  status, message)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_tables, only: SWIRL_CURVE_ROWS, SWIRL_CURVE_FOLD_ROWS
    use sloshdyn_layouts, only: INTEGRATION_SIZE, to_ode_options, to_method
    use sloshdyn_swirl_curve, only: curve_settings, core => swirl_boundary_curve
    real(c_double), intent(in) :: rpar(n_real_params), rho_edge, y_edge(4), rho_range(2), &
                                  A_range(2), A_values(n_A), ds, tol, newton_tol, &
                                  integration(INTEGRATION_SIZE)
    integer(c_int), intent(in) :: ipar(n_int_params), kind, k, n_A, max_points, max_iter, &
                                  capacity, max_at, max_folds
    real(c_double), intent(out) :: points(SWIRL_CURVE_ROWS, capacity), &
                                   at(SWIRL_CURVE_ROWS, max_at), &
                                   folds(SWIRL_CURVE_FOLD_ROWS, max_folds), &
                                   degenerate(SWIRL_CURVE_ROWS, max_folds)
    integer(c_int), intent(out) :: n_points, n_at, n_folds, n_degenerate, complete, status
    character(len=512), intent(out) :: message
    type(model_t) :: model
    integer :: code, found, found_at, found_folds, found_degenerate
    logical :: done
    points = 0; at = 0; folds = 0; degenerate = 0; found = 0; found_at = 0; found_folds = 0
    found_degenerate = 0; done = .false.
    call model_from_arrays(rpar, int(ipar), model, code, message)
    if (code == 0) call core(model, int(kind), rho_edge, y_edge, int(k), rho_range, A_range, &
                             A_values, curve_settings(ds, int(max_points), tol, newton_tol, &
                                                      int(max_iter)), &
                             to_ode_options(integration), to_method(integration), points, found, &
                             at, found_at, folds, found_folds, degenerate, found_degenerate, &
                             done, code, message)
    n_points = found
    n_at = found_at
    n_folds = found_folds
    n_degenerate = found_degenerate
    complete = merge(1, 0, done)
    status = code
  end subroutine swirl_boundary_curve

  !> A periodic orbit of period k T of the spatial model (its excitation along spatial's azimuth,
  !> with its ellipticity) from y0 after `transient` k T of integration (sloshdyn_swirl's
  !> swirl_orbit): y_orbit, multipliers(2, 8) = (Re, Im), info(SWIRL_ORBIT_INFO_SIZE) (layout
  !> 'swirl_orbit_info').
  subroutine swirl_orbit(rpar, ipar, spatial, y0, k, transient, integration, newton_tol, &
                         max_iter, y_orbit, multipliers, info, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_layouts, only: INTEGRATION_SIZE, SWIRL_ORBIT_INFO_SIZE, SPATIAL_SIZE, &
                                to_ode_options, to_method
    use sloshdyn_spatial, only: spatial_model_t, spatial_model
    use sloshdyn_swirl, only: core => swirl_orbit
    real(c_double), intent(in) :: rpar(n_real_params), spatial(SPATIAL_SIZE), y0(8), &
                                  integration(INTEGRATION_SIZE), newton_tol
    integer(c_int), intent(in) :: ipar(n_int_params), k, transient, max_iter
    real(c_double), intent(out) :: y_orbit(8), multipliers(2, 8), info(SWIRL_ORBIT_INFO_SIZE)
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
    type(model_t) :: planar
    type(spatial_model_t) :: model
    real(c_double) :: re(8), im(8), peak, amplitude, angular_momentum
    integer :: code, iterations
    y_orbit = 0; multipliers = 0; info = 0; iterations = 0
    peak = 0; amplitude = 0; angular_momentum = 0
    call model_from_arrays(rpar, int(ipar), planar, code, message)
    if (code == 0) call spatial_model(planar, spatial(1), spatial(2), model, code, message)
    if (code == 0) call core(model, y0, int(k), int(transient), to_ode_options(integration), &
                             to_method(integration), newton_tol, int(max_iter), y_orbit, re, &
                             im, iterations, peak, amplitude, angular_momentum, code, message)
    if (code == 0) multipliers = transpose(reshape([re, im], [8, 2]))
    info = [real(iterations, c_double), peak, amplitude, angular_momentum]
    status = code
  end subroutine swirl_orbit

  !> The tank at rest under ground motion in two components (sloshdyn_seismic_spatial):
  !> ground/samples the first component (along spatial's azimuth), ground_2/samples_2 the second
  !> (a record with the same dt, or ignored for harmonic motion, whose second component is
  !> spatial's ellipticity); table(SEISMIC_SPATIAL_ROWS, n_out), peaks(SEISMIC_SPATIAL_PEAKS).
  subroutine seismic_response_spatial(tank, ground, n, samples, ground_2, n_2, samples_2, &
                                      spatial, t_end, n_out, integration, table, peaks, status, &
                                      message)
    !f2py threadsafe
    use sloshdyn_tables, only: SEISMIC_SPATIAL_ROWS, SEISMIC_SPATIAL_PEAKS
    use sloshdyn_layouts, only: INTEGRATION_SIZE, TANK_SIZE, GROUND_SIZE, SPATIAL_SIZE, to_tank, &
                                to_ground, to_ode_options, to_method
    use sloshdyn_seismic_spatial, only: core => seismic_response_spatial
    integer(c_int), intent(in) :: n, n_2, n_out
    real(c_double), intent(in) :: tank(TANK_SIZE), ground(GROUND_SIZE), samples(n), &
                                  ground_2(GROUND_SIZE), samples_2(n_2), spatial(SPATIAL_SIZE), &
                                  t_end, integration(INTEGRATION_SIZE)
    real(c_double), intent(out) :: table(SEISMIC_SPATIAL_ROWS, n_out), &
                                   peaks(SEISMIC_SPATIAL_PEAKS)
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
    integer :: info
    call core(to_tank(tank), to_ground(ground, samples), to_ground(ground_2, samples_2), &
              spatial(1), spatial(2), t_end, int(n_out), to_ode_options(integration), &
              to_method(integration), table, peaks, info, message)
    status = info
  end subroutine seismic_response_spatial
end module sloshdyn_bridge_spatial
