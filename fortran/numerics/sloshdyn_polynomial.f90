!> Polynomials in four variables truncated at total degree 3: the algebra of the cubic Taylor
!> expansion of the equations of motion (eq 32-33) and of its modal form (eq 35-36).
!> A polynomial is the array c(0:3, 0:3, 0:3, 0:3) of the coefficients of z1^i z2^j z3^k z4^l;
!> entries with i + j + k + l > 3 stay zero.
module sloshdyn_polynomial
  use sloshdyn_kinds, only: wp
  implicit none
  private
  public :: poly, constant, variable, linear_form, add, scaled, times, reciprocal, sin_series, &
            cos_series, substitute, n_monomials, monomial_exponents

  integer, parameter :: max_degree = 3
  !> Monomials of degree 1 to 3 in four variables (4 + 10 + 20).
  integer, parameter :: n_monomials = 34

  type :: poly
    real(wp) :: c(0:max_degree, 0:max_degree, 0:max_degree, 0:max_degree) = 0
  end type poly

contains

  pure function constant(value) result(p)
    real(wp), intent(in) :: value
    type(poly) :: p
    p%c(0, 0, 0, 0) = value
  end function constant

  !> The variable z_k.
  pure function variable(k) result(p)
    integer, intent(in) :: k
    type(poly) :: p
    integer :: e(4)
    e = 0
    e(k) = 1
    p%c(e(1), e(2), e(3), e(4)) = 1
  end function variable

  !> w1 z1 + w2 z2 + w3 z3 + w4 z4.
  pure function linear_form(w) result(p)
    real(wp), intent(in) :: w(4)
    type(poly) :: p
    p%c(1, 0, 0, 0) = w(1)
    p%c(0, 1, 0, 0) = w(2)
    p%c(0, 0, 1, 0) = w(3)
    p%c(0, 0, 0, 1) = w(4)
  end function linear_form

  pure function add(a, b) result(p)
    type(poly), intent(in) :: a, b
    type(poly) :: p
    p%c = a%c + b%c
  end function add

  pure function scaled(s, a) result(p)
    real(wp), intent(in) :: s
    type(poly), intent(in) :: a
    type(poly) :: p
    p%c = s*a%c
  end function scaled

  !> a b, dropping terms of degree > 3.
  pure function times(a, b) result(p)
    type(poly), intent(in) :: a, b
    type(poly) :: p
    integer :: i, j, k, l, i2, j2, k2, l2
    do l = 0, max_degree
      do k = 0, max_degree - l
        do j = 0, max_degree - l - k
          do i = 0, max_degree - l - k - j
            if (a%c(i, j, k, l) == 0) cycle
            do l2 = 0, max_degree - i - j - k - l
              do k2 = 0, max_degree - i - j - k - l - l2
                do j2 = 0, max_degree - i - j - k - l - l2 - k2
                  do i2 = 0, max_degree - i - j - k - l - l2 - k2 - j2
                    p%c(i + i2, j + j2, k + k2, l + l2) = p%c(i + i2, j + j2, k + k2, l + l2) &
                                                          + a%c(i, j, k, l)*b%c(i2, j2, k2, l2)
                  end do
                end do
              end do
            end do
          end do
        end do
      end do
    end do
  end function times

  !> 1/a for a with a nonzero constant term d: (1/d) (1 - r + r^2 - r^3), r = (a - d)/d.
  pure function reciprocal(a) result(p)
    type(poly), intent(in) :: a
    type(poly) :: p
    type(poly) :: r, r2
    real(wp) :: d
    d = a%c(0, 0, 0, 0)
    r = scaled(1/d, a)
    r%c(0, 0, 0, 0) = 0
    r2 = times(r, r)
    p = add(add(constant(1.0_wp), scaled(-1.0_wp, r)), add(r2, scaled(-1.0_wp, times(r2, r))))
    p = scaled(1/d, p)
  end function reciprocal

  !> sin(a) for a without constant term: a - a^3/6.
  pure function sin_series(a) result(p)
    type(poly), intent(in) :: a
    type(poly) :: p
    p = add(a, scaled(-1.0_wp/6, times(a, times(a, a))))
  end function sin_series

  !> cos(a) for a without constant term: 1 - a^2/2.
  pure function cos_series(a) result(p)
    type(poly), intent(in) :: a
    type(poly) :: p
    p = add(constant(1.0_wp), scaled(-0.5_wp, times(a, a)))
  end function cos_series

  !> a(z) with z_k replaced by the polynomial forms(k) (e.g. a linear change of variables).
  pure function substitute(a, forms) result(p)
    type(poly), intent(in) :: a, forms(4)
    type(poly) :: p
    type(poly) :: powers(0:max_degree, 4), term
    integer :: i, j, k, l, m
    do m = 1, 4
      powers(0, m) = constant(1.0_wp)
      do i = 1, max_degree
        powers(i, m) = times(powers(i - 1, m), forms(m))
      end do
    end do
    p = constant(a%c(0, 0, 0, 0))
    do l = 0, max_degree
      do k = 0, max_degree - l
        do j = 0, max_degree - l - k
          do i = 0, max_degree - l - k - j
            if (i + j + k + l == 0 .or. a%c(i, j, k, l) == 0) cycle
            term = times(times(powers(i, 1), powers(j, 2)), times(powers(k, 3), powers(l, 4)))
            p = add(p, scaled(a%c(i, j, k, l), term))
          end do
        end do
      end do
    end do
  end function substitute

  !> Exponents (i, j, k, l) of the monomials of degree 1, 2, 3, in the order used to export
  !> coefficients: by degree, then lexicographically from z1^d downwards.
  pure function monomial_exponents() result(e)
    integer :: e(4, n_monomials)
    integer :: degree, i, j, k, n
    n = 0
    do degree = 1, max_degree
      do i = degree, 0, -1
        do j = degree - i, 0, -1
          do k = degree - i - j, 0, -1
            n = n + 1
            e(:, n) = [i, j, k, degree - i - j - k]
          end do
        end do
      end do
    end do
  end function monomial_exponents
end module sloshdyn_polynomial
