!> The input file: Fortran namelist groups, read and validated in full before anything is
!> computed. The only reader: the executable uses it directly and Python through the bridge, so
!> both front doors apply the same rules, defaults and messages. The groups and variables are
!> documented in docs/namelist.md.
!>
!> This module reads a whole file and applies the rules that tie its groups together; it is the
!> public face of the reader (it re-exports the run configuration). Its parts:
!> sloshdyn_namelist_scanner (the file split into groups, a group's text parsed, the culprit
!> named), sloshdyn_run_config (run_config, its settings types and code lists),
!> sloshdyn_namelist_groups (one reader per group) and sloshdyn_namelist_study (&study).
module sloshdyn_namelist
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, check_real
  use sloshdyn_text, only: num2str
  use sloshdyn_model, only: model_t, model_from_arrays, require_stable_trivial
  use sloshdyn_excitation, only: PARAMETER_RHO, PARAMETER_A, PARAMETER_FREQUENCY, &
                                 set_excitation_parameter
  use sloshdyn_vessel, only: tank_t, tank_properties, tank_model
  use sloshdyn_tank, only: SHAPE_CIRCULAR, shape_names
  use sloshdyn_ground, only: ground_motion_t, ground_excitation, GROUND_RECORD
  use sloshdyn_stability_chart, only: chart_settings
  use sloshdyn_ode, only: ode_options
  use sloshdyn_simulation, only: steady_options, check_steady
  use sloshdyn_periodic_response, only: lyapunov_options, check_lyapunov
  use sloshdyn_namelist_scanner, only: input_file, fail
  use sloshdyn_run_config, only: run_config, simulation_settings, sweep_settings, &
                                 response_settings, seismic_settings, study_settings, &
                                 study_kinds, worker_kinds, continuation_names, known_analyses, &
                                 path_len, chart_models, direction_names, DIRECTION_UP, &
                                 DIRECTION_DOWN, DIRECTION_BOTH, ANALYSIS_LINEAR, &
                                 ANALYSIS_SIMULATE, ANALYSIS_STEADY_STATE, ANALYSIS_SWEEP, &
                                 ANALYSIS_FREQUENCY_RESPONSE, ANALYSIS_PERIODIC_RESPONSE, &
                                 ANALYSIS_LYAPUNOV, ANALYSIS_SEISMIC, ANALYSIS_STABILITY_CHART, &
                                 ANALYSIS_SWIRL
  use sloshdyn_namelist_groups, only: open_input, describe_groups, check_threads, G_SWEEP, &
                                      G_MODEL, &
                                      G_TANK, G_GROUND_MOTION, G_EXCITATION, G_ANALYSIS, &
                                      read_model, read_tank, read_ground_motion, &
                                      read_excitation, read_analysis, read_output, &
                                      read_integration, read_simulation, read_steady, &
                                      read_sweep, read_response, read_lyapunov, read_seismic, &
                                      read_chart, frequency_of_sweep, read_design, G_DESIGN, &
                                      G_STEADY, G_LYAPUNOV, read_tank_structure, &
                                      G_TANK_STRUCTURE
  use sloshdyn_namelist_study, only: read_study
  use sloshdyn_layouts, only: check_layout, from_steady, from_lyapunov
  use sloshdyn_design_check, only: check_design_input
  use sloshdyn_tank_structure, only: tank_structure_t
  implicit none
  private
  public :: run_config, simulation_settings, sweep_settings, &
            response_settings, seismic_settings, study_settings, study_kinds, worker_kinds, &
            continuation_names, read_input, namelist_defaults, known_analyses, path_len, &
            check_threads
  public :: ANALYSIS_LINEAR, ANALYSIS_SIMULATE, ANALYSIS_STEADY_STATE, ANALYSIS_SWEEP, &
            ANALYSIS_FREQUENCY_RESPONSE, ANALYSIS_PERIODIC_RESPONSE, ANALYSIS_LYAPUNOV, &
            ANALYSIS_SEISMIC, ANALYSIS_STABILITY_CHART, ANALYSIS_SWIRL
  public :: chart_models
  public :: DIRECTION_UP, DIRECTION_DOWN, DIRECTION_BOTH, direction_names

