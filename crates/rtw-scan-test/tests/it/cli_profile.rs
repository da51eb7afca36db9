//! `rtw-scan profile` through the binary, on the Fig. 7(a) design over
//! φ ∈ [0.05, 0.3]: every located change is checked by direct simulation
//! (`rtw-scan simulate --json`, an independent run of the design at one
//! slope) at both ends of its bracket and at its middle ± tol; slopes inside
//! the reported widest interval are simulated and must be stable; the
//! Parquet file and its summary; the same profile on any thread count; bad
//! input named with its range.

use crate::common::*;
use serde_json::Value;

const DESIGN: [&str; 10] = [
    "--length", "0.8", "--rho", "2.5", "--alpha", "0.125", "--fn", "3.269", "--zeta", "0.0514",
];

/// `rtw-scan profile` of the design over [from, to], then `extra`.
fn args<'a>(from: &'a str, to: &'a str, extra: &[&'a str]) -> Vec<&'a str> {
    let mut a = vec!["profile"];
    a.extend(DESIGN);
    a.extend(["--from", from, "--to", to]);
    a.extend(extra);
    a
}

/// The column `name` of a row of [`rows`].
fn field<'a>(row: &'a [String], name: &str) -> &'a str {
    let prefix = format!("{name}=");
    row.iter()
        .find_map(|c| c.strip_prefix(&prefix))
        .unwrap_or_else(|| panic!("no {name} in {row:?}"))
}

fn profile(extra: &[&str]) -> Value {
    let a = args("0.05", "0.3", &[&["--json", "--quiet"], extra].concat());
    serde_json::from_str(&stdout(&run_ok(&a))).unwrap()
}

/// The label `rtw-scan simulate` gives the design at `phi`.
fn simulated_label(phi: f64) -> String {
    let phi = format!("{phi}");
    let mut args = vec!["simulate"];
    args.extend(DESIGN);
    args.extend(["--phi", &phi, "--json"]);
    let v: Value = serde_json::from_str(&stdout(&run_ok(&args))).unwrap();
    v["outcome"].as_str().unwrap().to_string()
}

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// The number `key` holds in the JSON object `text` (`simulate --json`),
/// parsed from its digits: serde_json's default float parsing is
/// best-effort and may land one unit in the last place off (215.31770833333334
/// read as …337), which an exact comparison must not inherit.
fn json_number(text: &str, key: &str) -> f64 {
    let tag = format!("\"{key}\":");
    let at = text
        .find(&tag)
        .unwrap_or_else(|| panic!("no {key} in {text}"))
        + tag.len();
    let rest = text[at..].trim_start();
    let end = rest.find([',', '}', '\n']).unwrap_or(rest.len());
    rest[..end].trim().parse().unwrap()
}

