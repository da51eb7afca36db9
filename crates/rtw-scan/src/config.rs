//! Scan configuration: a TOML file → a validated [`ScanConfig`].
//!
//! ```toml
//! name = "paper"            # optional
//! seed = 20240501
//! samples = 1000            # random draws per grid point
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

use anyhow::{Context, Result, anyhow, bail};
use rtw_model::options::{CannotStand, Damping, InitialShape, LabelOptions, Method};
use rtw_model::{Normalization, Options, Param, ParamError, Params};
use serde::de::{self, Deserializer, MapAccess, SeqAccess, Visitor};
use serde::{Deserialize, Serialize};
use std::fmt;
use std::path::Path;

/// The parameter keys of `[params]`, in the order used everywhere (grid
/// product order, sampling order, column order).
pub const PARAM_KEYS: [&str; 6] = ["length", "rho", "alpha", "fn", "zeta", "phi"];

/// How one parameter is chosen.
#[derive(Clone, Debug, PartialEq)]
pub enum Axis {
    /// The same value for every sample: `alpha = 0.125`.
    Fixed(f64),
    /// Uniform on `[lo, hi]`: `rho = { uniform = [1, 5] }`.
    Uniform { lo: f64, hi: f64 },
    /// `n` evenly spaced grid points from `lo` to `hi` inclusive:
    /// `fn = { linspace = [2, 5, 31] }`.
    Linspace { lo: f64, hi: f64, n: u64 },
    /// Explicit grid points: `length = [0.7, 0.8, 0.9]`.
    List(Vec<f64>),
}

impl Axis {
    /// The grid points of a grid axis (`None` for fixed and uniform axes).
    pub fn grid_points(&self) -> Option<Vec<f64>> {
        match self {
            Axis::Fixed(_) | Axis::Uniform { .. } => None,
            Axis::List(v) => Some(v.clone()),
            Axis::Linspace { lo, hi, n } => Some(linspace(*lo, *hi, *n)),
        }
    }

    /// The number of grid points of a grid axis (`None` for fixed and
    /// uniform axes), without making them: a linspace may have more points
    /// than memory can hold, and is refused by its count alone.
    pub fn grid_len(&self) -> Option<u64> {
        match self {
            Axis::Fixed(_) | Axis::Uniform { .. } => None,
            Axis::List(v) => Some(v.len() as u64),
            Axis::Linspace { n, .. } => Some(*n),
        }
    }

    fn to_toml(&self) -> toml::Value {
        use toml::Value;
        let table = |key: &str, items: Vec<Value>| {
            let mut t = toml::Table::new();
            t.insert(key.into(), Value::Array(items));
            Value::Table(t)
        };
        match self {
            Axis::Fixed(v) => Value::Float(*v),
            Axis::Uniform { lo, hi } => {
                table("uniform", vec![Value::Float(*lo), Value::Float(*hi)])
            }
            Axis::Linspace { lo, hi, n } => table(
                "linspace",
                vec![
                    Value::Float(*lo),
                    Value::Float(*hi),
                    Value::Integer(*n as i64),
                ],
            ),
            Axis::List(v) => Value::Array(v.iter().map(|x| Value::Float(*x)).collect()),
        }
    }
}

/// `n` points from `lo` to `hi`, both included (`n = 1`: just `lo`).
pub fn linspace(lo: f64, hi: f64, n: u64) -> Vec<f64> {
    (0..n).map(|i| linspace_point(lo, hi, n, i)).collect()
}

/// Point `i` (`i < n`) of [`linspace`]`(lo, hi, n)`, computed alone so that a
/// scan never holds its grid in memory.
pub fn linspace_point(lo: f64, hi: f64, n: u64, i: u64) -> f64 {
    if i == 0 {
        lo
    } else if i == n - 1 {
        hi
    } else {
        lo + (hi - lo) * i as f64 / (n - 1) as f64
    }
}

/// The most rows a scan may have (grid points × samples): about 100 TB of
/// Parquet and 10⁴ core-years at the paper scan's speed, far beyond any
/// machine; larger counts are refused up front rather than run out of
/// memory or disk. (`sample_id` itself could count to 2⁶³.)
pub const MAX_ROWS: u64 = 1_000_000_000_000;

