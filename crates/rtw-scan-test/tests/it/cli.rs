//! End-to-end tests of the scan machinery through the binary, with the fake
//! simulator (hidden `--fake-sim MS`): determinism, interruption and resume,
//! bad input, the `simulate`, `cluster` and `summary` commands. They need no
//! physics; `cli_physics.rs` runs the real simulator.

use crate::common::*;
use std::path::Path;
use std::time::{Duration, Instant};

fn write_config(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_string()
}

#[test]
fn same_seed_same_rows_with_one_or_two_threads() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write_config(dir.path(), "c.toml", &paper_like(50, 5));
    let (a, b) = (dir.path().join("a"), dir.path().join("b"));
    let (a_s, b_s) = (a.to_str().unwrap(), b.to_str().unwrap());
    run_ok(&[
        "run",
        &cfg,
        "--out",
        a_s,
        "--threads",
        "1",
        "--chunk-size",
        "7",
        "--fake-sim",
        "0",
    ]);
    run_ok(&[
        "run",
        &cfg,
        "--out",
        b_s,
        "--threads",
        "2",
        "--chunk-size",
        "7",
        "--fake-sim",
        "1",
    ]);
    let (ra, rb) = (
        rows(&a.join("samples.parquet")),
        rows(&b.join("samples.parquet")),
    );
    assert_eq!(ra.len(), 50);
    assert_eq!(ra, rb);
    // The rows are not all alike, and ids run 0..50 in order.
    assert!(
        ra.iter()
            .any(|r| r.contains(&"outcome=diverged".to_string()))
    );
    assert!(ra.iter().any(|r| r.contains(&"outcome=walk".to_string())));
    for (i, r) in ra.iter().enumerate() {
        assert_eq!(r[0], format!("sample_id={i}"));
    }
    for d in [&a, &b] {
        assert!(d.join("summary.json").exists() && d.join("summary.md").exists());
        assert!(!d.join(".partial").exists());
    }
    // A different seed gives different rows.
    let c = dir.path().join("c");
    let cfg2 = write_config(dir.path(), "c2.toml", &paper_like(50, 6));
    run_ok(&[
        "run",
        &cfg2,
        "--out",
        c.to_str().unwrap(),
        "--fake-sim",
        "0",
    ]);
    assert_ne!(rows(&c.join("samples.parquet")), ra);
}

fn chunk_files(partial: &Path) -> usize {
    std::fs::read_dir(partial)
        .map(|d| {
            d.filter_map(Result::ok)
                .filter(|e| {
                    let n = e.file_name().to_string_lossy().into_owned();
                    n.starts_with("chunk-") && n.ends_with(".parquet")
                })
                .count()
        })
        .unwrap_or(0)
}

/// Starts a slow fake run and waits until `chunks` chunk files have landed.
fn start_and_wait(cfg: &str, out: &Path, chunks: usize) -> std::process::Child {
    let child = bin()
        .args(["run", cfg, "--out", out.to_str().unwrap(), "--threads", "2"])
        .args(["--chunk-size", "4", "--fake-sim", "25"])
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let t0 = Instant::now();
    while chunk_files(&out.join(".partial")) < chunks {
        assert!(t0.elapsed() < Duration::from_secs(60), "no chunks landed");
        std::thread::sleep(Duration::from_millis(5));
    }
    child
}

#[test]
fn killed_run_resumes_to_the_same_rows() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write_config(dir.path(), "c.toml", &paper_like(80, 8));
    let full = dir.path().join("full");
    run_ok(&[
        "run",
        &cfg,
        "--out",
        full.to_str().unwrap(),
        "--chunk-size",
        "4",
        "--fake-sim",
        "0",
    ]);

    let out = dir.path().join("killed");
    let mut child = start_and_wait(&cfg, &out, 3);
    child.kill().unwrap(); // SIGKILL
    child.wait().unwrap();
    let kept = chunk_files(&out.join(".partial"));
    assert!((3..20).contains(&kept), "{kept} chunks kept");
    assert!(!out.join("samples.parquet").exists());
    assert!(!out.join("summary.json").exists());

    // Without --resume the unfinished run is refused, not overwritten.
    run_err(
        &[
            "run",
            &cfg,
            "--out",
            out.to_str().unwrap(),
            "--fake-sim",
            "0",
        ],
        &["--resume"],
    );

    let o = run_ok(&[
        "run",
        &cfg,
        "--out",
        out.to_str().unwrap(),
        "--resume",
        "--fake-sim",
        "0",
    ]);
    assert!(stdout(&o).contains("rtw-scan summary"));
    assert_eq!(
        rows(&out.join("samples.parquet")),
        rows(&full.join("samples.parquet"))
    );
    assert!(!out.join(".partial").exists());
    assert!(out.join("summary.md").exists());

    // Resuming a finished run recomputes nothing.
    let o = run_ok(&[
        "run",
        &cfg,
        "--out",
        out.to_str().unwrap(),
        "--resume",
        "--fake-sim",
        "0",
    ]);
    assert!(stderr(&o).contains("already complete"), "{}", stderr(&o));
}

