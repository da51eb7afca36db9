//! Rows and their Parquet, JSON and text forms.
//!
//! One table, [`COLUMNS`], defines every column of a scan row: its name,
//! type, nullability and how to read it from a [`Row`]. The Parquet schema,
//! the record batches, `simulate --json` and the `simulate` text table are all
//! generated from it, so they cannot drift apart.
//!
//! Parquet files are written through [`ParquetFile`]: to a temporary file in
//! the destination's directory, closed, synced and renamed into place, so a
//! file at its final name is always complete. `outcome` is a dictionary
//! column with signed `Int32` keys over the fixed label list
//! [`Label::ALL`] (pandas and polars read it as categorical); floats are
//! `Float64`, counts `Int64`; compression is zstd.

use crate::cluster::{Failure, FailureClusters};
use crate::config::{ScanConfig, Variant};
use crate::dictionary;
use anyhow::{Context, Result, anyhow, bail};
use arrow_array::cast::AsArray;
use arrow_array::types::{Float64Type, Int8Type, Int32Type, Int64Type};
use arrow_array::{
    Array, ArrayRef, DictionaryArray, Float64Array, Int8Array, Int32Array, Int64Array, RecordBatch,
    StringArray,
};
use arrow_schema::{DataType, Field, Schema, SchemaRef};
use parquet::arrow::ArrowWriter;
use parquet::arrow::arrow_reader::{ParquetRecordBatchReader, ParquetRecordBatchReaderBuilder};
use parquet::basic::{Compression, ZstdLevel};
use parquet::file::metadata::KeyValue;
use parquet::file::properties::WriterProperties;
use parquet::schema::types::ColumnPath;
use rtw_model::outcome::FailureDetail;
use rtw_model::{Label, Outcome, Params, Physical, TraceSample};
use serde::ser::{Serialize, SerializeMap, Serializer};
use std::collections::BTreeMap;
use std::fs::File;
use std::path::{Path, PathBuf};
use std::sync::{Arc, LazyLock};

/// Metadata key: the resolved scan config as TOML.
pub const META_CONFIG: &str = "rtw.config";
/// Metadata key: rtw-scan's version.
pub const META_VERSION: &str = "rtw.version";
/// Metadata key: the scan seed.
pub const META_SEED: &str = "rtw.seed";
/// Metadata key: one-line model variant summary ([`crate::config::Variant`]).
pub const META_VARIANT: &str = "rtw.variant";
/// Metadata key: seconds spent computing the rows (summed over resumed
/// sessions and, in a merged file, over the shards).
pub const META_WALL_TIME: &str = "rtw.wall_time_s";
/// Metadata key: seconds spent computing one chunk (chunk files only).
pub const META_CHUNK_WALL_TIME: &str = "rtw.chunk_wall_time_s";
/// Metadata key: [`ScanConfig::hash`] of the config in [`META_CONFIG`].
pub const META_CONFIG_HASH: &str = "rtw.config_hash";
/// Metadata key: the shard a part file holds, `K/N` (part files only).
pub const META_SHARD: &str = "rtw.shard";
/// Metadata key: the rows of the whole scan, all shards together (part files only).
pub const META_TOTAL_ROWS: &str = "rtw.total_rows";
/// Metadata key: how many shards a merged file was made of.
pub const META_SHARDS: &str = "rtw.shards";
/// Metadata key: [`ContentHash`] of the file's rows, written with them and
/// checked by every read ([`open`]), so a corrupt page is refused.
pub const META_CONTENT_HASH: &str = "rtw.content_hash";

/// Most rows per row group of a file rtw-scan writes whole (samples, part
/// and assignments files). One row group per 256-row chunk made the footer
/// grow with N (391 row groups at 100k rows, held in memory by the writer
/// and again by every reader); with this cap a 100k-row file has 13. The
/// writer buffers at most one row group, and since a column's 8192 numbers
/// (64 kB) fit in one page, a reader decompresses at most one row group's
/// worth of each column at a time: larger groups (16384 was measured) cost
/// a few MB more peak memory in `run` and `summary` for nothing.
pub const MAX_ROW_GROUP_ROWS: usize = 8192;

/// Rows per batch when a scan file is read back (merge, checks, summary,
/// clustering): bounds the decoded rows in memory whatever the row groups.
pub const READ_BATCH_ROWS: usize = 4096;

/// A key-value metadata entry.
pub fn kv(key: &str, value: String) -> KeyValue {
    KeyValue::new(key.to_string(), value)
}

/// The file metadata of a scan's Parquet files: config, its hash, version,
/// seed, variant.
pub fn scan_metadata(cfg: &ScanConfig) -> Vec<KeyValue> {
    vec![
        kv(META_CONFIG, cfg.to_toml()),
        kv(META_CONFIG_HASH, cfg.hash()),
        kv(META_VERSION, env!("CARGO_PKG_VERSION").to_string()),
        kv(META_SEED, cfg.seed.to_string()),
        kv(META_VARIANT, Variant::of(&cfg.simulation).to_string()),
    ]
}

/// What an rtw-scan Parquet file holds, told by the metadata it carries.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FileKind {
    /// Scan rows: `samples.parquet`, `part-K.parquet`, chunks (`rtw.config`).
    Scan,
    /// `cluster --assignments` (`rtw.clusters`).
    Assignments,
    /// `simulate --trace` (`rtw.params` and `rtw.options`).
    Trace,
    /// `bifurcation` per-value and per-step files (`rtw.bifurcation.param`).
    Bifurcation,
}

impl FileKind {
    /// The kind of a file with metadata `meta`, if rtw-scan wrote it.
    pub fn of(meta: &BTreeMap<String, String>) -> Option<Self> {
        if meta.contains_key(crate::bifurcation::META_PARAM) {
            Some(Self::Bifurcation)
        } else if meta.contains_key(META_CLUSTERS) {
            Some(Self::Assignments)
        } else if meta.contains_key(META_CONFIG) {
            Some(Self::Scan)
        } else if meta.contains_key("rtw.options") {
            Some(Self::Trace)
        } else {
            None
        }
    }

    fn describe(self) -> &'static str {
        match self {
            Self::Scan => "a scan (rows of `rtw-scan run`)",
            Self::Assignments => "cluster assignments (`cluster --assignments`)",
            Self::Trace => "a trace (`simulate --trace`)",
            Self::Bifurcation => "a bifurcation sweep (`bifurcation`)",
        }
    }
}

/// Refuses, unless `force`, to write a `kind` file at `dest` (given by the
/// option `flag`) when `dest` is one of the command's `inputs`, or exists and
/// is not a file of the same kind (another kind of rtw-scan file, another
/// Parquet file, or not a Parquet file at all). A file of the same kind is
/// the command's own earlier output and may be replaced.
pub fn check_destination(
    dest: &Path,
    kind: FileKind,
    inputs: &[&Path],
    flag: &str,
    force: bool,
) -> Result<()> {
    if force || !dest.exists() {
        return Ok(());
    }
    let shown = dest.display();
    let same = |a: &Path| match (a.canonicalize(), dest.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    };
    if let Some(input) = inputs.iter().find(|i| same(i)) {
        bail!(
            "{flag} {shown}: that is its own input {}: writing there would replace it; choose \
             another file, or pass --force",
            input.display()
        );
    }
    if dest.is_dir() {
        bail!("{flag} {shown}: is a directory");
    }
    let found = match open(dest, 1) {
        Err(_) => "a file that is not a Parquet file".to_string(),
        Ok(input) => match FileKind::of(&input.metadata) {
            Some(k) if k == kind => return Ok(()),
            Some(k) => format!("{} (from its metadata)", k.describe()),
            None => "a Parquet file rtw-scan did not write".to_string(),
        },
    };
    bail!(
        "{flag} {shown}: holds {found}, not {}: refusing to write over it; choose another file, \
         or pass --force to replace it",
        kind.describe()
    )
}

