!> Zeros of scalar functions: Brent's method on a bracket (the one implementation, also used by
!> the continuation to locate special points along a branch), and all real roots of a smooth
!> function on an interval: a grid finds sign changes and extrema (so pairs of close roots and
!> double roots are not missed), Brent's method refines. Also Brent's local minimum on an
!> interval (the peaks of an integration on its dense output, sloshdyn_ode).
module sloshdyn_roots
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_CAPACITY, SD_NOT_CONVERGED
  use sloshdyn_text, only: num2str
  implicit none
  private
  public :: scalar_function, find_all_roots, bracketed_function, bracketed_value, brent_zero, &
            brent_minimum

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

  !> A function for brent_zero; its evaluation may fail (status /= SD_OK ends the search) and
  !> may keep what it computed (e.g. the point of a branch at that arclength).
  type, abstract :: bracketed_function
  contains
    procedure(bracketed_value), deferred :: value
  end type bracketed_function

  abstract interface
    subroutine bracketed_value(self, x, fx, status, message)
      import :: wp, message_len, bracketed_function
      class(bracketed_function), intent(inout) :: self
      real(wp), intent(in) :: x
      real(wp), intent(out) :: fx
      integer, intent(out) :: status
      character(len=message_len), intent(out) :: message
    end subroutine bracketed_value
  end interface

  !> f or f' of a scalar_function, for brent_zero.
  type, extends(bracketed_function) :: scalar_or_slope
    class(scalar_function), allocatable :: f
    logical :: slope = .false.
  contains
    procedure :: value => scalar_or_slope_value
  end type scalar_or_slope

  integer, parameter :: max_brent_iterations = 200
  !> the bracket never shrinks below this, so a zero at x = 0 ends the search too
  real(wp), parameter :: tiny_step = 1.0e-300_wp

