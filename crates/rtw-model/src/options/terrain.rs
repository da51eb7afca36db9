//! The ground's shape as an option (`terrain.*`): what the plant's terrain
//! (`plant/terrain.rs`, docs/model.md §4) is made from, validated like every
//! other option.
//!
//! The ground is piecewise flat: level 0 before `step_at`, and from there on
//! either one segment `step_height` lower (the step) or, with a roughness,
//! patches of length `patch` each at its own height (the rough slope). Each
//! patch's height is a pure function of `(seed, patch index)`, so the ground
//! needs no storage and a run on it is reproducible.

use crate::params::{ParamError, check};
use serde::{Deserialize, Serialize};

/// The ground's shape (the keys `terrain.*` of a config's `[simulation]`
/// table). The default, `step_height = 0` and `roughness = 0`, is the flat
/// slope.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct TerrainOptions {
    /// Height of a single step down (m, along the slope normal; > 0 is down,
    /// 0 is the flat slope).
    pub step_height: f64,
    /// Where the step (and the rough ground) starts: its edge's distance
    /// along the slope from the front foot's start (m, > 0; the star stands
    /// at `x ≤ 0`).
    pub step_at: f64,
    /// Standard deviation of each rough patch's height (m; 0 is no
    /// roughness). Left out of a serialized config while 0.
    #[serde(skip_serializing_if = "is_zero")]
    pub roughness: f64,
    /// Seed of the patches' heights. Left out of a serialized config while 0.
    #[serde(skip_serializing_if = "is_zero_seed", with = "super::seed")]
    pub seed: u64,
    /// Length of a rough patch along the slope (m).
    #[serde(skip_serializing_if = "is_default_patch")]
    pub patch: f64,
    /// Where the rough ground's future was drawn afresh (the MFPT's
    /// walkers, `run/mfpt.rs`); none in a config.
    #[serde(skip)]
    pub(crate) branches: Branches,
}

/// How many branch points a rough ground keeps.
pub(crate) const BRANCHES: usize = 32;

/// Branch points of a rough ground: from patch `first[i]` on (until the
/// next branch) the heights are drawn with `seed[i]` instead of the
/// ground's seed. A walker's clone branches at a patch it has not reached
/// yet, so it keeps the patches under and behind it and meets a fresh
/// future, reproducibly. Each branch starts beyond the last; when
/// [`BRANCHES`] are kept the oldest is dropped, and the patches it covered
/// (at least `BRANCHES` patches behind the newest branch) take the heights
/// of the branch before it.
///
/// A branch may set its first patch's height itself (`z`, in units of the
/// roughness; none: drawn with its seed like the rest): the MFPT's chain
/// (`run/mfpt_chain.rs`) integrates over that height by quadrature, so a
/// step must be a function of the height it meets.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Branches {
    len: u8,
    first: [i64; BRANCHES],
    seed: [u64; BRANCHES],
    z: [Option<f64>; BRANCHES],
    /// The factor on the heights the branch draws with its seed (1 but for
    /// the chain's members, whose patch laid ahead is drawn from a wider
    /// law, `run/mfpt_chain.rs`).
    scale: [f64; BRANCHES],
}

impl Branches {
    /// The seed of patch `k`, and its standard-normal height if the branch
    /// set it, if a branch covers it.
    #[inline]
    fn seed_of(&self, k: i64) -> Option<(u64, Option<f64>, f64)> {
        (0..usize::from(self.len))
            .rev()
            .find(|&i| self.first[i] <= k)
            .map(|i| {
                (
                    self.seed[i],
                    self.z[i].filter(|_| self.first[i] == k),
                    self.scale[i],
                )
            })
    }

