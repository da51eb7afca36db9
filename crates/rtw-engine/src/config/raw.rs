//! The lowest layer of a config: a file read as UTF-8 text, the text as a
//! TOML table, a table deserialized with every error naming its key path,
//! a dotted key set in a table, and the valid range of a `[simulation]` key.

use crate::files::{CONFIG_MAX_BYTES, read_limited};
use anyhow::{Result, anyhow};
use rtw_model::Options;
use serde::Deserialize;
use std::path::Path;

/// Reads a UTF-8 text file of at most `CONFIG_MAX_BYTES`, with errors
/// naming what it is (`config`, `variant`) and the path.
pub fn read_text(path: &Path, what: &str) -> Result<String> {
    let bytes = read_limited(path, what, CONFIG_MAX_BYTES)?;
    String::from_utf8(bytes).map_err(|e| {
        anyhow!(
            "{what} {} is not valid UTF-8 (invalid byte at offset {})",
            path.display(),
            e.utf8_error().valid_up_to()
        )
    })
}

/// Parses TOML text into a table, keeping toml's line-and-column message.
pub fn parse_table(text: &str) -> Result<toml::Table> {
    text.parse::<toml::Table>()
        .map_err(|e| anyhow!("invalid TOML: {}", e.to_string().trim_end()))
}

/// Deserializes `value` into `T`, naming the key path (`prefix` + the path
/// inside `value`) in any error.
pub fn from_value<'de, T: Deserialize<'de>>(value: toml::Value, prefix: &str) -> Result<T> {
    from_value_ranged(value, prefix, |_| None)
}

/// [`from_value`], and a value of the wrong type (`t_max = "fast"`) is told
/// the key's valid range too: `range(path)`, the path inside `value`.
pub(crate) fn from_value_ranged<'de, T: Deserialize<'de>>(
    value: toml::Value,
    prefix: &str,
    range: impl Fn(&str) -> Option<&'static str>,
) -> Result<T> {
    serde_path_to_error::deserialize(value).map_err(|e| {
        let must = range(&e.path().to_string());
        let path = e.path().to_string();
        let key = match (prefix.is_empty(), path == ".") {
            (true, _) => path,
            (false, true) => prefix.to_string(),
            (false, false) => format!("{prefix}.{path}"),
        };
        // toml's own message may end with "in `table`" lines: the path says it.
        let inner = e.into_inner().to_string();
        let inner = inner
            .lines()
            .filter(|l| !l.starts_with("in `"))
            .collect::<Vec<_>>()
            .join("\n")
            .replace("unknown field", "unknown key")
            .replace("missing field", "missing key");
        let inner = match must {
            Some(r) if inner.starts_with("invalid ") => format!("{inner}: must be {r}"),
            _ => inner,
        };
        if key == "." || key.is_empty() {
            anyhow!("{inner}")
        } else {
            anyhow!("{key}: {inner}")
        }
    })
}

/// Sets the dotted `key` (`contact.mu`) of `table` to `value`, making the
/// tables on the way; the error names the key and the part that is not a table.
pub fn set_path(table: &mut toml::Table, key: &str, value: toml::Value) -> Result<()> {
    let parts: Vec<&str> = key.split('.').collect();
    let (last, path) = parts.split_last().expect("split yields at least one part");
    let mut t = table;
    for (depth, part) in path.iter().enumerate() {
        let entry = t
            .entry(part.to_string())
            .or_insert_with(|| toml::Value::Table(toml::Table::new()));
        t = entry
            .as_table_mut()
            .ok_or_else(|| anyhow!("{key}: `{}` is not a table", parts[..=depth].join(".")))?;
    }
    t.insert(last.to_string(), value);
    Ok(())
}

/// The valid range of the `[simulation]` option `key` (`t_max`,
/// `contact.mu`) in [`Options::validate`]'s words; `None` for a key without
/// one (a choice or a flag, whose own message lists what it takes). Found by
/// validating the default options with the key set to a value no range
/// holds (NaN, or 0 for an integer key), so the ranges live in rtw-model only.
pub fn option_range(key: &str) -> Option<&'static str> {
    [toml::Value::Float(f64::NAN), toml::Value::Integer(0)]
        .into_iter()
        .find_map(|probe| {
            let mut table = toml::Table::new();
            set_path(&mut table, key, probe).ok()?;
            let options: Options = toml::Value::Table(table).try_into().ok()?;
            let e = options.validate().err()?;
            (e.field == key).then_some(e.range)
        })
}
