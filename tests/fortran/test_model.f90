!> Tank pendulum (eq 2-3) against values worked by hand, and the groups of eq (9).
program test_model
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT
  use sloshdyn_model, only: model_t, model_from_arrays, model_from_physical
  use sloshdyn_tank, only: tank_pendulum
  use checks, only: check_close, check_true, finish
  implicit none
  real(wp) :: l, m, d1, m0, d0, mf, s1, mu1, kappa, beta, gamma, delta
  integer :: status
  character(len=message_len) :: message
  type(model_t) :: model

  ! R = 1 m, h = 1 m, water: x = 1.84, e^3.68 = 39.6464, tanh x = 38.6464/40.6464 = 0.950795,
  ! sinh 3.68 = 19.8106; l = 1/(1.84*0.950795) = 0.571604, m = 1000 pi/2.2*0.950795 = 1357.73,
  ! d1 = (1/3.68)/19.8106 = 0.0137169, m0 = 3141.59 - 1357.73 = 1783.86,
  ! d0 = 0 - (0.0137169 + 0.571604)*1357.73/1783.86 = -0.445500
  call tank_pendulum(1.0_wp, 1.0_wp, 1000.0_wp, 0.0_wp, l, m, d1, m0, d0, mf, status, message)
  call check_true('tank 1: status', status == SD_OK)
  call check_close('tank 1: m_F = pi rho R^2 h', mf, 3141.5927_wp, 1.0e-7_wp)
  call check_close('tank 1: l', l, 0.571604_wp, 2.0e-6_wp)
  call check_close('tank 1: m', m, 1357.73_wp, 5.0e-6_wp)
  call check_close('tank 1: d1 (csch)', d1, 0.0137169_wp, 1.0e-5_wp)
  call check_close('tank 1: m0', m0, 1783.86_wp, 5.0e-6_wp)
  call check_close('tank 1: d0', d0, -0.445500_wp, 1.0e-5_wp)
  ! R = 2 m, h = 0.5 m, m_F = 500 kg: x = 0.46, tanh x = 0.430084, sinh 0.92 = 1.055386;
  ! l = 1.086957/0.430084 = 2.52731, m = 909.0909*0.430084 = 390.986, d1 = 0.543478/1.055386
  ! = 0.514957, m0 = 109.014, d0 = 4.58655*(0.25 - 4) - 3.042267*3.586556 = -28.1108
  call tank_pendulum(2.0_wp, 0.5_wp, 0.0_wp, 500.0_wp, l, m, d1, m0, d0, mf, status, message)
  call check_close('tank 2: l', l, 2.52731_wp, 4.0e-6_wp)
  call check_close('tank 2: m', m, 390.986_wp, 4.0e-6_wp)
  call check_close('tank 2: d1', d1, 0.514957_wp, 4.0e-6_wp)
  call check_close('tank 2: m0', m0, 109.014_wp, 1.0e-5_wp)
  call check_close('tank 2: d0', d0, -28.1108_wp, 4.0e-6_wp)
  call tank_pendulum(2.0_wp, 0.5_wp, 1000.0_wp, 500.0_wp, l, m, d1, m0, d0, mf, status, message)
  call check_true('tank: density and mass both given is rejected', status == SD_BAD_INPUT)
  call tank_pendulum(-2.0_wp, 0.5_wp, 1000.0_wp, 0.0_wp, l, m, d1, m0, d0, mf, status, message)
  call check_true('tank: radius < 0 rejected, message names radius (as &tank and Python)', &
                  status == SD_BAD_INPUT .and. index(message, 'radius = -2') == 1)

  ! eq (9) by hand: g = 9.81, l = 0.5, omega^2 = 19.62, L = 2, M = 100, m = 10, k = 7848:
  ! s1 = 0.25, mu1 = 0.1, kappa = 7848/(19.62*4*100) = 1, beta = b/(19.62*10*0.25) = 49.05/49.05
  ! = 1, gamma = c/(4.42945*4*100) with c = 17.7178 -> 0.01, delta = d/(4.42945*10*0.25) with
  ! d = 0.553681 -> 0.05
  call model_from_physical(100.0_wp, 2.0_wp, 7848.0_wp, 17.7178_wp, 49.05_wp, 0.553681_wp, &
                           9.81_wp, 0.5_wp, 0.5_wp, 10.0_wp, s1, mu1, kappa, beta, gamma, delta, &
                           status, message)
  call check_close('eq 9: s1', s1, 0.25_wp, 1.0e-14_wp)
  call check_close('eq 9: mu1', mu1, 0.1_wp, 1.0e-14_wp)
  call check_close('eq 9: kappa', kappa, 1.0_wp, 1.0e-12_wp)
  call check_close('eq 9: beta', beta, 1.0_wp, 1.0e-12_wp)
  call check_close('eq 9: gamma', gamma, 0.01_wp, 1.0e-5_wp)
  call check_close('eq 9: delta', delta, 0.05_wp, 1.0e-5_wp)
  call model_from_physical(5.0_wp, 2.0_wp, 7848.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 9.81_wp, 0.5_wp, &
                           0.5_wp, 10.0_wp, s1, mu1, kappa, beta, gamma, delta, status, message)
  call check_true('eq 9: m > M rejected, message names M', &
                  status == SD_BAD_INPUT .and. index(message, 'M = 5') == 1)

  ! eq (11) coefficients at s1 = 1.5, mu1 = 0.5, theta0 = 0.5, kappa = 2, beta = 3, gamma = 0.1,
  ! delta = 0.2: a = [1/1.5, 0.5/1.5, 2, 6, 0.2, 1/0.75], b = [0.75, 0.375, 2, 3, 0.1, 2]
  call model_from_arrays([1.5_wp, 0.5_wp, 2.0_wp, 0.5_wp, 3.0_wp, 0.1_wp, 0.2_wp, 0.0_wp, 0.0_wp, 0.0_wp], &
                         [6, 2], model, status, message)
  call check_close('eq 11: a1', model%a_coef(1), 1/1.5_wp, 1.0e-15_wp)
  call check_close('eq 11: a2', model%a_coef(2), 1/3.0_wp, 1.0e-15_wp)
  call check_close('eq 11: a3', model%a_coef(3), 2.0_wp, 1.0e-15_wp)
  call check_close('eq 11: a4', model%a_coef(4), 6.0_wp, 1.0e-15_wp)
  call check_close('eq 11: a5', model%a_coef(5), 0.2_wp, 1.0e-15_wp)
  call check_close('eq 11: a6', model%a_coef(6), 1/0.75_wp, 1.0e-15_wp)
  call check_close('eq 11: b1', model%b_coef(1), 0.75_wp, 1.0e-15_wp)
  call check_close('eq 11: b2', model%b_coef(2), 0.375_wp, 1.0e-15_wp)
  call check_close('eq 11: b3', model%b_coef(3), 2.0_wp, 1.0e-15_wp)
  call check_close('eq 11: b4', model%b_coef(4), 3.0_wp, 1.0e-15_wp)
  call check_close('eq 11: b5', model%b_coef(5), 0.1_wp, 1.0e-15_wp)
  call check_close('eq 11: b6', model%b_coef(6), 2.0_wp, 1.0e-15_wp)
  call finish()
end program test_model
