!> The `sloshdyn` executable: reads a namelist input file, validates all of it, runs the requested
!> analysis, prints a summary and writes CSV files (header line, one quantity per column) into the
!> output directory. The only place that turns a status into an exit code.
program sloshdyn_main
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, status_name
  use sloshdyn_text, only: num2str
  use sloshdyn_model, only: model_t
  use sloshdyn_namelist, only: run_config, read_input
  use sloshdyn_linear, only: stiffness_matrix, natural_frequencies, natural_frequencies_eig, &
                             kappa_for_detuning
  use sloshdyn_equilibria, only: equilibria, trivial_routh_hurwitz, STABLE, MARGINAL
  use sloshdyn_files, only: make_directory, rename_file
  use sloshdyn_rk45, only: rk45_stats
  use sloshdyn_simulation, only: history_rows, time_history, steady_state, parameter_sweep, &
                                 summary_size, SWEEP_RHO, SWEEP_A
  use sloshdyn_status, only: SD_BAD_INPUT
  use sloshdyn_response, only: frequency_response, point_rows, special_rows, SPECIAL_FOLD
  use sloshdyn_slowflow, only: PARAMETER_RHO, PARAMETER_A
  use sloshdyn_periodic, only: tank_periodic_problem, shooting_newton, periodic_branch, &
                               largest_lyapunov
  use sloshdyn_continuation, only: continuation_options
  implicit none

  integer, parameter :: max_equilibria = 4096, max_kappa_roots = 64
  integer, parameter :: exit_usage = 2, exit_input = 3, exit_failure = 4
  character(len=*), parameter :: usage = 'usage: sloshdyn INPUT.nml   (see README.md for the '// &
                                         'namelist groups and variables)'
  character(len=4096) :: path
  character(len=message_len) :: message
  type(run_config) :: config
  integer :: status
  character(len=4200) :: pending(16)   !< result files written under temporary names
  integer :: n_pending

  if (command_argument_count() /= 1) call die(exit_usage, usage)
  call get_command_argument(1, path)
  if (path == '-h' .or. path == '--help') then
    print '(a)', usage
    stop
  end if
  call read_input(trim(path), config, status, message)
  if (status /= SD_OK) call die(exit_input, trim(message))

  n_pending = 0
  call print_model(config)
  select case (config%analysis)
  case ('linear')
    call run_linear(config)
  case ('simulate')
    call run_simulate(config)
  case ('steady_state')
    call run_steady_state(config)
  case ('sweep')
    call run_sweep(config)
  case ('frequency_response')
    call run_response(config)
  case ('periodic_response')
    call run_periodic(config)
  case ('lyapunov')
    call run_lyapunov(config)
  end select