#[test]
fn a_finished_scan_run_again_says_it_is_complete_and_computes_nothing() {
    // The same command twice (the README's main command, say): the second
    // finds the first's file, of this config and this version, and has
    // nothing to do; its rows would be the same, row for row.
    let dir = tempfile::tempdir().unwrap();
    let cfg = write_config(dir.path(), "c.toml", &paper_like(12, 3));
    let out = dir.path().join("done");
    fake_run_ok(&cfg, &out, &[]);
    let samples = out.join("samples.parquet");
    let before = std::fs::read(&samples).unwrap();

    // A fake sample of 20 ms: computing the 12 rows again would take 240 ms
    // of samples and rewrite the file with other wall times.
    let t0 = Instant::now();
    let o = run_ok(&["run", &cfg, "--out", s(&out), "--fake-sim", "20"]);
    let err = stderr(&o);
    assert!(err.contains("already complete"), "{err}");
    assert!(
        err.contains("--force"),
        "says how to compute it anew: {err}"
    );
    assert!(
        t0.elapsed() < Duration::from_millis(240),
        "{:?}",
        t0.elapsed()
    );
    assert_eq!(std::fs::read(&samples).unwrap(), before, "rewritten");
    assert!(stdout(&o).contains("rtw-scan summary"), "{}", stdout(&o));

    // --force computes it anew, as it says.
    let o = run_ok(&["run", &cfg, "--out", s(&out), "--fake-sim", "1", "--force"]);
    assert!(!stderr(&o).contains("already complete"), "{}", stderr(&o));
    assert_ne!(
        std::fs::read(&samples).unwrap(),
        before,
        "not computed anew"
    );
}

#[test]
fn ctrl_c_keeps_finished_chunks_and_resumes() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write_config(dir.path(), "c.toml", &paper_like(80, 9));
    let full = dir.path().join("full");
    run_ok(&[
        "run",
        &cfg,
        "--out",
        full.to_str().unwrap(),
        "--fake-sim",
        "0",
    ]);

    let out = dir.path().join("int");
    let mut child = start_and_wait(&cfg, &out, 2);
    let pid = child.id().to_string();
    assert!(
        std::process::Command::new("kill")
            .args(["-INT", &pid])
            .status()
            .unwrap()
            .success()
    );
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(130), "interrupted runs exit 130");
    assert!(chunk_files(&out.join(".partial")) >= 2);
    assert!(!out.join("samples.parquet").exists());

    // The resumed run may use another chunk size flag: the manifest's wins.
    run_ok(&[
        "run",
        &cfg,
        "--out",
        out.to_str().unwrap(),
        "--resume",
        "--chunk-size",
        "64",
        "--fake-sim",
        "0",
    ]);
    assert_eq!(
        rows(&out.join("samples.parquet")),
        rows(&full.join("samples.parquet"))
    );
}

/// Runs a config that must be refused: non-zero exit, the message names
/// `expect`, and nothing is written to the output directory.
fn refused(config_path: &str, out: &Path, expect: &[&str]) {
    let o = run(&[
        "run",
        config_path,
        "--out",
        out.to_str().unwrap(),
        "--fake-sim",
        "0",
    ]);
    let err = stderr(&o);
    assert!(!o.status.success(), "accepted {config_path}");
    assert_eq!(o.status.code(), Some(1));
    for e in expect {
        assert!(err.contains(e), "message lacks {e:?}: {err}");
    }
    assert!(err.starts_with("error: "), "{err}");
    for f in ["samples.parquet", "summary.json", "summary.md", ".partial"] {
        assert!(!out.join(f).exists(), "{f} was written");
    }
}

#[test]
fn bad_configs_are_refused_with_a_message_naming_the_key() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let good = paper_like(5, 1);
    let cases: &[(&str, &str, &[&str])] = &[
        (
            "zeta = { uniform = [0.05, 0.1] }",
            "zeta = 0.05\nrhoo = 2",
            &["params.rhoo", "unknown key `rhoo`"],
        ),
        (
            "alpha = { uniform = [0, 0.4] }",
            "alpha = 0.5",
            &["params.alpha: 0.5 is invalid: must be in [0, 0.49]"],
        ),
        (
            "alpha = { uniform = [0, 0.4] }",
            "alpha = { uniform = [0, 0.5] }",
            &["params.alpha.uniform[1] (hi): 0.5 is invalid"],
        ),
        (
            "rho = { uniform = [1, 5] }",
            "rho = { uniform = [5, 1] }",
            &["params.rho.uniform: lo 5 > hi 1"],
        ),
        (
            "phi = { uniform = [0.05, 0.3] }",
            "phi = nan",
            &["params.phi: NaN is invalid", "(-pi/2, pi/2)"],
        ),
        (
            "samples = 5",
            "samples = -3",
            &["samples: -3 is invalid: must be an integer >= 1"],
        ),
        (
            "t_max = 3.0",
            "t_max = 3.0\ncontact.muu = 1",
            &["simulation.contact.muu", "unknown key `muu`"],
        ),
        (
            "t_max = 3.0",
            "t_max = -1.0",
            &["simulation.t_max: -1 is invalid"],
        ),
        (
            "seed = 1",
            "seed = \"x\"",
            &["seed: invalid type: string \"x\""],
        ),
        (
            "fn = { uniform = [1.5, 5] }",
            "fn = { linspace = [1, 2, 0] }",
            &["params.fn", "n = 0"],
        ),
        ("seed = 1", "seed = 1\n[oops", &["invalid TOML", "line"]),
    ];
    for (i, (from, to, expect)) in cases.iter().enumerate() {
        assert!(good.contains(from), "{from}");
        let cfg = write_config(
            dir.path(),
            &format!("bad{i}.toml"),
            &good.replacen(from, to, 1),
        );
        refused(&cfg, &out, expect);
        assert!(!out.exists(), "case {i} created the output directory");
    }
}

