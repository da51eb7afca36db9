//! What a search will run and what it will cost, checked before any work:
//! the options of each kind of run it makes (the MFPT switched on for its
//! run at `mfpt_phi`, the measures off for the others), each validated as
//! `simulate` validates them; a first generation that would spend far more
//! than the budget refused, naming the keys that set its cost; and the
//! cost of the whole search estimated (simulations, and walker-steps with
//! the MFPT), said before it starts and warned of above
//! [`crate::profile::cost`]'s bounds.

use super::check::SLOPES;
use super::{Method, Objective, SearchSettings, profile_settings};
use crate::profile::cost::{self, Cost};
use anyhow::{Context, Result, bail};
use rtw_engine::config::validate_options;
use rtw_model::{Num, Options};

/// However small the budget, one generation may cost this many
/// simulations (the first generation always runs: `configs/design/fig7a.toml`
/// profiles its one design with `budget = 1`); a generation that costs more
/// than this and than the budget of its sub-search is refused.
pub const GENERATION_ALLOWANCE: u64 = 10_000;

/// The options of the search's profiles and of its run at `speed_phi`: the
/// config's model without the robustness measures, which cost seconds a
/// run and only the `mfpt` objective's run needs.
pub(crate) fn plain(options: &Options) -> Options {
    let mut o = *options;
    o.robustness.step_down = false;
    o.robustness.gsn = false;
    o.robustness.steps_to_fall = false;
    o.robustness.mfpt = false;
    o
}

/// The options of the run at `mfpt_phi`: the plain ones with the MFPT on.
pub(crate) fn with_mfpt(options: &Options) -> Options {
    let mut o = plain(options);
    o.robustness.mfpt = true;
    o
}

/// The simulations one design costs at least on `grid`: its coarse grid,
/// and the runs at `speed_phi` and `mfpt_phi` (those asked for).
fn design_runs(s: &SearchSettings, grid: f64) -> Result<u64> {
    let lowest = s.bounds.map(|b| b[0]);
    let coarse = profile_settings(s, &lowest, grid)?.coarse().len() as u64;
    Ok(coarse + s.speed_phi.is_some() as u64 + s.mfpt_phi.is_some() as u64)
}

/// The sub-searches the budget is shared by: one per weight, but one
/// for the Sobol sequence, which has nothing to weigh.
pub(super) fn rounds(s: &SearchSettings) -> u64 {
    if s.method != Method::Sobol {
        s.weights
    } else {
        1
    }
}

/// Refuses, before any work, a search whose runs' options are invalid (the
/// MFPT's run on a flat slope) or whose first generation would far exceed
/// its budget, naming the keys and what they may be.
pub fn check(s: &SearchSettings, options: &Options) -> Result<()> {
    validate_options(&plain(options), "simulation")?;
    if s.objectives.contains(&Objective::Mfpt) {
        validate_options(&with_mfpt(options), "simulation").context(
            "the objective \"mfpt\" runs each design at mfpt_phi with robustness.mfpt on",
        )?;
    }
    let per = design_runs(s, s.grid)?;
    let generation = s.batch * per;
    let share = s.budget / rounds(s);
    let allowed = share.max(GENERATION_ALLOWANCE);
    if generation <= allowed {
        return Ok(());
    }
    let mut ways = Vec::new();
    if allowed / per >= 2 {
        ways.push(format!("batch in [2, {}]", allowed / per));
    }
    let extra = s.speed_phi.is_some() as u64 + s.mfpt_phi.is_some() as u64;
    let slopes = allowed / s.batch;
    if slopes > extra + 1 {
        let span = s.to - s.from;
        ways.push(format!(
            "slopes.grid at least {} rad",
            Num(span / (slopes - extra - 1) as f64)
        ));
    }
    bail!(
        "budget: {} is invalid for this search: one generation of batch = {} designs costs at \
         least {generation} simulations ({per} a design: the coarse grid of slopes.grid = {} over \
         [{}, {}]{}), more than the budget{} and than {GENERATION_ALLOWANCE}, the most a \
         generation may spend past it: must be at least {}{}",
        s.budget,
        s.batch,
        Num(s.grid),
        Num(s.from),
        Num(s.to),
        if extra > 0 {
            " and the runs at speed_phi or mfpt_phi"
        } else {
            ""
        },
        if rounds(s) > 1 {
            " of a sub-search (budget / weights)"
        } else {
            ""
        },
        generation * rounds(s),
        if ways.is_empty() {
            String::new()
        } else {
            format!(", or set {}", ways.join(", or "))
        }
    )
}

