//! The sweep: at each value, in order, the step map continued from the
//! previous value's last section point, steps recorded after transients,
//! their period, and the limit cycle solved for its multipliers.

use anyhow::{Result, bail};
use hybrid_ode::limit;
use rtw_engine::config::axis::linspace;
use rtw_engine::config::params::SweepParam;
use rtw_engine::config::validate_options;
use rtw_engine::scan::Run;
use rtw_model::cycles::{
    CycleError, CycleOptions, LimitCycle, SectionPoint, Step, StepError, StepMap,
};
use rtw_model::{Label, Options, Params};
use std::time::Instant;

/// A sweep: which parameter, its values in order, the base point and model,
/// and how many steps to settle and to record at each value.
#[derive(Clone, Debug)]
pub struct Sweep {
    pub(crate) param: SweepParam,
    pub(crate) values: Vec<f64>,
    pub(crate) base: Params,
    pub(crate) options: Options,
    pub(crate) transient: usize,
    pub(crate) record: usize,
    pub(crate) cycle: CycleOptions,
}

/// Most values of a sweep: its rows are held in memory until written.
pub(crate) const MAX_POINTS: usize = 1_000_000;
/// Most recorded steps per value (periods up to 12 are detected).
pub(crate) const MAX_RECORD: usize = 10_000;
/// Most transient steps per value.
pub(crate) const MAX_TRANSIENT: usize = 10_000_000;

impl Sweep {
    /// `points` values from `from` to `to` (inclusive, either direction),
    /// checked: both ends valid for the parameter, `points ≥ 2`, `record ≥ 2`
    /// (a period-1 gait needs two section points to be recognised).
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        param: SweepParam,
        from: f64,
        to: f64,
        points: usize,
        base: Params,
        options: Options,
        transient: usize,
        record: usize,
    ) -> Result<Self> {
        if let Err(e) = base.validate() {
            bail!(
                "--{}: {} is invalid: must be {}",
                e.field,
                rtw_model::Num(e.value),
                e.range
            );
        }
        validate_options(&options, "simulation")?;
        param.check(&base, &options, from, "--from")?;
        param.check(&base, &options, to, "--to")?;
        if !(2..=MAX_POINTS).contains(&points) {
            bail!(
                "--points: {points} is invalid: must be an integer >= 2 and at most {MAX_POINTS}"
            );
        }
        if !(2..=MAX_RECORD).contains(&record) {
            bail!(
                "--record: {record} is invalid: must be an integer >= 2 and at most {MAX_RECORD}"
            );
        }
        if transient > MAX_TRANSIENT {
            bail!("--transient: {transient} is invalid: must be at most {MAX_TRANSIENT}");
        }
        Ok(Self {
            param,
            values: linspace(from, to, points as u64),
            base,
            options,
            transient,
            record,
            cycle: CycleOptions::default(),
        })
    }
}

/// One parameter value of a sweep.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct PointRow {
    pub(crate) value: f64,
    pub(crate) label: PointLabel,
    /// Period of the solved cycle: the period of the recorded section points,
    /// or a divisor of it when the fixed point found has a shorter one
    /// (`None`: no period ≤ the longest looked for, e.g. quasi-periodic or
    /// chaotic iterates; or a failure).
    pub(crate) period: Option<usize>,
    /// Largest Floquet multiplier modulus of the solved cycle.
    pub(crate) floquet_max: Option<f64>,
    /// The largest multiplier itself (its sign and phase tell the type of a
    /// bifurcation: −1 period doubling, +1 fold, a complex pair Neimark–Sacker).
    pub(crate) mu_re: Option<f64>,
    pub(crate) mu_im: Option<f64>,
    pub(crate) stable: Option<bool>,
    /// The map failed from the continued point and this value started again
    /// from the initial state.
    pub(crate) restarted: bool,
    /// Newton's scaled residual `|Pⁿ(z) − z|` at the fixed point.
    pub(crate) residual: Option<f64>,
    pub(crate) newton_iterations: Option<u32>,
    /// Why Newton found no fixed point although the iterates were periodic.
    pub(crate) newton_error: Option<String>,
    /// Why the step map failed (then `label` is collapse, stall, diverged or failure).
    pub(crate) failure: Option<String>,
    pub(crate) wall_time_s: f64,
}

