!> File-system calls of the front doors (POSIX, through C): create a directory with its parents,
!> rename and remove files, create a file under a unique temporary name (mkstemp: unique
!> across processes and threads, so runs sharing a directory never collide), tell a regular
!> file from a FIFO or a device before it is opened (stat, in sloshdyn_file_type.c), and check
!> that standard output still takes writes; and the run-directory rule of docs/failure.md (in
!> sloshdyn_run_directory.c): a file created new, a new directory under a unique name, the
!> first entry of a directory that no run wrote, a run's directory removed or swapped into place.
module sloshdyn_files
  use, intrinsic :: iso_c_binding, only: c_char, c_int, c_null_char, c_int64_t, c_size_t, &
                                         c_ptrdiff_t
  use, intrinsic :: iso_fortran_env, only: int64, output_unit
  implicit none
  private
  public :: make_directory, rename_file, remove_file, unique_file, process_id, file_type, &
            standard_output_writable, create_new, temporary_directory, foreign_entry, &
            remove_run_directory, swap_into_place, error_text, is_link, standard_input_text
  !> The marker file of a run's directory and its first line (the same as python/sloshdyn/
  !> _files.py's): the names a run wrote follow, one a line.
  character(len=*), parameter, public :: RUN_MARKER = '.sloshdyn-run', &
    MARKER_HEADER = 'sloshdyn run directory: every file listed below was written by one run '// &
                    'of sloshdyn, and the next run into this directory replaces it as a whole'
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
    integer(c_int) function c_create_new(path) bind(c, name='sloshdyn_create_new')
      import :: c_char, c_int
      character(kind=c_char), intent(in) :: path(*)
    end function c_create_new
    integer(c_int) function c_make_temporary_directory(template) &
      bind(c, name='sloshdyn_make_temporary_directory')
      import :: c_char, c_int
      character(kind=c_char), intent(inout) :: template(*)
    end function c_make_temporary_directory
    integer(c_int) function c_foreign_entry(dir, header, name, capacity) &
      bind(c, name='sloshdyn_foreign_entry')
      import :: c_char, c_int
      character(kind=c_char), intent(in) :: dir(*), header(*)
      character(kind=c_char), intent(out) :: name(*)
      integer(c_int), value :: capacity
    end function c_foreign_entry
    integer(c_int) function c_remove_run_directory(dir, header, all) &
      bind(c, name='sloshdyn_remove_run_directory')
      import :: c_char, c_int
      character(kind=c_char), intent(in) :: dir(*), header(*)
      integer(c_int), value :: all
    end function c_remove_run_directory
    integer(c_int) function c_swap_into_place(staging, target, previous, header, foreign, &
                                              capacity) bind(c, name='sloshdyn_swap_into_place')
      import :: c_char, c_int
      character(kind=c_char), intent(in) :: staging(*), target(*), previous(*), header(*)
      character(kind=c_char), intent(out) :: foreign(*)
      integer(c_int), value :: capacity
    end function c_swap_into_place
    integer(c_ptrdiff_t) function c_read(fd, buffer, count) bind(c, name='read')
      import :: c_char, c_int, c_size_t, c_ptrdiff_t
      integer(c_int), value :: fd
      character(kind=c_char), intent(out) :: buffer(*)
      integer(c_size_t), value :: count
    end function c_read
    integer(c_int) function c_is_link(path) bind(c, name='sloshdyn_is_link')
      import :: c_char, c_int
      character(kind=c_char), intent(in) :: path(*)
    end function c_is_link
    subroutine c_error_text(code, text, capacity) bind(c, name='sloshdyn_error_text')
      import :: c_char, c_int
      integer(c_int), value :: code, capacity
      character(kind=c_char), intent(out) :: text(*)
    end subroutine c_error_text
  end interface

  !> Room for a name returned by the C side.
  integer, parameter :: name_room = 4096

