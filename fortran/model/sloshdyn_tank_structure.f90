!> The tank's structure for the design check's structural checks (&tank_structure; docs/
!> namelist.md): shell courses (or concrete wall lifts) with their thickness and strength, the
!> bottom and its annulus, the roof's mass and height, the anchorage and the foundation's
!> friction; and what follows from them (shell_of): each course's mass and height, the masses
!> of shell, roof and bottom with their heights, and the equivalent uniform thickness.
!>
!> Masses: a circular course is the annulus rho pi t (D + t) h (D the inside diameter), a
!> rectangular tank's walls rho h (2 t (L + W) + 4 t^2) (L, W inside); the bottom plate
!> rho pi D^2/4 t_b (circular) or rho L W t_b. Thicknesses in mm and strengths in MPa as the
!> codes' SI editions write them; lengths in m.
module sloshdyn_tank_structure
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, check_real
  use sloshdyn_text, only: num2str
  use sloshdyn_vessel, only: tank_t
  use sloshdyn_tank, only: SHAPE_CIRCULAR
  implicit none
  private
  public :: tank_structure_t, shell_t, check_structure, shell_of, tank_top_height, &
            max_courses, material_names, anchorage_names, MATERIAL_STEEL, MATERIAL_CONCRETE, &
            ANCHORAGE_SELF, ANCHORAGE_MECHANICAL

  integer, parameter :: max_courses = 16
  integer, parameter :: MATERIAL_STEEL = 1, MATERIAL_CONCRETE = 2
  character(len=*), parameter :: material_names(2) = [character(len=8) :: 'steel', 'concrete']
  integer, parameter :: ANCHORAGE_SELF = 1, ANCHORAGE_MECHANICAL = 2
  character(len=*), parameter :: anchorage_names(2) = [character(len=10) :: 'self', &
                                                       'mechanical']
  !> Defaults of the wall's material: E [MPa] of steel; densities [kg/m^3].
  real(wp), parameter :: steel_modulus = 200000, steel_density = 7850, concrete_density = 2400
  !> The sum of the courses' heights equals the tank's height to this relative tolerance.
  real(wp), parameter :: height_tolerance = 1.0e-6_wp

  !> &tank_structure (courses bottom first; a course height 0 ends the list). Strengths 0
  !> mean "as the course below"; modulus and density 0 the material's default.
  type :: tank_structure_t
    logical :: given = .false.
    integer :: material = MATERIAL_STEEL
    real(wp), dimension(max_courses) :: course_height = 0, course_thickness = 0, &
                                        course_yield_strength = 0, course_tensile_strength = 0
    real(wp) :: corrosion_allowance = 0, joint_efficiency = 1, elastic_modulus = 0, density = 0
    real(wp) :: bottom_thickness = 0, annular_thickness = 0, bottom_corrosion_allowance = 0, &
                annular_yield_strength = 0
    real(wp) :: roof_mass = 0, roof_mass_height = 0
    integer :: anchorage = ANCHORAGE_SELF, anchor_count = 0
    real(wp) :: anchor_capacity = 0, friction = 0.4_wp
  end type tank_structure_t

  !> What follows from the structure: courses, each course's bottom z [m], mass [kg], corroded
  !> thickness [mm], F_y and F_t [MPa] (resolved); the shell's mass and the height of its
  !> centre X_s [m]; the roof's X_r [m]; the bottom's mass [kg]; the wall's E [MPa] and
  !> density [kg/m^3]; the equivalent uniform thickness t_u over the wetted height [mm].
  type :: shell_t
    integer :: courses = 0
    real(wp), dimension(max_courses) :: bottom = 0, mass = 0, corroded = 0, yield = 0, &
                                        tensile = 0
    real(wp) :: shell_mass = 0, shell_height = 0, roof_height = 0, bottom_mass = 0
    real(wp) :: modulus = 0, density = 0, uniform_thickness = 0
  end type shell_t

