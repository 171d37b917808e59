!> Equations of motion of the tank-pendulum system, eq (10), (13)-(15), with the base
!> acceleration X'' of the model's excitation (eq 29-31 for harmonic motion) and, beyond the
!> paper, a linear sloshing damping 2 zeta x1' in the pendulum's equation (zeta = 0: the paper). State y = (x1, x1', x2, x2'), x1 = theta/theta0, x2 = phi/theta0,
!> ' = d/dtau. No allocation and no I/O: these are called in every integrator step.
module sloshdyn_motion
  use sloshdyn_kinds, only: wp
  use sloshdyn_model, only: model_t
  use sloshdyn_excitation, only: base_acceleration
  implicit none
  private
  public :: inertia_matrix, forcing_vector, equations_of_motion, motion_jacobian, &
            excitation_direction, equations_of_motion_block

  !> Trigonometric functions and powers of one state, each evaluated once.
  type :: state_terms
    real(wp) :: cos12, sin12       !< cos, sin of theta0 (x1 + x2)
    real(wp) :: cos1, sin1         !< cos, sin of theta0 x1
    real(wp) :: cos2, sin2         !< cos, sin of theta0 x2
    real(wp) :: impact_pow         !< x1^(2n-1) (a zero of its sign where beta = 0)
    real(wp) :: dissipation_pow    !< x1^(2p) (0 where delta = 0)
    real(wp) :: xdd                !< base acceleration X''
  end type state_terms

