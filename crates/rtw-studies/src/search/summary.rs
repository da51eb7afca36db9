//! A design search's summary, `search.md`: its settings, its cost, how
//! often it drew a design that fell, and the reported designs.

use super::{Evaluation, Method, Reported, Search};
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
        "- {} designs evaluated in {} simulations (budget {}); {} infeasible ({:.1} %)\n",
        search.evaluations.len(),
        search.runs(),
        s.budget,
        falls,
        100.0 * falls as f64 / search.evaluations.len().max(1) as f64
    );
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
