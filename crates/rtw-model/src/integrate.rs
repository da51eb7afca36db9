//! Runge–Kutta integrators with dense output.
//!
//! Three methods, all written over fixed-size arrays (`[f64; N]`) so that a
//! step never allocates:
//!
//! * [`Method::Dp54`] — Dormand–Prince 5(4) (Hairer's `dopri5`): 7 stages,
//!   first-same-as-last, 4th-order embedded error estimate, 4th-order
//!   continuous extension (Hairer's `contd5`).
//! * [`Method::Dop853`] — Dormand–Prince 8(5,3) (Hairer's `dop853`): 12
//!   stages plus FSAL, the combined 5th/3rd-order error estimator, and the
//!   7th-order continuous extension that costs 3 extra stages.
//! * [`Method::Rk4`] — the classic 4-stage Runge–Kutta method with a fixed
//!   step and a cubic Hermite interpolant built from `y0, y1, f0, f1`.
//!
//! The adaptive step-size control and the event-driven step loop live in
//! [`crate::hybrid`]; this module provides the tableaux, one-step kernels,
//! the [`Dense`] output and a fixed-step driver ([`fixed_step_solve`]) used to
//! measure orders of convergence.
//!
//! Coefficients: Dormand & Prince (1980) for DP5 with Shampine's dense output
//! as in Hairer, Nørsett & Wanner, *Solving ODEs I*, §II.6; DOP853 from
//! Hairer's `dop853.f` (Prince & Dormand 1981, dense output of §II.6). Their
//! orders are checked by `tests/integrator.rs`.
#![allow(clippy::needless_range_loop, clippy::excessive_precision)]

/// Integration method.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Method {
    /// Dormand–Prince 5(4), adaptive, 4th-order dense output.
    Dp54,
    /// Dormand–Prince 8(5,3), adaptive, 7th-order dense output.
    Dop853,
    /// Classic RK4 with a fixed step `h` (cubic Hermite dense output).
    Rk4 { h: f64 },
}

impl Method {
    /// Order of the method's solution (global error `O(h^order)`): 5, 8 or 4.
    #[inline]
    pub const fn order(&self) -> u32 {
        match self {
            Method::Dp54 => 5,
            Method::Dop853 => 8,
            Method::Rk4 { .. } => 4,
        }
    }

    /// Order of the dense output (interpolation error `O(h^(order+1))` per
    /// step): 4, 7 or 3.
    #[inline]
    pub const fn dense_order(&self) -> u32 {
        match self {
            Method::Dp54 => 4,
            Method::Dop853 => 7,
            Method::Rk4 { .. } => 3,
        }
    }

    /// Whether the method controls its step size from an error estimate.
    #[inline]
    pub const fn is_adaptive(&self) -> bool {
        !matches!(self, Method::Rk4 { .. })
    }

    /// Right-hand-side evaluations of one step attempt, including the
    /// evaluation at the step's end that the next step reuses (FSAL), but not
    /// the extra stages of DOP853's dense output ([`DOP853_DENSE_EVALS`]).
    #[inline]
    pub const fn evals_per_step(&self) -> u64 {
        match self {
            Method::Dp54 => 6,
            Method::Dop853 => 12,
            Method::Rk4 { .. } => 4,
        }
    }
}

/// Extra right-hand-side evaluations that DOP853's 7th-order dense output costs.
pub const DOP853_DENSE_EVALS: u64 = 3;

/// Largest number of polynomial coefficient arrays a [`Dense`] holds.
pub const MAX_DENSE_TERMS: usize = 7;

/// Dense output of one step on `[t0, t1]`.
///
/// The interpolant is the polynomial, in `θ = (t − t0)/h` with `h` the length
/// of the step that produced it,
///
/// `y(θ) = y0 + θ(F0 + (1−θ)(F1 + θ(F2 + (1−θ)(F3 + θ(F4 + (1−θ)(F5 + θ F6))))))`
///
/// truncated after 3 (cubic Hermite), 4 (DP5, Hairer's `contd5`) or 7
/// (DOP853, Hairer's `contd8`) terms, with `F0 = y1 − y0`, so `y(1) = y1`.
/// When the engine cuts a step at an event it only moves `t1` and `y1`
/// (`y1 = eval(t1)`): the polynomial stays the same.
#[derive(Clone, Copy, Debug)]
pub struct Dense<const N: usize> {
    pub t0: f64,
    pub t1: f64,
    pub y0: [f64; N],
    pub y1: [f64; N],
    /// Length of the step the polynomial was built on (`θ = (t − t0)/h`).
    h: f64,
    /// Number of live coefficient arrays in `coef` (1, 3, 4 or 7).
    terms: usize,
    coef: [[f64; N]; MAX_DENSE_TERMS],
}

impl<const N: usize> Default for Dense<N> {
    fn default() -> Self {
        Self::constant(0.0, &[0.0; N])
    }
}

impl<const N: usize> Dense<N> {
    /// The constant dense output `y(t) = y` on the single point `[t, t]`.
    pub fn constant(t: f64, y: &[f64; N]) -> Self {
        Self {
            t0: t,
            t1: t,
            y0: *y,
            y1: *y,
            h: 1.0,
            terms: 1,
            coef: [[0.0; N]; MAX_DENSE_TERMS],
        }
    }

