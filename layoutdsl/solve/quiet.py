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
                replacement = _Passthrough(stream, copies[fd])
                _python_streams.append((name, stream, replacement))
                setattr(sys, name, replacement)


def _leave() -> None:
    global _depth
    with _lock:
        _depth -= 1
        if _depth > 0:
            return
        for name, original, replacement in reversed(_python_streams):
            replacement.detach_copy()  # from now on it writes to the original stream
            if getattr(sys, name) is replacement:
                setattr(sys, name, original)
        _python_streams.clear()
        _flush_c_stdio()
        for fd, copy in reversed(_saved):
            os.dup2(copy, fd)
            os.close(copy)
        _saved.clear()


class _Passthrough(io.TextIOBase):
    """sys.stdout/sys.stderr while silenced: writes go to the duplicate of the real
    descriptor; once the silence ends, to the original stream. A reference kept past the
    silence (a logging handler created meanwhile, a thread's `file=` argument) keeps
    working, and is never left holding a closed or reused descriptor."""

    def __init__(self, original, copy_fd: int):
        super().__init__()
        self._original = original
        self._copy: int | None = copy_fd
        self._encoding = getattr(original, "encoding", None) or "utf-8"
        self._errors = getattr(original, "errors", None) or "replace"

    @property
    def encoding(self) -> str:  # type: ignore[override]
        return self._encoding

    def writable(self) -> bool:
        return True

    def write(self, text: str) -> int:
        copy = self._copy
        if copy is None:
            return self._original.write(text)
        data = text.encode(self._encoding, self._errors)
        while data:
            try:
                written = os.write(copy, data)
            except OSError:
                return self._original.write(text)  # the copy went away: the stream as it is
            data = data[written:]
        return len(text)

    def flush(self) -> None:
        if self._copy is None:
            with contextlib.suppress(Exception):
                self._original.flush()

    def isatty(self) -> bool:
        return bool(getattr(self._original, "isatty", lambda: False)())

    def fileno(self) -> int:
        return self._original.fileno()

    def detach_copy(self) -> None:
        self._copy = None


@contextlib.contextmanager
def native_output_silenced() -> Iterator[None]:
    """Within: what C code writes to fds 1 and 2 is discarded; Python's prints still show."""
    _enter()
    try:
        yield
    finally:
        _leave()
