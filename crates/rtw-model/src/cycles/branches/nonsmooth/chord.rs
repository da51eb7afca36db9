//! The probes and the bisection of [`super::locate_end`] solve a periodic
//! orbit at many values of the input, each near one already solved: the
//! iterations towards it by plain runs with that orbit's Jacobian kept (a
//! chord iteration), and one run with the variational equations at the
//! end, which checks the point and gives its multipliers, instead of a
//! variational run per Newton iteration.

use super::{Orbit, Setting, map_at, watch};
use crate::cycles::map::section::SectionPoint;
use crate::cycles::map::stepmap::StepMap;
use hybrid_ode::limit;
use nalgebra::{DMatrix, DVector};

impl Setting<'_> {
    /// [`Setting::orbit`], with the iterations towards the fixed point done
    /// by plain runs and `jacobian` (`∂Pⁿ/∂z` at a nearby orbit) kept (a
    /// chord iteration), and one run with the variational equations where
    /// they converged, which checks the point and gives the multipliers:
    /// what the probes and the bisection of [`super::locate_end`] cost, instead of
    /// a variational run per Newton iteration. [`Setting::orbit`] itself
    /// where the chord iteration does not converge (across a change, where
    /// the Jacobian jumps).
    pub(super) fn orbit_near(
        &self,
        start: &SectionPoint,
        n: usize,
        value: f64,
        jacobian: &DMatrix<f64>,
    ) -> Option<Orbit> {
        let map = map_at(self.base, self.options, self.cycle, self.param, value)?;
        let warm = chord(&map, start, n, jacobian, self.cycle.newton_tol);
        let solved = warm.and_then(|z| map.solve(&start.with_coords(&z), n, self.cycle).ok());
        match solved {
            Some(cycle) => watch(&map, cycle, value),
            None => self.orbit(start, n, value),
        }
    }
}

/// The chord iteration's target, a fraction of Newton's tolerance (its
/// iterations are cheap; Newton's last, quadratic step lands far below the
/// tolerance, and so should it), as far as it contracts.
const CHORD_BEYOND: f64 = 1e-3;

/// Most chord iterations (it converges linearly: more than Newton's).
const CHORD_ITERS: usize = 30;

/// The fixed point of `Pⁿ` near `start` by the chord iteration with
/// `jacobian` kept: the best iterate, if within `tol` (scaled).
fn chord(
    map: &StepMap,
    start: &SectionPoint,
    n: usize,
    jacobian: &DMatrix<f64>,
    tol: f64,
) -> Option<Vec<f64>> {
    let d = start.coordinate_slots().len();
    if jacobian.shape() != (d, d) {
        return None;
    }
    let lu = (jacobian - DMatrix::<f64>::identity(d, d)).lu();
    let scale = map.coord_scale(start);
    let mut z = start.coords();
    let mut best: Option<(Vec<f64>, f64)> = None;
    for _ in 0..CHORD_ITERS {
        let Some(q) = map
            .iterate(&start.with_coords(&z), n)
            .ok()
            .and_then(|s| s.last().map(|s| s.to))
            .filter(|q| q.modes == start.modes)
        else {
            break;
        };
        let pz = q.coords();
        let r = limit::scaled_max(&pz, &z, &scale);
        if best.as_ref().is_some_and(|b| r > 0.5 * b.1) {
            break;
        }
        best = Some((z.clone(), r));
        if r <= CHORD_BEYOND * tol {
            break;
        }
        let rhs = DVector::from_iterator(d, (0..d).map(|k| z[k] - pz[k]));
        let delta = lu.solve(&rhs)?;
        for k in 0..d {
            z[k] += delta[k];
        }
    }
    best.filter(|b| b.1 <= tol).map(|b| b.0)
}
