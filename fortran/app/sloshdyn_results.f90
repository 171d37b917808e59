!> The result files of one run, all or nothing, by the run-directory rule of docs/failure.md:
!> a run writes into a new directory of its own beside its output directory (PARENT/
!> .NAME.run-PID-XXXXXX, mkdtemp), and commit swaps it into place whole, with its marker
!> (.sloshdyn-run, listing the run's files), the previous run's directory removed; an output
!> directory holding anything that no run wrote is refused by name (check_output_directory),
!> so an input can never be in it. Sloshdyn-py gives a directory it made itself (staging) and
!> swaps it by the same rule (python/sloshdyn/_files.py). In the run's directory each table is
!> written as CSV under a temporary name (.name.XXXXXX, mkstemp: created new), every open,
!> write and close checked and the size on disk compared with the bytes written (gfortran does
!> not report a full disk on write or close: the file is just shorter); commit renames them to
!> their names; discard removes the run's directory. A cancellation requested before commit
!> (Ctrl-C, SIGTERM) discards the run. Headers and column formats come from sloshdyn_tables, so
!> both front doors write the same files.
!>
!> A table whose rows come one after another as a long computation finishes them (a sweep's
!> points) is written to stem.partial.ext in the run's directory (begin_rows, created new),
!> each batch appended and flushed as it is done (append_rows), and renamed to its final name
!> by commit like the others; discard keeps it: the run's directory, holding only it, is
!> swapped into place, so a failed run leaves the rows it finished (a killed one, in its hidden
!> directory).
module sloshdyn_results
  use, intrinsic :: iso_fortran_env, only: int64
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_IO_ERROR
  use sloshdyn_cancel, only: check_cancel, cancel_signal
  use sloshdyn_text, only: num2str
  use sloshdyn_tables, only: table_header, table_formats, code_name
  use sloshdyn_files, only: make_directory, rename_file, remove_file, unique_file, create_new, &
                            temporary_directory, foreign_entry, remove_run_directory, &
                            swap_into_place, error_text, file_type, is_link, process_id, &
                            FILE_MISSING, FILE_DIRECTORY, RUN_MARKER, MARKER_HEADER
  implicit none
  private
  public :: result_files, check_output_directory

  !> Rows written between two polls of the cancellation flag.
  integer, parameter :: rows_per_poll = 4096

  type :: pending_file
    character(len=:), allocatable :: final, temporary, name   !< name: in the output directory
    logical :: keep = .false.      !< rows of a partial table: kept by discard
  end type pending_file

  type :: result_files
    !> the output directory (as given: in messages), and the run's own directory where the
    !> files are written (staged: one that sloshdyn-py made and swaps into place itself)
    character(len=:), allocatable :: target, directory
    logical :: staged = .false.
    type(pending_file), allocatable :: files(:)
  contains
    procedure :: create => create_directory
    procedure :: write_table
    procedure :: write_text
    procedure, private :: open_pending
    procedure, private :: close_pending
    procedure :: begin_rows
    procedure :: append_rows
    procedure :: partial_path
    procedure :: commit
    procedure :: discard
    procedure, private :: swap
  end type result_files

contains

  !> Refuse an output directory that a run may not take (status SD_IO_ERROR, the message
  !> naming it and why): something else than a directory (a symbolic link included), or a
  !> directory holding an entry that no run of sloshdyn wrote.
  subroutine check_output_directory(directory, status, message)
    character(len=*), intent(in) :: directory
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    character(len=:), allocatable :: foreign, last
    integer :: kind, code
    integer(int64) :: size
    status = SD_OK
    message = ''
    last = strip_slashes(directory)
    last = last(index(last, '/', back=.true.) + 1:)
    if (last == '.' .or. last == '..' .or. last == '') then
      status = SD_IO_ERROR
      message = 'cannot write into '''//directory//''': a run replaces its output directory '// &
                'whole, so it must be named (e.g. ''out''), not . or .. or /'
      return
    end if
    call file_type(directory, kind, size)
    if ((kind /= FILE_MISSING .and. kind /= FILE_DIRECTORY) .or. is_link(directory)) then
      status = SD_IO_ERROR
      message = 'cannot write into '''//directory//''': it is not a directory'
      if (is_link(directory)) message = trim(message)//' but a symbolic link'
      return
    end if
    call foreign_entry(directory, foreign, code)
    if (code /= 0) then
      status = SD_IO_ERROR
      message = 'cannot read the output directory '''//directory//''': '//error_text(code)
    else if (len(foreign) > 0) then
      status = SD_IO_ERROR
      message = 'cannot write into '''//directory//''': it holds '''//foreign//''', which no '// &
                'sloshdyn run wrote (an output directory belongs to a run and is replaced '// &
                'whole: give a new directory, or one a run wrote; its '//RUN_MARKER// &
                ' lists the run''s files)'
    end if
  end subroutine check_output_directory

  !> Start the run's files for output directory `directory`: checked, its parents created, and
  !> the run's own new directory beside it. When staged (sloshdyn-py set directory to a new
  !> directory that it made and swaps into place itself) the files go there instead.
  subroutine create_directory(self, directory, status, message)
    class(result_files), intent(inout) :: self
    character(len=*), intent(in) :: directory
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    logical :: ok
    integer :: code
    status = SD_OK
    message = ''
    self%target = strip_slashes(trim(directory))
    allocate (self%files(0))
    if (self%staged) return
    call check_output_directory(self%target, status, message)
    if (status /= SD_OK) return
    call make_directory(parent(self%target), ok)
    code = 0
    if (ok) call temporary_directory(beside(self%target, 'run'), self%directory, code)
    if (.not. ok .or. code /= 0) then
      status = SD_IO_ERROR
      message = 'cannot write into '''//self%target//''': cannot create its new directory in '''// &
                parent(self%target)//''''
      if (code /= 0) message = trim(message)//': '//error_text(code)
    end if
  end subroutine create_directory

  !> The prefix of a run's hidden directory beside `target` (PARENT/.NAME.what-PID-).
  function beside(target, what) result(prefix)
    character(len=*), intent(in) :: target, what
    character(len=:), allocatable :: prefix
    integer :: slash
    slash = index(target, '/', back=.true.)
    prefix = target(1:slash)//'.'//target(slash + 1:)//'.'//what//'-'//num2str(process_id())//'-'
  end function beside

  !> The folder that holds path ('.' for a bare name).
  function parent(path) result(folder)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: folder
    integer :: slash
    slash = index(path, '/', back=.true.)
    if (slash == 0) then
      folder = '.'
    else if (slash == 1) then
      folder = '/'
    else
      folder = path(1:slash - 1)
    end if
  end function parent

  !> path without trailing slashes (the root kept).
  function strip_slashes(path) result(stripped)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: stripped
    stripped = path
    do while (len(stripped) > 1)
      if (stripped(len(stripped):) /= '/') exit
      stripped = stripped(1:len(stripped) - 1)
    end do
  end function strip_slashes

  !> Write data (one column of the array per row of the file) as table `table` into file `name`
  !> under its temporary name.
  subroutine write_table(self, name, table, data, status, message)
    class(result_files), intent(inout) :: self
    character(len=*), intent(in) :: name, table
    real(wp), intent(in) :: data(:, :)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    character(len=message_len) :: iomsg
    integer :: unit, ios
    integer(int64) :: bytes, rows_bytes

    call self%open_pending(name, unit, ios, iomsg, status, message)
    if (status /= SD_OK) return
    if (ios == 0) write (unit, '(a)', iostat=ios, iomsg=iomsg) table_header(table)
    bytes = len(table_header(table)) + 1
    rows_bytes = 0
    if (ios == 0) call write_rows(unit, table, data, rows_bytes, ios, iomsg)
    call self%close_pending(unit, bytes + rows_bytes, ios, iomsg, status, message)
  end subroutine write_table

  !> Write lines of text (a header and rows made by the caller) into file `name` under its
  !> temporary name, committed with the tables.
  subroutine write_text(self, name, lines, status, message)
    class(result_files), intent(inout) :: self
    character(len=*), intent(in) :: name, lines(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    character(len=message_len) :: iomsg
    integer :: unit, ios, i
    integer(int64) :: bytes

    call self%open_pending(name, unit, ios, iomsg, status, message)
    if (status /= SD_OK) return
    bytes = 0
    do i = 1, size(lines)
      if (ios == 0) write (unit, '(a)', iostat=ios, iomsg=iomsg) trim(lines(i))
      bytes = bytes + len_trim(lines(i)) + 1
    end do
    call self%close_pending(unit, bytes, ios, iomsg, status, message)
  end subroutine write_text

  !> Open a new temporary file for file `name` (registered for commit), on unit.
  subroutine open_pending(self, name, unit, ios, iomsg, status, message)
    class(result_files), intent(inout) :: self
    character(len=*), intent(in) :: name
    integer, intent(out) :: unit, ios, status
    character(len=message_len), intent(out) :: iomsg, message
    type(pending_file) :: file
    status = SD_OK
    message = ''
    iomsg = ''
    ios = 0
    unit = -1
    file%final = self%directory//'/'//name
    file%name = name
    call unique_file(self%directory//'/.'//name//'.', file%temporary)
    if (len(file%temporary) == 0) then
      status = SD_IO_ERROR
      message = 'cannot write '//self%target//'/'//name//': cannot create a temporary file in '// &
                self%target
      return
    end if
    self%files = [self%files, file]
    open (newunit=unit, file=file%temporary, status='old', action='write', iostat=ios, &
          iomsg=iomsg)
  end subroutine open_pending

  !> Close the last pending file's unit, checking that bytes reached the disk.
  subroutine close_pending(self, unit, bytes, ios, iomsg, status, message)
    class(result_files), intent(inout) :: self
    integer, intent(in) :: unit
    integer(int64), intent(in) :: bytes
    integer, intent(inout) :: ios
    character(len=message_len), intent(inout) :: iomsg
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    associate (file => self%files(size(self%files)))
      call close_checked(unit, file%temporary, bytes, ios, iomsg)
      status = SD_OK
      message = ''
      if (ios /= 0) then
        status = SD_IO_ERROR
        message = 'cannot write '//self%target//'/'//file%name//': '//trim(iomsg)
      end if
    end associate
  end subroutine close_pending

  !> Close unit (if ios = 0 so far) and check that file `path` holds `bytes` bytes: a write that
  !> failed for want of space shows as a shorter file.
  subroutine close_checked(unit, path, bytes, ios, iomsg)
    integer, intent(in) :: unit
    character(len=*), intent(in) :: path
    integer(int64), intent(in) :: bytes
    integer, intent(inout) :: ios
    character(len=message_len), intent(inout) :: iomsg
    integer(int64) :: size_on_disk
    if (ios /= 0) then
      close (unit)
      return
    end if
    close (unit, iostat=ios, iomsg=iomsg)
    if (ios /= 0) return
    inquire (file=path, size=size_on_disk)
    if (size_on_disk /= bytes) then
      ios = -1
      write (iomsg, '(a, i0, a, i0, a)') 'only ', size_on_disk, ' of ', bytes, ' bytes '// &
        'reached the disk (is it full, or over a size limit?)'
    end if
  end subroutine close_checked

  !> The rows of data (one column of the array per row of the file) in table's formats.
  subroutine write_rows(unit, table, data, bytes, ios, iomsg)
    integer, intent(in) :: unit
    character(len=*), intent(in) :: table
    real(wp), intent(in) :: data(:, :)
    integer(int64), intent(out) :: bytes   !< written, newlines included
    integer, intent(out) :: ios
    character(len=message_len), intent(inout) :: iomsg
    character(len=:), allocatable :: formats, line
    character(len=32) :: field
    integer :: i, j, length
    ios = 0
    bytes = 0
    formats = table_formats(table)
    allocate (character(len=33*size(data, 1)) :: line)
    do j = 1, size(data, 2)
      length = 0
      do i = 1, size(data, 1)
        select case (formats(i:i))
        case ('i')
          write (field, '(i0)') nint(data(i, j))
        case ('s', 'v', 'c', 'o', 'k', 'd', 'e')
          field = code_name(formats(i:i), nint(data(i, j)))
        case default
          write (field, '(es24.16e3)') data(i, j)
        end select
        field = adjustl(field)
        if (i > 1) then
          length = length + 1
          line(length:length) = ','
        end if
        line(length + 1:length + len_trim(field)) = trim(field)
        length = length + len_trim(field)
      end do
      write (unit, '(a)', iostat=ios, iomsg=iomsg) line(1:length)
      if (ios /= 0) return
      bytes = bytes + length + 1
      if (mod(j, rows_per_poll) == 0 .and. cancel_signal() /= 0) then
        ios = -1          ! the caller discards the file; the run ends cancelled
        iomsg = 'stopped on request (Ctrl-C, SIGTERM or request_cancel)'
        return
      end if
    end do
  end subroutine write_rows

  !> Where the rows of table file `name` gather until commit: stem.partial.ext, in the run's
  !> directory (in_place: in the output directory, where a failed run leaves them).
  function partial_path(self, name, in_place) result(path)
    class(result_files), intent(in) :: self
    character(len=*), intent(in) :: name
    logical, intent(in), optional :: in_place
    character(len=:), allocatable :: path
    integer :: dot
    path = self%directory
    if (present(in_place)) then
      if (in_place) path = self%target
    end if
    dot = index(name, '.', back=.true.)
    if (dot == 0) then
      path = path//'/'//name//'.partial'
    else
      path = path//'/'//name(1:dot - 1)//'.partial'//name(dot:)
    end if
  end function partial_path

  !> Start the partial file of table `table` for file `name` (created new): its header, no rows
  !> yet.
  subroutine begin_rows(self, name, table, status, message)
    class(result_files), intent(inout) :: self
    character(len=*), intent(in) :: name, table
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    character(len=message_len) :: iomsg
    type(pending_file) :: file
    integer :: unit, ios, code
    status = SD_OK
    message = ''
    iomsg = ''
    file%final = self%directory//'/'//name
    file%name = name
    file%temporary = self%partial_path(name)
    file%keep = .true.
    call create_new(file%temporary, code)
    if (code /= 0) then
      status = SD_IO_ERROR
      message = 'cannot write '//self%partial_path(name, in_place=.true.)//': '//error_text(code)
      return
    end if
    self%files = [self%files, file]
    open (newunit=unit, file=file%temporary, status='old', action='write', iostat=ios, &
          iomsg=iomsg)
    if (ios == 0) write (unit, '(a)', iostat=ios, iomsg=iomsg) table_header(table)
    call close_checked(unit, file%temporary, len(table_header(table), int64) + 1, ios, iomsg)
    if (ios /= 0) then
      status = SD_IO_ERROR
      message = 'cannot write '//self%partial_path(name, in_place=.true.)//': '//trim(iomsg)
    end if
  end subroutine begin_rows

  !> Append rows to the partial file of `name` (begun by begin_rows); on disk when it returns.
  subroutine append_rows(self, name, table, data, status, message)
    class(result_files), intent(inout) :: self
    character(len=*), intent(in) :: name, table
    real(wp), intent(in) :: data(:, :)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    character(len=message_len) :: iomsg
    character(len=:), allocatable :: path
    integer :: unit, ios
    integer(int64) :: size_before, bytes
    status = SD_OK
    message = ''
    iomsg = ''
    path = self%partial_path(name)
    inquire (file=path, size=size_before)
    open (newunit=unit, file=path, status='old', position='append', action='write', &
          iostat=ios, iomsg=iomsg)
    if (ios == 0) call write_rows(unit, table, data, bytes, ios, iomsg)
    call close_checked(unit, path, size_before + bytes, ios, iomsg)
    if (ios /= 0) then
      status = SD_IO_ERROR
      message = 'cannot append to '//self%partial_path(name, in_place=.true.)//': '//trim(iomsg)
    end if
  end subroutine append_rows

  !> Rename every file to its name in the run's directory and swap that into place with its
  !> marker (staged: sloshdyn-py does), unless a cancellation is pending; if a step fails,
  !> nothing of the run is left under a final name.
  subroutine commit(self, status, message)
    class(result_files), intent(inout) :: self
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    integer :: i
    logical :: ok
    status = SD_OK
    message = ''
    call check_cancel(status, message)
    if (status /= SD_OK) then
      call self%discard()
      return
    end if
    do i = 1, size(self%files)
      call rename_file(self%files(i)%temporary, self%files(i)%final, ok)
      if (.not. ok) then
        status = SD_IO_ERROR
        message = 'cannot rename '//self%files(i)%temporary//' into '//self%files(i)%final// &
                  '; no result of this run is kept'
        self%files(:)%keep = .false.
        call self%discard()
        return
      end if
    end do
    if (.not. self%staged) call self%swap(status, message)
    deallocate (self%files)
    allocate (self%files(0))
  end subroutine commit

  !> Remove every file not yet committed; the rows of a partial table are kept: the run's
  !> directory, holding only them, takes the output directory's place.
  subroutine discard(self)
    class(result_files), intent(inout) :: self
    integer :: i, status
    character(len=message_len) :: message
    if (.not. allocated(self%files)) return
    do i = 1, size(self%files)
      if (.not. self%files(i)%keep) call remove_file(self%files(i)%temporary)
    end do
    if (.not. self%staged .and. allocated(self%directory)) then
      if (len(self%directory) == 0) then
        continue
      else if (any(self%files(:)%keep)) then
        self%files = pack(self%files, self%files(:)%keep)
        do i = 1, size(self%files)
          self%files(i)%name = self%partial_path(self%files(i)%name)
          self%files(i)%name = self%files(i)%name(index(self%files(i)%name, '/', back=.true.) &
                                                  + 1:)
        end do
        call self%swap(status, message)
      else
        call remove_run_directory(self%directory, all=.true.)
      end if
    end if
    deallocate (self%files)
    allocate (self%files(0))
  end subroutine discard

  !> Write the marker of the run's directory (the names of its files) and swap the directory
  !> into the output directory's place (sloshdyn_files' swap_into_place); on failure the run's
  !> directory is removed.
  subroutine swap(self, status, message)
    class(result_files), intent(inout) :: self
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    character(len=:), allocatable :: marker, foreign
    integer :: unit, ios, i, code
    logical :: ok
    status = SD_IO_ERROR
    call unique_file(self%directory//'/.marker.', marker)
    ios = -1
    if (len(marker) > 0) open (newunit=unit, file=marker, status='old', action='write', &
                               iostat=ios)
    if (ios == 0) write (unit, '(a)', iostat=ios) MARKER_HEADER
    do i = 1, size(self%files)
      if (ios == 0) write (unit, '(a)', iostat=ios) self%files(i)%name
    end do
    if (ios == 0) close (unit, iostat=ios)
    ok = ios == 0
    if (ok) call rename_file(marker, self%directory//'/'//RUN_MARKER, ok)
    if (.not. ok) then
      message = 'cannot write '//self%target//'/'//RUN_MARKER//'; no result of this run is kept'
      call remove_run_directory(self%directory, all=.true.)
      return
    end if
    call swap_into_place(self%directory, self%target, beside(self%target, 'previous'), &
                         foreign, code)
    if (code == 0) then
      status = SD_OK
      message = ''
      return
    end if
    if (code == 1) then
      call check_output_directory(self%target, status, message)
      if (status == SD_OK) message = 'cannot write into '''//self%target//''': it holds '''// &
                                     foreign//''', which no sloshdyn run wrote'
      status = SD_IO_ERROR
    else
      message = 'cannot put the run''s new directory in the place of '''//self%target// &
                ''': '//error_text(code)//'; no result of this run is kept'
    end if
    call remove_run_directory(self%directory, all=.true.)
  end subroutine swap
end module sloshdyn_results
