//! The layers of a config, from low level to high: TOML text → tables; a
//! variant file's `[simulation]` keys over the config's; the overrides over
//! both (typed keys and values: the command line reads its `--set
//! KEY=VALUE` text in `cli::validate`, Python passes a dict); then
//! [`super::parse`] validates the result. Every error names the file and
//! the key path.

use super::raw::{from_value, parse_table, read_text, set_path};
use super::{ScanConfig, options_from_table, parse_value};
use anyhow::{Context, Result, anyhow, bail};
use rtw_model::Options;
use serde::Deserialize;
use std::path::Path;

/// A model variant file (`configs/variants/*.toml`): a name, what it tests,
/// and the `[simulation]` keys it changes. Layered over a scan config by
/// `rtw-scan run CONFIG --variant FILE`, so one parameter box is scanned
/// under every variant without copying its `[params]`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct VariantFile {
    name: String,
    #[serde(default)]
    #[allow(dead_code)] // documentation for the reader of the file
    description: String,
    #[serde(default)]
    simulation: toml::Table,
}

/// The top layer of options, over a config's `[simulation]` table and a
/// variant's: values by dotted key (`contact.mu`), in order, a later key
/// winning. Where they came from names them in errors.
#[derive(Clone, Copy, Debug)]
pub enum Overrides<'a> {
    /// The command line's `--set KEY=VALUE` assignments, already read into
    /// typed values (`cli::validate`); errors say `--set`.
    Sets(&'a [(String, toml::Value)]),
    /// The Python package's `options=` dict, converted from Python objects
    /// without passing through text; errors say `options`.
    Values(&'a [(String, toml::Value)]),
}

impl Overrides<'_> {
    /// No overrides.
    pub const NONE: Overrides<'static> = Overrides::Values(&[]);

    fn is_empty(&self) -> bool {
        match self {
            Overrides::Sets(s) => s.is_empty(),
            Overrides::Values(v) => v.is_empty(),
        }
    }
}

/// Loads a scan config, layers a variant file's `[simulation]` keys over its
/// own (the variant wins; the scan is then named `NAME+VARIANT`), then the
/// overrides, and validates the result. Errors name the file and the key.
pub fn load_layered(
    path: &Path,
    variant: Option<&Path>,
    sets: Overrides<'_>,
) -> Result<ScanConfig> {
    let (table, simulation) = read_split(path)?;
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    layered(table, simulation, &stem, variant, sets)
        .with_context(|| format!("{} {}", layered_what(variant, sets), path.display()))
}

/// [`load_layered`] of config text instead of a file (`rtw.scan` from
/// Python given TOML): a variant's name is appended to the config's `name`
/// (or to `scan` when it has none).
pub fn parse_layered(
    text: &str,
    variant: Option<&Path>,
    sets: Overrides<'_>,
) -> Result<ScanConfig> {
    let (table, simulation) = split_simulation(parse_table(text)?).context("config text")?;
    layered(table, simulation, "scan", variant, sets)
        .with_context(|| format!("{} text", layered_what(variant, sets)))
}

