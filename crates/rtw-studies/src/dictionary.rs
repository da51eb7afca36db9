//! The data dictionary: the unit and meaning of every column of every Parquet
//! file rtw-scan writes, gathered from the column tables of [`rtw_engine::io`]
//! and `bifurcation` (this module sits above both).
//!
//! Each column's unit and description live beside its definition and are
//! written to the Arrow field metadata (`io::table`). [`markdown`]
//! renders the same schemas as docs/data-dictionary.md
//! (`cargo run -p rtw-scan --example data_dictionary > docs/data-dictionary.md`;
//! a test keeps the committed page equal to it).

use crate::bifurcation::files::{points_schema, steps_schema};
use crate::continuation;
use arrow_schema::{DataType, Field, SchemaRef};
use rtw_engine::analysis::assignments;
use rtw_engine::io::table::{DESCRIPTION, UNIT};
use rtw_engine::io::{scan_rows, trace};
use std::fmt::Write as _;

/// One kind of Parquet file rtw-scan writes.
pub(crate) struct ParquetOutput {
    /// Which files (name pattern and the command that writes them).
    files: &'static str,
    /// What one row is.
    row: &'static str,
    schema: SchemaRef,
}

/// Every kind of Parquet file rtw-scan writes, with its schema.
pub(crate) fn outputs() -> Vec<ParquetOutput> {
    vec![
        ParquetOutput {
            files: "`samples.parquet` (`run`, `merge`) and `part-K.parquet` (`run --shard K/N`)",
            row: "one sample of a scan",
            schema: scan_rows::schema(),
        },
        ParquetOutput {
            files: "robustness columns of `samples.parquet` (`run` with `robustness.*`)",
            row: "one sample of a scan, these columns after the ones above, each only when its \
                  measure is asked for (the same keys follow the columns in `simulate --json` \
                  and Python's `Outcome`). A measure that is infinite is inf in Parquet, \
                  `\"inf\"` in JSON (which has no number for it) and `float('inf')` in Python: an \
                  MFPT with no fall counted has `mfpt` and `mfpt_hi` infinite. Null (JSON null, \
                  Python `None`) is a measure not computed: no stable gait, or not computable",
            schema: rtw_engine::io::robustness_columns::all_columns_schema(),
        },
        ParquetOutput {
            files: "trace file (`simulate --trace FILE`)",
            row: "one recorded instant of a run (every `trace_dt` seconds, or every step)",
            schema: trace::trace_schema(),
        },
        ParquetOutput {
            files: "assignments file (`cluster --assignments FILE`)",
            row: "one failed sample and its k-means cluster",
            schema: assignments::assignments_schema(),
        },
        ParquetOutput {
            files: "`FILE.parquet` (`bifurcation --out FILE.parquet`)",
            row: "one value of the swept parameter",
            schema: points_schema(),
        },
        ParquetOutput {
            files: "`FILE.steps.parquet` (`bifurcation --out FILE.parquet`)",
            row: "one recorded step at one value",
            schema: steps_schema(),
        },
        ParquetOutput {
            files: "`FILE.parquet` (`continuation --out FILE.parquet`)",
            row: "one point of a branch at one step of its orbit",
            schema: continuation::files::branch_schema(),
        },
        ParquetOutput {
            files: "`FILE.special.parquet` (`continuation --out FILE.parquet`)",
            row: "a bifurcation, or a branch's first or last point",
            schema: continuation::files::special_schema(),
        },
        ParquetOutput {
            files: "`FILE.curve.parquet` (`continuation --curve P --out FILE.parquet`)",
            row: "one point of a fold or period-doubling curve in two inputs",
            schema: continuation::files::curve_schema(),
        },
        ParquetOutput {
            files: "`FILE.parquet` (`basin --out FILE.parquet`)",
            row: "one grid point of a basin slice",
            schema: crate::basin::files::schema(),
        },
        ParquetOutput {
            files: "`DIR/search.parquet` (`design CONFIG --out DIR`)",
            row: "one evaluated design of a design search, in the order of evaluation",
            schema: crate::search::files::search_schema(),
        },
        ParquetOutput {
            files: "`DIR/designs.parquet` (`design CONFIG --out DIR`)",
            row: "one reported design, profiled again on the fine grid",
            schema: crate::search::files::designs_schema(),
        },
        ParquetOutput {
            files: "`DIR/archive.parquet` (`design CONFIG --out DIR`)",
            row: "one elite of the search's archive: the best design of its cell",
            schema: crate::search::files::archive_schema(),
        },
    ]
}

