!> The named layouts of the flat arrays that cross the f2py bridge, both ways: each layout is a
!> list of fields (name, kind, what it is) in the order of the array, and its size is the list's
!> length; result tables have theirs in sloshdyn_tables, the model's rpar, ipar in
!> sloshdyn_model (real_param_names; 'model_integers' = [n, p]). Python asks the bridge for the
!> names, kinds, docs and defaults (names('layout:NAME'), 'kinds:NAME', 'docs:NAME',
!> layout_defaults) and makes its settings classes from them and builds and decodes every array
!> by name, so a new field of a settings group is a change here (its entry, its place in the
!> to_*/from_* conversion), in its option type and in the group's reader; Python follows.
!> The to_*/from_* functions below list the fields in the same order.
!> Integer entries are converted by to_int, which keeps out-of-range and NaN values out of range
!> (so the core's range checks report them) instead of letting them wrap or become 0.
module sloshdyn_layouts
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_namelist_scanner, only: join
  use sloshdyn_model, only: real_param_names, model_t, model_to_arrays, n_real_params, &
                            n_int_params
  use sloshdyn_ode, only: ode_options, ode_stats, check_options
  use sloshdyn_continuation, only: continuation_options, newton_options
  use sloshdyn_simulation, only: steady_options, check_steady
  use sloshdyn_response, only: response_options
  use sloshdyn_periodic_response, only: lyapunov_options, newton_tol_default, max_iter_default, &
                                       check_lyapunov
  use sloshdyn_integrator, only: METHOD_AUTO, check_method
  use sloshdyn_vessel, only: tank_t
  use sloshdyn_ground, only: ground_motion_t, harmonic_ground, record_ground, GROUND_RECORD
  use sloshdyn_stability_chart, only: chart_settings
  use sloshdyn_slowflow_chart, only: chart_parameter_name, CHART_RHO, CHART_KAPPA
  use sloshdyn_design_spectra, only: design_spectrum_t
  use sloshdyn_design_loads, only: design_factors_t
  use sloshdyn_tank_structure, only: tank_structure_t, max_courses
  use sloshdyn_run_config, only: run_config, simulation_settings, sweep_settings, &
                                 response_settings, seismic_settings, study_settings
  implicit none
  private
  public :: INTEGRATION_SIZE, STEADY_SIZE, RESPONSE_SIZE, LYAPUNOV_SIZE, TANK_SIZE, GROUND_SIZE, &
            CHART_SIZE, CHART_RANGE_SIZE, STUDY_SIZE, SWEEP_SIZE, SIMULATION_SIZE, &
            RESPONSE_RANGE_SIZE, SEISMIC_SIZE, ANALYSIS_SIZE, CONTINUATION_SIZE, &
            SHOOTING_SIZE, PENDULUM_SIZE, &
            PHYSICAL_SIZE, GROUPS_SIZE, ROUTH_TRIVIAL_SIZE, ORBIT_INFO_SIZE, &
            SWIRL_ORBIT_INFO_SIZE, &
            MODAL_SCALARS_SIZE, CHART_SIZES_SIZE, SPATIAL_SIZE, &
            NATURAL_FREQUENCIES_SIZE, DESIGN_SIZE, DESIGN_FROM_GROUND, TANK_STRUCTURE_SIZE
  public :: chart_axes, CHART_RHO
  public :: layout_names, layout_text, layout_defaults, check_layout, join, &
            excitation_parameters, ground_kinds, resonances
  public :: to_ode_options, to_method, to_steady, to_response, to_lyapunov
  public :: from_ode_options, from_steady, from_response, from_lyapunov, to_int, counts_array
  public :: to_continuation
  public :: to_tank, from_tank, to_ground, from_ground, to_chart, from_chart, from_chart_range
  public :: from_analysis, from_simulation, from_sweep, from_response_range, from_seismic, &
            from_study
  public :: field_index
  public :: to_design, from_design, design_spectra, to_tank_structure, from_tank_structure

  !> One field of a layout: its name; its kind ('real', 'integer', 'flag' (1/0), or 'code:LIST',
  !> a code of the enumerated option LIST that names() answers); what it is, with its unit (the
  !> Python settings classes are made from the layouts and take their help from doc).
  type :: field_t
    character(len=32) :: name = ''
    character(len=32) :: kind = 'real'
    character(len=160) :: doc = ''
  end type field_t
  !> Newton's settings of a continuation (sloshdyn_continuation's newton_options): the start,
  !> the corrector and the special points
  type(field_t), parameter :: newton_fields(*) = [ &
    field_t('x_tol', doc='Newton converges at a step <= x_tol (1 + max|x|) ...'), &
    field_t('f_tol', doc='... and a residual max|F| <= f_tol'), &
    field_t('max_iter', 'integer', 'Newton iterations at most')]
  !> &integration (sloshdyn_ode's ode_options and the method code of sloshdyn_integrator)
  type(field_t), parameter :: integration_fields(*) = [ &
    field_t('rtol', doc='relative tolerance of the step-size control'), &
    field_t('atol', doc='absolute tolerance of every component'), &
    field_t('h_initial', doc='first step in tau; 0: automatic (HINIT of Hairer''s codes)'), &
    field_t('h_max', doc='largest step in tau; 0: no limit'), &
    field_t('h_min', doc='smallest step error control may ask for; 0: 1e-14 max(1, |tau|)'), &
    field_t('max_steps', 'integer', 'attempted (accepted + rejected) steps at most'), &
    field_t('method', 'code:methods', '''auto'' (by rtol, see method_used), ''rk45'' '// &
            '(Dormand-Prince 5(4)), ''dop853'' (8(5,3)) or ''vern9'' (Verner 9(8))')]
  !> &steady (sloshdyn_simulation's steady_options)
  type(field_t), parameter :: steady_fields(*) = [ &
    field_t('transient_periods', doc='transient integrated before measuring, in forcing '// &
            'periods T = 2 pi/rho (the minimum when settle_tol > 0)'), &
    field_t('settle_tol', doc='> 0: extend the transient until successive Poincare points '// &
            'differ by less (relative); 0: a fixed transient'), &
    field_t('max_transient_periods', doc='the longest transient with settle_tol > 0 [periods]'), &
    field_t('window_periods', 'integer', 'periods over which the amplitudes are measured'), &
    field_t('samples_per_period', 'integer', 'dense-output probes per period at least of '// &
            'the scan that brackets the maxima'), &
    field_t('periodic_tol', doc='Poincare points this close (relative) coincide'), &
    field_t('shooting', 'flag', 'with settle_tol > 0: once the Poincare map contracts, jump '// &
            'to the periodic orbit by Newton shooting (kept only if stable and the attractor '// &
            'being approached); False: integration only')]
  !> &response's numbers (sloshdyn_response's response_options with its continuation)
  type(field_t), parameter :: response_fields(*) = [ &
    field_t('n_scan', 'integer', 'parameter values where steady states are searched'), &
    field_t('n_amplitudes', 'integer', 'Newton starts per mode: log-spaced |B| ...'), &
    field_t('n_phases', 'integer', '... times equally spaced phases'), &
    field_t('amplitude_min', doc='the smallest start |B|'), &
    field_t('amplitude_max', doc='the largest start |B|'), &
    field_t('ds', doc='first pseudo-arclength step'), &
    field_t('ds_min', doc='smallest step; failing at it ends the branch'), &
    field_t('ds_max', doc='largest step'), &
    field_t('x_scale', doc='weight of the amplitudes in the arclength norm'), &
    field_t('max_points', 'integer', 'points per branch and direction at most'), &
    newton_fields]
  !> &response's choices: resonance (code of resonances), parameter (of excitation_parameters),
  !> and the special point where periodic_response switches branches (0: none)
  type(field_t), parameter :: response_range_fields(*) = [ &
    field_t('resonance', 'code:resonances'), field_t('parameter', 'code:excitation_parameters'), &
    field_t('start'), field_t('stop'), &
    field_t('switch_at', 'integer', 'periodic_response: the special point (1, 2, ...) where '// &
            'the branch is switched; swirl: the edge (1, 2, ...) where the swirling orbits '// &
            'are followed; 0: none'), &
    field_t('curve_at', 'integer', 'periodic_response: the special point (1, 2, ...; a '// &
            'fold, period_doubling or neimark_sacker) whose two-parameter curve in (rho, A) '// &
            'is traced; swirl: the edge (1, 2, ...; a branch_point or period_doubling) '// &
            'continued as a curve in (rho, A); 0: none'), &
    field_t('curve_start', doc='the curve''s range of the other parameter (A when the '// &
            'branch is in rho), lower end'), &
    field_t('curve_stop', doc='... upper end')]
  !> &lyapunov (sloshdyn_periodic_response's lyapunov_options)
  type(field_t), parameter :: lyapunov_fields(*) = [ &
    field_t('transient_periods', 'integer', 'forcing periods integrated before measuring'), &
    field_t('n_periods', 'integer', 'forcing periods measured; a multiple of '// &
            'renormalise_every'), &
    field_t('renormalise_every', 'integer', 'periods between renormalisations of the '// &
            'tangent vectors'), &
    field_t('spectrum', 'flag', 'the executable''s lyapunov analysis: all four exponents '// &
            '(QR method), not the largest only; from Python the call decides '// &
            '(lyapunov_exponent or lyapunov_spectrum)'), &
    field_t('average', 'code:averages', 'how the renormalisations'' log growths are '// &
            'averaged into the exponents: ''plain'' (over the measured time) or '// &
            '''weighted'' (the weighted Birkhoff average, super-convergent on quasi-periodic '// &
            'growths; the history stays the plain running average)')]
  !> &tank: tank_t's components in order (sloshdyn_vessel; n, p, shape, modes and roof_contact
  !> as reals, shape a code of 'tank_shapes', roof_contact of 'roof_contacts')
  type(field_t), parameter :: tank_fields(*) = [ &
    field_t('radius'), field_t('liquid_depth'), field_t('freeboard'), &
    field_t('liquid_density'), field_t('liquid_mass'), field_t('tank_mass'), &
    field_t('support_frequency'), field_t('support_damping'), field_t('support_stiffness'), &
    field_t('support_damping_coefficient'), field_t('support_height'), &
    field_t('sloshing_damping'), field_t('impact_stiffness'), field_t('impact_damping'), &
    field_t('n', 'integer'), field_t('p', 'integer'), field_t('gravity'), &
    field_t('roof_slope', doc='a cone roof''s slope [degrees] (0: not a cone; at most one of '// &
            'roof_slope, roof_radius)'), &
    field_t('roof_radius', doc='a dome roof''s radius [m] (0: not a dome; neither: a flat '// &
            'roof)'), &
    field_t('shape', 'code:tank_shapes'), field_t('length'), field_t('width'), &
    field_t('modes', 'integer'), &
    field_t('roof_contact', 'code:roof_contacts', 'how the liquid meets the roof: ''none'' (the '// &
            'tank without contact below its roof, restricted sloshing above it) or ''impact'' '// &
            '(also the paper''s impact model of eq 4-5, for its impact force only)')]
  !> A ground motion (sloshdyn_ground): kind (ground_kinds), peak_acceleration [m/s^2],
  !> frequency [Hz], dt [s], scale_factor (what it was scaled by); a record's samples [m/s^2]
  !> travel in their own array.
  type(field_t), parameter :: ground_fields(*) = [ &
    field_t('kind', 'code:ground_kinds'), field_t('peak_acceleration'), field_t('frequency'), &
    field_t('dt'), field_t('scale_factor')]
  !> &chart's grid and curves (sloshdyn_stability_chart's chart_settings)
  type(field_t), parameter :: chart_fields(*) = [ &
    field_t('n_x', 'integer', 'grid columns (cells in x; their midpoints)'), &
    field_t('n_y', 'integer', 'grid rows: the values of y where the one-parameter runs in x '// &
            'seed the curves'), &
    field_t('n_scan', 'integer', 'parameter values of each one-parameter run where steady '// &
            'states are searched'), &
    field_t('max_points', 'integer', 'points of one curve at most'), &
    field_t('max_curves', 'integer', 'curves at most'), &
    field_t('brute_force_starts', 'integer', '> 0: integrate the slow flow from that many '// &
            'starts in every cell and count the stable steady states reached (a small basin '// &
            'may be missed; never more than there are); 0: none')]
  !> &chart's choices: model (code of 'chart_models'), x and y (of 'chart_axes'), the box, threads
  type(field_t), parameter :: chart_range_fields(*) = [ &
    field_t('model', 'code:chart_models'), field_t('x', 'code:chart_axes'), &
    field_t('y', 'code:chart_axes'), field_t('x_min'), field_t('x_max'), field_t('y_min'), &
    field_t('y_max'), field_t('threads', 'integer')]
  !> &study (given 1/0; kind, worker_kind and continuation codes of 'study_kinds',
  !> 'worker_kinds' and 'continuations'); its strings travel as text
  type(field_t), parameter :: study_fields(*) = [ &
    field_t('given', 'flag'), field_t('kind', 'code:study_kinds'), field_t('workers', 'integer'), &
    field_t('worker_kind', 'code:worker_kinds'), field_t('points_per_task', 'integer'), &
    field_t('frequency_start'), field_t('frequency_stop'), field_t('n_frequencies', 'integer'), &
    field_t('amplitude_start'), field_t('amplitude_stop'), field_t('n_amplitudes', 'integer'), &
    field_t('continuation', 'code:continuations'), field_t('x1_start'), field_t('x1_stop'), &
    field_t('dx1_start'), field_t('dx1_stop'), field_t('n_grid', 'integer'), field_t('tol'), &
    field_t('intensity_start'), field_t('intensity_stop'), field_t('n_intensities', 'integer'), &
    field_t('spectral_damping'), field_t('min_workers', 'integer'), field_t('grace_time')]
  !> &sweep (parameter of excitation_parameters, direction of 'directions', carry_state 1/0)
  type(field_t), parameter :: sweep_fields(*) = [ &
    field_t('parameter', 'code:excitation_parameters'), field_t('start'), field_t('stop'), &
    field_t('n_points', 'integer'), field_t('direction', 'code:directions'), &
    field_t('carry_state', 'flag'), field_t('threads', 'integer')]
  !> &simulation: t_end, n_out and the initial state y0 = (x1, x1', x2, x2') and, for the
  !> spatial model, (y1, y1', y2, y2')
  type(field_t), parameter :: simulation_fields(*) = [ &
    field_t('t_end'), field_t('n_out', 'integer'), field_t('y0_1'), field_t('y0_2'), &
    field_t('y0_3'), field_t('y0_4'), field_t('y0_5'), field_t('y0_6'), field_t('y0_7'), &
    field_t('y0_8')]
  !> &seismic
  type(field_t), parameter :: seismic_fields(*) = [field_t('t_end'), field_t('n_out', 'integer')]
  !> &analysis's numbers (the 3:1 tuning search)
  type(field_t), parameter :: analysis_fields(*) = [ &
    field_t('sigma1'), field_t('kappa_min'), field_t('kappa_max')]
  !> A continuation of periodic orbits or of the slow flow's limit cycles: the steps, the
  !> direction (+1 from the low end, -1 from the high end) and Newton's settings (its
  !> max_points set apart)
  type(field_t), parameter :: continuation_fields(*) = [ &
    field_t('ds'), field_t('ds_min'), field_t('ds_max'), field_t('x_scale'), &
    field_t('direction', 'integer'), newton_fields]
  !> Newton shooting of periodic orbits
  type(field_t), parameter :: shooting_fields(*) = [ &
    field_t('newton_tol', doc='Newton''s tolerance on the orbit''s state, relative'), &
    field_t('max_iter', 'integer', 'Newton iterations at most')]
  !> Small results: the equivalent pendulum of a tank (eq 2-3) [m, kg, m, kg, m, kg]; the SI
  !> values of eq (9) and their dimensionless groups; Routh-Hurwitz of eq (20) at the trivial
  !> equilibrium (routh_stable 1/0); a periodic orbit's Newton iterations and max|x1|.
  type(field_t), parameter :: pendulum_fields(*) = [ &
    field_t('pendulum_length'), field_t('sloshing_mass'), field_t('d1'), field_t('rigid_mass'), &
    field_t('d0'), field_t('liquid_mass')]
  type(field_t), parameter :: physical_fields(*) = [ &
    field_t('M'), field_t('L'), field_t('k'), field_t('c'), field_t('b'), field_t('d'), &
    field_t('g'), field_t('theta0'), field_t('l'), field_t('m')]
  type(field_t), parameter :: groups_fields(*) = [ &
    field_t('s1'), field_t('mu1'), field_t('kappa'), field_t('beta'), field_t('gamma'), &
    field_t('delta')]
  type(field_t), parameter :: routh_fields(*) = [ &
    field_t('c1'), field_t('c2'), field_t('c3'), field_t('c4'), field_t('delta2'), &
    field_t('delta3'), field_t('routh_stable', 'flag')]
  type(field_t), parameter :: orbit_info_fields(*) = [ &
    field_t('iterations', 'integer'), field_t('max_x1')]
  !> A periodic orbit of the spatial model (sloshdyn_swirl's swirl_orbit).
  type(field_t), parameter :: swirl_orbit_info_fields(*) = [ &
    field_t('iterations', 'integer'), field_t('max_x1'), &
    field_t('swirl_amplitude', doc='max|y1| over the orbit'), &
    field_t('angular_momentum', doc='about the vertical, averaged over the orbit '// &
            '[M L^2 omega]; > 0 counter-clockwise')]
  !> The scalars of the modal expansion (sloshdyn_modal: eq 34-36) and the sizes of a stability
  !> chart's four tables (sloshdyn_stability_chart's chart_table_sizes).
  type(field_t), parameter :: modal_scalars_fields(*) = [ &
    field_t('omega1'), field_t('omega2'), field_t('gamma11'), field_t('gamma22'), field_t('F11')]
  !> The natural frequencies of the linearised model about the trivial equilibrium: eq (28) and,
  !> independently, the eigenvalues of the undamped linearised equations (dgeev).
  type(field_t), parameter :: natural_frequencies_fields(*) = [ &
    field_t('omega1', doc='eq (28)'), field_t('omega2', doc='eq (28)'), &
    field_t('omega1_dgeev', doc='from dgeev'), field_t('omega2_dgeev', doc='from dgeev')]
  type(field_t), parameter :: chart_sizes_fields(*) = [ &
    field_t('curve_points', 'integer'), field_t('codim2_points', 'integer'), &
    field_t('curves', 'integer'), field_t('cells', 'integer')]
  !> The second horizontal component of the spatial model (sloshdyn_spatial's spatial_model_t)
  type(field_t), parameter :: spatial_fields(*) = [ &
    field_t('azimuth', doc='direction of the ground motion [rad from x]'), &
    field_t('ellipticity', doc='the ground moves by ellipticity A cos(rho tau) across '// &
            'azimuth as well as A sin(rho tau) along it')]
  !> &design (issue 25; docs/design.md): the spectrum (a code of 'design_spectra': a code
  !> design spectrum of sloshdyn_design_spectra, or the &ground_motion's), its parameters
  !> (design_spectrum_t) and the codes' factors (sloshdyn_design_loads' design_factors_t)
  type(field_t), parameter :: design_fields(*) = [ &
    field_t('spectrum', 'code:design_spectra', '''asce7'' (ASCE 7-16 11.4.6), ''aci350'' '// &
            '(ACI 350.3-06 9.4), ''ec8'' (EN 1998-1 3.2.2) or ''ground_motion'''), &
    field_t('s_ds', doc='ASCE 7 design spectral acceleration at short periods S_DS [g]'), &
    field_t('s_d1', doc='ASCE 7 design spectral acceleration at 1 s S_D1 [g]'), &
    field_t('t_l', doc='ASCE 7 long-period transition period T_L [s]'), &
    field_t('k', doc='API 650 E.4.6.1: factor from 5 % to 0.5 % damping'), &
    field_t('a_gr', doc='EN 1998-1 reference peak ground acceleration on type A ground [g]'), &
    field_t('gamma_i', doc='EN 1998-1 importance factor gamma_I (a_g = gamma_I a_gR)'), &
    field_t('ground_type', 'code:ground_types', 'EN 1998-1 ground type (Table 3.1)'), &
    field_t('spectrum_type', 'integer', 'EN 1998-1 spectrum type 1 or 2 (3.2.2.2(2))'), &
    field_t('q', doc='EN 1998-4 behaviour factor of the impulsive response (EN 1998-1 3.2.2.5)'), &
    field_t('beta', doc='EN 1998-1 3.2.2.5(4): lower bound factor of the design spectrum'), &
    field_t('importance', doc='importance factor I (API 650 Table E-5, ACI 350.3 Table '// &
            '4.1.1(a))'), &
    field_t('use_group', 'integer', 'API 650 seismic use group 1, 2 or 3 (E.3.1)'), &
    field_t('r_wi', doc='API 650 impulsive response modification factor R_wi (Table E-4); '// &
            '0: by the anchorage, 3.5 self-anchored, 4 mechanically anchored'), &
    field_t('r_wc', doc='API 650 convective response modification factor R_wc (Table E-4)'), &
    field_t('r_i', doc='ACI 350.3 impulsive response modification factor R_i (Table 4.1.1(b))'), &
    field_t('r_c', doc='ACI 350.3 convective response modification factor R_c (Table 4.1.1(b))'), &
    field_t('impulsive_period', doc='[s]; 0: from &tank_structure where the code uses it, '// &
            'else the plateau of the spectrum (a ground motion: the rigid tank, its peak)'), &
    field_t('impulsive_damping_ratio', doc='damping ratio of the impulsive response (of '// &
            'critical: 0.05 for 5 %)'), &
    field_t('tank_mass_height', doc='height of the tank''s own mass (shell, roof) above the '// &
            'base [m]; 0: (liquid_depth + freeboard)/2'), &
    field_t('vertical', 'flag', 'take each code''s vertical acceleration into account'), &
    field_t('vertical_acceleration', doc='the vertical design acceleration [g] in place of '// &
            'the codes'' own; 0: the codes'' own'), &
    field_t('wall_pressure', 'code:wall_pressures', 'the accelerations of wall_pressure.csv: '// &
            '''code'' (a code''s design accelerations) or ''elastic''')]
  !> &tank_structure (issue 38; docs/namelist.md): the structure of the design check's
  !> structural checks (sloshdyn_tank_structure's tank_structure_t); given = 1 when the group
  !> is there; the courses bottom first, 16 of each (course_height_1 ... _16, bottom first;
  !> 0: none).
  type(field_t), parameter :: tank_structure_fields(*) = [ &
    field_t('given', 'flag', '1: the structure is given (&tank_structure)'), &
    field_t('material', 'code:materials', '''steel'' or ''concrete'''), &
    field_t('course_height_1', doc='[m]'), field_t('course_height_2', doc='[m]'), &
    field_t('course_height_3', doc='[m]'), field_t('course_height_4', doc='[m]'), &
    field_t('course_height_5', doc='[m]'), field_t('course_height_6', doc='[m]'), &
    field_t('course_height_7', doc='[m]'), field_t('course_height_8', doc='[m]'), &
    field_t('course_height_9', doc='[m]'), field_t('course_height_10', doc='[m]'), &
    field_t('course_height_11', doc='[m]'), field_t('course_height_12', doc='[m]'), &
    field_t('course_height_13', doc='[m]'), field_t('course_height_14', doc='[m]'), &
    field_t('course_height_15', doc='[m]'), field_t('course_height_16', doc='[m]'), &
    field_t('course_thickness_1', doc='[mm] as built'), field_t('course_thickness_2', doc='[mm] as built'), &
    field_t('course_thickness_3', doc='[mm] as built'), field_t('course_thickness_4', doc='[mm] as built'), &
    field_t('course_thickness_5', doc='[mm] as built'), field_t('course_thickness_6', doc='[mm] as built'), &
    field_t('course_thickness_7', doc='[mm] as built'), field_t('course_thickness_8', doc='[mm] as built'), &
    field_t('course_thickness_9', doc='[mm] as built'), field_t('course_thickness_10', doc='[mm] as built'), &
    field_t('course_thickness_11', doc='[mm] as built'), field_t('course_thickness_12', doc='[mm] as built'), &
    field_t('course_thickness_13', doc='[mm] as built'), field_t('course_thickness_14', doc='[mm] as built'), &
    field_t('course_thickness_15', doc='[mm] as built'), field_t('course_thickness_16', doc='[mm] as built'), &
    field_t('course_yield_strength_1', doc='F_y [MPa]'), field_t('course_yield_strength_2', doc='F_y [MPa]'), &
    field_t('course_yield_strength_3', doc='F_y [MPa]'), field_t('course_yield_strength_4', doc='F_y [MPa]'), &
    field_t('course_yield_strength_5', doc='F_y [MPa]'), field_t('course_yield_strength_6', doc='F_y [MPa]'), &
    field_t('course_yield_strength_7', doc='F_y [MPa]'), field_t('course_yield_strength_8', doc='F_y [MPa]'), &
    field_t('course_yield_strength_9', doc='F_y [MPa]'), field_t('course_yield_strength_10', doc='F_y [MPa]'), &
    field_t('course_yield_strength_11', doc='F_y [MPa]'), field_t('course_yield_strength_12', doc='F_y [MPa]'), &
    field_t('course_yield_strength_13', doc='F_y [MPa]'), field_t('course_yield_strength_14', doc='F_y [MPa]'), &
    field_t('course_yield_strength_15', doc='F_y [MPa]'), field_t('course_yield_strength_16', doc='F_y [MPa]'), &
    field_t('course_tensile_strength_1', doc='F_t [MPa]'), field_t('course_tensile_strength_2', doc='F_t [MPa]'), &
    field_t('course_tensile_strength_3', doc='F_t [MPa]'), field_t('course_tensile_strength_4', doc='F_t [MPa]'), &
    field_t('course_tensile_strength_5', doc='F_t [MPa]'), field_t('course_tensile_strength_6', doc='F_t [MPa]'), &
    field_t('course_tensile_strength_7', doc='F_t [MPa]'), field_t('course_tensile_strength_8', doc='F_t [MPa]'), &
    field_t('course_tensile_strength_9', doc='F_t [MPa]'), field_t('course_tensile_strength_10', doc='F_t [MPa]'), &
    field_t('course_tensile_strength_11', doc='F_t [MPa]'), field_t('course_tensile_strength_12', doc='F_t [MPa]'), &
    field_t('course_tensile_strength_13', doc='F_t [MPa]'), field_t('course_tensile_strength_14', doc='F_t [MPa]'), &
    field_t('course_tensile_strength_15', doc='F_t [MPa]'), field_t('course_tensile_strength_16', doc='F_t [MPa]'), &
    field_t('corrosion_allowance', doc='of the shell [mm]'), &
    field_t('joint_efficiency', doc='E of the shell''s vertical joints'), &
    field_t('elastic_modulus', doc='E of the wall [MPa]; 0: 200 000 for steel'), &
    field_t('density', doc='of the wall [kg/m^3]; 0: 7850 steel, 2400 concrete'), &
    field_t('bottom_thickness', doc='the bottom plate [mm]; 0: not weighed'), &
    field_t('annular_thickness', doc='the bottom annulus under the shell [mm]; 0: the bottom'), &
    field_t('bottom_corrosion_allowance', doc='of the bottom and annulus [mm]'), &
    field_t('annular_yield_strength', doc='F_y of the annulus [MPa]; 0: the bottom course''s'), &
    field_t('roof_mass', doc='[kg]'), &
    field_t('roof_mass_height', doc='the roof''s centre of mass above the base [m]; 0: the '// &
            'shell''s top'), &
    field_t('anchorage', 'code:anchorages', '''self'' or ''mechanical'''), &
    field_t('anchor_count', 'integer', 'anchors around the circumference'), &
    field_t('anchor_capacity', doc='the allowable seismic design load of one anchor [N]'), &
    field_t('friction', doc='friction coefficient bottom on foundation (API 650 E.7.6)')]
  !> Every named layout (names('layouts')); 'model' and 'model_integers' are sloshdyn_model's
  !> rpar and ipar.
  character(len=*), parameter :: layout_names = 'model,model_integers,integration,steady,'// &
    'response,response_range,lyapunov,tank,ground,chart,chart_range,study,sweep,simulation,'// &
    'seismic,analysis,continuation,shooting,pendulum,physical,groups,'// &
    'routh,orbit_info,swirl_orbit_info,modal_scalars,chart_sizes,spatial,natural_frequencies,'// &
    'design,tank_structure'
  integer, parameter :: field_len = 32
  !> The codes of enumerated options that have no name list elsewhere: the parameter of a sweep
  !> or response (from PARAMETER_RHO of sloshdyn_excitation), the ground kinds (from
  !> GROUND_HARMONIC), the resonance of a frequency response (from 0).
  character(len=*), parameter :: excitation_parameters(*) = [character(len=field_len) :: &
    'rho', 'A', 'frequency']
  character(len=*), parameter :: ground_kinds(*) = [character(len=field_len) :: &
    'harmonic', 'record']
  character(len=*), parameter :: resonances(*) = [character(len=field_len) :: 'none', '3:1']
  !> &design's spectra, by code: design_spectrum_t's kinds, then the ground motion's.
  character(len=*), parameter :: design_spectra(*) = [character(len=field_len) :: &
    'asce7', 'aci350', 'ec8', 'ground_motion']
  integer, parameter :: DESIGN_FROM_GROUND = 4

  integer, parameter :: INTEGRATION_SIZE = size(integration_fields), &
                        STEADY_SIZE = size(steady_fields), RESPONSE_SIZE = size(response_fields), &
                        LYAPUNOV_SIZE = size(lyapunov_fields), TANK_SIZE = size(tank_fields), &
                        GROUND_SIZE = size(ground_fields), &
                        CHART_SIZE = size(chart_fields), &
                        CHART_RANGE_SIZE = size(chart_range_fields), &
                        STUDY_SIZE = size(study_fields), &
                        SWEEP_SIZE = size(sweep_fields), &
                        SIMULATION_SIZE = size(simulation_fields), &
                        RESPONSE_RANGE_SIZE = size(response_range_fields), &
                        SEISMIC_SIZE = size(seismic_fields), &
                        ANALYSIS_SIZE = size(analysis_fields), &
                        CONTINUATION_SIZE = size(continuation_fields), &
                        SHOOTING_SIZE = size(shooting_fields), &
                        PENDULUM_SIZE = size(pendulum_fields), &
                        PHYSICAL_SIZE = size(physical_fields), GROUPS_SIZE = size(groups_fields), &
                        ROUTH_TRIVIAL_SIZE = size(routh_fields), &
                        ORBIT_INFO_SIZE = size(orbit_info_fields), &
                        SWIRL_ORBIT_INFO_SIZE = size(swirl_orbit_info_fields), &
                        MODAL_SCALARS_SIZE = size(modal_scalars_fields), &
                        CHART_SIZES_SIZE = size(chart_sizes_fields), &
                        SPATIAL_SIZE = size(spatial_fields), &
                        NATURAL_FREQUENCIES_SIZE = size(natural_frequencies_fields), &
                        DESIGN_SIZE = size(design_fields), &
                        TANK_STRUCTURE_SIZE = size(tank_structure_fields)

contains

  !> The fields of a named layout (a settings, model or small-result array); none for an unknown
  !> name.
  pure function layout_of(name) result(fields)
    character(len=*), intent(in) :: name
    type(field_t), allocatable :: fields(:)
    integer :: k
    select case (name)
    case ('model')
      fields = [(field_t(real_param_names(k)), k = 1, size(real_param_names))]
    case ('model_integers'); fields = [field_t('n', 'integer'), field_t('p', 'integer')]
    case ('integration');    fields = integration_fields
    case ('steady');         fields = steady_fields
    case ('response');       fields = response_fields
    case ('response_range'); fields = response_range_fields
    case ('lyapunov');       fields = lyapunov_fields
    case ('tank');           fields = tank_fields
    case ('ground');         fields = ground_fields
    case ('chart');          fields = chart_fields
    case ('chart_range');    fields = chart_range_fields
    case ('study');          fields = study_fields
    case ('sweep');          fields = sweep_fields
    case ('simulation');     fields = simulation_fields
    case ('seismic');        fields = seismic_fields
    case ('analysis');       fields = analysis_fields
    case ('continuation');   fields = continuation_fields
    case ('shooting');       fields = shooting_fields
    case ('pendulum');       fields = pendulum_fields
    case ('physical');       fields = physical_fields
    case ('groups');         fields = groups_fields
    case ('routh');          fields = routh_fields
    case ('orbit_info');     fields = orbit_info_fields
    case ('swirl_orbit_info'); fields = swirl_orbit_info_fields
    case ('modal_scalars');  fields = modal_scalars_fields
    case ('chart_sizes');    fields = chart_sizes_fields
    case ('spatial');        fields = spatial_fields
    case ('natural_frequencies'); fields = natural_frequencies_fields
    case ('design');         fields = design_fields
    case ('tank_structure'); fields = tank_structure_fields
    case default;            allocate (fields(0))
    end select
  end function layout_of

  !> One column of a named layout's fields, joined: what = 'name' (comma-separated), 'kind'
  !> (comma-separated: real, integer, flag or code:LIST) or 'doc' (one line per field, a
  !> newline for a layout without docs); '' for an unknown layout.
  pure function layout_text(name, what) result(text)
    character(len=*), intent(in) :: name, what
    character(len=:), allocatable :: text
    type(field_t), allocatable :: fields(:)
    fields = layout_of(name)
    text = ''
    if (size(fields) == 0) return
    select case (what)
    case ('kind'); text = join(fields%kind, ',')
    case ('doc');  text = join(fields%doc, new_line('a'))//new_line('a')
    case default;  text = join(fields%name, ',')
    end select
  end function layout_text

  !> The defaults of a settings layout (the option types' defaults, as the namelist reader
  !> starts from them); found = .false. for a layout without defaults.
  pure subroutine layout_defaults(name, values, found)
    character(len=*), intent(in) :: name
    real(wp), allocatable, intent(out) :: values(:)
    logical, intent(out) :: found
    type(model_t) :: model
    integer :: ints(n_int_params)
    real(wp) :: rpar(n_real_params)
    found = .true.
    call model_to_arrays(model, rpar, ints)
    select case (name)
    case ('model');       values = rpar
    case ('model_integers'); values = real(ints, wp)
    case ('integration'); values = from_ode_options(ode_options(), METHOD_AUTO)
    case ('steady');      values = from_steady(steady_options())
    case ('response');    values = from_response(response_options())
    case ('lyapunov');    values = from_lyapunov(lyapunov_options())
    case ('shooting');    values = [newton_tol_default, real(max_iter_default, wp)]
    case ('tank');        values = from_tank(tank_t())
    case ('chart');       values = from_chart(chart_settings())
    case ('design');      values = from_design(design_spectrum_t(), design_factors_t(), .false.)
    case ('tank_structure'); values = from_tank_structure(tank_structure_t())
    case ('study');       values = from_study(study_settings())
    case default
      found = .false.
      allocate (values(0))
    end select
  end subroutine layout_defaults

  !> The core's range rules for a settings layout's values (the rules every analysis applies
  !> to them, so that a settings object is checked when it is built, by the same rules in both
  !> front doors): 'integration' (sloshdyn_ode's check_options, the method's code), 'steady'
  !> (check_steady, at any rho > 0), 'lyapunov' (check_lyapunov); status 0 for the others.
  pure subroutine check_layout(name, values, status, message)
    character(len=*), intent(in) :: name
    real(wp), intent(in) :: values(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(model_t) :: model
    status = 0
    message = ''
    select case (name)
    case ('integration')
      if (size(values) == INTEGRATION_SIZE) then
        call check_options(to_ode_options(values), [0.0_wp], status, message)
        if (status == 0) call check_method(to_method(values), status, message)
      end if
    case ('steady')
      model%excitation%rho = 1
      if (size(values) == STEADY_SIZE) call check_steady(model, to_steady(values), status, &
                                                         message)
    case ('lyapunov')
      if (size(values) == LYAPUNOV_SIZE) call check_lyapunov(to_lyapunov(values), status, &
                                                             message)
    end select
  end subroutine check_layout

  !> The parameters of a stability chart (its axes), comma-separated in code order from
  !> CHART_RHO.
  pure function chart_axes() result(names)
    character(len=:), allocatable :: names
    integer :: k
    names = chart_parameter_name(CHART_RHO)
    do k = CHART_RHO + 1, CHART_KAPPA
      names = names//','//chart_parameter_name(k)
    end do
  end function chart_axes

  !> x as an integer; NaN and values beyond the integer range become -huge (out of every range).
  elemental integer function to_int(x)
    real(wp), intent(in) :: x
    if (x == x .and. abs(x) < real(huge(1), wp)) then
      to_int = nint(x)
    else
      to_int = -huge(1)
    end if
  end function to_int

  pure function to_ode_options(a) result(options)
    real(wp), intent(in) :: a(INTEGRATION_SIZE)
    type(ode_options) :: options
    options%rtol = a(1)
    options%atol = a(2)
    options%h_initial = a(3)
    options%h_max = a(4)
    options%h_min = a(5)
    options%max_steps = to_int(a(6))
  end function to_ode_options

  pure integer function to_method(a) result(method)
    real(wp), intent(in) :: a(INTEGRATION_SIZE)
    method = to_int(a(7))
  end function to_method

  pure function from_ode_options(options, method) result(a)
    type(ode_options), intent(in) :: options
    integer, intent(in) :: method
    real(wp) :: a(INTEGRATION_SIZE)
    a = [options%rtol, options%atol, options%h_initial, options%h_max, options%h_min, &
         real(options%max_steps, wp), real(method, wp)]
  end function from_ode_options

  pure function to_steady(a) result(options)
    real(wp), intent(in) :: a(STEADY_SIZE)
    type(steady_options) :: options
    options = steady_options(a(1), a(2), a(3), to_int(a(4)), to_int(a(5)), a(6), a(7) /= 0)
  end function to_steady

  pure function from_steady(options) result(a)
    type(steady_options), intent(in) :: options
    real(wp) :: a(STEADY_SIZE)
    a = [options%transient_periods, options%settle_tol, options%max_transient_periods, &
         real(options%window_periods, wp), real(options%samples_per_period, wp), &
         options%periodic_tol, merge(1.0_wp, 0.0_wp, options%shooting)]
  end function from_steady

  pure function to_response(a) result(options)
    real(wp), intent(in) :: a(RESPONSE_SIZE)
    type(response_options) :: options
    options%n_scan = to_int(a(1))
    options%n_amplitudes = to_int(a(2))
    options%n_phases = to_int(a(3))
    options%amplitude_min = a(4)
    options%amplitude_max = a(5)
    options%continuation%ds = a(6)
    options%continuation%ds_min = a(7)
    options%continuation%ds_max = a(8)
    options%continuation%x_scale = a(9)
    options%continuation%max_points = to_int(a(10))
    options%continuation%newton = to_newton(a(11:13))
  end function to_response

  pure function from_response(options) result(a)
    type(response_options), intent(in) :: options
    real(wp) :: a(RESPONSE_SIZE)
    associate (c => options%continuation)
      a = [real(options%n_scan, wp), real(options%n_amplitudes, wp), &
           real(options%n_phases, wp), options%amplitude_min, options%amplitude_max, c%ds, &
           c%ds_min, c%ds_max, c%x_scale, real(c%max_points, wp), from_newton(c%newton)]
    end associate
  end function from_response

  pure function to_lyapunov(a) result(options)
    real(wp), intent(in) :: a(LYAPUNOV_SIZE)
    type(lyapunov_options) :: options
    options = lyapunov_options(to_int(a(1)), to_int(a(2)), to_int(a(3)), a(4) /= 0, &
                               to_int(a(5)))
  end function to_lyapunov

  pure function from_lyapunov(options) result(a)
    type(lyapunov_options), intent(in) :: options
    real(wp) :: a(LYAPUNOV_SIZE)
    a = real([options%transient_periods, options%n_periods, options%renormalise_every, &
              merge(1, 0, options%spectrum), options%average], wp)
  end function from_lyapunov

  !> A continuation of periodic orbits or slow-flow cycles (its max_points set apart).
  pure function to_continuation(a) result(options)
    real(wp), intent(in) :: a(CONTINUATION_SIZE)
    type(continuation_options) :: options
    options = continuation_options(ds=a(1), ds_min=a(2), ds_max=a(3), x_scale=a(4), &
                                   direction=to_int(a(5)), newton=to_newton(a(6:8)))
  end function to_continuation

  pure function to_newton(a) result(options)
    real(wp), intent(in) :: a(size(newton_fields))
    type(newton_options) :: options
    options = newton_options(x_tol=a(1), f_tol=a(2), max_iter=to_int(a(3)))
  end function to_newton

  pure function from_newton(options) result(a)
    type(newton_options), intent(in) :: options
    real(wp) :: a(size(newton_fields))
    a = [options%x_tol, options%f_tol, real(options%max_iter, wp)]
  end function from_newton

  !> tank(TANK_SIZE) in the order of tank_t's components (n and p as reals).
  pure function to_tank(a) result(tank)
    real(wp), intent(in) :: a(TANK_SIZE)
    type(tank_t) :: tank
    tank = tank_t(a(1), a(2), a(3), a(4), a(5), a(6), a(7), a(8), a(9), a(10), a(11), a(12), &
                  a(13), a(14), to_int(a(15)), to_int(a(16)), a(17), a(18), a(19), &
                  to_int(a(20)), a(21), a(22), to_int(a(23)), to_int(a(24)))
  end function to_tank

  pure function from_tank(tank) result(a)
    type(tank_t), intent(in) :: tank
    real(wp) :: a(TANK_SIZE)
    a = [tank%radius, tank%liquid_depth, tank%freeboard, tank%liquid_density, tank%liquid_mass, &
         tank%tank_mass, tank%support_frequency, tank%support_damping, tank%support_stiffness, &
         tank%support_damping_coefficient, tank%support_height, tank%sloshing_damping, &
         tank%impact_stiffness, tank%impact_damping, real(tank%n, wp), real(tank%p, wp), &
         tank%gravity, tank%roof_slope, tank%roof_radius, real(tank%shape, wp), tank%length, &
         tank%width, real(tank%modes, wp), real(tank%roof_contact, wp)]
  end function from_tank

  !> ground(GROUND_SIZE) = [kind (GROUND_HARMONIC, GROUND_RECORD), peak_acceleration [m/s^2],
  !> frequency [Hz], dt [s], scale_factor (what it was scaled by)] and, for a record, its
  !> samples [m/s^2].
  pure function to_ground(a, samples) result(ground)
    real(wp), intent(in) :: a(GROUND_SIZE), samples(:)
    type(ground_motion_t) :: ground
    if (to_int(a(1)) == GROUND_RECORD) then
      ground = record_ground(a(4), samples)
    else
      ground = harmonic_ground(a(2), a(3))
    end if
    ground%scale_factor = a(5)
  end function to_ground

  pure function from_ground(ground) result(a)
    type(ground_motion_t), intent(in) :: ground
    real(wp) :: a(GROUND_SIZE)
    a = [real(ground%kind, wp), ground%peak_acceleration, ground%frequency, ground%dt, &
         ground%scale_factor]
  end function from_ground

  !> The &chart settings from chart(CHART_SIZE) (the grid and the curves),
  !> chart_range(CHART_RANGE_SIZE) (the model and the axes as codes, the box, threads) and the
  !> one-parameter runs' response(RESPONSE_SIZE) (&response's numbers; n_scan is chart's).
  pure function to_chart(a, r, response) result(settings)
    real(wp), intent(in) :: a(CHART_SIZE), r(CHART_RANGE_SIZE), response(RESPONSE_SIZE)
    type(chart_settings) :: settings
    settings%response = to_response(response)
    settings%n_columns = to_int(a(1))
    settings%n_levels = to_int(a(2))
    settings%response%n_scan = to_int(a(3))
    settings%max_points = to_int(a(4))
    settings%max_curves = to_int(a(5))
    settings%brute_force_starts = to_int(a(6))
    settings%model = to_int(r(1))
    settings%parameters = to_int(r(2:3))
    settings%p_min = r([4, 6])
    settings%p_max = r([5, 7])
    settings%threads = to_int(r(8))
  end function to_chart

  pure function from_chart(settings) result(a)
    type(chart_settings), intent(in) :: settings
    real(wp) :: a(CHART_SIZE)
    a = real([settings%n_columns, settings%n_levels, settings%response%n_scan, &
              settings%max_points, settings%max_curves, settings%brute_force_starts], wp)
  end function from_chart

  pure function from_chart_range(settings) result(r)
    type(chart_settings), intent(in) :: settings
    real(wp) :: r(CHART_RANGE_SIZE)
    r = [real(settings%model, wp), real(settings%parameters, wp), settings%p_min(1), &
         settings%p_max(1), settings%p_min(2), settings%p_max(2), real(settings%threads, wp)]
  end function from_chart_range

  !> The groups of a run_config that only the namelist reader returns (bridge read_input).
  pure function from_analysis(config) result(a)
    type(run_config), intent(in) :: config
    real(wp) :: a(ANALYSIS_SIZE)
    a = [config%sigma1, config%kappa_min, config%kappa_max]
  end function from_analysis

  pure function from_simulation(settings) result(a)
    type(simulation_settings), intent(in) :: settings
    real(wp) :: a(SIMULATION_SIZE)
    a = [settings%t_end, real(settings%n_out, wp), settings%y0]
  end function from_simulation

  pure function from_sweep(settings) result(a)
    type(sweep_settings), intent(in) :: settings
    real(wp) :: a(SWEEP_SIZE)
    a = [real(settings%parameter, wp), settings%start, settings%stop, &
         real(settings%n_points, wp), real(settings%direction, wp), &
         merge(1.0_wp, 0.0_wp, settings%carry_state), real(settings%threads, wp)]
  end function from_sweep

  pure function from_response_range(settings) result(a)
    type(response_settings), intent(in) :: settings
    real(wp) :: a(RESPONSE_RANGE_SIZE)
    a = [merge(1.0_wp, 0.0_wp, settings%internal_resonance), real(settings%parameter, wp), &
         settings%start, settings%stop, real(settings%switch_at, wp), &
         real(settings%curve_at, wp), settings%curve_start, settings%curve_stop]
  end function from_response_range

  pure function from_seismic(settings) result(a)
    type(seismic_settings), intent(in) :: settings
    real(wp) :: a(SEISMIC_SIZE)
    a = [settings%t_end, real(settings%n_out, wp)]
  end function from_seismic

  !> &study's numbers (its strings travel as text).
  pure function from_study(st) result(a)
    type(study_settings), intent(in) :: st
    real(wp) :: a(STUDY_SIZE)
    a = [merge(1.0_wp, 0.0_wp, st%given), real(st%kind, wp), real(st%workers, wp), &
         real(st%worker_kind, wp), real(st%points_per_task, wp), st%frequency_start, &
         st%frequency_stop, real(st%n_frequencies, wp), st%amplitude_start, st%amplitude_stop, &
         real(st%n_amplitudes, wp), real(st%continuation, wp), st%x1_start, st%x1_stop, &
         st%dx1_start, st%dx1_stop, real(st%n_grid, wp), st%tol, st%intensity_start, &
         st%intensity_stop, real(st%n_intensities, wp), st%spectral_damping, &
         real(st%min_workers, wp), st%grace_time]
  end function from_study

  !> &design(DESIGN_SIZE) as the design spectrum, the codes' factors and whether the spectrum
  !> is the ground motion's (spectrum = DESIGN_FROM_GROUND; then the spectrum's kind stays its
  !> default and only k and q count).
  pure subroutine to_design(a, spec, factors, from_ground)
    real(wp), intent(in) :: a(DESIGN_SIZE)
    type(design_spectrum_t), intent(out) :: spec
    type(design_factors_t), intent(out) :: factors
    logical, intent(out) :: from_ground
    from_ground = to_int(a(1)) == DESIGN_FROM_GROUND
    if (.not. from_ground) spec%kind = to_int(a(1))
    spec%s_ds = a(2)
    spec%s_d1 = a(3)
    spec%t_l = a(4)
    spec%k = a(5)
    spec%a_gr = a(6)
    spec%gamma_i = a(7)
    spec%ground_type = to_int(a(8))
    spec%ec8_type = to_int(a(9))
    spec%q = a(10)
    spec%beta = a(11)
    factors = design_factors_t(a(12), to_int(a(13)), a(14), a(15), a(16), a(17), a(18), a(19), &
                               a(20), a(21) /= 0, a(22), to_int(a(23)))
  end subroutine to_design

  pure function from_design(spec, factors, from_ground) result(a)
    type(design_spectrum_t), intent(in) :: spec
    type(design_factors_t), intent(in) :: factors
    logical, intent(in) :: from_ground
    real(wp) :: a(DESIGN_SIZE)
    a = [real(merge(DESIGN_FROM_GROUND, spec%kind, from_ground), wp), spec%s_ds, spec%s_d1, &
         spec%t_l, spec%k, spec%a_gr, spec%gamma_i, real(spec%ground_type, wp), &
         real(spec%ec8_type, wp), spec%q, spec%beta, factors%importance, &
         real(factors%use_group, wp), factors%r_wi, factors%r_wc, factors%r_i, factors%r_c, &
         factors%impulsive_period, factors%impulsive_damping_ratio, factors%tank_mass_height, &
         merge(1.0_wp, 0.0_wp, factors%vertical), factors%vertical_acceleration, &
         real(factors%wall_pressure, wp)]
  end function from_design

  !> &tank_structure(TANK_STRUCTURE_SIZE) as tank_structure_t (and back): the layout's order.
  pure function to_tank_structure(a) result(st)
    real(wp), intent(in) :: a(TANK_STRUCTURE_SIZE)
    type(tank_structure_t) :: st
    integer, parameter :: n = max_courses, c = 3
    st%given = a(1) /= 0
    st%material = to_int(a(2))
    st%course_height = a(c:c + n - 1)
    st%course_thickness = a(c + n:c + 2*n - 1)
    st%course_yield_strength = a(c + 2*n:c + 3*n - 1)
    st%course_tensile_strength = a(c + 3*n:c + 4*n - 1)
    associate (b => a(c + 4*n:))
      st%corrosion_allowance = b(1); st%joint_efficiency = b(2); st%elastic_modulus = b(3)
      st%density = b(4); st%bottom_thickness = b(5); st%annular_thickness = b(6)
      st%bottom_corrosion_allowance = b(7); st%annular_yield_strength = b(8)
      st%roof_mass = b(9); st%roof_mass_height = b(10); st%anchorage = to_int(b(11))
      st%anchor_count = to_int(b(12)); st%anchor_capacity = b(13); st%friction = b(14)
    end associate
  end function to_tank_structure

  pure function from_tank_structure(st) result(a)
    type(tank_structure_t), intent(in) :: st
    real(wp) :: a(TANK_STRUCTURE_SIZE)
    a = [merge(1.0_wp, 0.0_wp, st%given), real(st%material, wp), st%course_height, &
         st%course_thickness, st%course_yield_strength, st%course_tensile_strength, &
         st%corrosion_allowance, st%joint_efficiency, st%elastic_modulus, st%density, &
         st%bottom_thickness, st%annular_thickness, st%bottom_corrosion_allowance, &
         st%annular_yield_strength, st%roof_mass, st%roof_mass_height, real(st%anchorage, wp), &
         real(st%anchor_count, wp), st%anchor_capacity, st%friction]
  end function from_tank_structure


  !> counts(4) = [rhs evaluations, accepted steps, rejected steps, tau reached].
  pure function counts_array(stats) result(counts)
    type(ode_stats), intent(in) :: stats
    real(wp) :: counts(4)
    counts = [real(stats%n_rhs, wp), real(stats%n_accepted, wp), real(stats%n_rejected, wp), &
              stats%t_reached]
  end function counts_array

  !> The position of the field named `field` in the named layout (names are case-sensitive:
  !> 'physical' has both M and m); 0 when there is none. The bridge fills and reads the small
  !> results (pendulum, physical, groups, natural_frequencies) by these names, never by number.
  pure integer function field_index(layout, field)
    character(len=*), intent(in) :: layout, field
    type(field_t), allocatable :: fields(:)
    fields = layout_of(layout)
    field_index = findloc(fields%name, field, dim=1)
  end function field_index
end module sloshdyn_layouts
