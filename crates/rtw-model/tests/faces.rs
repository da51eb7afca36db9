//! On the rough slope no tip goes below the ground under it: every face is
//! a contact (docs/model.md §4), so a foot that meets one stops against
//! it, slides along it, or rests in the corner at its foot.

use rtw_model::options::TerrainOptions;
use rtw_model::{Options, Params, TraceSample, simulate_traced};

/// Each tip's position, from its rod's centre and angle.
fn tip_heights(s: &TraceSample, half: f64) -> [[f64; 2]; 6] {
    let mut out = [[0.0; 2]; 6];
    for (r, p) in s.pose.iter().enumerate() {
        let (c, sn) = (p[2].cos(), p[2].sin());
        out[2 * r] = [p[0] + half * c, p[1] + half * sn];
        out[2 * r + 1] = [p[0] - half * c, p[1] - half * sn];
    }
    out
}

#[test]
fn no_tip_goes_below_the_rough_ground() {
    let p = Params::fig7a();
    // Each (roughness, patch, seed) had a tip go into the ground or a face
    // and on through it, before what stops it (plant::terrain's tests);
    // seeds 39, 62 and 7 met theirs on the way to the fixes of the others,
    // whose trajectories they change:
    // * 1 cm, seeds 2, 5, 9, 10: a tip put on a face at its foot slid back
    //   down it, through the lower patch (0.3 m below, then a collapse);
    // * 5 cm, seeds 12 and 42: a free tip cut a face's corner within one
    //   step (2.0 and 2.5 mm inside);
    // * 1 cm, seed 71: a tip went up a 1 mm face and over its top within
    //   one step, and on down through the lower patch;
    // * 3 cm, seed 39: a tip slid away from a face's foot and back into it;
    // * 3 cm, seed 62: a tip lifted off as another rod slipped, and fell
    //   through the ground;
    // * 2 cm on 0.2 m patches, seed 7: a tip bounced off a face was left
    //   on its far side by the rounding of its rod's centre.
    let cases = [
        (0.01, 0.8, 2),
        (0.01, 0.8, 5),
        (0.01, 0.8, 9),
        (0.01, 0.8, 10),
        (0.05, 0.8, 12),
        (0.05, 0.8, 42),
        (0.01, 0.8, 71),
        (0.03, 0.8, 39),
        (0.03, 0.8, 62),
        (0.02, 0.2, 7),
    ];
    for (sigma, patch, seed) in cases {
        let terrain = TerrainOptions::rough(sigma, seed, 1.0, patch);
        let o = Options {
            terrain,
            t_max: 300.0,
            stop_when_settled: false,
            ..Options::default()
        };
        let mut lowest: (f64, f64) = (f64::INFINITY, 0.0);
        let out = simulate_traced(&p, &o, &mut |s: &TraceSample| {
            for [x, y] in tip_heights(s, p.length / 2.0) {
                // A tip within a micrometre of a face is at its foot: the
                // lower of the two patches (a tip leaving the corner may
                // stray nanometres into the face before it moves away).
                let ground = terrain.ground(x - 1e-6).min(terrain.ground(x + 1e-6));
                let below = y - ground;
                if below < lowest.0 {
                    lowest = (below, s.t);
                }
            }
        });
        assert!(
            lowest.0 > -1e-6,
            "{sigma} m, {patch} m patches, seed {seed}: a tip {:.3e} m below the ground at t = {:.4} s ({:?}, {:?})",
            -lowest.0,
            lowest.1,
            out.label,
            out.failure
        );
    }
}

/// The survey behind the cases above (`cargo test --release -p rtw-model
/// --test faces -- --ignored --nocapture`, about a minute): Fig. 7(a) for
/// 300 s on rough slopes of 5 mm to 10 cm (seeds 1–100, odd seeds on
/// 0.2 m patches, even on 0.8 m) and over single steps of 2 cm to 2 m
/// (100 heights and places), printing each ground's deepest tip. No tip
/// goes 10 µm into the ground or a face; the deepest, 2 µm, are tips on a
/// face that dip below its foot for a moment and come back (two at 2 cm).
#[test]
#[ignore]
fn survey_no_tip_goes_into_the_ground_on_many_grounds() {
    let p = Params::fig7a();
    // A roughness (odd seeds on 0.2 m patches, even on 0.8 m), or with
    // none a single step of 2 cm per seed.
    let ground = |sigma: Option<f64>, seed: u64| match sigma {
        Some(sigma) => {
            let patch = if seed.is_multiple_of(2) { 0.8 } else { 0.2 };
            TerrainOptions::rough(sigma, seed, 1.0, patch)
        }
        None => {
            let mut t = TerrainOptions::default();
            t.step_height = 0.02 * seed as f64;
            t.step_at = 1.0 + 0.013 * seed as f64;
            t
        }
    };
    let grounds = [
        ("rough 5 mm", Some(0.005)),
        ("rough 1 cm", Some(0.01)),
        ("rough 2 cm", Some(0.02)),
        ("rough 3 cm", Some(0.03)),
        ("rough 5 cm", Some(0.05)),
        ("rough 10 cm", Some(0.1)),
        ("steps 2 cm to 2 m", None),
    ];
    for (name, sigma) in grounds {
        let mut worst = (0.0f64, 0u64);
        for seed in 1..=100 {
            let terrain = ground(sigma, seed);
            let o = Options {
                terrain,
                t_max: 300.0,
                stop_when_settled: false,
                ..Options::default()
            };
            let mut lowest = f64::INFINITY;
            simulate_traced(&p, &o, &mut |s: &TraceSample| {
                for [x, y] in tip_heights(s, p.length / 2.0) {
                    let under = terrain.ground(x - 1e-6).min(terrain.ground(x + 1e-6));
                    lowest = lowest.min(y - under);
                }
            });
            if lowest < worst.0 {
                worst = (lowest, seed);
            }
        }
        println!("{name}: deepest tip {:.3e} m (seed {})", -worst.0, worst.1);
        assert!(
            worst.0 > -1e-5,
            "{name}: seed {}, {:.3e} m",
            worst.1,
            -worst.0
        );
    }
}
