//! Normalized inputs (L, ρ, α, f_n, ζ, φ) and the physical parameters they
//! give (docs/model.md §1, supplementary S19–S22).

use serde::{Deserialize, Serialize};
use std::f64::consts::PI;
use std::fmt;

/// A number as a person writes it, for messages: plain decimals for
/// magnitudes in [1e-4, 1e15) (`0.125`, `500`), scientific notation outside
/// (`1e300`, `-2.5e-7`), and `inf`, `-inf`, `NaN`. f64's own `Display`
/// would print 1e300 as 301 digits and 1e-300 as 302.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Num(pub f64);

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let v = self.0;
        if v == 0.0 || !v.is_finite() || (1e-4..1e15).contains(&v.abs()) {
            write!(f, "{v}")
        } else {
            write!(f, "{v:e}")
        }
    }
}

/// A rejected input: names the field, the value and the valid range.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{field} = {} is invalid: must be {range}", Num(*value))]
pub struct ParamError {
    /// The key of the field (`"alpha"`, `"contact.mu"`, …).
    pub field: &'static str,
    /// The rejected value.
    pub value: f64,
    /// The valid range, in words.
    pub range: &'static str,
}

impl ParamError {
    /// The error for `value` of `field`, which must be `range`.
    pub(crate) fn new(field: &'static str, value: f64, range: &'static str) -> Self {
        Self {
            field,
            value,
            range,
        }
    }
}

/// Checks `ok(value)` and `value` finite, or names the field and its range.
pub(crate) fn check(
    field: &'static str,
    value: f64,
    range: &'static str,
    ok: impl Fn(f64) -> bool,
) -> Result<(), ParamError> {
    if value.is_finite() && ok(value) {
        Ok(())
    } else {
        Err(ParamError::new(field, value, range))
    }
}

/// The six normalized inputs of one sample (docs/model.md §1).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Params {
    /// Rod length `L` (m).
    pub length: f64,
    /// Mass per length `ρ` [kg/m].
    pub rho: f64,
    /// Connection ratio `α = l_c / L` [-].
    pub alpha: f64,
    /// Design eigen-frequency `f_n` of the approximate model (S18) (Hz).
    pub f_n: f64,
    /// Damping ratio `ζ` [-].
    pub zeta: f64,
    /// Slope `φ` (rad).
    pub phi: f64,
}

impl Params {
    /// Validated constructor.
    pub fn new(
        length: f64,
        rho: f64,
        alpha: f64,
        f_n: f64,
        zeta: f64,
        phi: f64,
    ) -> Result<Self, ParamError> {
        let p = Self {
            length,
            rho,
            alpha,
            f_n,
            zeta,
            phi,
        };
        p.validate()?;
        Ok(p)
    }

    /// The walking example of the article's Fig. 7(a): m = 2 kg, l_c = 0.1 m,
    /// k = 500 N/m, c = 1 N·s/m on φ = 0.15 rad.
    pub fn fig7a() -> Self {
        Self {
            length: 0.8,
            rho: 2.5,
            alpha: 0.125,
            f_n: 3.269,
            zeta: 0.0514,
            phi: 0.15,
        }
    }

    /// docs/model.md §1: L > 0, ρ > 0, 0 ≤ α < 0.5, f_n > 0, ζ ≥ 0, |φ| < π/2,
    /// all finite ([`Param::range`]); the first invalid input is named.
    pub fn validate(&self) -> Result<(), ParamError> {
        Param::ALL
            .iter()
            .try_for_each(|param| param.check(self[*param]))
    }
}

/// One of the six normalized inputs, by name: the one vocabulary of a
/// config's `params.*` keys, `--set`, a bifurcation sweep's `--param` and
/// validation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Param {
    /// Rod length `L` (m).
    Length,
    /// Mass per length `ρ` [kg/m].
    Rho,
    /// Connection ratio `α`.
    Alpha,
    /// Design eigen-frequency `f_n` (Hz).
    Fn,
    /// Damping ratio `ζ`.
    Zeta,
    /// Slope `φ` (rad).
    Phi,
}

impl Param {
    /// Every input, in the order of docs/model.md §1.
    pub const ALL: [Param; 6] = [
        Param::Length,
        Param::Rho,
        Param::Alpha,
        Param::Fn,
        Param::Zeta,
        Param::Phi,
    ];

