!> Sorting of the short arrays the analyses produce (a few hundred entries at most).
module sloshdyn_sort
  use sloshdyn_kinds, only: wp
  implicit none
  private
  public :: sort_index, sort_ascending

contains

  !> Indices that order values ascending (insertion sort, stable).
  pure subroutine sort_index(values, order)
    real(wp), intent(in) :: values(:)
    integer, intent(out) :: order(size(values))
    integer :: i, j, tmp
    order = [(i, i = 1, size(values))]
    do i = 2, size(values)
      tmp = order(i)
      j = i - 1
      do while (j >= 1)
        if (values(order(j)) <= values(tmp)) exit
        order(j + 1) = order(j)
        j = j - 1
      end do
      order(j + 1) = tmp
    end do
  end subroutine sort_index

  !> values sorted ascending in place.
  pure subroutine sort_ascending(values)
    real(wp), intent(inout) :: values(:)
    integer :: order(size(values))
    call sort_index(values, order)
    values = values(order)
  end subroutine sort_ascending
end module sloshdyn_sort
