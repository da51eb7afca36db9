//! The mean first-passage time of a stable gait on a rough slope
//! (docs/robustness-rough.md, "Mean first-passage time"): the RTW as a
//! step-to-step stochastic walker for [`hybrid_ode::metastable`].
//!
//! **The ground.** The rough slope of the steps to fall: patches
//! `terrain.patch` long with heights from N(0, σ²), σ = `robustness.sigma`,
//! from `EDGE_AHEAD × L` ahead of the settled gait's front-most grounded tip,
//! first drawn with seed `terrain.seed`.
//!
//! **A step** is a step of the flat gait: the run from the walker's state
//! for `1 / f_w_newfoot` seconds, never stopped early as settled (so the
//! MFPT counts the steps that `steps_to_fall` counts, `f_w_newfoot × t`).
//! Before it, the ground from the first patch that starts more than a rod
//! length beyond the walker's furthest tip (before the first step, the
//! whole rough slope) is drawn afresh
//! ([`TerrainOptions::branch_beyond`]): the patches under and behind the
//! walker are kept, the ones it has not reached are new, so a clone of the
//! walker meets a future of its own, and the walker's steps are a Markov
//! chain on (its state, the patches it has reached). The step **falls** when
//! its run fails (a collapse, a riser trip, a numerical failure; too little
//! progress within one step is not a fall), or when no tip has touched down
//! for `stall_time` seconds of steps.
//!
//! `mfpt` is the expected steps to fall from the settled gait meeting the
//! rough slope (what `steps_to_fall` estimates when nothing is censored):
//! the estimator's burn-in (60 steps) is plain Monte Carlo from there, the
//! rest `1 / fall_rate` from the quasi-stationary regime. A step's fall
//! counts as a whole step (Monte Carlo counts `f_w_newfoot × t_end`, so the
//! MFPT is about half a step longer).
//!
//! **The fall rate is counted** ([`FallRate::Counting`]): the falls of the
//! Fleming–Viot cloud over its walker-steps. The splitting, whose cost
//! grows only as `log(MFPT)`, needs a score that climbs before a fall; the
//! RTW's falls are set by ground already drawn a step or two ahead of it,
//! and a score of its state (the centre of mass's velocity, below) does
//! not climb before them: at Fig. 7(a) and σ = 1 cm the splitting gave
//! 5171 [2537, ∞] steps against plain Monte Carlo's 495 [422, 568]
//! (CHANGELOG.md, "The MFPT's estimators tried and dropped"; measured
//! while a tip put on a face at its foot could slide through the lower
//! patch, which made most of those falls).
//! Counting has a cost fixed by its batches (`robustness.mfpt_batches`) and
//! no score; beyond about a fifth of its counted walker-steps its interval
//! opens above.
//!
//! **The score** (the splitting's levels, kept so that the walker can be
//! split) is the distance of the centre of mass's velocity from the
//! settled gait's at the same phase (every step starts a flat step after
//! it), in units of the gait's mean speed.

use crate::options::{MFPT_BATCHES_DEFAULT, Options, RobustnessOptions, TerrainOptions};
use crate::outcome::{FailureDetail, MeanFirstPassage};
use crate::plant::geometry::SPOKES;
use crate::plant::rtw::Rtw;
use crate::plant::slots::{DISSIPATED, FRICTION, N};
use crate::run::recorder::run_from;
use crate::run::settled::SettledGait;
use hybrid_ode::Work;
use hybrid_ode::metastable::{FallRate, MfptOptions, Rng, Walker, mfpt};
use std::cell::RefCell;

