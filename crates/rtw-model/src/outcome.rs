//! What one run produces: the gait label and every metric of docs/model.md §5,
//! and the rule that labels a gait (Table S1).

use crate::options::LabelOptions;
use serde::{Deserialize, Serialize};

/// Longest gait period (in steps) the model looks for, on the touchdown
/// return map and on the step map.
pub(crate) const MAX_PERIOD: usize = 12;

/// The outcome label of a run (docs/model.md §5).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Label {
    /// Stable gait with flight (NLSP + SLSP).
    Skip,
    /// Stable gait with single and double support only (SLSP + DLSP).
    Walk,
    /// Stable gait with triple support (SLSP + DLSP + TLSP).
    Crawl,
    /// Stiffness collapse: a rod lies down or the centre of mass sinks.
    Collapse,
    /// Energy barrier: the star stops rolling.
    Stall,
    /// Numerical failure; a defect, never a physical outcome.
    Diverged,
}

impl Label {
    /// Every label.
    pub const ALL: [Label; 6] = [
        Label::Skip,
        Label::Walk,
        Label::Crawl,
        Label::Collapse,
        Label::Stall,
        Label::Diverged,
    ];

    /// The label's name (`skip`, `walk`, …); also its `Display`.
    pub fn as_str(self) -> &'static str {
        match self {
            Label::Skip => "skip",
            Label::Walk => "walk",
            Label::Crawl => "crawl",
            Label::Collapse => "collapse",
            Label::Stall => "stall",
            Label::Diverged => "diverged",
        }
    }

    /// A stable gait (skip, walk or crawl).
    pub fn is_stable(self) -> bool {
        matches!(self, Label::Skip | Label::Walk | Label::Crawl)
    }

    /// A physical failure (collapse or stall); `diverged` is neither.
    pub fn is_failure(self) -> bool {
        matches!(self, Label::Collapse | Label::Stall)
    }
}

impl std::fmt::Display for Label {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

impl std::str::FromStr for Label {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Label::ALL
            .into_iter()
            .find(|l| l.as_str() == s)
            .ok_or_else(|| format!("unknown outcome label {s:?}"))
    }
}

/// Why a failed run failed, in more detail than its label.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FailureDetail {
    /// A rod would have both tips on the ground.
    RodDown,
    /// The centre of mass fell below `collapse_height_ratio × h₀`.
    CentreOfMassLow,
    /// No standing equilibrium: `initial.shape = "static"` found none on two
    /// feet, or a star being set down (`"settled"`) never came to rest.
    NoStandingEquilibrium,
    /// A star being set down (`initial.shape = "settled"`) fell until a rod
    /// had both tips on the ground.
    StandingRodDown,
    /// A star being set down sank until its centre of mass was below
    /// `collapse_height_ratio × h₀`.
    StandingComLow,
    /// A star being set down rolled or slid away along the slope: it keeps
    /// its shape but has no static equilibrium there
    /// (`initial.cannot_stand = "collapse"`).
    StandingRollsAway,
    /// A tip met the riser of a step. No longer produced: a tip meeting a
    /// face of the ground is a contact (docs/model.md §4, "Faces"); the
    /// name stays so that older result files read.
    Riser,
    /// No touchdown for `stall_time`.
    NoTouchdown,
    /// The centre of mass moved less than L/2 downhill over the window.
    NoProgress,
    /// A state became NaN or infinite.
    NonFinite,
    /// The step size underflowed.
    StepUnderflow,
    /// The work budget (`max_steps`) ran out.
    WorkBudget,
    /// Many transitions in a microsecond (Zeno).
    Zeno,
}

