!> Ensembles: K independent trajectories of the integrator family (sloshdyn_ode) advanced
!> together, each with its own time, step size, error control and accept/reject, dense output
!> and peak tracker; a trajectory that reaches its last output time (or fails) leaves the
!> ensemble. At every stage the right-hand side is evaluated for all trajectories still at
!> that stage in one call (ensemble_system%rhs_block), so that their independent chains of
!> dependent operations overlap in the processor instead of running one after the other.
!>
!> Bit for bit the results of integrating each trajectory alone: every trajectory is an
!> rk_integrator of its own, stepped by the same plan, stage, trial_error, judge and conclude
!> procedures that rk_step runs (sloshdyn_ode); only the order in which the trajectories' work
!> is done differs, and a column of rhs_block must equal the member's right-hand side alone
!> (the rule of ensemble_system). tests/fortran/test_ensemble.f90 checks it for K = 1, 2, 3,
!> 8, 64 with trajectories finishing, rejecting and peaking at different times.
module sloshdyn_ensemble
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT
  use sloshdyn_text, only: num2str
  use sloshdyn_cancel, only: check_cancel
  use sloshdyn_ode, only: ode_system, ode_options, ode_stats, rk_integrator, &
                          observed_quantities, peak_tracker, rk_begin_step, deliver_outputs, &
                          check_outputs
  use sloshdyn_integrator, only: new_integrator, chosen_method
  implicit none
  private
  public :: ensemble_system, block_rhs, shared_system, member_system, integrate_ensemble, &
            advance_members, member_watch, accepted_step

  !> The right-hand sides of the members 1..K of an ensemble. rhs_block evaluates column c for
  !> member members(c) at (t(c), y(:, c)); each column must depend only on its own member and
  !> inputs, with the arithmetic of that member's right-hand side alone (so that an ensemble
  !> reproduces its single integrations bit for bit).
  type, abstract :: ensemble_system
  contains
    procedure(block_rhs), deferred :: rhs_block
  end type ensemble_system

  abstract interface
    subroutine block_rhs(self, members, t, y, dydt)
      import :: wp, ensemble_system
      class(ensemble_system), intent(in) :: self
      integer, intent(in) :: members(:)
      real(wp), intent(in) :: t(:), y(:, :)
      real(wp), intent(out) :: dydt(:, :)
    end subroutine block_rhs
  end interface

  !> One ode_system for every member (an ensemble of initial states or output times).
  type, extends(ensemble_system) :: shared_system
    class(ode_system), pointer :: sys => null()
  contains
    procedure :: rhs_block => shared_rhs_block
  end type shared_system

  !> Member i of an ensemble_system as an ode_system of its own (for init's first evaluations,
  !> and for anything that integrates one member alone).
  type, extends(ode_system) :: member_system
    class(ensemble_system), pointer :: ensemble => null()
    integer :: member = 1
  contains
    procedure :: rhs => member_rhs
  end type member_system

  !> A caller's look at the members of advance_members: accepted is called after every
  !> accepted step of member j (integ = integ(j), at its new time); a status other than SD_OK
  !> stops that member as a failed step would.
  type, abstract :: member_watch
  contains
    procedure(accepted_step), deferred :: accepted
  end type member_watch

  abstract interface
    subroutine accepted_step(self, j, integ, status, message)
      import :: member_watch, rk_integrator, message_len
      class(member_watch), intent(inout) :: self
      integer, intent(in) :: j
      class(rk_integrator), intent(in) :: integ
      integer, intent(out) :: status
      character(len=message_len), intent(out) :: message
    end subroutine accepted_step
  end interface

  !> integrate_ensemble's watch: each member's outputs and peaks after its accepted steps.
  !> observed is an allocatable copy: gfortran 12 miscompiles an element of a pointer to a
  !> polymorphic array; tracker points to the caller's (not copied: a tracker that records its
  !> steps holds megabytes).
  type, extends(member_watch) :: output_watch
    real(wp), allocatable :: t0(:), t_out(:, :), y_out(:, :, :)
    integer, allocatable :: next_out(:)
    logical :: tracking = .false.
    class(observed_quantities), allocatable :: observed(:)
    type(peak_tracker), pointer :: tracker(:) => null()
  contains
    procedure :: accepted => outputs_accepted
  end type output_watch

