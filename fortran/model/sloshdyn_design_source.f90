!> Where the design check's spectral accelerations come from (docs/design.md, "Which spectrum
!> feeds which code"): a code design spectrum (sloshdyn_design_spectra) or a ground motion's
!> pseudo-spectral acceleration (sloshdyn_ground), asked for by the code modules through one
!> type, so that a code's formulas do not depend on the source.
module sloshdyn_design_source
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK
  use sloshdyn_ground, only: ground_motion_t, ground_spectrum, peak_ground_acceleration
  use sloshdyn_design_spectra, only: design_spectrum_t, spectrum_sa, plateau_sa, &
                                     ec8_design_sa
  implicit none
  private
  public :: design_source_t, source_sa, source_impulsive_sa, record_sds

  !> ASCE 7-16 21.4: S_DS of a site-specific spectrum is 90 % of its largest Sa (5 %) between
  !> 0.2 and 5 s; sampled at this many log-spaced periods.
  integer, parameter :: sds_periods = 100

  !> The source: from_ground, the ground motion's spectrum (spec then supplies only K and q),
  !> else the code spectrum spec; gravity [m/s^2] turns the ground's [m/s^2] into g.
  type :: design_source_t
    type(design_spectrum_t) :: spec
    logical :: from_ground = .false.
    type(ground_motion_t) :: ground
    real(wp) :: gravity = 9.80665_wp
  end type design_source_t

contains

  !> Sa [g] at the period [s] and damping ratio of the code spectrum of kind `kind` (the
  !> source's own parameters, read as that code's spectrum), or of the ground motion.
  subroutine source_sa(source, kind, period, damping_ratio, value, status, message)
    type(design_source_t), intent(in) :: source
    integer, intent(in) :: kind
    real(wp), intent(in) :: period, damping_ratio
    real(wp), intent(out) :: value
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(design_spectrum_t) :: spec
    real(wp) :: sd(1), sv(1), psa(1)
    if (source%from_ground) then
      call ground_spectrum(source%ground, [period], damping_ratio, 5*period, 0.0_wp, sd, sv, &
                           psa, status, message)
      value = psa(1)/source%gravity
      if (status /= SD_OK) message = 'the ground motion''s spectrum for the design check: '// &
                                     trim(message)
    else
      spec = source%spec
      spec%kind = kind
      call spectrum_sa(spec, period, damping_ratio, value, status, message)
      if (status /= SD_OK) message = 'the design spectrum for the design check: '//trim(message)
    end if
  end subroutine source_sa

  !> The impulsive spectral acceleration [g] at period (0: on the spectrum's plateau; a ground
  !> motion: the rigid tank, its peak acceleration) and damping ratio, of the spectrum of kind
  !> `kind`; design (EN 1998-1): the design spectrum with q (a ground motion: its Sa / q).
  subroutine source_impulsive_sa(source, kind, period, damping_ratio, design, value, status, &
                                 message)
    type(design_source_t), intent(in) :: source
    integer, intent(in) :: kind
    real(wp), intent(in) :: period, damping_ratio
    logical, intent(in) :: design
    real(wp), intent(out) :: value
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(design_spectrum_t) :: spec
    status = SD_OK
    message = ''
    spec = source%spec
    spec%kind = kind
    if (source%from_ground .and. period == 0) then
      value = peak_ground_acceleration(source%ground)/source%gravity
    else if (source%from_ground .or. (period > 0 .and. .not. design)) then
      call source_sa(source, kind, period, damping_ratio, value, status, message)
    else if (period == 0) then
      call plateau_sa(spec, damping_ratio, design, value, status, message)
    else
      call ec8_design_sa(spec, period, value, status, message)
    end if
    if (source%from_ground .and. design) value = value/source%spec%q
    if (status /= SD_OK .and. index(message, 'design check') == 0) &
      message = 'the design spectrum for the design check: '//trim(message)
  end subroutine source_impulsive_sa

  !> S_DS [g] of the source: the code spectrum's, or ASCE 7-16 21.4's of the ground motion
  !> (90 % of its largest Sa at 5 % between 0.2 and 5 s).
  subroutine record_sds(source, value, status, message)
    type(design_source_t), intent(in) :: source
    real(wp), intent(out) :: value
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), dimension(sds_periods) :: periods, sd, sv, psa
    integer :: i
    status = SD_OK
    message = ''
    if (.not. source%from_ground) then
      value = source%spec%s_ds
      return
    end if
    periods = [(0.2_wp*25.0_wp**(real(i - 1, wp)/(sds_periods - 1)), i = 1, sds_periods)]
    call ground_spectrum(source%ground, periods, 0.05_wp, 5*periods(sds_periods), 0.0_wp, sd, &
                         sv, psa, status, message)
    value = 0.9_wp*maxval(psa)/source%gravity
  end subroutine record_sds
end module sloshdyn_design_source
