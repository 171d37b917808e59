!> The criticality of a period doubling (flip, issue 42) or of a Z2-symmetric pitchfork (issue
!> 41: a swirl edge, the out-of-plane mirror y -> -y) of a periodic orbit: the cubic normal-form
!> coefficient of the stroboscopic map P (over k forcing periods) restricted to its centre
!> manifold at a multiplier sigma = -1 or +1 (Kuznetsov, Elements of Applied Bifurcation Theory,
!> 3rd ed. 2004, sec 5.4 and 8.7.2, eq 8.24), on x = eta q + eta^2 w/2 + ...:
!>   c = 1/6 <p, C(q, q, q)> + 1/2 <p, B(q, w)>,   (I - A) w = B(q, q),
!> A = M (the monodromy matrix), A q = sigma q with |q| = 1, A^T p = sigma p with <p, q> = 1,
!> and B, C the second and third derivatives of P (for sigma = -1, w = -(A - I)^-1 B(q, q),
!> Kuznetsov's eq 8.24). The map on the centre manifold is eta -> sigma (1 + beta) eta + c eta^3
!> + ..., 1 + beta the modulus of the critical multiplier.
!>   Flip (sigma = -1, I - A invertible): for c > 0 the doubled orbits are born where the orbit
!> is unstable (beta > 0), stable, at |eta| = sqrt(beta/c) (supercritical); for c < 0 they are
!> born unstable where the orbit is stable, and past the point the motion jumps away
!> (subcritical).
!>   Pitchfork (sigma = +1, symmetric: q antisymmetric, B(q, q) symmetric, so <p, B(q, q)> = 0,
!> no eta^2 term): I - A is singular along q, and w is the solution with <p, w> = 0 of the
!> bordered system [I - A, q; p^T, 0] [w; s] = [B(q, q); 0] (s = <p, B(q, q)>, zero by the
!> symmetry up to the differences' error). The new fixed points are at eta^2 = -beta/c: for
!> c < 0 they are born where the orbit is unstable (beta > 0), stable (supercritical: a gentle
!> onset); for c > 0 unstable where it is stable (subcritical: past the point a jump away).
!>
!> B and C come from the monodromy matrices of the variational equations (never from second
!> differences of P): B(q, u) = D(M q) u = (M(y + h u) q - M(y - h u) q)/(2 h) and C(q, q, q)
!> = D^2(M q)(q, q) = (M(y + h q) q - 2 M(y) q + M(y - h q) q)/h^2, h = step (1 + max|y|).
!>
!> The criticality of a Neimark-Sacker point (a pair of multipliers e^{+-i theta}, 0 < theta <
!> pi): the first Lyapunov coefficient of the map's normal form z -> e^{i theta} z (1 + beta +
!> d |z|^2) (Kuznetsov 2004: the normal form sec 4.7, its coefficient on the centre manifold of
!> an n-dimensional map sec 5.4):
!>   d = 1/2 Re{e^{-i theta} [<p, C(q, q, qb)> + 2 <p, B(q, (I - A)^-1 B(q, qb))>
!>                            + <p, B(qb, (e^{2 i theta} I - A)^-1 B(q, q))>]},
!> A q = e^{i theta} q, A^T p = e^{-i theta} p, <p, q> = conj(p)^T q = 1, qb = conj(q). For d < 0
!> a stable invariant closed curve (a torus of the flow) is born where the orbit is unstable
!> (supercritical); d > 0: an unstable one where it is stable (subcritical). B and C extend to
!> complex vectors by linearity, from the same monodromy matrices: B(q, z) = (D_qr M + i D_qi
!> M) z and C(q, q, z) = (H_rr - H_ii + 2 i H_ri) z, q = qr + i qi, H_uv the second
!> derivatives of M along u, v (H_ri by polarisation along qr + qi and qr - qi).
!>
!> A caller that already has M(y) passes it in (optional argument monodromy): it must be
!> monodromy_matrix's at y for the same problem, k, options and method, without a parameter
!> column (a sensitivity column changes the integrator's steps). M(y) enters the second
!> differences beside M(y +- h u), and only with the same integration does their error cancel:
!> an M off by delta gives C off by delta/h^2 (1e8 delta at h = 1e-4).
module sloshdyn_map_normal_form
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT
  use sloshdyn_text, only: num2str
  use sloshdyn_lapack, only: solve_linear, eigenvalues
  use sloshdyn_ode, only: ode_options
  use sloshdyn_shooting, only: periodic_problem, monodromy_matrix, volume_preserving
  use sloshdyn_bifurcation, only: null_vectors
  implicit none
  private
  public :: cubic_coefficient, neimark_sacker_coefficient

  !> the finite-difference step relative to 1 + max|y|
  real(wp), parameter :: step = 1.0e-4_wp
  !> the critical multiplier must lie within this of -1 (+1)
  real(wp), parameter :: max_distance = 1.0e-3_wp
  !> a symmetric map at +1: |<p, B(q, q)>| at most this relative to |p| |B(q, q)|
  real(wp), parameter :: max_asymmetry = 1.0e-3_wp

contains

  !> The coefficient c (above) of the orbit of period k T through y at the problem's parameter,
  !> at the critical multiplier sigma = -1 (a period doubling) or +1 (a Z2-symmetric
  !> pitchfork, q antisymmetric), with the critical eigenvector q (|q| = 1), mu, the multiplier
  !> nearest sigma, and (optional) the size of its terms, |<p, C>|/6 + |<p, B>|/2 (c = 0 by
  !> their cancellation, or because both vanish, as for a linear map). Fails with SD_BAD_INPUT
  !> when no multiplier lies within 1e-3 of sigma, sigma is not -1 or +1, the map preserves
  !> volume (no damping: the critical multiplier is double) or, at +1, it is not symmetric
  !> (<p, B(q, q)> /= 0: a transcritical point). monodromy (optional): M(y), then not
  !> recomputed (module header).
  subroutine cubic_coefficient(problem, y, k, options, method, sigma, c, q, mu, status, &
                               message, size_of_terms, monodromy)
    class(periodic_problem), intent(in) :: problem
    real(wp), intent(in) :: y(:)
    integer, intent(in) :: k, method, sigma
    type(ode_options), intent(in) :: options
    real(wp), intent(out) :: c, q(:), mu
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), intent(out), optional :: size_of_terms
    real(wp), intent(in), optional :: monodromy(:, :)
    real(wp) :: a(size(y), size(y)), shifted(size(y), size(y)), p(size(y))
    real(wp) :: bqq(size(y)), cqqq(size(y)), w(size(y)), bqw(size(y)), h
    real(wp) :: bordered(size(y) + 1, size(y) + 1), wb(size(y) + 1), re(size(y)), im(size(y))
    integer :: n, i
    character(len=2) :: critical

    n = size(y)
    critical = merge('+1', '-1', sigma == 1)
    c = ieee_value(1.0_wp, ieee_quiet_nan)
    mu = c
    q = c
    if (abs(sigma) /= 1) then
      status = SD_BAD_INPUT
      message = 'sigma = '//num2str(sigma)//' is out of range: the critical multiplier is -1 '// &
                'or +1'
      return
    end if
    call central_monodromy(problem, y, k, options, method, a, status, message, monodromy)
    if (status /= SD_OK) return
    shifted = a
    do i = 1, n
      shifted(i, i) = shifted(i, i) - sigma
    end do
    call null_vectors(shifted, q, p, status, message)
    if (status /= SD_OK) return
    mu = dot_product(q, matmul(a, q))
    if (abs(mu - sigma) > max_distance) then
      status = SD_BAD_INPUT
      message = 'the multiplier nearest '//critical//' is '//num2str(mu)//': not a '// &
                trim(merge('pitchfork      ', 'period doubling', sigma == 1))// &
                ' (it must lie within '//num2str(max_distance)//' of '//critical//')'
      return
    end if
    ! a volume-preserving map (no damping) has its critical multipliers in a pair (mu, 1/mu),
    ! a double one at the point, where the one-dimensional centre manifold does not hold
    call eigenvalues(a, re, im, status, message)
    if (status /= SD_OK) return
    if (volume_preserving(re, im)) then
      status = SD_BAD_INPUT
      message = 'the map preserves volume (no damping): its multipliers at '//critical// &
                ' come in a pair, and the cubic normal form of a simple one does not apply'
      return
    end if
    p = p/dot_product(p, q)
    h = step*(1 + maxval(abs(y)))
    call second_and_third(q, bqq, cqqq)
    if (status /= SD_OK) return
    ! w: (I - A) w = B(q, q); at +1 the bordered system, <p, w> = 0 (module header)
    shifted = -a
    do i = 1, n
      shifted(i, i) = shifted(i, i) + 1
    end do
    if (sigma == 1) then
      bordered = 0
      bordered(1:n, 1:n) = shifted
      bordered(1:n, n + 1) = q
      bordered(n + 1, 1:n) = p
      wb = [bqq, 0.0_wp]
      call solve_linear(bordered, wb, status, message)
      w = wb(1:n)
      ! wb(n + 1) = <p, B(q, q)>, zero by the symmetry: else a transcritical point
      if (status == SD_OK .and. abs(wb(n + 1)) > max_asymmetry*norm2(bqq)*norm2(p)) then
        status = SD_BAD_INPUT
        message = 'the map is not symmetric about the orbit: <p, B(q, q)> = '// &
                  num2str(wb(n + 1))//' (a transcritical point, not a pitchfork)'
      end if
    else
      w = bqq
      call solve_linear(shifted, w, status, message)
    end if
    if (status /= SD_OK) return
    call mixed(w, bqw)
    if (status /= SD_OK) return
    c = dot_product(p, cqqq)/6 + dot_product(p, bqw)/2
    if (present(size_of_terms)) size_of_terms = abs(dot_product(p, cqqq))/6 + &
                                                abs(dot_product(p, bqw))/2

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
  end subroutine cubic_coefficient

  !> The Neimark-Sacker coefficient d (above) of the orbit of period k T through y at the
  !> problem's parameter, with the critical multiplier mu = |mu| e^{i theta} (Im mu > 0)
  !> nearest the unit circle, its eigenvector q (unit length) and (optional) the size of its
  !> terms, the sum of their moduli over 2. Fails with SD_BAD_INPUT when no complex multiplier
  !> lies within 1e-3 of the unit circle. monodromy (optional): M(y), then not recomputed
  !> (module header).
  subroutine neimark_sacker_coefficient(problem, y, k, options, method, d, q, mu, status, &
                                        message, size_of_terms, monodromy)
    class(periodic_problem), intent(in) :: problem
    real(wp), intent(in) :: y(:)
    integer, intent(in) :: k, method
    type(ode_options), intent(in) :: options
    real(wp), intent(out) :: d
    complex(wp), intent(out) :: q(:), mu
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), intent(out), optional :: size_of_terms
    real(wp), intent(in), optional :: monodromy(:, :)
    real(wp) :: a(size(y), size(y)), wr(size(y)), wi(size(y)), h
    real(wp) :: big(2*size(y), 2*size(y)), x(2*size(y)), xl(2*size(y)), rhs(2*size(y))
    real(wp), dimension(size(y), size(y)) :: g_r, g_i, h_rr, h_ii, h_ri, h_w, g_w, m_plus, &
                                             m_minus, eye
    real(wp) :: w1(size(y))
    complex(wp) :: p(size(y)), e, bqq(size(y)), w2(size(y)), terms(3)
    integer :: n, i, j

    n = size(y)
    d = ieee_value(1.0_wp, ieee_quiet_nan)
    mu = cmplx(d, d, wp)
    q = mu
    call central_monodromy(problem, y, k, options, method, a, status, message, monodromy)
    if (status /= SD_OK) return
    call eigenvalues(a, wr, wi, status, message)
    if (status /= SD_OK) return
    j = 0
    do i = 1, n
      if (wi(i) <= 0) cycle
      if (j == 0) then
        j = i
      else if (abs(hypot(wr(i), wi(i)) - 1) < abs(hypot(wr(j), wi(j)) - 1)) then
        j = i
      end if
    end do
    if (j == 0) then
      status = SD_BAD_INPUT
      message = 'no complex pair of multipliers: not a Neimark-Sacker point'
      return
    end if
    mu = cmplx(wr(j), wi(j), wp)
    if (abs(abs(mu) - 1) > max_distance) then
      status = SD_BAD_INPUT
      message = 'the complex multipliers nearest the unit circle have modulus '// &
                num2str(abs(mu))//': not a Neimark-Sacker point (it must lie within '// &
                num2str(max_distance)//' of 1)'
      return
    end if
    e = mu/abs(mu)
    eye = 0
    do i = 1, n
      eye(i, i) = 1
    end do
    ! q and p from the null vectors of the real form of A - mu I (and of its transpose)
    big(1:n, 1:n) = a - wr(j)*eye
    big(1:n, n + 1:) = wi(j)*eye
    big(n + 1:, 1:n) = -wi(j)*eye
    big(n + 1:, n + 1:) = a - wr(j)*eye
    call null_vectors(big, x, xl, status, message)
    if (status /= SD_OK) return
    q = cmplx(x(1:n), x(n + 1:), wp)
    q = q/sqrt(sum(abs(q)**2))
    p = cmplx(xl(1:n), xl(n + 1:), wp)
    p = p/conjg(dot_product(p, q))          ! dot_product(p, q) = conj(p)^T q
    h = step*(1 + maxval(abs(y)))
    call derivatives(real(q, wp), g_r, h_rr)
    if (status == SD_OK) call derivatives(aimag(q), g_i, h_ii)
    if (status /= SD_OK) return
    call derivatives(real(q, wp) + aimag(q), g_w, h_ri)        ! along qr + qi ...
    if (status == SD_OK) call derivatives(real(q, wp) - aimag(q), g_w, h_w)   ! ... qr - qi
    if (status /= SD_OK) return
    h_ri = (h_ri - h_w)/4
    ! (I - A) w1 = B(q, qb), a real vector
    w1 = real(matmul(cmplx(g_r, g_i, wp), conjg(q)), wp)
    call solve_linear(eye - a, w1, status, message)
    if (status /= SD_OK) return
    ! (e^2 I - A) w2 = B(q, q), in real form
    bqq = matmul(cmplx(g_r, g_i, wp), q)
    big(1:n, 1:n) = real(e**2, wp)*eye - a
    big(1:n, n + 1:) = -aimag(e**2)*eye
    big(n + 1:, 1:n) = aimag(e**2)*eye
    big(n + 1:, n + 1:) = real(e**2, wp)*eye - a
    rhs = [real(bqq, wp), aimag(bqq)]
    call solve_linear(big, rhs, status, message)
    if (status /= SD_OK) return
    w2 = cmplx(rhs(1:n), rhs(n + 1:), wp)
    terms = [dot_product(p, matmul(cmplx(h_rr - h_ii, 2*h_ri, wp), conjg(q))), &
             2*dot_product(p, matmul(cmplx(g_r, g_i, wp), cmplx(w1, 0.0_wp, wp))), &
             dot_product(p, matmul(cmplx(g_r, -g_i, wp), w2))]
    d = real(conjg(e)*sum(terms), wp)/2
    if (present(size_of_terms)) size_of_terms = sum(abs(terms))/2

  contains

    !> The first (central) and second differences of M along u.
    subroutine derivatives(u, first, second)
      real(wp), intent(in) :: u(:)
      real(wp), intent(out) :: first(:, :), second(:, :)
      real(wp) :: z_end(size(y))
      call monodromy_matrix(problem, y + h*u, k, options, method, z_end, m_plus, status, message)
      if (status == SD_OK) call monodromy_matrix(problem, y - h*u, k, options, method, z_end, &
                                                 m_minus, status, message)
      if (status /= SD_OK) return
      first = (m_plus - m_minus)/(2*h)
      second = (m_plus - 2*a + m_minus)/h**2
    end subroutine derivatives
  end subroutine neimark_sacker_coefficient

  !> M(y): the caller's (given) or by monodromy_matrix; a given one must have shape (n, n).
  subroutine central_monodromy(problem, y, k, options, method, a, status, message, given)
    class(periodic_problem), intent(in) :: problem
    real(wp), intent(in) :: y(:)
    integer, intent(in) :: k, method
    type(ode_options), intent(in) :: options
    real(wp), intent(out) :: a(:, :)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), intent(in), optional :: given(:, :)
    real(wp) :: y_end(size(y))
    if (.not. present(given)) then
      call monodromy_matrix(problem, y, k, options, method, y_end, a, status, message)
      return
    end if
    status = SD_OK
    message = ''
    if (any(shape(given) /= shape(a))) then
      status = SD_BAD_INPUT
      message = 'monodromy has shape ('//num2str(size(given, 1))//', '// &
                num2str(size(given, 2))//'); it must be (n, n), n = size(y) = '// &
                num2str(size(y))
      return
    end if
    a = given
  end subroutine central_monodromy
end module sloshdyn_map_normal_form
