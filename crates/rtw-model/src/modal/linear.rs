//! The linear analyses themselves, on a string set ([`StringSet`]); the
//! module documentation of [`crate::modal`] derives them.

#[cfg(test)]
use crate::options::Damping;
use crate::params::Physical;
use crate::plant::geometry::{RodFrame, RodState, rest_star};
use crate::plant::strings::StringSet;
use nalgebra::{Complex, Matrix3, Matrix6, SMatrix, SymmetricEigen};
use std::f64::consts::{FRAC_PI_3, PI};

/// Relative finite-difference step (angles in rad; lengths in units of r).
const FD_STEP: f64 = 1e-6;

/// An eigenvalue `ω²` counts as zero (a rigid mode) below this fraction of the largest.
const ZERO_TOL: f64 = 1e-8;

/// A state-matrix eigenvalue oscillates when `|Im λ| > OSC_TOL · |λ|`.
const OSC_TOL: f64 = 1e-6;

/// 9 × 9 real matrix (the full star's stiffness).
pub(crate) type Matrix9 = SMatrix<f64, 9, 9>;

/// The rest angles of the approximate model: θa = 0, θb = π/3, θc = 2π/3.
pub(crate) const REST_ANGLES: [f64; 3] = [0.0, FRAC_PI_3, 2.0 * FRAC_PI_3];

/// Modes of the approximate 3-rotor model (S1–S6), correctly linearized.
#[derive(Clone, Debug, PartialEq)]
pub struct ApproxModes {
    /// Stiffness `K = −∂τ/∂q` at the rest angles (finite differences).
    pub stiffness: Matrix3<f64>,
    /// Damping `C = −∂τ/∂q̇` at the rest angles (finite differences).
    pub damping: Matrix3<f64>,
    /// The six eigenvalues of `A = [[0, Id], [−M⁻¹K, −M⁻¹C]]` (1/s)
    /// (with `K` symmetrized and its zero modes set to exactly zero),
    /// sorted by modulus, then by imaginary part.
    pub eigenvalues: Vec<Complex<f64>>,
    /// Undamped frequencies of the oscillating modes, `√(eig(M⁻¹K))/2π` (Hz),
    /// sorted (zero modes left out): `[√3 f_n; 2]` with S21's k and zero rest length.
    pub freq_hz: Vec<f64>,
    /// Damped frequencies `|Im λ|/2π` of the complex pairs of `A` (Hz), one per
    /// pair, sorted by `|λ|` (the natural frequency).
    pub damped_freq_hz: Vec<f64>,
    /// Damping ratios `−Re λ/|λ|` of the same pairs, in the same order.
    pub damping_ratio: Vec<f64>,
    /// Number of zero eigenvalues of `M⁻¹K` (rigid modes): 1, the common rotation.
    pub zero_modes: usize,
    /// The string damping `c` above which no mode of `A` oscillates, found by
    /// bisection on `c`, everything else fixed (N·s/m); `NaN` if nothing
    /// oscillates at `c = 0`, `∞` if damping never stops the oscillation.
    pub critical_damping: f64,
}

/// Modes of the free 9-DOF star (no gravity, no ground), linearized at the rest shape.
#[derive(Clone, Debug, PartialEq)]
pub struct StarModes {
    /// The nine frequencies `√ω²/2π` (Hz), sorted; rigid modes come first (≈ 0).
    pub freq_hz: [f64; 9],
    /// The eigenvalues `ω²` of `K v = ω² M v` (rad²/s²), same order (rigid
    /// ones may be round-off negative).
    pub omega_sq: [f64; 9],
    /// Number of modes with `|ω²|` below `1e-8 · max ω²`: 3 (two translations, one rotation).
    pub rigid_modes: usize,
    /// Mode shapes, mass-normalized (`vᵀ M v = 1`), in the coordinates
    /// `(x_a, y_a, θ_a, x_b, y_b, θ_b, x_c, y_c, θ_c)`: `shapes[j]` belongs to
    /// `freq_hz[j]`. Within a repeated frequency the basis is arbitrary.
    pub shapes: [[f64; 9]; 9],
    /// The symmetrized stiffness `K = −∂(F, τ)/∂(x, y, θ)` (N/m, N, N·m).
    pub stiffness: SMatrix<f64, 9, 9>,
}

