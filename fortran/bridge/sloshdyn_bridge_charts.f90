!> The f2py bridge of charts.py: stability charts of the slow flows.
!> The bridge's contract (c_double/c_int arrays in named layouts, status and message,
!> threads and the GIL) is written once, in sloshdyn_bridge_model.f90.
module sloshdyn_bridge_charts
  use, intrinsic :: iso_c_binding, only: c_double, c_int
  implicit none

contains

  !> A stability chart of the model's slow flow (sloshdyn_stability_chart) as its four tables,
  !> each with room for max_* columns; the one-parameter runs with the settings of response
  !> (the 'response' layout) and the n_scan of settings; sizes = the columns used, in the
  !> 'chart_sizes' layout (curve points, codimension-2 points, curves, cells; if a table is too
  !> small: status SD_CAPACITY, sizes = those needed). complete = 0 if a curve stopped early;
  !> notes = a line per such curve.
  subroutine stability_chart(rpar, ipar, settings, chart_range, response, max_points, &
                             max_codim2, max_curves, n_cells, curves, codim2, ends, grid, &
                             sizes, complete, notes, status, message)
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_tables, only: CHART_CURVE_ROWS, CHART_CODIM2_ROWS, CHART_END_ROWS, &
                               CHART_GRID_ROWS
    use sloshdyn_layouts, only: CHART_SIZE, CHART_RANGE_SIZE, CHART_SIZES_SIZE, RESPONSE_SIZE, &
                                to_chart
    use sloshdyn_status, only: SD_CAPACITY
    use sloshdyn_text, only: num2str
    use sloshdyn_stability_chart, only: chart_result, core => stability_chart, chart_tables, &
                                        chart_table_sizes
    real(c_double), intent(in) :: rpar(n_real_params), settings(CHART_SIZE), &
                                  chart_range(CHART_RANGE_SIZE), response(RESPONSE_SIZE)
    integer(c_int), intent(in) :: ipar(n_int_params), max_points, max_codim2, max_curves, n_cells
    real(c_double), intent(out) :: curves(CHART_CURVE_ROWS, max_points), &
                                   codim2(CHART_CODIM2_ROWS, max_codim2), &
                                   ends(CHART_END_ROWS, max_curves), grid(CHART_GRID_ROWS, n_cells)
    integer(c_int), intent(out) :: sizes(CHART_SIZES_SIZE), complete, status
    character(len=4096), intent(out) :: notes
    character(len=512), intent(out) :: message
    type(model_t) :: model
    type(chart_result) :: chart
    integer :: info, used(4), c
    curves = 0; codim2 = 0; ends = 0; grid = 0; sizes = 0; complete = 0
    notes = ''
    call model_from_arrays(rpar, int(ipar), model, info, message)
    if (info == 0) call core(model, to_chart(settings, chart_range, response), chart, info, message)
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

  !> The two-parameter curve in (rho, A) of the full model's orbits (period k T) through a
  !> special point of a branch continued in rho (which = 1) or A (2): special = [kind, lambda,
  !> y0(1:4), max|x1|] (a fold, period doubling or Neimark-Sacker point;
  !> sloshdyn_orbit_chart's orbit_curve_from_special), inside the box p_min..p_max with at most
  !> max_points points; the tables as stability_chart's (one curve) and the curve's message
  !> (why it stopped early: it is kept up to there; status only when it has no point).
  subroutine orbit_curve(rpar, ipar, which, special, k, p_min, p_max, max_points, max_codim2, &
                         curves, codim2, ends, sizes, note, status, message)
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_tables, only: CHART_CURVE_ROWS, CHART_CODIM2_ROWS, CHART_END_ROWS
    use sloshdyn_layouts, only: CHART_SIZES_SIZE
    use sloshdyn_status, only: SD_CAPACITY
    use sloshdyn_text, only: num2str
    use sloshdyn_excitation, only: PARAMETER_RHO, PARAMETER_A
    use sloshdyn_stability_chart, only: chart_result, chart_tables, chart_table_sizes, &
                                        special_point_chart
    real(c_double), intent(in) :: rpar(n_real_params), special(7), p_min(2), p_max(2)
    integer(c_int), intent(in) :: ipar(n_int_params), which, k, max_points, max_codim2
    real(c_double), intent(out) :: curves(CHART_CURVE_ROWS, max_points), &
                                   codim2(CHART_CODIM2_ROWS, max_codim2), ends(CHART_END_ROWS, 1)
    integer(c_int), intent(out) :: sizes(CHART_SIZES_SIZE), status
    character(len=512), intent(out) :: note, message
    type(model_t) :: model
    type(chart_result) :: chart
    real(c_double) :: no_grid(8, 0)
    integer :: info, used(4)
    curves = 0; codim2 = 0; ends = 0; sizes = 0
    note = ''
    call model_from_arrays(rpar, int(ipar), model, info, message)
    status = info
    if (info /= 0) return
    call special_point_chart(model, merge(PARAMETER_RHO, PARAMETER_A, which == 1), special, k, &
                             p_min, p_max, max_points, chart, note, info, message)
    if (info /= 0) then
      status = info
      return
    end if
    call chart_table_sizes(chart, used(1), used(2), used(3), used(4))
    sizes = used
    if (used(1) > max_points .or. used(2) > max_codim2) then
      info = SD_CAPACITY
      message = 'the curve has '//num2str(used(1))//' points and '//num2str(used(2))// &
                ' codimension-2 points'
    else if (used(1) > 0) then
      call chart_tables(chart, curves(:, 1:used(1)), codim2(:, 1:used(2)), ends, no_grid)
    end if
    status = info
  end subroutine orbit_curve

  !> The slow flow (3:1 internal resonance: resonance = 1, n = 4; none: 0, n = 2) at the model's
  !> rho and A: f(x) and its Jacobian (sloshdyn_slowflow_chart; x = Re B1, Im B1, Re B2, Im B2).
  subroutine slow_flow_field(rpar, ipar, resonance, n, x, f, jacobian, status, message)
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_slowflow_chart, only: field_t => slow_flow_field, make_slow_flow_field, &
                                       CHART_RHO, CHART_A
    use sloshdyn_status, only: SD_BAD_INPUT
    use sloshdyn_text, only: num2str
    real(c_double), intent(in) :: rpar(n_real_params), x(n)
    integer(c_int), intent(in) :: ipar(n_int_params), resonance, n
    real(c_double), intent(out) :: f(n), jacobian(n, n)
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
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
end module sloshdyn_bridge_charts
