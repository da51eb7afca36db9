//! rtw's side of the peer benchmark (`scripts/peers_bench.sh`): `n`
//! trajectories of the bouncing ball and of the rimless wheel, each run to
//! its 10th impact, and of the impact oscillator near grazing to its first,
//! by [`hybrid_ode::run`] at each tolerance, timed on one
//! thread, with the work done and the errors against the closed forms
//! (`closed_form.rs`). Prints one JSON object a line, one per
//! model × method × tolerance.
//!
//! `cargo run --release -p hybrid-ode --example peers -- [--n N] [--reps R] [--tols 1e-6,1e-9]`

mod closed_form;

use closed_form::{
    Ball, IMPACTS, Impacts, Oscillator, ball_height, ball_reference, osc_epsilon, wheel,
    wheel_rate, wheel_reference,
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

fn simulate<S>(sys: S, t0: f64, y0: [f64; 2], impacts: usize, opts: &EngineOptions) -> Outcome
where
    S: HybridSystem<2>,
    Impacts: Observer<2, S>,
{
    let mut sys = sys;
    let mut obs = Impacts::stopping_after(impacts);
    let mut y = y0;
    let end = run(&mut sys, &mut obs, t0, &mut y, T_END, opts);
    Outcome {
        times: obs.times,
        impacts: obs.count,
        y,
        work: end.work,
    }
}

/// Far past the last impact of every model here.
const T_END: f64 = 100.0;

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
        "{{\"params\":{{\"g\":{},\"e\":{},\"impacts\":{},\"wheel_l\":{},\"wheel_gamma\":{},\"wheel_spokes\":{},\"osc_zeta\":{},\"osc_omega\":{},\"osc_sigma\":{},\"osc_r\":{},\"n\":{}}}}}",
        closed_form::G,
        closed_form::RESTITUTION,
        IMPACTS,
        closed_form::WHEEL_L,
        closed_form::WHEEL_GAMMA,
        closed_form::WHEEL_SPOKES,
        closed_form::OSC_ZETA,
        closed_form::OSC_OMEGA,
        closed_form::OSC_SIGMA,
        closed_form::OSC_R,
        args.n
    );
    for model in ["ball", "rimless", "oscillator"] {
        // The oscillator is scored on its first impact, the one with a
        // closed form.
        let impacts = if model == "oscillator" { 1 } else { IMPACTS };
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
                    "ball" => simulate(Ball, 0.0, [ball_height(i, args.n), 0.0], impacts, &opts),
                    "rimless" => {
                        let y0 = w.initial_state(wheel_rate(i, args.n));
                        simulate(w, 0.0, y0, impacts, &opts)
                    }
                    _ => {
                        let osc = Oscillator::past_grazing(osc_epsilon(i, args.n));
                        let (t0, y0) = osc.start();
                        simulate(osc, t0, y0, impacts, &opts)
                    }
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
                        "rimless" => wheel_reference(&w, wheel_rate(i, args.n), &mut want),
                        _ => {
                            let (t, y) =
                                Oscillator::past_grazing(osc_epsilon(i, args.n)).reference();
                            want[0] = t;
                            y
                        }
                    };
                    // A run short of its impacts, or one whose first impact
                    // is a later one (a crossing missed), failed.
                    if o.impacts < impacts || (o.times[0] - want[0]).abs() > 1.0 {
                        failed += 1;
                        continue;
                    }
                    for (got, want) in o.times.iter().zip(&want).take(impacts) {
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
