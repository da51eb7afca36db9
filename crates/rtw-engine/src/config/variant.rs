//! The model variant a run used, in one line: every open choice of
//! docs/model.md §9, written to each file's metadata and summary.

use rtw_model::Normalization;
use rtw_model::Options;
use rtw_model::options::{CannotStand, Damping, InitialShape, LabelOptions, Method};
use serde::Serialize;
use std::fmt;

/// The model variant of docs/model.md §9 that a run used: every open choice.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ModelChoices {
    pub(crate) rest_length_ratio: f64,
    /// Friction coefficient; `inf` (no slip) is `null` in JSON, which has no
    /// infinity (the one rule of every JSON rtw-scan writes: a non-finite
    /// number is `null`).
    pub(crate) mu: f64,
    pub(crate) slack: bool,
    pub(crate) damping: Damping,
    pub(crate) normalization: Normalization,
    pub(crate) initial_shape: InitialShape,
    pub(crate) initial_cannot_stand: CannotStand,
    pub(crate) initial_omega: f64,
    pub(crate) labels: LabelOptions,
    pub(crate) method: Method,
    pub(crate) rtol: f64,
    pub(crate) atol: f64,
    pub(crate) t_max: f64,
    /// The terrain and robustness settings that differ from the default, as
    /// `KEY=VALUE` with the config's dotted keys: empty for the flat run
    /// without measures, so that its line (and every file made by one) is
    /// the same as before terrain existed.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub(crate) ground_and_measures: Vec<String>,
}

impl ModelChoices {
    /// The choices `o` makes.
    pub fn of(o: &Options) -> Self {
        Self {
            rest_length_ratio: o.strings.rest_length_ratio,
            mu: o.contact.mu,
            slack: o.strings.slack,
            damping: o.strings.damping,
            normalization: o.normalization,
            initial_shape: o.initial.shape,
            initial_cannot_stand: o.initial.cannot_stand,
            initial_omega: o.initial.omega,
            labels: o.labels,
            method: o.method,
            rtol: o.rtol,
            atol: o.atol,
            t_max: o.t_max,
            ground_and_measures: [
                non_default("terrain", &o.terrain, &Options::default().terrain),
                non_default("robustness", &o.robustness, &Options::default().robustness),
            ]
            .concat(),
        }
    }
}

/// `PREFIX.KEY=VALUE` for each setting of `value` that differs from
/// `default`, as the config's TOML writes them (so the line names the keys a
/// user sets, and a setting added later is named without a change here).
fn non_default<T: Serialize>(prefix: &str, value: &T, default: &T) -> Vec<String> {
    let table = |v: &T| match toml::Value::try_from(v) {
        Ok(toml::Value::Table(t)) => t,
        _ => toml::Table::new(),
    };
    let (value, default) = (table(value), table(default));
    value
        .iter()
        .filter(|(k, v)| default.get(*k) != Some(*v))
        .map(|(k, v)| format!("{prefix}.{k}={v}"))
        .collect()
}

/// Lower-case name of a unit-variant enum, as serde writes it in configs.
pub(crate) fn enum_name<T: Serialize>(v: &T) -> String {
    match toml::Value::try_from(v) {
        Ok(toml::Value::String(s)) => s,
        _ => "?".into(),
    }
}

impl fmt::Display for ModelChoices {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "rest_length_ratio={} mu={} slack={} damping={} normalization={} initial={}(omega={}{}) \
             labels=(flight {} in {} of steps, triple {} in {}) method={} rtol={:e} atol={:e} t_max={}",
            self.rest_length_ratio,
            self.mu,
            self.slack,
            enum_name(&self.damping),
            enum_name(&self.normalization),
            enum_name(&self.initial_shape),
            self.initial_omega,
            match self.initial_shape {
                InitialShape::Settled =>
                    format!(", cannot_stand={}", enum_name(&self.initial_cannot_stand)),
                _ => String::new(),
            },
            self.labels.flight,
            self.labels.flight_steps,
            self.labels.triple,
            self.labels.triple_steps,
            enum_name(&self.method),
            self.rtol,
            self.atol,
            self.t_max
        )?;
        for s in &self.ground_and_measures {
            write!(f, " {s}")?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn variant_names_every_choice() {
        let v = ModelChoices::of(&Options::literal()).to_string();
        for s in [
            "rest_length_ratio=0",
            "mu=inf",
            "slack=false",
            "damping=along",
            "normalization=supplementary",
            "initial=rigid_star(omega=-2)",
            "method=",
        ] {
            assert!(v.contains(s), "{v} lacks {s}");
        }
    }

    /// A run on a step or with robustness measures is not the flat run of
    /// the same model: its variant line (the summary's "model variant", each
    /// file's `rtw.variant`) must say so, or two such scans read alike.
    #[test]
    fn variant_names_the_terrain_and_robustness_settings_that_differ_from_the_default() {
        let mut o = Options::default();
        o.terrain.step_height = 0.05;
        o.robustness.step_down = true;
        o.robustness.sigma = 0.02;
        let v = ModelChoices::of(&o).to_string();
        for s in [
            "terrain.step_height=0.05",
            "robustness.step_down=true",
            "robustness.sigma=0.02",
        ] {
            assert!(v.contains(s), "{v} lacks {s}");
        }
        // The flat run without measures names neither, so its line (and
        // every committed file's metadata) is what it was.
        let flat = ModelChoices::of(&Options::default()).to_string();
        assert!(
            !flat.contains("terrain") && !flat.contains("robustness"),
            "{flat}"
        );
    }
}
