//! `configs/template.toml`, the annotated config a new scan starts from: it
//! loads, it sets every key the config schema has to its default, and the
//! comment above each key states the valid range (or the choices) exactly
//! as the validation reports them, so the template cannot drift from the
//! schema.

use rtw_engine::config::{self, ClusterConfig, options_from_table};
use rtw_model::{Options, Param};
use std::collections::BTreeMap;
use std::path::PathBuf;

fn template_path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../configs/template.toml")
}

fn template_text() -> String {
    std::fs::read_to_string(template_path()).unwrap()
}

/// Every key of a table as a dotted path (`initial.omega`), with its value.
fn flatten(prefix: &str, table: &toml::Table, out: &mut BTreeMap<String, toml::Value>) {
    for (k, v) in table {
        let key = if prefix.is_empty() {
            k.clone()
        } else {
            format!("{prefix}.{k}")
        };
        match v {
            toml::Value::Table(t) => flatten(&key, t, out),
            _ => {
                out.insert(key, v.clone());
            }
        }
    }
}

/// The comment lines right above `key = …` in the table `[section]` of the
/// template, joined.
fn comment_above(section: &str, key: &str) -> String {
    let text = template_text();
    let mut current = String::new();
    let mut comment: Vec<&str> = Vec::new();
    for line in text.lines() {
        let line = line.trim();
        if let Some(name) = line.strip_prefix('[').and_then(|l| l.strip_suffix(']')) {
            current = name.to_string();
            comment.clear();
        } else if let Some(c) = line.strip_prefix('#') {
            comment.push(c.trim());
        } else if current == section && line.split('=').next().map(str::trim) == Some(key) {
            return comment.join(" ");
        } else {
            comment.clear();
        }
    }
    panic!("configs/template.toml has no `{key} = …` in [{section}]");
}

#[test]
fn template_loads_with_every_default() {
    let cfg = config::load(&template_path()).unwrap();
    assert_eq!(cfg.simulation, Options::default());
    assert_eq!(cfg.cluster, ClusterConfig::default());
}

#[test]
fn template_names_every_simulation_key() {
    let text = template_text();
    let table: toml::Table = toml::from_str(&text).unwrap();
    let mut written = BTreeMap::new();
    flatten("", table["simulation"].as_table().unwrap(), &mut written);
    let mut schema = BTreeMap::new();
    flatten(
        "",
        &toml::Table::try_from(Options::default()).unwrap(),
        &mut schema,
    );
    assert_eq!(
        written.keys().collect::<Vec<_>>(),
        schema.keys().collect::<Vec<_>>(),
        "the template's [simulation] keys against the schema's"
    );
    let mut cluster = BTreeMap::new();
    flatten(
        "",
        &toml::Table::try_from(ClusterConfig::default()).unwrap(),
        &mut cluster,
    );
    for key in cluster.keys() {
        assert!(
            comment_above("cluster", key).contains("Default"),
            "cluster.{key}"
        );
    }
    for p in Param::ALL {
        comment_above("params", p.name());
    }
}

/// What the validation says a key accepts: its range for a bad number, its
/// choices for a bad name; None for a bool.
fn accepted(key: &str) -> Option<String> {
    let probes = [
        toml::Value::Float(f64::NAN),
        toml::Value::String("?".into()),
        toml::Value::Integer(0),
    ];
    for probe in probes {
        let mut table = toml::Table::new();
        let mut parts: Vec<&str> = key.split('.').collect();
        let last = parts.pop().unwrap();
        let mut t = &mut table;
        for part in parts {
            t = t
                .entry(part)
                .or_insert_with(|| toml::Value::Table(toml::Table::new()))
                .as_table_mut()
                .unwrap();
        }
        t.insert(last.into(), probe);
        let Err(e) = options_from_table(table, "simulation") else {
            continue;
        };
        let e = format!("{e:#}");
        if let Some((_, range)) = e.split_once(" is invalid: must be ") {
            return Some(range.trim().to_string());
        }
        // serde names the choices `a` or `b`, or one of `a`, `b`, `c`.
        if let Some((_, choices)) = e.split_once("unknown variant `?`, expected ") {
            let choices = choices.lines().next().unwrap();
            let choices = choices.strip_prefix("one of ").unwrap_or(choices);
            return Some(choices.replace(" or ", ", ").trim().to_string());
        }
    }
    None
}

#[test]
fn template_states_each_range_as_the_validation_does() {
    let mut schema = BTreeMap::new();
    flatten(
        "",
        &toml::Table::try_from(Options::default()).unwrap(),
        &mut schema,
    );
    for (key, default) in &schema {
        let comment = comment_above("simulation", key);
        assert!(
            comment.contains("Default"),
            "{key}: no default in `{comment}`"
        );
        match accepted(key) {
            Some(choices) if choices.contains('`') => {
                for choice in choices.split(',').map(|c| c.trim().trim_matches('`')) {
                    assert!(
                        comment.contains(choice),
                        "{key}: `{comment}` lacks {choice}"
                    );
                }
            }
            Some(range) => assert!(
                comment.contains(&range),
                "{key}: `{comment}` lacks the range `{range}`"
            ),
            None => {
                assert!(default.is_bool(), "{key}: no range found");
                assert!(comment.contains("true or false"), "{key}: `{comment}`");
            }
        }
    }
    for p in Param::ALL {
        let comment = comment_above("params", p.name());
        assert!(
            comment.contains(p.range()),
            "params.{}: `{comment}` lacks `{}`",
            p.name(),
            p.range()
        );
    }
}
