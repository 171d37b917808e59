!> The design check's restricted-sloshing method (docs/design.md, "Roof loads from a design
!> spectrum"; docs/model.md, "Roof loads"): where a code's sloshing wave exceeds the freeboard
!> (API 650's delta_s of E.7.2-1, not Table E-7's reduced requirement; ACI 350.3's d_max;
!> EN 1998-4's d_max), the roof's head, the roof's uplift and the confined part of the
!> convective mass from that wave by sloshdyn_roof's formulas, the confined mass then moved from
!> the code's convective to its impulsive loads: the method of ASCE 7-16 15.7.6.1.2 as this
!> project reads it (the constrained convective mass treated as impulsive; the share's formula
!> is this project's, its text and Malhotra's papers were not at hand).
module sloshdyn_restricted_sloshing
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK
  use sloshdyn_vessel, only: tank_t
  use sloshdyn_tank, only: SHAPE_CIRCULAR
  use sloshdyn_roof, only: roof_loads
  use sloshdyn_design_report, only: design_report_t
  implicit none
  private
  public :: restricted_sloshing, method_name

  character(len=*), parameter :: method_name = 'the restricted-sloshing method of ASCE 7-16 '// &
    '15.7.6.1.2 as this project reads it (docs/model.md, Roof loads)'
  character(len=*), parameter :: clause = 'ASCE 7-16 15.7.6.1.2 (as read here)'

contains

  !> For a wave of height `wave` [m] at the wall (named with its clause in `wave_name`) of a
  !> tank of liquid density rho [kg/m^3] and convective mass m_c [kg] of the code: where the
  !> wave exceeds the freeboard, the steps and checks of the roof's loads and the confined mass
  !> m_conf [kg] (0 where the wave stays below the roof, and for a rectangular tank, whose roof
  !> loads sloshdyn_roof does not give: the report says so).
  subroutine restricted_sloshing(report, code, wave_name, tank, wave, density, m_c, m_conf, &
                                 status, message)
    type(design_report_t), intent(inout) :: report
    character(len=*), intent(in) :: code, wave_name
    type(tank_t), intent(in) :: tank
    real(wp), intent(in) :: wave, density, m_c
    real(wp), intent(out) :: m_conf
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: head, uplift, x
    status = SD_OK
    message = ''
    m_conf = 0
    if (wave <= tank%freeboard) return
    if (tank%shape /= SHAPE_CIRCULAR) then
      call report%note(code, 'the sloshing wave ('//wave_name//') exceeds the freeboard; the '// &
                       'roof''s loads and confined mass of a rectangular tank are not '// &
                       'computed (sloshdyn_roof is for circular tanks): the convective mass '// &
                       'stays convective', 'd − f', 'd > f', wave - tank%freeboard, 'm', clause)
      call report%info(code, 'wave above the roof (rectangular: roof loads not computed)', &
                       clause, wave - tank%freeboard, 'm')
      return
    end if
    call roof_loads(tank%radius, tank%freeboard, tank%roof_slope, tank%roof_radius, wave, &
                    density, tank%gravity, m_c, head, uplift, m_conf, status, message)
    if (status /= SD_OK) return
    call report%note(code, 'the sloshing wave ('//wave_name//') exceeds the freeboard: the '// &
                     'roof is loaded and the confined part of the convective mass moves with '// &
                     'the tank, impulsive, by '//method_name, 'd − f', 'd > f', &
                     wave - tank%freeboard, 'm', clause)
    x = report%step(code, 'roof head at the wall', 'h_roof', 'h_roof = d − f', '@ − @', &
                    [wave, tank%freeboard], head, 'm', clause)
    x = report%step(code, 'roof uplift: the free wave''s hydrostatic pressure above the '// &
                    'roof, integrated over its plan', 'F_roof', &
                    'F_roof = ρ g ∬ (η − z_roof)⁺ dA, η = d J₁(1.8412 r/R)/J₁(1.8412) cos a', &
                    'ρ = @, g = @, d = @, z_roof from f = @', &
                    [density, tank%gravity, wave, tank%freeboard], uplift, 'N', &
                    'docs/model.md, Roof loads')
    x = report%step(code, 'confined convective mass: the share of the wave''s first moment '// &
                    'above the roof', 'm_conf', 'm_conf = m_c ∬ x (η − z_roof)⁺ dA/∬ x η⁺ dA', &
                    'm_c = @', [m_c], m_conf, 'kg', 'docs/model.md, Roof loads')
    call report%info(code, 'roof head (restricted sloshing)', clause, head, 'm')
    call report%info(code, 'roof uplift (restricted sloshing)', clause, uplift, 'N')
    call report%info(code, 'confined convective mass, moved to impulsive', clause, m_conf, 'kg')
  end subroutine restricted_sloshing
end module sloshdyn_restricted_sloshing
