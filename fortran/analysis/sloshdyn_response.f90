!> Frequency (or amplitude) response of the slow flow (sec 3.3, 4.1-4.2): every branch of steady
!> states in a parameter interval by Newton and pseudo-arclength continuation, with the stability
!> of each point from the eigenvalues of the slow-flow Jacobian (dgeev), the Routh-Hurwitz
!> coefficients of eq (55), and the folds and Hopf points located on the branches.
!>
!> Branches are found, not assumed: at n_scan parameter values a grid of Newton starts collects
!> every steady state it reaches; each one not already on a computed branch is continued both
!> ways, so separate and isolated branches (isolas) are all followed.
!>
!> Results: a table of points, one column per point, in the 'response' layout of
!> sloshdyn_tables (branch, lambda, rho, A, |u1| = a1, |u2| = a2, phi1, phi2 of eq (54), stable,
!> special kind, eigenvalues, C1..C4, Delta2, Delta3, x = (Re B1, Im B1, Re B2, Im B2)), and the
!> special points, one column each, in its 'special' layout (kind, branch, lambda, rho, A, a1,
!> a2, Hopf frequency sqrt(C3/C1) in slow time (0 for folds), column of the point).
module sloshdyn_response
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_value, ieee_quiet_nan
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, SD_CAPACITY, SD_CANCELLED, check_real
  use sloshdyn_text, only: num2str
  use sloshdyn_model, only: model_t
  use sloshdyn_excitation, only: PARAMETER_RHO, PARAMETER_A
  use sloshdyn_lapack, only: eigenvalues
  use sloshdyn_slowflow, only: slow_flow, make_slow_flow, characteristic_coefficients, &
                               steady_states
  use sloshdyn_continuation, only: continuation_options, newton_options, branch_test, &
                                   newton_solve, continue_branch, locate_fold, &
                                   locate_zero_on_branch, STOP_CLOSED, STOP_MAX_POINTS, &
                                   continuation_check_options
  use sloshdyn_tables, only: POINT_ROWS, SPECIAL_ROWS, SPECIAL_FOLD, SPECIAL_HOPF, POINT_BRANCH, &
                             POINT_LAMBDA, POINT_RHO, POINT_A, POINT_A1, POINT_A2, POINT_STABLE, &
                             POINT_SPECIAL, POINT_RE, POINT_IM, POINT_C, POINT_DELTA2, &
                             POINT_DELTA3, POINT_X
  implicit none
  private
  public :: response_options, frequency_response, check_response_options

  type :: response_options
    integer :: n_scan = 5               !< parameter values where steady states are searched
    integer :: n_amplitudes = 6         !< Newton starts per mode: log-spaced |B| ...
    integer :: n_phases = 6             !< ... times equally spaced arg B
    real(wp) :: amplitude_min = 1.0e-4_wp, amplitude_max = 1.0_wp   !< range of start |B|
    !> steps and Newton settings; max_points is per branch and direction (a branch traced both
    !> ways from its seed has up to 2 max_points - 1 points); lambda_min/max and direction are
    !> set here
    type(continuation_options) :: continuation = continuation_options(ds=0.002_wp, &
      ds_min=1.0e-9_wp, ds_max=0.01_wp, max_points=4000)
  end type response_options

  !> Delta3 of eq (55) at a branch point: its zeros are Hopf points (or neutral saddles).
  type, extends(branch_test) :: delta3_test
    type(slow_flow) :: flow
  contains
    procedure :: value => delta3_value
  end type delta3_test

