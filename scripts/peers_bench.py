"""The peer benchmark's driver (run by scripts/peers_bench.sh in .venv-peers):
heyoka and diffrax on the bouncing ball, the rimless wheel and the impact
oscillator near grazing, beside rtw's
own figures (hybrid-ode's `peers` example, whose JSON lines it reads), all
scored against the same closed forms; writes results/bench/peers.md.

python scripts/peers_bench.py RTW_JSON OUT_MD [--n N] [--reps R] [--quick]

The ball and the wheel run to their 10th impact, the oscillator to its first
(the one with a closed form). Time per trajectory is the median
over R repetitions of (wall time of all N trajectories) / N, on one thread.
Compile or JIT time is measured once, apart; so is the cost of one round
trip from Python into the peer and back, which a reset done in Python pays
at every event.
"""

import argparse
import json
import os
import platform
import statistics
import sys
import time

# One thread for XLA, as rtw and heyoka run: the figures are per core. Set
# before jax is imported, or it is read too late.
os.environ.setdefault(
    "XLA_FLAGS", "--xla_cpu_multi_thread_eigen=false intra_op_parallelism_threads=1"
)

import numpy as np  # noqa: E402

# The same parameters as crates/hybrid-ode/examples/peers/closed_form.rs
# (checked against the ones rtw's example prints).
G = 9.81
E = 0.8
IMPACTS = 10
WHEEL_L = 1.0
WHEEL_GAMMA = 0.08
WHEEL_SPOKES = 12
ALPHA = np.pi / WHEEL_SPOKES
# The impact oscillator of crates/hybrid-ode/tests/grazing.rs.
OSC_ZETA = 0.05
OSC_OMEGA = 0.8
OSC_SIGMA = 1.0
OSC_R = 0.8
OSC_D = np.sqrt((1 - OSC_OMEGA**2) ** 2 + (2 * OSC_ZETA * OSC_OMEGA) ** 2)
OSC_THETA = np.arctan2(2 * OSC_ZETA * OSC_OMEGA, 1 - OSC_OMEGA**2)
T_END = 100.0
# Event location: rtw's default event_time_tol, used for diffrax's root
# finder too (heyoka locates its events to rounding by itself).
EVENT_TOL = 1e-13


def ball_heights(n):
    return 1.0 + np.arange(n) / n


def wheel_rates(n):
    return 1.2 + 0.8 * np.arange(n) / n


def ball_reference(h0):
    """Impact times t_1 = sqrt(2 h0/g), t_{k+1} = t_k + 2 e^k v_1/g, and the
    state just after the last impact, [0, e^K v_1]."""
    v1 = np.sqrt(2 * G * h0)
    times = np.empty((len(h0), IMPACTS))
    t = np.sqrt(2 * h0 / G)
    v = v1.copy()
    for k in range(IMPACTS):
        if k > 0:
            t = t + 2 * v / G
        times[:, k] = t
        v = v * E
    return times, np.stack([np.zeros_like(v), v], axis=1)


def wheel_reference(omega0):
    """McGeer's step map for the rates, a 64-node Gauss-Legendre quadrature
    of the (analytic) stance-time integral for the touchdown times."""
    a, b = WHEEL_GAMMA - ALPHA, WHEEL_GAMMA + ALPHA
    x, w = np.polynomial.legendre.leggauss(64)
    mid, half = 0.5 * (a + b), 0.5 * (b - a)
    theta = mid + half * x
    k = 2 * G / WHEEL_L
    gain = 4 * (G / WHEEL_L) * np.sin(ALPHA) * np.sin(WHEEL_GAMMA)
    c = np.cos(2 * ALPHA)
    times = np.empty((len(omega0), IMPACTS))
    t = np.zeros(len(omega0))
    om = omega0.copy()
    for j in range(IMPACTS):
        stance = half * (w / np.sqrt(om[:, None] ** 2 + k * (np.cos(a) - np.cos(theta)))).sum(1)
        t = t + stance
        times[:, j] = t
        om = c * np.sqrt(om * om + gain)
    return times, np.stack([np.full_like(om, a), om], axis=1)


def impacts_of(model):
    """The oscillator is scored on its first impact, the one with a closed form."""
    return 1 if model == "oscillator" else IMPACTS


