!> Prototype for issue 43 (benchmarks only, not the product): is a member-fastest DOP853
!> ensemble with the project's own vectorised sine and cosine >= 2.5x numbalsoda's dop853
!> looped? Standalone: no dependency on the sloshdyn library. benchmarks/ensemble_soa.py builds
!> it (gfortran -O3 -ffp-contract=off, SSE2 and -mavx2 -mno-fma), checks it and times it.
!>
!> The sine and cosine are benchmarks/sincos_kernels.f90's (built with this file): the same
!> bits scalar and vectorised; a call whose arguments are all below pi/4 skips the reduction.
!> The right-hand side makes two calls, one for its three small angles (pendulum angles and
!> their sum: below pi/4 in the Fig 14 case), one for the forcing phase rho tau. Built with
!> -DFULL_REDUCTION every call takes the full path (the kernels of 2026-12-03), for comparison.

!> The Fig 14 right-hand side (eq 15 of the paper, the numba cfunc `eom` of benchmarks/peers.py)
!> for m members at once, member-fastest: y(ld, 4), rows 1..m are the members.
module soa_model
  use, intrinsic :: iso_fortran_env, only: wp => real64
  use sincos_kernels, only: sin_cos_many
  implicit none
  private
  public :: model, model_from, rhs_block

  !> The parameter vector d of peers.Numba.data, with the constant products of the formula
  !> taken out of the member loop (each one is the same left-to-right product as in `eom`).
  type model
    real(wp) :: s1, mu1, kappa, t0, beta, gamma, delta, a, rho
    integer :: n_imp, n_dis
    real(wp) :: a_rho2, t0_s1, beta_t0, t0s1, mu1s1t0, s1_t0, mu1s1
  end type model

contains

  pure function model_from(d) result(p)
    real(wp), intent(in) :: d(11)
    type(model) :: p
    p%s1 = d(1); p%mu1 = d(2); p%kappa = d(3); p%t0 = d(4); p%beta = d(5)
    p%gamma = d(6); p%delta = d(7); p%a = d(8); p%rho = d(9)
    p%n_imp = nint(d(10)); p%n_dis = nint(d(11))
    p%a_rho2 = -p%a*p%rho*p%rho          ! xdd = -a*rho*rho*sin(rho*tau)
    p%t0_s1 = p%t0/p%s1                  ! t0/s1*s12*v2*v2
    p%beta_t0 = p%beta/p%t0              ! beta/t0*x1**n_imp
    p%t0s1 = p%t0*p%s1                   ! cos(q1)*xdd/(t0*s1)
    p%mu1s1t0 = p%mu1*p%s1*p%t0          ! mu1*s1*t0*s12*v1*v1
    p%s1_t0 = p%s1/p%t0                  ! s1/t0*sin(q2)
    p%mu1s1 = p%mu1*p%s1                 ! m21 = mu1*s1*c12
  end function model_from

  !> x**n (n >= 1) for every member by repeated squaring: the exponent is the same for all
  !> members, so the branches are uniform and the member loops vectorise.
  pure subroutine int_power(m, x, n, r)
    integer, intent(in) :: m, n
    real(wp), intent(in) :: x(m)
    real(wp), intent(out) :: r(m)
    real(wp) :: b(m)
    integer :: e
    logical :: first
    b = x
    e = n
    first = .true.
    do while (e > 0)
      if (mod(e, 2) == 1) then
        if (first) then
          r = b
        else
          r = r*b
        end if
        first = .false.
      end if
      e = e/2
      if (e > 0) b = b*b
    end do
  end subroutine int_power

  !> dy = f(tau, y) for members 1..m. The 4 angles of every member (theta0 x1, theta0 x2,
  !> their sum, rho tau) go through one vectorised sine-cosine call of 4 m arguments.
  subroutine rhs_block(m, ld, p, tau, y, dy)
    integer, intent(in) :: m, ld
    type(model), intent(in) :: p
    real(wp), intent(in) :: tau(ld), y(ld, 4)
    real(wp), intent(out) :: dy(ld, 4)
    real(wp) :: ang(4*m), s(4*m), c(4*m), pimp(m), pdis(m)
    real(wp) :: xdd, f1, f2, m12, m21, det
    integer :: i
    do i = 1, m
      ang(i) = p%t0*y(i, 1)
      ang(m + i) = p%t0*y(i, 3)
      ang(2*m + i) = ang(i) + ang(m + i)
      ang(3*m + i) = p%rho*tau(i)
    end do
    call sin_cos_many(ang(1:3*m), s(1:3*m), c(1:3*m))        ! small angles: no reduction
    call sin_cos_many(ang(3*m + 1:), s(3*m + 1:), c(3*m + 1:))   ! the forcing phase
    call int_power(m, y(1:m, 1), p%n_imp, pimp)
    call int_power(m, y(1:m, 1), p%n_dis, pdis)
    do i = 1, m
      ! s(i), c(i): q1; s(m+i), c(m+i): q2; s(2m+i), c(2m+i): q1 + q2; s(3m+i): rho tau
      xdd = p%a_rho2*s(3*m + i)
      f1 = p%t0_s1*s(2*m + i)*y(i, 4)*y(i, 4) - s(i)/p%t0 - p%beta_t0*pimp(i) &
           - p%delta*pdis(i)*y(i, 2) - c(i)*xdd/p%t0s1
      f2 = p%mu1s1t0*s(2*m + i)*y(i, 2)*y(i, 2) - p%kappa*y(i, 3) + p%s1_t0*s(m + i) &
           - p%gamma*y(i, 4) - xdd*c(m + i)/p%t0
      m12 = c(2*m + i)/p%s1
      m21 = p%mu1s1*c(2*m + i)
      det = 1.0_wp - m12*m21
      dy(i, 1) = y(i, 2)
      dy(i, 2) = (f1 - m12*f2)/det
      dy(i, 3) = y(i, 4)
      dy(i, 4) = (f2 - m21*f1)/det
    end do
  end subroutine rhs_block
