!> The Nigam-Jennings SDOF recurrence against closed forms (free decay, step, ramp, harmonic
!> steady state), its independence of dt for piecewise-linear loads, a second method (Newmark
!> average acceleration with a very small step, second order), and the response spectrum
!> (rigid limit, free-vibration tail, bad inputs).
program test_sdof
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT
  use sloshdyn_sdof, only: nigam_jennings_coefficients, sdof_response, response_spectrum
  use checks, only: check_close, check_true, finish
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  implicit none
  integer :: status
  character(len=message_len) :: message

  call test_free_decay()
  call test_step()
  call test_ramp_and_dt_independence()
  call test_harmonic_steady_state()
  call test_newmark()
  call test_coefficients()
  call test_spectrum()
  call test_bad_input()
  call finish()

contains

  !> No load, initial state (u0, v0): u = e^{-zeta w t} (u0 cos wd t + (v0 + zeta w u0)/wd sin wd t),
  !> wd = w sqrt(1 - zeta^2) (free vibration of a viscously damped oscillator, Chopra eq 2.2.4).
  subroutine test_free_decay()
    integer, parameter :: n = 2001
    real(wp), parameter :: dt = 0.01_wp, u0 = 0.03_wp, v0 = -0.4_wp
    real(wp) :: accel(n), u(n), v(n), a_abs(n), t, omega, damping, wd, expected, worst, worst_v
    real(wp) :: expected_v
    integer :: i, case

    accel = 0
    do case = 1, 2
      damping = merge(0.0_wp, 0.07_wp, case == 1)
      omega = 2*pi/0.7_wp
      wd = omega*sqrt(1 - damping**2)
      call sdof_response(dt, accel, omega, damping, u0, v0, u, v, a_abs, status, message)
      worst = 0
      worst_v = 0
      do i = 1, n
        t = (i - 1)*dt
        expected = exp(-damping*omega*t)*(u0*cos(wd*t) + (v0 + damping*omega*u0)/wd*sin(wd*t))
        ! the derivative of the same expression
        expected_v = exp(-damping*omega*t)*(v0*cos(wd*t) - (omega**2*u0 + damping*omega*v0)/wd &
                     *sin(wd*t))
        worst = max(worst, abs(u(i) - expected))
        worst_v = max(worst_v, abs(v(i) - expected_v))
      end do
      call check_true('free decay: status', status == SD_OK)
      call check_close('free decay zeta = '//merge('0   ', '0.07', case == 1)//': max |u - closed form|', &
                       worst, 0.0_wp, 0.0_wp, 1.0e-12_wp*abs(u0))
      call check_close('free decay zeta = '//merge('0   ', '0.07', case == 1)//': max |v - closed form|', &
                       worst_v, 0.0_wp, 0.0_wp, 1.0e-12_wp*abs(v0))
      print '(a, 2es10.2)', '    measured max |u err|, |v err|: ', worst, worst_v
    end do
  end subroutine test_free_decay

  !> Ground acceleration a from t = 0 on (a constant sequence is exactly piecewise linear), at rest:
  !> u = -a/w^2 (1 - e^{-zeta w t}(cos wd t + zeta/sqrt(1-zeta^2) sin wd t)) (Chopra eq 4.3.3);
  !> differentiating, u' = -a e^{-zeta w t} sin(wd t)/wd, so the absolute acceleration
  !> -w^2 u - 2 zeta w u' = a (1 - e^{-zeta w t}(cos wd t - zeta/sqrt(1-zeta^2) sin wd t)).
  subroutine test_step()
    integer, parameter :: n = 1001
    real(wp), parameter :: dt = 0.005_wp, a = 1.7_wp, damping = 0.05_wp
    real(wp) :: accel(n), u(n), v(n), a_abs(n), t, omega, wd, root, e, worst_u, worst_a
    integer :: i

    omega = 2*pi/0.35_wp
    root = sqrt(1 - damping**2)
    wd = omega*root
    accel = a
    call sdof_response(dt, accel, omega, damping, 0.0_wp, 0.0_wp, u, v, a_abs, status, message)
    worst_u = 0
    worst_a = 0
    do i = 1, n
      t = (i - 1)*dt
      e = exp(-damping*omega*t)
      worst_u = max(worst_u, abs(u(i) + a/omega**2*(1 - e*(cos(wd*t) + damping/root*sin(wd*t)))))
      worst_a = max(worst_a, abs(a_abs(i) - a*(1 - e*(cos(wd*t) - damping/root*sin(wd*t)))))
    end do
    call check_close('step: max |u - closed form| / (a/w^2)', worst_u/(a/omega**2), 0.0_wp, &
                     0.0_wp, 1.0e-12_wp)
    call check_close('step: max |a_abs - closed form| / a', worst_a/a, 0.0_wp, 0.0_wp, 1.0e-12_wp)
    print '(a, 2es10.2)', '    measured relative errors u, a_abs: ', worst_u/(a/omega**2), worst_a/a
  end subroutine test_step

  !> Ramp a_g = k t from rest. u'' + 2 zeta w u' + w^2 u = -k t has the particular solution
  !> u_p = -(k/w^2)(t - 2 zeta/w); u(0) = 0 and u'(0) = 0 fix the homogeneous part:
  !> u = u_p + e^{-zeta w t}(C1 cos wd t + C2 sin wd t), C1 = -2 zeta k/w^3,
  !> C2 = k (1 - 2 zeta^2)/(w^2 wd)   (check zeta = 0: u = -k t/w^2 + k sin(w t)/w^3).
  !> The ramp is exactly piecewise linear, so every dt gives the same u(1 s); so does a triangular
  !> pulse whose corners lie on every grid (independence of dt = exactness of the recurrence).
  subroutine test_ramp_and_dt_independence()
    real(wp), parameter :: k = 2.5_wp, damping = 0.05_wp, t_end = 1.2_wp
    real(wp) :: omega, wd, expected, at_end(4), pulse_end(4), dt
    real(wp), allocatable :: accel(:), u(:), v(:), a_abs(:)
    integer :: m, n, i
    integer, parameter :: steps(4) = [3, 30, 300, 12000]

    omega = 2*pi/0.45_wp
    wd = omega*sqrt(1 - damping**2)
    expected = -(k/omega**2)*(t_end - 2*damping/omega) + exp(-damping*omega*t_end)* &
               (-2*damping*k/omega**3*cos(wd*t_end) + k*(1 - 2*damping**2)/(omega**2*wd)* &
                sin(wd*t_end))
    do m = 1, 4
      n = steps(m)
      dt = t_end/n
      allocate (accel(n + 1), u(n + 1), v(n + 1), a_abs(n + 1))
      accel = [(k*i*dt, i = 0, n)]
      call sdof_response(dt, accel, omega, damping, 0.0_wp, 0.0_wp, u, v, a_abs, status, message)
      at_end(m) = u(n + 1)
      ! triangle: 0 at t = 0, 1 m/s^2 at 0.4 s, 0 at 0.8 s, then 0 (corners on every grid)
      accel = [(max(0.0_wp, 1 - abs(i*dt - 0.4_wp)/0.4_wp), i = 0, n)]
      call sdof_response(dt, accel, omega, damping, 0.0_wp, 0.0_wp, u, v, a_abs, status, message)
      pulse_end(m) = u(n + 1)
      deallocate (accel, u, v, a_abs)
    end do
    do m = 1, 4
      call check_close('ramp: u(1.2 s) = closed form, dt = 1.2/'//trim(itoa(steps(m))), &
                       at_end(m), expected, 1.0e-11_wp)
      call check_close('triangle pulse: u(1.2 s) independent of dt, dt = 1.2/'// &
                       trim(itoa(steps(m))), pulse_end(m), pulse_end(1), 1.0e-11_wp)
    end do
    print '(a, es10.2)', '    measured ramp spread over dt: ', &
      (maxval(at_end) - minval(at_end))/abs(expected)
    print '(a, es10.2)', '    measured pulse spread over dt: ', &
      (maxval(pulse_end) - minval(pulse_end))/abs(pulse_end(1))
  end subroutine test_ramp_and_dt_independence

  !> Ground acceleration A sin(W t) sampled at dt and taken piecewise linear: the steady-state
  !> amplitude of u for the true sine is (A/w^2)/sqrt((1 - r^2)^2 + (2 zeta r)^2), r = W/w
  !> (Chopra eq 3.2.5). Linear interpolation of samples is the sample train convolved with a
  !> triangle of width 2 dt, whose Fourier transform is dt sinc^2(W dt/2): the component at W of
  !> the interpolated load is the sine's times sinc^2(W dt/2) exactly (the other spectral lines
  !> sit at 2 pi k/dt +- W, far above w, and move u by ~1e-12 relative here). The amplitude of a
  !> harmonic u is sqrt(u^2 + (u'/W)^2) at any instant; after 100 s the transient has decayed
  !> by e^{-zeta w t} = 2e-14.
  subroutine test_harmonic_steady_state()
    real(wp), parameter :: damping = 0.05_wp, amplitude = 0.8_wp, t_end = 100.0_wp
    real(wp) :: omega, forcing, r, dt, steady, interpolated, measured, sinc, half
    real(wp), allocatable :: accel(:), u(:), v(:), a_abs(:)
    integer :: n, i

    omega = 2*pi
    forcing = 0.8_wp*omega
    r = forcing/omega
    dt = (2*pi/forcing)/1000
    n = nint(t_end/dt)
    allocate (accel(n + 1), u(n + 1), v(n + 1), a_abs(n + 1))
    accel = [(amplitude*sin(forcing*i*dt), i = 0, n)]
    call sdof_response(dt, accel, omega, damping, 0.0_wp, 0.0_wp, u, v, a_abs, status, message)
    steady = (amplitude/omega**2)/sqrt((1 - r**2)**2 + (2*damping*r)**2)
    half = forcing*dt/2
    sinc = sin(half)/half
    interpolated = steady*sinc**2
    measured = sqrt(u(n + 1)**2 + (v(n + 1)/forcing)**2)
    call check_close('harmonic: steady amplitude = closed form x sinc^2(W dt/2)', measured, &
                     interpolated, 1.0e-9_wp)
    call check_close('harmonic: steady amplitude = closed form to (W dt)^2/12', measured, &
                     steady, 1.1_wp*half**2/3)
    print '(a, es10.2)', '    measured relative difference from the interpolated-load amplitude: ', &
      abs(measured - interpolated)/interpolated
  end subroutine test_harmonic_steady_state

  !> A second method: Newmark's average acceleration (gamma = 1/2, beta = 1/4; Chopra sec 5.4)
  !> on the same piecewise-linear load with substeps dt/n. It is second order, so its error
  !> against the exact recurrence must fall by 4 when n doubles (n = 50 -> 100; below dt/400
  !> Newmark's own round-off, ~6e-8 of the peak here, starts to show), and be small at n = 100:
  !> its period error (w h)^2/12 (Chopra sec 5.5) over w t_end = 50 rad gives
  !> (2.5e-3)^2/12 * 50 = 2.6e-5 of the amplitude at most.
  subroutine test_newmark()
    integer, parameter :: n_samples = 201
    real(wp), parameter :: dt = 0.02_wp, damping = 0.05_wp
    real(wp) :: accel(n_samples), u(n_samples), v(n_samples), a_abs(n_samples), omega, peak
    real(wp) :: error_50, error_100
    integer :: i

    omega = 2*pi/0.5_wp
    do i = 1, n_samples
      accel(i) = sin(1.3_wp*i) + 0.5_wp*cos(0.7_wp*real(i, wp)**2/n_samples)
    end do
    call sdof_response(dt, accel, omega, damping, 0.0_wp, 0.0_wp, u, v, a_abs, status, message)
    peak = maxval(abs(u))
    error_50 = newmark_error(50, dt, accel, u, omega, damping)
    error_100 = newmark_error(100, dt, accel, u, omega, damping)
    call check_close('Newmark (dt/100): max |u_newmark - u| / max |u|', error_100/peak, 0.0_wp, &
                     0.0_wp, 2.6e-5_wp)
    call check_close('Newmark: error ratio between dt/50 and dt/100 = 4 (second order)', &
                     error_50/error_100, 4.0_wp, 0.01_wp)
    print '(a, 2es10.2, f8.4)', '    measured Newmark errors (dt/50, dt/100) and ratio: ', &
      error_50/peak, error_100/peak, error_50/error_100
  end subroutine test_newmark

  !> The coefficients: (a) the series (omega dt < 1) and the closed form (omega dt >= 1) meet
  !> continuously at the switch; (b) at small omega dt, zeta = 0, D = (1 - sin h/h)/w^2
  !> = dt^2 (1/6 - h^2/120 + h^4/5040) (the response at the end of a step to a load rising from
  !> 0 to 1), which the closed form would lose to cancellation; (c) the closed form of Chopra
  !> Table 5.2.1 written out here at omega dt = 0.6 agrees with the series.
  subroutine test_coefficients()
    real(wp) :: below(2, 4), above(2, 4), c(2, 4), omega, dt, h, e, s, co, root, zeta
    integer :: i, j
    character(len=2), parameter :: names(2, 4) = reshape( &
      ['A ', 'A''', 'B ', 'B''', 'C ', 'C''', 'D ', 'D'''], [2, 4])

    omega = 3.0_wp
    ! omega dt = 1 -+ 1e-14: the coefficients themselves move by ~1e-14 (derivatives of order 1)
    call nigam_jennings_coefficients(omega, 0.2_wp, (1 - 1.0e-14_wp)/omega, below, status, message)
    call nigam_jennings_coefficients(omega, 0.2_wp, (1 + 1.0e-14_wp)/omega, above, status, message)
    do j = 1, 4
      do i = 1, 2
        call check_close('coefficients continuous at omega dt = 1: '//names(i, j), below(i, j), &
                         above(i, j), 1.0e-13_wp, 1.0e-14_wp)
      end do
    end do
    h = 1.0e-4_wp
    dt = h/omega
    call nigam_jennings_coefficients(omega, 0.0_wp, dt, c, status, message)
    call check_close('D at omega dt = 1e-4 = dt^2 (1/6 - h^2/120)', c(1, 4), &
                     dt**2*(1.0_wp/6 - h**2/120 + h**4/5040), 1.0e-14_wp)
    ! (c) closed form written out independently
    zeta = 0.3_wp
    h = 0.6_wp
    dt = h/omega
    root = sqrt(1 - zeta**2)
    e = exp(-zeta*h)
    s = sin(root*h)
    co = cos(root*h)
    call nigam_jennings_coefficients(omega, zeta, dt, c, status, message)
    call check_close('series = Table 5.2.1 at omega dt = 0.6: A', c(1, 1), e*(zeta/root*s + co), &
                     1.0e-13_wp)
    call check_close('series = Table 5.2.1 at omega dt = 0.6: B', c(1, 2), e*s/(omega*root), &
                     1.0e-13_wp)
    call check_close('series = Table 5.2.1 at omega dt = 0.6: C', c(1, 3), (2*zeta/h + e*(((1 - &
                     2*zeta**2)/(root*h) - zeta/root)*s - (1 + 2*zeta/h)*co))/omega**2, 1.0e-12_wp)
    call check_close('series = Table 5.2.1 at omega dt = 0.6: D', c(1, 4), (1 - 2*zeta/h + &
                     e*((2*zeta**2 - 1)/(root*h)*s + 2*zeta/h*co))/omega**2, 1.0e-12_wp)
    call check_close('series = Table 5.2.1 at omega dt = 0.6: A''', c(2, 1), -e*omega/root*s, &
                     1.0e-13_wp)
    call check_close('series = Table 5.2.1 at omega dt = 0.6: B''', c(2, 2), e*(co - zeta/root*s), &
                     1.0e-13_wp)
    call check_close('series = Table 5.2.1 at omega dt = 0.6: C''', c(2, 3), (-1/dt + &
                     e*((omega/root + zeta/(dt*root))*s + co/dt))/omega**2, 1.0e-12_wp)
    call check_close('series = Table 5.2.1 at omega dt = 0.6: D''', c(2, 4), &
                     (1 - e*(zeta/root*s + co))/(omega**2*dt), 1.0e-12_wp)
  end subroutine test_coefficients

  !> Spectrum: (a) sd is the peak |u| of the time history, sv = w sd, psa = w^2 sd;
  !> (b) rigid limit T -> 0: the oscillator follows the ground quasi-statically, so psa -> PGA;
  !> the corners of the piecewise-linear load excite transients of relative size ~2/(w dt)
  !> = 3e-3 here (a slope jump ds leaves a velocity mismatch ds/w^2, amplitude ds/w^3);
  !> (c) a 1 s pulse and T = 4 s, zeta = 0: the peak comes after the record; with a tail it is
  !> the free-vibration amplitude sqrt(u^2 + (v/w)^2) of the end state, sampled at dt (within
  !> 1 - cos(w dt/2)); without a tail it is smaller.
  subroutine test_spectrum()
    integer, parameter :: n = 101
    real(wp), parameter :: dt = 0.01_wp
    real(wp) :: accel(n), u(n), v(n), a_abs(n), periods(3), sd(3), sv(3), psa(3), omega
    real(wp) :: sd_tail(1), sv_tail(1), psa_tail(1), amplitude, pulse(31)
    integer :: i

    accel = [(sin(pi*i*dt)*(1 + 0.3_wp*cos(7*i*dt)), i = 0, n - 1)]   ! ends at 0
    periods = [0.2_wp, 0.75_wp, 1.0e-4_wp]
    call response_spectrum(dt, accel, periods, 0.05_wp, sd, sv, psa, status, message)
    call check_true('spectrum: status', status == SD_OK)
    do i = 1, 2
      omega = 2*pi/periods(i)
      call sdof_response(dt, accel, omega, 0.05_wp, 0.0_wp, 0.0_wp, u, v, a_abs, status, message)
      call check_close('spectrum: sd = peak |u| of the history, T = '//trim(rtoa(periods(i))), &
                       sd(i), maxval(abs(u)), 1.0e-15_wp)
      call check_close('spectrum: sv = w sd', sv(i), omega*sd(i), 1.0e-15_wp)
      call check_close('spectrum: psa = w^2 sd', psa(i), omega**2*sd(i), 1.0e-15_wp)
    end do
    call check_close('spectrum: psa(T = 1e-4 s) = PGA (rigid limit)', psa(3), maxval(abs(accel)), &
                     5.0e-3_wp)
    print '(a, es10.2)', '    measured |psa(1e-4 s)/PGA - 1|: ', abs(psa(3)/maxval(abs(accel)) - 1)

    ! a 0.3 s half-sine pulse, T = 4 s: at its end u ~ -(0.3)^2/pi = -0.029 m and
    ! v ~ -0.6/pi = -0.19 m/s, so the free amplitude ~ sqrt(0.029^2 + (0.19/1.571)^2) = 0.125 m
    ! is reached after the record, and the peak within the record is < amplitude/2.
    omega = 2*pi/4.0_wp
    pulse = [(sin(pi*i*dt/0.3_wp), i = 0, 30)]
    call sdof_response(dt, pulse, omega, 0.0_wp, 0.0_wp, 0.0_wp, u(1:31), v(1:31), a_abs(1:31), &
                       status, message)
    amplitude = sqrt(u(31)**2 + (v(31)/omega)**2)
    call response_spectrum(dt, pulse, [4.0_wp], 0.0_wp, sd_tail, sv_tail, psa_tail, status, &
                           message, tail_duration=4.0_wp)
    call check_close('spectrum tail: sd(T = 4 s) = free-vibration amplitude after the record', &
                     sd_tail(1), amplitude, 1 - cos(omega*dt/2), 1.0e-15_wp)
    call response_spectrum(dt, pulse, [4.0_wp], 0.0_wp, sd, sv, psa, status, message)
    call check_true('spectrum without tail misses the late peak (sd < amplitude/2 here)', &
                    sd(1) < 0.5_wp*amplitude)
    print '(a, 3es12.4)', '    measured sd without tail, with tail, free amplitude: ', sd(1), &
      sd_tail(1), amplitude
  end subroutine test_spectrum

  subroutine test_bad_input()
    real(wp) :: c(2, 4), accel(4), u(4), v(4), a_abs(4), sd(2), sv(2), psa(2)
    real(wp) :: nan

    accel = [0.0_wp, 1.0_wp, 0.5_wp, 0.0_wp]
    call nigam_jennings_coefficients(2.0_wp, 1.0_wp, 0.01_wp, c, status, message)
    call check_true('zeta = 1 refused, message names damping', &
                    status == SD_BAD_INPUT .and. index(message, 'damping = 1') == 1)
    call nigam_jennings_coefficients(2.0_wp, 1.5_wp, 0.01_wp, c, status, message)
    call check_true('zeta > 1 refused', status == SD_BAD_INPUT)
    call nigam_jennings_coefficients(0.0_wp, 0.05_wp, 0.01_wp, c, status, message)
    call check_true('omega = 0 refused, message names omega', &
                    status == SD_BAD_INPUT .and. index(message, 'omega = 0') == 1)
    call sdof_response(-0.01_wp, accel, 2.0_wp, 0.05_wp, 0.0_wp, 0.0_wp, u, v, a_abs, status, &
                       message)
    call check_true('dt < 0 refused, message names dt', &
                    status == SD_BAD_INPUT .and. index(message, 'dt = -0.01') == 1)
    nan = ieee_value(nan, ieee_quiet_nan)
    accel(3) = nan
    call sdof_response(0.01_wp, accel, 2.0_wp, 0.05_wp, 0.0_wp, 0.0_wp, u, v, a_abs, status, message)
    call check_true('NaN sample refused, message names accel(3)', &
                    status == SD_BAD_INPUT .and. index(message, 'accel(3) = NaN') == 1)
    accel(3) = 0.5_wp
    call response_spectrum(0.01_wp, accel, [0.5_wp, 0.0_wp], 0.05_wp, sd, sv, psa, status, message)
    call check_true('period 0 refused, message names periods(2)', &
                    status == SD_BAD_INPUT .and. index(message, 'periods(2) = 0') == 1)
    call response_spectrum(0.01_wp, accel, [0.5_wp, 1.0_wp], 0.05_wp, sd, sv, psa, status, &
                           message, tail_duration=-1.0_wp)
    call check_true('negative tail refused, message names tail_duration', &
                    status == SD_BAD_INPUT .and. index(message, 'tail_duration = -1') == 1)
    print '(a)', '    last message: '//trim(message)
  end subroutine test_bad_input

  !> Newmark average acceleration (Chopra Table 5.4.2, gamma = 1/2, beta = 1/4, unit mass) on the
  !> piecewise-linear load -accel with substeps dt/substeps; max |x - u| at the samples.
  real(wp) function newmark_error(substeps, dt, accel, u, omega, damping) result(worst)
    integer, intent(in) :: substeps
    real(wp), intent(in) :: dt, accel(:), u(:), omega, damping
    real(wp) :: h, x, xd, xdd, p_next, k_hat, x_next, xd_next, xdd_next, frac
    integer :: sample, j
    h = dt/substeps
    x = 0
    xd = 0
    xdd = -accel(1)
    worst = 0
    k_hat = omega**2 + 2*damping*omega*2/h + 4/h**2
    do sample = 1, size(accel) - 1
      do j = 1, substeps
        frac = real(j, wp)/substeps
        p_next = -((1 - frac)*accel(sample) + frac*accel(sample + 1))
        x_next = (p_next + (4/h**2 + 2*damping*omega*2/h)*x + (4/h + 2*damping*omega)*xd &
                  + xdd)/k_hat
        xd_next = 2*(x_next - x)/h - xd
        xdd_next = 4*(x_next - x)/h**2 - 4*xd/h - xdd
        x = x_next
        xd = xd_next
        xdd = xdd_next
      end do
      worst = max(worst, abs(x - u(sample + 1)))
    end do
  end function newmark_error

  function itoa(i) result(text)
    integer, intent(in) :: i
    character(len=12) :: text
    write (text, '(i0)') i
  end function itoa

  function rtoa(x) result(text)
    real(wp), intent(in) :: x
    character(len=16) :: text
    write (text, '(g0.4)') x
  end function rtoa
end program test_sdof