def osc_epsilons(n):
    return 10.0 ** (-4 + 3 * np.arange(n) / n)


def initial(model, n):
    """Start times, start states, each trajectory's parameter (the
    oscillator's forcing amplitude; 0 for the others) and the reference."""
    zeros = np.zeros(n)
    if model == "ball":
        h = ball_heights(n)
        return zeros, np.stack([h, zeros], 1), zeros, ball_reference(h)
    if model == "rimless":
        om = wheel_rates(n)
        y0 = np.stack([np.full_like(om, WHEEL_GAMMA - ALPHA), om], 1)
        return zeros, y0, zeros, wheel_reference(om)
    # Past grazing by eps, from the free orbit's minimum: the first impact
    # at Ωt − θ = 2π − acos(σ/X), leaving at −r Ω √(X² − σ²).
    eps = osc_epsilons(n)
    x = OSC_SIGMA * (1 + eps)
    t0 = np.full(n, (OSC_THETA + np.pi) / OSC_OMEGA)
    t_ref = (OSC_THETA + 2 * np.pi - np.arccos(OSC_SIGMA / x)) / OSC_OMEGA
    y_ref = np.stack([np.full(n, OSC_SIGMA), -OSC_R * OSC_OMEGA * np.sqrt(x * x - OSC_SIGMA**2)], 1)
    return t0, np.stack([-x, zeros], 1), x * OSC_D, (t_ref[:, None], y_ref)


def reset(model, y):
    """The impact map, on a state or on rows of states."""
    y = np.array(y, dtype=float)
    if model == "ball":
        y[..., 1] *= -E
    elif model == "oscillator":
        y[..., 1] *= -OSC_R
    else:
        y[..., 0] -= 2 * ALPHA
        y[..., 1] *= np.cos(2 * ALPHA)
    return y


def timed(fn, reps):
    """fn() -> result; the wall time of each of reps calls, and the last result."""
    runs, out = [], None
    for _ in range(reps):
        t0 = time.perf_counter()
        out = fn()
        runs.append(time.perf_counter() - t0)
    return runs, out


def record(tool, method, model, tol, n, runs, compile_s, roundtrip_s, work, times, y, ref):
    t_ref, y_ref = ref
    times = times[:, : t_ref.shape[1]]
    # Short of its impacts, or a first impact that is a later one (a
    # crossing missed): failed.
    ok = np.isfinite(times).all(1) & (np.abs(times[:, 0] - t_ref[:, 0]) < 1.0)
    return {
        "tool": tool,
        "method": method,
        "model": model,
        "tol": tol,
        "n": n,
        "reps": len(runs),
        "time_per_traj_s": statistics.median(runs) / n,
        "time_per_traj_runs_s": [r / n for r in runs],
        "compile_s": compile_s,
        "roundtrip_s": roundtrip_s,
        **work,
        "failed": int((~ok).sum()),
        "max_event_time_err": float(np.abs(times[ok] - t_ref[ok]).max()) if ok.any() else None,
        "max_state_err": float(np.abs(y[ok] - y_ref[ok]).max()) if ok.any() else None,
    }


# --------------------------------------------------------------------------
# heyoka
# --------------------------------------------------------------------------


def heyoka_system(hy, model):
    x, v = hy.make_vars("x", "v")
    if model == "ball":
        # 0·x keeps the right-hand side an expression of the state.
        sys_ = [(x, v), (v, -G + 0.0 * x)]
        guard, direction = x, hy.event_direction.negative
    elif model == "oscillator":
        # The amplitude is a runtime parameter: one compile serves every
        # trajectory.
        sys_ = [(x, v), (v, hy.par[0] * hy.cos(OSC_OMEGA * hy.time) - 2 * OSC_ZETA * v - x)]
        guard, direction = OSC_SIGMA - x, hy.event_direction.negative
    else:
        sys_ = [(x, v), (v, (G / WHEEL_L) * hy.sin(x))]
        guard, direction = x - (WHEEL_GAMMA + ALPHA), hy.event_direction.positive
    return sys_, guard, direction


