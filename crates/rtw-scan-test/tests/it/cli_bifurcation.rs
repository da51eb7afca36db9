//! `rtw-scan bifurcation` through the binary, with the real step map: a tiny
//! φ sweep at the Fig. 7(a) point, its two Parquet files, and bad flags.

use crate::common::*;

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
        // The model the numbers below were measured with (strings of
        // natural length 0.85 r, every other choice the default's): the
        // test is about the sweep's files, not the fitted default.
        "--set",
        "strings.rest_length_ratio=0.85",
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
        // The article's walk (docs/model.md §9, s = 0.85): a stable period-1
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

/// Columns of `continuation`'s branch-point file, spelled out so a renamed
/// column fails here.
const BRANCH_COLUMNS: [&str; 12] = [
    "param",
    "branch",
    "period",
    "parent",
    "index",
    "k",
    "stable",
    "value",
    "omega",
    "floquet_max",
    "mu_re",
    "mu_im",
];

#[test]
fn a_short_continuation_in_phi_writes_its_branches_and_their_ends() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("phi.parquet");
    let o = run_ok(&[
        "continuation",
        "--from",
        "0.145",
        "--to",
        "0.155",
        // The model of the sweep's test above (s = 0.85).
        "--set",
        "strings.rest_length_ratio=0.85",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(column_names(&out), BRANCH_COLUMNS);
    let points = rows(&out);
    // Two branches through the start (up and down in φ), period 1, one row
    // per point; the walk is stable here (max |μ| 0.833 at 0.15, as the
    // sweep's test above) and its ω at the start is the same on both.
    for branch in ["0", "1"] {
        let b: Vec<_> = points
            .iter()
            .filter(|r| field(r, "branch") == branch)
            .collect();
        assert!(b.len() >= 2, "{branch}: {}", b.len());
        for r in &b {
            assert_eq!(field(r, "period"), "1");
            assert_eq!(field(r, "k"), "0");
            assert_eq!(field(r, "stable"), "true");
            let v: f64 = field(r, "value").parse().unwrap();
            assert!((0.145 - 0.01..=0.155 + 0.01).contains(&v), "{r:?}");
        }
        let mu: f64 = field(b[0], "floquet_max").parse().unwrap();
        assert!((mu - 0.833).abs() < 1e-3, "{mu}");
    }
    // No bifurcation between 0.145 and 0.155: a start and an end per branch,
    // each branch ending by leaving the range.
    let special = rows(&dir.path().join("phi.special.parquet"));
    let kinds: Vec<&str> = special.iter().map(|r| field(r, "kind")).collect();
    assert_eq!(
        kinds,
        [
            "start",
            "end_parameter_range",
            "start",
            "end_parameter_range"
        ]
    );
    // No --curve, no curve file; the summary printed and written.
    assert!(!dir.path().join("phi.curve.parquet").exists());
    let md = std::fs::read_to_string(dir.path().join("phi.md")).unwrap();
    assert_eq!(stdout(&o), md);
    assert!(md.contains("| 0 | 1 | the start |"), "{md}");
}

#[test]
fn continuation_refuses_bad_flags_naming_them() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x.parquet");
    let out = out.to_str().unwrap();
    run_err(
        &["continuation", "--param", "s", "--out", out],
        &[
            "--param: unknown input `s`",
            "length, rho, alpha, fn, zeta, phi",
        ],
    );
    run_err(
        &["continuation", "--to", "2", "--out", out],
        &["--to: phi = 2 is invalid: must be in (-pi/2, pi/2) rad"],
    );
    run_err(
        &["continuation", "--from", "0.16", "--out", out],
        &["the start's phi = 0.15 must lie strictly between them"],
    );
    run_err(
        &[
            "continuation",
            "--curve",
            "phi",
            "--curve-from",
            "0.1",
            "--curve-to",
            "0.2",
            "--out",
            out,
        ],
        &["--curve phi: must differ from --param"],
    );
    run_err(
        &["continuation", "--curve", "fn", "--out", out],
        &["--curve fn: needs --curve-from and --curve-to"],
    );
    run_err(
        &["continuation", "--section", "bounce", "--out", out],
        &["--section bounce: must be `stays` or `touch-and-go`"],
    );
    run_err(
        &["continuation", "--ds", "0", "--out", out],
        &["--ds 0 --ds-max 0.05: need 0 < ds ≤ ds-max"],
    );
    assert!(!std::path::Path::new(out).exists());
}

