//! `rtw-scan refine` through the binary, with the fake simulator: rounds,
//! determinism, resume, shards, and where the new samples fall.

use crate::common::*;
use arrow_array::{Array, Float64Array, Int64Array};
use std::path::Path;

/// A slice in (alpha, phi) where the fake simulator's labels are: stall for
/// phi < 0.1, else crawl for alpha > 0.3, else walk.
fn slice(samples: u64, seed: u64) -> String {
    format!(
        "seed = {seed}\nsamples = {samples}\n[params]\nlength = 0.8\nrho = 2.0\n\
         alpha = {{ uniform = [0, 0.4] }}\nfn = 3.0\nzeta = 0.05\nphi = {{ uniform = [0.05, 0.3] }}\n\
         [simulation]\nt_max = 3.0\n"
    )
}

fn refine(dir: &Path, extra: &[&str]) -> std::process::Output {
    run_ok(&[&["refine", s(dir), "--fake-sim", "0", "--quiet"], extra].concat())
}

fn f64s(path: &Path, name: &str) -> Vec<f64> {
    batches(path)
        .iter()
        .flat_map(|b| {
            let c = b.column_by_name(name).unwrap();
            let c = c.as_any().downcast_ref::<Float64Array>().unwrap();
            c.values().to_vec()
        })
        .collect()
}

fn ids(path: &Path) -> Vec<i64> {
    batches(path)
        .iter()
        .flat_map(|b| {
            let c = b.column_by_name("sample_id").unwrap();
            c.as_any()
                .downcast_ref::<Int64Array>()
                .unwrap()
                .values()
                .to_vec()
        })
        .collect()
}

/// A finished fake scan of `cfg` in `dir/name`.
fn scan(dir: &Path, name: &str, cfg: &str) -> std::path::PathBuf {
    let c = write(dir, &format!("{name}.toml"), cfg);
    let out = dir.join(name);
    fake_run_ok(&c, &out, &[]);
    out
}

#[test]
fn refine_adds_the_budget_in_rounds_with_new_ids_deterministically() {
    let dir = tempfile::tempdir().unwrap();
    let a = scan(dir.path(), "a", &slice(150, 4));
    let b = scan(dir.path(), "b", &slice(150, 4));
    let c = scan(dir.path(), "c", &slice(150, 4));
    refine(&a, &["--budget", "61", "--rounds", "3", "--seed", "9"]);
    refine(&b, &["--budget", "61", "--rounds", "3", "--seed", "9"]);
    refine(&c, &["--budget", "61", "--rounds", "3", "--seed", "10"]);
    let all = a.join("refine/samples.parquet");
    assert_eq!(ids(&all), (0..211).collect::<Vec<i64>>());
    for (round, n) in [(1, 21), (2, 20), (3, 20)] {
        let r = a.join(format!("refine/round-00{round}/samples.parquet"));
        assert_eq!(ids(&r).len(), n, "round {round}");
    }
    // The scan's rows come first, as they were.
    let base = rows(&a.join("samples.parquet"));
    assert_eq!(rows(&all)[..150], base[..]);
    // Same rows and seed: the same points; another seed: others.
    assert_eq!(rows(&all), rows(&b.join("refine/samples.parquet")));
    assert_ne!(
        f64s(&all, "alpha")[150..],
        f64s(&c.join("refine/samples.parquet"), "alpha")[150..]
    );
    // The combined file is a scan file the other commands read; its summary
    // says its shares are the refined sample's (its samples crowd where the
    // labels change), and a plain scan's says nothing of the kind.
    let summary = |f: &Path| String::from_utf8(run_ok(&["summary", s(f)]).stdout).unwrap();
    assert!(summary(&all).contains("not the box's"), "{}", summary(&all));
    assert!(!summary(&a.join("samples.parquet")).contains("not the box's"));
}

