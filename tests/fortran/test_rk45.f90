!> DOPRI5 on the test systems of rk_checks, with closed-form solutions: the independent source
!> of every expected value below.
program test_rk45
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK
  use sloshdyn_text, only: num2str
  use sloshdyn_ode, only: ode_options, ode_stats, linear_observation, peak_tracker
  use sloshdyn_dopri5, only: dopri5_integrator
  use sloshdyn_integrator, only: integrate, METHOD_DOPRI5
  use rk_checks, only: riccati, oscillator, check_orders, fixed_step_errors, dense_output_errors, &
                       check_stepwise_api, check_failures, check_bad_input, &
                       check_without_dense_output, check_replay
  use checks, only: check_close, check_true, finish
  implicit none

  integer, parameter :: n_halvings = 4

  call test_fixed_step_order()
  call test_dense_output_order()
  call test_adaptive_tolerances()
  call check_stepwise_api(METHOD_DOPRI5)
  call check_without_dense_output(METHOD_DOPRI5)
  call test_peak_tracker()
  call test_peaks_by_a_steps_end()
  call check_replay(METHOD_DOPRI5)
  call check_failures(METHOD_DOPRI5)
  call check_bad_input(METHOD_DOPRI5)
  call finish()

contains

  !> Fixed steps: the global error of the 5th-order solution falls like h**5, on the riccati
  !> problem over [0, 1] (h = 0.2 ... 0.0125) and the forced oscillator over [0, 10].
  subroutine test_fixed_step_order()
    real(wp) :: err_ric(0:n_halvings), err_osc(0:n_halvings)

    call fixed_step_errors(METHOD_DOPRI5, 'rk45', 5, 20, 6, err_ric, err_osc)
    call check_orders('order of y, riccati', err_ric, 5.0_wp, 0.3_wp)
    call check_orders('order of y, oscillator', err_osc, 5.0_wp, 0.3_wp)
  end subroutine test_fixed_step_order

  !> The continuous extension (CONTD5) has order 4: one step of size h from the exact y(t0)
  !> leaves an error C(theta) h**5 inside the step (exponent 5 = order + 1; the end point, of
  !> order 5, has h**6). Over many steps the end-point errors add up to O(h**5), while each
  !> step's interpolation error is used once and does not add up, so the global error at
  !> interior points is O(h**5) + O(h**5): exponent 5 again, not 4.
  !> t0 = 1.5 because at t0 = 0 the h**5 term of this problem vanishes (exponent 6 seen).
  subroutine test_dense_output_order()
    real(wp) :: err_local(0:n_halvings), err_global(0:n_halvings)

    call dense_output_errors(METHOD_DOPRI5, 1.5_wp, 0.2_wp, 3.0_wp, 6, err_local, err_global)
    call check_orders('dense output at mid-step, local error exponent (order 4 + 1)', &
                      err_local, 5.0_wp, 0.4_wp)
    call check_orders('dense output at mid-steps, global error exponent', err_global, &
                      5.0_wp, 0.4_wp)
  end subroutine test_dense_output_order

  !> Adaptive runs: the error falls as rtol falls and stays within 100 rtol; the counters obey
  !> n_rhs = 6 (accepted + rejected) + 2 (f(t0) and HINIT's Euler probe).
  subroutine test_adaptive_tolerances()
    type(riccati) :: ric
    type(oscillator) :: osc
    type(ode_options) :: opt
    type(ode_stats) :: stats
    real(wp), parameter :: rtols(4) = [1.0e-4_wp, 1.0e-6_wp, 1.0e-8_wp, 1.0e-10_wp]
    real(wp) :: t_out(5), y2(2, 5), y1(1, 1), err_osc(4), err_ric(4)
    integer :: i, j, status
    character(len=message_len) :: message

    t_out = [0.0_wp, 1.0_wp, 2.5_wp, 7.0_wp, 4*pi]
    do i = 1, size(rtols)
      opt%rtol = rtols(i)
      opt%atol = rtols(i)
      call integrate(METHOD_DOPRI5, osc, 0.0_wp, osc%exact(0.0_wp), t_out, y2, opt, stats, status, message)
      call check_true('oscillator runs, rtol = '//num2str(rtols(i)), status == SD_OK)
      err_osc(i) = 0
      do j = 1, size(t_out)
        err_osc(i) = max(err_osc(i), maxval(abs(y2(:, j) - osc%exact(t_out(j)))))
      end do
      call check_true('oscillator error '//num2str(err_osc(i))//' <= 100 rtol', &
                      err_osc(i) <= 100*rtols(i))
      call check_true('oscillator counters: n_rhs = 6 (accepted + rejected) + 2', &
                      stats%n_rhs == 6*(stats%n_accepted + stats%n_rejected) + 2)
      call check_true('oscillator reached the last output time', stats%t_reached == 4*pi)

      call integrate(METHOD_DOPRI5, ric, 0.0_wp, [1.0_wp], [10.0_wp], y1, opt, stats, status, message)
      call check_true('riccati runs, rtol = '//num2str(rtols(i)), status == SD_OK)
      err_ric(i) = abs(y1(1, 1) - ric%exact(10.0_wp))
      call check_true('riccati error '//num2str(err_ric(i))//' <= 100 rtol', &
                      err_ric(i) <= 100*rtols(i))
      call check_true('riccati counters: n_rhs = 6 (accepted + rejected) + 2', &
                      stats%n_rhs == 6*(stats%n_accepted + stats%n_rejected) + 2)
      print '(a, es8.1, 2(a, es9.2), 2(a, i0))', 'rtol ', rtols(i), ': oscillator error ', &
        err_osc(i), ', riccati error ', err_ric(i), ', riccati steps accepted ', &
        stats%n_accepted, ', rejected ', stats%n_rejected
    end do
    do i = 2, size(rtols)
      call check_true('oscillator error falls with rtol '//num2str(rtols(i)), &
                      err_osc(i) < err_osc(i - 1))
      call check_true('riccati error falls with rtol '//num2str(rtols(i)), &
                      err_ric(i) < err_ric(i - 1))
    end do

    ! a given first step skips HINIT's evaluation
    opt%h_initial = 1.0e-3_wp
    call integrate(METHOD_DOPRI5, ric, 0.0_wp, [1.0_wp], [10.0_wp], y1, opt, stats, status, message)
    call check_true('counters with h_initial: n_rhs = 6 (accepted + rejected) + 1', &
                    status == SD_OK .and. &
                    stats%n_rhs == 6*(stats%n_accepted + stats%n_rejected) + 1)
  end subroutine test_adaptive_tolerances

  !> The peaks of an integration are located between the steps, whatever the output times:
  !> y1 = cos t, y2 = -sin t on [0, 10]; max|y2| = 1 at pi/2 + k pi, |y2| enters [0.5, 1] at
  !> pi/6 + k pi (four times), first at pi/6 (closed forms).
  subroutine test_peak_tracker()
    type(oscillator) :: osc
    type(ode_options) :: opt
    type(ode_stats) :: stats
    type(linear_observation) :: y2
    type(peak_tracker) :: coarse, fine
    real(wp) :: y_coarse(2, 2), y_fine(2, 1001)
    integer :: status, j
    character(len=message_len) :: message

    opt%rtol = 1.0e-11_wp
    opt%atol = 1.0e-13_wp
    osc%force = 0
    y2 = linear_observation(reshape([0.0_wp, 1.0_wp], [1, 2]))
    coarse%level = [0.5_wp]
    fine%level = [0.5_wp]
    call integrate(METHOD_DOPRI5, osc, 0.0_wp, [1.0_wp, 0.0_wp], [5.0_wp, 10.0_wp], y_coarse, &
                   opt, stats, status, message, y2, coarse)
    call check_true('peak tracker: runs: '//trim(message), status == SD_OK)
    call integrate(METHOD_DOPRI5, osc, 0.0_wp, [1.0_wp, 0.0_wp], &
                   [(0.01_wp*j, j = 0, 1000)], y_fine, opt, stats, status, message, y2, fine)
    call check_close('peak tracker: max|sin t| = 1 (1e-9)', coarse%peak(1), 1.0_wp, 1.0e-9_wp)
    call check_close('peak tracker: at pi/2 + k pi (1e-5)', &
                     modulo(coarse%time(1) - pi/2 + 1, pi) - 1, 0.0_wp, 0.0_wp, 1.0e-5_wp)
    call check_true('peak tracker: the same peak and time for 2 and 1001 output times', &
                    coarse%peak(1) == fine%peak(1) .and. coarse%time(1) == fine%time(1))
    call check_true('peak tracker: |sin t| enters [0.5, 1] 4 times on [0, 10], got '// &
                    num2str(coarse%crossings(1)), coarse%crossings(1) == 4)
    call check_close('peak tracker: first entry at pi/6 (1e-9)', coarse%first_crossing(1), &
                     pi/6, 1.0e-9_wp)
  end subroutine test_peak_tracker

  !> A maximum just inside a step's end is refined, one the quantity rises into is the end
  !> itself: |sin t| (the oscillator above) started or stopped 1e-3 from its maximum at pi/2
  !> (well inside the last and first probe interval of steps ~0.03 long), and stopped at 1,
  !> still rising: the peaks 1, 1 and sin 1 (closed forms), the last at t = 1 exactly.
  subroutine test_peaks_by_a_steps_end()
    type(oscillator) :: osc
    type(ode_options) :: opt
    type(ode_stats) :: stats
    type(linear_observation) :: y2
    type(peak_tracker) :: tracker
    real(wp), parameter :: gap = 1.0e-3_wp
    real(wp) :: y(2, 1)
    integer :: status
    character(len=message_len) :: message

    opt%rtol = 1.0e-11_wp
    opt%atol = 1.0e-13_wp
    osc%force = 0
    y2 = linear_observation(reshape([0.0_wp, 1.0_wp], [1, 2]))
    call integrate(METHOD_DOPRI5, osc, 0.0_wp, [1.0_wp, 0.0_wp], [pi/2 + gap], y, opt, stats, &
                   status, message, y2, tracker)
    call check_true('peak by the end: runs: '//trim(message), status == SD_OK)
    call check_close('peak 1e-3 before the last step''s end = 1 (1e-10)', tracker%peak(1), &
                     1.0_wp, 1.0e-10_wp)
    call integrate(METHOD_DOPRI5, osc, pi/2 - gap, [cos(pi/2 - gap), -sin(pi/2 - gap)], &
                   [pi/2 + 1], y, opt, stats, status, message, y2, tracker)
    call check_true('peak by the start: runs: '//trim(message), status == SD_OK)
    call check_close('peak 1e-3 after the first step''s start = 1 (1e-10)', tracker%peak(1), &
                     1.0_wp, 1.0e-10_wp)
    call integrate(METHOD_DOPRI5, osc, 0.0_wp, [1.0_wp, 0.0_wp], [1.0_wp], y, opt, stats, &
                   status, message, y2, tracker)
    call check_true('rising to the end: the peak is |y2(1)| at t = 1 exactly, = sin 1 (1e-10)', &
                    status == SD_OK .and. tracker%peak(1) == abs(y(2, 1)) .and. &
                    tracker%time(1) == 1 .and. abs(tracker%peak(1) - sin(1.0_wp)) < 1.0e-10_wp)
  end subroutine test_peaks_by_a_steps_end

end program test_rk45