    /// Draws the patches from `first` on afresh with `seed`, the first at
    /// `z` (standard normal) if given.
    fn branch(&mut self, first: i64, seed: u64, z: Option<f64>, scale: f64) {
        while self.len > 0 && self.first[usize::from(self.len) - 1] >= first {
            self.len -= 1;
        }
        if usize::from(self.len) == BRANCHES {
            self.first.copy_within(1.., 0);
            self.seed.copy_within(1.., 0);
            self.z.copy_within(1.., 0);
            self.scale.copy_within(1.., 0);
            self.len -= 1;
        }
        let i = usize::from(self.len);
        self.first[i] = first;
        self.seed[i] = seed;
        self.z[i] = z;
        self.scale[i] = scale;
        self.len += 1;
    }
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

fn is_zero_seed(v: &u64) -> bool {
    *v == 0
}

fn is_default_patch(v: &f64) -> bool {
    *v == PATCH_DEFAULT
}

/// The default length of a rough patch (m): the article's rod. Every edge
/// is a face a foot can meet (docs/model.md §4), so shorter patches put more
/// faces in its way: at Fig. 7(a) the walk's mean steps to fall is 31–50 on
/// 0.2 m patches and 73–92 (mostly censored at 100) on 0.8 m patches at
/// roughnesses from 1 mm to 5 cm (docs/robustness-rough.md).
pub const PATCH_DEFAULT: f64 = 0.8;

impl Default for TerrainOptions {
    fn default() -> Self {
        Self {
            step_height: 0.0,
            step_at: 1.0,
            roughness: 0.0,
            seed: 0,
            patch: PATCH_DEFAULT,
            branches: Branches::default(),
        }
    }
}

/// Largest step height accepted (m): a thousand times the article's rod,
/// the scale bound of `L` (docs/model.md §1).
pub(crate) const STEP_HEIGHT_MAX: f64 = 1e3;

/// A patch of the ground: its index (−1 before `step_at`), its extent
/// `[lo, hi)` and its level.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Patch {
    index: i64,
    lo: f64,
    hi: f64,
}

impl TerrainOptions {
    /// Is this the flat slope (no step, no roughness)?
    #[inline]
    pub(crate) fn is_flat(&self) -> bool {
        self.step_height == 0.0 && self.roughness == 0.0
    }

    /// Is this the default flat slope, seed and patch included? A flat
    /// slope with another seed or patch is another scan: the steps to fall
    /// and the MFPT walk a rough slope drawn from them.
    pub(crate) fn is_default_flat(&self) -> bool {
        self.is_flat() && self.seed == 0 && self.patch == PATCH_DEFAULT
    }

    /// The slope with a step down of `height` at `at` (m).
    pub(crate) fn step(height: f64, at: f64) -> Self {
        Self {
            step_height: height,
            step_at: at,
            ..Self::default()
        }
    }

    /// The rough slope from `at` (m) on: patches of `patch` m whose heights
    /// are drawn from N(0, `roughness`²) by `seed`.
    pub fn rough(roughness: f64, seed: u64, at: f64, patch: f64) -> Self {
        Self {
            step_at: at,
            roughness,
            seed,
            patch,
            ..Self::default()
        }
    }

