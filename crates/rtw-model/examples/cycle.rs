//! Limit cycle of the Fig. 7(a) gait: `cargo run --release -p rtw-model --example
//! cycle [s|literal] [steps]`: iterates the step map from the start, solves for
//! the period-1 fixed point by Newton (variational Jacobians), prints the
//! multipliers, compares them with central differences of the map at three
//! steps, and times one step, one variational step and one difference Jacobian.
use rtw_model::cycles::stepmap::{CycleOptions, StepMap};
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
            timing(&map, &p);
            for rel in [1e-4, 1e-5, 1e-6] {
                let j = map.fd_jacobian(&p, rel).unwrap();
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

fn timing(map: &StepMap, p: &rtw_model::cycles::section::SectionPoint) {
    let t = std::time::Instant::now();
    for _ in 0..20 {
        let _ = map.step(p);
    }
    let a = t.elapsed().as_secs_f64() / 20.0;
    let t = std::time::Instant::now();
    for _ in 0..5 {
        let _ = map.step_with_jacobian(p);
    }
    let b = t.elapsed().as_secs_f64() / 5.0;
    let t = std::time::Instant::now();
    let _ = map.fd_jacobian(p, 1e-6);
    let c = t.elapsed().as_secs_f64();
    println!(
        "step {:.3} ms, variational {:.3} ms, fd {:.3} ms",
        a * 1e3,
        b * 1e3,
        c * 1e3
    );
}
