//! One run of the RTW on the hybrid engine: the star set down, the run, and
//! its observer, the `Recorder`, which gathers the statistics of
//! docs/model.md §5 as it goes. `simulate` (simulate.rs) adds the
//! robustness measures on top; the measures (robustness.rs) rerun from a
//! run's end state through [`with_end_state`] and [`run_from`].

use crate::cycles::map::limit_cycle::cycle_of_run;
use crate::cycles::map::section::SectionLog;
use crate::options::Options;
use crate::outcome::{Energy, FailureDetail, Label, Outcome, Stance, TraceSample};
use crate::params::{Params, Physical};
use crate::plant::initial::initial_state;
use crate::plant::rtw::{AtState, Rtw, Transition};
use crate::plant::slots::{DISSIPATED, FRICTION, N};
use crate::run::gait::{GaitStats, Settled};
use hybrid_ode::{Dense, EndReason, Flow, Observer, StepEnd, Work, run};
/// What one run records — gait statistics, energy lost in impacts, the trace,
/// the section crossings — and when it ends early (a stall, a settled gait):
/// the run's observer.
struct Recorder<'a> {
    stats: GaitStats,
    stall_time: f64,
    failure: Option<FailureDetail>,
    /// Largest friction ratio needed while sticking, over the window,
    /// sampled at every accepted step end (never at trial states past an event).
    mu_required: f64,
    /// Energy removed by resets (impacts; also the hair-width projections of
    /// a tip onto the ground and of a re-sticking tip to rest).
    impact_loss: f64,
    trace: Option<&'a mut dyn FnMut(&TraceSample)>,
    trace_dt: f64,
    next_trace: f64,
    /// `Options::stop_when_settled`.
    stop_when_settled: bool,
    /// Largest friction ratio needed since the last touchdown (early stop).
    mu_since_touchdown: f64,
    /// The settled gait, when the run stopped early for it.
    settled: Option<Settled>,
    /// The latest section crossings (`Options::limit_cycle` only).
    sections: Option<Box<SectionLog>>,
    /// Downhill position of the centre of mass and total energy just before
    /// the reset that follows (taken where a step ends at an event).
    before_reset: (f64, f64),
}

impl Recorder<'_> {
    fn sample(&self, rtw: &Rtw, t: f64, y: &[f64; N]) -> TraceSample {
        let rods = rtw.rods(y);
        let (kinetic, gravity_potential, string_potential) = rtw.energy(y);
        TraceSample {
            t,
            pose: std::array::from_fn(|i| [rods[i].c[0], rods[i].c[1], rods[i].theta]),
            vel: std::array::from_fn(|i| [rods[i].v[0], rods[i].v[1], rods[i].omega]),
            contact: std::array::from_fn(|i| rtw.modes[i].code()),
            contact_state: rtw.contact_state() as u8,
            kinetic,
            gravity_potential,
            string_potential,
            damping_loss: y[DISSIPATED],
            friction_loss: y[FRICTION],
            impact_loss: self.impact_loss,
        }
    }

    fn emit(&mut self, rtw: &Rtw, t: f64, y: &[f64; N]) {
        let s = self.sample(rtw, t, y);
        if let Some(trace) = self.trace.as_mut() {
            trace(&s);
        }
    }
}

impl Observer<N, Rtw> for Recorder<'_> {
    fn on_transition(&mut self, rtw: &Rtw, t: f64, y: &[f64; N], tr: &Transition) -> Flow {
        let (com_x, before) = self.before_reset;
        self.impact_loss += before - rtw.total_energy(y);
        let flow = match *tr {
            Transition::Touchdown {
                rod,
                tip,
                omega_after,
            } => {
                self.stats.on_touchdown(t, rod, tip, omega_after);
                if let Some(log) = self.sections.as_mut() {
                    log.on_touchdown(&rtw.modes, y, rod, tip);
                }
                if self.stop_when_settled {
                    let mu = std::mem::take(&mut self.mu_since_touchdown);
                    self.settled = self.stats.mark(t, omega_after, com_x, mu);
                }
                if self.settled.is_some() {
                    Flow::Stop
                } else {
                    Flow::Continue
                }
            }
            Transition::ModeChange { .. } => Flow::Continue,
            Transition::Failure(detail) => {
                self.failure = Some(detail);
                Flow::Stop
            }
        };
        if self.trace.is_some() {
            self.emit(rtw, t, y);
        }
        flow
    }

    fn reads_interior(&self, _: &Rtw, _t0: f64, t1: f64) -> bool {
        // Interior points are read only to sample a trace at `trace_dt` and
        // once, at the window's start: on the steps that reach them.
        (self.trace.is_some() && self.trace_dt > 0.0 && self.next_trace <= t1)
            || (self.stats.window_com_x.is_none() && t1 >= self.stats.window_start)
    }

    fn on_step(&mut self, rtw: &Rtw, dense: &Dense<N>, end: StepEnd<'_, AtState>) -> Flow {
        if crate::cancel::requested() {
            return Flow::Stop;
        }
        match end {
            StepEnd::Step { aux } => {
                self.observe_step(rtw, dense, || rtw.friction_ratio_of(&aux.lambda))
            }
            StepEnd::Event { .. } => {
                // The event state's frames, once for all that is read there.
                let y = &dense.y1;
                let frames = rtw.frames(y);
                let flow = self.observe_step(rtw, dense, || rtw.friction_ratio_at(&frames));
                if flow == Flow::Continue {
                    self.before_reset = (
                        Rtw::centre_of_mass_at(&frames)[0],
                        rtw.total_energy_at(y, &frames),
                    );
                }
                flow
            }
        }
    }
}

