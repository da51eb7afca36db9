//! Limit cycles of a return map, whatever the system: fixed points by Newton,
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

    #[test]
    fn newton_reports_a_failing_map() {
        let e = newton(&[0.0], &[1.0], 1e-12, 5, |_| None).unwrap_err();
        assert_eq!(e, NewtonError::MapFailed(0));
    }
}
