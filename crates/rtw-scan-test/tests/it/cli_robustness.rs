//! `rtw-scan simulate` over a step down and with the robustness measures
//! (`robustness.step_down`, `robustness.gsn`; docs/robustness.md), with the
//! real simulator.

use crate::common::*;

const FIG7A: [&str; 13] = [
    "simulate", "--length", "0.8", "--rho", "2.5", "--alpha", "0.125", "--fn", "3.269", "--zeta",
    "0.0514", "--phi", "0.15",
];

/// A star too soft to stand: it collapses as it is set down.
const SOFT: [&str; 13] = [
    "simulate", "--length", "0.8", "--rho", "2.5", "--alpha", "0.125", "--fn", "0.5", "--zeta",
    "0.0514", "--phi", "0.02",
];

fn json(extra: &[&str]) -> serde_json::Value {
    let o = run_ok(&[&FIG7A[..], &["--json"], extra].concat());
    serde_json::from_str(&stdout(&o)).unwrap()
}

#[test]
fn step_down_max_is_in_the_json_row_only_when_asked_for() {
    let flat = json(&[]);
    assert!(flat.get("step_down_max").is_none(), "{flat}");
    let v = json(&["--set", "robustness.step_down=true"]);
    let h = v["step_down_max"].as_f64().unwrap();
    assert!(h > 0.0, "{v}");
    // Asking for it changes nothing else in the row.
    for (key, value) in flat.as_object().unwrap() {
        if key != "wall_time_s" {
            assert_eq!(&v[key], value, "{key}");
        }
    }
}

#[test]
fn step_down_h50_is_in_the_json_row_only_when_asked_for() {
    // A positive height, alone in the row (not step_down_max); asking for
    // it changes nothing else in the row; a non-boolean is refused naming
    // the key.
    let flat = json(&[]);
    assert!(flat.get("step_down_h50").is_none(), "{flat}");
    let v = json(&["--set", "robustness.step_down_h50=true"]);
    let h = v["step_down_h50"].as_f64().unwrap();
    assert!(h > 0.0, "{v}");
    assert!(v.get("step_down_max").is_none(), "{v}");
    for (key, value) in flat.as_object().unwrap() {
        if key != "wall_time_s" {
            assert_eq!(&v[key], value, "{key}");
        }
    }
    run_err(
        &[&FIG7A[..], &["--set", "robustness.step_down_h50=2"]].concat(),
        &["step_down_h50"],
    );
}

/// A point of the survival curve: its five shares only when a height is
/// asked for, each a multiple of 1/20 adding up to 1; nothing else in the
/// row changes; a step the walk cannot miss (twice its largest) is not
/// survived everywhere, one it walks over at its best phase (a tenth of
/// it) is; a negative or non-finite height is refused naming the key and
/// its range.
#[test]
fn step_down_at_gives_the_shares_of_the_phases_by_outcome() {
    const KEYS: [&str; 5] = [
        "step_down_survival",
        "step_down_collapse",
        "step_down_stall",
        "step_down_other_gait",
        "step_down_diverged",
    ];
    let flat = json(&[]);
    for k in KEYS {
        assert!(flat.get(k).is_none(), "{flat}");
    }
    let top = json(&["--set", "robustness.step_down=true"])["step_down_max"]
        .as_f64()
        .unwrap();
    let at = |h: f64| json(&["--set", &format!("robustness.step_down_at={h}")]);
    let (low, high) = (at(0.1 * top), at(2.0 * top));
    for v in [&low, &high] {
        let shares: Vec<f64> = KEYS.iter().map(|k| v[k].as_f64().unwrap()).collect();
        for s in &shares {
            assert_eq!((s * 20.0).round(), s * 20.0, "{v}");
        }
        assert!((shares.iter().sum::<f64>() - 1.0).abs() < 1e-12, "{v}");
        for (key, value) in flat.as_object().unwrap() {
            if key != "wall_time_s" {
                assert_eq!(&v[key], value, "{key}");
            }
        }
    }
    assert_eq!(low["step_down_survival"].as_f64(), Some(1.0), "{low}");
    assert!(high["step_down_survival"].as_f64().unwrap() < 1.0, "{high}");
    for bad in ["-0.1", "nan", "inf"] {
        run_err(
            &[
                &FIG7A[..],
                &["--set", &format!("robustness.step_down_at={bad}")],
            ]
            .concat(),
            &["robustness.step_down_at", "in [0, 1000]"],
        );
    }
}

