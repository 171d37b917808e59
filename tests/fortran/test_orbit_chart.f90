!> Maps and periodically forced flows with closed-form bifurcation sets of their fixed points,
!> the independent source of every expected value.
module orbit_test_maps
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, SD_NON_FINITE
  use sloshdyn_shooting, only: periodic_problem
  use sloshdyn_map_bifurcation, only: two_parameter_map, stroboscopic_map
  implicit none
  private
  public :: henon_map, walled_henon, cusp_flip_map, frame_problem, frame_map, FRAME_CUSP, &
            FRAME_LINEAR

  !> The Henon map P(x, y) = (1 - a x^2 + y, b x), p = (a, b) (Kuznetsov, Elements of Applied
  !> Bifurcation Theory, sec 4.8 and exercises): fixed points a x^2 + (1 - b) x - 1 = 0, y = b x;
  !> M = [-2 a x, 1; b, 0], trace -2 a x, det -b. Fold a = -(1 - b)^2/4, x = 2/(1 - b);
  !> period doubling a = 3 (1 - b)^2/4, x = (1 - b)/(2 a); Neimark-Sacker b = -1 (det M = 1)
  !> with kappa = trace = 2 - 2 sqrt(1 + a) on x = (sqrt(1 + a) - 1)/a: 1:1 resonance at
  !> a = -1, 1:4 at a = 0, 1:3 at a = 5/4, 1:2 at a = 3 (all with b = -1), where the fold and
  !> period-doubling curves meet the Neimark-Sacker line.
  type, extends(two_parameter_map) :: henon_map
  contains
    procedure :: map => henon_evaluate
  end type henon_map

  !> The Henon map, undefined beyond a = wall (a map that fails: an incomplete curve).
  type, extends(henon_map) :: walled_henon
    real(wp) :: wall = 2
  contains
    procedure :: map => walled_evaluate
  end type walled_henon

  !> The cusp normal form of maps with a flipping direction (Kuznetsov sec 9.2 and 9.5):
  !> P(x, y) = (x + p1 + p2 x - x^3 + y^2, (x - 1 - c) y), p = (p1, p2). On y = 0 the
  !> multipliers are 1 + p2 - 3 x^2 and x - 1 - c: fold curve (p1, p2) = (-2 x^3, 3 x^2) with
  !> a cusp at p = 0 (x = 0) and a fold-flip at x = c, p = (-2 c^3, 3 c^2); period doubling on
  !> x = c: p1 = c^3 - p2 c.
  type, extends(two_parameter_map) :: cusp_flip_map
    real(wp) :: c = 0.5_wp
  contains
    procedure :: map => cusp_flip_evaluate
  end type cusp_flip_map

  integer, parameter :: FRAME_CUSP = 1, FRAME_LINEAR = 2

  !> y' = omega J y + R(omega t) G(R(omega t)^T y; p), J = [0 -1; 1 0], R the rotation: y = R z
  !> with z' = G(z) autonomous, so the stroboscopic map over T is y0 -> R(omega T) phi_T(y0).
  !>  FRAME_CUSP:   G = (p1 + p2 z1 - z1^3, -z2), T = 2 pi/omega (R(omega T) = I): fixed points
  !>                are the equilibria; fold curve (p1, p2) = (-2 z^3, 3 z^2), cusp at p = 0;
  !>                at an equilibrium z*, lambda = p2 - 3 z*^2, the map's second derivative
  !>                d^2 P1/dz1^2 = (g''/lambda) e^{lambda T} (e^{lambda T} - 1), g'' = -6 z*.
  !>  FRAME_LINEAR: G = (B - omega J) z, B = diag(p1, p2), T = pi/omega: M = -exp(C T),
  !>                C = [p1 omega; -omega p2] at the trivial orbit. Neimark-Sacker on p1 + p2 = 0
  !>                (|p1 - p2| < 2 omega) with kappa = -2 cos(pi s), s = sqrt(1 - (p1/omega)^2);
  !>                1:4 at p1 = omega sqrt(3)/2, 1:3 at omega sqrt(8)/3, 1:2 at p1 = omega;
  !>                period doubling on det C = 0: p1 p2 = -omega^2, through the 1:2 resonance.
  type, extends(periodic_problem) :: frame_problem
    integer :: kind = FRAME_CUSP
    real(wp) :: omega = 1, p(2) = 0
    integer :: varied = 1
  contains
    procedure :: rhs => frame_rhs
    procedure :: jacobian => frame_jacobian
    procedure :: period => frame_period
    procedure :: parameter_derivative => frame_parameter_derivative
    procedure :: set_parameter => frame_set_parameter
    procedure :: parameter => frame_parameter
    procedure :: period_derivative => frame_period_derivative
  end type frame_problem

  !> The stroboscopic map of a frame_problem, by shooting.
  type, extends(stroboscopic_map) :: frame_map
    integer :: kind = FRAME_CUSP
    real(wp) :: omega = 1
  contains
    procedure :: problem => frame_map_problem
  end type frame_map

contains

  subroutine henon_evaluate(self, x, p, px, mx, status, message, mp)
    class(henon_map), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2)
    real(wp), intent(out) :: px(:), mx(:, :)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), intent(out), optional :: mp(:, :)
    status = SD_OK
    message = ''
    px = [1 - p(1)*x(1)**2 + x(2), p(2)*x(1)]
    mx = reshape([-2*p(1)*x(1), p(2), 1.0_wp, 0.0_wp], [2, 2])
    if (present(mp)) mp = reshape([-x(1)**2, 0.0_wp, 0.0_wp, x(1)], [2, 2])
  end subroutine henon_evaluate

  subroutine walled_evaluate(self, x, p, px, mx, status, message, mp)
    class(walled_henon), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2)
    real(wp), intent(out) :: px(:), mx(:, :)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), intent(out), optional :: mp(:, :)
    call henon_evaluate(self, x, p, px, mx, status, message, mp)
    if (p(1) > self%wall) then
      status = SD_NON_FINITE
      message = 'the walled Henon map is undefined beyond a = wall'
    end if
  end subroutine walled_evaluate

  subroutine cusp_flip_evaluate(self, x, p, px, mx, status, message, mp)
    class(cusp_flip_map), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2)
    real(wp), intent(out) :: px(:), mx(:, :)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), intent(out), optional :: mp(:, :)
    status = SD_OK
    message = ''
    px = [x(1) + p(1) + p(2)*x(1) - x(1)**3 + x(2)**2, (x(1) - 1 - self%c)*x(2)]
    mx = reshape([1 + p(2) - 3*x(1)**2, x(2), 2*x(2), x(1) - 1 - self%c], [2, 2])
    if (present(mp)) mp = reshape([1.0_wp, 0.0_wp, x(1), 0.0_wp], [2, 2])
  end subroutine cusp_flip_evaluate

  pure function rotation(angle) result(r)
    real(wp), intent(in) :: angle
    real(wp) :: r(2, 2)
    r = reshape([cos(angle), sin(angle), -sin(angle), cos(angle)], [2, 2])
  end function rotation

  !> G(z), DG(z) and dG/dp (2 x 2) of the frame problem.
  pure subroutine frame_field(self, z, g, dg, gp)
    class(frame_problem), intent(in) :: self
    real(wp), intent(in) :: z(2)
    real(wp), intent(out) :: g(2), dg(2, 2), gp(2, 2)
    if (self%kind == FRAME_CUSP) then
      g = [self%p(1) + self%p(2)*z(1) - z(1)**3, -z(2)]
      dg = reshape([self%p(2) - 3*z(1)**2, 0.0_wp, 0.0_wp, -1.0_wp], [2, 2])
      gp = reshape([1.0_wp, 0.0_wp, z(1), 0.0_wp], [2, 2])
    else
      dg = reshape([self%p(1), -self%omega, self%omega, self%p(2)], [2, 2])
      g = matmul(dg, z)
      gp = reshape([z(1), 0.0_wp, 0.0_wp, z(2)], [2, 2])
    end if
  end subroutine frame_field

  subroutine frame_rhs(self, t, y, dydt)
    class(frame_problem), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: dydt(:)
    real(wp) :: r(2, 2), g(2), dg(2, 2), gp(2, 2)
    r = rotation(self%omega*t)
    call frame_field(self, matmul(transpose(r), y(1:2)), g, dg, gp)
    dydt = self%omega*[-y(2), y(1)] + matmul(r, g)
  end subroutine frame_rhs

  subroutine frame_jacobian(self, t, y, jac)
    class(frame_problem), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: jac(:, :)
    real(wp) :: r(2, 2), g(2), dg(2, 2), gp(2, 2)
    r = rotation(self%omega*t)
    call frame_field(self, matmul(transpose(r), y(1:2)), g, dg, gp)
    jac = matmul(r, matmul(dg, transpose(r))) + &
          self%omega*reshape([0.0_wp, 1.0_wp, -1.0_wp, 0.0_wp], [2, 2])
  end subroutine frame_jacobian

  function frame_period(self) result(value)
    class(frame_problem), intent(in) :: self
    real(wp) :: value
    value = merge(2, 1, self%kind == FRAME_CUSP)*pi/self%omega
  end function frame_period

  subroutine frame_parameter_derivative(self, t, y, df)
    class(frame_problem), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: df(:)
    real(wp) :: r(2, 2), g(2), dg(2, 2), gp(2, 2)
    r = rotation(self%omega*t)
    call frame_field(self, matmul(transpose(r), y(1:2)), g, dg, gp)
    df = matmul(r, gp(:, self%varied))
  end subroutine frame_parameter_derivative

  subroutine frame_set_parameter(self, lambda)
    class(frame_problem), intent(inout) :: self
    real(wp), intent(in) :: lambda
    self%p(self%varied) = lambda
  end subroutine frame_set_parameter

  function frame_parameter(self) result(value)
    class(frame_problem), intent(in) :: self
    real(wp) :: value
    value = self%p(self%varied)
  end function frame_parameter

  function frame_period_derivative(self) result(value)
    class(frame_problem), intent(in) :: self
    real(wp) :: value
    value = 0
  end function frame_period_derivative

  subroutine frame_map_problem(self, p, varied, problem)
    class(frame_map), intent(in) :: self
    real(wp), intent(in) :: p(2)
    integer, intent(in) :: varied
    class(periodic_problem), allocatable, intent(out) :: problem
    allocate (problem, source=frame_problem(kind=self%kind, omega=self%omega, p=p, &
                                            varied=varied))
  end subroutine frame_map_problem