#[test]
fn fig7a_changes_hold_under_direct_simulation_at_the_change_plus_minus_tol() {
    let tol = 1e-3;
    let p = profile(&[]);
    let changes = p["changes"].as_array().unwrap();
    assert!(!changes.is_empty(), "{p:#}");
    for c in changes {
        let (lo, hi) = (f(&c["phi_left"]), f(&c["phi_right"]));
        let (left, right) = (
            c["label_left"].as_str().unwrap(),
            c["label_right"].as_str().unwrap(),
        );
        assert_ne!(left, right, "{c}");
        assert!(hi > lo && hi - lo <= tol, "bracket wider than tol: {c}");
        assert_eq!(simulated_label(lo), left, "at phi_left of {c}");
        assert_eq!(simulated_label(hi), right, "at phi_right of {c}");
        // One tol either side of the change, direct simulation gives the
        // labels the profile reports there: its ends' labels where it is
        // sharp; others where two labels interleave below tol.
        let mid = 0.5 * (lo + hi);
        let (below, above) = (simulated_label(mid - tol), simulated_label(mid + tol));
        assert_eq!(below, c["label_below"].as_str().unwrap(), "{c}");
        assert_eq!(above, c["label_above"].as_str().unwrap(), "{c}");
        assert_eq!(c["sharp"], below == left && above == right, "{c}");
    }
    // Where the design stops being stable (skip → collapse) the change is
    // sharp; the walk turns into a skip through a band where both interleave
    // at scales below 1e-4 rad (0.2173..0.2286: walk at 0.2175, skip at 0.21755).
    let last = changes.last().unwrap();
    assert_eq!(
        (last["label_left"].as_str(), last["label_right"].as_str()),
        (Some("skip"), Some("collapse"))
    );
    assert_eq!(last["sharp"], true, "{last}");
    assert_eq!(changes[0]["sharp"], false, "{}", changes[0]);
    assert_eq!(simulated_label(0.2175), "walk");
    assert_eq!(simulated_label(0.21755), "skip");
    // Bisection, not a fine grid: the grid's 26 slopes, then at most
    // ceil(log2(0.01 / 1e-3)) = 4 per change (and 2 checks, not rows),
    // against 251 at a 1e-3 grid.
    let runs = p["runs"].as_u64().unwrap() as usize;
    assert_eq!(p["coarse_runs"], 26);
    assert!(runs <= 26 + 4 * changes.len(), "{runs} runs");
    // The widest stable interval holds: every slope tried inside it is stable.
    let (lo, hi) = (f(&p["phi_lo"]), f(&p["phi_hi"]));
    assert!(hi > lo);
    for i in 0..=8 {
        let phi = lo + (hi - lo) * f64::from(i) / 8.0;
        let label = simulated_label(phi);
        assert!(
            ["walk", "skip", "crawl"].contains(&label.as_str()),
            "{label} at {phi} inside [{lo}, {hi}]"
        );
    }
    // The article's walk from φ = 0.05 (Fig. S3): the profile starts walking.
    assert_eq!(f(&p["phi_min"]), 0.05);
    assert_eq!(p["segments"][0]["label"], "walk");
}

#[test]
fn the_profile_is_the_same_on_one_and_two_threads() {
    let one = profile(&["--threads", "1", "--tol", "1e-4"]);
    let two = profile(&["--threads", "2", "--tol", "1e-4"]);
    assert_eq!(one, two);
    for c in one["changes"].as_array().unwrap() {
        assert!(f(&c["phi_right"]) - f(&c["phi_left"]) <= 1e-4, "{c}");
    }
}

#[test]
fn out_writes_every_slope_and_its_summary_and_refuses_a_file_it_did_not_make() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("p.parquet");
    let p = profile(&["--out", s(&out)]);
    let names = column_names(&out);
    for c in ["sample_id", "phi", "outcome", "speed", "f_w"] {
        assert!(names.iter().any(|n| n == c), "no {c} in {names:?}");
    }
    let rows = rows(&out);
    assert_eq!(rows.len() as u64, p["runs"].as_u64().unwrap());
    let phis: Vec<f64> = rows
        .iter()
        .map(|r| field(r, "phi").parse().unwrap())
        .collect();
    assert!(phis.windows(2).all(|w| w[0] < w[1]), "not in φ order");
    assert_eq!((phis[0], *phis.last().unwrap()), (0.05, 0.3));
    let md = std::fs::read_to_string(dir.path().join("p.md")).unwrap();
    assert!(md.starts_with("# Slope profile of L = 0.8 m"), "{md}");
    assert!(md.contains("phi_lo = "), "{md}");
    // Its own earlier output is replaced; another file is not.
    profile(&["--out", s(&out)]);
    let other = dir.path().join("notes.parquet");
    std::fs::write(&other, "a person's notes").unwrap();
    let mut args = vec!["profile"];
    args.extend(DESIGN);
    args.extend(["--from", "0.05", "--to", "0.1", "--out", s(&other)]);
    run_err(&args, &["--out", "not a Parquet file", "--force"]);
    assert_eq!(std::fs::read(&other).unwrap(), b"a person's notes");
    std::fs::write(dir.path().join("mine.md"), "my summary").unwrap();
    let mine = dir.path().join("mine.parquet");
    let last = args.len() - 1;
    args[last] = s(&mine);
    run_err(&args, &["is not the summary of a slope profile"]);
    assert!(!mine.exists());
}

