!> Linear single-degree-of-freedom oscillator under a sampled ground acceleration,
!>     u'' + 2 zeta omega u' + omega^2 u = -a_g(t),
!> with a_g piecewise linear between samples taken at a uniform step dt: the exact recurrence of
!> Nigam & Jennings (1969), "Calculation of response spectra from strong-motion earthquake
!> records", Bull. Seism. Soc. Am. 59(2), 909-922 (in the notation of Chopra, Dynamics of
!> Structures, sec. 5.2, Table 5.2.1). The state at sample i+1 follows from the state and the
!> load at samples i and i+1 through eight coefficients that depend only on omega, zeta and dt,
!> so the result is exact (to round-off) for any dt when the load is truly piecewise linear.
!>
!> Round-off: the closed-form coefficients subtract terms of size 1/(omega dt), which loses
!> digits when omega dt is small (long periods, short steps). For omega dt < 1 the same
!> coefficients are taken from the Taylor series of the exponential of the augmented system
!> matrix (state, load, load rate), which has no such cancellation; both are the exact solution
!> of the same piecewise-linear problem and agree to round-off at the switch (tested).
!>
!> Response spectra: peak |u| at the samples for each period (the usual convention); the
!> pseudo-velocity and pseudo-acceleration are omega Sd and omega^2 Sd.
module sloshdyn_sdof
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, check_real
  use sloshdyn_text, only: num2str
  use sloshdyn_cancel, only: check_cancel
  implicit none
  private
  public :: nigam_jennings_coefficients, sdof_response, response_spectrum

  !> omega dt below which the coefficients come from the series (see the module comment).
  real(wp), parameter :: series_below = 1.0_wp
  !> The most steps of the free-vibration tail of a spectrum, and the steps between two polls
  !> of the cancellation flag (sloshdyn_cancel) in the spectrum's loops.
  real(wp), parameter :: max_tail_steps = 1.0e9_wp
  integer, parameter :: steps_per_poll = 65536

