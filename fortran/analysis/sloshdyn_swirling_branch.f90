!> The branch of swirling periodic orbits born at a swirl edge (issue 41).
!>
!> At an edge of the swirl band where an out-of-plane multiplier passes through +1
!> (sloshdyn_swirl) the planar orbit is a symmetry-breaking pitchfork of the spatial periodic
!> problem (the mirror y -> -y maps orbits to orbits): the swirling orbits leave it along the
!> critical out-of-plane Floquet eigenvector with dlambda/ds = 0 (sloshdyn_shooting's
!> switch_branch, Kuznetsov, Elements of Applied Bifurcation Theory, 3rd ed., section 7.4). They
!> are continued in rho or A on the 8 states by sloshdyn_shooting's periodic_branch, with their
!> 8 Floquet multipliers and special points (folds, branch points, period doublings,
!> Neimark-Sacker points: quasi-periodic swirl), and at each point max|x1|, the swirl amplitude
!> max|y1| and the mean angular momentum (sloshdyn_swirl's orbit_measures).
!>
!> Layouts (sloshdyn_tables): 'swirling_branch' points(:, j) = [lambda, y0(1:8), max|x1|,
!> swirl amplitude, angular momentum, stable (1/0), Re mu(1:8), Im mu(1:8)];
!> 'swirling_special_points' special(:, j) = [kind (SPECIAL_*), lambda, y0(1:8), max|x1|].
module sloshdyn_swirling_branch
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT
  use sloshdyn_text, only: num2str
  use sloshdyn_ode, only: ode_options
  use sloshdyn_continuation, only: continuation_options
  use sloshdyn_shooting, only: switch_branch
  use sloshdyn_tables, only: SWIRLING_BRANCH_ROWS, SWIRLING_SPECIAL_ROWS, SPECIAL_BRANCH_POINT
  use sloshdyn_model, only: model_t
  use sloshdyn_spatial, only: spatial_model
  use sloshdyn_spatial_system, only: spatial_tank_system
  use sloshdyn_swirl, only: orbit_measures
  implicit none
  private
  public :: swirling_branch

contains

  !> The swirling orbits (period k T) born at the swirl edge through the planar orbit y_edge
  !> (x1, x1', x2, x2' at tau = 0) of model, whose parameter (PARAMETER_RHO or PARAMETER_A)
  !> is at the edge, continued over [lambda_min, lambda_max] (continuation%ds: the first step
  !> off the edge along the critical eigenvector). points(SWIRLING_BRANCH_ROWS,
  !> >= continuation%max_points), special(SWIRLING_SPECIAL_ROWS, any): layouts in the module
  !> header; complete as sloshdyn_shooting's periodic_branch.
  subroutine swirling_branch(model, parameter, y_edge, k, lambda_min, lambda_max, continuation, &
                             options, method, points, n_points, special, n_special, complete, &
                             status, message)
    type(model_t), intent(in) :: model
    integer, intent(in) :: parameter, k, method
    real(wp), intent(in) :: y_edge(4), lambda_min, lambda_max
    type(continuation_options), intent(in) :: continuation
    type(ode_options), intent(in) :: options
    real(wp), intent(out) :: points(:, :), special(:, :)
    integer, intent(out) :: n_points, n_special, status
    logical, intent(out) :: complete
    character(len=message_len), intent(out) :: message
    type(spatial_tank_system) :: system
    real(wp), allocatable :: branch(:, :), multipliers(:, :)
    integer :: j, k_new, st
    character(len=message_len) :: msg

    points = ieee_value(1.0_wp, ieee_quiet_nan)
    special = points(1, 1)
    n_points = 0
    n_special = 0
    complete = .false.
    if (size(points, 1) /= SWIRLING_BRANCH_ROWS .or. size(special, 1) /= SWIRLING_SPECIAL_ROWS &
        .or. size(points, 2) < continuation%max_points) then
      status = SD_BAD_INPUT
      message = 'points must be '//num2str(SWIRLING_BRANCH_ROWS)//' x max_points and special '// &
                num2str(SWIRLING_SPECIAL_ROWS)//' x any'
      return
    end if
    call spatial_model(model, 0.0_wp, 0.0_wp, system%model, status, message)
    if (status /= SD_OK) return
    system%varied = parameter
    allocate (branch(11, max(continuation%max_points, 1)), &
              multipliers(16, max(continuation%max_points, 1)))
    call switch_branch(system, SPECIAL_BRANCH_POINT, [y_edge, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], &
                       k, lambda_min, lambda_max, continuation, options, method, branch, &
                       multipliers, n_points, special, n_special, complete, k_new, status, &
                       message)
    st = status
    msg = message
    do j = 1, n_points
      points(1:9, j) = branch(1:9, j)
      points(13, j) = branch(11, j)
      points(14:29, j) = multipliers(:, j)
      call system%set_parameter(branch(1, j))
      call orbit_measures(system, branch(2:9, j), k, options, method, points(10, j), &
                          points(11, j), points(12, j), status, message)
      if (status /= SD_OK) then
        message = 'swirling branch point '//num2str(j)//': '//trim(message)
        n_points = j - 1
        complete = .false.
        return
      end if
    end do
    status = st
    message = msg
  end subroutine swirling_branch
end module sloshdyn_swirling_branch
