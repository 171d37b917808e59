!> The Lyapunov spectrum of the full equations of motion (eq 15 with 29-31): the tank system
!> (sloshdyn_system) handed to the generic QR method of sloshdyn_lyapunov, with the settings of
!> the largest exponent (lyapunov_options) and the Kaplan-Yorke dimension.
module sloshdyn_tank_lyapunov
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK
  use sloshdyn_sort, only: sort_ascending
  use sloshdyn_model, only: model_t
  use sloshdyn_system, only: tank_system
  use sloshdyn_ode, only: ode_options
  use sloshdyn_lyapunov, only: lyapunov_spectrum, kaplan_yorke
  use sloshdyn_periodic_response, only: lyapunov_options, check_lyapunov
  implicit none
  private
  public :: tank_lyapunov_spectrum

contains

  !> All four Lyapunov exponents per unit tau from y0 (decreasing once converged), their running
  !> estimates history(:, b) after each block of options%renormalise_every forcing periods, and
  !> the Kaplan-Yorke dimension of the exponents sorted in decreasing order.
  subroutine tank_lyapunov_spectrum(model, y0, options, ode, method, exponents, history, &
                                    dimension_ky, status, message)
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: y0(4)
    type(lyapunov_options), intent(in) :: options
    type(ode_options), intent(in) :: ode
    integer, intent(in) :: method
    real(wp), intent(out) :: exponents(4), history(:, :), dimension_ky
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(tank_system) :: system
    real(wp) :: sorted(4)

    dimension_ky = 0
    status = SD_OK
    message = ''
    call check_lyapunov(options, status, message)
    if (status /= SD_OK) return
    system%model = model
    call lyapunov_spectrum(system, y0, options%transient_periods, options%n_periods, &
                           options%renormalise_every, ode, method, exponents, history, status, &
                           message)
    if (status /= SD_OK) return
    sorted = exponents
    call sort_ascending(sorted)
    dimension_ky = kaplan_yorke(sorted(4:1:-1))
  end subroutine tank_lyapunov_spectrum
end module sloshdyn_tank_lyapunov
