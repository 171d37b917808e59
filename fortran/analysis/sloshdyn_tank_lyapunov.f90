!> The Lyapunov spectrum of the full equations of motion: the planar tank system (eq 15 with
!> 29-31, sloshdyn_system: 4 exponents) or the spatial one (docs/model.md eq S7,
!> sloshdyn_spatial_system: 8 exponents) handed to the generic QR method of sloshdyn_lyapunov,
!> with the settings of the largest exponent (lyapunov_options) and the Kaplan-Yorke dimension.
module sloshdyn_tank_lyapunov
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK
  use sloshdyn_model, only: model_t
  use sloshdyn_system, only: tank_system
  use sloshdyn_spatial, only: spatial_model_t
  use sloshdyn_spatial_system, only: spatial_tank_system
  use sloshdyn_shooting, only: periodic_problem
  use sloshdyn_ode, only: ode_options
  use sloshdyn_lyapunov, only: lyapunov_spectrum, kaplan_yorke
  use sloshdyn_periodic_response, only: lyapunov_options, check_lyapunov
  implicit none
  private
  public :: tank_lyapunov_spectrum, spatial_lyapunov_spectrum

contains

  !> All four Lyapunov exponents per unit tau from y0 in decreasing order, their running
  !> estimates history(:, b) after each block of options%renormalise_every forcing periods (rows
  !> in the exponents' order), and the Kaplan-Yorke dimension.
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
    system%model = model
    call system_spectrum(system, y0, options, ode, method, exponents, history, dimension_ky, &
                         status, message)
  end subroutine tank_lyapunov_spectrum

  !> The same for the spatial model: all eight exponents from y0 = (x1, x1', x2, x2', y1, y1',
  !> y2, y2'). On a planar orbit they are the in-plane and the out-of-plane exponents together.
  subroutine spatial_lyapunov_spectrum(model, y0, options, ode, method, exponents, history, &
                                       dimension_ky, status, message)
    type(spatial_model_t), intent(in) :: model
    real(wp), intent(in) :: y0(8)
    type(lyapunov_options), intent(in) :: options
    type(ode_options), intent(in) :: ode
    integer, intent(in) :: method
    real(wp), intent(out) :: exponents(8), history(:, :), dimension_ky
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(spatial_tank_system) :: system
    system%model = model
    call system_spectrum(system, y0, options, ode, method, exponents, history, dimension_ky, &
                         status, message)
  end subroutine spatial_lyapunov_spectrum

  subroutine system_spectrum(system, y0, options, ode, method, exponents, history, &
                             dimension_ky, status, message)
    class(periodic_problem), intent(in) :: system
    real(wp), intent(in) :: y0(:)
    type(lyapunov_options), intent(in) :: options
    type(ode_options), intent(in) :: ode
    integer, intent(in) :: method
    real(wp), intent(out) :: exponents(:), history(:, :), dimension_ky
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    dimension_ky = 0
    call check_lyapunov(options, status, message)
    if (status /= SD_OK) return
    call lyapunov_spectrum(system, y0, options%transient_periods, options%n_periods, &
                           options%renormalise_every, ode, method, exponents, history, status, &
                           message, options%average)
    if (status == SD_OK) dimension_ky = kaplan_yorke(exponents)
  end subroutine system_spectrum
end module sloshdyn_tank_lyapunov