#[test]
fn terrain_options_run_over_a_step_and_are_validated() {
    let flat = json(&[]);
    let zero = json(&[
        "--set",
        "terrain.step_height=0",
        "--set",
        "terrain.step_at=3",
    ]);
    assert_eq!(zero["t_end"], flat["t_end"]);
    let step = json(&[
        "--set",
        "terrain.step_height=0.05",
        "--set",
        "terrain.step_at=3",
    ]);
    assert_ne!(step["t_end"], flat["t_end"]);
    run_err(
        &[&FIG7A[..], &["--set", "terrain.step_height=-0.1"]].concat(),
        &[
            "simulation.terrain.step_height: -0.1 is invalid",
            "in [0, 1000]",
        ],
    );
    run_err(
        &[&FIG7A[..], &["--set", "terrain.step_at=0"]].concat(),
        &["simulation.terrain.step_at: 0 is invalid", "(0, 1e6]"],
    );
}

#[test]
fn a_scan_has_the_step_down_column_only_when_asked_for_and_the_same_rows_besides() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write(dir.path(), "s.toml", &paper_like(12, 7));
    let (plain, step) = (dir.path().join("plain"), dir.path().join("step"));
    // Small chunks: the column must survive the chunks' concatenation.
    run_ok(&[
        "run",
        &cfg,
        "--out",
        s(&plain),
        "--quiet",
        "--chunk-size",
        "5",
    ]);
    run_ok(&[
        "run",
        &cfg,
        "--out",
        s(&step),
        "--quiet",
        "--chunk-size",
        "5",
        "--set",
        "robustness.step_down=true",
    ]);
    let (plain, step) = (plain.join("samples.parquet"), step.join("samples.parquet"));
    let names = column_names(&plain);
    assert!(!names.iter().any(|n| n == "step_down_max"));
    let mut with = names.clone();
    with.push("step_down_max".into());
    assert_eq!(column_names(&step), with);
    let (a, b) = (rows(&plain), rows(&step));
    assert_eq!(a.len(), 12);
    let mut stable = 0;
    for (a, b) in a.iter().zip(&b) {
        assert_eq!(a[..], b[..a.len()]);
        let label = &a[names.iter().position(|n| n == "outcome").unwrap()];
        let value = &b[a.len()];
        let is_stable = ["outcome=skip", "outcome=walk", "outcome=crawl"].contains(&label.as_str());
        stable += is_stable as usize;
        assert_eq!(value == "step_down_max=null", !is_stable, "{label} {value}");
    }
    assert!(stable > 0);
}

#[test]
fn gsn_is_in_the_json_row_only_when_asked_for_and_changes_nothing_else() {
    let flat = json(&[]);
    assert!(flat.get("gsn").is_none(), "{flat}");
    let v = json(&["--set", "robustness.gsn=true"]);
    // The Fig. 7(a) walk's norm (crates/rtw-model/src/cycles/robustness/gsn.rs checks
    // it against the full simulation's response to a small step).
    let g = v["gsn"].as_f64().unwrap();
    assert!((g - 4.6349).abs() < 1e-3, "{v}");
    assert!(v.get("step_down_max").is_none(), "{v}");
    for (key, value) in flat.as_object().unwrap() {
        if key != "wall_time_s" {
            assert_eq!(&v[key], value, "{key}");
        }
    }
    // Both measures: the same gsn.
    let both = json(&[
        "--set",
        "robustness.gsn=true",
        "--set",
        "robustness.step_down=true",
    ]);
    assert!(both["step_down_max"].as_f64().unwrap() > 0.0, "{both}");
    assert_eq!(both["gsn"], v["gsn"]);
}

