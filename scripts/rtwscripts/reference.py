"""An independent Python/NumPy port of rtw's default model, run by SciPy.

Written from docs/model.md (the authority; §1 parameters, §3 strings, §4
contact, §5 outcomes) for scripts/scipy_side_by_side.py: the same equations
in the same reduced coordinates, integrated by `scipy.integrate.solve_ivp`
(RK45 with terminal events, one solve per contact mode), so that it both
times SciPy against rtw on the same model and checks rtw's labels
independently.

What it ports: the three rods in their modes (free, stick, slide with Coulomb
friction), the six slack Kelvin–Voigt strings with natural length s·r, the
guards (touchdown at −touchdown_offset·L, lift-off, a rod lying down, slip,
re-stick, the centre of mass sinking), the resets (inelastic touchdown: a
sticking, sliding or frictionless impact; one mode-choice rule at touchdowns,
lift-offs, re-sticks and slips), the stall rules and the label by the typical
step over the last half of the run. What it does not: setting the star down
(`initial.shape = "settled"`, a dynamic relaxation): a run starts from rtw's
own initial state (its trace at t = 0), so samples that cannot stand (a
collapse before the push) are not compared; and the early stop
(`stop_when_settled`), which the comparison turns off in rtw too.
"""
import math

import numpy as np
from scipy.integrate import solve_ivp

FREE, STICK, SLIDE = 0, 1, 2
SPOKES = [(0, 1.0), (1, 1.0), (2, 1.0), (0, -1.0), (1, -1.0), (2, -1.0)]


class Model:
    """Physical constants (docs/model.md §1, normalization "supplementary")
    and the default variant's choices."""

    def __init__(self, length, rho, alpha, fn, zeta, phi, s, g=9.81, mu=0.8,
                 touchdown_offset=1e-10, collapse_height_ratio=0.5):
        w = (1.0 - 2.0 * alpha) ** 2
        self.L = length
        self.m = rho * length
        self.inertia = self.m * length * length / 12.0
        self.half = length / 2.0
        self.r = length / 2.0 - alpha * length
        self.k = 4.0 * math.pi ** 2 / 3.0 * rho * fn * fn * length / w
        self.c = 8.0 * math.pi / 15.0 * zeta * rho * fn * length / w
        self.rest = s * self.r
        self.gravity = (g * math.sin(phi), -g * math.cos(phi))
        self.mu = mu
        self.touchdown_height = -touchdown_offset * length
        self.restick_speed = 1e-9 * length
        self.collapse_height = collapse_height_ratio * 0.5 * length * math.cos(math.pi / 6.0)


# A rod's mode: (kind, tip sign, slide direction). Slots per rod, as in rtw:
# free (x, y, θ, ẋ, ẏ, ω); stick (x_P, 0, θ, 0, 0, ω); slide (x_t, 0, θ, ẋ_t, 0, ω).


def frame(M, mode, s):
    """Centre, centre velocity, ω, unit vector e of a rod from its slots."""
    kind, tip, _ = mode
    e = (math.cos(s[2]), math.sin(s[2]))
    if kind == FREE:
        return (s[0], s[1]), (s[3], s[4]), s[5], e
    d = (tip * M.half * e[0], tip * M.half * e[1])
    w = s[5]
    # c = P − d; v = v_P − ω d⊥ with d⊥ = (−d_y, d_x).
    return (s[0] - d[0], -d[1]), (s[3] + w * d[1], -w * d[0]), w, e


def point(fr, a):
    """Position and velocity of the point at signed distance a along a rod."""
    c, v, w, e = fr
    arm = (a * e[0], a * e[1])
    return (c[0] + arm[0], c[1] + arm[1]), (v[0] - w * arm[1], v[1] + w * arm[0]), arm


def loads(M, frames):
    """Net force and torque on each rod: slack Kelvin–Voigt strings + weight."""
    force = [[M.m * M.gravity[0], M.m * M.gravity[1]] for _ in range(3)]
    torque = [0.0, 0.0, 0.0]
    ends = [point(frames[i], tip * M.r) for i, tip in SPOKES]
    for j in range(6):
        n = (j + 1) % 6
        (p, vp, arm_p), (q, vq, arm_q) = ends[j], ends[n]
        dx, dy = p[0] - q[0], p[1] - q[1]
        length = math.hypot(dx, dy)
        ux, uy = (dx / length, dy / length) if length > 0.0 else (0.0, 0.0)
        stretch = length - M.rest
        rate = ux * (vp[0] - vq[0]) + uy * (vp[1] - vq[1])
        spring = 0.0 if stretch < 0.0 else M.k * stretch
        t = max(0.0, spring + M.c * rate)
        fx, fy = -t * ux, -t * uy
        ip, iq = SPOKES[j][0], SPOKES[n][0]
        force[ip][0] += fx
        force[ip][1] += fy
        force[iq][0] -= fx
        force[iq][1] -= fy
        torque[ip] += arm_p[0] * fy - arm_p[1] * fx
        torque[iq] -= arm_q[0] * fy - arm_q[1] * fx
    return force, torque


