!> Times the core's right-hand side alone (benchmarks/run.py compiles this against the meson
!> build directory). Reads rpar, ipar (the bridge layout, sloshdyn_model) and the number of
!> calls from stdin; prints the seconds per call of sloshdyn_motion's equations_of_motion
!> (eq 15) and a checksum. The state drifts by 1e-9 dy/dtau per call so no evaluation can be
!> reused.
program rhs_cost
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_model, only: model_t, model_from_arrays, n_real_params, n_int_params
  use sloshdyn_motion, only: equations_of_motion
  implicit none
  real(wp) :: rpar(n_real_params), y(4), dydt(4), tau, acc
  integer :: ipar(n_int_params), status, i, n
  integer(8) :: c0, c1, rate
  character(len=message_len) :: message
  type(model_t) :: model

  read (*, *) rpar, ipar, n
  call model_from_arrays(rpar, ipar, model, status, message)
  if (status /= 0) then
    print '(a)', trim(message)
    error stop 1
  end if
  y = [0.01_wp, 0.0_wp, 0.01_wp, 0.0_wp]
  acc = 0
  tau = 0
  call system_clock(c0, rate)
  do i = 1, n
    tau = tau + 0.01_wp
    call equations_of_motion(model, tau, y, dydt)
    y = y + 1.0e-9_wp*dydt
    acc = acc + dydt(2)
  end do
  call system_clock(c1)
  print '(es24.16, 1x, es24.16)', real(c1 - c0, wp)/real(rate, wp)/real(n, wp), acc
end program rhs_cost