end module orbit_test_maps

!> Fold, period-doubling and Neimark-Sacker curves of fixed points of maps and of periodic
!> orbits: against the closed forms of orbit_test_maps (Henon, a cusp-flip normal form, two
!> rotating-frame flows by shooting) and, for the tank at the parameters of Fig 12, against the
!> one-parameter continuation of periodic orbits (periodic_response) and independent shooting.
program test_orbit_chart
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT
  use sloshdyn_lapack, only: eigenvalues
  use sloshdyn_bifurcation, only: curve_options, bifurcation_curve, curve_crossings, &
                                  correct_to_curve, hopf_curve, codim2_name, curve_end_name, &
                                  CURVE_FOLD, CURVE_PERIOD_DOUBLING, &
                                  CURVE_NEIMARK_SACKER, CODIM2_R1, CODIM2_R2, CODIM2_R3, &
                                  CODIM2_R4, CODIM2_CUSP, CODIM2_FOLD_FLIP, END_BOX, &
                                  END_RESONANCE, END_FAILED, END_X_MAX
  use sloshdyn_map_bifurcation, only: map_fold_curve, period_doubling_curve, &
                                      neimark_sacker_curve
  use orbit_test_maps, only: henon_map, walled_henon, cusp_flip_map, frame_map, FRAME_CUSP, &
                             FRAME_LINEAR
  use sloshdyn_model, only: model_t, model_from_arrays
  use sloshdyn_excitation, only: PARAMETER_RHO, record_excitation
  use sloshdyn_ode, only: ode_options
  use sloshdyn_integrator, only: METHOD_DOP853
  use sloshdyn_continuation, only: continuation_options
  use sloshdyn_periodic_response, only: periodic_orbit, periodic_response
  use sloshdyn_system, only: tank_system
  use sloshdyn_shooting, only: monodromy_matrix
  use sloshdyn_tables, only: SPECIAL_FOLD, SPECIAL_NEIMARK_SACKER, SPECIAL_BRANCH_POINT
  use sloshdyn_orbit_chart, only: tank_orbit_map, orbit_chart_options, make_orbit_map, &
                                  orbit_curve_from_special, orbit_neimark_sacker_curve
  use curve_checks, only: box, report, find_codim2
  use checks, only: check_close, check_true, finish
  implicit none
  !> the continuation steps of the curves traced in a box
  real(wp), parameter :: ds = 0.05_wp, ds_max = 0.1_wp

  integer :: clock_start, clock_rate
  real(wp) :: clock_last = 0

  call system_clock(clock_start, clock_rate)
  call test_henon_neimark_sacker()
  call test_henon_neutral_saddles()
  call test_henon_fold_and_flip()
  call test_cusp_flip()
  call test_incomplete()
  call test_bad_input()
  call timed('textbook maps')
  call test_frame_derivatives()
  call test_frame_cusp()
  call test_frame_linear()
  call timed('rotating frames (shooting)')
  call test_fig12_neimark_sacker()
  call timed('Fig 12 Neimark-Sacker curve and its checks')
  call test_fig12_folds()
  call timed('Fig 12 fold curve and its checks')
  call test_tank_derivatives()
  call test_tank_bad_input()
  call finish()

