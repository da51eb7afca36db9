//! Variational equations of any [`HybridSystem`], integrated alongside the
//! motion on the same engine: the state's sensitivity `Φ = ∂y(t)/∂y₀`, carried
//! through every event by its saltation matrix.
//!
//! [`Variational`] wraps a system with an `N`-dimensional state into one with
//! state `[y, Φ]` (`M = N + N·N`, `Φ` row-major). Between events
//!
//! `Φ̇ = A(y) Φ`, `A = ∂f/∂y`,
//!
//! with `A` by central differences of the wrapped system's right-hand side
//! (step `ε^{1/3}` of the component's scale: the difference error, about
//! 1e-10 relative, is far below any integration tolerance used with it). At an
//! event of guard `g` with reset `R` (which may also change the mode, hence
//! the meaning of the state's slots), the sensitivity jumps by the saltation
//! matrix (Hiskens & Pai 2000; Aizerman & Gantmacher 1958):
//!
//! `Φ⁺ = R_y Φ⁻ + (f⁺ − R_y f⁻) (g_y Φ⁻) / (g_y f⁻)`,
//!
//! where `f⁻` is the vector field before the event at `y⁻`, `f⁺` the one after
//! it at `R(y⁻)`, and `R_y`, `g_y` are taken by central differences of the
//! wrapped system's reset (on copies of the system, replaying the discrete
//! choices the reset made at the event: [`HybridSystem::reset_replaying`])
//! and guard. The first term
//! is the reset's own derivative; the second accounts for the event time
//! moving with the initial state.
//!
//! When the reset ends the run (a Poincaré section: the state *at* the event
//! is the result, not the state at a later fixed time), the event-time shift
//! is applied without the flow after it:
//!
//! `Φ⁺ = R_y (I − f⁻ g_y / (g_y f⁻)) Φ⁻`,
//!
//! which is the Jacobian of the map "initial state ↦ state just after the
//! terminal event". (The `f⁺ w` terms of earlier events are shifts along the
//! flow; the flow and every later saltation carry the vector field into the
//! vector field, and this projection removes it: a Poincaré map's Jacobian
//! does not depend on them, only on the `R_y f⁻ w` part.)
//!
//! Whether a reset ends the run is the observer's call (a step map stops at
//! its section), so [`Variational`] carries the wrapped system's observer and
//! asks its [`Observer::on_transition`] at each reset; its
//! [`Observer::on_step`] is not called (the wrapped run only needs the
//! motion and its sensitivity). [`Variational::run`] runs the pair.
//!
//! The wrapped system must be autonomous (`f`, guards and resets not
//! depending on `t`): true of the RTW and the rimless wheel.

use crate::engine::{EngineOptions, RunEnd, run};
use crate::system::{EndsRun, Flow, Guards, HybridSystem, Observer};

/// Relative step of the central differences: `ε^{1/3}`, which balances the
/// truncation error `O(h²)` against rounding `O(ε/h)`.
pub const DIFF_STEP: f64 = 6.055_454_452_393_343e-6;

/// A system `S` with state `y ∈ ℝᴺ` and its sensitivity `Φ ∈ ℝᴺˣᴺ`, as a
/// hybrid system of dimension `M = N + N·N` (checked by
/// [`initial`](Variational::initial)), with the observer `O` that decides
/// where the wrapped run ends. Its transitions are that observer's verdicts.
#[derive(Clone, Debug)]
pub struct Variational<S, O, const N: usize> {
    /// The wrapped system.
    pub sys: S,
    /// The wrapped system's observer (only its transitions are observed).
    pub observer: O,
    /// Scale of each state slot for the difference steps: slot `j` is
    /// perturbed by `DIFF_STEP · max(|y_j|, scale[j])`.
    pub scale: [f64; N],
}

/// Ends a [`Variational`] run where the wrapped observer said so.
struct FollowVerdicts;

impl<S, O, const N: usize, const M: usize> Observer<M, Variational<S, O, N>> for FollowVerdicts
where
    S: HybridSystem<N> + Clone,
    O: Observer<N, S>,
{
    fn reads_interior(&self, _system: &Variational<S, O, N>, _t0: f64, _t1: f64) -> bool {
        false
    }
}

impl<S: HybridSystem<N> + Clone, O: Observer<N, S>, const N: usize> Variational<S, O, N> {
    /// Wraps `sys` watched by `observer`; `scale` as in [`Variational::scale`].
    pub fn new(sys: S, observer: O, scale: [f64; N]) -> Self {
        Self {
            sys,
            observer,
            scale,
        }
    }

    /// Integrates the augmented state `z` (from [`initial`](Self::initial))
    /// from `t0` to `t_end` on the engine ([`run`]), until then
    /// or until a reset the wrapped observer stops at.
    pub fn run<const M: usize>(
        &mut self,
        t0: f64,
        z: &mut [f64; M],
        t_end: f64,
        opts: &EngineOptions,
    ) -> RunEnd {
        run(self, &mut FollowVerdicts, t0, z, t_end, opts)
    }

    /// The augmented initial state `[y, Φ₀]` with `Φ₀ = I`.
    pub fn initial<const M: usize>(y: &[f64; N]) -> [f64; M] {
        assert_eq!(M, N + N * N, "Variational: M must be N + N·N");
        let mut z = [0.0; M];
        z[..N].copy_from_slice(y);
        for i in 0..N {
            z[N + i * N + i] = 1.0;
        }
        z
    }

    /// The state part of an augmented state.
    pub fn state<const M: usize>(z: &[f64; M]) -> [f64; N] {
        std::array::from_fn(|i| z[i])
    }

    /// Entry `Φ[i][j] = ∂y_i/∂y₀_j` of an augmented state.
    #[inline]
    pub fn sensitivity<const M: usize>(z: &[f64; M], i: usize, j: usize) -> f64 {
        z[N + i * N + j]
    }

