//! What the HTML report draws of a scan too large to send row by row: its
//! rows aggregated, as datashader does, rather than a random subset.
//!
//! - Each plotted column becomes one byte per row ([`Coded`]): the row's bin
//!   on an equal-width grid of [`CODE_BINS`] bins over the column's range, or
//!   [`CODE_NONE`]. The page counts every row in a brushed range from them
//!   (a row counts when its bin meets the range), and re-bins the maps of the
//!   brushed rows.
//! - [`density`]: per outcome, the rows counted on the grid of two coded
//!   columns: the 2-D map of every row, drawn before any brushing.
//! - [`stratified`]: the rows that the views drawing one mark per row show:
//!   every outcome an equal share, and an outcome with fewer rows than its
//!   share all of them, so rare outcomes are never thinned out.
//!
//! A million rows of nine columns code to 9 MB, read once.

use crate::hash::mix;
use crate::io::scan_rows::label_index;
use crate::io::table::label_column;
use anyhow::{Result, anyhow, bail};
use arrow_array::cast::AsArray;
use arrow_array::types::{Float64Type, Int64Type, UInt64Type};
use arrow_array::{ArrowPrimitiveType, PrimitiveArray, RecordBatch};
use rtw_model::Label;

/// The bins of a coded column: codes `0..CODE_BINS`.
pub const CODE_BINS: usize = 255;
/// The code of a row with no value (null or not finite).
pub const CODE_NONE: u8 = 255;

/// A column coded one byte per row.
#[derive(Clone, Debug, PartialEq)]
pub struct Coded {
    /// The smallest and largest finite value; `None` when there is none
    /// (then every code is [`CODE_NONE`]).
    pub range: Option<[f64; 2]>,
    /// Each row's [`code`] on `range`.
    pub codes: Vec<u8>,
}

/// The bin of `v` on `CODE_BINS` equal bins of `[lo, hi]`: the largest
/// value is in the last bin. A range of one value (a column the scan holds
/// fixed) is all the middle bin, so a map drawn over that value widened
/// both ways shows it at the value.
pub fn code(v: f64, [lo, hi]: [f64; 2]) -> u8 {
    if !v.is_finite() {
        return CODE_NONE;
    }
    if hi <= lo {
        return (CODE_BINS / 2) as u8;
    }
    let k = ((v - lo) / (hi - lo) * CODE_BINS as f64).floor();
    k.clamp(0.0, (CODE_BINS - 1) as f64) as u8
}

/// The values of a numeric column (Float64, Int64 or UInt64), nulls as NaN.
fn values(batches: &[RecordBatch], column: &str) -> Result<Vec<f64>> {
    fn push<T: ArrowPrimitiveType>(
        out: &mut Vec<f64>,
        a: &PrimitiveArray<T>,
        f: fn(T::Native) -> f64,
    ) {
        out.extend(a.iter().map(|v| v.map_or(f64::NAN, f)));
    }
    let mut out = Vec::new();
    for batch in batches {
        let col = batch
            .column_by_name(column)
            .ok_or_else(|| anyhow!("column `{column}` is missing"))?;
        if let Some(a) = col.as_primitive_opt::<Float64Type>() {
            push(&mut out, a, |v| v);
        } else if let Some(a) = col.as_primitive_opt::<Int64Type>() {
            push(&mut out, a, |v| v as f64);
        } else if let Some(a) = col.as_primitive_opt::<UInt64Type>() {
            push(&mut out, a, |v| v as f64);
        } else {
            bail!(
                "column `{column}` is {}, not a number column (Float64, Int64 or UInt64)",
                col.data_type()
            );
        }
    }
    Ok(out)
}

/// `column` of the rows in `batches`, coded on its own range.
pub fn coded(batches: &[RecordBatch], column: &str) -> Result<Coded> {
    let v = values(batches, column)?;
    let range = v
        .iter()
        .filter(|x| x.is_finite())
        .fold(None, |r: Option<[f64; 2]>, &x| {
            Some(r.map_or([x, x], |[lo, hi]| [lo.min(x), hi.max(x)]))
        });
    let codes = match range {
        Some(r) => v.iter().map(|&x| code(x, r)).collect(),
        None => vec![CODE_NONE; v.len()],
    };
    Ok(Coded { range, codes })
}

