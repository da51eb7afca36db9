//! One run at the Fig. 7(a) point, repeated, for profilers:
//! `cargo run --release -p rtw-model --example profile -- [s] [method] [rtol] [reps]`
//! (defaults: `default` dop853 1e-10 1; `s = default` keeps the default
//! model's rest-length ratio), e.g. under
//! `valgrind --tool=callgrind target/release/examples/profile` for repeatable
//! instruction counts of the RHS against the whole run.
use rtw_model::Method;
use rtw_model::{Options, Params, simulate};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let arg = |i: usize, default: &str| args.get(i).cloned().unwrap_or(default.to_string());
    let mut o = Options::default();
    let s = arg(0, "default");
    if s != "default" {
        o.strings.rest_length_ratio = s.parse().expect("s: `default` or a number in [0, 1)");
    }
    o.method = match arg(1, "dop853").as_str() {
        "dp54" => Method::Dp54,
        "dop853" => Method::Dop853,
        "rk4" => Method::Rk4,
        m => panic!("method: dp54, dop853 or rk4, not {m}"),
    };
    o.rtol = arg(2, "1e-10").parse().expect("rtol: a number in (0, 1)");
    o.atol = o.rtol * 1e-2;
    let reps: usize = arg(3, "1").parse().expect("reps: a count >= 1");
    for _ in 0..reps {
        let out = simulate(&Params::fig7a(), &o);
        println!(
            "{} f_w {:.4} rhs {} steps {} rejected {} events {}",
            out.label.as_str(),
            out.f_w,
            out.work.rhs_evals,
            out.work.steps,
            out.work.rejected,
            out.work.events
        );
    }
}
