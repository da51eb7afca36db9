//! Continuation of the fixed points of a map with a parameter,
//! `z = P(z; p)`: whole branches in `(z, p)`, stable and unstable, by
//! pseudo-arclength continuation, with the bifurcations on them found by
//! test functions on the Floquet multipliers and located on the branch.
//!
//! What passive-walking studies draw with AUTO or MatCont, for any return
//! map given as a closure `(z, p) ↦ (P, ∂P/∂z, ∂P/∂p)` ([`ParamMap`]):
//!
//! * [`continue_branch`]: from a fixed point, both stable and unstable parts
//!   of its branch, past folds, with step-size control;
//! * [`Bifurcation`]s on it: fold (a multiplier through +1, the branch turns
//!   back in `p`), branch point (through +1, the branch goes on), period
//!   doubling (through −1), Neimark–Sacker (a complex pair through the unit
//!   circle), each located by regula falsi on its test function to
//!   `Options::locate_tol` in arclength;
//! * [`switch_period_doubling`]: from a located period doubling onto the
//!   period-2 branch (fixed points of `P²`, [`Iterated`]).
//!
//! The unknowns are scaled (`z / z_scale`, `p / p_scale`) so that arclength
//! weighs coordinates of different units alike. Analysis code, not the hot
//! path: it allocates.

use nalgebra::{Complex, DMatrix, DVector};

mod chord;
mod curve;
pub use curve::{Curve, CurveOptions, CurvePoint, PlaneMapEval, continue_curve};

/// A map and its derivatives at one point `(z, p)`.
#[derive(Clone, Debug, PartialEq)]
pub struct MapEval {
    /// `P(z; p)`.
    pub value: Vec<f64>,
    /// `∂P/∂z`.
    pub dz: DMatrix<f64>,
    /// `∂P/∂p`.
    pub dp: Vec<f64>,
}

/// A map with a parameter: `None` where it is undefined (a run failed, the
/// pattern of events changed).
pub trait ParamMap {
    /// `P(z; p)` and its derivatives.
    fn eval(&mut self, z: &[f64], p: f64) -> Option<MapEval>;

    /// `P(z; p)` alone: what the corrector's iterations with a kept
    /// Jacobian need (a map whose derivatives cost far more than its value,
    /// such as a step map with variational equations, gives it cheaply).
    /// By default from [`ParamMap::eval`].
    fn value(&mut self, z: &[f64], p: f64) -> Option<Vec<f64>> {
        self.eval(z, p).map(|e| e.value)
    }
}

impl<F: FnMut(&[f64], f64) -> Option<MapEval>> ParamMap for F {
    fn eval(&mut self, z: &[f64], p: f64) -> Option<MapEval> {
        self(z, p)
    }
}

/// The `n`-th iterate `Pⁿ` of a map, with its derivatives by the chain rule:
/// a period-`n` orbit of `P` is a fixed point of `Pⁿ`.
pub struct Iterated<M> {
    /// The map iterated.
    pub map: M,
    /// How many times.
    pub n: u32,
}

impl<M: ParamMap> ParamMap for Iterated<M> {
    fn eval(&mut self, z: &[f64], p: f64) -> Option<MapEval> {
        let k = z.len();
        let mut acc = MapEval {
            value: z.to_vec(),
            dz: DMatrix::identity(k, k),
            dp: vec![0.0; k],
        };
        for _ in 0..self.n {
            let e = self.map.eval(&acc.value, p)?;
            let dp =
                &e.dz * DVector::from_column_slice(&acc.dp) + DVector::from_column_slice(&e.dp);
            acc = MapEval {
                dz: &e.dz * &acc.dz,
                dp: dp.iter().copied().collect(),
                value: e.value,
            };
        }
        Some(acc)
    }

    fn value(&mut self, z: &[f64], p: f64) -> Option<Vec<f64>> {
        let mut v = z.to_vec();
        for _ in 0..self.n {
            v = self.map.value(&v, p)?;
        }
        Some(v)
    }
}

