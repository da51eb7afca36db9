//! `rtw-scan continuation --through N`: the walk's branch continued through
//! the changes of its mode sequence, each change named, through the binary.

use crate::common::*;
use serde_json::Value;
use std::path::Path;

/// `continuation ARGS --through 3 --out DIR/phi.parquet`: its output and the
/// segments file it writes.
fn through(dir: &Path, args: &[&str]) -> (std::process::Output, Value) {
    let out = dir.join("phi.parquet");
    let o = run_ok(
        &[
            &["continuation"],
            args,
            &["--through", "3", "--out", out.to_str().unwrap()],
        ]
        .concat(),
    );
    let text = std::fs::read_to_string(dir.join("phi.segments.json")).unwrap();
    (o, serde_json::from_str(&text).unwrap())
}

/// From φ = 0.094 down to 0.0925 the walk's branch meets the grazing of its
/// landing foot at φ ≈ 0.09313 (the foot starts to bounce; the end that
/// `continuation` alone calls "no continuation"): two segments, the first
/// ending in a named grazing, the second at the range's end; upwards one
/// segment to the range's end.
#[test]
fn continuation_through_names_the_grazing_that_ended_the_walks_branch() {
    let dir = tempfile::tempdir().unwrap();
    let (o, doc) = through(
        dir.path(),
        &[
            "--phi",
            "0.094",
            // The model of this end: s = 0.85 (at the default 0.8875 it moves).
            "--set",
            "strings.rest_length_ratio=0.85",
            "--from",
            "0.0925",
            "--to",
            "0.0955",
        ],
    );
    assert_eq!(doc["kind"], "rtw-scan continuation segments");
    let dirs = doc["directions"].as_array().unwrap();
    let up = dirs[0]["segments"].as_array().unwrap();
    let down = dirs[1]["segments"].as_array().unwrap();
    assert_eq!(up.len(), 1, "{up:#?}");
    assert_eq!(up[0]["end"], "end_parameter_range");
    assert_eq!(down.len(), 2, "{down:#?}");
    assert_eq!(down[0]["end"], "grazing");
    let at = down[0]["end_at"]["p_old"].as_f64().unwrap();
    assert!((0.0931..0.0932).contains(&at), "{at}");
    assert!(
        down[0]["end_at"]["detail"]
            .as_str()
            .unwrap()
            .starts_with("td b+"),
        "{}",
        down[0]["end_at"]
    );
    assert_eq!(down[1]["end"], "end_parameter_range");
    for s in up.iter().chain(down) {
        assert_eq!(s["label"], "walk");
        for p in s["points"].as_array().unwrap() {
            assert_eq!(p["label"], "walk");
            assert_eq!(p["stable"], true);
            let f = p["step_frequency"].as_f64().unwrap();
            // The sweep (results/bifurcation) has 0.2628 s per step at φ = 0.09425.
            assert!((3.7..3.9).contains(&f), "{p}");
        }
    }
    let md = std::fs::read_to_string(dir.path().join("phi.md")).unwrap();
    assert_eq!(stdout(&o), md);
    assert!(md.contains("Through the changes of mode sequence"), "{md}");
    assert!(
        md.contains("| down | 0 | walk |") && md.contains("| grazing |"),
        "{md}"
    );
}

#[test]
fn continuation_through_refuses_a_bad_count_and_a_file_it_did_not_make() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("d.parquet");
    run_err(
        &[
            "continuation",
            "--through",
            "101",
            "--out",
            out.to_str().unwrap(),
        ],
        &["--through 101: must lie in [0, 100]"],
    );
    let theirs = dir.path().join("d.segments.json");
    std::fs::write(&theirs, "{\"not\": \"ours\"}").unwrap();
    run_err(
        &[
            "continuation",
            "--through",
            "2",
            "--out",
            out.to_str().unwrap(),
        ],
        &["d.segments.json exists and is not a continuation's segments file"],
    );
    assert_eq!(
        std::fs::read_to_string(&theirs).unwrap(),
        "{\"not\": \"ours\"}"
    );
    assert!(!out.exists());
}