#[test]
fn bad_input_is_named_with_its_range() {
    let base = |from: &str, to: &str, extra: &[&str], needles: &[&str]| {
        let mut args = vec!["profile"];
        args.extend(DESIGN);
        args.extend(["--from", from, "--to", to]);
        args.extend(extra);
        run_err(&args, needles);
    };
    base(
        "0.3",
        "0.05",
        &[],
        &["--to: 0.05 is invalid: must be above --from (0.3)"],
    );
    base(
        "0.05",
        "0.3",
        &["--tol", "0"],
        &["--tol: 0 is invalid: must be in [1e-9, 0.01] rad"],
    );
    base(
        "0.05",
        "0.3",
        &["--tol", "0.02"],
        &["--tol: 0.02 is invalid: must be in [1e-9, 0.01] rad (at most --grid"],
    );
    base(
        "-2",
        "0.3",
        &[],
        &["--from: -2 is invalid: must be a slope φ in (-pi/2, pi/2) rad"],
    );
    base(
        "0.05",
        "1.6",
        &[],
        &["--to: 1.6 is invalid: must be a slope φ in (-pi/2, pi/2) rad"],
    );
    base(
        "0.05",
        "0.3",
        &["--grid", "1"],
        &["--grid: 1 is invalid: must be in [2.5e-6, 0.25] rad"],
    );
    base(
        "0.05",
        "0.3",
        &["--threads", "0"],
        &["--threads: 0 is invalid: must be an integer in [1, "],
    );
    let mut args = vec!["profile"];
    args.extend(DESIGN);
    args[6] = "0.6";
    args.extend(["--from", "0.05", "--to", "0.3"]);
    run_err(&args, &["--alpha: 0.6 is invalid: must be in [0, 0.49]"]);
}

#[test]
fn ctrl_c_stops_a_profile_at_once_and_leaves_the_earlier_files_as_they_were() {
    use std::time::{Duration, Instant};
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("p.parquet");
    let md = dir.path().join("p.md");
    profile(&["--out", s(&out)]);
    let (before, before_md) = (std::fs::read(&out).unwrap(), std::fs::read(&md).unwrap());
    // 100 001 slopes on the grid: minutes of runs.
    let mut child = bin()
        .arg("profile")
        .args(DESIGN)
        .args([
            "--from", "0.05", "--to", "0.3", "--grid", "2.5e-6", "--tol", "1e-6",
        ])
        .args(["--quiet", "--out", s(&out)])
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(1500));
    assert!(
        child.try_wait().unwrap().is_none(),
        "it ended before the signal"
    );
    let sent = std::process::Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(sent.success());
    let t0 = Instant::now();
    let status = loop {
        if let Some(st) = child.try_wait().unwrap() {
            break st;
        }
        assert!(
            t0.elapsed() < Duration::from_secs(10),
            "still running 10 s after SIGINT"
        );
        std::thread::sleep(Duration::from_millis(10));
    };
    assert_eq!(status.code(), Some(130));
    assert_eq!(std::fs::read(&out).unwrap(), before);
    assert_eq!(std::fs::read(&md).unwrap(), before_md);
    let temps: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
        .collect();
    assert!(temps.is_empty(), "{temps:?}");
}

#[test]
fn the_mfpt_along_phi_is_in_the_file_as_simulate_gives_it() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("m.parquet");
    let mfpt = [
        "--set",
        "robustness.mfpt=true",
        "--set",
        "robustness.sigma=0.05",
    ];
    let out_s = s(&out);
    run_ok(&args(
        "0.27",
        "0.29",
        &[&["--quiet", "--out", out_s], &mfpt[..]].concat(),
    ));
    let names = column_names(&out);
    for c in ["mfpt", "mfpt_lo", "mfpt_hi", "fall_rate"] {
        assert!(names.iter().any(|n| n == c), "no {c} in {names:?}");
    }
    let rows = rows(&out);
    // A stable slope has the MFPT `simulate` gives at that slope; a
    // collapse has none.
    let first = &rows[0];
    assert_eq!(field(first, "outcome"), "skip");
    let mut sim = vec!["simulate"];
    sim.extend(DESIGN);
    let phi = field(first, "phi");
    sim.extend(["--phi", phi, "--json"]);
    sim.extend(mfpt);
    let text = stdout(&run_ok(&sim));
    assert_eq!(
        field(first, "mfpt").parse::<f64>().unwrap(),
        json_number(&text, "mfpt")
    );
    let last = rows.last().unwrap();
    assert_eq!(field(last, "outcome"), "collapse");
    assert_eq!(field(last, "mfpt"), "null");
    // A profile without the measure does not replace one with it.
    let plain = args("0.27", "0.29", &["--quiet", "--out", out_s]);
    run_err(&plain, &["its columns are not those of this one"]);
}