def accel(M, mode, fr, f, tau):
    """Slot derivatives of a rod in its mode and the ground's force λ on it."""
    kind, tip, direction = mode
    c, v, w, e = fr
    m, inertia = M.m, M.inertia
    if kind == FREE:
        return [v[0], v[1], w, f[0] / m, f[1] / m, tau / inertia], (0.0, 0.0)
    d = (tip * M.half * e[0], tip * M.half * e[1])
    w2 = w * w
    if kind == STICK:
        tau_p = tau - (d[0] * f[1] - d[1] * f[0])
        beta = tau_p / (inertia + m * M.half * M.half)
        # c̈ = −(β d⊥ − ω² d); λ = m c̈ − F.
        cdd = (-(-beta * d[1] - w2 * d[0]), -(beta * d[0] - w2 * d[1]))
        return [0.0, 0.0, w, 0.0, 0.0, beta], (m * cdd[0] - f[0], m * cdd[1] - f[1])
    kappa = -M.mu * direction
    lam_y = (m * w2 * d[1] - f[1] - m * d[0] * tau / inertia) / (
        1.0 + m * d[0] * (d[0] - kappa * d[1]) / inertia)
    beta = (tau + lam_y * (d[0] - kappa * d[1])) / inertia
    a = (f[0] + kappa * lam_y) / m - beta * d[1] - w2 * d[0]
    return [v[0] - w * d[1], 0.0, w, a, 0.0, beta], (kappa * lam_y, lam_y)


