!> sloshdyn_trig's sine and cosine against quadruple precision (libquadmath's sinq/cosq of the
!> same double argument, rounded): within one unit in the last place everywhere, including
!> next to multiples of pi/2, where the argument reduction must keep the bits that cancel.
program test_trig
  use, intrinsic :: iso_fortran_env, only: real128, int64
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_positive_inf, ieee_is_nan
  use sloshdyn_kinds, only: wp, pi
  use sloshdyn_trig, only: sin_cos, sine
  use sloshdyn_text, only: num2str
  use checks, only: check_true, finish
  implicit none

  real(wp) :: worst, x, s, c
  integer :: i

  call random_init(repeatable=.true., image_distinct=.false.)
  worst = 0
  ! the small angles theta0 x of the equations of motion: no reduction
  do i = 1, 20000
    worst = max(worst, ulp_error(uniform(-pi/4, pi/4)))
  end do
  call check_true('|x| <= pi/4: error <= 1 ulp ('//num2str(worst)//')', worst <= 1)
  worst = 0
  ! rho tau of a harmonic forcing over long runs: one to three parts of pi/2
  do i = 1, 20000
    worst = max(worst, ulp_error(uniform(-20.0_wp, 20.0_wp)))
    worst = max(worst, ulp_error(uniform(-1.0e5_wp, 1.0e5_wp)))
    worst = max(worst, ulp_error(uniform(1.0e5_wp, 1.6e6_wp)))
  end do
  call check_true('pi/4 < |x| < 1.6e6: error <= 1 ulp ('//num2str(worst)//')', worst <= 1)
  worst = 0
  ! next to n pi/2, where x - n pi/2 cancels most bits of x (the second and third parts of
  ! pi/2 are needed): the doubles nearest n pi/2 and their neighbours
  do i = 1, 4000
    x = real(i, wp)*(pi/2)
    worst = max(worst, ulp_error(x), ulp_error(nearest(x, 1.0_wp)), ulp_error(-nearest(x, -1.0_wp)))
    x = real(int(uniform(1.0_wp, 1.0e6_wp), int64), wp)*(pi/2)
    worst = max(worst, ulp_error(x), ulp_error(nearest(x, 1.0_wp)))
  end do
  call check_true('next to multiples of pi/2: error <= 1 ulp ('//num2str(worst)//')', worst <= 1)
  ! beyond the reduction's range the intrinsic functions answer; special values
  call check_true('|x| > 2^20 pi/2: error <= 1 ulp', max(ulp_error(3.0e6_wp), ulp_error(-1.0e15_wp)) <= 1)
  call sin_cos(-0.0_wp, s, c)
  call check_true('sin(-0) = -0, cos(-0) = 1', s == 0 .and. sign(1.0_wp, s) < 0 .and. c == 1)
  call sin_cos(ieee_value(1.0_wp, ieee_positive_inf), s, c)
  call check_true('sin, cos of +Inf are NaN', ieee_is_nan(s) .and. ieee_is_nan(c))
  call check_true('sine of NaN is NaN', ieee_is_nan(sine(ieee_value(1.0_wp, ieee_quiet_nan))))
  call finish()

contains

  !> The larger error of sin_cos's sine and cosine, and of sine, in units of the last place of
  !> the correctly rounded value.
  real(wp) function ulp_error(x) result(err)
    real(wp), intent(in) :: x
    real(wp) :: s, c, s_exact, c_exact
    call sin_cos(x, s, c)
    s_exact = real(sin(real(x, real128)), wp)
    c_exact = real(cos(real(x, real128)), wp)
    err = max(abs(s - s_exact)/spacing(s_exact), abs(c - c_exact)/spacing(c_exact), &
              abs(sine(x) - s_exact)/spacing(s_exact))
    if (sine(x) /= s) err = huge(1.0_wp)  ! the two entry points agree to the bit
  end function ulp_error

  real(wp) function uniform(low, high)
    real(wp), intent(in) :: low, high
    call random_number(uniform)
    uniform = low + (high - low)*uniform
  end function uniform
end program test_trig
