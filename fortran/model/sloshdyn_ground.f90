!> Ground motion in SI units: a recorded ground acceleration (uniform time step, piecewise linear
!> between samples, at rest after the record) or a harmonic acceleration u'' = -a sin(2 pi f t);
!> scaling of a record (a factor, a peak ground acceleration, or a spectral acceleration at a
!> period); its response spectrum (sloshdyn_sdof); and its excitation of a tank's model,
!> X'' = u''/(L omega^2) in the model's time tau = omega t.
module sloshdyn_ground
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, check_real
  use sloshdyn_text, only: num2str
  use sloshdyn_samples, only: check_samples, sampled_value
  use sloshdyn_excitation, only: excitation_t, record_excitation, EXCITATION_HARMONIC
  use sloshdyn_model, only: max_excitation
  use sloshdyn_sdof, only: response_spectrum
  implicit none
  private
  public :: ground_motion_t, harmonic_ground, record_ground, check_ground, ground_excitation, &
            ground_acceleration, ground_duration, ground_spectrum, scale_to_pga, scale_to_sa, &
            scale_ground, on_time_grid
  public :: spectral_acceleration, peak_ground_acceleration
  public :: GROUND_HARMONIC, GROUND_RECORD, harmonic_periods

  integer, parameter :: GROUND_HARMONIC = 1, GROUND_RECORD = 2
  !> Forcing periods that harmonic motion lasts unless told: its spectrum's samples, a seismic
  !> response's t_end (sloshdyn_seismic).
  integer, parameter :: harmonic_periods = 40
  !> Samples per period when a harmonic motion is sampled for its spectrum.
  integer, parameter :: samples_per_period = 200
  !> The finest time step of a record [s] (a thousand times finer than a 1 kHz accelerograph)
  !> and its longest duration (n - 1) dt [s] (11.6 days; earthquakes last minutes): beyond
  !> them the output grid of a response (t_end/dt outputs) and the spectra's free-vibration
  !> tails (5 periods/dt steps) no longer fit a count.
  real(wp), parameter, public :: min_record_step = 1.0e-6_wp, max_record_duration = 1.0e6_wp

  type :: ground_motion_t
    integer :: kind = GROUND_HARMONIC
    real(wp) :: peak_acceleration = 0      !< harmonic: a [m/s^2]
    real(wp) :: frequency = 0              !< harmonic: f [Hz]
    real(wp) :: dt = 0                     !< record: time step [s]
    real(wp), allocatable :: acceleration(:)   !< record: u'' [m/s^2] at t = (i - 1) dt
    real(wp) :: scale_factor = 1           !< the factor scale_ground applied
    character(len=96) :: scaling = ''      !< what it scaled to, with the damping and units
    character(len=96) :: name = ''         !< the record file's name (the namelist reader's)
  end type ground_motion_t