impl Recorder<'_> {
    /// Statistics of one step (or of the part of it before an event);
    /// `mu_end`: the friction ratio at `dense.y1`, from what is already known
    /// there.
    fn observe_step(&mut self, rtw: &Rtw, dense: &Dense<N>, mu_end: impl FnOnce() -> f64) -> Flow {
        let (t0, t1) = (dense.t0, dense.t1);
        self.stats
            .on_interval(t0, t1, rtw.contact_state(), rtw.sliding());
        if self.stats.window_com_x.is_none() && t1 >= self.stats.window_start {
            let mut y = [0.0; N];
            dense.eval(self.stats.window_start.max(t0), &mut y);
            self.stats.window_com_x = Some(rtw.centre_of_mass(&y)[0]);
        }
        // `mu_required` describes the gait: count it over the window only
        // (or, with an early stop, over the settled window).
        let in_window = t1 >= self.stats.window_start;
        if (in_window || self.stop_when_settled) && rtw.contact_state() > 0 {
            let mu = mu_end();
            if in_window {
                self.mu_required = self.mu_required.max(mu);
            }
            self.mu_since_touchdown = self.mu_since_touchdown.max(mu);
        }
        if self.trace.is_some() {
            if self.trace_dt > 0.0 {
                let mut y = [0.0; N];
                while self.next_trace <= t1 {
                    let t = self.next_trace;
                    dense.eval(t, &mut y);
                    self.emit(rtw, t, &y);
                    self.next_trace += self.trace_dt;
                }
            } else {
                let y1 = dense.y1;
                self.emit(rtw, t1, &y1);
            }
        }
        if t1 - self.stats.last_touchdown > self.stall_time {
            self.failure = Some(FailureDetail::NoTouchdown);
            return Flow::Stop;
        }
        Flow::Continue
    }
}

/// The run's end: its outcome, and the system and state it ended in.
type Ended = (Outcome, Rtw, [f64; N]);

/// Sets the star down and runs it: the physical parameters, and the run's
/// end, or the outcome of a star that could not start.
pub(crate) fn start_and_run(
    params: &Params,
    options: &Options,
    trace: Option<&mut dyn FnMut(&TraceSample)>,
) -> (Physical, Result<Ended, Outcome>) {
    if let Err(e) = params.validate().and_then(|_| options.validate()) {
        panic!("simulate: {e}");
    }
    let phys = Physical::new(params, options.normalization, options.g);
    let mut rtw = Rtw::new(&phys, options);
    // The work of standing the star up counts as the run's.
    let mut standing = Work::default();
    let ended = match initial_state(&mut rtw, options, &mut standing) {
        Ok((y, start)) => Ok(run_from(
            params, options, &phys, rtw, y, start, standing, trace,
        )),
        Err(detail) => Err(failed_at_start(detail, standing)),
    };
    (phys, ended)
}

/// Runs `params` under `options` (which must be valid) and hands `f` the
/// physical parameters, the system and state the run ended in and its
/// outcome; `None` if the star could not start.
#[cfg(test)]
pub(crate) fn with_end_state<T>(
    params: &Params,
    options: &Options,
    f: impl FnOnce(&Physical, &Rtw, &[f64; N], &Outcome) -> T,
) -> Option<T> {
    let (phys, ended) = start_and_run(params, options, None);
    let (outcome, rtw, y) = ended.ok()?;
    Some(f(&phys, &rtw, &y, &outcome))
}

