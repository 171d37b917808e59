!> The layouts of every result table and the names of every kind code, in one place: the
!> analyses fill arrays in these layouts, the executable writes CSV headers from them, and the
!> bridge hands them to Python, which names its columns and kinds after them.
!>
!> A layout is a comma-separated list of column names; row i of a result array is column i.
!> Named indices (e.g. SUMMARY_MAX_X1) are given for the columns code reads one at a time.
module sloshdyn_tables
  implicit none
  private
  public :: table_header, table_formats, table_size, count_items, kind_names, code_name, special_kind_name, &
            motion_name, verdict_name
  public :: SPECIAL_FOLD, SPECIAL_HOPF, SPECIAL_BRANCH_POINT, SPECIAL_PERIOD_DOUBLING, &
            SPECIAL_NEIMARK_SACKER
  public :: MOTION_PERIODIC, MOTION_QUASI_PERIODIC, MOTION_IRREGULAR, MOTION_SETTLING
  public :: VERDICT_STABLE, VERDICT_MARGINAL, VERDICT_UNSTABLE
  public :: HISTORY_ROWS, SUMMARY_SIZE, SUMMARY_RHO, SUMMARY_A, SUMMARY_MAX_X1, SUMMARY_MAX_X2, &
            SUMMARY_MAX_U1, SUMMARY_MAX_U2, SUMMARY_MOTION, SUMMARY_PERIOD, SUMMARY_TRANSIENT, &
            SUMMARY_SPREAD, SUMMARY_SETTLED
  public :: POINT_ROWS, POINT_BRANCH, POINT_LAMBDA, POINT_RHO, POINT_A, POINT_A1, POINT_A2, &
            POINT_STABLE, POINT_SPECIAL, POINT_RE, POINT_IM, POINT_C, POINT_DELTA2, &
            POINT_DELTA3, POINT_X
  public :: SPECIAL_ROWS, SPECIAL_KIND, SPECIAL_BRANCH, SPECIAL_LAMBDA, SPECIAL_RHO, SPECIAL_A, &
            SPECIAL_A1, SPECIAL_A2, SPECIAL_FREQUENCY, SPECIAL_COLUMN
  public :: SWIRL_BRANCH_ROWS, SWIRL_EDGE_ROWS, SEISMIC_SPATIAL_ROWS, SEISMIC_SPATIAL_PEAKS
  public :: SPATIAL_HISTORY_ROWS, SWIRL_ORBIT_ROWS, SWIRL_BOUNDARY_ROWS, SWIRLING_BRANCH_ROWS, &
            SWIRLING_SPECIAL_ROWS, SWIRL_CURVE_ROWS, SWIRL_CURVE_FOLD_ROWS
  public :: ROUTH_SIZE, COUNTS_SIZE, PERIODIC_POINT_ROWS, PERIODIC_MULTIPLIER_ROWS, &
            PERIODIC_SPECIAL_ROWS, PERIODIC_SPECIAL_KIND, PERIODIC_SPECIAL_LAMBDA, &
            PERIODIC_SPECIAL_MAX_X1
  public :: CYCLE_POINT_ROWS, CYCLE_MULTIPLIER_ROWS, CYCLE_AMPLITUDE_ROWS, CYCLE_SPECIAL_ROWS
  public :: HISTORY_X1, HISTORY_X2, HARMONIC_SWEEP_WAVE_HEIGHT, CHART_GRID_N_STABLE, &
            CHART_GRID_NEAR_CURVE, CHART_GRID_BRUTE_FORCE_STABLE
  public :: SEISMIC_WAVE_HEIGHT, SEISMIC_TANK_ACCELERATION, SEISMIC_CONVECTIVE_ACCELERATION, &
            SEISMIC_BASE_SHEAR, SEISMIC_OVERTURNING_MOMENT, SEISMIC_OVERTURNING_MOMENT_IBP, &
            SEISMIC_X1, SEISMIC_X2, SEISMIC_FREE_WAVE, SEISMIC_IMPACT_FORCE
  public :: SEISMIC_LOADS, SEISMIC_FREE_ROWS, SEISMIC_ROWS, PEAKS_FREE_SIZE, PEAKS_SIZE, &
            PEAKS_WAVE_HEIGHT, PEAKS_IMPACT_FORCE, &
            PEAKS_ROOF_REACHED, PEAKS_FIRST_ROOF_TIME, PEAKS_ROOF_IMPACTS, PEAKS_FREE_WAVE, &
            PEAKS_ROOF_EXCESS, PEAKS_ROOF_HEAD, PEAKS_ROOF_UPLIFT, PEAKS_CONFINED_MASS, &
            PEAKS_SCALE_FACTOR, PEAKS_SA, PEAKS_BETA_SENSITIVE, PEAK_INSTANT_ROWS, PEAK_INSTANTS, &
            CODES_COLUMNS, CODES_ROWS, CODES_SOURCES, TANK_SI_SIZE, &
            HARMONIC_SWEEP_ROWS, TANK_MODES_ROWS
  public :: WALL_HEIGHT, WALL_TOTAL_PRESSURE, WALL_HOOP_FORCE
  public :: PEAKS_BASE_SHEAR, PEAKS_OVERTURNING_MOMENT, PEAKS_OVERTURNING_MOMENT_IBP, &
            PRESSURE_INSTANT_TIME
  public :: WALL_PRESSURE_ROWS, BASE_PRESSURE_ROWS, PRESSURE_RESULTANT_ROWS, &
            PRESSURE_INSTANT_ROWS
  public :: DESIGN_ROWS, DESIGN_API650, DESIGN_EC8, DESIGN_ACI350, DESIGN_LINEAR, &
            DESIGN_NONLINEAR, DESIGN_LOADS_COLUMNS, FREEBOARD_COLUMNS, LOADS_CONVECTIVE_PERIOD, &
            LOADS_IMPULSIVE_ACCELERATION, LOADS_CONVECTIVE_ACCELERATION, &
            LOADS_BASE_SHEAR, LOADS_MOMENT_EBP, LOADS_MOMENT_IBP, FREEBOARD_WAVE_HEIGHT, &
            FREEBOARD_REQUIRED, FREEBOARD_AVAILABLE, FREEBOARD_SUFFICIENT
  public :: CHART_FOLD, CHART_HOPF, CHART_PERIOD_DOUBLING, CHART_NEIMARK_SACKER, CODIM2_NONE, &
            CODIM2_BOGDANOV_TAKENS, CODIM2_CUSP_POINT, CODIM2_FOLD_HOPF, &
            CODIM2_GENERALISED_HOPF, CODIM2_RESONANCE_1_1, CODIM2_RESONANCE_1_2, &
            CODIM2_RESONANCE_1_3, CODIM2_RESONANCE_1_4, CODIM2_FOLD_FLIP, &
            CODIM2_FOLD_NEIMARK_SACKER, CODIM2_FLIP_NEIMARK_SACKER, CODIM2_GENERALISED_FLIP, &
            CODIM2_CHENCINER, CHART_CURVE_ROWS, CHART_CODIM2_ROWS, CHART_END_ROWS, &
            CHART_GRID_ROWS

  !> Special points on branches (slow flow and periodic orbits).
  integer, parameter :: SPECIAL_FOLD = 1, SPECIAL_HOPF = 2, SPECIAL_BRANCH_POINT = 3, &
                        SPECIAL_PERIOD_DOUBLING = 4, SPECIAL_NEIMARK_SACKER = 5
  character(len=*), parameter :: special_kinds = &
    'fold,hopf,branch_point,period_doubling,neimark_sacker'
  !> Kinds of steady motion judged from Poincare points (sloshdyn_simulation).
  integer, parameter :: MOTION_PERIODIC = 1, MOTION_QUASI_PERIODIC = 2, MOTION_IRREGULAR = 3, &
                        MOTION_SETTLING = 4
  character(len=*), parameter :: motion_kinds = 'periodic,quasi-periodic,irregular,settling'
  !> Stability verdicts of equilibria, from -1.
  integer, parameter :: VERDICT_UNSTABLE = -1, VERDICT_MARGINAL = 0, VERDICT_STABLE = 1
  character(len=*), parameter :: verdict_kinds = 'unstable,marginal,stable'
  !> Stability charts (sloshdyn_stability_chart): the kinds of bifurcation curves, of their
  !> codimension-2 points (0: a regular point), and of the ends of a curve.
  integer, parameter :: CHART_FOLD = 1, CHART_HOPF = 2, CHART_PERIOD_DOUBLING = 3, &
                        CHART_NEIMARK_SACKER = 4
  character(len=*), parameter :: curve_kinds = 'fold,hopf,period_doubling,neimark_sacker'
  integer, parameter :: CODIM2_NONE = 0, CODIM2_BOGDANOV_TAKENS = 1, CODIM2_CUSP_POINT = 2, &
                        CODIM2_FOLD_HOPF = 3, CODIM2_GENERALISED_HOPF = 4, &
                        CODIM2_RESONANCE_1_1 = 5, CODIM2_RESONANCE_1_2 = 6, &
                        CODIM2_RESONANCE_1_3 = 7, CODIM2_RESONANCE_1_4 = 8, CODIM2_FOLD_FLIP = 9, &
                        CODIM2_FOLD_NEIMARK_SACKER = 10, CODIM2_FLIP_NEIMARK_SACKER = 11, &
                        CODIM2_GENERALISED_FLIP = 12, CODIM2_CHENCINER = 13
  character(len=*), parameter :: codim2_kinds = 'none,bogdanov_takens,cusp,fold_hopf,'// &
    'generalised_hopf,resonance_1_1,resonance_1_2,resonance_1_3,resonance_1_4,fold_flip,'// &
    'fold_neimark_sacker,flip_neimark_sacker,generalised_flip,chenciner'
  character(len=*), parameter :: curve_end_kinds = 'start,box,closed,x_max,bogdanov_takens,'// &
    'max_points,failed,resonance'

  !> Time history rows (after tau): state, modal coordinates (eq 34), impact force (eq 4),
  !> angles [rad].
  character(len=*), parameter :: history_columns = 'x1,dx1,x2,dx2,u1,u2,impact_force,theta,phi'
  integer, parameter :: HISTORY_ROWS = 9, HISTORY_X1 = 1, HISTORY_X2 = 3

  !> One steady-state summary.
  character(len=*), parameter :: summary_columns = 'rho,A,max_x1,max_x2,max_u1,max_u2,motion,'// &
    'period,transient_periods,spread,settled'
  integer, parameter :: SUMMARY_SIZE = 11, SUMMARY_RHO = 1, SUMMARY_A = 2, SUMMARY_MAX_X1 = 3, &
                        SUMMARY_MAX_X2 = 4, SUMMARY_MAX_U1 = 5, SUMMARY_MAX_U2 = 6, &
                        SUMMARY_MOTION = 7, SUMMARY_PERIOD = 8, SUMMARY_TRANSIENT = 9, &
                        SUMMARY_SPREAD = 10, SUMMARY_SETTLED = 11

  !> One point of a slow-flow branch: eigenvalues re1..re4, im1..im4 of its Jacobian, C1..C4 and
  !> Delta2, Delta3 of eq (55), the Cartesian unknowns x = (Re B1, Im B1, Re B2, Im B2).
  character(len=*), parameter :: point_columns = 'branch,lambda,rho,A,a1,a2,phi1,phi2,stable,'// &
    'special,re1,re2,re3,re4,im1,im2,im3,im4,C1,C2,C3,C4,delta2,delta3,re_B1,im_B1,re_B2,im_B2'
  integer, parameter :: POINT_ROWS = 28, POINT_BRANCH = 1, POINT_LAMBDA = 2, POINT_RHO = 3, &
                        POINT_A = 4, POINT_A1 = 5, POINT_A2 = 6, POINT_STABLE = 9, &
                        POINT_SPECIAL = 10, POINT_RE = 11, POINT_IM = 15, POINT_C = 19, &
                        POINT_DELTA2 = 23, POINT_DELTA3 = 24, POINT_X = 25

  !> A special point of a slow-flow branch; frequency: the Hopf frequency sqrt(C3/C1) (slow
  !> time; 0 for folds); column: the point's column in the point table.
  character(len=*), parameter :: special_columns = 'kind,branch,lambda,rho,A,a1,a2,frequency,column'
  integer, parameter :: SPECIAL_ROWS = 9, SPECIAL_KIND = 1, SPECIAL_BRANCH = 2, &
                        SPECIAL_LAMBDA = 3, SPECIAL_RHO = 4, SPECIAL_A = 5, SPECIAL_A1 = 6, &
                        SPECIAL_A2 = 7, SPECIAL_FREQUENCY = 8, SPECIAL_COLUMN = 9

  !> Routh-Hurwitz of eq (20) at the trivial equilibrium; work counts of an integration.
  integer, parameter :: ROUTH_SIZE = 8, COUNTS_SIZE = 4
  !> A branch of periodic orbits (sloshdyn_periodic_response): its points (the first 7 columns of
  !> 'periodic_branch'), their Floquet multipliers (the other 8) and its special points
  !> ('periodic_special_points').
  integer, parameter :: PERIODIC_POINT_ROWS = 7, PERIODIC_MULTIPLIER_ROWS = 8, &
                        PERIODIC_SPECIAL_ROWS = 7, PERIODIC_SPECIAL_KIND = 1, &
                        PERIODIC_SPECIAL_LAMBDA = 2, PERIODIC_SPECIAL_MAX_X1 = 7
  !> Swirl (sloshdyn_swirl): a planar branch's points with their out-of-plane Floquet
  !> multipliers nu ('swirl_branch'), and the edges of the swirl band, where max|nu| = 1
  !> ('swirl_edges'; refined 1: located by Brent's method, 0: interpolated between points;
  !> kind: SPECIAL_BRANCH_POINT (a multiplier through +1), SPECIAL_PERIOD_DOUBLING (-1),
  !> SPECIAL_NEIMARK_SACKER (a complex pair)).
  integer, parameter :: SWIRL_BRANCH_ROWS = 16, SWIRL_EDGE_ROWS = 8
  !> A tank under ground motion in two horizontal components (sloshdyn_seismic_spatial): at each
  !> output time ('seismic_spatial'), and the peaks over the output times beside the codes'
  !> combinations of the two planar runs, then the roof verdict of the free wave around the
  !> wall and its roof loads ('seismic_spatial_peaks').
  integer, parameter :: SEISMIC_SPATIAL_ROWS = 18, SEISMIC_SPATIAL_PEAKS = 28
  !> A time history of the spatial model ('spatial_history', rows after tau: the 8 states, the
  !> pendulum's tilt from the vertical over theta0 and the azimuth of the tilt [rad]), and one
  !> periodic orbit of it ('swirl_orbit': its 8 states at tau = 0, max|x1|, the swirl amplitude
  !> max|y1|, the mean angular momentum, Newton's iterations, its 8 Floquet multipliers).
  integer, parameter :: SPATIAL_HISTORY_ROWS = 10, SWIRL_ORBIT_ROWS = 28
  !> The edges of the swirl band along rho at several A ('swirl_boundary': A, then the
  !> 'swirl_edges' columns).
  integer, parameter :: SWIRL_BOUNDARY_ROWS = 9
  !> The swirling orbits born at a swirl edge (sloshdyn_swirling_branch: 'swirling_branch',
  !> 'swirling_special_points').
  integer, parameter :: SWIRLING_BRANCH_ROWS = 29, SWIRLING_SPECIAL_ROWS = 11
  !> The swirl boundary in (rho, A) continued as a curve (sloshdyn_swirl_curve:
  !> 'swirl_boundary_curve', its points with the planar orbit there; 'swirl_curve_folds', its
  !> folds in A, closing 1: a least A of the band, where damping closes it, 0: a greatest A;
  !> 'swirl_curve_degenerate', its points where the edge's criticality c vanishes: degenerate
  !> pitchforks, or flips, where the onset of swirl turns from super- to subcritical).
  integer, parameter :: SWIRL_CURVE_ROWS = 8, SWIRL_CURVE_FOLD_ROWS = 9

  !> A branch of limit cycles of the slow flow (sloshdyn_slowflow_cycles): its points (the
  !> first 7 columns of 'cycle_branch': x = (Re B1, Im B1, Re B2, Im B2) where Re B1 is largest,
  !> the period in tau, stable 1/0), their Floquet multipliers (the next 8) and the cycles'
  !> amplitude ranges (the last 4), and its special points ('cycle_special_points').
  integer, parameter :: CYCLE_POINT_ROWS = 7, CYCLE_MULTIPLIER_ROWS = 8, &
                        CYCLE_AMPLITUDE_ROWS = 4, CYCLE_SPECIAL_ROWS = 7

  !> A tank under ground motion, SI (sloshdyn_seismic): at each output time the loads of
  !> sloshdyn_vessel's tank_loads on the tank without contact below its roof and with the
  !> restricted-sloshing method above it (docs/model.md, "Loads"), then x1 and x2 and the free
  !> wave's height at the wall (the tank without a roof, what the roof verdict judges); the
  !> peaks of the loads (value, time), then the roof contact of the free wave: reached, first
  !> contact, entries above the freeboard, the free wave's largest height at the wall and its
  !> excess over the freeboard, and the roof loads of that wave (sloshdyn_roof: head d - f,
  !> uplift on the roof, confined convective mass); the traceability of the run: the ground
  !> motion's scale factor and its pseudo-spectral acceleration at the tank's sloshing period
  !> (0.5 %). With &tank roof_contact = 'impact' the tables '..._impact' add the paper's impact
  !> model (eq 4-5): its impact force (and peak), and whether its loads would be sensitive to
  !> beta and delta (1/0); those columns are last, so the tables without them are their first
  !> rows (SEISMIC_FREE_ROWS, PEAKS_FREE_SIZE).
  character(len=*), parameter :: seismic_columns = 't [s],ground_acceleration [m/s^2],'// &
    'sloshing_displacement [m],wave_height [m],pendulum_angle [rad],tank_drift [m],'// &
    'tank_acceleration [m/s^2],convective_acceleration [m/s^2],base_shear [N],'// &
    'overturning_moment [N m],overturning_moment_ibp [N m],x1,x2,free_wave_height [m]'
  character(len=*), parameter :: seismic_impact_columns = ',impact_force [N]'
  !> run_info.csv: the record and its scaling, with the method of the roof contact
  character(len=*), parameter :: seismic_run_columns = 'record,scaling,scale_factor,'// &
    'peak_ground_acceleration [m/s^2],sa_sloshing_period [m/s^2],sloshing_period [s],'// &
    'roof_contact'
  integer, parameter :: SEISMIC_LOADS = 11, SEISMIC_FREE_ROWS = 14, SEISMIC_ROWS = 15
  !> The rows of 'seismic' that higher sloshing modes and the restricted sloshing add to
  !> (sloshdyn_seismic)
  integer, parameter :: SEISMIC_WAVE_HEIGHT = 4, SEISMIC_TANK_ACCELERATION = 7, &
                        SEISMIC_CONVECTIVE_ACCELERATION = 8, SEISMIC_BASE_SHEAR = 9, &
                        SEISMIC_OVERTURNING_MOMENT = 10, SEISMIC_OVERTURNING_MOMENT_IBP = 11, &
                        SEISMIC_X1 = 12, SEISMIC_X2 = 13, SEISMIC_FREE_WAVE = 14, &
                        SEISMIC_IMPACT_FORCE = 15
  character(len=*), parameter :: peaks_columns = 'peak_ground_acceleration [m/s^2],'// &
    'time_ground_acceleration [s],peak_sloshing_displacement [m],time_sloshing_displacement [s],'// &
    'peak_wave_height [m],time_wave_height [s],peak_pendulum_angle [rad],'// &
    'time_pendulum_angle [s],peak_tank_drift [m],time_tank_drift [s],'// &
    'peak_tank_acceleration [m/s^2],time_tank_acceleration [s],'// &
    'peak_convective_acceleration [m/s^2],time_convective_acceleration [s],'// &
    'peak_base_shear [N],time_base_shear [s],peak_overturning_moment [N m],'// &
    'time_overturning_moment [s],peak_overturning_moment_ibp [N m],'// &
    'time_overturning_moment_ibp [s],roof_reached,first_roof_time [s],roof_impacts,'// &
    'free_wave_height [m],roof_excess [m],roof_head [m],roof_uplift_force [N],'// &
    'confined_convective_mass [kg],scale_factor,sa_sloshing_period [m/s^2]'
  character(len=*), parameter :: peaks_impact_columns = ',peak_impact_force [N],'// &
    'time_impact_force [s],beta_sensitive'
  integer, parameter :: PEAKS_FREE_SIZE = 30, PEAKS_SIZE = 33, PEAKS_WAVE_HEIGHT = 5, &
                        PEAKS_ROOF_REACHED = 21, PEAKS_FIRST_ROOF_TIME = 22, &
                        PEAKS_ROOF_IMPACTS = 23, PEAKS_FREE_WAVE = 24, PEAKS_ROOF_EXCESS = 25, &
                        PEAKS_ROOF_HEAD = 26, PEAKS_ROOF_UPLIFT = 27, PEAKS_CONFINED_MASS = 28, &
                        PEAKS_SCALE_FACTOR = 29, PEAKS_SA = 30, PEAKS_IMPACT_FORCE = 31, &
                        PEAKS_BETA_SENSITIVE = 33
  !> the base shear's and overturning moments' peaks (their times follow them)
  integer, parameter :: PEAKS_BASE_SHEAR = 15, PEAKS_OVERTURNING_MOMENT = 17, &
                        PEAKS_OVERTURNING_MOMENT_IBP = 19
  !> The instants of a seismic run's load peaks (base shear, overturning moment excluding and
  !> including the base pressure), one column each: the time, the tank's acceleration and the
  !> absolute accelerations of the sloshing modes 1..max_modes (0 beyond the tank's modes),
  !> what the pressure at the peaks needs (sloshdyn_seismic_pressure).
  integer, parameter :: PEAK_INSTANT_ROWS = 12, PEAK_INSTANTS = 3
  !> A stability chart (sloshdyn_stability_chart): its curves' points, codimension-2 points,
  !> the curves' ends, and the grid's cells with their counts of steady states.
  character(len=*), parameter :: chart_curve_columns = 'curve,kind,rho,A,gamma,kappa,x1,x2,x3,'// &
    'x4,omega,l1,codim2'
  character(len=*), parameter :: chart_codim2_columns = 'kind,curve,rho,A,gamma,kappa,omega'
  character(len=*), parameter :: chart_end_columns = 'curve,kind,n_points,complete,first_end,'// &
    'last_end,status'
  character(len=*), parameter :: chart_grid_columns = 'rho,A,gamma,kappa,n_stable,n_steady,'// &
    'near_curve,brute_force_stable'
  integer, parameter :: CHART_CURVE_ROWS = 13, CHART_CODIM2_ROWS = 7, CHART_END_ROWS = 7, &
                        CHART_GRID_ROWS = 8, CHART_GRID_N_STABLE = 5, CHART_GRID_NEAR_CURVE = 7, &
                        CHART_GRID_BRUTE_FORCE_STABLE = 8
  character(len=*), parameter :: harmonic_sweep_columns = 'frequency [Hz],'// &
    'peak_ground_acceleration [m/s^2],wave_height [m],sloshing_displacement [m],'// &
    'pendulum_angle [rad],tank_drift [m],roof_reached,motion,period [forcing periods],'// &
    'free_wave_height [m]'
  integer, parameter :: HARMONIC_SWEEP_ROWS = 10, HARMONIC_SWEEP_WAVE_HEIGHT = 3
  character(len=*), parameter :: codes_columns_names = 'source,convective_period [s],'// &
    'convective_mass [kg],impulsive_mass [kg],convective_height [m],impulsive_height [m],'// &
    'wave_height [m]'
  !> One row per source of the first mode (CODES_SOURCES), then sloshdyn's sums over the
  !> sloshing modes 1..N (SRSS, absolute), present when the tank has N > 1 modes.
  integer, parameter :: CODES_COLUMNS = 6, CODES_SOURCES = 4, CODES_ROWS = CODES_SOURCES + 2
  character(len=*), parameter :: code_sources = 'sloshdyn,API 650,EC8-4,ACI 350.3,'// &
                                                'modes SRSS,modes ABS'
  character(len=*), parameter :: tank_si_columns = 'radius [m],liquid_depth [m],freeboard [m],'// &
    'liquid_mass [kg],tank_mass [kg],total_mass [kg],pendulum_length [m],sloshing_mass [kg],'// &
    'd1 [m],rigid_mass [kg],d0 [m],convective_height [m],impulsive_height [m],'// &
    'sloshing_period [s],omega [rad/s],support_height [m],support_stiffness [N m/rad],'// &
    'support_damping_coefficient [N m s/rad],theta0 [rad],wave_factor [m],'// &
    'impact_coefficient [N m],s1,mu1,kappa,beta,gamma,delta,zeta'
  integer, parameter :: TANK_SI_SIZE = 28
  !> The sloshing modes of a tank, one column per mode (sloshdyn_seismic's tank_modes).
  character(len=*), parameter :: tank_modes_columns = 'mode,period [s],convective_mass [kg],'// &
    'convective_height [m],pendulum_length [m],wave_factor [m]'
  integer, parameter :: TANK_MODES_ROWS = 6
  !> The hydrodynamic pressure of a rigid circular tank (sloshdyn_wall_pressure): on the wall,
  !> one column per height (pressures at the chosen angle; the hoop force per unit height is
  !> the total pressure times R); on the base, one column per radius; and the resultants, one
  !> column per component (0: impulsive, n: convective mode n), heights and moments excluding
  !> (ebp) and including (ibp) the base pressure.
  character(len=*), parameter :: wall_pressure_columns = 'z [m],impulsive_pressure [Pa],'// &
    'convective_pressure [Pa],total_pressure [Pa],hoop_force [N/m]'
  character(len=*), parameter :: base_pressure_columns = 'r [m],impulsive_pressure [Pa],'// &
    'convective_pressure [Pa],total_pressure [Pa]'
  character(len=*), parameter :: pressure_resultant_columns = 'component,mass [kg],'// &
    'height_ebp [m],height_ibp [m],base_shear [N],moment_ebp [N m],moment_ibp [N m]'
  integer, parameter :: WALL_HEIGHT = 1, WALL_TOTAL_PRESSURE = 4, WALL_HOOP_FORCE = 5
  integer, parameter :: WALL_PRESSURE_ROWS = 5, BASE_PRESSURE_ROWS = 4, &
                        PRESSURE_RESULTANT_ROWS = 7
  !> Instants of a seismic run (sloshdyn_seismic_pressure), one column each: the output time,
  !> the tank's acceleration, and the loads of the pressures and the shell's inertia.
  character(len=*), parameter :: pressure_instant_columns = 't [s],'// &
    'tank_acceleration [m/s^2],base_shear [N],overturning_moment [N m],'// &
    'overturning_moment_ibp [N m]'
  integer, parameter :: PRESSURE_INSTANT_ROWS = 5, PRESSURE_INSTANT_TIME = 1
  !> The design check (sloshdyn_design_check): one row per source, the codes' loads in their
  !> own format (accelerations: each code's design coefficient in g, its factors applied) and
  !> sloshdyn's (linear: the response-spectrum method on its model; nonlinear: the peaks of the
  !> time history, with a record); the freeboard check per code (sufficient 1/0).
  character(len=*), parameter :: design_sources = 'API 650,EC8-4,ACI 350.3,sloshdyn linear,'// &
                                                  'sloshdyn nonlinear'
  integer, parameter :: DESIGN_ROWS = 5, DESIGN_API650 = 1, DESIGN_EC8 = 2, DESIGN_ACI350 = 3, &
                        DESIGN_LINEAR = 4, DESIGN_NONLINEAR = 5
  character(len=*), parameter :: design_loads_names = 'source,impulsive_period [s],'// &
    'convective_period [s],impulsive_acceleration [g],convective_acceleration [g],'// &
    'impulsive_mass [kg],convective_mass [kg],tank_mass [kg],impulsive_height [m],'// &
    'convective_height [m],impulsive_height_ibp [m],convective_height_ibp [m],'// &
    'tank_mass_height [m],impulsive_shear [N],convective_shear [N],base_shear [N],'// &
    'moment_ebp [N m],moment_ibp [N m]'
  character(len=*), parameter :: freeboard_names = 'source,convective_period [s],'// &
    'convective_acceleration [g],wave_height [m],required_freeboard [m],'// &
    'available_freeboard [m],margin [m],sufficient'
  integer, parameter :: DESIGN_LOADS_COLUMNS = 17, FREEBOARD_COLUMNS = 7
  !> The design check's tables for a checker (sloshdyn_design_report; text and numbers): one
  !> row per check (demand against capacity, verdict OK, NOT OK or INFO), and the hand
  !> calculation, one row per formula in the order a checker reads it.
  character(len=*), parameter :: design_checks_names = 'code,check,clause,demand,capacity,'// &
    'unit,ratio,verdict'
  character(len=*), parameter :: design_calc_names = 'code,step,quantity,symbol,formula,'// &
    'substituted,value,unit,clause'
  !> The design spectrum of the check (elastic, sloshdyn_design_spectra), one row per period.
  character(len=*), parameter :: design_spectrum_names = 'period [s],'// &
    'sa_5_percent [g],sa_0.5_percent [g]'
  !> Named columns of those tables (after the source): design_loads' and freeboard_check's.
  integer, parameter :: LOADS_CONVECTIVE_PERIOD = 2, LOADS_IMPULSIVE_ACCELERATION = 3, &
                        LOADS_CONVECTIVE_ACCELERATION = 4, LOADS_BASE_SHEAR = 15, &
                        LOADS_MOMENT_EBP = 16, LOADS_MOMENT_IBP = 17
  integer, parameter :: FREEBOARD_WAVE_HEIGHT = 3, FREEBOARD_REQUIRED = 4, &
                        FREEBOARD_AVAILABLE = 5, FREEBOARD_SUFFICIENT = 7

contains

  !> The CSV header (column names) of a result table, '' for an unknown name.
  pure function table_header(name) result(header)
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: header
    select case (name)
    case ('parameters')
      header = 's1,mu1,kappa,theta0,beta,gamma,delta,zeta,n,p,A,rho,a1,a2,a3,a4,a5,a6,'// &
               'b1,b2,b3,b4,b5,b6'
    case ('tank')
      header = 'R,h,m_liquid,l,m,d1,m0,d0,M,L,g,omega'
    case ('frequencies')
      header = 'omega1,omega2,omega1_dgeev,omega2_dgeev,ratio,k11,k12,k21,k22'
    case ('equilibria')
      header = 'theta,phi,x1,x2,physical,verdict,re1,im1,re2,im2,re3,im3,re4,im4'
    case ('routh_hurwitz')
      header = 'c1,c2,c3,c4,delta2,delta3,routh_stable,eigenvalue_verdict'
    case ('kappa_31')
      header = 'sigma1,kappa'
    case ('history')
      header = 'tau,'//history_columns
    case ('simulation')
      header = 'n_rhs,n_accepted,n_rejected,tau_reached'
    case ('summary')
      header = summary_columns
    case ('poincare')
      header = 'tau,x1,dx1,x2,dx2'
    case ('study_orbit')
      header = 'found,periods,attempts,y1,y2,y3,y4,re_mu1,re_mu2,re_mu3,re_mu4,im_mu1,im_mu2,'// &
               'im_mu3,im_mu4,max_mu'
    case ('response')
      header = point_columns
    case ('special_points')
      header = special_columns(1:index(special_columns, ',column') - 1)
    case ('periodic_branch')
      header = 'lambda,y1,y2,y3,y4,max_x1,stable,re_mu1,re_mu2,re_mu3,re_mu4,'// &
               'im_mu1,im_mu2,im_mu3,im_mu4'
    case ('periodic_special_points')
      header = 'kind,lambda,y1,y2,y3,y4,max_x1'
    case ('cycle_branch')
      header = 'lambda,re_B1,im_B1,re_B2,im_B2,period,stable,re_mu1,re_mu2,re_mu3,re_mu4,'// &
               'im_mu1,im_mu2,im_mu3,im_mu4,min_B1,max_B1,min_B2,max_B2'
    case ('cycle_special_points')
      header = 'kind,lambda,re_B1,im_B1,re_B2,im_B2,period'
    case ('swirl_branch')
      header = 'lambda,y1,y2,y3,y4,max_x1,planar_stable,max_abs_nu,re_nu1,re_nu2,re_nu3,'// &
               're_nu4,im_nu1,im_nu2,im_nu3,im_nu4'
    case ('swirl_edges')
      header = 'lambda,y1,y2,y3,y4,max_x1,refined,kind'
    case ('swirl_boundary')
      header = 'A,lambda,y1,y2,y3,y4,max_x1,refined,kind'
    case ('swirling_branch')
      header = 'lambda,y1,y2,y3,y4,y5,y6,y7,y8,max_x1,swirl_amplitude,angular_momentum,stable,'// &
               're_mu1,re_mu2,re_mu3,re_mu4,re_mu5,re_mu6,re_mu7,re_mu8,'// &
               'im_mu1,im_mu2,im_mu3,im_mu4,im_mu5,im_mu6,im_mu7,im_mu8'
    case ('swirling_special_points')
      header = 'kind,lambda,y1,y2,y3,y4,y5,y6,y7,y8,max_x1'
    case ('swirl_boundary_curve', 'swirl_curve_degenerate')
      header = 'rho,A,y1,y2,y3,y4,max_x1,c'
    case ('swirl_curve_folds')
      header = 'rho,A,y1,y2,y3,y4,max_x1,c,closing'
    case ('spatial_history')
      header = 'tau,x1,dx1,x2,dx2,y1,dy1,y2,dy2,tilt,tilt_azimuth'
    case ('swirl_orbit')
      header = 'y1,y2,y3,y4,y5,y6,y7,y8,max_x1,swirl_amplitude,angular_momentum,iterations,'// &
               're_mu1,re_mu2,re_mu3,re_mu4,re_mu5,re_mu6,re_mu7,re_mu8,'// &
               'im_mu1,im_mu2,im_mu3,im_mu4,im_mu5,im_mu6,im_mu7,im_mu8'
    case ('seismic_spatial')
      header = 't [s],ground_acceleration_x [m/s^2],ground_acceleration_y [m/s^2],'// &
               'wave_height_x [m],wave_height_y [m],wave_height [m],wave_azimuth [rad],'// &
               'base_shear_x [N],base_shear_y [N],base_shear [N],overturning_moment_x [N m],'// &
               'overturning_moment_y [N m],overturning_moment [N m],x1,x2,y1,y2,'// &
               'free_wave_height [m]'
    case ('seismic_spatial_peaks')
      header = 'wave_height [m],wave_azimuth [rad],wave_time [s],base_shear [N],'// &
               'base_shear_time [s],overturning_moment [N m],overturning_moment_time [s],'// &
               'wave_height_run_1 [m],wave_height_run_2 [m],wave_height_srss [m],'// &
               'wave_height_100_30 [m],base_shear_run_1 [N],base_shear_run_2 [N],'// &
               'base_shear_srss [N],base_shear_100_30 [N],overturning_moment_run_1 [N m],'// &
               'overturning_moment_run_2 [N m],overturning_moment_srss [N m],'// &
               'overturning_moment_100_30 [N m],roof_reached,first_roof_time [s],'// &
               'first_contact_azimuth [rad],roof_impacts,free_wave_height [m],roof_excess [m],'// &
               'roof_head [m],roof_uplift_force [N],confined_convective_mass [kg]'
    case ('lyapunov')
      header = 'periods,estimate'
    case ('lyapunov_spectrum')
      header = 'periods,lambda1,lambda2,lambda3,lambda4'
    case ('seismic')
      header = seismic_columns
    case ('seismic_impact')
      header = seismic_columns//seismic_impact_columns
    case ('seismic_peaks')
      header = peaks_columns
    case ('seismic_peaks_impact')
      header = peaks_columns//peaks_impact_columns
    case ('seismic_peak_instants')
      header = 't [s],tank_acceleration [m/s^2],mode_1_acceleration [m/s^2],'// &
               'mode_2_acceleration [m/s^2],mode_3_acceleration [m/s^2],'// &
               'mode_4_acceleration [m/s^2],mode_5_acceleration [m/s^2],'// &
               'mode_6_acceleration [m/s^2],mode_7_acceleration [m/s^2],'// &
               'mode_8_acceleration [m/s^2],mode_9_acceleration [m/s^2],'// &
               'mode_10_acceleration [m/s^2]'
    case ('seismic_run')
      header = seismic_run_columns
    case ('seismic_run_impact')
      header = seismic_run_columns//',impact_stiffness,impact_damping,beta_sensitive'
    case ('design_codes')
      header = codes_columns_names
    case ('harmonic_sweep')
      header = harmonic_sweep_columns
    case ('chart_curves')
      header = chart_curve_columns
    case ('chart_codim2')
      header = chart_codim2_columns
    case ('chart_ends')
      header = chart_end_columns
    case ('chart_grid')
      header = chart_grid_columns
    case ('tank_si')
      header = tank_si_columns
    case ('tank_modes')
      header = tank_modes_columns
    case ('wall_pressure')
      header = wall_pressure_columns
    case ('base_pressure')
      header = base_pressure_columns
    case ('pressure_resultants')
      header = pressure_resultant_columns
    case ('pressure_instants')
      header = pressure_instant_columns
    case ('design_loads')
      header = design_loads_names
    case ('freeboard_check')
      header = freeboard_names
    case ('design_spectrum')
      header = design_spectrum_names
    case ('design_checks')
      header = design_checks_names
    case ('design_calc')
      header = design_calc_names
    case default
      header = ''
    end select
  end function table_header

  !> How each column of a result table is written, one letter per column: r real, i integer,
  !> and names of codes (code_name): s special-point kind, v verdict, c the source of a
  !> design-code row, o the source of a design-check row, k curve kind, d codimension-2 kind, e curve end.
  pure function table_formats(name) result(formats)
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: formats
    select case (name)
    case ('parameters')
      formats = 'rrrrrrrriirrrrrrrrrrrrrr'
    case ('equilibria')
      formats = 'rrrrivrrrrrrrr'
    case ('routh_hurwitz')
      formats = 'rrrrrriv'
    case ('special_points')
      formats = 'srrrrrrr'
    case ('periodic_special_points', 'cycle_special_points')
      formats = 'srrrrrr'
    case ('swirl_edges')
      formats = 'rrrrrris'
    case ('swirling_special_points')
      formats = 's'//repeat('r', 10)
    case ('swirl_boundary')
      formats = 'rrrrrrris'
    case ('swirl_curve_folds')
      formats = 'rrrrrrrri'
    case ('simulation')
      formats = 'iiir'
    case ('lyapunov')
      formats = 'ir'
    case ('lyapunov_spectrum')
      formats = 'irrrr'
    case ('seismic_peaks')
      formats = repeat('r', 20)//'irirrrrrrr'
    case ('seismic_peaks_impact')
      formats = repeat('r', 20)//'irirrrrrrr'//'rri'
    case ('seismic_spatial_peaks')
      formats = repeat('r', 19)//'irrirrrrr'
    case ('design_codes')
      formats = 'c'//repeat('r', CODES_COLUMNS)
    case ('harmonic_sweep')
      formats = 'rrrrrriirr'
    case ('tank_modes')
      formats = 'irrrrr'
    case ('pressure_resultants')
      formats = 'i'//repeat('r', PRESSURE_RESULTANT_ROWS - 1)
    case ('design_loads')
      formats = 'o'//repeat('r', DESIGN_LOADS_COLUMNS)
    case ('freeboard_check')
      formats = 'o'//repeat('r', FREEBOARD_COLUMNS)
    case ('chart_curves')
      formats = 'ikrrrrrrrrrrd'
    case ('chart_codim2')
      formats = 'dirrrrr'
    case ('chart_ends')
      formats = 'ikiieei'
    case ('chart_grid')
      formats = 'rrrriiii'
    case default
      formats = repeat('r', table_size(name))
    end select
  end function table_formats

  !> Number of columns of a result table.
  pure integer function table_size(name) result(columns)
    character(len=*), intent(in) :: name
    columns = count_items(table_header(name))
  end function table_size

  !> Number of items of a comma-separated list (0 for '').
  pure integer function count_items(list) result(n)
    character(len=*), intent(in) :: list
    integer :: i
    n = 0
    if (len(list) > 0) n = 1
    do i = 1, len(list)
      if (list(i:i) == ',') n = n + 1
    end do
  end function count_items

  !> The names of the codes of a kind list ('special', 'motion', 'verdict'), comma-separated,
  !> in code order; first = the first code.
  pure subroutine kind_names(list, names, first)
    character(len=*), intent(in) :: list
    character(len=:), allocatable, intent(out) :: names
    integer, intent(out) :: first
    select case (list)
    case ('special')
      names = special_kinds
      first = SPECIAL_FOLD
    case ('motion')
      names = motion_kinds
      first = MOTION_PERIODIC
    case ('verdict')
      names = verdict_kinds
      first = VERDICT_UNSTABLE
    case ('source')
      names = code_sources
      first = 1
    case ('design_source')
      names = design_sources
      first = 1
    case ('curve')
      names = curve_kinds
      first = CHART_FOLD
    case ('codim2')
      names = codim2_kinds
      first = CODIM2_NONE
    case ('curve_end')
      names = curve_end_kinds
      first = 0
    case default
      names = ''
      first = 0
    end select
  end subroutine kind_names

  !> The name of a code in a table column written by format letter (table_formats): s special,
  !> v verdict, c source, o design-check source, k curve kind, d codimension-2 kind, e curve end.
  pure function code_name(letter, code) result(name)
    character, intent(in) :: letter
    integer, intent(in) :: code
    character(len=:), allocatable :: name, names
    integer :: first
    select case (letter)
    case ('s'); call kind_names('special', names, first)
    case ('v'); call kind_names('verdict', names, first)
    case ('c'); call kind_names('source', names, first)
    case ('o'); call kind_names('design_source', names, first)
    case ('k'); call kind_names('curve', names, first)
    case ('d'); call kind_names('codim2', names, first)
    case default; call kind_names('curve_end', names, first)
    end select
    name = item(names, code - first + 1)
  end function code_name

  pure function special_kind_name(code) result(name)
    integer, intent(in) :: code
    character(len=len_trim(item(special_kinds, code - SPECIAL_FOLD + 1))) :: name
    name = item(special_kinds, code - SPECIAL_FOLD + 1)
  end function special_kind_name

  pure function motion_name(code) result(name)
    integer, intent(in) :: code
    character(len=len_trim(item(motion_kinds, code - MOTION_PERIODIC + 1))) :: name
    name = item(motion_kinds, code - MOTION_PERIODIC + 1)
  end function motion_name

  pure function verdict_name(code) result(name)
    integer, intent(in) :: code
    character(len=len_trim(item(verdict_kinds, code - VERDICT_UNSTABLE + 1))) :: name
    name = item(verdict_kinds, code - VERDICT_UNSTABLE + 1)
  end function verdict_name

  !> Item i (from 1) of a comma-separated list; 'unknown' outside it. Fixed length (trimmed by
  !> the callers' result lengths): a deferred-length result would make gfortran keep its length
  !> in a static variable shared by threads (see sloshdyn_text).
  pure function item(list, i) result(name)
    character(len=*), intent(in) :: list
    integer, intent(in) :: i
    character(len=32) :: name
    integer :: start, k, next
    start = 1
    do k = 1, i - 1
      next = index(list(start:), ',')
      if (next == 0 .or. i < 1) then
        name = 'unknown'
        return
      end if
      start = start + next
    end do
    if (i < 1) then
      name = 'unknown'
      return
    end if
    next = index(list(start:), ',')
    if (next == 0) then
      name = list(start:)
    else
      name = list(start:start + next - 2)
    end if
  end function item
end module sloshdyn_tables