    /// The cubic Hermite interpolant on `[t0, t1]` through `(y0, f0)` and
    /// `(y1, f1)` (values and derivatives at both ends).
    pub fn hermite(
        t0: f64,
        y0: &[f64; N],
        f0: &[f64; N],
        t1: f64,
        y1: &[f64; N],
        f1: &[f64; N],
    ) -> Self {
        let mut d = Self::constant(t0, y0);
        d.set_hermite(t0, y0, f0, t1 - t0, t1, y1, f1);
        d
    }

    /// Cubic Hermite over a step of length `h` (the DP5 form with `r5 = 0`).
    #[inline]
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn set_hermite(
        &mut self,
        t0: f64,
        y0: &[f64; N],
        f0: &[f64; N],
        h: f64,
        t1: f64,
        y1: &[f64; N],
        f1: &[f64; N],
    ) {
        self.t0 = t0;
        self.t1 = t1;
        self.h = h;
        self.terms = 3;
        self.y0 = *y0;
        self.y1 = *y1;
        for i in 0..N {
            let dy = y1[i] - y0[i];
            let b = h * f0[i] - dy;
            self.coef[0][i] = dy;
            self.coef[1][i] = b;
            self.coef[2][i] = dy - h * f1[i] - b;
        }
    }

    /// Length of the step the interpolating polynomial was built on (equal
    /// to `t1 − t0` unless the step was cut at an event).
    #[inline]
    pub fn step_len(&self) -> f64 {
        self.h
    }

    /// Number of polynomial coefficient arrays in use: 3 for a cubic Hermite
    /// interpolant, 4 for DP5's, 7 for DOP853's (1 for [`Dense::constant`]).
    #[inline]
    pub fn terms(&self) -> usize {
        self.terms
    }

    /// Cuts the validity interval at `t ∈ [t0, t1]`: `t1 = t`, `y1 = eval(t)`.
    /// The polynomial is unchanged.
    #[inline]
    pub fn truncate(&mut self, t: f64) {
        let mut y = [0.0; N];
        self.eval(t, &mut y);
        self.t1 = t;
        self.y1 = y;
    }

    /// The interpolated state at `t ∈ [t0, t1]` (outside that interval the
    /// polynomial is extrapolated). `eval(t0)` is `y0` and `eval(t1)` is `y1`
    /// exactly.
    #[inline]
    pub fn eval(&self, t: f64, out: &mut [f64; N]) {
        if t == self.t1 {
            *out = self.y1;
            return;
        }
        let th = (t - self.t0) / self.h;
        let th1 = 1.0 - th;
        match self.terms {
            7 => {
                for i in 0..N {
                    let c = &self.coef;
                    let acc = c[5][i] + th * c[6][i];
                    let acc = c[4][i] + th1 * acc;
                    let acc = c[3][i] + th * acc;
                    let acc = c[2][i] + th1 * acc;
                    let acc = c[1][i] + th * acc;
                    let acc = c[0][i] + th1 * acc;
                    out[i] = self.y0[i] + th * acc;
                }
            }
            4 => {
                for i in 0..N {
                    let c = &self.coef;
                    let acc = c[2][i] + th1 * c[3][i];
                    let acc = c[1][i] + th * acc;
                    let acc = c[0][i] + th1 * acc;
                    out[i] = self.y0[i] + th * acc;
                }
            }
            3 => {
                for i in 0..N {
                    let c = &self.coef;
                    let acc = c[1][i] + th * c[2][i];
                    let acc = c[0][i] + th1 * acc;
                    out[i] = self.y0[i] + th * acc;
                }
            }
            m => {
                // General nesting: F_{j-1} + w_j · (inner), w_j = 1−θ for odd j, θ for even j.
                for i in 0..N {
                    let mut acc = self.coef[m - 1][i];
                    let mut j = m - 1;
                    while j >= 1 {
                        let w = if j % 2 == 1 { th1 } else { th };
                        acc = self.coef[j - 1][i] + w * acc;
                        j -= 1;
                    }
                    out[i] = self.y0[i] + th * acc;
                }
            }
        }
    }
}

// ---------------------------------------------------------------------------
// Tableaux
// ---------------------------------------------------------------------------

