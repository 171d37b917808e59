!> The f2py bridge of pressure.py: the hydrodynamic wall and base pressure of a rigid circular
!> tank (sloshdyn_wall_pressure); tank(TANK_SIZE) in the layout of sloshdyn_layouts.
!> The bridge's contract (c_double/c_int arrays in named layouts, status and message,
!> threads and the GIL) is written once, in sloshdyn_bridge_model.f90.
module sloshdyn_bridge_pressure
  use, intrinsic :: iso_c_binding, only: c_double, c_int
  implicit none

contains

  !> The tables 'wall_pressure' (a column per height), 'base_pressure' (a column per radius)
  !> and 'pressure_resultants' (impulsive, then convective modes 1..modes) of the tank under the
  !> impulsive acceleration and the modes' convective accelerations [m/s^2], at angle [rad],
  !> combined by combination (the codes of 'pressure_combinations').
  subroutine pressure_tables(tank, impulsive_acceleration, modes, convective_accelerations, &
                             angle, combination, n_heights, heights, n_radii, radii, wall, base, &
                             resultants, status, message)
    !f2py threadsafe
    use sloshdyn_layouts, only: TANK_SIZE, to_tank
    use sloshdyn_tables, only: WALL_PRESSURE_ROWS, BASE_PRESSURE_ROWS, PRESSURE_RESULTANT_ROWS
    use sloshdyn_wall_pressure, only: fill => pressure_tables
    real(c_double), intent(in) :: tank(TANK_SIZE), impulsive_acceleration, angle
    integer(c_int), intent(in) :: modes, combination, n_heights, n_radii
    real(c_double), intent(in) :: convective_accelerations(modes), heights(n_heights), &
                                  radii(n_radii)
    real(c_double), intent(out) :: wall(WALL_PRESSURE_ROWS, n_heights), &
                                   base(BASE_PRESSURE_ROWS, n_radii), &
                                   resultants(PRESSURE_RESULTANT_ROWS, modes + 1)
    integer(c_int), intent(out) :: status
    character(len=256), intent(out) :: message
    integer :: info
    call fill(to_tank(tank), impulsive_acceleration, convective_accelerations, angle, &
              combination, heights, radii, wall, base, resultants, info, message)
    status = info
  end subroutine pressure_tables

  !> The pressure at the output times nearest to times [s] of the tank's seismic run
  !> (sloshdyn_seismic_pressure; the same arguments as sloshdyn_bridge_seismic's
  !> seismic_response): instants in the 'pressure_instants' layout, modal (the modes' absolute
  !> accelerations), wall and base ('wall_pressure', 'base_pressure' at each instant).
  subroutine seismic_pressures(tank, ground, n, samples, t_end, n_out, integration, n_times, &
                               times, n_heights, heights, n_radii, radii, angle, instants, &
                               modal, wall, base, status, message)
    !f2py threadsafe
    use sloshdyn_layouts, only: INTEGRATION_SIZE, TANK_SIZE, GROUND_SIZE, to_tank, to_ground, &
                                to_ode_options, to_method
    use sloshdyn_tables, only: WALL_PRESSURE_ROWS, BASE_PRESSURE_ROWS, PRESSURE_INSTANT_ROWS
    use sloshdyn_tank, only: MAX_TANK_MODES => max_modes
    use sloshdyn_seismic_pressure, only: core => seismic_pressures
    integer(c_int), intent(in) :: n, n_out, n_times, n_heights, n_radii
    real(c_double), intent(in) :: tank(TANK_SIZE), ground(GROUND_SIZE), samples(n), t_end, &
                                  integration(INTEGRATION_SIZE), times(n_times), &
                                  heights(n_heights), radii(n_radii), angle
    real(c_double), intent(out) :: instants(PRESSURE_INSTANT_ROWS, n_times), &
                                   modal(MAX_TANK_MODES, n_times), &
                                   wall(WALL_PRESSURE_ROWS, n_heights, n_times), &
                                   base(BASE_PRESSURE_ROWS, n_radii, n_times)
    integer(c_int), intent(out) :: status
    character(len=256), intent(out) :: message
    integer :: info
    call core(to_tank(tank), to_ground(ground, samples), t_end, int(n_out), &
              to_ode_options(integration), to_method(integration), times, heights, radii, &
              angle, instants, modal, wall, base, info, message)
    status = info
  end subroutine seismic_pressures
end module sloshdyn_bridge_pressure
