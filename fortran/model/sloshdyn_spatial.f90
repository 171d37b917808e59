!> The spatial tank-pendulum system (issue 26): the tank on rods that tilt in x and y, the sloshing
!> mass as a spherical pendulum, a base acceleration in two horizontal components. It is the
!> paper's model (eq 6-10) with every planar angle replaced by a tilt in space; docs/model.md,
!> "Spatial model and swirl", derives it (eq S1-S9 there).
!>
!> Coordinates. A tilt (a, b) turns the unit vector u = (sin a cos b, sin b, sigma cos a cos b):
!> the rods' direction t (sigma = +1, angles phi_x, phi_y) and the pendulum's n (sigma = -1, angles
!> theta_x, theta_y). b = 0 is the paper's plane; the tilt angle Theta from the vertical obeys
!> cos Theta = cos a cos b. Dimensionless positions (unit L): tank point t + (X, Y, 0), sloshing
!> mass t + s1 n + (X, Y, 0); masses 1 - mu1 and mu1 (unit M); gravity s1 (unit L omega^2).
!>
!> State y = (x1, x1', x2, x2', y1, y1', y2, y2'): x1 = theta_x/theta0, x2 = phi_x/theta0,
!> y1 = theta_y/theta0, y2 = phi_y/theta0, ' = d/dtau. Its first four entries are the planar
!> state: with y1 = y2 = 0, their rates 0 and Y'' = 0 the equations are eq (10) with the linear
!> sloshing damping of sloshdyn_motion, and y1 = y2 = 0 stays so (the plane is invariant).
!>
!> Forces as in the paper, made isotropic: the rods' spring k/2 Phi^2 (Phi the rods' tilt) and
!> damping on the tank point's velocity c |dt/dt|^2/2; the impact potential eq (3) and the
!> dissipation eq (5) on the pendulum's tilt Theta (the wall is reached at any azimuth when
!> Theta = theta0); the linear sloshing damping on the whole velocity of the pendulum, 2 zeta n'.
!> The system is then symmetric under rotations about the vertical: without forcing and damping
!> it conserves the energy and the angular momentum about the vertical (spatial_invariants).
!>
!> No allocation and no I/O: the right-hand side is called in every integrator step.
module sloshdyn_spatial
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, check_real
  use sloshdyn_text, only: num2str
  use sloshdyn_model, only: model_t
  use sloshdyn_excitation, only: excitation_t, base_acceleration, acceleration_sensitivity, &
                                 EXCITATION_HARMONIC, EXCITATION_RECORD, PARAMETER_RHO, &
                                 PARAMETER_A
  implicit none
  private
  public :: spatial_model_t, spatial_model, spatial_equations, spatial_jacobian, &
            spatial_invariants, spatial_accelerations, spatial_mass_matrix, &
            spatial_excitation_direction, ground_acceleration, ground_sensitivity, &
            spatial_kinematics, pendulum_tilt

  !> The planar model (its groups and its excitation) and the second horizontal component.
  !> The ground acceleration (X'', Y'') is R(azimuth) (g1, g2): for harmonic excitation
  !> g1 = -A rho^2 sin(rho tau), g2 = -ellipticity A rho^2 cos(rho tau) (an ellipse with axes A
  !> along the azimuth and ellipticity A across it); for a record g1 is the planar record and g2
  !> record_y (two records, rotated by the azimuth). azimuth = ellipticity = 0 and no record_y:
  !> the planar excitation, exactly.
  type :: spatial_model_t
    type(model_t) :: planar
    real(wp) :: azimuth = 0       !< direction of g1 from the x axis [rad]
    real(wp) :: ellipticity = 0   !< harmonic: minor over major axis, in [0, 1]
    type(excitation_t) :: record_y   !< record: the second component (A = 0, none, by default)
  end type spatial_model_t

  !> A tilt (a, b) and the derivatives of its unit vector u up to the third order:
  !> du(:, i, j) = d^(i+j) u / da^i db^j, i + j <= 3; c = cos a cos b = cos(tilt) and its
  !> gradient and Hessian in (a, b).
  type :: tilt_t
    real(wp) :: du(3, 0:3, 0:3) = 0
    real(wp) :: tilt = 0, sin_tilt = 0, c = 1, c_q(2) = 0, c_qq(2, 2) = 0
  end type tilt_t

  !> Motion of one tilt at given rates w and angular accelerations alpha: velocity, acceleration
  !> and their derivatives in the angles (q) and rates (w).
  type :: tilt_motion_t
    real(wp) :: jac(3, 2), vel(3), acc(3), dvel_dq(3, 2), dacc_dq(3, 2), djac(3, 2, 2)
  end type tilt_motion_t

  !> State indices of the angles: pendulum (theta_x, theta_y), rods (phi_x, phi_y); their rates
  !> follow each angle.
  integer, parameter :: pendulum_index(2) = [1, 5], rods_index(2) = [3, 7]