// Dormand–Prince 5(4) (Hairer's dopri5).
const A21: f64 = 1.0 / 5.0;
const A31: f64 = 3.0 / 40.0;
const A32: f64 = 9.0 / 40.0;
const A41: f64 = 44.0 / 45.0;
const A42: f64 = -56.0 / 15.0;
const A43: f64 = 32.0 / 9.0;
const A51: f64 = 19372.0 / 6561.0;
const A52: f64 = -25360.0 / 2187.0;
const A53: f64 = 64448.0 / 6561.0;
const A54: f64 = -212.0 / 729.0;
const A61: f64 = 9017.0 / 3168.0;
const A62: f64 = -355.0 / 33.0;
const A63: f64 = 46732.0 / 5247.0;
const A64: f64 = 49.0 / 176.0;
const A65: f64 = -5103.0 / 18656.0;
const A71: f64 = 35.0 / 384.0;
const A73: f64 = 500.0 / 1113.0;
const A74: f64 = 125.0 / 192.0;
const A75: f64 = -2187.0 / 6784.0;
const A76: f64 = 11.0 / 84.0;
// Error weights e_i = b_i − b̂_i.
const E1: f64 = 71.0 / 57600.0;
const E3: f64 = -71.0 / 16695.0;
const E4: f64 = 71.0 / 1920.0;
const E5: f64 = -17253.0 / 339200.0;
const E6: f64 = 22.0 / 525.0;
const E7: f64 = -1.0 / 40.0;
// Dense output (Shampine), Hairer's d1..d7.
const D1: f64 = -12715105075.0 / 11282082432.0;
const D3: f64 = 87487479700.0 / 32700410799.0;
const D4: f64 = -10690763975.0 / 1880347072.0;
const D5: f64 = 701980252875.0 / 199316789632.0;
const D6: f64 = -1453857185.0 / 822651844.0;
const D7: f64 = 69997945.0 / 29380423.0;

