!> The f2py bridge of spatial.py: the spatial model of issue 26 (sloshdyn_spatial) and its swirl
!> analysis. The model crosses as the planar rpar, ipar (sloshdyn_model) plus spatial(2) =
!> [azimuth, ellipticity] (layout 'spatial' of sloshdyn_layouts). See sloshdyn_bridge_model for
!> the bridge's conventions.
module sloshdyn_bridge_spatial
  use, intrinsic :: iso_c_binding, only: c_double, c_int
  implicit none

contains

  !> The spatial equations at one state y = (x1, x1', x2, x2', y1, y1', y2, y2'): the inertia
  !> matrix (eq S7), y', the analytic Jacobian dy'/dy, and [energy, angular momentum about the
  !> vertical] (eq S2-S3).
  subroutine spatial_equations(rpar, ipar, spatial, tau, y, mass, dydt, jacobian, invariants, &
                               status, message)
    !f2py threadsafe
    use sloshdyn_model, only: n_real_params, n_int_params, model_t, model_from_arrays
    use sloshdyn_layouts, only: SPATIAL_SIZE
    use sloshdyn_status, only: SD_NON_FINITE
    use sloshdyn_spatial, only: spatial_model_t, spatial_model, spatial_mass_matrix, &
                                core_equations => spatial_equations, spatial_jacobian, &
                                spatial_invariants
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    real(c_double), intent(in) :: rpar(n_real_params), spatial(SPATIAL_SIZE), tau, y(8)
    integer(c_int), intent(in) :: ipar(n_int_params)
    real(c_double), intent(out) :: mass(4, 4), dydt(8), jacobian(8, 8), invariants(2)
    integer(c_int), intent(out) :: status
    character(len=256), intent(out) :: message
    type(model_t) :: planar
    type(spatial_model_t) :: model
    integer :: info
    mass = 0; dydt = 0; jacobian = 0; invariants = 0
    call model_from_arrays(rpar, int(ipar), planar, info, message)
    if (info == 0) call spatial_model(planar, spatial(1), spatial(2), model, info, message)
    status = info
    if (info /= 0) return
    call spatial_mass_matrix(model, y, mass)
    call core_equations(model, tau, y, dydt)
    call spatial_jacobian(model, tau, y, jacobian)
    call spatial_invariants(model, y, invariants(1), invariants(2))
    if (.not. (all(ieee_is_finite(mass)) .and. all(ieee_is_finite(dydt)) .and. &
               all(ieee_is_finite(jacobian)) .and. all(ieee_is_finite(invariants)))) then
      status = SD_NON_FINITE
      message = 'the spatial equations of motion overflow at this state'
      mass = 0; dydt = 0; jacobian = 0; invariants = 0
    end if
  end subroutine spatial_equations
end module sloshdyn_bridge_spatial
