"""Annealing runs on worker threads beside the construction's repairs (issue 11).

The construction (layoutdsl.compile.construct.Annealing) repairs greedy geometries on one
core while SCIP holds it; the annealing kernels release the GIL, so runs go on beside it.
A plan with a cycle block of generate.CORE_BLOCK_ROOMS rooms or more (one the satellites
split) runs the core-and-satellites annealer (layoutdsl.compile.satellites) from scratch, on
every worker at once; any other plan the sequence-pair annealer over the whole plan
(layoutdsl.compile.anneal), one run from scratch at a time. Runs from a given geometry (a
greedy placement the repair gave up on) are the sequence pair's.

Measured with `bench/generation.py --seeds 4` (bench/results/satellites.txt; four seeds
say little, the same seed's first layout varies twofold between runs), on the two plans the
satellites split, with the construction's main thread waiting for these runs
(construct._anneal_order "alone"): school_stjoseph_scatholichighschool (a 27-room block)
constructed 3 of 4 seeds, against 0 of 4 with one satellites run and one whole-plan run at a
time beside the greedy repairs; office_floor-1024x523 (14) 2 of 4, against 3 of 4 (runs of
4M moves; see satellites.CORE_MOVES_PER_PAIR for the runs compile makes now).
"""

from __future__ import annotations

import random
import threading
import time
from collections.abc import Callable

import numpy as np

from layoutdsl.compile.anneal import CHAINS, _Arrays, _cancel_at
from layoutdsl.compile.satellites import Satellites
from layoutdsl.layout.geometry import Rect
from layoutdsl.syntax.ast import Spec


SPLIT_KIND = "satellites"
"""The kind of run from scratch of a plan the satellites split: the satellites' alone (no
whole-plan runs between them) since their moves start warm (satellites.SATELLITES_TEMPERATURE).
With that, on school_stjoseph_scatholichighschool 11 of 16 runs end within 6 m of a layout,
where the whole-plan sequence pair's never came within 5 m."""


class AnnealingRuns:
    """Annealing runs of one spec on worker threads of their own, while the caller does other
    work (the construction repairs its greedy geometries meanwhile).

    `submit(geometry)` asks for a run from that geometry; runs asked for go first. A worker
    with nothing asked for starts the next run from scratch: for a spec the satellites split,
    theirs (SPLIT_KIND), as many at a time as there are workers, else the sequence pair's,
    one at a time. Each run is one chain, seeded with the next draw from `seed` (the runs
    asked for and the random ones from two streams, so a run's seed does not depend on when a
    worker fell idle). `pop_done` gives the finished run nearest a layout. Runs still going
    at `deadline` or at `close()` are cut off and give nothing.
    """

    def __init__(self, spec: Spec, seed: int, deadline: float | None, workers: int = CHAINS,
                 log: Callable[[str], None] | None = None):
        self.arrays = _Arrays.of(spec)
        self.satellites = Satellites.of(spec)
        self.kind = SPLIT_KIND if self.satellites is not None else "sequence pair"
        """the kind of run from scratch"""
        self.at_once = max(1, workers) if self.satellites is not None else 1
        """how many runs from scratch may go at a time"""
        self.log = log
        """told of each finished run (the construction's debug trace)"""
        self.draw = random.Random(seed)
        self.random_draw = random.Random(seed + 1)
        self.cancel = np.zeros(1, dtype=np.int64)
        self.timer = _cancel_at(deadline, self.cancel)
        self.condition = threading.Condition()
        self.asked: list[tuple[int, dict[str, Rect]]] = []
        self.done: list[tuple[dict[str, Rect], float, bool]] = []
        self.random_busy = 0
        """runs from scratch going"""
        self.threads = [threading.Thread(target=self._work, name="layoutdsl-anneal", daemon=True)
                        for _ in range(workers)]
        for thread in self.threads:
            thread.start()

    def submit(self, geometry: dict[str, Rect]) -> None:
        """Ask for a run from `geometry` (the spec's rooms, overlaps allowed)."""
        with self.condition:
            self.asked.append((self.draw.randrange(2**31), geometry))
            self.condition.notify_all()

    def _next_job(self):
        """(kernel seed, start or None, kind) for a free worker, or None to stop; holds the
        lock."""
        while not self.cancel[0]:
            if self.asked:
                return (*self.asked.pop(0), "sequence pair")
            if self.random_busy < self.at_once:
                self.random_busy += 1
                return self.random_draw.randrange(2**31), None, self.kind
            self.condition.wait(0.1)
        return None

    def _work(self) -> None:
        while True:
            with self.condition:
                job = self._next_job()
                if job is None:
                    return
            kernel_seed, start, kind = job
            began = time.monotonic()
            if kind == "satellites":
                result = self.satellites.chain(kernel_seed, self.cancel)
                kernel = self.satellites
            else:
                result = self.arrays.chain(kernel_seed, self.cancel, start)
                kernel = self.arrays
            # a chain cut off returns its best state so far, which depends on the clock
            finished = None if self.cancel[0] else kernel.geometry(result)
            # a satellites run beyond its reach is dropped: the next run, not a repair, follows
            dropped = finished is not None and kind == "satellites" and not self.satellites.repairable(finished[1])
            if finished is not None and self.log is not None:
                origin = "from a geometry" if start is not None else "from scratch"
                self.log(f"annealing run done ({kind}, {origin}, {time.monotonic() - began:.1f} s): "
                         f"{finished[1]:.2f} m from a layout" + (self._dropped(result) if dropped else ""))
            if dropped:
                finished = None
            with self.condition:
                if start is None:
                    self.random_busy -= 1
                if finished is not None:
                    self.done.append((*finished, start is not None))
                self.condition.notify_all()

    def _dropped(self, result) -> str:
        """For the debug trace: where a satellites run beyond its reach stopped."""
        made, moves = result[-1], self.satellites.moves()
        stopped = f", stopped after {made / moves:.0%} of its moves" if made < moves else ""
        return f"{stopped}; dropped, beyond satellites.REACH_M"

    def pop_done(self, fit=lambda violation: True) -> tuple[dict[str, Rect], float, bool] | None:
        """The finished run with the least violation among those that are `fit` (the first
        finished on a tie), dropping the unfit ones: (geometry, violation, whether it
        started from a given geometry), or None.

        The least, not the first: runs finish while a repair holds the construction, and
        measured on school_stjoseph_scatholichighschool's 27-room block, packings that met
        every door waited 18 s behind earlier ones 2-5 m from a layout whose repairs stalled.
        """
        with self.condition:
            self.done = [run for run in self.done if fit(run[1])]
            if not self.done:
                return None
            best = min(range(len(self.done)), key=lambda k: self.done[k][1])
            return self.done.pop(best)

    def has_done(self, fit=lambda violation: True) -> bool:
        """Whether a finished run's violation is `fit`."""
        with self.condition:
            return any(fit(run[1]) for run in self.done)

    def wait(self, fit, deadline: float) -> tuple[dict[str, Rect], float, bool] | None:
        """pop_done(fit), waiting for runs to finish until `deadline`."""
        while time.monotonic() < deadline and not self.cancel[0]:
            run = self.pop_done(fit)
            if run is not None:
                return run
            with self.condition:
                if not self.done:
                    self.condition.wait(min(0.5, max(0.0, deadline - time.monotonic())))
        return None

    def close(self) -> None:
        """Cut off the runs going (within CANCEL_CHECK moves) and wait for their threads."""
        self.cancel.fill(1)
        if self.timer is not None:
            self.timer.cancel()
        with self.condition:
            self.condition.notify_all()
        for thread in self.threads:
            thread.join()
