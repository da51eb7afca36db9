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
    }
}
