!> The peak tracker's procedures (a submodule of sloshdyn_ode, which declares the tracker's
!> type and these interfaces): the scan of each accepted step's continuous extension at probe
!> points, Brent's refinement of a maximum between them and the level crossings (the method:
!> peak_tracker's description in sloshdyn_ode).
submodule (sloshdyn_ode) sloshdyn_peak_tracker
  ! by use, not only from the parent: meson rebuilds a submodule when a module it uses changes,
  ! not when one its parent uses does (a stale object then calls the old interfaces)
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT
  use sloshdyn_roots, only: bracketed_function, brent_zero, brent_minimum
  use sloshdyn_cancel, only: check_cancel
  implicit none

  !> Probe intervals per step at least, and at most, of a peak_tracker's scan.
  integer, parameter :: step_probes = 4, max_probes = 100000
  !> A maximum is located to this part of the step (its value then to ~1e-20 relative).
  real(wp), parameter :: locate_tol = 1.0e-10_wp
  !> How far inside a step (a share of it) the tracker looks whether a quantity rises into the
  !> step's end: a maximum closer to the end than this differs from the end's value by
  !> ~ g'' (end_gap h)^2 / 2, below the integration's error
  real(wp), parameter :: end_gap = 1.0e-6_wp
  !> Recorded steps a replay takes in between two looks for a Ctrl-C (sloshdyn_cancel)
  integer, parameter :: replay_poll = 256
  !> Steps recorded before the record first grows: its pages are touched only as steps come,
  !> so a short run costs no more than its own steps, and most seismic runs never copy theirs
  integer, parameter :: first_capacity = 16384

  !> |g_i| - level (sign = 1, for zeros) or -|g_i| (sign = -1, for the maximum) on the
  !> continuous extension of the last step at t = a + s (b - a), s in [0, 1].
  type, extends(bracketed_function) :: dense_quantity
    class(rk_integrator), pointer :: integ => null()
    class(observed_quantities), pointer :: obs => null()
    real(wp) :: a = 0, b = 0, level = 0, sign = 1
    integer :: i = 1
    real(wp), pointer :: y(:) => null(), g(:) => null()   !< the tracker's point_y, point_g
  contains
    procedure :: value => dense_quantity_value
  end type dense_quantity