impl FailureDetail {
    /// Every failure detail.
    pub const ALL: [FailureDetail; 13] = [
        FailureDetail::RodDown,
        FailureDetail::CentreOfMassLow,
        FailureDetail::NoStandingEquilibrium,
        FailureDetail::StandingRodDown,
        FailureDetail::StandingComLow,
        FailureDetail::StandingRollsAway,
        FailureDetail::Riser,
        FailureDetail::NoTouchdown,
        FailureDetail::NoProgress,
        FailureDetail::NonFinite,
        FailureDetail::StepUnderflow,
        FailureDetail::WorkBudget,
        FailureDetail::Zeno,
    ];

    /// The outcome label of a run that failed this way (docs/model.md §5):
    /// collapse, stall, or diverged for a numerical failure.
    pub fn label(self) -> Label {
        match self {
            FailureDetail::RodDown
            | FailureDetail::CentreOfMassLow
            | FailureDetail::NoStandingEquilibrium
            | FailureDetail::StandingRodDown
            | FailureDetail::StandingComLow
            | FailureDetail::StandingRollsAway
            | FailureDetail::Riser => Label::Collapse,
            FailureDetail::NoTouchdown | FailureDetail::NoProgress => Label::Stall,
            FailureDetail::NonFinite
            | FailureDetail::StepUnderflow
            | FailureDetail::WorkBudget
            | FailureDetail::Zeno => Label::Diverged,
        }
    }

    /// The detail's name (`rod_down`, `com_low`, …); also its `Display`.
    pub fn as_str(self) -> &'static str {
        match self {
            FailureDetail::RodDown => "rod_down",
            FailureDetail::CentreOfMassLow => "com_low",
            FailureDetail::NoStandingEquilibrium => "no_standing_equilibrium",
            FailureDetail::StandingRodDown => "standing_rod_down",
            FailureDetail::StandingComLow => "standing_com_low",
            FailureDetail::StandingRollsAway => "standing_rolls_away",
            FailureDetail::Riser => "riser",
            FailureDetail::NoTouchdown => "no_touchdown",
            FailureDetail::NoProgress => "no_progress",
            FailureDetail::NonFinite => "non_finite",
            FailureDetail::StepUnderflow => "step_underflow",
            FailureDetail::WorkBudget => "work_budget",
            FailureDetail::Zeno => "zeno",
        }
    }

    /// One sentence a reader can act on: what happened, in the model's terms.
    pub fn describe(self) -> &'static str {
        match self {
            FailureDetail::RodDown => "a rod lay down: both of its tips reached the ground",
            FailureDetail::CentreOfMassLow => {
                "the centre of mass sank below collapse_height_ratio x the standing height"
            }
            FailureDetail::NoStandingEquilibrium => {
                "cannot stand: no static equilibrium found (no two-foot solution, \
                 or set down it never came to rest)"
            }
            FailureDetail::StandingRodDown => {
                "cannot stand: set down on the slope, it sagged until a rod lay on the ground"
            }
            FailureDetail::StandingComLow => {
                "cannot stand: set down on the slope, its centre of mass sank below \
                 collapse_height_ratio x the standing height"
            }
            FailureDetail::StandingRollsAway => {
                "cannot stand still: set down on the slope, it rolls or slides away from its feet"
            }
            FailureDetail::Riser => "tripped: a tip met the riser of the step",
            FailureDetail::NoTouchdown => "stalled: no touchdown for stall_time",
            FailureDetail::NoProgress => {
                "stalled: the centre of mass moved less than L/2 downhill over the window"
            }
            FailureDetail::NonFinite => "numerical failure: the state became NaN or infinite",
            FailureDetail::StepUnderflow => "numerical failure: the step size underflowed",
            FailureDetail::WorkBudget => "numerical failure: the work budget max_steps ran out",
            FailureDetail::Zeno => {
                "numerical failure: many transitions within a microsecond (Zeno)"
            }
        }
    }
}

impl std::fmt::Display for FailureDetail {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// Time fractions of the contact states over the analysis window.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ContactFractions {
    /// No foot on the ground (flight).
    pub nlsp: f64,
    /// One rod on the ground.
    pub slsp: f64,
    /// Two rods.
    pub dlsp: f64,
    /// Three rods.
    pub tlsp: f64,
}

