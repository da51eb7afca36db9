//! The RTW's step map: a Poincaré section at each touchdown of a new foot,
//! reduced by the star's symmetry, and its Jacobian.
//!
//! **Section.** The state just after the impact of a foot other than the
//! stance foot and the one behind it, when the foot stays on the ground (a
//! touch-and-go, or a foot that lands again after a bounce, is not a step).
//!
//! **Symmetry.** A 60° turn maps the spokes a+ → b+ → c+ → a− → b− → c− → a+
//! ([`SPOKES`]'s order): a relabelling of the rods, where a rod turned by π is
//! the same rod with its tips swapped. The gait is also invariant under a
//! shift along the slope. So every section point is stored *canonically*:
//! rods relabelled so that the landing foot is a+ (spoke `j` of the old labels
//! becomes spoke 0; the old rod of spoke `(i + j) mod 6` becomes rod `i`,
//! turned by π when that spoke is a − tip), shifted so that the landing foot
//! is at `x = 0`, angles wrapped to `(−π, π]`, dissipated energies zeroed.
//! A steady walk is then a fixed point of the map; the same physical posture
//! one step later has the same canonical coordinates.
//!
//! **Coordinates.** The state's slots are minimal coordinates in each rod's
//! mode ([`crate::contact`]): a sticking rod has (contact x, θ, ω), a sliding
//! one (tip x, θ, tip ẋ, ω), a free one all six. The map's coordinates `z`
//! are those slots of the three rods in the section's modes, without a+'s
//! contact x (zero by the shift). The section's own constraints (the landing
//! foot on the ground, at rest after a sticking impact) are thus built in and
//! the map has no trivial multipliers. A map is smooth only between points of
//! the same *mode pattern* (which rods touch, how); [`StepMap::step`] reports
//! the pattern it lands in, and a fixed point must keep its own.
//!
//! **Jacobian.** By the variational equations integrated alongside the step,
//! through every impact and mode switch with its saltation matrix
//! ([`crate::variational`]), then through the relabelling (linear); or by
//! central differences of the map ([`crate::limit::fd_jacobian`]). The tests
//! check one against the other.

use crate::contact::RodMode;
use crate::geometry::{SPOKES, Tip};
use crate::hybrid::{self, EndReason, EngineOptions, Flow, Guards, HybridSystem};
use crate::initial::initial_state;
use crate::integrate::{Dense, Method};
use crate::limit::{self, FixedPoint, NewtonError};
use crate::options::{LabelOptions, Options};
use crate::outcome::{ContactFractions, FailureDetail, Label};
use crate::params::{Params, Physical};
use crate::rtw::{AtState, DISSIPATED, FRICTION, N, Rtw, Transition};
use crate::variational::Variational;
use nalgebra::{Complex, DMatrix};
use std::f64::consts::PI;

/// Dimension of the RTW state with its sensitivity.
const M: usize = N + N * N;

/// Canonical spoke of the stance foot, and of the foot behind it (c−).
const STANCE_SPOKE: usize = 0;
const BEHIND_SPOKE: usize = 5;

/// A point on the section, in canonical labels (see the module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SectionPoint {
    pub modes: [RodMode; 3],
    pub y: [f64; N],
}

impl SectionPoint {
    /// The state slots that are the map's coordinates in this point's modes.
    pub fn coordinate_slots(&self) -> Vec<usize> {
        let mut slots = Vec::with_capacity(N);
        for (i, mode) in self.modes.iter().enumerate() {
            let own: &[usize] = match mode {
                RodMode::Free => &[0, 1, 2, 3, 4, 5],
                RodMode::Stick { .. } => &[0, 2, 5],
                RodMode::Slide { .. } => &[0, 2, 3, 5],
            };
            // a+'s contact x is zero by the shift.
            let skip = usize::from(i == 0 && *mode != RodMode::Free);
            slots.extend(own[skip..].iter().map(|s| 6 * i + s));
        }
        slots
    }

