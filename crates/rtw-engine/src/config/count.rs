//! Counts given as text (a flag's value, a Python integer's digits), read
//! against their range: one parser, so the command line and Python refuse
//! the same value in the same words, a number too large for any integer
//! type included.

use anyhow::{Result, bail};
use std::ops::RangeInclusive;

/// The integer `text` names, if it lies in `range`; otherwise the error
/// `NAME: TEXT is invalid: must be an integer in [LO, HI]NOTE`, where `name`
/// is the setting as the caller spells it (`--resamples`, `resamples`) and
/// `note` says where the bounds come from (empty, or ` (…)`).
pub fn count(name: &str, text: &str, range: RangeInclusive<u64>, note: &str) -> Result<u64> {
    match text.trim().parse::<u64>() {
        Ok(n) if range.contains(&n) => Ok(n),
        _ => bail!(
            "{name}: {} is invalid: must be an integer in [{}, {}]{note}",
            text.trim(),
            range.start(),
            range.end()
        ),
    }
}

/// [`count`] of a config's value: a TOML integer, or an integer's digits
/// in quotes (TOML's integers stop at 2⁶³ − 1, a seed's range does not);
/// any other value is refused in the same words, as written.
pub fn count_value(
    name: &str,
    value: &toml::Value,
    range: RangeInclusive<u64>,
    note: &str,
) -> Result<u64> {
    let text = match value {
        toml::Value::Integer(i) => i.to_string(),
        toml::Value::String(s) => s.clone(),
        v => v.to_string(),
    };
    count(name, &text, range, note)
}

/// [`count`] for a setting held in a `usize` (a length, a thread count):
/// `range` must fit in one, as every range of rtw's does on 64-bit targets.
pub fn count_usize(
    name: &str,
    text: &str,
    range: RangeInclusive<usize>,
    note: &str,
) -> Result<usize> {
    let wide = (*range.start() as u64)..=(*range.end() as u64);
    // In range, hence at most `range.end()`, a usize.
    count(name, text, wide, note).map(|n| n as usize)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_out_of_range_or_of_any_size_name_the_setting_and_its_range() {
        assert_eq!(count("--k", " 7 ", 1..=9, "").unwrap(), 7);
        for bad in [
            "0",
            "10",
            "-1",
            "2.5",
            "1e3",
            "",
            "100000000000000000000000000000000",
        ] {
            let e = count("--k", bad, 1..=9, " (why)").unwrap_err().to_string();
            assert_eq!(
                e,
                format!("--k: {bad} is invalid: must be an integer in [1, 9] (why)")
            );
        }
        assert_eq!(count_usize("n", "3", 2..=3, "").unwrap(), 3);
        let v = |t: &str| t.parse::<toml::Table>().unwrap()["k"].clone();
        let big = v("k = \"18446744073709551615\"");
        assert_eq!(count_value("k", &big, 0..=u64::MAX, "").unwrap(), u64::MAX);
        for (bad, shown) in [("k = -1", "-1"), ("k = 2.5", "2.5"), ("k = \"x\"", "x")] {
            let e = count_value("k", &v(bad), 0..=9, "")
                .unwrap_err()
                .to_string();
            assert_eq!(
                e,
                format!("k: {shown} is invalid: must be an integer in [0, 9]")
            );
        }
    }
}