#[test]
fn new_samples_fall_near_the_label_changes() {
    let dir = tempfile::tempdir().unwrap();
    let a = scan(dir.path(), "a", &slice(200, 7));
    refine(&a, &["--budget", "200", "--rounds", "2", "--seed", "1"]);
    let all = a.join("refine/samples.parquet");
    let (alpha, phi) = (f64s(&all, "alpha"), f64s(&all, "phi"));
    // Distance, in the unit box, to the nearest label change of the fake
    // simulator: phi = 0.1, and alpha = 0.3 where phi > 0.1.
    let dist = |i: usize| {
        let (u, v) = (alpha[i] / 0.4, (phi[i] - 0.05) / 0.25);
        let to_phi = (v - 0.2).abs();
        if v > 0.2 {
            to_phi.min((u - 0.75).abs())
        } else {
            to_phi
        }
    };
    let mean = |r: std::ops::Range<usize>| r.clone().map(dist).sum::<f64>() / r.len() as f64;
    let (uniform, refined) = (mean(0..200), mean(200..400));
    assert!(uniform > 0.1, "uniform mean distance {uniform}");
    assert!(
        refined < 0.4 * uniform,
        "refined {refined}, uniform {uniform}"
    );
}

#[test]
fn an_interrupted_refinement_keeps_its_finished_rounds() {
    let dir = tempfile::tempdir().unwrap();
    let a = scan(dir.path(), "a", &slice(100, 2));
    refine(&a, &["--budget", "40", "--rounds", "2"]);
    let all = a.join("refine/samples.parquet");
    let first = rows(&all);
    let round1 = a.join("refine/round-001/samples.parquet");
    let kept = std::fs::metadata(&round1).unwrap().modified().unwrap();
    // Round 2 and the combined file lost: the same command makes them again,
    // keeping round 1.
    std::fs::remove_dir_all(a.join("refine/round-002")).unwrap();
    std::fs::remove_file(&all).unwrap();
    refine(&a, &["--budget", "40", "--rounds", "2"]);
    assert_eq!(rows(&all), first);
    assert_eq!(
        std::fs::metadata(&round1).unwrap().modified().unwrap(),
        kept
    );
}

#[test]
fn a_round_runs_in_shards_like_any_scan() {
    let dir = tempfile::tempdir().unwrap();
    let one = scan(dir.path(), "one", &slice(100, 3));
    let split = scan(dir.path(), "split", &slice(100, 3));
    refine(&one, &["--budget", "30", "--rounds", "2"]);
    for round in ["round-001", "round-002"] {
        for k in ["0/2", "1/2"] {
            let o = refine(&split, &["--budget", "30", "--rounds", "2", "--shard", k]);
            assert!(stdout(&o).contains("rtw-scan merge"), "{}", stdout(&o));
        }
        run_ok(&["merge", s(&split.join("refine").join(round))]);
    }
    refine(&split, &["--budget", "30", "--rounds", "2"]);
    assert_eq!(
        rows(&one.join("refine/samples.parquet")),
        rows(&split.join("refine/samples.parquet"))
    );
}

#[test]
fn bad_refine_input_is_named_with_its_range() {
    let dir = tempfile::tempdir().unwrap();
    let a = scan(dir.path(), "a", &slice(20, 1));
    let d = s(&a);
    run_err(
        &["refine", d, "--budget", "0"],
        &["--budget", "0 is invalid", "[1, 100000]"],
    );
    run_err(
        &["refine", d, "--budget", "10", "--rounds", "11"],
        &["--rounds", "11 is invalid", "from 1 to --budget (10)"],
    );
    run_err(
        &["refine", d, "--budget", "10", "--rounds", "0"],
        &["--rounds", "0 is invalid"],
    );
    let grid = scan(
        dir.path(),
        "grid",
        &slice(5, 1).replace("phi = { uniform = [0.05, 0.3] }", "phi = [0.1, 0.2]"),
    );
    run_err(
        &["refine", s(&grid), "--budget", "10", "--fake-sim", "0"],
        &["`phi` is a grid"],
    );
    run_err(
        &["refine", s(&dir.path().join("none")), "--budget", "10"],
        &["samples.parquet"],
    );
    // Without --rounds: 16 rounds, or one per sample of a smaller budget.
    refine(&a, &["--budget", "3"]);
    assert!(a.join("refine/round-003").is_dir() && !a.join("refine/round-004").exists());
}