/// A scan named for messages: `config hash H (name N, seed S)`.
pub fn scan_label(hash: &str, name: Option<&str>, seed: u64) -> String {
    match name {
        Some(n) => format!("config hash {hash} (name {n}, seed {seed})"),
        None => format!("config hash {hash} (seed {seed})"),
    }
}

/// [`scan_label`] of a scan file from its metadata.
pub fn scan_label_of(meta: &BTreeMap<String, String>) -> String {
    let hash = meta.get(META_CONFIG_HASH).map_or("(none)", String::as_str);
    match meta.get(META_CONFIG).map(|c| crate::config::parse(c)) {
        Some(Ok(c)) => scan_label(hash, c.name.as_deref(), c.seed),
        _ => format!("config hash {hash}"),
    }
}

/// One scan row: a sample's inputs, derived parameters and outcome.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    pub sample_id: u64,
    pub params: Params,
    pub physical: Physical,
    /// `None` when the simulation panicked (the row is then `diverged`).
    pub outcome: Option<Outcome>,
    /// Why a sample became `diverged` without an outcome (panic message).
    pub message: Option<String>,
    pub wall_time_s: f64,
}

impl Row {
    pub fn label(&self) -> Label {
        self.outcome.map_or(Label::Diverged, |o| o.label)
    }
}

/// How a column reads its value from a row.
#[derive(Clone, Copy)]
pub enum Get {
    F64(fn(&Row) -> Option<f64>),
    I64(fn(&Row) -> Option<i64>),
    Str(fn(&Row) -> Option<&str>),
    /// The outcome label, dictionary-encoded.
    Label,
}

/// One column of the scan table.
pub struct Column {
    pub name: &'static str,
    /// Section of the `simulate` text table.
    pub group: &'static str,
    pub nullable: bool,
    /// Unit (`1`: dimensionless, `-`: not a quantity), written to the Arrow
    /// field metadata and docs/data-dictionary.md ([`crate::dictionary`]).
    pub unit: &'static str,
    pub description: &'static str,
    pub get: Get,
}

/// A float column of `group`.
const fn float(
    name: &'static str,
    group: &'static str,
    nullable: bool,
    unit: &'static str,
    description: &'static str,
    get: fn(&Row) -> Option<f64>,
) -> Column {
    Column {
        name,
        group,
        nullable,
        unit,
        description,
        get: Get::F64(get),
    }
}
const fn input(
    name: &'static str,
    unit: &'static str,
    description: &'static str,
    get: fn(&Row) -> Option<f64>,
) -> Column {
    float(name, "input", false, unit, description, get)
}
const fn derived(
    name: &'static str,
    unit: &'static str,
    description: &'static str,
    get: fn(&Row) -> Option<f64>,
) -> Column {
    float(name, "derived", false, unit, description, get)
}
/// Null when the sample panicked.
const fn metric(
    name: &'static str,
    unit: &'static str,
    description: &'static str,
    get: fn(&Row) -> Option<f64>,
) -> Column {
    float(name, "metric", true, unit, description, get)
}
const fn count(
    name: &'static str,
    group: &'static str,
    description: &'static str,
    get: fn(&Row) -> Option<i64>,
) -> Column {
    Column {
        name,
        group,
        nullable: true,
        unit: "1",
        description,
        get: Get::I64(get),
    }
}