    /// The map's coordinates of this point.
    pub fn coords(&self) -> Vec<f64> {
        self.coordinate_slots().iter().map(|&s| self.y[s]).collect()
    }

    /// This point with its coordinates replaced by `z` (same modes).
    pub fn with_coords(&self, z: &[f64]) -> SectionPoint {
        let mut p = *self;
        for (&s, &v) in self.coordinate_slots().iter().zip(z) {
            p.y[s] = v;
        }
        p
    }

    /// The landing rod's angular velocity just after the impact.
    pub fn omega(&self) -> f64 {
        self.y[5]
    }
}

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
        let shares = crate::gait::step_shares(steps.iter().map(|s| &s.state_time), labels);
        crate::gait::label(&Step::fractions(steps), &shares, labels)
    }

    /// Contact-state fractions of `steps` together.
    pub fn fractions(steps: &[Step]) -> ContactFractions {
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
    #[error("the run failed: {}", .0.as_str())]
    Failure(FailureDetail),
    #[error("no new foot landed within the step horizon")]
    NoNewFoot,
    #[error("the landing foot did not stay on the ground")]
    LandingFootLeft,
    #[error("the integration ended: {0:?}")]
    Numerical(EndReason),
}

/// The RTW between two section crossings, as a hybrid system.
#[derive(Clone, Debug)]
struct StepRun {
    rtw: Rtw,
    /// The stance foot and the one behind it, in this run's labels: their
    /// touchdowns are not steps.
    stance: (usize, Tip),
    behind: (usize, Tip),
    landed: Option<usize>,
    state_time: [f64; 4],
    failure: Option<FailureDetail>,
}

impl StepRun {
    fn new(rtw: Rtw) -> Self {
        Self {
            rtw,
            stance: SPOKES[STANCE_SPOKE],
            behind: SPOKES[BEHIND_SPOKE],
            landed: None,
            state_time: [0.0; 4],
            failure: None,
        }
    }
}

impl HybridSystem<N> for StepRun {
    type Aux = AtState;

    crate::rtw::delegate_rtw_flow!();

    fn reset(&mut self, _t: f64, y: &mut [f64; N], index: usize) -> Flow {
        match self.rtw.reset(y, index) {
            Transition::Touchdown { rod, tip, .. } => {
                // A touch-and-go (the foot leaves the ground at once) is not
                // a step either: the step ends where the foot stays.
                if (rod, tip) == self.stance
                    || (rod, tip) == self.behind
                    || self.rtw.modes[rod] == RodMode::Free
                {
                    Flow::Continue
                } else {
                    self.landed = SPOKES.iter().position(|&s| s == (rod, tip));
                    Flow::Stop
                }
            }
            Transition::ModeChange { .. } => Flow::Continue,
            Transition::Failure(detail) => {
                self.failure = Some(detail);
                Flow::Stop
            }
        }
    }

    fn reset_replaying(&mut self, t: f64, y: &mut [f64; N], index: usize, nominal: &Self) -> Flow {
        self.rtw.replay = nominal.rtw.last_choice;
        let flow = self.reset(t, y, index);
        self.rtw.replay = None;
        flow
    }

    fn observe(&mut self, dense: &Dense<N>) -> Flow {
        self.state_time[self.rtw.contact_state()] += dense.t1 - dense.t0;
        Flow::Continue
    }

    fn observes_interior(&self) -> bool {
        false
    }
}

/// Old rod of new rod `i` when spoke `j` becomes a+, and whether it is turned by π.
#[inline]
fn source(j: usize, i: usize) -> (usize, bool) {
    let s = (i + j) % 6;
    (s % 3, s >= 3)
}

/// The turned rod's mode: the same contact on its other tip's label.
fn turned(mode: RodMode) -> RodMode {
    match mode {
        RodMode::Free => RodMode::Free,
        RodMode::Stick { tip } => RodMode::Stick { tip: tip.other() },
        RodMode::Slide { tip, dir } => RodMode::Slide {
            tip: tip.other(),
            dir,
        },
    }
}