contains

  pure function harmonic_ground(peak_acceleration, frequency) result(ground)
    real(wp), intent(in) :: peak_acceleration, frequency
    type(ground_motion_t) :: ground
    ground%kind = GROUND_HARMONIC
    ground%peak_acceleration = peak_acceleration
    ground%frequency = frequency
  end function harmonic_ground

  pure function record_ground(dt, acceleration) result(ground)
    real(wp), intent(in) :: dt, acceleration(:)
    type(ground_motion_t) :: ground
    ground%kind = GROUND_RECORD
    ground%dt = dt
    allocate (ground%acceleration, source=acceleration)
  end function record_ground

  !> A record resampled onto the time grid t = (i - 1) dt of another record, over its own
  !> duration (n - 1) ground%dt (the last time within it, at least 2 samples): the same
  !> piecewise-linear function the model uses between samples (sloshdyn_samples' sampled_value;
  !> 0 after the record) evaluated there. Two components sampled at different steps so share
  !> the first one's grid, whose samples every integration steps to; between its samples the
  !> second is linear, so what it has between them is smoothed out (give the more finely
  !> sampled record first to keep it). The record as it is when dt is its own.
  pure function on_time_grid(ground, dt) result(resampled)
    type(ground_motion_t), intent(in) :: ground
    real(wp), intent(in) :: dt
    type(ground_motion_t) :: resampled
    integer :: i, n
    resampled = ground
    if (ground%kind /= GROUND_RECORD .or. ground%dt == dt) return
    ! the times within the duration; 1e-9 of a step keeps a last time that rounding puts just
    ! beyond it
    n = max(2, int((size(ground%acceleration) - 1)*(ground%dt/dt) + 1.0e-9_wp) + 1)
    resampled%dt = dt
    resampled%acceleration = [(sampled_value(ground%acceleration, ground%dt, (i - 1)*dt), &
                               i = 1, n)]
  end function on_time_grid

  !> The rules of a ground motion: a harmonic one with a >= 0 and f > 0; a record with dt >=
  !> min_record_step, at least 2 finite samples and a duration (n - 1) dt of at most
  !> max_record_duration.
  pure subroutine check_ground(ground, status, message)
    type(ground_motion_t), intent(in) :: ground
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    status = SD_OK
    message = ''
    if (ground%kind == GROUND_HARMONIC) then
      call check_real('peak_acceleration', ground%peak_acceleration, 0.0_wp, huge(1.0_wp), &
                      .false., .true., 'the peak ground acceleration must be >= 0', status, &
                      message)
      call check_real('frequency', ground%frequency, 0.0_wp, huge(1.0_wp), .true., .true., &
                      'the frequency of harmonic ground motion must be > 0 [Hz]', status, &
                      message)
      return
    end if
    call check_real('dt', ground%dt, min_record_step, huge(1.0_wp), .false., .true., &
                    'the time step of a record must be at least '//num2str(min_record_step)// &
                    ' s', status, message)
    if (status /= SD_OK) return
    if (.not. allocated(ground%acceleration)) then
      status = SD_BAD_INPUT
      message = 'the record has no samples: it needs at least 2'
    else
      call check_samples('the record', ground%acceleration, ground%dt, status, message)
    end if
    if (status == SD_OK) call check_real('the record''s duration (n - 1) dt', &
      ground_duration(ground), 0.0_wp, max_record_duration, .false., .false., &
      'a record ('//num2str(size(ground%acceleration))//' samples at dt = '// &
      num2str(ground%dt)//' s) may last at most '//num2str(max_record_duration)//' s', &
      status, message)
  end subroutine check_ground

  !> u''(t) [m/s^2].
  elemental real(wp) function ground_acceleration(ground, t) result(accel)
    type(ground_motion_t), intent(in) :: ground
    real(wp), intent(in) :: t
    if (ground%kind == GROUND_HARMONIC) then
      accel = -ground%peak_acceleration*sin(2*pi*ground%frequency*t)
      return
    end if
    accel = sampled_value(ground%acceleration, ground%dt, t)
  end function ground_acceleration

  !> Length of a record [s] (0 for harmonic motion, which does not end).
  elemental real(wp) function ground_duration(ground)
    type(ground_motion_t), intent(in) :: ground
    ground_duration = 0
    if (ground%kind == GROUND_RECORD) ground_duration = ground%dt*(size(ground%acceleration) - 1)
  end function ground_duration

  !> The excitation of a model whose time is tau = omega t and whose base displacement is
  !> X = u/L: X'' = u''/(L omega^2); harmonic: X = A sin(rho tau), rho = 2 pi f/omega,
  !> A = a/(L (2 pi f)^2).
  pure subroutine ground_excitation(ground, omega, rod_length, excitation, status, message)
    type(ground_motion_t), intent(in) :: ground
    real(wp), intent(in) :: omega, rod_length
    type(excitation_t), intent(out) :: excitation
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    call check_ground(ground, status, message)
    if (status /= SD_OK) return
    if (ground%kind == GROUND_HARMONIC) then
      excitation%kind = EXCITATION_HARMONIC
      excitation%rho = 2*pi*ground%frequency/omega
      excitation%A = ground%peak_acceleration/(rod_length*(2*pi*ground%frequency)**2)
      ! the rules of &excitation's rho and A, in the ground motion's terms
      call check_real('frequency', ground%frequency, 0.0_wp, max_excitation*omega/(2*pi), &
                      .true., .false., 'it gives rho = 2 pi f/omega = '// &
                      num2str(excitation%rho)//', and the model takes rho <= '// &
                      num2str(max_excitation)//': the frequency must be at most '// &
                      num2str(max_excitation*omega/(2*pi))//' Hz', status, message)
      call check_real('peak_acceleration', ground%peak_acceleration, 0.0_wp, &
                      max_excitation*rod_length*(2*pi*ground%frequency)**2, .false., .false., &
                      'it gives A = a/(L (2 pi f)^2) = '//num2str(excitation%A)// &
                      ', and the model takes A <= '//num2str(max_excitation)//' at f = '// &
                      num2str(ground%frequency)//' Hz', status, message)
    else
      call record_excitation(ground%acceleration/(rod_length*omega**2), omega*ground%dt, &
                             excitation, status, message)
    end if
  end subroutine ground_excitation

  !> Response spectrum of the ground motion (sloshdyn_sdof, exact for piecewise linear records):
  !> peak relative displacement sd [m], pseudo-velocity sv [m/s], pseudo-acceleration psa
  !> [m/s^2] at each period [s] for the damping ratio, followed by a free-vibration tail of
  !> tail_duration [s] so that late peaks count. Harmonic motion is sampled at 200 points per
  !> period over `duration` seconds (0: harmonic_periods forcing periods); a record is taken
  !> whole (duration is not used).
  subroutine ground_spectrum(ground, periods, damping, tail_duration, duration, sd, sv, &
                             psa, status, message)
    type(ground_motion_t), intent(in) :: ground
    real(wp), intent(in) :: periods(:), damping, tail_duration, duration
    real(wp), intent(out) :: sd(size(periods)), sv(size(periods)), psa(size(periods))
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: dt, span
    integer :: i, n
    sd = 0; sv = 0; psa = 0
    call check_ground(ground, status, message)
    if (status /= SD_OK) return
    if (ground%kind == GROUND_RECORD) then
      call response_spectrum(ground%dt, ground%acceleration, periods, damping, sd, sv, psa, &
                             status, message, tail_duration)
    else
      span = duration
      if (duration == 0) span = harmonic_periods/ground%frequency
      call check_real('duration', span, 0.0_wp, 1.0e7_wp/ground%frequency, .true., .false., &
                      'the duration of harmonic motion for a spectrum must be > 0 (0: '// &
                      num2str(real(harmonic_periods, wp))//' periods) and at most 1e7 periods', &
                      status, message)
      if (status /= SD_OK) return
      dt = 1/(samples_per_period*ground%frequency)
      n = int(span/dt) + 1
      call response_spectrum(dt, ground_acceleration(ground, [(dt*(i - 1), i = 1, n)]), periods, &
                             damping, sd, sv, psa, status, message, tail_duration)
    end if
  end subroutine ground_spectrum

  !> Scale a record (or a harmonic motion) so that its peak acceleration is pga [m/s^2].
  pure subroutine scale_to_pga(ground, pga, status, message)
    type(ground_motion_t), intent(inout) :: ground
    real(wp), intent(in) :: pga
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: peak
    call check_ground(ground, status, message)
    call check_real('target_pga', pga, 0.0_wp, huge(1.0_wp), .false., .true., &
                    'the target peak ground acceleration must be >= 0 [m/s^2]', status, message)
    if (status /= SD_OK) return
    if (ground%kind == GROUND_HARMONIC) then
      ground%peak_acceleration = pga
      return
    end if
    peak = peak_ground_acceleration(ground)
    if (peak == 0) then
      status = SD_BAD_INPUT
      message = 'the record is all zeros: it cannot be scaled to target_pga = '//num2str(pga)
      return
    end if
    ground%acceleration = ground%acceleration*(pga/peak)
  end subroutine scale_to_pga

  !> Scale so that the pseudo-spectral acceleration at period [s] (damping ratio) is sa [m/s^2].
  subroutine scale_to_sa(ground, sa, period, damping, status, message)
    type(ground_motion_t), intent(inout) :: ground
    real(wp), intent(in) :: sa, period, damping
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: psa, factor
    call check_real('target_sa', sa, 0.0_wp, huge(1.0_wp), .false., .true., &
                    'the target spectral acceleration must be >= 0 [m/s^2]', status, message)
    if (status /= SD_OK) return
    if (ground%kind == GROUND_RECORD .and. ground_duration(ground) < period) then
      ! the peak would come from the free-vibration tail alone: an extrapolation of the record
      status = SD_BAD_INPUT
      message = 'target_period = '//num2str(period)//' s is longer than the record ('// &
                num2str(ground_duration(ground))//' s): scaling to target_sa needs a record '// &
                'at least one target period long (or scale by target_pga or scale_factor)'
      return
    end if
    call spectral_acceleration(ground, period, damping, psa, status, message)
    if (status /= SD_OK) return
    if (psa == 0) then
      status = SD_BAD_INPUT
      message = 'the record has no spectral acceleration at period = '//num2str(period)// &
                ' s: it cannot be scaled to target_sa = '//num2str(sa)
      return
    end if
    factor = sa/psa
    if (ground%kind == GROUND_HARMONIC) then
      ground%peak_acceleration = ground%peak_acceleration*factor
    else
      ground%acceleration = ground%acceleration*factor
    end if
  end subroutine scale_to_sa

  !> The pseudo-spectral acceleration psa [m/s^2] of the ground motion at period [s] for the
  !> damping ratio, with the free-vibration tail of GroundMotion.response_spectrum's default (5
  !> periods): what target_sa scales to, and what a seismic run reports as achieved.
  subroutine spectral_acceleration(ground, period, damping, psa, status, message)
    type(ground_motion_t), intent(in) :: ground
    real(wp), intent(in) :: period, damping
    real(wp), intent(out) :: psa
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: sd(1), sv(1), sa(1)
    call ground_spectrum(ground, [period], damping, 5*period, 20*period, sd, sv, sa, status, &
                         message)
    psa = sa(1)
  end subroutine spectral_acceleration

  !> Scale by at most one of: a factor (1 = unscaled), a peak ground acceleration target_pga
  !> [m/s^2] (0 = none), or a pseudo-spectral acceleration target_sa [m/s^2] (0 = none) at
  !> target_period [s] for the damping ratio target_damping. ground%scale_factor is the factor
  !> applied, ground%scaling the target with its period, damping and units (summaries print
  !> them).
  subroutine scale_ground(ground, scale_factor, target_pga, target_sa, target_period, &
                          target_damping, status, message)
    type(ground_motion_t), intent(inout) :: ground
    real(wp), intent(in) :: scale_factor, target_pga, target_sa, target_period, target_damping
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    integer :: given
    real(wp) :: peak
    call check_ground(ground, status, message)
    call check_real('scale_factor', scale_factor, 0.0_wp, huge(1.0_wp), .false., .true., &
                    'scale_factor must be >= 0', status, message)
    call check_real('target_pga', target_pga, 0.0_wp, huge(1.0_wp), .false., .true., &
                    'target_pga must be >= 0 [m/s^2] (0: not scaled to a PGA)', status, message)
    call check_real('target_sa', target_sa, 0.0_wp, huge(1.0_wp), .false., .true., &
                    'target_sa must be >= 0 [m/s^2] (0: not scaled to a spectral acceleration)', &
                    status, message)
    if (status /= SD_OK) return
    given = count([target_pga > 0, target_sa > 0, scale_factor /= 1])
    if (given > 1) then
      status = SD_BAD_INPUT
      message = 'scale_factor = '//num2str(scale_factor)//', target_pga = '// &
                num2str(target_pga)//', target_sa = '//num2str(target_sa)//': give at most '// &
                'one of them'
      return
    end if
    peak = peak_ground_acceleration(ground)
    if (target_pga > 0) then
      call scale_to_pga(ground, target_pga, status, message)
      ground%scaling = 'PGA = '//num2str(target_pga)//' m/s^2'
    else if (target_sa > 0) then
      call check_real('target_period', target_period, 0.0_wp, huge(1.0_wp), .true., .true., &
                      'target_period must be > 0 [s]', status, message)
      call check_real('target_damping', target_damping, 0.0_wp, 1.0_wp, .false., .true., &
                      'target_damping must lie in [0, 1)', status, message)
      if (status == SD_OK) call scale_to_sa(ground, target_sa, target_period, target_damping, &
                                            status, message)
      ground%scaling = 'Sa('//num2str(target_period)//' s, '//num2str(100*target_damping)// &
                       ' % damping) = '//num2str(target_sa)//' m/s^2'
    else if (ground%kind == GROUND_RECORD) then
      ground%acceleration = ground%acceleration*scale_factor
    else
      ground%peak_acceleration = ground%peak_acceleration*scale_factor
    end if
    if (given == 1 .and. scale_factor /= 1) &
      ground%scaling = 'scale_factor = '//num2str(scale_factor)
    ground%scale_factor = scale_factor
    if ((target_pga > 0 .or. target_sa > 0) .and. peak > 0) &
      ground%scale_factor = peak_ground_acceleration(ground)/peak
  end subroutine scale_ground

  !> The largest |u''| [m/s^2] of a record's samples, or a harmonic motion's amplitude.
  pure real(wp) function peak_ground_acceleration(ground) result(peak)
    type(ground_motion_t), intent(in) :: ground
    if (ground%kind == GROUND_RECORD) then
      peak = maxval(abs(ground%acceleration))
    else
      peak = ground%peak_acceleration
    end if
  end function peak_ground_acceleration
end module sloshdyn_ground
