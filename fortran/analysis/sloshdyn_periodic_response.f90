!> Periodic responses of the full equations of motion (eq 15 with 29-31), not of the slow flow:
!> the tank system (sloshdyn_system) handed to the generic shooting, continuation and Lyapunov
!> code of the numerics layer. Result layouts are those of sloshdyn_shooting (n = 4).
module sloshdyn_periodic_response
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, SD_NOT_CONVERGED
  use sloshdyn_text, only: num2str
  use sloshdyn_model, only: model_t
  use sloshdyn_system, only: tank_system
  use sloshdyn_ode, only: ode_options, ode_stats
  use sloshdyn_continuation, only: continuation_options
  use sloshdyn_shooting, only: shooting_newton, periodic_branch, switch_branch, monodromy_matrix
  use sloshdyn_half_period, only: locate_symmetry_breaking
  use sloshdyn_map_normal_form, only: cubic_coefficient, neimark_sacker_coefficient
  use sloshdyn_excitation, only: EXCITATION_HARMONIC
  use sloshdyn_lyapunov, only: largest_lyapunov, check_lyapunov_counts, average_names, &
                               AVERAGE_PLAIN
  use sloshdyn_simulation, only: steady_options, steady_state
  use sloshdyn_response, only: response_options, frequency_response
  use sloshdyn_linear, only: modal_matrix
  use sloshdyn_excitation, only: PARAMETER_RHO
  use sloshdyn_tables, only: SUMMARY_SIZE, POINT_ROWS, SPECIAL_ROWS, POINT_RHO, POINT_STABLE, &
                             POINT_X, SPECIAL_BRANCH_POINT
  implicit none
  private
  public :: periodic_orbit, periodic_response, lyapunov_exponent, periodic_response_from_rest, &
            orbit_from_rest, periodic_switch, period_doubling_criticality, &
            neimark_sacker_criticality
  public :: lyapunov_options, check_lyapunov, newton_tol_default, max_iter_default
  public :: periodic_start_state, start_names

  !> The start states of periodic orbits (periodic_start_state), by name.
  character(len=*), parameter :: start_names(2) = [character(len=10) :: 'simulation', &
                                                                         'slow_flow']
  !> ... from a simulation: the steady state reached from rest within this many periods
  integer, parameter :: start_transient_periods = 5000
  !> ... from the slow flow: its steady states on rho (1 -+ start_band), on at most
  !> start_points points (the Python front door's table capacity)
  real(wp), parameter :: start_band = 1.0e-3_wp
  integer, parameter :: start_points = 20000, start_specials = 200

  !> Shooting's Newton settings unless given: |y(kT) - y0| and the step <= tol (max|y0| + 1e-12).
  real(wp), parameter :: newton_tol_default = 1.0e-10_wp
  integer, parameter :: max_iter_default = 30

  !> How a Lyapunov exponent is measured; times in forcing periods.
  type :: lyapunov_options
    integer :: transient_periods = 1000   !< integrated before measuring
    integer :: n_periods = 2000           !< measured; a multiple of renormalise_every
    integer :: renormalise_every = 1      !< periods between renormalisations of the tangent
    logical :: spectrum = .false.         !< all four exponents (QR method), not the largest only
    integer :: average = AVERAGE_PLAIN    !< how the log growths are averaged (average_names)
  end type lyapunov_options

contains

  !> The orbit of period k T near y0 by shooting: y_orbit, the monodromy matrix, the Floquet
  !> multipliers (re, im), Newton iterations and max|x1| over the orbit.
  subroutine periodic_orbit(model, y0, k, options, method, newton_tol, max_iter, y_orbit, &
                            monodromy, re, im, iterations, max_x1, status, message)
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: y0(4), newton_tol
    integer, intent(in) :: k, method, max_iter
    type(ode_options), intent(in) :: options
    real(wp), intent(out) :: y_orbit(4), monodromy(4, 4), re(4), im(4), max_x1
    integer, intent(out) :: iterations, status
    character(len=message_len), intent(out) :: message
    type(tank_system) :: system
    system%model = model
    call shooting_newton(system, y0, k, options, method, newton_tol, max_iter, y_orbit, &
                         monodromy, re, im, iterations, status, message, max_x1)
  end subroutine periodic_orbit

  !> Continuation of the orbit through y0 (at the excitation of model) in rho or A
  !> (parameter = PARAMETER_RHO, PARAMETER_A) over [lambda_min, lambda_max].
  subroutine periodic_response(model, parameter, y0, k, lambda_min, lambda_max, continuation, &
                               options, method, points, multipliers, n_points, special, &
                               n_special, complete, status, message)
    type(model_t), intent(in) :: model
    integer, intent(in) :: parameter, k, method
    real(wp), intent(in) :: y0(4), lambda_min, lambda_max
    type(continuation_options), intent(in) :: continuation
    type(ode_options), intent(in) :: options
    real(wp), intent(out) :: points(:, :), multipliers(:, :), special(:, :)
    integer, intent(out) :: n_points, n_special, status
    logical, intent(out) :: complete
    character(len=message_len), intent(out) :: message
    type(tank_system) :: system
    system%model = model
    system%varied = parameter
    call periodic_branch(system, y0, lambda_min, lambda_max, continuation, options, method, &
                         points, multipliers, n_points, special, n_special, complete, status, &
                         message, k)
    call refine_branch_points(system, k, options, method, special, n_special)
  end subroutine periodic_response

  !> Branch switching (sloshdyn_shooting's switch_branch) at the special point of kind
  !> SPECIAL_BRANCH_POINT or SPECIAL_PERIOD_DOUBLING at (y_special, lambda_special) of a branch
  !> of period k T in rho or A (parameter): the other branch, or the doubled orbits (period
  !> k_new T = 2 k T), continued over [lambda_min, lambda_max].
  subroutine periodic_switch(model, parameter, kind, y_special, lambda_special, k, lambda_min, &
                             lambda_max, continuation, options, method, points, multipliers, &
                             n_points, special, n_special, complete, k_new, status, message)
    type(model_t), intent(in) :: model
    integer, intent(in) :: parameter, kind, k, method
    real(wp), intent(in) :: y_special(4), lambda_special, lambda_min, lambda_max
    type(continuation_options), intent(in) :: continuation
    type(ode_options), intent(in) :: options
    real(wp), intent(out) :: points(:, :), multipliers(:, :), special(:, :)
    integer, intent(out) :: n_points, n_special, k_new, status
    logical, intent(out) :: complete
    character(len=message_len), intent(out) :: message
    type(tank_system) :: system
    system%model = model
    system%varied = parameter
    call system%set_parameter(lambda_special)
    call switch_branch(system, kind, y_special, k, lambda_min, lambda_max, continuation, &
                       options, method, points, multipliers, n_points, special, n_special, &
                       complete, k_new, status, message)
    call refine_branch_points(system, k_new, options, method, special, n_special)
  end subroutine periodic_switch

  !> The criticality of the period doubling of the orbit of period k T through y at the
  !> model's excitation (sloshdyn_map_normal_form): the flip coefficient c (> 0 supercritical),
  !> the critical eigenvector q and multiplier mu.
  subroutine period_doubling_criticality(model, y, k, options, method, c, q, mu, status, &
                                         message)
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: y(4)
    integer, intent(in) :: k, method
    type(ode_options), intent(in) :: options
    real(wp), intent(out) :: c, q(4), mu
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(tank_system) :: system
    system%model = model
    call cubic_coefficient(system, y, k, options, method, -1, c, q, mu, status, message)
  end subroutine period_doubling_criticality

  !> The criticality of the Neimark-Sacker point of the orbit of period k T through y at the
  !> model's excitation (sloshdyn_map_normal_form): the coefficient d (< 0 supercritical), the
  !> critical eigenvector q and multiplier mu (Im mu > 0).
  subroutine neimark_sacker_criticality(model, y, k, options, method, d, q, mu, status, message)
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: y(4)
    integer, intent(in) :: k, method
    type(ode_options), intent(in) :: options
    real(wp), intent(out) :: d
    complex(wp), intent(out) :: q(4), mu
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(tank_system) :: system
    system%model = model
    call neimark_sacker_coefficient(system, y, k, options, method, d, q, mu, status, message)
  end subroutine neimark_sacker_criticality

  !> The branch points among special(:, 1:n_special) (rows [kind, lambda, y(1:4), max|x1|])
  !> located again on the half-period map (sloshdyn_half_period), where they are regular: to
  !> ~1e-12 instead of the full-period map's ~1e-7. Only under harmonic excitation (the Z2
  !> symmetry) and when the new location is the same point (within 1e-4 in lambda, 1e-3 in
  !> y); otherwise the full-period location stays.
  subroutine refine_branch_points(system, k, options, method, special, n_special)
    type(tank_system), intent(in) :: system
    integer, intent(in) :: k, method, n_special
    type(ode_options), intent(in) :: options
    real(wp), intent(inout) :: special(:, :)
    type(tank_system) :: at
    real(wp) :: y0(4), lambda0, y(4), lambda, y_end(4), monodromy(4, 4), max_x1
    integer :: j, st
    character(len=message_len) :: msg
    ! y -> -y, tau -> tau + k T/2 is a symmetry for odd k under X = A sin(rho tau) only
    if (system%model%excitation%kind /= EXCITATION_HARMONIC .or. mod(k, 2) == 0) return
    do j = 1, n_special
      if (nint(special(1, j)) /= SPECIAL_BRANCH_POINT) cycle
      lambda0 = special(2, j)
      y0 = special(3:6, j)
      call locate_symmetry_breaking(system, y0, lambda0, 1.0e-6_wp*max(1.0_wp, abs(lambda0)), &
                                    k, options, method, y, lambda, st, msg)
      if (st /= SD_OK) cycle
      if (abs(lambda - lambda0) > 1.0e-4_wp*max(1.0_wp, abs(lambda0)) .or. &
          maxval(abs(y - y0)) > 1.0e-3_wp*max(1.0_wp, maxval(abs(y0)))) cycle
      at = system
      call at%set_parameter(lambda)
      call monodromy_matrix(at, y, k, options, method, y_end, monodromy, st, msg, &
                            max_abs_y1=max_x1)
      if (st /= SD_OK) cycle
      special(2:7, j) = [lambda, y, max_x1]
    end do
  end subroutine refine_branch_points

  !> A start state y_start (at forcing phase 0) for the shooting of a periodic orbit of model,
  !> by name: 'simulation', the steady state reached from rest (steady_state with
  !> max_transient_periods = 5000, the other &steady defaults); 'slow_flow', the 3:1 slow-flow
  !> steady state nearest to rho on rho (1 -+ 1e-3), stable ones first (|rho_k - rho| + 1e3
  !> for an unstable one), mapped to the full state by eq (42), (45) and x = P u (eq 34):
  !> u1 = Re(B1 e^{i rho tau}), u2 = Re(B2 e^{3 i rho tau}) at tau = 0.
  subroutine periodic_start_state(model, start, options, method, y_start, status, message)
    type(model_t), intent(in) :: model
    character(len=*), intent(in) :: start
    type(ode_options), intent(in) :: options
    integer, intent(in) :: method
    real(wp), intent(out) :: y_start(4)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(steady_options) :: steady
    type(ode_stats) :: stats
    real(wp) :: summary(SUMMARY_SIZE), p(2, 2), p_inv(2, 2), rho, u(2), du(2), x(2), dx(2)
    real(wp), allocatable :: poincare(:, :), table(:, :), special(:, :), distance(:)
    integer :: n_points, n_special, k
    logical :: complete

    y_start = 0
    select case (trim(start))
    case ('simulation')
      steady%max_transient_periods = start_transient_periods
      allocate (poincare(4, max(steady%window_periods, 1)))
      call steady_state(model, y_start, options, method, steady, summary, poincare, y_start, &
                        stats, status, message)
      if (status /= SD_OK) message = 'start (steady state): '//trim(message)
    case ('slow_flow')
      rho = model%excitation%rho
      allocate (table(POINT_ROWS, start_points), special(SPECIAL_ROWS, start_specials))
      call frequency_response(model, .true., PARAMETER_RHO, rho*(1 - start_band), &
                              rho*(1 + start_band), response_options(), table, n_points, &
                              special, n_special, complete, status, message)
      if (status == SD_OK .and. n_points == 0) then
        status = SD_NOT_CONVERGED
        message = 'no slow-flow steady state was found near rho = '//num2str(rho)
      end if
      if (status /= SD_OK) then
        message = 'start (frequency response): '//trim(message)
        return
      end if
      distance = abs(table(POINT_RHO, 1:n_points) - rho) + &
                 1.0e3_wp*merge(1.0_wp, 0.0_wp, table(POINT_STABLE, 1:n_points) == 0)
      k = minloc(distance, 1)
      call modal_matrix(model, p, p_inv, status, message)
      if (status /= SD_OK) return
      ! B1 = table(POINT_X:POINT_X + 1, k), B2 = table(POINT_X + 2:POINT_X + 3, k) (re, im)
      u = [table(POINT_X, k), table(POINT_X + 2, k)]
      du = [-rho*table(POINT_X + 1, k), -3*rho*table(POINT_X + 3, k)]
      x = matmul(p, u)
      dx = matmul(p, du)
      y_start = [x(1), dx(1), x(2), dx(2)]
    case default
      status = SD_BAD_INPUT
      message = "start = '"//trim(start)//"' is not known; allowed: simulation, slow_flow"
    end select
  end subroutine periodic_start_state

  !> The periodic response over [lambda_min, lambda_max] started from the steady state reached
  !> from y0 at lambda_min (steady settings), refined by shooting (period T).
  subroutine periodic_response_from_rest(model, parameter, y0, lambda_min, lambda_max, steady, &
                                         continuation, options, method, points, multipliers, &
                                         n_points, special, n_special, complete, status, message)
    type(model_t), intent(in) :: model
    integer, intent(in) :: parameter, method
    real(wp), intent(in) :: y0(4), lambda_min, lambda_max
    type(steady_options), intent(in) :: steady
    type(continuation_options), intent(in) :: continuation
    type(ode_options), intent(in) :: options
    real(wp), intent(out) :: points(:, :), multipliers(:, :), special(:, :)
    integer, intent(out) :: n_points, n_special, status
    logical, intent(out) :: complete
    character(len=message_len), intent(out) :: message
    type(tank_system) :: system
    real(wp) :: y_orbit(4)

    n_points = 0
    n_special = 0
    complete = .false.
    call orbit_from_rest(model, parameter, y0, lambda_min, steady, options, method, &
                         system%model, y_orbit, status, message)
    if (status /= SD_OK) return
    system%varied = parameter
    call periodic_branch(system, y_orbit, lambda_min, lambda_max, continuation, options, &
                         method, points, multipliers, n_points, special, n_special, complete, &
                         status, message)
    call refine_branch_points(system, 1, options, method, special, n_special)
  end subroutine periodic_response_from_rest

  !> The start of a branch of periodic responses from rest: the model with the varied parameter
  !> (PARAMETER_RHO, PARAMETER_A) set to lambda (start), and on it the steady state reached
  !> from y0 (steady settings) refined by shooting (period T) to the orbit through y_orbit.
  subroutine orbit_from_rest(model, parameter, y0, lambda, steady, options, method, start, &
                             y_orbit, status, message)
    type(model_t), intent(in) :: model
    integer, intent(in) :: parameter, method
    real(wp), intent(in) :: y0(4), lambda
    type(steady_options), intent(in) :: steady
    type(ode_options), intent(in) :: options
    type(model_t), intent(out) :: start
    real(wp), intent(out) :: y_orbit(4)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(tank_system) :: system
    real(wp) :: summary(SUMMARY_SIZE), y_start(4), monodromy(4, 4), re(4), im(4), max_x1
    real(wp), allocatable :: poincare(:, :)
    type(ode_stats) :: stats
    integer :: iterations

    y_orbit = 0
    system%model = model
    system%varied = parameter
    call system%set_parameter(lambda)
    start = system%model
    allocate (poincare(4, steady%window_periods))
    call steady_state(system%model, y0, options, method, steady, summary, poincare, y_start, &
                      stats, status, message)
    if (status /= SD_OK) then
      message = 'start (steady state): '//trim(message)
      return
    end if
    call periodic_orbit(system%model, y_start, 1, options, method, newton_tol_default, &
                        max_iter_default, y_orbit, monodromy, re, im, iterations, max_x1, &
                        status, message)
    if (status /= SD_OK) message = 'start (shooting): '//trim(message)
  end subroutine orbit_from_rest

  !> The rules of the Lyapunov settings (those of largest_lyapunov, checked before allocating).
  pure subroutine check_lyapunov(options, status, message)
    type(lyapunov_options), intent(in) :: options
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    if (status /= SD_OK) return
    call check_lyapunov_counts(options%transient_periods, options%n_periods, &
                               options%renormalise_every, status, message)
    if (status /= SD_OK) return
    if (options%average < 1 .or. options%average > size(average_names)) then
      status = SD_BAD_INPUT
      message = 'average = '//num2str(options%average)//' is out of range: it must lie in '// &
                '[1, '//num2str(size(average_names))//']'
    end if
  end subroutine check_lyapunov

  !> Largest Lyapunov exponent per unit tau from y0, with its running estimates (history);
  !> average: largest_lyapunov's.
  subroutine lyapunov_exponent(model, y0, transient_periods, n_periods, renormalise_every, &
                               options, method, exponent, history, status, message, average)
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: y0(4)
    integer, intent(in) :: transient_periods, n_periods, renormalise_every, method
    integer, intent(in), optional :: average
    type(ode_options), intent(in) :: options
    real(wp), intent(out) :: exponent, history(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(tank_system) :: system
    system%model = model
    call largest_lyapunov(system, y0, transient_periods, n_periods, renormalise_every, options, &
                          method, exponent, history, status, message, average)
  end subroutine lyapunov_exponent
end module sloshdyn_periodic_response
