"""Where buildings run: a local pool (default, nothing to install) or a Dask cluster.

Both run `building.run_isolated` once per building and yield `(job, outcome)` as buildings
finish, in whatever order; the driver does all writing. Each building runs in its own child
process (building.py), so the local pool needs no worker processes of its own: `workers`
threads each wait on one child at a time, and the children use the cores.

Dask `distributed` over Ray for the engine: both run long CPU-bound tasks fine here, because
the solving happens in the child process and the task only waits for it. Dask is pure Python
and small (no raylet/object-store binaries, no dashboard services), a LocalCluster of process
workers starts in about a second in tests, and a worker that dies mid-task is handled by the
scheduler (`allowed-failures` retries, then `KilledWorker`), which is exactly the "one
building fails, not the batch" rule. Ray's strengths (actors, GPUs, a shared object store)
buy this workload nothing.
"""

from __future__ import annotations

import os
import threading
import uuid
from collections.abc import Iterator
from concurrent.futures import FIRST_COMPLETED, ThreadPoolExecutor, wait

from layoutdsl.batch.building import Outcome, run_isolated, stop_all
from layoutdsl.batch.jobs import Job

ENGINES = ("pool", "dask")

CLUSTER_EXTRA_HINT = "install it with: pip install 'layoutdsl[cluster]'"

LOCAL_ALLOWED_FAILURES = 1
"""A building whose task killed a worker of a local cluster is retried once, then failed."""


class EngineUnavailable(RuntimeError):
    """The chosen engine is not installed or cannot be reached (a usage error)."""


def default_workers() -> int:
    """Every core this process may use."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:
        return max(1, os.cpu_count() or 1)


class Running:
    """How many buildings are being made right now (for the progress display)."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self.count = 0

    def add(self, delta: int) -> None:
        with self._lock:
            self.count += delta


def run_pool(jobs: list[Job], workers: int, running: Running) -> Iterator[tuple[Job, Outcome]]:
    """Make the buildings on this machine, `workers` at a time."""

    def task(job: Job) -> Outcome:
        running.add(1)
        try:
            return run_isolated(job)
        finally:
            running.add(-1)

    pool = ThreadPoolExecutor(max_workers=workers, thread_name_prefix="layoutdsl-batch")
    try:
        pending = {pool.submit(task, job): job for job in jobs}
        while pending:
            done, _ = wait(pending, return_when=FIRST_COMPLETED)
            for future in done:
                job = pending.pop(future)
                yield job, future.result()
    finally:
        # on an interrupt, buildings still running are abandoned, not waited for
        pool.shutdown(wait=False, cancel_futures=True)
        stop_all()


def _import_distributed():
    try:
        import dask  # noqa: F401
        import distributed
    except ImportError:
        raise EngineUnavailable(f"the dask engine needs the `distributed` package: {CLUSTER_EXTRA_HINT}") from None
    return distributed


def run_dask(jobs: list[Job], workers: int, running: Running, address: str | None = None) -> Iterator[tuple[Job, Outcome]]:
    """Make the buildings on a Dask cluster: the one at `address`, else a local one.

    A local cluster gets `workers` single-threaded worker processes (one building each at a
    time). On an existing cluster, each worker thread takes one building; size threads to cores.
    """
    distributed = _import_distributed()
    import dask

    cluster = None
    try:
        if address is None:
            with dask.config.set({"distributed.scheduler.allowed-failures": LOCAL_ALLOWED_FAILURES}):
                # no dashboard; the scheduler's HTTP server (health checks) still starts, on a
                # free port rather than 8787, which another scheduler on the machine may hold
                cluster = distributed.LocalCluster(
                    n_workers=workers, threads_per_worker=1, processes=True,
                    dashboard_address=None, scheduler_kwargs={"dashboard_address": ":0"},
                    host="127.0.0.1", silence_logs=50)
            client = distributed.Client(cluster)
        else:
            try:
                client = distributed.Client(address, timeout="20s")
            except (OSError, TimeoutError) as error:
                raise EngineUnavailable(f"cannot reach the Dask scheduler at `{address}`: {error}") from None
    except BaseException:
        if cluster is not None:
            cluster.close()
        raise
    try:
        capacity = sum(client.nthreads().values()) or 1
        batch_id = uuid.uuid4().hex[:8]
        futures = {}
        for job in jobs:
            future = client.submit(run_isolated, job, key=f"layoutdsl-{job.building}-{batch_id}", pure=False)
            futures[future] = job
        finished = 0
        for future in distributed.as_completed(futures):
            job = futures[future]
            finished += 1
            running.count = min(capacity, len(futures) - finished)
            try:
                outcome = future.result()
            except distributed.KilledWorker as error:
                # Dask's message goes on about logs; its first sentence says what happened
                first = str(error).split(". ")[0]
                outcome = Outcome(job.building, False, f"worker died while making it (KilledWorker: {first})")
            except Exception as error:  # raised inside the task: our bug or the engine's
                outcome = Outcome(job.building, False, f"engine error: {type(error).__name__}: {error}")
            future.release()
            yield job, outcome
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