class Rtw:
    """The hybrid system: modes, right-hand side, guards and resets."""

    def __init__(self, model, modes):
        self.M = model
        self.modes = list(modes)

    def frames(self, y):
        return [frame(self.M, self.modes[i], y[6 * i:6 * i + 6]) for i in range(3)]

    def dynamics(self, y):
        frames = self.frames(y)
        force, torque = loads(self.M, frames)
        dy = np.empty(18)
        lam = []
        for i in range(3):
            d, lm = accel(self.M, self.modes[i], frames[i], force[i], torque[i])
            dy[6 * i:6 * i + 6] = d
            lam.append(lm)
        return dy, frames, lam

    def rhs(self, _t, y):
        return self.dynamics(y)[0]

    def guard_kinds(self):
        """(kind, rod) in a fixed order per mode set, as rtw's guard_kinds."""
        out = []
        for i, (kind, _, _) in enumerate(self.modes):
            if kind == FREE:
                out += [("touchdown", i, 1.0), ("touchdown", i, -1.0)]
            elif kind == STICK:
                out += [("liftoff", i, 0), ("roddown", i, 0), ("slip", i, 0)]
            else:
                out += [("liftoff", i, 0), ("roddown", i, 0), ("restick", i, 0)]
        return out + [("comlow", 0, 0)]

    def guard(self, g, y):
        what, i, tip = g
        M = self.M
        if what in ("touchdown", "roddown"):
            fr = frame(M, self.modes[i], y[6 * i:6 * i + 6])
            if what == "touchdown":
                return point(fr, tip * M.half)[0][1] - M.touchdown_height
            return point(fr, -self.modes[i][1] * M.half)[0][1]
        if what == "restick":
            return y[6 * i + 3] * self.modes[i][2] + M.restick_speed
        if what == "comlow":
            return sum(frame(M, self.modes[j], y[6 * j:6 * j + 6])[0][1] for j in range(3)) / 3.0 \
                - M.collapse_height
        lam = self.dynamics(y)[2][i]
        if what == "liftoff":
            return lam[1]
        return M.mu * lam[1] - abs(lam[0])

    def rods(self, y):
        """Full coordinates (c, θ, v, ω) of every rod."""
        out = []
        for i, fr in enumerate(self.frames(y)):
            out.append([fr[0][0], fr[0][1], y[6 * i + 2], fr[1][0], fr[1][1], fr[2]])
        return out

    def store(self, rods, y):
        for i in range(3):
            cx, cy, th, vx, vy, w = rods[i]
            kind, tip, _ = self.modes[i]
            if kind == FREE:
                y[6 * i:6 * i + 6] = rods[i]
                continue
            e = (math.cos(th), math.sin(th))
            d = (tip * self.M.half * e[0], tip * self.M.half * e[1])
            vpx = vx - w * d[1]
            y[6 * i:6 * i + 6] = [cx + d[0], 0.0, th, vpx if kind == SLIDE else 0.0, 0.0, w]

    def choose(self, y, i, tip, at_rest, may_stick):
        """docs/model.md §4's mode-choice rule for rod i on `tip` (the loads
        are those of the rods as they are in y)."""
        M = self.M
        rods = self.rods(y)
        frames = self.frames(y)
        force, torque = loads(M, frames)
        cx, cy, th, vx, vy, w = rods[i]
        fr = ((cx, cy), (vx, vy), w, (math.cos(th), math.sin(th)))
        f, tau = force[i], torque[i]
        lam = accel(M, (STICK, tip, 0.0), fr, f, tau)[1]
        if may_stick and at_rest and lam[1] > 0.0 and abs(lam[0]) <= M.mu * lam[1]:
            return (STICK, tip, 0.0)
        d = (tip * M.half * fr[3][0], tip * M.half * fr[3][1])
        beta = tau / M.inertia
        free_ay = f[1] / M.m + beta * d[0] - w * w * d[1]
        if free_ay >= 0.0:
            return (FREE, 0.0, 0.0)
        v_tip_x = vx - w * d[1]
        if not at_rest:
            direction = math.copysign(1.0, v_tip_x)
        elif lam[1] > 0.0:
            direction = -math.copysign(1.0, lam[0])
        else:
            saved = M.mu
            M.mu = 0.0
            probe = accel(M, (SLIDE, tip, 1.0), fr, f, tau)[0][3]
            M.mu = saved
            direction = -1.0 if probe < 0.0 else 1.0
        slide = (SLIDE, tip, direction)
        return slide if accel(M, slide, fr, f, tau)[1][1] > 0.0 else (FREE, 0.0, 0.0)

    def rechoose(self, y, i, at_rest, leaving):
        tip = self.modes[i][1]
        rods = self.rods(y)
        mode = self.choose(y, i, tip, at_rest, True)
        if leaving is not None and mode == leaving:
            mode = self.choose(y, i, tip, at_rest, False)
            if mode == leaving:
                mode = (FREE, 0.0, 0.0)
        self.modes[i] = mode
        self.store(rods, y)

    def touchdown(self, y, i, tip):
        """Inelastic impact of rod i's tip, then the mode choice."""
        M = self.M
        rods = self.rods(y)
        cx, cy, th, vx, vy, w = rods[i]
        e = (math.cos(th), math.sin(th))
        d = (tip * M.half * e[0], tip * M.half * e[1])
        i_p = M.inertia + M.m * M.half * M.half
        omega = (M.inertia * w - M.m * (d[0] * vy - d[1] * vx)) / i_p
        v = (omega * d[1], -omega * d[0])
        impulse = (M.m * (v[0] - vx), M.m * (v[1] - vy))
        sticks = impulse[1] >= 0.0 and abs(impulse[0]) <= M.mu * impulse[1]
        if not sticks:
            kappa = M.mu * math.copysign(1.0, impulse[0]) if impulse[1] >= 0.0 else 0.0
            v_tip_y = vy + w * d[0]
            p_y = -v_tip_y / (1.0 / M.m + d[0] * (d[0] - kappa * d[1]) / M.inertia)
            imp = (kappa * p_y, p_y)
            v = (vx + imp[0] / M.m, vy + imp[1] / M.m)
            omega = w + (d[0] * imp[1] - d[1] * imp[0]) / M.inertia
        # Put the tip exactly on the ground.
        cy -= cy + d[1]
        rods[i] = [cx, cy, th, v[0], v[1], omega]
        self.modes[i] = (FREE, 0.0, 0.0)
        self.store(rods, y)
        mode = self.choose(y, i, tip, sticks, True)
        self.modes[i] = mode
        self.store(rods, y)
        return omega

    def contact_state(self):
        return sum(1 for m in self.modes if m[0] != FREE)

    def com(self, y):
        fr = self.frames(y)
        return (sum(f[0][0] for f in fr) / 3.0, sum(f[0][1] for f in fr) / 3.0)


def mode_of_code(code):
    """rtw's trace code: 0 free, ±1 stick on tip ±, ±2 slide on tip ± (the
    slide direction is not in the trace: taken from the tip's velocity)."""
    if code == 0:
        return (FREE, 0.0, 0.0)
    return (STICK if abs(code) == 1 else SLIDE, math.copysign(1.0, code), 1.0)