    /// Refuses a step height or roughness outside [0, 1000] m (a step up
    /// would put a riser in every foot's way), a step position outside
    /// (0, 1e6] m or a patch outside [0.001, 1000] m.
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
        )?;
        check(
            "terrain.roughness",
            self.roughness,
            "in [0, 1000] (m, standard deviation of a patch's height)",
            |v| (0.0..=STEP_HEIGHT_MAX).contains(&v),
        )?;
        check(
            "terrain.patch",
            self.patch,
            "in [0.001, 1000] (m, length of a rough patch)",
            |v| (1e-3..=1e3).contains(&v),
        )
    }

    /// The patch under `x`: before `step_at` the one flat patch, after it
    /// one segment without roughness, or patches of `patch` m with it.
    #[inline]
    fn patch_at(&self, x: f64) -> Patch {
        if x < self.step_at {
            return self.patch(-1);
        }
        if self.roughness == 0.0 {
            return self.patch(0);
        }
        // The index from the division, corrected so that `x` lies in
        // `[edge(k), edge(k + 1))` exactly as the edges are computed.
        let mut k = ((x - self.step_at) / self.patch).floor().max(0.0) as i64;
        while k > 0 && x < self.edge(k) {
            k -= 1;
        }
        while x >= self.edge(k + 1) {
            k += 1;
        }
        self.patch(k)
    }

    /// Patch `k`'s extent, the one [`patch_at`](Self::patch_at) finds it
    /// by; NaN for a patch there is not (beyond the first after `step_at`
    /// on a ground without roughness).
    #[inline]
    fn patch(&self, k: i64) -> Patch {
        let (lo, hi) = if k < 0 {
            (f64::NEG_INFINITY, self.step_at)
        } else if self.roughness == 0.0 {
            if k == 0 {
                (self.step_at, f64::INFINITY)
            } else {
                (f64::NAN, f64::NAN)
            }
        } else {
            (self.edge(k), self.edge(k + 1))
        };
        Patch { index: k, lo, hi }
    }

    /// The lower edge of rough patch `k`.
    #[inline]
    fn edge(&self, k: i64) -> f64 {
        self.step_at + k as f64 * self.patch
    }

    /// The height of patch `k` (−1: the flat slope before `step_at`).
    #[inline]
    fn level(&self, k: i64) -> f64 {
        if k < 0 {
            0.0
        } else if self.roughness == 0.0 {
            -self.step_height
        } else {
            let z = match self.branches.seed_of(k) {
                Some((_, Some(z), _)) => z,
                Some((seed, None, scale)) => standard_normal(seed, k as u64) * scale,
                None => standard_normal(self.seed, k as u64),
            };
            -self.step_height + self.roughness * z
        }
    }

    /// Draws the rough patches at and beyond `x` afresh with `seed`: those
    /// from the first patch that starts after `x` on. Nothing changes on a
    /// ground without roughness.
    pub(crate) fn branch_beyond(&mut self, x: f64, seed: u64) {
        self.branch_beyond_at(x, seed, f64::NAN);
    }

    /// [`branch_beyond`](Self::branch_beyond) with the first patch drawn
    /// afresh at the height `z × roughness` (`z` NaN: drawn with `seed`).
    pub(crate) fn branch_beyond_at(&mut self, x: f64, seed: u64, z: f64) {
        self.branch_beyond_scaled(x, seed, z, 1.0);
    }

    /// [`branch_beyond_at`](Self::branch_beyond_at) with the heights drawn
    /// with `seed` multiplied by `scale` (the first patch's `z` is not).
    pub(crate) fn branch_beyond_scaled(&mut self, x: f64, seed: u64, z: f64, scale: f64) {
        if self.roughness != 0.0 {
            let first = self.patch_at(x).index.max(-1) + 1;
            self.branches
                .branch(first, seed, (!z.is_nan()).then_some(z), scale);
        }
    }

    /// The standard-normal height of the patch under `x` (0 off the rough
    /// ground), and the distance from `x` to the next patch's edge.
    pub(crate) fn patch_ahead(&self, x: f64) -> (f64, f64) {
        if self.roughness == 0.0 || x < self.step_at {
            return (0.0, (self.step_at - x).max(0.0));
        }
        let p = self.patch_at(x);
        (
            (self.level(p.index) + self.step_height) / self.roughness,
            p.hi - x,
        )
    }

    /// The ground's height (slope normal) under `x`.
    #[inline]
    pub fn ground(&self, x: f64) -> f64 {
        if self.is_flat() {
            0.0
        } else {
            self.level(self.patch_at(x).index)
        }
    }

    /// Where a point `p` belongs when it lies at most `reach` inside a face
    /// (nearer the face than the top of the patch it is in, and at most
    /// `reach` below the face's foot): on the face, at its foot if below
    /// it; and the face's side. `None` anywhere else.
    pub(crate) fn out_of_face(&self, p: [f64; 2], reach: f64) -> Option<([f64; 2], f64)> {
        if self.is_flat() {
            return None;
        }
        let patch = self.patch_at(p[0]);
        let depth = self.level(patch.index) - p[1];
        [
            (patch.index - 1, p[0] - patch.lo, patch.index),
            (patch.index + 1, patch.hi - p[0], patch.index + 1),
        ]
        .into_iter()
        .map(|(k, across, face)| (self.level(k), across, face))
        .find(|&(low, across, _)| low - p[1] <= reach && across < depth && across <= reach)
        .map(|(low, _, face)| {
            let face = self.face_between(face);
            ([face.foot_x(), p[1].max(low)], face.side)
        })
    }

    /// The edge guard of a tip sliding at `x` on the patch at height
    /// `level`: the distance from `x` to the nearer edge of the patch under
    /// it, positive while that patch is the tip's own and negative once it
    /// has crossed into another (so it changes sign exactly at the edge).
    #[inline]
    pub(crate) fn edge_distance(&self, x: f64, level: f64) -> f64 {
        let p = self.patch_at(x);
        let (to_lo, to_hi) = (x - p.lo, p.hi - x);
        if self.level(p.index) == level {
            to_lo.min(to_hi)
        } else if to_hi <= to_lo {
            // Written as differences, not negated distances, so that the
            // step's guard is what it was, signed zeros included.
            x - p.hi
        } else {
            p.lo - x
        }
    }

    /// The rate of [`edge_distance`](Self::edge_distance) for a tip moving
    /// at `vx`.
    #[inline]
    pub(crate) fn edge_rate(&self, x: f64, vx: f64, level: f64) -> f64 {
        let p = self.patch_at(x);
        let rate = if p.hi - x <= x - p.lo { -vx } else { vx };
        if self.level(p.index) == level {
            rate
        } else {
            -rate
        }
    }

    /// The height of the patch a tip sliding at `x` with velocity `vx` on
    /// the patch at height `level` moves onto at its edge guard.
    pub(crate) fn level_beyond(&self, x: f64, vx: f64, level: f64) -> f64 {
        self.level(self.index_beyond(x, vx, level))
    }

    /// The index of that patch.
    fn index_beyond(&self, x: f64, vx: f64, level: f64) -> i64 {
        let k = self.patch_at(x).index;
        if self.level(k) != level {
            // Located just past the edge: already on the next patch.
            return k;
        }
        if vx >= 0.0 { k + 1 } else { k - 1 }
    }

    /// The patch under `x`, noted for a free tip over it.
    pub(crate) fn over_at(&self, x: f64) -> Over {
        self.over_patch(self.patch_at(x).index)
    }

    /// The patch a free tip at `x` moving at `vx`, over `own`, passes onto at
    /// its edge pass (as [`level_beyond`](Self::level_beyond) finds it).
    pub(crate) fn over_beyond(&self, x: f64, vx: f64, own: &Over) -> Over {
        self.over_patch(self.index_beyond(x, vx, own.level))
    }

    /// Patch `k` as a free tip notes it: its level and its extent (NaN
    /// where there is no such patch, so that the guards below take the
    /// general path).
    fn over_patch(&self, k: i64) -> Over {
        let Patch { lo, hi, .. } = self.patch(k);
        Over {
            level: self.level(k),
            lo,
            hi,
        }
    }

    /// [`edge_distance`](Self::edge_distance) from the patch a free tip is
    /// over. Inside it (nearly always) the distance to its nearer edge
    /// without finding the patch and its height again: the guards of a free
    /// tip are evaluated at every step and at every iterate of event
    /// location, and finding the patch under `x` and its height there was a
    /// tenth of a rough run's time. The same value, bit for bit.
    #[inline]
    pub(crate) fn edge_distance_over(&self, x: f64, over: &Over) -> f64 {
        if over.holds(x) {
            (x - over.lo).min(over.hi - x)
        } else {
            self.edge_distance(x, over.level)
        }
    }

    /// [`edge_rate`](Self::edge_rate) from the patch a free tip is over,
    /// as [`edge_distance_over`](Self::edge_distance_over).
    #[inline]
    pub(crate) fn edge_rate_over(&self, x: f64, vx: f64, over: &Over) -> f64 {
        if over.holds(x) {
            if over.hi - x <= x - over.lo { -vx } else { vx }
        } else {
            self.edge_rate(x, vx, over.level)
        }
    }

    /// The face between patch `k − 1` and patch `k` (patch −1 is the flat
    /// slope before `step_at`).
    fn face_between(&self, k: i64) -> Face {
        // `edge(0)` is `step_at` exactly: the step's face too.
        let x = self.edge(k);
        let (left, right) = (self.level(k - 1), self.level(k));
        Face {
            x,
            side: if left < right { -1.0 } else { 1.0 },
            low: left.min(right),
            high: left.max(right),
        }
    }

    /// The face whose foot a tip on the lower patch at `x` touches, given
    /// the face's side (`x` is [`Face::foot_x`] of it).
    pub(crate) fn face_beside(&self, x: f64, side: f64) -> Face {
        let k = self.patch_at(x).index;
        self.face_between(if side < 0.0 { k + 1 } else { k })
    }

    /// The face a tip at `x` moving at `vx` has just crossed into (located
    /// just past it, inside the higher patch).
    pub(crate) fn face_crossed(&self, x: f64, vx: f64) -> Face {
        let k = self.patch_at(x).index;
        self.face_between(if vx >= 0.0 { k } else { k + 1 })
    }

    /// The face a tip sliding at `x` with velocity `vx` on the patch at
    /// height `level` meets at its edge guard (located on either side of it).
    pub(crate) fn face_ahead(&self, x: f64, vx: f64, level: f64) -> Face {
        let k = self.patch_at(x).index;
        let crossed = self.level(k) != level;
        self.face_between(match (vx >= 0.0, crossed) {
            (true, true) | (false, false) => k,
            (true, false) | (false, true) => k + 1,
        })
    }

    /// A tip this far below the ground at the touchdown event met the riser,
    /// not the ground: a thousand touchdown offsets, far beyond where a
    /// touchdown is located and far below any step that matters.
    #[inline]
    pub(crate) fn met_riser(&self, gap: f64, touchdown_height: f64) -> bool {
        !self.is_flat() && gap < 1e3 * touchdown_height
    }
}

