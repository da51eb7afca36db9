//! Finished results are never lost (issue 14): no run, merge, summary,
//! cluster, simulate or bifurcation writes over another scan's results or its
//! own input without `--force`; sizes are bounded before anything is
//! allocated; corrupt files are refused; the CLI conventions (issue 15 item
//! 6): `--quiet`, SIGTERM and SIGHUP like Ctrl-C, `summary --json`, exit
//! codes in `--help`. Each test failed before its fix.

mod common;

use common::*;
use std::path::Path;
use std::process::{Child, Stdio};
use std::time::{Duration, Instant};

/// Files in `dir` whose name ends with `.tmp` (temporary files left behind).
fn temp_files(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .map(|d| {
            d.filter_map(Result::ok)
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .filter(|n| n.ends_with(".tmp"))
                .collect()
        })
        .unwrap_or_default()
}

fn signal(child: &Child, sig: &str) {
    let ok = std::process::Command::new("kill")
        .args([&format!("-{sig}"), &child.id().to_string()])
        .status()
        .unwrap()
        .success();
    assert!(ok, "kill -{sig} failed");
}

/// Waits for `child` at most `limit`; kills it and panics if it runs longer.
fn wait_at_most(child: &mut Child, limit: Duration, what: &str) -> std::process::ExitStatus {
    let t0 = Instant::now();
    loop {
        if let Some(st) = child.try_wait().unwrap() {
            return st;
        }
        if t0.elapsed() > limit {
            child.kill().ok();
            child.wait().ok();
            panic!("{what}: still running after {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(10));
    }
}

/// Starts a slow fake run (`ms` per sample, chunks of 4 rows) in the background.
fn spawn_slow(config: &str, out: &Path, threads: &str, ms: &str) -> Child {
    bin()
        .args(["run", config, "--out", s(out), "--threads", threads])
        .args(["--chunk-size", "4", "--fake-sim", ms])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap()
}

/// Waits until `path` exists; kills `child` and panics after `limit`.
fn wait_for(child: &mut Child, path: &Path, limit: Duration) {
    let t0 = Instant::now();
    while !path.exists() {
        if t0.elapsed() > limit {
            child.kill().ok();
            child.wait().ok();
            panic!("{} did not appear within {limit:?}", path.display());
        }
        std::thread::sleep(Duration::from_millis(5));
    }
}

// ---- item 1: finished results are not overwritten ----

#[test]
fn a_run_into_another_scans_directory_is_refused_unless_forced() {
    let dir = tempfile::tempdir().unwrap();
    let a = write(dir.path(), "a.toml", &paper_like(30, 1));
    let b = write(dir.path(), "b.toml", &paper_like(6, 2));
    let out = dir.path().join("x");
    fake_run_ok(&a, &out, &[]);
    let before = rows(&out.join("samples.parquet"));
    let summary = std::fs::read_to_string(out.join("summary.json")).unwrap();

    // Another config: refused, naming both configs, nothing touched.
    let o = fake_run(&b, &out, &[]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("another scan") && err.contains("--force"),
        "{err}"
    );
    let hash = |path: &str| rtw_scan::config::load(Path::new(path)).unwrap().hash();
    assert!(err.contains(&hash(&a)) && err.contains(&hash(&b)), "{err}");
    // --resume with another config: refused likewise.
    let o = fake_run(&b, &out, &["--resume"]);
    assert!(stderr(&o).contains(&hash(&a)), "{}", stderr(&o));
    assert_eq!(rows(&out.join("samples.parquet")), before);
    assert_eq!(
        std::fs::read_to_string(out.join("summary.json")).unwrap(),
        summary
    );
    // The same config again is fine (it recomputes the same rows).
    fake_run_ok(&a, &out, &[]);
    assert_eq!(rows(&out.join("samples.parquet")), before);
    // --force replaces it.
    fake_run_ok(&b, &out, &["--force"]);
    assert_eq!(rows(&out.join("samples.parquet")).len(), 6);
}

#[test]
fn a_shard_of_another_layout_or_config_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let a = write(dir.path(), "a.toml", &paper_like(40, 1));
    let b = write(dir.path(), "b.toml", &paper_like(40, 2));
    let out = dir.path().join("sharded");
    for k in 0..4 {
        fake_run_ok(&a, &out, &["--shard", &format!("{k}/4")]);
    }
    let part1 = rows(&out.join("part-1.parquet"));
    // Shard 1 of 2 would replace part-1 of the 4-shard layout.
    let o = fake_run(&a, &out, &["--shard", "1/2"]);
    assert!(!o.status.success());
    let err = stderr(&o);
    assert!(
        err.contains("4-shard split") && err.contains("shard 1/2"),
        "{err}"
    );
    // A shard of another config.
    let o = fake_run(&b, &out, &["--shard", "1/4"]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("another scan"), "{}", stderr(&o));
    assert_eq!(rows(&out.join("part-1.parquet")), part1);
    // The same shard of the same scan again is fine.
    fake_run_ok(&a, &out, &["--shard", "1/4"]);
    run_ok(&["merge", s(&out)]);
}

#[test]
fn ad_hoc_runs_default_to_runs_slash_name_and_variants_get_their_own() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write(dir.path(), "tiny.toml", &paper_like(3, 2));
    let var = write(
        dir.path(),
        "v.toml",
        "name = \"pre\"\n[simulation]\nstrings.rest_length_ratio = 0.8\n",
    );
    let go = |extra: &[&str]| {
        let o = bin()
            .current_dir(dir.path())
            .args([&["run", cfg.as_str(), "--fake-sim", "0"], extra].concat())
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", stderr(&o));
    };
    go(&[]);
    go(&["--variant", &var]);
    go(&["--set", "contact.mu=0.5"]);
    go(&["--set", "contact.mu=0.6"]);
    let runs = dir.path().join("runs");
    let mut names: Vec<String> = std::fs::read_dir(&runs)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names.len(), 4, "{names:?}");
    assert_eq!(names[0], "tiny");
    assert!(names.contains(&"tiny+pre".to_string()), "{names:?}");
    assert_eq!(
        names.iter().filter(|n| n.starts_with("tiny+set-")).count(),
        2,
        "{names:?}"
    );
    for n in &names {
        assert!(runs.join(n).join("samples.parquet").exists(), "{n}");
    }
    assert!(!dir.path().join("results").exists());
}