// The design search (`rtw-scan design`), which judges each design by its
// slope profile.

/// A small search: the paper's box, slopes [0.05, 0.3] on a 0.05 grid.
fn design_config(dir: &std::path::Path, name: &str, extra: &str) -> String {
    write(
        dir,
        &format!("{name}.toml"),
        &format!(
            "name = \"{name}\"\nseed = 4\nbudget = 400\nbatch = 4\nobjectives = [\"slope_range\"]\n\
             {extra}\n[box]\nrho = [1.0, 5.0]\nalpha = [0.0, 0.4]\nfn = [1.5, 5.0]\nzeta = [0.05, 0.1]\n\
             [slopes]\nfrom = 0.05\nto = 0.3\ngrid = 0.05\ntol = 0.01\nverify_grid = 0.025\n"
        ),
    )
}

/// The small search's settings, read as the library reads a config, at
/// the default options.
fn search_settings(
    dir: &std::path::Path,
    name: &str,
    extra: &str,
) -> (rtw_studies::search::SearchSettings, rtw_model::Options) {
    let cfg = design_config(dir, name, extra);
    let settings = rtw_studies::search::SearchSettings::read(std::path::Path::new(&cfg)).unwrap();
    (settings, rtw_model::Options::default())
}

/// Stops the search (its cancel flag) once `at` designs are evaluated (the
/// search's progress counts each generation's designs).
struct StopAfter<'a> {
    done: std::sync::atomic::AtomicU64,
    at: u64,
    cancel: &'a std::sync::atomic::AtomicBool,
}

impl rtw_engine::scan::Progress for StopAfter<'_> {
    fn computed(&self, _: rtw_model::Label) {}
    fn advanced(&self) {
        use std::sync::atomic::Ordering;
        if self.done.fetch_add(1, Ordering::SeqCst) + 1 >= self.at {
            self.cancel.store(true, Ordering::SeqCst);
        }
    }
}

#[test]
fn a_stopped_search_keeps_its_designs_and_resumes_to_the_uninterrupted_result() {
    stopped_and_resumed("");
}

#[test]
fn a_stopped_archive_search_resumes_to_the_uninterrupted_result_and_its_archive() {
    let dir = stopped_and_resumed("method = \"archive\"");
    // Each elite is the best-scoring design of its cell among every
    // evaluation, and the cells are those its descriptors give.
    let archive = rows(&dir.path().join("part/archive.parquet"));
    let search = rows(&dir.path().join("part/search.parquet"));
    assert!(archive.len() >= 3, "{} elites", archive.len());
    let num = |row: &[String], k: &str| field(row, k).parse::<f64>().unwrap();
    let cell = |row: &[String]| {
        let mid = 0.5 * (num(row, "phi_lo") + num(row, "phi_hi"));
        let bin = |t: f64, n: f64| ((t.clamp(0.0, 1.0) * n) as i64).min(n as i64 - 1);
        (
            bin((mid - 0.05) / 0.25, 8.0),
            bin(num(row, "walk_share"), 4.0),
        )
    };
    for elite in &archive {
        let c = (
            num(elite, "cell_slope") as i64,
            num(elite, "cell_walk") as i64,
        );
        assert_eq!(cell(elite), c);
        for row in search.iter().filter(|r| field(r, "feasible") == "true") {
            if cell(row) == c {
                assert!(
                    num(row, "score") <= num(elite, "score"),
                    "{row:?} beats {elite:?}"
                );
            }
        }
    }
}

