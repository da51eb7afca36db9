//! The MFPT by a Markov chain on a mesh of the extended states the walker
//! reaches (`robustness.mfpt_method = "chain"`, docs/robustness-estimators.md,
//! "The chain method"): the walker of `run/mfpt.rs` as a
//! [`ChainWalker`] for [`hybrid_ode::chain`].
//!
//! **The input** of a step is the height of the first patch drawn afresh
//! before it (the first that starts more than a rod beyond the furthest
//! tip), in standard deviations: the step lays it at that height
//! ([`TerrainOptions::branch_beyond_at`]) and the patches beyond it from a
//! seed that is a function of the height, so a step is a function of
//! (state, height). The patches beyond the first are met only by a step
//! that reaches more than a patch beyond where it started, and are drawn
//! afresh before the next.
//!
//! **The extended state's features** (lengths in rods, velocities in the
//! flat gait's mean speed; the estimator standardises them): the centre of
//! mass's velocity and its height above the ground under it; the six tips,
//! ordered downhill, each its position from the centre of mass, its height
//! above the ground under it and its velocity; the heights, from the
//! patch under the centre of mass, of the next three patches where they
//! are already laid (0 where they will be drawn afresh); the distance from
//! the furthest tip to the next edge; and how long no tip has touched down.
//!
//! **How the RTW falls on rough ground, and the doom test it needs.** At
//! Fig. 7(a) the falls at σ = 3 cm are stalls (all 8 of the cloud of
//! `falls_on_the_rough_slope_are_stalls_called_late`):
//! the walker meets a face it cannot climb, rocks before it, its tips
//! still touching down now and then, and the stall rule (no touchdown for
//! `stall_time`) calls the fall tens of steps later. The step that dooms
//! it is the one whose new patch is that face; a doom test of 4 steps
//! after it never saw the fall, so the chain counted nearly none.
//! An input therefore dooms a member when it falls within
//! [`CHAIN_SETTINGS`]'s `lookahead` (60 steps of ground at the mean
//! height) before its hindmost tip has passed the far edge of the patch
//! that input laid ([`ChainWalker::behind`]); a walker that walks on
//! leaves it in a few steps, so only the doomed inputs pay the long test.
//! The doom set in the input is not a clean tail (inputs a little below
//! the face it cannot climb doom it or not by its phase), so the input is
//! stratified in the halvings of each tail's mass
//! ([`ChainOptions::strata`]), not taken at Gauss–Hermite nodes.
//!
//! **The sample.** A Fleming–Viot cloud at the same roughness
//! ([`qsd_cloud`]) gives the members their states. A fall needs a face too
//! high to climb, which the patch a member has laid ahead (between its
//! furthest tip and its reach) makes with the input, and a plain sample
//! holds few high ones: that patch is drawn again from a law
//! [`KEPT_PATCH_WIDTH`] times wider and the member weighted by its
//! likelihood ratio ([`widen_kept_patches`]), except where the cloud
//! already falls more often than once in [`RARE_FALLS`]⁻¹ steps, whose
//! sample holds such ground by itself (at σ = 5 cm, widened, the chain gave
//! 103 [84, 125], plain 121 [101, 162], counting 153 [119, 215]). The
//! cells are quantile bins of a learned score of the fall
//! ([`ChainOptions::by_fall`]); each cell's row is its members' weighted
//! mean.
//!
//! **Status** (results/robustness/mfpt_chain-cli.md): at Fig. 7(a) its
//! interval holds the counted estimate at 5 and 3 cm. At 2 cm it is about
//! ten times too high and moves with the kept patch's width (3.1 × 10⁷,
//! 8.3 × 10⁶ and 1.4 × 10⁷ at widths 2, 3 and 4.5, against counting's
//! 8.2 × 10⁵): the falls there also go through the patches walked before
//! the face, which the walker's state remembers and a plain sample holds
//! too few of. It is not yet an answer below 3 cm.

