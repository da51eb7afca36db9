//! Trace files (`simulate --trace`): a run's time series, streamed to
//! Parquet, and the size it may reach.

use crate::files;
use crate::io::destination::check_destination;
use crate::io::metadata::{FileKind, META_OPTIONS, META_PARAMS, META_VERSION, kv};
use crate::io::parquet::{ParquetFile, writer_properties};
use crate::io::table;
use crate::sizes::human_bytes;
use anyhow::{Context, Result, bail};
use arrow_array::{ArrayRef, Float64Array, Int8Array, RecordBatch};
use arrow_schema::{DataType, Field, Schema, SchemaRef};
use parquet::file::metadata::KeyValue;
use rtw_model::{Options, Params, TraceSample};
use std::path::Path;
use std::sync::Arc;

/// Writes a trajectory ([`TraceSample`]s) to Parquet in row groups of
/// 8192 samples, so a long trace never sits in memory: [`Self::to_file`]
/// opens it, [`Self::push`] takes each sample, [`Self::finish`] moves the
/// file into place.
pub struct TraceWriter {
    file: ParquetFile,
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
            table::field(n, ty, false, unit, &description)
        })
        .collect();
    Arc::new(Schema::new(fields))
}

/// A trace's samples as one batch of [`trace_schema`]: what a trace file's
/// row groups hold, and what `rtw.trace` hands to Python.
pub fn trace_batch(samples: &[TraceSample]) -> RecordBatch {
    let arrays: Vec<ArrayRef> = trace_columns()
        .into_iter()
        .map(|(_, _, _, g)| match g {
            TraceGet::F64(g) => {
                Arc::new(samples.iter().map(&g).collect::<Float64Array>()) as ArrayRef
            }
            TraceGet::I8(g) => Arc::new(samples.iter().map(&g).collect::<Int8Array>()),
        })
        .collect();
    RecordBatch::try_new(trace_schema(), arrays).expect("the trace columns match their schema")
}

/// The metadata of a trace of a run of `params` with `options`: rtw-scan's
/// version, the parameters (JSON) and the resolved options (TOML).
pub fn trace_metadata(params: &Params, options: &Options) -> Result<Vec<KeyValue>> {
    Ok(vec![
        kv(META_VERSION, crate::io::metadata::VERSION.into()),
        kv(META_PARAMS, serde_json::to_string(params)?),
        kv(META_OPTIONS, toml::to_string(options)?),
    ])
}

/// How the caller spells the two settings a trace's size depends on, for
/// the message of [`check_trace_size`].
#[derive(Clone, Copy, Debug)]
pub struct TraceNames {
    /// The size limit (`--trace-limit`).
    pub limit: &'static str,
    /// The sampling interval (`trace_dt (--set trace_dt=...)`).
    pub dt: &'static str,
}

impl TraceNames {
    /// The names of `rtw-scan simulate`'s flags.
    pub const CLI: Self = Self {
        limit: "--trace-limit",
        dt: "trace_dt (--set trace_dt=...)",
    };
}

/// Refuses a trace of a run with `options` whose size estimate
/// (`trace_rows_bound` × `trace_row_bytes`) exceeds `limit` bytes;
/// `names` says how the caller spells the limit and the interval.
pub fn check_trace_size(options: &Options, limit: u64, names: TraceNames) -> Result<()> {
    let rows = trace_rows_bound(options);
    let bytes = rows as f64 * trace_row_bytes() as f64;
    let (limit_name, dt_name) = (names.limit, names.dt);
    if bytes > limit as f64 {
        bail!(
            "about {} ({rows} samples × {} bytes: t_max {} s / trace_dt {} s{}) is more \
             than {limit_name} {}: raise {dt_name}, lower t_max, or raise {limit_name}",
            human_bytes(bytes),
            trace_row_bytes(),
            rtw_model::Num(options.t_max),
            rtw_model::Num(options.trace_dt),
            if options.trace_dt > 0.0 {
                String::new()
            } else {
                format!(
                    ", i.e. one per step, up to max_steps = {}",
                    options.max_steps
                )
            },
            human_bytes(limit as f64)
        );
    }
    Ok(())
}

/// Bytes of one trace sample before compression (the sum of its columns'
/// widths): the unit of `simulate --trace`'s size estimate and limit.
pub(crate) fn trace_row_bytes() -> u64 {
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
pub(crate) fn trace_rows_bound(options: &Options) -> u64 {
    if options.trace_dt > 0.0 {
        (options.t_max / options.trace_dt).min(u64::MAX as f64 / 2.0) as u64 + 2
    } else {
        options.max_steps.saturating_add(1)
    }
}

impl TraceWriter {
    const BATCH: usize = 8192;

    /// The trace of the run of `params` under `options` (its metadata), to
    /// be written at `dest` (named `flag` in errors): refused, unless
    /// `force`, over a file that is not a trace (never over a symlink or a
    /// special file), and refused when its size before compression,
    /// estimated from the options, may pass `limit` bytes (in the caller's
    /// `names`); stray temporary files of an interrupted write are removed.
    pub fn to_file(
        dest: &Path,
        params: &Params,
        options: &Options,
        limit: u64,
        force: bool,
        flag: &str,
        names: TraceNames,
    ) -> Result<Self> {
        check_destination(dest, FileKind::Trace, &[], flag, force)?;
        check_trace_size(options, limit, names)
            .with_context(|| format!("{flag} {}", dest.display()))?;
        files::remove_stray_temps(dest)?;
        let meta = trace_metadata(params, options)?;
        Self::create(dest, meta, limit).with_context(|| format!("trace {}", dest.display()))
    }

    /// A trace of at most `limit` bytes before compression: a sample past it
    /// is an error (the estimate made before the run is an upper bound, this
    /// is the backstop).
    pub(crate) fn create(dest: &Path, metadata: Vec<KeyValue>, limit: u64) -> Result<Self> {
        let schema = trace_schema();
        let props = writer_properties(&schema, Self::BATCH, metadata);
        let file = ParquetFile::create(dest, schema, props)?;
        Ok(Self {
            file,
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
        self.file.write(&trace_batch(&self.buffer))?;
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
