!> The curve tracer of sloshdyn_bifurcation (see its header): a curve traced both ways (or one)
!> from its corrected start in segments of continue_branch, each starting with refreshed border
!> or reference vectors and lambda the parameter that moves most; ended on the parameter box,
!> as a closed loop, beyond x_max or at a terminal codimension-2 point; the codimension-2 points
!> located between consecutive points; the two halves assembled into one curve.
submodule (sloshdyn_bifurcation) sloshdyn_bifurcation_tracer
  implicit none

  !> A test function along a curve segment: tests(which) of the point, or (which = 0) the
  !> coordinate z(coordinate) - level (for ending on the box).
  type, extends(branch_test) :: curve_test
    class(curve_system), allocatable :: sys
    integer :: which = 0, coordinate = 0
    real(wp) :: level = 0
  contains
    procedure :: value => curve_test_value
  end type curve_test

  !> Points of one half of a curve, as computed.
  type :: curve_buffer
    integer :: count = 0
    real(wp), allocatable :: x(:, :), p(:, :), re(:, :), im(:, :), tests(:, :), omega(:), l1(:)
    integer, allocatable :: special(:)
    real(wp), allocatable :: codim2_omega(:)
    integer :: n_unlocated = 0
    character(len=message_len) :: unlocated_message = ''
  end type curve_buffer

  !> A segment ends before the point where the null vectors have turned by more than 60 degrees
  !> from its border / reference vectors (alignment > 2): beyond, the bordered system nears a
  !> singularity where v changes sign (and the test functions with it).
  real(wp), parameter :: max_alignment = 2
  !> A segment restarts at its last point whose tangent has a parameter component at least
  !> this large (the tangent is a unit vector in the scaled variables), so lambda is well defined.
  real(wp), parameter :: tangent_floor = 0.05_wp
  !> A located zero of a test function must be this small relative to the values at the ends of
  !> its bracket (else the sign changed through a pole, where Brent's last value is ~1e12 times
  !> the ends'). Not smaller: the normal-form coefficients of maps (generalised flip, Chenciner)
  !> come from differences of monodromy matrices, their located zeros ~1e-3 of the ends.
  real(wp), parameter :: pole_ratio = 0.1_wp

contains

  !> Point z (size m) and lambda of the state s = (x, extra, p1, p2).
  pure subroutine pack_state(sys, s, z, lambda)
    class(curve_system), intent(in) :: sys
    real(wp), intent(in) :: s(:)
    real(wp), intent(out) :: z(:), lambda
    integer :: k
    k = sys%n + sys%n_extra
    z(1:sys%n) = s(1:sys%n)/sys%x_scale
    z(sys%n + 1:k) = s(sys%n + 1:k)
    z(k + 1) = (s(k + sys%other) - sys%p_ref(sys%other))/sys%p_scale(sys%other)
    lambda = (s(k + sys%lam) - sys%p_ref(sys%lam))/sys%p_scale(sys%lam)
  end subroutine pack_state

  !> The state of the point z = (.., q_other, lambda) (size m + 1).
  pure function unpack_state(sys, z) result(s)
    class(curve_system), intent(in) :: sys
    real(wp), intent(in) :: z(:)
    real(wp) :: s(size(z))
    integer :: k
    k = sys%n + sys%n_extra
    s(1:sys%n) = sys%x_scale*z(1:sys%n)
    s(sys%n + 1:k) = z(sys%n + 1:k)
    s(k + sys%other) = sys%p_ref(sys%other) + sys%p_scale(sys%other)*z(k + 1)
    s(k + sys%lam) = sys%p_ref(sys%lam) + sys%p_scale(sys%lam)*z(k + 2)
  end function unpack_state

  !> Tangent of a segment (in its z, lambda) as a tangent of the scaled state (y, extra, q1, q2).
  pure function state_tangent(sys, t) result(ts)
    class(curve_system), intent(in) :: sys
    real(wp), intent(in) :: t(:)
    real(wp) :: ts(size(t))
    integer :: k
    k = sys%n + sys%n_extra
    ts(1:k) = t(1:k)
    ts(k + sys%other) = t(k + 1)
    ts(k + sys%lam) = t(k + 2)
  end function state_tangent

  module procedure correct_state
    real(wp) :: z(size(s0))
    integer :: m, attempt, iterations

    m = size(s0) - 1
    s = s0
    status = SD_NOT_CONVERGED
    message = 'no attempt'
    do attempt = 1, size(fixed)
      if (allocated(sys)) deallocate (sys)
      allocate (sys, source=proto)
      sys%lam = fixed(attempt)
      sys%other = 3 - fixed(attempt)
      s = s0
      call sys%refresh(s, status, message)
      if (status /= SD_OK) exit
      call pack_state(sys, s, z(1:m), z(m + 1))
      call newton_solve(sys, z(1:m), z(m + 1), options%continuation%newton, iterations, status, &
                        message)
      if (status == SD_OK) exit
    end do
    if (status /= SD_OK) then
      message = 'the point is not near a '//curve_kind_name(proto%kind)//' point: '// &
                trim(message)
      return
    end if
    s = unpack_state(sys, z)
    call sys%check_point(s, options%neutral_saddles, status, message)
  end procedure correct_state

  module procedure trace_curve
    class(curve_system), allocatable :: sys
    type(curve_buffer) :: ahead, behind
    real(wp), allocatable :: s(:)
    real(wp) :: z(size(s0)), t(size(s0)), e(size(s0)), ts(size(s0)), q_min(2), q_max(2)
    integer :: m, k, reason_ahead, reason_behind, status_behind, sense
    character(len=message_len) :: message_behind

    m = size(s0) - 1           ! unknowns besides lambda
    k = proto%n + proto%n_extra
    call correct_state(proto, s0, [2, 1], options, sys, s, status, message)
    if (status /= SD_OK) then
      message = 'at the start point: '//trim(message)
      return
    end if
    call sys%refresh(s, status, message)
    if (status /= SD_OK) return
    call pack_state(sys, s, z(1:m), z(m + 1))
    e = 0
    e(m + 1) = 1
    call branch_tangent(sys, z, e, t, status, message)
    if (status /= SD_OK) then
      e = 0
      e(m) = 1
      call branch_tangent(sys, z, e, t, status, message)
    end if
    if (status /= SD_OK) then
      status = SD_SINGULAR
      message = 'the curve has no unique tangent at the start point (p = ('// &
                num2str(s(k + 1))//', '//num2str(s(k + 2))//')): '//trim(message)
      return
    end if
    ts = state_tangent(sys, t)
    sense = 1
    if (options%direction /= 0) then
      if (abs(ts(k + 2)) > sqrt(epsilon(1.0_wp))) then
        sense = nint(sign(1.0_wp, ts(k + 2)))*options%direction
      else
        sense = nint(sign(1.0_wp, ts(k + 1)))*options%direction
      end if
    end if

    call box_in_q(proto, options, q_min, q_max)
    call trace_half(sys, s, sense*ts, options, options%max_points, q_min, q_max, .true., ahead, &
                    reason_ahead, status, message)
    reason_behind = END_START
    status_behind = SD_OK
    message_behind = ''
    if (options%direction == 0 .and. reason_ahead /= END_CLOSED) &
      call trace_half(sys, s, -ts, options, options%max_points - ahead%count + 1, q_min, &
                      q_max, .false., behind, reason_behind, status_behind, message_behind)
    if (status == SD_OK .and. status_behind /= SD_OK) then
      status = status_behind
      message = message_behind
    end if
    call assemble(curve, proto%n_tests, behind, ahead, reason_behind, reason_ahead)
  end procedure trace_curve

  !> The box in scaled parameters q = (p - p_ref)/p_scale.
  pure subroutine box_in_q(sys, options, q_min, q_max)
    class(curve_system), intent(in) :: sys
    type(curve_options), intent(in) :: options
    real(wp), intent(out) :: q_min(2), q_max(2)
    integer :: k
    do k = 1, 2
      q_min(k) = -huge(1.0_wp)
      q_max(k) = huge(1.0_wp)
      if (options%p_min(k) > -huge(1.0_wp)/4) &
        q_min(k) = (options%p_min(k) - sys%p_ref(k))/sys%p_scale(k)
      if (options%p_max(k) < huge(1.0_wp)/4) &
        q_max(k) = (options%p_max(k) - sys%p_ref(k))/sys%p_scale(k)
    end do
  end subroutine box_in_q

  !> One way along the curve from the state s0 with the state tangent ts0, in segments.
  subroutine trace_half(start, s0, ts0, options, capacity, q_min, q_max, check_closure, buf, &
                        reason, status, message)
    class(curve_system), intent(in) :: start
    real(wp), intent(in) :: s0(:), ts0(:), q_min(2), q_max(2)
    type(curve_options), intent(in) :: options
    integer, intent(in) :: capacity
    logical, intent(in) :: check_closure
    type(curve_buffer), intent(out) :: buf
    integer, intent(out) :: reason, status
    character(len=message_len), intent(out) :: message
    class(curve_system), allocatable :: sys
    type(continuation_options) :: opts
    real(wp), allocatable :: pts(:, :), tans(:, :), arc(:), s(:), ts(:), z(:), zb(:)
    real(wp) :: prev_tests(max_curve_tests), tests(max_curve_tests), re(start%n), im(start%n), &
                omega, l1, ds, &
                c0(start%n + 2), tc0(start%n + 2), c_prev(start%n + 2), c_new(start%n + 2), &
                g_prev, g_new, theta
    integer :: n, k, m, np, stop_reason, j, r, info, n_found, end_here
    logical :: done, on_boundary, capacity_reached, truncated
    character(len=message_len) :: info_message

    n = start%n
    k = n + start%n_extra
    m = k + 1
    status = SD_OK
    message = ''
    reason = END_FAILED
    call new_buffer(buf, n, capacity)
    allocate (sys, source=start)
    allocate (pts(m + 1, options%segment_points), tans(m + 1, options%segment_points), &
              arc(options%segment_points), s(size(s0)), ts(size(ts0)), z(m + 1), zb(m + 1))
    s = s0
    ts = ts0
    ds = options%continuation%ds

    ! the start point
    sys%lam = merge(2, 1, abs(ts(k + 2)) >= abs(ts(k + 1)))
    sys%other = 3 - sys%lam
    call sys%refresh(s, status, message)
    if (status /= SD_OK) return
    call pack_state(sys, s, z(1:m), z(m + 1))
    call sys%diagnose(z, re, im, prev_tests, omega, l1, status, message)
    if (status /= SD_OK) return
    call append(buf, s(1:n), s(k + 1:k + 2), re, im, prev_tests, omega, l1, 0, 0.0_wp)
    c0 = [s(1:n)/start%x_scale, (s(k + 1:k + 2) - start%p_ref)/start%p_scale]
    tc0 = [ts(1:n), ts(k + 1:k + 2)]
    if (any(tc0 /= 0)) tc0 = tc0/norm2(tc0)
    c_prev = c0

    done = .false.
    do
      ! a segment: lambda is the parameter that moves most
      sys%lam = merge(2, 1, abs(ts(k + 2)) >= abs(ts(k + 1)))
      sys%other = 3 - sys%lam
      call sys%refresh(s, status, message)
      if (status /= SD_OK) then
        reason = END_FAILED
        exit
      end if
      call pack_state(sys, s, z(1:m), z(m + 1))
      opts = options%continuation
      ! a start corrected onto the curve may lie on the box's boundary up to rounding: the
      ! segment may start there (a step outward then ends it on the boundary)
      opts%lambda_min = min(q_min(sys%lam), z(m + 1))
      opts%lambda_max = max(q_max(sys%lam), z(m + 1))
      opts%direction = nint(sign(1.0_wp, ts(k + sys%lam)))
      opts%x_scale = 1
      opts%x_max = huge(1.0_wp)
      opts%ds = min(max(ds, opts%ds_min), opts%ds_max)
      capacity_reached = buf%count + options%segment_points - 1 > capacity
      opts%max_points = min(options%segment_points, capacity - buf%count + 1)
      if (opts%max_points < 2) then
        reason = END_MAX_POINTS
        exit
      end if
      call continue_branch(sys, z(1:m), z(m + 1), opts, pts(:, 1:opts%max_points), &
                           tans(:, 1:opts%max_points), arc(1:opts%max_points), np, &
                           stop_reason, info, info_message)
      if (np < 1) then
        reason = END_FAILED
        status = info
        message = 'restarting at p = ('//num2str(s(k + 1))//', '//num2str(s(k + 2))//'): '// &
                  trim(info_message)
        exit
      end if

      ! the segment ends before its border vectors turn too far from the null vectors; if
      ! already its first step turns them too far, it is tried again with a shorter step
      r = np
      truncated = .false.
      do j = 2, np
        if (.not. sys%alignment(pts(:, j)) <= max_alignment) then
          r = j - 1
          truncated = .true.
          exit
        end if
      end do
      if (truncated .and. r == 1) then
        if (opts%ds <= opts%ds_min) then
          reason = END_FAILED
          status = SD_NOT_CONVERGED
          message = 'the null vectors turn by more than 60 degrees within a step of ds_min = '// &
                    num2str(opts%ds_min)//' at p = ('//num2str(s(k + 1))//', '// &
                    num2str(s(k + 2))//')'
          exit
        end if
        ds = max(opts%ds/4, opts%ds_min)
        cycle
      end if
      ! the restart point: the last one whose tangent has a clear parameter component
      if ((stop_reason == STOP_MAX_POINTS .or. truncated) .and. .not. capacity_reached) then
        do j = r, 2, -1
          if (max(abs(tans(m, j)), abs(tans(m + 1, j))) >= tangent_floor) exit
        end do
        if (j >= 2) r = j
      end if

      do j = 2, r
        z = pts(:, j)
        ! the other parameter left the box: end exactly on its boundary
        on_boundary = z(m) < q_min(sys%other) .or. z(m) > q_max(sys%other)
        if (on_boundary) then
          call boundary_point(sys, pts(:, j - 1), tans(:, j - 1), z, &
                              merge(q_min(sys%other), q_max(sys%other), &
                                    z(m) < q_min(sys%other)), opts, zb, status, message)
          if (status /= SD_OK) then
            reason = END_FAILED
            done = .true.
            exit
          end if
          z = zb
        end if
        call sys%diagnose(z, re, im, tests, omega, l1, status, message)
        if (status /= SD_OK) then
          reason = END_FAILED
          done = .true.
          exit
        end if
        call detect_codim2(sys, pts(:, j - 1), tans(:, j - 1), z, prev_tests, tests, opts, &
                           options%neutral_saddles, buf, n_found, end_here)
        done = end_here /= 0
        if (buf%count >= capacity) then
          reason = END_MAX_POINTS
          done = .true.
          exit
        end if
        if (done) then
          reason = end_here
          exit
        end if
        s = unpack_state(sys, z)
        c_new = [s(1:n)/start%x_scale, (s(k + 1:k + 2) - start%p_ref)/start%p_scale]
        ! closed curve: the step crosses the hyperplane through the start normal to its
        ! tangent from behind, within one step of the start (as in continue_branch)
        if (check_closure) then
          g_prev = sum(tc0*(c_prev - c0))
          g_new = sum(tc0*(c_new - c0))
          if (g_prev < 0 .and. g_new >= 0) then
            theta = g_prev/(g_prev - g_new)
            if (norm2(c_prev + theta*(c_new - c_prev) - c0) <= norm2(c_new - c_prev)) then
              call append(buf, buf%x(:, 1), buf%p(:, 1), buf%re(:, 1), buf%im(:, 1), &
                          buf%tests(:, 1), buf%omega(1), buf%l1(1), 0, 0.0_wp)
              reason = END_CLOSED
              done = .true.
              exit
            end if
          end if
        end if
        call append(buf, s(1:n), s(k + 1:k + 2), re, im, tests, omega, l1, 0, 0.0_wp)
        prev_tests = tests
        c_prev = c_new
        if (on_boundary) then
          reason = END_BOX
          done = .true.
          exit
        end if
        if (maxval(abs(s(1:n))) > options%x_max) then
          reason = END_X_MAX
          done = .true.
          exit
        end if
        if (buf%count >= capacity) then
          reason = END_MAX_POINTS
          done = .true.
          exit
        end if
      end do
      if (done) exit

      if (truncated) stop_reason = STOP_MAX_POINTS
      select case (stop_reason)
      case (STOP_LAMBDA_MIN, STOP_LAMBDA_MAX)
        reason = END_BOX
        exit
      case (STOP_CLOSED)
        reason = END_CLOSED
        exit
      case (STOP_FAILED)
        reason = END_FAILED
        status = info
        message = 'no continuation step converged beyond p = ('// &
                  num2str(buf%p(1, buf%count))//', '//num2str(buf%p(2, buf%count))// &
                  ') (lambda, x: scaled): '//trim(info_message)
        exit
      case (STOP_MAX_POINTS)
        if (buf%count >= capacity) then
          reason = END_MAX_POINTS
          exit
        end if
      case default
        reason = END_FAILED
        status = SD_NOT_CONVERGED
        message = 'continuation stopped unexpectedly: '//trim(info_message)
        exit
      end select
      s = unpack_state(sys, pts(:, r))
      ts = state_tangent(sys, tans(:, r))
      if (r > 1) ds = arc(r) - arc(r - 1)
    end do

    if (reason == END_MAX_POINTS .and. status == SD_OK) then
      status = SD_CAPACITY
      message = 'the curve reached max_points = '//num2str(options%max_points)// &
                ' at p = ('//num2str(buf%p(1, buf%count))//', '// &
                num2str(buf%p(2, buf%count))//') before the end of the box (raise max_points '// &
                'or ds_max)'
    else if (reason == END_FAILED .and. status == SD_OK) then
      status = SD_NOT_CONVERGED
      message = 'the curve stopped at p = ('//num2str(buf%p(1, buf%count))//', '// &
                num2str(buf%p(2, buf%count))//')'
    end if
  end subroutine trace_half

  !> The point where the segment from z_a (tangent t_a) to z_b crosses q_other = level.
  subroutine boundary_point(sys, z_a, t_a, z_b, level, opts, z, status, message)
    class(curve_system), intent(in) :: sys
    real(wp), intent(in) :: z_a(:), t_a(:), z_b(:), level
    type(continuation_options), intent(in) :: opts
    real(wp), intent(out) :: z(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(curve_test) :: test
    allocate (test%sys, source=sys)
    test%which = 0
    test%coordinate = size(z_a) - 1
    test%level = level
    call locate_zero_on_branch(sys, z_a, t_a, sum(t_a*(z_b - z_a)), test, z, status, message, &
                               opts)
    if (status /= SD_OK) message = 'ending the curve on the parameter box: '//trim(message)
  end subroutine boundary_point

  !> Sign changes of the test functions between z_a and z_b: locate each, confirm its kind and
  !> append the points in order along the curve. end_here: the END_* reason when one of them
  !> ends the curve (a Bogdanov-Takens point a Hopf curve, unless neutral_saddles), else 0.
  subroutine detect_codim2(sys, z_a, t_a, z_b, tests_a, tests_b, opts, neutral_saddles, buf, &
                           n_found, end_here)
    class(curve_system), intent(in) :: sys
    real(wp), intent(in) :: z_a(:), t_a(:), z_b(:), tests_a(max_curve_tests), &
                            tests_b(max_curve_tests)
    type(continuation_options), intent(in) :: opts
    logical, intent(in) :: neutral_saddles
    type(curve_buffer), intent(inout) :: buf
    integer, intent(out) :: n_found, end_here
    type(curve_test) :: test
    real(wp) :: found(size(z_a), max_curve_tests), position(max_curve_tests), &
                freq(max_curve_tests), z(size(z_a)), re(sys%n), im(sys%n), &
                tests(max_curve_tests), omega, l1, s(size(z_a)), ds_total
    integer :: kinds(max_curve_tests), tested(max_curve_tests), which, kind, info, &
               order(max_curve_tests), i, j, k, n, mask
    character(len=message_len) :: info_message

    n = sys%n
    k = n + sys%n_extra
    n_found = 0
    end_here = 0
    ds_total = sum(t_a*(z_b - z_a))
    do which = 1, sys%n_tests
      if (.not. (ieee_is_finite(tests_a(which)) .and. ieee_is_finite(tests_b(which)))) cycle
      if (.not. tests_a(which)*tests_b(which) < 0) cycle
      ! e.g. on a Hopf curve det J = kappa prod(other eigenvalues) vanishes with kappa at a
      ! Bogdanov-Takens point: that zero is the BT point, not a zero-Hopf point
      mask = sys%masks(which)
      if (mask > 0) then
        if (tests_a(mask)*tests_b(mask) < 0) cycle
      end if
      if (.not. allocated(test%sys)) allocate (test%sys, source=sys)
      test%which = which
      call locate_zero_on_branch(sys, z_a, t_a, ds_total, test, z, info, info_message, opts)
      if (info /= SD_OK) then
        buf%n_unlocated = buf%n_unlocated + 1
        if (buf%unlocated_message == '') buf%unlocated_message = 'a '// &
          codim2_name(sys%codim2_kinds(which))//' point between p = ('// &
          trim(p_text(sys, z_a))//') and ('//trim(p_text(sys, z_b))//') was not located: '// &
          trim(info_message)
        cycle
      end if
      call sys%diagnose(z, re, im, tests, omega, l1, info, info_message)
      if (info /= SD_OK) cycle
      ! a sign change through a pole (l1 at a zero-Hopf point) is no zero
      if (.not. abs(tests(which)) <= pole_ratio*max(abs(tests_a(which)), abs(tests_b(which)))) &
        cycle
      kind = sys%codim2_kinds(which)
      if (.not. sys%confirm_codim2(kind, re, im, tests)) cycle
      n_found = n_found + 1
      found(:, n_found) = z
      position(n_found) = sum(t_a*(z - z_a))
      kinds(n_found) = kind
      tested(n_found) = which
      freq(n_found) = sys%codim2_frequency(kind, re, im, omega)
    end do
    ! in order along the curve
    order(1:n_found) = [(i, i = 1, n_found)]
    do i = 2, n_found
      do j = i, 2, -1
        if (position(order(j)) >= position(order(j - 1))) exit
        order(j - 1:j) = order(j:j - 1:-1)
      end do
    end do
    do i = 1, n_found
      if (buf%count >= size(buf%omega)) return
      j = order(i)
      s = unpack_state(sys, found(:, j))
      call sys%diagnose(found(:, j), re, im, tests, omega, l1, info, info_message)
      call append(buf, s(1:n), s(k + 1:k + 2), re, im, tests, omega, l1, kinds(j), freq(j))
      if (.not. neutral_saddles) end_here = sys%ends(tested(j))
      if (end_here /= 0) return
    end do
  end subroutine detect_codim2

  function p_text(sys, z) result(text)
    class(curve_system), intent(in) :: sys
    real(wp), intent(in) :: z(:)
    character(len=:), allocatable :: text
    real(wp) :: x(sys%n), p(2)
    call point_x_p(sys, z, x, p)
    text = num2str(p(1))//', '//num2str(p(2))
  end function p_text

  function curve_test_value(self, z, t) result(g)
    class(curve_test), intent(in) :: self
    real(wp), intent(in) :: z(:), t(:)
    real(wp) :: g
    real(wp) :: re(self%sys%n), im(self%sys%n), tests(max_curve_tests), omega, l1
    integer :: info
    character(len=message_len) :: info_message
    if (self%which == 0) then
      g = z(self%coordinate) - self%level
      return
    end if
    call self%sys%diagnose(z, re, im, tests, omega, l1, info, info_message)
    g = tests(self%which)
    if (info /= SD_OK) g = ieee_value(1.0_wp, ieee_quiet_nan)
  end function curve_test_value

  ! ---- buffers and the result ---------------------------------------------------------------

  subroutine new_buffer(buf, n, capacity)
    type(curve_buffer), intent(out) :: buf
    integer, intent(in) :: n, capacity
    allocate (buf%x(n, capacity), buf%p(2, capacity), buf%re(n, capacity), &
              buf%im(n, capacity), buf%tests(max_curve_tests, capacity), buf%omega(capacity), &
              buf%l1(capacity), buf%special(capacity), buf%codim2_omega(capacity))
    buf%count = 0
  end subroutine new_buffer

  subroutine append(buf, x, p, re, im, tests, omega, l1, special, codim2_omega)
    type(curve_buffer), intent(inout) :: buf
    real(wp), intent(in) :: x(:), p(2), re(:), im(:), tests(max_curve_tests), omega, l1, &
                            codim2_omega
    integer, intent(in) :: special
    if (buf%count >= size(buf%omega)) return
    buf%count = buf%count + 1
    associate (j => buf%count)
      buf%x(:, j) = x
      buf%p(:, j) = p
      buf%re(:, j) = re
      buf%im(:, j) = im
      buf%tests(:, j) = tests
      buf%omega(j) = omega
      buf%l1(j) = l1
      buf%special(j) = special
      buf%codim2_omega(j) = codim2_omega
    end associate
  end subroutine append

  !> The curve: the half behind the start reversed, then the half ahead (the start once).
  subroutine assemble(curve, n_tests, behind, ahead, reason_behind, reason_ahead)
    type(bifurcation_curve), intent(inout) :: curve
    type(curve_buffer), intent(in) :: behind, ahead
    integer, intent(in) :: n_tests, reason_behind, reason_ahead
    integer :: nb, na, total, j, c
    integer, allocatable :: columns(:)
    logical, allocatable :: from_behind(:)

    nb = max(behind%count - 1, 0)   ! without the start point
    na = ahead%count
    total = nb + na
    allocate (columns(total), from_behind(total))
    columns(1:nb) = [(behind%count + 1 - j, j = 1, nb)]
    from_behind(1:nb) = .true.
    columns(nb + 1:total) = [(j, j = 1, na)]
    from_behind(nb + 1:total) = .false.
    curve%n_points = total
    curve%start_index = nb + 1
    allocate (curve%x(curve%n, total), curve%p(2, total), curve%eig_re(curve%n, total), &
              curve%eig_im(curve%n, total), curve%tests(n_tests, total), curve%omega(total), &
              curve%l1(total), curve%special(total))
    do j = 1, total
      if (from_behind(j)) then
        call copy_column(behind, columns(j), j)
      else
        call copy_column(ahead, columns(j), j)
      end if
    end do
    curve%n_codim2 = count(curve%special /= 0)
    allocate (curve%codim2(curve%n_codim2))
    c = 0
    do j = 1, total
      if (curve%special(j) == 0) cycle
      c = c + 1
      curve%codim2(c)%kind = curve%special(j)
      curve%codim2(c)%index = j
      curve%codim2(c)%p = curve%p(:, j)
      curve%codim2(c)%x = curve%x(:, j)
      if (from_behind(j)) then
        curve%codim2(c)%omega = behind%codim2_omega(columns(j))
      else
        curve%codim2(c)%omega = ahead%codim2_omega(columns(j))
      end if
    end do
    curve%end_reason = [reason_behind, reason_ahead]
    curve%complete = all(curve%end_reason /= END_MAX_POINTS .and. curve%end_reason /= END_FAILED)
    curve%n_unlocated = behind%n_unlocated + ahead%n_unlocated
    curve%unlocated_message = behind%unlocated_message
    if (curve%unlocated_message == '') curve%unlocated_message = ahead%unlocated_message

  contains

    subroutine copy_column(buf, from, to)
      type(curve_buffer), intent(in) :: buf
      integer, intent(in) :: from, to
      curve%x(:, to) = buf%x(:, from)
      curve%p(:, to) = buf%p(:, from)
      curve%eig_re(:, to) = buf%re(:, from)
      curve%eig_im(:, to) = buf%im(:, from)
      curve%tests(:, to) = buf%tests(1:n_tests, from)
      curve%omega(to) = buf%omega(from)
      curve%l1(to) = buf%l1(from)
      curve%special(to) = buf%special(from)
    end subroutine copy_column
  end subroutine assemble
end submodule sloshdyn_bifurcation_tracer
