//! The limit cycles of the RTW's step map ([`crate::cycles::map::stepmap`]):
//! the period recognised on the section points, then Newton on `Pⁿ(z) = z`
//! and the Floquet multipliers at the solution; and the limit cycle a
//! finished run settled into (a scan's `period`, `floquet_max` and
//! `cycle_residual`).

use crate::cycles::map::section::{SectionLog, SectionPoint};
use crate::cycles::map::stepmap::{CycleOptions, Jacobian, Step, StepError, StepMap};
use crate::options::{LabelOptions, Options};
use crate::outcome::{CycleSummary, Label};
use crate::params::Params;
use hybrid_ode::limit::{self, FixedPoint, NewtonError};
use nalgebra::Complex;

/// Scaled distance under which a simulation's section points count as a
/// period (a scan's run is integrated at a loose tolerance; Newton then
/// refines the point at [`CycleOptions`]' tolerance).
pub const RUN_PERIOD_TOL: f64 = 1e-3;

/// The limit cycle a finished run settled into: its period recognised on the
/// run's latest section crossings, then Newton on `Pⁿ(z) = z` from the last
/// one. `None` when no period shows or Newton fails.
pub fn cycle_of_run(params: &Params, options: &Options, log: &SectionLog) -> Option<CycleSummary> {
    let cycle = run_cycle_options();
    let map = StepMap::new(params, options, &cycle);
    let lc = map.cycle_of_crossings(&log.latest(), &cycle)?;
    Some(CycleSummary {
        period: lc.period as u32,
        floquet_max: lc.floquet_max(),
        residual: lc.fixed_point.residual,
    })
}

/// Difference step of the step map's Jacobian in a finished run's analysis
/// (the Floquet column, and the GSN's `A` and `C`), relative to each
/// coordinate's scale: 1e-4, not 1e-6, because what limits the Jacobian is
/// the perturbed steps' own error divided by the step. At 1e-6 the largest
/// multiplier moved by up to 2.3e-3, and a skip's GSN by up to 2.5 %, when
/// the orbit moved by 1e-9 of its scale
/// (`tests::limit_cycle::the_floquet_column_does_not_move_with_the_orbit`,
/// `gsn::tests::the_gsn_does_not_move_with_the_orbit_within_its_tolerance`).
pub(crate) const DIFFERENCE_REL: f64 = 1e-4;

/// The settings of the limit-cycle analysis of a finished run.
pub(crate) fn run_cycle_options() -> CycleOptions {
    // Differences: 4× cheaper than the variational equations here.
    CycleOptions {
        jacobian: Jacobian::Differences {
            rel: DIFFERENCE_REL,
        },
        ..CycleOptions::default()
    }
}

impl StepMap {
    /// The limit cycle of a run's section crossings `hist` (oldest first):
    /// the period recognised on them ([`RUN_PERIOD_TOL`]), then Newton on
    /// `Pⁿ(z) = z` from the last one. `None` when no period shows or Newton
    /// fails.
    pub(crate) fn cycle_of_crossings(
        &self,
        hist: &[SectionPoint],
        cycle: &CycleOptions,
    ) -> Option<LimitCycle> {
        let n = self.period_of(hist, cycle.max_period, RUN_PERIOD_TOL)?;
        self.solve(hist.last()?, n, cycle).ok()
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

/// Why no limit cycle was found. Its message holds its cause; it hands on
/// no `source` (a chain printer would say the cause twice).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CycleError {
    /// A step of the map failed.
    #[error("a step failed: {0}")]
    Step(StepError),
    /// No period up to this one showed after the settling steps.
    #[error("no period ≤ {0} on the step map after the settling steps")]
    NoPeriod(usize),
    /// Newton did not converge.
    #[error("Newton: {0}")]
    Newton(NewtonError),
}

impl From<StepError> for CycleError {
    fn from(e: StepError) -> Self {
        Self::Step(e)
    }
}

impl From<NewtonError> for CycleError {
    fn from(e: NewtonError) -> Self {
        Self::Newton(e)
    }
}

impl StepMap {
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