/// The estimator's settings for the RTW (besides the seed, `terrain.seed`,
/// and the batches, `robustness.mfpt_batches`): by default 6 batches of a
/// Fleming–Viot cloud; 16 walkers take 60 steps onto the
/// rough slope, and their 32 copies 60 more whose falls are counted
/// (11 520 walker-steps counted, 17 280 taken: what the paper scan's stable
/// gaits cost is measured by `scripts/mfpt_cost.sh`,
/// results/robustness/mfpt_cost.txt).
///
/// The burn-in is long because the fall rate still rises after 20 steps
/// (measured before the leak at a face's foot was closed,
/// docs/robustness-rough.md): at Fig. 7(a) and σ = 5 cm, counting steps 20–80 gave
/// `1/fall_rate` = 164, steps 100–200 gave 98 and 200–400 102, and the
/// MFPT from the start 174 against plain Monte Carlo's 132 [121, 144];
/// with 60 steps of burn-in it is 132. Half the walkers take it because
/// it was half the cost and the counted steps set the MFPT of every gait
/// that falls rarely: the burn-in's own Monte Carlo (the steps before the
/// first fall, the share still walking after it) weighs only where the
/// MFPT is tens of steps, and 96 walks still give it to a few steps.
pub const MFPT_SETTINGS: MfptOptions = MfptOptions {
    fall_rate: FallRate::Counting,
    seed: 0,
    batches: MFPT_BATCHES_DEFAULT as usize,
    burn_in: 60,
    sample_steps: 60,
    replicas: 32,
    burn_in_copies: 2,
    quantile: 0.5,
    max_excursion: 200,
    max_rounds: 60,
};

/// The walker's state at a step: the system (its contact modes and the
/// ground, with the patches it has reached), the state, and how long no tip
/// has touched down.
#[derive(Clone)]
pub(crate) struct State {
    pub(crate) rtw: Rtw,
    pub(crate) y: [f64; N],
    pub(crate) quiet: f64,
    /// The likelihood ratio of the ground it has laid ahead (1 but in the
    /// chain's sample, whose kept patch ahead is drawn from a wider law,
    /// `run/mfpt_chain.rs`).
    pub(crate) weight: f64,
    /// No step taken yet: the walker has reached no rough patch.
    fresh: bool,
}

/// The settled gait as a walker on the rough slope.
pub(crate) struct RtwWalker<'a, 'b> {
    pub(crate) s: &'a SettledGait<'b>,
    /// One step of the flat gait, never stopped early.
    pub(crate) options: Options,
    /// The centre of mass's velocity at the settled state.
    pub(crate) v_settled: [f64; 2],
    /// The flat gait's mean speed.
    pub(crate) speed: f64,
    pub(crate) work: RefCell<Work>,
}

/// The downhill positions of the six tips of `y`.
fn tips_downhill(rtw: &Rtw, y: &[f64; N]) -> impl Iterator<Item = f64> {
    let rods = rtw.rods(y);
    SPOKES
        .iter()
        .map(move |&(rod, tip)| rtw.body.tip_point(&rods[rod], tip).0[0])
}

/// The downhill position of the furthest tip of `y`.
pub(crate) fn furthest_tip(rtw: &Rtw, y: &[f64; N]) -> f64 {
    tips_downhill(rtw, y).fold(f64::NEG_INFINITY, f64::max)
}

/// The downhill position of the hindmost tip of `y`.
pub(crate) fn hindmost_tip(rtw: &Rtw, y: &[f64; N]) -> f64 {
    tips_downhill(rtw, y).fold(f64::INFINITY, f64::min)
}

/// The centre of mass's velocity (the rods are equal).
pub(crate) fn com_velocity(rtw: &Rtw, y: &[f64; N]) -> [f64; 2] {
    let rods = rtw.rods(y);
    let v = |k: usize| rods.iter().map(|r| r.v[k]).sum::<f64>() / 3.0;
    [v(0), v(1)]
}

impl RtwWalker<'_, '_> {
    /// One step from `st` after the patches beyond its reach are drawn
    /// afresh with `seed`, the first at `z` standard deviations unless `z`
    /// is NaN (then with `seed` too).
    pub(crate) fn step_branched(&self, st: &State, seed: u64, z: f64) -> Option<State> {
        let mut rtw = st.rtw.clone();
        // Before its first step the walker stands before the rough slope:
        // every patch is ahead of it.
        let reach = self.reach(st);
        if z.is_nan() {
            rtw.branch_terrain_beyond(reach, seed, &st.y);
        } else {
            rtw.branch_terrain_beyond_at(reach, seed, z, &st.y);
        }
        let (o, rtw, y) = run_from(
            self.s.params,
            &self.options,
            self.s.phys,
            rtw,
            st.y,
            self.s.flat.start,
            Work::default(),
            None,
        );
        *self.work.borrow_mut() += o.work;
        let failed = o.failure.is_some_and(|f| f != FailureDetail::NoProgress);
        let quiet = if o.touchdowns == 0 {
            st.quiet + o.t_end
        } else {
            0.0
        };
        (!failed && quiet < self.options.stall_time).then_some(State {
            rtw,
            y,
            quiet,
            weight: st.weight,
            fresh: false,
        })
    }