contains

  !> Every branch of slow-flow steady states for lambda (rho or A, as chosen by parameter) in
  !> [lambda_min, lambda_max]; the other excitation value is taken from model. complete is
  !> false (and status nonzero, with where in the message) if a branch could not be finished
  !> (a failed step, or max_points reached); what was computed is returned all the same.
  subroutine frequency_response(model, internal_resonance, parameter, lambda_min, lambda_max, &
                                options, table, n_points, special, n_special, complete, &
                                status, message)
    type(model_t), intent(in) :: model
    logical, intent(in) :: internal_resonance
    integer, intent(in) :: parameter
    real(wp), intent(in) :: lambda_min, lambda_max
    type(response_options), intent(in) :: options
    real(wp), intent(out) :: table(:, :), special(:, :)
    integer, intent(out) :: n_points, n_special, status
    logical, intent(out) :: complete
    character(len=message_len), intent(out) :: message
    type(slow_flow) :: flow
    type(continuation_options) :: cont
    real(wp), allocatable :: seeds(:, :), branch(:, :), branch_tangents(:, :)
    real(wp) :: lambda
    integer :: n, n_seeds, i, k, n_branch, branch_id, branch_status
    character(len=message_len) :: branch_message

    table = 0
    special = 0
    n_points = 0
    n_special = 0
    complete = .true.
    call make_slow_flow(model, internal_resonance, parameter, flow, status, message)
    if (status == SD_OK) call check_response_options(options, parameter, lambda_min, lambda_max, &
                                                     status, message)
    if (status == SD_OK .and. (size(table, 1) /= POINT_ROWS .or. &
                               size(special, 1) /= SPECIAL_ROWS)) then
      status = SD_BAD_INPUT
      message = 'the result tables must have '//num2str(POINT_ROWS)//' and '// &
                num2str(SPECIAL_ROWS)//' rows'
    end if
    if (status /= SD_OK) then
      complete = .false.
      return
    end if
    n = flow%dimension()
    cont = options%continuation
    cont%lambda_min = lambda_min
    cont%lambda_max = lambda_max
    call check_starts(options, n, status, message)
    if (status /= SD_OK) then
      complete = .false.
      return
    end if
    allocate (branch(n + 1, 2*cont%max_points), branch_tangents(n + 1, 2*cont%max_points))

    ! the scan values one after the other, each branch traced as soon as its first seed is
    ! found: a value whose every steady state (closed form) is already on a computed branch
    ! needs no Newton starts, since each seed they could give would be skipped below
    branch_id = 0
    do i = 1, options%n_scan
      lambda = lambda_min + (lambda_max - lambda_min)*(i - 0.5_wp)/options%n_scan
      if (all_on_computed_branches(lambda)) cycle
      call find_seeds(flow, n, lambda, options, seeds, n_seeds)
      do k = 1, n_seeds
        if (on_computed_branch(flow, seeds(:, k), table(:, 1:n_points), cont%newton)) cycle
        branch_id = branch_id + 1
        call trace_branch(flow, seeds(:, k), cont, branch, branch_tangents, n_branch, &
                          branch_status, branch_message)
        if (branch_status /= SD_OK .and. complete) then
          complete = .false.
          status = branch_status
          message = 'branch '//num2str(branch_id)//': '//trim(branch_message)
        end if
        if (n_branch > 0) call record_branch(flow, branch(:, 1:n_branch), &
                                             branch_tangents(:, 1:n_branch), branch_id, cont, &
                                             table, n_points, special, n_special, status, &
                                             message)
        if (status == SD_CAPACITY .or. status == SD_CANCELLED) then
          complete = .false.
          return
        end if
      end do
    end do

  contains

    !> Are the steady states at lambda known in closed form and all on computed branches?
    logical function all_on_computed_branches(lambda) result(all_on)
      real(wp), intent(in) :: lambda
      real(wp), allocatable :: states(:, :)
      integer :: n_states, j
      logical :: available
      call steady_states(flow, lambda, 10*options%amplitude_max, options%continuation%newton, &
                         states, n_states, available)
      all_on = available
      do j = 1, n_states
        if (.not. all_on) return
        all_on = on_computed_branch(flow, [states(:, j), lambda], table(:, 1:n_points), &
                                    cont%newton)
      end do
    end function all_on_computed_branches
  end subroutine frequency_response

  !> The Newton starts of find_seeds, n_scan (n_amplitudes n_phases)**(n/2), are all kept in
  !> memory and each costs a Newton solve: at most max_starts (40 MB, some seconds). Counted in
  !> real numbers, so a product beyond the integers is refused, not wrapped.
  pure subroutine check_starts(options, n, status, message)
    type(response_options), intent(in) :: options
    integer, intent(in) :: n
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    real(wp), parameter :: max_starts = 1.0e6_wp
    real(wp) :: starts
    if (status /= SD_OK) return
    starts = real(options%n_scan, wp)*(real(options%n_amplitudes, wp)* &
                                       real(options%n_phases, wp))**(n/2)
    if (starts <= max_starts) return
    status = SD_BAD_INPUT
    message = 'n_scan*(n_amplitudes*n_phases)**'//num2str(n/2)//' = '//num2str(starts)// &
              ' Newton starts (n_scan = '//num2str(options%n_scan)//', n_amplitudes = '// &
              num2str(options%n_amplitudes)//', n_phases = '//num2str(options%n_phases)// &
              ') is out of range: at most '//num2str(max_starts)
  end subroutine check_starts

  !> The settings and the parameter interval: the rules every reader applies.
  pure subroutine check_response_options(options, parameter, lambda_min, lambda_max, status, &
                                         message)
    type(response_options), intent(in) :: options
    integer, intent(in) :: parameter
    real(wp), intent(in) :: lambda_min, lambda_max
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    if (status /= SD_OK) return
    call check_real('lambda_min', lambda_min, -huge(1.0_wp), lambda_max, .false., .true., &
                    'the parameter interval must have lambda_min < lambda_max', status, message)
    if (status == SD_OK .and. parameter == PARAMETER_RHO .and. lambda_min <= 0) then
      status = SD_BAD_INPUT
      message = 'rho_min = '//num2str(lambda_min)//' is out of range: rho must be > 0'
    else if (status == SD_OK .and. parameter == PARAMETER_A .and. lambda_min < 0) then
      status = SD_BAD_INPUT
      message = 'A_min = '//num2str(lambda_min)//' is out of range: A must be >= 0'
    else if (status == SD_OK .and. parameter /= PARAMETER_RHO .and. parameter /= PARAMETER_A) then
      status = SD_BAD_INPUT
      message = 'the continuation parameter must be rho (1) or A (2)'
    end if
    call check_count('n_scan', options%n_scan, status, message)
    call check_count('n_amplitudes', options%n_amplitudes, status, message)
    call check_count('n_phases', options%n_phases, status, message)
    call check_real('amplitude_max', options%amplitude_max, 0.0_wp, huge(1.0_wp), .true., &
                    .false., 'amplitude_max must be > 0', status, message)
    call check_real('amplitude_min', options%amplitude_min, 0.0_wp, options%amplitude_max, &
                    .true., .false., 'amplitude_min must lie in (0, amplitude_max]', &
                    status, message)
    if (status == SD_OK) call continuation_check_options(options%continuation, status, message)
  end subroutine check_response_options

  pure subroutine check_count(name, value, status, message)
    character(len=*), intent(in) :: name
    integer, intent(in) :: value
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    if (status /= SD_OK .or. value >= 1) return
    status = SD_BAD_INPUT
    message = name//' = '//num2str(value)//' is out of range: it must be >= 1'
  end subroutine check_count

  !> Is the steady state z = (x, lambda) on a branch already in the table? Solve at its lambda
  !> from each table segment that spans it and compare.
  logical function on_computed_branch(flow, z, table, newton) result(found)
    type(slow_flow), intent(in) :: flow
    real(wp), intent(in) :: z(:), table(:, :)
    type(newton_options), intent(in) :: newton
    real(wp) :: x(size(z) - 1), weight
    integer :: j, n, iterations, info
    character(len=message_len) :: msg
    n = size(z) - 1
    found = .false.
    do j = 1, size(table, 2) - 1
      if (table(POINT_BRANCH, j) /= table(POINT_BRANCH, j + 1)) cycle
      if ((table(POINT_LAMBDA, j) - z(n + 1))*(table(POINT_LAMBDA, j + 1) - z(n + 1)) > 0) cycle
      weight = 0.5_wp
      if (table(POINT_LAMBDA, j + 1) /= table(POINT_LAMBDA, j)) &
        weight = (z(n + 1) - table(POINT_LAMBDA, j))/(table(POINT_LAMBDA, j + 1) - &
                                                      table(POINT_LAMBDA, j))
      x = (1 - weight)*table(POINT_X:POINT_X + n - 1, j) + &
          weight*table(POINT_X:POINT_X + n - 1, j + 1)
      call newton_solve(flow, x, z(n + 1), newton, iterations, info, msg)
      if (info /= SD_OK) cycle
      if (maxval(abs(x - z(1:n))) <= 1.0e-7_wp*(1 + maxval(abs(z(1:n))))) then
        found = .true.
        return
      end if
    end do
  end function on_computed_branch

  !> Continue from a seed both ways and join the halves: branch(:, 1:n_branch), with tangents
  !> all oriented along the branch. A half that stops on max_points is reported (SD_CAPACITY).
  subroutine trace_branch(flow, seed, cont, branch, branch_tangents, n_branch, status, message)
    type(slow_flow), intent(in) :: flow
    real(wp), intent(in) :: seed(:)
    type(continuation_options), intent(in) :: cont
    real(wp), intent(out) :: branch(:, :), branch_tangents(:, :)
    integer, intent(out) :: n_branch, status
    character(len=message_len), intent(out) :: message
    type(continuation_options) :: half
    real(wp) :: points(size(seed), cont%max_points), tangents(size(seed), cont%max_points), &
                arclength(cont%max_points)
    integer :: n, n_half, reason, direction, half_status
    character(len=message_len) :: half_message

    n = size(seed) - 1
    n_branch = 0
    status = SD_OK
    message = ''
    half = cont
    do direction = -1, 1, 2
      half%direction = direction
      call continue_branch(flow, seed(1:n), seed(n + 1), half, points, tangents, arclength, &
                           n_half, reason, half_status, half_message)
      if (half_status == SD_OK .and. reason == STOP_MAX_POINTS) then
        half_status = SD_CAPACITY
        half_message = 'the branch reached max_points = '//num2str(cont%max_points)// &
                       ' at lambda = '//num2str(points(n + 1, n_half))//' before the end of '// &
                       'the interval (raise max_points or ds_max)'
      end if
      if (status == SD_OK .and. half_status /= SD_OK) then
        status = half_status
        message = half_message
      end if
      if (direction < 0) then
        ! the backward half, reversed (tangents flipped), ends at the seed
        branch(:, 1:n_half) = points(:, n_half:1:-1)
        branch_tangents(:, 1:n_half) = -tangents(:, n_half:1:-1)
        n_branch = n_half
        if (reason == STOP_CLOSED .or. n_half == 0) return
      else if (n_half > 1) then
        branch(:, n_branch + 1:n_branch + n_half - 1) = points(:, 2:n_half)
        branch_tangents(:, n_branch + 1:n_branch + n_half - 1) = tangents(:, 2:n_half)
        n_branch = n_branch + n_half - 1
      end if
    end do
  end subroutine trace_branch

  !> Points of one branch into the table with their stability, then the special points found
  !> between consecutive points, inserted in order.
  subroutine record_branch(flow, branch, tangents, branch_id, cont, table, n_points, special, &
                           n_special, status, message)
    type(slow_flow), intent(in) :: flow
    real(wp), intent(in) :: branch(:, :), tangents(:, :)
    integer, intent(in) :: branch_id
    type(continuation_options), intent(in) :: cont
    real(wp), intent(inout) :: table(:, :), special(:, :)
    integer, intent(inout) :: n_points, n_special, status
    character(len=message_len), intent(inout) :: message
    real(wp) :: z_special(size(branch, 1)), w(size(branch, 1)), ds_total, row(POINT_ROWS)
    integer :: j, n, info, kind
    character(len=message_len) :: msg
    type(delta3_test) :: test

    n = size(branch, 1) - 1
    w(1:n) = cont%x_scale**2
    w(n + 1) = 1
    test%flow = flow
    test%value_tol = 0
    do j = 1, size(branch, 2)
      call add_point(branch(:, j), 0)
      if (status == SD_CAPACITY) return
      if (j == size(branch, 2)) exit
      ! a fold: the lambda-component of the tangent changes sign
      kind = 0
      if (tangents(n + 1, j)*tangents(n + 1, j + 1) < 0) then
        call locate_fold(flow, branch(:, j), tangents(:, j), branch(:, j + 1), &
                         tangents(:, j + 1), z_special, info, msg, cont)
        if (info == SD_OK) kind = SPECIAL_FOLD
      else if (n == 4) then
        ! a Hopf point: Delta3 changes sign with a complex pair on the imaginary axis (the
        ! 2-D flow of the non-resonant case has no Hopf points: its trace is -gamma11)
        call evaluate_point(flow, branch(:, j + 1), row, info, msg)
        if (info == SD_OK .and. table(POINT_DELTA3, n_points)*row(POINT_DELTA3) < 0) then
          ds_total = sum(tangents(:, j)*w*(branch(:, j + 1) - branch(:, j)))
          call locate_zero_on_branch(flow, branch(:, j), tangents(:, j), ds_total, test, &
                                     z_special, info, msg, cont)
          if (info == SD_OK) then
            call evaluate_point(flow, z_special, row, info, msg)
            if (info == SD_OK .and. is_hopf(row)) kind = SPECIAL_HOPF
          end if
        end if
      end if
      if (kind /= 0) then
        call add_point(z_special, kind)
        if (status == SD_CAPACITY) return
      end if
    end do

  contains

    !> Append the point z (and, for kind /= 0, its special-point record) to the tables.
    subroutine add_point(z, kind)
      real(wp), intent(in) :: z(:)
      integer, intent(in) :: kind
      integer :: info
      character(len=message_len) :: msg
      if (n_points == size(table, 2) .or. (kind /= 0 .and. n_special == size(special, 2))) then
        status = SD_CAPACITY
        message = 'more than '//num2str(size(table, 2))//' points or '// &
                  num2str(size(special, 2))//' special points: the result does not fit'
        return
      end if
      n_points = n_points + 1
      call evaluate_point(flow, z, table(:, n_points), info, msg)
      if (info /= SD_OK .and. status == SD_OK) then
        status = info
        message = 'at lambda = '//num2str(z(n + 1))//': '//trim(msg)
      end if
      table(POINT_BRANCH, n_points) = branch_id
      table(POINT_SPECIAL, n_points) = kind
      if (kind /= 0) then
        n_special = n_special + 1
        special(:, n_special) = [real(kind, wp), real(branch_id, wp), &
                                 table(POINT_LAMBDA:POINT_A2, n_points), &
                                 merge(sqrt(max(table(POINT_C + 2, n_points)/ &
                                                table(POINT_C, n_points), 0.0_wp)), &
                                       0.0_wp, kind == SPECIAL_HOPF), real(n_points, wp)]
      end if
    end subroutine add_point
  end subroutine record_branch

  !> A Delta3 zero is a Hopf point when a complex pair sits on the imaginary axis.
  pure logical function is_hopf(row)
    real(wp), intent(in) :: row(POINT_ROWS)
    real(wp) :: scale
    integer :: j
    scale = max(maxval(abs(row(POINT_RE:POINT_RE + 3))), maxval(abs(row(POINT_IM:POINT_IM + 3))), &
                tiny(1.0_wp))
    is_hopf = .false.
    do j = 0, 3
      if (abs(row(POINT_RE + j)) <= 1.0e-6_wp*scale .and. &
          abs(row(POINT_IM + j)) > 1.0e-6_wp*scale) is_hopf = .true.
    end do
  end function is_hopf

  !> Newton from a grid of starts at one parameter value lambda; distinct converged solutions,
  !> seeds(:, 1:n_seeds) = (x, lambda) (allocated for every start, so none is lost).
  subroutine find_seeds(flow, n, lambda, options, seeds, n_seeds)
    type(slow_flow), intent(in) :: flow
    integer, intent(in) :: n
    real(wp), intent(in) :: lambda
    type(response_options), intent(in) :: options
    real(wp), allocatable, intent(out) :: seeds(:, :)
    integer, intent(out) :: n_seeds
    real(wp) :: x(n), radii(options%n_amplitudes), angles(options%n_phases)
    integer :: j, a1, p1, a2, p2, iterations, info, n_second
    character(len=message_len) :: msg

    n_seeds = 0
    radii = [(options%amplitude_min*(options%amplitude_max/options%amplitude_min)** &
              (real(j - 1, wp)/max(options%n_amplitudes - 1, 1)), j = 1, options%n_amplitudes)]
    angles = [(2*pi*(j - 1)/options%n_phases, j = 1, options%n_phases)]
    n_second = merge(options%n_amplitudes*options%n_phases, 1, n == 4)
    allocate (seeds(n + 1, options%n_amplitudes*options%n_phases*n_second))
    do a1 = 1, options%n_amplitudes
      do p1 = 1, options%n_phases
        do j = 1, n_second
          x(1:2) = radii(a1)*[cos(angles(p1)), sin(angles(p1))]
          if (n == 4) then
            a2 = (j - 1)/options%n_phases + 1
            p2 = mod(j - 1, options%n_phases) + 1
            x(3:4) = radii(a2)*[cos(angles(p2)), sin(angles(p2))]
          end if
          call newton_solve(flow, x, lambda, options%continuation%newton, iterations, info, msg, &
                            explain=.false.)
          if (info /= SD_OK .or. .not. all(ieee_is_finite(x))) cycle
          if (maxval(abs(x)) > 10*options%amplitude_max) cycle
          if (known(x)) cycle
          n_seeds = n_seeds + 1
          seeds(:, n_seeds) = [x, lambda]
        end do
      end do
    end do

  contains

    pure logical function known(x)
      real(wp), intent(in) :: x(:)
      integer :: k
      known = .false.
      do k = 1, n_seeds
        if (maxval(abs(seeds(1:n, k) - x)) <= 1.0e-8_wp*(1 + maxval(abs(x)))) then
          known = .true.
          return
        end if
      end do
    end function known
  end subroutine find_seeds

  !> One table column (without branch and special) at z = (x, lambda); status of dgeev.
  subroutine evaluate_point(flow, z, row, status, message)
    type(slow_flow), intent(in) :: flow
    real(wp), intent(in) :: z(:)
    real(wp), intent(out) :: row(POINT_ROWS)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: fx(size(z) - 1, size(z) - 1), flambda(size(z) - 1), wr(size(z) - 1), &
                wi(size(z) - 1), c(size(z) - 1), rho, amplitude, phi1, phi2
    complex(wp) :: b1, b2
    integer :: n

    n = size(z) - 1
    row = 0
    call flow%jacobian(z(1:n), z(n + 1), fx, flambda)
    call eigenvalues(fx, wr, wi, status, message)
    if (status /= SD_OK) then
      message = 'eigenvalues of the slow-flow Jacobian: '//trim(message)
      return
    end if
    c = characteristic_coefficients(fx)
    rho = flow%model%excitation%rho
    amplitude = flow%model%excitation%A
    if (flow%parameter == PARAMETER_RHO) then
      rho = z(n + 1)
    else
      amplitude = z(n + 1)
    end if
    b1 = cmplx(z(1), z(2), wp)
    b2 = 0
    if (n == 4) b2 = cmplx(z(3), z(4), wp)
    ! eq (54) phases: B1 = a1 exp(-i phi2), B2 = a2 exp(i (phi1 - 3 phi2))
    phi2 = -atan2(aimag(b1), real(b1))
    phi1 = modulo(atan2(aimag(b2), real(b2)) + 3*phi2 + pi, 2*pi) - pi
    row(POINT_LAMBDA:POINT_SPECIAL) = [z(n + 1), rho, amplitude, abs(b1), abs(b2), phi1, phi2, &
                                      merge(1.0_wp, 0.0_wp, maxval(wr) < 0), 0.0_wp]
    row(POINT_RE:POINT_RE + n - 1) = wr
    row(POINT_IM:POINT_IM + n - 1) = wi
    row(POINT_C:POINT_C + n - 1) = c
    if (n == 4) then
      row(POINT_DELTA2) = c(1)*c(2) - c(3)
      row(POINT_DELTA3) = c(3)*row(POINT_DELTA2) - c(1)**2*c(4)
    end if
    row(POINT_X:POINT_X + n - 1) = z(1:n)
  end subroutine evaluate_point

  !> Delta3 at the branch point z (it depends on the point only, not on the tangent t); NaN
  !> when the eigenvalues fail, which stops the zero finder.
  function delta3_value(self, z, t) result(g)
    class(delta3_test), intent(in) :: self
    real(wp), intent(in) :: z(:)
    real(wp), intent(in) :: t(:)
    real(wp) :: g
    real(wp) :: row(POINT_ROWS)
    integer :: info
    character(len=message_len) :: msg
    call evaluate_point(self%flow, z, row, info, msg)
    g = row(POINT_DELTA3)
    if (info /= SD_OK) g = ieee_value(1.0_wp, ieee_quiet_nan)
  end function delta3_value
end module sloshdyn_response
