!> The Dormand-Prince 5(4) pair of Hairer's DOPRI5 (Hairer, Norsett & Wanner, Solving Ordinary
!> Differential Equations I, 2nd ed., sec. II.5, and the published dopri5.f) as a method of the
!> integrator family of sloshdyn_ode: 6 new right-hand sides per step (FSAL: the 7th stage, f at
!> the new point, is the next step's first), the local error estimate of the 4th-order embedded
!> solution (RMS norm), and Shampine's 4th-order continuous extension (CONTD5), so output times
!> never shorten a step. Step control defaults: fac1 = 0.2, fac2 = 10, beta = 0.04.
module sloshdyn_dopri5
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use sloshdyn_kinds, only: wp
  use sloshdyn_ode, only: rk_integrator, method_properties, rms_error_norm, &
                          dense_from_state
  implicit none
  private
  public :: dopri5_integrator

  type, extends(rk_integrator) :: dopri5_integrator
    real(wp), allocatable :: y_err(:)   !< local error estimate of the last trial step
  contains
    procedure :: stage => dopri5_stage
    procedure :: trial_error => dopri5_trial_error
    procedure :: finish_stages => dopri5_finish_stages
    procedure :: store_dense => dopri5_store_dense
    procedure :: dense => dopri5_dense
    procedure :: properties => dopri5_properties
    procedure :: allocate_extra => dopri5_allocate
  end type dopri5_integrator

  ! Dormand-Prince 5(4) tableau, as in dopri5.f (HNW I, sec. II.5)
  real(wp), parameter :: c2 = 1.0_wp/5, c3 = 3.0_wp/10, c4 = 4.0_wp/5, c5 = 8.0_wp/9
  real(wp), parameter :: a21 = 1.0_wp/5
  real(wp), parameter :: a31 = 3.0_wp/40, a32 = 9.0_wp/40
  real(wp), parameter :: a41 = 44.0_wp/45, a42 = -56.0_wp/15, a43 = 32.0_wp/9
  real(wp), parameter :: a51 = 19372.0_wp/6561, a52 = -25360.0_wp/2187, &
                         a53 = 64448.0_wp/6561, a54 = -212.0_wp/729
  real(wp), parameter :: a61 = 9017.0_wp/3168, a62 = -355.0_wp/33, a63 = 46732.0_wp/5247, &
                         a64 = 49.0_wp/176, a65 = -5103.0_wp/18656
  ! 5th-order weights; the 7th stage is evaluated at the new point (FSAL)
  real(wp), parameter :: a71 = 35.0_wp/384, a73 = 500.0_wp/1113, a74 = 125.0_wp/192, &
                         a75 = -2187.0_wp/6784, a76 = 11.0_wp/84
  ! 5th- minus 4th-order weights: the local error estimate
  real(wp), parameter :: e1 = 71.0_wp/57600, e3 = -71.0_wp/16695, e4 = 71.0_wp/1920, &
                         e5 = -17253.0_wp/339200, e6 = 22.0_wp/525, e7 = -1.0_wp/40
  ! Shampine's dense output coefficients d1..d7 of dopri5.f (d2 = 0), for rcont5
  real(wp), parameter :: d1 = -12715105075.0_wp/11282082432.0_wp, &
                         d3 = 87487479700.0_wp/32700410799.0_wp, &
                         d4 = -10690763975.0_wp/1880347072.0_wp, &
                         d5 = 701980252875.0_wp/199316789632.0_wp, &
                         d6 = -1453857185.0_wp/822651844.0_wp, &
                         d7 = 69997945.0_wp/29380423.0_wp

contains

  pure function dopri5_properties(self) result(info)
    class(dopri5_integrator), intent(in) :: self
    type(method_properties) :: info
    info = method_properties(name='dopri5', order=5, stages=7, trial_stages=6, &
                             dense_columns=5, &
                             expo_base=0.2_wp, beta_factor=0.75_wp, fac1=0.2_wp, fac2=10.0_wp, &
                             beta=0.04_wp)
  end function dopri5_properties

  pure subroutine dopri5_allocate(self, n)
    class(dopri5_integrator), intent(inout) :: self
    integer, intent(in) :: n
    allocate (self%y_err(n))
  end subroutine dopri5_allocate

  !> Stage s of a step (see sloshdyn_ode's method_stage): s = 1..5 are k2..k6, s = 6 is
  !> k7 = f(t_new, y_new) with the 5th-order y_new (part of the trial: the error estimate uses
  !> it, and it is the next step's k1).
  pure subroutine dopri5_stage(self, s, h, t_new, t_s, col)
    class(dopri5_integrator), intent(inout) :: self
    integer, intent(in) :: s
    real(wp), intent(in) :: h, t_new
    real(wp), intent(out) :: t_s
    integer, intent(out) :: col
    real(wp), parameter :: nodes(2:7) = [c2, c3, c4, c5, 1.0_wp, 1.0_wp]
    col = s + 1
    t_s = self%t + nodes(col)*h
    if (col >= 6) t_s = t_new
    call stage_input(size(self%y), col, h, self%y, self%k, self%y_stage, self%y_new)
  end subroutine dopri5_stage

  !> The input of stage col on explicit-shape arrays (the family's rule, sloshdyn_ode); for
  !> col = 7 it is y_new.
  pure subroutine stage_input(n, col, h, y, k, ys, yn)
    integer, intent(in) :: n, col
    real(wp), intent(in) :: h, y(n), k(n, 7)
    real(wp), intent(out) :: ys(n)
    real(wp), intent(inout) :: yn(n)

    select case (col)
    case (2)
      ys = y + h*a21*k(:, 1)
    case (3)
      ys = y + h*(a31*k(:, 1) + a32*k(:, 2))
    case (4)
      ys = y + h*(a41*k(:, 1) + a42*k(:, 2) + a43*k(:, 3))
    case (5)
      ys = y + h*(a51*k(:, 1) + a52*k(:, 2) + a53*k(:, 3) + a54*k(:, 4))
    case (6)
      ys = y + h*(a61*k(:, 1) + a62*k(:, 2) + a63*k(:, 3) + a64*k(:, 4) + a65*k(:, 5))
    case default
      yn = y + h*(a71*k(:, 1) + a73*k(:, 3) + a74*k(:, 4) + a75*k(:, 5) + a76*k(:, 6))
      ys = yn
    end select
  end subroutine stage_input

  !> After the trial stages (k7 included): the error estimate y_err and its RMS norm.
  pure subroutine dopri5_trial_error(self, h, err, finite)
    class(dopri5_integrator), intent(inout) :: self
    real(wp), intent(in) :: h
    real(wp), intent(out) :: err
    logical, intent(out) :: finite

    associate (k => self%k)
      self%y_err = h*(e1*k(:, 1) + e3*k(:, 3) + e4*k(:, 4) + e5*k(:, 5) + e6*k(:, 6) + &
                      e7*k(:, 7))
      finite = all(ieee_is_finite(self%y_new)) .and. all(ieee_is_finite(k(:, 7))) .and. &
               all(ieee_is_finite(self%y_err))
    end associate
    err = 0
    if (finite) err = rms_error_norm(self%y_err, self%y, self%y_new, self%atol, self%opt%rtol)
  end subroutine dopri5_trial_error

  !> Nothing more to evaluate: k7 is part of the trial step.
  pure integer function dopri5_finish_stages(self) result(n)
    class(dopri5_integrator), intent(in) :: self
    n = 0
  end function dopri5_finish_stages

  !> The dense output coefficients (rcont1..rcont5 of dopri5.f) of an accepted step, with dense
  !> output (init's dense_output); k7 becomes the next k1.
  pure subroutine dopri5_store_dense(self, h)
    class(dopri5_integrator), intent(inout) :: self
    real(wp), intent(in) :: h
    associate (y => self%y, k => self%k, cont => self%cont)
      if (self%dense_output) then
        cont(:, 1) = y
        cont(:, 2) = self%y_new - y
        cont(:, 3) = h*k(:, 1) - cont(:, 2)
        cont(:, 4) = cont(:, 2) - h*k(:, 7) - cont(:, 3)
        cont(:, 5) = h*(d1*k(:, 1) + d3*k(:, 3) + d4*k(:, 4) + d5*k(:, 5) + d6*k(:, 6) + &
                        d7*k(:, 7))
      end if
      k(:, 1) = k(:, 7)
    end associate
  end subroutine dopri5_store_dense

  !> Value at t of the continuous extension over the last accepted step [t_old, t] (CONTD5 of
  !> dopri5.f, 4th order). Outside that step it extrapolates; before any step it returns y.
  !> Without dense output (init's dense_output = .false.) it returns y at t = integ%t and NaN at
  !> any other time, as DOP853 and Vern9.
  pure subroutine dopri5_dense(self, t, y)
    class(dopri5_integrator), intent(in) :: self
    real(wp), intent(in) :: t
    real(wp), intent(out) :: y(:)
    real(wp) :: s, s1
    logical :: done

    call dense_from_state(self, t, y, done)
    if (done) return
    s = (t - self%t_old)/self%h_done
    s1 = 1 - s
    y = self%cont(:, 1) + s*(self%cont(:, 2) + s1*(self%cont(:, 3) + &
        s*(self%cont(:, 4) + s1*self%cont(:, 5))))
  end subroutine dopri5_dense
end module sloshdyn_dopri5
