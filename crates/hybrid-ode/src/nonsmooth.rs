//! Where an orbit's sequence of events changes with a parameter, and how:
//! the nonsmooth bifurcations that end a smooth continuation.
//!
//! A branch of periodic orbits continued in a parameter keeps its sequence of
//! events (which guard fires, in which order) until, at some value, the
//! sequence changes. Two generic ways (di Bernardo et al., *Piecewise-smooth
//! Dynamical Systems*, ch. 2 and 6):
//!
//! * **grazing**: a guard that did not fire touches zero tangentially — its
//!   local minimum over the orbit reaches zero (an impact oscillator's
//!   amplitude reaching the stop; a tip that just touches the ground; a
//!   contact force that just reaches zero). Past it, an event fires with a
//!   crossing slope that grows like the square root of the distance to the
//!   grazing value (Nordmark's square-root singularity);
//! * **corner**: two events coincide in time and swap order.
//!
//! This module gives the pieces: [`GuardMinima`], an observer that records
//! the events of a run with their crossing slopes and every local minimum of
//! the distance of each guard to firing; [`locate_change`], bisection on the
//! parameter between a value with one signature and a value with another;
//! and [`classify`], which names the change from the runs on both sides.
//! Analysis code, not the hot path: it allocates.

use crate::dense::Dense;
use crate::system::{Crossing, Flow, Guards, HybridSystem, Observer, StepEnd};

/// Samples of the dense output per step in which [`GuardMinima`] looks for
/// local minima (a minimum between samples is refined by golden section).
const SAMPLES: usize = 8;

/// Golden-section iterations of a local minimum's refinement (bracket shrinks
/// by 0.618⁶⁰ ≈ 3·10⁻¹³ of a step).
const GOLDEN_ITERS: usize = 60;

/// An event of a run: guard `guard` fired at time `t` with rate `rate` (the
/// guard's time derivative there, before the reset: 0 at a grazing contact).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Event {
    /// Event time.
    pub t: f64,
    /// Index of the guard that fired (in the mode before the event).
    pub guard: usize,
    /// The guard's time derivative at the event.
    pub rate: f64,
}

/// A local minimum of a guard's distance to firing over a run (`g` for a
/// falling guard, `−g` for a rising one, `|g|` for either): where a guard
/// that did not fire comes closest to firing. Zero at a grazing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GuardMinimum {
    /// Its time.
    pub t: f64,
    /// Index of the guard (in the mode at `t`).
    pub guard: usize,
    /// The distance to firing there (≥ 0 unless a crossing was missed).
    pub value: f64,
    /// At an event: the distance fell up to it (`t` is its time; the mode
    /// ends there). Zero there is a corner (the guard's zero coincides with
    /// the event), not a tangency. (A mode's start is no such minimum: a
    /// reset leaves guards of the rod it moved at zero by construction.)
    pub at_boundary: bool,
}

/// Records a run's events (with their crossing slopes) and the local minima
/// of every guard's distance to firing between them: what [`classify`] reads
/// to tell a grazing from a corner. Local minima are looked for in
/// `SAMPLES` points of each step's dense output, continued across steps of
/// one mode, and refined by golden section inside the step.
#[derive(Clone, Debug, Default)]
pub struct GuardMinima {
    /// The events, in order.
    pub events: Vec<Event>,
    /// The local minima, in order of time.
    pub minima: Vec<GuardMinimum>,
    /// The last two samples `(t, distance of each guard)` of the current mode.
    tail: Vec<(f64, Guards)>,
}

/// The distance of guard `i` of `g` to firing.
fn distance(g: &Guards, i: usize) -> f64 {
    match g.crossing[i] {
        Crossing::Falling => g.value[i],
        Crossing::Rising => -g.value[i],
        Crossing::Either => g.value[i].abs(),
    }
}

impl GuardMinima {
    /// The smallest local minimum recorded inside a mode, if any.
    pub fn smallest(&self) -> Option<GuardMinimum> {
        self.minima
            .iter()
            .filter(|m| !m.at_boundary)
            .copied()
            .min_by(|a, b| a.value.total_cmp(&b.value))
    }

    /// The guard's distance to firing at `t` on `dense`.
    fn distance_at<const N: usize, S: HybridSystem<N>>(
        sys: &S,
        dense: &Dense<N>,
        t: f64,
        i: usize,
    ) -> f64 {
        let mut y = [0.0; N];
        dense.eval(t, &mut y);
        let mut g = Guards::default();
        sys.guards(t, &y, &mut g);
        distance(&g, i)
    }

    /// Golden-section minimum of guard `i`'s distance on `[a, b]` of `dense`.
    fn refine<const N: usize, S: HybridSystem<N>>(
        sys: &S,
        dense: &Dense<N>,
        (mut a, mut b): (f64, f64),
        i: usize,
    ) -> (f64, f64) {
        let r = 0.5 * (5f64.sqrt() - 1.0);
        let mut c = b - r * (b - a);
        let mut d = a + r * (b - a);
        let (mut fc, mut fd) = (
            Self::distance_at(sys, dense, c, i),
            Self::distance_at(sys, dense, d, i),
        );
        for _ in 0..GOLDEN_ITERS {
            if fc <= fd {
                (b, d, fd) = (d, c, fc);
                c = b - r * (b - a);
                fc = Self::distance_at(sys, dense, c, i);
            } else {
                (a, c, fc) = (c, d, fd);
                d = a + r * (b - a);
                fd = Self::distance_at(sys, dense, d, i);
            }
        }
        if fc <= fd { (c, fc) } else { (d, fd) }
    }
}

