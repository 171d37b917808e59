!> Times and checks benchmarks/sincos_kernels.f90's kernels (benchmarks/sincos_kernels.py
!> builds both files together).
program sincos_bench
  use, intrinsic :: iso_fortran_env, only: wp => real64, int64
  use sincos_kernels, only: sin_cos, sin_cos_many
  implicit none
  character(len=256) :: mode, path
  integer :: n, u, i, r
  real(wp), allocatable :: x(:), s(:), c(:), s1(:), c1(:)
  call get_command_argument(1, mode)
  call get_command_argument(2, path)
  if (mode == 'values') then
    open (newunit=u, file=trim(path), access='stream', form='unformatted', status='old')
    read (u) n
    allocate (x(n), s(n), c(n), s1(n), c1(n))
    read (u) x
    close (u)
    call sin_cos_many(x, s, c)
    do i = 1, n
      call sin_cos(x(i), s1(i), c1(i))
    end do
    if (any(transfer(s, 1_int64, n) /= transfer(s1, 1_int64, n)) .or. &
        any(transfer(c, 1_int64, n) /= transfer(c1, 1_int64, n))) then
      print '(a)', 'scalar and vectorised calls differ'
    else
      print '(a)', 'scalar and vectorised calls agree'
    end if
    open (newunit=u, file=trim(path)//'.out', access='stream', form='unformatted', status='replace')
    write (u) s, c
    close (u)
  else
    call timings()
  end if
contains
  !> ns per (sine, cosine) pair: 192 pendulum-sized angles at once; and three angles at a time,
  !> as one right-hand side of the tank model needs them (two small, one forcing phase).
  subroutine timings()
    integer, parameter :: m = 192, reps = 20000
    real(wp) :: a(m), sa(m), ca(m), y(3), sy(3), cy(3), acc, t0, t1
    integer :: j
    call random_number(a)
    a = (a - 0.5_wp)*0.6_wp
    acc = 0
    call cpu_time(t0)
    do r = 1, reps
      a(1) = a(1) + 1e-12_wp*acc
      call sin_cos_many(a, sa, ca)
      acc = acc + sa(7) + ca(9)
    end do
    call cpu_time(t1)
    print '(a, f8.3)', 'kernels, 192 arguments per call: ', (t1 - t0)/(m*real(reps, wp))*1e9_wp
    call cpu_time(t0)
    do r = 1, reps
      a(1) = a(1) + 1e-12_wp*acc
      do j = 1, m
        sa(j) = sin(a(j))
        ca(j) = cos(a(j))
      end do
      acc = acc + sa(7) + ca(9)
    end do
    call cpu_time(t1)
    print '(a, f8.3)', 'libm, 192 arguments in a loop: ', (t1 - t0)/(m*real(reps, wp))*1e9_wp
    call cpu_time(t0)
    do r = 1, reps*m/3
      y = [0.21_wp, -0.13_wp, 700.0_wp] + r*1e-9_wp + acc*1e-30_wp
      call sin_cos_many(y, sy, cy)
      acc = acc + sy(1) + cy(3)
    end do
    call cpu_time(t1)
    print '(a, f8.3)', 'kernels, 3 arguments per call: ', (t1 - t0)/(m*real(reps, wp))*1e9_wp
    call cpu_time(t0)
    do r = 1, reps*m/3
      y = [0.21_wp, -0.13_wp, 700.0_wp] + r*1e-9_wp + acc*1e-30_wp
      do j = 1, 3
        call sin_cos(y(j), sy(j), cy(j))
      end do
      acc = acc + sy(1) + cy(3)
    end do
    call cpu_time(t1)
    print '(a, f8.3)', 'kernels, 3 scalar calls: ', (t1 - t0)/(m*real(reps, wp))*1e9_wp
    call cpu_time(t0)
    do r = 1, reps*m/3
      y = [0.21_wp, -0.13_wp, 700.0_wp] + r*1e-9_wp + acc*1e-30_wp
      do j = 1, 3
        sy(j) = sin(y(j))
        cy(j) = cos(y(j))
      end do
      acc = acc + sy(1) + cy(3)
    end do
    call cpu_time(t1)
    print '(a, f8.3)', 'libm, 3 arguments: ', (t1 - t0)/(m*real(reps, wp))*1e9_wp
    if (acc /= acc) print '(a)', 'NaN'
  end subroutine timings
end program sincos_bench
