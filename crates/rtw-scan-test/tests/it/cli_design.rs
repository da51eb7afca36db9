//! `rtw-scan design` and `rtw-scan profile` as studies that write: the
//! options they run checked before any work, one writer per result, a
//! budget that bounds the search, a cost estimated before it starts and a
//! progress that counts against a true total, the resume refusals naming
//! what differs, and a design folder that never mixes two builds' files.

use crate::common::*;
use std::path::Path;
use std::process::{Child, Stdio};
use std::time::{Duration, Instant};

/// A tiny search: the paper's box, slopes [0.05, 0.3] on a 0.05 grid (a
/// design costs about a dozen runs), `extra` keys added at the top.
fn tiny(dir: &Path, name: &str, budget: u64, extra: &str) -> String {
    write(
        dir,
        &format!("{name}.toml"),
        &format!(
            "name = \"{name}\"\nseed = 4\nbudget = {budget}\nbatch = 4\nreport = 1\n\
             objectives = [\"slope_range\"]\n{extra}\n\
             [box]\nrho = [1.0, 5.0]\nalpha = [0.0, 0.4]\nfn = [1.5, 5.0]\nzeta = [0.05, 0.1]\n\
             [slopes]\nfrom = 0.05\nto = 0.3\ngrid = 0.05\ntol = 0.01\nverify_grid = 0.025\n"
        ),
    )
}

/// The tiny search with the MFPT objective at φ = 0.15.
fn tiny_mfpt(dir: &Path, name: &str, budget: u64) -> String {
    let text = std::fs::read_to_string(tiny(dir, name, budget, "mfpt_phi = 0.15"))
        .unwrap()
        .replace("[\"slope_range\"]", "[\"mfpt\"]");
    write(dir, &format!("{name}.toml"), &text)
}

/// The value of `key` in `path`'s footer.
fn meta(path: &Path, key: &str) -> String {
    file_metadata(path, key)
}

/// Waits (at most 30 s) until `path` exists, the child still running.
fn wait_for(child: &mut Child, path: &Path) {
    let t0 = Instant::now();
    while !path.exists() {
        assert!(
            child.try_wait().unwrap().is_none(),
            "it ended before {} appeared",
            path.display()
        );
        assert!(
            t0.elapsed() < Duration::from_secs(30),
            "no {}",
            path.display()
        );
        std::thread::sleep(Duration::from_millis(5));
    }
}

fn spawn(args: &[&str]) -> Child {
    bin()
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap()
}

#[test]
fn an_mfpt_search_on_a_flat_slope_is_refused_before_any_work() {
    // The MFPT is switched on by the search for its run at mfpt_phi; the
    // options it will run are the ones checked, as `simulate` checks them.
    let dir = tempfile::tempdir().unwrap();
    let cfg = tiny_mfpt(dir.path(), "flat", 30);
    let out = dir.path().join("out");
    let want = "robustness.sigma: 0 is invalid: must be in (0, 1000] with robustness.mfpt";
    run_err(
        &[
            "design",
            &cfg,
            "--out",
            s(&out),
            "--quiet",
            "--set",
            "robustness.sigma=0",
        ],
        &[want],
    );
    assert!(!out.join("search.parquet").exists());
    // The same search on a rough slope runs.
    run_ok(&[
        "design",
        &cfg,
        "--out",
        s(&out),
        "--quiet",
        "--set",
        "robustness.sigma=0.05",
    ]);
}

#[test]
fn two_searches_into_one_folder_the_second_is_refused_naming_the_first() {
    let dir = tempfile::tempdir().unwrap();
    let a = tiny(dir.path(), "a", 3000, "");
    let b = tiny(dir.path(), "b", 60, "");
    let out = dir.path().join("tM");
    let mut first = spawn(&["design", &a, "--out", s(&out), "--quiet", "--threads", "1"]);
    wait_for(&mut first, &out.join(".search.parquet.lock"));
    let pid = first.id().to_string();
    run_err(
        &["design", &b, "--out", s(&out), "--quiet"],
        &[&format!("another rtw-scan (PID {pid})"), "search.parquet"],
    );
    let status = first.wait().unwrap();
    assert!(status.success(), "{status}");
    // The first search's files, whole.
    let json = meta(&out.join("search.parquet"), "rtw.design");
    assert!(json.contains("\"name\":\"a\""), "{json}");
    assert_eq!(
        meta(&out.join("designs.parquet"), "rtw.design"),
        json,
        "designs.parquet is not the first search's"
    );
    assert!(!out.join(".search.parquet.lock").exists());
}

