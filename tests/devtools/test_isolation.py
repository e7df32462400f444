"""A benchmark row's process, and whatever it started, end with the row."""

from __future__ import annotations

import os
import subprocess
import time
from pathlib import Path

from layoutdsl.devtools.isolation import run_isolated


def _answer(value: int) -> dict:
    return {"status": "ok", "value": value}


def _start_a_search_and_hang(pid_file: str) -> dict:
    # what a compile does: a child of its own for the search; here both never finish
    search = subprocess.Popen(["sleep", "300"])
    Path(pid_file).write_text(str(search.pid))
    time.sleep(300)
    return {"status": "ok"}


def _die() -> dict:
    os._exit(7)


def _gone(pid: int) -> bool:
    """No such process, or a zombie waiting to be reaped (it no longer runs)."""
    try:
        status = Path(f"/proc/{pid}/status").read_text()
    except FileNotFoundError:
        return True
    state = next(line for line in status.splitlines() if line.startswith("State:"))
    return "Z" in state.split()[1]


def test_an_answer_comes_back_as_the_row():
    assert run_isolated(_answer, 3, limit=30.0) == {"status": "ok", "value": 3}


def test_an_overrun_kills_the_row_and_the_search_it_started(tmp_path):
    pid_file = tmp_path / "search.pid"
    began = time.monotonic()
    row = run_isolated(_start_a_search_and_hang, str(pid_file), limit=1.0)
    assert row["status"] == "killed"
    assert time.monotonic() - began < 10.0
    search = int(pid_file.read_text())
    deadline = time.monotonic() + 5.0
    while not _gone(search) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert _gone(search)


def test_a_child_that_dies_without_answering_is_a_crash_row():
    row = run_isolated(_die, limit=30.0)
    assert row["status"] == "crashed (exit 7)"
