//! Sharded scans through the binary, with the fake simulator: `run --shard
//! K/N` and `merge` give the single-machine rows, and the faults of a cluster
//! run (a killed task, a missing part, parts of different configs, versions
//! or shard counts, overlapping or missing ids) are refused by `merge` with a
//! message naming the shard, before anything is written.

use crate::common::*;
use arrow_array::{Array, ArrayRef, Int64Array, RecordBatch};
use rtw_engine::io as output;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::{Duration, Instant};

fn write_config(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_string()
}

/// `rtw-scan run CFG --out OUT --shard K/N --fake-sim 0` plus `extra`.
fn run_shard(cfg: &str, out: &Path, shard: &str, extra: &[&str]) {
    let args = [
        &["run", cfg, "--out", out.to_str().unwrap(), "--shard", shard][..],
        &["--fake-sim", "0"],
        extra,
    ]
    .concat();
    let o = run_ok(&args);
    assert!(
        stdout(&o).contains(&format!("shard {shard}")),
        "{}",
        stdout(&o)
    );
}

/// The single-machine run of `cfg` into `out`.
fn run_whole(cfg: &str, out: &Path) -> PathBuf {
    run_ok(&[
        "run",
        cfg,
        "--out",
        out.to_str().unwrap(),
        "--fake-sim",
        "0",
    ]);
    out.join("samples.parquet")
}

fn merge(dir: &Path) -> std::process::Output {
    run_ok(&["merge", dir.to_str().unwrap()])
}

/// `merge DIR` fails naming every needle, and writes no samples.parquet.
fn merge_refused(dir: &Path, needles: &[&str]) {
    run_err(&["merge", dir.to_str().unwrap()], needles);
    assert!(!dir.join("samples.parquet").exists(), "merge wrote a file");
}

fn metadata(path: &Path) -> std::collections::BTreeMap<String, String> {
    output::open(path, 1).unwrap().metadata
}

fn summary_outcomes(dir: &Path) -> serde_json::Value {
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    serde_json::json!([s["samples"], s["outcomes"], s["clusters"]])
}

#[test]
fn shards_merge_to_the_single_machine_rows() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write_config(dir.path(), "c.toml", &paper_like(50, 5));
    let single = run_whole(&cfg, &dir.path().join("single"));
    let out = dir.path().join("sharded");
    // Different thread counts and chunk sizes per shard; --resume on a fresh
    // directory simply runs (the sbatch script always passes it).
    run_shard(&cfg, &out, "0/4", &["--threads", "1", "--chunk-size", "5"]);
    run_shard(&cfg, &out, "3/4", &["--threads", "2", "--resume"]);
    run_shard(&cfg, &out, "1/4", &["--chunk-size", "3"]);
    run_shard(&cfg, &out, "2/4", &["--resume", "--chunk-size", "100"]);
    assert!(!out.join("samples.parquet").exists() && !out.join("summary.md").exists());

    // Each part holds its contiguous ids: ⌊K·50/4⌋..⌊(K+1)·50/4⌋.
    let single_meta = metadata(&single);
    let bounds = [0, 12, 25, 37, 50];
    for k in 0..4 {
        let part = out.join(format!("part-{k}.parquet"));
        let ids: Vec<String> = rows(&part).iter().map(|r| r[0].clone()).collect();
        let want: Vec<String> = (bounds[k]..bounds[k + 1])
            .map(|i| format!("sample_id={i}"))
            .collect();
        assert_eq!(ids, want, "part-{k}");
        let m = metadata(&part);
        assert_eq!(m["rtw.shard"], format!("{k}/4"));
        assert_eq!(m["rtw.total_rows"], "50");
        assert_eq!(m["rtw.seed"], "5");
        assert_eq!(m["rtw.version"], rtw_engine::VERSION);
        assert_eq!(m["rtw.config_hash"], single_meta["rtw.config_hash"]);
        assert_eq!(m["rtw.config"], single_meta["rtw.config"]);
        assert_eq!(m["rtw.config_hash"].len(), 16);
        assert!(!out.join(format!(".partial-{k}")).exists());
    }

    let o = merge(&out);
    assert!(stdout(&o).contains("rtw-scan summary"), "{}", stdout(&o));
    assert!(
        stderr(&o).contains("merged 4 shards, 50 rows"),
        "{}",
        stderr(&o)
    );
    let merged = out.join("samples.parquet");
    assert_eq!(rows(&merged), rows(&single));
    assert_eq!(rows(&merged).len(), 50);
    // The merged file carries the single run's metadata, plus the shard count.
    let m = metadata(&merged);
    for key in [
        "rtw.config",
        "rtw.config_hash",
        "rtw.seed",
        "rtw.version",
        "rtw.variant",
    ] {
        assert_eq!(m[key], single_meta[key], "{key}");
    }
    assert_eq!(m["rtw.shards"], "4");
    assert!(!m.contains_key("rtw.shard"));
    // Same summary and clusters as the single run (k-means is seeded by the
    // config's seed and sees the same failures in the same order).
    assert_eq!(
        summary_outcomes(&out),
        summary_outcomes(&dir.path().join("single"))
    );
    // Merging again gives the same rows (the parts are kept).
    merge(&out);
    assert_eq!(rows(&out.join("samples.parquet")), rows(&single));

    // One shard of one is the whole scan.
    let one = dir.path().join("one");
    run_shard(&cfg, &one, "0/1", &[]);
    merge(&one);
    assert_eq!(rows(&one.join("samples.parquet")), rows(&single));
}

