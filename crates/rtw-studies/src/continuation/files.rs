//! A diagram's files: `FILE.parquet` (branch points), `FILE.special.parquet`
//! (bifurcations, starts and ends of branches) and `FILE.curve.parquet`
//! (two-parameter curves), each from one column table, with the settings in
//! their metadata.

use super::{Continuation, DiagramAndCurves, critical, end_name, kind_name};
use ::parquet::file::metadata::KeyValue;
use anyhow::Result;
use arrow_schema::SchemaRef;
use rtw_engine::config::variant::ModelChoices;
use rtw_engine::files::FileSet;
use rtw_engine::io::destination::{self, Output, companion};
use rtw_engine::io::metadata::{
    FileKind, META_CONT_CURVE, META_CONT_PARAM, META_CYCLE, META_OPTIONS, META_PARAMS,
    META_VARIANT, META_VERSION, META_WALL_TIME, kv,
};
use rtw_engine::io::parquet;
use rtw_engine::io::table::{self, Column, Get, column};
use std::path::Path;

/// Where a row's point is, and its multipliers: the columns every file of a
/// diagram has.
pub(crate) struct At {
    value: f64,
    omega: f64,
    floquet_max: f64,
    mu_re: f64,
    mu_im: f64,
}

/// A row with an [`At`].
trait HasAt {
    fn at(&self) -> &At;
}

/// The columns of [`At`], in file order.
fn at_columns<R: HasAt>() -> [Column<R>; 5] {
    [
        column(
            "value",
            false,
            "as param",
            VALUE,
            Get::F64(|r: &R| Some(r.at().value)),
        ),
        column(
            "omega",
            true,
            "rad/s",
            OMEGA,
            Get::F64(|r: &R| Some(r.at().omega)),
        ),
        column(
            "floquet_max",
            false,
            "1",
            "largest Floquet multiplier modulus",
            Get::F64(|r: &R| Some(r.at().floquet_max)),
        ),
        column(
            "mu_re",
            false,
            "1",
            MU_RE,
            Get::F64(|r: &R| Some(r.at().mu_re)),
        ),
        column(
            "mu_im",
            false,
            "1",
            MU_IM,
            Get::F64(|r: &R| Some(r.at().mu_im)),
        ),
    ]
}

/// One point of a branch at one step of its orbit.
pub(crate) struct PointRow {
    param: &'static str,
    branch: usize,
    period: usize,
    parent: Option<usize>,
    index: usize,
    k: usize,
    stable: bool,
    at: At,
}

/// What a special point is.
pub(crate) const SPECIAL_KINDS: [&str; 8] = [
    "start",
    "fold",
    "branch_point",
    "period_doubling",
    "neimark_sacker",
    "end_parameter_range",
    "end_max_points",
    "end_no_continuation",
];

/// A bifurcation, or a branch's first or last point.
pub(crate) struct SpecialRow {
    param: &'static str,
    branch: usize,
    kind: usize,
    at: At,
    test_value: Option<f64>,
}

/// One point of a two-parameter curve.
pub(crate) struct CurveRow {
    param: &'static str,
    param2: &'static str,
    curve: usize,
    branch: usize,
    kind: usize,
    direction: f64,
    index: usize,
    value2: f64,
    at: At,
    end: &'static str,
}

impl HasAt for PointRow {
    fn at(&self) -> &At {
        &self.at
    }
}

impl HasAt for SpecialRow {
    fn at(&self) -> &At {
        &self.at
    }
}

impl HasAt for CurveRow {
    fn at(&self) -> &At {
        &self.at
    }
}

fn kind_index(name: &str) -> usize {
    SPECIAL_KINDS
        .iter()
        .position(|k| *k == name)
        .expect("a listed kind")
}

fn kind_names() -> Vec<&'static str> {
    SPECIAL_KINDS.to_vec()
}

const PARAM: &str = "the continued input's name (length, rho, alpha, fn, zeta or phi)";
const VALUE: &str = "the continued input's value, in its unit in samples.parquet";
const BRANCH: &str = "branch number: 0 and 1 through the start (towards larger and smaller values), then the period-2 branches switched onto at period doublings";
const OMEGA: &str = "post-impact angular velocity of the new stance rod at the section point";
const MU_RE: &str = "real part of the multiplier nearest the unit circle";
const MU_IM: &str = "imaginary part of the multiplier nearest the unit circle";

