//! The settled gait of a stable flat run: the state every robustness
//! measure starts from (the step down, steps to fall, the mean first-passage
//! time), and the run from it on other ground. Its own file so that each
//! measure imports it without importing the others.

use crate::options::{Options, RobustnessOptions, TerrainOptions};
use crate::outcome::Outcome;
use crate::params::{Params, Physical};
use crate::plant::rtw::Rtw;
use crate::plant::slots::{DISSIPATED, FRICTION, N};
use crate::run::gait::steps_to_time;
use crate::run::recorder::run_from;
use hybrid_ode::Work;

/// The step's edge lies this many rod lengths ahead of the front-most
/// grounded tip of the settled gait: the next foot lands beyond it, and far
/// from the riser.
pub const EDGE_AHEAD: f64 = 0.05;
/// A step down is survived when, this many steps of the flat gait (at its
/// new-foot rate `f_w_newfoot`) after the settled state, the run has not failed
/// and the second half of them has the flat gait's label.
pub const SURVIVAL_STEPS: f64 = 20.0;

/// The settled gait of a stable flat run, ready to meet a step.
pub(crate) struct SettledGait<'a> {
    pub(super) params: &'a Params,
    pub(super) options: Options,
    pub(super) phys: &'a Physical,
    pub(super) rtw: &'a Rtw,
    pub(super) y: &'a [f64; N],
    pub(super) flat: &'a Outcome,
    /// Where the ground ahead of the gait starts (m): a step's edge, or the
    /// first rough patch.
    pub(super) edge: f64,
    /// The front-most grounded tip's `x` (m).
    pub(super) front: f64,
}

impl SettledGait<'_> {
    /// The run from the settled state on `terrain` under `options`.
    pub(super) fn run_on(
        &self,
        terrain: TerrainOptions,
        options: &Options,
        work: &mut Work,
    ) -> Outcome {
        let mut sys = self.rtw.clone();
        sys.set_terrain(terrain, self.y);
        // The energy dissipated so far is the flat run's, not this one's.
        let mut y = *self.y;
        y[DISSIPATED] = 0.0;
        y[FRICTION] = 0.0;
        let (o, _, _) = run_from(
            self.params,
            options,
            self.phys,
            sys,
            y,
            self.flat.start,
            Work::default(),
            None,
        );
        *work += o.work;
        o
    }
}

/// The settled state of a flat run that ended in `rtw`, `y` with outcome
/// `flat`.
pub(crate) fn settled<'a>(
    params: &'a Params,
    options: &Options,
    phys: &'a Physical,
    rtw: &'a Rtw,
    y: &'a [f64; N],
    flat: &'a Outcome,
) -> SettledGait<'a> {
    // Every stable gait has a foot down at a touchdown; a run that ended
    // mid-flight (no early stop) measures from its centre of mass instead.
    let front = rtw
        .front_foot(y)
        .map_or_else(|| rtw.centre_of_mass(y)[0], |(_, x)| x);
    let mut options = *options;
    options.limit_cycle = false;
    options.robustness = RobustnessOptions::default();
    // Judged over `SURVIVAL_STEPS` steps of the flat gait after the edge,
    // the label over their second half; at most the run's own `t_max`.
    options.t_max = steps_to_time(SURVIVAL_STEPS, flat, options.t_max).min(options.t_max);
    options.analysis_window = 0.5;
    SettledGait {
        params,
        options,
        phys,
        rtw,
        y,
        flat,
        edge: front + EDGE_AHEAD * phys.length,
        front,
    }
}
