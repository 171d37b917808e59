!> The executable's runs of the spatial model of issue 26 with &model or &tank planar = .false.
!> (a submodule of sloshdyn_driver, which declares their interfaces): the time history
!> (kind = 'simulate') and one periodic orbit by Newton shooting (kind = 'steady_state', a
!> swirling orbit when it leaves the plane), and the swirl band's boundary in (rho, A) (kind =
!> 'swirl' with &sweep). The seismic response in two components is in sloshdyn_driver_tank, the
!> swirl band in sloshdyn_driver.
submodule (sloshdyn_driver) sloshdyn_driver_spatial
  ! by use, not only from the parent: meson rebuilds a submodule when a module it uses changes,
  ! not when one its parent uses does (a stale object then calls the old interfaces)
  use sloshdyn_driver_common, only: begin_files, in_context, used_method, pad
  use sloshdyn_spatial, only: spatial_model_t, spatial_model
  use sloshdyn_excitation, only: excitation_t
  use sloshdyn_ground, only: ground_excitation
  use sloshdyn_simulation, only: spatial_time_history
  use sloshdyn_swirl, only: swirl_orbit
  use sloshdyn_swirling_branch, only: swirling_branch
  use sloshdyn_swirl_curve, only: swirl_boundary_curve, curve_settings
  use sloshdyn_periodic_response, only: newton_tol_default, max_iter_default
  use sloshdyn_tables, only: SPATIAL_HISTORY_ROWS, SWIRL_ORBIT_ROWS, SWIRL_BOUNDARY_ROWS, &
                             SWIRLING_BRANCH_ROWS, SWIRLING_SPECIAL_ROWS, SPECIAL_BRANCH_POINT, &
                             SPECIAL_PERIOD_DOUBLING, SWIRL_CURVE_ROWS, SWIRL_CURVE_FOLD_ROWS, &
                             special_kind_name
  implicit none

