!> The f2py bridge of research.py: the Lyapunov spectrum of the full equations and the
!> continuation of the slow flow's limit cycles (the beats).
!> The bridge's contract (c_double/c_int arrays in named layouts, status and message,
!> threads and the GIL) is written once, in sloshdyn_bridge_model.f90.
module sloshdyn_bridge_research
  use, intrinsic :: iso_c_binding, only: c_double, c_int
  implicit none

contains

  !> All n Lyapunov exponents per unit tau from y0 (QR method) in decreasing order, their
  !> running estimates history(n, n_hist) after each renormalisation block and the Kaplan-Yorke
  !> dimension; settings in the lyapunov layout. n = 4: the planar model; n = 8: the spatial
  !> one, its ground motion set by spatial = [azimuth, ellipticity] (layout 'spatial').
  subroutine lyapunov_spectrum(rpar, ipar, spatial, n, y0, settings, integration, n_hist, &
                               exponents, history, dimension_ky, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_spatial, only: spatial_model_t, spatial_model
    use sloshdyn_tank_lyapunov, only: tank_lyapunov_spectrum, spatial_lyapunov_spectrum
    use sloshdyn_layouts, only: INTEGRATION_SIZE, LYAPUNOV_SIZE, SPATIAL_SIZE, to_ode_options, &
                                to_method, to_lyapunov, field_index
    real(c_double), intent(in) :: rpar(n_real_params), spatial(SPATIAL_SIZE), y0(n), &
                                  settings(LYAPUNOV_SIZE), integration(INTEGRATION_SIZE)
    integer(c_int), intent(in) :: ipar(n_int_params), n, n_hist
    real(c_double), intent(out) :: exponents(n), history(n, n_hist), dimension_ky
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
    type(model_t) :: model
    type(spatial_model_t) :: spatial_tank
    integer :: code
    exponents = 0; history = 0; dimension_ky = 0
    call model_from_arrays(rpar, int(ipar), model, code, message)
    if (code /= 0) then
      status = code
      return
    end if
    if (n == 8) then
      call spatial_model(model, spatial(field_index('spatial', 'azimuth')), &
                         spatial(field_index('spatial', 'ellipticity')), spatial_tank, code, &
                         message)
      if (code == 0) call spatial_lyapunov_spectrum(spatial_tank, y0, to_lyapunov(settings), &
                                                    to_ode_options(integration), &
                                                    to_method(integration), exponents, &
                                                    history, dimension_ky, code, message)
    else
      call tank_lyapunov_spectrum(model, y0, to_lyapunov(settings), &
                                  to_ode_options(integration), to_method(integration), &
                                  exponents, history, dimension_ky, code, message)
    end if
    status = code
  end subroutine lyapunov_spectrum

  !> The branch of slow-flow limit cycles (the beats) through the cycle (x_cycle, period [tau])
  !> at the model's rho and A, in rho (which = 1) or A (2) over [lambda_min, lambda_max];
  !> settings in the continuation layout. points, multipliers and amplitudes: the columns of the
  !> table 'cycle_branch' in that order; special: 'cycle_special_points'; stop_reason:
  !> sloshdyn_continuation's.
  subroutine slow_flow_cycle_branch(rpar, ipar, which, x_cycle, period, lambda_min, lambda_max, &
                                    settings, integration, max_points, max_special, points, &
                                    multipliers, amplitudes, n_points, special, n_special, &
                                    stop_reason, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_continuation, only: continuation_options
    use sloshdyn_slowflow_cycles, only: core => slow_flow_cycle_branch
    use sloshdyn_tables, only: CYCLE_POINT_ROWS, CYCLE_MULTIPLIER_ROWS, CYCLE_AMPLITUDE_ROWS, &
                               CYCLE_SPECIAL_ROWS
    use sloshdyn_layouts, only: INTEGRATION_SIZE, CONTINUATION_SIZE, to_ode_options, &
                                to_method, to_continuation
    real(c_double), intent(in) :: rpar(n_real_params), x_cycle(4), period, lambda_min, &
                                  lambda_max, settings(CONTINUATION_SIZE), &
                                  integration(INTEGRATION_SIZE)
    integer(c_int), intent(in) :: ipar(n_int_params), which, max_points, max_special
    real(c_double), intent(out) :: points(CYCLE_POINT_ROWS, max_points), &
                                   multipliers(CYCLE_MULTIPLIER_ROWS, max_points), &
                                   amplitudes(CYCLE_AMPLITUDE_ROWS, max_points), &
                                   special(CYCLE_SPECIAL_ROWS, max_special)
    integer(c_int), intent(out) :: n_points, n_special, stop_reason, status
    character(len=512), intent(out) :: message
    type(model_t) :: model
    type(continuation_options) :: options
    integer :: code, found, found_special, reason
    points = 0; multipliers = 0; amplitudes = 0; special = 0
    found = 0; found_special = 0; reason = 0
    options = to_continuation(settings)
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

end module sloshdyn_bridge_research
