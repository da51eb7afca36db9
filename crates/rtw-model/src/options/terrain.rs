//! The ground's shape as an option (`terrain.*`): what the plant's terrain
//! (`plant/terrain.rs`, docs/model.md §2) is made from, validated like every
//! other option.

use crate::params::{ParamError, check};
use serde::{Deserialize, Serialize};

/// The ground's shape (the keys `terrain.*` of a config's `[simulation]`
/// table). The default, `step_height = 0`, is the flat slope.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct TerrainOptions {
    /// Height of a single step down (m, along the slope normal; > 0 is down,
    /// 0 is the flat slope).
    pub step_height: f64,
    /// Where the step is: its edge's distance along the slope from the front
    /// foot's start (m, > 0; the star stands at `x ≤ 0`).
    pub step_at: f64,
}

impl Default for TerrainOptions {
    fn default() -> Self {
        Self {
            step_height: 0.0,
            step_at: 1.0,
        }
    }
}

/// Largest step height accepted (m): a thousand times the article's rod,
/// the scale bound of `L` (docs/model.md §1).
pub(crate) const STEP_HEIGHT_MAX: f64 = 1e3;

impl TerrainOptions {
    /// Is this the flat slope (no step)?
    #[inline]
    pub(crate) fn is_flat(&self) -> bool {
        self.step_height == 0.0
    }

    /// The slope with a step down of `height` at `at` (m).
    pub(crate) fn step(height: f64, at: f64) -> Self {
        Self {
            step_height: height,
            step_at: at,
        }
    }

    /// Refuses a step height outside [0, 1000] m (a step up would put a riser
    /// in every foot's way) or a step position outside (0, 1e6] m.
    pub(crate) fn validate(&self) -> Result<(), ParamError> {
        check(
            "terrain.step_height",
            self.step_height,
            "in [0, 1000] (m, > 0 is a step down)",
            |v| (0.0..=STEP_HEIGHT_MAX).contains(&v),
        )?;
        check(
            "terrain.step_at",
            self.step_at,
            "in (0, 1e6] (m along the slope from the start)",
            |v| v > 0.0 && v <= 1e6,
        )
    }

    /// The ground's height (slope normal) under `x`.
    #[inline]
    pub(crate) fn ground(&self, x: f64) -> f64 {
        if self.is_flat() || x < self.step_at {
            0.0
        } else {
            -self.step_height
        }
    }

    /// The edge guard of a tip sliding at `x` on the segment at height
    /// `level`: its distance to the edge, positive on its own segment.
    #[inline]
    pub(crate) fn edge_distance(&self, x: f64, level: f64) -> f64 {
        if level == 0.0 {
            self.step_at - x
        } else {
            x - self.step_at
        }
    }

    /// The rate of [`edge_distance`](Self::edge_distance) for a tip moving
    /// at `vx`.
    #[inline]
    pub(crate) fn edge_rate(&self, vx: f64, level: f64) -> f64 {
        if level == 0.0 { -vx } else { vx }
    }

    /// A tip this far below the ground at the touchdown event met the riser,
    /// not the ground: a thousand touchdown offsets, far beyond where a
    /// touchdown is located and far below any step that matters.
    #[inline]
    pub(crate) fn met_riser(&self, gap: f64, touchdown_height: f64) -> bool {
        !self.is_flat() && gap < 1e3 * touchdown_height
    }
}
