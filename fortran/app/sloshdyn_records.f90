!> Ground-motion record files: the PEER NGA .AT2 format and two-column (time, acceleration)
!> text/CSV files. Each reader returns the uniform time step dt [s] and the ground acceleration
!> in m/s^2 (g = 9.80665 m/s^2), or a status and a message naming the file, the line and what is
!> wrong. Files are opened read-only and never modified.
!>
!> .AT2 (PEER NGA): 4 header lines; the 4th gives the number of points and the step, in either
!> form "NPTS=  5590, DT=   .0050 SEC" (any spacing, blanks or tabs, either order, with or
!> without the unit) or, in older files, "5590   0.0050   NPTS, DT"; then the NPTS values in
!> units of g, several per line, separated by blanks (or commas).
!>
!> Two-column files: one sample per line, "time, acceleration" separated by commas, semicolons
!> or blanks (tabs included); blank lines and lines whose first non-blank character is # are
!> skipped, and so is the first other line when its first field is not a number (one line of
!> column names such as "time_s,accel_g"). The time step must be uniform: every step within
!> 1e-6 (relative) of the first; the dt returned is the mean step (t_last - t_first)/(n - 1).
!> The caller gives the units of the acceleration (UNITS_G, UNITS_M_S2, UNITS_CM_S2;
!> units_code maps their names).
!>
!> Only a regular file of at most 1 GiB is read (read_text): a FIFO, a device or a directory is
!> refused before it is opened. Messages quote at most 40 characters of the file, escaped.
module sloshdyn_records
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, SD_IO_ERROR
  use sloshdyn_text, only: num2str
  use sloshdyn_cancel, only: check_cancel
  use sloshdyn_namelist_scanner, only: lower
  use sloshdyn_files, only: file_type, FILE_MISSING, FILE_REGULAR, FILE_DIRECTORY, FILE_OTHER
  use sloshdyn_ground, only: check_ground, record_ground
  use, intrinsic :: iso_fortran_env, only: int64
  implicit none
  private
  public :: read_at2, read_two_column, load_record, units_code, units_factor
  public :: UNITS_G, UNITS_M_S2, UNITS_CM_S2, standard_gravity

  !> Units of an acceleration column.
  integer, parameter :: UNITS_G = 1, UNITS_M_S2 = 2, UNITS_CM_S2 = 3
  !> Standard gravity (CGPM 1901) for records in g [m/s^2].
  real(wp), parameter :: standard_gravity = 9.80665_wp
  !> Relative tolerance on the uniformity of the time step of two-column files.
  real(wp), parameter :: step_tolerance = 1.0e-6_wp
  !> The largest record file read [bytes]: 1 GiB, some 70 million samples of AT2 text.
  integer(int64), parameter :: max_record_bytes = 2_int64**30
  !> The most characters of a file's text quoted in a message, escaped (excerpt).
  integer, parameter :: excerpt_len = 40
  !> Lines read between two looks at the cancellation flag (a 1 GiB file has ~5e7 lines).
  integer, parameter :: lines_per_poll = 4096
  character(len=*), parameter :: separators = ' ,;'//char(9)
  character(len=*), parameter :: number_characters = '0123456789+-.eEdD'