impl<const N: usize, S: HybridSystem<N>> Observer<N, S> for GuardMinima {
    fn on_step(&mut self, sys: &S, dense: &Dense<N>, end: StepEnd<'_, S::Aux>) -> Flow {
        let h = dense.t1 - dense.t0;
        if h > 0.0 {
            let first = if self.tail.is_empty() { 0 } else { 1 };
            for k in first..=SAMPLES {
                let t = dense.t0 + h * k as f64 / SAMPLES as f64;
                let mut y = [0.0; N];
                dense.eval(t, &mut y);
                let mut g = Guards::default();
                sys.guards(t, &y, &mut g);
                if self.tail.len() == 2 {
                    let ((ta, ga), (tm, gm)) = (self.tail[0], self.tail[1]);
                    for i in 0..gm.len.min(ga.len).min(g.len) {
                        let (da, dm, db) = (distance(&ga, i), distance(&gm, i), distance(&g, i));
                        if dm < da && dm <= db {
                            let (t, value) = if ta >= dense.t0 {
                                Self::refine(sys, dense, (ta, t), i)
                            } else {
                                (tm, dm)
                            };
                            self.minima.push(GuardMinimum {
                                t,
                                guard: i,
                                value,
                                at_boundary: false,
                            });
                        }
                    }
                    self.tail.remove(0);
                }
                self.tail.push((t, g));
            }
        }
        if let StepEnd::Event { guard } = end {
            // The other guards falling up to the event came closest there.
            if let [(_, ga), (tb, gb)] = self.tail[..] {
                for i in (0..ga.len.min(gb.len)).filter(|&i| i != guard) {
                    if distance(&gb, i) < distance(&ga, i) {
                        self.minima.push(GuardMinimum {
                            t: tb,
                            guard: i,
                            value: distance(&gb, i),
                            at_boundary: true,
                        });
                    }
                }
            }
            let mut dy = [0.0; N];
            dense.eval_rate(dense.t1, &mut dy);
            self.events.push(Event {
                t: dense.t1,
                guard,
                rate: sys.guard_rate(dense.t1, &dense.y1, &dy, guard),
            });
        }
        Flow::Continue
    }

    fn on_transition(&mut self, _sys: &S, _t: f64, _y: &[f64; N], _tr: &S::Transition) -> Flow {
        // The guards may mean other things in the new mode, and the one that
        // fired sits at zero: minima are looked for afresh.
        self.tail.clear();
        Flow::Continue
    }
}

/// Where a discrete signature of the orbit changes in the parameter: `old`
/// is the last value found with the signature at `lo`, `new` the first with
/// another, `|new − old| ≤ tol`.
#[derive(Clone, Debug, PartialEq)]
pub struct Change<T> {
    /// The last parameter value with the old signature.
    pub old: f64,
    /// The first parameter value with a new one.
    pub new: f64,
    /// The signature at `old`.
    pub old_signature: T,
    /// The signature at `new`.
    pub new_signature: T,
}

/// Bisection on the parameter between `lo` and `hi` (either order), whose
/// signatures differ, down to a bracket of `tol`: the signature (an event
/// sequence, `None` where the orbit is lost) keeps `lo`'s value on one side.
/// `None` if the signatures at `lo` and `hi` are equal.
pub fn locate_change<T: PartialEq + Clone>(
    lo: f64,
    hi: f64,
    tol: f64,
    mut signature: impl FnMut(f64) -> T,
) -> Option<Change<T>> {
    let (mut a, mut b) = (lo, hi);
    let (sa, mut sb) = (signature(a), signature(b));
    if sa == sb {
        return None;
    }
    while (b - a).abs() > tol {
        let c = 0.5 * (a + b);
        if c == a || c == b {
            break;
        }
        let sc = signature(c);
        if sc == sa {
            a = c;
        } else {
            (b, sb) = (c, sc);
        }
    }
    Some(Change {
        old: a,
        new: b,
        old_signature: sa,
        new_signature: sb,
    })
}

/// How an orbit's sequence of events changed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Kind {
    /// A guard touched zero tangentially: on the old side its distance to
    /// firing had a local minimum of `value` (≈ 0) at `t`.
    Grazing {
        /// The guard (in its mode at `t`).
        guard: usize,
        /// Time of the tangency along the orbit.
        t: f64,
        /// Its distance to firing there on the old side.
        value: f64,
    },
    /// Two events of one side coincide in time (to `time_tol`).
    Corner {
        /// The first of the two guards.
        first: usize,
        /// The second.
        second: usize,
        /// Their time apart.
        dt: f64,
    },
    /// Neither: the orbit changed otherwise (or was lost).
    Other,
}

/// Names the change between the runs of one orbit on its old side (`old`)
/// and its new side (`new`), as recorded by [`GuardMinima`]: a grazing if a
/// guard's local minimum on the old side is within `value_tol` of zero (the
/// nearest one), else a corner if two events of either side are within
/// `time_tol` of each other, else [`Kind::Other`].
pub fn classify(old: &GuardMinima, new: &GuardMinima, value_tol: f64, time_tol: f64) -> Kind {
    if let Some(m) = old.smallest().filter(|m| m.value.abs() <= value_tol) {
        return Kind::Grazing {
            guard: m.guard,
            t: m.t,
            value: m.value,
        };
    }
    let corner = [old, new]
        .into_iter()
        .flat_map(|side| side.events.windows(2))
        .map(|w| (w[0].guard, w[1].guard, w[1].t - w[0].t))
        .filter(|&(_, _, dt)| dt.abs() <= time_tol)
        .min_by(|a, b| a.2.abs().total_cmp(&b.2.abs()));
    match corner {
        Some((first, second, dt)) => Kind::Corner { first, second, dt },
        None => Kind::Other,
    }
}