/// The search's cost, estimated before it starts: at most this many
/// designs (every generation costs at least `batch` designs' coarse grids,
/// and none starts once the budget is spent), the budget's simulations and
/// the reported designs' fine profiles and checks, and the MFPT's
/// walker-steps of every design and reported design.
pub fn estimate(s: &SearchSettings, options: &Options) -> Result<(u64, Cost)> {
    let per = design_runs(s, s.grid)?;
    let generation = s.batch * per;
    let share = s.budget / rounds(s);
    let generations = rounds(s) * (share.div_ceil(generation) + 1);
    let designs = generations * s.batch;
    let fine = design_runs(s, s.verify_grid)? + SLOPES as u64;
    let simulations = s.budget + s.report * fine;
    let mfpts = if s.objectives.contains(&Objective::Mfpt) {
        designs + s.report
    } else {
        0
    };
    Ok((
        designs,
        Cost {
            simulations,
            walker_steps: mfpts * cost::mfpt_walker_steps(options),
        },
    ))
}

/// What the search will cost, in words, and a warning when it passes the
/// bounds of [`cost::Cost::warning`].
pub(crate) fn said(s: &SearchSettings, options: &Options) -> Result<(String, Option<String>)> {
    let (designs, c) = estimate(s, options)?;
    let mfpt = if c.walker_steps > 0 {
        format!(
            ", and at most {} MFPTs of {} walker-steps each ({} walker-steps)",
            c.walker_steps / cost::mfpt_walker_steps(options),
            cost::mfpt_walker_steps(options),
            c.walker_steps
        )
    } else {
        String::new()
    };
    let text = format!(
        "design search: budget {} simulations (at most {designs} designs, in generations of {}; \
         the last may pass the budget by one generation), then {} reported designs profiled \
         again and checked: about {} simulations{mfpt}",
        s.budget, s.batch, s.report, c.simulations
    );
    Ok((text, c.warning("the design search")))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn settings(extra: &str, slopes: &str) -> SearchSettings {
        SearchSettings::parse(&format!(
            "name = \"t\"\nseed = 3\n{extra}\nobjectives = [\"slope_range\"]\n\
             [box]\nrho = [1.0, 5.0]\nalpha = [0.0, 0.4]\nfn = [1.5, 5.0]\nzeta = [0.05, 0.1]\n\
             [slopes]\n{slopes}\n"
        ))
        .unwrap()
    }

    #[test]
    fn a_first_generation_far_past_the_budget_is_refused_and_a_small_one_runs() {
        // The repro: 1024 designs of 100 001 slopes, budget 1.
        let s = settings(
            "budget = 1\nbatch = 1024",
            "from = -1.5\nto = 1.5\ngrid = 3e-5\ntol = 1e-9\nverify_grid = 3e-5",
        );
        let e = check(&s, &Options::default()).unwrap_err().to_string();
        for want in [
            "budget: 1 is invalid",
            "102401024 simulations",
            "slopes.grid at least 0.375 rad",
        ] {
            assert!(e.contains(want), "{want:?} not in {e}");
        }
        // configs/design/fig7a.toml's one generation of two profiles, budget 1.
        let s = settings(
            "budget = 1\nbatch = 2",
            "from = 0.01\nto = 0.8\ngrid = 0.01",
        );
        check(&s, &Options::default()).unwrap();
        let (designs, c) = estimate(&s, &Options::default()).unwrap();
        assert_eq!(designs, 4);
        assert_eq!(c.walker_steps, 0);
        assert!(c.warning("x").is_none());
    }
}
