//! The continuation against maps whose branches and bifurcations are known
//! in closed form.

use hybrid_ode::continuation::*;
use nalgebra::{Complex, DMatrix};

fn eig(j: &DMatrix<f64>) -> Vec<Complex<f64>> {
    let mut mu: Vec<Complex<f64>> = j.complex_eigenvalues().iter().copied().collect();
    mu.sort_by(|a, b| b.norm().total_cmp(&a.norm()).then(b.im.total_cmp(&a.im)));
    mu
}

/// The logistic map x ↦ r x (1 − x).
fn logistic(z: &[f64], r: f64) -> Option<MapEval> {
    let x = z[0];
    Some(MapEval {
        value: vec![r * x * (1.0 - x)],
        dz: DMatrix::from_element(1, 1, r * (1.0 - 2.0 * x)),
        dp: vec![x * (1.0 - x)],
    })
}

#[test]
fn the_logistic_maps_first_period_doubling_is_at_r_3_and_its_period_2_branch_is_the_closed_form() {
    let opts = Options {
        p_max: 3.3,
        ds: 0.05,
        ..Options::default()
    };
    let mut map = logistic;
    let b = continue_branch(&mut map, &[0.4], 2.0, 1.0, &opts, &eig).unwrap();
    // Fixed points x* = 1 − 1/r with multiplier 2 − r.
    for pt in &b.points {
        assert!((pt.z[0] - (1.0 - 1.0 / pt.p)).abs() < 1e-10, "{pt:?}");
        assert!((pt.multipliers[0].re - (2.0 - pt.p)).abs() < 1e-9);
        assert_eq!(pt.stable, pt.p < 3.0);
    }
    assert_eq!(b.end, End::ParameterRange);
    assert_eq!(b.bifurcations.len(), 1, "{:?}", b.bifurcations);
    let pd = &b.bifurcations[0];
    assert_eq!(pd.kind, Kind::PeriodDoubling);
    // Located to locate_tol in arclength: |Δr| ≤ that (dr/ds ≤ 1).
    assert!((pd.point.p - 3.0).abs() < 1e-8, "{}", pd.point.p);
    // Onto the period-2 branch: x = ((r + 1) ± sqrt((r + 1)(r − 3))) / (2r),
    // stable until its own period doubling at r = 1 + √6.
    let opts2 = Options {
        p_max: 3.5,
        ds_max: 0.02,
        ..opts.clone()
    };
    let (two, _) = switch_period_doubling(logistic, pd, 1.0, &opts2, &eig).unwrap();
    assert!(two.points.len() > 10);
    for pt in &two.points {
        let r = pt.p;
        assert!(r > 3.0 - 1e-9, "the branch is born supercritical: r ≥ 3");
        let d = ((r + 1.0) * (r - 3.0)).max(0.0).sqrt();
        let closest = [((r + 1.0) + d) / (2.0 * r), ((r + 1.0) - d) / (2.0 * r)]
            .iter()
            .map(|x| (x - pt.z[0]).abs())
            .fold(f64::INFINITY, f64::min);
        assert!(
            closest < 1e-8,
            "r {r}: x {} off the closed form by {closest}",
            pt.z[0]
        );
    }
    let pd2: Vec<_> = two
        .bifurcations
        .iter()
        .filter(|b| b.kind == Kind::PeriodDoubling)
        .collect();
    assert_eq!(pd2.len(), 1, "{:?}", two.bifurcations);
    assert!(
        (pd2[0].point.p - (1.0 + 6f64.sqrt())).abs() < 1e-8,
        "{}",
        pd2[0].point.p
    );
}

#[test]
fn a_fold_is_located_and_the_branch_goes_on_unstable_past_it() {
    // z ↦ z + (p − z²)/2: fixed points p = z², multiplier 1 − z; a fold at
    // (z, p) = (0, 0); stable for z > 0, unstable for z < 0.
    let mut map = |z: &[f64], p: f64| {
        Some(MapEval {
            value: vec![z[0] + 0.5 * (p - z[0] * z[0])],
            dz: DMatrix::from_element(1, 1, 1.0 - z[0]),
            dp: vec![0.5],
        })
    };
    let opts = Options {
        p_max: 1.5,
        ds: 0.1,
        max_points: 200,
        ..Options::default()
    };
    let b = continue_branch(&mut map, &[1.0], 1.0, -1.0, &opts, &eig).unwrap();
    let folds: Vec<_> = b
        .bifurcations
        .iter()
        .filter(|b| b.kind == Kind::Fold)
        .collect();
    assert_eq!(folds.len(), 1, "{:?}", b.bifurcations);
    assert!(
        folds[0].point.p.abs() < 1e-12 && folds[0].point.z[0].abs() < 1e-8,
        "{:?}",
        folds[0].point
    );
    // Past the fold the branch comes back up in p on the unstable side.
    let last = b.points.last().unwrap();
    assert_eq!(b.end, End::ParameterRange);
    assert!(last.z[0] < -1.0 && !last.stable);
    for pt in &b.points {
        assert!((pt.p - pt.z[0] * pt.z[0]).abs() < 1e-9);
        assert_eq!(pt.stable, pt.z[0] > 0.0 && pt.z[0] < 2.0);
    }
}

