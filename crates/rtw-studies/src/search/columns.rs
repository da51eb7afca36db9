//! The columns of a design search's files (`search.parquet`,
//! `designs.parquet`, `archive.parquet`): each named with its unit and
//! meaning (docs/data-dictionary.md), and the tables of those rows.

use super::summary::width;
use super::{Evaluation, Reported, SearchSettings};
use arrow_array::RecordBatch;
use rtw_engine::io::table::{self, Column, Get, column};

/// A row of any of the files: an evaluation, the rod length, and (reported
/// designs) what the search had found.
struct Line {
    e: Evaluation,
    /// The gait the search is of (`None`: any stable gait).
    gait: Option<rtw_model::Label>,
    length: f64,
    found: Option<Evaluation>,
    checked: Option<super::check::Checked>,
    /// Its cell, in the archive's file.
    cell: Option<super::archive::Cell>,
}

impl Line {
    /// The row of evaluation `e` of the search of `s`, with nothing found,
    /// checked or placed in a cell.
    fn of(s: &SearchSettings, e: &Evaluation) -> Line {
        Line {
            e: e.clone(),
            gait: s.gait,
            length: s.length,
            found: None,
            checked: None,
            cell: None,
        }
    }
}

fn design_columns() -> Vec<Column<Line>> {
    vec![
        column(
            "index",
            false,
            "1",
            "the design's place in the order of evaluation",
            Get::I64(|r| Some(r.e.index as i64)),
        ),
        column(
            "length",
            false,
            "m",
            "rod length L (fixed)",
            Get::F64(|r| Some(r.length)),
        ),
        column(
            "rho",
            false,
            "kg/m",
            "mass per length ρ of a rod",
            Get::F64(|r| Some(r.e.design[0])),
        ),
        column(
            "alpha",
            false,
            "1",
            "connection ratio α",
            Get::F64(|r| Some(r.e.design[1])),
        ),
        column(
            "fn",
            false,
            "Hz",
            "design eigen-frequency f_n",
            Get::F64(|r| Some(r.e.design[2])),
        ),
        column(
            "zeta",
            false,
            "1",
            "damping ratio ζ",
            Get::F64(|r| Some(r.e.design[3])),
        ),
        column(
            "feasible",
            false,
            "-",
            "whether every objective is defined (it does not fall)",
            Get::Bool(|r| Some(r.e.feasible())),
        ),
        column(
            "infeasible",
            true,
            "-",
            "why not: no stable slope (of the gait) in the range, or not that gait at speed_phi",
            Get::Str(|r| r.e.infeasible.as_deref()),
        ),
        column(
            "phi_lo",
            true,
            "rad",
            "the widest interval of stable slopes (of the gait, if the config names one): its lowest \
             simulated slope; in designs.parquet, the widest run of directly checked slopes with no \
             failure in the fine profile's interval",
            Get::F64(|r| r.e.phi_lo),
        ),
        column(
            "phi_hi",
            true,
            "rad",
            "its highest simulated slope",
            Get::F64(|r| r.e.phi_hi),
        ),
        column(
            "slope_range",
            true,
            "rad",
            "phi_hi − phi_lo",
            Get::F64(|r| width(&r.e)),
        ),
        column(
            "phi_min",
            true,
            "rad",
            "the shallowest stable slope (of the gait)",
            Get::F64(|r| r.e.phi_min),
        ),
        column(
            "label_at_speed_phi",
            true,
            "-",
            "the gait at speed_phi (objective speed)",
            Get::Str(|r| r.e.label_at_speed_phi.map(|l| l.as_str())),
        ),
        column(
            "speed",
            true,
            "m/s",
            "mean downhill speed at speed_phi",
            Get::F64(|r| r.e.speed),
        ),
        column(
            "label_at_mfpt_phi",
            true,
            "-",
            "the gait at mfpt_phi (objective mfpt)",
            Get::Str(|r| r.e.label_at_mfpt_phi.map(|l| l.as_str())),
        ),
        column(
            "mfpt",
            true,
            "1",
            "mean first-passage time (expected steps to fall) at mfpt_phi on a rough slope of \
             robustness.sigma (docs/robustness.md)",
            Get::F64(|r| r.e.mfpt),
        ),
        column(
            "runs",
            false,
            "1",
            "simulations spent on the design",
            Get::I64(|r| Some(r.e.runs as i64)),
        ),
    ]
}

/// The sub-search and generation columns, and the walk share.
fn round_column() -> Column<Line> {
    column(
        "round",
        false,
        "1",
        "the sub-search (weight) of a two-objective search",
        Get::I64(|r: &Line| Some(r.e.round as i64)),
    )
}

fn walk_share_column() -> Column<Line> {
    column(
        "walk_share",
        true,
        "1",
        "the share of its stable slopes (by length) that walk: the archive's second descriptor",
        Get::F64(|r| r.e.walk_share),
    )
}

fn score_column() -> Column<Line> {
    column(
        "score",
        true,
        "1",
        "the value its sub-search maximised (normalised objective, or the weighted Chebyshev \
         scalarisation)",
        Get::F64(|r| r.e.score),
    )
}

