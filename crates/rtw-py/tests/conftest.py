"""Fixtures shared by the Python package's tests."""

from __future__ import annotations

import _thread
import signal
import threading
import time
from collections.abc import Callable, Iterator

import pytest

Press = Callable[[float, Callable[[], object]], float]


def _press(after: float, call: Callable[[], object]) -> float:
    """Runs `call`, pressing Ctrl-C `after` seconds in; it must raise
    KeyboardInterrupt. Returns the seconds from the start to the raise."""
    timer = threading.Timer(after, _thread.interrupt_main)
    started = time.monotonic()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            call()
        return time.monotonic() - started
    finally:
        timer.cancel()
        timer.join()


@pytest.fixture
def ctrl_c() -> Iterator[Press]:
    """Python's own Ctrl-C handler for the test's duration, and a way to press
    Ctrl-C during a call: `ctrl_c(after, call)` (seconds to the raise).

    A process that a non-interactive shell started in the background (`cmd &`,
    as a CI job may be) inherits SIGINT ignored, and Python then keeps it
    ignored: `_thread.interrupt_main`, which presses Ctrl-C here, does
    nothing, and the test of rtw's answer to it fails for a reason that is
    not rtw's.
    """
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        yield _press
    finally:
        signal.signal(signal.SIGINT, previous)
