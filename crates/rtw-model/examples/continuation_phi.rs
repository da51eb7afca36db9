//! The Fig. 7(a) walk's branch in the slope φ, stable and unstable, with its
//! bifurcations: `cargo run --release -p rtw-model --example continuation_phi`.
//!
//! Solves the period-1 walk at φ = 0.15 (as the `cycle` example), continues
//! its fixed point of the step map in φ both ways by pseudo-arclength
//! ([`StepMapFamily`]: Jacobians in z by the variational equations, in φ by
//! central differences), locates the bifurcations on it, and switches onto the
//! period-2 branch at the period doubling. Prints one line per point:
//! `branch φ stable max|μ| ω` and one per bifurcation.
use hybrid_ode::continuation::{self, Kind, Options as Cont};
use hybrid_ode::limit;
use nalgebra::DMatrix;
use rtw_model::cycles::continuation::StepMapFamily;
use rtw_model::cycles::stepmap::{CycleOptions, StepMap};
use rtw_model::{Options, Param, Params};

fn nontrivial(j: &DMatrix<f64>) -> Vec<nalgebra::Complex<f64>> {
    limit::nontrivial_multipliers(j)
}

fn main() {
    let options = Options::default();
    let base = Params::fig7a();
    let cycle = CycleOptions::default();
    let map = StepMap::new(&base, &options, &cycle);
    let lc = map
        .limit_cycle(&options, &cycle)
        .expect("the Fig. 7(a) walk");
    assert_eq!(lc.period, 1);
    let template = lc.orbit[0];
    let z0 = lc.fixed_point.z.clone();
    let opts = Cont {
        ds: 0.02,
        ds_max: 0.05,
        ds_min: 1e-6,
        p_min: 0.02,
        p_max: 0.35,
        tol: 1e-8,
        locate_tol: 1e-6,
        max_points: 400,
        z_scale: map.coord_scale(&template),
        p_scale: 0.1,
        ..Cont::default()
    };
    let t = std::time::Instant::now();
    for dir in [1.0, -1.0] {
        let mut f = StepMapFamily::new(&base, &options, &cycle, Param::Phi, template, 1);
        let b = continuation::continue_branch(&mut f, &z0, base.phi, dir, &opts, &nontrivial)
            .expect("a start");
        for pt in &b.points {
            let rho = limit::spectral_radius(&pt.multipliers);
            println!("P1 {:.6} {} {:.4} {:.6}", pt.p, pt.stable, rho, pt.z[1]);
        }
        println!("P1 end {:?} after {} points", b.end, b.points.len());
        for bif in &b.bifurcations {
            println!(
                "P1 bifurcation {:?} at phi {:.6} multipliers {:?}",
                bif.kind,
                bif.point.p,
                &bif.point.multipliers[..bif.point.multipliers.len().min(3)]
            );
            if bif.kind == Kind::PeriodDoubling {
                let f = StepMapFamily::new(&base, &options, &cycle, Param::Phi, template, 1);
                match continuation::switch_period_doubling(f, bif, 1.0, &opts, &nontrivial) {
                    Ok((two, _)) => {
                        for pt in &two.points {
                            let rho = limit::spectral_radius(&pt.multipliers);
                            println!("P2 {:.6} {} {:.4}", pt.p, pt.stable, rho);
                        }
                        println!("P2 end {:?} after {} points", two.end, two.points.len());
                        for b2 in &two.bifurcations {
                            println!("P2 bifurcation {:?} at phi {:.6}", b2.kind, b2.point.p);
                        }
                    }
                    Err(e) => println!("P2 switch failed: {e}"),
                }
            }
        }
    }
    eprintln!("{:?}", t.elapsed());
}
