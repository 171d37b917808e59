!> Two-parameter continuation of codimension-1 bifurcation curves of equilibria of
!> x' = f(x; p1, p2), x in R^n (n small), with the codimension-2 points on them located and the
!> first Lyapunov coefficient along Hopf curves (Yu. A. Kuznetsov, Elements of Applied Bifurcation
!> Theory, 3rd ed. 2004, ch. 3, 8 and 10.2; W. Govaerts, Numerical Methods for Bifurcations of
!> Dynamical Equilibria, SIAM 2000; the defining systems and test functions of MATCONT).
!>
!> Fold curves: the minimally augmented system (Govaerts; MATCONT's limit point curve)
!>   f(x, p) = 0,   g(x, p) = 0,   where  [J  b] [v]   [0]        [J^T  c] [w]   [0]
!>                                         [c^T 0] [g] = [1]  and   [b^T  0] [g] = [1],
!> J = df/dx. g = 0 exactly where J is singular (if the border vectors b, c are not orthogonal to
!> the left and right null vectors), and g_z = -w^T (dJ/dz) v, so the Jacobian needs only one
!> derivative of J in the direction v. n + 1 unknowns (x and one parameter) besides the
!> continuation parameter, against 2n + 1 for the standard system (f, J v, <v, v0> - 1); it is
!> regular at cusp and Bogdanov-Takens points, so the fold curve runs through both.
!>
!> Hopf curves: the standard (extended) system with kappa = omega^2 (Kuznetsov sec 10.2.2)
!>   f(x, p) = 0,   (J^2 + kappa I) v = 0,   <v_ref, v> = 1,   <u_ref, v> = 0,
!> where v_ref, u_ref are an orthonormal basis of the eigenplane at the start of a segment. v
!> spans with J v the real eigenplane of +-i omega, so the eigenvector q = v - i J v/omega comes
!> free for the Lyapunov coefficient; everything stays real; the system is regular at
!> Bogdanov-Takens points (kappa = 0), where the curve turns into a neutral-saddle curve
!> (kappa < 0: real eigenvalues +-sqrt(-kappa)), and at zero-Hopf points. Its 2n + 2 unknowns are
!> few for the small n here (the minimally augmented bialternate-product system would need
!> matrices of order n(n-1)/2 and their derivatives).
!>
!> Continuation: sloshdyn_continuation's continue_branch (Keller's pseudo-arclength method) with
!> one parameter as lambda and the other among the unknowns, in segments of a few points: at the
!> start of each segment the border vectors (fold) or reference vectors (Hopf) are refreshed from
!> the current point, so they never become orthogonal to the null vectors (as MATCONT adapts its
!> borders), and lambda is the parameter with the larger component of the curve's tangent, so a
!> segment never starts where the curve is vertical in its lambda. continue_branch passes turning
!> points of lambda inside a segment (the cusp, where the fold curve turns back in parameter
!> space, is one). A segment also ends before the null vectors have turned by more than 60 degrees
!> from its borders (|v| > 2 with <c, v> = 1): further on, the bordered matrix would pass a
!> singularity where v, and with it the test functions, change sign (a step that turns them
!> that far at once is retried shorter). Variables are scaled, x = x_scale y and
!> p = p0 + p_scale q, so that the arclength weighs state and parameters alike; kappa is scaled
!> by its start value.
!>
!> Codimension-2 points, as zeros of test functions between consecutive points, located by
!> locate_zero_on_branch (Brent's method on the arclength, to 1e-12 of the step):
!>   on fold curves  (tests(1:3) of each point)
!>     Bogdanov-Takens (BT)  <w, v>/(|w| |v|) (the zero eigenvalue has algebraic multiplicity 2)
!>     cusp (CP)             <w^, B(v^, v^)>, unit v^, w^ (the quadratic normal-form coefficient
!>                           a = <p, B(q, q)>/2, <p, q> = 1, vanishes)
!>     zero-Hopf (ZH)        prod_{i<j} (mu_i + mu_j) over the eigenvalues but the one closest
!>                           to 0; confirmed by a pair on the imaginary axis (a real pair +-mu,
!>                           a neutral saddle, is no bifurcation and is not reported)
!>   on Hopf curves
!>     Bogdanov-Takens (BT)  kappa = omega^2
!>     zero-Hopf (ZH)        det J (with kappa > 0)
!>     generalised Hopf (GH) l1 (Bautin point)
!> with B(u, v) = D^2_x f[u, v], C(u, v, w) = D^3_x f[u, v, w]. A located zero must be small
!> against the values at the ends of its bracket (l1 changes sign through a pole at a zero-Hopf
!> point); on a Hopf curve, the zero of det J at a Bogdanov-Takens point (det J = kappa times the
!> other eigenvalues) is that BT point. Double-Hopf points are not detected.
!>
!> First Lyapunov coefficient (Kuznetsov eq. (3.20) of the 3rd edition, (5.39) of the 2nd):
!>   l1 = Re[ <p, C(q, q, conj q)> - 2 <p, B(q, J^-1 B(q, conj q))>
!>           + <p, B(conj q, (2 i omega I - J)^-1 B(q, q))> ] / (2 omega)
!> with J q = i omega q, J^T p = -i omega p, <q, q> = 1 and <p, q> = conj(p)^T q = 1 (the
!> normalisation of Kuznetsov's n-dimensional formula and of MATCONT). l1 < 0: supercritical
!> (stable cycles are born), l1 > 0: subcritical. Its value depends on the normalisation of q,
!> its sign does not: x' = -omega y + l x r^2, y' = omega x + l y r^2 has l1 = 2 l/omega.
!>
!> Curves end on the parameter box, as closed loops, beyond x_max, or (Hopf, unless
!> neutral_saddles) at a Bogdanov-Takens point; a curve that stops for any other reason (a failed
!> step, max_points) comes back with complete = .false., a nonzero status and the reason.
!>
!> Public: the field type two_parameter_field (evaluate; jacobian_derivative, second_derivative,
!> third_derivative with finite-difference defaults), curve_options, bifurcation_curve (with its
!> codim2_point list), fold_curve and hopf_curve (a curve through a start point),
!> first_lyapunov_coefficient, correct_to_curve (a fold or Hopf point at a fixed parameter),
!> curve_crossings (where a computed curve crosses p_k = level), check_curve_options, and the
!> CURVE_*, CODIM2_* and END_* codes with codim2_name, curve_kind_name and curve_end_name.
!>
!> Extension interface (for defining systems in other modules, as the integrator components of
!> sloshdyn_ode are public for the methods): a field chooses the defining system of each curve
!> kind through its binding defining_system (for flows: the fold and Hopf systems of
!> sloshdyn_fold_hopf; sloshdyn_map_bifurcation overrides it for fixed points of maps: fold,
!> period-doubling and Neimark-Sacker curves). A defining system extends curve_system (or
!> fold_system, hopf_system) and names its own test functions (n_tests <= max_curve_tests) with
!> the codimension-2 kind of each, the tests that mask it and the ends it makes (tables given to
!> setup_system), and its bindings (confirm_codim2, codim2_frequency, neutral_saddle,
!> frequency_of); everything else -- segments, border refreshes, box, closure,
!> locating the codimension-2 points, end reasons, correct_to_curve and curve_crossings -- is
!> shared; curve_of_kind traces a curve of any kind (fold_curve and hopf_curve call it). The
!> helpers such systems need (setup_system, split_x_p, point_x_p, inverse_iteration,
!> null_vectors, nearest_pair, trace_curve, correct_state) are public for them.
!>
!> The parts: this module (the types, the public routines, the shared helpers); its submodules
!> sloshdyn_bifurcation_tracer (the curve tracer: segments, box, closure, codimension-2 points)
!> and sloshdyn_bifurcation_systems (the systems a field of a flow chooses, the Lyapunov
!> coefficient); the modules sloshdyn_fold_hopf (the fold and Hopf defining systems) and
!> sloshdyn_lyapunov_coefficient (Hopf points and l1).
module sloshdyn_bifurcation
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_value, ieee_quiet_nan
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, SD_NOT_CONVERGED, SD_SINGULAR, SD_CAPACITY, &
                             check_real
  use sloshdyn_text, only: num2str
  use sloshdyn_lapack, only: solve_linear
  use sloshdyn_continuation, only: parametrised_system, branch_test, continuation_options, &
                                   newton_solve, continue_branch, branch_tangent, &
                                   locate_zero_on_branch, continuation_check_options, &
                                   STOP_LAMBDA_MIN, STOP_LAMBDA_MAX, STOP_MAX_POINTS, STOP_CLOSED, &
                                   STOP_FAILED
  implicit none
  private
  public :: two_parameter_field, field_evaluate, field_jacobian_derivative, &
            field_second_derivative, field_third_derivative
  public :: curve_options, bifurcation_curve, codim2_point
  public :: fold_curve, hopf_curve, first_lyapunov_coefficient, correct_to_curve, &
            curve_crossings, check_curve_options, codim2_name, curve_end_name, curve_kind_name
  public :: CURVE_FOLD, CURVE_HOPF, CURVE_PERIOD_DOUBLING, CURVE_NEIMARK_SACKER, &
            CODIM2_BT, CODIM2_CUSP, CODIM2_ZH, CODIM2_GH, CODIM2_R1, CODIM2_R2, CODIM2_R3, &
            CODIM2_R4, CODIM2_FOLD_FLIP, CODIM2_FOLD_NS, CODIM2_FLIP_NS, CODIM2_GF, CODIM2_CH, &
            END_START, END_BOX, END_CLOSED, END_X_MAX, END_BT, END_MAX_POINTS, END_FAILED, &
            END_RESONANCE
  ! the extension interface (module header)
  public :: curve_system, system_refresh, system_diagnose, system_alignment, &
            max_curve_tests, trace_curve, correct_state, setup_system, &
            split_x_p, point_x_p, inverse_iteration, null_vectors, nearest_pair, &
            field_defining_system, &
            curve_of_kind

  !> Curve kinds: of equilibria of flows (fold, Hopf) and of fixed points of maps (fold,
  !> period doubling, Neimark-Sacker; sloshdyn_map_bifurcation).
  integer, parameter :: CURVE_FOLD = 1, CURVE_HOPF = 2, CURVE_PERIOD_DOUBLING = 3, &
                        CURVE_NEIMARK_SACKER = 4
  !> Kinds of codimension-2 points (codim2_name gives the words).
  integer, parameter :: CODIM2_BT = 1    !< Bogdanov-Takens: double zero eigenvalue
  integer, parameter :: CODIM2_CUSP = 2  !< cusp: fold with a = 0
  integer, parameter :: CODIM2_ZH = 3    !< zero-Hopf (fold-Hopf): 0 and +-i omega
  integer, parameter :: CODIM2_GH = 4    !< generalised Hopf (Bautin): l1 = 0
  !> ... of fixed points of maps (multipliers mu of M = dP/dx)
  integer, parameter :: CODIM2_R1 = 5    !< 1:1 resonance: double mu = +1 (Jordan block)
  integer, parameter :: CODIM2_R2 = 6    !< 1:2 resonance: double mu = -1 (Jordan block)
  integer, parameter :: CODIM2_R3 = 7    !< 1:3 resonance: Neimark-Sacker with theta = 2 pi/3
  integer, parameter :: CODIM2_R4 = 8    !< 1:4 resonance: Neimark-Sacker with theta = pi/2
  integer, parameter :: CODIM2_FOLD_FLIP = 9   !< fold-flip: mu = +1 and mu = -1
  integer, parameter :: CODIM2_FOLD_NS = 10    !< fold-Neimark-Sacker: +1 and e^{+-i theta}
  integer, parameter :: CODIM2_FLIP_NS = 11    !< flip-Neimark-Sacker: -1 and e^{+-i theta}
  integer, parameter :: CODIM2_GF = 12   !< generalised flip: the flip coefficient c = 0
  integer, parameter :: CODIM2_CH = 13   !< Chenciner: the Neimark-Sacker coefficient d = 0
  !> How an end of a curve came about (curve_end_name gives the words).
  integer, parameter :: END_START = 0       !< the start point (a curve traced one way only)
  integer, parameter :: END_BOX = 1         !< on the boundary of the parameter box
  integer, parameter :: END_CLOSED = 2      !< closed curve: back at the start point
  integer, parameter :: END_X_MAX = 3       !< the last point has max|x| > x_max
  integer, parameter :: END_BT = 4          !< Hopf curve at a Bogdanov-Takens point
  integer, parameter :: END_MAX_POINTS = 5  !< max_points computed (incomplete)
  integer, parameter :: END_FAILED = 6      !< no continuation step converged (incomplete)
  !> Neimark-Sacker curve at a 1:1 or 1:2 resonance (the pair leaves the unit circle as a
  !> double +1 or -1)
  integer, parameter :: END_RESONANCE = 7
  !> The most test functions a defining system may have.
  integer, parameter :: max_curve_tests = 7

  !> A vector field f(x; p1, p2) with its derivatives. evaluate is required; the higher
  !> derivatives default to finite differences of the Jacobian (central, steps eps^(1/3) and
  !> eps^(1/4); errors ~1e-10 and ~1e-7 relative for smooth fields of unit scale): override them
  !> with exact ones where the field is polynomial.
  type, abstract :: two_parameter_field
  contains
    procedure(field_evaluate), deferred :: evaluate
    procedure :: jacobian_derivative => fd_jacobian_derivative
    procedure :: second_derivative => default_second_derivative
    procedure :: third_derivative => fd_third_derivative
    !> the defining system of a curve kind (extension interface; fields of flows: fold, Hopf)
    procedure :: defining_system => field_defining_system
  end type two_parameter_field

  abstract interface
    !> f = f(x, p) (n), fx = df/dx (n x n), fp = df/dp (n x 2)
    subroutine field_evaluate(self, x, p, f, fx, fp)
      import :: wp, two_parameter_field
      class(two_parameter_field), intent(in) :: self
      real(wp), intent(in) :: x(:), p(2)
      real(wp), intent(out) :: f(:), fx(:, :), fp(:, :)
    end subroutine field_evaluate

    !> hx = d(J u)/dx (n x n), i.e. hx v = B(u, v); hp = d(J u)/dp (n x 2), u held fixed
    subroutine field_jacobian_derivative(self, x, p, u, hx, hp)
      import :: wp, two_parameter_field
      class(two_parameter_field), intent(in) :: self
      real(wp), intent(in) :: x(:), p(2), u(:)
      real(wp), intent(out) :: hx(:, :), hp(:, :)
    end subroutine field_jacobian_derivative

    !> b = B(u, v) = D^2_x f[u, v]
    subroutine field_second_derivative(self, x, p, u, v, b)
      import :: wp, two_parameter_field
      class(two_parameter_field), intent(in) :: self
      real(wp), intent(in) :: x(:), p(2), u(:), v(:)
      real(wp), intent(out) :: b(:)
    end subroutine field_second_derivative

    !> c = C(u, v, w) = D^3_x f[u, v, w]
    subroutine field_third_derivative(self, x, p, u, v, w, c)
      import :: wp, two_parameter_field
      class(two_parameter_field), intent(in) :: self
      real(wp), intent(in) :: x(:), p(2), u(:), v(:), w(:)
      real(wp), intent(out) :: c(:)
    end subroutine field_third_derivative
  end interface

  !> Settings of a curve. Unknowns are scaled: x = x_scale y, p = p_start + p_scale q; the
  !> continuation steps (continuation%ds, ds_min, ds_max) are arclengths in (y, q) (and the
  !> eigenvector and kappa/kappa_start of a Hopf curve).
  type :: curve_options
    real(wp) :: p_min(2) = -huge(1.0_wp)  !< the parameter box: the curve ends on its boundary
    real(wp) :: p_max(2) = huge(1.0_wp)
    real(wp) :: x_scale = 1               !< typical size of x, > 0
    real(wp) :: p_scale(2) = 1            !< typical change of p along the curve, > 0
    real(wp) :: x_max = huge(1.0_wp)      !< end after the first point with max|x| > x_max
    integer :: max_points = 2000          !< points of the whole curve (both ways), >= 3
    !> 0: both ways from the start point; +1 / -1: only the way in which p2 increases /
    !> decreases at the start (p1 if p2 does not move there)
    integer :: direction = 0
    integer :: segment_points = 25        !< points per segment (borders refreshed), >= 3
    !> Hopf curves: continue through Bogdanov-Takens points as neutral-saddle curves (kappa < 0)
    logical :: neutral_saddles = .false.
    !> steps and Newton settings; lambda_min/max, direction, max_points, x_max and x_scale are
    !> set by the curve routines
    type(continuation_options) :: continuation = continuation_options(ds=0.01_wp, &
      ds_min=1.0e-10_wp, ds_max=0.1_wp)
  end type curve_options

  !> A codimension-2 point on a curve: also column `index` of the curve's arrays.
  type :: codim2_point
    integer :: kind = 0                !< CODIM2_*
    integer :: index = 0               !< its column in the curve
    real(wp) :: p(2) = 0
    !> zero-Hopf, generalised Hopf: the frequency; maps: the angle theta of the multipliers
    !> on the unit circle (R1: 0, R2: pi, R3: 2 pi/3, R4: pi/2, fold-NS, flip-NS: theta); else 0
    real(wp) :: omega = 0
    real(wp), allocatable :: x(:)
  end type codim2_point

  !> A computed curve, columns in order along it (the start point is somewhere inside when the
  !> curve was traced both ways).
  type :: bifurcation_curve
    integer :: kind = 0                  !< CURVE_*
    integer :: n = 0                     !< dimension of x
    integer :: n_points = 0
    real(wp), allocatable :: x(:, :)     !< (n, n_points)
    real(wp), allocatable :: p(:, :)     !< (2, n_points)
    !> eigenvalues of J (n, n_points); of a map's curve: its multipliers (of M)
    real(wp), allocatable :: eig_re(:, :), eig_im(:, :)
    !> test functions (n_tests, n_points): fold (BT, cusp, ZH), Hopf (BT = kappa, ZH = det J,
    !> GH = l1) (3 each); those of map curves: sloshdyn_map_bifurcation
    real(wp), allocatable :: tests(:, :)
    !> Hopf: omega = sqrt(kappa), or -sqrt(-kappa) on a neutral-saddle part; fold: 0;
    !> Neimark-Sacker: theta (sloshdyn_map_bifurcation)
    real(wp), allocatable :: omega(:)
    real(wp), allocatable :: l1(:)       !< Hopf: first Lyapunov coefficient (NaN if kappa <= 0)
    integer, allocatable :: special(:)   !< CODIM2_* of the point, 0 for a regular point
    integer :: n_codim2 = 0
    type(codim2_point), allocatable :: codim2(:)
    !> how the first and the last column came about (END_*)
    integer :: end_reason(2) = END_START
    logical :: complete = .false.
    !> the status and message the curve routine returned (why it is not complete)
    integer :: status = SD_OK
    character(len=message_len) :: message = ''
    !> sign changes of a test function whose zero could not be located, and why (the first)
    integer :: n_unlocated = 0
    character(len=message_len) :: unlocated_message = ''
    integer :: start_index = 0           !< column of the start point
  end type bifurcation_curve

  ! ---- the extension interface (module header) -----------------------------------------

  !> An augmented system in scaled variables: point z = (x/x_scale, extra, q_other), lambda =
  !> q_lam, q = (p - p_ref)/p_scale; the state s = (x, extra, p1, p2) is the same point
  !> unscaled in x and p. Its test functions tests(1:n_tests) name codimension-2 points by
  !> their zeros (codim2_kinds); setup_system gives the tables.
  type, abstract, extends(parametrised_system) :: curve_system
    class(two_parameter_field), allocatable :: field
    integer :: kind = 0                   !< CURVE_*
    integer :: n = 0, n_extra = 0
    integer :: n_tests = 0                !< <= max_curve_tests
    !> the CODIM2_* kind whose points are the zeros of tests(which)
    integer :: codim2_kinds(max_curve_tests) = 0
    !> a test whose sign change over the same step explains a zero of tests(which) (0: none)
    integer :: masks(max_curve_tests) = 0
    !> the END_* reason when a zero of tests(which) ends the curve (0: it never does; none
    !> does with curve_options%neutral_saddles)
    integer :: ends(max_curve_tests) = 0
    integer :: lam = 2, other = 1
    real(wp) :: x_scale = 1, p_scale(2) = 1, p_ref(2) = 0
  contains
    procedure(system_refresh), deferred :: refresh
    procedure(system_diagnose), deferred :: diagnose
    procedure(system_alignment), deferred :: alignment
    !> is a located zero of a test a codimension-2 point of its kind? (default: yes)
    procedure :: confirm_codim2 => confirm_always
    !> the frequency / angle reported with a codimension-2 point (default 0)
    procedure :: codim2_frequency => no_codim2_frequency
    !> may a corrected state be a point of the curve? (not unless neutral_saddles, where
    !> neutral_saddle describes it)
    procedure :: check_point => check_point
    !> '' or what the state s is instead of a point of the curve (default '')
    procedure :: neutral_saddle => no_neutral_saddle
    !> the frequency / angle of the state s (default 0)
    procedure :: frequency_of => no_frequency
  end type curve_system

  abstract interface
    !> New border / reference vectors from the state s (which may be renormalised).
    subroutine system_refresh(self, s, status, message)
      import :: wp, message_len, curve_system
      class(curve_system), intent(inout) :: self
      real(wp), intent(inout) :: s(:)
      integer, intent(out) :: status
      character(len=message_len), intent(out) :: message
    end subroutine system_refresh

    !> How far the border / reference vectors have turned from the null vectors at the point z:
    !> 1/cos of the angle (1 at the start of a segment; infinite where the bordered system is
    !> singular).
    function system_alignment(self, z) result(growth)
      import :: wp, curve_system
      class(curve_system), intent(in) :: self
      real(wp), intent(in) :: z(:)
      real(wp) :: growth
    end function system_alignment

    !> Eigenvalues (of J; of M for maps), the test functions (tests(1:n_tests), the rest NaN),
    !> omega and l1 at the point z = (.., lambda).
    subroutine system_diagnose(self, z, re, im, tests, omega, l1, status, message)
      import :: wp, message_len, curve_system, max_curve_tests
      class(curve_system), intent(in) :: self
      real(wp), intent(in) :: z(:)
      real(wp), intent(out) :: re(:), im(:), tests(max_curve_tests), omega, l1
      integer, intent(out) :: status
      character(len=message_len), intent(out) :: message
    end subroutine system_diagnose
  end interface

  interface
    !> The first Lyapunov coefficient l1 (see the module header) at the Hopf point (x, p), with
    !> omega > 0 of the complex pair of J closest to the imaginary axis.
    module subroutine first_lyapunov_coefficient(field, x, p, l1, omega, status, message)
      class(two_parameter_field), intent(in) :: field
      real(wp), intent(in) :: x(:), p(2)
      real(wp), intent(out) :: l1, omega
      integer, intent(out) :: status
      character(len=message_len), intent(out) :: message
    end subroutine first_lyapunov_coefficient

    !> The defining system of a fold or Hopf curve of equilibria with its first borders /
    !> reference data, and the start state s0 = (x0, [v, kappa/kappa_scale,] p0) (the default
    !> defining_system of a field; kind is one of CURVE_*).
    module subroutine field_defining_system(field, kind, x0, p0, options, proto, s0, status, &
                                           message)
      class(two_parameter_field), intent(in) :: field
      integer, intent(in) :: kind
      real(wp), intent(in) :: x0(:), p0(2)
      type(curve_options), intent(in) :: options
      class(curve_system), allocatable, intent(out) :: proto
      real(wp), allocatable, intent(out) :: s0(:)
      integer, intent(out) :: status
      character(len=message_len), intent(out) :: message
    end subroutine field_defining_system

    !> Newton on the defining system from the state s0 with lambda = p(fixed(1)) fixed (then
    !> fixed(2), ... if it fails); sys is the system that converged, s the corrected state, which
    !> must pass sys%check_point (a Hopf point must have kappa > 0).
    module subroutine correct_state(proto, s0, fixed, options, sys, s, status, message)
      class(curve_system), intent(in) :: proto
      real(wp), intent(in) :: s0(:)
      integer, intent(in) :: fixed(:)
      type(curve_options), intent(in) :: options
      class(curve_system), allocatable, intent(out) :: sys
      real(wp), allocatable, intent(out) :: s(:)
      integer, intent(out) :: status
      character(len=message_len), intent(out) :: message
    end subroutine correct_state

    !> Correct the start, find the tangent, trace both halves (or one) and assemble the curve.
    module subroutine trace_curve(proto, s0, options, curve, status, message)
      class(curve_system), intent(in) :: proto
      real(wp), intent(in) :: s0(:)
      type(curve_options), intent(in) :: options
      type(bifurcation_curve), intent(inout) :: curve
      integer, intent(out) :: status
      character(len=message_len), intent(out) :: message
    end subroutine trace_curve
  end interface

  !> Inverse iterations for null vectors at the start of a curve, and their relative shift.
  integer, parameter :: inverse_iterations = 4
  real(wp), parameter :: inverse_shift = 1.0e-10_wp

contains

  ! ---- the public routines ----------------------------------------------------------------

  !> The fold curve through (x0, p0), a fold of equilibria (f(x0, p0) = 0 with a simple zero
  !> eigenvalue, approximately: the point is first corrected with p2 fixed, or p1 if that fails).
  subroutine fold_curve(field, x0, p0, options, curve, status, message)
    class(two_parameter_field), intent(in) :: field
    real(wp), intent(in) :: x0(:), p0(2)
    type(curve_options), intent(in) :: options
    type(bifurcation_curve), intent(out) :: curve
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    call curve_of_kind(field, CURVE_FOLD, 'fold_curve', x0, p0, options, curve, status, message)
  end subroutine fold_curve

  !> The Hopf curve through (x0, p0), a Hopf point of equilibria (approximately: corrected as for
  !> fold_curve). Its eigenvalue pair is the complex pair of J closest to the imaginary axis.
  subroutine hopf_curve(field, x0, p0, options, curve, status, message)
    class(two_parameter_field), intent(in) :: field
    real(wp), intent(in) :: x0(:), p0(2)
    type(curve_options), intent(in) :: options
    type(bifurcation_curve), intent(out) :: curve
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    call curve_of_kind(field, CURVE_HOPF, 'hopf_curve', x0, p0, options, curve, status, message)
  end subroutine hopf_curve

  !> The curve of the given kind (CURVE_*) through (x0, p0), for the public routines here and
  !> in other modules (sloshdyn_map_bifurcation): the status and message (prefixed by caller)
  !> are also kept in the curve.
  subroutine curve_of_kind(field, kind, caller, x0, p0, options, curve, status, message)
    class(two_parameter_field), intent(in) :: field
    integer, intent(in) :: kind
    character(len=*), intent(in) :: caller
    real(wp), intent(in) :: x0(:), p0(2)
    type(curve_options), intent(in) :: options
    type(bifurcation_curve), intent(out) :: curve
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    call any_curve(field, kind, x0, p0, options, curve, status, message)
    if (status /= SD_OK) message = caller//': '//trim(message)
    curve%status = status
    curve%message = message
  end subroutine curve_of_kind

  !> The fold (kind = CURVE_FOLD) or Hopf point (CURVE_HOPF) near (x_guess, p_guess) with
  !> p(fixed) = p_guess(fixed): Newton on the defining system with the other parameter free
  !> (options gives the scales and the Newton settings). omega: the Hopf frequency (0 for a fold).
  !> For a map (sloshdyn_map_bifurcation) also CURVE_PERIOD_DOUBLING and CURVE_NEIMARK_SACKER
  !> (omega: the angle theta of the multipliers).
  subroutine correct_to_curve(field, kind, x_guess, p_guess, fixed, options, x, p, omega, &
                              status, message)
    class(two_parameter_field), intent(in) :: field
    integer, intent(in) :: kind, fixed
    real(wp), intent(in) :: x_guess(:), p_guess(2)
    type(curve_options), intent(in) :: options
    real(wp), intent(out) :: x(:), p(2), omega
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    class(curve_system), allocatable :: proto, sys
    real(wp), allocatable :: s0(:), s(:)
    integer :: n

    n = size(x_guess)
    x = x_guess
    p = p_guess
    omega = 0
    call check_start(x_guess, p_guess, options, status, message)
    if (status == SD_OK .and. (fixed < 1 .or. fixed > 2)) then
      status = SD_BAD_INPUT
      message = 'fixed = '//num2str(fixed)//' is out of range: it must be 1 or 2'
    end if
    if (status == SD_OK) call check_kind(kind, status, message)
    if (status == SD_OK) call field%defining_system(kind, x_guess, p_guess, options, proto, s0, &
                                                    status, message)
    if (status == SD_OK) call correct_state(proto, s0, [fixed], options, sys, s, status, message)
    if (status /= SD_OK) then
      message = 'correct_to_curve: '//trim(message)
      return
    end if
    x = s(1:n)
    p = s(size(s) - 1:size(s))
    omega = sys%frequency_of(s)
  end subroutine correct_to_curve

  !> The points of a computed curve where p(k) = level, each corrected onto the curve
  !> (correct_to_curve from the interpolation between the columns around it): x(:, 1:n_found),
  !> p(:, 1:n_found). x needs curve%n rows; more crossings than columns of x: SD_CAPACITY (the
  !> first ones are returned).
  subroutine curve_crossings(field, curve, k, level, options, x, p, n_found, status, message)
    class(two_parameter_field), intent(in) :: field
    type(bifurcation_curve), intent(in) :: curve
    integer, intent(in) :: k
    real(wp), intent(in) :: level
    type(curve_options), intent(in) :: options
    real(wp), intent(out) :: x(:, :), p(:, :)
    integer, intent(out) :: n_found, status
    character(len=message_len), intent(out) :: message
    real(wp) :: a, b, theta, xg(curve%n), pg(2), omega
    integer :: j

    n_found = 0
    status = SD_OK
    message = ''
    if (k < 1 .or. k > 2) then
      status = SD_BAD_INPUT
      message = 'k = '//num2str(k)//' is out of range: it must be 1 or 2'
      return
    end if
    if (size(x, 1) /= curve%n .or. size(p, 1) /= 2 .or. size(p, 2) < size(x, 2)) then
      status = SD_BAD_INPUT
      message = 'x needs n = '//num2str(curve%n)//' rows and p 2 rows and as many columns'
      return
    end if
    do j = 1, curve%n_points
      a = curve%p(k, j) - level
      b = a
      if (j < curve%n_points) b = curve%p(k, j + 1) - level
      if (a == 0) then
        theta = 0
      else if (j < curve%n_points .and. a*b < 0) then
        theta = a/(a - b)
      else
        cycle
      end if
      if (n_found == size(x, 2)) then
        status = SD_CAPACITY
        message = 'curve_crossings: more than '//num2str(size(x, 2))//' crossings'
        return
      end if
      xg = curve%x(:, j)
      pg = curve%p(:, j)
      if (theta > 0) then
        xg = xg + theta*(curve%x(:, j + 1) - xg)
        pg = pg + theta*(curve%p(:, j + 1) - pg)
      end if
      pg(k) = level
      call correct_to_curve(field, curve%kind, xg, pg, k, options, x(:, n_found + 1), &
                            p(:, n_found + 1), omega, status, message)
      if (status /= SD_OK) then
        message = 'curve_crossings: at p'//achar(iachar('0') + k)//' = '//num2str(level)// &
                  ' (column '//num2str(j)//'): '//trim(message)
        return
      end if
      n_found = n_found + 1
    end do
  end subroutine curve_crossings

  !> The rules for curve_options (every reader applies them).
  pure subroutine check_curve_options(options, status, message)
    type(curve_options), intent(in) :: options
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    real(wp), parameter :: big = huge(1.0_wp)
    integer :: k
    character(len=2) :: name

    if (status /= SD_OK) return
    do k = 1, 2
      name = 'p'//achar(iachar('0') + k)
      if (status == SD_OK .and. .not. options%p_min(k) < options%p_max(k)) then
        status = SD_BAD_INPUT
        message = name//'_min = '//num2str(options%p_min(k))//' is out of range: the box '// &
                  'needs '//name//'_min < '//name//'_max = '//num2str(options%p_max(k))
      end if
      call check_real(name//'_scale', options%p_scale(k), 0.0_wp, big, .true., .false., &
                      name//'_scale must be > 0', status, message)
    end do
    call check_real('x_scale', options%x_scale, 0.0_wp, big, .true., .false., &
                    'x_scale must be > 0', status, message)
    if (status == SD_OK .and. .not. options%x_max > 0) then
      status = SD_BAD_INPUT
      message = 'x_max = '//num2str(options%x_max)//' is out of range: it must be > 0'
    end if
    if (status == SD_OK .and. options%max_points < 3) then
      status = SD_BAD_INPUT
      message = 'max_points = '//num2str(options%max_points)//' is out of range: it must be >= 3'
    end if
    if (status == SD_OK .and. options%segment_points < 3) then
      status = SD_BAD_INPUT
      message = 'segment_points = '//num2str(options%segment_points)// &
                ' is out of range: it must be >= 3'
    end if
    if (status == SD_OK .and. abs(options%direction) > 1) then
      status = SD_BAD_INPUT
      message = 'direction = '//num2str(options%direction)//' is out of range: it must be 0 '// &
                '(both ways), +1 or -1'
    end if
    if (status == SD_OK) call continuation_check_options(options%continuation, status, message)
  end subroutine check_curve_options

  !> Words for a CODIM2_* code.
  pure function codim2_name(kind) result(name)
    integer, intent(in) :: kind
    character(len=:), allocatable :: name
    character(len=*), parameter :: names(0:CODIM2_CH) = [character(len=19) :: 'regular', &
      'Bogdanov-Takens', 'cusp', 'zero-Hopf', 'generalised Hopf', '1:1 resonance', &
      '1:2 resonance', '1:3 resonance', '1:4 resonance', 'fold-flip', 'fold-Neimark-Sacker', &
      'flip-Neimark-Sacker', 'generalised flip', 'Chenciner']
    name = trim(names(merge(kind, 0, kind >= 0 .and. kind <= CODIM2_CH)))
  end function codim2_name

  !> Words for a CURVE_* code.
  pure function curve_kind_name(kind) result(name)
    integer, intent(in) :: kind
    character(len=:), allocatable :: name
    character(len=*), parameter :: names(0:CURVE_NEIMARK_SACKER) = [character(len=15) :: &
      'unknown', 'fold', 'Hopf', 'period-doubling', 'Neimark-Sacker']
    name = trim(names(merge(kind, 0, kind >= 1 .and. kind <= CURVE_NEIMARK_SACKER)))
  end function curve_kind_name

  !> Words for an END_* code.
  pure function curve_end_name(reason) result(name)
    integer, intent(in) :: reason
    character(len=:), allocatable :: name
    character(len=*), parameter :: names(-1:END_RESONANCE) = [character(len=22) :: &
      'unknown end', 'start point', 'parameter box', 'closed curve', 'max|x| exceeded x_max', &
      'Bogdanov-Takens point', 'max_points computed', 'step fell below ds_min', &
      '1:1 or 1:2 resonance']
    name = trim(names(merge(reason, -1, reason >= END_START .and. reason <= END_RESONANCE)))
  end function curve_end_name

  ! ---- default higher derivatives -----------------------------------------------------------

  !> Central differences of the Jacobian: hx = (J(x + h u) - J(x - h u))/(2h), hp likewise in p.
  subroutine fd_jacobian_derivative(self, x, p, u, hx, hp)
    class(two_parameter_field), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2), u(:)
    real(wp), intent(out) :: hx(:, :), hp(:, :)
    real(wp) :: f(size(x)), jp(size(x), size(x)), jm(size(x), size(x)), fp(size(x), 2), &
                h, u_norm, dp(2)
    real(wp), parameter :: step = epsilon(1.0_wp)**(1.0_wp/3)
    integer :: k

    hx = 0
    hp = 0
    u_norm = maxval(abs(u))
    if (u_norm > 0) then
      h = step*(1 + maxval(abs(x)))/u_norm
      call self%evaluate(x + h*u, p, f, jp, fp)
      call self%evaluate(x - h*u, p, f, jm, fp)
      hx = (jp - jm)/(2*h)
    end if
    do k = 1, 2
      dp = 0
      dp(k) = step*(1 + abs(p(k)))
      call self%evaluate(x, p + dp, f, jp, fp)
      call self%evaluate(x, p - dp, f, jm, fp)
      hp(:, k) = matmul(jp - jm, u)/(2*dp(k))
    end do
  end subroutine fd_jacobian_derivative

  !> B(u, v) = d(J u)/dx v.
  subroutine default_second_derivative(self, x, p, u, v, b)
    class(two_parameter_field), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2), u(:), v(:)
    real(wp), intent(out) :: b(:)
    real(wp) :: hx(size(x), size(x)), hp(size(x), 2)
    call self%jacobian_derivative(x, p, u, hx, hp)
    b = matmul(hx, v)
  end subroutine default_second_derivative

  !> C(u, v, w) = [J(x + h(u + w)) - J(x + h(u - w)) - J(x - h(u - w)) + J(x - h(u + w))] v/(4h^2)
  !> for unit-scaled u, w (the third-order terms cancel; error O(h^2) + O(eps/h^2)).
  subroutine fd_third_derivative(self, x, p, u, v, w, c)
    class(two_parameter_field), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2), u(:), v(:), w(:)
    real(wp), intent(out) :: c(:)
    real(wp) :: f(size(x)), fp(size(x), 2), j1(size(x), size(x)), j2(size(x), size(x)), &
                j3(size(x), size(x)), j4(size(x), size(x)), un(size(x)), wn(size(x)), &
                h, su, sw
    real(wp), parameter :: step = epsilon(1.0_wp)**0.25_wp

    c = 0
    su = maxval(abs(u))
    sw = maxval(abs(w))
    if (su == 0 .or. sw == 0) return
    un = u/su
    wn = w/sw
    h = step*(1 + maxval(abs(x)))
    call self%evaluate(x + h*(un + wn), p, f, j1, fp)
    call self%evaluate(x + h*(un - wn), p, f, j2, fp)
    call self%evaluate(x - h*(un - wn), p, f, j3, fp)
    call self%evaluate(x - h*(un + wn), p, f, j4, fp)
    c = su*sw*matmul(j1 - j2 - j3 + j4, v)/(4*h**2)
  end subroutine fd_third_derivative

  ! ---- the curve tracer ---------------------------------------------------------------------

  pure subroutine check_start(x0, p0, options, status, message)
    real(wp), intent(in) :: x0(:), p0(2)
    type(curve_options), intent(in) :: options
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    integer :: i, k

    status = SD_OK
    message = ''
    call check_curve_options(options, status, message)
    if (status == SD_OK .and. size(x0) < 1) then
      status = SD_BAD_INPUT
      message = 'x0 is empty'
    end if
    do i = 1, size(x0)
      call check_real('x0('//num2str(i)//')', x0(i), -huge(1.0_wp), huge(1.0_wp), .false., &
                      .false., 'must be finite', status, message)
    end do
    do k = 1, 2
      call check_real('p0('//num2str(k)//')', p0(k), options%p_min(k), options%p_max(k), &
                      .false., .false., 'the start point must lie in the parameter box ['// &
                      num2str(options%p_min(k))//', '//num2str(options%p_max(k))//']', &
                      status, message)
    end do
  end subroutine check_start

  !> The common part of a defining system: its field, kind, sizes, scales and reference point,
  !> and the tables of its tests (codim2_kinds: one per test; ends, masks: 0 if absent).
  subroutine setup_system(sys, field, kind, n, n_extra, p0, options, codim2_kinds, ends, masks)
    class(curve_system), intent(inout) :: sys
    class(two_parameter_field), intent(in) :: field
    integer, intent(in) :: kind, n, n_extra, codim2_kinds(:)
    real(wp), intent(in) :: p0(2)
    type(curve_options), intent(in) :: options
    integer, intent(in), optional :: ends(:), masks(:)
    allocate (sys%field, source=field)
    sys%kind = kind
    sys%n = n
    sys%n_extra = n_extra
    sys%n_tests = size(codim2_kinds)
    sys%codim2_kinds(1:sys%n_tests) = codim2_kinds
    if (present(ends)) sys%ends(1:size(ends)) = ends
    if (present(masks)) sys%masks(1:size(masks)) = masks
    sys%x_scale = options%x_scale
    sys%p_scale = options%p_scale
    sys%p_ref = p0
  end subroutine setup_system

  !> x and p of the point z = (.., q_other, lambda).
  pure subroutine point_x_p(sys, z, x, p)
    class(curve_system), intent(in) :: sys
    real(wp), intent(in) :: z(:)
    real(wp), intent(out) :: x(:), p(2)
    call split_x_p(sys, z(1:size(z) - 1), z(size(z)), x, p)
  end subroutine point_x_p

  !> x and p of the unknowns y = (.., q_other) and lambda (no temporary in evaluate).
  pure subroutine split_x_p(sys, y, lambda, x, p)
    class(curve_system), intent(in) :: sys
    real(wp), intent(in) :: y(:), lambda
    real(wp), intent(out) :: x(:), p(2)
    x = sys%x_scale*y(1:sys%n)
    p(sys%other) = sys%p_ref(sys%other) + sys%p_scale(sys%other)*y(size(y))
    p(sys%lam) = sys%p_ref(sys%lam) + sys%p_scale(sys%lam)*lambda
  end subroutine split_x_p

  !> Check, set up the defining system, trace the curve.
  subroutine any_curve(field, kind, x0, p0, options, curve, status, message)
    class(two_parameter_field), intent(in) :: field
    integer, intent(in) :: kind
    real(wp), intent(in) :: x0(:), p0(2)
    type(curve_options), intent(in) :: options
    type(bifurcation_curve), intent(inout) :: curve
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    class(curve_system), allocatable :: proto
    real(wp), allocatable :: s0(:)

    curve%kind = kind
    curve%n = size(x0)
    call check_start(x0, p0, options, status, message)
    if (status == SD_OK) call check_kind(kind, status, message)
    if (status /= SD_OK) return
    call field%defining_system(kind, x0, p0, options, proto, s0, status, message)
    if (status /= SD_OK) return
    call trace_curve(proto, s0, options, curve, status, message)
  end subroutine any_curve

  pure subroutine check_kind(kind, status, message)
    integer, intent(in) :: kind
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    if (status /= SD_OK) return
    if (kind < CURVE_FOLD .or. kind > CURVE_NEIMARK_SACKER) then
      status = SD_BAD_INPUT
      message = 'kind = '//num2str(kind)//' is out of range: CURVE_FOLD (1), CURVE_HOPF (2), '// &
                'CURVE_PERIOD_DOUBLING (3) or CURVE_NEIMARK_SACKER (4)'
    end if
  end subroutine check_kind

  ! ---- codimension-2 bookkeeping: defaults, fold and Hopf curves ----------------------------

  logical function confirm_always(self, kind, re, im, tests) result(confirmed)
    class(curve_system), intent(in) :: self
    integer, intent(in) :: kind
    real(wp), intent(in) :: re(:), im(:), tests(:)
    confirmed = .true.
  end function confirm_always

  real(wp) function no_codim2_frequency(self, kind, re, im, omega) result(frequency)
    class(curve_system), intent(in) :: self
    integer, intent(in) :: kind
    real(wp), intent(in) :: re(:), im(:), omega
    frequency = 0
  end function no_codim2_frequency

  !> A corrected state is a point of the curve unless it is a neutral saddle (neutral_saddle),
  !> which it may be with neutral_saddles.
  subroutine check_point(self, s, neutral_saddles, status, message)
    class(curve_system), intent(in) :: self
    real(wp), intent(in) :: s(:)
    logical, intent(in) :: neutral_saddles
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    character(len=:), allocatable :: saddle
    integer :: k
    status = SD_OK
    message = ''
    if (neutral_saddles) return
    saddle = self%neutral_saddle(s)
    if (len(saddle) == 0) return
    k = self%n + self%n_extra
    status = SD_BAD_INPUT
    message = 'the point converged to '//saddle//' at p = ('//num2str(s(k + 1))//', '// &
              num2str(s(k + 2))//'), not to a '//curve_kind_name(self%kind)//' point'
  end subroutine check_point

  function no_neutral_saddle(self, s) result(saddle)
    class(curve_system), intent(in) :: self
    real(wp), intent(in) :: s(:)
    character(len=:), allocatable :: saddle
    saddle = ''
  end function no_neutral_saddle

  real(wp) function no_frequency(self, s) result(frequency)
    class(curve_system), intent(in) :: self
    real(wp), intent(in) :: s(:)
    frequency = 0
  end function no_frequency

  !> singular a, even a = 0, is solvable).
  subroutine inverse_iteration(a, scale, v, status, message)
    real(wp), intent(in) :: a(:, :), scale
    real(wp), intent(out) :: v(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: shifted(size(v), size(v))
    integer :: i, iteration
    shifted = a
    do i = 1, size(v)
      shifted(i, i) = shifted(i, i) + inverse_shift*scale
      v(i) = 1 + 0.1_wp*i
    end do
    v = v/norm2(v)
    status = SD_OK
    message = ''
    do iteration = 1, inverse_iterations
      call solve_linear(shifted, v, status, message)
      if (status /= SD_OK) return
      if (.not. (all(ieee_is_finite(v)) .and. norm2(v) > 0)) then
        status = SD_SINGULAR
        message = 'inverse iteration failed (not finite)'
        return
      end if
      v = v/norm2(v)
    end do
  end subroutine inverse_iteration

  !> Unit vectors v, w near the right and left null spaces of the nearly singular a (inverse
  !> iteration on a and a^T relative to max|a_ij|).
  subroutine null_vectors(a, v, w, status, message)
    real(wp), intent(in) :: a(:, :)
    real(wp), intent(out) :: v(:), w(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: scale
    scale = max(maxval(abs(a)), tiny(1.0_wp))
    call inverse_iteration(a, scale, v, status, message)
    if (status == SD_OK) call inverse_iteration(transpose(a), scale, w, status, message)
  end subroutine null_vectors

  !> The eigenvalue re + i im with im > im_floor whose distance(i) is least (the first of equal
  !> ones) and at most max_distance, 0 if there is none: with distance |re|, the complex pair
  !> closest to the imaginary axis; with ||mu| - 1|, the multiplier pair nearest the unit circle.
  pure integer function nearest_pair(im, distance, im_floor, max_distance) result(best)
    real(wp), intent(in) :: im(:), distance(:), im_floor, max_distance
    integer :: i
    best = 0
    do i = 1, size(im)
      if (im(i) <= im_floor .or. distance(i) > max_distance) cycle
      if (best == 0) then
        best = i
      else if (distance(i) < distance(best)) then
        best = i
      end if
    end do
  end function nearest_pair
end module sloshdyn_bifurcation
