//! What a long study will cost, estimated before it starts, and the bounds
//! above which it is warned of: a slope profile's and a design search's
//! simulations, and the walker-steps of their MFPTs (each MFPT walks a
//! cloud of walkers over the rough slope, thousands of steps a batch).

use super::Settings;
use rtw_model::Options;

/// Above this many simulations a study is warned of: about an hour of a
/// core at the few milliseconds a run of the paper's designs takes.
pub const WARN_SIMULATIONS: u64 = 1_000_000;
/// Above this many walker-steps of the MFPT a study is warned of: hours of
/// a core at 90 to 290 µs a step.
pub const WARN_WALKER_STEPS: u64 = 100_000_000;
/// Walker-steps of one batch of the MFPT's cloud (rtw-model's
/// `MFPT_SETTINGS`: 16 walkers take 60 steps of burn-in, their 32 copies 60
/// more), as `robustness.mfpt_batches`' range states it.
pub const MFPT_BATCH_WALKER_STEPS: u64 = 2880;

/// The walker-steps of one run with the MFPT under `options`.
pub fn mfpt_walker_steps(options: &Options) -> u64 {
    u64::from(options.robustness.mfpt_batches) * MFPT_BATCH_WALKER_STEPS
}

/// A study's estimated cost.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Cost {
    /// Simulations.
    pub simulations: u64,
    /// Walker-steps of the MFPTs (0: none).
    pub walker_steps: u64,
}

impl Cost {
    /// The warning `study` gets when its cost passes [`WARN_SIMULATIONS`]
    /// or [`WARN_WALKER_STEPS`]; `None` below both.
    pub fn warning(&self, study: &str) -> Option<String> {
        let mut over = Vec::new();
        if self.simulations > WARN_SIMULATIONS {
            over.push(format!(
                "{} simulations (more than {WARN_SIMULATIONS})",
                self.simulations
            ));
        }
        if self.walker_steps > WARN_WALKER_STEPS {
            over.push(format!(
                "{} walker-steps of the MFPT (more than {WARN_WALKER_STEPS})",
                self.walker_steps
            ));
        }
        (!over.is_empty()).then(|| {
            format!(
                "rtw-scan: warning: {study} will cost about {}: hours of computing or more; \
                 stop it (Ctrl-C) and coarsen its grid, or lower robustness.mfpt_batches, if \
                 that is not what you meant",
                over.join(" and ")
            )
        })
    }
}

/// What the profile of `s` under `options` will cost, in words: its coarse
/// grid's runs (known), then about log2(cell / tol) + 2 runs for each change
/// of label it finds (not known before the grid is run), each an MFPT with
/// `robustness.mfpt`; and a warning when the grid alone passes the bounds.
pub(crate) fn of_profile(s: &Settings, options: &Options) -> (String, Option<String>) {
    let coarse = s.coarse().len() as u64;
    let cell = (s.to - s.from) / (coarse.max(2) - 1) as f64;
    let per_change = (cell / s.tol).log2().ceil().max(0.0) as u64 + 2;
    let per_run = if options.robustness.mfpt {
        mfpt_walker_steps(options)
    } else {
        0
    };
    let c = Cost {
        simulations: coarse,
        walker_steps: coarse * per_run,
    };
    let mfpt = if per_run > 0 {
        format!(
            "; each run an MFPT of {per_run} walker-steps (the grid alone {} walker-steps)",
            c.walker_steps
        )
    } else {
        String::new()
    };
    let text = format!(
        "profile: {coarse} slopes on the coarse grid, then about {per_change} runs for each \
         change of label found{mfpt}"
    );
    (text, c.warning("the profile"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_batch_walker_steps_are_those_the_batches_range_states() {
        let mut o = Options::default();
        o.robustness.mfpt = true;
        o.robustness.sigma = 0.05;
        o.robustness.mfpt_batches = 1;
        let e = o.validate().unwrap_err();
        assert!(
            e.range.contains(&format!(
                "{MFPT_BATCH_WALKER_STEPS} steps of the walker each"
            )),
            "{}",
            e.range
        );
        o.robustness.mfpt_batches = 3000;
        assert_eq!(mfpt_walker_steps(&o), 8_640_000);
        let c = Cost {
            simulations: 10,
            walker_steps: 1024 * mfpt_walker_steps(&o),
        };
        assert!(c.warning("it").unwrap().contains("walker-steps"));
    }
}
