!> Two-parameter curves of the full model's periodic orbits in (rho, A): folds (a Floquet
!> multiplier +1), period doublings (-1) and Neimark-Sacker points (a pair e^{+-i theta}) of the
!> orbits of period k T (T = 2 pi/rho), with their codimension-2 points (1:1, 1:2, 1:3, 1:4
!> resonances, cusps of orbits, fold-flip, fold-NS, flip-NS). The tank's equations of motion
!> (eq 15 with 29-31, sloshdyn_system) give the stroboscopic map P(y0; rho, A) = y(k T) by
!> shooting; sloshdyn_map_bifurcation holds the defining systems and sloshdyn_bifurcation traces
!> the curves, so the result is a bifurcation_curve with p = (rho, A), x = the orbit's state at
!> forcing phase 0, eig_re/eig_im its Floquet multipliers and, on Neimark-Sacker curves, omega =
!> theta (the torus' rotation angle per k T).
!>
!> A curve starts at a point of the kind (approximately: it is first corrected at fixed A, or at
!> fixed rho), e.g. one that periodic_response located (orbit_curve_from_special).
module sloshdyn_orbit_chart
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, check_real
  use sloshdyn_text, only: num2str
  use sloshdyn_model, only: model_t
  use sloshdyn_excitation, only: excitation_t, PARAMETER_RHO, PARAMETER_A, forcing_period
  use sloshdyn_system, only: tank_system
  use sloshdyn_ode, only: ode_options, check_options
  use sloshdyn_integrator, only: check_method, METHOD_AUTO
  use sloshdyn_shooting, only: periodic_problem
  use sloshdyn_continuation, only: continuation_options
  use sloshdyn_bifurcation, only: curve_options, bifurcation_curve, check_curve_options, &
                                  curve_of_kind, CURVE_FOLD, CURVE_PERIOD_DOUBLING, &
                                  CURVE_NEIMARK_SACKER
  use sloshdyn_map_bifurcation, only: stroboscopic_map
  use sloshdyn_tables, only: SPECIAL_FOLD, SPECIAL_BRANCH_POINT, SPECIAL_PERIOD_DOUBLING, &
                             SPECIAL_NEIMARK_SACKER, special_kind_name
  implicit none
  private
  public :: tank_orbit_map, orbit_chart_options, make_orbit_map, check_orbit_chart_options
  public :: orbit_fold_curve, orbit_period_doubling_curve, orbit_neimark_sacker_curve, &
            orbit_curve_from_special

  !> The tank's stroboscopic map with p = (rho, A); the rest of the model is fixed.
  type, extends(stroboscopic_map) :: tank_orbit_map
    type(model_t) :: model
  contains
    procedure :: problem => tank_problem
  end type tank_orbit_map

  !> Settings of a curve of orbits. The curve's scales and steps default to the paper's
  !> resonance (Fig 12: orbits of amplitude ~0.05, rho moving by ~1e-3 and A by ~1e-4).
  type :: orbit_chart_options
    type(curve_options) :: curve = curve_options(p_min=[1.0e-3_wp, 0.0_wp], x_scale=0.05_wp, &
      p_scale=[1.0e-3_wp, 1.0e-4_wp], max_points=400, segment_points=25, &
      continuation=continuation_options(ds=0.05_wp, ds_min=1.0e-8_wp, ds_max=1.0_wp))
    !> the shots; their rtol sets the finite-difference steps of the derivatives of M
    !> (rtol^(1/3) times x_scale and p_scale, sloshdyn_map_bifurcation): 1e-12 keeps those
    !> ~1e-8 relative and the curve's multipliers on the circle to ~1e-10
    type(ode_options) :: integration = ode_options(rtol=1.0e-12_wp, atol=1.0e-14_wp)
    !> auto: Verner 9(8) at rtol = 1e-12 (DOP853 takes about a quarter of DOPRI5's time there)
    integer :: method = METHOD_AUTO
    integer :: periods = 1   !< orbits of period periods*T, >= 1
  end type orbit_chart_options

contains

  !> The map of the model's tank (its rho and A are replaced by p along a curve).
  subroutine make_orbit_map(model, options, map, status, message)
    type(model_t), intent(in) :: model
    type(orbit_chart_options), intent(in) :: options
    type(tank_orbit_map), intent(out) :: map
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(excitation_t) :: probe
    real(wp) :: fraction
    status = SD_OK
    message = ''
    call check_orbit_chart_options(options, status, message)
    if (status /= SD_OK) return
    ! rho and A are those of a harmonic excitation; another kind has no forcing period at any rho
    probe = model%excitation
    probe%rho = 1
    if (.not. forcing_period(probe) < huge(1.0_wp)) then
      status = SD_BAD_INPUT
      message = 'the excitation has no forcing period: curves of periodic orbits in (rho, A) '// &
                'need the harmonic excitation X = A sin(rho tau)'
      return
    end if
    map%model = model
    map%periods = options%periods
    map%method = options%method
    map%integration = options%integration
    ! steps balancing truncation and integration noise (sloshdyn_map_bifurcation header)
    fraction = max(options%integration%rtol, epsilon(1.0_wp))**(1.0_wp/3)
    map%x_step = fraction*options%curve%x_scale
    map%p_step = fraction*options%curve%p_scale
  end subroutine make_orbit_map

  !> The rules of orbit_chart_options (those of curve_options and of the integrator, the box
  !> inside rho > 0, periods >= 1).
  subroutine check_orbit_chart_options(options, status, message)
    type(orbit_chart_options), intent(in) :: options
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    if (status /= SD_OK) return
    call check_curve_options(options%curve, status, message)
    call check_real('p_min(1) (rho_min)', options%curve%p_min(1), 0.0_wp, huge(1.0_wp), &
                    .true., .false., 'the forcing frequency must stay > 0', status, message)
    call check_options(options%integration, [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], status, message)
    call check_method(options%method, status, message)
    if (status == SD_OK .and. options%periods < 1) then
      status = SD_BAD_INPUT
      message = 'periods = '//num2str(options%periods)//' is out of range: it must be >= 1'
    end if
  end subroutine check_orbit_chart_options

  !> The fold curve of orbits through (y0, p0 = (rho, A)), an orbit with a multiplier near +1.
  subroutine orbit_fold_curve(model, y0, p0, options, curve, status, message)
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: y0(4), p0(2)
    type(orbit_chart_options), intent(in) :: options
    type(bifurcation_curve), intent(out) :: curve
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    call orbit_curve(model, CURVE_FOLD, 'orbit_fold_curve', y0, p0, options, curve, status, &
                     message)
  end subroutine orbit_fold_curve

  !> The period-doubling curve through (y0, p0), an orbit with a multiplier near -1.
  subroutine orbit_period_doubling_curve(model, y0, p0, options, curve, status, message)
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: y0(4), p0(2)
    type(orbit_chart_options), intent(in) :: options
    type(bifurcation_curve), intent(out) :: curve
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    call orbit_curve(model, CURVE_PERIOD_DOUBLING, 'orbit_period_doubling_curve', y0, p0, &
                     options, curve, status, message)
  end subroutine orbit_period_doubling_curve

  !> The Neimark-Sacker curve through (y0, p0), an orbit with a complex multiplier pair near
  !> the unit circle.
  subroutine orbit_neimark_sacker_curve(model, y0, p0, options, curve, status, message)
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: y0(4), p0(2)
    type(orbit_chart_options), intent(in) :: options
    type(bifurcation_curve), intent(out) :: curve
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    call orbit_curve(model, CURVE_NEIMARK_SACKER, 'orbit_neimark_sacker_curve', y0, p0, &
                     options, curve, status, message)
  end subroutine orbit_neimark_sacker_curve

  !> The curve through a special point of periodic_response (a column of its `special`:
  !> [kind, lambda, y0(1:4), max|x1|]) computed in `parameter` (PARAMETER_RHO or PARAMETER_A)
  !> for the model, whose other parameter completes p0: a fold, period-doubling or
  !> Neimark-Sacker curve (a branch point has no curve of its own).
  subroutine orbit_curve_from_special(model, parameter, special, options, curve, status, message)
    type(model_t), intent(in) :: model
    integer, intent(in) :: parameter
    real(wp), intent(in) :: special(:)
    type(orbit_chart_options), intent(in) :: options
    type(bifurcation_curve), intent(out) :: curve
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: p0(2)
    integer :: kind

    status = SD_BAD_INPUT
    if (parameter /= PARAMETER_RHO .and. parameter /= PARAMETER_A) then
      message = 'orbit_curve_from_special: parameter = '//num2str(parameter)//' is out of '// &
                'range: PARAMETER_RHO or PARAMETER_A'
    else if (size(special) < 6) then
      message = 'orbit_curve_from_special: special has '//num2str(size(special))// &
                ' entries; a column of periodic_response has [kind, lambda, y0(1:4), max|x1|]'
    else
      select case (nint(special(1)))
      case (SPECIAL_FOLD)
        kind = CURVE_FOLD
      case (SPECIAL_PERIOD_DOUBLING)
        kind = CURVE_PERIOD_DOUBLING
      case (SPECIAL_NEIMARK_SACKER)
        kind = CURVE_NEIMARK_SACKER
      case (SPECIAL_BRANCH_POINT)
        kind = 0
        message = 'orbit_curve_from_special: special(1) = '//num2str(nint(special(1)))// &
                  ' is a '//special_kind_name(SPECIAL_BRANCH_POINT)//', which has no curve '// &
                  'of its own (a fold, period doubling or Neimark-Sacker point has)'
      case default
        kind = 0
        message = 'orbit_curve_from_special: special(1) = '//num2str(special(1))// &
                  ' is not a kind of special point of periodic_response'
      end select
      if (kind /= 0) status = SD_OK
    end if
    if (status /= SD_OK) then
      curve%status = status
      curve%message = message
      return
    end if
    if (parameter == PARAMETER_RHO) then
      p0 = [special(2), model%excitation%A]
    else
      p0 = [model%excitation%rho, special(2)]
    end if
    call orbit_curve(model, kind, 'orbit_curve_from_special ('//special_kind_name(nint( &
                     special(1)))//')', special(3:6), p0, options, curve, status, message)
  end subroutine orbit_curve_from_special

  ! ---- private --------------------------------------------------------------------------------

  !> The tank at p = (rho, A) with lambda = p(varied).
  subroutine tank_problem(self, p, varied, problem)
    class(tank_orbit_map), intent(in) :: self
    real(wp), intent(in) :: p(2)
    integer, intent(in) :: varied
    class(periodic_problem), allocatable, intent(out) :: problem
    allocate (tank_system :: problem)
    select type (problem)
    type is (tank_system)
      problem%model = self%model
      problem%model%excitation%rho = p(1)
      problem%model%excitation%A = p(2)
      problem%varied = merge(PARAMETER_RHO, PARAMETER_A, varied == 1)
    end select
  end subroutine tank_problem

  !> Build the map and trace the curve (status and message also in the curve).
  subroutine orbit_curve(model, kind, caller, y0, p0, options, curve, status, message)
    type(model_t), intent(in) :: model
    integer, intent(in) :: kind
    character(len=*), intent(in) :: caller
    real(wp), intent(in) :: y0(4), p0(2)
    type(orbit_chart_options), intent(in) :: options
    type(bifurcation_curve), intent(out) :: curve
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(tank_orbit_map) :: map

    call make_orbit_map(model, options, map, status, message)
    if (status /= SD_OK) then
      message = caller//': '//trim(message)
      curve%status = status
      curve%message = message
      return
    end if
    call curve_of_kind(map, kind, caller, y0, p0, options%curve, curve, status, message)
  end subroutine orbit_curve
end module sloshdyn_orbit_chart
