!> What the tests of bifurcation curves share (test_bifurcation, test_orbit_chart): the options
!> of a curve in a parameter box, and a report of a traced curve on standard output.
module curve_checks
  use sloshdyn_kinds, only: wp
  use sloshdyn_bifurcation, only: curve_options, bifurcation_curve, curve_end_name, codim2_name
  implicit none
  private
  public :: box, report

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
