!> The choice of integration method: every analysis that integrates takes a method code and
!> gets an integrator of the family (sloshdyn_ode) from here. 'auto', the default everywhere,
!> picks the pair that is fastest at the requested relative tolerance on the work-precision
!> ladder of benchmarks/run.py (see benchmarks/README.md): DOPRI5 for loose tolerances, DOP853
!> in between, Verner's 9(8) for tight ones.
module sloshdyn_integrator
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT
  use sloshdyn_text, only: num2str
  use sloshdyn_ode, only: ode_system, ode_options, ode_stats, rk_integrator, integrate_with, &
                          observed_quantities, peak_tracker
  use sloshdyn_dopri5, only: dopri5_integrator
  use sloshdyn_dop853, only: dop853_integrator
  use sloshdyn_vern9, only: vern9_integrator
  implicit none
  private
  public :: new_integrator, integrate, check_method, method_name, chosen_method
  public :: METHOD_DOPRI5, METHOD_DOP853, METHOD_VERN9, METHOD_AUTO, method_names

  integer, parameter :: METHOD_DOPRI5 = 0, METHOD_DOP853 = 1, METHOD_VERN9 = 2, METHOD_AUTO = 3
  !> Names by code (index = code + 1), as the namelist and Python spell them.
  character(len=6), parameter :: method_names(0:3) = &
    [character(len=6) :: 'rk45', 'dop853', 'vern9', 'auto']
  !> The crossovers of 'auto' (measured, benchmarks/README.md): DOP853 for rtol below the
  !> first, Verner 9(8) for rtol below the second.
  real(wp), parameter :: auto_dop853_below = 1.0e-3_wp, auto_vern9_below = 1.0e-10_wp

contains

  pure subroutine check_method(method, status, message)
    integer, intent(in) :: method
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    if (status /= SD_OK) return
    if (method < lbound(method_names, 1) .or. method > ubound(method_names, 1)) then
      status = SD_BAD_INPUT
      message = 'method = '//num2str(method)//' is not known: 0 = rk45 (Dormand-Prince 5(4)), '// &
                '1 = dop853 (Dormand-Prince 8(5,3)), 2 = vern9 (Verner 9(8)), 3 = auto (by rtol)'
    end if
  end subroutine check_method

  pure function method_name(method) result(name)
    integer, intent(in) :: method
    character(len=:), allocatable :: name
    name = trim(method_names(method))
  end function method_name

  !> The method that runs for the code method at relative tolerance rtol: method itself, or
  !> for METHOD_AUTO the pair fastest at that tolerance.
  pure integer function chosen_method(method, rtol) result(chosen)
    integer, intent(in) :: method
    real(wp), intent(in) :: rtol
    chosen = method
    if (method /= METHOD_AUTO) return
    if (rtol < auto_vern9_below) then
      chosen = METHOD_VERN9
    else if (rtol < auto_dop853_below) then
      chosen = METHOD_DOP853
    else
      chosen = METHOD_DOPRI5
    end if
  end function chosen_method

  !> An integrator of the given method (for METHOD_AUTO, the one chosen for rtol), ready for
  !> init.
  subroutine new_integrator(method, rtol, integ, status, message)
    integer, intent(in) :: method
    real(wp), intent(in) :: rtol
    class(rk_integrator), allocatable, intent(out) :: integ
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    status = SD_OK
    message = ''
    call check_method(method, status, message)
    if (status /= SD_OK) return
    select case (chosen_method(method, rtol))
    case (METHOD_DOP853)
      allocate (dop853_integrator :: integ)
    case (METHOD_VERN9)
      allocate (vern9_integrator :: integ)
    case default
      allocate (dopri5_integrator :: integ)
    end select
  end subroutine new_integrator

  !> y at every t_out by the chosen method (see integrate_with for failures and the optional
  !> peak tracking).
  subroutine integrate(method, sys, t0, y0, t_out, y_out, options, stats, status, message, &
                       observed, tracker)
    integer, intent(in) :: method
    class(ode_system), intent(in) :: sys
    real(wp), intent(in) :: t0, y0(:), t_out(:)
    real(wp), intent(out) :: y_out(:, :)
    type(ode_options), intent(in) :: options
    type(ode_stats), intent(out) :: stats
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    class(observed_quantities), intent(in), optional :: observed
    type(peak_tracker), intent(inout), optional :: tracker
    class(rk_integrator), allocatable :: integ
    call new_integrator(method, options%rtol, integ, status, message)
    if (status /= SD_OK) then
      y_out = 0
      return
    end if
    call integrate_with(integ, sys, t0, y0, t_out, y_out, options, stats, status, message, &
                        observed, tracker)
  end subroutine integrate
end module sloshdyn_integrator