fn chunk_files(partial: &Path) -> usize {
    std::fs::read_dir(partial)
        .map(|d| {
            d.filter_map(Result::ok)
                .filter(|e| e.file_name().to_string_lossy().starts_with("chunk-"))
                .count()
        })
        .unwrap_or(0)
}

#[test]
fn killed_shard_rerun_with_resume_merges_to_the_identical_file() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write_config(dir.path(), "c.toml", &paper_like(80, 8));
    let single = run_whole(&cfg, &dir.path().join("single"));
    let out = dir.path().join("sharded");
    for k in [0, 1, 3] {
        run_shard(&cfg, &out, &format!("{k}/4"), &["--chunk-size", "4"]);
    }
    // Shard 2 (ids 40..59) is killed (SIGKILL) after a few chunks.
    let partial = out.join(".partial-2");
    let mut child = bin()
        .args([
            "run",
            &cfg,
            "--out",
            out.to_str().unwrap(),
            "--shard",
            "2/4",
        ])
        .args(["--threads", "2", "--chunk-size", "4", "--fake-sim", "25"])
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let t0 = Instant::now();
    while chunk_files(&partial) < 2 {
        assert!(t0.elapsed() < Duration::from_secs(60), "no chunks landed");
        std::thread::sleep(Duration::from_millis(5));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    let kept = chunk_files(&partial);
    assert!((2..5).contains(&kept), "{kept} of 5 chunks kept");
    assert!(!out.join("part-2.parquet").exists());

    // The merge names the missing shard, its ids and its unfinished chunks.
    merge_refused(
        &out,
        &[
            "1 of 4 shards missing",
            "part-2.parquet (shard 2/4, sample_ids 40..59, unfinished: .partial-2 holds its finished chunks)",
            "--shard K/4",
            "--resume",
        ],
    );
    // Its chunks cannot be taken over by shard 2 of another split.
    run_err(
        &[
            "run",
            &cfg,
            "--out",
            out.to_str().unwrap(),
            "--shard",
            "2/5",
            "--resume",
            "--fake-sim",
            "0",
        ],
        &["4-shard split", "this run is shard 2/5"],
    );
    // Rerun with --resume: the kept chunks are reused, the rest computed.
    let o = run_ok(&[
        "run",
        &cfg,
        "--out",
        out.to_str().unwrap(),
        "--shard",
        "2/4",
        "--resume",
        "--fake-sim",
        "0",
    ]);
    assert!(stdout(&o).contains("20 rows"), "{}", stdout(&o));
    assert!(!partial.exists());
    merge(&out);
    assert_eq!(rows(&out.join("samples.parquet")), rows(&single));

    // A finished shard resumed again recomputes nothing.
    let o = run_ok(&[
        "run",
        &cfg,
        "--out",
        out.to_str().unwrap(),
        "--shard",
        "2/4",
        "--resume",
        "--fake-sim",
        "0",
    ]);
    assert!(stderr(&o).contains("already complete"), "{}", stderr(&o));
    // Shard 2 of another split would replace part-2 of this one: refused
    // (finished results are never lost), unless forced.
    let args = [
        "run",
        &cfg,
        "--out",
        out.to_str().unwrap(),
        "--shard",
        "2/5",
        "--resume",
        "--fake-sim",
        "0",
    ];
    run_err(
        &args,
        &["4-shard split", "this run is shard 2/5", "--force"],
    );
    assert_eq!(metadata(&out.join("part-2.parquet"))["rtw.shard"], "2/4");
    run_ok(&[&args[..], &["--force"]].concat());
    assert_eq!(metadata(&out.join("part-2.parquet"))["rtw.shard"], "2/5");
    // …and now part-2 is from another split: refused.
    std::fs::remove_file(out.join("samples.parquet")).unwrap();
    merge_refused(
        &out,
        &[
            "split the scan differently",
            "part-0.parquet is shard 0/4",
            "part-2.parquet is shard 2/5",
        ],
    );
}