    /// The key: `length`, `rho`, `alpha`, `fn`, `zeta`, `phi`; also its
    /// `Display` (and what `str::parse` reads).
    pub fn name(self) -> &'static str {
        match self {
            Param::Length => "length",
            Param::Rho => "rho",
            Param::Alpha => "alpha",
            Param::Fn => "fn",
            Param::Zeta => "zeta",
            Param::Phi => "phi",
        }
    }

    /// The valid range, in words (with the unit).
    pub fn range(self) -> &'static str {
        match self {
            Param::Length => "in [1e-3, 1e3] (m)",
            Param::Rho => "in [1e-3, 1e3] (kg/m)",
            Param::Alpha => "in [0, 0.49]",
            Param::Fn => "in [1e-2, 1e2] (Hz)",
            Param::Zeta => "in [0, 10]",
            Param::Phi => "in (-pi/2, pi/2) rad",
        }
    }

    /// Whether `value` is valid: finite and in [`range`](Param::range).
    pub(crate) fn admits(self, value: f64) -> bool {
        // Six orders of magnitude around the article's box for the scales;
        // at each end the Fig. 7(a) point still gives a physical outcome
        // (tests/option_ranges.rs). Beyond them the integrator's absolute
        // tolerances and the start's thresholds stop meaning anything, and
        // α → 0.5 attaches the strings at the hub (r = L/2 − αL → 0), where
        // the settling underflows its step.
        value.is_finite()
            && match self {
                Param::Length | Param::Rho => (1e-3..=1e3).contains(&value),
                Param::Alpha => (0.0..=0.49).contains(&value),
                Param::Fn => (1e-2..=1e2).contains(&value),
                Param::Zeta => (0.0..=10.0).contains(&value),
                Param::Phi => value.abs() < PI / 2.0,
            }
    }

    /// `value` if it is valid, else the error naming this input and its range.
    pub fn check(self, value: f64) -> Result<(), ParamError> {
        check(self.name(), value, self.range(), |v| self.admits(v))
    }
}

/// `params[Param::Alpha]`: one input by name (the sweep, continuation and
/// sampling set inputs they know only as a [`Param`]). Setting through
/// `IndexMut` is unchecked: see [`Param::check`].
impl std::ops::Index<Param> for Params {
    type Output = f64;
    fn index(&self, param: Param) -> &f64 {
        match param {
            Param::Length => &self.length,
            Param::Rho => &self.rho,
            Param::Alpha => &self.alpha,
            Param::Fn => &self.f_n,
            Param::Zeta => &self.zeta,
            Param::Phi => &self.phi,
        }
    }
}

impl std::ops::IndexMut<Param> for Params {
    fn index_mut(&mut self, param: Param) -> &mut f64 {
        match param {
            Param::Length => &mut self.length,
            Param::Rho => &mut self.rho,
            Param::Alpha => &mut self.alpha,
            Param::Fn => &mut self.f_n,
            Param::Zeta => &mut self.zeta,
            Param::Phi => &mut self.phi,
        }
    }
}

impl fmt::Display for Param {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for Param {
    type Err = String;
    /// The input with this key, or a message listing the keys.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Param::ALL
            .into_iter()
            .find(|p| p.name() == s)
            .ok_or_else(|| {
                let keys: Vec<&str> = Param::ALL.iter().map(|p| p.name()).collect();
                format!("unknown input {s:?}: one of {}", keys.join(", "))
            })
    }
}

/// How (f_n, ζ) map to (k, c) (docs/model.md §9, `normalization`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Normalization {
    /// S21–S22 as printed: the approximate model's true frequency is then √3·f_n.
    #[default]
    Supplementary,
    /// k and c chosen so that the correctly linearized approximate model
    /// oscillates at f_n with damping ratio ζ: k/3, and c = 4 I ζ (2π f_n) / (9 r²).
    Eigen,
}

/// Physical parameters of one RTW (SI units), derived from [`Params`].
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Physical {
    /// Rod length L.
    pub length: f64,
    /// Rod mass m = ρ L.
    pub m: f64,
    /// Connection offset from each tip, l_c = α L.
    pub l_c: f64,
    /// Rod inertia about its centre, I = m L² / 12.
    pub inertia: f64,
    /// Connection radius r = L/2 − l_c.
    pub r: f64,
    /// String stiffness k.
    pub k: f64,
    /// String damping c.
    pub c: f64,
    /// Slope φ.
    pub phi: f64,
    /// Gravity g.
    pub g: f64,
}

impl Physical {
    /// The physical parameters of `p` under `normalization` and gravity `g`.
    pub fn new(p: &Params, normalization: Normalization, g: f64) -> Self {
        let l = p.length;
        let m = p.rho * l;
        let l_c = p.alpha * l;
        let inertia = m * l * l / 12.0;
        let r = l / 2.0 - l_c;
        let w = (1.0 - 2.0 * p.alpha).powi(2);
        // S21, S22.
        let k_supp = 4.0 * PI * PI / 3.0 * p.rho * p.f_n * p.f_n * l / w;
        let c_supp = 8.0 * PI / 15.0 * p.zeta * p.rho * p.f_n * l / w;
        let (k, c) = match normalization {
            Normalization::Supplementary => (k_supp, c_supp),
            // The rotor mode has stiffness 3 k r² and decay rate 9 c r² / (4 I)
            // (docs/model.md §7): match ω = 2π f_n and σ/ω = ζ.
            Normalization::Eigen => (
                k_supp / 3.0,
                4.0 * inertia * p.zeta * 2.0 * PI * p.f_n / (9.0 * r * r),
            ),
        };
        Self {
            length: l,
            m,
            l_c,
            inertia,
            r,
            k,
            c,
            phi: p.phi,
            g,
        }
    }

    /// Height of the hub of the rigid star standing on two feet: h₀ = (L/2) cos(π/6).
    #[inline]
    pub(crate) fn standing_height(&self) -> f64 {
        0.5 * self.length * (PI / 6.0).cos()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_in_messages_are_written_as_a_person_writes_them() {
        let shown = |v: f64| Num(v).to_string();
        assert_eq!(shown(1e300), "1e300");
        assert_eq!(shown(-1e300), "-1e300");
        assert_eq!(shown(1e-300), "1e-300");
        assert_eq!(shown(2.5e-7), "2.5e-7");
        assert_eq!(shown(0.125), "0.125");
        assert_eq!(shown(500.0), "500");
        assert_eq!(shown(0.0), "0");
        assert_eq!(shown(f64::INFINITY), "inf");
        assert_eq!(shown(f64::NAN), "NaN");
        let e = ParamError::new("t_max", -1e300, "finite and > 0 (s)");
        assert_eq!(
            e.to_string(),
            "t_max = -1e300 is invalid: must be finite and > 0 (s)"
        );
    }

    #[test]
    fn fig7a_test_vector() {
        // docs/model.md §1: the article's round numbers.
        let ph = Physical::new(&Params::fig7a(), Normalization::Supplementary, 9.81);
        assert!((ph.m - 2.0).abs() < 1e-12);
        assert!((ph.l_c - 0.1).abs() < 1e-12);
        assert!((ph.inertia - 0.106_666_666_666_666_67).abs() < 1e-12);
        assert!((ph.r - 0.3).abs() < 1e-12);
        assert!((ph.k - 500.0067).abs() < 5e-5, "k = {}", ph.k);
        assert!((ph.c - 1.00100).abs() < 5e-6, "c = {}", ph.c);
    }

    #[test]
    fn s21_s22_agree_with_their_unreduced_forms() {
        // k = f_n² (4π)² I / (L − 2 l_c)², c = ζ (4/5) sqrt(I k / ((L − 2 l_c)²/4)).
        let p = Params::new(0.7, 3.1, 0.31, 4.2, 0.07, 0.2).unwrap();
        let ph = Physical::new(&p, Normalization::Supplementary, 9.81);
        let d = p.length - 2.0 * ph.l_c;
        let k = p.f_n.powi(2) * (4.0 * PI).powi(2) * ph.inertia / (d * d);
        let c = p.zeta * 0.8 * (ph.inertia * k / (d * d / 4.0)).sqrt();
        assert!((ph.k - k).abs() < 1e-9 * k);
        assert!((ph.c - c).abs() < 1e-9 * c);
        let e = Physical::new(&p, Normalization::Eigen, 9.81);
        assert!((e.k - k / 3.0).abs() < 1e-9 * k);
        // Eigen damping is the supplementary one scaled by 5/9.
        assert!((e.c - c * 5.0 / 9.0).abs() < 1e-9 * c);
    }

    #[test]
    fn every_param_round_trips_by_name_and_value() {
        for (i, param) in Param::ALL.into_iter().enumerate() {
            assert_eq!(param.name().parse::<Param>(), Ok(param));
            assert_eq!(param.to_string(), param.name());
            let mut p = Params::fig7a();
            p[param] = 0.01 * (i + 1) as f64;
            assert_eq!(p[param], 0.01 * (i + 1) as f64);
            // Only that field moved.
            for other in Param::ALL.into_iter().filter(|&o| o != param) {
                assert_eq!(p[other], Params::fig7a()[other]);
            }
            let e = param.check(f64::NAN).unwrap_err();
            assert_eq!((e.field, e.range), (param.name(), param.range()));
        }
        assert_eq!(
            "mu".parse::<Param>().unwrap_err(),
            "unknown input \"mu\": one of length, rho, alpha, fn, zeta, phi"
        );
    }

    #[test]
    fn invalid_inputs_name_field_and_range() {
        let e = Params::new(0.8, 2.5, 0.5, 3.0, 0.05, 0.1).unwrap_err();
        assert_eq!(e.field, "alpha");
        assert!(e.to_string().contains("[0, 0.49]"), "{e}");
        assert_eq!(
            Params::new(0.0, 2.5, 0.1, 3.0, 0.05, 0.1)
                .unwrap_err()
                .field,
            "length"
        );
        assert_eq!(
            Params::new(0.8, -1.0, 0.1, 3.0, 0.05, 0.1)
                .unwrap_err()
                .field,
            "rho"
        );
        assert_eq!(
            Params::new(0.8, 1.0, 0.1, f64::NAN, 0.05, 0.1)
                .unwrap_err()
                .field,
            "fn"
        );
        assert_eq!(
            Params::new(0.8, 1.0, 0.1, 3.0, -0.1, 0.1)
                .unwrap_err()
                .field,
            "zeta"
        );
        assert_eq!(
            Params::new(0.8, 1.0, 0.1, 3.0, 0.1, 1.6).unwrap_err().field,
            "phi"
        );
        assert_eq!(
            Params::new(0.8, 1.0, -0.01, 3.0, 0.1, 0.1)
                .unwrap_err()
                .field,
            "alpha"
        );
    }
}
