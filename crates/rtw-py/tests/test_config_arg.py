"""A config given to rtw as a path, as its TOML text, or as a dict of its
tables is the same config: one rule in the native module decides which it
is (a str holding a newline or "=" is text), for every function that takes
one, so Python never writes a config to a temporary file to pass it on."""

from __future__ import annotations

from pathlib import Path

import pytest

import rtw

FIG7A = dict(length=0.8, rho=2.5, alpha=0.125, fn=3.269, zeta=0.0514, phi=0.15)
TEXT = "[simulation]\nt_max = 6.0\n[simulation.contact]\nmu = 0.3\n"
TABLES = {"simulation": {"t_max": 6.0, "contact": {"mu": 0.3}}}


def run(**kwargs) -> dict:
    """One run's row, without its wall time (the one column that differs between two runs)."""
    row = rtw.simulate(**FIG7A, **kwargs).to_dict()
    row.pop("wall_time_s")
    return row


def test_a_config_as_a_path_as_text_and_as_a_dict_is_one_model(tmp_path: Path) -> None:
    path = tmp_path / "c.toml"
    path.write_text(TEXT)
    by_path = run(config=path)
    assert run(config=str(path)) == by_path
    assert run(config=TEXT) == by_path
    assert run(config=TABLES) == by_path
    # The same model as the options layer gives it, and not the default's.
    assert run(options={"t_max": 6.0, "contact.mu": 0.3}) == by_path
    assert run() != by_path
    traced, by_file = rtw.trace(**FIG7A, config=TEXT, dt=0.05), rtw.trace(**FIG7A, config=path, dt=0.05)
    assert traced.equals(by_file)
    assert traced.schema.metadata[b"rtw.options"] == by_file.schema.metadata[b"rtw.options"]


def test_a_bad_config_is_named(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match=r"config: 3 is invalid: must be a path, TOML text or a dict"):
        rtw.simulate(**FIG7A, config=3)
    with pytest.raises(ValueError, match=r"config text"):
        rtw.simulate(**FIG7A, config="[simulation\nt_max = 1")
    with pytest.raises(ValueError, match=r"contact\.mu"):
        rtw.simulate(**FIG7A, config={"simulation": {"contact": {"mu": -1.0}}})


def test_a_scan_takes_a_dict_of_its_tables_as_its_text(tmp_path: Path) -> None:
    text = ('name = "tiny"\nseed = 3\nsamples = 4\n[params]\nlength = 0.8\nrho = 2.5\n'
            'alpha = { uniform = [0.05, 0.3] }\nfn = 3.269\nzeta = 0.0514\nphi = 0.15\n')
    import tomllib

    a = rtw.scan(text, progress=False)
    b = rtw.scan(tomllib.loads(text), progress=False)
    cols = ["sample_id", "alpha", "outcome", "speed"]
    assert a.select(cols).equals(b.select(cols))