contains

  !> The tank's height with its roof [m]: liquid depth, freeboard and the roof's rise above the
  !> shell (a cone: R tan(alpha); a dome: R_d - sqrt(R_d^2 - R^2); flat: 0).
  pure real(wp) function tank_top_height(tank) result(top)
    type(tank_t), intent(in) :: tank
    top = tank%liquid_depth + tank%freeboard
    if (tank%shape /= SHAPE_CIRCULAR) return
    if (tank%roof_slope > 0) then
      top = top + tank%radius*tan(tank%roof_slope*pi/180)
    else if (tank%roof_radius > 0) then
      top = top + tank%roof_radius - sqrt(max(tank%roof_radius**2 - tank%radius**2, 0.0_wp))
    end if
  end function tank_top_height

  !> The structure's variables in their ranges and consistent with the tank (the message
  !> names the variable, its value and the rule).
  pure subroutine check_structure(tank, st, status, message)
    type(tank_t), intent(in) :: tank
    type(tank_structure_t), intent(in) :: st
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    integer :: n, k
    real(wp) :: total, f_y, f_t
    logical :: steel
    if (status /= SD_OK .or. .not. st%given) return
    steel = st%material == MATERIAL_STEEL
    if (st%material /= MATERIAL_STEEL .and. st%material /= MATERIAL_CONCRETE) then
      status = SD_BAD_INPUT
      message = 'material = '//num2str(st%material)//' is out of range: steel or concrete'
      return
    end if
    n = course_count(st)
    if (n == 0) then
      status = SD_BAD_INPUT
      message = 'course_height(1) = '//num2str(st%course_height(1))//' is out of range: '// &
                'the bottom course''s height is required, > 0 [m]'
      return
    end if
    call check_real('corrosion_allowance', st%corrosion_allowance, 0.0_wp, 100.0_wp, .false., &
                    .false., 'the shell''s corrosion allowance must be in [0, 100] [mm]', &
                    status, message)
    f_y = 0
    f_t = 0
    do k = 1, n
      call check_real('course_height('//num2str(k)//')', st%course_height(k), 0.0_wp, &
                      100.0_wp, .true., .false., 'a course''s height must be in (0, 100] [m]', &
                      status, message)
      call check_real('course_thickness('//num2str(k)//')', st%course_thickness(k), &
                      st%corrosion_allowance, 3000.0_wp, .true., .false., 'a course''s '// &
                      'thickness must be in (corrosion_allowance = '// &
                      num2str(st%corrosion_allowance)//', 3000] [mm]', status, message)
      if (st%course_yield_strength(k) /= 0 .or. (steel .and. k == 1)) &
        call check_real('course_yield_strength('//num2str(k)//')', &
                        st%course_yield_strength(k), 0.0_wp, 1000.0_wp, .true., .false., &
                        'F_y must be in (0, 1000] [MPa] (0 above the bottom course: as the '// &
                        'course below; the bottom course''s is required for steel)', status, &
                        message)
      if (st%course_yield_strength(k) > 0) f_y = st%course_yield_strength(k)
      if (st%course_tensile_strength(k) /= 0 .or. (steel .and. k == 1)) &
        call check_real('course_tensile_strength('//num2str(k)//')', &
                        st%course_tensile_strength(k), f_y, 2000.0_wp, .false., .false., &
                        'F_t must be in [F_y = '//num2str(f_y)//', 2000] [MPa] (0 above the '// &
                        'bottom course: as the course below; the bottom course''s is '// &
                        'required for steel)', status, message)
      if (st%course_tensile_strength(k) > 0) f_t = st%course_tensile_strength(k)
      if (status == SD_OK .and. f_t > 0 .and. f_t < f_y) then
        status = SD_BAD_INPUT
        message = 'course_yield_strength('//num2str(k)//') = '//num2str(f_y)//' is out of '// &
                  'range: F_y must not exceed the course''s F_t = '//num2str(f_t)//' [MPa]'
      end if
    end do
    do k = n + 1, max_courses
      if (status == SD_OK .and. (st%course_height(k) /= 0 .or. st%course_thickness(k) /= 0)) then
        status = SD_BAD_INPUT
        message = 'course_height('//num2str(k)//') = '//num2str(st%course_height(k))// &
                  ' and course_thickness('//num2str(k)//') = '// &
                  num2str(st%course_thickness(k))//': a course above a course of height 0 '// &
                  '(the list ends at the first 0)'
      end if
    end do
    total = sum(st%course_height(1:n))
    if (status == SD_OK .and. abs(total - (tank%liquid_depth + tank%freeboard)) > &
        height_tolerance*(tank%liquid_depth + tank%freeboard)) then
      status = SD_BAD_INPUT
      message = 'course_height: their sum '//num2str(total)//' m is out of range: it must '// &
                'equal liquid_depth + freeboard = '// &
                num2str(tank%liquid_depth + tank%freeboard)//' m (the roof meets the shell''s top)'
    end if
    call check_real('joint_efficiency', st%joint_efficiency, 0.0_wp, 1.0_wp, .true., .false., &
                    'the joint efficiency E must be in (0, 1]', status, message)
    if (st%elastic_modulus /= 0 .or. .not. steel) &
      call check_real('elastic_modulus', st%elastic_modulus, 0.0_wp, 1.0e6_wp, .true., .false., &
                      'E must be in (0, 1e6] [MPa] (0: 200 000 for steel; required for '// &
                      'concrete)', status, message)
    call check_real('density', st%density, 0.0_wp, 30000.0_wp, .false., .false., &
                    'the wall''s density must be in [0, 30000] [kg/m^3] (0: 7850 steel, '// &
                    '2400 concrete)', status, message)
    call check_real('bottom_thickness', st%bottom_thickness, 0.0_wp, 3000.0_wp, .false., &
                    .false., 'the bottom plate''s thickness must be in [0, 3000] [mm] (0: '// &
                    'not weighed)', status, message)
    call check_real('annular_thickness', st%annular_thickness, 0.0_wp, 3000.0_wp, .false., &
                    .false., 'the annulus'' thickness must be in [0, 3000] [mm] (0: the '// &
                    'bottom plate)', status, message)
    call check_real('bottom_corrosion_allowance', st%bottom_corrosion_allowance, 0.0_wp, &
                    merge(st%annular_thickness, st%bottom_thickness, st%annular_thickness > 0), &
                    .false., st%annular_thickness > 0 .or. st%bottom_thickness > 0, &
                    'the bottom''s corrosion allowance must be in [0, t_a) [mm] (t_a: the '// &
                    'annulus, or the bottom plate)', status, message)
    call check_real('annular_yield_strength', st%annular_yield_strength, 0.0_wp, 1000.0_wp, &
                    .false., .false., 'F_y of the annulus must be in [0, 1000] [MPa] (0: the '// &
                    'bottom course''s)', status, message)
    call check_real('roof_mass', st%roof_mass, 0.0_wp, 1.0e10_wp, .false., .false., &
                    'the roof''s mass must be in [0, 1e10] [kg]', status, message)
    call check_real('roof_mass_height', st%roof_mass_height, 0.0_wp, tank_top_height(tank), &
                    .false., .false., 'the roof''s centre of mass must lie within the tank: '// &
                    '[0, '//num2str(tank_top_height(tank))//'] [m] (0: the shell''s top)', &
                    status, message)
    if (status == SD_OK .and. st%anchorage /= ANCHORAGE_SELF .and. &
        st%anchorage /= ANCHORAGE_MECHANICAL) then
      status = SD_BAD_INPUT
      message = 'anchorage = '//num2str(st%anchorage)//' is out of range: self or mechanical'
    end if
    if (status == SD_OK .and. st%anchorage == ANCHORAGE_MECHANICAL .and. &
        (st%anchor_count < 4 .or. st%anchor_count > 10000)) then
      status = SD_BAD_INPUT
      message = 'anchor_count = '//num2str(st%anchor_count)//' is out of range: a '// &
                'mechanically anchored tank needs [4, 10000] anchors'
    end if
    if (st%anchorage == ANCHORAGE_MECHANICAL) &
      call check_real('anchor_capacity', st%anchor_capacity, 0.0_wp, 1.0e10_wp, .true., .false., &
                      'a mechanically anchored tank needs the allowable seismic load of one '// &
                      'anchor, in (0, 1e10] [N]', status, message)
    call check_real('friction', st%friction, 0.0_wp, 1.0_wp, .true., .false., &
                    'the friction coefficient mu must be in (0, 1] (API 650 E.7.6: 0.4)', &
                    status, message)
  end subroutine check_structure

  !> The number of courses: up to the first of height 0.
  pure integer function course_count(st) result(n)
    type(tank_structure_t), intent(in) :: st
    n = 0
    do while (n < max_courses)
      if (st%course_height(n + 1) == 0) exit
      n = n + 1
    end do
  end function course_count

  !> The shell's courses, masses and heights from a checked structure (check_structure).
  pure function shell_of(tank, st) result(shell)
    type(tank_t), intent(in) :: tank
    type(tank_structure_t), intent(in) :: st
    type(shell_t) :: shell
    real(wp) :: z, t, wetted
    integer :: k
    logical :: steel
    steel = st%material == MATERIAL_STEEL
    shell%courses = course_count(st)
    shell%modulus = merge(steel_modulus, st%elastic_modulus, st%elastic_modulus == 0)
    shell%density = st%density
    if (st%density == 0) shell%density = merge(steel_density, concrete_density, steel)
    z = 0
    do k = 1, shell%courses
      shell%bottom(k) = z
      t = st%course_thickness(k)/1000
      if (tank%shape == SHAPE_CIRCULAR) then
        shell%mass(k) = shell%density*pi*t*(2*tank%radius + t)*st%course_height(k)
      else
        shell%mass(k) = shell%density*st%course_height(k)*(2*t*(tank%length + tank%width) + &
                                                            4*t**2)
      end if
      shell%corroded(k) = st%course_thickness(k) - st%corrosion_allowance
      shell%yield(k) = st%course_yield_strength(k)
      shell%tensile(k) = st%course_tensile_strength(k)
      if (k > 1) then         ! 0: as the course below
        if (shell%yield(k) == 0) shell%yield(k) = shell%yield(k - 1)
        if (shell%tensile(k) == 0) shell%tensile(k) = shell%tensile(k - 1)
      end if
      ! the wetted part of the course, for the equivalent uniform thickness
      wetted = max(min(z + st%course_height(k), tank%liquid_depth) - z, 0.0_wp)
      shell%uniform_thickness = shell%uniform_thickness + st%course_thickness(k)*wetted
      z = z + st%course_height(k)
    end do
    shell%uniform_thickness = shell%uniform_thickness/tank%liquid_depth
    shell%shell_mass = sum(shell%mass(1:shell%courses))
    shell%shell_height = sum(shell%mass(1:shell%courses)*(shell%bottom(1:shell%courses) + &
                             st%course_height(1:shell%courses)/2))/shell%shell_mass
    shell%roof_height = merge(z, st%roof_mass_height, st%roof_mass_height == 0)
    if (tank%shape == SHAPE_CIRCULAR) then
      shell%bottom_mass = shell%density*pi*tank%radius**2*st%bottom_thickness/1000
    else
      shell%bottom_mass = shell%density*tank%length*tank%width*st%bottom_thickness/1000
    end if
  end function shell_of
end module sloshdyn_tank_structure
