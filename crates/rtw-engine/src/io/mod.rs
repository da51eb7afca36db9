//! Files: the column tables and Parquet forms of what rtw-scan writes, read
//! back checked; files that appear whole or not at all.
//!
//! | module | role |
//! |---|---|
//! | `table` | a file's columns listed once (name, unit, meaning, getter) → schema and batches |
//! | `scan_rows` | the scan row and its table; its JSON and text forms |
//! | `robustness_columns` | the optional robustness columns of a scan (`robustness.*`) |
//! | `robustness_measures` | the robustness measures a row can carry, by name, and the options that ask for them |
//! | `scan_files` | scan batches read back and checked; chunks and parts concatenated |
//! | `parquet` | Parquet files written atomically with a content hash, read back verified |
//! | `content_hash` | the hash of a table's values, independent of batches and pages, and of its metadata |
//! | `metadata` | the metadata keys, a scan's metadata, the kind of a file |
//! | `destination` | the refusal to write one kind of file over another |
//! | `trace` | `simulate --trace` files and their size bound |
//! | `markdown` | a Markdown table's cell text |
//! | `page` | a report's HTML page written with the same refusals, atomically |
//!
//! Public: what a reader of rtw-scan's files needs, re-exported here.

pub mod content_hash;
pub mod destination;
pub mod markdown;
pub mod metadata;
pub mod page;
pub mod parquet;
pub mod robustness_columns;
pub(crate) mod robustness_measures;
pub mod scan_files;
pub mod scan_rows;
pub mod table;
pub mod trace;

pub use crate::sizes::parse_size;
pub use metadata::kv;
pub use parquet::{ParquetInput, VerifiedReader, open, write_file};
pub use scan_rows::{ColumnKind, Kind, Value, row_columns, schema};
pub use trace::{
    TraceNames, TraceWriter, check_trace_size, trace_batch, trace_metadata, trace_schema,
};
