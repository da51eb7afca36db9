//! A slice of a gait's basin of attraction on the step map's section
//! (after Schwab & Wisse 2001, simplified from cell mapping to a grid of
//! direct simulations): which perturbed section states return to the gait.
//!
//! **The slice.** The gait's fixed point on the section (the limit cycle a
//! run from `options`' start settles into, [`StepMap::limit_cycle`]) is
//! perturbed in two of its coordinates, [`Coord`]: a rod's angle `θ` or
//! angular velocity `ω`, in canonical labels (rod a is the landing rod,
//! b and c follow it round the star). Each grid point adds its offsets to
//! those two coordinates and holds every other coordinate of the section
//! point at the fixed point's value, in the fixed point's contact modes. The
//! coordinates are the section's minimal ones ([`SectionPoint::coords`]),
//! so the contacts stay satisfied: a grounded rod turns about its grounded
//! tip (which stays where it is), a free rod about its centre, and since the
//! other rods are held, a change of `θ_b` is a change of rod b's angle
//! relative to rod a. The strings take up the new shape at once (they are
//! elastic); a point where a tip that is not on the ground would start
//! below it is [`Fate::Infeasible`] and not simulated.
//!
//! **Classification.** Each feasible point is iterated on the step map for
//! at most `steps` steps ([`follow`]):
//! * [`Fate::Returns`] when its scaled distance to the gait's orbit (the
//!   nearest orbit point in the same contact modes, in the map's scales:
//!   positions over L, rates over √(g/L), …) falls to `tol` or below. The
//!   gait is stable (max |μ| < 1), so a point that close stays: the
//!   iteration stops there;
//! * [`Fate::Survives`] when all `steps` steps are taken without returning:
//!   the last steps' gait label and period (if any) say what it walks in
//!   instead (another gait, or one still on its way);
//! * [`Fate::Fails`] when a step fails (a collapse, a stall, a numerical
//!   end, or no new foot within the map's step horizon): [`StepError`].

use crate::cycles::map::limit_cycle::{CycleError, LimitCycle, RUN_PERIOD_TOL};
use crate::cycles::map::section::SectionPoint;
use crate::cycles::map::stepmap::{CycleOptions, Step, StepError, StepMap};
use crate::options::Options;
use crate::outcome::{Label, MAX_PERIOD};
use crate::params::{Params, Physical};
use crate::plant::contact::RodMode;
use crate::plant::geometry::Tip;
use crate::plant::rtw::Rtw;
use crate::plant::slots::{self, OMEGA, THETA};
use hybrid_ode::limit;

/// A section coordinate a basin slice varies: a rod's angle or angular
/// velocity, in canonical labels (rod 0 = a, the landing rod).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Coord {
    /// Rod `i`'s angle θ (rad).
    Theta(usize),
    /// Rod `i`'s angular velocity ω (rad/s).
    Omega(usize),
}

impl Coord {
    /// Every coordinate: `omega_a`, `omega_b`, `omega_c`, `theta_a`, `theta_b`,
    /// `theta_c` as `Display` writes them and `str::parse` reads them.
    pub const ALL: [Coord; 6] = [
        Coord::Omega(0),
        Coord::Omega(1),
        Coord::Omega(2),
        Coord::Theta(0),
        Coord::Theta(1),
        Coord::Theta(2),
    ];

    /// `omega_a` … `theta_c`.
    fn name(self) -> &'static str {
        const NAMES: [&str; 6] = [
            "omega_a", "omega_b", "omega_c", "theta_a", "theta_b", "theta_c",
        ];
        NAMES[Self::ALL.iter().position(|&c| c == self).expect("in ALL")]
    }

    /// The state slot it is.
    fn slot(self) -> usize {
        match self {
            Coord::Theta(i) => slots::at(i, THETA),
            Coord::Omega(i) => slots::at(i, OMEGA),
        }
    }
}

