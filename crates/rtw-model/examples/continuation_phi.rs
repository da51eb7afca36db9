//! The Fig. 7(a) walk's branch in the slope φ, stable and unstable, with its
//! bifurcations: `cargo run --release -p rtw-model --example continuation_phi`.
//!
//! The library call behind `rtw-scan continuation` ([`diagram`]): solves the
//! period-1 walk at φ = 0.15, continues its fixed point of the step map in φ
//! both ways by pseudo-arclength, locates the bifurcations on it, and
//! switches onto the period-2 branch at the period doubling. Prints one line
//! per point (`branch period φ stable max|μ|`) and one per bifurcation.
use hybrid_ode::continuation::Options as Cont;
use hybrid_ode::limit;
use rtw_model::cycles::CycleOptions;
use rtw_model::cycles::{DiagramOptions, diagram};
use rtw_model::{Options, Param, Params};

fn main() {
    let opts = DiagramOptions {
        continuation: Cont {
            ds: 0.02,
            ds_max: 0.05,
            ds_min: 1e-6,
            p_min: 0.02,
            p_max: 0.35,
            tol: 1e-8,
            locate_tol: 1e-6,
            max_points: 400,
            p_scale: 0.1,
            ..Cont::default()
        },
        switch_period_doubling: true,
    };
    let t = std::time::Instant::now();
    let d = diagram(
        &Params::fig7a(),
        &Options::default(),
        &CycleOptions::default(),
        Param::Phi,
        &opts,
    )
    .expect("the Fig. 7(a) walk");
    for (i, b) in d.branches.iter().enumerate() {
        for pt in &b.branch.points {
            let rho = limit::spectral_radius(&pt.multipliers);
            println!("{i} P{} {:.6} {} {rho:.4}", b.period, pt.p, pt.stable);
        }
        println!(
            "{i} end {:?} after {} points",
            b.branch.end,
            b.branch.points.len()
        );
        for bif in &b.branch.bifurcations {
            println!("{i} bifurcation {:?} at phi {:.6}", bif.kind, bif.point.p);
        }
    }
    eprintln!("{:?}", t.elapsed());
}
