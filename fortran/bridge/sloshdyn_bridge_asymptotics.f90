!> The f2py bridge of asymptotics.py: the modal expansion, the slow flows and their frequency
!> response.
!> The bridge's contract (c_double/c_int arrays in named layouts, status and message,
!> threads and the GIL) is written once, in sloshdyn_bridge_model.f90.
module sloshdyn_bridge_asymptotics
  use, intrinsic :: iso_c_binding, only: c_double, c_int
  implicit none

contains

  !> Cubic expansion (eq 32-33) and modal form (eq 35-36). Polynomials are given by their
  !> coefficients on the 34 monomials of degree 1..3 whose exponents are exponents(:, k), in the
  !> variables (x1, x2, x1', x2') for g and (u1, u2, u1', u2') for h; the forcing polynomials
  !> (factor of rho^2 A sin(rho tau)) add a constant term: *_forcing(:, 0).
  !> scalars in the 'modal_scalars' layout (omega1, omega2, gamma11, gamma22, F11); c = c11..c23.
  subroutine modal_expansion(rpar, ipar, scalars, c, exponents, g, g_forcing, h, h_forcing, &
                             status, message)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_modal, only: modal_coefficients, expand_model
    use sloshdyn_polynomial, only: monomial_exponents, poly
    use sloshdyn_layouts, only: MODAL_SCALARS_SIZE
    real(c_double), intent(in) :: rpar(n_real_params)
    integer(c_int), intent(in) :: ipar(n_int_params)
    real(c_double), intent(out) :: scalars(MODAL_SCALARS_SIZE), c(2, 3), g(2, 34), &
                                   g_forcing(2, 0:34), h(2, 34), h_forcing(2, 0:34)
    integer(c_int), intent(out) :: exponents(4, 34), status
    character(len=512), intent(out) :: message
    type(model_t) :: model
    type(modal_coefficients) :: mc
    integer :: info, r, k, e(4, 34)
    scalars = 0; c = 0; g = 0; g_forcing = 0; h = 0; h_forcing = 0
    e = monomial_exponents()
    exponents = e
    call model_from_arrays(rpar, int(ipar), model, info, message)
    if (info == 0) call expand_model(model, mc, info, message)
    status = info
    if (info /= 0) return
    scalars = [mc%omega1, mc%omega2, mc%gamma11, mc%gamma22, mc%F11]
    c = mc%c
    do r = 1, 2
      g_forcing(r, 0) = mc%g_forcing(r)%c(0, 0, 0, 0)
      h_forcing(r, 0) = mc%h_forcing(r)%c(0, 0, 0, 0)
      do k = 1, 34
        g(r, k) = coefficient(mc%g(r), e(:, k))
        h(r, k) = coefficient(mc%h(r), e(:, k))
        g_forcing(r, k) = coefficient(mc%g_forcing(r), e(:, k))
        h_forcing(r, k) = coefficient(mc%h_forcing(r), e(:, k))
      end do
    end do
  contains
    pure real(c_double) function coefficient(p, ex)
      type(poly), intent(in) :: p
      integer, intent(in) :: ex(4)
      coefficient = p%c(ex(1), ex(2), ex(3), ex(4))
    end function coefficient
  end subroutine modal_expansion

  !> Every real solution |u1| of eq (49) at each rho (A from rpar): amplitudes(1:counts(i), i).
  subroutine nonresonant_amplitudes(rpar, ipar, n, rho, amplitudes, counts, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_modal, only: modal_coefficients, expand_model
    use sloshdyn_slowflow, only: core => nonresonant_amplitudes
    use sloshdyn_text, only: num2str
    real(c_double), intent(in) :: rpar(n_real_params), rho(n)
    integer(c_int), intent(in) :: ipar(n_int_params), n
    real(c_double), intent(out) :: amplitudes(3, n)
    integer(c_int), intent(out) :: counts(n), status
    character(len=512), intent(out) :: message
    type(model_t) :: model
    type(modal_coefficients) :: mc
    integer :: info, i, found
    amplitudes = 0; counts = 0
    call model_from_arrays(rpar, int(ipar), model, info, message)
    if (info == 0) call expand_model(model, mc, info, message)
    do i = 1, n
      if (info /= 0) exit
      call core(mc, rho(i), model%excitation%A, amplitudes(:, i), found, info, message)
      if (info /= 0) message = 'rho('//num2str(i)//'): '//trim(message)
      counts(i) = found
    end do
    status = info
  end subroutine nonresonant_amplitudes

  !> Slow-flow frequency response (sloshdyn_response): branches in lambda = rho (which = 1) or
  !> A (which = 2) over [lambda_min, lambda_max], 3:1 internal resonance or none. table in the
  !> 'response' layout (room for max_points points), special in the 'special' layout;
  !> complete = 0 if a branch could not be finished (status says where).
  subroutine frequency_response(rpar, ipar, resonance, which, lambda_min, lambda_max, settings, &
                                max_points, max_special, table, n_points, special, n_special, &
                                complete, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_tables, only: POINT_ROWS, SPECIAL_ROWS
    use sloshdyn_layouts, only: RESPONSE_SIZE, to_response
    use sloshdyn_response, only: core => frequency_response
    real(c_double), intent(in) :: rpar(n_real_params), lambda_min, lambda_max, &
                                  settings(RESPONSE_SIZE)
    integer(c_int), intent(in) :: ipar(n_int_params), resonance, which, max_points, max_special
    real(c_double), intent(out) :: table(POINT_ROWS, max_points), &
                                   special(SPECIAL_ROWS, max_special)
    integer(c_int), intent(out) :: n_points, n_special, complete, status
    character(len=512), intent(out) :: message
    type(model_t) :: model
    integer :: info, points, specials
    logical :: done
    table = 0; special = 0; points = 0; specials = 0; done = .false.
    call model_from_arrays(rpar, int(ipar), model, info, message)
    if (info == 0) call core(model, resonance == 1, int(which), lambda_min, lambda_max, &
                             to_response(settings), table, points, special, specials, done, &
                             info, message)
    n_points = points
    n_special = specials
    complete = merge(1, 0, done)
    status = info
  end subroutine frequency_response

  !> The limit cycle of the 3:1 slow flow at the model's rho and A (sloshdyn_slowflow_cycle):
  !> x_cycle = (Re B1, Im B1, Re B2, Im B2) on it, its period [tau], multipliers(2, 4) =
  !> (Re, Im) and the Newton shots; times settle_time, max_period in tau.
  subroutine slow_flow_cycle(rpar, ipar, settle_time, max_period, n_samples, integration, &
                             x_cycle, period, multipliers, iterations, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_layouts, only: INTEGRATION_SIZE, to_ode_options, to_method
    use sloshdyn_slowflow_cycle, only: core => slow_flow_cycle
    real(c_double), intent(in) :: rpar(n_real_params), settle_time, max_period, &
                                  integration(INTEGRATION_SIZE)
    integer(c_int), intent(in) :: ipar(n_int_params), n_samples
    real(c_double), intent(out) :: x_cycle(4), period, multipliers(2, 4)
    integer(c_int), intent(out) :: iterations, status
    character(len=512), intent(out) :: message
    type(model_t) :: model
    integer :: code, shots
    real(c_double) :: re(4), im(4)
    x_cycle = 0; period = 0; multipliers = 0; shots = 0
    call model_from_arrays(rpar, int(ipar), model, code, message)
    if (code == 0) call core(model, settle_time, max_period, int(n_samples), &
                             to_ode_options(integration), to_method(integration), x_cycle, &
                             period, re, im, shots, code, message)
    if (code == 0) multipliers = transpose(reshape([re, im], [4, 2]))
    iterations = shots
    status = code
  end subroutine slow_flow_cycle
end module sloshdyn_bridge_asymptotics