impl std::fmt::Display for Coord {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for Coord {
    type Err = String;
    /// The coordinate with this name, or a message listing the names.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|c| c.name() == s)
            .ok_or_else(|| {
                let names: Vec<&str> = Self::ALL.iter().map(|c| c.name()).collect();
                format!(
                    "unknown coordinate `{s}`: must be one of {}",
                    names.join(", ")
                )
            })
    }
}

/// One axis of a slice: offsets `from … to` from the fixed point's value
/// of `coord`, `points` of them evenly spaced (both ends included; one
/// point is `from`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Axis {
    /// The coordinate varied.
    pub coord: Coord,
    /// The first offset.
    pub from: f64,
    /// The last offset (above `from`).
    pub to: f64,
    /// How many offsets.
    pub points: usize,
}

/// Most points on one axis (a slice's rows are held in memory).
pub const MAX_AXIS_POINTS: usize = 1000;
/// Most steps a point is iterated.
pub const MAX_STEPS: usize = 100_000;

impl Axis {
    /// The offsets.
    pub(crate) fn offsets(&self) -> Vec<f64> {
        // As a scan's linspace axis: the ends exact, and a symmetric range
        // with an odd count has an exact 0 (the fixed point itself).
        let n = self.points;
        (0..n)
            .map(|k| match k {
                0 => self.from,
                _ if k + 1 == n => self.to,
                _ => self.from + (self.to - self.from) * k as f64 / (n - 1) as f64,
            })
            .collect()
    }

    fn validate(&self, name: &'static str) -> Result<(), BasinError> {
        let bad = |what: String, range: &'static str| {
            Err(BasinError::Invalid {
                field: name,
                what,
                range,
            })
        };
        if !self.from.is_finite() || !self.to.is_finite() || self.from > self.to {
            return bad(
                format!("from {} to {}", self.from, self.to),
                "finite offsets with from <= to",
            );
        }
        if !(1..=MAX_AXIS_POINTS).contains(&self.points) {
            return bad(format!("points {}", self.points), "an integer in [1, 1000]");
        }
        if self.points == 1 && self.from != self.to {
            return bad(
                format!("points 1 from {} to {}", self.from, self.to),
                "from = to when points is 1",
            );
        }
        Ok(())
    }
}

/// A basin slice's settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BasinSpec {
    /// The first axis (the grid's columns).
    pub x: Axis,
    /// The second axis (the grid's rows), another coordinate.
    pub y: Axis,
    /// Most steps each point is iterated.
    pub steps: usize,
    /// A point returns when its scaled distance to the orbit is at most this.
    pub tol: f64,
}

impl BasinSpec {
    /// Checks every field; the error names it and its valid range.
    pub fn validate(&self) -> Result<(), BasinError> {
        self.x.validate("x")?;
        self.y.validate("y")?;
        if self.x.coord == self.y.coord {
            return Err(BasinError::Invalid {
                field: "y",
                what: format!("coordinate {}", self.y.coord),
                range: "a coordinate other than x's",
            });
        }
        if !(1..=MAX_STEPS).contains(&self.steps) {
            return Err(BasinError::Invalid {
                field: "steps",
                what: self.steps.to_string(),
                range: "an integer in [1, 100000]",
            });
        }
        // Above 0.1 a point may pass close by on its way elsewhere; the
        // distance is in the map's scales (L, √(gL), …), so 0.1 is far.
        if !(self.tol > 0.0 && self.tol <= 0.1) {
            return Err(BasinError::Invalid {
                field: "tol",
                what: self.tol.to_string(),
                range: "in (0, 0.1]",
            });
        }
        Ok(())
    }
}

/// Why a slice cannot be made.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum BasinError {
    /// A setting is out of range.
    #[error("{field}: {what} is invalid: must be {range}")]
    Invalid {
        /// The setting (`x`, `y`, `steps`, `tol`).
        field: &'static str,
        /// Its value.
        what: String,
        /// What it must be.
        range: &'static str,
    },
    /// The design's gait has no limit cycle on the step map (the message
    /// holds the cause; no `source`, so that it is said once).
    #[error("the gait's limit cycle: {0}")]
    Cycle(CycleError),
    /// The design's gait is not stable: it has no basin.
    #[error("the gait's limit cycle is unstable (max |mu| = {0:.4}): it has no basin")]
    Unstable(f64),
}

