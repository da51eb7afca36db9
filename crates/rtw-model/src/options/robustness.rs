//! Which robustness measures a stable run adds (docs/robustness.md), and
//! the bounds that keep their cost known before anything runs.

use super::terrain::STEP_HEIGHT_MAX;
use crate::params::{ParamError, check};
use serde::{Deserialize, Serialize};

/// Which robustness measures a stable run adds (the keys `robustness.*` of a
/// config's `[simulation]` table). All off by default; the Monte Carlo
/// settings are left out of a serialized config while at their defaults.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RobustnessOptions {
    /// Measure the largest survivable step down (`step_down_max`).
    pub step_down: bool,
    /// Measure the step down over every phase (`step_down_h50`): the height
    /// half of the edge positions over one step survive.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub step_down_h50: bool,
    /// A height (m) to meet a step down of at every phase of the gait, 0 for
    /// none: the share of the `step_down_h50` edge positions that survive it
    /// (`step_down_survival`) and the shares that fail by each kind (a point
    /// of the survival curve; docs/robustness.md).
    #[serde(skip_serializing_if = "is_zero")]
    pub step_down_at: f64,
    /// Compute the gait sensitivity norm (`gsn`, docs/robustness.md).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub gsn: bool,
    /// Measure the mean steps to fall on a rough slope (`steps_to_fall`,
    /// docs/robustness.md): Monte Carlo over seeded rough grounds.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub steps_to_fall: bool,
    /// The rough ground's roughness for `steps_to_fall` (m, the standard
    /// deviation of a patch's height; its patches are `terrain.patch` long
    /// and trial `i` has seed `terrain.seed + i`).
    #[serde(skip_serializing_if = "is_default_sigma")]
    pub sigma: f64,
    /// Monte Carlo trials (seeded grounds) per gait.
    #[serde(skip_serializing_if = "is_default_trials")]
    pub trials: u32,
    /// A trial that has not fallen after this many steps of the flat gait
    /// is censored there.
    #[serde(skip_serializing_if = "is_default_max_steps")]
    pub max_steps: u32,
    /// Estimate the mean first-passage time on the rough slope of
    /// roughness `sigma` (`mfpt`, `mfpt_lo`, `mfpt_hi`, `fall_rate`,
    /// docs/robustness.md): uncensored, from the falls of a Fleming–Viot
    /// cloud.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub mfpt: bool,
    /// Batches of the MFPT's cloud, each 2 880 steps of the walker of which
    /// 1 920 are counted: the cost, and how deep an MFPT its interval
    /// closes for (about a fifth of the counted steps; docs/robustness.md).
    #[serde(skip_serializing_if = "is_default_mfpt_batches")]
    pub mfpt_batches: u32,
    /// The MFPT's estimator (docs/robustness-rough.md): `"counted"` (the
    /// default, left out of a serialized config so that every config's
    /// hash stays what it was), `"chain"` (a Markov chain on a mesh of the
    /// extended states the walker reaches, `run/mfpt_chain.rs`) or
    /// `"splitting"` (adaptive multilevel splitting with a score learned
    /// at σ = 5 cm, `run/mfpt_splitting.rs`).
    #[serde(skip_serializing_if = "MfptMethod::is_counted")]
    pub mfpt_method: MfptMethod,
}

/// The MFPT's estimators (`robustness.mfpt_method`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MfptMethod {
    /// The falls of a Fleming–Viot cloud, counted (`run/mfpt.rs`): its cost
    /// grows with the MFPT.
    #[default]
    Counted,
    /// The Markov chain on k-means cells of the cloud's extended states
    /// (`run/mfpt_chain.rs`, `hybrid_ode::chain`): its cost does not.
    Chain,
    /// Adaptive multilevel splitting of the excursions from the
    /// quasi-stationary regime, with a learned score of the extended state
    /// (`run/mfpt_splitting.rs`, `hybrid_ode::splitting`): its cost grows as
    /// `log(MFPT)`.
    Splitting,
}

impl MfptMethod {
    fn is_counted(&self) -> bool {
        *self == MfptMethod::Counted
    }
}

/// The default roughness of `steps_to_fall` (m).
pub(crate) const SIGMA_DEFAULT: f64 = 0.01;
const TRIALS_DEFAULT: u32 = 20;
const MAX_STEPS_DEFAULT: u32 = 100;
/// The MFPT's batches by default (`MFPT_SETTINGS`, run/mfpt.rs).
pub(crate) const MFPT_BATCHES_DEFAULT: u32 = 6;
/// Most batches of the MFPT: 3 000 take 8.6 × 10⁶ steps of the walker, the
/// same bound of a sample's cost as the Monte Carlo's 10⁷.
const MFPT_BATCHES_MAX: u32 = 3000;
/// Most steps of the flat gait the rough-slope trials of one sample may
/// take together (`trials × max_steps`).
const MAX_TRIAL_STEPS: f64 = 1e7;

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

fn is_default_sigma(v: &f64) -> bool {
    *v == SIGMA_DEFAULT
}

fn is_default_trials(v: &u32) -> bool {
    *v == TRIALS_DEFAULT
}