def run_heyoka(model, tol, n, reps):
    import heyoka as hy

    t0s, y0, par, ref = initial(model, n)
    K = impacts_of(model)
    sys_, guard, direction = heyoka_system(hy, model)
    t0 = time.perf_counter()
    ta = hy.taylor_adaptive(
        sys_, list(y0[0]), t_events=[hy.t_event(guard, direction=direction)], tol=tol,
        pars=[par[0]] if model == "oscillator" else [],
    )
    compile_s = time.perf_counter() - t0

    def all_trajectories():
        times = np.full((n, K), np.nan)
        yk = np.full((n, 2), np.nan)
        steps = 0
        for i in range(n):
            ta.time = t0s[i]
            ta.state[:] = y0[i]
            if model == "oscillator":
                ta.pars[0] = par[i]
            ta.reset_cooldowns()
            for k in range(K):
                res = ta.propagate_until(T_END)
                steps += res[3]
                # A terminal event ends the call with outcome -(index + 1).
                if int(res[0]) != -1:
                    break
                times[i, k] = ta.time
                ta.state[:] = reset(model, ta.state)
            yk[i] = ta.state
        return times, yk, steps

    runs, (times, yk, steps) = timed(all_trajectories, reps)

    # The round trip a reset in Python pays per event: a call that
    # integrates nothing and a write of the state.
    def roundtrip():
        for _ in range(1000):
            ta.propagate_until(ta.time)
            ta.state[:] = ta.state

    rt, _ = timed(roundtrip, 5)
    work = {"steps": steps / n, "rejected": 0, "rhs_evals": None, "events": K,
            "order": ta.order}
    return record("heyoka", "taylor", model, tol, n, runs, compile_s,
                  statistics.median(rt) / 1000, work, times, yk, ref)


def run_heyoka_batch(model, tol, n, reps):
    """taylor_adaptive_batch: lanes of one SIMD register integrated together;
    a terminal event stops its own lane, so every call moves each lane on
    to its next impact, and one Python reset serves all lanes."""
    import heyoka as hy

    lanes = hy.recommended_simd_size()
    t0s, y0, par, ref = initial(model, n)
    K = impacts_of(model)
    sys_, guard, direction = heyoka_system(hy, model)
    t0 = time.perf_counter()
    extra = {"pars": np.full((1, lanes), par[0])} if model == "oscillator" else {}
    ta = hy.taylor_adaptive_batch(
        sys_, np.ascontiguousarray(np.repeat(y0[:1].T, lanes, axis=1)),
        t_events=[hy.t_event_batch(guard, direction=direction)], tol=tol, **extra,
    )
    compile_s = time.perf_counter() - t0

    def all_trajectories():
        times = np.full((n, K), np.nan)
        yk = np.full((n, 2), np.nan)
        steps = 0
        for s in range(0, n, lanes):
            idx = np.arange(s, s + lanes) % n  # the last batch wraps around
            ta.set_time(t0s[idx].copy())
            ta.state[:] = y0[idx].T
            if model == "oscillator":
                ta.pars[0, :] = par[idx]
            ta.reset_cooldowns()
            done = np.zeros(lanes, dtype=int)
            while (done < K).any():
                ta.propagate_until(T_END)
                fired = np.array([int(r[0]) == -1 for r in ta.propagate_res])
                steps += sum(r[3] for r in ta.propagate_res)
                if not fired.any():
                    break
                new = ta.state.copy()
                new[:, fired] = reset(model, new.T).T[:, fired]
                ta.state[:] = new
                # Lanes past their 10th impact go on bouncing unread: a lane
                # cannot be left out of the batch's step. (Lanes that wrap
                # around repeat an earlier trajectory and write the same.)
                for j in np.nonzero(fired)[0]:
                    if done[j] < K:
                        times[idx[j], done[j]] = ta.time[j]
                        done[j] += 1
                        if done[j] == K:
                            yk[idx[j]] = new[:, j]
        return times, yk, steps

    runs, (times, yk, steps) = timed(all_trajectories, reps)
    work = {"steps": steps / n, "rejected": 0, "rhs_evals": None, "events": K,
            "order": ta.order, "lanes": lanes}
    return record("heyoka", f"taylor batch ({lanes} lanes)", model, tol, n, runs,
                  compile_s, None, work, times, yk, ref)


# --------------------------------------------------------------------------
# diffrax
# --------------------------------------------------------------------------

# New right-hand-side evaluations per step (both tableaus are FSAL).
NEW_EVALS = {"Dopri8": 13, "Tsit5": 6}


