!> The input file of the `sloshdyn` executable: Fortran namelist groups, read and validated in
!> full before anything is computed. The groups and variables are documented in README.md.
module sloshdyn_namelist
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_is_nan
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, SD_IO_ERROR, check_real
  use sloshdyn_text, only: num2str
  use sloshdyn_model, only: model_t, model_from_arrays, model_from_physical, require_stable_trivial
  use sloshdyn_tank, only: tank_pendulum
  use sloshdyn_rk45, only: rk45_options, rk45_check_setup
  use sloshdyn_simulation, only: steady_options, check_steady
  use sloshdyn_response, only: response_options
  use sloshdyn_integrator, only: METHOD_RK45, METHOD_DOP853
  implicit none
  private
  public :: run_config, read_input, known_analyses

  character(len=*), parameter :: known_groups(12) = &
    [character(len=11) :: 'model', 'tank', 'structure', 'excitation', 'analysis', 'output', &
     'integration', 'simulation', 'steady', 'sweep', 'response', 'lyapunov']
  character(len=*), parameter :: known_analyses(7) = &
    [character(len=18) :: 'linear', 'simulate', 'steady_state', 'sweep', 'frequency_response', &
     'periodic_response', 'lyapunov']
  integer, parameter :: path_len = 1024

  !> Everything one run needs, validated.
  type :: run_config
    type(model_t) :: model
    logical :: dimensional = .false.     !< model built from &tank and &structure
    real(wp) :: radius = 0, depth = 0, liquid_mass = 0                 !< &tank (m_F computed)
    real(wp) :: total_mass = 0, rod_length = 0, gravity = 0            !< &structure
    real(wp) :: pendulum_length = 0, sloshing_mass = 0, d1 = 0, rigid_mass = 0, d0 = 0  !< eq (2)-(3)
    character(len=18) :: analysis = 'linear'
    real(wp) :: sigma1 = 0, kappa_min = 0, kappa_max = 0                 !< 3:1 tuning search
    character(len=path_len) :: directory = 'sloshdyn_output'
    type(rk45_options) :: integration                                  !< &integration
    integer :: method = METHOD_RK45
    real(wp) :: t_end = 0, y0(4) = 0                                   !< &simulation
    integer :: n_out = 0
    type(steady_options) :: steady                                     !< &steady
    character(len=3) :: sweep_parameter = 'rho'                        !< &sweep
    real(wp) :: sweep_start = 0, sweep_stop = 0
    integer :: sweep_points = 0
    character(len=4) :: sweep_direction = 'up'
    type(response_options) :: response                                 !< &response
    logical :: internal_resonance = .true.
    integer :: lyapunov_transient = 500, lyapunov_periods = 2000, lyapunov_every = 1  !< &lyapunov
  end type run_config

