"""Gaits you can watch: rtw.draw, rtw.animation and `python -m rtw animate`.

The short trace comes from the release binary (`rtw-scan simulate --trace`,
target/release/rtw-scan or $RTW_SCAN), else from rtw.trace when the compiled
package is installed; with neither the tests fail, they do not skip.
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[3]
SOURCE = ROOT / "crates/rtw-py/python"
try:
    import rtw.animation  # noqa: F401  (the installed package)

    ENV = dict(os.environ)
except ImportError:
    # The pure-Python modules straight from the checkout (no compiled part needed).
    sys.path.insert(0, str(SOURCE))
    ENV = {**os.environ, "PYTHONPATH": os.pathsep.join(filter(None, [str(SOURCE), os.environ.get("PYTHONPATH")]))}

from PIL import Image  # noqa: E402
from rtw import animation  # noqa: E402
from rtw.animation import animate, frame_times  # noqa: E402
from rtw.draw import Geometry, GeometryError, Trace, check_geometry  # noqa: E402

# Tests that build an animation only to count its frames do not render it.
pytestmark = pytest.mark.filterwarnings("ignore:Animation was deleted without rendering")

FIG7A = dict(length=0.8, rho=2.5, alpha=0.125, fn=3.269, zeta=0.0514, phi=0.15)
# Two seconds of the Fig. 7(a) walk, sampled every 10 ms (events recorded as well).
T_MAX, DT = 2.0, 0.01


@pytest.fixture(scope="module")
def run(tmp_path_factory) -> tuple[Path, dict]:
    """A short trace file and the run's metrics."""
    path = tmp_path_factory.mktemp("trace") / "walk.parquet"
    binary = Path(os.environ.get("RTW_SCAN", ROOT / "target/release/rtw-scan"))
    if binary.is_file():
        args = [str(binary), "simulate", *(a for k, v in FIG7A.items() for a in (f"--{k}", str(v))),
                "--set", f"t_max={T_MAX}", "--set", f"trace_dt={DT}", "--json", "--trace", str(path)]
        out = subprocess.run(args, check=True, capture_output=True, text=True)
        return path, json.loads(out.stdout)
    try:
        import pyarrow.parquet as pq
        import rtw._rtw  # noqa: F401
    except ImportError:
        pytest.fail(f"no trace source: build {binary} (cargo build --release -p rtw-scan) or install the package")
    import rtw as pkg

    options = {"t_max": T_MAX}
    pq.write_table(pkg.trace(**FIG7A, options=options, dt=DT), path)
    return path, pkg.simulate(**FIG7A, options=options).to_dict()


def test_design_from_the_trace_metadata_is_the_models(run):
    path, m = run
    trace = Trace.read(path)
    d = trace.design
    assert (d.length, d.phi) == (FIG7A["length"], FIG7A["phi"])
    assert math.isclose(d.r, m["r"], rel_tol=1e-12)
    # The default variant's strings (docs/model.md §9): prestressed, slack when short.
    assert d.rest_length_ratio == 0.8875 and d.slack
    # Feet on the ground and the strings' energy exactly the trace's, with the run's k ...
    check_geometry(trace, m["k"])
    # ... and the fitted k is the run's.
    assert math.isclose(check_geometry(trace), m["k"], rel_tol=1e-9)


def test_a_wrong_geometry_is_refused(run):
    path, m = run
    trace = Trace.read(path)
    with pytest.raises(GeometryError, match="energy"):
        check_geometry(Trace.read(path, Geometry(**{**trace.design.__dict__, "r": 0.99 * trace.design.r})))
    with pytest.raises(GeometryError, match="energy"):
        check_geometry(trace, 1.01 * m["k"])
    # A foot said to be in contact while it is in the air.
    lifted = Trace.read(path)
    lifted.y = lifted.y + 0.01 * (lifted.contact != 0)
    with pytest.raises(GeometryError, match="off the ground"):
        check_geometry(lifted, m["k"])


def test_frame_count_rule(run):
    path, _ = run
    trace = Trace.read(path)
    # floor(duration·fps/speed) + 1 frames, frame k at start + k·speed/fps.
    anim = animate(trace, fps=10, speed=1.0, start=0.2, duration=0.5)
    assert anim.frame_count == 6
    np.testing.assert_allclose(anim.times, 0.2 + 0.1 * np.arange(6))
    assert animate(trace, fps=25, speed=0.5, start=1.0, duration=0.3).frame_count == 16
    assert animate(trace, fps=25, speed=2.0, start=1.0, duration=0.3).frame_count == 4
    # The whole trace by default.
    whole = animate(trace, fps=20)
    assert whole.frame_count == math.floor((trace.t[-1] - trace.t[0]) * 20) + 1
    assert whole._save_count == whole.frame_count  # what FuncAnimation renders
    # Each frame draws the sample nearest its time.
    assert np.all(np.abs(trace.t[anim.samples] - anim.times) <= DT / 2 + 1e-12)