use crate::options::{RobustnessOptions, TerrainOptions};
use crate::outcome::{ChainDiagnostics, MeanFirstPassage};
use crate::plant::geometry::SPOKES;
use crate::run::mfpt::{RtwWalker, State, com_velocity, furthest_tip, hindmost_tip, walker};
use crate::run::settled::SettledGait;
use hybrid_ode::Work;
use hybrid_ode::chain::{ChainOptions, ChainWalker, chain_mfpt, qsd_cloud};
use hybrid_ode::metastable::Rng;

/// The chain's settings for the RTW (besides the seed, `terrain.seed`).
pub const CHAIN_SETTINGS: ChainOptions = ChainOptions {
    seed: 0,
    cells: 50,
    members: 1500,
    nodes: 9,
    lookahead: 60,
    bootstrap: 40,
    min_members: 5,
    strata: 40,
    by_fall: true,
};

/// The cloud that samples the cells: walkers, steps of burn-in, steps
/// sampled (32 × 60 = 1920 states).
const CLOUD: (usize, usize, usize) = (64, 60, 100);

impl ChainWalker for RtwWalker<'_, '_> {
    type State = State;

    fn step_with(&self, st: &State, z: f64) -> Option<State> {
        self.step_branched(st, z.to_bits() ^ 0x7a7a_7a7a, z)
    }

    fn features(&self, st: &State) -> Vec<f64> {
        let (rtw, y) = (&st.rtw, &st.y);
        let l = self.s.phys.length;
        let speed = self.speed;
        let ground = |x: f64| rtw.terrain().ground(x);
        let rods = rtw.rods(y);
        let com = [
            rods.iter().map(|r| r.c[0]).sum::<f64>() / 3.0,
            rods.iter().map(|r| r.c[1]).sum::<f64>() / 3.0,
        ];
        let v = com_velocity(rtw, y);
        let mut f = vec![v[0] / speed, v[1] / speed, (com[1] - ground(com[0])) / l];
        let mut tips: Vec<([f64; 2], [f64; 2])> = SPOKES
            .iter()
            .map(|&(rod, tip)| rtw.body.tip_point(&rods[rod], tip))
            .collect();
        tips.sort_by(|a, b| a.0[0].total_cmp(&b.0[0]));
        for (p, v) in &tips {
            f.extend([
                (p[0] - com[0]) / l,
                (p[1] - ground(p[0])) / l,
                v[0] / speed,
                v[1] / speed,
            ]);
        }
        // The ground within reach: laid patches ahead of the centre of
        // mass, and where the next edge is.
        let terrain = rtw.terrain();
        let (z_com, to_edge) = terrain.patch_ahead(com[0]);
        let reach = self.reach(st);
        let mut x = com[0] + to_edge;
        for _ in 0..3 {
            let laid = x <= reach;
            let (z, len) = terrain.patch_ahead(x + 1e-9);
            f.push(if laid { z - z_com } else { 0.0 });
            x += len.max(1e-9);
        }
        let tip = furthest_tip(rtw, y);
        f.push(terrain.patch_ahead(tip).1 / terrain.patch);
        // How long no tip has touched down, of the stall time that makes
        // it a fall: without it a standing walker's cell keeps its mass
        // with no fall, a trap of the chain.
        f.push(st.quiet / self.options.stall_time);
        f
    }

    /// The walker has left the patch a step from `from` lays afresh (the
    /// first beyond its reach) when its hindmost tip is past that patch's
    /// far edge: a walker that meets a face too high to climb rocks before
    /// it for tens of steps before the stall rule calls the fall, and one
    /// in a hole must still climb out at its far edge.
    fn behind(&self, from: &State, now: &State) -> bool {
        let reach = self.reach(from);
        if !reach.is_finite() {
            return false;
        }
        let terrain = now.rtw.terrain();
        let start = reach + terrain.patch_ahead(reach).1;
        let far = start + terrain.patch;
        hindmost_tip(&now.rtw, &now.y) > far
    }

