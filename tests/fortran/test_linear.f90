!> Natural frequencies (eq 28) against the paper (sec 4.2) and against dgeev; the modal matrix
!> (eq 34) diagonalises K; kappa for 3:1 against the paper; the ratio map (Fig 7).
program test_linear
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT
  use sloshdyn_model, only: model_t, model_from_arrays
  use sloshdyn_linear, only: natural_frequencies, natural_frequencies_eig, modal_matrix, &
                             stiffness_matrix, kappa_for_detuning, frequency_ratio, &
                             frequencies_from_groups
  use checks, only: check_close, check_true, finish
  implicit none
  type(model_t) :: model
  integer :: status, n_roots, i
  character(len=message_len) :: message
  real(wp) :: omega1, omega2, eig1, eig2, p(2, 2), p_inv(2, 2), d(2, 2), roots(16), r_min
  real(wp) :: kappas(3) = [1.6_wp, 1.804897259_wp, 4.5_wp]

  ! Paper sec 4.2: omega1 = 0.50936, omega2 = 1.53308 at s1 = 1.5, mu1 = 0.5, kappa = 1.804897259
  call fig12(1.804897259_wp)
  call natural_frequencies(model, omega1, omega2, status, message)
  call check_close('sec 4.2: omega1 = 0.50936', omega1, 0.50936_wp, 0.0_wp, 5.0e-6_wp)
  call check_close('sec 4.2: omega2 = 1.53308', omega2, 1.53308_wp, 0.0_wp, 5.0e-6_wp)

  do i = 1, size(kappas)
    call fig12(kappas(i))
    call natural_frequencies(model, omega1, omega2, status, message)
    call natural_frequencies_eig(model, eig1, eig2, status, message)
    call check_close('eq 28 = dgeev of the linearised equations: omega1', omega1, eig1, 1.0e-12_wp)
    call check_close('eq 28 = dgeev of the linearised equations: omega2', omega2, eig2, 1.0e-12_wp)
    ! eq 34: P^-1 K P = diag(omega1^2, omega2^2)
    call modal_matrix(model, p, p_inv, status, message)
    d = matmul(p_inv, matmul(stiffness_matrix(model), p))
    call check_close('eq 34: (P^-1 K P)11 = omega1^2', d(1, 1), omega1**2, 1.0e-12_wp)
    call check_close('eq 34: (P^-1 K P)22 = omega2^2', d(2, 2), omega2**2, 1.0e-12_wp)
    call check_close('eq 34: (P^-1 K P)12 = 0', d(1, 2), 0.0_wp, 0.0_wp, 1.0e-12_wp)
    call check_close('eq 34: P^-1 P = I', maxval(abs(matmul(p_inv, p) - reshape([1, 0, 0, 1], [2, 2]))), &
                     0.0_wp, 0.0_wp, 1.0e-13_wp)
  end do

  ! kappa_hat <= 1: no natural frequencies (the upright tank is unstable), error names kappa
  call fig12(1.4_wp)
  call natural_frequencies(model, omega1, omega2, status, message)
  call check_true('kappa < s1 rejected, message names kappa', &
                  status == SD_BAD_INPUT .and. index(message, 'kappa = 1.4') == 1)

  ! Paper sec 4.2: kappa = 1.808 gives sigma1 = 0 (Fig 11), kappa = 1.8049 gives 0.005 (Fig 12)
  call kappa_for_detuning(1.5_wp, 0.5_wp, 0.0_wp, 0.0_wp, 1001.5_wp, roots, n_roots, status, message)
  call check_true('sigma1 = 0: two tunings of 3:1 (Fig 7: ratio 3 is crossed twice)', n_roots == 2)
  call check_close('sec 4.2: kappa = 1.808 for omega2 = 3 omega1', roots(1), 1.808_wp, 0.0_wp, 5.0e-4_wp)
  call kappa_for_detuning(1.5_wp, 0.5_wp, 0.005_wp, 0.0_wp, 1001.5_wp, roots, n_roots, status, message)
  call check_close('sec 4.2: kappa = 1.8049 for sigma1 = 0.005', roots(1), 1.8049_wp, 0.0_wp, 5.0e-5_wp)
  call check_close('Fig 14: kappa = 1.804897259 for sigma1 = 0.005', roots(1), 1.804897259_wp, &
                   0.0_wp, 1.0e-9_wp)
  call frequencies_from_groups(roots(2) - 1.5_wp, 0.5_wp, omega1, omega2)
  call check_close('second root also has omega2 - 3 omega1 = 0.005', omega2 - 3*omega1, 0.005_wp, &
                   1.0e-9_wp)
  ! sigma1 far below the minimum of omega2 - 3 omega1: no root
  call kappa_for_detuning(1.5_wp, 0.5_wp, -5.0_wp, 0.0_wp, 1001.5_wp, roots, n_roots, status, message)
  call check_true('no kappa when the detuning cannot be reached', status == SD_OK .and. n_roots == 0)

  ! Fig 7 (sec 3.2): for mu~ = 0.5, 3:1 at sigma~ ~ 0.305
  call check_close('sec 3.2: ratio 3 at sigma~ = 0.305, mu~ = 0.5', frequency_ratio(0.305_wp, 0.5_wp), &
                   3.0_wp, 0.0_wp, 0.01_wp)
  ! closed form: the ratio is smallest at sigma~ = 1, where beta^/alpha^2 = mu~ and
  ! ratio^2 = (1 + sqrt(1 - mu~))/(1 - sqrt(1 - mu~))
  r_min = sqrt((1 + sqrt(0.5_wp))/(1 - sqrt(0.5_wp)))
  call check_close('minimum ratio at sigma~ = 1 (closed form)', frequency_ratio(1.0_wp, 0.5_wp), &
                   r_min, 1.0e-13_wp)
  call check_true('ratio larger on both sides of sigma~ = 1', &
                  frequency_ratio(0.9_wp, 0.5_wp) > r_min .and. frequency_ratio(1.1_wp, 0.5_wp) > r_min)
  call finish()

contains

  subroutine fig12(kappa)
    real(wp), intent(in) :: kappa
    call model_from_arrays([1.5_wp, 0.5_wp, kappa, pi/4, 1.0_wp, 0.001_wp, 0.0_wp, 0.00075_wp, &
                            0.509615_wp, 0.0_wp], [6, 2], model, status, message)
  end subroutine fig12
end program test_linear
