!> The tank's equations of motion (sloshdyn_motion) as a system for the numerics layer, once for
!> every analysis: an ode_system for the integrators (simulation, steady states) and a
!> periodic_problem for shooting, continuation of periodic orbits and Lyapunov exponents, with
!> T = the forcing period and lambda = rho or A (PARAMETER_RHO, PARAMETER_A).
module sloshdyn_system
  use sloshdyn_kinds, only: wp, pi
  use sloshdyn_model, only: model_t
  use sloshdyn_motion, only: equations_of_motion, motion_jacobian, excitation_direction, &
                             equations_of_motion_block
  use sloshdyn_excitation, only: forcing_period, acceleration_sensitivity, PARAMETER_RHO, &
                                 PARAMETER_A
  use sloshdyn_shooting, only: periodic_problem
  use sloshdyn_ensemble, only: ensemble_system
  implicit none
  private
  public :: tank_system, tank_ensemble

  type, extends(periodic_problem) :: tank_system
    type(model_t) :: model
    integer :: varied = PARAMETER_RHO   !< lambda of continuations: PARAMETER_RHO or PARAMETER_A
  contains
    procedure :: rhs => tank_rhs
    procedure :: jacobian => tank_jacobian
    procedure :: period => tank_period
    procedure :: parameter_derivative => tank_parameter_derivative
    procedure :: set_parameter => tank_set_parameter
    procedure :: parameter => tank_parameter
    procedure :: period_derivative => tank_period_derivative
    procedure :: state_size => tank_state_size
  end type tank_system

  !> Many tanks, one model per member, as an ensemble_system (sloshdyn_ensemble): column c is
  !> tank_rhs of member members(c), the same arithmetic, so ensembles reproduce single runs.
  type, extends(ensemble_system) :: tank_ensemble
    type(model_t), allocatable :: models(:)
  contains
    procedure :: rhs_block => tank_rhs_block
  end type tank_ensemble

contains

  subroutine tank_rhs_block(self, members, t, y, dydt)
    class(tank_ensemble), intent(in) :: self
    integer, intent(in) :: members(:)
    real(wp), intent(in) :: t(:), y(:, :)
    real(wp), intent(out) :: dydt(:, :)
    call equations_of_motion_block(self%models, members, t, y, dydt)
  end subroutine tank_rhs_block

  subroutine tank_rhs(self, t, y, dydt)
    class(tank_system), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: dydt(:)
    call equations_of_motion(self%model, t, y, dydt)
  end subroutine tank_rhs

  subroutine tank_jacobian(self, t, y, jac)
    class(tank_system), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: jac(:, :)
    call motion_jacobian(self%model, t, y, jac)
  end subroutine tank_jacobian

  !> T = 2 pi/rho (+Infinity without a frequency: the input checks report it).
  function tank_period(self) result(v)
    class(tank_system), intent(in) :: self
    real(wp) :: v
    v = forcing_period(self%model%excitation)
  end function tank_period

  !> f is affine in X'' with direction e (excitation_direction), so df/dlambda = e dX''/dlambda.
  subroutine tank_parameter_derivative(self, t, y, df)
    class(tank_system), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: df(:)
    real(wp) :: e(4)
    call excitation_direction(self%model, y, e)
    df = e*acceleration_sensitivity(self%model%excitation, self%varied, t)
  end subroutine tank_parameter_derivative

  subroutine tank_set_parameter(self, lambda)
    class(tank_system), intent(inout) :: self
    real(wp), intent(in) :: lambda
    if (self%varied == PARAMETER_A) then
      self%model%excitation%A = lambda
    else
      self%model%excitation%rho = lambda
    end if
  end subroutine tank_set_parameter

  function tank_parameter(self) result(v)
    class(tank_system), intent(in) :: self
    real(wp) :: v
    v = merge(self%model%excitation%A, self%model%excitation%rho, &
                  self%varied == PARAMETER_A)
  end function tank_parameter

  !> dT/dlambda: -2 pi/rho^2 in rho, 0 in A.
  function tank_period_derivative(self) result(v)
    class(tank_system), intent(in) :: self
    real(wp) :: v
    v = merge(0.0_wp, -2*pi/self%model%excitation%rho**2, self%varied == PARAMETER_A)
  end function tank_period_derivative

  integer function tank_state_size(self)
    class(tank_system), intent(in) :: self
    tank_state_size = 4
  end function tank_state_size
end module sloshdyn_system
