//! `rtw-scan simulate` over a step down and with the robustness measures
//! (`robustness.step_down`, `robustness.gsn`; docs/robustness.md), with the
//! real simulator.

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
fn step_down_max_is_in_the_json_row_only_when_asked_for() {
    let flat = json(&[]);
    assert!(flat.get("step_down_max").is_none(), "{flat}");
    let v = json(&["--set", "robustness.step_down=true"]);
    let h = v["step_down_max"].as_f64().unwrap();
    assert!(h > 0.0, "{v}");
    // Asking for it changes nothing else in the row.
    for (key, value) in flat.as_object().unwrap() {
        if key != "wall_time_s" {
            assert_eq!(&v[key], value, "{key}");
        }
    }
}

#[test]
fn step_down_h50_is_in_the_json_row_only_when_asked_for() {
    // A positive height, alone in the row (not step_down_max); asking for
    // it changes nothing else in the row; a non-boolean is refused naming
    // the key.
    let flat = json(&[]);
    assert!(flat.get("step_down_h50").is_none(), "{flat}");
    let v = json(&["--set", "robustness.step_down_h50=true"]);
    let h = v["step_down_h50"].as_f64().unwrap();
    assert!(h > 0.0, "{v}");
    assert!(v.get("step_down_max").is_none(), "{v}");
    for (key, value) in flat.as_object().unwrap() {
        if key != "wall_time_s" {
            assert_eq!(&v[key], value, "{key}");
        }
    }
    run_err(
        &[&FIG7A[..], &["--set", "robustness.step_down_h50=2"]].concat(),
        &["step_down_h50"],
    );
}

#[test]
fn terrain_options_run_over_a_step_and_are_validated() {
    let flat = json(&[]);
    let zero = json(&[
        "--set",
        "terrain.step_height=0",
        "--set",
        "terrain.step_at=3",
    ]);
    assert_eq!(zero["t_end"], flat["t_end"]);
    let step = json(&[
        "--set",
        "terrain.step_height=0.05",
        "--set",
        "terrain.step_at=3",
    ]);
    assert_ne!(step["t_end"], flat["t_end"]);
    run_err(
        &[&FIG7A[..], &["--set", "terrain.step_height=-0.1"]].concat(),
        &[
            "simulation.terrain.step_height: -0.1 is invalid",
            "in [0, 1000]",
        ],
    );
    run_err(
        &[&FIG7A[..], &["--set", "terrain.step_at=0"]].concat(),
        &["simulation.terrain.step_at: 0 is invalid", "(0, 1e6]"],
    );
}

#[test]
fn a_scan_has_the_step_down_column_only_when_asked_for_and_the_same_rows_besides() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write(dir.path(), "s.toml", &paper_like(12, 7));
    let (plain, step) = (dir.path().join("plain"), dir.path().join("step"));
    // Small chunks: the column must survive the chunks' concatenation.
    run_ok(&[
        "run",
        &cfg,
        "--out",
        s(&plain),
        "--quiet",
        "--chunk-size",
        "5",
    ]);
    run_ok(&[
        "run",
        &cfg,
        "--out",
        s(&step),
        "--quiet",
        "--chunk-size",
        "5",
        "--set",
        "robustness.step_down=true",
    ]);
    let (plain, step) = (plain.join("samples.parquet"), step.join("samples.parquet"));
    let names = column_names(&plain);
    assert!(!names.iter().any(|n| n == "step_down_max"));
    let mut with = names.clone();
    with.push("step_down_max".into());
    assert_eq!(column_names(&step), with);
    let (a, b) = (rows(&plain), rows(&step));
    assert_eq!(a.len(), 12);
    let mut stable = 0;
    for (a, b) in a.iter().zip(&b) {
        assert_eq!(a[..], b[..a.len()]);
        let label = &a[names.iter().position(|n| n == "outcome").unwrap()];
        let value = &b[a.len()];
        let is_stable = ["outcome=skip", "outcome=walk", "outcome=crawl"].contains(&label.as_str());
        stable += is_stable as usize;
        assert_eq!(value == "step_down_max=null", !is_stable, "{label} {value}");
    }
    assert!(stable > 0);
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
    // Both measures: the same gsn.
    let both = json(&[
        "--set",
        "robustness.gsn=true",
        "--set",
        "robustness.step_down=true",
    ]);
    assert!(both["step_down_max"].as_f64().unwrap() > 0.0, "{both}");
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
