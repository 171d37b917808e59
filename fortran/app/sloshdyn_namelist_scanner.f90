!> The namelist scanner: the generic text work of reading a namelist file, knowing nothing of
!> its groups but their names. scan_file splits the file into groups (any line length, several
!> groups on a line, comments, quotes) and rejects unknown, repeated or unclosed groups and text
!> outside groups; a group_reader then parses one group's text with the group's namelist read
!> and, if that fails, parses each assignment alone to name the culprit (sloshdyn_namelist_groups
!> holds the groups, sloshdyn_namelist the reader of a whole file).
!>
!> Every pass is linear in the length of the file: the body of a group is copied once, and the
!> positions of its assignments are found in one pass (with the next ')', '=' and non-blank
!> character of every position precomputed), so a line of megabytes costs no more per character
!> than a short one (tests/python/test_namelist_scanner.py).
module sloshdyn_namelist_scanner
  use, intrinsic :: iso_fortran_env, only: int64
  use sloshdyn_kinds, only: message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, SD_IO_ERROR
  use sloshdyn_text, only: num2str
  use sloshdyn_files, only: file_type, FILE_OTHER, standard_input_text
  implicit none
  private
  public :: input_file, group_reader, type_hint, scan_file, start_description, require, &
            given, list_length, fail, lower, join

  !> Longest group name.
  integer, parameter :: name_len = 32
  !> The longest input file read from standard input (-).
  integer(int64), parameter :: max_input_bytes = 256_int64*2**20
  !> Values tried on a variable whose value does not parse, to tell its type by which one the
  !> namelist read takes first (gfortran: a quoted string only for a character variable, .true.
  !> only for a logical one, 1.5 for a real one, 1 for an integer one; none: not a variable of
  !> the group).
  character(len=*), parameter :: PROBES(4) = ["'a'   ", ".true.", "1.5   ", "1     "]
  character(len=*), parameter :: PROBED_TYPES(4) = [character(len=24) :: 'a quoted string', &
                                                    '.true. or .false.', 'a real number', &
                                                    'an integer']

  abstract interface
    !> What a variable must be (for the message on a value that does not parse).
    pure function type_hint(name) result(text)
      character(len=*), intent(in) :: name
      character(len=:), allocatable :: text
    end function type_hint
  end interface

  !> The text of one group: its body between the name and the closing '/' (comments removed,
  !> lines joined), the line it starts on, the positions of its assignments in the body and the
  !> names of the variables they assign (',name1,name2,...,').
  type :: group_text
    logical :: given = .false.
    character(len=:), allocatable :: body, assigned
    integer, allocatable :: starts(:)
    integer :: line = 0
  end type group_text

  !> A scanned file: its groups, by the index of their name in `names`.
  type :: input_file
    character(len=:), allocatable :: path
    character(len=name_len), allocatable :: names(:)
    type(group_text), allocatable :: groups(:)
    !> describe instead of read: every group is written with its defaults into description
    logical :: describing = .false.
    character(len=:), allocatable :: description
  end type input_file

  !> Reading one group. The reader loop of every group is
  !>   call reader%start(file, G_X, status)
  !>   do while (reader%next())
  !>     if (reader%describing) then
  !>       write (reader%written, nml=x, iostat=reader%ios)
  !>     else
  !>       read (reader%text, nml=x, iostat=reader%ios, iomsg=reader%iomsg)
  !>     end if
  !>     call reader%check(file, status, message)
  !>   end do
  !> The whole group is parsed first; if it fails, each assignment alone, to name the culprit.
  !> Describing, the group is written with its values instead (namelist_defaults). The owner of
  !> the groups extends it with `hint`, what a variable must be, for messages.
  type, abstract :: group_reader
    integer :: group = 0, step = 0, line = 0, ios = 0
    !> the assignment parsed last (an index into starts) and the position of the next one in
    !> the body (0: none)
    integer :: current = 0, next_start = 0
    integer, allocatable :: starts(:)
    logical :: describing = .false., done = .true.
    character(len=:), allocatable :: name, body, path, text, assignment
    !> after an assignment that does not parse: the index of the PROBES value tried on its
    !> variable (0: none), which tells the variable's type (probed_type)
    integer :: probe = 0
    character(len=message_len) :: iomsg = ''
    character(len=8192) :: written = ''   !< the group written with its values
  contains
    procedure :: start => start_group
    procedure :: next => next_text
    procedure :: check => check_text
    procedure(type_hint), deferred, nopass :: hint
  end type group_reader

