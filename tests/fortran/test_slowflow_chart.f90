!> The slow flow as a two-parameter field, against sloshdyn_slowflow (f and J), finite
!> differences (the higher derivatives), and the one-parameter continuation of
!> sloshdyn_response (Hopf points and folds at fixed A, fold counts around the cusp).
module slowflow_chart_helpers
  use sloshdyn_kinds, only: wp
  use sloshdyn_bifurcation, only: two_parameter_field
  use sloshdyn_slowflow_chart, only: slow_flow_field
  use sloshdyn_ode, only: ode_system
  implicit none
  private
  public :: fd_slow_flow, slow_flow_ode

  !> The slow flow x' = f(x; p) at fixed p, to integrate.
  type, extends(ode_system) :: slow_flow_ode
    type(slow_flow_field) :: field
    real(wp) :: p(2) = 0
  contains
    procedure :: rhs => ode_rhs
  end type slow_flow_ode

  !> The same field with the finite-difference higher derivatives of sloshdyn_bifurcation.
  type, extends(two_parameter_field) :: fd_slow_flow
    type(slow_flow_field) :: exact
  contains
    procedure :: evaluate => fd_evaluate
  end type fd_slow_flow

contains

  subroutine ode_rhs(self, t, y, dydt)
    class(slow_flow_ode), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: dydt(:)
    real(wp) :: fx(size(y), size(y)), fp(size(y), 2)
    call self%field%evaluate(y, self%p, dydt, fx, fp)
    dydt = dydt + 0*t
  end subroutine ode_rhs

  subroutine fd_evaluate(self, x, p, f, fx, fp)
    class(fd_slow_flow), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2)
    real(wp), intent(out) :: f(:), fx(:, :), fp(:, :)
    call self%exact%evaluate(x, p, f, fx, fp)
  end subroutine fd_evaluate
end module slowflow_chart_helpers

program test_slowflow_chart
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT
  use sloshdyn_model, only: model_t, model_from_arrays, set_coefficients
  use sloshdyn_modal, only: modal_coefficients, expand_model
  use sloshdyn_excitation, only: PARAMETER_RHO, PARAMETER_A
  use sloshdyn_slowflow, only: slow_flow, make_slow_flow, nonresonant_cubic
  use sloshdyn_response, only: response_options, frequency_response
  use sloshdyn_tables, only: POINT_ROWS, SPECIAL_ROWS, POINT_X, SPECIAL_KIND, SPECIAL_RHO, &
                             SPECIAL_A, SPECIAL_COLUMN, SPECIAL_FOLD, SPECIAL_HOPF
  use sloshdyn_bifurcation, only: curve_options, bifurcation_curve, fold_curve, hopf_curve, &
                                  curve_crossings, first_lyapunov_coefficient, codim2_name, &
                                  curve_end_name, CURVE_FOLD, &
                                  CURVE_HOPF, CODIM2_CUSP
  use sloshdyn_slowflow_chart, only: slow_flow_field, make_slow_flow_field, CHART_RHO, &
                                     CHART_A, CHART_GAMMA
  use slowflow_chart_helpers, only: fd_slow_flow, slow_flow_ode
  use sloshdyn_ode, only: ode_options, ode_stats
  use sloshdyn_dop853, only: dop853_integrator
  use sloshdyn_lapack, only: eigenvalues
  use sloshdyn_continuation, only: newton_options, newton_solve
  use checks, only: check_close, check_true, finish
  implicit none

  !> Fig 12 (sec 4.2): s1 = 1.5, mu1 = 0.5, kappa = 1.804897259, theta0 = pi/4, beta = 10,
  !> gamma = 0.001, delta = 0.1, n = 6, p = 2, A = 0.00075; Fig 11: kappa = 1.807915943,
  !> gamma = 0.0025.
  real(wp), parameter :: kappa12 = 1.804897259_wp, gamma12 = 0.001_wp, a12 = 0.00075_wp
  real(wp), parameter :: kappa11 = 1.807915943_wp, gamma11 = 0.0025_wp
  real(wp), parameter :: rho_min = 0.49_wp, rho_max = 0.53_wp

  call test_field_matches_slow_flow(.true.)
  call test_field_matches_slow_flow(.false.)
  call test_higher_derivatives()
  call test_gamma_parameter()
  call test_bad_parameters()
  call test_fig12_chart()
  call test_fig11_cusp()
  call test_lyapunov_by_simulation()
  call test_nonresonant_cusp(4.5_wp)
  call test_nonresonant_cusp(4.7_wp)
  call finish()

