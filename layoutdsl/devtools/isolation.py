"""One benchmark measurement in a process of its own, together with what it starts.

A benchmark row (bench/bench.py, bench/generation.py) runs a whole compile in a forked
child, so that a compile that overruns, or a crash inside SCIP, costs one row and not the
run. The compile starts a child of its own for the search (layoutdsl.solve.isolated).
Killing only the row's child left that search running as an orphan, holding a core
through the rows that followed and skewing their times. So the row's child leads a
process group of its own, and the whole group is killed when the row is over.
"""

from __future__ import annotations

import multiprocessing
import os
import queue as queue_module
import signal
import time
from collections.abc import Callable
from typing import Any

POLL_SECONDS = 0.2
"""How often the parent looks whether the child died without answering."""


def _child(queue, function: Callable[..., dict], *args: Any) -> None:
    os.setpgrp()  # the row's processes form one group: see the module docstring
    try:
        queue.put(function(*args))
    except Exception as error:  # one plan's failure is a row, never the end of the run
        queue.put({"status": "error", "error": f"{type(error).__name__}: {error}"})


def run_isolated(function: Callable[..., dict], *args: Any, limit: float) -> dict:
    """function(*args) (a dict) in a forked process; after `limit` seconds without an
    answer the process and everything it started are killed and the row says "killed";
    a process that died without answering gives "crashed (exit N)"."""
    context = multiprocessing.get_context("fork")
    queue = context.Queue()
    process = context.Process(target=_child, args=(queue, function, *args))
    began = time.monotonic()
    process.start()
    row: dict | None = None
    while row is None:
        try:
            row = queue.get(timeout=POLL_SECONDS)
        except queue_module.Empty:
            if not process.is_alive():
                break
            if time.monotonic() - began > limit:
                row = {"status": "killed", "seconds": round(time.monotonic() - began, 3)}
    if row is None:
        try:  # it may have answered just before it exited
            row = queue.get(timeout=POLL_SECONDS)
        except queue_module.Empty:
            pass
    _kill_group(process.pid)
    process.join()
    if row is None:
        row = {"status": f"crashed (exit {process.exitcode})",
               "seconds": round(time.monotonic() - began, 3)}
    return row


def _kill_group(pid: int) -> None:
    """SIGKILL to the child's process group, if anything of it is left."""
    try:
        os.killpg(pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass
