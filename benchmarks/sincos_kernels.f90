!> The sine and cosine kernels of issue 43's experiments (2026-12-03, 2026-12-07), kept as
!> benchmarks (not used by the core; benchmarks/README.md, "Own sine and cosine kernels" and
!> "A member-fastest ensemble, prototyped"): fdlibm's method (FreeBSD msun k_sin.c, k_cos.c,
!> e_rem_pio2.c) with the reduction's branches replaced by exact two-sums and the quadrant
!> chosen by rounding, so that a loop over many arguments vectorises with the bits of one
!> argument at a time. Preprocess it (-cpp); -DFULL_REDUCTION takes the reduction for every
!> call (the 2026-12-03 kernels). Used by sincos_bench.f90 (sincos_kernels.py) and
!> ensemble_soa.f90 (ensemble_soa.py).
module sincos_kernels
  use, intrinsic :: iso_fortran_env, only: wp => real64
  implicit none
  private
  public :: sin_cos, sin_cos_many, REDUCTION_LIMIT

  !> |x| up to which the kernels' reduction is exact (fdlibm's medium range, 2^20 pi/2 ~ 1.647e6).
  real(wp), parameter :: REDUCTION_LIMIT = 1.6e6_wp
  !> |x| below which x*2/pi rounds to n = 0 with room to spare (pi/4 = 0.785398...)
  real(wp), parameter :: SMALL_LIMIT = 0.78_wp

  real(wp), parameter :: two_over_pi = 6.36619772367581382433e-01_wp
  !> pi/2 = pio2_1 + pio2_2 + pio2_3 + pio2_3t (e_rem_pio2.c: 33 + 33 + 33 + 53 bits)
  real(wp), parameter :: pio2_1 = 1.57079632673412561417e+00_wp, &
                         pio2_2 = 6.07710050630396597660e-11_wp, &
                         pio2_3 = 2.02226624871116645580e-21_wp, &
                         pio2_3t = 8.47842766036889956997e-32_wp
  !> 1.5 * 2^52: (v + round_shift) - round_shift rounds v to the nearest integer (|v| < 2^51)
  real(wp), parameter :: round_shift = 6755399441055744.0_wp
  real(wp), parameter :: S1 = -1.66666666666666324348e-01_wp, S2 = 8.33333333332248946124e-03_wp, &
                         S3 = -1.98412698298579493134e-04_wp, S4 = 2.75573137070700676789e-06_wp, &
                         S5 = -2.50507602534068634195e-08_wp, S6 = 1.58969099521155010221e-10_wp
  real(wp), parameter :: C1 = 4.16666666666666019037e-02_wp, C2 = -1.38888888888741095749e-03_wp, &
                         C3 = 2.48015872894767294178e-05_wp, C4 = -2.75573143513906633035e-07_wp, &
                         C5 = 2.08757232129817482790e-09_wp, C6 = -1.13596475577881948265e-11_wp

contains

  !> sin(x) and cos(x) of one argument.
  elemental subroutine sin_cos(x, s, c)
    real(wp), intent(in) :: x
    real(wp), intent(out) :: s, c
    real(wp) :: sv(1), cv(1)
    call sin_cos_many([x], sv, cv)
    s = sv(1)
    c = cv(1)
  end subroutine sin_cos

  !> sin_cos of every element of x: the kernels run as one loop that the compiler vectorises,
  !> the arguments beyond REDUCTION_LIMIT are redone one at a time (the same bits as sin_cos).
  pure subroutine sin_cos_many(x, s, c)
    real(wp), intent(in) :: x(:)
    real(wp), intent(out) :: s(:), c(:)
    integer :: i
    real(wp) :: big
    real(wp) :: fn, q, odd, a, r1, e1, r2, e2, lo, y0, y1, ks, kc, swapped_s, swapped_c
    ! (prototype's addition: when every argument is below pi/4, fdlibm's own first case, the
    ! reduction below would give n = 0, y0 = x + 0, y1 = +0 exactly, so it is skipped; the
    ! test is one vectorised pass and the bits are those of the full path)
