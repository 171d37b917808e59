!> Sine and cosine for the right-hand sides: the equations of motion take three of them per
!> evaluation (theta0 x1, theta0 x2 and rho tau), the evaluation's costliest part. These take
!> 11 % fewer instructions per integration step than libm's calls, the same time in a portable
!> build, and 18 % less time where the compiler may use fused multiply-add (benchmarks/README.md,
!> issue 28, fourth session).
!>
!> The method is fdlibm's (Sun Microsystems 1993; k_sin.c, k_cos.c, e_rem_pio2.c): minimax
!> polynomials of degree 13 (sine) and 14 (cosine) on |r| <= pi/4, with an error below one unit
!> in the last place, after r = x - n pi/2 with pi/2 split in three parts (Cody and Waite
!> reduction, as fdlibm for |x| < 2^20 pi/2, exact enough there for every double). Beyond that
!> range, and for Inf and NaN, the intrinsic functions answer. Results may differ from libm's in
!> the last bit; tests/fortran/test_trig.f90 bounds the difference.
module sloshdyn_trig
  use sloshdyn_kinds, only: wp
  implicit none
  private
  public :: sin_cos, sine

  ! fdlibm k_sin.c: sin r = r + r^3 (S1 + r^2 S2 + ... + r^10 S6)
  real(wp), parameter :: S1 = -1.66666666666666324348e-01_wp, S2 = 8.33333333332248946124e-03_wp, &
                         S3 = -1.98412698298579493134e-04_wp, S4 = 2.75573137070700676789e-06_wp, &
                         S5 = -2.50507602534068634195e-08_wp, S6 = 1.58969099521155010221e-10_wp
  ! fdlibm k_cos.c (FreeBSD's form): cos r = 1 - r^2/2 + r^4 (C1 + r^2 C2 + ... + r^10 C6)
  real(wp), parameter :: C1 = 4.16666666666666019037e-02_wp, C2 = -1.38888888888741095749e-03_wp, &
                         C3 = 2.48015872894767294178e-05_wp, C4 = -2.75573143513906633035e-07_wp, &
                         C5 = 2.08757232129817482790e-09_wp, C6 = -1.13596475577881948265e-11_wp
  ! fdlibm e_rem_pio2.c: 2/pi, and pi/2 = pio2_1 + pio2_2 + pio2_3 + pio2_3t in 33-bit parts
  ! (pio2_kt = the rest after part k)
  real(wp), parameter :: inv_pio2 = 6.36619772367581382433e-01_wp, &
                         pio2_1 = 1.57079632673412561417e+00_wp, pio2_1t = 6.07710050650619224932e-11_wp, &
                         pio2_2 = 6.07710050630396597660e-11_wp, pio2_2t = 2.02226624879595063154e-21_wp, &
                         pio2_3 = 2.02226624871116645580e-21_wp, pio2_3t = 8.47842766036889956997e-32_wp
  real(wp), parameter :: pio2_part(2) = [pio2_2, pio2_3], pio2_rest(2) = [pio2_2t, pio2_3t]
  !> |r| below these fractions of |x| (2^-16, 2^-49) call for the second and third part
  real(wp), parameter :: cancellation(2) = [2.0_wp**(-16), 2.0_wp**(-49)]
  real(wp), parameter :: pio4 = 7.85398163397448278999e-01_wp
  !> Above this |x| the reduction would lose bits: the intrinsic functions take over.
  real(wp), parameter :: reduction_limit = 1647099.0_wp  ! 2^20 pi/2
  !> 1.5 2^52: (u + round_shift) - round_shift rounds u to the nearest integer (|u| < 2^51).
  real(wp), parameter :: round_shift = 6755399441055744.0_wp

contains

  !> s = sin x, c = cos x.
  elemental subroutine sin_cos(x, s, c)
    real(wp), intent(in) :: x
    real(wp), intent(out) :: s, c
    real(wp) :: r, r_low
    integer :: quadrant
    if (abs(x) <= pio4) then
      s = kernel_sin(x, 0.0_wp)
      c = kernel_cos(x, 0.0_wp)
    else if (abs(x) < reduction_limit) then
      call reduce(x, r, r_low, quadrant)
      select case (quadrant)
      case (0)
        s = kernel_sin(r, r_low); c = kernel_cos(r, r_low)
      case (1)
        s = kernel_cos(r, r_low); c = -kernel_sin(r, r_low)
      case (2)
        s = -kernel_sin(r, r_low); c = -kernel_cos(r, r_low)
      case default
        s = -kernel_cos(r, r_low); c = kernel_sin(r, r_low)
      end select
    else
      s = sin(x); c = cos(x)
    end if
  end subroutine sin_cos

  !> sin x.
  elemental real(wp) function sine(x) result(s)
    real(wp), intent(in) :: x
    real(wp) :: r, r_low
    integer :: quadrant
    if (abs(x) <= pio4) then
      s = kernel_sin(x, 0.0_wp)
    else if (abs(x) < reduction_limit) then
      call reduce(x, r, r_low, quadrant)
      select case (quadrant)
      case (0)
        s = kernel_sin(r, r_low)
      case (1)
        s = kernel_cos(r, r_low)
      case (2)
        s = -kernel_sin(r, r_low)
      case default
        s = -kernel_cos(r, r_low)
      end select
    else
      s = sin(x)
    end if
  end function sine

  !> x = n pi/2 + r + r_low with |r + r_low| <= pi/4 (to about 2^-1 ulp), quadrant = n mod 4.
  !> A second and third part of pi/2 enter only when the first cancels many bits of x: fdlibm
  !> tests for more than 16 and 49 binary orders of magnitude between x and r; |r| < 2^-16 |x|
  !> and |r| < 2^-49 |x| hold in all those cases (and a few more, where the extra part is
  !> harmless), without the call of frexp that exponent() costs.
  elemental subroutine reduce(x, r, r_low, quadrant)
    real(wp), intent(in) :: x
    real(wp), intent(out) :: r, r_low
    integer, intent(out) :: quadrant
    real(wp) :: n, head, w, t
    integer :: part
    n = (x*inv_pio2 + round_shift) - round_shift
    quadrant = iand(int(n), 3)
    head = x - n*pio2_1
    w = n*pio2_1t
    r = head - w
    do part = 1, 2
      if (abs(r) >= abs(x)*cancellation(part)) exit
      t = head
      w = n*pio2_part(part)
      head = t - w
      w = n*pio2_rest(part) - ((t - head) - w)
      r = head - w
    end do
    r_low = (head - r) - w
  end subroutine reduce

  !> sin(r + r_low) for |r + r_low| <= pi/4, r_low a correction below ulp(r) (fdlibm k_sin.c).
  elemental real(wp) function kernel_sin(r, r_low) result(s)
    real(wp), intent(in) :: r, r_low
    real(wp) :: z, w, p, v
    z = r*r
    w = z*z
    p = S2 + z*(S3 + z*S4) + z*w*(S5 + z*S6)
    v = z*r
    s = r - ((z*(0.5_wp*r_low - v*p) - r_low) - v*S1)
  end function kernel_sin

  !> cos(r + r_low) for |r + r_low| <= pi/4 (fdlibm k_cos.c, FreeBSD's form).
  elemental real(wp) function kernel_cos(r, r_low) result(c)
    real(wp), intent(in) :: r, r_low
    real(wp) :: z, w, p, half_z
    z = r*r
    w = z*z
    p = z*(C1 + z*(C2 + z*C3)) + w*w*(C4 + z*(C5 + z*C6))
    half_z = 0.5_wp*z
    w = 1 - half_z
    c = w + (((1 - w) - half_z) + (z*p - r*r_low))
  end function kernel_cos
end module sloshdyn_trig
