!> Stability charts of the slow flow in two parameters (sec 3.3; issue: the chart behind Fig
!> 11-12): the fold and Hopf curves of its steady states with their codimension-2 points
!> (sloshdyn_bifurcation on the field of sloshdyn_slowflow_chart), the number of stable steady
!> states in each cell of a grid, and, optionally, that number found again by brute force.
!>
!> How a chart is made, for parameters (p1, p2) in a box (p1 is rho or A, p2 any other of rho,
!> A, gamma, kappa; kappa re-expands the modal coefficients at each value):
!> 1. At n_levels values of p2 (the grid's rows, cell midpoints) the one-parameter frequency
!>    response in p1 (sloshdyn_response: Newton from a grid of starts at n_scan values of p1,
!>    then continuation of every branch found) gives the steady states, their stability and
!>    their folds and Hopf points.
!> 2. Every fold or Hopf point not yet on a computed curve (no crossing of that curve with its
!>    level within seed_tolerance in p1) starts a curve, traced both ways to the box.
!> 3. Each grid cell (n_columns values of p1 at cell midpoints, on every row) counts the stable
!>    and all steady states on the branches of its row; a cell is marked near a curve when a
!>    curve point lies within half a cell of it (there the count may change inside the cell).
!> 4. With brute_force_starts > 0, the slow flow is integrated (DOP853) at every cell from that
!>    many starting points spread like the Newton starts, and the distinct stable steady
!>    states it settles on are counted: an independent check of step 3.
!>
!> Tables (sloshdyn_tables): 'chart_curves' (a column per curve point), 'chart_codim2',
!> 'chart_ends' (a column per curve), 'chart_grid' (a column per cell).
module sloshdyn_stability_chart
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, SD_CAPACITY, check_real
  use sloshdyn_text, only: num2str
  use sloshdyn_cancel, only: check_cancel
  use sloshdyn_model, only: model_t, set_coefficients
  use sloshdyn_lapack, only: eigenvalues, solve_linear
  use sloshdyn_ode, only: ode_options, ode_stats
  use sloshdyn_integrator, only: integrate, METHOD_DOP853
  use sloshdyn_bifurcation, only: two_parameter_field, curve_options, bifurcation_curve, &
                                  fold_curve, hopf_curve, curve_crossings, check_curve_options, &
                                  CURVE_FOLD, CURVE_HOPF, CURVE_PERIOD_DOUBLING, &
                                  CURVE_NEIMARK_SACKER, CODIM2_BT, &
                                  CODIM2_CUSP, CODIM2_ZH, CODIM2_GH, CODIM2_R1, CODIM2_R2, &
                                  CODIM2_R3, CODIM2_R4, CODIM2_FOLD_NS, CODIM2_FLIP_NS, &
                                  CODIM2_GF, CODIM2_CH, FOLD_FLIP => CODIM2_FOLD_FLIP
  use sloshdyn_excitation, only: PARAMETER_RHO
  use sloshdyn_simulation, only: steady_options
  use sloshdyn_periodic_response, only: periodic_response_from_rest
  use sloshdyn_orbit_chart, only: tank_orbit_map, orbit_chart_options, make_orbit_map, &
                                  orbit_curve_from_special
  use sloshdyn_slowflow_chart, only: slow_flow_field, make_slow_flow_field, &
                                     chart_parameter_name, CHART_RHO, CHART_A, CHART_GAMMA, &
                                     CHART_KAPPA
  use sloshdyn_slowflow_cycle, only: frozen_slow_flow
  use sloshdyn_response, only: response_options, frequency_response, check_response_options
  use sloshdyn_tables, only: POINT_ROWS, SPECIAL_ROWS, POINT_BRANCH, POINT_LAMBDA, POINT_STABLE, &
                             POINT_X, SPECIAL_KIND, SPECIAL_LAMBDA, SPECIAL_COLUMN, SPECIAL_FOLD, &
                             SPECIAL_HOPF, SPECIAL_PERIOD_DOUBLING, SPECIAL_NEIMARK_SACKER, &
                             CHART_FOLD, CHART_HOPF, CHART_PERIOD_DOUBLING, &
                             CHART_NEIMARK_SACKER, CODIM2_NONE, CODIM2_BOGDANOV_TAKENS, &
                             CODIM2_CUSP_POINT, CODIM2_FOLD_HOPF, CODIM2_GENERALISED_HOPF, &
                             CODIM2_RESONANCE_1_1, CODIM2_RESONANCE_1_2, CODIM2_RESONANCE_1_3, &
                             CODIM2_RESONANCE_1_4, CODIM2_FOLD_FLIP, CODIM2_FOLD_NEIMARK_SACKER, &
                             CODIM2_FLIP_NEIMARK_SACKER, CODIM2_GENERALISED_FLIP, CODIM2_CHENCINER
  implicit none
  private
  public :: chart_settings, stability_chart, check_chart_settings, chart_tables, &
            chart_table_sizes, chart_kind, chart_codim2_kind, special_point_chart
  public :: CHART_SLOW_FLOW_31, CHART_SLOW_FLOW_NONRESONANT, CHART_FULL

  !> Which model a chart is of: a slow flow, or the full equations' periodic orbits.
  integer, parameter :: CHART_SLOW_FLOW_31 = 1, CHART_SLOW_FLOW_NONRESONANT = 2, CHART_FULL = 3

  type :: chart_settings
    integer :: model = CHART_SLOW_FLOW_31
    !> (p1, p2): CHART_RHO, CHART_A, CHART_GAMMA, CHART_KAPPA (p1: rho or A)
    integer :: parameters(2) = [CHART_RHO, CHART_A]
    real(wp) :: p_min(2) = 0, p_max(2) = 0            !< the box (required)
    integer :: n_levels = 9                           !< grid rows (values of p2)
    integer :: n_columns = 41                         !< grid columns (values of p1)
    !> the one-parameter runs at each level; n_scan 41 finds the small isolas of Fig 12 that 5
    !> Newton scans miss
    type(response_options) :: response = response_options(n_scan=41)
    integer :: max_points = 3000                      !< points of one curve at most
    integer :: max_curves = 200
    integer :: brute_force_starts = 0                 !< starts per cell (0: no brute force)
    integer :: threads = 1                            !< share the runs and cells (same result)
  end type chart_settings

  !> A computed chart.
  type, public :: chart_result
    integer :: parameters(2) = [CHART_RHO, CHART_A]
    real(wp) :: base(4) = 0                 !< the model's rho, A, gamma, kappa (non-chart values)
    integer :: n_curves = 0
    logical :: complete = .true.            !< every curve traced to its ends
    type(bifurcation_curve), allocatable :: curves(:)
    !> (p1, p2, n_stable, n_steady, near a curve (1/0), brute-force count (-1: not done)) per
    !> cell
    real(wp), allocatable :: cells(:, :)
  end type chart_result

  !> Capacity of one one-parameter run (points, special points); a seed is (kind, p1, state).
  integer, parameter :: max_run_points = 20000, max_run_special = 500, seed_rows = 6

  !> A seed is on a computed curve if the curve crosses its level this close (relative to the
  !> p1 interval).
  real(wp), parameter :: seed_tolerance = 1.0e-6_wp

contains

  !> The rules of the settings (the box, the grid, the curve and response settings).
  pure subroutine check_chart_settings(settings, status, message)
    type(chart_settings), intent(in) :: settings
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    character(len=:), allocatable :: name
    character :: axis
    integer :: k
    if (status /= SD_OK) return
    if (all(settings%model /= [CHART_SLOW_FLOW_31, CHART_SLOW_FLOW_NONRESONANT, CHART_FULL])) then
      status = SD_BAD_INPUT
      message = 'model = '//num2str(settings%model)//' is not a chart model'
    else if (settings%model == CHART_FULL .and. any(settings%parameters /= [CHART_RHO, CHART_A])) &
      then
      status = SD_BAD_INPUT
      message = "x = '"//chart_parameter_name(settings%parameters(1))//"', y = '"// &
                chart_parameter_name(settings%parameters(2))//"': the full model's chart is "// &
                'in x = rho and y = A'
    else if (settings%model == CHART_FULL .and. settings%brute_force_starts /= 0) then
      status = SD_BAD_INPUT
      message = 'brute_force_starts = '//num2str(settings%brute_force_starts)//': brute force '// &
                'integrates the slow flow; for the full model it must be 0 (a study maps it)'
    else if (all(settings%parameters(1) /= [CHART_RHO, CHART_A])) then
      status = SD_BAD_INPUT
      message = "x = '"//chart_parameter_name(settings%parameters(1))//"' is out of range: the "// &
                'x axis must be rho or A (the one-parameter runs vary it)'
    else if (all(settings%parameters(2) /= [CHART_RHO, CHART_A, CHART_GAMMA, CHART_KAPPA]) .or. &
             settings%parameters(1) == settings%parameters(2)) then
      status = SD_BAD_INPUT
      message = "y = '"//chart_parameter_name(settings%parameters(2))//"' is out of range: the "// &
                'y axis must be another of rho, A, gamma, kappa than x'
    end if
    do k = 1, 2
      if (status /= SD_OK) return
      axis = merge('x', 'y', k == 1)
      name = chart_parameter_name(settings%parameters(k))
      call check_real(axis//'_min', settings%p_min(k), 0.0_wp, huge(1.0_wp), &
                      settings%parameters(k) == CHART_RHO, .true., 'the '//axis//' axis ('// &
                      name//') must start at '//trim(merge('> 0 ', '>= 0', &
                      settings%parameters(k) == CHART_RHO)), status, message)
      call check_real(axis//'_max', settings%p_max(k), settings%p_min(k), huge(1.0_wp), .true., &
                      .true., 'the '//axis//' axis ('//name//') must end above '//axis// &
                      '_min = '//num2str(settings%p_min(k)), status, message)
    end do
    call check_count('n_levels', settings%n_levels, 1, 1000, status, message)
    call check_count('n_columns', settings%n_columns, 1, 10000, status, message)
    call check_count('max_points', settings%max_points, 3, 10000000, status, message)
    call check_count('max_curves', settings%max_curves, 1, 100000, status, message)
    call check_count('brute_force_starts', settings%brute_force_starts, 0, 100000, status, &
                     message)
    call check_count('threads', settings%threads, 1, 1024, status, message)
    if (status == SD_OK) call check_response_options(settings%response, &
                                                     settings%parameters(1), &
                                                     settings%p_min(1), settings%p_max(1), &
                                                     status, message)
  end subroutine check_chart_settings

  pure subroutine check_count(name, value, lowest, highest, status, message)
    character(len=*), intent(in) :: name
    integer, intent(in) :: value, lowest, highest
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    if (status /= SD_OK .or. (value >= lowest .and. value <= highest)) return
    status = SD_BAD_INPUT
    message = name//' = '//num2str(value)//' is out of range: it must lie in ['// &
              num2str(lowest)//', '//num2str(highest)//']'
  end subroutine check_count

  !> The chart of the model's slow flow (the model's values of the non-chart parameters). A
  !> curve that cannot be continued to its ends is kept up to where it stopped, with its status
  !> and reason (chart%complete is then false); status is nonzero only when the chart itself
  !> cannot be made (bad settings, a one-parameter run that fails, too many curves).
  subroutine stability_chart(model, settings, chart, status, message)
    type(model_t), intent(in) :: model
    type(chart_settings), intent(in) :: settings
    type(chart_result), intent(out) :: chart
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(slow_flow_field) :: field
    type(tank_orbit_map) :: orbit_map
    type(orbit_chart_options) :: orbits
    type(curve_options) :: options
    real(wp), allocatable :: levels(:), columns(:), seeds(:, :, :)
    integer, allocatable :: n_seeds(:), level_status(:)
    character(len=message_len), allocatable :: level_message(:)
    real(wp) :: start_p(2)
    integer :: l, k, curve_status, run_status, one_status
    character(len=message_len) :: curve_message, run_message, one_message

    status = SD_OK
    message = ''
    call check_chart_settings(settings, status, message)
    if (status /= SD_OK) return
    options = curve_settings(settings)
    if (settings%model == CHART_FULL) then
      orbits%curve = options
      orbits%curve%continuation%ds_max = 1   ! the orbits' curves take longer steps (their scales)
      call make_orbit_map(model, orbits, orbit_map, status, message)
    else
      call make_slow_flow_field(model, settings%model == CHART_SLOW_FLOW_31, &
                                settings%parameters, field, status, message)
      if (status == SD_OK) call check_curve_options(options, status, message)
    end if
    if (status /= SD_OK) return
    levels = cell_midpoints(settings%p_min(2), settings%p_max(2), settings%n_levels)
    columns = cell_midpoints(settings%p_min(1), settings%p_max(1), settings%n_columns)
    chart%parameters = settings%parameters
    chart%base = [model%excitation%rho, model%excitation%A, model%gamma, model%kappa]
    allocate (chart%curves(settings%max_curves))
    allocate (chart%cells(6, settings%n_columns*settings%n_levels))

    ! the one-parameter runs are independent: threads share them out; the curves are then
    ! seeded in level order, so the chart does not depend on the number of threads
    allocate (seeds(seed_rows, max_run_special, size(levels)), n_seeds(size(levels)), &
              level_status(size(levels)), level_message(size(levels)))
    !$omp parallel do num_threads(settings%threads) schedule(dynamic, 1) &
    !$omp private(one_status, one_message)
    do l = 1, size(levels)
      ! a thread's own status (the continuation writes it at every step): neighbouring
      ! entries of level_status share a cache line, which two threads would pass to and fro
      call run_level(l, one_status, one_message)
      level_status(l) = one_status
      level_message(l) = one_message
    end do
    !$omp end parallel do
    do l = 1, size(levels)
      if (level_status(l) /= SD_OK) then
        status = level_status(l)
        message = 'the one-parameter run at '//level_text(settings, levels(l))//': '// &
                  trim(level_message(l))
        return
      end if
    end do
    do l = 1, size(levels)
      do k = 1, n_seeds(l)
        associate (seed => seeds(:, k, l))
          start_p = [seed(2), levels(l)]
          if (settings%model == CHART_FULL) then
            if (on_a_curve(orbit_map, chart, curve_kind_of(nint(seed(1))), start_p, options, &
                           seed_tolerance*(settings%p_max(1) - settings%p_min(1)))) cycle
          else
            if (on_a_curve(field, chart, curve_kind_of(nint(seed(1))), start_p, options, &
                           seed_tolerance*(settings%p_max(1) - settings%p_min(1)))) cycle
          end if
          if (chart%n_curves == size(chart%curves)) then
            status = SD_CAPACITY
            message = 'more than max_curves = '//num2str(size(chart%curves))//' curves'
            return
          end if
          chart%n_curves = chart%n_curves + 1
          if (settings%model == CHART_FULL) then
            call orbit_curve_from_special(level_model(l), PARAMETER_RHO, seed, orbits, &
                                          chart%curves(chart%n_curves), curve_status, &
                                          curve_message)
          else if (nint(seed(1)) == SPECIAL_FOLD) then
            call fold_curve(field, seed(3:2 + field%dimension()), start_p, options, &
                            chart%curves(chart%n_curves), curve_status, curve_message)
          else
            call hopf_curve(field, seed(3:2 + field%dimension()), start_p, options, &
                            chart%curves(chart%n_curves), curve_status, curve_message)
          end if
        end associate
        ! an incomplete curve keeps its status, reason and last point (chart%complete tells)
        if (curve_status /= SD_OK) chart%complete = .false.
      end do
    end do
    call mark_near_curves(chart, settings, status, message)
    if (status /= SD_OK) return
    if (settings%brute_force_starts > 0) call brute_force_counts(field, settings, chart%cells, &
                                                                 run_status, run_message)
    if (settings%brute_force_starts > 0 .and. run_status /= SD_OK .and. status == SD_OK) then
      status = run_status
      message = 'brute force: '//trim(run_message)
    end if

  contains

    !> The run at level l: its cells' counts, and its folds and Hopf points as seeds (kind,
    !> p1, state).
    subroutine run_level(l, status_at_level, message_at_level)
      integer, intent(in) :: l
      integer, intent(out) :: status_at_level
      character(len=message_len), intent(out) :: message_at_level
      real(wp), allocatable :: table(:, :), special(:, :), multipliers(:, :)
      integer :: n_points, n_special, k, column
      logical :: complete
      n_seeds(l) = 0
      seeds(:, :, l) = 0
      status_at_level = SD_OK
      message_at_level = ''
      call check_cancel(status_at_level, message_at_level)   ! the levels left after a request
      if (status_at_level /= SD_OK) return
      associate (row => chart%cells(:, (l - 1)*size(columns) + 1:l*size(columns)))
        if (settings%model == CHART_FULL) then
          ! the branch of orbits continued from the steady state reached from rest
          allocate (table(7, max_run_points), multipliers(8, max_run_points), &
                    special(7, max_run_special))
          call periodic_response_from_rest(level_model(l), PARAMETER_RHO, [0.0_wp, 0.0_wp, &
                                           0.0_wp, 0.0_wp], settings%p_min(1), &
                                           settings%p_max(1), steady_options(), &
                                           settings%response%continuation, orbits%integration, &
                                           orbits%method, table, multipliers, n_points, special, &
                                           n_special, complete, status_at_level, &
                                           message_at_level)
          if (status_at_level /= SD_OK) return
          call count_cells(table(1, 1:n_points), table(7, 1:n_points), &
                           [(1, k = 1, n_points)], columns, row)
          do k = 1, n_special
            if (all(nint(special(1, k)) /= [SPECIAL_FOLD, SPECIAL_PERIOD_DOUBLING, &
                                             SPECIAL_NEIMARK_SACKER])) cycle
            n_seeds(l) = n_seeds(l) + 1
            seeds(:, n_seeds(l), l) = special(1:seed_rows, k)
          end do
        else
          allocate (table(POINT_ROWS, max_run_points), special(SPECIAL_ROWS, max_run_special))
          call frequency_response(level_model(l), settings%model == CHART_SLOW_FLOW_31, &
                                  settings%parameters(1), settings%p_min(1), settings%p_max(1), &
                                  settings%response, table, n_points, special, n_special, &
                                  complete, status_at_level, message_at_level)
          if (status_at_level /= SD_OK) return
          call count_cells(table(POINT_LAMBDA, 1:n_points), table(POINT_STABLE, 1:n_points), &
                           nint(table(POINT_BRANCH, 1:n_points)), columns, row)
          do k = 1, n_special
            if (all(nint(special(SPECIAL_KIND, k)) /= [SPECIAL_FOLD, SPECIAL_HOPF])) cycle
            n_seeds(l) = n_seeds(l) + 1
            column = nint(special(SPECIAL_COLUMN, k))
            seeds(1:2, n_seeds(l), l) = [special(SPECIAL_KIND, k), special(SPECIAL_LAMBDA, k)]
            seeds(3:2 + field%dimension(), n_seeds(l), l) = &
              table(POINT_X:POINT_X + field%dimension() - 1, column)
          end do
        end if
        row(1, :) = columns
        row(2, :) = levels(l)
      end associate
    end subroutine run_level

    !> The model at level l.
    pure function level_model(l) result(at_level)
      integer, intent(in) :: l
      type(model_t) :: at_level
      at_level = model
      call set_chart_parameter(at_level, settings%parameters(2), levels(l))
    end function level_model
  end subroutine stability_chart

  !> Curve settings from the chart's: the box, and scales from its size and the response's.
  pure function curve_settings(settings) result(options)
    type(chart_settings), intent(in) :: settings
    type(curve_options) :: options
    options%p_min = settings%p_min
    options%p_max = settings%p_max
    options%p_scale = (settings%p_max - settings%p_min)/40
    options%x_scale = 0.05_wp
    options%max_points = settings%max_points
    options%continuation%ds = 0.05_wp
    options%continuation%ds_max = 0.2_wp
    options%continuation%ds_min = 1.0e-9_wp
  end function curve_settings

  pure function cell_midpoints(low, high, n) result(points)
    real(wp), intent(in) :: low, high
    integer, intent(in) :: n
    real(wp) :: points(n)
    integer :: i
    points = [(low + (high - low)*(i - 0.5_wp)/n, i = 1, n)]
  end function cell_midpoints

  pure subroutine set_chart_parameter(model, code, value)
    type(model_t), intent(inout) :: model
    integer, intent(in) :: code
    real(wp), intent(in) :: value
    select case (code)
    case (CHART_RHO)
      model%excitation%rho = value
    case (CHART_A)
      model%excitation%A = value
    case (CHART_GAMMA)
      model%gamma = value
    case (CHART_KAPPA)
      model%kappa = value
    end select
    call set_coefficients(model)   ! gamma and kappa enter eq (11)
  end subroutine set_chart_parameter

  pure function level_text(settings, level) result(text)
    type(chart_settings), intent(in) :: settings
    real(wp), intent(in) :: level
    character(len=:), allocatable :: text
    text = chart_parameter_name(settings%parameters(2))//' = '//num2str(level)
  end function level_text

  !> Is a point of a curve of this kind at p on a computed curve of that kind (a crossing with
  !> p2 = p(2) within tolerance of p(1))?
  logical function on_a_curve(field, chart, kind, p, options, tolerance) result(found)
    class(two_parameter_field), intent(in) :: field
    type(chart_result), intent(in) :: chart
    integer, intent(in) :: kind
    real(wp), intent(in) :: p(2), tolerance
    type(curve_options), intent(in) :: options
    real(wp) :: x(4, 100), crossing(2, 100)
    integer :: c, n_found, status
    character(len=message_len) :: message
    found = .false.
    do c = 1, chart%n_curves
      if (chart%curves(c)%kind /= kind) cycle
      call curve_crossings(field, chart%curves(c), 2, p(2), options, &
                           x(1:chart%curves(c)%n, :), crossing, n_found, status, message)
      if (n_found > 0) found = any(abs(crossing(1, 1:n_found) - p(1)) <= tolerance)
      if (found) return
    end do
  end function on_a_curve

  !> The stable and all steady states of a row from its branch points (lambda, stable (1/0),
  !> branch id): the segments between consecutive points of one branch that span each column
  !> value; cells(3:5, :) = n_stable, n_steady, 0 (near a curve: set later; a segment whose
  !> ends differ in stability makes the count uncertain: 1 there), cells(6, :) = -1 (no brute
  !> force yet).
  pure subroutine count_cells(lambda, stable, branch, columns, cells)
    real(wp), intent(in) :: lambda(:), stable(:), columns(:)
    integer, intent(in) :: branch(:)
    real(wp), intent(out) :: cells(:, :)
    integer :: i, j
    real(wp) :: a, b
    cells = 0
    cells(6, :) = -1
    do j = 1, size(lambda) - 1
      if (branch(j) /= branch(j + 1)) cycle
      a = min(lambda(j), lambda(j + 1))
      b = max(lambda(j), lambda(j + 1))
      do i = 1, size(columns)
        if (columns(i) < a .or. columns(i) >= b) cycle
        cells(4, i) = cells(4, i) + 1
        if (stable(j) > 0 .and. stable(j + 1) > 0) cells(3, i) = cells(3, i) + 1
        if ((stable(j) > 0) .neqv. (stable(j + 1) > 0)) cells(5, i) = 1
      end do
    end do
  end subroutine count_cells

  !> Mark the cells within half a cell of a curve point (in both directions); a cancellation
  !> request (sloshdyn_cancel) stops it at the next cell: SD_CANCELLED.
  subroutine mark_near_curves(chart, settings, status, message)
    type(chart_result), intent(inout) :: chart
    type(chart_settings), intent(in) :: settings
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    real(wp) :: half(2)
    integer :: c, j, i
    half = (settings%p_max - settings%p_min)/[settings%n_columns, settings%n_levels]/2
    do i = 1, size(chart%cells, 2)
      call check_cancel(status, message)
      if (status /= SD_OK) return
      do c = 1, chart%n_curves
        do j = 1, chart%curves(c)%n_points
          if (abs(chart%curves(c)%p(1, j) - chart%cells(1, i)) <= half(1) .and. &
              abs(chart%curves(c)%p(2, j) - chart%cells(2, i)) <= half(2)) chart%cells(5, i) = 1
        end do
      end do
    end do
  end subroutine mark_near_curves

  !> At each cell: integrate the slow flow from brute_force_starts points (|B| log-spaced
  !> between the response's amplitude_min and amplitude_max, phases spread) for long enough to
  !> settle, keep the end states that are steady (|f| small) and stable, and count the distinct
  !> ones: cells(6, :).
  subroutine brute_force_counts(field, settings, cells, status, message)
    type(slow_flow_field), intent(in) :: field
    type(chart_settings), intent(in) :: settings
    real(wp), intent(inout) :: cells(:, :)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    integer :: i, cell_status(size(cells, 2)), one_status
    character(len=message_len) :: cell_message(size(cells, 2)), one_message
    real(wp) :: n_attractors
    status = SD_OK
    message = ''
    !$omp parallel do num_threads(settings%threads) schedule(dynamic, 1) &
    !$omp private(n_attractors, one_status, one_message)
    do i = 1, size(cells, 2)
      ! a thread's own status and count (as in stability_chart's levels)
      call attractors_at(field, settings, cells(1:2, i), n_attractors, one_status, one_message)
      cells(6, i) = n_attractors
      cell_status(i) = one_status
      cell_message(i) = one_message
    end do
    !$omp end parallel do
    do i = 1, size(cells, 2)
      if (cell_status(i) /= SD_OK) then
        status = cell_status(i)
        message = cell_message(i)
        return
      end if
    end do
  end subroutine brute_force_counts

  !> The number of distinct stable steady states the slow flow at p settles on: each start is
  !> integrated, chunk_times decay times of the trivial state at a time (settle_times at most),
  !> until Newton from its state converges within 1 % of it to a stable steady state (the flow
  !> was settling there); it counts once.
  subroutine attractors_at(field, settings, p, count, status, message)
    type(slow_flow_field), intent(in) :: field
    type(chart_settings), intent(in) :: settings
    real(wp), intent(in) :: p(2)
    real(wp), intent(out) :: count
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), parameter :: settle_times = 15, chunk_times = 2.5_wp
    !> sqrt(2), sqrt(3), sqrt(5), sqrt(7): the steps of the start sequence, one per coordinate
    real(wp), parameter :: irrational(4) = [1.4142135623730951_wp, 1.7320508075688772_wp, &
                                            2.2360679774997898_wp, 2.6457513110645907_wp]
    type(frozen_slow_flow) :: flow
    type(ode_options) :: ode
    type(ode_stats) :: stats
    integer :: n, s, k, n_found, chunk
    logical :: settled
    real(wp) :: y(field%dimension()), x(field%dimension()), f(field%dimension()), &
                fx(field%dimension(), field%dimension()), fp(field%dimension(), 2), &
                re(field%dimension()), im(field%dimension()), &
                found(field%dimension(), settings%brute_force_starts), &
                y_end(field%dimension(), 1), decay, radius, angle, scale
    logical :: converged
    n = field%dimension()
    flow%field = field
    flow%p = p
    ! loose: the end state only has to lie in the basin; Newton polishes it
    ode%rtol = 1.0e-6_wp
    ode%atol = 1.0e-9_wp
    call field%evaluate([(0.0_wp, k = 1, n)], p, f, fx, fp)
    call eigenvalues(fx, re, im, status, message)
    if (status /= SD_OK) return
    decay = max(minval(abs(re)), 1.0e-12_wp)
    n_found = 0
    do s = 1, settings%brute_force_starts
      ! start s: each |B_k| log-uniform in [amplitude_min, amplitude_max] and each phase
      ! uniform, by an additive recurrence (a Kronecker sequence: spread, without a grid)
      do k = 1, n, 2
        radius = settings%response%amplitude_max*modulo(s*irrational(k), 1.0_wp)
        angle = 2*pi*modulo(s*irrational(k + 1), 1.0_wp)
        y(k:k + 1) = radius*[cos(angle), sin(angle)]
      end do
      ! integrate a few decay times at a time until the state is within 1 % of a stable steady
      ! state (then Newton's) or settle_times have passed
      settled = .false.
      do chunk = 1, nint(settle_times/chunk_times)
        call integrate(METHOD_DOP853, flow, 0.0_wp, y, [min(chunk_times/decay, 1.0e8_wp)], &
                       y_end, ode, stats, status, message)
        if (status /= SD_OK) exit
        y = y_end(:, 1)
        call polish(y, x, converged)
        scale = max(maxval(abs(y)), settings%response%amplitude_min)
        if (.not. converged .or. maxval(abs(x - y)) > 0.01_wp*scale) cycle
        call field%evaluate(x, p, f, fx, fp)
        call eigenvalues(fx, re, im, status, message)
        if (status /= SD_OK) return
        settled = maxval(re) < 0
        if (settled) exit
      end do
      if (status /= SD_OK) then
        status = SD_OK          ! a start that runs away is no steady state
        cycle
      end if
      if (.not. settled) cycle
      if (any([(maxval(abs(found(:, k) - x)) <= 1.0e-6_wp*scale, k = 1, n_found)])) cycle
      n_found = n_found + 1
      found(:, n_found) = x
    end do
    count = n_found

  contains

    !> Newton from y: x with f(x, p) = 0 (converged) or the last iterate.
    subroutine polish(y, x, converged)
      real(wp), intent(in) :: y(:)
      real(wp), intent(out) :: x(:)
      logical, intent(out) :: converged
      real(wp) :: step(size(y)), g(size(y)), gx(size(y), size(y)), gp(size(y), 2)
      integer :: iteration, info
      character(len=message_len) :: text
      x = y
      converged = .false.
      do iteration = 1, 30
        call field%evaluate(x, p, g, gx, gp)
        step = -g
        call solve_linear(gx, step, info, text)
        if (info /= SD_OK) return
        x = x + step
        if (maxval(abs(step)) <= 1.0e-12_wp*max(maxval(abs(x)), 1.0e-8_wp)) then
          converged = .true.
          return
        end if
      end do
    end subroutine polish
  end subroutine attractors_at

  !> The chart of one curve in (rho, A): the full model's orbits (period k T) through a special
  !> point of a branch continued in `parameter` (PARAMETER_RHO or PARAMETER_A): special =
  !> [kind, lambda, y0(1:4), max|x1|] (a fold, period doubling or Neimark-Sacker point;
  !> sloshdyn_orbit_chart's orbit_curve_from_special), inside the box p_min..p_max (rho, A) with
  !> at most max_points points. A curve that stopped early is kept up to there (status SD_OK,
  !> chart%complete false, note why); status only when it has no point. The one place both
  !> front doors set such a curve up (bridge orbit_curve, the executable's periodic_response
  !> with &response curve_at).
  subroutine special_point_chart(model, parameter, special, k, p_min, p_max, max_points, chart, &
                                 note, status, message)
    type(model_t), intent(in) :: model
    integer, intent(in) :: parameter, k, max_points
    real(wp), intent(in) :: special(:), p_min(2), p_max(2)
    type(chart_result), intent(out) :: chart
    character(len=message_len), intent(out) :: note
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(orbit_chart_options) :: options
    options%curve%p_min = p_min
    options%curve%p_max = p_max
    options%curve%max_points = max_points
    options%curve%continuation%ds_max = 1   ! as the chart's curves of orbits
    options%periods = k
    chart%base = [model%excitation%rho, model%excitation%A, model%gamma, model%kappa]
    allocate (chart%curves(1), chart%cells(6, 0))
    chart%n_curves = 1
    call orbit_curve_from_special(model, parameter, special, options, chart%curves(1), status, &
                                  message)
    chart%complete = chart%curves(1)%complete
    note = chart%curves(1)%message
    if (status /= SD_OK .and. chart%curves(1)%n_points > 0) then
      note = message
      status = SD_OK
    end if
  end subroutine special_point_chart

  !> Columns the tables need: points of all curves, codimension-2 points, curves, cells.
  pure subroutine chart_table_sizes(chart, n_points, n_codim2, n_curves, n_cells)
    type(chart_result), intent(in) :: chart
    integer, intent(out) :: n_points, n_codim2, n_curves, n_cells
    n_curves = chart%n_curves
    n_points = sum(chart%curves(1:n_curves)%n_points)
    n_codim2 = sum(chart%curves(1:n_curves)%n_codim2)
    n_cells = size(chart%cells, 2)
  end subroutine chart_table_sizes

  !> The chart as tables (sizes from chart_table_sizes), each point with all of rho, A, gamma,
  !> kappa: 'chart_curves' (curve, kind, rho, A, gamma, kappa, x1..x4 (0 beyond the state's
  !> dimension), omega, l1, codimension-2 kind), 'chart_codim2' (kind, curve, rho, A, gamma,
  !> kappa, omega), 'chart_ends' (curve, kind, n_points, complete, first end, last end, status)
  !> and 'chart_grid' (rho, A, gamma, kappa, n_stable, n_steady, near a curve, brute-force count
  !> or -1).
  pure subroutine chart_tables(chart, curves, codim2, ends, grid)
    type(chart_result), intent(in) :: chart
    real(wp), intent(out) :: curves(:, :), codim2(:, :), ends(:, :), grid(:, :)
    integer :: c, j, row, k
    curves = 0
    codim2 = 0
    ends = 0
    row = 0
    k = 0
    do c = 1, chart%n_curves
      associate (curve => chart%curves(c))
        do j = 1, curve%n_points
          row = row + 1
          curves(1:6, row) = [real(c, wp), real(chart_kind(curve%kind), wp), &
                              chart_point(chart, curve%p(:, j))]
          curves(7:6 + curve%n, row) = curve%x(:, j)
          curves(11:13, row) = [curve%omega(j), curve%l1(j), &
                                real(chart_codim2_kind(curve%special(j)), wp)]
        end do
        do j = 1, curve%n_codim2
          k = k + 1
          codim2(:, k) = [real(chart_codim2_kind(curve%codim2(j)%kind), wp), real(c, wp), &
                          chart_point(chart, curve%codim2(j)%p), curve%codim2(j)%omega]
        end do
        ends(:, c) = [real(c, wp), real(chart_kind(curve%kind), wp), real(curve%n_points, wp), &
                      merge(1.0_wp, 0.0_wp, curve%complete), real(curve%end_reason, wp), &
                      real(curve%status, wp)]
      end associate
    end do
    do j = 1, size(chart%cells, 2)
      grid(:, j) = [chart_point(chart, chart%cells(1:2, j)), chart%cells(3:6, j)]
    end do
  end subroutine chart_tables

  !> (rho, A, gamma, kappa) of the chart point p = (p1, p2).
  pure function chart_point(chart, p) result(point)
    type(chart_result), intent(in) :: chart
    real(wp), intent(in) :: p(2)
    real(wp) :: point(4)
    point = chart%base
    point(chart%parameters) = p
  end function chart_point

  !> The tables' kind of a curve (CHART_*) and of a codimension-2 point (CODIM2_* of
  !> sloshdyn_tables) for sloshdyn_bifurcation's codes.
  pure integer function chart_kind(kind)
    integer, intent(in) :: kind
    select case (kind)
    case (CURVE_FOLD);            chart_kind = CHART_FOLD
    case (CURVE_HOPF);            chart_kind = CHART_HOPF
    case (CURVE_PERIOD_DOUBLING); chart_kind = CHART_PERIOD_DOUBLING
    case default;                 chart_kind = CHART_NEIMARK_SACKER
    end select
  end function chart_kind

  pure integer function chart_codim2_kind(kind)
    integer, intent(in) :: kind
    select case (kind)
    case (CODIM2_BT);        chart_codim2_kind = CODIM2_BOGDANOV_TAKENS
    case (CODIM2_CUSP);      chart_codim2_kind = CODIM2_CUSP_POINT
    case (CODIM2_ZH);        chart_codim2_kind = CODIM2_FOLD_HOPF
    case (CODIM2_GH);        chart_codim2_kind = CODIM2_GENERALISED_HOPF
    case (CODIM2_R1);        chart_codim2_kind = CODIM2_RESONANCE_1_1
    case (CODIM2_R2);        chart_codim2_kind = CODIM2_RESONANCE_1_2
    case (CODIM2_R3);        chart_codim2_kind = CODIM2_RESONANCE_1_3
    case (CODIM2_R4);        chart_codim2_kind = CODIM2_RESONANCE_1_4
    case (FOLD_FLIP);        chart_codim2_kind = CODIM2_FOLD_FLIP
    case (CODIM2_FOLD_NS);   chart_codim2_kind = CODIM2_FOLD_NEIMARK_SACKER
    case (CODIM2_FLIP_NS);   chart_codim2_kind = CODIM2_FLIP_NEIMARK_SACKER
    case (CODIM2_GF);        chart_codim2_kind = CODIM2_GENERALISED_FLIP
    case (CODIM2_CH);        chart_codim2_kind = CODIM2_CHENCINER
    case default;            chart_codim2_kind = CODIM2_NONE
    end select
  end function chart_codim2_kind

  !> The curve kind through a special point of a one-parameter run.
  pure integer function curve_kind_of(special_kind)
    integer, intent(in) :: special_kind
    select case (special_kind)
    case (SPECIAL_FOLD);            curve_kind_of = CURVE_FOLD
    case (SPECIAL_HOPF);            curve_kind_of = CURVE_HOPF
    case (SPECIAL_PERIOD_DOUBLING); curve_kind_of = CURVE_PERIOD_DOUBLING
    case default;                   curve_kind_of = CURVE_NEIMARK_SACKER
    end select
  end function curve_kind_of
end module sloshdyn_stability_chart
