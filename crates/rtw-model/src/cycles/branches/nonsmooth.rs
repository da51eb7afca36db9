//! Where a gait's branch leaves its mode sequence, and what happens there:
//! the nonsmooth bifurcations that end a smooth continuation of the step
//! map ([`crate::cycles::branches::continuation`]), located and named, and the branch
//! continued on the other side.
//!
//! A fixed point's **mode sequence** is what happens over its `n` steps:
//! every guard that fires, in order (touchdowns, lift-offs, slips,
//! re-sticks; [`GuardKind`]), and the contact modes at each section point.
//! Along a branch it stays the same until, at some value of the input, it
//! changes. [`locate_end`] finds that value by bisection between the last
//! value with the old sequence and the first with another, and names the
//! change ([`EndKind`]):
//!
//! * **grazing**: a guard touches zero tangentially — a swinging tip that
//!   just touches the ground, a contact force that just reaches zero (a
//!   flight phase appears), a friction ratio that just reaches μ: its
//!   closest approach over the orbit shrinks to zero at the change (or an
//!   event's crossing slope does, where an event vanishes);
//! * **corner**: two events coincide in time and swap;
//! * **gait lost**: past the change there is no fixed point with the same
//!   period (the gait fails or turns into another one).
//!
//! [`continue_segments`] then restarts the branch past the change with the
//! new sequence: a branch of [`Segment`]s, each with its mode sequence and
//! gait label, whose corrector rejects any point of another sequence.

use crate::cycles::map::limit_cycle::LimitCycle;
use crate::cycles::map::section::SectionPoint;
use crate::cycles::map::stepmap::{CycleOptions, StepMap};
use crate::options::Options;
use crate::params::{Param, Params};
use crate::plant::contact::RodMode;
use crate::plant::rtw::{AtState, GuardKind, Rtw, Transition};
use crate::plant::slots::N;
use hybrid_ode::nonsmooth::{GuardMinima, locate_change};
use hybrid_ode::{Dense, Flow, Observer, StepEnd};

mod chord;
mod classify;

use classify::{appearing, corner, shrunk};

/// One event of a periodic orbit: guard `kind` fired in step `step` of the
/// orbit (in that step's canonical labels: its stance rod is rod 0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModeEvent {
    /// The orbit's step (0 … n − 1).
    pub step: usize,
    /// What fired.
    pub kind: GuardKind,
    /// The rods' modes after its reset (a touchdown may stick or slide).
    pub after: [RodMode; 3],
}

/// The mode sequence of a periodic orbit: its events in order and the
/// contact modes at each of its section points.
#[derive(Clone, Debug, PartialEq)]
pub struct ModeSequence {
    /// Every event over the orbit's steps, in order.
    pub events: Vec<ModeEvent>,
    /// The rods' modes at each section point.
    pub section_modes: Vec<[RodMode; 3]>,
}

impl ModeSequence {
    /// A short text: each step's events, steps apart by ` | ` (e.g.
    /// `td b- · lo c | …`); also its `Display`.
    pub(crate) fn describe(&self) -> String {
        let steps = self.section_modes.len();
        (0..steps)
            .map(|k| {
                self.events
                    .iter()
                    .filter(|e| e.step == k)
                    .map(|e| guard_name(e.kind))
                    .collect::<Vec<_>>()
                    .join(" · ")
            })
            .collect::<Vec<_>>()
            .join(" | ")
    }
}

impl std::fmt::Display for ModeSequence {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.describe())
    }
}

impl std::fmt::Display for GuardKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&guard_name(*self))
    }
}

