//! Every modelling and numerical choice of docs/model.md, as options.
//!
//! Two named sets of modelling choices (docs/model.md §9):
//!
//! * [`Options::default`], **the adopted model**
//!   (`prestress-0.8875-settled-mu0.8-slack-steps`): strings with natural length
//!   ℓ₀ = 0.8875 r that go slack rather than push, Coulomb friction μ = 0.8, a
//!   start set down and settled on the slope (on two or three feet; a star
//!   that cannot stand still fails, the article's "cannot maintain standing
//!   position"), and gaits labelled by their typical step. It was chosen by
//!   the variant study (`./scripts/variants.sh` →
//!   `results/variants/summary.md`): of the variants that walk at the
//!   article's Fig. 7(a) point on a floor a real robot can have (μ ≤ 1),
//!   show both failure clusters of Fig. S4, step at a median rate within
//!   0.8–1.25 f_n over Fig. S2's stable gaits and match the article's
//!   stable, skip and walk shares within both sampling errors over five
//!   seeds, it is among those closest to the article's statistic (ties
//!   within the seeds' error) the one whose strings cannot push and whose
//!   Fig. S2 rate is nearest f_n. The natural length is fitted to those
//!   figures, not published; `crates/rtw-scan-test/tests/it/default_variant.rs`
//!   fails when this default and the study's pick differ.
//! * [`Options::literal`]: docs/model.md §1–§6 as first written, the supplementary's
//!   S5–S6 taken literally (zero rest length, no slip, a rigid start, any
//!   flight makes a skip). It is the paper-faithful reconstruction; it skips
//!   where the article walks.
//!
//! Everything else (integrator, thresholds of §5) is the same in both.
//!
//! The field names are the keys of a scan config's `[simulation]` table
//! (`initial.omega`, `strings.slack`, `contact.mu`, …); unknown keys are refused.

use crate::params::{Normalization, ParamError, check};
use hybrid_ode::EngineOptions;
/// The integration method, as chosen in a config (`"dp54"`, `"dop853"`,
/// `"rk4"`): the engine's own [`hybrid_ode::Method`].
#[doc(no_inline)]
pub use hybrid_ode::Method;
use serde::{Deserialize, Serialize};

mod robustness;
mod seed;
mod terrain;
pub(crate) use robustness::MFPT_BATCHES_DEFAULT;
pub use robustness::{MfptMethod, RobustnessOptions};
pub use terrain::TerrainOptions;
pub(crate) use terrain::{Face, Over};

/// The initial shape of the star (docs/model.md §6).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum InitialShape {
    /// The rest shape, a regular six-spoked star, on two feet.
    RigidStar,
    /// The static equilibrium standing on the same two feet: front foot
    /// pinned, rear foot frictionless, rod b free (Newton). A star that
    /// would need a third foot has none: `no_standing_equilibrium`.
    Static,
    /// Set down and let settle: the rest star placed at rest on its two
    /// feet, then relaxed to a static equilibrium under gravity with the
    /// run's own contact law (friction, slip, a third foot landing), as a
    /// robot is stood on the slope by hand before the push. A star that
    /// cannot stand falls while settling (a rod lies down, the centre of
    /// mass sinks) or never comes to rest: a `collapse` that says which.
    #[default]
    Settled,
}

/// What a `settled` start does with a star that cannot stand still: set
/// down, it rolls or slides away along the slope while keeping its shape.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CannotStand {
    /// A failure, `collapse` (`standing_rolls_away`): the article's "cannot
    /// maintain standing position" (Fig. S4), read literally.
    #[default]
    Collapse,
    /// Pushed as it is set down, from its rest shape (as `rigid_star`).
    Push,
}

/// How the string damper acts (docs/model.md §9, `strings.damping`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Damping {
    /// Kelvin–Voigt along the string: tension `c ℓ̇` (S6).
    #[default]
    Along,
    /// Isotropic: force `−c (Ṗ − Q̇)` on end P.
    Relative,
}

/// How the star starts (docs/model.md §6), as config keys `initial.*`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct InitialOptions {
    /// How it stands before the push.
    pub shape: InitialShape,
    /// `settled` only: a star that rolls away as it is set down.
    pub cannot_stand: CannotStand,
    /// Rigid angular velocity about the front foot [rad/s]; negative rolls downhill.
    pub omega: f64,
}

