//! Limit cycles of a return map, whatever the system: fixed points by Newton
//! or by Anderson acceleration (no Jacobian),
//! Jacobians by finite differences, Floquet multipliers.
//!
//! A steady gait is a fixed point `z* = P(z*)` of its step map `P` (a period-n
//! gait: of `Pⁿ`). Its Floquet multipliers are the eigenvalues of `∂P/∂z` at
//! `z*`; the gait is (linearly) stable when all lie inside the unit circle.
//! The maps themselves live with their systems (the `rimless` test fixture
//! for McGeer's wheel; the RTW's step map in `rtw-model`); this module only needs
//! them as closures `z ↦ (P(z), ∂P/∂z)`.
//!
//! Analysis code, not the hot path: it allocates (small `DMatrix`es).

use nalgebra::{Complex, DMatrix, DVector};

/// A fixed point found by [`newton`].
#[derive(Clone, Debug, PartialEq)]
pub struct FixedPoint {
    /// The fixed point (the last iterate).
    pub z: Vec<f64>,
    /// `∂P/∂z` at `z` (the last Jacobian evaluated, at the converged point).
    pub jacobian: DMatrix<f64>,
    /// `max_k |P(z)_k − z_k| / scale_k` at `z`.
    pub residual: f64,
    /// Newton iterations taken.
    pub iterations: u32,
}

/// Why [`newton`] gave up.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum NewtonError {
    /// The map is undefined at the iterate of this iteration.
    #[error("the map is undefined at an iterate (iteration {0})")]
    MapFailed(u32),
    /// `∂P/∂z − I` is singular at an iterate.
    #[error("P − I is singular at an iterate (a multiplier at 1)")]
    Singular,
    /// The iteration cap was reached.
    #[error("no convergence in {iterations} iterations (scaled residual {residual:.3e})")]
    NoConvergence {
        /// Iterations taken.
        iterations: u32,
        /// The scaled residual at the last iterate.
        residual: f64,
    },
}

/// Newton's method on `P(z) − z = 0`.
///
/// `map(z)` returns `P(z)` and `∂P/∂z` at `z`, or `None` where the map is
/// undefined (the run failed, the mode pattern changed). Converged when the
/// scaled residual `max_k |P(z)_k − z_k| / scale_k ≤ tol`; the point returned
/// is the last iterate `z` (not the Newton update from it), so that its
/// residual and Jacobian are the ones measured there.
pub fn newton(
    z0: &[f64],
    scale: &[f64],
    tol: f64,
    max_iter: u32,
    mut map: impl FnMut(&[f64]) -> Option<(Vec<f64>, DMatrix<f64>)>,
) -> Result<FixedPoint, NewtonError> {
    let n = z0.len();
    let mut z = z0.to_vec();
    let mut residual = f64::INFINITY;
    for it in 0..=max_iter {
        let (pz, j) = map(&z).ok_or(NewtonError::MapFailed(it))?;
        residual = scaled_max(&pz, &z, scale);
        if residual <= tol {
            return Ok(FixedPoint {
                z,
                jacobian: j,
                residual,
                iterations: it,
            });
        }
        if it == max_iter {
            break;
        }
        // (J − I) δ = −(P(z) − z)
        let a = j - DMatrix::<f64>::identity(n, n);
        let r = DVector::from_iterator(n, (0..n).map(|k| z[k] - pz[k]));
        let delta = a.lu().solve(&r).ok_or(NewtonError::Singular)?;
        for k in 0..n {
            z[k] += delta[k];
        }
    }
    Err(NewtonError::NoConvergence {
        iterations: max_iter,
        residual,
    })
}

/// A fixed point found by [`anderson`] (no Jacobian is taken).
#[derive(Clone, Debug, PartialEq)]
pub struct AndersonPoint {
    /// The fixed point (the last iterate at which the map was evaluated).
    pub z: Vec<f64>,
    /// `max_k |P(z)_k − z_k| / scale_k` at `z`.
    pub residual: f64,
    /// Evaluations of the map.
    pub evaluations: u32,
}

