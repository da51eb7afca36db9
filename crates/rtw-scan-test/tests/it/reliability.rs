//! Finished results are never lost: no run, merge, summary, cluster, simulate
//! or bifurcation writes over another scan's results or its own input without
//! `--force`; sizes are bounded before anything is allocated; corrupt files
//! are refused; and the CLI conventions of docs/cli.md hold: `--quiet`,
//! SIGTERM and SIGHUP like Ctrl-C, `summary --json`, exit codes in `--help`.
//! Each test failed before its fix.

use crate::common::*;
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
    let hash = |path: &str| rtw_engine::config::load(Path::new(path)).unwrap().hash();
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
        err.contains(&format!(
            "--threads: 1000000000 is invalid: must be an integer in [1, {}] (4 per core, {cores} cores)",
            4 * cores
        )),
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

/// A fake scan of `n` rows (seed 5) in `dir/o`; its `samples.parquet` and
/// its config file.
fn fake_scan(dir: &Path, n: u64) -> (std::path::PathBuf, String) {
    let cfg = write(dir, "c.toml", &paper_like(n, 5));
    let out = dir.join("o");
    fake_run_ok(&cfg, &out, &[]);
    (out.join("samples.parquet"), cfg)
}

/// The same scan as `cfg`'s, run as two shards into `dir/sh` (not merged).
fn fake_shards(dir: &Path, cfg: &str) -> std::path::PathBuf {
    let sharded = dir.join("sh");
    for k in 0..2 {
        fake_run_ok(cfg, &sharded, &["--shard", &format!("{k}/2")]);
    }
    sharded
}

type Column = arrow_array::ArrayRef;
type Metadata = std::collections::BTreeMap<String, String>;

/// `samples`' rows with column `col` changed by `edit` and its metadata by
/// `meta`, written to `dest` through rtw-scan's own writer, so every hash
/// matches and only the value checks can tell.
fn forge(
    samples: &Path,
    dest: &Path,
    col: &str,
    edit: impl FnOnce(Column) -> Column,
    meta: impl FnOnce(&mut Metadata),
) {
    let input = rtw_engine::io::open(samples, 1 << 20).unwrap();
    let mut m = input.metadata.clone();
    meta(&mut m);
    let batch: arrow_array::RecordBatch = input.reader.map(|b| b.unwrap()).next().unwrap();
    let i = batch.schema().index_of(col).unwrap();
    let mut cols = batch.columns().to_vec();
    cols[i] = edit(cols[i].clone());
    let batch = arrow_array::RecordBatch::try_new(batch.schema(), cols).unwrap();
    let kv = m
        .into_iter()
        .map(|(k, v)| rtw_engine::io::kv(&k, v))
        .collect();
    rtw_engine::io::write_file(dest, &batch, kv).unwrap();
}

/// `edit` applied to the values of a column of Arrow type `T`.
fn values<T: arrow_array::types::ArrowPrimitiveType>(
    edit: impl FnOnce(&mut Vec<T::Native>),
) -> impl FnOnce(Column) -> Column {
    use arrow_array::{PrimitiveArray, cast::AsArray};
    move |c| {
        let mut v = c.as_primitive::<T>().values().to_vec();
        edit(&mut v);
        std::sync::Arc::new(PrimitiveArray::<T>::from_iter_values(v))
    }
}

/// `edit` applied to a `Float64` column.
fn floats(edit: impl FnOnce(&mut Vec<f64>)) -> impl FnOnce(Column) -> Column {
    values::<arrow_array::types::Float64Type>(edit)
}

#[test]
fn values_outside_their_range_are_refused_naming_file_column_and_row() {
    let dir = tempfile::tempdir().unwrap();
    let (samples, _) = fake_scan(dir.path(), 20);
    // The same rows and metadata with alpha of row 7 set to 0.7.
    let bad = dir.path().join("bad.parquet");
    forge(&samples, &bad, "alpha", floats(|v| v[7] = 0.7), |_| {});
    run_err(
        &["summary", s(&bad)],
        &["bad.parquet", "alpha", "row 7", "0.7", "[0, 0.49]"],
    );
    run_err(&["cluster", s(&bad)], &["bad.parquet", "alpha", "row 7"]);
}

