//! Median wall time and integrator work of one 20 s run at the Fig. 7(a)
//! point, per method and tolerance, as a Markdown table (medians of 9 runs):
//! `cargo run --release -p rtw-model --example work`.
use rtw_model::Method;
use rtw_model::{Options, Params, simulate};

fn main() {
    println!("| s | method | rtol | label | median ms | RHS evals | steps | rejected | events |");
    println!("|---|---|---|---|---|---|---|---|---|");
    // s = 0 (no prestress) and the default model's natural length.
    for s in [0.0, Options::default().strings.rest_length_ratio] {
        for (method, name) in [(Method::Dp54, "dp54"), (Method::Dop853, "dop853")] {
            for rtol in [1e-6, 1e-8, 1e-10] {
                let mut o = Options {
                    method,
                    rtol,
                    atol: rtol * 1e-2,
                    ..Options::default()
                };
                o.strings.rest_length_ratio = s;
                let mut times = Vec::new();
                let mut out = None;
                for _ in 0..9 {
                    let t = std::time::Instant::now();
                    out = Some(simulate(&Params::fig7a(), &o));
                    times.push(t.elapsed().as_secs_f64() * 1e3);
                }
                times.sort_by(f64::total_cmp);
                let out = out.expect("ran");
                let w = out.work;
                println!(
                    "| {s} | {name} | {rtol:e} | {} | {:.2} | {} | {} | {} | {} |",
                    out.label.as_str(),
                    times[4],
                    w.rhs_evals,
                    w.steps,
                    w.rejected,
                    w.events
                );
            }
        }
    }
}