#[test]
fn missing_unreadable_and_unwritable_paths_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let missing = dir.path().join("missing.toml");
    refused(
        missing.to_str().unwrap(),
        &out,
        &["cannot read config", "missing.toml"],
    );
    refused(dir.path().to_str().unwrap(), &out, &["cannot read config"]);
    let binary = dir.path().join("binary.toml");
    std::fs::write(&binary, b"seed = 1\n\xff\xfe\n").unwrap();
    refused(
        binary.to_str().unwrap(),
        &out,
        &["binary.toml is not valid UTF-8"],
    );
    assert!(!out.exists());
    // An output directory under a regular file.
    let file = dir.path().join("plain");
    std::fs::write(&file, "x").unwrap();
    let cfg = write_config(dir.path(), "ok.toml", &paper_like(3, 1));
    refused(
        &cfg,
        &file.join("out"),
        &["cannot create output directory", "plain/out"],
    );
}

#[test]
fn default_output_directory_is_runs_slash_scan_name() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write_config(dir.path(), "tiny-scan.toml", &paper_like(3, 2));
    let o = bin()
        .current_dir(dir.path())
        .args(["run", &cfg, "--fake-sim", "0"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    let d = dir.path().join("runs/tiny-scan");
    assert!(d.join("samples.parquet").exists() && d.join("summary.md").exists());
    // Never into results/, which holds the committed results.
    assert!(!dir.path().join("results").exists());
}

#[test]
fn samples_file_has_the_documented_columns_and_metadata() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write_config(
        dir.path(),
        "c.toml",
        &format!("name = \"meta\"\n{}", paper_like(20, 4)),
    );
    let out = dir.path().join("o");
    run_ok(&[
        "run",
        &cfg,
        "--out",
        out.to_str().unwrap(),
        "--fake-sim",
        "0",
    ]);
    let path = out.join("samples.parquet");
    let names = column_names(&path);
    for c in [
        "sample_id",
        "length",
        "rho",
        "alpha",
        "fn",
        "zeta",
        "phi",
        "m",
        "l_c",
        "inertia",
        "r",
        "k",
        "c",
        "outcome",
        "failure",
        "message",
        "t_end",
        "nlsp",
        "slsp",
        "dlsp",
        "tlsp",
        "touchdowns",
        "f_w",
        "f_w_newfoot",
        "speed",
        "mu_required",
        "slide_time",
        "energy_initial",
        "energy_last",
        "energy_gravity_released",
        "energy_impact_loss",
        "energy_damping_loss",
        "energy_balance_error",
        "period",
        "steps",
        "rejected",
        "rhs_evals",
        "events",
        "wall_time_s",
    ] {
        assert!(names.iter().any(|n| n == c), "missing column {c}");
    }
    let b = batches(&path);
    let schema = b[0].schema();
    assert_eq!(
        schema.field_with_name("outcome").unwrap().data_type(),
        &arrow_schema::DataType::Dictionary(
            Box::new(arrow_schema::DataType::Int32),
            Box::new(arrow_schema::DataType::Utf8)
        )
    );
    assert_eq!(
        schema.field_with_name("alpha").unwrap().data_type(),
        &arrow_schema::DataType::Float64
    );
    // The data dictionary travels in the file: every column has a unit and a
    // description in its Arrow field metadata.
    for f in schema.fields() {
        for key in ["unit", "description"] {
            assert!(
                f.metadata().get(key).is_some_and(|v| !v.is_empty()),
                "column {} has no {key} in the written file",
                f.name()
            );
        }
    }
    assert_eq!(
        schema.field_with_name("fn").unwrap().metadata()["unit"],
        "Hz"
    );
    assert_eq!(
        schema.field_with_name("phi").unwrap().metadata()["unit"],
        "rad"
    );
    let f = std::fs::File::open(&path).unwrap();
    let reader = parquet::file::reader::SerializedFileReader::new(f).unwrap();
    use parquet::file::reader::FileReader;
    let meta = reader.metadata();
    let kv: std::collections::HashMap<_, _> = meta
        .file_metadata()
        .key_value_metadata()
        .unwrap()
        .iter()
        .map(|kv| (kv.key.clone(), kv.value.clone().unwrap_or_default()))
        .collect();
    assert!(kv["rtw.config"].contains("samples = 20") && kv["rtw.config"].contains("[simulation]"));
    assert_eq!(kv["rtw.seed"], "4");
    assert_eq!(kv["rtw.version"], rtw_engine::VERSION);
    assert!(kv["rtw.variant"].contains("rest_length_ratio=0"));
    assert!(kv.contains_key("rtw.wall_time_s"));
    let rg = meta.row_group(0);
    assert_eq!(
        rg.column(1).compression(),
        parquet::basic::Compression::ZSTD(Default::default())
    );
}

