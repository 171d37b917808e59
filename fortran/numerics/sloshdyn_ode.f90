!> The explicit Runge-Kutta integrator family (in the style of rklib): the ODE system interface,
!> the options and work counts, and one driver shared by every embedded pair -- step planning,
!> the accept/reject loop with Hairer's stabilised (PI) step-size control, HINIT's automatic
!> first step, replacing the state, and the dense-output loop over output times. A method is a
!> small extension of rk_integrator that supplies its tableau one stage at a time (stage: the
!> input of stage s; trial_error: y_new and the error norm after the trial stages;
!> finish_stages: how many stages follow an accepted error test), its continuous extension
!> (store_dense, dense) and its properties (order, stage counts, step-control defaults). The
!> driver evaluates the right-hand side between the stages, so the same method code serves a
!> single integration (rk_step) and an ensemble (sloshdyn_ensemble), with the same bits. After
!> an accepted error test the stages stop at the first NaN or infinite one (the step is then
!> retried with the largest cut). Integrates forward in time only.
!>
!> Speed: a method does the arithmetic of its stages in a procedure of its own whose arrays are
!> explicit-shape dummies (contiguous, and free of aliasing by the rules of dummy arguments), not
!> on the integrator's allocatable components, whose sums of n-element columns compile to 2-3
!> times the instructions (callgrind, issue 28); the values are the same to the bit.
!>
!> References: Hairer, Norsett & Wanner, Solving Ordinary Differential Equations I, 2nd ed.,
!> sec. II.4 (step-size control), II.5 and II.10 (the pairs), II.6 (dense output); the published
!> dopri5.f and dop853.f.
!>
!> Options follow Hairer's codes: a step-control setting left at 0 takes the method's default
!> (safety 0.9; fac1, fac2, beta = 0.2, 10, 0.04 for DOPRI5 and 0.333, 6, 0 for DOP853); a
!> negative beta means beta = 0 (no PI stabilisation). rtol and atol have one default each,
!> here, for every analysis and both front doors.
module sloshdyn_ode
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_value, ieee_quiet_nan
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, SD_STEP_TOO_SMALL, SD_TOO_MANY_STEPS, &
                             SD_NON_FINITE, check_real
  use sloshdyn_text, only: num2str
  use sloshdyn_cancel, only: check_cancel
  implicit none
  private
  public :: ode_system, ode_rhs, ode_options, ode_stats, rk_integrator, method_properties
  public :: check_options, integrate_with, rms_error_norm, dense_from_state, rk_begin_step
  public :: deliver_outputs, check_outputs
  public :: default_rtol, default_atol, default_max_steps
  public :: observed_quantities, linear_observation, peak_tracker, recorded_steps

  real(wp), parameter :: default_rtol = 1.0e-9_wp   !< relative tolerance unless given
  real(wp), parameter :: default_atol = 1.0e-12_wp  !< absolute tolerance unless given
  integer, parameter :: default_max_steps = 100000000

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

  !> Integrator settings. Step-control settings at 0 take the method's default (see header).
  type :: ode_options
    real(wp) :: rtol = default_rtol   !< relative tolerance, >= 10*epsilon
    real(wp) :: atol = default_atol   !< absolute tolerance for every component, >= 0
    !> per-component absolute tolerances (size(y0), each >= 0); replace atol when allocated
    real(wp), allocatable :: atol_vector(:)
    real(wp) :: h_initial = 0      !< first step; 0 = automatic (HINIT)
    real(wp) :: h_max = 0          !< largest step; 0 = no limit but t_bound - t0
    !> smallest step error control may ask for; 0 = 1e-14*max(1, |t|). Any step must also
    !> exceed ten rounding units of t (10*epsilon*|t|), else t + h == t.
    real(wp) :: h_min = 0
    integer :: max_steps = default_max_steps  !< limit on attempted (accepted + rejected) steps
    real(wp) :: safety = 0         !< safety factor of the step-size formula, in (1e-4, 1)
    real(wp) :: fac1 = 0           !< fac1 <= h_new/h_old <= fac2, with 0 < fac1 <= 1 <= fac2
    real(wp) :: fac2 = 0
    real(wp) :: beta = 0           !< PI (Lund) stabilisation exponent, <= 0.2; < 0 means 0
    !> > 0: steps of exactly this size, no error control (the last step is shortened to end
    !> at t_bound); h_initial, h_max and the PI settings are then ignored. 0 = adaptive.
    real(wp) :: fixed_step = 0
    !> > 0: no step crosses a breakpoint t = k breakpoint_step, 0 < t <= breakpoint_end (where
    !> the right-hand side has a kink, e.g. the samples of a piecewise linear record): steps
    !> are clipped to end on them. 0 = none.
    real(wp) :: breakpoint_step = 0, breakpoint_end = 0
  end type ode_options

  !> Work counts of an integration and how far it got.
  type :: ode_stats
    integer :: n_rhs = 0        !< right-hand side evaluations
    integer :: n_accepted = 0   !< accepted steps
    integer :: n_rejected = 0   !< rejected steps (including those before the first acceptance)
    real(wp) :: t_reached = 0   !< time of the last accepted step
  end type ode_stats

  !> What distinguishes one pair from another in the shared driver.
  type :: method_properties
    character(len=16) :: name = ''
    integer :: order = 0           !< of the error estimate's reference solution (HINIT's IORD)
    integer :: stages = 0          !< columns of the stage array k
    integer :: trial_stages = 0    !< new right-hand sides of a trial step
    integer :: dense_columns = 0   !< coefficient vectors of the continuous extension
    !> step control: h_new = h / (err**(expo_base - beta_factor*beta) / err_old**beta / safety)
    real(wp) :: expo_base = 0, beta_factor = 0
    real(wp) :: fac1 = 0, fac2 = 0, beta = 0   !< the method's defaults
  end type method_properties

  !> One integration. The components are public for the methods (extensions in other modules)
  !> and for reading; change the state only through init, step and set_state.
  type, abstract :: rk_integrator
    real(wp) :: t = 0                !< current time (end of the last accepted step)
    real(wp) :: t_old = 0            !< start of the last accepted step
    real(wp) :: t_bound = 0          !< final time; the last step is clipped to end exactly here
    real(wp), allocatable :: y(:)    !< state at t
    integer :: n_rhs = 0             !< right-hand side evaluations
    integer :: n_accepted = 0        !< accepted steps
    integer :: n_rejected = 0        !< rejected steps
    type(ode_options) :: opt         !< the options, method defaults filled in
    real(wp), allocatable :: atol(:)      !< absolute tolerance per component
    real(wp), allocatable :: k(:, :)      !< stages; k(:, 1) = f(t, y) (FSAL)
    real(wp), allocatable :: y_stage(:), y_new(:), scratch(:)
    real(wp), allocatable :: cont(:, :)   !< coefficients of the continuous extension
    real(wp) :: h = 0                !< step to try next
    real(wp) :: h_done = 0           !< size of the last accepted step (0 = none yet)
    real(wp) :: h_max = 0            !< options%h_max, or t_bound - t0 when that is 0
    real(wp) :: fac_old = 1.0e-4_wp  !< previous accepted error norm (FACOLD)
    logical :: rejected = .false.    !< the previous trial step was rejected
    !> the last trial step of this step had NaN or infinite stages (rk_step's retry rule)
    logical :: non_finite_trial = .false.
    integer :: trial_stages = 0      !< right-hand sides of a trial step (method_properties)
    real(wp) :: expo1 = 0            !< exponent of err in the step-size formula
    logical :: dense_output = .true. !< compute the continuous extension of each step
  contains
    procedure :: init => rk_init
    procedure :: step => rk_step
    procedure :: set_state => rk_set_state
    procedure :: statistics => rk_statistics
    procedure :: trial => rk_trial
    procedure :: finish => rk_finish
    procedure :: plan => rk_plan
    procedure :: judge => rk_judge
    procedure :: conclude => rk_conclude
    procedure(method_stage), deferred :: stage
    procedure(method_trial_error), deferred :: trial_error
    procedure(method_finish_stages), deferred :: finish_stages
    procedure(method_store_dense), deferred :: store_dense
    procedure(method_dense), deferred :: dense
    procedure(method_info), deferred :: properties
    procedure(method_allocate), deferred :: allocate_extra
  end type rk_integrator

  abstract interface
    !> The input of stage s of a step of size h from (t, y) to t_new: s = 1..trial_stages are
    !> the trial step's new stages, s = trial_stages + 1.. those after an accepted error test
    !> (finish_stages of them). Fills y_stage; f(t_s, y_stage) goes into k(:, col). A stage
    !> may use the stages before it only (the driver evaluates them in order).
    pure subroutine method_stage(self, s, h, t_new, t_s, col)
      import :: wp, rk_integrator
      class(rk_integrator), intent(inout) :: self
      integer, intent(in) :: s
      real(wp), intent(in) :: h, t_new
      real(wp), intent(out) :: t_s
      integer, intent(out) :: col
    end subroutine method_stage

    !> After the trial stages: y_new and the error norm err (scaled so that err <= 1 passes).
    !> finite = .false. when any of them is NaN or infinite.
    pure subroutine method_trial_error(self, h, err, finite)
      import :: wp, rk_integrator
      class(rk_integrator), intent(inout) :: self
      real(wp), intent(in) :: h
      real(wp), intent(out) :: err
      logical, intent(out) :: finite
    end subroutine method_trial_error

    !> Stages needed once the error test passed (f at the new point, dense-output stages).
    pure integer function method_finish_stages(self)
      import :: rk_integrator
      class(rk_integrator), intent(in) :: self
    end function method_finish_stages

    !> Before the state moves to y_new: the continuous extension over [t, t + h] into cont,
    !> and the next step's first stage into k(:, 1) (FSAL).
    pure subroutine method_store_dense(self, h)
      import :: wp, rk_integrator
      class(rk_integrator), intent(inout) :: self
      real(wp), intent(in) :: h
    end subroutine method_store_dense

    !> Value at t of the continuous extension over the last accepted step [t_old, t].
    pure subroutine method_dense(self, t, y)
      import :: wp, rk_integrator
      class(rk_integrator), intent(in) :: self
      real(wp), intent(in) :: t
      real(wp), intent(out) :: y(:)
    end subroutine method_dense

    pure function method_info(self) result(info)
      import :: rk_integrator, method_properties
      class(rk_integrator), intent(in) :: self
      type(method_properties) :: info
    end function method_info

    !> Work arrays of the method beyond those of rk_integrator, for n components.
    pure subroutine method_allocate(self, n)
      import :: rk_integrator
      class(rk_integrator), intent(inout) :: self
      integer, intent(in) :: n
    end subroutine method_allocate
  end interface

  !> Quantities g(t, y) observed along an integration (loads of a state, components of it),
  !> whose largest |g_i| a peak_tracker finds on the integrator's continuous extension.
  type, abstract :: observed_quantities
  contains
    procedure(observe), deferred :: values
    procedure(observed_count), deferred :: count
  end type observed_quantities

  abstract interface
    pure subroutine observe(self, t, y, g)
      import :: wp, observed_quantities
      class(observed_quantities), intent(in) :: self
      real(wp), intent(in) :: t, y(:)
      real(wp), intent(out) :: g(:)
    end subroutine observe

    pure integer function observed_count(self)
      import :: observed_quantities
      class(observed_quantities), intent(in) :: self
    end function observed_count
  end interface

  !> g = C y(1:size(C, 2)): components of the state or linear combinations of them.
  type, extends(observed_quantities) :: linear_observation
    real(wp), allocatable :: c(:, :)
  contains
    procedure :: values => linear_values
    procedure :: count => linear_count
  end type linear_observation

  !> A peak_tracker's findings after steps 1..at of a record (peak_tracker's fields of the
  !> same names), taken at time t, the end of step at (at = -1: none taken).
  type :: tracker_checkpoint
    integer :: at = -1
    real(wp) :: t = 0, end_time = 0
    real(wp), allocatable :: peak(:), time(:), state(:, :), first_crossing(:), end_state(:), &
                             end_values(:)
    integer, allocatable :: crossings(:)
    logical, allocatable :: above(:)
  end type tracker_checkpoint

  !> The accepted steps a peak_tracker took in (its record_steps): column k of data holds step
  !> k's t_old, t, h_done, its end state y and the coefficients of its continuous extension
  !> (cont); mold is an integrator of the run's method, whose dense output reads them. With
  !> them tracker_replay observes the run again, other quantities, without integrating it.
  type :: recorded_steps
    integer :: n = 0, state_size = 0
    real(wp), allocatable :: data(:, :)
    class(rk_integrator), allocatable :: mold
    !> with the tracker's rewind_quantity: the last two checkpoints (1 the older); the steps
    !> before checkpoint 1 are no longer in data (dropped: how many of the run's steps)
    type(tracker_checkpoint) :: checkpoint(2)
    integer :: dropped = 0
  end type recorded_steps

  !> The largest |g_i| of observed quantities over an integration (or a window [t_from, t_to]
  !> of it), located between the steps: after each accepted step `watch` scans the continuous
  !> extension over the step at probe points, and where the best probe could hide a larger
  !> value (its rise over its lower neighbour could lie beyond it) Brent's localmin on the
  !> neighbouring probes finds the maximum of the interpolant. The result does not depend on
  !> the output times or on sampling; only on the steps, which output times never change.
  !> With a level_i > 0 it also counts the entries of |g_i| into [level_i, inf) and locates
  !> the first one (Brent's zero on the interpolant).
  type :: peak_tracker
    real(wp), allocatable :: peak(:)            !< largest |g_i|
    real(wp), allocatable :: time(:)            !< where it is
    !> with keep_states (set before start), the state at each peak, state(:, i)
    real(wp), allocatable :: state(:, :)
    logical :: keep_states = .false.
    real(wp), allocatable :: level(:)           !< crossing levels (set before start; 0 = none)
    integer, allocatable :: crossings(:)        !< entries of |g_i| into [level_i, inf)
    real(wp), allocatable :: first_crossing(:)  !< time of the first (NaN: none)
    !> > 0: probes at most this far apart (besides at least step_probes + 1 per step)
    real(wp) :: spacing = 0
    logical, allocatable :: above(:)
    !> g at the last step's end (time, state, values): the next step's first probe, the same
    !> state, is not evaluated again
    real(wp) :: end_time = 0
    real(wp), allocatable :: end_state(:), end_values(:)
    !> with record_steps (set before start), the steps taken in, for tracker_replay
    logical :: record_steps = .false.
    type(recorded_steps) :: steps
    !> with record_steps, i > 0 (set before start): until |g_i| first reaches level_i the
    !> record keeps only the steps since the older of two checkpoints of the tracker, taken
    !> every checkpoint_interval steps (a replay from the older one repeats at most twice as
    !> many steps, and the record holds as many); a replay whose quantities equal these up to
    !> a time (its `before`) starts at the latest checkpoint before it. No checkpoints where
    !> i is not a quantity with a level_i > 0 or checkpoint_interval < 1.
    integer :: rewind_quantity = 0, checkpoint_interval = 256
    !> watch's work arrays, kept from step to step (allocating them at every step cost ~2 %
    !> of a seismic run's instructions): the probes' positions, values and order, the values
    !> just inside the step's ends, and the state and values at one point of the step
    real(wp), allocatable :: probe_s(:), probe_g(:, :), inside_g(:, :), point_y(:), point_g(:)
    !> the probes' states (a new peak at a probe takes its state from there)
    real(wp), allocatable :: probe_y(:, :)
    integer, allocatable :: probe_order(:)
  contains
    procedure :: start => tracker_start
    procedure :: watch => tracker_watch
    procedure :: replay => tracker_replay
  end type peak_tracker

  interface
    !> Begin tracking at (t, y): the peaks are |g(t, y)|; an |g_i| already at or above level_i
    !> counts as an entry at t.
    module subroutine tracker_start(self, obs, t, y)
      class(peak_tracker), intent(inout) :: self
      class(observed_quantities), intent(in) :: obs
      real(wp), intent(in) :: t, y(:)
    end subroutine tracker_start

    !> Take in the part [a, b] = [t_old, t] & [t_from, t_to] of the integrator's last accepted
    !> step (see peak_tracker).
    module subroutine tracker_watch(self, integ, obs, t_from, t_to, status, message)
      class(peak_tracker), intent(inout), target :: self
      class(rk_integrator), intent(in), target :: integ
      class(observed_quantities), intent(in), target :: obs
      real(wp), intent(in) :: t_from, t_to
      integer, intent(out) :: status
      character(len=message_len), intent(out) :: message
    end subroutine tracker_watch

    !> Start at (t0, y0) and take in the recorded steps of another tracker's run (its
    !> record_steps) with the quantities obs, over the same [t_from, t_to]: the peaks, their
    !> states and crossings of obs along that run, bit for bit those of tracking obs while
    !> integrating it again, without integrating. Set level and keep_states before. t_reached:
    !> the end of the last step taken in (t0 before the first), where integrating again would
    !> have stopped had a step failed. before: obs equals the recorded run's quantities at
    !> every t < before, and self the recorded tracker in levels, keep_states, spacing, window
    !> and start (t0, y0): the replay may start at the record's latest checkpoint taken before
    !> it (rewind_quantity), else from (t0, y0) -- refused if the record dropped the steps
    !> that needs, or if its checkpoint has other quantities or keeps no states.
    module subroutine tracker_replay(self, steps, obs, t0, y0, t_from, t_to, status, message, &
                                     t_reached, before)
      class(peak_tracker), intent(inout) :: self
      type(recorded_steps), intent(in) :: steps
      class(observed_quantities), intent(in) :: obs
      real(wp), intent(in) :: t0, y0(:), t_from, t_to
      integer, intent(out) :: status
      character(len=message_len), intent(out) :: message
      real(wp), intent(out), optional :: t_reached
      real(wp), intent(in), optional :: before
    end subroutine tracker_replay
  end interface

  !> In fixed-step mode a remainder this much longer than the step (relative) is taken as one
  !> last step, so rounding in t never leaves a sliver step at t_bound.
  real(wp), parameter :: fixed_slack = 1.0e-6_wp

contains

  !> Validate the inputs, allocate the work arrays and evaluate f(t0, y0); choose the first step.
  !> dense_output = .false. (default .true.) lets a method skip the work of its continuous
  !> extension; dense then returns y at t and NaN elsewhere.
  subroutine rk_init(self, sys, t0, y0, t_bound, options, status, message, dense_output)
    class(rk_integrator), intent(out) :: self
    class(ode_system), intent(in) :: sys
    real(wp), intent(in) :: t0, y0(:), t_bound
    type(ode_options), intent(in) :: options
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    logical, intent(in), optional :: dense_output
    type(method_properties) :: info
    integer :: n

    status = SD_OK
    message = ''
    call check_options(options, y0, status, message)
    call check_real('t0', t0, -huge(t0), huge(t0), .false., .false., 't0 must be finite', &
                    status, message)
    call check_real('t_bound', t_bound, t0, huge(t0), .true., .false., &
                    't_bound must be finite and > t0 = '//num2str(t0), status, message)
    if (status /= SD_OK) return

    info = self%properties()
    n = size(y0)
    allocate (self%y(n), self%atol(n), self%k(n, info%stages), self%y_stage(n), self%y_new(n), &
              self%scratch(n), self%cont(n, info%dense_columns))
    call self%allocate_extra(n)
    self%opt = with_method_defaults(options, info)
    if (allocated(options%atol_vector)) then
      self%atol = options%atol_vector
    else
      self%atol = options%atol
    end if
    if (present(dense_output)) self%dense_output = dense_output
    self%t = t0
    self%t_old = t0
    self%t_bound = t_bound
    self%y = y0
    self%h_max = merge(options%h_max, t_bound - t0, options%h_max > 0)
    self%trial_stages = info%trial_stages
    self%expo1 = info%expo_base - info%beta_factor*self%opt%beta

    call sys%rhs(t0, self%y, self%k(:, 1))
    self%n_rhs = 1
    if (.not. all(ieee_is_finite(self%k(:, 1)))) then
      status = SD_NON_FINITE
      message = 'the right-hand side is NaN or infinite at the initial state, tau = '//num2str(t0)
      return
    end if

    if (options%fixed_step > 0) then
      self%h = options%fixed_step
    else if (options%h_initial > 0) then
      self%h = min(options%h_initial, self%h_max)
    else
      call initial_step(self, sys, info%order)
    end if
  end subroutine rk_init

  !> Advance by one accepted step (rejected trial steps are retried inside). On failure the
  !> integrator stays at its last accepted step. The step is the sequence plan, trial, judge,
  !> finish, conclude, which an ensemble (sloshdyn_ensemble) drives for many integrators at
  !> once with the same arithmetic.
  subroutine rk_step(self, sys, status, message)
    class(rk_integrator), intent(inout) :: self
    class(ode_system), intent(in) :: sys
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: h, t_new, err, h_new
    logical :: finite, go_on, accepted

    call rk_begin_step(self, status, message)
    if (status /= SD_OK) return
    ! every integration of every analysis passes here: Ctrl-C is honoured within one step
    call check_cancel(status, message)
    if (status /= SD_OK) return
    do
      call self%plan(h, t_new, status, message)
      if (status /= SD_OK) return
      call self%trial(sys, h, t_new, err, finite)
      call self%judge(h, err, finite, h_new, go_on)
      if (.not. go_on) cycle
      if (finite) call self%finish(sys, h, t_new, finite)
      call self%conclude(h, t_new, err, h_new, finite, accepted, status, message)
      if (status /= SD_OK .or. accepted) return
    end do
  end subroutine rk_step

  !> The checks before a step: set up by init, t_bound not yet reached.
  subroutine rk_begin_step(self, status, message)
    class(rk_integrator), intent(inout) :: self
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    status = SD_OK
    message = ''
    if (.not. allocated(self%k)) then
      status = SD_BAD_INPUT
      message = 'step needs an integrator set up by a successful init'
    else if (self%t >= self%t_bound) then
      status = SD_BAD_INPUT
      message = 'the integration already reached t_bound = '//num2str(self%t_bound)
    end if
    self%non_finite_trial = .false.
  end subroutine rk_begin_step

  !> The next trial step h from t to t_new (see plan_trial), or the failure that ends the
  !> integration (step budget, step floor).
  pure subroutine rk_plan(self, h, t_new, status, message)
    class(rk_integrator), intent(in) :: self
    real(wp), intent(out) :: h, t_new
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    call plan_trial(self%opt, self%t, self%t_bound, self%h, self%n_accepted + self%n_rejected, &
                    self%non_finite_trial, h, t_new, status, message)
  end subroutine rk_plan

  !> The trial step: the method's trial stages in order, then its error estimate.
  subroutine rk_trial(self, sys, h, t_new, err, finite)
    class(rk_integrator), intent(inout) :: self
    class(ode_system), intent(in) :: sys
    real(wp), intent(in) :: h, t_new
    real(wp), intent(out) :: err
    logical, intent(out) :: finite
    real(wp) :: t_s
    integer :: s, col
    do s = 1, self%trial_stages
      call self%stage(s, h, t_new, t_s, col)
      call sys%rhs(t_s, self%y_stage, self%k(:, col))
    end do
    self%n_rhs = self%n_rhs + self%trial_stages
    call self%trial_error(h, err, finite)
  end subroutine rk_trial

  !> The stages after a passed error test, in order; finite = .false. (and no more stages) as
  !> soon as one is NaN or infinite.
  subroutine rk_finish(self, sys, h, t_new, finite)
    class(rk_integrator), intent(inout) :: self
    class(ode_system), intent(in) :: sys
    real(wp), intent(in) :: h, t_new
    logical, intent(out) :: finite
    real(wp) :: t_s
    integer :: s, col
    finite = .true.
    do s = self%trial_stages + 1, self%trial_stages + self%finish_stages()
      call self%stage(s, h, t_new, t_s, col)
      call sys%rhs(t_s, self%y_stage, self%k(:, col))
      self%n_rhs = self%n_rhs + 1
      finite = all(ieee_is_finite(self%k(:, col)))
      if (.not. finite) return
    end do
  end subroutine rk_finish

  !> Hairer's step-size control after a trial step with error norm err: go_on = .false. when
  !> the error test rejects it (the next h is set); otherwise h_new is the step to try after
  !> it is accepted (h itself for fixed steps or a non-finite trial).
  pure subroutine rk_judge(self, h, err, finite, h_new, go_on)
    class(rk_integrator), intent(inout) :: self
    real(wp), intent(in) :: h, err
    logical, intent(in) :: finite
    real(wp), intent(out) :: h_new
    logical, intent(out) :: go_on
    real(wp) :: fac11, fac

    h_new = h
    go_on = .true.
    if (.not. finite .or. self%opt%fixed_step > 0) return
    ! h_new = h*safety/(err**expo1/err_old**beta), clamped
    fac11 = err**self%expo1
    if (err > 1) then
      ! rejected: the plain (non-PI) formula
      self%h = h/min(1/self%opt%fac1, fac11/self%opt%safety)
      self%rejected = .true.
      self%n_rejected = self%n_rejected + 1
      self%non_finite_trial = .false.
      go_on = .false.
      return
    end if
    fac = fac11
    ! err_old**0 = 1: DOP853's default beta = 0 needs no pow call (a call per step)
    if (self%opt%beta /= 0) fac = fac/self%fac_old**self%opt%beta
    fac = max(1/self%opt%fac2, min(1/self%opt%fac1, fac/self%opt%safety))
    h_new = h/fac
  end subroutine rk_judge

  !> After the finishing stages: accept the step (accepted = .true.: the state moves to t_new,
  !> the next step is h_new), or, when a stage was NaN or infinite, retry with the largest
  !> allowed cut (a failure in fixed-step mode).
  pure subroutine rk_conclude(self, h, t_new, err, h_new, finite, accepted, status, message)
    class(rk_integrator), intent(inout) :: self
    real(wp), intent(in) :: h, t_new, err, h_new
    logical, intent(in) :: finite
    logical, intent(out) :: accepted
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: h_next

    status = SD_OK
    message = ''
    accepted = .false.
    self%non_finite_trial = .not. finite
    if (.not. finite) then
      if (self%opt%fixed_step > 0) then
        status = SD_NON_FINITE
        message = 'the state became NaN or infinite in the fixed step from tau = '// &
                  num2str(self%t)//' to '//num2str(t_new)
        return
      end if
      ! the trial left the region where f is defined: retry with the largest allowed cut
      self%h = h*self%opt%fac1
      self%rejected = .true.
      self%n_rejected = self%n_rejected + 1
      return
    end if
    accepted = .true.
    call self%store_dense(h)
    self%y(:) = self%y_new
    self%t_old = self%t
    self%t = t_new
    self%h_done = h
    self%n_accepted = self%n_accepted + 1
    if (self%opt%fixed_step > 0) return
    self%fac_old = max(err, 1.0e-4_wp)
    h_next = min(h_new, self%h_max)
    ! no growth right after a rejection
    if (self%rejected) h_next = min(h_next, h)
    self%rejected = .false.
    self%h = h_next
  end subroutine rk_conclude

  !> Replace the state at the current time (e.g. to renormalise variational vectors). This
  !> re-evaluates f for FSAL and ends dense output of the previous step; the step size is kept.
  subroutine rk_set_state(self, sys, y, status, message)
    class(rk_integrator), intent(inout) :: self
    class(ode_system), intent(in) :: sys
    real(wp), intent(in) :: y(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message

    status = SD_OK
    message = ''
    if (.not. allocated(self%k)) then
      status = SD_BAD_INPUT
      message = 'set_state needs an integrator set up by a successful init'
      return
    end if
    if (size(y) /= size(self%y)) then
      status = SD_BAD_INPUT
      message = 'y has size '//num2str(size(y))//'; the integrator state has size '// &
                num2str(size(self%y))
      return
    end if
    if (.not. all(ieee_is_finite(y))) then
      status = SD_BAD_INPUT
      message = 'y is out of range: the new state must be finite'
      return
    end if
    self%y = y
    call sys%rhs(self%t, self%y, self%k(:, 1))
    self%n_rhs = self%n_rhs + 1
    self%t_old = self%t
    self%h_done = 0
    if (.not. all(ieee_is_finite(self%k(:, 1)))) then
      status = SD_NON_FINITE
      message = 'the right-hand side is NaN or infinite at the new state, tau = '//num2str(self%t)
    end if
  end subroutine rk_set_state

  !> Counters of the integration so far and the time reached.
  pure function rk_statistics(self) result(stats)
    class(rk_integrator), intent(in) :: self
    type(ode_stats) :: stats
    stats = ode_stats(self%n_rhs, self%n_accepted, self%n_rejected, self%t)
  end function rk_statistics

  !> y at every time of t_out (ascending, all >= t0) by the integrator integ (of any method):
  !> y_out(:, j) = y(t_out(j)), shape (size(y0), size(t_out)). On failure the columns already
  !> reached are filled, the rest are NaN, and stats%t_reached says how far the integration got.
  !> When every output time after t0 is the final one, the continuous extension is skipped.
  !> With observed and tracker: the peaks of the observed quantities over [t0, t_out(n)]
  !> (tracker%level and tracker%spacing as set by the caller).
  subroutine integrate_with(integ, sys, t0, y0, t_out, y_out, options, stats, status, message, &
                            observed, tracker)
    class(rk_integrator), intent(inout), target :: integ
    class(ode_system), intent(in) :: sys
    real(wp), intent(in) :: t0, y0(:), t_out(:)
    real(wp), intent(out) :: y_out(:, :)
    type(ode_options), intent(in) :: options
    type(ode_stats), intent(out) :: stats
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    class(observed_quantities), intent(in), optional, target :: observed
    type(peak_tracker), intent(inout), optional :: tracker
    integer :: j, n_out
    logical :: tracking

    stats%t_reached = t0
    n_out = size(t_out)
    call check_outputs(t0, y0, t_out, y_out, options, status, message)
    if (status /= SD_OK) return
    tracking = present(observed) .and. present(tracker)
    if (tracking) call tracker%start(observed, t0, y0)

    ! outputs at t0 itself need no step
    j = 1
    do while (j <= n_out)
      if (t_out(j) > t0) exit
      y_out(:, j) = y0
      j = j + 1
    end do
    if (j > n_out) return

    call integ%init(sys, t0, y0, t_out(n_out), options, status, message, &
                    dense_output=t_out(j) < t_out(n_out) .or. tracking)
    do while (status == SD_OK .and. j <= n_out)
      call integ%step(sys, status, message)
      if (status /= SD_OK) exit
      if (tracking) call tracker%watch(integ, observed, t0, t_out(n_out), status, message)
      if (status /= SD_OK) exit
      call deliver_outputs(integ, t_out, j, y_out)
    end do
    stats = integ%statistics()
  end subroutine integrate_with

  !> integrate_with's checks of its inputs (y_out is set to NaN first): the shape of y_out,
  !> t_out ascending from t0, the options and y0.
  pure subroutine check_outputs(t0, y0, t_out, y_out, options, status, message)
    real(wp), intent(in) :: t0, y0(:), t_out(:)
    real(wp), intent(out) :: y_out(:, :)
    type(ode_options), intent(in) :: options
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    integer :: j, n_out

    n_out = size(t_out)
    status = SD_OK
    message = ''
    y_out = ieee_value(1.0_wp, ieee_quiet_nan)
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
    call check_options(options, y0, status, message)
  end subroutine check_outputs

  !> After an accepted step: y at the output times t_out(j), t_out(j + 1), ... up to integ%t
  !> (the state itself at integ%t, the continuous extension before it); j moves past them.
  pure subroutine deliver_outputs(integ, t_out, j, y_out)
    class(rk_integrator), intent(in) :: integ
    real(wp), intent(in) :: t_out(:)
    integer, intent(inout) :: j
    real(wp), intent(inout) :: y_out(:, :)
    do while (j <= size(t_out))
      if (t_out(j) > integ%t) exit
      if (t_out(j) == integ%t) then
        y_out(:, j) = integ%y
      else
        call integ%dense(t_out(j), y_out(:, j))
      end if
      j = j + 1
    end do
  end subroutine deliver_outputs

  pure subroutine linear_values(self, t, y, g)
    class(linear_observation), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: g(:)
    g = matmul(self%c, y(1:size(self%c, 2)))
  end subroutine linear_values

  pure integer function linear_count(self)
    class(linear_observation), intent(in) :: self
    linear_count = size(self%c, 1)
  end function linear_count


  !> Hairer's RMS error norm, scale sk = atol_i + rtol*max(|y0_i|, |y1_i|). Zero error terms are
  !> skipped so that a component with sk = 0 (atol_i = 0, y_i = 0) cannot give 0/0.
  pure function rms_error_norm(e, y0, y1, atol, rtol) result(err)
    real(wp), intent(in) :: e(:), y0(:), y1(:), atol(:), rtol
    real(wp) :: err
    integer :: i

    err = 0
    do i = 1, size(e)
      if (e(i) /= 0) err = err + (e(i)/(atol(i) + rtol*max(abs(y0(i)), abs(y1(i)))))**2
    end do
    err = sqrt(err/size(e))
  end function rms_error_norm

  !> For a method's dense: done = .true. (with y filled) when there is no continuous extension
  !> to evaluate -- before any step (y = the state), or without dense output (init's
  !> dense_output = .false.: the state at t = integ%t, NaN at any other time).
  pure subroutine dense_from_state(integ, t, y, done)
    class(rk_integrator), intent(in) :: integ
    real(wp), intent(in) :: t
    real(wp), intent(inout) :: y(:)
    logical, intent(out) :: done
    done = integ%h_done == 0 .or. .not. integ%dense_output
    if (.not. done) return
    if (integ%h_done == 0 .or. t == integ%t) then
      y = integ%y
    else
      y = ieee_value(1.0_wp, ieee_quiet_nan)
    end if
  end subroutine dense_from_state

  !> The options with the method's defaults in place of zeros (and beta < 0 as 0).
  pure function with_method_defaults(options, info) result(opt)
    type(ode_options), intent(in) :: options
    type(method_properties), intent(in) :: info
    type(ode_options) :: opt
    opt = options
    if (opt%safety == 0) opt%safety = 0.9_wp
    if (opt%fac1 == 0) opt%fac1 = info%fac1
    if (opt%fac2 == 0) opt%fac2 = info%fac2
    if (opt%beta == 0) then
      opt%beta = info%beta
    else if (opt%beta < 0) then
      opt%beta = 0
    end if
  end function with_method_defaults

  !> HINIT of dopri5.f/dop853.f: an explicit Euler step sized so that its increment is small
  !> against y, then h with h**order * max(|f|, |f'|) = 0.01 in the scaled norm, at most 100
  !> times the Euler guess. Uses k(:, 2), y_stage and scratch; one right-hand side evaluation.
  subroutine initial_step(self, sys, order)
    class(rk_integrator), intent(inout) :: self
    class(ode_system), intent(in) :: sys
    integer, intent(in) :: order
    real(wp) :: dnf, dny, der2, der12, h1, h

    associate (y => self%y, f0 => self%k(:, 1), f1 => self%k(:, 2), y1 => self%y_stage, &
               sk => self%scratch)
      sk = self%atol + self%opt%rtol*abs(y)
      dnf = sum((f0/sk)**2)
      dny = sum((y/sk)**2)
      if (dnf <= 1.0e-10_wp .or. dny <= 1.0e-10_wp) then
        h = 1.0e-6_wp
      else
        h = 0.01_wp*sqrt(dny/dnf)
      end if
      h = min(h, self%h_max)
      y1 = y + h*f0
      call sys%rhs(self%t + h, y1, f1)
      self%n_rhs = self%n_rhs + 1
      ! f undefined a small step ahead: keep the cautious Euler guess
      if (all(ieee_is_finite(f1))) then
        der2 = sqrt(sum(((f1 - f0)/sk)**2))/h
        der12 = max(der2, sqrt(dnf))
        if (der12 <= 1.0e-15_wp) then
          h1 = max(1.0e-6_wp, h*1.0e-3_wp)
        else
          h1 = (0.01_wp/der12)**(1.0_wp/order)
        end if
        h = min(100*h, h1, self%h_max)
      end if
    end associate
    self%h = h
  end subroutine initial_step

  !> Smallest step error control may ask for at time t (see ode_options%h_min).
  pure function step_floor(h_min, t) result(h_floor)
    real(wp), intent(in) :: h_min, t
    real(wp) :: h_floor
    h_floor = merge(h_min, 1.0e-14_wp*max(1.0_wp, abs(t)), h_min > 0)
    h_floor = max(h_floor, 10*epsilon(t)*abs(t))
  end function step_floor

  !> The next trial step: the step budget and the step floor are checked (the floor before
  !> clipping: a short last step to t_bound is no sign of trouble), and the step is clipped to
  !> end exactly on t_bound; adaptive steps are stretched by up to 1 % rather than leave a
  !> sliver (as DOPRI5 and DOP853 do).
  pure subroutine plan_trial(opt, t, t_bound, h_wanted, attempts, non_finite_trial, h, t_new, &
                             status, message)
    type(ode_options), intent(in) :: opt
    real(wp), intent(in) :: t, t_bound, h_wanted
    integer, intent(in) :: attempts
    logical, intent(in) :: non_finite_trial
    real(wp), intent(out) :: h, t_new
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: breakpoint
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
    if (opt%breakpoint_step > 0) then
      breakpoint = next_breakpoint(t, opt%breakpoint_step, opt%breakpoint_end)
      if (breakpoint < t_new) then
        h = breakpoint - t
        t_new = breakpoint
      end if
    end if
  end subroutine plan_trial

  !> The first breakpoint k step > t (k >= 1, k step <= last), or +huge when there is none. A t
  !> within rounding of a breakpoint counts as on it.
  pure real(wp) function next_breakpoint(t, step, last) result(breakpoint)
    real(wp), intent(in) :: t, step, last
    real(wp) :: k
    breakpoint = huge(1.0_wp)
    if (t >= last) return
    k = real(floor(t/step), wp)
    if ((k + 1)*step - t <= 4*epsilon(t)*max(abs(t), step)) k = k + 1
    breakpoint = min((k + 1)*step, last)
  end function next_breakpoint

  !> The options and the initial state: the checks every integration and every input reader
  !> applies (readers validate before computing).
  pure subroutine check_options(options, y0, status, message)
    type(ode_options), intent(in) :: options
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
    call check_real('rtol', options%rtol, 10*epsilon(1.0_wp), 1.0_wp, .false., .false., &
                    'rtol must lie in [10*epsilon, 1] = ['//num2str(10*epsilon(1.0_wp))//', 1]', &
                    status, message)
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
    if (options%safety /= 0) &
      call check_real('safety', options%safety, 1.0e-4_wp, 1.0_wp, .true., .true., &
                      'safety must lie in (1e-4, 1), or be 0 (the default, 0.9)', status, message)
    if (options%fac1 /= 0) &
      call check_real('fac1', options%fac1, 0.0_wp, 1.0_wp, .true., .false., &
                      'fac1 must lie in (0, 1], or be 0 (the method''s default)', status, message)
    if (options%fac2 /= 0) &
      call check_real('fac2', options%fac2, 1.0_wp, big, .false., .false., &
                      'fac2 must be >= 1, or 0 (the method''s default)', status, message)
    call check_real('beta', options%beta, -big, 0.2_wp, .false., .false., &
                    'beta must be <= 0.2 (0: the method''s default; < 0: no PI stabilisation)', &
                    status, message)
    call check_real('fixed_step', options%fixed_step, 0.0_wp, big, .false., .false., &
                    'fixed_step must be >= 0 (0 = adaptive)', status, message)
    call check_real('breakpoint_step', options%breakpoint_step, 0.0_wp, big, .false., .false., &
                    'breakpoint_step must be >= 0 (0 = none)', status, message)
  end subroutine check_options
end module sloshdyn_ode
