!> The choice of integration method: every analysis that integrates takes a method code and
!> gets an integrator of the family (sloshdyn_ode) from here.
module sloshdyn_integrator
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT
  use sloshdyn_text, only: num2str
  use sloshdyn_ode, only: ode_system, ode_options, ode_stats, rk_integrator, integrate_with
  use sloshdyn_dopri5, only: dopri5_integrator
  use sloshdyn_dop853, only: dop853_integrator
  implicit none
  private
  public :: new_integrator, integrate, check_method, method_name
  public :: METHOD_DOPRI5, METHOD_DOP853, method_names

  integer, parameter :: METHOD_DOPRI5 = 0, METHOD_DOP853 = 1
  !> Names by code (index = code + 1), as the namelist and Python spell them.
  character(len=6), parameter :: method_names(0:1) = [character(len=6) :: 'rk45', 'dop853']

contains

  pure subroutine check_method(method, status, message)
    integer, intent(in) :: method
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    if (status /= SD_OK) return
    if (method < lbound(method_names, 1) .or. method > ubound(method_names, 1)) then
      status = SD_BAD_INPUT
      message = 'method = '//num2str(method)//' is not known: 0 = rk45 (Dormand-Prince 5(4)), '// &
                '1 = dop853 (Dormand-Prince 8(5,3))'
    end if
  end subroutine check_method

  pure function method_name(method) result(name)
    integer, intent(in) :: method
    character(len=:), allocatable :: name
    name = trim(method_names(method))
  end function method_name

  !> An integrator of the given method, ready for init.
  subroutine new_integrator(method, integ, status, message)
    integer, intent(in) :: method
    class(rk_integrator), allocatable, intent(out) :: integ
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    status = SD_OK
    message = ''
    call check_method(method, status, message)
    if (status /= SD_OK) return
    select case (method)
    case (METHOD_DOP853)
      allocate (dop853_integrator :: integ)
    case default
      allocate (dopri5_integrator :: integ)
    end select
  end subroutine new_integrator

  !> y at every t_out by the chosen method (see integrate_with for failures).
  subroutine integrate(method, sys, t0, y0, t_out, y_out, options, stats, status, message)
    integer, intent(in) :: method
    class(ode_system), intent(in) :: sys
    real(wp), intent(in) :: t0, y0(:), t_out(:)
    real(wp), intent(out) :: y_out(:, :)
    type(ode_options), intent(in) :: options
    type(ode_stats), intent(out) :: stats
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    class(rk_integrator), allocatable :: integ
    call new_integrator(method, integ, status, message)
    if (status /= SD_OK) then
      y_out = 0
      return
    end if
    call integrate_with(integ, sys, t0, y0, t_out, y_out, options, stats, status, message)
  end subroutine integrate
end module sloshdyn_integrator