impl<'de> Deserialize<'de> for Axis {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct AxisVisitor;
        impl<'de> Visitor<'de> for AxisVisitor {
            type Value = Axis;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str(
                    "a number, a list of numbers, { uniform = [lo, hi] } or { linspace = [lo, hi, n] }",
                )
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Axis, E> {
                Ok(Axis::Fixed(v))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Axis, E> {
                Ok(Axis::Fixed(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Axis, E> {
                Ok(Axis::Fixed(v as f64))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Axis, A::Error> {
                let mut v = Vec::new();
                while let Some(x) = seq.next_element::<f64>()? {
                    v.push(x);
                }
                Ok(Axis::List(v))
            }
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Axis, A::Error> {
                const KINDS: &[&str] = &["uniform", "linspace"];
                let Some(key) = map.next_key::<String>()? else {
                    return Err(de::Error::custom(
                        "empty table: expected { uniform = [lo, hi] } or { linspace = [lo, hi, n] }",
                    ));
                };
                let axis = match key.as_str() {
                    "uniform" => {
                        let [lo, hi] = map.next_value::<[f64; 2]>()?;
                        Axis::Uniform { lo, hi }
                    }
                    "linspace" => {
                        let (lo, hi, n) = map.next_value::<(f64, f64, i64)>()?;
                        if n < 1 {
                            return Err(de::Error::custom(format!(
                                "linspace: n = {n} is invalid: must be an integer >= 1"
                            )));
                        }
                        Axis::Linspace {
                            lo,
                            hi,
                            n: n as u64,
                        }
                    }
                    other => return Err(de::Error::unknown_field(other, KINDS)),
                };
                if let Some(extra) = map.next_key::<String>()? {
                    return Err(de::Error::custom(format!(
                        "unexpected second key `{extra}`: give exactly one of `uniform`, `linspace`"
                    )));
                }
                Ok(axis)
            }
        }
        d.deserialize_any(AxisVisitor)
    }
}

/// The six parameter axes, indexed like [`PARAM_KEYS`].
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
    cluster: ClusterConfig,
    #[serde(default)]
    simulation: Options,
}

/// A validated scan configuration.
#[derive(Clone, Debug, PartialEq)]
pub struct ScanConfig {
    pub name: Option<String>,
    pub seed: u64,
    /// Random draws per grid point.
    pub samples: u64,
    /// Parameter axes, indexed like [`PARAM_KEYS`].
    pub params: [Axis; 6],
    pub cluster: ClusterConfig,
    pub simulation: Options,
}

/// Reads and validates a config file; errors name the file and the key.
pub fn load(path: &Path) -> Result<ScanConfig> {
    let text = read_text(path, "config")?;
    parse(&text).with_context(|| format!("config {}", path.display()))
}

/// Reads a UTF-8 text file, with errors naming what it is (`config`,
/// `variant`) and the path.
pub fn read_text(path: &Path, what: &str) -> Result<String> {
    let bytes =
        std::fs::read(path).with_context(|| format!("cannot read {what} {}", path.display()))?;
    String::from_utf8(bytes).map_err(|e| {
        anyhow!(
            "{what} {} is not valid UTF-8 (invalid byte at offset {})",
            path.display(),
            e.utf8_error().valid_up_to()
        )
    })
}

/// Parses TOML text into a table, keeping toml's line-and-column message.
pub fn parse_table(text: &str) -> Result<toml::Table> {
    text.parse::<toml::Table>()
        .map_err(|e| anyhow!("invalid TOML: {}", e.to_string().trim_end()))
}

/// Deserializes `value` into `T`, naming the key path (`prefix` + the path
/// inside `value`) in any error.
fn from_value<'de, T: Deserialize<'de>>(value: toml::Value, prefix: &str) -> Result<T> {
    serde_path_to_error::deserialize(value).map_err(|e| {
        let path = e.path().to_string();
        let key = match (prefix.is_empty(), path == ".") {
            (true, _) => path,
            (false, true) => prefix.to_string(),
            (false, false) => format!("{prefix}.{path}"),
        };
        // toml's own message may end with "in `table`" lines: the path says it.
        let inner = e.into_inner().to_string();
        let inner = inner
            .lines()
            .filter(|l| !l.starts_with("in `"))
            .collect::<Vec<_>>()
            .join("\n")
            .replace("unknown field", "unknown key")
            .replace("missing field", "missing key");
        if key == "." || key.is_empty() {
            anyhow!("{inner}")
        } else {
            anyhow!("{key}: {inner}")
        }
    })
}

/// Parses and validates config text.
pub fn parse(text: &str) -> Result<ScanConfig> {
    parse_value(parse_table(text)?)
}

/// A model variant file (`configs/variants/*.toml`): a name, what it tests,
/// and the `[simulation]` keys it changes. Layered over a scan config by
/// `rtw-scan run CONFIG --variant FILE`, so one parameter box is scanned
/// under every variant without copying its `[params]`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawVariant {
    name: String,
    #[serde(default)]
    #[allow(dead_code)] // documentation for the reader of the file
    description: String,
    #[serde(default)]
    simulation: toml::Table,
}

/// Loads a scan config, layers a variant file's `[simulation]` keys over its
/// own (the variant wins; the scan is then named `NAME+VARIANT`), then the
/// `--set KEY=VALUE` overrides, and validates the result. Errors name the
/// file and the key.
pub fn load_layered(path: &Path, variant: Option<&Path>, sets: &[String]) -> Result<ScanConfig> {
    let (mut table, mut simulation) = read_split(path)?;
    let suffix = layer_variant_and_sets(&mut simulation, variant, sets)?;
    table.insert("simulation".into(), simulation.into());
    if let Some(suffix) = suffix {
        let base = match table.get("name") {
            Some(toml::Value::String(n)) => n.clone(),
            _ => path
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default(),
        };
        table.insert("name".into(), format!("{base}+{suffix}").into());
    }
    let what = if variant.is_some() || !sets.is_empty() {
        "config (with variant and --set)"
    } else {
        "config"
    };
    parse_value(table).with_context(|| format!("{what} {}", path.display()))
}

/// Layers a variant file's `[simulation]` keys (the variant wins), then the
/// `--set KEY=VALUE` overrides, over the `[simulation]` table `simulation`;
/// returns the variant's name. Errors name the file and the key.
fn layer_variant_and_sets(
    simulation: &mut toml::Table,
    variant: Option<&Path>,
    sets: &[String],
) -> Result<Option<String>> {
    let mut name = None;
    if let Some(vpath) = variant {
        let vt = parse_table(&read_text(vpath, "variant")?)
            .with_context(|| format!("variant {}", vpath.display()))?;
        let v: RawVariant = from_value(toml::Value::Table(vt), "")
            .with_context(|| format!("variant {}", vpath.display()))?;
        merge_tables(simulation, v.simulation);
        name = Some(v.name);
    }
    for s in sets {
        apply_set(simulation, s)?;
    }
    Ok(name)
}

/// The simulation options of a single model (`simulate`, `bifurcation`):
/// the `[simulation]` table of `config_file` (default: the adopted model, docs/model.md §9),
/// then a variant file, then the `--set` overrides, validated.
pub fn simulation_options(
    config_file: Option<&Path>,
    variant: Option<&Path>,
    sets: &[String],
) -> Result<Options> {
    let mut table = match config_file {
        Some(path) => read_split(path)?.1,
        None => toml::Table::new(),
    };
    layer_variant_and_sets(&mut table, variant, sets)?;
    options_from_table(table, "simulation")
}

/// Reads a config file into its top-level table and, taken out of it, its
/// `[simulation]` table (empty when absent). Errors name the file.
pub fn read_split(path: &Path) -> Result<(toml::Table, toml::Table)> {
    let mut table = parse_table(&read_text(path, "config")?)
        .with_context(|| format!("config {}", path.display()))?;
    let simulation = match table.remove("simulation") {
        None => toml::Table::new(),
        Some(toml::Value::Table(s)) => s,
        Some(_) => bail!("config {}: `simulation` is not a table", path.display()),
    };
    Ok((table, simulation))
}

/// Deep-merges `over` into `base`: nested tables merge key by key, any other
/// value replaces the one in `base`.
fn merge_tables(base: &mut toml::Table, over: toml::Table) {
    for (k, v) in over {
        match (base.get_mut(&k), v) {
            (Some(toml::Value::Table(b)), toml::Value::Table(o)) => merge_tables(b, o),
            (_, v) => {
                base.insert(k, v);
            }
        }
    }
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
    let raw: RawConfig = from_value(toml::Value::Table(table), "")?;
    if raw.samples < 1 || raw.samples as u64 > MAX_ROWS {
        bail!(
            "samples: {} is invalid: must be an integer >= 1 and at most {MAX_ROWS} (10^12)",
            raw.samples
        );
    }
    let max_k = crate::cluster::CLUSTER_MAX_POINTS as i64;
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
    for (i, axis) in params.iter().enumerate() {
        validate_axis(i, axis)?;
    }
    let cfg = ScanConfig {
        name: raw.name,
        seed: raw.seed,
        samples: raw.samples as u64,
        params,
        cluster: raw.cluster,
        simulation: raw.simulation,
    };
    cfg.total_rows()?;
    Ok(cfg)
}

/// Most k-means restarts accepted (`cluster.restarts`): each is a full
/// k-means of up to [`crate::cluster::CLUSTER_MAX_POINTS`] points.
pub const MAX_RESTARTS: i64 = 1000;

/// Options → validated, the error naming `prefix.key`.
pub fn validate_options(options: &Options, prefix: &str) -> Result<()> {
    options.validate().map_err(|e| {
        anyhow!(
            "{prefix}.{}: {} is invalid: must be {}",
            e.field,
            e.value,
            e.range
        )
    })
}

/// Deserializes a `[simulation]` table into validated [`Options`].
pub fn options_from_table(table: toml::Table, prefix: &str) -> Result<Options> {
    let options: Options = from_value(toml::Value::Table(table), prefix)?;
    validate_options(&options, prefix)?;
    Ok(options)
}

/// Checks one value of parameter `index` against docs/model.md §1 via
/// [`Params::validate`] (the ranges live in rtw-model only).
pub fn check_param(index: usize, value: f64) -> Result<(), ParamError> {
    Param::ALL[index].check(value)
}

/// The parameter of index `i` (order of [`PARAM_KEYS`]).
pub fn param_mut(p: &mut Params, i: usize) -> &mut f64 {
    match i {
        0 => &mut p.length,
        1 => &mut p.rho,
        2 => &mut p.alpha,
        3 => &mut p.f_n,
        4 => &mut p.zeta,
        5 => &mut p.phi,
        _ => panic!("parameter index {i} out of range"),
    }
}

fn validate_axis(i: usize, axis: &Axis) -> Result<()> {
    let key = PARAM_KEYS[i];
    let check = |value: f64, at: &str| {
        check_param(i, value).map_err(|e| {
            anyhow!(
                "params.{key}{at}: {} is invalid: must be {}",
                e.value,
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
                bail!("params.{key}.uniform: lo {lo} > hi {hi}: must be lo <= hi");
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
    /// grid), at most [`MAX_ROWS`].
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
        PARAM_KEYS
            .iter()
            .zip(&self.params)
            .filter_map(|(k, a)| a.grid_len().map(|n| format!("{k} {n}")))
            .collect::<Vec<_>>()
            .join(" × ")
    }

    /// Rows of the scan: grid points × samples, at most [`MAX_ROWS`].
    pub fn total_rows(&self) -> Result<u64> {
        let grid = self.grid_size()?;
        grid.checked_mul(self.samples)
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
        let params: toml::Table = PARAM_KEYS
            .iter()
            .zip(&self.params)
            .map(|(k, a)| (k.to_string(), a.to_toml()))
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
        toml::to_string(&t).expect("config serializes")
    }

    /// The config hash: [`config_hash`] of [`Self::to_toml`]. Two runs with
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

/// FNV-1a (64-bit) of `bytes`. A fixed algorithm, the same on every machine
/// and in every process (std's hasher is randomly keyed per process, so it
/// could not tell whether shards run on different nodes share a config).
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    const OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
    const PRIME: u64 = 0x0000_0100_0000_01b3;
    bytes
        .iter()
        .fold(OFFSET, |h, b| (h ^ u64::from(*b)).wrapping_mul(PRIME))
}

/// The hash of a resolved config's TOML text, as 16 hex digits.
pub fn config_hash(toml_text: &str) -> String {
    format!("{:016x}", fnv1a64(toml_text.as_bytes()))
}

/// The model variant of docs/model.md §9 that a run used: every open choice.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Variant {
    pub rest_length_ratio: f64,
    /// Friction coefficient; `inf` (no slip) is `null` in JSON, which has no
    /// infinity (the one rule of every JSON rtw-scan writes: a non-finite
    /// number is `null`).
    pub mu: f64,
    pub slack: bool,
    pub damping: Damping,
    pub normalization: Normalization,
    pub initial_shape: InitialShape,
    pub initial_cannot_stand: CannotStand,
    pub initial_omega: f64,
    pub labels: LabelOptions,
    pub method: Method,
    pub rtol: f64,
    pub atol: f64,
    pub t_max: f64,
}

impl Variant {
    pub fn of(o: &Options) -> Self {
        Self {
            rest_length_ratio: o.strings.rest_length_ratio,
            mu: o.contact.mu,
            slack: o.strings.slack,
            damping: o.strings.damping,
            normalization: o.normalization,
            initial_shape: o.initial.shape,
            initial_cannot_stand: o.initial.cannot_stand,
            initial_omega: o.initial.omega,
            labels: o.labels,
            method: o.method,
            rtol: o.rtol,
            atol: o.atol,
            t_max: o.t_max,
        }
    }
}

/// Lower-case name of a unit-variant enum, as serde writes it in configs.
pub fn enum_name<T: Serialize>(v: &T) -> String {
    match toml::Value::try_from(v) {
        Ok(toml::Value::String(s)) => s,
        _ => "?".into(),
    }
}

impl fmt::Display for Variant {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "rest_length_ratio={} mu={} slack={} damping={} normalization={} initial={}(omega={}{}) \
             labels=(flight {} in {} of steps, triple {} in {}) method={} rtol={:e} atol={:e} t_max={}",
            self.rest_length_ratio,
            self.mu,
            self.slack,
            enum_name(&self.damping),
            enum_name(&self.normalization),
            enum_name(&self.initial_shape),
            self.initial_omega,
            match self.initial_shape {
                InitialShape::Settled =>
                    format!(", cannot_stand={}", enum_name(&self.initial_cannot_stand)),
                _ => String::new(),
            },
            self.labels.flight,
            self.labels.flight_steps,
            self.labels.triple,
            self.labels.triple_steps,
            enum_name(&self.method),
            self.rtol,
            self.atol,
            self.t_max
        )
    }
}

/// Applies `KEY=VALUE` overrides to a table. `KEY` is a dotted path
/// (`contact.mu`); `VALUE` is read as a TOML value (`true`, `inf`, `-3`,
/// `"dop853"`), or taken as a bare string when it is not one (`dop853`).
pub fn apply_set(table: &mut toml::Table, assignment: &str) -> Result<()> {
    let (key, value) = assignment
        .split_once('=')
        .ok_or_else(|| anyhow!("--set {assignment:?}: expected KEY=VALUE"))?;
    let (key, value) = (key.trim(), value.trim());
    if value.contains(['\n', '\r']) {
        bail!(
            "--set {key}: the value contains a newline: give one KEY=VALUE per --set (repeat --set for more)"
        );
    }
    let parts: Vec<&str> = key.split('.').collect();
    if parts.iter().any(|p| p.is_empty()) {
        bail!("--set {assignment:?}: empty key segment in {key:?}");
    }
    let parsed = format!("v = {value}")
        .parse::<toml::Table>()
        .ok()
        .and_then(|mut t| t.remove("v"))
        .unwrap_or_else(|| toml::Value::String(value.to_string()));
    let (last, path) = parts.split_last().expect("split yields at least one part");
    let mut t = table;
    for (depth, part) in path.iter().enumerate() {
        let entry = t
            .entry(part.to_string())
            .or_insert_with(|| toml::Value::Table(toml::Table::new()));
        t = entry.as_table_mut().ok_or_else(|| {
            anyhow!(
                "--set {key}: `{}` is not a table",
                parts[..=depth].join(".")
            )
        })?;
    }
    t.insert(last.to_string(), parsed);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    const BASE: &str = r#"
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
    fn linspace_includes_both_ends() {
        assert_eq!(linspace(2.0, 5.0, 4), vec![2.0, 3.0, 4.0, 5.0]);
        assert_eq!(linspace(0.3, 0.1, 1), vec![0.3]);
        let v = linspace(0.05, 0.2, 7);
        assert_eq!((v[0], v[6]), (0.05, 0.2));
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
            e.contains("params.alpha.uniform[1] (hi): 0.5 is invalid: must be in [0, 0.5)"),
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
    fn variant_and_sets_layer_over_the_config() {
        let dir = tempfile::tempdir().unwrap();
        let cfg = dir.path().join("base.toml");
        let text = format!(
            "name = \"box\"\n{BASE}\n[simulation]\nt_max = 5.0\nstrings.slack = true\ncontact.mu = 0.5\n"
        );
        std::fs::write(&cfg, text).unwrap();
        let var = dir.path().join("v.toml");
        std::fs::write(
            &var,
            "name = \"pre\"\ndescription = \"prestress\"\n[simulation]\nstrings.rest_length_ratio = 0.85\ncontact.mu = 0.8\n",
        )
        .unwrap();
        let c = load_layered(&cfg, Some(&var), &["initial.omega=-3".into()]).unwrap();
        assert_eq!(c.name.as_deref(), Some("box+pre"));
        // The variant's keys win, the config's other keys stay (deep merge).
        assert_eq!(c.simulation.strings.rest_length_ratio, 0.85);
        assert!(c.simulation.strings.slack);
        assert_eq!(c.simulation.contact.mu, 0.8);
        assert_eq!(c.simulation.t_max, 5.0);
        assert_eq!(c.simulation.initial.omega, -3.0);
        // Without a variant the file loads as it is.
        assert_eq!(load_layered(&cfg, None, &[]).unwrap(), load(&cfg).unwrap());
        // A bad variant key is named.
        std::fs::write(
            &var,
            "name = \"x\"\n[simulation]\nstrings.rest_length_ratio = 1.5\n",
        )
        .unwrap();
        let e = format!("{:#}", load_layered(&cfg, Some(&var), &[]).unwrap_err());
        assert!(
            e.contains("simulation.strings.rest_length_ratio: 1.5 is invalid"),
            "{e}"
        );
        std::fs::write(&var, "name = \"x\"\nseed = 3\n").unwrap();
        let e = format!("{:#}", load_layered(&cfg, Some(&var), &[]).unwrap_err());
        assert!(
            e.contains("unknown key `seed`") && e.contains("v.toml"),
            "{e}"
        );
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
    fn set_overrides_parse_toml_values_or_bare_strings() {
        let mut t = toml::Table::new();
        for s in [
            "initial.omega=-3",
            "contact.mu=inf",
            "strings.slack=true",
            "method=dop853",
            "normalization=\"eigen\"",
        ] {
            apply_set(&mut t, s).unwrap();
        }
        let o = options_from_table(t.clone(), "simulation").unwrap();
        assert_eq!(o.initial.omega, -3.0);
        assert!(o.contact.mu.is_infinite());
        assert!(o.strings.slack);
        assert_eq!(o.method, Method::Dop853);
        assert_eq!(o.normalization, Normalization::Eigen);
        apply_set(&mut t, "contact.mu=0.8").unwrap();
        assert_eq!(
            options_from_table(t.clone(), "simulation")
                .unwrap()
                .contact
                .mu,
            0.8
        );
        assert!(apply_set(&mut t, "method.x=1").is_err());
        assert!(apply_set(&mut t, "novalue").is_err());
        apply_set(&mut t, "contact.nope=1").unwrap();
        let e = format!("{:#}", options_from_table(t, "simulation").unwrap_err());
        assert!(
            e.contains("simulation.contact.nope: unknown key `nope`"),
            "{e}"
        );
    }

    #[test]
    fn variant_names_every_choice() {
        let v = Variant::of(&Options::literal()).to_string();
        for s in [
            "rest_length_ratio=0",
            "mu=inf",
            "slack=false",
            "damping=along",
            "normalization=supplementary",
            "initial=rigid_star(omega=-2)",
            "method=",
        ] {
            assert!(v.contains(s), "{v} lacks {s}");
        }
    }

    #[test]
    fn fnv1a64_matches_the_published_test_vectors() {
        // Reference values: the FNV test suite of Fowler, Noll and Vo
        // (FNV-1a, 64 bit): "" is the offset basis itself.
        assert_eq!(fnv1a64(b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(fnv1a64(b"a"), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(fnv1a64(b"foobar"), 0x8594_4171_f739_67e8);
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
}
