//! The RTW's step map on its section ([`crate::cycles::map::section`]) and its
//! Jacobian; the limit cycles it finds are in [`crate::cycles::map::limit_cycle`].
//!
//! **Jacobian.** By the variational equations integrated alongside the step,
//! through every impact and mode switch with its saltation matrix
//! ([`hybrid_ode::Variational`]), then through the relabelling (linear); or by
//! central differences of the map ([`hybrid_ode::limit::fd_jacobian`]). The tests
//! check one against the other.

use crate::cycles::map::section::{
    STANCE_SPOKE, SectionPoint, canonical, canonical_jacobian, new_foot, source,
};
use crate::options::{LabelOptions, Method, Options};
use crate::outcome::{ContactFractions, FailureDetail, Label, MAX_PERIOD, StepShares};
use crate::params::{Params, Physical};
use crate::plant::initial::initial_state;
use crate::plant::rtw::{AtState, Rtw, Transition};
use crate::plant::slots::{self, DISSIPATED, FRICTION, N, X};
use hybrid_ode::limit;
use hybrid_ode::{Dense, EndReason, EngineOptions, Flow, Observer, StepEnd, Variational, run};
use nalgebra::DMatrix;

/// Which touchdowns cross the map's section, as its settings
/// ([`CycleOptions::section`]) name it.
pub use crate::cycles::map::section::Section;

/// Dimension of the RTW state with its sensitivity.
const M: usize = N + N * N;

/// The RTW with its sensitivity, over one step.
type Sensitivity = Variational<Rtw, StepLog, N>;

/// One application of the map.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Step {
    /// Where it lands (canonical).
    pub to: SectionPoint,
    /// Step time (s).
    pub time: f64,
    /// Seconds in each contact state (0…3 rods on the ground) during the step.
    pub state_time: [f64; 4],
    /// Downhill advance of the landing foot (m).
    pub advance: f64,
}

impl Step {
    /// The gait label of `steps` together (docs/model.md §5).
    pub fn label(steps: &[Step], labels: &LabelOptions) -> Label {
        let shares = StepShares::of_steps(steps.iter().map(|s| &s.state_time), labels);
        Label::of_gait(&Step::fractions(steps), &shares, labels)
    }

    /// Contact-state fractions of `steps` together.
    pub(crate) fn fractions(steps: &[Step]) -> ContactFractions {
        let mut t = [0.0; 4];
        for s in steps {
            for (a, b) in t.iter_mut().zip(s.state_time) {
                *a += b;
            }
        }
        let total: f64 = t.iter().sum::<f64>().max(f64::MIN_POSITIVE);
        ContactFractions {
            nlsp: t[0] / total,
            slsp: t[1] / total,
            dlsp: t[2] / total,
            tlsp: t[3] / total,
        }
    }
}

/// Why a step did not reach the section.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum StepError {
    /// The run failed (a rod lay down, the centre of mass sank).
    #[error("the run failed: {}", .0.as_str())]
    Failure(FailureDetail),
    /// No new foot landed within the step horizon.
    #[error("no new foot landed within the step horizon")]
    NoNewFoot,
    /// The landing foot did not stay on the ground.
    #[error("the landing foot did not stay on the ground")]
    LandingFootLeft,
    /// The integration ended otherwise (step underflow, work budget, …).
    #[error("the integration ended: {0:?}")]
    Numerical(EndReason),
}

/// Watches the RTW between two section crossings: stops where a new foot
/// lands and stays ([`new_foot`], from the canonical stance a+), and times
/// the contact states on the way.
#[derive(Clone, Debug, Default)]
struct StepLog {
    section: Section,
    landed: Option<usize>,
    state_time: [f64; 4],
    failure: Option<FailureDetail>,
}

impl Observer<N, Rtw> for StepLog {
    fn on_transition(&mut self, rtw: &Rtw, _t: f64, _y: &[f64; N], tr: &Transition) -> Flow {
        match *tr {
            Transition::Touchdown { rod, tip, .. } => {
                match new_foot(STANCE_SPOKE, &rtw.modes(), rod, tip, self.section) {
                    Some(j) => {
                        self.landed = Some(j);
                        Flow::Stop
                    }
                    None => Flow::Continue,
                }
            }
            Transition::ModeChange { .. } => Flow::Continue,
            Transition::Failure(detail) => {
                self.failure = Some(detail);
                Flow::Stop
            }
        }
    }

