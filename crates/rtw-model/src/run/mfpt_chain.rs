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
//! are already laid (0 where they will be drawn afresh); and the distance
//! from the furthest tip to the next edge. A fall comes a step or two after
//! the patch that sets it is laid: a node's step dooms it when it falls or
//! [`CHAIN_SETTINGS`]'s `lookahead` steps after it on patches at the mean
//! height do.
//!
//! **The cells** are cut over a Fleming–Viot cloud at the same roughness
//! ([`qsd_cloud`]; a cloud at a larger roughness would lay its kept
//! patches at that roughness, and they are part of the state).
//!
//! **Status: not yet right below σ = 3 cm** (results/robustness/mfpt_chain.md).
//! At Fig. 7(a) it overlaps the counted estimate at 5 and 3 cm and is 5 000
//! times too high at 2 cm; its MFPT equals its one-step estimate at every
//! roughness, so the mesh (about 530 cells over a cloud of effective
//! dimension 11 to 17 of these 31 features) carries no memory from step to
//! step and misses the falls that come through several moderate patches.

use crate::options::{RobustnessOptions, TerrainOptions};
use crate::outcome::{ChainDiagnostics, MeanFirstPassage};
use crate::plant::geometry::SPOKES;
use crate::run::mfpt::{RtwWalker, State, com_velocity, furthest_tip, walker};
use crate::run::settled::SettledGait;
use hybrid_ode::Work;
use hybrid_ode::chain::{ChainOptions, ChainWalker, chain_mfpt, qsd_cloud};
use hybrid_ode::metastable::Rng;

/// The chain's settings for the RTW (besides the seed, `terrain.seed`).
pub const CHAIN_SETTINGS: ChainOptions = ChainOptions {
    seed: 0,
    cells: 800,
    members: 6000,
    nodes: 9,
    lookahead: 4,
    bootstrap: 40,
    min_members: 5,
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

    fn stopped(&self) -> bool {
        crate::cancel::requested()
    }
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
        let sample = qsd_cloud(
            &walker, &start, replicas, burn_in, sampled, &mut rng, &mut steps,
        )?;
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
