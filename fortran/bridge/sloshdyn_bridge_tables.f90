!> The f2py bridge of _tables.py: the names the core defines once (layouts, table columns, codes)
!> and the defaults of the option types.
!> The bridge's contract (c_double/c_int arrays in named layouts, status and message,
!> threads and the GIL) is written once, in sloshdyn_bridge_model.f90.
module sloshdyn_bridge_tables
  use, intrinsic :: iso_c_binding, only: c_double, c_int
  implicit none

contains

  !> Names: a result table's comma-separated column names (list = 'table:NAME') or their format
  !> letters ('formats:NAME'); a settings or model array's field names ('layout:NAME',
  !> sloshdyn_layouts), their kinds ('kinds:NAME': real, integer, flag or code:LIST) and what
  !> they are ('docs:NAME', one line per field); every layout ('layouts'); every enumerated
  !> option ('code_lists'); or the names of the codes of an enumerated option: 'analyses',
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
    use sloshdyn_vessel, only: roof_contact_names, ROOF_CONTACT_NONE
    use sloshdyn_wall_pressure, only: combination_names, COMBINE_SRSS
    use sloshdyn_layouts, only: layout_names, layout_text, join, &
                                excitation_parameters, ground_kinds, resonances, chart_axes, &
                                CHART_RHO, design_spectra
    use sloshdyn_design_spectra, only: ground_types
    use sloshdyn_design_loads, only: wall_pressure_names, WALL_PRESSURE_CODE
    use sloshdyn_tank_structure, only: material_names, anchorage_names, MATERIAL_STEEL, &
                                       ANCHORAGE_SELF
    use sloshdyn_lyapunov, only: average_names, AVERAGE_PLAIN
    character(len=*), intent(in) :: list
    character(len=8192), intent(out) :: text
    integer(c_int), intent(out) :: first, status
    character(len=512), intent(out) :: message
    !> The enumerated options (the cases below, then the kind lists of sloshdyn_tables).
    character(len=*), parameter :: code_lists = 'analyses,methods,chart_models,chart_axes,'// &
      'excitation_parameters,directions,study_kinds,worker_kinds,continuations,ground_kinds,'// &
      'resonances,tank_shapes,roof_contacts,pressure_combinations,design_spectra,ground_types,'// &
      'special,motion,verdict,source,curve,codim2,curve_end,design_source,wall_pressures,'// &
      'materials,anchorages,averages'
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
      joined = layout_text(list(8:), 'name')
    else if (index(list, 'kinds:') == 1) then
      joined = layout_text(list(7:), 'kind')
    else if (index(list, 'docs:') == 1) then
      joined = layout_text(list(6:), 'doc')
    else
      select case (list)
      case ('layouts');       joined = layout_names
      case ('code_lists');    joined = code_lists
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
      case ('design_spectra'); joined = join(design_spectra, ',')
      case ('ground_types');   joined = join(ground_types, ',')
      case ('tank_shapes')
        joined = join(shape_names, ',')
        code = SHAPE_CIRCULAR
      case ('roof_contacts')
        joined = join(roof_contact_names, ',')
        code = ROOF_CONTACT_NONE
      case ('pressure_combinations')
        joined = join(combination_names, ',')
        code = COMBINE_SRSS
      case ('wall_pressures')
        joined = join(wall_pressure_names, ',')
        code = WALL_PRESSURE_CODE
      case ('materials')
        joined = join(material_names, ',')
        code = MATERIAL_STEEL
      case ('anchorages')
        joined = join(anchorage_names, ',')
        code = ANCHORAGE_SELF
      case ('averages')
        joined = join(average_names, ',')
        code = AVERAGE_PLAIN
      case default
        call kind_names(list, joined, code)
      end select
    end if
    first = code
    text = joined
    if (len(joined) == 0) then
      status = 1
      message = "no names for '"//list//"'"
    else if (len(joined) > len(text)) then
      status = 1
      message = "the names of '"//list//"' are longer than the bridge's text"
    end if
  end subroutine names

  !> The defaults of a settings layout (sloshdyn_layouts' layout_defaults: the option types'
  !> defaults, the model's (its excitation and groups 0)), n = the layout's size.
  subroutine layout_defaults(name, n, values, status, message)
    !f2py threadsafe
    use sloshdyn_kinds, only: wp
    use sloshdyn_text, only: num2str
    use sloshdyn_layouts, only: core => layout_defaults
    character(len=*), intent(in) :: name
    integer(c_int), intent(in) :: n
    real(c_double), intent(out) :: values(n)
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
    real(wp), allocatable :: defaults(:)
    logical :: found
    values = 0
    status = 0
    message = ''
    call core(name, defaults, found)
    if (.not. found) then
      status = 1
      message = "no defaults for '"//name//"'"
    else if (size(defaults) /= n) then
      status = 1
      message = "the layout '"//name//"' has "//num2str(size(defaults))//' fields, not '// &
                num2str(int(n))
    else
      values = defaults
    end if
  end subroutine layout_defaults

  !> The core's range rules for the values(n) of a settings layout (sloshdyn_layouts'
  !> check_layout): status 0, or the status and message naming the variable.
  subroutine check_settings(name, n, values, status, message)
    !f2py threadsafe
    use sloshdyn_kinds, only: wp, message_len
    use sloshdyn_layouts, only: core => check_layout
    character(len=*), intent(in) :: name
    integer(c_int), intent(in) :: n
    real(c_double), intent(in) :: values(n)
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
    integer :: info
    character(len=message_len) :: text
    call core(name, real(values, wp), info, text)
    status = info
    message = text
  end subroutine check_settings
end module sloshdyn_bridge_tables