contains

  !> Split the file into its groups, whose names are `names` (retired(k), if given, is a name
  !> no longer read, refused with retired_hint(k)). Errors: a missing or unreadable file, text
  !> outside groups, unknown, retired, repeated or unclosed groups, no group at all.
  subroutine scan_file(path, names, file, status, message, retired, retired_hint)
    character(len=*), intent(in) :: path, names(:)
    type(input_file), intent(out) :: file
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    character(len=*), intent(in), optional :: retired(:), retired_hint(:)
    character(len=:), allocatable :: text, name, buffer
    integer :: i, k, n, line, group, start_line, name_start, filled
    logical :: inside_quotes
    character :: quote

    file%path = path
    file%names = names
    allocate (file%groups(size(names)))
    call read_text(path, text, status, message)
    if (status /= SD_OK) return
    n = len(text)
    allocate (character(len=n) :: buffer)
    i = 1
    line = 1
    do while (i <= n)
      select case (text(i:i))
      case (' ', char(9), char(13))
        i = i + 1
      case (char(10))
        line = line + 1
        i = i + 1
      case ('!')
        call skip_comment()
      case ('&', '$')
        ! a group: its name, then its body up to '/' (or &end) outside quotes
        start_line = line
        i = i + 1
        name_start = i
        do while (i <= n)
          if (.not. is_name_char(text(i:i))) exit
          i = i + 1
        end do
        name = lower(text(name_start:i - 1))
        group = 0
        do k = 1, size(names)
          if (names(k) == name) group = k
        end do
        if (len(name) == 0 .or. name == 'end') then
          call fail(status, message, 'a group name must follow & in '''//path//''' (line '// &
                    num2str(start_line)//')')
        else if (group == 0) then
          if (present(retired)) then
            do k = 1, size(retired)
              if (retired(k) == name) call fail(status, message, 'namelist group &'//name// &
                ' in '''//path//''' (line '//num2str(start_line)//') is no longer read: '// &
                trim(retired_hint(k)))
            end do
          end if
          call fail(status, message, 'unknown namelist group &'//name//' in '''//path// &
                    ''' (line '//num2str(start_line)//'); known groups: &'// &
                    join(names, ', &'))
        else if (file%groups(group)%given) then
          call fail(status, message, 'namelist group &'//name//' appears twice in '''//path// &
                    ''' (lines '//num2str(file%groups(group)%line)//' and '// &
                    num2str(start_line)//')')
        end if
        if (status /= SD_OK) return
        filled = 0
        inside_quotes = .false.
        quote = ' '
        do
          if (i > n) then
            call fail(status, message, 'namelist group &'//name//' in '''//path//''' (line '// &
                      num2str(start_line)//') is not closed: end it with /')
            return
          end if
          if (inside_quotes) then
            if (text(i:i) == quote) inside_quotes = .false.
          else if (text(i:i) == '"' .or. text(i:i) == '''') then
            inside_quotes = .true.
            quote = text(i:i)
          else if (text(i:i) == '!') then
            call skip_comment()
            call put(' ')
            cycle
          else if (text(i:i) == '/') then
            i = i + 1
            exit
          else if (text(i:i) == '&' .or. text(i:i) == '$') then
            ! &end (or $end, $) closes the group
            i = i + 1
            do while (i <= n)
              if (.not. is_name_char(text(i:i))) exit
              i = i + 1
            end do
            exit
          end if
          if (text(i:i) == char(10)) then
            line = line + 1
            call put(' ')
          else if (text(i:i) == char(9) .or. text(i:i) == char(13)) then
            call put(' ')
          else
            call put(text(i:i))
          end if
          i = i + 1
        end do
        associate (g => file%groups(group))
          g%given = .true.
          g%line = start_line
          g%body = buffer(1:filled)
          g%starts = assignment_starts(g%body)
          g%assigned = assignment_names(g%body, g%starts)
        end associate
      case default
        call fail(status, message, 'unexpected text '''//trim(next_word())//''' outside a '// &
                  'namelist group in '''//path//''' (line '//num2str(line)//'): groups start '// &
                  'with &name and end with /')
        return
      end select
    end do
    if (.not. any(file%groups%given)) &
      call fail(status, message, 'no namelist group found in '''//path//''' (expected &'// &
                trim(names(1))//' ... /)')

  contains

    !> The body grows by one character (in place: the buffer holds the whole file).
    subroutine put(ch)
      character, intent(in) :: ch
      filled = filled + 1
      buffer(filled:filled) = ch
    end subroutine put

    subroutine skip_comment()
      do while (i <= n)
        if (text(i:i) == char(10)) exit
        i = i + 1
      end do
    end subroutine skip_comment

    function next_word() result(word)
      character(len=:), allocatable :: word
      integer :: j
      j = i
      do while (j <= n .and. j < i + 40)
        if (text(j:j) == ' ' .or. text(j:j) == char(10) .or. text(j:j) == char(13)) exit
        j = j + 1
      end do
      word = text(i:j - 1)
    end function next_word
  end subroutine scan_file

  !> A file that describes its groups (`names`) instead of reading them: each group reader
  !> writes its group with its values into file%description.
  subroutine start_description(names, file)
    character(len=*), intent(in) :: names(:)
    type(input_file), intent(out) :: file
    file%names = names
    allocate (file%groups(size(names)))
    file%describing = .true.
    file%description = ''
  end subroutine start_description

  !> The whole file as one string.
  subroutine read_text(path, text, status, message)
    character(len=*), intent(in) :: path
    character(len=:), allocatable, intent(out) :: text   !< unallocated on failure
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    character(len=message_len) :: iomsg
    integer :: unit, ios, file_size, kind
    integer(int64) :: bytes
    logical :: exists

    status = SD_OK
    message = ''
    if (path == '-') then       ! standard input (its relative paths: to the current directory)
      call standard_input_text(max_input_bytes, text, exists)
      if (.not. exists) then
        status = SD_IO_ERROR
        message = 'cannot read the input file from standard input (-): a read error, or more '// &
                  'than '//num2str(int(max_input_bytes/2**20))//' MiB'
        deallocate (text)
      end if
      return
    end if
    inquire (file=path, exist=exists)
    if (exists) inquire (file=trim(path)//'/.', exist=exists)
    if (exists) then
      status = SD_IO_ERROR
      message = 'cannot read input file '''//path//''': it is a directory'
      return
    end if
    call file_type(path, kind, bytes)
    if (kind == FILE_OTHER) then   ! opening a FIFO waits for a writer; a device may never end
      status = SD_IO_ERROR
      message = 'cannot read input file '''//path//''': it is not a regular file (a FIFO, a '// &
                'device or a socket); give a file, or - for standard input'
      return
    end if
    open (newunit=unit, file=path, status='old', action='read', access='stream', &
          form='unformatted', iostat=ios, iomsg=iomsg)
    if (ios /= 0) then
      status = SD_IO_ERROR
      message = 'cannot open input file '''//path//''': '//trim(iomsg)
      return
    end if
    inquire (unit=unit, size=file_size)
    allocate (character(len=max(file_size, 0)) :: text)
    if (file_size > 0) then
      read (unit, iostat=ios, iomsg=iomsg) text
      if (ios /= 0) then
        status = SD_IO_ERROR
        message = 'cannot read input file '''//path//''': '//trim(iomsg)
      end if
    end if
    close (unit)
  end subroutine read_text

  ! ---- reading groups --------------------------------------------------------------------------

  !> Start reading group `group` of the file (nothing to read after an earlier failure).
  subroutine start_group(reader, file, group, status)
    class(group_reader), intent(out) :: reader
    type(input_file), intent(in) :: file
    integer, intent(in) :: group, status
    reader%group = group
    reader%name = trim(file%names(group))
    reader%describing = file%describing
    reader%done = status /= SD_OK
    if (.not. reader%done .and. .not. file%describing) reader%done = .not. file%groups(group)%given
    if (.not. file%describing .and. .not. reader%done) then
      reader%body = file%groups(group)%body
      reader%line = file%groups(group)%line
      reader%path = file%path
      reader%starts = file%groups(group)%starts
      reader%current = 0
      reader%next_start = next_of(reader)
    end if
  end subroutine start_group

  !> The position of the assignment after the current one, 0 if there is none.
  pure integer function next_of(reader) result(position)
    class(group_reader), intent(in) :: reader
    position = 0
    if (reader%current < size(reader%starts)) position = reader%starts(reader%current + 1)
  end function next_of

  !> Whether there is a text to parse (or, describing, the group to write): the whole group
  !> first; if that fails, each assignment alone, to name the one at fault.
  logical function next_text(reader)
    class(group_reader), intent(inout) :: reader
    integer :: start, next
    next_text = .false.
    if (reader%done) return
    next_text = .true.
    reader%step = reader%step + 1
    if (reader%probe > 0) then
      reader%text = '&'//reader%name//' '//variable_name(reader%assignment(1:index( &
                    reader%assignment, '=') - 1))//' = '//trim(PROBES(reader%probe))//' /'
    else if (reader%describing) then
      reader%text = ''
    else if (reader%step == 1) then
      reader%text = '&'//reader%name//' '//reader%body//' /'
    else
      start = reader%next_start
      reader%current = reader%current + 1
      next = next_of(reader)
      if (next > 0) then
        reader%assignment = trim(reader%body(start:next - 1))
      else
        reader%assignment = trim(reader%body(start:))
      end if
      ! the separator before the next assignment is not part of this one
      if (reader%assignment(len(reader%assignment):) == ',') &
        reader%assignment = trim(reader%assignment(:len(reader%assignment) - 1))
      reader%text = '&'//reader%name//' '//reader%assignment//' /'
      reader%next_start = next
    end if
  end function next_text

  !> The outcome of parsing the current text (reader%ios, reader%iomsg of the namelist read), or,
  !> describing, the group written with its values (reader%written).
  subroutine check_text(reader, file, status, message)
    class(group_reader), intent(inout) :: reader
    type(input_file), intent(inout) :: file
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    character(len=:), allocatable :: prefix, token
    integer :: equals

    if (reader%describing) then
      file%description = file%description//trim(reader%written)//new_line('a')
      reader%done = .true.
      return
    end if
    if (reader%probe > 0) then
      call check_probe(reader, status, message)
      return
    end if
    if (reader%step == 1) then
      reader%done = reader%ios == 0
      if (reader%done) return
      ! text before the first assignment is at fault, or else one of the assignments
      prefix = reader%body(1:merge(reader%next_start - 1, len(reader%body), &
                                   reader%next_start > 0))
      if (len_trim(prefix) > 0) then
        call fail(status, message, '&'//reader%name//" in '"//reader%path//"' (line "// &
                  num2str(reader%line)//"): unexpected text '"//trim(adjustl(prefix))// &
                  "' before the first assignment")
        reader%done = .true.
      end if
    else
      equals = index(reader%assignment, '=')
      token = bad_value(reader%assignment(equals + 1:))
      if (len(token) > 0) then
        call fail(status, message, '&'//reader%name//" in '"//reader%path//"': "// &
                  trim(adjustl(reader%assignment(1:equals - 1)))//' ='// &
                  trim(reader%assignment(equals + 1:))//": '"//token//"' is not a value "// &
                  "(a number or a quoted string; a variable needs 'name = value')")
        reader%done = .true.
      else if (reader%ios /= 0) then
        reader%probe = 1           ! what the variable is: check_probe
        return
      end if
    end if
    if (.not. reader%done .and. reader%next_start == 0) then
      ! every assignment parses alone, the group does not
      call fail(status, message, '&'//reader%name//" in '"//reader%path//"' cannot be read: "// &
                trim(reader%iomsg))
      reader%done = .true.
    end if
  end subroutine check_text

  !> The outcome of a probe of the variable of an assignment that does not parse: the first
  !> value the read takes tells its type; the message names the variable and what it must be
  !> (the group's own hint if it has one), or that the group has no such variable.
  subroutine check_probe(reader, status, message)
    class(group_reader), intent(inout) :: reader
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    character(len=:), allocatable :: name, must
    integer :: equals
    if (reader%ios /= 0 .and. reader%probe < size(PROBES)) then
      reader%probe = reader%probe + 1
      return
    end if
    equals = index(reader%assignment, '=')
    name = variable_name(reader%assignment(1:equals - 1))
    must = reader%hint(name)
    if (len(must) == 0 .and. reader%ios == 0) then
      must = name//' must be '//trim(PROBED_TYPES(reader%probe))
    else if (len(must) == 0) then
      must = 'unknown variable '''//name//''' (not one of &'//reader%name// &
             '; see the namelist reference, docs/namelist.md)'
    end if
    call fail(status, message, '&'//reader%name//" in '"//reader%path//"': "// &
              trim(adjustl(reader%assignment(1:equals - 1)))//' ='// &
              trim(reader%assignment(equals + 1:))//' is not valid: '//must)
    reader%done = .true.
  end subroutine check_probe

  !> A required variable must be assigned in its group (an explicit NaN is assigned, and fails
  !> its range check instead).
  subroutine require(file, group, name, status, message)
    type(input_file), intent(in) :: file
    integer, intent(in) :: group
    character(len=*), intent(in) :: name
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    if (status /= SD_OK .or. file%describing) return
    if (given(file, group, name)) return
    call fail(status, message, '&'//trim(file%names(group))//': required variable '//name// &
              ' is missing')
  end subroutine require

  !> Whether the file assigns the variable in the group.
  pure logical function given(file, group, name)
    type(input_file), intent(in) :: file
    integer, intent(in) :: group
    character(len=*), intent(in) :: name
    given = .false.
    if (file%groups(group)%given) given = index(file%groups(group)%assigned, ','//name//',') > 0
  end function given

  !> How many values the group's last assignment of the whole array `name` (no index) gives:
  !> its values separated by commas or blanks, r*value counting r times; -1 if the group has
  !> no such assignment (none, or only `name(i) = ...`).
  pure integer function list_length(file, group, name) result(n)
    type(input_file), intent(in) :: file
    integer, intent(in) :: group
    character(len=*), intent(in) :: name
    integer :: k, last, equals
    n = -1
    if (file%describing .or. .not. allocated(file%groups)) return
    if (.not. file%groups(group)%given) return
    associate (g => file%groups(group))
      do k = 1, size(g%starts)
        last = len(g%body)
        if (k < size(g%starts)) last = g%starts(k + 1) - 1
        equals = g%starts(k) + index(g%body(g%starts(k):last), '=') - 1
        if (lower(trim(adjustl(g%body(g%starts(k):equals - 1)))) == name) &
          n = count_values(g%body(equals + 1:last))
      end do
    end associate
  end function list_length

  pure subroutine fail(status, message, text)
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    character(len=*), intent(in) :: text
    if (status /= SD_OK) return
    status = SD_BAD_INPUT
    message = text
  end subroutine fail

  ! ---- values ----------------------------------------------------------------------------------

  !> The first token of an assignment's value text that is no value: values are numbers (with an
  !> optional repeat count r*), quoted strings or logicals, separated by commas or blanks. A bare
  !> name there is a variable without '='. '' if every token is a value.
  pure function bad_value(values) result(token)
    character(len=*), intent(in) :: values
    character(len=:), allocatable :: token
    integer :: i, start, finish, star

    token = ''
    i = 1
    do
      call next_token(values, i, start, finish)
      if (start == 0) return
      if (values(start:start) == '''' .or. values(start:start) == '"') cycle
      token = values(start:finish)
      star = index(token, '*')
      if (star > 0) then
        if (verify(token(1:star - 1), '0123456789') == 0 .and. star > 1) token = token(star + 1:)
      end if
      if (len(token) == 0 .or. is_number(lower(token)) .or. is_logical(lower(token))) then
        token = ''
      else
        token = values(start:finish)
        return
      end if
    end do
  end function bad_value

  !> The number of values in an assignment's value text (its tokens as bad_value reads them):
  !> r*value counts r, a quoted string one.
  pure integer function count_values(values) result(n)
    character(len=*), intent(in) :: values
    integer :: i, start, finish, star, repeat, ios
    n = 0
    i = 1
    do
      call next_token(values, i, start, finish)
      if (start == 0) return
      star = index(values(start:finish), '*')
      repeat = 1
      if (star > 1 .and. star <= 10 .and. values(start:start) /= '''' .and. &
          values(start:start) /= '"') then
        if (verify(values(start:start + star - 2), '0123456789') == 0) &
          read (values(start:start + star - 2), *, iostat=ios) repeat
      end if
      n = n + repeat
    end do
  end function count_values

  !> The next token of a value text from position i: values(start:finish), a quoted string
  !> (doubled quotes inside) or a run of characters up to a comma or blank; start = 0 if none.
  !> i moves past it.
  pure subroutine next_token(values, i, start, finish)
    character(len=*), intent(in) :: values
    integer, intent(inout) :: i
    integer, intent(out) :: start, finish
    character :: quote
    start = 0
    finish = 0
    do while (i <= len(values))
      if (values(i:i) /= ' ' .and. values(i:i) /= ',') exit
      i = i + 1
    end do
    if (i > len(values)) return
    start = i
    if (values(i:i) == '''' .or. values(i:i) == '"') then
      quote = values(i:i)
      i = i + 1
      do while (i <= len(values))
        if (values(i:i) == quote) then
          if (i < len(values)) then
            if (values(i + 1:i + 1) == quote) then
              i = i + 2
              cycle
            end if
          end if
          exit
        end if
        i = i + 1
      end do
      finish = min(i, len(values))
      i = i + 1
      return
    end if
    do while (i <= len(values))
      if (values(i:i) == ' ' .or. values(i:i) == ',') exit
      i = i + 1
    end do
    finish = i - 1
  end subroutine next_token

  !> A Fortran real or integer literal, or NaN/Infinity as list-directed input reads them.
  pure logical function is_number(text)
    character(len=*), intent(in) :: text
    integer :: i, digits, more
    is_number = .false.
    if (text == 'nan' .or. text == 'inf' .or. text == 'infinity' .or. text == '+inf' .or. &
        text == '-inf' .or. text == '+infinity' .or. text == '-infinity') then
      is_number = .true.
      return
    end if
    i = 1
    if (scan(text(1:1), '+-') == 1) i = 2
    call skip_digits(text, i, digits)
    if (i <= len(text)) then
      if (text(i:i) == '.') then
        i = i + 1
        call skip_digits(text, i, more)
        digits = digits + more
      end if
    end if
    if (digits == 0) return
    if (i <= len(text)) then
      if (scan(text(i:i), 'ed') == 1) then
        i = i + 1
        if (i <= len(text)) then
          if (scan(text(i:i), '+-') == 1) i = i + 1
        end if
        call skip_digits(text, i, digits)
        if (digits == 0) return
      end if
    end if
    is_number = i > len(text)
  end function is_number

  !> Move i past the digits of text(i:); digits: how many.
  pure subroutine skip_digits(text, i, digits)
    character(len=*), intent(in) :: text
    integer, intent(inout) :: i
    integer, intent(out) :: digits
    digits = 0
    do while (i <= len(text))
      if (index('0123456789', text(i:i)) == 0) exit
      digits = digits + 1
      i = i + 1
    end do
  end subroutine skip_digits

  pure logical function is_logical(text)
    character(len=*), intent(in) :: text
    is_logical = text == 't' .or. text == 'f' .or. text == '.t.' .or. text == '.f.' .or. &
                 text == '.true.' .or. text == '.false.'
  end function is_logical

  ! ---- assignments -----------------------------------------------------------------------------

  !> Positions of every `name =` or `name(index) =` outside quotes in a group body, in one pass.
  pure function assignment_starts(text) result(starts)
    character(len=*), intent(in) :: text
    integer, allocatable :: starts(:)
    integer, allocatable :: found(:), close_after(:), nonblank_after(:)
    integer :: i, j, n, count
    logical :: quoted
    character :: quote

    n = len(text)
    ! close_after(i): the first ')' at or after i (0: none); nonblank_after(i): the first
    ! non-blank at or after i (n + 1: none)
    allocate (found(n), close_after(n + 1), nonblank_after(n + 1))
    close_after(n + 1) = 0
    nonblank_after(n + 1) = n + 1
    do i = n, 1, -1
      close_after(i) = merge(i, close_after(i + 1), text(i:i) == ')')
      nonblank_after(i) = merge(nonblank_after(i + 1), i, text(i:i) == ' ')
    end do
    count = 0
    quoted = .false.
    quote = ' '
    i = 1
    do while (i <= n)
      if (quoted) then
        if (text(i:i) == quote) quoted = .false.
        i = i + 1
        cycle
      end if
      if (text(i:i) == '"' .or. text(i:i) == '''') then
        quoted = .true.
        quote = text(i:i)
        i = i + 1
        cycle
      end if
      if (.not. is_name_start(text(i:i))) then
        i = i + 1
        cycle
      end if
      if (i > 1) then
        if (is_name_char(text(i - 1:i - 1))) then
          i = i + 1
          cycle
        end if
      end if
      j = i
      do while (j <= n)
        if (.not. is_name_char(text(j:j))) exit
        j = j + 1
      end do
      j = nonblank_after(j)
      if (j <= n) then
        if (text(j:j) == '(') then
          ! an array index: up to the closing parenthesis
          if (close_after(j) == 0) then
            i = i + 1
            cycle
          end if
          j = nonblank_after(close_after(j) + 1)
        end if
      end if
      if (j <= n) then
        if (text(j:j) == '=') then
          count = count + 1
          found(count) = i
        end if
      end if
      i = i + 1
    end do
    starts = found(1:count)
  end function assignment_starts

  !> ',name1,name2,...,' of the variables assigned at starts (lower case, indices dropped).
  pure function assignment_names(body, starts) result(names)
    character(len=*), intent(in) :: body
    integer, intent(in) :: starts(:)
    character(len=:), allocatable :: names
    integer :: k, j, length
    length = 1
    do k = 1, size(starts)
      length = length + name_end(starts(k)) - starts(k) + 1
    end do
    allocate (character(len=length) :: names)
    names(1:1) = ','
    length = 1
    do k = 1, size(starts)
      j = name_end(starts(k))
      names(length + 1:length + j - starts(k) + 1) = lower(body(starts(k):j - 1))//','
      length = length + j - starts(k) + 1
    end do

  contains

    !> The position after the name that starts at `start`.
    pure integer function name_end(start) result(j)
      integer, intent(in) :: start
      j = start
      do while (j <= len(body))
        if (.not. is_name_char(body(j:j))) exit
        j = j + 1
      end do
    end function name_end
  end function assignment_names

  !> The variable of the left side of an assignment: 'y0(2) ' -> 'y0', lower case.
  pure function variable_name(left) result(name)
    character(len=*), intent(in) :: left
    character(len=:), allocatable :: name
    integer :: paren
    name = trim(adjustl(left))
    paren = index(name, '(')
    if (paren > 0) name = trim(name(1:paren - 1))
    name = lower(name)
  end function variable_name

  pure logical function is_name_start(ch)
    character, intent(in) :: ch
    is_name_start = index('abcdefghijklmnopqrstuvwxyz', lower(ch)) > 0
  end function is_name_start

  pure logical function is_name_char(ch)
    character, intent(in) :: ch
    is_name_char = index('abcdefghijklmnopqrstuvwxyz0123456789_', lower(ch)) > 0
  end function is_name_char

  pure function lower(text) result(low)
    character(len=*), intent(in) :: text
    character(len=len(text)) :: low
    integer :: i
    low = text
    do i = 1, len(text)
      if (text(i:i) >= 'A' .and. text(i:i) <= 'Z') low(i:i) = achar(iachar(text(i:i)) + 32)
    end do
  end function lower

  pure function join(items, separator) result(text)
    character(len=*), intent(in) :: items(:)
    character(len=*), intent(in), optional :: separator
    character(len=:), allocatable :: text
    integer :: i
    text = trim(items(1))
    do i = 2, size(items)
      if (present(separator)) then
        text = text//separator//trim(items(i))
      else
        text = text//', '//trim(items(i))
      end if
    end do
  end function join
end module sloshdyn_namelist_scanner