fn is_default_max_steps(v: &u32) -> bool {
    *v == MAX_STEPS_DEFAULT
}

fn is_default_mfpt_batches(v: &u32) -> bool {
    *v == MFPT_BATCHES_DEFAULT
}

impl Default for RobustnessOptions {
    fn default() -> Self {
        Self {
            step_down: false,
            step_down_h50: false,
            step_down_at: 0.0,
            gsn: false,
            steps_to_fall: false,
            sigma: SIGMA_DEFAULT,
            trials: TRIALS_DEFAULT,
            max_steps: MAX_STEPS_DEFAULT,
            mfpt: false,
            mfpt_batches: MFPT_BATCHES_DEFAULT,
            mfpt_method: MfptMethod::Counted,
        }
    }
}

impl RobustnessOptions {
    /// Is every measure off?
    pub(crate) fn is_off(&self) -> bool {
        !self.step_down
            && !self.step_down_h50
            && self.step_down_at == 0.0
            && !self.gsn
            && !self.steps_to_fall
            && !self.mfpt
    }

    /// Refuses a step-down height outside [0, 1000] m, a roughness outside
    /// [0, 1000] m (or 0 with `mfpt`: on the
    /// flat slope the walker never falls), fewer than 2 or more than
    /// 100000 trials, a censoring step count outside [1, 1000000], more
    /// than 10⁷ steps in all (`trials × max_steps`), or MFPT batches outside
    /// [2, 3000].
    pub fn validate(&self) -> Result<(), ParamError> {
        check(
            "robustness.step_down_at",
            self.step_down_at,
            "in [0, 1000] (m, the height of the step down; 0 for none)",
            |v| (0.0..=STEP_HEIGHT_MAX).contains(&v),
        )?;
        if self.mfpt {
            check(
                "robustness.sigma",
                self.sigma,
                "in (0, 1000] with robustness.mfpt (m, standard deviation of a patch's height)",
                |v| v > 0.0 && v <= STEP_HEIGHT_MAX,
            )?;
        }
        check(
            "robustness.sigma",
            self.sigma,
            "in [0, 1000] (m, standard deviation of a patch's height)",
            |v| (0.0..=STEP_HEIGHT_MAX).contains(&v),
        )?;
        check(
            "robustness.trials",
            f64::from(self.trials),
            "in [2, 100000]",
            |v| (2.0..=1e5).contains(&v),
        )?;
        check(
            "robustness.mfpt_batches",
            f64::from(self.mfpt_batches),
            "in [2, 3000] (batches of the MFPT's cloud, 2880 steps of the walker each)",
            |v| (2.0..=f64::from(MFPT_BATCHES_MAX)).contains(&v),
        )?;
        check(
            "robustness.max_steps",
            f64::from(self.max_steps),
            "in [1, 1000000] (steps of the flat gait)",
            |v| (1.0..=1e6).contains(&v),
        )?;
        // Each in range, the two together can still ask for 10¹¹ steps a
        // sample: the Monte Carlo's cost, bounded before anything runs.
        check(
            "robustness.trials × robustness.max_steps",
            f64::from(self.trials) * f64::from(self.max_steps),
            "at most 10000000 (steps simulated a sample: 15 to 50 minutes of one core at 90 to \
             290 µs a step; split a larger study over several scans of other terrain.seed)",
            |v| v <= MAX_TRIAL_STEPS,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde::de::value::{Error, MapDeserializer};

    /// The options a config's `robustness` table of `pairs` gives.
    fn from(pairs: &[(&'static str, &'static str)]) -> Result<RobustnessOptions, Error> {
        RobustnessOptions::deserialize(MapDeserializer::new(pairs.iter().copied()))
    }

    #[test]
    fn the_mfpt_method_is_counted_by_default_and_chain_on_request() {
        assert_eq!(from(&[]).unwrap().mfpt_method, MfptMethod::Counted);
        assert_eq!(
            RobustnessOptions::default().mfpt_method,
            MfptMethod::Counted
        );
        for (text, method) in [
            ("counted", MfptMethod::Counted),
            ("chain", MfptMethod::Chain),
        ] {
            let r = from(&[("mfpt_method", text)]).unwrap();
            assert_eq!(r.mfpt_method, method);
            assert_eq!(
                RobustnessOptions {
                    mfpt_method: MfptMethod::Counted,
                    ..r
                },
                RobustnessOptions::default()
            );
        }
        // The default is left out of a serialized config (every config hash
        // stays what it was), another method is not.
        assert!(MfptMethod::Counted.is_counted());
        assert!(!MfptMethod::Chain.is_counted());
    }

    #[test]
    fn an_unknown_mfpt_method_is_refused_naming_the_valid_ones() {
        let e = from(&[("mfpt_method", "sampled")]).unwrap_err().to_string();
        assert!(e.contains("sampled"), "{e}");
        for valid in ["counted", "chain", "splitting"] {
            assert!(e.contains(valid), "{e}");
        }
        let r = from(&[("mfpt_method", "splitting")]).unwrap();
        assert_eq!(r.mfpt_method, MfptMethod::Splitting);
    }
}