// ---- item 3: no command clobbers its input or a file of another kind ----

#[test]
fn no_command_writes_over_its_input_or_another_kind_of_file() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write(dir.path(), "c.toml", &paper_like(60, 3));
    let out = dir.path().join("o");
    fake_run_ok(&cfg, &out, &[]);
    let samples = out.join("samples.parquet");
    let before = rows(&samples);

    run_err(
        &["cluster", s(&samples), "--assignments", s(&samples)],
        &["--assignments", "its own input", "--force"],
    );
    assert_eq!(rows(&samples), before);
    // The scan file is not a trace.
    run_err(
        &[&SIMULATE_FIG7A[..], &["--trace", s(&samples)]].concat(),
        &["--trace", "scan", "--force"],
    );
    assert_eq!(rows(&samples), before);
    // Nor a bifurcation diagram.
    run_err(
        &["bifurcation", "--points", "2", "--out", s(&samples)],
        &["--out", "scan", "--force"],
    );
    assert_eq!(rows(&samples), before);
    // Nor is the config an assignments file.
    run_err(
        &["cluster", s(&samples), "--assignments", &cfg],
        &["--assignments", "not a Parquet file"],
    );
    assert!(std::fs::read_to_string(&cfg).unwrap().contains("seed = 3"));
    // An assignments file may be rewritten by `cluster` (same kind).
    let assign = dir.path().join("a.parquet");
    run_ok(&["cluster", s(&samples), "--assignments", s(&assign)]);
    run_ok(&["cluster", s(&samples), "--assignments", s(&assign)]);

    // summary of a part must not replace the merged scan's summary files.
    let sharded = dir.path().join("sh");
    for k in 0..2 {
        fake_run_ok(&cfg, &sharded, &["--shard", &format!("{k}/2")]);
    }
    run_ok(&["merge", s(&sharded)]);
    let merged_summary = std::fs::read_to_string(sharded.join("summary.json")).unwrap();
    run_err(
        &["summary", s(&sharded.join("part-0.parquet"))],
        &["summary.json", "samples.parquet", "--force"],
    );
    assert_eq!(
        std::fs::read_to_string(sharded.join("summary.json")).unwrap(),
        merged_summary
    );
    // merge over a samples.parquet of another scan.
    let other = write(dir.path(), "other.toml", &paper_like(8, 9));
    let other_out = dir.path().join("other");
    fake_run_ok(&other, &other_out, &[]);
    std::fs::copy(
        other_out.join("samples.parquet"),
        sharded.join("samples.parquet"),
    )
    .unwrap();
    run_err(&["merge", s(&sharded)], &["another scan", "--force"]);
    assert_eq!(rows(&sharded.join("samples.parquet")).len(), 8);
    run_ok(&["merge", s(&sharded), "--force"]);
    assert_eq!(rows(&sharded.join("samples.parquet")), before);
}

