//! A design search's summary, `search.md`: its settings, its cost, how
//! often it drew a design that fell, and the reported designs.

use super::{Evaluation, Method, Objective, Reported, Search, oriented};
use std::fmt::Write;

/// The summary's first line, before the search's name: how a folder's
/// `search.md` is known as a search's.
pub(super) const HEADING: &str = "# Design search ";

/// The width of a design's walking slope interval.
pub(super) fn width(e: &Evaluation) -> Option<f64> {
    Some(e.phi_hi? - e.phi_lo?)
}

fn opt(v: Option<f64>) -> String {
    v.map_or("–".into(), |v| format!("{v:.4}"))
}

/// The search's summary: its settings, its cost, how often it drew a design
/// that fell, and the reported designs with their verified intervals.
pub fn markdown(search: &Search, reported: &[Reported]) -> String {
    let s = &search.settings;
    let mut m = String::new();
    let objectives: Vec<&str> = s.objectives.iter().map(|o| o.as_str()).collect();
    let _ = writeln!(m, "{HEADING}{}\n", s.name);
    let method = match s.method {
        Method::Cmaes => "CMA-ES with the learned fall constraint",
        Method::Sobol => "Sobol designs (baseline)",
        Method::Archive => "MAP-Elites archive with the learned fall constraint",
    };
    let _ = writeln!(
        m,
        "- objectives: {} (gait: {}); method: {method}; seed {}",
        objectives.join(", "),
        s.gait.map_or("any stable", |g| g.as_str()),
        s.seed
    );
    let _ = writeln!(
        m,
        "- slopes [{}, {}] rad, grid {}, tol {}; reported designs verified on grid {}",
        s.from, s.to, s.grid, s.tol, s.verify_grid
    );
    let falls = search.evaluations.iter().filter(|e| !e.feasible()).count();
    let _ = writeln!(
        m,
        "- {} designs evaluated in {} simulations (budget {}); {} infeasible ({:.1} %)",
        search.evaluations.len(),
        search.runs(),
        s.budget,
        falls,
        100.0 * falls as f64 / search.evaluations.len().max(1) as f64
    );
    let (coverage, qd) = super::archive::coverage_and_qd(s, &search.evaluations);
    let _ = writeln!(
        m,
        "- archive (`archive.parquet`): {:.0} % of its {} × {} cells filled (the widest \
         interval's middle slope × the share that walks), QD-score {qd:.3}\n",
        100.0 * coverage,
        super::archive::SLOPE_BINS,
        super::archive::WALK_BINS,
    );
    if !reported.is_empty() {
        let _ = writeln!(m, "{}\n", order(search, reported));
    }
    let _ = writeln!(
        m,
        "| index | ρ | α | f_n | ζ | phi_lo | phi_hi | slope range | phi_min | speed | mfpt | search's slope range |"
    );
    let _ = writeln!(
        m,
        "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    );
    for r in reported {
        let e = &r.verified;
        let _ = writeln!(
            m,
            "| {} | {:.3} | {:.4} | {:.3} | {:.4} | {} | {} | {} | {} | {} | {} | {} |",
            e.index,
            e.design[0],
            e.design[1],
            e.design[2],
            e.design[3],
            opt(e.phi_lo),
            opt(e.phi_hi),
            opt(width(e)),
            opt(e.phi_min),
            opt(e.speed),
            e.mfpt.map_or("–".into(), |v| format!("{v:.1}")),
            opt(width(&r.found))
        );
    }
    m
}

/// The table's column of an objective's verified value.
fn column(o: Objective) -> &'static str {
    match o {
        Objective::SlopeRange => "slope range",
        Objective::PhiMin => "phi_min",
        Objective::Speed => "speed",
        Objective::Mfpt => "mfpt",
    }
}

/// What the rows' order is. They come in the search's order (its own values,
/// from the coarse profile), which the verification on the fine grid may
/// not keep: a reader who reads the verified columns would otherwise take
/// row 1 for the best of them. Said, not re-sorted, so that the summary,
/// `designs.parquet` and the design page number the designs alike.
fn order(search: &Search, reported: &[Reported]) -> String {
    let s = &search.settings;
    let first = s.objectives[0];
    let best = if first == Objective::PhiMin {
        "smallest"
    } else {
        "largest"
    };
    let rows = if s.objectives.len() == 1 {
        format!(
            "Rows: the search's {} best designs by its own {} (its coarse profile), best first",
            reported.len(),
            first.as_str()
        )
    } else {
        format!(
            "Rows: designs of the search's Pareto front of {}, by its own values (its coarse \
             profile), spread along {} from the best",
            s.objectives
                .iter()
                .map(|o| o.as_str())
                .collect::<Vec<_>>()
                .join(" and "),
            first.as_str()
        )
    };
    let verified = reported
        .iter()
        .filter(|r| r.verified.feasible() && !r.verified.values.is_empty())
        .max_by(|a, b| {
            oriented(s, &a.verified.values)[0]
                .total_cmp(&oriented(s, &b.verified.values)[0])
                .then(b.verified.index.cmp(&a.verified.index))
        });
    match verified {
        Some(r) => format!(
            "{rows}; verified on the fine grid they may rank otherwise: the {best} verified {} \
             is index {}'s.",
            column(first),
            r.verified.index
        ),
        None => format!("{rows}; none is stable once verified on the fine grid."),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::search::SearchSettings;

    fn eval(index: u64, lo: f64, hi: f64) -> Evaluation {
        Evaluation {
            index,
            round: 0,
            generation: 0,
            design: [1.0 + index as f64, 0.1, 3.0, 0.06],
            p_fall: None,
            runs: 1,
            phi_lo: Some(lo),
            phi_hi: Some(hi),
            phi_min: Some(lo),
            walk_share: None,
            label_at_speed_phi: None,
            speed: None,
            label_at_mfpt_phi: None,
            mfpt: None,
            infeasible: None,
            values: vec![hi - lo],
            score: Some(hi - lo),
        }
    }

    #[test]
    fn the_summary_says_its_rows_are_in_the_search_s_order_and_which_verified_best() {
        let settings = SearchSettings::parse(
            "name = \"t\"\nseed = 3\nbudget = 100\nobjectives = [\"slope_range\"]\n\
             [box]\nrho = [1.0, 5.0]\nalpha = [0.0, 0.4]\nfn = [1.5, 5.0]\nzeta = [0.05, 0.1]\n\
             [slopes]\nfrom = 0.0\nto = 0.4\n",
        )
        .unwrap();
        // The search's best (index 4, 0.30 wide) is cut to 0.10 on the fine
        // grid; its runner-up (index 7, 0.25) keeps 0.20.
        let reported = vec![
            Reported {
                found: eval(4, 0.05, 0.35),
                verified: eval(4, 0.05, 0.15),
                checked: None,
            },
            Reported {
                found: eval(7, 0.10, 0.35),
                verified: eval(7, 0.10, 0.30),
                checked: None,
            },
        ];
        let search = Search {
            settings,
            evaluations: reported.iter().map(|r| r.found.clone()).collect(),
        };
        let md = markdown(&search, &reported);
        assert!(
            md.contains("Rows: the search's 2 best designs by its own slope_range"),
            "{md}"
        );
        assert!(
            md.contains("the largest verified slope range is index 7's."),
            "{md}"
        );
        // Said before the table, whose first row stays the search's best.
        let (said, table) = md.split_once("| index |").unwrap();
        assert!(said.contains("Rows:"), "{md}");
        assert!(table.lines().nth(2).unwrap().starts_with("| 4 |"), "{md}");
    }
}