/// Rewrites the key-value metadata of a Parquet file in place, as an editor
/// of its footer would: the row groups and pages keep their bytes; only the
/// footer after them is written anew, with its entries (in file order) passed
/// through `edit`.
fn rewrite_footer(path: &Path, edit: impl FnOnce(&mut Vec<(String, String)>)) {
    use parquet::file::metadata::{
        FileMetaData, KeyValue, ParquetMetaData, ParquetMetaDataReader, ParquetMetaDataWriter,
    };
    let bytes = std::fs::read(path).unwrap();
    let meta = ParquetMetaDataReader::new()
        .parse_and_finish(&std::fs::File::open(path).unwrap())
        .unwrap();
    let footer_len =
        u32::from_le_bytes(bytes[bytes.len() - 8..bytes.len() - 4].try_into().unwrap());
    let data_end = bytes.len() - 8 - footer_len as usize;
    let fm = meta.file_metadata();
    let mut kv: Vec<(String, String)> = fm
        .key_value_metadata()
        .into_iter()
        .flatten()
        .map(|kv| (kv.key.clone(), kv.value.clone().unwrap_or_default()))
        .collect();
    edit(&mut kv);
    let file_meta = FileMetaData::new(
        fm.version(),
        fm.num_rows(),
        fm.created_by().map(str::to_string),
        Some(kv.into_iter().map(|(k, v)| KeyValue::new(k, v)).collect()),
        fm.schema_descr_ptr(),
        fm.column_orders().cloned(),
    );
    let meta = ParquetMetaData::new(file_meta, meta.row_groups().to_vec());
    let mut out = bytes[..data_end].to_vec();
    ParquetMetaDataWriter::new(&mut out, &meta)
        .finish()
        .unwrap();
    std::fs::write(path, out).unwrap();
}

/// `key`'s value in `kv`, edited by `f`.
fn edit_value(kv: &mut [(String, String)], key: &str, f: impl FnOnce(&str) -> String) {
    let e = kv
        .iter_mut()
        .find(|(k, _)| k == key)
        .unwrap_or_else(|| panic!("no {key}"));
    e.1 = f(&e.1);
}

/// `key`'s name in `kv` with bit 0 of its last byte flipped.
fn flip_key_bit(kv: &mut [(String, String)], key: &str) -> String {
    let e = kv.iter_mut().find(|(k, _)| k == key).unwrap();
    let mut b = e.0.clone().into_bytes();
    *b.last_mut().unwrap() ^= 1;
    e.0 = String::from_utf8(b).unwrap();
    e.0.clone()
}

