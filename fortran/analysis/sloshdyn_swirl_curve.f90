!> The swirl boundary in (rho, A) as one continued curve (issue 41, item 4): a swirl edge of kind
!> SPECIAL_BRANCH_POINT (an out-of-plane multiplier nu of the planar orbit at +1) or
!> SPECIAL_PERIOD_DOUBLING (at -1) continued in (rho, A) on g(rho, A) = det(M_b -+ I) = 0
!> (sloshdyn_swirl's edge_test: M_b the out-of-plane block of the planar orbit's monodromy, rods
!> included, the orbit found by Newton shooting from the last one found). The continuation is
!> sloshdyn_continuation's pseudo-arclength in x = rho - rho_mid (rho_mid the middle of rho's
!> range, so that the range is |x| <= x_max) and lambda = A/A_0 (A_0 the A of the edge), x
!> weighted in the arclength (x_scale) so that the box is a square of side 1 in it, both
!> ways from the edge until the curve leaves the box. g's gradient is by forward differences
!> (step 1e-7), and the corrector is quasi-Newton from the last tangent's gradient, updated by
!> Broyden's formula (newton_options%reuse_jacobian): a step costs its corrector's evaluations
!> of g and three for the new tangent. The folds of the curve in A (locate_fold: the tangent's A-component through 0) are
!> its codimension-2 points where the band opens or closes: with damping the band exists only
!> above a least A, the closing point. The curve's points at given A are found by Newton in rho
!> at that A (newton_solve) from the points on either side.
!>
!> Along the curve, the edge's criticality c (sloshdyn_swirl's edge_criticality: the cubic
!> coefficient of the spatial stroboscopic map on its centre manifold, Kuznetsov, Elements of
!> Applied Bifurcation Theory, 3rd ed. 2004, sec 5.4 and 8.7) at every point; where it changes
!> sign between two points, its zero located by Brent's method along the arclength
!> (sloshdyn_continuation's locate_zero_on_branch) is the curve's other codimension-2 point, a
!> degenerate pitchfork (at a branch_point edge; a degenerate flip at a period_doubling one):
!> on one side the onset of swirl is supercritical (c < 0 at a pitchfork: stable swirling
!> orbits born inside the band, a gentle onset), on the other subcritical (c > 0: unstable ones
!> born outside it, and entering the band the motion jumps to swirl, with hysteresis).
!>
!> Layouts (sloshdyn_tables): 'swirl_boundary_curve' points(:, j) = [rho, A, y0(1:4), max|x1|,
!> c] (the planar orbit at tau = 0) in arclength order; 'swirl_curve_folds' folds(:, j) = [the
!> same, closing (1: a least A of the band, 0: a greatest A)]; 'swirl_curve_degenerate'
!> degenerate(:, j) = [the same as points, c = 0 to the location's accuracy].
module sloshdyn_swirl_curve
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, SD_NOT_CONVERGED, check_real
  use sloshdyn_text, only: num2str
  use sloshdyn_ode, only: ode_options
  use sloshdyn_continuation, only: parametrised_system, continuation_options, newton_options, &
                                   continue_branch, locate_fold, newton_solve, STOP_MAX_POINTS, &
                                   STOP_CLOSED, branch_test, locate_zero_on_branch
  use sloshdyn_shooting, only: shooting_newton
  use sloshdyn_tables, only: SWIRL_CURVE_ROWS, SWIRL_CURVE_FOLD_ROWS, SPECIAL_BRANCH_POINT, &
                             SPECIAL_PERIOD_DOUBLING, special_kind_name
  use sloshdyn_model, only: model_t
  use sloshdyn_system, only: tank_system
  use sloshdyn_swirl, only: edge_test, edge_criticality
  implicit none
  private
  public :: swirl_boundary_curve, curve_settings

  !> Settings of the curve.
  type :: curve_settings
    real(wp) :: ds = 0.1_wp            !< largest step in (rho, A/A_0), > 0; the first is ds/4
    integer :: max_points = 400        !< points each way from the edge (it included), >= 2
    real(wp) :: tol = 1.0e-12_wp       !< the corrector's step tolerance (relative), > 0
    real(wp) :: newton_tol = 1.0e-10_wp  !< the planar orbit's shooting: tolerance ...
    integer :: max_iter = 30           !< ... and shots
  end type curve_settings

  !> forward-difference step of g's gradient, in x and lambda
  real(wp), parameter :: h = 1.0e-7_wp
  !> the corrector's iterations at most, and the smallest step
  integer, parameter :: corrector_iterations = 12
  real(wp), parameter :: smallest_step = 1.0e-9_wp

  !> The planar orbit last found: the shooting's guess at the next (rho, A).
  type :: orbit_memory
    real(wp) :: y(4) = 0
  end type orbit_memory

  !> F(x, lambda) = g(rho_mid + x, A_0 lambda), n = 1.
  type, extends(parametrised_system) :: edge_function
    type(tank_system) :: planar
    integer :: kind = SPECIAL_BRANCH_POINT, k = 1, method = 0, max_iter = 30
    type(ode_options) :: options
    real(wp) :: newton_tol = 1.0e-10_wp, rho_mid = 0, scale = 1
    type(orbit_memory), pointer :: last => null()
  contains
    procedure :: evaluate => edge_evaluate
    procedure :: residual_only => edge_residual
    procedure :: at => edge_at
  end type edge_function

  !> The criticality c along the curve (locate_zero_on_branch's test): at z, on the planar
  !> orbit shot from the last one.
  type, extends(branch_test) :: criticality_test
    type(edge_function) :: f
  contains
    procedure :: value => criticality_value
  end type criticality_test

contains

  !> The swirl edge of kind `kind` at rho_edge through the planar orbit y_edge (x1, x1', x2, x2'
  !> at tau = 0, period k T) of model (at the edge's A, A_0 = model's A > 0) continued as a curve
  !> in rho_range x A_range (module header). points(SWIRL_CURVE_ROWS, >= 2 max_points - 1),
  !> at(SWIRL_CURVE_ROWS, any): the curve's points at each A of A_values, where it crosses it;
  !> folds(SWIRL_CURVE_FOLD_ROWS, any), degenerate(SWIRL_CURVE_ROWS, any): the zeros of c.
  !> complete: both ways left the box (or closed) and every point found was stored; otherwise
  !> status = SD_NOT_CONVERGED and message says why, the points so far kept.
  subroutine swirl_boundary_curve(model, kind, rho_edge, y_edge, k, rho_range, A_range, &
                                  A_values, settings, options, method, points, n_points, at, &
                                  n_at, folds, n_folds, degenerate, n_degenerate, complete, &
                                  status, message)
    type(model_t), intent(in) :: model
    integer, intent(in) :: kind, k, method
    real(wp), intent(in) :: rho_edge, y_edge(4), rho_range(2), A_range(2), A_values(:)
    type(curve_settings), intent(in) :: settings
    type(ode_options), intent(in) :: options
    real(wp), intent(out) :: points(:, :), at(:, :), folds(:, :), degenerate(:, :)
    integer, intent(out) :: n_points, n_at, n_folds, n_degenerate, status
    logical, intent(out) :: complete
    character(len=message_len), intent(out) :: message
    type(edge_function) :: f
    type(orbit_memory), target :: memory
    type(continuation_options) :: steps
    type(criticality_test) :: criticality
    real(wp), allocatable :: z(:, :, :), t(:, :, :), arclength(:), orbits(:, :)
    real(wp) :: z_fold(2), x(1), a, rho_guess, w(2)
    integer :: n(2), stop_reason, half, j, i, i_next, m, iterations, st
    character(len=message_len) :: msg, why

    points = ieee_value(1.0_wp, ieee_quiet_nan)
    at = points(1, 1)
    folds = points(1, 1)
    degenerate = points(1, 1)
    n_degenerate = 0
    n_points = 0
    n_at = 0
    n_folds = 0
    complete = .false.
    call check_input(status, message)
    if (status /= SD_OK) return

    f%planar%model = model
    f%kind = kind
    f%k = k
    f%method = method
    f%options = options
    f%newton_tol = settings%newton_tol
    f%max_iter = settings%max_iter
    f%rho_mid = (rho_range(1) + rho_range(2))/2
    f%scale = model%excitation%A
    f%last => memory
    steps%ds = settings%ds/4
    steps%ds_max = settings%ds
    steps%ds_min = min(smallest_step, steps%ds)
    steps%max_points = settings%max_points
    steps%lambda_min = A_range(1)/f%scale
    steps%lambda_max = A_range(2)/f%scale
    steps%x_max = (rho_range(2) - rho_range(1))/2
    steps%newton = newton_options(x_tol=settings%tol, f_tol=huge(1.0_wp), &
                                  max_iter=corrector_iterations, reuse_jacobian=.true.)
    ! rho weighted in the arclength so that the box is a square: near the band's closing point
    ! rho moves by 1e-4 while A doubles, and unweighted the fold is too sharp to pass
    steps%x_scale = (steps%lambda_max - steps%lambda_min)/(rho_range(2) - rho_range(1))

    ! both ways from the edge (one, if the first closes the curve)
    m = settings%max_points
    allocate (z(2, m, 2), t(2, m, 2), arclength(m))
    n = 0
    why = ''
    do half = 1, 2
      memory%y = y_edge
      steps%direction = merge(-1, 1, half == 1)
      call continue_branch(f, [rho_edge - f%rho_mid], 1.0_wp, steps, z(:, :, half), &
                           t(:, :, half), arclength, n(half), stop_reason, st, msg)
      if (st /= SD_OK) then
        call note('lost the curve at rho = '//num2str(f%rho_mid + z(1, max(n(half), 1), half))// &
                  ', A = '//num2str(f%scale*z(2, max(n(half), 1), half))//': '//trim(msg))
      else if (stop_reason == STOP_MAX_POINTS) then
        call note('max_points = '//num2str(m)//' reached before leaving the box')
      end if
      if (n(half) == 0) then
        status = st
        message = why
        return
      end if
      if (stop_reason == STOP_CLOSED) exit
    end do

    ! the points in arclength order (the first half reversed), with their planar orbits found
    ! outwards from the edge
    n_points = n(1) + max(n(2) - 1, 0)
    do j = 1, n(1)
      points(1:2, j) = z(:, n(1) + 1 - j, 1)
    end do
    do j = 2, n(2)
      points(1:2, n(1) + j - 1) = z(:, j, 2)
    end do
    allocate (orbits(4, n_points))
    memory%y = y_edge
    do j = n(1), 1, -1
      call store_orbit(j)
      if (status /= SD_OK) return
    end do
    memory%y = orbits(:, n(1))
    do j = n(1) + 1, n_points
      call store_orbit(j)
      if (status /= SD_OK) return
    end do

    ! folds in A, in each half between points whose tangents' A-components differ in sign
    do half = 1, 2
      do j = 1, n(half) - 1
        if (.not. t(2, j, half)*t(2, j + 1, half) < 0) cycle
        i = merge(n(1) + 1 - j, n(1) + j - 1, half == 1)
        memory%y = orbits(:, i)
        call locate_fold(f, z(:, j, half), t(:, j, half), z(:, j + 1, half), t(:, j + 1, half), &
                         z_fold, status, message, steps)
        if (status /= SD_OK) then
          message = 'the fold near rho = '//num2str(f%rho_mid + z(1, j, half))// &
                    ' not located: '//trim(message)
          return
        end if
        if (n_folds == size(folds, 2)) then
          call note('more folds than the '//num2str(size(folds, 2))//' columns of folds')
          exit
        end if
        n_folds = n_folds + 1
        call orbit_row(z_fold, folds(1:SWIRL_CURVE_ROWS, n_folds))
        if (status /= SD_OK) return
        folds(SWIRL_CURVE_FOLD_ROWS, n_folds) = merge(1, 0, t(2, j, half) < 0)
      end do
    end do

    ! the zeros of the criticality c, in each half between points where it differs in sign
    criticality%f = f
    w = [steps%x_scale**2, 1.0_wp]
    do half = 1, 2
      do j = 1, n(half) - 1
        i = merge(n(1) + 1 - j, n(1) + j - 1, half == 1)
        i_next = merge(n(1) - j, n(1) + j, half == 1)
        if (.not. points(SWIRL_CURVE_ROWS, i)*points(SWIRL_CURVE_ROWS, i_next) < 0) cycle
        memory%y = orbits(:, i)
        call locate_zero_on_branch(f, z(:, j, half), t(:, j, half), &
                                   sum(w*t(:, j, half)*(z(:, j + 1, half) - z(:, j, half))), &
                                   criticality, z_fold, status, message, steps)
        if (status /= SD_OK) then
          message = 'the degenerate point near rho = '//num2str(f%rho_mid + z(1, j, half))// &
                    ' not located: '//trim(message)
          return
        end if
        if (n_degenerate == size(degenerate, 2)) then
          call note('more degenerate points than the '//num2str(size(degenerate, 2))// &
                    ' columns of degenerate')
          exit
        end if
        n_degenerate = n_degenerate + 1
        call orbit_row(z_fold, degenerate(:, n_degenerate))
        if (status /= SD_OK) return
      end do
    end do

    ! the points at the A of A_values: Newton in rho at that A between the points around it
    do i = 1, size(A_values)
      a = A_values(i)
      do j = 1, n_points - 1
        if (.not. ((points(2, j) - a/f%scale)*(points(2, j + 1) - a/f%scale) <= 0 .and. &
                   points(2, j) /= a/f%scale)) cycle
        if (n_at == size(at, 2)) then
          call note('more points at the A values than the '//num2str(size(at, 2))// &
                    ' columns of at')
          exit
        end if
        rho_guess = points(1, j) + (points(1, j + 1) - points(1, j))* &
                    (a/f%scale - points(2, j))/(points(2, j + 1) - points(2, j))
        x = rho_guess
        memory%y = orbits(:, j)
        call newton_solve(f, x, a/f%scale, steps%newton, iterations, status, message)
        if (status /= SD_OK) then
          message = 'no point at A = '//num2str(a)//' near rho = '// &
                    num2str(f%rho_mid + rho_guess)//': '//trim(message)
          return
        end if
        n_at = n_at + 1
        call orbit_row([x(1), a/f%scale], at(:, n_at))
        if (status /= SD_OK) return
      end do
    end do

    ! the scaled coordinates of the curve's points to rho, A
    do j = 1, n_points
      points(1:2, j) = [f%rho_mid + points(1, j), f%scale*points(2, j)]
      points(3:6, j) = orbits(:, j)
    end do
    complete = why == ''
    status = merge(SD_OK, SD_NOT_CONVERGED, complete)
    message = why

  contains

    !> Append a reason the curve is incomplete.
    subroutine note(text)
      character(len=*), intent(in) :: text
      if (why == '') then
        why = text
      else
        why = trim(why)//'; '//text
      end if
    end subroutine note

    !> The planar orbit at point j (scaled coordinates in points(1:2, j)) into orbits and
    !> points(7, j), from the memory's guess.
    subroutine store_orbit(j)
      integer, intent(in) :: j
      real(wp) :: row(SWIRL_CURVE_ROWS)
      call orbit_row(points(1:2, j), row)
      orbits(:, j) = row(3:6)
      points(7:8, j) = row(7:8)
    end subroutine store_orbit

    !> The row [rho, A, y0(1:4), max|x1|, c] of the curve's point zs = (x, lambda): the planar
    !> orbit by shooting from the memory's guess, which it then replaces.
    subroutine orbit_row(zs, row)
      real(wp), intent(in) :: zs(2)
      real(wp), intent(out) :: row(SWIRL_CURVE_ROWS)
      call edge_coefficient(f, zs(1), zs(2), row(3:6), row(7), row(8), status, message)
      row(1:2) = [f%rho_mid + zs(1), f%scale*zs(2)]
      if (status /= SD_OK) message = 'the planar orbit at rho = '//num2str(row(1))//', A = '// &
                                     num2str(row(2))//': '//trim(message)
    end subroutine orbit_row

    subroutine check_input(status, message)
      integer, intent(out) :: status
      character(len=message_len), intent(out) :: message
      real(wp), parameter :: big = huge(1.0_wp)
      status = SD_OK
      message = ''
      if (kind /= SPECIAL_BRANCH_POINT .and. kind /= SPECIAL_PERIOD_DOUBLING) then
        status = SD_BAD_INPUT
        message = 'kind = '//special_kind_name(kind)//': the curve follows a branch_point or '// &
                  'a period_doubling edge'
        return
      end if
      call check_real('rho_range(2)', rho_range(2), rho_range(1), big, .true., .false., &
                      'rho_range must be an interval: its end > its start = '// &
                      num2str(rho_range(1)), status, message)
      call check_real('A_range(2)', A_range(2), A_range(1), big, .true., .false., &
                      'A_range must be an interval: its end > its start = '// &
                      num2str(A_range(1)), status, message)
      call check_real('rho_edge', rho_edge, rho_range(1), rho_range(2), .false., .false., &
                      'the edge must lie in rho_range = ['//num2str(rho_range(1))//', '// &
                      num2str(rho_range(2))//']', status, message)
      call check_real('A', model%excitation%A, 0.0_wp, big, .true., .false., &
                      'the edge''s A must be > 0', status, message)
      if (status == SD_OK .and. (model%excitation%A < A_range(1) .or. &
                                 model%excitation%A > A_range(2))) then
        status = SD_BAD_INPUT
        message = 'A_range = ['//num2str(A_range(1))//', '//num2str(A_range(2))// &
                  '] is out of range: it must contain the edge''s A = '// &
                  num2str(model%excitation%A)
      end if
      call check_real('ds', settings%ds, 0.0_wp, big, .true., .false., 'ds must be > 0', &
                      status, message)
      call check_real('tol', settings%tol, 0.0_wp, big, .true., .false., 'tol must be > 0', &
                      status, message)
      if (status /= SD_OK) return
      if (settings%max_points < 2) then
        status = SD_BAD_INPUT
        message = 'max_points = '//num2str(settings%max_points)//' is out of range: it must '// &
                  'be >= 2'
      else if (size(points, 1) /= SWIRL_CURVE_ROWS .or. size(at, 1) /= SWIRL_CURVE_ROWS .or. &
               size(folds, 1) /= SWIRL_CURVE_FOLD_ROWS .or. &
               size(degenerate, 1) /= SWIRL_CURVE_ROWS .or. &
               size(points, 2) < 2*settings%max_points - 1) then
        status = SD_BAD_INPUT
        message = 'points must be '//num2str(SWIRL_CURVE_ROWS)//' x (2 max_points - 1), at '// &
                  'and degenerate '//num2str(SWIRL_CURVE_ROWS)//' x any and folds '// &
                  num2str(SWIRL_CURVE_FOLD_ROWS)//' x any'
      end if
    end subroutine check_input
  end subroutine swirl_boundary_curve

  !> g and its forward-difference gradient; the orbit found at (x, lambda) is remembered.
  subroutine edge_evaluate(self, x, lambda, f, fx, flambda)
    class(edge_function), intent(in) :: self
    real(wp), intent(in) :: x(:), lambda
    real(wp), intent(out) :: f(:), fx(:, :), flambda(:)
    f(1) = edge_value(self, x(1), lambda, .true.)
    fx = ieee_value(1.0_wp, ieee_quiet_nan)
    flambda = fx(1, 1)
    if (f(1) /= f(1)) return
    fx(1, 1) = (edge_value(self, x(1) + h, lambda, .false.) - f(1))/h
    flambda(1) = (edge_value(self, x(1), lambda + h, .false.) - f(1))/h
  end subroutine edge_evaluate

  subroutine edge_residual(self, x, lambda, f)
    class(edge_function), intent(in) :: self
    real(wp), intent(in) :: x(:), lambda
    real(wp), intent(out) :: f(:)
    f(1) = edge_value(self, x(1), lambda, .true.)
  end subroutine edge_residual

  !> g at (x, lambda) on the planar orbit shot from the last one (NaN if the shooting or the
  !> multipliers fail); remember: that orbit becomes the last.
  real(wp) function edge_value(self, x, lambda, remember) result(g)
    class(edge_function), intent(in) :: self
    real(wp), intent(in) :: x, lambda
    logical, intent(in) :: remember
    type(tank_system) :: planar
    real(wp) :: y(4), max_x1
    integer :: status
    character(len=message_len) :: message
    planar = planar_at(self, x, lambda)
    call edge_test(planar, self%kind, self%last%y, self%k, self%options, self%method, &
                   self%newton_tol, self%max_iter, y, max_x1, g, status, message)
    if (status == SD_OK .and. remember) self%last%y = y
  end function edge_value

  !> The planar orbit y (tau = 0) and its max|x1| at (x, lambda), shot from the last one, which
  !> it replaces.
  subroutine edge_at(self, x, lambda, y, max_x1, status, message)
    class(edge_function), intent(in) :: self
    real(wp), intent(in) :: x, lambda
    real(wp), intent(out) :: y(4), max_x1
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(tank_system) :: planar
    real(wp) :: monodromy(4, 4), re(4), im(4)
    integer :: iterations
    planar = planar_at(self, x, lambda)
    call shooting_newton(planar, self%last%y, self%k, self%options, self%method, &
                         self%newton_tol, self%max_iter, y, monodromy, re, im, iterations, &
                         status, message, max_x1)
    if (status == SD_OK) self%last%y = y
  end subroutine edge_at

  !> The planar system at (x, lambda): rho = rho_mid + x, A = A_0 lambda.
  function planar_at(f, x, lambda) result(planar)
    class(edge_function), intent(in) :: f
    real(wp), intent(in) :: x, lambda
    type(tank_system) :: planar
    planar = f%planar
    planar%model%excitation%rho = f%rho_mid + x
    planar%model%excitation%A = f%scale*lambda
  end function planar_at

  !> The planar orbit y, its max|x1| and the edge's criticality c at (x, lambda), the orbit
  !> shot from the last one, which it replaces.
  subroutine edge_coefficient(f, x, lambda, y, max_x1, c, status, message)
    class(edge_function), intent(in) :: f
    real(wp), intent(in) :: x, lambda
    real(wp), intent(out) :: y(4), max_x1, c
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(tank_system) :: planar
    real(wp) :: nu, size_of_terms
    c = ieee_value(1.0_wp, ieee_quiet_nan)
    call f%at(x, lambda, y, max_x1, status, message)
    if (status /= SD_OK) return
    planar = planar_at(f, x, lambda)
    call edge_criticality(planar%model, f%kind, y, f%k, f%options, f%method, c, nu, &
                          size_of_terms, status, message)
  end subroutine edge_coefficient

  !> c at the curve's point z (NaN if the shooting or the coefficient fails).
  function criticality_value(self, z, t) result(g)
    class(criticality_test), intent(in) :: self
    real(wp), intent(in) :: z(:), t(:)
    real(wp) :: g
    real(wp) :: y(4), max_x1
    integer :: status
    character(len=message_len) :: message
    call edge_coefficient(self%f, z(1), z(2), y, max_x1, g, status, message)
  end function criticality_value
end module sloshdyn_swirl_curve
