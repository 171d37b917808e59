!> Number formatting for messages and summaries (no I/O).
!>
!> The results have a length given by a specification function (text_width), not a deferred
!> length: for a deferred-length function result gfortran keeps the length in a static variable
!> of the caller ("slen"), shared by every thread, so two threads building messages at once
!> could corrupt each other's strings. With the length computed in the caller's frame the
!> formatting is thread-safe (checked by tests/python/test_studies.py, which looks for such
!> statics in the extension).
module sloshdyn_text
  use sloshdyn_kinds, only: wp
  implicit none
  private
  public :: num2str

  interface num2str
    module procedure real2str, rounded2str, int2str
  end interface num2str

  integer, parameter :: buffer_len = 64

contains

  !> Shortest readable form of a real: up to 10 decimals (or 10 significant digits in
  !> exponent form), no trailing zeros.
  pure function real2str(x) result(text)
    real(wp), intent(in) :: x
    character(len=real_width(x)) :: text
    character(len=buffer_len) :: buffer
    integer :: length
    call format_real(x, buffer, length)
    text = buffer(1:length)
  end function real2str

  !> The same, rounded to `significant` digits first (num2str(x, significant)).
  pure function rounded2str(x, significant) result(text)
    real(wp), intent(in) :: x
    integer, intent(in) :: significant
    character(len=real_width(rounded_to(x, significant))) :: text
    text = real2str(rounded_to(x, significant))
  end function rounded2str

  pure integer function real_width(x)
    real(wp), intent(in) :: x
    character(len=buffer_len) :: buffer
    call format_real(x, buffer, real_width)
  end function real_width

  !> x rounded to `significant` digits (NaN and infinities unchanged).
  pure real(wp) function rounded_to(x, significant)
    real(wp), intent(in) :: x
    integer, intent(in) :: significant
    character(len=40) :: buffer
    character(len=20) :: form
    rounded_to = x
    if (x /= x .or. abs(x) > huge(x)) return
    write (form, '(a, i0, a)') '(es40.', max(significant, 1) - 1, 'e3)'
    write (buffer, form) x
    read (buffer, *) rounded_to
  end function rounded_to

  !> The text of real2str in buffer(1:length).
  pure subroutine format_real(x, text, length)
    real(wp), intent(in) :: x
    character(len=buffer_len), intent(out) :: text
    integer, intent(out) :: length
    character(len=40) :: buffer
    character(len=20) :: exponent_text
    integer :: cut, epos

    text = ''
    if (x /= x) then
      text = 'NaN'
    else if (abs(x) > huge(x)) then
      text = merge('+Infinity', '-Infinity', x > 0)
    else if (x == 0 .or. (abs(x) >= 1.0e-4_wp .and. abs(x) < 1.0e9_wp)) then
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
      write (exponent_text, '(i0)') abs(exponent_of(buffer(epos+1:)))
      text = buffer(1:cut)//'e'//trim(merge('-', ' ', buffer(epos+1:epos+1) == '-'))// &
             trim(exponent_text)
    end if
    length = len_trim(text)
  end subroutine format_real

  pure integer function exponent_of(text)
    character(len=*), intent(in) :: text
    read (text, *) exponent_of
  end function exponent_of

  pure function int2str(i) result(text)
    integer, intent(in) :: i
    character(len=int_width(i)) :: text
    character(len=20) :: buffer
    write (buffer, '(i0)') i
    text = trim(buffer)
  end function int2str

  pure integer function int_width(i)
    integer, intent(in) :: i
    character(len=20) :: buffer
    write (buffer, '(i0)') i
    int_width = len_trim(buffer)
  end function int_width
end module sloshdyn_text
