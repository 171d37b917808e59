!> The spatial model (sloshdyn_spatial, docs/model.md "Spatial model and swirl"):
!> - exact reduction to the planar equations eq (10) (sloshdyn_motion) in the plane, and the plane
!>   invariant (y1'' = y2'' = 0);
!> - M Q'' = F with the inertia matrix reducing to eq (13);
!> - the analytic Jacobian against central differences, at states near and far from the vertical;
!> - without forcing and damping: energy and angular momentum about the vertical conserved to
!>   the integrator's tolerance along a swirling, impacting orbit (independent invariants);
!> - rotating the forcing's azimuth rotates the motion (the model is isotropic);
!> - at rest the out-of-plane Floquet multipliers (sloshdyn_swirl) are the in-plane ones.
program test_spatial
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_model, only: model_t, model_from_arrays
  use sloshdyn_motion, only: equations_of_motion, motion_jacobian, inertia_matrix
  use sloshdyn_spatial, only: spatial_model_t, spatial_model, spatial_equations, &
                              spatial_jacobian, spatial_invariants, spatial_mass_matrix, &
                              spatial_excitation_direction, ground_acceleration, ground_sensitivity
  use sloshdyn_spatial_system, only: spatial_tank_system
  use sloshdyn_ode, only: ode_options, ode_stats
  use sloshdyn_integrator, only: integrate, METHOD_DOP853
  use sloshdyn_excitation, only: PARAMETER_RHO, PARAMETER_A
  use sloshdyn_system, only: tank_system
  use sloshdyn_shooting, only: monodromy_matrix
  use sloshdyn_lapack, only: eigenvalues
  use sloshdyn_swirl, only: out_of_plane_multipliers
  use sloshdyn_tables, only: table_size, SWIRL_BRANCH_ROWS, SWIRL_EDGE_ROWS, &
                             SWIRLING_BRANCH_ROWS, SWIRLING_SPECIAL_ROWS, SWIRL_BOUNDARY_ROWS
  use checks, only: check_close, check_true, finish
  implicit none
  type(model_t) :: planar
  type(spatial_model_t) :: model
  integer :: status, trial, i, j
  character(len=message_len) :: message
  real(wp) :: y(8), dydt(8), jac(8, 8), fd(8, 8), yp(8), ym(8), fp(8), fm(8), step, worst, tau, &
              yq(4), dq(4), jq(4, 4), mass(4, 4), mq(2, 2)

  ! a forced case with impacts (n = 6), dissipation (p = 2), rod and linear sloshing damping
  call model_from_arrays([1.5_wp, 0.5_wp, 1.8_wp, pi/4, 0.7_wp, 0.01_wp, 0.05_wp, 0.3_wp, &
                          0.51_wp, 0.02_wp], [6, 2], planar, status, message)
  call check_true('planar model valid', status == 0)
  call spatial_model(planar, 0.0_wp, 0.0_wp, model, status, message)
  call check_true('spatial model valid', status == 0)
  tau = 2.3_wp

  ! planar states: the spatial equations are eq (10) to rounding, and y stays 0
  do trial = 1, 20
    call random_number(yq)
    yq = 2.4_wp*yq - 1.2_wp
    y = 0
    y(1:4) = yq
    call spatial_equations(model, tau, y, dydt)
    call equations_of_motion(planar, tau, yq, dq)
    worst = maxval(abs(dydt(1:4) - dq)/(1 + abs(dq)))
    call check_close('planar reduction of the right-hand side', worst, 0.0_wp, 0.0_wp, 1.0e-14_wp)
    call check_true('the plane is invariant: y1'''' = y2'''' = 0 exactly', all(dydt(5:8) == 0))
    call spatial_jacobian(model, tau, y, jac)
    call motion_jacobian(planar, tau, yq, jq)
    worst = maxval(abs(jac(1:4, 1:4) - jq)/(1 + abs(jq)))
    call check_close('planar reduction of the Jacobian', worst, 0.0_wp, 0.0_wp, 1.0e-13_wp)
    call check_true('in-plane and out-of-plane blocks decouple on the plane', &
                    all(jac(1:4, 5:8) == 0) .and. all(jac(5:8, 1:4) == 0))
    call spatial_mass_matrix(model, y, mass)
    call inertia_matrix(planar, yq, mq)
    call check_close('inertia matrix reduces to eq (13)', &
                     maxval(abs(mass([1, 2], [1, 2]) - mq)), 0.0_wp, 0.0_wp, 1.0e-15_wp)
  end do

  ! random spatial states, some near the vertical (where tilt/sin(tilt) is switched to its
  ! series): the analytic Jacobian against central differences
  model%azimuth = 0.3_wp
  model%ellipticity = 0.4_wp
  do trial = 1, 30
    call random_number(y)
    y = 2*y - 1
    if (trial > 20) y([1, 3, 5, 7]) = 1.0e-3_wp*y([1, 3, 5, 7])
    if (trial == 30) y([1, 3, 5, 7]) = 0
    call spatial_jacobian(model, tau, y, jac)
    do j = 1, 8
      step = 1.0e-6_wp
      yp = y; yp(j) = y(j) + step
      ym = y; ym(j) = y(j) - step
      call spatial_equations(model, tau, yp, fp)
      call spatial_equations(model, tau, ym, fm)
      fd(:, j) = (fp - fm)/(2*step)
    end do
    worst = 0
    do j = 1, 8
      do i = 1, 8
        worst = max(worst, abs(jac(i, j) - fd(i, j))/max(1.0_wp, abs(fd(i, j))))
      end do
    end do
    call check_close('analytic Jacobian = central differences', worst, 0.0_wp, 0.0_wp, 1.0e-7_wp)
  end do

  ! affine in (X'', Y''): dydt - dydt(no ground motion) = X'' e1 + Y'' e2
  block
    type(spatial_model_t) :: still
    real(wp) :: e(8, 2), f0(8)
    still = model
    still%planar%excitation%A = 0

    call random_number(y)
    call spatial_equations(model, tau, y, dydt)
    call spatial_equations(still, tau, y, f0)
    call spatial_excitation_direction(model, y, e)
    call check_close('excitation directions: affine in X'''' and Y''''', maxval(abs(dydt - f0 &
                     - matmul(e, ground_acceleration(model, tau)))), 0.0_wp, 0.0_wp, &
                     1.0e-14_wp)
  end block

  ! the sensitivities of (X'', Y'') in rho and A against central differences (elliptical motion)
  block
    type(spatial_model_t) :: plus, minus
    real(wp) :: h
    h = 1.0e-6_wp
    plus = model; minus = model
    plus%planar%excitation%rho = model%planar%excitation%rho + h
    minus%planar%excitation%rho = model%planar%excitation%rho - h
    call check_close('d(X'''', Y'''')/drho', &
                     maxval(abs(ground_sensitivity(model, PARAMETER_RHO, tau) &
                     - (ground_acceleration(plus, tau) - ground_acceleration(minus, tau))/(2*h))), &
                     0.0_wp, 0.0_wp, 1.0e-8_wp)
    plus = model; minus = model
    plus%planar%excitation%A = model%planar%excitation%A + h
    minus%planar%excitation%A = model%planar%excitation%A - h
    call check_close('d(X'''', Y'''')/dA', maxval(abs(ground_sensitivity(model, PARAMETER_A, tau) &
                     - (ground_acceleration(plus, tau) - ground_acceleration(minus, tau))/(2*h))), &
                     0.0_wp, 0.0_wp, 1.0e-8_wp)
  end block

  ! isotropy: an elliptical ground motion turned by an azimuth turns the motion of the sloshing
  ! mass from rest by the same angle (the equations are written in non-rotating angles, so this
  ! checks them against a symmetry they do not show term by term)
  block
    type(spatial_tank_system) :: sys
    type(ode_options) :: options
    type(ode_stats) :: stats
    real(wp) :: t_out(40), y0(8), y_a(8, 40), y_b(8, 40), alpha, p_a(2), p_b(2), worst_p
    integer :: k
    alpha = 1.1_wp
    sys%model = model
    sys%model%azimuth = 0
    sys%model%ellipticity = 0.5_wp
    y0 = 0
    t_out = [(0.5_wp*k, k = 1, 40)]
    options%rtol = 1.0e-11_wp
    options%atol = 1.0e-11_wp
    call integrate(METHOD_DOP853, sys, 0.0_wp, y0, t_out, y_a, options, stats, status, message)
    sys%model%azimuth = alpha
    call integrate(METHOD_DOP853, sys, 0.0_wp, y0, t_out, y_b, options, stats, status, message)
    worst_p = 0
    do k = 1, 40
      p_a = mass_position(sys%model%planar, y_a(:, k))
      p_b = mass_position(sys%model%planar, y_b(:, k))
      worst_p = max(worst_p, maxval(abs(p_b - [cos(alpha)*p_a(1) - sin(alpha)*p_a(2), &
                                               sin(alpha)*p_a(1) + cos(alpha)*p_a(2)])))
    end do
    call check_true('the elliptical run moves in both directions', &
                    maxval(abs(y_a(5, :))) > 0.1_wp*maxval(abs(y_a(1, :))))
    call check_close('azimuth turns the sloshing mass''s path', worst_p, 0.0_wp, 0.0_wp, 1.0e-8_wp)
  end block

  ! out-of-plane multipliers at rest (no forcing) are the planar ones: the linearisation at
  ! rest is the same in every vertical plane (isotropy); the planar monodromy comes from the
  ! planar equations alone (sloshdyn_system)
  block
    type(tank_system) :: still
    type(ode_options) :: options
    real(wp) :: y_end(4), monodromy(4, 4), re(4), im(4), re_p(4), im_p(4)
    still%model = planar
    still%model%excitation%A = 0
    options%rtol = 1.0e-11_wp
    options%atol = 1.0e-12_wp
    call out_of_plane_multipliers(still%model, [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], 1, options, &
                                  METHOD_DOP853, re, im, status, message)
    call check_true('out-of-plane multipliers computed', status == 0)
    call monodromy_matrix(still, [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], 1, options, METHOD_DOP853, &
                          y_end, monodromy, status, message)
    call eigenvalues(monodromy, re_p, im_p, status, message)
    call check_close('out-of-plane = in-plane multipliers at rest: sum of moduli', &
                     sum(hypot(re, im)), sum(hypot(re_p, im_p)), 1.0e-9_wp)
    call check_close('out-of-plane = in-plane multipliers at rest: sum of real parts', &
                     sum(re), sum(re_p), 1.0e-9_wp, 1.0e-9_wp)
    call check_true('swirl tables have their documented sizes', &
                    table_size('swirl_branch') == SWIRL_BRANCH_ROWS .and. &
                    table_size('swirl_edges') == SWIRL_EDGE_ROWS .and. &
                    table_size('swirl_boundary') == SWIRL_BOUNDARY_ROWS .and. &
                    table_size('swirling_branch') == SWIRLING_BRANCH_ROWS .and. &
                    table_size('swirling_special_points') == SWIRLING_SPECIAL_ROWS)
  end block

  ! p = 0 is refused, naming p
  block
    type(model_t) :: linear
    type(spatial_model_t) :: refused
    linear = planar
    linear%p = 0
    call spatial_model(linear, 0.0_wp, 0.0_wp, refused, status, message)
    call check_true('p = 0 is refused naming p', status /= 0 .and. index(message, 'p = 0') > 0)
  end block

  ! invariants without forcing and damping, along a swirling orbit that reaches the wall
  block
    type(spatial_tank_system) :: sys
    type(ode_options) :: options
    type(ode_stats) :: stats
    real(wp) :: t_out(50), y_out(8, 50), e0, l0, e, l, e_worst, l_worst
    integer :: k
    sys%model = model
    sys%model%planar%excitation%A = 0
    sys%model%planar%gamma = 0
    sys%model%planar%delta = 0
    sys%model%planar%zeta = 0
    ! tilt 0.9 theta0 in x, a swirling rate in y: the pendulum circles into the wall's potential
    y = [0.9_wp, 0.0_wp, 0.01_wp, 0.0_wp, 0.0_wp, 1.1_wp, 0.0_wp, -0.02_wp]
    t_out = [(0.5_wp*k, k = 1, 50)]
    options%rtol = 1.0e-12_wp
    options%atol = 1.0e-12_wp
    call integrate(METHOD_DOP853, sys, 0.0_wp, y, t_out, y_out, options, stats, status, message)
    call check_true('unforced undamped orbit integrated', status == 0)
    call spatial_invariants(sys%model, y, e0, l0)
    e_worst = 0; l_worst = 0
    do k = 1, 50
      call spatial_invariants(sys%model, y_out(:, k), e, l)
      e_worst = max(e_worst, abs(e - e0))
      l_worst = max(l_worst, abs(l - l0))
    end do
    call check_true('the orbit swirls: L_z is not 0', abs(l0) > 1.0e-3_wp)
    call check_true('the orbit reaches the wall potential: max tilt > 0.95 theta0', &
                    maxval(hypot(y_out(1, :), y_out(5, :))) > 0.95_wp)
    call check_close('energy conserved', e_worst, 0.0_wp, 0.0_wp, 1.0e-9_wp*abs(e0))
    call check_close('angular momentum about the vertical conserved', l_worst, 0.0_wp, 0.0_wp, &
                     1.0e-9_wp*abs(l0))
  end block
  call finish()

contains

  !> Horizontal position of the sloshing mass relative to the base, t + s1 n (unit L).
  pure function mass_position(p, y) result(r)
    type(model_t), intent(in) :: p
    real(wp), intent(in) :: y(8)
    real(wp) :: r(2)
    associate (t0 => p%theta0)
      r = [sin(t0*y(3))*cos(t0*y(7)), sin(t0*y(7))] &
          + p%s1*[sin(t0*y(1))*cos(t0*y(5)), sin(t0*y(5))]
    end associate
  end function mass_position
end program test_spatial