/// Settings of a continuation.
#[derive(Clone, Debug, PartialEq)]
pub struct Options {
    /// First step, in scaled arclength.
    pub ds: f64,
    /// Smallest step before the branch is given up.
    pub ds_min: f64,
    /// Largest step.
    pub ds_max: f64,
    /// Most points on the branch.
    pub max_points: usize,
    /// The branch ends once `p` leaves `[p_min, p_max]`.
    pub p_min: f64,
    /// See `p_min`.
    pub p_max: f64,
    /// Newton converges when `max_k |P_k − z_k| / z_scale_k` is below this.
    pub tol: f64,
    /// Newton iterations per corrector.
    pub max_iter: u32,
    /// Bifurcations are located to this bracket in scaled arclength.
    pub locate_tol: f64,
    /// Scale of each coordinate of `z` (empty: all 1).
    pub z_scale: Vec<f64>,
    /// Scale of `p`.
    pub p_scale: f64,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            ds: 1e-2,
            ds_min: 1e-8,
            ds_max: 0.1,
            max_points: 500,
            p_min: f64::NEG_INFINITY,
            p_max: f64::INFINITY,
            tol: 1e-10,
            max_iter: 12,
            locate_tol: 1e-9,
            z_scale: Vec::new(),
            p_scale: 1.0,
        }
    }
}

/// One point of a branch.
#[derive(Clone, Debug, PartialEq)]
pub struct Point {
    /// The fixed point.
    pub z: Vec<f64>,
    /// Its parameter.
    pub p: f64,
    /// Its Floquet multipliers, largest modulus first.
    pub multipliers: Vec<Complex<f64>>,
    /// Every multiplier inside the unit circle.
    pub stable: bool,
    /// The `p` component of the unit tangent (scaled): its sign says which
    /// way the branch goes in `p`; it changes sign at a fold.
    pub tangent_p: f64,
    /// `∂P/∂z` there (for branch switching).
    pub jacobian: DMatrix<f64>,
}

/// What happens at a bifurcation of a fixed point of a map.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A multiplier through +1 where the branch turns back in `p`: two
    /// fixed points meet and vanish (saddle-node). Test function
    /// `Π (μᵢ − 1)`.
    Fold,
    /// A multiplier through +1 where the branch goes on in `p`: another
    /// branch of fixed points crosses it (transcritical or pitchfork).
    BranchPoint,
    /// A multiplier through −1: a period-2 orbit is born. Test function
    /// `Π (μᵢ + 1)`.
    PeriodDoubling,
    /// A complex pair through the unit circle: an invariant circle (a
    /// quasi-periodic gait) is born. Test function `Π_{i<j} (μᵢ μⱼ − 1)`.
    NeimarkSacker,
}

/// A located bifurcation.
#[derive(Clone, Debug, PartialEq)]
pub struct Bifurcation {
    /// What it is.
    pub kind: Kind,
    /// The branch point where its test function vanishes (to `locate_tol`).
    pub point: Point,
    /// It lies between points `after` and `after + 1` of the branch.
    pub after: usize,
    /// The test function's value at `point` (its values at the two branch
    /// points around it have opposite signs).
    pub test_value: f64,
}

/// Why a branch ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum End {
    /// `p` left `[p_min, p_max]`.
    ParameterRange,
    /// `max_points` reached.
    MaxPoints,
    /// The corrector failed at the smallest step (the branch ends, or the
    /// map is undefined beyond).
    StepTooSmall,
}

/// A branch of fixed points.
#[derive(Clone, Debug, PartialEq)]
pub struct Branch {
    /// Its points in order of arclength.
    pub points: Vec<Point>,
    /// The bifurcations located on it, in order.
    pub bifurcations: Vec<Bifurcation>,
    /// Why it ended.
    pub end: End,
}

/// Why a continuation could not start.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum Error {
    /// The starting point did not converge to a fixed point.
    #[error("no fixed point near the starting point (Newton at fixed p failed)")]
    NoStart,
    /// The branch is singular at the start: no unique tangent.
    #[error("the branch has no unique tangent at the start (a bifurcation there?)")]
    SingularStart,
    /// The operation does not apply to this kind of bifurcation (branch
    /// switching needs a period doubling, a curve a fold or one).
    #[error("not possible from a {0:?}")]
    UnsupportedKind(Kind),
}

/// The scaled problem `G(x) = (P(z; p) − z) / z_scale` in `x = (z / z_scale, p / p_scale)`.
struct Scaled<'a, M> {
    map: &'a mut M,
    zs: Vec<f64>,
    ps: f64,
    multipliers: &'a dyn Fn(&DMatrix<f64>) -> Vec<Complex<f64>>,
}

/// `G` and its Jacobian `[G_u | G_q]` at `x`, with the map's own derivatives.
struct At {
    g: DVector<f64>,
    gx: DMatrix<f64>,
    eval: MapEval,
}

