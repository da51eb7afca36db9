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
//! [`crate::engine`]; the coefficients in `tableau`; the
//! interpolant in [`crate::dense`]. This module provides the one-step
//! kernels and a fixed-step driver ([`fixed_step_solve`]) used to measure
//! orders of convergence.
#![allow(clippy::needless_range_loop)]

use crate::dense::Dense;
use crate::tableau::{A5, A8, BHH8, C5, C8, D8, DENSE5, E8, ERR5, NZ_D8, NZ_E8, NZ_ERR5, NZ5, NZ8};

/// Integration method. With the `serde` feature it reads and writes as
/// `"dp54"`, `"dop853"`, `"rk4"`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "snake_case")
)]
pub enum Method {
    /// Dormand–Prince 5(4), adaptive, 4th-order dense output.
    #[default]
    Dp54,
    /// Dormand–Prince 8(5,3), adaptive, 7th-order dense output.
    Dop853,
    /// Classic RK4 with the fixed step
    /// [`EngineOptions::rk4_step`](crate::EngineOptions::rk4_step) (cubic
    /// Hermite dense output).
    Rk4,
}

impl Method {
    /// Order of the method's solution (global error `O(h^order)`): 5, 8 or 4.
    #[inline]
    pub const fn order(&self) -> u32 {
        match self {
            Method::Dp54 => 5,
            Method::Dop853 => 8,
            Method::Rk4 => 4,
        }
    }

    /// Order of the dense output (interpolation error `O(h^(order+1))` per
    /// step): 4, 7 or 3.
    #[inline]
    pub const fn dense_order(&self) -> u32 {
        match self {
            Method::Dp54 => 4,
            Method::Dop853 => 7,
            Method::Rk4 => 3,
        }
    }

    /// Whether the method controls its step size from an error estimate.
    #[inline]
    pub const fn is_adaptive(&self) -> bool {
        !matches!(self, Method::Rk4)
    }

    /// Right-hand-side evaluations of one step attempt, including the
    /// evaluation at the step's end that the next step reuses (FSAL), but not
    /// the three extra stages of DOP853's dense output.
    #[inline]
    pub const fn evals_per_step(&self) -> u64 {
        match self {
            Method::Dp54 => 6,
            Method::Dop853 => 12,
            Method::Rk4 => 4,
        }
    }
}

/// Extra right-hand-side evaluations that DOP853's 7th-order dense output costs.
pub const DOP853_DENSE_EVALS: u64 = 3;

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
    /// The step's local error estimate (the embedded solution's difference;
    /// 0 for RK4), the state's uncertainty over the step.
    pub err: [f64; N],
}

impl<const N: usize> Stages<N> {
    #[inline]
    pub fn new() -> Self {
        Self {
            k: [[0.0; N]; 16],
            yt: [0.0; N],
            ynew: [0.0; N],
            fnew: [0.0; N],
            err: [0.0; N],
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
        Method::Rk4 => {
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
        Method::Rk4 => 0,
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

/// Stages `$s` (with `$m` nonzero columns each) of tableau `$a`/`$c`/`$nz`,
/// in order: each one's state from the stages before it into `st.yt`, then
/// its derivative into `st.k[$s]`.
macro_rules! stages {
    ($st:ident, $f:ident, $t:ident, $y:ident, $h:ident, $a:ident, $c:ident, $nz:ident;
     $(($s:literal, $m:literal)),*) => {$(
        stage!(&mut $st.yt, $y, $h, $a, $nz, $s, $m, &$st.k);
        $f($t + $c[$s] * $h, &$st.yt, &mut $st.k[$s]);
    )*};
}

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
    stages!(st, f, t, y, h, A5, C5, NZ5; (1, 1), (2, 2), (3, 3), (4, 4), (5, 5));
    // The last stage is the 5th-order solution (FSAL).
    stage!(&mut st.ynew, y, h, A5, NZ5, 6, 5, &st.k);
    f(t + h, &st.ynew, &mut st.k[6]);
    st.fnew = st.k[6];
    // The error estimate h Σ (b − b̂)_j k_j.
    combine(&mut st.err, &[0.0; N], h, &ERR5, &NZ_ERR5, &st.k);
    let mut sum = 0.0;
    for i in 0..N {
        let r = st.err[i] / scale(atol, rtol, y[i], st.ynew[i]);
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
    stages!(
        st, f, t, y, h, A8, C8, NZ8;
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
        // The 5th-order error estimate h Σ e_j k_j.
        st.err[i] = h * e5[i];
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
    stages!(st, f, t, y, h, A8, C8, NZ8; (13, 8), (14, 8), (15, 8));
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
/// engine's `rk4_step` plays no part). On return `y` holds the state at `t1`.
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