/// S18 as printed: `f_n = (L − 2 l_c)/(4π) · √(k/I)` (Hz).
pub fn s18_frequency(phys: &Physical) -> f64 {
    (phys.length - 2.0 * phys.l_c) / (4.0 * PI) * (phys.k / phys.inertia).sqrt()
}

/// Rest-length ratio `s = ℓ₀ / r` of a string set.
fn rest_ratio(strings: &StringSet) -> f64 {
    strings.rest_length / strings.r
}

/// Closed form of the approximate model's stiffness: `K = κ [[2,−1,−1],[−1,2,−1],[−1,−1,2]]`
/// with `κ = k r² (1 + s/2)` (`s = ℓ₀/r`; `κ = k r²` for S5's zero rest length).
pub(crate) fn approx_stiffness_closed_form(strings: &StringSet) -> Matrix3<f64> {
    let kappa = strings.k * strings.r * strings.r * (1.0 + 0.5 * rest_ratio(strings));
    laplacian() * kappa
}

#[cfg(test)]
/// Closed form of the approximate model's damping matrix: `along`:
/// `(3/2) c r² [[2,−1,−1],[−1,2,−1],[−1,−1,2]]`; `relative`:
/// `c r² [[4,−1,−1],[−1,4,−1],[−1,−1,4]]`.
pub(crate) fn approx_damping_closed_form(strings: &StringSet) -> Matrix3<f64> {
    let cr2 = strings.c * strings.r * strings.r;
    match strings.damping {
        Damping::Along => laplacian() * (1.5 * cr2),
        Damping::Relative => (Matrix3::identity() * 2.0 + laplacian()) * cr2,
    }
}

/// `[[2,−1,−1],[−1,2,−1],[−1,−1,2]]`: eigenvalues 0 (common rotation) and 3, 3.
fn laplacian() -> Matrix3<f64> {
    Matrix3::from_fn(|i, j| if i == j { 2.0 } else { -1.0 })
}

#[cfg(test)]
/// Closed form of the approximate model's oscillating (double) pair: undamped
/// frequency `√(3 κ / I)/2π` (Hz), `κ` as in [`approx_stiffness_closed_form`];
/// `= √3 · f_n` (S18) for zero rest length.
pub(crate) fn approx_frequency_closed_form(phys: &Physical, strings: &StringSet) -> f64 {
    let kappa = strings.k * strings.r * strings.r * (1.0 + 0.5 * rest_ratio(strings));
    (3.0 * kappa / phys.inertia).sqrt() / (2.0 * PI)
}

#[cfg(test)]
/// Closed form of the decay rate `σ = −Re λ` of the oscillating pair (1/s):
/// `9 c r² / (4 I)` (`along`), `5 c r² / (2 I)` (`relative`).
pub(crate) fn approx_decay_rate_closed_form(phys: &Physical, strings: &StringSet) -> f64 {
    let cr2 = strings.c * strings.r * strings.r;
    match strings.damping {
        Damping::Along => 9.0 * cr2 / (4.0 * phys.inertia),
        Damping::Relative => 5.0 * cr2 / (2.0 * phys.inertia),
    }
}

#[cfg(test)]
/// Closed form of the critical damping `c_crit` (decay rate = natural frequency):
/// `along`: `4 √(3 κ I) / (9 r²)`, i.e. `4 √(3 k I) / (9 r)` at zero rest length
/// (S17 prints `(4/5) √(k I) / r`); `relative`: `2 √(3 κ I) / (5 r²)`.
pub(crate) fn critical_damping_closed_form(phys: &Physical, strings: &StringSet) -> f64 {
    let r2 = strings.r * strings.r;
    let kappa = strings.k * r2 * (1.0 + 0.5 * rest_ratio(strings));
    let root = (3.0 * kappa * phys.inertia).sqrt();
    match strings.damping {
        Damping::Along => 4.0 * root / (9.0 * r2),
        Damping::Relative => 2.0 * root / (5.0 * r2),
    }
}