impl<M: ParamMap> Scaled<'_, M> {
    fn n(&self) -> usize {
        self.zs.len()
    }

    fn unscale(&self, x: &DVector<f64>) -> (Vec<f64>, f64) {
        let n = self.n();
        ((0..n).map(|k| x[k] * self.zs[k]).collect(), x[n] * self.ps)
    }

    fn at(&mut self, x: &DVector<f64>) -> Option<At> {
        let n = self.n();
        let (z, p) = self.unscale(x);
        let eval = self.map.eval(&z, p)?;
        if eval.value.len() != n || !eval.value.iter().chain(&eval.dp).all(|v| v.is_finite()) {
            return None;
        }
        let g = DVector::from_fn(n, |k, _| (eval.value[k] - z[k]) / self.zs[k]);
        let gx = DMatrix::from_fn(n, n + 1, |r, c| {
            if c < n {
                let d = eval.dz[(r, c)] - if r == c { 1.0 } else { 0.0 };
                d * self.zs[c] / self.zs[r]
            } else {
                eval.dp[r] * self.ps / self.zs[r]
            }
        });
        Some(At { g, gx, eval })
    }

    /// Newton on `G(x) = 0`, `t·(x − x0) = ds`, from `x`.
    fn correct_from(
        &mut self,
        x0: &DVector<f64>,
        t: &DVector<f64>,
        ds: f64,
        mut x: DVector<f64>,
        tol: f64,
        max_iter: u32,
    ) -> Option<(DVector<f64>, At)> {
        for _ in 0..=max_iter {
            let at = self.at(&x)?;
            let arc = t.dot(&(&x - x0)) - ds;
            if at.g.amax() <= tol && arc.abs() <= tol {
                return Some((x, at));
            }
            x += arclength_update(&at.gx, t, &at.g, arc)?;
        }
        None
    }

    fn point(&self, x: &DVector<f64>, at: &At, tangent: &DVector<f64>) -> Point {
        let (z, p) = self.unscale(x);
        let multipliers = (self.multipliers)(&at.eval.dz);
        let stable = multipliers.iter().all(|m| m.norm() < 1.0);
        Point {
            z,
            p,
            multipliers,
            stable,
            tangent_p: tangent[self.n()],
            jacobian: at.eval.dz.clone(),
        }
    }
}

/// `[J; tᵀ]`: the Jacobian of a curve's equations bordered by the arclength
/// condition's row.
fn bordered(jac: &DMatrix<f64>, t: &DVector<f64>) -> DMatrix<f64> {
    let m = jac.nrows();
    let mut a = jac.clone().insert_row(m, 0.0);
    a.set_row(m, &t.transpose());
    a
}

/// The unit tangent of the curve whose equations have Jacobian `jac`,
/// oriented along `t`: `[J; tᵀ] τ = (0, 1)`.
fn unit_tangent(jac: &DMatrix<f64>, t: &DVector<f64>) -> Option<DVector<f64>> {
    let mut rhs = DVector::zeros(jac.nrows() + 1);
    rhs[jac.nrows()] = 1.0;
    let tau = bordered(jac, t).lu().solve(&rhs)?;
    let norm = tau.norm();
    (norm.is_finite() && norm > 0.0).then(|| tau / norm)
}

/// The Newton update of `[F(x); t·(x − x0) − ds] = 0` at a point where the
/// equations have residual `f` and Jacobian `jac` and the arclength condition
/// is off by `arc`.
fn arclength_update(
    jac: &DMatrix<f64>,
    t: &DVector<f64>,
    f: &DVector<f64>,
    arc: f64,
) -> Option<DVector<f64>> {
    let m = f.len();
    let mut r = -f.clone().insert_row(m, 0.0);
    r[m] = -arc;
    let dx = bordered(jac, t).lu().solve(&r)?;
    dx.iter().all(|v| v.is_finite()).then_some(dx)
}

/// The test functions (fold/branch point, period doubling, Neimark–Sacker)
/// at a point with Jacobian `j`, from all its eigenvalues: a system's
/// trivial multipliers (exact zeros of a step map's constrained coordinates)
/// only contribute constant factors −1, however many of them a
/// `multipliers` closure leaves out at each point.
fn tests(j: &DMatrix<f64>) -> [f64; 3] {
    let mu: Vec<Complex<f64>> = j.complex_eigenvalues().iter().copied().collect();
    let one = Complex::new(1.0, 0.0);
    let fold = mu.iter().fold(one, |a, m| a * (m - one)).re;
    let pd = mu.iter().fold(one, |a, m| a * (m + one)).re;
    let mut ns = one;
    for i in 0..mu.len() {
        for j in i + 1..mu.len() {
            ns *= mu[i] * mu[j] - one;
        }
    }
    [fold, pd, ns.re]
}

