//! `continuation --through N`: the gait's branch continued through the
//! changes of its mode sequence ([`rtw_model::cycles::BranchEnd`]), up to
//! `N` segments each way from the start, each segment with its mode
//! sequence and gait label and each end named (grazing, corner, the gait
//! lost, the range's end). Each period-2 branch born at a period doubling
//! whose smooth continuation stopped short is continued the same way from
//! its last point, so that its end is named too and the branch goes on
//! past it where an orbit does. Written as `FILE.segments.json` (every point with
//! its stability, period, step frequency and label, for the figures and the
//! check against the attractor sweep) and a table in `FILE.md`.

use super::Continuation;
use anyhow::{Result, bail};
use hybrid_ode::continuation::End;
use rtw_engine::files::FileSet;
use rtw_engine::io::markdown::cell;
use rtw_engine::scan::progress::Progress;
use rtw_model::Num;
use rtw_model::cycles::{
    BranchEnd, Diagram, EndKind, EndOptions, Segment, Setting, Step, StepMap, continue_segments,
};
use serde_json::{Value, json};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

/// What the file's `kind` says: a file without it is not this command's.
const KIND: &str = "rtw-scan continuation segments";

/// The segments file beside `out`.
pub(crate) fn segments_path(out: &Path) -> PathBuf {
    out.with_extension("segments.json")
}

/// Refuses to replace a file at the segments path that this command did not
/// write, unless `force`.
pub(crate) fn check_output(out: &Path, force: bool) -> Result<()> {
    let path = segments_path(out);
    if force || !path.exists() {
        return Ok(());
    }
    let ours = std::fs::read_to_string(&path)
        .ok()
        .and_then(|s| serde_json::from_str::<Value>(&s).ok())
        .is_some_and(|v| v["kind"] == KIND);
    if !ours {
        bail!(
            "--out: {} exists and is not a continuation's segments file (--force to replace it)",
            path.display()
        );
    }
    Ok(())
}

/// The segments of one direction from one start.
pub(crate) struct Direction {
    /// +1 / −1: first towards larger or smaller values of the input.
    pub direction: f64,
    /// The period of the branch continued.
    pub period: usize,
    /// Where it starts: the diagram's start, or the last point of a
    /// period-2 branch whose smooth continuation stopped there.
    pub from: Origin,
    /// The value of the input it starts at.
    pub p0: f64,
    /// The segments in order.
    pub segments: Vec<Segment>,
}

/// Where a continued direction starts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Origin {
    /// The diagram's start.
    Start,
    /// The end of the smooth diagram's branch of this index.
    BranchEnd(usize),
}

/// Both directions from the diagram's start, `max` segments each; then each
/// period-2 branch of `diagram` that ended inside the range for want of a
/// smooth continuation ("no continuation"), continued on from its last
/// point. The directions share nothing, so two threads take them in turn;
/// they are returned in that order.
pub(crate) fn run(
    c: &Continuation,
    diagram: &Diagram,
    max: usize,
    progress: &dyn Progress,
) -> Vec<Direction> {
    let s = Setting {
        base: &c.base,
        options: &c.options,
        cycle: &c.cycle,
        param: c.param,
    };
    let start = &diagram.start;
    let p0 = c.base[c.param];
    // Each direction's start: section point, period, input, way, origin.
    let mut jobs = vec![
        (start.orbit[0], start.period, p0, 1.0, Origin::Start),
        (start.orbit[0], start.period, p0, -1.0, Origin::Start),
    ];
    // The switched branches share the start's template
    // (rtw_model::cycles::diagram): a point z is start.orbit[0].with_coords(z).
    for (k, b) in diagram.branches.iter().enumerate() {
        if b.parent.is_none() || b.branch.end != End::StepTooSmall {
            continue;
        }
        // From a few points before its end, so that the segment's own
        // continuation retraces the last stretch and stops where the smooth
        // one did (started at the very end, it has no room for a tangent).
        let pts = &b.branch.points;
        let Some(from) = pts.len().checked_sub(4).map(|i| &pts[i]) else {
            continue;
        };
        let [.., a, last] = &pts[..] else {
            continue;
        };
        if a.p == last.p {
            continue;
        }
        let at = start.orbit[0].with_coords(&from.z);
        jobs.push((
            at,
            b.period,
            from.p,
            (last.p - a.p).signum(),
            Origin::BranchEnd(k),
        ));
    }
    let go = |i: usize| {
        let (at, period, p0, direction, from) = jobs[i];
        Direction {
            direction,
            period,
            from,
            p0,
            segments: continue_segments(
                &s,
                &at,
                period,
                p0,
                direction,
                &c.diagram.continuation,
                &EndOptions::default(),
                max,
            ),
        }
    };
    progress.start(jobs.len() as u64);
    let next = AtomicUsize::new(0);
    let work = || {
        let mut done = Vec::new();
        loop {
            let i = next.fetch_add(1, Ordering::Relaxed);
            if i >= jobs.len() {
                return done;
            }
            done.push((i, go(i)));
            progress.advanced();
        }
    };
    let mut done = std::thread::scope(|scope| {
        let other = scope.spawn(work);
        let mut mine = work();
        mine.extend(
            other
                .join()
                .unwrap_or_else(|e| std::panic::resume_unwind(e)),
        );
        mine
    });
    done.sort_by_key(|(i, _)| *i);
    done.into_iter().map(|(_, d)| d).collect()
}