/// A guard's short name: `td a+` (touchdown of rod a's + tip), `lo b`
/// (lift-off), `down c` (a rod lies down), `slip a`, `stick a`, `com`,
/// `edge a` (a sliding tip reaches a step's edge).
pub(crate) fn guard_name(kind: GuardKind) -> String {
    let rod = |r: usize| ["a", "b", "c"].get(r).copied().unwrap_or("?");
    match kind {
        GuardKind::Touchdown { rod: r, tip } => {
            format!("td {}{}", rod(r), if tip.sign() > 0.0 { "+" } else { "-" })
        }
        GuardKind::LiftOff { rod: r } => format!("lo {}", rod(r)),
        GuardKind::RodDown { rod: r } => format!("down {}", rod(r)),
        GuardKind::Restick { rod: r } => format!("stick {}", rod(r)),
        GuardKind::Slip { rod: r } => format!("slip {}", rod(r)),
        GuardKind::ComLow => "com".to_string(),
        GuardKind::Edge { rod: r } => format!("edge {}", rod(r)),
        GuardKind::FaceTop { rod: r } => format!("top {}", rod(r)),
        GuardKind::EdgePass { rod: r, tip } => {
            format!(
                "pass {}{}",
                rod(r),
                if tip.sign() > 0.0 { "+" } else { "-" }
            )
        }
    }
}

/// Where a guard that did not fire came closest to firing over the orbit
/// (a local minimum of its distance: tip height, normal force, friction
/// margin), or an event's crossing slope.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Approach {
    /// The orbit's step.
    pub step: usize,
    /// The guard.
    pub kind: GuardKind,
    /// Time since the step's start (s).
    pub t: f64,
    /// The distance to firing there (a closest approach), or the guard's
    /// rate at the event (an event).
    pub value: f64,
    /// A closest approach at an event or a mode's start (see
    /// [`hybrid_ode::nonsmooth::GuardMinimum::at_boundary`]): at zero, a
    /// corner.
    pub at_boundary: bool,
}

/// A periodic orbit at one value of the input, with what its steps did.
#[derive(Clone, Debug)]
pub struct Orbit {
    /// The input's value.
    pub p: f64,
    /// The limit cycle (fixed point, steps, Floquet multipliers).
    pub cycle: LimitCycle,
    /// Its mode sequence.
    pub sequence: ModeSequence,
    /// Closest approaches of the guards that did not fire.
    pub approaches: Vec<Approach>,
    /// The events with their crossing slopes (`value`: the guard's rate).
    pub events: Vec<Approach>,
}

/// Watches a step: its events and guard minima, named by [`GuardKind`].
#[derive(Default)]
pub(crate) struct Watch {
    minima: GuardMinima,
    pub(crate) events: Vec<GuardKind>,
    approaches: Vec<GuardKind>,
    pub(crate) after: Vec<[RodMode; 3]>,
}

/// The `index`-th guard of `rtw`'s current modes.
fn kind_of(rtw: &Rtw, index: usize) -> GuardKind {
    let mut k = 0;
    let mut found = GuardKind::ComLow;
    rtw.guard_kinds(|g| {
        if k == index {
            found = g;
        }
        k += 1;
    });
    found
}

impl Observer<N, Rtw> for Watch {
    fn on_step(&mut self, rtw: &Rtw, dense: &Dense<N>, end: StepEnd<'_, AtState>) -> Flow {
        let flow = self.minima.on_step(rtw, dense, end);
        for m in &self.minima.minima[self.approaches.len()..] {
            self.approaches.push(kind_of(rtw, m.guard));
        }
        for e in &self.minima.events[self.events.len()..] {
            self.events.push(kind_of(rtw, e.guard));
        }
        flow
    }

    fn on_transition(&mut self, rtw: &Rtw, t: f64, y: &[f64; N], tr: &Transition) -> Flow {
        self.after.push(rtw.modes());
        self.minima.on_transition(rtw, t, y, tr)
    }
}

