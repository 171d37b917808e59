!> Lyapunov exponents of a periodically forced system, by the integrator family: the largest
!> (Benettin's method: the orbit and one tangent vector of the variational equations) and the
!> spectrum (QR method: the orbit and m tangent vectors, orthonormalised by modified
!> Gram-Schmidt), and the Kaplan-Yorke dimension. The exponents are the plain time average of
!> the renormalisations' log growths, or their weighted Birkhoff average (average_names).
module sloshdyn_lyapunov
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, SD_NON_FINITE
  use sloshdyn_text, only: num2str
  use sloshdyn_ode, only: ode_options, rk_integrator
  use sloshdyn_integrator, only: new_integrator
  use sloshdyn_shooting, only: periodic_problem, shooting_setup, make_setup, check_setup
  use sloshdyn_sort, only: sort_index
  implicit none
  private
  public :: largest_lyapunov, lyapunov_spectrum, kaplan_yorke, check_lyapunov_counts
  public :: average_names, AVERAGE_PLAIN, AVERAGE_WEIGHTED

  integer, parameter :: max_periods = 10000000
  !> How the renormalisations' log growths are averaged (codes 1, 2): 'plain', sum log R(j, j)
  !> / measured time; 'weighted', the weighted Birkhoff average with the weight
  !> w(s) = exp(-1/(s (1 - s))) at the midpoint s in (0, 1) of each renormalisation interval
  !> in the measured time, sum w log R(j, j) / sum w dt (Das, Saiki, Sander and Yorke,
  !> Nonlinearity 30 (2017) 4111; Das and Yorke, Nonlinearity 31 (2018) 491): for a smooth
  !> quasi-periodic log growth (a complex pair's frame turning by arg(mu) each period) its
  !> error falls faster than any power of the measured time, the plain one's as 1/time.
  character(len=*), parameter :: average_names(2) = [character(len=8) :: 'plain', 'weighted']
  integer, parameter :: AVERAGE_PLAIN = 1, AVERAGE_WEIGHTED = 2

contains

  !> Largest Lyapunov exponent (per unit tau) from y0 at tau = 0 (Benettin's method): the
  !> spectrum's first exponent, with one tangent vector (lyapunov_spectrum with one column).
  !> history(j) = the running estimate after measurement block j. On a periodic orbit it tends
  !> to log(max|mu|)/(k T). average: as lyapunov_spectrum's.
  subroutine largest_lyapunov(problem, y0, transient_periods, n_periods, renormalise_every, &
                              options, method, exponent, history, status, message, average)
    class(periodic_problem), intent(in) :: problem
    real(wp), intent(in) :: y0(:)
    integer, intent(in) :: transient_periods, n_periods, renormalise_every, method
    integer, intent(in), optional :: average
    type(ode_options), intent(in) :: options
    real(wp), intent(out) :: exponent, history(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: exponents(1), histories(1, size(history))

    call lyapunov_spectrum(problem, y0, transient_periods, n_periods, renormalise_every, &
                           options, method, exponents, histories, status, message, average)
    exponent = exponents(1)
    history = histories(1, :)
  end subroutine largest_lyapunov

  !> The m = size(exponents) largest Lyapunov exponents (per unit tau, m <= n = size(y0)) from
  !> y0 at tau = 0 by the QR method: the orbit and m tangent vectors V' = J V of the variational
  !> equations are integrated together; every renormalise_every forcing periods (the steps
  !> end on the periods' boundaries) V is orthonormalised by modified Gram-Schmidt,
  !> V = Q R, and log R(j, j) is summed for each j (Benettin et al. 1980; Shimada and Nagashima
  !> 1979). The first transient_periods are not counted; exponents(j) = sum log R(j, j) /
  !> measured time over n_periods (a multiple of renormalise_every), returned sorted in
  !> decreasing order (the QR columns come out in that order only once the run has converged:
  !> a short run or a complex pair of multipliers can leave them unordered); history(:, b) = the
  !> running estimates after measurement block b, its rows in the order of the sorted exponents
  !> (n_periods/renormalise_every blocks; later columns are NaN). The start frame is the
  !> orthonormalised first m columns of the Hilbert matrix (column 1 the direction 1/i of the
  !> one-vector method). On a periodic orbit exponents(j) tends to log|mu_j|/(k T); their sum
  !> over all n is the mean of trace J along the run (Liouville). average (default
  !> AVERAGE_PLAIN): how the log growths are averaged into the exponents (average_names); the
  !> history holds the plain running estimates either way (a weighted average is defined
  !> only over the whole run), its last column the plain exponents.
  subroutine lyapunov_spectrum(problem, y0, transient_periods, n_periods, renormalise_every, &
                               options, method, exponents, history, status, message, average)
    class(periodic_problem), intent(in) :: problem
    real(wp), intent(in) :: y0(:)
    integer, intent(in) :: transient_periods, n_periods, renormalise_every, method
    integer, intent(in), optional :: average
    type(ode_options), intent(in) :: options
    real(wp), intent(out) :: exponents(:), history(:, :)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(shooting_setup) :: setup
    class(rk_integrator), allocatable :: integ
    real(wp), allocatable :: z(:), sum_log(:), growth(:), weighted_log(:)
    real(wp) :: period, t_end, t_start, t_last, s, weight_time
    integer :: n, m, i, j, next_count, total, n_blocks, blocks_done, averaging
    integer, allocatable :: order(:)
    logical :: measuring

    n = size(y0)
    m = size(exponents)
    exponents = ieee_value(1.0_wp, ieee_quiet_nan)
    history = ieee_value(1.0_wp, ieee_quiet_nan)
    call check_setup(problem, y0, 1, status, message)
    if (status /= SD_OK) return
    call check_lyapunov_counts(transient_periods, n_periods, renormalise_every, status, message)
    if (status /= SD_OK) return
    averaging = AVERAGE_PLAIN
    if (present(average)) averaging = average
    if (averaging < 1 .or. averaging > size(average_names)) then
      status = SD_BAD_INPUT
      message = 'average = '//num2str(averaging)//' is out of range: it must lie in [1, '// &
                num2str(size(average_names))//']'
      return
    end if
    if (m < 1 .or. m > n) then
      status = SD_BAD_INPUT
      message = 'the number of exponents is '//num2str(m)//'; it must lie in [1, size(y0) = '// &
                num2str(n)//']'
      return
    end if
    n_blocks = n_periods/renormalise_every
    if (size(history, 1) /= m .or. size(history, 2) < n_blocks) then
      status = SD_BAD_INPUT
      message = 'history has shape ('//num2str(size(history, 1))//', '// &
                num2str(size(history, 2))//'); it needs ('//num2str(m)//', n_periods/'// &
                'renormalise_every = '//num2str(n_blocks)//')'
      return
    end if

    call make_setup(setup, problem, n, 1, m, .false., options, method)
    period = problem%period()
    total = transient_periods + n_periods
    t_end = total*period
    ! steps end on the forcing periods' boundaries, so that the renormalisations and the
    ! measured time are whole periods (on a periodic orbit the sum of the exponents is then
    ! the mean divergence over a period, not shifted by a step's part of one)
    if (setup%options%breakpoint_step <= 0) then
      setup%options%breakpoint_step = period
      setup%options%breakpoint_end = t_end
    end if
    allocate (z(n*(m + 1)), sum_log(m), growth(m), weighted_log(m))
    z(1:n) = y0
    ! a generic start frame (not aligned with any coordinate): columns of the Hilbert matrix
    do j = 1, m
      z(n*j + 1:n*j + n) = [(1.0_wp/(i + j - 1), i = 1, n)]
    end do
    call orthonormalise(z(n + 1:), growth)
    call new_integrator(method, setup%options%rtol, integ, status, message)
    if (status == SD_OK) call integ%init(setup%sys, 0.0_wp, z, t_end, setup%options, status, &
                                         message)
    if (status /= SD_OK) then
      message = 'Lyapunov exponent: '//trim(message)
      return
    end if

    measuring = transient_periods == 0
    t_start = 0
    t_last = t_start
    sum_log = 0
    weighted_log = 0
    weight_time = 0
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
      ! renormalise (V = Q R); the growths R(j, j) since the last renormalisation count once
      ! measuring
      z = integ%y
      call orthonormalise(z(n + 1:), growth)
      do j = 1, m
        if (.not. (growth(j) > 0 .and. growth(j) <= huge(growth))) then
          status = SD_NON_FINITE
          message = 'the tangent vector norm is '//num2str(growth(j))//' at tau = '// &
                    num2str(integ%t)//' (renormalise more often)'
          return
        end if
      end do
      if (measuring) then
        sum_log = sum_log + log(growth)
        ! the weight at the interval's midpoint s in the measured time (0 < s < 1)
        s = ((t_last + integ%t)/2 - t_start)/(t_end - t_start)
        weighted_log = weighted_log + exp(-1/(s*(1 - s)))*log(growth)
        weight_time = weight_time + exp(-1/(s*(1 - s)))*(integ%t - t_last)
      end if
      t_last = integ%t
      do while (next_count <= total)
        if (next_count*period > integ%t) exit
        if (next_count > transient_periods) then
          blocks_done = blocks_done + 1
          history(:, blocks_done) = sum_log/(integ%t - t_start)
        end if
        next_count = next_boundary(next_count)
      end do
      if (.not. measuring .and. integ%t >= transient_periods*period) then
        measuring = .true.
        t_start = integ%t
      end if
      call integ%set_state(setup%sys, z, status, message)
      if (status /= SD_OK) then
        message = 'Lyapunov exponent, renormalising at tau = '//num2str(integ%t)//': '// &
                  trim(message)
        return
      end if
    end do
    if (averaging == AVERAGE_WEIGHTED) then
      exponents = weighted_log/weight_time
    else
      exponents = sum_log/(t_end - t_start)
    end if
    ! decreasing order, the history's rows with them
    allocate (order(m))
    call sort_index(-exponents, order)
    exponents = exponents(order)
    history = history(order, :)

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

    !> Modified Gram-Schmidt on the m columns of length n stored one after another in v:
    !> v := Q, r_diag = diag(R). A column with r_diag not > 0 is left unscaled.
    pure subroutine orthonormalise(v, r_diag)
      real(wp), intent(inout) :: v(:)
      real(wp), intent(out) :: r_diag(:)
      integer :: a, b
      do b = 1, m
        associate (vb => v(n*(b - 1) + 1:n*b))
          do a = 1, b - 1
            vb = vb - dot_product(v(n*(a - 1) + 1:n*a), vb)*v(n*(a - 1) + 1:n*a)
          end do
          r_diag(b) = norm2(vb)
          if (r_diag(b) > 0) vb = vb/r_diag(b)
        end associate
      end do
    end subroutine orthonormalise
  end subroutine lyapunov_spectrum

  !> The Kaplan-Yorke (Lyapunov) dimension of exponents in decreasing order: D = k +
  !> (l_1 + .. + l_k)/|l_{k+1}| with k the largest count whose partial sum is >= 0; 0 when
  !> l_1 < 0 and n when the sum of all n is >= 0 (Kaplan and Yorke 1979).
  pure real(wp) function kaplan_yorke(exponents) result(d_ky)
    real(wp), intent(in) :: exponents(:)
    real(wp) :: partial
    integer :: k
    d_ky = 0
    partial = 0
    do k = 1, size(exponents)
      if (partial + exponents(k) < 0) then
        if (k > 1) d_ky = (k - 1) + partial/abs(exponents(k))
        return
      end if
      partial = partial + exponents(k)
    end do
    d_ky = size(exponents)
  end function kaplan_yorke

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
