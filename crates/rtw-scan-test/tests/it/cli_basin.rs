//! `rtw-scan basin` through the binary, with the real step map: a 2 × 2
//! slice of the Fig. 7(a) walk (cheap points: two that start with a tip in
//! the ground, the fixed point itself, and a far point that fails), its
//! columns, the same rows on any thread count, bad axes named with their
//! range, and the refusal to write over a file it did not make.

use crate::common::*;

/// The slice file's columns, spelled out so a renamed column fails here.
const COLUMNS: [&str; 10] = [
    "x", "y", "x_value", "y_value", "outcome", "label", "failure", "steps", "distance", "period",
];

fn field<'a>(row: &'a [String], name: &str) -> &'a str {
    let prefix = format!("{name}=");
    row.iter()
        .find_map(|c| c.strip_prefix(&prefix))
        .unwrap_or_else(|| panic!("no {name} in {row:?}"))
}

fn slice(out: &str, threads: &str) -> std::process::Output {
    run_ok(&[
        "basin",
        "--x",
        "omega_a:0:40:2",
        "--y",
        "theta_b:-1.5:0:2",
        "--threads",
        threads,
        "--out",
        out,
    ])
}

#[test]
fn a_two_by_two_slice_writes_its_grid_the_same_on_any_thread_count() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("b.parquet");
    let o = slice(s(&out), "1");
    assert!(
        stdout(&o).contains("gait: walk, period 1"),
        "{}",
        stdout(&o)
    );
    assert!(
        stdout(&o).contains("4 points: returns 1, survives 0, fails 1, infeasible 2"),
        "{}",
        stdout(&o)
    );
    assert_eq!(column_names(&out), COLUMNS);
    let r = rows(&out);
    assert_eq!(r.len(), 4);
    // Row-major, y outer: (0, −1.5), (40, −1.5), (0, 0), (40, 0).
    let xy: Vec<(&str, &str)> = r.iter().map(|r| (field(r, "x"), field(r, "y"))).collect();
    assert_eq!(
        xy,
        [
            ("0.0", "-1.5"),
            ("40.0", "-1.5"),
            ("0.0", "0.0"),
            ("40.0", "0.0")
        ]
    );
    // θ_b turned by −1.5 rad puts a tip of rod b in the ground.
    for row in &r[..2] {
        assert_eq!(field(row, "outcome"), "infeasible");
        assert_eq!((field(row, "label"), field(row, "steps")), ("null", "0"));
    }
    // The fixed point returns in one step; its x_value is the walk's ω_a.
    assert_eq!(field(&r[2], "outcome"), "returns");
    assert_eq!(field(&r[2], "label"), "walk");
    assert_eq!((field(&r[2], "steps"), field(&r[2], "period")), ("1", "1"));
    let d: f64 = field(&r[2], "distance").parse().unwrap();
    assert!(d < 1e-8, "{d}");
    let w: f64 = field(&r[2], "x_value").parse().unwrap();
    assert!((w + 2.4911).abs() < 1e-3, "{w}");
    // Rod a spun 40 rad/s against the roll lays the star down.
    assert_eq!(field(&r[3], "outcome"), "fails");
    assert_eq!(field(&r[3], "label"), "collapse");
    assert_eq!(field(&r[3], "failure"), "rod_down");
    // Two threads, same rows; and a slice replaces its own earlier file.
    let out2 = dir.path().join("b2.parquet");
    slice(s(&out2), "2");
    assert_eq!(rows(&out2), r);
    slice(s(&out), "2");
    assert_eq!(rows(&out), r);
}

