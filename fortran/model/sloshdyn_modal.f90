!> The cubic expansion of the equations of motion about the trivial equilibrium (eq 32-33), its
!> modal form (eq 34-36), and the coefficients of the multiple-scales solvability conditions
!> (eq 44, 52; c11..c23 of Appendix A).
!>
!> The expansion is derived here from eq (15)/(29), Q'' = M^-1 F with M^-1 expanded, by exact
!> arithmetic on truncated polynomials, instead of typing in Appendix A, which has misprints
!> (docs/errata.md). Terms beyond cubic order are dropped, as in the paper: the impact force
!> beta x1^(2n-1) enters only for n = 2 and the dissipation delta x1^(2p) x1' only for p = 1.
module sloshdyn_modal
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT
  use sloshdyn_text, only: num2str
  use sloshdyn_model, only: model_t
  use sloshdyn_linear, only: stiffness_matrix, natural_frequencies, modal_matrix
  use sloshdyn_polynomial, only: poly, constant, variable, linear_form, add, scaled, times, &
                                 reciprocal, sin_series, cos_series, substitute
  implicit none
  private
  public :: modal_coefficients, expand_model

  type :: modal_coefficients
    real(wp) :: omega1 = 0, omega2 = 0     !< eq (28)
    !> eq (32): x'' + K x = g(x1, x2, x1', x2') + rho^2 A sin(rho tau) g_forcing(x1, x2)
    type(poly) :: g(2), g_forcing(2)
    !> eq (35): u'' + omega^2 u = h(u1, u2, u1', u2') + rho^2 A sin(rho tau) h_forcing(u1, u2)
    type(poly) :: h(2), h_forcing(2)
    real(wp) :: gamma11 = 0, gamma22 = 0   !< modal damping: h1 = -gamma11 u1' ..., h2 = -gamma22 u2' ...
    real(wp) :: F11 = 0                    !< modal forcing of eq (36): h1 = ... - F11 rho^2 A sin
    real(wp) :: c(2, 3) = 0                !< c11, c12, c13; c21, c22, c23 (Appendix A, eq 52)
  end type modal_coefficients

