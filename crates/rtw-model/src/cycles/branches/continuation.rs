//! The step map as a map with a parameter, for
//! [`hybrid_ode::continuation`]: the branch of a gait's limit cycle in any
//! input of docs/model.md §1, stable and unstable, and its bifurcations.
//!
//! A point of the branch is a fixed point of the step map's `n`-th power at
//! section points in one pattern of contact modes (the template's): where
//! the branch meets a change of pattern the map is not smooth and the
//! continuation stops there.

use crate::cycles::map::limit_cycle::{CycleError, LimitCycle};
use crate::cycles::map::section::SectionPoint;
use crate::cycles::map::stepmap::{CycleOptions, Jacobian, StepMap};
use crate::plant::slots::{self, OMEGA};
use crate::{Options, Param, Params};
use hybrid_ode::continuation::{
    self, Bifurcation, Branch, Error as ContError, Kind, MapEval, Options as ContOptions, ParamMap,
    PlaneMapEval,
};
use hybrid_ode::limit;
use nalgebra::DMatrix;

/// Relative step of the central differences in the parameter.
const PARAM_STEP: f64 = 1e-6;

/// `z ↦ Pⁿ(z)` of the step map at section points in `template`'s modes, as a
/// function of the input `param` (the other inputs, the model and the
/// map's integrator fixed).
#[derive(Clone, Debug)]
pub struct StepMapFamily {
    base: Params,
    options: Options,
    cycle: CycleOptions,
    param: Param,
    template: SectionPoint,
    n: usize,
}

impl StepMapFamily {
    /// The family through `base` in `param`, at section points in the modes
    /// of `template`, for the `n`-th power of the map.
    pub fn new(
        base: &Params,
        options: &Options,
        cycle: &CycleOptions,
        param: Param,
        template: SectionPoint,
        n: usize,
    ) -> Self {
        Self {
            base: *base,
            options: *options,
            cycle: *cycle,
            param,
            template,
            n,
        }
    }

    /// The step map at `value` of the parameter; `None` outside its range.
    fn map_at(&self, value: f64) -> Option<StepMap> {
        let mut p = self.base;
        p[self.param] = value;
        p.validate().ok()?;
        Some(StepMap::new(&p, &self.options, &self.cycle))
    }

    /// `Pⁿ(z)` at `value`, if its orbit ends in the template's modes.
    fn power(&self, value: f64, at: &SectionPoint) -> Option<Vec<f64>> {
        let steps = self.map_at(value)?.iterate(at, self.n).ok()?;
        let to = steps.last()?.to;
        (to.modes == self.template.modes).then(|| to.coords())
    }
}

impl ParamMap for StepMapFamily {
    /// `Pⁿ` and `∂Pⁿ/∂z` by the variational equations; `∂Pⁿ/∂p` by central
    /// differences of the map (two plain runs of `n` steps).
    fn eval(&mut self, z: &[f64], value: f64) -> Option<MapEval> {
        let at = self.template.with_coords(z);
        let (q, dz) =
            self.map_at(value)?
                .power_with_jacobian(&at, self.n, Jacobian::Variational)?;
        let h = PARAM_STEP * value.abs().max(1.0);
        let (plus, minus) = (self.power(value + h, &at)?, self.power(value - h, &at)?);
        Some(MapEval {
            value: q.coords(),
            dz,
            dp: plus
                .iter()
                .zip(&minus)
                .map(|(a, b)| (a - b) / (2.0 * h))
                .collect(),
        })
    }

    /// `Pⁿ` alone: one plain run of `n` steps.
    fn value(&mut self, z: &[f64], value: f64) -> Option<Vec<f64>> {
        self.power(value, &self.template.with_coords(z))
    }
}

/// The step map with two inputs as parameters, for the curves of folds and
/// period doublings in a parameter plane
/// ([`hybrid_ode::continuation::continue_curve`]).
#[derive(Clone, Debug)]
pub struct StepMapPlane {
    family: StepMapFamily,
    second: Param,
}

