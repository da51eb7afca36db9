//! What rtw-scan writes beside the rows of its Parquet files: the metadata
//! keys, a scan's metadata, the kind of file they tell, and the refusal to
//! write one kind of file over another.

use crate::config::variant::ModelChoices;
use crate::config::{self, ScanConfig};
use anyhow::{Result, bail};
use arrow_array::RecordBatch;
use arrow_schema::ArrowError;
use parquet::file::metadata::KeyValue;
use std::collections::{BTreeMap, HashMap};
use std::sync::Arc;

/// Metadata key: the resolved scan config as TOML.
pub const META_CONFIG: &str = "rtw.config";
/// Metadata key: rtw-scan's version.
pub const META_VERSION: &str = "rtw.version";
/// Metadata key: the scan seed.
pub(crate) const META_SEED: &str = "rtw.seed";
/// Metadata key: one-line model variant summary ([`crate::config::variant::ModelChoices`]).
pub const META_VARIANT: &str = "rtw.variant";
/// Metadata key of a refine's combined file: what the refinement was (JSON:
/// budget, rounds, seed, the files joined). Its presence marks rows that are
/// not draws from the inputs' distribution.
pub const META_REFINE: &str = "rtw.refine";
/// Metadata key: seconds spent computing the rows (summed over resumed
/// sessions and, in a merged file, over the shards).
pub const META_WALL_TIME: &str = "rtw.wall_time_s";
/// Metadata key: seconds spent computing one chunk (chunk files only).
pub(crate) const META_CHUNK_WALL_TIME: &str = "rtw.chunk_wall_time_s";
/// Metadata key: [`ScanConfig::hash`] of the config in [`META_CONFIG`].
pub(crate) const META_CONFIG_HASH: &str = "rtw.config_hash";
/// Metadata key: the shard a part file holds, `K/N` (part files only).
pub(crate) const META_SHARD: &str = "rtw.shard";
/// Metadata key: the rows of the whole scan, all shards together (part files only).
pub(crate) const META_TOTAL_ROWS: &str = "rtw.total_rows";
/// Metadata key: how many shards a merged file was made of.
pub(crate) const META_SHARDS: &str = "rtw.shards";
/// Metadata key: [`ContentHash`](crate::io::content_hash::ContentHash) of
/// the file's rows, written with them and checked by every read
/// ([`open`](crate::io::parquet::open)), so a corrupt page is refused.
pub const META_CONTENT_HASH: &str = "rtw.content_hash";
/// Metadata key: [`metadata_hash`](crate::io::content_hash::metadata_hash)
/// of every other `rtw.*` key, checked when a file is opened, so an edited
/// or damaged footer is refused before anything is read from it.
pub(crate) const META_METADATA_HASH: &str = "rtw.metadata_hash";