/// The patch a free tip is over (`Rtw::over`): its level, from which the
/// tip's touchdown guard measures, and its extent `[lo, hi)` (NaN where
/// the guards find the patch under the tip afresh instead).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Over {
    /// The patch's height.
    pub(crate) level: f64,
    lo: f64,
    hi: f64,
}

impl Over {
    /// The level `level`, with no extent noted.
    pub(crate) const fn level(level: f64) -> Self {
        Self {
            level,
            lo: f64::NAN,
            hi: f64::NAN,
        }
    }

    /// Whether `x` lies in the patch's extent (never where none is noted).
    #[inline]
    fn holds(&self, x: f64) -> bool {
        self.lo <= x && x < self.hi
    }
}

/// A face of the ground: the vertical surface at a patch edge, between the
/// lower and the higher of the two patches (docs/model.md §4).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Face {
    /// The edge's `x`.
    pub(crate) x: f64,
    /// The side of the lower patch (±1 along x): the face's outward normal
    /// is `(side, 0)`.
    pub(crate) side: f64,
    /// The lower patch's level: the face's foot.
    pub(crate) low: f64,
    /// The higher patch's level: the face's top.
    pub(crate) high: f64,
}

impl Face {
    /// The `x` of a tip against the face: the edge itself when the lower
    /// patch starts there, else the last float before it, so that the
    /// ground under the tip is the lower patch's (patches are `[lo, hi)`).
    pub(crate) fn foot_x(&self) -> f64 {
        if self.side > 0.0 {
            self.x
        } else {
            self.x.next_down()
        }
    }
}

