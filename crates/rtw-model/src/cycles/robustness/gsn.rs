//! The gait sensitivity norm (Hobbelen & Wisse, IEEE T-RO 23(6), 2007): how
//! strongly a gait's step-to-step indicators answer a change of floor height
//! (docs/robustness-gsn.md, "The gait sensitivity norm").
//!
//! **The system.** The step map at the gait's fixed point, linearised with
//! the floor height as its input:
//!
//! ```text
//! x_{k+1} = A_k x_k + B_k e_k,    y_k = C_k x_k + D_k e_k,
//! ```
//!
//! `x_k` the deviation of the section point ([`crate::cycles::map::section`])
//! before step `k`, `e_k` the drop of the floor met by step `k`'s landing
//! foot (a step down of `e_k` between the stance foot and where the next
//! foot lands; the floor stays at the lower level from there on), `y_k` the
//! deviations of step `k`'s **step time** `T_k` (section to section) and
//! **step length** `ℓ_k` (the landing foot's advance along the slope). A
//! walking speed is `ℓ/T`, a function of the two, so it adds nothing. All
//! are made dimensionless (lengths in `L`, times in `sqrt(L/g)`, state
//! coordinates in the map's scales), so the norm is too.
//!
//! **The norm.** `GSN = sqrt(Σ_k |y_k|²)` for a unit impulse `e_0 = 1`:
//! `y_0 = D_0`, `x_1 = B_0`, `y_k = C_k x_k`, summed until `|x_k|` has fallen
//! by [`DECAY`] from its largest (the H2 norm of the system from `e` to `y`).
//! A period-`n` gait is time-varying: `A_k … D_k` are those of the orbit's
//! step `k mod n`, and the norm is the root mean square over the `n` phases
//! at which the disturbance can meet the gait (each as likely).
//!
//! **The linearisation.** `A` and `C` by central differences of the map,
//! steps `rel · scale` ([`STATE_REL`], the Floquet column's); `B` and `D` by
//! one-sided differences of the step over a real step down of `ε` and `2ε`
//! (`ε` = [`FLOOR_STEP`] `L`; the terrain of [`crate::plant::terrain`]), to
//! second order: `(4 F(ε) − F(2ε) − 3 F(0)) / 2ε`. One-sided because a step
//! up would put a riser in the landing foot's way. The edge lies a given
//! number of rod lengths ahead of the front-most grounded foot (the largest
//! step down's 0.05 L). NaN when a perturbed step
//! fails or lands in another mode pattern (the map is not smooth there), or
//! when the response does not decay within [`MAX_STEPS`] steps.

use crate::cycles::map::limit_cycle::{DIFFERENCE_REL, RUN_PERIOD_TOL, run_cycle_options};
use crate::cycles::map::section::{SectionLog, SectionPoint};
use crate::cycles::map::stepmap::{CycleOptions, Step, StepMap};
use crate::options::{Options, RobustnessOptions, TerrainOptions};
use crate::outcome::MAX_PERIOD;
use crate::params::Params;
use crate::plant::contact::RodMode;
use crate::plant::rtw::{Rtw, Transition};
use crate::plant::slots::{N, X, Y, at};
use hybrid_ode::limit::{FixedPoint, NewtonError};
use hybrid_ode::{Flow, Observer, Work, limit, run};

use nalgebra::{DMatrix, DVector};

/// Difference step of the state coordinates, relative to each one's scale:
/// the Floquet column's ([`DIFFERENCE_REL`]).
///
/// What limits `A` is the perturbed steps' own error (the integration's and
/// the located events'), divided by the step, and the norm sums powers of
/// `A`: at a step of 1e-6 an orbit moved by 1e-9 of its scale,
/// well within Newton's tolerance, moved the norm of a paper-scan skip by
/// up to 2.5 %. At 1e-4 that error is a hundredth, and the truncation error, of
/// order `rel²`, smaller still (`tests::the_gsn_does_not_move_with_the_orbit_within_its_tolerance`).
/// A map that changes its mode pattern within the step has no norm (NaN).
pub const STATE_REL: f64 = DIFFERENCE_REL;
/// The floor drop of the one-sided differences, in rod lengths.
pub const FLOOR_STEP: f64 = 1e-5;
/// The impulse response is summed until the state deviation has fallen by
/// this factor from its largest.
pub const DECAY: f64 = 1e-9;
/// … or for at most this many steps (NaN when it has not decayed by then).
pub const MAX_STEPS: usize = 200_000;