contains

  function paper_model(kappa, gamma, amplitude, rho) result(model)
    real(wp), intent(in) :: kappa, gamma, amplitude, rho
    type(model_t) :: model
    integer :: status
    character(len=message_len) :: message
    call model_from_arrays([1.5_wp, 0.5_wp, kappa, pi/4, 10.0_wp, gamma, 0.1_wp, amplitude, &
                            rho, 0.0_wp], [6, 2], model, status, message)
  end function paper_model

  !> Chart settings for the slow flow: rho in [0.49, 0.53], A in (0, 0.002].
  function chart_options() result(opt)
    type(curve_options) :: opt
    opt%p_min = [rho_min, 1.0e-6_wp]
    opt%p_max = [rho_max, 0.002_wp]
    opt%x_scale = 0.05_wp
    opt%p_scale = [1.0e-3_wp, 1.0e-4_wp]
    opt%continuation%ds = 0.05_wp
    opt%continuation%ds_max = 0.2_wp
    opt%continuation%ds_min = 1.0e-9_wp
    opt%max_points = 5000
  end function chart_options

  !> f, df/dx and df/d(rho, A) against slow_flow's residual and Jacobian (its dF/dlambda for
  !> lambda = rho and lambda = A) at scattered points.
  subroutine test_field_matches_slow_flow(internal_resonance)
    logical, intent(in) :: internal_resonance
    type(slow_flow_field) :: field
    type(slow_flow) :: flow_rho, flow_a
    type(model_t) :: model
    real(wp), allocatable :: x(:), f(:), fx(:, :), fp(:, :), g(:), gx(:, :), glam(:)
    real(wp) :: p(2), worst
    integer :: status, trial, n, i
    character(len=message_len) :: message
    character(len=*), parameter :: tag(2) = ['3:1 ', 'none']

    n = merge(4, 2, internal_resonance)
    allocate (x(n), f(n), fx(n, n), fp(n, 2), g(n), gx(n, n), glam(n))
    worst = 0
    do trial = 1, 5
      p = [0.505_wp + 0.002_wp*trial, 0.0002_wp*trial]
      x = [(0.03_wp*sin(1.7_wp*i + trial), i = 1, n)]
      model = paper_model(kappa12, gamma12, p(2), p(1))
      call make_slow_flow_field(model, internal_resonance, [CHART_RHO, CHART_A], field, status, &
                                message)
      call make_slow_flow(model, internal_resonance, PARAMETER_RHO, flow_rho, status, message)
      call make_slow_flow(model, internal_resonance, PARAMETER_A, flow_a, status, message)
      call field%evaluate(x, p, f, fx, fp)
      call flow_rho%residual(x, p(1), g)
      call flow_rho%jacobian(x, p(1), gx, glam)
      worst = max(worst, maxval(abs(f - g))/maxval(abs(g)), maxval(abs(fx - gx))/maxval(abs(gx)), &
                  maxval(abs(fp(:, 1) - glam))/maxval(abs(glam)))
      call flow_a%jacobian(x, p(2), gx, glam)
      worst = max(worst, maxval(abs(fp(:, 2) - glam))/maxval(abs(glam)))
    end do
    print '(a, es10.2)', '  slow flow field vs sloshdyn_slowflow ('//trim(tag(merge(1, 2, &
      internal_resonance)))//'): max relative difference ', worst
    call check_true('slow flow field = slow_flow: f, df/dx, df/drho, df/dA ('// &
                    trim(tag(merge(1, 2, internal_resonance)))//', 1e-13)', worst < 1.0e-13_wp)
  end subroutine test_field_matches_slow_flow

  !> The exact d(J u)/dx, d(J u)/dp, B and C against the finite-difference defaults.
  subroutine test_higher_derivatives()
    type(slow_flow_field) :: field
    type(fd_slow_flow) :: fd
    real(wp) :: x(4), p(2), u(4), v(4), w(4), hx(4, 4), hp(4, 2), hx_f(4, 4), hp_f(4, 2), &
                b(4), b_f(4), b_swap(4), c(4), c_f(4), c_perm(4)
    integer :: status
    character(len=message_len) :: message

    call make_slow_flow_field(paper_model(kappa12, gamma12, a12, 0.509_wp), .true., &
                              [CHART_RHO, CHART_A], field, status, message)
    fd%exact = field
    x = [0.07_wp, -0.02_wp, 0.05_wp, 0.09_wp]
    p = [0.5095_wp, 0.0008_wp]
    u = [0.3_wp, -1.0_wp, 0.5_wp, 0.2_wp]
    v = [0.8_wp, 0.1_wp, -0.4_wp, 1.0_wp]
    w = [-0.2_wp, 0.6_wp, 0.9_wp, -0.7_wp]
    call field%jacobian_derivative(x, p, u, hx, hp)
    call fd%jacobian_derivative(x, p, u, hx_f, hp_f)
    print '(a, 2es10.2)', '  slow flow: relative difference to finite differences of d(Ju)/dx, '// &
      'd(Ju)/dp: ', maxval(abs(hx - hx_f))/maxval(abs(hx)), maxval(abs(hp - hp_f))/maxval(abs(hp))
    call check_true('slow flow d(Ju)/dx = finite differences (1e-8)', &
                    maxval(abs(hx - hx_f)) <= 1.0e-8_wp*maxval(abs(hx)))
    call check_true('slow flow d(Ju)/dp = finite differences (1e-8)', &
                    maxval(abs(hp - hp_f)) <= 1.0e-8_wp*maxval(abs(hp)))
    call field%second_derivative(x, p, u, v, b)
    call field%second_derivative(x, p, v, u, b_swap)
    call fd%second_derivative(x, p, u, v, b_f)
    call check_true('slow flow B symmetric and = d(Ju)/dx v', &
                    maxval(abs(b - b_swap)) <= 1.0e-15_wp*maxval(abs(b)) .and. &
                    maxval(abs(b - matmul(hx, v))) <= 1.0e-15_wp*maxval(abs(b)))
    call check_true('slow flow B = finite differences (1e-8)', &
                    maxval(abs(b - b_f)) <= 1.0e-8_wp*maxval(abs(b)))
    call field%third_derivative(x, p, u, v, w, c)
    call field%third_derivative(x, p, w, u, v, c_perm)
    call fd%third_derivative(x, p, u, v, w, c_f)
    print '(a, es10.2)', '  slow flow: relative difference of C to finite differences: ', &
      maxval(abs(c - c_f))/maxval(abs(c))
    call check_true('slow flow C symmetric', maxval(abs(c - c_perm)) <= 1.0e-14_wp*maxval(abs(c)))
    call check_true('slow flow C = finite differences (1e-6)', &
                    maxval(abs(c - c_f)) <= 1.0e-6_wp*maxval(abs(c)))
  end subroutine test_higher_derivatives

  !> gamma as a chart parameter: gamma11, gamma22 linear in gamma (checked against the modal
  !> expansion at a third value), df/dgamma against a central difference.
  subroutine test_gamma_parameter()
    type(slow_flow_field) :: field, reference
    type(modal_coefficients) :: modal
    type(model_t) :: model
    real(wp) :: x(4), p(2), f(4), fx(4, 4), fp(4, 2), fa(4), fb(4), h
    integer :: status
    character(len=message_len) :: message

    model = paper_model(kappa12, gamma12, a12, 0.509_wp)
    call make_slow_flow_field(model, .true., [CHART_GAMMA, CHART_RHO], field, status, message)
    call check_true('gamma chart field made ('//trim(message)//')', status == SD_OK)
    model%gamma = 0.0037_wp
    call set_coefficients(model)
    call expand_model(model, modal, status, message)
    associate (c => field%constants)
      call check_close('gamma11 linear in gamma', c%gamma11_0 + c%gamma11_slope*0.0037_wp, &
                       modal%gamma11, 1.0e-12_wp)
      call check_close('gamma22 linear in gamma', c%gamma22_0 + c%gamma22_slope*0.0037_wp, &
                       modal%gamma22, 1.0e-12_wp)
    end associate
    call make_slow_flow_field(model, .true., [CHART_RHO, CHART_A], reference, status, message)
    call check_true('c_ij independent of gamma', maxval(abs(reference%constants%c - &
                    field%constants%c)) <= 1.0e-13_wp*maxval(abs(field%constants%c)))
    x = [0.07_wp, -0.02_wp, 0.05_wp, 0.09_wp]
    p = [0.0037_wp, 0.5095_wp]
    call field%evaluate(x, p, f, fx, fp)
    call reference%evaluate(x, [0.5095_wp, a12], fa, fx, fp(:, 1:2))
    call check_true('gamma field = (rho, A) field at the same values', &
                    maxval(abs(f - fa)) <= 1.0e-14_wp*maxval(abs(fa)))
    call field%evaluate(x, p, f, fx, fp)
    h = 1.0e-4_wp
    call field%evaluate(x, p + [h, 0.0_wp], fa, fx, fp)
    call field%evaluate(x, p - [h, 0.0_wp], fb, fx, fp)
    call field%evaluate(x, p, f, fx, fp)
    call check_true('df/dgamma = central difference (f is linear in gamma)', &
                    maxval(abs(fp(:, 1) - (fa - fb)/(2*h))) <= 1.0e-9_wp*maxval(abs(fp(:, 1))))
  end subroutine test_gamma_parameter

  subroutine test_bad_parameters()
    type(slow_flow_field) :: field
    integer :: status
    character(len=message_len) :: message
    call make_slow_flow_field(paper_model(kappa12, gamma12, a12, 0.509_wp), .true., &
                              [CHART_A, CHART_A], field, status, message)
    call check_true('same chart parameter twice: SD_BAD_INPUT ('//trim(message)//')', &
                    status == SD_BAD_INPUT .and. index(message, 'differ') > 0)
    call make_slow_flow_field(paper_model(kappa12, gamma12, a12, 0.509_wp), .true., &
                              [CHART_RHO, 7], field, status, message)
    call check_true('unknown chart parameter: SD_BAD_INPUT naming it ('//trim(message)//')', &
                    status == SD_BAD_INPUT .and. index(message, 'chart parameter 2') > 0)
  end subroutine test_bad_parameters

  !> One-parameter continuation in rho at amplitude (n_scan rho values seeded): the folds and
  !> Hopf points (rho).
  subroutine special_points(kappa, gamma, amplitude, rho_lo, rho_hi, ds_max, n_scan, folds, &
                            n_folds, hopfs, n_hopfs, table, special, n_special)
    real(wp), intent(in) :: kappa, gamma, amplitude, rho_lo, rho_hi, ds_max
    integer, intent(in) :: n_scan
    real(wp), intent(out) :: folds(:), hopfs(:)
    integer, intent(out) :: n_folds, n_hopfs, n_special
    real(wp), intent(out) :: table(:, :), special(:, :)
    type(response_options) :: ropt
    integer :: n_points, status, k
    logical :: complete
    character(len=message_len) :: message
    ropt%n_scan = n_scan
    ropt%continuation%ds_max = ds_max
    ropt%continuation%ds = min(ropt%continuation%ds, ds_max)
    call frequency_response(paper_model(kappa, gamma, amplitude, 0.5_wp*(rho_lo + rho_hi)), &
                            .true., PARAMETER_RHO, rho_lo, rho_hi, ropt, table, n_points, &
                            special, n_special, complete, status, message)
    if (status /= SD_OK) print '(a)', '    frequency_response: '//trim(message)
    n_folds = 0
    n_hopfs = 0
    do k = 1, n_special
      if (nint(special(SPECIAL_KIND, k)) == SPECIAL_FOLD) then
        n_folds = n_folds + 1
        folds(n_folds) = special(SPECIAL_RHO, k)
      else if (nint(special(SPECIAL_KIND, k)) == SPECIAL_HOPF) then
        n_hopfs = n_hopfs + 1
        hopfs(n_hopfs) = special(SPECIAL_RHO, k)
      end if
    end do
  end subroutine special_points

  !> The crossings of the curves with A = level, their rho.
  subroutine crossings_at(field, curves, n_curves, kind, level, rho, n_rho)
    type(slow_flow_field), intent(in) :: field
    type(bifurcation_curve), intent(in) :: curves(:)
    integer, intent(in) :: n_curves, kind
    real(wp), intent(in) :: level
    real(wp), intent(out) :: rho(:)
    integer, intent(out) :: n_rho
    real(wp) :: x(4, 20), p(2, 20)
    integer :: c, found, status
    character(len=message_len) :: message
    n_rho = 0
    do c = 1, n_curves
      if (curves(c)%kind /= kind) cycle
      call curve_crossings(field, curves(c), 2, level, chart_options(), x, p, found, status, &
                           message)
      if (status /= SD_OK) print '(a)', '    '//trim(message)
      rho(n_rho + 1:n_rho + found) = p(1, 1:found)
      n_rho = n_rho + found
    end do
  end subroutine crossings_at

  !> The crossings of the curves of one kind (named curve_name) with the level A = level must be
  !> the points the one-parameter continuation found there (points, named points_name), as a set
  !> to 1e-7 in rho.
  subroutine check_crossings(label, curve_name, points_name, field, curves, kind, level, points)
    character(len=*), intent(in) :: label, curve_name, points_name
    type(slow_flow_field), intent(in) :: field
    type(bifurcation_curve), intent(in) :: curves(:)
    integer, intent(in) :: kind
    real(wp), intent(in) :: level, points(:)
    real(wp) :: crossing(40), worst
    integer :: n_cross

    call crossings_at(field, curves, size(curves), kind, level, crossing, n_cross)
    print '(a, 10f13.9)', '    '//trim(label)//': '//points_name//' (one-parameter) ', points
    print '(a, 10f13.9)', '    '//trim(label)//': '//curve_name//' curve crossings ', &
      crossing(1:n_cross)
    call check_true('Fig 12 '//trim(label)//': '//curve_name//' curve crossings = '// &
                    'one-parameter '//points_name//' (1e-7 in rho)', &
                    same_sets(crossing(1:n_cross), points, 1.0e-7_wp, worst))
    print '(a, es10.2)', '      max |difference| in rho: ', worst
  end subroutine check_crossings

  !> Is every value of a within tol of some value of b, and the other way round?
  logical function same_sets(a, b, tol, worst)
    real(wp), intent(in) :: a(:), b(:), tol
    real(wp), intent(out) :: worst
    integer :: i
    worst = 0
    same_sets = size(a) == size(b)
    do i = 1, size(a)
      if (size(b) > 0) worst = max(worst, minval(abs(b - a(i))))
    end do
    do i = 1, size(b)
      if (size(a) > 0) worst = max(worst, minval(abs(a - b(i))))
    end do
    same_sets = same_sets .and. worst <= tol
  end function same_sets

  !> The Fig 12 chart in (rho, A): a fold or Hopf curve from every special point of the
  !> one-parameter continuations (seeded densely, n_scan = 41) at four amplitudes that is not on a
  !> curve already; at each amplitude the crossings of the fold curves and of the Hopf curves are
  !> exactly the folds and Hopf points of the one-parameter continuation (1e-7 in rho). The
  !> curves from the points at A = 0.00075 alone, the chart of Fig 12, are timed.
  subroutine test_fig12_chart()
    type(slow_flow_field) :: field
    type(bifurcation_curve) :: curves(20)
    real(wp), allocatable :: table(:, :), special(:, :)
    real(wp) :: folds(40), hopfs(40), crossing(40), start_p(2), elapsed
    real(wp), parameter :: levels(4) = [0.00075_wp, 0.0005_wp, 0.001_wp, 0.0015_wp]
    integer :: n_folds, n_hopfs, n_special, n_curves, k, c, col, kind, status, n_cross, l, &
               clock0, clock1, rate, i, n_fig12
    character(len=message_len) :: message
    character(len=16) :: label
    logical :: covered

    allocate (table(POINT_ROWS, 60000), special(SPECIAL_ROWS, 200))
    call make_slow_flow_field(paper_model(kappa12, gamma12, a12, 0.51_wp), .true., &
                              [CHART_RHO, CHART_A], field, status, message)
    n_curves = 0
    elapsed = 0
    do l = 1, size(levels)
      call special_points(kappa12, gamma12, levels(l), rho_min, rho_max, 0.01_wp, 41, folds, &
                          n_folds, hopfs, n_hopfs, table, special, n_special)
      if (l == 1) call check_true('Fig 12 at A = 0.00075: two Hopf points and folds '// &
                                  '(one-parameter)', n_hopfs == 2 .and. n_folds >= 2)
      call system_clock(clock0, rate)
      do k = 1, n_special
        kind = merge(CURVE_FOLD, CURVE_HOPF, nint(special(SPECIAL_KIND, k)) == SPECIAL_FOLD)
        start_p = [special(SPECIAL_RHO, k), special(SPECIAL_A, k)]
        covered = .false.
        do c = 1, n_curves
          if (curves(c)%kind /= kind) cycle
          call crossings_at(field, curves(c:c), 1, kind, start_p(2), crossing, n_cross)
          if (any(abs(crossing(1:n_cross) - start_p(1)) < 1.0e-7_wp)) covered = .true.
        end do
        if (covered) cycle
        n_curves = n_curves + 1
        col = nint(special(SPECIAL_COLUMN, k))
        if (kind == CURVE_FOLD) then
          call fold_curve(field, table(POINT_X:POINT_X + 3, col), start_p, chart_options(), &
                          curves(n_curves), status, message)
        else
          call hopf_curve(field, table(POINT_X:POINT_X + 3, col), start_p, chart_options(), &
                          curves(n_curves), status, message)
        end if
        write (label, '(a, i0)') merge('fold curve ', 'Hopf curve ', kind == CURVE_FOLD), n_curves
        call check_true('Fig 12 '//trim(label)//': complete, status 0 ('//trim(message)//')', &
                        status == SD_OK .and. curves(n_curves)%complete .and. &
                        curves(n_curves)%n_unlocated == 0)
      end do
      call system_clock(clock1)
      if (l == 1) then
        elapsed = real(clock1 - clock0, wp)/rate
        n_fig12 = n_curves
      end if
    end do
    print '(a, f8.4, a, i0, a, i0, a)', '  Fig 12 chart (seeds at A = 0.00075): ', elapsed, &
      ' s for ', n_fig12, ' curves, ', sum(curves(1:n_fig12)%n_points), &
      ' points (with the checks for duplicates)'
    do c = 1, n_curves
      print '(a, i0, a, a, a, i0, a, a, a, a)', '    curve ', c, ' (', &
        trim(merge('fold', 'Hopf', curves(c)%kind == CURVE_FOLD)), '): ', curves(c)%n_points, &
        ' points, ends ', curve_end_name(curves(c)%end_reason(1)), ' / ', &
        curve_end_name(curves(c)%end_reason(2))
      do i = 1, curves(c)%n_codim2
        print '(a, a, a, f12.9, a, es15.8)', '      ', codim2_name(curves(c)%codim2(i)%kind), &
          ' at rho = ', curves(c)%codim2(i)%p(1), ', A = ', curves(c)%codim2(i)%p(2)
      end do
    end do
    call check_true('Fig 12 chart: one Hopf curve through both Hopf points at A = 0.00075', &
                    count(curves(1:n_fig12)%kind == CURVE_HOPF) == 1)

    do l = 1, size(levels)
      call special_points(kappa12, gamma12, levels(l), rho_min, rho_max, 0.01_wp, 41, folds, &
                          n_folds, hopfs, n_hopfs, table, special, n_special)
      write (label, '(a, es9.2)') 'A =', levels(l)
      call check_crossings(label, 'Hopf', 'Hopf points', field, curves(:n_curves), CURVE_HOPF, &
                           levels(l), hopfs(1:n_hopfs))
      call check_crossings(label, 'fold', 'folds', field, curves(:n_curves), CURVE_FOLD, &
                           levels(l), folds(1:n_folds))
    end do
  end subroutine test_fig12_chart

  !> Fig 11 (sec 4.2: "for a critical threshold saddle-node bifurcation takes place"): the fold
  !> pair is born at a cusp between A = 0.00025 and 0.0005, where the one-parameter
  !> continuations find no fold and two folds; bisection on that number brackets the cusp's A.
  subroutine test_fig11_cusp()
    type(slow_flow_field) :: field
    type(bifurcation_curve) :: curve
    real(wp), allocatable :: table(:, :), special(:, :)
    real(wp) :: folds(20), hopfs(20), a_low, a_high, a_mid, a_cusp, rho_cusp
    integer :: n_folds, n_hopfs, n_special, k, status, column, i, iteration, n_low, n_high
    character(len=message_len) :: message
    real(wp), parameter :: fine = 2.0e-4_wp   ! ds_max of the one-parameter continuations

    allocate (table(POINT_ROWS, 40000), special(SPECIAL_ROWS, 200))
    call special_points(kappa11, gamma11, 0.0005_wp, rho_min, rho_max, 0.01_wp, 5, folds, &
                        n_folds, hopfs, n_hopfs, table, special, n_special)
    call check_true('Fig 11 at A = 0.0005: two folds (one-parameter)', n_folds == 2)
    call special_points(kappa11, gamma11, 0.00025_wp, rho_min, rho_max, 0.01_wp, 5, folds, n_low, &
                        hopfs, n_hopfs, table, special, n_special)
    call check_true('Fig 11 at A = 0.00025: no fold (one-parameter)', n_low == 0)
    call special_points(kappa11, gamma11, 0.0005_wp, rho_min, rho_max, 0.01_wp, 5, folds, &
                        n_folds, hopfs, n_hopfs, table, special, n_special)
    call make_slow_flow_field(paper_model(kappa11, gamma11, 0.0005_wp, 0.51_wp), .true., &
                              [CHART_RHO, CHART_A], field, status, message)
    do k = 1, n_special
      if (nint(special(SPECIAL_KIND, k)) == SPECIAL_FOLD) exit
    end do
    column = nint(special(SPECIAL_COLUMN, k))
    call fold_curve(field, table(POINT_X:POINT_X + 3, column), &
                    [special(SPECIAL_RHO, k), special(SPECIAL_A, k)], chart_options(), curve, &
                    status, message)
    call check_true('Fig 11 fold curve: complete ('//trim(message)//')', &
                    status == SD_OK .and. curve%complete)
    a_cusp = -1
    rho_cusp = -1
    do i = 1, curve%n_codim2
      if (curve%codim2(i)%kind /= CODIM2_CUSP) cycle
      a_cusp = curve%codim2(i)%p(2)
      rho_cusp = curve%codim2(i)%p(1)
    end do
    print '(a, f12.9, a, es16.9)', '  Fig 11 cusp at rho = ', rho_cusp, ', A = ', a_cusp
    call check_true('Fig 11: a cusp between A = 0.00025 and 0.0005', &
                    count(curve%codim2%kind == CODIM2_CUSP) == 1 .and. a_cusp > 0.00025_wp .and. &
                    a_cusp < 0.0005_wp)
    call check_true('Fig 11 fold curve: A >= A_cusp on all of it (the fold pair is born there)', &
                    minval(curve%p(2, 1:curve%n_points)) >= a_cusp*(1 - 1.0e-12_wp))

    ! bisection on the number of folds of the one-parameter continuation (near rho_cusp)
    a_low = 0.00025_wp
    a_high = 0.0005_wp
    do iteration = 1, 9
      a_mid = (a_low + a_high)/2
      call special_points(kappa11, gamma11, a_mid, rho_cusp - 0.01_wp, rho_cusp + 0.01_wp, fine, &
                          5, folds, n_folds, hopfs, n_hopfs, table, special, n_special)
      if (n_folds == 0) then
        a_low = a_mid
      else
        a_high = a_mid
      end if
    end do
    print '(a, 2es16.9)', '  Fig 11: bisection on the fold count brackets the birth in ', &
      a_low, a_high
    call check_true('Fig 11: the cusp lies in the bracket of the bisection', &
                    a_low <= a_cusp .and. a_cusp <= a_high)
    call special_points(kappa11, gamma11, a_cusp*(1 - 1.0e-3_wp), rho_cusp - 0.01_wp, &
                        rho_cusp + 0.01_wp, fine, 5, folds, n_low, hopfs, n_hopfs, table, &
                        special, n_special)
    call special_points(kappa11, gamma11, a_cusp*(1 + 1.0e-3_wp), rho_cusp - 0.01_wp, &
                        rho_cusp + 0.01_wp, fine, 5, folds, n_high, hopfs, n_hopfs, table, &
                        special, n_special)
    print '(a, i0, a, i0, a, 2f13.9)', '  Fig 11: folds at A_cusp (1 -+ 1e-3): ', n_low, ', ', &
      n_high, ' at rho ', folds(1:n_high)
    call check_true('Fig 11: no fold just below the cusp, two just above', &
                    n_low == 0 .and. n_high == 2)
    if (n_high == 2) call check_true('Fig 11: the two folds just above are near rho_cusp', &
                                     all(abs(folds(1:2) - rho_cusp) < 1.0e-4_wp))
  end subroutine test_fig11_cusp

  !> l1 at the Fig 12 Hopf points (A = 0.00075) against direct integration of the slow flow
  !> (DOP853): just inside the unstable interval, at distance mu = Re(eigenvalue) from the
  !> imaginary axis, the normal form z' = (mu + i omega) z + l1 omega z|z|^2 (unit q) has a
  !> stable cycle (l1 < 0) with |z|^2 = -mu/(l1 omega), so the mean of |x - x_eq|^2 over it,
  !> 2 |z|^2 |q|^2, is -2 mu/(l1 omega) + O(mu^2). Two distances mu and mu/2 remove the O(mu^2)
  !> term (Richardson); the paper's Fig 14 shows the stable beating between the Hopf points.
  subroutine test_lyapunov_by_simulation()
    type(slow_flow_field) :: field
    type(slow_flow) :: flow
    type(bifurcation_curve) :: curve
    real(wp), allocatable :: table(:, :), special(:, :)
    real(wp) :: folds(40), hopfs(40), x_h(4, 4), p_h(2, 4), l1, omega, rho, ratio(2), &
                predicted, measured, side
    integer :: n_folds, n_hopfs, n_special, k, status, found, h, trial
    character(len=message_len) :: message

    allocate (table(POINT_ROWS, 40000), special(SPECIAL_ROWS, 200))
    call special_points(kappa12, gamma12, a12, rho_min, rho_max, 0.01_wp, 5, folds, n_folds, &
                        hopfs, n_hopfs, table, special, n_special)
    call make_slow_flow_field(paper_model(kappa12, gamma12, a12, 0.51_wp), .true., &
                              [CHART_RHO, CHART_A], field, status, message)
    call make_slow_flow(paper_model(kappa12, gamma12, a12, 0.51_wp), .true., PARAMETER_RHO, flow, &
                        status, message)
    do k = 1, n_special
      if (nint(special(SPECIAL_KIND, k)) == SPECIAL_HOPF) exit
    end do
    call hopf_curve(field, table(POINT_X:POINT_X + 3, nint(special(SPECIAL_COLUMN, k))), &
                    [special(SPECIAL_RHO, k), a12], chart_options(), curve, status, message)
    call curve_crossings(field, curve, 2, a12, chart_options(), x_h, p_h, found, status, message)
    call check_true('Fig 12: the Hopf curve crosses A = 0.00075 twice', found == 2)
    do h = 1, found
      call first_lyapunov_coefficient(field, x_h(:, h), p_h(:, h), l1, omega, status, message)
      ! the unstable side: towards the other Hopf point
      side = sign(1.0_wp, p_h(1, 3 - h) - p_h(1, h))
      do trial = 1, 2
        rho = p_h(1, h) + side*2.0e-6_wp/trial
        call cycle_ratio(field, flow, rho, x_h(:, h), l1, ratio(trial))
      end do
      predicted = -2/(l1*omega)
      measured = 2*ratio(2) - ratio(1)
      print '(a, f12.9, a, es12.4, a, es12.4, a, 2es12.4, a, es12.4)', '  Hopf point rho = ', &
        p_h(1, h), ': l1 = ', l1, ', -2/(l1 omega) = ', predicted, &
        '; simulated <|x - x_eq|^2>/mu = ', ratio, ' -> ', measured
      call check_true('Fig 12 Hopf point: supercritical (l1 < 0; the beating of Fig 14)', l1 < 0)
      call check_close('Fig 12 Hopf point: cycle size by simulation = -2 mu/(l1 omega) (1e-3)', &
                       measured, predicted, 1.0e-3_wp)
    end do
  end subroutine test_lyapunov_by_simulation

  !> Without internal resonance (Fig 9: kappa = 4.5 hardening, 4.7 softening; gamma = 0.0025)
  !> the steady states solve eq (49), a cubic in z = a1^2,
  !>   k^2 z^3 - 2 sigma k z^2 + (sigma^2 + g^2) z - F^2 = 0
  !> (k = c11/(8 omega1), g = gamma11/2, sigma = rho - omega1, F = rho^2 A F11/(2 omega1)).
  !> A fold is a double root, the cusp a triple root: sigma^2 = 3 g^2 with sign(sigma) = sign(k),
  !> z0 = 2 sigma/(3 k), F^2 = k^2 z0^3. Every point of the fold curve is a double root of the
  !> cubic, and its cusp is that point.
  subroutine test_nonresonant_cusp(kappa)
    real(wp), intent(in) :: kappa
    type(slow_flow_field) :: field
    type(modal_coefficients) :: modal
    type(bifurcation_curve) :: curve
    type(curve_options) :: opt
    type(response_options) :: ropt
    real(wp), allocatable :: table(:, :), special(:, :)
    real(wp) :: k, g, sigma, z0, rho_c, a_c, c(4), z, worst, scale
    integer :: n_points, n_special, status, i, j, column, found
    logical :: complete
    character(len=message_len) :: message
    character(len=12) :: tag

    write (tag, '(a, f3.1)') 'kappa = ', kappa
    call expand_model(paper_model(kappa, 0.0025_wp, 0.0005_wp, 0.5_wp), modal, status, message)
    k = modal%c(1, 1)/(8*modal%omega1)
    g = modal%gamma11/2
    sigma = sign(sqrt(3.0_wp)*g, k)
    z0 = 2*sigma/(3*k)
    rho_c = modal%omega1 + sigma
    a_c = abs(k)*z0**1.5_wp*2*modal%omega1/(rho_c**2*abs(modal%F11))

    allocate (table(POINT_ROWS, 20000), special(SPECIAL_ROWS, 50))
    call frequency_response(paper_model(kappa, 0.0025_wp, 0.0005_wp, modal%omega1), .false., &
                            PARAMETER_RHO, modal%omega1 - 0.04_wp, modal%omega1 + 0.04_wp, ropt, &
                            table, n_points, special, n_special, complete, status, message)
    call check_true('non-resonant ('//tag//'): folds at A = 0.0005 (one-parameter)', &
                    n_special >= 1)
    if (n_special < 1) return
    column = nint(special(SPECIAL_COLUMN, 1))
    call make_slow_flow_field(paper_model(kappa, 0.0025_wp, 0.0005_wp, modal%omega1), .false., &
                              [CHART_RHO, CHART_A], field, status, message)
    opt = chart_options()
    opt%p_min = [modal%omega1 - 0.05_wp, 1.0e-8_wp]
    opt%p_max = [modal%omega1 + 0.05_wp, 0.002_wp]
    call fold_curve(field, table(POINT_X:POINT_X + 1, column), [special(SPECIAL_RHO, 1), &
                    special(SPECIAL_A, 1)], opt, curve, status, message)
    call check_true('non-resonant ('//tag//') fold curve: complete ('//trim(message)//')', &
                    status == SD_OK .and. curve%complete)
    worst = 0
    do j = 1, curve%n_points
      c = nonresonant_cubic(modal, curve%p(1, j), curve%p(2, j))
      z = sum(curve%x(:, j)**2)
      scale = abs(c(1))*z**3 + abs(c(2))*z**2 + abs(c(3))*z + abs(c(4))
      worst = max(worst, abs(((c(1)*z + c(2))*z + c(3))*z + c(4))/scale, &
                  abs((3*c(1)*z + 2*c(2))*z + c(3))*z/scale)
    end do
    print '(a, es10.2)', '  non-resonant ('//tag//'): max relative residual of the double root '// &
      'of eq (49) on the fold curve: ', worst
    call check_true('non-resonant ('//tag//') fold curve: every point a double root of eq (49) '// &
                    '(1e-10)', worst < 1.0e-10_wp)
    found = 0
    do i = 1, curve%n_codim2
      if (curve%codim2(i)%kind /= CODIM2_CUSP) cycle
      found = found + 1
      print '(a, 2es20.12, a, 2es20.12)', '  non-resonant ('//tag//') cusp at ', &
        curve%codim2(i)%p, '; eq (49): ', rho_c, a_c
      call check_close('non-resonant ('//tag//'): cusp rho = omega1 + sign(k) sqrt(3) g', &
                       curve%codim2(i)%p(1), rho_c, 1.0e-10_wp)
      call check_close('non-resonant ('//tag//'): cusp A from F^2 = k^2 z0^3', &
                       curve%codim2(i)%p(2), a_c, 1.0e-8_wp)
      call check_close('non-resonant ('//tag//'): cusp |B1|^2 = z0', &
                       sum(curve%codim2(i)%x**2), z0, 1.0e-8_wp)
    end do
    call check_true('non-resonant ('//tag//'): one cusp, nothing else', found == 1 .and. &
                    curve%n_codim2 == 1)
  end subroutine test_nonresonant_cusp

    !> mean |x - x_eq|^2 over the cycle at rho, divided by mu (the real part of the pair).
    subroutine cycle_ratio(field, flow, rho, x_guess, l1, value)
      type(slow_flow_field), intent(in) :: field
      type(slow_flow), intent(in) :: flow
      real(wp), intent(in) :: rho, x_guess(4), l1
      real(wp), intent(out) :: value
      type(slow_flow_ode) :: sys
      type(dop853_integrator) :: integ
      type(ode_options) :: opt
      type(ode_stats) :: stats
      real(wp) :: x_eq(4), gx(4, 4), glam(4), re(4), im(4), mu, w, period, t_settle
      real(wp), allocatable :: t_out(:), y_out(:, :)
      integer :: iterations, info, j, i, n_out
      character(len=message_len) :: msg
      x_eq = x_guess
      call newton_solve(flow, x_eq, rho, newton_options(), iterations, info, msg)
      call flow%jacobian(x_eq, rho, gx, glam)
      call eigenvalues(gx, re, im, info, msg)
      i = maxloc(re, 1, mask=im > 0)
      mu = re(i)
      w = im(i)
      period = 2*pi/w
      t_settle = 8/mu
      n_out = 400
      allocate (t_out(n_out), y_out(4, n_out))
      t_out = [(t_settle + 20*period*(j - 1)/n_out, j = 1, n_out)]
      sys%field = field
      sys%p = [rho, a12]
      opt%rtol = 1.0e-11_wp
      opt%atol = 1.0e-14_wp
      ! start on the predicted cycle, near enough for the transient to die out in t_settle
      call integrate_with_dop853(integ, sys, x_eq + sqrt(-2*mu/(l1*w))*[1.0_wp, 0.0_wp, 0.0_wp, &
                                 0.0_wp], t_out, y_out, opt, stats, info, msg)
      value = sum((y_out - spread(x_eq, 2, n_out))**2)/n_out/mu
      if (info /= SD_OK) value = huge(1.0_wp)
    end subroutine cycle_ratio

  subroutine integrate_with_dop853(integ, sys, y0, t_out, y_out, opt, stats, status, message)
    use sloshdyn_ode, only: integrate_with
    type(dop853_integrator), intent(inout) :: integ
    type(slow_flow_ode), intent(in) :: sys
    real(wp), intent(in) :: y0(:), t_out(:)
    real(wp), intent(out) :: y_out(:, :)
    type(ode_options), intent(in) :: opt
    type(ode_stats), intent(out) :: stats
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    call integrate_with(integ, sys, 0.0_wp, y0, t_out, y_out, opt, stats, status, message)
  end subroutine integrate_with_dop853
end program test_slowflow_chart