#[test]
fn summary_and_cluster_commands_redo_the_steps_from_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write_config(dir.path(), "c.toml", &paper_like(120, 3));
    let out = dir.path().join("o");
    // μ = ∞ (the literal variant's) to check how JSON spells infinity.
    let printed = stdout(&run_ok(&[
        "run",
        &cfg,
        "--set",
        "contact.mu=inf",
        "--out",
        out.to_str().unwrap(),
        "--fake-sim",
        "0",
    ]));
    let samples = out.join("samples.parquet");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(json["samples"], 120);
    let total: u64 = json["outcomes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|o| o["count"].as_u64().unwrap())
        .sum();
    assert_eq!(total, 120);
    assert_eq!(json["paper_scan"], true);
    assert_eq!(json["stable"]["paper_percent"], 73.7);
    assert!(
        json["stable"]["ci95"][0].as_f64().unwrap() < json["stable"]["percent"].as_f64().unwrap()
    );
    assert_eq!(json["clusters"]["k"], 2);
    assert_eq!(json["variant"]["normalization"], "supplementary");
    assert!(
        json["variant"]["mu"].is_null(),
        "JSON has no infinity: null"
    );
    let md = std::fs::read_to_string(out.join("summary.md")).unwrap();
    assert_eq!(md, printed);
    assert!(md.contains("| skip |") && md.contains("paper %") && md.contains("stiffness collapse"));
    assert!(md.contains("energy barrier") && md.contains("silhouette"));

    // `summary` rebuilds the same files (wall time comes from the file).
    std::fs::remove_file(out.join("summary.json")).unwrap();
    let again = stdout(&run_ok(&["summary", samples.to_str().unwrap()]));
    assert_eq!(again, printed);
    assert!(out.join("summary.json").exists());

    let o = run_ok(&["cluster", samples.to_str().unwrap(), "--k", "3", "--json"]);
    let c: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(c["k"], 3);
    assert_eq!(c["clusters"].as_array().unwrap().len(), 3);
    let o = run_ok(&["cluster", samples.to_str().unwrap()]);
    assert!(stdout(&o).contains("| cluster | name |"));

    // Not a samples file.
    run_err(&["summary", cfg.as_str()], &["not a readable Parquet file"]);
}

#[test]
fn cluster_assignments_name_every_failure_once_and_match_the_summary() {
    use arrow_array::{Float64Array, Int64Array, StringArray, cast::AsArray};
    use std::collections::BTreeMap;
    let dir = tempfile::tempdir().unwrap();
    let cfg = write_config(dir.path(), "c.toml", &paper_like(150, 4));
    let out = dir.path().join("o");
    run_ok(&[
        "run",
        &cfg,
        "--out",
        out.to_str().unwrap(),
        "--fake-sim",
        "0",
    ]);
    let samples = out.join("samples.parquet");
    let assign = dir.path().join("assign.parquet");
    let o = run_ok(&[
        "cluster",
        samples.to_str().unwrap(),
        "--json",
        "--assignments",
        assign.to_str().unwrap(),
    ]);
    let printed: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();

    // The failed samples of the scan itself: sample_id → (outcome, alpha, fn, phi) as printed.
    let field = |r: &[String], name: &str| {
        r.iter()
            .find_map(|c| c.strip_prefix(&format!("{name}=")).map(str::to_string))
            .unwrap()
    };
    let failed: BTreeMap<i64, [String; 4]> = rows(&samples)
        .iter()
        .filter(|r| ["collapse", "stall"].contains(&field(r, "outcome").as_str()))
        .map(|r| {
            (
                field(r, "sample_id").parse().unwrap(),
                ["outcome", "alpha", "fn", "phi"].map(|n| field(r, n)),
            )
        })
        .collect();
    for kind in ["collapse", "stall"] {
        assert!(
            failed.values().filter(|f| f[0] == kind).count() >= 5,
            "the fake scan has {kind} failures"
        );
    }

    let mut seen: BTreeMap<i64, [String; 4]> = BTreeMap::new();
    let mut sizes: BTreeMap<i64, u64> = BTreeMap::new();
    let mut kinds: BTreeMap<(i64, String), u64> = BTreeMap::new();
    for b in batches(&assign) {
        let col = |n: &str| {
            b.column_by_name(n)
                .unwrap_or_else(|| panic!("no column {n}"))
        };
        let id = col("sample_id")
            .as_any()
            .downcast_ref::<Int64Array>()
            .unwrap();
        let cluster = col("cluster")
            .as_any()
            .downcast_ref::<Int64Array>()
            .unwrap();
        let outcome = col("outcome")
            .as_any()
            .downcast_ref::<StringArray>()
            .unwrap();
        let name = col("cluster_name").as_string::<i32>();
        let f = |n: &str| {
            col(n)
                .as_any()
                .downcast_ref::<Float64Array>()
                .unwrap()
                .clone()
        };
        let (alpha, f_n, phi) = (f("alpha"), f("fn"), f("phi"));
        for i in 0..b.num_rows() {
            let c = cluster.value(i);
            let prev = seen.insert(
                id.value(i),
                [
                    outcome.value(i).to_string(),
                    alpha.value(i).to_string(),
                    f_n.value(i).to_string(),
                    phi.value(i).to_string(),
                ],
            );
            assert!(prev.is_none(), "sample {} listed twice", id.value(i));
            *sizes.entry(c).or_default() += 1;
            *kinds.entry((c, outcome.value(i).to_string())).or_default() += 1;
            let row = &printed["clusters"][(c - 1) as usize];
            assert_eq!(row["name"], name.value(i), "cluster {c}: name");
        }
    }
    // Every failed sample exactly once, with its own outcome and coordinates.
    assert_eq!(seen, failed);
    // Cluster sizes and the kind cross-table are those of `cluster --json`.
    let clusters = printed["clusters"].as_array().unwrap();
    assert_eq!(sizes.len(), clusters.len());
    for (j, c) in clusters.iter().enumerate() {
        let j = j as i64 + 1;
        assert_eq!(sizes[&j], c["size"].as_u64().unwrap(), "cluster {j}: size");
        for kind in ["collapse", "stall"] {
            let n = kinds.get(&(j, kind.to_string())).copied().unwrap_or(0);
            assert_eq!(n, c[kind].as_u64().unwrap(), "cluster {j}: {kind}");
        }
    }
    // ... and those of the run's summary, which the file's metadata repeats.
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["clusters"], printed);
    let f = std::fs::File::open(&assign).unwrap();
    let meta = parquet::file::reader::FileReader::metadata(
        &parquet::file::serialized_reader::SerializedFileReader::new(f).unwrap(),
    )
    .file_metadata()
    .key_value_metadata()
    .unwrap()
    .iter()
    .find(|kv| kv.key == "rtw.clusters")
    .and_then(|kv| kv.value.clone())
    .unwrap();
    assert_eq!(
        serde_json::from_str::<serde_json::Value>(&meta).unwrap(),
        printed
    );
    // The file records the scan it clusters, by which a reader tells it from another scan's.
    assert_eq!(
        file_metadata(&assign, "rtw.scan_content_hash"),
        file_metadata(&samples, "rtw.content_hash")
    );

    // Fewer failures than clusters: a clear error, and no file.
    let none = dir.path().join("none.parquet");
    run_err(
        &[
            "cluster",
            samples.to_str().unwrap(),
            "--k",
            "1000",
            "--assignments",
            none.to_str().unwrap(),
        ],
        &["--assignments", "fewer than k = 1000"],
    );
    assert!(!none.exists());
}