/// How the star stood before the push (`initial.shape`, docs/model.md §6).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Stance {
    /// In its rest shape on two feet, not in equilibrium: `rigid_star`, or a
    /// `settled` star that cannot stand still (set down, it rolls or slides
    /// away along the slope, keeping its shape) pushed as it is set down
    /// (`initial.cannot_stand = "push"`).
    #[default]
    RestShape,
    /// In static equilibrium on two feet.
    TwoFeet,
    /// In static equilibrium on three feet (a tip of rod b down too).
    ThreeFeet,
}

impl Stance {
    /// The stance's name (`rest_shape`, `two_feet`, `three_feet`); also its
    /// `Display`.
    pub fn as_str(self) -> &'static str {
        match self {
            Stance::RestShape => "rest_shape",
            Stance::TwoFeet => "two_feet",
            Stance::ThreeFeet => "three_feet",
        }
    }
}

impl std::fmt::Display for Stance {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// Shares of the window's steps (one new foot's touchdown to the next) with flight and
/// with triple support, each step judged by its own contact fractions
/// against `labels.flight` and `labels.triple`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct StepShares {
    /// Number of whole steps in the window.
    pub steps: u64,
    /// Share of them with flight.
    pub flight: f64,
    /// Share of them with triple support.
    pub triple: f64,
}

/// Energy bookkeeping of a run (J). `balance_error` =
/// E_end + impact_loss + damping_loss + friction_loss − E_start, where E
/// includes gravity's potential: zero up to integration error.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Energy {
    /// Total mechanical energy at the start.
    pub initial: f64,
    /// Total mechanical energy at the end.
    pub last: f64,
    /// Potential energy of gravity released (E_grav,start − E_grav,end).
    pub gravity_released: f64,
    /// Energy removed by resets (impacts, and the hair-width projections of
    /// a tip onto the ground and of a re-sticking tip to rest).
    pub impact_loss: f64,
    /// Energy dissipated by the string dampers.
    pub damping_loss: f64,
    /// Work of sliding friction (finite μ only).
    pub friction_loss: f64,
    /// The balance's residual (zero up to integration error).
    pub balance_error: f64,
}

impl Energy {
    /// Largest [`Self::relative_balance_error`] of a run whose integration
    /// is trusted: the default tolerance keeps Fig. 7(a) at 0.015 %, while at
    /// the stiff end of the range (f_n 100, ζ 0, α 0.4, φ 0.3) it leaves
    /// 1.6 %, where a tighter `rtol` is needed to trust the outcome.
    pub const BALANCE_BOUND: f64 = 0.01;

    /// `|balance_error|` as a share of the energy at stake: the larger of
    /// the start's total energy and the gravity energy released.
    pub fn relative_balance_error(&self) -> f64 {
        let scale = self.initial.abs().max(self.gravity_released.abs());
        if scale > 0.0 {
            self.balance_error.abs() / scale
        } else {
            self.balance_error.abs()
        }
    }

    /// Whether the balance is off by more than [`Self::BALANCE_BOUND`] (a
    /// NaN error counts as off).
    pub fn balance_exceeds_bound(&self) -> bool {
        let r = self.relative_balance_error();
        r.is_nan() || r > Self::BALANCE_BOUND
    }
}

/// Integrator work over a run: accepted and rejected steps, RHS evaluations
/// and events (touchdowns, lift-offs, mode switches), as the engine counts
/// them.
pub type IntegratorWork = hybrid_ode::Work;