#[test]
fn a_missing_part_is_named_with_its_ids() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write_config(dir.path(), "c.toml", &paper_like(50, 5));
    let out = dir.path().join("o");
    for k in [0, 2] {
        run_shard(&cfg, &out, &format!("{k}/4"), &[]);
    }
    merge_refused(
        &out,
        &[
            "2 of 4 shards missing",
            "part-1.parquet (shard 1/4, sample_ids 12..24)",
            "part-3.parquet (shard 3/4, sample_ids 37..49)",
        ],
    );
    // No parts at all, or no directory.
    let empty = dir.path().join("empty");
    std::fs::create_dir(&empty).unwrap();
    merge_refused(&empty, &["no part-K.parquet files in", "--shard K/N"]);
    run_err(
        &["merge", dir.path().join("nope").to_str().unwrap()],
        &["cannot read directory", "nope"],
    );
}

#[test]
fn a_long_list_of_missing_parts_is_counted_and_summarised_at_once() {
    // One part of a 10^12-way split (and of a 10^6-way one): merge counts
    // the missing parts without listing them all, names the first few, and
    // says how many more.
    let dir = tempfile::tempdir().unwrap();
    let cfg = write_config(
        dir.path(),
        "c.toml",
        &paper_like(1, 5).replacen("samples = 1", "samples = 1000000000000", 1),
    );
    for n in ["1000000", "1000000000000"] {
        let out = dir.path().join(format!("o{n}"));
        run_shard(&cfg, &out, &format!("1/{n}"), &[]);
        let missing = (n.parse::<u64>().unwrap() - 1).to_string();
        let t0 = Instant::now();
        let o = run_err(
            &["merge", out.to_str().unwrap()],
            &[
                &format!("{missing} of {n} shards missing"),
                &format!("part-0.parquet (shard 0/{n}"),
                &format!("part-2.parquet (shard 2/{n}"),
                "more",
            ],
        );
        assert!(t0.elapsed() < Duration::from_secs(10));
        assert!(stderr(&o).len() < 2000, "{}", stderr(&o).len());
    }
}

#[test]
fn parts_from_different_configs_or_versions_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let a = write_config(dir.path(), "a.toml", &paper_like(40, 5));
    let b = write_config(dir.path(), "b.toml", &paper_like(40, 6));
    let out = dir.path().join("o");
    run_shard(&a, &out, "0/2", &[]);
    // `run` itself refuses to mix two scans in one directory: --force does.
    run_shard(&b, &out, "1/2", &["--force"]);
    let (ha, hb) = (
        metadata(&out.join("part-0.parquet"))["rtw.config_hash"].clone(),
        metadata(&out.join("part-1.parquet"))["rtw.config_hash"].clone(),
    );
    assert_ne!(ha, hb);
    merge_refused(
        &out,
        &[
            "different configs",
            &format!("part-0.parquet has config hash {ha} (seed 5, 40 samples)"),
            &format!("part-1.parquet has config hash {hb} (seed 6, 40 samples)"),
        ],
    );

    // Same config, another rtw-scan version.
    run_shard(&a, &out, "1/2", &["--force"]);
    merge(&out);
    std::fs::remove_file(out.join("samples.parquet")).unwrap();
    rewrite_part(
        &out.join("part-1.parquet"),
        |_| {},
        |m| {
            m.insert("rtw.version".into(), "0.0.9".into());
        },
    );
    merge_refused(
        &out,
        &["different rtw-scan versions", "part-1.parquet from 0.0.9"],
    );

    // A part whose config was edited no longer matches its hash.
    run_shard(&a, &out, "1/2", &[]);
    rewrite_part(
        &out.join("part-1.parquet"),
        |_| {},
        |m| {
            let c = m["rtw.config"].replace("t_max = 3.0", "t_max = 4.0");
            m.insert("rtw.config".into(), c);
        },
    );
    merge_refused(
        &out,
        &["part-1.parquet: its config does not hash to", "altered"],
    );

    // A renamed part.
    run_shard(&a, &out, "1/2", &[]);
    std::fs::copy(out.join("part-1.parquet"), out.join("part-7.parquet")).unwrap();
    merge_refused(&out, &["part-7.parquet holds shard 1/2, not shard 7"]);
}