// Dormand–Prince 8(5,3) (Hairer's dop853).
/// Nodes `c_i` of DOP853 (index 12 is the FSAL node c = 1, 13..15 the dense-output stages).
const C8: [f64; 16] = [
    0.0,
    0.526001519587677318785587544488e-1,
    0.789002279381515978178381316732e-1,
    0.118350341907227396726757197510,
    0.281649658092772603273242802490,
    1.0 / 3.0,
    0.25,
    4.0 / 13.0,
    127.0 / 195.0,
    0.6,
    6.0 / 7.0,
    1.0,
    1.0,
    0.1,
    0.2,
    7.0 / 9.0,
];
/// Coupling coefficients `a_ij` of DOP853 (rows 0..=11 the stages, row 12 the 8th-order weights `b`, rows 13..=15 the dense-output stages).
const A8: [[f64; 16]; 16] = {
    let mut a = [[0.0; 16]; 16];
    a[1][0] = 5.26001519587677318785587544488e-2;
    a[2][0] = 1.97250569845378994544595329183e-2;
    a[2][1] = 5.91751709536136983633785987549e-2;
    a[3][0] = 2.95875854768068491816892993775e-2;
    a[3][2] = 8.87627564304205475450678981324e-2;
    a[4][0] = 2.41365134159266685502369798665e-1;
    a[4][2] = -8.84549479328286085344864962717e-1;
    a[4][3] = 9.24834003261792003115737966543e-1;
    a[5][0] = 3.7037037037037037037037037037e-2;
    a[5][3] = 1.70828608729473871279604482173e-1;
    a[5][4] = 1.25467687566822425016691814123e-1;
    a[6][0] = 3.7109375e-2;
    a[6][3] = 1.70252211019544039314978060272e-1;
    a[6][4] = 6.02165389804559606850219397283e-2;
    a[6][5] = -1.7578125e-2;
    a[7][0] = 3.70920001185047927108779319836e-2;
    a[7][3] = 1.70383925712239993810214054705e-1;
    a[7][4] = 1.07262030446373284651809199168e-1;
    a[7][5] = -1.53194377486244017527936158236e-2;
    a[7][6] = 8.27378916381402288758473766002e-3;
    a[8][0] = 6.24110958716075717114429577812e-1;
    a[8][3] = -3.36089262944694129406857109825;
    a[8][4] = -8.68219346841726006818189891453e-1;
    a[8][5] = 2.75920996994467083049415600797e1;
    a[8][6] = 2.01540675504778934086186788979e1;
    a[8][7] = -4.34898841810699588477366255144e1;
    a[9][0] = 4.77662536438264365890433908527e-1;
    a[9][3] = -2.48811461997166764192642586468;
    a[9][4] = -5.90290826836842996371446475743e-1;
    a[9][5] = 2.12300514481811942347288949897e1;
    a[9][6] = 1.52792336328824235832596922938e1;
    a[9][7] = -3.32882109689848629194453265587e1;
    a[9][8] = -2.03312017085086261358222928593e-2;
    a[10][0] = -9.3714243008598732571704021658e-1;
    a[10][3] = 5.18637242884406370830023853209;
    a[10][4] = 1.09143734899672957818500254654;
    a[10][5] = -8.14978701074692612513997267357;
    a[10][6] = -1.85200656599969598641566180701e1;
    a[10][7] = 2.27394870993505042818970056734e1;
    a[10][8] = 2.49360555267965238987089396762;
    a[10][9] = -3.0467644718982195003823669022;
    a[11][0] = 2.27331014751653820792359768449;
    a[11][3] = -1.05344954667372501984066689879e1;
    a[11][4] = -2.00087205822486249909675718444;
    a[11][5] = -1.79589318631187989172765950534e1;
    a[11][6] = 2.79488845294199600508499808837e1;
    a[11][7] = -2.85899827713502369474065508674;
    a[11][8] = -8.87285693353062954433549289258;
    a[11][9] = 1.23605671757943030647266201528e1;
    a[11][10] = 6.43392746015763530355970484046e-1;
    a[12][0] = 5.42937341165687622380535766363e-2;
    a[12][5] = 4.45031289275240888144113950566;
    a[12][6] = 1.89151789931450038304281599044;
    a[12][7] = -5.8012039600105847814672114227;
    a[12][8] = 3.1116436695781989440891606237e-1;
    a[12][9] = -1.52160949662516078556178806805e-1;
    a[12][10] = 2.01365400804030348374776537501e-1;
    a[12][11] = 4.47106157277725905176885569043e-2;
    a[13][0] = 5.61675022830479523392909219681e-2;
    a[13][6] = 2.53500210216624811088794765333e-1;
    a[13][7] = -2.46239037470802489917441475441e-1;
    a[13][8] = -1.24191423263816360469010140626e-1;
    a[13][9] = 1.5329179827876569731206322685e-1;
    a[13][10] = 8.20105229563468988491666602057e-3;
    a[13][11] = 7.56789766054569976138603589584e-3;
    a[13][12] = -8.298e-3;
    a[14][0] = 3.18346481635021405060768473261e-2;
    a[14][5] = 2.83009096723667755288322961402e-2;
    a[14][6] = 5.35419883074385676223797384372e-2;
    a[14][7] = -5.49237485713909884646569340306e-2;
    a[14][10] = -1.08347328697249322858509316994e-4;
    a[14][11] = 3.82571090835658412954920192323e-4;
    a[14][12] = -3.40465008687404560802977114492e-4;
    a[14][13] = 1.41312443674632500278074618366e-1;
    a[15][0] = -4.28896301583791923408573538692e-1;
    a[15][5] = -4.69762141536116384314449447206;
    a[15][6] = 7.68342119606259904184240953878;
    a[15][7] = 4.06898981839711007970213554331;
    a[15][8] = 3.56727187455281109270669543021e-1;
    a[15][12] = -1.39902416515901462129418009734e-3;
    a[15][13] = 2.9475147891527723389556272149;
    a[15][14] = -9.15095847217987001081870187138;
    a
};
/// `b_j - bhh_j`'s `bhh`: weights of the embedded 3rd-order solution (stages 0, 8, 11).
const BHH8: [f64; 3] = [
    0.244094488188976377952755905512,
    0.733846688281611857341361741547,
    0.220588235294117647058823529412e-1,
];
/// Weights of the 5th-order error estimate.
const E8: [f64; 12] = {
    let mut e = [0.0; 12];
    e[0] = 0.1312004499419488073250102996e-1;
    e[5] = -0.1225156446376204440720569753e1;
    e[6] = -0.4957589496572501915214079952;
    e[7] = 0.1664377182454986536961530415e1;
    e[8] = -0.3503288487499736816886487290;
    e[9] = 0.3341791187130174790297318841;
    e[10] = 0.8192320648511571246570742613e-1;
    e[11] = -0.2235530786388629525884427845e-1;
    e
};
/// Dense-output coefficients `d_4j .. d_7j` over the 16 stages.
const D8: [[f64; 16]; 4] = {
    let mut d = [[0.0; 16]; 4];
    d[0][0] = -0.84289382761090128651353491142e1;
    d[0][5] = 0.56671495351937776962531783590;
    d[0][6] = -0.30689499459498916912797304727e1;
    d[0][7] = 0.23846676565120698287728149680e1;
    d[0][8] = 0.21170345824450282767155149946e1;
    d[0][9] = -0.87139158377797299206789907490;
    d[0][10] = 0.22404374302607882758541771650e1;
    d[0][11] = 0.63157877876946881815570249290;
    d[0][12] = -0.88990336451333310820698117400e-1;
    d[0][13] = 0.18148505520854727256656404962e2;
    d[0][14] = -0.91946323924783554000451984436e1;
    d[0][15] = -0.44360363875948939664310572000e1;
    d[1][0] = 0.10427508642579134603413151009e2;
    d[1][5] = 0.24228349177525818288430175319e3;
    d[1][6] = 0.16520045171727028198505394887e3;
    d[1][7] = -0.37454675472269020279518312152e3;
    d[1][8] = -0.22113666853125306036270938578e2;
    d[1][9] = 0.77334326684722638389603898808e1;
    d[1][10] = -0.30674084731089398182061213626e2;
    d[1][11] = -0.93321305264302278729567221706e1;
    d[1][12] = 0.15697238121770843886131091075e2;
    d[1][13] = -0.31139403219565177677282850411e2;
    d[1][14] = -0.93529243588444783865713862664e1;
    d[1][15] = 0.35816841486394083752465898540e2;
    d[2][0] = 0.19985053242002433820987653617e2;
    d[2][5] = -0.38703730874935176555105901742e3;
    d[2][6] = -0.18917813819516756882830838328e3;
    d[2][7] = 0.52780815920542364900561016686e3;
    d[2][8] = -0.11573902539959630126141871134e2;
    d[2][9] = 0.68812326946963000169666922661e1;
    d[2][10] = -0.10006050966910838403183860980e1;
    d[2][11] = 0.77771377980534432092869265740;
    d[2][12] = -0.27782057523535084065932004339e1;
    d[2][13] = -0.60196695231264120758267380846e2;
    d[2][14] = 0.84320405506677161018159903784e2;
    d[2][15] = 0.11992291136182789328035130030e2;
    d[3][0] = -0.25693933462703749003312586129e2;
    d[3][5] = -0.15418974869023643374053993627e3;
    d[3][6] = -0.23152937917604549567536039109e3;
    d[3][7] = 0.35763911791061412378285349910e3;
    d[3][8] = 0.93405324183624310003907691704e2;
    d[3][9] = -0.37458323136451633156875139351e2;
    d[3][10] = 0.10409964950896230045147246184e3;
    d[3][11] = 0.29840293426660503123344363579e2;
    d[3][12] = -0.43533456590011143754432175058e2;
    d[3][13] = 0.96324553959188282948394950600e2;
    d[3][14] = -0.39177261675615439165231486172e2;
    d[3][15] = -0.14972683625798562581422125276e3;
    d
};