#[test]
fn simulate_prints_flat_json_and_validates_input() {
    let base = [
        "simulate", "--length", "0.8", "--rho", "2.5", "--alpha", "0.125", "--fn", "3.269",
        "--zeta", "0.0514",
    ];
    let o = run_ok(&[&base[..], &["--phi", "0.15", "--json", "--fake-sim"]].concat());
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(v["outcome"], "walk");
    for key in [
        "nlsp",
        "slsp",
        "dlsp",
        "tlsp",
        "f_w",
        "f_w_newfoot",
        "mu_required",
        "energy_balance_error",
        "steps",
        "m",
        "k",
        "c",
        "r",
        "inertia",
        "l_c",
    ] {
        assert!(v.get(key).is_some(), "JSON lacks {key}");
    }
    assert!((v["k"].as_f64().unwrap() - 500.0067).abs() < 1e-3);
    // Text form.
    let o = run_ok(&[&base[..], &["--phi", "-0.05", "--fake-sim"]].concat());
    assert!(stdout(&o).contains("[outcome]") && stdout(&o).contains("stall"));
    // Bad parameter, bad option, bad --set.
    let with = |extra: &[&'static str]| [&base[..], extra, &["--fake-sim"]].concat();
    run_err(&with(&["--phi", "1.6"]), &["--phi: 1.6 is invalid"]);
    run_err(
        &with(&["--phi", "0.1", "--set", "contact.mu=2"]),
        &["simulation.contact.mu: 2 is invalid"],
    );
    run_err(
        &with(&["--phi", "0.1", "--set", "contact.nope=2"]),
        &["simulation.contact.nope: unknown key"],
    );
    run_err(
        &with(&["--phi", "0.1", "--set", "method=euler"]),
        &["simulation.method", "dop853"],
    );
    // --config takes its [simulation] table.
    let dir = tempfile::tempdir().unwrap();
    let cfg = write_config(dir.path(), "s.toml", "[simulation]\nt_max = 2.0\n");
    let o = run_ok(
        &[
            &base[..],
            &["--phi", "0.15", "--json", "--fake-sim", "--config", &cfg],
        ]
        .concat(),
    );
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(v["t_end"], 2.0);
}

#[test]
fn help_documents_every_subcommand_and_hides_test_flags() {
    let h = stdout(&run_ok(&["--help"]));
    for s in ["run", "simulate", "cluster", "summary"] {
        assert!(h.contains(s), "{h}");
    }
    let h = stdout(&run_ok(&["run", "--help"]));
    for s in ["--out", "--threads", "--resume", "runs/<scan name>"] {
        assert!(h.contains(s), "{h}");
    }
    assert!(!h.contains("--fake-sim") && !h.contains("--chunk-size"));
    let h = stdout(&run_ok(&["simulate", "--help"]));
    for s in ["--fn", "--set", "--json", "--trace", "--config"] {
        assert!(h.contains(s), "{h}");
    }
}

#[test]
fn variant_files_layer_over_a_config_and_are_recorded() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write_config(dir.path(), "box.toml", &paper_like(20, 3));
    let variant = write_config(
        dir.path(),
        "pre.toml",
        "name = \"pre\"\ndescription = \"prestress\"\n[simulation]\nstrings.rest_length_ratio = 0.85\n",
    );
    let out = dir.path().join("o");
    run_ok(&[
        "run",
        &cfg,
        "--variant",
        &variant,
        "--set",
        "contact.mu=0.8",
        "--out",
        out.to_str().unwrap(),
        "--fake-sim",
        "0",
    ]);
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["name"], "box+pre");
    assert_eq!(summary["variant"]["rest_length_ratio"], 0.85);
    assert_eq!(summary["variant"]["mu"], 0.8);
    // The base config's own keys stay.
    assert_eq!(summary["variant"]["t_max"], 3.0);
    // A bad variant value is refused, naming the file and the key.
    let bad = write_config(
        dir.path(),
        "bad.toml",
        "name = \"bad\"\n[simulation]\ncontact.mu = -1\n",
    );
    run_err(
        &["run", &cfg, "--variant", &bad, "--fake-sim", "0"],
        &["simulation.contact.mu: -1 is invalid"],
    );
}

