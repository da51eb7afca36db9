//! The corrector keeps the last point's Jacobian through its iterations
//! (they need only the map's value) and evaluates the derivatives once per
//! accepted point: for a step map whose Jacobian comes from variational
//! equations that is most of a branch's cost. The branch is the same to the
//! corrector's tolerance.

use hybrid_ode::continuation::*;
use nalgebra::{Complex, DMatrix};

fn eig(j: &DMatrix<f64>) -> Vec<Complex<f64>> {
    j.complex_eigenvalues().iter().copied().collect()
}

/// The logistic map x ↦ r x (1 − x), counting its evaluations with and
/// without derivatives.
#[derive(Default)]
struct Counted {
    full: usize,
    values: usize,
}

impl ParamMap for Counted {
    fn eval(&mut self, z: &[f64], r: f64) -> Option<MapEval> {
        self.full += 1;
        let x = z[0];
        Some(MapEval {
            value: vec![r * x * (1.0 - x)],
            dz: DMatrix::from_element(1, 1, r * (1.0 - 2.0 * x)),
            dp: vec![x * (1.0 - x)],
        })
    }

    fn value(&mut self, z: &[f64], r: f64) -> Option<Vec<f64>> {
        self.values += 1;
        Some(vec![r * z[0] * (1.0 - z[0])])
    }
}

#[test]
fn a_branch_costs_about_one_derivative_evaluation_per_point_and_keeps_its_accuracy() {
    let opts = Options {
        p_max: 3.3,
        ds: 0.05,
        ..Options::default()
    };
    let mut map = Counted::default();
    let b = continue_branch(&mut map, &[0.4], 2.0, 1.0, &opts, &eig).unwrap();
    for pt in &b.points {
        assert!((pt.z[0] - (1.0 - 1.0 / pt.p)).abs() < 1e-10, "{pt:?}");
    }
    assert_eq!(b.bifurcations.len(), 1);
    assert!((b.bifurcations[0].point.p - 3.0).abs() < 1e-8);
    // The start's Newton, one full evaluation per accepted point and per
    // iterate of the period doubling's location; Newton at every iterate
    // would take two or more per point.
    let points = b.points.len();
    assert!(points > 10);
    assert!(
        map.full <= points + 10,
        "{} full evaluations for {points} points",
        map.full
    );
    assert!(map.values >= points, "{} values", map.values);
}