contains

  !> Read a PEER NGA .AT2 record: dt [s] and accel [m/s^2] (the file's values in g times
  !> standard_gravity). accel is unallocated on failure.
  subroutine read_at2(path, dt, accel, status, message)
    character(len=*), intent(in) :: path
    real(wp), intent(out) :: dt
    real(wp), allocatable, intent(out) :: accel(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    character(len=:), allocatable :: text
    integer :: position, first, last, line_number, npts, count, values_start
    logical :: found

    dt = 0
    call read_text(path, text, status, message)
    if (status /= SD_OK) return
    position = 1
    do line_number = 1, 4
      call next_line(text, position, first, last, found)
      if (.not. found) then
        call fail(SD_BAD_INPUT, path, line_number, 'the file ends before the 4 header lines '// &
                  'of an AT2 record (the 4th gives NPTS and DT)', status, message)
        return
      end if
    end do
    call parse_at2_header(text(first:last), npts, dt, status, message)
    if (status /= SD_OK) then
      message = located(path, 4, trim(message))
      return
    end if
    values_start = position
    call scan_values(text, values_start, 5, path, count, status, message)
    if (status /= SD_OK) return
    if (count /= npts) then
      call fail(SD_BAD_INPUT, path, 4, 'the header gives NPTS = '//num2str(npts)//' but the '// &
                'file has '//num2str(count)//' values after it', status, message)
      return
    end if
    if (count < 2) then
      call fail(SD_BAD_INPUT, path, 0, 'only '//num2str(count)//' sample(s): a record needs '// &
                'at least 2', status, message)
      return
    end if
    allocate (accel(count))
    call scan_values(text, values_start, 5, path, count, status, message, accel)
    accel = accel*standard_gravity
  end subroutine read_at2

  !> Read a two-column (time [s], acceleration) file; units: UNITS_G, UNITS_M_S2 or UNITS_CM_S2,
  !> the units of the acceleration column, converted to m/s^2. accel is unallocated on failure.
  subroutine read_two_column(path, units, dt, accel, status, message)
    character(len=*), intent(in) :: path
    integer, intent(in) :: units
    real(wp), intent(out) :: dt
    real(wp), allocatable, intent(out) :: accel(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    character(len=:), allocatable :: text
    real(wp), allocatable :: time(:)
    real(wp) :: factor
    integer :: count

    dt = 0
    call units_factor(units, factor, status, message)
    if (status /= SD_OK) return
    call read_text(path, text, status, message)
    if (status /= SD_OK) return
    call scan_columns(text, path, count, status, message)
    if (status /= SD_OK) return
    if (count < 2) then
      call fail(SD_BAD_INPUT, path, 0, 'only '//num2str(count)//' sample(s): a record needs '// &
                'at least 2', status, message)
      return
    end if
    allocate (time(count), accel(count))
    call scan_columns(text, path, count, status, message, time, accel)
    if (status /= SD_OK) then
      deallocate (accel)
      return
    end if
    dt = (time(count) - time(1))/(count - 1)
    accel = accel*factor
  end subroutine read_two_column

  !> Read a record file by its format: 'at2' (PEER NGA, in g), 'columns' (time, acceleration in
  !> the given units) or 'auto' (.AT2 by its extension, any case; otherwise columns), and check
  !> the rules of a record (sloshdyn_ground's check_ground: its step and duration). The
  !> acceleration in m/s^2; unallocated on failure.
  subroutine load_record(path, format, units, dt, accel, status, message)
    character(len=*), intent(in) :: path, format, units
    real(wp), intent(out) :: dt
    real(wp), allocatable, intent(out) :: accel(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    character(len=:), allocatable :: kind
    integer :: code
    dt = 0
    call units_code(units, code, status, message)
    if (status /= SD_OK) return
    kind = lower(trim(adjustl(format)))
    if (kind == 'auto') then
      kind = 'columns'
      if (len_trim(path) > 4) then
        if (lower(path(len_trim(path) - 3:len_trim(path))) == '.at2') kind = 'at2'
      end if
    end if
    select case (kind)
    case ('at2')
      call read_at2(path, dt, accel, status, message)
    case ('columns')
      call read_two_column(path, code, dt, accel, status, message)
    case default
      status = SD_BAD_INPUT
      message = 'format = '''//trim(adjustl(format))//''' is not known: use auto, at2 or columns'
    end select
    if (status /= SD_OK) return
    ! the rules of a record (its step and duration), named with the file
    call check_ground(record_ground(dt, accel), status, message)
    if (status /= SD_OK) then
      message = located(path, 0, trim(message))
      deallocate (accel)
    end if
  end subroutine load_record

  !> The units code of a name: 'g'; 'm/s^2' (also 'm/s2', 'm/s**2'); 'cm/s^2' (also 'cm/s2',
  !> 'cm/s**2', 'gal'); any case, surrounding blanks ignored.
  pure subroutine units_code(name, code, status, message)
    character(len=*), intent(in) :: name
    integer, intent(out) :: code
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    status = SD_OK
    message = ''
    select case (lower(trim(adjustl(name))))
    case ('g')
      code = UNITS_G
    case ('m/s^2', 'm/s2', 'm/s**2')
      code = UNITS_M_S2
    case ('cm/s^2', 'cm/s2', 'cm/s**2', 'gal')
      code = UNITS_CM_S2
    case default
      code = 0
      status = SD_BAD_INPUT
      message = 'units = '''//trim(adjustl(name))//''' is unknown: use g, m/s^2 or cm/s^2'
    end select
  end subroutine units_code

  !> The factor that turns an acceleration in the given units into m/s^2.
  pure subroutine units_factor(units, factor, status, message)
    integer, intent(in) :: units
    real(wp), intent(out) :: factor
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    status = SD_OK
    message = ''
    select case (units)
    case (UNITS_G)
      factor = standard_gravity
    case (UNITS_M_S2)
      factor = 1
    case (UNITS_CM_S2)
      factor = 0.01_wp
    case default
      factor = 0
      status = SD_BAD_INPUT
      message = 'units = '//num2str(units)//' is unknown: use UNITS_G (1, g), UNITS_M_S2 '// &
                '(2, m/s^2) or UNITS_CM_S2 (3, cm/s^2)'
    end select
  end subroutine units_factor

  !> NPTS and DT from the 4th header line of an AT2 file (message without the location).
  pure subroutine parse_at2_header(line, npts, dt, status, message)
    character(len=*), intent(in) :: line
    integer, intent(out) :: npts
    real(wp), intent(out) :: dt
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    character(len=:), allocatable :: low, npts_text, dt_text
    character(len=*), parameter :: expected = ' (expected e.g. "NPTS=  5590, DT=   .0050 SEC"'// &
                                              ' or "5590  .0050  NPTS, DT")'
    integer :: ios, after_npts, after_dt

    status = SD_OK
    message = ''
    npts = -1
    dt = 0
    low = lower(line)     ! the keys in any case; number_characters has both exponent cases
    if (value_after(low, 'npts') /= '' .or. value_after(low, 'dt') /= '') then
      npts_text = value_after(low, 'npts')
      dt_text = value_after(low, 'dt')
    else
      ! older form: "5590   0.0050   NPTS, DT"
      call next_token(low, 1, npts_text, after_npts)
      call next_token(low, after_npts, dt_text, after_dt)
    end if
    ios = 1
    if (len(npts_text) > 0 .and. verify(npts_text, '0123456789') == 0) &
      read (npts_text, *, iostat=ios) npts
    if (ios /= 0) then
      status = SD_BAD_INPUT
      message = 'malformed AT2 header: no number of points NPTS in '//excerpt(trim(line))//expected
      return
    end if
    ios = 1
    if (len(dt_text) > 0 .and. verify(dt_text, number_characters) == 0) &
      read (dt_text, *, iostat=ios) dt
    if (ios /= 0 .or. .not. (dt > 0 .and. dt <= huge(dt))) then
      status = SD_BAD_INPUT
      message = 'malformed AT2 header: no time step DT > 0 in '//excerpt(trim(line))//expected
    end if
  end subroutine parse_at2_header

  !> The number text after "key =" (blanks or tabs allowed around =), '' if key = is absent.
  !> The text ends at the first character that cannot be part of a number.
  pure function value_after(line, key) result(text)
    character(len=*), intent(in) :: line, key
    character(len=:), allocatable :: text
    character(len=*), parameter :: blanks = ' '//char(9)
    integer :: start, i, equals
    text = ''
    start = 1
    do
      i = index(line(start:), key)
      if (i == 0) return
      i = start + i - 1 + len(key)
      equals = verify(line(i:), blanks)
      if (equals > 0) then
        equals = i + equals - 1
        if (line(equals:equals) == '=') exit
      end if
      start = i
    end do
    i = equals + 1
    do while (i <= len(line))
      if (index(blanks, line(i:i)) == 0) exit
      i = i + 1
    end do
    start = i
    do while (i <= len(line))
      if (index(number_characters, line(i:i)) == 0) exit
      i = i + 1
    end do
    text = line(start:i - 1)
  end function value_after

  !> The token (separated by blanks, tabs, commas or semicolons) starting at or after position
  !> from of line, '' if none; after = the position just past it.
  pure subroutine next_token(line, from, text, after)
    character(len=*), intent(in) :: line
    integer, intent(in) :: from
    character(len=:), allocatable, intent(out) :: text
    integer, intent(out) :: after
    integer :: start, stop
    text = ''
    after = len(line) + 1
    if (from > len(line)) return
    start = verify(line(from:), separators)
    if (start == 0) return
    start = from + start - 1
    stop = scan(line(start:), separators)
    if (stop == 0) then
      stop = len(line)
    else
      stop = start + stop - 2
    end if
    text = line(start:stop)
    after = stop + 1
  end subroutine next_token

  !> Count (and store, if values is present) the numbers of text from position start on,
  !> separated by blanks or commas; first_line = the line number at start (for messages).
  subroutine scan_values(text, start, first_line, path, count, status, message, values)
    character(len=*), intent(in) :: text, path
    integer, intent(in) :: start, first_line
    integer, intent(out) :: count
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), intent(out), optional :: values(:)
    integer :: position, first, last, line_number, from, after
    character(len=:), allocatable :: token
    real(wp) :: value
    logical :: found

    status = SD_OK
    message = ''
    count = 0
    position = start
    line_number = first_line - 1
    do
      call next_counted_line(text, position, first, last, line_number, found, status, message)
      if (status /= SD_OK) return
      if (.not. found) exit
      from = first
      do
        call next_token(text(1:last), from, token, after)
        if (len(token) == 0) exit
        call parse_number(token, value, status, message)
        if (status /= SD_OK) then
          message = located(path, line_number, 'value '//num2str(count + 1)//': '//trim(message))
          return
        end if
        count = count + 1
        if (present(values)) values(count) = value
        from = after
      end do
    end do
  end subroutine scan_values

  !> Count (and store, if time and accel are present) the samples of a two-column file, checking
  !> the form of every line and, when storing, that time increases in uniform steps.
  subroutine scan_columns(text, path, count, status, message, time, accel)
    character(len=*), intent(in) :: text, path
    integer, intent(out) :: count
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), intent(out), optional :: time(:), accel(:)
    integer :: position, first, last, line_number, from, after, n_tokens, lead
    character(len=:), allocatable :: token
    real(wp) :: pair(2), step, first_step
    logical :: found, first_line

    status = SD_OK
    message = ''
    count = 0
    position = 1
    line_number = 0
    first_step = 0
    first_line = .true.
    do
      call next_counted_line(text, position, first, last, line_number, found, status, message)
      if (status /= SD_OK) return
      if (.not. found) exit
      lead = verify(text(first:last), separators(1:1)//char(9))
      if (lead == 0) cycle                                   ! blank line
      if (text(first + lead - 1:first + lead - 1) == '#') cycle   ! comment line
      if (first_line) then
        first_line = .false.
        call next_token(text(1:last), first, token, after)
        if (is_header(text(first:last), token)) cycle        ! column names: time_s,accel_g
      end if
      n_tokens = 0
      from = first
      do
        call next_token(text(1:last), from, token, after)
        if (len(token) == 0) exit
        n_tokens = n_tokens + 1
        if (n_tokens <= 2) then
          call parse_number(token, pair(n_tokens), status, message)
          if (status /= SD_OK) then
            message = located(path, line_number, trim(merge('time        ', &
                              'acceleration', n_tokens == 1))//': '//trim(message))
            return
          end if
        end if
        from = after
      end do
      if (n_tokens /= 2) then
        call fail(SD_BAD_INPUT, path, line_number, 'expected 2 values (time, acceleration), '// &
                  'found '//num2str(n_tokens), status, message)
        return
      end if
      count = count + 1
      if (.not. present(time)) cycle
      time(count) = pair(1)
      accel(count) = pair(2)
      if (count < 2) cycle
      step = time(count) - time(count - 1)
      if (.not. step > 0) then
        call fail(SD_BAD_INPUT, path, line_number, 'time does not increase: t = '// &
                  num2str(time(count))//' s after t = '//num2str(time(count - 1))//' s', &
                  status, message)
        return
      end if
      if (count == 2) first_step = step
      if (abs(step - first_step) > step_tolerance*first_step) then
        call fail(SD_BAD_INPUT, path, line_number, 'non-uniform time step: '//num2str(step)// &
                  ' s from t = '//num2str(time(count - 1))//' s, but the first step is '// &
                  num2str(first_step)//' s (tolerance 1e-6 relative)', status, message)
        return
      end if
    end do
  end subroutine scan_columns

  !> Whether the first line of a two-column file names the columns (time_s,accel_g) rather
  !> than giving a sample: text without control characters whose first field is not a number,
  !> nor a NaN or an infinity (errors, as binary junk is).
  logical function is_header(line, token)
    character(len=*), intent(in) :: line, token
    real(wp) :: value
    integer :: status, i, code
    character(len=message_len) :: message
    is_header = .false.
    do i = 1, len(line)
      code = modulo(ichar(line(i:i)), 256)
      if ((code < 32 .and. code /= 9) .or. code == 127) return
    end do
    if (index(lower(token), 'nan') > 0 .or. index(lower(token), 'inf') > 0) return
    call parse_number(token, value, status, message)
    is_header = status /= SD_OK
  end function is_header

  !> A finite real from a token of digits, signs, point and exponent letters; the message says
  !> what is wrong (NaN or infinite, not a number, out of range).
  subroutine parse_number(token, value, status, message)
    character(len=*), intent(in) :: token
    real(wp), intent(out) :: value
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    integer :: ios
    character(len=:), allocatable :: word

    status = SD_OK
    message = ''
    value = 0
    word = lower(token)
    if (index(word, 'nan') > 0 .or. index(word, 'inf') > 0) then
      status = SD_BAD_INPUT
      message = excerpt(token)//' is not finite (NaN or infinite values are not allowed)'
      return
    end if
    ios = 1
    if (verify(token, number_characters) == 0 .and. scan(token, '0123456789') > 0) &
      read (token, *, iostat=ios) value
    if (ios /= 0) then
      status = SD_BAD_INPUT
      message = excerpt(token)//' is not a number'
    else if (.not. abs(value) <= huge(value)) then
      status = SD_BAD_INPUT
      message = excerpt(token)//' is out of range (not finite)'
    end if
  end subroutine parse_number

  !> The whole file as one string, read-only. Only a regular file of at most max_record_bytes
  !> is read: a missing file, a directory, a FIFO (opening it would wait for a writer) or a
  !> device (/dev/zero never ends) is refused before it is opened.
  subroutine read_text(path, text, status, message)
    character(len=*), intent(in) :: path
    character(len=:), allocatable, intent(out) :: text
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    character(len=message_len) :: iomsg
    integer :: unit, ios, kind
    integer(int64) :: file_size

    status = SD_OK
    message = ''
    if (len_trim(path) < len(path)) then
      ! Fortran pads names with blanks: 'a.AT2 ' would open a.AT2, another file
      call fail(SD_BAD_INPUT, path, 0, 'the name ends in a blank: a record file''s name must '// &
                'not end in blanks', status, message)
      return
    end if
    call file_type(path, kind, file_size)
    select case (kind)
    case (FILE_MISSING)
      call fail(SD_IO_ERROR, path, 0, 'no such file', status, message)
    case (FILE_DIRECTORY)
      call fail(SD_IO_ERROR, path, 0, 'it is a directory, not a record file', status, message)
    case (FILE_OTHER)
      call fail(SD_IO_ERROR, path, 0, 'it is not a regular file (a FIFO, a device or a '// &
                'socket): only regular files are read as records', status, message)
    case (FILE_REGULAR)
      if (file_size > max_record_bytes) call fail(SD_IO_ERROR, path, 0, 'it has '// &
        num2str(real(file_size, wp))//' bytes, more than the 1 GiB ('// &
        num2str(real(max_record_bytes, wp))//' bytes) a record file may have', status, message)
    end select
    if (status /= SD_OK) return
    open (newunit=unit, file=path, status='old', action='read', access='stream', &
          form='unformatted', iostat=ios, iomsg=iomsg)
    if (ios /= 0) then
      call fail(SD_IO_ERROR, path, 0, 'cannot open it: '//trim(iomsg), status, message)
      return
    end if
    allocate (character(len=file_size) :: text)
    if (file_size > 0) then
      read (unit, iostat=ios, iomsg=iomsg) text
      if (ios /= 0) call fail(SD_IO_ERROR, path, 0, 'cannot read it: '//trim(iomsg), status, &
                              message)
    end if
    close (unit)
  end subroutine read_text

  !> The next line of text from position on (LF, CRLF or CR endings): text(first:last), with
  !> last = first - 1 for an empty line; position moves past the line ending; found is false
  !> at the end of the text.
  pure subroutine next_line(text, position, first, last, found)
    character(len=*), intent(in) :: text
    integer, intent(inout) :: position
    integer, intent(out) :: first, last
    logical, intent(out) :: found
    integer :: ending
    found = position <= len(text)
    first = position
    last = position - 1
    if (.not. found) return
    ending = scan(text(position:), char(10)//char(13))
    if (ending == 0) then
      last = len(text)
      position = len(text) + 1
    else
      last = position + ending - 2
      position = position + ending
      if (text(position - 1:position - 1) == char(13) .and. position <= len(text)) then
        if (text(position:position) == char(10)) position = position + 1
      end if
    end if
  end subroutine next_line

  !> next_line, counting the lines in line_number; every lines_per_poll lines it polls the
  !> cancellation flag (a long file: Ctrl-C and SIGTERM), status SD_CANCELLED.
  subroutine next_counted_line(text, position, first, last, line_number, found, status, message)
    character(len=*), intent(in) :: text
    integer, intent(inout) :: position, line_number
    integer, intent(out) :: first, last
    logical, intent(out) :: found
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    status = SD_OK
    message = ''
    call next_line(text, position, first, last, found)
    if (.not. found) return
    line_number = line_number + 1
    if (mod(line_number, lines_per_poll) == 0) call check_cancel(status, message)
  end subroutine next_counted_line

  pure subroutine fail(code, path, line_number, what, status, message)
    integer, intent(in) :: code, line_number
    character(len=*), intent(in) :: path, what
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    status = code
    message = located(path, line_number, what)
  end subroutine fail

  !> "record file 'path', line n: what" (no line for line_number 0).
  pure function located(path, line_number, what) result(text)
    character(len=*), intent(in) :: path, what
    integer, intent(in) :: line_number
    character(len=:), allocatable :: text
    text = 'record file '''//path//''''
    if (line_number > 0) text = text//', line '//num2str(line_number)
    text = text//': '//what
  end function located

  !> text quoted, at most about excerpt_len characters of quote ('...' after it when cut),
  !> every character outside printable ASCII shown as \xNN: a message never carries a file's
  !> raw bytes, and stays short.
  pure function excerpt(text) result(quoted)
    character(len=*), intent(in) :: text
    character(len=:), allocatable :: quoted
    character(len=*), parameter :: hex = '0123456789abcdef'
    integer :: i, code
    quoted = ''''
    do i = 1, len(text)
      if (len(quoted) > excerpt_len) exit
      code = modulo(ichar(text(i:i)), 256)
      if (code >= 32 .and. code <= 126) then
        quoted = quoted//text(i:i)
      else
        quoted = quoted//'\x'//hex(code/16 + 1:code/16 + 1)// &
                 hex(mod(code, 16) + 1:mod(code, 16) + 1)
      end if
    end do
    quoted = quoted//''''
    if (i <= len(text)) quoted = quoted//'...'
  end function excerpt
end module sloshdyn_records