contains

  !> The recurrence of one step dt for the load p = -a_g (unit mass):
  !>     u(i+1) = A u + B v + C p(i) + D p(i+1),   v(i+1) = A' u + B' v + C' p(i) + D' p(i+1),
  !> returned as coefficients(1, :) = [A, B, C, D] and coefficients(2, :) = [A', B', C', D']
  !> (Nigam & Jennings 1969; Chopra Table 5.2.1 with k = omega^2, m = 1).
  pure subroutine nigam_jennings_coefficients(omega, damping, dt, coefficients, status, message)
    real(wp), intent(in) :: omega, damping, dt
    real(wp), intent(out) :: coefficients(2, 4)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message

    coefficients = 0
    call check_oscillator(omega, damping, dt, status, message)
    if (status /= SD_OK) return
    if (omega*dt < series_below) then
      call coefficients_by_series(omega, damping, dt, coefficients)
    else
      call coefficients_closed_form(omega, damping, dt, coefficients)
    end if
  end subroutine nigam_jennings_coefficients

  !> Time history at the samples of accel (ground acceleration [m/s^2], step dt [s]) from the
  !> initial state u0 [m], v0 [m/s] at the first sample: relative displacement u, relative
  !> velocity v and absolute acceleration a_abs = u'' + a_g = -2 zeta omega v - omega^2 u.
  pure subroutine sdof_response(dt, accel, omega, damping, u0, v0, u, v, a_abs, status, message)
    real(wp), intent(in) :: dt, accel(:), omega, damping, u0, v0
    real(wp), intent(out) :: u(size(accel)), v(size(accel)), a_abs(size(accel))
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: coefficients(2, 4)
    integer :: i

    u = 0; v = 0; a_abs = 0
    call check_record(dt, accel, status, message)
    call check_real('u0', u0, -huge(1.0_wp), huge(1.0_wp), .false., .false., &
                    'the initial displacement must be finite', status, message)
    call check_real('v0', v0, -huge(1.0_wp), huge(1.0_wp), .false., .false., &
                    'the initial velocity must be finite', status, message)
    if (status /= SD_OK) return
    call nigam_jennings_coefficients(omega, damping, dt, coefficients, status, message)
    if (status /= SD_OK) return
    u(1) = u0
    v(1) = v0
    do i = 1, size(accel) - 1
      call advance(coefficients, -accel(i), -accel(i + 1), u(i), v(i), u(i + 1), v(i + 1))
    end do
    a_abs = -2*damping*omega*v - omega**2*u
  end subroutine sdof_response

  !> Elastic response spectrum of a record (ground acceleration accel [m/s^2] at step dt [s],
  !> the oscillator at rest at the first sample): for each period T [s] of periods, damping
  !> ratio zeta = damping, the peak relative displacement sd = max |u| [m], the pseudo-velocity
  !> sv = omega sd [m/s] and the pseudo-acceleration psa = omega^2 sd [m/s^2], omega = 2 pi/T.
  !>
  !> tail_duration [s] (optional, default 0): the oscillator keeps vibrating freely for this long
  !> after the record, so that a peak after the last sample (long periods, short records) is not
  !> missed. The ground is at rest after the last sample, as in the model's excitation
  !> (sloshdyn_excitation): free vibration from the end state, sampled at the record's step,
  !> also for a record that stops at a nonzero acceleration. The default 0 gives the peak over
  !> the record alone, the usual convention of published spectra; a tail of about the longest
  !> period catches the late peaks; at most max_tail_steps steps of dt.
  !>
  !> A cancellation request (sloshdyn_cancel) stops it within steps_per_poll steps: status
  !> SD_CANCELLED.
  subroutine response_spectrum(dt, accel, periods, damping, sd, sv, psa, status, message, &
                               tail_duration)
    real(wp), intent(in) :: dt, accel(:), periods(:), damping
    real(wp), intent(out) :: sd(size(periods)), sv(size(periods)), psa(size(periods))
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), intent(in), optional :: tail_duration
    real(wp) :: coefficients(2, 4), omega, u, v, u_next, v_next, peak, tail, load(2)
    integer :: j, i, tail_steps

    sd = 0; sv = 0; psa = 0
    tail = 0
    if (present(tail_duration)) tail = tail_duration
    call check_record(dt, accel, status, message)
    call check_real('tail_duration', tail, 0.0_wp, max_tail_steps*dt, &
      .false., .false., 'the free-vibration tail after the record must be >= 0 [s] and at '// &
      'most '//num2str(max_tail_steps)//' steps of dt = '//num2str(dt)//' s', status, message)
    if (status /= SD_OK) return
    tail_steps = ceiling(tail/dt)
    do j = 1, size(periods)
      call check_real('periods('//num2str(j)//')', periods(j), 0.0_wp, huge(1.0_wp), .true., &
                      .true., 'every period must be > 0 [s]', status, message)
      if (status /= SD_OK) return
    end do
    do j = 1, size(periods)
      omega = 2*pi/periods(j)
      call nigam_jennings_coefficients(omega, damping, dt, coefficients, status, message)
      if (status /= SD_OK) return
      u = 0
      v = 0
      peak = 0
      do i = 1, size(accel) - 1 + tail_steps   ! the record, then the free-vibration tail
        load = 0
        if (i < size(accel)) load = -accel(i:i + 1)
        call advance(coefficients, load(1), load(2), u, v, u_next, v_next)
        u = u_next
        v = v_next
        peak = max(peak, abs(u))
        if (mod(i, steps_per_poll) == 0) call check_cancel(status, message)
        if (status /= SD_OK) return
      end do
      sd(j) = peak
      sv(j) = omega*peak
      psa(j) = omega**2*peak
    end do
  end subroutine response_spectrum

  !> One step of the recurrence from (u, v) under the load p_start -> p_end.
  pure subroutine advance(coefficients, p_start, p_end, u, v, u_next, v_next)
    real(wp), intent(in) :: coefficients(2, 4), p_start, p_end, u, v
    real(wp), intent(out) :: u_next, v_next
    u_next = coefficients(1, 1)*u + coefficients(1, 2)*v + coefficients(1, 3)*p_start + &
             coefficients(1, 4)*p_end
    v_next = coefficients(2, 1)*u + coefficients(2, 2)*v + coefficients(2, 3)*p_start + &
             coefficients(2, 4)*p_end
  end subroutine advance

  !> Nigam & Jennings (1969) closed form (Chopra Table 5.2.1), valid for 0 <= zeta < 1.
  pure subroutine coefficients_closed_form(omega, damping, dt, coefficients)
    real(wp), intent(in) :: omega, damping, dt
    real(wp), intent(out) :: coefficients(2, 4)
    real(wp) :: h, root, decay, s, c, k

    h = omega*dt
    root = sqrt(1 - damping**2)
    decay = exp(-damping*h)
    s = sin(root*h)
    c = cos(root*h)
    k = omega**2
    coefficients(1, 1) = decay*(damping/root*s + c)                                  ! A
    coefficients(1, 2) = decay*s/(omega*root)                                        ! B
    coefficients(1, 3) = (2*damping/h + decay*(((1 - 2*damping**2)/(root*h) - damping/root)*s &
                          - (1 + 2*damping/h)*c))/k                                  ! C
    coefficients(1, 4) = (1 - 2*damping/h + decay*((2*damping**2 - 1)/(root*h)*s &
                          + 2*damping/h*c))/k                                        ! D
    coefficients(2, 1) = -decay*omega/root*s                                         ! A'
    coefficients(2, 2) = decay*(c - damping/root*s)                                  ! B'
    coefficients(2, 3) = (-1/dt + decay*((omega/root + damping/(dt*root))*s + c/dt))/k  ! C'
    coefficients(2, 4) = (1 - decay*(damping/root*s + c))/(k*dt)                     ! D'
  end subroutine coefficients_closed_form

  !> The same coefficients from exp(M h), h = omega dt, M the augmented system matrix in the
  !> dimensionless time omega t of z = [u, v/omega, p/omega^2, (dp/d(omega t))/omega^2]:
  !>     z' = [[0, 1, 0, 0], [-1, -2 zeta, 1, 0], [0, 0, 0, 1], [0, 0, 0, 0]] z,
  !> summed as a Taylor series (|M h| < 3 here, so terms fall below round-off within ~30 terms).
  pure subroutine coefficients_by_series(omega, damping, dt, coefficients)
    real(wp), intent(in) :: omega, damping, dt
    real(wp), intent(out) :: coefficients(2, 4)
    real(wp) :: h, step(4, 4), term(4, 4), total(4, 4)
    integer :: n, i

    h = omega*dt
    step = 0
    step(1, 2) = h
    step(2, 1) = -h
    step(2, 2) = -2*damping*h
    step(2, 3) = h
    step(3, 4) = h
    total = 0
    term = 0
    do i = 1, 4
      total(i, i) = 1
      term(i, i) = 1
    end do
    do n = 1, 60
      term = matmul(term, step)/n
      total = total + term
      if (maxval(abs(term)) <= epsilon(1.0_wp)*1.0e-3_wp*maxval(abs(total))) exit
    end do
    ! the load rate entering z(4) is (p(i+1) - p(i))/h in dimensionless time
    coefficients(1, 1) = total(1, 1)
    coefficients(1, 2) = total(1, 2)/omega
    coefficients(1, 3) = (total(1, 3) - total(1, 4)/h)/omega**2
    coefficients(1, 4) = total(1, 4)/(h*omega**2)
    coefficients(2, 1) = total(2, 1)*omega
    coefficients(2, 2) = total(2, 2)
    coefficients(2, 3) = (total(2, 3) - total(2, 4)/h)/omega
    coefficients(2, 4) = total(2, 4)/(h*omega)
  end subroutine coefficients_by_series

  pure subroutine check_oscillator(omega, damping, dt, status, message)
    real(wp), intent(in) :: omega, damping, dt
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    status = SD_OK
    message = ''
    call check_real('omega', omega, 0.0_wp, huge(1.0_wp), .true., .true., &
                    'the circular frequency must be > 0 [rad/s]', status, message)
    call check_real('damping', damping, 0.0_wp, 1.0_wp, .false., .true., &
                    'the damping ratio must be in [0, 1): the recurrence is for an '// &
                    'underdamped oscillator', status, message)
    call check_real('dt', dt, 0.0_wp, huge(1.0_wp), .true., .true., &
                    'the time step must be > 0 [s]', status, message)
  end subroutine check_oscillator

  pure subroutine check_record(dt, accel, status, message)
    real(wp), intent(in) :: dt, accel(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    integer :: i
    status = SD_OK
    message = ''
    call check_real('dt', dt, 0.0_wp, huge(1.0_wp), .true., .true., &
                    'the time step must be > 0 [s]', status, message)
    if (status /= SD_OK) return
    if (size(accel) < 1) then
      status = SD_BAD_INPUT
      message = 'accel is empty: the record needs at least one sample'
      return
    end if
    do i = 1, size(accel)
      if (ieee_is_finite(accel(i))) cycle   ! a number in a message only for a bad sample
      call check_real('accel('//num2str(i)//')', accel(i), -huge(1.0_wp), huge(1.0_wp), &
                      .false., .false., 'every ground acceleration sample must be finite', &
                      status, message)
      return
    end do
  end subroutine check_record
end module sloshdyn_sdof