    /// Beyond where the ground is drawn afresh before a step from `st`: a
    /// rod length beyond its furthest tip (before its first step, all of
    /// the rough slope).
    pub(crate) fn reach(&self, st: &State) -> f64 {
        if st.fresh {
            f64::NEG_INFINITY
        } else {
            furthest_tip(&st.rtw, &st.y) + self.s.phys.length
        }
    }
}

impl Walker for RtwWalker<'_, '_> {
    type State = State;

    fn step(&self, st: &State, rng: &mut Rng) -> Option<State> {
        self.step_branched(st, rng.next_u64(), f64::NAN)
    }

    fn score(&self, st: &State) -> f64 {
        let v = com_velocity(&st.rtw, &st.y);
        (v[0] - self.v_settled[0]).hypot(v[1] - self.v_settled[1]) / self.speed
    }

    /// The stop flag every run reads at its step ends: a stopped step's run
    /// ends at once, but thousands of batches of them would still take
    /// minutes, so the estimator's loops read it too.
    fn stopped(&self) -> bool {
        crate::cancel::requested()
    }
}

/// The MFPT of the settled gait `s` on the rough slope of `r.sigma` with
/// `terrain`'s seed and patch length (see the module doc); `None` when the
/// computation's stop flag ([`crate::cancellable`]) ended it part way.
pub(crate) fn mean_first_passage(
    s: &SettledGait<'_>,
    r: &RobustnessOptions,
    terrain: TerrainOptions,
    work: &mut Work,
) -> Option<MeanFirstPassage> {
    let (walker, start) = walker(s, r, terrain);
    let m = mfpt(
        &walker,
        &start,
        &MfptOptions {
            seed: terrain.seed,
            batches: r.mfpt_batches as usize,
            ..MFPT_SETTINGS
        },
    );
    *work += walker.work.into_inner();
    let m = m?;
    Some(MeanFirstPassage {
        mfpt: m.mfpt,
        lo: m.lo,
        hi: m.hi,
        fall_rate: m.fall_rate,
        steps: m.steps,
    })
}

/// The settled gait `s` as a walker on the rough slope of `r.sigma`, and
/// its start (see the module doc).
pub(crate) fn walker<'a, 'b>(
    s: &'a SettledGait<'b>,
    r: &RobustnessOptions,
    terrain: TerrainOptions,
) -> (RtwWalker<'a, 'b>, State) {
    let walker = RtwWalker::new(s);
    let start = walker.start(r.sigma, terrain);
    (walker, start)
}

impl<'a, 'b> RtwWalker<'a, 'b> {
    /// The settled gait `s` as a walker: one step is a run of its flat
    /// gait's step time, never stopped early.
    pub(crate) fn new(s: &'a SettledGait<'b>) -> Self {
        RtwWalker {
            s,
            options: Options {
                t_max: 1.0 / s.flat.f_w_newfoot,
                stop_when_settled: false,
                ..s.options
            },
            v_settled: com_velocity(s.rtw, s.y),
            speed: if s.flat.speed > 0.0 {
                s.flat.speed
            } else {
                1.0
            },
            work: RefCell::new(Work::default()),
        }
    }

    /// The walker at the settled state, meeting the rough slope of `sigma`
    /// with `terrain`'s seed and patch length at the gait's edge.
    pub(crate) fn start(&self, sigma: f64, terrain: TerrainOptions) -> State {
        let s = self.s;
        let mut rtw = s.rtw.clone();
        rtw.set_terrain(
            TerrainOptions::rough(sigma, terrain.seed, s.edge, terrain.patch),
            s.y,
        );
        // The energy dissipated so far is the flat run's, not this one's.
        let mut y = *s.y;
        y[DISSIPATED] = 0.0;
        y[FRICTION] = 0.0;
        State {
            rtw,
            y,
            quiet: 0.0,
            weight: 1.0,
            fresh: true,
        }
    }
}
