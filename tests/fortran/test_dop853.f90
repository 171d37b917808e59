!> DOP853 and Verner's 9(8) (the higher-order pairs) on the test systems of rk_checks, with
!> closed-form solutions (the independent source of the expected values below) except Van der
!> Pol, which is checked against DOPRI5.
program test_dop853
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK
  use sloshdyn_text, only: num2str
  use sloshdyn_ode, only: ode_options, ode_stats
  use sloshdyn_vern9, only: vern9_integrator
  use sloshdyn_integrator, only: integrate, chosen_method, METHOD_DOPRI5, METHOD_DOP853, &
                                 METHOD_VERN9, METHOD_AUTO
  use rk_checks, only: riccati, oscillator, van_der_pol, check_orders, fixed_step_errors, &
                       dense_output_errors, check_stepwise_api, check_failures, check_bad_input, &
                       check_without_dense_output, check_replay
  use checks, only: check_close, check_true, finish
  implicit none

  call test_fixed_step_order()
  call test_dense_output_order()
  call test_adaptive_tolerances()
  call test_van_der_pol_against_rk45()
  call check_stepwise_api(METHOD_DOP853)
  call check_without_dense_output(METHOD_DOP853)
  call check_without_dense_output(METHOD_VERN9)
  call check_replay(METHOD_DOP853)
  call check_replay(METHOD_VERN9)
  call check_failures(METHOD_DOP853)
  call check_bad_input(METHOD_DOP853)
  call test_vern9_dense_output_order()
  call test_vern9_adaptive()
  call test_auto_choice()
  call finish()

