//! A closed stdout (`rtw-scan … | head -c 1`, `| true`): every command ends
//! quietly with exit status 141 (128 + SIGPIPE, as a shell reports a
//! process a closed pipe ended), no panic, its finished files kept and no
//! temporary file left.

use crate::common::*;
use std::path::Path;
use std::process::{Output, Stdio};

/// Runs the binary with `args`, its stdout a pipe whose reading end is
/// already closed: its first write to stdout meets EPIPE.
fn closed_stdout(args: &[&str]) -> Output {
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    bin()
        .args(args)
        .stdout(Stdio::from(writer))
        .stderr(Stdio::piped())
        .output()
        .unwrap()
}

/// Asserts the quiet exit of a closed stdout.
fn ended_quietly(args: &[&str]) {
    let out = closed_stdout(args);
    let err = stderr(&out);
    assert_eq!(
        out.status.code(),
        Some(141),
        "{args:?}: {}\n{err}",
        out.status
    );
    assert!(
        !err.contains("panicked") && !err.contains("Broken pipe"),
        "{args:?}: {err}"
    );
}

/// The names of the files under `dir` (recursively) that look temporary.
fn temporaries(dir: &Path) -> Vec<String> {
    let mut found = Vec::new();
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        let name = p.file_name().unwrap().to_string_lossy().to_string();
        if p.is_dir() {
            found.extend(temporaries(&p));
        } else if name.ends_with(".tmp") || name.ends_with(".lock") {
            found.push(p.display().to_string());
        }
    }
    found
}

#[test]
fn simulate_to_a_closed_pipe_ends_quietly() {
    ended_quietly(&[&SIMULATE_FIG7A[..], &["--json"]].concat());
    ended_quietly(&SIMULATE_FIG7A);
}

#[test]
fn profile_to_a_closed_pipe_keeps_its_files() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("pp.parquet");
    ended_quietly(&[
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
        "0.1",
        "--to",
        "0.2",
        "--json",
        "--quiet",
        "--out",
        s(&out),
    ]);
    assert!(out.exists() && dir.path().join("pp.md").exists());
    assert_eq!(temporaries(dir.path()), Vec::<String>::new());
}

#[test]
fn run_to_a_closed_pipe_keeps_its_scan() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("pipe_run");
    ended_quietly(&[
        "run",
        s(&config("smoke")),
        "--out",
        s(&out),
        "--fake-sim",
        "0",
        "--quiet",
    ]);
    assert!(out.join("samples.parquet").exists());
    assert!(!out.join(".partial").exists());
    assert_eq!(temporaries(dir.path()), Vec::<String>::new());
}
