//! Curves of folds and period doublings in two parameters: the boundary of
//! the region of a parameter plane where a fixed point exists (fold) or is
//! stable against period doubling.

use super::{Bifurcation, End, Error, Kind, Options, arclength_update, unit_tangent};
use nalgebra::{Complex, DMatrix, DVector};

/// A map with two parameters and its derivatives at `(z, p)`.
#[derive(Clone, Debug, PartialEq)]
pub struct PlaneMapEval {
    /// `P(z; p)`.
    pub value: Vec<f64>,
    /// `∂P/∂z`.
    pub dz: DMatrix<f64>,
    /// `∂P/∂p₁` and `∂P/∂p₂`.
    pub dp: [Vec<f64>; 2],
}

/// A point of a curve of bifurcations in two parameters.
#[derive(Clone, Debug, PartialEq)]
pub struct CurvePoint {
    /// The fixed point on the bifurcation.
    pub z: Vec<f64>,
    /// The two parameters.
    pub p: [f64; 2],
    /// Its multipliers (one on +1 for a fold, on −1 for a period doubling).
    pub multipliers: Vec<Complex<f64>>,
}

/// A curve of folds or period doublings in the parameter plane: the
/// boundary of the region where a fixed point exists (fold) or is stable
/// against period doubling.
#[derive(Clone, Debug, PartialEq)]
pub struct Curve {
    /// Fold or period doubling.
    pub kind: Kind,
    /// Its points in order of arclength.
    pub points: Vec<CurvePoint>,
    /// Why it ended.
    pub end: End,
}

/// Settings of a two-parameter continuation: `p_min`/`p_max`/`p_scale` of
/// `base` apply to the first parameter, these to the second.
#[derive(Clone, Debug, PartialEq)]
pub struct CurveOptions {
    /// Steps, tolerances, first-parameter range and scales.
    pub base: Options,
    /// The curve ends once the second parameter leaves this range.
    pub p2_range: (f64, f64),
    /// Scale of the second parameter.
    pub p2_scale: f64,
    /// Step of the central differences of the test function (scaled units).
    pub fd_step: f64,
}

/// The augmented system at a point: `F`, its Jacobian and `∂P/∂z`.
type Augmented = (DVector<f64>, DMatrix<f64>, DMatrix<f64>);

/// The augmented system at `x`, with the test function's gradient given
/// (kept) or computed afresh (`None`).
type AugmentedSystem<'a> =
    dyn FnMut(&DVector<f64>, Option<&DVector<f64>>) -> Option<Augmented> + 'a;