/// The fixed point of `P` by Anderson acceleration of the iteration
/// `z ← P(z)` (type II, depth `depth`: Walker and Ni, SIAM J. Numer. Anal.
/// 49(4), 2011): each iterate is `P(z_k)` corrected by the combination of
/// the last `depth` differences of `P` whose residuals best cancel the
/// latest one (least squares, in the scaled coordinates `z_k / scale_k`).
///
/// Near a fixed point `P` is nearly linear, and the acceleration then
/// behaves like GMRES on `(∂P/∂z − I) δ = −(P(z) − z)`: the slow directions
/// that take the plain iteration `log(tol) / log(μ)` evaluations (60 for a
/// multiplier of 0.8) are taken in a few, without the `2d` evaluations a
/// difference Jacobian costs. No Jacobian comes out, so it suits a caller
/// that needs the point only.
///
/// `map(z)` returns `P(z)`, or `None` where the map is undefined. Converged
/// when the scaled residual at an evaluated iterate is at most `tol`; that
/// iterate is returned. Gives up after `max_evals` evaluations.
pub fn anderson(
    z0: &[f64],
    scale: &[f64],
    tol: f64,
    depth: usize,
    max_evals: u32,
    mut map: impl FnMut(&[f64]) -> Option<Vec<f64>>,
) -> Result<AndersonPoint, NewtonError> {
    let n = z0.len();
    let scaled = |v: &[f64]| DVector::from_iterator(n, (0..n).map(|k| v[k] / scale[k]));
    let mut z = z0.to_vec();
    // The latest `depth + 1` values of P and residuals, scaled, oldest first.
    let mut gs: Vec<DVector<f64>> = Vec::with_capacity(depth + 1);
    let mut fs: Vec<DVector<f64>> = Vec::with_capacity(depth + 1);
    let mut residual = f64::INFINITY;
    for it in 0..max_evals {
        let pz = map(&z).ok_or(NewtonError::MapFailed(it))?;
        residual = scaled_max(&pz, &z, scale);
        if residual <= tol {
            return Ok(AndersonPoint {
                z,
                residual,
                evaluations: it + 1,
            });
        }
        let g = scaled(&pz);
        let f = &g - scaled(&z);
        if gs.len() == depth + 1 {
            gs.remove(0);
            fs.remove(0);
        }
        gs.push(g);
        fs.push(f);
        let m = gs.len() - 1;
        let (g, f) = (&gs[m], &fs[m]);
        let next = if m == 0 {
            g.clone()
        } else {
            let df = DMatrix::from_fn(n, m, |r, c| fs[c + 1][r] - fs[c][r]);
            let dg = DMatrix::from_fn(n, m, |r, c| gs[c + 1][r] - gs[c][r]);
            let svd = df.svd(true, true);
            let cut = 1e-12 * svd.singular_values.max();
            match svd.solve(f, cut) {
                Ok(gamma) => g - dg * gamma,
                Err(_) => g.clone(),
            }
        };
        z = (0..n).map(|k| next[k] * scale[k]).collect();
    }
    Err(NewtonError::NoConvergence {
        iterations: max_evals,
        residual,
    })
}

/// `max_k |a_k − b_k| / scale_k`.
pub fn scaled_max(a: &[f64], b: &[f64], scale: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .zip(scale)
        .map(|((x, y), s)| (x - y).abs() / s)
        .fold(0.0, f64::max)
}

/// `∂P/∂z` at `z` by central differences with step `step_k` in coordinate `k`
/// (two map evaluations per column). `None` if the map fails at a perturbed
/// point.
pub fn fd_jacobian(
    z: &[f64],
    step: &[f64],
    mut map: impl FnMut(&[f64]) -> Option<Vec<f64>>,
) -> Option<DMatrix<f64>> {
    let n = z.len();
    let mut j = DMatrix::<f64>::zeros(n, n);
    let mut zp = z.to_vec();
    for c in 0..n {
        zp[c] = z[c] + step[c];
        let fp = map(&zp)?;
        zp[c] = z[c] - step[c];
        let fm = map(&zp)?;
        zp[c] = z[c];
        if fp.len() != n || fm.len() != n {
            return None;
        }
        for r in 0..n {
            j[(r, c)] = (fp[r] - fm[r]) / (2.0 * step[c]);
        }
    }
    Some(j)
}