/// A search of the small config with `extra` keys, stopped after a dozen
/// designs and resumed, against the same search uninterrupted; the
/// folder (`part/`: stopped and resumed; `whole/`).
fn stopped_and_resumed(extra: &str) -> tempfile::TempDir {
    use rtw_engine::scan::Run;
    use rtw_studies::search::files;
    use std::sync::atomic::AtomicBool;
    let dir = tempfile::tempdir().unwrap();
    let (settings, options) = search_settings(dir.path(), "resume", extra);
    let quiet = rtw_engine::scan::progress::Silent;
    let never = AtomicBool::new(false);
    let whole = dir.path().join("whole");
    let (full, reported) = files::run_to_files(
        &settings,
        &options,
        &whole,
        false,
        &Run::new(&quiet, &never),
    )
    .unwrap();
    assert!(full.evaluations.len() > 8, "{}", full.evaluations.len());

    let part = dir.path().join("part");
    let cancel = AtomicBool::new(false);
    let stop = StopAfter {
        done: 0.into(),
        at: 12,
        cancel: &cancel,
    };
    let e = files::run_to_files(&settings, &options, &part, false, &Run::new(&stop, &cancel))
        .expect_err("stopped");
    assert!(format!("{e:#}").contains("stopped"), "{e:#}");
    let kept = files::stored(&part, &settings, &options, false)
        .unwrap()
        .evaluations;
    assert!(
        !kept.is_empty() && kept.len() < full.evaluations.len(),
        "{} of {}",
        kept.len(),
        full.evaluations.len()
    );
    // Every kept design is the uninterrupted search's, as it was evaluated there.
    for k in &kept {
        assert_eq!(Some(k), full.evaluations.get(k.index as usize));
    }
    let (resumed, reported2) =
        files::run_to_files(&settings, &options, &part, false, &Run::new(&quiet, &never)).unwrap();
    assert_eq!(resumed.evaluations, full.evaluations);
    assert_eq!(
        reported2.iter().map(|r| &r.verified).collect::<Vec<_>>(),
        reported.iter().map(|r| &r.verified).collect::<Vec<_>>()
    );
    assert_eq!(
        rows(&files::designs_path(&part)),
        rows(&files::designs_path(&whole))
    );
    assert_eq!(
        rows(&files::archive_path(&part)),
        rows(&files::archive_path(&whole))
    );
    dir
}

/// A stored search made by another build is not resumed: its evaluations
/// may be numbers that this build no longer computes (an earlier MFPT
/// estimator's, say), and a resume would report them as this build's.
#[test]
fn a_search_stored_by_another_build_is_refused_and_force_computes_it_anew() {
    use rtw_engine::io as output;
    use rtw_engine::scan::Run;
    use rtw_studies::search::files;
    use std::sync::atomic::AtomicBool;
    let dir = tempfile::tempdir().unwrap();
    let (settings, options) = search_settings(dir.path(), "build", "");
    let out = dir.path().join("out");
    let cancel = AtomicBool::new(false);
    let stop = StopAfter {
        done: 0.into(),
        at: 3,
        cancel: &cancel,
    };
    files::run_to_files(&settings, &options, &out, false, &Run::new(&stop, &cancel))
        .expect_err("stopped");
    let stored = files::stored(&out, &settings, &options, false).unwrap();
    assert!(!stored.evaluations.is_empty());
    // The same file as another build would have written it.
    let path = files::search_path(&out);
    let input = output::open(&path, 1 << 20).unwrap();
    let mut meta = input.metadata.clone();
    let batches: Vec<_> = input.reader.map(|b| b.unwrap()).collect();
    assert_eq!(meta["rtw.version"], rtw_engine::VERSION);
    meta.insert("rtw.version".into(), "0.1.0+0000000000000000".into());
    let kv = meta.into_iter().map(|(k, v)| output::kv(&k, v)).collect();
    output::write_file(&path, &batches[0], kv).unwrap();

    let e = files::stored(&out, &settings, &options, false).expect_err("another build");
    let msg = format!("{e:#}");
    for want in [
        "different rtw-scan versions",
        "0.1.0+0000000000000000",
        rtw_engine::VERSION,
        "--force",
    ] {
        assert!(msg.contains(want), "{want:?} not in {msg}");
    }
    // --force keeps none of them: the search starts anew.
    assert!(
        files::stored(&out, &settings, &options, true)
            .unwrap()
            .evaluations
            .is_empty()
    );
}