    fn on_step(&mut self, rtw: &Rtw, dense: &Dense<N>, _: StepEnd<'_, AtState>) -> Flow {
        // A study stopped from outside (`cancellable`) ends its step maps at
        // their next step too, as it ends its plain runs: a continuation is
        // thousands of them.
        if crate::cancel::requested() {
            return Flow::Stop;
        }
        self.state_time[rtw.contact_state()] += dense.t1 - dense.t0;
        Flow::Continue
    }

    fn reads_interior(&self, _: &Rtw, _t0: f64, _t1: f64) -> bool {
        false
    }
}

/// A step's [`StepLog`] and another observer, both told everything.
struct Watched<'a, O> {
    log: StepLog,
    extra: &'a mut O,
}

impl<O: Observer<N, Rtw>> Observer<N, Rtw> for Watched<'_, O> {
    fn on_transition(&mut self, rtw: &Rtw, t: f64, y: &[f64; N], tr: &Transition) -> Flow {
        let extra = self.extra.on_transition(rtw, t, y, tr);
        match self.log.on_transition(rtw, t, y, tr) {
            Flow::Stop => Flow::Stop,
            Flow::Continue => extra,
        }
    }

    fn on_step(&mut self, rtw: &Rtw, dense: &Dense<N>, end: StepEnd<'_, AtState>) -> Flow {
        let extra = self.extra.on_step(rtw, dense, end);
        match self.log.on_step(rtw, dense, end) {
            Flow::Stop => Flow::Stop,
            Flow::Continue => extra,
        }
    }

    fn reads_interior(&self, rtw: &Rtw, t0: f64, t1: f64) -> bool {
        self.log.reads_interior(rtw, t0, t1) || self.extra.reads_interior(rtw, t0, t1)
    }
}

/// Settings of the limit-cycle analysis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CycleOptions {
    /// Integrator of the map (tighter than a scan's: the fixed point and its
    /// multipliers are only as good as the map).
    pub method: Method,
    /// Relative tolerance of the map's integration.
    pub rtol: f64,
    /// Absolute tolerance of the map's integration.
    pub atol: f64,
    /// Steps iterated from the start before looking for a period.
    pub settle_steps: usize,
    /// Longest period looked for.
    pub max_period: usize,
    /// A period is recognised when `P^n(z)` returns within this scaled distance.
    pub period_tol: f64,
    /// Newton stops when the scaled residual `|Pⁿ(z) − z|` is below this.
    pub newton_tol: f64,
    /// Newton's iteration cap.
    pub newton_max_iter: u32,
    /// Longest step (s) before the map gives up ([`StepError::NoNewFoot`]).
    pub step_horizon: f64,
    /// How Newton gets the map's Jacobian.
    pub jacobian: Jacobian,
    /// Which touchdowns cross the section ([`Section`]).
    pub section: Section,
}

/// How the step map's Jacobian is computed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Jacobian {
    /// The variational equations with saltation (about 110 steps' work per
    /// step at Fig. 7(a): the sensitivities share the state's error control).
    Variational,
    /// Central differences of the map with steps `rel · scale` (2 steps per
    /// coordinate: about 25 steps' work at Fig. 7(a)). The tests check it
    /// against the variational Jacobian to 6 digits at `rel` = 1e-5 and 1e-6.
    Differences {
        /// Difference step, relative to each coordinate's scale.
        rel: f64,
    },
}

impl Default for CycleOptions {
    fn default() -> Self {
        Self {
            method: Method::Dop853,
            rtol: 1e-11,
            atol: 1e-13,
            settle_steps: 60,
            max_period: MAX_PERIOD,
            period_tol: 1e-4,
            newton_tol: 1e-9,
            newton_max_iter: 12,
            step_horizon: 5.0,
            jacobian: Jacobian::Variational,
            section: Section::Stays,
        }
    }
}

/// The RTW's step map for one parameter set and model.
#[derive(Clone, Debug)]
pub struct StepMap {
    /// The RTW's constants (its modes are set from each section point).
    rtw: Rtw,
    engine: EngineOptions,
    horizon: f64,
    section: Section,
    /// Per-slot scale: positions L, angles 1, speeds sqrt(g L), rates
    /// sqrt(g / L), energies m g L.
    slot_scale: [f64; N],
}

