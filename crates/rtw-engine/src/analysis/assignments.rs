//! The assignments file of `cluster --assignments`: each failed sample and
//! its cluster.

use crate::analysis::clusters::{Failure, FailureClusters};
use crate::io::metadata::{META_CLUSTERS, kv};
use crate::io::parquet::{MAX_ROW_GROUP_ROWS, ParquetFile, writer_properties};
use crate::io::table;
use anyhow::Result;
use arrow_array::{ArrayRef, Float64Array, Int64Array, RecordBatch, StringArray};
use arrow_schema::{DataType, Schema, SchemaRef};
use parquet::file::metadata::KeyValue;
use std::path::Path;
use std::sync::Arc;

/// Writes the cluster of each failed sample (`cluster --assignments`): one
/// row per failure with `sample_id`, `cluster` (1-based, the row of the
/// cluster table), `cluster_name`, `outcome` (collapse or stall) and the
/// clustered coordinates `alpha`, `fn`, `phi`; the clustering itself goes in
/// the file's metadata under [`META_CLUSTERS`]. Written batch by batch, in
/// row groups of at most [`MAX_ROW_GROUP_ROWS`].
pub(crate) struct AssignmentsWriter<'a> {
    file: ParquetFile,
    clusters: &'a FailureClusters,
}

impl<'a> AssignmentsWriter<'a> {
    pub(crate) fn create(
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
    pub(crate) fn write(&mut self, failures: &[Failure], cluster: &[usize]) -> Result<()> {
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

    pub(crate) fn finish(self) -> Result<()> {
        self.file.finish()
    }
}

/// The schema of `cluster --assignments`: one row per failed sample.
pub fn assignments_schema() -> SchemaRef {
    let f = |name, ty, unit, description| table::field(name, ty, false, unit, description);
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