#[test]
fn two_profiles_into_one_file_the_second_is_refused_naming_the_first() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("p.parquet");
    let design = [
        "--length", "0.8", "--rho", "2.5", "--alpha", "0.125", "--fn", "3.269", "--zeta", "0.0514",
    ];
    let args = |grid: &'static str| -> Vec<&str> {
        let mut a = vec!["profile"];
        a.extend(design);
        a.extend([
            "--from", "0.05", "--to", "0.3", "--grid", grid, "--tol", "1e-4",
        ]);
        a.extend(["--quiet", "--out", s(&out), "--threads", "1"]);
        a
    };
    let mut first = spawn(&args("1e-4"));
    wait_for(&mut first, &dir.path().join(".p.parquet.lock"));
    let pid = first.id().to_string();
    run_err(&args("0.01"), &[&format!("another rtw-scan (PID {pid})")]);
    assert!(first.wait().unwrap().success());
    let json: serde_json::Value = serde_json::from_str(&meta(&out, "rtw.profile")).unwrap();
    assert_eq!(
        json["grid"].as_f64(),
        Some(1e-4),
        "not the first profile's file"
    );
}

#[test]
fn seeds_take_the_whole_unsigned_range_and_bad_counts_name_their_key_and_range() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let top = tiny(dir.path(), "top", 30, "");
    let text = std::fs::read_to_string(&top)
        .unwrap()
        .replace("seed = 4", "seed = \"18446744073709551615\"");
    let top = write(dir.path(), "top.toml", &text);
    run_ok(&["design", &top, "--out", s(&out), "--quiet"]);
    let json = meta(&out.join("search.parquet"), "rtw.design");
    assert!(json.contains("\"seed\":18446744073709551615"), "{json}");
    let base = std::fs::read_to_string(tiny(dir.path(), "c", 30, "")).unwrap();
    for (from, to, want) in [
        (
            "seed = 4",
            "seed = -1",
            "seed: -1 is invalid: must be an integer in [0, 18446744073709551615]",
        ),
        (
            "seed = 4",
            "seed = \"18446744073709551616\"",
            "seed: 18446744073709551616 is invalid: must be an integer in [0, 18446744073709551615]",
        ),
        (
            "budget = 30",
            "budget = -1",
            "budget: -1 is invalid: must be an integer in [1, 10000000]",
        ),
        (
            "batch = 4",
            "batch = 2.5",
            "batch: 2.5 is invalid: must be an integer in [2, 1024]",
        ),
    ] {
        let cfg = write(dir.path(), "bad.toml", &base.replace(from, to));
        run_err(&["design", &cfg, "--out", s(&out), "--quiet"], &[want]);
    }
}

/// Every progress line `… D/T (P %) …` of `err`: (D, T).
fn progress_counts(err: &str) -> Vec<(u64, u64)> {
    err.lines()
        .filter_map(|l| {
            let at = l.find("] ")?;
            let rest = &l[at + 2..];
            let (counts, _) = rest.split_once(" (")?;
            let (d, t) = counts.split_once('/')?;
            Some((d.parse().ok()?, t.parse().ok()?))
        })
        .collect()
}

#[test]
fn the_budget_bounds_the_search_and_its_progress_never_passes_its_total() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = tiny(dir.path(), "b", 30, "");
    let out = dir.path().join("out");
    let done = run_ok(&["design", &cfg, "--out", s(&out), "--threads", "2"]);
    let err = stderr(&done);
    let counts = progress_counts(&err);
    assert!(!counts.is_empty(), "no progress line in:\n{err}");
    for (d, t) in &counts {
        assert!(d <= t, "{d}/{t} in:\n{err}");
    }
    // Fewer lines than units: never one per unit past the total.
    assert!(counts.len() < 40, "{} progress lines:\n{err}", counts.len());
    // It says what it spent against the budget, and the search stops at
    // the first generation that reaches it.
    assert!(err.contains("budget 30"), "{err}");
    let rows = rows(&out.join("search.parquet"));
    let names = column_names(&out.join("search.parquet"));
    let col = |n: &str| names.iter().position(|c| c == n).unwrap();
    let (runs, generation) = (col("runs"), col("generation"));
    let last = rows.iter().map(|r| r[generation].clone()).max().unwrap();
    let before_last: u64 = rows
        .iter()
        .filter(|r| r[generation] != last)
        .map(|r| r[runs].parse::<u64>().unwrap())
        .sum();
    assert!(
        before_last < 30,
        "{before_last} spent before the last generation"
    );
}