def diffrax_parts(model, solver_name):
    import jax
    import jax.numpy as jnp
    import diffrax as dx
    import optimistix as optx

    # float64, as rtw and heyoka (jax's default is float32).
    jax.config.update("jax_enable_x64", True)
    if model == "ball":
        def f(t, y, args):
            return jnp.stack([y[1], -G + 0.0 * y[0]])

        # diffrax's events fire on a sign change either way: the guard is
        # the height only while falling, so the take-off from the floor
        # (a hair below it after the root find) is no event.
        def cond(t, y, args, **kw):
            return jnp.where(y[1] < 0, y[0], 1.0)

        def jreset(y):
            return jnp.stack([y[0], -E * y[1]])

        # That guard jumps (from 1 to the height) where a step spans the
        # apex, and Newton can be sent into its flat part and fail: bisection
        # keeps the bracket and finds the landing.
        root = optx.Bisection(rtol=EVENT_TOL, atol=EVENT_TOL)
    else:
        def f(t, y, args):
            return jnp.stack([y[1], (G / WHEEL_L) * jnp.sin(y[0])])

        def cond(t, y, args, **kw):
            return y[0] - (WHEEL_GAMMA + ALPHA)

        def jreset(y):
            return jnp.stack([y[0] - 2 * ALPHA, jnp.cos(2 * ALPHA) * y[1]])

        # The guard rises monotonically through a stance: Newton, diffrax's
        # own suggestion, converges in a few iterations.
        root = optx.Newton(rtol=EVENT_TOL, atol=EVENT_TOL)

    if model == "oscillator":
        # args: the forcing amplitude (diffrax passes it by that name).
        def f(t, y, args):
            return jnp.stack([y[1], args * jnp.cos(OSC_OMEGA * t) - 2 * OSC_ZETA * y[1] - y[0]])

        def cond(t, y, args, **kw):
            return OSC_SIGMA - y[0]

        def jreset(y):
            return jnp.stack([y[0], -OSC_R * y[1]])

        # Near grazing the guard has two close roots in the step, where
        # Newton fails to converge: bisection keeps the bracket.
        root = optx.Bisection(rtol=EVENT_TOL, atol=EVENT_TOL)

    solver = getattr(dx, solver_name)()

    def segment(t0, y0, tol, a):
        sol = dx.diffeqsolve(
            dx.ODETerm(f), solver, t0, T_END, None, y0, args=a,
            stepsize_controller=dx.PIDController(rtol=tol, atol=tol),
            event=dx.Event(cond, root_finder=root),
            max_steps=100_000,
        )
        hit = sol.result == dx.RESULTS.event_occurred
        return sol.ts[-1], sol.ys[-1], sol.stats["num_steps"], sol.stats["num_accepted_steps"], hit

    K = impacts_of(model)

    def trajectory(t0, y0, tol, a):
        def body(k, c):
            t, y, times, steps, acc, ok = c
            te, ye, ns, na, hit = segment(t, y, tol, a)
            return (te, jreset(ye), times.at[k].set(jnp.where(hit, te, jnp.nan)),
                    steps + ns, acc + na, ok & hit)
        init = (jnp.asarray(t0), y0, jnp.full(K, jnp.nan), jnp.array(0), jnp.array(0),
                jnp.array(True))
        _, y, times, steps, acc, ok = jax.lax.fori_loop(0, K, body, init)
        return times, y, steps, acc

    return jax, jnp, jax.jit(segment), jax.jit(trajectory), jax.jit(jax.vmap(trajectory, (0, 0, None, 0)))