// ---- item 4: trace size bound, temporary files ----

#[test]
fn an_oversized_trace_is_refused_with_its_estimate_and_leaves_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let trace = dir.path().join("t.parquet");
    let base = SIMULATE_FIG7A;
    let o = run_err(
        &[&base[..], &["--trace", s(&trace), "--set", "trace_dt=1e-9"]].concat(),
        &["--trace", "GB", "--trace-limit"],
    );
    assert!(
        o.status.code() == Some(1),
        "refused, not crashed: {}",
        o.status
    );
    assert!(!trace.exists());
    assert!(temp_files(dir.path()).is_empty());
    // A stray temporary file of a killed trace is removed by the next one.
    std::fs::write(dir.path().join(".t.parquet.abc123.tmp"), b"junk").unwrap();
    run_ok(
        &[
            &base[..],
            &[
                "--trace",
                s(&trace),
                "--set",
                "t_max=1",
                "--set",
                "trace_dt=0.01",
            ],
        ]
        .concat(),
    );
    assert!(trace.exists());
    assert_eq!(temp_files(dir.path()), Vec::<String>::new());
}

#[test]
fn ctrl_c_during_a_trace_removes_its_temporary_file() {
    let dir = tempfile::tempdir().unwrap();
    let trace = dir.path().join("t.parquet");
    let mut child = bin()
        .args(SIMULATE_FIG7A)
        .arg("--trace")
        .arg(&trace)
        .args(["--set", "trace_dt=2e-6", "--set", "t_max=20"])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let t0 = Instant::now();
    while temp_files(dir.path()).is_empty() {
        assert!(t0.elapsed() < Duration::from_secs(30), "no temporary file");
        std::thread::sleep(Duration::from_millis(5));
    }
    std::thread::sleep(Duration::from_millis(200));
    signal(&child, "INT");
    let st = wait_at_most(&mut child, Duration::from_secs(30), "interrupted trace");
    assert_eq!(st.code(), Some(130));
    assert!(!trace.exists());
    assert_eq!(temp_files(dir.path()), Vec::<String>::new());
}

#[test]
fn the_next_run_cleans_its_own_stray_temporary_files() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write(dir.path(), "c.toml", &paper_like(10, 1));
    let out = dir.path().join("o");
    std::fs::create_dir_all(&out).unwrap();
    // A merge killed while writing leaves `.samples.parquet.XXXX.tmp`.
    std::fs::write(out.join(".samples.parquet.x1y2z3.tmp"), b"junk").unwrap();
    // Not ours: another shard's, and a file of the user's.
    std::fs::write(out.join("notes.tmp"), b"mine").unwrap();
    fake_run_ok(&cfg, &out, &[]);
    assert_eq!(temp_files(&out), vec!["notes.tmp".to_string()]);
}

// ---- item 5: absurd sizes ----