impl StepMap {
    /// # Panics
    /// If `params` or `options` are invalid (call their `validate` first).
    pub fn new(params: &Params, options: &Options, cycle: &CycleOptions) -> Self {
        if let Err(e) = params.validate().and_then(|_| options.validate()) {
            panic!("StepMap: {e}");
        }
        let phys = Physical::new(params, options.normalization, options.g);
        let rtw = Rtw::new(&phys, options);
        let engine = EngineOptions {
            method: cycle.method,
            rtol: cycle.rtol,
            atol: cycle.atol,
            ..options.engine()
        };
        let l = phys.length;
        let g = phys.g;
        let unit = [l, l, 1.0, (g * l).sqrt(), (g * l).sqrt(), (g / l).sqrt()];
        let mut slot_scale = [0.0; N];
        for i in 0..3 {
            slots::rod_mut(&mut slot_scale, i).copy_from_slice(&unit);
        }
        slot_scale[DISSIPATED] = phys.m * g * l;
        slot_scale[FRICTION] = phys.m * g * l;
        Self {
            rtw,
            engine,
            horizon: cycle.step_horizon,
            section: cycle.section,
            slot_scale,
        }
    }

    /// Scale of each of `p`'s coordinates (for residuals and difference steps).
    pub fn coord_scale(&self, p: &SectionPoint) -> Vec<f64> {
        p.coordinate_slots()
            .iter()
            .map(|&s| self.slot_scale[s])
            .collect()
    }

    /// The first section crossing of a run from `options`' initial state
    /// (its stance foot, a+, is the front foot).
    pub fn first(&self, options: &Options) -> Result<Step, StepError> {
        let mut rtw = self.rtw.clone();
        let (y, _) = initial_state(&mut rtw, options, &mut Default::default())
            .map_err(StepError::Failure)?;
        self.run_step(rtw, y, &mut ())
    }

    /// One step from `p`.
    pub fn step(&self, p: &SectionPoint) -> Result<Step, StepError> {
        self.step_watched(p, &mut ())
    }

    /// One step from `p` with `extra` watching it too (the events and guard
    /// minima of [`crate::cycles::branches::nonsmooth`]).
    pub(crate) fn step_watched<O: Observer<N, Rtw>>(
        &self,
        p: &SectionPoint,
        extra: &mut O,
    ) -> Result<Step, StepError> {
        let mut rtw = self.rtw.clone();
        rtw.enter(p.modes, &p.y);
        self.run_step(rtw, p.y, extra)
    }

    /// The map's system at `p` (in its modes) and integrator settings: for a
    /// run of the full simulation from a section point.
    pub(crate) fn plant_at(&self, p: &SectionPoint) -> (Rtw, EngineOptions) {
        let mut rtw = self.rtw.clone();
        rtw.enter(p.modes, &p.y);
        (rtw, self.engine)
    }

    /// Longest step (s) before the map gives up.
    pub(crate) fn horizon(&self) -> f64 {
        self.horizon
    }

    /// The units of the map's lengths and times: `L` (m) and `sqrt(L/g)` (s).
    pub(crate) fn units(&self) -> (f64, f64) {
        let l = self.slot_scale[X];
        (l, 1.0 / self.slot_scale[slots::OMEGA])
    }

    fn run_step<O: Observer<N, Rtw>>(
        &self,
        mut rtw: Rtw,
        mut y: [f64; N],
        extra: &mut O,
    ) -> Result<Step, StepError> {
        let mut both = Watched {
            log: StepLog {
                section: self.section,
                ..StepLog::default()
            },
            extra,
        };
        let end = run(&mut rtw, &mut both, 0.0, &mut y, self.horizon, &self.engine);
        let j = finish(&both.log, end.reason)?;
        let to = canonical(&rtw.modes, &y, j, self.section).ok_or(StepError::LandingFootLeft)?;
        Ok(Step {
            to,
            time: end.t,
            state_time: both.log.state_time,
            advance: y[slots::at(source(j, 0).0, X)],
        })
    }

    /// One step from `p` and the map's Jacobian `∂z'/∂z` there, by the
    /// variational equations. The step's `state_time` is not gathered (zero).
    pub(crate) fn step_with_jacobian(
        &self,
        p: &SectionPoint,
    ) -> Result<(Step, DMatrix<f64>), StepError> {
        let mut rtw = self.rtw.clone();
        rtw.enter(p.modes, &p.y);
        let log = StepLog {
            section: self.section,
            ..StepLog::default()
        };
        let mut var = Variational::new(rtw, log, self.slot_scale);
        let mut z: [f64; M] = Sensitivity::initial(&p.y);
        let end = var.run(0.0, &mut z, self.horizon, &self.engine);
        let j = finish(&var.observer, end.reason)?;
        let y = Sensitivity::state(&z);
        let to =
            canonical(&var.sys.modes, &y, j, self.section).ok_or(StepError::LandingFootLeft)?;
        let c = canonical_jacobian(j);
        let (rows, cols) = (to.coordinate_slots(), p.coordinate_slots());
        let jac = DMatrix::from_fn(rows.len(), cols.len(), |r, k| {
            (0..N)
                .map(|m| c[rows[r]][m] * Sensitivity::sensitivity(&z, m, cols[k]))
                .sum()
        });
        Ok((
            Step {
                to,
                time: end.t,
                state_time: [0.0; 4],
                advance: y[slots::at(source(j, 0).0, X)],
            },
            jac,
        ))
    }