/// A run's new-foot landings (the section crossings, [`SectionLog`]), with
/// their times and the landing foot's `x`, until `until` of them or, with a
/// `map`, until a period shows on them.
struct Crossings<'a> {
    log: SectionLog,
    landings: Vec<(f64, f64)>,
    until: usize,
    map: Option<&'a StepMap>,
    /// Stop at the first landing with every grounded foot on this level.
    level: Option<f64>,
    failed: bool,
}

impl Observer<N, Rtw> for Crossings<'_> {
    fn on_transition(&mut self, rtw: &Rtw, t: f64, y: &[f64; N], tr: &Transition) -> Flow {
        match *tr {
            Transition::Touchdown { rod, tip, .. } => {
                let before = self.log.count();
                self.log.on_touchdown(&rtw.modes, y, rod, tip);
                if self.log.count() == before {
                    return Flow::Continue;
                }
                self.landings.push((t, y[at(rod, X)]));
                let periodic = self.map.is_some_and(|m| {
                    m.period_of(&self.log.latest(), MAX_PERIOD, RUN_PERIOD_TOL)
                        .is_some()
                });
                let level = self.level.is_some_and(|h| {
                    (0..3).all(|i| rtw.modes[i] == RodMode::Free || y[at(i, Y)] == h)
                });
                if periodic || level || self.landings.len() >= self.until {
                    Flow::Stop
                } else {
                    Flow::Continue
                }
            }
            Transition::ModeChange { .. } => Flow::Continue,
            Transition::Failure(_) => {
                self.failed = true;
                Flow::Stop
            }
        }
    }
}

fn crossings<'a>(rtw: &Rtw, y: &[f64; N], until: usize, map: Option<&'a StepMap>) -> Crossings<'a> {
    // The stance foot now is the front-most grounded one (every stable
    // gait has a foot down at the touchdown its run stopped at).
    let stance = rtw.front_foot(y).map_or(0, |(j, _)| j);
    Crossings {
        log: SectionLog::starting_at(stance),
        landings: Vec::new(),
        until,
        map,
        level: None,
        failed: false,
    }
}

/// The step map on the flat slope and the periodic orbit of the gait a
/// stable flat run settled into, from the state `y` of `rtw` it ended in:
/// the run continued on the flat slope until a period shows on its section
/// crossings, then the fixed point of `Pⁿ` near the last one to the
/// tolerance of the run's `floquet_max`
/// ([`crate::cycles::map::limit_cycle::cycle_of_run`]), by [`orbit_near`].
/// `work` gains the continued run's.
pub(crate) fn settled_cycle(
    params: &Params,
    options: &Options,
    rtw: &Rtw,
    y: &[f64; N],
    work: &mut Work,
) -> Option<(StepMap, Vec<SectionPoint>)> {
    let (map, start, n) = settled_period(params, options, rtw, y, work)?;
    let orbit = orbit_near(&map, &start, n, &run_cycle_options())?;
    Some((map, orbit))
}

/// The step map on the flat slope, the last section crossing of the flat
/// run continued from `y` until a period shows on its crossings, and that
/// period: where [`settled_cycle`] starts its search for the orbit.
fn settled_period(
    params: &Params,
    options: &Options,
    rtw: &Rtw,
    y: &[f64; N],
    work: &mut Work,
) -> Option<(StepMap, SectionPoint, usize)> {
    let mut flat = *options;
    flat.terrain = TerrainOptions::default();
    flat.robustness = RobustnessOptions::default();
    let cycle = run_cycle_options();
    let map = StepMap::new(params, &flat, &cycle);
    let mut sys = rtw.clone();
    sys.set_terrain(flat.terrain, y);
    // Not bounded by the run's `t_max`: a short run's gait may need more
    // steps than it had to show its period.
    let mut obs = crossings(&sys, y, SETTLE_LANDINGS, Some(&map));
    let mut y = *y;
    let horizon = SETTLE_LANDINGS as f64 * map.horizon();
    let end = run(&mut sys, &mut obs, 0.0, &mut y, horizon, &flat.engine());
    *work += end.work;
    if obs.failed {
        return None;
    }
    let hist = obs.log.latest();
    let n = map.period_of(&hist, cycle.max_period, RUN_PERIOD_TOL)?;
    Some((map, *hist.last()?, n))
}