/// Every column of a scan row, in file order. Metrics and counts are null in
/// a row whose sample panicked (its `message` says why).
pub static COLUMNS: &[Column] = &[
    Column {
        name: "sample_id",
        group: "id",
        nullable: false,
        unit: "-",
        description: "sample index; the row depends only on (seed, sample_id)",
        get: Get::I64(|r| Some(r.sample_id as i64)),
    },
    input("length", "m", "rod length L", |r| Some(r.params.length)),
    input("rho", "kg/m", "mass per length ρ of a rod", |r| {
        Some(r.params.rho)
    }),
    input(
        "alpha",
        "1",
        "connection ratio α: each string end sits α·L from a rod's tip",
        |r| Some(r.params.alpha),
    ),
    input(
        "fn",
        "Hz",
        "eigen-frequency f_n of the normalization (docs/model.md §1; the true mode is √3·f_n, §7)",
        |r| Some(r.params.f_n),
    ),
    input("zeta", "1", "damping ratio ζ of the normalization", |r| {
        Some(r.params.zeta)
    }),
    input("phi", "rad", "slope angle φ", |r| Some(r.params.phi)),
    derived("m", "kg", "rod mass m = ρ L", |r| Some(r.physical.m)),
    derived(
        "l_c",
        "m",
        "connection offset from each tip l_c = α L",
        |r| Some(r.physical.l_c),
    ),
    derived(
        "inertia",
        "kg·m²",
        "rod inertia about its centre I = m L²/12",
        |r| Some(r.physical.inertia),
    ),
    derived("r", "m", "connection radius r = L/2 − l_c", |r| {
        Some(r.physical.r)
    }),
    derived("k", "N/m", "string stiffness k", |r| Some(r.physical.k)),
    derived("c", "N·s/m", "string damping coefficient c", |r| {
        Some(r.physical.c)
    }),
    Column {
        name: "outcome",
        group: "outcome",
        nullable: false,
        unit: "-",
        description: "gait (skip, walk, crawl) or failure (collapse, stall, diverged), docs/model.md §5",
        get: Get::Label,
    },
    Column {
        name: "failure",
        group: "outcome",
        nullable: true,
        unit: "-",
        description: "why the run failed (rod_down, com_low, no_standing_equilibrium, standing_rod_down, \
                      standing_com_low, standing_rolls_away, no_touchdown, no_progress, non_finite, \
                      step_underflow, work_budget, zeno); null for a gait",
        get: Get::Str(|r| r.outcome.and_then(|o| o.failure).map(|f| f.as_str())),
    },
    Column {
        name: "message",
        group: "outcome",
        nullable: true,
        unit: "-",
        description: "the error message of a sample that panicked (outcome diverged), else what its \
                      failure means in words; null for a gait",
        // A panic's message, else what the failure means in words.
        get: Get::Str(|r| {
            r.message.as_deref().or_else(|| {
                r.outcome
                    .and_then(|o| o.failure)
                    .map(FailureDetail::describe)
            })
        }),
    },
    Column {
        name: "start",
        group: "outcome",
        nullable: true,
        unit: "-",
        description: "how the star stood before the push: two_feet, three_feet (static equilibrium), \
                      rest_shape (not in equilibrium), docs/model.md §6",
        get: Get::Str(|r| r.outcome.map(|o| o.start.as_str())),
    },
    metric(
        "t_end",
        "s",
        "simulated time at the end of the run (t_max unless it failed or settled early)",
        |r| r.outcome.map(|o| o.t_end),
    ),
    metric(
        "nlsp",
        "1",
        "fraction of the analysis window with no foot on the ground (flight)",
        |r| r.outcome.map(|o| o.fractions.nlsp),
    ),
    metric(
        "slsp",
        "1",
        "fraction of the analysis window with one rod on the ground",
        |r| r.outcome.map(|o| o.fractions.slsp),
    ),
    metric(
        "dlsp",
        "1",
        "fraction of the analysis window with two rods on the ground",
        |r| r.outcome.map(|o| o.fractions.dlsp),
    ),
    metric(
        "tlsp",
        "1",
        "fraction of the analysis window with three rods on the ground",
        |r| r.outcome.map(|o| o.fractions.tlsp),
    ),
    count(
        "window_steps",
        "metric",
        "whole steps (one new foot's touchdown to the next) in the analysis window",
        |r| r.outcome.map(|o| o.step_shares.steps as i64),
    ),
    metric(
        "flight_steps",
        "1",
        "share of the window's steps whose own flight fraction exceeds labels.flight (docs/model.md §5)",
        |r| r.outcome.map(|o| o.step_shares.flight),
    ),
    metric(
        "triple_steps",
        "1",
        "share of the window's steps whose own triple-support fraction exceeds labels.triple",
        |r| r.outcome.map(|o| o.step_shares.triple),
    ),
    count(
        "touchdowns",
        "metric",
        "touchdowns over the whole run",
        |r| r.outcome.map(|o| o.touchdowns as i64),
    ),
    metric(
        "f_w",
        "Hz",
        "step frequency: touchdowns per second over the analysis window",
        |r| r.outcome.map(|o| o.f_w),
    ),
    metric(
        "f_w_newfoot",
        "Hz",
        "touchdowns of a tip other than the one that rod last landed on, per second over the analysis window",
        |r| r.outcome.map(|o| o.f_w_newfoot),
    ),
    metric(
        "speed",
        "m/s",
        "mean downhill speed of the centre of mass over the analysis window",
        |r| r.outcome.map(|o| o.speed),
    ),
    metric(
        "mu_required",
        "1",
        "largest |λ_x|/λ_y while a rod sticks with λ_y > 0.05 m g, over the analysis window (docs/model.md §4)",
        |r| r.outcome.map(|o| o.mu_required),
    ),
    metric(
        "slide_time",
        "s",
        "rod-seconds spent sliding over the whole run",
        |r| r.outcome.map(|o| o.slide_time),
    ),
    metric(
        "energy_initial",
        "J",
        "total energy at the start (kinetic, string and gravity potential)",
        |r| r.outcome.map(|o| o.energy.initial),
    ),
    metric(
        "energy_last",
        "J",
        "total energy at the end of the run",
        |r| r.outcome.map(|o| o.energy.last),
    ),
    metric(
        "energy_gravity_released",
        "J",
        "potential energy of gravity released over the run",
        |r| r.outcome.map(|o| o.energy.gravity_released),
    ),
    metric(
        "energy_impact_loss",
        "J",
        "energy lost in touchdown impacts",
        |r| r.outcome.map(|o| o.energy.impact_loss),
    ),
    metric(
        "energy_damping_loss",
        "J",
        "energy dissipated by the string dampers",
        |r| r.outcome.map(|o| o.energy.damping_loss),
    ),
    metric(
        "energy_friction_loss",
        "J",
        "work of sliding friction (finite μ only)",
        |r| r.outcome.map(|o| o.energy.friction_loss),
    ),
    metric(
        "energy_balance_error",
        "J",
        "energy_last + the three losses − energy_initial: zero up to integration error",
        |r| r.outcome.map(|o| o.energy.balance_error),
    ),
    // From the step map's Newton solution when the run asked for its limit
    // cycle (`limit_cycle = true`) and one was found, else from the
    // touchdown return times.
    count(
        "period",
        "metric",
        "period of the gait in steps (0: none found); from the step map with limit_cycle = true, \
         else from the touchdown return map",
        |r| {
            r.outcome
                .map(|o| i64::from(o.cycle.map_or(o.period, |c| c.period)))
        },
    ),
    metric(
        "floquet_max",
        "1",
        "largest Floquet multiplier modulus of the gait's limit cycle (< 1: stable); null unless limit_cycle = true found one",
        |r| r.outcome.and_then(|o| o.cycle).map(|c| c.floquet_max),
    ),
    metric(
        "cycle_residual",
        "1",
        "scaled Newton residual |Pⁿ(z) − z| of the limit cycle's fixed point; null as floquet_max",
        |r| r.outcome.and_then(|o| o.cycle).map(|c| c.residual),
    ),
    count("steps", "work", "accepted integrator steps", |r| {
        r.outcome.map(|o| o.work.steps as i64)
    }),
    count("rejected", "work", "rejected integrator steps", |r| {
        r.outcome.map(|o| o.work.rejected as i64)
    }),
    count(
        "rhs_evals",
        "work",
        "right-hand-side evaluations (the machine-independent work)",
        |r| r.outcome.map(|o| o.work.rhs_evals as i64),
    ),
    count(
        "events",
        "work",
        "events located (touchdowns, lift-offs, mode switches)",
        |r| r.outcome.map(|o| o.work.events as i64),
    ),
    Column {
        name: "wall_time_s",
        group: "work",
        nullable: false,
        unit: "s",
        description: "wall-clock time of this sample's simulation (machine-dependent)",
        get: Get::F64(|r| Some(r.wall_time_s)),
    },
];

/// The Arrow type of the `outcome` column: dictionary with signed keys.
pub fn label_type() -> DataType {
    DataType::Dictionary(Box::new(DataType::Int32), Box::new(DataType::Utf8))
}

static SCHEMA: LazyLock<SchemaRef> = LazyLock::new(|| {
    let fields: Vec<Field> = COLUMNS
        .iter()
        .map(|c| {
            let ty = match c.get {
                Get::F64(_) => DataType::Float64,
                Get::I64(_) => DataType::Int64,
                Get::Str(_) => DataType::Utf8,
                Get::Label => label_type(),
            };
            dictionary::field(c.name, ty, c.nullable, c.unit, c.description)
        })
        .collect();
    Arc::new(Schema::new(fields))
});

/// The Arrow schema of scan rows.
pub fn schema() -> SchemaRef {
    SCHEMA.clone()
}

/// Position of a label in [`Label::ALL`]: its dictionary key in the
/// `outcome` column and its slot in per-label counts.
pub fn label_index(label: Label) -> usize {
    Label::ALL
        .iter()
        .position(|l| *l == label)
        .expect("every label is in Label::ALL")
}

/// Labels as a dictionary array over the fixed value list [`Label::ALL`].
fn label_array(labels: impl Iterator<Item = Label>) -> ArrayRef {
    let keys: Int32Array = labels.map(|l| label_index(l) as i32).collect();
    let values = StringArray::from_iter_values(Label::ALL.iter().map(|l| l.as_str()));
    Arc::new(DictionaryArray::<Int32Type>::try_new(keys, Arc::new(values)).expect("keys in range"))
}

/// Rows → one record batch in [`schema`].
pub fn to_batch(rows: &[Row]) -> RecordBatch {
    let arrays: Vec<ArrayRef> = COLUMNS
        .iter()
        .map(|c| match c.get {
            Get::F64(g) => Arc::new(rows.iter().map(g).collect::<Float64Array>()) as ArrayRef,
            Get::I64(g) => Arc::new(rows.iter().map(g).collect::<Int64Array>()),
            Get::Str(g) => Arc::new(rows.iter().map(g).collect::<StringArray>()),
            Get::Label => label_array(rows.iter().map(Row::label)),
        })
        .collect();
    RecordBatch::try_new(schema(), arrays).expect("rows match the schema")
}

/// A row as one flat JSON object, keys in column order (`outcome` is the
/// label string; absent metrics and non-finite floats are `null`).
pub struct JsonRow<'a>(pub &'a Row);

impl Serialize for JsonRow<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let r = self.0;
        let mut map = s.serialize_map(Some(COLUMNS.len()))?;
        for c in COLUMNS {
            match c.get {
                Get::F64(g) => map.serialize_entry(c.name, &g(r).filter(|v| v.is_finite()))?,
                Get::I64(g) => map.serialize_entry(c.name, &g(r))?,
                Get::Str(g) => map.serialize_entry(c.name, &g(r))?,
                Get::Label => map.serialize_entry(c.name, r.label().as_str())?,
            }
        }
        map.end()
    }
}