contains

  !> Read and validate the whole input file. On failure nothing is returned but a status and a
  !> message naming the group, the variable, its value and the allowed range.
  subroutine read_input(path, config, status, message)
    character(len=*), intent(in) :: path
    type(run_config), intent(out) :: config
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    logical :: given(size(known_groups))
    integer :: unit, ios
    character(len=message_len) :: iomsg
    real(wp) :: nan
    ! namelist variables, named as the user writes them
    real(wp) :: s1, mu1, kappa, theta0, beta, gamma, delta, A, rho
    real(wp) :: R, h, rho_liquid, m_liquid
    real(wp) :: M, L, k, c, b, d, g
    real(wp) :: sigma1, kappa_min, kappa_max
    integer :: n, p
    character(len=18) :: kind
    character(len=8) :: resonance
    integer :: renormalise_every
    integer :: n_scan, n_amplitudes, n_phases
    real(wp) :: amplitude_min, amplitude_max, ds, ds_min, ds_max, x_scale
    character(len=path_len) :: directory
    real(wp) :: rtol, atol, h_initial, h_max, h_min
    integer :: max_steps
    character(len=8) :: method
    real(wp) :: t_end, y0(4)
    integer :: n_out
    real(wp) :: transient_periods, settle_tol, max_transient_periods, periodic_tol
    integer :: window_periods, samples_per_period
    character(len=16) :: parameter, direction
    real(wp) :: start, stop
    integer :: n_points, n_periods
    namelist /model/ s1, mu1, kappa, theta0, beta, gamma, delta, n, p
    namelist /tank/ R, h, rho_liquid, m_liquid
    namelist /structure/ M, L, k, c, b, d, g, theta0, n, p
    namelist /excitation/ A, rho
    namelist /analysis/ kind, sigma1, kappa_min, kappa_max
    namelist /output/ directory
    namelist /integration/ rtol, atol, h_initial, h_max, h_min, max_steps, method
    namelist /simulation/ t_end, n_out, y0
    namelist /steady/ transient_periods, settle_tol, max_transient_periods, window_periods, &
                      samples_per_period, periodic_tol
    namelist /sweep/ parameter, start, stop, n_points, direction
    namelist /response/ resonance, parameter, start, stop, n_scan, n_amplitudes, n_phases, &
                        amplitude_min, amplitude_max, ds, ds_min, ds_max, x_scale
    namelist /lyapunov/ transient_periods, n_periods, renormalise_every

    status = SD_OK
    message = ''
    nan = ieee_value(1.0_wp, ieee_quiet_nan)
    ! NaN marks "not given" for required values
    s1 = nan; mu1 = nan; kappa = nan; theta0 = nan
    beta = 10; gamma = 0; delta = 0.1_wp; n = 6; p = 2
    A = 0; rho = 0
    R = nan; h = nan; rho_liquid = 0; m_liquid = 0
    M = nan; L = nan; k = nan; c = 0; b = 0; d = 0; g = 9.81_wp
    kind = 'linear'; sigma1 = 0; kappa_min = 0; kappa_max = nan
    directory = 'sloshdyn_output'
    rtol = 1.0e-9_wp; atol = 1.0e-12_wp
    h_initial = 0; h_max = 0; h_min = 0; max_steps = 10**8; method = 'rk45'
    t_end = nan; n_out = 0; y0 = 0
    transient_periods = config%steady%transient_periods; settle_tol = config%steady%settle_tol
    max_transient_periods = config%steady%max_transient_periods
    window_periods = config%steady%window_periods
    samples_per_period = config%steady%samples_per_period
    periodic_tol = config%steady%periodic_tol
    parameter = 'rho'; start = nan; stop = nan; n_points = 0; direction = 'up'
    resonance = '3:1'
    renormalise_every = 1; n_periods = 2000
    n_scan = config%response%n_scan; n_amplitudes = config%response%n_amplitudes
    n_phases = config%response%n_phases; amplitude_min = config%response%amplitude_min
    amplitude_max = config%response%amplitude_max; ds = 0.002_wp; ds_min = 1.0e-9_wp
    ds_max = 0.01_wp; x_scale = 1

    open (newunit=unit, file=path, status='old', action='read', iostat=ios, iomsg=iomsg)
    if (ios /= 0) then
      status = SD_IO_ERROR
      message = 'cannot open input file '''//trim(path)//''': '//trim(iomsg)
      return
    end if
    call scan_groups(unit, path, given, status, message)
    if (status == SD_OK .and. given(1)) then
      read (unit, nml=model, iostat=ios, iomsg=iomsg)
      call read_failed('model', ios, iomsg)
    end if
    if (status == SD_OK .and. given(2)) then
      rewind (unit)
      read (unit, nml=tank, iostat=ios, iomsg=iomsg)
      call read_failed('tank', ios, iomsg)
    end if
    if (status == SD_OK .and. given(3)) then
      rewind (unit)
      read (unit, nml=structure, iostat=ios, iomsg=iomsg)
      call read_failed('structure', ios, iomsg)
    end if
    if (status == SD_OK .and. given(4)) then
      rewind (unit)
      read (unit, nml=excitation, iostat=ios, iomsg=iomsg)
      call read_failed('excitation', ios, iomsg)
    end if
    if (status == SD_OK .and. given(5)) then
      rewind (unit)
      read (unit, nml=analysis, iostat=ios, iomsg=iomsg)
      call read_failed('analysis', ios, iomsg)
    end if
    if (status == SD_OK .and. given(6)) then
      rewind (unit)
      read (unit, nml=output, iostat=ios, iomsg=iomsg)
      call read_failed('output', ios, iomsg)
    end if
    if (status == SD_OK .and. given(7)) then
      rewind (unit)
      read (unit, nml=integration, iostat=ios, iomsg=iomsg)
      call read_failed('integration', ios, iomsg)
    end if
    if (status == SD_OK .and. given(8)) then
      rewind (unit)
      read (unit, nml=simulation, iostat=ios, iomsg=iomsg)
      call read_failed('simulation', ios, iomsg)
    end if
    if (status == SD_OK .and. given(9)) then
      rewind (unit)
      read (unit, nml=steady, iostat=ios, iomsg=iomsg)
      call read_failed('steady', ios, iomsg)
    end if
    if (status == SD_OK .and. given(10)) then
      rewind (unit)
      read (unit, nml=sweep, iostat=ios, iomsg=iomsg)
      call read_failed('sweep', ios, iomsg)
    end if
    if (status == SD_OK .and. given(11)) then
      rewind (unit)
      read (unit, nml=response, iostat=ios, iomsg=iomsg)
      call read_failed('response', ios, iomsg)
    end if
    if (status == SD_OK .and. given(12)) then
      rewind (unit)
      read (unit, nml=lyapunov, iostat=ios, iomsg=iomsg)
      call read_failed('lyapunov', ios, iomsg)
    end if
    close (unit)
    if (status /= SD_OK) return

    ! which description of the system: dimensionless (&model) or dimensional (&tank + &structure)
    if (given(1) .and. (given(2) .or. given(3))) then
      call fail('give either &model (dimensionless) or &tank with &structure (dimensional), '// &
                'not both')
    else if (.not. given(1) .and. .not. (given(2) .or. given(3))) then
      call fail('missing group &model (or &tank with &structure): the system is not described')
    else if (given(2) .neqv. given(3)) then
      call fail('&tank and &structure go together: group &'// &
                trim(merge('structure', 'tank     ', given(2)))//' is missing')
    end if
    if (status /= SD_OK) return

    config%dimensional = given(2)
    if (config%dimensional) then
      call require('tank', 'R', R)
      call require('tank', 'h', h)
      call require('structure', 'M', M)
      call require('structure', 'L', L)
      call require('structure', 'k', k)
      call require('structure', 'theta0', theta0)
      if (status /= SD_OK) return
      call tank_pendulum(R, h, rho_liquid, m_liquid, config%pendulum_length, &
                         config%sloshing_mass, config%d1, config%rigid_mass, config%d0, &
                         config%liquid_mass, status, message)
      if (status /= SD_OK) then
        message = '&tank: '//trim(message)
        return
      end if
      call model_from_physical(M, L, k, c, b, d, g, theta0, config%pendulum_length, &
                               config%sloshing_mass, s1, mu1, kappa, beta, gamma, delta, &
                               status, message)
      if (status /= SD_OK) then
        message = '&structure: '//trim(message)
        return
      end if
      config%radius = R; config%depth = h
      config%total_mass = M; config%rod_length = L; config%gravity = g
    else
      call require('model', 's1', s1)
      call require('model', 'mu1', mu1)
      call require('model', 'kappa', kappa)
      call require('model', 'theta0', theta0)
      if (status /= SD_OK) return
    end if
    call model_from_arrays([s1, mu1, kappa, theta0, beta, gamma, delta, A, rho], [n, p], &
                           config%model, status, message)
    if (status /= SD_OK) then
      message = trim(merge('&structure ', '&model     ', config%dimensional))//': '//trim(message)
      return
    end if

    kind = adjustl(kind)
    if (.not. any(known_analyses == kind)) then
      call fail('&analysis: kind = '''//trim(kind)//''' is not known; allowed: '// &
                join(known_analyses))
      return
    end if
    config%analysis = kind
    if (ieee_is_nan(kappa_max)) kappa_max = s1 + 1000
    call check_real('sigma1', sigma1, -huge(1.0_wp), huge(1.0_wp), .false., .false., &
                    'sigma1 must be finite', status, message)
    call check_real('kappa_max', kappa_max, s1, huge(1.0_wp), .true., .true., &
                    'kappa_max must be > s1 = '//num2str(s1), status, message)
    call check_real('kappa_min', kappa_min, -huge(1.0_wp), kappa_max, .false., .true., &
                    'kappa_min must be < kappa_max = '//num2str(kappa_max), status, message)
    if (status /= SD_OK) then
      message = '&analysis: '//trim(message)
      return
    end if
    config%sigma1 = sigma1; config%kappa_min = kappa_min; config%kappa_max = kappa_max
    if (len_trim(directory) == 0) then
      call fail('&output: directory = '''' is empty: give a directory name')
      return
    end if
    config%directory = directory

    ! integration and the analysis' own settings
    config%integration%rtol = rtol; config%integration%atol = atol
    config%integration%h_initial = h_initial; config%integration%h_max = h_max
    config%integration%h_min = h_min; config%integration%max_steps = max_steps
    config%y0 = y0
    method = adjustl(method)
    if (method /= 'rk45' .and. method /= 'dop853') then
      call fail('&integration: method = '''//trim(method)//''' is not known; allowed: rk45, dop853')
      return
    end if
    config%method = merge(METHOD_DOP853, METHOD_RK45, method == 'dop853')
    call rk45_check_setup(config%integration, [1.0_wp, 1.0_wp, 1.0_wp, 1.0_wp], status, message)
    if (status /= SD_OK) then
      message = '&integration: '//trim(message)
      return
    end if
    config%steady%transient_periods = transient_periods; config%steady%settle_tol = settle_tol
    config%steady%max_transient_periods = max_transient_periods
    config%steady%window_periods = window_periods
    config%steady%samples_per_period = samples_per_period
    config%steady%periodic_tol = periodic_tol
    select case (config%analysis)
    case ('linear')
      call require_stable_trivial(config%model, status, message)
      if (status /= SD_OK) return
    case ('simulate')
      call require('simulation', 't_end', t_end)
      if (status /= SD_OK) return
      call check_real('t_end', t_end, 0.0_wp, huge(1.0_wp), .true., .true., &
                      't_end must be > 0 (the simulation starts at tau = 0)', status, message)
      if (status == SD_OK .and. n_out == 0) n_out = 2001
      if (status == SD_OK .and. (n_out < 2 .or. n_out > 10000000)) then
        status = SD_BAD_INPUT
        message = 'n_out = '//num2str(n_out)//' is out of range: it must lie in [2, 10000000]'
      end if
      if (status == SD_OK .and. .not. all(abs(y0) <= huge(1.0_wp))) then
        status = SD_BAD_INPUT
        message = 'y0 must be finite (x1, x1'', x2, x2'')'
      end if
      if (status /= SD_OK) then
        message = '&simulation: '//trim(message)
        return
      end if
      config%t_end = t_end; config%n_out = n_out
    case ('steady_state', 'sweep')
      if (config%analysis == 'sweep') call read_sweep()
      if (status /= SD_OK) return
      call check_steady(config%model, config%steady, status, message)
      if (status == SD_OK .and. config%analysis == 'sweep' .and. config%sweep_parameter == 'rho') &
        call check_steady(with_rho(config%model, min(start, stop)), config%steady, status, message)
      if (status /= SD_OK) then
        message = trim(merge('&steady    ', '&excitation', index(message, 'rho') /= 1))// &
                  ': '//trim(message)
        return
      end if
    case ('frequency_response', 'periodic_response')
      call read_response()
      if (status /= SD_OK) return
      call require_stable_trivial(config%model, status, message)
      if (status /= SD_OK) return
      if (config%analysis == 'periodic_response') then
        call check_steady(with_rho(config%model, merge(config%sweep_start, config%model%rho, &
                          config%sweep_parameter == 'rho')), config%steady, status, message)
        if (status /= SD_OK) then
          message = '&steady/&excitation: '//trim(message)
          return
        end if
      end if
    case ('lyapunov')
      call check_real('rho', config%model%rho, 0.0_wp, huge(1.0_wp), .true., .true., &
                      'the Lyapunov exponent needs a forcing frequency rho > 0', status, message)
      if (status == SD_OK .and. (nint(transient_periods) < 0 .or. n_periods < 1 .or. &
                                 renormalise_every < 1)) then
        status = SD_BAD_INPUT
        message = 'transient_periods >= 0, n_periods >= 1 and renormalise_every >= 1 are needed'
      else if (status == SD_OK .and. mod(n_periods, max(renormalise_every, 1)) /= 0) then
        status = SD_BAD_INPUT
        message = 'n_periods = '//num2str(n_periods)//' is out of range: it must be a multiple '// &
                  'of renormalise_every = '//num2str(renormalise_every)
      end if
      if (status /= SD_OK) then
        message = '&lyapunov: '//trim(message)
        return
      end if
      config%lyapunov_transient = nint(transient_periods)
      config%lyapunov_periods = n_periods
      config%lyapunov_every = renormalise_every
    end select

  contains

    !> &response: the slow-flow frequency response; the ranges are checked here, the
    !> continuation settings by the continuation module when the analysis starts (before output).
    subroutine read_response()
      resonance = adjustl(resonance)
      parameter = adjustl(parameter)
      if (resonance /= '3:1' .and. resonance /= 'none') then
        call fail('&response: resonance = '''//trim(resonance)//''' is not known; allowed: '// &
                  '3:1, none')
        return
      end if
      if (parameter /= 'rho' .and. parameter /= 'A' .and. parameter /= 'a') then
        call fail('&response: parameter = '''//trim(parameter)//''' is not known; allowed: rho, A')
        return
      end if
      call require('response', 'start', start)
      call require('response', 'stop', stop)
      if (status /= SD_OK) return
      call check_real('start', min(start, stop), merge(0.0_wp, -tiny(1.0_wp), parameter == 'rho'), &
                      huge(1.0_wp), .true., .true., &
                      trim(merge('rho must be > 0 ', 'A must be >= 0  ', parameter == 'rho')), &
                      status, message)
      if (status == SD_OK .and. start == stop) then
        status = SD_BAD_INPUT
        message = 'start = stop = '//num2str(start)//': the interval is empty'
      end if
      if (status /= SD_OK) then
        message = '&response: '//trim(message)
        return
      end if
      config%internal_resonance = resonance == '3:1'
      config%sweep_parameter = merge('rho', 'A  ', parameter == 'rho')
      config%sweep_start = min(start, stop); config%sweep_stop = max(start, stop)
      config%response%n_scan = n_scan; config%response%n_amplitudes = n_amplitudes
      config%response%n_phases = n_phases; config%response%amplitude_min = amplitude_min
      config%response%amplitude_max = amplitude_max
      config%response%continuation%ds = ds; config%response%continuation%ds_min = ds_min
      config%response%continuation%ds_max = ds_max; config%response%continuation%x_scale = x_scale
    end subroutine read_response

    subroutine read_sweep()
      parameter = adjustl(parameter)
      direction = adjustl(direction)
      if (parameter /= 'rho' .and. parameter /= 'A' .and. parameter /= 'a') then
        call fail('&sweep: parameter = '''//trim(parameter)//''' is not known; allowed: rho, A')
        return
      end if
      if (direction /= 'up' .and. direction /= 'down' .and. direction /= 'both') then
        call fail('&sweep: direction = '''//trim(direction)//''' is not known; allowed: up, '// &
                  'down, both')
        return
      end if
      call require('sweep', 'start', start)
      call require('sweep', 'stop', stop)
      if (status /= SD_OK) return
      if (parameter == 'rho') then
        call check_real('start', start, 0.0_wp, huge(1.0_wp), .true., .true., &
                        'sweep values of rho must be > 0', status, message)
        call check_real('stop', stop, 0.0_wp, huge(1.0_wp), .true., .true., &
                        'sweep values of rho must be > 0', status, message)
      else
        call check_real('start', start, 0.0_wp, huge(1.0_wp), .false., .true., &
                        'sweep values of A must be >= 0', status, message)
        call check_real('stop', stop, 0.0_wp, huge(1.0_wp), .false., .true., &
                        'sweep values of A must be >= 0', status, message)
      end if
      if (status == SD_OK .and. (n_points < 1 .or. n_points > 100000)) then
        status = SD_BAD_INPUT
        message = 'n_points = '//num2str(n_points)//' is out of range: it must lie in [1, 100000]'
      end if
      if (status /= SD_OK) then
        message = '&sweep: '//trim(message)
        return
      end if
      config%sweep_parameter = merge('rho', 'A  ', parameter == 'rho')
      config%sweep_start = start; config%sweep_stop = stop
      config%sweep_points = n_points; config%sweep_direction = direction(1:4)
    end subroutine read_sweep

    subroutine fail(text)
      character(len=*), intent(in) :: text
      if (status /= SD_OK) return
      status = SD_BAD_INPUT
      message = text
    end subroutine fail

    subroutine require(group, name, value)
      character(len=*), intent(in) :: group, name
      real(wp), intent(in) :: value
      if (ieee_is_nan(value)) call fail('&'//group//': required variable '//name//' is missing')
    end subroutine require

    !> A failed namelist read: find the assignment that fails on its own to name the variable.
    subroutine read_failed(group, ios, iomsg)
      character(len=*), intent(in) :: group
      integer, intent(in) :: ios
      character(len=*), intent(in) :: iomsg
      character(len=message_len) :: culprit
      if (ios == 0) return
      call find_bad_assignment(path, group, culprit)
      if (len_trim(culprit) > 0) then
        call fail('&'//group//' in '''//trim(path)//''': '//trim(culprit))
      else
        call fail('&'//group//' in '''//trim(path)//''' cannot be read: '//trim(iomsg))
      end if
    end subroutine read_failed

    !> Read `&group <one assignment> /` from an internal file for each assignment of the group.
    subroutine find_bad_assignment(path, group, culprit)
      character(len=*), intent(in) :: path, group
      character(len=*), intent(out) :: culprit
      character(len=:), allocatable :: text
      character(len=:), allocatable :: assignment
      character(len=4096) :: buffer
      integer :: start, next, ios2, equals
      character(len=message_len) :: msg2

      culprit = ''
      assignment = ''
      call group_text(path, group, text)
      start = next_assignment(text, 1)
      do while (start > 0)
        next = next_assignment(text, start + 1)
        if (next > 0) then
          assignment = trim(text(start:next - 1))
        else
          assignment = trim(text(start:))
        end if
        ! the separator before the next assignment is not part of this one
        if (assignment(len(assignment):) == ',') assignment = trim(assignment(:len(assignment) - 1))
        buffer = '&'//group//' '//trim(assignment)//' /'
        select case (group)
        case ('model');      read (buffer, nml=model, iostat=ios2, iomsg=msg2)
        case ('tank');       read (buffer, nml=tank, iostat=ios2, iomsg=msg2)
        case ('structure');  read (buffer, nml=structure, iostat=ios2, iomsg=msg2)
        case ('excitation'); read (buffer, nml=excitation, iostat=ios2, iomsg=msg2)
        case ('analysis');   read (buffer, nml=analysis, iostat=ios2, iomsg=msg2)
        case ('output');     read (buffer, nml=output, iostat=ios2, iomsg=msg2)
        case ('integration'); read (buffer, nml=integration, iostat=ios2, iomsg=msg2)
        case ('simulation'); read (buffer, nml=simulation, iostat=ios2, iomsg=msg2)
        case ('steady');     read (buffer, nml=steady, iostat=ios2, iomsg=msg2)
        case ('sweep');      read (buffer, nml=sweep, iostat=ios2, iomsg=msg2)
        case ('response');   read (buffer, nml=response, iostat=ios2, iomsg=msg2)
        case default;        read (buffer, nml=lyapunov, iostat=ios2, iomsg=msg2)
        end select
        if (ios2 /= 0) then
          equals = index(assignment, '=')
          culprit = trim(adjustl(assignment(1:equals - 1)))//' ='//trim(assignment(equals + 1:))// &
                    ' is not valid: '//expected_type(lower(trim(adjustl(assignment(1:equals - 1)))))
          return
        end if
        start = next
      end do
    end subroutine find_bad_assignment
  end subroutine read_input

  pure function with_rho(model, rho) result(changed)
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: rho
    type(model_t) :: changed
    changed = model
    changed%rho = rho
  end function with_rho

  !> What a variable must be, for messages.
  pure function expected_type(name) result(text)
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: text
    select case (name)
    case ('n', 'p', 'max_steps', 'n_out', 'window_periods', 'samples_per_period', 'n_points', &
          'n_scan', 'n_amplitudes', 'n_phases', 'n_periods', 'renormalise_every')
      text = name//' must be an integer'
    case ('kind', 'directory', 'parameter', 'direction', 'resonance', 'method')
      text = name//' must be a quoted string'
    case ('y0')
      text = 'y0 must be four real numbers (x1, x1'''', x2, x2'''')'
    case ('s1', 'mu1', 'kappa', 'theta0', 'beta', 'gamma', 'delta', 'a', 'rho', 'r', 'h', &
          'rho_liquid', 'm_liquid', 'm', 'l', 'k', 'c', 'b', 'd', 'g', 'sigma1', 'kappa_min', &
          'kappa_max', 'rtol', 'atol', 'h_initial', 'h_max', 'h_min', 't_end', &
          'transient_periods', 'settle_tol', 'max_transient_periods', 'periodic_tol', 'start', &
          'stop', 'amplitude_min', 'amplitude_max', 'ds', 'ds_min', 'ds_max', 'x_scale')
      text = name//' must be a real number'
    case default
      text = 'unknown variable '''//name//''' (see the namelist reference in README.md)'
    end select
  end function expected_type

  !> Find every group name (&name) in the file; unknown or repeated groups are errors.
  !> Leaves the file rewound.
  subroutine scan_groups(unit, path, given, status, message)
    integer, intent(in) :: unit
    character(len=*), intent(in) :: path
    logical, intent(out) :: given(size(known_groups))
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    character(len=4096) :: line
    character(len=:), allocatable :: name
    integer :: ios, i, j, line_number

    given = .false.
    line_number = 0
    do
      read (unit, '(a)', iostat=ios) line
      if (ios /= 0) exit
      line_number = line_number + 1
      line = adjustl(line)
      if (line(1:1) /= '&' .and. line(1:1) /= '$') cycle
      j = 2
      do while (j <= len_trim(line))
        if (index('abcdefghijklmnopqrstuvwxyz0123456789_', lower(line(j:j))) == 0) exit
        j = j + 1
      end do
      name = lower(line(2:j - 1))
      if (name == 'end') cycle
      do i = size(known_groups), 1, -1
        if (known_groups(i) == name) exit
      end do
      if (i == 0) then
        status = SD_BAD_INPUT
        message = 'unknown namelist group &'//name//' in '''//trim(path)//''' (line '// &
                  num2str(line_number)//'); known groups: &'//join(known_groups, ', &')
        exit
      else if (given(i)) then
        status = SD_BAD_INPUT
        message = 'namelist group &'//name//' appears twice in '''//trim(path)//''''
        exit
      end if
      given(i) = .true.
    end do
    rewind (unit)
    if (status == SD_OK .and. .not. any(given)) then
      status = SD_BAD_INPUT
      message = 'no namelist group found in '''//trim(path)//''' (expected &model ... /)'
    end if
  end subroutine scan_groups

  !> The text of group `group` in the file, from after its name to its closing '/', with
  !> comments removed and lines joined.
  subroutine group_text(path, group, text)
    character(len=*), intent(in) :: path, group
    character(len=:), allocatable, intent(out) :: text
    character(len=4096) :: line
    integer :: unit, ios, i
    logical :: inside, quoted
    character :: quote

    text = ''
    inside = .false.
    quoted = .false.
    quote = ' '
    open (newunit=unit, file=path, status='old', action='read', iostat=ios)
    if (ios /= 0) return
    do
      read (unit, '(a)', iostat=ios) line
      if (ios /= 0) exit
      if (.not. inside) then
        line = adjustl(line)
        if (lower(line(1:len(group) + 1)) == '&'//group .and. &
            verify(line(len(group) + 2:len(group) + 2), ' ') == 0) then
          inside = .true.
          line = line(len(group) + 2:)
        else
          cycle
        end if
      end if
      do i = 1, len_trim(line)
        if (quoted) then
          if (line(i:i) == quote) quoted = .false.
        else if (line(i:i) == '"' .or. line(i:i) == '''') then
          quoted = .true.
          quote = line(i:i)
        else if (line(i:i) == '!') then
          exit
        else if (line(i:i) == '/') then
          close (unit)
          return
        end if
        text = text//line(i:i)
      end do
      text = text//' '
    end do
    close (unit)
  end subroutine group_text

  !> Position of the next `name =` at or after `from` outside quotes, 0 if none.
  pure integer function next_assignment(text, from) result(position)
    character(len=*), intent(in) :: text
    integer, intent(in) :: from
    integer :: i, j
    logical :: quoted
    character :: quote

    position = 0
    quoted = .false.
    quote = ' '
    do i = 1, len(text)
      if (quoted) then
        if (text(i:i) == quote) quoted = .false.
        cycle
      end if
      if (text(i:i) == '"' .or. text(i:i) == '''') then
        quoted = .true.
        quote = text(i:i)
        cycle
      end if
      if (i < from) cycle
      if (.not. is_name_start(text(i:i))) cycle
      if (i > 1) then
        if (is_name_char(text(i - 1:i - 1))) cycle
      end if
      j = i
      do while (j <= len(text))
        if (.not. is_name_char(text(j:j))) exit
        j = j + 1
      end do
      do while (j <= len(text))
        if (text(j:j) /= ' ') exit
        j = j + 1
      end do
      if (j <= len(text)) then
        if (text(j:j) == '=') then
          position = i
          return
        end if
      end if
    end do
  end function next_assignment

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
end module sloshdyn_namelist
