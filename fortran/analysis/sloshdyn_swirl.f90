!> Swirl: the stability of planar periodic responses to motion out of their plane (issue 26).
!>
!> The plane of the ground motion is invariant for the spatial model (sloshdyn_spatial): along a
!> planar orbit the spatial Jacobian is block diagonal, in-plane (x1, x2) and out-of-plane
!> (y1, y2), so the spatial monodromy matrix is too, and its out-of-plane block (rows and
!> columns 5-8) carries the four out-of-plane Floquet multipliers nu. A planar response with
!> max|nu| > 1 is unstable to swirl: an out-of-plane perturbation grows and the liquid leaves the
!> plane (rotary sloshing; Miles 1962, 1984). The swirl band is where this holds along a branch
!> of planar responses; its edges are the bifurcations of the planar orbit out of its plane,
!> where a multiplier nu passes through +1 (the symmetry-breaking pitchfork onto the swirling
!> orbits, det(M_b - I) = 0, M_b the out-of-plane block), through -1 (swirl of period 2 k T,
!> det(M_b + I) = 0), or a complex pair crosses the unit circle (Neimark-Sacker). The first two
!> tests hold in the conservative limit too (zeta = gamma = delta = 0, beta any: the
!> monodromy is symplectic, its multipliers in reciprocal pairs on the unit circle while
!> stable), where max|nu| - 1 is 0 on the whole stable side and the complex pairs' test
!> vanishes identically: that one is skipped then (and the planar branch's too).
!>
!> Layouts (sloshdyn_tables): 'swirl_branch' points(:, j) = [lambda, y0(1:4), max|x1|,
!> planar_stable (1/0), max|nu|, Re nu(1:4), Im nu(1:4)]; 'swirl_edges' edges(:, j) = [lambda,
!> y0(1:4), max|x1|, refined (1/0), kind (SPECIAL_BRANCH_POINT: nu = +1,
!> SPECIAL_PERIOD_DOUBLING: nu = -1, SPECIAL_NEIMARK_SACKER: a complex pair)].
!>
!> The criticality of an edge (edge_criticality, issue 41): the cubic coefficient c of the
!> spatial stroboscopic map on its centre manifold at the edge (sloshdyn_map_normal_form: the
!> Z2-symmetric pitchfork at nu = +1, the flip at nu = -1). At a pitchfork c < 0: the swirling
!> orbits are born stable where the planar orbit is unstable (a gentle onset of swirl,
!> supercritical); c > 0: born unstable where it is stable, and entering the band the motion
!> jumps to swirl (subcritical, hysteretic). At a flip the signs are the other way round.
module sloshdyn_swirl
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT
  use sloshdyn_text, only: num2str
  use sloshdyn_lapack, only: eigenvalues
  use sloshdyn_ode, only: ode_options, ode_stats, linear_observation, peak_tracker
  use sloshdyn_integrator, only: integrate
  use sloshdyn_roots, only: bracketed_function, brent_zero
  use sloshdyn_continuation, only: continuation_options
  use sloshdyn_map_normal_form, only: cubic_coefficient
  use sloshdyn_shooting, only: monodromy_matrix, shooting_newton, periodic_branch, &
                               samples_per_period, kind_test_value, complex_pair_count, &
                               volume_preserving
  use sloshdyn_tables, only: SWIRL_BRANCH_ROWS, SWIRL_EDGE_ROWS, PERIODIC_POINT_ROWS, &
                             PERIODIC_MULTIPLIER_ROWS, PERIODIC_SPECIAL_ROWS, &
                             SPECIAL_BRANCH_POINT, SPECIAL_PERIOD_DOUBLING, SPECIAL_NEIMARK_SACKER
  use sloshdyn_model, only: model_t
  use sloshdyn_system, only: tank_system
  use sloshdyn_spatial, only: spatial_model_t, spatial_model, spatial_invariants
  use sloshdyn_spatial_system, only: spatial_tank_system
  implicit none
  private
  public :: out_of_plane_multipliers, swirl_branch, swirl_orbit, orbit_measures, edge_test, &
            edge_criticality, stability_margin

  !> Newton shooting of the planar orbit at an edge candidate
  real(wp), parameter :: newton_tol = 1.0e-10_wp
  integer, parameter :: newton_iterations = 20
  !> the edge tests, in the order they are tried between two branch points
  integer, parameter :: edge_kinds(3) = [SPECIAL_BRANCH_POINT, SPECIAL_PERIOD_DOUBLING, &
                                         SPECIAL_NEIMARK_SACKER]
  !> max|nu| beyond 1 + this: unstable out of the plane (undamped, a pair about to collide on
  !> the unit circle has moduli 1 only to about the square root of the integration error)
  real(wp), parameter :: stability_margin = 1.0e-6_wp

  !> The edge test of kind `kind` (sloshdyn_shooting's kind_test_value: det(M_b - I),
  !> det(M_b + I), the complex pairs' moduli) at lambda, on the planar orbit found by shooting
  !> from a guess interpolated linearly in lambda between two branch points (sloshdyn_roots'
  !> brent_zero).
  type, extends(bracketed_function) :: swirl_margin
    type(tank_system) :: planar
    real(wp) :: lambda(2) = 0, y0(4, 2) = 0
    integer :: k = 1, method = 0, kind = SPECIAL_BRANCH_POINT
    type(ode_options) :: options
    real(wp) :: y_orbit(4) = 0, max_x1 = 0
  contains
    procedure :: value => swirl_margin_value
  end type swirl_margin

contains

  !> The out-of-plane Floquet multipliers nu (re, im) of the planar orbit of period k T through
  !> y_orbit (at tau = 0) of the planar model: the eigenvalues of the out-of-plane block of the
  !> spatial monodromy matrix from (y_orbit, 0, 0, 0, 0).
  subroutine out_of_plane_multipliers(model, y_orbit, k, options, method, re, im, status, &
                                      message)
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: y_orbit(4)
    integer, intent(in) :: k, method
    type(ode_options), intent(in) :: options
    real(wp), intent(out) :: re(4), im(4)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(spatial_tank_system) :: system
    real(wp) :: y_end(8), monodromy(8, 8)
    re = ieee_value(1.0_wp, ieee_quiet_nan)
    im = re
    call spatial_model(model, 0.0_wp, 0.0_wp, system%model, status, message)
    if (status /= SD_OK) return
    call monodromy_matrix(system, [y_orbit, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], k, options, method, &
                          y_end, monodromy, status, message)
    if (status /= SD_OK) then
      message = 'out-of-plane multipliers: '//trim(message)
      return
    end if
    call eigenvalues(monodromy(5:8, 5:8), re, im, status, message)
    if (status /= SD_OK) message = 'out-of-plane multipliers: '//trim(message)
  end subroutine out_of_plane_multipliers

  !> The branch of planar orbits of period k T through y0 (at the model's excitation), continued
  !> in rho or A (parameter = PARAMETER_RHO, PARAMETER_A) over [lambda_min, lambda_max]
  !> (sloshdyn_shooting's periodic_branch), the out-of-plane multipliers at each of its points,
  !> and the edges of the swirl band between consecutive points where a test of the module
  !> header changes sign (det(M_b - I), det(M_b + I), and, unless conservative, the complex
  !> pairs' moduli at an equal number of pairs), located by Brent's method on the planar orbit
  !> found by shooting (refined = 1), or, where that shooting fails (a fold of the branch
  !> between the points), interpolated linearly (refined = 0); where max|nu| crosses
  !> 1 + stability_margin with no test changing sign (a Krein collision of a conservative
  !> system) an interpolated Neimark-Sacker edge. points(SWIRL_BRANCH_ROWS,
  !> >= continuation%max_points), edges(SWIRL_EDGE_ROWS, any): layouts in the module header.
  !> complete: the planar branch reached lambda_min or lambda_max (or closed) and every edge
  !> found was stored. conservative: the in-plane monodromy preserves volume at every point
  !> (sloshdyn_shooting's volume_preserving: no damping), so the Neimark-Sacker tests, in the
  !> plane and out of it, were skipped.
  subroutine swirl_branch(model, parameter, y0, k, lambda_min, lambda_max, continuation, &
                          options, method, points, n_points, edges, n_edges, complete, &
                          conservative, status, message)
    type(model_t), intent(in) :: model
    integer, intent(in) :: parameter, k, method
    real(wp), intent(in) :: y0(4), lambda_min, lambda_max
    type(continuation_options), intent(in) :: continuation
    type(ode_options), intent(in) :: options
    real(wp), intent(out) :: points(:, :), edges(:, :)
    integer, intent(out) :: n_points, n_edges, status
    logical, intent(out) :: complete, conservative
    character(len=message_len), intent(out) :: message
    type(tank_system) :: planar
    type(swirl_margin) :: margin
    real(wp), allocatable :: branch(:, :), multipliers(:, :), special(:, :)
    real(wp) :: re(4), im(4), g_ends(2)
    integer :: i, j, kind, n_special, st
    logical :: found, full
    character(len=message_len) :: msg

    points = ieee_value(1.0_wp, ieee_quiet_nan)
    edges = points(1, 1)
    n_points = 0
    n_edges = 0
    complete = .false.
    conservative = .false.
    full = .false.
    if (size(points, 1) /= SWIRL_BRANCH_ROWS .or. size(edges, 1) /= SWIRL_EDGE_ROWS .or. &
        size(points, 2) < continuation%max_points) then
      status = SD_BAD_INPUT
      message = 'points must be '//num2str(SWIRL_BRANCH_ROWS)//' x max_points and edges '// &
                num2str(SWIRL_EDGE_ROWS)//' x any'
      return
    end if
    planar%model = model
    planar%varied = parameter
    allocate (branch(PERIODIC_POINT_ROWS, max(continuation%max_points, 1)), &
              multipliers(PERIODIC_MULTIPLIER_ROWS, max(continuation%max_points, 1)), &
              special(PERIODIC_SPECIAL_ROWS, 4*max(continuation%max_points, 1)))
    call periodic_branch(planar, y0, lambda_min, lambda_max, continuation, options, method, &
                         branch, multipliers, n_points, special, n_special, complete, status, &
                         message, k)
    if (n_points == 0) return
    st = status
    msg = message
    do j = 1, n_points
      call planar%set_parameter(branch(1, j))
      call out_of_plane_multipliers(planar%model, branch(2:5, j), k, options, method, re, im, &
                                    status, message)
      if (status /= SD_OK) then
        n_points = j - 1
        message = 'at lambda = '//num2str(branch(1, j))//': '//trim(message)
        complete = .false.
        return
      end if
      points(1:7, j) = branch(1:7, j)
      points(8, j) = maxval(hypot(re, im))
      points(9:12, j) = re
      points(13:16, j) = im
    end do

    ! the Neimark-Sacker tests need damping: a conservative system's stable multipliers sit on
    ! the unit circle, where the complex pairs' test vanishes identically
    conservative = all([(volume_preserving(multipliers(1:4, j), multipliers(5:8, j)), &
                         j = 1, n_points)])
    margin%planar = planar
    margin%k = k
    margin%method = method
    margin%options = options
    do j = 1, n_points - 1
      found = .false.
      do i = 1, size(edge_kinds)
        kind = edge_kinds(i)
        if (kind == SPECIAL_NEIMARK_SACKER) then
          if (conservative .or. found .or. &
              complex_pair_count(points(9:12, j), points(13:16, j)) /= &
              complex_pair_count(points(9:12, j + 1), points(13:16, j + 1))) cycle
        end if
        g_ends = [kind_test_value(kind, points(9:12, j), points(13:16, j)), &
                  kind_test_value(kind, points(9:12, j + 1), points(13:16, j + 1))]
        if (.not. g_ends(1)*g_ends(2) < 0) cycle
        call add_edge(kind, g_ends, .true.)
        found = .true.
      end do
      ! stability lost or gained out of the plane without a located test (a conservative
      ! system's Krein collision: two pairs on the circle leave it as a complex quadruplet)
      if (.not. found .and. ((points(8, j) > 1 + stability_margin) .neqv. &
                             (points(8, j + 1) > 1 + stability_margin))) &
        call add_edge(SPECIAL_NEIMARK_SACKER, [points(8, j) - 1, points(8, j + 1) - 1], .false.)
      if (full) exit
    end do
    if (full) then
      complete = .false.
      msg = 'more swirl edges than the '//num2str(size(edges, 2))//' columns of edges'
    end if
    status = st
    message = msg

  contains

    !> Store the edge of kind `kind` between points j and j + 1, where its test takes the values
    !> g_ends: interpolated linearly, then, with locate, by Brent's method on the planar orbit
    !> found by shooting (kept interpolated where that fails: a fold between the points).
    subroutine add_edge(kind, g_ends, locate)
      integer, intent(in) :: kind
      real(wp), intent(in) :: g_ends(2)
      logical, intent(in) :: locate
      real(wp) :: s, lambda, g
      if (n_edges == size(edges, 2)) then
        full = .true.
        return
      end if
      n_edges = n_edges + 1
      s = g_ends(1)/(g_ends(1) - g_ends(2))
      edges(1:6, n_edges) = (1 - s)*points(1:6, j) + s*points(1:6, j + 1)
      edges(7, n_edges) = 0
      edges(8, n_edges) = kind
      if (.not. locate .or. points(1, j) == points(1, j + 1)) return
      margin%kind = kind
      margin%lambda = points(1, [j, j + 1])
      margin%y0 = points(2:5, [j, j + 1])
      call brent_zero(margin, points(1, j), points(1, j + 1), g_ends(1), g_ends(2), &
                      1.0e-10_wp*max(1.0_wp, abs(points(1, j))), 0.0_wp, lambda, g, status, &
                      message)
      if (status /= SD_OK) return
      ! the orbit of the last evaluation is at the returned lambda only if it was the last
      call margin%value(lambda, g, status, message)
      if (status == SD_OK) edges(:, n_edges) = [lambda, margin%y_orbit, margin%max_x1, 1.0_wp, &
                                                real(kind, wp)]
    end subroutine add_edge
  end subroutine swirl_branch

  !> A periodic orbit of period k T of the spatial model (its excitation: along x for the swirl
  !> of a planar response, or at any azimuth and ellipticity),
  !> found by Newton shooting on the 8 states (sloshdyn_shooting's shooting_newton) from y0, or
  !> from the state reached from y0 after `transient` k T of integration (transient >= 0): a
  !> swirling orbit from a planar one perturbed out of its plane inside the swirl band. y_orbit
  !> at tau = 0, its multipliers (re, im), Newton's iterations, max|x1| and the swirl amplitude
  !> max|y1| over the orbit, and the angular momentum about the vertical averaged over the
  !> orbit (orbit_measures).
  subroutine swirl_orbit(model, y0, k, transient, options, method, newton_tol, max_iter, &
                         y_orbit, re, im, iterations, max_x1, amplitude, angular_momentum, &
                         status, message)
    type(spatial_model_t), intent(in) :: model
    real(wp), intent(in) :: y0(8), newton_tol
    integer, intent(in) :: k, transient, method, max_iter
    type(ode_options), intent(in) :: options
    real(wp), intent(out) :: y_orbit(8), re(8), im(8), max_x1, amplitude, angular_momentum
    integer, intent(out) :: iterations, status
    character(len=message_len), intent(out) :: message
    type(spatial_tank_system) :: system
    type(ode_stats) :: stats
    real(wp) :: y_start(8), monodromy(8, 8), period
    real(wp), allocatable :: y_out(:, :)

    y_orbit = ieee_value(1.0_wp, ieee_quiet_nan)
    max_x1 = y_orbit(1); amplitude = y_orbit(1); angular_momentum = y_orbit(1)
    iterations = 0
    if (transient < 0) then
      status = SD_BAD_INPUT
      message = 'transient = '//num2str(transient)//' is out of range: it must be >= 0'
      return
    end if
    status = SD_OK
    message = ''
    system%model = model
    period = k*system%period()
    y_start = y0
    if (transient > 0) then
      allocate (y_out(8, 1))
      call integrate(method, system, 0.0_wp, y0, [transient*period], y_out, options, stats, &
                     status, message)
      if (status /= SD_OK) then
        message = 'swirl orbit, transient: '//trim(message)
        return
      end if
      y_start = y_out(:, 1)
      deallocate (y_out)
    end if
    call shooting_newton(system, y_start, k, options, method, newton_tol, max_iter, y_orbit, &
                         monodromy, re, im, iterations, status, message)
    if (status /= SD_OK) then
      message = 'swirl orbit: '//trim(message)
      return
    end if
    call orbit_measures(system, y_orbit, k, options, method, max_x1, amplitude, &
                        angular_momentum, status, message)
  end subroutine swirl_orbit

  !> max|x1| and the swirl amplitude max|y1| over the orbit of period k T through y_orbit of the
  !> spatial system (located on the integrator's continuous extension by sloshdyn_ode's
  !> peak_tracker, as the planar orbits' max|x1|), and the angular momentum about the vertical
  !> averaged over it (sloshdyn_spatial's spatial_invariants; > 0: counter-clockwise seen from
  !> above; the trapezoidal rule on samples_per_period samples per forcing period, spectrally
  !> accurate on a periodic function: 16 times as many change it by 1e-15 relatively).
  subroutine orbit_measures(system, y_orbit, k, options, method, max_x1, amplitude, &
                            angular_momentum, status, message)
    type(spatial_tank_system), intent(in) :: system
    real(wp), intent(in) :: y_orbit(8)
    integer, intent(in) :: k, method
    type(ode_options), intent(in) :: options
    real(wp), intent(out) :: max_x1, amplitude, angular_momentum
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(ode_stats) :: stats
    type(linear_observation) :: tilts
    type(peak_tracker) :: tracker
    real(wp) :: period, energy, l
    real(wp), allocatable :: t_out(:), y_out(:, :)
    integer :: j, n

    period = k*system%period()
    n = k*samples_per_period
    t_out = [(j*period/n, j = 1, n)]
    allocate (y_out(8, n))
    allocate (tilts%c(2, 8))
    tilts%c = 0
    tilts%c(1, 1) = 1
    tilts%c(2, 5) = 1
    tracker%spacing = period/n
    call integrate(method, system, 0.0_wp, y_orbit, t_out, y_out, options, stats, status, &
                   message, tilts, tracker)
    if (status /= SD_OK) then
      message = 'swirl orbit, sampling: '//trim(message)
      max_x1 = ieee_value(1.0_wp, ieee_quiet_nan)
      amplitude = max_x1
      angular_momentum = max_x1
      return
    end if
    max_x1 = tracker%peak(1)
    amplitude = tracker%peak(2)
    angular_momentum = 0
    do j = 1, n
      call spatial_invariants(system%model, y_out(:, j), energy, l)
      angular_momentum = angular_momentum + l/n
    end do
  end subroutine orbit_measures

  subroutine swirl_margin_value(self, x, fx, status, message)
    class(swirl_margin), intent(inout) :: self
    real(wp), intent(in) :: x
    real(wp), intent(out) :: fx
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: s
    s = (x - self%lambda(1))/(self%lambda(2) - self%lambda(1))
    call self%planar%set_parameter(x)
    call edge_test(self%planar, self%kind, (1 - s)*self%y0(:, 1) + s*self%y0(:, 2), self%k, &
                   self%options, self%method, newton_tol, newton_iterations, self%y_orbit, &
                   self%max_x1, fx, status, message)
  end subroutine swirl_margin_value

  !> The edge test of kind `kind` (kind_test_value of the out-of-plane multipliers: det(M_b - I),
  !> det(M_b + I), the complex pairs' moduli) on the planar orbit of period k T of `planar`
  !> found by Newton shooting (to newton_tol, at most max_iter shots) from the guess; y_orbit
  !> and its max|x1|. g is NaN when the shooting or the multipliers fail (status says why).
  subroutine edge_test(planar, kind, guess, k, options, method, newton_tol, max_iter, y_orbit, &
                       max_x1, g, status, message)
    type(tank_system), intent(in) :: planar
    integer, intent(in) :: kind, k, method, max_iter
    real(wp), intent(in) :: guess(4), newton_tol
    type(ode_options), intent(in) :: options
    real(wp), intent(out) :: y_orbit(4), max_x1, g
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: monodromy(4, 4), re(4), im(4)
    integer :: iterations
    g = ieee_value(1.0_wp, ieee_quiet_nan)
    call shooting_newton(planar, guess, k, options, method, newton_tol, max_iter, y_orbit, &
                         monodromy, re, im, iterations, status, message, max_x1)
    if (status /= SD_OK) return
    call out_of_plane_multipliers(planar%model, y_orbit, k, options, method, re, im, status, &
                                  message)
    if (status == SD_OK) g = kind_test_value(kind, re, im)
  end subroutine edge_test

  !> The criticality c (module header) of the swirl edge of kind SPECIAL_BRANCH_POINT (nu = +1)
  !> or SPECIAL_PERIOD_DOUBLING (nu = -1) through the planar orbit y_orbit (tau = 0, period
  !> k T) of the planar model at the edge, from the spatial monodromy at (y_orbit, 0, 0, 0, 0),
  !> with the critical multiplier nu, the size of c's terms and (optional) the unit critical
  !> eigenvector q (8 states, out of the plane).
  subroutine edge_criticality(model, kind, y_orbit, k, options, method, c, nu, size_of_terms, &
                              status, message, q)
    type(model_t), intent(in) :: model
    integer, intent(in) :: kind, k, method
    real(wp), intent(in) :: y_orbit(4)
    type(ode_options), intent(in) :: options
    real(wp), intent(out) :: c, nu, size_of_terms
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), intent(out), optional :: q(8)
    type(spatial_tank_system) :: system
    real(wp) :: y(8), vector(8)
    c = ieee_value(1.0_wp, ieee_quiet_nan)
    nu = c
    size_of_terms = c
    if (present(q)) q = c
    if (kind /= SPECIAL_BRANCH_POINT .and. kind /= SPECIAL_PERIOD_DOUBLING) then
      status = SD_BAD_INPUT
      message = 'kind = '//num2str(kind)//': the criticality is of a branch_point or a '// &
                'period_doubling edge'
      return
    end if
    call spatial_model(model, 0.0_wp, 0.0_wp, system%model, status, message)
    if (status /= SD_OK) return
    y = [y_orbit, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp]
    ! the pitchfork at nu = +1, the flip at -1
    call cubic_coefficient(system, y, k, options, method, &
                           merge(1, -1, kind == SPECIAL_BRANCH_POINT), c, vector, nu, status, &
                           message, size_of_terms)
    if (status /= SD_OK) message = 'the swirl edge''s criticality: '//trim(message)
    if (present(q)) q = vector
  end subroutine edge_criticality
end module sloshdyn_swirl
