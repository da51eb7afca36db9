//! A branch continued through its mode-sequence changes, segment by
//! segment: each segment's corrector refuses any point whose mode sequence
//! is not the segment's, and each segment ends where [`locate_end`] names
//! the change (docs/continuation.md).

use crate::cycles::branches::continuation::StepMapFamily;
use crate::cycles::branches::nonsmooth::*;
use crate::cycles::map::section::SectionPoint;
use crate::outcome::Label;
use hybrid_ode::continuation::{self, Branch, End, MapEval, Options as ContOptions, ParamMap};
use hybrid_ode::limit;
use nalgebra::DMatrix;

/// The step map family of one segment: [`StepMapFamily`] that is undefined
/// wherever the orbit's mode sequence is not the segment's, so that the
/// corrector cannot jump back across the change it came through.
struct SegmentFamily<'a> {
    inner: StepMapFamily,
    setting: Setting<'a>,
    template: SectionPoint,
    n: usize,
    sequence: ModeSequence,
}

impl SegmentFamily<'_> {
    /// `Pⁿ(z)` at `p` by one plain run of `n` steps, if the run's events are
    /// the segment's sequence.
    fn in_sequence(&self, z: &[f64], p: f64) -> Option<Vec<f64>> {
        let map = map_at(
            self.setting.base,
            self.setting.options,
            self.setting.cycle,
            self.setting.param,
            p,
        )?;
        // The orbit of the point itself (not yet a fixed point): its events.
        let mut at = self.template.with_coords(z);
        let mut events = Vec::new();
        for k in 0..self.n {
            let mut w = Watch::default();
            let step = map.step_watched(&at, &mut w).ok()?;
            events.extend(
                w.events
                    .iter()
                    .zip(&w.after)
                    .map(|(&kind, &after)| ModeEvent {
                        step: k,
                        kind,
                        after,
                    }),
            );
            at = step.to;
        }
        (events == self.sequence.events && at.modes == self.template.modes).then(|| at.coords())
    }
}

impl ParamMap for SegmentFamily<'_> {
    /// The sequence checked first (a plain run): the variational run is
    /// spent only on points of the segment.
    fn eval(&mut self, z: &[f64], p: f64) -> Option<MapEval> {
        self.in_sequence(z, p)?;
        self.inner.eval(z, p)
    }

    fn value(&mut self, z: &[f64], p: f64) -> Option<Vec<f64>> {
        self.in_sequence(z, p)
    }
}

/// One segment of a continued branch: one mode sequence.
#[derive(Clone, Debug)]
pub struct Segment {
    /// Its mode sequence.
    pub sequence: ModeSequence,
    /// The gait label of its first point's orbit.
    pub label: Label,
    /// Its section points' template: a branch point `z` is the section
    /// point `template.with_coords(z)`.
    pub template: SectionPoint,
    /// Its points (the smooth continuation's branch).
    pub branch: Branch,
    /// How it ended, where its continuation failed at the smallest step
    /// (`None`: it left the input's range or reached its point cap).
    pub end: Option<BranchEnd>,
}

/// Continues the period-`n` fixed point `start` at `p0` towards
/// `direction` within `range`, segment by segment: each segment is a smooth
/// branch in one mode sequence ([`continuation::continue_branch`], its
/// corrector rejecting points of another sequence); where it ends,
/// a bisection between the last value with the old sequence and the first
/// with another names why ([`EndKind`](crate::cycles::EndKind)), and if there is an
/// orbit past the change the next segment starts from it. At most `max_segments`.
#[allow(clippy::too_many_arguments)]
pub fn continue_segments(
    s: &Setting<'_>,
    start: &SectionPoint,
    n: usize,
    p0: f64,
    direction: f64,
    cont: &ContOptions,
    end_opts: &EndOptions,
    max_segments: usize,
) -> Vec<Segment> {
    let mut out = Vec::new();
    let Some(mut next_orbit) = s.orbit(start, n, p0) else {
        return out;
    };
    let multipliers = |j: &DMatrix<f64>| limit::nontrivial_multipliers(j);
    let range = (cont.p_min, cont.p_max);
    let mut direction = direction;
    while out.len() < max_segments {
        let Some((orbit_used, template, z_scale, branch)) =
            start_segment(s, &next_orbit, n, direction, cont, &multipliers).or_else(|| {
                // Right past a corner the new side's events are still as
                // near in time as the bracket is narrow, and the segment's
                // first Newton can see them in the old order: start the
                // segment 1, 2 or 4 probe steps on.
                if out.is_empty() {
                    return None;
                }
                (0..3).find_map(|k| {
                    let p = next_orbit.p + direction * end_opts.probe * f64::from(1 << k);
                    if !(range.0..=range.1).contains(&p) {
                        return None;
                    }
                    let o = s.orbit(&next_orbit.cycle.orbit[0], n, p)?;
                    start_segment(s, &o, n, direction, cont, &multipliers)
                })
            })
        else {
            break;
        };
        let orbit = orbit_used;
        let label = orbit.cycle.label(&s.options.labels);
        // The way the branch was going at its end: its last step in the
        // input (the tangent there may have turned, computed with the
        // Jacobian of the other side of a nonsmooth point).
        if let [.., a, b] = &branch.points[..]
            && b.p != a.p
        {
            direction = (b.p - a.p).signum();
        }
        let end = (branch.end == End::StepTooSmall)
            .then(|| {
                let last = branch.points.last().expect("the start");
                locate_end(
                    s,
                    &template.with_coords(&last.z),
                    n,
                    last.p,
                    direction,
                    range,
                    end_opts,
                )
            })
            .flatten();
        let end = end.map(|e| match came_back(&branch, &e, &z_scale, end_opts) {
            true => fold(s, &template, n, &branch).unwrap_or(e),
            false => e,
        });
        let next = end.as_ref().and_then(|e| e.new.clone());
        out.push(Segment {
            sequence: orbit.sequence.clone(),
            label,
            template,
            branch,
            end,
        });
        match next {
            Some(o) => next_orbit = o,
            None => break,
        }
    }
    out
}

