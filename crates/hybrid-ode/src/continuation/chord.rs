//! The corrector with a kept Jacobian (a chord iteration): along a smooth
//! branch the Jacobian at the last point is close to the one at the next, so
//! the corrector's iterations need only the map's value
//! ([`ParamMap::value`]); its derivatives are evaluated once, at the point
//! the iterations converged to, for the multipliers, the tangent and the
//! test functions. For a step map whose Jacobian comes from variational
//! equations (tens of times the cost of a plain run) this is most of a
//! branch's cost. The point accepted satisfies the same tolerance as with
//! Newton: the last check is on a full evaluation, and where it fails, or
//! the chord iteration does not contract, Newton takes over.

use super::{At, ParamMap, Scaled, bordered};
use nalgebra::{DMatrix, DVector};

/// The chord iteration is given up (and Newton takes over) where a residual
/// does not shrink below this fraction of the one before.
const CONTRACTION: f64 = 0.5;

/// The chord iteration goes on below the tolerance, to this fraction of it
/// (or as far as it contracts: a map's own rounding stops it), since its
/// iterations are cheap: the point is then as accurate as Newton's, whose
/// last, quadratic step usually lands far below the tolerance.
const BEYOND: f64 = 1e-3;

impl<M: ParamMap> Scaled<'_, M> {
    /// Newton on `G(x) = 0`, `t·(x − x0) = ds`, from `x0 + ds t`.
    pub(super) fn correct(
        &mut self,
        x0: &DVector<f64>,
        t: &DVector<f64>,
        ds: f64,
        tol: f64,
        max_iter: u32,
    ) -> Option<(DVector<f64>, At)> {
        self.correct_from(x0, t, ds, x0 + t * ds, tol, max_iter)
    }

    /// `G(x)` alone.
    fn residual(&mut self, x: &DVector<f64>) -> Option<DVector<f64>> {
        let n = self.n();
        let (z, p) = self.unscale(x);
        let value = self.map.value(&z, p)?;
        (value.len() == n && value.iter().all(|v| v.is_finite()))
            .then(|| DVector::from_fn(n, |k, _| (value[k] - z[k]) / self.zs[k]))
    }

    /// The corrector of [`Scaled::correct`] with the Jacobian `gx` (of `G`,
    /// at a nearby point) kept through its iterations; then Newton from the
    /// best iterate where it is within `tol` (one full evaluation, which
    /// accepts it). `None` where the map is undefined at the predictor;
    /// Newton from the predictor where the chord iteration does not get
    /// within `tol`.
    pub(super) fn correct_kept(
        &mut self,
        x0: &DVector<f64>,
        t: &DVector<f64>,
        ds: f64,
        gx: &DMatrix<f64>,
        tol: f64,
        max_iter: u32,
    ) -> Option<(DVector<f64>, At)> {
        let predictor = x0 + t * ds;
        let lu = bordered(gx, t).lu();
        let mut x = predictor.clone();
        // The iterate with the smallest residual so far and that residual.
        let mut best: Option<(DVector<f64>, f64)> = None;
        for k in 0..=max_iter {
            let Some(g) = self.residual(&x) else {
                if k == 0 {
                    return None;
                }
                break;
            };
            let arc = t.dot(&(&x - x0)) - ds;
            let size = g.amax().max(arc.abs());
            let last = best.as_ref().map_or(f64::INFINITY, |b| b.1);
            if size > CONTRACTION * last {
                break;
            }
            best = Some((x.clone(), size));
            if size <= BEYOND * tol {
                break;
            }
            let m = g.len();
            let mut r = -g.insert_row(m, 0.0);
            r[m] = -arc;
            let Some(dx) = lu.solve(&r).filter(|d| d.iter().all(|v| v.is_finite())) else {
                break;
            };
            x += dx;
        }
        if let Some((x, size)) = best
            && size <= tol
        {
            return self.correct_from(x0, t, ds, x, tol, max_iter);
        }
        self.correct_from(x0, t, ds, predictor, tol, max_iter)
    }
}