impl Default for InitialOptions {
    /// The adopted model's start: set down and settled on the slope (a star
    /// that cannot stand still fails), pushed downhill.
    fn default() -> Self {
        Self {
            shape: InitialShape::Settled,
            cannot_stand: CannotStand::Collapse,
            omega: -2.0,
        }
    }
}

/// The strings' law (docs/model.md §3, §9), as config keys `strings.*`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct StringOptions {
    /// Natural length as a fraction `s` of the rest hexagon's side r: ℓ₀ = s r.
    pub rest_length_ratio: f64,
    /// A slack string cannot push: tension max(0, T).
    pub slack: bool,
    /// How the damper acts.
    pub damping: Damping,
}

impl Default for StringOptions {
    /// The adopted model's strings: natural length 0.8875 r (fitted,
    /// docs/model.md §9), slack when short.
    fn default() -> Self {
        Self {
            rest_length_ratio: 0.8875,
            slack: true,
            damping: Damping::Along,
        }
    }
}

/// The ground contact (docs/model.md §4), as config keys `contact.*`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ContactOptions {
    /// Coulomb friction coefficient; `inf` = no slip (frictionless slide fallback).
    pub mu: f64,
}

impl Default for ContactOptions {
    /// The adopted model's floor: Coulomb friction μ = 0.8 (rubber on
    /// concrete or wood is about 0.6–1).
    fn default() -> Self {
        Self { mu: 0.8 }
    }
}

/// How a stable gait is labelled (docs/model.md §5, Table S1's row for the RTW:
/// skipping has flight, crawling has triple support, walking neither), as
/// config keys `labels.*`. A *step* is the time from one touchdown to the
/// next; the per-step shares count the window's whole steps.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct LabelOptions {
    /// A gait has flight when its NLSP fraction over the window exceeds this;
    /// a step has flight when its own NLSP fraction does.
    pub flight: f64,
    /// The same for triple support (TLSP).
    pub triple: f64,
    /// A skip also needs at least this share of its steps to have flight
    /// (0: any flight over the window makes a skip).
    pub flight_steps: f64,
    /// A crawl also needs at least this share of its steps to have triple
    /// support (0: any).
    pub triple_steps: f64,
}

impl Default for LabelOptions {
    /// The adopted rule: a gait is labelled by its typical step. Table S1
    /// names each gait by the contact states of its step cycle, so a gait
    /// skips when at least half of its steps have flight (over 1 % of the
    /// step), and crawls when at least half have triple support. On the
    /// paper scan, the skips' shares of steps with flight are bimodal (most
    /// fly in every step); the rule separates those from walks with an
    /// occasional hop (`results/fidelity.md`).
    fn default() -> Self {
        Self {
            flight: 0.01,
            triple: 0.01,
            flight_steps: 0.5,
            triple_steps: 0.5,
        }
    }
}

impl LabelOptions {
    /// docs/model.md §5 as written: any flight (then any triple support) above
    /// 1 % of the window makes the label.
    pub(crate) fn any() -> Self {
        Self {
            flight_steps: 0.0,
            triple_steps: 0.0,
            ..Self::default()
        }
    }

    /// Checks every threshold, naming its key and range.
    pub(crate) fn validate(&self) -> Result<(), ParamError> {
        check("labels.flight", self.flight, "in [0, 1)", |v| {
            (0.0..1.0).contains(&v)
        })?;
        check("labels.triple", self.triple, "in [0, 1)", |v| {
            (0.0..1.0).contains(&v)
        })?;
        check("labels.flight_steps", self.flight_steps, "in [0, 1]", |v| {
            (0.0..=1.0).contains(&v)
        })?;
        check("labels.triple_steps", self.triple_steps, "in [0, 1]", |v| {
            (0.0..=1.0).contains(&v)
        })
    }
}