contains

  !> Read and validate the whole input file. On failure nothing is returned but a status and a
  !> message naming the group, the variable, its value and the allowed range.
  subroutine read_input(path, config, status, message)
    character(len=*), intent(in) :: path
    type(run_config), intent(out) :: config
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(input_file) :: file
    real(wp) :: groups(8), A, rho
    integer :: exponents(2)

    call open_input(path, file, status, message)
    if (status /= SD_OK) return

    ! which description of the system: dimensionless (&model) or a tank in SI (&tank)
    associate (g => file%groups)
      if (g(G_MODEL)%given .and. g(G_TANK)%given) then
        call fail(status, message, 'give either &model (dimensionless) or &tank (a tank in '// &
                  'SI units), not both')
      else if (.not. (g(G_MODEL)%given .or. g(G_TANK)%given)) then
        call fail(status, message, 'missing group &model (or &tank): the system is not described')
      else if (g(G_MODEL)%given .and. g(G_GROUND_MOTION)%given) then
        call fail(status, message, '&ground_motion goes with &tank (SI units); with &model, '// &
                  'give the dimensionless excitation in &excitation')
      else if (g(G_TANK)%given .and. g(G_EXCITATION)%given) then
        call fail(status, message, '&excitation goes with &model (dimensionless); with &tank, '// &
                  'give the ground motion in &ground_motion (SI units)')
      end if
      if (status /= SD_OK) return
      config%dimensional = g(G_TANK)%given
      config%has_ground = g(G_GROUND_MOTION)%given
    end associate

    if (config%dimensional) then
      call read_tank(file, config%tank, config%planar, status, message)
      if (status /= SD_OK) return
      call tank_model(config%tank, config%model, config%tank_props, status, message)
      if (status /= SD_OK) then
        message = '&tank: '//trim(message)
        return
      end if
      call read_ground_motion(file, config%tank_props, frequency_of_sweep(file), config%ground, &
                              config%ground_y, config%has_ground_y, config%azimuth, &
                              config%ellipticity, status, message)
      if (status /= SD_OK) return
      if (config%has_ground) then
        call ground_excitation(config%ground, config%tank_props%omega, &
                               config%tank_props%rod_length, config%model%excitation, status, &
                               message)
        if (status /= SD_OK) then
          message = '&ground_motion: '//trim(message)
          return
        end if
      end if
    else
      call read_excitation(file, A, rho, config%azimuth, config%ellipticity, status, message)
      if (status /= SD_OK) return
      call read_model(file, groups, exponents, config%planar, status, message)
      if (status /= SD_OK) return
      call model_from_arrays([groups(1:7), A, rho, groups(8)], exponents, config%model, status, &
                             message)
      if (status /= SD_OK) then
        ! the model's rules name the variable first: A and rho belong to &excitation
        if (index(message, 'A = ') == 1 .or. index(message, 'rho = ') == 1) then
          message = '&excitation: '//trim(message)
        else
          message = '&model: '//trim(message)
        end if
        return
      end if
    end if

    call read_analysis(file, config, status, message)
    if (status == SD_OK) call read_output(file, config%directory, status, message)
    if (status == SD_OK) call read_integration(file, config%integration, config%method, &
                                               status, message)
    if (status == SD_OK) call read_simulation(file, config%analysis == ANALYSIS_SIMULATE, &
                                              config%simulation, status, message)
    if (status == SD_OK) call read_steady(file, config%steady, status, message)
    ! kind = 'swirl' with &sweep: the band at each A of the sweep (its boundary in (rho, A))
    if (status == SD_OK) call read_sweep(file, config%analysis == ANALYSIS_SWEEP .or. &
                                         (config%analysis == ANALYSIS_SWIRL .and. &
                                          file%groups(G_SWEEP)%given), config%sweep, status, &
                                         message)
    if (status == SD_OK) call read_response(file, any(config%analysis == &
                                            [ANALYSIS_FREQUENCY_RESPONSE, &
                                             ANALYSIS_PERIODIC_RESPONSE, ANALYSIS_SWIRL]), &
                                            config%response, status, message)
    if (status == SD_OK) call read_lyapunov(file, config%lyapunov, status, message)
    if (status == SD_OK) call read_seismic(file, config%seismic, status, message)
    if (status == SD_OK) call read_chart(file, config%analysis == ANALYSIS_STABILITY_CHART, &
                                         config%model, config%response%options, config%chart, &
                                         status, message)
    ! the settings groups by the core's rules whatever the analysis, as Python's settings
    ! objects check them when built (sloshdyn_layouts' check_layout): one rule in both doors
    if (status == SD_OK .and. file%groups(G_STEADY)%given) then
      call check_layout('steady', from_steady(config%steady), status, message)
      if (status /= SD_OK) message = '&steady: '//trim(message)
    end if
    if (status == SD_OK .and. file%groups(G_LYAPUNOV)%given) then
      call check_layout('lyapunov', from_lyapunov(config%lyapunov), status, message)
      if (status /= SD_OK) message = '&lyapunov: '//trim(message)
    end if
    if (status == SD_OK) call read_study(file, config, status, message)
    if (status == SD_OK) call read_design(file, config%design_spectrum, config%design_factors, &
                                          config%design_from_ground, status, message)
    if (status == SD_OK) call read_tank_structure(file, config%structure, status, message)
    if (status == SD_OK .and. file%groups(G_TANK_STRUCTURE)%given .and. &
        .not. file%groups(G_DESIGN)%given) &
      call fail(status, message, '&tank_structure goes with &design (the structure of the '// &
                'design check''s structural checks)')
    if (status == SD_OK .and. file%groups(G_DESIGN)%given) then
      config%has_design = .true.
      if (.not. config%dimensional) then
        call fail(status, message, '&design goes with &tank (the design check of a tank in SI '// &
                  'units)')
      else if (config%design_from_ground .and. .not. config%has_ground) then
        call fail(status, message, "&design: spectrum = 'ground_motion' needs the ground "// &
                  'motion (&ground_motion)')
      else
        ! the design check's rules with the tank: the same as Python's (sloshdyn_design_check)
        call check_design_input(config%tank, config%design_spectrum, config%design_factors, &
                                config%design_from_ground, tank_structure_t(), status, message)
        if (status /= SD_OK) then
          message = '&design: '//trim(message)
        else
          call check_design_input(config%tank, config%design_spectrum, config%design_factors, &
                                  config%design_from_ground, config%structure, status, message)
          if (status /= SD_OK) message = '&tank_structure: '//trim(message)
        end if
      end if
    end if
    ! a study file describes no analysis of the executable: the default one is not checked
    if (status == SD_OK .and. .not. (config%study%given .and. .not. file%groups(G_ANALYSIS)%given)) &
      call check_analysis(config, status, message)
  end subroutine read_input

  !> Every group with its variables and their defaults, as the namelist write statement gives
  !> them (the source for the documentation's namelist reference and its test). Required
  !> variables show their placeholder (0).
  subroutine namelist_defaults(text)
    character(len=:), allocatable, intent(out) :: text
    type(input_file) :: file
    type(run_config) :: config
    type(tank_t) :: tank
    type(tank_properties) :: props
    type(ground_motion_t) :: ground, ground_y
    type(ode_options) :: integration
    type(simulation_settings) :: simulation
    type(steady_options) :: steady
    type(sweep_settings) :: sweep
    type(response_settings) :: response
    type(lyapunov_options) :: lyapunov
    type(seismic_settings) :: seismic
    type(chart_settings) :: chart
    character(len=path_len) :: directory
    type(run_config) :: study_config
    real(wp) :: groups(8), A, rho, azimuth, ellipticity
    integer :: exponents(2), method, status
    logical :: planar, has_y
    character(len=message_len) :: message

    call describe_groups(file)
    call read_model(file, groups, exponents, planar, status, message)
    call read_tank(file, tank, planar, status, message)
    call read_ground_motion(file, props, -1.0_wp, ground, ground_y, has_y, azimuth, ellipticity, &
                            status, message)
    call read_excitation(file, A, rho, azimuth, ellipticity, status, message)
    call read_analysis(file, config, status, message)
    call read_output(file, directory, status, message)
    call read_integration(file, integration, method, status, message)
    call read_simulation(file, .false., simulation, status, message)
    call read_steady(file, steady, status, message)
    call read_sweep(file, .false., sweep, status, message)
    call read_response(file, .false., response, status, message)
    call read_lyapunov(file, lyapunov, status, message)
    call read_seismic(file, seismic, status, message)
    call read_chart(file, .false., config%model, response%options, chart, status, message)
    call read_study(file, study_config, status, message)
    call read_design(file, study_config%design_spectrum, study_config%design_factors, has_y, &
                     status, message)
    call read_tank_structure(file, study_config%structure, status, message)
    text = file%description
  end subroutine namelist_defaults

  !> The rules that tie the groups to the analysis asked for.
  subroutine check_analysis(config, status, message)
    type(run_config), intent(inout) :: config
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    type(model_t) :: first

    call check_spatial(config, status, message)
    if (status /= SD_OK) return
    if (config%analysis == ANALYSIS_SEISMIC .and. .not. (config%dimensional .and. &
                                                         config%has_ground)) then
      call fail(status, message, "&analysis: kind = 'seismic' needs a tank (&tank) and its "// &
                'ground motion (&ground_motion)')
      return
    end if
    if (config%has_ground .and. config%ground%kind == GROUND_RECORD .and. .not. any( &
        config%analysis == [ANALYSIS_SEISMIC, ANALYSIS_SIMULATE, ANALYSIS_LINEAR])) then
      call fail(status, message, "&analysis: kind = '"//trim(known_analyses(config%analysis))// &
                "' needs harmonic ground motion (peak_acceleration, frequency), not a record")
      return
    end if

    select case (config%analysis)
    case (ANALYSIS_LINEAR)
      call require_stable_trivial(config%model, status, message)
    case (ANALYSIS_STEADY_STATE, ANALYSIS_SWEEP)
      first = config%model
      if (config%analysis == ANALYSIS_SWEEP .and. config%sweep%parameter == PARAMETER_RHO) &
        first%excitation%rho = min(config%sweep%start, config%sweep%stop)
      if (config%analysis == ANALYSIS_SWEEP .and. &
          config%sweep%parameter == PARAMETER_FREQUENCY) then
        if (.not. (config%dimensional .and. config%has_ground)) then
          call fail(status, message, "&sweep: parameter = 'frequency' sweeps a tank's harmonic "// &
                    'ground motion: it needs &tank and &ground_motion')
          return
        end if
        call set_excitation_parameter(first%excitation, PARAMETER_FREQUENCY, &
                                      2*pi*min(config%sweep%start, config%sweep%stop)/ &
                                      config%tank_props%omega, status, message)
      end if
      call check_steady(first, config%steady, status, message)
      if (status /= SD_OK) message = trim(merge('&excitation', '&steady    ', &
                                                index(message, 'rho') == 1))//': '//trim(message)
    case (ANALYSIS_FREQUENCY_RESPONSE, ANALYSIS_STABILITY_CHART)
      call require_stable_trivial(config%model, status, message)
    case (ANALYSIS_PERIODIC_RESPONSE, ANALYSIS_SWIRL)
      call require_stable_trivial(config%model, status, message)
      if (status /= SD_OK) return
      if (config%analysis == ANALYSIS_SWIRL .and. config%sweep%n_points > 0) then
        if (config%sweep%parameter /= PARAMETER_A .or. &
            config%response%parameter /= PARAMETER_RHO) then
          call fail(status, message, "&sweep: with kind = 'swirl' it gives the values of A at "// &
                    'which the swirl band along rho is found (its boundary in (rho, A)): '// &
                    "&sweep parameter = 'A' and &response parameter = 'rho'")
          return
        end if
      end if
      first = config%model
      if (config%response%parameter == PARAMETER_RHO) first%excitation%rho = config%response%start
      call check_steady(first, config%steady, status, message)
      if (status /= SD_OK) message = '&steady/&excitation: '//trim(message)
    case (ANALYSIS_LYAPUNOV)
      call check_real('rho', config%model%excitation%rho, 0.0_wp, huge(1.0_wp), .true., .true., &
                      'the Lyapunov exponent needs a forcing frequency rho > 0', status, message)
      if (status /= SD_OK) then
        message = '&excitation: '//trim(message)
        return
      end if
      call check_lyapunov(config%lyapunov, status, message)
      if (status /= SD_OK) message = '&lyapunov: '//trim(message)
    end select
  end subroutine check_analysis

  !> The rules of the spatial model (issue 26): planar = .false. (&model or &tank) with p >= 1
  !> (sloshdyn_spatial's spatial_model) for the analyses that have it, of a circular tank with
  !> one sloshing mode; a second component and the out-of-plane initial state only for it. The
  !> analyses that have it: 'simulate' (its time history), 'steady_state' (a periodic orbit of
  !> it by Newton shooting, sloshdyn_swirl's swirl_orbit), 'seismic' (two components) and
  !> 'swirl' ('swirl' only); the others are refused, each with its reason (spatial_refusal).
  subroutine check_spatial(config, status, message)
    type(run_config), intent(in) :: config
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    character(len=:), allocatable :: group
    group = trim(merge('&tank ', '&model', config%dimensional))
    if (config%planar) then
      if (config%analysis == ANALYSIS_SWIRL) then
        call fail(status, message, "&analysis: kind = 'swirl' is the stability of planar "// &
                  'responses out of their plane: it needs the spatial model, planar = .false. '// &
                  'in '//group)
      else if (config%dimensional .and. (config%has_ground_y .or. config%azimuth /= 0 .or. &
                                         config%ellipticity /= 0)) then
        call fail(status, message, '&ground_motion: record_y, azimuth and ellipticity '// &
                  'describe ground motion in two components: they need the spatial model, '// &
                  'planar = .false. in &tank')
      else if (config%azimuth /= 0 .or. config%ellipticity /= 0) then
        call fail(status, message, '&excitation: azimuth and ellipticity describe base '// &
                  'motion in two components: they need the spatial model, planar = .false. '// &
                  'in &model')
      else if (any(config%simulation%y0(5:8) /= 0)) then
        call fail(status, message, '&simulation: y0(5:8) = '// &
                  num2str(config%simulation%y0(5))//', '//num2str(config%simulation%y0(6))// &
                  ', '//num2str(config%simulation%y0(7))//', '// &
                  num2str(config%simulation%y0(8))//' are the out-of-plane states (y1, y1'''// &
                  ', y2, y2'') of the spatial model: they need planar = .false. in '//group)
      else
        call check_y0_values(4, 'planar model (x1, x1'', x2, x2'')')
      end if
      return
    end if
    if (config%model%p < 1) then
      call fail(status, message, group//': planar = .false. needs p >= 1, not p = '// &
                num2str(config%model%p)//' (eq 5 acts on the radial motion of the spatial '// &
                'model, whose direction is undefined at the vertical for p = 0)')
    else if (config%dimensional .and. (config%tank%shape /= SHAPE_CIRCULAR .or. &
                                       config%tank%modes /= 1)) then
      call fail(status, message, '&tank: planar = .false. (the spherical pendulum) is for a '// &
                "circular tank with one sloshing mode, not shape = '"// &
                trim(shape_names(config%tank%shape))// &
                "' with modes = "//num2str(config%tank%modes))
    else if (config%analysis == ANALYSIS_SWIRL .and. (config%azimuth /= 0 .or. &
                                                      config%ellipticity /= 0)) then
      call fail(status, message, "&excitation: kind = 'swirl' follows planar responses to "// &
                'base motion along x: azimuth = '//num2str(config%azimuth)// &
                ' and ellipticity = '//num2str(config%ellipticity)//' must be 0')
    else if (.not. any(config%analysis == [ANALYSIS_SIMULATE, ANALYSIS_STEADY_STATE, &
                                           ANALYSIS_SEISMIC, ANALYSIS_SWIRL])) then
      call fail(status, message, group//": planar = .false. (the spatial model) is not for "// &
                "kind = '"//trim(known_analyses(config%analysis))//"': "// &
                spatial_refusal(config%analysis))
    else
      call check_y0_values(8, 'spatial model (x1, x1'', x2, x2'', y1, y1'', y2, y2'')')
    end if

  contains

    !> y0 given as a list has one value per state of the model, as Python's y0 has
    subroutine check_y0_values(states, model)
      integer, intent(in) :: states
      character(len=*), intent(in) :: model
      integer :: given
      given = config%simulation%y0_values
      if (given < 0 .or. given == states) return
      call fail(status, message, '&simulation: y0 has '//num2str(given)//' value'// &
                trim(merge('s', ' ', given /= 1))//', the '//model//' has '// &
                num2str(states)//' states: give all '//num2str(states)// &
                ', or single ones as y0(i) = value')
    end subroutine check_y0_values
  end subroutine check_spatial

  !> Why an analysis does not take the spatial model.
  pure function spatial_refusal(analysis) result(why)
    integer, intent(in) :: analysis
    character(len=:), allocatable :: why
    select case (analysis)
    case (ANALYSIS_LINEAR)
      why = 'it is symmetric about the vertical, its linear modes are the planar ones in x '// &
            'and in y; run planar = .true.'
    case (ANALYSIS_SWEEP)
      why = 'its steady states are orbits by shooting (kind = ''steady_state''), along rho '// &
            'see the swirl band (kind = ''swirl'')'
    case (ANALYSIS_FREQUENCY_RESPONSE, ANALYSIS_STABILITY_CHART)
      why = 'the slow flow (eq 41-55) is derived for the planar model; the swirl band is '// &
            'kind = ''swirl'''
    case (ANALYSIS_PERIODIC_RESPONSE)
      why = 'the continuation of swirling orbits is not built; kind = ''swirl'' (planar '// &
            'orbits) or ''steady_state'' (one swirling orbit)'
    case (ANALYSIS_LYAPUNOV)
      why = 'its Lyapunov exponents (8 states) are not built, only the planar model''s 4'
    case default
      why = 'not built for it'
    end select
  end function spatial_refusal
end module sloshdyn_namelist
