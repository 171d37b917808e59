!> Writes the C header that gives f2py's wrapper of the bridge the sizes of the named layouts
!> (sloshdyn_layouts, sloshdyn_tables, sloshdyn_model, sloshdyn_studies): the bridge declares its
!> arrays with these constants, f2py copies their names into C (lower case, --lower), and the
!> build includes this program's output there, so no size is written twice.
program sloshdyn_bridge_sizes
  use sloshdyn_model, only: n_real_params, n_int_params
  use sloshdyn_simulation, only: max_period
  use sloshdyn_studies, only: ORBIT_ROWS
  use sloshdyn_tables, only: HISTORY_ROWS, SUMMARY_SIZE, COUNTS_SIZE, POINT_ROWS, SPECIAL_ROWS, &
                             PERIODIC_POINT_ROWS, PERIODIC_MULTIPLIER_ROWS, &
                             PERIODIC_SPECIAL_ROWS, CHART_CURVE_ROWS, CHART_CODIM2_ROWS, &
                             CHART_END_ROWS, CHART_GRID_ROWS, TANK_SI_SIZE, CODES_COLUMNS, &
                             CODES_ROWS, SEISMIC_ROWS, PEAKS_SIZE, HARMONIC_SWEEP_ROWS, &
                             CYCLE_POINT_ROWS, CYCLE_MULTIPLIER_ROWS, CYCLE_AMPLITUDE_ROWS, &
                             CYCLE_SPECIAL_ROWS, TANK_MODES_ROWS, &
                             SWIRL_BRANCH_ROWS, SWIRL_EDGE_ROWS, SWIRLING_BRANCH_ROWS, &
                             SWIRLING_SPECIAL_ROWS, SEISMIC_SPATIAL_ROWS, &
                             SEISMIC_SPATIAL_PEAKS
  use sloshdyn_tables, only: WALL_PRESSURE_ROWS, BASE_PRESSURE_ROWS, PRESSURE_RESULTANT_ROWS, &
                             PRESSURE_INSTANT_ROWS
  use sloshdyn_tables, only: SPATIAL_HISTORY_ROWS, PEAK_INSTANT_ROWS, PEAK_INSTANTS, &
                             SWIRL_CURVE_ROWS, SWIRL_CURVE_FOLD_ROWS
  use sloshdyn_tank, only: max_modes
  use sloshdyn_layouts, only: INTEGRATION_SIZE, STEADY_SIZE, RESPONSE_SIZE, LYAPUNOV_SIZE, &
                              TANK_SIZE, GROUND_SIZE, CHART_SIZE, CHART_RANGE_SIZE, STUDY_SIZE, &
                              SWEEP_SIZE, SIMULATION_SIZE, RESPONSE_RANGE_SIZE, SEISMIC_SIZE, &
                              ANALYSIS_SIZE, CONTINUATION_SIZE, &
                              SHOOTING_SIZE, PENDULUM_SIZE, &
                              PHYSICAL_SIZE, GROUPS_SIZE, ROUTH_TRIVIAL_SIZE, ORBIT_INFO_SIZE, &
                              SWIRL_ORBIT_INFO_SIZE, &
                              MODAL_SCALARS_SIZE, CHART_SIZES_SIZE, SPATIAL_SIZE, &
                              NATURAL_FREQUENCIES_SIZE, DESIGN_SIZE, &
                              TANK_STRUCTURE_SIZE
  use sloshdyn_tables, only: DESIGN_ROWS, DESIGN_LOADS_COLUMNS, FREEBOARD_COLUMNS
  implicit none
  call define('n_real_params', n_real_params)
  call define('n_int_params', n_int_params)
  call define('orbit_rows', ORBIT_ROWS)
  call define('max_orbit_periods', max_period)
  call define('history_rows', HISTORY_ROWS)
  call define('summary_size', SUMMARY_SIZE)
  call define('counts_size', COUNTS_SIZE)
  call define('point_rows', POINT_ROWS)
  call define('special_rows', SPECIAL_ROWS)
  call define('periodic_point_rows', PERIODIC_POINT_ROWS)
  call define('periodic_multiplier_rows', PERIODIC_MULTIPLIER_ROWS)
  call define('periodic_special_rows', PERIODIC_SPECIAL_ROWS)
  call define('chart_curve_rows', CHART_CURVE_ROWS)
  call define('chart_codim2_rows', CHART_CODIM2_ROWS)
  call define('chart_end_rows', CHART_END_ROWS)
  call define('chart_grid_rows', CHART_GRID_ROWS)
  call define('tank_si_size', TANK_SI_SIZE)
  call define('tank_modes_rows', TANK_MODES_ROWS)
  call define('max_tank_modes', max_modes)
  call define('codes_columns', CODES_COLUMNS)
  call define('codes_rows', CODES_ROWS)
  call define('seismic_rows', SEISMIC_ROWS)
  call define('peaks_size', PEAKS_SIZE)
  call define('peak_instant_rows', PEAK_INSTANT_ROWS)
  call define('peak_instants', PEAK_INSTANTS)
  call define('harmonic_sweep_rows', HARMONIC_SWEEP_ROWS)
  call define('cycle_point_rows', CYCLE_POINT_ROWS)
  call define('cycle_multiplier_rows', CYCLE_MULTIPLIER_ROWS)
  call define('cycle_amplitude_rows', CYCLE_AMPLITUDE_ROWS)
  call define('cycle_special_rows', CYCLE_SPECIAL_ROWS)
  call define('integration_size', INTEGRATION_SIZE)
  call define('steady_size', STEADY_SIZE)
  call define('response_size', RESPONSE_SIZE)
  call define('lyapunov_size', LYAPUNOV_SIZE)
  call define('tank_size', TANK_SIZE)
  call define('ground_size', GROUND_SIZE)
  call define('chart_size', CHART_SIZE)
  call define('chart_range_size', CHART_RANGE_SIZE)
  call define('study_size', STUDY_SIZE)
  call define('sweep_size', SWEEP_SIZE)
  call define('simulation_size', SIMULATION_SIZE)
  call define('response_range_size', RESPONSE_RANGE_SIZE)
  call define('seismic_size', SEISMIC_SIZE)
  call define('analysis_size', ANALYSIS_SIZE)
  call define('continuation_size', CONTINUATION_SIZE)
  call define('shooting_size', SHOOTING_SIZE)
  call define('pendulum_size', PENDULUM_SIZE)
  call define('physical_size', PHYSICAL_SIZE)
  call define('groups_size', GROUPS_SIZE)
  call define('routh_trivial_size', ROUTH_TRIVIAL_SIZE)
  call define('orbit_info_size', ORBIT_INFO_SIZE)
  call define('swirl_orbit_info_size', SWIRL_ORBIT_INFO_SIZE)
  call define('modal_scalars_size', MODAL_SCALARS_SIZE)
  call define('chart_sizes_size', CHART_SIZES_SIZE)
  call define('spatial_size', SPATIAL_SIZE)
  call define('swirl_branch_rows', SWIRL_BRANCH_ROWS)
  call define('swirl_edge_rows', SWIRL_EDGE_ROWS)
  call define('swirling_branch_rows', SWIRLING_BRANCH_ROWS)
  call define('swirling_special_rows', SWIRLING_SPECIAL_ROWS)
  call define('swirl_curve_rows', SWIRL_CURVE_ROWS)
  call define('swirl_curve_fold_rows', SWIRL_CURVE_FOLD_ROWS)
  call define('seismic_spatial_rows', SEISMIC_SPATIAL_ROWS)
  call define('seismic_spatial_peaks', SEISMIC_SPATIAL_PEAKS)
  call define('natural_frequencies_size', NATURAL_FREQUENCIES_SIZE)
  call define('wall_pressure_rows', WALL_PRESSURE_ROWS)
  call define('base_pressure_rows', BASE_PRESSURE_ROWS)
  call define('pressure_resultant_rows', PRESSURE_RESULTANT_ROWS)
  call define('pressure_instant_rows', PRESSURE_INSTANT_ROWS)
  call define('spatial_history_rows', SPATIAL_HISTORY_ROWS)
  call define('design_size', DESIGN_SIZE)
  call define('tank_structure_size', TANK_STRUCTURE_SIZE)
  call define('design_rows', DESIGN_ROWS)
  call define('design_loads_columns', DESIGN_LOADS_COLUMNS)
  call define('freeboard_columns', FREEBOARD_COLUMNS)
contains
  subroutine define(name, value)
    character(len=*), intent(in) :: name
    integer, intent(in) :: value
    character(len=12) :: text
    write (text, '(i0)') value
    print '(a)', '#define '//name//' '//trim(text)
  end subroutine define
end program sloshdyn_bridge_sizes