#[test]
fn the_reported_designs_intervals_hold_under_direct_simulation() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = design_config(dir.path(), "widest", "report = 3");
    let out = dir.path().join("out");
    run_ok(&["design", &cfg, "--out", s(&out), "--quiet"]);
    let designs = rows(&out.join("designs.parquet"));
    assert!(!designs.is_empty());
    for d in &designs {
        let (lo, hi): (f64, f64) = (
            field(d, "phi_lo").parse().unwrap(),
            field(d, "phi_hi").parse().unwrap(),
        );
        assert!(hi >= lo && lo >= 0.05 && hi <= 0.3, "{d:?}");
        // Five slopes inside the verified interval, each simulated directly.
        for i in 0..5 {
            let phi = format!("{}", lo + (hi - lo) * i as f64 / 4.0);
            let mut a = vec!["simulate", "--length", "0.8"];
            for k in ["rho", "alpha", "fn", "zeta"] {
                a.extend([["--", k].concat().leak() as &str, field(d, k)]);
            }
            a.extend(["--phi", &phi, "--json"]);
            let v: Value = serde_json::from_str(&stdout(&run_ok(&a))).unwrap();
            let label = v["outcome"].as_str().unwrap();
            assert!(
                ["walk", "skip", "crawl"].contains(&label),
                "design {d:?} at φ = {phi}: {label}"
            );
        }
    }
    let summary = std::fs::read_to_string(out.join("search.md")).unwrap();
    assert!(summary.starts_with("# Design search widest"), "{summary}");
}

#[test]
fn cma_es_and_the_archive_draw_fewer_designs_that_fall_than_sobol_designs() {
    // Walking at φ = 0.15 is the constraint: about a third of the paper's box
    // walks (docs/model.md §8), so a design drawn blindly mostly falls. A
    // search that moves towards good designs stays where designs walk; how
    // much of that is the learned fall model's doing is measured by the
    // benchmark against the same searches without it (results/design/bench.md).
    let dir = tempfile::tempdir().unwrap();
    let extra = "gait = \"walk\"\nobjectives = [\"speed\"]\nspeed_phi = 0.15\nbatch = 8";
    let share = |method: &str| -> f64 {
        let text = std::fs::read_to_string(design_config(dir.path(), method, extra))
            .unwrap()
            .replace("objectives = [\"slope_range\"]\n", "")
            .replace(
                "budget = 400\nbatch = 4",
                &format!("budget = 1500\nmethod = \"{method}\""),
            );
        let cfg = write(dir.path(), &format!("{method}.toml"), &text);
        let out = dir.path().join(method);
        run_ok(&["design", &cfg, "--out", s(&out), "--quiet"]);
        let r = rows(&out.join("search.parquet"));
        r.iter()
            .filter(|row| field(row, "feasible") == "false")
            .count() as f64
            / r.len() as f64
    };
    let (cmaes, sobol, archive) = (share("cmaes"), share("sobol"), share("archive"));
    assert!(sobol > 0.3, "Sobol designs that fall: {sobol}");
    assert!(cmaes < 0.5 * sobol, "CMA-ES {cmaes} against Sobol {sobol}");
    assert!(
        archive < 0.5 * sobol,
        "archive {archive} against Sobol {sobol}"
    );
}

#[test]
fn a_search_refuses_another_searchs_folder_and_names_bad_keys() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let a = design_config(dir.path(), "a", "budget = 100");
    run_err(&["design", &a, "--out", s(&out)], &["duplicate key"]);
    let a = design_config(dir.path(), "a", "report = 1");
    run_ok(&["design", &a, "--out", s(&out), "--quiet"]);
    let b = design_config(dir.path(), "b", "report = 1");
    run_err(
        &["design", &b, "--out", s(&out), "--quiet"],
        &["holds the search \"a\" of other settings", "--force"],
    );
    run_ok(&["design", &b, "--out", s(&out), "--quiet", "--force"]);
    let bad = design_config(dir.path(), "c", "avoid = 2");
    run_err(
        &["design", &bad, "--out", s(&out), "--quiet"],
        &["avoid: 2 is invalid: must be in [0.5, 1]"],
    );
}

