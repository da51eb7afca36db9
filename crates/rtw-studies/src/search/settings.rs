//! A design search's config (`rtw-scan design CONFIG`, `rtw.design`): what
//! to maximise, over which box of designs, on which slopes, with how many
//! simulations; read from TOML and checked, each refusal naming its key and
//! the valid range.

use crate::profile::{MAX_GRID_POINTS, MIN_TOL};
use anyhow::{Result, bail};
use rtw_engine::config::choice::{choice, one_of};
use rtw_engine::config::count::count_value;
use rtw_model::{Label, Num, Param};
use serde::{Deserialize, Serialize};

/// Most simulations one search may spend.
pub const MAX_BUDGET: u64 = 10_000_000;
/// Most candidates in one generation.
pub const MAX_BATCH: u64 = 1024;
/// Most weights (sub-searches) of a search with two objectives.
pub const MAX_WEIGHTS: u64 = 64;
/// Most designs reported (each profiled again on the fine grid).
pub const MAX_REPORT: u64 = 100;

/// What a search maximises (or, for `phi_min`, minimises).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Objective {
    /// Width of the widest interval of stable slopes (of `gait`, if set),
    /// rad: maximised.
    SlopeRange,
    /// The shallowest stable slope (of `gait`, if set), rad: minimised.
    PhiMin,
    /// The mean downhill speed at `speed_phi` (m/s), the gait there stable
    /// (and `gait`, if set): maximised.
    Speed,
    /// The mean first-passage time (expected steps to fall) at `mfpt_phi`
    /// on a rough slope of `robustness.sigma` (docs/robustness.md), the gait
    /// there stable (and `gait`, if set): maximised.
    Mfpt,
}

impl Objective {
    /// Every objective, as spelled in a config.
    pub const ALL: [Objective; 4] = [
        Objective::SlopeRange,
        Objective::PhiMin,
        Objective::Speed,
        Objective::Mfpt,
    ];

    /// The name in a config and in the files' columns.
    pub fn as_str(self) -> &'static str {
        match self {
            Objective::SlopeRange => "slope_range",
            Objective::PhiMin => "phi_min",
            Objective::Speed => "speed",
            Objective::Mfpt => "mfpt",
        }
    }
}

/// How candidates are drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Method {
    /// CMA-ES with the learned fall constraint.
    Cmaes,
    /// The designs of a scrambled Sobol sequence in the box, in order: the
    /// baseline a search must beat at equal cost.
    Sobol,
    /// MAP-Elites over the archive's cells (where the design works, how
    /// much of it walks), its variation with the learned fall constraint.
    Archive,
}

