!> File-system calls of the front doors (POSIX, through C): create a directory with its parents,
!> rename and remove files, and the process id that makes temporary names unique per run.
module sloshdyn_files
  use, intrinsic :: iso_c_binding, only: c_char, c_int, c_null_char
  implicit none
  private
  public :: make_directory, rename_file, remove_file, process_id

  interface
    integer(c_int) function c_mkdir(path, mode) bind(c, name='mkdir')
      import :: c_char, c_int
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int), value :: mode
    end function c_mkdir
    integer(c_int) function c_rename(old, new) bind(c, name='rename')
      import :: c_char, c_int
      character(kind=c_char), intent(in) :: old(*), new(*)
    end function c_rename
    integer(c_int) function c_unlink(path) bind(c, name='unlink')
      import :: c_char, c_int
      character(kind=c_char), intent(in) :: path(*)
    end function c_unlink
    integer(c_int) function c_getpid() bind(c, name='getpid')
      import :: c_int
    end function c_getpid
  end interface

contains

  !> Create directory `path` and its parents if missing; ok = it exists afterwards.
  subroutine make_directory(path, ok)
    character(len=*), intent(in) :: path
    logical, intent(out) :: ok
    integer :: i, ignored
    do i = 2, len_trim(path)
      if (path(i:i) == '/') ignored = c_mkdir(path(1:i - 1)//c_null_char, int(o'755', c_int))
    end do
    ignored = c_mkdir(trim(path)//c_null_char, int(o'755', c_int))
    inquire (file=trim(path)//'/.', exist=ok)
  end subroutine make_directory

  subroutine rename_file(old, new, ok)
    character(len=*), intent(in) :: old, new
    logical, intent(out) :: ok
    ok = c_rename(trim(old)//c_null_char, trim(new)//c_null_char) == 0
  end subroutine rename_file

  subroutine remove_file(path)
    character(len=*), intent(in) :: path
    integer :: ignored
    ignored = c_unlink(trim(path)//c_null_char)
  end subroutine remove_file

  integer function process_id()
    process_id = c_getpid()
  end function process_id
end module sloshdyn_files