/// Floquet multipliers: the eigenvalues of `j`, largest modulus first
/// (a conjugate pair: positive imaginary part first).
pub fn multipliers(j: &DMatrix<f64>) -> Vec<Complex<f64>> {
    let mut mu: Vec<Complex<f64>> = j.complex_eigenvalues().iter().copied().collect();
    mu.sort_by(|a, b| b.norm().total_cmp(&a.norm()).then(b.im.total_cmp(&a.im)));
    mu
}

/// The Floquet multipliers of a step map with Jacobian `j`, without the
/// trivial ones: a coordinate that the map sets to the same value whatever
/// its input (a zero row of `j`, e.g. a foot's velocity, zero after every
/// sticking impact) is a constraint of the section, not a direction of the
/// motion. Expanding `det(j − μI)` along such a row gives a factor `−μ` and
/// the minor without that row and column, so the nontrivial multipliers are
/// the eigenvalues of `j` with those rows and columns removed. A row counts
/// as zero when no entry exceeds `1e-12` times `j`'s largest entry.
pub fn nontrivial_multipliers(j: &DMatrix<f64>) -> Vec<Complex<f64>> {
    let floor = 1e-12 * j.abs().max();
    let keep: Vec<usize> = (0..j.nrows())
        .filter(|&r| j.row(r).iter().any(|v| v.abs() > floor))
        .collect();
    let minor = DMatrix::from_fn(keep.len(), keep.len(), |r, c| j[(keep[r], keep[c])]);
    multipliers(&minor)
}

