!> The hydrodynamic pressure on the wall and base of a circular tank at chosen instants of a
!> seismic run (sloshdyn_seismic's seismic_response with the same tank, ground motion, t_end,
!> n_out, options and method), e.g. those of its base shear and overturning moment peaks: the
!> run is integrated again on the same output times (the same states), and at the output time
!> nearest each instant the tank's absolute acceleration a_t and the modes' absolute
!> accelerations a_1..a_N give the pressure of sloshdyn_wall_pressure's
!> instant_pressure_tables (docs/model.md, "Pressure at an instant of a time history"):
!>   a_t = u'' + L (cos(phi) phi'' - sin(phi) phi'^2)              (sloshdyn_vessel)
!>   a_1 = a_t + l (cos(theta) theta'' - sin(theta) theta'^2)      (the pendulum, mode 1)
!>   a_n = a_t + x_n'' for n = 2..N, x_n the linear oscillator of mode n on a_t between the
!>         output times (sloshdyn_seismic's add_higher_modes, Nigam & Jennings).
!> Table 'pressure_instants' (one column per instant): the output time, the accelerations and
!> the base shear and overturning moments that the pressures and the shell's inertia give.
module sloshdyn_seismic_pressure
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, check_real
  use sloshdyn_text, only: num2str
  use sloshdyn_model, only: model_t
  use sloshdyn_motion, only: equations_of_motion
  use sloshdyn_excitation, only: base_acceleration
  use sloshdyn_vessel, only: tank_t, tank_properties, tank_acceleration, &
                             sloshing_mass_acceleration
  use sloshdyn_ground, only: ground_motion_t
  use sloshdyn_ode, only: ode_options, ode_stats
  use sloshdyn_simulation, only: time_history
  use sloshdyn_sdof, only: sdof_response
  use sloshdyn_seismic, only: seismic_setup
  use sloshdyn_tank, only: max_modes
  use sloshdyn_wall_pressure, only: instant_pressure_tables, convective_resultants, &
                                    check_pressure_input, COMBINE_SUM
  use sloshdyn_tables, only: HISTORY_ROWS, WALL_PRESSURE_ROWS, BASE_PRESSURE_ROWS, &
                             PRESSURE_INSTANT_ROWS
  implicit none
  private
  public :: seismic_pressures

contains

  !> The pressure at the output times nearest to times(:) [s] (each in [0, t_end]) of the run
  !> of seismic_response(tank, ground, t_end, n_out, options, method): instants(:, k) (the
  !> 'pressure_instants' columns), wall(:, :, k) and base(:, :, k) (the 'wall_pressure' and
  !> 'base_pressure' tables at heights and radii, angle [rad]), modal(1:N, k) the modes'
  !> absolute accelerations [m/s^2] (the rest 0).
  subroutine seismic_pressures(tank, ground, t_end, n_out, options, method, times, heights, &
                               radii, angle, instants, modal, wall, base, status, message)
    type(tank_t), intent(in) :: tank
    type(ground_motion_t), intent(in) :: ground
    real(wp), intent(in) :: t_end, times(:), heights(:), radii(:), angle
    integer, intent(in) :: n_out, method
    type(ode_options), intent(in) :: options
    real(wp), intent(out) :: instants(PRESSURE_INSTANT_ROWS, size(times)), &
                             modal(max_modes, size(times)), &
                             wall(WALL_PRESSURE_ROWS, size(heights), size(times)), &
                             base(BASE_PRESSURE_ROWS, size(radii), size(times))
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(model_t) :: model
    type(tank_properties) :: props
    type(ode_stats) :: stats
    real(wp), allocatable :: tau(:), history(:, :), a_t(:), a_n(:, :), x(:), v(:)
    real(wp) :: dydt(4), dt
    integer :: i, k, n

    instants = 0
    modal = 0
    wall = 0
    base = 0
    call seismic_setup(tank, ground, t_end, n_out, model, props, tau, status, message)
    do k = 1, size(times)
      call check_real('times('//num2str(k)//')', times(k), 0.0_wp, t_end, .false., .false., &
                      'the instants [s] must lie in [0, t_end = '//num2str(t_end)//']', &
                      status, message)
    end do
    if (status == SD_OK) call check_pressure_input(tank, 0.0_wp, props%modal_mass(1:props%modes), &
                                                   angle, COMBINE_SUM, heights, radii, status, &
                                                   message)
    if (status /= SD_OK) return
    ! the run's output times and states (sloshdyn_seismic's seismic_response)
    allocate (history(HISTORY_ROWS, n_out), a_t(n_out), a_n(n_out, props%modes), x(n_out), &
              v(n_out))
    call time_history(model, 0.0_wp, [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], tau, options, method, &
                      history, stats, status, message)
    if (status /= SD_OK) return
    do i = 1, n_out
      call equations_of_motion(model, tau(i), history(1:4, i), dydt)
      a_t(i) = tank_acceleration(props, model, history(1:4, i), dydt, props%rod_length* &
                                 props%omega**2*base_acceleration(model%excitation, tau(i)))
      a_n(i, 1) = sloshing_mass_acceleration(props, model, history(1:4, i), dydt, a_t(i))
    end do
    dt = t_end/(n_out - 1)
    do n = 2, props%modes
      call sdof_response(dt, a_t, 2*pi/props%modal_period(n), tank%sloshing_damping, 0.0_wp, &
                         0.0_wp, x, v, a_n(:, n), status, message)
      if (status /= SD_OK) return
    end do
    do k = 1, size(times)
      i = nint(times(k)/dt) + 1
      modal(1:props%modes, k) = a_n(i, :)
      call instant_pressure_tables(tank, a_t(i), a_n(i, :), angle, heights, radii, &
                                   wall(:, :, k), base(:, :, k), status, message)
      if (status /= SD_OK) return
      instants(:, k) = instant_loads(tau(i)/props%omega, a_t(i), a_n(i, :))
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
  end subroutine seismic_pressures
end module sloshdyn_seismic_pressure
