//! The errata of docs/model.md §7 checked numerically from the string model
//! and the linear analyses (`cargo run -p rtw-model --example errata` prints
//! [`errata_table`]; `results/errata.md`).

use super::linear::{
    approx_matrices, approx_stiffness_closed_form, approximate_modes_of, free_star_modes_of,
    rotor_torques, s18_frequency,
};
use crate::options::Damping;
use crate::params::{Normalization, Params, Physical};
use crate::plant::geometry::{RodFrame, RodState};
use crate::plant::strings::StringSet;
use std::f64::consts::PI;
use std::fmt::Write;

fn frames(theta: [f64; 3]) -> [RodFrame; 3] {
    std::array::from_fn(|i| {
        RodFrame::new(&RodState {
            c: [0.0, 0.0],
            theta: theta[i],
            v: [0.0, 0.0],
            omega: 0.0,
        })
    })
}

fn max_abs(v: [f64; 3]) -> f64 {
    v.iter().fold(0.0_f64, |m, x| m.max(x.abs()))
}

/// The numerical check behind each erratum of docs/model.md §7 at the
/// Fig. 7(a) point (zero rest length, S5–S6), as a Markdown table: the
/// rest angle (S7–S10), the sign of the string force (S1), the linearization
/// and its frequency (S7–S18), the damping (S14).
pub fn errata_table() -> String {
    let mut out = String::new();
    let p = Params::fig7a();
    let ph = Physical::new(&p, Normalization::Supplementary, 9.81);
    let strings = StringSet {
        k: ph.k,
        c: ph.c,
        r: ph.r,
        rest_length: 0.0,
        slack: false,
        damping: Damping::Along,
    };
    let _ = writeln!(
        out,
        "Fig. 7(a) point, zero rest length (S5-S6), k = {:.1} N/m, r = {:.3} m\n",
        ph.k, ph.r
    );
    let _ = writeln!(out, "| erratum (docs/model.md §7) | check | value |");
    let _ = writeln!(out, "|---|---|---:|");

    // 1. The rest angle: the star is in equilibrium at θa − θb = −π/3 and
    //    not at −3/π (S7–S10).
    let at = |d: f64| max_abs(rotor_torques(&strings, [0.0, d, 2.0 * d], [0.0; 3]));
    let _ = writeln!(
        out,
        "| S7–S10 rest angle θa − θb = −3/π | max string torque on a rod at θb − θa = π/3 = {:.4} | {:.2e} N·m |",
        PI / 3.0,
        at(PI / 3.0)
    );
    let _ = writeln!(
        out,
        "| | same at θb − θa = 3/π = {:.4} (S7–S10 as printed) | {:.2e} N·m |",
        3.0 / PI,
        at(3.0 / PI)
    );

    // 2. The sign of F: the string torque is −∂V/∂θ (central differences of
    //    the potential), so S1's `M q̈ = F` with F = +∂V/∂q pushes the rods
    //    apart. Checked at a perturbed, non-rest shape.
    let theta = [0.05, PI / 3.0 - 0.08, 2.0 * PI / 3.0 + 0.03];
    let tau = rotor_torques(&strings, theta, [0.0; 3]);
    let h = 1e-6;
    let grad: [f64; 3] = std::array::from_fn(|j| {
        let (mut a, mut b) = (theta, theta);
        a[j] += h;
        b[j] -= h;
        (strings.potential(&frames(a)) - strings.potential(&frames(b))) / (2.0 * h)
    });
    let err_minus = max_abs(std::array::from_fn(|i| tau[i] + grad[i]));
    let err_plus = max_abs(std::array::from_fn(|i| tau[i] - grad[i]));
    let _ = writeln!(
        out,
        "| S1 sign of F | max abs(τ + ∂V/∂θ): torque is −∇V | {err_minus:.2e} N·m |"
    );
    let _ = writeln!(
        out,
        "| | max abs(τ − ∂V/∂θ): S1's sign, torque = +∇V | {err_plus:.2e} N·m |"
    );

    // 3. The linearization about −π/3 for every pair: the true stiffness is
    //    k r² [[2,−1,−1],[−1,2,−1],[−1,−1,2]] and the oscillating pair sits at
    //    √3·f_n; the damping ratio of that pair is 9/(5√3)·ζ.
    let (k_fd, _) = approx_matrices(&strings);
    let k_cf = approx_stiffness_closed_form(&strings);
    let rel = (k_fd - k_cf).abs().max() / k_cf.abs().max();
    let _ = writeln!(
        out,
        "| S7–S16 linearization of θa − θc about −π/3 | max rel. difference of finite-difference K from k r² [[2,−1,−1],…] | {rel:.2e} |"
    );
    let modes = approximate_modes_of(&ph, &strings);
    let f_n = s18_frequency(&ph);
    let _ = writeln!(out, "| | S18's f_n | {f_n:.4} Hz |");
    for f in &modes.freq_hz {
        let _ = writeln!(
            out,
            "| | approximate model's oscillating mode (of 2) | {f:.4} Hz = {:.5} f_n (√3 = {:.5}) |",
            f / f_n,
            3f64.sqrt()
        );
    }
    let star = free_star_modes_of(&ph, &strings);
    let _ = writeln!(
        out,
        "| | free 9-DOF star: rigid modes; oscillating frequencies | {}; {} Hz |",
        star.rigid_modes,
        star.freq_hz[star.rigid_modes..]
            .iter()
            .map(|f| format!("{f:.3}"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    for z in &modes.damping_ratio {
        let _ = writeln!(
            out,
            "| S14 damping | damping ratio of the pair / ζ (9/(5√3) = {:.4}) | {:.4} |",
            9.0 / (5.0 * 3f64.sqrt()),
            z / p.zeta
        );
    }
    let _ = writeln!(
        out,
        "| | state-matrix eigenvalues of the pair (real parts < 0: S14's positive real parts are artefacts) | {} |",
        modes
            .eigenvalues
            .iter()
            .filter(|l| l.im > 1e-6)
            .map(|l| format!("{:.3} + {:.3}i", l.re, l.im))
            .collect::<Vec<_>>()
            .join(", ")
    );
    out
}
