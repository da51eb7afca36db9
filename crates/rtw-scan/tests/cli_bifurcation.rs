//! `rtw-scan bifurcation` through the binary, with the real step map: a tiny
//! φ sweep at the Fig. 7(a) point, its two Parquet files, and bad flags.

mod common;

use common::*;

/// Columns of the per-value and per-step files (`bifurcation::POINT_COLUMNS`,
/// `STEP_COLUMNS`), spelled out so a renamed column fails here.
const POINT_COLUMNS: [&str; 16] = [
    "param",
    "value",
    "label",
    "period",
    "floquet_max",
    "mu_re",
    "mu_im",
    "stable",
    "restarted",
    "residual",
    "newton_iterations",
    "newton_error",
    "failure",
    "transient",
    "record",
    "wall_time_s",
];
const STEP_COLUMNS: [&str; 7] = [
    "param",
    "value",
    "k",
    "omega",
    "step_time",
    "advance",
    "label",
];

fn field<'a>(row: &'a [String], name: &str) -> &'a str {
    let prefix = format!("{name}=");
    row.iter()
        .find_map(|c| c.strip_prefix(&prefix))
        .unwrap_or_else(|| panic!("no {name} in {row:?}"))
}

#[test]
fn a_three_point_phi_sweep_writes_both_files() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("phi.parquet");
    let o = run_ok(&[
        "bifurcation",
        "--from",
        "0.14",
        "--to",
        "0.16",
        "--points",
        "3",
        "--transient",
        "60",
        "--record",
        "4",
        "--out",
        out.to_str().unwrap(),
    ]);
    let steps = dir.path().join("phi.steps.parquet");
    assert_eq!(column_names(&out), POINT_COLUMNS);
    assert_eq!(column_names(&steps), STEP_COLUMNS);
    let points = rows(&out);
    assert_eq!(points.len(), 3);
    for (row, phi) in points.iter().zip(["0.14", "0.15", "0.16"]) {
        assert_eq!(field(row, "param"), "phi");
        assert!(field(row, "value").starts_with(phi), "{row:?}");
        // The article's walk (docs/model.md §9, default model): a stable period-1
        // gait, found by continuation, no restart. At φ = 0.15 its largest
        // multiplier is 0.833 (examples/cycle.rs, the variational Jacobian
        // agreeing with central differences to 5e-8); a 0.01 change of φ
        // keeps it inside the unit circle.
        assert_eq!(field(row, "label"), "walk");
        assert_eq!(field(row, "period"), "1");
        assert_eq!(field(row, "stable"), "true");
        assert_eq!(field(row, "restarted"), "false");
        assert_eq!(field(row, "failure"), "null");
        let mu: f64 = field(row, "floquet_max").parse().unwrap();
        assert!((0.5..1.0).contains(&mu), "{row:?}");
        let residual: f64 = field(row, "residual").parse().unwrap();
        assert!(residual <= 1e-9, "{row:?}");
    }
    let mu15: f64 = field(&points[1], "floquet_max").parse().unwrap();
    assert!((mu15 - 0.833).abs() < 1e-3, "{mu15}");
    // Four recorded steps per value, k = 0..3; a period-1 walk repeats its
    // post-impact ω to the period tolerance.
    let st = rows(&steps);
    assert_eq!(st.len(), 12);
    for (i, row) in st.iter().enumerate() {
        assert_eq!(field(row, "k"), (i % 4).to_string());
        assert_eq!(field(row, "label"), "walk");
        let t: f64 = field(row, "step_time").parse().unwrap();
        assert!(t > 0.0 && t < 1.0, "{row:?}");
    }
    let w: Vec<f64> = st[4..8]
        .iter()
        .map(|r| field(r, "omega").parse().unwrap())
        .collect();
    assert!(
        w.iter().all(|x| (x - w[0]).abs() < 1e-3 * w[0].abs()),
        "{w:?}"
    );
    // The summary is printed and written beside the file.
    let md = std::fs::read_to_string(dir.path().join("phi.md")).unwrap();
    assert_eq!(stdout(&o), md);
    assert!(
        md.contains("| 0.1400 | 0.1600 | 3 | walk | 1 | yes |"),
        "{md}"
    );
}

#[test]
fn bad_flags_name_the_flag_and_the_range() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x.parquet");
    let out = out.to_str().unwrap();
    run_err(
        &["bifurcation", "--param", "mu", "--out", out],
        &[
            "--param: unknown parameter `mu`",
            "length, rho, alpha, fn, zeta, phi, s",
        ],
    );
    run_err(
        &["bifurcation", "--to", "2", "--out", out],
        &["--to: 2 is invalid for --param phi: phi must be"],
    );
    run_err(
        &[
            "bifurcation",
            "--param",
            "s",
            "--from",
            "0.8",
            "--to",
            "1.2",
            "--out",
            out,
        ],
        &["--to: 1.2 is invalid for --param s: strings.rest_length_ratio must be"],
    );
    run_err(
        &["bifurcation", "--points", "1", "--out", out],
        &["--points: 1 is invalid: must be an integer >= 2"],
    );
    run_err(
        &["bifurcation", "--record", "1", "--out", out],
        &["--record: 1 is invalid: must be an integer >= 2"],
    );
    run_err(
        &["bifurcation", "--alpha", "0.6", "--out", out],
        &["--alpha: 0.6 is invalid: must be"],
    );
    run_err(
        &["bifurcation", "--set", "contact.mu=2", "--out", out],
        &["simulation.contact.mu: 2 is invalid"],
    );
    assert!(!std::path::Path::new(out).exists());
}