/// Refined samples crowd where the labels change, so they are not draws from
/// the inputs' distribution, and the given-data estimator weighs each row as
/// one: Sobol indices from them would be biased. `sensitivity` refuses the
/// combined file and points to the scan's own rows.
#[test]
fn sensitivity_refuses_the_refined_file_whose_samples_are_not_draws() {
    let dir = tempfile::tempdir().unwrap();
    let a = scan(dir.path(), "a", &slice(150, 4));
    refine(&a, &["--budget", "40", "--rounds", "2", "--seed", "3"]);
    let all = a.join("refine/samples.parquet");
    run_err(
        &["sensitivity", s(&all), "--resamples", "20"],
        &["refined", "not draws", "a/samples.parquet"],
    );
    run_ok(&[
        "sensitivity",
        s(&a.join("samples.parquet")),
        "--resamples",
        "20",
    ]);
}

/// A budget beyond what a round can hold in memory (`propose` draws 20
/// candidates a point: 10¹² points aborted with "memory allocation failed",
/// 10⁷ took 4 GB in 30 s) is refused up front, naming the flag and its
/// range, before anything is read or written.
#[test]
fn a_refine_budget_beyond_its_range_is_refused_up_front() {
    let dir = tempfile::tempdir().unwrap();
    let a = scan(dir.path(), "a", &slice(20, 1));
    for budget in ["1000000000000", "10000000", "100001"] {
        run_err(
            &[
                "refine",
                s(&a),
                "--budget",
                budget,
                "--rounds",
                "1",
                "--fake-sim",
                "0",
            ],
            &[&format!("--budget: {budget} is invalid"), "[1, 100000]"],
        );
    }
    // A round stores its points in its config, at most 10⁴ of them.
    run_err(
        &[
            "refine",
            s(&a),
            "--budget",
            "20001",
            "--rounds",
            "2",
            "--fake-sim",
            "0",
        ],
        &["--rounds: 2 is invalid: must be an integer from 3 to --budget (20001)"],
    );
    assert!(!a.join("refine").exists());
}

/// What refine writes on stderr, progress shown, adding 30 samples in 3
/// rounds to a scan of 100.
fn refine_in_three_rounds_stderr() -> String {
    let dir = tempfile::tempdir().unwrap();
    let a = scan(dir.path(), "a", &slice(100, 2));
    let o = run_ok(&[
        "refine",
        s(&a),
        "--budget",
        "30",
        "--rounds",
        "3",
        "--fake-sim",
        "0",
    ]);
    stderr(&o)
}

/// Refine's progress counts each round on its own, says which round it is,
/// and never passes its total (it ran on across rounds: "893/62
/// (1440.3 %) … ETA 169200271151644288 s").
#[test]
fn refine_progress_counts_each_round_and_names_it() {
    let err = refine_in_three_rounds_stderr();
    let mut seen = std::collections::BTreeSet::new();
    for line in err.lines().filter(|l| l.contains(" samples/s")) {
        let round = line
            .split("round ")
            .nth(1)
            .and_then(|r| r.split(" of 3").next())
            .unwrap_or_else(|| panic!("no round in {line:?}"));
        seen.insert(round.to_string());
        let counts = line.split("] ").nth(1).unwrap().split(' ').next().unwrap();
        let (done, total) = counts.split_once('/').unwrap();
        let (done, total): (u64, u64) = (done.parse().unwrap(), total.parse().unwrap());
        assert_eq!(total, 10, "{line}");
        assert!(done <= total, "{line}");
    }
    assert_eq!(seen.len(), 3, "{err}");
}

