!> Explicit Runge-Kutta pair of order 8(5,3): Hairer's DOP853, the Dormand-Prince pair
!> (Hairer, Norsett & Wanner, Solving Ordinary Differential Equations I, 2nd ed., sec. II.10,
!> and the published dop853.f, version of April 25, 1996 with the corrections of March 4, 2002),
!> as a method of the integrator family of sloshdyn_ode: 12 stages per step (11 new right-hand
!> sides, the first is the previous step's last), the error estimate that combines the 5th- and
!> 3rd-order embedded differences, and the 7th-order dense output (CONTD8) built with 3 extra
!> stages per accepted step. Step control defaults of dop853.f: fac1 = 0.333, fac2 = 6, beta = 0.
!>
!> Cost: 11 right-hand sides per trial step, plus 4 per accepted step (f at the new point,
!> which is the next step's first stage, and the 3 dense output stages; 1 without dense output).
!>
!> Departures from dop853.f, shared by the family: rejected steps are counted from the first
!> trial on; max_steps limits accepted + rejected steps; a trial step whose stages are NaN or
!> infinite is rejected with the largest cut (fac1); the smallest step is the family's h_min
!> rule instead of 0.1|h| <= uround|t|; no stiffness detection; no output routine (dense output
!> is read after each step).
module sloshdyn_dop853
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use sloshdyn_kinds, only: wp
  use sloshdyn_ode, only: rk_integrator, method_properties, dense_from_state
  implicit none
  private
  public :: dop853_integrator

  type, extends(rk_integrator) :: dop853_integrator
    real(wp), allocatable :: slope(:)       !< sum b_i k_i: y_new = y + h*slope
    real(wp), allocatable :: e5(:), e3(:)   !< 5th- and 3rd-order error estimates / h
  contains
    procedure :: stage => dop853_stage
    procedure :: trial_error => dop853_trial_error
    procedure :: finish_stages => dop853_finish_stages
    procedure :: store_dense => dop853_store_dense
    procedure :: dense => dop853_dense
    procedure :: properties => dop853_properties
    procedure :: allocate_extra => dop853_allocate
  end type dop853_integrator

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

  pure function dop853_properties(self) result(info)
    class(dop853_integrator), intent(in) :: self
    type(method_properties) :: info
    info = method_properties(name='dop853', order=8, stages=16, trial_stages=11, &
                             dense_columns=8, &
                             expo_base=0.125_wp, beta_factor=0.2_wp, fac1=0.333_wp, &
                             fac2=6.0_wp, beta=0.0_wp)
  end function dop853_properties

  pure subroutine dop853_allocate(self, n)
    class(dop853_integrator), intent(inout) :: self
    integer, intent(in) :: n
    allocate (self%slope(n), self%e5(n), self%e3(n))
  end subroutine dop853_allocate

  !> Stage s of a step (see sloshdyn_ode's method_stage): s = 1..11 are k2..k12 (DP86CO's loops
  !> 22-32), s = 12 is k13 = f(t_new, y_new) (the next step's k1), s = 13..15 the dense-output
  !> stages k14..k16 (loops 51-53).
  pure subroutine dop853_stage(self, s, h, t_new, t_s, col)
    class(dop853_integrator), intent(inout) :: self
    integer, intent(in) :: s
    real(wp), intent(in) :: h, t_new
    real(wp), intent(out) :: t_s
    integer, intent(out) :: col
    real(wp), parameter :: nodes(2:16) = [c2, c3, c4, c5, c6, c7, c8, c9, c10, c11, 1.0_wp, &
                                          1.0_wp, c14, c15, c16]
    col = s + 1
    t_s = self%t + nodes(col)*h
    if (col == 12 .or. col == 13) t_s = t_new
    if (col == 13) then
      self%y_stage = self%y_new
    else
      call stage_input(size(self%y), col, h, self%y, self%k, self%y_stage)
    end if
  end subroutine dop853_stage

  !> The input y + h sum_j a(col, j) k_j of stage col, on explicit-shape arrays (the family's
  !> rule, sloshdyn_ode).
  pure subroutine stage_input(n, col, h, y, k, ys)
    integer, intent(in) :: n, col
    real(wp), intent(in) :: h, y(n), k(n, 16)
    real(wp), intent(out) :: ys(n)

    select case (col)
    case (2)
      ys = y + h*a21*k(:, 1)
    case (3)
      ys = y + h*(a31*k(:, 1) + a32*k(:, 2))
    case (4)
      ys = y + h*(a41*k(:, 1) + a43*k(:, 3))
    case (5)
      ys = y + h*(a51*k(:, 1) + a53*k(:, 3) + a54*k(:, 4))
    case (6)
      ys = y + h*(a61*k(:, 1) + a64*k(:, 4) + a65*k(:, 5))
    case (7)
      ys = y + h*(a71*k(:, 1) + a74*k(:, 4) + a75*k(:, 5) + a76*k(:, 6))
    case (8)
      ys = y + h*(a81*k(:, 1) + a84*k(:, 4) + a85*k(:, 5) + a86*k(:, 6) + a87*k(:, 7))
    case (9)
      ys = y + h*(a91*k(:, 1) + a94*k(:, 4) + a95*k(:, 5) + a96*k(:, 6) + a97*k(:, 7) + &
                  a98*k(:, 8))
    case (10)
      ys = y + h*(a101*k(:, 1) + a104*k(:, 4) + a105*k(:, 5) + a106*k(:, 6) + a107*k(:, 7) + &
                  a108*k(:, 8) + a109*k(:, 9))
    case (11)
      ys = y + h*(a111*k(:, 1) + a114*k(:, 4) + a115*k(:, 5) + a116*k(:, 6) + a117*k(:, 7) + &
                  a118*k(:, 8) + a119*k(:, 9) + a1110*k(:, 10))
    case (12)
      ys = y + h*(a121*k(:, 1) + a124*k(:, 4) + a125*k(:, 5) + a126*k(:, 6) + a127*k(:, 7) + &
                  a128*k(:, 8) + a129*k(:, 9) + a1210*k(:, 10) + a1211*k(:, 11))
    case (14)
      ys = y + h*(a141*k(:, 1) + a147*k(:, 7) + a148*k(:, 8) + a149*k(:, 9) + &
                  a1410*k(:, 10) + a1411*k(:, 11) + a1412*k(:, 12) + a1413*k(:, 13))
    case (15)
      ys = y + h*(a151*k(:, 1) + a156*k(:, 6) + a157*k(:, 7) + a158*k(:, 8) + &
                  a1511*k(:, 11) + a1512*k(:, 12) + a1513*k(:, 13) + a1514*k(:, 14))
    case default
      ys = y + h*(a161*k(:, 1) + a166*k(:, 6) + a167*k(:, 7) + a168*k(:, 8) + &
                  a169*k(:, 9) + a1613*k(:, 13) + a1614*k(:, 14) + a1615*k(:, 15))
    end select
  end subroutine stage_input

  !> After the trial stages: the 8th-order y_new, the error estimates e5, e3 (divided by h) and
  !> the error norm.
  pure subroutine dop853_trial_error(self, h, err, finite)
    class(dop853_integrator), intent(inout) :: self
    real(wp), intent(in) :: h
    real(wp), intent(out) :: err
    logical, intent(out) :: finite

    call trial_end(size(self%y), h, self%y, self%k, self%y_new, self%slope, self%e3, self%e5, &
                   finite)
    err = 0
    if (finite) err = error_norm(self%e5, self%e3, h, self%y, self%y_new, self%atol, &
                                 self%opt%rtol)
  end subroutine dop853_trial_error

  pure subroutine trial_end(n, h, y, k, yn, slope, e3, e5, finite)
    integer, intent(in) :: n
    real(wp), intent(in) :: h, y(n), k(n, 16)
    real(wp), intent(out) :: yn(n), slope(n), e3(n), e5(n)
    logical, intent(out) :: finite

    slope = b1*k(:, 1) + b6*k(:, 6) + b7*k(:, 7) + b8*k(:, 8) + b9*k(:, 9) + &
            b10*k(:, 10) + b11*k(:, 11) + b12*k(:, 12)
    yn = y + h*slope
    e3 = slope - bhh1*k(:, 1) - bhh2*k(:, 9) - bhh3*k(:, 12)
    e5 = er1*k(:, 1) + er6*k(:, 6) + er7*k(:, 7) + er8*k(:, 8) + er9*k(:, 9) + &
         er10*k(:, 10) + er11*k(:, 11) + er12*k(:, 12)
    finite = all(ieee_is_finite(yn)) .and. all(ieee_is_finite(e3)) .and. &
             all(ieee_is_finite(e5))
  end subroutine trial_end

  !> k13 (the next step's k1), and with dense output the 3 extra stages k14..k16.
  pure integer function dop853_finish_stages(self) result(n)
    class(dop853_integrator), intent(in) :: self
    n = merge(4, 1, self%dense_output)
  end function dop853_finish_stages

  !> The dense output coefficients (CONT of DP86CO's loops 62 and 63) of an accepted step;
  !> k13 becomes the next k1.
  pure subroutine dop853_store_dense(self, h)
    class(dop853_integrator), intent(inout) :: self
    real(wp), intent(in) :: h

    associate (y => self%y, k => self%k, cont => self%cont)
      if (self%dense_output) then
        cont(:, 1) = y
        cont(:, 2) = self%y_new - y
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
      k(:, 1) = k(:, 13)
    end associate
  end subroutine dop853_store_dense

  !> Value at t of the continuous extension over the last accepted step [t_old, t] (CONTD8 of
  !> dop853.f, 7th order). Outside that step it extrapolates; before any step it returns y.
  !> Without dense output (init's dense_output = .false.) it returns y at t = integ%t and NaN at
  !> any other time.
  pure subroutine dop853_dense(self, t, y)
    class(dop853_integrator), intent(in) :: self
    real(wp), intent(in) :: t
    real(wp), intent(out) :: y(:)
    real(wp) :: s, s1
    logical :: done

    call dense_from_state(self, t, y, done)
    if (done) return
    s = (t - self%t_old)/self%h_done
    s1 = 1 - s
    associate (c => self%cont)
      y = c(:, 1) + s*(c(:, 2) + s1*(c(:, 3) + s*(c(:, 4) + s1*(c(:, 5) + &
          s*(c(:, 6) + s1*(c(:, 7) + s*c(:, 8)))))))
    end associate
  end subroutine dop853_dense

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