contains

  !> Roots of f in [lower, upper], ascending, found on a grid of n_cells cells. A root is also
  !> reported where f touches zero without crossing (|f| <= zero_tol at an extremum).
  !> Each cell must hold at most one extremum of f: choose n_cells accordingly.
  subroutine find_all_roots(f, lower, upper, n_cells, zero_tol, roots, n_roots, status, message)
    class(scalar_function), intent(in) :: f
    real(wp), intent(in) :: lower, upper, zero_tol
    integer, intent(in) :: n_cells
    real(wp), intent(out) :: roots(:)
    integer, intent(out) :: n_roots, status
    character(len=message_len), intent(out) :: message
    real(wp) :: x0, x1, f0, f1, d0, d1, x_ext, f_ext, x_root, f_root
    type(scalar_or_slope) :: values, slopes
    integer :: i

    status = SD_OK
    message = ''
    n_roots = 0
    roots = 0
    allocate (values%f, source=f)
    allocate (slopes%f, source=f)
    slopes%slope = .true.
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
        call brent_zero(values, x0, x1, f0, f1, 0.0_wp, 0.0_wp, x_root, f_root, status, message)
        call add(x_root, roots, n_roots, status, message)
      else if (f0 /= 0 .and. d0*d1 < 0) then
        ! an extremum inside the cell: it may touch zero or hide two close roots
        call brent_zero(slopes, x0, x1, d0, d1, 0.0_wp, 0.0_wp, x_ext, f_root, status, message)
        f_ext = f%value(x_ext)
        if (status /= SD_OK) then
          return
        else if (abs(f_ext) <= zero_tol) then
          call add(x_ext, roots, n_roots, status, message)
        else if (f_ext*f0 < 0) then
          call brent_zero(values, x0, x_ext, f0, f_ext, 0.0_wp, 0.0_wp, x_root, f_root, status, &
                          message)
          call add(x_root, roots, n_roots, status, message)
          if (status /= SD_OK) return
          call brent_zero(values, x_ext, x1, f_ext, f1, 0.0_wp, 0.0_wp, x_root, f_root, status, &
                          message)
          call add(x_root, roots, n_roots, status, message)
        end if
      end if
      if (status /= SD_OK) return
      x0 = x1
      f0 = f1
      d0 = d1
    end do

  end subroutine find_all_roots

  subroutine scalar_or_slope_value(self, x, fx, status, message)
    class(scalar_or_slope), intent(inout) :: self
    real(wp), intent(in) :: x
    real(wp), intent(out) :: fx
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    status = SD_OK
    message = ''
    if (self%slope) then
      fx = self%f%derivative(x)
    else
      fx = self%f%value(x)
    end if
  end subroutine scalar_or_slope_value

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

  !> Brent's method (R. P. Brent, Algorithms for Minimization without Derivatives, 1973, ch. 4,
  !> "zero"): bisection safeguarding secant and inverse quadratic interpolation steps, for a
  !> zero of f in [a, b] where fa = f(a) and fb = f(b) differ in sign. Stops when the bracket
  !> is within 2 epsilon |x| + max(x_tol/2, 1e-300) of x or |f(x)| <= f_tol (x_tol = f_tol = 0:
  !> to machine precision); x is the last iterate, fx its
  !> value. A failed evaluation of f ends the search with its status; no convergence in 200
  !> iterations is SD_NOT_CONVERGED.
  subroutine brent_zero(f, a_in, b_in, fa_in, fb_in, x_tol, f_tol, x, fx, status, message)
    class(bracketed_function), intent(inout) :: f
    real(wp), intent(in) :: a_in, b_in, fa_in, fb_in, x_tol, f_tol
    real(wp), intent(out) :: x, fx
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: a, b, c, d, e, fa, fb, fc, tol, m, p, q, r, s
    integer :: iteration

    status = SD_OK
    message = ''
    a = a_in; b = b_in; fa = fa_in; fb = fb_in
    c = a; fc = fa
    d = b - a; e = d
    do iteration = 1, max_brent_iterations
      if (fb*fc > 0) then
        c = a; fc = fa
        d = b - a; e = d
      end if
      if (abs(fc) < abs(fb)) then
        a = b; b = c; c = a
        fa = fb; fb = fc; fc = fa
      end if
      tol = 2*epsilon(b)*abs(b) + max(x_tol/2, tiny_step)
      m = (c - b)/2
      if (abs(m) <= tol .or. abs(fb) <= f_tol) then
        x = b
        fx = fb
        return
      end if
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
      call f%value(b, fb, status, message)
      if (status /= SD_OK) then
        x = b
        fx = fb
        return
      end if
    end do
    x = b
    fx = fb
    status = SD_NOT_CONVERGED
    message = 'no zero to '//num2str(x_tol)//' in '//num2str(max_brent_iterations)// &
              ' iterations of Brent''s method; last x = '//num2str(b)//', f(x) = '//num2str(fb)
  end subroutine brent_zero

  !> Brent's local minimum (R. P. Brent, Algorithms for Minimization without Derivatives, 1973,
  !> ch. 5, "localmin"): golden section safeguarding parabolic interpolation, for a minimum of f
  !> in (a, b); x is located to within 2 sqrt(epsilon) |x| + x_tol (the ends themselves are
  !> never evaluated: compare them yourself). A failed evaluation of f ends the search with
  !> its status; no convergence in 200 iterations is SD_NOT_CONVERGED.
  subroutine brent_minimum(f, a_in, b_in, x_tol, x, fx, status, message)
    class(bracketed_function), intent(inout) :: f
    real(wp), intent(in) :: a_in, b_in, x_tol
    real(wp), intent(out) :: x, fx
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), parameter :: golden = 0.5_wp*(3 - sqrt(5.0_wp))
    real(wp) :: a, b, d, e, m, p, q, r, tol, t2, u, v, w, fu, fv, fw
    integer :: iteration

    status = SD_OK
    message = ''
    a = min(a_in, b_in)
    b = max(a_in, b_in)
    v = a + golden*(b - a)
    w = v
    x = v
    d = 0
    e = 0
    call f%value(x, fx, status, message)
    if (status /= SD_OK) return
    fv = fx
    fw = fx
    do iteration = 1, max_brent_iterations
      m = (a + b)/2
      tol = sqrt(epsilon(x))*abs(x) + x_tol/3
      t2 = 2*tol
      if (abs(x - m) <= t2 - (b - a)/2) return
      p = 0
      q = 0
      r = 0
      if (abs(e) > tol) then
        ! a parabola through x, v and w
        r = (x - w)*(fx - fv)
        q = (x - v)*(fx - fw)
        p = (x - v)*q - (x - w)*r
        q = 2*(q - r)
        if (q > 0) then
          p = -p
        else
          q = -q
        end if
        r = e
        e = d
      end if
      if (abs(p) < abs(q*r/2) .and. p > q*(a - x) .and. p < q*(b - x)) then
        d = p/q
        u = x + d
        if (u - a < t2 .or. b - u < t2) d = sign(tol, m - x)
      else
        ! golden section into the larger part
        e = merge(a - x, b - x, x >= m)
        d = golden*e
      end if
      u = x + merge(d, sign(tol, d), abs(d) >= tol)
      call f%value(u, fu, status, message)
      if (status /= SD_OK) return
      if (fu <= fx) then
        if (u < x) then
          b = x
        else
          a = x
        end if
        v = w; fv = fw
        w = x; fw = fx
        x = u; fx = fu
      else
        if (u < x) then
          a = u
        else
          b = u
        end if
        if (fu <= fw .or. w == x) then
          v = w; fv = fw
          w = u; fw = fu
        else if (fu <= fv .or. v == x .or. v == w) then
          v = u; fv = fu
        end if
      end if
    end do
    status = SD_NOT_CONVERGED
    message = 'no minimum to '//num2str(x_tol)//' in '//num2str(max_brent_iterations)// &
              ' iterations of Brent''s localmin; last x = '//num2str(x)//', f(x) = '//num2str(fx)
  end subroutine brent_minimum
end module sloshdyn_roots
