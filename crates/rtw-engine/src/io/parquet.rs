//! Parquet files written whole or not at all, and read back checked.
//!
//! Files are written through [`ParquetFile`]: to a temporary file in the
//! destination's directory, closed, synced and renamed into place, so a file
//! at its final name is always complete, with the [`ContentHash`] of its rows
//! and the `metadata_hash` of its other metadata in its footer; [`open`]
//! checks the second before anything is read from the footer, and the first
//! as the rows are read. Compression is zstd; files of other tools (snappy, gzip, lz4; large
//! strings) are read too ([`open`]).

use crate::config;
use crate::config::variant::ModelChoices;
use crate::files::{Temp, temp_file_for};
use crate::io::content_hash::{ContentHash, metadata_hash};
use crate::io::metadata::{
    KEYS_BEFORE_METADATA_HASH, META_CONFIG, META_CONFIG_HASH, META_CONTENT_HASH,
    META_METADATA_HASH, META_SEED, META_VARIANT, kv,
};
use anyhow::{Context, Result, anyhow, bail};
use arrow_array::RecordBatch;
use arrow_schema::{DataType, Field, Schema, SchemaRef};
use parquet::arrow::ArrowWriter;
use parquet::arrow::arrow_reader::{
    ArrowReaderMetadata, ArrowReaderOptions, ParquetRecordBatchReader,
    ParquetRecordBatchReaderBuilder,
};
use parquet::basic::{Compression, ZstdLevel};
use parquet::file::metadata::{KeyValue, ParquetMetaData};
use parquet::file::properties::WriterProperties;
use parquet::schema::types::ColumnPath;
use std::collections::BTreeMap;
use std::fs::File;
use std::path::{Path, PathBuf};
use std::sync::Arc;

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

/// Writer properties for files of `schema`: zstd, row groups of at most
/// `max_rows`, the given key-value metadata (but for the two hash keys,
/// which [`ParquetFile::finish`] computes: a copied stale value would
/// otherwise be written beside them), and dictionary encoding only for
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
        .set_key_value_metadata(Some(
            metadata
                .into_iter()
                .filter(|kv| kv.key != META_CONTENT_HASH && kv.key != META_METADATA_HASH)
                .collect(),
        ))
        .build()
}

/// A Parquet file being written under a temporary name next to `dest`;
/// [`ParquetFile::finish`] closes, syncs and renames it, with the
/// [`ContentHash`] of every row written and the `metadata_hash` of its
/// metadata in its footer. Dropped unfinished, the temporary file is removed.
pub struct ParquetFile {
    tmp: Temp,
    writer: ArrowWriter<File>,
    dest: PathBuf,
    hash: ContentHash,
    /// The metadata written so far, as a reader will see it (a key given
    /// twice keeps its last value).
    metadata: BTreeMap<String, String>,
}

impl ParquetFile {
    /// A file to be written to `dest` with `schema`: its rows go to a
    /// temporary file beside it, which [`ParquetFile::finish`] renames into place.
    pub fn create(dest: &Path, schema: SchemaRef, props: WriterProperties) -> Result<Self> {
        let tmp = temp_file_for(dest)?;
        let file = tmp
            .file
            .reopen()
            .with_context(|| format!("cannot open {}", tmp.file.path().display()))?;
        let hash = ContentHash::new(schema.fields().len());
        let metadata = props
            .key_value_metadata()
            .into_iter()
            .flatten()
            .filter_map(|kv| Some((kv.key.clone(), kv.value.clone()?)))
            .collect();
        let writer = ArrowWriter::try_new(file, schema, Some(props))?;
        Ok(Self {
            tmp,
            writer,
            dest: dest.to_path_buf(),
            hash,
            metadata,
        })
    }

    /// Appends `batch`, hashing its values for the file's content hash.
    pub fn write(&mut self, batch: &RecordBatch) -> Result<()> {
        self.hash.update(batch)?;
        self.writer
            .write(batch)
            .with_context(|| format!("writing {}", self.dest.display()))
    }

