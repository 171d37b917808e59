!> The criticality of a period doubling (flip) of a periodic orbit (issue 42): the cubic
!> normal-form coefficient of the stroboscopic map P (over k forcing periods) restricted to its
!> centre manifold at a multiplier -1 (Kuznetsov, Elements of Applied Bifurcation Theory, 3rd
!> ed. 2004, sec 5.4 and 8.7.2, eq 8.24):
!>   c = 1/6 <p, C(q, q, q)> - 1/2 <p, B(q, (A - I)^-1 B(q, q))>,
!> A = M (the monodromy matrix), A q = -q with |q| = 1, A^T p = -p with <p, q> = 1, and B, C the
!> second and third derivatives of P. On the centre manifold x = eta q the map is
!> eta -> -(1 + beta) eta + c eta^3 + ..., with mu = -(1 + beta) the critical multiplier: for
!> c > 0 the doubled orbits are born where the orbit is unstable (beta > 0), stable, at
!> |eta| = sqrt(beta/c) (supercritical); for c < 0 they are born unstable where the orbit is
!> stable, and past the point the motion jumps away (subcritical).
!>
!> B and C come from the monodromy matrices of the variational equations (never from second
!> differences of P): B(q, u) = D(M q) u = (M(y + h u) q - M(y - h u) q)/(2 h) and C(q, q, q)
!> = D^2(M q)(q, q) = (M(y + h q) q - 2 M(y) q + M(y - h q) q)/h^2, h = step (1 + max|y|).
module sloshdyn_map_normal_form
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT
  use sloshdyn_text, only: num2str
  use sloshdyn_lapack, only: solve_linear
  use sloshdyn_ode, only: ode_options
  use sloshdyn_shooting, only: periodic_problem, monodromy_matrix
  use sloshdyn_bifurcation, only: null_vectors
  implicit none
  private
  public :: period_doubling_coefficient

  !> the finite-difference step relative to 1 + max|y|
  real(wp), parameter :: step = 1.0e-4_wp
  !> the critical multiplier must lie within this of -1
  real(wp), parameter :: max_distance = 1.0e-3_wp

contains

  !> The flip coefficient c (above) of the orbit of period k T through y at the problem's
  !> parameter (a period doubling point), with the critical eigenvector q (|q| = 1) and the
  !> multiplier mu nearest -1 of M. Fails with SD_BAD_INPUT when no multiplier lies within
  !> 1e-3 of -1.
  subroutine period_doubling_coefficient(problem, y, k, options, method, c, q, mu, status, &
                                         message)
    class(periodic_problem), intent(in) :: problem
    real(wp), intent(in) :: y(:)
    integer, intent(in) :: k, method
    type(ode_options), intent(in) :: options
    real(wp), intent(out) :: c, q(:), mu
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: a(size(y), size(y)), shifted(size(y), size(y)), p(size(y)), y_end(size(y))
    real(wp) :: bqq(size(y)), cqqq(size(y)), w(size(y)), bqw(size(y)), h
    integer :: n, i

    n = size(y)
    c = ieee_value(1.0_wp, ieee_quiet_nan)
    mu = c
    q = c
    call monodromy_matrix(problem, y, k, options, method, y_end, a, status, message)
    if (status /= SD_OK) return
    shifted = a
    do i = 1, n
      shifted(i, i) = shifted(i, i) + 1
    end do
    call null_vectors(shifted, q, p, status, message)
    if (status /= SD_OK) return
    mu = dot_product(q, matmul(a, q))
    if (abs(mu + 1) > max_distance) then
      status = SD_BAD_INPUT
      message = 'the multiplier nearest -1 is '//num2str(mu)//': not a period doubling '// &
                '(it must lie within '//num2str(max_distance)//' of -1)'
      return
    end if
    p = p/dot_product(p, q)
    h = step*(1 + maxval(abs(y)))
    call second_and_third(q, bqq, cqqq)
    if (status /= SD_OK) return
    ! w = (A - I)^-1 B(q, q)
    shifted = a
    do i = 1, n
      shifted(i, i) = shifted(i, i) - 1
    end do
    w = bqq
    call solve_linear(shifted, w, status, message)
    if (status /= SD_OK) return
    call mixed(w, bqw)
    if (status /= SD_OK) return
    c = dot_product(p, cqqq)/6 - dot_product(p, bqw)/2

  contains

    !> M(z) q at z = y + s u
    subroutine m_times_q(u, s, v)
      real(wp), intent(in) :: u(:), s
      real(wp), intent(out) :: v(:)
      real(wp) :: m(size(y), size(y)), z_end(size(y))
      call monodromy_matrix(problem, y + s*u, k, options, method, z_end, m, status, message)
      v = matmul(m, q)
    end subroutine m_times_q

    !> B(q, q) and C(q, q, q)
    subroutine second_and_third(u, b, third)
      real(wp), intent(in) :: u(:)
      real(wp), intent(out) :: b(:), third(:)
      real(wp) :: plus(size(y)), minus(size(y))
      call m_times_q(u, h, plus)
      if (status == SD_OK) call m_times_q(u, -h, minus)
      if (status /= SD_OK) return
      b = (plus - minus)/(2*h)
      third = (plus - 2*matmul(a, q) + minus)/h**2
    end subroutine second_and_third

    !> B(q, u) for any u (scaled to unit length for the difference)
    subroutine mixed(u, b)
      real(wp), intent(in) :: u(:)
      real(wp), intent(out) :: b(:)
      real(wp) :: plus(size(y)), minus(size(y)), scale
      scale = norm2(u)
      b = 0
      if (scale == 0) return
      call m_times_q(u/scale, h, plus)
      if (status == SD_OK) call m_times_q(u/scale, -h, minus)
      if (status /= SD_OK) return
      b = scale*(plus - minus)/(2*h)
    end subroutine mixed
  end subroutine period_doubling_coefficient
end module sloshdyn_map_normal_form
