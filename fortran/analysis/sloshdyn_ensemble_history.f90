!> Time histories of many tanks at once (issue 43): the members' runs of time_history
!> (sloshdyn_simulation) handed to the ensemble integrator (sloshdyn_ensemble), with the same
!> results bit for bit, each member with its own model (parameters, excitation), start, initial
!> state and output times.
module sloshdyn_ensemble_history
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK
  use sloshdyn_model, only: model_t
  use sloshdyn_system, only: tank_ensemble
  use sloshdyn_ode, only: ode_options, ode_stats
  use sloshdyn_ensemble, only: integrate_ensemble
  use sloshdyn_simulation, only: check_history, with_breakpoints, derive_history
  implicit none
  private
  public :: ensemble_history

contains

  !> For every member i (of size(models)): time_history(models(i), tau0(i), y0(:, i),
  !> tau_out(:, i), options, method) into history(:, :, i), stats(i), status(i), message(i).
  !> A member whose inputs fail time_history's checks reports them and is not integrated; the
  !> others run together.
  subroutine ensemble_history(models, tau0, y0, tau_out, options, method, history, stats, &
                              status, message)
    type(model_t), intent(in) :: models(:)
    real(wp), intent(in) :: tau0(:), y0(:, :), tau_out(:, :)
    type(ode_options), intent(in) :: options
    integer, intent(in) :: method
    real(wp), intent(out) :: history(:, :, :)
    type(ode_stats), intent(out) :: stats(:)
    integer, intent(out) :: status(:)
    character(len=message_len), intent(out) :: message(:)
    type(tank_ensemble) :: ens
    type(ode_options), allocatable :: settings(:)
    integer, allocatable :: run(:)
    real(wp), allocatable :: states(:, :, :)
    type(ode_stats), allocatable :: run_stats(:)
    integer, allocatable :: run_status(:)
    character(len=message_len), allocatable :: run_message(:)
    integer :: i

    history = 0
    do i = 1, size(models)
      stats(i)%t_reached = tau0(i)
      call check_history(tau0(i), y0(:, i), tau_out(:, i), status(i), message(i))
    end do
    run = pack([(i, i = 1, size(models))], status == SD_OK)
    if (size(run) == 0) return
    ens%models = models(run)
    settings = [(with_breakpoints(options, models(run(i))%excitation), i = 1, size(run))]
    allocate (states(4, size(tau_out, 1), size(run)), run_stats(size(run)), &
              run_status(size(run)), run_message(size(run)))
    call integrate_ensemble(method, ens, tau0(run), y0(:, run), tau_out(:, run), states, &
                            settings, run_stats, run_status, run_message)
    stats(run) = run_stats
    status(run) = run_status
    message(run) = run_message
    do i = 1, size(run)
      history(1:4, :, run(i)) = states(:, :, i)
      call derive_history(models(run(i)), history(:, :, run(i)))
    end do
  end subroutine ensemble_history
end module sloshdyn_ensemble_history