/// The way a direction is shown in the table: `up` / `down` from the start,
/// or the branch and period it continues.
fn way(d: &Direction) -> String {
    let w = if d.direction > 0.0 { "up" } else { "down" };
    match d.from {
        Origin::Start => w.to_string(),
        Origin::BranchEnd(k) => {
            format!("{w}, branch {k} (period {}) on from {:.5}", d.period, d.p0)
        }
    }
}

/// The step map at `value` of the continued input.
fn map_at(c: &Continuation, value: f64) -> Option<StepMap> {
    let mut p = c.base;
    p[c.param] = value;
    p.validate().ok()?;
    Some(StepMap::new(&p, &c.options, &c.cycle))
}

/// What a segment's end is called in the files: its kind, or the smooth
/// continuation's own end where the segment left the range.
fn end_name(seg: &Segment) -> String {
    match &seg.end {
        Some(e) => e.kind.to_string(),
        None => super::end_name(seg.branch.end).to_string(),
    }
}

/// A one-line account of an end: what touched or coincided.
fn end_detail(e: &BranchEnd) -> String {
    match &e.kind {
        EndKind::Grazing(a) => format!(
            "{} in step {} at t = {:.4} s (closest {:.2e})",
            a.kind,
            a.step + 1,
            a.t,
            a.value
        ),
        EndKind::Corner { first, second, dt } => {
            format!("{} and {} {:.1e} s apart", first, second, dt)
        }
        EndKind::GaitLost => "no orbit of the period past it".into(),
        EndKind::Other => "the sequence changed otherwise".into(),
        EndKind::RangeEnd => "the range ends".into(),
        EndKind::NoChange => "no change of sequence near it".into(),
        EndKind::Fold { multiplier } => format!(
            "the branch turns back (a multiplier at {multiplier:.4}) and the corrector did not pass the fold"
        ),
    }
}

fn radius(m: &[nalgebra::Complex<f64>]) -> f64 {
    hybrid_ode::limit::spectral_radius(m)
}

