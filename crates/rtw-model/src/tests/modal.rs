//! Modal analysis against closed forms (see the documentation of `crate::modal`).

use crate::modal::linear::{
    approx_damping_closed_form, approx_decay_rate_closed_form, approx_stiffness_closed_form,
    approximate_modes_of as approximate_modes, critical_damping_closed_form, free_star_closed_form,
    free_star_modes_of as free_star_modes, s18_frequency, star_rest_forces,
};
use crate::options::Damping;
use crate::plant::strings::StringSet;
use crate::{Normalization, Params, Physical};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::PI;

fn strings(ph: &Physical, s: f64, damping: Damping) -> StringSet {
    StringSet {
        k: ph.k,
        c: ph.c,
        r: ph.r,
        rest_length: s * ph.r,
        slack: false,
        damping,
    }
}

fn fig7a(normalization: Normalization) -> Physical {
    Physical::new(&Params::fig7a(), normalization, 9.81)
}

/// Random parameter sets over the supplementary's scan ranges (L varied too).
fn random_params(n: usize) -> Vec<Params> {
    let mut rng = ChaCha8Rng::seed_from_u64(20_240_611);
    (0..n)
        .map(|_| {
            Params::new(
                rng.random_range(0.3..1.5),
                rng.random_range(1.0..5.0),
                rng.random_range(0.0..0.4),
                rng.random_range(1.5..5.0),
                rng.random_range(0.01..0.1),
                0.1,
            )
            .unwrap()
        })
        .collect()
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

#[test]
fn s18_formula_recovers_f_n() {
    // S18 with S21's k: (L − 2 l_c)/(4π) √(k/I) = f_n exactly.
    for p in random_params(10) {
        let ph = Physical::new(&p, Normalization::Supplementary, 9.81);
        assert!(rel(s18_frequency(&ph), p.f_n) < 1e-12);
    }
}

#[test]
fn approx_frequency_is_sqrt3_times_s18_and_f_n_with_eigen_normalization() {
    // Closed form: K = k r² Λ, M = I Id → ω² = 3 k r²/I = 3 (2π f_S18)²,
    // so f = √3 · f_S18 (supplementary normalization), and with the eigen
    // normalization (k/3) f = f_n. The oscillating pair is double.
    for p in random_params(12) {
        for damping in [Damping::Along, Damping::Relative] {
            let ph = Physical::new(&p, Normalization::Supplementary, 9.81);
            let m = approximate_modes(&ph, &strings(&ph, 0.0, damping));
            let want = 3f64.sqrt() * s18_frequency(&ph);
            assert_eq!(m.freq_hz.len(), 2, "{m:?}");
            for f in &m.freq_hz {
                assert!(rel(*f, want) < 1e-6, "{f} vs {want} for {p:?}");
            }
            assert_eq!(m.zero_modes, 1);

            let ph = Physical::new(&p, Normalization::Eigen, 9.81);
            let m = approximate_modes(&ph, &strings(&ph, 0.0, damping));
            for f in &m.freq_hz {
                assert!(rel(*f, p.f_n) < 1e-6, "{f} vs {} for {p:?}", p.f_n);
            }
        }
    }
}

#[test]
fn approx_damping_ratio_is_9_over_5_root3_zeta_and_zeta_with_eigen_normalization() {
    // Linear damped oscillator I ẍ + (9/2) c r² ẋ + 3 k r² x = 0 (along damper):
    // λ = −σ ± i ω_d with σ = 9 c r²/(4 I), ω_n = √(3 k r²/I), and
    // −Re λ/|λ| = σ/ω_n exactly. With S22's c = (4/5) ζ √(I k)/r this is
    // 9/(5√3) ζ; with the eigen normalization c = 4 I ζ ω_n/(9 r²) it is ζ.
    for p in random_params(12) {
        let ph = Physical::new(&p, Normalization::Supplementary, 9.81);
        let m = approximate_modes(&ph, &strings(&ph, 0.0, Damping::Along));
        let want = 9.0 / (5.0 * 3f64.sqrt()) * p.zeta;
        // Re λ = −σ = −9 c r²/(4 I) on both members of the double pair.
        let set = strings(&ph, 0.0, Damping::Along);
        let sigma = 9.0 * ph.c * ph.r * ph.r / (4.0 * ph.inertia);
        assert!(rel(approx_decay_rate_closed_form(&ph, &set), sigma) < 1e-12);
        let osc: Vec<_> = m.eigenvalues.iter().filter(|l| l.im.abs() > 1e-3).collect();
        assert_eq!(osc.len(), 4, "{:?}", m.eigenvalues);
        assert!(osc.iter().all(|l| rel(-l.re, sigma) < 1e-6), "{osc:?}");
        assert_eq!(m.damping_ratio.len(), 2, "{m:?}");
        for z in &m.damping_ratio {
            assert!(rel(*z, want) < 1e-6, "{z} vs {want} for {p:?}");
        }
        // Damped frequency ω_n √(1 − ratio²).
        let wn = 2.0 * PI * 3f64.sqrt() * p.f_n;
        for fd in &m.damped_freq_hz {
            assert!(rel(*fd, wn * (1.0 - want * want).sqrt() / (2.0 * PI)) < 1e-6);
        }

        let ph = Physical::new(&p, Normalization::Eigen, 9.81);
        let m = approximate_modes(&ph, &strings(&ph, 0.0, Damping::Along));
        for z in &m.damping_ratio {
            assert!(rel(*z, p.zeta) < 1e-6, "{z} vs {} for {p:?}", p.zeta);
        }
    }
}

#[test]
fn relative_damper_decays_at_5_c_r2_over_2i() {
    // C = c r² [[4,−1,−1],…]: eigenvalue 5 c r² on the oscillating pair, so
    // σ = 5 c r²/(2 I) and the ratio is σ/ω_n; the common rotation is damped
    // too: one real eigenvalue −2 c r²/I.
    let ph = fig7a(Normalization::Supplementary);
    let m = approximate_modes(&ph, &strings(&ph, 0.0, Damping::Relative));
    let wn = (3.0 * ph.k * ph.r * ph.r / ph.inertia).sqrt();
    let sigma = 5.0 * ph.c * ph.r * ph.r / (2.0 * ph.inertia);
    for z in &m.damping_ratio {
        assert!(rel(*z, sigma / wn) < 1e-6, "{z} vs {}", sigma / wn);
    }
    let set = strings(&ph, 0.0, Damping::Relative);
    assert!(rel(approx_decay_rate_closed_form(&ph, &set), sigma) < 1e-12);
    let pairs: Vec<_> = m.eigenvalues.iter().filter(|l| l.im > 0.0).collect();
    assert_eq!(pairs.len(), 2, "{:?}", m.eigenvalues);
    assert!(pairs.iter().all(|l| rel(-l.re, sigma) < 1e-6), "{pairs:?}");
    let rot = -2.0 * ph.c * ph.r * ph.r / ph.inertia;
    assert!(
        m.eigenvalues
            .iter()
            .any(|l| l.im.abs() <= 1e-12 * l.norm() && rel(l.re, rot) < 1e-6),
        "{:?}",
        m.eigenvalues
    );
}

#[test]
fn finite_difference_matrices_match_the_closed_forms() {
    // K = k r² (1 + s/2) Λ, Λ = [[2,−1,−1],[−1,2,−1],[−1,−1,2]] (k r² Λ at s = 0);
    // C = (3/2) c r² Λ (along), c r² [[4,−1,−1],…] (relative).
    let ph = fig7a(Normalization::Supplementary);
    for s in [0.0, 0.5, 0.85] {
        for damping in [Damping::Along, Damping::Relative] {
            let set = strings(&ph, s, damping);
            let m = approximate_modes(&ph, &set);
            let (k, c) = (
                approx_stiffness_closed_form(&set),
                approx_damping_closed_form(&set),
            );
            let kr2 = ph.k * ph.r * ph.r * (1.0 + 0.5 * s);
            assert!(rel(k[(0, 0)], 2.0 * kr2) < 1e-12 && rel(k[(0, 1)], -kr2) < 1e-12);
            let cr2 = ph.c * ph.r * ph.r;
            match damping {
                Damping::Along => assert!(rel(c[(1, 1)], 3.0 * cr2) < 1e-12),
                Damping::Relative => assert!(rel(c[(1, 1)], 4.0 * cr2) < 1e-12),
            }
            assert!((m.stiffness - k).amax() < 1e-6 * kr2, "{}", m.stiffness);
            assert!((m.damping - c).amax() < 1e-6 * cr2, "{}", m.damping);
            // Exactly one zero mode, the common rotation.
            assert_eq!(m.zero_modes, 1);
            assert_eq!(m.freq_hz.len(), 2);
            let f = (3.0 * kr2 / ph.inertia).sqrt() / (2.0 * PI);
            assert!(m.freq_hz.iter().all(|x| rel(*x, f) < 1e-6), "{m:?}");
        }
    }
}

#[test]
fn critical_damping_bisection_matches_closed_form() {
    // The pair turns real when σ = ω_n: along, 9 c r²/(4 I) = √(3 k r²/I)
    // → c = 4 √(3 k I)/(9 r); relative, 5 c r²/(2 I) = ω_n → c = 2 √(3 k I)/(5 r).
    // S17 prints (4/5) √(k I)/r instead.
    for p in random_params(6) {
        let ph = Physical::new(&p, Normalization::Supplementary, 9.81);
        for damping in [Damping::Along, Damping::Relative] {
            let set = strings(&ph, 0.0, damping);
            let m = approximate_modes(&ph, &set);
            let want = match damping {
                Damping::Along => 4.0 * (3.0 * ph.k * ph.inertia).sqrt() / (9.0 * ph.r),
                Damping::Relative => 2.0 * (3.0 * ph.k * ph.inertia).sqrt() / (5.0 * ph.r),
            };
            assert!(rel(critical_damping_closed_form(&ph, &set), want) < 1e-12);
            assert!(
                rel(m.critical_damping, want) < 1e-6,
                "{} vs {want} ({damping:?}, {p:?})",
                m.critical_damping
            );
        }
        // S17 vs the true value: ratio (4/5) / (4√3/9) = 9/(5√3).
        let s17 = 0.8 * (ph.k * ph.inertia).sqrt() / ph.r;
        let m = approximate_modes(&ph, &strings(&ph, 0.0, Damping::Along));
        assert!(rel(s17 / m.critical_damping, 9.0 / (5.0 * 3f64.sqrt())) < 1e-6);
    }
}

#[test]
fn rest_star_is_an_equilibrium_for_any_rest_length() {
    let ph = fig7a(Normalization::Supplementary);
    for s in [0.0, 0.25, 0.5, 0.85, 0.99] {
        let f = star_rest_forces(&strings(&ph, s, Damping::Along));
        assert!(f.iter().all(|v| v.abs() < 1e-10 * ph.k * ph.r), "{f:?}");
    }
}

#[test]
fn free_star_at_fig7a_point() {
    // Closed form (module documentation): rigid ×3, rotor pair √3 f_n √(1 + s/2),
    // translations √(6k/m · {1 − s, 1 − s/2, 1 − s/2, 1})/2π.
    // Measured at s = 0:    0 ×3, 5.6621 ×2, 6.1641 ×4 Hz;
    // measured at s = 0.85: 0 ×3, 2.3873, 4.6741 ×2, 6.1641, 6.7590 ×2 Hz.
    let ph = fig7a(Normalization::Supplementary);
    let sqrt3_fn = 3f64.sqrt() * s18_frequency(&ph);
    let f_t = (6.0 * ph.k / ph.m).sqrt() / (2.0 * PI);
    for (s, table) in [
        (0.0, [5.6621, 5.6621, 6.1641, 6.1641, 6.1641, 6.1641]),
        (0.85, [2.3873, 4.6741, 4.6741, 6.1641, 6.7590, 6.7590]),
    ] {
        let set = strings(&ph, s, Damping::Along);
        let m = free_star_modes(&ph, &set);
        assert_eq!(m.rigid_modes, 3, "s = {s}: {:?}", m.freq_hz);
        for j in 0..3 {
            assert!(m.freq_hz[j] < 1e-3, "{:?}", m.freq_hz);
        }
        for (f, t) in m.freq_hz[3..].iter().zip(table) {
            assert!((f - t).abs() < 1e-4, "s = {s}: {:?}", m.freq_hz);
        }
        let closed = free_star_closed_form(&ph, &set);
        for j in 3..9 {
            assert!(
                rel(m.freq_hz[j], closed[j]) < 1e-6,
                "{:?} vs {closed:?}",
                m.freq_hz
            );
        }
        // Shapes are mass-normalized: vᵀ M v = 1.
        for v in &m.shapes {
            let n: f64 = (0..9)
                .map(|i| v[i] * v[i] * if i % 3 < 2 { ph.m } else { ph.inertia })
                .sum();
            assert!((n - 1.0).abs() < 1e-9);
        }
    }
    // At s = 0: the √3 f_n pair (the approximate model's), and 6k/m ×4.
    let m = free_star_modes(&ph, &strings(&ph, 0.0, Damping::Along));
    let pair = m
        .freq_hz
        .iter()
        .filter(|f| rel(**f, sqrt3_fn) < 1e-4)
        .count();
    assert_eq!(pair, 2, "{:?}", m.freq_hz);
    let quad = m.freq_hz.iter().filter(|f| rel(**f, f_t) < 1e-6).count();
    assert_eq!(quad, 4, "{:?}", m.freq_hz);
}

#[test]
fn free_star_has_three_rigid_modes_over_parameters() {
    for p in random_params(6) {
        let ph = Physical::new(&p, Normalization::Supplementary, 9.81);
        for s in [0.0, 0.85] {
            let set = strings(&ph, s, Damping::Along);
            let m = free_star_modes(&ph, &set);
            assert_eq!(m.rigid_modes, 3, "{p:?} s = {s}: {:?}", m.freq_hz);
            let closed = free_star_closed_form(&ph, &set);
            for j in 3..9 {
                assert!(
                    rel(m.freq_hz[j], closed[j]) < 1e-6,
                    "{:?} vs {closed:?}",
                    m.freq_hz
                );
            }
        }
    }
}

#[test]
fn prestress_softening_laws() {
    // K(s) = (1 − s) K(0) + s K₁ with fixed (symmetry-determined) shapes:
    // mechanism f(s)/f(0) = √(1 − s), translation pair √(1 − s/2), one
    // translation unchanged, rotor pair √(1 + s/2); f(0) = √(6k/m)/2π for
    // the translations, √3 f_n for the rotor pair.
    let ph = fig7a(Normalization::Supplementary);
    let f_t = (6.0 * ph.k / ph.m).sqrt() / (2.0 * PI);
    let f_r = 3f64.sqrt() * s18_frequency(&ph);
    for s in [0.25, 0.5, 0.85] {
        let m = free_star_modes(&ph, &strings(&ph, s, Damping::Along));
        let count = |f: f64| m.freq_hz.iter().filter(|x| rel(**x, f) < 1e-6).count();
        assert_eq!(count(f_t * (1.0 - s).sqrt()), 1, "s = {s}: {:?}", m.freq_hz);
        assert_eq!(
            count(f_t * (1.0 - 0.5 * s).sqrt()),
            2,
            "s = {s}: {:?}",
            m.freq_hz
        );
        assert_eq!(count(f_t), 1, "s = {s}: {:?}", m.freq_hz);
        assert_eq!(
            count(f_r * (1.0 + 0.5 * s).sqrt()),
            2,
            "s = {s}: {:?}",
            m.freq_hz
        );
        // The softest mode is the mechanism: each rod slides along its own
        // axis, δc = (+e_a, −e_b, +e_c), no rotation (rest_star with θa = 0).
        let (h, c) = (0.5, 3f64.sqrt() / 2.0);
        let mech = [1.0, 0.0, 0.0, -h, -c, 0.0, -h, c, 0.0];
        let v = m.shapes[3];
        assert!(rel(m.freq_hz[3], f_t * (1.0 - s).sqrt()) < 1e-6);
        let dot: f64 = v.iter().zip(mech).map(|(a, b)| a * b).sum();
        let nv: f64 = v.iter().map(|a| a * a).sum::<f64>().sqrt();
        let nm: f64 = mech.iter().map(|a| a * a).sum::<f64>().sqrt();
        assert!(dot.abs() / (nv * nm) > 1.0 - 1e-9, "{v:?}");
    }
}
