"""rtw.profile is `rtw-scan profile`: the same library entry point, the same
profile, the same refusals in the same words (the CLI's `--from` is
Python's `phi_from`, `--to` is `phi_to`, `--alpha` is `alpha`)."""

from __future__ import annotations

import json
import re
import subprocess

import pyarrow as pa
import pyarrow.parquet as pq
import pytest
from test_same_checks import BINARY, cli_error, python_error

import rtw

FIG7A = dict(length=0.8, rho=2.5, alpha=0.125, fn=3.269, zeta=0.0514)
FLAGS = ["--length", "0.8", "--rho", "2.5", "--alpha", "0.125", "--fn", "3.269", "--zeta", "0.0514"]


def test_profile_equals_the_cli_profile_and_its_file(tmp_path) -> None:
    out = tmp_path / "p.parquet"
    cli = json.loads(
        subprocess.run(
            [str(BINARY), "profile", *FLAGS, "--from", "0.05", "--to", "0.3", "--json", "--quiet", "--out", str(out)],
            check=True,
            capture_output=True,
            text=True,
        ).stdout
    )
    p = rtw.profile(**FIG7A, phi_from=0.05, phi_to=0.3)
    assert isinstance(p, rtw.Profile)
    assert (p.phi_min, p.phi_lo, p.phi_hi, p.runs) == (cli["phi_min"], cli["phi_lo"], cli["phi_hi"], cli["runs"])
    assert {g: [list(i) for i in v] for g, v in p.intervals.items()} == cli["intervals"]
    assert [list(i) for i in p.stable_intervals] == cli["stable_intervals"]
    want = [(c["phi_left"], c["phi_right"], c["label_left"], c["label_right"], c["sharp"]) for c in cli["changes"]]
    assert list(p.changes) == want
    for lo, hi, left, right, _ in p.changes:
        assert 0 < hi - lo <= 1e-3 and left != right
    # The table is the file's rows (the runs' own wall times aside).
    assert isinstance(p.table, pa.Table) and p.table.num_rows == p.runs
    file = pq.read_table(out)
    assert p.table.schema.equals(file.schema, check_metadata=False)
    assert p.table.drop_columns(["wall_time_s"]).to_pylist() == file.drop_columns(["wall_time_s"]).to_pylist()
    phi = p.table.column("phi").to_pylist()
    assert phi == sorted(phi) and (phi[0], phi[-1]) == (0.05, 0.3)
    # A Design's phi is not used: the slope is the profile's axis.
    again = rtw.profile(rtw.Design(**FIG7A, phi=0.2), phi_from=0.05, phi_to=0.3)
    assert again.to_dict() | {"table": None} == p.to_dict() | {"table": None}
    assert again.table.drop_columns(["wall_time_s"]).equals(p.table.drop_columns(["wall_time_s"]))
    with pytest.raises(TypeError, match="takes no phi"):
        rtw.profile(**FIG7A, phi=0.1, phi_from=0.05, phi_to=0.3)


def as_python(cli: str) -> str:
    """A CLI message in Python's spelling."""
    return re.sub(r"--to\b", "phi_to", cli.replace("--from", "phi_from")).replace("--", "")


@pytest.mark.parametrize(
    "flags, kwargs",
    [
        (["--from", "0.3", "--to", "0.05"], dict(phi_from=0.3, phi_to=0.05)),
        (["--from", "-2", "--to", "0.3"], dict(phi_from=-2, phi_to=0.3)),
        (["--from", "0.05", "--to", "1.6"], dict(phi_from=0.05, phi_to=1.6)),
        (["--from", "0.05", "--to", "0.3", "--tol", "0"], dict(phi_from=0.05, phi_to=0.3, tol=0)),
        (["--from", "0.05", "--to", "0.3", "--tol", "0.02"], dict(phi_from=0.05, phi_to=0.3, tol=0.02)),
        (["--from", "0.05", "--to", "0.3", "--grid", "1"], dict(phi_from=0.05, phi_to=0.3, grid=1)),
        (["--from", "0.05", "--to", "0.3", "--threads", "0"], dict(phi_from=0.05, phi_to=0.3, threads=0)),
    ],
)
def test_a_bad_setting_gets_the_clis_refusal(flags: list[str], kwargs: dict) -> None:
    cli = cli_error("profile", *FLAGS, *flags)
    py = python_error(lambda: rtw.profile(**FIG7A, **kwargs))
    assert py == as_python(cli)


def test_a_bad_design_gets_the_clis_refusal() -> None:
    flags = [*FLAGS]
    flags[5] = "0.6"
    cli = cli_error("profile", *flags, "--from", "0.05", "--to", "0.3")
    py = python_error(lambda: rtw.profile(**{**FIG7A, "alpha": 0.6}, phi_from=0.05, phi_to=0.3))
    assert py == as_python(cli) == "alpha: 0.6 is invalid: must be in [0, 0.49]"


def test_the_mfpt_along_phi_is_in_the_table_when_asked() -> None:
    options = {"robustness.mfpt": True, "robustness.sigma": 0.05}
    p = rtw.profile(**FIG7A, phi_from=0.27, phi_to=0.29, options=options)
    rows = p.table.select(["phi", "outcome", "mfpt"]).to_pylist()
    for r in rows:
        assert (r["mfpt"] is not None) == (r["outcome"] in rtw.STABLE_LABELS), r
    first = rows[0]
    assert first["mfpt"] == rtw.simulate(**FIG7A, phi=first["phi"], options=options).mfpt