    /// Sets the metadata `key` to `value` (the last value given wins).
    pub fn append_metadata(&mut self, key: &str, value: String) {
        self.metadata.insert(key.to_string(), value.clone());
        self.writer
            .append_key_value_metadata(KeyValue::new(key.to_string(), value));
    }

    /// Closes the writer, syncs the data and moves the file to its name.
    pub fn finish(self) -> Result<()> {
        let (tmp, dest) = self.close()?;
        tmp.persist(&dest)
    }

    /// Closes the writer and syncs the data: the finished temporary file
    /// and its name, for a [`crate::files::FileSet`] to move into place.
    pub(crate) fn close(self) -> Result<(Temp, PathBuf)> {
        let Self {
            tmp,
            mut writer,
            dest,
            hash,
            mut metadata,
        } = self;
        let rows = hash.value();
        writer.append_key_value_metadata(kv(META_CONTENT_HASH, rows.clone()));
        metadata.insert(META_CONTENT_HASH.to_string(), rows);
        writer.append_key_value_metadata(kv(META_METADATA_HASH, metadata_hash(&metadata)));
        writer
            .close()
            .with_context(|| format!("closing {}", dest.display()))?;
        tmp.file.as_file().sync_all()?;
        Ok((tmp, dest))
    }
}

/// `batches` under one schema of `fields` that carries `metadata`, the
/// file's key-value metadata: a table read back keeps what its file said
/// of it (`rtw.config`, `rtw.design`, …), as pyarrow shows it in
/// `schema.metadata`.
pub fn with_metadata(
    batches: Vec<RecordBatch>,
    fields: arrow_schema::Fields,
    metadata: BTreeMap<String, String>,
) -> Result<(Vec<RecordBatch>, SchemaRef)> {
    let schema = Arc::new(
        Schema::new(fields).with_metadata(
            metadata
                .into_iter()
                .collect::<std::collections::HashMap<_, _>>(),
        ),
    );
    let batches = batches
        .into_iter()
        .map(|b| b.with_schema(Arc::clone(&schema)))
        .collect::<Result<_, _>>()?;
    Ok((batches, schema))
}

/// Writes `batch` as one complete Parquet file at `dest` (atomically).
pub fn write_file(dest: &Path, batch: &RecordBatch, metadata: Vec<KeyValue>) -> Result<()> {
    let mut set = crate::files::FileSet::default();
    add_file(&mut set, dest, batch, metadata)?;
    set.commit()
}

/// Writes `batch` as one complete Parquet file for `dest` into `set`, to
/// appear with the set's other files.
pub fn add_file(
    set: &mut crate::files::FileSet,
    dest: &Path,
    batch: &RecordBatch,
    metadata: Vec<KeyValue>,
) -> Result<()> {
    let props = writer_properties(&batch.schema(), batch.num_rows(), metadata);
    let mut f = ParquetFile::create(dest, batch.schema(), props)?;
    f.write(batch)?;
    let (tmp, dest) = f.close()?;
    set.add(tmp, &dest);
    Ok(())
}

/// An open Parquet file: its key-value metadata and a batch reader.
pub struct ParquetInput {
    /// The file's key-value metadata (`rtw.config`, `rtw.seed`, ...).
    pub metadata: BTreeMap<String, String>,
    /// Its row count, from the footer.
    pub rows: i64,
    /// Its rows, batch by batch, checked against the content hash.
    pub reader: VerifiedReader,
}

/// The batches of a Parquet file, checked: a page that does not decode, and
/// (once the last batch has been read) rows that do not hash to the file's
/// `rtw.content_hash`, are errors naming the file. A file that [`open`]
/// accepted without the key has no rtw-scan metadata at all: what a reader
/// needs of rtw-scan's is missing, and it refuses the file for that.
pub struct VerifiedReader {
    inner: ParquetRecordBatchReader,
    path: PathBuf,
    hash: ContentHash,
    expected: Option<String>,
    done: bool,
}