/// The events and closest approaches of the `n` steps from `orbit[0]`.
fn watch(map: &StepMap, cycle: LimitCycle, p: f64) -> Option<Orbit> {
    let mut events = Vec::new();
    let mut approaches = Vec::new();
    let mut seq = Vec::new();
    for (k, at) in cycle.orbit.iter().enumerate() {
        let mut w = Watch::default();
        map.step_watched(at, &mut w).ok()?;
        for ((e, kind), after) in w.minima.events.iter().zip(&w.events).zip(&w.after) {
            seq.push(ModeEvent {
                step: k,
                kind: *kind,
                after: *after,
            });
            events.push(Approach {
                step: k,
                kind: *kind,
                t: e.t,
                value: e.rate,
                at_boundary: false,
            });
        }
        for (m, kind) in w.minima.minima.iter().zip(&w.approaches) {
            approaches.push(Approach {
                step: k,
                kind: *kind,
                t: m.t,
                value: m.value,
                at_boundary: m.at_boundary,
            });
        }
    }
    let section_modes = cycle.orbit.iter().map(|o| o.modes).collect();
    Some(Orbit {
        p,
        cycle,
        sequence: ModeSequence {
            events: seq,
            section_modes,
        },
        approaches,
        events,
    })
}

/// The step map of `base` with `param` at `value`; `None` outside its range.
pub(crate) fn map_at(
    base: &Params,
    options: &Options,
    cycle: &CycleOptions,
    param: Param,
    value: f64,
) -> Option<StepMap> {
    let mut p = *base;
    p[param] = value;
    p.validate().ok()?;
    Some(StepMap::new(&p, options, cycle))
}

/// What a branch is continued in: the model, the map's settings, the input.
#[derive(Clone, Copy, Debug)]
pub struct Setting<'a> {
    /// The inputs other than the continued one.
    pub base: &'a Params,
    /// The model.
    pub options: &'a Options,
    /// The step map's settings.
    pub cycle: &'a CycleOptions,
    /// The continued input.
    pub param: Param,
}

impl Setting<'_> {
    /// The period-`n` orbit at `value` near `start` (Newton on `Pⁿ`; if the
    /// start's modes do not come back, from its image, whose modes may be the
    /// new side's; failing both, from where the map settles after
    /// [`SETTLE_PERIODS`] periods from it), with its mode sequence. `None`
    /// where there is none.
    pub(crate) fn orbit(&self, start: &SectionPoint, n: usize, value: f64) -> Option<Orbit> {
        let map = map_at(self.base, self.options, self.cycle, self.param, value)?;
        let cycle = match map.solve(start, n, self.cycle) {
            Ok(c) => c,
            Err(_) => {
                let q = map.iterate(start, n).ok()?.last()?.to;
                match map.solve(&q, n, self.cycle) {
                    Ok(c) => c,
                    Err(_) => settled(&map, start, n, self.cycle)?,
                }
            }
        };
        watch(&map, cycle, value)
    }
}

/// Periods of the map run from a start before Newton is tried from where
/// they end ([`Setting::orbit`]'s last resort).
pub(crate) const SETTLE_PERIODS: usize = 30;

/// Past a corner or a grazing the orbit's section point can jump farther
/// than Newton reaches from the old side's orbit (a border collision moves
/// it at a rate that is not small), although a stable gait goes on: the
/// period-`n` orbit the map settles into from `start`, if it has period `n`
/// (not a divisor of it: the period-1 walk is a fixed point of `P²` too).
fn settled(
    map: &StepMap,
    start: &SectionPoint,
    n: usize,
    cycle: &CycleOptions,
) -> Option<LimitCycle> {
    let q = map.iterate(start, SETTLE_PERIODS * n).ok()?.last()?.to;
    let c = map.solve(&q, n, cycle).ok()?;
    let twice: Vec<SectionPoint> = c.orbit.iter().chain(&c.orbit).copied().collect();
    (map.period_of(&twice, n, cycle.period_tol) == Some(n)).then_some(c)
}

/// How [`continue_segments`](crate::cycles::continue_segments) locates and names a
/// branch's end.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EndOptions {
    /// The change is located to this bracket in the input.
    pub p_tol: f64,
    /// First probe past the branch's last point, in the input.
    pub probe: f64,
    /// Farthest probe past it: no change within it is [`EndKind::NoChange`].
    pub reach: f64,
    /// A closest approach (or an event's slope) counts as grazing where it
    /// has shrunk below this fraction of its value a probe step back.
    pub grazing_ratio: f64,
    /// Two events this close in time (s) make a corner.
    pub corner_dt: f64,
}