/// Metadata key of an assignments file: the clustering (centres, sizes,
/// cross-table) as JSON, exactly what `cluster --json` prints.
pub(crate) const META_CLUSTERS: &str = "rtw.clusters";
/// Metadata key of an assignments file: the `rtw.content_hash` of the scan
/// it clusters, by which a reader tells that scan's assignments from another's.
pub(crate) const META_SCAN_HASH: &str = "rtw.scan_content_hash";
/// Metadata key: the swept parameter of a bifurcation file.
pub const META_PARAM: &str = "rtw.bifurcation.param";
/// Metadata key of `rtw-scan sensitivity`'s indices: JSON (method, scan,
/// config hash, rows, resamples, seed).
pub const META_SENSITIVITY: &str = "rtw.sensitivity";
/// Metadata key: the continued input of a continuation diagram's files.
pub const META_CONT_PARAM: &str = "rtw.continuation.param";
/// Metadata key: a diagram's second input and its range (`--curve`).
pub const META_CONT_CURVE: &str = "rtw.continuation.curve";
/// Metadata key: the parameters of a trace, the base point of a sweep (JSON
/// of the six inputs).
pub const META_PARAMS: &str = "rtw.params";
/// Metadata key: the resolved simulation options of a trace or a sweep (TOML).
pub const META_OPTIONS: &str = "rtw.options";
/// Metadata key: a sweep's step map settings (integrator, tolerances, periods).
pub const META_CYCLE: &str = "rtw.cycle";
/// Metadata key: a sweep's steps iterated before recording (`--transient`).
pub const META_TRANSIENT: &str = "rtw.bifurcation.transient";
/// Metadata key: a sweep's steps recorded at each value (`--record`).
pub const META_RECORD: &str = "rtw.bifurcation.record";
/// Metadata key of a basin slice (`basin`): its axes, steps, tolerance and
/// the gait's fixed point, as JSON.
pub const META_BASIN: &str = "rtw.basin";
/// Metadata key of a slope profile (`profile`): its settings, changes and
/// intervals, as JSON (what `profile --json` prints).
pub const META_PROFILE: &str = "rtw.profile";
/// Metadata key: a design search's settings and every evaluation as JSON
/// (`rtw-scan design`), from which an interrupted search resumes.
pub const META_DESIGN: &str = "rtw.design";

/// Every key rtw-scan wrote before [`META_METADATA_HASH`] existed (the
/// committed results are such files), and the Arrow schema the parquet crate
/// writes. A file without `rtw.metadata_hash` is taken for such an old file
/// only if its keys are all in this list: a damaged name of one of the two
/// hash keys is not, so it is refused rather than read unchecked. Fixed for
/// good: a key added later is always covered by the metadata hash.
pub(crate) const KEYS_BEFORE_METADATA_HASH: [&str; 21] = [
    META_CONFIG,
    META_VERSION,
    META_SEED,
    META_VARIANT,
    META_WALL_TIME,
    META_CHUNK_WALL_TIME,
    META_CONFIG_HASH,
    META_SHARD,
    META_TOTAL_ROWS,
    META_SHARDS,
    META_CONTENT_HASH,
    META_CLUSTERS,
    META_PARAM,
    META_CONT_PARAM,
    META_CONT_CURVE,
    META_PARAMS,
    META_OPTIONS,
    META_CYCLE,
    META_TRANSIENT,
    META_RECORD,
    "ARROW:schema",
];

/// rtw-scan's version, written into every file it makes (`rtw.version`)
/// and resume manifest: the crate's version, then `+` and the identity of
/// the sources that make its numbers (`build.rs`), so that a build whose
/// sources differ is another version, even at the same crate version.
pub const VERSION: &str = concat!(env!("CARGO_PKG_VERSION"), "+", env!("RTW_BUILD_ID"));

/// The rule for rows of two rtw-scan versions: they never end up in one
/// result (which carries one version label, while a row's numbers may differ
/// between versions). `merge` refuses such parts, `run --resume` such an
/// unfinished run, and a resume computes such a chunk again. `what` names
/// both sides (`the parts`), `a` and `b` each side and its version, `then`
/// what to do.
pub(crate) fn refuse_mixed_versions(
    what: &str,
    a: (&str, &str),
    b: (&str, &str),
    then: &str,
) -> Result<()> {
    if a.1 != b.1 {
        bail!(
            "{what} come from different rtw-scan versions: {} from {}, {} from {}; {then}",
            a.0,
            a.1,
            b.0,
            b.1
        );
    }
    Ok(())
}

/// `refuse_mixed_versions` for the rows of a file whose metadata is
/// `meta` (`their` names them) and this build's ([`VERSION`], `ours`):
/// the file's `rtw.version`, or `(none)` when it has none.
pub fn refuse_other_version(
    what: &str,
    meta: &BTreeMap<String, String>,
    their: &str,
    ours: &str,
    then: &str,
) -> Result<()> {
    let version = meta.get(META_VERSION).map_or("(none)", String::as_str);
    refuse_mixed_versions(what, (their, version), (ours, VERSION), then)
}