/// Everything one run measures (docs/model.md §5).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Outcome {
    /// The outcome label.
    pub label: Label,
    /// Why a failed run failed (`None` for a stable gait).
    pub failure: Option<FailureDetail>,
    /// How the star stood before the push.
    pub start: Stance,
    /// Time at which the run ended (t_max unless it failed).
    pub t_end: f64,
    /// Contact-state fractions over the analysis window.
    pub fractions: ContactFractions,
    /// Shares of the window's steps with flight and with triple support.
    pub step_shares: StepShares,
    /// All touchdowns of the run.
    pub touchdowns: u64,
    /// Touchdowns per second in the window.
    pub f_w: f64,
    /// Touchdowns of a tip other than the one that rod last landed on, per second.
    pub f_w_newfoot: f64,
    /// Mean downhill speed of the centre of mass over the window [m/s].
    pub speed: f64,
    /// Largest |λ_x|/λ_y while sticking with λ_y > 0.05 m g, over the window.
    pub mu_required: f64,
    /// Rod-seconds spent sliding over the whole run.
    pub slide_time: f64,
    /// The energy bookkeeping.
    pub energy: Energy,
    /// Period of the gait on the touchdown return map (0: none found).
    pub period: u32,
    /// The gait's limit cycle on the step map, if `Options::limit_cycle`
    /// asked for it and Newton found one.
    pub cycle: Option<CycleSummary>,
    /// Integrator work, the standing start's included (not the work of the
    /// robustness measures).
    pub work: IntegratorWork,
    /// The gait's robustness measures, if `Options::robustness` asked for
    /// any (docs/robustness.md); each measure is `None` unless the gait is
    /// stable.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub robustness: Option<Robustness>,
}

/// A run's limit cycle on the step map ([`crate::cycles::StepMap`]).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct CycleSummary {
    /// Period in steps (new-foot touchdowns).
    pub period: u32,
    /// Largest Floquet multiplier modulus (< 1: stable).
    pub floquet_max: f64,
    /// Scaled residual `|Pⁿ(z) − z|` of the fixed point.
    pub residual: f64,
}

/// One sample of a recorded trajectory, in full coordinates.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct TraceSample {
    /// Time (s).
    pub t: f64,
    /// Per rod a, b, c: centre x, y, angle θ.
    pub pose: [[f64; 3]; 3],
    /// Per rod: centre velocity x, y, angular velocity.
    pub vel: [[f64; 3]; 3],
    /// Per rod: 0 free, +1 / −1 stick on tip ±, +2 / −2 slide on tip ±.
    pub contact: [i8; 3],
    /// Number of rods on the ground (0 NLSP … 3 TLSP).
    pub contact_state: u8,
    /// Kinetic energy (J).
    pub kinetic: f64,
    /// Potential energy of gravity (J).
    pub gravity_potential: f64,
    /// Elastic energy of the strings (J).
    pub string_potential: f64,
    /// Energy dissipated by the dampers so far (J).
    pub damping_loss: f64,
    /// Energy dissipated by sliding friction so far (J).
    pub friction_loss: f64,
    /// Energy removed by resets so far (J).
    pub impact_loss: f64,
}

/// Counts of steps, of steps with flight and of steps with triple support.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct StepCounts {
    steps: u64,
    flight: u64,
    triple: u64,
}

impl StepCounts {
    pub(crate) fn shares(self) -> StepShares {
        let n = self.steps.max(1) as f64;
        StepShares {
            steps: self.steps,
            flight: self.flight as f64 / n,
            triple: self.triple as f64 / n,
        }
    }

    /// Counts one more step, with flight and triple support as `kind` says.
    pub(crate) fn add(&mut self, (flight, triple): (bool, bool)) {
        self.steps += 1;
        self.flight += flight as u64;
        self.triple += triple as u64;
    }

    pub(crate) fn since(self, earlier: StepCounts) -> StepCounts {
        StepCounts {
            steps: self.steps - earlier.steps,
            flight: self.flight - earlier.flight,
            triple: self.triple - earlier.triple,
        }
    }
}

/// Whether a step with `state_time` seconds per contact state has flight
/// and whether it has triple support.
pub(crate) fn step_kind(state_time: &[f64; 4], labels: &LabelOptions) -> (bool, bool) {
    let total: f64 = state_time.iter().sum();
    (
        state_time[0] > labels.flight * total,
        state_time[3] > labels.triple * total,
    )
}