    fn weight(&self, st: &State) -> f64 {
        st.weight
    }

    fn stopped(&self) -> bool {
        crate::cancel::requested()
    }
}

/// The kept patch ahead of each of the chain's members (the one that
/// starts between its furthest tip and its reach) is drawn again from a
/// law this many times wider than the ground's, and the member weighted by
/// its likelihood ratio (module doc).
pub const KEPT_PATCH_WIDTH: f64 = 3.0;

/// The cloud's falls per walker-step below which its members' kept patch
/// is widened (at Fig. 7(a): about 1 in 120 steps at σ = 5 cm, 1 in 8 000
/// at 3 cm).
pub const RARE_FALLS: f64 = 1e-3;

/// The chain's walker, counting the falls of its steps.
struct Falls<'w, 'a, 'b> {
    walker: &'w RtwWalker<'a, 'b>,
    falls: std::cell::Cell<u64>,
}

impl<'w, 'a, 'b> Falls<'w, 'a, 'b> {
    fn new(walker: &'w RtwWalker<'a, 'b>) -> Self {
        Self {
            walker,
            falls: std::cell::Cell::new(0),
        }
    }
}

impl ChainWalker for Falls<'_, '_, '_> {
    type State = State;

    fn step_with(&self, st: &State, z: f64) -> Option<State> {
        let next = self.walker.step_with(st, z);
        if next.is_none() {
            self.falls.set(self.falls.get() + 1);
        }
        next
    }

    fn features(&self, st: &State) -> Vec<f64> {
        self.walker.features(st)
    }

    fn stopped(&self) -> bool {
        self.walker.stopped()
    }
}

/// The likelihood ratio under the ground's law of the patches from the one
/// under `from` to the last that starts by `to`, drawn from a law `wide`
/// times wider.
fn patches_ratio(terrain: &TerrainOptions, from: f64, to: f64, wide: f64) -> f64 {
    let mut x = from;
    let mut ratio = 1.0;
    while x <= to {
        let (z, len) = terrain.patch_ahead(x + 1e-9);
        ratio *= wide * (-0.5 * z * z * (1.0 - 1.0 / (wide * wide))).exp();
        x += len.max(1e-9);
    }
    ratio
}

/// Draws the ground ahead of `st`'s furthest tip again from a law `wide`
/// times wider (`seed`), and sets its weight to the likelihood ratio of the
/// patches laid there that its next step keeps (those that start before its
/// reach): `∏ wide · exp(−z²(1 − 1/wide²)/2)`, `z` each one's height in
/// standard deviations of the ground's law.
pub(crate) fn widen_kept_patches(w: &RtwWalker<'_, '_>, st: &mut State, wide: f64, seed: u64) {
    let tip = furthest_tip(&st.rtw, &st.y);
    let y = st.y;
    st.rtw
        .branch_terrain_beyond_scaled(tip, seed, f64::NAN, wide, &y);
    let reach = w.reach(st);
    let terrain = st.rtw.terrain();
    // From the first edge beyond the furthest tip: the patches laid ahead.
    let weight = patches_ratio(terrain, tip + terrain.patch_ahead(tip).1, reach, wide);
    st.weight = weight;
}

