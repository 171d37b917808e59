!> A tank under ground motion in two horizontal components (issue 26): the spatial model
!> (sloshdyn_spatial) of the tank of sloshdyn_vessel, and beside it the design codes' ways of
!> combining two planar analyses.
!>
!> Ground motion: component 1 along the azimuth alpha (from the x axis), component 2 across it
!> (alpha + 90 degrees); both records (scaled by one factor by the caller, as FEMA P695 scales a
!> pair; the second resampled onto the first one's time grid, sloshdyn_ground's on_time_grid), or harmonic motion along alpha with the ellipticity e of
!> sloshdyn_spatial (component 2 is then e times component 1, a quarter period later).
!>
!> Loads (SI) at each output time, from the horizontal accelerations of the tank and of the
!> sloshing mass (sloshdyn_spatial's spatial_kinematics), as sloshdyn_vessel's tank_loads for
!> one component: the base shear vector (M - m) a_tank + m a_mass, the overturning moment
!> vector of the same inertia forces at their heights (its x entry is the moment of the forces
!> along x, about the y axis), their resultants, and the wave height at the wall: linear first
!> mode, eta(psi) = wave_factor sin(Theta) cos(psi - psi_n) at azimuth psi for a pendulum tilted
!> by Theta towards psi_n, so that eta_x = wave_factor n_x, eta_y = wave_factor n_y, and its
!> maximum over the wall wave_factor |n_h| is at psi = psi_n (docs/model.md, "Spatial model and
!> swirl"); in the plane these are tank_loads' rows.
!>
!> The roof, as in the planar run (sloshdyn_seismic): the model is the tank's without contact
!> (beta = delta = 0); the roof is judged on the free wave around the whole wall (its largest
!> height over the azimuth, at the output times: reached, the first contact's time, linear
!> between the outputs, and azimuth, the entries above the freeboard, the largest free wave and
!> its excess), and from the first contact on the confined convective mass of the largest free
!> wave (sloshdyn_roof) moves with the tank: a_mass + phi (a_tank - a_mass) in the loads; the
!> reported wave height is capped at the roof, the free one beside it.
!>
!> Beside the spatial peaks, the codes' combinations of two planar runs (run 1: component 1
!> alone; run 2: component 2 alone): the SRSS, sqrt(P1^2 + P2^2), and the 100/30 rule,
!> max(P1 + 0.3 P2, 0.3 P1 + P2) (ASCE 7-16 12.5.3.1(a); EN 1998-1 4.3.3.5.1, SRSS and eq
!> 4.18-4.20), with the peaks P of each run over the same output times. For harmonic motion
!> component 2 is the ellipse's minor axis, e a cos(2 pi f t); the codes combine peaks and leave
!> the phases out, and so does run 2: the planar run under e a sin(2 pi f t) (none for e = 0:
!> P2 = 0, and both combinations are P1).
!>
!> Layouts (sloshdyn_tables): table(:, i) = 'seismic_spatial', peaks = 'seismic_spatial_peaks'.
module sloshdyn_seismic_spatial
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT
  use sloshdyn_model, only: model_t
  use sloshdyn_excitation, only: excitation_t
  use sloshdyn_vessel, only: tank_t, tank_properties
  use sloshdyn_ground, only: ground_motion_t, ground_excitation, harmonic_ground, on_time_grid, &
                             GROUND_RECORD
  use sloshdyn_spatial, only: spatial_model_t, spatial_model, spatial_kinematics, &
                              ground_acceleration
  use sloshdyn_ode, only: ode_options, ode_stats
  use sloshdyn_simulation, only: spatial_time_history
  use sloshdyn_seismic, only: seismic_response, seismic_setup, contact_free, &
                              confined_convective_mass
  use sloshdyn_tables, only: SEISMIC_ROWS, PEAKS_SIZE, SEISMIC_SPATIAL_ROWS, &
                             SEISMIC_SPATIAL_PEAKS, SPATIAL_HISTORY_ROWS, SEISMIC_WAVE_HEIGHT, &
                             SEISMIC_BASE_SHEAR, SEISMIC_OVERTURNING_MOMENT, PEAK_INSTANT_ROWS, &
                             PEAK_INSTANTS
  implicit none
  private
  public :: seismic_response_spatial

  !> rows of the planar 'seismic' table used for the combinations: wave height at the wall,
  !> base shear, overturning moment
  integer, parameter :: planar_rows(3) = [SEISMIC_WAVE_HEIGHT, SEISMIC_BASE_SHEAR, &
                                           SEISMIC_OVERTURNING_MOMENT]
  !> rows of 'seismic_spatial': the wave at the wall (capped resultant, azimuth), the
  !> base shear's and the overturning moment's resultants, the free wave; and the roof's
  !> entries of 'seismic_spatial_peaks'
  integer, parameter :: WAVE_ROW = 6, WAVE_AZIMUTH_ROW = 7, SHEAR_ROW = 10, MOMENT_ROW = 13, &
                        FREE_WAVE = 18
  integer, parameter :: ROOF_REACHED = 20, ROOF_CONFINED = 28

contains

  !> The response of the tank at rest at t = 0 to the two components ground_1 (along azimuth
  !> [rad]) and ground_2 (across it; a record, resampled onto ground_1's time grid if its dt
  !> differs, or, with harmonic ground_1, ignored: ellipticity gives the second component) at
  !> n_out times evenly spaced over [0, t_end] [s]: table(SEISMIC_SPATIAL_ROWS, n_out) and
  !> peaks(SEISMIC_SPATIAL_PEAKS).
  subroutine seismic_response_spatial(tank, ground_1, ground_2, azimuth, ellipticity, t_end, &
                                      n_out, options, method, table, peaks, status, message)
    type(tank_t), intent(in) :: tank
    type(ground_motion_t), intent(in) :: ground_1, ground_2
    real(wp), intent(in) :: azimuth, ellipticity, t_end
    integer, intent(in) :: n_out, method
    type(ode_options), intent(in) :: options
    real(wp), intent(out) :: table(SEISMIC_SPATIAL_ROWS, n_out), peaks(SEISMIC_SPATIAL_PEAKS)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(model_t) :: planar
    type(tank_properties) :: props
    type(excitation_t) :: second
    type(spatial_model_t) :: model
    type(ode_stats) :: stats
    type(ground_motion_t) :: across
    real(wp), allocatable :: tau(:), y(:, :), run(:, :)
    real(wp) :: run_peaks(PEAKS_SIZE), instants(PEAK_INSTANT_ROWS, PEAK_INSTANTS), p1(3), &
                p2(3), n_h(2), a_tank(2), a_mass(2), scale, shear(2), moment(2), share, &
                tau_contact, freeboard
    integer :: i, k
    logical :: records

    table = ieee_value(1.0_wp, ieee_quiet_nan)
    peaks = ieee_value(1.0_wp, ieee_quiet_nan)
    call seismic_setup(tank, ground_1, t_end, n_out, planar, props, tau, status, message)
    records = ground_1%kind == GROUND_RECORD
    if (status == SD_OK .and. records) then
      if (ground_2%kind /= GROUND_RECORD) then
        status = SD_BAD_INPUT
        message = 'the second component must be a record, as the first one is'
      else
        across = on_time_grid(ground_2, ground_1%dt)
        call ground_excitation(across, props%omega, props%rod_length, second, status, message)
      end if
    end if
    if (status /= SD_OK) return
    ! the tank without contact below its roof (sloshdyn_seismic's contact_free)
    planar = contact_free(planar)
    if (records) then
      call spatial_model(planar, azimuth, 0.0_wp, model, status, message, second)
    else
      call spatial_model(planar, azimuth, ellipticity, model, status, message)
      ! the second component of the codes' combination: harmonic motion of peak e a
      across = harmonic_ground(ellipticity*ground_1%peak_acceleration, ground_1%frequency)
    end if
    if (status /= SD_OK) return

    allocate (y(SPATIAL_HISTORY_ROWS, n_out))
    call spatial_time_history(model, 0.0_wp, [(0.0_wp, i = 1, 8)], tau, options, method, y, &
                              stats, status, message)
    if (status /= SD_OK) return
    ! the roof, judged on the free wave around the wall, and its confined mass
    freeboard = tank%freeboard
    peaks(ROOF_REACHED:ROOF_CONFINED) = 0
    do i = 1, n_out
      call spatial_kinematics(model, tau(i), y(1:8, i), n_h, a_tank, a_mass)
      table(FREE_WAVE, i) = props%wave_factor*norm2(n_h)
    end do
    call roof_of_free_wave(table(FREE_WAVE, :), tau/props%omega, freeboard, peaks(ROOF_REACHED:))
    share = 0
    tau_contact = huge(1.0_wp)
    if (peaks(ROOF_REACHED) > 0) then
      call confined_convective_mass(tank, props, peaks(ROOF_REACHED + 4), &
                                    peaks(ROOF_REACHED + 6), peaks(ROOF_REACHED + 7), &
                                    peaks(ROOF_CONFINED), status, message)
      if (status /= SD_OK) return
      share = peaks(ROOF_CONFINED)/props%sloshing_mass
      tau_contact = props%omega*peaks(ROOF_REACHED + 1)
      k = findloc(table(FREE_WAVE, :) >= freeboard, .true., dim=1)
      call spatial_kinematics(model, tau(k), y(1:8, k), n_h, a_tank, a_mass)
      peaks(ROOF_REACHED + 2) = atan2(n_h(2), n_h(1))
    end if
    scale = props%rod_length*props%omega**2     ! L omega^2 [m/s^2]
    do i = 1, n_out
      call spatial_kinematics(model, tau(i), y(1:8, i), n_h, a_tank, a_mass)
      if (tau(i) >= tau_contact) a_mass = a_mass + share*(a_tank - a_mass)
      shear = ((props%total_mass - props%sloshing_mass)*a_tank + props%sloshing_mass*a_mass)* &
              scale
      moment = ((props%rigid_mass*props%impulsive_height + tank%tank_mass*props%shell_height)* &
                a_tank + props%sloshing_mass*props%convective_height*a_mass)*scale
      table(1:FREE_WAVE - 1, i) = [tau(i)/props%omega, ground_acceleration(model, tau(i))*scale, &
                                   props%wave_factor*n_h, &
                                   min(props%wave_factor*norm2(n_h), freeboard), &
                                   atan2(n_h(2), n_h(1)), shear, norm2(shear), moment, &
                                   norm2(moment), y(1:7:2, i)]
    end do
    k = maxloc(table(FREE_WAVE, :), 1)
    peaks(1:3) = [table(WAVE_ROW, k), table(WAVE_AZIMUTH_ROW, k), table(1, k)]
    k = maxloc(table(SHEAR_ROW, :), 1)
    peaks(4:5) = [table(SHEAR_ROW, k), table(1, k)]
    k = maxloc(table(MOMENT_ROW, :), 1)
    peaks(6:7) = [table(MOMENT_ROW, k), table(1, k)]

    ! the two planar runs, one per component (the second none for harmonic motion along azimuth)
    allocate (run(SEISMIC_ROWS, n_out))
    call planar_peaks(ground_1, '1', p1)
    if (status == SD_OK) then
      if (records .or. ellipticity > 0) then
        call planar_peaks(across, '2', p2)
      else
        p2 = 0
      end if
    end if
    if (status /= SD_OK) return
    do k = 1, 3
      peaks(4 + 4*k:7 + 4*k) = [p1(k), p2(k), hypot(p1(k), p2(k)), &
                                max(p1(k) + 0.3_wp*p2(k), 0.3_wp*p1(k) + p2(k))]
    end do

  contains

    !> The peaks over the output times of the planar run of one component (planar_rows).
    subroutine planar_peaks(ground, label, p)
      type(ground_motion_t), intent(in) :: ground
      character(len=1), intent(in) :: label
      real(wp), intent(out) :: p(3)
      call seismic_response(tank, ground, t_end, n_out, options, method, run, run_peaks, &
                            instants, status, message)
      if (status /= SD_OK) message = 'the planar run of component '//label//': '//trim(message)
      p = maxval(abs(run(planar_rows, :)), 2)
    end subroutine planar_peaks
  end subroutine seismic_response_spatial

  !> The roof verdict of the free wave's largest height around the wall, wave(:) [m] at the
  !> times t(:) [s], against the freeboard f: roof(1:6) = [reached (1/0), the first time it
  !> reaches f (linear between the samples; NaN: never), the azimuth there [rad] (set by the
  !> caller), the entries into [f, inf), the largest height [m], its excess over f [m]].
  pure subroutine roof_of_free_wave(wave, t, freeboard, roof)
    real(wp), intent(in) :: wave(:), t(:), freeboard
    real(wp), intent(inout) :: roof(:)
    logical :: above(size(wave))
    integer :: i
    above = wave >= freeboard
    i = findloc(above, .true., dim=1)
    roof(1:6) = [merge(1.0_wp, 0.0_wp, i > 0), ieee_value(1.0_wp, ieee_quiet_nan), &
                 ieee_value(1.0_wp, ieee_quiet_nan), &
                 real(count(above(2:) .and. .not. above(:size(wave) - 1)) + &
                      merge(1, 0, above(1)), wp), maxval(wave), maxval(wave) - freeboard]
    if (i == 1) then
      roof(2) = t(1)
    else if (i > 1) then
      roof(2) = t(i - 1) + (t(i) - t(i - 1))*(freeboard - wave(i - 1))/(wave(i) - wave(i - 1))
    end if
  end subroutine roof_of_free_wave
end module sloshdyn_seismic_spatial