contains

  !> Begin tracking at (t, y): the peaks are |g(t, y)|; an |g_i| already at or above level_i
  !> counts as an entry at t.
  module subroutine tracker_start(self, obs, t, y)
    class(peak_tracker), intent(inout) :: self
    class(observed_quantities), intent(in) :: obs
    real(wp), intent(in) :: t, y(:)
    real(wp) :: g(obs%count())
    if (.not. allocated(self%level)) then
      allocate (self%level(obs%count()))
      self%level = 0
    end if
    call obs%values(t, y, g)
    call remember_end(self, t, y, g)
    if (self%record_steps) then
      self%steps%n = 0
      self%steps%dropped = 0
      self%steps%checkpoint = tracker_checkpoint()     ! none, and no arrays of a run before
      if (allocated(self%steps%mold)) deallocate (self%steps%mold)
    end if
    self%peak = abs(g)
    self%time = spread(t, 1, size(g))
    if (self%keep_states) self%state = spread(y, 2, size(g))
    self%above = self%level > 0 .and. abs(g) >= self%level
    self%crossings = merge(1, 0, self%above)
    self%first_crossing = merge(t, ieee_value(1.0_wp, ieee_quiet_nan), self%above)
  end subroutine tracker_start

  !> Take in the part [a, b] = [t_old, t] & [t_from, t_to] of the integrator's last accepted
  !> step (see peak_tracker). The interpolant of a step taken without dense output is not
  !> available: then only its end counts.
  module subroutine tracker_watch(self, integ, obs, t_from, t_to, status, message)
    class(peak_tracker), intent(inout), target :: self
    class(rk_integrator), intent(in), target :: integ
    class(observed_quantities), intent(in), target :: obs
    real(wp), intent(in) :: t_from, t_to
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(dense_quantity) :: f
    real(wp), pointer :: s(:), g(:, :), g_peak(:), g_inside(:, :), y_probe(:, :)
    logical :: inside_known(0:1), refine, at_probe
    real(wp) :: a, b, best, rise, s_best, f_best, s_left, s_right, s_root, f_root, v_left, v
    integer :: m, n, i, j, k, n_points
    integer, pointer :: order(:)

    status = SD_OK
    message = ''
    if (integ%h_done == 0) return
    a = max(integ%t_old, t_from)
    b = min(integ%t, t_to)
    if (b <= a) return
    if (self%record_steps) then
      if (self%rewind_quantity > 0) call take_checkpoint(self, integ%t_old)
      call record_step(self%steps, integ)
    end if
    m = obs%count()
    n = step_probes
    if (self%spacing > 0) n = max(n, min(max_probes, ceiling((b - a)/self%spacing)))
    if (.not. integ%dense_output) then
      a = b
      n = 0
    end if
    call prepare_work(self, m, n, size(integ%y))
    ! the probes, and room for one refined maximum per quantity
    s(0:n + 1) => self%probe_s
    g(1:m, 0:n + 1) => self%probe_g
    order(0:n + 1) => self%probe_order
    g_inside(1:m, 0:1) => self%inside_g
    y_probe(1:size(integ%y), 0:n + 1) => self%probe_y
    f%y => self%point_y
    f%g => self%point_g
    g_peak => self%point_g          ! free while no search runs: state_at's values at a peak
    f%integ => integ
    f%obs => obs
    f%a = a
    f%b = b
    do j = 0, n
      s(j) = real(j, wp)/max(n, 1)
      call state_at(s(j), g(:, j), y_probe(:, j))
    end do
    inside_known = .false.
    do i = 1, m
      f%i = i
      ! maxloc(abs(g(i, 0:n)), dim=1) - 1: the first largest, NaNs skipped (0 if all are)
      j = 0
      best = abs(g(i, 0))
      do k = 1, n
        v = abs(g(i, k))
        ! NaNs so far (maxloc skips them): this one if it is none
        if (v > best .or. (best /= best .and. v == v)) then
          j = k
          best = v
        end if
      end do
      s_best = s(j)
      n_points = n
      rise = 0
      at_probe = .true.
      if (j > 0) rise = max(rise, best - abs(g(i, j - 1)))
      if (j < n) rise = max(rise, best - abs(g(i, j + 1)))
      refine = n > 0 .and. (best + rise >= self%peak(i) .or. &
                            (self%level(i) > 0 .and. best + rise >= self%level(i)))
      if (refine) refine = .not. rises_to_end(j)
      if (refine) then
        s_left = s(max(j - 1, 0))
        s_right = s(min(j + 1, n))
        f%level = 0
        f%sign = -1
        call brent_minimum(f, s_left, s_right, locate_tol, s_best, f_best, status, message)
        if (status /= SD_OK) return
        n_points = n + 1
        s(n_points) = s_best
        g(i, n_points) = -f_best
        if (-f_best > best) then
          best = -f_best
          at_probe = .false.
        else
          s_best = s(j)
        end if
      end if
      if (best > self%peak(i)) then
        self%peak(i) = best
        self%time(i) = a + s_best*(b - a)
        if (self%keep_states) then
          if (at_probe) then            ! the probe's state, as state_at(s(j)) gave it
            do k = 1, size(y_probe, 1)  ! not an array assignment: a malloc'ed temporary
              self%state(k, i) = y_probe(k, j)
            end do
          else
            call state_at(s_best, g_peak, self%state(:, i))
          end if
        end if
      end if
      if (.not. self%level(i) > 0) cycle
      ! entries into [level, inf) along the probes and the refined maximum, in order
      do k = 0, n_points                ! not [(k, k = 0, n_points)]: a malloc'ed temporary
        order(k) = k
      end do
      if (n_points > n) then
        do k = n_points, 1, -1
          if (s(order(k - 1)) <= s(n_points)) exit
          order(k) = order(k - 1)
          order(k - 1) = n_points
        end do
      end if
      v_left = abs(g(i, order(0)))
      if (n == 0) v_left = merge(self%level(i), 0.0_wp, self%above(i))
      do k = merge(1, 0, n > 0), n_points
        v = abs(g(i, order(k)))
        if (v >= self%level(i) .and. .not. self%above(i)) then
          self%crossings(i) = self%crossings(i) + 1
          if (self%crossings(i) == 1) then
            if (k == 0) then
              s_root = s(order(k))
            else
              f%level = self%level(i)
              f%sign = 1
              call brent_zero(f, s(order(k - 1)), s(order(k)), v_left - self%level(i), &
                              v - self%level(i), 0.0_wp, 0.0_wp, s_root, f_root, status, message)
              if (status /= SD_OK) return
            end if
            self%first_crossing(i) = a + s_root*(b - a)
          end if
        end if
        self%above(i) = v >= self%level(i)
        v_left = v
      end do
    end do

  contains

    !> The best probe of quantity i is the step's end k (j = 0 or n) and |g_i| rises into it
    !> (it is larger there than end_gap inside): then the largest value by that end is the
    !> end itself, which the neighbouring step's scan sees too, and Brent's search, which
    !> only approaches an end, would be discarded after ~30 evaluations. The values end_gap
    !> inside are evaluated once per step, for all quantities, when first asked for.
    logical function rises_to_end(k)
      integer, intent(in) :: k
      integer :: side
      rises_to_end = .false.
      if (k /= 0 .and. k /= n) return
      side = merge(0, 1, k == 0)
      if (.not. inside_known(side)) then
        call state_at(merge(end_gap, 1 - end_gap, k == 0), g_inside(:, side), f%y)
        inside_known(side) = .true.
      end if
      rises_to_end = abs(g_inside(i, side)) < abs(g(i, k))
    end function rises_to_end

    !> g at s in [0, 1] of [a, b]: the state itself at the step's end (and that state, y_point).
    subroutine state_at(s_point, g_point, y_point)
      real(wp), intent(in) :: s_point
      real(wp), intent(out) :: g_point(:), y_point(:)
      real(wp) :: t
      logical :: same_as_end
      t = a + s_point*(b - a)
      if (s_point >= 1) then
        t = b
        if (b == integ%t) then
          call obs%values(t, integ%y, g_point)
          call remember_end(self, t, integ%y, g_point)
          y_point = integ%y
          return
        end if
      end if
      call integ%dense(t, y_point)
      same_as_end = t == self%end_time .and. allocated(self%end_state)
      if (same_as_end) same_as_end = all(y_point == self%end_state)
      if (same_as_end) then
        g_point = self%end_values
      else
        call obs%values(t, y_point, g_point)
      end if
    end subroutine state_at
  end subroutine tracker_watch

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
    class(rk_integrator), allocatable, target :: integ
    integer :: k, n, c, columns, from, first

    status = SD_OK
    message = ''
    if (present(t_reached)) t_reached = t0
    n = size(y0)
    if (steps%n > 0 .and. steps%state_size /= n) then
      status = SD_BAD_INPUT
      message = 'tracker_replay: y0 has '//num2str(n)//' components, the recorded run''s '// &
                'state has '//num2str(steps%state_size)
      return
    end if
    call self%start(obs, t0, y0)
    ! the latest checkpoint before `before`, if any (0: from the start)
    from = 0
    if (present(before)) then
      do from = 2, 1, -1
        if (steps%checkpoint(from)%at >= 0) then
          if (steps%checkpoint(from)%t < before) exit
        end if
      end do
    end if
    first = 1
    if (from > 0) then
      if (size(steps%checkpoint(from)%peak) /= size(self%peak) .or. &
          (self%keep_states .neqv. allocated(steps%checkpoint(from)%state))) then
        status = SD_BAD_INPUT
        message = 'tracker_replay: the record''s checkpoint holds '// &
                  num2str(size(steps%checkpoint(from)%peak))//' quantities'// &
                  trim(merge(' and states   ', ' and no states', &
                             allocated(steps%checkpoint(from)%state)))//', obs has '// &
                  num2str(size(self%peak))//' (keep_states must be the same)'
        return
      end if
      call restore_checkpoint(self, steps%checkpoint(from))
      if (present(t_reached)) t_reached = steps%checkpoint(from)%t
      first = steps%checkpoint(from)%at + 1
    else if (steps%dropped > 0) then
      status = SD_BAD_INPUT
      message = 'tracker_replay: the record dropped its first '//num2str(steps%dropped)// &
                ' steps, and before is missing or not after its checkpoints'
      return
    end if
    if (steps%n == 0) return
    allocate (integ, source=steps%mold)
    columns = (size(steps%data, 1) - 3 - n)/n
    if (integ%dense_output) then           ! the mold has no arrays: its type and settings only
      if (allocated(integ%cont)) deallocate (integ%cont)
      allocate (integ%cont(n, columns))
    end if
    do k = first, steps%n
      if (mod(k, replay_poll) == 0) call check_cancel(status, message)
      if (status /= SD_OK) return
      if (present(t_reached)) t_reached = steps%data(2, k)
      ! what watch and the method's dense output read of the integrator after step k
      integ%t_old = steps%data(1, k)
      integ%t = steps%data(2, k)
      integ%h_done = steps%data(3, k)
      integ%y = steps%data(4:3 + n, k)
      if (integ%dense_output) then
        do c = 1, columns        ! not reshape: it copies through a temporary
          integ%cont(:, c) = steps%data(4 + c*n:3 + (c + 1)*n, k)
        end do
      end if
      call self%watch(integ, obs, t_from, t_to, status, message)
      if (status /= SD_OK) return
    end do
  end subroutine tracker_replay

  !> Append the integrator's last accepted step to steps (recorded_steps).
  subroutine record_step(steps, integ)
    type(recorded_steps), intent(inout) :: steps
    class(rk_integrator), intent(in) :: integ
    real(wp), allocatable :: grown(:, :)
    integer :: n, width, c
    n = size(integ%y)
    if (.not. allocated(steps%mold)) then
      allocate (steps%mold, mold=integ)
      steps%mold%dense_output = integ%dense_output
      steps%state_size = n
      width = 3 + n
      if (integ%dense_output) width = width + size(integ%cont)
      if (allocated(steps%data)) deallocate (steps%data)
      allocate (steps%data(width, first_capacity))
      steps%n = 0
    end if
    if (steps%n == size(steps%data, 2)) then
      allocate (grown(size(steps%data, 1), 2*steps%n))
      grown(:, :steps%n) = steps%data
      call move_alloc(grown, steps%data)
    end if
    steps%n = steps%n + 1
    associate (column => steps%data(:, steps%n))
      column(1:3) = [integ%t_old, integ%t, integ%h_done]
      column(4:3 + n) = integ%y
      if (integ%dense_output) then
        do c = 1, size(integ%cont, 2)       ! not reshape: it copies through a temporary
          column(4 + c*n:3 + (c + 1)*n) = integ%cont(:, c)
        end do
      end if
    end associate
  end subroutine record_step

  !> Before a step starting at t is recorded: while the rewind quantity has not reached its
  !> level, a checkpoint every checkpoint_interval steps; the record then keeps the steps
  !> from the older checkpoint on (the newer one before the new becomes the older one).
  subroutine take_checkpoint(self, t)
    class(peak_tracker), intent(inout) :: self
    real(wp), intent(in) :: t
    integer :: c, moved
    if (self%rewind_quantity > size(self%level) .or. self%checkpoint_interval < 1) return
    if (.not. self%level(self%rewind_quantity) > 0) return
    if (self%crossings(self%rewind_quantity) > 0) return
    associate (steps => self%steps, older => self%steps%checkpoint(1), &
               newer => self%steps%checkpoint(2))
      if (steps%n - max(newer%at, 0) < self%checkpoint_interval) return
      if (newer%at > 0) then
        moved = newer%at
        do c = 1, steps%n - moved            ! forward: the columns overlap
          steps%data(:, c) = steps%data(:, moved + c)
        end do
        steps%n = steps%n - moved
        steps%dropped = steps%dropped + moved
        older = newer
        older%at = 0
      end if
      newer%at = steps%n
      newer%t = t
      newer%end_time = self%end_time
      newer%peak = self%peak
      newer%time = self%time
      if (self%keep_states) newer%state = self%state
      newer%first_crossing = self%first_crossing
      newer%crossings = self%crossings
      newer%above = self%above
      newer%end_state = self%end_state
      newer%end_values = self%end_values
    end associate
  end subroutine take_checkpoint

  !> The tracker's findings as at a checkpoint (take_checkpoint).
  subroutine restore_checkpoint(self, point)
    class(peak_tracker), intent(inout) :: self
    type(tracker_checkpoint), intent(in) :: point
    self%end_time = point%end_time
    self%peak = point%peak
    self%time = point%time
    if (self%keep_states) self%state = point%state
    self%first_crossing = point%first_crossing
    self%crossings = point%crossings
    self%above = point%above
    self%end_state = point%end_state
    self%end_values = point%end_values
  end subroutine restore_checkpoint

  !> watch's work arrays (peak_tracker's probe_s ... point_g) for m quantities, n + 1 probes
  !> and a state of size n_y, allocated when missing or too small.
  subroutine prepare_work(self, m, n, n_y)
    class(peak_tracker), intent(inout) :: self
    integer, intent(in) :: m, n, n_y
    logical :: fits
    fits = allocated(self%probe_g)
    if (fits) fits = size(self%probe_g, 1) == m .and. size(self%probe_s) >= n + 2 .and. &
                     size(self%point_y) == n_y
    if (fits) return
    if (allocated(self%probe_g)) deallocate (self%probe_s, self%probe_g, self%probe_order, &
                                             self%inside_g, self%point_y, self%point_g, &
                                             self%probe_y)
    allocate (self%probe_s(n + 2), self%probe_g(m, n + 2), self%probe_order(n + 2), &
              self%inside_g(m, 2), self%point_y(n_y), self%point_g(m), self%probe_y(n_y, n + 2))
  end subroutine prepare_work

  !> Keep g = g(t, y) of a step's end (or the start) for the next step's first probe.
  pure subroutine remember_end(self, t, y, g)
    class(peak_tracker), intent(inout) :: self
    real(wp), intent(in) :: t, y(:), g(:)
    self%end_time = t
    self%end_state = y
    self%end_values = g
  end subroutine remember_end

  subroutine dense_quantity_value(self, x, fx, status, message)
    class(dense_quantity), intent(inout) :: self
    real(wp), intent(in) :: x
    real(wp), intent(out) :: fx
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: t
    status = SD_OK
    message = ''
    t = self%a + x*(self%b - self%a)
    call self%integ%dense(t, self%y)
    call self%obs%values(t, self%y, self%g)
    fx = self%sign*(abs(self%g(self%i)) - self%level)
  end subroutine dense_quantity_value
end submodule sloshdyn_peak_tracker