impl StepMapPlane {
    /// `family`'s map with `second` as its second parameter.
    pub fn new(family: StepMapFamily, second: Param) -> Self {
        Self { family, second }
    }

    /// `Pⁿ` at `(z; p₁, p₂)` with `∂Pⁿ/∂z` (variational) and both parameter
    /// derivatives (central differences).
    pub fn eval(&self, z: &[f64], p: [f64; 2]) -> Option<PlaneMapEval> {
        let mut at = self.family.clone();
        at.base[self.second] = p[1];
        let first = at.eval(z, p[0])?;
        let h = PARAM_STEP * p[1].abs().max(1.0);
        let power = |v: f64| {
            let mut f = self.family.clone();
            f.base[self.second] = v;
            f.power(p[0], &f.template.with_coords(z))
        };
        let (plus, minus) = (power(p[1] + h)?, power(p[1] - h)?);
        let dp2 = plus
            .iter()
            .zip(&minus)
            .map(|(a, b)| (a - b) / (2.0 * h))
            .collect();
        Some(PlaneMapEval {
            value: first.value,
            dz: first.dz,
            dp: [first.dp, dp2],
        })
    }
}

/// Settings of a [`diagram`].
#[derive(Clone, Debug)]
pub struct DiagramOptions {
    /// The continuation's settings: steps, tolerances, the parameter's range
    /// (`p_min`, `p_max`) and scale. Its `z_scale` is set from the map.
    pub continuation: ContOptions,
    /// Switch onto the period-2 branch at each period doubling of the
    /// branch through the start (not recursively: one cascade level).
    pub switch_period_doubling: bool,
}

/// One branch of a [`diagram`]: fixed points of `Pⁿ`, in order.
#[derive(Clone, Debug)]
pub struct DiagramBranch {
    /// The branch's period in steps (`n`).
    pub period: usize,
    /// Index of the branch it was switched from (`None`: through the start).
    pub parent: Option<usize>,
    /// +1 / −1: the first direction of the continuation (in `p` for the
    /// branch through the start, along the −1 eigenvector for a switch).
    pub direction: f64,
    /// Its points, bifurcations and end.
    pub branch: Branch,
    /// For each point, the post-impact angular velocity ω of the new stance
    /// rod at each of the orbit's `n` section points (the diagram's
    /// vertical axis: one value per step of the orbit, so a period-2
    /// branch shows as two curves).
    pub omega: Vec<Vec<f64>>,
}

/// A bifurcation diagram of a gait in one input: the branch of its limit
/// cycle through the start, both ways, stable and unstable, with its
/// bifurcations, and the period-2 branches born at its period doublings.
#[derive(Clone, Debug)]
pub struct Diagram {
    /// The input continued.
    pub param: Param,
    /// The limit cycle the branches start from.
    pub start: LimitCycle,
    /// The branches: through the start upwards and downwards in `p`, then
    /// the switched ones.
    pub branches: Vec<DiagramBranch>,
}

impl Diagram {
    /// ω of the new stance rod at the section point with coordinates `z`
    /// in the start's mode pattern (for bifurcation points and curves).
    pub fn omega_at(&self, z: &[f64]) -> f64 {
        stance_omega(&self.start.orbit[0].with_coords(z))
    }
}

/// Why a diagram could not be started. Its message holds its cause; it
/// hands on no `source` (a chain printer would say the cause twice).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum DiagramError {
    /// No limit cycle at the start.
    #[error("no limit cycle at the start: {0}")]
    Cycle(CycleError),
    /// The continuation could not start from it.
    #[error("the continuation could not start: {0}")]
    Continuation(ContError),
}

impl From<CycleError> for DiagramError {
    fn from(e: CycleError) -> Self {
        Self::Cycle(e)
    }
}

impl From<ContError> for DiagramError {
    fn from(e: ContError) -> Self {
        Self::Continuation(e)
    }
}