/// A row as a readable two-column table, grouped by section.
pub fn to_text(r: &Row) -> String {
    let mut out = String::new();
    let mut group = "";
    for c in COLUMNS {
        if c.group != group {
            group = c.group;
            out.push_str(&format!("[{group}]\n"));
        }
        let value = match c.get {
            Get::F64(g) => g(r).map(|v| format!("{v:.6}")),
            Get::I64(g) => g(r).map(|v| v.to_string()),
            Get::Str(g) => g(r).map(str::to_string),
            Get::Label => Some(r.label().as_str().to_string()),
        };
        out.push_str(&format!(
            "  {:<24} {}\n",
            c.name,
            value.as_deref().unwrap_or("-")
        ));
    }
    out
}

/// Writer properties for files of `schema`: zstd, row groups of at most
/// `max_rows`, the given key-value metadata, and dictionary encoding only for
/// the string and label columns. Numbers are plain-encoded: a scan's floats
/// are all distinct, so a dictionary would not shrink them, yet each
/// column's dictionary builder holds every value of the row group in memory
/// (about 10 MB more at 16k-row groups of scan rows). Pages keep their
/// default size limit: with smaller pages a column's page is compressed
/// before the row group ends, and every column then holds its own zstd
/// context (about 0.5 MB each) at once (measured: 12 MB more at 10k rows).
pub fn writer_properties(
    schema: &Schema,
    max_rows: usize,
    metadata: Vec<KeyValue>,
) -> WriterProperties {
    schema
        .fields()
        .iter()
        .filter(|f| f.data_type().is_numeric())
        .fold(WriterProperties::builder(), |b, f| {
            b.set_column_dictionary_enabled(ColumnPath::from(f.name().as_str()), false)
        })
        .set_compression(Compression::ZSTD(
            ZstdLevel::try_new(3).expect("valid zstd level"),
        ))
        .set_max_row_group_row_count(Some(max_rows.max(1)))
        .set_key_value_metadata(Some(metadata))
        .build()
}

/// A temporary file next to `dest` (same directory, so a rename moves it
/// into place atomically), named `.NAME.XXXXXX.tmp`, with the usual
/// permissions (0666 less the umask) rather than tempfile's 0600.
fn temp_file_for(dest: &Path) -> Result<Temp> {
    let file = named_temp_for(dest)?;
    let guard = Registered::new(file.path().to_path_buf());
    Ok(Temp { file, guard })
}

/// A temporary file, known to [`remove_live_files`] until it is dropped or
/// moved into place.
struct Temp {
    file: tempfile::NamedTempFile,
    guard: Registered,
}

impl Temp {
    fn persist(self, dest: &Path) -> Result<()> {
        let Temp { file, guard } = self;
        file.persist(dest)
            .with_context(|| format!("cannot move the finished file to {}", dest.display()))?;
        drop(guard);
        Ok(())
    }
}

/// Files that exist only while a command runs (temporary files, locks):
/// removed by [`remove_live_files`] when a signal ends the process at once.
static LIVE: std::sync::Mutex<Vec<PathBuf>> = std::sync::Mutex::new(Vec::new());

/// Registers a path in [`LIVE`] for as long as it lives.
pub(crate) struct Registered(PathBuf);

impl Registered {
    pub(crate) fn new(path: PathBuf) -> Self {
        if let Ok(mut live) = LIVE.lock() {
            live.push(path.clone());
        }
        Self(path)
    }
}

impl Drop for Registered {
    fn drop(&mut self) {
        if let Ok(mut live) = LIVE.lock()
            && let Some(i) = live.iter().rposition(|p| *p == self.0)
        {
            live.swap_remove(i);
        }
    }
}

/// Removes every temporary and lock file this process has open: called by
/// the signal handler before it exits, since a process ending in
/// `std::process::exit` runs no destructors.
pub fn remove_live_files() {
    let live = match LIVE.try_lock() {
        Ok(live) => live.clone(),
        // Held by a thread that will never resume: read it anyway.
        Err(std::sync::TryLockError::Poisoned(p)) => p.into_inner().clone(),
        Err(std::sync::TryLockError::WouldBlock) => {
            std::thread::sleep(std::time::Duration::from_millis(50));
            LIVE.lock().map(|l| l.clone()).unwrap_or_default()
        }
    };
    for p in live {
        let _ = std::fs::remove_file(p);
    }
}

/// Removes the temporary files `.NAME.XXXXXX.tmp` that an earlier, killed
/// writer of `dest` left beside it (never anything else). Call it only while
/// no other process can be writing `dest` (under its [`Lock`]).
pub fn remove_stray_temps(dest: &Path) -> Result<()> {
    let dir = dest
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let Some(name) = dest.file_name().and_then(|n| n.to_str()) else {
        return Ok(());
    };
    let prefix = format!(".{name}.");
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Ok(());
    };
    for entry in entries.flatten() {
        let n = entry.file_name();
        let n = n.to_string_lossy();
        if n.starts_with(&prefix) && n.ends_with(".tmp") && n.len() == prefix.len() + 10 {
            std::fs::remove_file(entry.path())
                .with_context(|| format!("cannot remove {}", entry.path().display()))?;
        }
    }
    Ok(())
}

/// An exclusive lock on writing one result (`DIR/.NAME.lock` for `DIR/NAME`),
/// held by one process at a time; the file names the holder's PID. The
/// operating system releases it when the process ends, however it ends, so a
/// killed run never leaves a stale lock; the file itself is removed on drop.
pub struct Lock {
    _file: File,
    path: PathBuf,
    _live: Registered,
}

impl Lock {
    /// The lock file of the result `dest`.
    pub fn path_for(dest: &Path) -> PathBuf {
        let name = dest.file_name().and_then(|n| n.to_str()).unwrap_or("out");
        dest.with_file_name(format!(".{name}.lock"))
    }

    /// Takes the lock of `dest`, or says which process holds it; `doing`
    /// says what the holder is doing ("running this scan in DIR").
    pub fn acquire(dest: &Path, doing: &str) -> Result<Self> {
        use std::io::Write;
        let path = Self::path_for(dest);
        loop {
            let mut file = std::fs::OpenOptions::new()
                .read(true)
                .write(true)
                .create(true)
                .truncate(false)
                .open(&path)
                .with_context(|| format!("cannot create the lock file {}", path.display()))?;
            match file.try_lock() {
                Ok(()) => {}
                Err(std::fs::TryLockError::WouldBlock) => {
                    let pid = std::fs::read_to_string(&path).unwrap_or_default();
                    let pid = pid.trim();
                    let pid = if pid.is_empty() { "?" } else { pid };
                    bail!(
                        "another rtw-scan (PID {pid}) is {doing} (it holds {}): wait for it to \
                         finish, or stop it (kill -INT {pid}); what it leaves unfinished, --resume finishes",
                        path.display()
                    );
                }
                Err(std::fs::TryLockError::Error(e)) => {
                    return Err(e).with_context(|| format!("cannot lock {}", path.display()));
                }
            }
            // The last holder removes the file as it lets go: if that
            // happened between our open and our lock, we hold a file that is
            // no longer at `path`; try again with the one that is.
            if same_file(&file, &path) {
                file.set_len(0)?;
                writeln!(file, "{}", std::process::id())?;
                return Ok(Self {
                    _file: file,
                    _live: Registered::new(path.clone()),
                    path,
                });
            }
        }
    }
}

impl Drop for Lock {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.path);
    }
}

