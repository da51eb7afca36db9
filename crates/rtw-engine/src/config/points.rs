//! Stored points: a scan whose rows are given, not drawn (`sampling =
//! "points"`).
//!
//! ```toml
//! samples = 3
//! sampling = "points"
//! [params]
//! rho = { uniform = [1, 5] }     # the box the points lie in
//! alpha = { uniform = [0, 0.4] }
//! # … the other inputs fixed
//! [points]                       # one value per sample for each uniform input
//! rho = [1.5, 2.25, 4.0]
//! alpha = [0.1, 0.3, 0.05]
//! ```
//!
//! A refinement round's points depend on the rows before it, not on (seed,
//! sample id) alone, so its config carries them. Run again (`run`,
//! `--resume`, a shard, `merge`), the config replays the same rows; and the
//! readers that weigh each row as a draw from the inputs' distribution
//! (`sensitivity`) know to refuse them.

use super::axis::Axis;
use anyhow::{Result, bail};
use rtw_model::{Num, Param, Params};
use std::sync::Arc;

/// Most points a config stores. Every chunk of a run carries its config, so
/// the points are written once per chunk: 10⁴ points of six inputs are about
/// 1.2 MB of text, and a run of 10⁴ rows has 40 chunks.
pub const MAX_POINTS: u64 = 10_000;

/// The points of `[points]` as full parameter sets (fixed inputs filled in),
/// checked against `sampling`, `samples` and the inputs' boxes; `None` when
/// the config stores none. Errors name `points.INPUT[i]` and the valid range.
pub(crate) fn parse(
    table: Option<toml::Table>,
    stored: bool,
    samples: u64,
    params: &[Axis; 6],
) -> Result<Option<Arc<[Params]>>> {
    let table = match (table, stored) {
        (None, false) => return Ok(None),
        (Some(_), false) => bail!(
            "points: a [points] table is given, but the config's sampling draws its points: \
             write `sampling = \"points\"` to run the stored points"
        ),
        (None, true) => bail!(
            "sampling: \"points\" needs a [points] table: one value per sample for each uniform \
             input (a refinement round's config has one)"
        ),
        (Some(t), true) => t,
    };
    if samples > MAX_POINTS {
        bail!(
            "samples: {samples} is invalid for sampling = \"points\": must be at most \
             {MAX_POINTS} (the points are stored in the config, which every chunk carries)"
        );
    }
    let mut base = Params::fig7a();
    let mut uniform = Vec::new();
    for (input, axis) in Param::ALL.into_iter().zip(params) {
        match axis {
            Axis::Fixed(v) => base[input] = *v,
            Axis::Uniform { lo, hi } => uniform.push((input, *lo, *hi)),
            _ => bail!(
                "params.{}: a grid is invalid for sampling = \"points\": every input must be \
                 fixed or {{ uniform = [lo, hi] }} (the points give the uniform inputs)",
                input.name()
            ),
        }
    }
    if let Some(key) = table
        .keys()
        .find(|k| !uniform.iter().any(|(p, ..)| p.name() == k.as_str()))
    {
        let names: Vec<&str> = uniform.iter().map(|(p, ..)| p.name()).collect();
        bail!(
            "points.{key}: not a uniform input of [params]: the points give exactly {}",
            names.join(", ")
        );
    }
    let mut points = vec![base; samples as usize];
    for (input, lo, hi) in uniform {
        let key = input.name();
        let Some(toml::Value::Array(values)) = table.get(key) else {
            bail!("points.{key}: missing, or not an array: give one value per sample ({samples})");
        };
        if values.len() as u64 != samples {
            bail!(
                "points.{key}: {} values is invalid: must be one per sample (samples = {samples})",
                values.len()
            );
        }
        for (i, (value, point)) in values.iter().zip(&mut points).enumerate() {
            let v = match value {
                toml::Value::Float(v) => *v,
                toml::Value::Integer(v) => *v as f64,
                other => bail!("points.{key}[{i}]: {other} is invalid: must be a number"),
            };
            // The uniform box holds every valid point (the parameter check
            // has passed on both ends), and NaN is outside it.
            if !(lo..=hi).contains(&v) {
                bail!(
                    "points.{key}[{i}]: {} is invalid: must be in [{}, {}] (params.{key}.uniform)",
                    Num(v),
                    Num(lo),
                    Num(hi)
                );
            }
            point[input] = v;
        }
    }
    Ok(Some(points.into()))
}

