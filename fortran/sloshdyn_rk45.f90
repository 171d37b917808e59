!> Explicit Runge-Kutta integrator: the Dormand-Prince 5(4) pair as in Hairer's DOPRI5
!> (Hairer, Norsett & Wanner, Solving Ordinary Differential Equations I, 2nd ed.: step-size
!> control sec. II.4, the pair sec. II.5, dense output sec. II.6; and the published dopri5.f):
!> FSAL (6 new right-hand sides per step), the stabilised (PI) step-size control, HINIT's
!> automatic first step, and dense output by the 4th-order continuous extension (CONTD5), so
!> output times never shorten a step. Integrates forward in time only.
!>
!> Step-wise use: rk45_init once, then rk45_step until integ%t == integ%t_bound, reading values
!> inside the last step [integ%t_old, integ%t] with rk45_dense. rk45_integrate does this for a
!> list of output times.
module sloshdyn_rk45
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_value, ieee_quiet_nan
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, SD_STEP_TOO_SMALL, SD_TOO_MANY_STEPS, &
                             SD_NON_FINITE, check_real
  use sloshdyn_text, only: num2str
  implicit none
  private
  public :: ode_system, ode_rhs, rk45_options, rk45_integrator, rk45_stats
  public :: rk45_init, rk45_step, rk45_dense, rk45_set_state, rk45_statistics, rk45_integrate, &
            rk45_check_setup, plan_trial

  !> A system y' = f(t, y); extend it with the parameters f depends on.
  type, abstract :: ode_system
  contains
    procedure(ode_rhs), deferred :: rhs
  end type ode_system

  abstract interface
    subroutine ode_rhs(self, t, y, dydt)
      import :: wp, ode_system
      class(ode_system), intent(in) :: self
      real(wp), intent(in) :: t, y(:)
      real(wp), intent(out) :: dydt(:)
    end subroutine ode_rhs
  end interface

  !> Integrator settings; the defaults are DOPRI5's where it has one.
  type :: rk45_options
    real(wp) :: rtol = 1.0e-8_wp   !< relative tolerance, >= 10*epsilon
    real(wp) :: atol = 1.0e-10_wp  !< absolute tolerance for every component, >= 0
    !> per-component absolute tolerances (size(y0), each >= 0); replace atol when allocated
    real(wp), allocatable :: atol_vector(:)
    real(wp) :: h_initial = 0      !< first step; 0 = automatic (HINIT of dopri5.f)
    real(wp) :: h_max = 0          !< largest step; 0 = no limit but t_bound - t0
    !> smallest step error control may ask for; 0 = 1e-14*max(1, |tau|). Any step must also
    !> exceed ten rounding units of tau (10*epsilon*|tau|), else tau + h == tau.
    real(wp) :: h_min = 0
    integer :: max_steps = 10**7   !< limit on attempted (accepted + rejected) steps
    real(wp) :: safety = 0.9_wp    !< safety factor of the step-size formula, in (1e-4, 1)
    real(wp) :: fac1 = 0.2_wp      !< fac1 <= h_new/h_old <= fac2, with 0 < fac1 <= 1 <= fac2
    real(wp) :: fac2 = 10.0_wp
    real(wp) :: beta = 0.04_wp     !< PI (Lund) stabilisation exponent, in [0, 0.2]
    !> > 0: steps of exactly this size, no error control (the last step is shortened to end
    !> at t_bound); h_initial, h_max and the PI settings are then ignored. 0 = adaptive.
    real(wp) :: fixed_step = 0
  end type rk45_options

  !> Work counts of an integration and how far it got.
  type :: rk45_stats
    integer :: n_rhs = 0        !< right-hand side evaluations
    integer :: n_accepted = 0   !< accepted steps
    integer :: n_rejected = 0   !< rejected steps (including those before the first acceptance)
    real(wp) :: t_reached = 0   !< time of the last accepted step
  end type rk45_stats

  !> State of one integration; all work arrays are allocated by rk45_init, none while stepping.
  !> The public components are for reading: change the state only through rk45_set_state.
  type :: rk45_integrator
    real(wp) :: t = 0                !< current time (end of the last accepted step)
    real(wp) :: t_old = 0            !< start of the last accepted step
    real(wp) :: t_bound = 0          !< final time; the last step is clipped to end exactly here
    real(wp), allocatable :: y(:)    !< state at t
    integer :: n_rhs = 0             !< right-hand side evaluations
    integer :: n_accepted = 0        !< accepted steps
    integer :: n_rejected = 0        !< rejected steps
    type(rk45_options), private :: opt
    real(wp), allocatable, private :: atol(:)      !< absolute tolerance per component
    real(wp), allocatable, private :: k(:, :)      !< stages k1..k7; k7 = f(t+h, y_new) is next k1
    real(wp), allocatable, private :: y_stage(:), y_new(:), y_err(:)
    real(wp), allocatable, private :: cont(:, :)   !< rcont1..rcont5 of dopri5.f for CONTD5
    real(wp), private :: h = 0         !< step to try next
    real(wp), private :: h_done = 0    !< size of the last accepted step (0 = none yet)
    real(wp), private :: h_max = 0     !< options%h_max, or t_bound - t0 when that is 0
    real(wp), private :: fac_old = 1.0e-4_wp  !< previous accepted error norm (FACOLD)
    logical, private :: rejected = .false.    !< the previous trial step was rejected
  end type rk45_integrator

  ! Dormand-Prince 5(4) tableau, as in dopri5.f (HNW I, sec. II.5)
  real(wp), parameter :: c2 = 1.0_wp/5, c3 = 3.0_wp/10, c4 = 4.0_wp/5, c5 = 8.0_wp/9
  real(wp), parameter :: a21 = 1.0_wp/5
  real(wp), parameter :: a31 = 3.0_wp/40, a32 = 9.0_wp/40
  real(wp), parameter :: a41 = 44.0_wp/45, a42 = -56.0_wp/15, a43 = 32.0_wp/9
  real(wp), parameter :: a51 = 19372.0_wp/6561, a52 = -25360.0_wp/2187, &
                         a53 = 64448.0_wp/6561, a54 = -212.0_wp/729
  real(wp), parameter :: a61 = 9017.0_wp/3168, a62 = -355.0_wp/33, a63 = 46732.0_wp/5247, &
                         a64 = 49.0_wp/176, a65 = -5103.0_wp/18656
  ! 5th-order weights; the 7th stage is evaluated at the new point (FSAL)
  real(wp), parameter :: a71 = 35.0_wp/384, a73 = 500.0_wp/1113, a74 = 125.0_wp/192, &
                         a75 = -2187.0_wp/6784, a76 = 11.0_wp/84
  ! 5th- minus 4th-order weights: the local error estimate
  real(wp), parameter :: e1 = 71.0_wp/57600, e3 = -71.0_wp/16695, e4 = 71.0_wp/1920, &
                         e5 = -17253.0_wp/339200, e6 = 22.0_wp/525, e7 = -1.0_wp/40
  ! Shampine's dense output coefficients d1..d7 of dopri5.f (d2 = 0), for rcont5
  real(wp), parameter :: d1 = -12715105075.0_wp/11282082432.0_wp, &
                         d3 = 87487479700.0_wp/32700410799.0_wp, &
                         d4 = -10690763975.0_wp/1880347072.0_wp, &
                         d5 = 701980252875.0_wp/199316789632.0_wp, &
                         d6 = -1453857185.0_wp/822651844.0_wp, &
                         d7 = 69997945.0_wp/29380423.0_wp

  !> In fixed-step mode a remainder this much longer than the step (relative) is taken as one
  !> last step, so rounding in tau never leaves a sliver step at t_bound.
  real(wp), parameter :: fixed_slack = 1.0e-6_wp

