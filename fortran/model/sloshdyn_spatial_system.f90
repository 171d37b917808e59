!> The spatial equations of motion (sloshdyn_spatial) as a system for the numerics layer, as
!> sloshdyn_system is for the planar ones: an ode_system for the integrators and a
!> periodic_problem for shooting and Floquet multipliers, T = the forcing period of the x
!> excitation and lambda = rho or A of the harmonic excitation (PARAMETER_RHO, PARAMETER_A).
module sloshdyn_spatial_system
  use sloshdyn_kinds, only: wp, pi
  use sloshdyn_spatial, only: spatial_model_t, spatial_equations, spatial_jacobian, &
                              spatial_excitation_direction, ground_sensitivity
  use sloshdyn_excitation, only: forcing_period, PARAMETER_RHO, PARAMETER_A
  use sloshdyn_shooting, only: periodic_problem
  implicit none
  private
  public :: spatial_tank_system

  type, extends(periodic_problem) :: spatial_tank_system
    type(spatial_model_t) :: model
    integer :: varied = PARAMETER_RHO   !< lambda: PARAMETER_RHO or PARAMETER_A
  contains
    procedure :: rhs => spatial_rhs
    procedure :: jacobian => spatial_system_jacobian
    procedure :: period => spatial_period
    procedure :: parameter_derivative => spatial_parameter_derivative
    procedure :: set_parameter => spatial_set_parameter
    procedure :: parameter => spatial_parameter
    procedure :: period_derivative => spatial_period_derivative
    procedure :: state_size => spatial_state_size
  end type spatial_tank_system

contains

  subroutine spatial_rhs(self, t, y, dydt)
    class(spatial_tank_system), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: dydt(:)
    call spatial_equations(self%model, t, y, dydt)
  end subroutine spatial_rhs

  subroutine spatial_system_jacobian(self, t, y, jac)
    class(spatial_tank_system), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: jac(:, :)
    call spatial_jacobian(self%model, t, y, jac)
  end subroutine spatial_system_jacobian

  function spatial_period(self) result(v)
    class(spatial_tank_system), intent(in) :: self
    real(wp) :: v
    v = forcing_period(self%model%planar%excitation)
  end function spatial_period

  !> f is affine in (X'', Y'') with directions e(:, 1), e(:, 2).
  subroutine spatial_parameter_derivative(self, t, y, df)
    class(spatial_tank_system), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: df(:)
    real(wp) :: e(8, 2)
    call spatial_excitation_direction(self%model, y, e)
    df = matmul(e, ground_sensitivity(self%model, self%varied, t))
  end subroutine spatial_parameter_derivative

  subroutine spatial_set_parameter(self, lambda)
    class(spatial_tank_system), intent(inout) :: self
    real(wp), intent(in) :: lambda
    if (self%varied == PARAMETER_A) then
      self%model%planar%excitation%A = lambda
    else
      self%model%planar%excitation%rho = lambda
    end if
  end subroutine spatial_set_parameter

  function spatial_parameter(self) result(v)
    class(spatial_tank_system), intent(in) :: self
    real(wp) :: v
    v = merge(self%model%planar%excitation%A, self%model%planar%excitation%rho, &
              self%varied == PARAMETER_A)
  end function spatial_parameter

  function spatial_period_derivative(self) result(v)
    class(spatial_tank_system), intent(in) :: self
    real(wp) :: v
    v = merge(0.0_wp, -2*pi/self%model%planar%excitation%rho**2, self%varied == PARAMETER_A)
  end function spatial_period_derivative

  integer function spatial_state_size(self)
    class(spatial_tank_system), intent(in) :: self
    spatial_state_size = 8
  end function spatial_state_size
end module sloshdyn_spatial_system