#[test]
fn absurd_sizes_are_refused_or_start_at_once_and_stop_on_the_first_ctrl_c() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o");
    let base = paper_like(1, 1);
    // Beyond what can be held: refused with a message, not an abort.
    for (from, to, needle) in [
        ("samples = 1", "samples = 9000000000000000000", "samples"),
        (
            "fn = { uniform = [1.5, 5] }",
            "fn = { linspace = [1.5, 5, 10000000000000] }",
            "params.fn",
        ),
        ("samples = 1", "samples = 1000000\nname = \"g\"", "grid"),
    ] {
        let mut text = base.replacen(from, to, 1);
        if needle == "grid" {
            text = text
                .replace(
                    "rho = { uniform = [1, 5] }",
                    "rho = { linspace = [1, 5, 1000000] }",
                )
                .replace(
                    "alpha = { uniform = [0, 0.4] }",
                    "alpha = { linspace = [0, 0.4, 1000000] }",
                );
        }
        let cfg = write(dir.path(), "big.toml", &text);
        let t0 = Instant::now();
        let o = fake_run(&cfg, &out, &[]);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{needle}: {err}");
        assert!(err.contains(needle) && err.contains("at most"), "{err}");
        assert!(!err.contains("memory allocation"), "{err}");
        assert!(t0.elapsed() < Duration::from_secs(10));
    }
    // A trillion samples: accepted with --force (its output would not fit
    // on the disk), and the first sample runs at once (no pass over the
    // sample ids first); the first Ctrl-C stops it.
    let cfg = write(
        dir.path(),
        "huge.toml",
        &base.replacen("samples = 1", "samples = 1000000000000", 1),
    );
    let mut child = bin()
        .args(["run", &cfg, "--out", s(&out), "--fake-sim", "0"])
        .args(["--chunk-size", "1000", "--force"])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    wait_for(
        &mut child,
        &out.join(".partial/chunk-00000.parquet"),
        Duration::from_secs(20),
    );
    signal(&child, "INT");
    let st = wait_at_most(&mut child, Duration::from_secs(20), "interrupted huge run");
    assert_eq!(st.code(), Some(130));
    // Resuming it checks the chunks on disk without a pass over the ids.
    let mut child = bin()
        .args(["run", &cfg, "--out", s(&out), "--fake-sim", "0", "--resume"])
        .arg("--force")
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(1500));
    signal(&child, "INT");
    let st = wait_at_most(&mut child, Duration::from_secs(20), "interrupted resume");
    assert_eq!(st.code(), Some(130));
}

// ---- item 6: --threads ----

#[test]
fn threads_are_capped_at_a_multiple_of_the_cores() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write(dir.path(), "c.toml", &paper_like(4, 1));
    let out = dir.path().join("o");
    let cores = std::thread::available_parallelism().unwrap().get();
    let t0 = Instant::now();
    let o = fake_run(&cfg, &out, &["--threads", "1000000000"]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("--threads") && err.contains(&format!("at most {}", 4 * cores)),
        "{err}"
    );
    assert!(t0.elapsed() < Duration::from_secs(10));
    fake_run_ok(&cfg, &out, &["--threads", &(4 * cores).to_string()]);
}

// ---- item 7: corruption ----

/// Byte range of column `name`'s data in row group 0 of a Parquet file.
fn column_bytes(path: &Path, name: &str) -> (u64, u64) {
    use parquet::file::reader::{FileReader, SerializedFileReader};
    let r = SerializedFileReader::new(std::fs::File::open(path).unwrap()).unwrap();
    let rg = r.metadata().row_group(0);
    let col = (0..rg.num_columns())
        .map(|i| rg.column(i))
        .find(|c| c.column_path().string() == name)
        .unwrap();
    let (start, len) = col.byte_range();
    (start, len)
}

fn flip_bytes(path: &Path, at: u64, n: u64) {
    let mut b = std::fs::read(path).unwrap();
    for i in at..at + n {
        b[i as usize] ^= 0x5a;
    }
    std::fs::write(path, b).unwrap();
}

#[test]
fn a_corrupt_page_is_refused_by_summary_cluster_and_merge() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write(dir.path(), "c.toml", &paper_like(300, 5));
    let out = dir.path().join("o");
    fake_run_ok(&cfg, &out, &[]);
    let samples = out.join("samples.parquet");
    // 40 bytes in the middle of the alpha page: random doubles do not
    // compress, so zstd stores them raw and the bytes decode to other numbers.
    let (start, len) = column_bytes(&samples, "alpha");
    flip_bytes(&samples, start + len / 2, 40);
    let summary = std::fs::read_to_string(out.join("summary.json")).unwrap();
    for cmd in [vec!["summary"], vec!["cluster"], vec!["summary", "--json"]] {
        let args: Vec<&str> = cmd.iter().copied().chain([s(&samples)]).collect();
        run_err(&args, &["samples.parquet", "corrupt"]);
    }
    assert_eq!(
        std::fs::read_to_string(out.join("summary.json")).unwrap(),
        summary
    );

    let sharded = dir.path().join("sh");
    for k in 0..2 {
        fake_run_ok(&cfg, &sharded, &["--shard", &format!("{k}/2")]);
    }
    let part = sharded.join("part-1.parquet");
    let (start, len) = column_bytes(&part, "phi");
    flip_bytes(&part, start + len / 2, 40);
    run_err(&["merge", s(&sharded)], &["part-1.parquet", "corrupt"]);
    assert!(!sharded.join("samples.parquet").exists());
}