/// `θ` wrapped to `(−π, π]`.
#[inline]
fn wrap(theta: f64) -> f64 {
    let w = theta.rem_euclid(2.0 * PI);
    if w > PI { w - 2.0 * PI } else { w }
}

/// The canonical section point of the state `y` (in modes `modes`) just after
/// spoke `j` landed; `None` if the landing rod is not on the ground.
fn canonical(modes: &[RodMode; 3], y: &[f64; N], j: usize) -> Option<SectionPoint> {
    let (o0, _) = source(j, 0);
    if modes[o0] == RodMode::Free {
        return None;
    }
    let x0 = y[6 * o0];
    let mut p = SectionPoint {
        modes: [RodMode::Free; 3],
        y: [0.0; N],
    };
    for i in 0..3 {
        let (o, flip) = source(j, i);
        p.y[6 * i..6 * i + 6].copy_from_slice(&y[6 * o..6 * o + 6]);
        p.y[6 * i] -= x0;
        if flip {
            p.y[6 * i + 2] += PI;
        }
        p.y[6 * i + 2] = wrap(p.y[6 * i + 2]);
        p.modes[i] = if flip { turned(modes[o]) } else { modes[o] };
    }
    p.y[DISSIPATED] = 0.0;
    p.y[FRICTION] = 0.0;
    Some(p)
}

/// `∂(canonical y)/∂y` for landing spoke `j`: a permutation of the rods' slots
/// minus the landing foot's x from every rod's x slot (the π turns and the
/// wrapping add constants).
fn canonical_jacobian(j: usize) -> [[f64; N]; N] {
    let mut c = [[0.0; N]; N];
    let (o0, _) = source(j, 0);
    for i in 0..3 {
        let (o, _) = source(j, i);
        for s in 0..6 {
            c[6 * i + s][6 * o + s] += 1.0;
        }
        c[6 * i][6 * o0] -= 1.0;
    }
    c
}

impl SectionPoint {
    /// The canonical section point just after `tip` of `rod` landed, the
    /// state `y` in modes `modes` (the run's labels); `None` if the rod did
    /// not stay on the ground.
    pub fn after_touchdown(
        modes: &[RodMode; 3],
        y: &[f64; N],
        rod: usize,
        tip: Tip,
    ) -> Option<SectionPoint> {
        let j = SPOKES.iter().position(|&s| s == (rod, tip))?;
        canonical(modes, y, j)
    }
}

/// Longest history a [`SectionLog`] keeps: two of the longest periods, and one.
const LOG_LEN: usize = 2 * crate::gait::MAX_PERIOD + 1;

/// The latest section crossings of a simulation, in a fixed ring (no
/// allocation in the run): where the limit-cycle analysis of a run starts.
#[derive(Clone, Debug)]
pub struct SectionLog {
    ring: [SectionPoint; LOG_LEN],
    len: usize,
    /// Spoke of the stance foot, in the run's labels (a+ at the start).
    stance: usize,
}

impl Default for SectionLog {
    fn default() -> Self {
        Self {
            ring: [SectionPoint {
                modes: [RodMode::Free; 3],
                y: [0.0; N],
            }; LOG_LEN],
            len: 0,
            stance: STANCE_SPOKE,
        }
    }
}

impl SectionLog {
    /// Records the touchdown of `tip` of `rod` (state `y` just after it, in
    /// `modes`) if it crosses the section: a new foot that stays down.
    pub fn on_touchdown(&mut self, modes: &[RodMode; 3], y: &[f64; N], rod: usize, tip: Tip) {
        let Some(j) = SPOKES.iter().position(|&s| s == (rod, tip)) else {
            return;
        };
        let behind = (self.stance + BEHIND_SPOKE) % 6;
        if j == self.stance || j == behind {
            return;
        }
        if let Some(p) = canonical(modes, y, j) {
            self.ring[self.len % LOG_LEN] = p;
            self.len += 1;
            self.stance = j;
        }
    }

