!> Test problems with closed-form periodic orbits and Floquet multipliers.
module periodic_test_systems
  use sloshdyn_kinds, only: wp, pi
  use sloshdyn_shooting, only: periodic_problem
  implicit none
  private
  public :: linear_oscillator, rotating_frame, ROT_LINEAR, ROT_FOLD, ROT_PITCHFORK, ROT_FLIP

  !> x'' + 2 z w x' + w^2 x = F cos(W t), lambda = W. Steady state a cos(W t - phi) with
  !> a = F/sqrt((w^2 - W^2)^2 + (2 z w W)^2), tan phi = 2 z w W/(w^2 - W^2); multipliers
  !> exp(lambda_i T), lambda_i = -z w +- i w sqrt(1 - z^2), T = 2 pi/W.
  type, extends(periodic_problem) :: linear_oscillator
    real(wp) :: w = 1, z = 0.05_wp, f = 1, forcing_frequency = 1.3_wp
  contains
    procedure :: rhs => oscillator_rhs
    procedure :: jacobian => oscillator_jacobian
    procedure :: period => oscillator_period
    procedure :: parameter_derivative => oscillator_parameter_derivative
    procedure :: set_parameter => oscillator_set_parameter
    procedure :: parameter => oscillator_parameter
    procedure :: period_derivative => oscillator_period_derivative
  end type linear_oscillator

  !> y' = omega J y + R(omega t) G(R(omega t)^T y), J = [0 -1; 1 0], R the rotation: y = R z
  !> with z' = G(z) autonomous, so every equilibrium z* of G is a periodic orbit through y0 = z*
  !> and the monodromy over T = turn pi/omega is R(turn pi) exp(DG(z*) T).
  !>  ROT_LINEAR:    G = (B - omega J) z, B = diag(p1 + q1 lambda, p2 + q2 lambda), turn = 1:
  !>                 y' = R B R^T y, M = -exp(C T), C = [b1 omega; -omega b2], trivial orbit.
  !>  ROT_FOLD:      G = (lambda + z1 - z1^3/3, -z2), turn = 2: folds at lambda = +-2/3,
  !>                 z1 = -+1; M = diag(exp((1 - z1^2) T), exp(-T)).
  !>  ROT_PITCHFORK: G = (lambda z1 - z1^3, -z2), turn = 2: the trivial orbit has a branch
  !>                 point at lambda = 0 (multiplier exp(lambda T) crosses +1).
  !>  ROT_FLIP:      the same G with turn = 1: R(pi) = -I, so the trivial orbit's multiplier
  !>                 -exp(lambda T) crosses -1 at lambda = 0, a period doubling; the doubled
  !>                 orbits (period 2T) are y = R(omega t) z*, z* = (+-sqrt(lambda), 0).
  type, extends(periodic_problem) :: rotating_frame
    integer :: kind = 1
    real(wp) :: omega = 1, lambda = 0
    real(wp) :: p1 = 0, p2 = 0, q1 = 1, q2 = 1
  contains
    procedure :: rhs => rotating_rhs
    procedure :: jacobian => rotating_jacobian
    procedure :: period => rotating_period
    procedure :: parameter_derivative => rotating_parameter_derivative
    procedure :: set_parameter => rotating_set_parameter
    procedure :: parameter => rotating_parameter
    procedure :: period_derivative => rotating_period_derivative
  end type rotating_frame

  integer, parameter :: ROT_LINEAR = 1, ROT_FOLD = 2, ROT_PITCHFORK = 3, ROT_FLIP = 4

contains

  subroutine oscillator_rhs(self, t, y, dydt)
    class(linear_oscillator), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: dydt(:)
    dydt(1) = y(2)
    dydt(2) = self%f*cos(self%forcing_frequency*t) - 2*self%z*self%w*y(2) - self%w**2*y(1)
  end subroutine oscillator_rhs

  subroutine oscillator_jacobian(self, t, y, jac)
    class(linear_oscillator), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: jac(:, :)
    jac = reshape([0.0_wp, -self%w**2, 1.0_wp, -2*self%z*self%w], [2, 2])
  end subroutine oscillator_jacobian

  function oscillator_period(self) result(value)
    class(linear_oscillator), intent(in) :: self
    real(wp) :: value
    value = 2*pi/self%forcing_frequency
  end function oscillator_period

  subroutine oscillator_parameter_derivative(self, t, y, df)
    class(linear_oscillator), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: df(:)
    df = [0.0_wp, -self%f*t*sin(self%forcing_frequency*t)]
  end subroutine oscillator_parameter_derivative

  subroutine oscillator_set_parameter(self, lambda)
    class(linear_oscillator), intent(inout) :: self
    real(wp), intent(in) :: lambda
    self%forcing_frequency = lambda
  end subroutine oscillator_set_parameter

  function oscillator_parameter(self) result(value)
    class(linear_oscillator), intent(in) :: self
    real(wp) :: value
    value = self%forcing_frequency
  end function oscillator_parameter

  function oscillator_period_derivative(self) result(value)
    class(linear_oscillator), intent(in) :: self
    real(wp) :: value
    value = -2*pi/self%forcing_frequency**2
  end function oscillator_period_derivative

  pure function rotation(angle) result(r)
    real(wp), intent(in) :: angle
    real(wp) :: r(2, 2)
    r = reshape([cos(angle), sin(angle), -sin(angle), cos(angle)], [2, 2])
  end function rotation

  !> G(z) and DG(z) of the rotating-frame system.
  pure subroutine frame_field(self, z, g, dg, g_lambda)
    class(rotating_frame), intent(in) :: self
    real(wp), intent(in) :: z(2)
    real(wp), intent(out) :: g(2), dg(2, 2), g_lambda(2)
    select case (self%kind)
    case (ROT_LINEAR)
      dg = reshape([self%p1 + self%q1*self%lambda, -self%omega, &
                    self%omega, self%p2 + self%q2*self%lambda], [2, 2])
      g = matmul(dg, z)
      g_lambda = [self%q1*z(1), self%q2*z(2)]
    case (ROT_FOLD)
      g = [self%lambda + z(1) - z(1)**3/3, -z(2)]
      dg = reshape([1 - z(1)**2, 0.0_wp, 0.0_wp, -1.0_wp], [2, 2])
      g_lambda = [1.0_wp, 0.0_wp]
    case default
      g = [self%lambda*z(1) - z(1)**3, -z(2)]
      dg = reshape([self%lambda - 3*z(1)**2, 0.0_wp, 0.0_wp, -1.0_wp], [2, 2])
      g_lambda = [z(1), 0.0_wp]
    end select
  end subroutine frame_field

  subroutine rotating_rhs(self, t, y, dydt)
    class(rotating_frame), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: dydt(:)
    real(wp) :: r(2, 2), g(2), dg(2, 2), gl(2)
    r = rotation(self%omega*t)
    call frame_field(self, matmul(transpose(r), y(1:2)), g, dg, gl)
    dydt = self%omega*[-y(2), y(1)] + matmul(r, g)
  end subroutine rotating_rhs

  subroutine rotating_jacobian(self, t, y, jac)
    class(rotating_frame), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: jac(:, :)
    real(wp) :: r(2, 2), g(2), dg(2, 2), gl(2)
    r = rotation(self%omega*t)
    call frame_field(self, matmul(transpose(r), y(1:2)), g, dg, gl)
    jac = matmul(r, matmul(dg, transpose(r))) + &
          self%omega*reshape([0.0_wp, 1.0_wp, -1.0_wp, 0.0_wp], [2, 2])
  end subroutine rotating_jacobian

  function rotating_period(self) result(value)
    class(rotating_frame), intent(in) :: self
    real(wp) :: value
    value = merge(1, 2, self%kind == ROT_LINEAR .or. self%kind == ROT_FLIP)*pi/self%omega
  end function rotating_period

  subroutine rotating_parameter_derivative(self, t, y, df)
    class(rotating_frame), intent(in) :: self
    real(wp), intent(in) :: t, y(:)
    real(wp), intent(out) :: df(:)
    real(wp) :: r(2, 2), g(2), dg(2, 2), gl(2)
    r = rotation(self%omega*t)
    call frame_field(self, matmul(transpose(r), y(1:2)), g, dg, gl)
    df = matmul(r, gl)
  end subroutine rotating_parameter_derivative

  subroutine rotating_set_parameter(self, lambda)
    class(rotating_frame), intent(inout) :: self
    real(wp), intent(in) :: lambda
    self%lambda = lambda
  end subroutine rotating_set_parameter

  function rotating_parameter(self) result(value)
    class(rotating_frame), intent(in) :: self
    real(wp) :: value
    value = self%lambda
  end function rotating_parameter

  function rotating_period_derivative(self) result(value)
    class(rotating_frame), intent(in) :: self
    real(wp) :: value
    value = 0
  end function rotating_period_derivative
