//! Prints the outcome at the article's Fig. 7(a) point for the literal model
//! (docs/model.md §9) with string rest-length ratios `s` (default 0 and 0.85),
//! then for the adopted default model:
//! `cargo run --release -p rtw-model --example fig7a [-- s ...]`.
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
    let mut runs: Vec<(String, Options)> = ratios
        .into_iter()
        .map(|s| {
            let mut o = Options::literal();
            o.strings.rest_length_ratio = s;
            (format!("literal s={s}"), o)
        })
        .collect();
    runs.push(("default".into(), Options::default()));
    for (name, o) in runs {
        let start = std::time::Instant::now();
        let out = simulate(&Params::fig7a(), &o);
        let ms = start.elapsed().as_secs_f64() * 1e3;
        let f = out.fractions;
        let w = out.work;
        println!(
            "{name:<16} {label:<8} NLSP {n:.3} SLSP {sl:.3} DLSP {d:.3} TLSP {t:.3}  \
             f_w {fw:.2} newfoot {nf:.2}  speed {v:.3} m/s  period {p}  mu_req {mu:.2}  \
             slide {slide:.3} s  touchdowns {td}  steps {st} rejected {rj} rhs {rhs} events {ev}  \
             balance {bal:.1e} J  {ms:.1} ms",
            label = out.label.as_str(),
            n = f.nlsp,
            sl = f.slsp,
            d = f.dlsp,
            t = f.tlsp,
            fw = out.f_w,
            nf = out.f_w_newfoot,
            v = out.speed,
            p = out.period,
            mu = out.mu_required,
            slide = out.slide_time,
            td = out.touchdowns,
            st = w.steps,
            rj = w.rejected,
            rhs = w.rhs_evals,
            ev = w.events,
            bal = out.energy.balance_error,
        );
    }
}
