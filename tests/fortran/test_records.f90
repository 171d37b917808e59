!> Record readers: small files written here (valid AT2 in the PEER NGA and older header forms,
!> CRLF endings, two-column files with comments and each separator and unit), their values
!> (AT2 values are in g: times 9.80665; cm/s^2 times 0.01), every documented error with the file,
!> line and cause in the message, and that a file is never modified by reading it.
program test_records
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, SD_IO_ERROR
  use sloshdyn_records, only: read_at2, read_two_column, units_code, UNITS_G, UNITS_M_S2, &
                              UNITS_CM_S2, standard_gravity
  use sloshdyn_files, only: make_directory, remove_file, process_id
  use checks, only: check_close, check_true, finish
  use, intrinsic :: iso_c_binding, only: c_char, c_int, c_null_char
  implicit none
  character(len=*), parameter :: lf = char(10), crlf = char(13)//char(10)
  character(len=:), allocatable :: folder
  character(len=256), allocatable :: written(:)
  character(len=message_len) :: message
  real(wp), allocatable :: accel(:)
  real(wp) :: dt
  integer :: status
  logical :: ok
  character(len=20) :: pid

  write (pid, '(i0)') process_id()
  folder = 'test_records_'//trim(pid)
  call make_directory(folder, ok)
  call check_true('scratch folder created', ok)
  allocate (written(0))

  call test_at2_valid()
  call test_at2_errors()
  call test_two_column_valid()
  call test_two_column_errors()
  call test_units()
  call test_file_errors()
  call cleanup()
  call finish()

