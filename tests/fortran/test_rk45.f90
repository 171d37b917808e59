!> Test systems with closed-form solutions, the independent source of every expected value below.
module rk45_test_systems
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use sloshdyn_kinds, only: wp
  use sloshdyn_ode, only: ode_system
  implicit none
  private
  public :: riccati, oscillator, nan_beyond

  !> y' = -a t y**2, y(0) = 1: y = 1/(1 + a t**2/2) (nonautonomous, nonlinear)
  type, extends(ode_system) :: riccati
    real(wp) :: a = 2
  contains
    procedure :: rhs => riccati_rhs
    procedure :: exact => riccati_exact
  end type riccati

  !> Forced oscillator y1' = y2, y2' = -omega**2 y1 + force cos(drive t), y(0) = (1, 0):
  !> y1 = cos(omega t) + force/(omega**2 - drive**2) (cos(drive t) - cos(omega t)), y2 = y1'
  type, extends(ode_system) :: oscillator
    real(wp) :: omega = 1, force = 0.5_wp, drive = 2
  contains
    procedure :: rhs => oscillator_rhs
    procedure :: exact => oscillator_exact
  end type oscillator

  !> y' = -y up to t = t_edge, NaN beyond: a right-hand side that leaves its domain
  type, extends(ode_system) :: nan_beyond
    real(wp) :: t_edge = 1
  contains
    procedure :: rhs => nan_beyond_rhs
  end type nan_beyond

contains

  subroutine riccati_rhs(self, t, y, dydt)
    class(riccati), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: dydt(:)
    dydt(1) = -self%a*t*y(1)**2
  end subroutine riccati_rhs

  pure real(wp) function riccati_exact(self, t) result(y)
    class(riccati), intent(in) :: self
    real(wp), intent(in) :: t
    y = 1/(1 + self%a*t**2/2)
  end function riccati_exact

  subroutine oscillator_rhs(self, t, y, dydt)
    class(oscillator), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: dydt(:)
    dydt(1) = y(2)
    dydt(2) = -self%omega**2*y(1) + self%force*cos(self%drive*t)
  end subroutine oscillator_rhs

  pure function oscillator_exact(self, t) result(y)
    class(oscillator), intent(in) :: self
    real(wp), intent(in) :: t
    real(wp) :: y(2)
    real(wp) :: c
    c = self%force/(self%omega**2 - self%drive**2)
    y(1) = cos(self%omega*t) + c*(cos(self%drive*t) - cos(self%omega*t))
    y(2) = -self%omega*sin(self%omega*t) + c*(-self%drive*sin(self%drive*t) + &
                                              self%omega*sin(self%omega*t))
  end function oscillator_exact

  subroutine nan_beyond_rhs(self, t, y, dydt)
    class(nan_beyond), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: dydt(:)
    if (t <= self%t_edge) then
      dydt = -y
    else
      dydt = ieee_value(1.0_wp, ieee_quiet_nan)
    end if
  end subroutine nan_beyond_rhs
end module rk45_test_systems

program test_rk45
  use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, SD_STEP_TOO_SMALL, SD_TOO_MANY_STEPS, &
                             SD_NON_FINITE
  use sloshdyn_text, only: num2str
  use sloshdyn_ode, only: ode_options, ode_stats, linear_observation, peak_tracker
  use sloshdyn_dopri5, only: dopri5_integrator
  use sloshdyn_integrator, only: integrate, METHOD_DOPRI5
  use rk45_test_systems, only: riccati, oscillator, nan_beyond
  use checks, only: check_close, check_true, finish
  implicit none

  integer, parameter :: n_halvings = 4

  call test_fixed_step_order()
  call test_dense_output_order()
  call test_adaptive_tolerances()
  call test_stepwise_api()
  call test_peak_tracker()
  call test_failures()
  call test_bad_input()
  call finish()

