!> The per-point work of parameter studies (the Python study engine cuts a study into tasks of
!> many points and calls these once per task): steady states at a list of points, each from its
!> own initial state or continued from the previous one; the periodic orbit each one settled on
!> (through the shooting code, with Floquet multipliers); and the attractors of a set of runs,
!> told apart by their orbits. Every point is computed exactly as steady_state computes it
!> alone, so a study equals a serial loop of steady states, bit for bit. No global state.
!>
!> Layout of orbit(ORBIT_ROWS, n), per point (the table 'study_orbit' of sloshdyn_tables):
!>   [found (1/0), periods k, attempts, y1..y4 (the orbit's state at forcing phase 0),
!>    re_mu1..re_mu4, im_mu1..im_mu4 (Floquet multipliers), max|mu|]
!> found = 1 when the steady state jumped to the orbit by shooting, 2 when it was reached by
!> integration and the orbit was then refined by shooting (attractor_points only), else 0 and
!> the rest NaN.
module sloshdyn_studies
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, check_real
  use sloshdyn_text, only: num2str
  use sloshdyn_model, only: model_t
  use sloshdyn_system, only: tank_system
  use sloshdyn_ode, only: ode_options, ode_stats
  use sloshdyn_shooting, only: shooting_newton
  use sloshdyn_simulation, only: steady_options, steady_state, steady_state_block, &
                                 steady_state_points, steady_orbit, max_period, check_block
  use sloshdyn_tables, only: SUMMARY_SIZE, SUMMARY_MOTION, SUMMARY_PERIOD, MOTION_PERIODIC
  implicit none
  private
  public :: steady_path, attractor_points, label_attractors, roof_impact
  public :: ORBIT_ROWS

  integer, parameter :: ORBIT_ROWS = 16
  !> Refining an orbit reached by integration: Newton's tolerance and iterations, and how far
  !> (relative) the orbit may lie from the state the integration ended in.
  real(wp), parameter :: refine_tol = 1.0e-10_wp, refine_distance = 1.0e-3_wp
  integer, parameter :: refine_max_iter = 20

contains

  !> The wall (roof) is reached: max|x1| >= 1, the pendulum at theta0 (eq 3-4), where the
  !> impact potential acts.
  elemental logical function roof_impact(max_x1)
    real(wp), intent(in) :: max_x1
    roof_impact = max_x1 >= 1
  end function roof_impact

  !> Steady states at the points (rho(i), A(i)), i = 1..n. carry = .false.: each from y0(:, i)
  !> (independent points); carry = .true.: the first from y0(:, 1), each next one from the
  !> previous point's final state (a sweep along the path, so jumps and hysteresis show).
  !> summaries(:, i) in the 'summary' layout, y_end(:, i) the final state (forcing phase 0),
  !> orbit(:, i) in the layout above. A point that fails gets point_status(i) /= 0, NaN
  !> results and point_message(i) = what its run alone says (no point number: the same in any
  !> task); independent points go on, a carried path stops there (the rest get the same status
  !> and point_message ''). status and message are those of the first failure (SD_OK if none),
  !> the message naming the point; a call refused as a whole gives every point its status and
  !> message.
  subroutine steady_path(model, rho, A, y0, carry, options, method, steady, summaries, y_end, &
                         orbit, point_status, point_message, status, message, block)
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: rho(:), A(:), y0(:, :)
    logical, intent(in) :: carry
    type(ode_options), intent(in) :: options
    integer, intent(in) :: method
    type(steady_options), intent(in) :: steady
    real(wp), intent(out) :: summaries(:, :), y_end(:, :), orbit(:, :)
    integer, intent(out) :: point_status(:), status
    character(len=message_len), intent(out) :: point_message(:), message
    integer, intent(in), optional :: block
    type(model_t) :: point
    type(ode_stats) :: stats
    type(steady_orbit) :: found
    real(wp) :: start(4), poincare(4, max(steady%window_periods, 1))
    integer :: i, n, info, points
    character(len=message_len) :: text

    n = size(rho)
    status = SD_OK
    message = ''
    summaries = ieee_value(1.0_wp, ieee_quiet_nan)
    y_end = ieee_value(1.0_wp, ieee_quiet_nan)
    orbit = ieee_value(1.0_wp, ieee_quiet_nan)
    point_status = SD_OK
    point_message = ''
    if (size(A) /= n .or. size(y0, 1) /= 4 .or. (size(y0, 2) /= n .and. .not. carry) .or. &
        (carry .and. size(y0, 2) < 1) .or. size(summaries, 1) /= SUMMARY_SIZE .or. &
        size(summaries, 2) /= n .or. any(shape(y_end) /= [4, n]) .or. &
        any(shape(orbit) /= [ORBIT_ROWS, n]) .or. size(point_status) /= n .or. &
        size(point_message) /= n) then
      status = SD_BAD_INPUT
      message = 'steady_path: the arrays must be rho(n), A(n), y0(4, n), summaries('// &
                num2str(SUMMARY_SIZE)//', n), y_end(4, n), orbit('//num2str(ORBIT_ROWS)// &
                ', n), point_status(n), point_message(n); n = '//num2str(n)
      call all_failed(status, message, point_status, point_message)
      return
    end if
    points = 1
    if (present(block)) points = block
    call check_block(points, status, message)
    if (status /= SD_OK) then
      call all_failed(status, message, point_status, point_message)
      return
    end if
    if (.not. carry) then
      call independent_points(model, rho, A, y0, options, method, steady, points, summaries, &
                              y_end, orbit, point_status, point_message, status, message)
      return
    end if
    start = y0(:, 1)
    do i = 1, n
      call point_model(model, rho(i), A(i), point, info, text)
      if (info == SD_OK) &
        call steady_state(point, start, options, method, steady, summaries(:, i), poincare, &
                          y_end(:, i), stats, info, text, found)
      if (info /= SD_OK) then
        call path_point_failed(i, rho(i), A(i), info, text, summaries, y_end, point_status, &
                               point_message, status, message)
        point_status(i:) = info
        return
      end if
      orbit(:, i) = orbit_row(found, 0)
      start = y_end(:, i)
    end do
  end subroutine steady_path

  !> steady_path's independent points (carry = .false.): those with a valid (rho, A) go to
  !> steady_state_block `block` at a time (steady_state_points), each equal to its
  !> steady_state alone; the failures are then reported in the order of the points.
  subroutine independent_points(model, rho, A, y0, options, method, steady, block, summaries, &
                                y_end, orbit, point_status, point_message, status, message)
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: rho(:), A(:), y0(:, :)
    type(ode_options), intent(in) :: options
    integer, intent(in) :: method, block
    type(steady_options), intent(in) :: steady
    real(wp), intent(inout) :: summaries(:, :), y_end(:, :), orbit(:, :)
    integer, intent(inout) :: point_status(:), status
    character(len=message_len), intent(inout) :: point_message(:), message
    type(model_t), allocatable :: models(:)
    type(steady_orbit), allocatable :: found(:)
    integer, allocatable :: infos(:)
    character(len=message_len), allocatable :: texts(:)
    integer :: i

    allocate (models(size(rho)), found(size(rho)), infos(size(rho)), texts(size(rho)))
    do i = 1, size(rho)
      call point_model(model, rho(i), A(i), models(i), infos(i), texts(i))
    end do
    call steady_state_points(models, y0, options, method, steady, block, summaries, y_end, &
                             found, infos, texts)
    do i = 1, size(rho)
      if (infos(i) == SD_OK) then
        orbit(:, i) = orbit_row(found(i), 0)
      else
        call path_point_failed(i, rho(i), A(i), infos(i), texts(i), summaries, y_end, &
                               point_status, point_message, status, message)
      end if
    end do
  end subroutine independent_points

  !> The model at point (rho, A) of a path, or the status naming a bad rho or A.
  subroutine point_model(model, rho, A, point, info, text)
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: rho, A
    type(model_t), intent(out) :: point
    integer, intent(out) :: info
    character(len=message_len), intent(out) :: text
    info = SD_OK
    text = ''
    call check_real('rho', rho, 0.0_wp, huge(1.0_wp), .true., .true., &
                    'a steady state needs a forcing frequency rho > 0', info, text)
    call check_real('A', A, 0.0_wp, huge(1.0_wp), .false., .true., &
                    'the forcing amplitude A must be >= 0 and finite', info, text)
    point = model
    point%excitation%rho = rho
    point%excitation%A = A
  end subroutine point_model

  !> point_failed for point i of a path, its message naming (rho, A).
  subroutine path_point_failed(i, rho, A, info, text, summaries, y_end, point_status, &
                               point_message, status, message)
    integer, intent(in) :: i, info
    real(wp), intent(in) :: rho, A
    character(len=*), intent(in) :: text
    real(wp), intent(inout) :: summaries(:, :), y_end(:, :)
    integer, intent(inout) :: point_status(:), status
    character(len=message_len), intent(inout) :: point_message(:), message
    call point_failed(i, info, 'point '//num2str(i)//' (rho = '//num2str(rho)//', A = '// &
                      num2str(A)//')', text, summaries, y_end, point_status, point_message, &
                      status, message)
  end subroutine path_point_failed

  !> Point i failed with status info and message text (its run's alone): its summaries and
  !> final state are NaN, point_message(i) = text, and the first failure gives the status and
  !> the message (point: what names the point, before the reason).
  pure subroutine point_failed(i, info, point, text, summaries, y_end, point_status, &
                               point_message, status, message)
    integer, intent(in) :: i, info
    character(len=*), intent(in) :: point, text
    real(wp), intent(inout) :: summaries(:, :), y_end(:, :)
    integer, intent(inout) :: point_status(:), status
    character(len=message_len), intent(inout) :: point_message(:), message
    summaries(:, i) = ieee_value(1.0_wp, ieee_quiet_nan)
    y_end(:, i) = ieee_value(1.0_wp, ieee_quiet_nan)
    point_status(i) = info
    point_message(i) = text
    if (status == SD_OK) then
      status = info
      message = point//': '//trim(text)
    end if
  end subroutine point_failed

  !> A call refused as a whole (status, message): every point has its status and message.
  pure subroutine all_failed(status, message, point_status, point_message)
    integer, intent(in) :: status
    character(len=*), intent(in) :: message
    integer, intent(out) :: point_status(:)
    character(len=message_len), intent(out) :: point_message(:)
    point_status = status
    point_message = message
  end subroutine all_failed

  !> The orbit layout of a steady_orbit (found = 1), or NaN with found = 0; kind overrides the
  !> found code when > 0.
  pure function orbit_row(found, kind) result(row)
    type(steady_orbit), intent(in) :: found
    integer, intent(in) :: kind
    real(wp) :: row(ORBIT_ROWS)
    row = ieee_value(1.0_wp, ieee_quiet_nan)
    row(1) = 0
    row(3) = found%attempts
    if (.not. found%found) return
    row(1) = merge(kind, 1, kind > 0)
    row(2) = found%periods
    row(4:7) = found%y
    row(8:11) = found%multipliers_re
    row(12:15) = found%multipliers_im
    row(16) = maxval(hypot(found%multipliers_re, found%multipliers_im))
  end function orbit_row

  !> Steady states from the initial states y0(:, i) at the excitation of model (a basin of
  !> attraction), each with the attractor it reached: steady_path's results, and for periodic
  !> motion reached by integration (no jump) the orbit refined by shooting from the final state
  !> (period k T from the classification; kept if Newton converges within refine_distance of
  !> that state); orbit_points(:, j, i), j = 1..k, the orbit's Poincare points over one orbit
  !> period (from the window), NaN beyond k and for other motions. The points go to
  !> steady_state_block `block` at a time (>= 1), each equal to its steady_state alone; a
  !> failed point's point_message as steady_path's.
  subroutine attractor_points(model, y0, options, method, steady, block, summaries, y_end, &
                              orbit, orbit_points, point_status, point_message, status, message)
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: y0(:, :)
    type(ode_options), intent(in) :: options
    integer, intent(in) :: method, block
    type(steady_options), intent(in) :: steady
    real(wp), intent(out) :: summaries(:, :), y_end(:, :), orbit(:, :), orbit_points(:, :, :)
    integer, intent(out) :: point_status(:), status
    character(len=message_len), intent(out) :: point_message(:), message
    type(ode_stats), allocatable :: stats(:)
    type(steady_orbit), allocatable :: found(:)
    integer, allocatable :: infos(:)
    character(len=message_len), allocatable :: texts(:)
    real(wp), allocatable :: poincare(:, :, :)
    type(tank_system) :: system
    real(wp) :: y_orbit(4), monodromy(4, 4), re(4), im(4), scale
    integer :: i, c, n, nb, first, info, k, iterations
    character(len=message_len) :: text

    n = size(y0, 2)
    status = SD_OK
    message = ''
    summaries = ieee_value(1.0_wp, ieee_quiet_nan)
    y_end = ieee_value(1.0_wp, ieee_quiet_nan)
    orbit = ieee_value(1.0_wp, ieee_quiet_nan)
    orbit_points = ieee_value(1.0_wp, ieee_quiet_nan)
    point_status = SD_OK
    point_message = ''
    if (size(y0, 1) /= 4 .or. size(summaries, 1) /= SUMMARY_SIZE .or. &
        size(summaries, 2) /= n .or. any(shape(y_end) /= [4, n]) .or. &
        any(shape(orbit) /= [ORBIT_ROWS, n]) .or. &
        any(shape(orbit_points) /= [4, max_period, n]) .or. size(point_status) /= n .or. &
        size(point_message) /= n) then
      status = SD_BAD_INPUT
      message = 'attractor_points: the arrays must be y0(4, n), summaries('// &
                num2str(SUMMARY_SIZE)//', n), y_end(4, n), orbit('//num2str(ORBIT_ROWS)// &
                ', n), orbit_points(4, '//num2str(max_period)//', n), point_status(n), '// &
                'point_message(n); n = '//num2str(n)
      call all_failed(status, message, point_status, point_message)
      return
    end if
    call check_block(block, status, message)
    if (status /= SD_OK) then
      call all_failed(status, message, point_status, point_message)
      return
    end if
    system%model = model
    allocate (stats(block), found(block), infos(block), texts(block), &
              poincare(4, max(steady%window_periods, 1), block))
    do first = 1, n, block
      nb = min(block, n - first + 1)
      call steady_state_block([model], y0(:, first:first + nb - 1), options, method, steady, &
                              summaries(:, first:first + nb - 1), poincare(:, :, 1:nb), &
                              y_end(:, first:first + nb - 1), stats(1:nb), infos(1:nb), &
                              texts(1:nb), found(1:nb))
      do c = 1, nb
        i = first + c - 1
        if (infos(c) /= SD_OK) then
          call point_failed(i, infos(c), 'initial state '//num2str(i), texts(c), summaries, &
                            y_end, point_status, point_message, status, message)
          cycle
        end if
        orbit(:, i) = orbit_row(found(c), 0)
        if (nint(summaries(SUMMARY_MOTION, i)) /= MOTION_PERIODIC) cycle
        k = nint(summaries(SUMMARY_PERIOD, i))
        orbit_points(:, 1:k, i) = poincare(:, 1:k, c)
        if (found(c)%found) cycle
        ! reached by integration: refine the orbit by shooting from where the integration ended
        call shooting_newton(system, y_end(:, i), k, options, method, refine_tol, &
                             refine_max_iter, y_orbit, monodromy, re, im, iterations, info, text)
        scale = max(norm2(y_end(:, i)), tiny(1.0_wp))
        if (info == SD_OK .and. norm2(y_orbit - y_end(:, i)) <= refine_distance*scale) then
          found(c)%found = .true.
          found(c)%periods = k
          found(c)%y = y_orbit
          found(c)%multipliers_re = re
          found(c)%multipliers_im = im
          orbit(:, i) = orbit_row(found(c), 2)
        end if
      end do
    end do
  end subroutine attractor_points

  !> Attractors of a set of runs: label(i) = the attractor run i reached, 1..n_attractors, in
  !> order of first appearance; 0 for failed runs (motion NaN). Periodic runs (orbit_points
  !> given, period k = periods(i)) share an attractor when their periods agree and every
  !> Poincare point of one lies within tol (relative to the larger state) of a point of the
  !> other; every other motion (quasi-periodic, irregular, settling) forms one attractor per
  !> motion kind. representative(j) = the first run with label j.
  pure subroutine label_attractors(motions, periods, orbit_points, tol, label, n_attractors, &
                                   representative)
    real(wp), intent(in) :: motions(:), periods(:), orbit_points(:, :, :), tol
    integer, intent(out) :: label(:), n_attractors, representative(:)
    integer :: i, j, r
    label = 0
    representative = 0
    n_attractors = 0
    do i = 1, size(motions)
      if (motions(i) /= motions(i)) cycle
      do j = 1, n_attractors
        r = representative(j)
        if (same_attractor(i, r)) then
          label(i) = j
          exit
        end if
      end do
      if (label(i) == 0) then
        n_attractors = n_attractors + 1
        label(i) = n_attractors
        representative(n_attractors) = i
      end if
    end do

  contains

    pure logical function same_attractor(a, b)
      integer, intent(in) :: a, b
      integer :: k, p, q
      real(wp) :: scale
      same_attractor = .false.
      if (nint(motions(a)) /= nint(motions(b))) return
      if (nint(motions(a)) /= MOTION_PERIODIC) then
        same_attractor = .true.
        return
      end if
      k = nint(periods(a))
      if (k /= nint(periods(b)) .or. k < 1 .or. k > size(orbit_points, 2)) return
      scale = max(maxval(norm2(orbit_points(:, 1:k, a), dim=1)), &
                  maxval(norm2(orbit_points(:, 1:k, b), dim=1)), tiny(1.0_wp))
      do p = 1, k
        if (.not. any([(norm2(orbit_points(:, p, a) - orbit_points(:, q, b)) <= tol*scale, &
                        q = 1, k)])) return
      end do
      same_attractor = .true.
    end function same_attractor
  end subroutine label_attractors
end module sloshdyn_studies
