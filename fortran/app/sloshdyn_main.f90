!> The `sloshdyn` executable: reads a namelist input file, validates all of it, runs the requested
!> analysis (sloshdyn_driver: a summary on standard output, CSV files in the output directory)
!> and turns the status into an exit code -- the only place that does (the table is in
!> sloshdyn_status). SIGINT and SIGTERM end the run, while it reads (at once: nothing is
!> written yet) or computes (cancelled: its temporaries are removed); the exit code is 128 +
!> the signal. Standard output that takes no writes (/dev/full, a closed descriptor) is a
!> failed write: exit 5 before anything runs. (gfortran reports no error on writes to standard
!> output, so a disk that fills during the run cannot be told.)
program sloshdyn_main
  use sloshdyn_kinds, only: message_len
  use sloshdyn_status, only: SD_OK, exit_code, EXIT_USAGE, EXIT_IO
  use sloshdyn_cancel, only: cancel_signal
  use sloshdyn_signals, only: install_exit_handlers, install_signal_handlers
  use sloshdyn_namelist, only: run_config, read_input
  use sloshdyn_driver, only: run_analysis
  use sloshdyn_files, only: standard_output_writable
  use sloshdyn_text, only: num2str
  implicit none

  character(len=*), parameter :: usage = 'usage: sloshdyn INPUT.nml   (the namelist groups and '// &
                                         'variables: namelist.md, installed with the package, '// &
                                         'whose path sloshdyn-py --help prints; example '// &
                                         'inputs: sloshdyn-py examples DIR)'
  character(len=*), parameter :: no_output = 'standard output takes no writes (a full disk or '// &
                                             'device, or closed): the summary would be lost'
  character(len=:), allocatable :: path
  character(len=message_len) :: message
  type(run_config) :: config
  integer :: status, length

  if (command_argument_count() /= 1) call finish(EXIT_USAGE, usage)
  call get_command_argument(1, length=length)
  allocate (character(len=length) :: path)
  call get_command_argument(1, path)
  if (path == '-h' .or. path == '--help') then
    print '(a)', usage
    stop
  end if
  if (path == '--version') then
    print '(a)', 'sloshdyn '//SLOSHDYN_VERSION   ! defined by fortran/app/meson.build
    stop
  end if
  if (.not. standard_output_writable()) call finish(EXIT_IO, no_output)
  call install_exit_handlers()
  call read_input(path, config, status, message)
  if (status /= SD_OK) call finish(exit_code(status, reading=.true.), trim(message))
  call install_signal_handlers()
  call run_analysis(config, status, message)
  if (status /= SD_OK .and. cancel_signal() > 0) &
    call finish(128 + cancel_signal(), 'signal '//num2str(cancel_signal())//': '//trim(message))
  if (status /= SD_OK) call finish(exit_code(status, reading=.false.), trim(message))

contains

  subroutine finish(code, text)
    integer, intent(in) :: code
    character(len=*), intent(in) :: text
    write (0, '(a)') 'sloshdyn: error: '//text
    stop code, quiet=.true.
  end subroutine finish
end program sloshdyn_main
