!> The slow flow of the multiple-scales analysis (sec 3.3) in a regular Cartesian form.
!>
!> With u1 ~ Re(B1 exp(i rho tau)) and u2 ~ Re(B2 exp(3 i rho tau)) (eq 42, 45 with
!> B1 = a1 exp(-i phi2), B2 = a2 exp(i (phi1 - 3 phi2))), the solvability conditions (eq 52) read
!>   B1' = -(gamma11/2 + i sigma2) B1 + i/(8 omega1) (c11 |B1|^2 B1 + 2 c12 |B2|^2 B1
!>         - c13 conj(B1)^2 B2) + rho^2 A F11/(2 omega1)
!>   B2' = -(gamma22/2 + i (3 sigma2 - sigma1)) B2 + i/(8 omega2) (c21 |B2|^2 B2
!>         + 2 c22 |B1|^2 B2 - c23 B1^3)
!> with sigma2 = rho - omega1, sigma1 = omega2 - 3 omega1 (eq 51), in the original time tau.
!> This is eq (53) without its divisions by a1 and a2, so branches through small a2 are regular.
!> Without internal resonance (sec 3.3.1) the c13, c23 couplings drop and B2 decays: the steady
!> states are those of the B1 equation alone (eq 46, 49). The unknowns are
!> x = (Re B1, Im B1[, Re B2, Im B2]).
module sloshdyn_slowflow
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, check_real
  use sloshdyn_model, only: model_t
  use sloshdyn_modal, only: modal_coefficients, expand_model
  use sloshdyn_continuation, only: separable_system
  use sloshdyn_lapack, only: eigenvalues
  use sloshdyn_sort, only: sort_ascending
  use sloshdyn_excitation, only: PARAMETER_RHO, PARAMETER_A
  implicit none
  private
  public :: slow_flow, make_slow_flow, characteristic_coefficients, nonresonant_cubic, &
            nonresonant_amplitudes

  !> The steady-state equations F(x; lambda) = 0 of the slow flow, lambda = rho or A.
  type, extends(separable_system) :: slow_flow
    type(model_t) :: model                  !< rho and A here are replaced by lambda
    type(modal_coefficients) :: modal
    logical :: internal_resonance = .true.  !< 3:1 (4 unknowns) or none (2 unknowns)
    integer :: parameter = PARAMETER_RHO    !< which of rho, A is lambda
  contains
    procedure :: residual => slow_flow_residual
    procedure :: jacobian => slow_flow_jacobian
    procedure :: dimension => slow_flow_dimension
  end type slow_flow