impl PointRow {
    /// A row with its label only (no period, cycle or failure yet).
    fn new(value: f64, label: PointLabel) -> Self {
        Self {
            value,
            label,
            period: None,
            floquet_max: None,
            mu_re: None,
            mu_im: None,
            stable: None,
            restarted: false,
            residual: None,
            newton_iterations: None,
            newton_error: None,
            failure: None,
            wall_time_s: 0.0,
        }
    }
}

/// One recorded step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct StepRow {
    pub(crate) value: f64,
    /// Index among the recorded steps (0 … record − 1).
    pub(crate) k: usize,
    /// Post-impact angular velocity of the new stance rod (rad/s).
    pub(crate) omega: f64,
    pub(crate) step_time: f64,
    /// Downhill advance of the landing foot (m).
    pub(crate) advance: f64,
    pub(crate) label: PointLabel,
}

/// The label of a value: a gait or a run's failure label (the scan's
/// [`Label`]), or `failure` when the step map itself stopped (no new foot
/// within the step horizon, or the landing foot left at once): the map cannot
/// say whether the star stopped (a stall) or went on in a way that has no
/// step on its section.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum PointLabel {
    Outcome(Label),
    Failure,
}

/// The values of the `label` dictionary column, in key order.
pub(crate) const LABELS: [&str; 7] = [
    "skip", "walk", "crawl", "collapse", "stall", "diverged", "failure",
];

impl PointLabel {
    pub(crate) fn as_str(self) -> &'static str {
        match self {
            Self::Outcome(l) => l.as_str(),
            Self::Failure => "failure",
        }
    }

    /// Position in [`LABELS`]: the key in the `label` dictionary column.
    pub(crate) fn index(self) -> usize {
        LABELS
            .iter()
            .position(|l| *l == self.as_str())
            .expect("every label is in LABELS")
    }
}

/// The label of a failed step: the scan's label of a run's failure, a
/// numerical end as `diverged`, the map's own stops as `failure`.
pub(crate) fn failure_label(e: &StepError) -> PointLabel {
    match e {
        StepError::Failure(detail) => PointLabel::Outcome(detail.label()),
        StepError::Numerical(_) => PointLabel::Outcome(Label::Diverged),
        StepError::NoNewFoot | StepError::LandingFootLeft => PointLabel::Failure,
    }
}

/// `transient` then `record` steps from `start`; the recorded ones.
fn settle_and_record(
    map: &StepMap,
    start: &SectionPoint,
    sweep: &Sweep,
) -> Result<Vec<Step>, StepError> {
    let settled = match sweep.transient {
        0 => *start,
        n => map.iterate(start, n)?.last().expect("n > 0").to,
    };
    map.iterate(&settled, sweep.record)
}

/// Newton on `Pⁿ` from `start`, then on `Pᵈ` if the fixed point found has a
/// shorter period `d | n`: slowly converging iterates near a period doubling
/// look period-2 to [`StepMap::period_of`], while Newton on `P²` may land on
/// the period-1 orbit (a fixed point of `P²` too), whose own multipliers are
/// the ones that tell the bifurcation.
fn solve_minimal(
    map: &StepMap,
    start: &SectionPoint,
    n: usize,
    cycle: &CycleOptions,
) -> Result<LimitCycle, CycleError> {
    let lc = map.solve(start, n, cycle)?;
    let p = &lc.orbit[0];
    let scale = map.coord_scale(p);
    let shorter = (1..n).filter(|d| n.is_multiple_of(*d)).find(|&d| {
        let q = &lc.orbit[d];
        q.modes == p.modes
            && limit::scaled_max(&q.coords(), &p.coords(), &scale) <= cycle.period_tol
    });
    match shorter {
        Some(d) => map.solve(p, d, cycle),
        None => Ok(lc),
    }
}

