!> Symmetric periodic orbits on the half-period map, where their symmetry-breaking branch
!> points are regular (issue 42). For a system with the Z2 symmetry y -> -y, t -> t + kT/2
!> (docs/model.md, "Branch switching": eq 10 under X = A sin(rho tau)), a symmetric orbit of
!> period k T is a fixed point of the half-period map P(y) = -phi(k T/2; y), and its monodromy
!> matrix is M = (DP)^2 = Phi(kT/2)^2, Phi = d phi/dy. A branch point of the full-period
!> problem (a multiplier of M at +1 with an antisymmetric eigenvector) is where Phi has the
!> eigenvalue +1; there the fixed-point equation phi(y) + y = 0 keeps the regular Jacobian
!> Phi + I (eigenvalue 2). So the branch point is the zero of g(lambda) = det(Phi(lambda) - I)
!> along the symmetric orbits y(lambda), each found by Newton on phi(y) + y = 0: both steps are
!> regular, and the point is located to the integration's accuracy (on the full-period map
!> M - I is singular there and the location stalls near 1e-7).
module sloshdyn_half_period
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_NOT_CONVERGED
  use sloshdyn_text, only: num2str
  use sloshdyn_lapack, only: solve_linear
  use sloshdyn_ode, only: ode_options
  use sloshdyn_shooting, only: periodic_problem, monodromy_matrix
  implicit none
  private
  public :: symmetric_orbit, locate_symmetry_breaking

  !> The half-period problem: the system itself, its "period" k T/2, so that one shot of
  !> sloshdyn_shooting's monodromy_matrix integrates y and Phi over half an orbit.
  type, extends(periodic_problem) :: half_period_problem
    class(periodic_problem), allocatable :: full
    integer :: k = 1
  contains
    procedure :: rhs => half_rhs
    procedure :: jacobian => half_jacobian
    procedure :: period => half_period
    procedure :: parameter_derivative => half_parameter_derivative
    procedure :: set_parameter => half_set_parameter
    procedure :: parameter => half_parameter
    procedure :: period_derivative => half_period_derivative
    procedure :: state_size => half_state_size
  end type half_period_problem

  !> Newton on phi(y) + y = 0: converged at max|step| <= newton_tol (max|y| + 1e-12)
  real(wp), parameter :: newton_tol = 1.0e-13_wp
  integer, parameter :: max_newton = 30, max_secant = 40

