!> Equations of motion: M Q'' = F holds, the analytic Jacobian matches central differences, and at
!> rest it is the paper's eq (19).
program test_motion
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_model, only: model_t, model_from_arrays
  use sloshdyn_motion, only: inertia_matrix, forcing_vector, equations_of_motion, motion_jacobian, &
                             excitation_direction
  use sloshdyn_excitation, only: base_acceleration
  use checks, only: check_close, check_true, finish
  implicit none
  type(model_t) :: model
  integer :: status, i, j, trial
  character(len=message_len) :: message
  real(wp) :: y(4), dydt(4), mass(2, 2), force(2), jac(4, 4), fd(4, 4), yp(4), ym(4), fp(4), &
              fm(4), step, worst, tau
  real(wp), parameter :: states(4, 3) = reshape([0.3_wp, -0.7_wp, 0.2_wp, 0.4_wp, &
                                                 1.1_wp, 0.5_wp, -0.3_wp, -0.9_wp, &
                                                 -0.8_wp, 1.3_wp, 0.05_wp, 0.2_wp], [4, 3])

  ! a forced case with impacts (n = 6), dissipation (p = 2) and rod damping
  call model_from_arrays([1.5_wp, 0.5_wp, 1.8_wp, pi/4, 0.7_wp, 0.01_wp, 0.05_wp, 0.3_wp, 0.51_wp, 0.0_wp], &
                         [6, 2], model, status, message)
  call check_true('model valid', status == 0)
  tau = 2.3_wp
  do trial = 1, 3
    y = states(:, trial)
    call inertia_matrix(model, y, mass)
    call forcing_vector(model, tau, y, force)
    call equations_of_motion(model, tau, y, dydt)
    call check_close('eq 12: M Q'''' = F, row 1', mass(1, 1)*dydt(2) + mass(1, 2)*dydt(4), force(1), &
                     1.0e-13_wp, 1.0e-13_wp)
    call check_close('eq 12: M Q'''' = F, row 2', mass(2, 1)*dydt(2) + mass(2, 2)*dydt(4), force(2), &
                     1.0e-13_wp, 1.0e-13_wp)
    call motion_jacobian(model, tau, y, jac)
    worst = 0
    do j = 1, 4
      step = 1.0e-6_wp*max(1.0_wp, abs(y(j)))
      yp = y; yp(j) = y(j) + step
      ym = y; ym(j) = y(j) - step
      call equations_of_motion(model, tau, yp, fp)
      call equations_of_motion(model, tau, ym, fm)
      fd(:, j) = (fp - fm)/(2*step)
    end do
    do j = 1, 4
      do i = 1, 4
        worst = max(worst, abs(jac(i, j) - fd(i, j))/max(1.0_wp, abs(fd(i, j))))
      end do
    end do
    call check_close('analytic Jacobian = central differences', worst, 0.0_wp, 0.0_wp, 1.0e-7_wp)
  end do

  ! the equations are affine in X'': dydt(A) - dydt(0) = X'' e(y)
  block
    type(model_t) :: unforced
    real(wp) :: e(4), f0(4)
    unforced = model
    unforced%excitation%A = 0
    y = states(:, 2)
    call equations_of_motion(model, tau, y, dydt)
    call equations_of_motion(unforced, tau, y, f0)
    call excitation_direction(model, y, e)
    call check_close('excitation direction: affine in X''''', &
                     maxval(abs(dydt - f0 - base_acceleration(model%excitation, tau)*e)), 0.0_wp, 0.0_wp, 1.0e-14_wp)
  end block

  ! eq (19): the Jacobian at the trivial equilibrium (p >= 1, so delta does not enter)
  call motion_jacobian(model, 0.0_wp, [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], jac)
  associate (mu1 => model%mu1, s1 => model%s1, kappa => model%kappa, gamma => model%gamma)
    call check_close('eq 19: J21', jac(2, 1), -1/(1 - mu1), 1.0e-14_wp)
    call check_close('eq 19: J23', jac(2, 3), (kappa - s1)/(s1*(1 - mu1)), 1.0e-14_wp)
    call check_close('eq 19: J24', jac(2, 4), gamma/(s1*(1 - mu1)), 1.0e-14_wp)
    call check_close('eq 19: J41', jac(4, 1), mu1*s1/(1 - mu1), 1.0e-14_wp)
    call check_close('eq 19: J43', jac(4, 3), -(kappa - s1)/(1 - mu1), 1.0e-14_wp)
    call check_close('eq 19: J44', jac(4, 4), -gamma/(1 - mu1), 1.0e-14_wp)
    call check_close('eq 19: J22 = 0', jac(2, 2), 0.0_wp, 0.0_wp, 1.0e-15_wp)
  end associate
  call finish()
end program test_motion