/// The largest modulus among `mu` (0 if empty).
pub fn spectral_radius(mu: &[Complex<f64>]) -> f64 {
    mu.iter().map(|m| m.norm()).fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A linear map `P(z) = A z + b` has its fixed point at `(I − A)⁻¹ b`,
    /// found by one Newton step; its multipliers are A's eigenvalues.
    #[test]
    fn newton_solves_an_affine_map_in_one_step() {
        let a = DMatrix::from_row_slice(2, 2, &[0.5, 0.2, -0.1, 0.3]);
        let b = DVector::from_row_slice(&[1.0, -2.0]);
        let map = |z: &[f64]| {
            let p = &a * DVector::from_row_slice(z) + &b;
            Some((p.iter().copied().collect(), a.clone()))
        };
        let fp = newton(&[0.0, 0.0], &[1.0, 1.0], 1e-12, 5, map).unwrap();
        assert_eq!(fp.iterations, 1);
        let exact = (DMatrix::identity(2, 2) - &a).lu().solve(&b).unwrap();
        for k in 0..2 {
            assert!((fp.z[k] - exact[k]).abs() < 1e-14);
        }
        // Eigenvalues of [[0.5, 0.2], [−0.1, 0.3]]: 0.4 ± 0.1 i (trace 0.8,
        // determinant 0.17).
        let mu = multipliers(&a);
        assert!((mu[0] - Complex::new(0.4, 0.1)).norm() < 1e-14);
        assert!((mu[1] - Complex::new(0.4, -0.1)).norm() < 1e-14);
        assert!((spectral_radius(&mu) - 0.17f64.sqrt()).abs() < 1e-14);
    }

    /// Central differences of a quadratic are exact up to rounding.
    #[test]
    fn fd_jacobian_of_a_quadratic_map() {
        let map = |z: &[f64]| Some(vec![z[0] * z[0] + z[1], 3.0 * z[0] * z[1]]);
        let j = fd_jacobian(&[1.5, -2.0], &[1e-3, 1e-3], map).unwrap();
        let exact = [[3.0, 1.0], [-6.0, 4.5]];
        for r in 0..2 {
            for c in 0..2 {
                assert!((j[(r, c)] - exact[r][c]).abs() < 1e-10);
            }
        }
    }

    /// A coordinate the map always resets (a zero row) adds a multiplier 0
    /// that is not one of the motion's.
    #[test]
    fn constrained_coordinates_are_trivial_multipliers() {
        let j = DMatrix::from_row_slice(3, 3, &[0.5, 0.1, 2.0, 0.0, 0.0, 0.0, 0.2, 0.3, -0.4]);
        assert_eq!(multipliers(&j).len(), 3);
        let mu = nontrivial_multipliers(&j);
        // The minor [[0.5, 2.0], [0.2, −0.4]]: trace 0.1, determinant −0.6,
        // eigenvalues (0.1 ± sqrt(0.01 + 2.4)) / 2.
        let d = (0.01f64 + 2.4).sqrt();
        assert_eq!(mu.len(), 2);
        assert!((mu[0].re - (0.1 + d) / 2.0).abs() < 1e-14);
        assert!((mu[1].re - (0.1 - d) / 2.0).abs() < 1e-14);
    }

    /// An affine contraction in 8 dimensions, not normal, whose slowest
    /// multipliers are 0.9 ± 0.39 i (modulus 0.98) and 0.97: the plain
    /// iteration needs about `log(1e-10) / log(0.98)` ≈ 1100 evaluations to
    /// reach the tolerance; accelerated to depth 6 it reaches the exact
    /// fixed point `(I − A)⁻¹ b` in under 30, as GMRES would.
    #[test]
    fn anderson_finds_the_fixed_point_of_a_slow_affine_map() {
        let n = 8;
        let mut a = DMatrix::<f64>::zeros(n, n);
        a[(0, 0)] = 0.97;
        a[(1, 1)] = 0.9;
        a[(1, 2)] = 0.3;
        a[(2, 1)] = -0.3;
        a[(2, 2)] = 0.9;
        for k in 3..n {
            a[(k, k)] = 0.5 - 0.1 * k as f64;
        }
        // Couplings above the diagonal: not normal.
        for r in 0..n - 1 {
            a[(r, r + 1)] += 0.2;
        }
        let b = DVector::from_fn(n, |k, _| 1.0 + k as f64);
        let scale: Vec<f64> = (0..n).map(|k| 1.0 + 0.5 * k as f64).collect();
        let map = |z: &[f64]| {
            let p = &a * DVector::from_column_slice(z) + &b;
            Some(p.iter().copied().collect())
        };
        let tol = 1e-10;
        let fp = anderson(&vec![0.0; n], &scale, tol, 6, 60, map).unwrap();
        assert!(fp.evaluations < 30, "{}", fp.evaluations);
        assert!(fp.residual <= tol);
        let exact = (DMatrix::identity(n, n) - &a).lu().solve(&b).unwrap();
        // The residual bounds the error by ‖(I − A)⁻¹‖∞, 65 here (NumPy).
        for k in 0..n {
            assert!((fp.z[k] - exact[k]).abs() <= 100.0 * tol * scale[k], "{k}");
        }
    }

    /// The logistic map's fixed point `1 − 1/r` (multiplier `2 − r` = −0.9
    /// at r = 2.9, so the plain iteration alternates about it and takes some
    /// 260 evaluations to 1e-12): a nonlinear map, found in under 20.
    #[test]
    fn anderson_finds_the_logistic_maps_fixed_point() {
        let r = 2.9;
        let fp = anderson(&[0.5], &[1.0], 1e-12, 3, 40, |z| {
            Some(vec![r * z[0] * (1.0 - z[0])])
        })
        .unwrap();
        assert!((fp.z[0] - (1.0 - 1.0 / r)).abs() < 1e-11);
        assert!(fp.evaluations < 20, "{}", fp.evaluations);
    }

    /// A map that fails at the third iterate, and one that cannot converge
    /// (`z + 1`), are reported as such.
    #[test]
    fn anderson_reports_a_failing_map_and_no_convergence() {
        let mut calls = 0;
        let e = anderson(&[0.0], &[1.0], 1e-12, 3, 10, |z| {
            calls += 1;
            (calls < 3).then(|| vec![0.5 * z[0] + 1.0])
        })
        .unwrap_err();
        assert_eq!(e, NewtonError::MapFailed(2));
        let e = anderson(&[0.0], &[1.0], 1e-12, 3, 10, |z| Some(vec![z[0] + 1.0])).unwrap_err();
        assert!(
            matches!(e, NewtonError::NoConvergence { iterations: 10, .. }),
            "{e:?}"
        );
    }

    #[test]
    fn newton_reports_a_failing_map() {
        let e = newton(&[0.0], &[1.0], 1e-12, 5, |_| None).unwrap_err();
        assert_eq!(e, NewtonError::MapFailed(0));
    }
}