#[test]
fn a_footer_edited_in_place_is_refused_by_every_reader() {
    let dir = tempfile::tempdir().unwrap();
    let (samples, cfg) = fake_scan(dir.path(), 300);
    let pristine = std::fs::read(&samples).unwrap();
    // The helper itself keeps a file readable: an untouched footer rewritten.
    rewrite_footer(&samples, |_| {});
    run_ok(&["summary", s(&samples), "--json"]);

    // The model (the config text), the run's timing and version: each
    // decides what summary and cluster print.
    type Edit = fn(&str) -> String;
    let edits: [(&str, Edit); 4] = [
        ("rtw.config", |c| c.replace("t_max = 3.0", "t_max = 4.0")),
        ("rtw.config", |c| c.replace("seed = 5", "seed = 6")),
        ("rtw.wall_time_s", |_| "1e-9".into()),
        ("rtw.version", |_| "9.9.9".into()),
    ];
    for (key, f) in edits {
        std::fs::write(&samples, &pristine).unwrap();
        rewrite_footer(&samples, |kv| edit_value(kv, key, f));
        for cmd in [vec!["summary"], vec!["cluster"], vec!["summary", "--json"]] {
            let args: Vec<&str> = cmd.iter().copied().chain([s(&samples)]).collect();
            run_err(&args, &["samples.parquet", "metadata", "rtw.metadata_hash"]);
        }
    }

    // A part's shard and row count decide what merge joins.
    let sharded = fake_shards(dir.path(), &cfg);
    let part = sharded.join("part-1.parquet");
    rewrite_footer(&part, |kv| {
        edit_value(kv, "rtw.config", |c| {
            c.replace("t_max = 3.0", "t_max = 4.0")
        })
    });
    run_err(
        &["merge", s(&sharded)],
        &["part-1.parquet", "rtw.metadata_hash"],
    );
    assert!(!sharded.join("samples.parquet").exists());

    // A finished chunk of an interrupted run: --resume redoes it, saying
    // why, and the rows are the uninterrupted run's.
    let resumed = dir.path().join("r");
    let mut first = spawn_slow(&cfg, &resumed, "1", "20");
    let chunk = resumed.join(".partial/chunk-00000.parquet");
    wait_for(&mut first, &chunk, Duration::from_secs(30));
    signal(&first, "INT");
    wait_at_most(&mut first, Duration::from_secs(30), "first run");
    rewrite_footer(&chunk, |kv| {
        edit_value(kv, "rtw.config", |c| {
            c.replace("t_max = 3.0", "t_max = 4.0")
        })
    });
    let o = fake_run(&cfg, &resumed, &["--resume", "--chunk-size", "4"]);
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert!(
        err.contains("redoing") && err.contains("chunk-00000.parquet"),
        "{err}"
    );
    assert!(err.contains("rtw.metadata_hash"), "{err}");
    assert_eq!(rows(&resumed.join("samples.parquet")), rows(&samples));
}

#[test]
fn a_file_from_before_the_metadata_hash_is_read_only_if_its_config_matches_its_hash() {
    let dir = tempfile::tempdir().unwrap();
    let (samples, _) = fake_scan(dir.path(), 300);
    let want = stdout(&run_ok(&["summary", s(&samples), "--json"]));
    // Without the key, the file is as rtw-scan wrote it before the key
    // existed (the committed results): rows checked, config checked
    // against `rtw.config_hash`, same summary.
    rewrite_footer(&samples, |kv| kv.retain(|(k, _)| k != "rtw.metadata_hash"));
    let old = std::fs::read(&samples).unwrap();
    assert_eq!(stdout(&run_ok(&["summary", s(&samples), "--json"])), want);
    // Its config edited: refused, naming the key it no longer matches.
    rewrite_footer(&samples, |kv| {
        edit_value(kv, "rtw.config", |c| {
            c.replace("t_max = 3.0", "t_max = 4.0")
        })
    });
    for cmd in ["summary", "cluster"] {
        run_err(&[cmd, s(&samples)], &["samples.parquet", "rtw.config_hash"]);
    }
    // Its seed key disagreeing with its config: refused.
    std::fs::write(&samples, &old).unwrap();
    rewrite_footer(&samples, |kv| edit_value(kv, "rtw.seed", |_| "6".into()));
    run_err(&["summary", s(&samples)], &["samples.parquet", "rtw.seed"]);
    // A committed result (written before the key existed) still reads (a
    // copy: summary writes its summary beside it).
    let paper = dir.path().join("paper.parquet");
    std::fs::copy(workspace().join("results/paper/samples.parquet"), &paper).unwrap();
    run_ok(&["summary", s(&paper), "--json"]);
}

/// Every Parquet file under `dir`, recursively.
fn parquet_files(dir: &Path, found: &mut Vec<std::path::PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            parquet_files(&p, found);
        } else if p.extension().is_some_and(|x| x == "parquet") {
            found.push(p);
        }
    }
}

