!> The slow flow of the 3:1 internal resonance (sec 3.3.2, eq 52; or the non-resonant one of
!> sec 3.3.1) as a vector field in two of its parameters, for stability charts
!> (sloshdyn_bifurcation): any two of rho, A and gamma are (p1, p2), the third and everything
!> else come from the model.
!>
!> In the Cartesian form of sloshdyn_slowflow, x = (Re B1, Im B1, Re B2, Im B2),
!>   B1' = lin1 B1 + rho^2 A F11/(2 omega1) + sum of cubic terms
!>   B2' = lin2 B2 + sum of cubic terms,
!>   lin1 = -(gamma11/2 + i sigma2), lin2 = -(gamma22/2 + i (3 sigma2 - sigma1)),
!> sigma2 = rho - omega1, sigma1 = omega2 - 3 omega1, and the cubic terms of eq (52) (as coded
!> in sloshdyn_slowflow, which tests/fortran/test_slowflow_chart.f90 checks against this one):
!>   B1': i/(8 omega1) (c11 B1 B1 conj(B1) + 2 c12 B1 B2 conj(B2) - c13 conj(B1) conj(B1) B2)
!>   B2': i/(8 omega2) (c21 B2 B2 conj(B2) + 2 c22 B2 B1 conj(B1) - c23 B1 B1 B1)
!> The field is a cubic polynomial in (B, conj B), so all its derivatives are exact: each cubic
!> term c s1 s2 s3 (each slot s a B_a or conj(B_a)) has the symmetric multilinear form
!> T(U, V, W) = c s1(U) s2(V) s3(W), and D f[u] = T(U,B,B) + T(B,U,B) + T(B,B,U), D^2 f[u, v] and
!> D^3 f[u, v, w] are the sums over the placements of the directions (U = u1 + i u2, ...).
!>
!> gamma enters only through the modal damping: gamma11 and gamma22 are linear in gamma (the rod
!> damping -gamma x2' and the sloshing damping -2 zeta x1' are the only terms linear in a
!> velocity; the c_ij come from terms with zero or two velocities), so with gamma a chart
!> parameter they are taken from the modal expansion at gamma and at gamma + 1.
module sloshdyn_slowflow_chart
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT
  use sloshdyn_text, only: num2str
  use sloshdyn_model, only: model_t, set_coefficients
  use sloshdyn_modal, only: modal_coefficients, expand_model
  use sloshdyn_excitation, only: PARAMETER_RHO, PARAMETER_A
  use sloshdyn_bifurcation, only: two_parameter_field
  implicit none
  private
  public :: slow_flow_field, make_slow_flow_field, chart_parameter_name
  public :: CHART_RHO, CHART_A, CHART_GAMMA, CHART_KAPPA

  !> Which model value a chart parameter is (rho and A keep the excitation's codes).
  integer, parameter :: CHART_RHO = PARAMETER_RHO, CHART_A = PARAMETER_A, CHART_GAMMA = 3, &
                        CHART_KAPPA = 4
  !> Relative step of the central differences in kappa (the modal constants are smooth in it).
  real(wp), parameter :: kappa_step = 1.0e-6_wp

  !> The cubic terms: row (1: B1', 2: B2'), the variable (1: B1, 2: B2) of each slot and whether
  !> the slot is conjugated; coefficients in slow_flow_terms.
  integer, parameter :: n_terms = 6
  integer, parameter :: term_row(n_terms) = [1, 1, 1, 2, 2, 2]
  integer, parameter :: term_var(3, n_terms) = reshape([1, 1, 1, 1, 2, 2, 1, 1, 2, &
                                                        2, 2, 2, 2, 1, 1, 1, 1, 1], [3, n_terms])
  logical, parameter :: term_conj(3, n_terms) = reshape([.false., .false., .true., &
                                                         .false., .false., .true., &
                                                         .true., .true., .false., &
                                                         .false., .false., .true., &
                                                         .false., .false., .true., &
                                                         .false., .false., .false.], [3, n_terms])

  !> What the slow flow takes from the modal expansion of a model.
  type :: slow_flow_constants
    real(wp) :: omega1 = 0, omega2 = 0, F11 = 0, c(2, 3) = 0
    !> gamma11 = gamma11_0 + gamma11_slope gamma (likewise gamma22)
    real(wp) :: gamma11_0 = 0, gamma11_slope = 0, gamma22_0 = 0, gamma22_slope = 0
  end type slow_flow_constants

  type, extends(two_parameter_field) :: slow_flow_field
    logical :: internal_resonance = .true.   !< 3:1 (4 unknowns) or none (2 unknowns)
    integer :: parameters(2) = [CHART_RHO, CHART_A]   !< what p1 and p2 are
    real(wp) :: rho = 0, amplitude = 0, gamma = 0     !< the model's values (non-chart ones used)
    type(slow_flow_constants) :: constants            !< at the model's kappa
    !> the model (with kappa a chart parameter, the constants are expanded again at each kappa)
    type(model_t) :: model
  contains
    procedure :: evaluate => field_evaluate
    procedure :: jacobian_derivative => field_jacobian_derivative
    procedure :: second_derivative => field_second_derivative
    procedure :: third_derivative => field_third_derivative
    procedure :: dimension => field_dimension
  end type slow_flow_field

contains

  !> The field of the model's slow flow with chart parameters (p1, p2) = parameters (CHART_*,
  !> distinct). Needs what the modal expansion needs (kappa > s1, n >= 2, p >= 1).
  subroutine make_slow_flow_field(model, internal_resonance, parameters, field, status, message)
    type(model_t), intent(in) :: model
    logical, intent(in) :: internal_resonance
    integer, intent(in) :: parameters(2)
    type(slow_flow_field), intent(out) :: field
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    integer :: k

    status = SD_OK
    message = ''
    do k = 1, 2
      if (parameters(k) < CHART_RHO .or. parameters(k) > CHART_KAPPA) then
        status = SD_BAD_INPUT
        message = 'chart parameter '//num2str(k)//' = '//num2str(parameters(k))// &
                  ' is out of range: it must be rho (1), A (2), gamma (3) or kappa (4)'
        return
      end if
    end do
    if (parameters(1) == parameters(2)) then
      status = SD_BAD_INPUT
      message = 'the two chart parameters must differ (both are '// &
                chart_parameter_name(parameters(1))//')'
      return
    end if
    field%internal_resonance = internal_resonance
    field%parameters = parameters
    field%rho = model%excitation%rho
    field%amplitude = model%excitation%A
    field%gamma = model%gamma
    field%model = model
    call expand_constants(model, any(parameters == CHART_GAMMA), field%constants, status, message)
  end subroutine make_slow_flow_field

  !> The slow flow's constants of a model; with_gamma: also their slopes in gamma (gamma11 and
  !> gamma22 are linear in it), from a second expansion at gamma + 1.
  pure subroutine expand_constants(model, with_gamma, constants, status, message)
    type(model_t), intent(in) :: model
    logical, intent(in) :: with_gamma
    type(slow_flow_constants), intent(out) :: constants
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(modal_coefficients) :: modal, shifted
    type(model_t) :: other
    call expand_model(model, modal, status, message)
    if (status /= SD_OK) return
    constants%omega1 = modal%omega1
    constants%omega2 = modal%omega2
    constants%F11 = modal%F11
    constants%c = modal%c
    constants%gamma11_0 = modal%gamma11
    constants%gamma22_0 = modal%gamma22
    if (.not. with_gamma) return
    other = model
    other%gamma = model%gamma + 1
    call set_coefficients(other)
    call expand_model(other, shifted, status, message)
    if (status /= SD_OK) return
    constants%gamma11_slope = shifted%gamma11 - modal%gamma11
    constants%gamma22_slope = shifted%gamma22 - modal%gamma22
    constants%gamma11_0 = modal%gamma11 - model%gamma*constants%gamma11_slope
    constants%gamma22_0 = modal%gamma22 - model%gamma*constants%gamma22_slope
  end subroutine expand_constants

  pure function chart_parameter_name(code) result(name)
    integer, intent(in) :: code
    character(len=:), allocatable :: name
    select case (code)
    case (CHART_RHO);   name = 'rho'
    case (CHART_A);     name = 'A'
    case (CHART_GAMMA); name = 'gamma'
    case (CHART_KAPPA); name = 'kappa'
    case default;       name = 'unknown'
    end select
  end function chart_parameter_name

  pure integer function field_dimension(self) result(n)
    class(slow_flow_field), intent(in) :: self
    n = merge(4, 2, self%internal_resonance)
  end function field_dimension

  ! ---- the terms --------------------------------------------------------------------------

  !> rho, A, gamma at p; lin = (lin1, lin2), their derivatives in p1, p2 (dlin(:, k)), the
  !> forcing F and dF/dp, and the cubic coefficients.
  pure subroutine slow_flow_terms(self, p, lin, dlin, forcing, dforcing, coef)
    class(slow_flow_field), intent(in) :: self
    real(wp), intent(in) :: p(2)
    complex(wp), intent(out) :: lin(2), dlin(2, 2), coef(n_terms)
    real(wp), intent(out) :: forcing, dforcing(2)
    complex(wp), parameter :: i = (0.0_wp, 1.0_wp)
    type(slow_flow_constants) :: c
    type(model_t) :: at_kappa
    real(wp) :: rho, amplitude, gamma, k1, k2
    integer :: k, status
    character(len=message_len) :: message

    rho = self%rho
    amplitude = self%amplitude
    gamma = self%gamma
    c = self%constants
    do k = 1, 2
      select case (self%parameters(k))
      case (CHART_RHO);   rho = p(k)
      case (CHART_A);     amplitude = p(k)
      case (CHART_GAMMA); gamma = p(k)
      case (CHART_KAPPA)
        ! the modal constants at this kappa (NaN where the expansion fails: Newton stops there)
        at_kappa = self%model
        at_kappa%kappa = p(k)
        call set_coefficients(at_kappa)
        call expand_constants(at_kappa, any(self%parameters == CHART_GAMMA), c, status, message)
        if (status /= SD_OK) c = nan_constants()
      end select
    end do
    lin(1) = -((c%gamma11_0 + c%gamma11_slope*gamma)/2 + i*(rho - c%omega1))
    lin(2) = -((c%gamma22_0 + c%gamma22_slope*gamma)/2 + &
               i*(3*(rho - c%omega1) - (c%omega2 - 3*c%omega1)))
    forcing = rho**2*amplitude*c%F11/(2*c%omega1)
    do k = 1, 2
      select case (self%parameters(k))
      case (CHART_RHO)
        dlin(:, k) = [-i, -3*i]
        dforcing(k) = 2*rho*amplitude*c%F11/(2*c%omega1)
      case (CHART_A)
        dlin(:, k) = 0
        dforcing(k) = rho**2*c%F11/(2*c%omega1)
      case (CHART_GAMMA)
        dlin(:, k) = [cmplx(-c%gamma11_slope/2, 0.0_wp, wp), &
                      cmplx(-c%gamma22_slope/2, 0.0_wp, wp)]
        dforcing(k) = 0
      case default   ! kappa: by differences of the whole field (field_evaluate)
        dlin(:, k) = 0
        dforcing(k) = 0
      end select
    end do
    k1 = 1/(8*c%omega1)
    k2 = 1/(8*c%omega2)
    coef = [i*k1*c%c(1, 1), 2*i*k1*c%c(1, 2), -i*k1*c%c(1, 3), &
            i*k2*c%c(2, 1), 2*i*k2*c%c(2, 2), -i*k2*c%c(2, 3)]
  end subroutine slow_flow_terms

  pure function nan_constants() result(c)
    type(slow_flow_constants) :: c
    real(wp) :: nan
    nan = ieee_value(1.0_wp, ieee_quiet_nan)
    c = slow_flow_constants(nan, nan, nan, nan, nan, nan, nan, nan)
  end function nan_constants

  !> f(x, p) alone, and J(x, p) u alone (for the differences in kappa).
  pure function field_value(self, x, p) result(f)
    class(slow_flow_field), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2)
    real(wp) :: f(size(x))
    complex(wp) :: lin(2), dlin(2, 2), coef(n_terms), b(2)
    real(wp) :: forcing, dforcing(2)
    call slow_flow_terms(self, p, lin, dlin, forcing, dforcing, coef)
    b = complex_of(self, x)
    f = real_of(self, lin*b + [cmplx(forcing, 0.0_wp, wp), (0.0_wp, 0.0_wp)] + &
                      trilinear(self, coef, b, b, b))
  end function field_value

  pure function jacobian_times(self, x, p, u) result(ju)
    class(slow_flow_field), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2), u(:)
    real(wp) :: ju(size(x))
    complex(wp) :: lin(2), dlin(2, 2), coef(n_terms), b(2), uu(2)
    real(wp) :: forcing, dforcing(2)
    call slow_flow_terms(self, p, lin, dlin, forcing, dforcing, coef)
    b = complex_of(self, x)
    uu = complex_of(self, u)
    ju = real_of(self, lin*uu + trilinear(self, coef, uu, b, b) + trilinear(self, coef, b, uu, b) + &
                       trilinear(self, coef, b, b, uu))
  end function jacobian_times

  !> The central-difference step in kappa at p(k).
  pure real(wp) function kappa_difference(p) result(h)
    real(wp), intent(in) :: p
    h = kappa_step*max(1.0_wp, abs(p))
  end function kappa_difference

  !> (B1, B2) of a real vector (B2 = 0 without internal resonance).
  pure function complex_of(self, u) result(b)
    class(slow_flow_field), intent(in) :: self
    real(wp), intent(in) :: u(:)
    complex(wp) :: b(2)
    b(1) = cmplx(u(1), u(2), wp)
    b(2) = 0
    if (self%internal_resonance) b(2) = cmplx(u(3), u(4), wp)
  end function complex_of

  !> The real vector of (f1, f2) (f2 dropped without internal resonance).
  pure function real_of(self, f) result(r)
    class(slow_flow_field), intent(in) :: self
    complex(wp), intent(in) :: f(2)
    real(wp) :: r(merge(4, 2, self%internal_resonance))
    r(1:2) = [real(f(1)), aimag(f(1))]
    if (self%internal_resonance) r(3:4) = [real(f(2)), aimag(f(2))]
  end function real_of

  !> The cubic terms' multilinear form T(a1, a2, a3) (rows B1', B2'); only the c11 term
  !> without internal resonance (the others vanish with B2 = 0 there).
  pure function trilinear(self, coef, a1, a2, a3) result(t)
    class(slow_flow_field), intent(in) :: self
    complex(wp), intent(in) :: coef(n_terms), a1(2), a2(2), a3(2)
    complex(wp) :: t(2)
    integer :: k, last
    t = 0
    last = merge(n_terms, 1, self%internal_resonance)
    do k = 1, last
      t(term_row(k)) = t(term_row(k)) + coef(k)*slot(a1, term_var(1, k), term_conj(1, k))* &
                       slot(a2, term_var(2, k), term_conj(2, k))* &
                       slot(a3, term_var(3, k), term_conj(3, k))
    end do
  end function trilinear

  pure complex(wp) function slot(a, var, conjugated)
    complex(wp), intent(in) :: a(2)
    integer, intent(in) :: var
    logical, intent(in) :: conjugated
    slot = a(var)
    if (conjugated) slot = conjg(a(var))
  end function slot

  !> D^2 of the cubic terms at b in the directions u, v: T summed over the six placements.
  pure function second_form(self, coef, b, u, v) result(t)
    class(slow_flow_field), intent(in) :: self
    complex(wp), intent(in) :: coef(n_terms), b(2), u(2), v(2)
    complex(wp) :: t(2)
    t = trilinear(self, coef, u, v, b) + trilinear(self, coef, v, u, b) + &
        trilinear(self, coef, u, b, v) + trilinear(self, coef, v, b, u) + &
        trilinear(self, coef, b, u, v) + trilinear(self, coef, b, v, u)
  end function second_form

  ! ---- the field ----------------------------------------------------------------------------

  subroutine field_evaluate(self, x, p, f, fx, fp)
    class(slow_flow_field), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2)
    real(wp), intent(out) :: f(:), fx(:, :), fp(:, :)
    complex(wp) :: lin(2), dlin(2, 2), coef(n_terms), b(2), e(2), col(2)
    real(wp) :: forcing, dforcing(2), unit(size(x)), h(2)
    integer :: j, k

    call slow_flow_terms(self, p, lin, dlin, forcing, dforcing, coef)
    b = complex_of(self, x)
    f = real_of(self, lin*b + [cmplx(forcing, 0.0_wp, wp), (0.0_wp, 0.0_wp)] + &
                      trilinear(self, coef, b, b, b))
    do j = 1, size(x)
      unit = 0
      unit(j) = 1
      e = complex_of(self, unit)
      col = lin*e + trilinear(self, coef, e, b, b) + trilinear(self, coef, b, e, b) + &
            trilinear(self, coef, b, b, e)
      fx(:, j) = real_of(self, col)
    end do
    do k = 1, 2
      if (self%parameters(k) == CHART_KAPPA) then
        h = 0
        h(k) = kappa_difference(p(k))
        fp(:, k) = (field_value(self, x, p + h) - field_value(self, x, p - h))/(2*h(k))
      else
        fp(:, k) = real_of(self, dlin(:, k)*b + [cmplx(dforcing(k), 0.0_wp, wp), &
                                                (0.0_wp, 0.0_wp)])
      end if
    end do
  end subroutine field_evaluate

  !> hx = d(J u)/dx (column j: D^2 f[u, e_j]), hp = d(J u)/dp = dlin u.
  subroutine field_jacobian_derivative(self, x, p, u, hx, hp)
    class(slow_flow_field), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2), u(:)
    real(wp), intent(out) :: hx(:, :), hp(:, :)
    complex(wp) :: lin(2), dlin(2, 2), coef(n_terms), b(2), uu(2), e(2)
    real(wp) :: forcing, dforcing(2), unit(size(x)), h(2)
    integer :: j, k

    call slow_flow_terms(self, p, lin, dlin, forcing, dforcing, coef)
    b = complex_of(self, x)
    uu = complex_of(self, u)
    do j = 1, size(x)
      unit = 0
      unit(j) = 1
      e = complex_of(self, unit)
      hx(:, j) = real_of(self, second_form(self, coef, b, uu, e))
    end do
    do k = 1, 2
      if (self%parameters(k) == CHART_KAPPA) then
        h = 0
        h(k) = kappa_difference(p(k))
        hp(:, k) = (jacobian_times(self, x, p + h, u) - jacobian_times(self, x, p - h, u))/ &
                   (2*h(k))
      else
        hp(:, k) = real_of(self, dlin(:, k)*uu)
      end if
    end do
  end subroutine field_jacobian_derivative

  subroutine field_second_derivative(self, x, p, u, v, b)
    class(slow_flow_field), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2), u(:), v(:)
    real(wp), intent(out) :: b(:)
    complex(wp) :: lin(2), dlin(2, 2), coef(n_terms)
    real(wp) :: forcing, dforcing(2)
    call slow_flow_terms(self, p, lin, dlin, forcing, dforcing, coef)
    b = real_of(self, second_form(self, coef, complex_of(self, x), complex_of(self, u), &
                                  complex_of(self, v)))
  end subroutine field_second_derivative

  !> D^3 f[u, v, w]: T summed over the six permutations of (U, V, W).
  subroutine field_third_derivative(self, x, p, u, v, w, c)
    class(slow_flow_field), intent(in) :: self
    real(wp), intent(in) :: x(:), p(2), u(:), v(:), w(:)
    real(wp), intent(out) :: c(:)
    complex(wp) :: lin(2), dlin(2, 2), coef(n_terms), uu(2), vv(2), ww(2)
    real(wp) :: forcing, dforcing(2)
    call slow_flow_terms(self, p, lin, dlin, forcing, dforcing, coef)
    uu = complex_of(self, u)
    vv = complex_of(self, v)
    ww = complex_of(self, w)
    c = real_of(self, trilinear(self, coef, uu, vv, ww) + trilinear(self, coef, uu, ww, vv) + &
                      trilinear(self, coef, vv, uu, ww) + trilinear(self, coef, vv, ww, uu) + &
                      trilinear(self, coef, ww, uu, vv) + trilinear(self, coef, ww, vv, uu) + &
                      0*x(1))
  end subroutine field_third_derivative
end module sloshdyn_slowflow_chart
