!> Ensembles (sloshdyn_ensemble) against the single-trajectory path (integrate, the
!> independent reference: its own driver loop, rk_step): for K = 1, 2, 3, 8, 64 tanks of the
!> Fig 14 family (rho and the initial state varied per member, so that the members take
!> different steps, reject at different times and hit their peaks at different times), each
!> with its own final time (so that they leave the ensemble at different rounds), the outputs,
!> the work counts and the peak trackers (peaks, their times and states, level crossings) must
!> equal the single runs bit for bit, for DOP853, Verner 9(8) and DOPRI5. A member that fails
!> (step budget) must fail as it does alone, with the same partial output, while the others
!> go on. advance_members, resumed stretch after stretch with each member's own targets (some
!> calls advancing only some members), must equal integ%step looped to the same targets.
program test_ensemble
  use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, SD_TOO_MANY_STEPS, SD_BAD_INPUT
  use sloshdyn_text, only: num2str
  use sloshdyn_ode, only: ode_options, ode_stats, linear_observation, peak_tracker
  use sloshdyn_integrator, only: integrate, method_name, METHOD_DOPRI5, METHOD_DOP853, &
                                 METHOD_VERN9, METHOD_AUTO, new_integrator
  use sloshdyn_ode, only: rk_integrator
  use sloshdyn_ensemble, only: integrate_ensemble, advance_members
  use sloshdyn_model, only: model_t, model_from_arrays
  use sloshdyn_system, only: tank_system, tank_ensemble
  use checks, only: check_true, finish
  implicit none

  integer, parameter :: sizes(5) = [1, 2, 3, 8, 64], n_out = 7
  integer :: i, method

  do method = METHOD_DOPRI5, METHOD_VERN9
    do i = 1, size(sizes)
      call compare(method, sizes(i), 1.0e-9_wp, 0)
    end do
  end do
  call compare(METHOD_DOP853, 8, 1.0e-6_wp, 0)
  call compare(METHOD_VERN9, 8, 1.0e-12_wp, 0)
  ! a step budget that the longer members exhaust
  call compare(METHOD_DOP853, 8, 1.0e-9_wp, 450)
  do method = METHOD_DOPRI5, METHOD_VERN9
    call stretches(method)
  end do
  call bad_inputs()
  call finish()