/// A standard normal deviate that is a pure function of `(seed, k)`:
/// SplitMix64 of both, then Box–Muller on the two uniforms it gives.
///
/// Remembered per thread: the guards and the contact forces ask for the
/// height of the same few patches many times a step, and the logarithm and
/// cosine of Box–Muller were a tenth of a rough run's time. A remembered
/// value is the very value [`box_muller`] gives, so the ground is unchanged.
fn standard_normal(seed: u64, k: u64) -> f64 {
    use std::cell::Cell;
    const SLOTS: usize = 64;
    thread_local! {
        // (seed, k + 1, height bits): k + 1 is never 0, so the zeroed
        // slots of a new thread match no patch.
        static HEIGHTS: [Cell<(u64, u64, u64)>; SLOTS] =
            const { [const { Cell::new((0, 0, 0)) }; SLOTS] };
    }
    let slot = (k ^ seed.rotate_left(17) ^ (seed >> 40)) as usize % SLOTS;
    HEIGHTS.with(|h| {
        let (s, k1, bits) = h[slot].get();
        if s == seed && k1 == k.wrapping_add(1) {
            f64::from_bits(bits)
        } else {
            let z = box_muller(seed, k);
            h[slot].set((seed, k.wrapping_add(1), z.to_bits()));
            z
        }
    })
}