impl Method {
    /// Each method by its name in a config.
    pub const NAMES: [(&'static str, Method); 3] = [
        ("cmaes", Method::Cmaes),
        ("sobol", Method::Sobol),
        ("archive", Method::Archive),
    ];
}

/// The design inputs a search varies, in the order of its unit box.
pub const INPUTS: [Param; 4] = [Param::Rho, Param::Alpha, Param::Fn, Param::Zeta];

/// A search's settings, checked.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SearchSettings {
    /// The search's name (its summary's heading).
    pub name: String,
    /// Seed of every draw.
    pub seed: u64,
    /// Simulations to spend: no generation starts once they are spent.
    pub budget: u64,
    /// How candidates are drawn.
    pub method: Method,
    /// Candidates per generation (λ), evaluated in parallel.
    pub batch: u64,
    /// One or two objectives; two give a Pareto front.
    pub objectives: Vec<Objective>,
    /// The gait the objectives are of (`None`: any stable gait).
    pub gait: Option<Label>,
    /// The slope of `speed` (rad), an objective or only measured.
    pub speed_phi: Option<f64>,
    /// The slope of `mfpt` (rad).
    pub mfpt_phi: Option<f64>,
    /// Sub-searches of a two-objective search, one per weight.
    pub weights: u64,
    /// A candidate whose learned fall probability is above this is drawn again.
    pub avoid: f64,
    /// The rod length L (m), fixed.
    pub length: f64,
    /// The box of (ρ, α, f_n, ζ), each `[lo, hi]` (`lo = hi`: fixed).
    pub bounds: [[f64; 2]; 4],
    /// The slope range of every profile.
    pub from: f64,
    /// Its end.
    pub to: f64,
    /// The profiles' coarse grid (rad).
    pub grid: f64,
    /// The profiles' tolerance (rad).
    pub tol: f64,
    /// The reported designs' profiles are made again on this finer grid.
    pub verify_grid: f64,
    /// Most designs reported.
    pub report: u64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Raw {
    name: String,
    seed: toml::Value,
    budget: toml::Value,
    #[serde(default)]
    method: Option<String>,
    #[serde(default)]
    batch: Option<toml::Value>,
    objectives: Vec<String>,
    #[serde(default)]
    gait: Option<String>,
    #[serde(default)]
    speed_phi: Option<f64>,
    #[serde(default)]
    mfpt_phi: Option<f64>,
    #[serde(default)]
    weights: Option<toml::Value>,
    #[serde(default)]
    avoid: Option<f64>,
    #[serde(default)]
    length: Option<f64>,
    #[serde(rename = "box")]
    bounds: RawBox,
    slopes: RawSlopes,
    #[serde(default)]
    report: Option<toml::Value>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawBox {
    rho: [f64; 2],
    alpha: [f64; 2],
    #[serde(rename = "fn")]
    f_n: [f64; 2],
    zeta: [f64; 2],
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSlopes {
    from: f64,
    to: f64,
    #[serde(default)]
    grid: Option<f64>,
    #[serde(default)]
    tol: Option<f64>,
    #[serde(default)]
    verify_grid: Option<f64>,
}

/// `key: value is invalid: must be range`.
fn invalid(key: &str, value: impl std::fmt::Display, range: &str) -> anyhow::Error {
    anyhow::anyhow!("{key}: {value} is invalid: must be {range}")
}

/// The count at `key` (its default when absent), through the project's
/// one count check ([`count_value`]).
fn count(key: &str, v: Option<&toml::Value>, default: u64, lo: u64, hi: u64) -> Result<u64> {
    match v {
        Some(v) => count_value(key, v, lo..=hi, ""),
        None => Ok(default),
    }
}

impl SearchSettings {
    /// The settings of the config file at `path`, each error naming it.
    pub fn read(path: &std::path::Path) -> Result<Self> {
        let text = rtw_engine::config::raw::read_text(path, "design config")?;
        Self::parse(&text).map_err(|e| anyhow::anyhow!("design config {}: {e:#}", path.display()))
    }

    /// The settings of a config's text, every key checked.
    pub fn parse(text: &str) -> Result<Self> {
        let mut table = rtw_engine::config::raw::parse_table(text).map_err(|e| {
            // TOML's integers stop at 2⁶³ − 1; a larger seed is written in quotes.
            if format!("{e:#}").contains("too large") {
                e.context("an integer above 9223372036854775807 (a seed up to 2⁶⁴ − 1) is written in quotes: seed = \"18446744073709551615\"")
            } else {
                e
            }
        })?;
        // The model's options (`[simulation]`) are the options' first layer
        // (`config::layers::simulation_options` reads them), not settings.
        match table.remove("simulation") {
            None | Some(toml::Value::Table(_)) => {}
            Some(_) => {
                bail!("simulation: is not a table: must be [simulation] with the model's keys")
            }
        }
        let raw: Raw = rtw_engine::config::raw::from_value(toml::Value::Table(table), "")?;
        if raw.name.trim().is_empty() || raw.name.len() > 100 {
            bail!(invalid(
                "name",
                format!("{:?}", raw.name),
                "1 to 100 characters"
            ));
        }
        let seed = count_value("seed", &raw.seed, 0..=u64::MAX, "")?;
        let budget = count_value("budget", &raw.budget, 1..=MAX_BUDGET, "")?;
        let method = choice(
            "method",
            raw.method.as_deref().unwrap_or("cmaes"),
            &Method::NAMES,
        )?;
        let batch = count("batch", raw.batch.as_ref(), 8, 2, MAX_BATCH)?;
        let names = Objective::ALL.map(|o| (o.as_str(), o));
        if raw.objectives.is_empty() || raw.objectives.len() > 2 {
            bail!(invalid(
                "objectives",
                format!("{:?}", raw.objectives),
                &format!(
                    "one or two of {}",
                    one_of(&names).trim_start_matches("one of ")
                )
            ));
        }
        let mut objectives = Vec::new();
        for (i, o) in raw.objectives.iter().enumerate() {
            let obj = choice(&format!("objectives[{i}]"), o, &names)?;
            if objectives.contains(&obj) {
                bail!(invalid(
                    &format!("objectives[{i}]"),
                    format!("{o:?}"),
                    "named once"
                ));
            }
            objectives.push(obj);
        }
        let gait = match raw.gait.as_deref() {
            None => None,
            Some(g) => match g.parse::<Label>().ok().filter(|l| l.is_stable()) {
                Some(l) => Some(l),
                None => bail!(invalid(
                    "gait",
                    format!("{g:?}"),
                    "\"walk\", \"skip\" or \"crawl\""
                )),
            },
        };
        let slope_range = Param::Phi.range();
        let slope = |key: &str, v: f64| -> Result<f64> {
            if Param::Phi.check(v).is_ok() {
                Ok(v)
            } else {
                Err(invalid(key, Num(v), slope_range))
            }
        };
        // The slope of an objective measured at one slope: needed when the
        // objective is asked for. The speed may also be measured alone, to
        // place a design on the axes of a front of speed (one run per
        // design); the MFPT is too dear to measure unasked.
        let at = |obj: Objective, key: &str, given: Option<f64>| -> Result<Option<f64>> {
            match (given, objectives.contains(&obj)) {
                (Some(p), true) => Ok(Some(slope(key, p)?)),
                (Some(p), false) if obj == Objective::Speed => Ok(Some(slope(key, p)?)),
                (None, true) => bail!(
                    "{key}: missing: the objective \"{}\" needs the slope it is measured at, {slope_range}",
                    obj.as_str()
                ),
                (Some(_), false) => bail!("{key}: only with the objective \"{}\"", obj.as_str()),
                (None, false) => Ok(None),
            }
        };
        let speed_phi = at(Objective::Speed, "speed_phi", raw.speed_phi)?;
        let mfpt_phi = at(Objective::Mfpt, "mfpt_phi", raw.mfpt_phi)?;
        let weights = match (&raw.weights, objectives.len()) {
            (Some(w), 2) => count("weights", Some(w), 5, 2, MAX_WEIGHTS)?,
            (None, 2) => 5,
            (Some(_), _) => bail!("weights: only with two objectives"),
            (None, _) => 1,
        };
        let avoid = raw.avoid.unwrap_or(0.5);
        if !(avoid > 0.5 - 1e-12 && avoid <= 1.0) {
            bail!(invalid(
                "avoid",
                Num(avoid),
                "in [0.5, 1] (1: no candidate is avoided)"
            ));
        }
        let length = raw.length.unwrap_or(0.8);
        Param::Length
            .check(length)
            .map_err(|_| invalid("length", Num(length), Param::Length.range()))?;
        let b = &raw.bounds;
        let bounds = [b.rho, b.alpha, b.f_n, b.zeta];
        for (p, [lo, hi]) in INPUTS.iter().zip(bounds) {
            let key = format!("box.{}", p.name());
            for v in [lo, hi] {
                if p.check(v).is_err() {
                    bail!(invalid(&key, Num(v), p.range()));
                }
            }
            if lo > hi {
                bail!(invalid(
                    &key,
                    format!("[{}, {}]", Num(lo), Num(hi)),
                    "[lo, hi] with lo ≤ hi"
                ));
            }
        }
        let s = &raw.slopes;
        let from = slope("slopes.from", s.from)?;
        let to = slope("slopes.to", s.to)?;
        if to <= from {
            bail!(invalid(
                "slopes.to",
                Num(to),
                &format!("above slopes.from ({})", Num(from))
            ));
        }
        let span = to - from;
        let grid = s.grid.unwrap_or(0.01);
        let finest = span / MAX_GRID_POINTS;
        if !(grid.is_finite() && grid >= finest && grid <= span) {
            bail!(invalid(
                "slopes.grid",
                Num(grid),
                &format!("in [{}, {}] rad", Num(finest), Num(span))
            ));
        }
        let tol = s.tol.unwrap_or(1e-3);
        if !(tol.is_finite() && (MIN_TOL..=grid).contains(&tol)) {
            bail!(invalid(
                "slopes.tol",
                Num(tol),
                &format!(
                    "in [{}, {}] rad (at most slopes.grid)",
                    Num(MIN_TOL),
                    Num(grid)
                )
            ));
        }
        let verify_grid = s.verify_grid.unwrap_or(grid / 5.0);
        if !(verify_grid.is_finite() && verify_grid >= finest.max(tol) && verify_grid <= grid) {
            bail!(invalid(
                "slopes.verify_grid",
                Num(verify_grid),
                &format!(
                    "in [{}, {}] rad (at least slopes.tol, at most slopes.grid)",
                    Num(finest.max(tol)),
                    Num(grid)
                )
            ));
        }
        let report = count("report", raw.report.as_ref(), 20, 1, MAX_REPORT)?;
        Ok(Self {
            name: raw.name,
            seed,
            budget,
            method,
            batch,
            objectives,
            gait,
            speed_phi,
            mfpt_phi,
            weights,
            avoid,
            length,
            bounds,
            from,
            to,
            grid,
            tol,
            verify_grid,
            report,
        })
    }

    /// The inputs the search varies: indices into [`INPUTS`] whose box is
    /// wider than a point.
    pub(crate) fn free(&self) -> Vec<usize> {
        (0..INPUTS.len())
            .filter(|&i| self.bounds[i][1] > self.bounds[i][0])
            .collect()
    }

    /// The design `[ρ, α, f_n, ζ]` at `u` in the free inputs' unit box.
    pub(crate) fn design_at(&self, u: &[f64]) -> [f64; 4] {
        let mut x = self.bounds.map(|b| b[0]);
        for (&i, &ui) in self.free().iter().zip(u) {
            let [lo, hi] = self.bounds[i];
            x[i] = if ui >= 1.0 { hi } else { lo + ui * (hi - lo) };
        }
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = r#"
name = "widest"
seed = 1
budget = 1000
objectives = ["slope_range"]
[box]
rho = [1.0, 5.0]
alpha = [0.0, 0.4]
fn = [1.5, 5.0]
zeta = [0.05, 0.1]
[slopes]
from = 0.01
to = 0.4
"#;

    #[test]
    fn a_config_reads_with_its_defaults() {
        let s = SearchSettings::parse(GOOD).unwrap();
        assert_eq!(
            (s.method, s.batch, s.weights, s.report),
            (Method::Cmaes, 8, 1, 20)
        );
        assert_eq!((s.grid, s.tol, s.length), (0.01, 1e-3, 0.8));
        assert_eq!(s.free(), [0, 1, 2, 3]);
        let x = s.design_at(&[0.5, 0.5, 0.0, 1.0]);
        assert_eq!(x, [3.0, 0.2, 1.5, 0.1]);
    }

    #[test]
    fn each_bad_key_is_named_with_its_range() {
        let cases = [
            (
                "budget = 1000",
                "budget = 0",
                "budget: 0 is invalid: must be an integer in [1, 10000000]",
            ),
            (
                "objectives = [\"slope_range\"]",
                "objectives = [\"width\"]",
                "objectives[0]: \"width\" is invalid",
            ),
            (
                "objectives = [\"slope_range\"]",
                "objectives = [\"speed\"]",
                "speed_phi: missing",
            ),
            (
                "objectives = [\"slope_range\"]",
                "objectives = [\"slope_range\"]\ngait = \"collapse\"",
                "gait: \"collapse\" is invalid: must be \"walk\", \"skip\" or \"crawl\"",
            ),
            (
                "rho = [1.0, 5.0]",
                "rho = [5.0, 1.0]",
                "box.rho: [5, 1] is invalid",
            ),
            (
                "zeta = [0.05, 0.1]",
                "zeta = [0.05, -0.1]",
                "box.zeta: -0.1 is invalid",
            ),
            (
                "to = 0.4",
                "to = 0.005",
                "slopes.to: 0.005 is invalid: must be above slopes.from (0.01)",
            ),
            (
                "to = 0.4",
                "to = 0.4\ntol = 0.5",
                "slopes.tol: 0.5 is invalid",
            ),
            (
                "seed = 1",
                "seed = 1\nmethod = \"grid\"",
                "method: \"grid\" is invalid: must be one of \"cmaes\", \"sobol\", \"archive\"",
            ),
            (
                "seed = 1",
                "seed = 1\nbatch = 1",
                "batch: 1 is invalid: must be an integer in [2, 1024]",
            ),
            (
                "seed = 1",
                "seed = 1\nspeeed = 2",
                "speeed: unknown key `speeed`",
            ),
        ];
        for (from, to, expected) in cases {
            let text = GOOD.replace(from, to);
            let e = SearchSettings::parse(&text).unwrap_err();
            let msg = format!("{e:#}");
            assert!(msg.contains(expected), "{to}: {msg}");
        }
    }

    #[test]
    fn a_speed_slope_without_the_speed_objective_is_measured_not_searched() {
        // A design placed on a front's axes (the Fig. 7(a) design beside the
        // front of slope range against speed) needs its speed at the front's
        // slope without being searched for it.
        let s =
            SearchSettings::parse(&GOOD.replace("seed = 1", "seed = 1\nspeed_phi = 0.15")).unwrap();
        assert_eq!(
            (s.speed_phi, s.objectives.as_slice()),
            (Some(0.15), [Objective::SlopeRange].as_slice())
        );
        let e = SearchSettings::parse(&GOOD.replace("seed = 1", "seed = 1\nmfpt_phi = 0.15"))
            .unwrap_err();
        assert!(
            format!("{e:#}").contains("mfpt_phi: only with the objective \"mfpt\""),
            "{e:#}"
        );
    }
}
