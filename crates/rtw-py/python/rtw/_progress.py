"""The ``progress=`` of every rtw function that can take long, drawn by tqdm.

``progress=True`` draws a tqdm bar on stderr: redrawn in place on a
terminal or in a notebook (ipykernel's stream draws ``\\r`` too), and on any
other stream (a log, a pipe), where ``\\r`` would pile up, a plain tqdm
status line every 10 s and at the end. ``False`` draws nothing; a callable
gets ``(done, total)`` as the library reports them.
"""

from __future__ import annotations

import sys
import time
from typing import Any, Callable, TextIO

from tqdm.std import tqdm

Observer = Callable[[int, int], object]

# tqdm's own look, with the rate always as units per second.
BAR = "{l_bar}{bar}| {n_fmt}/{total_fmt} [{elapsed}<{remaining}, {rate_noinv_fmt}]"
LINE = "{desc}: {n_fmt}/{total_fmt} ({percentage:.0f}%) [{elapsed}<{remaining}, {rate_noinv_fmt}]"
REDRAW = 0.1  # s between redraws in place
LOG_EVERY = 10.0  # s between lines in a log


class _Lines(tqdm):  # type: ignore[misc]
    """tqdm for a stream that cannot redraw a line: each refresh is a line of its own."""

    def display(self, msg: str | None = None, pos: int | None = None) -> bool:
        if msg == "":  # tqdm clearing its line on close: a log keeps its lines
            return False
        self.fp.write(f"{self if msg is None else msg}\n")
        self.fp.flush()
        return True


def _in_place(stream: TextIO) -> bool:
    """Whether ``\\r`` redraws a line on ``stream``: a terminal, or a notebook's output."""
    if type(stream).__module__.startswith("ipykernel"):
        return True
    try:
        return stream.isatty()
    except (AttributeError, ValueError):
        return False


class Progress:
    """What ``progress=`` asks for, checked when made; ``with`` it to get the
    observer to hand to ``_rtw`` (None for nothing), and the bar is closed
    however the call ends."""

    def __init__(self, progress: bool | Observer, name: str, unit: str) -> None:
        if isinstance(progress, bool):
            self.show, self.observer = progress, None
        elif callable(progress):
            self.show, self.observer = False, progress
        else:
            raise ValueError(f"progress: {progress!r} is invalid: must be True, False or a callable")
        self.name, self.unit = name, unit
        self.bar: tqdm | None = None
        self.finished = False

    def __enter__(self) -> Observer | None:
        if self.observer is not None:
            return self.observer
        self.stream = sys.stderr
        self.started = time.time()  # tqdm's clock
        return self.update if self.show and self.stream is not None else None

    def __exit__(self, *exc: Any) -> None:
        self.close()

    def update(self, done: int, total: int) -> None:
        if self.finished or total <= 0:  # drawn to its end already, or nothing to count
            return
        if self.bar is None:
            in_place = _in_place(self.stream)
            self.bar = (tqdm if in_place else _Lines)(
                total=total,
                desc=self.name,
                unit=self.unit,
                file=self.stream,
                bar_format=BAR if in_place else LINE,
                mininterval=REDRAW if in_place else LOG_EVERY,
                # A log keeps its lines as they are: no last line drawn again on close.
                leave=in_place,
                # A log's lines give the mean rate so far; a bar tqdm's smoothed one.
                smoothing=0.3 if in_place else 0.0,
            )
            # The first count comes a while after the call began: its times run from the call.
            self.bar.start_t = self.started
            if (self.bar.ncols or 0) <= 0:
                # A terminal of no size (a bare pseudo-terminal): tqdm would
                # draw nothing; its defaults for a stream of unknown size.
                self.bar.ncols = self.bar.nrows = None
        if self.bar.total != total:
            self.bar.total = total
        self.bar.update(done - self.bar.n)
        if done >= total:
            self.finished = True
            self.close()

    def close(self) -> None:
        bar, self.bar = self.bar, None
        if bar is None:
            return
        if isinstance(bar, _Lines) and bar.last_print_n != bar.n:
            bar.refresh()  # a log's last line: where the run ended
        bar.close()