def run_diffrax(model, solver_name, tol, n, reps, modes):
    jax, jnp, seg, traj, vtraj = diffrax_parts(model, solver_name)
    t0s, y0, par, ref = initial(model, n)
    K = impacts_of(model)
    out = []
    per_step = NEW_EVALS[solver_name]

    def work(steps, acc):
        return {"steps": steps / n, "rejected": (steps - acc) / n,
                "rhs_evals": per_step * steps / n, "events": K}

    if "loop" in modes:
        # The reset and restart in a Python loop around one jitted segment.
        c0 = time.perf_counter()
        jax.block_until_ready(seg(t0s[0], jnp.asarray(y0[0]), tol, par[0]))
        compile_s = time.perf_counter() - c0

        def all_trajectories():
            times = np.full((n, K), np.nan)
            yk = np.full((n, 2), np.nan)
            steps = acc = 0
            for i in range(n):
                t, y = t0s[i], jnp.asarray(y0[i])
                for k in range(K):
                    te, ye, ns, na, hit = seg(t, y, tol, par[i])
                    steps += int(ns)
                    acc += int(na)
                    if not bool(hit):
                        break
                    t = float(te)
                    times[i, k] = t
                    y = jnp.asarray(reset(model, np.asarray(ye)))
                yk[i] = np.asarray(y)
            return times, yk, steps, acc

        runs, (times, yk, steps, acc) = timed(all_trajectories, reps)
        # The round trip per event, apart from integrating: a jitted call
        # that does nothing with the same arguments, and the host reads the
        # loop makes.
        noop = jax.jit(lambda t, y, tol, a: (t, y, jnp.array(0), jnp.array(0), jnp.array(True)))
        jax.block_until_ready(noop(0.0, jnp.asarray(y0[0]), tol, par[0]))

        def roundtrip():
            y = jnp.asarray(y0[0])
            for _ in range(1000):
                te, ye, ns, na, hit = noop(0.0, y, tol, par[0])
                int(ns), int(na), bool(hit), float(te)
                y = jnp.asarray(reset(model, np.asarray(ye)))

        rt, _ = timed(roundtrip, 5)
        out.append(record("diffrax", f"{solver_name}, Python loop", model, tol, n, runs,
                          compile_s, statistics.median(rt) / 1000, work(steps, acc), times, yk, ref))

    if "jit" in modes:
        # The ten segments and resets in one jitted call per trajectory.
        c0 = time.perf_counter()
        jax.block_until_ready(traj(t0s[0], jnp.asarray(y0[0]), tol, par[0]))
        compile_s = time.perf_counter() - c0

        def all_trajectories():
            res = [traj(t0s[i], jnp.asarray(y0[i]), tol, par[i]) for i in range(n)]
            jax.block_until_ready(res)
            return res

        runs, res = timed(all_trajectories, reps)
        times = np.stack([np.asarray(r[0]) for r in res])
        yk = np.stack([np.asarray(r[1]) for r in res])
        steps = sum(int(r[2]) for r in res)
        acc = sum(int(r[3]) for r in res)
        out.append(record("diffrax", f"{solver_name}, jit loop", model, tol, n, runs,
                          compile_s, None, work(steps, acc), times, yk, ref))

    if "vmap" in modes:
        # All n trajectories in one vmapped call: lanes step together until
        # the last lane's event, so every lane pays for the slowest.
        ys, ts, ps = jnp.asarray(y0), jnp.asarray(t0s), jnp.asarray(par)
        c0 = time.perf_counter()
        jax.block_until_ready(vtraj(ts, ys, tol, ps))
        compile_s = time.perf_counter() - c0
        runs, res = timed(lambda: jax.block_until_ready(vtraj(ts, ys, tol, ps)), reps)
        times, yk, steps, acc = (np.asarray(r) for r in res)
        out.append(record("diffrax", f"{solver_name}, vmap", model, tol, n, runs, compile_s,
                          None, work(int(steps.sum()), int(acc.sum())), times, yk, ref))
    return out


# --------------------------------------------------------------------------
# The page
# --------------------------------------------------------------------------


def fmt_time(s):
    return f"{s * 1e6:.3g}" if s is not None else "–"


def fmt_num(x, digits=3):
    if x is None:
        return "–"
    return f"{x:.{digits}g}"


def fmt_err(x):
    return "–" if x is None else f"{x:.1e}"


def machine():
    with open("/proc/loadavg") as f:
        load = f.read().split()[:3]
    cpu = "?"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return cpu, os.cpu_count(), load


def versions():
    import heyoka
    import jax
    import diffrax
    return {"heyoka": heyoka.__version__, "jax": jax.__version__,
            "diffrax": diffrax.__version__, "numpy": np.__version__,
            "python": platform.python_version()}