contains

  !> Member i of K: rho across the Fig 14 resonance, A = 0.00075 (A = 0.2 for every third,
  !> which drives the impacts: many rejections), y0 of its own, final time 60 + 15 i.
  subroutine member(i, model, y0, t_end)
    integer, intent(in) :: i
    type(model_t), intent(out) :: model
    real(wp), intent(out) :: y0(4), t_end
    real(wp) :: rho, amplitude
    integer :: status
    character(len=message_len) :: message
    rho = 0.49_wp + 0.0007_wp*i
    amplitude = merge(0.2_wp, 0.00075_wp, mod(i, 3) == 0)
    call model_from_arrays([1.5_wp, 0.5_wp, 1.804897259_wp, pi/4, 10.0_wp, 0.001_wp, 0.1_wp, &
                            amplitude, rho, 0.0_wp], [6, 2], model, status, message)
    if (status /= SD_OK) error stop 'test_ensemble: bad model'
    y0 = [0.01_wp + 0.002_wp*mod(i, 5), 0.0_wp, 0.01_wp, 0.001_wp*mod(i, 2)]
    t_end = 60 + 15*i
  end subroutine member

  subroutine compare(method, k, rtol, max_steps)
    integer, intent(in) :: method, k, max_steps
    real(wp), intent(in) :: rtol
    type(tank_ensemble) :: ens
    type(tank_system) :: alone
    type(ode_options) :: options
    type(linear_observation) :: obs(1)
    type(peak_tracker) :: trackers(k), single
    type(ode_stats) :: stats(k), stats1
    real(wp) :: peak_times(k), y0(4, k), t0(k), t_out(n_out, k), y_out(4, n_out, k), y1(4, n_out), t_end
    integer :: status(k), status1, i, j, n_rejected(k), n_failed, n_distinct
    character(len=message_len) :: message(k), message1
    character(len=:), allocatable :: label
    logical :: same, peaks_differ, rejections_differ

    label = method_name(method)//', K = '//num2str(k)//', rtol = '//num2str(rtol)
    if (max_steps > 0) label = label//', max_steps = '//num2str(max_steps)
    options%rtol = rtol
    options%atol = rtol*1.0e-3_wp
    if (max_steps > 0) options%max_steps = max_steps
    obs(1)%c = reshape([1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp], [2, 4])
    allocate (ens%models(k))
    do i = 1, k
      call member(i, ens%models(i), y0(:, i), t_end)
      t0(i) = 0.5_wp*mod(i, 2)
      ! outputs inside the run (dense output), one at t0, the last at t_end
      t_out(:, i) = [t0(i), 3.3_wp, 17.0_wp, 29.5_wp, 41.25_wp, 55.0_wp, t_end]
      trackers(i)%level = [0.02_wp, 0.02_wp]
      trackers(i)%keep_states = .true.
    end do
    call integrate_ensemble(method, ens, t0, y0, t_out, y_out, [options], stats, status, &
                            message, obs, trackers)

    same = .true.
    n_failed = 0
    do i = 1, k
      alone%model = ens%models(i)
      single = peak_tracker()
      single%level = [0.02_wp, 0.02_wp]
      single%keep_states = .true.
      call integrate(method, alone, t0(i), y0(:, i), t_out(:, i), y1, options, stats1, status1, &
                     message1, obs(1), single)
      if (status1 /= SD_OK) n_failed = n_failed + 1
      same = same .and. status(i) == status1 .and. message(i) == message1 .and. &
             bits_equal(reshape(y_out(:, :, i), [4*n_out]), reshape(y1, [4*n_out])) .and. &
             stats(i)%n_rhs == stats1%n_rhs .and. stats(i)%n_accepted == stats1%n_accepted .and. &
             stats(i)%n_rejected == stats1%n_rejected .and. &
             bits_equal([stats(i)%t_reached], [stats1%t_reached]) .and. &
             bits_equal(trackers(i)%peak, single%peak) .and. &
             bits_equal(trackers(i)%time, single%time) .and. &
             bits_equal(reshape(trackers(i)%state, [8]), reshape(single%state, [8])) .and. &
             all(trackers(i)%crossings == single%crossings) .and. &
             bits_equal(trackers(i)%first_crossing, single%first_crossing)
      n_rejected(i) = stats1%n_rejected
    end do
    call check_true(label//': every member equals its single run bit for bit', same)
    if (k < 3) return
    ! the test exercises what it claims: members reject, peak and finish differently
    rejections_differ = any(n_rejected /= n_rejected(1)) .and. any(n_rejected > 0)
    n_distinct = 0
    do j = 1, k
      peak_times(j) = trackers(j)%time(1)
      if (all(peak_times(1:j - 1) /= peak_times(j))) n_distinct = n_distinct + 1
    end do
    peaks_differ = 2*n_distinct >= k
    call check_true(label//': members reject at different counts', rejections_differ)
    call check_true(label//': members peak at different times', peaks_differ)
    if (max_steps > 0) then
      call check_true(label//': some members fail, some finish', n_failed > 0 .and. &
                      n_failed < k .and. count(status == SD_TOO_MANY_STEPS) == n_failed)
    else
      call check_true(label//': every member finished', all(status == SD_OK))
    end if
  end subroutine compare

  !> K = 6 members advanced by advance_members in 5 stretches, member i to the targets
  !> j (7.3 + 0.9 i), j = 1..5 (each stops just past its target, keeps its state and goes on
  !> at the next call); in the even stretches only the odd members move. The state read by
  !> dense output at the last target and the work counts must equal a single integrator of
  !> the same member stepped with integ%step while t < target, stretch after stretch.
  subroutine stretches(method)
    integer, intent(in) :: method
    integer, parameter :: k = 6, n_stretches = 5
    type(tank_ensemble) :: ens
    type(tank_system) :: alone
    type(ode_options) :: options
    class(rk_integrator), allocatable :: proto, integ(:), single
    real(wp) :: y0(4, k), t_end, target(k), z(4), z1(4)
    integer :: status(k), i, j, st, moved(k), m
    character(len=message_len) :: message(k), msg
    logical :: same
    options%rtol = 1.0e-9_wp
    options%atol = 1.0e-12_wp
    allocate (ens%models(k))
    call new_integrator(method, options%rtol, proto, st, msg)
    allocate (integ(k), mold=proto)
    do i = 1, k
      call member(i, ens%models(i), y0(:, i), t_end)
      alone%model = ens%models(i)
      call integ(i)%init(alone, 0.0_wp, y0(:, i), 100.0_wp, options, st, msg)
    end do
    same = .true.
    target = 0
    do j = 1, n_stretches
      m = 0
      do i = 1, k
        if (mod(j, 2) == 0 .and. mod(i, 2) == 0) cycle
        m = m + 1
        moved(m) = i
        target(i) = target(i) + 7.3_wp + 0.9_wp*i
      end do
      call advance_members(ens, integ, moved(1:m), target(moved(1:m)), status(1:m), &
                           message(1:m))
      same = same .and. all(status(1:m) == SD_OK)
    end do
    do i = 1, k
      ! the single path: the same member to the same targets, one step call at a time
      alone%model = ens%models(i)
      call new_integrator(method, options%rtol, single, st, msg)
      call single%init(alone, 0.0_wp, y0(:, i), 100.0_wp, options, st, msg)
      do while (single%t < target(i))
        call single%step(alone, st, msg)
      end do
      call single%dense(target(i), z1)
      call integ(i)%dense(target(i), z)
      same = same .and. bits_equal(z, z1) .and. bits_equal(integ(i)%y, single%y) .and. &
             integ(i)%n_rhs == single%n_rhs .and. integ(i)%n_accepted == single%n_accepted .and. &
             integ(i)%n_rejected == single%n_rejected .and. bits_equal([integ(i)%h], [single%h])
    end do
    call check_true(method_name(method)//': advance_members in stretches equals step '// &
                    'looped to the same targets, bit for bit', same)
    ! a member listed twice would be stepped twice a round: refused, by name, nothing moved
    z = integ(2)%y
    call advance_members(ens, integ, [2, 2], [200.0_wp, 200.0_wp], status(1:2), message(1:2))
    call check_true(method_name(method)//': advance_members refuses a member listed twice', &
                    all(status(1:2) /= SD_OK) .and. index(message(1), 'members(2) = 2') > 0 &
                    .and. bits_equal(integ(2)%y, z))
  end subroutine stretches

  !> Inputs an ensemble cannot run are reported for every member, naming what is wrong: a
  !> y_out of the wrong shape, and members whose rtol would make 'auto' pick different
  !> methods (each alone would run another method).
  subroutine bad_inputs()
    type(tank_ensemble) :: ens
    type(ode_options) :: options(2)
    type(ode_stats) :: stats(2)
    real(wp) :: y0(4, 2), t_end, t_out(2, 2), y_out(4, 2, 2), wrong(4, 3, 2)
    integer :: status(2), i
    character(len=message_len) :: message(2)
    allocate (ens%models(2))
    do i = 1, 2
      call member(i, ens%models(i), y0(:, i), t_end)
      t_out(:, i) = [0.0_wp, 10.0_wp]
    end do
    call integrate_ensemble(METHOD_DOP853, ens, [0.0_wp, 0.0_wp], y0, t_out, wrong, &
                            options(1:1), stats, status, message)
    call check_true('ensemble: a wrong y_out shape is named: '//trim(message(1)), &
                    all(status == SD_BAD_INPUT) .and. index(message(1), 'y_out') > 0)
    options(1)%rtol = 1.0e-6_wp
    options(2)%rtol = 1.0e-12_wp
    call integrate_ensemble(METHOD_AUTO, ens, [0.0_wp, 0.0_wp], y0, t_out, y_out, options, &
                            stats, status, message)
    call check_true('ensemble: auto with rtol on both sides of a crossover is refused: '// &
                    trim(message(2)), all(status == SD_BAD_INPUT) .and. &
                    index(message(2), 'rtol') > 0)
  end subroutine bad_inputs

  !> a and b hold the same bits (NaN equal to NaN).
  pure logical function bits_equal(a, b)
    real(wp), intent(in) :: a(:), b(:)
    bits_equal = size(a) == size(b)
    if (.not. bits_equal) return
    bits_equal = all(transfer(a, 1_8, size(a)) == transfer(b, 1_8, size(b)) .or. &
                     (ieee_is_nan(a) .and. ieee_is_nan(b)))
  end function bits_equal
end program test_ensemble