#[test]
fn a_generation_far_beyond_the_budget_is_refused_naming_its_keys() {
    let dir = tempfile::tempdir().unwrap();
    // The issue's repro: 1024 designs of 100 001 slopes each, budget 1.
    let text = "name = \"x\"\nseed = 1\nbudget = 1\nbatch = 1024\nreport = 100\n\
                objectives = [\"slope_range\"]\n[box]\nrho = [1.0, 5.0]\nalpha = [0.0, 0.4]\n\
                fn = [1.5, 5.0]\nzeta = [0.05, 0.1]\n[slopes]\nfrom = -1.5\nto = 1.5\n\
                grid = 3e-5\ntol = 1e-9\nverify_grid = 3e-5\n";
    let cfg = write(dir.path(), "huge.toml", text);
    let out = dir.path().join("out");
    let t0 = Instant::now();
    run_err(
        &["design", &cfg, "--out", s(&out), "--quiet"],
        &["budget: 1 is invalid", "batch", "slopes.grid", "must be"],
    );
    assert!(t0.elapsed() < Duration::from_secs(10));
    assert!(!out.join("search.parquet").exists());
}

/// The first stderr line of `child` holding `needle`, within `secs`.
fn first_line_with(child: &mut Child, needle: &str, secs: u64) -> Option<(String, Duration)> {
    let t0 = Instant::now();
    let rx = stderr_lines(child);
    while let Ok(line) = rx.recv_timeout(Duration::from_secs(secs).saturating_sub(t0.elapsed())) {
        if line.contains(needle) {
            return Some((line, t0.elapsed()));
        }
    }
    None
}

fn stop(mut child: Child) {
    let _ = child.kill();
    let _ = child.wait();
}

#[test]
fn a_costly_mfpt_search_and_profile_say_their_cost_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = tiny_mfpt(dir.path(), "dear", 300);
    let out = dir.path().join("out");
    let sets = [
        "--set",
        "robustness.sigma=0.05",
        "--set",
        "robustness.mfpt_batches=3000",
    ];
    let mut search = spawn(&[&["design", &cfg, "--out", s(&out), "--quiet"], &sets[..]].concat());
    let found = first_line_with(&mut search, "warning:", 5);
    stop(search);
    let (line, _) = found.expect("no warning of the MFPT's walker-steps within 5 s");
    assert!(line.contains("walker-steps"), "{line}");
    let p = dir.path().join("p.parquet");
    let mut profile = spawn(
        &[
            &[
                "profile",
                "--length",
                "0.8",
                "--rho",
                "2.5",
                "--alpha",
                "0.125",
                "--fn",
                "3.269",
                "--zeta",
                "0.0514",
                "--from",
                "0.27",
                "--to",
                "0.29",
                "--grid",
                "1e-5",
                "--tol",
                "1e-9",
                "--out",
                s(&p),
                "--set",
                "robustness.mfpt=true",
            ][..],
            &sets[..],
        ]
        .concat(),
    );
    let found = first_line_with(&mut profile, "warning:", 5);
    stop(profile);
    let (line, took) = found.expect("no warning of the profile's walker-steps within 5 s");
    assert!(line.contains("walker-steps"), "{line}");
    eprintln!("the profile's estimate after {took:?}");
}

#[test]
fn a_resume_refused_names_the_setting_and_both_values() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let cfg = tiny(dir.path(), "r", 60, "");
    run_ok(&["design", &cfg, "--out", s(&out), "--quiet"]);
    let more = tiny(dir.path(), "r", 90, "");
    run_err(
        &["design", &more, "--out", s(&out), "--quiet"],
        &["budget 60 there, 90 here"],
    );
    let cfg = tiny(dir.path(), "r", 60, "");
    run_err(
        &[
            "design",
            &cfg,
            "--out",
            s(&out),
            "--quiet",
            "--set",
            "contact.mu=0.3",
        ],
        &["contact.mu", "0.3 here"],
    );
}