#[cfg(unix)]
fn same_file(file: &File, path: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    match (file.metadata(), std::fs::metadata(path)) {
        (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
        _ => false,
    }
}

#[cfg(not(unix))]
fn same_file(_: &File, path: &Path) -> bool {
    path.exists()
}

fn named_temp_for(dest: &Path) -> Result<tempfile::NamedTempFile> {
    let dir = dest
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let name = dest.file_name().and_then(|n| n.to_str()).unwrap_or("out");
    let prefix = format!(".{name}.");
    let mut builder = tempfile::Builder::new();
    builder.prefix(&prefix).suffix(".tmp");
    #[cfg(unix)]
    builder.permissions(std::os::unix::fs::PermissionsExt::from_mode(0o666));
    builder
        .tempfile_in(dir)
        .with_context(|| format!("cannot create a file in {}", dir.display()))
}

/// Writes `bytes` to `path` through a temporary file and a rename.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    use std::io::Write;
    let mut tmp = temp_file_for(path)?;
    tmp.file
        .write_all(bytes)
        .with_context(|| format!("cannot write {}", path.display()))?;
    tmp.file.as_file().sync_all()?;
    tmp.persist(path)
}

/// A Parquet file being written under a temporary name next to `dest`;
/// [`ParquetFile::finish`] closes, syncs and renames it, with the
/// [`ContentHash`] of every row written in its metadata. Dropped unfinished,
/// the temporary file is removed.
pub struct ParquetFile {
    tmp: Temp,
    writer: ArrowWriter<File>,
    dest: PathBuf,
    hash: ContentHash,
}

impl ParquetFile {
    pub fn create(dest: &Path, schema: SchemaRef, props: WriterProperties) -> Result<Self> {
        let tmp = temp_file_for(dest)?;
        let file = tmp
            .file
            .reopen()
            .with_context(|| format!("cannot open {}", tmp.file.path().display()))?;
        let hash = ContentHash::new(schema.fields().len());
        let writer = ArrowWriter::try_new(file, schema, Some(props))?;
        Ok(Self {
            tmp,
            writer,
            dest: dest.to_path_buf(),
            hash,
        })
    }

    pub fn write(&mut self, batch: &RecordBatch) -> Result<()> {
        self.hash.update(batch)?;
        self.writer
            .write(batch)
            .with_context(|| format!("writing {}", self.dest.display()))
    }

    pub fn append_metadata(&mut self, key: &str, value: String) {
        self.writer
            .append_key_value_metadata(KeyValue::new(key.to_string(), value));
    }

    /// Closes the writer, syncs the data and moves the file to its name.
    pub fn finish(self) -> Result<()> {
        let Self {
            tmp,
            mut writer,
            dest,
            hash,
        } = self;
        writer.append_key_value_metadata(kv(META_CONTENT_HASH, hash.value()));
        writer
            .close()
            .with_context(|| format!("closing {}", dest.display()))?;
        tmp.file.as_file().sync_all()?;
        tmp.persist(&dest)
    }
}

/// A hash of a table's values, column by column in file order: for each
/// column, its values in row order (a null as a marker word, a number as its
/// 64 bits, a string as its length and bytes, a dictionary entry as its
/// string) folded through SplitMix64's finalizer; then the column hashes
/// folded the same way. It depends on the rows only, not on how they are cut
/// into batches, row groups or pages, nor on the compression. Unlike a CRC
/// per page (which the parquet crate can check but not write), it also
/// catches a page that decodes cleanly to wrong numbers.
#[derive(Clone, Debug)]
pub struct ContentHash {
    columns: Vec<u64>,
}

impl ContentHash {
    const NULL: u64 = 0x6e75_6c6c_6e75_6c6c;

    pub fn new(columns: usize) -> Self {
        Self {
            columns: vec![0; columns],
        }
    }

    fn fold(h: &mut u64, word: u64) {
        *h = crate::cluster::mix(*h ^ word);
    }

    fn fold_str(h: &mut u64, s: &str) {
        Self::fold(h, s.len() as u64);
        for chunk in s.as_bytes().chunks(8) {
            let mut w = [0u8; 8];
            w[..chunk.len()].copy_from_slice(chunk);
            Self::fold(h, u64::from_le_bytes(w));
        }
    }

    /// Adds the rows of `batch` (the columns of the schema it was made with).
    pub fn update(&mut self, batch: &RecordBatch) -> Result<()> {
        if batch.num_columns() != self.columns.len() {
            bail!(
                "{} columns where the file has {}",
                batch.num_columns(),
                self.columns.len()
            );
        }
        for (h, col) in self.columns.iter_mut().zip(batch.columns()) {
            let words = |h: &mut u64, w: &mut dyn Iterator<Item = Option<u64>>| {
                for v in w {
                    Self::fold(h, v.unwrap_or(Self::NULL));
                }
            };
            match col.data_type() {
                DataType::Float64 => words(
                    h,
                    &mut col
                        .as_primitive::<Float64Type>()
                        .iter()
                        .map(|v| v.map(f64::to_bits)),
                ),
                DataType::Int64 => words(
                    h,
                    &mut col
                        .as_primitive::<Int64Type>()
                        .iter()
                        .map(|v| v.map(|x| x as u64)),
                ),
                DataType::Int8 => words(
                    h,
                    &mut col
                        .as_primitive::<Int8Type>()
                        .iter()
                        .map(|v| v.map(|x| x as u64)),
                ),
                DataType::Int32 => words(
                    h,
                    &mut col
                        .as_primitive::<Int32Type>()
                        .iter()
                        .map(|v| v.map(|x| x as u64)),
                ),
                DataType::Boolean => {
                    words(h, &mut col.as_boolean().iter().map(|v| v.map(u64::from)))
                }
                DataType::Utf8 => {
                    for v in col.as_string::<i32>().iter() {
                        match v {
                            Some(s) => Self::fold_str(h, s),
                            None => Self::fold(h, Self::NULL),
                        }
                    }
                }
                DataType::Dictionary(k, v) if **k == DataType::Int32 && **v == DataType::Utf8 => {
                    let dict = col.as_dictionary::<Int32Type>();
                    let values = dict.values().as_string::<i32>();
                    for key in dict.keys().iter() {
                        match key.filter(|k| (*k as usize) < values.len()) {
                            Some(k) => Self::fold_str(h, values.value(k as usize)),
                            None => Self::fold(h, Self::NULL),
                        }
                    }
                }
                other => bail!("cannot hash a column of type {other}"),
            }
        }
        Ok(())
    }

    /// The hash, as it is written in [`META_CONTENT_HASH`]: 16 hex digits.
    pub fn value(&self) -> String {
        let mut h = 0;
        for c in &self.columns {
            Self::fold(&mut h, *c);
        }
        format!("{h:016x}")
    }
}

/// Writes `batch` as one complete Parquet file at `dest` (atomically).
pub fn write_file(dest: &Path, batch: &RecordBatch, metadata: Vec<KeyValue>) -> Result<()> {
    let props = writer_properties(&batch.schema(), batch.num_rows(), metadata);
    let mut f = ParquetFile::create(dest, batch.schema(), props)?;
    f.write(batch)?;
    f.finish()
}

/// An open Parquet file: its key-value metadata and a batch reader.
pub struct ParquetInput {
    pub metadata: BTreeMap<String, String>,
    pub rows: i64,
    pub reader: VerifiedReader,
}

/// The batches of a Parquet file, checked: a page that does not decode, and
/// (once the last batch has been read) rows that do not hash to the file's
/// [`META_CONTENT_HASH`], are errors naming the file. Files without the key
/// (written before it existed) are read unchecked.
pub struct VerifiedReader {
    inner: ParquetRecordBatchReader,
    path: PathBuf,
    hash: ContentHash,
    expected: Option<String>,
    done: bool,
}

impl Iterator for VerifiedReader {
    type Item = Result<RecordBatch>;