end module periodic_test_systems

!> Shooting, Floquet multipliers, continuation of periodic orbits and Lyapunov exponents against
!> closed forms (linear oscillator, rotating-frame systems), invariants of the undamped tank and
!> long direct simulations of the tank at the parameters of Fig 12.
program test_periodic
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, SD_SINGULAR, SD_CAPACITY
  use sloshdyn_text, only: num2str
  use sloshdyn_model, only: model_t, model_from_arrays
  use sloshdyn_linear, only: natural_frequencies, modal_matrix
  use sloshdyn_ode, only: ode_options, ode_stats
  use sloshdyn_integrator, only: integrate, METHOD_DOPRI5
  use sloshdyn_continuation, only: continuation_options
  use sloshdyn_excitation, only: PARAMETER_RHO, PARAMETER_A
  use sloshdyn_system, only: tank_system
  use sloshdyn_shooting, only: monodromy_matrix, shooting_newton, &
                               floquet_kind, fold_test, period_doubling_test, &
                               neimark_sacker_test, complex_pair_count, periodic_branch, &
                               switch_branch, FLOQUET_STABLE, FLOQUET_NEUTRAL, FLOQUET_UNSTABLE
  use sloshdyn_lyapunov, only: largest_lyapunov
  use sloshdyn_tables, only: SPECIAL_FOLD, SPECIAL_BRANCH_POINT, SPECIAL_PERIOD_DOUBLING, &
                             SPECIAL_NEIMARK_SACKER
  use periodic_test_systems, only: linear_oscillator, rotating_frame, ROT_LINEAR, ROT_FOLD, &
                                   ROT_PITCHFORK, ROT_FLIP
  use checks, only: check_close, check_true, finish
  implicit none

  integer :: clock_start, clock_rate

  call system_clock(clock_start, clock_rate)
  call test_test_functions()
  call test_linear_oscillator()
  call test_linear_continuation()
  call test_period_doubling()
  call test_neimark_sacker()
  call test_folds()
  call test_branch_point()
  call test_branch_switching(ROT_PITCHFORK)
  call test_branch_switching(ROT_FLIP)
  call test_undamped_tank()
  call test_fig12_orbit()
  call test_parameter_column()
  call test_fig12_resonance()
  call test_bad_input()
  call finish()

