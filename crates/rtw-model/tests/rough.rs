//! The RTW on a rough slope (docs/robustness.md): a roughness of 0 is the
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
