//! The indices as a reader sees them: a Markdown table, a warning when an
//! interval is too wide to rank the inputs by, and what a negative S1 means.
//! `rtw-scan sensitivity` prints these and `rtw.sensitivity` warns with the
//! same words, so the rule lives here once.

use super::Index;

/// A 95 % half-width above this makes an index too rough to rank inputs by
/// (the indices lie in [0, 1]): a Saltelli design of a few hundred base rows
/// gives ±0.8 on a class that is 2 % of the runs.
pub const WIDE: f64 = 0.1;

/// The warning when any 95 % half-width (of S1 or ST) is above [`WIDE`],
/// naming how many and the widest; `None` when all are within it.
pub fn wide_warning(indices: &[Index]) -> Option<String> {
    let widths = indices.iter().flat_map(|r| {
        [("S1", r.s1_conf), ("ST", r.st_conf)]
            .into_iter()
            .filter(|(_, w)| w.is_finite())
            .map(move |(which, w)| (r, which, w))
    });
    let wide: Vec<_> = widths.filter(|(_, _, w)| *w > WIDE).collect();
    let (r, which, w) = wide.iter().max_by(|a, b| a.2.total_cmp(&b.2)).copied()?;
    Some(format!(
        "{} 95 % half-widths are above {WIDE} (the widest: {which} of {} to {}, ± {w:.3}): \
         these indices cannot rank the inputs; run the scan with more samples",
        wide.len(),
        r.output,
        r.parameter
    ))
}

/// The indices as a Markdown table, ± the 95 % half-widths, with a note
/// when an S1 is negative within its half-width (an index is never below
/// 0; the estimator's noise is).
pub fn markdown(method: &str, rows: &[Index]) -> String {
    let mut s = format!(
        "Sobol indices ({method}), ± 95 % bootstrap half-width\n\n| output | parameter | S1 | ST |\n|---|---|---:|---:|\n"
    );
    for r in rows {
        let st = if r.st.is_nan() {
            "–".to_string()
        } else {
            format!("{:.3} ± {:.3}", r.st, r.st_conf)
        };
        s.push_str(&format!(
            "| {} | {} | {:.3} ± {:.3} | {st} |\n",
            r.output, r.parameter, r.s1, r.s1_conf
        ));
    }
    if rows.iter().any(|r| r.s1 < 0.0 && r.s1 + r.s1_conf >= 0.0) {
        s.push_str(
            "\nA negative S1 within its half-width of 0 is the estimator's noise: \
             the index itself is never below 0, read it as 0.\n",
        );
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn index(s1: f64, s1_conf: f64, st_conf: f64) -> Index {
        Index {
            output: "crawl".into(),
            parameter: "alpha",
            s1,
            s1_conf,
            st: 0.5,
            st_conf,
        }
    }

    #[test]
    fn a_half_width_above_a_tenth_is_warned_of_naming_the_widest() {
        assert_eq!(wide_warning(&[index(0.2, 0.05, 0.1)]), None);
        assert_eq!(wide_warning(&[index(0.2, 0.05, f64::NAN)]), None);
        let w = wide_warning(&[index(0.2, 0.05, 0.11), index(0.2, 0.76, 0.3)]).unwrap();
        assert!(w.contains("3 95 % half-widths are above 0.1"), "{w}");
        assert!(w.contains("S1 of crawl to alpha, ± 0.760"), "{w}");
    }

    #[test]
    fn a_negative_s1_within_its_half_width_is_noted_as_noise() {
        let note = "estimator's noise";
        assert!(!markdown("saltelli", &[index(0.2, 0.05, 0.01)]).contains(note));
        assert!(!markdown("saltelli", &[index(-0.2, 0.05, 0.01)]).contains(note));
        let md = markdown("saltelli", &[index(-0.02, 0.05, 0.01)]);
        assert!(md.contains(note), "{md}");
        assert!(
            md.contains("| crawl | alpha | -0.020 ± 0.050 | 0.500 ± 0.010 |"),
            "{md}"
        );
    }
}
