//! Design search (`rtw-scan design`, Python's `rtw.design`): the design
//! (ρ, α, f_n, ζ) in a box that walks on the widest range of slopes, on the
//! shallowest slope, or fastest at a slope; with two objectives, the Pareto
//! front between them.
//!
//! Each candidate is judged by its slope profile ([`crate::profile`]): the
//! gait along φ with every change of label located by bisection. A design
//! with no stable slope (or none of the gait asked for) is infeasible: it
//! falls. The search does not score a fall with a made-up bad value. Its
//! candidates come from CMA-ES (`cmaes.rs`), which recombines only feasible
//! designs, and a learned model of where designs fall (`fall_model.rs`)
//! sends a candidate back to be drawn again when the designs near it mostly
//! fell. The baseline, `method = "sobol"`, profiles the designs of a
//! scrambled Sobol sequence in the same box at the same cost.
//!
//! Two objectives are searched as `weights` sub-searches, each maximising
//! an augmented Chebyshev scalarisation of the two with its own weight (as
//! MOEA/D and ParEGO decompose a front); the front is the non-dominated set
//! of every feasible design evaluated.
//!
//! A generation's candidates are drawn in order from the seed's stream and
//! profiled in parallel on the worker pool; every draw depends on the seed
//! and the earlier evaluations only, so a search resumed from its stored
//! evaluations replays them and goes on exactly as the uninterrupted one.

pub mod archive;
pub mod budget;
pub mod check;
mod cmaes;
mod columns;
mod fall_model;
pub mod files;
mod identity;
mod propose;
pub mod read;
mod settings;
mod summary;

pub use settings::{INPUTS, Method, Objective, SearchSettings};

use crate::profile::{self, Profile, Settings as ProfileSettings};
use anyhow::{Result, anyhow, bail};
use propose::Proposer;
use rayon::prelude::*;
use rtw_engine::config::params::checked_params;
use rtw_engine::scan::Run;
use rtw_engine::scan::progress::Silent;
use rtw_engine::scan::workers::{Stopped, worker_pool};
use rtw_model::{Label, Options, Params};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::sync::atomic::AtomicBool;

/// Standard gravity (m/s²): speeds are scaled by sqrt(g L) to be weighed
/// against slope widths.
const G: f64 = 9.81;
/// Weight of the sum in the augmented Chebyshev scalarisation.
const AUGMENT: f64 = 0.05;

/// One evaluated design.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Evaluation {
    /// Its place in the order of evaluation.
    pub index: u64,
    /// Its sub-search (weight) of a two-objective search; 0 otherwise.
    pub round: u64,
    /// Its generation within the sub-search.
    pub generation: u64,
    /// `[ρ, α, f_n, ζ]`.
    pub design: [f64; 4],
    /// The learned fall probability when it was drawn (CMA-ES only).
    pub p_fall: Option<f64>,
    /// Simulations spent on it.
    pub runs: u64,
    /// The widest stable interval (of the gait, if one is asked for).
    pub phi_lo: Option<f64>,
    /// Its upper end.
    pub phi_hi: Option<f64>,
    /// The shallowest stable slope (of the gait, if one is asked for).
    pub phi_min: Option<f64>,
    /// The share of its stable slopes (by length) that walk: the archive's
    /// second descriptor (`archive.rs`).
    pub walk_share: Option<f64>,
    /// The label at `speed_phi` (objective `speed`).
    pub label_at_speed_phi: Option<Label>,
    /// The speed there (m/s).
    pub speed: Option<f64>,
    /// The label at `mfpt_phi` (objective `mfpt`).
    pub label_at_mfpt_phi: Option<Label>,
    /// The mean first-passage time there (steps), when the gait is stable.
    pub mfpt: Option<f64>,
    /// Why it is infeasible (`None`: feasible).
    pub infeasible: Option<String>,
    /// The objectives' values, in the config's order (empty when infeasible).
    pub values: Vec<f64>,
    /// The value its sub-search maximised (`None` when infeasible).
    pub score: Option<f64>,
}

impl Evaluation {
    /// Whether it is feasible.
    pub fn feasible(&self) -> bool {
        self.infeasible.is_none()
    }
}