#[test]
fn every_committed_result_verifies_as_it_is() {
    // The committed results were written before `rtw.metadata_hash` and stay
    // bit-identical: each must pass the checks for such files, rows included.
    let mut files = Vec::new();
    parquet_files(&workspace().join("results"), &mut files);
    assert!(files.len() > 50, "{} files", files.len());
    for f in files {
        let input = rtw_engine::io::open(&f, 1 << 16).unwrap_or_else(|e| panic!("{e:#}"));
        assert!(
            input.metadata.contains_key("rtw.content_hash"),
            "{}",
            f.display()
        );
        for b in input.reader {
            b.unwrap_or_else(|e| panic!("{e:#}"));
        }
    }
}

#[test]
fn a_damaged_hash_key_is_refused_naming_the_file_and_the_key() {
    let dir = tempfile::tempdir().unwrap();
    let (samples, cfg) = fake_scan(dir.path(), 300);
    let pristine = std::fs::read(&samples).unwrap();
    let (start, len) = column_bytes(&samples, "alpha");
    for key in ["rtw.content_hash", "rtw.metadata_hash"] {
        // One bit of the key's name, then one data page.
        std::fs::write(&samples, &pristine).unwrap();
        let mut damaged = String::new();
        rewrite_footer(&samples, |kv| damaged = flip_key_bit(kv, key));
        flip_bytes(&samples, start + len / 2, 40);
        for cmd in [vec!["summary"], vec!["cluster"], vec!["summary", "--json"]] {
            let args: Vec<&str> = cmd.iter().copied().chain([s(&samples)]).collect();
            run_err(&args, &["samples.parquet", key]);
        }
    }
    // A file that looks old (no metadata hash) with its content hash's name
    // damaged: nothing vouches for its rows.
    std::fs::write(&samples, &pristine).unwrap();
    rewrite_footer(&samples, |kv| {
        kv.retain(|(k, _)| k != "rtw.metadata_hash");
        flip_key_bit(kv, "rtw.content_hash");
    });
    run_err(
        &["summary", s(&samples)],
        &["samples.parquet", "rtw.content_hash"],
    );

    // A merge part and a resumed run's chunk alike.
    let sharded = fake_shards(dir.path(), &cfg);
    let part = sharded.join("part-0.parquet");
    rewrite_footer(&part, |kv| {
        flip_key_bit(kv, "rtw.content_hash");
    });
    run_err(
        &["merge", s(&sharded)],
        &["part-0.parquet", "rtw.content_hash"],
    );
}