#[test]
fn a_scan_has_the_gsn_column_only_when_asked_for_and_the_same_rows_besides() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write(dir.path(), "s.toml", &paper_like(12, 7));
    let (plain, with) = (dir.path().join("plain"), dir.path().join("gsn"));
    let args = |out| ["run", &cfg, "--out", s(out), "--quiet", "--chunk-size", "5"];
    run_ok(&args(&plain));
    run_ok(&[&args(&with)[..], &["--set", "robustness.gsn=true"]].concat());
    let (plain, with) = (plain.join("samples.parquet"), with.join("samples.parquet"));
    let names = column_names(&plain);
    let mut expected = names.clone();
    expected.push("gsn".into());
    assert_eq!(column_names(&with), expected);
    let (a, b) = (rows(&plain), rows(&with));
    let mut computed = 0;
    for (a, b) in a.iter().zip(&b) {
        assert_eq!(a[..], b[..a.len()]);
        let label = &a[names.iter().position(|n| n == "outcome").unwrap()];
        let is_stable = ["outcome=skip", "outcome=walk", "outcome=crawl"].contains(&label.as_str());
        let value = &b[a.len()];
        if !is_stable {
            assert_eq!(value, "gsn=null", "{label}");
        }
        computed += (value != "gsn=null") as usize;
    }
    assert!(computed > 0);
}

/// The robustness measures' cost is bounded up front: `trials × max_steps`
/// steps a sample (10¹¹ for 100000 × 1000000, about 100 days a sample) is
/// refused, naming both keys and the limit, before anything runs.
#[test]
fn a_steps_to_fall_too_costly_to_finish_is_refused_up_front() {
    let o = run_err(
        &[
            &FIG7A[..],
            &[
                "--set",
                "robustness.steps_to_fall=true",
                "--set",
                "robustness.trials=100000",
                "--set",
                "robustness.max_steps=1000000",
            ],
        ]
        .concat(),
        &[
            "robustness.trials × robustness.max_steps",
            "at most 10000000",
        ],
    );
    assert!(stdout(&o).is_empty());
}

/// `run`'s first Ctrl-C stops the samples in flight, not only the ones not
/// started: a sample whose steps to fall take minutes (2 trials of 200000
/// steps on a flat slope, σ = 0, where the walk never falls) is cut within seconds, the run exits 130 and keeps no row of it;
/// `--resume` would compute it again.
#[test]
fn the_first_interrupt_stops_a_long_robustness_sample_within_seconds() {
    use std::process::Stdio;
    use std::time::Duration;
    let dir = tempfile::tempdir().unwrap();
    let cfg = write(
        dir.path(),
        "c.toml",
        "seed = 1\nsamples = 2\n[params]\nlength = 0.8\nrho = 2.5\nalpha = 0.125\nfn = 3.269\n\
         zeta = 0.0514\nphi = 0.15\n[simulation]\nrobustness.steps_to_fall = true\n\
         robustness.trials = 2\nrobustness.max_steps = 200000\nrobustness.sigma = 0.0\n",
    );
    let out = dir.path().join("out");
    let mut child = bin()
        .args(["run", &cfg, "--out", s(&out), "--threads", "1", "--quiet"])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // The flat run takes well under a second; the trials then run.
    std::thread::sleep(Duration::from_secs(3));
    assert!(child.try_wait().unwrap().is_none(), "the run ended early");
    let (status, _) = interrupt(&mut child, Duration::from_secs(10));
    let err = std::io::read_to_string(child.stderr.take().unwrap()).unwrap();
    assert_eq!(status.code(), Some(130), "{err}");
    assert!(err.contains("stopping the samples in flight"), "{err}");
    assert!(!out.join("samples.parquet").exists());
}