/// A finished (or stopped) search: every evaluation, in order.
#[derive(Clone, Debug)]
pub struct Search {
    /// The settings.
    pub settings: SearchSettings,
    /// Every evaluation, in order.
    pub evaluations: Vec<Evaluation>,
}

impl Search {
    /// Simulations spent.
    pub fn runs(&self) -> u64 {
        self.evaluations.iter().map(|e| e.runs).sum()
    }

    /// The feasible designs that no other feasible design dominates (at
    /// least as good in every objective, better in one), best first in the
    /// first objective; with one objective, the best design.
    pub fn front(&self) -> Vec<&Evaluation> {
        let s = &self.settings;
        let feasible: Vec<&Evaluation> = self.evaluations.iter().filter(|e| e.feasible()).collect();
        let better = |a: &Evaluation| -> Vec<f64> { oriented(s, &a.values) };
        let mut front: Vec<&Evaluation> = feasible
            .iter()
            .copied()
            .filter(|a| {
                let fa = better(a);
                !feasible.iter().any(|b| {
                    let fb = better(b);
                    fb.iter().zip(&fa).all(|(x, y)| x >= y)
                        && fb.iter().zip(&fa).any(|(x, y)| x > y)
                })
            })
            .collect();
        front.sort_by(|a, b| {
            better(b)[0]
                .total_cmp(&better(a)[0])
                .then(a.index.cmp(&b.index))
        });
        // Equal values (the same design found twice): the first found.
        front.dedup_by(|a, b| a.values == b.values);
        front
    }

    /// The feasible designs best first in the first objective (ties: the
    /// first found), each design once.
    pub fn ranked(&self) -> Vec<&Evaluation> {
        let s = &self.settings;
        let mut all: Vec<&Evaluation> = self.evaluations.iter().filter(|e| e.feasible()).collect();
        all.sort_by(|a, b| {
            oriented(s, &b.values)[0]
                .total_cmp(&oriented(s, &a.values)[0])
                .then(a.index.cmp(&b.index))
        });
        let mut seen: Vec<[f64; 4]> = Vec::new();
        all.retain(|e| {
            let new = !seen.contains(&e.design);
            seen.push(e.design);
            new
        });
        all
    }

    /// The best design's evaluation of objective `k` (the largest value, the
    /// smallest for `phi_min`).
    pub fn best(&self, k: usize) -> Option<&Evaluation> {
        self.evaluations
            .iter()
            .filter(|e| e.feasible())
            .max_by(|a, b| {
                oriented(&self.settings, &a.values)[k]
                    .total_cmp(&oriented(&self.settings, &b.values)[k])
                    .then(b.index.cmp(&a.index))
            })
    }
}

/// The objectives' values turned so that larger is better.
fn oriented(s: &SearchSettings, values: &[f64]) -> Vec<f64> {
    s.objectives
        .iter()
        .zip(values)
        .map(|(o, v)| if *o == Objective::PhiMin { -v } else { *v })
        .collect()
}

/// The objectives on a common scale, larger better: slope widths and
/// slopes over the range's span, speeds over sqrt(g L).
fn normalised(s: &SearchSettings, values: &[f64]) -> Vec<f64> {
    let span = s.to - s.from;
    s.objectives
        .iter()
        .zip(values)
        .map(|(o, v)| match o {
            Objective::SlopeRange => v / span,
            Objective::PhiMin => (s.to - v) / span,
            Objective::Speed => v / (G * s.length).sqrt(),
            // Expected steps to fall span decades: their logarithm, a
            // million steps counting as 1.
            Objective::Mfpt => (1.0 + v).log10() / 6.0,
        })
        .collect()
}

/// The value sub-search `round` maximises: the normalised objective, or
/// with two the augmented Chebyshev scalarisation at weight
/// `(round + ½) / weights`.
fn score(s: &SearchSettings, round: u64, values: &[f64]) -> f64 {
    let f = normalised(s, values);
    if f.len() == 1 {
        return f[0];
    }
    let w = (round as f64 + 0.5) / s.weights as f64;
    let (a, b) = (w * f[0], (1.0 - w) * f[1]);
    a.min(b) + AUGMENT * (a + b)
}