/// [`standard_normal`] computed afresh.
fn box_muller(seed: u64, k: u64) -> f64 {
    // SplitMix64's output for the state x: the first draw of the seeded
    // generator the MFPT estimator uses.
    let mix = |x: u64| hybrid_ode::metastable::Rng::new(x).next_u64();
    let a = mix(mix(seed) ^ k);
    let b = mix(a);
    const UNIT: f64 = 1.0 / (1u64 << 53) as f64;
    // u1 in (0, 1], never 0, so its logarithm is finite.
    let u1 = ((a >> 11) as f64 + 1.0) * UNIT;
    let u2 = (b >> 11) as f64 * UNIT;
    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_patch_height_is_splitmix64_then_box_muller() {
        // SplitMix64 written out (Steele, Lea and Flood 2014), then
        // Box–Muller with u1 in (0, 1]: the heights every committed rough
        // result was drawn with.
        fn splitmix(mut x: u64) -> u64 {
            x = x.wrapping_add(0x9e37_79b9_7f4a_7c15);
            x = (x ^ (x >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            x = (x ^ (x >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
            x ^ (x >> 31)
        }
        for (seed, k) in [(0, 0), (7, 3), (u64::MAX, 41), (1 << 40, 999)] {
            let a = splitmix(splitmix(seed) ^ k);
            let b = splitmix(a);
            let unit = 1.0 / (1u64 << 53) as f64;
            let (u1, u2) = (((a >> 11) as f64 + 1.0) * unit, (b >> 11) as f64 * unit);
            let z = (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos();
            assert_eq!(box_muller(seed, k).to_bits(), z.to_bits());
        }
    }

    #[test]
    fn a_remembered_patch_height_is_the_height_computed_afresh() {
        // Patches of several branches asked for in a mixed order, so that
        // slots are shared and overwritten: every answer must be the
        // Box–Muller value itself, bit for bit.
        for round in 0..3u64 {
            for k in (0..500u64).rev().chain(0..500) {
                for seed in [1u64, 2, 1 << 41, u64::MAX, 7 + round] {
                    let k = (k * 37 + round) % 1000;
                    assert_eq!(
                        standard_normal(seed, k).to_bits(),
                        box_muller(seed, k).to_bits()
                    );
                }
            }
        }
    }

    #[test]
    fn the_patch_heights_are_a_standard_normal_function_of_seed_and_index() {
        let z: Vec<f64> = (0..20_000).map(|k| standard_normal(7, k)).collect();
        let n = z.len() as f64;
        let mean = z.iter().sum::<f64>() / n;
        let var = z.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n;
        assert!(mean.abs() < 0.03, "mean {mean}");
        assert!((var - 1.0).abs() < 0.05, "variance {var}");
        assert_eq!(standard_normal(7, 3).to_bits(), z[3].to_bits());
        assert_ne!(standard_normal(8, 3), z[3]);
    }

    #[test]
    fn a_rough_ground_is_flat_before_its_start_and_piecewise_flat_after() {
        let t = TerrainOptions::rough(0.01, 3, 1.0, 0.2);
        t.validate().unwrap();
        assert!(!t.is_flat());
        assert_eq!(t.ground(0.999), 0.0);
        // Constant within a patch, and each patch at its own height.
        assert_eq!(t.ground(1.0), t.ground(1.199));
        assert_ne!(t.ground(1.199), t.ground(1.2));
        assert_eq!(t.ground(1.2), 0.01 * standard_normal(3, 1));
        // Another seed, another ground.
        assert_ne!(
            t.ground(1.5),
            TerrainOptions::rough(0.01, 4, 1.0, 0.2).ground(1.5)
        );
        // The edge guard: positive on its own patch, negative beyond, zero
        // at the edge.
        let own = t.ground(1.1);
        assert!((t.edge_distance(1.15, own) - 0.05).abs() < 1e-12);
        assert!((t.edge_distance(1.25, own) + 0.05).abs() < 1e-12);
        assert_eq!(t.edge_rate(1.15, 2.0, own), -2.0);
        assert_eq!(t.level_beyond(1.19, 1.0, own), t.ground(1.2));
        assert_eq!(t.level_beyond(1.01, -1.0, own), 0.0);
    }

    /// The edge guard of a free tip from the patch it noted is the general
    /// one, bit for bit: inside the patch from its extent, beyond it (the
    /// crossed side, and far beyond) from the patch found afresh; on a
    /// rough slope, on a step down, and over the flat slope before either.
    #[test]
    fn a_free_tip_s_edge_guard_from_its_noted_patch_is_the_general_one_bit_for_bit() {
        let grounds = [
            TerrainOptions::rough(0.01, 3, 1.0, 0.2),
            TerrainOptions::rough(0.05, 7, 0.3, 0.8),
            TerrainOptions::step(0.1, 1.0),
        ];
        for t in grounds {
            for start in [0.2, 0.999, 1.0, 1.05, 1.2, 1.37, 2.61] {
                let own = t.over_at(start);
                assert_eq!(own.level, t.ground(start));
                for i in -400..=400 {
                    let x = start + i as f64 * 1.3e-3;
                    for vx in [-0.7, 0.0, 1.1] {
                        let general =
                            (t.edge_distance(x, own.level), t.edge_rate(x, vx, own.level));
                        let fast = (t.edge_distance_over(x, &own), t.edge_rate_over(x, vx, &own));
                        assert_eq!(fast.0.to_bits(), general.0.to_bits(), "{start} {x}");
                        assert_eq!(fast.1.to_bits(), general.1.to_bits(), "{start} {x} {vx}");
                    }
                }
                // The patch passed onto is the one whose level the general
                // rule names, with that patch's own extent.
                for (x, vx) in [(start, 1.0), (start, -1.0)] {
                    let next = t.over_beyond(x, vx, &own);
                    assert_eq!(next.level, t.level_beyond(x, vx, own.level));
                }
            }
        }
    }

    #[test]
    fn a_branch_keeps_the_patches_behind_it_and_draws_those_beyond_afresh() {
        let t = TerrainOptions::rough(0.01, 3, 1.0, 0.2);
        let mut b = t;
        // x = 1.5 lies on patch 2: patches 3 on are drawn afresh.
        b.branch_beyond(1.5, 99);
        for x in [0.5, 1.0, 1.3, 1.5, 1.599] {
            assert_eq!(b.ground(x).to_bits(), t.ground(x).to_bits(), "{x}");
        }
        for x in [1.6, 1.9, 3.0] {
            assert_ne!(b.ground(x), t.ground(x), "{x}");
        }
        assert_eq!(b.ground(1.7), 0.01 * standard_normal(99, 3));
        // Reproducible: the same branch gives the same ground.
        let mut again = t;
        again.branch_beyond(1.5, 99);
        assert_eq!(again, b);
        // A later branch keeps the earlier one's patches before it.
        let mut c = b;
        c.branch_beyond(2.1, 7);
        assert_eq!(c.ground(1.7), b.ground(1.7));
        assert_eq!(c.ground(2.25), 0.01 * standard_normal(7, 6));
        // A branch before the last one replaces it.
        c.branch_beyond(1.5, 8);
        assert_eq!(c.ground(2.25), 0.01 * standard_normal(8, 6));
        // The oldest of too many is dropped: its patches take the ground's
        // seed again, the newer ones are kept.
        let mut d = t;
        for i in 0..=BRANCHES {
            d.branch_beyond(1.1 + 0.2 * i as f64, 100 + i as u64);
        }
        assert_eq!(d.ground(1.3), t.ground(1.3));
        assert_eq!(d.ground(1.5), 0.01 * standard_normal(101, 2));
        // No roughness, no branch.
        let mut step = TerrainOptions::step(0.02, 1.5);
        step.branch_beyond(1.6, 5);
        assert_eq!(step, TerrainOptions::step(0.02, 1.5));
    }

    #[test]
    fn roughness_zero_is_the_step_bit_for_bit() {
        let step = TerrainOptions::step(0.02, 1.5);
        for x in [-1.0, 1.2, 1.4999, 1.5, 2.0, 9.0] {
            for level in [0.0, -0.02] {
                let old = if level == 0.0 { 1.5 - x } else { x - 1.5 };
                assert_eq!(step.edge_distance(x, level).to_bits(), old.to_bits());
                let vx = 0.3;
                let old_rate = if level == 0.0 { -vx } else { vx };
                assert_eq!(step.edge_rate(x, vx, level), old_rate, "{x} {level}");
            }
        }
    }

    #[test]
    fn out_of_range_roughness_is_refused_naming_the_field() {
        for (t, field) in [
            (
                TerrainOptions::rough(-0.01, 0, 1.0, 0.2),
                "terrain.roughness",
            ),
            (
                TerrainOptions::rough(f64::NAN, 0, 1.0, 0.2),
                "terrain.roughness",
            ),
            (TerrainOptions::rough(0.01, 0, 1.0, 0.0), "terrain.patch"),
            (
                TerrainOptions::rough(0.01, 0, 1.0, f64::INFINITY),
                "terrain.patch",
            ),
        ] {
            let e = t.validate().unwrap_err().to_string();
            assert!(e.starts_with(field), "{e}");
            assert!(e.contains("must be in"), "{e}");
        }
    }
}