contains

  !> Check that the curve has exactly one codimension-2 point of the kind, at p_exact (tol)
  !> with the angle theta_exact (tol).
  subroutine check_codim2(label, curve, kind, p_exact, theta_exact, tol)
    character(len=*), intent(in) :: label
    type(bifurcation_curve), intent(in) :: curve
    integer, intent(in) :: kind
    real(wp), intent(in) :: p_exact(2), theta_exact, tol
    integer :: i, count
    count = find_codim2(curve, kind, first=i)
    call check_true(label//': one '//codim2_name(kind)//' point', count == 1)
    if (i == 0) return
    print '(a, 2es10.2, a, es10.2)', '    '//label//': '//codim2_name(kind)// &
      ' error in p ', abs(curve%codim2(i)%p - p_exact), ', in theta ', &
      abs(curve%codim2(i)%omega - theta_exact)
    call check_true(label//': '//codim2_name(kind)//' at the exact p', &
                    maxval(abs(curve%codim2(i)%p - p_exact)) <= tol)
    call check_close(label//': '//codim2_name(kind)//' theta', curve%codim2(i)%omega, &
                     theta_exact, 0.0_wp, tol)
  end subroutine check_codim2

  !> Henon's Neimark-Sacker line b = -1, from a = 0.5 to the 1:1 (a = -1) and 1:2 (a = 3)
  !> resonances, where it ends, through 1:4 (a = 0) and 1:3 (a = 5/4).
  subroutine test_henon_neimark_sacker()
    type(henon_map) :: map
    type(bifurcation_curve) :: curve
    real(wp) :: x0, worst_b, worst_kappa, worst_circle, kappa, re(2), im(2)
    integer :: status, j
    character(len=message_len) :: message
    x0 = (sqrt(1.5_wp) - 1)/0.5_wp
    call neimark_sacker_curve(map, [x0, -x0], [0.5_wp, -1.0_wp], box(-2.0_wp, 4.0_wp, -2.0_wp, &
                              0.0_wp, ds, ds_max), curve, status, message)
    call report('Henon NS', curve)
    call check_true('Henon NS: complete, status 0 ('//trim(message)//')', status == SD_OK .and. &
                    curve%complete .and. curve%kind == CURVE_NEIMARK_SACKER)
    call check_true('Henon NS: both ends at a resonance', &
                    all(curve%end_reason == END_RESONANCE))
    worst_b = 0
    worst_kappa = 0
    worst_circle = 0
    do j = 1, curve%n_points
      kappa = 2*cos(curve%omega(j))
      worst_b = max(worst_b, abs(curve%p(2, j) + 1))
      worst_kappa = max(worst_kappa, abs(kappa - (2 - 2*sqrt(1 + curve%p(1, j)))))
      re = curve%eig_re(:, j)
      im = curve%eig_im(:, j)
      if (curve%special(j) == 0) worst_circle = max(worst_circle, maxval(abs(hypot(re, im) - 1)))
    end do
    print '(a, 3es10.2)', '    Henon NS: max |b + 1|, |kappa - exact|, ||mu| - 1|: ', &
      worst_b, worst_kappa, worst_circle
    call check_true('Henon NS: b = -1 at every point (1e-10)', worst_b < 1.0e-10_wp)
    call check_true('Henon NS: kappa = 2 - 2 sqrt(1 + a) at every point (1e-9)', &
                    worst_kappa < 1.0e-9_wp)
    call check_true('Henon NS: multipliers on the unit circle (1e-8; points but the '// &
                    'resonances, where dgeev meets a Jordan block)', worst_circle < 1.0e-8_wp)
    call check_codim2('Henon NS', curve, CODIM2_R1, [-1.0_wp, -1.0_wp], 0.0_wp, 1.0e-8_wp)
    call check_codim2('Henon NS', curve, CODIM2_R2, [3.0_wp, -1.0_wp], pi, 1.0e-8_wp)
    call check_codim2('Henon NS', curve, CODIM2_R3, [1.25_wp, -1.0_wp], 2*pi/3, 1.0e-8_wp)
    call check_codim2('Henon NS', curve, CODIM2_R4, [0.0_wp, -1.0_wp], pi/2, 1.0e-8_wp)
  end subroutine test_henon_neimark_sacker

  !> With neutral_saddles the curve goes on through both resonances to the box as real
  !> multipliers mu, 1/mu (det M = 1 on all of b = -1).
  subroutine test_henon_neutral_saddles()
    type(henon_map) :: map
    type(bifurcation_curve) :: curve
    type(curve_options) :: opt
    real(wp) :: x0, worst
    integer :: status, j
    character(len=message_len) :: message
    x0 = (sqrt(1.5_wp) - 1)/0.5_wp
    opt = box(-2.0_wp, 4.0_wp, -2.0_wp, 0.0_wp, ds, ds_max)
    opt%neutral_saddles = .true.
    ! beyond the 1:1 resonance the curve follows the other fixed point, x ~ -2/a -> infinity
    opt%x_max = 10
    call neimark_sacker_curve(map, [x0, -x0], [0.5_wp, -1.0_wp], opt, curve, status, message)
    call report('Henon NS with neutral saddles', curve)
    worst = 0
    do j = 1, curve%n_points
      worst = max(worst, abs(curve%p(2, j) + 1), &
                  abs(curve%eig_re(1, j)*curve%eig_re(2, j) - curve%eig_im(1, j)* &
                      curve%eig_im(2, j) - 1))
    end do
    call check_true('Henon neutral saddles: complete, through R2 to the box and through R1 '// &
                    'to x_max ('//trim(message)//')', status == SD_OK .and. curve%complete .and. &
                    any(curve%end_reason == END_BOX) .and. any(curve%end_reason == END_X_MAX))
    call check_true('Henon neutral saddles: b = -1 and mu1 mu2 = 1 all along (1e-10)', &
                    worst < 1.0e-10_wp)
    call check_codim2('Henon neutral saddles', curve, CODIM2_R2, [3.0_wp, -1.0_wp], pi, &
                      1.0e-8_wp)
    call check_codim2('Henon neutral saddles', curve, CODIM2_R1, [-1.0_wp, -1.0_wp], 0.0_wp, &
                      1.0e-8_wp)
  end subroutine test_henon_neutral_saddles

  !> Henon's fold curve a = -(1 - b)^2/4 through the 1:1 resonance (-1, -1) and its period-
  !> doubling curve a = 3 (1 - b)^2/4 through the 1:2 resonance (3, -1).
  subroutine test_henon_fold_and_flip()
    type(henon_map) :: map
    type(bifurcation_curve) :: curve
    real(wp) :: b, a, x, worst, worst_mu
    integer :: status, j
    character(len=message_len) :: message
    b = -0.5_wp
    a = -(1 - b)**2/4
    x = 2/(1 - b)
    call map_fold_curve(map, [x, b*x], [a, b], box(-3.0_wp, 5.0_wp, -2.0_wp, 0.5_wp, ds, ds_max), &
                        curve, status, message)
    call report('Henon fold', curve)
    call check_true('Henon fold: complete to the box ('//trim(message)//')', &
                    status == SD_OK .and. curve%complete .and. all(curve%end_reason == END_BOX))
    worst = 0
    worst_mu = 0
    do j = 1, curve%n_points
      worst = max(worst, abs(curve%p(1, j) + (1 - curve%p(2, j))**2/4), &
                  abs(curve%x(1, j) - 2/(1 - curve%p(2, j))))
      if (curve%special(j) == 0) &
        worst_mu = max(worst_mu, minval(hypot(curve%eig_re(:, j) - 1, curve%eig_im(:, j))))
    end do
    print '(a, 2es10.2)', '    Henon fold: max error of a(b), x(b); of the multiplier 1: ', &
      worst, worst_mu
    call check_true('Henon fold: a = -(1 - b)^2/4, x = 2/(1 - b) (1e-10)', worst < 1.0e-10_wp)
    call check_true('Henon fold: a multiplier at +1 (1e-8)', worst_mu < 1.0e-8_wp)
    call check_codim2('Henon fold', curve, CODIM2_R1, [-1.0_wp, -1.0_wp], 0.0_wp, 1.0e-8_wp)

    a = 3*(1 - b)**2/4
    x = (1 - b)/(2*a)
    call period_doubling_curve(map, [x, b*x], [a, b], &
                               box(-3.0_wp, 8.0_wp, -2.0_wp, 0.5_wp, ds, ds_max), &
                               curve, status, message)
    call report('Henon period doubling', curve)
    call check_true('Henon PD: complete to the box ('//trim(message)//')', &
                    status == SD_OK .and. curve%complete .and. &
                    curve%kind == CURVE_PERIOD_DOUBLING .and. all(curve%end_reason == END_BOX))
    worst = 0
    worst_mu = 0
    do j = 1, curve%n_points
      worst = max(worst, abs(curve%p(1, j) - 3*(1 - curve%p(2, j))**2/4))
      if (curve%special(j) == 0) &
        worst_mu = max(worst_mu, minval(hypot(curve%eig_re(:, j) + 1, curve%eig_im(:, j))))
    end do
    print '(a, 2es10.2)', '    Henon PD: max error of a(b); of the multiplier -1: ', worst, &
      worst_mu
    call check_true('Henon PD: a = 3 (1 - b)^2/4 (1e-10)', worst < 1.0e-10_wp)
    call check_true('Henon PD: a multiplier at -1 (1e-8)', worst_mu < 1.0e-8_wp)
    call check_codim2('Henon PD', curve, CODIM2_R2, [3.0_wp, -1.0_wp], pi, 1.0e-8_wp)
  end subroutine test_henon_fold_and_flip

  !> The cusp-flip normal form: fold curve (-2 x^3, 3 x^2) with the cusp at 0 and the fold-flip
  !> at x = c; the period-doubling line p1 = c^3 - p2 c through the fold-flip.
  subroutine test_cusp_flip()
    type(cusp_flip_map) :: map
    type(bifurcation_curve) :: curve
    real(wp) :: z, worst, c
    integer :: status, j
    character(len=message_len) :: message
    c = map%c
    z = 0.3_wp
    call map_fold_curve(map, [z, 0.0_wp], [-2*z**3, 3*z**2], box(-1.0_wp, 1.0_wp, -0.5_wp, &
                        1.5_wp, ds, ds_max), curve, status, message)
    call report('cusp-flip fold', curve)
    call check_true('cusp-flip fold: complete ('//trim(message)//')', status == SD_OK .and. &
                    curve%complete)
    worst = 0
    do j = 1, curve%n_points
      worst = max(worst, abs(curve%p(1, j) + 2*curve%x(1, j)**3), &
                  abs(curve%p(2, j) - 3*curve%x(1, j)**2), abs(curve%x(2, j)))
    end do
    call check_true('cusp-flip fold: p = (-2 x^3, 3 x^2), y = 0 (1e-10)', worst < 1.0e-10_wp)
    call check_codim2('cusp-flip fold', curve, CODIM2_CUSP, [0.0_wp, 0.0_wp], 0.0_wp, 1.0e-8_wp)
    call check_codim2('cusp-flip fold', curve, CODIM2_FOLD_FLIP, [-2*c**3, 3*c**2], 0.0_wp, &
                      1.0e-8_wp)

    call period_doubling_curve(map, [c, 0.0_wp], [c**3 - 0.5_wp*c, 0.5_wp], box(-1.0_wp, &
                               1.0_wp, -0.5_wp, 1.5_wp, ds, ds_max), curve, status, message)
    call report('cusp-flip period doubling', curve)
    worst = 0
    do j = 1, curve%n_points
      worst = max(worst, abs(curve%p(1, j) - (c**3 - curve%p(2, j)*c)), &
                  abs(curve%x(1, j) - c), abs(curve%x(2, j)))
    end do
    call check_true('cusp-flip PD: complete ('//trim(message)//')', status == SD_OK .and. &
                    curve%complete)
    call check_true('cusp-flip PD: p1 = c^3 - p2 c, x = (c, 0) (1e-10)', worst < 1.0e-10_wp)
    call check_codim2('cusp-flip PD', curve, CODIM2_FOLD_FLIP, [-2*c**3, 3*c**2], 0.0_wp, &
                      1.0e-8_wp)
  end subroutine test_cusp_flip

  !> Finite differences of shots: the second derivative d^2 P1/dz1^2 of the rotating-frame
  !> cusp flow at an equilibrium against its closed form, for three steps.
  subroutine test_frame_derivatives()
    type(frame_map) :: map
    real(wp) :: z, p(2), lam, t, exact, b(2)
    real(wp), parameter :: fractions(3) = [1.0e-3_wp, 1.0e-4_wp, 1.0e-6_wp]
    integer :: i
    map%kind = FRAME_CUSP
    map%integration%rtol = 1.0e-12_wp
    map%integration%atol = 1.0e-14_wp
    map%method = METHOD_DOP853
    z = 0.4_wp
    p(2) = 0.2_wp
    p(1) = z**3 - p(2)*z
    lam = p(2) - 3*z**2
    t = 2*pi
    exact = (-6*z/lam)*exp(lam*t)*(exp(lam*t) - 1)
    do i = 1, 3
      map%x_step = fractions(i)
      call map%second_derivative([z, 0.0_wp], p, [1.0_wp, 0.0_wp], [1.0_wp, 0.0_wp], b)
      print '(a, es8.1, a, es10.2, a, es10.2, a, es10.2)', '  shots at rtol 1e-12, step ', &
        fractions(i), ': d2P1/dz1^2 relative error ', abs(b(1)/exact - 1), ' (exact ', exact, &
        '), |d2P2| ', abs(b(2))
      if (i == 2) call check_close('finite differences of shots: d2P/dz^2 with the step '// &
                                   'rtol^(1/3) (1e-6 relative)', b(1), exact, 1.0e-6_wp)
    end do
  end subroutine test_frame_derivatives

  !> The fold curve of the rotating-frame cusp flow by shooting: p = (-2 z^3, 3 z^2), the cusp
  !> at p = 0, a multiplier +1 all along.
  subroutine test_frame_cusp()
    type(frame_map) :: map
    type(bifurcation_curve) :: curve
    type(curve_options) :: opt
    real(wp) :: z, worst, worst_mu
    integer :: status, j
    character(len=message_len) :: message
    map%kind = FRAME_CUSP
    map%integration%rtol = 1.0e-12_wp
    map%integration%atol = 1.0e-14_wp
    map%method = METHOD_DOP853
    map%x_step = 1.0e-4_wp
    map%p_step = 1.0e-4_wp
    opt = box(-0.3_wp, 0.3_wp, -0.1_wp, 0.5_wp, ds, ds_max)
    opt%continuation%newton%f_tol = 1.0e-10_wp
    z = 0.3_wp
    call map_fold_curve(map, [z, 0.0_wp], [-2*z**3, 3*z**2], opt, curve, status, message)
    call report('frame cusp (shooting) fold', curve)
    call check_true('frame cusp fold: complete ('//trim(message)//')', status == SD_OK .and. &
                    curve%complete)
    worst = 0
    worst_mu = 0
    do j = 1, curve%n_points
      worst = max(worst, abs(curve%p(1, j) + 2*curve%x(1, j)**3), &
                  abs(curve%p(2, j) - 3*curve%x(1, j)**2), abs(curve%x(2, j)))
      if (curve%special(j) == 0) &
        worst_mu = max(worst_mu, minval(hypot(curve%eig_re(:, j) - 1, curve%eig_im(:, j))))
    end do
    print '(a, 2es10.2)', '    frame cusp fold: max error of p(z), of the multiplier 1: ', &
      worst, worst_mu
    call check_true('frame cusp fold: p = (-2 z^3, 3 z^2) (1e-9)', worst < 1.0e-9_wp)
    call check_true('frame cusp fold: a multiplier at +1 (1e-8)', worst_mu < 1.0e-8_wp)
    call check_codim2('frame cusp fold', curve, CODIM2_CUSP, [0.0_wp, 0.0_wp], 0.0_wp, 1.0e-8_wp)

    ! orbits of period 2 T: the same equilibria, multipliers squared
    map%periods = 2
    call map_fold_curve(map, [z, 0.0_wp], [-2*z**3, 3*z**2], opt, curve, status, message)
    worst = 0
    do j = 1, curve%n_points
      worst = max(worst, abs(curve%p(1, j) + 2*curve%x(1, j)**3), &
                  abs(curve%p(2, j) - 3*curve%x(1, j)**2), abs(curve%x(2, j)))
    end do
    call check_true('frame cusp fold, period 2 T: complete, p = (-2 z^3, 3 z^2) (1e-9) ('// &
                    trim(message)//')', status == SD_OK .and. curve%complete .and. &
                    worst < 1.0e-9_wp)
    call check_codim2('frame cusp fold, period 2 T', curve, CODIM2_CUSP, [0.0_wp, 0.0_wp], &
                      0.0_wp, 1.0e-8_wp)
  end subroutine test_frame_cusp

  !> The linear rotating-frame flow by shooting: the Neimark-Sacker line p1 + p2 = 0 with its
  !> closed-form angle, 1:4, 1:3 and (its end) 1:2 resonances; the period-doubling hyperbola
  !> p1 p2 = -1 through the 1:2 resonance.
  subroutine test_frame_linear()
    type(frame_map) :: map
    type(bifurcation_curve) :: curve
    type(curve_options) :: opt
    real(wp) :: worst, worst_theta, worst_mu, s
    integer :: status, j
    character(len=message_len) :: message
    map%kind = FRAME_LINEAR
    map%integration%rtol = 1.0e-12_wp
    map%integration%atol = 1.0e-14_wp
    map%method = METHOD_DOP853
    map%x_step = 1.0e-4_wp
    map%p_step = 1.0e-4_wp
    opt = box(0.3_wp, 2.0_wp, -2.0_wp, 0.0_wp, ds, ds_max)
    opt%continuation%newton%f_tol = 1.0e-10_wp
    call neimark_sacker_curve(map, [0.0_wp, 0.0_wp], [0.6_wp, -0.6_wp], opt, curve, status, &
                              message)
    call report('frame linear (shooting) NS', curve)
    call check_true('frame linear NS: complete, box and 1:2 resonance ('//trim(message)//')', &
                    status == SD_OK .and. curve%complete .and. any(curve%end_reason == END_BOX) &
                    .and. any(curve%end_reason == END_RESONANCE))
    worst = 0
    worst_theta = 0
    worst_mu = 0
    do j = 1, curve%n_points
      s = sqrt(max(1 - curve%p(1, j)**2, 0.0_wp))
      worst = max(worst, abs(curve%p(1, j) + curve%p(2, j)), maxval(abs(curve%x(:, j))))
      worst_theta = max(worst_theta, abs(2*cos(curve%omega(j)) + 2*cos(pi*s)))
      if (curve%special(j) == 0) worst_mu = max(worst_mu, &
        maxval(abs(hypot(curve%eig_re(:, j), curve%eig_im(:, j)) - 1)))
    end do
    print '(a, 3es10.2)', '    frame linear NS: max |p1 + p2|, |kappa - exact|, ||mu| - 1|: ', &
      worst, worst_theta, worst_mu
    call check_true('frame linear NS: p1 + p2 = 0 (1e-9)', worst < 1.0e-9_wp)
    call check_true('frame linear NS: kappa = -2 cos(pi s) (1e-8)', worst_theta < 1.0e-8_wp)
    call check_true('frame linear NS: multipliers on the unit circle (1e-8)', worst_mu < 1.0e-8_wp)
    call check_codim2('frame linear NS', curve, CODIM2_R2, [1.0_wp, -1.0_wp], pi, 1.0e-8_wp)
    call check_codim2('frame linear NS', curve, CODIM2_R3, [sqrt(8.0_wp)/3, -sqrt(8.0_wp)/3], &
                      2*pi/3, 1.0e-8_wp)
    call check_codim2('frame linear NS', curve, CODIM2_R4, [sqrt(3.0_wp)/2, -sqrt(3.0_wp)/2], &
                      pi/2, 1.0e-8_wp)

    opt = box(0.3_wp, 2.0_wp, -3.0_wp, 0.0_wp, ds, ds_max)
    opt%continuation%newton%f_tol = 1.0e-10_wp
    call period_doubling_curve(map, [0.0_wp, 0.0_wp], [2.0_wp, -0.5_wp], opt, curve, status, &
                               message)
    call report('frame linear (shooting) PD', curve)
    call check_true('frame linear PD: complete ('//trim(message)//')', status == SD_OK .and. &
                    curve%complete)
    worst = 0
    worst_mu = 0
    do j = 1, curve%n_points
      worst = max(worst, abs(curve%p(1, j)*curve%p(2, j) + 1))
      if (curve%special(j) == 0) &
        worst_mu = max(worst_mu, minval(hypot(curve%eig_re(:, j) + 1, curve%eig_im(:, j))))
    end do
    print '(a, 2es10.2)', '    frame linear PD: max |p1 p2 + 1|, of the multiplier -1: ', &
      worst, worst_mu
    call check_true('frame linear PD: p1 p2 = -1 (1e-9)', worst < 1.0e-9_wp)
    call check_true('frame linear PD: a multiplier at -1 (1e-8)', worst_mu < 1.0e-8_wp)
    call check_codim2('frame linear PD', curve, CODIM2_R2, [1.0_wp, -1.0_wp], pi, 1.0e-8_wp)
  end subroutine test_frame_linear

  !> A map that fails beyond a = 2: the curve comes back up to there, incomplete, with the reason.
  subroutine test_incomplete()
    type(walled_henon) :: map
    type(bifurcation_curve) :: curve
    real(wp) :: x0
    integer :: status
    character(len=message_len) :: message
    x0 = (sqrt(1.5_wp) - 1)/0.5_wp
    call neimark_sacker_curve(map, [x0, -x0], [0.5_wp, -1.0_wp], box(-2.0_wp, 4.0_wp, -2.0_wp, &
                              0.0_wp, ds, ds_max), curve, status, message)
    call report('walled Henon NS', curve)
    call check_true('failing map: incomplete, status, message, reason END_FAILED', &
                    status /= SD_OK .and. .not. curve%complete .and. curve%status == status .and. &
                    len_trim(message) > 0 .and. any(curve%end_reason == END_FAILED))
    call check_true('failing map: the points up to the wall kept (a in (1.99, 2])', &
                    maxval(curve%p(1, 1:curve%n_points)) <= 2 .and. &
                    maxval(curve%p(1, 1:curve%n_points)) > 1.99_wp .and. &
                    minval(curve%p(1, 1:curve%n_points)) < -0.999_wp)
    call check_true('failing map: the message says where (p = ...)', index(message, 'p = (') > 0)
  end subroutine test_incomplete

  !> Rules: a Hopf curve of a map, a Neimark-Sacker start without a complex pair.
  subroutine test_bad_input()
    type(henon_map) :: map
    type(bifurcation_curve) :: curve
    real(wp) :: x(2), p(2), theta, a, b, x0
    integer :: status
    character(len=message_len) :: message
    call hopf_curve(map, [0.5_wp, -0.5_wp], [0.0_wp, -1.0_wp], box(-2.0_wp, 4.0_wp, -2.0_wp, &
                    0.0_wp, ds, ds_max), curve, status, message)
    print '(a)', '    '//trim(message)
    call check_true('a Hopf curve of a map is refused: '//trim(message), &
                    status == SD_BAD_INPUT .and. index(message, 'Neimark-Sacker') > 0)
    b = -0.5_wp
    a = 3*(1 - b)**2/4
    x0 = (1 - b)/(2*a)
    call neimark_sacker_curve(map, [x0, b*x0], [a, b], &
                              box(-2.0_wp, 8.0_wp, -2.0_wp, 0.5_wp, ds, ds_max), &
                              curve, status, message)
    print '(a)', '    '//trim(message)
    call check_true('a Neimark-Sacker start with real multipliers is refused', &
                    status == SD_BAD_INPUT .and. index(message, 'complex multiplier pair') > 0)
    call correct_to_curve(map, 7, [0.5_wp, -0.5_wp], [0.0_wp, -1.0_wp], 2, box(-2.0_wp, 4.0_wp, &
                          -2.0_wp, 0.0_wp, ds, ds_max), x, p, theta, status, message)
    call check_true('correct_to_curve: kind out of range named: '//trim(message), &
                    status == SD_BAD_INPUT .and. index(message, 'kind') > 0)
    ! correct_to_curve at fixed a = 0: the 1:4 resonance point of the Neimark-Sacker line
    call correct_to_curve(map, CURVE_NEIMARK_SACKER, [0.49_wp, -0.5_wp], [0.0_wp, -0.98_wp], 1, &
                          box(-2.0_wp, 4.0_wp, -2.0_wp, 0.0_wp, ds, ds_max), x, p, theta, status, &
                          message)
    call check_true('correct_to_curve (NS) at a = 0: b = -1, theta = pi/2, x = (1/2, -1/2)', &
                    status == SD_OK .and. abs(p(2) + 1) < 1.0e-12_wp .and. &
                    abs(theta - pi/2) < 1.0e-12_wp .and. maxval(abs(x - [0.5_wp, -0.5_wp])) < &
                    1.0e-12_wp)
  end subroutine test_bad_input
  !> Print the wall time since the last call (sections of this test).
  subroutine timed(label)
    character(len=*), intent(in) :: label
    print '(a, f8.2, a)', '  -- '//label//': ', elapsed() - clock_last, ' s'
    clock_last = elapsed()
  end subroutine timed

  real(wp) function elapsed()
    integer :: now
    call system_clock(now)
    elapsed = real(now - clock_start, wp)/clock_rate
  end function elapsed

  !> The Fig 12 model (s1 = 1.5, mu1 = 0.5, kappa = 1.804897259, theta0 = pi/4, beta = 10,
  !> gamma = 0.001, delta = 0.1, n = 6, p = 2) at (rho, A).
  function fig12_model(rho, amplitude) result(model)
    real(wp), intent(in) :: rho, amplitude
    type(model_t) :: model
    integer :: status
    character(len=message_len) :: message
    call model_from_arrays([1.5_wp, 0.5_wp, 1.804897259_wp, pi/4, 10.0_wp, 0.001_wp, 0.1_wp, &
                            amplitude, rho, 0.0_wp], [6, 2], model, status, message)
  end function fig12_model

  !> The shots of the tank tests (as in test_periodic, tighter: the finite-difference steps of
  !> the chart follow rtol^(1/3)).
  function tank_integration() result(opt)
    type(ode_options) :: opt
    opt%rtol = 1.0e-12_wp
    opt%atol = 1.0e-14_wp
  end function tank_integration

  function tank_chart_options() result(opt)
    type(orbit_chart_options) :: opt
    opt%integration = tank_integration()
    opt%curve%p_min = [0.505_wp, 1.0e-4_wp]
    opt%curve%p_max = [0.515_wp, 0.0015_wp]
    opt%curve%continuation%newton%f_tol = 1.0e-10_wp
  end function tank_chart_options

  !> One-parameter continuation of the Fig 12 orbits in rho over [0.50, 0.52] at the amplitude:
  !> its special points (periodic_response's layout).
  subroutine one_parameter(amplitude, special, n_special, rho_range, y_guess)
    real(wp), intent(in) :: amplitude
    real(wp), intent(out) :: special(:, :)
    integer, intent(out) :: n_special
    real(wp), intent(in), optional :: rho_range(2), y_guess(4)
    integer, parameter :: capacity = 400
    type(continuation_options) :: opt
    real(wp) :: y(4), m(4, 4), re(4), im(4), max_x1, points(7, capacity), mult(8, capacity), &
                range(2), guess(4)
    integer :: iterations, status, n_points, j
    logical :: complete
    character(len=message_len) :: message
    range = [0.50_wp, 0.52_wp]
    guess = 0
    opt%ds = 0.002_wp
    opt%ds_max = 0.01_wp
    if (present(rho_range)) then
      range = rho_range
      guess = y_guess
      ! the orbit changes fast with rho there (|dy0/drho| ~ 1e3): arclength steps of ~1e-5 in rho
      opt%ds = 0.005_wp
      opt%ds_max = 0.02_wp
    end if
    call periodic_orbit(fig12_model(range(1), amplitude), guess, 1, tank_integration(), 0, &
                        1.0e-10_wp, 20, y, m, re, im, iterations, max_x1, status, message)
    opt%max_points = capacity
    call periodic_response(fig12_model(range(1), amplitude), PARAMETER_RHO, y, 1, range(1), &
                           range(2), opt, tank_integration(), 0, points, mult, n_points, &
                           special, n_special, complete, status, message)
    if (status /= SD_OK) print '(a)', '    periodic_response: '//trim(message)
    print '(a, es9.2, a, 2f9.5, a, i0, a)', '  one-parameter continuation at A = ', amplitude, &
      ' over rho in', range, ': ', n_special, ' special points'
    do j = 1, n_special
      print '(a, i0, a, f14.10)', '    kind ', nint(special(1, j)), ' at rho = ', special(2, j)
    end do
  end subroutine one_parameter

  !> The rho of the special points of the kind.
  subroutine rho_of(special, n_special, kind, rho, n_rho)
    real(wp), intent(in) :: special(:, :)
    integer, intent(in) :: n_special, kind
    real(wp), intent(out) :: rho(:)
    integer, intent(out) :: n_rho
    integer :: j
    n_rho = 0
    do j = 1, n_special
      if (nint(special(1, j)) /= kind) cycle
      n_rho = n_rho + 1
      rho(n_rho) = special(2, j)
    end do
  end subroutine rho_of

  !> The largest distance from a value of a to the nearest of b and the other way round.
  real(wp) function set_distance(a, b) result(worst)
    real(wp), intent(in) :: a(:), b(:)
    integer :: i
    worst = huge(1.0_wp)
    if (size(a) == 0 .or. size(b) == 0) return
    worst = 0
    do i = 1, size(a)
      worst = max(worst, minval(abs(b - a(i))))
    end do
    do i = 1, size(b)
      worst = max(worst, minval(abs(a - b(i))))
    end do
  end function set_distance

  !> Fig 12's Neimark-Sacker curve of the full model in (rho, A), started from the first
  !> Neimark-Sacker point of the one-parameter continuation at A = 0.00075: it crosses A =
  !> 0.00075 at both Neimark-Sacker points of that continuation and A = 0.001 at those of a
  !> second one-parameter continuation (3e-5 in rho); independent shooting at points of the curve
  !> puts the pair on the unit circle (1e-8). Timed.
  subroutine test_fig12_neimark_sacker()
    type(tank_orbit_map) :: map
    type(orbit_chart_options) :: opt
    type(bifurcation_curve) :: curve
    real(wp) :: special(7, 12), local(7, 12), ns_rho(20), crossing_x(4, 8), crossing_p(2, 8), &
                start, seconds, y(4), m(4, 4), re(4), im(4), max_x1, worst, distance, &
                cpu_start, cpu_end, stored
    real(wp), parameter :: levels(2) = [0.00075_wp, 0.001_wp]
    integer :: n_special, n_ns, status, n_found, l, j, iterations, column, n_checked, i, k, &
               n_local
    character(len=message_len) :: message

    call one_parameter(levels(1), special, n_special)
    call rho_of(special, n_special, SPECIAL_NEIMARK_SACKER, ns_rho, n_ns)
    call check_true('Fig 12 (full model): two Neimark-Sacker points at A = 0.00075', n_ns == 2)
    if (n_ns < 1) return
    opt = tank_chart_options()
    column = 0
    do j = 1, n_special
      if (nint(special(1, j)) == SPECIAL_NEIMARK_SACKER .and. column == 0) column = j
    end do
    start = elapsed()
    call cpu_time(cpu_start)
    call orbit_curve_from_special(fig12_model(0.50_wp, levels(1)), PARAMETER_RHO, &
                                  special(:, column), opt, curve, status, message)
    call cpu_time(cpu_end)
    seconds = elapsed() - start
    call report('Fig 12 Neimark-Sacker curve (full model)', curve)
    print '(a, f8.2, a, f8.2, a, i0, a)', '    time: ', cpu_end - cpu_start, ' s CPU (', &
      seconds, ' s wall) for ', curve%n_points, ' points'
    call check_true('Fig 12 NS curve: complete, status 0 ('//trim(message)//')', &
                    status == SD_OK .and. curve%complete .and. curve%kind == CURVE_NEIMARK_SACKER)
    call make_orbit_map(fig12_model(0.50_wp, levels(1)), opt, map, status, message)

    do l = 1, size(levels)
      if (l > 1) then
        call one_parameter(levels(l), special, n_special)
        call rho_of(special, n_special, SPECIAL_NEIMARK_SACKER, ns_rho, n_ns)
      end if
      call curve_crossings(map, curve, 2, levels(l), opt%curve, crossing_x, crossing_p, &
                           n_found, status, message)
      if (status /= SD_OK) print '(a)', '    '//trim(message)
      ! a crossing on a family of orbits the continuation from rest does not reach: a second
      ! one-parameter continuation through that orbit, over rho_crossing -+ 2e-4
      do i = 1, n_found
        if (n_ns > 0) then
          if (minval(abs(ns_rho(1:n_ns) - crossing_p(1, i))) <= 3.0e-5_wp) cycle
        end if
        call one_parameter(levels(l), local, n_local, crossing_p(1, i) + [-2.0e-4_wp, &
                           2.0e-4_wp], crossing_x(:, i))
        call rho_of(local, n_local, SPECIAL_NEIMARK_SACKER, ns_rho(n_ns + 1:), k)
        n_ns = n_ns + k
      end do
      print '(a, es9.2, a, 4f15.10)', '    A = ', levels(l), ': NS (one-parameter)  ', &
        ns_rho(1:n_ns)
      print '(a, es9.2, a, 4f15.10)', '    A = ', levels(l), ': NS curve crossings ', &
        crossing_p(1, 1:n_found)
      distance = set_distance(crossing_p(1, 1:n_found), ns_rho(1:n_ns))
      print '(a, es10.2)', '      max |difference| in rho: ', distance
      call check_true('Fig 12 NS curve: its crossings of A = '//trim(num_text(levels(l)))// &
                      ' are the one-parameter NS points (3e-5 in rho)', status == SD_OK .and. &
                      n_found == n_ns .and. n_ns > 0 .and. distance <= 3.0e-5_wp)
    end do

    ! independent shooting (Newton on y(T) - y0 from the curve's state) at every fifth point
    worst = 0
    n_checked = 0
    do j = 1, curve%n_points, 5
      call periodic_orbit(fig12_model(curve%p(1, j), curve%p(2, j)), curve%x(:, j), 1, &
                          tank_integration(), 0, 1.0e-12_wp, 20, y, m, re, im, iterations, &
                          max_x1, status, message)
      if (status /= SD_OK) then
        worst = huge(1.0_wp)
        exit
      end if
      worst = max(worst, pair_off_circle(re, im))
      n_checked = n_checked + 1
    end do
    stored = 0
    do j = 1, curve%n_points
      stored = max(stored, pair_off_circle(curve%eig_re(:, j), curve%eig_im(:, j)))
    end do
    print '(a, es10.2)', '    the curve''s own multipliers, every point: max ||mu| - 1| ', stored
    call check_true('Fig 12 NS curve: its multiplier pair on the unit circle at every point '// &
                    '(1e-8)', stored < 1.0e-8_wp)
    print '(a, i0, a, es10.2)', '    independent shooting at ', n_checked, &
      ' points: max ||mu| - 1| of the pair ', worst
    call check_true('Fig 12 NS curve: a multiplier pair on the unit circle (1e-8, independent '// &
                    'shooting)', worst < 1.0e-8_wp)
  end subroutine test_fig12_neimark_sacker

  !> Fig 12's fold curve(s) of orbits through the one-parameter folds at A = 0.00075: they cross
  !> A = 0.00075 exactly there; independent shooting finds a multiplier +1 (1e-8); the fold pair
  !> is born at a cusp of orbits (the slow flow's is at rho = 0.509325, A = 5.455e-4,
  !> test_slowflow_chart). Timed.
  subroutine test_fig12_folds()
    type(tank_orbit_map) :: map
    type(orbit_chart_options) :: opt
    type(bifurcation_curve) :: curve
    type(tank_system) :: tank
    real(wp) :: special(7, 12), fold_rho(4), crossing_x(4, 8), crossing_p(2, 8), start, &
                seconds, y(4), m(4, 4), re(4), im(4), worst, distance, residual, cpu_start, &
                cpu_end, stored
    integer :: n_special, n_folds, status, n_found, j, column, n_checked, i, count
    character(len=message_len) :: message

    call one_parameter(0.00075_wp, special, n_special)
    call rho_of(special, n_special, SPECIAL_FOLD, fold_rho, n_folds)
    column = 0
    do j = 1, n_special
      if (nint(special(1, j)) == SPECIAL_FOLD .and. column == 0) column = j
    end do
    if (column == 0) then
      call check_true('Fig 12 folds: the one-parameter continuation has folds', .false.)
      return
    end if
    opt = tank_chart_options()
    start = elapsed()
    call cpu_time(cpu_start)
    call orbit_curve_from_special(fig12_model(0.50_wp, 0.00075_wp), PARAMETER_RHO, &
                                  special(:, column), opt, curve, status, message)
    call cpu_time(cpu_end)
    seconds = elapsed() - start
    call report('Fig 12 fold curve of orbits (full model)', curve)
    print '(a, f8.2, a, f8.2, a, i0, a)', '    time: ', cpu_end - cpu_start, ' s CPU (', &
      seconds, ' s wall) for ', curve%n_points, ' points'
    call check_true('Fig 12 fold curve: complete, status 0 ('//trim(message)//')', &
                    status == SD_OK .and. curve%complete .and. curve%kind == CURVE_FOLD)
    call make_orbit_map(fig12_model(0.50_wp, 0.00075_wp), opt, map, status, message)
    call curve_crossings(map, curve, 2, 0.00075_wp, opt%curve, crossing_x, crossing_p, n_found, &
                         status, message)
    print '(a, 4f15.10)', '    A = 7.5e-4: folds (one-parameter)  ', fold_rho(1:n_folds)
    print '(a, 4f15.10)', '    A = 7.5e-4: fold curve crossings  ', crossing_p(1, 1:n_found)
    distance = set_distance(crossing_p(1, 1:n_found), fold_rho(1:n_folds))
    print '(a, es10.2)', '      max |difference| in rho: ', distance
    call check_true('Fig 12 fold curve: one curve through both folds, its crossings of A = '// &
                    '7.5e-4 are the one-parameter folds (3e-5 in rho)', status == SD_OK .and. &
                    n_found == n_folds .and. distance <= 3.0e-5_wp)
    count = find_codim2(curve, CODIM2_CUSP, first=i)
    call check_true('Fig 12 fold curve: the fold pair is born at one cusp of orbits', count == 1)
    if (i > 0) then
      print '(a, f12.8, a, es14.6, a, 2es11.3)', '    cusp of orbits at rho = ', &
        curve%codim2(i)%p(1), ', A = ', curve%codim2(i)%p(2), '; slow flow''s: difference ', &
        curve%codim2(i)%p - [0.509325415_wp, 5.45535038e-4_wp]
      call check_true('Fig 12 fold curve: the cusp of orbits near the slow flow''s (2e-4 in '// &
                      'rho, 10 % in A)', abs(curve%codim2(i)%p(1) - 0.509325415_wp) < 2.0e-4_wp &
                      .and. abs(curve%codim2(i)%p(2)/5.45535038e-4_wp - 1) < 0.1_wp)
    end if
    ! one shot by the other integrator (DOPRI5; Newton's M - I is singular at a fold): the
    ! curve's state is a fixed point and has a multiplier +1
    worst = 0
    residual = 0
    n_checked = 0
    tank%varied = PARAMETER_RHO
    do j = 1, curve%n_points, 5
      if (curve%special(j) /= 0) cycle
      tank%model = fig12_model(curve%p(1, j), curve%p(2, j))
      call monodromy_matrix(tank, curve%x(:, j), 1, tank_integration(), 0, y, m, status, message)
      if (status == SD_OK) call eigenvalues(m, re, im, status, message)
      if (status /= SD_OK) then
        print '(a)', '    '//trim(message)
        worst = huge(1.0_wp)
        exit
      end if
      residual = max(residual, maxval(abs(y - curve%x(:, j))))
      worst = max(worst, minval(hypot(re - 1, im)))
      n_checked = n_checked + 1
    end do
    stored = 0
    do j = 1, curve%n_points
      if (curve%special(j) /= 0) cycle
      stored = max(stored, minval(hypot(curve%eig_re(:, j) - 1, curve%eig_im(:, j))))
    end do
    print '(a, es10.2)', '    the curve''s own multipliers, every point but the cusp: '// &
      'max |mu - 1| ', stored
    call check_true('Fig 12 fold curve: a multiplier +1 at every point (1e-8)', stored < 1.0e-8_wp)
    print '(a, i0, a, es10.2, a, es10.2)', '    one DOPRI5 shot at ', n_checked, &
      ' points: max |P(y0) - y0| ', residual, ', max |mu - 1| of the multiplier nearest +1 ', &
      worst
    call check_true('Fig 12 fold curve: fixed points (1e-10) with a multiplier at +1 (1e-8), '// &
                    'by an independent shot', residual < 1.0e-10_wp .and. worst < 1.0e-8_wp)
  end subroutine test_fig12_folds

  !> The tank's map: dP/d(rho, A) from the sensitivity equations (with dT/drho) and M from the
  !> variational equations against central differences of P (steps 1e-4 of the scales:
  !> truncation ~1e-8); the finite-difference second derivative B(v, v) of the curves at the
  !> default step (rtol^(1/3) x_scale) against one ten times smaller.
  subroutine test_tank_derivatives()
    type(tank_orbit_map) :: map, finer
    type(orbit_chart_options) :: opt
    real(wp) :: x(4), p(2), px(4), mx(4, 4), mp(4, 2), plus(4), minus(4), m_dummy(4, 4), h, &
                error_p(2), error_x, v(4), b(4), b_fine(4)
    integer :: k, status
    character(len=message_len) :: message
    opt = tank_chart_options()
    ! the orbit near the first Neimark-Sacker point of Fig 12 (rho = 0.5092, A = 0.00075)
    p = [0.5092_wp, 0.00075_wp]
    call periodic_orbit(fig12_model(p(1), p(2)), [-0.011_wp, -0.045_wp, -0.051_wp, 0.116_wp], &
                        1, tank_integration(), 0, 1.0e-12_wp, 20, x, mx, px, mp(:, 1), k, h, &
                        status, message)
    call check_true('tank derivatives: an orbit at rho = 0.5092 ('//trim(message)//')', &
                    status == SD_OK)
    call make_orbit_map(fig12_model(p(1), p(2)), opt, map, status, message)
    call map%map(x, p, px, mx, status, message, mp)
    do k = 1, 2
      h = 1.0e-4_wp*opt%curve%p_scale(k)
      call map%map(x, p + h*unit(k, 2), plus, m_dummy, status, message)
      call map%map(x, p - h*unit(k, 2), minus, m_dummy, status, message)
      error_p(k) = maxval(abs((plus - minus)/(2*h) - mp(:, k)))/maxval(abs(mp(:, k)))
    end do
    error_x = 0
    h = 1.0e-4_wp*opt%curve%x_scale
    do k = 1, 4
      call map%map(x + h*unit(k, 4), p, plus, m_dummy, status, message)
      call map%map(x - h*unit(k, 4), p, minus, m_dummy, status, message)
      error_x = max(error_x, maxval(abs((plus - minus)/(2*h) - mx(:, k))))
    end do
    error_x = error_x/maxval(abs(mx))
    print '(a, 3es10.2)', '  tank map: relative difference of dP/drho, dP/dA, M from '// &
      'differences of P: ', error_p, error_x
    call check_true('tank map: dP/d(rho, A) (sensitivities, dT/drho) = differences of P (1e-6)', &
                    maxval(error_p) < 1.0e-6_wp)
    call check_true('tank map: M (variational equations) = differences of P (1e-6)', &
                    error_x < 1.0e-6_wp)
    v = [0.3_wp, -0.5_wp, 0.6_wp, 0.5_wp]
    call map%second_derivative(x, p, v, v, b)
    finer = map
    finer%x_step = map%x_step/10
    call finer%second_derivative(x, p, v, v, b_fine)
    print '(a, es10.2, a, es10.2)', '  tank map: B(v, v) at steps x_step and x_step/10 differ '// &
      'by ', maxval(abs(b - b_fine))/maxval(abs(b_fine)), ' relative; x_step = ', map%x_step
    call check_true('tank map: B(v, v) settled in the step (1e-5 relative)', &
                    maxval(abs(b - b_fine)) < 1.0e-5_wp*maxval(abs(b_fine)))
  end subroutine test_tank_derivatives

  pure function unit(k, n) result(e)
    integer, intent(in) :: k, n
    real(wp) :: e(n)
    e = 0
    e(k) = 1
  end function unit

  !> ||mu| - 1| of the complex pair nearest the unit circle.
  real(wp) function pair_off_circle(re, im) result(distance)
    real(wp), intent(in) :: re(:), im(:)
    integer :: i
    distance = huge(1.0_wp)
    do i = 1, size(re)
      if (im(i) > 0) distance = min(distance, abs(hypot(re(i), im(i)) - 1))
    end do
  end function pair_off_circle

  function num_text(value) result(text)
    real(wp), intent(in) :: value
    character(len=16) :: text
    write (text, '(es9.2)') value
    text = adjustl(text)
  end function num_text

  !> Rules of the tank's curves: a branch point has no curve, periods >= 1, rho > 0 in the box.
  subroutine test_tank_bad_input()
    type(orbit_chart_options) :: opt
    type(model_t) :: model
    type(bifurcation_curve) :: curve
    integer :: status
    character(len=message_len) :: message
    opt = tank_chart_options()
    call orbit_curve_from_special(fig12_model(0.5_wp, 0.00075_wp), PARAMETER_RHO, &
                                  [real(SPECIAL_BRANCH_POINT, wp), 0.5_wp, 0.0_wp, 0.0_wp, &
                                   0.0_wp, 0.0_wp, 0.0_wp], opt, curve, status, message)
    call check_true('tank: a branch point has no curve, special(1) named: '//trim(message), &
                    status == SD_BAD_INPUT .and. index(message, 'special(1)') > 0 .and. &
                    curve%status == status)
    opt%periods = 0
    call orbit_neimark_sacker_curve(fig12_model(0.5_wp, 0.00075_wp), [0.0_wp, 0.0_wp, 0.0_wp, &
                                    0.0_wp], [0.5_wp, 0.00075_wp], opt, curve, status, message)
    call check_true('tank: periods = 0 named: '//trim(message), &
                    status == SD_BAD_INPUT .and. index(message, 'periods') > 0)
    opt = tank_chart_options()
    opt%curve%p_min(1) = 0
    call orbit_neimark_sacker_curve(fig12_model(0.5_wp, 0.00075_wp), [0.0_wp, 0.0_wp, 0.0_wp, &
                                    0.0_wp], [0.5_wp, 0.00075_wp], opt, curve, status, message)
    call check_true('tank: rho_min = 0 named: '//trim(message), &
                    status == SD_BAD_INPUT .and. index(message, 'rho') > 0)
    call orbit_curve_from_special(fig12_model(0.5_wp, 0.00075_wp), 3, &
                                  [real(SPECIAL_FOLD, wp), 0.5_wp, 0.0_wp, 0.0_wp, &
                                   0.0_wp, 0.0_wp, 0.0_wp], tank_chart_options(), curve, status, &
                                  message)
    call check_true('tank: parameter out of range named: '//trim(message), &
                    status == SD_BAD_INPUT .and. index(message, 'parameter') > 0)
    model = fig12_model(0.5_wp, 0.00075_wp)
    call record_excitation([0.0_wp, 0.1_wp, 0.0_wp], 0.5_wp, model%excitation, status, message)
    call orbit_neimark_sacker_curve(model, [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], &
                                    [0.5_wp, 0.00075_wp], tank_chart_options(), curve, status, &
                                    message)
    call check_true('tank: a record excitation is refused: '//trim(message), &
                    status == SD_BAD_INPUT .and. index(message, 'harmonic') > 0)
  end subroutine test_tank_bad_input
end program test_orbit_chart