    #[inline]
    fn step(&self, y: &[f64; N], j: usize) -> f64 {
        DIFF_STEP * y[j].abs().max(self.scale[j])
    }

    /// `A = ∂f/∂y` at `y` by central differences, row-major.
    fn flow_jacobian(&self, t: f64, y: &[f64; N], a: &mut [[f64; N]; N]) {
        let mut yp = *y;
        let (mut fp, mut fm) = ([0.0; N], [0.0; N]);
        for j in 0..N {
            let h = self.step(y, j);
            yp[j] = y[j] + h;
            self.sys.rhs(t, &yp, &mut fp);
            yp[j] = y[j] - h;
            self.sys.rhs(t, &yp, &mut fm);
            yp[j] = y[j];
            for i in 0..N {
                a[i][j] = (fp[i] - fm[i]) / (2.0 * h);
            }
        }
    }

    /// `g_y` of guard `index` at `y` by central differences.
    fn guard_gradient(&self, t: f64, y: &[f64; N], index: usize) -> [f64; N] {
        let mut g = Guards::default();
        let mut yp = *y;
        std::array::from_fn(|j| {
            let h = self.step(y, j);
            yp[j] = y[j] + h;
            self.sys.guards(t, &yp, &mut g);
            let gp = g.value[index];
            yp[j] = y[j] - h;
            self.sys.guards(t, &yp, &mut g);
            let gm = g.value[index];
            yp[j] = y[j];
            (gp - gm) / (2.0 * h)
        })
    }

    /// `R_y` of the reset of guard `index` at `y` by central differences, each
    /// on a fresh copy of the system as it was before the event, replaying the
    /// choices `nominal` made there.
    fn reset_jacobian(&self, t: f64, y: &[f64; N], index: usize, nominal: &S) -> [[f64; N]; N] {
        let mut r = [[0.0; N]; N];
        for j in 0..N {
            let h = self.step(y, j);
            let mut yp = *y;
            yp[j] += h;
            self.sys.clone().reset_replaying(t, &mut yp, index, nominal);
            let mut ym = *y;
            ym[j] -= h;
            self.sys.clone().reset_replaying(t, &mut ym, index, nominal);
            for i in 0..N {
                r[i][j] = (yp[i] - ym[i]) / (2.0 * h);
            }
        }
        r
    }
}

impl<S: HybridSystem<N> + Clone, O: Observer<N, S>, const N: usize, const M: usize> HybridSystem<M>
    for Variational<S, O, N>
{
    type Aux = ();
    type Transition = Flow;

    fn rhs(&self, t: f64, z: &[f64; M], dz: &mut [f64; M]) {
        let y = Self::state(z);
        let mut f = [0.0; N];
        self.sys.rhs(t, &y, &mut f);
        dz[..N].copy_from_slice(&f);
        let mut a = [[0.0; N]; N];
        self.flow_jacobian(t, &y, &mut a);
        // Φ̇ = A Φ, row-major.
        for i in 0..N {
            for j in 0..N {
                let mut s = 0.0;
                for (k, aik) in a[i].iter().enumerate() {
                    s += aik * z[N + k * N + j];
                }
                dz[N + i * N + j] = s;
            }
        }
    }

    fn guards(&self, t: f64, z: &[f64; M], out: &mut Guards) {
        self.sys.guards(t, &Self::state(z), out);
    }

    fn guard(&self, t: f64, z: &[f64; M], index: usize) -> f64 {
        self.sys.guard(t, &Self::state(z), index)
    }

    fn reset(&mut self, t: f64, z: &mut [f64; M], index: usize) -> Flow {
        let y_minus = Self::state(z);
        let mut f_minus = [0.0; N];
        self.sys.rhs(t, &y_minus, &mut f_minus);
        let g_y = self.guard_gradient(t, &y_minus, index);
        let mut after = self.sys.clone();
        let mut y_plus = y_minus;
        let transition = after.reset(t, &mut y_plus, index);
        let verdict = self.observer.on_transition(&after, t, &y_plus, &transition);
        let flow = if transition.ends_run() {
            Flow::Stop
        } else {
            verdict
        };
        let r_y = self.reset_jacobian(t, &y_minus, index, &after);
        self.sys = after;

        // dτ = −(g_y Φ⁻ δ)/(g_y f⁻): the row vector w = g_y Φ⁻ / (g_y f⁻).
        let g_f: f64 = (0..N).map(|k| g_y[k] * f_minus[k]).sum();
        let w: [f64; N] =
            std::array::from_fn(|j| (0..N).map(|k| g_y[k] * z[N + k * N + j]).sum::<f64>() / g_f);
        // Φ⁻ − f⁻ w: the sensitivity at the moving event time, before the reset.
        let mut phi: [[f64; N]; N] =
            std::array::from_fn(|i| std::array::from_fn(|j| z[N + i * N + j] - f_minus[i] * w[j]));
        // R_y (Φ⁻ − f⁻ w)
        let mut out = [[0.0; N]; N];
        for i in 0..N {
            for j in 0..N {
                out[i][j] = (0..N).map(|k| r_y[i][k] * phi[k][j]).sum();
            }
        }
        if flow == Flow::Continue {
            // Back to a fixed time after the event: + f⁺ w.
            let mut f_plus = [0.0; N];
            self.sys.rhs(t, &y_plus, &mut f_plus);
            for i in 0..N {
                for j in 0..N {
                    out[i][j] += f_plus[i] * w[j];
                }
            }
        }
        phi = out;
        z[..N].copy_from_slice(&y_plus);
        for i in 0..N {
            z[N + i * N..N + i * N + N].copy_from_slice(&phi[i]);
        }
        flow
    }
}