#[test]
fn bad_axes_and_settings_name_the_flag_and_the_range() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("b.parquet");
    let out = s(&out);
    let base = |x: &'static str, y: &'static str| vec!["basin", "--x", x, "--y", y, "--out", out];
    run_err(
        &base("omega:-1:1:3", "theta_b:0:0:1"),
        &["--x omega:-1:1:3: unknown coordinate `omega`: must be one of omega_a, omega_b"],
    );
    run_err(
        &base("omega_a:1:-1:3", "theta_b:0:0:1"),
        &["--x omega_a:1:-1:3: from 1 to -1 is invalid: must be finite offsets with from <= to"],
    );
    run_err(
        &base("omega_a:-1:1:3", "theta_b:0:0:2000"),
        &["--y theta_b:0:0:2000: points 2000 is invalid: must be an integer in [1, 1000]"],
    );
    run_err(
        &base("omega_a:-1:1:3", "omega_a:0:0:1"),
        &["--y omega_a:0:0:1: coordinate omega_a is invalid: must be a coordinate other than x's"],
    );
    run_err(
        &base("omega_a:-1:1", "theta_b:0:0:1"),
        &["--x omega_a:-1:1: must be COORD:FROM:TO:POINTS"],
    );
    let mut a = base("omega_a:-1:1:3", "theta_b:0:0:1");
    a.extend(["--steps", "0"]);
    run_err(
        &a,
        &["--steps: 0 is invalid: must be an integer in [1, 100000]"],
    );
    let mut a = base("omega_a:-1:1:3", "theta_b:0:0:1");
    a.extend(["--tol", "1"]);
    run_err(&a, &["--tol: 1 is invalid: must be in (0, 0.1]"]);
    let mut a = base("omega_a:-1:1:3", "theta_b:0:0:1");
    a.extend(["--alpha", "0.6"]);
    run_err(&a, &["--alpha: 0.6 is invalid: must be"]);
    // Counts too large for any integer type, and no threads at all, are
    // refused by their range like any other value.
    let mut a = base("omega_a:-1:1:3", "theta_b:0:0:1");
    a.extend(["--steps", "1000000000000000000000000000000"]);
    run_err(
        &a,
        &["--steps: 1000000000000000000000000000000 is invalid: must be an integer in [1, 100000]"],
    );
    let mut a = base("omega_a:-1:1:3", "theta_b:0:0:1");
    a.extend(["--threads", "0"]);
    run_err(&a, &["--threads: 0 is invalid: must be an integer in [1, "]);
    assert!(!std::path::Path::new(out).exists());
}

#[test]
fn a_slice_never_writes_over_a_file_it_did_not_make() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("notes.parquet");
    std::fs::write(&out, "not mine").unwrap();
    run_err(
        &[
            "basin",
            "--x",
            "omega_a:0:0:1",
            "--y",
            "theta_b:0:0:1",
            "--out",
            s(&out),
        ],
        &["--out", "refusing to write over it"],
    );
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "not mine");
}

/// A slice and a sensitivity analysis can run for minutes: each shows its
/// progress on stderr (plain lines when stderr is not a terminal, its units
/// named), and `--quiet` shows none.
#[test]
fn basin_and_sensitivity_show_their_progress_and_quiet_silences_it() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("b.parquet");
    let o = slice(out.to_str().unwrap(), "1");
    let err = stderr(&o);
    let last = err
        .lines()
        .rfind(|l| l.starts_with("basin: grid points: "))
        .unwrap_or_else(|| panic!("{err}"));
    assert!(last.contains("4/4 (100.0 %)"), "{err}");
    let again = dir.path().join("c.parquet");
    let o = run_ok(&[
        "basin",
        "--x",
        "omega_a:-10:10:2",
        "--y",
        "theta_b:-0.2:0.2:2",
        "--steps",
        "4",
        "--threads",
        "1",
        "--out",
        s(&again),
        "--quiet",
    ]);
    assert!(!stderr(&o).contains("grid points"), "{}", stderr(&o));
    let cfg = write(dir.path(), "p.toml", &paper_like(40, 3));
    let scan = dir.path().join("scan");
    fake_run_ok(&cfg, &scan, &[]);
    let o = run_ok(&["sensitivity", s(&scan), "--resamples", "5"]);
    let err = stderr(&o);
    let last = err
        .lines()
        .rfind(|l| l.starts_with("sensitivity: bootstrap resamples: "))
        .unwrap_or_else(|| panic!("{err}"));
    assert!(last.contains("(100.0 %)"), "{err}");
    let o = run_ok(&[
        "sensitivity",
        s(&scan),
        "--resamples",
        "5",
        "--quiet",
        "--force",
    ]);
    assert!(!stderr(&o).contains("resamples:"), "{}", stderr(&o));
}