contains

  pure subroutine evaluate_terms(model, tau, y, t)
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: tau, y(4)
    type(state_terms), intent(out) :: t
    real(wp) :: q1, q2
    q1 = model%theta0*y(1)
    q2 = model%theta0*y(3)
    t%cos1 = cos(q1); t%sin1 = sin(q1)
    t%cos2 = cos(q2); t%sin2 = sin(q2)
    ! angle addition instead of a third sine/cosine pair: the right-hand side's costliest part
    t%cos12 = t%cos1*t%cos2 - t%sin1*t%sin2
    t%sin12 = t%sin1*t%cos2 + t%cos1*t%sin2
    ! the contact-free models (beta = delta = 0, e.g. a tank's below the roof) skip the powers
    ! where their coefficient's zero times them is a zero of the same sign: x1^(2n-1) has the
    ! sign of x1, x1^(2p) >= +0, and both are finite while |x1| <= 1
    if (model%a_coef(4) == 0 .and. abs(y(1)) <= 1) then
      t%impact_pow = sign(0.0_wp, y(1))
    else
      t%impact_pow = integer_power(y(1), 2*model%n - 1)
    end if
    if (model%a_coef(5) == 0 .and. abs(y(1)) <= 1) then
      t%dissipation_pow = 0
    else
      t%dissipation_pow = integer_power(y(1), 2*model%p)
    end if
    t%xdd = base_acceleration(model%excitation, tau)
  end subroutine evaluate_terms

  !> x**k for k >= 0 by binary powering, step for step the loop of libgcc's __powidf2 that
  !> gfortran calls for x**k with a variable k: the same value to the bit, without the call
  !> into the shared library (2 of them cost 56 of ~575 instructions per right-hand side).
  pure real(wp) function integer_power(x, k) result(r)
    real(wp), intent(in) :: x
    integer, intent(in) :: k
    real(wp) :: s
    integer :: m
    m = k
    s = x
    r = 1
    if (iand(m, 1) /= 0) r = x
    do
      m = shiftr(m, 1)
      if (m == 0) exit
      s = s*s
      if (iand(m, 1) /= 0) r = r*s
    end do
  end function integer_power

  !> Inertia matrix, eq (13).
  pure subroutine inertia_matrix(model, y, mass)
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: y(4)
    real(wp), intent(out) :: mass(2, 2)
    real(wp) :: c
    c = cos(model%theta0*(y(1) + y(3)))
    mass = reshape([1.0_wp, model%b_coef(1)*c, model%a_coef(1)*c, 1.0_wp], [2, 2])
  end subroutine inertia_matrix

  !> Forcing vector, eq (14) with b6 (printed b8) and X'' of eq (31).
  pure subroutine forcing_vector(model, tau, y, force)
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: tau, y(4)
    real(wp), intent(out) :: force(2)
    type(state_terms) :: t
    call evaluate_terms(model, tau, y, t)
    force = forcing_from_terms(model, y, t)
  end subroutine forcing_vector

  pure function forcing_from_terms(model, y, t) result(force)
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: y(4)
    type(state_terms), intent(in) :: t
    real(wp) :: force(2)
    associate (a => model%a_coef, b => model%b_coef)
      ! the linear sloshing damping 2 zeta x1' comes last: zeta = 0 leaves the sum unchanged
      force(1) = a(2)*t%sin12*y(4)**2 - a(3)*t%sin1 - a(4)*t%impact_pow &
                 - a(5)*t%dissipation_pow*y(2) - a(6)*t%cos1*t%xdd - 2*model%zeta*y(2)
      force(2) = b(2)*t%sin12*y(2)**2 - b(3)*y(3) + b(4)*t%sin2 - b(5)*y(4) - b(6)*t%xdd*t%cos2
    end associate
  end function forcing_from_terms

  !> First-order form of eq (15), Q'' = M^-1 F: dydt = (x1', x1'', x2', x2'').
  !> With angles: also (cos, sin) of theta0 x1 and of theta0 x2, and with xdd X'', as the
  !> right-hand side computed them (the tank's loads need them too).
  pure subroutine equations_of_motion(model, tau, y, dydt, angles, xdd)
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: tau, y(4)
    real(wp), intent(out) :: dydt(4)
    real(wp), intent(out), optional :: angles(4), xdd
    type(state_terms) :: t
    real(wp) :: force(2), qdd(2)
    call evaluate_terms(model, tau, y, t)
    force = forcing_from_terms(model, y, t)
    qdd = solve_inertia(model, t%cos12, force)
    dydt = [y(2), qdd(1), y(4), qdd(2)]
    if (present(angles)) angles = [t%cos1, t%sin1, t%cos2, t%sin2]
    if (present(xdd)) xdd = t%xdd
  end subroutine equations_of_motion

  !> equations_of_motion for many states at once, column c of models(members(c)) at
  !> (tau(c), y(:, c)): the same operations per column (the same bits), ordered so that the
  !> columns' independent sine and cosine evaluations follow each other and overlap in the
  !> processor (the ensembles of sloshdyn_ensemble).
  pure subroutine equations_of_motion_block(models, members, tau, y, dydt)
    type(model_t), intent(in) :: models(:)
    integer, intent(in) :: members(:)
    real(wp), intent(in) :: tau(:), y(:, :)
    real(wp), intent(out) :: dydt(:, :)
    type(state_terms) :: t(size(members))
    real(wp) :: force(2), qdd(2)
    integer :: c
    do c = 1, size(members)
      call evaluate_terms(models(members(c)), tau(c), y(:, c), t(c))
    end do
    do c = 1, size(members)
      force = forcing_from_terms(models(members(c)), y(:, c), t(c))
      qdd = solve_inertia(models(members(c)), t(c)%cos12, force)
      dydt(:, c) = [y(2, c), qdd(1), y(4, c), qdd(2)]
    end do
  end subroutine equations_of_motion_block

  !> M^-1 v for the 2x2 inertia matrix of eq (13); det M = 1 - mu1 cos^2 > 0 for mu1 < 1.
  pure function solve_inertia(model, cos12, v) result(w)
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: cos12, v(2)
    real(wp) :: w(2)
    real(wp) :: m12, m21, det
    m12 = model%a_coef(1)*cos12
    m21 = model%b_coef(1)*cos12
    det = 1 - m12*m21
    w = [(v(1) - m12*v(2))/det, (v(2) - m21*v(1))/det]
  end function solve_inertia

  !> d(dydt)/dX'': the equations of motion are affine in the base acceleration X'' (eq 10, 14),
  !> dydt = f0(y) + X'' e(y) with e = (0, q1, 0, q2), q = M^-1 (-a6 cos(theta0 x1), -b6 cos(theta0 x2)).
  !> Parameter sensitivities follow: d(dydt)/dlambda = e dX''/dlambda.
  pure subroutine excitation_direction(model, y, e)
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: y(4)
    real(wp), intent(out) :: e(4)
    real(wp) :: q(2)
    q = solve_inertia(model, cos(model%theta0*(y(1) + y(3))), &
                      [-model%a_coef(6)*cos(model%theta0*y(1)), -model%b_coef(6)*cos(model%theta0*y(3))])
    e = [0.0_wp, q(1), 0.0_wp, q(2)]
  end subroutine excitation_direction

  !> Analytic Jacobian d(dydt)/dy of equations_of_motion:
  !> dQ''/dz = M^-1 (dF/dz - (dM/dz) Q'').
  pure subroutine motion_jacobian(model, tau, y, jac)
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: tau, y(4)
    real(wp), intent(out) :: jac(4, 4)
    type(state_terms) :: t
    real(wp) :: force(2), qdd(2), dforce(2, 4), dmass_q(2), lower_pow, column(2)
    integer :: n, p, j

    call evaluate_terms(model, tau, y, t)
    force = forcing_from_terms(model, y, t)
    qdd = solve_inertia(model, t%cos12, force)
    n = model%n
    p = model%p
    associate (a => model%a_coef, b => model%b_coef, t0 => model%theta0)
      ! x1^(2p-1) only where its coefficient 2p is nonzero
      lower_pow = 0
      if (p > 0) lower_pow = 2*p*y(1)**(2*p - 1)
      ! dF/d(x1, x1', x2, x2')
      dforce(1, 1) = a(2)*t0*t%cos12*y(4)**2 - a(3)*t0*t%cos1 &
                     - a(4)*(2*n - 1)*y(1)**(2*n - 2) - a(5)*lower_pow*y(2) &
                     + a(6)*t0*t%sin1*t%xdd
      dforce(1, 2) = -a(5)*t%dissipation_pow - 2*model%zeta
      dforce(1, 3) = a(2)*t0*t%cos12*y(4)**2
      dforce(1, 4) = 2*a(2)*t%sin12*y(4)
      dforce(2, 1) = b(2)*t0*t%cos12*y(2)**2
      dforce(2, 2) = 2*b(2)*t%sin12*y(2)
      dforce(2, 3) = b(2)*t0*t%cos12*y(2)**2 - b(3) + b(4)*t0*t%cos2 + b(6)*t%xdd*t0*t%sin2
      dforce(2, 4) = -b(5)
      ! dM/dx1 = dM/dx2 = -theta0 sin12 [[0, a1], [b1, 0]]; minus it times Q''
      dmass_q = t0*t%sin12*[a(1)*qdd(2), b(1)*qdd(1)]
    end associate
    dforce(:, 1) = dforce(:, 1) + dmass_q
    dforce(:, 3) = dforce(:, 3) + dmass_q

    jac = 0
    jac(1, 2) = 1
    jac(3, 4) = 1
    do j = 1, 4
      column = solve_inertia(model, t%cos12, dforce(:, j))
      jac(2, j) = column(1)
      jac(4, j) = column(2)
    end do
  end subroutine motion_jacobian
end module sloshdyn_motion