impl DiagramBranch {
    /// A branch of fixed points of `family`'s map (period `family.n`), with
    /// the orbit's ω at each point.
    fn of(family: &StepMapFamily, parent: Option<usize>, direction: f64, branch: Branch) -> Self {
        let omega = branch
            .points
            .iter()
            .map(|pt| orbit_omega(family, &pt.z, pt.p))
            .collect();
        Self {
            period: family.n,
            parent,
            direction,
            branch,
            omega,
        }
    }
}

/// ω of the new stance rod (a+ in canonical labels) at a section point.
fn stance_omega(p: &SectionPoint) -> f64 {
    p.y[slots::at(0, OMEGA)]
}

/// ω at each of the `n` section points of the orbit from `z` at `value`.
fn orbit_omega(family: &StepMapFamily, z: &[f64], value: f64) -> Vec<f64> {
    let at = family.template.with_coords(z);
    let Some(map) = family.map_at(value) else {
        return vec![f64::NAN; family.n];
    };
    let mut out = vec![stance_omega(&at)];
    if let Ok(steps) = map.iterate(&at, family.n - 1) {
        out.extend(steps.iter().map(|s| stance_omega(&s.to)));
    }
    out.resize(family.n, f64::NAN);
    out
}

/// The bifurcation diagram of the gait that `base` settles into, in
/// `param`: solves its limit cycle ([`StepMap::limit_cycle`]; where the
/// settled iterates show no period, the period-1 cycle nearest them), continues
/// the fixed point of `Pⁿ` (`n` its period) both ways by pseudo-arclength
/// ([`continuation::continue_branch`]), and, if asked, switches onto the
/// period-2ⁿ branch at each period doubling found
/// ([`continuation::switch_period_doubling`], first towards +1 along the
/// eigenvector of −1).
pub fn diagram(
    base: &Params,
    options: &Options,
    cycle: &CycleOptions,
    param: Param,
    opts: &DiagramOptions,
) -> Result<Diagram, DiagramError> {
    let map = StepMap::new(base, options, cycle);
    let start = match map.limit_cycle(options, cycle) {
        // A cycle near a Neimark–Sacker point (or just past one, inside the
        // invariant circle its iterates settle on) shows no period: Newton
        // for a period-1 cycle from where the settled iterates are.
        Err(CycleError::NoPeriod(_)) => {
            let mut p = map.first(options).map_err(CycleError::from)?.to;
            for _ in 0..cycle.settle_steps {
                p = map.step(&p).map_err(CycleError::from)?.to;
            }
            map.solve(&p, 1, cycle)?
        }
        other => other?,
    };
    let template = start.orbit[0];
    let cont = ContOptions {
        z_scale: map.coord_scale(&template),
        ..opts.continuation.clone()
    };
    let family = StepMapFamily::new(base, options, cycle, param, template, start.period);
    let multipliers = |j: &DMatrix<f64>| limit::nontrivial_multipliers(j);
    let z0 = start.fixed_point.z.clone();
    let p0 = base[param];
    let mut branches = Vec::new();
    for direction in [1.0, -1.0] {
        let mut f = family.clone();
        let branch =
            continuation::continue_branch(&mut f, &z0, p0, direction, &cont, &multipliers)?;
        branches.push(DiagramBranch::of(&family, None, direction, branch));
    }
    if opts.switch_period_doubling {
        for parent in 0..branches.len() {
            let doublings: Vec<Bifurcation> = branches[parent]
                .branch
                .bifurcations
                .iter()
                .filter(|b| b.kind == Kind::PeriodDoubling)
                .cloned()
                .collect();
            for bif in doublings {
                // A switch that does not start (the −1 eigenvector leads off
                // the template's mode pattern) leaves the diagram without that
                // branch; the parent's bifurcation point still marks it.
                let Ok((branch, _)) = continuation::switch_period_doubling(
                    family.clone(),
                    &bif,
                    1.0,
                    &cont,
                    &multipliers,
                ) else {
                    continue;
                };
                let doubled = StepMapFamily {
                    n: 2 * family.n,
                    ..family.clone()
                };
                branches.push(DiagramBranch::of(&doubled, Some(parent), 1.0, branch));
            }
        }
    }
    Ok(Diagram {
        param,
        start,
        branches,
    })
}
