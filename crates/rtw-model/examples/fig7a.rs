//! Prints the outcome at the article's Fig. 7(a) point for each string
//! variant: `cargo run --release -p rtw-model --example fig7a [-- s ...]`.
use rtw_model::{Options, Params, simulate};

fn main() {
    let ratios: Vec<f64> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let ratios = if ratios.is_empty() {
        vec![0.0, 0.85]
    } else {
        ratios
    };
    for s in ratios {
        let mut o = Options::default();
        o.strings.rest_length_ratio = s;
        let t = std::time::Instant::now();
        let out = simulate(&Params::fig7a(), &o);
        let f = out.fractions;
        println!(
            "s={s:<5} {:<8} NLSP {:.3} SLSP {:.3} DLSP {:.3} TLSP {:.3}  f_w {:.3} newfoot {:.3} speed {:.3} m/s  period {}  mu_req {:.2}  td {}  steps {} rej {} rhs {} events {}  balance {:.1e}  {:.1} ms",
            out.label.as_str(),
            f.nlsp,
            f.slsp,
            f.dlsp,
            f.tlsp,
            out.f_w,
            out.f_w_newfoot,
            out.speed,
            out.period,
            out.mu_required,
            out.touchdowns,
            out.work.steps,
            out.work.rejected,
            out.work.rhs_evals,
            out.work.events,
            out.energy.balance_error,
            t.elapsed().as_secs_f64() * 1e3
        );
    }
}
