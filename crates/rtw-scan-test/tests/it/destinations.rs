//! Where rtw-scan writes and what it reads whole: it never writes over a file
//! it cannot prove it made (another result's companion file, a summary a
//! person wrote), never through a symlink or over something that is not a
//! plain file (not even with `--force`); it reads configs and its own small
//! files with a stated size limit; and a scan that cannot fit on its disk is
//! refused before it starts. Each test failed before its fix.

use crate::common::*;
use std::path::Path;
use std::time::{Duration, Instant};

fn mkfifo(path: &Path) {
    let ok = std::process::Command::new("mkfifo")
        .arg(path)
        .status()
        .unwrap()
        .success();
    assert!(ok, "mkfifo {}", path.display());
}

fn is_fifo(path: &Path) -> bool {
    use std::os::unix::fs::FileTypeExt;
    std::fs::symlink_metadata(path)
        .map(|m| m.file_type().is_fifo())
        .unwrap_or(false)
}

fn is_symlink(path: &Path) -> bool {
    std::fs::symlink_metadata(path)
        .map(|m| m.file_type().is_symlink())
        .unwrap_or(false)
}

/// A tiny sweep at the Fig. 7(a) point into `out` (and its steps file).
fn tiny_sweep(out: &Path, extra: &[&str]) -> std::process::Output {
    run(&[
        &[
            "bifurcation",
            "--from",
            "0.14",
            "--to",
            "0.15",
            "--points",
            "2",
            "--transient",
            "10",
            "--record",
            "4",
            "--quiet",
            "--out",
            s(out),
        ][..],
        extra,
    ]
    .concat())
}

#[test]
fn another_results_companion_file_is_not_taken_for_an_earlier_output() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("phi.parquet");
    let o = tiny_sweep(&out, &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    let steps = dir.path().join("phi.steps.parquet");
    let before = std::fs::read(&steps).unwrap();
    // The steps file is a sweep's file, but not a sweep's per-value file.
    let o = tiny_sweep(&steps, &[]);
    let err = stderr(&o);
    assert!(!o.status.success(), "{err}");
    assert!(
        err.contains("--out") && err.contains("steps") && err.contains("--force"),
        "{err}"
    );
    assert_eq!(std::fs::read(&steps).unwrap(), before);
    // Nor is a per-value file a steps file: `--out x` where x.steps.parquet
    // is the per-value file of another sweep.
    std::fs::copy(&out, dir.path().join("y.steps.parquet")).unwrap();
    let o = tiny_sweep(&dir.path().join("y.parquet"), &[]);
    let err = stderr(&o);
    assert!(!o.status.success(), "{err}");
    assert!(err.contains("--out (steps file)"), "{err}");
    // A diagram's special-points file is not a diagram's branch file.
    let diagram = |out: &Path| {
        let flags = ["continuation", "--from", "0.145", "--to", "0.155", "--out"];
        run(&[&flags[..], &[s(out)]].concat())
    };
    let d = dir.path().join("d.parquet");
    let o = diagram(&d);
    assert!(o.status.success(), "{}", stderr(&o));
    let special = dir.path().join("d.special.parquet");
    let before = std::fs::read(&special).unwrap();
    let o = diagram(&special);
    let err = stderr(&o);
    assert!(!o.status.success(), "{err}");
    assert!(
        err.contains("another file of a continuation diagram") && err.contains("--force"),
        "{err}"
    );
    assert_eq!(std::fs::read(&special).unwrap(), before);
    // Its own earlier output may be replaced.
    let o = diagram(&d);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = tiny_sweep(&out, &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    // A Markdown file where the summary goes, beside an earlier sweep, is
    // not the sweep's summary when rtw-scan did not write it.
    std::fs::write(dir.path().join("phi.md"), "my notes\n").unwrap();
    let o = tiny_sweep(&out, &[]);
    let err = stderr(&o);
    assert!(!o.status.success(), "{err}");
    assert!(err.contains("phi.md") && err.contains("--force"), "{err}");
    assert_eq!(
        std::fs::read_to_string(dir.path().join("phi.md")).unwrap(),
        "my notes\n"
    );
}

#[test]
fn summaries_a_person_wrote_are_not_replaced_by_run_or_summary() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write(dir.path(), "c.toml", &paper_like(20, 3));
    for name in ["summary.md", "summary.json"] {
        let out = dir.path().join(format!("o-{name}"));
        std::fs::create_dir(&out).unwrap();
        std::fs::write(out.join(name), "mine\n").unwrap();
        let o = fake_run(&cfg, &out, &[]);
        let err = stderr(&o);
        assert!(!o.status.success(), "{name}: {err}");
        assert!(err.contains(name) && err.contains("--force"), "{err}");
        assert_eq!(std::fs::read_to_string(out.join(name)).unwrap(), "mine\n");
        assert!(
            !out.join("samples.parquet").exists(),
            "refused before the scan"
        );
        // --force replaces a plain file that is not rtw-scan's.
        let o = fake_run(&cfg, &out, &["--force"]);
        assert!(o.status.success(), "{}", stderr(&o));
        assert_ne!(std::fs::read_to_string(out.join(name)).unwrap(), "mine\n");
        // Its own summary is replaced by a rerun (`summary`) without --force.
        run_ok(&["summary", s(&out.join("samples.parquet"))]);
    }
    // `summary` with no summary.json but a summary.md of someone else's.
    let out = dir.path().join("o-summary.md");
    std::fs::remove_file(out.join("summary.json")).unwrap();
    std::fs::write(out.join("summary.md"), "mine\n").unwrap();
    run_err(
        &["summary", s(&out.join("samples.parquet"))],
        &["summary.md", "--force"],
    );
    assert_eq!(
        std::fs::read_to_string(out.join("summary.md")).unwrap(),
        "mine\n"
    );
}