#[test]
fn the_delayed_logistic_maps_neimark_sacker_is_at_r_2() {
    // (x, y) ↦ (r x (1 − y), x): fixed point x = y = 1 − 1/r; its
    // multipliers are the roots of μ² − μ + (r − 1) = 0, a complex pair of
    // modulus √(r − 1): on the unit circle at r = 2.
    let mut map = |z: &[f64], r: f64| {
        let (x, y) = (z[0], z[1]);
        Some(MapEval {
            value: vec![r * x * (1.0 - y), x],
            dz: DMatrix::from_row_slice(2, 2, &[r * (1.0 - y), -r * x, 1.0, 0.0]),
            dp: vec![x * (1.0 - y), 0.0],
        })
    };
    let opts = Options {
        p_max: 2.2,
        ds: 0.05,
        ..Options::default()
    };
    let b = continue_branch(&mut map, &[0.5, 0.5], 1.5, 1.0, &opts, &eig).unwrap();
    let ns: Vec<_> = b
        .bifurcations
        .iter()
        .filter(|b| b.kind == Kind::NeimarkSacker)
        .collect();
    assert_eq!(ns.len(), 1, "{:?}", b.bifurcations);
    assert!((ns[0].point.p - 2.0).abs() < 1e-8, "{}", ns[0].point.p);
    assert!(b.bifurcations.iter().all(|b| b.kind == Kind::NeimarkSacker));
}

#[test]
fn the_period_doubling_curve_of_the_shifted_logistic_map_is_the_closed_form() {
    // x ↦ r x (1 − x) + c: a period doubling where r (1 − 2x) = −1 on the
    // fixed point, i.e. x = (r + 1)/(2r) and c = (r + 1)(3 − r)/(4r).
    let map2 = |z: &[f64], p: [f64; 2]| {
        let (x, r, c) = (z[0], p[0], p[1]);
        Some(PlaneMapEval {
            value: vec![r * x * (1.0 - x) + c],
            dz: DMatrix::from_element(1, 1, r * (1.0 - 2.0 * x)),
            dp: [vec![x * (1.0 - x)], vec![1.0]],
        })
    };
    // Locate the c = 0 period doubling by one-parameter continuation first.
    let opts = Options {
        p_max: 3.3,
        ds: 0.05,
        ..Options::default()
    };
    let mut map = |z: &[f64], r: f64| {
        let e = map2(z, [r, 0.0])?;
        Some(MapEval {
            value: e.value,
            dz: e.dz,
            dp: e.dp[0].clone(),
        })
    };
    let b = continue_branch(&mut map, &[0.4], 2.0, 1.0, &opts, &eig).unwrap();
    let pd = &b.bifurcations[0];
    let opts2 = CurveOptions {
        base: Options {
            p_min: 2.0,
            p_max: 4.0,
            ds_max: 0.05,
            ..Options::default()
        },
        p2_range: (-0.5, 0.5),
        p2_scale: 1.0,
        fd_step: 1e-6,
    };
    for dir in [1.0, -1.0] {
        let curve = continue_curve(map2, pd, 0.0, dir, &opts2, &eig).unwrap();
        assert_eq!(curve.end, End::ParameterRange, "{:?}", curve.points.last());
        assert!(curve.points.len() > 5);
        for pt in &curve.points {
            let [r, c] = pt.p;
            assert!(
                (c - (r + 1.0) * (3.0 - r) / (4.0 * r)).abs() < 1e-9,
                "r {r} c {c}"
            );
            assert!((pt.z[0] - (r + 1.0) / (2.0 * r)).abs() < 1e-9);
            assert!((pt.multipliers[0].re + 1.0).abs() < 1e-8);
        }
    }
}