#[test]
fn the_mfpt_objective_is_the_mfpt_simulate_gives_at_its_slope() {
    // One generation of four designs (the budget is spent by the first),
    // their MFPT on a rough slope of σ = 5 cm at φ = 0.15.
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(design_config(dir.path(), "m", ""))
        .unwrap()
        .replace("budget = 400", "budget = 1")
        .replace("[\"slope_range\"]", "[\"mfpt\"]\nmfpt_phi = 0.15");
    let cfg = write(dir.path(), "mfpt.toml", &text);
    let out = dir.path().join("out");
    let sigma = ["--set", "robustness.sigma=0.05"];
    run_ok(&[&["design", &cfg, "--out", s(&out), "--quiet"], &sigma[..]].concat());
    let rows = rows(&out.join("search.parquet"));
    assert_eq!(rows.len(), 4);
    let mut stable = 0;
    for r in &rows {
        let mut a = vec!["simulate", "--length", "0.8", "--phi", "0.15", "--json"];
        for k in ["rho", "alpha", "fn", "zeta"] {
            a.extend([["--", k].concat().leak() as &str, field(r, k)]);
        }
        a.extend(["--set", "robustness.mfpt=true"]);
        a.extend(sigma);
        let text = stdout(&run_ok(&a));
        let v: Value = serde_json::from_str(&text).unwrap();
        let label = v["outcome"].as_str().unwrap();
        assert_eq!(field(r, "label_at_mfpt_phi"), label);
        if ["walk", "skip", "crawl"].contains(&label) {
            stable += 1;
            assert_eq!(
                field(r, "mfpt").parse::<f64>().unwrap(),
                json_number(&text, "mfpt")
            );
            assert_eq!(field(r, "feasible"), "true");
        } else {
            assert_eq!(field(r, "mfpt"), "null");
            assert_eq!(field(r, "feasible"), "false");
            assert!(
                field(r, "infeasible").starts_with("not stable at mfpt_phi"),
                "{r:?}"
            );
        }
    }
    assert!(stable > 0, "no stable design among {rows:?}");
}

#[test]
fn a_search_configs_simulation_table_is_its_model_as_set_gives_it() {
    // The model of a search belongs in its config, as a scan's does: the
    // `[simulation]` table is the options' first layer, under `--variant`
    // and `--set`, and the search it makes is the one `--set` makes.
    let dir = tempfile::tempdir().unwrap();
    let plain = design_config(dir.path(), "mu", "report = 1");
    let text = std::fs::read_to_string(&plain).unwrap() + "[simulation.contact]\nmu = 0.3\n";
    let in_config = write(dir.path(), "mu-in-config.toml", &text);
    let (a, b) = (dir.path().join("a"), dir.path().join("b"));
    run_ok(&["design", &in_config, "--out", s(&a), "--quiet"]);
    run_ok(&[
        "design",
        &plain,
        "--out",
        s(&b),
        "--quiet",
        "--set",
        "contact.mu=0.3",
    ]);
    assert_eq!(
        rows(&a.join("search.parquet")),
        rows(&b.join("search.parquet"))
    );
    let meta = |p: &std::path::Path| {
        let r = parquet::file::reader::SerializedFileReader::new(std::fs::File::open(p).unwrap())
            .unwrap();
        use parquet::file::reader::FileReader;
        let kv = r
            .metadata()
            .file_metadata()
            .key_value_metadata()
            .unwrap()
            .clone();
        let get = |k: &str| {
            kv.iter()
                .find(|e| e.key == k)
                .and_then(|e| e.value.clone())
                .unwrap()
        };
        (get("rtw.design"), get("rtw.variant"))
    };
    let (ma, mb) = (
        meta(&a.join("search.parquet")),
        meta(&b.join("search.parquet")),
    );
    assert_eq!(ma, mb);
    assert!(ma.1.contains("mu=0.3"), "{}", ma.1);
    // There is no `--config`: the search's config is the table's one place.
    run_err(
        &["design", &in_config, "--out", s(&a), "--config", &plain],
        &["unexpected argument '--config'"],
    );
    // A bad key in it is named with its path.
    let bad = write(
        dir.path(),
        "bad.toml",
        &(std::fs::read_to_string(&plain).unwrap() + "[simulation.contact]\nmu = -1\n"),
    );
    run_err(
        &["design", &bad, "--out", s(&a), "--quiet"],
        &["contact.mu"],
    );
}
