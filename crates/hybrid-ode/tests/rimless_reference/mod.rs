//! The rimless wheel on per-step random slopes and its reference: Byl and
//! Tedrake's Markov chain on the one-dimensional post-impact state, fine
//! enough to be exact to its discretisation (shared by the estimators'
//! tests, `mfpt_rimless.rs` and `chain_rimless.rs`).
//!
//! See `mfpt_rimless.rs` for the walker and the chain.
#![allow(dead_code)]

use hybrid_ode::rimless::RimlessWheel;

pub const L: f64 = 1.0;
pub const G: f64 = 9.81;
pub const GAMMA0: f64 = 0.08;
/// Twelve spokes: the impact keeps `cos² 2α = 0.75` of a deviation per
/// step, so a slow wheel stays slow for several steps and its falls build
/// up over steps (with 8 spokes they are mostly one unlucky slope).
pub const SPOKES: u32 = 12;

/// The wheel on per-step random slopes of standard deviation `sigma`.
pub struct Rough {
    pub sigma: f64,
}

impl Rough {
    pub fn wheel(gamma: f64) -> RimlessWheel {
        RimlessWheel::with_spokes(SPOKES, L, gamma, G)
    }

    /// The gait on the mean slope: McGeer's fixed point.
    pub fn omega_star() -> f64 {
        Self::wheel(GAMMA0).omega_star()
    }
}

/// `erfc` (Numerical Recipes' Chebyshev fit, relative error below 1.2e-7
/// everywhere, so tail probabilities keep their digits).
fn erfc(x: f64) -> f64 {
    let z = x.abs();
    let t = 1.0 / (1.0 + 0.5 * z);
    // Horner's rule from the highest coefficient, in the order of the
    // nested form `c₁ + t(c₂ + t(… + t c₉))`: the same operations, so the
    // same bits, and a loop rustfmt formats in milliseconds where the
    // nine-deep nest took it 15 s.
    const C: [f64; 9] = [
        1.000_023_68,
        0.374_091_96,
        0.096_784_18,
        -0.186_288_06,
        0.278_868_07,
        -1.135_203_98,
        1.488_515_87,
        -0.822_152_23,
        0.170_872_77,
    ];
    let poly = C[..8].iter().rev().fold(C[8], |acc, c| c + t * acc);
    let r = t * (-z * z - 1.265_512_23 + t * poly).exp();
    if x >= 0.0 { r } else { 2.0 - r }
}

/// The standard normal distribution function.
fn phi(x: f64) -> f64 {
    0.5 * erfc(-x / std::f64::consts::SQRT_2)
}

/// The chain on `n` cells of `[lo, hi]` (the mass below `lo` lumped into
/// the bottom cell, above `hi` into the top one): each row of `Q` as the
/// first column it reaches and its entries from there, and each cell's
/// probability of rolling back.
pub struct Chain {
    lo: f64,
    h: f64,
    rows: Vec<(usize, Vec<f64>)>,
    fall: Vec<f64>,
}

pub fn chain(sigma: f64, n: usize, lo: f64, hi: f64) -> Chain {
    let w = Rough::wheel(GAMMA0);
    let (c, k) = (w.impact_ratio(), 4.0 * (G / L) * w.alpha.sin());
    let alpha = w.alpha;
    let h = (hi - lo) / n as f64;
    let cdf = |gamma: f64| phi((gamma - GAMMA0) / sigma);
    // Gauss–Legendre on [-1, 1], 4 points.
    let gl = [
        (-0.861_136_311_594_053, 0.347_854_845_137_454),
        (-0.339_981_043_584_856, 0.652_145_154_862_546),
        (0.339_981_043_584_856, 0.652_145_154_862_546),
        (0.861_136_311_594_053, 0.347_854_845_137_454),
    ];
    let mut rows = Vec::with_capacity(n);
    let mut fall = vec![0.0; n];
    for (i, fall_i) in fall.iter_mut().enumerate() {
        let mut row = vec![0.0; n];
        for (x, wt) in gl {
            let omega = lo + h * (i as f64 + 0.5 + 0.5 * x);
            // The slopes that pass the apex: γ > α − acos(1 − ω² l / 2g).
            let arg = 1.0 - omega * omega * L / (2.0 * G);
            let f_fall = if arg <= -1.0 {
                0.0
            } else {
                cdf(alpha - arg.acos())
            };
            *fall_i += 0.5 * wt * f_fall;
            // The slope that lands on `ω' = e`.
            let slope_to = |e: f64| {
                (((e / c).powi(2) - omega * omega) / k)
                    .clamp(-1.0, 1.0)
                    .asin()
            };
            // No mass lands below the slope 40 σ under the mean: start at
            // the cell it maps to, and stop once the distribution is 1.
            let steepest_down = (GAMMA0 - 40.0 * sigma).max(-std::f64::consts::FRAC_PI_2);
            let from = c * (omega * omega + k * steepest_down.sin()).max(0.0).sqrt();
            let j0 = (((from - lo) / h).floor().max(0.0) as usize).min(n - 1);
            let mut below = f_fall;
            for (j, r) in row.iter_mut().enumerate().skip(j0) {
                let upper = if j + 1 == n {
                    1.0
                } else {
                    cdf(slope_to(lo + h * (j + 1) as f64)).max(below)
                };
                *r += 0.5 * wt * (upper - below);
                below = upper;
                if below == 1.0 {
                    break;
                }
            }
        }
        let first = row.iter().position(|&v| v > 0.0).unwrap_or(0);
        let last = row.iter().rposition(|&v| v > 0.0).map_or(first, |l| l + 1);
        rows.push((first, row[first..last].to_vec()));
    }
    Chain { lo, h, rows, fall }
}

impl Chain {
    /// The MFPT from the quasi-stationary regime, `1/(1 − λ)`: the QSD `ν`
    /// by power iteration on `ν Q`, and `1 − λ = ν·fall / ν·1`.
    pub fn qsd_mfpt(&self) -> f64 {
        let n = self.rows.len();
        let mut v = vec![1.0 / n as f64; n];
        for _ in 0..400 {
            let mut w = vec![0.0; n];
            for (vi, (first, row)) in v.iter().zip(&self.rows) {
                for (wj, q) in w[*first..].iter_mut().zip(row) {
                    *wj += vi * q;
                }
            }
            let s: f64 = w.iter().sum();
            v = w.iter().map(|x| x / s).collect();
        }
        1.0 / v.iter().zip(&self.fall).map(|(a, b)| a * b).sum::<f64>()
    }

    /// The MFPT from `omega`: `m = 1 + Q m` iterated `iters` times (it
    /// converges as `λ^iters`).
    pub fn mfpt_from(&self, omega: f64, iters: usize) -> f64 {
        let n = self.rows.len();
        let mut m = vec![0.0; n];
        for _ in 0..iters {
            m = self
                .rows
                .iter()
                .map(|(first, row)| {
                    1.0 + row
                        .iter()
                        .zip(&m[*first..])
                        .map(|(a, b)| a * b)
                        .sum::<f64>()
                })
                .collect();
        }
        m[(((omega - self.lo) / self.h) as usize).min(n - 1)]
    }
}

/// The mesh's top: McGeer's fixed point on a slope 8 σ steeper than the
/// mean, 1.5 times over.
pub fn omega_max(sigma: f64) -> f64 {
    1.5 * Rough::wheel(GAMMA0 + 8.0 * sigma).omega_star()
}

/// The chain on 2000 cells of `[0.3, omega_max]` rad/s.
pub fn reference(sigma: f64) -> Chain {
    chain(sigma, 2000, 0.3, omega_max(sigma))
}