/// The analysis at one value from the recorded steps: period, cycle, label.
fn analyse(
    map: &StepMap,
    sweep: &Sweep,
    options: &Options,
    value: f64,
    steps: &[Step],
) -> PointRow {
    let hist: Vec<SectionPoint> = steps.iter().map(|s| s.to).collect();
    let max_period = sweep.cycle.max_period.min(hist.len() / 2);
    let period = map.period_of(&hist, max_period, sweep.cycle.period_tol);
    let label = Step::label(steps, &options.labels);
    let mut row = PointRow {
        period,
        ..PointRow::new(value, PointLabel::Outcome(label))
    };
    if let Some(n) = period {
        match solve_minimal(map, hist.last().expect("record >= 2"), n, &sweep.cycle) {
            Ok(lc) => {
                row.period = Some(lc.period);
                row.floquet_max = Some(lc.floquet_max());
                // `multipliers` is sorted by modulus, largest first.
                row.mu_re = lc.multipliers.first().map(|m| m.re);
                row.mu_im = lc.multipliers.first().map(|m| m.im);
                row.stable = Some(lc.is_stable());
                row.residual = Some(lc.fixed_point.residual);
                row.newton_iterations = Some(lc.fixed_point.iterations);
            }
            Err(e) => row.newton_error = Some(e.to_string()),
        }
    }
    row
}

/// The result of one value: its row, its recorded steps, and the section
/// point the next value continues from (`None` after a failure).
struct PointResult {
    row: PointRow,
    steps: Vec<Step>,
    next: Option<SectionPoint>,
}

/// One value of the sweep, continued from `from` (or from the initial state).
fn sweep_point(sweep: &Sweep, value: f64, from: Option<SectionPoint>) -> PointResult {
    let t0 = Instant::now();
    let (params, options) = sweep
        .param
        .at(&sweep.base, &sweep.options, value)
        .expect("the sweep's ends were checked, and the values lie between them");
    let map = StepMap::new(&params, &options, &sweep.cycle);
    let fresh = || -> Result<Vec<Step>, StepError> {
        let first = map.first(&options)?;
        settle_and_record(&map, &first.to, sweep)
    };
    let (recorded, restarted) = match from {
        Some(p) => match settle_and_record(&map, &p, sweep) {
            Ok(steps) => (Ok(steps), false),
            Err(_) => (fresh(), true),
        },
        None => (fresh(), false),
    };
    let (mut row, steps, next) = match recorded {
        Ok(steps) => {
            let row = analyse(&map, sweep, &options, value, &steps);
            let next = steps.last().map(|s| s.to);
            (row, steps, next)
        }
        Err(e) => {
            let row = PointRow {
                failure: Some(e.to_string()),
                ..PointRow::new(value, failure_label(&e))
            };
            (row, Vec::new(), None)
        }
    };
    row.restarted = restarted;
    row.wall_time_s = t0.elapsed().as_secs_f64();
    PointResult { row, steps, next }
}

/// The whole sweep, in order (continuation is sequential), calling
/// `progress(i, row)` after each value; [`Stopped`] as soon as `run`'s stop
/// flag is set (the value in flight ends at its model run's next step).
///
/// [`Stopped`]: rtw_engine::scan::workers::Stopped
pub(crate) fn run_sweep(
    sweep: &Sweep,
    run: &Run,
    mut progress: impl FnMut(usize, &PointRow),
) -> Result<(Vec<PointRow>, Vec<StepRow>)> {
    let mut points = Vec::with_capacity(sweep.values.len());
    let mut step_rows = Vec::new();
    let mut carry = None;
    for (i, &value) in sweep.values.iter().enumerate() {
        let r = run.cancellable(|| sweep_point(sweep, value, carry))?;
        step_rows.extend(r.steps.iter().enumerate().map(|(k, s)| StepRow {
            value,
            k,
            omega: s.to.omega(),
            step_time: s.time,
            advance: s.advance,
            label: r.row.label,
        }));
        progress(i, &r.row);
        points.push(r.row);
        carry = r.next;
    }
    Ok((points, step_rows))
}

#[cfg(test)]
mod tests {
    use super::*;
    use rtw_engine::scan::workers::Stopped;
    use std::sync::atomic::AtomicBool;