/// A key-value metadata entry.
pub fn kv(key: &str, value: String) -> KeyValue {
    KeyValue::new(key.to_string(), value)
}

/// `batch` with `metadata` in its schema, where an in-memory table (a
/// pyarrow table from Python) carries what a file carries in its footer.
pub(crate) fn with_metadata(
    batch: RecordBatch,
    metadata: Vec<KeyValue>,
) -> Result<RecordBatch, ArrowError> {
    let schema = batch.schema().as_ref().clone().with_metadata(
        metadata
            .into_iter()
            .map(|kv| (kv.key, kv.value.unwrap_or_default()))
            .collect::<HashMap<_, _>>(),
    );
    batch.with_schema(Arc::new(schema))
}

/// The file metadata of a scan's Parquet files: config, its hash, version,
/// seed, variant.
pub fn scan_metadata(cfg: &ScanConfig) -> Vec<KeyValue> {
    vec![
        kv(META_CONFIG, cfg.to_toml()),
        kv(META_CONFIG_HASH, cfg.hash()),
        kv(META_VERSION, VERSION.to_string()),
        kv(META_SEED, cfg.seed.to_string()),
        kv(META_VARIANT, ModelChoices::of(&cfg.simulation).to_string()),
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
    /// `continuation` diagram files (`rtw.continuation.param`).
    Continuation,
    /// `sensitivity` indices (`rtw.sensitivity`).
    Sensitivity,
    /// A basin slice (`rtw.basin`).
    Basin,
    /// A slope profile (`rtw.profile`).
    Profile,
    /// A design search's evaluations or reported designs (`rtw.design`).
    Design,
}

impl FileKind {
    /// The kind of a file with metadata `meta`, if rtw-scan wrote it.
    pub fn of(meta: &BTreeMap<String, String>) -> Option<Self> {
        if meta.contains_key(META_DESIGN) {
            Some(Self::Design)
        } else if meta.contains_key(META_PROFILE) {
            Some(Self::Profile)
        } else if meta.contains_key(META_SENSITIVITY) {
            Some(Self::Sensitivity)
        } else if meta.contains_key(META_BASIN) {
            Some(Self::Basin)
        } else if meta.contains_key(META_CONT_PARAM) {
            Some(Self::Continuation)
        } else if meta.contains_key(META_PARAM) {
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

    pub(crate) fn describe(self) -> &'static str {
        match self {
            Self::Scan => "a scan (rows of `rtw-scan run`)",
            Self::Assignments => "cluster assignments (`cluster --assignments`)",
            Self::Trace => "a trace (`simulate --trace`)",
            Self::Bifurcation => "a bifurcation sweep (`bifurcation`)",
            Self::Continuation => "a continuation diagram (`continuation`)",
            Self::Sensitivity => "sensitivity indices (`sensitivity`)",
            Self::Basin => "a basin slice (`basin`)",
            Self::Profile => "a slope profile (`profile`)",
            Self::Design => "a design search (`design`)",
        }
    }
}

/// A scan named for messages: `config hash H (name N, seed S)`.
pub(crate) fn scan_label(hash: &str, name: Option<&str>, seed: u64) -> String {
    match name {
        Some(n) => format!("config hash {hash} (name {n}, seed {seed})"),
        None => format!("config hash {hash} (seed {seed})"),
    }
}

/// [`scan_label`] of a scan file from its metadata.
pub(crate) fn scan_label_of(meta: &BTreeMap<String, String>) -> String {
    let hash = meta.get(META_CONFIG_HASH).map_or("(none)", String::as_str);
    match meta.get(META_CONFIG).map(|c| config::parse(c)) {
        Some(Ok(c)) => scan_label(hash, c.name.as_deref(), c.seed),
        _ => format!("config hash {hash}"),
    }
}