#[test]
fn continuation_refuses_to_write_over_a_file_it_did_not_make() {
    // A scan's rows where the diagram would go: refused, the scan's file
    // untouched (rtw never writes over a file it did not make; here for this
    // command's three files).
    let dir = tempfile::tempdir().unwrap();
    let scan = dir.path().join("scan");
    run_ok(&[
        "run",
        config("smoke").to_str().unwrap(),
        "--out",
        scan.to_str().unwrap(),
    ]);
    let samples = scan.join("samples.parquet");
    let before = std::fs::read(&samples).unwrap();
    run_err(
        &["continuation", "--out", samples.to_str().unwrap()],
        &[
            "holds a scan (rows of `rtw-scan run`) (from its metadata), not a continuation diagram",
            "refusing to write over it",
        ],
    );
    // The special-points file beside a diagram is guarded too.
    let special = dir.path().join("d.special.parquet");
    std::fs::copy(&samples, &special).unwrap();
    run_err(
        &[
            "continuation",
            "--out",
            dir.path().join("d.parquet").to_str().unwrap(),
        ],
        &["--out (special points file)", "refusing to write over it"],
    );
    assert_eq!(std::fs::read(&samples).unwrap(), before);
    assert!(!dir.path().join("d.parquet").exists());
}

/// Ctrl-C during a study of the step map (`args`, writing `NAME.parquet` in
/// a folder of its own): it ends within the bound with exit 130, saying
/// nothing was written, and leaves the folder as it was: no file of the
/// study, no temporary file, no lock. `started` is a stderr line that shows
/// the study is under way.
fn interrupted_leaves_nothing(args: &[&str], started: &str) {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("phi.parquet");
    let mut child = bin()
        .args(args)
        .args(["--out", out.to_str().unwrap()])
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let lines = stderr_lines(&mut child);
    let t0 = std::time::Instant::now();
    let mut said = Vec::new();
    loop {
        let line = lines
            .recv_timeout(std::time::Duration::from_secs(120))
            .unwrap_or_else(|_| panic!("no {started:?} within 120 s: {said:?}"));
        let found = line.contains(started);
        said.push(line);
        if found {
            break;
        }
        assert!(t0.elapsed().as_secs() < 120, "{said:?}");
    }
    // The study's contract is 2 s; the bound leaves room for a loaded machine.
    let (status, took) = interrupt(&mut child, std::time::Duration::from_secs(5));
    said.extend(lines.try_iter());
    eprintln!("{}: ended {took:?} after the interrupt", args[0]);
    assert_eq!(status.code(), Some(130), "{said:?}");
    assert!(
        said.iter()
            .any(|l| l.contains("interrupted") && l.contains("nothing was written")),
        "{said:?}"
    );
    let left: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert!(left.is_empty(), "left behind: {left:?}");
}

#[test]
fn an_interrupted_sweep_stops_at_once_and_writes_nothing() {
    interrupted_leaves_nothing(
        &[
            "bifurcation",
            "--from",
            "0.14",
            "--to",
            "0.16",
            "--points",
            "400",
            "--transient",
            "60",
            "--record",
            "4",
        ],
        "(1/400)",
    );
}

#[test]
fn an_interrupted_continuation_stops_at_once_and_writes_nothing() {
    interrupted_leaves_nothing(
        &[
            "continuation",
            "--from",
            "0.02",
            "--to",
            "0.4",
            "--curve",
            "fn",
            "--curve-from",
            "2",
            "--curve-to",
            "5",
            "--through",
            "4",
        ],
        "continuation",
    );
}