/// Continues the branch of fixed points through the fixed point near
/// `(z0, p0)`, first towards larger `p` if `direction > 0` (else smaller),
/// with `multipliers` computing the Floquet multipliers from `∂P/∂z` (e.g.
/// all eigenvalues, or only the nontrivial ones of a step map).
pub fn continue_branch<M: ParamMap>(
    map: &mut M,
    z0: &[f64],
    p0: f64,
    direction: f64,
    opts: &Options,
    multipliers: &dyn Fn(&DMatrix<f64>) -> Vec<Complex<f64>>,
) -> Result<Branch, Error> {
    let n = z0.len();
    let mut s = scaled(map, n, opts, multipliers);
    // The fixed point at p0: Newton with p held (the tangent (0, …, 0, 1)).
    let mut e_p = DVector::zeros(n + 1);
    e_p[n] = 1.0;
    let x_guess = DVector::from_fn(
        n + 1,
        |k, _| if k < n { z0[k] / s.zs[k] } else { p0 / s.ps },
    );
    let (x0, at0) = s
        .correct(&x_guess, &e_p, 0.0, opts.tol, opts.max_iter)
        .ok_or(Error::NoStart)?;
    let t0 = unit_tangent(&at0.gx, &(e_p * direction.signum())).ok_or(Error::SingularStart)?;
    Ok(trace(&mut s, x0, at0, t0, opts))
}

fn scaled<'a, M: ParamMap>(
    map: &'a mut M,
    n: usize,
    opts: &Options,
    multipliers: &'a dyn Fn(&DMatrix<f64>) -> Vec<Complex<f64>>,
) -> Scaled<'a, M> {
    let zs = if opts.z_scale.is_empty() {
        vec![1.0; n]
    } else {
        opts.z_scale.clone()
    };
    Scaled {
        map,
        zs,
        ps: opts.p_scale,
        multipliers,
    }
}

/// Follows the branch from `x0` (a fixed point, `at0` there) along `t0`.
fn trace<M: ParamMap>(
    s: &mut Scaled<'_, M>,
    x0: DVector<f64>,
    at0: At,
    t0: DVector<f64>,
    opts: &Options,
) -> Branch {
    let mut points = vec![s.point(&x0, &at0, &t0)];
    let mut bifurcations = Vec::new();
    // The Jacobian of G at the last point, kept through the next corrector.
    let mut gx = at0.gx;
    let (mut x, mut t, mut ds) = (x0, t0, opts.ds);
    let end = loop {
        if points.len() >= opts.max_points {
            break End::MaxPoints;
        }
        // A corrector that lands farther from its predictor than the step
        // is long has likely jumped to another branch: a shorter step.
        let corrected = s
            .correct_kept(&x, &t, ds, &gx, opts.tol, opts.max_iter)
            .filter(|(xn, _)| (xn - (&x + &t * ds)).norm() <= ds);
        let Some((xn, at)) = corrected else {
            ds *= 0.5;
            if ds < opts.ds_min {
                break End::StepTooSmall;
            }
            continue;
        };
        let Some(tn) = unit_tangent(&at.gx, &t) else {
            ds *= 0.5;
            if ds < opts.ds_min {
                break End::StepTooSmall;
            }
            continue;
        };
        let new = s.point(&xn, &at, &tn);
        let prev = points.last().expect("the start");
        let (ta, tb) = (tests(&prev.jacobian), tests(&new.jacobian));
        let mut found = Vec::new();
        for (k, kind) in [
            (0, Kind::Fold),
            (1, Kind::PeriodDoubling),
            (2, Kind::NeimarkSacker),
        ] {
            if ta[k] * tb[k] < 0.0
                && let Some(b) = locate(s, &x, &t, &gx, ds, k, ta[k], tb[k], opts)
            {
                let kind = match kind {
                    Kind::Fold if prev.tangent_p * new.tangent_p > 0.0 => Kind::BranchPoint,
                    other => other,
                };
                // The NS test also vanishes where two real multipliers
                // multiply to 1 (a neutral saddle): keep only a complex
                // pair on the unit circle.
                let on_circle =
                    b.0.multipliers
                        .iter()
                        .any(|m| m.im.abs() > 1e-9 && (m.norm() - 1.0).abs() < 1e-4);
                if kind != Kind::NeimarkSacker || on_circle {
                    found.push(Bifurcation {
                        kind,
                        point: b.0,
                        after: points.len() - 1,
                        test_value: b.1,
                    });
                }
            }
        }
        found.sort_by(|a, b| {
            (a.point.p - prev.p)
                .abs()
                .total_cmp(&(b.point.p - prev.p).abs())
        });
        bifurcations.extend(found);
        let p = new.p;
        points.push(new);
        if !(opts.p_min..=opts.p_max).contains(&p) {
            break End::ParameterRange;
        }
        // A step that converged: try a longer one (a failed one halves).
        ds = (ds * 1.5).min(opts.ds_max);
        x = xn;
        t = tn;
        gx = at.gx;
    };
    Branch {
        points,
        bifurcations,
        end,
    }
}