/// `param` and `branch`, the first columns of every file of a diagram.
fn head<R>(
    branch: &'static str,
    param: fn(&R) -> Option<&str>,
    b: fn(&R) -> Option<i64>,
) -> [Column<R>; 2] {
    [
        column("param", false, "-", PARAM, Get::Str(param)),
        column("branch", false, "-", branch, Get::I64(b)),
    ]
}

fn point_columns() -> Vec<Column<PointRow>> {
    let mut cols = Vec::from(head(
        BRANCH,
        |r: &PointRow| Some(r.param),
        |r| Some(r.branch as i64),
    ));
    cols.extend([
        column(
            "period",
            false,
            "1",
            "the branch's period in steps (fixed points of the step map's period-th power)",
            Get::I64(|r: &PointRow| Some(r.period as i64)),
        ),
        column(
            "parent",
            true,
            "-",
            "the branch this one was switched from (null: through the start)",
            Get::I64(|r: &PointRow| r.parent.map(|p| p as i64)),
        ),
        column(
            "index",
            false,
            "-",
            "the point's place along its branch (arclength order)",
            Get::I64(|r: &PointRow| Some(r.index as i64)),
        ),
        column(
            "k",
            false,
            "-",
            "step of the orbit (0 … period − 1): a period-n branch has n rows per point",
            Get::I64(|r: &PointRow| Some(r.k as i64)),
        ),
        column(
            "stable",
            false,
            "-",
            "every nontrivial Floquet multiplier inside the unit circle",
            Get::Bool(|r: &PointRow| Some(r.stable)),
        ),
    ]);
    cols.extend(at_columns());
    cols
}

fn special_columns() -> Vec<Column<SpecialRow>> {
    let mut cols = Vec::from(head(
        BRANCH,
        |r: &SpecialRow| Some(r.param),
        |r| Some(r.branch as i64),
    ));
    cols.push(column(
        "kind",
        false,
        "-",
        "start (a branch's first point), a bifurcation located on the branch (fold, branch_point, period_doubling, neimark_sacker), or why the branch ended (end_parameter_range, end_max_points, end_no_continuation: no fixed point in the start's mode pattern beyond)",
        Get::Label {
            index: |r: &SpecialRow| r.kind,
            names: kind_names,
        },
    ));
    cols.extend(at_columns());
    cols.push(column(
        "test_value",
        true,
        "1",
        "the bifurcation's test function at the located point (null: not a bifurcation)",
        Get::F64(|r: &SpecialRow| r.test_value),
    ));
    cols
}

fn curve_columns() -> Vec<Column<CurveRow>> {
    let mut cols = Vec::from(head(
        "the branch whose bifurcation the curve starts from",
        |r: &CurveRow| Some(r.param),
        |r| Some(r.branch as i64),
    ));
    cols.extend([
        column(
            "param2",
            false,
            "-",
            "the second input's name (--curve)",
            Get::Str(|r: &CurveRow| Some(r.param2)),
        ),
        column(
            "curve",
            false,
            "-",
            "curve number",
            Get::I64(|r: &CurveRow| Some(r.curve as i64)),
        ),
        column(
            "kind",
            false,
            "-",
            "fold (the gait's existence boundary) or period_doubling (its stability boundary)",
            Get::Label {
                index: |r: &CurveRow| r.kind,
                names: kind_names,
            },
        ),
        column(
            "direction",
            false,
            "1",
            "+1 / −1: the curve was followed first towards larger / smaller values of param2",
            Get::F64(|r: &CurveRow| Some(r.direction)),
        ),
        column(
            "index",
            false,
            "-",
            "the point's place along its curve",
            Get::I64(|r: &CurveRow| Some(r.index as i64)),
        ),
        column(
            "value2",
            false,
            "as param2",
            "the second input's value",
            Get::F64(|r: &CurveRow| Some(r.value2)),
        ),
    ]);
    cols.extend(at_columns());
    cols.push(column(
        "end",
        false,
        "-",
        "why the curve ended (as the kinds end_*)",
        Get::Str(|r: &CurveRow| Some(r.end)),
    ));
    cols
}