fn archive_columns() -> Vec<Column<Line>> {
    let mut c = design_columns();
    c.splice(
        1..1,
        [
            round_column(),
            column(
                "cell_slope",
                false,
                "1",
                "its cell's bin of the widest interval's middle slope, 0 to SLOPE_BINS − 1 over \
                 the search's slopes",
                Get::I64(|r: &Line| Some(r.cell?.0 as i64)),
            ),
            column(
                "cell_walk",
                false,
                "1",
                "its cell's bin of walk_share, 0 to WALK_BINS − 1 over [0, 1]",
                Get::I64(|r: &Line| Some(r.cell?.1 as i64)),
            ),
        ],
    );
    c.push(walk_share_column());
    c.push(score_column());
    c
}

fn search_columns() -> Vec<Column<Line>> {
    let mut c = design_columns();
    c.splice(
        1..1,
        [
            round_column(),
            column(
                "generation",
                false,
                "1",
                "the generation within its sub-search",
                Get::I64(|r: &Line| Some(r.e.generation as i64)),
            ),
        ],
    );
    c.push(walk_share_column());
    c.push(column(
        "p_fall",
        true,
        "1",
        "the learned probability that the design falls, when it was drawn (cmaes, archive)",
        Get::F64(|r| r.e.p_fall),
    ));
    c.push(score_column());
    c
}

fn reported_columns() -> Vec<Column<Line>> {
    let mut c = design_columns();
    c.extend([
        column(
            "found_phi_lo",
            true,
            "rad",
            "phi_lo of the search's own (coarser) profile",
            Get::F64(|r: &Line| r.found.as_ref()?.phi_lo),
        ),
        column(
            "found_phi_hi",
            true,
            "rad",
            "phi_hi of the search's own profile",
            Get::F64(|r: &Line| r.found.as_ref()?.phi_hi),
        ),
        column(
            "found_slope_range",
            true,
            "rad",
            "slope_range of the search's own profile",
            Get::F64(|r: &Line| width(r.found.as_ref()?)),
        ),
        column(
            "profile_phi_lo",
            true,
            "rad",
            "the fine profile's widest interval (of the gait), before the direct check",
            Get::F64(|r: &Line| Some(r.checked?.profile.0)),
        ),
        column(
            "profile_phi_hi",
            true,
            "rad",
            "its upper end",
            Get::F64(|r: &Line| Some(r.checked?.profile.1)),
        ),
        column(
            "checked_slopes",
            true,
            "1",
            "slopes of the fine profile's interval simulated directly (201 across it and every \
             multiple of 0.005 inside it)",
            Get::I64(|r: &Line| Some(r.checked?.slopes as i64)),
        ),
        column(
            "checked_failures",
            true,
            "1",
            "of them, not stable (for a search of one gait: not that gait): isolated failing \
             slopes the profile's grid did not resolve",
            Get::I64(|r: &Line| Some(r.checked?.failures as i64)),
        ),
        column(
            "gait",
            false,
            "-",
            "the gait phi_lo..phi_hi was checked for at every checked slope (\"any\": any \
             stable gait)",
            Get::Str(|r: &Line| Some(r.gait.map_or("any", |g| g.as_str()))),
        ),
        column(
            "phi_lo_end",
            true,
            "-",
            "how the interval ends at phi_lo: \"sharp\" (no slope below it holds the gait, \
             checked or profiled) or \"interleaved\" (some do, between failures)",
            Get::Str(|r: &Line| Some(r.checked?.ends().0)),
        ),
        column(
            "phi_hi_end",
            true,
            "-",
            "how it ends at phi_hi: \"sharp\" or \"interleaved\"",
            Get::Str(|r: &Line| Some(r.checked?.ends().1)),
        ),
    ]);
    c
}

/// `search.parquet`'s schema.
pub(crate) fn search_schema() -> arrow_schema::SchemaRef {
    table::schema(&search_columns())
}

/// `archive.parquet`'s schema.
pub(crate) fn archive_schema() -> arrow_schema::SchemaRef {
    table::schema(&archive_columns())
}

/// `designs.parquet`'s schema.
pub(crate) fn designs_schema() -> arrow_schema::SchemaRef {
    table::schema(&reported_columns())
}

/// Every evaluation as a table: the columns of `search.parquet`
/// (docs/results-other-commands.md).
pub fn search_batch(s: &SearchSettings, evals: &[Evaluation]) -> RecordBatch {
    let rows: Vec<Line> = evals.iter().map(|e| Line::of(s, e)).collect();
    let cols = search_columns();
    table::batch(&cols, table::schema(&cols), &rows)
}

/// The archive of a search as a table: the columns of `archive.parquet`,
/// one row per elite in order of sub-search and cell.
pub fn archive_batch(s: &SearchSettings, evals: &[Evaluation]) -> RecordBatch {
    let by_index: std::collections::BTreeMap<u64, &Evaluation> =
        evals.iter().map(|e| (e.index, e)).collect();
    let rows: Vec<Line> = super::archive::of(s, evals)
        .into_iter()
        .map(|((_, cell), (index, _))| Line {
            cell: Some(cell),
            ..Line::of(s, by_index[&index])
        })
        .collect();
    let cols = archive_columns();
    table::batch(&cols, table::schema(&cols), &rows)
}

/// The reported designs as a table: the columns of `designs.parquet`.
pub fn reported_batch(s: &SearchSettings, reported: &[Reported]) -> RecordBatch {
    let rows: Vec<Line> = reported
        .iter()
        .map(|r| Line {
            found: Some(r.found.clone()),
            checked: r.checked,
            ..Line::of(s, &r.verified)
        })
        .collect();
    let cols = reported_columns();
    table::batch(&cols, table::schema(&cols), &rows)
}