def simulate(model, rods0, codes, t_max=20.0, rtol=1e-4, atol=1e-6, stall_time=3.0,
             window=0.5, flight=0.01, triple=0.01, flight_steps=0.5, triple_steps=0.5,
             max_events=100_000):
    """One run from full coordinates `rods0` (per rod x, y, θ, ẋ, ẏ, ω) in the
    modes of rtw's trace `codes`: returns (label, detail, stats)."""
    sys_ = Rtw(model, [mode_of_code(c) for c in codes])
    y = np.zeros(18)
    sys_.store(rods0, y)
    for i, m in enumerate(sys_.modes):
        if m[0] == SLIDE:
            sys_.modes[i] = (SLIDE, m[1], math.copysign(1.0, y[6 * i + 3]))
    window_start = t_max * (1.0 - window)
    t, last_td, events, nfev = 0.0, 0.0, 0, 0
    state_time = [0.0] * 4
    step_time = [0.0] * 4
    last_tip = [None] * 3
    step_start = None
    window_steps = [0, 0, 0]  # steps, with flight, with triple support
    touchdowns = window_touchdowns = 0
    com_x0 = None

    def interval(t0, t1):
        cs = sys_.contact_state()
        step_time[cs] += t1 - t0
        lo = max(t0, window_start)
        if t1 > lo:
            state_time[cs] += t1 - lo

    while t < t_max:
        kinds = sys_.guard_kinds()

        def make(g):
            def ev(_t, yy):
                return sys_.guard(g, yy)
            ev.terminal = True
            ev.direction = -1
            return ev

        evs = [make(g) for g in kinds]
        stall = lambda tt, _yy: last_td + stall_time - tt  # noqa: E731
        stall.terminal = True
        stall.direction = -1
        t_stop = t_max if com_x0 is not None or t >= window_start else window_start
        sol = solve_ivp(sys_.rhs, (t, t_stop), y, method="RK45", rtol=rtol, atol=atol,
                        events=evs + [stall])
        nfev += sol.nfev
        if sol.status == -1:
            return "diverged", "solver", {"nfev": nfev}
        hit = [(te[0], j) for j, te in enumerate(sol.t_events) if len(te)]
        if not hit:
            interval(t, sol.t[-1])
            t, y = sol.t[-1], sol.y[:, -1].copy()
            if com_x0 is None and t >= window_start:
                com_x0 = sys_.com(y)[0]
            continue
        te, j = min(hit)
        ye = sol.y_events[j][0].copy()
        interval(t, te)
        t, y = te, ye
        if j == len(kinds):
            return "stall", "no_touchdown", {"nfev": nfev, "t_end": t}
        events += 1
        if events > max_events:
            return "diverged", "zeno", {"nfev": nfev}
        what, i, tip = kinds[j]
        if what in ("roddown", "comlow"):
            return "collapse", "rod_down" if what == "roddown" else "com_low", {"nfev": nfev}
        if what == "touchdown":
            sys_.touchdown(y, i, tip)
            touchdowns += 1
            last_td = t
            if last_tip[i] != tip:
                if step_start is not None and step_start >= window_start:
                    total = sum(step_time)
                    window_steps[0] += 1
                    window_steps[1] += step_time[0] > flight * total
                    window_steps[2] += step_time[3] > triple * total
                step_time[:] = [0.0] * 4
                step_start = t
            last_tip[i] = tip
            window_touchdowns += t >= window_start
        elif what == "liftoff":
            sys_.rechoose(y, i, sys_.modes[i][0] == STICK, sys_.modes[i])
        elif what == "restick":
            y[6 * i + 3] = 0.0
            sys_.rechoose(y, i, True, None)
        elif what == "slip":
            sys_.rechoose(y, i, True, sys_.modes[i])
    span = t_max - window_start
    speed = (sys_.com(y)[0] - com_x0) / span
    total = sum(state_time)
    frac = [s / total for s in state_time]
    n = max(window_steps[0], 1)
    stats = {"nfev": nfev, "events": events, "f_w": window_touchdowns / span, "fractions": frac}
    if speed * span < 0.5 * model.L:
        return "stall", "no_progress", stats
    if frac[0] > flight and window_steps[1] / n >= flight_steps:
        return "skip", None, stats
    if frac[3] > triple and window_steps[2] / n >= triple_steps:
        return "crawl", None, stats
    return "walk", None, stats
