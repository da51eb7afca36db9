//! Parsers of flag values that clap's own do not phrase with their rule.

/// Parses a count that must be at least 1 (`--threads`, `--k`) with the
/// rule in the message: clap's own parser of `NonZeroUsize` says only
/// "number would be zero for non-zero type".
pub(super) fn positive(s: &str) -> Result<std::num::NonZeroUsize, String> {
    s.trim()
        .parse::<usize>()
        .ok()
        .and_then(std::num::NonZeroUsize::new)
        .ok_or_else(|| format!("{s} is invalid: must be an integer >= 1"))
}

/// Parses `continuation --through`: an integer in [0, THROUGH_MAX], the
/// range said whatever was given (a float, a count beyond any integer).
pub(super) fn through(s: &str) -> Result<usize, String> {
    use crate::studies::continuation::{THROUGH_MAX, check_through};
    let n = s
        .trim()
        .parse::<usize>()
        .map_err(|_| format!("{s} is invalid: must be an integer in [0, {THROUGH_MAX}]"))?;
    check_through(n).map_err(|e| e.to_string())?;
    Ok(n)
}