impl Default for EndOptions {
    fn default() -> Self {
        Self {
            p_tol: 1e-7,
            probe: 1e-4,
            reach: 0.02,
            grazing_ratio: 0.05,
            corner_dt: 1e-5,
        }
    }
}

/// How a branch's mode sequence changed.
#[derive(Clone, Debug, PartialEq)]
pub enum EndKind {
    /// A guard touched zero tangentially ([`Approach`] on the old side: its
    /// closest approach, or the slope of a vanishing event).
    Grazing(Approach),
    /// Two events coincided.
    Corner {
        /// The first.
        first: GuardKind,
        /// The second.
        second: GuardKind,
        /// Their time apart on the side where they are nearest (s).
        dt: f64,
    },
    /// No fixed point of the period past the change, and neither a grazing
    /// nor a corner before it: the gait fails there.
    GaitLost,
    /// The sequence changed for no reason found.
    Other,
    /// The input's range ends before any change.
    RangeEnd,
    /// No change within [`EndOptions::reach`]: the branch ended otherwise
    /// (a fold the corrector did not pass).
    NoChange,
    /// The branch turned back in the input at a fold (a multiplier through
    /// +1) that its corrector did not pass: probed on from its last point,
    /// it led back along the stretch it came by.
    Fold {
        /// The real multiplier nearest +1 at the branch's last point.
        multiplier: f64,
    },
}

impl EndKind {
    /// The name written in a diagram's files; also its `Display`.
    fn name(&self) -> &'static str {
        match self {
            EndKind::Grazing(_) => "grazing",
            EndKind::Corner { .. } => "corner",
            EndKind::GaitLost => "gait_lost",
            EndKind::Other => "sequence_change",
            EndKind::RangeEnd => "end_parameter_range",
            EndKind::NoChange => "end_no_continuation",
            EndKind::Fold { .. } => "fold",
        }
    }
}

impl std::fmt::Display for EndKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// A located end of a branch.
#[derive(Clone, Debug)]
pub struct BranchEnd {
    /// What happened.
    pub kind: EndKind,
    /// The orbit at the last value with the old sequence.
    pub old: Orbit,
    /// The orbit at the first value with a new one (`None`: none there).
    pub new: Option<Orbit>,
    /// That first value.
    pub p_new: f64,
    /// `‖J_new − J_old‖ / ‖J_old‖` (Frobenius) of `∂Pⁿ/∂z` across the change
    /// (the variational Jacobians, saltation included), where both sides
    /// have the same section coordinates.
    pub jacobian_jump: Option<f64>,
}