#[test]
fn symlinks_and_special_files_are_refused_even_with_force() {
    let dir = tempfile::tempdir().unwrap();
    let victim = dir.path().join("victim.txt");
    std::fs::write(&victim, "keep me\n").unwrap();

    // A lock file that is a symlink: its target is not truncated.
    let cfg = write(dir.path(), "c.toml", &paper_like(8, 3));
    let out = dir.path().join("o");
    std::fs::create_dir(&out).unwrap();
    let lock = out.join(".samples.parquet.lock");
    std::os::unix::fs::symlink(&victim, &lock).unwrap();
    let o = fake_run(&cfg, &out, &["--force"]);
    let err = stderr(&o);
    assert!(!o.status.success(), "{err}");
    assert!(
        err.contains(".samples.parquet.lock") && err.contains("symlink"),
        "{err}"
    );
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "keep me\n");
    assert!(is_symlink(&lock));
    std::fs::remove_file(&lock).unwrap();
    // A plain file by that name that holds something else than a PID.
    std::fs::write(&lock, "keep me too\n").unwrap();
    let o = fake_run(&cfg, &out, &["--force"]);
    let err = stderr(&o);
    assert!(!o.status.success(), "{err}");
    assert!(err.contains("did not make it"), "{err}");
    assert_eq!(std::fs::read_to_string(&lock).unwrap(), "keep me too\n");
    std::fs::remove_file(&lock).unwrap();
    // A stale lock of a killed run (a PID) is taken over.
    std::fs::write(&lock, "12345\n").unwrap();
    let o = fake_run(&cfg, &out, &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!lock.exists());
    std::fs::remove_dir_all(&out).unwrap();
    std::fs::create_dir(&out).unwrap();

    // --trace on a FIFO (a special file like a device) or a symlink.
    let fifo = dir.path().join("fifo");
    mkfifo(&fifo);
    let link = dir.path().join("link.parquet");
    std::os::unix::fs::symlink(&victim, &link).unwrap();
    for (dest, needle) in [(&fifo, "not a regular file"), (&link, "symlink")] {
        let o = run(&[
            &SIMULATE_FIG7A[..],
            &["--set", "t_max=0.2", "--trace", s(dest), "--force"],
        ]
        .concat());
        let err = stderr(&o);
        assert!(!o.status.success(), "{err}");
        assert!(err.contains("--trace") && err.contains(needle), "{err}");
    }
    assert!(is_fifo(&fifo), "the FIFO is still a FIFO");
    assert!(is_symlink(&link));
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "keep me\n");

    // summary.md a symlink, with --force: refused; the link and its target stay.
    let o = fake_run(&cfg, &out, &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    let md = out.join("summary.md");
    std::fs::remove_file(&md).unwrap();
    std::os::unix::fs::symlink(&victim, &md).unwrap();
    run_err(
        &["summary", s(&out.join("samples.parquet")), "--force"],
        &["summary.md", "symlink"],
    );
    assert!(is_symlink(&md));
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "keep me\n");
    // A directory where samples.parquet goes.
    let o2 = dir.path().join("o2");
    std::fs::create_dir_all(o2.join("samples.parquet")).unwrap();
    let o = fake_run(&cfg, &o2, &["--force"]);
    let err = stderr(&o);
    assert!(!o.status.success(), "{err}");
    assert!(
        err.contains("samples.parquet") && err.contains("not a regular file"),
        "{err}"
    );
    assert!(o2.join("samples.parquet").is_dir());
}

