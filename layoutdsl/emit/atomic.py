"""Atomic file writes: a reader sees each output whole or not at all.

A file is written to a temporary sibling (same directory, so `os.replace` is a rename on one
file system, atomic on POSIX and Windows) and renamed into place. A *set* of files is
written all-or-nothing: every temporary file is written first, then all are renamed; if any
step fails, the files already renamed are rolled back to what was there before the call.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Mapping
from pathlib import Path


def _new_file_mode() -> int:
    """The permission bits a plain `open(path, "w")` would give a new file (umask applied)."""
    umask = os.umask(0o022)
    os.umask(umask)
    return 0o666 & ~umask


def _write_temp(target: Path, data: bytes) -> Path:
    """Write `data` to a new temporary file next to `target` and return its path."""
    fd, temp_name = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=target.parent)
    try:
        # mkstemp creates 0600 files; outputs should be as readable as any other file
        os.fchmod(fd, _new_file_mode())
        with os.fdopen(fd, "wb") as handle:
            handle.write(data)
            handle.flush()
            os.fsync(handle.fileno())
    except BaseException:
        _unlink_quietly(Path(temp_name))
        raise
    return Path(temp_name)


def _unlink_quietly(path: Path) -> None:
    try:
        path.unlink()
    except FileNotFoundError:
        pass


def write_bytes_atomic(path: Path | str, data: bytes) -> Path:
    """Write one file atomically (temp file in the same directory, then os.replace)."""
    target = Path(path)
    temp = _write_temp(target, data)
    try:
        os.replace(temp, target)
    except BaseException:
        _unlink_quietly(temp)
        raise
    return target


def write_text_atomic(path: Path | str, text: str) -> Path:
    """Write one UTF-8 text file atomically."""
    return write_bytes_atomic(path, text.encode("utf-8"))


def write_files_atomic(files: Mapping[Path | str, bytes | str]) -> list[Path]:
    """Write several files all-or-nothing and return their paths in the given order.

    On failure every file this call already put in place is restored to its previous
    content (or removed when it did not exist), no temporary file is left, and the
    exception propagates.
    """
    targets = [Path(path) for path in files]
    if len({os.path.normpath(os.path.abspath(t)) for t in targets}) != len(targets):
        raise ValueError("the same output path was given twice")
    payloads = [data.encode("utf-8") if isinstance(data, str) else data for data in files.values()]
    temps: list[Path] = []
    # (target, backup or None) for each file already renamed into place, to undo on failure
    placed: list[tuple[Path, Path | None]] = []
    try:
        for target, data in zip(targets, payloads, strict=True):
            temps.append(_write_temp(target, data))
        for target, temp in zip(targets, temps, strict=True):
            backup = None
            if target.exists():
                # A hard link keeps the old content reachable without copying it.
                backup = target.with_name(f".{target.name}.{os.getpid()}.bak")
                _unlink_quietly(backup)
                os.link(target, backup)
            try:
                os.replace(temp, target)
            except BaseException:
                if backup is not None:
                    _unlink_quietly(backup)
                raise
            placed.append((target, backup))
    except BaseException:
        for target, backup in reversed(placed):
            if backup is None:
                _unlink_quietly(target)
            else:
                os.replace(backup, target)
        for temp in temps:
            _unlink_quietly(temp)
        raise
    for _target, backup in placed:
        if backup is not None:
            _unlink_quietly(backup)
    return targets
