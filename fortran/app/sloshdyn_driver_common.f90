!> What the run driver (sloshdyn_driver) and its submodule sloshdyn_driver_tank share: the
!> beginning of the result files (the output directory, the parameters and, for a tank, its
!> properties and the design-code cross-check), the context of a failed step, the name of the
!> method that runs, and the summaries' number texts. A module of its own, so that the driver
!> exports none of them (gfortran does not export a module's private procedures to its
!> submodules' object files).
module sloshdyn_driver_common
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, status_name
  use sloshdyn_text, only: num2str
  use sloshdyn_tables, only: table_size, CODES_COLUMNS, CODES_ROWS, CODES_SOURCES, &
                             TANK_SI_SIZE, TANK_MODES_ROWS
  use sloshdyn_integrator, only: method_name, chosen_method, METHOD_AUTO
  use sloshdyn_seismic, only: design_code_checks, tank_summary, tank_modes
  use sloshdyn_tank, only: max_modes
  use sloshdyn_namelist, only: run_config
  use sloshdyn_results, only: result_files
  implicit none
  private
  public :: begin_files, in_context, used_method, value_text, difference, pad

contains

  !> A failed step: keep the status, put the context (and the kind of failure) in the message.
  pure subroutine in_context(context, status, message)
    character(len=*), intent(in) :: context
    integer, intent(in) :: status
    character(len=message_len), intent(inout) :: message
    if (status == SD_OK) return
    if (status == SD_BAD_INPUT) then
      message = context//': '//trim(message)
    else
      message = context//': '//status_name(status)//': '//trim(message)
    end if
  end subroutine in_context

  !> Create the output directory (only once the analysis succeeded) and write the parameters
  !> (and, for a tank, its properties and the design-code cross-check).
  subroutine begin_files(config, files, status, message)
    type(run_config), intent(in) :: config
    type(result_files), intent(inout) :: files
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: row(TANK_SI_SIZE), codes(CODES_COLUMNS, CODES_ROWS), &
                modes(TANK_MODES_ROWS, max_modes)
    integer :: i, n_codes
    call files%create(config%directory, status, message)
    if (status /= SD_OK) return
    associate (m => config%model)
      call files%write_table('parameters.csv', 'parameters', reshape([m%s1, m%mu1, m%kappa, &
                             m%theta0, m%beta, m%gamma, m%delta, m%zeta, real(m%n, wp), &
                             real(m%p, wp), m%excitation%A, m%excitation%rho, m%a_coef, &
                             m%b_coef], [table_size('parameters'), 1]), status, message)
    end associate
    if (status /= SD_OK .or. .not. config%dimensional) return
    call tank_summary(config%tank, config%tank_props, config%model, row)
    call files%write_table('tank.csv', 'tank_si', reshape(row, [TANK_SI_SIZE, 1]), status, &
                           message)
    if (status == SD_OK .and. config%tank_props%modes > 1) then
      call tank_modes(config%tank_props, modes(:, 1:config%tank_props%modes))
      call files%write_table('tank_modes.csv', 'tank_modes', &
                             modes(:, 1:config%tank_props%modes), status, message)
    end if
    if (status == SD_OK) call design_code_checks(config%tank, config%ground, config%has_ground, &
                                                 codes, status, message)
    ! the modal sums only with modes > 1
    n_codes = merge(CODES_ROWS, CODES_SOURCES, config%tank_props%modes > 1)
    if (status == SD_OK) call files%write_table('design_codes.csv', 'design_codes', &
                                                reshape([(real(i, wp), codes(:, i), &
                                                i = 1, n_codes)], &
                                                [CODES_COLUMNS + 1, n_codes]), status, message)
  end subroutine begin_files

  pure function value_text(x) result(text)
    real(wp), intent(in) :: x
    character(len=:), allocatable :: text
    if (x /= x) then
      text = '-'
    else
      text = num2str(x, significant=6)
    end if
  end function value_text

  pure function difference(x, reference) result(text)
    real(wp), intent(in) :: x, reference
    character(len=:), allocatable :: text
    text = ''
    if (x == x .and. reference == reference .and. reference /= 0) &
      text = ' ('//trim(percent(100*(x - reference)/reference))//')'
  end function difference

  pure function percent(x) result(text)
    real(wp), intent(in) :: x
    character(len=:), allocatable :: text
    character(len=16) :: buffer
    write (buffer, '(sp, f16.1)') x
    text = trim(adjustl(buffer))//'%'
  end function percent

  pure function pad(text, width) result(padded)
    character(len=*), intent(in) :: text
    integer, intent(in) :: width
    character(len=max(width, len(text) + 1)) :: padded
    padded = text
  end function pad

  !> The name of the integration method that runs, as the summaries print it: the method, or
  !> for 'auto' the one chosen for rtol, e.g. 'dop853 by auto'.
  function used_method(config) result(name)
    type(run_config), intent(in) :: config
    character(len=:), allocatable :: name
    name = method_name(chosen_method(config%method, config%integration%rtol))
    if (config%method == METHOD_AUTO) name = name//' by auto'
  end function used_method
end module sloshdyn_driver_common