/// A field's unit and description, if its metadata has both (non-empty).
pub(crate) fn unit_and_description(f: &Field) -> Option<(&str, &str)> {
    let get = |key| {
        f.metadata()
            .get(key)
            .map(String::as_str)
            .filter(|s| !s.is_empty())
    };
    Some((get(UNIT)?, get(DESCRIPTION)?))
}

fn type_name(ty: &DataType) -> String {
    match ty {
        DataType::Float64 => "float64".into(),
        DataType::Int64 => "int64".into(),
        DataType::Int8 => "int8".into(),
        DataType::Utf8 => "string".into(),
        DataType::Boolean => "bool".into(),
        DataType::Dictionary(_, v) if **v == DataType::Utf8 => "string (dictionary)".into(),
        other => other.to_string(),
    }
}

/// docs/data-dictionary.md.
pub fn markdown() -> String {
    let mut s = String::from(
        "# Data dictionary\n\n\
         Generated by `cargo run -p rtw-scan --example data_dictionary > docs/data-dictionary.md`\n\
         from the schemas rtw-scan writes (a test fails if this page differs). The same\n\
         unit and description are in each file's Arrow field metadata, under the keys\n\
         `unit` and `description` (pyarrow: `pq.read_schema(path).field(\"fn\").metadata`).\n\n\
         Units: SI symbols; `1` for a dimensionless number (a ratio, a fraction, a count);\n\
         `-` for what is not a quantity (ids, labels, text, flags). \"null\" marks a column\n\
         that can be empty. What each file holds besides its rows (config, seed, version,\n\
         variant in the file metadata) and where it is written:\n\
         [results-on-disk.md](results-on-disk.md). The model behind the columns:\n\
         [model.md](model.md).\n",
    );
    for o in outputs() {
        let _ = write!(
            s,
            "\n## {}\n\nOne row: {}.\n\n| column | type | unit | meaning |\n|---|---|---|---|\n",
            o.files, o.row
        );
        for f in o.schema.fields() {
            let (unit, description) = unit_and_description(f).unwrap_or(("?", "?"));
            let null = if f.is_nullable() { ", null" } else { "" };
            let _ = writeln!(
                s,
                "| `{}` | {}{} | {} | {} |",
                f.name(),
                type_name(f.data_type()),
                null,
                unit,
                rtw_engine::io::markdown::cell(description)
            );
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    #[test]
    fn every_column_of_every_output_has_a_unit_and_a_description() {
        let mut missing = Vec::new();
        for o in outputs() {
            assert!(!o.schema.fields().is_empty(), "{} has no columns", o.files);
            for f in o.schema.fields() {
                if unit_and_description(f).is_none() {
                    missing.push(format!("{}: {}", o.files, f.name()));
                }
            }
        }
        assert!(
            missing.is_empty(),
            "columns without unit or description: {missing:#?}"
        );
    }

    #[test]
    fn the_committed_data_dictionary_is_the_generated_one() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/data-dictionary.md");
        let committed = std::fs::read_to_string(&path).unwrap_or_default();
        assert!(
            committed == markdown(),
            "docs/data-dictionary.md is out of date: run \
             `cargo run -p rtw-scan --example data_dictionary > docs/data-dictionary.md`"
        );
    }
}
