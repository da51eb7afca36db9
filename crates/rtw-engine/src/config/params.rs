//! The parameter vocabulary of rtw-scan, in one place: the six parameters
//! a scan samples (rtw-model's [`Param`], the `[params]` keys and the first
//! Parquet columns) and the parameters a bifurcation sweep can vary ([`SweepParam`]:
//! the inputs and `s`). Config parsing, `--set`, sweeps and the checks of
//! values read back from files all name, read, write and validate a
//! parameter through these types.
//!
//! A design's six parameters are rtw-model's [`Param`], under the one name
//! the model, the paper (docs/model.md §1, "Parameters") and the `[params]`
//! table use (their names, ranges and checks live there only); `s` is
//! checked through [`Options::validate`].

use anyhow::{Result, bail};
use rtw_model::{Num, Options, Param, ParamError, Params};

/// The six inputs (L, ρ, α, f_n, ζ, φ) as validated [`Params`]; an invalid
/// one is named `{prefix}{name}` (`--alpha` on the command line, `alpha`
/// from Python) with its value and valid range.
pub fn checked_params(values: [f64; 6], prefix: &str) -> Result<Params> {
    let [length, rho, alpha, f_n, zeta, phi] = values;
    Params::new(length, rho, alpha, f_n, zeta, phi).map_err(|e| {
        anyhow::anyhow!(
            "{prefix}{}: {} is invalid: must be {}",
            e.field,
            Num(e.value),
            e.range
        )
    })
}

/// A parameter a bifurcation sweep can vary: an input of docs/model.md §1 or
/// `s`, the strings' rest-length ratio (`strings.rest_length_ratio`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SweepParam {
    /// One of the six parameters of a design.
    Param(Param),
    /// `strings.rest_length_ratio`, named `s`.
    RestLengthRatio,
}

impl SweepParam {
    /// Every sweepable parameter, the inputs first.
    pub const ALL: [SweepParam; 7] = [
        Self::Param(Param::Length),
        Self::Param(Param::Rho),
        Self::Param(Param::Alpha),
        Self::Param(Param::Fn),
        Self::Param(Param::Zeta),
        Self::Param(Param::Phi),
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
            Self::Param(i) => i.name(),
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
            Self::Param(i) => p[i] = v,
            Self::RestLengthRatio => o.strings.rest_length_ratio = v,
        }
        p.validate()?;
        o.validate()?;
        Ok((p, o))
    }

    /// Checks a bound of a sweep given with `flag`.
    pub fn check(self, base: &Params, options: &Options, v: f64, flag: &str) -> Result<()> {
        match self.at(base, options, v) {
            Ok(_) => Ok(()),
            Err(e) => bail!(
                "{flag}: {} is invalid for --param {}: {} must be {}",
                Num(v),
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
        for (k, i) in Param::ALL.into_iter().enumerate() {
            p[i] = 0.01 * (k + 1) as f64;
        }
        assert_eq!(
            Param::ALL.map(|i| p[i]),
            [0.01, 0.02, 0.03, 0.04, 0.05, 0.06]
        );
        assert_eq!(
            (p.length, p.rho, p.alpha, p.f_n, p.zeta, p.phi),
            (0.01, 0.02, 0.03, 0.04, 0.05, 0.06)
        );
        // An out-of-range value is named by rtw-model with the field's name.
        let e = Param::Phi.check(2.0).unwrap_err();
        assert_eq!(e.field, "phi");
        assert!(Param::Alpha.check(0.2).is_ok());
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