/// Differences of `Pⁿ` the acceleration of the orbit's iteration combines.
const ANDERSON_DEPTH: usize = 6;
/// Most runs of `Pⁿ` the acceleration takes before the chord takes over
/// (a Jacobian by differences costs 2d + 1 ≈ 35).
const ANDERSON_EVALS: u32 = 25;
/// Most times the chord takes a fresh Jacobian where it stopped converging.
const REFRESHES: usize = 2;

/// The period-`n` orbit through the fixed point of `Pⁿ` near `start`, to
/// `cycle`'s Newton tolerance. The norm needs the orbit, not its
/// multipliers: the iteration `z ← Pⁿ(z)` from `start`, accelerated
/// ([`limit::anderson`]), reaches the point in a dozen or so runs of `Pⁿ`,
/// where one Jacobian by differences costs 2d + 1, and it needs no
/// Jacobian at the start (where the chord's can cross into another mode
/// pattern). Where it does not converge, the chord ([`chord_orbit`]).
fn orbit_near(
    map: &StepMap,
    start: &SectionPoint,
    n: usize,
    cycle: &CycleOptions,
) -> Option<Vec<SectionPoint>> {
    let accelerated = limit::anderson(
        &start.coords(),
        &map.coord_scale(start),
        cycle.newton_tol,
        ANDERSON_DEPTH,
        ANDERSON_EVALS,
        |z| power_in_modes(map, &start.with_coords(z), n).map(|q| q.coords()),
    );
    let z = match accelerated {
        Ok(fixed) => fixed.z,
        Err(_) => chord_orbit(map, start, n, cycle)?,
    };
    orbit_through(map, start.with_coords(&z), n)
}

/// `Pⁿ(p)`, where the map is defined and comes back to `p`'s mode pattern
/// (the fixed-point iterations compare the two coordinate by coordinate).
fn power_in_modes(map: &StepMap, p: &SectionPoint, n: usize) -> Option<SectionPoint> {
    let q = map.iterate(p, n).ok()?.last()?.to;
    (q.modes == p.modes).then_some(q)
}

/// The period-`n` orbit through `p`: `p` and its next `n − 1` images.
fn orbit_through(map: &StepMap, p: SectionPoint, n: usize) -> Option<Vec<SectionPoint>> {
    let mut orbit = vec![p];
    orbit.extend(map.iterate(&p, n - 1).ok()?.iter().map(|s| s.to));
    Some(orbit)
}

/// The fixed point of `Pⁿ` near `start` by chord iterations:
/// [`limit::newton`] with `Pⁿ`'s Jacobian computed once, at `start`, and
/// kept, so that each later iterate costs a plain run of the map; from a
/// start the run settled near, the chord gains about three digits an
/// iteration. Where it stops short of the tolerance (multipliers near 1
/// make the kept Jacobian's error contract slowly, or the map fails at an
/// iterate), it starts again from its best iterate with the Jacobian there,
/// at most [`REFRESHES`] times: one Jacobian more, where Newton from the
/// start ([`StepMap::solve`]) takes one at each of its 4 to 7 iterates.
/// `None` where the map already fails at the start or the chord still does
/// not converge.
fn chord_orbit(
    map: &StepMap,
    start: &SectionPoint,
    n: usize,
    cycle: &CycleOptions,
) -> Option<Vec<f64>> {
    let mut from = start.coords();
    for refresh in 0..=REFRESHES {
        let (chord, best) = chord_from(map, start, &from, n, cycle);
        match chord {
            Ok(fixed) => return Some(fixed.z),
            // The map failed at the start itself.
            Err(NewtonError::MapFailed(0)) if refresh == 0 => return None,
            Err(_) => match best {
                Some(z) if z != from => from = z,
                _ => return None,
            },
        }
    }
    None
}