    /// The recorded crossings, oldest first (at most the ring's length).
    pub fn latest(&self) -> Vec<SectionPoint> {
        let n = self.len.min(LOG_LEN);
        (self.len - n..self.len)
            .map(|k| self.ring[k % LOG_LEN])
            .collect()
    }
}

/// Scaled distance under which a simulation's section points count as a
/// period (a scan's run is integrated at a loose tolerance; Newton then
/// refines the point at [`CycleOptions`]' tolerance).
pub const RUN_PERIOD_TOL: f64 = 1e-3;

/// The limit cycle a finished run settled into: its period recognised on the
/// run's latest section crossings, then Newton on `Pⁿ(z) = z` from the last
/// one. `None` when no period shows or Newton fails.
pub fn cycle_of_run(
    params: &Params,
    options: &Options,
    log: &SectionLog,
) -> Option<crate::outcome::CycleSummary> {
    // Differences: 4× cheaper than the variational equations here, and as
    // good for a scan column (the tests check the two against each other).
    let cycle = CycleOptions {
        jacobian: Jacobian::Differences { rel: 1e-6 },
        ..CycleOptions::default()
    };
    let map = StepMap::new(params, options, &cycle);
    let hist = log.latest();
    let n = map.period_of(&hist, cycle.max_period, RUN_PERIOD_TOL)?;
    let lc = map.solve(hist.last()?, n, &cycle).ok()?;
    Some(crate::outcome::CycleSummary {
        period: n as u32,
        floquet_max: lc.floquet_max(),
        residual: lc.fixed_point.residual,
    })
}

/// Settings of the limit-cycle analysis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CycleOptions {
    /// Integrator of the map (tighter than a scan's: the fixed point and its
    /// multipliers are only as good as the map).
    pub method: Method,
    pub rtol: f64,
    pub atol: f64,
    /// Steps iterated from the start before looking for a period.
    pub settle_steps: usize,
    /// Longest period looked for.
    pub max_period: usize,
    /// A period is recognised when `P^n(z)` returns within this scaled distance.
    pub period_tol: f64,
    /// Newton stops when the scaled residual `|Pⁿ(z) − z|` is below this.
    pub newton_tol: f64,
    pub newton_max_iter: u32,
    /// Longest step (s) before the map gives up ([`StepError::NoNewFoot`]).
    pub step_horizon: f64,
    /// How Newton gets the map's Jacobian.
    pub jacobian: Jacobian,
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
    Differences { rel: f64 },
}

