"""The dataset manifest: one JSON record per building.

Two files in the batch's output folder:
- `.batch/records.jsonl`, the log: the driver appends one line per finished or failed
  building, with a single `write` on an O_APPEND file followed by fsync, so a killed driver
  leaves whole lines (at worst a last line cut short, which reading skips). A building's record
  is appended only after all its files are in place, so the log never lists half-written
  output as done.
- `manifest.jsonl`, for users: every building of the batch once (its latest record), in input
  order, rewritten atomically at the start and the end of each run. JSON Lines loads with
  `pandas.read_json(path, lines=True)`, `datasets.load_dataset("json", ...)` or a loop over
  `json.loads`.

A building counts as done for a later run when its latest record says `done`, was made with
the same fingerprint (input bytes, seed, limits, formats, version) and every listed file
still has the recorded sha256. The files were verified before they were written; equal hashes
prove they are those bytes, for every format and not only the layout JSON, at the cost of
reading them once (no re-import, no re-solve).
"""

from __future__ import annotations

import hashlib
import json
import os
from pathlib import Path

from layoutdsl.emit.atomic import write_text_atomic

MANIFEST_NAME = "manifest.jsonl"
STATE_FOLDER = ".batch"
LOG_NAME = "records.jsonl"

RECORD_FIELDS = (
    "building", "source", "kind", "variant", "seed", "status", "reason", "seconds",
    "solve_status", "objective", "difference", "area_m2", "rooms", "files", "sha256",
    "layoutdsl_version", "fingerprint",
)
"""The manifest's columns, in order. status: 'done' or 'failed'; reason: why it failed;
seconds: wall time of the building's process (a timing field); solve_status: the rule that
stopped the solve; difference: from the original plan, 0..1 (layout.difference; null
without hints); area_m2: sum of the rooms' areas; files: paths relative to the output folder."""

TIMING_FIELDS = ("seconds",)
"""Fields that vary from run to run of the same batch (the layout JSON's solve.seconds and
solve.first_feasible_seconds too, inside the files)."""


def log_path(outdir: Path) -> Path:
    return outdir / STATE_FOLDER / LOG_NAME


def read_log(outdir: Path) -> dict[str, dict]:
    """The latest record of each building in the log; a torn last line is ignored."""
    latest: dict[str, dict] = {}
    try:
        text = log_path(outdir).read_text(encoding="utf-8")
    except FileNotFoundError:
        return latest
    for line in text.splitlines():
        try:
            record = json.loads(line)
        except json.JSONDecodeError:
            continue  # only a driver killed mid-write leaves one, and only at the end
        if isinstance(record, dict) and isinstance(record.get("building"), str):
            latest[record["building"]] = record
    return latest


def append_record(outdir: Path, record: dict) -> None:
    """Append one record as one line, durably (see the module doc)."""
    path = log_path(outdir)
    path.parent.mkdir(parents=True, exist_ok=True)
    line = (json.dumps(record, sort_keys=False) + "\n").encode("utf-8")
    fd = os.open(path, os.O_WRONLY | os.O_APPEND | os.O_CREAT, 0o644)
    try:
        # a torn line after a crash must not glue itself to this one
        if os.fstat(fd).st_size and _last_byte(path) != b"\n":
            line = b"\n" + line
        os.write(fd, line)
        os.fsync(fd)
    finally:
        os.close(fd)


def _last_byte(path: Path) -> bytes:
    with open(path, "rb") as handle:
        handle.seek(-1, os.SEEK_END)
        return handle.read(1)


def sha256_of(path: Path) -> str:
    digest = hashlib.sha256()
    with open(path, "rb") as handle:
        for block in iter(lambda: handle.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def is_done(outdir: Path, record: dict | None, fingerprint: str) -> bool:
    """Whether a record proves its building finished with these settings and is intact."""
    if not record or record.get("status") != "done" or record.get("fingerprint") != fingerprint:
        return False
    hashes = record.get("sha256") or {}
    if not hashes or set(hashes) != set(record.get("files") or ()):
        return False
    for name, expected in hashes.items():
        try:
            if sha256_of(outdir / name) != expected:
                return False
        except OSError:
            return False
    return True


def write_manifest(outdir: Path, buildings: list[str], records: dict[str, dict]) -> Path:
    """Rewrite manifest.jsonl atomically (unless it already says the same): each listed
    building with a record, once, in order."""
    lines = [json.dumps({key: records[b].get(key) for key in RECORD_FIELDS}) for b in buildings if b in records]
    text = "".join(line + "\n" for line in lines)
    path = outdir / MANIFEST_NAME
    try:
        if path.read_text(encoding="utf-8") == text:
            return path  # a re-run with nothing to do rewrites nothing, not even the manifest
    except (OSError, UnicodeDecodeError):
        pass
    return write_text_atomic(path, text)
