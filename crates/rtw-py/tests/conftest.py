"""Fixtures shared by the Python package's tests."""

from __future__ import annotations

import signal
from collections.abc import Iterator

import pytest


@pytest.fixture
def ctrl_c() -> Iterator[None]:
    """Python's own Ctrl-C handler for the test's duration.

    A process that a non-interactive shell started in the background (`cmd &`,
    as a CI job may be) inherits SIGINT ignored, and Python then keeps it
    ignored: `_thread.interrupt_main`, which the Ctrl-C tests use to press
    Ctrl-C, does nothing, and the test of rtw's answer to it fails for a
    reason that is not rtw's.
    """
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
