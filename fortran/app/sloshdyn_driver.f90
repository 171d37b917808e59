!> The run of one validated input, shared by both front doors (the executable, and Python's
!> `sloshdyn-py run` through the bridge): the analysis, a summary on standard output, and the CSV
!> files in the output directory, all committed together or none. Failures come back as a
!> status and a message saying where; nothing stops the process.
module sloshdyn_driver
  use, intrinsic :: iso_fortran_env, only: output_unit
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, status_name
  use sloshdyn_text, only: num2str
  use sloshdyn_model, only: model_t
  use sloshdyn_excitation, only: forcing_period, PARAMETER_RHO
  use sloshdyn_tables, only: HISTORY_ROWS, SUMMARY_SIZE, SUMMARY_RHO, SUMMARY_A, SUMMARY_MAX_X1, &
                             SUMMARY_MAX_X2, SUMMARY_MAX_U1, SUMMARY_MAX_U2, SUMMARY_MOTION, &
                             SUMMARY_PERIOD, SUMMARY_TRANSIENT, SUMMARY_SPREAD, SUMMARY_SETTLED, &
                             POINT_ROWS, SPECIAL_ROWS, SPECIAL_KIND, SPECIAL_LAMBDA, SPECIAL_A1, &
                             SPECIAL_A2, SPECIAL_FREQUENCY, SPECIAL_HOPF, POINT_BRANCH, &
                             MOTION_PERIODIC, motion_name, special_kind_name, verdict_name
  use sloshdyn_linear, only: stiffness_matrix, natural_frequencies, natural_frequencies_eig, &
                             kappa_for_detuning
  use sloshdyn_equilibria, only: equilibria, trivial_routh_hurwitz
  use sloshdyn_ode, only: ode_stats
  use sloshdyn_integrator, only: method_name
  use sloshdyn_simulation, only: time_history, steady_state, parameter_sweep, independent_sweep
  use sloshdyn_response, only: frequency_response
  use sloshdyn_periodic_response, only: periodic_response_from_rest, lyapunov_exponent
  use sloshdyn_namelist, only: run_config, known_analyses, ANALYSIS_LINEAR, ANALYSIS_SIMULATE, &
                               ANALYSIS_STEADY_STATE, ANALYSIS_SWEEP, ANALYSIS_FREQUENCY_RESPONSE, &
                               ANALYSIS_PERIODIC_RESPONSE, ANALYSIS_LYAPUNOV, DIRECTION_DOWN, &
                               DIRECTION_BOTH, direction_names
  use sloshdyn_results, only: result_files
  use sloshdyn_layouts, only: counts_array
  implicit none
  private
  public :: run_analysis, print_model, sweep_points

  integer, parameter :: max_equilibria = 4096, max_kappa_roots = 64
  !> Room for the slow-flow response table and its special points.
  integer, parameter :: max_response_points = 20000, max_special_points = 200

