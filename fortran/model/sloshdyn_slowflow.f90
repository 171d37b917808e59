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
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, check_real
  use sloshdyn_model, only: model_t
  use sloshdyn_modal, only: modal_coefficients, expand_model
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use sloshdyn_continuation, only: separable_system, newton_options, newton_solve
  use sloshdyn_lapack, only: eigenvalues
  use sloshdyn_sort, only: sort_ascending
  use sloshdyn_excitation, only: PARAMETER_RHO, PARAMETER_A
  implicit none
  private
  public :: slow_flow, make_slow_flow, characteristic_coefficients, nonresonant_cubic, &
            nonresonant_amplitudes, steady_states

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

  !> Every steady state x of the slow flow at lambda with max|x| <= x_max, from the closed
  !> form of its amplitudes (available = .false. where it does not apply: no forcing or no
  !> damping, c21 = 0 with internal resonance, or amplitude bounds more than 62 decades apart).
  !> With r = |B1|^2, s = |B2|^2:
  !>   B2' = 0:  D2 B2 = i k2 c23 B1^3,  D2 = -gamma22/2 + i q2,  q2 = -(3 sigma2 - sigma1)
  !>             + k2 (c21 s + 2 c22 r),  k2 = 1/(8 omega2);
  !>   B1' = 0:  E B1 = -F D2,  E = D1 D2 + k1 k2 c13 c23 r^2,  D1 = -gamma11/2 + i q1,
  !>             q1 = -sigma2 + k1 (c11 r + 2 c12 s),  k1 = 1/(8 omega1),
  !>             F = rho^2 A F11/(2 omega1)
  !> (the slow flow of the header with conj(B1)^2 B2 = i k2 c23 r^2 B1/D2), so the amplitudes
  !> solve P(r, s) = s |D2|^2 - k2^2 c23^2 r^3 = 0 and Q(r, s) = r |E|^2 - F^2 |D2|^2 = 0
  !> (without internal resonance s = 0 and Q = r |D1|^2 - F^2, eq 49). P is a cubic in s for
  !> each r and a cubic in r for each s, so the curve P = 0 is followed twice over logarithmic
  !> grids between bounds that every steady state respects: in r (its points are the real roots
  !> s) and in s (the real roots r), so that a piece where s changes fast with r is resolved in
  !> s, and one where r changes fast (the curve turns back in s) in r. Q is watched along it:
  !> each sign change and each local minimum of |Q| (a close pair of zeros) on a branch gives
  !> a candidate (r, s), B1 = -F D2/E and B2 = i k2 c23 B1^3/D2, which Newton refines on the slow flow itself, so a candidate that is no steady state is
  !> dropped and every state returned solves F = 0 to the Newton tolerances.
  !> states(:, 1:n_states), distinct.
  subroutine steady_states(self, lambda, x_max, newton, states, n_states, available)
    class(slow_flow), intent(in) :: self
    real(wp), intent(in) :: lambda, x_max
    type(newton_options), intent(in) :: newton
    real(wp), allocatable, intent(out) :: states(:, :)
    integer, intent(out) :: n_states
    logical, intent(out) :: available
    integer, parameter :: per_decade = 64, max_grid = 4000
    real(wp) :: rho, amplitude, alpha1, alpha2, forcing, r_lo, r_hi, e_max, ratio
    real(wp), allocatable :: grid(:), other(:, :), g(:, :)
    integer, allocatable :: m_roots(:)
    integer :: n, n_grid, k, j, along_s
    logical :: coupled

    n = self%dimension()
    n_states = 0
    allocate (states(n, 0))
    call rho_and_amplitude(self, lambda, rho, amplitude)
    coupled = self%internal_resonance
    associate (m => self%modal, c => self%modal%c)
      alpha1 = m%gamma11/2
      alpha2 = m%gamma22/2
      forcing = rho**2*amplitude*m%F11/(2*m%omega1)
      available = forcing /= 0 .and. alpha1 > 0 .and. ieee_is_finite(forcing)
      if (coupled) available = available .and. c(2, 1) /= 0 .and. alpha2 > 0
      if (.not. available) return
      ! r, s <= 2 x_max^2; r = F^2 |D2|^2/|E|^2 >= F^2 alpha2^2/max|E|^2 (F^2/max|D1|^2)
      r_hi = 2*x_max**2
      e_max = alpha1 + abs(rho - m%omega1) + (abs(c(1, 1)) + 2*abs(c(1, 2)))*r_hi/(8*m%omega1)
      if (coupled) e_max = e_max*(alpha2 + abs(3*(rho - m%omega1) - (m%omega2 - 3*m%omega1)) + &
                                  (abs(c(2, 1)) + 2*abs(c(2, 2)))*r_hi/(8*m%omega2)) + &
                           abs(c(1, 3)*c(2, 3))*r_hi**2/(64*m%omega1*m%omega2)
      r_lo = (forcing*merge(alpha2, 1.0_wp, coupled)/e_max)**2/2
    end associate
    available = r_lo > 0 .and. r_lo < r_hi .and. ieee_is_finite(e_max)
    if (.not. available) return
    ! a coarser grid could miss states: beyond max_grid points the closed form is not used
    available = per_decade*log10(r_hi/r_lo) < max_grid - 1
    if (.not. available) return
    n_grid = max(2, ceiling(per_decade*log10(r_hi/r_lo)) + 1)
    ratio = (r_hi/r_lo)**(1.0_wp/(n_grid - 1))
    grid = [(r_lo*ratio**(k - 1), k = 1, n_grid)]
    deallocate (states)
    allocate (other(3, n_grid), g(3, n_grid), m_roots(n_grid), states(n, 8*n_grid))
    do along_s = 0, merge(1, 0, coupled)
      do k = 1, n_grid
        call curve_points(grid(k), other(:, k), g(:, k), m_roots(k))
      end do
      available = all(ieee_is_finite(g))
      if (.not. available) return
      do k = 1, n_grid - 1
        if (m_roots(k) /= m_roots(k + 1)) cycle   ! a turn: resolved by the other scan
        do j = 1, m_roots(k)
          if (g(j, k) == 0 .or. (g(j, k) > 0 .neqv. g(j, k + 1) > 0)) then
            call zero_on_branch(grid(k), grid(k + 1), j, g(j, k) > 0)
          else if (k > 1) then
            if (m_roots(k - 1) == m_roots(k) .and. abs(g(j, k)) < abs(g(j, k - 1)) .and. &
                abs(g(j, k)) < abs(g(j, k + 1))) call close_pair(grid(k - 1), grid(k + 1), j, &
                                                                g(j, k) > 0)
          end if
        end do
      end do
    end do

  contains

    !> The points of P = 0 at t (r, or s when along_s = 1): the real roots of the other
    !> amplitude, ascending, and Q there (without internal resonance: s = 0, m = 1).
    subroutine curve_points(t, roots, q_values, m)
      real(wp), intent(in) :: t
      real(wp), intent(out) :: roots(3), q_values(3)
      integer, intent(out) :: m
      real(wp) :: p(0:2), q(0:4)
      integer :: j
      roots = 0
      q_values = 0
      m = 1
      if (along_s == 0) then
        call amplitude_polynomials(t, p, q)
        if (coupled) call cubic_roots(p, roots, m)
        do j = 1, m
          q_values(j) = horner(q, roots(j))
        end do
      else
        call cubic_roots(radius_cubic(t), roots, m)
        do j = 1, m
          call amplitude_polynomials(roots(j), p, q)
          q_values(j) = horner(q, t)
        end do
      end if
    end subroutine curve_points

    !> P(r, s)/(-k2^2 c23^2) = r^3 + a2 r^2 + a1 r + a0 at s: with q2 = u0 + k2 (c21 s + 2 c22 r),
    !> s (alpha2^2 + q2^2) = k2^2 c23^2 r^3.
    function radius_cubic(s) result(a)
      real(wp), intent(in) :: s
      real(wp) :: a(0:2), k, slope, q0
      associate (m => self%modal, c => self%modal%c)
        k = (c(2, 3)/(8*m%omega2))**2
        slope = 2*c(2, 2)/(8*m%omega2)
        q0 = -(3*(rho - m%omega1) - (m%omega2 - 3*m%omega1)) + c(2, 1)*s/(8*m%omega2)
      end associate
      a = -s/k*[alpha2**2 + q0**2, 2*slope*q0, slope**2]
    end function radius_cubic

    !> The zero of Q along branch j of the curve between t_a and t_b (Q positive at t_a if
    !> positive_a), by bisection while the branch exists; then refined.
    subroutine zero_on_branch(t_a, t_b, j, positive_a)
      real(wp), intent(in) :: t_a, t_b
      integer, intent(in) :: j
      logical, intent(in) :: positive_a
      real(wp) :: low, high, t, roots(3), q_values(3), t_best, root_best
      integer :: step, m
      low = t_a
      high = t_b
      t_best = t_a
      call curve_points(t_a, roots, q_values, m)
      root_best = roots(j)
      do step = 1, 60
        t = low + (high - low)/2
        if (t == low .or. t == high) exit
        call curve_points(t, roots, q_values, m)
        if (m < j) exit
        t_best = t
        root_best = roots(j)
        if (q_values(j) > 0 .eqv. positive_a) then
          low = t
        else
          high = t
        end if
      end do
      call refine_at(t_best, root_best)
    end subroutine zero_on_branch

    !> Between t_a and t_b, |Q| on branch j has a local minimum at a grid point (Q positive
    !> there if positive): the minimum of |Q| by golden-section search; if Q changes sign
    !> there, the two zeros on either side, else a state is sought from the minimum (a zero
    !> pair about to form or just merged).
    subroutine close_pair(t_a, t_b, j, positive)
      real(wp), intent(in) :: t_a, t_b
      integer, intent(in) :: j
      logical, intent(in) :: positive
      real(wp), parameter :: golden = 0.6180339887498949_wp
      real(wp) :: low, high, t1, t2, f1, f2, roots(3), q_values(3)
      integer :: step, m
      low = t_a
      high = t_b
      t1 = high - golden*(high - low)
      t2 = low + golden*(high - low)
      f1 = signed_q(t1, j, positive)
      f2 = signed_q(t2, j, positive)
      do step = 1, 80
        if (f1 <= f2) then
          high = t2
          t2 = t1
          f2 = f1
          t1 = high - golden*(high - low)
          f1 = signed_q(t1, j, positive)
        else
          low = t1
          t1 = t2
          f1 = f2
          t2 = low + golden*(high - low)
          f2 = signed_q(t2, j, positive)
        end if
        if (f1 < 0 .or. f2 < 0 .or. high - low <= 1.0e-15_wp*high) exit
      end do
      t1 = merge(t1, t2, f1 <= f2)
      call curve_points(t1, roots, q_values, m)
      if (m < j) return
      if (min(f1, f2) < 0) then
        call zero_on_branch(t_a, t1, j, positive)
        call zero_on_branch(t1, t_b, j, .not. positive)
      else
        call refine_at(t1, roots(j))
      end if
    end subroutine close_pair

    !> Q on branch j at t, negated if not positive (huge where the branch does not exist).
    real(wp) function signed_q(t, j, positive)
      real(wp), intent(in) :: t
      integer, intent(in) :: j
      logical, intent(in) :: positive
      real(wp) :: roots(3), q_values(3)
      integer :: m
      call curve_points(t, roots, q_values, m)
      signed_q = huge(1.0_wp)
      if (m >= j) signed_q = merge(q_values(j), -q_values(j), positive)
    end function signed_q

    !> refine at the grid variable t and the other amplitude.
    subroutine refine_at(t, root)
      real(wp), intent(in) :: t, root
      if (along_s == 0) then
        call refine(t, root)
      else
        call refine(root, t)
      end if
    end subroutine refine_at

    pure real(wp) function horner(q, s)
      real(wp), intent(in) :: q(0:4), s
      horner = (((q(4)*s + q(3))*s + q(2))*s + q(1))*s + q(0)
    end function horner

    !> P(r, s)/v^2 = s^3 + p2 s^2 + p1 s + p0 (v = k2 c21) and Q(r, s) = sum_j q_j s^j.
    subroutine amplitude_polynomials(r, p, q)
      real(wp), intent(in) :: r
      real(wp), intent(out) :: p(0:2), q(0:4)
      real(wp) :: w, y, u, v, kk, e_re(0:2), e_im(0:1), d2(0:2)
      associate (m => self%modal, c => self%modal%c)
        w = -(rho - m%omega1) + c(1, 1)*r/(8*m%omega1)   ! q1 = w + y s
        y = 2*c(1, 2)/(8*m%omega1)
        if (.not. coupled) then
          p = 0
          q = [r*(alpha1**2 + w**2) - forcing**2, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp]
          return
        end if
        u = -(3*(rho - m%omega1) - (m%omega2 - 3*m%omega1)) + 2*c(2, 2)*r/(8*m%omega2)
        v = c(2, 1)/(8*m%omega2)                           ! q2 = u + v s
        kk = c(1, 3)*c(2, 3)/(64*m%omega1*m%omega2)
        p = [-(c(2, 3)/(8*m%omega2))**2*r**3, alpha2**2 + u**2, 2*u*v]/v**2
        e_re = [alpha1*alpha2 + kk*r**2 - w*u, -(w*v + y*u), -y*v]   ! Re E
        e_im = [-(alpha1*u + alpha2*w), -(alpha1*v + alpha2*y)]      ! Im E
        d2 = [alpha2**2 + u**2, 2*u*v, v**2]                         ! |D2|^2
      end associate
      q(0) = r*(e_re(0)**2 + e_im(0)**2) - forcing**2*d2(0)
      q(1) = r*(2*e_re(0)*e_re(1) + 2*e_im(0)*e_im(1)) - forcing**2*d2(1)
      q(2) = r*(e_re(1)**2 + 2*e_re(0)*e_re(2) + e_im(1)**2) - forcing**2*d2(2)
      q(3) = r*2*e_re(1)*e_re(2)
      q(4) = r*e_re(2)**2
    end subroutine amplitude_polynomials

    !> The steady state from amplitudes (r, s), refined by Newton; kept if new and within
    !> x_max.
    subroutine refine(r, s)
      real(wp), intent(in) :: r, s
      complex(wp), parameter :: i = (0.0_wp, 1.0_wp)
      real(wp) :: x(n), q1, q2
      complex(wp) :: d2, e, b1, b2
      integer :: iterations, info
      character(len=message_len) :: msg
      associate (m => self%modal, c => self%modal%c)
        q1 = -(rho - m%omega1) + (c(1, 1)*r + 2*c(1, 2)*s)/(8*m%omega1)
        if (coupled) then
          q2 = -(3*(rho - m%omega1) - (m%omega2 - 3*m%omega1)) + &
               (c(2, 1)*s + 2*c(2, 2)*r)/(8*m%omega2)
          d2 = cmplx(-alpha2, q2, wp)
          e = cmplx(-alpha1, q1, wp)*d2 + c(1, 3)*c(2, 3)/(64*m%omega1*m%omega2)*r**2
          b1 = -forcing*d2/e
          b2 = i*c(2, 3)/(8*m%omega2)*b1**3/d2
          x = [real(b1), aimag(b1), real(b2), aimag(b2)]
        else
          b1 = -forcing/cmplx(-alpha1, q1, wp)
          x = [real(b1), aimag(b1)]
        end if
      end associate
      call newton_solve(self, x, lambda, newton, iterations, info, msg, explain=.false.)
      if (info /= SD_OK .or. .not. all(ieee_is_finite(x))) return
      if (maxval(abs(x)) > x_max .or. known(x) .or. n_states == size(states, 2)) return
      n_states = n_states + 1
      states(:, n_states) = x
    end subroutine refine

    logical function known(x)
      real(wp), intent(in) :: x(:)
      integer :: k
      known = .false.
      do k = 1, n_states
        if (maxval(abs(states(:, k) - x)) <= 1.0e-8_wp*(1 + maxval(abs(x)))) known = .true.
      end do
    end function known
  end subroutine steady_states

  !> The real roots, ascending, of s^3 + p2 s^2 + p1 s + p0 (Cardano, or Viete's cosines for
  !> three real roots), each refined by two Newton steps.
  pure subroutine cubic_roots(p, roots, m)
    real(wp), intent(in) :: p(0:2)
    real(wp), intent(out) :: roots(3)
    integer, intent(out) :: m
    real(wp) :: a, b, disc, t, angle
    integer :: j, step
    a = p(1) - p(2)**2/3                              ! t^3 + a t + b = 0, s = t - p2/3
    b = 2*p(2)**3/27 - p(2)*p(1)/3 + p(0)
    disc = (b/2)**2 + (a/3)**3
    roots = 0
    if (disc > 0 .or. a >= 0) then
      m = 1
      t = sqrt(max(disc, 0.0_wp))
      roots(1) = cube_root(-b/2 + t) + cube_root(-b/2 - t) - p(2)/3
    else
      m = 3
      angle = acos(max(-1.0_wp, min(1.0_wp, 3*b/(2*a)*sqrt(-3/a))))/3
      roots = [(2*sqrt(-a/3)*cos(angle - 2*pi*j/3) - p(2)/3, j = 0, 2)]
      call sort_ascending(roots)
    end if
    do j = 1, m
      do step = 1, 2
        t = (3*roots(j) + 2*p(2))*roots(j) + p(1)
        if (t /= 0) roots(j) = roots(j) - (((roots(j) + p(2))*roots(j) + p(1))*roots(j) + p(0))/t
      end do
    end do
  end subroutine cubic_roots

  pure real(wp) function cube_root(y)
    real(wp), intent(in) :: y
    cube_root = sign(abs(y)**(1.0_wp/3), y)
  end function cube_root
end module sloshdyn_slowflow
