use rtw_model::modal::*;
use rtw_model::options::Damping;
use rtw_model::strings::StringSet;
use rtw_model::{Normalization, Params, Physical};

fn set(ph: &Physical, s: f64, d: Damping) -> StringSet {
    StringSet { k: ph.k, c: ph.c, r: ph.r, rest_length: s * ph.r, slack: false, damping: d }
}

#[test]
fn explore() {
    let ph = Physical::new(&Params::fig7a(), Normalization::Supplementary, 9.81);
    for d in [Damping::Along, Damping::Relative] {
        let a = approximate_modes(&ph, &set(&ph, 0.0, d));
        println!("{d:?} {:?}\nK={} C={}", a, a.stiffness, a.damping);
        println!("cc closed {}", critical_damping_closed_form(&ph, &set(&ph, 0.0, d)));
    }
    println!("s18 {}", s18_frequency(&ph));
    for s in [0.0, 0.25, 0.5, 0.85] {
        let m = free_star_modes(&ph, &set(&ph, s, Damping::Along));
        println!("s={s} rigid {} f={:?}", m.rigid_modes, m.freq_hz);
        println!("rest forces {:?}", star_rest_forces(&set(&ph, s, Damping::Along)));
        for j in 0..9 { println!("  {:.4} {:?}", m.freq_hz[j], m.shapes[j].map(|v| (v*1000.0).round()/1000.0)); }
    }
}
