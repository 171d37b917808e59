!> The hydrodynamic pressure on the wall and base of a circular tank at instants of a seismic
!> run (sloshdyn_seismic's seismic_response), from the accelerations the run kept: at its load
!> peaks the run's own instants ('seismic_peak_instants': the tank's absolute acceleration a_t
!> and the modes' absolute accelerations a_1..a_N at the peak), and at any other times the output
!> times nearest them (output_instants, from the run's table). No integration is repeated. The
!> pressure is that of sloshdyn_wall_pressure's instant_pressure_tables (docs/model.md,
!> "Pressure at an instant of a time history"):
!>   a_t = u'' + L (cos(phi) phi'' - sin(phi) phi'^2)              (sloshdyn_vessel)
!>   a_1 = the convective mass's mean acceleration (the pendulum's, with the roof's confined
!>         share moving with the tank after the first contact: sloshdyn_vessel's tank_loads)
!>   a_n = a_t + x_n'' for n = 2..N, x_n the linear oscillator of mode n on a_t between the
!>         output times (sloshdyn_seismic's modal_responses, Nigam & Jennings).
!> Table 'pressure_instants' (one column per instant): the time, a_t and the base shear and
!> overturning moments that the pressures and the shell's inertia give.
module sloshdyn_seismic_pressure
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, check_real
  use sloshdyn_text, only: num2str
  use sloshdyn_model, only: model_t
  use sloshdyn_vessel, only: tank_t, tank_properties, tank_model
  use sloshdyn_seismic, only: modal_responses
  use sloshdyn_tank, only: max_modes
  use sloshdyn_wall_pressure, only: instant_pressure_tables, convective_resultants, &
                                    check_pressure_input, COMBINE_SUM
  use sloshdyn_tables, only: WALL_PRESSURE_ROWS, BASE_PRESSURE_ROWS, PRESSURE_INSTANT_ROWS, &
                             PEAK_INSTANT_ROWS
  implicit none
  private
  public :: instant_pressures, output_instants

contains

  !> The instants ('seismic_peak_instants' columns: t, a_t, a_1..a_max_modes) of the output
  !> times nearest to times(:) [s] of a run whose table gave t(:) [s] (evenly spaced), the
  !> tank's acceleration tank_accel(:) and the convective mass's convective_accel(:) [m/s^2]
  !> there; modes 2..N from a_t as the run computed them.
  subroutine output_instants(tank, t, tank_accel, convective_accel, times, instants, status, &
                             message)
    type(tank_t), intent(in) :: tank
    real(wp), intent(in) :: t(:), tank_accel(size(t)), convective_accel(size(t)), times(:)
    real(wp), intent(out) :: instants(PEAK_INSTANT_ROWS, size(times))
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(model_t) :: model
    type(tank_properties) :: props
    real(wp) :: modal(size(t), max_modes), wave(size(t))
    integer :: i, k

    instants = 0
    call tank_model(tank, model, props, status, message)
    if (status /= SD_OK) return
    do k = 1, size(times)
      call check_real('times('//num2str(k)//')', times(k), t(1), t(size(t)), .false., .false., &
                      'the instants [s] must lie in the run, [0, t_end = '//num2str(t(size(t)))// &
                      ']', status, message)
    end do
    if (status /= SD_OK) return
    modal = 0
    modal(:, 1) = convective_accel
    wave = 0
    call modal_responses(props, tank%sloshing_damping, t, tank_accel, wave, status, message, &
                         modal=modal(:, 1:props%modes))
    if (status /= SD_OK) return
    do k = 1, size(times)
      i = nint((times(k) - t(1))/(t(2) - t(1))) + 1
      instants(:, k) = [t(i), tank_accel(i), modal(i, :)]
    end do
  end subroutine output_instants

  !> The pressure at instants(:, k) (t, a_t, a_1..a_max_modes; those beyond the tank's modes
  !> unused): loads(:, k) (the 'pressure_instants' columns), wall(:, :, k) and base(:, :, k)
  !> (the 'wall_pressure' and 'base_pressure' tables at heights and radii, angle [rad]).
  subroutine instant_pressures(tank, instants, heights, radii, angle, loads, wall, base, status, &
                               message)
    type(tank_t), intent(in) :: tank
    real(wp), intent(in) :: instants(:, :), heights(:), radii(:), angle
    real(wp), intent(out) :: loads(PRESSURE_INSTANT_ROWS, size(instants, 2)), &
                             wall(WALL_PRESSURE_ROWS, size(heights), size(instants, 2)), &
                             base(BASE_PRESSURE_ROWS, size(radii), size(instants, 2))
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(model_t) :: model
    type(tank_properties) :: props
    integer :: k

    loads = 0
    wall = 0
    base = 0
    call tank_model(tank, model, props, status, message)
    if (status == SD_OK) call check_pressure_input(tank, 0.0_wp, props%modal_mass(1:props%modes), &
                                                   angle, COMBINE_SUM, heights, radii, status, &
                                                   message)
    if (status /= SD_OK) return
    do k = 1, size(instants, 2)
      associate (t => instants(1, k), a_t => instants(2, k), &
                 a_n => instants(3:2 + props%modes, k))
        call instant_pressure_tables(tank, a_t, a_n, angle, heights, radii, wall(:, :, k), &
                                     base(:, :, k), status, message)
        if (status /= SD_OK) return
        loads(:, k) = instant_loads(t, a_t, a_n)
      end associate
    end do

  contains

    !> One column of 'pressure_instants': the time, a_t, and the base shear and overturning
    !> moments (excluding and including the base pressure) of the pressures of
    !> instant_pressure_tables plus the shell's inertia, m_shell a_t at (h + f)/2 as in
    !> sloshdyn_vessel's loads: the rigid liquid gives m_F a_t at h/2 on the wall and
    !> m_F a_t R^2/(4h) of moment on the base, each mode n m_cn (a_n - a_t) at h_cn (h_cn').
    pure function instant_loads(t, tank_accel, mode_accel) result(column)
      real(wp), intent(in) :: t, tank_accel, mode_accel(:)
      real(wp) :: column(PRESSURE_INSTANT_ROWS)
      real(wp), dimension(size(mode_accel)) :: mass, height, height_ibp
      integer :: j
      call convective_resultants([(j, j = 1, size(mode_accel))], tank%liquid_depth/tank%radius, &
                                 mass, height, height_ibp)
      associate (m_f => props%liquid_mass, h => tank%liquid_depth, relative => mode_accel - &
                 tank_accel, m_shell => tank%tank_mass)
        column(1:2) = [t, tank_accel]
        column(3) = (m_shell + m_f)*tank_accel + m_f*sum(mass*relative)
        column(4) = (m_shell*props%shell_height + m_f*h/2)*tank_accel + &
                    m_f*h*sum(mass*height*relative)
        column(5) = column(4) + m_f*tank%radius**2/(4*h)*tank_accel + &
                    m_f*h*sum(mass*(height_ibp - height)*relative)
      end associate
    end function instant_loads
  end subroutine instant_pressures
end module sloshdyn_seismic_pressure