contains

  !> Seven values in g, 5 on the first line and 2 on the second: a = g * value.
  subroutine test_at2_valid()
    character(len=*), parameter :: values = &
      '  .1000000E-01 -.2500000E-02  .0000000E+00  .3125000E-01 -.1000000E+00'//lf// &
      '  .5000000E-02  .2000000E+00'//lf
    real(wp), parameter :: expected(7) = [1.0e-2_wp, -2.5e-3_wp, 0.0_wp, 3.125e-2_wp, -0.1_wp, &
                                          5.0e-3_wp, 0.2_wp]
    character(len=*), parameter :: header_lines = 'PEER NGA STRONG MOTION DATABASE RECORD'//lf// &
      'IMPERIAL VALLEY 10/15/79 2316, EL CENTRO ARRAY #6, 140'//lf// &
      'ACCELERATION TIME SERIES IN UNITS OF G'//lf
    character(len=40) :: fourth(6)
    character(len=:), allocatable :: path, content
    integer :: k

    fourth(1) = 'NPTS=      7, DT=   .0050 SEC'      ! NGA form
    fourth(2) = 'NPTS= 7, DT= 0.005 SEC'              ! common variant
    fourth(3) = '     7   0.0050   NPTS, DT'          ! older form
    fourth(4) = 'DT= .005 SEC, NPTS= 7'               ! either order
    fourth(5) = 'npts =7 , dt = 5.0e-3'               ! lower case, blanks around =, no unit
    fourth(6) = 'NPTS='//char(9)//'7,'//char(9)//'DT'//char(9)//'= .005'   ! tabs around =
    do k = 1, size(fourth)
      path = scratch('valid_'//achar(iachar('0') + k)//'.AT2')
      content = header_lines//trim(fourth(k))//lf//values
      call write_file(path, content)
      call read_at2(path, dt, accel, status, message)
      call check_true('AT2 header "'//trim(fourth(k))//'": status', status == SD_OK)
      if (status /= SD_OK) then
        print '(a)', '    '//trim(message)
        cycle
      end if
      call check_close('AT2 header "'//trim(fourth(k))//'": dt = 0.005 s', dt, 0.005_wp, 1.0e-15_wp)
      call check_true('AT2 header "'//trim(fourth(k))//'": 7 samples', size(accel) == 7)
      call check_close('AT2: max |a - 9.80665 * value| (m/s^2)', &
                       maxval(abs(accel - standard_gravity*expected)), 0.0_wp, 0.0_wp, 1.0e-15_wp)
      call check_true('AT2: file unchanged by reading', file_text(path) == content)
    end do
    ! Windows line endings
    path = scratch('crlf.AT2')
    call write_file(path, 'header 1'//crlf//'header 2'//crlf//'UNITS OF G'//crlf// &
                    'NPTS= 3, DT= .0100 SEC'//crlf//' .1E+00 .2E+00'//crlf//' -.3E+00'//crlf)
    call read_at2(path, dt, accel, status, message)
    call check_true('AT2 with CRLF endings: status, dt, values', status == SD_OK .and. &
                    abs(dt - 0.01_wp) < 1.0e-16_wp .and. size(accel) == 3)
    if (status == SD_OK) call check_close('AT2 with CRLF endings: a(3) = -0.3 g', accel(3), &
                                          -0.3_wp*standard_gravity, 1.0e-15_wp)
  end subroutine test_at2_valid

  subroutine test_at2_errors()
    character(len=*), parameter :: head = 'h1'//lf//'h2'//lf//'h3'//lf
    character(len=:), allocatable :: path

    path = scratch('short.AT2')
    call write_file(path, 'h1'//lf//'h2'//lf)
    call read_at2(path, dt, accel, status, message)
    call expect('AT2 with 2 header lines', SD_BAD_INPUT, [character(len=40) :: 'short.AT2''', &
                'line 3', 'header'])
    call check_true('AT2 failure leaves accel unallocated', .not. allocated(accel))

    path = scratch('bad_npts.AT2')
    call write_file(path, head//'NPTS= abc, DT= .005 SEC'//lf//' .1 .2'//lf)
    call read_at2(path, dt, accel, status, message)
    call expect('AT2 malformed NPTS', SD_BAD_INPUT, [character(len=40) :: 'bad_npts.AT2''', &
                'line 4', 'NPTS'])

    path = scratch('bad_dt.AT2')
    call write_file(path, head//'NPTS= 2, DT= -.005 SEC'//lf//' .1 .2'//lf)
    call read_at2(path, dt, accel, status, message)
    call expect('AT2 DT <= 0', SD_BAD_INPUT, [character(len=40) :: 'line 4', 'DT > 0'])

    path = scratch('no_header.AT2')
    call write_file(path, head//'PEER record'//lf//' .1 .2'//lf)
    call read_at2(path, dt, accel, status, message)
    call expect('AT2 4th line without NPTS and DT', SD_BAD_INPUT, &
                [character(len=40) :: 'line 4', 'malformed AT2 header'])

    path = scratch('mismatch.AT2')
    call write_file(path, head//'NPTS= 4, DT= .005 SEC'//lf//' .1 .2'//lf//' .3'//lf)
    call read_at2(path, dt, accel, status, message)
    call expect('AT2 NPTS = 4 but 3 values', SD_BAD_INPUT, &
                [character(len=40) :: 'NPTS = 4', '3 values'])

    path = scratch('one.AT2')
    call write_file(path, head//'NPTS= 1, DT= .005 SEC'//lf//' .1'//lf)
    call read_at2(path, dt, accel, status, message)
    call expect('AT2 with 1 sample', SD_BAD_INPUT, [character(len=40) :: 'only 1 sample', &
                'at least 2'])

    path = scratch('nan.AT2')
    call write_file(path, head//'NPTS= 4, DT= .005 SEC'//lf//' .1 .2'//lf//' NaN .4'//lf)
    call read_at2(path, dt, accel, status, message)
    call expect('AT2 NaN value', SD_BAD_INPUT, [character(len=40) :: 'line 6', 'value 3', &
                'not finite'])

    path = scratch('garbage.AT2')
    call write_file(path, head//'NPTS= 3, DT= .005 SEC'//lf//' .1 1.2.3 .4'//lf)
    call read_at2(path, dt, accel, status, message)
    call expect('AT2 malformed value', SD_BAD_INPUT, [character(len=40) :: 'line 5', &
                '''1.2.3'' is not a number'])
  end subroutine test_at2_errors

  !> Comments (#, also indented), blank lines, each separator; cm/s^2 -> m/s^2 (times 0.01).
  subroutine test_two_column_valid()
    character(len=:), allocatable :: path, content

    path = scratch('record.csv')
    content = '# station XYZ, units cm/s^2'//lf//'   # time [s], acceleration [cm/s^2]'//lf// &
              lf//'0.00, 1.5'//lf//'0.02;-3.0'//lf//'0.04 2.5e1'//lf//'  0.06'//char(9)// &
              '0'//lf//'0.08 ,  -100'//lf
    call write_file(path, content)
    call read_two_column(path, UNITS_CM_S2, dt, accel, status, message)
    call check_true('CSV: status', status == SD_OK)
    if (status /= SD_OK) print '(a)', '    '//trim(message)
    call check_close('CSV: dt = 0.02 s (mean step)', dt, 0.02_wp, 1.0e-14_wp)
    call check_true('CSV: 5 samples', size(accel) == 5)
    call check_close('CSV: max |a - [1.5, -3, 25, 0, -100]/100|', &
                     maxval(abs(accel - [0.015_wp, -0.03_wp, 0.25_wp, 0.0_wp, -1.0_wp])), 0.0_wp, &
                     0.0_wp, 1.0e-16_wp)
    call check_true('CSV: file unchanged by reading', file_text(path) == content)

    ! one first line of column names, without #
    path = scratch('named.csv')
    call write_file(path, 'time_s,accel_g'//lf//'0.0, 1'//lf//'0.01, 2'//lf)
    call read_two_column(path, UNITS_G, dt, accel, status, message)
    call check_true('CSV with a line of column names: status and 2 samples', &
                    status == SD_OK .and. size(accel) == 2)
    if (status == SD_OK) call check_close('CSV with column names: a(2) = 2 g', accel(2), &
                                          2*standard_gravity, 1.0e-15_wp)

    path = scratch('record_g.txt')
    call write_file(path, '1.000 0.1'//lf//'1.005 -0.2'//lf//'1.010 0.3')   ! no final newline
    call read_two_column(path, UNITS_G, dt, accel, status, message)
    call check_true('two columns in g without a final newline: status and 3 samples', &
                    status == SD_OK .and. size(accel) == 3)
    call check_close('two columns in g: dt = 0.005 s', dt, 0.005_wp, 1.0e-12_wp)
    call check_close('two columns in g: a(2) = -0.2 * 9.80665', accel(2), -0.2_wp*9.80665_wp, &
                     1.0e-15_wp)
    call read_two_column(path, UNITS_M_S2, dt, accel, status, message)
    call check_close('two columns in m/s^2: a(3) = 0.3', accel(3), 0.3_wp, 1.0e-15_wp)
  end subroutine test_two_column_valid

  subroutine test_two_column_errors()
    character(len=:), allocatable :: path

    path = scratch('decreasing.csv')
    call write_file(path, '# t, a'//lf//'0.0, 1'//lf//'0.1, 2'//lf//'0.1, 3'//lf)
    call read_two_column(path, UNITS_M_S2, dt, accel, status, message)
    call expect('CSV time not increasing', SD_BAD_INPUT, [character(len=40) :: 'decreasing.csv''', &
                'line 4', 'does not increase'])
    call check_true('CSV failure leaves accel unallocated', .not. allocated(accel))

    path = scratch('uneven.csv')
    call write_file(path, '0.0, 1'//lf//'0.01, 2'//lf//'0.02, 3'//lf//'0.0301, 4'//lf)
    call read_two_column(path, UNITS_M_S2, dt, accel, status, message)
    call expect('CSV non-uniform step (1e-2 off by 1e-4)', SD_BAD_INPUT, &
                [character(len=40) :: 'line 4', 'non-uniform time step', '1e-6'])

    path = scratch('almost_even.csv')
    call write_file(path, '0.0, 1'//lf//'0.01, 2'//lf//'0.02000000001, 3'//lf)
    call read_two_column(path, UNITS_M_S2, dt, accel, status, message)
    call check_true('CSV step off by 1e-9 relative is uniform (tolerance 1e-6)', status == SD_OK)

    path = scratch('three.csv')
    call write_file(path, '0.0, 1'//lf//'0.01, 2, 7'//lf)
    call read_two_column(path, UNITS_M_S2, dt, accel, status, message)
    call expect('CSV with 3 columns', SD_BAD_INPUT, [character(len=40) :: 'line 2', &
                'expected 2 values', 'found 3'])

    path = scratch('inf.csv')
    call write_file(path, '0.0, 1'//lf//'0.01, Inf'//lf)
    call read_two_column(path, UNITS_M_S2, dt, accel, status, message)
    call expect('CSV infinite acceleration', SD_BAD_INPUT, [character(len=40) :: 'line 2', &
                'acceleration', 'not finite'])

    path = scratch('nan_time.csv')
    call write_file(path, '0.0, 1'//lf//'nan, 2'//lf)
    call read_two_column(path, UNITS_M_S2, dt, accel, status, message)
    call expect('CSV NaN time', SD_BAD_INPUT, [character(len=40) :: 'line 2', 'time', &
                'not finite'])

    ! one line of column names is read as such; a second is an error naming its line
    path = scratch('header.csv')
    call write_file(path, 'time,accel'//lf//'seconds,g'//lf//'0.0, 1'//lf//'0.01, 2'//lf)
    call read_two_column(path, UNITS_M_S2, dt, accel, status, message)
    call expect('CSV second header row', SD_BAD_INPUT, [character(len=40) :: 'line 2', &
                '''seconds'' is not a number'])
    ! binary junk is no header: quoted short and escaped
    path = scratch('junk.csv')
    call write_file(path, char(27)//'[31m'//char(0)//repeat(char(255), 100)//lf//'0.0, 1'//lf)
    call read_two_column(path, UNITS_M_S2, dt, accel, status, message)
    call expect('CSV binary junk', SD_BAD_INPUT, [character(len=40) :: 'line 1', &
                '''\x1b[31m\x00\xff', '''... is not a number'])

    path = scratch('single.csv')
    call write_file(path, '# only one sample'//lf//'0.0, 1'//lf)
    call read_two_column(path, UNITS_M_S2, dt, accel, status, message)
    call expect('CSV with 1 sample', SD_BAD_INPUT, [character(len=40) :: 'only 1 sample'])

    path = scratch('empty.csv')
    call write_file(path, '')
    call read_two_column(path, UNITS_M_S2, dt, accel, status, message)
    call expect('empty CSV', SD_BAD_INPUT, [character(len=40) :: 'only 0 sample'])
  end subroutine test_two_column_errors

  subroutine test_units()
    integer :: code
    character(len=:), allocatable :: path
    call units_code(' G ', code, status, message)
    call check_true('units_code: " G " -> UNITS_G', status == SD_OK .and. code == UNITS_G)
    call units_code('m/s2', code, status, message)
    call check_true('units_code: m/s2 -> UNITS_M_S2', status == SD_OK .and. code == UNITS_M_S2)
    call units_code('Gal', code, status, message)
    call check_true('units_code: Gal -> UNITS_CM_S2', status == SD_OK .and. code == UNITS_CM_S2)
    call units_code('ft/s^2', code, status, message)
    call check_true('units_code: unknown name refused, message names it', &
                    status == SD_BAD_INPUT .and. index(message, 'units = ''ft/s^2'' is unknown') == 1)
    path = scratch('units.csv')
    call write_file(path, '0.0, 1'//lf//'0.01, 2'//lf)
    call read_two_column(path, 7, dt, accel, status, message)
    call check_true('read_two_column: unknown units code refused, message names units', &
                    status == SD_BAD_INPUT .and. index(message, 'units = 7 is unknown') == 1)
  end subroutine test_units

  subroutine test_file_errors()
    call read_at2(folder//'/missing.AT2', dt, accel, status, message)
    call expect('missing AT2 file', SD_IO_ERROR, [character(len=40) :: 'missing.AT2''', &
                'no such file'])
    call read_two_column(folder//'/missing.csv', UNITS_G, dt, accel, status, message)
    call expect('missing CSV file', SD_IO_ERROR, [character(len=40) :: 'missing.csv''', &
                'no such file'])
    call read_at2(folder, dt, accel, status, message)
    call expect('a directory', SD_IO_ERROR, [character(len=40) :: 'is a directory'])
    ! a device is refused before it is read (/dev/zero never ends)
    call read_two_column('/dev/zero', UNITS_G, dt, accel, status, message)
    call expect('a device', SD_IO_ERROR, [character(len=40) :: '''/dev/zero''', &
                'not a regular file'])
    ! a name ending in a blank would open another file: refused by that name
    call write_file(scratch('blank.csv'), '0.0, 1'//lf//'0.01, 2'//lf)
    call read_two_column(scratch('blank.csv')//' ', UNITS_G, dt, accel, status, message)
    call expect('a name ending in a blank', SD_BAD_INPUT, [character(len=40) :: 'blank.csv ''', &
                'ends in a blank'])
  end subroutine test_file_errors

  !> status == code and every part in the message.
  subroutine expect(label, code, parts)
    character(len=*), intent(in) :: label
    integer, intent(in) :: code
    character(len=*), intent(in) :: parts(:)
    logical :: found
    integer :: i
    found = status == code
    do i = 1, size(parts)
      found = found .and. index(message, trim(parts(i))) > 0
    end do
    call check_true(label//': status and message', found)
    print '(a)', '    message: '//trim(message)
  end subroutine expect

  function scratch(name) result(path)
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: path
    path = folder//'/'//name
  end function scratch

  subroutine write_file(path, text)
    character(len=*), intent(in) :: path, text
    integer :: unit
    open (newunit=unit, file=path, status='replace', access='stream', form='unformatted', &
          action='write')
    if (len(text) > 0) write (unit) text
    close (unit)
    written = [written, [character(len=256) :: path]]
  end subroutine write_file

  function file_text(path) result(text)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: text
    integer :: unit, file_size
    open (newunit=unit, file=path, status='old', access='stream', form='unformatted', &
          action='read')
    inquire (unit=unit, size=file_size)
    allocate (character(len=file_size) :: text)
    if (file_size > 0) read (unit) text
    close (unit)
  end function file_text

  !> Remove the files written and the scratch folder (POSIX rmdir through C).
  subroutine cleanup()
    interface
      integer(c_int) function c_rmdir(path) bind(c, name='rmdir')
        import :: c_char, c_int
        character(kind=c_char), intent(in) :: path(*)
      end function c_rmdir
    end interface
    integer :: i
    do i = 1, size(written)
      call remove_file(trim(written(i)))
    end do
    call check_true('scratch folder removed', c_rmdir(folder//c_null_char) == 0)
  end subroutine cleanup
end program test_records