#[test]
fn ids_and_numbers_a_reader_relies_on_are_checked_in_every_file() {
    let dir = tempfile::tempdir().unwrap();
    let (samples, _) = fake_scan(dir.path(), 20);
    let file = |name: &str| dir.path().join(name);
    forge(
        &samples,
        &file("dup.parquet"),
        "sample_id",
        values::<arrow_array::types::Int64Type>(|v| v[5] = 4),
        |_| {},
    );
    forge(
        &samples,
        &file("neg.parquet"),
        "sample_id",
        values::<arrow_array::types::Int64Type>(|v| v[0] = -1),
        |_| {},
    );
    let nan = floats(|v| v[3] = f64::NAN);
    forge(&samples, &file("nan.parquet"), "wall_time_s", nan, |_| {});
    let inf = floats(|v| v[3] = f64::INFINITY);
    forge(&samples, &file("inf.parquet"), "wall_time_s", inf, |_| {});
    forge(
        &samples,
        &file("k.parquet"),
        "sample_id",
        |c| c,
        |m| {
            let c = m["rtw.config"].replace("k = 2", "k = -1");
            m.insert("rtw.config".into(), c);
        },
    );
    for (name, needles) in [
        ("dup.parquet", &["sample_id", "row 5", "4"][..]),
        ("neg.parquet", &["sample_id", "row 0", "-1"][..]),
        ("nan.parquet", &["wall_time_s", "row 3", "NaN"][..]),
        ("inf.parquet", &["wall_time_s", "row 3", "inf"][..]),
        ("k.parquet", &["cluster.k", "-1"][..]),
    ] {
        for cmd in ["summary", "cluster"] {
            let needles = [&[name][..], needles].concat();
            run_err(&[cmd, s(&file(name))], &needles);
        }
    }
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

// ---- CLI conventions: quiet runs, signals, JSON summaries, exit codes ----

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

/// A fake run of `cfg` into `out` (chunks of 4 rows) stopped by signal `sig`
/// once its second chunk exists, which must end it with status 130.
fn interrupted_by(cfg: &str, out: &Path, sig: &str) {
    let mut child = spawn_slow(cfg, out, "2", "25");
    wait_for(
        &mut child,
        &out.join(".partial/chunk-00001.parquet"),
        Duration::from_secs(60),
    );
    signal(&child, sig);
    let st = wait_at_most(&mut child, Duration::from_secs(30), sig);
    assert_eq!(st.code(), Some(130), "SIG{sig}");
}

#[test]
fn sigterm_and_sighup_keep_finished_chunks_like_ctrl_c() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write(dir.path(), "c.toml", &paper_like(80, 9));
    let full = dir.path().join("full");
    fake_run_ok(&cfg, &full, &[]);
    for sig in ["TERM", "HUP"] {
        let out = dir.path().join(sig);
        interrupted_by(&cfg, &out, sig);
        assert!(out.join(".partial/chunk-00001.parquet").exists());
        fake_run_ok(&cfg, &out, &["--resume"]);
        assert_eq!(
            rows(&out.join("samples.parquet")),
            rows(&full.join("samples.parquet"))
        );
    }
}

// ---- resume at any instant, across versions, and what it refuses ----

/// A fake run of `cfg` into `out` (chunks of 4 rows) stopped by SIGTERM once
/// its second chunk exists: an unfinished run with finished chunks.
fn interrupted(cfg: &str, out: &Path) {
    interrupted_by(cfg, out, "TERM");
}

/// Names in `dir`, sorted (none if it does not exist).
fn names(dir: &Path) -> Vec<String> {
    let mut n: Vec<String> = std::fs::read_dir(dir)
        .map(|d| {
            d.filter_map(Result::ok)
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .collect()
        })
        .unwrap_or_default();
    n.sort();
    n
}

#[test]
fn a_resume_by_another_rtw_scan_version_is_refused_naming_both() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write(dir.path(), "c.toml", &paper_like(80, 9));
    let full = dir.path().join("full");
    fake_run_ok(&cfg, &full, &[]);
    let out = dir.path().join("o");
    interrupted(&cfg, &out);
    // The unfinished run was started by an older rtw-scan.
    let ours = rtw_engine::VERSION;
    let manifest = out.join(".partial/manifest.json");
    let text = std::fs::read_to_string(&manifest).unwrap();
    let older = text.replace(
        &format!("\"version\": \"{ours}\""),
        "\"version\": \"0.0.9\"",
    );
    assert_ne!(text, older);
    std::fs::write(&manifest, older).unwrap();
    let before = names(&out.join(".partial"));
    let o = fake_run(&cfg, &out, &["--resume"]);
    assert!(!o.status.success());
    let err = stderr(&o);
    for needle in [
        "different rtw-scan versions",
        "from 0.0.9",
        &format!("from {ours}"),
    ] {
        assert!(err.contains(needle), "no {needle:?} in:\n{err}");
    }
    // Nothing was mixed or lost.
    assert!(!out.join("samples.parquet").exists());
    assert_eq!(names(&out.join(".partial")), before);
    // --force discards it and computes the scan anew with this version.
    fake_run_ok(&cfg, &out, &["--force"]);
    assert_eq!(
        rows(&out.join("samples.parquet")),
        rows(&full.join("samples.parquet"))
    );
}