/// The profile settings of design `x` over the search's slopes at `grid`.
fn profile_settings(s: &SearchSettings, x: &[f64; 4], grid: f64) -> Result<ProfileSettings> {
    let [rho, alpha, f_n, zeta] = *x;
    Ok(ProfileSettings {
        design: checked_params([s.length, rho, alpha, f_n, zeta, s.from], "")?,
        from: s.from,
        to: s.to,
        tol: s.tol.min(grid),
        grid,
    })
}

/// The intervals the objectives read: the gait's, or every stable one.
fn intervals(s: &SearchSettings, p: &Profile) -> Vec<(f64, f64)> {
    match s.gait {
        Some(g) => p.intervals(g),
        None => p.stable_intervals(),
    }
}

/// The objectives' values of an evaluation, in the config's order, from
/// what its profile gave: `None` when one is undefined (the design falls).
pub(crate) fn values_of(s: &SearchSettings, e: &Evaluation) -> Option<Vec<f64>> {
    s.objectives.iter().map(|o| value_of(s, e, *o)).collect()
}

/// One objective's value of an evaluation (`None`: undefined).
fn value_of(s: &SearchSettings, e: &Evaluation, o: Objective) -> Option<f64> {
    let gait_at = |l: Option<Label>| l.filter(|l| l.is_stable() && s.gait.is_none_or(|g| g == *l));
    match o {
        Objective::SlopeRange => Some(e.phi_hi? - e.phi_lo?),
        Objective::PhiMin => e.phi_min,
        Objective::Speed => gait_at(e.label_at_speed_phi).and(e.speed),
        Objective::Mfpt => gait_at(e.label_at_mfpt_phi).and(e.mfpt),
    }
}

/// What a profile (and the run at `speed_phi`, its label and speed) gives
/// design `x`.
fn judge(
    s: &SearchSettings,
    x: [f64; 4],
    p: &Profile,
    at_speed: Option<(Label, Option<f64>)>,
    at_mfpt: Option<(Label, Option<f64>)>,
) -> Evaluation {
    let iv = intervals(s, p);
    let widest = profile::widest(iv.iter().copied());
    let mut e = Evaluation {
        index: 0,
        round: 0,
        generation: 0,
        design: x,
        p_fall: None,
        runs: p.runs() as u64 + at_speed.is_some() as u64 + at_mfpt.is_some() as u64,
        phi_lo: widest.map(|w| w.0),
        phi_hi: widest.map(|w| w.1),
        phi_min: iv.first().map(|i| i.0),
        walk_share: archive::walk_share(p.segments.iter().map(|g| (g.label, g.lo, g.hi))),
        label_at_speed_phi: at_speed.map(|a| a.0),
        speed: at_speed.and_then(|a| a.1),
        label_at_mfpt_phi: at_mfpt.map(|a| a.0),
        mfpt: at_mfpt.and_then(|a| a.1),
        infeasible: None,
        values: Vec::new(),
        score: None,
    };
    match values_of(s, &e) {
        Some(v) => e.values = v,
        None => {
            let which = s.gait.map_or("stable", |g| g.as_str());
            let at = |key: &str, l: Option<Label>| {
                format!("not {which} at {key} ({})", l.map_or("-", |l| l.as_str()))
            };
            let first = s.objectives.iter().find(|o| value_of(s, &e, **o).is_none());
            e.infeasible = Some(match first {
                Some(Objective::Speed) => at("speed_phi", e.label_at_speed_phi),
                Some(Objective::Mfpt) => at("mfpt_phi", e.label_at_mfpt_phi),
                _ => format!("no {which} slope in [{}, {}]", s.from, s.to),
            });
        }
    }
    e
}

/// The label and `value` of design `params` run at `phi` under `options`;
/// `None` when stopped.
fn run_at(
    params: Params,
    phi: f64,
    options: &Options,
    value: impl Fn(&rtw_model::Outcome) -> Option<f64>,
    cancel: &AtomicBool,
) -> Option<(Label, Option<f64>)> {
    let row = profile::run_at_slope(params, phi, options, cancel)?;
    Some((row.label(), row.outcome.as_ref().and_then(value)))
}