/// String torques on three rods pinned at a common centre (the approximate
/// model), at angles `theta` and angular velocities `omega`.
pub(crate) fn rotor_torques(strings: &StringSet, theta: [f64; 3], omega: [f64; 3]) -> [f64; 3] {
    let frames: [RodFrame; 3] = std::array::from_fn(|i| {
        RodFrame::new(&RodState {
            c: [0.0, 0.0],
            theta: theta[i],
            v: [0.0, 0.0],
            omega: omega[i],
        })
    });
    strings.loads(&frames).torque
}

/// `K = −∂τ/∂q` and `C = −∂τ/∂q̇` of the approximate model at [`REST_ANGLES`],
/// by central finite differences of [`StringSet::loads`].
pub(crate) fn approx_matrices(strings: &StringSet) -> (Matrix3<f64>, Matrix3<f64>) {
    let h = FD_STEP;
    let mut k = Matrix3::zeros();
    let mut c = Matrix3::zeros();
    for j in 0..3 {
        let (mut tp, mut tm) = (REST_ANGLES, REST_ANGLES);
        tp[j] += h;
        tm[j] -= h;
        let (fp, fm) = (
            rotor_torques(strings, tp, [0.0; 3]),
            rotor_torques(strings, tm, [0.0; 3]),
        );
        let (mut wp, mut wm) = ([0.0; 3], [0.0; 3]);
        wp[j] = h;
        wm[j] = -h;
        let (gp, gm) = (
            rotor_torques(strings, REST_ANGLES, wp),
            rotor_torques(strings, REST_ANGLES, wm),
        );
        for i in 0..3 {
            k[(i, j)] = -(fp[i] - fm[i]) / (2.0 * h);
            c[(i, j)] = -(gp[i] - gm[i]) / (2.0 * h);
        }
    }
    (k, c)
}

/// The state matrix `[[0, Id], [−K/I, −C/I]]`.
fn state_matrix(k: &Matrix3<f64>, c: &Matrix3<f64>, inertia: f64) -> Matrix6<f64> {
    let mut a = Matrix6::zeros();
    for i in 0..3 {
        a[(i, i + 3)] = 1.0;
        for j in 0..3 {
            a[(i + 3, j)] = -k[(i, j)] / inertia;
            a[(i + 3, j + 3)] = -c[(i, j)] / inertia;
        }
    }
    a
}

/// The eigenvalues of `A` that oscillate (`Im λ > 0` member of each pair,
/// `|λ|` above `zero`), sorted by `|λ|`.
fn oscillating_pairs(eig: &[Complex<f64>], zero: f64) -> Vec<Complex<f64>> {
    let mut out: Vec<Complex<f64>> = eig
        .iter()
        .copied()
        .filter(|l| l.norm() > zero && l.im > OSC_TOL * l.norm())
        .collect();
    out.sort_by(|a, b| a.norm().total_cmp(&b.norm()));
    out
}