#[test]
fn a_resume_of_another_config_names_both_and_what_differs() {
    let dir = tempfile::tempdir().unwrap();
    let named = |seed| format!("name = \"walk\"\n{}", paper_like(80, seed));
    let a = write(dir.path(), "a.toml", &named(9));
    let b = write(dir.path(), "b.toml", &named(10));
    let hash = |cfg: &str, name: &str| {
        let d = dir.path().join(name);
        fake_run_ok(cfg, &d, &[]);
        rtw_engine::io::open(&d.join("samples.parquet"), 1)
            .unwrap()
            .metadata["rtw.config_hash"]
            .clone()
    };
    let (ha, hb) = (hash(&a, "ra"), hash(&b, "rb"));
    let out = dir.path().join("o");
    interrupted(&a, &out);
    for extra in [&["--resume"][..], &[]] {
        let o = fake_run(&b, &out, extra);
        assert!(!o.status.success());
        let err = stderr(&o);
        for needle in [
            format!("config hash {ha} (name walk, seed 9)"),
            format!("config hash {hb} (name walk, seed 10)"),
            "seed 9 there, 10 here".to_string(),
        ] {
            assert!(err.contains(&needle), "no {needle:?} in:\n{err}");
        }
    }
}

#[test]
fn resume_finishes_every_state_a_kill_can_leave() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write(dir.path(), "c.toml", &paper_like(40, 3));
    let full = dir.path().join("full");
    fake_run_ok(&cfg, &full, &[]);
    let reference = rows(&full.join("samples.parquet"));
    let finished = |out: &Path, extra: &[&str]| -> String {
        let o = fake_run(&cfg, out, extra);
        let err = stderr(&o);
        assert!(o.status.success(), "{}: {err}", out.display());
        // Nothing refused (a refusal says "pass --force"); a rerun over
        // the complete scan may say --force computes it anew.
        assert!(!err.contains("pass --force"), "{err}");
        assert_eq!(rows(&out.join("samples.parquet")), reference);
        assert!(temp_files(out).is_empty(), "{:?}", names(out));
        err
    };

    // Killed before the manifest existed: `.partial` holds at most the
    // manifest's temporary file. Nothing was finished: resumed or not, the
    // run starts.
    for extra in [&["--resume"][..], &[]] {
        let out = dir.path().join(format!("no-manifest{}", extra.len()));
        std::fs::create_dir_all(out.join(".partial")).unwrap();
        std::fs::write(out.join(".partial/.manifest.json.a1b2c3.tmp"), "{").unwrap();
        finished(&out, extra);
        assert!(!out.join(".partial").exists());
    }

    // Killed while `.partial` was being removed after the merge: the scan is
    // complete; the resume only finishes the clean-up.
    let out = dir.path().join("cleanup");
    interrupted(&cfg, &out);
    std::fs::copy(full.join("samples.parquet"), out.join("samples.parquet")).unwrap();
    std::fs::remove_file(out.join(".partial/manifest.json")).unwrap();
    let err = finished(&out, &["--resume"]);
    assert!(err.contains("already complete"), "{err}");
    assert!(!out.join(".partial").exists());

    // Stray files rtw-scan did not make are reported and left alone, and do
    // not stop the resume.
    let out = dir.path().join("stray");
    interrupted(&cfg, &out);
    std::fs::write(out.join(".partial/notes.txt"), "mine").unwrap();
    std::fs::create_dir(out.join(".partial/plots")).unwrap();
    let err = finished(&out, &["--resume", "--chunk-size", "4"]);
    assert!(err.contains("notes.txt") && err.contains("plots"), "{err}");
    assert_eq!(names(&out.join(".partial")), ["notes.txt", "plots"]);
    assert_eq!(
        std::fs::read_to_string(out.join(".partial/notes.txt")).unwrap(),
        "mine"
    );
    // ... and still do not, once the scan is complete, resumed or rerun.
    finished(&out, &["--resume"]);
    finished(&out, &[]);
    assert_eq!(names(&out.join(".partial")), ["notes.txt", "plots"]);
}