// ---------------------------------------------------------------------------
// One-step kernels
// ---------------------------------------------------------------------------

/// Stage storage of one step (no heap): `k[0]` must hold `f(t, y)` at the
/// step's start before a trial; after it, `ynew` and `fnew = f(t+h, ynew)`
/// hold the step's end.
#[derive(Clone, Copy)]
pub(crate) struct Stages<const N: usize> {
    pub k: [[f64; N]; 16],
    pub yt: [f64; N],
    pub ynew: [f64; N],
    pub fnew: [f64; N],
}

impl<const N: usize> Stages<N> {
    #[inline]
    pub fn new() -> Self {
        Self {
            k: [[0.0; N]; 16],
            yt: [0.0; N],
            ynew: [0.0; N],
            fnew: [0.0; N],
        }
    }
}

/// Error scale of one component: `atol + rtol·max(|y0_i|, |y1_i|)`.
#[inline]
fn scale(atol: f64, rtol: f64, y0: f64, y1: f64) -> f64 {
    atol + rtol * y0.abs().max(y1.abs())
}

/// One trial step of `method` from `(t, y)` of length `h`; returns the scaled
/// RMS error norm (0 for RK4). Uses `st.k[0] = f(t, y)`; writes `st.ynew`,
/// `st.fnew`.
#[inline]
#[allow(clippy::too_many_arguments)]
pub(crate) fn trial<const N: usize, F: FnMut(f64, &[f64; N], &mut [f64; N])>(
    method: Method,
    f: &mut F,
    t: f64,
    y: &[f64; N],
    h: f64,
    atol: f64,
    rtol: f64,
    st: &mut Stages<N>,
) -> f64 {
    match method {
        Method::Dp54 => dp5_trial(f, t, y, h, atol, rtol, st),
        Method::Dop853 => dop853_trial(f, t, y, h, atol, rtol, st),
        Method::Rk4 { .. } => {
            rk4_trial(f, t, y, h, st);
            0.0
        }
    }
}

/// Fills `dense` for the step just taken by [`trial`] on `[t, t1]` (length
/// `h`). With `full == false` the interior is the cubic Hermite interpolant
/// (no extra stages); with `full == true` it is the method's own dense output.
/// Returns the extra right-hand-side evaluations made (3 for a full DOP853).
#[inline]
#[allow(clippy::too_many_arguments)]
pub(crate) fn fill_dense<const N: usize, F: FnMut(f64, &[f64; N], &mut [f64; N])>(
    method: Method,
    f: &mut F,
    t: f64,
    y: &[f64; N],
    h: f64,
    t1: f64,
    st: &mut Stages<N>,
    full: bool,
    dense: &mut Dense<N>,
) -> u64 {
    dense.set_hermite(t, y, &st.k[0], h, t1, &st.ynew, &st.fnew);
    if !full {
        return 0;
    }
    match method {
        Method::Dp54 => {
            dense.terms = 4;
            // `k[6]` holds f(t + h, y_new) (set by the trial).
            combine(&mut dense.coef[3], &[0.0; N], h, &DENSE5, &NZ_ERR5, &st.k);
            0
        }
        Method::Dop853 => {
            dop853_dense(f, t, y, h, st, dense);
            DOP853_DENSE_EVALS
        }
        Method::Rk4 { .. } => 0,
    }
}

/// `out = base + h · Σ_{j ∈ cols} a[j] · k[j]`: one Runge–Kutta stage
/// combination over the nonzero columns `cols` of a tableau row `a` (the
/// tableaux are sparse; their zeros are skipped, not multiplied).
///
/// One pass over the components with the sum in a register: the column
/// count `M` is a constant, so the inner sum unrolls and the component loop
/// vectorizes, with no copy of `base` and no store per column. Each component
/// is still summed in column order, `((base + c₀k₀) + c₁k₁) + …` with
/// `c_j = h·a_j`, so the result is bit for bit that of a column-by-column loop.
#[inline(always)]
fn combine<const N: usize, const S: usize, const M: usize>(
    out: &mut [f64; N],
    base: &[f64; N],
    h: f64,
    a: &[f64; S],
    cols: &[usize; M],
    k: &[[f64; N]; 16],
) {
    let c: [f64; M] = core::array::from_fn(|n| h * a[cols[n]]);
    let ks: [&[f64; N]; M] = core::array::from_fn(|n| &k[cols[n]]);
    for i in 0..N {
        let mut acc = base[i];
        for n in 0..M {
            acc += c[n] * ks[n][i];
        }
        out[i] = acc;
    }
}

