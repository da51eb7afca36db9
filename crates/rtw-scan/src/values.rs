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
    use rtw_studies::continuation::{THROUGH_MAX, check_through};
    let n = s
        .trim()
        .parse::<usize>()
        .map_err(|_| format!("{s} is invalid: must be an integer in [0, {THROUGH_MAX}]"))?;
    check_through(n).map_err(|e| e.to_string())?;
    Ok(n)
}

/// Parses a float flag (`--tol`, `--phi`, `--from`): every float flag of
/// every subcommand goes through it, so a number written beyond what a
/// 64-bit float holds is refused with the text typed, as `--set` refuses
/// it ([`beyond_f64`]), not with the value it reads as (`1e400` as inf,
/// `1e-400` as 0), which the option's own check would then show.
pub(super) fn float(s: &str) -> Result<f64, String> {
    let t = s.trim();
    if beyond_f64(t) {
        return Err(format!("{t} is invalid: {BEYOND_F64}"));
    }
    t.parse::<f64>()
        .map_err(|_| format!("{t} is invalid: must be a number"))
}

/// Why a literal [`beyond_f64`] is refused.
pub(super) const BEYOND_F64: &str =
    "beyond the range of a 64-bit float (magnitudes from 2.2e-308 to 1.8e308)";

/// Whether `literal` is a number written beyond what a 64-bit float holds
/// (`1e400` reads as inf, `1e-400` as 0): TOML refuses it, and taken as a
/// string it would be refused as "invalid type: string".
pub(super) fn beyond_f64(literal: &str) -> bool {
    let Ok(v) = literal.parse::<f64>() else {
        return false;
    };
    let mantissa = literal.split(['e', 'E']).next().unwrap_or("");
    let spelled_inf = literal.to_ascii_lowercase().contains("inf");
    (v.is_infinite() && !spelled_inf)
        || (v == 0.0 && mantissa.contains(|c: char| ('1'..='9').contains(&c)))
}
