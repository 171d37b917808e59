!> The f2py bridge of studies.py: the tasks of distributed studies.
!> The bridge's contract (c_double/c_int arrays in named layouts, status and message,
!> threads and the GIL) is written once, in sloshdyn_bridge_model.f90.
module sloshdyn_bridge_studies
  use, intrinsic :: iso_c_binding, only: c_double, c_int
  implicit none

contains

  !> Steady states at the points (rho(i), A(i)) of a study task: each from y0(:, i) (carry = 0)
  !> or, carry = 1, the first from y0(:, 1) and each next from the previous final state.
  !> summaries(SUMMARY_SIZE, n) in the 'summary' layout, y_end(4, n), orbit(ORBIT_ROWS,
  !> n) in the layout of
  !> sloshdyn_studies, impact(n) = 1 where max|x1| >= 1 (the wall is reached), point_status(n)
  !> and point_message(n) (each failed point's message, what its run alone says; '' where it
  !> succeeded, and after a carried path's failure); status and message of the first failing
  !> point. Independent points go to the ensemble block at a time (>= 1; the results do not
  !> depend on it).
  subroutine steady_path(rpar, ipar, n, rho, A, y0, carry, integration, steady, block, &
                         summaries, y_end, orbit, impact, point_status, point_message, status, &
                         message)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_studies, only: ORBIT_ROWS, core => steady_path, roof_impact
    use sloshdyn_tables, only: SUMMARY_SIZE
    use sloshdyn_layouts, only: INTEGRATION_SIZE, STEADY_SIZE, to_ode_options, to_method, &
                                to_steady
    real(c_double), intent(in) :: rpar(n_real_params), rho(n), A(n), y0(4, n), &
                                  integration(INTEGRATION_SIZE), steady(STEADY_SIZE)
    integer(c_int), intent(in) :: ipar(n_int_params), n, carry, block
    real(c_double), intent(out) :: summaries(SUMMARY_SIZE, n), y_end(4, n), orbit(ORBIT_ROWS, n)
    integer(c_int), intent(out) :: impact(n), point_status(n), status
    character(len=512), intent(out) :: point_message(n), message
    type(model_t) :: model
    integer :: info, statuses(n)
    summaries = 0; y_end = 0; orbit = 0; impact = 0; statuses = 0
    call model_from_arrays(rpar, int(ipar), model, info, message)
    if (info == 0) then
      call core(model, rho, A, y0, carry /= 0, to_ode_options(integration), &
                to_method(integration), to_steady(steady), summaries, y_end, orbit, statuses, &
                point_message, info, message, int(block))
    else
      statuses = info
      point_message = message
    end if
    impact = merge(1, 0, roof_impact(summaries(3, :)))
    point_status = statuses
    status = info
  end subroutine steady_path

  !> Steady states from the initial states y0(:, i) at the excitation of rpar, with the orbit
  !> each periodic one settled on (sloshdyn_studies: orbit(ORBIT_ROWS, n), orbit_points(4,
  !> MAX_ORBIT_PERIODS, n)), the points going to the ensemble block at a time (>= 1; the
  !> results do not depend on it); point_status and point_message as steady_path's.
  subroutine attractor_points(rpar, ipar, n, y0, integration, steady, block, summaries, y_end, &
                              orbit, orbit_points, point_status, point_message, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_simulation, only: MAX_ORBIT_PERIODS => max_period
    use sloshdyn_studies, only: ORBIT_ROWS, core => attractor_points
    use sloshdyn_tables, only: SUMMARY_SIZE
    use sloshdyn_layouts, only: INTEGRATION_SIZE, STEADY_SIZE, to_ode_options, to_method, &
                                to_steady
    real(c_double), intent(in) :: rpar(n_real_params), y0(4, n), integration(INTEGRATION_SIZE), &
                                  steady(STEADY_SIZE)
    integer(c_int), intent(in) :: ipar(n_int_params), n, block
    real(c_double), intent(out) :: summaries(SUMMARY_SIZE, n), y_end(4, n), orbit(ORBIT_ROWS, n), &
                                   orbit_points(4, MAX_ORBIT_PERIODS, n)
    integer(c_int), intent(out) :: point_status(n), status
    character(len=512), intent(out) :: point_message(n), message
    type(model_t) :: model
    integer :: info, statuses(n)
    summaries = 0; y_end = 0; orbit = 0; orbit_points = 0; statuses = 0
    call model_from_arrays(rpar, int(ipar), model, info, message)
    if (info == 0) then
      call core(model, y0, to_ode_options(integration), to_method(integration), &
                to_steady(steady), int(block), summaries, y_end, orbit, orbit_points, statuses, &
                point_message, info, message)
    else
      statuses = info
      point_message = message
    end if
    point_status = statuses
    status = info
  end subroutine attractor_points

  !> Attractors of a set of runs (sloshdyn_studies%label_attractors): label(n) from 1, 0 for
  !> failed runs; representative(1:n_attractors) the first run of each.
  subroutine label_attractors(n, motions, periods, orbit_points, tol, label, n_attractors, &
                              representative)
    !f2py threadsafe
    use sloshdyn_simulation, only: MAX_ORBIT_PERIODS => max_period
    use sloshdyn_studies, only: core => label_attractors
    integer(c_int), intent(in) :: n
    real(c_double), intent(in) :: motions(n), periods(n), orbit_points(4, MAX_ORBIT_PERIODS, n), tol
    integer(c_int), intent(out) :: label(n), n_attractors, representative(n)
    integer :: labels(n), found, first(n)
    call core(motions, periods, orbit_points, tol, labels, found, first)
    label = labels
    n_attractors = found
    representative = first
  end subroutine label_attractors
end module sloshdyn_bridge_studies