    fn next(&mut self) -> Option<Result<RecordBatch>> {
        if self.done {
            return None;
        }
        let corrupt = |why: String| {
            anyhow!(
                "{} is corrupt: {why}; restore it or rerun what made it",
                self.path.display()
            )
        };
        match self.inner.next() {
            Some(Ok(batch)) => {
                if let Err(e) = self.hash.update(&batch) {
                    self.done = true;
                    return Some(Err(corrupt(format!("{e:#}"))));
                }
                Some(Ok(batch))
            }
            Some(Err(e)) => {
                self.done = true;
                Some(Err(corrupt(format!("a page does not decode ({e})"))))
            }
            None => {
                self.done = true;
                let got = self.hash.value();
                match &self.expected {
                    Some(want) if *want != got => Some(Err(corrupt(format!(
                        "its rows hash to {got}, not to the {want} written with them \
                         (`{META_CONTENT_HASH}`)"
                    )))),
                    _ => None,
                }
            }
        }
    }
}

/// Opens a Parquet file for reading, with errors naming the path; its
/// batches are checked against its content hash ([`VerifiedReader`]).
pub fn open(path: &Path, batch_size: usize) -> Result<ParquetInput> {
    let file = File::open(path).with_context(|| format!("cannot open {}", path.display()))?;
    let builder = ParquetRecordBatchReaderBuilder::try_new(file)
        .with_context(|| format!("{} is not a readable Parquet file", path.display()))?;
    let meta = builder.metadata().file_metadata();
    let rows = meta.num_rows();
    let metadata: BTreeMap<String, String> = meta
        .key_value_metadata()
        .into_iter()
        .flatten()
        .filter_map(|kv| Some((kv.key.clone(), kv.value.clone()?)))
        .collect();
    let columns = builder.schema().fields().len();
    let inner = builder.with_batch_size(batch_size.max(1)).build()?;
    Ok(ParquetInput {
        rows,
        reader: VerifiedReader {
            inner,
            path: path.to_path_buf(),
            hash: ContentHash::new(columns),
            expected: metadata.get(META_CONTENT_HASH).cloned(),
            done: false,
        },
        metadata,
    })
}

/// Checks the values of a batch of scan rows that every reader relies on:
/// each input parameter inside its range (docs/model.md §1), the derived
/// parameters finite. `first_row` is the batch's first row in the file; an
/// error names the file, the column and the row.
pub fn check_scan_values(batch: &RecordBatch, path: &Path, first_row: u64) -> Result<()> {
    for (i, key) in crate::config::PARAM_KEYS.iter().enumerate() {
        let col = f64_column(batch, key).with_context(|| path.display().to_string())?;
        for (r, v) in col.iter().enumerate() {
            let bad = match v {
                None => Some("null: must be a number".to_string()),
                Some(v) => crate::config::check_param(i, v).err().map(|e| {
                    // Corrupt bits are often huge or tiny: keep them readable.
                    let shown = if v != 0.0 && !(1e-6..1e6).contains(&v.abs()) {
                        format!("{v:e}")
                    } else {
                        v.to_string()
                    };
                    format!("{shown} is invalid: must be {}", e.range)
                }),
            };
            if let Some(why) = bad {
                bail!(
                    "{}: column `{key}`, row {}: {why}; the file is corrupt or was not written by rtw-scan",
                    path.display(),
                    first_row + r as u64
                );
            }
        }
    }
    for c in COLUMNS.iter().filter(|c| c.group == "derived") {
        let col = f64_column(batch, c.name).with_context(|| path.display().to_string())?;
        if let Some(r) = col.iter().position(|v| !v.is_some_and(f64::is_finite)) {
            bail!(
                "{}: column `{}`, row {}: {:?} is invalid: must be a finite number; the file is corrupt",
                path.display(),
                c.name,
                first_row + r as u64,
                col.iter().nth(r).flatten()
            );
        }
    }
    Ok(())
}

/// A `Float64` column of a scan batch, by name.
pub fn f64_column<'a>(batch: &'a RecordBatch, name: &str) -> Result<&'a Float64Array> {
    let col = batch
        .column_by_name(name)
        .ok_or_else(|| anyhow!("column `{name}` is missing"))?;
    col.as_primitive_opt::<Float64Type>()
        .ok_or_else(|| anyhow!("column `{name}` is {}, expected Float64", col.data_type()))
}

/// An `Int64` column of a scan batch, by name.
pub fn i64_column<'a>(batch: &'a RecordBatch, name: &str) -> Result<&'a Int64Array> {
    let col = batch
        .column_by_name(name)
        .ok_or_else(|| anyhow!("column `{name}` is missing"))?;
    col.as_primitive_opt::<Int64Type>()
        .ok_or_else(|| anyhow!("column `{name}` is {}, expected Int64", col.data_type()))
}

/// Metadata key of an assignments file: the clustering (centres, sizes,
/// cross-table) as JSON, exactly what `cluster --json` prints.
pub const META_CLUSTERS: &str = "rtw.clusters";

/// Writes the cluster of each failed sample (`cluster --assignments`): one
/// row per failure with `sample_id`, `cluster` (1-based, the row of the
/// cluster table), `cluster_name`, `outcome` (collapse or stall) and the
/// clustered coordinates `alpha`, `fn`, `phi`; the clustering itself goes in
/// the file's metadata under [`META_CLUSTERS`]. Written batch by batch, in
/// row groups of at most [`MAX_ROW_GROUP_ROWS`].
pub struct AssignmentsWriter<'a> {
    file: ParquetFile,
    clusters: &'a FailureClusters,
}

impl<'a> AssignmentsWriter<'a> {
    pub fn create(
        dest: &Path,
        clusters: &'a FailureClusters,
        mut metadata: Vec<KeyValue>,
    ) -> Result<Self> {
        metadata.push(kv(META_CLUSTERS, serde_json::to_string(clusters)?));
        let schema = assignments_schema();
        let props = writer_properties(&schema, MAX_ROW_GROUP_ROWS, metadata);
        Ok(Self {
            file: ParquetFile::create(dest, schema, props)?,
            clusters,
        })
    }

    /// Writes `failures` with their clusters (indices into `clusters.clusters`).
    pub fn write(&mut self, failures: &[Failure], cluster: &[usize]) -> Result<()> {
        let f64s = |g: fn(&Failure) -> f64| -> ArrayRef {
            Arc::new(failures.iter().map(g).collect::<Float64Array>())
        };
        let columns: Vec<ArrayRef> = vec![
            Arc::new(
                failures
                    .iter()
                    .map(|f| f.sample_id as i64)
                    .collect::<Int64Array>(),
            ),
            Arc::new(
                cluster
                    .iter()
                    .map(|a| *a as i64 + 1)
                    .collect::<Int64Array>(),
            ),
            Arc::new(StringArray::from_iter_values(
                cluster
                    .iter()
                    .map(|a| self.clusters.clusters[*a].name.as_str()),
            )),
            Arc::new(StringArray::from_iter_values(
                failures.iter().map(|f| f.label.as_str()),
            )),
            f64s(|f| f.alpha),
            f64s(|f| f.f_n),
            f64s(|f| f.phi),
        ];
        self.file
            .write(&RecordBatch::try_new(assignments_schema(), columns)?)
    }

    pub fn finish(self) -> Result<()> {
        self.file.finish()
    }
}

/// The schema of `cluster --assignments`: one row per failed sample.
pub fn assignments_schema() -> SchemaRef {
    let f = |name, ty, unit, description| dictionary::field(name, ty, false, unit, description);
    Arc::new(Schema::new(vec![
        f(
            "sample_id",
            DataType::Int64,
            "-",
            "the failed sample's id in the scan",
        ),
        f(
            "cluster",
            DataType::Int64,
            "-",
            "index of the k-means cluster of its nearest centre",
        ),
        f(
            "cluster_name",
            DataType::Utf8,
            "-",
            "the cluster's name by its kind of failure (e.g. collapse region, barrier region)",
        ),
        f(
            "outcome",
            DataType::Utf8,
            "-",
            "the sample's failure label (collapse, stall, diverged)",
        ),
        f(
            "alpha",
            DataType::Float64,
            "1",
            "connection ratio α (a clustering coordinate)",
        ),
        f(
            "fn",
            DataType::Float64,
            "Hz",
            "eigen-frequency f_n (a clustering coordinate)",
        ),
        f(
            "phi",
            DataType::Float64,
            "rad",
            "slope angle φ (a clustering coordinate)",
        ),
    ]))
}

