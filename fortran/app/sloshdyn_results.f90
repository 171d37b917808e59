!> The result files of one run, all or nothing: each table is written as CSV under a temporary
!> name unique to the run (dir/.name.XXXXXX, mkstemp), every open, write and close checked and
!> the size on disk compared with the bytes written (gfortran does not report a full disk on
!> write or close: the file is just shorter); commit renames them all into place once every one
!> is complete, and if a rename fails it removes the files it already renamed and the
!> temporaries; discard removes the temporaries. A cancellation requested before commit (Ctrl-C,
!> SIGTERM) discards the run. Headers and column formats come from sloshdyn_tables, so both
!> front doors write the same files.
!>
!> A table whose rows come one after another as a long computation finishes them (a sweep's
!> points) is written to dir/stem.partial.ext (begin_rows), each batch appended and flushed as
!> it is done (append_rows), and renamed to its final name by commit like the others; discard
!> keeps it, so a failed or killed run leaves the rows it finished.
module sloshdyn_results
  use, intrinsic :: iso_fortran_env, only: int64
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_IO_ERROR
  use sloshdyn_cancel, only: check_cancel, cancel_signal
  use sloshdyn_text, only: num2str
  use sloshdyn_tables, only: table_header, table_formats, code_name
  use sloshdyn_files, only: make_directory, rename_file, remove_file, unique_file
  implicit none
  private
  public :: result_files

  !> Rows written between two polls of the cancellation flag.
  integer, parameter :: rows_per_poll = 4096

  type :: pending_file
    character(len=:), allocatable :: final, temporary
    logical :: keep = .false.      !< rows of a partial table: kept by discard
  end type pending_file

  type :: result_files
    character(len=:), allocatable :: directory
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
  end type result_files

contains

  !> Create the output directory (with its parents).
  subroutine create_directory(self, directory, status, message)
    class(result_files), intent(inout) :: self
    character(len=*), intent(in) :: directory
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    logical :: ok
    status = SD_OK
    message = ''
    self%directory = trim(directory)
    allocate (self%files(0))
    call make_directory(self%directory, ok)
    if (.not. ok) then
      status = SD_IO_ERROR
      message = 'cannot create output directory '''//self%directory//''''
    end if
  end subroutine create_directory

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
    call unique_file(self%directory//'/.'//name//'.', file%temporary)
    if (len(file%temporary) == 0) then
      status = SD_IO_ERROR
      message = 'cannot write '//file%final//': cannot create a temporary file in '// &
                self%directory
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
        message = 'cannot write '//file%final//': '//trim(iomsg)
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

  !> Where the rows of table file `name` gather until commit: dir/stem.partial.ext.
  function partial_path(self, name) result(path)
    class(result_files), intent(in) :: self
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: path
    integer :: dot
    dot = index(name, '.', back=.true.)
    if (dot == 0) then
      path = self%directory//'/'//name//'.partial'
    else
      path = self%directory//'/'//name(1:dot - 1)//'.partial'//name(dot:)
    end if
  end function partial_path

  !> Start the partial file of table `table` for file `name`: its header, no rows yet.
  subroutine begin_rows(self, name, table, status, message)
    class(result_files), intent(inout) :: self
    character(len=*), intent(in) :: name, table
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    character(len=message_len) :: iomsg
    type(pending_file) :: file
    integer :: unit, ios
    status = SD_OK
    message = ''
    iomsg = ''
    file%final = self%directory//'/'//name
    file%temporary = self%partial_path(name)
    file%keep = .true.
    self%files = [self%files, file]
    open (newunit=unit, file=file%temporary, status='replace', action='write', iostat=ios, &
          iomsg=iomsg)
    if (ios == 0) write (unit, '(a)', iostat=ios, iomsg=iomsg) table_header(table)
    call close_checked(unit, file%temporary, len(table_header(table), int64) + 1, ios, iomsg)
    if (ios /= 0) then
      status = SD_IO_ERROR
      message = 'cannot write '//file%temporary//': '//trim(iomsg)
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
      message = 'cannot append to '//path//': '//trim(iomsg)
    end if
  end subroutine append_rows

  !> Rename every file into place, unless a cancellation is pending; if one rename fails, remove
  !> the files of this run already renamed and discard the rest: nothing of the run is left
  !> under a final name.
  subroutine commit(self, status, message)
    class(result_files), intent(inout) :: self
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    integer :: i, j
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
        do j = 1, i - 1
          call remove_file(self%files(j)%final)
        end do
        call self%discard()
        return
      end if
    end do
    deallocate (self%files)
    allocate (self%files(0))
  end subroutine commit

  !> Remove every file not yet committed.
  subroutine discard(self)
    class(result_files), intent(inout) :: self
    integer :: i
    if (.not. allocated(self%files)) return
    do i = 1, size(self%files)
      if (.not. self%files(i)%keep) call remove_file(self%files(i)%temporary)
    end do
    deallocate (self%files)
    allocate (self%files(0))
  end subroutine discard
end module sloshdyn_results