/// A segment's smooth branch from `orbit` towards `direction`: the orbit
/// it started from (`orbit`), its template, the scales of its coordinates
/// (the map's, [`crate::cycles::StepMap::coord_scale`]) and the branch; `None` if the
/// continuation cannot start there.
fn start_segment(
    s: &Setting<'_>,
    orbit: &Orbit,
    n: usize,
    direction: f64,
    cont: &ContOptions,
    multipliers: &dyn Fn(&DMatrix<f64>) -> Vec<nalgebra::Complex<f64>>,
) -> Option<(Orbit, SectionPoint, Vec<f64>, Branch)> {
    let template = orbit.cycle.orbit[0];
    let map = map_at(s.base, s.options, s.cycle, s.param, orbit.p)?;
    let opts = ContOptions {
        z_scale: map.coord_scale(&template),
        ..cont.clone()
    };
    let mut family = SegmentFamily {
        inner: StepMapFamily::new(s.base, s.options, s.cycle, s.param, template, n),
        setting: *s,
        template,
        n,
        sequence: orbit.sequence.clone(),
    };
    let branch = continuation::continue_branch(
        &mut family,
        &orbit.cycle.fixed_point.z,
        orbit.p,
        direction,
        &opts,
        multipliers,
    )
    .ok()?;
    Some((orbit.clone(), template, opts.z_scale, branch))
}

/// Whether `end` lies on the segment's own way back: the orbit where it was
/// located is one the branch already passed at least a probe step before its
/// end in the input (the same value within ten brackets, the same fixed
/// point within [`CAME_BACK_TOL`] in the segment's `scale`; the points it
/// accepted at its end, as its step shrank, all lie within a probe step of
/// the last). Then the branch turned at a fold its corrector did not pass
/// and the probes from its last point followed it back to where it came
/// from.
fn came_back(branch: &Branch, end: &BranchEnd, scale: &[f64], opts: &EndOptions) -> bool {
    let z = &end.old.cycle.fixed_point.z;
    let Some(last) = branch.points.last() else {
        return false;
    };
    branch.points.iter().any(|pt| {
        (pt.p - last.p).abs() >= opts.probe
            && (pt.p - end.old.p).abs() <= 10.0 * opts.p_tol
            && pt.z.len() == z.len()
            && limit::scaled_max(&pt.z, z, scale) <= CAME_BACK_TOL
    })
}

/// Two fixed points of one branch this close in the map's scales
/// ([`limit::scaled_max`]) are the same orbit passed twice: far above the
/// corrector's tolerance, far below how far a fixed point moves over a
/// probe step near a fold (as the square root of the step).
const CAME_BACK_TOL: f64 = 1e-4;

/// The end of a segment whose branch turned at a fold: the orbit at its
/// last point, with the real multiplier nearest +1 there.
fn fold(s: &Setting<'_>, template: &SectionPoint, n: usize, branch: &Branch) -> Option<BranchEnd> {
    let last = branch.points.last()?;
    let old = s.orbit(&template.with_coords(&last.z), n, last.p)?;
    let multiplier = last
        .multipliers
        .iter()
        .filter(|m| m.im.abs() < 1e-9)
        .map(|m| m.re)
        .min_by(|a, b| (a - 1.0).abs().total_cmp(&(b - 1.0).abs()))?;
    Some(BranchEnd {
        kind: EndKind::Fold { multiplier },
        p_new: last.p,
        old,
        new: None,
        jacobian_jump: None,
    })
}