#[test]
fn every_committed_variant_and_sensitivity_file_is_valid() {
    let tmp = tempfile::tempdir().unwrap();
    let mut n = 0;
    for sub in ["variants", "sensitivity"] {
        for entry in std::fs::read_dir(workspace().join("configs").join(sub)).unwrap() {
            let path = entry.unwrap().path();
            let name = path.file_stem().unwrap().to_str().unwrap().to_string();
            let text = std::fs::read_to_string(&path).unwrap();
            // The file names itself, so results say which variant made them.
            assert!(
                text.contains(&format!("name = \"{name}\"")),
                "{}: name must match the file name",
                path.display()
            );
            // It layers over a scan config (name, description and valid
            // [simulation] keys only), and `simulate --config` reads it too.
            let out = tmp.path().join(&name);
            let smoke = config("smoke");
            let file = path.to_str().unwrap();
            run_ok(&[
                "run",
                smoke.to_str().unwrap(),
                "--variant",
                file,
                "--out",
                out.to_str().unwrap(),
                "--fake-sim",
                "0",
            ]);
            let summary = std::fs::read_to_string(out.join("summary.json")).unwrap();
            assert!(summary.contains(&format!("\"smoke+{name}\"")), "{summary}");
            run_ok(&[
                "simulate",
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
                "--phi",
                "0.15",
                "--config",
                file,
                "--fake-sim",
            ]);
            n += 1;
        }
    }
    assert!(n >= 20, "only {n} files");
}

#[test]
fn simulate_exits_1_for_a_run_that_did_not_finish() {
    // `--help` promises 1 for a `diverged` run: a numerical failure (the
    // fake simulator's ρ < 1.1 runs out of its work budget) as well as a
    // panic (ρ > 4.75). The row is still printed.
    let base = [
        "simulate",
        "--length",
        "0.8",
        "--zeta",
        "0.05",
        "--phi",
        "0.2",
        "--fake-sim",
    ];
    let design = ["--alpha", "0.2", "--fn", "3.0"];
    for rho in ["1.05", "4.9"] {
        for json in [&["--json"][..], &[]] {
            let o = run(&[&base[..], &design, &["--rho", rho], json].concat());
            assert_eq!(o.status.code(), Some(1), "rho {rho}: {}", stderr(&o));
            assert!(stdout(&o).contains("diverged"), "{}", stdout(&o));
            assert!(
                stderr(&o).contains("the simulation did not finish"),
                "{}",
                stderr(&o)
            );
        }
    }
    // A physical failure finishes: exit 0 (whatever the label).
    let o = run(&[
        &base[..],
        &["--rho", "2.5", "--alpha", "0.1", "--fn", "2.0"],
    ]
    .concat());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(stdout(&o).contains("collapse"), "{}", stdout(&o));
}