#[test]
fn values_outside_their_range_are_refused_naming_file_column_and_row() {
    use arrow::array::{Array, Float64Array, RecordBatch};
    use std::sync::Arc;
    let dir = tempfile::tempdir().unwrap();
    let cfg = write(dir.path(), "c.toml", &paper_like(20, 5));
    let out = dir.path().join("o");
    fake_run_ok(&cfg, &out, &[]);
    let samples = out.join("samples.parquet");
    // The same rows and metadata with alpha of row 7 set to 0.7, written
    // through rtw-scan's own writer (so the content hash matches).
    let input = rtw_scan::io::open(&samples, 1000).unwrap();
    let meta: Vec<_> = input
        .metadata
        .iter()
        .filter(|(k, _)| k.starts_with("rtw.") && k.as_str() != "rtw.content_hash")
        .map(|(k, v)| rtw_scan::io::kv(k, v.clone()))
        .collect();
    let batch: RecordBatch = input.reader.map(|b| b.unwrap()).next().unwrap();
    let i = batch.schema().index_of("alpha").unwrap();
    let alpha = batch
        .column(i)
        .as_any()
        .downcast_ref::<Float64Array>()
        .unwrap();
    let mut values: Vec<f64> = (0..alpha.len()).map(|r| alpha.value(r)).collect();
    values[7] = 0.7;
    let mut cols = batch.columns().to_vec();
    cols[i] = Arc::new(Float64Array::from(values));
    let bad = dir.path().join("bad.parquet");
    let batch = RecordBatch::try_new(batch.schema(), cols).unwrap();
    rtw_scan::io::write_file(&bad, &batch, meta).unwrap();
    run_err(
        &["summary", s(&bad)],
        &["bad.parquet", "alpha", "row 7", "0.7", "[0, 0.49]"],
    );
    run_err(&["cluster", s(&bad)], &["bad.parquet", "alpha", "row 7"]);
}

// ---- item 8: the small ones ----

#[test]
fn diverged_rows_carry_a_message() {
    let dir = tempfile::tempdir().unwrap();
    // ρ < 1.1 makes the fake simulator return a numerical `diverged`.
    let cfg = write(
        dir.path(),
        "c.toml",
        &paper_like(40, 4).replace(
            "rho = { uniform = [1, 5] }",
            "rho = { uniform = [1, 1.05] }",
        ),
    );
    let out = dir.path().join("o");
    fake_run_ok(&cfg, &out, &[]);
    let r = rows(&out.join("samples.parquet"));
    assert_eq!(r.len(), 40);
    for row in &r {
        assert!(row.contains(&"outcome=diverged".to_string()), "{row:?}");
        // The failure column names the kind; the message says it in words.
        assert!(row.contains(&"failure=work_budget".to_string()), "{row:?}");
        let msg = row.iter().find(|c| c.starts_with("message=")).unwrap();
        assert_eq!(
            msg,
            "message=numerical failure: the work budget max_steps ran out"
        );
    }
}

#[test]
fn a_concurrent_run_is_refused_naming_the_holder() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write(dir.path(), "c.toml", &paper_like(200, 4));
    let out = dir.path().join("o");
    let mut first = spawn_slow(&cfg, &out, "1", "20");
    wait_for(
        &mut first,
        &out.join(".partial/chunk-00000.parquet"),
        Duration::from_secs(30),
    );
    for extra in [&[][..], &["--resume"][..]] {
        let o = fake_run(&cfg, &out, extra);
        let err = stderr(&o);
        assert!(!o.status.success());
        assert!(
            err.contains(&format!("PID {}", first.id())) && !err.contains("pass --resume"),
            "{err}"
        );
    }
    signal(&first, "INT");
    assert_eq!(
        wait_at_most(&mut first, Duration::from_secs(30), "first run").code(),
        Some(130)
    );
    // Once it is gone, --resume finishes it.
    fake_run_ok(&cfg, &out, &["--resume"]);
    assert_eq!(rows(&out.join("samples.parquet")).len(), 200);
}

