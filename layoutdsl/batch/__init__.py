"""Batch generation: many buildings from many plans, resumable, locally or on a Dask cluster.

    jobs = plan_jobs(["plans/"], variants=4, base_seed=0, limits=SolveLimits(node_limit=20))
    summary = run_batch(jobs, "dataset/", engine="pool")   # or engine="dask", address=...

See `jobs` (what to do, seeds), `building` (one building in its own process), `executors`
(local pool, Dask), `driver` (resume, writing, the log) and `manifest` (the dataset manifest).
"""

from layoutdsl.batch.driver import BatchBusy, BatchSummary, near_copies, run_batch
from layoutdsl.batch.executors import ENGINES, EngineUnavailable, default_workers
from layoutdsl.batch.jobs import BatchInputError, Job, SolveLimits, derive_seed, plan_jobs
from layoutdsl.batch.manifest import MANIFEST_NAME, RECORD_FIELDS, TIMING_FIELDS

__all__ = [
    "ENGINES", "MANIFEST_NAME", "RECORD_FIELDS", "TIMING_FIELDS", "BatchBusy",
    "BatchInputError", "BatchSummary", "EngineUnavailable", "Job", "SolveLimits", "default_workers",
    "derive_seed", "near_copies", "plan_jobs", "run_batch",
]
