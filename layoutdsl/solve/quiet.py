"""Keep the solver's own console output off the user's terminal.

SCIP, SoPlex (SCIP's LP solver) and Pyomo's translation write from C and C++ straight to
file descriptors 1 and 2, past Python's `sys.stdout`/`sys.stderr`, so `hideOutput()` and
`display/verblevel 0` do not silence all of it. Seen on every compile before this module
existed: SoPlex's "Cannot set feasibility tolerance to small value 1e-12 without GMP -
using 1e-9." twice on the terminal (SCIP retries a numerically unstable LP with its
feasibility tolerance times 0.001; with `numerics/feastol` 1e-9 that asks SoPlex for
1e-12, below what it accepts without GMP).

`native_output_silenced()` points fds 1 and 2 at /dev/null while SCIP runs, and points
Python's `sys.stdout` and `sys.stderr` at duplicates of the real ones meanwhile, so our
own progress lines (printed by any thread) still reach the terminal. It nests and may be
entered by several threads at once: the first to enter redirects, the last to leave
restores. Before restoring, C's stdio buffers are flushed into /dev/null, so nothing
written during the solve trickles out afterwards.

Output goes to a pipe nowhere: SCIP cannot block on a full pipe (solver scouting: more
than ~64 KiB of console output through Pyomo's capture pipe deadlocked the process).
"""

from __future__ import annotations

import contextlib
import ctypes
import io
import os
import sys
import threading
from collections.abc import Iterator

_lock = threading.Lock()
_depth = 0
_saved: list[tuple[int, int]] = []
"""(fd, its duplicate) for each redirected descriptor, while silenced."""
_python_streams: list[tuple[str, object, object]] = []
"""(name in sys, original stream, replacement) for each swapped Python stream."""

_LIBC = None


def _flush_c_stdio() -> None:
    """fflush(NULL): push out whatever C code buffered, while it still goes to /dev/null."""
    global _LIBC
    try:
        if _LIBC is None:
            _LIBC = ctypes.CDLL(None)
        _LIBC.fflush(None)
    except (OSError, AttributeError):  # no C library to reach (unusual platform): nothing buffered we can flush
        pass


def _fd_of(stream) -> int | None:
    try:
        return stream.fileno()
    except (AttributeError, OSError, ValueError, io.UnsupportedOperation):
        return None


def _enter() -> None:
    global _depth
    with _lock:
        _depth += 1
        if _depth > 1:
            return
        for name in ("stdout", "stderr"):
            stream = getattr(sys, name)
            with contextlib.suppress(Exception):
                stream.flush()
        _flush_c_stdio()
        devnull = os.open(os.devnull, os.O_WRONLY)
        try:
            for fd in (1, 2):
                try:
                    copy = os.dup(fd)
                except OSError:
                    continue  # no such descriptor (a daemon without a terminal): nothing to hide
                os.dup2(devnull, fd)
                _saved.append((fd, copy))
        finally:
            os.close(devnull)
        copies = dict(_saved)
        for name, fd in (("stdout", 1), ("stderr", 2)):
            stream = getattr(sys, name)
            # only a stream writing to the redirected descriptor is swapped (pytest's capsys
            # and other in-memory streams keep working as they are)
            if fd in copies and _fd_of(stream) == fd:
                replacement = open(copies[fd], "w", buffering=1, closefd=False,  # noqa: SIM115
                                   encoding=getattr(stream, "encoding", None) or "utf-8",
                                   errors=getattr(stream, "errors", None) or "strict")
                _python_streams.append((name, stream, replacement))
                setattr(sys, name, replacement)


def _leave() -> None:
    global _depth
    with _lock:
        _depth -= 1
        if _depth > 0:
            return
        for name, original, replacement in reversed(_python_streams):
            with contextlib.suppress(Exception):
                replacement.flush()
            if getattr(sys, name) is replacement:
                setattr(sys, name, original)
            with contextlib.suppress(Exception):
                replacement.close()
        _python_streams.clear()
        _flush_c_stdio()
        for fd, copy in reversed(_saved):
            os.dup2(copy, fd)
            os.close(copy)
        _saved.clear()


@contextlib.contextmanager
def native_output_silenced() -> Iterator[None]:
    """Within: what C code writes to fds 1 and 2 is discarded; Python's prints still show."""
    _enter()
    try:
        yield
    finally:
        _leave()