contains

  !> DOP853, fixed steps: the global error of the 8th-order solution falls like h**8. An error
  !> that falls by 256 per halving leaves room for only two or three halvings between the
  !> pre-asymptotic range and rounding (~1e-15), so: the riccati problem at t = 1 with 4, 8, 16
  !> steps (errors 2e-10 ... 3e-15; with 2 steps the ratio is still 8.5), and the forced
  !> oscillator at t = 10 with 20, 40, 80 steps (8e-9 ... 1e-13).
  !> Verner's 9(8), fixed steps: the global error of the 9th-order solution falls like h**9
  !> (512 per halving), on the forced oscillator at t = 10 with 10, 20, 40 steps (2e-7 ... 3e-13;
  !> the next halving reaches rounding). The observed orders approach 9 from above (9.8, 9.7:
  !> the h**10 term still shows), so they must lie in [9, 10]; an 8th-order method (a wrong
  !> coefficient in a 9th-order condition) would show 8. The riccati problem (2, 4, 8 steps) has
  !> a larger pre-asymptotic excess (10.8, 10.6) and only has to show at least order 9. 16
  !> evaluations per step without dense output.
  subroutine test_fixed_step_order()
    real(wp) :: err_ric(0:2), err_osc(0:2)

    call fixed_step_errors(METHOD_DOP853, 'dop853', 4, 20, 12, err_ric, err_osc)
    call check_orders('order of y, riccati', err_ric, 8.0_wp, 0.5_wp)
    call check_orders('order of y, oscillator', err_osc, 8.0_wp, 0.5_wp)

    call fixed_step_errors(METHOD_VERN9, 'vern9', 2, 10, 16, err_ric, err_osc)
    call check_orders('vern9, order of y, riccati', err_ric, 10.0_wp, 1.0_wp)
    call check_orders('vern9, order of y, oscillator', err_osc, 9.5_wp, 0.5_wp)
  end subroutine test_fixed_step_order

  !> The continuous extension (CONTD8) has order 7: one step of size h from the exact y(t0)
  !> leaves an error C(theta) h**8 inside the step (exponent 8 = order + 1; the end point, of
  !> order 8, has h**9). Over many steps the end-point errors add up to O(h**8), and the
  !> interpolant carries that error of y_n into the step unchanged to leading order, while each
  !> step's own interpolation error O(h**8) is used once and does not add up: the global error
  !> at interior points is O(h**8) + O(h**8), exponent 8 as well (7th-order interpolation of an
  !> 8th-order method loses nothing globally). Measured at mid-step, h = 0.4 ... 0.05 (the
  !> interpolation error at h = 0.05 is ~1e-14, still 100 rounding units).
  subroutine test_dense_output_order()
    real(wp) :: err_local(0:3), err_global(0:3)

    call dense_output_errors(METHOD_DOP853, 0.0_wp, 0.4_wp, 4.0_wp, 15, err_local, err_global)
    call check_orders('dense output at mid-step, local error exponent (order 7 + 1)', &
                      err_local, 8.0_wp, 0.5_wp)
    call check_orders('dense output at mid-steps, global error exponent', err_global, &
                      8.0_wp, 0.5_wp)
  end subroutine test_dense_output_order

  !> Adaptive runs: the error falls as rtol falls and stays within 100 rtol; the counters obey
  !> n_rhs = 11 (accepted + rejected) + 4 accepted + 2 (f(t0) and HINIT's Euler probe). At
  !> rtol = 1e-10 DOP853 needs far fewer steps than DOPRI5 (rk45_integrate) on the same runs.
  subroutine test_adaptive_tolerances()
    type(riccati) :: ric
    type(oscillator) :: osc
    type(ode_options) :: opt
    type(ode_stats) :: stats, stats_rk45
    real(wp), parameter :: rtols(4) = [1.0e-6_wp, 1.0e-8_wp, 1.0e-10_wp, 1.0e-12_wp]
    real(wp) :: t_out(5), y2(2, 5), y1(1, 2), err_osc(4), err_ric(4)
    integer :: i, j, status, steps_osc, steps_ric
    character(len=message_len) :: message

    t_out = [0.0_wp, 1.0_wp, 2.5_wp, 7.0_wp, 4*pi]
    do i = 1, size(rtols)
      opt%rtol = rtols(i)
      opt%atol = rtols(i)
      call integrate(METHOD_DOP853, osc, 0.0_wp, osc%exact(0.0_wp), t_out, y2, opt, stats, status, &
                            message)
      call check_true('oscillator runs, rtol = '//num2str(rtols(i)), status == SD_OK)
      err_osc(i) = 0
      do j = 1, size(t_out)
        err_osc(i) = max(err_osc(i), maxval(abs(y2(:, j) - osc%exact(t_out(j)))))
      end do
      call check_true('oscillator error '//num2str(err_osc(i))//' <= 100 rtol', &
                      err_osc(i) <= 100*rtols(i))
      call check_true('oscillator counters: n_rhs = 11 (accepted + rejected) + 4 accepted + 2', &
                      stats%n_rhs == 11*(stats%n_accepted + stats%n_rejected) + &
                      4*stats%n_accepted + 2)
      call check_true('oscillator reached the last output time', stats%t_reached == 4*pi)
      steps_osc = stats%n_accepted

      call integrate(METHOD_DOP853, ric, 0.0_wp, [1.0_wp], [5.0_wp, 10.0_wp], y1, opt, stats, status, &
                            message)
      call check_true('riccati runs, rtol = '//num2str(rtols(i)), status == SD_OK)
      err_ric(i) = max(abs(y1(1, 1) - ric%exact(5.0_wp)), abs(y1(1, 2) - ric%exact(10.0_wp)))
      call check_true('riccati error '//num2str(err_ric(i))//' <= 100 rtol', &
                      err_ric(i) <= 100*rtols(i))
      call check_true('riccati counters: n_rhs = 11 (accepted + rejected) + 4 accepted + 2', &
                      stats%n_rhs == 11*(stats%n_accepted + stats%n_rejected) + &
                      4*stats%n_accepted + 2)
      steps_ric = stats%n_accepted
      print '(a, es8.1, 2(a, es9.2), 3(a, i0), a)', 'rtol ', rtols(i), ': oscillator error ', &
        err_osc(i), ', riccati error ', err_ric(i), '; accepted steps: oscillator ', steps_osc, &
        ', riccati ', steps_ric, ' (rejected ', stats%n_rejected, ')'

      if (rtols(i) == 1.0e-10_wp) then
        call integrate(METHOD_DOPRI5, osc, 0.0_wp, osc%exact(0.0_wp), t_out, y2, opt, stats_rk45, status, &
                            message)
        print '(2(a, i0))', '    oscillator at rtol 1e-10: rk45 accepted steps ', &
          stats_rk45%n_accepted, ', dop853 ', steps_osc
        call check_true('oscillator, rtol 1e-10: dop853 takes < 1/3 of the rk45 steps', &
                        status == SD_OK .and. 3*steps_osc < stats_rk45%n_accepted)
        call integrate(METHOD_DOPRI5, ric, 0.0_wp, [1.0_wp], [5.0_wp, 10.0_wp], y1, opt, stats_rk45, &
                            status, message)
        print '(2(a, i0))', '    riccati at rtol 1e-10: rk45 accepted steps ', &
          stats_rk45%n_accepted, ', dop853 ', steps_ric
        call check_true('riccati, rtol 1e-10: dop853 takes < 1/3 of the rk45 steps', &
                        status == SD_OK .and. 3*steps_ric < stats_rk45%n_accepted)
      end if
    end do
    do i = 2, size(rtols)
      call check_true('oscillator error falls with rtol '//num2str(rtols(i)), &
                      err_osc(i) < err_osc(i - 1))
      call check_true('riccati error falls with rtol '//num2str(rtols(i)), &
                      err_ric(i) < err_ric(i - 1))
    end do

    ! a given first step skips HINIT's evaluation; one output time: no dense stages
    opt%h_initial = 1.0e-3_wp
    call integrate(METHOD_DOP853, ric, 0.0_wp, [1.0_wp], [10.0_wp], y1(:, 1:1), opt, stats, status, &
                          message)
    call check_true('counters with h_initial and no dense output: '// &
                    'n_rhs = 11 (accepted + rejected) + accepted + 1', status == SD_OK .and. &
                    stats%n_rhs == 11*(stats%n_accepted + stats%n_rejected) + &
                    stats%n_accepted + 1)
    call check_close('riccati at t = 10 without dense output', y1(1, 1), ric%exact(10.0_wp), &
                     0.0_wp, 1.0e-10_wp)
  end subroutine test_adaptive_tolerances

  !> Van der Pol, mu = 2 (period ~7.63) over [0, 20], rtol = atol = 1e-12: DOP853 and DOPRI5
  !> agree to 1e-9 at the step ends and inside steps (dense output of both).
  subroutine test_van_der_pol_against_rk45()
    type(van_der_pol) :: vdp
    type(ode_options) :: opt
    type(ode_stats) :: stats_dop, stats_rk45
    real(wp) :: t_out(41), y_dop(2, 41), y_rk45(2, 41)
    integer :: j, status_dop, status_rk45
    character(len=message_len) :: message

    t_out = [(0.5_wp*j, j = 0, 40)]
    opt%rtol = 1.0e-12_wp
    opt%atol = 1.0e-12_wp
    call integrate(METHOD_DOP853, vdp, 0.0_wp, [2.0_wp, 0.0_wp], t_out, y_dop, opt, stats_dop, &
                          status_dop, message)
    call integrate(METHOD_DOPRI5, vdp, 0.0_wp, [2.0_wp, 0.0_wp], t_out, y_rk45, opt, stats_rk45, &
                        status_rk45, message)
    call check_true('Van der Pol runs with both methods', &
                    status_dop == SD_OK .and. status_rk45 == SD_OK)
    print '(a, es9.2, 2(a, i0))', '    Van der Pol, rtol 1e-12: max |dop853 - rk45| ', &
      maxval(abs(y_dop - y_rk45)), '; accepted steps dop853 ', stats_dop%n_accepted, &
      ', rk45 ', stats_rk45%n_accepted
    call check_close('Van der Pol: dop853 agrees with rk45', maxval(abs(y_dop - y_rk45)), &
                     0.0_wp, 0.0_wp, 1.0e-9_wp)
  end subroutine test_van_der_pol_against_rk45

  !> Verner's 8th-order interpolant: one step from the exact y(t0) leaves an error C(theta) h**9
  !> inside the step (exponent = order + 1), measured at mid-step for h = 0.8 ... 0.2 on the
  !> forced oscillator (observed 9.8, 9.5: in [9, 10] as for the step itself). The interpolant
  !> passes through both ends of the step: exactly at the start, and at the end to the rounding
  !> of its coefficients in double precision (weights of size up to 1e4 that sum to b_i: about
  !> 1e-12 h |f|). 20 new evaluations per step with dense output (15 + f at the new point + 4).
  subroutine test_vern9_dense_output_order()
    type(oscillator) :: osc
    type(vern9_integrator) :: integ
    type(ode_options) :: opt
    real(wp) :: h, err_local(0:2), y(2)
    integer :: i, status
    character(len=message_len) :: message

    do i = 0, 2
      h = 0.8_wp/2**i
      opt%fixed_step = h
      call integ%init(osc, 0.0_wp, osc%exact(0.0_wp), 2*h, opt, status, message)
      call integ%step(osc, status, message)
      call check_true('vern9, one fixed step, h = '//num2str(h), status == SD_OK .and. &
                      integ%t == h)
      call check_true('vern9, 20 new evaluations per step with dense output', &
                      integ%n_rhs == 21)
      call integ%dense(h/2, y)
      err_local(i) = maxval(abs(y - osc%exact(h/2)))
      call integ%dense(0.0_wp, y)
      call check_close('vern9 dense output at the step start, h = '//num2str(h), y(1), &
                       1.0_wp, 0.0_wp, 1.0e-15_wp)
      call integ%dense(h, y)
      call check_close('vern9 dense output at the step end, h = '//num2str(h), y(1), &
                       integ%y(1), 0.0_wp, 2.0e-12_wp*h)
    end do
    call check_orders('vern9 dense output at mid-step, local error exponent (order 8 + 1)', &
                      err_local, 9.5_wp, 0.5_wp)
  end subroutine test_vern9_dense_output_order

  !> Adaptive Verner 9(8): the error stays within 100 rtol at rtol = 1e-8 ... 1e-12, with dense
  !> output at 50 times, and at rtol = 1e-12 it takes fewer steps than DOP853.
  subroutine test_vern9_adaptive()
    type(oscillator) :: osc
    type(ode_options) :: opt
    type(ode_stats) :: stats, stats_853
    real(wp), parameter :: rtols(3) = [1.0e-8_wp, 1.0e-10_wp, 1.0e-12_wp]
    real(wp) :: t_out(50), y(2, 50), err
    integer :: i, j, status
    character(len=message_len) :: message

    t_out = [(0.4_wp*j, j = 1, 50)]
    do i = 1, size(rtols)
      opt%rtol = rtols(i)
      opt%atol = rtols(i)
      call integrate(METHOD_VERN9, osc, 0.0_wp, osc%exact(0.0_wp), t_out, y, opt, stats, &
                     status, message)
      err = 0
      do j = 1, size(t_out)
        err = max(err, maxval(abs(y(:, j) - osc%exact(t_out(j)))))
      end do
      call check_true('vern9 at rtol '//num2str(rtols(i))//': error '//num2str(err)// &
                      ' within 100 rtol', status == SD_OK .and. err < 100*rtols(i))
    end do
    call integrate(METHOD_DOP853, osc, 0.0_wp, osc%exact(0.0_wp), t_out, y, opt, stats_853, &
                   status, message)
    call check_true('vern9 takes fewer steps than dop853 at rtol 1e-12 ('// &
                    num2str(stats%n_accepted)//' < '//num2str(stats_853%n_accepted)//')', &
                    stats%n_accepted < stats_853%n_accepted)
  end subroutine test_vern9_adaptive

  !> 'auto' runs DOPRI5 at loose, DOP853 at medium and Verner 9(8) at tight tolerances, and the
  !> same steps as the method it chose.
  subroutine test_auto_choice()
    type(oscillator) :: osc
    type(ode_options) :: opt
    type(ode_stats) :: stats_auto, stats_chosen
    real(wp), parameter :: rtols(3) = [1.0e-3_wp, 1.0e-8_wp, 1.0e-13_wp]
    integer, parameter :: expected(3) = [METHOD_DOPRI5, METHOD_DOP853, METHOD_VERN9]
    real(wp) :: y(2, 1)
    integer :: i, status
    character(len=message_len) :: message

    do i = 1, size(rtols)
      call check_true('auto at rtol '//num2str(rtols(i))//' chooses method '// &
                      num2str(expected(i)), chosen_method(METHOD_AUTO, rtols(i)) == expected(i))
      opt%rtol = rtols(i)
      call integrate(METHOD_AUTO, osc, 0.0_wp, osc%exact(0.0_wp), [10.0_wp], y, opt, &
                     stats_auto, status, message)
      call integrate(expected(i), osc, 0.0_wp, osc%exact(0.0_wp), [10.0_wp], y, opt, &
                     stats_chosen, status, message)
      call check_true('auto at rtol '//num2str(rtols(i))//' runs the chosen method', &
                      stats_auto%n_rhs == stats_chosen%n_rhs .and. &
                      stats_auto%n_accepted == stats_chosen%n_accepted)
    end do
  end subroutine test_auto_choice
end program test_dop853
