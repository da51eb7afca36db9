//! Column tables: a file's columns listed once, each with its name, unit,
//! meaning and how to read it from a row, and the Arrow schema and record
//! batches made from that one list, so they cannot drift apart. The scan
//! rows (`scan_rows::COLUMNS`) and the bifurcation files are written this
//! way.
//!
//! The columns of a batch read back are taken by name and type
//! ([`f64_column`], `i64_column`, [`label_column`]).
//!
//! Each column's unit and meaning go to its Arrow field metadata under the
//! keys [`UNIT`] and [`DESCRIPTION`], so a reader finds them in the file
//! itself (pyarrow: `pq.read_schema(path).field("fn").metadata`). Units: SI
//! symbols; `1` for a dimensionless number (a ratio, a fraction, a count);
//! `-` for what is not a quantity (ids, labels, text, flags).

use anyhow::{Result, anyhow, bail};
use arrow_array::cast::AsArray;
use arrow_array::types::{Float64Type, Int32Type, Int64Type};
use arrow_array::{
    Array, ArrayRef, ArrowPrimitiveType, BooleanArray, DictionaryArray, Float64Array, Int32Array,
    Int64Array, PrimitiveArray, RecordBatch, StringArray,
};
use arrow_schema::{DataType, Field, Schema, SchemaRef};
use rtw_model::Label;
use std::collections::HashMap;
use std::sync::Arc;

/// Field-metadata key of a column's unit.
pub const UNIT: &str = "unit";
/// Field-metadata key of a column's meaning.
pub const DESCRIPTION: &str = "description";

/// A column with its unit and meaning in the field metadata.
pub(crate) fn field(
    name: impl Into<String>,
    ty: DataType,
    nullable: bool,
    unit: &str,
    description: &str,
) -> Field {
    Field::new(name, ty, nullable).with_metadata(HashMap::from([
        (UNIT.to_string(), unit.to_string()),
        (DESCRIPTION.to_string(), description.to_string()),
    ]))
}

/// The Arrow type of a label column: a dictionary with signed `Int32` keys
/// over strings (pandas and polars read it as categorical).
pub(crate) fn label_type() -> DataType {
    DataType::Dictionary(Box::new(DataType::Int32), Box::new(DataType::Utf8))
}

/// How a column reads its value from a row of type `R`.
pub enum Get<R> {
    /// A float.
    F64(fn(&R) -> Option<f64>),
    /// An integer.
    I64(fn(&R) -> Option<i64>),
    /// A yes or no.
    Bool(fn(&R) -> Option<bool>),
    /// A text.
    Str(fn(&R) -> Option<&str>),
    /// A label: the row's index into a fixed list of names, stored as a
    /// dictionary column (`label_type`) over that list.
    Label {
        /// The row's index into `names`.
        index: fn(&R) -> usize,
        /// The names.
        names: fn() -> Vec<&'static str>,
    },
}

/// One column of a table of rows of type `R`.
pub struct Column<R> {
    pub(crate) name: &'static str,
    /// Section of a row's text form (`simulate`); empty where unused.
    pub(crate) group: &'static str,
    pub(crate) nullable: bool,
    /// Unit (`1`: dimensionless, `-`: not a quantity).
    pub(crate) unit: &'static str,
    pub(crate) description: &'static str,
    pub(crate) get: Get<R>,
}

/// A column with no text form (no group): the bifurcation and continuation
/// files' columns.
pub const fn column<R>(
    name: &'static str,
    nullable: bool,
    unit: &'static str,
    description: &'static str,
    get: Get<R>,
) -> Column<R> {
    Column {
        name,
        group: "",
        nullable,
        unit,
        description,
        get,
    }
}

impl<R> Column<R> {
    /// The column's Arrow type.
    pub(crate) fn data_type(&self) -> DataType {
        match self.get {
            Get::F64(_) => DataType::Float64,
            Get::I64(_) => DataType::Int64,
            Get::Bool(_) => DataType::Boolean,
            Get::Str(_) => DataType::Utf8,
            Get::Label { .. } => label_type(),
        }
    }

    /// The column's values over `rows`.
    pub(crate) fn array(&self, rows: &[R]) -> ArrayRef {
        match &self.get {
            Get::F64(g) => Arc::new(rows.iter().map(g).collect::<Float64Array>()),
            Get::I64(g) => Arc::new(rows.iter().map(g).collect::<Int64Array>()),
            Get::Bool(g) => Arc::new(rows.iter().map(g).collect::<BooleanArray>()),
            Get::Str(g) => Arc::new(rows.iter().map(g).collect::<StringArray>()),
            Get::Label { index, names } => {
                let keys: Int32Array = rows.iter().map(|r| index(r) as i32).collect();
                let values = StringArray::from_iter_values(names());
                Arc::new(
                    DictionaryArray::<Int32Type>::try_new(keys, Arc::new(values))
                        .expect("label indices are in the name list"),
                )
            }
        }
    }
}

/// The Arrow schema of a table: its columns with their units and meanings.
pub fn schema<R>(columns: &[Column<R>]) -> SchemaRef {
    let fields: Vec<Field> = columns
        .iter()
        .map(|c| field(c.name, c.data_type(), c.nullable, c.unit, c.description))
        .collect();
    Arc::new(Schema::new(fields))
}

/// Rows → one record batch of `schema` (made by [`schema`] from `columns`).
pub fn batch<R>(columns: &[Column<R>], schema: SchemaRef, rows: &[R]) -> RecordBatch {
    let arrays: Vec<ArrayRef> = columns.iter().map(|c| c.array(rows)).collect();
    RecordBatch::try_new(schema, arrays).expect("the arrays are made from the schema's columns")
}

/// A column of primitive type `T` of a batch read back, by name.
fn primitive_column<'a, T: ArrowPrimitiveType>(
    batch: &'a RecordBatch,
    name: &str,
) -> Result<&'a PrimitiveArray<T>> {
    let col = batch
        .column_by_name(name)
        .ok_or_else(|| anyhow!("column `{name}` is missing"))?;
    col.as_primitive_opt::<T>().ok_or_else(|| {
        anyhow!(
            "column `{name}` is {}, expected {}",
            col.data_type(),
            T::DATA_TYPE
        )
    })
}

/// A `Float64` column of a batch read back, by name.
pub fn f64_column<'a>(batch: &'a RecordBatch, name: &str) -> Result<&'a Float64Array> {
    primitive_column::<Float64Type>(batch, name)
}

/// An `Int64` column of a batch read back, by name.
pub(crate) fn i64_column<'a>(batch: &'a RecordBatch, name: &str) -> Result<&'a Int64Array> {
    primitive_column::<Int64Type>(batch, name)
}

/// The `outcome` column of a batch read back, decoded to labels.
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