/// Modes of the approximate model (S1–S6): rods of inertia `I = phys.inertia`
/// pinned at one common centre, no gravity, strings `strings`, linearized at
/// the rest angles by finite differences (see the module documentation).
pub(crate) fn approximate_modes_of(phys: &Physical, strings: &StringSet) -> ApproxModes {
    let inertia = phys.inertia;
    let (k, c) = approx_matrices(strings);

    // Undamped: eigenvalues of M⁻¹K = K/I (symmetrized).
    let ks = SymmetricEigen::new((k + k.transpose()) * 0.5);
    let k_max = ks.eigenvalues.iter().fold(0.0_f64, |m, &v| m.max(v.abs()));
    let is_zero = |v: f64| k_max <= 0.0 || v.abs() <= ZERO_TOL * k_max;
    let zero_modes = ks.eigenvalues.iter().filter(|&&v| is_zero(v)).count();
    let mut freq_hz: Vec<f64> = ks
        .eigenvalues
        .iter()
        .filter(|&&v| !is_zero(v))
        .map(|&v| (v.max(0.0) / inertia).sqrt() / (2.0 * PI))
        .collect();
    freq_hz.sort_by(f64::total_cmp);
    let w2_max = k_max / inertia;
    // The state matrix uses K with its zero modes set to exactly zero: the
    // finite-difference noise on the common rotation (≈ 1e-9 k r²) would
    // otherwise split its Jordan block at λ = 0 into a spurious slow pair.
    let k_clean = {
        let mut e = ks;
        e.eigenvalues.iter_mut().for_each(|v| {
            if is_zero(*v) {
                *v = 0.0;
            }
        });
        e.recompose()
    };

    // Damped: eigenvalues of the state matrix.
    let zero = 1e-6 * w2_max.sqrt();
    let mut eigenvalues: Vec<Complex<f64>> = state_matrix(&k_clean, &c, inertia)
        .complex_eigenvalues()
        .iter()
        .copied()
        .collect();
    eigenvalues.sort_by(|a, b| a.norm().total_cmp(&b.norm()).then(a.im.total_cmp(&b.im)));
    let pairs = oscillating_pairs(&eigenvalues, zero);
    let damped_freq_hz = pairs.iter().map(|l| l.im / (2.0 * PI)).collect();
    let damping_ratio = pairs.iter().map(|l| -l.re / l.norm()).collect();

    let critical_damping = critical_damping_bisection(strings, &k_clean, inertia, zero);
    ApproxModes {
        stiffness: k,
        damping: c,
        eigenvalues,
        freq_hz,
        damped_freq_hz,
        damping_ratio,
        zero_modes,
        critical_damping,
    }
}

