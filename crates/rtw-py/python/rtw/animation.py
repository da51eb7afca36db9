"""Gaits you can watch: a trace as a matplotlib animation (GIF, MP4, or inline in a notebook).

    import rtw
    anim = rtw.animate("walk.parquet", fps=25, speed=0.5, start=10, duration=3)
    anim.save("walk.gif")   # or .mp4 (needs ffmpeg); in a notebook, `anim` shows itself

Frames: frame k (k = 0 … N−1) shows simulated time start + k·speed/fps, and
N = floor(duration·fps/speed) + 1, so the first and, when duration·fps/speed
is whole, the last instant of the window are both shown. Played at fps frames
a second, the gait runs `speed` times as fast as real time. Each frame draws
the trace sample nearest its time (the earlier on a tie), so the time shown is
the sample's; a trace sampled more finely than speed/fps (`--set trace_dt=…`)
moves smoothly. The drawing is rtw.draw's, the one the gait gallery uses.
"""

from __future__ import annotations

import math
import shutil
from pathlib import Path

import numpy as np
from matplotlib.animation import FFMpegWriter, FuncAnimation, PillowWriter
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from .draw import ROD_COLOR, STATE_COLOR, STATE_NAMES, Geometry, Star, Trace, state_label

FPS_RANGE = (1.0, 100.0)
SPEED_RANGE = (0.01, 100.0)
WIDTH_RANGE = (160, 1920)
# The figure's shape; its width in pixels is FIGSIZE[0] · dpi.
FIGSIZE = (6.4, 3.6)
SAVERS = {".gif": "pillow", ".mp4": "ffmpeg"}


def _finite(name: str, value) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number, got {value!r}") from None
    if not math.isfinite(v):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return v


def _in_range(name: str, value, lo: float, hi: float) -> float:
    v = _finite(name, value)
    if not lo <= v <= hi:
        raise ValueError(f"{name} must be in [{lo:g}, {hi:g}], got {v:g}")
    return v


def saver(path, name: str = "the output") -> str:
    """The writer for an output file (by its extension); raises if it cannot be written."""
    path = Path(path)
    kind = SAVERS.get(path.suffix.lower())
    if kind is None:
        raise ValueError(f"{name} must end in {' or '.join(SAVERS)}, got {path.name!r}")
    if kind == "ffmpeg" and shutil.which("ffmpeg") is None:
        raise RuntimeError(f"{name}: saving .mp4 needs ffmpeg on PATH, which is not found: install ffmpeg "
                           "(e.g. apt-get install ffmpeg) or save a .gif")
    if not path.parent.is_dir():
        raise FileNotFoundError(f"{name}: the folder {path.parent} does not exist")
    return kind


def frame_times(t_first: float, t_last: float, *, fps: float = 25, speed: float = 1.0,
                start: float | None = None, duration: float | None = None,
                names: dict[str, str] | None = None) -> np.ndarray:
    """The simulated time of every frame: start + k·speed/fps for
    k = 0 … floor(duration·fps/speed), within the trace's [t_first, t_last].
    start defaults to t_first, duration to the rest of the trace. Out-of-range
    values raise ValueError naming the argument (as `names` spells it: the CLI
    passes its flags)."""
    n = {"fps": "fps", "speed": "speed", "start": "start", "duration": "duration", **(names or {})}
    fps = _in_range(n["fps"], fps, *FPS_RANGE)
    speed = _in_range(n["speed"], speed, *SPEED_RANGE)
    start = t_first if start is None else _in_range(n["start"], start, t_first, t_last)
    rest = t_last - start
    if duration is None:
        duration = rest
    else:
        duration = _finite(n["duration"], duration)
        if not 0 <= duration <= rest:
            raise ValueError(f"{n['duration']} must be in [0, {rest:g}] (the trace ends at t = {t_last:g} s, "
                             f"the window starts at {start:g} s), got {duration:g}")
    step = speed / fps
    # The small tolerance keeps a whole number of frame steps whole despite rounding (3 s at 25 fps: 75).
    count = math.floor(duration / step + 1e-9) + 1
    return start + step * np.arange(count)