#[test]
fn refusals_name_the_field_and_range_with_numbers_as_written() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o");
    let out = out.to_str().unwrap();
    let smoke = config("smoke.toml");
    let smoke = smoke.to_str().unwrap();
    // Counts that must be positive: clap's own "number would be zero for
    // non-zero type" named neither the rule nor the range.
    for (args, needle) in [
        (
            vec!["run", smoke, "--out", out, "--threads", "0"],
            "--threads: 0 is invalid: must be an integer in [1, ",
        ),
        (
            vec!["run", smoke, "--out", out, "--threads", "two"],
            "--threads: two is invalid: must be an integer in [1, ",
        ),
        (
            vec!["cluster", "x.parquet", "--k", "0"],
            "'--k <K>': 0 is invalid: must be an integer >= 1",
        ),
        (
            vec!["summary", "x.parquet", "--k", "0"],
            "'--k <K>': 0 is invalid: must be an integer >= 1",
        ),
    ] {
        let o = run(&args);
        let err = stderr(&o);
        assert!(!o.status.success(), "{args:?} accepted");
        assert!(err.contains(needle), "{args:?}: no {needle:?} in:\n{err}");
        assert!(!err.contains("non-zero type"), "{err}");
    }
    // Fig. 7(a) but the length, which some cases set.
    let base: Vec<&str> = "simulate --rho 2.5 --alpha 0.125 --fn 3.269 --zeta 0.0514 --fake-sim"
        .split(' ')
        .collect();
    let with = |extra: &[&'static str]| {
        let length: &[&str] = if extra.contains(&"--length") {
            &[]
        } else {
            &["--length", "0.8"]
        };
        [&base[..], length, extra].concat()
    };
    // Numbers are shown as a person writes them, never as 300 digits.
    for (extra, needles) in [
        (
            &["--phi", "0.1", "--set", "t_max=1e400"][..],
            &["t_max", "1e400", "finite and > 0"][..],
        ),
        (
            &["--phi", "0.1", "--set", "t_max=-1e400"],
            &["t_max", "-1e400", "finite and > 0"],
        ),
        (
            &["--phi", "0.1", "--set", "rtol=1e-400"],
            &["rtol", "1e-400", "in (0, 0.1]"],
        ),
        (
            &["--phi", "0.1", "--set", "t_max=-1e300"],
            &["simulation.t_max: -1e300 is invalid: must be finite and > 0"],
        ),
        (&["--phi", "0.1", "--set", "rtol=1e-300"], &[]),
        (&["--phi", "1e300"], &["--phi: 1e300 is invalid"]),
        (
            &["--phi", "0.1", "--set", "max_steps=1e400"],
            &["max_steps", "1e400", ">= 1"],
        ),
        (
            &["--phi", "0.1", "--set", "t_max=fast"],
            &["simulation.t_max", "\"fast\"", "finite and > 0"],
        ),
    ] {
        let o = run(&with(extra));
        let err = stderr(&o);
        if needles.is_empty() {
            assert!(o.status.success(), "{extra:?}: {err}");
            continue;
        }
        assert_eq!(o.status.code(), Some(1), "{extra:?}: {err}");
        for n in needles {
            assert!(err.contains(n), "{extra:?}: no {n:?} in:\n{err}");
        }
        assert!(!err.contains("00000000"), "{extra:?}: {err}");
    }
    let o = run(&with(&["--phi", "1e-300", "--length", "1e-300"]));
    let err = stderr(&o);
    assert!(err.contains("--length: 1e-300 is invalid"), "{err}");
    // A config file: the same rule.
    let cfg = write_config(
        dir.path(),
        "c.toml",
        "seed = 1\nsamples = 2\n[params]\nlength = 0.8\nrho = 2.5\nalpha = 0.1\nfn = { uniform = [2, 1e300] }\nzeta = 0.05\nphi = 0.1\n",
    );
    refused(
        &cfg,
        &dir.path().join("o2"),
        &["params.fn.uniform[1] (hi): 1e300 is invalid"],
    );
}

/// A finished fake scan of `paper_like(samples, seed)` in `dir/scan`; returns that directory.
fn fake_scan(dir: &Path, samples: u64, seed: u64) -> std::path::PathBuf {
    let cfg = write_config(dir, "c.toml", &paper_like(samples, seed));
    let out = dir.join("scan");
    let args = [
        "run",
        &cfg,
        "--out",
        out.to_str().unwrap(),
        "--fake-sim",
        "0",
        "--quiet",
    ];
    run_ok(&args);
    out
}

/// `src` rewritten as another tool would: strings as large strings, the
/// label as a dictionary of `UInt32` keys over large strings (polars),
/// compressed with `codec` (pyarrow's default is snappy), the key-value
/// metadata kept (pyarrow keeps it).
fn rewrite_as_another_tool(src: &Path, dest: &Path, codec: parquet::basic::Compression) {
    use arrow_schema::{DataType, Field, Schema};
    use parquet::arrow::ArrowWriter;
    use parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder;
    use parquet::file::properties::WriterProperties;
    use std::sync::Arc;
    let b = ParquetRecordBatchReaderBuilder::try_new(std::fs::File::open(src).unwrap()).unwrap();
    let kv = b.metadata().file_metadata().key_value_metadata().cloned();
    let other = |t: &DataType| match t {
        DataType::Utf8 => DataType::LargeUtf8,
        DataType::Dictionary(_, _) => {
            DataType::Dictionary(Box::new(DataType::UInt32), Box::new(DataType::LargeUtf8))
        }
        t => t.clone(),
    };
    let fields: Vec<Field> = b
        .schema()
        .fields()
        .iter()
        .map(|f| f.as_ref().clone().with_data_type(other(f.data_type())))
        .collect();
    let schema = Arc::new(Schema::new(fields));
    let props = WriterProperties::builder()
        .set_compression(codec)
        .set_key_value_metadata(kv)
        .build();
    let mut w = ArrowWriter::try_new(
        std::fs::File::create(dest).unwrap(),
        schema.clone(),
        Some(props),
    )
    .unwrap();
    for batch in b.build().unwrap() {
        let batch = batch.unwrap();
        let cols = batch
            .columns()
            .iter()
            .zip(schema.fields())
            .map(|(c, f)| as_another_tool(c, f.data_type()))
            .collect();
        w.write(&arrow_array::RecordBatch::try_new(schema.clone(), cols).unwrap())
            .unwrap();
    }
    w.close().unwrap();
}

/// Column `c` as `rewrite_as_another_tool` types it: strings as large
/// strings, a dictionary as `UInt32` keys over large strings.
fn as_another_tool(
    c: &arrow_array::ArrayRef,
    to: &arrow_schema::DataType,
) -> arrow_array::ArrayRef {
    use arrow_array::cast::AsArray;
    use arrow_array::{DictionaryArray, LargeStringArray, UInt32Array};
    use std::sync::Arc;
    match to {
        arrow_schema::DataType::LargeUtf8 => {
            Arc::new(c.as_string::<i32>().iter().collect::<LargeStringArray>())
        }
        arrow_schema::DataType::Dictionary(_, _) => {
            let d = c.as_any_dictionary();
            let keys = d.normalized_keys();
            let keys: UInt32Array = (0..c.len())
                .map(|i| c.is_valid(i).then(|| keys[i] as u32))
                .collect();
            let values = d
                .values()
                .as_string::<i32>()
                .iter()
                .collect::<LargeStringArray>();
            Arc::new(DictionaryArray::try_new(keys, Arc::new(values)).unwrap())
        }
        _ => c.clone(),
    }
}

