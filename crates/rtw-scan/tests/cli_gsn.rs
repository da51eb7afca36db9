//! `rtw-scan simulate` and `run` with the gait sensitivity norm
//! (`robustness.gsn`, docs/robustness.md), with the real simulator.

mod common;

use common::*;

const FIG7A: [&str; 13] = [
    "simulate", "--length", "0.8", "--rho", "2.5", "--alpha", "0.125", "--fn", "3.269", "--zeta",
    "0.0514", "--phi", "0.15",
];

fn json(extra: &[&str]) -> serde_json::Value {
    let o = run_ok(&[&FIG7A[..], &["--json"], extra].concat());
    serde_json::from_str(&stdout(&o)).unwrap()
}

#[test]
fn gsn_is_in_the_json_row_only_when_asked_for_and_changes_nothing_else() {
    let flat = json(&[]);
    assert!(flat.get("gsn").is_none(), "{flat}");
    let v = json(&["--set", "robustness.gsn=true"]);
    // The Fig. 7(a) walk's norm (crates/rtw-model/src/cycles/gsn.rs checks
    // it against the full simulation's response to a small step).
    let g = v["gsn"].as_f64().unwrap();
    assert!((g - 4.6349).abs() < 1e-3, "{v}");
    assert!(v.get("step_down_max").is_none(), "{v}");
    for (key, value) in flat.as_object().unwrap() {
        if key != "wall_time_s" {
            assert_eq!(&v[key], value, "{key}");
        }
    }
    // Both measures: step_down_max first, then gsn, the same values.
    let both = json(&[
        "--set",
        "robustness.gsn=true",
        "--set",
        "robustness.step_down=true",
    ]);
    let keys: Vec<_> = both.as_object().unwrap().keys().cloned().collect();
    assert_eq!(keys[keys.len() - 2..], ["step_down_max", "gsn"]);
    assert_eq!(both["gsn"], v["gsn"]);
}

#[test]
fn a_scan_has_the_gsn_column_only_when_asked_for_and_the_same_rows_besides() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write(dir.path(), "s.toml", &paper_like(12, 7));
    let (plain, with) = (dir.path().join("plain"), dir.path().join("gsn"));
    let args = |out| ["run", &cfg, "--out", s(out), "--quiet", "--chunk-size", "5"];
    run_ok(&args(&plain));
    run_ok(&[&args(&with)[..], &["--set", "robustness.gsn=true"]].concat());
    let (plain, with) = (plain.join("samples.parquet"), with.join("samples.parquet"));
    let names = column_names(&plain);
    let mut expected = names.clone();
    expected.push("gsn".into());
    assert_eq!(column_names(&with), expected);
    let (a, b) = (rows(&plain), rows(&with));
    let mut computed = 0;
    for (a, b) in a.iter().zip(&b) {
        assert_eq!(a[..], b[..a.len()]);
        let label = &a[names.iter().position(|n| n == "outcome").unwrap()];
        let is_stable = ["outcome=skip", "outcome=walk", "outcome=crawl"].contains(&label.as_str());
        let value = &b[a.len()];
        if !is_stable {
            assert_eq!(value, "gsn=null", "{label}");
        }
        computed += (value != "gsn=null") as usize;
    }
    assert!(computed > 0);
}
