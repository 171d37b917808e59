!> Explicit Runge-Kutta integrator of order 8(5,3): Hairer's DOP853, the Dormand-Prince pair
!> (Hairer, Norsett & Wanner, Solving Ordinary Differential Equations I, 2nd ed., sec. II.10,
!> and the published dop853.f, version of April 25, 1996 with the corrections of March 4, 2002):
!> 12 stages per step (11 new right-hand sides, the first is the previous step's last), the
!> error estimate that combines the 5th- and 3rd-order embedded differences, the step-size
!> control of dop853.f, HINIT's automatic first step, and the 7th-order dense output (CONTD8)
!> built with 3 extra stages per accepted step. Integrates forward in time only.
!>
!> A second method for the callers of sloshdyn_rk45, with the same types and calling
!> conventions: dop853_init / dop853_step / dop853_dense / dop853_set_state /
!> dop853_statistics / dop853_integrate behave like their rk45_ namesakes. The system type
!> (ode_system), the options (rk45_options) and the counters (rk45_stats) are sloshdyn_rk45's,
!> re-exported here, so `use sloshdyn_dop853` alone is enough.
!>
!> Options: rtol, atol, atol_vector, h_initial, h_max, h_min, max_steps and fixed_step mean
!> exactly what they mean for rk45, and rk45_check_setup validates them. The step-size control
!> is dop853.f's: h_new = h * min(1/fac1, max(1/fac2, safety/(err**(1/8 - beta/5) *
!> err_old**(-beta)))), with no growth right after a rejection. Its defaults differ from
!> DOPRI5's, so each of fac1, fac2 and beta that still holds rk45_options' default value
!> (0.2, 10, 0.04) is replaced by dop853.f's default (0.333, 6, 0); any other value is used
!> as given. safety has the same default, 0.9, in both codes. (Asking for exactly 0.2, 10 or
!> 0.04 with DOP853 is therefore not possible; 0.2000001 etc. is.)
!>
!> Cost: 11 right-hand sides per trial step, plus 4 per accepted step (f at the new point,
!> which is the next step's first stage, and the 3 dense output stages), plus 2 at the start
!> (f(t0, y0) and HINIT's Euler probe; 1 when h_initial is given). dop853_init's optional
!> dense_output = .false. drops the 3 dense stages when only step end points are read.
!>
!> Departures from dop853.f, all shared with sloshdyn_rk45: rejected steps are counted from
!> the first trial on; max_steps limits accepted + rejected steps; a trial step whose stages
!> are NaN or infinite is rejected with the largest cut (fac1) instead of feeding NaN into the
!> step-size formula; the smallest step is rk45's h_min rule instead of 0.1|h| <= uround|t|;
!> no stiffness detection; no output routine (dense output is read after each step).
module sloshdyn_dop853
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_value, ieee_quiet_nan
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, SD_STEP_TOO_SMALL, SD_TOO_MANY_STEPS, &
                             SD_NON_FINITE, check_real
  use sloshdyn_text, only: num2str
  use sloshdyn_rk45, only: ode_system, rk45_options, rk45_stats, rk45_check_setup, plan_trial
  implicit none
  private
  public :: ode_system, rk45_options, rk45_stats
  public :: dop853_integrator
  public :: dop853_init, dop853_step, dop853_dense, dop853_set_state, dop853_statistics, &
            dop853_integrate

  !> State of one integration; all work arrays are allocated by dop853_init, none while
  !> stepping. The public components are for reading: change the state only through
  !> dop853_set_state.
  type :: dop853_integrator
    real(wp) :: t = 0                !< current time (end of the last accepted step)
    real(wp) :: t_old = 0            !< start of the last accepted step
    real(wp) :: t_bound = 0          !< final time; the last step is clipped to end exactly here
    real(wp), allocatable :: y(:)    !< state at t
    integer :: n_rhs = 0             !< right-hand side evaluations
    integer :: n_accepted = 0        !< accepted steps
    integer :: n_rejected = 0        !< rejected steps
    !> options as used: fac1, fac2, beta hold the effective (possibly dop853.f default) values
    type(rk45_options), private :: opt
    real(wp), allocatable, private :: atol(:)      !< absolute tolerance per component
    !> stages k1..k16: k1..k12 of the step, k13 = f(t+h, y_new) (the next k1), k14..k16 the
    !> extra stages of the dense output
    real(wp), allocatable, private :: k(:, :)
    real(wp), allocatable, private :: y_stage(:), y_new(:)
    real(wp), allocatable, private :: slope(:)     !< sum b_i k_i: y_new = y + h*slope
    real(wp), allocatable, private :: e5(:), e3(:) !< 5th- and 3rd-order error estimates / h
    real(wp), allocatable, private :: cont(:, :)   !< the 8 coefficient vectors of CONTD8
    real(wp), private :: h = 0         !< step to try next
    real(wp), private :: h_done = 0    !< size of the last accepted step (0 = none yet)
    real(wp), private :: h_max = 0     !< options%h_max, or t_bound - t0 when that is 0
    real(wp), private :: fac_old = 1.0e-4_wp  !< previous accepted error norm (FACOLD)
    logical, private :: rejected = .false.    !< the previous trial step was rejected
    logical, private :: dense = .true.        !< compute the dense output stages
  end type dop853_integrator

  ! dop853.f's step-size control defaults, used in place of rk45_options' DOPRI5 defaults
  real(wp), parameter :: dop853_fac1 = 0.333_wp, dop853_fac2 = 6.0_wp, dop853_beta = 0.0_wp

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
  ! the 3 extra stages of the dense output (k14 at c14, k15 at c15, k16 at c16)
  real(wp), parameter :: &
    a141 = 5.61675022830479523392909219681e-2_wp, &
    a147 = 2.53500210216624811088794765333e-1_wp, &
    a148 = -2.46239037470802489917441475441e-1_wp, &
    a149 = -1.24191423263816360469010140626e-1_wp, &
    a1410 = 1.5329179827876569731206322685e-1_wp, &
    a1411 = 8.20105229563468988491666602057e-3_wp, &
    a1412 = 7.56789766054569976138603589584e-3_wp, &
    a1413 = -8.298e-3_wp
  real(wp), parameter :: &
    a151 = 3.18346481635021405060768473261e-2_wp, &
    a156 = 2.83009096723667755288322961402e-2_wp, &
    a157 = 5.35419883074385676223797384372e-2_wp, &
    a158 = -5.49237485713909884646569340306e-2_wp, &
    a1511 = -1.08347328697249322858509316994e-4_wp, &
    a1512 = 3.82571090835658412954920192323e-4_wp, &
    a1513 = -3.40465008687404560802977114492e-4_wp, &
    a1514 = 1.41312443674632500278074618366e-1_wp, &
    a161 = -4.28896301583791923408573538692e-1_wp, &
    a166 = -4.69762141536116384314449447206e0_wp, &
    a167 = 7.68342119606259904184240953878e0_wp, &
    a168 = 4.06898981839711007970213554331e0_wp, &
    a169 = 3.56727187455281109270669543021e-1_wp, &
    a1613 = -1.39902416515901462129418009734e-3_wp, &
    a1614 = 2.9475147891527723389556272149e0_wp, &
    a1615 = -9.15095847217987001081870187138e0_wp
  ! dense output: the 5th..8th coefficient vectors of CONTD8, cont(:, 5) = h sum d4j k_j, ...
  real(wp), parameter :: &
    d41 = -0.84289382761090128651353491142e+01_wp, &
    d46 = 0.56671495351937776962531783590e+00_wp, &
    d47 = -0.30689499459498916912797304727e+01_wp, &
    d48 = 0.23846676565120698287728149680e+01_wp, &
    d49 = 0.21170345824450282767155149946e+01_wp, &
    d410 = -0.87139158377797299206789907490e+00_wp, &
    d411 = 0.22404374302607882758541771650e+01_wp, &
    d412 = 0.63157877876946881815570249290e+00_wp, &
    d413 = -0.88990336451333310820698117400e-01_wp, &
    d414 = 0.18148505520854727256656404962e+02_wp, &
    d415 = -0.91946323924783554000451984436e+01_wp, &
    d416 = -0.44360363875948939664310572000e+01_wp
  real(wp), parameter :: &
    d51 = 0.10427508642579134603413151009e+02_wp, &
    d56 = 0.24228349177525818288430175319e+03_wp, &
    d57 = 0.16520045171727028198505394887e+03_wp, &
    d58 = -0.37454675472269020279518312152e+03_wp, &
    d59 = -0.22113666853125306036270938578e+02_wp, &
    d510 = 0.77334326684722638389603898808e+01_wp, &
    d511 = -0.30674084731089398182061213626e+02_wp, &
    d512 = -0.93321305264302278729567221706e+01_wp, &
    d513 = 0.15697238121770843886131091075e+02_wp, &
    d514 = -0.31139403219565177677282850411e+02_wp, &
    d515 = -0.93529243588444783865713862664e+01_wp, &
    d516 = 0.35816841486394083752465898540e+02_wp
  real(wp), parameter :: &
    d61 = 0.19985053242002433820987653617e+02_wp, &
    d66 = -0.38703730874935176555105901742e+03_wp, &
    d67 = -0.18917813819516756882830838328e+03_wp, &
    d68 = 0.52780815920542364900561016686e+03_wp, &
    d69 = -0.11573902539959630126141871134e+02_wp, &
    d610 = 0.68812326946963000169666922661e+01_wp, &
    d611 = -0.10006050966910838403183860980e+01_wp, &
    d612 = 0.77771377980534432092869265740e+00_wp, &
    d613 = -0.27782057523535084065932004339e+01_wp, &
    d614 = -0.60196695231264120758267380846e+02_wp, &
    d615 = 0.84320405506677161018159903784e+02_wp, &
    d616 = 0.11992291136182789328035130030e+02_wp
  real(wp), parameter :: &
    d71 = -0.25693933462703749003312586129e+02_wp, &
    d76 = -0.15418974869023643374053993627e+03_wp, &
    d77 = -0.23152937917604549567536039109e+03_wp, &
    d78 = 0.35763911791061412378285349910e+03_wp, &
    d79 = 0.93405324183624310003907691704e+02_wp, &
    d710 = -0.37458323136451633156875139351e+02_wp, &
    d711 = 0.10409964950896230045147246184e+03_wp, &
    d712 = 0.29840293426660503123344363579e+02_wp, &
    d713 = -0.43533456590011143754432175058e+02_wp, &
    d714 = 0.96324553959188282948394950600e+02_wp, &
    d715 = -0.39177261675615439165231486172e+02_wp, &
    d716 = -0.14972683625798562581422125276e+03_wp

contains

  !> Validate the inputs, allocate the work arrays and evaluate f(t0, y0); choose the first step.
  !> dense_output = .false. (default .true.) skips the 3 dense output stages of every accepted
  !> step; dop853_dense then only returns y at the end of the step, NaN elsewhere.
  subroutine dop853_init(integ, sys, t0, y0, t_bound, options, status, message, dense_output)
    type(dop853_integrator), intent(out) :: integ
    class(ode_system), intent(in) :: sys
    real(wp), intent(in) :: t0, y0(:), t_bound
    type(rk45_options), intent(in) :: options
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    logical, intent(in), optional :: dense_output
    type(rk45_options) :: rk45_defaults
    integer :: n

    status = SD_OK
    message = ''
    call rk45_check_setup(options, y0, status, message)
    call check_real('t0', t0, -huge(t0), huge(t0), .false., .false., 't0 must be finite', &
                    status, message)
    call check_real('t_bound', t_bound, t0, huge(t0), .true., .false., &
                    't_bound must be finite and > t0 = '//num2str(t0), status, message)
    if (status /= SD_OK) return

    n = size(y0)
    allocate (integ%y(n), integ%atol(n), integ%k(n, 16), integ%y_stage(n), integ%y_new(n), &
              integ%slope(n), integ%e5(n), integ%e3(n), integ%cont(n, 8))
    integ%opt = options
    ! DOPRI5's defaults left in place by the caller become dop853.f's
    if (options%fac1 == rk45_defaults%fac1) integ%opt%fac1 = dop853_fac1
    if (options%fac2 == rk45_defaults%fac2) integ%opt%fac2 = dop853_fac2
    if (options%beta == rk45_defaults%beta) integ%opt%beta = dop853_beta
    if (allocated(options%atol_vector)) then
      integ%atol = options%atol_vector
    else
      integ%atol = options%atol
    end if
    if (present(dense_output)) integ%dense = dense_output
    integ%t = t0
    integ%t_old = t0
    integ%t_bound = t_bound
    integ%y = y0
    integ%h_max = merge(options%h_max, t_bound - t0, options%h_max > 0)

    call sys%rhs(t0, integ%y, integ%k(:, 1))
    integ%n_rhs = 1
    if (.not. all(ieee_is_finite(integ%k(:, 1)))) then
      status = SD_NON_FINITE
      message = 'the right-hand side is NaN or infinite at the initial state, tau = '//num2str(t0)
      return
    end if

    if (options%fixed_step > 0) then
      integ%h = options%fixed_step
    else if (options%h_initial > 0) then
      integ%h = min(options%h_initial, integ%h_max)
    else
      call initial_step(integ, sys, integ%h)
    end if
  end subroutine dop853_init

  !> Advance by one accepted step (rejected trial steps are retried inside). On failure the
  !> integrator stays at its last accepted step.
  subroutine dop853_step(integ, sys, status, message)
    type(dop853_integrator), intent(inout) :: integ
    class(ode_system), intent(in) :: sys
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    real(wp) :: h, t_new, err, fac11, fac, h_new
    logical :: finite, fixed, non_finite_trial

    status = SD_OK
    message = ''
    if (.not. allocated(integ%k)) then
      status = SD_BAD_INPUT
      message = 'dop853_step needs an integrator set up by a successful dop853_init'
      return
    end if
    if (integ%t >= integ%t_bound) then
      status = SD_BAD_INPUT
      message = 'the integration already reached t_bound = '//num2str(integ%t_bound)
      return
    end if

    fixed = integ%opt%fixed_step > 0
    non_finite_trial = .false.
    do
      call plan_trial(integ%opt, integ%t, integ%t_bound, integ%h, &
                      integ%n_accepted + integ%n_rejected, non_finite_trial, h, t_new, status, &
                      message)
      if (status /= SD_OK) return

      call trial_step(integ, sys, h, t_new, finite)
      h_new = h
      err = 0
      if (finite .and. .not. fixed) then
        ! step-size control of dop853.f: h_new = h*safety/(err**expo1/err_old**beta), clamped
        err = error_norm(integ%e5, integ%e3, h, integ%y, integ%y_new, integ%atol, &
                         integ%opt%rtol)
        fac11 = err**(0.125_wp - 0.2_wp*integ%opt%beta)
        if (err > 1) then
          ! rejected: the plain (non-PI) formula, as in dop853.f
          integ%h = h/min(1/integ%opt%fac1, fac11/integ%opt%safety)
          integ%rejected = .true.
          integ%n_rejected = integ%n_rejected + 1
          non_finite_trial = .false.
          cycle
        end if
        fac = fac11/integ%fac_old**integ%opt%beta
        fac = max(1/integ%opt%fac2, min(1/integ%opt%fac1, fac/integ%opt%safety))
        h_new = h/fac
      end if
      ! f at the new point and the dense output stages, for steps that pass the error test
      if (finite) call closing_stages(integ, sys, h, t_new, finite)
      non_finite_trial = .not. finite

      if (.not. finite) then
        if (fixed) then
          status = SD_NON_FINITE
          message = 'the state became NaN or infinite in the fixed step from tau = '// &
                    num2str(integ%t)//' to '//num2str(t_new)
          return
        end if
        ! the trial left the region where f is defined: retry with the largest allowed cut
        integ%h = h*integ%opt%fac1
        integ%rejected = .true.
        integ%n_rejected = integ%n_rejected + 1
        cycle
      end if

      call accept(integ, h, t_new)
      if (fixed) return
      integ%fac_old = max(err, 1.0e-4_wp)
      h_new = min(h_new, integ%h_max)
      ! no growth right after a rejection
      if (integ%rejected) h_new = min(h_new, h)
      integ%rejected = .false.
      integ%h = h_new
      return
    end do
  end subroutine dop853_step

  !> Value at t of the continuous extension over the last accepted step [t_old, t] (CONTD8 of
  !> dop853.f, 7th order). Outside that step it extrapolates; before any step it returns y.
  !> Without dense output (dop853_init's dense_output = .false.) it returns y at t = integ%t
  !> and NaN at any other time.
  pure subroutine dop853_dense(integ, t, y)
    type(dop853_integrator), intent(in) :: integ
    real(wp), intent(in) :: t
    real(wp), intent(out) :: y(:)
    real(wp) :: s, s1

    if (integ%h_done == 0 .or. (.not. integ%dense .and. t == integ%t)) then
      y = integ%y
      return
    end if
    if (.not. integ%dense) then
      y = ieee_value(1.0_wp, ieee_quiet_nan)
      return
    end if
    s = (t - integ%t_old)/integ%h_done
    s1 = 1 - s
    associate (c => integ%cont)
      y = c(:, 1) + s*(c(:, 2) + s1*(c(:, 3) + s*(c(:, 4) + s1*(c(:, 5) + &
          s*(c(:, 6) + s1*(c(:, 7) + s*c(:, 8)))))))
    end associate
  end subroutine dop853_dense

  !> Replace the state at the current time (e.g. to renormalise variational vectors). This
  !> re-evaluates f for the next step's first stage and ends dense output of the previous step;
  !> the step size is kept.
  subroutine dop853_set_state(integ, sys, y, status, message)
    type(dop853_integrator), intent(inout) :: integ
    class(ode_system), intent(in) :: sys
    real(wp), intent(in) :: y(:)
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message

    status = SD_OK
    message = ''
    if (.not. allocated(integ%k)) then
      status = SD_BAD_INPUT
      message = 'dop853_set_state needs an integrator set up by a successful dop853_init'
      return
    end if
    if (size(y) /= size(integ%y)) then
      status = SD_BAD_INPUT
      message = 'y has size '//num2str(size(y))//'; the integrator state has size '// &
                num2str(size(integ%y))
      return
    end if
    if (.not. all(ieee_is_finite(y))) then
      status = SD_BAD_INPUT
      message = 'y is out of range: the new state must be finite'
      return
    end if
    integ%y = y
    call sys%rhs(integ%t, integ%y, integ%k(:, 1))
    integ%n_rhs = integ%n_rhs + 1
    integ%t_old = integ%t
    integ%h_done = 0
    if (.not. all(ieee_is_finite(integ%k(:, 1)))) then
      status = SD_NON_FINITE
      message = 'the right-hand side is NaN or infinite at the new state, tau = '//num2str(integ%t)
    end if
  end subroutine dop853_set_state

  !> Counters of the integration so far and the time reached.
  pure function dop853_statistics(integ) result(stats)
    type(dop853_integrator), intent(in) :: integ
    type(rk45_stats) :: stats
    stats = rk45_stats(integ%n_rhs, integ%n_accepted, integ%n_rejected, integ%t)
  end function dop853_statistics

  !> y at every time of t_out (ascending, all >= t0) by dense output: y_out(:, j) = y(t_out(j)),
  !> shape (size(y0), size(t_out)). On failure the columns already reached are filled, the rest
  !> are NaN, and stats%t_reached says how far the integration got. When every output time
  !> after t0 is the final one, the dense output stages are skipped.
  subroutine dop853_integrate(sys, t0, y0, t_out, y_out, options, stats, status, message)
    class(ode_system), intent(in) :: sys
    real(wp), intent(in) :: t0, y0(:), t_out(:)
    real(wp), intent(out) :: y_out(:, :)
    type(rk45_options), intent(in) :: options
    type(rk45_stats), intent(out) :: stats
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    type(dop853_integrator) :: integ
    integer :: j, n_out

    status = SD_OK
    message = ''
    stats%t_reached = t0
    y_out = ieee_value(1.0_wp, ieee_quiet_nan)
    n_out = size(t_out)
    if (size(y_out, 1) /= size(y0) .or. size(y_out, 2) /= n_out) then
      status = SD_BAD_INPUT
      message = 'y_out has shape ('//num2str(size(y_out, 1))//', '//num2str(size(y_out, 2))// &
                '); it must be (size(y0), size(t_out)) = ('//num2str(size(y0))//', '// &
                num2str(n_out)//')'
      return
    end if
    if (n_out > 0) call check_real('t_out(1)', t_out(1), t0, huge(t0), .false., .false., &
                                   't_out must start at or after t0 = '//num2str(t0), status, &
                                   message)
    do j = 2, n_out
      if (t_out(j) >= t_out(j - 1) .and. t_out(j) <= huge(t0)) cycle
      call check_real('t_out('//num2str(j)//')', t_out(j), t_out(j - 1), huge(t0), .false., &
                      .false., 't_out must be ascending, >= t_out('//num2str(j - 1)//') = '// &
                      num2str(t_out(j - 1)), status, message)
      exit
    end do
    call rk45_check_setup(options, y0, status, message)
    if (status /= SD_OK) return

    ! outputs at t0 itself need no step
    j = 1
    do while (j <= n_out)
      if (t_out(j) > t0) exit
      y_out(:, j) = y0
      j = j + 1
    end do
    if (j > n_out) return

    call dop853_init(integ, sys, t0, y0, t_out(n_out), options, status, message, &
                     dense_output=t_out(j) < t_out(n_out))
    do while (status == SD_OK .and. j <= n_out)
      call dop853_step(integ, sys, status, message)
      if (status /= SD_OK) exit
      do while (j <= n_out)
        if (t_out(j) > integ%t) exit
        if (t_out(j) == integ%t) then
          y_out(:, j) = integ%y
        else
          call dop853_dense(integ, t_out(j), y_out(:, j))
        end if
        j = j + 1
      end do
    end do
    stats = dop853_statistics(integ)
  end subroutine dop853_integrate

  !> One trial step of size h from (t, y) to t_new: stages k2..k12 (DP86CO's loops 22-32), the
  !> 8th-order y_new and the error estimates e5, e3 (divided by h). finite = .false. when any
  !> of them is NaN or infinite.
  subroutine trial_step(integ, sys, h, t_new, finite)
    type(dop853_integrator), intent(inout) :: integ
    class(ode_system), intent(in) :: sys
    real(wp), intent(in) :: h, t_new
    logical, intent(out) :: finite
    real(wp) :: t

    t = integ%t
    associate (y => integ%y, k => integ%k, ys => integ%y_stage, yn => integ%y_new, &
               slope => integ%slope)
      ys = y + h*a21*k(:, 1)
      call sys%rhs(t + c2*h, ys, k(:, 2))
      ys = y + h*(a31*k(:, 1) + a32*k(:, 2))
      call sys%rhs(t + c3*h, ys, k(:, 3))
      ys = y + h*(a41*k(:, 1) + a43*k(:, 3))
      call sys%rhs(t + c4*h, ys, k(:, 4))
      ys = y + h*(a51*k(:, 1) + a53*k(:, 3) + a54*k(:, 4))
      call sys%rhs(t + c5*h, ys, k(:, 5))
      ys = y + h*(a61*k(:, 1) + a64*k(:, 4) + a65*k(:, 5))
      call sys%rhs(t + c6*h, ys, k(:, 6))
      ys = y + h*(a71*k(:, 1) + a74*k(:, 4) + a75*k(:, 5) + a76*k(:, 6))
      call sys%rhs(t + c7*h, ys, k(:, 7))
      ys = y + h*(a81*k(:, 1) + a84*k(:, 4) + a85*k(:, 5) + a86*k(:, 6) + a87*k(:, 7))
      call sys%rhs(t + c8*h, ys, k(:, 8))
      ys = y + h*(a91*k(:, 1) + a94*k(:, 4) + a95*k(:, 5) + a96*k(:, 6) + a97*k(:, 7) + &
                  a98*k(:, 8))
      call sys%rhs(t + c9*h, ys, k(:, 9))
      ys = y + h*(a101*k(:, 1) + a104*k(:, 4) + a105*k(:, 5) + a106*k(:, 6) + a107*k(:, 7) + &
                  a108*k(:, 8) + a109*k(:, 9))
      call sys%rhs(t + c10*h, ys, k(:, 10))
      ys = y + h*(a111*k(:, 1) + a114*k(:, 4) + a115*k(:, 5) + a116*k(:, 6) + a117*k(:, 7) + &
                  a118*k(:, 8) + a119*k(:, 9) + a1110*k(:, 10))
      call sys%rhs(t + c11*h, ys, k(:, 11))
      ys = y + h*(a121*k(:, 1) + a124*k(:, 4) + a125*k(:, 5) + a126*k(:, 6) + a127*k(:, 7) + &
                  a128*k(:, 8) + a129*k(:, 9) + a1210*k(:, 10) + a1211*k(:, 11))
      call sys%rhs(t_new, ys, k(:, 12))
      slope = b1*k(:, 1) + b6*k(:, 6) + b7*k(:, 7) + b8*k(:, 8) + b9*k(:, 9) + &
              b10*k(:, 10) + b11*k(:, 11) + b12*k(:, 12)
      yn = y + h*slope
      integ%e3 = slope - bhh1*k(:, 1) - bhh2*k(:, 9) - bhh3*k(:, 12)
      integ%e5 = er1*k(:, 1) + er6*k(:, 6) + er7*k(:, 7) + er8*k(:, 8) + er9*k(:, 9) + &
                 er10*k(:, 10) + er11*k(:, 11) + er12*k(:, 12)
      finite = all(ieee_is_finite(yn)) .and. all(ieee_is_finite(integ%e3)) .and. &
               all(ieee_is_finite(integ%e5))
    end associate
    integ%n_rhs = integ%n_rhs + 11
  end subroutine trial_step

  !> For a trial step that passed: k13 = f(t_new, y_new) (the next step's k1), then, with dense
  !> output, the 3 extra stages k14..k16 (DP86CO's loops 51-53). finite = .false. when any of
  !> them is NaN or infinite.
  subroutine closing_stages(integ, sys, h, t_new, finite)
    type(dop853_integrator), intent(inout) :: integ
    class(ode_system), intent(in) :: sys
    real(wp), intent(in) :: h, t_new
    logical, intent(out) :: finite
    real(wp) :: t

    t = integ%t
    associate (y => integ%y, k => integ%k, ys => integ%y_stage)
      call sys%rhs(t_new, integ%y_new, k(:, 13))
      integ%n_rhs = integ%n_rhs + 1
      finite = all(ieee_is_finite(k(:, 13)))
      if (.not. finite .or. .not. integ%dense) return
      ys = y + h*(a141*k(:, 1) + a147*k(:, 7) + a148*k(:, 8) + a149*k(:, 9) + &
                  a1410*k(:, 10) + a1411*k(:, 11) + a1412*k(:, 12) + a1413*k(:, 13))
      call sys%rhs(t + c14*h, ys, k(:, 14))
      ys = y + h*(a151*k(:, 1) + a156*k(:, 6) + a157*k(:, 7) + a158*k(:, 8) + &
                  a1511*k(:, 11) + a1512*k(:, 12) + a1513*k(:, 13) + a1514*k(:, 14))
      call sys%rhs(t + c15*h, ys, k(:, 15))
      ys = y + h*(a161*k(:, 1) + a166*k(:, 6) + a167*k(:, 7) + a168*k(:, 8) + &
                  a169*k(:, 9) + a1613*k(:, 13) + a1614*k(:, 14) + a1615*k(:, 15))
      call sys%rhs(t + c16*h, ys, k(:, 16))
      integ%n_rhs = integ%n_rhs + 3
      finite = all(ieee_is_finite(k(:, 14:16)))
    end associate
  end subroutine closing_stages

  !> Accept the trial step: store the dense output coefficients (CONT of DP86CO's loops 62 and
  !> 63) and move to (t_new, y_new), reusing k13 as the next k1.
  pure subroutine accept(integ, h, t_new)
    type(dop853_integrator), intent(inout) :: integ
    real(wp), intent(in) :: h, t_new

    associate (y => integ%y, k => integ%k, cont => integ%cont)
      if (integ%dense) then
        cont(:, 1) = y
        cont(:, 2) = integ%y_new - y
        cont(:, 3) = h*k(:, 1) - cont(:, 2)
        cont(:, 4) = cont(:, 2) - h*k(:, 13) - cont(:, 3)
        cont(:, 5) = h*(d41*k(:, 1) + d46*k(:, 6) + d47*k(:, 7) + d48*k(:, 8) + d49*k(:, 9) + &
                        d410*k(:, 10) + d411*k(:, 11) + d412*k(:, 12) + d413*k(:, 13) + &
                        d414*k(:, 14) + d415*k(:, 15) + d416*k(:, 16))
        cont(:, 6) = h*(d51*k(:, 1) + d56*k(:, 6) + d57*k(:, 7) + d58*k(:, 8) + d59*k(:, 9) + &
                        d510*k(:, 10) + d511*k(:, 11) + d512*k(:, 12) + d513*k(:, 13) + &
                        d514*k(:, 14) + d515*k(:, 15) + d516*k(:, 16))
        cont(:, 7) = h*(d61*k(:, 1) + d66*k(:, 6) + d67*k(:, 7) + d68*k(:, 8) + d69*k(:, 9) + &
                        d610*k(:, 10) + d611*k(:, 11) + d612*k(:, 12) + d613*k(:, 13) + &
                        d614*k(:, 14) + d615*k(:, 15) + d616*k(:, 16))
        cont(:, 8) = h*(d71*k(:, 1) + d76*k(:, 6) + d77*k(:, 7) + d78*k(:, 8) + d79*k(:, 9) + &
                        d710*k(:, 10) + d711*k(:, 11) + d712*k(:, 12) + d713*k(:, 13) + &
                        d714*k(:, 14) + d715*k(:, 15) + d716*k(:, 16))
      end if
      y = integ%y_new
      k(:, 1) = k(:, 13)
    end associate
    integ%t_old = integ%t
    integ%t = t_new
    integ%h_done = h
    integ%n_accepted = integ%n_accepted + 1
  end subroutine accept

  !> HINIT of dop853.f with IORD = 8: an explicit Euler step sized so that its increment is
  !> small against y, then h with h**8 * max(|f|, |f'|) = 0.01 in the scaled norm, at most 100
  !> times the Euler guess. Uses k2, y_stage and e5 as scratch; one right-hand side evaluation.
  subroutine initial_step(integ, sys, h)
    type(dop853_integrator), intent(inout) :: integ
    class(ode_system), intent(in) :: sys
    real(wp), intent(out) :: h
    real(wp) :: dnf, dny, der2, der12, h1

    associate (y => integ%y, f0 => integ%k(:, 1), f1 => integ%k(:, 2), y1 => integ%y_stage, &
               sk => integ%e5)
      sk = integ%atol + integ%opt%rtol*abs(y)
      dnf = sum((f0/sk)**2)
      dny = sum((y/sk)**2)
      if (dnf <= 1.0e-10_wp .or. dny <= 1.0e-10_wp) then
        h = 1.0e-6_wp
      else
        h = 0.01_wp*sqrt(dny/dnf)
      end if
      h = min(h, integ%h_max)
      y1 = y + h*f0
      call sys%rhs(integ%t + h, y1, f1)
      integ%n_rhs = integ%n_rhs + 1
      ! f undefined a small step ahead: keep the cautious Euler guess
      if (.not. all(ieee_is_finite(f1))) return
      der2 = sqrt(sum(((f1 - f0)/sk)**2))/h
      der12 = max(der2, sqrt(dnf))
      if (der12 <= 1.0e-15_wp) then
        h1 = max(1.0e-6_wp, h*1.0e-3_wp)
      else
        h1 = (0.01_wp/der12)**0.125_wp
      end if
      h = min(100*h, h1, integ%h_max)
    end associate
  end subroutine initial_step

  !> dop853.f's error norm: with sk_i = atol_i + rtol*max(|y0_i|, |y1_i|), E5 = sum (e5_i/sk_i)**2
  !> and E3 = sum (e3_i/sk_i)**2, err = |h| E5 / sqrt(n (E5 + 0.01 E3)) (= 0 when both vanish).
  !> Zero terms are skipped so that sk_i = 0 cannot give 0/0; an overflow counts as huge.
  pure function error_norm(e5, e3, h, y0, y1, atol, rtol) result(err)
    real(wp), intent(in) :: e5(:), e3(:), h, y0(:), y1(:), atol(:), rtol
    real(wp) :: err
    real(wp) :: err5, err3, sk, deno
    integer :: i

    err5 = 0
    err3 = 0
    do i = 1, size(e5)
      sk = atol(i) + rtol*max(abs(y0(i)), abs(y1(i)))
      if (e5(i) /= 0) err5 = err5 + (e5(i)/sk)**2
      if (e3(i) /= 0) err3 = err3 + (e3(i)/sk)**2
    end do
    deno = err5 + 0.01_wp*err3
    if (deno <= 0) deno = 1
    err = abs(h)*err5*sqrt(1/(size(e5)*deno))
    if (.not. err <= huge(err)) err = huge(err)
  end function error_norm

end module sloshdyn_dop853