#[test]
fn set_values_variant_files_and_empty_configs_get_plain_messages() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write(dir.path(), "c.toml", &paper_like(3, 1));
    let out = dir.path().join("o");
    let o = fake_run(
        &cfg,
        &out,
        &["--set", "contact.mu=0.5\nstrings.slack=false"],
    );
    assert!(!o.status.success());
    assert!(stderr(&o).contains("newline"), "{}", stderr(&o));
    let missing = dir.path().join("nope.toml");
    let o = fake_run(&cfg, &out, &["--variant", s(&missing)]);
    let err = stderr(&o);
    assert!(
        err.contains("cannot read variant") && err.contains("nope.toml"),
        "{err}"
    );
    let empty = write(dir.path(), "empty.toml", "");
    let o = fake_run(&empty, &out, &[]);
    let err = stderr(&o);
    assert!(
        err.contains("empty.toml")
            && err.contains("seed")
            && err.contains("samples")
            && err.contains("[params]")
            && !err.contains("missing field"),
        "{err}"
    );
    assert!(!out.exists());
}

// ---- issue 15 item 6: CLI conventions ----

#[test]
fn quiet_json_summary_and_documented_exit_codes() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write(dir.path(), "c.toml", &paper_like(30, 2));
    let out = dir.path().join("o");
    let o = run_ok(&[
        "run",
        &cfg,
        "--out",
        s(&out),
        "--fake-sim",
        "0",
        "--quiet",
        "--set",
        "contact.mu=inf",
    ]);
    assert_eq!(stderr(&o), "", "--quiet prints nothing on stderr");
    assert!(stdout(&o).contains("rtw-scan summary"));
    // summary --json prints what summary.json holds; non-finite numbers are null.
    let samples = out.join("samples.parquet");
    let o = run_ok(&["summary", s(&samples), "--json"]);
    let printed: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    let file: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(printed, file);
    assert!(file["variant"]["mu"].is_null(), "{}", file["variant"]);
    let shard = dir.path().join("sh");
    for k in 0..2 {
        fake_run_ok(&cfg, &shard, &["--shard", &format!("{k}/2"), "--quiet"]);
    }
    let o = run_ok(&["merge", s(&shard), "--quiet"]);
    assert_eq!(stderr(&o), "");
    for cmd in [
        "run",
        "merge",
        "simulate",
        "bifurcation",
        "cluster",
        "summary",
    ] {
        let h = stdout(&run_ok(&[cmd, "--help"]));
        assert!(h.contains("Exit status:") && h.contains("0 "), "{cmd}: {h}");
        if ["run", "merge", "bifurcation"].contains(&cmd) {
            assert!(h.contains("--quiet"), "{cmd}");
        }
        if cmd == "run" {
            assert!(h.contains("130") && h.contains("SIGTERM"), "{h}");
        }
    }
}

#[test]
fn sigterm_and_sighup_keep_finished_chunks_like_ctrl_c() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write(dir.path(), "c.toml", &paper_like(80, 9));
    let full = dir.path().join("full");
    fake_run_ok(&cfg, &full, &[]);
    for sig in ["TERM", "HUP"] {
        let out = dir.path().join(sig);
        let mut child = spawn_slow(&cfg, &out, "2", "25");
        wait_for(
            &mut child,
            &out.join(".partial/chunk-00001.parquet"),
            Duration::from_secs(60),
        );
        signal(&child, sig);
        let st = wait_at_most(&mut child, Duration::from_secs(30), sig);
        assert_eq!(st.code(), Some(130), "SIG{sig}");
        assert!(out.join(".partial/chunk-00001.parquet").exists());
        fake_run_ok(&cfg, &out, &["--resume"]);
        assert_eq!(
            rows(&out.join("samples.parquet")),
            rows(&full.join("samples.parquet"))
        );
    }
}