impl StepShares {
    /// The step shares of steps given by their seconds per contact state.
    pub(crate) fn of_steps<'a>(
        steps: impl IntoIterator<Item = &'a [f64; 4]>,
        labels: &LabelOptions,
    ) -> StepShares {
        let mut c = StepCounts::default();
        for st in steps {
            c.add(step_kind(st, labels));
        }
        c.shares()
    }
}

impl Label {
    /// The label of a stable gait, Table S1's row for the RTW: flight → skip,
    /// else triple support → crawl, else walk. Flight counts when the
    /// window's NLSP fraction exceeds `labels.flight` and at least
    /// `labels.flight_steps` of the steps have flight; triple support likewise.
    pub fn of_gait(f: &ContactFractions, steps: &StepShares, labels: &LabelOptions) -> Label {
        if f.nlsp > labels.flight && steps.flight >= labels.flight_steps {
            Label::Skip
        } else if f.tlsp > labels.triple && steps.triple >= labels.triple_steps {
            Label::Crawl
        } else {
            Label::Walk
        }
    }
}

/// A gait's robustness measures (each `None` unless asked for, or when the
/// run is not a stable gait).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Robustness {
    /// The measures the run was asked for (its `robustness.*` options).
    pub asked: crate::options::RobustnessOptions,
    /// The largest survivable step down (m), see the module doc.
    pub step_down_max: Option<f64>,
    /// The height the gait failed at just above it: the bisection's upper
    /// end (`None` when even the cap survived).
    pub step_down_fail: Option<f64>,
    /// The step down over every phase (m): the height at which half of the
    /// edge positions over one step of the gait survive, see the module doc
    /// of `run::robustness`.
    pub step_down_h50: Option<f64>,
    /// A step down of `robustness.step_down_at` met at every phase of the
    /// gait: the shares of the edge positions that survive it and that
    /// fail by each kind.
    pub step_down_at: Option<PhaseSurvival>,
    /// The gait sensitivity norm (dimensionless; NaN where it cannot be
    /// computed), docs/robustness.md.
    pub gsn: Option<f64>,
    /// The mean steps to fall on a rough slope (Monte Carlo,
    /// docs/robustness.md).
    pub steps_to_fall: Option<StepsToFall>,
    /// The mean first-passage time on a rough slope (Fleming–Viot,
    /// docs/robustness.md).
    pub mfpt: Option<MeanFirstPassage>,
    /// How the chain estimator made `mfpt` (`robustness.mfpt_method =
    /// "chain"`; absent for the counted one, so that old JSON is unchanged).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mfpt_chain: Option<ChainDiagnostics>,
    /// Integrator work of the measures' runs.
    pub work: hybrid_ode::Work,
}

/// A point of a gait's survival curve: a step down of one height met with
/// its edge at each of the `step_down_h50` positions over one step of the
/// gait (docs/robustness.md), and the share of them that ended each way.
/// The shares add up to 1.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PhaseSurvival {
    /// Survived: the flat gait's label over the run's last ten steps.
    pub survived: f64,
    /// Collapsed (a rod down or the centre of mass too low).
    pub collapse: f64,
    /// Stalled (the star stopped rolling).
    pub stall: f64,
    /// Walked on in another gait (or was still hopping ten steps after).
    pub other_gait: f64,
    /// Failed numerically (a defect, never a physical outcome).
    pub diverged: f64,
}

/// Steps to fall on seeded rough slopes (docs/robustness.md): over the
/// trials, the mean of the steps of the flat gait each walked before it
/// failed, a trial that had not failed after `max_steps` counting as
/// `max_steps` (censored). With any trial censored the mean is a lower bound
/// of the mean first-passage time.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct StepsToFall {
    /// The (censored) mean steps to fall.
    pub mean: f64,
    /// The lower end of its 95 % confidence interval (normal, mean ± 1.96
    /// standard errors, cut at 0).
    pub lo: f64,
    /// The upper end.
    pub hi: f64,
    /// How many trials were censored (never failed).
    pub censored: u32,
    /// How many trials were run.
    pub trials: u32,
}

