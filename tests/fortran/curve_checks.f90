!> What the tests of bifurcation curves share (test_bifurcation, test_orbit_chart): the options
!> of a curve in a parameter box, a report of a traced curve on standard output, and its
!> codimension-2 points of a kind.
module curve_checks
  use sloshdyn_kinds, only: wp
  use sloshdyn_bifurcation, only: curve_options, bifurcation_curve, curve_end_name, codim2_name
  implicit none
  private
  public :: box, report, find_codim2

contains

  !> Curve options for the box [p1_min, p1_max] x [p2_min, p2_max] with continuation steps ds
  !> (the first) up to ds_max.
  function box(p1_min, p1_max, p2_min, p2_max, ds, ds_max) result(opt)
    real(wp), intent(in) :: p1_min, p1_max, p2_min, p2_max, ds, ds_max
    type(curve_options) :: opt
    opt%p_min = [p1_min, p2_min]
    opt%p_max = [p1_max, p2_max]
    opt%continuation%ds = ds
    opt%continuation%ds_max = ds_max
  end function box

  !> The curve's codimension-2 points of a kind: how many (result), the first one's column of
  !> the curve (column) and its place in curve%codim2 (first); 0 when there is none.
  integer function find_codim2(curve, kind, column, first) result(count)
    type(bifurcation_curve), intent(in) :: curve
    integer, intent(in) :: kind
    integer, intent(out), optional :: column, first
    integer :: i, first_i
    count = 0
    first_i = 0
    do i = 1, curve%n_codim2
      if (curve%codim2(i)%kind /= kind) cycle
      count = count + 1
      if (first_i == 0) first_i = i
    end do
    if (present(first)) first = first_i
    if (present(column)) then
      column = 0
      if (first_i > 0) column = curve%codim2(first_i)%index
    end if
  end function find_codim2

  !> The number of points, the ends, completeness and message of a curve, and its
  !> codimension-2 points.
  subroutine report(label, curve)
    character(len=*), intent(in) :: label
    type(bifurcation_curve), intent(in) :: curve
    integer :: i
    print '(a, i0, a, a, a, a, a, l1, a, a)', '  '//label//': ', curve%n_points, &
      ' points, ends ', curve_end_name(curve%end_reason(1)), ' / ', &
      curve_end_name(curve%end_reason(2)), ', complete ', curve%complete, ' ', &
      trim(curve%message)
    do i = 1, curve%n_codim2
      print '(a, a, a, 2es23.15, a, f10.6)', '    ', codim2_name(curve%codim2(i)%kind), &
        ' at p =', curve%codim2(i)%p, ', theta =', curve%codim2(i)%omega
    end do
  end subroutine report
end module curve_checks
