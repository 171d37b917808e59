!> The closed-form steady states of the slow flow (sloshdyn_slowflow's steady_states, which lets
!> frequency_response skip Newton scans) against an independent search: Newton from the grid of
!> starts that frequency_response uses, 6 x 6 per mode. Every state the grid finds must be among
!> the closed-form ones, and every closed-form state must solve the slow flow (the closed form
!> may find more: states the grid of starts misses). Cases: 3:1 resonance at the Fig 12 and
!> Fig 11 parameters in rho and in A, no internal resonance (also against eq 49's cubic), and
!> A = 0 (no forcing) and A = 1e-25, where the closed form does not apply.
program test_steady_states
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_model, only: model_t, model_from_arrays
  use sloshdyn_excitation, only: PARAMETER_RHO, PARAMETER_A
  use sloshdyn_slowflow, only: slow_flow, make_slow_flow, steady_states, nonresonant_amplitudes
  use sloshdyn_continuation, only: newton_options, newton_solve
  use sloshdyn_sort, only: sort_ascending
  use sloshdyn_text, only: num2str
  use checks, only: check_true, finish
  implicit none

  real(wp), parameter :: fig12_kappa = 1.804897259_wp, fig11_kappa = 1.807915943_wp
  type(slow_flow) :: flow
  real(wp), allocatable :: states(:, :)
  integer :: n_states, k, n_roots, status
  logical :: available
  real(wp) :: a1(3)
  character(len=message_len) :: message

  do k = 1, 3
    call compare('Fig 12, 3:1, rho at A = '//trim(num2str(0.0004_wp*k)), fig12_kappa, 0.001_wp, &
                 0.0004_wp*k, 0.51_wp, .true., PARAMETER_RHO, 0.49_wp, 0.53_wp)
  end do
  call compare('Fig 11, 3:1, rho at A = 0.0004', fig11_kappa, 0.0025_wp, 0.0004_wp, 0.51_wp, &
               .true., PARAMETER_RHO, 0.49_wp, 0.53_wp)
  call compare('Fig 12, 3:1, A at rho = 0.509', fig12_kappa, 0.001_wp, 0.00075_wp, 0.509_wp, &
               .true., PARAMETER_A, 0.0_wp, 0.002_wp)
  call compare('Fig 12, no internal resonance', fig12_kappa, 0.001_wp, 0.00075_wp, 0.51_wp, &
               .false., PARAMETER_RHO, 0.49_wp, 0.53_wp)

  ! without internal resonance the amplitudes are eq (49)'s positive roots
  call make(fig12_kappa, 0.001_wp, 0.0015_wp, 0.51_wp, .false., PARAMETER_RHO)
  do k = 1, 21
    associate (rho => 0.49_wp + 0.04_wp*(k - 0.5_wp)/21)
      call steady_states(flow, rho, 10.0_wp, newton_options(), states, n_states, available)
      call nonresonant_amplitudes(flow%modal, rho, 0.0015_wp, a1, n_roots, status, message)
      call check_true('eq (49) has as many roots as steady states at rho = '//trim(num2str(rho)), &
                      available .and. status == 0 .and. n_roots == n_states)
      if (n_roots == n_states .and. n_states > 0) &
        call check_true('and the same amplitudes at rho = '//trim(num2str(rho)), &
                        maxval(abs(sorted_amplitudes() - a1(1:n_roots))) <= 1.0e-9_wp)
    end associate
  end do

  call make(fig12_kappa, 0.001_wp, 0.0_wp, 0.51_wp, .true., PARAMETER_RHO)
  call steady_states(flow, 0.51_wp, 10.0_wp, newton_options(), states, n_states, available)
  call check_true('A = 0: no closed form (the unforced flow has circles of steady states)', &
                  .not. available)
  call make(fig12_kappa, 0.001_wp, 1.0e-25_wp, 0.51_wp, .true., PARAMETER_RHO)
  call steady_states(flow, 0.51_wp, 10.0_wp, newton_options(), states, n_states, available)
  call check_true('A = 1e-25: no closed form (its grid of amplitudes would span > 62 decades)', &
                  .not. available)
  call finish()

contains

  subroutine make(kappa, gamma, amplitude, rho, internal_resonance, parameter)
    real(wp), intent(in) :: kappa, gamma, amplitude, rho
    logical, intent(in) :: internal_resonance
    integer, intent(in) :: parameter
    type(model_t) :: model
    call model_from_arrays([1.5_wp, 0.5_wp, kappa, pi/4, 10.0_wp, gamma, 0.1_wp, amplitude, &
                            rho, 0.0_wp], [6, 2], model, status, message)
    call make_slow_flow(model, internal_resonance, parameter, flow, status, message)
    call check_true('model: '//trim(message), status == 0)
  end subroutine make

  !> At 21 values of lambda in (lambda_min, lambda_max): the grid's states against the closed
  !> form's.
  subroutine compare(label, kappa, gamma, amplitude, rho, internal_resonance, parameter, &
                     lambda_min, lambda_max)
    character(len=*), intent(in) :: label
    real(wp), intent(in) :: kappa, gamma, amplitude, rho, lambda_min, lambda_max
    logical, intent(in) :: internal_resonance
    integer, intent(in) :: parameter
    real(wp), allocatable :: grid_states(:, :)
    real(wp) :: lambda, f(4)
    integer :: i, j, k, n_grid_states, missed, not_solving, total
    missed = 0
    not_solving = 0
    total = 0
    call make(kappa, gamma, amplitude, rho, internal_resonance, parameter)
    do i = 1, 21
      lambda = lambda_min + (lambda_max - lambda_min)*(i - 0.5_wp)/21
      call steady_states(flow, lambda, 10.0_wp, newton_options(), states, n_states, available)
      call check_true(label//': closed form available at '//trim(num2str(lambda)), available)
      call newton_grid(lambda, grid_states, n_grid_states)
      total = total + n_grid_states
      do j = 1, n_grid_states
        if (.not. any([(maxval(abs(states(:, k) - grid_states(:, j))) <= &
                        1.0e-7_wp*(1 + maxval(abs(grid_states(:, j)))), k = 1, n_states)])) &
          missed = missed + 1
      end do
      do k = 1, n_states
        call flow%residual(states(:, k), lambda, f(1:flow%dimension()))
        if (maxval(abs(f(1:flow%dimension()))) > 1.0e-10_wp) not_solving = not_solving + 1
      end do
    end do
    call check_true(label//': every state of the Newton grid found in closed form ('// &
                    num2str(missed)//' of '//num2str(total)//' missed)', &
                    missed == 0 .and. total >= 21)
    call check_true(label//': every closed-form state solves the slow flow', not_solving == 0)
  end subroutine compare

  !> Distinct solutions of Newton from |B| in 1e-4 ... 1 (6, log-spaced) times 6 phases per
  !> mode, with max|x| <= 10 (as frequency_response's scan).
  subroutine newton_grid(lambda, found, n_found)
    real(wp), intent(in) :: lambda
    real(wp), allocatable, intent(out) :: found(:, :)
    integer, intent(out) :: n_found
    real(wp) :: x(flow%dimension()), radii(6), angles(6)
    integer :: a1, p1, j, k, n_second, iterations, info, n
    n = flow%dimension()
    radii = [(1.0e-4_wp*1.0e4_wp**((j - 1)/5.0_wp), j = 1, 6)]
    angles = [(2*pi*(j - 1)/6, j = 1, 6)]
    n_second = merge(36, 1, n == 4)
    allocate (found(n, 36*n_second))
    n_found = 0
    do a1 = 1, 6
      do p1 = 1, 6
        do j = 1, n_second
          x(1:2) = radii(a1)*[cos(angles(p1)), sin(angles(p1))]
          if (n == 4) x(3:4) = radii((j - 1)/6 + 1)*[cos(angles(mod(j - 1, 6) + 1)), &
                                                     sin(angles(mod(j - 1, 6) + 1))]
          call newton_solve(flow, x, lambda, newton_options(), iterations, info, message, &
                            explain=.false.)
          if (info /= 0 .or. maxval(abs(x)) > 10) cycle
          if (any([(maxval(abs(found(:, k) - x)) <= 1.0e-8_wp*(1 + maxval(abs(x))), &
                    k = 1, n_found)])) cycle
          n_found = n_found + 1
          found(:, n_found) = x
        end do
      end do
    end do
  end subroutine newton_grid

  function sorted_amplitudes() result(amplitudes)
    real(wp) :: amplitudes(n_states)
    integer :: i
    amplitudes = [(hypot(states(1, i), states(2, i)), i = 1, n_states)]
    call sort_ascending(amplitudes)
  end function sorted_amplitudes
end program test_steady_states