contains

  real(wp) function elapsed()
    integer :: now
    call system_clock(now)
    elapsed = real(now - clock_start, wp)/clock_rate
  end function elapsed

  function tight() result(opt)
    type(ode_options) :: opt
    opt%rtol = 1.0e-10_wp
    opt%atol = 1.0e-12_wp
  end function tight

  !> The Fig 12 model (s1 = 1.5, mu1 = 0.5, kappa = 1.804897259, theta0 = pi/4, beta = 10,
  !> gamma = 0.001, delta = 0.1, n = 6, p = 2, A = 0.00075) at rho.
  function fig12_model(rho) result(model)
    real(wp), intent(in) :: rho
    type(model_t) :: model
    integer :: status
    character(len=message_len) :: message
    call model_from_arrays([1.5_wp, 0.5_wp, 1.804897259_wp, pi/4, 10.0_wp, 0.001_wp, 0.1_wp, &
                            0.00075_wp, rho, 0.0_wp], [6, 2], model, status, message)
  end function fig12_model

  !> The test functions on given multiplier sets: signs follow the crossings.
  subroutine test_test_functions()
    real(wp) :: re(4), im(4)
    re = [0.5_wp, 0.5_wp, -1.2_wp, 0.3_wp]
    im = [0.6_wp, -0.6_wp, 0.0_wp, 0.0_wp]
    call check_true('fold test det(M - I) > 0 with no real multiplier above 1', &
                    fold_test(re, im) > 0)
    call check_close('fold test = prod(mu - 1)', fold_test(re, im), &
                     ((0.5_wp - 1)**2 + 0.36_wp)*(-2.2_wp)*(-0.7_wp), 1.0e-14_wp)
    call check_close('period doubling test = prod(mu + 1)', period_doubling_test(re, im), &
                     (1.5_wp**2 + 0.36_wp)*(-0.2_wp)*1.3_wp, 1.0e-14_wp)
    call check_close('Neimark-Sacker test = |mu|^2 - 1 of the pair', neimark_sacker_test(re, im), &
                     0.61_wp - 1, 1.0e-14_wp)
    call check_true('one complex pair', complex_pair_count(re, im) == 1)
    call check_true('a multiplier at -1.2 is unstable', &
                    floquet_kind(re, im, 1.0e-9_wp) == FLOQUET_UNSTABLE)
    re(3) = -0.9_wp
    call check_true('all |mu| < 1 is stable', floquet_kind(re, im, 1.0e-9_wp) == FLOQUET_STABLE)
    re(3) = -1
    call check_true('|mu| = 1 is neutral', floquet_kind(re, im, 1.0e-9_wp) == FLOQUET_NEUTRAL)
  end subroutine test_test_functions

  !> Shooting for x'' + 2 z w x' + w^2 x = F cos(W t): the closed-form steady state, the
  !> multipliers exp(lambda_i T) and Liouville's det M = exp(-2 z w T).
  subroutine test_linear_oscillator()
    type(linear_oscillator) :: osc
    real(wp) :: y(2), m(2, 2), re(2), im(2), amplitude, phase, period, decay, damped, max_x
    integer :: iterations, status, i
    character(len=message_len) :: message

    osc = linear_oscillator(w=1.0_wp, z=0.05_wp, f=1.0_wp, forcing_frequency=1.3_wp)
    call shooting_newton(osc, [0.0_wp, 0.0_wp], 1, tight(), METHOD_DOPRI5, 1.0e-11_wp, 10, y, m, re, im, &
                         iterations, status, message, max_x)
    call check_true('linear oscillator: shooting converges: '//trim(message), status == SD_OK)
    call check_true('linear oscillator: a linear map converges in 2 Newton iterations ('// &
                    num2str(iterations)//')', iterations <= 2)
    associate (w => osc%w, z => osc%z, big_w => osc%forcing_frequency)
      amplitude = osc%f/sqrt((w**2 - big_w**2)**2 + (2*z*w*big_w)**2)
      phase = atan2(2*z*w*big_w, w**2 - big_w**2)
      period = 2*pi/big_w
      decay = -z*w
      damped = w*sqrt(1 - z**2)
      call check_close('linear oscillator: x(0) = a cos(phi)', y(1), amplitude*cos(phase), &
                       0.0_wp, 1.0e-8_wp)
      call check_close('linear oscillator: x''(0) = a W sin(phi)', y(2), &
                       amplitude*big_w*sin(phase), 0.0_wp, 1.0e-8_wp)
      ! located on the dense output, not sampled (64 samples could be low by 1 - cos(pi/64))
      call check_close('linear oscillator: max|x| over the orbit = a (1e-8)', max_x, amplitude, &
                       1.0e-8_wp)
      print '(a, 2(es24.16), a, 2(es24.16))', '  multipliers ', re(1), im(1), ' and ', re(2), im(2)
      do i = 1, 2
        call check_close('linear oscillator: Re mu = exp(-z w T) cos(w_d T)', re(i), &
                         exp(decay*period)*cos(damped*period), 0.0_wp, 1.0e-8_wp)
        call check_close('linear oscillator: Im mu = +-exp(-z w T) sin(w_d T)', abs(im(i)), &
                         exp(decay*period)*abs(sin(damped*period)), 0.0_wp, 1.0e-8_wp)
      end do
      call check_true('linear oscillator: a conjugate pair', im(1) == -im(2) .and. im(1) /= 0)
      call check_close('linear oscillator: det M = exp(-2 z w T) (Liouville)', &
                       m(1, 1)*m(2, 2) - m(1, 2)*m(2, 1), exp(2*decay*period), 1.0e-9_wp)
    end associate
    call check_true('linear oscillator: stable', floquet_kind(re, im, 1.0e-9_wp) == FLOQUET_STABLE)
  end subroutine test_linear_oscillator

  !> Continuation in the forcing frequency W through the resonance (the period changes with the
  !> parameter): every point on the closed-form response curve, multipliers exp(lambda_i T(W)).
  subroutine test_linear_continuation()
    integer, parameter :: capacity = 200
    type(linear_oscillator) :: osc
    type(continuation_options) :: opt
    real(wp) :: points(5, capacity), mult(4, capacity), special(5, 4), big_w, amplitude, &
                worst_amplitude, worst_mu, period
    integer :: n_points, n_special, status, j
    logical :: complete
    character(len=message_len) :: message

    osc = linear_oscillator(w=1.0_wp, z=0.05_wp, f=0.1_wp, forcing_frequency=0.8_wp)
    opt%ds = 0.02_wp
    opt%ds_max = 0.05_wp
    opt%max_points = capacity
    call periodic_branch(osc, [0.0_wp, 0.0_wp], 0.8_wp, 1.2_wp, opt, tight(), METHOD_DOPRI5, points, mult, &
                         n_points, special, n_special, complete, status, message)
    call check_true('oscillator branch: complete: '//trim(message), &
                    status == SD_OK .and. complete)
    call check_close('oscillator branch: ends at W = 1.2', points(1, max(n_points, 1)), &
                     1.2_wp, 0.0_wp, 1.0e-12_wp)
    call check_true('oscillator branch: no special points ('//num2str(n_special)//')', &
                    n_special == 0)
    worst_amplitude = 0
    worst_mu = 0
    do j = 1, n_points
      big_w = points(1, j)
      amplitude = osc%f/sqrt((1 - big_w**2)**2 + (2*osc%z*big_w)**2)
      worst_amplitude = max(worst_amplitude, &
                            abs(hypot(points(2, j), points(3, j)/big_w) - amplitude)/amplitude)
      period = 2*pi/big_w
      worst_mu = max(worst_mu, abs(hypot(mult(1, j), mult(3, j)) - exp(-osc%z*period)), &
                     abs(mult(1, j) - exp(-osc%z*period)*cos(sqrt(1 - osc%z**2)*period)))
    end do
    print '(a, i0, a, 2es10.2)', '  oscillator branch: ', n_points, &
      ' points; worst relative amplitude error, worst multiplier error ', worst_amplitude, worst_mu
    call check_true('oscillator branch: '//num2str(n_points)//' points through the resonance', &
                    n_points >= 10)
    call check_true('oscillator branch: every amplitude on the closed form (1e-8)', &
                    worst_amplitude <= 1.0e-8_wp)
    call check_true('oscillator branch: every multiplier exp(lambda T(W)) (1e-8)', &
                    worst_mu <= 1.0e-8_wp)
    call check_true('oscillator branch: all stable', all(points(5, 1:n_points) == 1))
  end subroutine test_linear_continuation

  !> ROT_LINEAR with b1,2 = -d +- lambda: M = -exp(C T), eig C = -d +- sqrt(lambda^2 - omega^2);
  !> a multiplier crosses -1 at lambda = sqrt(d^2 + omega^2).
  subroutine test_period_doubling()
    integer, parameter :: capacity = 100
    type(rotating_frame) :: sys
    type(continuation_options) :: opt
    real(wp) :: points(5, capacity), mult(4, capacity), special(5, 4), expected, lam, c1, c2
    integer :: n_points, n_special, status
    logical :: complete
    character(len=message_len) :: message

    sys = rotating_frame(kind=ROT_LINEAR, omega=1.0_wp, lambda=0.5_wp, p1=-0.1_wp, p2=-0.1_wp, &
                         q1=1.0_wp, q2=-1.0_wp)
    opt%ds = 0.05_wp
    opt%max_points = capacity
    call periodic_branch(sys, [0.0_wp, 0.0_wp], 0.5_wp, 1.5_wp, opt, tight(), METHOD_DOPRI5, points, mult, &
                         n_points, special, n_special, complete, status, message)
    call check_true('period doubling branch: complete: '//trim(message), &
                    status == SD_OK .and. complete)
    call check_true('period doubling branch: one special point ('//num2str(n_special)//')', &
                    n_special == 1)
    if (n_special < 1) return
    expected = sqrt(0.1_wp**2 + 1)
    print '(a, f18.14, a, f18.14)', '  period doubling at ', special(2, 1), ', closed form ', expected
    call check_true('period doubling branch: kind', nint(special(1, 1)) == SPECIAL_PERIOD_DOUBLING)
    call check_close('period doubling at lambda = sqrt(d^2 + omega^2)', special(2, 1), expected, &
                     0.0_wp, 1.0e-8_wp)
    ! at the end, lambda = 1.5: two real multipliers -exp((-d +- sqrt(lambda^2 - 1)) pi)
    lam = points(1, n_points)
    c1 = -exp((-0.1_wp + sqrt(lam**2 - 1))*pi)
    c2 = -exp((-0.1_wp - sqrt(lam**2 - 1))*pi)
    call check_close('period doubling branch: end multipliers closed form', &
                     minval(mult(1:2, n_points)), c1, 1.0e-8_wp)
    call check_close('period doubling branch: end multipliers closed form (2)', &
                     maxval(mult(1:2, n_points)), c2, 1.0e-8_wp)
    call check_true('period doubling branch: stable before, unstable after', &
                    points(5, 1) == 1 .and. points(5, n_points) == 0)
  end subroutine test_period_doubling

  !> ROT_LINEAR with b1,2 = lambda +- e: multipliers -exp((lambda +- i sqrt(omega^2 - e^2)) T),
  !> a complex pair crossing |mu| = 1 at lambda = 0.
  subroutine test_neimark_sacker()
    integer, parameter :: capacity = 100
    type(rotating_frame) :: sys
    type(continuation_options) :: opt
    real(wp) :: points(5, capacity), mult(4, capacity), special(5, 4)
    integer :: n_points, n_special, status
    logical :: complete
    character(len=message_len) :: message

    sys = rotating_frame(kind=ROT_LINEAR, omega=1.0_wp, lambda=-0.3_wp, p1=0.5_wp, p2=-0.5_wp, &
                         q1=1.0_wp, q2=1.0_wp)
    opt%ds = 0.05_wp
    opt%max_points = capacity
    call periodic_branch(sys, [0.0_wp, 0.0_wp], -0.3_wp, 0.3_wp, opt, tight(), METHOD_DOPRI5, points, mult, &
                         n_points, special, n_special, complete, status, message)
    call check_true('Neimark-Sacker branch: complete: '//trim(message), &
                    status == SD_OK .and. complete)
    call check_true('Neimark-Sacker branch: one special point ('//num2str(n_special)//')', &
                    n_special == 1)
    if (n_special < 1) return
    print '(a, es12.3)', '  Neimark-Sacker at ', special(2, 1)
    call check_true('Neimark-Sacker branch: kind', nint(special(1, 1)) == SPECIAL_NEIMARK_SACKER)
    call check_close('Neimark-Sacker at lambda = 0', special(2, 1), 0.0_wp, 0.0_wp, 1.0e-8_wp)
    call check_close('Neimark-Sacker branch: |mu| = exp(lambda pi) at the end', &
                     hypot(mult(1, n_points), mult(3, n_points)), exp(0.3_wp*pi), 1.0e-8_wp)
    call check_close('Neimark-Sacker branch: arg mu = pi +- sqrt(1 - e^2) pi', &
                     abs(atan2(mult(3, n_points), mult(1, n_points))), &
                     pi - sqrt(1 - 0.25_wp)*pi, 1.0e-8_wp)
  end subroutine test_neimark_sacker

  !> ROT_FOLD: the S-shaped branch lambda = z1^3/3 - z1 turns at lambda = 2/3 (z1 = -1) and
  !> lambda = -2/3 (z1 = 1); multipliers exp((1 - z1^2) 2 pi), exp(-2 pi).
  subroutine test_folds()
    integer, parameter :: capacity = 300
    type(rotating_frame) :: sys
    type(continuation_options) :: opt
    real(wp) :: points(5, capacity), mult(4, capacity), special(5, 4), worst, z1, expected(2)
    integer :: n_points, n_special, status, j
    logical :: unstable_ok
    logical :: complete
    character(len=message_len) :: message

    sys = rotating_frame(kind=ROT_FOLD, omega=1.0_wp, lambda=-1.0_wp)
    opt%ds = 0.05_wp
    opt%ds_max = 0.1_wp
    opt%max_points = capacity
    call periodic_branch(sys, [-2.1_wp, 0.0_wp], -1.0_wp, 1.0_wp, opt, tight(), METHOD_DOPRI5, points, mult, &
                         n_points, special, n_special, complete, status, message)
    call check_true('S branch: complete: '//trim(message), status == SD_OK .and. complete)
    call check_true('S branch: two special points ('//num2str(n_special)//')', n_special == 2)
    call check_close('S branch: ends at lambda = 1', points(1, max(n_points, 1)), 1.0_wp, &
                     0.0_wp, 1.0e-12_wp)
    worst = 0
    unstable_ok = .true.
    do j = 1, n_points
      z1 = points(2, j)
      worst = max(worst, abs(z1**3/3 - z1 - points(1, j)) + abs(points(3, j)))
      ! multipliers {exp((1 - z1^2) T), exp(-T)}, relative
      expected = [exp((1 - z1**2)*2*pi), exp(-2*pi)]
      worst = max(worst, abs(maxval(mult(1:2, j)) - maxval(expected))/maxval(expected), &
                  abs(minval(mult(1:2, j)) - minval(expected))/minval(expected), &
                  maxval(abs(mult(3:4, j))))
      ! stable exactly where |z1| > 1 (away from the folds, where mu = 1)
      if (abs(abs(z1) - 1) > 0.05_wp) unstable_ok = unstable_ok .and. &
        ((points(5, j) == 1) .eqv. (abs(z1) > 1))
    end do
    call check_true('S branch: stable exactly where |z1| > 1', unstable_ok)
    call check_true('S branch: points and multipliers on the closed form (1e-8): '// &
                    num2str(worst), worst <= 1.0e-8_wp)
    if (n_special < 2) return
    print '(a, 2(f18.14, a, f18.14, a))', '  folds at lambda = ', special(2, 1), ' (z1 = ', &
      special(3, 1), '), ', special(2, 2), ' (z1 = ', special(3, 2), ')'
    call check_true('S branch: both are folds', all(nint(special(1, 1:2)) == SPECIAL_FOLD))
    call check_close('S branch: fold at lambda = 2/3', special(2, 1), 2.0_wp/3, 0.0_wp, 1.0e-9_wp)
    call check_close('S branch: ... with z1 = -1', special(3, 1), -1.0_wp, 0.0_wp, 1.0e-5_wp)
    call check_close('S branch: fold at lambda = -2/3', special(2, 2), -2.0_wp/3, 0.0_wp, 1.0e-9_wp)
    call check_close('S branch: ... with z1 = 1', special(3, 2), 1.0_wp, 0.0_wp, 1.0e-5_wp)
  end subroutine test_folds

  !> ROT_PITCHFORK: the trivial orbit loses stability at lambda = 0, where the symmetric pair
  !> z1 = +-sqrt(lambda) branches off; the continuation passes straight through.
  subroutine test_branch_point()
    integer, parameter :: capacity = 100
    type(rotating_frame) :: sys
    type(continuation_options) :: opt
    real(wp) :: points(5, capacity), mult(4, capacity), special(5, 4)
    integer :: n_points, n_special, status
    logical :: complete
    character(len=message_len) :: message

    sys = rotating_frame(kind=ROT_PITCHFORK, omega=1.0_wp, lambda=-0.5_wp)
    opt%ds = 0.07_wp
    opt%max_points = capacity
    call periodic_branch(sys, [0.0_wp, 0.0_wp], -0.5_wp, 0.5_wp, opt, tight(), METHOD_DOPRI5, points, mult, &
                         n_points, special, n_special, complete, status, message)
    call check_true('pitchfork branch: complete: '//trim(message), status == SD_OK .and. complete)
    call check_true('pitchfork branch: one special point ('//num2str(n_special)//')', &
                    n_special == 1)
    call check_true('pitchfork branch: stays on the trivial orbit', &
                    all(abs(points(2:3, 1:n_points)) <= 1.0e-12_wp))
    if (n_special < 1) return
    print '(a, es12.3)', '  branch point at ', special(2, 1)
    call check_true('pitchfork branch: kind', nint(special(1, 1)) == SPECIAL_BRANCH_POINT)
    call check_close('pitchfork branch: at lambda = 0', special(2, 1), 0.0_wp, 0.0_wp, 1.0e-8_wp)
  end subroutine test_branch_point

  !> Switching at the branch point of ROT_PITCHFORK and the period doubling of ROT_FLIP (both at
  !> lambda = 0 on the trivial orbit): the new branch is z* = (+-sqrt(lambda), 0), y0 = z*
  !> (R(2 pi) = I), of period T (pitchfork) or 2T (flip), with multipliers exp(-2 lambda t_k) and
  !> exp(-t_k) over its period t_k = 2 pi/omega (DG(z*) = diag(-2 lambda, -1)).
  subroutine test_branch_switching(kind)
    integer, intent(in) :: kind
    integer, parameter :: capacity = 100
    type(rotating_frame) :: sys
    type(continuation_options) :: opt
    real(wp) :: points(5, capacity), mult(4, capacity), special(5, 4), &
                new_points(5, capacity), new_mult(4, capacity), new_special(5, 4)
    integer :: n_points, n_special, n_new, n_new_special, k_new, status, j, expected
    logical :: complete
    character(len=message_len) :: message
    character(len=:), allocatable :: name

    name = merge('switching at the pitchfork: ', 'switching at the flip:      ', &
                 kind == ROT_PITCHFORK)
    expected = merge(SPECIAL_BRANCH_POINT, SPECIAL_PERIOD_DOUBLING, kind == ROT_PITCHFORK)
    sys = rotating_frame(kind=kind, omega=1.0_wp, lambda=-0.5_wp)
    opt%ds = 0.07_wp
    opt%max_points = capacity
    call periodic_branch(sys, [0.0_wp, 0.0_wp], -0.5_wp, 0.5_wp, opt, tight(), METHOD_DOPRI5, &
                         points, mult, n_points, special, n_special, complete, status, message)
    call check_true(name//'the special point at lambda = 0: '//trim(message), &
                    status == SD_OK .and. n_special == 1)
    if (n_special /= 1) return
    call check_true(name//'its kind', nint(special(1, 1)) == expected)
    call sys%set_parameter(special(2, 1))
    opt%ds = 0.02_wp
    call switch_branch(sys, nint(special(1, 1)), special(3:4, 1), 1, -0.5_wp, 0.5_wp, opt, &
                       tight(), METHOD_DOPRI5, new_points, new_mult, n_new, new_special, &
                       n_new_special, complete, k_new, status, message)
    call check_true(name//'the new branch is complete: '//trim(message), &
                    status == SD_OK .and. complete .and. n_new > 3)
    call check_true(name//'of period '//num2str(k_new)//' T', &
                    k_new == merge(1, 2, kind == ROT_PITCHFORK))
    call check_true(name//'it reaches lambda = 0.5', abs(new_points(1, n_new) - 0.5_wp) < 1.0e-12_wp)
    do j = 1, n_new
      associate (lambda => new_points(1, j), y => new_points(2:3, j))
        call check_close(name//'y1^2 = lambda', y(1)**2, lambda, 0.0_wp, 1.0e-8_wp)
        call check_close(name//'y2 = 0', y(2), 0.0_wp, 0.0_wp, 1.0e-8_wp)
        call check_close(name//'multiplier exp(-2 lambda 2 pi)', maxval(new_mult(1:2, j)), &
                         max(exp(-4*pi*lambda), exp(-2*pi)), 1.0e-6_wp, 1.0e-9_wp)
      end associate
    end do
  end subroutine test_branch_switching

  !> Undamped, unforced tank (gamma = delta = 0, A = 0): a conservative system, so a small
  !> linear-regime motion has multipliers on the unit circle, exp(+-i omega_j T) (eq 28), and
  !> an orbit on the first mode with T = 2 pi/omega1 has a multiplier 1 (and the Lyapunov
  !> exponent is about 0).
  subroutine test_undamped_tank()
    type(tank_system) :: tank
    type(model_t) :: model
    real(wp) :: omega1, omega2, period, y_end(4), m(4, 4), re(4), im(4), p(2, 2), p_inv(2, 2), &
                y0(4), exponent, history(20), phase, expected_phase
    integer :: status, i, j
    character(len=message_len) :: message

    model = fig12_model(0.7_wp)
    model%gamma = 0
    model%delta = 0
    model%excitation%A = 0
    model%a_coef(5) = 0
    model%b_coef(5) = 0
    call natural_frequencies(model, omega1, omega2, status, message)
    tank%model = model
    tank%varied = PARAMETER_RHO

    ! a fictitious period T = 2 pi/0.7, small generic start
    period = 2*pi/0.7_wp
    call monodromy_matrix(tank, 1.0e-4_wp*[1.0_wp, 0.3_wp, -0.5_wp, 0.2_wp], 1, tight(), METHOD_DOPRI5, y_end, &
                          m, status, message)
    call check_true('undamped tank: monodromy: '//trim(message), status == SD_OK)
    call eigenvalues_of(m, re, im)
    print '(a, 4(es12.3))', '  undamped tank, generic start: |mu| - 1 = ', hypot(re, im) - 1
    call check_true('undamped tank: all |mu| = 1 (1e-6)', all(abs(hypot(re, im) - 1) <= 1.0e-6_wp))
    call check_true('undamped tank: neutral', floquet_kind(re, im, 1.0e-6_wp) == FLOQUET_NEUTRAL)
    do j = 1, 2
      expected_phase = modulo(merge(omega1, omega2, j == 1)*period + pi, 2*pi) - pi
      phase = huge(1.0_wp)
      do i = 1, 4
        phase = min(phase, abs(abs(atan2(im(i), re(i))) - abs(expected_phase)))
      end do
      call check_true('undamped tank: a multiplier exp(i omega'//num2str(j)//' T), phase '// &
                      'error '//num2str(phase), phase <= 1.0e-6_wp)
    end do

    ! the first linear mode (eq 34, x = P u), T = 2 pi/omega1
    tank%model%excitation%rho = omega1
    call modal_matrix(tank%model, p, p_inv, status, message)
    y0 = 1.0e-4_wp*[p(1, 1), 0.0_wp, p(2, 1), 0.0_wp]/maxval(abs(p(:, 1)))
    call monodromy_matrix(tank, y0, 1, tight(), METHOD_DOPRI5, y_end, m, status, message)
    call eigenvalues_of(m, re, im)
    print '(a, 4(es12.3))', '  undamped tank, first mode: |mu - 1| = ', &
      abs(cmplx(re - 1, im, wp))
    call check_true('undamped tank: the mode returns after 2 pi/omega1 (1e-8 of 1e-4)', &
                    maxval(abs(y_end - y0)) <= 1.0e-8_wp)
    call check_true('undamped tank, first mode: a multiplier at 1 (1e-6)', &
                    minval(abs(cmplx(re - 1, im, wp))) <= 1.0e-6_wp)
    call check_true('undamped tank, first mode: all |mu| = 1 (1e-6)', &
                    all(abs(hypot(re, im) - 1) <= 1.0e-6_wp))

    call largest_lyapunov(tank, y0, 0, 200, 10, tight(), METHOD_DOPRI5, exponent, history, status, message)
    print '(a, es12.3)', '  undamped tank: largest Lyapunov exponent ', exponent
    call check_true('undamped tank: Lyapunov runs: '//trim(message), status == SD_OK)
    call check_true('undamped tank: Lyapunov exponent about 0 (|.| < 1e-4)', &
                    abs(exponent) < 1.0e-4_wp)
  end subroutine test_undamped_tank

  !> Fig 12 parameters at rho = 0.50: the period-1 orbit by shooting from rest agrees with a
  !> long direct simulation sampled at the same phases; it is stable; a short continuation
  !> to rho = 0.505 stays on stable orbits; the Lyapunov exponent is negative, the largest
  !> Floquet exponent log(max|mu|)/T.
  subroutine test_fig12_orbit()
    !> brute force: the direct simulation sampled this often per period (max low by at most
    !> 1 - cos(pi/brute) = 1.2e-8)
    integer, parameter :: transient = 4000, capacity = 100, brute = 20000
    type(tank_system) :: tank
    type(tank_system) :: direct
    type(ode_stats) :: stats
    type(continuation_options) :: opt
    real(wp) :: y(4), m(4, 4), re(4), im(4), max_x1, period, t_out(brute + 1), &
                y_out(4, brute + 1), direct_max, start, floquet_exponent, &
                exponent, history(100), points(7, capacity), mult(8, capacity), special(7, 4), &
                y_end(4), worst_residual
    integer :: iterations, status, j, n_points, n_special
    logical :: complete
    character(len=message_len) :: message

    tank%model = fig12_model(0.50_wp)
    tank%varied = PARAMETER_RHO
    period = 2*pi/0.50_wp
    start = elapsed()
    call shooting_newton(tank, [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], 1, tight(), METHOD_DOPRI5, 1.0e-10_wp, 20, y, &
                         m, re, im, iterations, status, message, max_x1)
    print '(a, i0, a, f8.3, a)', '  Fig 12, rho = 0.5: shooting from rest, ', iterations, &
      ' iterations, ', elapsed() - start, ' s'
    print '(a, 4es14.6)', '    y0 = ', y
    do j = 1, 4
      print '(a, 2es16.8, a, es16.8)', '    mu = ', re(j), im(j), '  |mu| = ', hypot(re(j), im(j))
    end do
    call check_true('Fig 12, rho = 0.5: shooting converges: '//trim(message), status == SD_OK)
    call check_true('Fig 12, rho = 0.5: all |mu| < 1', all(hypot(re, im) < 1))
    call check_true('Fig 12, rho = 0.5: stable', floquet_kind(re, im, 1.0e-9_wp) == FLOQUET_STABLE)

    start = elapsed()
    direct%model = tank%model
    t_out = [(transient*period + j*(period/brute), j = 0, brute)]
    call integrate(METHOD_DOPRI5, direct, 0.0_wp, [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], t_out, y_out, tight(), &
                        stats, status, message)
    direct_max = maxval(abs(y_out(1, 1:brute)))
    print '(a, i0, a, f8.3, a, 2es20.12)', '  direct simulation over ', transient, ' periods: ', &
      elapsed() - start, ' s; max|x1| shooting, direct ', max_x1, direct_max
    call check_true('Fig 12: direct simulation runs: '//trim(message), status == SD_OK)
    call check_close('Fig 12, rho = 0.5: max|x1| of the orbit = direct simulation (1e-6)', &
                     max_x1, direct_max, 1.0e-6_wp)
    call check_true('Fig 12, rho = 0.5: y0 = state of the direct simulation at phase 0 (1e-6)', &
                    maxval(abs(y - y_out(:, 1))) <= 1.0e-6_wp*maxval(abs(y)))

    start = elapsed()
    opt%ds = 0.002_wp
    opt%ds_max = 0.004_wp
    opt%max_points = capacity
    call periodic_branch(tank, y, 0.50_wp, 0.505_wp, opt, tight(), METHOD_DOPRI5, points, mult, n_points, &
                         special, n_special, complete, status, message)
    print '(a, i0, a, f8.3, a)', '  continuation rho = 0.5 .. 0.505: ', n_points, ' points, ', &
      elapsed() - start, ' s'
    call check_true('Fig 12 branch: complete: '//trim(message), status == SD_OK .and. complete)
    call check_true('Fig 12 branch: no special points ('//num2str(n_special)//')', n_special == 0)
    worst_residual = 0
    do j = 1, n_points
      tank%model%excitation%rho = points(1, j)
      call monodromy_matrix(tank, points(2:5, j), 1, tight(), METHOD_DOPRI5, y_end, m, status, message)
      worst_residual = max(worst_residual, maxval(abs(y_end - points(2:5, j))))
      print '(a, f10.6, a, es14.6, a, f12.8)', '    rho ', points(1, j), ' max|x1| ', &
        points(6, j), ' max|mu| ', maxval(hypot(mult(1:4, j), mult(5:8, j)))
    end do
    call check_true('Fig 12 branch: every |y(T) - y0| <= 1e-9: '//num2str(worst_residual), &
                    worst_residual <= 1.0e-9_wp)
    call check_true('Fig 12 branch: all multipliers inside the unit circle', &
                    all(hypot(mult(1:4, 1:n_points), mult(5:8, 1:n_points)) < 1))
    call check_true('Fig 12 branch: all stable', all(points(7, 1:n_points) == 1))

    start = elapsed()
    tank%model%excitation%rho = 0.50_wp
    floquet_exponent = log(maxval(hypot(re, im)))/period
    call largest_lyapunov(tank, y, 200, 1000, 10, tight(), METHOD_DOPRI5, exponent, history, status, message)
    print '(a, es14.6, a, es14.6, a, f8.3, a)', '  Fig 12 orbit: Lyapunov exponent ', exponent, &
      ', log(max|mu|)/T ', floquet_exponent, ' (', elapsed() - start, ' s)'
    call check_true('Fig 12 orbit: Lyapunov runs: '//trim(message), status == SD_OK)
    call check_true('Fig 12 orbit: Lyapunov exponent < 0', exponent < 0)
    call check_close('Fig 12 orbit: Lyapunov exponent = largest Floquet exponent (2 %)', &
                     exponent, floquet_exponent, 0.02_wp)
    call check_true('Fig 12 orbit: history ends on the exponent', history(100) == exponent)
    call check_close('Fig 12 orbit: the running estimate has settled (halfway within 10 %)', &
                     history(50), exponent, 0.1_wp)
  end subroutine test_fig12_orbit

  !> dF/dlambda of the shooting map (sensitivity equations plus the moving end time k T(rho))
  !> against central differences of y(k T) - y0, for lambda = rho and lambda = A.
  subroutine test_parameter_column()
    type(tank_system) :: tank
    real(wp), parameter :: y0(4) = [-1.75e-4_wp, 2.4e-3_wp, -7.9e-4_wp, 1.05e-2_wp]
    real(wp) :: column(4), y_plus(4), y_minus(4), m(4, 4), h, difference(4)
    integer :: status, which
    character(len=message_len) :: message

    do which = PARAMETER_RHO, PARAMETER_A
      tank%model = fig12_model(0.50_wp)
      tank%varied = which
      call monodromy_matrix(tank, y0, 2, tight(), METHOD_DOPRI5, y_plus, m, status, message, column)
      h = 1.0e-6_wp*tank%parameter()
      call tank%set_parameter(tank%parameter() + h)
      call monodromy_matrix(tank, y0, 2, tight(), METHOD_DOPRI5, y_plus, m, status, message)
      call tank%set_parameter(tank%parameter() - 2*h)
      call monodromy_matrix(tank, y0, 2, tight(), METHOD_DOPRI5, y_minus, m, status, message)
      difference = (y_plus - y_minus)/(2*h)
      print '(a, i0, a, 4es14.6)', '  dF/dlambda (', which, '): ', column
      call check_true('dF/d'//trim(merge('rho', 'A  ', which == PARAMETER_RHO))//' over 2 T = '// &
                      'central difference (1e-5 relative): '// &
                      num2str(maxval(abs(column - difference))/maxval(abs(column))), &
                      maxval(abs(column - difference)) <= 1.0e-5_wp*maxval(abs(column)))
    end do
  end subroutine test_parameter_column

  !> Through the resonance of Fig 12 (rho = 0.5 .. 0.52): the full equations show the two folds
  !> of the bent response curve and the two Neimark-Sacker points (a torus: the quasi-periodic
  !> motion of Fig 14) that the slow flow gives as Hopf points at rho = 0.50925 and 0.50998
  !> (paper, sec 4.1, Fig 13; equal to the asymptotic accuracy, here 1e-4).
  subroutine test_fig12_resonance()
    integer, parameter :: capacity = 400
    type(tank_system) :: tank
    type(continuation_options) :: opt
    real(wp) :: y(4), m(4, 4), re(4), im(4), points(7, capacity), mult(8, capacity), &
                special(7, 8), start
    integer :: iterations, status, n_points, n_special, j, kinds(8)
    logical :: complete
    character(len=message_len) :: message

    tank%model = fig12_model(0.50_wp)
    tank%varied = PARAMETER_RHO
    call shooting_newton(tank, [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], 1, tight(), METHOD_DOPRI5, 1.0e-10_wp, 20, y, &
                         m, re, im, iterations, status, message)
    opt%ds = 0.002_wp
    opt%ds_max = 0.01_wp
    opt%max_points = capacity
    start = elapsed()
    call periodic_branch(tank, y, 0.50_wp, 0.52_wp, opt, tight(), METHOD_DOPRI5, points, mult, n_points, &
                         special, n_special, complete, status, message)
    print '(a, i0, a, i0, a, f8.3, a)', '  Fig 12 resonance: ', n_points, ' points, ', n_special, &
      ' special points, ', elapsed() - start, ' s'
    do j = 1, n_special
      print '(a, i0, a, f12.8, a, es12.4)', '    kind ', nint(special(1, j)), ' rho ', &
        special(2, j), ' max|x1| ', special(7, j)
    end do
    call check_true('Fig 12 resonance: complete: '//trim(message), status == SD_OK .and. complete)
    call check_true('Fig 12 resonance: four special points', n_special == 4)
    if (n_special /= 4) return
    kinds(1:4) = nint(special(1, 1:4))
    call check_true('Fig 12 resonance: two folds, then two Neimark-Sacker points', &
                    all(kinds(1:4) == [SPECIAL_FOLD, SPECIAL_FOLD, SPECIAL_NEIMARK_SACKER, &
                                       SPECIAL_NEIMARK_SACKER]))
    call check_close('Fig 12 resonance: first Neimark-Sacker at the slow-flow Hopf rho = 0.50925', &
                     special(2, 3), 0.50925_wp, 0.0_wp, 1.0e-4_wp)
    call check_close('Fig 12 resonance: second Neimark-Sacker at the slow-flow Hopf rho = 0.50998', &
                     special(2, 4), 0.50998_wp, 0.0_wp, 1.0e-4_wp)
    call check_true('Fig 12 resonance: unstable between the Neimark-Sacker points', &
                    all(points(7, 1:n_points) == 0 .or. points(1, 1:n_points) < special(2, 3) &
                        .or. points(1, 1:n_points) > special(2, 4)))
  end subroutine test_fig12_resonance

  subroutine eigenvalues_of(m, re, im)
    use sloshdyn_lapack, only: eigenvalues
    real(wp), intent(in) :: m(:, :)
    real(wp), intent(out) :: re(:), im(:)
    integer :: status
    character(len=message_len) :: message
    call eigenvalues(m, re, im, status, message)
  end subroutine eigenvalues_of

  !> Each documented rule fails with a message naming the variable.
  subroutine test_bad_input()
    type(tank_system) :: tank
    type(linear_oscillator) :: osc
    type(continuation_options) :: opt
    type(ode_options) :: rk
    real(wp) :: y(4), m(4, 4), re(4), im(4), history(5), exponent, y2(2), m2(2, 2), re2(2), &
                im2(2), points(5, 3), mult(4, 3), special(5, 2)
    integer :: iterations, status, n_points, n_special
    logical :: complete
    character(len=message_len) :: message

    tank%model = fig12_model(0.5_wp)
    call shooting_newton(tank, [0.0_wp, 0.0_wp, 0.0_wp], 1, tight(), METHOD_DOPRI5, 1.0e-10_wp, 5, y(1:3), &
                         m(1:3, 1:3), re(1:3), im(1:3), iterations, status, message)
    call check_true('bad input: y0 of size 3 for the tank: '//trim(message), &
                    status == SD_BAD_INPUT .and. index(message, 'y0') > 0)
    call shooting_newton(tank, [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], 0, tight(), METHOD_DOPRI5, 1.0e-10_wp, 5, y, &
                         m, re, im, iterations, status, message)
    call check_true('bad input: k = 0: '//trim(message), &
                    status == SD_BAD_INPUT .and. index(message, 'k = 0') > 0)
    tank%model%excitation%rho = 0
    call shooting_newton(tank, [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], 1, tight(), METHOD_DOPRI5, 1.0e-10_wp, 5, y, &
                         m, re, im, iterations, status, message)
    call check_true('bad input: rho = 0 (no period): '//trim(message), &
                    status == SD_BAD_INPUT .and. index(message, 'T =') > 0)
    tank%model%excitation%rho = 0.5_wp
    call shooting_newton(tank, [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], 1, tight(), METHOD_DOPRI5, 0.0_wp, 5, y, &
                         m, re, im, iterations, status, message)
    call check_true('bad input: newton_tol = 0: '//trim(message), &
                    status == SD_BAD_INPUT .and. index(message, 'newton_tol') > 0)
    call largest_lyapunov(tank, [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], 0, 25, 10, tight(), METHOD_DOPRI5, exponent, &
                          history, status, message)
    call check_true('bad input: n_periods not a multiple of renormalise_every: '//trim(message), &
                    status == SD_BAD_INPUT .and. index(message, 'n_periods') > 0)
    call largest_lyapunov(tank, [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], 0, 60, 10, tight(), METHOD_DOPRI5, exponent, &
                          history, status, message)
    call check_true('bad input: history too short: '//trim(message), &
                    status == SD_BAD_INPUT .and. index(message, 'history') > 0)
    ! failures of a branch are reported, never a silent truncation
    osc = linear_oscillator(w=1.0_wp, z=0.05_wp, f=0.1_wp, forcing_frequency=0.8_wp)
    opt%max_points = 3
    opt%ds = 0.01_wp
    call periodic_branch(osc, [0.0_wp, 0.0_wp], 0.8_wp, 1.2_wp, opt, tight(), METHOD_DOPRI5, points, mult, &
                         n_points, special, n_special, complete, status, message)
    call check_true('branch cut by max_points: SD_CAPACITY, incomplete, 3 points: '// &
                    trim(message), status == SD_CAPACITY .and. .not. complete .and. n_points == 3)
    rk = tight()
    rk%max_steps = 5
    call periodic_branch(osc, [0.0_wp, 0.0_wp], 0.8_wp, 1.2_wp, opt, rk, METHOD_DOPRI5, points, mult, &
                         n_points, special, n_special, complete, status, message)
    call check_true('branch with a failing integrator: incomplete, the integrator''s message: '// &
                    trim(message), status /= SD_OK .and. .not. complete .and. &
                    index(message, 'max_steps') > 0)
    ! a free particle x'' = 0 has M = [1 T; 0 1] exactly: M - I is singular (multiplier +1)
    osc = linear_oscillator(w=0.0_wp, z=0.0_wp, f=0.0_wp, forcing_frequency=1.0_wp)
    call shooting_newton(osc, [1.0_wp, 0.0_wp], 1, tight(), METHOD_DOPRI5, 1.0e-10_wp, 5, y2, m2, re2, im2, &
                         iterations, status, message)
    call check_true('free particle: M - I singular is reported: '//trim(message), &
                    status == SD_SINGULAR .and. index(message, 'M - I') > 0)
  end subroutine test_bad_input
end program test_periodic
