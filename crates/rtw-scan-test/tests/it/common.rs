//! Helpers shared by the CLI tests: running the binary, reading rows back.

use arrow_array::RecordBatch;
use parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The `rtw-scan` command under test: `rtw-scan-test`, its test build (the
/// hidden `--fake-sim`, the pauses), which a plain `cargo build` beside the
/// tests never overwrites.
pub fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_rtw-scan-test"))
}

/// The workspace root.
pub fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// `configs/NAME.toml`.
pub fn config(name: &str) -> PathBuf {
    workspace().join("configs").join(format!("{name}.toml"))
}

/// `simulate` at the Fig. 7(a) point (main article): add flags after it.
pub const SIMULATE_FIG7A: [&str; 13] = [
    "simulate", "--length", "0.8", "--rho", "2.5", "--alpha", "0.125", "--fn", "3.269", "--zeta",
    "0.0514", "--phi", "0.15",
];

/// Runs the binary and returns its output, whatever the exit status.
pub fn run(args: &[&str]) -> Output {
    bin().args(args).output().expect("rtw-scan runs")
}

/// Runs the binary and asserts success.
pub fn run_ok(args: &[&str]) -> Output {
    let out = run(args);
    assert!(
        out.status.success(),
        "rtw-scan {args:?} failed ({}):\n{}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// Runs the binary and asserts it fails with every one of `needles` in its
/// error message.
pub fn run_err(args: &[&str], needles: &[&str]) -> Output {
    let out = run(args);
    let err = stderr(&out);
    assert!(
        !out.status.success(),
        "rtw-scan {args:?} should fail:\n{err}"
    );
    for needle in needles {
        assert!(
            err.contains(needle),
            "rtw-scan {args:?}: no {needle:?} in:\n{err}"
        );
    }
    out
}

/// Writes `text` to `dir/name` and returns the path as a string.
pub fn write(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_string()
}

pub fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// `run CONFIG --out OUT --fake-sim 0` plus `extra`.
pub fn fake_run(config: &str, out: &Path, extra: &[&str]) -> Output {
    run(&[&["run", config, "--out", s(out), "--fake-sim", "0"], extra].concat())
}

pub fn fake_run_ok(config: &str, out: &Path, extra: &[&str]) {
    let o = fake_run(config, out, extra);
    assert!(o.status.success(), "{}", stderr(&o));
}

pub fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

pub fn stdout(out: &Output) -> String {
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// A scan config with the paper's ranges and `samples` rows.
pub fn paper_like(samples: u64, seed: u64) -> String {
    format!(
        "seed = {seed}\nsamples = {samples}\n[params]\nlength = 0.8\nrho = {{ uniform = [1, 5] }}\n\
         alpha = {{ uniform = [0, 0.4] }}\nfn = {{ uniform = [1.5, 5] }}\nzeta = {{ uniform = [0.05, 0.1] }}\n\
         phi = {{ uniform = [0.05, 0.3] }}\n[simulation]\nt_max = 3.0\n"
    )
}

/// All batches of a Parquet file.
pub fn batches(path: &Path) -> Vec<RecordBatch> {
    let f = std::fs::File::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    ParquetRecordBatchReaderBuilder::try_new(f)
        .unwrap()
        .build()
        .unwrap()
        .map(|b| b.unwrap())
        .collect()
}

/// Every row of a samples file as strings, all columns but `wall_time_s`
/// (floats print as their shortest round-trip form: equal strings, equal bits).
pub fn rows(path: &Path) -> Vec<Vec<String>> {
    let mut rows = Vec::new();
    for b in batches(path) {
        let schema = b.schema();
        let cols: Vec<_> = schema
            .fields()
            .iter()
            .zip(b.columns())
            .filter(|(f, _)| f.name() != "wall_time_s")
            .map(|(f, c)| (f.name().clone(), c.as_ref()))
            .collect();
        for i in 0..b.num_rows() {
            rows.push(
                cols.iter()
                    .map(|(n, c)| format!("{n}={}", value(*c, i)))
                    .collect(),
            );
        }
    }
    rows
}

/// Row `i` of column `c` as text: `null`, a number in its shortest
/// round-trip form (equal strings, equal bits; `40.0`, `1e-7`), a string, or a dictionary's
/// value. Written here rather than taken from `arrow-cast`, whose build (with
/// `arrow-ord`) was a third of the test build's time.
pub fn value(c: &dyn arrow_array::Array, i: usize) -> String {
    use arrow_array::cast::AsArray;
    use arrow_array::types::*;
    use arrow_schema::DataType as T;
    if c.is_null(i) {
        return "null".into();
    }
    match c.data_type() {
        T::Boolean => c.as_boolean().value(i).to_string(),
        T::Int8 => c.as_primitive::<Int8Type>().value(i).to_string(),
        T::Int16 => c.as_primitive::<Int16Type>().value(i).to_string(),
        T::Int32 => c.as_primitive::<Int32Type>().value(i).to_string(),
        T::Int64 => c.as_primitive::<Int64Type>().value(i).to_string(),
        T::UInt8 => c.as_primitive::<UInt8Type>().value(i).to_string(),
        T::UInt16 => c.as_primitive::<UInt16Type>().value(i).to_string(),
        T::UInt32 => c.as_primitive::<UInt32Type>().value(i).to_string(),
        T::UInt64 => c.as_primitive::<UInt64Type>().value(i).to_string(),
        // Debug: the shortest round-trip form, whole numbers with ".0".
        T::Float32 => format!("{:?}", c.as_primitive::<Float32Type>().value(i)),
        T::Float64 => format!("{:?}", c.as_primitive::<Float64Type>().value(i)),
        T::Utf8 => c.as_string::<i32>().value(i).to_string(),
        T::LargeUtf8 => c.as_string::<i64>().value(i).to_string(),
        T::Dictionary(_, _) => {
            let d = c.as_any_dictionary();
            value(d.values().as_ref(), d.normalized_keys()[i])
        }
        t => panic!("rows: no text form for a column of {t}"),
    }
}

/// The column names of a Parquet file.
pub fn column_names(path: &Path) -> Vec<String> {
    let f = std::fs::File::open(path).unwrap();
    let b = ParquetRecordBatchReaderBuilder::try_new(f).unwrap();
    b.schema()
        .fields()
        .iter()
        .map(|f| f.name().clone())
        .collect()
}

/// The value of key `key` in a Parquet file's key-value metadata.
pub fn file_metadata(path: &Path, key: &str) -> String {
    let f = std::fs::File::open(path).unwrap();
    let b = ParquetRecordBatchReaderBuilder::try_new(f).unwrap();
    b.metadata()
        .file_metadata()
        .key_value_metadata()
        .and_then(|kv| kv.iter().find(|k| k.key == key))
        .and_then(|k| k.value.clone())
        .unwrap_or_else(|| panic!("{}: no `{key}` in its metadata", path.display()))
}

/// The lines `child` (its stderr piped) writes to stderr, as they come:
/// read on a thread of their own, so that a test can wait for one with a
/// timeout while the child runs.
pub fn stderr_lines(child: &mut std::process::Child) -> std::sync::mpsc::Receiver<String> {
    use std::io::BufRead;
    let err = child.stderr.take().expect("the child's stderr is piped");
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        for line in std::io::BufReader::new(err).lines().map_while(Result::ok) {
            if tx.send(line).is_err() {
                break;
            }
        }
    });
    rx
}

/// Sends SIGINT to `child` (as Ctrl-C does) and waits for it to end, at
/// most `limit`: past it the child is killed and the test fails. Its exit
/// status, and how long after the signal it ended.
pub fn interrupt(
    child: &mut std::process::Child,
    limit: std::time::Duration,
) -> (std::process::ExitStatus, std::time::Duration) {
    let sent = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(sent.success(), "kill -INT {}: {sent}", child.id());
    let t0 = std::time::Instant::now();
    loop {
        if let Some(status) = child.try_wait().unwrap() {
            return (status, t0.elapsed());
        }
        if t0.elapsed() > limit {
            child.kill().ok();
            child.wait().ok();
            panic!("still running {limit:?} after the interrupt");
        }
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
}