/// All simulation options (docs/model.md §4–§6, §9). The default is the adopted
/// model, [`Options::literal`] the paper-faithful one (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Options {
    /// Simulated time (s).
    pub t_max: f64,
    /// Integration method. The default, DP5(4) at rtol 1e-4, was chosen by
    /// the work–precision benchmark (`cargo run --release -p rtw-bench`)
    /// when the strings' natural length was s = 0.85: the cheapest setting
    /// whose scan outcome fractions stayed within 1 pp of DOP853 at rtol
    /// 1e-13 and whose f_w erred by < 1 %, with no step cap (a cap of 0.01 s
    /// cost 23 % more right-hand-side evaluations and gained no accuracy).
    /// At today's default model the same rule picks DOP853 at 1e-6, and
    /// DP5(4) at 1e-4 is 2.0 pp off (results/bench/work-precision.md): the
    /// choice is open (docs/performance.md), and changing it changes every
    /// committed result. DOP853 is the benchmark's reference; RK4 takes
    /// fixed steps `rk4_step`.
    pub method: Method,
    /// Relative tolerance of the adaptive methods.
    pub rtol: f64,
    /// Absolute tolerance of the adaptive methods.
    pub atol: f64,
    /// Fixed step of RK4 (s).
    pub rk4_step: f64,
    /// Largest adaptive step (s); `inf` (the default): none, the tolerance
    /// alone sets the step. Event detection needs no cap: a guard that
    /// crosses and comes back inside a step is found too (each guard's cubic
    /// model on the step tells where its dense output must be sampled).
    pub h_max: f64,
    /// Work budget (accepted + rejected steps) before `diverged`.
    pub max_steps: u64,
    /// Gravity [m/s²].
    pub g: f64,
    /// How (f_n, ζ) map to (k, c).
    pub normalization: Normalization,
    /// The analysis window is the last `analysis_window` fraction of the run.
    pub analysis_window: f64,
    /// Collapse when the centre of mass falls below this × h₀.
    pub collapse_height_ratio: f64,
    /// Stall when no touchdown happens for this long (s).
    pub stall_time: f64,
    /// Touchdown is declared at tip height −touchdown_offset·L (guard against
    /// re-triggering a touchdown at a tip released at y = 0); in (0, 1e-6].
    pub touchdown_offset: f64,
    /// Sample the trajectory every `trace_dt` seconds when recording (0: every step).
    pub trace_dt: f64,
    /// End a run once its gait has settled: the latest
    /// 36 (`SETTLE_RETURNS`) touchdown returns
    /// repeat with a period (the test of `period`). Its statistics are then
    /// taken over a whole number of periods ending there instead of over the
    /// last `analysis_window` of `t_max`. On by default: it saves about
    /// 9 % of the RHS evaluations (most of a scan's work is in chaotic
    /// gaits) and, at the benchmark's setting, moves the paper scan's shares
    /// by at most 0.7 pp (results/bench/work-precision.md, "Early stop").
    /// A chaotic gait never settles and runs to `t_max`.
    pub stop_when_settled: bool,
    /// After a stable run, find its gait's limit cycle on the step map
    /// ([`crate::cycles::StepMap`]): the period from the map and the largest Floquet
    /// multiplier ([`Outcome::cycle`](crate::Outcome::cycle)). Costs a Newton
    /// solve with variational Jacobians at tight tolerance per periodic run.
    pub limit_cycle: bool,
    /// The start.
    pub initial: InitialOptions,
    /// The strings.
    pub strings: StringOptions,
    /// The ground contact.
    pub contact: ContactOptions,
    /// The gait labels' thresholds.
    pub labels: LabelOptions,
    /// The ground (`terrain.*`, [`TerrainOptions`]): the flat slope unless a
    /// step is set. Left out of a serialized config while it is the default
    /// flat slope, so such a config's text and hash are those it had before
    /// terrain existed; a flat slope with another seed or patch is written,
    /// because the robustness measures' rough slope is drawn from them.
    #[serde(skip_serializing_if = "TerrainOptions::is_default_flat")]
    pub terrain: TerrainOptions,
    /// The robustness measures a stable run adds (`robustness.*`,
    /// [`RobustnessOptions`]); all off by default, and then left out of a
    /// serialized config.
    #[serde(skip_serializing_if = "RobustnessOptions::is_off")]
    pub robustness: RobustnessOptions,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            t_max: 20.0,
            method: Method::Dp54,
            rtol: 1e-4,
            atol: 1e-6,
            rk4_step: 1e-4,
            h_max: f64::INFINITY,
            max_steps: 5_000_000,
            g: 9.81,
            normalization: Normalization::Supplementary,
            analysis_window: 0.5,
            collapse_height_ratio: 0.5,
            stall_time: 3.0,
            touchdown_offset: 1e-10,
            trace_dt: 0.0,
            stop_when_settled: true,
            limit_cycle: false,
            initial: InitialOptions::default(),
            strings: StringOptions::default(),
            contact: ContactOptions::default(),
            labels: LabelOptions::default(),
            terrain: TerrainOptions::default(),
            robustness: RobustnessOptions::default(),
        }
    }
}