/// The chain's MFPT of the settled gait `s` on the rough slope of `r.sigma`
/// (see the module doc), and its diagnostics; `None` when the stop flag
/// ended it part way.
pub(crate) fn chain_first_passage(
    s: &SettledGait<'_>,
    r: &RobustnessOptions,
    terrain: TerrainOptions,
    work: &mut Work,
) -> Option<(MeanFirstPassage, ChainDiagnostics)> {
    let (walker, start) = walker(s, r, terrain);
    let estimate = (|| {
        let mut rng = Rng::new(terrain.seed ^ 0x636c_6f75_6400);
        rng.next_u64();
        let mut steps = 0;
        let (replicas, burn_in, sampled) = CLOUD;
        let counting = Falls::new(&walker);
        let mut sample = qsd_cloud(
            &counting, &start, replicas, burn_in, sampled, &mut rng, &mut steps,
        )?;
        // Where the cloud falls often, its own sample holds the falls'
        // ground; widened, it gave too short an MFPT (module doc).
        if (counting.falls.get() as f64) < RARE_FALLS * steps as f64 {
            for (i, st) in sample.iter_mut().enumerate() {
                widen_kept_patches(&walker, st, KEPT_PATCH_WIDTH, 0x51de ^ i as u64);
            }
        }
        let c = chain_mfpt(
            &walker,
            &sample,
            &ChainOptions {
                seed: terrain.seed,
                ..CHAIN_SETTINGS
            },
        )?;
        Some((c, steps))
    })();
    *work += walker.work.into_inner();
    let (c, cloud_steps) = estimate?;
    Some((
        MeanFirstPassage {
            mfpt: c.mfpt,
            lo: c.lo,
            hi: c.hi,
            fall_rate: c.fall_rate,
            steps: c.steps + cloud_steps,
        },
        ChainDiagnostics {
            cells: c.cells,
            members: c.members,
            nodes: c.nodes,
            dimension: c.dimension,
            features: c.features,
            mfpt_fine: c.mfpt_fine,
            mfpt_one_step: c.mfpt_one_step,
        },
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::options::Options;
    use crate::run::mfpt_splitting::with_settled;

    /// Fig. 7(a) on the rough slope of 3 cm after ten steps of mean ground.
    fn on_the_rough_slope<T>(f: impl FnOnce(&RtwWalker<'_, '_>, State) -> T) -> T {
        let r = RobustnessOptions {
            sigma: 0.03,
            ..RobustnessOptions::default()
        };
        with_settled(&crate::params::Params::fig7a(), &Options::default(), |s| {
            let (w, mut st) = walker(s, &r, TerrainOptions::default());
            for _ in 0..10 {
                st = w.step_with(&st, 0.0).expect("ten steps of mean ground");
            }
            f(&w, st)
        })
        .expect("Fig. 7(a) is a stable gait")
    }

    /// Steps of mean ground after the step from `st` with input `z` until
    /// the walker has left that input's patch (`Ok`) or falls (`Err`),
    /// within `most`.
    fn until_behind(
        w: &RtwWalker<'_, '_>,
        st: &State,
        z: f64,
        most: usize,
    ) -> Result<usize, usize> {
        let mut t = w.step_with(st, z).ok_or(0usize)?;
        for k in 1..=most {
            if w.behind(st, &t) {
                return Ok(k);
            }
            t = w.step_with(&t, 0.0).ok_or(k)?;
        }
        Ok(most + 1)
    }

    /// The fall that a face too high to climb deals comes many steps after
    /// the step that lays it (the walker rocks before the face until the
    /// stall rule calls it), so a doom test of a few steps never sees it,
    /// and the test runs to the walker leaving that patch: on ground at the
    /// mean height it leaves it within a few steps; a face of 8 σ (24 cm),
    /// laid by the step from each of 12 states in a row, stops it whenever
    /// the step reaches it (a patch the step does not reach is drawn
    /// afresh before the next), and it falls: some at once (a trip), some
    /// only after tens of steps, which a test of 4 steps never saw.
    #[test]
    fn a_face_too_high_to_climb_dooms_the_walker_many_steps_later() {
        on_the_rough_slope(|w, mut st| {
            let mut blocked = Vec::new();
            for _ in 0..12 {
                let walked = until_behind(w, &st, 0.0, 60);
                assert!(matches!(walked, Ok(k) if k <= 15), "{walked:?}");
                blocked.push(until_behind(w, &st, 8.0, 60));
                st = w.step_with(&st, 0.0).expect("mean ground");
            }
            eprintln!("a face of 8 sigma: {blocked:?}");
            let falls: Vec<usize> = blocked.iter().filter_map(|b| b.err()).collect();
            assert!(falls.len() >= 3, "{blocked:?}");
            assert!(falls.iter().any(|&k| k > 20), "{blocked:?}");
        });
    }

    /// The widened kept patch's weight is its likelihood ratio: over many
    /// redraws of the same state's ground ahead its mean is 1 (the ratio's
    /// mean under the wider law), and no patch weighs more than the width
    /// (the ratio's largest value, at the mean height) per patch.
    #[test]
    fn the_widened_kept_patch_is_weighted_by_its_likelihood_ratio() {
        on_the_rough_slope(|w, st| {
            let n = 4000;
            let weights: Vec<f64> = (0..n)
                .map(|i| {
                    let mut t = st.clone();
                    widen_kept_patches(w, &mut t, KEPT_PATCH_WIDTH, i);
                    t.weight
                })
                .collect();
            let mean = weights.iter().sum::<f64>() / n as f64;
            let sd = (weights.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / n as f64).sqrt();
            eprintln!("mean weight {mean:.4} (sd {sd:.3})");
            assert!(sd > 0.0, "the redraws changed no kept patch");
            assert!(
                (mean - 1.0).abs() < 4.0 * sd / (n as f64).sqrt(),
                "{mean} ± {sd}"
            );
            assert!(
                weights
                    .iter()
                    .all(|x| *x > 0.0 && *x <= KEPT_PATCH_WIDTH.powi(2))
            );
        });
    }

    /// How the RTW falls on the rough slope of 3 cm: a Fleming–Viot cloud
    /// of 64 walkers walks 1 200 steps, and each walker's fall is a stall
    /// (no touchdown for `stall_time`) called while it stands before the
    /// ground it stopped at: its furthest tip moved less than a patch over
    /// the 15 steps before. That is why the doom test must run for tens of
    /// steps, not the 4 it once did.
    #[test]
    fn falls_on_the_rough_slope_are_stalls_called_late() {
        let r = RobustnessOptions {
            sigma: 0.03,
            ..RobustnessOptions::default()
        };
        with_settled(&crate::params::Params::fig7a(), &Options::default(), |s| {
            let (w, start) = walker(s, &r, TerrainOptions::default());
            let mut rng = Rng::new(7);
            let n = 64;
            // Each walker's state and its furthest tip over the last 16 steps.
            let mut cloud: Vec<(State, Vec<f64>)> = vec![(start, Vec::new()); n];
            let mut falls = Vec::new();
            for _ in 0..1200 {
                let next: Vec<Option<(State, Vec<f64>)>> = cloud
                    .iter()
                    .map(|(st, tips)| match w.step_with(st, rng.normal()) {
                        Some(t) => {
                            let mut tips = tips.clone();
                            tips.push(furthest_tip(&t.rtw, &t.y));
                            if tips.len() > 16 {
                                tips.remove(0);
                            }
                            Some((t, tips))
                        }
                        None => {
                            let moved = tips.last().unwrap_or(&0.0) - tips.first().unwrap_or(&0.0);
                            falls.push((st.quiet, moved, tips.len()));
                            None
                        }
                    })
                    .collect();
                let alive: Vec<usize> = (0..n).filter(|&i| next[i].is_some()).collect();
                cloud = (0..n)
                    .map(|i| {
                        next[i]
                            .clone()
                            .unwrap_or_else(|| next[alive[rng.below(alive.len())]].clone().unwrap())
                    })
                    .collect();
            }
            eprintln!("falls (quiet s, furthest tip's advance over 15 steps m): {falls:?}");
            assert!(falls.len() >= 3, "{falls:?}");
            let step = 1.0 / s.flat.f_w_newfoot;
            for &(quiet, moved, seen) in &falls {
                assert!(
                    quiet + step >= w.options.stall_time,
                    "not a stall: {falls:?}"
                );
                assert!(seen < 16 || moved < s.phys.length, "walked on: {falls:?}");
            }
        });
    }
}