impl VerifiedReader {
    /// The schema of the file's batches.
    pub fn schema(&self) -> arrow_schema::SchemaRef {
        arrow_array::RecordBatchReader::schema(&self.inner)
    }
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

/// Checks that what a file's footer says can be trusted, before anything is
/// read from it. A file with no `rtw.*` key makes no claim (readers refuse
/// it for the key they need). Any other must carry `rtw.content_hash`, and:
/// - with `rtw.metadata_hash` (every file rtw-scan writes now), every `rtw.*`
///   value must hash to it;
/// - without it (files written before it existed), its keys must all be
///   keys of that time ([`KEYS_BEFORE_METADATA_HASH`]: a damaged hash key's
///   name is not), and a scan's config text must hash to its
///   `rtw.config_hash`, which `rtw.seed` and `rtw.variant` must agree with.
///   Such a file's `rtw.version` and wall time are taken as written.
fn check_metadata(path: &Path, meta: &BTreeMap<String, String>) -> Result<()> {
    let shown = path.display();
    let Some(ours) = meta.keys().find(|k| k.starts_with("rtw.")) else {
        return Ok(());
    };
    let refuse = |why: String| {
        anyhow!(
            "{shown}: {why}: its footer was edited or damaged; restore the file or rerun what made it"
        )
    };
    if !meta.contains_key(META_CONTENT_HASH) {
        return Err(refuse(format!(
            "it has rtw-scan metadata (`{ours}`) but no `{META_CONTENT_HASH}` to check its rows with"
        )));
    }
    if let Some(want) = meta.get(META_METADATA_HASH) {
        let got = metadata_hash(meta);
        if got != *want {
            return Err(refuse(format!(
                "its metadata hashes to {got}, not to the {want} written with it (`{META_METADATA_HASH}`)"
            )));
        }
        return Ok(());
    }
    if let Some(k) = meta
        .keys()
        .find(|k| !KEYS_BEFORE_METADATA_HASH.contains(&k.as_str()))
    {
        return Err(refuse(format!(
            "it has no `{META_METADATA_HASH}`, yet a key `{k}` that rtw-scan never wrote without one"
        )));
    }
    let Some(text) = meta.get(META_CONFIG) else {
        return Ok(());
    };
    let hash = meta.get(META_CONFIG_HASH).map_or("(none)", String::as_str);
    if config::config_hash(text) != hash {
        return Err(refuse(format!(
            "its `{META_CONFIG}` does not hash to its `{META_CONFIG_HASH}` {hash}"
        )));
    }
    // A config that no longer parses is refused by the reader that needs it,
    // with the field named.
    let Ok(cfg) = config::parse(text) else {
        return Ok(());
    };
    let expect = [
        (META_SEED, cfg.seed.to_string()),
        (META_VARIANT, ModelChoices::of(&cfg.simulation).to_string()),
    ];
    for (key, want) in expect {
        if let Some(got) = meta.get(key).filter(|got| **got != want) {
            return Err(refuse(format!(
                "its `{key}` {got} disagrees with its config's {want}"
            )));
        }
    }
    Ok(())
}

/// Opens a Parquet file for reading, with errors naming the path; its
/// metadata is checked at once (`check_metadata`), its batches against its
/// content hash as they are read ([`VerifiedReader`]).
///
/// Files rewritten by other tools read as rtw-scan's own: any codec but
/// Brotli and LZO (pyarrow writes snappy by default, others gzip or lz4;
/// those two are refused up front, naming the codec), and string columns
/// of any Arrow string type (polars writes large strings, others string
/// views) read as the plain `Utf8` strings and `Int32`-keyed dictionaries
/// rtw-scan writes, so their checks and content hash are the same.
pub fn open(path: &Path, batch_size: usize) -> Result<ParquetInput> {
    // Told from the path first: a FIFO or device never ends (and opening a
    // FIFO waits for a writer); a Parquet file is read by seeking.
    if std::fs::metadata(path).is_ok_and(|m| !m.is_file()) {
        bail!(
            "{} is not a regular file: not a Parquet file",
            path.display()
        );
    }
    let file = File::open(path).with_context(|| format!("cannot open {}", path.display()))?;
    let reopened = file
        .try_clone()
        .with_context(|| format!("cannot open {}", path.display()))?;
    let builder = ParquetRecordBatchReaderBuilder::try_new(file)
        .with_context(|| format!("{} is not a readable Parquet file", path.display()))?;
    refuse_unsupported_codecs(path, builder.metadata())?;
    let builder = match plain_strings(builder.schema()) {
        None => builder,
        Some(schema) => {
            let options = ArrowReaderOptions::new().with_schema(schema);
            let meta = ArrowReaderMetadata::try_new(Arc::clone(builder.metadata()), options)
                .with_context(|| {
                    format!(
                        "{}: its string columns cannot be read as strings",
                        path.display()
                    )
                })?;
            ParquetRecordBatchReaderBuilder::new_with_metadata(reopened, meta)
        }
    };
    let meta = builder.metadata().file_metadata();
    let rows = meta.num_rows();
    let metadata: BTreeMap<String, String> = meta
        .key_value_metadata()
        .into_iter()
        .flatten()
        .filter_map(|kv| Some((kv.key.clone(), kv.value.clone()?)))
        .collect();
    check_metadata(path, &metadata)?;
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

/// Refuses a file with a column compressed by a codec rtw-scan cannot
/// decode (Brotli, LZO), naming it and the codecs it reads, before any page
/// is read: otherwise the page would "not decode" and the file be called corrupt.
fn refuse_unsupported_codecs(path: &Path, meta: &ParquetMetaData) -> Result<()> {
    let unsupported = meta
        .row_groups()
        .iter()
        .flat_map(|g| g.columns())
        .find_map(|c| match c.compression() {
            Compression::BROTLI(_) => Some("Brotli"),
            Compression::LZO => Some("LZO"),
            _ => None,
        });
    match unsupported {
        Some(c) => Err(anyhow!(
            "{}: its columns are compressed with {}, which rtw-scan does not read: it reads \
             zstd, snappy, gzip, lz4 and uncompressed files; rewrite it with one of those (e.g. \
             pyarrow.parquet.write_table(table, path, compression=\"zstd\"))",
            path.display(),
            c
        )),
        None => Ok(()),
    }
}

/// `schema` with every string column as the types rtw-scan writes: `Utf8`,
/// and dictionaries of `Int32` keys over `Utf8` (the label column); `None`
/// when it has no other string type (large strings, string views, other
/// dictionary keys).
fn plain_strings(schema: &SchemaRef) -> Option<SchemaRef> {
    let plain = |t: &DataType| match t {
        DataType::LargeUtf8 | DataType::Utf8View => Some(DataType::Utf8),
        DataType::Dictionary(k, v)
            if matches!(
                **v,
                DataType::Utf8 | DataType::LargeUtf8 | DataType::Utf8View
            ) && (**k != DataType::Int32 || **v != DataType::Utf8) =>
        {
            Some(DataType::Dictionary(
                Box::new(DataType::Int32),
                Box::new(DataType::Utf8),
            ))
        }
        _ => None,
    };
    if !schema
        .fields()
        .iter()
        .any(|f| plain(f.data_type()).is_some())
    {
        return None;
    }
    let fields: Vec<Field> = schema
        .fields()
        .iter()
        .map(|f| match plain(f.data_type()) {
            Some(t) => f.as_ref().clone().with_data_type(t),
            None => f.as_ref().clone(),
        })
        .collect();
    Some(Arc::new(Schema::new_with_metadata(
        fields,
        schema.metadata().clone(),
    )))
}