#[test]
fn a_search_file_without_its_metadata_hash_is_named_for_what_it_is() {
    use parquet::arrow::ArrowWriter;
    use parquet::file::properties::WriterProperties;
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let cfg = tiny(dir.path(), "f", 30, "");
    run_ok(&["design", &cfg, "--out", s(&out), "--quiet"]);
    let path = out.join("search.parquet");
    let batches = batches(&path);
    let file = std::fs::File::open(&path).unwrap();
    let reader = parquet::file::reader::SerializedFileReader::new(file).unwrap();
    let kv: Vec<_> = parquet::file::reader::FileReader::metadata(&reader)
        .file_metadata()
        .key_value_metadata()
        .unwrap()
        .iter()
        .filter(|e| e.key != "rtw.metadata_hash" && e.key != "ARROW:schema")
        .cloned()
        .collect();
    let props = WriterProperties::builder()
        .set_key_value_metadata(Some(kv))
        .build();
    let forged = std::fs::File::create(&path).unwrap();
    let mut w = ArrowWriter::try_new(forged, batches[0].schema(), Some(props)).unwrap();
    for b in &batches {
        w.write(b).unwrap();
    }
    w.close().unwrap();
    let out_ = run_err(
        &["design", &cfg, "--out", s(&out), "--quiet"],
        &["rtw.metadata_hash"],
    );
    assert!(
        !stderr(&out_).contains("not a Parquet file"),
        "{}",
        stderr(&out_)
    );
}

#[test]
fn a_design_folder_with_two_builds_files_is_refused_naming_both() {
    use rtw_engine::io as output;
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let cfg = tiny(dir.path(), "v", 30, "");
    run_ok(&["design", &cfg, "--out", s(&out), "--quiet"]);
    assert!(
        rtw_studies::search::read::read_folder(&out)
            .unwrap()
            .is_some()
    );
    let path = out.join("designs.parquet");
    let input = output::open(&path, 1 << 20).unwrap();
    let mut m = input.metadata.clone();
    let batches: Vec<_> = input.reader.map(|b| b.unwrap()).collect();
    m.insert("rtw.version".into(), "0.1.0+0000000000000000".into());
    let kv = m.into_iter().map(|(k, v)| output::kv(&k, v)).collect();
    output::write_file(&path, &batches[0], kv).unwrap();
    let e = match rtw_studies::search::read::read_folder(&out) {
        Err(e) => format!("{e:#}"),
        Ok(_) => panic!("two builds' files read as one result"),
    };
    for want in [
        "search.parquet",
        "designs.parquet",
        "0.1.0+0000000000000000",
        rtw_engine::VERSION,
    ] {
        assert!(e.contains(want), "{want:?} not in {e}");
    }
}

#[test]
fn ctrl_c_stops_a_search_saying_what_it_kept_and_how_to_go_on() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = tiny(dir.path(), "i", 3000, "");
    let out = dir.path().join("out");
    let args = [
        "design",
        &cfg,
        "--out",
        s(&out),
        "--quiet",
        "--threads",
        "1",
    ];
    let mut child = spawn(&args);
    wait_for(&mut child, &out.join("search.part-000001.parquet"));
    interrupt(&mut child, Duration::from_secs(30));
    let done = child.wait_with_output().unwrap();
    assert_eq!(done.status.code(), Some(130));
    let err = stderr(&done);
    assert!(err.contains("kept in"), "{err}");
    assert!(err.contains("search.parquet"), "{err}");
    assert!(err.contains("same command"), "{err}");
    let kept = rows(&out.join("search.parquet")).len();
    assert!(kept > 0);
    assert!(err.contains(&format!("{kept} designs")), "{kept}: {err}");
    // The parts appended while it ran are merged into search.parquet.
    assert_eq!(parts_in(&out), Vec::<String>::new());
}

/// The names of the parts a running search appends in `out`, in order.
fn parts_in(out: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with("search.part-"))
        .collect();
    names.sort();
    names
}

