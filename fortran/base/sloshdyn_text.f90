!> Number formatting for messages and summaries (no I/O).
module sloshdyn_text
  use sloshdyn_kinds, only: wp
  implicit none
  private
  public :: num2str

  interface num2str
    module procedure real2str, int2str
  end interface num2str

contains

  !> Shortest readable form of a real: up to 10 decimals (or 10 significant digits in
  !> exponent form), no trailing zeros; rounded to `significant` digits first if given.
  pure recursive function real2str(x, significant) result(text)
    real(wp), intent(in) :: x
    integer, intent(in), optional :: significant
    character(len=:), allocatable :: text
    character(len=40) :: buffer
    integer :: cut, epos
    real(wp) :: rounded

    if (x /= x) then
      text = 'NaN'
      return
    else if (abs(x) > huge(x)) then
      text = merge('+Infinity', '-Infinity', x > 0)
      return
    end if
    if (present(significant)) then
      write (buffer, '(es40.'//int2str(max(significant, 1) - 1)//'e3)') x
      read (buffer, *) rounded
      text = real2str(rounded)
      return
    end if
    if (x == 0 .or. (abs(x) >= 1.0e-4_wp .and. abs(x) < 1.0e9_wp)) then
      write (buffer, '(f40.10)') x
      buffer = adjustl(buffer)
      cut = len_trim(buffer)
      do while (buffer(cut:cut) == '0')
        cut = cut - 1
      end do
      if (buffer(cut:cut) == '.') cut = cut - 1
      text = buffer(1:cut)
    else
      write (buffer, '(es40.9e3)') x
      buffer = adjustl(buffer)
      epos = index(buffer, 'E')
      cut = epos - 1
      do while (buffer(cut:cut) == '0')
        cut = cut - 1
      end do
      if (buffer(cut:cut) == '.') cut = cut - 1
      ! exponent without leading zeros: 4e-6, not 4e-006
      text = buffer(1:cut)//'e'//trim(merge('-', ' ', buffer(epos+1:epos+1) == '-'))// &
             int2str(abs(exponent_of(buffer(epos+1:))))
    end if
  end function real2str

  pure integer function exponent_of(text)
    character(len=*), intent(in) :: text
    read (text, *) exponent_of
  end function exponent_of

  pure function int2str(i) result(text)
    integer, intent(in) :: i
    character(len=:), allocatable :: text
    character(len=20) :: buffer
    write (buffer, '(i0)') i
    text = trim(buffer)
  end function int2str
end module sloshdyn_text
