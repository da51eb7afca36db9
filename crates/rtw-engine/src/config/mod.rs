//! Scan configuration: a TOML file → a validated [`ScanConfig`].
//!
//! ```toml
//! name = "paper"            # optional
//! seed = 20240501
//! samples = 1000            # draws per grid point
//! sampling = "random"       # or sobol, halton, lhs, grid, saltelli (sampling);
//!                           # "points" with a [points] table (config::points)
//!
//! [params]                  # each: fixed, uniform range, or grid
//! length = 0.8                          # fixed
//! rho    = { uniform = [1.0, 5.0] }     # uniform on [lo, hi]
//! fn     = { linspace = [2.0, 5.0, 31] } # grid: lo, hi, n points
//! phi    = [0.05, 0.1, 0.15]            # grid: explicit list
//! alpha  = 0.125
//! zeta   = 0.0514
//!
//! [cluster]
//! k = 2                     # default 2
//!
//! [simulation]              # rtw_model::Options, every key of docs/model.md §9
//! t_max = 20.0
//! contact.mu = 0.8
//! ```
//!
//! Unknown keys are refused everywhere, and every error names the key path,
//! the offending value and what is allowed. Every parameter value a scan can
//! produce is checked against docs/model.md §1 up front (fixed values, both ends of
//! a uniform range, every grid point): the valid sets are intervals, so a
//! range whose ends are valid only yields valid samples.

pub mod axis;
pub mod choice;
pub mod count;
pub mod layers;
pub mod params;
pub mod points;
pub mod raw;
pub mod variant;

use crate::hash::fnv1a64;
use crate::sampling::{self, Sampling};
use anyhow::{Context, Result, anyhow, bail};
use axis::Axis;
use raw::{from_value_ranged, parse_table, read_text};
use rtw_model::Param;
use rtw_model::{Num, Options, Params};
use serde::{Deserialize, Serialize};
use std::path::Path;
use std::sync::Arc;

/// The most rows a scan may have (grid points × samples): about 100 TB of
/// Parquet and 10⁴ core-years at the paper scan's speed, far beyond any
/// machine; larger counts are refused up front rather than run out of
/// memory or disk. (`sample_id` itself could count to 2⁶³.)
pub(crate) const MAX_ROWS: u64 = 1_000_000_000_000;

/// The six parameter axes, indexed like [`Param::ALL`].
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawParams {
    length: Axis,
    rho: Axis,
    alpha: Axis,
    #[serde(rename = "fn")]
    f_n: Axis,
    zeta: Axis,
    phi: Axis,
}

/// `[cluster]`: k-means of the failed samples.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ClusterConfig {
    /// Number of clusters.
    pub k: i64,
    /// k-means++ restarts; the best inertia wins.
    pub restarts: i64,
}