/// One chord iteration towards the fixed point of `Pⁿ`, from the
/// coordinates `from` (in `start`'s modes) with `Pⁿ`'s Jacobian there kept:
/// its result, and its best iterate (the smallest scaled residual).
fn chord_from(
    map: &StepMap,
    start: &SectionPoint,
    from: &[f64],
    n: usize,
    cycle: &CycleOptions,
) -> (Result<FixedPoint, NewtonError>, Option<Vec<f64>>) {
    let scale = map.coord_scale(start);
    let mut kept: Option<DMatrix<f64>> = None;
    let mut best: Option<(Vec<f64>, f64)> = None;
    let chord = limit::newton(from, &scale, cycle.newton_tol, cycle.newton_max_iter, |z| {
        let p = start.with_coords(z);
        let (q, j) = match &kept {
            Some(j) => (power_in_modes(map, &p, n)?, j.clone()),
            None => {
                let (q, j) = map.power_with_jacobian(&p, n, cycle.jacobian)?;
                kept = Some(j.clone());
                (q, j)
            }
        };
        let r = limit::scaled_max(&q.coords(), z, &scale);
        if best.as_ref().is_none_or(|b| r < b.1) {
            best = Some((z.to_vec(), r));
        }
        Some((q.coords(), j))
    });
    (chord, best.map(|(z, _)| z))
}

/// The step map linearised at one point of the orbit, in scaled
/// coordinates (see the module doc): `A`, `C` of its step, and the response
/// to a floor drop met by it, differentiated on the full simulation over the
/// `m` steps until every grounded foot is on the lower floor: `d` the
/// indicators of those steps, `b` the state after them.
#[derive(Clone, Debug)]
pub(crate) struct Linearised {
    pub a: DMatrix<f64>,
    pub c: DMatrix<f64>,
    pub b: DVector<f64>,
    pub d: DVector<f64>,
    pub m: usize,
}

/// The scaled indicators (step time, step length) of a step of `time` (s)
/// and `advance` (m).
fn indicators(map: &StepMap, time: f64, advance: f64) -> [f64; 2] {
    let (l, tu) = map.units();
    [time / tu, advance / l]
}

/// The scaled coordinates of `q`, in the scales of `like` (same modes).
fn scaled(map: &StepMap, q: &SectionPoint, like: &SectionPoint) -> Option<Vec<f64>> {
    (q.modes == like.modes).then(|| {
        let scale = map.coord_scale(like);
        q.coords().iter().zip(&scale).map(|(v, s)| v / s).collect()
    })
}

/// The full simulation from `p` over a floor that drops by `h` rod lengths
/// at `edge_ahead` rod lengths beyond its front-most grounded foot, for `m`
/// new-foot landings (or, with `m = None`, until every grounded foot is on
/// the lower floor): the steps taken, then the state after them (canonical,
/// lifted back by the drop, so on the flat map's section) in the scales of
/// `like`, then the indicators of each step.
fn over_step(
    map: &StepMap,
    p: &SectionPoint,
    like: &[SectionPoint],
    h: f64,
    edge_ahead: f64,
    m: Option<usize>,
) -> Option<(usize, DVector<f64>)> {
    let (l, _) = map.units();
    let (mut rtw, engine) = map.plant_at(p);
    let front = rtw.front_foot(&p.y).map_or(0.0, |(_, x)| x);
    rtw.set_terrain(TerrainOptions::step(h * l, front + edge_ahead * l), &p.y);
    let mut obs = crossings(&rtw, &p.y, m.unwrap_or(MAX_STEPS_OVER), None);
    if m.is_none() {
        obs.level = Some(rtw.terrain.ground(f64::INFINITY));
    }
    let mut y = p.y;
    let horizon = map.horizon() * MAX_STEPS_OVER as f64;
    run(&mut rtw, &mut obs, 0.0, &mut y, horizon, &engine);
    let steps = obs.landings.len();
    if obs.failed || m.is_some_and(|m| m != steps) || steps == 0 || steps >= MAX_STEPS_OVER {
        return None;
    }
    let mut q = *obs.log.latest().last()?;
    for i in 0..3 {
        q.y[at(i, Y)] += h * l;
    }
    let mut out = scaled(map, &q, &like[steps % like.len()])?;
    let mut last = (0.0, 0.0);
    for &(t, x) in &obs.landings {
        out.extend(indicators(map, t - last.0, x - last.1));
        last = (t, x);
    }
    Some((steps, DVector::from_vec(out)))
}

