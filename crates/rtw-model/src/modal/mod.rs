//! Linear modal analysis: the supplementary's approximate 3-rotor model
//! (S1–S18), linearized correctly, and the full free 9-DOF star.
//!
//! Both analyses linearize the string model's loads numerically (central finite
//! differences, step `1e-6` rad on angles and `1e-6 r` on positions) at the
//! rest shape, without gravity or ground, and compare with closed forms that
//! are also exported here, so that the tests check one against the other.
//!
//! # The approximate model, and how it differs from S18
//!
//! Three rods of inertia `I` pinned at one common centre, `q = (θa, θb, θc)`
//! at rest at `(θa, θa + π/3, θa + 2π/3)`, `M = I·Id`. With
//! `K = −∂τ/∂q`, `C = −∂τ/∂q̇` the state matrix is
//! `A = [[0, Id], [−M⁻¹K, −M⁻¹C]]` ([`approximate_modes`]).
//!
//! The supplementary's linearization (S7–S16) is wrong in three ways
//! (docs/model.md §7):
//!
//! * S7–S10 write `−3/π` for the rest angle `θa − θb`; it is `−π/3`.
//! * S1 with S5–S6 has the sign of `F` reversed: `F` is the gradient of the
//!   string potential, so the motion is `M q̈ = −F`, not `M q̈ = F`.
//! * It expands every `sin/cos(θi − θj)` about `−π/3`, although `θa − θc`
//!   rests at `−2π/3`.
//!
//! Linearized correctly (zero rest length, as S5–S6), with `r = L/2 − l_c`
//! and `Λ = [[2,−1,−1],[−1,2,−1],[−1,−1,2]]`:
//!
//! * stiffness `K = k r² Λ` (eigenvalues 0 — the common rotation, the one
//!   zero mode — and `3 k r²` twice);
//! * damping `C = (3/2) c r² Λ` for the `along` damper (S6), and
//!   `C = c r² [[4,−1,−1],[−1,4,−1],[−1,−1,4]]` for the `relative` one
//!   (which also damps the common rotation: a real eigenvalue `−2 c r²/I`);
//! * so the oscillating modes are one double pair
//!   `λ = −σ ± i √(ω² − σ²)` with `ω = √(3 k r²/I) = √3 · 2π f_n`, where
//!   `f_n = (L − 2 l_c)/(4π) √(k/I)` is S18's value ([`s18_frequency`]): the
//!   true frequency is `√3 · f_n`, not `f_n`;
//! * the decay rate is `σ = 9 c r²/(4 I)` (`along`; `5 c r²/(2 I)` for
//!   `relative`), so the true damping ratio is `σ/ω = 9 c r/(4 √(3 k I))`,
//!   which with S22's `c` is `9/(5√3) · ζ ≈ 1.039 ζ`;
//! * critical damping (the pair turns real when `σ = ω`) is
//!   `c_crit = 4 √(3 k I)/(9 r)` (`along`), against S17's `(4/5) √(k I)/r`
//!   (`relative`: `2 √(3 k I)/(5 r)`); [`approximate_modes`] also finds it by
//!   bisection on `c`.
//!
//! S14's two different pairs (with `5c` and `9c`) and their positive real
//! parts are artefacts of the wrong sign and of the wrong expansion point. The
//! design parameter stays `f_n` as S18 defines it: the normalization
//! S21–S22 ([`Normalization::Supplementary`](crate::Normalization)) is kept as
//! printed, and [`Normalization::Eigen`](crate::Normalization) is the
//! alternative that makes the true frequency `f_n` and the true damping
//! ratio `ζ` (`k/3`, `c = 4 I ζ (2π f_n)/(9 r²)`).
//!
//! With a natural length `ℓ₀ = s r` the tension is `k (ℓ − ℓ₀)` and the same
//! computation gives `K = k r² (1 + s/2) Λ` (the damping is unchanged).
//!
//! # The free 9-DOF star
//!
//! [`free_star_modes`]: the star with `(x, y, θ)` per rod, `M = diag(m, m, I)`
//! per rod, linearized at the rest star (an equilibrium for every `s < 1`,
//! by symmetry), solving `K v = ω² M v` through `M^{-1/2} K M^{-1/2}`.
//! Because every string has length `r` at rest, its Hessian is
//! `k ∇ℓ ∇ℓᵀ + k (1 − s) r ∇²ℓ`, i.e. `K(s) = (1 − s) K(0) + s K₁` with
//! `K₁ = k Σ ∇ℓ ∇ℓᵀ`. Central symmetry decouples the translations of the
//! centres from the rotations at first order, and 3-fold symmetry fixes the
//! mode shapes, which gives the closed form (`free_star_closed_form`,
//! checked by the tests to 1e-6):
//!
//! * 3 rigid modes (two translations, one rotation);
//! * the rotor pair of the approximate model (centres at rest):
//!   `√3 f_n · √(1 + s/2)` — it *stiffens* with prestress;
//! * four relative translations with `ω² = 6 k/m · {1, 1 − s/2, 1 − s/2, 1 − s}`:
//!   at `s = 0` a quadruple frequency `√(6 k/m)/2π = √2 f_n/(1 − 2α)`; for
//!   `s > 0` one stays, a pair softens as `√(1 − s/2)`, and one — the
//!   tensegrity's infinitesimal mechanism, each rod sliding along its own
//!   axis with `δc = (+e_a, −e_b, +e_c)`, which changes no string length at
//!   first order and is held only by prestress — softens as `√(1 − s)`.
//!
//! At the Fig. 7(a) point (`k = 500`, `r = 0.3`, `m = 2`, `I = 0.10667`,
//! `f_n = 3.269`), in Hz:
//!
//! | s | rigid | mechanism | pair | translation | rotor pair |
//! |---|---|---|---|---|---|
//! | 0 | 0 ×3 | 6.164 | 6.164 ×2 | 6.164 | 5.662 ×2 |
//! | 0.85 | 0 ×3 | 2.387 | 4.674 ×2 | 6.164 | 6.759 ×2 |
//!
//! This confirms docs/model.md §9 (5.66 Hz ×2 = `√3 f_n` and 6.16 Hz ×4 at
//! `s = 0`, one 6.16 Hz mode softening as `√(1 − s)`), and completes it: two
//! more 6.16 Hz modes soften as `√(1 − s/2)` and the 5.66 Hz pair stiffens
//! as `√(1 + s/2)`.
//!
//! The module does no I/O.
//!
//! The checks of docs/model.md §7's errata, computed from the same string
//! model, are [`errata_table`] (`cargo run -p rtw-model --example errata`).

mod errata;
pub(crate) mod linear;

pub use errata::errata_table;
pub use linear::{ApproxModes, StarModes, s18_frequency};

use crate::options::{Options, StringOptions};
use crate::params::Physical;
use crate::plant::strings::StringSet;

/// The strings of `phys` with the string model `strings` (what the plant uses).
fn string_set(phys: &Physical, strings: &StringOptions) -> StringSet {
    let options = Options {
        strings: *strings,
        ..Options::default()
    };
    StringSet::new(phys, &options)
}

/// Modes of the approximate model (S1–S6): rods of inertia `I = phys.inertia`
/// pinned at one common centre, no gravity, the strings of `strings`
/// (rest length, slack, damper), linearized at the rest angles by finite
/// differences.
pub fn approximate_modes(phys: &Physical, strings: &StringOptions) -> ApproxModes {
    linear::approximate_modes_of(phys, &string_set(phys, strings))
}

/// Modes of the free 9-DOF star (no gravity, no ground) with the strings of
/// `strings`: `K v = ω² M v` with `M = diag(m, m, I)` per rod.
pub fn free_star_modes(phys: &Physical, strings: &StringOptions) -> StarModes {
    linear::free_star_modes_of(phys, &string_set(phys, strings))
}