/// A refinement replaces only its own files. Over another refinement's
/// (other --budget, --rounds or --seed), refine says what differs and what
/// to do, not "Choose another --out" (refine has no --out); over a
/// combined file of another scan's refinement, or a scan file that is no
/// refinement's, it refuses rather than replace it; each file is kept.
#[test]
fn refine_refuses_another_refinements_files_saying_what_differs() {
    let dir = tempfile::tempdir().unwrap();
    let a = scan(dir.path(), "a", &slice(100, 4));
    let b = scan(dir.path(), "b", &slice(100, 5));
    refine(&a, &["--budget", "30", "--rounds", "3", "--seed", "9"]);
    let all = a.join("refine/samples.parquet");
    let before = std::fs::read(&all).unwrap();
    let o = run_err(
        &[
            "refine",
            s(&a),
            "--budget",
            "20",
            "--rounds",
            "2",
            "--seed",
            "9",
            "--fake-sim",
            "0",
        ],
        &["--budget 30 there, 20 here", "--rounds 3 there, 2 here"],
    );
    assert!(!stderr(&o).contains("--out"), "{}", stderr(&o));
    assert_eq!(std::fs::read(&all).unwrap(), before);
    // Without the combined file, the first round that differs says so.
    std::fs::remove_file(&all).unwrap();
    let o = run_err(
        &[
            "refine",
            s(&a),
            "--budget",
            "30",
            "--rounds",
            "3",
            "--seed",
            "8",
            "--fake-sim",
            "0",
        ],
        &["round 1 of another refinement", "--seed 8"],
    );
    assert!(!stderr(&o).contains("--out"), "{}", stderr(&o));
    refine(&a, &["--budget", "30", "--rounds", "3", "--seed", "9"]);
    assert_eq!(std::fs::read(&all).unwrap(), before);
    // Another scan's refined file, with the same flags: its base rows differ.
    refine(&b, &["--budget", "30", "--rounds", "3", "--seed", "9"]);
    let c = scan(dir.path(), "c", &slice(100, 4));
    std::fs::create_dir_all(c.join("refine")).unwrap();
    let theirs = std::fs::read(b.join("refine/samples.parquet")).unwrap();
    std::fs::write(c.join("refine/samples.parquet"), &theirs).unwrap();
    run_err(
        &[
            "refine",
            s(&c),
            "--budget",
            "30",
            "--rounds",
            "3",
            "--seed",
            "9",
            "--fake-sim",
            "0",
        ],
        &["another refinement's rows", "the scan's rows (content hash"],
    );
    assert_eq!(
        std::fs::read(c.join("refine/samples.parquet")).unwrap(),
        theirs
    );
    // A plain scan file there is no refinement's.
    let plain = std::fs::read(b.join("samples.parquet")).unwrap();
    std::fs::write(c.join("refine/samples.parquet"), &plain).unwrap();
    run_err(
        &[
            "refine",
            s(&c),
            "--budget",
            "30",
            "--rounds",
            "3",
            "--seed",
            "9",
            "--fake-sim",
            "0",
        ],
        &["not a refinement's file"],
    );
    assert_eq!(
        std::fs::read(c.join("refine/samples.parquet")).unwrap(),
        plain
    );
}

/// A round's points depend on the rows before it, not on (seed, id), so the
/// round must carry them: its config stores them (`sampling = "points"`).
/// Then `run` of that config, resumed in the round's folder, replays the
/// same points; the round's summary says it is refined; and `sensitivity`
/// refuses the round, whose points crowd where the labels change.
#[test]
fn a_round_carries_its_points_so_a_rerun_replays_them_and_sensitivity_refuses_them() {
    let dir = tempfile::tempdir().unwrap();
    let a = scan(dir.path(), "a", &slice(100, 6));
    refine(&a, &["--budget", "40", "--rounds", "2", "--seed", "2"]);
    let round = a.join("refine/round-002");
    let finished = round.join("samples.parquet");
    let want = rows(&finished);
    // The round's own config, as stored in its file, run again from nothing.
    let text = file_metadata(&finished, "rtw.config");
    assert!(text.contains("sampling = \"points\""), "{text}");
    let cfg = write(dir.path(), "round.toml", &text);
    let again = dir.path().join("again");
    fake_run_ok(&cfg, &again, &[]);
    assert_eq!(rows(&again.join("samples.parquet")), want);
    // Its summary says its shares are not the box's, in text and JSON.
    let o = run_ok(&["summary", s(&finished), "--json"]);
    assert!(stdout(&o).contains("\"refined\": true"), "{}", stdout(&o));
    run_err(
        &["sensitivity", s(&round), "--resamples", "20"],
        &["refined", "not draws", "a/samples.parquet"],
    );
}