impl From<CycleError> for BasinError {
    fn from(e: CycleError) -> Self {
        Self::Cycle(e)
    }
}

/// What became of one point of a slice.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Fate<E> {
    /// It came within the tolerance of the gait.
    Returns,
    /// It took every step without coming back to the gait.
    Survives,
    /// A step failed.
    Fails(E),
    /// Its start puts a tip below the ground: not simulated.
    Infeasible,
}

/// A point followed on a map ([`follow`]).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Followed<P, E> {
    /// What became of it.
    pub fate: Fate<E>,
    /// Steps taken without failing (the step it returned at, for a return).
    pub steps: usize,
    /// Its last point.
    pub last: P,
    /// The last point's distance to the gait.
    pub distance: f64,
}

/// Iterates `step` from `start` at most `steps` times, until the distance
/// to the gait is at most `tol` ([`Fate::Returns`]), a step fails
/// ([`Fate::Fails`]) or the steps run out ([`Fate::Survives`]). The
/// classification rule of every basin slice, for any map (the tests check
/// it on the rimless wheel against its closed-form basin).
pub(crate) fn follow<P, E>(
    start: P,
    steps: usize,
    tol: f64,
    mut step: impl FnMut(&P) -> Result<P, E>,
    distance: impl Fn(&P) -> f64,
) -> Followed<P, E> {
    let mut last = start;
    let mut d = distance(&last);
    for k in 0..steps {
        match step(&last) {
            Ok(next) => {
                last = next;
                d = distance(&last);
                if d <= tol {
                    return Followed {
                        fate: Fate::Returns,
                        steps: k + 1,
                        last,
                        distance: d,
                    };
                }
            }
            Err(e) => {
                return Followed {
                    fate: Fate::Fails(e),
                    steps: k,
                    last,
                    distance: d,
                };
            }
        }
    }
    Followed {
        fate: Fate::Survives,
        steps,
        last,
        distance: d,
    }
}

/// One point of a slice.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BasinPoint {
    /// Offset of the x coordinate from the fixed point.
    pub dx: f64,
    /// Offset of the y coordinate.
    pub dy: f64,
    /// What became of it.
    pub fate: Fate<StepError>,
    /// Steps taken without failing (for a return, the step it came back at).
    pub steps: usize,
    /// Scaled distance of its last section point to the gait's orbit
    /// (infinite when no orbit point has its contact modes).
    pub distance: f64,
    /// The gait label of its last steps (at most two of the longest
    /// periods) when it took every step; the gait's own for a return.
    pub label: Option<Label>,
    /// The period of its last section points, when it took every step and
    /// they repeat (within the scan's period tolerance).
    pub period: Option<usize>,
}

/// A design's gait and the slice of its basin to compute.
#[derive(Clone, Debug)]
pub struct Basin {
    map: StepMap,
    rtw: Rtw,
    spec: BasinSpec,
    options: Options,
    /// The gait's limit cycle (the slice is centred on its first orbit point).
    pub cycle: LimitCycle,
    /// The gait's label.
    pub label: Label,
}

impl Basin {
    /// The gait `params` settles into under `options` (its limit cycle on
    /// the step map with `cycle`'s settings), ready for the slice `spec`.
    /// Refuses invalid settings, a gait without a limit cycle and an
    /// unstable one.
    ///
    /// # Panics
    /// If `params` or `options` are invalid (call their `validate` first).
    pub fn new(
        params: &Params,
        options: &Options,
        cycle: &CycleOptions,
        spec: BasinSpec,
    ) -> Result<Basin, BasinError> {
        spec.validate()?;
        let map = StepMap::new(params, options, cycle);
        let lc = map.limit_cycle(options, cycle)?;
        if !lc.is_stable() {
            return Err(BasinError::Unstable(lc.floquet_max()));
        }
        let phys = Physical::new(params, options.normalization, options.g);
        Ok(Basin {
            rtw: Rtw::new(&phys, options),
            label: lc.label(&options.labels),
            map,
            spec,
            options: *options,
            cycle: lc,
        })
    }