/// Regula falsi (Illinois) on test function `k` along the step from `x0`
/// (tangent `t`, `G`'s Jacobian `gx` there) of length `ds`, where it goes
/// from `fa` to `fb`: the point where it vanishes, to a bracket of
/// `opts.locate_tol` in arclength.
#[allow(clippy::too_many_arguments)]
fn locate<M: ParamMap>(
    s: &mut Scaled<'_, M>,
    x0: &DVector<f64>,
    t: &DVector<f64>,
    gx: &DMatrix<f64>,
    ds: f64,
    k: usize,
    fa: f64,
    fb: f64,
    opts: &Options,
) -> Option<(Point, f64)> {
    let (mut a, mut fa, mut b, mut fb) = (0.0f64, fa, ds, fb);
    let mut best = None;
    for _ in 0..200 {
        let (lo, hi) = (a.min(b), a.max(b));
        let c = b - fb * (b - a) / (fb - fa);
        let c = if c > lo && c < hi { c } else { 0.5 * (lo + hi) };
        let (xc, at) = s.correct_kept(x0, t, c, gx, opts.tol, opts.max_iter)?;
        let tc = unit_tangent(&at.gx, t)?;
        let point = s.point(&xc, &at, &tc);
        let fc = tests(&point.jacobian)[k];
        best = Some((point, fc));
        if fc == 0.0 {
            break;
        }
        if fc * fb < 0.0 {
            (a, fa) = (b, fb);
        } else {
            // Illinois: the end kept again weighs half.
            fa *= 0.5;
        }
        (b, fb) = (c, fc);
        if (b - a).abs() <= opts.locate_tol {
            break;
        }
    }
    best
}

/// Switches from a located period doubling of `map` onto the branch of
/// period-2 orbits born there: continues the fixed points of `P²` from the
/// bifurcation point along the eigenvector of the multiplier −1 (where the
/// new branch leaves the old one, which `P²` also has, at right angles in
/// `z`), first towards `side` (±1) along it.
pub fn switch_period_doubling<M: ParamMap>(
    map: M,
    at: &Bifurcation,
    side: f64,
    opts: &Options,
    multipliers: &dyn Fn(&DMatrix<f64>) -> Vec<Complex<f64>>,
) -> Result<(Branch, Iterated<M>), Error> {
    if at.kind != Kind::PeriodDoubling {
        return Err(Error::UnsupportedKind(at.kind));
    }
    let n = at.point.z.len();
    // The eigenvector of −1: the right singular vector of J + I with the
    // smallest singular value.
    let a = &at.point.jacobian + DMatrix::<f64>::identity(n, n);
    let svd = a.svd(false, true);
    let v_t = svd.v_t.expect("asked for V");
    let smallest = (0..n)
        .min_by(|&i, &j| svd.singular_values[i].total_cmp(&svd.singular_values[j]))
        .expect("n > 0");
    let v = v_t.row(smallest).transpose();
    let mut doubled = Iterated { map, n: 2 };
    let mut s = scaled(&mut doubled, n, opts, multipliers);
    let x0 = DVector::from_fn(n + 1, |k, _| {
        if k < n {
            at.point.z[k] / s.zs[k]
        } else {
            at.point.p / s.ps
        }
    });
    let mut t0 = DVector::from_fn(n + 1, |k, _| if k < n { v[k] / s.zs[k] } else { 0.0 });
    t0 /= t0.norm() * side.signum();
    // The first point off the old branch, then the branch from there.
    let (x1, at1) = s
        .correct(&x0, &t0, opts.ds, opts.tol, opts.max_iter)
        .ok_or(Error::NoStart)?;
    let t1 = unit_tangent(&at1.gx, &t0).ok_or(Error::SingularStart)?;
    let branch = trace(&mut s, x1, at1, t1, opts);
    Ok((branch, doubled))
}