end module soa_model

!> DOP853 (Hairer's dop853.f: 12 stages, the error estimate from the 5th- and 3rd-order
!> differences, safe 0.9, fac1 0.333, fac2 6, beta 0, HINIT's first step) for m members at once,
!> each with its own t, h, accept/reject and last-step flags. All arrays are member-fastest and
!> every per-member operation is a loop over the members (vectorisable); the members that
!> reach t_end are compacted out. No dense output, no stiffness detection.
module soa_dop853
  use, intrinsic :: iso_fortran_env, only: wp => real64, int64
  use soa_model, only: model, rhs_block
  implicit none
  private
  public :: dop853_block

  ! The DOP853 tableau, digit for digit from the PARAMETER statements of DP86CO in dop853.f
  ! (Hairer & Wanner, version of April 25, 1996; HNW I, sec. II.10). c12 = c13 = 1.
  real(wp), parameter :: &
    c2 = 0.526001519587677318785587544488e-01_wp, &
    c3 = 0.789002279381515978178381316732e-01_wp, &
    c4 = 0.118350341907227396726757197510e+00_wp, &
    c5 = 0.281649658092772603273242802490e+00_wp, &
    c6 = 0.333333333333333333333333333333e+00_wp, &
    c7 = 0.25e+00_wp, &
    c8 = 0.307692307692307692307692307692e+00_wp, &
    c9 = 0.651282051282051282051282051282e+00_wp, &
    c10 = 0.6e+00_wp, &
    c11 = 0.857142857142857142857142857142e+00_wp, &
    c14 = 0.1e+00_wp, &
    c15 = 0.2e+00_wp, &
    c16 = 0.777777777777777777777777777778e+00_wp
  ! 8th-order weights (b2..b5 = 0)
  real(wp), parameter :: &
    b1 = 5.42937341165687622380535766363e-2_wp, &
    b6 = 4.45031289275240888144113950566e0_wp, &
    b7 = 1.89151789931450038304281599044e0_wp, &
    b8 = -5.8012039600105847814672114227e0_wp, &
    b9 = 3.1116436695781989440891606237e-1_wp, &
    b10 = -1.52160949662516078556178806805e-1_wp, &
    b11 = 2.01365400804030348374776537501e-1_wp, &
    b12 = 4.47106157277725905176885569043e-2_wp
  ! 3rd-order embedded weights: err3 = sum b_i k_i - bhh1 k1 - bhh2 k9 - bhh3 k12
  real(wp), parameter :: &
    bhh1 = 0.244094488188976377952755905512e+00_wp, &
    bhh2 = 0.733846688281611857341361741547e+00_wp, &
    bhh3 = 0.220588235294117647058823529412e-01_wp
  ! 5th-order error estimate: err5 = sum er_i k_i
  real(wp), parameter :: &
    er1 = 0.1312004499419488073250102996e-01_wp, &
    er6 = -0.1225156446376204440720569753e+01_wp, &
    er7 = -0.4957589496572501915214079952e+00_wp, &
    er8 = 0.1664377182454986536961530415e+01_wp, &
    er9 = -0.3503288487499736816886487290e+00_wp, &
    er10 = 0.3341791187130174790297318841e+00_wp, &
    er11 = 0.8192320648511571246570742613e-01_wp, &
    er12 = -0.2235530786388629525884427845e-01_wp
  real(wp), parameter :: &
    a21 = 5.26001519587677318785587544488e-2_wp, &
    a31 = 1.97250569845378994544595329183e-2_wp, &
    a32 = 5.91751709536136983633785987549e-2_wp, &
    a41 = 2.95875854768068491816892993775e-2_wp, &
    a43 = 8.87627564304205475450678981324e-2_wp, &
    a51 = 2.41365134159266685502369798665e-1_wp, &
    a53 = -8.84549479328286085344864962717e-1_wp, &
    a54 = 9.24834003261792003115737966543e-1_wp, &
    a61 = 3.7037037037037037037037037037e-2_wp, &
    a64 = 1.70828608729473871279604482173e-1_wp, &
    a65 = 1.25467687566822425016691814123e-1_wp, &
    a71 = 3.7109375e-2_wp, &
    a74 = 1.70252211019544039314978060272e-1_wp, &
    a75 = 6.02165389804559606850219397283e-2_wp, &
    a76 = -1.7578125e-2_wp
  real(wp), parameter :: &
    a81 = 3.70920001185047927108779319836e-2_wp, &
    a84 = 1.70383925712239993810214054705e-1_wp, &
    a85 = 1.07262030446373284651809199168e-1_wp, &
    a86 = -1.53194377486244017527936158236e-2_wp, &
    a87 = 8.27378916381402288758473766002e-3_wp, &
    a91 = 6.24110958716075717114429577812e-1_wp, &
    a94 = -3.36089262944694129406857109825e0_wp, &
    a95 = -8.68219346841726006818189891453e-1_wp, &
    a96 = 2.75920996994467083049415600797e1_wp, &
    a97 = 2.01540675504778934086186788979e1_wp, &
    a98 = -4.34898841810699588477366255144e1_wp, &
    a101 = 4.77662536438264365890433908527e-1_wp, &
    a104 = -2.48811461997166764192642586468e0_wp, &
    a105 = -5.90290826836842996371446475743e-1_wp, &
    a106 = 2.12300514481811942347288949897e1_wp, &
    a107 = 1.52792336328824235832596922938e1_wp, &
    a108 = -3.32882109689848629194453265587e1_wp, &
    a109 = -2.03312017085086261358222928593e-2_wp
  real(wp), parameter :: &
    a111 = -9.3714243008598732571704021658e-1_wp, &
    a114 = 5.18637242884406370830023853209e0_wp, &
    a115 = 1.09143734899672957818500254654e0_wp, &
    a116 = -8.14978701074692612513997267357e0_wp, &
    a117 = -1.85200656599969598641566180701e1_wp, &
    a118 = 2.27394870993505042818970056734e1_wp, &
    a119 = 2.49360555267965238987089396762e0_wp, &
    a1110 = -3.0467644718982195003823669022e0_wp, &
    a121 = 2.27331014751653820792359768449e0_wp, &
    a124 = -1.05344954667372501984066689879e1_wp, &
    a125 = -2.00087205822486249909675718444e0_wp, &
    a126 = -1.79589318631187989172765950534e1_wp, &
    a127 = 2.79488845294199600508499808837e1_wp, &
    a128 = -2.85899827713502369474065508674e0_wp, &
    a129 = -8.87285693353062954433549289258e0_wp, &
    a1210 = 1.23605671757943030647266201528e1_wp, &
    a1211 = 6.43392746015763530355970484046e-1_wp
  real(wp), parameter :: safe = 0.9_wp, facc1 = 1/0.333_wp, facc2 = 1/6.0_wp, &
                         expo1 = 1.0_wp/8.0_wp, uround = 2.3e-16_wp

contains

  !> ys = y + h sum_l a(s, l) k_l for stage s = 2..12 (DP86CO's loops 22-32, the same sums).
  pure subroutine stage_input(m, ld, s, h, y, k, ys)
    integer, intent(in) :: m, ld, s
    real(wp), intent(in) :: h(ld), y(ld, 4), k(ld, 4, 12)
    real(wp), intent(out) :: ys(ld, 4)
    integer :: j
    do j = 1, 4
      select case (s)
      case (2)
        ys(1:m, j) = y(1:m, j) + h(1:m)*a21*k(1:m, j, 1)
      case (3)
        ys(1:m, j) = y(1:m, j) + h(1:m)*(a31*k(1:m, j, 1) + a32*k(1:m, j, 2))
      case (4)
        ys(1:m, j) = y(1:m, j) + h(1:m)*(a41*k(1:m, j, 1) + a43*k(1:m, j, 3))
      case (5)
        ys(1:m, j) = y(1:m, j) + h(1:m)*(a51*k(1:m, j, 1) + a53*k(1:m, j, 3) + a54*k(1:m, j, 4))
      case (6)
        ys(1:m, j) = y(1:m, j) + h(1:m)*(a61*k(1:m, j, 1) + a64*k(1:m, j, 4) + a65*k(1:m, j, 5))
      case (7)
        ys(1:m, j) = y(1:m, j) + h(1:m)*(a71*k(1:m, j, 1) + a74*k(1:m, j, 4) + a75*k(1:m, j, 5) + &
            a76*k(1:m, j, 6))
      case (8)
        ys(1:m, j) = y(1:m, j) + h(1:m)*(a81*k(1:m, j, 1) + a84*k(1:m, j, 4) + a85*k(1:m, j, 5) + &
            a86*k(1:m, j, 6) + a87*k(1:m, j, 7))
      case (9)
        ys(1:m, j) = y(1:m, j) + h(1:m)*(a91*k(1:m, j, 1) + a94*k(1:m, j, 4) + a95*k(1:m, j, 5) + &
            a96*k(1:m, j, 6) + a97*k(1:m, j, 7) + a98*k(1:m, j, 8))
      case (10)
        ys(1:m, j) = y(1:m, j) + h(1:m)*(a101*k(1:m, j, 1) + a104*k(1:m, j, 4) + &
            a105*k(1:m, j, 5) + a106*k(1:m, j, 6) + a107*k(1:m, j, 7) + a108*k(1:m, j, 8) + &
                a109*k(1:m, j, 9))
      case (11)
        ys(1:m, j) = y(1:m, j) + h(1:m)*(a111*k(1:m, j, 1) + a114*k(1:m, j, 4) + &
            a115*k(1:m, j, 5) + a116*k(1:m, j, 6) + a117*k(1:m, j, 7) + a118*k(1:m, j, 8) + &
                a119*k(1:m, j, 9) + a1110*k(1:m, j, 10))
      case (12)
        ys(1:m, j) = y(1:m, j) + h(1:m)*(a121*k(1:m, j, 1) + a124*k(1:m, j, 4) + &
            a125*k(1:m, j, 5) + a126*k(1:m, j, 6) + a127*k(1:m, j, 7) + a128*k(1:m, j, 8) + &
                a129*k(1:m, j, 9) + a1210*k(1:m, j, 10) + a1211*k(1:m, j, 11))
      end select
    end do
  end subroutine stage_input

  !> Integrates the n members y(n, 4) from t = 0 to t_end; y is overwritten with the end
  !> states. nfev counts the evaluations as dop853.f's NFCN does (2 at the start, 11 per trial
  !> step, 1 per accepted step); n_eval_done adds the k13 evaluated for rejected trials too.
  subroutine dop853_block(n, p, t_end, rtol, atol, y_io, nfev, nacc, nrej, n_eval_done, ok)
    integer, intent(in) :: n
    type(model), intent(in) :: p
    real(wp), intent(in) :: t_end, rtol, atol
    real(wp), intent(inout) :: y_io(n, 4)
    integer(int64), intent(out) :: nfev(n), nacc(n), nrej(n), n_eval_done
    logical, intent(out) :: ok
    real(wp) :: y(n, 4), k(n, 4, 12), k13(n, 4), ys(n, 4), yn(n, 4), e3(n, 4), e5(n, 4)
    real(wp) :: t(n), h(n), ts(n), err(n), err2(n), sk(n), dnf(n), dny(n), der2(n), hmax
    real(wp) :: fac11, fac, hnew
    logical :: last(n), reject(n), done(n)
    integer(int64) :: cf(n), ca(n), cr(n)
    integer :: id(n), m, i, j, s
    real(wp), parameter :: cnode(2:11) = [c2, c3, c4, c5, c6, c7, c8, c9, c10, c11]

    m = n
    ok = .true.
    y = y_io
    id = [(i, i=1, n)]
    t = 0
    hmax = t_end                       ! dop853.f's default HMAX = XEND - X
    last = .false.
    reject = .false.
    ca = 0
    cr = 0
    ! k1 = f(0, y0) and HINIT (posneg = 1, iord = 8)
    call rhs_block(m, n, p, t, y, k(:, :, 1))
    dnf = 0
    dny = 0
    do j = 1, 4
      sk(1:m) = atol + rtol*abs(y(1:m, j))
      dnf(1:m) = dnf(1:m) + (k(1:m, j, 1)/sk(1:m))**2
      dny(1:m) = dny(1:m) + (y(1:m, j)/sk(1:m))**2
    end do
    do i = 1, m
      if (dnf(i) <= 1.0e-10_wp .or. dny(i) <= 1.0e-10_wp) then
        h(i) = 1.0e-6_wp
      else
        h(i) = sqrt(dny(i)/dnf(i))*0.01_wp
      end if
      h(i) = min(h(i), hmax)
    end do
    do j = 1, 4
      ys(1:m, j) = y(1:m, j) + h(1:m)*k(1:m, j, 1)
    end do
    ts(1:m) = t(1:m) + h(1:m)
    call rhs_block(m, n, p, ts, ys, k13)
    der2 = 0
    do j = 1, 4
      sk(1:m) = atol + rtol*abs(y(1:m, j))
      der2(1:m) = der2(1:m) + ((k13(1:m, j) - k(1:m, j, 1))/sk(1:m))**2
    end do
    do i = 1, m
      der2(i) = sqrt(der2(i))/h(i)
      fac = max(abs(der2(i)), sqrt(dnf(i)))           ! DER12
      if (fac <= 1.0e-15_wp) then
        hnew = max(1.0e-6_wp, abs(h(i))*1.0e-3_wp)
      else
        hnew = (0.01_wp/fac)**(1.0_wp/8)
      end if
      h(i) = min(100*abs(h(i)), hnew, hmax)
    end do
    cf = 2
    n_eval_done = 2*int(n, int64)

    do while (m > 0)
      ! --- the trial step of every active member
      do i = 1, m
        if (0.1_wp*abs(h(i)) <= abs(t(i))*uround) ok = .false.   ! step size too small
        if ((t(i) + 1.01_wp*h(i) - t_end) > 0) then
          h(i) = t_end - t(i)
          last(i) = .true.
        end if
      end do
      if (.not. ok) return
      do s = 2, 12
        call stage_input(m, n, s, h, y, k, ys)
        if (s <= 11) then
          ts(1:m) = t(1:m) + cnode(s)*h(1:m)
        else
          ts(1:m) = t(1:m) + h(1:m)                          ! XPH
        end if
        call rhs_block(m, n, p, ts, ys, k(:, :, s))
      end do
      ! --- 8th-order solution and the error estimate (loops 35 and 41)
      err = 0
      err2 = 0
      do j = 1, 4
        do i = 1, m
          ys(i, j) = b1*k(i, j, 1) + b6*k(i, j, 6) + b7*k(i, j, 7) + b8*k(i, j, 8) + &
                     b9*k(i, j, 9) + b10*k(i, j, 10) + b11*k(i, j, 11) + b12*k(i, j, 12)
          yn(i, j) = y(i, j) + h(i)*ys(i, j)
          sk(i) = atol + rtol*max(abs(y(i, j)), abs(yn(i, j)))
          e3(i, j) = ys(i, j) - bhh1*k(i, j, 1) - bhh2*k(i, j, 9) - bhh3*k(i, j, 12)
          err2(i) = err2(i) + (e3(i, j)/sk(i))**2
          e5(i, j) = er1*k(i, j, 1) + er6*k(i, j, 6) + er7*k(i, j, 7) + er8*k(i, j, 8) + &
                     er9*k(i, j, 9) + er10*k(i, j, 10) + er11*k(i, j, 11) + er12*k(i, j, 12)
          err(i) = err(i) + (e5(i, j)/sk(i))**2
        end do
      end do
      do i = 1, m
        fac = err(i) + 0.01_wp*err2(i)                       ! DENO
        if (fac <= 0) fac = 1
        err(i) = abs(h(i))*err(i)*sqrt(1.0_wp/(4*fac))
      end do
      ! --- k13 = f(t + h, y_new) for every member (used by the accepted ones only: one
      !     block call instead of gathering the accepted members)
      ts(1:m) = t(1:m) + h(1:m)
      call rhs_block(m, n, p, ts, yn, k13)
      n_eval_done = n_eval_done + 12*int(m, int64)
      ! --- step size control, per member (dop853.f after label 41; beta = 0: FACOLD**BETA = 1)
      do i = 1, m
        fac11 = err(i)**expo1
        fac = max(facc2, min(facc1, fac11/safe))
        hnew = h(i)/fac
        done(i) = .false.
        if (err(i) <= 1) then
          ca(i) = ca(i) + 1
          cf(i) = cf(i) + 12
          t(i) = t(i) + h(i)
          done(i) = last(i)
          if (abs(hnew) > hmax) hnew = hmax
          if (reject(i)) hnew = min(abs(hnew), abs(h(i)))
          reject(i) = .false.
        else
          hnew = h(i)/min(facc1, fac11/safe)
          if (ca(i) >= 1) cr(i) = cr(i) + 1
          cf(i) = cf(i) + 11
          reject(i) = .true.
          last(i) = .false.
        end if
        h(i) = hnew
      end do
      do j = 1, 4
        do i = 1, m
          if (.not. reject(i)) then      ! accepted: y = y_new, k1 = k13
            y(i, j) = yn(i, j)
            k(i, j, 1) = k13(i, j)
          end if
        end do
      end do
      ! --- members at t_end leave; the last active member takes the place
      do i = m, 1, -1
        if (done(i)) then
          y_io(id(i), :) = y(i, :)
          nfev(id(i)) = cf(i)
          nacc(id(i)) = ca(i)
          nrej(id(i)) = cr(i)
          if (i /= m) then
            y(i, :) = y(m, :)
            k(i, :, 1) = k(m, :, 1)
            t(i) = t(m); h(i) = h(m); last(i) = last(m); reject(i) = reject(m)
            cf(i) = cf(m); ca(i) = ca(m); cr(i) = cr(m); id(i) = id(m)
          end if
          m = m - 1
        end if
      end do
    end do
  end subroutine dop853_block
end module soa_dop853

!> stdin: K B reps, rtol atol t_end, the 11 numbers of peers.Numba.data (without the counter),
!> K lines of 4 initial states. Integrates the K members in blocks of B (B = 1: the scalar
!> path, one member per call), reps times (the first is a warm-up; the reported time is the
!> last run's). stdout: per member the 4 end states as hex bits and decimals and the counts,
!> then 'cpu' with the CPU seconds of each run's integration loop.
program ensemble_soa
  use, intrinsic :: iso_fortran_env, only: wp => real64, int64
  use soa_model, only: model, model_from
  use soa_dop853, only: dop853_block
  implicit none
  integer :: nk, nb, reps, i, j, r, b0, b1
  real(wp) :: rtol, atol, t_end, d(11), c0, c1
  real(wp), allocatable :: y0(:, :), y(:, :), cpu(:)
  integer(int64), allocatable :: nfev(:), nacc(:), nrej(:)
  integer(int64) :: done_eval, done_total
  logical :: ok, all_ok
  type(model) :: p

  read (*, *) nk, nb, reps
  read (*, *) rtol, atol, t_end
  read (*, *) d
  allocate (y0(nk, 4), y(nk, 4), nfev(nk), nacc(nk), nrej(nk), cpu(reps))
  do i = 1, nk
    read (*, *) y0(i, :)
  end do
  p = model_from(d)
  do r = 1, reps
    y = y0
    all_ok = .true.
    done_total = 0
    call cpu_time(c0)
    do b0 = 1, nk, nb
      b1 = min(nk, b0 + nb - 1)
      call dop853_block(b1 - b0 + 1, p, t_end, rtol, atol, y(b0:b1, :), nfev(b0:b1), &
                        nacc(b0:b1), nrej(b0:b1), done_eval, ok)
      all_ok = all_ok .and. ok
      done_total = done_total + done_eval
    end do
    call cpu_time(c1)
    cpu(r) = c1 - c0
  end do
  if (.not. all_ok) print '(a)', 'failed: step size too small'
  do i = 1, nk
    print '(a, 4(1x, z16.16), 4(1x, es24.16e3), 3(1x, i0))', 'y', (y(i, j), j=1, 4), &
      (y(i, j), j=1, 4), nfev(i), nacc(i), nrej(i)
  end do
  print '(a, 1x, i0)', 'evaluations_done', done_total
  print '(a, *(1x, es12.5))', 'cpu', cpu
end program ensemble_soa