    #[test]
    fn bad_bounds_name_the_flag_and_the_range() {
        let (p, o) = (Params::fig7a(), Options::default());
        let new = |param: &str, from: f64, to: f64, points: usize| {
            Sweep::new(
                SweepParam::parse(param).unwrap(),
                from,
                to,
                points,
                p,
                o,
                10,
                24,
            )
        };
        let e = new("phi", 0.1, 2.0, 5).unwrap_err().to_string();
        assert!(
            e.starts_with("--to: 2 is invalid for --param phi: phi must be"),
            "{e}"
        );
        let e = new("s", -0.1, 0.5, 5).unwrap_err().to_string();
        assert!(
            e.starts_with(
                "--from: -0.1 is invalid for --param s: strings.rest_length_ratio must be"
            ),
            "{e}"
        );
        let e = new("alpha", 0.1, 0.2, 1).unwrap_err().to_string();
        assert!(
            e.contains("--points: 1 is invalid: must be an integer >= 2"),
            "{e}"
        );
        let s = new("fn", 5.0, 2.0, 4).unwrap();
        assert_eq!(s.values, vec![5.0, 4.0, 3.0, 2.0]);
    }

    /// Continuation: the second value starts from the first value's last
    /// section point, so its rows equal a sweep of that one value started
    /// there by hand (an independent path through the same map calls).
    #[test]
    fn continuation_starts_from_the_previous_last_section_point() {
        let options = Options::default();
        let mut sweep = Sweep::new(
            SweepParam::parse("phi").unwrap(),
            0.15,
            0.16,
            2,
            Params::fig7a(),
            options,
            20,
            6,
        )
        .unwrap();
        sweep.cycle.newton_max_iter = 8;
        let go = AtomicBool::new(false);
        let (points, steps) = run_sweep(&sweep, &Run::silent(&go), |_, _| {}).unwrap();
        assert_eq!(points.len(), 2);
        assert!(!points[0].restarted && !points[1].restarted);
        // By hand: the first value from the initial state ...
        let (p0, o0) = sweep.param.at(&sweep.base, &options, 0.15).unwrap();
        let m0 = StepMap::new(&p0, &o0, &sweep.cycle);
        let first = m0.first(&o0).unwrap();
        let rec0 = settle_and_record(&m0, &first.to, &sweep).unwrap();
        // ... then the second from its last section point.
        let (p1, o1) = sweep.param.at(&sweep.base, &options, 0.16).unwrap();
        let m1 = StepMap::new(&p1, &o1, &sweep.cycle);
        let rec1 = settle_and_record(&m1, &rec0.last().unwrap().to, &sweep).unwrap();
        let omegas = |v: f64| -> Vec<f64> {
            steps
                .iter()
                .filter(|s| s.value == v)
                .map(|s| s.omega)
                .collect()
        };
        assert_eq!(
            omegas(0.15),
            rec0.iter().map(|s| s.to.omega()).collect::<Vec<_>>()
        );
        assert_eq!(
            omegas(0.16),
            rec1.iter().map(|s| s.to.omega()).collect::<Vec<_>>()
        );
        // A fresh start at 0.16 takes a different path (it is not what the
        // sweep did): its recorded steps differ from the continued ones.
        let fresh = settle_and_record(&m1, &m1.first(&o1).unwrap().to, &sweep).unwrap();
        assert_ne!(fresh[0].to.omega(), rec1[0].to.omega());
        // And the analysis is the one of those steps.
        let row = analyse(&m1, &sweep, &o1, 0.16, &rec1);
        assert_eq!(
            (row.period, row.floquet_max),
            (points[1].period, points[1].floquet_max)
        );
    }

    /// A stop flag set after the first value ends the sweep there, with
    /// `Stopped`: the second value's runs end at their next step.
    #[test]
    fn a_stop_flag_ends_the_sweep_with_stopped() {
        let sweep = Sweep::new(
            SweepParam::parse("phi").unwrap(),
            0.15,
            0.16,
            3,
            Params::fig7a(),
            Options::default(),
            20,
            6,
        )
        .unwrap();
        let stop = AtomicBool::new(false);
        let mut seen = 0;
        let t0 = std::time::Instant::now();
        let e = run_sweep(&sweep, &Run::silent(&stop), |_, _| {
            seen += 1;
            stop.store(true, std::sync::atomic::Ordering::SeqCst);
        })
        .unwrap_err();
        assert!(e.downcast_ref::<Stopped>().is_some(), "{e:#}");
        assert_eq!(seen, 1, "the sweep went on past its stop");
        assert!(t0.elapsed().as_secs() < 60);
    }
}
