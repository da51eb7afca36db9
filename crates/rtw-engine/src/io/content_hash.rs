//! The content hash of a table's rows and the hash of the metadata beside
//! them, written with them and checked by every read.

use crate::hash::mix;
use crate::io::metadata::META_METADATA_HASH;
use anyhow::{Result, bail};
use arrow_array::cast::AsArray;
use arrow_array::types::{Float64Type, Int8Type, Int32Type, Int64Type};
use arrow_array::{Array, RecordBatch};
use arrow_schema::DataType;
use std::collections::BTreeMap;

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

    /// The hash of an empty table of `columns` columns.
    pub fn new(columns: usize) -> Self {
        Self {
            columns: vec![0; columns],
        }
    }

    fn fold(h: &mut u64, word: u64) {
        *h = mix(*h ^ word);
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

    /// The hash, as it is written in `META_CONTENT_HASH`: 16 hex digits.
    pub fn value(&self) -> String {
        let mut h = 0;
        for c in &self.columns {
            Self::fold(&mut h, *c);
        }
        format!("{h:016x}")
    }
}

/// The hash of a file's metadata, as it is written in [`META_METADATA_HASH`]:
/// every `rtw.*` key and its value but that key itself, in key order, each
/// folded as a string the way [`ContentHash`] folds a string value. It covers
/// `rtw.content_hash`, so a file's rows and everything its readers take from
/// its footer (the config, the version, the shard, the wall time...) hang on
/// this one value; a key added, removed, renamed or edited changes it.
/// `meta` is the footer as a reader sees it (the last value of a repeated
/// key), so it covers exactly what is read.
pub(crate) fn metadata_hash(meta: &BTreeMap<String, String>) -> String {
    let mut h = 0;
    for (k, v) in meta
        .iter()
        .filter(|(k, _)| k.starts_with("rtw.") && *k != META_METADATA_HASH)
    {
        ContentHash::fold_str(&mut h, k);
        ContentHash::fold_str(&mut h, v);
    }
    format!("{h:016x}")
}
