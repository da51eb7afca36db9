//! The dense output of one step: the interpolating polynomial the engine
//! locates events on and hands to observers.
#![allow(clippy::needless_range_loop)]

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
    /// Start of the interval.
    pub t0: f64,
    /// End of the interval (an event time when the engine cut the step there).
    pub t1: f64,
    /// The state at `t0`.
    pub y0: [f64; N],
    /// The state at `t1`.
    pub y1: [f64; N],
    /// Length of the step the polynomial was built on (`θ = (t − t0)/h`).
    h: f64,
    /// Number of live coefficient arrays in `coef` (1, 3, 4 or 7).
    pub(crate) terms: usize,
    /// The coefficient arrays `F0, F1, …` of the polynomial.
    pub(crate) coef: [[f64; N]; MAX_DENSE_TERMS],
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

    /// The time derivative of the interpolant at `t`: the nested form of
    /// [`eval`](Self::eval) differentiated term by term (forward mode). At
    /// `t0` and at the step's end it is the right-hand side there (the
    /// interpolants are C¹ through `f0` and `f1`).
    pub fn eval_rate(&self, t: f64, out: &mut [f64; N]) {
        let th = (t - self.t0) / self.h;
        let th1 = 1.0 - th;
        let m = self.terms;
        for i in 0..N {
            // acc_j = F_{j-1} + w_j acc_{j+1}, w_j = 1−θ (odd j) or θ (even j).
            let mut acc = self.coef[m - 1][i];
            let mut dacc = 0.0;
            let mut j = m - 1;
            while j >= 1 {
                let (w, dw) = if j % 2 == 1 { (th1, -1.0) } else { (th, 1.0) };
                dacc = w * dacc + dw * acc;
                acc = self.coef[j - 1][i] + w * acc;
                j -= 1;
            }
            // y = y0 + θ acc.
            out[i] = (acc + th * dacc) / self.h;
        }
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
