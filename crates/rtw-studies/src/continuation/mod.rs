//! Continuation diagrams: a gait's limit cycle followed in one input by
//! pseudo-arclength continuation on the step map
//! ([`rtw_model::cycles::diagram`]), stable and unstable, with
//! its bifurcations located on the Floquet multipliers and the period-2
//! branches born at its period doublings; and, optionally, each fold or
//! period doubling found continued in a second input: the boundary of the
//! region of that plane where the gait exists and is stable.
//!
//! Unlike `bifurcation` (which follows the attractor the robot settles in,
//! value by value), a diagram follows one fixed point through its loss of
//! stability, as far as it exists in the start's mode pattern.
//!
//! Output: `FILE.parquet` (one row per branch point and orbit step),
//! `FILE.special.parquet` (bifurcations and branch ends), and with
//! `--curve`, `FILE.curve.parquet` (points of the two-parameter curves);
//! the settings in their metadata, and a Markdown summary `FILE.md`.

pub(crate) mod files;
pub(crate) mod segments;
pub(crate) mod study;

pub use study::{THROUGH_MAX, check_through, run_to_files};
pub(crate) mod summary;

use anyhow::{Result, anyhow, bail};
use hybrid_ode::continuation::{self, Curve, CurveOptions, End, Kind, Options as ContOptions};
use hybrid_ode::limit;
use nalgebra::{Complex, DMatrix};
use rtw_model::cycles::{
    CycleOptions, Diagram, DiagramOptions, StepMap, StepMapFamily, StepMapPlane, diagram,
};
use rtw_model::{Num, Options, Param, Params};

/// A second input and its range: the plane of the two-parameter curves.
#[derive(Clone, Copy, Debug)]
pub struct CurveSettings {
    /// The second input.
    pub param: Param,
    /// Its range: a curve ends where it leaves it.
    pub range: (f64, f64),
}

/// A checked continuation: what to follow, where, how.
#[derive(Clone, Debug)]
pub struct Continuation {
    /// The input continued.
    pub param: Param,
    /// The start (its limit cycle is the one followed).
    pub base: Params,
    /// The model.
    pub options: Options,
    /// The step map's integrator and Newton settings.
    pub cycle: CycleOptions,
    /// Steps, range, scales, period-doubling switches.
    pub diagram: DiagramOptions,
    /// The plane of the two-parameter curves, if any.
    pub curve: Option<CurveSettings>,
}

impl Continuation {
    /// Checks the settings, naming the flag and the valid range.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        param: Param,
        base: Params,
        options: Options,
        range: (f64, f64),
        ds: f64,
        ds_max: f64,
        max_points: usize,
        curve: Option<CurveSettings>,
    ) -> Result<Self> {
        base.validate()?;
        options.validate()?;
        for (flag, v) in [("--from", range.0), ("--to", range.1)] {
            param.check(v).map_err(|e| anyhow!("{flag}: {e}"))?;
        }
        let p0 = base[param];
        if !(range.0 < p0 && p0 < range.1) {
            bail!(
                "--from {} --to {}: the start's {} = {} must lie strictly between them",
                Num(range.0),
                Num(range.1),
                param.name(),
                Num(p0)
            );
        }
        if !(ds > 0.0 && ds.is_finite() && ds_max >= ds && ds_max.is_finite()) {
            bail!(
                "--ds {} --ds-max {}: need 0 < ds ≤ ds-max, both finite",
                Num(ds),
                Num(ds_max)
            );
        }
        if !(1..=100_000).contains(&max_points) {
            bail!("--max-points {max_points}: must lie in [1, 100000]");
        }
        if let Some(c) = &curve {
            if c.param == param {
                bail!("--curve {}: must differ from --param", c.param.name());
            }
            for (flag, v) in [("--curve-from", c.range.0), ("--curve-to", c.range.1)] {
                c.param.check(v).map_err(|e| anyhow!("{flag}: {e}"))?;
            }
            let v2 = base[c.param];
            if !(c.range.0 < v2 && v2 < c.range.1) {
                bail!(
                    "--curve-from {} --curve-to {}: the start's {} = {} must lie strictly between them",
                    Num(c.range.0),
                    Num(c.range.1),
                    c.param.name(),
                    Num(v2)
                );
            }
        }
        let p_scale = 0.1 * p0.abs().max(1.0);
        Ok(Self {
            param,
            base,
            options,
            cycle: CycleOptions::default(),
            diagram: DiagramOptions {
                continuation: ContOptions {
                    ds,
                    ds_max,
                    ds_min: 1e-6,
                    p_min: range.0,
                    p_max: range.1,
                    tol: 1e-8,
                    locate_tol: 1e-6,
                    max_points,
                    p_scale,
                    ..ContOptions::default()
                },
                switch_period_doubling: true,
            },
            curve,
        })
    }
}