def test_tables_without_metadata_need_the_design(run):
    path, _ = run
    import pandas as pd
    import polars as pl

    design = Trace.read(path).design
    for frame in (pl.read_parquet(path), pd.read_parquet(path)):
        with pytest.raises(ValueError, match="design"):
            animate(frame)
        assert animate(frame, design=design, fps=10, duration=0.2).frame_count == 3


def test_saved_gif_has_the_frames_and_the_feet_stand_on_the_ground(run, tmp_path):
    path, _ = run
    anim = animate(path, fps=10, speed=1.0, start=1.0, duration=0.6)
    out = tmp_path / "walk.gif"
    anim.save(out)
    with Image.open(out) as gif:
        assert gif.n_frames == anim.frame_count == 7
        assert gif.size == (480, 270)
    # Every foot the trace has in contact is drawn, on the drawn ground line.
    trace, star = anim.trace, anim.star
    seen = 0
    for k in range(anim.frame_count):
        anim._draw(k)
        i = anim.samples[k]
        feet = np.concatenate([np.column_stack(a.get_data()) for a in (star.stick, star.slide)])
        assert len(feet) == np.count_nonzero(trace.contact[:, i])
        (x0, x1), (y0, y1) = star.ground.get_data()
        # Distance of each foot from the ground line through (x0, y0), (x1, y1).
        normal = np.array([y0 - y1, x1 - x0]) / math.hypot(x1 - x0, y1 - y0)
        assert np.all(np.abs((feet - [x0, y0]) @ normal) < 1e-9)
        assert anim.label.get_text().startswith(f"t = {trace.t[i]:.2f} s  ")
        seen += len(feet)
    assert seen > 0


def test_inline_html(run):
    path, _ = run
    html = animate(path, fps=10, start=0.5, duration=0.2)._repr_html_()
    assert "<script" in html and html.count("data:image/png;base64") == 3


def test_mp4_without_ffmpeg_is_a_clear_error(run, tmp_path, monkeypatch):
    path, _ = run
    monkeypatch.setattr(animation.shutil, "which", lambda name: None)
    with pytest.raises(RuntimeError, match="ffmpeg"):
        animate(path, fps=10, duration=0.2).save(tmp_path / "walk.mp4")


@pytest.mark.skipif(animation.shutil.which("ffmpeg") is None or animation.shutil.which("ffprobe") is None,
                    reason="ffmpeg/ffprobe not on PATH (the error without them is tested above)")
def test_mp4_has_the_frames(run, tmp_path):
    path, _ = run
    anim = animate(path, fps=25, start=1.0, duration=0.4)
    out = tmp_path / "walk.mp4"
    anim.save(out)
    probe = subprocess.run(["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
                            "stream=nb_read_frames,width", "-of", "csv=p=0", str(out)],
                           check=True, capture_output=True, text=True)
    assert probe.stdout.strip() == f"480,{anim.frame_count}" and anim.frame_count == 11


def test_api_errors_name_the_argument(run):
    path, _ = run
    for kwargs, name in (({"fps": 0}, "fps"), ({"speed": -1}, "speed"), ({"start": -5}, "start"),
                         ({"duration": 1e3}, "duration"), ({"fps": float("nan")}, "fps"), ({"width": 20}, "width")):
        with pytest.raises(ValueError, match=f"^{name} must"):
            animate(path, **kwargs)
    with pytest.raises(ValueError, match="duration must be in \\[0, 1\\]"):
        frame_times(0.0, 2.0, start=1.0, duration=1.5)


def cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "rtw", *args], capture_output=True, text=True, env=ENV,
                          cwd=ROOT)


def test_cli_writes_the_gif(run, tmp_path):
    path, _ = run
    out = tmp_path / "cli.gif"
    res = cli("animate", str(path), str(out), "--fps", "20", "--speed", "0.5", "--start", "1",
              "--duration", "0.2", "--width", "320")
    assert res.returncode == 0, res.stderr
    with Image.open(out) as gif:
        assert gif.n_frames == 9  # floor(0.2·20/0.5) + 1
        assert gif.size[0] == 320


@pytest.mark.parametrize("flags, named", [
    (["--fps", "0"], "--fps must be in [1, 100]"),
    (["--fps", "x"], "--fps must be a number"),
    (["--speed", "0"], "--speed must be in [0.01, 100]"),
    (["--start", "99"], "--start must be in [0, "),
    (["--start", "1.5", "--duration", "1"], "--duration must be in [0, {rest:g}]"),
    (["--width", "100000"], "--width must be in [160, 1920]"),
])
def test_cli_bad_flags_name_the_flag(run, tmp_path, flags, named):
    path, _ = run
    out = tmp_path / "bad.gif"
    res = cli("animate", str(path), str(out), *flags)
    assert res.returncode == 2
    assert named.format(rest=Trace.read(path).t[-1] - 1.5) in res.stderr
    assert not out.exists()


def test_cli_bad_files(run, tmp_path):
    path, _ = run
    res = cli("animate", str(path), str(tmp_path / "walk.avi"))
    assert res.returncode == 2 and "OUT must end in .gif or .mp4" in res.stderr
    res = cli("animate", str(tmp_path / "missing.parquet"), str(tmp_path / "walk.gif"))
    assert res.returncode == 2 and "missing.parquet does not exist" in res.stderr
