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
use arrow::array::{
    Array, ArrayRef, AsArray, DictionaryArray, Float64Array, Int8Array, Int32Array, Int64Array,
    RecordBatch, StringArray,
};
use arrow::datatypes::{DataType, Field, Float64Type, Int32Type, Int64Type, Schema, SchemaRef};
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
fn temp_file_for(dest: &Path) -> Result<tempfile::NamedTempFile> {
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
    tmp.write_all(bytes)?;
    tmp.as_file().sync_all()?;
    tmp.persist(path)
        .with_context(|| format!("cannot write {}", path.display()))?;
    Ok(())
}

/// A Parquet file being written under a temporary name next to `dest`;
/// [`ParquetFile::finish`] closes, syncs and renames it. Dropped unfinished,
/// the temporary file is removed.
pub struct ParquetFile {
    tmp: tempfile::NamedTempFile,
    writer: ArrowWriter<File>,
    dest: PathBuf,
}

impl ParquetFile {
    pub fn create(dest: &Path, schema: SchemaRef, props: WriterProperties) -> Result<Self> {
        let tmp = temp_file_for(dest)?;
        let file = tmp
            .reopen()
            .with_context(|| format!("cannot open {}", tmp.path().display()))?;
        let writer = ArrowWriter::try_new(file, schema, Some(props))?;
        Ok(Self {
            tmp,
            writer,
            dest: dest.to_path_buf(),
        })
    }

    pub fn write(&mut self, batch: &RecordBatch) -> Result<()> {
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
        let Self { tmp, writer, dest } = self;
        writer
            .close()
            .with_context(|| format!("closing {}", dest.display()))?;
        tmp.as_file().sync_all()?;
        tmp.persist(&dest)
            .with_context(|| format!("cannot move the finished file to {}", dest.display()))?;
        Ok(())
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
    pub reader: ParquetRecordBatchReader,
}

/// Opens a Parquet file for reading, with errors naming the path.
pub fn open(path: &Path, batch_size: usize) -> Result<ParquetInput> {
    let file = File::open(path).with_context(|| format!("cannot open {}", path.display()))?;
    let builder = ParquetRecordBatchReaderBuilder::try_new(file)
        .with_context(|| format!("{} is not a readable Parquet file", path.display()))?;
    let meta = builder.metadata().file_metadata();
    let rows = meta.num_rows();
    let metadata = meta
        .key_value_metadata()
        .into_iter()
        .flatten()
        .filter_map(|kv| Some((kv.key.clone(), kv.value.clone()?)))
        .collect();
    let reader = builder.with_batch_size(batch_size.max(1)).build()?;
    Ok(ParquetInput {
        metadata,
        rows,
        reader,
    })
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

impl TraceWriter {
    const BATCH: usize = 8192;

    pub fn create(dest: &Path, metadata: Vec<KeyValue>) -> Result<Self> {
        let schema = trace_schema();
        let props = writer_properties(&schema, Self::BATCH, metadata);
        let file = ParquetFile::create(dest, schema.clone(), props)?;
        Ok(Self {
            file,
            schema,
            buffer: Vec::with_capacity(Self::BATCH),
            rows: 0,
        })
    }

    /// Buffers one sample, writing a row group when the buffer is full.
    pub fn push(&mut self, s: &TraceSample) -> Result<()> {
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