#[test]
fn configs_and_variants_are_read_within_a_size_limit_and_only_from_plain_files() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o");
    let t0 = Instant::now();
    run_err(
        &["run", "/dev/zero", "--out", s(&out)],
        &["config /dev/zero", "not a regular file"],
    );
    let cfg = write(dir.path(), "c.toml", &paper_like(3, 1));
    run_err(
        &["run", &cfg, "--variant", "/dev/zero", "--out", s(&out)],
        &["variant /dev/zero", "not a regular file"],
    );
    run_err(
        &[&SIMULATE_FIG7A[..], &["--config", "/dev/zero"]].concat(),
        &["config /dev/zero", "not a regular file"],
    );
    // A regular file larger than the limit (4 MB: a refinement round's
    // config stores up to 10⁴ points): named, with the limit.
    let big = dir.path().join("big.toml");
    let mut text = paper_like(3, 1);
    text.push_str(&"# padding\n".repeat(500_000));
    std::fs::write(&big, text).unwrap();
    run_err(
        &["run", s(&big), "--out", s(&out)],
        &["big.toml", "4.0 MB", "at most"],
    );
    assert!(t0.elapsed() < Duration::from_secs(20));
    assert!(!out.exists());
}

#[test]
fn a_scan_larger_than_the_free_space_is_refused_unless_forced() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write(
        dir.path(),
        "huge.toml",
        &paper_like(1, 1).replacen("samples = 1", "samples = 1000000000000", 1),
    );
    let out = dir.path().join("o");
    for extra in [&[][..], &["--shard", "0/2"][..]] {
        let o = fake_run(&cfg, &out, extra);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{err}");
        assert!(
            err.contains("TB") && err.contains("free") && err.contains("--force"),
            "{err}"
        );
        assert!(!out.join(".partial").exists() && !out.join(".partial-0").exists());
    }
    // A small scan fits.
    let small = write(dir.path(), "small.toml", &paper_like(5, 1));
    let o = fake_run(&small, &dir.path().join("s"), &[]);
    assert!(o.status.success(), "{}", stderr(&o));
}

/// An output directory where something else is (a device, a plain file, a
/// dangling `.partial` link) is refused saying what is there and what to
/// do, not with the OS's "File exists (os error 17)"; nothing is changed.
#[test]
fn an_output_directory_that_is_not_one_is_refused_saying_what_is_there() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = config("smoke");
    let cfg = s(&cfg);
    let o = fake_run(cfg, Path::new("/dev/null"), &[]);
    let err = stderr(&o);
    assert!(!o.status.success());
    for needle in [
        "--out /dev/null",
        "character device",
        "not a directory",
        "choose",
    ] {
        assert!(err.contains(needle), "no {needle:?} in:\n{err}");
    }
    assert!(!err.contains("os error 17"), "{err}");
    let plain = dir.path().join("plainfile");
    std::fs::write(&plain, "notes").unwrap();
    let o = fake_run(cfg, &plain, &[]);
    let err = stderr(&o);
    assert!(!o.status.success());
    for needle in ["plainfile", "a regular file", "not a directory", "choose"] {
        assert!(err.contains(needle), "no {needle:?} in:\n{err}");
    }
    assert!(!err.contains("os error 17"), "{err}");
    assert_eq!(std::fs::read(&plain).unwrap(), b"notes");
    let out = dir.path().join("r");
    std::fs::create_dir(&out).unwrap();
    std::os::unix::fs::symlink("/nonexistent/rtw", out.join(".partial")).unwrap();
    let o = fake_run(cfg, &out, &[]);
    let err = stderr(&o);
    assert!(!o.status.success());
    for needle in [".partial", "symlink", "/nonexistent/rtw", "remove"] {
        assert!(err.contains(needle), "no {needle:?} in:\n{err}");
    }
    assert!(!err.contains("os error 17"), "{err}");
    assert!(is_symlink(&out.join(".partial")));
}
