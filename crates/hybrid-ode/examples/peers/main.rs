//! rtw's side of the peer benchmark (`scripts/peers_bench.sh`): `n`
//! trajectories of the bouncing ball and of the rimless wheel, each run to
//! its 10th impact by [`hybrid_ode::run`] at each tolerance, timed on one
//! thread, with the work done and the errors against the closed forms
//! (`closed_form.rs`). Prints one JSON object a line, one per
//! model × method × tolerance.
//!
//! `cargo run --release -p hybrid-ode --example peers -- [--n N] [--reps R] [--tols 1e-6,1e-9]`

mod closed_form;

use closed_form::{
    Ball, IMPACTS, Impacts, ball_height, ball_reference, wheel, wheel_rate, wheel_reference,
};
use hybrid_ode::{EngineOptions, HybridSystem, Method, Observer, Work, run};
use std::time::Instant;

struct Args {
    n: usize,
    reps: usize,
    tols: Vec<f64>,
}

fn parse() -> Args {
    let mut a = Args {
        n: 200,
        reps: 7,
        tols: vec![1e-6, 1e-9, 1e-12],
    };
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        let value = it.next().unwrap_or_else(|| panic!("{flag} needs a value"));
        match flag.as_str() {
            "--n" => a.n = value.parse().expect("--n: a count"),
            "--reps" => a.reps = value.parse().expect("--reps: a count"),
            "--tols" => {
                a.tols = value
                    .split(',')
                    .map(|s| s.parse().expect("--tols: numbers"))
                    .collect()
            }
            _ => panic!("unknown flag {flag} (--n, --reps, --tols)"),
        }
    }
    a
}

/// One trajectory's outcome: impact times, the state after the last
/// impact, and the work.
struct Outcome {
    times: [f64; IMPACTS],
    impacts: usize,
    y: [f64; 2],
    work: Work,
}

fn simulate<S>(sys: S, y0: [f64; 2], t_end: f64, opts: &EngineOptions) -> Outcome
where
    S: HybridSystem<2>,
    Impacts: Observer<2, S>,
{
    let mut sys = sys;
    let mut obs = Impacts::default();
    let mut y = y0;
    let end = run(&mut sys, &mut obs, 0.0, &mut y, t_end, opts);
    Outcome {
        times: obs.times,
        impacts: obs.count,
        y,
        work: end.work,
    }
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let m = v.len() / 2;
    if v.len() % 2 == 1 {
        v[m]
    } else {
        0.5 * (v[m - 1] + v[m])
    }
}

fn main() {
    let args = parse();
    let w = wheel();
    // The parameters, for the driver to check against its own copy.
    println!(
        "{{\"params\":{{\"g\":{},\"e\":{},\"impacts\":{},\"wheel_l\":{},\"wheel_gamma\":{},\"wheel_spokes\":{},\"n\":{}}}}}",
        closed_form::G,
        closed_form::RESTITUTION,
        IMPACTS,
        closed_form::WHEEL_L,
        closed_form::WHEEL_GAMMA,
        closed_form::WHEEL_SPOKES,
        args.n
    );
    for model in ["ball", "rimless"] {
        for (method, name) in [(Method::Dop853, "dop853"), (Method::Dp54, "dp54")] {
            for &tol in &args.tols {
                let opts = EngineOptions {
                    method,
                    rtol: tol,
                    atol: tol,
                    // No step cap: the peers have none, and event detection
                    // does not need one.
                    h_max: 0.0,
                    ..EngineOptions::default()
                };
                let one = |i: usize| match model {
                    "ball" => simulate(Ball, [ball_height(i, args.n), 0.0], 100.0, &opts),
                    _ => simulate(w, w.initial_state(wheel_rate(i, args.n)), 100.0, &opts),
                };
                let mut per_traj = Vec::with_capacity(args.reps);
                let mut outcomes = Vec::new();
                for _ in 0..args.reps {
                    let start = Instant::now();
                    outcomes = (0..args.n).map(one).collect::<Vec<_>>();
                    per_traj.push(start.elapsed().as_secs_f64() / args.n as f64);
                }
                let (mut t_err, mut y_err, mut failed) = (0.0f64, 0.0f64, 0usize);
                let mut work = Work::default();
                for (i, o) in outcomes.iter().enumerate() {
                    work += o.work;
                    let mut want = [0.0; IMPACTS];
                    let y_ref = match model {
                        "ball" => ball_reference(ball_height(i, args.n), &mut want),
                        _ => wheel_reference(&w, wheel_rate(i, args.n), &mut want),
                    };
                    if o.impacts < IMPACTS {
                        failed += 1;
                        continue;
                    }
                    for (got, want) in o.times.iter().zip(&want) {
                        t_err = t_err.max((got - want).abs());
                    }
                    for (got, want) in o.y.iter().zip(&y_ref) {
                        y_err = y_err.max((got - want).abs());
                    }
                }
                let n = args.n as f64;
                println!(
                    "{{\"tool\":\"rtw\",\"method\":\"{name}\",\"model\":\"{model}\",\"tol\":{tol:e},\"n\":{},\"reps\":{},\"time_per_traj_s\":{:e},\"time_per_traj_runs_s\":[{}],\"compile_s\":0,\"steps\":{},\"rejected\":{},\"rhs_evals\":{},\"events\":{},\"failed\":{failed},\"max_event_time_err\":{t_err:e},\"max_state_err\":{y_err:e}}}",
                    args.n,
                    args.reps,
                    median(per_traj.clone()),
                    per_traj
                        .iter()
                        .map(|t| format!("{t:e}"))
                        .collect::<Vec<_>>()
                        .join(","),
                    work.steps as f64 / n,
                    work.rejected as f64 / n,
                    work.rhs_evals as f64 / n,
                    work.events as f64 / n,
                );
            }
        }
    }
}