/// Largest finite friction coefficient accepted: above 4/3 a uniform rod can
/// meet the Painlevé paradox (docs/model.md §4).
pub(crate) const MU_MAX_FINITE: f64 = 4.0 / 3.0;

impl Options {
    /// The supplementary taken literally (docs/model.md §9: the
    /// paper-faithful reconstruction, variant `literal`): zero-rest-length strings, no slip (μ = ∞, frictionless
    /// slide fallback), a rigid star started at ω = −2 rad/s.
    pub fn literal() -> Self {
        Self {
            initial: InitialOptions {
                shape: InitialShape::RigidStar,
                omega: -2.0,
                ..InitialOptions::default()
            },
            strings: StringOptions {
                rest_length_ratio: 0.0,
                slack: false,
                damping: Damping::Along,
            },
            contact: ContactOptions { mu: f64::INFINITY },
            labels: LabelOptions::any(),
            ..Self::default()
        }
    }

    /// The hybrid engine's settings for a run with these options.
    pub(crate) fn engine(&self) -> EngineOptions {
        EngineOptions {
            method: self.method,
            rk4_step: self.rk4_step,
            rtol: self.rtol,
            atol: self.atol,
            h_max: self.h_max,
            max_steps: self.max_steps,
            ..EngineOptions::default()
        }
    }

