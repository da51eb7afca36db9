//! Sampling designs through the binary (shards, merge, resume) and the
//! `sensitivity` command, with the fake simulator.

use crate::common::*;

fn designed(sampling: &str, samples: u64) -> String {
    paper_like(samples, 3).replace(
        &format!("samples = {samples}\n"),
        &format!("samples = {samples}\nsampling = \"{sampling}\"\n"),
    )
}

#[test]
fn a_saltelli_scan_in_shards_merges_to_the_rows_and_indices_of_one_run() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write(dir.path(), "salt.toml", &designed("saltelli", 16));
    let one = dir.path().join("one");
    fake_run_ok(&cfg, &one, &[]);
    let split = dir.path().join("split");
    for k in ["0/2", "1/2"] {
        fake_run_ok(&cfg, &split, &["--shard", k]);
    }
    run_ok(&["merge", s(&split)]);
    let a = run_ok(&["sensitivity", s(&one), "--json"]);
    let b = run_ok(&["sensitivity", s(&split), "--json"]);
    assert_eq!(stdout(&a), stdout(&b));
    let rows: Vec<serde_json::Value> = serde_json::from_str(&stdout(&a)).unwrap();
    // Every label, stable and failure (and the continuous outputs the fake
    // run gives every row) × 5 uniform inputs; a Saltelli scan has total indices.
    for output in [
        "skip", "walk", "crawl", "collapse", "stall", "diverged", "stable", "failure",
    ] {
        let n = rows.iter().filter(|r| r["output"] == output).count();
        assert_eq!(n, 5, "{output}");
    }
    assert_eq!(rows.len() % 5, 0);
    assert!(
        rows.iter()
            .all(|r| r["ST"].is_number() || r["ST"].is_null())
    );
    assert!(rows.iter().any(|r| r["ST"].is_number()));
    assert!(one.join("indices.parquet").exists());
    // Its own earlier output is replaced; its input and other files are not.
    run_ok(&["sensitivity", s(&one)]);
    let samples = one.join("samples.parquet");
    run_err(
        &["sensitivity", s(&one), "--out", s(&samples)],
        &["its own input"],
    );
    let summary = one.join("summary.json");
    std::fs::write(one.join("x.parquet"), b"not parquet").unwrap();
    run_err(
        &["sensitivity", s(&one), "--out", s(&one.join("x.parquet"))],
        &["not a Parquet file", "--force"],
    );
    assert!(summary.exists());
}

#[test]
fn a_random_scan_gets_given_data_indices_and_a_grid_scan_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write(dir.path(), "r.toml", &paper_like(200, 4));
    let out = dir.path().join("r");
    fake_run_ok(&cfg, &out, &[]);
    let o = run_ok(&["sensitivity", s(&out), "--json", "--resamples", "20"]);
    let rows: Vec<serde_json::Value> = serde_json::from_str(&stdout(&o)).unwrap();
    assert!(
        rows.iter()
            .all(|r| r["ST"].is_null() && r["S1"].is_number())
    );
    let grid = paper_like(4, 4).replace("length = 0.8", "length = [0.7, 0.8]");
    let g = write(dir.path(), "g.toml", &grid);
    let gout = dir.path().join("g");
    fake_run_ok(&g, &gout, &[]);
    run_err(&["sensitivity", s(&gout)], &["grid axes"]);
    // The resamples' range is the library's, as in Python: at least 2 (a
    // half-width needs two resamples), at most 10^4 (not an allocation that
    // aborts).
    for n in [
        "0",
        "1",
        "1000000000000",
        "100000000000000000000000000000000000000000",
    ] {
        run_err(
            &["sensitivity", s(&out), "--resamples", n],
            &[&format!(
                "--resamples: {n} is invalid: must be an integer in [2, 10000]"
            )],
        );
    }
    run_err(
        &["sensitivity", s(&out), "--seed", "18446744073709551616"],
        &[
            "--seed: 18446744073709551616 is invalid: must be an integer in [0, 18446744073709551615]",
        ],
    );
}

#[test]
fn a_shard_of_another_design_is_refused_and_threads_do_not_change_a_design() {
    let dir = tempfile::tempdir().unwrap();
    let random = write(dir.path(), "random.toml", &designed("random", 40));
    let sobol = write(dir.path(), "sobol.toml", &designed("sobol", 40));
    let out = dir.path().join("mixed");
    fake_run_ok(&random, &out, &["--shard", "0/2"]);
    let o = fake_run(&sobol, &out, &["--shard", "1/2", "--resume"]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("config hash"), "{}", stderr(&o));
    // The same rows for any thread count and for a resumed run hold for a design too.
    let a = dir.path().join("a");
    let b = dir.path().join("b");
    fake_run_ok(&sobol, &a, &["--threads", "1"]);
    fake_run_ok(&sobol, &b, &["--threads", "2"]);
    let rows = |d: &std::path::Path| {
        let o = run_ok(&["sensitivity", s(d), "--json", "--resamples", "5"]);
        stdout(&o)
    };
    assert_eq!(rows(&a), rows(&b));
}

#[test]
fn indices_record_their_scan_and_another_scans_are_never_replaced() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (dir.path().join("a"), dir.path().join("b"));
    fake_run_ok(&write(dir.path(), "a.toml", &paper_like(40, 1)), &a, &[]);
    fake_run_ok(&write(dir.path(), "b.toml", &paper_like(40, 2)), &b, &[]);
    let theirs = b.join("indices.parquet");
    run_ok(&["sensitivity", s(&b), "--resamples", "5"]);
    let before = std::fs::read(&theirs).unwrap();
    // The file says whose indices it holds: the scan's content hash.
    let footer = |p: &std::path::Path, key: &str| -> String {
        use parquet::file::reader::FileReader;
        let f = std::fs::File::open(p).unwrap();
        let r = parquet::file::reader::SerializedFileReader::new(f).unwrap();
        let kv = r.metadata().file_metadata().key_value_metadata().unwrap();
        let v = kv.iter().find(|k| k.key == key).unwrap();
        v.value.clone().unwrap()
    };
    let meta = |p: &std::path::Path| -> serde_json::Value {
        serde_json::from_str(&footer(p, "rtw.sensitivity")).unwrap()
    };
    let hash = |p: &std::path::Path| footer(p, "rtw.content_hash");
    assert_eq!(
        meta(&theirs)["scan_content_hash"],
        hash(&b.join("samples.parquet"))
    );
    // A's indices are not written over B's.
    run_err(
        &["sensitivity", s(&a), "--out", s(&theirs)],
        &["holds the indices of another scan", "--force"],
    );
    assert_eq!(std::fs::read(&theirs).unwrap(), before);
    // B's own are replaced; with --force A's go there too.
    run_ok(&["sensitivity", s(&b), "--resamples", "6"]);
    run_ok(&["sensitivity", s(&a), "--out", s(&theirs), "--force"]);
    assert_eq!(
        meta(&theirs)["scan_content_hash"],
        hash(&a.join("samples.parquet"))
    );
}