#ifndef FULL_REDUCTION
    big = 0
    do i = 1, size(x)
      big = big + merge(0.0_wp, 1.0_wp, abs(x(i)) <= SMALL_LIMIT)
    end do
    if (big == 0) then
      do i = 1, size(x)
        y0 = x(i) + 0.0_wp
        s(i) = kernel_sin(y0, 0.0_wp)
        c(i) = kernel_cos(y0, 0.0_wp)
      end do
      return
    end if
#endif
    do i = 1, size(x)
      fn = (x(i)*two_over_pi + round_shift) - round_shift
      ! q = n mod 4 and odd = n mod 2 by the same rounding (floor(v) = round(v - 3/8) for v in Z/4)
      q = fn - 4*((0.25_wp*fn - 0.375_wp + round_shift) - round_shift)
      odd = q - 2*((0.5_wp*q - 0.25_wp + round_shift) - round_shift)
      a = x(i) - fn*pio2_1                 ! exact (e_rem_pio2.c)
      call two_sum(a, -(fn*pio2_2), r1, e1)
      call two_sum(r1, -(fn*pio2_3), r2, e2)
      lo = (e1 + e2) - fn*pio2_3t
      y0 = r2 + lo
      y1 = (r2 - y0) + lo
      ks = kernel_sin(y0, y1)
      kc = kernel_cos(y0, y1)
      ! x = n pi/2 + r: (sin, cos)(x) = (s, c), (c, -s), (-s, -c), (-c, s) for n mod 4 = 0..3
      swapped_s = merge(kc, ks, odd > 0.5_wp)
      swapped_c = merge(ks, kc, odd > 0.5_wp)
      s(i) = merge(-swapped_s, swapped_s, q > 1.5_wp)
      c(i) = merge(-swapped_c, swapped_c, abs(q - 1.5_wp) < 1)
    end do
    ! (prototype's change: a vectorisable test for arguments out of range, then the scalar
    ! redo only if there is one; the bits are those of the original)
    big = 0
    do i = 1, size(x)
      big = big + merge(1.0_wp, 0.0_wp, .not. abs(x(i)) <= REDUCTION_LIMIT)
    end do
    if (big == 0) return
    do i = 1, size(x)
      if (.not. abs(x(i)) <= REDUCTION_LIMIT) then
        s(i) = sin(x(i))
        c(i) = cos(x(i))
      end if
    end do
  end subroutine sin_cos_many

  !> s + e = a + b exactly (Knuth's two-sum: no assumption on the magnitudes).
  elemental subroutine two_sum(a, b, s, e)
    real(wp), intent(in) :: a, b
    real(wp), intent(out) :: s, e
    real(wp) :: bb
    s = a + b
    bb = s - a
    e = (a - (s - bb)) + (b - bb)
  end subroutine two_sum

  !> sin(x + y) for |x| <= pi/4, y the tail of x (k_sin.c, FreeBSD's grouping).
  elemental real(wp) function kernel_sin(x, y) result(v)
    real(wp), intent(in) :: x, y
    real(wp) :: z, w, r, zx
    z = x*x
    w = z*z
    r = S2 + z*(S3 + z*S4) + z*w*(S5 + z*S6)
    zx = z*x
    v = x - ((z*(0.5_wp*y - zx*r) - y) - zx*S1)
  end function kernel_sin

  !> cos(x + y) for |x| <= pi/4, y the tail of x (k_cos.c, FreeBSD's grouping).
  elemental real(wp) function kernel_cos(x, y) result(v)
    real(wp), intent(in) :: x, y
    real(wp) :: z, w, r, hz, one_minus_hz
    z = x*x
    w = z*z
    r = z*(C1 + z*(C2 + z*C3)) + w*w*(C4 + z*(C5 + z*C6))
    hz = 0.5_wp*z
    one_minus_hz = 1 - hz
    v = one_minus_hz + (((1 - one_minus_hz) - hz) + (z*r - x*y))
  end function kernel_cos

end module sincos_kernels