/// At the default model the walk doubles its period at φ ≈ 0.1948; the
/// period-2 branch born there stops its smooth continuation at φ ≈ 0.19829
/// ("no continuation" in the diagram's table). `--through` continues it from
/// there: the end is named (a corner: a re-stick of rod a and the touchdown
/// of b+ coincide) and the branch goes on past it, a stable period-2 walk,
/// to the range's end. The attractor sweep, an independent brute-force
/// computation (results/bifurcation/phi-fig7a.parquet, made by
/// ./scripts/bifurcation.sh), has a stable period-2 walk at φ = 0.19875 with
/// max |μ| = 0.804033: the continued segment passes there with the same
/// period and label and, interpolated, the same multiplier within 2e-3.
#[test]
fn continuation_through_continues_the_period_2_branch_past_its_corner() {
    let dir = tempfile::tempdir().unwrap();
    let (_, doc) = through(
        dir.path(),
        &["--phi", "0.194", "--from", "0.188", "--to", "0.2"],
    );
    let dirs = doc["directions"].as_array().unwrap();
    let p2: Vec<&Value> = dirs.iter().filter(|d| d["period"] == 2).collect();
    assert_eq!(p2.len(), 1, "{dirs:#?}");
    assert_eq!(p2[0]["direction"], 1.0);
    assert!(p2[0]["from"]["branch_end"].is_u64(), "{}", p2[0]["from"]);
    let segs = p2[0]["segments"].as_array().unwrap();
    assert!(segs.len() >= 2, "{segs:#?}");
    assert_eq!(segs[0]["end"], "corner");
    let at = segs[0]["end_at"]["p_old"].as_f64().unwrap();
    assert!((0.1982..0.1984).contains(&at), "{at}");
    let last = segs.last().unwrap();
    assert_eq!(last["end"], "end_parameter_range");
    let pts = last["points"].as_array().unwrap();
    let p = |q: &Value| q["p"].as_f64().unwrap();
    assert!(
        p(&pts[0]) - at <= 1e-3,
        "starts {} after the corner",
        p(&pts[0]) - at
    );
    for q in pts {
        assert_eq!(q["label"], "walk", "{q}");
        assert_eq!(q["stable"], true, "{q}");
    }
    assert!(segs.iter().all(|s| s["period"] == 2));
    let k = pts
        .windows(2)
        .position(|w| p(&w[0]) <= 0.19875 && 0.19875 <= p(&w[1]))
        .expect("the segment passes the sweep's value 0.19875");
    let (a, b) = (&pts[k], &pts[k + 1]);
    let w = (0.19875 - p(a)) / (p(b) - p(a));
    let mu = |q: &Value| q["floquet_max"].as_f64().unwrap();
    let m = (1.0 - w) * mu(a) + w * mu(b);
    assert!(
        (m - 0.804033).abs() < 2e-3,
        "max|μ| {m} against the sweep's 0.804033"
    );
}

/// The files of a diagram with `--through` (branch points, special points,
/// summary, segments) in `dir`, by name, with their bytes.
fn diagram_files(dir: &Path) -> Vec<(String, Vec<u8>)> {
    ["d.parquet", "d.special.parquet", "d.md", "d.segments.json"]
        .iter()
        .filter_map(|n| Some((n.to_string(), std::fs::read(dir.join(n)).ok()?)))
        .collect()
}

/// Files in `dir` a killed writer could leave: temporary files.
fn leftovers(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .filter_map(Result::ok)
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".tmp"))
        .collect()
}

/// `continuation --through 1 ... --out DIR/d.parquet` stopped by SIGTERM
/// where the test build pauses, while the segments are being followed (the
/// test build's `RTW_SCAN_PAUSE=continuation-segments`).
fn interrupted_through(dir: &Path, to: &str) {
    use std::io::BufRead;
    let out = dir.join("d.parquet");
    let mut child = bin()
        .args(["continuation", "--phi", "0.094", "--set"])
        .args([
            "strings.rest_length_ratio=0.85",
            "--from",
            "0.0925",
            "--to",
            to,
        ])
        .args(["--through", "1", "--out", s(&out)])
        .env("RTW_SCAN_PAUSE", "continuation-segments")
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut err = std::io::BufReader::new(child.stderr.take().unwrap());
    let mut line = String::new();
    loop {
        line.clear();
        let n = err.read_line(&mut line).unwrap();
        assert!(n > 0, "continuation ended without pausing");
        if line.contains("paused at continuation-segments") {
            break;
        }
    }
    let ok = std::process::Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .unwrap()
        .success();
    assert!(ok);
    let st = child.wait().unwrap();
    assert_eq!(st.code(), Some(130), "{st}");
}

/// docs/cli.md: no command leaves a partial result. A diagram's files with
/// `--through` appear together at the end or not at all: a `continuation
/// --through` interrupted while it follows the segments leaves no file of
/// its own in a fresh folder, and leaves an earlier diagram's files in
/// place, byte for byte.
#[test]
fn an_interrupted_continuation_through_leaves_no_partial_set_of_files() {
    let dir = tempfile::tempdir().unwrap();
    interrupted_through(dir.path(), "0.0955");
    assert_eq!(
        diagram_files(dir.path())
            .iter()
            .map(|f| &f.0)
            .collect::<Vec<_>>(),
        Vec::<&String>::new(),
        "files left by an interrupted diagram"
    );
    assert_eq!(leftovers(dir.path()), Vec::<String>::new());
    let out = dir.path().join("d.parquet");
    run_ok(&[
        "continuation",
        "--phi",
        "0.094",
        "--set",
        "strings.rest_length_ratio=0.85",
        "--from",
        "0.0925",
        "--to",
        "0.0955",
        "--through",
        "1",
        "--out",
        s(&out),
    ]);
    let before = diagram_files(dir.path());
    assert_eq!(before.len(), 4);
    // Another range: every file would change.
    interrupted_through(dir.path(), "0.095");
    assert!(
        diagram_files(dir.path()) == before,
        "the earlier diagram's files were changed"
    );
    assert_eq!(leftovers(dir.path()), Vec::<String>::new());
}

/// `--through` that is not an integer in range (a count beyond any integer,
/// a float) is refused with the valid range, not clap's "number too large"
/// or "invalid digit".
#[test]
fn continuation_through_beyond_an_integer_is_refused_with_the_range() {
    for bad in ["1000000000000000000000", "1e3"] {
        run_err(
            &["continuation", "--through", bad],
            &[&format!("{bad} is invalid"), "[0, 100]"],
        );
    }
}