contains

  !> The spatial model from a validated planar model and the second component (azimuth in
  !> [-2 pi, 2 pi], ellipticity in [0, 1]; record_y, if given, a record with the planar one).
  !> The dissipation eq (5) on the pendulum's tilt needs p >= 1: for p = 0 the radial direction,
  !> and so the force, is undefined at the vertical.
  pure subroutine spatial_model(planar, azimuth, ellipticity, model, status, message, record_y)
    type(model_t), intent(in) :: planar
    real(wp), intent(in) :: azimuth, ellipticity
    type(spatial_model_t), intent(out) :: model
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(excitation_t), intent(in), optional :: record_y
    status = SD_OK
    message = ''
    call check_real('azimuth', azimuth, -2*pi, 2*pi, .false., .false., &
                    'azimuth must lie in [-2 pi, 2 pi] rad', status, message)
    call check_real('ellipticity', ellipticity, 0.0_wp, 1.0_wp, .false., .false., &
                    'ellipticity (minor over major axis) must lie in [0, 1]', status, message)
    if (status /= SD_OK) return
    if (present(record_y)) then
      if (record_y%kind /= EXCITATION_RECORD .or. &
          planar%excitation%kind /= EXCITATION_RECORD) then
        status = SD_BAD_INPUT
        message = 'record_y needs a record in both components'
        return
      end if
      model%record_y = record_y
    end if
    if (planar%p < 1) then
      status = SD_BAD_INPUT
      message = 'p = '//num2str(planar%p)//' is out of range for the spatial model: the '// &
                'dissipation exponent p must be >= 1 (eq 5 acts on the radial motion, '// &
                'whose direction is undefined at the vertical for p = 0)'
      return
    end if
    model%planar = planar
    model%azimuth = azimuth
    model%ellipticity = ellipticity
  end subroutine spatial_model

  !> The ground acceleration (X'', Y'') at tau (see spatial_model_t).
  pure function ground_acceleration(model, tau) result(g)
    type(spatial_model_t), intent(in) :: model
    real(wp), intent(in) :: tau
    real(wp) :: g(2)
    real(wp) :: major, minor
    associate (ex => model%planar%excitation)
      major = base_acceleration(ex, tau)
      if (ex%kind == EXCITATION_RECORD) then
        minor = 0
        if (allocated(model%record_y%samples)) minor = base_acceleration(model%record_y, tau)
      else
        minor = -model%ellipticity*ex%A*ex%rho**2*cos(ex%rho*tau)
      end if
    end associate
    g = [cos(model%azimuth)*major - sin(model%azimuth)*minor, &
         sin(model%azimuth)*major + cos(model%azimuth)*minor]
  end function ground_acceleration

  !> d(X'', Y'')/dlambda at fixed tau, lambda = rho (PARAMETER_RHO) or A (PARAMETER_A) of the
  !> harmonic excitation (0 for a record).
  pure function ground_sensitivity(model, varied, tau) result(dg)
    type(spatial_model_t), intent(in) :: model
    integer, intent(in) :: varied
    real(wp), intent(in) :: tau
    real(wp) :: dg(2)
    real(wp) :: major, minor
    associate (ex => model%planar%excitation)
      major = acceleration_sensitivity(ex, varied, tau)
      minor = 0
      if (ex%kind == EXCITATION_HARMONIC) then
        if (varied == PARAMETER_A) then
          minor = -model%ellipticity*ex%rho**2*cos(ex%rho*tau)
        else if (varied == PARAMETER_RHO) then
          minor = -model%ellipticity*ex%A*(2*ex%rho*cos(ex%rho*tau) &
                                           - ex%rho**2*tau*sin(ex%rho*tau))
        end if
      end if
    end associate
    dg = [cos(model%azimuth)*major - sin(model%azimuth)*minor, &
          sin(model%azimuth)*major + cos(model%azimuth)*minor]
  end function ground_sensitivity

  !> First-order form: dydt = (x1', x1'', x2', x2'', y1', y1'', y2', y2'').
  pure subroutine spatial_equations(model, tau, y, dydt)
    type(spatial_model_t), intent(in) :: model
    real(wp), intent(in) :: tau, y(8)
    real(wp), intent(out) :: dydt(8)
    real(wp) :: xdd(4)
    call spatial_accelerations(model, tau, y, xdd)
    dydt(1:7:2) = y(2:8:2)
    dydt(2:8:2) = xdd
  end subroutine spatial_equations

  !> The accelerations (x1'', x2'', y1'', y2'') from M Q'' = F (eq S7 of docs/model.md).
  pure subroutine spatial_accelerations(model, tau, y, xdd)
    type(spatial_model_t), intent(in) :: model
    real(wp), intent(in) :: tau, y(8)
    real(wp), intent(out) :: xdd(4)
    real(wp) :: mass(4, 4), residual(4), dres(4, 8), rhs(4, 1)
    call residual_terms(model, tau, y, [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], .false., mass, &
                        residual, dres)
    rhs(:, 1) = -residual
    call solve_small(mass, rhs)
    xdd = rhs(:, 1)/model%planar%theta0
  end subroutine spatial_accelerations

  !> The inertia matrix M of eq S7 (rows: the pendulum's equations divided by mu1 s1^2, the
  !> rods' by M L^2 omega^2; unknowns x1'', x2'', y1'', y2''), as eq (13) in the plane.
  pure subroutine spatial_mass_matrix(model, y, mass)
    type(spatial_model_t), intent(in) :: model
    real(wp), intent(in) :: y(8)
    real(wp), intent(out) :: mass(4, 4)
    real(wp) :: residual(4), dres(4, 8)
    call residual_terms(model, 0.0_wp, y, [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], .false., mass, &
                        residual, dres)
  end subroutine spatial_mass_matrix

  !> Analytic Jacobian d(dydt)/dy: with E(q, q', q'') = M q'' - F = 0,
  !> dq''/dz = -M^-1 dE/dz at the solved q'' (angles in units of theta0 cancel).
  pure subroutine spatial_jacobian(model, tau, y, jac)
    type(spatial_model_t), intent(in) :: model
    real(wp), intent(in) :: tau, y(8)
    real(wp), intent(out) :: jac(8, 8)
    real(wp) :: mass(4, 4), residual(4), dres(4, 8), xdd(4), rhs(4, 8)
    integer :: k
    call spatial_accelerations(model, tau, y, xdd)
    call residual_terms(model, tau, y, xdd*model%planar%theta0, .true., mass, residual, dres)
    rhs = -dres
    call solve_small(mass, rhs)
    jac = 0
    do k = 1, 4
      jac(2*k - 1, 2*k) = 1
      jac(2*k, :) = rhs(k, :)
    end do
  end subroutine spatial_jacobian

  !> d(dydt)/dX'' and d(dydt)/dY'' (columns 1, 2): the equations are affine in the base
  !> acceleration G = (X'', Y''), whose coefficient in E is J_n^T/s1 (pendulum rows) and J_t^T
  !> (rods rows); parameter sensitivities follow as in sloshdyn_motion's excitation_direction.
  pure subroutine spatial_excitation_direction(model, y, e)
    type(spatial_model_t), intent(in) :: model
    real(wp), intent(in) :: y(8)
    real(wp), intent(out) :: e(8, 2)
    type(tilt_t) :: n, t
    real(wp) :: mass(4, 4), rhs(4, 2)
    integer :: i
    associate (t0 => model%planar%theta0, s1 => model%planar%s1)
      n = tilt(t0*y(pendulum_index(1)), t0*y(pendulum_index(2)), -1.0_wp)
      t = tilt(t0*y(rods_index(1)), t0*y(rods_index(2)), 1.0_wp)
      do i = 1, 2
        rhs(:, i) = -[n%du(i, 1, 0)/s1, t%du(i, 1, 0), n%du(i, 0, 1)/s1, t%du(i, 0, 1)]
      end do
      call spatial_mass_matrix(model, y, mass)
      call solve_small(mass, rhs)
      e = 0
      e(2:8:2, :) = rhs/t0
    end associate
  end subroutine spatial_excitation_direction

  !> The horizontal direction of the pendulum n_h = sin(Theta) (cos, sin of its azimuth), and
  !> the horizontal accelerations of the rod tops (tank) and of the sloshing mass, ground
  !> included (unit L omega^2): a_tank = G + (J_t phi'' + H_t), a_mass = a_tank + s1 (J_n
  !> theta'' + H_n), horizontal parts.
  pure subroutine spatial_kinematics(model, tau, y, n_h, a_tank, a_mass)
    type(spatial_model_t), intent(in) :: model
    real(wp), intent(in) :: tau, y(8)
    real(wp), intent(out) :: n_h(2), a_tank(2), a_mass(2)
    type(tilt_t) :: n, t
    type(tilt_motion_t) :: mn, mt
    real(wp) :: xdd(4)
    call spatial_accelerations(model, tau, y, xdd)
    associate (t0 => model%planar%theta0)
      n = tilt(t0*y(pendulum_index(1)), t0*y(pendulum_index(2)), -1.0_wp)
      t = tilt(t0*y(rods_index(1)), t0*y(rods_index(2)), 1.0_wp)
      mn = tilt_motion(n, t0*y(pendulum_index + 1), t0*xdd([1, 3]))
      mt = tilt_motion(t, t0*y(rods_index + 1), t0*xdd([2, 4]))
    end associate
    n_h = n%du(1:2, 0, 0)
    a_tank = ground_acceleration(model, tau) + mt%acc(1:2)
    a_mass = a_tank + model%planar%s1*mn%acc(1:2)
  end subroutine spatial_kinematics

  !> The pendulum's tilt from the vertical Theta over theta0 (cos Theta = cos(theta0 x1)
  !> cos(theta0 y1); the impact potential eq (3) acts on it, the wall is at 1) and the azimuth
  !> [rad, from x] towards which it tilts, atan2(n_y, n_x) of its horizontal direction n_h (0 at
  !> the vertical). In the plane (y1 = 0) they are |x1| and 0 or pi.
  pure function pendulum_tilt(model, y) result(r)
    type(spatial_model_t), intent(in) :: model
    real(wp), intent(in) :: y(8)
    real(wp) :: r(2)
    type(tilt_t) :: n
    associate (t0 => model%planar%theta0)
      n = tilt(t0*y(pendulum_index(1)), t0*y(pendulum_index(2)), -1.0_wp)
      r = [n%tilt/t0, atan2(n%du(2, 0, 0), n%du(1, 0, 0))]
    end associate
  end function pendulum_tilt

  !> Energy T + V (eq S2-S3, unit M L^2 omega^2) and angular momentum about the vertical
  !> (unit M L^2 omega), relative to the ground: both constant without forcing and damping.
  pure subroutine spatial_invariants(model, y, energy, angular_momentum)
    type(spatial_model_t), intent(in) :: model
    real(wp), intent(in) :: y(8)
    real(wp), intent(out) :: energy, angular_momentum
    type(tilt_t) :: n, t
    real(wp) :: vn(3), vt(3), rb(3), vb(3)
    associate (p => model%planar, t0 => model%planar%theta0)
      n = tilt(t0*y(pendulum_index(1)), t0*y(pendulum_index(2)), -1.0_wp)
      t = tilt(t0*y(rods_index(1)), t0*y(rods_index(2)), 1.0_wp)
      vn = t0*(n%du(:, 1, 0)*y(pendulum_index(1) + 1) + n%du(:, 0, 1)*y(pendulum_index(2) + 1))
      vt = t0*(t%du(:, 1, 0)*y(rods_index(1) + 1) + t%du(:, 0, 1)*y(rods_index(2) + 1))
      rb = t%du(:, 0, 0) + p%s1*n%du(:, 0, 0)
      vb = vt + p%s1*vn
      energy = (1 - p%mu1)*dot_product(vt, vt)/2 + p%mu1*dot_product(vb, vb)/2 &
               + p%kappa*t%tilt**2/2 + p%s1*(t%du(3, 0, 0) + p%mu1*p%s1*n%du(3, 0, 0)) &
               + p%mu1*p%s1**2*p%beta*t0/(2*p%n)*(n%tilt/t0)**(2*p%n)
      angular_momentum = (1 - p%mu1)*(t%du(1, 0, 0)*vt(2) - t%du(2, 0, 0)*vt(1)) &
                         + p%mu1*(rb(1)*vb(2) - rb(2)*vb(1))
    end associate
  end subroutine spatial_invariants

  ! ---- internals ------------------------------------------------------------------------------

  !> The residual E = M q'' - F of the Lagrange equations (eq S6) at given angular accelerations
  !> qdd (rad, in state order theta_x, phi_x, theta_y, phi_y), the inertia matrix in the state's
  !> angles, and with `derivatives` dE/dq and dE/dq' at fixed qdd (columns in state order: the
  !> column of an angle's x holds d/dq, of its rate d/dq'; -M^-1 dE/dq = dq''/dq = dx''/dx).
  !>   pendulum rows:  J_n^T [ (a_t + G)/s1 + a_n + 2 zeta v_n ] + dU/dq + D_q
  !>   rods rows:      J_t^T [ a_t + G + mu1 s1 a_n + gamma v_t ] + kappa Phi dPhi/dq
  !> with G = (X'', Y'', s1) (base acceleration and gravity) and a, v the tilts' accelerations
  !> and velocities.
  pure subroutine residual_terms(model, tau, y, qdd, derivatives, mass, residual, dres)
    type(spatial_model_t), intent(in) :: model
    real(wp), intent(in) :: tau, y(8), qdd(4)
    logical, intent(in) :: derivatives
    real(wp), intent(out) :: mass(4, 4), residual(4), dres(4, 8)
    type(tilt_t) :: n, t
    type(tilt_motion_t) :: mn, mt
    real(wp) :: g(3), wn(3), wt(3), wwn(2), wwt(2), force(2), dforce_dq(2, 2), dforce_dw(2, 2), &
                spring(2), dspring(2, 2)
    integer :: i, k, rn(2), rt(2)

    associate (p => model%planar, t0 => model%planar%theta0)
      rn = pendulum_index
      rt = rods_index
      ! equation rows and unknown columns: (x1, x2, y1, y2) = pendulum x, rods x, pendulum y, rods y
      n = tilt(t0*y(rn(1)), t0*y(rn(2)), -1.0_wp)
      t = tilt(t0*y(rt(1)), t0*y(rt(2)), 1.0_wp)
      wwn = t0*y(rn + 1)
      wwt = t0*y(rt + 1)
      mn = tilt_motion(n, wwn, qdd([1, 3]))
      mt = tilt_motion(t, wwt, qdd([2, 4]))
      g = [ground_acceleration(model, tau), p%s1]

      wn = (mt%acc + g)/p%s1 + mn%acc + 2*p%zeta*mn%vel
      wt = mt%acc + g + p%mu1*p%s1*mn%acc + p%gamma*mt%vel
      call impact_and_dissipation(p, n, wwn, force, dforce_dq, dforce_dw)
      call rods_spring(t, spring, dspring)
      do i = 1, 2
        residual(2*i - 1) = dot_product(mn%jac(:, i), wn) + force(i)
        residual(2*i) = dot_product(mt%jac(:, i), wt) + p%kappa*spring(i)
        do k = 1, 2
          mass(2*i - 1, 2*k - 1) = dot_product(mn%jac(:, i), mn%jac(:, k))
          mass(2*i - 1, 2*k) = dot_product(mn%jac(:, i), mt%jac(:, k))/p%s1
          mass(2*i, 2*k - 1) = p%mu1*p%s1*dot_product(mt%jac(:, i), mn%jac(:, k))
          mass(2*i, 2*k) = dot_product(mt%jac(:, i), mt%jac(:, k))
        end do
      end do

      dres = 0
      if (.not. derivatives) return
      ! columns: state index of the angle (rn(k), rt(k)) and of its rate (+1); q = t0 x
      do i = 1, 2
        do k = 1, 2
          ! pendulum row i
          dres(2*i - 1, rn(k)) = dot_product(mn%djac(:, i, k), wn) &
            + dot_product(mn%jac(:, i), mn%dacc_dq(:, k) + 2*p%zeta*mn%dvel_dq(:, k)) &
            + dforce_dq(i, k)
          dres(2*i - 1, rn(k) + 1) = dot_product(mn%jac(:, i), 2*mn%dvel_dq(:, k) &
            + 2*p%zeta*mn%jac(:, k)) + dforce_dw(i, k)
          dres(2*i - 1, rt(k)) = dot_product(mn%jac(:, i), mt%dacc_dq(:, k))/p%s1
          dres(2*i - 1, rt(k) + 1) = dot_product(mn%jac(:, i), 2*mt%dvel_dq(:, k))/p%s1
          ! rods row i
          dres(2*i, rt(k)) = dot_product(mt%djac(:, i, k), wt) &
            + dot_product(mt%jac(:, i), mt%dacc_dq(:, k) + p%gamma*mt%dvel_dq(:, k)) &
            + p%kappa*dspring(i, k)
          dres(2*i, rt(k) + 1) = dot_product(mt%jac(:, i), 2*mt%dvel_dq(:, k) &
            + p%gamma*mt%jac(:, k))
          dres(2*i, rn(k)) = p%mu1*p%s1*dot_product(mt%jac(:, i), mn%dacc_dq(:, k))
          dres(2*i, rn(k) + 1) = p%mu1*p%s1*dot_product(mt%jac(:, i), 2*mn%dvel_dq(:, k))
        end do
      end do
    end associate
  end subroutine residual_terms

  !> The tilt (a, b) with sigma the sign of the vertical component at rest.
  pure function tilt(a, b, sigma) result(s)
    real(wp), intent(in) :: a, b, sigma
    type(tilt_t) :: s
    real(wp) :: da(0:3), ca(0:3), db(0:3), cb(0:3)
    integer :: i, j
    ! derivatives of sin and cos: sin, cos, -sin, -cos and cos, -sin, -cos, sin
    da = [sin(a), cos(a), -sin(a), -cos(a)]
    ca = [cos(a), -sin(a), -cos(a), sin(a)]
    db = [sin(b), cos(b), -sin(b), -cos(b)]
    cb = [cos(b), -sin(b), -cos(b), sin(b)]
    do j = 0, 3
      do i = 0, 3 - j
        s%du(1, i, j) = da(i)*cb(j)
        s%du(2, i, j) = merge(db(j), 0.0_wp, i == 0)
        s%du(3, i, j) = sigma*ca(i)*cb(j)
      end do
    end do
    s%c = ca(0)*cb(0)
    s%c_q = [ca(1)*cb(0), ca(0)*cb(1)]
    s%c_qq = reshape([ca(2)*cb(0), ca(1)*cb(1), ca(1)*cb(1), ca(0)*cb(2)], [2, 2])
    ! sin(tilt) from the horizontal components: no cancellation near the vertical
    s%sin_tilt = hypot(s%du(1, 0, 0), s%du(2, 0, 0))
    s%tilt = atan2(s%sin_tilt, s%c)
  end function tilt

  !> d^(i+j) u/da^i db^j for the directions listed in k (1 = a, 2 = b).
  pure function partial(s, k) result(d)
    type(tilt_t), intent(in) :: s
    integer, intent(in) :: k(:)
    real(wp) :: d(3)
    d = s%du(:, count(k == 1), count(k == 2))
  end function partial

  !> Velocity u_q w, acceleration u_q alpha + u_qq w w, and their derivatives in q (the
  !> derivative in w of the acceleration is 2 dvel_dq).
  pure function tilt_motion(s, w, alpha) result(m)
    type(tilt_t), intent(in) :: s
    real(wp), intent(in) :: w(2), alpha(2)
    type(tilt_motion_t) :: m
    integer :: i, k, l
    m%vel = 0; m%acc = 0; m%dvel_dq = 0; m%dacc_dq = 0
    do k = 1, 2
      m%jac(:, k) = partial(s, [k])
      m%vel = m%vel + m%jac(:, k)*w(k)
      m%acc = m%acc + m%jac(:, k)*alpha(k)
      do l = 1, 2
        m%acc = m%acc + partial(s, [k, l])*w(k)*w(l)
        m%djac(:, k, l) = partial(s, [k, l])
      end do
    end do
    do i = 1, 2
      do k = 1, 2
        m%dvel_dq(:, i) = m%dvel_dq(:, i) + partial(s, [k, i])*w(k)
        m%dacc_dq(:, i) = m%dacc_dq(:, i) + partial(s, [k, i])*alpha(k)
        do l = 1, 2
          m%dacc_dq(:, i) = m%dacc_dq(:, i) + partial(s, [k, l, i])*w(k)*w(l)
        end do
      end do
    end do
  end function tilt_motion

  !> Tilt/sin(tilt) (1 at the vertical).
  elemental real(wp) function tilt_ratio(angle, sin_angle) result(r)
    real(wp), intent(in) :: angle, sin_angle
    r = 1
    if (sin_angle /= 0) r = angle/sin_angle
  end function tilt_ratio

  !> (sin T - T cos T)/sin^3 T = -d(T/sin T)/d(cos T); its Taylor series below 0.1, where the
  !> difference cancels (series by sympy; the first omitted term is below 1e-17 there).
  elemental real(wp) function ratio_slope(angle, sin_angle) result(s)
    real(wp), intent(in) :: angle, sin_angle
    real(wp), parameter :: coef(0:7) = [1.0_wp/3, 2.0_wp/15, 2.0_wp/63, 4.0_wp/675, &
                                        2.0_wp/2079, 2764.0_wp/19348875, 4.0_wp/200475, &
                                        28936.0_wp/10854718875.0_wp]
    real(wp) :: t2
    integer :: i
    if (angle < 0.1_wp) then
      t2 = angle**2
      s = coef(7)
      do i = 6, 0, -1
        s = s*t2 + coef(i)
      end do
    else
      s = (sin_angle - angle*cos(angle))/sin_angle**3
    end if
  end function ratio_slope

  !> The rods' spring: d(Phi^2/2)/dq = -r c_q and its Hessian -r c_qq + s c_q c_q^T,
  !> r = Phi/sin Phi,
  !> s = ratio_slope (eq S4).
  pure subroutine rods_spring(t, spring, dspring)
    type(tilt_t), intent(in) :: t
    real(wp), intent(out) :: spring(2), dspring(2, 2)
    real(wp) :: r, s
    integer :: k
    r = tilt_ratio(t%tilt, t%sin_tilt)
    s = ratio_slope(t%tilt, t%sin_tilt)
    spring = -r*t%c_q
    do k = 1, 2
      dspring(:, k) = -r*t%c_qq(:, k) + s*t%c_q*t%c_q(k)
    end do
  end subroutine rods_spring

  !> The impact force of eq (4) and the dissipation of eq (5) on the pendulum's tilt Theta,
  !> divided by mu1 s1^2 (eq S5): with r = Theta/sin Theta, Theta_q = -r c_q/Theta,
  !>   dU/dq = beta (Theta/theta0)^(2n-1) Theta_q = -beta/theta0 (Theta/theta0)^(2n-2) r c_q,
  !>   D_q   = delta (Theta/theta0)^(2p) Theta' Theta_q
  !>         = delta/theta0^2 (Theta/theta0)^(2p-2) r^2 (c_q.w) c_q,
  !> and their derivatives in q and in the rates w (dr/dc = -s, dTheta^m/dc = -m Theta^(m-2) r).
  pure subroutine impact_and_dissipation(p, n, w, force, dforce_dq, dforce_dw)
    type(model_t), intent(in) :: p
    type(tilt_t), intent(in) :: n
    real(wp), intent(in) :: w(2)
    real(wp), intent(out) :: force(2), dforce_dq(2, 2), dforce_dw(2, 2)
    real(wp) :: r, s, x, fi, dfi_dc, fd, dfd_dc, cw, dcw(2)
    integer :: k
    r = tilt_ratio(n%tilt, n%sin_tilt)
    s = ratio_slope(n%tilt, n%sin_tilt)
    x = n%tilt/p%theta0
    ! impact: force = -fi c_q, fi = beta/theta0 x^(2n-2) r
    fi = p%beta/p%theta0*x**(2*p%n - 2)*r
    dfi_dc = -p%beta/p%theta0*x**(2*p%n - 2)*s
    if (p%n > 1) dfi_dc = dfi_dc - p%beta/p%theta0**3*(2*p%n - 2)*x**(2*p%n - 4)*r**2
    ! dissipation: force = fd (c_q.w) c_q, fd = delta/theta0^2 x^(2p-2) r^2 (p >= 1)
    fd = p%delta/p%theta0**2*x**(2*p%p - 2)*r**2
    dfd_dc = -2*p%delta/p%theta0**2*x**(2*p%p - 2)*r*s
    if (p%p > 1) dfd_dc = dfd_dc - p%delta/p%theta0**4*(2*p%p - 2)*x**(2*p%p - 4)*r**3
    cw = dot_product(n%c_q, w)
    dcw = matmul(w, n%c_qq)
    force = -fi*n%c_q + fd*cw*n%c_q
    do k = 1, 2
      dforce_dq(:, k) = -dfi_dc*n%c_q(k)*n%c_q - fi*n%c_qq(:, k) &
                        + dfd_dc*n%c_q(k)*cw*n%c_q + fd*dcw(k)*n%c_q + fd*cw*n%c_qq(:, k)
      dforce_dw(:, k) = fd*n%c_q(k)*n%c_q
    end do
  end subroutine impact_and_dissipation

  !> Solves a x = b in place (b becomes x) by Gaussian elimination with partial pivoting; a is
  !> the 4 x 4 inertia matrix, nonsingular away from b = +-pi/2.
  pure subroutine solve_small(a, b)
    real(wp), intent(in) :: a(:, :)
    real(wp), intent(inout) :: b(:, :)
    real(wp) :: lu(size(a, 1), size(a, 2)), row(size(a, 2)), rhs(size(b, 2)), factor
    integer :: i, j, pivot, nn
    nn = size(a, 1)
    lu = a
    do j = 1, nn - 1
      pivot = j - 1 + maxloc(abs(lu(j:, j)), 1)
      if (pivot /= j) then
        row = lu(j, :); lu(j, :) = lu(pivot, :); lu(pivot, :) = row
        rhs = b(j, :); b(j, :) = b(pivot, :); b(pivot, :) = rhs
      end if
      do i = j + 1, nn
        if (lu(i, j) == 0) cycle
        factor = lu(i, j)/lu(j, j)
        lu(i, j + 1:) = lu(i, j + 1:) - factor*lu(j, j + 1:)
        b(i, :) = b(i, :) - factor*b(j, :)
      end do
    end do
    do i = nn, 1, -1
      b(i, :) = (b(i, :) - matmul(lu(i, i + 1:), b(i + 1:, :)))/lu(i, i)
    end do
  end subroutine solve_small
end module sloshdyn_spatial
