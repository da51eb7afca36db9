//! `rtw.scan`'s design options (`sampling`, `samples`, `seed`): the config's
//! top-level design keys, set over the loaded config. The result is parsed
//! again by rtw-scan's config parser, so the keys are checked together (a
//! grid's `m^D` samples, a Saltelli design's dimensions, the row limit) with
//! the messages a config file holding them gets, and the rows are those
//! `rtw-scan run` computes for that file.

use anyhow::{Result, anyhow};
use rtw_engine::config::count::count;
use rtw_engine::config::{self, ScanConfig};
use rtw_engine::sampling::Sampling;

/// The design keys of one `rtw.scan` call (`None`: the config's own);
/// `samples` and `seed` as the caller's value reads (`crate::digits`).
pub(crate) struct DesignKeys {
    pub(crate) sampling: Option<String>,
    pub(crate) samples: Option<String>,
    pub(crate) seed: Option<String>,
}

/// The integers a config's `samples` and `seed` can hold: TOML's (the
/// resolved config is parsed again as TOML), whose own checks of the value
/// (`samples` at least 1, at most 10^12 rows) come after.
const TOML_INTEGER: std::ops::RangeInclusive<u64> = 0..=i64::MAX as u64;

impl DesignKeys {
    /// `cfg` with these keys set, validated as a config file is.
    pub(crate) fn apply(&self, mut cfg: ScanConfig) -> Result<ScanConfig> {
        if self.sampling.is_none() && self.samples.is_none() && self.seed.is_none() {
            return Ok(cfg);
        }
        if let Some(name) = &self.sampling {
            cfg.sampling = Sampling::ALL
                .into_iter()
                .find(|s| s.name() == name)
                .ok_or_else(|| invalid_sampling(&format!("{name:?}")))?;
        }
        if let Some(n) = &self.samples {
            cfg.samples = count("samples", n, TOML_INTEGER, "")?;
        }
        if let Some(s) = &self.seed {
            cfg.seed = count("seed", s, TOML_INTEGER, "")?;
        }
        // The resolved config parses back to itself; parsing it checks the new keys.
        config::parse(&cfg.to_toml())
    }
}

/// The error of a `sampling` that names no design (`shown`: the value as the
/// caller spells it), listing the designs.
pub(crate) fn invalid_sampling(shown: &str) -> anyhow::Error {
    let valid: Vec<&str> = Sampling::ALL.iter().map(|s| s.name()).collect();
    anyhow!(
        "sampling: {shown} is invalid: must be one of {}",
        valid.join(", ")
    )
}