/// Rewrites a part file with its sample_ids changed by `ids` and its metadata
/// by `meta` (forging what a buggy or foreign writer could leave behind).
fn rewrite_part(
    path: &Path,
    ids: impl Fn(&mut Vec<i64>),
    meta: impl FnOnce(&mut std::collections::BTreeMap<String, String>),
) {
    let input = output::open(path, 1 << 20).unwrap();
    let mut m = input.metadata.clone();
    let batches: Vec<RecordBatch> = input.reader.map(|b| b.unwrap()).collect();
    let b = arrow_select::concat::concat_batches(&output::schema(), &batches).unwrap();
    let col = b.column(0).as_any().downcast_ref::<Int64Array>().unwrap();
    let mut v: Vec<i64> = col.values().to_vec();
    ids(&mut v);
    let mut cols = b.columns().to_vec();
    cols[0] = Arc::new(Int64Array::from(v)) as ArrayRef;
    let b = RecordBatch::try_new(output::schema(), cols).unwrap();
    meta(&mut m);
    let kv = m.into_iter().map(|(k, v)| output::kv(&k, v)).collect();
    output::write_file(path, &b, kv).unwrap();
}

#[test]
fn overlapping_duplicate_or_missing_ids_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write_config(dir.path(), "c.toml", &paper_like(30, 5));
    let out = dir.path().join("o");
    // --force: a part damaged below is still this scan's complete part by
    // its metadata, which a plain run leaves as it is; forced, it is made
    // again.
    let run_all = || {
        for k in 0..3 {
            run_shard(&cfg, &out, &format!("{k}/3"), &["--force"]);
        }
    };
    run_all();
    // Part 1 (ids 10..19) shifted down by one overlaps part 0.
    rewrite_part(
        &out.join("part-1.parquet"),
        |v| v.iter_mut().for_each(|i| *i -= 1),
        |_| {},
    );
    merge_refused(
        &out,
        &[
            "part-1.parquet: sample_id 9 is already in an earlier file",
            "overlap",
        ],
    );
    // Shifted up by one: id 10 is in no file.
    run_all();
    rewrite_part(
        &out.join("part-1.parquet"),
        |v| v.iter_mut().for_each(|i| *i += 1),
        |_| {},
    );
    merge_refused(
        &out,
        &[
            "part-1.parquet: sample_id 11 where 10 was expected",
            "sample_ids 10..10 are in no file",
        ],
    );
    // A duplicated row inside one part.
    run_all();
    rewrite_part(&out.join("part-2.parquet"), |v| v[3] = v[2], |_| {});
    merge_refused(
        &out,
        &["part-2.parquet: sample_id 22 is already in an earlier file (or twice in this one)"],
    );
    run_all();
    merge(&out);
}

#[test]
fn bad_shard_values_are_refused_naming_the_flag() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write_config(dir.path(), "c.toml", &paper_like(6, 1));
    let out = dir.path().join("o");
    for (shard, why) in [
        ("4/4", "K must be in 0..=3"),
        ("0/0", "N must be an integer >= 1"),
        ("2", "must be K/N"),
        ("x/2", "K must be an integer >= 0"),
        ("0/7", "N = 7 is more than the scan's 6 samples"),
    ] {
        run_err(
            &[
                "run",
                &cfg,
                "--out",
                out.to_str().unwrap(),
                "--shard",
                shard,
                "--fake-sim",
                "0",
            ],
            &["--shard", why],
        );
    }
    assert!(!out.join("part-0.parquet").exists());
    let h = stdout(&run_ok(&["run", "--help"]));
    assert!(
        h.contains("--shard <K/N>") && h.contains("rtw-scan merge DIR"),
        "{h}"
    );
    let h = stdout(&run_ok(&["--help"]));
    assert!(h.contains("merge"), "{h}");
}

/// A foreign part with a name `run` never writes (`part-01.parquet`, another
/// scan's shard 1) beside the good `part-1.parquet`: merge names the
/// foreign file, never the good one, so that removing the file it names
/// loses nothing. Every message names the file as it is on disk.
#[test]
fn merge_names_the_foreign_part_not_the_good_one_it_shadows() {
    let dir = tempfile::tempdir().unwrap();
    let a = write_config(dir.path(), "a.toml", &paper_like(40, 5));
    let b = write_config(dir.path(), "b.toml", &paper_like(40, 6));
    let (good, other) = (dir.path().join("good"), dir.path().join("other"));
    run_shard(&a, &good, "0/2", &[]);
    run_shard(&a, &good, "1/2", &[]);
    run_shard(&b, &other, "1/2", &[]);
    std::fs::copy(other.join("part-1.parquet"), good.join("part-01.parquet")).unwrap();
    let o = run_err(&["merge", s(&good)], &["part-01.parquet"]);
    let err = stderr(&o);
    assert!(
        !err.contains("part-1.parquet"),
        "merge blamed the good part:\n{err}"
    );
    assert!(!good.join("samples.parquet").exists());
    // Once the named file is gone, the good parts merge.
    std::fs::remove_file(good.join("part-01.parquet")).unwrap();
    merge(&good);
}