#[test]
fn parquet_files_rewritten_by_other_tools_are_read() {
    use parquet::basic::{Compression, GzipLevel};
    let dir = tempfile::tempdir().unwrap();
    let out = fake_scan(dir.path(), 60, 5);
    let summary = |f: &Path| {
        let o = run_ok(&["summary", f.to_str().unwrap(), "--json"]);
        let mut v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
        v.as_object_mut().unwrap().remove("file");
        v
    };
    let want = summary(&out.join("samples.parquet"));
    let clusters = |f: &Path| stdout(&run_ok(&["cluster", f.to_str().unwrap(), "--json"]));
    let want_clusters = clusters(&out.join("samples.parquet"));
    for (name, codec) in [
        ("snappy", Compression::SNAPPY),
        ("gzip", Compression::GZIP(GzipLevel::default())),
        ("lz4", Compression::LZ4_RAW),
        ("lz4-hadoop", Compression::LZ4),
        ("none", Compression::UNCOMPRESSED),
    ] {
        let other = dir.path().join(name);
        std::fs::create_dir(&other).unwrap();
        let f = other.join("samples.parquet");
        rewrite_as_another_tool(&out.join("samples.parquet"), &f, codec);
        assert_eq!(summary(&f), want, "{name}");
        assert_eq!(clusters(&f), want_clusters, "{name}");
    }
}

/// A float flag beyond what a 64-bit float holds is refused with the text
/// that was typed, as `--set` does, not with the value it would have been
/// read as (`1e400` as inf, `1e-400` as 0): every float flag of every
/// subcommand.
#[test]
fn a_float_flag_beyond_a_float_is_refused_with_what_was_typed() {
    let design = [
        "--length", "0.8", "--rho", "2.5", "--alpha", "0.125", "--fn", "3.269", "--zeta", "0.0514",
    ];
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            [
                &["profile"],
                &design[..],
                &["--from", "0.1", "--to", "0.2", "--tol", "1e400"],
            ]
            .concat(),
            "1e400",
        ),
        (
            [
                &["profile"],
                &design[..],
                &["--from", "0.1", "--to", "0.2", "--grid", "1e-400"],
            ]
            .concat(),
            "1e-400",
        ),
        (
            [
                &["profile"],
                &design[..],
                &["--from", "-1e400", "--to", "0.2"],
            ]
            .concat(),
            "-1e400",
        ),
        (
            [&["simulate"], &design[..], &["--phi", "1e-400"]].concat(),
            "1e-400",
        ),
        (
            vec![
                "simulate", "--length", "1e400", "--rho", "2.5", "--alpha", "0.125", "--fn",
                "3.269", "--zeta", "0.0514", "--phi", "0.15",
            ],
            "1e400",
        ),
        (vec!["bifurcation", "--rho", "1e400"], "1e400"),
        (vec!["bifurcation", "--to", "1e400"], "1e400"),
        (vec!["continuation", "--ds", "1e-400"], "1e-400"),
        (
            vec!["continuation", "--curve", "fn", "--curve-from", "1e400"],
            "1e400",
        ),
        (
            vec![
                "basin",
                "--x",
                "theta:0:1:2",
                "--y",
                "omega:0:1:2",
                "--out",
                "b.parquet",
                "--tol",
                "1e400",
            ],
            "1e400",
        ),
    ];
    for (args, typed) in cases {
        let o = run(&args);
        let err = stderr(&o);
        assert!(!o.status.success(), "{args:?} passed:\n{err}");
        assert!(
            err.contains(&format!("{typed} is invalid")),
            "{args:?}: not the text typed, {typed}:\n{err}"
        );
        assert!(err.contains("64-bit float"), "{args:?}: no reason:\n{err}");
    }
}

/// Progress in lines (stderr not a terminal) starts with a line at once, not
/// when the first sample finishes: a run whose samples take 20 s each says
/// within seconds that it is under way and how much there is to do.
#[test]
fn progress_lines_start_before_the_first_sample_finishes() {
    use std::io::BufRead;
    use std::process::Stdio;
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("slow");
    let mut child = bin()
        .args([
            "run",
            s(&config("smoke")),
            "--out",
            s(&out),
            "--threads",
            "1",
        ])
        .args(["--fake-sim", "20000"])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let err = child.stderr.take().unwrap();
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let mut first = String::new();
        let _ = std::io::BufReader::new(err).read_line(&mut first);
        let _ = tx.send((first, Instant::now()));
    });
    let t0 = Instant::now();
    let got = rx.recv_timeout(Duration::from_secs(15));
    child.kill().ok();
    child.wait().ok();
    let (line, at) = got.expect("no progress line within 15 s");
    let took = at.duration_since(t0);
    eprintln!("first progress line after {took:?}: {line}");
    assert!(line.contains("0/6"), "{line}");
    // 2 s promised; 5 s allowed on a loaded machine (a sample takes 20 s).
    assert!(took < Duration::from_secs(5), "{took:?}");
}
