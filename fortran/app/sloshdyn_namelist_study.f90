!> &study: a parameter study run by Python on Dask (sloshdyn-py study), read and checked here
!> like every group so that both front doors know it (the executable refuses to run it); the
!> rules of the kind of study chosen apply (study_settings in sloshdyn_run_config).
module sloshdyn_namelist_study
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, check_real
  use sloshdyn_text, only: num2str
  use sloshdyn_namelist_scanner, only: input_file, require, fail, join
  use sloshdyn_namelist_groups, only: namelist_reader, G_STUDY, G_TANK, G_ANALYSIS
  use sloshdyn_run_config, only: run_config, study_settings, study_kinds, worker_kinds, &
                                 continuation_names, study_text_len, word_len
  use sloshdyn_model, only: model_t
  use sloshdyn_simulation, only: check_steady
  implicit none
  private
  public :: read_study

contains

  !> &study (see study_settings). The rules of the kind of study chosen apply.
  subroutine read_study(file, config, status, message)
    type(input_file), intent(inout) :: file
    type(run_config), intent(inout) :: config
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(study_settings) :: defaults
    character(len=word_len) :: kind, worker_kind, continuation
    character(len=study_text_len + 1) :: store, figure, scheduler, records
    real(wp) :: frequency_start, frequency_stop, amplitude_start, amplitude_stop, x1_start, &
                x1_stop, dx1_start, dx1_stop, tol, intensity_start, intensity_stop, &
                spectral_damping, grace_time
    integer :: workers, min_workers, points_per_task, n_frequencies, n_amplitudes, n_grid, n_intensities
    type(model_t) :: first
    type(namelist_reader) :: reader
    namelist /study/ kind, store, figure, scheduler, workers, worker_kind, points_per_task, &
                     min_workers, grace_time, &
                     frequency_start, frequency_stop, n_frequencies, amplitude_start, &
                     amplitude_stop, n_amplitudes, continuation, x1_start, x1_stop, dx1_start, &
                     dx1_stop, n_grid, tol, records, intensity_start, intensity_stop, &
                     n_intensities, spectral_damping

    kind = study_kinds(defaults%kind); store = ''; figure = ''; scheduler = ''
    workers = defaults%workers; worker_kind = worker_kinds(defaults%worker_kind)
    points_per_task = defaults%points_per_task
    min_workers = defaults%min_workers; grace_time = defaults%grace_time
    frequency_start = defaults%frequency_start; frequency_stop = defaults%frequency_stop
    n_frequencies = defaults%n_frequencies; amplitude_start = defaults%amplitude_start
    amplitude_stop = defaults%amplitude_stop; n_amplitudes = defaults%n_amplitudes
    continuation = continuation_names(defaults%continuation)
    x1_start = defaults%x1_start; x1_stop = defaults%x1_stop
    dx1_start = defaults%dx1_start; dx1_stop = defaults%dx1_stop
    n_grid = defaults%n_grid; tol = defaults%tol
    records = ''; intensity_start = defaults%intensity_start
    intensity_stop = defaults%intensity_stop; n_intensities = defaults%n_intensities
    spectral_damping = defaults%spectral_damping
    status = SD_OK
    message = ''
    call reader%start(file, G_STUDY, status)
    do while (reader%next())
      if (reader%describing) then
        write (reader%written, nml=study, iostat=reader%ios)
      else
        read (reader%text, nml=study, iostat=reader%ios, iomsg=reader%iomsg)
      end if
      call reader%check(file, status, message)
    end do
    if (status /= SD_OK .or. file%describing) return
    if (.not. file%groups(G_STUDY)%given) return
    associate (st => config%study)
      st%given = .true.
      call pick('kind', kind, study_kinds, st%kind)
      call pick('worker_kind', worker_kind, worker_kinds, st%worker_kind)
      call pick('continuation', continuation, continuation_names, st%continuation)
      call require(file, G_STUDY, 'store', status, message)
      if (status /= SD_OK) return
      if (len_trim(store) == 0) call fail(status, message, &
        '&study: store = '''' is empty: give the path of the Zarr store')
      if (len_trim(store) > study_text_len .or. len_trim(figure) > study_text_len .or. &
          len_trim(scheduler) > study_text_len) call fail(status, message, '&study: store, '// &
        'figure and scheduler must have at most '//num2str(study_text_len)//' characters')
      if (status /= SD_OK) return
      st%store = store(1:study_text_len)
      st%figure = figure(1:study_text_len)
      st%scheduler = scheduler(1:study_text_len)
      call check_count('workers', workers, 0, 1024)
      call check_count('points_per_task', points_per_task, 0, 1000000)
      call check_count('min_workers', min_workers, 1, 100000)
      if (status == SD_OK .and. workers > 0 .and. min_workers > workers .and. &
          len_trim(scheduler) == 0) call fail(status, message, '&study: min_workers = '// &
        num2str(min_workers)//' is out of range: the embedded cluster has workers = '// &
        num2str(workers))
      if (status == SD_OK) call check_real('grace_time', grace_time, 0.0_wp, 86400.0_wp, &
                                           .true., .false., 'grace_time must lie in (0, '// &
                                           '86400] seconds', status, message)
      if (status /= SD_OK) then
        if (index(message, '&study') /= 1) message = '&study: '//trim(message)
        return
      end if
      st%workers = workers
      st%points_per_task = points_per_task
      st%min_workers = min_workers
      st%grace_time = grace_time
      ! the studies run the planar model (issue 37): the spatial one is refused before they start
      if (.not. config%planar) call fail(status, message, '&study: a '// &
        trim(study_kinds(st%kind))//' study runs the planar model only: planar = .false. '// &
        '(the spatial model) in '//trim(merge('&tank ', '&model', config%dimensional))// &
        ' is not for studies; give planar = .true. or run one point with &analysis')
      if (status /= SD_OK) return
      first = config%model
      select case (st%kind)
      case (1)     ! response_map
        call require(file, G_STUDY, 'frequency_start', status, message)
        call require(file, G_STUDY, 'frequency_stop', status, message)
        call require(file, G_STUDY, 'amplitude_start', status, message)
        call require(file, G_STUDY, 'amplitude_stop', status, message)
        if (status /= SD_OK) return
        call check_real('frequency_start', frequency_start, 0.0_wp, huge(1.0_wp), .true., &
                        .true., 'frequencies (rho) must be > 0', status, message)
        call check_real('frequency_stop', frequency_stop, 0.0_wp, huge(1.0_wp), .true., &
                        .true., 'frequencies (rho) must be > 0', status, message)
        call check_real('amplitude_start', amplitude_start, 0.0_wp, huge(1.0_wp), .false., &
                        .true., 'amplitudes (A) must be >= 0', status, message)
        call check_real('amplitude_stop', amplitude_stop, 0.0_wp, huge(1.0_wp), .false., &
                        .true., 'amplitudes (A) must be >= 0', status, message)
        if (status /= SD_OK) then
          message = '&study: '//trim(message)
          return
        end if
        call check_count('n_frequencies', n_frequencies, 1, 100000)
        call check_count('n_amplitudes', n_amplitudes, 1, 100000)
        if (status == SD_OK .and. n_frequencies > 1 .and. frequency_start == frequency_stop) &
          call fail(status, message, '&study: frequency_start = frequency_stop with '// &
                    'n_frequencies > 1 repeats one frequency')
        if (status == SD_OK .and. n_amplitudes > 1 .and. amplitude_start == amplitude_stop) &
          call fail(status, message, '&study: amplitude_start = amplitude_stop with '// &
                    'n_amplitudes > 1 repeats one amplitude')
        if (status /= SD_OK) return
        st%frequency_start = frequency_start; st%frequency_stop = frequency_stop
        st%amplitude_start = amplitude_start; st%amplitude_stop = amplitude_stop
        st%n_frequencies = n_frequencies; st%n_amplitudes = n_amplitudes
        first%excitation%rho = min(frequency_start, frequency_stop)
      case (2)     ! basins
        call require(file, G_STUDY, 'x1_start', status, message)
        call require(file, G_STUDY, 'x1_stop', status, message)
        call require(file, G_STUDY, 'dx1_start', status, message)
        call require(file, G_STUDY, 'dx1_stop', status, message)
        if (status /= SD_OK) return
        call check_real('x1_stop', x1_stop, x1_start, huge(1.0_wp), .true., .true., &
                        'x1_stop must be > x1_start = '//num2str(x1_start), status, message)
        call check_real('dx1_stop', dx1_stop, dx1_start, huge(1.0_wp), .true., .true., &
                        'dx1_stop must be > dx1_start = '//num2str(dx1_start), status, message)
        call check_real('x1_start', x1_start, -huge(1.0_wp), huge(1.0_wp), .false., .false., &
                        'x1_start must be finite', status, message)
        call check_real('dx1_start', dx1_start, -huge(1.0_wp), huge(1.0_wp), .false., .false., &
                        'dx1_start must be finite', status, message)
        call check_real('tol', tol, 0.0_wp, 1.0_wp, .true., .true., 'tol must lie in (0, 1)', &
                        status, message)
        if (status /= SD_OK) then
          message = '&study: '//trim(message)
          return
        end if
        call check_count('n_grid', n_grid, 2, 10000)
        if (status /= SD_OK) return
        st%x1_start = x1_start; st%x1_stop = x1_stop
        st%dx1_start = dx1_start; st%dx1_stop = dx1_stop
        st%n_grid = n_grid; st%tol = tol
      case (3)     ! fragility
        if (.not. file%groups(G_TANK)%given) then
          call fail(status, message, '&study: a fragility study needs the tank: group &tank '// &
                    'is missing')
          return
        end if
        call require(file, G_STUDY, 'records', status, message)
        call require(file, G_STUDY, 'intensity_start', status, message)
        call require(file, G_STUDY, 'intensity_stop', status, message)
        if (status /= SD_OK) return
        if (len_trim(records) == 0 .or. len_trim(records) > study_text_len) &
          call fail(status, message, '&study: records must name the record files (a pattern '// &
                    'such as ''records/*.AT2''), at most '//num2str(study_text_len)// &
                    ' characters')
        call check_real('intensity_start', intensity_start, 0.0_wp, huge(1.0_wp), .true., &
                        .true., 'intensities (Sa [g]) must be > 0', status, message)
        call check_real('intensity_stop', intensity_stop, intensity_start, huge(1.0_wp), &
                        .false., .true., 'intensity_stop must be >= intensity_start = '// &
                        num2str(intensity_start), status, message)
        call check_real('spectral_damping', spectral_damping, 0.0_wp, 1.0_wp, .false., .true., &
                        'spectral_damping must lie in [0, 1)', status, message)
        if (status /= SD_OK) then
          if (index(message, '&study') /= 1) message = '&study: '//trim(message)
          return
        end if
        call check_count('n_intensities', n_intensities, 1, 100000)
        if (status == SD_OK .and. n_intensities > 1 .and. intensity_start == intensity_stop) &
          call fail(status, message, '&study: intensity_start = intensity_stop with '// &
                    'n_intensities > 1 repeats one intensity')
        if (status /= SD_OK) return
        st%records = records(1:study_text_len)
        st%intensity_start = intensity_start; st%intensity_stop = intensity_stop
        st%n_intensities = n_intensities; st%spectral_damping = spectral_damping
      end select
      if (file%groups(G_ANALYSIS)%given) then
        call fail(status, message, 'give &analysis (a run of the executable) or &study (a '// &
                  'study, sloshdyn-py study), not both')
        return
      end if
      if (st%kind == 3) return
      call check_steady(first, config%steady, status, message)
      if (status /= SD_OK) message = trim(merge('&excitation', '&steady    ', &
                                                index(message, 'rho') == 1))//': '//trim(message)
    end associate

  contains

    subroutine pick(name, value, names, code)
      character(len=*), intent(in) :: name, value, names(:)
      integer, intent(inout) :: code
      integer :: i
      if (status /= SD_OK) return
      code = 0
      do i = 1, size(names)
        if (names(i) == adjustl(value)) code = i
      end do
      if (code == 0) call fail(status, message, '&study: '//name//' = '''// &
                               trim(adjustl(value))//''' is not known; allowed: '//join(names))
    end subroutine pick

    subroutine check_count(name, value, lower, upper)
      character(len=*), intent(in) :: name
      integer, intent(in) :: value, lower, upper
      if (status /= SD_OK) return
      if (value < lower .or. value > upper) call fail(status, message, '&study: '//name// &
        ' = '//num2str(value)//' is out of range: it must lie in ['//num2str(lower)//', '// &
        num2str(upper)//']')
    end subroutine check_count
  end subroutine read_study
end module sloshdyn_namelist_study