contains

  !> Create path as a new empty file (never an existing file, never through a symbolic link);
  !> code: 0 or the errno (error_text says it).
  subroutine create_new(path, code)
    character(len=*), intent(in) :: path
    integer, intent(out) :: code
    code = c_create_new(path//c_null_char)
  end subroutine create_new

  !> Create a new directory named prefix followed by six unique characters; path is its name
  !> ('' when it could not be created, code the errno).
  subroutine temporary_directory(prefix, path, code)
    character(len=*), intent(in) :: prefix
    character(len=:), allocatable, intent(out) :: path
    integer, intent(out) :: code
    character(kind=c_char) :: template(len(prefix) + 7)
    call to_c(prefix//'XXXXXX', template)
    code = c_make_temporary_directory(template)
    path = ''
    if (code == 0) path = from_c(template)
  end subroutine temporary_directory

  !> The first entry of directory dir that no run of sloshdyn wrote (not listed by its marker,
  !> or not a regular file), '' when there is none or dir does not exist; code: 0, or the
  !> errno of reading dir.
  subroutine foreign_entry(dir, name, code)
    character(len=*), intent(in) :: dir
    character(len=:), allocatable, intent(out) :: name
    integer, intent(out) :: code
    character(kind=c_char) :: found(name_room)
    code = c_foreign_entry(dir//c_null_char, MARKER_HEADER//new_line('a')//c_null_char, found, &
                           name_room)
    name = from_c(found)
    if (code == 1) code = 0
  end subroutine foreign_entry

  !> Remove a run's directory: the files its marker lists (all its files when all: the run's
  !> own new directory), the marker, the directory; anything else is left, with the directory.
  subroutine remove_run_directory(dir, all)
    character(len=*), intent(in) :: dir
    logical, intent(in) :: all
    integer(c_int) :: ignored
    ignored = c_remove_run_directory(dir//c_null_char, MARKER_HEADER//new_line('a')// &
                                     c_null_char, merge(1_c_int, 0_c_int, all))
  end subroutine remove_run_directory

  !> Put the run's new directory staging (complete, with its marker) in the place of target,
  !> the previous run's directory removed (sloshdyn_run_directory.c). code: 0; 1 when target
  !> holds `foreign`, which no run wrote (refused); otherwise the errno of the failed step.
  subroutine swap_into_place(staging, target, previous_prefix, foreign, code)
    character(len=*), intent(in) :: staging, target, previous_prefix
    character(len=:), allocatable, intent(out) :: foreign
    integer, intent(out) :: code
    character(kind=c_char) :: found(name_room)
    code = c_swap_into_place(staging//c_null_char, target//c_null_char, &
                             previous_prefix//'XXXXXX'//c_null_char, &
                             MARKER_HEADER//new_line('a')//c_null_char, found, name_room)
    foreign = from_c(found)
  end subroutine swap_into_place

  !> All of standard input, read once (later calls return the same text: both doors read an
  !> input file more than once); ok = it was read to its end within max_bytes.
  subroutine standard_input_text(max_bytes, text, ok)
    integer(int64), intent(in) :: max_bytes
    character(len=:), allocatable, intent(out) :: text
    logical, intent(out) :: ok
    character(len=:), allocatable, save :: kept
    logical, save :: done = .false., kept_ok = .false.
    integer, parameter :: chunk = 65536
    character(kind=c_char) :: buffer(chunk)
    character(len=:), allocatable :: grown
    integer(c_ptrdiff_t) :: n
    integer(int64) :: used
    integer :: i
    if (.not. done) then
      done = .true.
      allocate (character(len=chunk) :: kept)
      used = 0
      kept_ok = .false.
      do
        n = c_read(0_c_int, buffer, int(chunk, c_size_t))
        if (n < 0 .or. used + n > max_bytes) exit
        if (n == 0) then
          kept_ok = .true.
          exit
        end if
        if (used + n > len(kept)) then
          allocate (character(len=2*len(kept)) :: grown)
          grown(1:used) = kept(1:used)
          call move_alloc(grown, kept)
        end if
        do i = 1, int(n)
          kept(used + i:used + i) = buffer(i)
        end do
        used = used + n
      end do
      kept = kept(1:used)
    end if
    text = kept
    ok = kept_ok
  end subroutine standard_input_text

  !> Whether path is a symbolic link (not followed).
  logical function is_link(path)
    character(len=*), intent(in) :: path
    is_link = c_is_link(path//c_null_char) /= 0
  end function is_link

  !> What errno code means.
  function error_text(code) result(text)
    integer, intent(in) :: code
    character(len=:), allocatable :: text
    character(kind=c_char) :: buffer(256)
    call c_error_text(int(code, c_int), buffer, 256_c_int)
    text = from_c(buffer)
  end function error_text

  subroutine to_c(text, chars)
    character(len=*), intent(in) :: text
    character(kind=c_char), intent(out) :: chars(:)
    integer :: i
    do i = 1, len(text)
      chars(i) = text(i:i)
    end do
    chars(len(text) + 1) = c_null_char
  end subroutine to_c

  !> A NUL-terminated C string as Fortran text.
  function from_c(chars) result(text)
    character(kind=c_char), intent(in) :: chars(:)
    character(len=:), allocatable :: text
    integer :: i, n
    n = 0
    do i = 1, size(chars)
      if (chars(i) == c_null_char) exit
      n = i
    end do
    allocate (character(len=n) :: text)
    do i = 1, n
      text(i:i) = chars(i)
    end do
  end function from_c

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