def write_page(path, rows, meta):
    lines = []
    add = lines.append
    add("# rtw's engine against heyoka and diffrax on the smallest hybrid systems")
    add("")
    add(f"Written by `{meta['command']}` (every number on this page is from that one run; "
        "the script builds rtw's side, makes `.venv-peers` with heyoka and diffrax from the "
        "package index, runs all three and writes this page).")
    add("")
    add(f"**Machine**: {meta['cpu']}, nproc {meta['nproc']}, shared with other jobs; load "
        f"average (1, 5, 15 min) {' '.join(meta['load_before'])} before the run and "
        f"{' '.join(meta['load_after'])} after it; {meta['date']}. Everything ran in the same "
        "session, one tool at a time, each on one thread.")
    add("")
    v = meta["versions"]
    add(f"**Versions**: rtw's hybrid-ode (this commit, release build), heyoka {v['heyoka']}, "
        f"diffrax {v['diffrax']} on jax {v['jax']} (CPU, float64), NumPy {v['numpy']}, "
        f"Python {v['python']}.")
    add("")
    add("## The models and their closed forms")
    add("")
    add(f"- **Bouncing ball**: `ÿ = −g`, g = {G}, impact where the height falls through 0, "
        f"`v ← −e v` with e = {E}. Dropped from rest at h0 spread over [1, 2) m. Impact times "
        "`t_1 = √(2 h0/g)`, `t_{k+1} = t_k + 2 e^k v_1/g` with `v_1 = √(2 g h0)`; the state "
        "just after impact K is `[0, e^K v_1]`.")
    add(f"- **Rimless wheel** (McGeer): {WHEEL_SPOKES} spokes (α = π/{WHEEL_SPOKES}), l = "
        f"{WHEEL_L}, slope γ = {WHEEL_GAMMA}; stance `θ̈ = (g/l) sin θ` from `θ = γ − α`, "
        "touchdown at `θ = γ + α`, reset `θ ← θ − 2α`, `θ̇ ← θ̇ cos 2α`. Started at post-impact "
        "rates ω0 spread over [1.2, 2.0) rad/s around the fixed point ω* = "
        f"{meta['omega_star']:.4f} rad/s. The rate after each step is McGeer's closed-form "
        "map `P(ω) = cos 2α · √(ω² + 4 (g/l) sin α sin γ)`; a stance's duration is an "
        "elliptic integral, taken by 64-node Gauss–Legendre quadrature (its integrand is "
        "analytic there, so it is exact to rounding).")
    add(f"- **Impact oscillator near grazing** (Nordmark; the system of hybrid-ode's "
        f"`tests/grazing.rs`): `ẍ + 2ζẋ + x = A cos Ωt`, ζ = {OSC_ZETA}, Ω = {OSC_OMEGA}, impact "
        f"at `x = σ` = {OSC_SIGMA} with `ẋ ← −r ẋ`, r = {OSC_R}. Its free periodic orbit "
        "`x = X cos(Ωt − θ)` grazes the stop at X = σ; here `A = A_g (1 + ε)` with ε "
        "log-spaced over [1e-4, 1e-1), started at the orbit's minimum `t0 = (θ + π)/Ω`. The "
        "first impact is at `Ωt − θ = 2π − acos(σ/X)` with speed `Ω √(X² − σ²)` (the grazing "
        "law's square root, exactly); only that impact is scored. Near grazing the orbit is "
        "past the stop for a sliver of its period (0.035 s of 7.85 s at ε = 1e-4), inside one "
        "step: a method that only compares the guard's signs at step ends misses it, and the "
        "impact time's error is the state error over the small speed, so it grows as the "
        "impact grazes.")
    add("")
    add(f"Each of n = {meta['n']} trajectories of the ball and the wheel runs to its "
        f"{IMPACTS}th impact, of the oscillator to its first. **Event-time "
        "error**: the largest |t_k − t_k,ref| over the scored impacts of all trajectories. "
        "**Failed**: trajectories short of their impacts or whose first impact is a later "
        "one (a crossing missed); the errors are over the others. "
        "**State error**: the largest component error of the state just after the last scored "
        "impact. "
        "Tolerance `tol` is rtol = atol = tol for rtw and diffrax and heyoka's single `tol`. "
        f"Event times are located to {EVENT_TOL:g} s by rtw (its default `event_time_tol`) and "
        "diffrax (its root finder on the solver's dense output, at rtol = atol = that: "
        "bisection for the ball and the oscillator, whose guards Newton fails on, Newton for "
        "the wheel); heyoka's "
        "Taylor events are located to rounding by its own polynomial root finder.")
    add("")
    add("## How the comparison is made fair")
    add("")
    add(f"- **Time per trajectory** is the median over {meta['reps']} repetitions of the wall "
        "time for all n trajectories divided by n, on one thread (XLA is held to one thread; "
        "heyoka runs one integrator; rtw's example is single-threaded). It excludes "
        "compilation.")
    add("- **Compile / JIT** is measured once, apart: heyoka compiles each tolerance's Taylor "
        "integrator with LLVM when it is built; diffrax's jax.jit traces and compiles on the "
        "first call (one compile serves every tolerance, which is a traced argument). rtw is "
        "compiled ahead of time (its build is not counted; `cargo build --release` of the "
        "example takes minutes from cold, seconds when only relinking).")
    add("- **Python round trip per event**: where the reset is done in Python (heyoka's scalar "
        "integrator, diffrax's Python loop), every event costs a return to Python and a new "
        "call. That cost alone (a call that integrates nothing, plus the state read and "
        "write) is measured and listed; it is part of the time per trajectory. diffrax's "
        "`jit loop` (all of a trajectory's segments and resets in one jitted `fori_loop`, one call per "
        "trajectory) and `vmap` (all trajectories in one call) pay none of it per event.")
    add("- **Work**: rtw counts steps (accepted), rejected steps and right-hand-side "
        "evaluations itself. diffrax reports steps (accepted + rejected); its RHS count is "
        "estimated as steps × new stages per step (Dopri8 13, Tsit5 6; both FSAL). heyoka "
        "reports Taylor steps, whose cost is one Taylor expansion of the given order, not RHS "
        "evaluations, so that column is empty for it. In the vmap runs the steps are each "
        "lane's own, though every lane is carried until the slowest lane's event.")
    add("- **Methods**: rtw's DOP853 (Hairer's 8(5,3)) and DP5(4); diffrax's Dopri8 "
        "(Dormand–Prince 8(7)) and Tsit5 with PIDController (its defaults: an I controller); "
        "heyoka's adaptive Taylor method, whose order follows from tol.")
    add("")
    for model, title in (("ball", "Bouncing ball"), ("rimless", "Rimless wheel"),
                         ("oscillator", "Impact oscillator near grazing")):
        add(f"## {title}")
        add("")
        add("| tool | method | tol | µs per trajectory | compile / JIT (s) | Python round "
            "trip per event (µs) | steps | rejected | RHS evals | event-time error (s) | "
            "state error | failed |")
        add("|---|---|---|---|---|---|---|---|---|---|---|---|")
        for r in rows:
            if r["model"] != model:
                continue
            method = r["method"]
            if r.get("order"):
                method += f", order {r['order']}"
            add(f"| {r['tool']} | {method} | {r['tol']:g} | {fmt_time(r['time_per_traj_s'])} | "
                f"{fmt_num(r['compile_s'], 2) if r['compile_s'] else '0 (ahead of time)'} | "
                f"{fmt_time(r.get('roundtrip_s'))} | {fmt_num(r['steps'])} | "
                f"{fmt_num(r['rejected'])} | {fmt_num(r['rhs_evals'])} | "
                f"{fmt_err(r['max_event_time_err'])} | {fmt_err(r['max_state_err'])} | "
                f"{r['failed']} |")
        add("")
        add(f"Fastest per tolerance ({title.lower()}), and the best event-time error (rows "
            "with a failed trajectory left out, here and below):")
        add("")
        for tol in meta["tols"]:
            group = [r for r in rows if r["model"] == model and r["tol"] == tol and not r["failed"]]
            if not group:
                continue
            fast = sorted(group, key=lambda r: r["time_per_traj_s"])
            best = min(group, key=lambda r: r["max_event_time_err"])
            f0, f1 = fast[0], fast[1]
            add(f"- tol {tol:g}: fastest {f0['tool']} {f0['method']} "
                f"({fmt_time(f0['time_per_traj_s'])} µs), then {f1['tool']} {f1['method']} "
                f"({fmt_time(f1['time_per_traj_s'])} µs, "
                f"{f1['time_per_traj_s'] / f0['time_per_traj_s']:.2g}×); smallest event-time "
                f"error {best['tool']} {best['method']} ({fmt_err(best['max_event_time_err'])} s).")
        add("")
        add(f"At matched accuracy ({title.lower()}): the cheapest row of each tool whose "
            "event-time error is at most the bound (tolerances mean different things to a "
            "Taylor method and to an embedded Runge–Kutta pair, so equal tol is not equal "
            "accuracy):")
        add("")
        for bound in (1e-5, 1e-8, 1e-11):
            picks = []
            for tool in ("rtw", "heyoka", "diffrax"):
                ok = [r for r in rows if r["model"] == model and r["tool"] == tool
                      and not r["failed"] and r["max_event_time_err"] <= bound]
                if ok:
                    r = min(ok, key=lambda r: r["time_per_traj_s"])
                    picks.append(f"{tool} {r['method']} at tol {r['tol']:g}, "
                                 f"{fmt_time(r['time_per_traj_s'])} µs")
                else:
                    picks.append(f"{tool} none")
            add(f"- error ≤ {bound:g} s: " + "; ".join(picks) + ".")
        add("")
    add("## Raw figures")
    add("")
    add("Every row above with its repetitions, as JSON lines (the rtw lines as the example "
        "printed them):")
    add("")
    add("```text")
    for r in rows:
        add(json.dumps(r, separators=(",", ":")))
    add("```")
    add("")
    with open(path, "w") as f:
        f.write("\n".join(lines))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("rtw_json")
    ap.add_argument("out_md")
    ap.add_argument("--n", type=int, default=100)
    ap.add_argument("--reps", type=int, default=5)
    ap.add_argument("--tols", default="1e-6,1e-9,1e-12")
    ap.add_argument("--command", default="scripts/peers_bench.sh")
    ap.add_argument("--load-before", default=None)
    ap.add_argument("--notes", default=None, help="a Markdown file appended to the page")
    a = ap.parse_args()
    tols = [float(t) for t in a.tols.split(",")]
    load_before = a.load_before.split() if a.load_before else machine()[2]

    rows = []
    with open(a.rtw_json) as f:
        for line in f:
            d = json.loads(line)
            if "params" in d:
                p = d["params"]
                mine = {"g": G, "e": E, "impacts": IMPACTS, "wheel_l": WHEEL_L,
                        "wheel_gamma": WHEEL_GAMMA, "wheel_spokes": WHEEL_SPOKES,
                        "osc_zeta": OSC_ZETA, "osc_omega": OSC_OMEGA, "osc_sigma": OSC_SIGMA,
                        "osc_r": OSC_R, "n": a.n}
                if p != mine:
                    sys.exit(f"rtw's parameters {p} are not the driver's {mine}")
            else:
                rows.append(d)
    # rtw's errors are its example's, against closed_form.rs: the same
    # formulas as here, at the parameters checked above.
    for model in ("ball", "rimless", "oscillator"):
        for tol in tols:
            print(f"heyoka {model} {tol:g}", file=sys.stderr, flush=True)
            rows.append(run_heyoka(model, tol, a.n, a.reps))
            rows.append(run_heyoka_batch(model, tol, a.n, a.reps))
        for solver, modes in (("Dopri8", ("loop", "jit", "vmap")), ("Tsit5", ("jit", "vmap"))):
            for tol in tols:
                print(f"diffrax {solver} {model} {tol:g}", file=sys.stderr, flush=True)
                rows.extend(run_diffrax(model, solver, tol, a.n, a.reps, modes))
    gain = 4 * (G / WHEEL_L) * np.sin(ALPHA) * np.sin(WHEEL_GAMMA)
    cpu, nproc, load_after = machine()
    meta = {
        "command": a.command, "cpu": cpu, "nproc": nproc, "load_before": load_before,
        "load_after": load_after, "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
        "versions": versions(), "n": a.n, "reps": a.reps, "tols": tols,
        "omega_star": np.sqrt(gain) / np.tan(2 * ALPHA),
    }
    order = {"rtw": 0, "heyoka": 1, "diffrax": 2}
    rows.sort(key=lambda r: (r["model"] != "ball", tols.index(r["tol"]), order[r["tool"]],
                             r["method"]))
    write_page(a.out_md, rows, meta)
    if a.notes:
        with open(a.notes) as f, open(a.out_md, "a") as out:
            out.write("\n" + f.read())


if __name__ == "__main__":
    main()