    /// Checks every option, naming the offending key and its valid range.
    pub fn validate(&self) -> Result<(), ParamError> {
        check("t_max", self.t_max, "finite and > 0 (s)", |v| v > 0.0)?;
        // Without a step cap the tolerances alone bound the step: the
        // Fig. 7(a) walk stays a walk up to rtol 0.4, atol 0.1 and an RK4 step
        // of 0.2 s (rtol 0.5 underflows its step, an RK4 step of 0.5 s
        // stalls): tests/option_ranges.rs. Above atol 0.1 the tips chatter
        // (f_w 11 Hz at 0.2, 967 Hz at 0.5, against 4 Hz) and at atol 1 the
        // star collapses. The ranges stop at round values inside those.
        check("rtol", self.rtol, "in (0, 0.1]", |v| v > 0.0 && v <= 0.1)?;
        check("atol", self.atol, "in (0, 0.1]", |v| v > 0.0 && v <= 0.1)?;
        check("rk4_step", self.rk4_step, "in (0, 0.1] (s)", |v| {
            v > 0.0 && v <= 0.1
        })?;
        if self.h_max.is_nan() || self.h_max <= 0.0 {
            return Err(ParamError::new(
                "h_max",
                self.h_max,
                "> 0 (s), or inf for no cap",
            ));
        }
        check("max_steps", self.max_steps as f64, ">= 1", |v| v >= 1.0)?;
        // Each lower or upper end below is the last value at which the
        // Fig. 7(a) walk is still judged a walk (or, for g and initial.omega,
        // still gives a physical outcome): tests/option_ranges.rs. Below g =
        // 0.1 the standing equilibrium is not found (its tolerance scales
        // with g); at g = f64::MAX the start overflows, so g stops at 1000
        // (100 Earth gravities); a window under 10 % of t_max holds too few returns to
        // judge a gait; a stall time under 1 s is shorter than a step; a
        // collapse height above 0.75 h₀ is reached by a walking gait; at
        // |ω₀| ≫ 50 rad/s the state overflows.
        check("g", self.g, "in [0.1, 1000] (m/s^2)", |v| {
            (0.1..=1000.0).contains(&v)
        })?;
        check(
            "analysis_window",
            self.analysis_window,
            "in [0.1, 1]",
            |v| (0.1..=1.0).contains(&v),
        )?;
        self.labels.validate()?;
        check(
            "collapse_height_ratio",
            self.collapse_height_ratio,
            "in [0, 0.75]",
            |v| (0.0..=0.75).contains(&v),
        )?;
        check("stall_time", self.stall_time, "finite and >= 1 (s)", |v| {
            v >= 1.0
        })?;
        // Not 0: a tip released on the ground starts its touchdown guard at
        // exactly 0, which event location does not count as a crossing, so
        // its next touchdown would be missed (the walk falls through the floor).
        check(
            "touchdown_offset",
            self.touchdown_offset,
            "in (0, 1e-6]",
            |v| v > 0.0 && v <= 1e-6,
        )?;
        check("trace_dt", self.trace_dt, "finite and >= 0 (s)", |v| {
            v >= 0.0
        })?;
        check(
            "initial.omega",
            self.initial.omega,
            "in [-50, 50] (rad/s)",
            |v| v.abs() <= 50.0,
        )?;
        check(
            "strings.rest_length_ratio",
            self.strings.rest_length_ratio,
            "in [0, 1)",
            |v| (0.0..1.0).contains(&v),
        )?;
        self.terrain.validate()?;
        self.robustness.validate()?;
        let mu = self.contact.mu;
        if !(mu == f64::INFINITY || (mu.is_finite() && (0.0..=MU_MAX_FINITE).contains(&mu))) {
            return Err(ParamError::new(
                "contact.mu",
                mu,
                "inf (no slip) or in [0, 4/3] (Painlevé-free Coulomb friction)",
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn literal_is_model_md_and_default_differs_only_in_the_adopted_choices() {
        let o = Options::literal();
        o.validate().unwrap();
        assert_eq!(o.t_max, 20.0);
        assert_eq!(o.initial.omega, -2.0);
        assert_eq!(o.initial.shape, InitialShape::RigidStar);
        assert_eq!(o.collapse_height_ratio, 0.5);
        assert_eq!(o.stall_time, 3.0);
        assert_eq!(o.labels, LabelOptions::any());
        assert_eq!((o.labels.flight, o.labels.triple), (0.01, 0.01));
        assert_eq!((o.labels.flight_steps, o.labels.triple_steps), (0.0, 0.0));
        assert!(o.contact.mu.is_infinite());
        assert_eq!(o.strings.rest_length_ratio, 0.0);
        assert!(!o.strings.slack);
        assert!(o.stop_when_settled);
        assert_eq!(o.strings.damping, Damping::Along);
        assert_eq!(o.normalization, Normalization::Supplementary);
        let d = Options::default();
        d.validate().unwrap();
        let adopted = Options {
            initial: InitialOptions {
                shape: InitialShape::Settled,
                cannot_stand: CannotStand::Collapse,
                omega: -2.0,
            },
            strings: StringOptions {
                rest_length_ratio: 0.8875,
                slack: true,
                damping: Damping::Along,
            },
            contact: ContactOptions { mu: 0.8 },
            labels: LabelOptions {
                flight_steps: 0.5,
                triple_steps: 0.5,
                ..o.labels
            },
            ..o
        };
        assert_eq!(d, adopted);
    }

    #[test]
    fn the_rough_slope_trials_cost_is_bounded_up_front() {
        let mut o = Options::default();
        o.robustness.trials = 100_000;
        o.robustness.max_steps = 1_000_000;
        let e = o.validate().unwrap_err();
        assert_eq!(e.field, "robustness.trials × robustness.max_steps");
        assert!(e.to_string().contains("at most 10000000"), "{e}");
        // At the bound, accepted.
        o.robustness.max_steps = 100;
        o.validate().unwrap();
    }

    #[test]
    fn bad_options_name_the_key() {
        let mut o = Options::default();
        o.contact.mu = 2.0;
        assert_eq!(o.validate().unwrap_err().field, "contact.mu");
        let mut o = Options::default();
        o.strings.rest_length_ratio = 1.0;
        assert_eq!(o.validate().unwrap_err().field, "strings.rest_length_ratio");
        let o = Options {
            rtol: f64::NAN,
            ..Options::default()
        };
        assert_eq!(o.validate().unwrap_err().field, "rtol");
    }

    #[test]
    fn mfpt_on_the_flat_slope_is_refused_naming_the_roughness() {
        let mut r = RobustnessOptions {
            mfpt: true,
            sigma: 0.0,
            ..RobustnessOptions::default()
        };
        let e = r.validate().unwrap_err();
        assert_eq!(e.field, "robustness.sigma");
        assert!(e.to_string().contains("robustness.mfpt"), "{e}");
        r.sigma = 0.01;
        r.validate().unwrap();
        r.mfpt = false;
        r.sigma = 0.0;
        r.validate().unwrap();
    }

    #[test]
    fn the_mfpt_s_batches_are_bounded_and_named() {
        let mut r = RobustnessOptions {
            mfpt: true,
            ..RobustnessOptions::default()
        };
        assert_eq!(r.mfpt_batches, 6);
        for bad in [0, 1, 3001, u32::MAX] {
            r.mfpt_batches = bad;
            let e = r.validate().unwrap_err();
            assert_eq!(e.field, "robustness.mfpt_batches");
            assert!(e.to_string().contains("[2, 3000]"), "{e}");
        }
        for good in [2, 3000] {
            r.mfpt_batches = good;
            r.validate().unwrap();
        }
    }
}
