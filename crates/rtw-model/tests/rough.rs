//! The RTW on a rough slope (docs/robustness-rough.md): a roughness of 0 is the
//! flat slope bit for bit, and a rough ground is a pure function of its seed.

use rtw_model::options::TerrainOptions;
use rtw_model::{Options, Params, simulate};

fn on(terrain: TerrainOptions) -> Options {
    Options {
        terrain,
        ..Options::default()
    }
}

#[test]
fn roughness_zero_or_out_of_reach_is_the_flat_run_bit_for_bit() {
    let p = Params::fig7a();
    let flat = format!("{:?}", simulate(&p, &Options::default()));
    for terrain in [
        TerrainOptions::rough(0.0, 5, 3.0, 0.2),
        // Rough patches the run never reaches: the ground hooks and edge
        // guards run all along, and change nothing.
        TerrainOptions::rough(0.01, 5, 1e6, 0.2),
    ] {
        assert_eq!(
            format!("{:?}", simulate(&p, &on(terrain))),
            flat,
            "{terrain:?}"
        );
    }
}

#[test]
fn a_rough_slope_is_a_function_of_its_seed() {
    let p = Params::fig7a();
    let flat = simulate(&p, &Options::default());
    let rough = |seed| simulate(&p, &on(TerrainOptions::rough(0.01, seed, 3.0, 0.2)));
    let (a, b, c) = (rough(1), rough(1), rough(2));
    assert_eq!(format!("{a:?}"), format!("{b:?}"));
    // A control: the ground is met, and another seed is another ground.
    assert_ne!(a.t_end, flat.t_end);
    assert_ne!(format!("{a:?}"), format!("{c:?}"));
}

#[test]
fn a_tip_meeting_a_face_is_a_contact_that_makes_no_energy() {
    // Short patches, where the flat gait's feet meet faces often (before
    // faces were contacts, these runs ended as `riser` collapses within a
    // few steps). Every reset may only take energy: the energy removed by
    // resets so far never falls; and the balance, which also covers the
    // wall slide and the corner in between, closes at a tight tolerance.
    let p = Params::fig7a();
    let mut faces = 0;
    for seed in 1..=4 {
        let o = Options {
            method: rtw_model::Method::Dop853,
            rtol: 1e-10,
            atol: 1e-12,
            ..on(TerrainOptions::rough(0.01, seed, 3.0, 0.2))
        };
        let mut last = 0.0;
        let mut worst_gain = 0.0f64;
        let out = rtw_model::simulate_traced(&p, &o, &mut |s| {
            worst_gain = worst_gain.max(last - s.impact_loss);
            last = s.impact_loss;
            faces += s.contact.iter().filter(|c| c.abs() >= 3).count();
        });
        assert!(out.failure.is_none_or(|f| f.as_str() != "riser"), "{out:?}");
        let scale = out.energy.gravity_released.abs() + out.energy.initial.abs();
        assert!(
            worst_gain <= 1e-9 * scale,
            "seed {seed}: a reset made {worst_gain} J"
        );
        assert!(
            out.energy.balance_error.abs() < 1e-6 * scale,
            "seed {seed}: {:?}",
            out.energy
        );
    }
    assert!(faces > 0, "no tip met a face");
}