/// A scan's own samples file copied into `DIR/refine/` is named for what it
/// is, a scan's samples file and not a refinement's, and the advice is what
/// can be done: move it away or pass --force, not "keep it and go on from
/// it", which no refinement can.
#[test]
fn a_scan_file_in_refine_is_called_a_scan_s_samples_file() {
    let dir = tempfile::tempdir().unwrap();
    let a = scan(dir.path(), "a", &slice(60, 4));
    std::fs::create_dir_all(a.join("refine")).unwrap();
    let plain = std::fs::read(a.join("samples.parquet")).unwrap();
    std::fs::write(a.join("refine/samples.parquet"), &plain).unwrap();
    let o = run_err(
        &[
            "refine",
            s(&a),
            "--budget",
            "30",
            "--rounds",
            "3",
            "--fake-sim",
            "0",
        ],
        &["a scan's samples file", "not a refinement's", "--force"],
    );
    let err = stderr(&o);
    assert!(!err.contains("another refinement's rows"), "{err}");
    assert!(!err.contains("goes on from it"), "{err}");
    assert_eq!(
        std::fs::read(a.join("refine/samples.parquet")).unwrap(),
        plain
    );
}

/// Before each round runs, refine says what it is doing: choosing the
/// round's points among their candidates by the rows so far (with a large
/// scan, minutes of neighbour search), the candidates counted as they are
/// scored.
#[test]
fn refine_says_it_is_choosing_each_round_s_points() {
    let err = refine_in_three_rounds_stderr();
    for (round, rows) in [(1, 100), (2, 110), (3, 120)] {
        let want = format!(
            "round {round} of 3: choosing 10 points among 200 candidates by their neighbours in \
             {rows} rows"
        );
        assert!(err.contains(&want), "no {want:?} in:\n{err}");
    }
    assert!(err.contains("/200 (100.0 %)"), "{err}");
}

/// A Ctrl-C while a round chooses its points (a pass over every row for
/// each of its candidates: minutes with many rows) stops refine within
/// moments, saying that the finished rounds are kept, with exit 130.
#[test]
fn a_ctrl_c_while_a_round_chooses_its_points_stops_it_at_once() {
    use std::process::Stdio;
    use std::time::Duration;
    let dir = tempfile::tempdir().unwrap();
    // 40 000 rows and 10 000 new points: 200 000 candidates, each against
    // every row, far longer than the stop may take.
    let a = scan(dir.path(), "a", &slice(40_000, 3));
    let mut child = bin()
        .args([
            "refine",
            s(&a),
            "--budget",
            "10000",
            "--rounds",
            "1",
            "--fake-sim",
            "0",
        ])
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let rx = stderr_lines(&mut child);
    let mut seen = Vec::new();
    loop {
        let line = rx
            .recv_timeout(Duration::from_secs(60))
            .expect("refine never said it was choosing the round's points");
        let choosing = line.contains("choosing");
        seen.push(line);
        if choosing {
            break;
        }
    }
    std::thread::sleep(Duration::from_millis(500));
    assert!(
        child.try_wait().unwrap().is_none(),
        "refine ended before the interrupt: {seen:?}"
    );
    let (status, took) = interrupt(&mut child, Duration::from_secs(60));
    seen.extend(rx.try_iter());
    assert_eq!(status.code(), Some(130), "{seen:?}");
    assert!(
        took < Duration::from_secs(5),
        "stopped {took:?} after the interrupt"
    );
    assert!(
        seen.iter()
            .any(|l| l.contains("interrupted while choosing the points of round 1")),
        "{seen:?}"
    );
    assert!(!a.join("refine").join("samples.parquet").exists());
}
