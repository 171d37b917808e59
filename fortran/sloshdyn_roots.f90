!> All real roots of a smooth scalar function on an interval: a grid finds sign changes and
!> extrema (so pairs of close roots and double roots are not missed), Brent's method refines.
module sloshdyn_roots
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_CAPACITY
  use sloshdyn_text, only: num2str
  implicit none
  private
  public :: scalar_function, find_all_roots

  !> A function f(x) with its derivative; extend it to carry the parameters f depends on.
  type, abstract :: scalar_function
  contains
    procedure(scalar_eval), deferred :: value
    procedure(scalar_eval), deferred :: derivative
  end type scalar_function

  abstract interface
    pure real(wp) function scalar_eval(self, x)
      import :: wp, scalar_function
      class(scalar_function), intent(in) :: self
      real(wp), intent(in) :: x
    end function scalar_eval
  end interface

  integer, parameter :: use_value = 1, use_derivative = 2

contains

  !> Roots of f in [lower, upper], ascending, found on a grid of n_cells cells. A root is also
  !> reported where f touches zero without crossing (|f| <= zero_tol at an extremum).
  !> Each cell must hold at most one extremum of f: choose n_cells accordingly.
  pure subroutine find_all_roots(f, lower, upper, n_cells, zero_tol, roots, n_roots, status, message)
    class(scalar_function), intent(in) :: f
    real(wp), intent(in) :: lower, upper, zero_tol
    integer, intent(in) :: n_cells
    real(wp), intent(out) :: roots(:)
    integer, intent(out) :: n_roots, status
    character(len=message_len), intent(out) :: message
    real(wp) :: x0, x1, f0, f1, d0, d1, x_ext, f_ext
    integer :: i

    status = SD_OK
    message = ''
    n_roots = 0
    roots = 0
    x0 = lower
    f0 = f%value(x0)
    d0 = f%derivative(x0)
    if (f0 == 0) call add(x0, roots, n_roots, status, message)
    do i = 1, n_cells
      x1 = lower + (upper - lower)*real(i, wp)/n_cells
      f1 = f%value(x1)
      d1 = f%derivative(x1)
      if (f1 == 0) then
        call add(x1, roots, n_roots, status, message)
      else if (f0*f1 < 0) then
        call add(brent(f, use_value, x0, x1, f0, f1), roots, n_roots, status, message)
      else if (f0 /= 0 .and. d0*d1 < 0) then
        ! an extremum inside the cell: it may touch zero or hide two close roots
        x_ext = brent(f, use_derivative, x0, x1, d0, d1)
        f_ext = f%value(x_ext)
        if (abs(f_ext) <= zero_tol) then
          call add(x_ext, roots, n_roots, status, message)
        else if (f_ext*f0 < 0) then
          call add(brent(f, use_value, x0, x_ext, f0, f_ext), roots, n_roots, status, message)
          call add(brent(f, use_value, x_ext, x1, f_ext, f1), roots, n_roots, status, message)
        end if
      end if
      x0 = x1
      f0 = f1
      d0 = d1
    end do

  end subroutine find_all_roots

  !> Append root x unless it repeats the last one (a root on a cell boundary is seen twice).
  pure subroutine add(x, roots, n_roots, status, message)
    real(wp), intent(in) :: x
    real(wp), intent(inout) :: roots(:)
    integer, intent(inout) :: n_roots, status
    character(len=message_len), intent(inout) :: message
    if (status /= SD_OK) return
    if (n_roots > 0) then
      if (x <= roots(n_roots)) return
    end if
    if (n_roots == size(roots)) then
      status = SD_CAPACITY
      message = 'more than '//num2str(size(roots))//' roots'
      return
    end if
    n_roots = n_roots + 1
    roots(n_roots) = x
  end subroutine add

  !> Brent's method (Brent 1973, zeroin) for a zero of f (which = use_value) or of f'
  !> (which = use_derivative) in [a, b], where fa and fb have opposite signs.
  pure real(wp) function brent(f, which, a_in, b_in, fa_in, fb_in) result(b)
    class(scalar_function), intent(in) :: f
    integer, intent(in) :: which
    real(wp), intent(in) :: a_in, b_in, fa_in, fb_in
    real(wp) :: a, c, d, e, fa, fb, fc, tol, m, p, q, r, s
    integer :: iteration

    a = a_in; b = b_in; fa = fa_in; fb = fb_in
    c = a; fc = fa
    d = b - a; e = d
    do iteration = 1, 200
      if (fb*fc > 0) then
        c = a; fc = fa
        d = b - a; e = d
      end if
      if (abs(fc) < abs(fb)) then
        a = b; b = c; c = a
        fa = fb; fb = fc; fc = fa
      end if
      tol = 2*epsilon(b)*abs(b) + 1.0e-300_wp
      m = (c - b)/2
      if (abs(m) <= tol .or. fb == 0) return
      if (abs(e) >= tol .and. abs(fa) > abs(fb)) then
        s = fb/fa
        if (a == c) then
          p = 2*m*s
          q = 1 - s
        else
          q = fa/fc
          r = fb/fc
          p = s*(2*m*q*(q - r) - (b - a)*(r - 1))
          q = (q - 1)*(r - 1)*(s - 1)
        end if
        if (p > 0) then
          q = -q
        else
          p = -p
        end if
        if (2*p < min(3*m*q - abs(tol*q), abs(e*q))) then
          e = d
          d = p/q
        else
          d = m; e = m
        end if
      else
        d = m; e = m
      end if
      a = b; fa = fb
      if (abs(d) > tol) then
        b = b + d
      else
        b = b + sign(tol, m)
      end if
      if (which == use_value) then
        fb = f%value(b)
      else
        fb = f%derivative(b)
      end if
    end do
  end function brent
end module sloshdyn_roots