/// How a layered config is named in errors.
fn layered_what(variant: Option<&Path>, sets: Overrides<'_>) -> &'static str {
    match sets {
        _ if variant.is_none() && sets.is_empty() => "config",
        Overrides::Sets(_) => "config (with variant and --set)",
        Overrides::Values(_) => "config (with variant and options)",
    }
}

/// The layers of [`load_layered`] over a config's top-level and
/// `[simulation]` tables; `stem` names the scan when the config does not.
fn layered(
    mut table: toml::Table,
    mut simulation: toml::Table,
    stem: &str,
    variant: Option<&Path>,
    sets: Overrides<'_>,
) -> Result<ScanConfig> {
    let suffix = layer_variant_and_sets(&mut simulation, variant, sets)?;
    table.insert("simulation".into(), simulation.into());
    if let Some(suffix) = suffix {
        let base = match table.get("name") {
            Some(toml::Value::String(n)) => n.clone(),
            _ => stem.to_string(),
        };
        table.insert("name".into(), format!("{base}+{suffix}").into());
    }
    parse_value(table)
}

/// Layers a variant file's `[simulation]` keys (the variant wins), then the
/// overrides, over the `[simulation]` table `simulation`; returns the
/// variant's name. Errors name the file and the key.
fn layer_variant_and_sets(
    simulation: &mut toml::Table,
    variant: Option<&Path>,
    sets: Overrides<'_>,
) -> Result<Option<String>> {
    let mut name = None;
    if let Some(vpath) = variant {
        let vt = parse_table(&read_text(vpath, "variant")?)
            .with_context(|| format!("variant {}", vpath.display()))?;
        let v: VariantFile = from_value(toml::Value::Table(vt), "")
            .with_context(|| format!("variant {}", vpath.display()))?;
        merge_tables(simulation, v.simulation);
        name = Some(v.name);
    }
    let (values, who) = match sets {
        Overrides::Sets(values) => (values, "--set"),
        Overrides::Values(values) => (values, "options:"),
    };
    for (key, value) in values {
        if key.is_empty() || key.split('.').any(str::is_empty) {
            bail!("{who} {key:?} is not an option key (a dotted name such as contact.mu)");
        }
        set_path(simulation, key, value.clone()).map_err(|e| anyhow!("{who} {e}"))?;
    }
    Ok(name)
}

/// The simulation options of a single model (`simulate`, `bifurcation`):
/// the `[simulation]` table of `config_file` (default: the adopted model, docs/model.md §9),
/// then a variant file, then the overrides, validated. Errors name the file
/// and the key, the value and the valid range.
pub fn simulation_options(
    config_file: Option<&Path>,
    variant: Option<&Path>,
    sets: Overrides<'_>,
) -> Result<Options> {
    simulation_options_of(config_file.map(ConfigSource::File), variant, sets)
}

/// Where a config comes from: a file, or its TOML text (Python's `rtw`
/// takes a config's text, or a dict of its tables, where the command line
/// takes a file).
#[derive(Clone, Copy, Debug)]
pub enum ConfigSource<'a> {
    /// A config file.
    File(&'a Path),
    /// A config's TOML text.
    Text(&'a str),
}

/// [`simulation_options`] of a config given as a file or as text. Errors
/// name the file (or "config text") and the key.
pub fn simulation_options_of(
    config: Option<ConfigSource<'_>>,
    variant: Option<&Path>,
    sets: Overrides<'_>,
) -> Result<Options> {
    let mut table = match config {
        Some(ConfigSource::File(path)) => read_split(path)?.1,
        Some(ConfigSource::Text(text)) => {
            split_simulation(parse_table(text).context("config text")?)
                .context("config text")?
                .1
        }
        None => toml::Table::new(),
    };
    layer_variant_and_sets(&mut table, variant, sets)?;
    options_from_table(table, "simulation")
}

/// Reads a config file into its top-level table and, taken out of it, its
/// `[simulation]` table (empty when absent). Errors name the file.
pub(crate) fn read_split(path: &Path) -> Result<(toml::Table, toml::Table)> {
    let table = parse_table(&read_text(path, "config")?)
        .with_context(|| format!("config {}", path.display()))?;
    split_simulation(table).with_context(|| format!("config {}", path.display()))
}

/// A config's top-level table and, taken out of it, its `[simulation]`
/// table (empty when absent).
fn split_simulation(mut table: toml::Table) -> Result<(toml::Table, toml::Table)> {
    let simulation = match table.remove("simulation") {
        None => toml::Table::new(),
        Some(toml::Value::Table(s)) => s,
        Some(_) => bail!("`simulation` is not a table"),
    };
    Ok((table, simulation))
}

/// Deep-merges `over` into `base`: nested tables merge key by key, any other
/// value replaces the one in `base`.
fn merge_tables(base: &mut toml::Table, over: toml::Table) {
    for (k, v) in over {
        match (base.get_mut(&k), v) {
            (Some(toml::Value::Table(b)), toml::Value::Table(o)) => merge_tables(b, o),
            (_, v) => {
                base.insert(k, v);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::load;
    use crate::config::tests::BASE;

    /// One typed `--set` override.
    fn set(key: &str, value: f64) -> [(String, toml::Value); 1] {
        [(key.to_string(), toml::Value::Float(value))]
    }

    #[test]
    fn variant_and_sets_layer_over_the_config() {
        let dir = tempfile::tempdir().unwrap();
        let cfg = dir.path().join("base.toml");
        let text = format!(
            "name = \"box\"\n{BASE}\n[simulation]\nt_max = 5.0\nstrings.slack = true\ncontact.mu = 0.5\n"
        );
        std::fs::write(&cfg, text).unwrap();
        let var = dir.path().join("v.toml");
        std::fs::write(
            &var,
            "name = \"pre\"\ndescription = \"prestress\"\n[simulation]\nstrings.rest_length_ratio = 0.85\ncontact.mu = 0.8\n",
        )
        .unwrap();
        let c = load_layered(
            &cfg,
            Some(&var),
            Overrides::Sets(&set("initial.omega", -3.0)),
        )
        .unwrap();
        assert_eq!(c.name.as_deref(), Some("box+pre"));
        // The variant's keys win, the config's other keys stay (deep merge).
        assert_eq!(c.simulation.strings.rest_length_ratio, 0.85);
        assert!(c.simulation.strings.slack);
        assert_eq!(c.simulation.contact.mu, 0.8);
        assert_eq!(c.simulation.t_max, 5.0);
        assert_eq!(c.simulation.initial.omega, -3.0);
        // Without a variant the file loads as it is.
        assert_eq!(
            load_layered(&cfg, None, Overrides::NONE).unwrap(),
            load(&cfg).unwrap()
        );
        // A bad variant key is named.
        std::fs::write(
            &var,
            "name = \"x\"\n[simulation]\nstrings.rest_length_ratio = 1.5\n",
        )
        .unwrap();
        let e = format!(
            "{:#}",
            load_layered(&cfg, Some(&var), Overrides::NONE).unwrap_err()
        );
        assert!(
            e.contains("simulation.strings.rest_length_ratio: 1.5 is invalid"),
            "{e}"
        );
        std::fs::write(&var, "name = \"x\"\nseed = 3\n").unwrap();
        let e = format!(
            "{:#}",
            load_layered(&cfg, Some(&var), Overrides::NONE).unwrap_err()
        );
        assert!(
            e.contains("unknown key `seed`") && e.contains("v.toml"),
            "{e}"
        );
    }

    #[test]
    fn config_text_layers_like_the_file() {
        let dir = tempfile::tempdir().unwrap();
        let cfg = dir.path().join("base.toml");
        let text = format!("name = \"box\"\n{BASE}\n[simulation]\nt_max = 5.0\n");
        std::fs::write(&cfg, &text).unwrap();
        let var = dir.path().join("v.toml");
        std::fs::write(&var, "name = \"pre\"\n[simulation]\ncontact.mu = 0.8\n").unwrap();
        let sets = set("initial.omega", -3.0);
        assert_eq!(
            parse_layered(&text, Some(&var), Overrides::Sets(&sets)).unwrap(),
            load_layered(&cfg, Some(&var), Overrides::Sets(&sets)).unwrap()
        );
        // Without a name, a variant is appended to `scan`.
        let c = parse_layered(BASE, Some(&var), Overrides::NONE).unwrap();
        assert_eq!(c.name.as_deref(), Some("scan+pre"));
        let e = format!(
            "{:#}",
            parse_layered(BASE, None, Overrides::Sets(&set("contact.mu", -1.0))).unwrap_err()
        );
        assert!(
            e.starts_with(
                "config (with variant and --set) text: simulation.contact.mu: -1 is invalid"
            ),
            "{e}"
        );
        let e = format!(
            "{:#}",
            parse_layered("simulation = 1\n", None, Overrides::NONE).unwrap_err()
        );
        assert!(e.contains("`simulation` is not a table"), "{e}");
    }

    #[test]
    fn typed_values_layer_as_the_sets_do() {
        let values = [
            ("contact.mu".to_string(), toml::Value::Float(0.8)),
            ("t_max".to_string(), toml::Value::Float(5.5)),
            ("method".to_string(), toml::Value::String("rk4".into())),
        ];
        let from_sets = simulation_options(None, None, Overrides::Sets(&values)).unwrap();
        let from_values = simulation_options(None, None, Overrides::Values(&values)).unwrap();
        assert_eq!(
            toml::to_string(&from_sets).unwrap(),
            toml::to_string(&from_values).unwrap()
        );
        assert_eq!(from_values.t_max, 5.5);
        // Where the values came from names them.
        let nested = [
            ("t_max".to_string(), toml::Value::Float(5.5)),
            ("t_max.x".to_string(), toml::Value::Float(1.0)),
        ];
        let e = format!(
            "{:#}",
            simulation_options(None, None, Overrides::Sets(&nested)).unwrap_err()
        );
        assert!(
            e.starts_with("--set t_max.x: `t_max` is not a table"),
            "{e}"
        );
        let bad = |key: &str, value: toml::Value| {
            let values = [(key.to_string(), value)];
            format!(
                "{:#}",
                simulation_options(None, None, Overrides::Values(&values)).unwrap_err()
            )
        };
        let e = bad("contact..mu", toml::Value::Float(0.8));
        assert!(e.contains("\"contact..mu\" is not an option key"), "{e}");
        let e = bad("contact.mu", toml::Value::Float(-1.0));
        assert!(e.contains("simulation.contact.mu: -1 is invalid"), "{e}");
        // A string is a string: no TOML read of it.
        let e = bad("t_max", toml::Value::String("5".into()));
        assert!(e.contains("simulation.t_max"), "{e}");
    }
}
