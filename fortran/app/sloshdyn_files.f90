!> File-system calls of the front doors (POSIX, through C): create a directory with its parents,
!> rename and remove files, create a file under a unique temporary name (mkstemp: unique
!> across processes and threads, so runs sharing a directory never collide), tell a regular
!> file from a FIFO or a device before it is opened (stat, in sloshdyn_file_type.c), and check
!> that standard output still takes writes.
module sloshdyn_files
  use, intrinsic :: iso_c_binding, only: c_char, c_int, c_null_char, c_int64_t, c_size_t, &
                                         c_ptrdiff_t
  use, intrinsic :: iso_fortran_env, only: int64, output_unit
  implicit none
  private
  public :: make_directory, rename_file, remove_file, unique_file, process_id, file_type, &
            standard_output_writable
  !> Kinds of file_type: no such file, a regular file, a directory, anything else (a FIFO, a
  !> device, a socket), and a file stat could not look at (e.g. permission denied).
  integer, parameter, public :: FILE_MISSING = 0, FILE_REGULAR = 1, FILE_DIRECTORY = 2, &
                                FILE_OTHER = 3, FILE_UNKNOWN = -1

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
    integer(c_int) function c_file_type(path, size) bind(c, name='sloshdyn_file_type')
      import :: c_char, c_int, c_int64_t
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int64_t), intent(out) :: size
    end function c_file_type
    integer(c_ptrdiff_t) function c_write(fd, buffer, count) bind(c, name='write')
      import :: c_char, c_int, c_size_t, c_ptrdiff_t
      integer(c_int), value :: fd
      character(kind=c_char), intent(in) :: buffer(*)
      integer(c_size_t), value :: count
    end function c_write
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

  !> What path is (FILE_MISSING, FILE_REGULAR, FILE_DIRECTORY, FILE_OTHER or FILE_UNKNOWN),
  !> without opening it; size: its bytes when it is a regular file, else 0.
  subroutine file_type(path, kind, size)
    character(len=*), intent(in) :: path
    integer, intent(out) :: kind
    integer(int64), intent(out) :: size
    integer(c_int64_t) :: bytes
    kind = c_file_type(path//c_null_char, bytes)
    size = bytes
  end subroutine file_type

  !> Whether standard output takes writes: gfortran's writes and flushes of it report no
  !> error (a full disk or /dev/full loses the text silently), so the buffered text is flushed
  !> and an empty write(2) asks the file itself (it fails on /dev/full or a closed descriptor).
  logical function standard_output_writable() result(ok)
    character(kind=c_char) :: nothing(1)
    flush (output_unit)
    nothing = ' '
    ok = c_write(1_c_int, nothing, 0_c_size_t) == 0
  end function standard_output_writable

  integer function process_id()
    process_id = c_getpid()
  end function process_id
end module sloshdyn_files