#[test]
fn a_killed_search_keeps_each_generation_in_its_own_part_and_resumes_from_them() {
    // Each generation's new designs are appended as one small file, not the
    // whole search written again: the writes grow with the designs, not
    // with their square. A kill (no chance to merge) leaves the parts; the
    // same command resumes from them and ends with the uninterrupted
    // search's rows, the parts merged and gone.
    let dir = tempfile::tempdir().unwrap();
    let cfg = tiny(dir.path(), "k", 3000, "");
    let reference = dir.path().join("ref");
    run_ok(&["design", &cfg, "--out", s(&reference), "--quiet"]);
    let out = dir.path().join("out");
    let mut child = spawn(&[
        "design",
        &cfg,
        "--out",
        s(&out),
        "--quiet",
        "--threads",
        "1",
    ]);
    wait_for(&mut child, &out.join("search.part-000003.parquet"));
    child.kill().unwrap();
    child.wait().unwrap();
    let parts = parts_in(&out);
    assert!(parts.len() >= 3, "{parts:?}");
    assert!(!out.join("search.parquet").exists());
    let want = rows(&reference.join("search.parquet"));
    let mut seen = 0;
    for p in &parts[..3] {
        // A whole generation of 4 designs each, the next ones in order.
        let got = rows(&out.join(p));
        assert_eq!(got.len(), 4, "{p}");
        assert_eq!(got, want[seen..seen + 4].to_vec(), "{p}");
        seen += 4;
    }
    run_ok(&["design", &cfg, "--out", s(&out), "--quiet"]);
    assert_eq!(rows(&out.join("search.parquet")), want);
    assert_eq!(parts_in(&out), Vec::<String>::new());
}

#[test]
fn two_sensitivity_analyses_into_one_file_the_second_is_refused_naming_the_first() {
    // The lock is every writing study's, not the search's and the
    // profile's only: one more of them, through the binary.
    let dir = tempfile::tempdir().unwrap();
    let cfg = write(dir.path(), "scan.toml", &paper_like(5000, 3));
    let scan = dir.path().join("scan");
    fake_run_ok(&cfg, &scan, &[]);
    let out = dir.path().join("idx.parquet");
    let args = |n: &'static str| -> Vec<&str> {
        vec![
            "sensitivity",
            s(&scan),
            "--resamples",
            n,
            "--out",
            s(&out),
            "--quiet",
        ]
    };
    let mut first = spawn(&args("10000"));
    wait_for(&mut first, &dir.path().join(".idx.parquet.lock"));
    let pid = first.id().to_string();
    run_err(&args("100"), &[&format!("another rtw-scan (PID {pid})")]);
    assert!(first.wait().unwrap().success());
    let about: serde_json::Value = serde_json::from_str(&meta(&out, "rtw.sensitivity")).unwrap();
    assert_eq!(about["resamples"].as_u64(), Some(10000), "{about}");
}

/// A search's `--out` that is not a folder — a device, a plain file — is
/// refused saying what is there and what to do, as `run` and `profile`
/// refuse theirs, not with the OS's "File exists (os error 17)"; the file is
/// left as it was.
#[test]
fn a_search_folder_that_is_a_device_or_a_file_is_refused_saying_what_is_there() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = tiny(dir.path(), "t", 60, "");
    run_err(
        &["design", &cfg, "--out", "/dev/null", "--quiet"],
        &["--out /dev/null", "a character device, not a directory"],
    );
    let plain = write(dir.path(), "plainfile", "a user's file\n");
    let out = run_err(
        &["design", &cfg, "--out", &plain, "--quiet"],
        &["a regular file, not a directory", "choose another path"],
    );
    let err = stderr(&out);
    assert!(!err.contains("os error 17"), "{err}");
    assert_eq!(std::fs::read_to_string(&plain).unwrap(), "a user's file\n");
}

#[test]
fn docs_design_md_names_every_config_of_configs_design() {
    // The page's table of configs, not a count that a new config makes
    // wrong: each file of configs/design/ has its row, and each row a file.
    let doc = std::fs::read_to_string(workspace().join("docs/design.md")).unwrap();
    let mut on_disk: Vec<String> = std::fs::read_dir(workspace().join("configs/design"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".toml"))
        .collect();
    on_disk.sort();
    let mut rows: Vec<String> = doc
        .lines()
        .filter_map(|l| l.strip_prefix("| `")?.split_once(".toml` |"))
        .map(|(name, _)| format!("{name}.toml"))
        .collect();
    rows.sort();
    assert!(on_disk.len() >= 2, "{on_disk:?}");
    assert_eq!(rows, on_disk, "docs/design.md's table of configs/design/");
}