contains

  !> Run the analysis of config: summary to standard output, CSV files into its directory.
  subroutine run_analysis(config, status, message)
    type(run_config), intent(in) :: config
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(result_files) :: files

    if (config%study%given) then
      status = SD_BAD_INPUT
      message = '&study: this file describes a parameter study, which runs in Python on Dask: '// &
                'sloshdyn-py study FILE'
      return
    end if
    call print_model(config)
    select case (config%analysis)
    case (ANALYSIS_LINEAR)
      call run_linear(config, files, status, message)
    case (ANALYSIS_SIMULATE)
      call run_simulate(config, files, status, message)
    case (ANALYSIS_STEADY_STATE)
      call run_steady_state(config, files, status, message)
    case (ANALYSIS_SWEEP)
      call run_sweep(config, files, status, message)
    case (ANALYSIS_FREQUENCY_RESPONSE)
      call run_response(config, files, status, message)
    case (ANALYSIS_PERIODIC_RESPONSE)
      call run_periodic(config, files, status, message)
    case (ANALYSIS_LYAPUNOV)
      call run_lyapunov(config, files, status, message)
    end select
    if (status == SD_OK) call files%commit(status, message)
    if (status == SD_OK) then
      print '(/a)', 'Results written to '//files%directory//'/'
    else
      call files%discard()
    end if
    flush (output_unit)
  end subroutine run_analysis

  !> A failed step: keep the status, put the context (and the kind of failure) in the message.
  pure subroutine in_context(context, status, message)
    character(len=*), intent(in) :: context
    integer, intent(in) :: status
    character(len=message_len), intent(inout) :: message
    if (status == SD_OK) return
    if (status == SD_BAD_INPUT) then
      message = context//': '//trim(message)
    else
      message = context//': '//status_name(status)//': '//trim(message)
    end if
  end subroutine in_context

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
                           k(2, 2)], [9, 1]), status, message)
    if (status /= SD_OK) return
    allocate (rows(14, n_eq))
    do i = 1, n_eq
      rows(1:6, i) = [theta(i), phi(i), theta(i)/model%theta0, phi(i)/model%theta0, &
                      merge(1.0_wp, 0.0_wp, physical(i)), real(verdict(i), wp)]
      rows(7:14, i) = [(eig_re(j, i), eig_im(j, i), j = 1, 4)]
    end do
    call files%write_table('equilibria.csv', 'equilibria', rows, status, message)
    if (status /= SD_OK) return
    call files%write_table('routh_hurwitz.csv', 'routh_hurwitz', reshape([rh_coefficients, &
                           hurwitz(2:3), merge(1.0_wp, 0.0_wp, routh_stable), &
                           real(verdict(trivial), wp)], [8, 1]), status, message)
    if (status /= SD_OK) return
    call files%write_table('kappa_31.csv', 'kappa_31', reshape([(config%sigma1, &
                           kappa_roots(i), i = 1, n_kappa)], [2, n_kappa]), status, message)
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
      call time_history(config%model, 0.0_wp, sim%y0, tau, config%integration, config%method, &
                        history(2:, :), stats, status, message)
      call in_context('simulation', status, message)
      if (status /= SD_OK) return
      print '(/a)', 'Simulation ('//method_name(config%method)//', eq 15 with 29-31) from '// &
                    'tau = 0 to '//num2str(sim%t_end)
    end associate
    print '(a)', '  steps accepted '//num2str(stats%n_accepted)//', rejected '// &
                 num2str(stats%n_rejected)//', right-hand sides '//num2str(stats%n_rhs)
    print '(a)', '  max|x1| = '//num2str(maxval(abs(history(2, :))))//', max|x2| = '// &
                 num2str(maxval(abs(history(4, :))))//' at the output times'
    call begin_files(config, files, status, message)
    if (status == SD_OK) call files%write_table('history.csv', 'history', history, status, &
                                                message)
    if (status == SD_OK) call files%write_table('simulation.csv', 'simulation', &
                                                reshape(counts_array(stats), [4, 1]), status, message)
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
    allocate (poincare(4, window), rows(5, window))
    call steady_state(config%model, config%simulation%y0, config%integration, config%method, &
                      config%steady, summary, poincare, y_end, stats, status, message)
    call in_context('steady state', status, message)
    if (status /= SD_OK) return
    print '(/a)', 'Steady state ('//method_name(config%method)//') at rho = '// &
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
    real(wp), allocatable :: values(:), summaries(:, :)
    real(wp) :: y(4), y_next(4)
    integer :: first, last, i, n_done, step, status_rows
    character(len=:), allocatable :: name, how
    character(len=message_len) :: message_rows

    associate (sw => config%sweep)
      values = sweep_points(min(sw%start, sw%stop), max(sw%start, sw%stop), sw%n_points, &
                            sw%direction)
      name = trim(merge('rho', 'A  ', sw%parameter == PARAMETER_RHO))
      how = 'each from the previous final state'
      if (.not. sw%carry_state) how = 'each from y0, '//num2str(sw%threads)//' thread(s)'
      print '(/a)', 'Sweep in '//name//' ('//trim(direction_names(sw%direction))//', '// &
                    num2str(size(values))//' points), '//how
      ! one point per call when the state is carried, four per thread otherwise (threads that
      ! finish early take the next point), so progress shows as the sweep runs
      step = merge(1, 4*sw%threads, sw%carry_state)
    end associate
    allocate (summaries(SUMMARY_SIZE, size(values)))
    ! the points go to sweep.partial.csv as they finish: a failed or killed sweep keeps them
    call begin_files(config, files, status, message)
    if (status == SD_OK) call files%begin_rows('sweep.csv', 'summary', status, message)
    if (status /= SD_OK) return
    print '(a)', '  (points are written to '//files%partial_path('sweep.csv')//' as they '// &
                 'finish; renamed to sweep.csv when the sweep is complete)'
    print '(a)', '  '//pad(name, 14)//pad('max|x1|', 14)//pad('max|x2|', 14)// &
                 pad('max|u1|', 14)//pad('max|u2|', 14)//'motion'
    flush (output_unit)
    y = config%simulation%y0
    do first = 1, size(values), step
      last = min(first + step - 1, size(values))
      if (config%sweep%carry_state) then
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
                  ' points completed are kept in '//files%partial_path('sweep.csv')
        return
      end if
      do i = first, last
        print '(a)', '  '//pad(num2str(values(i)), 14)// &
                     pad(num2str(summaries(SUMMARY_MAX_X1, i)), 14)// &
                     pad(num2str(summaries(SUMMARY_MAX_X2, i)), 14)// &
                     pad(num2str(summaries(SUMMARY_MAX_U1, i)), 14)// &
                     pad(num2str(summaries(SUMMARY_MAX_U2, i)), 14)// &
                     motion_text(summaries(SUMMARY_MOTION, i), summaries(SUMMARY_PERIOD, i))
      end do
      flush (output_unit)
    end do
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
      name = trim(merge('rho', 'A  ', r%parameter == PARAMETER_RHO))
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
  !> A from the steady state reached from y0 at the start of the range.
  subroutine run_periodic(config, files, status, message)
    type(run_config), intent(in) :: config
    type(result_files), intent(inout) :: files
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), allocatable :: points(:, :), multipliers(:, :), special(:, :)
    integer :: n_points, n_special, i, capacity
    logical :: complete
    character(len=:), allocatable :: name

    associate (r => config%response)
      capacity = r%options%continuation%max_points
      allocate (points(7, capacity), multipliers(8, capacity), special(7, 100))
      call periodic_response_from_rest(config%model, r%parameter, config%simulation%y0, &
                                       r%start, r%stop, config%steady, r%options%continuation, &
                                       config%integration, config%method, points, multipliers, &
                                       n_points, special, n_special, complete, status, message)
      call in_context('periodic response', status, message)
      if (status /= SD_OK) return
      name = trim(merge('rho', 'A  ', r%parameter == PARAMETER_RHO))
      print '(/a)', 'Periodic orbits of the full equations (shooting, Floquet multipliers; '// &
                    method_name(config%method)//') for '//name//' in ['//num2str(r%start)// &
                    ', '//num2str(r%stop)//']'
    end associate
    print '(a)', '  '//num2str(n_points)//' orbits; special points:'
    do i = 1, n_special
      print '(a)', '  '//pad(special_kind_name(nint(special(1, i))), 16)//name//' = '// &
                   pad(num2str(special(2, i)), 14)//'max|x1| = '//num2str(special(7, i))
    end do
    call begin_files(config, files, status, message)
    if (status == SD_OK) call files%write_table('periodic_branch.csv', 'periodic_branch', &
                                                reshape([(points(:, i), multipliers(:, i), &
                                                i = 1, n_points)], [15, n_points]), status, &
                                                message)
    if (status == SD_OK) call files%write_table('periodic_special_points.csv', &
                                                'periodic_special_points', &
                                                special(:, 1:n_special), status, message)
  end subroutine run_periodic

  !> Largest Lyapunov exponent from y0 with its running estimates.
  subroutine run_lyapunov(config, files, status, message)
    type(run_config), intent(in) :: config
    type(result_files), intent(inout) :: files
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), allocatable :: history(:)
    real(wp) :: exponent
    integer :: i

    associate (ly => config%lyapunov)
      allocate (history(ly%n_periods/ly%renormalise_every))
      call lyapunov_exponent(config%model, config%simulation%y0, ly%transient_periods, &
                             ly%n_periods, ly%renormalise_every, config%integration, &
                             config%method, exponent, history, status, message)
      call in_context('Lyapunov exponent', status, message)
      if (status /= SD_OK) return
      print '(/a)', 'Largest Lyapunov exponent (per unit tau; '//method_name(config%method)// &
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

  !> Create the output directory (only once the analysis succeeded) and write the parameters.
  subroutine begin_files(config, files, status, message)
    type(run_config), intent(in) :: config
    type(result_files), intent(inout) :: files
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    call files%create(config%directory, status, message)
    if (status /= SD_OK) return
    associate (m => config%model)
      call files%write_table('parameters.csv', 'parameters', reshape([m%s1, m%mu1, m%kappa, &
                             m%theta0, m%beta, m%gamma, m%delta, real(m%n, wp), real(m%p, wp), &
                             m%excitation%A, m%excitation%rho, m%a_coef, m%b_coef], [23, 1]), &
                             status, message)
    end associate
    if (status /= SD_OK .or. .not. config%dimensional) return
    associate (t => config%tank)
      call files%write_table('tank.csv', 'tank', reshape([t%radius, t%depth, t%liquid_mass, &
                             t%pendulum_length, t%sloshing_mass, t%d1, t%rigid_mass, t%d0, &
                             t%total_mass, t%rod_length, t%gravity, &
                             sqrt(t%gravity/t%pendulum_length)], [12, 1]), status, message)
    end associate
  end subroutine begin_files

  subroutine print_model(config)
    type(run_config), intent(in) :: config
    print '(a)', 'sloshdyn: '//trim(known_analyses(config%analysis))
    if (config%dimensional) then
      associate (t => config%tank)
        print '(/a)', 'Tank (eq 2-3): R = '//num2str(t%radius)//' m, h = '//num2str(t%depth)// &
                      ' m, liquid mass m_F = '//num2str(t%liquid_mass)//' kg'
        print '(a)', '  pendulum l = '//num2str(t%pendulum_length)//' m, m = '// &
                     num2str(t%sloshing_mass)//' kg, d1 = '//num2str(t%d1)//' m; rigid m0 = '// &
                     num2str(t%rigid_mass)//' kg, d0 = '//num2str(t%d0)//' m'
        print '(a)', '  pendulum frequency omega = sqrt(g/l) = '// &
                     num2str(sqrt(t%gravity/t%pendulum_length))//' rad/s'
      end associate
    end if
    associate (m => config%model)
      print '(/a)', 'Dimensionless model (eq 9): s1 = '//num2str(m%s1)//', mu1 = '// &
                    num2str(m%mu1)//', kappa = '//num2str(m%kappa)//', theta0 = '// &
                    num2str(m%theta0)//' rad'
      print '(a)', '  beta = '//num2str(m%beta)//', gamma = '//num2str(m%gamma)//', delta = '// &
                   num2str(m%delta)//', n = '//num2str(m%n)//', p = '//num2str(m%p)// &
                   ', kappa_hat = kappa/s1 = '//num2str(m%kappa/m%s1)
      print '(a)', '  excitation X = A sin(rho tau): A = '//num2str(m%excitation%A)// &
                   ', rho = '//num2str(m%excitation%rho)
      print '(a)', '  a1..a6 (eq 11) = '//list(m%a_coef)
      print '(a)', '  b1..b6 (eq 11) = '//list(m%b_coef)
    end associate
  end subroutine print_model

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

  pure function pad(text, width) result(padded)
    character(len=*), intent(in) :: text
    integer, intent(in) :: width
    character(len=max(width, len(text) + 1)) :: padded
    padded = text
  end function pad
end module sloshdyn_driver