/// Continues a located fold or period doubling (`at`, found at second
/// parameter `p2`) in both parameters: the curve where `P(z; p₁, p₂) = z`
/// and `det(∂P/∂z ∓ I) = 0` (− for a fold, + for a period doubling), first
/// towards larger `p₂` if `direction > 0`.
pub fn continue_curve<F>(
    mut map: F,
    at: &Bifurcation,
    p2: f64,
    direction: f64,
    opts: &CurveOptions,
    multipliers: &dyn Fn(&DMatrix<f64>) -> Vec<Complex<f64>>,
) -> Result<Curve, Error>
where
    F: FnMut(&[f64], [f64; 2]) -> Option<PlaneMapEval>,
{
    let sign = match at.kind {
        Kind::Fold => -1.0,
        Kind::PeriodDoubling => 1.0,
        other => return Err(Error::UnsupportedKind(other)),
    };
    let n = at.point.z.len();
    let o = &opts.base;
    let zs = if o.z_scale.is_empty() {
        vec![1.0; n]
    } else {
        o.z_scale.clone()
    };
    let (ps1, ps2) = (o.p_scale, opts.p2_scale);
    let unscale = |x: &DVector<f64>| -> (Vec<f64>, [f64; 2]) {
        (
            (0..n).map(|k| x[k] * zs[k]).collect(),
            [x[n] * ps1, x[n + 1] * ps2],
        )
    };
    // F(x) = [(P − z)/zs; det(J ∓ I)] and its Jacobian (n + 1) × (n + 2).
    // The last row (the test function's gradient, by central differences:
    // 2(n + 2) Jacobians of the map) is the costly part. It is computed at
    // the first iterate of a corrector and then kept, from iterate to iterate
    // and from point to point (a chord iteration in that row; the map's own
    // rows are exact at every iterate); a corrector that fails with a kept
    // gradient is retried with a fresh one before the step is shortened.
    let mut system = |x: &DVector<f64>,
                      gradient: Option<&DVector<f64>>|
     -> Option<(DVector<f64>, DMatrix<f64>, DMatrix<f64>)> {
        let (z, p) = unscale(x);
        let e = map(&z, p)?;
        let test = |j: &DMatrix<f64>| (j + DMatrix::<f64>::identity(n, n) * sign).determinant();
        let mut f = DVector::from_fn(n + 1, |k, _| {
            if k < n {
                (e.value[k] - z[k]) / zs[k]
            } else {
                0.0
            }
        });
        f[n] = test(&e.dz);
        if !f.iter().all(|v| v.is_finite()) {
            return None;
        }
        let mut jac = DMatrix::zeros(n + 1, n + 2);
        for r in 0..n {
            for c in 0..n {
                let d = e.dz[(r, c)] - if r == c { 1.0 } else { 0.0 };
                jac[(r, c)] = d * zs[c] / zs[r];
            }
            jac[(r, n)] = e.dp[0][r] * ps1 / zs[r];
            jac[(r, n + 1)] = e.dp[1][r] * ps2 / zs[r];
        }
        match gradient {
            Some(g) => jac.row_mut(n).copy_from(&g.transpose()),
            None => {
                for c in 0..n + 2 {
                    let mut xp = x.clone();
                    xp[c] += opts.fd_step;
                    let (zp, pp) = unscale(&xp);
                    let fp = test(&map(&zp, pp)?.dz);
                    xp[c] -= 2.0 * opts.fd_step;
                    let (zm, pm) = unscale(&xp);
                    let fm = test(&map(&zm, pm)?.dz);
                    jac[(n, c)] = (fp - fm) / (2.0 * opts.fd_step);
                }
            }
        }
        Some((f, jac, e.dz))
    };
    let correct = |system: &mut AugmentedSystem<'_>,
                   gradient: &mut Option<DVector<f64>>,
                   x0: &DVector<f64>,
                   t: &DVector<f64>,
                   ds: f64|
     -> Option<Augmented> {
        let mut x = x0 + t * ds;
        // The last step and test value, for Broyden's update of the kept row.
        let mut last: Option<(DVector<f64>, f64)> = None;
        for _ in 0..=o.max_iter {
            let (f, mut jac, dz) = system(&x, gradient.as_ref())?;
            if let (Some(g), Some((dx, f_prev))) = (gradient.as_mut(), last.as_ref()) {
                // Secant update after a step: the kept row then predicts the
                // test function's change along that step exactly
                // (superlinear convergence instead of the chord's linear one).
                let miss = f[n] - f_prev - g.dot(dx);
                *g += dx * (miss / dx.norm_squared());
                jac.row_mut(n).copy_from(&g.transpose());
            }
            let arc = t.dot(&(&x - x0)) - ds;
            let scale_f = f.rows(0, n).amax();
            // The test function's residual over its gradient: the distance
            // to its zero set, to first order, in the same scaled units.
            let off = f[n].abs() / jac.row(n).norm().max(f64::MIN_POSITIVE);
            if scale_f <= o.tol && arc.abs() <= o.tol && off <= o.tol {
                return Some((x, jac, dz));
            }
            gradient.get_or_insert_with(|| jac.row(n).transpose());
            let dx = arclength_update(&jac, t, &f, arc)?;
            x += &dx;
            last = Some((dx, f[n]));
        }
        None
    };
    // A corrector with the kept gradient, and if it fails, with a fresh one.
    let mut gradient: Option<DVector<f64>> = None;
    let mut correct = |system: &mut AugmentedSystem<'_>,
                       x0: &DVector<f64>,
                       t: &DVector<f64>,
                       ds: f64|
     -> Option<Augmented> {
        if gradient.is_some() {
            if let Some(found) = correct(system, &mut gradient, x0, t, ds) {
                return Some(found);
            }
            gradient = None;
        }
        correct(system, &mut gradient, x0, t, ds)
    };
    // The start: the bifurcation corrected at fixed p₂, then the tangent
    // oriented towards `direction` in p₂.
    let mut e2 = DVector::zeros(n + 2);
    e2[n + 1] = 1.0;
    let guess = DVector::from_fn(n + 2, |k, _| match k {
        k if k < n => at.point.z[k] / zs[k],
        k if k == n => at.point.p / ps1,
        _ => p2 / ps2,
    });
    let (mut x, jac0, dz0) = correct(&mut system, &guess, &e2, 0.0).ok_or(Error::NoStart)?;
    let mut t = unit_tangent(&jac0, &(e2 * direction.signum())).ok_or(Error::SingularStart)?;
    let point = |x: &DVector<f64>, dz: &DMatrix<f64>| {
        let (z, p) = unscale(x);
        CurvePoint {
            z,
            p,
            multipliers: multipliers(dz),
        }
    };
    let mut points = vec![point(&x, &dz0)];
    let mut ds = o.ds;
    let end = loop {
        if points.len() >= o.max_points {
            break End::MaxPoints;
        }
        let step = correct(&mut system, &x, &t, ds)
            .and_then(|(xn, jac, dz)| Some((unit_tangent(&jac, &t)?, xn, dz)));
        let Some((tn, xn, dz)) = step else {
            ds *= 0.5;
            if ds < o.ds_min {
                break End::StepTooSmall;
            }
            continue;
        };
        let pt = point(&xn, &dz);
        let [p1, p2] = pt.p;
        points.push(pt);
        if !(o.p_min..=o.p_max).contains(&p1) || !(opts.p2_range.0..=opts.p2_range.1).contains(&p2)
        {
            break End::ParameterRange;
        }
        ds = (ds * 1.5).min(o.ds_max);
        x = xn;
        t = tn;
    };
    Ok(Curve {
        kind: at.kind,
        points,
        end,
    })
}