/// The `outcome` column of a scan batch, decoded to labels.
pub fn label_column(batch: &RecordBatch) -> Result<Vec<Label>> {
    let col = batch
        .column_by_name("outcome")
        .ok_or_else(|| anyhow!("column `outcome` is missing"))?;
    let decode = |s: &str| {
        s.parse::<Label>()
            .map_err(|e| anyhow!("column `outcome`: {e}"))
    };
    if let Some(dict) = col.as_dictionary_opt::<Int32Type>() {
        let values = dict
            .values()
            .as_string_opt::<i32>()
            .ok_or_else(|| anyhow!("column `outcome`: dictionary values are not strings"))?;
        let table: Vec<Label> = values
            .iter()
            .map(|v| decode(v.unwrap_or("")))
            .collect::<Result<_>>()?;
        dict.keys()
            .iter()
            .map(|k| {
                k.and_then(|k| table.get(k as usize).copied())
                    .ok_or_else(|| anyhow!("column `outcome`: null or bad key"))
            })
            .collect()
    } else if let Some(s) = col.as_string_opt::<i32>() {
        s.iter().map(|v| decode(v.unwrap_or(""))).collect()
    } else {
        bail!(
            "column `outcome` is {}, expected a string dictionary",
            col.data_type()
        )
    }
}

/// Writes a trajectory ([`TraceSample`]s) to Parquet in row groups of
/// `BATCH` samples, so a long trace never sits in memory.
pub struct TraceWriter {
    file: ParquetFile,
    schema: SchemaRef,
    buffer: Vec<TraceSample>,
    rows: u64,
    max_rows: u64,
}

enum TraceGet {
    F64(Box<dyn Fn(&TraceSample) -> f64>),
    I8(Box<dyn Fn(&TraceSample) -> i8>),
}

/// A scalar field of a trace sample.
type TraceScalar = fn(&TraceSample) -> f64;