contains

  subroutine die(code, text)
    integer, intent(in) :: code
    character(len=*), intent(in) :: text
    write (0, '(a)') 'sloshdyn: error: '//text
    stop code, quiet=.true.
  end subroutine die

  subroutine check(status, message, context)
    integer, intent(in) :: status
    character(len=*), intent(in) :: message, context
    if (status == SD_BAD_INPUT) call die(exit_input, context//': '//trim(message))
    if (status /= SD_OK) call die(exit_failure, context//': '//status_name(status)//': '//trim(message))
  end subroutine check

  !> Linear analysis (sec 3.1-3.2): coefficients, natural frequencies, equilibria with their
  !> eigenvalues and verdicts, Routh-Hurwitz at the trivial equilibrium, kappa for 3:1.
  subroutine run_linear(config)
    type(run_config), intent(in) :: config
    type(model_t) :: model
    real(wp) :: omega1, omega2, omega1_eig, omega2_eig, k(2, 2)
    real(wp), allocatable :: theta(:), phi(:), eig_re(:, :), eig_im(:, :)
    real(wp) :: rh_coefficients(4), hurwitz(4), kappa_roots(max_kappa_roots)
    integer, allocatable :: verdict(:)
    logical, allocatable :: physical(:)
    integer :: n_eq, n_kappa, i, j, trivial, unit
    logical :: truncated, routh_stable
    character(len=:), allocatable :: dir

    allocate (theta(max_equilibria), phi(max_equilibria), eig_re(4, max_equilibria), &
              eig_im(4, max_equilibria), verdict(max_equilibria), physical(max_equilibria))
    model = config%model
    call natural_frequencies(model, omega1, omega2, status, message)
    call check(status, message, 'natural frequencies (eq 28)')
    call natural_frequencies_eig(model, omega1_eig, omega2_eig, status, message)
    call check(status, message, 'natural frequencies (dgeev)')
    k = stiffness_matrix(model)
    call equilibria(model, theta, phi, physical, eig_re, eig_im, verdict, n_eq, truncated, &
                    status, message)
    call check(status, message, 'equilibria (eq 16-18)')
    call trivial_routh_hurwitz(model, rh_coefficients, hurwitz, routh_stable)
    trivial = findloc(theta(1:n_eq) == 0 .and. phi(1:n_eq) == 0, .true., dim=1)
    call kappa_for_detuning(model%s1, model%mu1, config%sigma1, config%kappa_min, &
                            config%kappa_max, kappa_roots, n_kappa, status, message)
    call check(status, message, 'kappa for 3:1 internal resonance (eq 51)')

    ! summary
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
                   pad(trim(merge('physical    ', 'non-physical', physical(i))), 13)// &
                   pad(verdict_name(verdict(i)), 9)//eigen_text(eig_re(:, i), eig_im(:, i))
    end do
    if (truncated) print '(a)', '  (roots beyond |angle| = 32 pi were not searched)'
    print '(/a)', 'Routh-Hurwitz at the trivial equilibrium (eq 20):'
    print '(a)', '  c1..c4 = '//num2str(rh_coefficients(1))//', '//num2str(rh_coefficients(2))// &
                 ', '//num2str(rh_coefficients(3))//', '//num2str(rh_coefficients(4))// &
                 '; Delta2 = '//num2str(hurwitz(2))//', Delta3 = '//num2str(hurwitz(3))
    print '(a)', '  Routh-Hurwitz: '//trim(merge('stable    ', 'not stable', routh_stable))// &
                 '; eigenvalues: '//verdict_name(verdict(trivial))
    print '(/a)', 'kappa giving omega2 - 3 omega1 = sigma1 = '//num2str(config%sigma1)// &
                  ' (eq 51) for kappa in ('//num2str(max(config%kappa_min, model%s1))//', '// &
                  num2str(config%kappa_max)//']:'
    if (n_kappa == 0) print '(a)', '  none'
    do i = 1, n_kappa
      print '(a)', '  kappa = '//num2str(kappa_roots(i))
    end do

    ! CSV files, renamed into place only when all are written
    dir = output_directory(config)
    call write_parameters(config, dir)
    call open_csv(dir, 'frequencies.csv', unit)
    write (unit, '(a)') 'omega1,omega2,omega1_dgeev,omega2_dgeev,ratio,k11,k12,k21,k22'
    write (unit, '(*(es24.16e3, :, ","))') omega1, omega2, omega1_eig, omega2_eig, &
      omega2/omega1, k(1, 1), -k(1, 2), -k(2, 1), k(2, 2)
    close (unit)
    call open_csv(dir, 'equilibria.csv', unit)
    write (unit, '(a)') 'theta,phi,x1,x2,physical,verdict,re1,im1,re2,im2,re3,im3,re4,im4'
    do i = 1, n_eq
      write (unit, '(2(es24.16e3, ","), 2(es24.16e3, ","), i0, ",", a, ",", *(es24.16e3, :, ","))') &
        theta(i), phi(i), theta(i)/model%theta0, phi(i)/model%theta0, merge(1, 0, physical(i)), &
        verdict_name(verdict(i)), (eig_re(j, i), eig_im(j, i), j = 1, 4)
    end do
    close (unit)
    call open_csv(dir, 'routh_hurwitz.csv', unit)
    write (unit, '(a)') 'c1,c2,c3,c4,delta2,delta3,routh_stable,eigenvalue_verdict'
    write (unit, '(6(es24.16e3, ","), i0, ",", a)') rh_coefficients, hurwitz(2:3), &
      merge(1, 0, routh_stable), verdict_name(verdict(trivial))
    close (unit)
    call open_csv(dir, 'kappa_31.csv', unit)
    write (unit, '(a)') 'sigma1,kappa'
    do i = 1, n_kappa
      write (unit, '(es24.16e3, ",", es24.16e3)') config%sigma1, kappa_roots(i)
    end do
    close (unit)
    call commit_files(dir)
  end subroutine run_linear

  !> Time history from y0 at tau = 0 to t_end, n_out evenly spaced outputs (RK45, dense output).
  subroutine run_simulate(config)
    type(run_config), intent(in) :: config
    real(wp), allocatable :: tau(:), history(:, :)
    type(rk45_stats) :: stats
    integer :: i, unit
    character(len=:), allocatable :: dir

    allocate (tau(config%n_out), history(history_rows, config%n_out))
    tau = [(config%t_end*(i - 1)/(config%n_out - 1), i = 1, config%n_out)]
    call time_history(config%model, 0.0_wp, config%y0, tau, config%integration, config%method, &
                      history, stats, status, message)
    call check(status, message, 'simulation')
    print '(/a)', 'Simulation (RK45, eq 15 with 29-31) from tau = 0 to '//num2str(config%t_end)
    print '(a)', '  steps accepted '//num2str(stats%n_accepted)//', rejected '// &
                 num2str(stats%n_rejected)//', right-hand sides '//num2str(stats%n_rhs)
    print '(a)', '  max|x1| = '//num2str(maxval(abs(history(1, :))))//', max|x2| = '// &
                 num2str(maxval(abs(history(3, :))))//' at the output times'
    dir = output_directory(config)
    call write_parameters(config, dir)
    call open_csv(dir, 'history.csv', unit)
    write (unit, '(a)') 'tau,x1,dx1,x2,dx2,u1,u2,impact_force,theta,phi'
    do i = 1, config%n_out
      write (unit, '(*(es24.16e3, :, ","))') tau(i), history(:, i)
    end do
    close (unit)
    call open_csv(dir, 'simulation.csv', unit)
    write (unit, '(a)') 'n_rhs,n_accepted,n_rejected,tau_reached'
    write (unit, '(3(i0, ","), es24.16e3)') stats%n_rhs, stats%n_accepted, stats%n_rejected, &
      stats%t_reached
    close (unit)
    call commit_files(dir)
  end subroutine run_simulate

  !> Steady state at (rho, A) from y0: amplitudes, kind of motion and Poincare points.
  subroutine run_steady_state(config)
    type(run_config), intent(in) :: config
    real(wp) :: summary(summary_size), y_end(4)
    real(wp), allocatable :: poincare(:, :)
    type(rk45_stats) :: stats
    integer :: i, unit
    character(len=:), allocatable :: dir

    allocate (poincare(4, config%steady%window_periods))
    call steady_state(config%model, config%y0, config%integration, config%method, config%steady, &
                      summary, poincare, y_end, stats, status, message)
    call check(status, message, 'steady state')
    print '(/a)', 'Steady state (RK45) at rho = '//num2str(summary(1))//', A = '//num2str(summary(2))
    call print_summary(summary)
    print '(a)', '  steps accepted '//num2str(stats%n_accepted)//', rejected '// &
                 num2str(stats%n_rejected)//', right-hand sides '//num2str(stats%n_rhs)
    dir = output_directory(config)
    call write_parameters(config, dir)
    call open_csv(dir, 'steady_state.csv', unit)
    call write_summary_header(unit)
    write (unit, '(*(es24.16e3, :, ","))') summary
    close (unit)
    call open_csv(dir, 'poincare.csv', unit)
    write (unit, '(a)') 'tau,x1,dx1,x2,dx2'
    do i = 1, config%steady%window_periods
      write (unit, '(*(es24.16e3, :, ","))') (summary(9) + i)*2*acos(-1.0_wp)/config%model%rho, &
        poincare(:, i)
    end do
    close (unit)
    call commit_files(dir)
  end subroutine run_steady_state

  !> Steady states along rho or A, each from the previous final state; a line per point.
  subroutine run_sweep(config)
    type(run_config), intent(in) :: config
    real(wp), allocatable :: values(:), summaries(:, :)
    real(wp) :: y(4), y_next(4), lower, upper
    integer :: i, n, n_done, unit, which
    character(len=:), allocatable :: dir

    n = config%sweep_points
    lower = min(config%sweep_start, config%sweep_stop)
    upper = max(config%sweep_start, config%sweep_stop)
    allocate (values(merge(2*n - 1, n, config%sweep_direction == 'both')))
    values(1:n) = [(lower + (upper - lower)*(i - 1)/max(n - 1, 1), i = 1, n)]
    if (config%sweep_direction == 'down') values = values(n:1:-1)
    if (config%sweep_direction == 'both') values(n + 1:) = values(n - 1:1:-1)
    which = merge(SWEEP_RHO, SWEEP_A, config%sweep_parameter == 'rho')
    allocate (summaries(summary_size, size(values)))
    print '(/a)', 'Sweep in '//trim(config%sweep_parameter)//' ('//trim(config%sweep_direction)// &
                  ', '//num2str(size(values))//' points), each from the previous final state'
    print '(a)', '  '//pad(trim(config%sweep_parameter), 14)//pad('max|x1|', 14)// &
                 pad('max|x2|', 14)//pad('max|u1|', 14)//pad('max|u2|', 14)//'motion'
    y = config%y0
    do i = 1, size(values)
      ! one point per call, so progress shows as the sweep runs
      call parameter_sweep(config%model, which, values(i:i), y, config%integration, config%method, &
                           config%steady, summaries(:, i:i), y_next, n_done, status, message)
      call check(status, message, 'sweep')
      y = y_next
      print '(a)', '  '//pad(num2str(values(i)), 14)//pad(num2str(summaries(3, i)), 14)// &
                   pad(num2str(summaries(4, i)), 14)//pad(num2str(summaries(5, i)), 14)// &
                   pad(num2str(summaries(6, i)), 14)//motion_name(summaries(7, i), summaries(8, i))
      flush (6)
    end do
    dir = output_directory(config)
    call write_parameters(config, dir)
    call open_csv(dir, 'sweep.csv', unit)
    call write_summary_header(unit)
    do i = 1, size(values)
      write (unit, '(*(es24.16e3, :, ","))') summaries(:, i)
    end do
    close (unit)
    call commit_files(dir)
  end subroutine run_sweep

  !> Slow-flow frequency response (sec 3.3): branches, stability, folds and Hopf points.
  !> An incomplete branch is an error: nothing is written.
  subroutine run_response(config)
    type(run_config), intent(in) :: config
    real(wp), allocatable :: table(:, :), special(:, :)
    integer :: n_points, n_special, i, unit
    logical :: complete
    character(len=:), allocatable :: dir, name

    allocate (table(point_rows, 20000), special(special_rows, 200))
    call frequency_response(config%model, config%internal_resonance, &
                            merge(PARAMETER_RHO, PARAMETER_A, config%sweep_parameter == 'rho'), &
                            config%sweep_start, config%sweep_stop, config%response, table, &
                            n_points, special, n_special, complete, status, message)
    call check(status, message, 'frequency response')
    name = trim(config%sweep_parameter)
    print '(/a)', 'Slow-flow frequency response ('//trim(merge('3:1 internal resonance', &
                  'no internal resonance ', config%internal_resonance))//') for '//name// &
                  ' in ['//num2str(config%sweep_start)//', '//num2str(config%sweep_stop)//']'
    print '(a)', '  '//num2str(nint(maxval(table(1, 1:n_points))))//' branches, '// &
                 num2str(n_points)//' points; special points:'
    do i = 1, n_special
      print '(a)', '  '//pad(trim(merge('fold', 'Hopf', nint(special(1, i)) == SPECIAL_FOLD)), 6)// &
                   name//' = '//pad(num2str(special(3, i)), 14)//'|u1| = '// &
                   pad(num2str(special(6, i)), 14)//'|u2| = '//pad(num2str(special(7, i)), 14)// &
                   hopf_frequency(special(:, i))
    end do
    dir = output_directory(config)
    call write_parameters(config, dir)
    call open_csv(dir, 'response.csv', unit)
    write (unit, '(a)') 'branch,lambda,rho,A,a1,a2,phi1,phi2,stable,special,re1,re2,re3,re4,'// &
                        'im1,im2,im3,im4,C1,C2,C3,C4,delta2,delta3,re_B1,im_B1,re_B2,im_B2'
    do i = 1, n_points
      write (unit, '(*(es24.16e3, :, ","))') table(:, i)
    end do
    close (unit)
    call open_csv(dir, 'special_points.csv', unit)
    write (unit, '(a)') 'kind,branch,lambda,rho,A,a1,a2,frequency'
    do i = 1, n_special
      write (unit, '(a, ",", *(es24.16e3, :, ","))') &
        trim(merge('fold', 'hopf', nint(special(1, i)) == SPECIAL_FOLD)), special(2:8, i)
    end do
    close (unit)
    call commit_files(dir)
  end subroutine run_response

  !> Periodic orbits of the full equations (shooting, Floquet multipliers) continued in rho or
  !> A from the steady state reached from y0 at the start of the range.
  subroutine run_periodic(config)
    type(run_config), intent(in) :: config
    type(tank_periodic_problem) :: problem
    type(continuation_options) :: options
    real(wp), allocatable :: points(:, :), multipliers(:, :), special(:, :), poincare(:, :)
    real(wp) :: summary(summary_size), y_start(4), y_orbit(4), monodromy(4, 4), re(4), im(4), peak
    type(rk45_stats) :: stats
    integer :: n_points, n_special, iterations, i, unit
    logical :: complete
    character(len=:), allocatable :: dir, name
    character(len=*), parameter :: kinds(4) = [character(len=15) :: 'fold', 'branch_point', &
                                              'period_doubling', 'neimark_sacker']

    name = trim(config%sweep_parameter)
    problem%model = config%model
    problem%which = merge(SWEEP_RHO, SWEEP_A, name == 'rho')
    if (name == 'rho') then
      problem%model%rho = config%sweep_start
    else
      problem%model%A = config%sweep_start
    end if
    allocate (poincare(4, config%steady%window_periods), points(7, 4000), multipliers(8, 4000), &
              special(7, 100))
    call steady_state(problem%model, config%y0, config%integration, config%method, &
                      config%steady, summary, poincare, y_start, stats, status, message)
    call check(status, message, 'periodic response: start (steady state)')
    call shooting_newton(problem, y_start, 1, config%integration, 1.0e-10_wp, 30, y_orbit, &
                         monodromy, re, im, iterations, status, message, peak)
    call check(status, message, 'periodic response: start (shooting)')
    options%ds = config%response%continuation%ds
    options%ds_min = config%response%continuation%ds_min
    options%ds_max = config%response%continuation%ds_max
    options%x_scale = config%response%continuation%x_scale
    options%max_points = size(points, 2)
    call periodic_branch(problem, y_orbit, config%sweep_start, config%sweep_stop, options, &
                         config%integration, points, multipliers, n_points, special, n_special, &
                         complete, status, message)
    call check(status, message, 'periodic response')
    print '(/a)', 'Periodic orbits of the full equations (shooting, Floquet multipliers) for '// &
                  name//' in ['//num2str(config%sweep_start)//', '//num2str(config%sweep_stop)//']'
    print '(a)', '  '//num2str(n_points)//' orbits; special points:'
    do i = 1, n_special
      print '(a)', '  '//pad(trim(kinds(nint(special(1, i)))), 16)//name//' = '// &
                   pad(num2str(special(2, i)), 14)//'max|x1| = '//num2str(special(7, i))
    end do
    dir = output_directory(config)
    call write_parameters(config, dir)
    call open_csv(dir, 'periodic_branch.csv', unit)
    write (unit, '(a)') 'lambda,y1,y2,y3,y4,max_x1,stable,re_mu1,re_mu2,re_mu3,re_mu4,'// &
                        'im_mu1,im_mu2,im_mu3,im_mu4'
    do i = 1, n_points
      write (unit, '(*(es24.16e3, :, ","))') points(:, i), multipliers(:, i)
    end do
    close (unit)
    call open_csv(dir, 'periodic_special_points.csv', unit)
    write (unit, '(a)') 'kind,lambda,y1,y2,y3,y4,max_x1'
    do i = 1, n_special
      write (unit, '(a, ",", *(es24.16e3, :, ","))') trim(kinds(nint(special(1, i)))), special(2:7, i)
    end do
    close (unit)
    call commit_files(dir)
  end subroutine run_periodic

  !> Largest Lyapunov exponent from y0 with its running estimates.
  subroutine run_lyapunov(config)
    type(run_config), intent(in) :: config
    type(tank_periodic_problem) :: problem
    real(wp), allocatable :: history(:)
    real(wp) :: exponent
    integer :: i, unit
    character(len=:), allocatable :: dir

    problem%model = config%model
    allocate (history(config%lyapunov_periods/config%lyapunov_every))
    call largest_lyapunov(problem, config%y0, config%lyapunov_transient, config%lyapunov_periods, &
                          config%lyapunov_every, config%integration, exponent, history, status, &
                          message)
    call check(status, message, 'Lyapunov exponent')
    print '(/a)', 'Largest Lyapunov exponent (per unit tau) = '//num2str(exponent)
    print '(a)', '  running estimate at 1/4, 1/2, 3/4 of the run: '// &
                 num2str(history(max(1, size(history)/4)))//', '// &
                 num2str(history(max(1, size(history)/2)))//', '// &
                 num2str(history(max(1, 3*size(history)/4)))
    dir = output_directory(config)
    call write_parameters(config, dir)
    call open_csv(dir, 'lyapunov.csv', unit)
    write (unit, '(a)') 'periods,estimate'
    do i = 1, size(history)
      write (unit, '(i0, ",", es24.16e3)') i*config%lyapunov_every, history(i)
    end do
    close (unit)
    call commit_files(dir)
  end subroutine run_lyapunov

  pure function hopf_frequency(point) result(text)
    real(wp), intent(in) :: point(:)
    character(len=:), allocatable :: text
    text = ''
    if (nint(point(1)) /= SPECIAL_FOLD) text = 'frequency sqrt(C3/C1) = '//num2str(point(8))
  end function hopf_frequency

  subroutine print_summary(summary)
    real(wp), intent(in) :: summary(summary_size)
    print '(a)', '  max|x1| = '//num2str(summary(3))//', max|x2| = '//num2str(summary(4))// &
                 ', max|u1| = '//num2str(summary(5))//', max|u2| = '//num2str(summary(6))
    print '(a)', '  motion: '//motion_name(summary(7), summary(8))//' (Poincare spread '// &
                 num2str(summary(10))//'); transient '//num2str(summary(9))//' periods'// &
                 trim(merge('                           ', ', not settled to settle_tol', &
                 summary(11) > 0))
  end subroutine print_summary

  subroutine write_summary_header(unit)
    integer, intent(in) :: unit
    write (unit, '(a)') 'rho,A,max_x1,max_x2,max_u1,max_u2,motion,period,transient_periods,'// &
                        'spread,settled'
  end subroutine write_summary_header

  pure function motion_name(code, period) result(name)
    real(wp), intent(in) :: code, period
    character(len=:), allocatable :: name
    select case (nint(code))
    case (1)
      name = 'periodic (period '//num2str(nint(period))//' T)'
    case (2)
      name = 'quasi-periodic'
    case (4)
      name = 'settling (lengthen the transient)'
    case default
      name = 'irregular'
    end select
  end function motion_name

  !> Create the output directory (only once all input is known to be valid).
  function output_directory(config) result(dir)
    type(run_config), intent(in) :: config
    character(len=:), allocatable :: dir
    logical :: created
    dir = trim(config%directory)
    call make_directory(dir, created)
    if (.not. created) call die(exit_failure, 'cannot create output directory '''//dir//'''')
  end function output_directory

  subroutine print_model(config)
    type(run_config), intent(in) :: config
    associate (m => config%model)
      print '(a)', 'sloshdyn: '//trim(config%analysis)
      if (config%dimensional) then
        print '(/a)', 'Tank (eq 2-3): R = '//num2str(config%radius)//' m, h = '// &
                      num2str(config%depth)//' m, liquid mass m_F = '//num2str(config%liquid_mass)//' kg'
        print '(a)', '  pendulum l = '//num2str(config%pendulum_length)//' m, m = '// &
                     num2str(config%sloshing_mass)//' kg, d1 = '//num2str(config%d1)// &
                     ' m; rigid m0 = '//num2str(config%rigid_mass)//' kg, d0 = '// &
                     num2str(config%d0)//' m'
        print '(a)', '  pendulum frequency omega = sqrt(g/l) = '// &
                     num2str(sqrt(config%gravity/config%pendulum_length))//' rad/s'
      end if
      print '(/a)', 'Dimensionless model (eq 9): s1 = '//num2str(m%s1)//', mu1 = '// &
                    num2str(m%mu1)//', kappa = '//num2str(m%kappa)//', theta0 = '// &
                    num2str(m%theta0)//' rad'
      print '(a)', '  beta = '//num2str(m%beta)//', gamma = '//num2str(m%gamma)//', delta = '// &
                   num2str(m%delta)//', n = '//num2str(m%n)//', p = '//num2str(m%p)// &
                   ', kappa_hat = kappa/s1 = '//num2str(m%kappa/m%s1)
      print '(a)', '  excitation X = A sin(rho tau): A = '//num2str(m%A)//', rho = '//num2str(m%rho)
      print '(a)', '  a1..a6 (eq 11) = '//list(m%a_coef)
      print '(a)', '  b1..b6 (eq 11) = '//list(m%b_coef)
    end associate
  end subroutine print_model

  subroutine write_parameters(config, dir)
    type(run_config), intent(in) :: config
    character(len=*), intent(in) :: dir
    integer :: unit
    call open_csv(dir, 'parameters.csv', unit)
    write (unit, '(a)') 's1,mu1,kappa,theta0,beta,gamma,delta,n,p,A,rho,'// &
                        'a1,a2,a3,a4,a5,a6,b1,b2,b3,b4,b5,b6'
    associate (m => config%model)
      write (unit, '(7(es24.16e3, ","), 2(i0, ","), *(es24.16e3, :, ","))') m%s1, m%mu1, &
        m%kappa, m%theta0, m%beta, m%gamma, m%delta, m%n, m%p, m%A, m%rho, m%a_coef, m%b_coef
    end associate
    close (unit)
    if (.not. config%dimensional) return
    call open_csv(dir, 'tank.csv', unit)
    write (unit, '(a)') 'R,h,m_liquid,l,m,d1,m0,d0,M,L,g,omega'
    write (unit, '(*(es24.16e3, :, ","))') config%radius, config%depth, config%liquid_mass, &
      config%pendulum_length, config%sloshing_mass, config%d1, config%rigid_mass, config%d0, &
      config%total_mass, config%rod_length, config%gravity, &
      sqrt(config%gravity/config%pendulum_length)
    close (unit)
  end subroutine write_parameters

  !> Open `dir/.name.tmp` for writing and remember it for commit_files.
  subroutine open_csv(dir, name, unit)
    character(len=*), intent(in) :: dir, name
    integer, intent(out) :: unit
    integer :: ios
    character(len=message_len) :: iomsg
    open (newunit=unit, file=dir//'/.'//name//'.tmp', status='replace', action='write', &
          iostat=ios, iomsg=iomsg)
    if (ios /= 0) call die(exit_failure, 'cannot write '//dir//'/'//name//': '//trim(iomsg))
    n_pending = n_pending + 1
    pending(n_pending) = dir//'/'//name
  end subroutine open_csv

  subroutine commit_files(dir)
    character(len=*), intent(in) :: dir
    integer :: i, slash
    logical :: ok
    character(len=:), allocatable :: final
    do i = 1, n_pending
      final = trim(pending(i))
      slash = index(final, '/', back=.true.)
      call rename_file(final(1:slash)//'.'//final(slash + 1:)//'.tmp', final, ok)
      if (.not. ok) call die(exit_failure, 'cannot rename into '//final)
    end do
    print '(/a)', 'Results written to '//dir//'/'
  end subroutine commit_files

  pure function verdict_name(verdict) result(name)
    integer, intent(in) :: verdict
    character(len=:), allocatable :: name
    if (verdict == STABLE) then
      name = 'stable'
    else if (verdict == MARGINAL) then
      name = 'marginal'
    else
      name = 'unstable'
    end if
  end function verdict_name

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
end program sloshdyn_main
