"""What rtw's functions take: a yes/no argument is True or False, never a
value Python would call truthy (``force="no"`` is not ``force=True``); a
number is a number, never its text; and the checks are made once, where the
library makes them."""

from __future__ import annotations

import inspect
import subprocess
import sys
from pathlib import Path

import pytest

import rtw
from test_design_search import CONFIG

ROOT = Path(__file__).resolve().parents[3]
SCAN = ROOT / "results/paper"
FIG7A = dict(length=0.8, rho=2.5, alpha=0.125, fn=3.269, zeta=0.0514)
# test_design_search's small search, at a budget of 8 simulations and one reported design.
SEARCH = CONFIG.replace("budget = 300\n", "budget = 8\n").replace("report = 2\n", "report = 1\n")
NOT_BOOLS = ["no", "", 0, 1, 1.0, None, b"yes", [True]]


def _functions():
    """Every public function of the package, with its name."""
    for name in rtw.__all__:
        f = getattr(rtw, name)
        if inspect.isfunction(f):
            yield name, f


def _bool_parameters() -> set[str]:
    """`function.parameter` for every parameter of the package's functions annotated bool."""
    found = set()
    for name, f in _functions():
        for p in inspect.signature(f).parameters.values():
            if "bool" in str(p.annotation):
                found.add(f"{name}.{p.name}")
    return found


def test_every_boolean_parameter_of_the_package_is_checked_here() -> None:
    # A new bool parameter must be added to the cases below.
    assert _bool_parameters() == {
        "design.force",
        "report.force",
        "scan.progress",
        "basin.progress",
        "design.progress",
        "report.progress",
        "sensitivity.progress",
    }


@pytest.mark.parametrize("value", NOT_BOOLS)
def test_force_takes_true_or_false_only_and_a_search_folder_is_kept(value, tmp_path) -> None:
    cfg = tmp_path / "search.toml"
    cfg.write_text(SEARCH)
    out = tmp_path / "theirs"
    other = tmp_path / "other.toml"
    other.write_text(SEARCH.replace("seed = 2", "seed = 3"))
    rtw.design(other, out=out, progress=False)
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    with pytest.raises(ValueError, match="holds the search"):
        rtw.design(cfg, out=out, force=False, progress=False)
    with pytest.raises(ValueError) as e:
        rtw.design(cfg, out=out, force=value, progress=False)
    assert str(e.value) == f"force: {value!r} is invalid: must be True or False"
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before


@pytest.mark.parametrize("value", NOT_BOOLS)
def test_report_force_takes_true_or_false_only_and_a_users_file_is_kept(value, tmp_path) -> None:
    mine = tmp_path / "user.html"
    mine.write_text("<p>my notes</p>")
    with pytest.raises(ValueError) as e:
        rtw.report(SCAN, out=mine, force=value, per_outcome=0, progress=False)
    assert str(e.value) == f"force: {value!r} is invalid: must be True or False"
    assert mine.read_text() == "<p>my notes</p>"


@pytest.mark.parametrize(
    "call",
    [
        lambda v, tmp: rtw.scan(ROOT / "configs/smoke.toml", progress=v),
        lambda v, tmp: rtw.basin(**FIG7A, phi=0.15, x="omega_a:-1:1:2", y="theta_b:-0.1:0.1:2", progress=v),
        lambda v, tmp: rtw.design(ROOT / "configs/smoke.toml", progress=v),
        lambda v, tmp: rtw.report(SCAN, out=tmp / "r.html", per_outcome=0, progress=v),
        lambda v, tmp: rtw.sensitivity(SCAN, progress=v),
    ],
    ids=["scan", "basin", "design", "report", "sensitivity"],
)
@pytest.mark.parametrize("value", ["no", 0, None])
def test_progress_takes_true_false_or_a_callable_only(call, value, tmp_path) -> None:
    with pytest.raises(ValueError) as e:
        call(value, tmp_path)
    assert str(e.value) == f"progress: {value!r} is invalid: must be True, False or a callable"
    assert not (tmp_path / "r.html").exists()


@pytest.mark.parametrize("name", ["phi_from", "phi_to", "tol", "grid"])
@pytest.mark.parametrize("value", ["0.05", b"0.05", None, True, [0.05]])
def test_profile_takes_numbers_only_naming_the_argument(name, value) -> None:
    kwargs = dict(phi_from=0.05, phi_to=0.3, tol=1e-3, grid=0.01) | {name: value}
    with pytest.raises(ValueError) as e:
        rtw.profile(**FIG7A, **kwargs)
    assert str(e.value) == f"{name}: {value!r} is invalid: must be a number"


@pytest.mark.parametrize("value", ["1e-3", b"1e-3", None, True])
def test_basin_tol_takes_numbers_only_naming_it(value) -> None:
    with pytest.raises(ValueError) as e:
        rtw.basin(**FIG7A, phi=0.15, x="omega_a:-1:1:2", y="theta_b:-0.1:0.1:2", tol=value, progress=False)
    assert str(e.value) == f"tol: {value!r} is invalid: must be a number"


@pytest.mark.parametrize("name", ["nlsp", "tlsp", "flight_steps", "triple_steps"])
@pytest.mark.parametrize("value", ["0.5", b"0.5", None, True])
def test_label_takes_numbers_only_naming_the_argument(name, value) -> None:
    kwargs = dict(nlsp=0.0, tlsp=0.0, flight_steps=0.0, triple_steps=0.0) | {name: value}
    with pytest.raises(ValueError) as e:
        rtw.label(**kwargs)
    assert str(e.value) == f"{name}: {value!r} is invalid: must be a number"


def test_a_number_is_still_taken_as_it_was() -> None:
    np = pytest.importorskip("numpy")
    p = rtw.profile(**FIG7A, phi_from=np.float64(0.14), phi_to=0.16, tol=np.float32(0.005), grid=0.02)
    assert p.runs >= 2
    assert rtw.label(0, 0, 0, 0) == rtw.label(np.float64(0), 0.0, 0, 0) == "walk"


@pytest.mark.parametrize(
    "value, shown",
    [(0, "0"), (10_000_001, "10000001"), (-1, "-1"), (True, "True"), ("60", "'60'"), (2.5, "2.5"), (None, "None")],
)
def test_settle_steps_is_checked_once_naming_it_its_range_and_the_value(value, shown) -> None:
    with pytest.raises(ValueError) as e:
        rtw.limit_cycle(**FIG7A, phi=0.15, settle_steps=value)
    assert str(e.value) == f"settle_steps: {shown} is invalid: must be an integer in [1, 10000000]"


def test_an_absurd_count_raises_in_python_it_does_not_abort_it() -> None:
    # The report's density grids, one per group of a byte's values: a count
    # sized their allocation, which aborted the interpreter.
    code = "from rtw import _rtw\ntry:\n    _rtw.density_grid(b'', 10**15, b'', b'')\nexcept ValueError as e:\n    print(e)\n"
    o = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert (o.returncode, o.stdout.strip()) == (0, "groups: 1000000000000000 is invalid: must be at most 256 (a group "
                                                   "is one byte)"), o.stderr[-2000:]


@pytest.mark.parametrize("value", ["1.96", b"1.96", None, True])
def test_wilson_z_takes_numbers_only_naming_it(value) -> None:
    with pytest.raises(ValueError) as e:
        rtw.wilson(3, 10, value)
    assert str(e.value) == f"z: {value!r} is invalid: must be a number"