/// Design `x` evaluated: its profile on `grid`, the run at `speed_phi` and
/// the MFPT at `mfpt_phi` (those asked for), under the options
/// [`budget::check`] checked, on the pool the caller installed; `None`
/// when stopped.
fn evaluate(
    s: &SearchSettings,
    options: &Options,
    x: [f64; 4],
    grid: f64,
    cancel: &AtomicBool,
) -> Option<(Evaluation, Profile)> {
    let plain = budget::plain(options);
    let ps = profile_settings(s, &x, grid).expect("the box's designs are valid");
    let p = profile::profile_here(&ps, &plain, &Silent, cancel)?;
    let at_speed = match s.speed_phi {
        Some(phi) => Some(run_at(ps.design, phi, &plain, |o| Some(o.speed), cancel)?),
        None => None,
    };
    let at_mfpt = match s.mfpt_phi {
        Some(phi) => {
            let o = budget::with_mfpt(options);
            let mfpt = |out: &rtw_model::Outcome| Some(out.robustness?.mfpt?.mfpt);
            Some(run_at(ps.design, phi, &o, mfpt, cancel)?)
        }
        None => None,
    };
    Some((judge(s, x, &p, at_speed, at_mfpt), p))
}

/// Runs the search of `s` under `options`, every generation's designs
/// profiled in parallel on `threads` workers. Before any work the options
/// of its runs and its budget are checked ([`budget::check`]) and its cost
/// estimated (`budget::said`: a note, and a warning above the bounds);
/// `progress` counts each generation's designs against its batch (a stage
/// per generation, naming the simulations spent of the budget), and is
/// told what was spent at the end. `earlier` are evaluations stored by
/// an interrupted run of the same settings: they are taken as they are, not
/// run again. After each generation `stored` gets every evaluation so far.
/// Setting `cancel` stops it within moments with the error [`Stopped`],
/// after `stored` got every finished evaluation.
pub fn run(
    s: &SearchSettings,
    options: &Options,
    earlier: &[Evaluation],
    run: &Run,
    stored: &mut dyn FnMut(&[Evaluation]) -> Result<()>,
) -> Result<Search> {
    let (threads, progress, cancel) = (run.threads, run.progress, run.stop);
    budget::check(s, options)?;
    let (said, warning) = budget::said(s, options)?;
    if let Some(w) = warning {
        progress.warn(&w);
    }
    let pool = worker_pool(threads)?;
    let earlier: BTreeMap<u64, &Evaluation> = earlier.iter().map(|e| (e.index, e)).collect();
    let mut said = Some(said);
    let rounds = budget::rounds(s);
    let mut evaluations: Vec<Evaluation> = Vec::new();
    let mut spent = 0u64;
    for round in 0..rounds {
        let until = s.budget * (round + 1) / rounds;
        let mut proposer = Proposer::new(s, round);
        let mut generation = 0;
        while spent < until {
            progress.stage(&format!(
                "design search{}, generation {} ({spent} of {} simulations spent): designs",
                if rounds > 1 {
                    format!(" (weight {} of {rounds})", round + 1)
                } else {
                    String::new()
                },
                generation + 1,
                s.budget
            ));
            progress.start(s.batch);
            // After the start, so that a bar shows it too.
            if let Some(said) = said.take() {
                progress.note(&said);
            }
            let drawn: Vec<(Vec<f64>, Option<f64>)> =
                (0..s.batch).map(|_| proposer.propose(s.avoid)).collect();
            let first = evaluations.len() as u64;
            let results: Vec<Option<Evaluation>> = pool.install(|| {
                drawn
                    .par_iter()
                    .enumerate()
                    .map(|(k, (u, p))| {
                        let index = first + k as u64;
                        let x = s.design_at(u);
                        if let Some(e) = earlier.get(&index) {
                            progress.advanced();
                            return Some((*e).clone());
                        }
                        let (mut e, _) = evaluate(s, options, x, s.grid, cancel)?;
                        e.index = index;
                        e.round = round;
                        e.generation = generation;
                        e.p_fall = *p;
                        e.score = e.feasible().then(|| score(s, round, &e.values));
                        progress.advanced();
                        Some(e)
                    })
                    .collect()
            });
            let stopped = results.iter().any(Option::is_none);
            for (k, e) in results.iter().enumerate() {
                if let Some(e) = e {
                    let x = s.design_at(&drawn[k].0);
                    if e.design != x || e.index != first + k as u64 {
                        bail!(
                            "the stored evaluation {} is of design {:?}, this search draws {:?} \
                             there: the stored evaluations are not this config's",
                            e.index,
                            e.design,
                            x
                        );
                    }
                }
            }
            progress.finish(!stopped);
            if stopped {
                evaluations.extend(results.into_iter().flatten());
                stored(&evaluations)?;
                return Err(anyhow!(Stopped));
            }
            let evals: Vec<Evaluation> = results.into_iter().flatten().collect();
            spent += evals.iter().map(|e| e.runs).sum::<u64>();
            let us: Vec<Vec<f64>> = drawn.into_iter().map(|d| d.0).collect();
            proposer.tell(&us, &evals);
            evaluations.extend(evals);
            stored(&evaluations)?;
            generation += 1;
        }
    }
    let search = Search {
        settings: s.clone(),
        evaluations,
    };
    progress.note(&spent_note(&search));
    Ok(search)
}

/// What a finished search spent against its budget, in words.
fn spent_note(search: &Search) -> String {
    let s = &search.settings;
    let spent = search.runs();
    let past = if spent > s.budget {
        format!(
            ", {} past it: no generation starts once it is spent, and the last one runs whole",
            spent - s.budget
        )
    } else {
        String::new()
    };
    format!(
        "design search: {spent} simulations spent of the budget {} ({} designs){past}",
        s.budget,
        search.evaluations.len()
    )
}

/// A reported design: its search evaluation and its profile made again on
/// the finer `verify_grid`, whose widest interval is the one reported.
#[derive(Clone, Debug)]
pub struct Reported {
    /// The search's evaluation.
    pub found: Evaluation,
    /// The same design judged on the fine profile, its widest interval
    /// (`phi_lo`, `phi_hi`) that of `checked`.
    pub verified: Evaluation,
    /// The fine profile's widest interval checked by direct simulation
    /// ([`check`]); `None` when it has none.
    pub checked: Option<check::Checked>,
}

/// The designs a search reports, each profiled again on `verify_grid` on
/// the worker pool: with two objectives its front, at most `report` of them
/// spread along the first objective; with one, its `report` best designs,
/// best first (the finer profile may cut the best one's interval, and a
/// designer wants the runners-up beside it).
pub fn report(search: &Search, options: &Options, run: &Run) -> Result<Vec<Reported>> {
    let (threads, progress, cancel) = (run.threads, run.progress, run.stop);
    let s = &search.settings;
    let front = if s.objectives.len() == 1 {
        search.ranked()
    } else {
        search.front()
    };
    let k = (s.report as usize).min(front.len());
    let chosen: Vec<&Evaluation> = if s.objectives.len() == 1 {
        front.into_iter().take(k).collect()
    } else if k == front.len() {
        front
    } else {
        (0..k)
            .map(|i| front[i * (front.len() - 1) / (k - 1).max(1)])
            .collect()
    };
    let pool = worker_pool(threads)?;
    progress.stage("verifying the reported designs on the fine grid");
    progress.start(chosen.len() as u64);
    let out: Option<Vec<Reported>> = pool.install(|| {
        chosen
            .par_iter()
            .map(|e| {
                let (mut v, fine) = evaluate(s, options, e.design, s.verify_grid, cancel)?;
                let checked = match (v.phi_lo, v.phi_hi) {
                    (Some(lo), Some(hi)) => {
                        let params = fine.settings.design;
                        let mut c = check::check(
                            params,
                            (lo, hi),
                            &budget::plain(options),
                            s.gait,
                            cancel,
                        )?;
                        // An end is interleaved too when another interval
                        // of the fine profile holds beyond it.
                        let others = intervals(s, &fine);
                        c.beyond_lo |= others.iter().any(|&(_, b)| b < lo);
                        c.beyond_hi |= others.iter().any(|&(a, _)| a > hi);
                        // The interval reported is the checked one.
                        v.phi_lo = Some(c.lo).filter(|x| x.is_finite());
                        v.phi_hi = Some(c.hi).filter(|x| x.is_finite());
                        match values_of(s, &v) {
                            Some(values) => v.values = values,
                            None => {
                                v.values.clear();
                                v.infeasible = Some("no checked stable slope".into());
                            }
                        }
                        Some(c)
                    }
                    _ => None,
                };
                progress.advanced();
                v.index = e.index;
                v.round = e.round;
                v.generation = e.generation;
                v.score = v.feasible().then(|| score(s, e.round, &v.values));
                Some(Reported {
                    found: (*e).clone(),
                    verified: v,
                    checked,
                })
            })
            .collect()
    });
    progress.finish(true);
    out.ok_or_else(|| anyhow!(Stopped))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn settings(objectives: &str, extra: &str) -> SearchSettings {
        SearchSettings::parse(&format!(
            "name = \"t\"\nseed = 3\nbudget = 100\nobjectives = {objectives}\n{extra}\n\
             [box]\nrho = [1.0, 5.0]\nalpha = [0.0, 0.4]\nfn = [1.5, 5.0]\nzeta = [0.05, 0.1]\n\
             [slopes]\nfrom = 0.0\nto = 0.4\n"
        ))
        .unwrap()
    }

    fn eval(index: u64, values: Vec<f64>) -> Evaluation {
        Evaluation {
            index,
            round: 0,
            generation: 0,
            design: [1.0 + index as f64, 1.0, 1.0, 1.0],
            p_fall: None,
            runs: 1,
            phi_lo: None,
            phi_hi: None,
            phi_min: None,
            walk_share: None,
            label_at_speed_phi: None,
            speed: None,
            label_at_mfpt_phi: None,
            mfpt: None,
            infeasible: values.is_empty().then(|| "falls".into()),
            values,
            score: None,
        }
    }

    #[test]
    fn the_front_keeps_the_non_dominated_feasible_designs_with_phi_min_minimised() {
        let s = settings("[\"phi_min\", \"slope_range\"]", "");
        let search = Search {
            settings: s,
            evaluations: vec![
                eval(0, vec![0.05, 0.10]),
                eval(1, vec![0.02, 0.05]),
                eval(2, vec![0.06, 0.10]), // dominated by 0: steeper, no wider
                eval(3, vec![]),           // falls
                eval(4, vec![0.10, 0.30]),
                Evaluation {
                    design: [1.0; 4], // design 0, found again
                    ..eval(5, vec![0.05, 0.10])
                },
            ],
        };
        let front: Vec<u64> = search.front().iter().map(|e| e.index).collect();
        // Best first in phi_min (the smallest).
        assert_eq!(front, [1, 0, 4]);
        // Ranked by phi_min alone: the design found twice (0 and 5) once.
        let ranked: Vec<u64> = search.ranked().iter().map(|e| e.index).collect();
        assert_eq!(ranked, [1, 0, 2, 4]);
        assert_eq!(search.best(0).unwrap().index, 1);
        assert_eq!(search.best(1).unwrap().index, 4);
    }

    #[test]
    fn the_chebyshev_score_weighs_each_objective_by_its_round() {
        let s = settings(
            "[\"slope_range\", \"speed\"]",
            "speed_phi = 0.1\nweights = 2",
        );
        let v = [0.2, 0.5 * (G * 0.8).sqrt()]; // normalised 0.5 and 0.5
        // round 0: w = 1/4: min(0.125, 0.375) + 0.05 × 0.5.
        assert!((score(&s, 0, &v) - (0.125 + 0.025)).abs() < 1e-15);
        assert!((score(&s, 1, &v) - (0.125 + 0.025)).abs() < 1e-15);
        let v = [0.4, 0.0];
        assert!((score(&s, 0, &v) - AUGMENT * 0.25).abs() < 1e-15);
    }
}
