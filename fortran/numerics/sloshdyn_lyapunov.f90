!> The largest Lyapunov exponent of a periodically forced system (Benettin's method), by the
!> integrator family: the orbit and one tangent vector of the variational equations together.
module sloshdyn_lyapunov
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, SD_NON_FINITE
  use sloshdyn_text, only: num2str
  use sloshdyn_ode, only: ode_options, rk_integrator
  use sloshdyn_integrator, only: new_integrator
  use sloshdyn_shooting, only: periodic_problem, shooting_setup, make_setup, check_setup
  implicit none
  private
  public :: largest_lyapunov, check_lyapunov_counts

  integer, parameter :: max_periods = 10000000

contains

  !> Largest Lyapunov exponent (per unit tau) from y0 at tau = 0: the orbit and one tangent
  !> vector v' = J v are integrated together; every renormalise_every forcing periods (at the
  !> first step end on or after each boundary) |v| is reset to 1 by set_state and log|v|
  !> is summed (Benettin's method). The first transient_periods are not counted; exponent =
  !> sum log|v| / measured time over n_periods (a multiple of renormalise_every).
  !> history(j) = the running estimate after measurement block j (n_periods/renormalise_every
  !> blocks; entries beyond are NaN). On a periodic orbit it tends to log(max|mu|)/(k T).
  subroutine largest_lyapunov(problem, y0, transient_periods, n_periods, renormalise_every, &
                              options, method, exponent, history, status, message)
    class(periodic_problem), intent(in) :: problem
    real(wp), intent(in) :: y0(:)
    integer, intent(in) :: transient_periods, n_periods, renormalise_every, method
    type(ode_options), intent(in) :: options
    real(wp), intent(out) :: exponent, history(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(shooting_setup) :: setup
    class(rk_integrator), allocatable :: integ
    real(wp), allocatable :: z(:)
    real(wp) :: period, t_end, growth, sum_log, t_start
    integer :: n, i, next_count, total, n_blocks, blocks_done
    logical :: measuring

    n = size(y0)
    exponent = ieee_value(1.0_wp, ieee_quiet_nan)
    history = ieee_value(1.0_wp, ieee_quiet_nan)
    call check_setup(problem, y0, 1, status, message)
    if (status /= SD_OK) return
    call check_lyapunov_counts(transient_periods, n_periods, renormalise_every, status, message)
    if (status /= SD_OK) return
    n_blocks = n_periods/renormalise_every
    if (size(history) < n_blocks) then
      status = SD_BAD_INPUT
      message = 'history has size '//num2str(size(history))//'; it needs n_periods/'// &
                'renormalise_every = '//num2str(n_blocks)//' entries'
      return
    end if

    call make_setup(setup, problem, n, 1, 1, .false., options, method)
    period = problem%period()
    total = transient_periods + n_periods
    t_end = total*period
    allocate (z(2*n))
    z(1:n) = y0
    ! a generic start direction (not aligned with any coordinate)
    z(n + 1:2*n) = [(1.0_wp/i, i = 1, n)]
    z(n + 1:2*n) = z(n + 1:2*n)/norm2(z(n + 1:2*n))
    call new_integrator(method, setup%options%rtol, integ, status, message)
    if (status == SD_OK) call integ%init(setup%sys, 0.0_wp, z, t_end, setup%options, status, &
                                         message)
    if (status /= SD_OK) then
      message = 'Lyapunov exponent: '//trim(message)
      return
    end if

    measuring = transient_periods == 0
    t_start = 0
    sum_log = 0
    blocks_done = 0
    next_count = next_boundary(0)
    do while (integ%t < t_end)
      call integ%step(setup%sys, status, message)
      if (status /= SD_OK) then
        message = 'Lyapunov exponent, after '//num2str(blocks_done)//' of '// &
                  num2str(n_blocks)//' blocks: '//trim(message)
        return
      end if
      if (integ%t < next_count*period) cycle
      ! renormalise; the growth since the last renormalisation counts once measuring
      z = integ%y
      growth = norm2(z(n + 1:2*n))
      if (.not. (growth > 0 .and. growth <= huge(growth))) then
        status = SD_NON_FINITE
        message = 'the tangent vector norm is '//num2str(growth)//' at tau = '// &
                  num2str(integ%t)//' (renormalise more often)'
        return
      end if
      if (measuring) sum_log = sum_log + log(growth)
      do while (next_count <= total)
        if (next_count*period > integ%t) exit
        if (next_count > transient_periods) then
          blocks_done = blocks_done + 1
          history(blocks_done) = sum_log/(integ%t - t_start)
        end if
        next_count = next_boundary(next_count)
      end do
      if (.not. measuring .and. integ%t >= transient_periods*period) then
        measuring = .true.
        t_start = integ%t
      end if
      z(n + 1:2*n) = z(n + 1:2*n)/growth
      call integ%set_state(setup%sys, z, status, message)
      if (status /= SD_OK) then
        message = 'Lyapunov exponent, renormalising at tau = '//num2str(integ%t)//': '// &
                  trim(message)
        return
      end if
    end do
    exponent = sum_log/(t_end - t_start)

  contains

    !> The renormalisation boundary (in forcing periods) after count: every renormalise_every
    !> periods, and the end of the transient.
    integer function next_boundary(count)
      integer, intent(in) :: count
      if (count < transient_periods) then
        next_boundary = min(count + renormalise_every, transient_periods)
      else
        next_boundary = count + renormalise_every
      end if
    end function next_boundary
  end subroutine largest_lyapunov

  !> The counts of largest_lyapunov, checked before anything is allocated for them (readers call
  !> this first): n_periods at most max_periods (each period integrates the 4 + 16 variational
  !> equations: 10**7 periods take hours).
  pure subroutine check_lyapunov_counts(transient_periods, n_periods, renormalise_every, &
                                        status, message)
    integer, intent(in) :: transient_periods, n_periods, renormalise_every
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    status = SD_OK
    message = ''
    if (transient_periods < 0 .or. n_periods < 1 .or. renormalise_every < 1) then
      status = SD_BAD_INPUT
      message = 'transient_periods = '//num2str(transient_periods)//', n_periods = '// &
                num2str(n_periods)//', renormalise_every = '//num2str(renormalise_every)// &
                ' are out of range: they must be >= 0, >= 1, >= 1'
      return
    end if
    if (n_periods > max_periods) then
      status = SD_BAD_INPUT
      message = 'n_periods = '//num2str(n_periods)//' is out of range: it must lie in [1, '// &
                num2str(max_periods)//']'
      return
    end if
    if (mod(n_periods, renormalise_every) /= 0) then
      status = SD_BAD_INPUT
      message = 'n_periods = '//num2str(n_periods)//' is out of range: it must be a multiple '// &
                'of renormalise_every = '//num2str(renormalise_every)
      return
    end if
  end subroutine check_lyapunov_counts
end module sloshdyn_lyapunov