/// The mean first-passage time on seeded rough slopes (docs/robustness.md):
/// the expected steps of the flat gait to the fall from the walker's
/// quasi-stationary regime, estimated without censoring.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct MeanFirstPassage {
    /// Expected steps to fall, `1 / fall_rate`.
    pub mfpt: f64,
    /// Lower end of its 95 % interval.
    pub lo: f64,
    /// Upper end (infinite when the fall rate's interval reaches 0).
    pub hi: f64,
    /// Per-step fall probability in the quasi-stationary regime.
    pub fall_rate: f64,
    /// Steps the estimate simulated (its cost).
    pub steps: u64,
}

/// How the chain estimator's MFPT was made (docs/robustness-estimators.md, "The
/// chain method"): its mesh, and its discretisation test.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ChainDiagnostics {
    /// Cells of the mesh.
    pub cells: usize,
    /// Sampled extended states whose one step was integrated.
    pub members: usize,
    /// Inputs of a member's step (twice the strata of the new patch's height).
    pub nodes: usize,
    /// Principal components holding 95 % of the cloud's standardised
    /// variance (the effective dimension), of `features`.
    pub dimension: usize,
    /// Features of the extended state.
    pub features: usize,
    /// The MFPT at twice the cells (the discretisation test).
    pub mfpt_fine: f64,
    /// One over the sampled states' mean exact fall mass: the MFPT without
    /// the mesh (a check of it).
    pub mfpt_one_step: f64,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn energy_balance_is_judged_against_the_energy_at_stake() {
        // The two runs of the stiff corner and Fig. 7(a) (J, from `simulate --json`).
        let stiff = Energy {
            initial: 2867.96,
            gravity_released: 2745.66,
            balance_error: -63.51,
            ..Energy::default()
        };
        assert!((stiff.relative_balance_error() - 0.0221).abs() < 1e-4);
        assert!(stiff.balance_exceeds_bound());
        let fig7a = Energy {
            initial: 26.81,
            gravity_released: 235.73,
            balance_error: -0.0785,
            ..Energy::default()
        };
        assert!((fig7a.relative_balance_error() - 0.000333).abs() < 1e-5);
        assert!(!fig7a.balance_exceeds_bound());
        let nan = Energy {
            balance_error: f64::NAN,
            ..fig7a
        };
        assert!(nan.balance_exceeds_bound());
    }

    #[test]
    fn labels_follow_table_s1() {
        let f = |n, s, d, t| ContactFractions {
            nlsp: n,
            slsp: s,
            dlsp: d,
            tlsp: t,
        };
        let any = LabelOptions::any();
        let every = StepShares {
            steps: 10,
            flight: 1.0,
            triple: 1.0,
        };
        let label = |f: ContactFractions, labels: &LabelOptions| Label::of_gait(&f, &every, labels);
        assert_eq!(label(f(0.3, 0.7, 0.0, 0.0), &any), Label::Skip);
        assert_eq!(label(f(0.005, 0.5, 0.495, 0.0), &any), Label::Walk);
        assert_eq!(label(f(0.0, 0.4, 0.5, 0.1), &any), Label::Crawl);
        // Flight wins over triple support.
        assert_eq!(label(f(0.05, 0.4, 0.45, 0.1), &any), Label::Skip);
        // Separate thresholds: 5 % triple support is a crawl at 0.04, not at 0.06.
        let t = |triple| LabelOptions { triple, ..any };
        assert_eq!(label(f(0.0, 0.5, 0.45, 0.05), &t(0.04)), Label::Crawl);
        assert_eq!(label(f(0.0, 0.5, 0.45, 0.05), &t(0.06)), Label::Walk);
    }
}
