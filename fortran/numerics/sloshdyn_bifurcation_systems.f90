!> The defining systems a field of a flow chooses (fold and Hopf, sloshdyn_fold_hopf) and the
!> first Lyapunov coefficient of a Hopf point (sloshdyn_lyapunov_coefficient), for
!> sloshdyn_bifurcation.
submodule (sloshdyn_bifurcation) sloshdyn_bifurcation_systems
  use sloshdyn_fold_hopf, only: fold_system, hopf_system
  use sloshdyn_lyapunov_coefficient, only: hopf_start, lyapunov_core
  implicit none

contains

  module procedure field_defining_system
    real(wp) :: f(size(x0)), fx(size(x0), size(x0)), fp(size(x0), 2), v(size(x0)), &
                w(size(x0)), omega
    integer :: n

    n = size(x0)
    status = SD_OK
    message = ''
    if (kind == CURVE_PERIOD_DOUBLING .or. kind == CURVE_NEIMARK_SACKER) then
      status = SD_BAD_INPUT
      message = 'a '//curve_kind_name(kind)//' curve is a curve of fixed points of a map: '// &
                'the field must be a two_parameter_map (sloshdyn_map_bifurcation)'
      return
    end if
    if (kind == CURVE_FOLD) then
      call field%evaluate(x0, p0, f, fx, fp)
      call null_vectors(fx, v, w, status, message)
      if (status /= SD_OK) then
        message = 'no null vector of df/dx at the start point: '//trim(message)
        return
      end if
      allocate (fold_system :: proto)
      select type (proto)
      type is (fold_system)
        proto%c = v
        proto%b = w
      end select
      call setup_system(proto, field, CURVE_FOLD, n, 0, p0, options, &
                        [CODIM2_BT, CODIM2_CUSP, CODIM2_ZH])
      s0 = [x0, p0]
    else
      if (n < 2) then
        status = SD_BAD_INPUT
        message = 'x0 has size 1; a Hopf point needs n >= 2'
        return
      end if
      call hopf_start(field, x0, p0, fx, omega, v, status, message)
      if (status /= SD_OK) return
      allocate (hopf_system :: proto)
      select type (proto)
      type is (hopf_system)
        proto%kappa_scale = omega**2
        allocate (proto%v_ref(n), proto%u_ref(n))
      end select
      ! det J (ZH) vanishes with kappa (BT) at a Bogdanov-Takens point, which ends the curve
      call setup_system(proto, field, CURVE_HOPF, n, n + 1, p0, options, &
                        [CODIM2_BT, CODIM2_ZH, CODIM2_GH], ends=[END_BT], masks=[0, 1])
      s0 = [x0, v, 1.0_wp, p0]
    end if
  end procedure field_defining_system

  module procedure first_lyapunov_coefficient
    real(wp) :: fx(size(x), size(x)), v(size(x))

    l1 = ieee_value(1.0_wp, ieee_quiet_nan)
    omega = 0
    status = SD_OK
    message = ''
    if (size(x) < 2) then
      status = SD_BAD_INPUT
      message = 'x has size 1; a Hopf point needs n >= 2'
      return
    end if
    call hopf_start(field, x, p, fx, omega, v, status, message)
    if (status == SD_OK) call lyapunov_core(field, x, p, fx, v, omega, l1, status, message)
    if (status /= SD_OK) message = 'first_lyapunov_coefficient: '//trim(message)
  end procedure first_lyapunov_coefficient
end submodule sloshdyn_bifurcation_systems