#[test]
fn the_fold_curve_of_a_two_parameter_map_is_the_closed_form() {
    // z ↦ z + (p₁ − z² + p₂ z)/2: fixed points p₁ = z² − p₂ z, a fold where
    // 2z = p₂, on the curve p₁ = −p₂²/4.
    let map2 = |z: &[f64], p: [f64; 2]| {
        let x = z[0];
        Some(PlaneMapEval {
            value: vec![x + 0.5 * (p[0] - x * x + p[1] * x)],
            dz: DMatrix::from_element(1, 1, 1.0 + 0.5 * (p[1] - 2.0 * x)),
            dp: [vec![0.5], vec![0.5 * x]],
        })
    };
    let mut map = |z: &[f64], p1: f64| {
        let e = map2(z, [p1, 0.0])?;
        Some(MapEval {
            value: e.value,
            dz: e.dz,
            dp: e.dp[0].clone(),
        })
    };
    let opts = Options {
        p_max: 1.5,
        ds: 0.1,
        ..Options::default()
    };
    let b = continue_branch(&mut map, &[1.0], 1.0, -1.0, &opts, &eig).unwrap();
    let fold = b
        .bifurcations
        .iter()
        .find(|b| b.kind == Kind::Fold)
        .unwrap();
    let opts2 = CurveOptions {
        base: Options {
            ds_max: 0.05,
            ..Options::default()
        },
        p2_range: (-1.0, 1.0),
        p2_scale: 1.0,
        fd_step: 1e-6,
    };
    let curve = continue_curve(map2, fold, 0.0, 1.0, &opts2, &eig).unwrap();
    assert_eq!(curve.end, End::ParameterRange);
    for pt in &curve.points {
        let [p1, p2] = pt.p;
        assert!((p1 + p2 * p2 / 4.0).abs() < 1e-9, "p1 {p1} p2 {p2}");
        assert!((pt.z[0] - p2 / 2.0).abs() < 1e-7);
    }
}

#[test]
fn the_rimless_wheels_branch_and_its_existence_limit_in_the_slope_are_the_closed_form() {
    use hybrid_ode::EngineOptions;
    use hybrid_ode::Method;
    use hybrid_ode::rimless::RimlessWheel;
    // McGeer's wheel, 8 spokes, l = 1 m: the fixed point of the post-impact
    // rate is ω*(γ) = cot 2α · sqrt(4 (g/l) sin α sin γ) with multiplier
    // cos² 2α whatever γ (so no fold): the branch ends where the fixed-point
    // wheel no longer passes the apex, ω*² = 2 (g/l)(1 − cos(α − γ)).
    let (n, l, g) = (8, 1.0, 9.81);
    let engine = EngineOptions {
        method: Method::Dop853,
        rtol: 1e-12,
        atol: 1e-12,
        ..EngineOptions::default()
    };
    let mut map = |z: &[f64], gamma: f64| {
        let (p, slope) =
            RimlessWheel::with_spokes(n, l, gamma, g).step_map_with_slope(z[0], &engine)?;
        let h = 1e-6;
        let plus = RimlessWheel::with_spokes(n, l, gamma + h, g).step_map(z[0], &engine)?;
        let minus = RimlessWheel::with_spokes(n, l, gamma - h, g).step_map(z[0], &engine)?;
        Some(MapEval {
            value: vec![p],
            dz: DMatrix::from_element(1, 1, slope),
            dp: vec![(plus - minus) / (2.0 * h)],
        })
    };
    let start = RimlessWheel::with_spokes(n, l, 0.1, g);
    let opts = Options {
        p_min: 0.0,
        ds: 0.02,
        ds_max: 0.05,
        ds_min: 1e-7,
        tol: 1e-9,
        ..Options::default()
    };
    let b = continue_branch(&mut map, &[start.omega_star()], 0.1, -1.0, &opts, &eig).unwrap();
    let cos2 = (2.0 * start.alpha).cos().powi(2);
    // The existence limit, by bisection on the closed forms.
    let exists = |gamma: f64| {
        let w = RimlessWheel::with_spokes(n, l, gamma, g);
        w.omega_star().powi(2) > w.apex_rate_sq()
    };
    let (mut lo, mut hi) = (1e-6, 0.1);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if exists(mid) { hi = mid } else { lo = mid }
    }
    for pt in &b.points {
        let w = RimlessWheel::with_spokes(n, l, pt.p, g);
        assert!(
            (pt.z[0] - w.omega_star()).abs() < 1e-8,
            "γ {}: ω {} vs {}",
            pt.p,
            pt.z[0],
            w.omega_star()
        );
        // Within 1e-4 of the limit the stance creeps over the apex for ever
        // longer and the variational derivative loses digits (1e-6 there,
        // 1e-10 elsewhere).
        let tol = if pt.p - hi > 1e-4 { 1e-8 } else { 1e-5 };
        let mu = pt.multipliers[0].re;
        assert!((mu - cos2).abs() < tol, "γ {}: μ {mu} vs {cos2}", pt.p);
        assert!(pt.stable);
    }
    assert!(b.bifurcations.is_empty(), "{:?}", b.bifurcations);
    assert_eq!(b.end, End::StepTooSmall);
    let last = b.points.last().unwrap().p;
    assert!(
        last >= hi - 1e-12 && last - hi < 1e-4,
        "the branch ends at γ {last}, the limit is {hi}"
    );
}
