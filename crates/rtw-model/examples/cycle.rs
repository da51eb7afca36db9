//! Limit cycle of the Fig. 7(a) gait: `cargo run --release -p rtw-model --example
//! cycle [s|literal] [steps]`: iterates the step map from the start, solves for
//! the period-1 fixed point by Newton (variational Jacobians), prints the
//! multipliers, compares them with the Jacobian by central differences of the
//! map at three steps (a Newton solve from the fixed point with
//! `Jacobian::Differences`), and times one step and one solve of each kind.
use rtw_model::cycles::{CycleOptions, Jacobian, SectionPoint, StepMap};
use rtw_model::{Options, Params};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let mut options = Options::default();
    match args.get(1).map(String::as_str) {
        Some("literal") => options = Options::literal(),
        Some(s) => options.strings.rest_length_ratio = s.parse().expect("s: a number or `literal`"),
        None => {}
    }
    let steps: usize = args.get(2).map(|s| s.parse().unwrap()).unwrap_or(200);
    let params = Params::fig7a();
    let cycle = CycleOptions::default();
    let map = StepMap::new(&params, &options, &cycle);
    let first = map.first(&options).unwrap();
    let it = map.iterate(&first.to, steps).unwrap();
    for (k, s) in it.iter().enumerate() {
        if k % 10 == 0 || k + 5 > steps {
            println!(
                "{k:4} t {:.9} omega {:.9} modes {:?}",
                s.time,
                s.to.omega(),
                s.to.modes
            );
        }
    }
    let last = it.last().unwrap().to;
    let t = std::time::Instant::now();
    let lc = map.solve(&last, 1, &cycle);
    println!("{:?}", t.elapsed());
    match lc {
        Ok(lc) => {
            println!(
                "period {} label {:?} residual {:.2e} iters {}",
                lc.period,
                lc.label(&options.labels),
                lc.fixed_point.residual,
                lc.fixed_point.iterations
            );
            println!("z {:?}", lc.fixed_point.z);
            for m in &lc.multipliers {
                println!("  {:.9} {:+.9}i |{:.9}|", m.re, m.im, m.norm());
            }
            let p = lc.orbit[0];
            timing(&map, &p, &cycle);
            for rel in [1e-4, 1e-5, 1e-6] {
                let fd = differences(rel);
                let j = StepMap::new(&params, &options, &fd)
                    .solve(&p, 1, &fd)
                    .unwrap()
                    .fixed_point
                    .jacobian;
                let mu = hybrid_ode::limit::multipliers(&j);
                println!(
                    "fd {rel:e}: {:?}",
                    mu.iter()
                        .map(|m| format!("{:.9}{:+.9}i", m.re, m.im))
                        .collect::<Vec<_>>()
                );
                println!(
                    "   max |J_fd - J_var| = {:.3e}",
                    (&j - &lc.fixed_point.jacobian).abs().max()
                );
            }
        }
        Err(e) => println!("error: {e}"),
    }
}

/// Newton with the Jacobian by central differences of relative step `rel`.
fn differences(rel: f64) -> CycleOptions {
    CycleOptions {
        jacobian: Jacobian::Differences { rel },
        ..CycleOptions::default()
    }
}

fn timing(map: &StepMap, p: &SectionPoint, cycle: &CycleOptions) {
    let t = std::time::Instant::now();
    for _ in 0..20 {
        let _ = map.step(p);
    }
    let a = t.elapsed().as_secs_f64() / 20.0;
    let t = std::time::Instant::now();
    let _ = map.solve(p, 1, cycle);
    let b = t.elapsed().as_secs_f64();
    let t = std::time::Instant::now();
    let _ = map.solve(p, 1, &differences(1e-6));
    let c = t.elapsed().as_secs_f64();
    println!(
        "step {:.3} ms, solve (variational) {:.3} ms, solve (fd) {:.3} ms",
        a * 1e3,
        b * 1e3,
        c * 1e3
    );
}
