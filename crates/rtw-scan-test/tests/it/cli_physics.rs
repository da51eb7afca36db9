//! End-to-end tests with the real `rtw_model::simulate`: they check that the
//! physics runs through the CLI (no panics, no `diverged` rows on the smoke
//! scan, a trace file), not what the physics says. The scan machinery itself
//! is tested with the fake simulator in `tests/cli.rs`.

use crate::common::*;
use arrow_array::cast::AsArray;
use arrow_array::types::Float64Type;

const FIG7A: [&str; 13] = [
    "simulate", "--length", "0.8", "--rho", "2.5", "--alpha", "0.125", "--fn", "3.269", "--zeta",
    "0.0514", "--phi", "0.15",
];

#[test]
fn simulate_fig7a_reports_every_metric() {
    let o = run_ok(&[&FIG7A[..], &["--json"]].concat());
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    let label = v["outcome"].as_str().unwrap();
    assert!(
        ["skip", "walk", "crawl", "collapse", "stall"].contains(&label),
        "outcome {label}: {v}"
    );
    assert!(v["message"].is_null(), "{v}");
    let t_end = v["t_end"].as_f64().unwrap();
    assert!(t_end > 0.0 && t_end <= 20.0, "t_end {t_end}");
    assert!(v["steps"].as_u64().unwrap() > 0 && v["rhs_evals"].as_u64().unwrap() > 0);
    let fractions: f64 = ["nlsp", "slsp", "dlsp", "tlsp"]
        .iter()
        .map(|k| v[k].as_f64().unwrap())
        .sum();
    assert!(
        (fractions - 1.0).abs() < 1e-6,
        "fractions sum to {fractions}"
    );
    assert!((v["m"].as_f64().unwrap() - 2.0).abs() < 1e-12);
}

#[test]
fn simulate_with_sets_and_a_trace_file() {
    let dir = tempfile::tempdir().unwrap();
    let trace = dir.path().join("trace.parquet");
    let o = run_ok(
        &[
            &FIG7A[..],
            &[
                "--set",
                "t_max=2",
                "--set",
                "trace_dt=0.01",
                "--set",
                "initial.omega=-3",
                "--set",
                "contact.mu=0.8",
                "--set",
                "method=dop853",
                "--trace",
                trace.to_str().unwrap(),
            ],
        ]
        .concat(),
    );
    assert!(stdout(&o).contains("[outcome]"));
    let b = batches(&trace);
    let n: usize = b.iter().map(|b| b.num_rows()).sum();
    assert!(n > 100, "{n} trace rows");
    let names = column_names(&trace);
    for c in [
        "t",
        "x_a",
        "theta_c",
        "omega_b",
        "contact_a",
        "contact_state",
        "kinetic",
        "impact_loss",
    ] {
        assert!(names.iter().any(|n| n == c), "trace lacks {c}");
    }
    let t = b[0]
        .column_by_name("t")
        .unwrap()
        .as_primitive::<Float64Type>();
    assert!(
        t.values().windows(2).all(|w| w[0] <= w[1]),
        "time runs forward"
    );
    assert!(t.value(t.len() - 1) <= 2.0 + 1e-9);
}

#[test]
fn smoke_scan_runs_without_diverged_rows_and_independent_of_threads() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (dir.path().join("a"), dir.path().join("b"));
    let smoke = config("smoke");
    let smoke = smoke.to_str().unwrap();
    let o = run_ok(&["run", smoke, "--out", a.to_str().unwrap(), "--threads", "1"]);
    run_ok(&["run", smoke, "--out", b.to_str().unwrap(), "--threads", "2"]);
    let ra = rows(&a.join("samples.parquet"));
    assert_eq!(ra.len(), 6);
    for r in &ra {
        // A message without a failure is a panic's (a failure's message
        // says what the failure means).
        assert!(
            r.contains(&"message=null".to_string()) || !r.contains(&"failure=null".to_string()),
            "a sample panicked: {r:?}"
        );
        assert!(
            !r.contains(&"outcome=diverged".to_string()),
            "diverged: {r:?}"
        );
    }
    assert_eq!(ra, rows(&b.join("samples.parquet")));
    assert!(stdout(&o).contains("| **stable** |"));
    assert!(a.join("summary.json").exists() && a.join("summary.md").exists());
}

#[test]
fn simulate_takes_a_variant_like_run() {
    // `--variant FILE` layers the variant's [simulation] table as `run` does:
    // the same run as taking the file as the config, not the default model's.
    let literal = config("variants/literal");
    let literal = literal.to_str().unwrap();
    let json = |extra: &[&str]| -> serde_json::Value {
        let o = run_ok(&[&FIG7A[..], extra, &["--json"]].concat());
        serde_json::from_str(&stdout(&o)).unwrap()
    };
    let by_variant = json(&["--variant", literal]);
    let by_config = json(&["--config", literal]);
    let default = json(&[]);
    for k in ["outcome", "speed", "steps", "slsp", "dlsp"] {
        assert_eq!(by_variant[k], by_config[k], "{k}");
    }
    assert_eq!(by_variant["outcome"], "skip", "{by_variant}");
    assert_eq!(default["outcome"], "walk", "{default}");
}

#[test]
fn simulate_warns_when_the_energy_balance_is_off() {
    // At the stiff end of the range the default tolerance leaves a 2.2 %
    // energy-balance error (Fig. 7(a): 0.03 %): `simulate` says so, in text
    // and JSON modes alike (on stderr, so the JSON stays the row), and the
    // warning goes away at the tighter tolerance it suggests. Measured with
    // strings of natural length s = 0.85 (at the fitted default 0.8875 the
    // same point is off by 1.6 %): the test is about the warning, so it
    // keeps that model.
    let stiff = [
        "simulate",
        "--length",
        "0.8",
        "--rho",
        "2.5",
        "--alpha",
        "0.4",
        "--fn",
        "100",
        "--zeta",
        "0",
        "--phi",
        "0.3",
        "--set",
        "strings.rest_length_ratio=0.85",
    ];
    for extra in [&["--json"][..], &[]] {
        let o = run_ok(&[&stiff[..], extra].concat());
        let err = stderr(&o);
        assert!(
            err.contains("warning: the energy balance is off by 2.")
                && err.contains("above the bound of 1 %")
                && err.contains("rtol=1e-6"),
            "{err}"
        );
    }
    let o = run_ok(&[&stiff[..], &["--set", "rtol=1e-6"]].concat());
    assert!(!stderr(&o).contains("energy balance"), "{}", stderr(&o));
    let o = run_ok(&FIG7A);
    assert!(!stderr(&o).contains("energy balance"), "{}", stderr(&o));
}