/// Locates and names the end of a branch whose last point is the period-`n`
/// fixed point `last` at `p_last`, going towards `direction` (±1) in the
/// input, within `range`: probes past it for the first value where the mode
/// sequence differs (doubling steps from [`EndOptions::probe`] up to
/// [`EndOptions::reach`]), bisects to [`EndOptions::p_tol`], and names the
/// change from the orbits on both sides. `None` if there is no orbit at
/// `p_last`.
pub(crate) fn locate_end(
    s: &Setting<'_>,
    last: &SectionPoint,
    n: usize,
    p_last: f64,
    direction: f64,
    range: (f64, f64),
    opts: &EndOptions,
) -> Option<BranchEnd> {
    let first = s.orbit(last, n, p_last)?;
    let inside = |p: f64| range.0 <= p && p <= range.1;
    // Probe outwards, each orbit from the previous one.
    let (mut near, mut far) = (first.clone(), first.clone());
    let mut h = opts.probe;
    let mut moved = 0.0;
    let bracket_end = loop {
        if moved + h > opts.reach {
            return Some(no_change(first, EndKind::NoChange));
        }
        let p = near.p + direction * h;
        if !inside(p) {
            return Some(no_change(first, EndKind::RangeEnd));
        }
        match s.orbit_near(&near.cycle.orbit[0], n, p, &near.cycle.fixed_point.jacobian) {
            Some(o) if o.sequence == near.sequence => {
                moved += h;
                h *= 2.0;
                far = near;
                near = o;
            }
            _ => break p,
        }
    };
    let from = near.cycle.orbit[0];
    let jacobian = near.cycle.fixed_point.jacobian.clone();
    // The orbits the bisection finds (each from the same start, so that the
    // two sides are the orbits it compared), by value of the input.
    let mut seen: Vec<(f64, Option<Orbit>)> = Vec::new();
    let change = locate_change(near.p, bracket_end, opts.p_tol, |p| {
        let o = s.orbit_near(&from, n, p, &jacobian);
        let sig = o.as_ref().map(|o| o.sequence.clone());
        seen.push((p, o));
        sig
    })?;
    let at = |p: f64| {
        seen.iter()
            .find(|(q, _)| *q == p)
            .and_then(|(_, o)| o.clone())
    };
    let old = at(change.old)?;
    let new = at(change.new);
    // The farther reference: a probe step back, or the branch's last point;
    // if both lie within a probe step of the change (a branch that stopped
    // right next to it), the orbit a probe step back into the branch, or a
    // quarter or a sixteenth of one where the old sequence is shorter than
    // that. A reference as near as the change itself hides a closest
    // approach that has shrunk to zero.
    let back = |o: &Orbit| (o.p - old.p).abs() >= opts.probe;
    let stepped_back;
    let reference = if back(&far) {
        &far
    } else if back(&first) {
        &first
    } else {
        stepped_back = [1.0, 0.25, 0.0625].iter().find_map(|f| {
            s.orbit_near(&from, n, old.p - direction * opts.probe * f, &jacobian)
                .filter(|o| o.sequence == old.sequence)
        });
        stepped_back
            .as_ref()
            .unwrap_or(if far.p == old.p { &first } else { &far })
    };
    let kind = match shrunk(&old, reference, opts.grazing_ratio) {
        // A guard's zero reached at an event: the two coincide.
        Some(a) if a.at_boundary => EndKind::Corner {
            first: old
                .events
                .iter()
                .filter(|e| e.step == a.step)
                .min_by(|x, y| (x.t - a.t).abs().total_cmp(&(y.t - a.t).abs()))
                .map_or(a.kind, |e| e.kind),
            second: a.kind,
            dt: 0.0,
        },
        Some(a) => EndKind::Grazing(a),
        None => match new
            .as_ref()
            .and_then(|o| appearing(&old, o, opts.grazing_ratio))
        {
            Some(a) => EndKind::Grazing(a),
            None => match corner(&old, opts.corner_dt)
                .into_iter()
                .chain(new.as_ref().and_then(|o| corner(o, opts.corner_dt)))
                .min_by(|x, y| x.2.abs().total_cmp(&y.2.abs()))
            {
                Some((first, second, dt)) => EndKind::Corner { first, second, dt },
                None if new.is_none() => EndKind::GaitLost,
                None => EndKind::Other,
            },
        },
    };
    let jacobian_jump = new.as_ref().and_then(|o| {
        let (a, b) = (
            &old.cycle.fixed_point.jacobian,
            &o.cycle.fixed_point.jacobian,
        );
        (a.shape() == b.shape() && old.sequence.section_modes == o.sequence.section_modes)
            .then(|| (b - a).norm() / a.norm())
    });
    Some(BranchEnd {
        kind,
        p_new: change.new,
        old,
        new,
        jacobian_jump,
    })
}

fn no_change(first: Orbit, kind: EndKind) -> BranchEnd {
    let p = first.p;
    BranchEnd {
        kind,
        old: first,
        new: None,
        p_new: p,
        jacobian_jump: None,
    }
}
