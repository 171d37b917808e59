!> Time histories of many tanks at once (issue 43): the members' runs of time_history
!> (sloshdyn_simulation) handed to the ensemble integrator (sloshdyn_ensemble), with the same
!> results bit for bit, each member with its own model (parameters, excitation), start, initial
!> state and output times.
module sloshdyn_ensemble_history
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK
  use sloshdyn_model, only: model_t
  use sloshdyn_system, only: tank_ensemble
  use sloshdyn_ode, only: ode_options, ode_stats, observed_quantities, peak_tracker
  use sloshdyn_ensemble, only: integrate_ensemble
  use sloshdyn_simulation, only: check_history, with_breakpoints, derive_history, time_history
  implicit none
  private
  public :: ensemble_history, tank_histories

contains

  !> For every member i (of size(models)): time_history(models(i), tau0(i), y0(:, i),
  !> tau_out(:, i), options, method) into history(:, :, i), stats(i), status(i), message(i).
  !> A member whose inputs fail time_history's checks reports them and is not integrated; the
  !> others run together. With observed(i) (or observed(1) for all) and tracker(i): member i's
  !> peaks, as time_history's (a member that failed the checks has its tracker started, and
  !> nothing else).
  subroutine ensemble_history(models, tau0, y0, tau_out, options, method, history, stats, &
                              status, message, observed, tracker)
    type(model_t), intent(in) :: models(:)
    real(wp), intent(in) :: tau0(:), y0(:, :), tau_out(:, :)
    type(ode_options), intent(in) :: options
    integer, intent(in) :: method
    real(wp), intent(out) :: history(:, :, :)
    type(ode_stats), intent(out) :: stats(:)
    integer, intent(out) :: status(:)
    character(len=message_len), intent(out) :: message(:)
    class(observed_quantities), intent(in), optional, target :: observed(:)
    type(peak_tracker), intent(inout), optional :: tracker(:)
    type(tank_ensemble) :: ens
    type(ode_options), allocatable :: settings(:)
    real(wp), allocatable :: states(:, :, :), t_run(:, :), y_run(:, :)
    integer :: checked(size(models)), i
    character(len=message_len) :: checked_message(size(models))

    history = 0
    do i = 1, size(models)
      call check_history(tau0(i), y0(:, i), tau_out(:, i), checked(i), checked_message(i))
    end do
    ! a member that failed the checks takes part with no step to take (every output at tau0,
    ! from rest), so that every member's argument stays whole: observed(run), a vector
    ! subscript of a polymorphic array, loses its components' values in gfortran 12
    t_run = tau_out
    y_run = y0
    do i = 1, size(models)
      if (checked(i) == SD_OK) cycle
      t_run(:, i) = tau0(i)
      y_run(:, i) = 0
    end do
    ens%models = models
    settings = [(with_breakpoints(options, models(i)%excitation), i = 1, size(models))]
    allocate (states(4, size(tau_out, 1), size(models)))
    if (present(observed) .and. present(tracker)) then
      call integrate_ensemble(method, ens, tau0, y_run, t_run, states, settings, stats, status, &
                              message, observed, tracker)
    else
      call integrate_ensemble(method, ens, tau0, y_run, t_run, states, settings, stats, status, &
                              message)
    end if
    do i = 1, size(models)
      if (checked(i) /= SD_OK) then
        status(i) = checked(i)
        message(i) = checked_message(i)
        stats(i) = ode_stats()
        stats(i)%t_reached = tau0(i)
        cycle
      end if
      history(1:4, :, i) = states(:, :, i)
      call derive_history(models(i), history(:, :, i))
    end do
  end subroutine ensemble_history

  !> The time histories of the members, with observed(i) and tracker(i) as ensemble_history's:
  !> one member alone by time_history (the single path), two or more by the ensemble.
  subroutine tank_histories(models, tau0, y0, tau_out, options, method, history, stats, &
                            status, message, observed, tracker)
    type(model_t), intent(in) :: models(:)
    real(wp), intent(in) :: tau0(:), y0(:, :), tau_out(:, :)
    type(ode_options), intent(in) :: options
    integer, intent(in) :: method
    real(wp), intent(out) :: history(:, :, :)
    type(ode_stats), intent(out) :: stats(:)
    integer, intent(out) :: status(:)
    character(len=message_len), intent(out) :: message(:)
    class(observed_quantities), intent(in), target :: observed(:)
    type(peak_tracker), intent(inout) :: tracker(:)
    if (size(models) == 1) then
      call time_history(models(1), tau0(1), y0(:, 1), tau_out(:, 1), options, method, &
                        history(:, :, 1), stats(1), status(1), message(1), observed(1), &
                        tracker(1))
    else
      call ensemble_history(models, tau0, y0, tau_out, options, method, history, stats, &
                            status, message, observed, tracker)
    end if
  end subroutine tank_histories
end module sloshdyn_ensemble_history
