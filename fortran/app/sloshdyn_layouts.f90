!> The flat arrays that carry settings and work counts across the f2py bridge, both ways:
!>   integration(INTEGRATION_SIZE) = [rtol, atol, h_initial, h_max, h_min, max_steps, method]
!>   steady(STEADY_SIZE)           = [transient_periods, settle_tol, max_transient_periods,
!>                                    window_periods, samples_per_period, periodic_tol,
!>                                    shooting (1/0)]
!>   response(RESPONSE_SIZE)       = [n_scan, n_amplitudes, n_phases, amplitude_min,
!>                                    amplitude_max, ds, ds_min, ds_max, x_scale, max_points]
!>   lyapunov(LYAPUNOV_SIZE)       = [transient_periods, n_periods, renormalise_every]
!>   tank(TANK_SIZE)               = tank_t's components in order (sloshdyn_vessel)
!>   ground(GROUND_SIZE)           = [kind, peak_acceleration, frequency, dt] (+ the samples)
!>   chart(CHART_SETTINGS_SIZE)    = the &chart variables (to_chart)
!> Python's Integration, Steady, Continuation and the Lyapunov settings list their fields in
!> these orders and take their defaults from defaults_* below (through the bridge).
!> Integer entries are converted by to_int, which keeps out-of-range and NaN values out of range
!> (so the core's range checks report them) instead of letting them wrap or become 0.
module sloshdyn_layouts
  use sloshdyn_kinds, only: wp
  use sloshdyn_ode, only: ode_options, ode_stats
  use sloshdyn_simulation, only: steady_options
  use sloshdyn_response, only: response_options
  use sloshdyn_periodic_response, only: lyapunov_options
  use sloshdyn_vessel, only: tank_t
  use sloshdyn_ground, only: ground_motion_t, harmonic_ground, record_ground, GROUND_RECORD
  use sloshdyn_stability_chart, only: chart_settings
  implicit none
  private
  public :: INTEGRATION_SIZE, STEADY_SIZE, RESPONSE_SIZE, LYAPUNOV_SIZE, TANK_SIZE, GROUND_SIZE, &
            CHART_SETTINGS_SIZE
  public :: to_ode_options, to_method, to_steady, to_response, to_lyapunov
  public :: from_ode_options, from_steady, from_response, from_lyapunov, to_int, counts_array
  public :: to_tank, from_tank, to_ground, from_ground, to_chart, from_chart

  integer, parameter :: INTEGRATION_SIZE = 7, STEADY_SIZE = 7, RESPONSE_SIZE = 10, &
                        LYAPUNOV_SIZE = 3, TANK_SIZE = 17, GROUND_SIZE = 4, &
                        CHART_SETTINGS_SIZE = 14

contains

  !> x as an integer; NaN and values beyond the integer range become -huge (out of every range).
  elemental integer function to_int(x)
    real(wp), intent(in) :: x
    if (x == x .and. abs(x) < real(huge(1), wp)) then
      to_int = nint(x)
    else
      to_int = -huge(1)
    end if
  end function to_int

  pure function to_ode_options(a) result(options)
    real(wp), intent(in) :: a(INTEGRATION_SIZE)
    type(ode_options) :: options
    options%rtol = a(1)
    options%atol = a(2)
    options%h_initial = a(3)
    options%h_max = a(4)
    options%h_min = a(5)
    options%max_steps = to_int(a(6))
  end function to_ode_options

  pure integer function to_method(a) result(method)
    real(wp), intent(in) :: a(INTEGRATION_SIZE)
    method = to_int(a(7))
  end function to_method

  pure function from_ode_options(options, method) result(a)
    type(ode_options), intent(in) :: options
    integer, intent(in) :: method
    real(wp) :: a(INTEGRATION_SIZE)
    a = [options%rtol, options%atol, options%h_initial, options%h_max, options%h_min, &
         real(options%max_steps, wp), real(method, wp)]
  end function from_ode_options

  pure function to_steady(a) result(options)
    real(wp), intent(in) :: a(STEADY_SIZE)
    type(steady_options) :: options
    options = steady_options(a(1), a(2), a(3), to_int(a(4)), to_int(a(5)), a(6), a(7) /= 0)
  end function to_steady

  pure function from_steady(options) result(a)
    type(steady_options), intent(in) :: options
    real(wp) :: a(STEADY_SIZE)
    a = [options%transient_periods, options%settle_tol, options%max_transient_periods, &
         real(options%window_periods, wp), real(options%samples_per_period, wp), &
         options%periodic_tol, merge(1.0_wp, 0.0_wp, options%shooting)]
  end function from_steady

  pure function to_response(a) result(options)
    real(wp), intent(in) :: a(RESPONSE_SIZE)
    type(response_options) :: options
    options%n_scan = to_int(a(1))
    options%n_amplitudes = to_int(a(2))
    options%n_phases = to_int(a(3))
    options%amplitude_min = a(4)
    options%amplitude_max = a(5)
    options%continuation%ds = a(6)
    options%continuation%ds_min = a(7)
    options%continuation%ds_max = a(8)
    options%continuation%x_scale = a(9)
    options%continuation%max_points = to_int(a(10))
  end function to_response

  pure function from_response(options) result(a)
    type(response_options), intent(in) :: options
    real(wp) :: a(RESPONSE_SIZE)
    associate (c => options%continuation)
      a = [real(options%n_scan, wp), real(options%n_amplitudes, wp), &
           real(options%n_phases, wp), options%amplitude_min, options%amplitude_max, c%ds, &
           c%ds_min, c%ds_max, c%x_scale, real(c%max_points, wp)]
    end associate
  end function from_response

  pure function to_lyapunov(a) result(options)
    real(wp), intent(in) :: a(LYAPUNOV_SIZE)
    type(lyapunov_options) :: options
    options = lyapunov_options(to_int(a(1)), to_int(a(2)), to_int(a(3)))
  end function to_lyapunov

  pure function from_lyapunov(options) result(a)
    type(lyapunov_options), intent(in) :: options
    real(wp) :: a(LYAPUNOV_SIZE)
    a = real([options%transient_periods, options%n_periods, options%renormalise_every], wp)
  end function from_lyapunov

  !> tank(TANK_SIZE) in the order of tank_t's components (n and p as reals).
  pure function to_tank(a) result(tank)
    real(wp), intent(in) :: a(TANK_SIZE)
    type(tank_t) :: tank
    tank = tank_t(a(1), a(2), a(3), a(4), a(5), a(6), a(7), a(8), a(9), a(10), a(11), a(12), &
                  a(13), a(14), to_int(a(15)), to_int(a(16)), a(17))
  end function to_tank

  pure function from_tank(tank) result(a)
    type(tank_t), intent(in) :: tank
    real(wp) :: a(TANK_SIZE)
    a = [tank%radius, tank%liquid_depth, tank%freeboard, tank%liquid_density, tank%liquid_mass, &
         tank%tank_mass, tank%support_frequency, tank%support_damping, tank%support_stiffness, &
         tank%support_damping_coefficient, tank%support_height, tank%sloshing_damping, &
         tank%impact_stiffness, tank%impact_damping, real(tank%n, wp), real(tank%p, wp), &
         tank%gravity]
  end function from_tank

  !> ground(GROUND_SIZE) = [kind (GROUND_HARMONIC, GROUND_RECORD), peak_acceleration [m/s^2],
  !> frequency [Hz], dt [s]] and, for a record, its samples [m/s^2].
  pure function to_ground(a, samples) result(ground)
    real(wp), intent(in) :: a(GROUND_SIZE), samples(:)
    type(ground_motion_t) :: ground
    if (to_int(a(1)) == GROUND_RECORD) then
      ground = record_ground(a(4), samples)
    else
      ground = harmonic_ground(a(2), a(3))
    end if
  end function to_ground

  pure function from_ground(ground) result(a)
    type(ground_motion_t), intent(in) :: ground
    real(wp) :: a(GROUND_SIZE)
    a = [real(ground%kind, wp), ground%peak_acceleration, ground%frequency, ground%dt]
  end function from_ground

  !> chart(CHART_SETTINGS_SIZE) = [model, x, y, x_min, x_max, y_min, y_max, n_x, n_y, n_scan,
  !> max_points, max_curves, brute_force_starts, threads] (the &chart variables; x, y and model
  !> as codes).
  pure function to_chart(a) result(settings)
    real(wp), intent(in) :: a(CHART_SETTINGS_SIZE)
    type(chart_settings) :: settings
    settings%model = to_int(a(1))
    settings%parameters = to_int(a(2:3))
    settings%p_min = a([4, 6])
    settings%p_max = a([5, 7])
    settings%n_columns = to_int(a(8))
    settings%n_levels = to_int(a(9))
    settings%response%n_scan = to_int(a(10))
    settings%max_points = to_int(a(11))
    settings%max_curves = to_int(a(12))
    settings%brute_force_starts = to_int(a(13))
    settings%threads = to_int(a(14))
  end function to_chart

  pure function from_chart(settings) result(a)
    type(chart_settings), intent(in) :: settings
    real(wp) :: a(CHART_SETTINGS_SIZE)
    a = [real(settings%model, wp), real(settings%parameters, wp), settings%p_min(1), &
         settings%p_max(1), settings%p_min(2), settings%p_max(2), &
         real([settings%n_columns, settings%n_levels, settings%response%n_scan, &
               settings%max_points, settings%max_curves, settings%brute_force_starts, &
               settings%threads], wp)]
  end function from_chart

  !> counts(4) = [rhs evaluations, accepted steps, rejected steps, tau reached].
  pure function counts_array(stats) result(counts)
    type(ode_stats), intent(in) :: stats
    real(wp) :: counts(4)
    counts = [real(stats%n_rhs, wp), real(stats%n_accepted, wp), real(stats%n_rejected, wp), &
              stats%t_reached]
  end function counts_array
end module sloshdyn_layouts