impl Default for ClusterConfig {
    fn default() -> Self {
        Self { k: 2, restarts: 10 }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawConfig {
    name: Option<String>,
    seed: u64,
    samples: i64,
    params: RawParams,
    #[serde(default)]
    sampling: Sampling,
    #[serde(default)]
    cluster: ClusterConfig,
    #[serde(default)]
    simulation: Options,
    points: Option<toml::Table>,
}

/// A validated scan configuration.
#[derive(Clone, Debug, PartialEq)]
pub struct ScanConfig {
    /// The scan's name (results go to `runs/NAME/` by default).
    pub name: Option<String>,
    /// Seed of every random draw: a row depends only on (seed, sample_id).
    pub seed: u64,
    /// Draws per grid point (base rows per grid point of a Saltelli design).
    pub samples: u64,
    /// The design of the uniform axes (`sampling = "…"`, default random).
    pub sampling: Sampling,
    /// Parameter axes, indexed like [`Param::ALL`].
    pub params: [Axis; 6],
    /// `[cluster]`: k-means of the failures.
    pub cluster: ClusterConfig,
    /// `[simulation]`: the model's options, validated.
    pub simulation: Options,
    /// `[points]` (with `sampling = "points"`): row `i`'s parameters, given
    /// rather than drawn, as a refinement round stores them ([`points`]).
    pub points: Option<Arc<[Params]>>,
}

/// Reads and validates a config file; errors name the file and the key.
pub fn load(path: &Path) -> Result<ScanConfig> {
    let text = read_text(path, "config")?;
    parse(&text).with_context(|| format!("config {}", path.display()))
}

/// Parses and validates config text.
pub fn parse(text: &str) -> Result<ScanConfig> {
    parse_value(parse_table(text)?)
}

fn parse_value(table: toml::Table) -> Result<ScanConfig> {
    let missing: Vec<&str> = [
        ("seed", "seed"),
        ("samples", "samples"),
        ("params", "[params]"),
    ]
    .into_iter()
    .filter(|(key, _)| !table.contains_key(*key))
    .map(|(_, shown)| shown)
    .collect();
    if !missing.is_empty() {
        let what = if missing.len() == 3 && table.keys().all(|k| k == "simulation") {
            "the config has no scan in it".to_string()
        } else {
            format!("{} missing", missing.join(", "))
        };
        bail!(
            "{what}: a scan config needs `seed = INTEGER`, `samples = INTEGER` (draws per grid point) \
             and a [params] table giving length, rho, alpha, fn, zeta and phi (see configs/paper.toml)"
        );
    }
    let raw: RawConfig = from_value_ranged(toml::Value::Table(table), "", |path| {
        path.strip_prefix("simulation.").and_then(raw::option_range)
    })?;
    if raw.samples < 1 || raw.samples as u64 > MAX_ROWS {
        bail!(
            "samples: {} is invalid: must be an integer >= 1 and at most {MAX_ROWS} (10^12)",
            raw.samples
        );
    }
    let max_k = CLUSTER_MAX_POINTS as i64;
    if !(1..=max_k).contains(&raw.cluster.k) {
        bail!(
            "cluster.k: {} is invalid: must be an integer >= 1 and at most {max_k} (the most failures k-means is run on)",
            raw.cluster.k
        );
    }
    if !(1..=MAX_RESTARTS).contains(&raw.cluster.restarts) {
        bail!(
            "cluster.restarts: {} is invalid: must be an integer >= 1 and at most {MAX_RESTARTS}",
            raw.cluster.restarts
        );
    }
    validate_options(&raw.simulation, "simulation")?;
    let p = raw.params;
    let params = [p.length, p.rho, p.alpha, p.f_n, p.zeta, p.phi];
    for (input, axis) in Param::ALL.into_iter().zip(&params) {
        validate_axis(input, axis)?;
    }
    let points = points::parse(
        raw.points,
        raw.sampling == Sampling::Points,
        raw.samples as u64,
        &params,
    )?;
    let cfg = ScanConfig {
        name: raw.name,
        seed: raw.seed,
        samples: raw.samples as u64,
        sampling: raw.sampling,
        params,
        cluster: raw.cluster,
        simulation: raw.simulation,
        points,
    };
    sampling::check(cfg.sampling, cfg.samples, cfg.uniform_axes()).map_err(|e| anyhow!(e))?;
    cfg.total_rows()?;
    Ok(cfg)
}

/// Most failures k-means (and the silhouette's subsample) is run on, and so
/// the largest `cluster.k`. 20k points in three dimensions pin two or three
/// centres down far more finely than the printed three decimals, and keep
/// the clustering's memory (and time) bounded whatever the scan size.
pub(crate) const CLUSTER_MAX_POINTS: usize = 20_000;

/// Most k-means restarts accepted (`cluster.restarts`): each is a full
/// k-means of up to [`CLUSTER_MAX_POINTS`] points.
pub(crate) const MAX_RESTARTS: i64 = 1000;

/// The one-line model variant of `options` that every file rtw-scan writes
/// records as `rtw.variant`: every open choice of docs/model.md §9, then the
/// run's integrator settings from ` method=` on. rtw-bench states the model
/// of each of its cases with it, so that scripts/check_default_model.py can
/// compare a benchmark called the default model's with the default.
pub fn variant_line(options: &Options) -> String {
    variant::ModelChoices::of(options).to_string()
}

/// Options → validated, the error naming `prefix.key`, the value and the
/// valid range (`simulation.contact.mu: 2 is invalid: must be in [0, 1] or inf`).
pub fn validate_options(options: &Options, prefix: &str) -> Result<()> {
    options.validate().map_err(|e| {
        anyhow!(
            "{prefix}.{}: {} is invalid: must be {}",
            e.field,
            Num(e.value),
            e.range
        )
    })
}

/// Deserializes a `[simulation]` table into validated [`Options`]; an
/// unknown key or a bad value is named as `prefix.key`.
pub fn options_from_table(table: toml::Table, prefix: &str) -> Result<Options> {
    let options: Options = from_value_ranged(toml::Value::Table(table), prefix, raw::option_range)?;
    validate_options(&options, prefix)?;
    Ok(options)
}

fn validate_axis(input: Param, axis: &Axis) -> Result<()> {
    let key = input.name();
    let check = |value: f64, at: &str| {
        input.check(value).map_err(|e| {
            anyhow!(
                "params.{key}{at}: {} is invalid: must be {}",
                Num(e.value),
                e.range
            )
        })
    };
    match axis {
        Axis::Fixed(v) => check(*v, ""),
        Axis::Uniform { lo, hi } => {
            check(*lo, ".uniform[0] (lo)")?;
            check(*hi, ".uniform[1] (hi)")?;
            if lo > hi {
                bail!(
                    "params.{key}.uniform: lo {} > hi {}: must be lo <= hi",
                    Num(*lo),
                    Num(*hi)
                );
            }
            Ok(())
        }
        Axis::Linspace { lo, hi, n } => {
            if *n > MAX_ROWS {
                bail!(
                    "params.{key}.linspace[2] (n): {n} points is invalid: must be at most {MAX_ROWS} (10^12, the most rows a scan may have)"
                );
            }
            check(*lo, ".linspace[0] (lo)")?;
            check(*hi, ".linspace[1] (hi)")
        }
        Axis::List(v) => {
            if v.is_empty() {
                bail!("params.{key}: empty list: give at least one grid point");
            }
            v.iter()
                .enumerate()
                .try_for_each(|(j, x)| check(*x, &format!("[{j}]")))
        }
    }
}

impl ScanConfig {
    /// Number of grid points (product of the grid axes' sizes; 1 without
    /// grid), at most `MAX_ROWS` (10¹²).
    pub fn grid_size(&self) -> Result<u64> {
        let too_many = || {
            anyhow!(
                "params: the grid (the product of the grid axes' point counts: {}) has more than \
                 {MAX_ROWS} points: a scan may have at most {MAX_ROWS} (10^12) rows",
                self.grid_counts()
            )
        };
        self.params.iter().try_fold(1u64, |acc, a| {
            let n = a.grid_len().unwrap_or(1);
            acc.checked_mul(n)
                .filter(|g| *g <= MAX_ROWS)
                .ok_or_else(too_many)
        })
    }

    /// `key n × key n …` of the grid axes, for messages.
    fn grid_counts(&self) -> String {
        Param::ALL
            .iter()
            .zip(&self.params)
            .filter_map(|(i, a)| a.grid_len().map(|n| format!("{} {n}", i.name())))
            .collect::<Vec<_>>()
            .join(" × ")
    }

    /// Number of uniform axes: the dimensions of the sampling design.
    pub fn uniform_axes(&self) -> usize {
        self.params
            .iter()
            .filter(|a| matches!(a, Axis::Uniform { .. }))
            .count()
    }

    /// Rows per grid point: `samples`, times `D + 2` for a Saltelli design
    /// of `D` uniform axes.
    pub fn rows_per_grid_point(&self) -> Option<u64> {
        self.sampling
            .rows_per_grid_point(self.samples, self.uniform_axes())
    }

    /// Rows of the scan: grid points × rows per grid point, at most
    /// `MAX_ROWS` (10¹²).
    pub fn total_rows(&self) -> Result<u64> {
        let grid = self.grid_size()?;
        self.rows_per_grid_point()
            .and_then(|n| grid.checked_mul(n))
            .filter(|rows| *rows <= MAX_ROWS)
            .ok_or_else(|| {
                anyhow!(
                    "samples: {grid} grid points × {} samples is more rows than a scan may have: \
                     at most {MAX_ROWS} (10^12)",
                    self.samples
                )
            })
    }

    /// The resolved config (every simulation option spelled out) as TOML; it
    /// parses back to the same config.
    pub fn to_toml(&self) -> String {
        let mut t = toml::Table::new();
        if let Some(name) = &self.name {
            t.insert("name".into(), name.clone().into());
        }
        t.insert("seed".into(), toml::Value::Integer(self.seed as i64));
        t.insert("samples".into(), toml::Value::Integer(self.samples as i64));
        // Random sampling is not written: the configs (and hashes) of the
        // scans made before designs existed stay what they were.
        if self.sampling != Sampling::Random {
            t.insert("sampling".into(), self.sampling.name().into());
        }
        let params: toml::Table = Param::ALL
            .iter()
            .zip(&self.params)
            .map(|(i, a)| (i.name().to_string(), a.to_toml()))
            .collect();
        t.insert("params".into(), params.into());
        t.insert(
            "cluster".into(),
            toml::Value::try_from(self.cluster).expect("cluster config serializes"),
        );
        t.insert(
            "simulation".into(),
            toml::Value::try_from(self.simulation).expect("options serialize"),
        );
        if let Some(points) = &self.points {
            t.insert(
                "points".into(),
                points::to_toml(points, &self.params).into(),
            );
        }
        toml::to_string(&t).expect("config serializes")
    }

    /// The config hash: `config_hash` of [`Self::to_toml`]. Two runs with
    /// the same hash computed the same rows (given the same rtw-scan version).
    pub fn hash(&self) -> String {
        config_hash(&self.to_toml())
    }

    /// Is this the article's 1000-sample scan (docs/model.md §8: L = 0.8 and the
    /// stated uniform ranges), whatever the sample count, seed or variant?
    pub fn is_paper_scan(&self) -> bool {
        let u = |lo, hi| Axis::Uniform { lo, hi };
        self.params
            == [
                Axis::Fixed(0.8),
                u(1.0, 5.0),
                u(0.0, 0.4),
                u(1.5, 5.0),
                u(0.05, 0.1),
                u(0.05, 0.3),
            ]
    }
}

/// The hash of a resolved config's TOML text, as 16 hex digits.
pub(crate) fn config_hash(toml_text: &str) -> String {
    format!("{:016x}", fnv1a64(toml_text.as_bytes()))
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    pub(crate) const BASE: &str = r#"
seed = 7
samples = 10
[params]
length = 0.8
rho = { uniform = [1, 5] }
alpha = { uniform = [0.0, 0.4] }
fn = { linspace = [2, 5, 4] }
zeta = 0.05
phi = [0.1, 0.2]
"#;

    fn err(text: &str) -> String {
        format!("{:#}", parse(text).unwrap_err())
    }

    #[test]
    fn parses_every_axis_kind() {
        let c = parse(BASE).unwrap();
        assert_eq!(c.seed, 7);
        assert_eq!(c.params[0], Axis::Fixed(0.8));
        assert_eq!(c.params[1], Axis::Uniform { lo: 1.0, hi: 5.0 });
        assert_eq!(
            c.params[3],
            Axis::Linspace {
                lo: 2.0,
                hi: 5.0,
                n: 4
            }
        );
        assert_eq!(c.params[5], Axis::List(vec![0.1, 0.2]));
        assert_eq!(c.grid_size().unwrap(), 8);
        assert_eq!(c.total_rows().unwrap(), 80);
        assert_eq!(c.cluster.k, 2);
        assert_eq!(c.simulation, Options::default());
    }

    #[test]
    fn round_trips_through_toml() {
        let text = format!("{BASE}\n[simulation]\ncontact.mu = 0.8\nstrings.slack = true\n");
        let c = parse(&text).unwrap();
        assert_eq!(c.simulation.contact.mu, 0.8);
        assert_eq!(parse(&c.to_toml()).unwrap(), c);
        // Infinite mu (the default) survives as TOML `inf`.
        let d = parse(BASE).unwrap();
        assert_eq!(parse(&d.to_toml()).unwrap(), d);
    }

    #[test]
    fn errors_name_key_value_and_range() {
        let e = err(&BASE.replace("zeta = 0.05", "zeta = 0.05\nrhoo = 1"));
        assert!(
            e.contains("params.rhoo: unknown key `rhoo`, expected one of `length`"),
            "{e}"
        );
        let e = err(&BASE.replace("[0.0, 0.4]", "[0.0, 0.5]"));
        assert!(
            e.contains("params.alpha.uniform[1] (hi): 0.5 is invalid: must be in [0, 0.49]"),
            "{e}"
        );
        let e = err(&BASE.replace("[1, 5]", "[5, 1]"));
        assert!(e.contains("params.rho.uniform: lo 5 > hi 1"), "{e}");
        let e = err(&BASE.replace("zeta = 0.05", "zeta = nan"));
        assert!(e.contains("params.zeta: NaN is invalid"), "{e}");
        let e = err(&BASE.replace("samples = 10", "samples = -3"));
        assert!(e.contains("samples: -3 is invalid"), "{e}");
        let e = err(&BASE.replace("seed = 7", ""));
        assert!(e.starts_with("seed missing: a scan config needs"), "{e}");
        let e = err(&BASE.replace("phi = [0.1, 0.2]", ""));
        assert!(e.contains("params: missing key `phi`"), "{e}");
        let e = err(&format!("{BASE}\n[simulation]\ncontact.muu = 1\n"));
        assert!(
            e.contains("simulation.contact.muu: unknown key `muu`, expected `mu`"),
            "{e}"
        );
        let e = err(&format!("{BASE}\n[simulation]\ncontact.mu = 2.0\n"));
        assert!(e.contains("simulation.contact.mu: 2 is invalid"), "{e}");
        let e = err(&format!("{BASE}\n[simulation]\nt_max = \"long\"\n"));
        assert!(e.contains("simulation.t_max"), "{e}");
        let e = err(&BASE.replace("phi = [0.1, 0.2]", "phi = []"));
        assert!(e.contains("params.phi: empty list"), "{e}");
        let e = err(&BASE.replace("[0.1, 0.2]", "[0.1, 2.0]"));
        assert!(e.contains("params.phi[1]: 2 is invalid"), "{e}");
        let e = err(&BASE.replace("[2, 5, 4]", "[2, 5, 0]"));
        assert!(e.contains("params.fn") && e.contains("n = 0"), "{e}");
        let e = err(&BASE.replace("length = 0.8", "length = { normal = [1, 2] }"));
        assert!(
            e.contains("params.length") && e.contains("unknown key `normal`"),
            "{e}"
        );
        let e = err(&format!("{BASE}\n[cluster]\nk = 0\n"));
        assert!(e.contains("cluster.k: 0 is invalid"), "{e}");
        let e = err("seed = 1\nsamples = [");
        assert!(e.contains("invalid TOML"), "{e}");
    }

    #[test]
    fn sampling_designs_parse_round_trip_and_change_the_hash() {
        let random = parse(BASE).unwrap();
        assert_eq!(random.sampling, Sampling::Random);
        // Random sampling is not written, so older scans keep their hash.
        assert!(!random.to_toml().contains("sampling"));
        let explicit =
            parse(&BASE.replace("samples = 10", "samples = 10\nsampling = \"random\"")).unwrap();
        assert_eq!(explicit.hash(), random.hash());
        let salt =
            parse(&BASE.replace("samples = 10", "samples = 10\nsampling = \"saltelli\"")).unwrap();
        assert_eq!(salt.sampling, Sampling::Saltelli);
        assert_eq!(parse(&salt.to_toml()).unwrap(), salt);
        assert_ne!(salt.hash(), random.hash());
        // Two uniform axes: 10 base rows × (2 + 2) runs at each of 8 grid points.
        assert_eq!(salt.total_rows().unwrap(), 8 * 10 * 4);
        let e = err(&BASE.replace("samples = 10", "samples = 10\nsampling = \"sobolev\""));
        assert!(
            e.contains("sampling: unknown variant `sobolev`") && e.contains("`saltelli`"),
            "{e}"
        );
        let e = err(&BASE.replace("samples = 10", "samples = 10\nsampling = \"grid\""));
        assert!(
            e.contains("samples: 10 is invalid for sampling = \"grid\" with 2 uniform axes"),
            "{e}"
        );
        let fixed = "seed = 1\nsamples = 4\nsampling = \"sobol\"\n[params]\nlength = 0.8\nrho = 2\n\
                     alpha = 0.1\nfn = 3\nzeta = 0.05\nphi = 0.1\n";
        assert!(err(fixed).contains("needs at least one uniform axis"));
    }

    #[test]
    fn detects_the_paper_scan() {
        let text = r#"
seed = 1
samples = 1000
[params]
length = 0.8
rho = { uniform = [1, 5] }
alpha = { uniform = [0, 0.4] }
fn = { uniform = [1.5, 5] }
zeta = { uniform = [0.05, 0.1] }
phi = { uniform = [0.05, 0.3] }
"#;
        assert!(parse(text).unwrap().is_paper_scan());
        assert!(!parse(BASE).unwrap().is_paper_scan());
    }

    #[test]
    fn config_hash_is_the_fnv1a64_of_the_text_in_16_hex_digits() {
        // FNV-1a 64 of "a" (the FNV test suite of Fowler, Noll and Vo).
        assert_eq!(config_hash("a"), "af63dc4c8601ec8c");
    }

    #[test]
    fn config_hash_follows_the_resolved_config() {
        let text = "seed = 1\nsamples = 4\n[params]\nlength = 0.8\nrho = 2\nalpha = 0.1\n\
                    fn = 3\nzeta = 0.05\nphi = 0.1\n";
        let a = parse(text).unwrap();
        // Keys in another order and a default spelled out resolve to the same config.
        let b = parse(&format!(
            "samples = 4\n{}[simulation]\nt_max = 20.0\n",
            text.replace("samples = 4\n", "")
        ))
        .unwrap();
        assert_eq!(a.hash(), b.hash());
        assert_eq!(a.hash(), config_hash(&a.to_toml()));
        let c = parse(&text.replace("seed = 1", "seed = 2")).unwrap();
        assert_ne!(a.hash(), c.hash());
    }

    #[test]
    fn the_rough_slope_of_a_flat_scan_is_in_its_config() {
        // The steps to fall and the MFPT of a scan on flat ground walk a rough
        // slope drawn from terrain.seed with terrain.patch: two draws are two
        // scans (a resume or a shard must not mix them), and the stored
        // config must rerun the one it describes.
        let text = "seed = 1\nsamples = 4\n[params]\nlength = 0.8\nrho = 2\nalpha = 0.1\n\
                    fn = 3\nzeta = 0.05\nphi = 0.1\n[simulation]\nrobustness.steps_to_fall = true\n";
        let a = parse(text).unwrap();
        for other in ["terrain.seed = 1\n", "terrain.patch = 0.5\n"] {
            let b = parse(&format!("{text}{other}")).unwrap();
            assert_ne!(a.hash(), b.hash(), "{other}");
            assert_eq!(parse(&b.to_toml()).unwrap().hash(), b.hash(), "{other}");
        }
        // The default ground leaves the text as it was before terrain existed.
        assert!(!a.to_toml().contains("terrain"), "{}", a.to_toml());
    }
}