/// The first Ctrl-C stops an MFPT in flight too, whose batches are many
/// one-step runs: a grid of two samples, the first a star too soft to stand
/// (f_n = 0.5 Hz: no gait, no MFPT, a finished chunk at once), the second
/// Fig. 7(a)'s gait with the MFPT at its most batches (3000, minutes), is
/// stopped within seconds of SIGINT, exits 130 and keeps the first chunk.
#[test]
fn the_first_interrupt_stops_an_mfpt_of_many_batches_within_seconds() {
    use std::process::Stdio;
    use std::time::{Duration, Instant};
    let dir = tempfile::tempdir().unwrap();
    let cfg = write(
        dir.path(),
        "c.toml",
        "seed = 1\nsamples = 1\n[params]\nlength = 0.8\nrho = 2.5\nalpha = 0.125\n\
         fn = { linspace = [0.5, 3.269, 2] }\nzeta = 0.0514\nphi = 0.15\n[simulation]\n\
         robustness.mfpt = true\nrobustness.sigma = 0.05\nrobustness.mfpt_batches = 3000\n",
    );
    let out = dir.path().join("out");
    let chunk = out.join(".partial/chunk-00000.parquet");
    let mut child = bin()
        .args(["run", &cfg, "--out", s(&out), "--threads", "1", "--quiet"])
        .args(["--chunk-size", "1"])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let t0 = Instant::now();
    while !chunk.exists() {
        if t0.elapsed() > Duration::from_secs(30) || child.try_wait().unwrap().is_some() {
            child.kill().ok();
            child.wait().ok();
            panic!("the first chunk did not appear");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    // The second sample's flat run takes well under a second; its MFPT runs.
    std::thread::sleep(Duration::from_secs(2));
    assert!(child.try_wait().unwrap().is_none(), "the run ended early");
    let (status, took) = interrupt(&mut child, Duration::from_secs(30));
    eprintln!("SIGINT to exit: {took:?}");
    let err = std::io::read_to_string(child.stderr.take().unwrap()).unwrap();
    assert_eq!(status.code(), Some(130), "{err}");
    // 2 s promised; 5 s allowed on a loaded machine.
    assert!(took < Duration::from_secs(5), "{took:?}");
    assert!(chunk.exists(), "the finished chunk was not kept");
    assert!(!out.join("samples.parquet").exists());
}

/// `simulate --json` has one schema for given options: the scan row's
/// columns, then the robustness measures asked for, null where a run has
/// none, however it ended. A star too soft to stand (f_n = 0.5 Hz, φ = 0.02:
/// it collapses as it is set down, before the run starts) has the keys of
/// the walk at Fig. 7(a), the measures null.
#[test]
fn simulate_json_has_the_same_keys_however_the_run_failed() {
    let asked = [
        "--set",
        "robustness.step_down=true",
        "--set",
        "robustness.gsn=true",
        "--set",
        "robustness.steps_to_fall=true",
        "--set",
        "robustness.trials=2",
        "--set",
        "robustness.max_steps=2",
    ];
    let keys =
        |v: &serde_json::Value| -> Vec<String> { v.as_object().unwrap().keys().cloned().collect() };
    let walk = json(&asked);
    assert_eq!(walk["outcome"], "walk");
    let soft_args = [&SOFT[..], &["--json"], &asked].concat();
    let soft: serde_json::Value = serde_json::from_str(&stdout(&run_ok(&soft_args))).unwrap();
    assert_eq!(soft["failure"], "standing_com_low", "{soft}");
    assert_eq!(keys(&soft), keys(&walk));
    for k in [
        "step_down_max",
        "gsn",
        "steps_to_fall",
        "steps_to_fall_censored",
    ] {
        assert!(walk[k].is_number(), "{k}: {walk}");
        assert!(soft[k].is_null(), "{k}: {soft}");
    }
    // The text form too: the robustness section, with "-" for each.
    let o = run_ok(&[&SOFT[..], &asked].concat());
    let text = stdout(&o);
    assert!(text.contains("[robustness]"), "{text}");
    assert!(text.contains("steps_to_fall_censored"), "{text}");
}

/// An MFPT with no fall counted is unbounded (mfpt and mfpt_hi infinite),
/// which is not the MFPT that was not computed: JSON writes the former
/// `"inf"` and the latter null; Parquet the former inf and the latter null.
/// Fig. 7(a)'s walk on a slope of σ = 2 mm counts no fall in its batches;
/// a star too soft to stand (f_n = 0.5 Hz) has no gait, so no MFPT.
#[test]
fn an_unbounded_mfpt_is_told_from_a_missing_one_in_json_and_parquet() {
    use arrow_array::{Array, Float64Array};
    let mfpt = [
        "--set",
        "robustness.mfpt=true",
        "--set",
        "robustness.sigma=0.002",
    ];
    let j = json(&mfpt);
    assert_eq!(j["outcome"], "walk", "{j}");
    assert_eq!(j["fall_rate"], 0.0, "{j}");
    assert_eq!(j["mfpt"], "inf", "{j}");
    assert_eq!(j["mfpt_hi"], "inf", "{j}");
    assert!(j["mfpt_lo"].as_f64().is_some_and(f64::is_finite), "{j}");
    let mut soft = FIG7A.to_vec();
    let at = soft.iter().position(|a| *a == "--fn").unwrap();
    soft[at + 1] = "0.5";
    let o = run_ok(&[&soft[..], &["--json"], &mfpt[..]].concat());
    let none: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert!(
        none["mfpt"].is_null() && none["mfpt_hi"].is_null(),
        "{none}"
    );
    // The same two in a scan's file.
    let dir = tempfile::tempdir().unwrap();
    let cfg = write(
        dir.path(),
        "c.toml",
        "seed = 1\nsamples = 1\n[params]\nlength = 0.8\nrho = 2.5\nalpha = 0.125\n\
         fn = { linspace = [0.5, 3.269, 2] }\nzeta = 0.0514\nphi = 0.15\n[simulation]\n\
         robustness.mfpt = true\nrobustness.sigma = 0.002\n",
    );
    let out = dir.path().join("out");
    run_ok(&["run", &cfg, "--out", s(&out), "--quiet"]);
    let b = &batches(&out.join("samples.parquet"))[0];
    let col = |name: &str| {
        b.column_by_name(name)
            .unwrap()
            .as_any()
            .downcast_ref::<Float64Array>()
            .unwrap()
            .clone()
    };
    for name in ["mfpt", "mfpt_hi"] {
        let c = col(name);
        assert!(c.is_null(0), "{name}: {c:?}");
        assert_eq!(c.value(1), f64::INFINITY, "{name}: {c:?}");
    }
}

/// `simulate` with robustness measures says, before it runs them, which it
/// measures: they take seconds (minutes for a deep MFPT), and a command
/// silent that long looks hung. A bare run, milliseconds long, prints
/// nothing on stderr.
#[test]
fn simulate_names_the_robustness_measures_it_runs_before_it_runs_them() {
    let sets = [
        "--set",
        "robustness.gsn=true",
        "--set",
        "robustness.sigma=0.05",
        "--set",
        "robustness.mfpt=true",
    ];
    let o = run_ok(&[&SIMULATE_FIG7A[..], &sets, &["--json", "--fake-sim"]].concat());
    let err = stderr(&o);
    assert!(
        err.contains("rtw-scan: simulating, then measuring gsn, mfpt"),
        "{err}"
    );
    let o = run_ok(&[&SIMULATE_FIG7A[..], &["--json", "--fake-sim"]].concat());
    assert_eq!(stderr(&o), "");
}