contains

  !> Observed orders log2(e(h)/e(h/2)) of errors at h, h/2, h/4, ... must all be expected +- tol.
  subroutine check_orders(label, errors, expected, tol)
    character(len=*), intent(in) :: label
    real(wp), intent(in) :: errors(:), expected, tol
    real(wp) :: orders(size(errors) - 1)
    integer :: i

    orders = log(errors(:size(errors) - 1)/errors(2:))/log(2.0_wp)
    print '(2a, *(es10.2))', label, ': errors', errors
    print '(2a, *(f7.3))', label, ': orders', orders
    do i = 1, size(orders)
      call check_close(label//', halving '//num2str(i), orders(i), expected, 0.0_wp, tol)
    end do
  end subroutine check_orders

  !> Fixed steps: the global error of the 5th-order solution falls like h**5, on the riccati
  !> problem over [0, 1] (h = 0.2 ... 0.0125) and the forced oscillator over [0, 10].
  subroutine test_fixed_step_order()
    type(riccati) :: ric
    type(oscillator) :: osc
    type(ode_options) :: opt
    type(ode_stats) :: stats
    real(wp) :: err_ric(0:n_halvings), err_osc(0:n_halvings), y1(1, 1), y2(2, 1)
    integer :: i, status, n_steps
    character(len=message_len) :: message

    do i = 0, n_halvings
      n_steps = 5*2**i
      opt%fixed_step = 1.0_wp/n_steps
      call integrate(METHOD_DOPRI5, ric, 0.0_wp, [1.0_wp], [1.0_wp], y1, opt, stats, status, message)
      call check_true('fixed steps on riccati: '//num2str(n_steps)//' steps, none rejected', &
                      status == SD_OK .and. stats%n_accepted == n_steps .and. &
                      stats%n_rejected == 0)
      err_ric(i) = abs(y1(1, 1) - ric%exact(1.0_wp))

      n_steps = 20*2**i
      opt%fixed_step = 10.0_wp/n_steps
      call integrate(METHOD_DOPRI5, osc, 0.0_wp, osc%exact(0.0_wp), [10.0_wp], y2, opt, stats, status, &
                          message)
      call check_true('fixed steps on the oscillator: '//num2str(n_steps)//' steps', &
                      status == SD_OK .and. stats%n_accepted == n_steps)
      err_osc(i) = maxval(abs(y2(:, 1) - osc%exact(10.0_wp)))
    end do
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
    type(riccati) :: ric
    type(dopri5_integrator) :: integ
    type(ode_options) :: opt
    real(wp), parameter :: t0 = 1.5_wp
    real(wp) :: h, t_mid, err_local(0:n_halvings), err_global(0:n_halvings), y(1)
    integer :: i, status
    character(len=message_len) :: message

    do i = 0, n_halvings
      h = 0.2_wp/2**i
      opt%fixed_step = h
      call integ%init(ric, t0, [ric%exact(t0)], t0 + h, opt, status, message)
      call integ%step(ric, status, message)
      call check_true('one fixed step, h = '//num2str(h), status == SD_OK .and. integ%t == t0 + h)
      call integ%dense(t0 + h/2, y)
      err_local(i) = abs(y(1) - ric%exact(t0 + h/2))
      ! the interpolant passes through both ends of the step
      call integ%dense(t0, y)
      call check_close('dense output at the step start, h = '//num2str(h), y(1), ric%exact(t0), &
                       0.0_wp, 1.0e-15_wp)
      call integ%dense(t0 + h, y)
      call check_close('dense output at the step end, h = '//num2str(h), y(1), integ%y(1), &
                       0.0_wp, 1.0e-15_wp)

      opt%fixed_step = 0.2_wp/2**i
      call integ%init(ric, 0.0_wp, [1.0_wp], 3.0_wp, opt, status, message)
      err_global(i) = 0
      do while (status == SD_OK .and. integ%t < integ%t_bound)
        call integ%step(ric, status, message)
        t_mid = (integ%t_old + integ%t)/2
        call integ%dense(t_mid, y)
        err_global(i) = max(err_global(i), abs(y(1) - ric%exact(t_mid)))
      end do
      call check_true('fixed steps over [0, 3] with dense output, h = '// &
                      num2str(opt%fixed_step), status == SD_OK)
    end do
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

  !> Driving the integrator step by step, reading dense output and replacing the state.
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

  subroutine test_stepwise_api()
    type(oscillator) :: osc
    type(dopri5_integrator) :: integ
    type(ode_options) :: opt
    type(ode_stats) :: stats
    real(wp) :: y(2), t_mid, y_out(2, 4)
    integer :: status
    logical :: scaled
    character(len=message_len) :: message

    opt%rtol = 1.0e-10_wp
    opt%atol = 1.0e-12_wp
    ! unforced, so after doubling the state the exact solution is twice the old one
    osc%force = 0
    call integ%init(osc, 0.0_wp, osc%exact(0.0_wp), 3.0_wp, opt, status, message)
    call check_true('rk45_init succeeds', status == SD_OK)
    scaled = .false.
    do while (status == SD_OK .and. integ%t < integ%t_bound)
      call integ%step(osc, status, message)
      if (.not. scaled .and. integ%t > 1) then
        t_mid = (integ%t_old + integ%t)/2
        call integ%dense(t_mid, y)
        call check_close('dense output inside a step', maxval(abs(y - osc%exact(t_mid))), &
                         0.0_wp, 0.0_wp, 1.0e-9_wp)
        call integ%set_state(osc, 2*integ%y, status, message)
        scaled = .true.
      end if
    end do
    call check_true('stepping reaches t_bound exactly', status == SD_OK .and. integ%t == 3.0_wp)
    call check_close('rk45_set_state: the state follows the doubled solution', &
                     maxval(abs(integ%y - 2*osc%exact(3.0_wp))), 0.0_wp, 0.0_wp, 1.0e-8_wp)
    call integ%step(osc, status, message)
    call check_true('a step past t_bound is refused: '//trim(message), status == SD_BAD_INPUT)

    call integrate(METHOD_DOPRI5, osc, 0.0_wp, osc%exact(0.0_wp), [0.0_wp, 0.5_wp, 0.5_wp, 2.0_wp], &
                        y_out, opt, stats, status, message)
    call check_true('rk45_integrate with outputs at t0 and a repeated time', status == SD_OK)
    call check_close('output at t0 is y0', maxval(abs(y_out(:, 1) - osc%exact(0.0_wp))), &
                     0.0_wp, 0.0_wp, 0.0_wp)
    call check_close('a repeated output time gives the same y', &
                     maxval(abs(y_out(:, 2) - y_out(:, 3))), 0.0_wp, 0.0_wp, 0.0_wp)
    call check_close('output at 0.5', maxval(abs(y_out(:, 3) - osc%exact(0.5_wp))), &
                     0.0_wp, 0.0_wp, 1.0e-9_wp)
  end subroutine test_stepwise_api

  !> Failures during the integration: partial output, NaN after, the time reached.
  subroutine test_failures()
    type(oscillator) :: osc
    type(nan_beyond) :: nb
    type(riccati) :: ric
    type(ode_options) :: opt
    type(ode_stats) :: stats
    real(wp) :: t_out(1000), y_out(2, 1000), y_nb(1, 2)
    integer :: j, status
    logical :: partition_ok
    character(len=message_len) :: message

    ! outputs every 0.1 up to 100: ten steps end after a few of them
    t_out = [(0.1_wp*j, j = 1, size(t_out))]
    opt%max_steps = 10
    call integrate(METHOD_DOPRI5, osc, 0.0_wp, osc%exact(0.0_wp), t_out, y_out, opt, stats, status, &
                        message)
    print '(a)', '    message: '//trim(message)
    call check_true('max_steps = 10 gives SD_TOO_MANY_STEPS', status == SD_TOO_MANY_STEPS)
    call check_true('message names max_steps and tau', &
                    index(message, 'max_steps') > 0 .and. index(message, 'tau') > 0)
    call check_true('10 steps attempted', stats%n_accepted + stats%n_rejected == 10)
    call check_true('time reached '//num2str(stats%t_reached)//' lies past the first output', &
                    stats%t_reached > t_out(1) .and. stats%t_reached < t_out(size(t_out)))
    call check_close('first output before the failure', &
                     maxval(abs(y_out(:, 1) - osc%exact(t_out(1)))), 0.0_wp, 0.0_wp, 1.0e-8_wp)
    partition_ok = .true.
    do j = 1, size(t_out)
      if (t_out(j) <= stats%t_reached) then
        partition_ok = partition_ok .and. .not. any(ieee_is_nan(y_out(:, j)))
      else
        partition_ok = partition_ok .and. all(ieee_is_nan(y_out(:, j)))
      end if
    end do
    call check_true('outputs filled up to t_reached, NaN after', partition_ok)

    opt = ode_options()
    call integrate(METHOD_DOPRI5, nb, 0.0_wp, [1.0_wp], [0.5_wp, 2.0_wp], y_nb, opt, stats, status, message)
    print '(a)', '    message: '//trim(message)
    call check_true('NaN right-hand side gives SD_NON_FINITE', status == SD_NON_FINITE)
    call check_true('message names tau', index(message, 'tau') > 0)
    call check_close('output before the NaN region', y_nb(1, 1), exp(-0.5_wp), 1.0e-7_wp)
    call check_true('output in the NaN region is NaN', ieee_is_nan(y_nb(1, 2)))
    call check_close('integration stops at the edge t = 1', stats%t_reached, 1.0_wp, 0.0_wp, &
                     1.0e-6_wp)

    opt%fixed_step = 0.3_wp
    call integrate(METHOD_DOPRI5, nb, 0.0_wp, [1.0_wp], [0.5_wp, 2.0_wp], y_nb, opt, stats, status, message)
    call check_true('NaN in fixed-step mode gives SD_NON_FINITE', status == SD_NON_FINITE)

    opt = ode_options(rtol=1.0e-10_wp, h_min=0.5_wp)
    call integrate(METHOD_DOPRI5, ric, 0.0_wp, [1.0_wp], [10.0_wp], y_nb(:, 1:1), opt, stats, status, &
                        message)
    print '(a)', '    message: '//trim(message)
    call check_true('h_min = 0.5 gives SD_STEP_TOO_SMALL', status == SD_STEP_TOO_SMALL)
    call check_true('message names h_min and tau', &
                    index(message, 'h_min') > 0 .and. index(message, 'tau') > 0)
  end subroutine test_failures

  !> Each rule on the inputs is reported with the name of the offending input.
  subroutine test_bad_input()
    type(ode_options) :: opt
    type(dopri5_integrator) :: integ
    type(riccati) :: ric
    integer :: status
    character(len=message_len) :: message

    opt%rtol = -1
    call expect_bad(opt, [0.5_wp, 1.0_wp], 'rtol')
    opt = ode_options(atol=-1.0e-3_wp)
    call expect_bad(opt, [0.5_wp, 1.0_wp], 'atol')
    opt = ode_options(atol_vector=[1.0e-8_wp, 1.0e-8_wp])
    call expect_bad(opt, [0.5_wp, 1.0_wp], 'atol_vector')
    opt = ode_options(beta=0.5_wp)
    call expect_bad(opt, [0.5_wp, 1.0_wp], 'beta')
    opt = ode_options(max_steps=0)
    call expect_bad(opt, [0.5_wp, 1.0_wp], 'max_steps')
    opt = ode_options(fixed_step=-0.1_wp)
    call expect_bad(opt, [0.5_wp, 1.0_wp], 'fixed_step')
    opt = ode_options()
    call expect_bad(opt, [1.0_wp, 0.5_wp], 't_out(2)')
    call expect_bad(opt, [-1.0_wp, 0.5_wp], 't_out(1)')

    call integ%init(ric, 1.0_wp, [1.0_wp], 1.0_wp, opt, status, message)
    call check_true('t_bound = t0 gives SD_BAD_INPUT: '//trim(message), &
                    status == SD_BAD_INPUT .and. index(message, 't_bound') == 1)
    call integ%step(ric, status, message)
    call check_true('rk45_step after a failed rk45_init is refused: '//trim(message), &
                    status == SD_BAD_INPUT)
    opt%atol = 0
    call integ%init(ric, 0.0_wp, [0.0_wp], 1.0_wp, opt, status, message)
    call check_true('atol = 0 with a zero component of y0 gives SD_BAD_INPUT: '//trim(message), &
                    status == SD_BAD_INPUT .and. index(message, 'atol') == 1)
  end subroutine test_bad_input

  !> rk45_integrate on the riccati problem must return SD_BAD_INPUT with a message that starts
  !> with the name of the input, and only NaN outputs.
  subroutine expect_bad(opt, t_out, name)
    type(ode_options), intent(in) :: opt
    real(wp), intent(in) :: t_out(:)
    character(len=*), intent(in) :: name
    type(riccati) :: ric
    type(ode_stats) :: stats
    real(wp) :: y_out(1, size(t_out))
    integer :: status
    character(len=message_len) :: message

    call integrate(METHOD_DOPRI5, ric, 0.0_wp, [1.0_wp], t_out, y_out, opt, stats, status, message)
    call check_true('bad '//name//' gives SD_BAD_INPUT: '//trim(message), &
                    status == SD_BAD_INPUT .and. index(message, name) == 1)
    call check_true('bad '//name//': all outputs NaN', all(ieee_is_nan(y_out)))
  end subroutine expect_bad
end program test_rk45
