!> The run of one validated input, shared by both front doors (the executable, and Python's
!> `sloshdyn-py run` through the bridge): the analysis, a summary on standard output, and the CSV
!> files in the output directory, all committed together or none. Failures come back as a
!> status and a message saying where; nothing stops the process.
module sloshdyn_driver
  use, intrinsic :: iso_fortran_env, only: output_unit
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT
  use sloshdyn_text, only: num2str
  use sloshdyn_model, only: model_t
  use sloshdyn_excitation, only: forcing_period, PARAMETER_RHO, PARAMETER_A, &
                                 PARAMETER_FREQUENCY, EXCITATION_RECORD
  use sloshdyn_tables, only: HISTORY_ROWS, SUMMARY_SIZE, SUMMARY_RHO, SUMMARY_A, SUMMARY_MAX_X1, &
                             SUMMARY_MAX_X2, SUMMARY_MAX_U1, SUMMARY_MAX_U2, SUMMARY_MOTION, &
                             SUMMARY_PERIOD, SUMMARY_TRANSIENT, SUMMARY_SPREAD, SUMMARY_SETTLED, &
                             POINT_ROWS, SPECIAL_ROWS, SPECIAL_KIND, SPECIAL_LAMBDA, SPECIAL_A1, &
                             SPECIAL_A2, SPECIAL_FREQUENCY, SPECIAL_HOPF, POINT_BRANCH, &
                             SPECIAL_BRANCH_POINT, SPECIAL_PERIOD_DOUBLING, SPECIAL_FOLD, &
                             SPECIAL_NEIMARK_SACKER, MOTION_PERIODIC, motion_name, special_kind_name, verdict_name, &
                             SEISMIC_LOADS, SEISMIC_ROWS, PEAKS_SIZE, PEAKS_WAVE_HEIGHT, &
                             PEAKS_IMPACT_FORCE, PEAKS_ROOF_REACHED, PEAKS_FIRST_ROOF_TIME, &
                             PEAKS_ROOF_IMPACTS, PEAKS_FREE_WAVE, PEAKS_ROOF_HEAD, &
                             PEAKS_ROOF_UPLIFT, PEAKS_CONFINED_MASS, PEAKS_SCALE_FACTOR, &
                             PEAKS_SA, PEAKS_BETA_SENSITIVE, table_header, &
                             CODES_COLUMNS, CODES_ROWS, CODES_SOURCES, &
                             HARMONIC_SWEEP_ROWS, CHART_CURVE_ROWS, &
                             CHART_CODIM2_ROWS, CHART_END_ROWS, CHART_GRID_ROWS, code_name, &
                             CHART_GRID_N_STABLE, CHART_GRID_NEAR_CURVE, &
                             CHART_GRID_BRUTE_FORCE_STABLE, HISTORY_X1, HISTORY_X2, &
                             HARMONIC_SWEEP_WAVE_HEIGHT, PERIODIC_POINT_ROWS, &
                             PERIODIC_MULTIPLIER_ROWS, PERIODIC_SPECIAL_ROWS, &
                             PERIODIC_SPECIAL_KIND, PERIODIC_SPECIAL_LAMBDA, PERIODIC_SPECIAL_MAX_X1, &
                             COUNTS_SIZE, ROUTH_SIZE, table_size, SWIRL_BRANCH_ROWS, &
                             SWIRL_EDGE_ROWS, SEISMIC_SPATIAL_ROWS, SEISMIC_SPATIAL_PEAKS
  use sloshdyn_linear, only: stiffness_matrix, natural_frequencies, natural_frequencies_eig, &
                             kappa_for_detuning
  use sloshdyn_equilibria, only: equilibria, trivial_routh_hurwitz
  use sloshdyn_ode, only: ode_stats
  use sloshdyn_simulation, only: time_history, steady_state, parameter_sweep, independent_sweep
  use sloshdyn_response, only: frequency_response
  use sloshdyn_periodic_response, only: periodic_response_from_rest, lyapunov_exponent, &
                                        orbit_from_rest, periodic_switch
  use sloshdyn_swirl, only: swirl_branch, stability_margin
  use sloshdyn_seismic_spatial, only: seismic_response_spatial
  use sloshdyn_tank_lyapunov, only: tank_lyapunov_spectrum
  use sloshdyn_namelist, only: run_config, known_analyses, ANALYSIS_LINEAR, ANALYSIS_SIMULATE, &
                               ANALYSIS_STEADY_STATE, ANALYSIS_SWEEP, ANALYSIS_FREQUENCY_RESPONSE, &
                               ANALYSIS_PERIODIC_RESPONSE, ANALYSIS_LYAPUNOV, ANALYSIS_SEISMIC, &
                               ANALYSIS_STABILITY_CHART, ANALYSIS_SWIRL, chart_models, &
                              DIRECTION_DOWN, &
                               DIRECTION_BOTH, direction_names
  use sloshdyn_results, only: result_files, check_output_directory
  use sloshdyn_stability_chart, only: chart_result, stability_chart, chart_tables, &
                                      chart_table_sizes, chart_kind, chart_codim2_kind, &
                                      special_point_chart
  use sloshdyn_slowflow_chart, only: chart_parameter_name
  use sloshdyn_seismic, only: seismic_response, seismic_defaults, design_code_checks, &
                              harmonic_sweep
  use sloshdyn_ground, only: ground_duration, GROUND_RECORD, ground_motion_t
  use sloshdyn_vessel, only: tank_t
  use sloshdyn_layouts, only: counts_array
  use sloshdyn_driver_common, only: begin_files, in_context, used_method, value_text, &
                                    difference, pad, write_peak_pressures
  use sloshdyn_tank, only: SHAPE_CIRCULAR
  implicit none
  private
  public :: run_analysis, print_model, sweep_points, design_codes_table
  !> Used by the submodule sloshdyn_driver_spatial too; public because gfortran does not export
  !> a module's private procedures to its submodules' object files.
  public :: swirl_band

  integer, parameter :: max_equilibria = 4096, max_kappa_roots = 64
  !> Room for the slow-flow response table and its special points.
  integer, parameter :: max_response_points = 20000, max_special_points = 200
  !> Room for the edges of a swirl band (as sloshdyn.spatial.swirl_band's max_edges).
  integer, parameter, public :: max_swirl_edges = 100

  !> The runs of a tank in SI units, in the submodule sloshdyn_driver_tank, and of the spatial
  !> model, in sloshdyn_driver_spatial
  interface
    module subroutine run_simulate_spatial(config, files, status, message)
      type(run_config), intent(in) :: config
      type(result_files), intent(inout) :: files
      integer, intent(out) :: status
      character(len=message_len), intent(out) :: message
    end subroutine run_simulate_spatial
    module subroutine run_swirl_boundary(config, files, status, message)
      type(run_config), intent(in) :: config
      type(result_files), intent(inout) :: files
      integer, intent(out) :: status
      character(len=message_len), intent(out) :: message
    end subroutine run_swirl_boundary
    module subroutine run_swirl_orbit(config, files, status, message)
      type(run_config), intent(in) :: config
      type(result_files), intent(inout) :: files
      integer, intent(out) :: status
      character(len=message_len), intent(out) :: message
    end subroutine run_swirl_orbit
    module subroutine run_swirling(config, files, edges, n_edges, status, message)
      type(run_config), intent(in) :: config
      type(result_files), intent(inout) :: files
      real(wp), intent(in) :: edges(:, :)
      integer, intent(in) :: n_edges
      integer, intent(out) :: status
      character(len=message_len), intent(out) :: message
    end subroutine run_swirling
    module subroutine run_swirl_curve(config, files, edges, n_edges, status, message)
      type(run_config), intent(in) :: config
      type(result_files), intent(inout) :: files
      real(wp), intent(in) :: edges(:, :)
      integer, intent(in) :: n_edges
      integer, intent(out) :: status
      character(len=message_len), intent(out) :: message
    end subroutine run_swirl_curve
    module subroutine run_seismic_spatial(config, files, status, message)
      type(run_config), intent(in) :: config
      type(result_files), intent(inout) :: files
      integer, intent(out) :: status
      character(len=message_len), intent(out) :: message
    end subroutine run_seismic_spatial
    module subroutine run_seismic(config, files, status, message)
      type(run_config), intent(in) :: config
      type(result_files), intent(inout) :: files
      integer, intent(out) :: status
      character(len=message_len), intent(out) :: message
    end subroutine run_seismic
    module subroutine print_tank(config)
      type(run_config), intent(in) :: config
    end subroutine print_tank
    pure module function design_codes_table(codes) result(text)
      real(wp), intent(in) :: codes(CODES_COLUMNS, CODES_ROWS)
      character(len=:), allocatable :: text
    end function design_codes_table
  end interface

contains

  !> Run the analysis of config: summary to standard output, CSV files into its directory (by
  !> the run-directory rule, sloshdyn_results; an output directory that a run may not take is
  !> refused before anything runs). With staging not blank (sloshdyn-py) the files go into that
  !> new directory instead, which the caller swaps into place.
  subroutine run_analysis(config, status, message, staging)
    type(run_config), intent(in) :: config
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    character(len=*), intent(in), optional :: staging
    type(result_files) :: files

    if (config%study%given) then
      status = SD_BAD_INPUT
      message = '&study: this file describes a parameter study, which runs in Python on Dask: '// &
                'sloshdyn-py study FILE'
      return
    end if
    if (present(staging)) then
      files%staged = len_trim(staging) > 0
      if (files%staged) files%directory = trim(staging)
    end if
    if (.not. files%staged) then
      call check_output_directory(trim(config%directory), status, message)
      if (status /= SD_OK) return
    end if
    call print_model(config)
    ! the summary's first lines out before the analysis runs: the program is ready, its signal
    ! handlers installed (docs/failure.md, "Signals")
    flush (output_unit)
    select case (config%analysis)
    case (ANALYSIS_LINEAR)
      call run_linear(config, files, status, message)
    case (ANALYSIS_SIMULATE)
      if (config%planar) then
        call run_simulate(config, files, status, message)
      else
        call run_simulate_spatial(config, files, status, message)
      end if
    case (ANALYSIS_STEADY_STATE)
      if (config%planar) then
        call run_steady_state(config, files, status, message)
      else
        call run_swirl_orbit(config, files, status, message)
      end if
    case (ANALYSIS_SWEEP)
      call run_sweep(config, files, status, message)
    case (ANALYSIS_FREQUENCY_RESPONSE)
      call run_response(config, files, status, message)
    case (ANALYSIS_PERIODIC_RESPONSE)
      call run_periodic(config, files, status, message)
    case (ANALYSIS_LYAPUNOV)
      call run_lyapunov(config, files, status, message)
    case (ANALYSIS_SEISMIC)
      if (config%planar) then
        call run_seismic(config, files, status, message)
      else
        call run_seismic_spatial(config, files, status, message)
      end if
    case (ANALYSIS_SWIRL)
      if (config%sweep%n_points > 0) then
        call run_swirl_boundary(config, files, status, message)
      else
        call run_swirl(config, files, status, message)
      end if
    case (ANALYSIS_STABILITY_CHART)
      call run_chart(config, files, status, message)
    end select
    if (status == SD_OK) call files%commit(status, message)
    if (status == SD_OK) then
      print '(/a)', 'Results written to '//files%target//'/'
    else
      call files%discard()
    end if
    flush (output_unit)
  end subroutine run_analysis

  !> Stability chart of the slow flow: curves with their codimension-2 points, the grid's
  !> counts of steady states (and brute force). Incomplete curves are written as far as they
  !> go, each marked in chart_ends.csv and named here.
  subroutine run_chart(config, files, status, message)
    type(run_config), intent(in) :: config
    type(result_files), intent(inout) :: files
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(chart_result) :: chart
    real(wp), allocatable :: curves(:, :), codim2(:, :), ends(:, :), grid(:, :)
    integer :: n_points, n_codim2, n_curves, n_cells, c, j, agree, checked

    associate (s => config%chart)
      print '(/a)', 'Stability chart ('//trim(chart_models(s%model))//') in '// &
                    chart_parameter_name(s%parameters(1))//' in ['//num2str(s%p_min(1))//', '// &
                    num2str(s%p_max(1))//'] x '//chart_parameter_name(s%parameters(2))// &
                    ' in ['//num2str(s%p_min(2))//', '//num2str(s%p_max(2))//']: '// &
                    num2str(s%n_levels)//' one-parameter runs seed the curves'
    end associate
    flush (output_unit)
    call stability_chart(config%model, config%chart, chart, status, message)
    call in_context('stability chart', status, message)
    if (status /= SD_OK) return
    do c = 1, chart%n_curves
      associate (curve => chart%curves(c))
        print '(a)', '  curve '//pad(num2str(c), 4)//pad(code_name('k', chart_kind(curve%kind)), &
                     6)//pad(num2str(curve%n_points)//' points', 13)//'ends: '// &
                     code_name('e', curve%end_reason(1))//' / '// &
                     code_name('e', curve%end_reason(2))// &
                     trim(merge('              ', ', INCOMPLETE  ', curve%complete))
        if (.not. curve%complete) print '(a)', '      '//trim(curve%message)
        do j = 1, curve%n_codim2
          print '(a)', '      '//pad(code_name('d', chart_codim2_kind(curve%codim2(j)%kind)), &
                       18)//'at '//chart_parameter_name(config%chart%parameters(1))//' = '// &
                       num2str(curve%codim2(j)%p(1))//', '// &
                       chart_parameter_name(config%chart%parameters(2))//' = '// &
                       num2str(curve%codim2(j)%p(2))
        end do
      end associate
    end do
    call chart_table_sizes(chart, n_points, n_codim2, n_curves, n_cells)
    allocate (curves(CHART_CURVE_ROWS, n_points), codim2(CHART_CODIM2_ROWS, n_codim2), &
              ends(CHART_END_ROWS, n_curves), grid(CHART_GRID_ROWS, n_cells))
    call chart_tables(chart, curves, codim2, ends, grid)
    print '(a)', '  grid of '//num2str(n_cells)//' cells: '// &
                 num2str(count(grid(CHART_GRID_N_STABLE, :) == 0))// &
                 ' with no stable steady state, '// &
                 num2str(count(grid(CHART_GRID_N_STABLE, :) == 1))//' with one, '// &
                 num2str(count(grid(CHART_GRID_N_STABLE, :) > 1))//' with more; '// &
                 num2str(count(grid(CHART_GRID_NEAR_CURVE, :) > 0))//' near a curve'
    if (config%chart%brute_force_starts > 0) then
      checked = count(grid(CHART_GRID_NEAR_CURVE, :) == 0)
      agree = count(grid(CHART_GRID_NEAR_CURVE, :) == 0 .and. &
                    grid(CHART_GRID_BRUTE_FORCE_STABLE, :) == grid(CHART_GRID_N_STABLE, :))
      print '(a)', '  brute force ('//num2str(config%chart%brute_force_starts)// &
                   ' integrations per cell): the same number of stable steady states in '// &
                   num2str(agree)//' of the '//num2str(checked)//' cells away from the curves'
    end if
    if (.not. chart%complete) print '(a)', '  WARNING: not every curve could be continued to '// &
                                           'its ends (see above and chart_ends.csv)'
    call begin_files(config, files, status, message)
    if (status == SD_OK) call files%write_table('chart_curves.csv', 'chart_curves', curves, &
                                                status, message)
    if (status == SD_OK) call files%write_table('chart_codim2.csv', 'chart_codim2', codim2, &
                                                status, message)
    if (status == SD_OK) call files%write_table('chart_ends.csv', 'chart_ends', ends, status, &
                                                message)
    if (status == SD_OK) call files%write_table('chart_grid.csv', 'chart_grid', grid, status, &
                                                message)
  end subroutine run_chart

  !> Linear analysis (sec 3.1-3.2): coefficients, natural frequencies, equilibria with their
  !> eigenvalues and verdicts, Routh-Hurwitz at the trivial equilibrium, kappa for 3:1.
  subroutine run_linear(config, files, status, message)
    type(run_config), intent(in) :: config
    type(result_files), intent(inout) :: files
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(model_t) :: model
    real(wp) :: omega1, omega2, omega1_eig, omega2_eig, k(2, 2)
    real(wp), allocatable :: theta(:), phi(:), eig_re(:, :), eig_im(:, :), rows(:, :)
    real(wp) :: rh_coefficients(4), hurwitz(4), kappa_roots(max_kappa_roots)
    integer, allocatable :: verdict(:)
    logical, allocatable :: physical(:)
    integer :: n_eq, n_kappa, i, j, trivial
    logical :: truncated, routh_stable

    allocate (theta(max_equilibria), phi(max_equilibria), eig_re(4, max_equilibria), &
              eig_im(4, max_equilibria), verdict(max_equilibria), physical(max_equilibria))
    model = config%model
    call natural_frequencies(model, omega1, omega2, status, message)
    call in_context('natural frequencies (eq 28)', status, message)
    if (status /= SD_OK) return
    call natural_frequencies_eig(model, omega1_eig, omega2_eig, status, message)
    call in_context('natural frequencies (dgeev)', status, message)
    if (status /= SD_OK) return
    k = stiffness_matrix(model)
    call equilibria(model, theta, phi, physical, eig_re, eig_im, verdict, n_eq, truncated, &
                    status, message)
    call in_context('equilibria (eq 16-18)', status, message)
    if (status /= SD_OK) return
    call trivial_routh_hurwitz(model, rh_coefficients, hurwitz, routh_stable)
    trivial = findloc(theta(1:n_eq) == 0 .and. phi(1:n_eq) == 0, .true., dim=1)
    call kappa_for_detuning(model%s1, model%mu1, config%sigma1, config%kappa_min, &
                            config%kappa_max, kappa_roots, n_kappa, status, message)
    call in_context('kappa for 3:1 internal resonance (eq 51)', status, message)
    if (status /= SD_OK) return

    print '(/a)', 'Linear analysis about the trivial equilibrium (sec 3.2)'
    print '(a)', '  stiffness matrix K (eq 26):  [['//num2str(k(1, 1))//', '//num2str(k(1, 2))// &
                 '], ['//num2str(k(2, 1))//', '//num2str(k(2, 2))//']]'
    print '(a)', '  omega1 = '//num2str(omega1)//', omega2 = '//num2str(omega2)//'   (eq 28)'
    print '(a)', '  omega1 = '//num2str(omega1_eig)//', omega2 = '//num2str(omega2_eig)// &
                 '   (dgeev of the undamped linearised equations)'
    print '(a)', '  omega2/omega1 = '//num2str(omega2/omega1)//', omega2 - 3 omega1 = '// &
                 num2str(omega2 - 3*omega1)
    print '(/a)', 'Equilibria (eq 16-18): theta [rad], phi [rad], eigenvalues of the Jacobian'
    print '(a)', '  '//num2str(n_eq)//' equilibria, '//num2str(count(physical(1:n_eq)))// &
                 ' physical (|theta|, |phi| < pi/2) listed here; all in equilibria.csv'
    do i = 1, n_eq
      if (.not. physical(i)) cycle
      print '(a)', '  theta = '//pad(num2str(theta(i)), 14)//' phi = '//pad(num2str(phi(i)), 14)// &
                   pad('physical', 13)//pad(verdict_name(verdict(i)), 9)// &
                   eigen_text(eig_re(:, i), eig_im(:, i))
    end do
    if (truncated) print '(a)', '  (roots beyond |angle| = 32 pi were not searched)'
    print '(/a)', 'Routh-Hurwitz at the trivial equilibrium (eq 20):'
    print '(a)', '  c1..c4 = '//list(rh_coefficients)//'; Delta2 = '//num2str(hurwitz(2))// &
                 ', Delta3 = '//num2str(hurwitz(3))
    print '(a)', '  Routh-Hurwitz: '//trim(merge('stable    ', 'not stable', routh_stable))// &
                 '; eigenvalues: '//verdict_name(verdict(trivial))
    print '(/a)', 'kappa giving omega2 - 3 omega1 = sigma1 = '//num2str(config%sigma1)// &
                  ' (eq 51) for kappa in ('//num2str(max(config%kappa_min, model%s1))//', '// &
                  num2str(config%kappa_max)//']:'
    if (n_kappa == 0) print '(a)', '  none'
    do i = 1, n_kappa
      print '(a)', '  kappa = '//num2str(kappa_roots(i))
    end do

    call begin_files(config, files, status, message)
    if (status /= SD_OK) return
    call files%write_table('frequencies.csv', 'frequencies', reshape([omega1, omega2, &
                           omega1_eig, omega2_eig, omega2/omega1, k(1, 1), -k(1, 2), -k(2, 1), &
                           k(2, 2)], [table_size('frequencies'), 1]), status, message)
    if (status /= SD_OK) return
    allocate (rows(table_size('equilibria'), n_eq))
    do i = 1, n_eq
      rows(1:6, i) = [theta(i), phi(i), theta(i)/model%theta0, phi(i)/model%theta0, &
                      merge(1.0_wp, 0.0_wp, physical(i)), real(verdict(i), wp)]
      rows(7:, i) = [(eig_re(j, i), eig_im(j, i), j = 1, 4)]
    end do
    call files%write_table('equilibria.csv', 'equilibria', rows, status, message)
    if (status /= SD_OK) return
    call files%write_table('routh_hurwitz.csv', 'routh_hurwitz', reshape([rh_coefficients, &
                           hurwitz(2:3), merge(1.0_wp, 0.0_wp, routh_stable), &
                           real(verdict(trivial), wp)], [ROUTH_SIZE, 1]), status, message)
    if (status /= SD_OK) return
    call files%write_table('kappa_31.csv', 'kappa_31', reshape([(config%sigma1, &
                           kappa_roots(i), i = 1, n_kappa)], [table_size('kappa_31'), n_kappa]), &
                           status, message)
  end subroutine run_linear

  !> Time history from y0 at tau = 0 to t_end, n_out evenly spaced outputs (dense output).
  subroutine run_simulate(config, files, status, message)
    type(run_config), intent(in) :: config
    type(result_files), intent(inout) :: files
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), allocatable :: tau(:), history(:, :)
    type(ode_stats) :: stats
    integer :: i

    associate (sim => config%simulation)
      allocate (tau(sim%n_out), history(HISTORY_ROWS + 1, sim%n_out))
      tau = [(sim%t_end*(i - 1)/(sim%n_out - 1), i = 1, sim%n_out)]
      history(1, :) = tau
      call time_history(config%model, 0.0_wp, sim%y0(1:4), tau, config%integration, &
                        config%method, history(2:, :), stats, status, message)
      call in_context('simulation', status, message)
      if (status /= SD_OK) return
      print '(/a)', 'Simulation ('//used_method(config)//', eq 15'// &
                    trim(merge(' with 29-31', ', a record ', &
                               config%model%excitation%kind /= EXCITATION_RECORD))//') from '// &
                    'tau = 0 to '//num2str(sim%t_end)
    end associate
    print '(a)', '  steps accepted '//num2str(stats%n_accepted)//', rejected '// &
                 num2str(stats%n_rejected)//', right-hand sides '//num2str(stats%n_rhs)
    print '(a)', '  max|x1| = '//num2str(maxval(abs(history(1 + HISTORY_X1, :))))// &
                 ', max|x2| = '// &
                 num2str(maxval(abs(history(1 + HISTORY_X2, :))))//' at the output times'
    call begin_files(config, files, status, message)
    if (status == SD_OK) call files%write_table('history.csv', 'history', history, status, &
                                                message)
    if (status == SD_OK) call files%write_table('simulation.csv', 'simulation', &
                                                reshape(counts_array(stats), [COUNTS_SIZE, 1]), &
                                                status, message)
  end subroutine run_simulate

  !> Steady state at (rho, A) from y0: amplitudes, kind of motion and Poincare points.
  subroutine run_steady_state(config, files, status, message)
    type(run_config), intent(in) :: config
    type(result_files), intent(inout) :: files
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: summary(SUMMARY_SIZE), y_end(4), period
    real(wp), allocatable :: poincare(:, :), rows(:, :)
    type(ode_stats) :: stats
    integer :: i, window

    window = config%steady%window_periods
    allocate (poincare(4, window), rows(table_size('poincare'), window))
    call steady_state(config%model, config%simulation%y0(1:4), config%integration, &
                      config%method, config%steady, summary, poincare, y_end, stats, status, &
                      message)
    call in_context('steady state', status, message)
    if (status /= SD_OK) return
    print '(/a)', 'Steady state ('//used_method(config)//') at rho = '// &
                  num2str(summary(SUMMARY_RHO))//', A = '//num2str(summary(SUMMARY_A))
    call print_summary(summary)
    print '(a)', '  steps accepted '//num2str(stats%n_accepted)//', rejected '// &
                 num2str(stats%n_rejected)//', right-hand sides '//num2str(stats%n_rhs)
    period = forcing_period(config%model%excitation)
    do i = 1, window
      rows(:, i) = [(summary(SUMMARY_TRANSIENT) + i)*period, poincare(:, i)]
    end do
    call begin_files(config, files, status, message)
    if (status == SD_OK) call files%write_table('steady_state.csv', 'summary', &
                                                reshape(summary, [SUMMARY_SIZE, 1]), status, &
                                                message)
    if (status == SD_OK) call files%write_table('poincare.csv', 'poincare', rows, status, message)
  end subroutine run_steady_state

  !> The values of a sweep in the order they are visited.
  pure function sweep_points(lower, upper, n, direction) result(values)
    real(wp), intent(in) :: lower, upper
    integer, intent(in) :: n, direction
    real(wp), allocatable :: values(:)
    integer :: i
    allocate (values(merge(2*n - 1, n, direction == DIRECTION_BOTH)))
    values(1:n) = [(lower + (upper - lower)*(i - 1)/max(n - 1, 1), i = 1, n)]
    if (direction == DIRECTION_DOWN) values = values(n:1:-1)
    if (direction == DIRECTION_BOTH) values(n + 1:) = values(n - 1:1:-1)
  end function sweep_points

  !> Steady states along rho or A, each from the previous final state (or each from y0, shared
  !> out to threads); a line per point as the sweep runs.
  subroutine run_sweep(config, files, status, message)
    type(run_config), intent(in) :: config
    type(result_files), intent(inout) :: files
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), allocatable :: values(:), summaries(:, :), si(:, :)
    real(wp) :: y(4), y_next(4)
    integer :: first, last, i, n_done, step, status_rows
    logical :: in_frequency
    character(len=:), allocatable :: name, how, line
    character(len=message_len) :: message_rows

    associate (sw => config%sweep)
      values = sweep_points(min(sw%start, sw%stop), max(sw%start, sw%stop), sw%n_points, &
                            sw%direction)
      in_frequency = sw%parameter == PARAMETER_FREQUENCY
      name = parameter_label(sw%parameter)
      how = 'each from the previous final state'
      if (.not. sw%carry_state) how = 'each from y0, '//num2str(sw%threads)//' thread(s)'
      print '(/a)', 'Sweep in '//name//' ('//trim(direction_names(sw%direction))//', '// &
                    num2str(size(values))//' points, '//used_method(config)//'), '//how
      if (in_frequency) print '(a)', '  at the constant peak ground acceleration '// &
                                     num2str(config%ground%peak_acceleration)//' m/s^2'
      ! one point per call when the state is carried, four per thread otherwise (threads that
      ! finish early take the next point), so progress shows as the sweep runs
      step = merge(1, 4*sw%threads, sw%carry_state)
    end associate
    allocate (summaries(SUMMARY_SIZE, size(values)), si(HARMONIC_SWEEP_ROWS, size(values)))
    ! the points go to sweep.partial.csv as they finish: a failed or killed sweep keeps them
    call begin_files(config, files, status, message)
    if (status == SD_OK) call files%begin_rows('sweep.csv', 'summary', status, message)
    if (status /= SD_OK) return
    print '(a)', '  (points are written to '//files%partial_path('sweep.csv')//' as they '// &
                 'finish; renamed to sweep.csv when the sweep is complete)'
    line = '  '//pad(name, 14)//pad('max|x1|', 14)//pad('max|x2|', 14)//pad('max|u1|', 14)// &
           pad('max|u2|', 14)
    if (in_frequency) line = line//pad('wave [m]', 14)
    print '(a)', line//'motion'
    flush (output_unit)
    y = config%simulation%y0(1:4)
    do first = 1, size(values), step
      last = min(first + step - 1, size(values))
      if (in_frequency) then
        call harmonic_sweep(config%tank, config%ground, values(first:last), y, &
                            config%integration, config%method, config%steady, &
                            config%sweep%carry_state, config%sweep%threads, &
                            summaries(:, first:last), si(:, first:last), y_next, n_done, status, &
                            message)
        if (config%sweep%carry_state) y = y_next
      else if (config%sweep%carry_state) then
        call parameter_sweep(config%model, config%sweep%parameter, values(first:last), y, &
                             config%integration, config%method, config%steady, &
                             summaries(:, first:last), y_next, n_done, status, message)
        y = y_next
      else
        call independent_sweep(config%model, config%sweep%parameter, values(first:last), y, &
                               config%integration, config%method, config%steady, &
                               config%sweep%threads, summaries(:, first:last), n_done, status, &
                               message)
      end if
      if (status == SD_OK) then
        call files%append_rows('sweep.csv', 'summary', summaries(:, first:last), status, &
                               message)
      else if (config%sweep%carry_state .and. n_done > 0) then
        call files%append_rows('sweep.csv', 'summary', summaries(:, first:first + n_done - 1), &
                               status_rows, message_rows)
      end if
      if (status /= SD_OK) then
        call in_context('sweep', status, message)
        message = trim(message)//'; the '//num2str(first - 1 + merge(n_done, 0, &
                  config%sweep%carry_state))//' of '//num2str(size(values))// &
                  ' points completed are kept in '// &
                  files%partial_path('sweep.csv', in_place=.true.)
        return
      end if
      do i = first, last
        line = '  '//pad(num2str(values(i)), 14)// &
               pad(num2str(summaries(SUMMARY_MAX_X1, i)), 14)// &
               pad(num2str(summaries(SUMMARY_MAX_X2, i)), 14)// &
               pad(num2str(summaries(SUMMARY_MAX_U1, i)), 14)// &
               pad(num2str(summaries(SUMMARY_MAX_U2, i)), 14)
        if (in_frequency) line = line//pad(num2str(si(HARMONIC_SWEEP_WAVE_HEIGHT, i)), 14)
        print '(a)', line//motion_text(summaries(SUMMARY_MOTION, i), summaries(SUMMARY_PERIOD, i))
      end do
      flush (output_unit)
    end do
    if (in_frequency) &
      call files%write_table('harmonic_sweep.csv', 'harmonic_sweep', si, status, message)
  end subroutine run_sweep

  !> Slow-flow frequency response (sec 3.3): branches, stability, folds and Hopf points.
  !> An incomplete branch is an error: nothing is written.
  subroutine run_response(config, files, status, message)
    type(run_config), intent(in) :: config
    type(result_files), intent(inout) :: files
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), allocatable :: table(:, :), special(:, :)
    integer :: n_points, n_special, i
    logical :: complete
    character(len=:), allocatable :: name

    allocate (table(POINT_ROWS, max_response_points), special(SPECIAL_ROWS, max_special_points))
    associate (r => config%response)
      call frequency_response(config%model, r%internal_resonance, r%parameter, r%start, r%stop, &
                              r%options, table, n_points, special, n_special, complete, status, &
                              message)
      call in_context('frequency response', status, message)
      if (status /= SD_OK) return
      name = parameter_label(r%parameter)
      print '(/a)', 'Slow-flow response ('//trim(merge('3:1 internal resonance', &
                    'no internal resonance ', r%internal_resonance))//') for '//name// &
                    ' in ['//num2str(r%start)//', '//num2str(r%stop)//']'
    end associate
    print '(a)', '  '//num2str(nint(maxval(table(POINT_BRANCH, 1:n_points))))//' branches, '// &
                 num2str(n_points)//' points; special points:'
    do i = 1, n_special
      print '(a)', '  '//pad(special_kind_label(nint(special(SPECIAL_KIND, i))), 6)//name// &
                   ' = '//pad(num2str(special(SPECIAL_LAMBDA, i)), 14)//'|u1| = '// &
                   pad(num2str(special(SPECIAL_A1, i)), 14)//'|u2| = '// &
                   pad(num2str(special(SPECIAL_A2, i)), 14)//hopf_frequency(special(:, i))
    end do
    call begin_files(config, files, status, message)
    if (status == SD_OK) call files%write_table('response.csv', 'response', &
                                                table(:, 1:n_points), status, message)
    if (status == SD_OK) call files%write_table('special_points.csv', 'special_points', &
                                                special(1:SPECIAL_ROWS - 1, 1:n_special), &
                                                status, message)
  end subroutine run_response

  !> Periodic orbits of the full equations (shooting, Floquet multipliers) continued in rho or
  !> A from the steady state reached from y0 at the start of the range; with switch_at, also
  !> the branch born at that special point (periodic_switched_branch.csv,
  !> periodic_switched_special_points.csv); with curve_at, the two-parameter curve through that
  !> special point (periodic_curve.csv, periodic_curve_codim2.csv, periodic_curve_ends.csv).
  subroutine run_periodic(config, files, status, message)
    type(run_config), intent(in) :: config
    type(result_files), intent(inout) :: files
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), allocatable :: points(:, :), multipliers(:, :), special(:, :), &
                             new_points(:, :), new_multipliers(:, :), new_special(:, :)
    integer :: n_points, n_special, capacity, n_new, n_new_special, k_new, kind
    logical :: complete
    character(len=:), allocatable :: name
    type(chart_result) :: chart

    associate (r => config%response)
      capacity = r%options%continuation%max_points
      allocate (points(PERIODIC_POINT_ROWS, capacity), &
                multipliers(PERIODIC_MULTIPLIER_ROWS, capacity), &
                special(PERIODIC_SPECIAL_ROWS, 100))
      call periodic_response_from_rest(config%model, r%parameter, config%simulation%y0(1:4), &
                                       r%start, r%stop, config%steady, r%options%continuation, &
                                       config%integration, config%method, points, multipliers, &
                                       n_points, special, n_special, complete, status, message)
      call in_context('periodic response', status, message)
      if (status /= SD_OK) return
      name = parameter_label(r%parameter)
      print '(/a)', 'Periodic orbits of the full equations (shooting, Floquet multipliers; '// &
                    used_method(config)//') for '//name//' in ['//num2str(r%start)// &
                    ', '//num2str(r%stop)//']'
      call print_branch(n_points, special(:, 1:n_special))
      if (r%switch_at > 0) then
        if (r%switch_at > n_special) then
          status = SD_BAD_INPUT
          message = '&response: switch_at = '//num2str(r%switch_at)//' is out of range: the '// &
                    'branch has '//num2str(n_special)//' special points'
          return
        end if
        kind = nint(special(PERIODIC_SPECIAL_KIND, r%switch_at))
        if (kind /= SPECIAL_BRANCH_POINT .and. kind /= SPECIAL_PERIOD_DOUBLING) then
          status = SD_BAD_INPUT
          message = '&response: switch_at = '//num2str(r%switch_at)//' is a '// &
                    special_kind_name(kind)//': branches are switched at a branch_point '// &
                    'or a period_doubling'
          return
        end if
        allocate (new_points(PERIODIC_POINT_ROWS, capacity), &
                  new_multipliers(PERIODIC_MULTIPLIER_ROWS, capacity), &
                  new_special(PERIODIC_SPECIAL_ROWS, 100))
        call periodic_switch(config%model, r%parameter, kind, &
                             special(PERIODIC_SPECIAL_LAMBDA + 1:PERIODIC_SPECIAL_LAMBDA + 4, &
                                     r%switch_at), &
                             special(PERIODIC_SPECIAL_LAMBDA, r%switch_at), 1, r%start, r%stop, &
                             r%options%continuation, config%integration, config%method, &
                             new_points, new_multipliers, n_new, new_special, n_new_special, &
                             complete, k_new, status, message)
        call in_context('branch switching at special point '//num2str(r%switch_at), status, &
                        message)
        if (status /= SD_OK) return
        print '(/a)', 'The branch born at the '//special_kind_name(kind)//' '// &
                      num2str(r%switch_at)//' (orbits of period '//num2str(k_new)//' T)'
        call print_branch(n_new, new_special(:, 1:n_new_special))
      end if
      if (r%curve_at > 0) then
        call periodic_curve(config, special(:, 1:n_special), chart, status, message)
        if (status /= SD_OK) return
      end if
    end associate
    call begin_files(config, files, status, message)
    call write_branch('periodic_branch.csv', 'periodic_special_points.csv', points, &
                      multipliers, n_points, special(:, 1:n_special))
    if (allocated(new_points)) &
      call write_branch('periodic_switched_branch.csv', 'periodic_switched_special_points.csv', &
                        new_points, new_multipliers, n_new, new_special(:, 1:n_new_special))
    if (allocated(chart%curves)) call write_chart_tables(chart, 'periodic_curve.csv', &
                                                         'periodic_curve_codim2.csv', &
                                                         'periodic_curve_ends.csv')

  contains

    subroutine print_branch(count, found)
      integer, intent(in) :: count
      real(wp), intent(in) :: found(:, :)
      integer :: i
      print '(a)', '  '//num2str(count)//' orbits; special points:'
      do i = 1, size(found, 2)
        print '(a)', '  '//pad(special_kind_name(nint(found(PERIODIC_SPECIAL_KIND, i))), 16)// &
                     name//' = '// &
                     pad(num2str(found(PERIODIC_SPECIAL_LAMBDA, i)), 14)//'max|x1| = '// &
                     num2str(found(PERIODIC_SPECIAL_MAX_X1, i))
      end do
    end subroutine print_branch

    subroutine write_branch(branch_file, special_file, pts, mult, count, found)
      character(len=*), intent(in) :: branch_file, special_file
      real(wp), intent(in) :: pts(:, :), mult(:, :), found(:, :)
      integer, intent(in) :: count
      integer :: i
      if (status == SD_OK) call files%write_table(branch_file, 'periodic_branch', &
                                                  reshape([(pts(:, i), mult(:, i), &
                                                  i = 1, count)], &
                                                  [PERIODIC_POINT_ROWS + &
                                                   PERIODIC_MULTIPLIER_ROWS, count]), status, &
                                                  message)
      if (status == SD_OK) call files%write_table(special_file, 'periodic_special_points', &
                                                  found, status, message)
    end subroutine write_branch

    subroutine write_chart_tables(found, curve_file, codim2_file, ends_file)
      type(chart_result), intent(in) :: found
      character(len=*), intent(in) :: curve_file, codim2_file, ends_file
      real(wp), allocatable :: curves(:, :), codim2(:, :), ends(:, :), grid(:, :)
      integer :: n_curve, n_codim2, n_curves, n_cells
      call chart_table_sizes(found, n_curve, n_codim2, n_curves, n_cells)
      allocate (curves(CHART_CURVE_ROWS, n_curve), codim2(CHART_CODIM2_ROWS, n_codim2), &
                ends(CHART_END_ROWS, n_curves), grid(CHART_GRID_ROWS, n_cells))
      call chart_tables(found, curves, codim2, ends, grid)
      if (status == SD_OK) call files%write_table(curve_file, 'chart_curves', curves, status, &
                                                  message)
      if (status == SD_OK) call files%write_table(codim2_file, 'chart_codim2', codim2, status, &
                                                  message)
      if (status == SD_OK) call files%write_table(ends_file, 'chart_ends', ends, status, message)
    end subroutine write_chart_tables
  end subroutine run_periodic

  !> &response curve_at = j: the two-parameter curve in (rho, A) of the orbits through special
  !> point j of the branch (a fold, period doubling or Neimark-Sacker point), inside the box of
  !> the branch's range times [curve_start, curve_stop] of the other parameter, with at most
  !> max_points points (as Python's PeriodicBranch.curve with that box and Chart(max_points)).
  subroutine periodic_curve(config, special, chart, status, message)
    type(run_config), intent(in) :: config
    real(wp), intent(in) :: special(:, :)
    type(chart_result), intent(out) :: chart
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(model_t) :: model
    real(wp) :: p_min(2), p_max(2)
    character(len=message_len) :: note
    integer :: kind, j, c
    associate (r => config%response)
      j = r%curve_at
      status = SD_BAD_INPUT
      if (j > size(special, 2)) then
        message = '&response: curve_at = '//num2str(j)//' is out of range: the branch has '// &
                  num2str(size(special, 2))//' special points'
        return
      end if
      kind = nint(special(PERIODIC_SPECIAL_KIND, j))
      if (kind /= SPECIAL_FOLD .and. kind /= SPECIAL_PERIOD_DOUBLING .and. &
          kind /= SPECIAL_NEIMARK_SACKER) then
        message = '&response: curve_at = '//num2str(j)//' is a '//special_kind_name(kind)// &
                  ': a curve starts at a fold, a period_doubling or a neimark_sacker'
        return
      end if
      model = config%model
      if (r%parameter == PARAMETER_RHO) then
        model%excitation%rho = special(PERIODIC_SPECIAL_LAMBDA, j)
        p_min = [r%start, r%curve_start]
        p_max = [r%stop, r%curve_stop]
      else
        model%excitation%A = special(PERIODIC_SPECIAL_LAMBDA, j)
        p_min = [r%curve_start, r%start]
        p_max = [r%curve_stop, r%stop]
      end if
      call special_point_chart(model, r%parameter, special(:, j), 1, p_min, p_max, &
                               max(r%options%continuation%max_points, 3), chart, note, status, &
                               message)
      call in_context('curve at special point '//num2str(j), status, message)
      if (status /= SD_OK) return
      c = chart%curves(1)%n_points
      print '(/a)', 'The '//trim(code_name('k', chart_kind(chart%curves(1)%kind)))// &
                    ' curve through special point '//num2str(j)//' in rho in ['// &
                    num2str(p_min(1))//', '//num2str(p_max(1))//'] x A in ['// &
                    num2str(p_min(2))//', '//num2str(p_max(2))//']: '//num2str(c)//' points, '// &
                    num2str(chart%curves(1)%n_codim2)//' codimension-2 points'// &
                    trim(merge('              ', ', INCOMPLETE: ', chart%complete))
      if (.not. chart%complete) print '(a)', '  '//trim(note)
    end associate
  end subroutine periodic_curve

  !> The swirl band (sloshdyn_swirl): the branch of planar periodic responses (started as
  !> run_periodic's) with the out-of-plane Floquet multipliers at each point, and the band's
  !> edges.
  subroutine run_swirl(config, files, status, message)
    type(run_config), intent(in) :: config
    type(result_files), intent(inout) :: files
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), allocatable :: points(:, :), edges(:, :)
    integer :: n_points, n_edges, i
    logical :: complete, conservative
    character(len=:), allocatable :: name

    associate (r => config%response)
      call swirl_band(config, config%model, points, n_points, edges, n_edges, complete, status, &
                      message, conservative)
      call in_context('swirl', status, message)
      if (status /= SD_OK) return
      name = parameter_label(r%parameter)
      print '(/a)', 'Swirl: out-of-plane Floquet multipliers of the planar periodic orbits '// &
                    '(spatial model; '//used_method(config)//') for '//name//' in ['// &
                    num2str(r%start)//', '//num2str(r%stop)//']'
    end associate
    print '(a)', '  '//num2str(n_points)//' orbits, '// &
                 num2str(count(points(8, 1:n_points) > 1 + stability_margin))// &
                 ' unstable out of their plane (max|nu| > 1 + '//num2str(stability_margin)//'); edges of the swirl band:'
    if (n_edges == 0) print '(a)', '  none'
    do i = 1, n_edges
      print '(a)', '  '//name//' = '//pad(num2str(edges(1, i)), 14)//'max|x1| = '// &
                   pad(num2str(edges(6, i)), 14)//pad(special_kind_name(nint(edges(8, i))), 17)// &
                   trim(merge('(located)     ', '(interpolated)', edges(7, i) > 0))
    end do
    if (conservative) print '(a)', '  no damping (the monodromy preserves volume): the '// &
      'Neimark-Sacker tests, in the plane and out of it, were skipped (stable multipliers '// &
      'sit on the unit circle, where they vanish)'
    call begin_files(config, files, status, message)
    if (status == SD_OK) call files%write_table('swirl_branch.csv', 'swirl_branch', &
                                                points(:, 1:n_points), status, message)
    if (status == SD_OK) call files%write_table('swirl_edges.csv', 'swirl_edges', &
                                                edges(:, 1:n_edges), status, message)
    if (status == SD_OK .and. config%response%switch_at > 0) &
      call run_swirling(config, files, edges, n_edges, status, message)
    if (status == SD_OK .and. config%response%curve_at > 0) &
      call run_swirl_curve(config, files, edges, n_edges, status, message)
  end subroutine run_swirl

  !> The swirl band of model along &response's range (sloshdyn_swirl's swirl_branch, from the
  !> planar orbit reached from &simulation's y0 at its start): points(SWIRL_BRANCH_ROWS, :) and
  !> edges(SWIRL_EDGE_ROWS, :), allocated here.
  subroutine swirl_band(config, model, points, n_points, edges, n_edges, complete, status, &
                        message, conservative)
    type(run_config), intent(in) :: config
    type(model_t), intent(in) :: model
    real(wp), allocatable, intent(out) :: points(:, :), edges(:, :)
    integer, intent(out) :: n_points, n_edges, status
    logical, intent(out) :: complete
    logical, intent(out), optional :: conservative
    character(len=message_len), intent(out) :: message
    type(model_t) :: start
    real(wp) :: y_orbit(4)
    logical :: no_damping
    n_points = 0
    n_edges = 0
    complete = .false.
    no_damping = .false.
    associate (r => config%response)
      allocate (points(SWIRL_BRANCH_ROWS, r%options%continuation%max_points), &
                edges(SWIRL_EDGE_ROWS, max_swirl_edges))
      call orbit_from_rest(model, r%parameter, config%simulation%y0(1:4), r%start, &
                           config%steady, config%integration, config%method, start, y_orbit, &
                           status, message)
      if (status == SD_OK) &
        call swirl_branch(start, r%parameter, y_orbit, 1, r%start, r%stop, &
                          r%options%continuation, config%integration, config%method, points, &
                          n_points, edges, n_edges, complete, no_damping, status, message)
    end associate
    if (present(conservative)) conservative = no_damping
  end subroutine swirl_band

  !> Largest Lyapunov exponent from y0 with its running estimates.
  subroutine run_lyapunov(config, files, status, message)
    type(run_config), intent(in) :: config
    type(result_files), intent(inout) :: files
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), allocatable :: history(:)
    real(wp) :: exponent
    integer :: i

    if (config%lyapunov%spectrum) then
      call run_lyapunov_spectrum(config, files, status, message)
      return
    end if
    associate (ly => config%lyapunov)
      allocate (history(ly%n_periods/ly%renormalise_every))
      call lyapunov_exponent(config%model, config%simulation%y0(1:4), ly%transient_periods, &
                             ly%n_periods, ly%renormalise_every, config%integration, &
                             config%method, exponent, history, status, message, ly%average)
      call in_context('Lyapunov exponent', status, message)
      if (status /= SD_OK) return
      print '(/a)', 'Largest Lyapunov exponent (per unit tau; '//used_method(config)// &
                    ') = '//num2str(exponent)
      print '(a)', '  running estimate at 1/4, 1/2, 3/4 of the run: '// &
                   num2str(history(max(1, size(history)/4)))//', '// &
                   num2str(history(max(1, size(history)/2)))//', '// &
                   num2str(history(max(1, 3*size(history)/4)))
      call begin_files(config, files, status, message)
      if (status == SD_OK) call files%write_table('lyapunov.csv', 'lyapunov', &
                                                  reshape([(real(i*ly%renormalise_every, wp), &
                                                  history(i), i = 1, size(history))], &
                                                  [2, size(history)]), status, message)
    end associate
  end subroutine run_lyapunov

  !> &lyapunov spectrum = .true.: all four Lyapunov exponents (QR method) from y0, their running
  !> estimates and the Kaplan-Yorke dimension.
  subroutine run_lyapunov_spectrum(config, files, status, message)
    type(run_config), intent(in) :: config
    type(result_files), intent(inout) :: files
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), allocatable :: history(:, :)
    real(wp) :: exponents(4), dimension_ky
    integer :: i

    associate (ly => config%lyapunov)
      allocate (history(4, ly%n_periods/ly%renormalise_every))
      call tank_lyapunov_spectrum(config%model, config%simulation%y0(1:4), ly, config%integration, &
                                  config%method, exponents, history, dimension_ky, status, &
                                  message)
      call in_context('Lyapunov spectrum', status, message)
      if (status /= SD_OK) return
      print '(/a)', 'Lyapunov spectrum (per unit tau; QR method; '//used_method(config)//'):'
      print '(a)', '  '//num2str(exponents(1))//', '//num2str(exponents(2))//', '// &
                   num2str(exponents(3))//', '//num2str(exponents(4))
      print '(a)', '  sum (mean phase-space contraction rate) = '//num2str(sum(exponents))// &
                   '; Kaplan-Yorke dimension = '//num2str(dimension_ky)
      call begin_files(config, files, status, message)
      if (status == SD_OK) call files%write_table('lyapunov_spectrum.csv', 'lyapunov_spectrum', &
                                                  reshape([(real(i*ly%renormalise_every, wp), &
                                                  history(:, i), i = 1, size(history, 2))], &
                                                  [5, size(history, 2)]), status, message)
    end associate
  end subroutine run_lyapunov_spectrum

  subroutine print_model(config)
    type(run_config), intent(in) :: config
    print '(a)', 'sloshdyn: '//trim(known_analyses(config%analysis))
    if (config%dimensional) call print_tank(config)
    associate (m => config%model)
      print '(/a)', 'Dimensionless model (eq 9): s1 = '//num2str(m%s1)//', mu1 = '// &
                    num2str(m%mu1)//', kappa = '//num2str(m%kappa)//', theta0 = '// &
                    num2str(m%theta0)//' rad'
      print '(a)', '  beta = '//num2str(m%beta)//', gamma = '//num2str(m%gamma)//', delta = '// &
                   num2str(m%delta)//', zeta = '//num2str(m%zeta)//', n = '//num2str(m%n)// &
                   ', p = '//num2str(m%p)// &
                   ', kappa_hat = kappa/s1 = '//num2str(m%kappa/m%s1)
      if (m%excitation%kind == EXCITATION_RECORD) then
        print '(a)', '  excitation: a record of '//num2str(size(m%excitation%samples))// &
                     ' samples of X'''' every '//num2str(m%excitation%step)//' in tau'
      else
        print '(a)', '  excitation X = A sin(rho tau): A = '//num2str(m%excitation%A)// &
                     ', rho = '//num2str(m%excitation%rho)
      end if
      if (.not. (config%planar .or. config%dimensional)) &
        print '(a)', '  spatial model (planar = .false.): the base moves along azimuth '// &
                     num2str(config%azimuth)//' rad, ellipticity '//num2str(config%ellipticity)
      print '(a)', '  a1..a6 (eq 11) = '//list(m%a_coef)
      print '(a)', '  b1..b6 (eq 11) = '//list(m%b_coef)
    end associate
  end subroutine print_model

  !> The name of a swept or continued parameter.
  pure function parameter_label(parameter) result(label)
    integer, intent(in) :: parameter
    character(len=:), allocatable :: label
    select case (parameter)
    case (PARAMETER_RHO)
      label = 'rho'
    case (PARAMETER_A)
      label = 'A'
    case default
      label = 'f [Hz]'
    end select
  end function parameter_label

  subroutine print_summary(summary)
    real(wp), intent(in) :: summary(SUMMARY_SIZE)
    print '(a)', '  max|x1| = '//num2str(summary(SUMMARY_MAX_X1))//', max|x2| = '// &
                 num2str(summary(SUMMARY_MAX_X2))//', max|u1| = '// &
                 num2str(summary(SUMMARY_MAX_U1))//', max|u2| = '//num2str(summary(SUMMARY_MAX_U2))
    print '(a)', '  motion: '//motion_text(summary(SUMMARY_MOTION), summary(SUMMARY_PERIOD))// &
                 ' (Poincare spread '//num2str(summary(SUMMARY_SPREAD))//'); transient '// &
                 num2str(summary(SUMMARY_TRANSIENT))//' periods'// &
                 trim(merge('                           ', ', not settled to settle_tol', &
                 summary(SUMMARY_SETTLED) > 0))
  end subroutine print_summary

  !> The kind of motion in words, with its period when periodic.
  pure function motion_text(code, period) result(text)
    real(wp), intent(in) :: code, period
    character(len=:), allocatable :: text
    text = motion_name(nint(code))
    if (nint(code) == MOTION_PERIODIC) text = text//' (period '//num2str(nint(period))//' T)'
  end function motion_text

  !> 'fold' or 'Hopf' for the summary.
  pure function special_kind_label(code) result(label)
    integer, intent(in) :: code
    character(len=:), allocatable :: label
    label = special_kind_name(code)
    if (code == SPECIAL_HOPF) label = 'Hopf'
  end function special_kind_label

  pure function hopf_frequency(point) result(text)
    real(wp), intent(in) :: point(:)
    character(len=:), allocatable :: text
    text = ''
    if (nint(point(SPECIAL_KIND)) == SPECIAL_HOPF) &
      text = 'frequency sqrt(C3/C1) = '//num2str(point(SPECIAL_FREQUENCY))
  end function hopf_frequency

  pure function eigen_text(re, im) result(text)
    real(wp), intent(in) :: re(:), im(:)
    character(len=:), allocatable :: text
    integer :: i
    text = ''
    do i = 1, size(re)
      text = text//' '//num2str(re(i))//merge('+', '-', im(i) >= 0)//num2str(abs(im(i)))//'i'
    end do
  end function eigen_text

  pure function list(values) result(text)
    real(wp), intent(in) :: values(:)
    character(len=:), allocatable :: text
    integer :: i
    text = num2str(values(1))
    do i = 2, size(values)
      text = text//', '//num2str(values(i))
    end do
  end function list
end module sloshdyn_driver
