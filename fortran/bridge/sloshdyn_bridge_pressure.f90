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
    character(len=512), intent(out) :: message
    integer :: info
    call fill(to_tank(tank), impulsive_acceleration, convective_accelerations, angle, &
              combination, heights, radii, wall, base, resultants, info, message)
    status = info
  end subroutine pressure_tables

  !> The instants of the output times nearest to times [s] of a seismic run whose table gave
  !> t [s], the tank's and the convective mass's accelerations [m/s^2] at its n_out outputs
  !> (sloshdyn_seismic_pressure's output_instants; 'seismic_peak_instants' columns).
  subroutine output_instants(tank, n_out, t, tank_accel, convective_accel, n_times, times, &
                             instants, status, message)
    !f2py threadsafe
    use sloshdyn_layouts, only: TANK_SIZE, to_tank
    use sloshdyn_tables, only: PEAK_INSTANT_ROWS
    use sloshdyn_seismic_pressure, only: core => output_instants
    integer(c_int), intent(in) :: n_out, n_times
    real(c_double), intent(in) :: tank(TANK_SIZE), t(n_out), tank_accel(n_out), &
                                  convective_accel(n_out), times(n_times)
    real(c_double), intent(out) :: instants(PEAK_INSTANT_ROWS, n_times)
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
    integer :: info
    call core(to_tank(tank), t, tank_accel, convective_accel, times, instants, info, message)
    status = info
  end subroutine output_instants

  !> The pressure at instants ('seismic_peak_instants' columns: t, a_t, a_1..a_10) of a seismic
  !> run (sloshdyn_seismic_pressure's instant_pressures): loads in the 'pressure_instants'
  !> layout, wall and base ('wall_pressure', 'base_pressure' at each instant).
  subroutine instant_pressures(tank, n_times, instants, n_heights, heights, n_radii, radii, &
                               angle, loads, wall, base, status, message)
    !f2py threadsafe
    use sloshdyn_layouts, only: TANK_SIZE, to_tank
    use sloshdyn_tables, only: WALL_PRESSURE_ROWS, BASE_PRESSURE_ROWS, PRESSURE_INSTANT_ROWS, &
                               PEAK_INSTANT_ROWS
    use sloshdyn_seismic_pressure, only: core => instant_pressures
    integer(c_int), intent(in) :: n_times, n_heights, n_radii
    real(c_double), intent(in) :: tank(TANK_SIZE), instants(PEAK_INSTANT_ROWS, n_times), &
                                  heights(n_heights), radii(n_radii), angle
    real(c_double), intent(out) :: loads(PRESSURE_INSTANT_ROWS, n_times), &
                                   wall(WALL_PRESSURE_ROWS, n_heights, n_times), &
                                   base(BASE_PRESSURE_ROWS, n_radii, n_times)
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
    integer :: info
    call core(to_tank(tank), instants, heights, radii, angle, loads, wall, base, info, message)
    status = info
  end subroutine instant_pressures
end module sloshdyn_bridge_pressure
