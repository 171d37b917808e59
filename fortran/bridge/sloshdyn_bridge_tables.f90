!> The f2py bridge of _tables.py: the names the core defines once (layouts, table columns, codes)
!> and the defaults of the option types.
!> The bridge's contract (c_double/c_int arrays in named layouts, status and message,
!> threads and the GIL) is written once, in sloshdyn_bridge_model.f90.
module sloshdyn_bridge_tables
  use, intrinsic :: iso_c_binding, only: c_double, c_int
  implicit none

contains

  !> Names: a result table's comma-separated column names (list = 'table:NAME') or their format
  !> letters ('formats:NAME'), a settings or model array's field names ('layout:NAME',
  !> sloshdyn_layouts), or the names of the codes of an enumerated option: 'analyses',
  !> 'methods', 'chart_models', 'chart_axes', 'excitation_parameters', 'directions',
  !> 'study_kinds', 'worker_kinds', 'continuations', 'ground_kinds', 'resonances' and the kind
  !> lists of sloshdyn_tables ('special', 'motion', 'verdict', ...); first = the code of the
  !> first name.
  subroutine names(list, text, first, status, message)
    use sloshdyn_tables, only: table_header, table_formats, kind_names
    use sloshdyn_namelist, only: known_analyses, chart_models, direction_names, study_kinds, &
                                 worker_kinds, continuation_names, DIRECTION_UP
    use sloshdyn_integrator, only: method_names
    use sloshdyn_excitation, only: PARAMETER_RHO
    use sloshdyn_ground, only: GROUND_HARMONIC
    use sloshdyn_tank, only: shape_names, SHAPE_CIRCULAR
    use sloshdyn_layouts, only: layout_fields, join, excitation_parameters, ground_kinds, &
                                resonances, chart_axes, CHART_RHO
    character(len=*), intent(in) :: list
    character(len=1024), intent(out) :: text
    integer(c_int), intent(out) :: first, status
    character(len=256), intent(out) :: message
    character(len=:), allocatable :: joined
    integer :: code
    status = 0
    message = ''
    code = 1
    if (index(list, 'table:') == 1) then
      joined = table_header(list(7:))
    else if (index(list, 'formats:') == 1) then
      joined = table_formats(list(9:))
    else if (index(list, 'layout:') == 1) then
      joined = layout_fields(list(8:))
    else
      select case (list)
      case ('analyses');      joined = join(known_analyses, ',')
      case ('methods')
        joined = join(method_names, ',')
        code = lbound(method_names, 1)
      case ('chart_models');  joined = join(chart_models, ',')
      case ('chart_axes')
        joined = chart_axes()
        code = CHART_RHO
      case ('excitation_parameters')
        joined = join(excitation_parameters, ',')
        code = PARAMETER_RHO
      case ('directions')
        joined = join(direction_names, ',')
        code = DIRECTION_UP
      case ('study_kinds');   joined = join(study_kinds, ',')
      case ('worker_kinds');  joined = join(worker_kinds, ',')
      case ('continuations'); joined = join(continuation_names, ',')
      case ('ground_kinds')
        joined = join(ground_kinds, ',')
        code = GROUND_HARMONIC
      case ('resonances')
        joined = join(resonances, ',')
        code = 0
      case ('tank_shapes')
        joined = join(shape_names, ',')
        code = SHAPE_CIRCULAR
      case default
        call kind_names(list, joined, code)
      end select
    end if
    first = code
    text = joined
    if (len(joined) == 0) then
      status = 1
      message = "no names for '"//list//"'"
    end if
  end subroutine names

  !> The defaults of the option types, each in its layout: the model (rpar, ipar of
  !> sloshdyn_model; its excitation and groups 0), integration, steady, response, lyapunov and
  !> shooting.
  subroutine defaults(model, model_integers, integration, steady, response, lyapunov, shooting)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_to_arrays
    use sloshdyn_layouts, only: INTEGRATION_SIZE, STEADY_SIZE, RESPONSE_SIZE, LYAPUNOV_SIZE, &
                                SHOOTING_SIZE, from_ode_options, from_steady, from_response, &
                                from_lyapunov
    use sloshdyn_ode, only: ode_options
    use sloshdyn_simulation, only: steady_options
    use sloshdyn_response, only: response_options
    use sloshdyn_periodic_response, only: lyapunov_options, newton_tol_default, max_iter_default
    use sloshdyn_integrator, only: METHOD_AUTO
    real(c_double), intent(out) :: model(n_real_params), integration(INTEGRATION_SIZE), &
                                   steady(STEADY_SIZE), response(RESPONSE_SIZE), &
                                   lyapunov(LYAPUNOV_SIZE), shooting(SHOOTING_SIZE)
    integer(c_int), intent(out) :: model_integers(n_int_params)
    type(model_t) :: m
    integer :: ints(n_int_params)
    call model_to_arrays(m, model, ints)
    model_integers = ints
    integration = from_ode_options(ode_options(), METHOD_AUTO)
    steady = from_steady(steady_options())
    response = from_response(response_options())
    lyapunov = from_lyapunov(lyapunov_options())
    shooting = [newton_tol_default, real(max_iter_default, c_double)]
  end subroutine defaults
end module sloshdyn_bridge_tables
