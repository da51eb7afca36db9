"""The typed boundary: results are frozen objects whose fields are the Rust
definitions', the stub ``_rtw.pyi`` says the same, options go in as typed
values, and a design's six inputs are one ``Design`` or six keywords."""

from __future__ import annotations

import ast
import json
import tomllib
import warnings
from pathlib import Path

import polars as pl
import pyarrow.parquet as pq
import pytest

import rtw
from test_design_search import CONFIG
from rtw import _rtw

ROOT = Path(__file__).resolve().parents[3]
FIG7A = dict(length=0.8, rho=2.5, alpha=0.125, fn=3.269, zeta=0.0514, phi=0.15)
STUB = ast.parse((Path(rtw.__file__).parent / "_rtw.pyi").read_text())


def stub_fields(cls: str) -> dict[str, str]:
    """The annotated fields of a class of the stub, in order, as written."""
    (node,) = [n for n in STUB.body if isinstance(n, ast.ClassDef) and n.name == cls]
    return {
        n.target.id: ast.unparse(n.annotation)
        for n in node.body
        if isinstance(n, ast.AnnAssign) and isinstance(n.target, ast.Name)
    }


def without_wall_time(d: dict) -> dict:
    return {k: v for k, v in d.items() if k != "wall_time_s"}


def test_outcome_stub_is_the_rust_row_columns() -> None:
    # Names, order, types and nullability, from rtw-scan's column table.
    assert stub_fields("Outcome") == dict(_rtw.Outcome.__annotations__)
    # The same columns as a scan file's, in order.
    names = pq.read_schema(ROOT / "results" / "paper" / "samples.parquet").names
    assert list(_rtw.Outcome.__annotations__) == names
    o = rtw.simulate(**FIG7A)
    assert list(o.to_dict()) == names
    for name, ty in _rtw.Outcome.__annotations__.items():
        v = getattr(o, name)
        assert v is None and ty.endswith("| None") or type(v).__name__ == ty.split(" ")[0], name


@pytest.mark.parametrize("cls", ["LimitCycle", "Modes", "Profile"])
def test_result_class_stub_is_the_pyclass(cls: str) -> None:
    c = getattr(_rtw, cls)
    getters = {n for n, v in vars(c).items() if type(v).__name__ == "getset_descriptor" and not n.startswith("_")}
    assert list(stub_fields(cls)) == list(c.__match_args__)
    assert set(c.__match_args__) == getters


def test_results_are_frozen_compared_by_value_and_shown() -> None:
    lc, again = rtw.limit_cycle(**FIG7A), rtw.limit_cycle(rtw.Design(**FIG7A))
    m = rtw.modal(**FIG7A)
    assert lc == again and m == rtw.modal(**FIG7A) and m != rtw.modal(**{**FIG7A, "fn": 3.0})
    for obj in (lc, m, rtw.simulate(**FIG7A)):
        with pytest.raises(AttributeError):
            obj.period = 2  # type: ignore[misc]
        with pytest.raises(TypeError):
            hash(obj)
    assert list(lc.to_dict()) == list(rtw.LimitCycle.__match_args__)
    assert lc.to_dict()["multipliers"] == lc.multipliers and isinstance(lc.multipliers[0], complex)
    assert repr(lc).startswith("LimitCycle(period=1, fixed_point=(")
    assert repr(m).startswith("Modes(s18_hz=3.269")
    out = rtw.simulate(**FIG7A)
    assert repr(out).startswith(f"Outcome(outcome='walk', failure=None, speed={out.speed!r}, f_w={out.f_w!r}")
    # Positional patterns in the fields' order.
    match lc:
        case rtw.LimitCycle(period, _, residual):
            assert (period, residual) == (1, lc.residual)


# test_design_search's small search, at a budget of 20 simulations and one reported design.
SEARCH = CONFIG.replace("budget = 300\n", "budget = 20\n").replace("report = 2\n", "report = 1\n")


def test_equal_is_the_same_result_never_the_same_timing(tmp_path) -> None:
    # Two identical runs: their results, not their wall times (machine-dependent).
    a, b = rtw.simulate(**FIG7A), rtw.simulate(**FIG7A)
    assert a == b and not a != b
    assert a != rtw.simulate(**{**FIG7A, "phi": 0.16})
    assert a != rtw.simulate(**FIG7A, t_max=10.0)
    design = {k: v for k, v in FIG7A.items() if k != "phi"}
    k = dict(**design, phi_from=0.14, phi_to=0.2)
    p, q = rtw.profile(**k), rtw.profile(**k)
    assert p.table.column("wall_time_s") != q.table.column("wall_time_s")  # what == must not see
    assert p == q and not p != q
    assert p != rtw.profile(**{**k, "phi_to": 0.21})
    assert p != rtw.profile(**k, t_max=15.0)
    cfg = tmp_path / "search.toml"
    cfg.write_text(SEARCH)
    assert rtw.design(cfg, progress=False) == rtw.design(cfg, threads=1, progress=False)
    cfg.write_text(SEARCH.replace("seed = 2", "seed = 3"))
    other = rtw.design(cfg, progress=False)
    cfg.write_text(SEARCH)
    assert other != rtw.design(cfg, progress=False)


