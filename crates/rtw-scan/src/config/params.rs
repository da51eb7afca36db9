//! The parameter vocabulary of rtw-scan, in one place: the six inputs a
//! scan samples ([`Input`], the `[params]` keys and the first Parquet
//! columns) and the parameters a bifurcation sweep can vary ([`SweepParam`]:
//! the inputs and `s`). Config parsing, `--set`, sweeps and the checks of
//! values read back from files all name, read, write and validate a
//! parameter through these types.
//!
//! The valid ranges live in rtw-model only ([`Params::validate`],
//! [`Options::validate`]): a value is checked by setting it on a valid point
//! and validating that point. When rtw-model gains its own parameter
//! vocabulary, the bodies of [`Input::name`], [`Input::get`], [`Input::set`]
//! and [`Input::check`] (and [`SweepParam`]'s) delegate to it here, and
//! nothing else changes.

use anyhow::{Result, bail};
use rtw_model::{Options, ParamError, Params};

/// One of the six inputs of docs/model.md §1.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Input {
    /// Rod length L (m).
    Length,
    /// Mass per length ρ of a rod (kg/m).
    Rho,
    /// Connection ratio α.
    Alpha,
    /// Eigen-frequency f_n of the normalization (Hz; key `fn`).
    Fn,
    /// Damping ratio ζ.
    Zeta,
    /// Slope angle φ (rad).
    Phi,
}

impl Input {
    /// The inputs in the order used everywhere: grid product order, sampling
    /// order, column order, and the index of `ScanConfig::params`.
    pub const ALL: [Input; 6] = [
        Self::Length,
        Self::Rho,
        Self::Alpha,
        Self::Fn,
        Self::Zeta,
        Self::Phi,
    ];

    /// The key of `[params]`, of the Parquet column and of the CLI flag.
    pub fn name(self) -> &'static str {
        match self {
            Self::Length => "length",
            Self::Rho => "rho",
            Self::Alpha => "alpha",
            Self::Fn => "fn",
            Self::Zeta => "zeta",
            Self::Phi => "phi",
        }
    }

    /// This input's value in `p`.
    pub fn get(self, p: &Params) -> f64 {
        match self {
            Self::Length => p.length,
            Self::Rho => p.rho,
            Self::Alpha => p.alpha,
            Self::Fn => p.f_n,
            Self::Zeta => p.zeta,
            Self::Phi => p.phi,
        }
    }

    /// Sets this input of `p` to `v` (unchecked: see [`Self::check`]).
    pub fn set(self, p: &mut Params, v: f64) {
        let slot = match self {
            Self::Length => &mut p.length,
            Self::Rho => &mut p.rho,
            Self::Alpha => &mut p.alpha,
            Self::Fn => &mut p.f_n,
            Self::Zeta => &mut p.zeta,
            Self::Phi => &mut p.phi,
        };
        *slot = v;
    }

    /// Checks one value of this input against docs/model.md §1 via
    /// [`Params::validate`]; the ranges of the inputs do not depend on each
    /// other, so any valid point serves as the rest.
    pub fn check(self, v: f64) -> Result<(), ParamError> {
        let mut p = Params::fig7a();
        self.set(&mut p, v);
        p.validate()
    }
}

/// A parameter a bifurcation sweep can vary: an input of docs/model.md §1 or
/// `s`, the strings' rest-length ratio (`strings.rest_length_ratio`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SweepParam {
    /// One of the six inputs.
    Input(Input),
    /// `strings.rest_length_ratio`, named `s`.
    RestLengthRatio,
}

impl SweepParam {
    /// Every sweepable parameter, the inputs first.
    pub const ALL: [SweepParam; 7] = [
        Self::Input(Input::Length),
        Self::Input(Input::Rho),
        Self::Input(Input::Alpha),
        Self::Input(Input::Fn),
        Self::Input(Input::Zeta),
        Self::Input(Input::Phi),
        Self::RestLengthRatio,
    ];

    /// Parses a name of [`Self::ALL`]; the error names `--param` and the choices.
    pub fn parse(name: &str) -> Result<Self> {
        match Self::ALL.into_iter().find(|p| p.name() == name) {
            Some(p) => Ok(p),
            None => bail!(
                "--param: unknown parameter `{name}`: must be one of {}",
                Self::ALL.map(Self::name).join(", ")
            ),
        }
    }

    /// The name of `--param` and of the sweep files' `param` column.
    pub fn name(self) -> &'static str {
        match self {
            Self::Input(i) => i.name(),
            Self::RestLengthRatio => "s",
        }
    }

    /// The parameters and options at value `v` of this parameter, the rest
    /// from `base` and `options`; an invalid `v` is named by
    /// [`Params::validate`] or [`Options::validate`].
    pub fn at(
        self,
        base: &Params,
        options: &Options,
        v: f64,
    ) -> Result<(Params, Options), ParamError> {
        let (mut p, mut o) = (*base, *options);
        match self {
            Self::Input(i) => i.set(&mut p, v),
            Self::RestLengthRatio => o.strings.rest_length_ratio = v,
        }
        p.validate()?;
        o.validate()?;
        Ok((p, o))
    }

    /// Checks a bound of a sweep given with `flag`.
    pub(crate) fn check(self, base: &Params, options: &Options, v: f64, flag: &str) -> Result<()> {
        match self.at(base, options, v) {
            Ok(_) => Ok(()),
            Err(e) => bail!(
                "{flag}: {v} is invalid for --param {}: {} must be {}",
                self.name(),
                e.field,
                e.range
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inputs_read_back_what_they_set_and_name_the_params_fields() {
        let mut p = Params::fig7a();
        for (k, i) in Input::ALL.into_iter().enumerate() {
            i.set(&mut p, 0.01 * (k + 1) as f64);
        }
        assert_eq!(
            Input::ALL.map(|i| i.get(&p)),
            [0.01, 0.02, 0.03, 0.04, 0.05, 0.06]
        );
        assert_eq!(
            (p.length, p.rho, p.alpha, p.f_n, p.zeta, p.phi),
            (0.01, 0.02, 0.03, 0.04, 0.05, 0.06)
        );
        // An out-of-range value is named by rtw-model with the field's name.
        let e = Input::Phi.check(2.0).unwrap_err();
        assert_eq!(e.field, "phi");
        assert!(Input::Alpha.check(0.2).is_ok());
    }

    #[test]
    fn sweep_params_parse_and_name_each_other() {
        for p in SweepParam::ALL {
            assert_eq!(SweepParam::parse(p.name()).unwrap(), p);
        }
        let e = SweepParam::parse("mu").unwrap_err().to_string();
        assert!(
            e.contains("--param") && e.contains("`mu`") && e.contains("phi, s"),
            "{e}"
        );
    }
}
