!> A real tank in SI units and its mapping to the dimensionless model: the equivalent pendulum of
!> eq (2)-(3), the supports given by their natural frequency and damping ratio (or stiffness and
!> damping directly), the wall angle theta0 from the freeboard, the linear sloshing damping, and
!> the physical loads (SI) of a state of the model. Every front door uses these, so one tank
!> gives one model.
!>
!> Conventions (docs/model.md): x horizontal; the base moves by u(t); the tank (and the liquid
!> that does not slosh) by u + L sin(phi); the sloshing mass m by u + L sin(phi) + l sin(theta).
!> Heights are measured from the tank bottom.
!>
!> Freeboard and theta0: in linear potential flow, the first sloshing mode of a cylinder raises
!> the free surface at the wall by eta = 2 R sin(theta)/(xi^2 - 1) when the equivalent pendulum
!> (eq 2, xi = 1.84) swings by theta: equating the liquid's horizontal momentum,
!> rho pi R^2 (A J1(xi)) tanh(xi h/R)/xi, with that of the pendulum, m l cos(theta) theta', and
!> using eq (2) for m and l. The wave reaches the roof when eta = freeboard, which sets
!> sin(theta0) = freeboard (xi^2 - 1)/(2 R). (Eurocode 8-4 A.2.1.4 writes the same relation as
!> d_max = 0.84 R Se/g, with theta = Se/g.) A rectangular tank of length L (along the motion)
!> has the same relation with wave_factor = 4 L/pi^2 (sloshdyn_tank's sloshing_modes).
!>
!> Higher modes (modes = N > 1): modes 2..N are linear oscillators of sloshdyn_tank's
!> sloshing_modes, driven by the tank's acceleration; the rigid (impulsive) mass is m_F minus
!> the N modal masses. The paper's pendulum (mode 1) and its model are the same for every N.
!>
!> The roof (roof_contact): a tank's liquid feels no contact until its wave reaches the roof,
!> so the tank's model has no impact wall (beta = delta = 0, ROOF_CONTACT_NONE, the default);
!> above the roof the seismic run applies the restricted-sloshing method (sloshdyn_seismic).
!> The paper's smooth wall of eq (4)-(5) with the tank's impact_stiffness and impact_damping
!> is opt-in (ROOF_CONTACT_IMPACT), for its impact force only (docs/model.md, "Loads").
module sloshdyn_vessel
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, SD_NON_FINITE, check_real
  use sloshdyn_text, only: num2str
  use sloshdyn_model, only: model_t, model_from_arrays, n_real_params, set_coefficients
  use sloshdyn_roof, only: check_roof
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_is_finite
  use sloshdyn_tank, only: tank_pendulum, sloshing_modes, modal_wave_number, max_modes, &
                           shape_names, &
                           SHAPE_CIRCULAR, SHAPE_RECTANGULAR, min_tank_size, max_tank_size, &
                           max_liquid_density
  use sloshdyn_tables, only: SEISMIC_LOADS
  implicit none
  private
  public :: tank_t, tank_properties, tank_model, tank_loads, wave_height_factor
  public :: standard_gravity, LOAD_ROWS
  public :: roof_contact_names, ROOF_CONTACT_NONE, ROOF_CONTACT_IMPACT

  real(wp), parameter :: standard_gravity = 9.80665_wp   !< m/s^2
  !> xi = 1.84 of eq (2): the first root of J1', as the paper rounds it
  real(wp), parameter :: xi = 1.84_wp
  !> The largest wall angle of a tank's model [rad] (a freeboard beyond the linear wave's
  !> reach caps theta0 there, just below the model's bound pi/2).
  real(wp), parameter, public :: max_theta0 = 0.4999_wp*pi

  !> A cylindrical or rectangular tank on supports, SI units. Zero (or negative) means "not given" where an
  !> alternative exists: the liquid by its density or its mass; the supports by their natural
  !> frequency and damping ratio or by stiffness and damping coefficient.
  !> The convective (sloshing) damping ratio of the design codes, 0.5 %: the default of a
  !> tank's sloshing_damping and of every spectral acceleration's damping (&ground_motion
  !> target_damping, &study spectral_damping; Python's GroundMotion.scaled, response_spectrum).
  real(wp), parameter, public :: convective_damping = 0.005_wp

  !> How the liquid meets the roof (&tank roof_contact): 'none', no contact model (the tank's
  !> model is free below the roof; above it the restricted-sloshing method), or 'impact', the
  !> paper's smooth wall of eq (4)-(5) beside it, for its impact force (roof_contact_names in
  !> the order of the codes).
  integer, parameter :: ROOF_CONTACT_NONE = 1, ROOF_CONTACT_IMPACT = 2
  character(len=*), parameter :: roof_contact_names(*) = [character(len=6) :: 'none', 'impact']

  type :: tank_t
    real(wp) :: radius = 0                  !< R [m]
    real(wp) :: liquid_depth = 0            !< h [m]
    real(wp) :: freeboard = 0               !< liquid surface to roof [m]
    real(wp) :: liquid_density = 0          !< [kg/m^3] (or liquid_mass)
    real(wp) :: liquid_mass = 0             !< m_F [kg] (or liquid_density)
    real(wp) :: tank_mass = 0               !< shell and roof [kg]
    real(wp) :: support_frequency = 0       !< natural frequency of the tank on its supports [Hz]
    real(wp) :: support_damping = 0.05_wp   !< its damping ratio (of critical)
    real(wp) :: support_stiffness = 0       !< k [N m/rad] (instead of support_frequency)
    real(wp) :: support_damping_coefficient = 0   !< c [N m s/rad] (with support_stiffness)
    real(wp) :: support_height = 0          !< rod length L [m]; 0 = the tank's height h + freeboard
    real(wp) :: sloshing_damping = convective_damping !< linear, of critical for the sloshing mode
    real(wp) :: impact_stiffness = 10       !< beta: roof/wall impact moment over m g l at theta0
    real(wp) :: impact_damping = 0.1_wp     !< delta: dissipation at the wall (eq 5)
    integer :: n = 6, p = 2                 !< exponents of eq (4)-(5)
    real(wp) :: gravity = standard_gravity  !< [m/s^2]
    real(wp) :: roof_slope = 0              !< a cone roof's slope [degrees]; 0: not a cone
    real(wp) :: roof_radius = 0             !< a dome roof's radius [m]; 0: not a dome
    integer :: shape = SHAPE_CIRCULAR       !< SHAPE_CIRCULAR (radius) or SHAPE_RECTANGULAR
    real(wp) :: length = 0                  !< rectangular: L along the motion [m]
    real(wp) :: width = 0                   !< rectangular: W across it [m]
    integer :: modes = 1                    !< sloshing modes 1..N (N <= max_modes)
    integer :: roof_contact = ROOF_CONTACT_NONE  !< ROOF_CONTACT_NONE or ROOF_CONTACT_IMPACT
  end type tank_t

  !> What a tank is in the model's terms, and what the loads need.
  type :: tank_properties
    real(wp) :: liquid_mass = 0, total_mass = 0           !< m_F, M = m_F + tank mass [kg]
    real(wp) :: pendulum_length = 0, sloshing_mass = 0    !< l [m], m [kg] (eq 2)
    real(wp) :: d1 = 0, rigid_mass = 0, d0 = 0            !< eq (2)-(3) [m, kg, m]
    real(wp) :: omega = 0                                 !< sqrt(g/l) [rad/s]
    real(wp) :: sloshing_period = 0                       !< 2 pi/omega [s] (rigid tank)
    real(wp) :: rod_length = 0                            !< L [m]
    real(wp) :: stiffness = 0, damping = 0                !< k [N m/rad], c [N m s/rad]
    real(wp) :: theta0 = 0                                !< wall angle [rad]
    real(wp) :: convective_height = 0                     !< of m (wall pressures) [m]
    real(wp) :: impulsive_height = 0                      !< of m0 (wall pressures) [m]
    !> the base pressure's moment of the liquid moving rigidly, over m_F times its acceleration:
    !> R^2/(4 h) (circular), L^2/(12 h) (rectangular) [m]
    real(wp) :: rigid_base_arm = 0
    real(wp) :: shell_height = 0                          !< of the tank mass, (h + freeboard)/2
    real(wp) :: wave_factor = 0                           !< eta = wave_factor sin(theta) [m]
    real(wp) :: impact_coefficient = 0                    !< b = beta m g l [N m]
    !> .false. where the freeboard exceeds what the linear wave reaches (theta0 then capped
    !> at max_theta0; the roof verdicts compare the free wave with the freeboard itself)
    logical :: roof_reachable = .true.
    !> the sloshing modes 1..modes (mode 1: the pendulum above): period [s], mass [kg], height
    !> of its wall pressure's resultant and of its wall and base pressures' [m], pendulum length
    !> [m], wave at the wall per sin(theta_n) [m]
    integer :: modes = 1
    real(wp), dimension(max_modes) :: modal_period = 0, modal_mass = 0, modal_height = 0, &
                                      modal_height_ibp = 0, modal_length = 0, modal_wave = 0
  end type tank_properties

  !> Rows of tank_loads: t [s], ground acceleration [m/s^2], sloshing displacement l sin(theta)
  !> [m], wave height at the wall [m], pendulum angle [rad], tank drift L sin(phi) [m], the
  !> accelerations of the tank and of the convective mass [m/s^2], base shear [N], overturning
  !> moments excluding and including the base pressure [N m] (the 'seismic' table of
  !> sloshdyn_tables, which adds x1, x2 and the free wave).
  integer, parameter :: LOAD_ROWS = SEISMIC_LOADS

contains

  !> eta/sin(theta) = 2 R/(xi^2 - 1): the wave height at the wall per unit sin(theta).
  elemental real(wp) function wave_height_factor(radius)
    real(wp), intent(in) :: radius
    wave_height_factor = 2*radius/(xi**2 - 1)
  end function wave_height_factor

  !> The model of a tank (groups of eq 9, linear sloshing damping, no excitation yet) and its
  !> properties. The supports: from their frequency f_s and damping ratio zeta_s with all of M
  !> on them, M L^2 phi'' + c phi' + (k - M g L) phi = 0, so k = M L^2 (2 pi f_s)^2 + M g L and
  !> c = 2 zeta_s M L^2 (2 pi f_s); or k and c as given.
  pure subroutine tank_model(tank, model, props, status, message)
    type(tank_t), intent(in) :: tank
    type(model_t), intent(out) :: model
    type(tank_properties), intent(out) :: props
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp), parameter :: big = huge(1.0_wp)
    real(wp) :: omega_s, sin_theta0, rpar(n_real_params)

    status = SD_OK
    message = ''
    call check_shape(tank, status, message)
    if (status /= SD_OK) return
    if (tank%shape == SHAPE_CIRCULAR) &
      call check_real('radius', tank%radius, 0.0_wp, big, .true., .true., &
                      'the tank radius must be > 0 [m]', status, message)
    call check_real('liquid_depth', tank%liquid_depth, 0.0_wp, big, .true., .true., &
                    'the liquid depth must be > 0 [m]', status, message)
    if (status == SD_OK .and. (tank%liquid_density > 0 .eqv. tank%liquid_mass > 0)) then
      status = SD_BAD_INPUT
      message = 'liquid_density = '//num2str(tank%liquid_density)//' and liquid_mass = '// &
                num2str(tank%liquid_mass)//': give exactly one, > 0 (the density [kg/m^3] or '// &
                'the mass [kg] of the liquid)'
    end if
    call check_real('liquid_density', max(tank%liquid_density, 0.0_wp), 0.0_wp, big, .false., &
                    .true., 'the liquid density must be finite [kg/m^3]', status, message)
    call check_real('liquid_mass', max(tank%liquid_mass, 0.0_wp), 0.0_wp, big, .false., &
                    .true., 'the liquid mass must be finite [kg]', status, message)
    call check_real('freeboard', tank%freeboard, 0.0_wp, big, .true., .true., &
                    'the freeboard (liquid surface to roof) must be > 0 [m]', status, message)
    call check_real('tank_mass', tank%tank_mass, 0.0_wp, big, .false., .true., &
                    'the tank mass (shell and roof) must be >= 0 [kg]', status, message)
    call check_real('gravity', tank%gravity, 0.0_wp, big, .true., .true., &
                    'gravity must be > 0 [m/s^2]', status, message)
    if (status == SD_OK .and. tank%shape /= SHAPE_CIRCULAR .and. &
        (tank%roof_slope /= 0 .or. tank%roof_radius /= 0)) then
      status = SD_BAD_INPUT
      message = 'roof_slope = '//num2str(tank%roof_slope)//' and roof_radius = '// &
                num2str(tank%roof_radius)//': cone and dome roofs are for circular tanks; '// &
                'a rectangular tank''s roof is flat (both 0)'
    end if
    if (tank%shape == SHAPE_CIRCULAR) &
      call check_roof(tank%radius, tank%roof_slope, tank%roof_radius, status, message)
    call check_real('sloshing_damping', tank%sloshing_damping, 0.0_wp, 1.0_wp, .false., .true., &
                    'the sloshing damping ratio must lie in [0, 1)', status, message)
    if (status == SD_OK .and. (tank%roof_contact < 1 .or. &
                               tank%roof_contact > size(roof_contact_names))) then
      status = SD_BAD_INPUT
      message = 'roof_contact = '//num2str(tank%roof_contact)//' is not a code of '// &
                "'none' (1) or 'impact' (2)"
    end if
    call check_real('support_height', tank%support_height, 0.0_wp, big, .false., .true., &
                    'the support height must be >= 0 [m] (0: the tank height h + freeboard)', &
                    status, message)
    if (status == SD_OK .and. (tank%support_frequency > 0 .eqv. tank%support_stiffness > 0)) then
      status = SD_BAD_INPUT
      message = 'support_frequency = '//num2str(tank%support_frequency)//' and '// &
                'support_stiffness = '//num2str(tank%support_stiffness)//': give exactly one, '// &
                '> 0 (the natural frequency [Hz] of the tank on its supports, or the rods'' '// &
                'stiffness [N m/rad])'
    end if
    if (tank%support_frequency > 0) then
      call check_real('support_frequency', tank%support_frequency, 0.0_wp, big, .true., .true., &
                      'the support frequency must be > 0 [Hz]', status, message)
      call check_real('support_damping', tank%support_damping, 0.0_wp, 1.0_wp, .false., .true., &
                      'the support damping ratio must lie in [0, 1)', status, message)
    else
      call check_real('support_stiffness', tank%support_stiffness, 0.0_wp, big, .true., .true., &
                      'the support stiffness must be > 0 [N m/rad]', status, message)
      call check_real('support_damping_coefficient', tank%support_damping_coefficient, 0.0_wp, &
                      big, .false., .true., 'the support damping coefficient must be >= 0 '// &
                      '[N m s/rad]', status, message)
    end if
    if (status /= SD_OK) return
    if (tank%shape == SHAPE_CIRCULAR) then
      call tank_pendulum(tank%radius, tank%liquid_depth, tank%liquid_density, tank%liquid_mass, &
                         props%pendulum_length, props%sloshing_mass, props%d1, props%rigid_mass, &
                         props%d0, props%liquid_mass, status, message)
      if (status /= SD_OK) return
      props%wave_factor = wave_height_factor(tank%radius)
    else
      call rectangular_pendulum(tank, props, status, message)
      if (status /= SD_OK) return
    end if
    ! a freeboard the linear wave cannot reach (it rises at most wave_factor at the wall):
    ! theta0 capped below pi/2 for the model, and the roof is out of the linear wave's reach
    sin_theta0 = tank%freeboard/props%wave_factor
    props%roof_reachable = sin_theta0 < sin(max_theta0)
    props%theta0 = asin(min(sin_theta0, sin(max_theta0)))
    props%total_mass = props%liquid_mass + tank%tank_mass
    props%rod_length = merge(tank%support_height, tank%liquid_depth + tank%freeboard, &
                             tank%support_height > 0)
    associate (m_total => props%total_mass, rod => props%rod_length, g => tank%gravity)
      if (tank%support_frequency > 0) then
        omega_s = 2*pi*tank%support_frequency
        props%stiffness = m_total*rod**2*omega_s**2 + m_total*g*rod
        props%damping = 2*tank%support_damping*m_total*rod**2*omega_s
      else
        props%stiffness = tank%support_stiffness
        props%damping = tank%support_damping_coefficient
      end if
    end associate
    props%omega = sqrt(tank%gravity/props%pendulum_length)
    props%sloshing_period = 2*pi/props%omega
    ! heights of application of the wall pressures (the bottom's excluded): the first mode's by
    ! potential flow, h [1 - (cosh x - 1)/(x sinh x)] = h - (R/xi) tanh(x/2) with x = xi h/R;
    ! m0's such that slow (quasi-static) motion gives the liquid's exact moment m_F h/2
    ! (docs/model.md, "Loads")
    if (tank%shape == SHAPE_CIRCULAR) props%convective_height = tank%liquid_depth - &
      tank%radius/xi*tanh(xi*tank%liquid_depth/(2*tank%radius))
    call higher_modes(tank, props)
    props%impulsive_height = (props%liquid_mass*tank%liquid_depth/2 - dot_product( &
                              props%modal_mass(1:props%modes), &
                              props%modal_height(1:props%modes)))/props%rigid_mass
    props%shell_height = (tank%liquid_depth + tank%freeboard)/2
    props%rigid_base_arm = merge(tank%radius**2/4, tank%length**2/12, &
                                 tank%shape == SHAPE_CIRCULAR)/tank%liquid_depth
    props%impact_coefficient = tank%impact_stiffness*props%sloshing_mass*tank%gravity* &
                               props%pendulum_length

    ! the groups of eq (9); beta and delta are given dimensionless, zeta is the damping ratio
    associate (pendulum => props%pendulum_length, rod => props%rod_length, w => props%omega)
      rpar = [pendulum/rod, props%sloshing_mass/props%total_mass, &
              props%stiffness/(w**2*rod**2*props%total_mass), props%theta0, &
              tank%impact_stiffness, props%damping/(w*rod**2*props%total_mass), &
              tank%impact_damping, 0.0_wp, 0.0_wp, tank%sloshing_damping]
    end associate
    call model_from_arrays(rpar, [tank%n, tank%p], model, status, message)
    if (status /= SD_OK) call rename(message)
    ! without the impact model the tank's liquid feels no wall below its roof: beta = delta = 0
    ! (beta and delta checked above all the same, one rule whatever the roof contact)
    if (status == SD_OK .and. tank%roof_contact /= ROOF_CONTACT_IMPACT) then
      model%beta = 0
      model%delta = 0
      call set_coefficients(model)
    end if

  contains

    !> The first mode of a rectangular tank (sloshdyn_tank's sloshing_modes) as the pendulum;
    !> the paper's d1 and d0 (eq 2-3) are for a cylinder: NaN.
    pure subroutine rectangular_pendulum(tank, props, status, message)
      type(tank_t), intent(in) :: tank
      type(tank_properties), intent(inout) :: props
      integer, intent(inout) :: status
      character(len=message_len), intent(inout) :: message
      real(wp) :: l(1), m(1), h(1), wave(1)
      call check_real('liquid_density', tank%liquid_density, 0.0_wp, max_liquid_density, &
                      .false., .false., 'the liquid density [kg/m^3] must lie in [0, 1e5]: '// &
                      'every liquid is lighter', status, message)
      if (status /= SD_OK) return
      props%liquid_mass = merge(tank%liquid_density*tank%length*tank%width* &
                                tank%liquid_depth, tank%liquid_mass, tank%liquid_density > 0)
      if (.not. ieee_is_finite(props%liquid_mass)) then
        status = SD_NON_FINITE
        message = 'the liquid mass of this rectangular tank is not finite: overflow'
        return
      end if
      call sloshing_modes(SHAPE_RECTANGULAR, tank%length, tank%liquid_depth, props%liquid_mass, &
                          l, m, h, wave)
      props%pendulum_length = l(1)
      props%sloshing_mass = m(1)
      props%convective_height = h(1)
      props%wave_factor = wave(1)
      props%rigid_mass = props%liquid_mass - m(1)
      props%d1 = ieee_value(1.0_wp, ieee_quiet_nan)
      props%d0 = props%d1
    end subroutine rectangular_pendulum

    !> Modes 1..tank%modes in props (mode 1: the pendulum's), and the rigid mass m_F minus
    !> their masses (for one mode eq (3)'s m0 = m_F - m as it stands).
    pure subroutine higher_modes(tank, props)
      type(tank_t), intent(in) :: tank
      type(tank_properties), intent(inout) :: props
      real(wp) :: plan_size, wave_number
      integer :: n, k
      n = tank%modes
      props%modes = n
      plan_size = merge(tank%radius, tank%length, tank%shape == SHAPE_CIRCULAR)
      if (n > 1) then
        call sloshing_modes(tank%shape, plan_size, tank%liquid_depth, props%liquid_mass, &
                            props%modal_length(1:n), props%modal_mass(1:n), &
                            props%modal_height(1:n), props%modal_wave(1:n))
        props%modal_period(2:n) = 2*pi*sqrt(props%modal_length(2:n)/tank%gravity)
        props%rigid_mass = props%liquid_mass - props%sloshing_mass - sum(props%modal_mass(2:n))
      end if
      props%modal_period(1) = props%sloshing_period
      props%modal_mass(1) = props%sloshing_mass
      props%modal_height(1) = props%convective_height
      props%modal_length(1) = props%pendulum_length
      props%modal_wave(1) = props%wave_factor
      ! with the base pressure a mode's resultant rises by csch(k_n h)/k_n (k_n its wave number;
      ! mode 1 of a cylinder at eq (2)'s xi = 1.84, as its convective height; docs/model.md)
      do k = 1, n
        wave_number = modal_wave_number(tank%shape, plan_size, k)
        if (k == 1 .and. tank%shape == SHAPE_CIRCULAR) wave_number = xi/tank%radius
        props%modal_height_ibp(k) = props%modal_height(k) + &
                                    1/(wave_number*sinh(wave_number*tank%liquid_depth))
      end do
    end subroutine higher_modes

    !> The model's names in a message are the tank's: tell which tank inputs made them.
    pure subroutine rename(text)
      character(len=message_len), intent(inout) :: text
      select case (text(1:index(text, ' ') - 1))
      case ('s1', 'mu1', 'kappa', 'gamma')
        text = 'the supports, tank and liquid give '//trim(text)
      case ('beta');       text = 'impact_stiffness = beta'//text(5:)
      case ('delta');      text = 'impact_damping = delta'//text(6:)
      case ('zeta');       text = 'sloshing_damping = zeta'//text(5:)
      end select
    end subroutine rename
  end subroutine tank_model

  !> The tank's shape and modes: a known shape with its own plan dimensions only (radius for a
  !> cylinder; length and width, from a millimetre to a kilometre as for a cylinder, for a
  !> rectangular tank), and 1 <= modes <= max_modes.
  pure subroutine check_shape(tank, status, message)
    type(tank_t), intent(in) :: tank
    integer, intent(inout) :: status
    character(len=message_len), intent(inout) :: message
    character(len=*), parameter :: size_rule = ' [m] must lie in [1e-3, 1e3]: the potential '// &
                                               'flow of the sloshing modes holds for tanks '// &
                                               'from a millimetre to a kilometre'
    if (tank%shape /= SHAPE_CIRCULAR .and. tank%shape /= SHAPE_RECTANGULAR) then
      status = SD_BAD_INPUT
      message = 'shape = '//num2str(tank%shape)//' is not known; allowed: '// &
                trim(shape_names(1))//' (1), '//trim(shape_names(2))//' (2)'
    else if (tank%modes < 1 .or. tank%modes > max_modes) then
      status = SD_BAD_INPUT
      message = 'modes = '//num2str(tank%modes)//' is out of range: the sloshing modes '// &
                'taken must lie in [1, '//num2str(max_modes)//']'
    else if (tank%shape == SHAPE_CIRCULAR .and. (tank%length /= 0 .or. tank%width /= 0)) then
      status = SD_BAD_INPUT
      message = 'length = '//num2str(tank%length)//' and width = '//num2str(tank%width)// &
                ': length and width are for shape = ''rectangular''; a circular tank takes radius'
    else if (tank%shape == SHAPE_RECTANGULAR) then
      if (tank%radius /= 0) then
        status = SD_BAD_INPUT
        message = 'radius = '//num2str(tank%radius)//': a rectangular tank takes length (along '// &
                  'the motion) and width, not radius'
        return
      end if
      call check_real('length', tank%length, min_tank_size, max_tank_size, .false., .false., &
                      'the tank length L (along the motion)'//size_rule, status, message)
      call check_real('width', tank%width, min_tank_size, max_tank_size, .false., .false., &
                      'the tank width W (across the motion)'//size_rule, status, message)
      call check_real('liquid_depth', tank%liquid_depth, min_tank_size, max_tank_size, .false., &
                      .false., 'the liquid depth h'//size_rule, status, message)
    end if
  end subroutine check_shape

  !> arm (cos(a) a'' - sin(a) a'^2): the horizontal acceleration of the end of an arm swinging
  !> by the angle a = theta0 y(k) (k = 1: theta, the pendulum; k = 3: phi, the rods), with
  !> cos_a = cos(a) and sin_a = sin(a) (computed once per state by the caller).
  pure real(wp) function swing(props, model, y, dydt, k, arm, cos_a, sin_a)
    type(tank_properties), intent(in) :: props
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: y(4), dydt(4), arm, cos_a, sin_a
    integer, intent(in) :: k
    real(wp) :: a_d, a_dd
    associate (w => props%omega, t0 => model%theta0)
      a_d = w*t0*y(k + 1)
      a_dd = w**2*t0*dydt(k + 1)
      swing = arm*(cos_a*a_dd - sin_a*a_d**2)
    end associate
  end function swing

  !> The loads of the state y with rates dydt = (x1', x1'', x2', x2'') at tau, in SI (the rows
  !> of LOAD_ROWS); angles = (cos, sin) of theta = theta0 x1 and of phi = theta0 x2 (as
  !> equations_of_motion returns them); ground_acceleration = u'' [m/s^2] at that time.
  !> confined_share: the share phi of the convective mass that the roof confines (0 before
  !> the wave reaches the roof; sloshdyn_seismic): it moves with the tank, so the convective
  !> mass's mean acceleration is a_c = a_m + phi (a_t - a_m) (the restricted-sloshing method,
  !> docs/model.md "Roof loads").
  pure function tank_loads(tank, props, model, tau, y, dydt, angles, ground_acceleration, &
                           confined_share) result(row)
    type(tank_t), intent(in) :: tank
    type(tank_properties), intent(in) :: props
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: tau, y(4), dydt(4), angles(4), ground_acceleration, confined_share
    real(wp) :: row(LOAD_ROWS)
    real(wp) :: tank_accel, convective_accel
    associate (w => props%omega, t0 => model%theta0, pendulum => props%pendulum_length, &
               rod => props%rod_length, m => props%sloshing_mass, &
               cos_theta => angles(1), sin_theta => angles(2), &
               cos_phi => angles(3), sin_phi => angles(4))
      ! horizontal accelerations of the tank, u'' + L (cos(phi) phi'' - sin(phi) phi'^2), and
      ! of the convective (sloshing) mass, a_t + l (cos(theta) theta'' - sin(theta) theta'^2)
      tank_accel = ground_acceleration + swing(props, model, y, dydt, 3, rod, cos_phi, sin_phi)
      convective_accel = tank_accel + swing(props, model, y, dydt, 1, pendulum, cos_theta, &
                                            sin_theta)
      convective_accel = convective_accel + confined_share*(tank_accel - convective_accel)
      row(1:8) = [tau/w, ground_acceleration, pendulum*sin_theta, props%wave_factor*sin_theta, &
                  t0*y(1), rod*sin_phi, tank_accel, convective_accel]
      ! the base shear: the rate of the horizontal momentum (M - m) X_t' + m X_c'
      row(9) = (props%total_mass - m)*tank_accel + m*convective_accel
      ! the overturning moment about the tank bottom of the wall pressures and the shell's
      ! inertia: each mass's horizontal inertia force at its height; with the base pressure,
      ! the rigid liquid's m_F a_t rigid_base_arm and the mode's rise to its IBP height
      row(10) = (props%rigid_mass*props%impulsive_height + tank%tank_mass*props%shell_height)* &
                tank_accel + m*props%convective_height*convective_accel
      row(11) = row(10) + props%liquid_mass*props%rigid_base_arm*tank_accel + &
                m*(props%modal_height_ibp(1) - props%convective_height)* &
                (convective_accel - tank_accel)
    end associate
  end function tank_loads
end module sloshdyn_vessel
