#!/usr/bin/env python3
"""Where the instructions of one run go: the "Hot path" table of docs/performance.md.

Usage: scripts/hot_path.py CALLGRIND_OUT [CALLGRIND_OUT ...]

Reads each file with `callgrind_annotate --inclusive=yes --tree=caller` (all
functions: `--threshold=100`) and
prints one Markdown column per file. Every share is of the whole program's
instructions (process start-up and the initial state included). "Inside the
RHS" is the inclusive cost of `Rtw::dynamics` and `dynamics_into`, the
right-hand side (its `sin_cos` included); everything else is outside it. Made by
`scripts/hot_path.sh` (which builds the profile example and runs callgrind).
"""
import re
import subprocess
import sys

LINE = re.compile(r"^\s*([\d,]+) \([ \d.]+%\)\s+([<*>]?)\s*(.*)$")


def blocks(path):
    """(function, inclusive cost, {caller: cost}) for every function."""
    out = subprocess.run(
        ["callgrind_annotate", "--inclusive=yes", "--tree=caller", "--threshold=100", path],
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    total = None
    callers = {}
    for line in out.splitlines():
        m = LINE.match(line)
        if not m:
            if not line.strip():
                callers = {}
            continue
        cost, mark, name = int(m.group(1).replace(",", "")), m.group(2), m.group(3)
        if name.startswith("PROGRAM TOTALS"):
            total = cost
        elif mark == "<":
            callers[name] = callers.get(name, 0) + cost
        elif mark == "*":
            yield name, cost, callers
            callers = {}
    yield "TOTAL", total, {}


def measure(path):
    fn = {}
    callers_of = {}
    for name, cost, callers in blocks(path):
        fn[name] = fn.get(name, 0) + cost
        callers_of[name] = callers

    def incl(pattern):
        return sum(c for n, c in fn.items() if re.search(pattern, n))

    def called_from(callee, caller):
        return sum(
            c
            for n, cs in callers_of.items()
            if re.search(callee, n)
            for k, c in cs.items()
            if re.search(caller, k)
        )

    total = fn["TOTAL"]
    # `dynamics` returns what `dynamics_into` writes in place (the engine's
    # call); a wrapper's call of the in-place one is counted once.
    rtw_rhs = r"::dynamics::<impl rtw_model::plant::rtw::model::Rtw>::dynamics"
    rhs = (
        incl(rtw_rhs + r" \[")
        + incl(rtw_rhs + r"_into \[")
        - called_from(rtw_rhs + r"_into \[", rtw_rhs + r" \[")
    )
    # Root finding: the guard evaluations at the iterates (`Rtw::guards`,
    # all of them, before; `Rtw::guard`, the located one, after).
    root = incl(r"HybridSystem<20_usize> for rtw_model::plant::rtw::model::Rtw>::guards \[") + incl(
        r"HybridSystem<20_usize> for rtw_model::plant::rtw::model::Rtw>::guard \["
    )
    # Step ends: the guard set from the RHS's by-products (`guards_of` called
    # from the engine, not from `Rtw::guards`).
    step_end = incl(r"<impl rtw_model::plant::rtw::model::Rtw>::guards_of \[") - called_from(
        r"<impl rtw_model::plant::rtw::model::Rtw>::guards_of \[", r"for rtw_model::plant::rtw::model::Rtw>::guards \("
    )
    # Runge–Kutta arithmetic: the tableau code inlined into the engine, and
    # the dense output.
    stages = incl(r"integrate\.rs:hybrid_ode::engine::run$") + incl(
        r"integrate::fill_dense \["
    )
    # The test for a crossing inside a step: the guards' rates at each step
    # end, and the search of the dense output where the model allows a dip.
    rates = incl(r"for rtw_model::plant::rtw::model::Rtw>::guard_rates \[")
    dips = incl(r"events::find_dip")
    resets = incl(r"for rtw_model::plant::rtw::model::Rtw>::reset \[")
    # The run's observer: its step statistics (mu_required) and, at events,
    # the energy and centre of mass before and after the reset.
    observe = incl(r"Recorder as hybrid_ode::system::Observer<20_usize,rtw_model::plant::rtw::model::Rtw>>::on_step \[") + incl(
        r"Recorder as hybrid_ode::system::Observer<20_usize,rtw_model::plant::rtw::model::Rtw>>::on_transition \["
    )
    sincos = incl(r"__sincos_fma \[")
    return {
        "instructions per run": f"{total / 1e6:.1f} M",
        "inside the RHS": pct(rhs, total),
        "outside the RHS": pct(total - rhs, total),
        "guards (step ends + root finding)": pct(step_end + root, total),
        "of which root finding": pct(root, total),
        "Runge–Kutta stage arithmetic + dense output": pct(stages, total),
        "guard rates at step ends": pct(rates, total),
        # `find_dip` is usually inlined into `locate_earliest`: its cost is
        # then inside root finding and has no name of its own (built with
        # `#[inline(never)]` it measured 3.6 % of the DP5 run).
        "search for dips inside steps": pct(dips, total) if dips else "in root finding (inlined)",
        "resets (events, energy bookkeeping)": pct(resets, total),
        "observer (statistics, mu_required, energy at events)": pct(observe, total),
        "sincos (all callers)": pct(sincos, total),
        "run cost / its RHS evaluations alone": f"{total / rhs:.2f}×",
        "RHS evaluations / steps / rejected / events": work(path),
    }


def work(path):
    """RHS evaluations / steps / rejected / events, from the profile
    example's line (`PATH.work`, written by scripts/hot_path.sh), if any."""
    try:
        line = open(path + ".work").read().split("\n")[0]
    except OSError:
        return "–"
    got = dict(re.findall(r"(rhs|steps|rejected|events) (\d+)", line))
    return " / ".join(f"{int(got[k]):,}".replace(",", " ") for k in ("rhs", "steps", "rejected", "events"))


def pct(x, total):
    return f"{100.0 * x / total:.1f} %"


def main():
    cols = [measure(p) for p in sys.argv[1:]]
    print("| | " + " | ".join(sys.argv[1:]) + " |")
    print("|---|" + "---:|" * len(cols))
    for key in cols[0]:
        print(f"| {key} | " + " | ".join(c[key] for c in cols) + " |")


if __name__ == "__main__":
    main()