class GaitAnimation(FuncAnimation):
    """A FuncAnimation of a trace that saves itself to .gif or .mp4 and shows
    itself inline in a notebook (`_repr_html_`, matplotlib's to_jshtml)."""

    def __init__(self, trace: Trace, times: np.ndarray, fps: float, figsize=FIGSIZE, dpi: float = 75,
                 window: float | None = None, marks: float | None = 0.2):
        self.trace, self.times, self.fps = trace, times, fps
        self.samples = trace.nearest(times)
        d = trace.design
        fig = Figure(figsize=figsize, dpi=dpi)
        FigureCanvasAgg(fig)  # no pyplot: a notebook shows the animation, not a stray still
        ax = fig.add_axes((0, 0, 1, 1))
        aspect = figsize[1] / figsize[0]
        # Wide enough that the view is 1.5 L high.
        self.star = Star(ax, d, window if window is not None else 1.5 * d.length / aspect, marks=marks,
                         aspect=aspect)
        self.label = ax.text(0.02, 0.96, "", transform=ax.transAxes, va="top", fontsize=11,
                             family="monospace", fontweight="bold")
        ax.legend(handles=[
            Line2D([], [], marker="o", color="black", ls="none", label="stick"),
            Line2D([], [], marker="D", color="black", markerfacecolor="white", ls="none", label="slide"),
            *(Line2D([], [], color=ROD_COLOR[i], lw=3, label=f"rod {'abc'[i]}") for i in range(3)),
        ], loc="lower right", fontsize=7, ncol=5, frameon=False, handlelength=1.2, columnspacing=0.8)
        ax.text(0.02, 0.02, f"φ = {d.phi:g} rad, L = {d.length:g} m", transform=ax.transAxes, fontsize=7,
                color="#444444")
        super().__init__(fig, self._draw, frames=len(times), interval=1000.0 / fps, blit=False, repeat=True)

    @property
    def frame_count(self) -> int:
        return len(self.times)

    def _draw(self, k: int) -> list:
        i = int(self.samples[k])
        artists = self.star.update(self.trace, i)
        self.label.set_text(state_label(self.trace, i))
        self.label.set_color(STATE_COLOR[STATE_NAMES[self.trace.state[i]]])
        return [*artists, self.label]

    def save(self, filename, writer=None, fps=None, dpi=None, **kwargs) -> None:
        """Save as .gif (Pillow) or .mp4 (ffmpeg, which must be on PATH), at the animation's fps."""
        path = Path(filename)
        if writer is None:
            if saver(path) == "ffmpeg":
                writer = FFMpegWriter(fps=fps or self.fps, codec="h264", extra_args=["-pix_fmt", "yuv420p"])
            else:
                writer = PillowWriter(fps=fps or self.fps)
        super().save(str(path), writer=writer, dpi=dpi, **kwargs)

    def _repr_html_(self) -> str:
        return self.to_jshtml(fps=self.fps)


def animate(trace, *, fps: float = 25, speed: float = 1.0, start: float | None = None,
            duration: float | None = None, design: Geometry | None = None, width: int = 480,
            window: float | None = None, names: dict[str, str] | None = None) -> GaitAnimation:
    """Animate a trace: rods, strings, slope, each foot's contact mode
    (● stick, ◇ slide), time and contact state, following the star downhill.

    trace: a trace Parquet path, an rtw.draw.Trace, or a table with the trace
    columns (pyarrow.Table from rtw.trace, polars/pandas DataFrame; a table
    without rtw.params metadata needs `design`). fps: frames per second of
    the video, in [1, 100]; speed: simulated seconds per real second, in
    [0.01, 100]; start, duration: the window of simulated time shown (default
    the whole trace). Frame count: floor(duration·fps/speed) + 1 (module
    docstring). width: pixels, in [160, 1920]. window: the view's width in
    metres (default 1.6 L)."""
    if isinstance(trace, (str, Path)):
        trace = Trace.read(trace, design)
    elif not isinstance(trace, Trace):
        trace = Trace(trace, design)
    times = frame_times(float(trace.t[0]), float(trace.t[-1]), fps=fps, speed=speed, start=start,
                        duration=duration, names=names)
    w = _in_range((names or {}).get("width", "width"), width, *WIDTH_RANGE)
    return GaitAnimation(trace, times, float(fps), dpi=w / FIGSIZE[0], window=window)