/// Each row's outcome as its index in [`Label::ALL`].
pub fn outcome_codes(batches: &[RecordBatch]) -> Result<Vec<u8>> {
    let mut out = Vec::new();
    for batch in batches {
        out.extend(
            label_column(batch)?
                .into_iter()
                .map(|l| label_index(l) as u8),
        );
    }
    Ok(out)
}

/// Per class `0..classes`, its rows counted on the `CODE_BINS` × `CODE_BINS`
/// grid of two coded columns (row-major: `y * CODE_BINS + x`); rows of
/// another class, or with no value in either column, are not on the map.
pub fn density(class: &[u8], classes: usize, x: &[u8], y: &[u8]) -> Vec<Vec<u32>> {
    let mut grids = vec![vec![0u32; CODE_BINS * CODE_BINS]; classes];
    for ((&k, &cx), &cy) in class.iter().zip(x).zip(y) {
        if (k as usize) < classes && cx != CODE_NONE && cy != CODE_NONE {
            grids[k as usize][cy as usize * CODE_BINS + cx as usize] += 1;
        }
    }
    grids
}

/// At most `total` row indices, in order: the labels share `total` equally,
/// a label with fewer rows than its share keeping all of them and leaving
/// the rest to the others; within a label, the rows with the smallest keys
/// of (seed, sample id), so the choice is seeded and does not depend on the
/// rows' order.
pub fn stratified(outcomes: &[u8], ids: &[i64], total: usize, seed: u64) -> Vec<u32> {
    let mut by_label: Vec<Vec<(u64, u32)>> = vec![Vec::new(); Label::ALL.len()];
    let seed_key = mix(seed);
    for (row, (&o, &id)) in outcomes.iter().zip(ids).enumerate() {
        by_label[o as usize].push((mix(seed_key ^ mix(id as u64)), row as u32));
    }
    // Water-filling: the smallest labels first, each taking at most an
    // equal share of what is left.
    let mut order: Vec<usize> = (0..by_label.len())
        .filter(|&l| !by_label[l].is_empty())
        .collect();
    order.sort_by_key(|&l| (by_label[l].len(), l));
    let mut left = total;
    let mut chosen = Vec::with_capacity(total.min(outcomes.len()));
    for (k, &l) in order.iter().enumerate() {
        let share = left / (order.len() - k);
        let rows = &mut by_label[l];
        let take = rows.len().min(share);
        if take < rows.len() {
            rows.select_nth_unstable(take);
        }
        chosen.extend(rows[..take].iter().map(|&(_, r)| r));
        left -= take;
    }
    chosen.sort_unstable();
    chosen
}

/// The sample ids of the rows in `batches`.
pub fn sample_ids(batches: &[RecordBatch]) -> Result<Vec<i64>> {
    let mut out = Vec::new();
    for batch in batches {
        out.extend_from_slice(crate::io::table::i64_column(batch, "sample_id")?.values());
    }
    Ok(out)
}

/// What the report sends of a scan in place of its rows.
#[derive(Clone, Debug)]
pub struct Views {
    /// Each row's outcome ([`outcome_codes`]).
    pub outcomes: Vec<u8>,
    /// The columns asked for, coded, in the order asked.
    pub columns: Vec<(String, Coded)>,
    /// The rows per outcome ([`Label::ALL`]'s order) on the grid of the columns `x` and `y`.
    pub density: Vec<Vec<u32>>,
    /// The rows the one-mark-per-row views draw ([`stratified`]).
    pub sample: Vec<u32>,
}

