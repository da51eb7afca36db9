//! `rtw-scan simulate` on a rough slope and with the Monte Carlo steps to
//! fall (docs/robustness-rough.md), with the real simulator.

use crate::common::*;

const FIG7A: [&str; 13] = SIMULATE_FIG7A;

fn json(extra: &[&str]) -> serde_json::Value {
    let o = run_ok(&[&FIG7A[..], &["--json"], extra].concat());
    serde_json::from_str(&stdout(&o)).unwrap()
}

const MC: [&str; 6] = [
    "--set",
    "robustness.steps_to_fall=true",
    "--set",
    "robustness.trials=6",
    "--set",
    "robustness.max_steps=40",
];

#[test]
fn steps_to_fall_is_in_the_json_row_only_when_asked_for_and_a_function_of_the_seed() {
    let flat = json(&[]);
    assert!(flat.get("steps_to_fall").is_none(), "{flat}");
    let v = json(&MC);
    let mean = v["steps_to_fall"].as_f64().unwrap();
    let (lo, hi) = (
        v["steps_to_fall_lo"].as_f64().unwrap(),
        v["steps_to_fall_hi"].as_f64().unwrap(),
    );
    assert!(lo <= mean && mean <= hi && mean <= 40.0, "{v}");
    assert!(v["steps_to_fall_censored"].as_f64().unwrap() <= 6.0, "{v}");
    // The same seed gives the same trials, another seed others: on ground
    // rough enough (30 cm) that trials fall before the censoring count (at
    // the default 1 cm, with a foot at a face a contact, all six walk on).
    let rough = [&MC[..], &["--set", "robustness.sigma=0.3"]].concat();
    let r = json(&rough);
    assert!(r["steps_to_fall_censored"].as_f64().unwrap() < 6.0, "{r}");
    assert_eq!(json(&rough)["steps_to_fall"], r["steps_to_fall"]);
    let other = json(&[&rough[..], &["--set", "terrain.seed=1"]].concat());
    assert_ne!(other["steps_to_fall"], r["steps_to_fall"]);
    // Asking for it changes nothing else in the row.
    for (key, value) in flat.as_object().unwrap() {
        if key != "wall_time_s" {
            assert_eq!(&v[key], value, "{key}");
        }
    }
    // σ = 0 is the flat slope: every trial is censored.
    let smooth = json(&[&MC[..], &["--set", "robustness.sigma=0"]].concat());
    assert_eq!(smooth["steps_to_fall"], 40.0);
    assert_eq!(smooth["steps_to_fall_censored"], 6.0);
}

#[test]
fn rough_terrain_options_run_and_are_validated() {
    let flat = json(&[]);
    let zero = json(&["--set", "terrain.roughness=0", "--set", "terrain.seed=9"]);
    assert_eq!(zero, {
        let mut f = flat.clone();
        f["wall_time_s"] = zero["wall_time_s"].clone();
        f
    });
    let rough = json(&[
        "--set",
        "terrain.roughness=0.01",
        "--set",
        "terrain.step_at=3",
    ]);
    assert_ne!(rough["t_end"], flat["t_end"]);
    for (set, message) in [
        (
            "terrain.roughness=-0.1",
            "simulation.terrain.roughness: -0.1 is invalid",
        ),
        ("terrain.patch=0", "simulation.terrain.patch: 0 is invalid"),
        (
            "robustness.sigma=-1",
            "simulation.robustness.sigma: -1 is invalid",
        ),
        (
            "robustness.trials=1",
            "simulation.robustness.trials: 1 is invalid",
        ),
        (
            "robustness.mfpt_batches=1",
            "simulation.robustness.mfpt_batches: 1 is invalid: must be in [2, 3000]",
        ),
        (
            "robustness.mfpt_batches=3001",
            "simulation.robustness.mfpt_batches: 3001 is invalid: must be in [2, 3000]",
        ),
    ] {
        run_err(
            &[&FIG7A[..], &["--set", set]].concat(),
            &[message, "must be in"],
        );
    }
}