/// The schema of the branch-point file `FILE.parquet`.
pub(crate) fn branch_schema() -> SchemaRef {
    table::schema(&point_columns())
}

/// The schema of the special-point file `FILE.special.parquet`.
pub(crate) fn special_schema() -> SchemaRef {
    table::schema(&special_columns())
}

/// The schema of the curve file `FILE.curve.parquet`.
pub(crate) fn curve_schema() -> SchemaRef {
    table::schema(&curve_columns())
}

/// The rows of the three files.
pub(crate) struct Rows {
    pub points: Vec<PointRow>,
    pub special: Vec<SpecialRow>,
    pub curves: Vec<CurveRow>,
}

impl Rows {
    /// The special points of branch `branch` (for the summary).
    pub(crate) fn special_of(
        &self,
        branch: usize,
    ) -> impl Iterator<Item = (&'static str, f64, f64, f64)> + '_ {
        self.special
            .iter()
            .filter(move |s| s.branch == branch)
            .map(|s| (SPECIAL_KINDS[s.kind], s.at.value, s.at.mu_re, s.at.mu_im))
    }

    /// `(value, stable)` of each point of branch `branch` (its first orbit step).
    pub(crate) fn points_of(&self, branch: usize) -> impl Iterator<Item = (f64, bool)> + '_ {
        self.points
            .iter()
            .filter(move |p| p.branch == branch && p.k == 0)
            .map(|p| (p.at.value, p.stable))
    }

    /// The period of branch `branch`.
    pub(crate) fn period_of(&self, branch: usize) -> Option<usize> {
        self.points
            .iter()
            .find(|p| p.branch == branch)
            .map(|p| p.period)
    }

    /// The branch `branch` was switched from.
    pub(crate) fn parent_of(&self, branch: usize) -> Option<usize> {
        self.points
            .iter()
            .find(|p| p.branch == branch)
            .and_then(|p| p.parent)
    }

    /// Each curve's kind, direction, ends and length, for the summary.
    pub(crate) fn curve_spans(&self) -> Vec<CurveSpan> {
        let mut out: Vec<CurveSpan> = Vec::new();
        for r in &self.curves {
            match out.last_mut() {
                Some(last) if last.curve == r.curve => {
                    last.last = (r.at.value, r.value2);
                    last.points += 1;
                }
                _ => out.push(CurveSpan {
                    curve: r.curve,
                    branch: r.branch,
                    kind: SPECIAL_KINDS[r.kind],
                    direction: r.direction,
                    first: (r.at.value, r.value2),
                    last: (r.at.value, r.value2),
                    points: 1,
                    end: r.end,
                }),
            }
        }
        out
    }
}

/// A two-parameter curve in brief.
pub(crate) struct CurveSpan {
    pub curve: usize,
    pub branch: usize,
    pub kind: &'static str,
    pub direction: f64,
    pub first: (f64, f64),
    pub last: (f64, f64),
    pub points: usize,
    pub end: &'static str,
}

/// The [`At`] of a point with coordinates `z` at `value`.
fn at(value: f64, omega: f64, m: &[nalgebra::Complex<f64>]) -> At {
    let (mu_re, mu_im) = critical(m).map_or((f64::NAN, f64::NAN), |c| (c.re, c.im));
    At {
        value,
        omega,
        floquet_max: hybrid_ode::limit::spectral_radius(m),
        mu_re,
        mu_im,
    }
}

