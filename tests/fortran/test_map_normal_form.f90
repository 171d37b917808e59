!> A flow with a Z2-symmetric pitchfork of its time-T map in closed form.
module pitchfork_test_flow
  use sloshdyn_kinds, only: wp
  use sloshdyn_shooting, only: periodic_problem
  implicit none
  private
  public :: mirror_flow

  !> x' = -x^3 + x z, z' = -z + k x^2 (the mirror x -> -x): the origin's time-T map has the
  !> multipliers 1 (along x, antisymmetric) and e^{-T} (along z, symmetric). Its centre
  !> manifold is the flow's, z = k x^2 + O(x^4), on which x' = (k - 1) x^3, so the map is
  !> x -> x + (k - 1) T x^3 + O(x^5): c = (k - 1) T, by the cancellation of the cubic term
  !> along z = 0 (the map's <p, C(q, q, q)>/6) against the slaved z (its <p, B(q, w)>/2).
  type, extends(periodic_problem) :: mirror_flow
    real(wp) :: k = 3, t_period = 2
  contains
    procedure :: rhs => mirror_rhs
    procedure :: jacobian => mirror_jacobian
    procedure :: period => mirror_period
    procedure :: parameter_derivative => mirror_parameter_derivative
    procedure :: set_parameter => mirror_set_parameter
    procedure :: parameter => mirror_parameter
    procedure :: period_derivative => mirror_period_derivative
  end type mirror_flow

contains

  subroutine mirror_rhs(self, t, y, dydt)
    class(mirror_flow), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: dydt(:)
    dydt = [-y(1)**3 + y(1)*y(2), -y(2) + self%k*y(1)**2]
  end subroutine mirror_rhs

  subroutine mirror_jacobian(self, t, y, jac)
    class(mirror_flow), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: jac(:, :)
    jac = reshape([-3*y(1)**2 + y(2), 2*self%k*y(1), y(1), -1.0_wp], [2, 2])
  end subroutine mirror_jacobian

  function mirror_period(self) result(value)
    class(mirror_flow), intent(in) :: self
    real(wp) :: value
    value = self%t_period
  end function mirror_period

  subroutine mirror_parameter_derivative(self, t, y, df)
    class(mirror_flow), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: df(:)
    df = [0.0_wp, y(1)**2]
  end subroutine mirror_parameter_derivative

  subroutine mirror_set_parameter(self, lambda)
    class(mirror_flow), intent(inout) :: self
    real(wp), intent(in) :: lambda
    self%k = lambda
  end subroutine mirror_set_parameter

  function mirror_parameter(self) result(value)
    class(mirror_flow), intent(in) :: self
    real(wp) :: value
    value = self%k
  end function mirror_parameter

  function mirror_period_derivative(self) result(value)
    class(mirror_flow), intent(in) :: self
    real(wp) :: value
    value = 0
  end function mirror_period_derivative
end module pitchfork_test_flow

!> sloshdyn_map_normal_form's cubic_coefficient at the multiplier +1 (a Z2-symmetric
!> pitchfork) against the closed form of pitchfork_test_flow, also with the monodromy matrix
!> passed in (the curve codes' path); bad input named.
program test_map_normal_form
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT
  use sloshdyn_text, only: num2str
  use sloshdyn_ode, only: ode_options
  use sloshdyn_integrator, only: METHOD_DOP853
  use sloshdyn_map_normal_form, only: cubic_coefficient
  use sloshdyn_shooting, only: monodromy_matrix
  use checks, only: check_close, check_true, finish
  use pitchfork_test_flow, only: mirror_flow
  implicit none
  type(ode_options) :: options
  real(wp) :: c, q(2), mu, terms, k, m(2, 2), y_end(2), c_given, q_given(2), mu_given, &
              terms_given
  real(wp), parameter :: k_values(3) = [3.0_wp, 0.5_wp, 1.0_wp]
  integer :: status, i
  character(len=message_len) :: message

  options%rtol = 1.0e-12_wp
  options%atol = 1.0e-14_wp
  do i = 1, 3
    k = k_values(i)
    call cubic_coefficient(mirror_flow(k=k, t_period=2.0_wp), [0.0_wp, 0.0_wp], 1, options, &
                           METHOD_DOP853, 1, c, q, mu, status, message, terms)
    call check_true('pitchfork k = '//num2str(k)//': status 0 ('// &
                    trim(message)//')', status == SD_OK)
    call check_close('pitchfork k = '//num2str(k)//': mu = 1', mu, 1.0_wp, &
                     1.0e-10_wp)
    call check_close('pitchfork k = '//num2str(k)//': q along x', abs(q(1)), &
                     1.0_wp, 1.0e-10_wp)
    ! c = (k - 1) T: supercritical (c < 0) for k < 1, subcritical for k > 1, and at k = 1 the
    ! two terms cancel (a degenerate pitchfork)
    call check_close('pitchfork k = '//num2str(k)//': c = (k - 1) T', c, &
                     (k - 1)*2, 1.0e-6_wp, 1.0e-6_wp*terms)
    call check_true('pitchfork k = '//num2str(k)//': terms of size >= |c|', &
                    terms >= abs(c) .and. terms > 1)
    ! M passed in, as monodromy_matrix gives it: the same integrations, so the same c to the bit
    call monodromy_matrix(mirror_flow(k=k, t_period=2.0_wp), [0.0_wp, 0.0_wp], 1, options, &
                          METHOD_DOP853, y_end, m, status, message)
    call check_close('pitchfork k = '//num2str(k)//': M = diag(1, e^-T)', &
                     maxval(abs(m - reshape([1.0_wp, 0.0_wp, 0.0_wp, exp(-2.0_wp)], [2, 2]))), &
                     0.0_wp, 0.0_wp, 1.0e-10_wp)
    call cubic_coefficient(mirror_flow(k=k, t_period=2.0_wp), [0.0_wp, 0.0_wp], 1, options, &
                           METHOD_DOP853, 1, c_given, q_given, mu_given, status, message, &
                           terms_given, m)
    call check_true('pitchfork k = '//num2str(k)//', M given: status 0 and c, q, mu, terms '// &
                    'equal to the bit ('//trim(message)//')', status == SD_OK .and. &
                    c_given == c .and. all(q_given == q) .and. mu_given == mu .and. &
                    terms_given == terms)
  end do

  ! the given M is the one used: with its multiplier along x moved to 0.5 there is none at +1
  m = reshape([0.5_wp, 0.0_wp, 0.0_wp, exp(-2.0_wp)], [2, 2])
  call cubic_coefficient(mirror_flow(), [0.0_wp, 0.0_wp], 1, options, METHOD_DOP853, 1, c, &
                         q, mu, status, message, terms, m)
  call check_true('a given M without a multiplier at +1 is refused ('//trim(message)//')', &
                  status == SD_BAD_INPUT .and. index(message, 'nearest +1') > 0 .and. mu < 0.9_wp)
  call cubic_coefficient(mirror_flow(), [0.0_wp, 0.0_wp], 1, options, METHOD_DOP853, 1, c, &
                         q, mu, status, message, terms, m(:, 1:1))
  call check_true('a given M of shape (2, 1) is named ('//trim(message)//')', &
                  status == SD_BAD_INPUT .and. index(message, 'monodromy has shape (2, 1)') > 0 &
                  .and. c /= c)

  call cubic_coefficient(mirror_flow(), [0.0_wp, 0.0_wp], 1, options, METHOD_DOP853, 2, c, &
                         q, mu, status, message, terms)
  call check_true('sigma = 2 is named ('//trim(message)//')', status == SD_BAD_INPUT .and. &
                  index(message, 'sigma = 2') > 0 .and. c /= c)
  ! at -1 there is no multiplier: e^{-2} and 1 are both far from it
  call cubic_coefficient(mirror_flow(), [0.0_wp, 0.0_wp], 1, options, METHOD_DOP853, -1, c, &
                         q, mu, status, message, terms)
  call check_true('no multiplier at -1 is named ('//trim(message)//')', &
                  status == SD_BAD_INPUT .and. index(message, 'nearest -1') > 0)
  call finish()
end program test_map_normal_form