contains

  pure subroutine make_slow_flow(model, internal_resonance, parameter, flow, status, message)
    type(model_t), intent(in) :: model
    logical, intent(in) :: internal_resonance
    integer, intent(in) :: parameter
    type(slow_flow), intent(out) :: flow
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    flow%model = model
    flow%internal_resonance = internal_resonance
    flow%parameter = parameter
    call expand_model(model, flow%modal, status, message)
    if (status == SD_OK .and. parameter /= PARAMETER_RHO .and. parameter /= PARAMETER_A) then
      status = SD_BAD_INPUT
      message = 'the continuation parameter must be rho (1) or A (2)'
    end if
  end subroutine make_slow_flow

  pure integer function slow_flow_dimension(self) result(n)
    class(slow_flow), intent(in) :: self
    n = merge(4, 2, self%internal_resonance)
  end function slow_flow_dimension

  !> rho and A at parameter value lambda.
  pure subroutine rho_and_amplitude(self, lambda, rho, amplitude)
    class(slow_flow), intent(in) :: self
    real(wp), intent(in) :: lambda
    real(wp), intent(out) :: rho, amplitude
    rho = self%model%excitation%rho
    amplitude = self%model%excitation%A
    if (self%parameter == PARAMETER_RHO) then
      rho = lambda
    else
      amplitude = lambda
    end if
  end subroutine rho_and_amplitude

  subroutine slow_flow_residual(self, x, lambda, f)
    class(slow_flow), intent(in) :: self
    real(wp), intent(in) :: x(:), lambda
    real(wp), intent(out) :: f(:)
    complex(wp) :: b1, b2, f1, f2
    real(wp) :: rho, amplitude
    call rho_and_amplitude(self, lambda, rho, amplitude)
    b1 = cmplx(x(1), x(2), wp)
    b2 = 0
    if (self%internal_resonance) b2 = cmplx(x(3), x(4), wp)
    call complex_flow(self, rho, amplitude, b1, b2, f1, f2)
    f(1:2) = [real(f1), aimag(f1)]
    if (self%internal_resonance) f(3:4) = [real(f2), aimag(f2)]
  end subroutine slow_flow_residual

  pure subroutine complex_flow(self, rho, amplitude, b1, b2, f1, f2)
    class(slow_flow), intent(in) :: self
    real(wp), intent(in) :: rho, amplitude
    complex(wp), intent(in) :: b1, b2
    complex(wp), intent(out) :: f1, f2
    complex(wp), parameter :: i = (0.0_wp, 1.0_wp)
    real(wp) :: sigma2, sigma1
    associate (m => self%modal, c => self%modal%c)
      sigma2 = rho - m%omega1
      sigma1 = m%omega2 - 3*m%omega1
      f1 = -(m%gamma11/2 + i*sigma2)*b1 + rho**2*amplitude*m%F11/(2*m%omega1) &
           + i/(8*m%omega1)*(c(1, 1)*abs(b1)**2*b1 + 2*c(1, 2)*abs(b2)**2*b1 &
                             - c(1, 3)*conjg(b1)**2*b2)
      f2 = -(m%gamma22/2 + i*(3*sigma2 - sigma1))*b2 &
           + i/(8*m%omega2)*(c(2, 1)*abs(b2)**2*b2 + 2*c(2, 2)*abs(b1)**2*b2 - c(2, 3)*b1**3)
    end associate
    if (.not. self%internal_resonance) f2 = 0
  end subroutine complex_flow

  !> Analytic Jacobian. With Wirtinger derivatives d/dB and d/dconj(B):
  !> df/dRe B = df/dB + df/dconj(B), df/dIm B = i (df/dB - df/dconj(B)).
  subroutine slow_flow_jacobian(self, x, lambda, fx, flambda)
    class(slow_flow), intent(in) :: self
    real(wp), intent(in) :: x(:), lambda
    real(wp), intent(out) :: fx(:, :), flambda(:)
    complex(wp), parameter :: i = (0.0_wp, 1.0_wp)
    complex(wp) :: b1, b2, d(2, 4), dl(2), col
    real(wp) :: rho, amplitude, k1, k2, sigma2, sigma1
    integer :: n, row, j

    call rho_and_amplitude(self, lambda, rho, amplitude)
    n = merge(4, 2, self%internal_resonance)
    b1 = cmplx(x(1), x(2), wp)
    b2 = 0
    if (self%internal_resonance) b2 = cmplx(x(3), x(4), wp)
    associate (m => self%modal, c => self%modal%c)
      k1 = 1/(8*m%omega1)
      k2 = 1/(8*m%omega2)
      sigma2 = rho - m%omega1
      sigma1 = m%omega2 - 3*m%omega1
      ! d(:, 1:4) = df/dB1, df/dconj(B1), df/dB2, df/dconj(B2)
      d(1, 1) = -(m%gamma11/2 + i*sigma2) + i*k1*(2*c(1, 1)*abs(b1)**2 + 2*c(1, 2)*abs(b2)**2)
      d(1, 2) = i*k1*(c(1, 1)*b1**2 - 2*c(1, 3)*conjg(b1)*b2)
      d(1, 3) = i*k1*(2*c(1, 2)*conjg(b2)*b1 - c(1, 3)*conjg(b1)**2)
      d(1, 4) = i*k1*2*c(1, 2)*b2*b1
      d(2, 1) = i*k2*(2*c(2, 2)*conjg(b1)*b2 - 3*c(2, 3)*b1**2)
      d(2, 2) = i*k2*2*c(2, 2)*b1*b2
      d(2, 3) = -(m%gamma22/2 + i*(3*sigma2 - sigma1)) &
                + i*k2*(2*c(2, 1)*abs(b2)**2 + 2*c(2, 2)*abs(b1)**2)
      d(2, 4) = i*k2*c(2, 1)*b2**2
      if (self%parameter == PARAMETER_RHO) then
        dl = [-i*b1 + rho*amplitude*m%F11/m%omega1, -3*i*b2]
      else
        dl = [cmplx(rho**2*m%F11/(2*m%omega1), 0.0_wp, wp), (0.0_wp, 0.0_wp)]
      end if
    end associate
    if (.not. self%internal_resonance) d(1, 2) = i*k1*self%modal%c(1, 1)*b1**2
    do row = 1, n/2
      do j = 1, n/2
        col = d(row, 2*j - 1) + d(row, 2*j)
        fx(2*row - 1:2*row, 2*j - 1) = [real(col), aimag(col)]
        col = i*(d(row, 2*j - 1) - d(row, 2*j))
        fx(2*row - 1:2*row, 2*j) = [real(col), aimag(col)]
      end do
      flambda(2*row - 1:2*row) = [real(dl(row)), aimag(dl(row))]
    end do
  end subroutine slow_flow_jacobian

  !> Coefficients C1..Cn of the characteristic polynomial lambda^n + C1 lambda^(n-1) + ... of a
  !> 2x2 or 4x4 matrix (eq 55): C_k = (-1)^k times the sum of the principal minors of order k.
  pure function characteristic_coefficients(a) result(coefficients)
    real(wp), intent(in) :: a(:, :)
    real(wp) :: coefficients(size(a, 1))
    integer :: n, k, mask, count_bits, rows(4), m, bit
    n = size(a, 1)
    coefficients = 0
    do mask = 1, 2**n - 1
      count_bits = 0
      do bit = 0, n - 1
        if (btest(mask, bit)) then
          count_bits = count_bits + 1
          rows(count_bits) = bit + 1
        end if
      end do
      m = count_bits
      k = m
      coefficients(k) = coefficients(k) + (-1)**k*determinant(a(rows(1:m), rows(1:m)))
    end do
  end function characteristic_coefficients

  !> Determinant by cofactor expansion along the first row (order <= 4).
  pure recursive function determinant(a) result(det)
    real(wp), intent(in) :: a(:, :)
    real(wp) :: det
    integer :: j, k, n, others(size(a, 1) - 1)
    n = size(a, 1)
    if (n == 1) then
      det = a(1, 1)
      return
    end if
    det = 0
    do j = 1, n
      others = [(merge(k, k + 1, k < j), k = 1, n - 1)]
      det = det + (-1)**(j + 1)*a(1, j)*determinant(a(2:n, others))
    end do
  end function determinant

  !> Coefficients of eq (49) as a cubic in z = a1^2 without internal resonance:
  !> k^2 z^3 - 2 sigma k z^2 + (sigma^2 + (gamma11/2)^2) z - F^2 = 0, k = c11/(8 omega1),
  !> sigma = rho - omega1, F = rho^2 A F11/(2 omega1) (eq 49-50 with the square of docs/errata.md).
  pure function nonresonant_cubic(modal, rho, amplitude) result(cubic)
    type(modal_coefficients), intent(in) :: modal
    real(wp), intent(in) :: rho, amplitude
    real(wp) :: cubic(4)
    real(wp) :: k, sigma, forcing
    k = modal%c(1, 1)/(8*modal%omega1)
    sigma = rho - modal%omega1
    forcing = rho**2*amplitude*modal%F11/(2*modal%omega1)
    cubic = [k**2, -2*sigma*k, sigma**2 + (modal%gamma11/2)**2, -forcing**2]
  end function nonresonant_cubic

  !> Every real solution a1 = |u1| > 0 of eq (49) (no internal resonance), ascending: the
  !> positive real roots z = a1^2 of the cubic, from the eigenvalues of its companion matrix.
  subroutine nonresonant_amplitudes(modal, rho, amplitude, a1, n_roots, status, message)
    type(modal_coefficients), intent(in) :: modal
    real(wp), intent(in) :: rho, amplitude
    real(wp), intent(out) :: a1(3)
    integer, intent(out) :: n_roots, status
    character(len=message_len), intent(out) :: message
    real(wp) :: cubic(4), companion(3, 3), wr(3), wi(3), z
    integer :: i

    a1 = 0
    n_roots = 0
    status = SD_OK
    message = ''
    call check_real('rho', rho, 0.0_wp, huge(1.0_wp), .true., .true., &
                    'rho (excitation frequency) must be > 0', status, message)
    if (status /= SD_OK) return
    cubic = nonresonant_cubic(modal, rho, amplitude)
    if (cubic(1) == 0) then
      ! c11 = 0: the backbone is straight and eq (49) is linear in z
      if (cubic(4) /= 0) then
        n_roots = 1
        a1(1) = sqrt(-cubic(4)/cubic(3))
      end if
      return
    end if
    companion = 0
    companion(1, :) = -cubic(2:4)/cubic(1)
    companion(2, 1) = 1
    companion(3, 2) = 1
    call eigenvalues(companion, wr, wi, status, message)
    if (status /= SD_OK) return
    do i = 1, 3
      z = wr(i)
      if (abs(wi(i)) > 1.0e-9_wp*max(abs(wr(i)), tiny(1.0_wp)) .or. z <= 0) cycle
      n_roots = n_roots + 1
      a1(n_roots) = sqrt(z)
    end do
    call sort_ascending(a1(1:n_roots))
  end subroutine nonresonant_amplitudes
end module sloshdyn_slowflow