/// The file's JSON: settings, then per direction and segment its sequence,
/// label, end and points.
pub(crate) fn to_json(c: &Continuation, dirs: &[Direction]) -> Value {
    let directions: Vec<Value> = dirs
        .iter()
        .map(|d| {
            let segments: Vec<Value> = d
                .segments
                .iter()
                .map(|seg| {
                    let n = seg.sequence.section_modes.len();
                    let points: Vec<Value> = seg
                        .branch
                        .points
                        .iter()
                        .map(|pt| {
                            let steps = map_at(c, pt.p).and_then(|m| {
                                let z = seg.template.with_coords(&pt.z);
                                m.iterate(&z, n).ok()
                            });
                            let (freq, label) = match &steps {
                                Some(st) => (
                                    n as f64 / st.iter().map(|s| s.time).sum::<f64>(),
                                    Step::label(st, &c.options.labels).as_str(),
                                ),
                                None => (f64::NAN, ""),
                            };
                            json!({
                                "p": pt.p,
                                "stable": pt.stable,
                                "floquet_max": radius(&pt.multipliers),
                                "step_frequency": freq,
                                "label": label,
                                "omega": seg.template.with_coords(&pt.z).omega(),
                            })
                        })
                        .collect();
                    let end = seg.end.as_ref().map(|e| {
                        json!({
                            "p_old": e.old.p,
                            "p_new": e.p_new,
                            "detail": end_detail(e),
                            "floquet_max_old": radius(&e.old.cycle.multipliers),
                            "floquet_max_new": e.new.as_ref().map(|o| radius(&o.cycle.multipliers)),
                            "jacobian_jump": e.jacobian_jump,
                        })
                    });
                    json!({
                        "period": n,
                        "label": seg.label.as_str(),
                        "sequence": seg.sequence.to_string(),
                        "end": end_name(seg),
                        "end_at": end,
                        "points": points,
                    })
                })
                .collect();
            json!({
                "way": way(d),
                "direction": d.direction,
                "period": d.period,
                "from": match d.from {
                    Origin::Start => json!("start"),
                    Origin::BranchEnd(k) => json!({ "branch_end": k }),
                },
                "p0": d.p0,
                "segments": segments,
            })
        })
        .collect();
    json!({
        "kind": KIND,
        "param": c.param.name(),
        "range": [c.diagram.continuation.p_min, c.diagram.continuation.p_max],
        "start": c.base[c.param],
        "length": c.base.length,
        "directions": directions,
    })
}

/// Writes the segments file beside `out` into `set`.
pub(crate) fn write(
    set: &mut FileSet,
    out: &Path,
    c: &Continuation,
    dirs: &[Direction],
) -> Result<()> {
    let v = to_json(c, dirs);
    set.add_bytes(
        &segments_path(out),
        serde_json::to_string_pretty(&v)?.as_bytes(),
    )
}

/// The segments as a Markdown table for the summary.
pub(crate) fn markdown(c: &Continuation, dirs: &[Direction]) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "\nThrough the changes of mode sequence (`--through`), from {} = {}:\n",
        c.param.name(),
        Num(c.base[c.param])
    );
    s.push_str(
        "| way | segment | gait | mode sequence | from | to | stable on | end | at | what | max\\|μ\\| before → after | Jacobian jump |\n",
    );
    s.push_str("|---|---:|---|---|---|---|---|---|---|---|---|---|\n");
    for d in dirs {
        for (i, seg) in d.segments.iter().enumerate() {
            let pts = &seg.branch.points;
            let (first, last) = (pts[0].p, pts[pts.len() - 1].p);
            let stable: Vec<f64> = pts.iter().filter(|p| p.stable).map(|p| p.p).collect();
            let stable_on = if stable.is_empty() {
                "nowhere".to_string()
            } else {
                let lo = stable.iter().copied().fold(f64::INFINITY, f64::min);
                let hi = stable.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                format!("{lo:.5}–{hi:.5}")
            };
            let (at, what, mu, jump) = match &seg.end {
                Some(e) => (
                    format!("{:.6}", e.old.p),
                    cell(&end_detail(e)),
                    format!(
                        "{:.4} → {}",
                        radius(&e.old.cycle.multipliers),
                        e.new.as_ref().map_or("none".to_string(), |o| format!(
                            "{:.4}",
                            radius(&o.cycle.multipliers)
                        ))
                    ),
                    e.jacobian_jump
                        .map_or("".to_string(), |j| format!("{j:.3}")),
                ),
                None => (
                    format!("{last:.6}"),
                    String::new(),
                    String::new(),
                    String::new(),
                ),
            };
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {first:.5} | {last:.5} | {stable_on} | {} | {at} | {what} | {mu} | {jump} |",
                way(d),
                i,
                seg.label.as_str(),
                cell(&seg.sequence.to_string()),
                end_name(seg).replace('_', " "),
            );
        }
    }
    s
}