contains

  !> The symmetric orbit of period k T of problem (at its current parameter) near y0: y with
  !> phi(k T/2; y) = -y by Newton with the exact Jacobian Phi + I, and Phi(k T/2) there.
  subroutine symmetric_orbit(problem, y0, k, options, method, y, phi, status, message)
    class(periodic_problem), intent(in) :: problem
    real(wp), intent(in) :: y0(:)
    integer, intent(in) :: k, method
    type(ode_options), intent(in) :: options
    real(wp), intent(out) :: y(:), phi(:, :)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(half_period_problem) :: half
    real(wp) :: y_half(size(y0)), a(size(y0), size(y0)), step(size(y0))
    integer :: i, iteration

    allocate (half%full, source=problem)
    half%k = k
    y = y0
    do iteration = 1, max_newton
      call monodromy_matrix(half, y, 1, options, method, y_half, phi, status, message)
      if (status /= SD_OK) return
      a = phi
      do i = 1, size(y)
        a(i, i) = a(i, i) + 1
      end do
      step = -(y_half + y)
      call solve_linear(a, step, status, message)
      if (status /= SD_OK) return
      y = y + step
      if (maxval(abs(step)) <= newton_tol*(maxval(abs(y)) + 1.0e-12_wp)) then
        call monodromy_matrix(half, y, 1, options, method, y_half, phi, status, message)
        return
      end if
    end do
    status = SD_NOT_CONVERGED
    message = 'the symmetric orbit (phi(kT/2; y) + y = 0) did not converge in '// &
              num2str(max_newton)//' Newton steps'
  end subroutine symmetric_orbit

  !> The symmetry-breaking branch point of the symmetric orbits of period k T near (y0,
  !> lambda0) (e.g. as located on the full-period map): lambda where det(Phi(k T/2) - I) = 0
  !> along the symmetric orbits, by the secant method from lambda0 and lambda0 + dlambda,
  !> to |step| <= 1e-14 (1 + |lambda|); y the symmetric orbit there. problem's parameter is
  !> the continued one (set_parameter).
  subroutine locate_symmetry_breaking(problem, y0, lambda0, dlambda, k, options, method, y, &
                                      lambda, status, message)
    class(periodic_problem), intent(in) :: problem
    real(wp), intent(in) :: y0(:), lambda0, dlambda
    integer, intent(in) :: k, method
    type(ode_options), intent(in) :: options
    real(wp), intent(out) :: y(:), lambda
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    class(periodic_problem), allocatable :: at
    real(wp) :: s(2), g(2), y_guess(size(y0)), lambda_new
    integer :: iteration

    allocate (at, source=problem)
    y_guess = y0
    s = [lambda0, lambda0 + dlambda]
    call det_at(s(1), g(1))
    if (status /= SD_OK) return
    call det_at(s(2), g(2))
    if (status /= SD_OK) return
    do iteration = 1, max_secant
      if (g(2) == g(1)) exit
      lambda_new = s(2) - g(2)*(s(2) - s(1))/(g(2) - g(1))
      if (.not. ieee_is_finite(lambda_new)) exit
      s = [s(2), lambda_new]
      g(1) = g(2)
      call det_at(lambda_new, g(2))
      if (status /= SD_OK) return
      if (abs(s(2) - s(1)) <= 1.0e-14_wp*(1 + abs(s(2))) .or. g(2) == 0) then
        lambda = s(2)
        return
      end if
    end do
    status = SD_NOT_CONVERGED
    message = 'the branch point on the half-period map (det(Phi(kT/2) - I) = 0) did not '// &
              'converge near lambda = '//num2str(lambda0)
    lambda = s(2)

  contains

    !> det(Phi - I) of the symmetric orbit at parameter value v (y and y_guess updated).
    subroutine det_at(v, det)
      real(wp), intent(in) :: v
      real(wp), intent(out) :: det
      real(wp) :: phi(size(y0), size(y0))
      integer :: i
      call at%set_parameter(v)
      call symmetric_orbit(at, y_guess, k, options, method, y, phi, status, message)
      det = 0
      if (status /= SD_OK) then
        message = 'the symmetric orbit at lambda = '//num2str(v)//': '//trim(message)
        return
      end if
      y_guess = y
      do i = 1, size(y0)
        phi(i, i) = phi(i, i) - 1
      end do
      det = determinant(phi)
    end subroutine det_at
  end subroutine locate_symmetry_breaking

  !> The determinant by Gaussian elimination with partial pivoting (small n).
  pure real(wp) function determinant(a_in) result(det)
    real(wp), intent(in) :: a_in(:, :)
    real(wp) :: a(size(a_in, 1), size(a_in, 2)), row(size(a_in, 2))
    integer :: n, i, p
    a = a_in
    n = size(a, 1)
    det = 1
    do i = 1, n
      p = i - 1 + maxloc(abs(a(i:n, i)), 1)
      if (a(p, i) == 0) then
        det = 0
        return
      end if
      if (p /= i) then
        row = a(i, :)
        a(i, :) = a(p, :)
        a(p, :) = row
        det = -det
      end if
      det = det*a(i, i)
      a(i + 1:n, i:n) = a(i + 1:n, i:n) - &
                        spread(a(i + 1:n, i)/a(i, i), 2, n - i + 1)*spread(a(i, i:n), 1, n - i)
    end do
  end function determinant

  subroutine half_rhs(self, t, y, dydt)
    class(half_period_problem), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: dydt(:)
    call self%full%rhs(t, y, dydt)
  end subroutine half_rhs

  subroutine half_jacobian(self, t, y, jac)
    class(half_period_problem), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: jac(:, :)
    call self%full%jacobian(t, y, jac)
  end subroutine half_jacobian

  function half_period(self) result(v)
    class(half_period_problem), intent(in) :: self
    real(wp) :: v
    v = self%k*self%full%period()/2
  end function half_period

  subroutine half_parameter_derivative(self, t, y, df)
    class(half_period_problem), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: df(:)
    call self%full%parameter_derivative(t, y, df)
  end subroutine half_parameter_derivative

  subroutine half_set_parameter(self, lambda)
    class(half_period_problem), intent(inout) :: self
    real(wp), intent(in) :: lambda
    call self%full%set_parameter(lambda)
  end subroutine half_set_parameter

  function half_parameter(self) result(v)
    class(half_period_problem), intent(in) :: self
    real(wp) :: v
    v = self%full%parameter()
  end function half_parameter

  function half_period_derivative(self) result(v)
    class(half_period_problem), intent(in) :: self
    real(wp) :: v
    v = self%k*self%full%period_derivative()/2
  end function half_period_derivative

  integer function half_state_size(self)
    class(half_period_problem), intent(in) :: self
    half_state_size = self%full%state_size()
  end function half_state_size
end module sloshdyn_half_period
