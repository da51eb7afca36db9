//! Byte counts as people write and read them (`2GB`, `500 MB`; `2.0 GB`):
//! the sizes of `--trace-limit`, `--max-file-size` and the messages that
//! name a size.

/// A byte count in decimal units (`2.0 GB`).
pub(crate) fn human_bytes(b: f64) -> String {
    let units = ["B", "kB", "MB", "GB", "TB", "PB", "EB"];
    let mut v = b;
    let mut u = 0;
    while v >= 1000.0 && u + 1 < units.len() {
        v /= 1000.0;
        u += 1;
    }
    format!("{v:.1} {}", units[u])
}

/// Parses a size such as `2GB`, `500 MB`, `1e9` (bytes), `64kB`; decimal units.
pub fn parse_size(s: &str) -> Result<u64, String> {
    let t = s.trim();
    let split = t.find(|c: char| c.is_ascii_alphabetic()).unwrap_or(t.len());
    let (num, unit) = t.split_at(split);
    let factor = match unit.trim().to_ascii_lowercase().as_str() {
        "" | "b" => 1.0,
        "kb" | "k" => 1e3,
        "mb" | "m" => 1e6,
        "gb" | "g" => 1e9,
        "tb" | "t" => 1e12,
        _ => {
            return Err(format!(
                "`{s}`: unknown unit `{unit}`: use B, kB, MB, GB or TB"
            ));
        }
    };
    let v: f64 = num
        .trim()
        .parse()
        .map_err(|_| format!("`{s}` is not a size such as 2GB or 500MB"))?;
    if !(v.is_finite() && v > 0.0) {
        return Err(format!("`{s}`: must be a finite size > 0"));
    }
    Ok((v * factor).min(u64::MAX as f64) as u64)
}
