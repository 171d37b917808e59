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
!> kind through its binding defining_system (here: fold and Hopf systems of equilibria;
!> sloshdyn_map_bifurcation overrides it for fixed points of maps: fold, period-doubling and
!> Neimark-Sacker curves). A defining system extends curve_system (or fold_system, hopf_system)
!> and names its own test functions (n_tests <= max_curve_tests) and codimension-2 kinds
!> (codim2_kind, confirm_codim2, codim2_frequency, masked_by, terminal, check_point,
!> frequency_of); everything else -- segments, border refreshes, box, closure, locating the
!> codimension-2 points, end reasons, correct_to_curve and curve_crossings -- is shared;
!> curve_of_kind traces a curve of any kind (fold_curve and hopf_curve call it). The helpers such
!> systems need (setup_system, split_x_p, point_x_p, bordered_vectors, inverse_iteration,
!> trace_curve, correct_state) are public for them.
module sloshdyn_bifurcation
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_value, ieee_quiet_nan
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, SD_NOT_CONVERGED, SD_SINGULAR, SD_CAPACITY, &
                             check_real
  use sloshdyn_text, only: num2str
  use sloshdyn_lapack, only: eigenvalues, solve_linear
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
            CODIM2_R4, CODIM2_FOLD_FLIP, CODIM2_FOLD_NS, CODIM2_FLIP_NS, &
            END_START, END_BOX, END_CLOSED, END_X_MAX, END_BT, END_MAX_POINTS, END_FAILED, &
            END_RESONANCE
  ! the extension interface (module header)
  public :: curve_system, fold_system, hopf_system, system_refresh, system_diagnose, &
            system_alignment, system_codim2_kind, max_curve_tests, trace_curve, &
            correct_state, setup_system, split_x_p, point_x_p, bordered_vectors, &
            inverse_iteration, field_defining_system, curve_of_kind

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
  integer, parameter :: max_curve_tests = 6

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
  !> their zeros (codim2_kind).
  type, abstract, extends(parametrised_system) :: curve_system
    class(two_parameter_field), allocatable :: field
    integer :: kind = 0                   !< CURVE_*
    integer :: n = 0, n_extra = 0
    integer :: n_tests = 3                !< <= max_curve_tests
    integer :: lam = 2, other = 1
    real(wp) :: x_scale = 1, p_scale(2) = 1, p_ref(2) = 0
  contains
    procedure(system_refresh), deferred :: refresh
    procedure(system_diagnose), deferred :: diagnose
    procedure(system_alignment), deferred :: alignment
    procedure(system_codim2_kind), deferred :: codim2_kind
    !> is a located zero of a test a codimension-2 point of its kind? (default: yes)
    procedure :: confirm_codim2 => confirm_always
    !> the frequency / angle reported with a codimension-2 point (default 0)
    procedure :: codim2_frequency => no_codim2_frequency
    !> a test whose sign change over the same step explains a zero of this one (default 0)
    procedure :: masked_by => no_mask
    !> the END_* reason if a codimension-2 kind ends the curve (default 0: it never does)
    procedure :: terminal => never_terminal
    !> may a corrected state be a point of the curve? (default: yes)
    procedure :: check_point => any_point
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

    !> The CODIM2_* kind whose points are the zeros of tests(which).
    pure integer function system_codim2_kind(self, which) result(kind)
      import :: curve_system
      class(curve_system), intent(in) :: self
      integer, intent(in) :: which
    end function system_codim2_kind
  end interface

  !> The minimally augmented fold system (module header) on the matrix J + shift I (shift = 0:
  !> folds; a map's period doubling is a fold system on M + I = (M - I) + 2 I).
  type, extends(curve_system) :: fold_system
    real(wp), allocatable :: b(:), c(:)   !< border vectors
    real(wp) :: shift = 0
  contains
    procedure :: evaluate => fold_evaluate
    procedure :: refresh => fold_refresh
    procedure :: diagnose => fold_diagnose
    procedure :: alignment => fold_alignment
    procedure :: codim2_kind => fold_codim2_kind
    procedure :: confirm_codim2 => fold_confirm
    procedure :: codim2_frequency => fold_codim2_frequency
  end type fold_system

  type, extends(curve_system) :: hopf_system
    real(wp), allocatable :: v_ref(:), u_ref(:)   !< orthonormal basis of the eigenplane
    real(wp) :: kappa_scale = 1
  contains
    procedure :: evaluate => hopf_evaluate
    procedure :: refresh => hopf_refresh
    procedure :: diagnose => hopf_diagnose
    procedure :: alignment => hopf_alignment
    procedure :: codim2_kind => hopf_codim2_kind
    procedure :: confirm_codim2 => hopf_confirm
    procedure :: codim2_frequency => hopf_codim2_frequency
    procedure :: masked_by => hopf_masked_by
    procedure :: terminal => hopf_terminal
    procedure :: check_point => hopf_check_point
    procedure :: frequency_of => hopf_frequency_of
  end type hopf_system

  ! ---- private ----------------------------------------------------------------------------

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
  !> Relative size (to max|eigenvalue|) below which a real part counts as zero, and above which
  !> an imaginary part counts as nonzero, when a zero-Hopf point is confirmed.
  real(wp), parameter :: axis_tol = 1.0e-6_wp
  !> A located zero of a test function must be this small relative to the values at the ends of
  !> its bracket (else the sign changed through a pole).
  real(wp), parameter :: pole_ratio = 1.0e-6_wp
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

  !> The first Lyapunov coefficient l1 (see the module header) at the Hopf point (x, p), with
  !> omega > 0 of the complex pair of J closest to the imaginary axis.
  subroutine first_lyapunov_coefficient(field, x, p, l1, omega, status, message)
    class(two_parameter_field), intent(in) :: field
    real(wp), intent(in) :: x(:), p(2)
    real(wp), intent(out) :: l1, omega
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: fx(size(x), size(x)), v(size(x))

    l1 = ieee_value(1.0_wp, ieee_quiet_nan)
    omega = 0
    status = SD_OK
    message = ''
    if (size(x) < 2) then
      status = SD_BAD_INPUT
      message = 'x has size 1; a Hopf point needs n >= 2'
      return
    end if
    call hopf_start(field, x, p, fx, omega, v, status, message)
    if (status == SD_OK) call lyapunov_core(field, x, p, fx, v, omega, l1, status, message)
    if (status /= SD_OK) message = 'first_lyapunov_coefficient: '//trim(message)
  end subroutine first_lyapunov_coefficient

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
    select case (kind)
    case (CODIM2_BT);   name = 'Bogdanov-Takens'
    case (CODIM2_CUSP); name = 'cusp'
    case (CODIM2_ZH);   name = 'zero-Hopf'
    case (CODIM2_GH);   name = 'generalised Hopf'
    case (CODIM2_R1);   name = '1:1 resonance'
    case (CODIM2_R2);   name = '1:2 resonance'
    case (CODIM2_R3);   name = '1:3 resonance'
    case (CODIM2_R4);   name = '1:4 resonance'
    case (CODIM2_FOLD_FLIP); name = 'fold-flip'
    case (CODIM2_FOLD_NS);   name = 'fold-Neimark-Sacker'
    case (CODIM2_FLIP_NS);   name = 'flip-Neimark-Sacker'
    case default;       name = 'regular'
    end select
  end function codim2_name

  !> Words for a CURVE_* code.
  pure function curve_kind_name(kind) result(name)
    integer, intent(in) :: kind
    character(len=:), allocatable :: name
    select case (kind)
    case (CURVE_FOLD);            name = 'fold'
    case (CURVE_HOPF);            name = 'Hopf'
    case (CURVE_PERIOD_DOUBLING); name = 'period-doubling'
    case (CURVE_NEIMARK_SACKER);  name = 'Neimark-Sacker'
    case default;                 name = 'unknown'
    end select
  end function curve_kind_name

  !> Words for an END_* code.
  pure function curve_end_name(reason) result(name)
    integer, intent(in) :: reason
    character(len=:), allocatable :: name
    select case (reason)
    case (END_START);      name = 'start point'
    case (END_BOX);        name = 'parameter box'
    case (END_CLOSED);     name = 'closed curve'
    case (END_X_MAX);      name = 'max|x| exceeded x_max'
    case (END_BT);         name = 'Bogdanov-Takens point'
    case (END_MAX_POINTS); name = 'max_points computed'
    case (END_FAILED);     name = 'step fell below ds_min'
    case (END_RESONANCE);  name = '1:1 or 1:2 resonance'
    case default;          name = 'unknown end'
    end select
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

  !> The common part of a defining system: its field, kind, sizes, scales and reference point.
  subroutine setup_system(sys, field, kind, n, n_extra, p0, options)
    class(curve_system), intent(inout) :: sys
    class(two_parameter_field), intent(in) :: field
    integer, intent(in) :: kind, n, n_extra
    real(wp), intent(in) :: p0(2)
    type(curve_options), intent(in) :: options
    allocate (sys%field, source=field)
    sys%kind = kind
    sys%n = n
    sys%n_extra = n_extra
    sys%x_scale = options%x_scale
    sys%p_scale = options%p_scale
    sys%p_ref = p0
  end subroutine setup_system

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

  !> The defining system of a fold or Hopf curve of equilibria with its first borders /
  !> reference data, and the start state s0 = (x0, [v, kappa/kappa_scale,] p0) (the default
  !> defining_system of a field; kind is one of CURVE_*).
  subroutine field_defining_system(field, kind, x0, p0, options, proto, s0, status, message)
    class(two_parameter_field), intent(in) :: field
    integer, intent(in) :: kind
    real(wp), intent(in) :: x0(:), p0(2)
    type(curve_options), intent(in) :: options
    class(curve_system), allocatable, intent(out) :: proto
    real(wp), allocatable, intent(out) :: s0(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: f(size(x0)), fx(size(x0), size(x0)), fp(size(x0), 2), v(size(x0)), &
                w(size(x0)), omega, scale
    integer :: n

    n = size(x0)
    status = SD_OK
    message = ''
    if (kind == CURVE_PERIOD_DOUBLING .or. kind == CURVE_NEIMARK_SACKER) then
      status = SD_BAD_INPUT
      message = 'a '//curve_kind_name(kind)//' curve is a curve of fixed points of a map: '// &
                'the field must be a two_parameter_map (sloshdyn_map_bifurcation)'
      return
    end if
    if (kind == CURVE_FOLD) then
      call field%evaluate(x0, p0, f, fx, fp)
      scale = max(maxval(abs(fx)), tiny(1.0_wp))
      call inverse_iteration(fx, scale, v, status, message)
      if (status == SD_OK) call inverse_iteration(transpose(fx), scale, w, status, message)
      if (status /= SD_OK) then
        message = 'no null vector of df/dx at the start point: '//trim(message)
        return
      end if
      allocate (fold_system :: proto)
      select type (proto)
      type is (fold_system)
        proto%c = v
        proto%b = w
      end select
      call setup_system(proto, field, CURVE_FOLD, n, 0, p0, options)
      s0 = [x0, p0]
    else
      if (n < 2) then
        status = SD_BAD_INPUT
        message = 'x0 has size 1; a Hopf point needs n >= 2'
        return
      end if
      call hopf_start(field, x0, p0, fx, omega, v, status, message)
      if (status /= SD_OK) return
      allocate (hopf_system :: proto)
      select type (proto)
      type is (hopf_system)
        proto%kappa_scale = omega**2
        allocate (proto%v_ref(n), proto%u_ref(n))
      end select
      call setup_system(proto, field, CURVE_HOPF, n, n + 1, p0, options)
      s0 = [x0, v, 1.0_wp, p0]
    end if
  end subroutine field_defining_system

  !> Newton on the defining system from the state s0 with lambda = p(fixed(1)) fixed (then
  !> fixed(2), ... if it fails); sys is the system that converged, s the corrected state, which
  !> must pass sys%check_point (a Hopf point must have kappa > 0).
  subroutine correct_state(proto, s0, fixed, options, sys, s, status, message)
    class(curve_system), intent(in) :: proto
    real(wp), intent(in) :: s0(:)
    integer, intent(in) :: fixed(:)
    type(curve_options), intent(in) :: options
    class(curve_system), allocatable, intent(out) :: sys
    real(wp), allocatable, intent(out) :: s(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
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
  end subroutine correct_state

  !> Correct the start, find the tangent, trace both halves (or one) and assemble the curve.
  subroutine trace_curve(proto, s0, options, curve, status, message)
    class(curve_system), intent(in) :: proto
    real(wp), intent(in) :: s0(:)
    type(curve_options), intent(in) :: options
    type(bifurcation_curve), intent(inout) :: curve
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
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
  end subroutine trace_curve

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
    integer :: kinds(max_curve_tests), which, kind, info, order(max_curve_tests), i, j, k, n, &
               mask
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
      mask = sys%masked_by(which)
      if (mask > 0) then
        if (tests_a(mask)*tests_b(mask) < 0) cycle
      end if
      if (.not. allocated(test%sys)) allocate (test%sys, source=sys)
      test%which = which
      call locate_zero_on_branch(sys, z_a, t_a, ds_total, test, z, info, info_message, opts)
      if (info /= SD_OK) then
        buf%n_unlocated = buf%n_unlocated + 1
        if (buf%unlocated_message == '') buf%unlocated_message = 'a '// &
          codim2_name(sys%codim2_kind(which))//' point between p = ('// &
          trim(p_text(sys, z_a))//') and ('//trim(p_text(sys, z_b))//') was not located: '// &
          trim(info_message)
        cycle
      end if
      call sys%diagnose(z, re, im, tests, omega, l1, info, info_message)
      if (info /= SD_OK) cycle
      ! a sign change through a pole (l1 at a zero-Hopf point) is no zero
      if (.not. abs(tests(which)) <= pole_ratio*max(abs(tests_a(which)), abs(tests_b(which)))) &
        cycle
      kind = sys%codim2_kind(which)
      if (.not. sys%confirm_codim2(kind, re, im, tests)) cycle
      n_found = n_found + 1
      found(:, n_found) = z
      position(n_found) = sum(t_a*(z - z_a))
      kinds(n_found) = kind
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
      end_here = sys%terminal(kinds(j), neutral_saddles)
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

  ! ---- the fold system ----------------------------------------------------------------------

  !> F = (f, g) with the bordered g; see the module header.
  subroutine fold_evaluate(self, x, lambda, f, fx, flambda)
    class(fold_system), intent(in) :: self
    real(wp), intent(in) :: x(:), lambda
    real(wp), intent(out) :: f(:), fx(:, :), flambda(:)
    real(wp) :: xx(self%n), p(2), ff(self%n), jj(self%n, self%n), fp(self%n, 2), v(self%n), &
                w(self%n), g, hx(self%n, self%n), hp(self%n, 2)
    integer :: n, info, o, l

    n = self%n
    o = self%other
    l = self%lam
    call split_x_p(self, x, lambda, xx, p)
    call self%field%evaluate(xx, p, ff, jj, fp)
    call bordered_vectors(jj, self%b, self%c, v, w, g, info, self%shift)
    if (info /= SD_OK) then
      f = ieee_value(1.0_wp, ieee_quiet_nan)
      fx = 0
      flambda = 0
      return
    end if
    call self%field%jacobian_derivative(xx, p, v, hx, hp)
    f(1:n) = ff
    f(n + 1) = g
    fx(1:n, 1:n) = jj*self%x_scale
    fx(1:n, n + 1) = fp(:, o)*self%p_scale(o)
    ! d(J + shift I)v/dx = d(J v)/dx
    fx(n + 1, 1:n) = -matmul(w, hx)*self%x_scale
    fx(n + 1, n + 1) = -sum(w*hp(:, o))*self%p_scale(o)
    flambda(1:n) = fp(:, l)*self%p_scale(l)
    flambda(n + 1) = -sum(w*hp(:, l))*self%p_scale(l)
  end subroutine fold_evaluate

  !> New borders: the current null vectors v, w (unit), so <c, v> = 1 and <b, w> = 1 keep the
  !> orientation of v and w from one segment to the next.
  subroutine fold_refresh(self, s, status, message)
    class(fold_system), intent(inout) :: self
    real(wp), intent(inout) :: s(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: ff(self%n), jj(self%n, self%n), fp(self%n, 2), v(self%n), w(self%n), g
    integer :: n
    n = self%n
    call self%field%evaluate(s(1:n), s(n + 1:n + 2), ff, jj, fp)
    call bordered_vectors(jj, self%b, self%c, v, w, g, status, self%shift)
    message = ''
    if (status /= SD_OK) then
      message = 'the bordered Jacobian is singular at p = ('//num2str(s(n + 1))//', '// &
                num2str(s(n + 2))//'): the null space of df/dx + shift I has dimension > 1 '// &
                '(shift = '//num2str(self%shift)//')'
      return
    end if
    self%c = v/norm2(v)
    self%b = w/norm2(w)
  end subroutine fold_refresh

  !> Tests (BT, cusp, ZH); see the module header.
  subroutine fold_diagnose(self, z, re, im, tests, omega, l1, status, message)
    class(fold_system), intent(in) :: self
    real(wp), intent(in) :: z(:)
    real(wp), intent(out) :: re(:), im(:), tests(max_curve_tests), omega, l1
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: xx(self%n), p(2), ff(self%n), jj(self%n, self%n), fp(self%n, 2), v(self%n), &
                w(self%n), g, bvv(self%n)

    tests = ieee_value(1.0_wp, ieee_quiet_nan)
    omega = 0
    l1 = ieee_value(1.0_wp, ieee_quiet_nan)
    call point_x_p(self, z, xx, p)
    call self%field%evaluate(xx, p, ff, jj, fp)
    call eigenvalues(jj, re, im, status, message)
    if (status /= SD_OK) return
    call bordered_vectors(jj, self%b, self%c, v, w, g, status, self%shift)
    if (status /= SD_OK) then
      message = 'the bordered Jacobian is singular'
      return
    end if
    v = v/norm2(v)
    w = w/norm2(w)
    call self%field%second_derivative(xx, p, v, v, bvv)
    tests(1) = sum(w*v)
    tests(2) = sum(w*bvv)
    tests(3) = pair_sum_product(re, im)
  end subroutine fold_diagnose

  !> max(|v|, |w|) with <c, v> = <b, w> = 1 and unit borders.
  function fold_alignment(self, z) result(growth)
    class(fold_system), intent(in) :: self
    real(wp), intent(in) :: z(:)
    real(wp) :: growth
    real(wp) :: xx(self%n), p(2), ff(self%n), jj(self%n, self%n), fp(self%n, 2), v(self%n), &
                w(self%n), g
    integer :: info
    call point_x_p(self, z, xx, p)
    call self%field%evaluate(xx, p, ff, jj, fp)
    call bordered_vectors(jj, self%b, self%c, v, w, g, info, self%shift)
    growth = huge(1.0_wp)
    if (info == SD_OK) growth = max(norm2(v), norm2(w))
  end function fold_alignment

  !> v, w and g of the bordered systems [J b; c^T 0] (v; g) = e and its transpose (J + shift I
  !> in place of J with shift).
  subroutine bordered_vectors(jj, b, c, v, w, g, status, shift)
    real(wp), intent(in) :: jj(:, :), b(:), c(:)
    real(wp), intent(out) :: v(:), w(:), g
    integer, intent(out) :: status
    real(wp), intent(in), optional :: shift
    real(wp) :: a(size(b) + 1, size(b) + 1), r(size(b) + 1)
    integer :: n, i
    character(len=message_len) :: message
    n = size(b)
    a(1:n, 1:n) = jj
    if (present(shift)) then
      do i = 1, n
        a(i, i) = a(i, i) + shift
      end do
    end if
    a(1:n, n + 1) = b
    a(n + 1, 1:n) = c
    a(n + 1, n + 1) = 0
    r = 0
    r(n + 1) = 1
    call solve_linear(a, r, status, message)
    v = r(1:n)
    g = r(n + 1)
    if (status /= SD_OK) return
    r = 0
    r(n + 1) = 1
    call solve_linear(transpose(a), r, status, message)
    w = r(1:n)
    if (status == SD_OK .and. .not. (all(ieee_is_finite(v)) .and. all(ieee_is_finite(w)))) &
      status = SD_SINGULAR
  end subroutine bordered_vectors

  !> prod_{i<j} (mu_i + mu_j) over the eigenvalues mu but the one of smallest modulus (real).
  pure real(wp) function pair_sum_product(re, im) result(product_value)
    real(wp), intent(in) :: re(:), im(:)
    complex(wp) :: mu(size(re)), prod
    integer :: i, j, skip
    mu = cmplx(re, im, wp)
    skip = minloc(abs(mu), 1)
    prod = 1
    do i = 1, size(mu)
      if (i == skip) cycle
      do j = i + 1, size(mu)
        if (j == skip) cycle
        prod = prod*(mu(i) + mu(j))
      end do
    end do
    product_value = real(prod)
  end function pair_sum_product

  ! ---- the Hopf system ----------------------------------------------------------------------

  !> F = (f, (J^2 + kappa I) v/kappa_scale, <v_ref, v> - 1, <u_ref, v>); z = (x/x_scale, v,
  !> kappa/kappa_scale, q_other).
  subroutine hopf_evaluate(self, x, lambda, f, fx, flambda)
    class(hopf_system), intent(in) :: self
    real(wp), intent(in) :: x(:), lambda
    real(wp), intent(out) :: f(:), fx(:, :), flambda(:)
    real(wp) :: xx(self%n), p(2), ff(self%n), jj(self%n, self%n), fp(self%n, 2), v(self%n), &
                jv(self%n), kappa, ks, hxv(self%n, self%n), hpv(self%n, 2), &
                hxjv(self%n, self%n), hpjv(self%n, 2)
    integer :: n, o, l, i

    n = self%n
    o = self%other
    l = self%lam
    ks = self%kappa_scale
    call split_x_p(self, x, lambda, xx, p)
    v = x(n + 1:2*n)
    kappa = ks*x(2*n + 1)
    call self%field%evaluate(xx, p, ff, jj, fp)
    jv = matmul(jj, v)
    call self%field%jacobian_derivative(xx, p, v, hxv, hpv)
    call self%field%jacobian_derivative(xx, p, jv, hxjv, hpjv)
    f(1:n) = ff
    f(n + 1:2*n) = (matmul(jj, jv) + kappa*v)/ks
    f(2*n + 1) = sum(self%v_ref*v) - 1
    f(2*n + 2) = sum(self%u_ref*v)
    fx = 0
    fx(1:n, 1:n) = jj*self%x_scale
    fx(1:n, 2*n + 2) = fp(:, o)*self%p_scale(o)
    fx(n + 1:2*n, 1:n) = (hxjv + matmul(jj, hxv))*(self%x_scale/ks)
    fx(n + 1:2*n, n + 1:2*n) = matmul(jj, jj)/ks
    do i = 1, n
      fx(n + i, n + i) = fx(n + i, n + i) + kappa/ks
    end do
    fx(n + 1:2*n, 2*n + 1) = v
    fx(n + 1:2*n, 2*n + 2) = (hpjv(:, o) + matmul(jj, hpv(:, o)))*(self%p_scale(o)/ks)
    fx(2*n + 1, n + 1:2*n) = self%v_ref
    fx(2*n + 2, n + 1:2*n) = self%u_ref
    flambda = 0
    flambda(1:n) = fp(:, l)*self%p_scale(l)
    flambda(n + 1:2*n) = (hpjv(:, l) + matmul(jj, hpv(:, l)))*(self%p_scale(l)/ks)
  end subroutine hopf_evaluate

  !> New reference vectors: v_ref = v/|v|, u_ref = the unit part of J v orthogonal to v_ref; v
  !> in the state becomes v_ref (so <v_ref, v> = 1, <u_ref, v> = 0 hold).
  subroutine hopf_refresh(self, s, status, message)
    class(hopf_system), intent(inout) :: self
    real(wp), intent(inout) :: s(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: ff(self%n), jj(self%n, self%n), fp(self%n, 2), v(self%n), u(self%n)
    integer :: n
    n = self%n
    status = SD_OK
    message = ''
    call self%field%evaluate(s(1:n), s(2*n + 2:2*n + 3), ff, jj, fp)
    v = s(n + 1:2*n)
    if (.not. norm2(v) > 0) then
      status = SD_SINGULAR
      message = 'the eigenvector of the Hopf system vanished'
      return
    end if
    v = v/norm2(v)
    u = matmul(jj, v)
    u = u - sum(u*v)*v
    if (.not. norm2(u) > 0) then
      status = SD_SINGULAR
      message = 'J v is parallel to v at p = ('//num2str(s(2*n + 2))//', '// &
                num2str(s(2*n + 3))//'): no eigenplane of a complex pair (or kappa = 0 exactly)'
      return
    end if
    self%v_ref = v
    self%u_ref = u/norm2(u)
    s(n + 1:2*n) = v
  end subroutine hopf_refresh

  !> |v| with <v_ref, v> = 1.
  function hopf_alignment(self, z) result(growth)
    class(hopf_system), intent(in) :: self
    real(wp), intent(in) :: z(:)
    real(wp) :: growth
    growth = norm2(z(self%n + 1:2*self%n))
  end function hopf_alignment

  !> Tests (BT = kappa, ZH = det J, GH = l1); omega = sign(kappa) sqrt|kappa|.
  subroutine hopf_diagnose(self, z, re, im, tests, omega, l1, status, message)
    class(hopf_system), intent(in) :: self
    real(wp), intent(in) :: z(:)
    real(wp), intent(out) :: re(:), im(:), tests(max_curve_tests), omega, l1
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: xx(self%n), p(2), ff(self%n), jj(self%n, self%n), fp(self%n, 2), kappa
    complex(wp) :: det
    integer :: n, i

    n = self%n
    tests = ieee_value(1.0_wp, ieee_quiet_nan)
    l1 = ieee_value(1.0_wp, ieee_quiet_nan)
    call point_x_p(self, z, xx, p)
    kappa = self%kappa_scale*z(2*n + 1)
    omega = sign(sqrt(abs(kappa)), kappa)
    call self%field%evaluate(xx, p, ff, jj, fp)
    call eigenvalues(jj, re, im, status, message)
    if (status /= SD_OK) return
    det = 1
    do i = 1, n
      det = det*cmplx(re(i), im(i), wp)
    end do
    tests(1) = kappa
    tests(2) = real(det)
    if (kappa > 0) then
      call lyapunov_core(self%field, xx, p, jj, z(n + 1:2*n), omega, l1, status, message)
      if (status /= SD_OK) then
        status = SD_OK   ! a point where l1 fails (J singular: zero-Hopf) keeps l1 = NaN
        message = ''
        l1 = ieee_value(1.0_wp, ieee_quiet_nan)
      end if
      tests(3) = l1
    end if
  end subroutine hopf_diagnose

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

  pure integer function no_mask(self, which) result(mask)
    class(curve_system), intent(in) :: self
    integer, intent(in) :: which
    mask = 0
  end function no_mask

  pure integer function never_terminal(self, kind, neutral_saddles) result(reason)
    class(curve_system), intent(in) :: self
    integer, intent(in) :: kind
    logical, intent(in) :: neutral_saddles
    reason = 0
  end function never_terminal

  subroutine any_point(self, s, neutral_saddles, status, message)
    class(curve_system), intent(in) :: self
    real(wp), intent(in) :: s(:)
    logical, intent(in) :: neutral_saddles
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    status = SD_OK
    message = ''
  end subroutine any_point

  real(wp) function no_frequency(self, s) result(frequency)
    class(curve_system), intent(in) :: self
    real(wp), intent(in) :: s(:)
    frequency = 0
  end function no_frequency

  !> Fold curves: tests (BT, cusp, ZH).
  pure integer function fold_codim2_kind(self, which) result(kind)
    class(fold_system), intent(in) :: self
    integer, intent(in) :: which
    integer, parameter :: kinds(3) = [CODIM2_BT, CODIM2_CUSP, CODIM2_ZH]
    kind = kinds(which)
  end function fold_codim2_kind

  !> Zero-Hopf on a fold curve needs a pair on the imaginary axis (not a real pair +-mu).
  logical function fold_confirm(self, kind, re, im, tests) result(confirmed)
    class(fold_system), intent(in) :: self
    integer, intent(in) :: kind
    real(wp), intent(in) :: re(:), im(:), tests(:)
    real(wp) :: scale
    integer :: i
    confirmed = .true.
    if (kind /= CODIM2_ZH) return
    scale = max(maxval(abs(cmplx(re, im, wp))), tiny(1.0_wp))
    confirmed = .false.
    do i = 1, size(re)
      if (abs(re(i)) <= axis_tol*scale .and. abs(im(i)) > axis_tol*scale) confirmed = .true.
    end do
  end function fold_confirm

  !> The imaginary eigenvalue of a zero-Hopf point on a fold curve.
  real(wp) function fold_codim2_frequency(self, kind, re, im, omega) result(frequency)
    class(fold_system), intent(in) :: self
    integer, intent(in) :: kind
    real(wp), intent(in) :: re(:), im(:), omega
    integer :: i, best
    frequency = 0
    if (kind /= CODIM2_ZH) return
    best = 0
    do i = 1, size(re)
      if (im(i) <= 0) cycle
      if (best == 0) then
        best = i
      else if (abs(re(i)) < abs(re(best))) then
        best = i
      end if
    end do
    if (best > 0) frequency = im(best)
  end function fold_codim2_frequency

  !> Hopf curves: tests (BT = kappa, ZH = det J, GH = l1).
  pure integer function hopf_codim2_kind(self, which) result(kind)
    class(hopf_system), intent(in) :: self
    integer, intent(in) :: which
    integer, parameter :: kinds(3) = [CODIM2_BT, CODIM2_ZH, CODIM2_GH]
    kind = kinds(which)
  end function hopf_codim2_kind

  !> Zero-Hopf and generalised Hopf need kappa > 0 (det J also vanishes at the
  !> Bogdanov-Takens point).
  logical function hopf_confirm(self, kind, re, im, tests) result(confirmed)
    class(hopf_system), intent(in) :: self
    integer, intent(in) :: kind
    real(wp), intent(in) :: re(:), im(:), tests(:)
    real(wp) :: scale
    confirmed = .true.
    if (kind /= CODIM2_ZH .and. kind /= CODIM2_GH) return
    scale = max(maxval(abs(cmplx(re, im, wp))), tiny(1.0_wp))
    confirmed = tests(1) > axis_tol*scale**2
  end function hopf_confirm

  real(wp) function hopf_codim2_frequency(self, kind, re, im, omega) result(frequency)
    class(hopf_system), intent(in) :: self
    integer, intent(in) :: kind
    real(wp), intent(in) :: re(:), im(:), omega
    frequency = 0
    if (kind == CODIM2_GH .or. kind == CODIM2_ZH) frequency = omega
  end function hopf_codim2_frequency

  !> det J (ZH) vanishes with kappa at a Bogdanov-Takens point.
  pure integer function hopf_masked_by(self, which) result(mask)
    class(hopf_system), intent(in) :: self
    integer, intent(in) :: which
    mask = merge(1, 0, which == 2)
  end function hopf_masked_by

  pure integer function hopf_terminal(self, kind, neutral_saddles) result(reason)
    class(hopf_system), intent(in) :: self
    integer, intent(in) :: kind
    logical, intent(in) :: neutral_saddles
    reason = 0
    if (kind == CODIM2_BT .and. .not. neutral_saddles) reason = END_BT
  end function hopf_terminal

  !> A Hopf point has kappa > 0 (unless neutral saddles are asked for).
  subroutine hopf_check_point(self, s, neutral_saddles, status, message)
    class(hopf_system), intent(in) :: self
    real(wp), intent(in) :: s(:)
    logical, intent(in) :: neutral_saddles
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    integer :: k
    status = SD_OK
    message = ''
    k = self%n + self%n_extra
    if (neutral_saddles .or. s(2*self%n + 1) > 0) return
    status = SD_BAD_INPUT
    message = 'the point converged to a neutral saddle (real eigenvalues +-mu, kappa = '// &
              num2str(s(2*self%n + 1)*self%kappa_scale)//' < 0) at p = ('// &
              num2str(s(k + 1))//', '//num2str(s(k + 2))//'), not to a Hopf point'
  end subroutine hopf_check_point

  real(wp) function hopf_frequency_of(self, s) result(frequency)
    class(hopf_system), intent(in) :: self
    real(wp), intent(in) :: s(:)
    frequency = sqrt(max(s(2*self%n + 1)*self%kappa_scale, 0.0_wp))
  end function hopf_frequency_of

  ! ---- Hopf points: start and Lyapunov coefficient ------------------------------------------

  !> J at (x, p), omega of the complex pair closest to the imaginary axis, and a real vector v
  !> of its eigenplane (inverse iteration on J^2 + omega^2 I).
  subroutine hopf_start(field, x, p, jj, omega, v, status, message)
    class(two_parameter_field), intent(in) :: field
    real(wp), intent(in) :: x(:), p(2)
    real(wp), intent(out) :: jj(:, :), omega, v(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: f(size(x)), fp(size(x), 2), re(size(x)), im(size(x)), a(size(x), size(x))
    integer :: i, best

    omega = 0
    v = 0
    call field%evaluate(x, p, f, jj, fp)
    call eigenvalues(jj, re, im, status, message)
    if (status /= SD_OK) return
    best = 0
    do i = 1, size(x)
      if (im(i) <= 0) cycle
      if (best == 0) then
        best = i
      else if (abs(re(i)) < abs(re(best))) then
        best = i
      end if
    end do
    if (best == 0) then
      status = SD_BAD_INPUT
      message = 'df/dx has no complex eigenvalue pair at p = ('//num2str(p(1))//', '// &
                num2str(p(2))//'): not near a Hopf point'
      return
    end if
    omega = im(best)
    a = matmul(jj, jj)
    do i = 1, size(x)
      a(i, i) = a(i, i) + omega**2
    end do
    call inverse_iteration(a, max(maxval(abs(jj))**2, omega**2), v, status, message)
  end subroutine hopf_start

  !> A unit vector near the null space of the nearly singular a: inverse iteration with a tiny
  !> shift relative to scale, the size of the matrix a is a small perturbation of (so an exactly
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

  !> l1 at a Hopf point with J = df/dx, omega > 0 and v in the real eigenplane (module header).
  subroutine lyapunov_core(field, x, p, jj, v, omega, l1, status, message)
    class(two_parameter_field), intent(in) :: field
    real(wp), intent(in) :: x(:), p(2), jj(:, :), v(:), omega
    real(wp), intent(out) :: l1
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: qr(size(x)), qi(size(x)), pr(size(x)), pi_(size(x)), ar(size(x) + 1, size(x) + 1), &
                ai(size(x) + 1, size(x) + 1), br(size(x) + 1), bi(size(x) + 1), &
                b1(size(x)), b2(size(x)), b3(size(x)), h11(size(x)), h20r(size(x)), &
                h20i(size(x)), tr(size(x)), ti(size(x)), c1(size(x)), c2(size(x)), &
                a2r(size(x), size(x)), a2i(size(x), size(x)), scale
    integer :: n, i

    n = size(x)
    l1 = ieee_value(1.0_wp, ieee_quiet_nan)
    ! q = v - i J v/omega, |q| = 1: J q = i omega q
    qr = v
    qi = -matmul(jj, v)/omega
    scale = sqrt(sum(qr**2) + sum(qi**2))
    qr = qr/scale
    qi = qi/scale
    ! p: [J^T + i omega I, q; q^H, 0] (p; s) = (0; 1), so q^H p = 1 = <p, q>
    ar = 0
    ai = 0
    ar(1:n, 1:n) = transpose(jj)
    do i = 1, n
      ai(i, i) = omega
    end do
    ar(1:n, n + 1) = qr
    ai(1:n, n + 1) = qi
    ar(n + 1, 1:n) = qr
    ai(n + 1, 1:n) = -qi
    br = 0
    br(n + 1) = 1
    bi = 0
    call solve_complex(ar, ai, br, bi, status, message)
    if (status /= SD_OK) return
    pr = br(1:n)
    pi_ = bi(1:n)
    ! h11 = J^-1 B(q, conj q), B(q, conj q) = B(qr, qr) + B(qi, qi)
    call field%second_derivative(x, p, qr, qr, b1)
    call field%second_derivative(x, p, qi, qi, b2)
    h11 = b1 + b2
    call solve_linear(jj, h11, status, message)
    if (status /= SD_OK) then
      message = 'J is singular at the Hopf point (a zero-Hopf point): '//trim(message)
      return
    end if
    ! h20 = (2 i omega I - J)^-1 B(q, q), B(q, q) = B(qr, qr) - B(qi, qi) + 2 i B(qr, qi)
    call field%second_derivative(x, p, qr, qi, b3)
    h20r = b1 - b2
    h20i = 2*b3
    a2r = -jj
    a2i = 0
    do i = 1, n
      a2i(i, i) = 2*omega
    end do
    call solve_complex(a2r, a2i, h20r, h20i, status, message)
    if (status /= SD_OK) return
    ! C(q, q, conj q) = C(qr, qr, qr) + C(qr, qi, qi) + i (C(qr, qr, qi) + C(qi, qi, qi))
    call field%third_derivative(x, p, qr, qr, qr, c1)
    call field%third_derivative(x, p, qr, qi, qi, c2)
    tr = c1 + c2
    call field%third_derivative(x, p, qr, qr, qi, c1)
    call field%third_derivative(x, p, qi, qi, qi, c2)
    ti = c1 + c2
    ! - 2 B(q, h11) = -2 (B(qr, h11) + i B(qi, h11))
    call field%second_derivative(x, p, qr, h11, b1)
    call field%second_derivative(x, p, qi, h11, b2)
    tr = tr - 2*b1
    ti = ti - 2*b2
    ! + B(conj q, h20) = B(qr, h20r) + B(qi, h20i) + i (B(qr, h20i) - B(qi, h20r))
    call field%second_derivative(x, p, qr, h20r, b1)
    call field%second_derivative(x, p, qi, h20i, b2)
    tr = tr + b1 + b2
    call field%second_derivative(x, p, qr, h20i, b1)
    call field%second_derivative(x, p, qi, h20r, b2)
    ti = ti + b1 - b2
    ! Re <p, t> = Re conj(p)^T t
    l1 = (sum(pr*tr) + sum(pi_*ti))/(2*omega)
    if (.not. ieee_is_finite(l1)) then
      status = SD_SINGULAR
      message = 'l1 is not finite'
    end if
  end subroutine lyapunov_core

  !> Solve (ar + i ai)(xr + i xi) = br + i bi in real arithmetic; x overwrites b.
  subroutine solve_complex(ar, ai, br, bi, status, message)
    real(wp), intent(in) :: ar(:, :), ai(:, :)
    real(wp), intent(inout) :: br(:), bi(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: a(2*size(br), 2*size(br)), r(2*size(br))
    integer :: n
    n = size(br)
    a(1:n, 1:n) = ar
    a(1:n, n + 1:2*n) = -ai
    a(n + 1:2*n, 1:n) = ai
    a(n + 1:2*n, n + 1:2*n) = ar
    r = [br, bi]
    call solve_linear(a, r, status, message)
    if (status /= SD_OK) return
    br = r(1:n)
    bi = r(n + 1:2*n)
  end subroutine solve_complex
end module sloshdyn_bifurcation
