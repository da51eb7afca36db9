//! A setting whose value is one of a closed set of names (`method =
//! "cmaes"`, `gait = "walk"`): one reader and one error for every such
//! setting, so that each refuses a name it does not know in the same words,
//! listing what it takes.

use anyhow::{Result, bail};

/// The choice `text` names among `choices` (each its name and value),
/// otherwise the error `NAME: "TEXT" is invalid: must be one of "A", "B"`,
/// `name` being the setting as the caller spells it.
pub fn choice<T: Copy>(name: &str, text: &str, choices: &[(&str, T)]) -> Result<T> {
    match choices.iter().find(|(n, _)| *n == text) {
        Some(&(_, v)) => Ok(v),
        None => bail!("{name}: {text:?} is invalid: must be {}", one_of(choices)),
    }
}

/// `one of "A", "B"` (or `"A"` when there is one): the names of `choices`
/// as [`choice`]'s error lists them.
pub fn one_of<T>(choices: &[(&str, T)]) -> String {
    let names: Vec<String> = choices.iter().map(|(n, _)| format!("{n:?}")).collect();
    match names.len() {
        1 => names[0].clone(),
        _ => format!("one of {}", names.join(", ")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_known_name_is_its_value_and_an_unknown_one_is_refused_listing_all() {
        let c = [("cmaes", 1), ("sobol", 2)];
        assert_eq!(choice("method", "sobol", &c).unwrap(), 2);
        let e = choice("method", "grid", &c).unwrap_err().to_string();
        assert_eq!(
            e,
            "method: \"grid\" is invalid: must be one of \"cmaes\", \"sobol\""
        );
        // Names are matched exactly, as written.
        assert!(choice("method", "CMAES", &c).is_err());
        assert!(choice("method", " cmaes", &c).is_err());
        assert_eq!(one_of(&[("walk", ())]), "\"walk\"");
    }
}