contains

  !> The time history of the spatial model from &simulation's y0 (8 states) at tau = 0 to t_end,
  !> n_out evenly spaced outputs: spatial_history.csv (the 8 states, the pendulum's tilt over
  !> theta0 and its azimuth) and simulation.csv.
  module subroutine run_simulate_spatial(config, files, status, message)
    type(run_config), intent(in) :: config
    type(result_files), intent(inout) :: files
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(spatial_model_t) :: model
    real(wp), allocatable :: tau(:), history(:, :)
    type(ode_stats) :: stats
    integer :: i

    call config_spatial_model(config, model, status, message)
    if (status /= SD_OK) return
    associate (sim => config%simulation)
      allocate (tau(sim%n_out), history(SPATIAL_HISTORY_ROWS + 1, sim%n_out))
      tau = [(sim%t_end*(i - 1)/(sim%n_out - 1), i = 1, sim%n_out)]
      history(1, :) = tau
      call spatial_time_history(model, 0.0_wp, sim%y0, tau, config%integration, config%method, &
                                history(2:, :), stats, status, message)
      call in_context('simulation of the spatial model', status, message)
      if (status /= SD_OK) return
      print '(/a)', 'Simulation of the spatial model ('//used_method(config)//', eq S7'// &
                    trim(merge('          ', ', a record', &
                               config%model%excitation%kind /= EXCITATION_RECORD))// &
                    ') from tau = 0 to '//num2str(sim%t_end)
    end associate
    print '(a)', '  steps accepted '//num2str(stats%n_accepted)//', rejected '// &
                 num2str(stats%n_rejected)//', right-hand sides '//num2str(stats%n_rhs)
    print '(a)', '  max|x1| = '//num2str(maxval(abs(history(2, :))))//', max|y1| = '// &
                 num2str(maxval(abs(history(6, :))))//', max tilt/theta0 = '// &
                 num2str(maxval(history(10, :)))//' at the output times'
    call begin_files(config, files, status, message)
    if (status == SD_OK) call files%write_table('spatial_history.csv', 'spatial_history', &
                                                history, status, message)
    if (status == SD_OK) call files%write_table('simulation.csv', 'simulation', &
                                                reshape(counts_array(stats), [COUNTS_SIZE, 1]), &
                                                status, message)
  end subroutine run_simulate_spatial

  !> A periodic orbit of the spatial model (period T, Newton shooting on the 8 states,
  !> sloshdyn_swirl's swirl_orbit) from &simulation's y0 after &steady's transient_periods
  !> (rounded to whole periods): swirl_orbit.csv.
  module subroutine run_swirl_orbit(config, files, status, message)
    type(run_config), intent(in) :: config
    type(result_files), intent(inout) :: files
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(spatial_model_t) :: model
    real(wp) :: row(SWIRL_ORBIT_ROWS), y_orbit(8), re(8), im(8), max_x1, amplitude, &
                angular_momentum
    integer :: iterations, transient

    call config_spatial_model(config, model, status, message)
    if (status /= SD_OK) return
    transient = nint(config%steady%transient_periods)
    call swirl_orbit(model, config%simulation%y0, 1, transient, config%integration, &
                     config%method, newton_tol_default, max_iter_default, y_orbit, re, im, &
                     iterations, max_x1, amplitude, angular_momentum, status, message)
    call in_context('periodic orbit of the spatial model', status, message)
    if (status /= SD_OK) return
    print '(/a)', 'Periodic orbit of the spatial model ('//used_method(config)//') at rho = '// &
                  num2str(config%model%excitation%rho)//', A = '// &
                  num2str(config%model%excitation%A)//', after '//num2str(transient)// &
                  ' forcing periods from y0: '//num2str(iterations)//' Newton iterations'
    print '(a)', '  max|x1| = '//num2str(max_x1)//', swirl amplitude max|y1| = '// &
                 num2str(amplitude)//', mean angular momentum '//num2str(angular_momentum)// &
                 ' ('//trim(swirl_direction(angular_momentum))//'); '// &
                 trim(merge('stable  ', 'unstable', maxval(hypot(re, im)) < 1))// &
                 ' (max |Floquet multiplier| = '//num2str(maxval(hypot(re, im)))//')'
    row = [y_orbit, max_x1, amplitude, angular_momentum, real(iterations, wp), re, im]
    call begin_files(config, files, status, message)
    if (status == SD_OK) call files%write_table('swirl_orbit.csv', 'swirl_orbit', &
                                                reshape(row, [SWIRL_ORBIT_ROWS, 1]), status, &
                                                message)
  end subroutine run_swirl_orbit

  !> The boundary of the swirl band in (rho, A) (kind = 'swirl' with &sweep parameter = 'A'):
  !> the band along rho over &response's range (as run_swirl) at each of &sweep's n_points
  !> values of A from start to stop, its edges with their A in swirl_boundary.csv (as Python's
  !> sloshdyn.spatial.swirl_boundary).
  module subroutine run_swirl_boundary(config, files, status, message)
    type(run_config), intent(in) :: config
    type(result_files), intent(inout) :: files
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(model_t) :: at_A
    real(wp) :: A
    real(wp), allocatable :: points(:, :), edges(:, :), rows(:, :)
    integer :: n_points, n_edges, i, j, n_rows
    logical :: complete

    associate (r => config%response, sw => config%sweep)
      allocate (rows(SWIRL_BOUNDARY_ROWS, max_swirl_edges*sw%n_points))
      print '(/a)', 'Swirl boundary: the swirl band along rho in ['//num2str(r%start)//', '// &
                    num2str(r%stop)//'] at '//num2str(sw%n_points)//' values of A in ['// &
                    num2str(sw%start)//', '//num2str(sw%stop)//'] (spatial model; '// &
                    used_method(config)//')'
      n_rows = 0
      do i = 1, sw%n_points
        A = sw%start + (sw%stop - sw%start)*(i - 1)/max(sw%n_points - 1, 1)
        at_A = config%model
        at_A%excitation%A = A
        call swirl_band(config, at_A, points, n_points, edges, n_edges, complete, status, &
                        message)
        if (status /= SD_OK) message = 'at A = '//num2str(A)//': '//trim(message)
        call in_context('swirl boundary', status, message)
        if (status /= SD_OK) return
        print '(a)', '  A = '//pad(num2str(A), 14)//num2str(n_edges)//' edge(s) at rho = '// &
                     join_values(edges(1, 1:n_edges))
        do j = 1, n_edges
          n_rows = n_rows + 1
          rows(:, n_rows) = [A, edges(:, j)]
        end do
      end do
    end associate
    call begin_files(config, files, status, message)
    if (status == SD_OK) call files%write_table('swirl_boundary.csv', 'swirl_boundary', &
                                                rows(:, 1:n_rows), status, message)
  end subroutine run_swirl_boundary

  !> With &response switch_at = j (kind = 'swirl'): the swirling orbits born at edge j of the
  !> swirl band (edges as run_swirl's; a branch_point edge), continued over &response's range
  !> (sloshdyn_swirling_branch, as Python's sloshdyn.spatial.swirling_branch):
  !> swirling_branch.csv and swirling_special_points.csv.
  module subroutine run_swirling(config, files, edges, n_edges, status, message)
    type(run_config), intent(in) :: config
    type(result_files), intent(inout) :: files
    real(wp), intent(in) :: edges(:, :)
    integer, intent(in) :: n_edges
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(model_t) :: at_edge
    real(wp), allocatable :: points(:, :), special(:, :)
    integer :: n_points, n_special, j, i
    logical :: complete

    associate (r => config%response)
      j = r%switch_at
      call edge_at(config, 'switch_at', j, edges, n_edges, [SPECIAL_BRANCH_POINT], &
                   'swirling orbits are born at a branch_point edge', at_edge, status, message)
      if (status /= SD_OK) return
      allocate (points(SWIRLING_BRANCH_ROWS, r%options%continuation%max_points), &
                special(SWIRLING_SPECIAL_ROWS, 4*max(r%options%continuation%max_points, 1)))
      call swirling_branch(at_edge, r%parameter, edges(2:5, j), 1, r%start, r%stop, &
                           r%options%continuation, config%integration, config%method, points, &
                           n_points, special, n_special, complete, status, message)
      call in_context('swirling branch at swirl edge '//num2str(j), status, message)
      if (status /= SD_OK) return
      print '(/a)', 'Swirling orbits born at swirl edge '//num2str(j)//' ('// &
                    num2str(edges(1, j))//'): '//num2str(n_points)//' orbits, '// &
                    num2str(count(points(13, 1:n_points) > 0))//' stable; special points:'
      if (n_special == 0) print '(a)', '  none'
      do i = 1, n_special
        print '(a)', '  '//pad(special_kind_name(nint(special(1, i))), 16)// &
                     pad(num2str(special(2, i)), 14)//'max|x1| = '//num2str(special(11, i))
      end do
    end associate
    call files%write_table('swirling_branch.csv', 'swirling_branch', points(:, 1:n_points), &
                           status, message)
    if (status == SD_OK) call files%write_table('swirling_special_points.csv', &
                                                'swirling_special_points', &
                                                special(:, 1:n_special), status, message)
  end subroutine run_swirling

  !> With &response curve_at = j (kind = 'swirl'): edge j of the swirl band (a branch_point or
  !> period_doubling edge) continued as a curve in (rho, A) (sloshdyn_swirl_curve, as Python's
  !> sloshdyn.spatial.swirl_boundary_curve with its default ds and tol and &response's
  !> max_points) in the box of &response's range times [curve_start, curve_stop] of the other
  !> parameter: swirl_boundary_curve.csv, swirl_curve_folds.csv and swirl_curve_degenerate.csv
  !> (the degenerate pitchforks or flips, where the edge's criticality c changes sign).
  module subroutine run_swirl_curve(config, files, edges, n_edges, status, message)
    type(run_config), intent(in) :: config
    type(result_files), intent(inout) :: files
    real(wp), intent(in) :: edges(:, :)
    integer, intent(in) :: n_edges
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(model_t) :: at_edge
    type(curve_settings) :: settings
    real(wp) :: rho_range(2), A_range(2), no_values(0), at(SWIRL_CURVE_ROWS, 1)
    real(wp), allocatable :: points(:, :), folds(:, :), degenerate(:, :)
    integer :: n_points, n_at, n_folds, n_degenerate, j, kind, i
    logical :: complete

    associate (r => config%response)
      j = r%curve_at
      call edge_at(config, 'curve_at', j, edges, n_edges, &
                   [SPECIAL_BRANCH_POINT, SPECIAL_PERIOD_DOUBLING], &
                   'the curve follows a branch_point or a period_doubling edge', at_edge, &
                   status, message)
      if (status /= SD_OK) return
      kind = nint(edges(8, j))
      if (r%parameter == PARAMETER_RHO) then
        rho_range = [r%start, r%stop]
        A_range = [r%curve_start, r%curve_stop]
      else
        rho_range = [r%curve_start, r%curve_stop]
        A_range = [r%start, r%stop]
      end if
      if (at_edge%excitation%A < A_range(1) .or. at_edge%excitation%A > A_range(2) .or. &
          at_edge%excitation%rho < rho_range(1) .or. at_edge%excitation%rho > rho_range(2)) then
        status = SD_BAD_INPUT
        message = '&response: curve_start, curve_stop = '//num2str(r%curve_start)//', '// &
                  num2str(r%curve_stop)//' must contain the edge''s '// &
                  trim(merge('A  ', 'rho', r%parameter == PARAMETER_RHO))//' = '// &
                  num2str(merge(at_edge%excitation%A, at_edge%excitation%rho, &
                                r%parameter == PARAMETER_RHO))
        return
      end if
      settings%max_points = r%options%continuation%max_points
      settings%newton_tol = newton_tol_default
      settings%max_iter = max_iter_default
      allocate (points(SWIRL_CURVE_ROWS, 2*settings%max_points - 1), &
                folds(SWIRL_CURVE_FOLD_ROWS, 2*settings%max_points), &
                degenerate(SWIRL_CURVE_ROWS, 2*settings%max_points))
      call swirl_boundary_curve(at_edge, kind, at_edge%excitation%rho, edges(2:5, j), 1, &
                                rho_range, A_range, no_values, settings, config%integration, &
                                config%method, points, n_points, at, n_at, folds, n_folds, &
                                degenerate, n_degenerate, complete, status, message)
      call in_context('swirl boundary curve through swirl edge '//num2str(j), status, message)
      if (status /= SD_OK) return
      print '(/a)', 'The swirl boundary through edge '//num2str(j)//' ('// &
                    special_kind_name(kind)//') in rho in ['//num2str(rho_range(1))//', '// &
                    num2str(rho_range(2))//'] x A in ['//num2str(A_range(1))//', '// &
                    num2str(A_range(2))//']: '//num2str(n_points)//' points; folds in A:'
      if (n_folds == 0) print '(a)', '  none'
      do i = 1, n_folds
        print '(a)', '  '//trim(merge('closing', 'opening', &
                                      folds(SWIRL_CURVE_FOLD_ROWS, i) > 0))//' at rho = '// &
                     pad(num2str(folds(1, i)), 14)//'A = '//num2str(folds(2, i))
      end do
      print '(a)', 'degenerate '//trim(merge('pitchforks', 'flips     ', &
                                             kind == SPECIAL_BRANCH_POINT))// &
                   ' (the onset of swirl turns between super- and subcritical):'
      if (n_degenerate == 0) print '(a)', '  none'
      do i = 1, n_degenerate
        print '(a)', '  at rho = '//pad(num2str(degenerate(1, i)), 14)//'A = '// &
                     num2str(degenerate(2, i))
      end do
    end associate
    call files%write_table('swirl_boundary_curve.csv', 'swirl_boundary_curve', &
                           points(:, 1:n_points), status, message)
    if (status == SD_OK) call files%write_table('swirl_curve_folds.csv', 'swirl_curve_folds', &
                                                folds(:, 1:n_folds), status, message)
    if (status == SD_OK) call files%write_table('swirl_curve_degenerate.csv', &
                                                'swirl_curve_degenerate', &
                                                degenerate(:, 1:n_degenerate), status, message)
  end subroutine run_swirl_curve

  !> The model at swirl edge j of the band (edges(:, 1:n_edges), layout 'swirl_edges'), chosen
  !> by &response's `key`: SD_BAD_INPUT unless the edge exists and its kind is one of `kinds`
  !> (`rule` says why).
  subroutine edge_at(config, key, j, edges, n_edges, kinds, rule, at_edge, status, message)
    type(run_config), intent(in) :: config
    character(len=*), intent(in) :: key, rule
    integer, intent(in) :: j, n_edges, kinds(:)
    real(wp), intent(in) :: edges(:, :)
    type(model_t), intent(out) :: at_edge
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    status = SD_BAD_INPUT
    if (j > n_edges) then
      message = '&response: '//key//' = '//num2str(j)//' is out of range: the swirl band has '// &
                num2str(n_edges)//' edge(s)'
      return
    end if
    if (all(kinds /= nint(edges(8, j)))) then
      message = '&response: '//key//' = '//num2str(j)//' is a '// &
                special_kind_name(nint(edges(8, j)))//' edge: '//rule
      return
    end if
    status = SD_OK
    message = ''
    at_edge = config%model
    if (config%response%parameter == PARAMETER_RHO) then
      at_edge%excitation%rho = edges(1, j)
    else
      at_edge%excitation%A = edges(1, j)
    end if
  end subroutine edge_at

  !> Values separated by commas.
  pure function join_values(values) result(text)
    real(wp), intent(in) :: values(:)
    character(len=:), allocatable :: text
    integer :: i
    text = ''
    do i = 1, size(values)
      text = text//trim(merge(', ', '  ', i > 1))//num2str(values(i))
    end do
  end function join_values

  !> The sense of rotation of an orbit with mean angular momentum l about the vertical (seen
  !> from above).
  pure function swirl_direction(l) result(name)
    real(wp), intent(in) :: l
    character(len=17) :: name
    if (l > 0) then
      name = 'counter-clockwise'
    else if (l < 0) then
      name = 'clockwise'
    else
      name = 'planar'
    end if
  end function swirl_direction

  !> The spatial model of config: its planar model, the second component (&excitation's or
  !> &ground_motion's azimuth and ellipticity, or record_y, which the reader put on the first
  !> record's time grid).
  subroutine config_spatial_model(config, model, status, message)
    type(run_config), intent(in) :: config
    type(spatial_model_t), intent(out) :: model
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(excitation_t) :: second
    if (config%has_ground_y) then
      call ground_excitation(config%ground_y, config%tank_props%omega, &
                             config%tank_props%rod_length, second, status, message)
      if (status == SD_OK) call spatial_model(config%model, config%azimuth, 0.0_wp, model, &
                                              status, message, second)
    else
      call spatial_model(config%model, config%azimuth, config%ellipticity, model, status, &
                         message)
    end if
  end subroutine config_spatial_model
end submodule sloshdyn_driver_spatial