/// The views of the rows in `batches`: `columns` coded, the density of the
/// columns `x` and `y` (two of `columns`), and a stratified sample of at
/// most `sample` rows, seeded by `seed`.
pub fn views(
    batches: &[RecordBatch],
    columns: &[String],
    (x, y): (&str, &str),
    sample: usize,
    seed: u64,
) -> Result<Views> {
    let outcomes = outcome_codes(batches)?;
    let columns = columns
        .iter()
        .map(|c| Ok((c.clone(), coded(batches, c)?)))
        .collect::<Result<Vec<_>>>()?;
    let of = |name: &str| {
        columns
            .iter()
            .find(|(c, _)| c == name)
            .map(|(_, coded)| &coded.codes)
            .ok_or_else(|| anyhow!("the density's column `{name}` is not one of the columns coded"))
    };
    let density = density(&outcomes, Label::ALL.len(), of(x)?, of(y)?);
    let sample = stratified(&outcomes, &sample_ids(batches)?, sample, seed);
    Ok(Views {
        outcomes,
        columns,
        density,
        sample,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_code_is_the_bin_of_equal_width_bins_and_none_has_its_own() {
        let r = [0.0, 255.0];
        assert_eq!(code(0.0, r), 0);
        assert_eq!(code(0.999, r), 0);
        assert_eq!(code(1.0, r), 1);
        assert_eq!(code(254.5, r), 254);
        // The largest value is in the last bin, not one past it.
        assert_eq!(code(255.0, r), 254);
        assert_eq!(code(f64::NAN, r), CODE_NONE);
        assert_eq!(code(f64::INFINITY, r), CODE_NONE);
        assert_eq!(
            code(3.0, [3.0, 3.0]),
            127,
            "one value: the middle of 255 bins"
        );
    }

    #[test]
    fn the_density_counts_every_row_with_both_values_once() {
        let o = [0, 0, 1, 2, 2, 3];
        let x = [0, 0, 3, CODE_NONE, 7, 1];
        let y = [1, 1, 2, 4, 0, 1];
        let g = density(&o, 3, &x, &y);
        assert_eq!(g.len(), 3, "class 3 is beyond the 3 asked for");
        assert_eq!(g[0][CODE_BINS], 2, "x 0, y 1");
        assert_eq!(g[1][2 * CODE_BINS + 3], 1);
        assert_eq!(g[2][7], 1);
        let total: u32 = g.iter().flatten().sum();
        assert_eq!(
            total, 4,
            "neither the row with no x nor the class-3 row is on the map"
        );
    }

    #[test]
    fn a_stratified_sample_keeps_every_rare_row_and_shares_the_rest_equally() {
        // 1000 of label 0, 300 of label 1, 7 of label 2; 100 rows to draw.
        let mut o = vec![0u8; 1000];
        o.extend(vec![1u8; 300]);
        o.extend(vec![2u8; 7]);
        let ids: Vec<i64> = (0..o.len() as i64).collect();
        let s = stratified(&o, &ids, 100, 9);
        let count = |l: u8| s.iter().filter(|&&r| o[r as usize] == l).count();
        assert_eq!(count(2), 7, "the rare label is kept whole");
        // The 93 left are shared: 46 and 47 (the larger label last).
        assert_eq!((count(1), count(0)), (46, 47));
        assert!(s.windows(2).all(|w| w[0] < w[1]), "in row order, once each");
        // Seeded, and independent of the rows' order.
        assert_eq!(s, stratified(&o, &ids, 100, 9));
        assert_ne!(s, stratified(&o, &ids, 100, 10));
        let rev_o: Vec<u8> = o.iter().rev().copied().collect();
        let rev_ids: Vec<i64> = ids.iter().rev().copied().collect();
        let mut back: Vec<i64> = stratified(&rev_o, &rev_ids, 100, 9)
            .iter()
            .map(|&r| rev_ids[r as usize])
            .collect();
        back.sort_unstable();
        let fwd: Vec<i64> = s.iter().map(|&r| ids[r as usize]).collect();
        assert_eq!(back, fwd);
        // Fewer rows than asked: all of them.
        assert_eq!(stratified(&o[..5], &ids[..5], 100, 9).len(), 5);
    }
}