/// A two-parameter curve from one of the diagram's bifurcations.
#[derive(Clone, Debug)]
pub(crate) struct CurveRun {
    /// The branch and bifurcation index it starts from.
    pub branch: usize,
    /// +1 / −1: first towards larger or smaller values of the second input.
    pub direction: f64,
    /// The curve.
    pub curve: Curve,
}

/// A diagram and its curves.
#[derive(Clone, Debug)]
pub(crate) struct DiagramAndCurves {
    pub diagram: Diagram,
    pub curves: Vec<CurveRun>,
}

fn nontrivial(j: &DMatrix<f64>) -> Vec<Complex<f64>> {
    limit::nontrivial_multipliers(j)
}

/// Runs the diagram, then each fold and period doubling of the branches
/// through the start continued in the second input, both ways.
pub(crate) fn run(c: &Continuation) -> Result<DiagramAndCurves> {
    let d = diagram(&c.base, &c.options, &c.cycle, c.param, &c.diagram)?;
    let mut curves = Vec::new();
    if let Some(cs) = c.curve {
        let map = StepMap::new(&c.base, &c.options, &c.cycle);
        let template = d.start.orbit[0];
        let family = StepMapFamily::new(
            &c.base,
            &c.options,
            &c.cycle,
            c.param,
            template,
            d.start.period,
        );
        let opts2 = CurveOptions {
            // A curve is smooth and each of its points costs a Newton solve
            // of the augmented system: longer steps than along a branch.
            base: ContOptions {
                z_scale: map.coord_scale(&template),
                ds_max: 4.0 * c.diagram.continuation.ds_max,
                ..c.diagram.continuation.clone()
            },
            p2_range: cs.range,
            p2_scale: 0.1 * c.base[cs.param].abs().max(1.0),
            fd_step: 1e-6,
        };
        for (i, b) in d.branches.iter().enumerate() {
            if b.parent.is_some() {
                continue;
            }
            for bif in b.branch.bifurcations.iter().filter(|x| on_curve(x.kind)) {
                for direction in [1.0, -1.0] {
                    let f2 = StepMapPlane::new(family.clone(), cs.param);
                    let curve = continuation::continue_curve(
                        |z: &[f64], p: [f64; 2]| f2.eval(z, p),
                        bif,
                        c.base[cs.param],
                        direction,
                        &opts2,
                        &nontrivial,
                    )?;
                    curves.push(CurveRun {
                        branch: i,
                        direction,
                        curve,
                    });
                }
            }
        }
    }
    Ok(DiagramAndCurves { diagram: d, curves })
}

/// The kinds a two-parameter curve can follow.
fn on_curve(kind: Kind) -> bool {
    matches!(kind, Kind::Fold | Kind::PeriodDoubling)
}

/// The multiplier of `m` nearest the unit circle (at a bifurcation: the
/// critical one).
pub(crate) fn critical(m: &[Complex<f64>]) -> Option<Complex<f64>> {
    m.iter()
        .copied()
        .min_by(|a, b| (a.norm() - 1.0).abs().total_cmp(&(b.norm() - 1.0).abs()))
}

/// A special point's kind, as written in the `kind` column.
pub(crate) fn kind_name(kind: Kind) -> &'static str {
    match kind {
        Kind::Fold => "fold",
        Kind::BranchPoint => "branch_point",
        Kind::PeriodDoubling => "period_doubling",
        Kind::NeimarkSacker => "neimark_sacker",
    }
}

/// Why a branch ended, as written in the `kind` column of its end.
pub(crate) fn end_name(end: End) -> &'static str {
    match end {
        End::ParameterRange => "end_parameter_range",
        End::MaxPoints => "end_max_points",
        End::StepTooSmall => "end_no_continuation",
    }
}
