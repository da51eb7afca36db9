//! A diagram summarized in Markdown: its branches with where they are
//! stable and why they end, its bifurcations, its curves.

use super::Continuation;
use super::files::Rows;
use rtw_engine::config::variant::ModelChoices;
use std::fmt::Write as _;

/// The ranges of value over which a branch's points are stable, in branch
/// order (a range per run of stable points).
fn stable_ranges(points: &[(f64, bool)]) -> Vec<(f64, f64)> {
    let mut out: Vec<(f64, f64)> = Vec::new();
    let mut open: Option<(f64, f64)> = None;
    for &(v, stable) in points {
        match (stable, open.as_mut()) {
            (true, Some(r)) => r.1 = v,
            (true, None) => open = Some((v, v)),
            (false, Some(_)) => out.extend(open.take()),
            (false, None) => {}
        }
    }
    out.extend(open);
    out
}

fn range_str(r: &[(f64, f64)]) -> String {
    if r.is_empty() {
        return "nowhere".into();
    }
    r.iter()
        .map(|(a, b)| format!("{:.5}–{:.5}", a.min(*b), a.max(*b)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The summary of a diagram.
pub(crate) fn summary_markdown(
    c: &Continuation,
    start_period: usize,
    start_floquet: f64,
    rows: &Rows,
    branches: usize,
    wall_time_s: f64,
) -> String {
    let name = c.param.name();
    let o = &c.diagram.continuation;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "Continuation in {name} over [{}, {}] from the period-{start_period} gait at {name} = {} \
         (max|μ| {start_floquet:.4}); step map {:?} rtol {:e}; model: {}; {:.1} s",
        o.p_min,
        o.p_max,
        c.base[c.param],
        c.cycle.method,
        c.cycle.rtol,
        ModelChoices::of(&c.options),
        wall_time_s,
    );
    s.push('\n');
    s.push_str("| branch | period | from | points | values | stable on | end |\n|---|---:|---|---:|---|---|---|\n");
    for b in 0..branches {
        let pts: Vec<(f64, bool)> = rows.points_of(b).collect();
        let (Some(first), Some(last)) = (pts.first(), pts.last()) else {
            continue;
        };
        let period = rows.period_of(b).unwrap_or(0);
        let from = rows.parent_of(b).map_or("the start".to_string(), |p| {
            format!("period doubling on branch {p}")
        });
        let end = rows
            .special_of(b)
            .filter(|k| k.0.starts_with("end_"))
            .map(|k| k.0.trim_start_matches("end_").replace('_', " "))
            .next()
            .unwrap_or_default();
        let _ = writeln!(
            s,
            "| {b} | {period} | {from} | {} | {:.5} → {:.5} | {} | {end} |",
            pts.len(),
            first.0,
            last.0,
            range_str(&stable_ranges(&pts))
        );
    }
    s.push_str("\n| branch | bifurcation | value | critical multiplier |\n|---:|---|---|---|\n");
    for b in 0..branches {
        for (kind, v, re, im) in rows.special_of(b) {
            if kind == "start" || kind.starts_with("end_") {
                continue;
            }
            let _ = writeln!(
                s,
                "| {b} | {} | {v:.6} | {re:.4}{im:+.4}i |",
                kind.replace('_', " ")
            );
        }
    }
    if let Some(cs) = c.curve {
        let _ = writeln!(
            s,
            "\nCurves in ({name}, {}) over {} ∈ [{}, {}]:\n",
            cs.param.name(),
            cs.param.name(),
            cs.range.0,
            cs.range.1
        );
        s.push_str("| curve | kind | from branch | direction | first point | last point | points | end |\n|---:|---|---:|---:|---|---|---:|---|\n");
        for c in rows.curve_spans() {
            let _ = writeln!(
                s,
                "| {} | {} | {} | {:+} | ({:.5}, {:.4}) | ({:.5}, {:.4}) | {} | {} |",
                c.curve,
                c.kind.replace('_', " "),
                c.branch,
                c.direction,
                c.first.0,
                c.first.1,
                c.last.0,
                c.last.1,
                c.points,
                c.end.trim_start_matches("end_").replace('_', " ")
            );
        }
    }
    s
}
