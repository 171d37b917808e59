!> The f2py bridge of simulation.py: time histories, steady states and sweeps of the full
!> equations.
!> The bridge's contract (c_double/c_int arrays in named layouts, status and message,
!> threads and the GIL) is written once, in sloshdyn_bridge_model.f90.
module sloshdyn_bridge_simulation
  use, intrinsic :: iso_c_binding, only: c_double, c_int
  implicit none

contains

  !> Time history at tau_out (ascending, >= tau0): history(HISTORY_ROWS, n_out) in the rows of
  !> the 'history' table after tau. On failure the columns not reached are NaN.
  subroutine simulate(rpar, ipar, tau0, y0, n_out, tau_out, integration, history, counts, status, &
                      message)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_tables, only: HISTORY_ROWS, COUNTS_SIZE
    use sloshdyn_layouts, only: INTEGRATION_SIZE, to_ode_options, to_method, counts_array
    use sloshdyn_ode, only: ode_stats
    use sloshdyn_simulation, only: time_history
    real(c_double), intent(in) :: rpar(n_real_params), tau0, y0(4), tau_out(n_out), &
                                  integration(INTEGRATION_SIZE)
    integer(c_int), intent(in) :: ipar(n_int_params), n_out
    real(c_double), intent(out) :: history(HISTORY_ROWS, n_out), counts(COUNTS_SIZE)
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
    type(model_t) :: model
    type(ode_stats) :: stats
    integer :: info
    history = 0
    counts = 0
    call model_from_arrays(rpar, int(ipar), model, info, message)
    if (info == 0) then
      call time_history(model, tau0, y0, tau_out, to_ode_options(integration), &
                        to_method(integration), history, stats, info, message)
      counts = counts_array(stats)
    end if
    status = info
  end subroutine simulate

  !> Time histories of k tanks in one ensemble (sloshdyn_ensemble_history): member i has the
  !> parameters rpar(:, i), ipar(:, i), the start tau0(i), the state y0(:, i) and the output
  !> times tau_out(:, i); history(:, :, i) and counts(:, i) as simulate's, bit for bit.
  !> status(i) per member; message is the first failure's, naming its member.
  subroutine simulate_ensemble(k, rpar, ipar, tau0, y0, n_out, tau_out, integration, history, &
                               counts, status, message)
    !f2py threadsafe
    use sloshdyn_kinds, only: message_len
    use sloshdyn_text, only: num2str
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_tables, only: HISTORY_ROWS, COUNTS_SIZE
    use sloshdyn_layouts, only: INTEGRATION_SIZE, to_ode_options, to_method, counts_array
    use sloshdyn_ode, only: ode_stats
    use sloshdyn_ensemble_history, only: ensemble_history
    integer(c_int), intent(in) :: k, n_out, ipar(n_int_params, k)
    real(c_double), intent(in) :: rpar(n_real_params, k), tau0(k), y0(4, k), &
                                  tau_out(n_out, k), integration(INTEGRATION_SIZE)
    real(c_double), intent(out) :: history(HISTORY_ROWS, n_out, k), counts(COUNTS_SIZE, k)
    integer(c_int), intent(out) :: status(k)
    character(len=512), intent(out) :: message
    type(model_t) :: models(k)
    type(ode_stats) :: stats(k)
    integer :: info(k), i
    character(len=message_len) :: messages(k)
    history = 0
    counts = 0
    info = 0
    do i = 1, k
      call model_from_arrays(rpar(:, i), int(ipar(:, i)), models(i), info(i), messages(i))
    end do
    if (all(info == 0)) then
      call ensemble_history(models, tau0, y0, tau_out, to_ode_options(integration), &
                            to_method(integration), history, stats, info, messages)
      do i = 1, k
        counts(:, i) = counts_array(stats(i))
      end do
    end if
    status = info
    message = ''
    do i = 1, k
      if (info(i) == 0) cycle
      message = 'member '//num2str(i - 1)//': '//trim(messages(i))
      exit
    end do
  end subroutine simulate_ensemble

  !> Steady state from y0 at tau = 0: summary in the 'summary' layout, the window's Poincare
  !> points and the final state (at forcing phase 0).
  subroutine steady_state(rpar, ipar, y0, integration, steady, window, summary, poincare, y_end, &
                          counts, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_tables, only: SUMMARY_SIZE, COUNTS_SIZE
    use sloshdyn_layouts, only: INTEGRATION_SIZE, STEADY_SIZE, to_ode_options, to_method, &
                                to_steady, counts_array
    use sloshdyn_ode, only: ode_stats
    use sloshdyn_simulation, only: core => steady_state
    real(c_double), intent(in) :: rpar(n_real_params), y0(4), integration(INTEGRATION_SIZE), &
                                  steady(STEADY_SIZE)
    integer(c_int), intent(in) :: ipar(n_int_params), window
    real(c_double), intent(out) :: summary(SUMMARY_SIZE), poincare(4, window), y_end(4), &
                                   counts(COUNTS_SIZE)
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
    type(model_t) :: model
    type(ode_stats) :: stats
    integer :: info
    summary = 0; poincare = 0; y_end = 0; counts = 0
    call model_from_arrays(rpar, int(ipar), model, info, message)
    if (info == 0) then
      call core(model, y0, to_ode_options(integration), to_method(integration), &
                to_steady(steady), summary, poincare, y_end, stats, info, message)
      counts = counts_array(stats)
    end if
    status = info
  end subroutine steady_state

  !> Steady states along values of rho (which = 1) or A (which = 2), each from the previous
  !> final state; summaries(SUMMARY_SIZE, n) as for steady_state, n_done points completed.
  subroutine parameter_sweep(rpar, ipar, which, n, values, y0, integration, steady, summaries, &
                             y_final, n_done, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_tables, only: SUMMARY_SIZE
    use sloshdyn_layouts, only: INTEGRATION_SIZE, STEADY_SIZE, to_ode_options, to_method, &
                                to_steady
    use sloshdyn_simulation, only: core => parameter_sweep
    real(c_double), intent(in) :: rpar(n_real_params), values(n), y0(4), &
                                  integration(INTEGRATION_SIZE), &
                                  steady(STEADY_SIZE)
    integer(c_int), intent(in) :: ipar(n_int_params), which, n
    real(c_double), intent(out) :: summaries(SUMMARY_SIZE, n), y_final(4)
    integer(c_int), intent(out) :: n_done, status
    character(len=512), intent(out) :: message
    type(model_t) :: model
    integer :: info, done
    summaries = 0; y_final = y0; done = 0
    call model_from_arrays(rpar, int(ipar), model, info, message)
    if (info == 0) call core(model, int(which), values, y0, to_ode_options(integration), &
                             to_method(integration), to_steady(steady), summaries, y_final, &
                             done, info, message)
    n_done = done
    status = info
  end subroutine parameter_sweep

  !> Steady states at values of rho (which = 1) or A (which = 2), each from y0 (independent
  !> points) in blocks of `block` points for the ensemble (0: the core's default), the blocks
  !> shared out to n_threads threads; the results depend neither on n_threads nor on block.
  subroutine independent_sweep(rpar, ipar, which, n, values, y0, integration, steady, n_threads, &
                            block, summaries, n_done, status, message)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_tables, only: SUMMARY_SIZE
    use sloshdyn_layouts, only: INTEGRATION_SIZE, STEADY_SIZE, to_ode_options, to_method, &
                                to_steady
    use sloshdyn_simulation, only: core => independent_sweep
    real(c_double), intent(in) :: rpar(n_real_params), values(n), y0(4), &
                                  integration(INTEGRATION_SIZE), &
                                  steady(STEADY_SIZE)
    integer(c_int), intent(in) :: ipar(n_int_params), which, n, n_threads, block
    real(c_double), intent(out) :: summaries(SUMMARY_SIZE, n)
    integer(c_int), intent(out) :: n_done, status
    character(len=512), intent(out) :: message
    type(model_t) :: model
    integer :: info, done
    summaries = 0; done = 0
    call model_from_arrays(rpar, int(ipar), model, info, message)
    if (info == 0) call core(model, int(which), values, y0, to_ode_options(integration), &
                             to_method(integration), to_steady(steady), int(n_threads), &
                             summaries, done, info, message, int(block))
    n_done = done
    status = info
  end subroutine independent_sweep

  !> The core's number of independent sweep points a block by default (independent_sweep's
  !> block = 0), for the callers that cut a sweep into calls of a block per thread.
  subroutine default_sweep_block(block)
    use sloshdyn_simulation, only: core => default_sweep_block
    integer(c_int), intent(out) :: block
    block = core
  end subroutine default_sweep_block

  !> The rule for the threads of a sweep (carry = 1: the state is carried from point to point).
  subroutine sweep_threads(threads, carry, status, message)
    use sloshdyn_namelist, only: check_threads
    integer(c_int), intent(in) :: threads, carry
    integer(c_int), intent(out) :: status
    character(len=512), intent(out) :: message
    integer :: info
    info = 0
    message = ''
    call check_threads(int(threads), carry /= 0, info, message)
    status = info
  end subroutine sweep_threads

  !> The method code that runs for the settings integration (layout of sloshdyn_layouts):
  !> the method itself, or for 'auto' the pair chosen for its rtol.
  subroutine method_used(integration, code)
    !f2py threadsafe
    use sloshdyn_layouts, only: INTEGRATION_SIZE, to_method, to_ode_options
    use sloshdyn_integrator, only: chosen_method
    use sloshdyn_ode, only: ode_options
    real(c_double), intent(in) :: integration(INTEGRATION_SIZE)
    integer(c_int), intent(out) :: code
    type(ode_options) :: options
    options = to_ode_options(integration)
    code = int(chosen_method(to_method(integration), options%rtol), c_int)
  end subroutine method_used
end module sloshdyn_bridge_simulation
