//! How one parameter of a scan is chosen: fixed, uniform, or a grid.

use serde::Deserialize;
use serde::de::{self, Deserializer, MapAccess, SeqAccess, Visitor};
use std::fmt;

/// How one parameter is chosen.
#[derive(Clone, Debug, PartialEq)]
pub enum Axis {
    /// The same value for every sample: `alpha = 0.125`.
    Fixed(f64),
    /// Uniform on `[lo, hi]`: `rho = { uniform = [1, 5] }`.
    Uniform {
        /// Lower end.
        lo: f64,
        /// Upper end.
        hi: f64,
    },
    /// `n` evenly spaced grid points from `lo` to `hi` inclusive:
    /// `fn = { linspace = [2, 5, 31] }`.
    Linspace {
        /// First point.
        lo: f64,
        /// Last point.
        hi: f64,
        /// Number of points (≥ 1).
        n: u64,
    },
    /// Explicit grid points: `length = [0.7, 0.8, 0.9]`.
    List(Vec<f64>),
}

impl Axis {
    /// The number of grid points of a grid axis (`None` for fixed and
    /// uniform axes), without making them: a linspace may have more points
    /// than memory can hold, and is refused by its count alone.
    pub fn grid_len(&self) -> Option<u64> {
        match self {
            Axis::Fixed(_) | Axis::Uniform { .. } => None,
            Axis::List(v) => Some(v.len() as u64),
            Axis::Linspace { n, .. } => Some(*n),
        }
    }

    pub(crate) fn to_toml(&self) -> toml::Value {
        use toml::Value;
        let table = |key: &str, items: Vec<Value>| {
            let mut t = toml::Table::new();
            t.insert(key.into(), Value::Array(items));
            Value::Table(t)
        };
        match self {
            Axis::Fixed(v) => Value::Float(*v),
            Axis::Uniform { lo, hi } => {
                table("uniform", vec![Value::Float(*lo), Value::Float(*hi)])
            }
            Axis::Linspace { lo, hi, n } => table(
                "linspace",
                vec![
                    Value::Float(*lo),
                    Value::Float(*hi),
                    Value::Integer(*n as i64),
                ],
            ),
            Axis::List(v) => Value::Array(v.iter().map(|x| Value::Float(*x)).collect()),
        }
    }
}

/// `n` points from `lo` to `hi`, both included (`n = 1`: just `lo`).
pub fn linspace(lo: f64, hi: f64, n: u64) -> Vec<f64> {
    (0..n).map(|i| linspace_point(lo, hi, n, i)).collect()
}

/// Point `i` (`i < n`) of [`linspace`]`(lo, hi, n)`, computed alone so that a
/// scan never holds its grid in memory.
pub(crate) fn linspace_point(lo: f64, hi: f64, n: u64, i: u64) -> f64 {
    if i == 0 {
        lo
    } else if i == n - 1 {
        hi
    } else {
        lo + (hi - lo) * i as f64 / (n - 1) as f64
    }
}

impl<'de> Deserialize<'de> for Axis {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct AxisVisitor;
        impl<'de> Visitor<'de> for AxisVisitor {
            type Value = Axis;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str(
                    "a number, a list of numbers, { uniform = [lo, hi] } or { linspace = [lo, hi, n] }",
                )
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Axis, E> {
                Ok(Axis::Fixed(v))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Axis, E> {
                Ok(Axis::Fixed(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Axis, E> {
                Ok(Axis::Fixed(v as f64))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Axis, A::Error> {
                let mut v = Vec::new();
                while let Some(x) = seq.next_element::<f64>()? {
                    v.push(x);
                }
                Ok(Axis::List(v))
            }
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Axis, A::Error> {
                const KINDS: &[&str] = &["uniform", "linspace"];
                let Some(key) = map.next_key::<String>()? else {
                    return Err(de::Error::custom(
                        "empty table: expected { uniform = [lo, hi] } or { linspace = [lo, hi, n] }",
                    ));
                };
                let axis = match key.as_str() {
                    "uniform" => {
                        let [lo, hi] = map.next_value::<[f64; 2]>()?;
                        Axis::Uniform { lo, hi }
                    }
                    "linspace" => {
                        let (lo, hi, n) = map.next_value::<(f64, f64, i64)>()?;
                        if n < 1 {
                            return Err(de::Error::custom(format!(
                                "linspace: n = {n} is invalid: must be an integer >= 1"
                            )));
                        }
                        Axis::Linspace {
                            lo,
                            hi,
                            n: n as u64,
                        }
                    }
                    other => return Err(de::Error::unknown_field(other, KINDS)),
                };
                if let Some(extra) = map.next_key::<String>()? {
                    return Err(de::Error::custom(format!(
                        "unexpected second key `{extra}`: give exactly one of `uniform`, `linspace`"
                    )));
                }
                Ok(axis)
            }
        }
        d.deserialize_any(AxisVisitor)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linspace_includes_both_ends() {
        assert_eq!(linspace(2.0, 5.0, 4), vec![2.0, 3.0, 4.0, 5.0]);
        assert_eq!(linspace(0.3, 0.1, 1), vec![0.3]);
        let v = linspace(0.05, 0.2, 7);
        assert_eq!((v[0], v[6]), (0.05, 0.2));
    }
}