/// Most landings the flat run is continued for until a period shows.
const SETTLE_LANDINGS: usize = 200;

/// Most steps a floor drop is followed on the full simulation.
const MAX_STEPS_OVER: usize = 2 * MAX_PERIOD;

/// The linearisation at point `j` of the periodic `orbit`; `None` if a
/// perturbed run fails or lands in another mode pattern.
pub(crate) fn linearise(
    map: &StepMap,
    orbit: &[SectionPoint],
    j: usize,
    edge_ahead: f64,
) -> Option<Linearised> {
    let p = &orbit[j];
    let next = &orbit[(j + 1) % orbit.len()];
    let z = p.coords();
    let scale = map.coord_scale(p);
    let rows = next.coords().len();
    let outputs = |s: Step| {
        let mut v = scaled(map, &s.to, next)?;
        v.extend(indicators(map, s.time, s.advance));
        Some(DVector::from_vec(v))
    };
    let mut ac = DMatrix::zeros(rows + 2, z.len());
    let mut zp = z.clone();
    for k in 0..z.len() {
        let h = STATE_REL * scale[k];
        zp[k] = z[k] + h;
        let plus = outputs(map.step(&p.with_coords(&zp)).ok()?)?;
        zp[k] = z[k] - h;
        let minus = outputs(map.step(&p.with_coords(&zp)).ok()?)?;
        zp[k] = z[k];
        ac.set_column(k, &((plus - minus) / (2.0 * STATE_REL)));
    }
    // The rest of the orbit, from p on: the points the drop's run ends near.
    let like: Vec<SectionPoint> = (0..orbit.len())
        .map(|i| orbit[(j + i) % orbit.len()])
        .collect();
    let (m, f1) = over_step(map, p, &like, FLOOR_STEP, edge_ahead, None)?;
    let (_, f2) = over_step(map, p, &like, 2.0 * FLOOR_STEP, edge_ahead, Some(m))?;
    let (_, f0) = over_step(map, p, &like, 0.0, edge_ahead, Some(m))?;
    let bd = (f1 * 4.0 - f2 - f0 * 3.0) / (2.0 * FLOOR_STEP);
    let rows_m = bd.len() - 2 * m;
    Some(Linearised {
        a: ac.rows(0, rows).into_owned(),
        c: ac.rows(rows, 2).into_owned(),
        b: bd.rows(0, rows_m).into_owned(),
        d: bd.rows(rows_m, 2 * m).into_owned(),
        m,
    })
}

/// The H2 norm from `e` to `y` of the periodic system whose steps are
/// `phases` (the orbit's, in order): the root mean square over the phases
/// of `sqrt(Σ_k |y_k|²)` for a unit impulse there; NaN when a response has
/// not decayed by [`DECAY`] within [`MAX_STEPS`] steps.
pub(crate) fn h2_norm(phases: &[Linearised]) -> f64 {
    let n = phases.len();
    let total: Option<f64> = (0..n).map(|j| impulse_response(phases, j)).sum();
    total.map_or(f64::NAN, |t| (t / n as f64).sqrt())
}

/// `Σ_k |y_k|²` for a unit impulse at phase `j` of `phases`; `None` when it
/// has not decayed by [`DECAY`] within [`MAX_STEPS`] steps.
pub(crate) fn impulse_response(phases: &[Linearised], j: usize) -> Option<f64> {
    let n = phases.len();
    let mut sum = phases[j].d.norm_squared();
    let mut x = phases[j].b.clone();
    let mut largest = 0.0f64;
    let mut k = (j + phases[j].m) % n;
    for _ in 0..MAX_STEPS {
        let size = x.norm();
        if !size.is_finite() {
            return None;
        }
        largest = largest.max(size);
        if size <= DECAY * largest {
            return Some(sum);
        }
        sum += (&phases[k].c * &x).norm_squared();
        x = &phases[k].a * &x;
        k = (k + 1) % n;
    }
    None
}