impl Default for CycleOptions {
    fn default() -> Self {
        Self {
            method: Method::Dop853,
            rtol: 1e-11,
            atol: 1e-13,
            settle_steps: 60,
            max_period: crate::gait::MAX_PERIOD,
            period_tol: 1e-4,
            newton_tol: 1e-9,
            newton_max_iter: 12,
            step_horizon: 5.0,
            jacobian: Jacobian::Variational,
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
            slot_scale[6 * i..6 * i + 6].copy_from_slice(&unit);
        }
        slot_scale[DISSIPATED] = phys.m * g * l;
        slot_scale[FRICTION] = phys.m * g * l;
        Self {
            rtw,
            engine,
            horizon: cycle.step_horizon,
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
        self.run_step(rtw, y)
    }

    /// One step from `p`.
    pub fn step(&self, p: &SectionPoint) -> Result<Step, StepError> {
        let mut rtw = self.rtw.clone();
        rtw.modes = p.modes;
        self.run_step(rtw, p.y)
    }

    fn run_step(&self, rtw: Rtw, mut y: [f64; N]) -> Result<Step, StepError> {
        let mut run = StepRun::new(rtw);
        let end = hybrid::run(&mut run, 0.0, &mut y, self.horizon, &self.engine);
        let j = finish(&run, end.reason)?;
        let to = canonical(&run.rtw.modes, &y, j).ok_or(StepError::LandingFootLeft)?;
        Ok(Step {
            to,
            time: end.t,
            state_time: run.state_time,
            advance: y[6 * source(j, 0).0],
        })
    }

    /// One step from `p` and the map's Jacobian `∂z'/∂z` there, by the
    /// variational equations. The step's `state_time` is not gathered (zero).
    pub fn step_with_jacobian(&self, p: &SectionPoint) -> Result<(Step, DMatrix<f64>), StepError> {
        let mut rtw = self.rtw.clone();
        rtw.modes = p.modes;
        let mut var = Variational::new(StepRun::new(rtw), self.slot_scale);
        let mut z: [f64; M] = Variational::<StepRun, N>::initial(&p.y);
        let end = hybrid::run(&mut var, 0.0, &mut z, self.horizon, &self.engine);
        let j = finish(&var.sys, end.reason)?;
        let y = Variational::<StepRun, N>::state(&z);
        let to = canonical(&var.sys.rtw.modes, &y, j).ok_or(StepError::LandingFootLeft)?;
        let c = canonical_jacobian(j);
        let (rows, cols) = (to.coordinate_slots(), p.coordinate_slots());
        let jac = DMatrix::from_fn(rows.len(), cols.len(), |r, k| {
            (0..N)
                .map(|m| c[rows[r]][m] * Variational::<StepRun, N>::sensitivity(&z, m, cols[k]))
                .sum()
        });
        Ok((
            Step {
                to,
                time: end.t,
                state_time: [0.0; 4],
                advance: y[6 * source(j, 0).0],
            },
            jac,
        ))
    }

    /// The map's Jacobian at `p` by central differences of the map, with
    /// steps `rel · scale` in each coordinate. `None` if a perturbed step
    /// fails or lands in another mode pattern.
    pub fn fd_jacobian(&self, p: &SectionPoint, rel: f64) -> Option<DMatrix<f64>> {
        let z = p.coords();
        let to = self.step(p).ok()?.to;
        let step: Vec<f64> = self.coord_scale(p).iter().map(|s| rel * s).collect();
        limit::fd_jacobian(&z, &step, |zz| {
            let s = self.step(&p.with_coords(zz)).ok()?;
            (s.to.modes == to.modes).then(|| s.to.coords())
        })
    }
}

/// The landing spoke of a finished step run, or why there is none.
fn finish(run: &StepRun, reason: EndReason) -> Result<usize, StepError> {
    if let Some(detail) = run.failure {
        return Err(StepError::Failure(detail));
    }
    match (reason, run.landed) {
        (EndReason::Stopped, Some(j)) => Ok(j),
        (EndReason::TimeUp, _) => Err(StepError::NoNewFoot),
        (reason, _) => Err(StepError::Numerical(reason)),
    }
}

/// A periodic gait found on the step map.
#[derive(Clone, Debug)]
pub struct LimitCycle {
    /// Period in steps (1: every step the same).
    pub period: usize,
    /// The orbit's section points, from the fixed point of `Pⁿ` on.
    pub orbit: Vec<SectionPoint>,
    /// The steps along the orbit.
    pub steps: Vec<Step>,
    /// The Newton solve of `Pⁿ(z) = z`.
    pub fixed_point: FixedPoint,
    /// Floquet multipliers of `Pⁿ`, largest modulus first, without the
    /// trivial ones ([`limit::nontrivial_multipliers`]).
    pub multipliers: Vec<Complex<f64>>,
}

impl LimitCycle {
    /// Largest multiplier modulus.
    pub fn floquet_max(&self) -> f64 {
        limit::spectral_radius(&self.multipliers)
    }

    /// Stable when every multiplier lies inside the unit circle.
    pub fn is_stable(&self) -> bool {
        self.floquet_max() < 1.0
    }

