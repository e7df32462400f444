"""A long SCIP search in a child process, so a crash inside SCIP costs the search, not the compile.

SCIP 10 (through PySCIPOpt 6) aborts now and then deep into a long branch-and-bound on
L-room models: `free(): invalid size`, SIGABRT, the whole Python process gone with the
verified layout it already had (measured: office_324-Elm-Furn-Plan imported with its
L-rooms, compile seed 0, after about 55 s of search, every run). The search is an
improvement on a layout the compile already holds, so it runs in a forked child: the
child sends its outcome and the variables' values back through a pipe; when it dies
instead, the parent gets a 'solver_crashed' outcome without a solution and keeps what it had.

A child can also hang instead of dying: measured on school_RomainRolland1 and
office_324-Elm-Furn-Plan, glibc's `malloc(): invalid size` abort left the child's two
threads (SCIP's and the progress ticker) waiting on each other's locks for good. The
parent therefore waits at most the search's time limit plus a grace (child_grace), then
kills the child and reports the crash, saying which of the two happened (`crash_detail`).

The grace used to be a flat 5 s, and a child that was merely slow was reported as hung:
the child translates the model, SCIP overshoots its limit by up to an LP solve, and the
model is freed, all before it answers. Measured on school_wilbraham (52 rooms, kept
arrangement) at a load of 5.5 on 2 cores: a search given 0.5 s answered after 3.3 s. With
8 processes on 2 cores such a child passes 5 s, and the compile said "the solver's search
aborted or hung (a crash inside SCIP)" although nothing had crashed. The grace now grows
with the search's limit and the model's size (child_grace).

Forking is safe only while the process has no other thread (a lock another thread holds
stays held in the child); otherwise, and where there is no fork (Windows), the search runs
in this process as before. The progress callback runs in the child: lines it prints reach
the same stderr; state it keeps stays in the child.
"""

from __future__ import annotations

import os
import pickle
import select
import signal
import threading
import time

import pyomo.environ as pyo

from layoutdsl.solve import ProgressCallback, SolveOptions, SolveOutcome, solve

SOLVER_CRASHED = "solver_crashed"
"""The status of a search whose child process died (SCIP aborted or was killed) or hung."""

CHILD_GRACE_SECONDS = 10.0
"""Seconds past the search's time limit the parent waits at least for the child's answer:
SCIP's own wall-clock guard stops it within about a second (solve.GUARD_GRACE_SECONDS) on
an idle machine; translating and freeing a large model and the machine's load add the rest
(see child_grace)."""


def child_grace(time_limit: float, variables: int) -> float:
    """Seconds past `time_limit` before a silent child counts as hung: CHILD_GRACE_SECONDS,
    plus a quarter of the limit (an LP solve SCIP cannot interrupt grows with the search),
    plus a second per 5000 variables (translating and freeing the model; a 52-room model
    has about 12 000)."""
    return CHILD_GRACE_SECONDS + 0.25 * max(0.0, time_limit) + variables / 5000


def can_isolate() -> bool:
    """Whether a search can run in a forked child here (fork exists, no other thread runs)."""
    return hasattr(os, "fork") and threading.active_count() == 1


def solve_isolated(
    model: pyo.ConcreteModel,
    options: SolveOptions,
    *,
    progress: ProgressCallback | None = None,
    warm_start: bool = False,
) -> SolveOutcome:
    """`solve(model, options, ...)` in a forked child; the best solution is loaded on the model.

    Returns an outcome with status SOLVER_CRASHED (and no solution) when the child dies.
    """
    if not can_isolate():
        return solve(model, options, progress=progress, warm_start=warm_start)
    variables = list(model.component_data_objects(pyo.Var, descend_into=True))
    started = time.monotonic()
    read_end, write_end = os.pipe()
    pid = os.fork()
    if pid == 0:  # the child: solve, send, and leave without running the parent's cleanup
        os.close(read_end)
        code = 0
        try:
            outcome = solve(model, options, progress=progress, warm_start=warm_start)
            values = [v.value for v in variables] if outcome.has_solution else None
            message = pickle.dumps(("done", outcome, values))
        except KeyboardInterrupt:
            message = pickle.dumps(("interrupted", None, None))
        except BaseException as error:  # noqa: BLE001  (re-raised in the parent)
            try:
                message = pickle.dumps(("error", error, None))
            except Exception:  # noqa: BLE001  (an error that does not pickle: its text)
                message = pickle.dumps(("error", RuntimeError(f"the solver's child process failed: {error!r}"), None))
        try:
            with os.fdopen(write_end, "wb") as pipe:
                pipe.write(message)
        except BaseException:  # noqa: BLE001
            code = 1
        os._exit(code)
    os.close(write_end)
    try:
        data = _read_until(read_end, started + options.time_limit + child_grace(options.time_limit, len(variables)))
    except KeyboardInterrupt:
        _kill(pid)
        raise
    finally:
        os.close(read_end)
    if data is None:  # the child hangs: it will not answer
        _kill(pid)
        seconds = time.monotonic() - started
        return SolveOutcome(status=SOLVER_CRASHED, has_solution=False, seconds=seconds,
                            wall_clock_limited=True,
                            crash_detail=f"no answer {seconds - options.time_limit:.1f} s past its "
                                         f"{options.time_limit:.1f} s limit: killed")
    _, wait_status = os.waitpid(pid, 0)
    try:
        kind, outcome, values = pickle.loads(data)
    except Exception:  # noqa: BLE001  (nothing or a torn message: the child died)
        return SolveOutcome(status=SOLVER_CRASHED, has_solution=False,
                            seconds=time.monotonic() - started, crash_detail=_death(wait_status))
    if kind == "interrupted":
        raise KeyboardInterrupt
    if kind == "error":
        raise outcome  # as the search in this process would have raised it
    if values is not None:
        for variable, value in zip(variables, values):
            variable.set_value(value, skip_validation=True)
    return outcome


def _read_until(fd: int, deadline: float) -> bytes | None:
    """Everything written to the pipe until its writer closes it, or None at the deadline."""
    chunks: list[bytes] = []
    while True:
        left = deadline - time.monotonic()
        if left <= 0:
            return None
        ready, _, _ = select.select([fd], [], [], left)
        if not ready:
            continue
        chunk = os.read(fd, 1 << 16)
        if not chunk:
            return b"".join(chunks)
        chunks.append(chunk)


def _death(wait_status: int) -> str:
    """How the child ended, in words ('killed by SIGABRT', 'exit code 1')."""
    if os.WIFSIGNALED(wait_status):
        number = os.WTERMSIG(wait_status)
        try:
            name = signal.Signals(number).name
        except ValueError:
            name = f"signal {number}"
        return f"killed by {name}"
    return f"exit code {os.WEXITSTATUS(wait_status)} without an answer"


def _kill(pid: int) -> None:
    os.kill(pid, signal.SIGKILL)
    os.waitpid(pid, 0)
