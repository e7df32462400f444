"""The batch driver: decide what is left, run it, write each finished building, keep the log.

Only the driver writes into the output folder, one building at a time: the building's files
first (all or nothing, `emit.write_rendered`), then its record in the log. A driver killed at
any moment therefore leaves every building either listed with all its files, or not listed
(its files, if any, are simply made again). A lock file keeps two drivers out of one folder.
"""

from __future__ import annotations

import fcntl
import hashlib
import os
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from layoutdsl import __version__
from layoutdsl.batch import manifest
from layoutdsl.batch.building import Outcome
from layoutdsl.batch.executors import Running, default_workers, run_dask, run_pool
from layoutdsl.batch.jobs import Job


class BatchBusy(RuntimeError):
    """Another batch is writing into the same output folder."""


@dataclass(slots=True)
class BatchSummary:
    """What one run did."""

    total: int
    skipped: int
    """Already done and intact before this run."""
    done: int = 0
    failed: int = 0
    seconds: float = 0.0
    failures: list[tuple[str, str]] = field(default_factory=list)
    manifest: Path | None = None
    close: dict[str, list[tuple[str, float]]] = field(default_factory=dict)
    """Plan -> (building, its least difference from the plan's earlier variants) of each done
    building within variants.MIN_PAIRWISE of an earlier variant of its plan (near_copies)."""


ProgressHook = Callable[[str, object], None]
"""progress(event, payload): 'start' with the number of buildings this run makes, 'finished'
with a building's Outcome, 'end' with the BatchSummary."""


def run_batch(
    jobs: list[Job],
    outdir: Path | str,
    *,
    engine: str = "pool",
    workers: int | None = None,
    address: str | None = None,
    progress: ProgressHook | None = None,
    running: Running | None = None,
) -> BatchSummary:
    """Make every building of `jobs` not yet done in `outdir`; return what happened."""
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    (outdir / manifest.STATE_FOLDER).mkdir(exist_ok=True)
    workers = workers or default_workers()
    running = running or Running()
    began = time.monotonic()
    with _lock(outdir):
        records = manifest.read_log(outdir)
        order = [job.building for job in jobs]
        pending = [job for job in jobs if not manifest.is_done(outdir, records.get(job.building), job.fingerprint)]
        summary = BatchSummary(total=len(jobs), skipped=len(jobs) - len(pending))
        if records:
            # consolidate what earlier runs logged, before anything else can fail
            manifest.write_manifest(outdir, order, records)
        if progress:
            progress("start", len(pending))
        if pending:
            if engine == "dask":
                results = run_dask(pending, workers, running, address)
            else:
                results = run_pool(pending, workers, running)
            for job, outcome in results:
                record = _commit(outdir, job, outcome)
                records[job.building] = record
                if record["status"] == "done":
                    summary.done += 1
                else:
                    summary.failed += 1
                    summary.failures.append((job.building, record["reason"]))
                if progress:
                    progress("finished", outcome if record["status"] == "done" else
                             Outcome(job.building, False, record["reason"], outcome.seconds))
        summary.manifest = manifest.write_manifest(outdir, order, records)
        summary.close = near_copies(outdir, jobs, records)
    summary.seconds = time.monotonic() - began
    if progress:
        progress("end", summary)
    return summary


def near_copies(outdir: Path, jobs: list[Job], records: dict[str, dict]) -> dict[str, list[tuple[str, float]]]:
    """Per plan, the done buildings (with their least difference) that lie within the
    difference at which `compile --variants` keeps a new arrangement (variants.MIN_PAIRWISE)
    of a variant of the same plan before them, in variant order.

    A batch makes each variant from its own seed and does not compare them while it runs (a
    building's bytes must not depend on which others are done); this reads the finished
    layouts afterwards. A long, narrow plan gives much the same arrangement at every seed
    (W906 says the same of `compile --variants`).
    """
    from layoutdsl.compile.variants import MIN_PAIRWISE
    from layoutdsl.layout import Layout
    from layoutdsl.layout.difference import layout_centres, least_from_earlier

    by_plan: dict[str, list[Job]] = {}
    for job in sorted(jobs, key=lambda job: (job.plan, job.variant)):
        record = records.get(job.building)
        if record and record.get("status") == "done":
            by_plan.setdefault(job.plan, []).append(job)
    close: dict[str, list[tuple[str, float]]] = {}
    for plan, done in by_plan.items():
        if len(done) < 2:
            continue
        centres = []
        for job in done:
            # the layout JSON among the files its record lists
            name = next(name for name in records[job.building]["files"] if name.endswith(".layout.json"))
            try:
                text = (outdir / name).read_text(encoding="utf-8")
            except OSError:
                break  # damaged since: the next run makes it again
            centres.append(layout_centres(Layout.from_json(text)))
        else:
            near = [(job.building, least) for job, least in zip(done, least_from_earlier(centres))
                    if least is not None and least < MIN_PAIRWISE]
            if near:
                close[plan] = near
    return close


def _commit(outdir: Path, job: Job, outcome: Outcome) -> dict:
    """Write a finished building's files, then log its record; a failed one only logs."""
    record = {
        "building": job.building, "source": job.source, "kind": job.kind, "variant": job.variant,
        "seed": job.seed, "status": "done" if outcome.ok else "failed", "reason": outcome.reason,
        "seconds": round(outcome.seconds, 3), **{key: None for key in
                                                  ("solve_status", "objective", "difference", "area_m2", "rooms")},
        "files": [], "sha256": {}, "layoutdsl_version": __version__, "fingerprint": job.fingerprint,
    }
    record.update(outcome.facts)
    if outcome.ok:
        from layoutdsl.emit import write_rendered

        folder = outdir / job.building
        try:
            write_rendered(outcome.files, folder)
        except OSError as error:
            record.update(status="failed", reason=f"cannot write `{folder}`: {error.strerror or error}")
        else:
            names = [f"{job.building}/{name}" for name in outcome.files]
            record["files"] = names
            record["sha256"] = {name: hashlib.sha256(data).hexdigest()
                                for name, data in zip(names, outcome.files.values())}
    manifest.append_record(outdir, record)
    return record


class _lock:
    """An exclusive, non-blocking lock on OUTDIR/.batch/lock (released when the process dies)."""

    def __init__(self, outdir: Path) -> None:
        self.path = outdir / manifest.STATE_FOLDER / "lock"
        self.fd: int | None = None

    def __enter__(self):
        self.fd = os.open(self.path, os.O_RDWR | os.O_CREAT, 0o644)
        try:
            fcntl.flock(self.fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            os.close(self.fd)
            raise BatchBusy(f"another batch is writing into `{self.path.parent.parent}`") from None
        return self

    def __exit__(self, *exc) -> None:
        assert self.fd is not None
        fcntl.flock(self.fd, fcntl.LOCK_UN)
        os.close(self.fd)