    /// The gait label of the orbit's contact fractions and steps (docs/model.md §5).
    pub fn label(&self, labels: &LabelOptions) -> Label {
        Step::label(&self.steps, labels)
    }
}

/// Why no limit cycle was found.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CycleError {
    #[error("a step failed: {0}")]
    Step(#[from] StepError),
    #[error("no period ≤ {0} on the step map after the settling steps")]
    NoPeriod(usize),
    #[error("Newton: {0}")]
    Newton(#[from] NewtonError),
}

impl StepMap {
    /// `n` steps from `p`; `None` if one fails or the mode pattern at the end
    /// differs from `p`'s.
    pub fn iterate(&self, p: &SectionPoint, n: usize) -> Result<Vec<Step>, StepError> {
        let mut steps = Vec::with_capacity(n);
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
    pub fn power_with_jacobian(
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
                    (self.step(&q).ok()?.to, self.fd_jacobian(&q, rel)?)
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

    /// The limit cycle a run from `options`' initial state settles into:
    /// `settle_steps` steps, the period recognised on the section points,
    /// then Newton on `Pⁿ(z) = z` from the last point, with Jacobians by the
    /// variational equations, and the Floquet multipliers at the solution.
    pub fn limit_cycle(
        &self,
        options: &Options,
        cycle: &CycleOptions,
    ) -> Result<LimitCycle, CycleError> {
        let first = self.first(options)?;
        let mut hist = vec![first.to];
        hist.extend(
            self.iterate(&first.to, cycle.settle_steps)?
                .iter()
                .map(|s| s.to),
        );
        let n = self
            .period_of(&hist, cycle.max_period, cycle.period_tol)
            .ok_or(CycleError::NoPeriod(cycle.max_period))?;
        self.solve(hist.last().expect("non-empty"), n, cycle)
    }

    /// Newton on `Pⁿ(z) = z` from `start`, and the multipliers there.
    pub fn solve(
        &self,
        start: &SectionPoint,
        n: usize,
        cycle: &CycleOptions,
    ) -> Result<LimitCycle, CycleError> {
        let scale = self.coord_scale(start);
        let fixed_point = limit::newton(
            &start.coords(),
            &scale,
            cycle.newton_tol,
            cycle.newton_max_iter,
            |z| {
                let (q, j) = self.power_with_jacobian(&start.with_coords(z), n, cycle.jacobian)?;
                Some((q.coords(), j))
            },
        )?;
        let p = start.with_coords(&fixed_point.z);
        let steps = self.iterate(&p, n)?;
        let mut orbit = vec![p];
        orbit.extend(steps.iter().take(n - 1).map(|s| s.to));
        let multipliers = limit::nontrivial_multipliers(&fixed_point.jacobian);
        Ok(LimitCycle {
            period: n,
            orbit,
            steps,
            fixed_point,
            multipliers,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn relabelling_is_a_sixty_degree_turn() {
        // Landing spoke j becomes a+: new rod i is old spoke (i + j) mod 6.
        assert_eq!(source(0, 0), (0, false));
        assert_eq!(source(1, 0), (1, false));
        assert_eq!(source(1, 2), (0, true));
        assert_eq!(source(4, 0), (1, true));
        // Six turns come back to the start: j and j + 6 agree.
        for j in 0..6 {
            for i in 0..3 {
                assert_eq!(source(j, i), source(j + 6, i));
            }
        }
    }

    #[test]
    fn wrap_keeps_angles_in_the_half_open_circle() {
        for &t in &[0.0, 1.0, -1.0, PI, -PI, 3.0 * PI, 7.5, -7.5] {
            let w = wrap(t);
            assert!(w > -PI - 1e-12 && w <= PI + 1e-12, "{t} -> {w}");
            let k = (t - w) / (2.0 * PI);
            assert!((k - k.round()).abs() < 1e-12);
        }
    }
}