/// The smallest string damping `c` at which no eigenvalue of `A` oscillates,
/// by bisection (the damping matrix is linear in `c`: `C = c C₁`).
fn critical_damping_bisection(
    strings: &StringSet,
    k: &Matrix3<f64>,
    inertia: f64,
    zero: f64,
) -> f64 {
    let unit = StringSet { c: 1.0, ..*strings };
    let (_, c1) = approx_matrices(&unit);
    let oscillates = |c: f64| {
        let eig = state_matrix(k, &(c1 * c), inertia).complex_eigenvalues();
        !oscillating_pairs(eig.as_slice(), zero).is_empty()
    };
    if !oscillates(0.0) {
        return f64::NAN;
    }
    // A first guess of the scale: the c whose decay rate is the largest ω.
    let c1_max = SymmetricEigen::new((c1 + c1.transpose()) * 0.5)
        .eigenvalues
        .iter()
        .fold(0.0_f64, |m, &v| m.max(v.abs()));
    let w_max = SymmetricEigen::new((k + k.transpose()) * (0.5 / inertia))
        .eigenvalues
        .iter()
        .fold(0.0_f64, |m, &v| m.max(v.abs()))
        .sqrt();
    if c1_max <= 0.0 {
        return f64::INFINITY;
    }
    let (mut lo, mut hi) = (0.0, inertia * w_max / c1_max);
    let mut doublings = 0;
    while oscillates(hi) {
        lo = hi;
        hi *= 2.0;
        doublings += 1;
        if doublings > 200 {
            return f64::INFINITY;
        }
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if hi - lo <= 1e-14 * hi {
            break;
        }
        if oscillates(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The full star's generalized string forces `(F_x, F_y, τ)` per rod at the
/// rest shape displaced by `dz` (coordinates `(x, y, θ)` per rod).
fn star_forces(strings: &StringSet, dz: &[f64; 9]) -> [f64; 9] {
    let rest = rest_star([0.0, 0.0], 0.0);
    let frames: [RodFrame; 3] = std::array::from_fn(|i| {
        RodFrame::new(&RodState {
            c: [rest[i].c[0] + dz[3 * i], rest[i].c[1] + dz[3 * i + 1]],
            theta: rest[i].theta + dz[3 * i + 2],
            v: [0.0, 0.0],
            omega: 0.0,
        })
    });
    let l = strings.loads(&frames);
    std::array::from_fn(|n| {
        let (i, dof) = (n / 3, n % 3);
        if dof < 2 {
            l.force[i][dof]
        } else {
            l.torque[i]
        }
    })
}

/// The free star's stiffness `K = −∂(F, τ)/∂(x, y, θ)` at the rest shape
/// (`rest_star([0, 0], 0)`), central finite differences (step `1e-6 r` on
/// positions, `1e-6` rad on angles), symmetrized.
pub(crate) fn star_stiffness(strings: &StringSet) -> Matrix9 {
    let mut k = Matrix9::zeros();
    for j in 0..9 {
        let h = if j % 3 < 2 {
            FD_STEP * strings.r
        } else {
            FD_STEP
        };
        let (mut zp, mut zm) = ([0.0; 9], [0.0; 9]);
        zp[j] = h;
        zm[j] = -h;
        let (fp, fm) = (star_forces(strings, &zp), star_forces(strings, &zm));
        for i in 0..9 {
            k[(i, j)] = -(fp[i] - fm[i]) / (2.0 * h);
        }
    }
    (k + k.transpose()) * 0.5
}

#[cfg(test)]
/// The free star's generalized string forces at the rest shape (zero: the
/// regular star is an equilibrium for every `s < 1`, by symmetry).
pub(crate) fn star_rest_forces(strings: &StringSet) -> [f64; 9] {
    star_forces(strings, &[0.0; 9])
}

/// Modes of the free 9-DOF star (no gravity, no ground): `K v = ω² M v` with
/// `M = diag(m, m, I)` per rod, solved as the symmetric eigenproblem of
/// `M^{-1/2} K M^{-1/2}`.
pub(crate) fn free_star_modes_of(phys: &Physical, strings: &StringSet) -> StarModes {
    let k = star_stiffness(strings);
    let mass: [f64; 9] = std::array::from_fn(|n| if n % 3 < 2 { phys.m } else { phys.inertia });
    let inv_sqrt: [f64; 9] = std::array::from_fn(|n| 1.0 / mass[n].sqrt());
    let scaled = Matrix9::from_fn(|i, j| k[(i, j)] * inv_sqrt[i] * inv_sqrt[j]);
    let eig = SymmetricEigen::new(scaled);
    let mut order: [usize; 9] = std::array::from_fn(|n| n);
    order.sort_by(|&a, &b| eig.eigenvalues[a].total_cmp(&eig.eigenvalues[b]));
    let omega_sq: [f64; 9] = std::array::from_fn(|n| eig.eigenvalues[order[n]]);
    let w2_max = omega_sq.iter().fold(0.0_f64, |m, &v| m.max(v.abs()));
    let rigid_modes = omega_sq
        .iter()
        .filter(|&&v| w2_max <= 0.0 || v.abs() <= ZERO_TOL * w2_max)
        .count();
    let freq_hz = omega_sq.map(|v| v.max(0.0).sqrt() / (2.0 * PI));
    let shapes = std::array::from_fn(|n| {
        let col = eig.eigenvectors.column(order[n]);
        std::array::from_fn(|i| col[i] * inv_sqrt[i])
    });
    StarModes {
        freq_hz,
        omega_sq,
        rigid_modes,
        shapes,
        stiffness: k,
    }
}

#[cfg(test)]
/// Closed form of the free star's nine frequencies (Hz), sorted (see the
/// module documentation): three rigid modes (0), the rotor pair
/// `√(3 k r² (1 + s/2) / I)/2π` (×2) and four relative translations
/// `√(6 k/m · {1 − s, 1 − s/2, 1 − s/2, 1})/2π`, with `s = ℓ₀/r`.
pub(crate) fn free_star_closed_form(phys: &Physical, strings: &StringSet) -> [f64; 9] {
    let s = rest_ratio(strings);
    let rotor = approx_frequency_closed_form(phys, strings);
    let w2_t = 6.0 * strings.k / phys.m;
    let trans = |f: f64| (w2_t * f).sqrt() / (2.0 * PI);
    let mut out = [
        0.0,
        0.0,
        0.0,
        rotor,
        rotor,
        trans(1.0 - s),
        trans(1.0 - 0.5 * s),
        trans(1.0 - 0.5 * s),
        trans(1.0),
    ];
    out.sort_by(f64::total_cmp);
    out
}