/// The rows of a run.
pub(crate) fn rows(c: &Continuation, r: &DiagramAndCurves) -> Rows {
    let param = c.param.name();
    let d = &r.diagram;
    let mut points = Vec::new();
    let mut special = Vec::new();
    for (b, br) in d.branches.iter().enumerate() {
        for (index, (pt, omega)) in br.branch.points.iter().zip(&br.omega).enumerate() {
            for (k, &w) in omega.iter().enumerate() {
                points.push(PointRow {
                    param,
                    branch: b,
                    period: br.period,
                    parent: br.parent,
                    index,
                    k,
                    stable: pt.stable,
                    at: at(pt.p, w, &pt.multipliers),
                });
            }
        }
        let special_row = |kind: &str, pt: &hybrid_ode::continuation::Point, test| SpecialRow {
            param,
            branch: b,
            kind: kind_index(kind),
            at: at(pt.p, d.omega_at(&pt.z), &pt.multipliers),
            test_value: test,
        };
        if let Some(first) = br.branch.points.first() {
            special.push(special_row("start", first, None));
        }
        for bif in &br.branch.bifurcations {
            special.push(special_row(
                kind_name(bif.kind),
                &bif.point,
                Some(bif.test_value),
            ));
        }
        if let Some(last) = br.branch.points.last() {
            special.push(special_row(end_name(br.branch.end), last, None));
        }
    }
    let mut curves = Vec::new();
    if let Some(cs) = c.curve {
        for (i, run) in r.curves.iter().enumerate() {
            for (index, pt) in run.curve.points.iter().enumerate() {
                curves.push(CurveRow {
                    param,
                    param2: cs.param.name(),
                    curve: i,
                    branch: run.branch,
                    kind: kind_index(kind_name(run.curve.kind)),
                    direction: run.direction,
                    index,
                    value2: pt.p[1],
                    at: at(pt.p[0], d.omega_at(&pt.z), &pt.multipliers),
                    end: end_name(run.curve.end),
                });
            }
        }
    }
    Rows {
        points,
        special,
        curves,
    }
}

fn file_metadata(c: &Continuation, wall_time_s: f64) -> Result<Vec<KeyValue>> {
    let mut m = vec![
        kv(META_VERSION, rtw_engine::io::metadata::VERSION.into()),
        kv(META_CONT_PARAM, c.param.name().into()),
        kv(META_PARAMS, serde_json::to_string(&c.base)?),
        kv(META_OPTIONS, toml::to_string(&c.options)?),
        kv(META_VARIANT, ModelChoices::of(&c.options).to_string()),
        kv(META_CYCLE, format!("{:?}", c.cycle)),
        kv(META_WALL_TIME, format!("{wall_time_s:.3}")),
    ];
    if let Some(cs) = c.curve {
        m.push(kv(
            META_CONT_CURVE,
            format!("{} in [{}, {}]", cs.param.name(), cs.range.0, cs.range.1),
        ));
    }
    Ok(m)
}

/// Writes the files (the curve file only with `--curve`) into `set`, to
/// appear together with the diagram's other files.
pub(crate) fn write(
    set: &mut FileSet,
    out: &Path,
    c: &Continuation,
    rows: &Rows,
    wall_time_s: f64,
) -> Result<()> {
    if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)?;
    }
    let meta = file_metadata(c, wall_time_s)?;
    let batch = table::batch(&point_columns(), branch_schema(), &rows.points);
    parquet::add_file(set, out, &batch, meta.clone())?;
    let batch = table::batch(&special_columns(), special_schema(), &rows.special);
    parquet::add_file(set, &companion(out, "special"), &batch, meta.clone())?;
    if c.curve.is_some() {
        let batch = table::batch(&curve_columns(), curve_schema(), &rows.curves);
        parquet::add_file(set, &companion(out, "curve"), &batch, meta)?;
    }
    Ok(())
}

/// Refuses, unless `force`, to write over files that are not a diagram's.
pub(crate) fn check_outputs(out: &Path, force: bool) -> Result<()> {
    let files_ = [
        Output {
            path: out.to_path_buf(),
            flag: "--out",
            schema: branch_schema(),
        },
        Output {
            path: companion(out, "special"),
            flag: "--out (special points file)",
            schema: special_schema(),
        },
        Output {
            path: companion(out, "curve"),
            flag: "--out (curve file)",
            schema: curve_schema(),
        },
    ];
    // A diagram's summary starts "Continuation in PARAM over ...".
    let ours = |first: &str| first.starts_with("Continuation in ");
    destination::check_outputs(
        out,
        &files_,
        FileKind::Continuation,
        "a diagram",
        ours,
        force,
    )
}