/// A nonzero-column list as a fixed-size array (for [`combine`]'s constant
/// column count); `M` must be the list's length.
const fn cols<const M: usize>(list: &[usize]) -> [usize; M] {
    assert!(list.len() == M, "column count");
    let mut a = [0; M];
    let mut i = 0;
    while i < M {
        a[i] = list[i];
        i += 1;
    }
    a
}

/// [`combine`] over row `$row` of tableau `$a` with its nonzero columns
/// `$nz[$row]` (a list of `$m` entries, checked at compile time).
macro_rules! stage {
    ($out:expr, $base:expr, $h:expr, $a:ident, $nz:ident, $row:literal, $m:literal, $k:expr) => {
        combine(
            $out,
            $base,
            $h,
            &$a[$row],
            &const { cols::<$m>($nz[$row]) },
            $k,
        )
    };
}

/// DP5's tableau as rows (row 6 is the 5th-order solution's weights b).
const A5: [[f64; 7]; 7] = [
    [0.0; 7],
    [A21, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [A31, A32, 0.0, 0.0, 0.0, 0.0, 0.0],
    [A41, A42, A43, 0.0, 0.0, 0.0, 0.0],
    [A51, A52, A53, A54, 0.0, 0.0, 0.0],
    [A61, A62, A63, A64, A65, 0.0, 0.0],
    [A71, 0.0, A73, A74, A75, A76, 0.0],
];
/// DP5's nodes.
const C5: [f64; 7] = [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];
/// DP5's error weights (b − b̂) and dense-output weights, over k[0..7]
/// with k[6] = f(t + h, y_new).
const ERR5: [f64; 7] = [E1, 0.0, E3, E4, E5, E6, E7];
const DENSE5: [f64; 7] = [D1, 0.0, D3, D4, D5, D6, D7];
/// Nonzero columns of each row of [`A5`].
const NZ5: [&[usize]; 7] = [
    &[],
    &[0],
    &[0, 1],
    &[0, 1, 2],
    &[0, 1, 2, 3],
    &[0, 1, 2, 3, 4],
    &[0, 2, 3, 4, 5],
];
/// Nonzero columns of [`ERR5`] and [`DENSE5`].
const NZ_ERR5: [usize; 6] = [0, 2, 3, 4, 5, 6];

/// Nonzero columns of each row of [`A8`] (row 12 is the 8th-order weights b;
/// rows 13–15 are the dense output's extra stages, where column 12 stands
/// for f(t + h, y_new)).
const NZ8: [&[usize]; 16] = [
    &[],
    &[0],
    &[0, 1],
    &[0, 2],
    &[0, 2, 3],
    &[0, 3, 4],
    &[0, 3, 4, 5],
    &[0, 3, 4, 5, 6],
    &[0, 3, 4, 5, 6, 7],
    &[0, 3, 4, 5, 6, 7, 8],
    &[0, 3, 4, 5, 6, 7, 8, 9],
    &[0, 3, 4, 5, 6, 7, 8, 9, 10],
    &[0, 5, 6, 7, 8, 9, 10, 11],
    &[0, 6, 7, 8, 9, 10, 11, 12],
    &[0, 5, 6, 7, 10, 11, 12, 13],
    &[0, 5, 6, 7, 8, 12, 13, 14],
];
/// Nonzero columns of [`E8`].
const NZ_E8: [usize; 8] = [0, 5, 6, 7, 8, 9, 10, 11];
/// Nonzero columns of the rows of [`D8`].
const NZ_D8: [usize; 12] = [0, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15];

#[inline]
fn dp5_trial<const N: usize, F: FnMut(f64, &[f64; N], &mut [f64; N])>(
    f: &mut F,
    t: f64,
    y: &[f64; N],
    h: f64,
    atol: f64,
    rtol: f64,
    st: &mut Stages<N>,
) -> f64 {
    stage!(&mut st.yt, y, h, A5, NZ5, 1, 1, &st.k);
    f(t + C5[1] * h, &st.yt, &mut st.k[1]);
    stage!(&mut st.yt, y, h, A5, NZ5, 2, 2, &st.k);
    f(t + C5[2] * h, &st.yt, &mut st.k[2]);
    stage!(&mut st.yt, y, h, A5, NZ5, 3, 3, &st.k);
    f(t + C5[3] * h, &st.yt, &mut st.k[3]);
    stage!(&mut st.yt, y, h, A5, NZ5, 4, 4, &st.k);
    f(t + C5[4] * h, &st.yt, &mut st.k[4]);
    stage!(&mut st.yt, y, h, A5, NZ5, 5, 5, &st.k);
    f(t + C5[5] * h, &st.yt, &mut st.k[5]);
    stage!(&mut st.ynew, y, h, A5, NZ5, 6, 5, &st.k);
    f(t + h, &st.ynew, &mut st.k[6]);
    st.fnew = st.k[6];
    // The error estimate h Σ (b − b̂)_j k_j, into `yt`.
    combine(&mut st.yt, &[0.0; N], h, &ERR5, &NZ_ERR5, &st.k);
    let mut sum = 0.0;
    for i in 0..N {
        let r = st.yt[i] / scale(atol, rtol, y[i], st.ynew[i]);
        sum += r * r;
    }
    if N == 0 { 0.0 } else { (sum / N as f64).sqrt() }
}

#[inline]
fn dop853_trial<const N: usize, F: FnMut(f64, &[f64; N], &mut [f64; N])>(
    f: &mut F,
    t: f64,
    y: &[f64; N],
    h: f64,
    atol: f64,
    rtol: f64,
    st: &mut Stages<N>,
) -> f64 {
    macro_rules! stages {
        ($(($s:literal, $m:literal)),*) => {$(
            stage!(&mut st.yt, y, h, A8, NZ8, $s, $m, &st.k);
            f(t + C8[$s] * h, &st.yt, &mut st.k[$s]);
        )*};
    }
    stages!(
        (1, 1),
        (2, 2),
        (3, 2),
        (4, 3),
        (5, 3),
        (6, 4),
        (7, 5),
        (8, 6),
        (9, 7),
        (10, 8),
        (11, 9)
    );
    // 8th-order solution; `yt` keeps Σ b_j k_j for the 3rd-order estimate.
    stage!(&mut st.yt, &[0.0; N], 1.0, A8, NZ8, 12, 8, &st.k);
    for i in 0..N {
        st.ynew[i] = y[i] + h * st.yt[i];
    }
    f(t + h, &st.ynew, &mut st.fnew);
    // Hairer's estimator: err = h·‖e5‖² / sqrt(‖e5‖² + 0.01‖e3‖²) (RMS).
    let mut e5 = [0.0; N];
    combine(&mut e5, &[0.0; N], 1.0, &E8, &NZ_E8, &st.k);
    let mut err5 = 0.0;
    let mut err3 = 0.0;
    for i in 0..N {
        let sk = scale(atol, rtol, y[i], st.ynew[i]);
        let e3 = st.yt[i] - BHH8[0] * st.k[0][i] - BHH8[1] * st.k[8][i] - BHH8[2] * st.k[11][i];
        let r3 = e3 / sk;
        err3 += r3 * r3;
        let r5 = e5[i] / sk;
        err5 += r5 * r5;
    }
    let mut deno = err5 + 0.01 * err3;
    if deno <= 0.0 {
        deno = 1.0;
    }
    if N == 0 {
        0.0
    } else {
        h.abs() * err5 * (1.0 / (N as f64 * deno)).sqrt()
    }
}

/// The 3 extra stages and the coefficients F3..F6 of DOP853's dense output;
/// `dense` must already hold F0..F2 (the Hermite part).
#[inline]
fn dop853_dense<const N: usize, F: FnMut(f64, &[f64; N], &mut [f64; N])>(
    f: &mut F,
    t: f64,
    y: &[f64; N],
    h: f64,
    st: &mut Stages<N>,
    dense: &mut Dense<N>,
) {
    st.k[12] = st.fnew;
    stage!(&mut st.yt, y, h, A8, NZ8, 13, 8, &st.k);
    f(t + C8[13] * h, &st.yt, &mut st.k[13]);
    stage!(&mut st.yt, y, h, A8, NZ8, 14, 8, &st.k);
    f(t + C8[14] * h, &st.yt, &mut st.k[14]);
    stage!(&mut st.yt, y, h, A8, NZ8, 15, 8, &st.k);
    f(t + C8[15] * h, &st.yt, &mut st.k[15]);
    for (d, row) in D8.iter().enumerate() {
        combine(&mut dense.coef[3 + d], &[0.0; N], h, row, &NZ_D8, &st.k);
    }
    dense.terms = 7;
}

#[inline]
fn rk4_trial<const N: usize, F: FnMut(f64, &[f64; N], &mut [f64; N])>(
    f: &mut F,
    t: f64,
    y: &[f64; N],
    h: f64,
    st: &mut Stages<N>,
) {
    let h2 = 0.5 * h;
    for i in 0..N {
        st.yt[i] = y[i] + h2 * st.k[0][i];
    }
    f(t + h2, &st.yt, &mut st.k[1]);
    for i in 0..N {
        st.yt[i] = y[i] + h2 * st.k[1][i];
    }
    f(t + h2, &st.yt, &mut st.k[2]);
    for i in 0..N {
        st.yt[i] = y[i] + h * st.k[2][i];
    }
    f(t + h, &st.yt, &mut st.k[3]);
    let h6 = h / 6.0;
    for i in 0..N {
        st.ynew[i] = y[i] + h6 * (st.k[0][i] + 2.0 * (st.k[1][i] + st.k[2][i]) + st.k[3][i]);
    }
    f(t + h, &st.ynew, &mut st.fnew);
}

/// Hairer's initial step-size guess (`hinit` of dopri5/dop853) for a method
/// of order `order`, bounded by `h_max`. Uses `st.k[0] = f(t, y)`; makes one
/// right-hand-side evaluation.
#[allow(clippy::too_many_arguments)]
pub(crate) fn hinit<const N: usize, F: FnMut(f64, &[f64; N], &mut [f64; N])>(
    f: &mut F,
    t: f64,
    y: &[f64; N],
    order: u32,
    h_max: f64,
    atol: f64,
    rtol: f64,
    st: &mut Stages<N>,
) -> f64 {
    let mut dnf = 0.0;
    let mut dny = 0.0;
    for i in 0..N {
        let sk = atol + rtol * y[i].abs();
        let a = st.k[0][i] / sk;
        let b = y[i] / sk;
        dnf += a * a;
        dny += b * b;
    }
    let mut h = if dnf <= 1e-10 || dny <= 1e-10 {
        1.0e-6
    } else {
        (dny / dnf).sqrt() * 0.01
    };
    h = h.min(h_max);
    // Explicit Euler step, then the second derivative's estimate.
    for i in 0..N {
        st.yt[i] = y[i] + h * st.k[0][i];
    }
    f(t + h, &st.yt, &mut st.k[1]);
    let mut der2 = 0.0;
    for i in 0..N {
        let sk = atol + rtol * y[i].abs();
        let d = (st.k[1][i] - st.k[0][i]) / sk;
        der2 += d * d;
    }
    let der2 = der2.sqrt() / h;
    let der12 = der2.abs().max(dnf.sqrt());
    let h1 = if der12 <= 1e-15 {
        (h.abs() * 1e-3).max(1e-6)
    } else {
        (0.01 / der12).powf(1.0 / order as f64)
    };
    let h = (100.0 * h.abs()).min(h1).min(h_max);
    if h.is_finite() && h > 0.0 {
        h
    } else {
        h_max.min(1e-6)
    }
}

// ---------------------------------------------------------------------------
// Public fixed-step helpers
// ---------------------------------------------------------------------------

/// Integrates `y' = rhs(t, y)` from `(t0, y)` to `t1` with `steps` equal steps
/// of `method`'s tableau, without error control (for [`Method::Rk4`] the
/// variant's own `h` is ignored). On return `y` holds the state at `t1`.
/// Returns the number of right-hand-side evaluations. This is how the
/// convergence orders are measured; it allocates nothing.
pub fn fixed_step_solve<const N: usize, F: FnMut(f64, &[f64; N], &mut [f64; N])>(
    method: Method,
    mut rhs: F,
    t0: f64,
    y: &mut [f64; N],
    t1: f64,
    steps: u64,
) -> u64 {
    if steps == 0 {
        return 0;
    }
    let h = (t1 - t0) / steps as f64;
    let mut st = Stages::<N>::new();
    rhs(t0, y, &mut st.k[0]);
    let mut evals = 1;
    for n in 0..steps {
        let t = t0 + n as f64 * h;
        trial(method, &mut rhs, t, y, h, 1.0, 0.0, &mut st);
        evals += method.evals_per_step();
        *y = st.ynew;
        st.k[0] = st.fnew;
    }
    evals
}

/// One step of `method`'s tableau from `(t0, y0)` of length `h`, without error
/// control, writing the method's full dense output on `[t0, t0 + h]` into
/// `dense` (the new state is `dense.y1`). Returns the number of
/// right-hand-side evaluations.
pub fn step_with_dense<const N: usize, F: FnMut(f64, &[f64; N], &mut [f64; N])>(
    method: Method,
    mut rhs: F,
    t0: f64,
    y0: &[f64; N],
    h: f64,
    dense: &mut Dense<N>,
) -> u64 {
    let mut st = Stages::<N>::new();
    rhs(t0, y0, &mut st.k[0]);
    trial(method, &mut rhs, t0, y0, h, 1.0, 0.0, &mut st);
    1 + method.evals_per_step()
        + fill_dense(method, &mut rhs, t0, y0, h, t0 + h, &mut st, true, dense)
}

#[cfg(test)]
mod sparsity_tests {
    use super::*;

    /// The nonzero-column lists that [`combine`] walks must name exactly the
    /// nonzero entries of each tableau row: a missing column would silently
    /// drop a term.
    fn nonzeros<const S: usize>(row: &[f64; S]) -> Vec<usize> {
        (0..S).filter(|&j| row[j] != 0.0).collect()
    }

    #[test]
    fn column_lists_match_the_tableaux() {
        for s in 0..7 {
            assert_eq!(nonzeros(&A5[s]), NZ5[s], "DP5 row {s}");
        }
        assert_eq!(nonzeros(&ERR5), NZ_ERR5);
        assert_eq!(nonzeros(&DENSE5), NZ_ERR5);
        for s in 0..16 {
            assert_eq!(nonzeros(&A8[s]), NZ8[s], "DOP853 row {s}");
        }
        assert_eq!(nonzeros(&E8), NZ_E8);
        for (d, row) in D8.iter().enumerate() {
            assert_eq!(nonzeros(row), NZ_D8, "DOP853 dense row {d}");
        }
    }
}
