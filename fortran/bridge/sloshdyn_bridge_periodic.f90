!> The f2py bridge of periodic.py: periodic orbits, their continuation and Lyapunov exponents.
!> The bridge's contract (c_double/c_int arrays in named layouts, status and message,
!> threads and the GIL) is written once, in sloshdyn_bridge_model.f90.
module sloshdyn_bridge_periodic
  use, intrinsic :: iso_c_binding, only: c_double, c_int
  implicit none

contains

  !> A periodic orbit of period k T by shooting from the guess y0 (full equations):
  !> y_orbit(4), monodromy(4, 4), multipliers(2, 4) = (Re, Im),
  !> info(ORBIT_INFO_SIZE) = [iterations, max|x1|].
  subroutine periodic_orbit(rpar, ipar, y0, k, integration, newton_tol, max_iter, y_orbit, &
                            monodromy, multipliers, info, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_layouts, only: INTEGRATION_SIZE, ORBIT_INFO_SIZE, to_ode_options, to_method
    use sloshdyn_periodic_response, only: core => periodic_orbit
    real(c_double), intent(in) :: rpar(n_real_params), y0(4), integration(INTEGRATION_SIZE), &
                                  newton_tol
    integer(c_int), intent(in) :: ipar(n_int_params), k, max_iter
    real(c_double), intent(out) :: y_orbit(4), monodromy(4, 4), multipliers(2, 4), &
                                   info(ORBIT_INFO_SIZE)
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
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

  !> The criticality of the period doubling of the orbit of period k T through y (at the
  !> model's excitation): the flip coefficient c (> 0 supercritical), the critical eigenvector
  !> q (unit) and multiplier mu (sloshdyn_map_normal_form).
  subroutine period_doubling_criticality(rpar, ipar, y, k, integration, c, q, mu, status, &
                                         message)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_layouts, only: INTEGRATION_SIZE, to_ode_options, to_method
    use sloshdyn_periodic_response, only: core => period_doubling_criticality
    real(c_double), intent(in) :: rpar(n_real_params), y(4), integration(INTEGRATION_SIZE)
    integer(c_int), intent(in) :: ipar(n_int_params), k
    real(c_double), intent(out) :: c, q(4), mu
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
    type(model_t) :: model
    integer :: code
    c = 0; q = 0; mu = 0
    call model_from_arrays(rpar, int(ipar), model, code, message)
    if (code == 0) call core(model, y, int(k), to_ode_options(integration), &
                             to_method(integration), c, q, mu, code, message)
    status = code
  end subroutine period_doubling_criticality

  !> The Neimark-Sacker coefficient d of the orbit of period k T through y (a Neimark-Sacker
  !> point; < 0 supercritical), with its eigenvector q = q_re + i q_im and multiplier mu.
  subroutine neimark_sacker_criticality(rpar, ipar, y, k, integration, d, q_re, q_im, mu_re, &
                                        mu_im, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_layouts, only: INTEGRATION_SIZE, to_ode_options, to_method
    use sloshdyn_periodic_response, only: core => neimark_sacker_criticality
    real(c_double), intent(in) :: rpar(n_real_params), y(4), integration(INTEGRATION_SIZE)
    integer(c_int), intent(in) :: ipar(n_int_params), k
    real(c_double), intent(out) :: d, q_re(4), q_im(4), mu_re, mu_im
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
    type(model_t) :: model
    complex(c_double) :: q(4), mu
    integer :: code
    d = 0; q_re = 0; q_im = 0; mu_re = 0; mu_im = 0
    call model_from_arrays(rpar, int(ipar), model, code, message)
    if (code == 0) then
      call core(model, y, int(k), to_ode_options(integration), to_method(integration), d, q, &
                mu, code, message)
      q_re = real(q, c_double); q_im = aimag(q); mu_re = real(mu, c_double); mu_im = aimag(mu)
    end if
    status = code
  end subroutine neimark_sacker_criticality

  !> Continuation of periodic orbits (period k T) in rho (which = 1) or A (which = 2) from the
  !> orbit through y0 at the parameters of rpar; settings = [ds, ds_min, ds_max, x_scale,
  !> direction]; points(7, :) = [lambda, y0(4), max|x1|, stable], multipliers(8, :) =
  !> [Re(4), Im(4)], special(7, :) = [kind, lambda, y0(4), max|x1|] (kinds of sloshdyn_tables);
  !> complete = 0 if the branch stopped early.
  subroutine periodic_branch(rpar, ipar, which, y0, k, lambda_min, lambda_max, settings, &
                             integration, max_points, max_special, points, multipliers, n_points, &
                             special, n_special, complete, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_tables, only: PERIODIC_POINT_ROWS, PERIODIC_MULTIPLIER_ROWS, &
                               PERIODIC_SPECIAL_ROWS
    use sloshdyn_layouts, only: INTEGRATION_SIZE, CONTINUATION_SIZE, to_ode_options, to_method, &
                                to_continuation
    use sloshdyn_continuation, only: continuation_options
    use sloshdyn_periodic_response, only: periodic_response
    real(c_double), intent(in) :: rpar(n_real_params), y0(4), lambda_min, lambda_max, &
                                  settings(CONTINUATION_SIZE), &
                                  integration(INTEGRATION_SIZE)
    integer(c_int), intent(in) :: ipar(n_int_params), which, k, max_points, max_special
    real(c_double), intent(out) :: points(PERIODIC_POINT_ROWS, max_points), &
                                   multipliers(PERIODIC_MULTIPLIER_ROWS, max_points), &
                                   special(PERIODIC_SPECIAL_ROWS, max_special)
    integer(c_int), intent(out) :: n_points, n_special, complete, status
    character(len=512), intent(out) :: message
    type(model_t) :: model
    type(continuation_options) :: options
    integer :: code, found, found_special
    logical :: done
    points = 0; multipliers = 0; special = 0; found = 0; found_special = 0; done = .false.
    options = to_continuation(settings)
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

  !> A start state (forcing phase 0) for shooting, by name: 'simulation' or 'slow_flow'
  !> (sloshdyn_periodic_response's periodic_start_state).
  subroutine start_state(rpar, ipar, start, integration, y_start, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_layouts, only: INTEGRATION_SIZE, to_ode_options, to_method
    use sloshdyn_periodic_response, only: periodic_start_state
    real(c_double), intent(in) :: rpar(n_real_params), integration(INTEGRATION_SIZE)
    integer(c_int), intent(in) :: ipar(n_int_params)
    character(len=*), intent(in) :: start
    real(c_double), intent(out) :: y_start(4)
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
    type(model_t) :: model
    integer :: code
    y_start = 0
    call model_from_arrays(rpar, int(ipar), model, code, message)
    if (code == 0) call periodic_start_state(model, start, to_ode_options(integration), &
                                             to_method(integration), y_start, code, message)
    status = code
  end subroutine start_state

  !> Branch switching at a special point of kind (the codes of sloshdyn_tables: branch point or
  !> period doubling) at (y_special, lambda_special) of a branch of period k T in rho
  !> (which = 1) or A (which = 2), the other parameters from rpar: the other branch, or the
  !> doubled orbits (period k_new T = 2 k T), in the layouts of periodic_branch.
  subroutine switch_branch(rpar, ipar, which, kind, y_special, lambda_special, k, lambda_min, &
                           lambda_max, &
                           settings, integration, max_points, max_special, points, multipliers, &
                           n_points, special, n_special, complete, k_new, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_tables, only: PERIODIC_POINT_ROWS, PERIODIC_MULTIPLIER_ROWS, &
                               PERIODIC_SPECIAL_ROWS
    use sloshdyn_layouts, only: INTEGRATION_SIZE, CONTINUATION_SIZE, to_ode_options, to_method, &
                                to_continuation
    use sloshdyn_continuation, only: continuation_options
    use sloshdyn_periodic_response, only: periodic_switch
    real(c_double), intent(in) :: rpar(n_real_params), y_special(4), lambda_special, &
                                  lambda_min, lambda_max, &
                                  settings(CONTINUATION_SIZE), &
                                  integration(INTEGRATION_SIZE)
    integer(c_int), intent(in) :: ipar(n_int_params), which, kind, k, max_points, max_special
    real(c_double), intent(out) :: points(PERIODIC_POINT_ROWS, max_points), &
                                   multipliers(PERIODIC_MULTIPLIER_ROWS, max_points), &
                                   special(PERIODIC_SPECIAL_ROWS, max_special)
    integer(c_int), intent(out) :: n_points, n_special, complete, k_new, status
    character(len=512), intent(out) :: message
    type(model_t) :: model
    type(continuation_options) :: options
    integer :: code, found, found_special, periods
    logical :: done
    points = 0; multipliers = 0; special = 0; found = 0; found_special = 0; done = .false.
    periods = int(k)
    options = to_continuation(settings)
    options%max_points = max_points
    call model_from_arrays(rpar, int(ipar), model, code, message)
    if (code == 0) call periodic_switch(model, int(which), int(kind), y_special, &
                                        lambda_special, int(k), &
                                        lambda_min, lambda_max, options, &
                                        to_ode_options(integration), to_method(integration), &
                                        points, multipliers, found, special, found_special, &
                                        done, periods, code, message)
    n_points = found
    n_special = found_special
    complete = merge(1, 0, done)
    k_new = periods
    status = code
  end subroutine switch_branch

  !> Largest Lyapunov exponent (per unit tau) from y0, with its running estimates history(n_hist);
  !> settings in the lyapunov layout.
  subroutine lyapunov_exponent(rpar, ipar, y0, settings, integration, n_hist, exponent, history, &
                               status, message)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_layouts, only: INTEGRATION_SIZE, LYAPUNOV_SIZE, to_ode_options, to_method, &
                                to_lyapunov
    use sloshdyn_periodic_response, only: core => lyapunov_exponent, lyapunov_options, &
                                          check_lyapunov
    real(c_double), intent(in) :: rpar(n_real_params), y0(4), settings(LYAPUNOV_SIZE), &
                                  integration(INTEGRATION_SIZE)
    integer(c_int), intent(in) :: ipar(n_int_params), n_hist
    real(c_double), intent(out) :: exponent, history(n_hist)
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
    type(model_t) :: model
    type(lyapunov_options) :: options
    integer :: code
    exponent = 0; history = 0
    options = to_lyapunov(settings)
    call model_from_arrays(rpar, int(ipar), model, code, message)
    call check_lyapunov(options, code, message)
    if (code == 0) call core(model, y0, options%transient_periods, options%n_periods, &
                             options%renormalise_every, to_ode_options(integration), &
                             to_method(integration), exponent, history, code, message, &
                             options%average)
    status = code
  end subroutine lyapunov_exponent
end module sloshdyn_bridge_periodic
