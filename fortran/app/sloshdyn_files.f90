!> File-system calls of the front doors (POSIX, through C): create a directory with its parents,
!> rename and remove files, and create a file under a unique temporary name (mkstemp: unique
!> across processes and threads, so runs sharing a directory never collide).
module sloshdyn_files
  use, intrinsic :: iso_c_binding, only: c_char, c_int, c_null_char
  implicit none
  private
  public :: make_directory, rename_file, remove_file, unique_file, process_id

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
    integer(c_int) function c_mkstemp(template) bind(c, name='mkstemp')
      import :: c_char, c_int
      character(kind=c_char), intent(inout) :: template(*)
    end function c_mkstemp
    integer(c_int) function c_fchmod(fd, mode) bind(c, name='fchmod')
      import :: c_int
      integer(c_int), value :: fd, mode
    end function c_fchmod
    integer(c_int) function c_getpid() bind(c, name='getpid')
      import :: c_int
    end function c_getpid
    integer(c_int) function c_close(fd) bind(c, name='close')
      import :: c_int
      integer(c_int), value :: fd
    end function c_close
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

  !> Create an empty file named prefix followed by six unique characters; path is its name
  !> ('' when it could not be created). Readable by all, as a file opened by Fortran would be.
  subroutine unique_file(prefix, path)
    character(len=*), intent(in) :: prefix
    character(len=:), allocatable, intent(out) :: path
    character(kind=c_char) :: template(len(prefix) + 7)
    integer(c_int) :: fd, ignored
    integer :: i
    do i = 1, len(prefix)
      template(i) = prefix(i:i)
    end do
    template(len(prefix) + 1:len(prefix) + 6) = 'X'
    template(len(prefix) + 7) = c_null_char
    fd = c_mkstemp(template)
    if (fd < 0) then
      path = ''
      return
    end if
    ignored = c_fchmod(fd, int(o'644', c_int))
    ignored = c_close(fd)
    allocate (character(len=len(prefix) + 6) :: path)
    do i = 1, len(path)
      path(i:i) = template(i)
    end do
  end subroutine unique_file

  integer function process_id()
    process_id = c_getpid()
  end function process_id
end module sloshdyn_files