/// The `[points]` table of `points`: one array per uniform input of `params`.
pub(crate) fn to_toml(points: &[Params], params: &[Axis; 6]) -> toml::Table {
    Param::ALL
        .into_iter()
        .zip(params)
        .filter(|(_, a)| matches!(a, Axis::Uniform { .. }))
        .map(|(input, _)| {
            let values: Vec<toml::Value> = points.iter().map(|p| p[input].into()).collect();
            (input.name().to_string(), values.into())
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use crate::config::parse;
    use crate::scan::sample::Sampler;
    use rtw_model::Param;

    const STORED: &str = r#"
seed = 1
samples = 3
sampling = "points"
[params]
length = 0.8
rho = { uniform = [1, 5] }
alpha = { uniform = [0, 0.4] }
fn = 3.0
zeta = 0.05
phi = 0.15
[points]
rho = [1.5, 2.25, 4]
alpha = [0.1, 0.3, 0.05]
"#;

    fn err(text: &str) -> String {
        format!("{:#}", parse(text).unwrap_err())
    }

    #[test]
    fn stored_points_are_the_rows_and_survive_the_round_trip() {
        let cfg = parse(STORED).unwrap();
        let s = Sampler::new(&cfg);
        assert_eq!(s.total(), 3);
        let p = s.params(2);
        assert_eq!(
            (p[Param::Rho], p[Param::Alpha], p[Param::Fn]),
            (4.0, 0.05, 3.0)
        );
        assert_eq!(s.params(1)[Param::Rho], 2.25);
        // The resolved text parses back to the same points, bit for bit.
        let again = parse(&cfg.to_toml()).unwrap();
        assert_eq!(again, cfg);
        // Other points, another config hash: a run of one never resumes the other.
        let other = parse(&STORED.replace("2.25", "2.5")).unwrap();
        assert_ne!(other.hash(), cfg.hash());
    }

    #[test]
    fn bad_points_are_named_with_the_valid_range() {
        let e = err(&STORED.replace("rho = [1.5, 2.25, 4]", "rho = [1.5, 7, 4]"));
        assert!(
            e.contains("points.rho[1]: 7 is invalid: must be in [1, 5]"),
            "{e}"
        );
        let e = err(&STORED.replace("rho = [1.5, 2.25, 4]", "rho = [1.5, 2.25]"));
        assert!(
            e.contains("points.rho: 2 values is invalid: must be one per sample (samples = 3)"),
            "{e}"
        );
        let e = err(&STORED.replace("rho = [1.5, 2.25, 4]", "rho = [1.5, \"a\", 4]"));
        assert!(
            e.contains("points.rho[1]: \"a\" is invalid: must be a number"),
            "{e}"
        );
        let e = err(&STORED.replace("rho = [1.5, 2.25, 4]\n", ""));
        assert!(e.contains("points.rho: missing"), "{e}");
        let e = err(&format!("{STORED}zeta = [0.05, 0.05, 0.05]\n"));
        assert!(
            e.contains(
                "points.zeta: not a uniform input of [params]: the points give exactly rho, alpha"
            ),
            "{e}"
        );
        let e = err(&STORED.replace("sampling = \"points\"\n", ""));
        assert!(e.contains("write `sampling = \"points\"`"), "{e}");
        let e = err(&STORED[..STORED.find("[points]").unwrap()]);
        assert!(
            e.contains("sampling: \"points\" needs a [points] table"),
            "{e}"
        );
        let e = err(&STORED.replace("phi = 0.15", "phi = [0.1, 0.15]"));
        assert!(
            e.contains("params.phi: a grid is invalid for sampling = \"points\""),
            "{e}"
        );
        let e = err(&STORED.replace("rho = [1.5, 2.25, 4]", "rho = [1.5, nan, 4]"));
        assert!(e.contains("points.rho[1]: NaN is invalid"), "{e}");
    }
}