contains

  subroutine shared_rhs_block(self, members, t, y, dydt)
    class(shared_system), intent(in) :: self
    integer, intent(in) :: members(:)
    real(wp), intent(in) :: t(:), y(:, :)
    real(wp), intent(out) :: dydt(:, :)
    integer :: c
    do c = 1, size(members)
      call self%sys%rhs(t(c), y(:, c), dydt(:, c))
    end do
  end subroutine shared_rhs_block

  subroutine member_rhs(self, t, y, dydt)
    class(member_system), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: dydt(:)
    real(wp) :: f(size(y), 1)
    call self%ensemble%rhs_block([self%member], [t], reshape(y, [size(y), 1]), f)
    dydt = f(:, 1)
  end subroutine member_rhs

  !> Advance the members listed (indices into integ) each from its time integ(j)%t until it
  !> passes its own target(c) (it steps while integ(j)%t < target(c), as the single path's
  !> `do while (integ%t < tau); call integ%step(...)`), and stop there with its step size and
  !> state kept, so that a caller can inspect the members (dense output up to integ(j)%t) and
  !> advance them again by other stretches. Every member steps exactly as integ(j)%step would
  !> alone: the same plan, stages, trial_error, judge, finish and conclude, one attempt per
  !> round; only the stages of all members at one stage go in one esys%rhs_block, whose
  !> column c is member members(c)'s right-hand side (ensemble_system's rule). watch%accepted
  !> (optional) is called after each accepted step of a member. Failures are per member
  !> (status(c), message(c); the member stays at its last accepted step). A Ctrl-C
  !> (sloshdyn_cancel) stops all members still running, with its status. Members already at
  !> or past their target on entry do nothing.
  subroutine advance_members(esys, integ, members, target, status, message, watch)
    class(ensemble_system), intent(in) :: esys
    class(rk_integrator), intent(inout) :: integ(:)
    integer, intent(in) :: members(:)
    real(wp), intent(in) :: target(:)
    integer, intent(out) :: status(:)
    character(len=message_len), intent(out) :: message(:)
    class(member_watch), intent(inout), optional :: watch
    real(wp) :: h(size(integ)), t_new(size(integ)), err(size(integ)), h_new(size(integ)), &
                goal(size(integ))
    logical :: finite(size(integ)), go_on(size(integ)), fresh(size(integ)), arrived(size(members))
    integer :: active(size(members)), slot(size(integ)), cols(size(members))
    integer :: n, n_trial, i, m, st
    character(len=message_len) :: msg
    logical :: accepted

    status = SD_OK
    message = ''
    if (size(target) /= size(members) .or. size(status) /= size(members) .or. &
        size(message) /= size(members)) then
      status = SD_BAD_INPUT
      message = 'advance_members: target, status and message need one entry per member ('// &
                num2str(size(members))//')'
      return
    end if
    do i = 1, size(members)
      if (members(i) < 1 .or. members(i) > size(integ) .or. any(members(:i - 1) == members(i))) then
        status = SD_BAD_INPUT
        message = 'advance_members: members('//num2str(i)//') = '//num2str(members(i))// &
                  ' must be a distinct index in [1, '//num2str(size(integ))//']'
        return
      end if
    end do
    m = 0
    do i = 1, size(members)
      slot(members(i)) = i
      goal(members(i)) = target(i)
      if (integ(members(i))%t >= target(i)) cycle
      m = m + 1
      active(m) = members(i)
    end do
    if (m == 0) return
    n = size(integ(active(1))%y)
    n_trial = integ(active(1))%trial_stages
    fresh = .true.

    ! rounds: every active member tries one step (the single path's rk_step, one attempt)
    do while (m > 0)
      st = SD_OK   ! check_cancel reports only into a status still SD_OK
      call check_cancel(st, msg)
      if (st /= SD_OK) then
        status(slot(active(1:m))) = st
        message(slot(active(1:m))) = msg
        exit
      end if
      do i = 1, m
        associate (j => active(i), c => slot(active(i)))
          if (fresh(j)) call rk_begin_step(integ(j), status(c), message(c))
          fresh(j) = .false.
          if (status(c) == SD_OK) &
            call integ(j)%plan(h(j), t_new(j), status(c), message(c))
        end associate
      end do
      call leave_if(status(slot(active(1:m))) /= SD_OK)
      if (m == 0) exit

      call stages(active(1:m), 1, n_trial, cols(1:m))
      do i = 1, m
        associate (j => active(i))
          integ(j)%n_rhs = integ(j)%n_rhs + integ(j)%trial_stages
          call integ(j)%trial_error(h(j), err(j), finite(j))
          call integ(j)%judge(h(j), err(j), finite(j), h_new(j), go_on(j))
        end associate
      end do
      call finish_stages(pack(active(1:m), go_on(active(1:m)) .and. finite(active(1:m))))

      do i = 1, m
        associate (j => active(i), c => slot(active(i)))
          if (.not. go_on(j)) cycle
          call integ(j)%conclude(h(j), t_new(j), err(j), h_new(j), finite(j), accepted, &
                                 status(c), message(c))
          if (status(c) /= SD_OK .or. .not. accepted) cycle
          fresh(j) = .true.
          if (present(watch)) call watch%accepted(j, integ(j), status(c), message(c))
        end associate
      end do
      do i = 1, m
        arrived(i) = status(slot(active(i))) /= SD_OK .or. integ(active(i))%t >= goal(active(i))
      end do
      call leave_if(arrived(1:m))
    end do

  contains

    !> The stages first..last of the members listed, stage by stage, one rhs_block per stage.
    !> col(c): the k column of the last stage of member c.
    subroutine stages(list, first, last, col)
      integer, intent(in) :: list(:)
      integer, intent(in) :: first, last
      integer, intent(out) :: col(:)
      real(wp) :: t_s(size(list)), y_s(n, size(list)), f_s(n, size(list))
      integer :: s, c
      do s = first, last
        do c = 1, size(list)
          associate (j => list(c))
            call integ(j)%stage(s, h(j), t_new(j), t_s(c), col(c))
            y_s(:, c) = integ(j)%y_stage
          end associate
        end do
        call esys%rhs_block(list, t_s, y_s, f_s)
        do c = 1, size(list)
          integ(list(c))%k(:, col(c)) = f_s(:, c)
        end do
      end do
    end subroutine stages

    !> rk_finish for the members listed: stage after stage for those that need it and whose
    !> stages so far are finite.
    subroutine finish_stages(list)
      integer, intent(in) :: list(:)
      integer :: s, c, counts(size(list)), col(size(list))
      logical :: going(size(list))
      if (size(list) == 0) return
      do c = 1, size(list)
        counts(c) = integ(list(c))%finish_stages()
      end do
      going = counts > 0
      s = 0
      do while (any(going))
        s = s + 1
        call stages(pack(list, going), n_trial + s, n_trial + s, col(1:count(going)))
        col = unpack(col(1:count(going)), going, col)
        do c = 1, size(list)
          if (.not. going(c)) cycle
          associate (j => list(c))
            integ(j)%n_rhs = integ(j)%n_rhs + 1
            finite(j) = all(ieee_is_finite(integ(j)%k(:, col(c))))
            going(c) = finite(j) .and. s < counts(c)
          end associate
        end do
      end do
    end subroutine finish_stages

    !> Drop the active members flagged (arrived or failed), keeping the others' order.
    subroutine leave_if(leaving)
      logical, intent(in) :: leaving(:)
      integer :: kept
      kept = count(.not. leaving)
      active(1:kept) = pack(active(1:m), .not. leaving)
      m = kept
    end subroutine leave_if
  end subroutine advance_members

  subroutine outputs_accepted(self, j, integ, status, message)
    class(output_watch), intent(inout) :: self
    integer, intent(in) :: j
    class(rk_integrator), intent(in) :: integ
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    integer :: n_out
    status = SD_OK
    message = ''
    n_out = size(self%t_out, 1)
    if (self%tracking) call self%tracker(j)%watch(integ, self%observed(min(j, &
                                                  size(self%observed))), self%t0(j), &
                                                  self%t_out(n_out, j), status, message)
    if (status /= SD_OK) return
    call deliver_outputs(integ, self%t_out(:, j), self%next_out(j), self%y_out(:, :, j))
  end subroutine outputs_accepted

  !> For every member i = 1..K (K = size(y0, 2)): y at the times t_out(:, i) (ascending, from
  !> t0(i)), y_out(:, j, i) = y(t_out(j, i)), by the method of code method (sloshdyn_integrator),
  !> exactly as integrate_with would give it alone with options(i) (or options(1) for all; the
  !> method for METHOD_AUTO is chosen by options(1)%rtol), and with observed(i) (or
  !> observed(1)) and tracker(i): the peaks over [t0(i), t_out(n, i)]). Failures are
  !> per member: status(i), message(i), stats(i)%t_reached, and NaN in y_out beyond the
  !> outputs reached; the other members go on. A Ctrl-C (sloshdyn_cancel) stops all members
  !> still running, with its status. The members go together through advance_members to
  !> their last output times, an output_watch delivering their outputs and peaks.
  subroutine integrate_ensemble(method, esys, t0, y0, t_out, y_out, options, stats, status, &
                                message, observed, tracker)
    integer, intent(in) :: method
    class(ensemble_system), intent(in), target :: esys
    real(wp), intent(in) :: t0(:), y0(:, :), t_out(:, :)
    real(wp), intent(out) :: y_out(:, :, :)
    type(ode_options), intent(in) :: options(:)
    type(ode_stats), intent(out) :: stats(:)
    integer, intent(out) :: status(:)
    character(len=message_len), intent(out) :: message(:)
    class(observed_quantities), intent(in), optional, target :: observed(:)
    type(peak_tracker), intent(inout), optional, target :: tracker(:)
    class(rk_integrator), allocatable :: proto, integ(:)
    type(member_system) :: alone
    type(output_watch) :: watch
    integer, allocatable :: active(:), run_status(:)
    character(len=message_len), allocatable :: run_message(:)
    integer :: n_members, n_out, i, m, st
    character(len=message_len) :: msg

    n_members = size(y0, 2)
    n_out = size(t_out, 1)
    watch%tracking = present(observed) .and. present(tracker)
    status = SD_OK
    message = ''
    call check_shapes(st, msg)
    if (st == SD_OK) call new_integrator(method, options(1)%rtol, proto, st, msg)
    if (st /= SD_OK) then
      status = st
      message = msg
      y_out = 0
      return
    end if
    allocate (integ(n_members), mold=proto)
    allocate (active(n_members))
    alone%ensemble => esys
    watch%t0 = t0
    watch%t_out = t_out
    allocate (watch%y_out(size(y_out, 1), n_out, n_members), watch%next_out(n_members))
    if (watch%tracking) then
      allocate (watch%observed, source=observed)
      watch%tracker => tracker
    end if

    ! set up every member as integrate_with does; those with a step to take become active
    m = 0
    do i = 1, n_members
      stats(i)%t_reached = t0(i)
      call check_outputs(t0(i), y0(:, i), t_out(:, i), watch%y_out(:, :, i), options_of(i), &
                         status(i), message(i))
      if (status(i) /= SD_OK) cycle
      if (watch%tracking) call watch%tracker(i)%start(observed(min(i, size(observed))), t0(i), &
                                                      y0(:, i))
      watch%next_out(i) = 1
      do while (watch%next_out(i) <= n_out)
        if (t_out(watch%next_out(i), i) > t0(i)) exit
        watch%y_out(:, watch%next_out(i), i) = y0(:, i)
        watch%next_out(i) = watch%next_out(i) + 1
      end do
      if (watch%next_out(i) > n_out) cycle
      alone%member = i
      call integ(i)%init(alone, t0(i), y0(:, i), t_out(n_out, i), options_of(i), status(i), &
                         message(i), dense_output=t_out(watch%next_out(i), i) < &
                         t_out(n_out, i) .or. watch%tracking)
      if (status(i) /= SD_OK) then
        stats(i) = integ(i)%statistics()
        cycle
      end if
      m = m + 1
      active(m) = i
    end do

    if (m > 0) then
      allocate (run_status(m), run_message(m))
      call advance_members(esys, integ, active(1:m), t_out(n_out, active(1:m)), run_status, &
                           run_message, watch)
      status(active(1:m)) = run_status
      message(active(1:m)) = run_message
    end if
    do i = 1, n_members
      if (allocated(integ(i)%k)) stats(i) = integ(i)%statistics()
    end do
    y_out = watch%y_out

  contains

    !> The options of member j: options(j), or options(1) for all.
    function options_of(j) result(opt)
      integer, intent(in) :: j
      type(ode_options) :: opt
      opt = options(min(j, size(options)))
    end function options_of

    subroutine check_shapes(st, msg)
      integer, intent(out) :: st
      character(len=message_len), intent(out) :: msg
      integer :: i
      st = SD_OK
      msg = ''
      if (size(t0) /= n_members .or. size(t_out, 2) /= n_members .or. &
          size(y_out, 1) /= size(y0, 1) .or. size(y_out, 2) /= n_out .or. &
          size(y_out, 3) /= n_members .or. size(stats) /= n_members .or. &
          size(status) /= n_members .or. size(message) /= n_members .or. &
          (size(options) /= 1 .and. size(options) /= n_members)) then
        st = SD_BAD_INPUT
        msg = 'ensemble of '//num2str(n_members)//' members (size(y0, 2)): t0, t_out(:, i), '// &
              'y_out(:, :, i), stats, status and message need one entry per member, '// &
              'options one or one per member'
      else if (any([(chosen_method(method, options(i)%rtol), i = 1, size(options))] /= &
                   chosen_method(method, options(1)%rtol))) then
        st = SD_BAD_INPUT
        msg = 'the members'' rtol pick different methods for method = '//num2str(method)// &
              ' (auto): give one method, or rtol on one side of the crossovers'
      else if (watch%tracking) then
        if (size(tracker) /= n_members .or. &
            (size(observed) /= 1 .and. size(observed) /= n_members)) then
          st = SD_BAD_INPUT
          msg = 'tracker needs one entry per member ('//num2str(n_members)// &
                '), observed one or one per member'
        end if
      end if
    end subroutine check_shapes
  end subroutine integrate_ensemble

end module sloshdyn_ensemble