contains

  !> Validate the inputs, allocate the work arrays and evaluate f(t0, y0); choose the first step.
  subroutine rk45_init(integ, sys, t0, y0, t_bound, options, status, message)
    type(rk45_integrator), intent(out) :: integ
    class(ode_system), intent(in) :: sys
    real(wp), intent(in) :: t0, y0(:), t_bound
    type(rk45_options), intent(in) :: options
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    integer :: n

    status = SD_OK
    message = ''
    call rk45_check_setup(options, y0, status, message)
    call check_real('t0', t0, -huge(t0), huge(t0), .false., .false., 't0 must be finite', &
                    status, message)
    call check_real('t_bound', t_bound, t0, huge(t0), .true., .false., &
                    't_bound must be finite and > t0 = '//num2str(t0), status, message)
    if (status /= SD_OK) return

    n = size(y0)
    allocate (integ%y(n), integ%atol(n), integ%k(n, 7), integ%y_stage(n), integ%y_new(n), &
              integ%y_err(n), integ%cont(n, 5))
    integ%opt = options
    if (allocated(options%atol_vector)) then
      integ%atol = options%atol_vector
    else
      integ%atol = options%atol
    end if
    integ%t = t0
    integ%t_old = t0
    integ%t_bound = t_bound
    integ%y = y0
    integ%h_max = merge(options%h_max, t_bound - t0, options%h_max > 0)

    call sys%rhs(t0, integ%y, integ%k(:, 1))
    integ%n_rhs = 1
    if (.not. all(ieee_is_finite(integ%k(:, 1)))) then
      status = SD_NON_FINITE
      message = 'the right-hand side is NaN or infinite at the initial state, tau = '//num2str(t0)
      return
    end if

    if (options%fixed_step > 0) then
      integ%h = options%fixed_step
    else if (options%h_initial > 0) then
      integ%h = min(options%h_initial, integ%h_max)
    else
      call initial_step(integ, sys, integ%h)
    end if
  end subroutine rk45_init

  !> Advance by one accepted step (rejected trial steps are retried inside). On failure the
  !> integrator stays at its last accepted step.
  subroutine rk45_step(integ, sys, status, message)
    type(rk45_integrator), intent(inout) :: integ
    class(ode_system), intent(in) :: sys
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: h, t_new, err, fac11, fac, h_new
    logical :: finite, fixed, non_finite_trial

    status = SD_OK
    message = ''
    if (.not. allocated(integ%k)) then
      status = SD_BAD_INPUT
      message = 'rk45_step needs an integrator set up by a successful rk45_init'
      return
    end if
    if (integ%t >= integ%t_bound) then
      status = SD_BAD_INPUT
      message = 'the integration already reached t_bound = '//num2str(integ%t_bound)
      return
    end if

    fixed = integ%opt%fixed_step > 0
    non_finite_trial = .false.
    do
      call plan_trial(integ%opt, integ%t, integ%t_bound, integ%h, &
                      integ%n_accepted + integ%n_rejected, non_finite_trial, h, t_new, status, &
                      message)
      if (status /= SD_OK) return

      call trial_step(integ, sys, h, t_new, finite)
      non_finite_trial = .not. finite

      if (fixed) then
        if (.not. finite) then
          status = SD_NON_FINITE
          message = 'the state became NaN or infinite in the fixed step from tau = '// &
                    num2str(integ%t)//' to '//num2str(t_new)
          return
        end if
        call accept(integ, h, t_new)
        return
      end if

      if (.not. finite) then
        ! the trial left the region where f is defined: retry with the largest allowed cut
        integ%h = h*integ%opt%fac1
        integ%rejected = .true.
        integ%n_rejected = integ%n_rejected + 1
        cycle
      end if

      ! step-size control of DOPRI5: h_new = h*safety/(err**expo1/err_old**beta), clamped
      err = error_norm(integ%y_err, integ%y, integ%y_new, integ%atol, integ%opt%rtol)
      fac11 = err**(0.2_wp - 0.75_wp*integ%opt%beta)
      fac = fac11/integ%fac_old**integ%opt%beta
      fac = max(1/integ%opt%fac2, min(1/integ%opt%fac1, fac/integ%opt%safety))
      h_new = h/fac
      if (err <= 1) then
        integ%fac_old = max(err, 1.0e-4_wp)
        call accept(integ, h, t_new)
        h_new = min(h_new, integ%h_max)
        ! no growth right after a rejection
        if (integ%rejected) h_new = min(h_new, h)
        integ%rejected = .false.
        integ%h = h_new
        return
      end if
      ! rejected: the plain (non-PI) formula, as in DOPRI5
      integ%h = h/min(1/integ%opt%fac1, fac11/integ%opt%safety)
      integ%rejected = .true.
      integ%n_rejected = integ%n_rejected + 1
    end do
  end subroutine rk45_step

  !> Value at t of the continuous extension over the last accepted step [t_old, t] (CONTD5 of
  !> dopri5.f, 4th order). Outside that step it extrapolates; before any step it returns y.
  pure subroutine rk45_dense(integ, t, y)
    type(rk45_integrator), intent(in) :: integ
    real(wp), intent(in) :: t
    real(wp), intent(out) :: y(:)
    real(wp) :: s, s1

    if (integ%h_done == 0) then
      y = integ%y
      return
    end if
    s = (t - integ%t_old)/integ%h_done
    s1 = 1 - s
    y = integ%cont(:, 1) + s*(integ%cont(:, 2) + s1*(integ%cont(:, 3) + &
        s*(integ%cont(:, 4) + s1*integ%cont(:, 5))))
  end subroutine rk45_dense

  !> Replace the state at the current time (e.g. to renormalise variational vectors). This
  !> re-evaluates f for FSAL and ends dense output of the previous step; the step size is kept.
  subroutine rk45_set_state(integ, sys, y, status, message)
    type(rk45_integrator), intent(inout) :: integ
    class(ode_system), intent(in) :: sys
    real(wp), intent(in) :: y(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message

    status = SD_OK
    message = ''
    if (.not. allocated(integ%k)) then
      status = SD_BAD_INPUT
      message = 'rk45_set_state needs an integrator set up by a successful rk45_init'
      return
    end if
    if (size(y) /= size(integ%y)) then
      status = SD_BAD_INPUT
      message = 'y has size '//num2str(size(y))//'; the integrator state has size '// &
                num2str(size(integ%y))
      return
    end if
    if (.not. all(ieee_is_finite(y))) then
      status = SD_BAD_INPUT
      message = 'y is out of range: the new state must be finite'
      return
    end if
    integ%y = y
    call sys%rhs(integ%t, integ%y, integ%k(:, 1))
    integ%n_rhs = integ%n_rhs + 1
    integ%t_old = integ%t
    integ%h_done = 0
    if (.not. all(ieee_is_finite(integ%k(:, 1)))) then
      status = SD_NON_FINITE
      message = 'the right-hand side is NaN or infinite at the new state, tau = '//num2str(integ%t)
    end if
  end subroutine rk45_set_state

  !> Counters of the integration so far and the time reached.
  pure function rk45_statistics(integ) result(stats)
    type(rk45_integrator), intent(in) :: integ
    type(rk45_stats) :: stats
    stats = rk45_stats(integ%n_rhs, integ%n_accepted, integ%n_rejected, integ%t)
  end function rk45_statistics

  !> y at every time of t_out (ascending, all >= t0) by dense output: y_out(:, j) = y(t_out(j)),
  !> shape (size(y0), size(t_out)). On failure the columns already reached are filled, the rest
  !> are NaN, and stats%t_reached says how far the integration got.
  subroutine rk45_integrate(sys, t0, y0, t_out, y_out, options, stats, status, message)
    class(ode_system), intent(in) :: sys
    real(wp), intent(in) :: t0, y0(:), t_out(:)
    real(wp), intent(out) :: y_out(:, :)
    type(rk45_options), intent(in) :: options
    type(rk45_stats), intent(out) :: stats
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(rk45_integrator) :: integ
    integer :: j, n_out

    status = SD_OK
    message = ''
    stats%t_reached = t0
    y_out = ieee_value(1.0_wp, ieee_quiet_nan)
    n_out = size(t_out)
    if (size(y_out, 1) /= size(y0) .or. size(y_out, 2) /= n_out) then
      status = SD_BAD_INPUT
      message = 'y_out has shape ('//num2str(size(y_out, 1))//', '//num2str(size(y_out, 2))// &
                '); it must be (size(y0), size(t_out)) = ('//num2str(size(y0))//', '// &
                num2str(n_out)//')'
      return
    end if
    if (n_out > 0) call check_real('t_out(1)', t_out(1), t0, huge(t0), .false., .false., &
                                   't_out must start at or after t0 = '//num2str(t0), status, &
                                   message)
    do j = 2, n_out
      if (t_out(j) >= t_out(j - 1) .and. t_out(j) <= huge(t0)) cycle
      call check_real('t_out('//num2str(j)//')', t_out(j), t_out(j - 1), huge(t0), .false., &
                      .false., 't_out must be ascending, >= t_out('//num2str(j - 1)//') = '// &
                      num2str(t_out(j - 1)), status, message)
      exit
    end do
    call rk45_check_setup(options, y0, status, message)
    if (status /= SD_OK) return

    ! outputs at t0 itself need no step
    j = 1
    do while (j <= n_out)
      if (t_out(j) > t0) exit
      y_out(:, j) = y0
      j = j + 1
    end do
    if (j > n_out) return

    call rk45_init(integ, sys, t0, y0, t_out(n_out), options, status, message)
    do while (status == SD_OK .and. j <= n_out)
      call rk45_step(integ, sys, status, message)
      if (status /= SD_OK) exit
      do while (j <= n_out)
        if (t_out(j) > integ%t) exit
        if (t_out(j) == integ%t) then
          y_out(:, j) = integ%y
        else
          call rk45_dense(integ, t_out(j), y_out(:, j))
        end if
        j = j + 1
      end do
    end do
    stats = rk45_statistics(integ)
  end subroutine rk45_integrate

  !> One trial step of size h from (t, y) to t_new: the stages, y_new (5th order), k7 = f(t_new,
  !> y_new) and the error estimate y_err. finite = .false. when any of them is NaN or infinite.
  subroutine trial_step(integ, sys, h, t_new, finite)
    type(rk45_integrator), intent(inout) :: integ
    class(ode_system), intent(in) :: sys
    real(wp), intent(in) :: h, t_new
    logical, intent(out) :: finite
    real(wp) :: t

    t = integ%t
    associate (y => integ%y, k => integ%k, ys => integ%y_stage, yn => integ%y_new)
      ys = y + h*a21*k(:, 1)
      call sys%rhs(t + c2*h, ys, k(:, 2))
      ys = y + h*(a31*k(:, 1) + a32*k(:, 2))
      call sys%rhs(t + c3*h, ys, k(:, 3))
      ys = y + h*(a41*k(:, 1) + a42*k(:, 2) + a43*k(:, 3))
      call sys%rhs(t + c4*h, ys, k(:, 4))
      ys = y + h*(a51*k(:, 1) + a52*k(:, 2) + a53*k(:, 3) + a54*k(:, 4))
      call sys%rhs(t + c5*h, ys, k(:, 5))
      ys = y + h*(a61*k(:, 1) + a62*k(:, 2) + a63*k(:, 3) + a64*k(:, 4) + a65*k(:, 5))
      call sys%rhs(t_new, ys, k(:, 6))
      yn = y + h*(a71*k(:, 1) + a73*k(:, 3) + a74*k(:, 4) + a75*k(:, 5) + a76*k(:, 6))
      call sys%rhs(t_new, yn, k(:, 7))
      integ%y_err = h*(e1*k(:, 1) + e3*k(:, 3) + e4*k(:, 4) + e5*k(:, 5) + e6*k(:, 6) + &
                       e7*k(:, 7))
      finite = all(ieee_is_finite(yn)) .and. all(ieee_is_finite(k(:, 7))) .and. &
               all(ieee_is_finite(integ%y_err))
    end associate
    integ%n_rhs = integ%n_rhs + 6
  end subroutine trial_step

  !> Accept the trial step: store the dense output coefficients (rcont1..rcont5 of dopri5.f)
  !> and move to (t_new, y_new), reusing k7 as the next k1 (FSAL).
  pure subroutine accept(integ, h, t_new)
    type(rk45_integrator), intent(inout) :: integ
    real(wp), intent(in) :: h, t_new

    associate (y => integ%y, k => integ%k, cont => integ%cont)
      cont(:, 1) = y
      cont(:, 2) = integ%y_new - y
      cont(:, 3) = h*k(:, 1) - cont(:, 2)
      cont(:, 4) = cont(:, 2) - h*k(:, 7) - cont(:, 3)
      cont(:, 5) = h*(d1*k(:, 1) + d3*k(:, 3) + d4*k(:, 4) + d5*k(:, 5) + d6*k(:, 6) + &
                      d7*k(:, 7))
      y = integ%y_new
      k(:, 1) = k(:, 7)
    end associate
    integ%t_old = integ%t
    integ%t = t_new
    integ%h_done = h
    integ%n_accepted = integ%n_accepted + 1
  end subroutine accept

  !> HINIT of dopri5.f: an explicit Euler step sized so that its increment is small against y,
  !> then h with h**5 * max(|f|, |f'|) = 0.01 in the scaled norm, at most 100 times the Euler
  !> guess. Uses k2, y_stage and y_err as scratch; one right-hand side evaluation.
  subroutine initial_step(integ, sys, h)
    type(rk45_integrator), intent(inout) :: integ
    class(ode_system), intent(in) :: sys
    real(wp), intent(out) :: h
    real(wp) :: dnf, dny, der2, der12, h1

    associate (y => integ%y, f0 => integ%k(:, 1), f1 => integ%k(:, 2), y1 => integ%y_stage, &
               sk => integ%y_err)
      sk = integ%atol + integ%opt%rtol*abs(y)
      dnf = sum((f0/sk)**2)
      dny = sum((y/sk)**2)
      if (dnf <= 1.0e-10_wp .or. dny <= 1.0e-10_wp) then
        h = 1.0e-6_wp
      else
        h = 0.01_wp*sqrt(dny/dnf)
      end if
      h = min(h, integ%h_max)
      y1 = y + h*f0
      call sys%rhs(integ%t + h, y1, f1)
      integ%n_rhs = integ%n_rhs + 1
      ! f undefined a small step ahead: keep the cautious Euler guess
      if (.not. all(ieee_is_finite(f1))) return
      der2 = sqrt(sum(((f1 - f0)/sk)**2))/h
      der12 = max(der2, sqrt(dnf))
      if (der12 <= 1.0e-15_wp) then
        h1 = max(1.0e-6_wp, h*1.0e-3_wp)
      else
        h1 = (0.01_wp/der12)**0.2_wp
      end if
      h = min(100*h, h1, integ%h_max)
    end associate
  end subroutine initial_step

  !> Hairer's RMS error norm, scale sk = atol_i + rtol*max(|y0_i|, |y1_i|). Zero error terms are
  !> skipped so that a component with sk = 0 (atol_i = 0, y_i = 0) cannot give 0/0.
  pure function error_norm(e, y0, y1, atol, rtol) result(err)
    real(wp), intent(in) :: e(:), y0(:), y1(:), atol(:), rtol
    real(wp) :: err
    integer :: i

    err = 0
    do i = 1, size(e)
      if (e(i) /= 0) err = err + (e(i)/(atol(i) + rtol*max(abs(y0(i)), abs(y1(i)))))**2
    end do
    err = sqrt(err/size(e))
  end function error_norm

  !> Smallest step error control may ask for at time t (see rk45_options%h_min).
  pure function step_floor(h_min, t) result(h_floor)
    real(wp), intent(in) :: h_min, t
    real(wp) :: h_floor
    h_floor = merge(h_min, 1.0e-14_wp*max(1.0_wp, abs(t)), h_min > 0)
    h_floor = max(h_floor, 10*epsilon(t)*abs(t))
  end function step_floor

  !> The next trial step of an embedded Runge-Kutta integrator (rk45 and dop853 share it): the
  !> step budget and the step floor are checked (the floor before clipping: a short last step to
  !> t_bound is no sign of trouble), and the step is clipped to end exactly on t_bound; adaptive
  !> steps are stretched by up to 1 % rather than leave a sliver (as DOPRI5 and DOP853 do).
  pure subroutine plan_trial(opt, t, t_bound, h_wanted, attempts, non_finite_trial, h, t_new, &
                             status, message)
    type(rk45_options), intent(in) :: opt
    real(wp), intent(in) :: t, t_bound, h_wanted
    integer, intent(in) :: attempts
    logical, intent(in) :: non_finite_trial
    real(wp), intent(out) :: h, t_new
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    logical :: last

    status = SD_OK
    message = ''
    h = h_wanted
    t_new = t
    if (attempts >= opt%max_steps) then
      status = SD_TOO_MANY_STEPS
      message = 'max_steps = '//num2str(opt%max_steps)//' steps taken at tau = '// &
                num2str(t)//', before reaching t_bound = '//num2str(t_bound)
      return
    end if
    if (h < step_floor(opt%h_min, t)) then
      if (non_finite_trial) then
        status = SD_NON_FINITE
        message = 'the state became NaN or infinite in every trial step from tau = '// &
                  num2str(t)//', down to h = '//num2str(h/opt%fac1)
      else
        status = SD_STEP_TOO_SMALL
        message = 'step size '//num2str(h)//' below h_min '// &
                  num2str(step_floor(opt%h_min, t))//' at tau = '//num2str(t)
      end if
      return
    end if
    if (opt%fixed_step > 0) then
      last = t + h*(1 + fixed_slack) >= t_bound
    else
      last = t + 1.01_wp*h >= t_bound
    end if
    if (last) then
      h = t_bound - t
      t_new = t_bound
    else
      t_new = t + h
    end if
  end subroutine plan_trial

  !> Checks shared by rk45_init and rk45_integrate (and by input readers that validate before
  !> computing): the options and the initial state.
  pure subroutine rk45_check_setup(options, y0, status, message)
    type(rk45_options), intent(in) :: options
    real(wp), intent(in) :: y0(:)
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    real(wp), parameter :: big = huge(1.0_wp)
    integer :: i

    if (status /= SD_OK) return
    if (size(y0) == 0) then
      status = SD_BAD_INPUT
      message = 'y0 is empty: the system needs at least one component'
      return
    end if
    do i = 1, size(y0)
      if (abs(y0(i)) <= big) cycle
      call check_real('y0('//num2str(i)//')', y0(i), -big, big, .false., .false., &
                      'the initial state must be finite', status, message)
      return
    end do
    call check_real('rtol', options%rtol, 10*epsilon(1.0_wp), big, .false., .false., &
                    'rtol must be >= 10*epsilon = '//num2str(10*epsilon(1.0_wp)), status, message)
    if (allocated(options%atol_vector)) then
      if (status == SD_OK .and. size(options%atol_vector) /= size(y0)) then
        status = SD_BAD_INPUT
        message = 'atol_vector has size '//num2str(size(options%atol_vector))// &
                  '; it must have one entry per component, size(y0) = '//num2str(size(y0))
      end if
      if (status /= SD_OK) return
      do i = 1, size(options%atol_vector)
        if (options%atol_vector(i) >= 0 .and. options%atol_vector(i) <= big) cycle
        call check_real('atol_vector('//num2str(i)//')', options%atol_vector(i), 0.0_wp, big, &
                        .false., .false., 'absolute tolerances must be >= 0', status, message)
        return
      end do
      do i = 1, size(y0)
        if (options%atol_vector(i) == 0 .and. y0(i) == 0) then
          status = SD_BAD_INPUT
          message = 'atol_vector('//num2str(i)//') = 0 is out of range: y0('//num2str(i)// &
                    ') = 0 too, so component '//num2str(i)//' has no error scale; give atol > 0'
          return
        end if
      end do
    else
      call check_real('atol', options%atol, 0.0_wp, big, .false., .false., &
                      'atol must be >= 0', status, message)
      if (status == SD_OK .and. options%atol == 0 .and. any(y0 == 0)) then
        status = SD_BAD_INPUT
        message = 'atol = 0 is out of range: y0 has a zero component, which then has no '// &
                  'error scale; give atol > 0'
      end if
    end if
    call check_real('h_initial', options%h_initial, 0.0_wp, big, .false., .false., &
                    'h_initial must be >= 0 (0 = automatic)', status, message)
    call check_real('h_max', options%h_max, 0.0_wp, big, .false., .false., &
                    'h_max must be >= 0 (0 = no limit)', status, message)
    call check_real('h_min', options%h_min, 0.0_wp, big, .false., .false., &
                    'h_min must be >= 0 (0 = 1e-14*max(1, |tau|))', status, message)
    if (status == SD_OK .and. options%h_max > 0 .and. options%h_min > options%h_max) then
      status = SD_BAD_INPUT
      message = 'h_min = '//num2str(options%h_min)//' is out of range: it must not exceed '// &
                'h_max = '//num2str(options%h_max)
    end if
    if (status == SD_OK .and. options%max_steps < 1) then
      status = SD_BAD_INPUT
      message = 'max_steps = '//num2str(options%max_steps)//' is out of range: it must be >= 1'
    end if
    call check_real('safety', options%safety, 1.0e-4_wp, 1.0_wp, .true., .true., &
                    'safety must lie in (1e-4, 1)', status, message)
    call check_real('fac1', options%fac1, 0.0_wp, 1.0_wp, .true., .false., &
                    'fac1 must lie in (0, 1]', status, message)
    call check_real('fac2', options%fac2, 1.0_wp, big, .false., .false., &
                    'fac2 must be >= 1', status, message)
    call check_real('beta', options%beta, 0.0_wp, 0.2_wp, .false., .false., &
                    'beta must lie in [0, 0.2]', status, message)
    call check_real('fixed_step', options%fixed_step, 0.0_wp, big, .false., .false., &
                    'fixed_step must be >= 0 (0 = adaptive)', status, message)
  end subroutine rk45_check_setup
end module sloshdyn_rk45