def test_options_are_typed_values_dotted_or_nested() -> None:
    dotted = rtw.simulate(**FIG7A, options={"contact.mu": 0.9, "t_max": 5.0})
    nested = rtw.simulate(**FIG7A, options={"contact": {"mu": 0.9}}, t_max=5)
    assert without_wall_time(dotted.to_dict()) == without_wall_time(nested.to_dict())
    assert dotted.t_end <= 5.0
    # A nested dict sets its keys and keeps the table's others.
    one = rtw.simulate(**FIG7A, options={"labels.flight": 0.02, "labels.triple": 0.03})
    two = rtw.simulate(**FIG7A, options={"labels.flight": 0.02, "labels": {"triple": 0.03}})
    assert without_wall_time(one.to_dict()) == without_wall_time(two.to_dict())
    for options, needles in [
        ({"t_max": "5"}, ["simulation.t_max", '"5"']),  # a str stays a str
        ({"t_max": 10**30}, ["t_max: 1000000000000000000000000000000 is invalid", "64-bit integer"]),
        ({"t_max": object()}, ["t_max: <object", "must be a bool, int, float, str"]),
        ({"contact": {"mu": -1.0}}, ["simulation.contact.mu: -1 is invalid", "[0, 4/3]"]),
        ({"contact..mu": 1.0}, ['"contact..mu" is not an option key']),
        ({"t_max.x": 1.0}, ["simulation.t_max: invalid type: map", "must be finite and > 0"]),
    ]:
        with pytest.raises(ValueError) as e:
            rtw.simulate(**FIG7A, options=options)
        for n in needles:
            assert n in str(e.value), str(e.value)


def test_a_design_is_one_object_or_six_keywords() -> None:
    d = rtw.Design(**FIG7A)
    by_keywords = rtw.simulate(**FIG7A).to_dict()
    for out in (rtw.simulate(d), rtw.simulate(*FIG7A.values())):
        assert without_wall_time(out.to_dict()) == without_wall_time(by_keywords)
    assert rtw.trace(d, dt=0.01).num_rows == rtw.trace(**FIG7A, dt=0.01).num_rows
    with pytest.raises(TypeError, match="a Design and the input 'phi'"):
        rtw.simulate(d, phi=0.1)
    with pytest.raises(TypeError, match="missing the input.s. zeta, phi"):
        rtw.simulate(length=0.8, rho=2.5, alpha=0.125, fn=3.269)
    with pytest.raises(ValueError, match="rho: 'heavy' is invalid: must be a number"):
        rtw.Design(**{**FIG7A, "rho": "heavy"})
    with pytest.raises(AttributeError):
        d.length = 1.0  # type: ignore[misc]


def test_scan_takes_options_and_set_still_works_with_a_warning() -> None:
    smoke = ROOT / "configs" / "smoke.toml"
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        new = rtw.scan(smoke, options={"t_max": 4.0}, progress=False)
    with pytest.warns(DeprecationWarning, match="use options="):
        old = rtw.scan(smoke, set={"t_max": 4.0}, progress=False)
    assert new.drop(["wall_time_s"]).equals(old.drop(["wall_time_s"]))
    with pytest.raises(TypeError), pytest.warns(DeprecationWarning):
        rtw.scan(smoke, set={"t_max": 4.0}, options={"t_max": 4.0}, progress=False)


def test_label_is_the_models_rule_on_every_stored_stable_row() -> None:
    path = ROOT / "results" / "paper" / "samples.parquet"
    config = tomllib.loads(pq.read_metadata(path).metadata[b"rtw.config"].decode())
    labels = config.get("simulation", {}).get("labels", {})
    df = pl.read_parquet(path).with_columns(pl.col("outcome").cast(pl.Utf8))
    stable = df.filter(pl.col("outcome").is_in(rtw.STABLE_LABELS))
    assert stable.height > 500
    got = [
        rtw.label(r["nlsp"], r["tlsp"], r["flight_steps"], r["triple_steps"], options={"labels": labels})
        for r in stable.iter_rows(named=True)
    ]
    assert got == stable["outcome"].to_list()
    with pytest.raises(ValueError, match="labels.flight: 2 is invalid"):
        rtw.label(0.1, 0.0, 1.0, 0.0, options={"labels.flight": 2.0})


def test_wilson_and_labels_are_rtw_scans() -> None:
    summary = json.loads((ROOT / "results" / "paper" / "summary.json").read_text())
    for share in summary["outcomes"]:
        lo, hi = rtw.wilson(share["count"], summary["samples"])
        assert [100 * lo, 100 * hi] == pytest.approx(share["ci95"], rel=1e-12)
    assert rtw.wilson(0, 0) == (0.0, 1.0)
    with pytest.raises(ValueError, match="k: 3 is invalid: must be at most n"):
        rtw.wilson(3, 2)
    assert [s["outcome"] for s in summary["outcomes"]][: len(rtw.LABELS)] == list(rtw.LABELS)[: len(summary["outcomes"])]
    assert rtw.STABLE_LABELS == ("skip", "walk", "crawl") and rtw.FAILURE_LABELS == ("collapse", "stall")
    from rtw import draw

    assert draw.STABLE == rtw.STABLE_LABELS and draw.FAILED == rtw.FAILURE_LABELS


def test_the_python_pages_design_example_prints_what_it_says(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    import re

    text = (ROOT / "docs" / "python.md").read_text()
    (code,) = [b for b in re.findall(r"```python\n(.*?)```", text, re.S) if "rtw.Design(" in b]
    monkeypatch.chdir(ROOT)
    exec(compile(code, "docs/python.md", "exec"), {})
    (said,) = re.findall(r"# (.*)\n", code)
    assert capsys.readouterr().out.strip() == said.strip()
