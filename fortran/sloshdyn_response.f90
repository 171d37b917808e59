!> Frequency (or amplitude) response of the slow flow (sec 3.3, 4.1-4.2): every branch of steady
!> states in a parameter interval by Newton and pseudo-arclength continuation, with the stability
!> of each point from the eigenvalues of the slow-flow Jacobian (dgeev), the Routh-Hurwitz
!> coefficients of eq (55), and the folds and Hopf points located on the branches.
!>
!> Branches are found, not assumed: at n_scan parameter values a grid of Newton starts collects
!> every steady state it reaches; each one not already on a computed branch is continued both
!> ways, so separate and isolated branches (isolas) are all followed.
!>
!> Table of points, one column per point (point_rows rows):
!>   1 branch, 2 lambda, 3 rho, 4 A, 5 |u1| = a1, 6 |u2| = a2, 7 phi1, 8 phi2 (eq 54),
!>   9 stable (1/0), 10 special (0, or SPECIAL_FOLD / SPECIAL_HOPF for a located point),
!>   11-14 Re(eigenvalues), 15-18 Im(eigenvalues), 19-22 C1..C4, 23 Delta2, 24 Delta3,
!>   25-28 x = (Re B1, Im B1, Re B2, Im B2)
!> Special points, one column each (special_rows rows):
!>   1 kind, 2 branch, 3 lambda, 4 rho, 5 A, 6 a1, 7 a2, 8 Hopf frequency sqrt(C3/C1) (slow
!>   time; 0 for folds), 9 column of the point in the table
module sloshdyn_response
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, SD_CAPACITY, SD_NOT_CONVERGED, check_real
  use sloshdyn_text, only: num2str
  use sloshdyn_model, only: model_t
  use sloshdyn_lapack, only: eigenvalues
  use sloshdyn_slowflow, only: slow_flow, make_slow_flow, characteristic_coefficients, &
                               PARAMETER_RHO, PARAMETER_A
  use sloshdyn_continuation, only: continuation_options, newton_options, branch_test, &
                                   newton_solve, continue_branch, locate_fold, &
                                   locate_zero_on_branch, STOP_CLOSED, continuation_check_options
  implicit none
  private
  public :: response_options, frequency_response, point_rows, special_rows, SPECIAL_FOLD, &
            SPECIAL_HOPF

  integer, parameter :: point_rows = 28, special_rows = 9
  integer, parameter :: SPECIAL_FOLD = 1, SPECIAL_HOPF = 2

  type :: response_options
    integer :: n_scan = 5               !< parameter values where steady states are searched
    integer :: n_amplitudes = 6         !< Newton starts per mode: log-spaced |B| ...
    integer :: n_phases = 6             !< ... times equally spaced arg B
    real(wp) :: amplitude_min = 1.0e-4_wp, amplitude_max = 1.0_wp   !< range of start |B|
    type(continuation_options) :: continuation   !< lambda_min/max and direction are set here
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
  !> false (and status nonzero, with where in the message) if a branch could not be finished;
  !> what was computed is returned all the same.
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
    real(wp), allocatable :: seeds(:, :), points(:, :), tangents(:, :), arclength(:), &
                             branch(:, :), branch_tangents(:, :)
    integer :: n, n_seeds, k, n_branch, branch_id
    character(len=message_len) :: branch_message
    integer :: branch_status

    table = 0
    special = 0
    n_points = 0
    n_special = 0
    complete = .true.
    call make_slow_flow(model, internal_resonance, parameter, flow, status, message)
    call check_options(status, message)
    if (status /= SD_OK) return
    n = merge(4, 2, internal_resonance)
    cont = options%continuation
    cont%lambda_min = lambda_min
    cont%lambda_max = lambda_max
    allocate (seeds(n + 1, 4096), points(n + 1, cont%max_points), &
              tangents(n + 1, cont%max_points), arclength(cont%max_points), &
              branch(n + 1, 2*cont%max_points), branch_tangents(n + 1, 2*cont%max_points))
    call find_seeds(flow, n, lambda_min, lambda_max, options, seeds, n_seeds)

    branch_id = 0
    do k = 1, n_seeds
      if (on_computed_branch(seeds(:, k))) cycle
      branch_id = branch_id + 1
      call trace_branch(seeds(:, k), n_branch, branch_status, branch_message)
      if (branch_status /= SD_OK .and. complete) then
        complete = .false.
        status = branch_status
        message = 'branch '//num2str(branch_id)//': '//trim(branch_message)
      end if
      if (n_branch > 0) call record_branch(n_branch)
      if (status == SD_CAPACITY) return
    end do

  contains

    pure subroutine check_options(status, message)
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
      end if
      if (status == SD_OK .and. (options%n_scan < 1 .or. options%n_amplitudes < 1 .or. &
                                 options%n_phases < 1)) then
        status = SD_BAD_INPUT
        message = 'n_scan, n_amplitudes and n_phases must be >= 1'
      end if
      call check_real('amplitude_min', options%amplitude_min, 0.0_wp, options%amplitude_max, &
                      .true., .false., 'amplitude_min must lie in (0, amplitude_max]', &
                      status, message)
      if (status == SD_OK) call continuation_check_options(options%continuation, status, message)
      if (status == SD_OK .and. size(table, 1) /= point_rows .or. size(special, 1) /= special_rows) then
        status = SD_BAD_INPUT
        message = 'the result tables must have '//num2str(point_rows)//' and '// &
                  num2str(special_rows)//' rows'
      end if
    end subroutine check_options

    !> Is the steady state z = (x, lambda) on a branch already in the table? Solve at its lambda
    !> from each table segment that spans it and compare.
    logical function on_computed_branch(z) result(found)
      real(wp), intent(in) :: z(:)
      real(wp) :: x(n), weight
      integer :: j, iterations, info
      character(len=message_len) :: msg
      found = .false.
      do j = 1, n_points - 1
        if (table(1, j) /= table(1, j + 1)) cycle
        if ((table(2, j) - z(n + 1))*(table(2, j + 1) - z(n + 1)) > 0) cycle
        weight = 0.5_wp
        if (table(2, j + 1) /= table(2, j)) &
          weight = (z(n + 1) - table(2, j))/(table(2, j + 1) - table(2, j))
        x = (1 - weight)*table(25:24 + n, j) + weight*table(25:24 + n, j + 1)
        call newton_solve(flow, x, z(n + 1), cont%newton, iterations, info, msg)
        if (info /= SD_OK) cycle
        if (maxval(abs(x - z(1:n))) <= 1.0e-7_wp*(1 + maxval(abs(z(1:n))))) then
          found = .true.
          return
        end if
      end do
    end function on_computed_branch

    !> Continue from a seed both ways and join the halves: branch(:, 1:n_branch), with tangents
    !> all oriented along the branch.
    subroutine trace_branch(seed, n_branch, info, msg)
      real(wp), intent(in) :: seed(:)
      integer, intent(out) :: n_branch, info
      character(len=message_len), intent(out) :: msg
      integer :: n_up, n_down, reason, info2
      character(len=message_len) :: msg2
      cont%direction = -1
      call continue_branch(flow, seed(1:n), seed(n + 1), cont, points, tangents, arclength, &
                           n_down, reason, info, msg)
      ! the backward half, reversed (tangents flipped), ends at the seed
      branch(:, 1:n_down) = points(:, n_down:1:-1)
      branch_tangents(:, 1:n_down) = -tangents(:, n_down:1:-1)
      n_branch = n_down
      if (reason == STOP_CLOSED .or. n_down == 0) return
      cont%direction = 1
      call continue_branch(flow, seed(1:n), seed(n + 1), cont, points, tangents, arclength, &
                           n_up, reason, info2, msg2)
      if (n_up > 1) then
        branch(:, n_branch + 1:n_branch + n_up - 1) = points(:, 2:n_up)
        branch_tangents(:, n_branch + 1:n_branch + n_up - 1) = tangents(:, 2:n_up)
        n_branch = n_branch + n_up - 1
      end if
      if (info == SD_OK .and. info2 /= SD_OK) then
        info = info2
        msg = msg2
      end if
    end subroutine trace_branch

    !> Points of one branch into the table with their stability, then the special points found
    !> between consecutive points, inserted in order.
    subroutine record_branch(n_branch)
      integer, intent(in) :: n_branch
      real(wp) :: z_special(n + 1), ds_total, delta3_next
      integer :: j, info, kind
      character(len=message_len) :: msg
      type(delta3_test) :: test
      logical :: hopf

      test%flow = flow
      test%value_tol = 0
      do j = 1, n_branch
        call add_point(branch(:, j), 0)
        if (status == SD_CAPACITY) return
        if (j == n_branch) exit
        ! a fold: the lambda-component of the tangent changes sign
        kind = 0
        if (branch_tangents(n + 1, j)*branch_tangents(n + 1, j + 1) < 0) then
          call locate_fold(flow, branch(:, j), branch_tangents(:, j), branch(:, j + 1), &
                           branch_tangents(:, j + 1), z_special, info, msg, cont)
          if (info == SD_OK) kind = SPECIAL_FOLD
        else if (internal_resonance) then
          ! a Hopf point: Delta3 changes sign with a complex pair on the imaginary axis (the
          ! 2-D flow of the non-resonant case has no Hopf points: its trace is -gamma11)
          delta3_next = delta3_at(branch(:, j + 1))
          if (table(24, n_points)*delta3_next < 0) then
            ds_total = sum(branch_tangents(:, j)*weights()*(branch(:, j + 1) - branch(:, j)))
            call locate_zero_on_branch(flow, branch(:, j), branch_tangents(:, j), ds_total, &
                                       test, z_special, info, msg, cont)
            if (info == SD_OK) then
              hopf = is_hopf(z_special)
              if (hopf) kind = SPECIAL_HOPF
            end if
          end if
        end if
        if (kind /= 0) then
          call add_point(z_special, kind)
          if (status == SD_CAPACITY) return
        end if
      end do

    end subroutine record_branch

    pure function weights() result(w)
      real(wp) :: w(n + 1)
      w(1:n) = cont%x_scale**2
      w(n + 1) = 1
    end function weights

    real(wp) function delta3_at(z)
      real(wp), intent(in) :: z(:)
      real(wp) :: row(point_rows)
      call evaluate_point(flow, z, row)
      delta3_at = row(24)
    end function delta3_at

    !> A Delta3 zero is a Hopf point when a complex pair sits on the imaginary axis.
    logical function is_hopf(z)
      real(wp), intent(in) :: z(:)
      real(wp) :: row(point_rows), scale
      integer :: j
      call evaluate_point(flow, z, row)
      scale = max(maxval(abs(row(11:14))), maxval(abs(row(15:18))), tiny(1.0_wp))
      is_hopf = .false.
      do j = 11, 14
        if (abs(row(j)) <= 1.0e-6_wp*scale .and. abs(row(j + 4)) > 1.0e-6_wp*scale) is_hopf = .true.
      end do
    end function is_hopf

    subroutine add_point(z, kind)
      real(wp), intent(in) :: z(:)
      integer, intent(in) :: kind
      if (n_points == size(table, 2) .or. (kind /= 0 .and. n_special == size(special, 2))) then
        status = SD_CAPACITY
        message = 'more than '//num2str(size(table, 2))//' points or '// &
                  num2str(size(special, 2))//' special points: the result does not fit'
        complete = .false.
        return
      end if
      n_points = n_points + 1
      call evaluate_point(flow, z, table(:, n_points))
      table(1, n_points) = branch_id
      table(10, n_points) = kind
      if (kind /= 0) then
        n_special = n_special + 1
        special(:, n_special) = [real(kind, wp), real(branch_id, wp), table(2:6, n_points), &
                                 merge(sqrt(max(table(21, n_points)/table(19, n_points), 0.0_wp)), &
                                       0.0_wp, kind == SPECIAL_HOPF), real(n_points, wp)]
      end if
    end subroutine add_point
  end subroutine frequency_response

  !> Newton from a grid of starts at n_scan parameter values; distinct converged solutions.
  subroutine find_seeds(flow, n, lambda_min, lambda_max, options, seeds, n_seeds)
    type(slow_flow), intent(in) :: flow
    integer, intent(in) :: n
    real(wp), intent(in) :: lambda_min, lambda_max
    type(response_options), intent(in) :: options
    real(wp), intent(out) :: seeds(:, :)
    integer, intent(out) :: n_seeds
    real(wp) :: lambda, x(n), radii(options%n_amplitudes), angles(options%n_phases)
    integer :: i, j, a1, p1, a2, p2, iterations, info, n_second
    character(len=message_len) :: msg

    n_seeds = 0
    radii = [(options%amplitude_min*(options%amplitude_max/options%amplitude_min)** &
              (real(j - 1, wp)/max(options%n_amplitudes - 1, 1)), j = 1, options%n_amplitudes)]
    angles = [(2*pi*(j - 1)/options%n_phases, j = 1, options%n_phases)]
    n_second = merge(options%n_amplitudes*options%n_phases, 1, n == 4)
    do i = 1, options%n_scan
      lambda = lambda_min + (lambda_max - lambda_min)*(i - 0.5_wp)/options%n_scan
      do a1 = 1, options%n_amplitudes
        do p1 = 1, options%n_phases
          do j = 1, n_second
            x(1:2) = radii(a1)*[cos(angles(p1)), sin(angles(p1))]
            if (n == 4) then
              a2 = (j - 1)/options%n_phases + 1
              p2 = mod(j - 1, options%n_phases) + 1
              x(3:4) = radii(a2)*[cos(angles(p2)), sin(angles(p2))]
            end if
            call newton_solve(flow, x, lambda, options%continuation%newton, iterations, info, msg)
            if (info /= SD_OK .or. .not. all(ieee_is_finite(x))) cycle
            if (maxval(abs(x)) > 10*options%amplitude_max) cycle
            if (known(x, lambda)) cycle
            if (n_seeds == size(seeds, 2)) return
            n_seeds = n_seeds + 1
            seeds(:, n_seeds) = [x, lambda]
          end do
        end do
      end do
    end do

  contains

    pure logical function known(x, lambda)
      real(wp), intent(in) :: x(:), lambda
      integer :: k
      known = .false.
      do k = 1, n_seeds
        if (seeds(n + 1, k) /= lambda) cycle
        if (maxval(abs(seeds(1:n, k) - x)) <= 1.0e-8_wp*(1 + maxval(abs(x)))) then
          known = .true.
          return
        end if
      end do
    end function known
  end subroutine find_seeds

  !> One table column (without branch and special) at z = (x, lambda).
  subroutine evaluate_point(flow, z, row)
    type(slow_flow), intent(in) :: flow
    real(wp), intent(in) :: z(:)
    real(wp), intent(out) :: row(point_rows)
    real(wp) :: fx(size(z) - 1, size(z) - 1), flambda(size(z) - 1), wr(size(z) - 1), &
                wi(size(z) - 1), c(size(z) - 1), rho, amplitude, phi1, phi2
    complex(wp) :: b1, b2
    integer :: n, info
    character(len=message_len) :: msg

    n = size(z) - 1
    row = 0
    call flow%jacobian(z(1:n), z(n + 1), fx, flambda)
    call eigenvalues(fx, wr, wi, info, msg)
    c = characteristic_coefficients(fx)
    rho = flow%model%rho
    amplitude = flow%model%A
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
    row(2:10) = [z(n + 1), rho, amplitude, abs(b1), abs(b2), phi1, phi2, &
                 merge(1.0_wp, 0.0_wp, maxval(wr) < 0), 0.0_wp]
    row(11:10 + n) = wr
    row(15:14 + n) = wi
    row(19:18 + n) = c
    if (n == 4) then
      row(23) = c(1)*c(2) - c(3)                  ! Delta2
      row(24) = c(3)*row(23) - c(1)**2*c(4)       ! Delta3
    end if
    row(25:24 + n) = z(1:n)
  end subroutine evaluate_point

  function delta3_value(self, z, t) result(g)
    class(delta3_test), intent(in) :: self
    real(wp), intent(in) :: z(:)
    real(wp), intent(in) :: t(:)   ! unused: required by the branch_test interface
    real(wp) :: g
    real(wp) :: row(point_rows)
    call evaluate_point(self%flow, z, row)
    g = row(24)   ! Delta3 depends on the point only, not on the tangent t
  end function delta3_value
end module sloshdyn_response
