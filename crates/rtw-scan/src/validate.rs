//! The command line's second stage: the text of the flags (as clap hands
//! them over in each subcommand's `…Args`, the first stage) → typed,
//! checked values the library takes. The library never reads flag syntax:
//! `--set KEY=VALUE` becomes a typed key and value here
//! ([`Overrides::Sets`]), and the config layers (`config::layers`) only
//! place and validate values. Errors name the flag, and for a value beyond
//! a float the option's valid range.

use anyhow::{Result, anyhow, bail};
use rtw_engine::config::ScanConfig;
use rtw_engine::config::layers::{self, Overrides};
use rtw_engine::config::raw::option_range;
use rtw_model::Options;
use std::path::Path;

/// `--set` assignments, in order, as typed dotted keys and values (see
/// [`set`]).
pub(super) fn sets(assignments: &[String]) -> Result<Vec<(String, toml::Value)>> {
    assignments.iter().map(|a| set(a)).collect()
}

/// One `--set KEY=VALUE`: `KEY` a dotted path (`contact.mu`), `VALUE` read
/// as a TOML value (`true`, `inf`, `-3`, `"dop853"`), or taken as a bare
/// string when it is not one (`dop853`). Whether the key is an option is
/// checked when the layers are validated, not here.
pub(super) fn set(assignment: &str) -> Result<(String, toml::Value)> {
    let (key, value) = assignment
        .split_once('=')
        .ok_or_else(|| anyhow!("--set {assignment:?}: expected KEY=VALUE"))?;
    let (key, value) = (key.trim(), value.trim());
    if value.contains(['\n', '\r']) {
        bail!(
            "--set {key}: the value contains a newline: give one KEY=VALUE per --set (repeat --set for more)"
        );
    }
    if key.split('.').any(str::is_empty) {
        bail!("--set {assignment:?}: empty key segment in {key:?}");
    }
    if super::values::beyond_f64(value) {
        bail!(
            "--set {key}: {value} is invalid: {}{}",
            super::values::BEYOND_F64,
            option_range(key).map_or(String::new(), |r| format!("; {key} must be {r}"))
        );
    }
    let parsed = format!("v = {value}")
        .parse::<toml::Table>()
        .ok()
        .and_then(|mut t| t.remove("v"))
        .unwrap_or_else(|| toml::Value::String(value.to_string()));
    Ok((key.to_string(), parsed))
}

/// The simulation options of `--config`, `--variant` and `--set`
/// (`simulate`, `bifurcation`, `continuation`, `sensitivity`), validated.
pub(super) fn simulation_options(
    config: Option<&Path>,
    variant: Option<&Path>,
    set: &[String],
) -> Result<Options> {
    layers::simulation_options(config, variant, Overrides::Sets(&sets(set)?))
}

/// The scan config of `run CONFIG --variant FILE --set …`, validated.
pub(super) fn scan_config(
    config: &Path,
    variant: Option<&Path>,
    set: &[String],
) -> Result<ScanConfig> {
    layers::load_layered(config, variant, Overrides::Sets(&sets(set)?))
}

#[cfg(test)]
mod tests {
    use super::*;
    use rtw_engine::config::options_from_table;
    use rtw_engine::config::raw::set_path;
    use rtw_model::{Method, Normalization};

    /// The table the assignments make, as the config layers would place them.
    fn table(assignments: &[&str]) -> Result<toml::Table> {
        let mut t = toml::Table::new();
        for a in assignments {
            let (k, v) = set(a)?;
            set_path(&mut t, &k, v)?;
        }
        Ok(t)
    }

    #[test]
    fn set_overrides_parse_toml_values_or_bare_strings() {
        let t = table(&[
            "initial.omega=-3",
            "contact.mu=inf",
            "strings.slack=true",
            "method=dop853",
            "normalization=\"eigen\"",
        ])
        .unwrap();
        let o = options_from_table(t.clone(), "simulation").unwrap();
        assert_eq!(o.initial.omega, -3.0);
        assert!(o.contact.mu.is_infinite());
        assert!(o.strings.slack);
        assert_eq!(o.method, Method::Dop853);
        assert_eq!(o.normalization, Normalization::Eigen);
        let t = table(&["contact.mu=inf", "contact.mu=0.8"]).unwrap();
        assert_eq!(options_from_table(t, "simulation").unwrap().contact.mu, 0.8);
        assert!(table(&["method=dop853", "method.x=1"]).is_err());
        let e = set("novalue").unwrap_err().to_string();
        assert!(e.contains("expected KEY=VALUE"), "{e}");
        let e = set("contact..mu=1").unwrap_err().to_string();
        assert!(e.contains("empty key segment"), "{e}");
        let e = set("contact.mu=1e400").unwrap_err().to_string();
        assert!(
            e.contains("--set contact.mu: 1e400 is invalid: beyond the range of a 64-bit float")
                && e.contains("contact.mu must be"),
            "{e}"
        );
        let t = table(&["contact.nope=1"]).unwrap();
        let e = format!("{:#}", options_from_table(t, "simulation").unwrap_err());
        assert!(
            e.contains("simulation.contact.nope: unknown key `nope`"),
            "{e}"
        );
    }

    /// `terrain.seed` takes every u64 (TOML's integers end at 2⁶³ − 1: a
    /// larger seed is stored as a string of digits, and read back), and
    /// refuses anything else naming the range.
    #[test]
    fn terrain_seed_takes_every_u64_and_refuses_the_rest_with_the_range() {
        for seed in [
            "0",
            "7",
            "9223372036854775807",
            "9223372036854775808",
            "18446744073709551615",
        ] {
            // A rough slope: a flat one's terrain is left out of the text.
            let sets = [
                format!("terrain.seed={seed}"),
                "terrain.roughness=0.01".into(),
            ];
            let o = simulation_options(None, None, &sets).unwrap();
            assert_eq!(o.terrain.seed.to_string(), seed);
            let text = toml::to_string(&o).unwrap();
            let back = options_from_table(toml::from_str(&text).unwrap(), "simulation").unwrap();
            assert_eq!(back.terrain.seed, o.terrain.seed, "{text}");
        }
        for bad in ["-1", "1.5", "\"a\"", "a", "18446744073709551616", "true"] {
            let e = format!(
                "{:#}",
                simulation_options(None, None, &[format!("terrain.seed={bad}")]).unwrap_err()
            );
            assert!(
                e.contains("terrain.seed")
                    && e.contains("expected an integer in [0, 18446744073709551615]"),
                "{bad}: {e}"
            );
        }
    }

    #[test]
    fn typed_sets_layer_as_the_python_values_do() {
        let sets = [
            "contact.mu=0.8".to_string(),
            "t_max=5.5".into(),
            "method=rk4".into(),
        ];
        let values = [
            ("contact.mu".to_string(), toml::Value::Float(0.8)),
            ("t_max".to_string(), toml::Value::Float(5.5)),
            ("method".to_string(), toml::Value::String("rk4".into())),
        ];
        let from_sets = simulation_options(None, None, &sets).unwrap();
        let from_values =
            layers::simulation_options(None, None, Overrides::Values(&values)).unwrap();
        assert_eq!(
            toml::to_string(&from_sets).unwrap(),
            toml::to_string(&from_values).unwrap()
        );
    }
}