    /// The slice's settings.
    pub fn spec(&self) -> &BasinSpec {
        &self.spec
    }

    /// Number of grid points (x offsets × y offsets).
    pub fn len(&self) -> usize {
        self.spec.x.points * self.spec.y.points
    }

    /// Whether the grid is empty (never: each axis has a point).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The fixed point's values of the x and y coordinates.
    pub fn centre(&self) -> (f64, f64) {
        let p = &self.cycle.orbit[0];
        (p.y[self.spec.x.coord.slot()], p.y[self.spec.y.coord.slot()])
    }

    /// Grid point `i` (row-major: `i = iy · x.points + ix`), simulated.
    /// Each point depends only on its offsets: any order, any thread.
    pub fn point(&self, i: usize) -> BasinPoint {
        let nx = self.spec.x.points;
        let (ix, iy) = (i % nx, i / nx);
        let dx = self.spec.x.offsets()[ix];
        let dy = self.spec.y.offsets()[iy];
        let mut start = self.cycle.orbit[0];
        start.y[self.spec.x.coord.slot()] += dx;
        start.y[self.spec.y.coord.slot()] += dy;
        let mut point = BasinPoint {
            dx,
            dy,
            fate: Fate::Infeasible,
            steps: 0,
            distance: self.distance(&start),
            label: None,
            period: None,
        };
        if !self.tips_clear(&start) {
            return point;
        }
        // The last steps, for the label and period of a point that walks on.
        let keep = 2 * MAX_PERIOD;
        let mut last_steps: Vec<Step> = Vec::with_capacity(keep);
        let f = follow(
            start,
            self.spec.steps,
            self.spec.tol,
            |p| {
                let s = self.map.step(p)?;
                if last_steps.len() == keep {
                    last_steps.remove(0);
                }
                last_steps.push(s);
                Ok(s.to)
            },
            |p| self.distance(p),
        );
        point.fate = f.fate;
        point.steps = f.steps;
        point.distance = f.distance;
        match f.fate {
            Fate::Returns => {
                point.label = Some(self.label);
                point.period = Some(self.cycle.period);
            }
            Fate::Survives => {
                point.label = Some(Step::label(&last_steps, &self.options.labels));
                let hist: Vec<SectionPoint> = last_steps.iter().map(|s| s.to).collect();
                point.period = self.map.period_of(&hist, MAX_PERIOD, RUN_PERIOD_TOL);
            }
            Fate::Fails(_) | Fate::Infeasible => {}
        }
        point
    }

    /// Scaled distance from `p` to the nearest orbit point in its modes.
    fn distance(&self, p: &SectionPoint) -> f64 {
        let scale = self.map.coord_scale(p);
        self.cycle
            .orbit
            .iter()
            .filter(|q| q.modes == p.modes)
            .map(|q| limit::scaled_max(&p.coords(), &q.coords(), &scale))
            .fold(f64::INFINITY, f64::min)
    }

    /// Whether every tip of `p` that is not a grounded rod's contact tip
    /// lies above the ground (a grounded rod's other tip too: at the ground
    /// it would be lying down).
    fn tips_clear(&self, p: &SectionPoint) -> bool {
        let mut rtw = self.rtw.clone();
        rtw.modes = p.modes;
        let rods = rtw.rods(&p.y);
        rods.iter().zip(p.modes).all(|(r, mode)| {
            [Tip::Plus, Tip::Minus]
                .into_iter()
                .filter(|&tip| !matches!(mode, RodMode::Stick { tip: t } | RodMode::Slide { tip: t, .. } if t == tip))
                .all(|tip| {
                    let q = rtw.body.tip_point(r, tip).0;
                    q[1] - rtw.ground(q[0]) > 0.0
                })
        })
    }
}