/// Starts a fake run (chunks of 4 rows) that stops at `point` (the hidden
/// `RTW_SCAN_PAUSE` of test builds), waits until it says so, and kills it
/// with SIGKILL there.
fn kill_at(cfg: &str, out: &Path, point: &str, extra: &[&str]) {
    use std::io::BufRead;
    let mut child = bin()
        .args(["run", cfg, "--out", s(out), "--chunk-size", "4"])
        .args(["--fake-sim", "0"])
        .args(extra)
        .env("RTW_SCAN_PAUSE", point)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut err = std::io::BufReader::new(child.stderr.take().unwrap());
    let mut line = String::new();
    loop {
        line.clear();
        let n = err.read_line(&mut line).unwrap();
        assert!(n > 0, "the run ended without pausing at {point}");
        if line.contains(&format!("paused at {point}")) {
            break;
        }
    }
    child.kill().unwrap();
    child.wait().unwrap();
}

#[test]
fn a_sigkill_at_each_step_of_the_end_of_a_run_resumes_without_recomputing() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write(dir.path(), "c.toml", &paper_like(40, 4));
    let full = dir.path().join("full");
    fake_run_ok(&cfg, &full, &[]);
    for (point, there) in [
        ("manifest", ".partial"),
        ("merge", ".partial/manifest.json"),
        ("merged", "samples.parquet"),
        ("cleanup", "samples.parquet"),
    ] {
        let out = dir.path().join(point);
        kill_at(&cfg, &out, point, &[]);
        assert!(out.join(there).exists(), "{point}: {:?}", names(&out));
        assert!(out.join(".partial").exists(), "{point}");
        let o = fake_run(&cfg, &out, &["--resume"]);
        let err = stderr(&o);
        assert!(o.status.success(), "{point}: {err}");
        if point != "manifest" {
            // Every chunk was finished: none is computed again.
            assert!(err.contains("already complete"), "{point}: {err}");
        }
        assert_eq!(
            rows(&out.join("samples.parquet")),
            rows(&full.join("samples.parquet")),
            "{point}"
        );
        assert!(!out.join(".partial").exists(), "{point}");
        assert!(temp_files(&out).is_empty(), "{point}: {:?}", names(&out));
    }
    // A shard the same: killed during its clean-up, resumed, merged.
    let out = dir.path().join("shards");
    fake_run_ok(&cfg, &out, &["--shard", "0/2"]);
    kill_at(&cfg, &out, "cleanup", &["--shard", "1/2"]);
    assert!(out.join("part-1.parquet").exists() && out.join(".partial-1").exists());
    let o = fake_run(&cfg, &out, &["--shard", "1/2", "--resume"]);
    assert!(stderr(&o).contains("already complete"), "{}", stderr(&o));
    assert!(!out.join(".partial-1").exists());
    run_ok(&["merge", s(&out), "--quiet"]);
    assert_eq!(
        rows(&out.join("samples.parquet")),
        rows(&full.join("samples.parquet"))
    );
}

#[test]
fn a_chunk_size_beyond_its_range_is_refused_before_anything_is_allocated() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write(dir.path(), "c.toml", &paper_like(40, 3));
    for bad in ["10000000000", "65537"] {
        let out = dir.path().join(bad);
        let o = fake_run(&cfg, &out, &["--chunk-size", bad]);
        let err = stderr(&o);
        assert!(!o.status.success(), "{bad}: {err}");
        for needle in ["--chunk-size", bad, "1..=65536"] {
            assert!(err.contains(needle), "no {needle:?} in:\n{err}");
        }
        assert!(!out.join(".partial").exists());
    }
    fake_run_ok(&cfg, &dir.path().join("ok"), &["--chunk-size", "65536"]);
}
