//! The sweep summarized in Markdown: ranges of one gait, where the period
//! changes and where the leading multiplier crosses the unit circle.

use crate::bifurcation::sweep::{PointRow, Sweep};
use rtw_engine::config::variant::ModelChoices;
use std::fmt::Write as _;

/// The bifurcation type a leading multiplier `μ` points to as it reaches the
/// unit circle.
pub(crate) fn crossing_type(re: f64, im: f64) -> &'static str {
    if im.abs() > 1e-9 * (re.hypot(im)).max(1.0) {
        "complex pair (Neimark–Sacker)"
    } else if re < 0.0 {
        "real, negative (period doubling)"
    } else {
        "real, positive (fold)"
    }
}

pub(crate) fn period_str(p: Option<usize>) -> String {
    p.map_or("none".into(), |p| p.to_string())
}

/// Within this distance of the unit circle the leading multiplier names the
/// bifurcation; farther inside, the change of gait is not a local
/// bifurcation of this cycle (another attractor took over, or the grid is
/// too coarse to tell) and the summary says so.
const NEAR_UNIT_CIRCLE: f64 = 0.05;

fn mu_str(r: &PointRow) -> String {
    match (r.mu_re, r.mu_im, r.floquet_max) {
        (Some(re), Some(im), Some(m)) if (m - 1.0).abs() <= NEAR_UNIT_CIRCLE => {
            format!("{re:.3}{im:+.3}i (|μ| = {m:.3}, {})", crossing_type(re, im))
        }
        (Some(re), Some(im), Some(m)) => {
            format!(
                "{re:.3}{im:+.3}i (|μ| = {m:.3}, inside the unit circle: not a local bifurcation at this resolution)"
            )
        }
        _ => "-".into(),
    }
}

/// The sweep summarized: contiguous ranges of (label, period, stable), where
/// the period changes (with the leading multiplier of the last cycle before
/// the change), where `floquet_max` crosses 1, and restarts and timing.
pub(crate) fn summary_markdown(sweep: &Sweep, rows: &[PointRow], wall_time_s: f64) -> String {
    let name = sweep.param.name();
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{} values of {name} from {} to {} (transient {}, record {} steps; step map {:?} rtol {:e}); model: {}",
        rows.len(),
        sweep.values.first().copied().unwrap_or(f64::NAN),
        sweep.values.last().copied().unwrap_or(f64::NAN),
        sweep.transient,
        sweep.record,
        sweep.cycle.method,
        sweep.cycle.rtol,
        ModelChoices::of(&sweep.options),
    );
    let _ = writeln!(s);
    let _ = writeln!(
        s,
        "| {name} from | {name} to | values | label | period | stable | max \\|μ\\| range |"
    );
    let _ = writeln!(s, "|---:|---:|---:|---|---:|---|---|");
    let key = |r: &PointRow| (r.label, r.period, r.stable);
    let mut i = 0;
    while i < rows.len() {
        let mut j = i;
        while j + 1 < rows.len() && key(&rows[j + 1]) == key(&rows[i]) {
            j += 1;
        }
        let seg = &rows[i..=j];
        let mus: Vec<f64> = seg.iter().filter_map(|r| r.floquet_max).collect();
        let range = if mus.is_empty() {
            "-".to_string()
        } else {
            let lo = mus.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = mus.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            format!("{lo:.3} – {hi:.3}")
        };
        let stable = match rows[i].stable {
            Some(true) => "yes",
            Some(false) => "no",
            None => "-",
        };
        let _ = writeln!(
            s,
            "| {:.4} | {:.4} | {} | {} | {} | {stable} | {range} |",
            rows[i].value,
            rows[j].value,
            seg.len(),
            rows[i].label.as_str(),
            period_str(rows[i].period),
        );
        i = j + 1;
    }
    let _ = writeln!(s);
    for w in rows.windows(2) {
        let (a, b) = (&w[0], &w[1]);
        if a.period != b.period {
            let _ = writeln!(
                s,
                "- period {} → {} between {name} = {:.4} and {:.4}; leading multiplier at {:.4}: {}",
                period_str(a.period),
                period_str(b.period),
                a.value,
                b.value,
                a.value,
                mu_str(a),
            );
        }
        // A crossing on one branch: the same period on both sides.
        if let (Some(ma), Some(mb)) = (a.floquet_max, b.floquet_max)
            && a.period == b.period
            && (ma < 1.0) != (mb < 1.0)
        {
            let outside = if mb >= 1.0 { b } else { a };
            let _ = writeln!(
                s,
                "- max |μ| crosses 1 between {name} = {:.4} ({ma:.3}) and {:.4} ({mb:.3}); leading multiplier at {:.4}: {}",
                a.value,
                b.value,
                outside.value,
                mu_str(outside),
            );
        }
    }
    let restarts: Vec<String> = rows
        .iter()
        .filter(|r| r.restarted)
        .map(|r| format!("{:.4}", r.value))
        .collect();
    if !restarts.is_empty() {
        let _ = writeln!(
            s,
            "- restarted from the initial state (continuation failed) at {name} = {}",
            restarts.join(", ")
        );
    }
    let mut times: Vec<f64> = rows.iter().map(|r| r.wall_time_s).collect();
    times.sort_by(f64::total_cmp);
    let median = times.get(times.len() / 2).copied().unwrap_or(0.0);
    let _ = writeln!(
        s,
        "- wall time {wall_time_s:.1} s in all, median {median:.3} s per value"
    );
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crossing_types_follow_the_multiplier() {
        assert_eq!(
            crossing_type(-1.01, 0.0),
            "real, negative (period doubling)"
        );
        assert_eq!(crossing_type(1.01, 0.0), "real, positive (fold)");
        assert_eq!(crossing_type(-0.7, 0.75), "complex pair (Neimark–Sacker)");
    }
}