    /// The map's Jacobian at `p` by central differences of the map, with
    /// steps `rel · scale` in each coordinate. `None` if a perturbed step
    /// fails or lands in another mode pattern.
    #[cfg(test)]
    pub(crate) fn fd_jacobian(&self, p: &SectionPoint, rel: f64) -> Option<DMatrix<f64>> {
        self.step_with_fd_jacobian(p, rel).map(|(_, j)| j)
    }

    /// The step from `p` and [`fd_jacobian`](Self::fd_jacobian) there: the
    /// unperturbed step, whose modes the perturbed ones must land in, is
    /// taken once for both.
    fn step_with_fd_jacobian(&self, p: &SectionPoint, rel: f64) -> Option<(Step, DMatrix<f64>)> {
        let z = p.coords();
        let centre = self.step(p).ok()?;
        let step: Vec<f64> = self.coord_scale(p).iter().map(|s| rel * s).collect();
        let j = limit::fd_jacobian(&z, &step, |zz| {
            let s = self.step(&p.with_coords(zz)).ok()?;
            (s.to.modes == centre.to.modes).then(|| s.to.coords())
        })?;
        Some((centre, j))
    }
}

/// The landing spoke of a finished step run, or why there is none.
fn finish(run: &StepLog, reason: EndReason) -> Result<usize, StepError> {
    if let Some(detail) = run.failure {
        return Err(StepError::Failure(detail));
    }
    match (reason, run.landed) {
        (EndReason::Stopped, Some(j)) => Ok(j),
        (EndReason::TimeUp, _) => Err(StepError::NoNewFoot),
        (reason, _) => Err(StepError::Numerical(reason)),
    }
}

impl StepMap {
    /// `n` steps from `p`, or the error of the first step that fails. The
    /// mode pattern at the end is not checked: it may differ from `p`'s.
    pub fn iterate(&self, p: &SectionPoint, n: usize) -> Result<Vec<Step>, StepError> {
        // Grown as the steps come (n may be a user's 10⁷ settling steps, most
        // runs fail long before): no up-front allocation sized by the caller.
        let mut steps = Vec::with_capacity(n.min(1024));
        let mut q = *p;
        for _ in 0..n {
            let s = self.step(&q)?;
            q = s.to;
            steps.push(s);
        }
        Ok(steps)
    }

    /// `Pⁿ` at `p` and its Jacobian (the chain rule over the `n` steps, each
    /// by `method`); `None` if a step fails or the orbit does not come back to
    /// `p`'s mode pattern.
    pub(crate) fn power_with_jacobian(
        &self,
        p: &SectionPoint,
        n: usize,
        method: Jacobian,
    ) -> Option<(SectionPoint, DMatrix<f64>)> {
        let mut q = *p;
        let d = p.coordinate_slots().len();
        let mut jac = DMatrix::<f64>::identity(d, d);
        for _ in 0..n {
            let (to, j) = match method {
                Jacobian::Variational => {
                    let (s, j) = self.step_with_jacobian(&q).ok()?;
                    (s.to, j)
                }
                Jacobian::Differences { rel } => {
                    let (s, j) = self.step_with_fd_jacobian(&q, rel)?;
                    (s.to, j)
                }
            };
            if j.ncols() != jac.nrows() {
                return None;
            }
            jac = j * jac;
            q = to;
        }
        (q.modes == p.modes).then_some((q, jac))
    }

    /// The smallest period `n ≤ max_period` of the sequence of section
    /// points `hist` (the latest last): its last point returns within `tol`
    /// (scaled) to the one `n` before, in the same mode pattern, and so do the
    /// `n` points before it.
    pub fn period_of(&self, hist: &[SectionPoint], max_period: usize, tol: f64) -> Option<usize> {
        let last = hist.len().checked_sub(1)?;
        (1..=max_period).find(|&n| {
            (0..n).all(|back| {
                let (Some(a), Some(b)) = (last.checked_sub(back), last.checked_sub(back + n))
                else {
                    return false;
                };
                let (p, q) = (&hist[a], &hist[b]);
                p.modes == q.modes
                    && limit::scaled_max(&p.coords(), &q.coords(), &self.coord_scale(p)) <= tol
            })
        })
    }
}