/// One column of a trace file: name, unit, description, value.
type TraceColumn = (String, &'static str, String, TraceGet);

fn trace_columns() -> Vec<TraceColumn> {
    use TraceGet::{F64, I8};
    let mut cols: Vec<TraceColumn> = vec![(
        "t".into(),
        "s",
        "time since the start of the run".into(),
        F64(Box::new(|s| s.t)),
    )];
    for (rod, name) in ["a", "b", "c"].into_iter().enumerate() {
        let pose = [
            (
                "x",
                "m",
                "centre's position along the slope (downhill positive)",
            ),
            (
                "y",
                "m",
                "centre's height above the ground, along the slope normal",
            ),
            ("theta", "rad", "angle from the slope's x axis"),
        ];
        for (j, (q, unit, what)) in pose.into_iter().enumerate() {
            cols.push((
                format!("{q}_{name}"),
                unit,
                format!("rod {name}: {what}"),
                F64(Box::new(move |s| s.pose[rod][j])),
            ));
        }
        let vel = [
            ("vx", "m/s", "centre's velocity along x"),
            ("vy", "m/s", "centre's velocity along y"),
            ("omega", "rad/s", "angular velocity"),
        ];
        for (j, (q, unit, what)) in vel.into_iter().enumerate() {
            cols.push((
                format!("{q}_{name}"),
                unit,
                format!("rod {name}: {what}"),
                F64(Box::new(move |s| s.vel[rod][j])),
            ));
        }
        cols.push((
            format!("contact_{name}"),
            "-",
            format!(
                "rod {name}'s contact mode: 0 free, +1/−1 stick on tip ±, +2/−2 slide on tip ±"
            ),
            I8(Box::new(move |s| s.contact[rod])),
        ));
    }
    cols.push((
        "contact_state".into(),
        "1",
        "rods on the ground: 0 NLSP (flight), 1 SLSP, 2 DLSP, 3 TLSP".into(),
        I8(Box::new(|s| s.contact_state as i8)),
    ));
    let scalars: [(&str, &str, TraceScalar); 5] = [
        ("kinetic", "kinetic energy", |s| s.kinetic),
        ("gravity_potential", "potential energy of gravity", |s| {
            s.gravity_potential
        }),
        ("string_potential", "elastic energy of the strings", |s| {
            s.string_potential
        }),
        (
            "damping_loss",
            "energy dissipated by the dampers so far",
            |s| s.damping_loss,
        ),
        ("impact_loss", "energy lost in impacts so far", |s| {
            s.impact_loss
        }),
    ];
    for (n, what, g) in scalars {
        cols.push((n.into(), "J", what.into(), F64(Box::new(g))));
    }
    cols
}

/// The schema of a trace file (`simulate --trace`).
pub fn trace_schema() -> SchemaRef {
    let fields: Vec<Field> = trace_columns()
        .into_iter()
        .map(|(n, unit, description, g)| {
            let ty = match g {
                TraceGet::F64(_) => DataType::Float64,
                TraceGet::I8(_) => DataType::Int8,
            };
            dictionary::field(n, ty, false, unit, &description)
        })
        .collect();
    Arc::new(Schema::new(fields))
}

/// Bytes of one trace sample before compression (the sum of its columns'
/// widths): the unit of `simulate --trace`'s size estimate and limit.
pub fn trace_row_bytes() -> u64 {
    trace_columns()
        .iter()
        .map(|(_, _, _, g)| match g {
            TraceGet::F64(_) => 8,
            TraceGet::I8(_) => 1,
        })
        .sum()
}

/// Most samples a trace of a run with `options` can have: one every
/// `trace_dt` over `t_max`, or with `trace_dt = 0` one per step, at most the
/// work budget `max_steps`.
pub fn trace_rows_bound(options: &rtw_model::Options) -> u64 {
    if options.trace_dt > 0.0 {
        (options.t_max / options.trace_dt).min(u64::MAX as f64 / 2.0) as u64 + 2
    } else {
        options.max_steps.saturating_add(1)
    }
}

/// A byte count in decimal units (`2.0 GB`).
pub fn human_bytes(b: f64) -> String {
    let units = ["B", "kB", "MB", "GB", "TB", "PB", "EB"];
    let mut v = b;
    let mut u = 0;
    while v >= 1000.0 && u + 1 < units.len() {
        v /= 1000.0;
        u += 1;
    }
    format!("{v:.1} {}", units[u])
}

/// Parses a size such as `2GB`, `500 MB`, `1e9` (bytes), `64kB`; decimal units.
pub fn parse_size(s: &str) -> Result<u64, String> {
    let t = s.trim();
    let split = t.find(|c: char| c.is_ascii_alphabetic()).unwrap_or(t.len());
    let (num, unit) = t.split_at(split);
    let factor = match unit.trim().to_ascii_lowercase().as_str() {
        "" | "b" => 1.0,
        "kb" | "k" => 1e3,
        "mb" | "m" => 1e6,
        "gb" | "g" => 1e9,
        "tb" | "t" => 1e12,
        _ => {
            return Err(format!(
                "`{s}`: unknown unit `{unit}`: use B, kB, MB, GB or TB"
            ));
        }
    };
    let v: f64 = num
        .trim()
        .parse()
        .map_err(|_| format!("`{s}` is not a size such as 2GB or 500MB"))?;
    if !(v.is_finite() && v > 0.0) {
        return Err(format!("`{s}`: must be a size > 0"));
    }
    Ok((v * factor).min(u64::MAX as f64) as u64)
}

impl TraceWriter {
    const BATCH: usize = 8192;

    /// A trace of at most `limit` bytes before compression: a sample past it
    /// is an error (the estimate made before the run is an upper bound, this
    /// is the backstop).
    pub fn create(dest: &Path, metadata: Vec<KeyValue>, limit: u64) -> Result<Self> {
        let schema = trace_schema();
        let props = writer_properties(&schema, Self::BATCH, metadata);
        let file = ParquetFile::create(dest, schema.clone(), props)?;
        Ok(Self {
            file,
            schema,
            buffer: Vec::with_capacity(Self::BATCH),
            rows: 0,
            max_rows: limit / trace_row_bytes(),
        })
    }

    /// Buffers one sample, writing a row group when the buffer is full.
    pub fn push(&mut self, s: &TraceSample) -> Result<()> {
        if self.rows + self.buffer.len() as u64 >= self.max_rows {
            bail!(
                "the trace reached its limit of {} samples ({}); raise --trace-limit or trace_dt",
                self.max_rows,
                human_bytes((self.max_rows * trace_row_bytes()) as f64)
            );
        }
        self.buffer.push(*s);
        if self.buffer.len() >= Self::BATCH {
            self.flush()?;
        }
        Ok(())
    }

    fn flush(&mut self) -> Result<()> {
        if self.buffer.is_empty() {
            return Ok(());
        }
        let arrays: Vec<ArrayRef> = trace_columns()
            .into_iter()
            .map(|(_, _, _, g)| match g {
                TraceGet::F64(g) => {
                    Arc::new(self.buffer.iter().map(&g).collect::<Float64Array>()) as ArrayRef
                }
                TraceGet::I8(g) => Arc::new(self.buffer.iter().map(&g).collect::<Int8Array>()),
            })
            .collect();
        self.file
            .write(&RecordBatch::try_new(self.schema.clone(), arrays)?)?;
        self.rows += self.buffer.len() as u64;
        self.buffer.clear();
        Ok(())
    }

    /// Writes what is buffered and moves the file into place; returns the row count.
    pub fn finish(mut self) -> Result<u64> {
        self.flush()?;
        self.file.finish()?;
        Ok(self.rows)
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use rtw_model::Normalization;
    use rtw_model::outcome::{ContactFractions, Energy, FailureDetail, IntegratorWork};

    pub(crate) fn outcome(label: Label) -> Outcome {
        Outcome {
            label,
            failure: (label == Label::Stall).then_some(FailureDetail::NoTouchdown),
            start: rtw_model::outcome::Stance::TwoFeet,
            t_end: 20.0,
            fractions: ContactFractions {
                nlsp: 0.1,
                slsp: 0.5,
                dlsp: 0.4,
                tlsp: 0.0,
            },
            step_shares: rtw_model::outcome::StepShares {
                steps: 30,
                flight: 0.4,
                triple: 0.0,
            },
            touchdowns: 40,
            f_w: 3.2,
            f_w_newfoot: 2.9,
            speed: 0.8,
            mu_required: 7.5,
            slide_time: 0.01,
            energy: Energy::default(),
            period: 1,
            cycle: Some(rtw_model::CycleSummary {
                period: 1,
                floquet_max: 0.8,
                residual: 1e-10,
            }),
            work: IntegratorWork {
                steps: 100,
                rejected: 3,
                rhs_evals: 700,
                events: 50,
            },
        }
    }

    pub(crate) fn row(id: u64, outcome: Option<Outcome>) -> Row {
        let params = Params::fig7a();
        Row {
            sample_id: id,
            params,
            physical: Physical::new(&params, Normalization::Supplementary, 9.81),
            outcome,
            message: outcome.is_none().then(|| "boom".to_string()),
            wall_time_s: 0.25,
        }
    }

    #[test]
    fn batch_has_every_column_and_signed_dictionary_keys() {
        let rows = vec![
            row(0, Some(outcome(Label::Walk))),
            row(1, None),
            row(2, Some(outcome(Label::Stall))),
        ];
        let b = to_batch(&rows);
        assert_eq!(b.num_rows(), 3);
        assert_eq!(b.num_columns(), COLUMNS.len());
        assert_eq!(
            b.schema().field_with_name("outcome").unwrap().data_type(),
            &label_type()
        );
        assert_eq!(
            label_column(&b).unwrap(),
            vec![Label::Walk, Label::Diverged, Label::Stall]
        );
        let t_end = f64_column(&b, "t_end").unwrap();
        assert!(t_end.is_valid(0) && t_end.is_null(1));
        let failure = b.column_by_name("failure").unwrap().as_string::<i32>();
        assert!(failure.is_null(0));
        assert_eq!(failure.value(2), "no_touchdown");
        let message = b.column_by_name("message").unwrap().as_string::<i32>();
        assert_eq!(message.value(1), "boom");
    }

    #[test]
    fn parquet_round_trip_keeps_types_and_metadata() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("x.parquet");
        let rows: Vec<Row> = (0..5).map(|i| row(i, Some(outcome(Label::Skip)))).collect();
        write_file(
            &path,
            &to_batch(&rows),
            vec![KeyValue::new(META_SEED.into(), "7".to_string())],
        )
        .unwrap();
        let input = open(&path, 100).unwrap();
        assert_eq!(input.rows, 5);
        assert_eq!(input.metadata[META_SEED], "7");
        let batches: Vec<RecordBatch> = input.reader.collect::<Result<_, _>>().unwrap();
        assert_eq!(batches[0].schema().fields(), schema().fields());
        assert_eq!(batches[0], to_batch(&rows));
        // Nothing but the file is left in the directory.
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn json_is_flat_and_ordered() {
        let r = row(4, Some(outcome(Label::Walk)));
        let s = serde_json::to_string(&JsonRow(&r)).unwrap();
        let v: serde_json::Value = serde_json::from_str(&s).unwrap();
        assert_eq!(v["outcome"], "walk");
        assert_eq!(v["slsp"], 0.5);
        assert_eq!(v["steps"], 100);
        assert_eq!(v["k"].as_f64().unwrap().round(), 500.0);
        assert!(v["failure"].is_null());
        assert!(s.starts_with("{\"sample_id\":4,\"length\":0.8"));
        let d = serde_json::to_value(JsonRow(&row(1, None))).unwrap();
        assert_eq!(d["outcome"], "diverged");
        assert_eq!(d["message"], "boom");
        assert!(d["t_end"].is_null());
        let text = to_text(&r);
        // Every field of Outcome has a column: nested structs flatten to
        // their field names (`energy` with an `energy_` prefix).
        let o = serde_json::to_value(r.outcome.unwrap()).unwrap();
        for (k, val) in o.as_object().unwrap() {
            let names: Vec<String> = match val.as_object() {
                Some(inner) if k == "energy" => {
                    inner.keys().map(|f| format!("energy_{f}")).collect()
                }
                Some(inner) if k == "step_shares" => inner
                    .keys()
                    .map(|f| match f.as_str() {
                        "steps" => "window_steps".into(),
                        _ => format!("{f}_steps"),
                    })
                    .collect(),
                Some(inner) if k == "cycle" => inner
                    .keys()
                    .map(|f| match f.as_str() {
                        "residual" => "cycle_residual".into(),
                        _ => f.clone(),
                    })
                    .collect(),
                Some(inner) => inner.keys().cloned().collect(),
                None if k == "label" => vec!["outcome".into()],
                None => vec![k.clone()],
            };
            for n in names {
                assert!(
                    COLUMNS.iter().any(|c| c.name == n),
                    "Outcome field {n} has no column"
                );
            }
        }
        assert!(text.contains("[metric]") && text.contains("outcome") && text.contains("walk"));
    }
}