/// The run from state `y` of `rtw` (standing as `start`, after `standing`
/// work to set it down) to its end: its outcome, and the system and state
/// it ended in. The system is autonomous, so the run's clock starts at 0.
#[allow(clippy::too_many_arguments)] // the pieces of a started run
pub(crate) fn run_from(
    params: &Params,
    options: &Options,
    phys: &Physical,
    mut rtw: Rtw,
    mut y: [f64; N],
    start: Stance,
    standing: Work,
    trace: Option<&mut dyn FnMut(&TraceSample)>,
) -> (Outcome, Rtw, [f64; N]) {
    let window_start = options.t_max * (1.0 - options.analysis_window);
    let mut rec = Recorder {
        stats: GaitStats::new(window_start, options.labels),
        stall_time: options.stall_time,
        failure: None,
        mu_required: 0.0,
        impact_loss: 0.0,
        trace,
        trace_dt: options.trace_dt,
        next_trace: 0.0,
        stop_when_settled: options.stop_when_settled,
        mu_since_touchdown: 0.0,
        settled: None,
        sections: options.limit_cycle.then(Box::default),
        before_reset: (0.0, 0.0),
    };
    let e0 = rtw.total_energy(&y);
    let g0 = rtw.energy(&y).1;
    if rec.trace.is_some() {
        rec.emit(&rtw, 0.0, &y);
        rec.next_trace = options.trace_dt;
    }
    let end = run(
        &mut rtw,
        &mut rec,
        0.0,
        &mut y,
        options.t_max,
        &options.engine(),
    );

    let (_, g1, _) = rtw.energy(&y);
    let e1 = rtw.total_energy(&y);
    let energy = Energy {
        initial: e0,
        last: e1,
        gravity_released: g0 - g1,
        impact_loss: rec.impact_loss,
        damping_loss: y[DISSIPATED],
        friction_loss: y[FRICTION],
        balance_error: e1 + rec.impact_loss + y[DISSIPATED] + y[FRICTION] - e0,
    };
    let numerical = match end.reason {
        EndReason::TimeUp | EndReason::Stopped => None,
        EndReason::NonFinite => Some(FailureDetail::NonFinite),
        EndReason::StepUnderflow => Some(FailureDetail::StepUnderflow),
        EndReason::WorkBudget => Some(FailureDetail::WorkBudget),
        EndReason::Zeno => Some(FailureDetail::Zeno),
    };
    let window = (options.t_max - window_start).max(f64::MIN_POSITIVE);
    let stats = &rec.stats;
    // What the analysis window measures: over the last `analysis_window` of
    // the run, or over the settled gait's whole periods after an early stop.
    let (fractions, step_shares, f_w, f_w_newfoot, speed, mu_required, period) = match rec.settled {
        Some(s) => (
            s.fractions,
            s.step_shares,
            s.f_w,
            s.f_w_newfoot,
            s.speed,
            s.mu_required,
            s.period,
        ),
        None => (
            stats.fractions(),
            stats.step_shares(),
            stats.window_touchdowns as f64 / window,
            stats.window_newfoot as f64 / window,
            match stats.window_com_x {
                Some(x0) if end.reason == EndReason::TimeUp => {
                    (rtw.centre_of_mass(&y)[0] - x0) / window
                }
                _ => 0.0,
            },
            rec.mu_required,
            stats.period(),
        ),
    };
    let failure = numerical.or(rec.failure).or_else(|| {
        // Over the window the star must roll at least half a rod downhill
        // (for a settled gait: at the same mean speed).
        (speed * window < 0.5 * phys.length).then_some(FailureDetail::NoProgress)
    });
    let label = match failure {
        None => Label::of_gait(&fractions, &step_shares, &options.labels),
        Some(detail) => detail.label(),
    };
    let cycle = match &rec.sections {
        Some(log) if label.is_stable() => cycle_of_run(params, options, log),
        _ => None,
    };
    let outcome = Outcome {
        label,
        failure,
        start,
        t_end: end.t,
        fractions,
        step_shares,
        touchdowns: stats.touchdowns,
        f_w,
        f_w_newfoot,
        speed,
        mu_required,
        slide_time: stats.slide_time,
        energy,
        period: if label.is_stable() { period } else { 0 },
        cycle,
        work: {
            let mut work = end.work;
            work += standing;
            work
        },
        robustness: None,
    };
    (outcome, rtw, y)
}

/// The outcome of a run that could not start, after `work` trying.
fn failed_at_start(detail: FailureDetail, work: Work) -> Outcome {
    Outcome {
        // A star that cannot stand is a collapse; a numerical failure while
        // it was being set down is `diverged`, like any other.
        label: detail.label(),
        failure: Some(detail),
        start: Stance::RestShape,
        t_end: 0.0,
        fractions: Default::default(),
        step_shares: Default::default(),
        touchdowns: 0,
        f_w: 0.0,
        f_w_newfoot: 0.0,
        speed: 0.0,
        mu_required: 0.0,
        slide_time: 0.0,
        energy: Energy::default(),
        period: 0,
        cycle: None,
        work,
        robustness: None,
    }
}