contains

  !> All expansion and modal coefficients; needs kappa > s1 (modes exist), n >= 2 and p >= 1
  !> (no linear impact or dissipation force, which would change K).
  pure subroutine expand_model(model, mc, status, message)
    type(model_t), intent(in) :: model
    type(modal_coefficients), intent(out) :: mc
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(poly) :: x1, x2, v1, v2, sin12, cos12, force(2), excitation(2), inverse_det, q(2), &
                  qf(2), forms(4), g_modal(2), gf_modal(2)
    real(wp) :: k(2, 2), p(2, 2), p_inv(2, 2)
    integer :: r

    call natural_frequencies(model, mc%omega1, mc%omega2, status, message)
    if (status /= SD_OK) return
    if (model%n < 2) then
      status = SD_BAD_INPUT
      message = 'n = '//num2str(model%n)//' is out of range: the multiple-scales analysis needs '// &
                'n >= 2 (n = 1 makes the impact force linear and changes the stiffness matrix)'
      return
    else if (model%p < 1) then
      status = SD_BAD_INPUT
      message = 'p = '//num2str(model%p)//' is out of range: the multiple-scales analysis needs '// &
                'p >= 1 (p = 0 makes the dissipation linear)'
      return
    end if

    x1 = variable(1); x2 = variable(2); v1 = variable(3); v2 = variable(4)
    associate (a => model%a_coef, b => model%b_coef, t0 => model%theta0)
      sin12 = sin_series(linear_form([t0, t0, 0.0_wp, 0.0_wp]))
      cos12 = cos_series(linear_form([t0, t0, 0.0_wp, 0.0_wp]))
      ! F of eq (14) without the base motion
      force(1) = add(scaled(a(2), times(sin12, times(v2, v2))), &
                     scaled(-a(3), sin_series(scaled(t0, x1))))
      if (model%n == 2) force(1) = add(force(1), scaled(-a(4), times(x1, times(x1, x1))))
      if (model%p == 1) force(1) = add(force(1), scaled(-a(5), times(times(x1, x1), v1)))
      if (model%zeta /= 0) force(1) = add(force(1), scaled(-2*model%zeta, v1))
      force(2) = add(add(scaled(b(2), times(sin12, times(v1, v1))), scaled(-b(3), x2)), &
                     add(scaled(b(4), sin_series(scaled(t0, x2))), scaled(-b(5), v2)))
      ! the factor of rho^2 A sin(rho tau) in F (eq 31)
      excitation(1) = scaled(a(6), cos_series(scaled(t0, x1)))
      excitation(2) = scaled(b(6), cos_series(scaled(t0, x2)))
      ! M^-1 = [[1, -a1 cos12], [-b1 cos12, 1]] / (1 - mu1 cos12^2), eq (13)
      inverse_det = reciprocal(add(constant(1.0_wp), scaled(-model%mu1, times(cos12, cos12))))
      q(1) = times(inverse_det, add(force(1), scaled(-a(1), times(cos12, force(2)))))
      q(2) = times(inverse_det, add(force(2), scaled(-b(1), times(cos12, force(1)))))
      qf(1) = times(inverse_det, add(excitation(1), scaled(-a(1), times(cos12, excitation(2)))))
      qf(2) = times(inverse_det, add(excitation(2), scaled(-b(1), times(cos12, excitation(1)))))
    end associate
    ! eq (32): g = Q'' + K x
    k = stiffness_matrix(model)
    do r = 1, 2
      mc%g(r) = add(q(r), linear_form([k(r, 1), k(r, 2), 0.0_wp, 0.0_wp]))
    end do
    mc%g_forcing = qf

    ! eq (34)-(36): x = P u, x' = P u', h = P^-1 g
    call modal_matrix(model, p, p_inv, status, message)
    if (status /= SD_OK) return
    forms(1) = linear_form([p(1, 1), p(1, 2), 0.0_wp, 0.0_wp])
    forms(2) = linear_form([p(2, 1), p(2, 2), 0.0_wp, 0.0_wp])
    forms(3) = linear_form([0.0_wp, 0.0_wp, p(1, 1), p(1, 2)])
    forms(4) = linear_form([0.0_wp, 0.0_wp, p(2, 1), p(2, 2)])
    do r = 1, 2
      g_modal(r) = substitute(mc%g(r), forms)
      gf_modal(r) = substitute(mc%g_forcing(r), forms)
    end do
    do r = 1, 2
      mc%h(r) = add(scaled(p_inv(r, 1), g_modal(1)), scaled(p_inv(r, 2), g_modal(2)))
      mc%h_forcing(r) = add(scaled(p_inv(r, 1), gf_modal(1)), scaled(p_inv(r, 2), gf_modal(2)))
    end do

    ! coefficients of the solvability conditions, named as in eq (36): h1 = -gamma11 u1'
    ! - alpha11 u1^3 - gamma17 u1 u1'^2 - ... ; exponents are of (u1, u2, u1', u2')
    associate (h1 => mc%h(1)%c, h2 => mc%h(2)%c, w1 => mc%omega1, w2 => mc%omega2)
      mc%gamma11 = -h1(0, 0, 1, 0)
      mc%gamma22 = -h2(0, 0, 0, 1)
      mc%F11 = -mc%h_forcing(1)%c(0, 0, 0, 0)
      ! c11 = gamma17 w1^2 + 3 alpha11
      mc%c(1, 1) = -h1(1, 0, 2, 0)*w1**2 - 3*h1(3, 0, 0, 0)
      ! c12 = alpha14 + gamma19 w2^2
      mc%c(1, 2) = -h1(1, 2, 0, 0) - h1(1, 0, 0, 2)*w2**2
      ! c13 = -gamma18 w1 w2 + gamma111 w1^2 - alpha13
      mc%c(1, 3) = h1(1, 0, 1, 1)*w1*w2 - h1(0, 1, 2, 0)*w1**2 + h1(2, 1, 0, 0)
      ! c21 = 3 alpha22 + gamma213 w2^2
      mc%c(2, 1) = -3*h2(0, 3, 0, 0) - h2(0, 1, 0, 2)*w2**2
      ! c22 = gamma211 w1^2 + alpha23
      mc%c(2, 2) = -h2(0, 1, 2, 0)*w1**2 - h2(2, 1, 0, 0)
      ! c23 = gamma27 w1^2 - alpha21 (docs/errata.md: eq 53 uses c23 without defining it)
      mc%c(2, 3) = -h2(1, 0, 2, 0)*w1**2 + h2(3, 0, 0, 0)
    end associate
  end subroutine expand_model
end module sloshdyn_modal