/// The gait sensitivity norm of the periodic `orbit` of `map` (its section
/// points in order), the step's edge `edge_ahead` rod lengths ahead of the
/// front-most grounded foot (see the module doc).
pub(crate) fn gsn(map: &StepMap, orbit: &[SectionPoint], edge_ahead: f64) -> f64 {
    let phases: Option<Vec<_>> = (0..orbit.len())
        .map(|j| linearise(map, orbit, j, edge_ahead))
        .collect();
    phases.map_or(f64::NAN, |ph| h2_norm(&ph))
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::run::recorder::with_end_state;
    /// The step's edge ahead of the front-most grounded foot, in rod
    /// lengths: the largest step down's (run/robustness.rs).
    const EDGE_AHEAD: f64 = 0.05;
    use hybrid_ode::EngineOptions;

    /// The step map and periodic orbit the stable gait `params` settles into at
    /// the default model, as the GSN finds it after a scan's run (the tests of
    /// the GSN and of the Floquet column).
    pub(crate) fn settled_orbit(params: &Params) -> (StepMap, Vec<SectionPoint>) {
        let options = Options::default();
        with_end_state(params, &options, |_, rtw, y, flat| {
            assert!(flat.label.is_stable(), "{:?}", flat.label);
            settled_cycle(params, &options, rtw, y, &mut Work::default()).expect("a limit cycle")
        })
        .expect("the star stands")
    }

    /// The new-foot landings (time, landing foot's `x`) of `rtw` run from `y`
    /// for at most `t_max` seconds or `until` landings, or `None` if it fails.
    fn landings(
        rtw: &Rtw,
        y: &[f64; N],
        t_max: f64,
        until: usize,
        engine: &EngineOptions,
    ) -> Option<Vec<(f64, f64)>> {
        let mut obs = crossings(rtw, y, until, None);
        let (mut rtw, mut y) = (rtw.clone(), *y);
        run(&mut rtw, &mut obs, 0.0, &mut y, t_max, engine);
        (!obs.failed).then_some(obs.landings)
    }

    /// The full simulation's response to a real step of `eps` rod lengths
    /// met by the gait at the fixed point: `Σ_k |Δy_k / ε|²` over `steps`
    /// steps, `Δy_k` the step time and length (in `sqrt(L/g)` and `L`)
    /// against the same run on the flat slope.
    fn simulated_response(map: &StepMap, orbit: &[SectionPoint], eps: f64, steps: usize) -> f64 {
        let p = &orbit[0];
        let (l, tu) = map.units();
        let (rtw, engine) = map.plant_at(p);
        let t_max = 2.0 * steps as f64 * map.step(p).unwrap().time;
        let flat = landings(&rtw, &p.y, t_max, steps + 1, &engine).unwrap();
        let mut stepped = rtw.clone();
        let front = rtw.front_foot(&p.y).unwrap().1;
        stepped.set_terrain(TerrainOptions::step(eps * l, front + EDGE_AHEAD * l), &p.y);
        let over = landings(&stepped, &p.y, t_max, steps + 1, &engine).unwrap();
        assert_eq!((flat.len(), over.len()), (steps + 1, steps + 1));
        let with_start = |v: &[(f64, f64)]| {
            let mut w = vec![(0.0, 0.0)];
            w.extend_from_slice(v);
            w
        };
        let (flat, over) = (with_start(&flat), with_start(&over));
        // 200 steps: the flat gait's multipliers (at most 0.83) have taken
        // the response below 1e-16 of its start.
        (0..steps)
            .map(|k| {
                let dt = (over[k + 1].0 - over[k].0) - (flat[k + 1].0 - flat[k].0);
                let dl = (over[k + 1].1 - over[k].1) - (flat[k + 1].1 - flat[k].1);
                (dt / tu / eps).powi(2) + (dl / l / eps).powi(2)
            })
            .sum()
    }

    #[test]
    fn the_gsn_is_the_full_simulations_response_to_a_small_step() {
        let (map, orbit) = settled_orbit(&Params::fig7a());
        let phases: Vec<_> = (0..orbit.len())
            .map(|j| linearise(&map, &orbit, j, EDGE_AHEAD).unwrap())
            .collect();
        let linear = impulse_response(&phases, 0).unwrap().sqrt();
        assert_eq!(orbit.len(), 1);
        assert!((linear - gsn(&map, &orbit, EDGE_AHEAD)).abs() < 1e-12);
        let rel: Vec<f64> = [1e-3, 1e-4]
            .iter()
            .map(|&eps| {
                let simulated = simulated_response(&map, &orbit, eps, 200).sqrt();
                eprintln!(
                    "Fig. 7(a): GSN {linear:.6}, simulated over a step of {eps} L {simulated:.6}"
                );
                (simulated - linear).abs() / linear
            })
            .collect();
        // What is left is the response's nonlinearity, of order ε: it falls
        // with ε (2.2e-3 at 1e-3 L, 2.0e-4 at 1e-4 L when written), and at
        // 1e-4 L is within 1e-3.
        assert!(rel[1] < 1e-3 && rel[1] < rel[0] / 3.0, "{rel:?}");
    }

    /// The step map, the flat run's last crossing and the period that
    /// [`settled_cycle`] starts from.
    fn start_of(params: &Params) -> (StepMap, SectionPoint, usize) {
        let options = Options::default();
        with_end_state(params, &options, |_, rtw, y, _| {
            settled_period(params, &options, rtw, y, &mut Work::default())
        })
        .unwrap()
        .expect("a period shows")
    }

    /// `orbit` is `Pⁿ`'s fixed point that Newton finds from `start`, and
    /// periodic to the tolerance. Two points whose residuals are within the
    /// tolerance `tol` lie within `2 tol ‖(I − J)⁻¹‖` of each other (scaled,
    /// max norms; `J` Newton's Jacobian of `Pⁿ`): a gait with a multiplier
    /// near 1 is pinned down less tightly by the same residual.
    fn assert_newtons(map: &StepMap, start: &SectionPoint, orbit: &[SectionPoint]) {
        let cycle = run_cycle_options();
        let n = orbit.len();
        let newton = map.solve(start, n, &cycle).unwrap();
        let scale = map.coord_scale(start);
        let j = &newton.fixed_point.jacobian;
        let d = j.nrows();
        let inverse = (DMatrix::<f64>::identity(d, d) - j).try_inverse().unwrap();
        let spread = (0..d)
            .map(|r| {
                (0..d)
                    .map(|c| (inverse[(r, c)] * scale[c] / scale[r]).abs())
                    .sum::<f64>()
            })
            .fold(0.0, f64::max);
        let bound = 2.0 * cycle.newton_tol * spread;
        for (a, b) in orbit.iter().zip(&newton.orbit) {
            let dist = limit::scaled_max(&a.coords(), &b.coords(), &scale);
            assert!(dist <= bound, "{dist} > {bound}");
        }
        let back = map.iterate(&orbit[0], n).unwrap().last().unwrap().to;
        let r = limit::scaled_max(&back.coords(), &orbit[0].coords(), &scale);
        assert!(r <= cycle.newton_tol, "{r}");
    }

    /// The accelerated iteration lands on Newton's fixed point from the
    /// same crossing, to within what the tolerance allows: for the Fig. 7(a) walk, the paper-scan skip of the
    /// robustness tests (two touchdowns a step) and the period-2 skip 432.
    #[test]
    fn the_orbit_is_newtons_fixed_point() {
        for params in [
            Params::fig7a(),
            crate::tests::two_touchdown_skip(),
            crate::tests::skip_432(),
        ] {
            let (map, start, n) = start_of(&params);
            let orbit = orbit_near(&map, &start, n, &run_cycle_options()).unwrap();
            assert_newtons(&map, &start, &orbit);
        }
    }

    /// Skip 432's chord from the run's last crossing does not reach the
    /// tolerance in its 12 iterations: started again from its best iterate
    /// with the Jacobian there, it lands on Newton's fixed point.
    #[test]
    fn a_chord_that_stalls_starts_again_with_a_fresh_jacobian_and_lands_on_newtons_point() {
        let (map, start, n) = start_of(&crate::tests::skip_432());
        assert_eq!(n, 2);
        let cycle = run_cycle_options();
        let (first, _) = chord_from(&map, &start, &start.coords(), n, &cycle);
        assert!(
            matches!(first, Err(NewtonError::NoConvergence { .. })),
            "{first:?}"
        );
        let z = chord_orbit(&map, &start, n, &cycle).expect("the chord started again");
        let orbit = orbit_through(&map, start.with_coords(&z), n).unwrap();
        assert_newtons(&map, &start, &orbit);
    }

    /// The norm is a property of the gait, not of where within Newton's
    /// tolerance its orbit was found: moved by 1e-9 of a coordinate's scale
    /// (a tenth of the tolerance) in each of three coordinates, the orbit
    /// of skip 432 and of Fig. 7(a) gives the same norm within 1e-3. (With
    /// a difference step of 1e-6, skip 432's moved by up
    /// to 2.5 %: 17.94 to 17.89, 17.93 and 17.49.)
    #[test]
    fn the_gsn_does_not_move_with_the_orbit_within_its_tolerance() {
        for params in [crate::tests::skip_432(), Params::fig7a()] {
            let (map, orbit) = settled_orbit(&params);
            let at = gsn(&map, &orbit, EDGE_AHEAD);
            let scale = map.coord_scale(&orbit[0]);
            for k in [0, 3, 7] {
                let mut z = orbit[0].coords();
                z[k] += 1e-9 * scale[k];
                let moved = orbit_through(&map, orbit[0].with_coords(&z), orbit.len()).unwrap();
                let there = gsn(&map, &moved, EDGE_AHEAD);
                assert!((there - at).abs() <= 1e-3 * at, "{k}: {at} {there}");
            }
        }
    }

    /// McGeer's rimless wheel (docs/robustness-gsn.md): state (θ⁺, ω⁺) after an
    /// impact, indicator the rate after the next impact (its speed), input
    /// the drop met by the next landing. Its linearisation at the fixed
    /// point is in closed form, and so is its impulse response: `y_0 = b`,
    /// `y_k = c^{2(k−1)} r` with `r = a_θ δ' + c² b`, so
    /// `GSN² = b² + r² / (1 − c⁴)`.
    #[test]
    fn the_h2_norm_of_the_rimless_wheels_step_map_is_its_closed_form() {
        let (g, l, alpha, gamma) = (9.81, 1.0, std::f64::consts::PI / 8.0, 0.08f64);
        let c2 = (2.0 * alpha).cos().powi(2);
        let w = (4.0 * (g / l) * alpha.sin() * gamma.sin()).sqrt() / (2.0 * alpha).tan();
        let d_delta = 1.0 / (2.0 * l * alpha.sin());
        let a_theta = -c2 * (g / l) * (gamma - alpha).sin() / w;
        let b = c2 * (g / l) * (gamma + alpha).sin() * d_delta / w;
        let lin = Linearised {
            a: DMatrix::from_row_slice(2, 2, &[0.0, 0.0, a_theta, c2]),
            b: DVector::from_column_slice(&[d_delta, b]),
            c: DMatrix::from_row_slice(1, 2, &[a_theta, c2]),
            d: DVector::from_column_slice(&[b]),
            m: 1,
        };
        let r = a_theta * d_delta + c2 * b;
        let closed = (b * b + r * r / (1.0 - c2 * c2)).sqrt();
        let norm = h2_norm(std::slice::from_ref(&lin));
        assert!((norm - closed).abs() <= 1e-12 * closed, "{norm} {closed}");
        // As a period-2 system of two equal steps, the same.
        assert!((h2_norm(&[lin.clone(), lin]) - closed).abs() <= 1e-12 * closed);
    }
}
