"""The core-and-satellites annealer: the split of a plan, the runs' geometry, their seeds.

Geometry is checked here with plain arithmetic of its own, not with the annealer's score.
"""

from __future__ import annotations

import dataclasses
import itertools
import time
from pathlib import Path

import numpy as np
import pytest

from layoutdsl.api import load_spec
from layoutdsl.compile import construct, satellites as satellites_module
from layoutdsl.compile.anneal_runs import AnnealingRuns
from layoutdsl.compile.generate import room_graph
from layoutdsl.compile.satellites import Satellites
from layoutdsl.layout.verify import verify
from layoutdsl.syntax.ast import Boundary

from _specs import cycle_spec, ladder_spec, ring_block_spec, tree_spec

SPECS = Path(__file__).resolve().parents[2] / "specs"
TOL = 1e-6


def _school():
    spec, _ = load_spec(str(SPECS / "school_cycle.lay"))
    assert spec is not None
    return spec


def _run(spec, seed: int):
    satellites = Satellites.of(spec)
    return satellites.geometry(satellites.chain(seed, np.zeros(1, dtype=np.int64)))


def _gaps(a, b):
    """Gap along x and along y between two (x, y, w, h) rectangles (negative: overlap)."""
    return (max(b[0] - a[0] - a[2], a[0] - b[0] - b[2]), max(b[1] - a[1] - a[3], a[1] - b[1] - b[3]))


def _shared(a, b):
    """Length of wall two rectangles share along x and along y (negative: none)."""
    return (min(a[0] + a[2], b[0] + b[2]) - max(a[0], b[0]), min(a[1] + a[3], b[1] + b[3]) - max(a[1], b[1]))


def test_the_core_is_the_large_blocks_and_every_other_room_hangs_off_one_placed_before():
    spec = ring_block_spec()
    satellites = Satellites.of(spec)
    core = {f"K{i}" for i in range(12)}
    assert set(satellites.core.ids) == core
    graph = room_graph(spec)
    hanging = satellites.ids[len(core):]
    assert sorted(hanging) == ["H1", "H2", "H3", "LONE", "T1", "T2"]
    for k, room_id in enumerate(hanging):
        parent = satellites.parent[k]
        assert parent < len(core) + k  # placed before it
        if room_id == "LONE":
            assert satellites.need[k] == 0.0  # no door: only put beside a room
        else:
            assert graph.has_edge(room_id, satellites.ids[parent])
            assert satellites.need[k] == pytest.approx(0.9 / spec.settings.door_utilization)
    # the triangle's second room hangs off K0 and has a door to the first too: the small
    # block's cycle closes as it is placed
    t2 = hanging.index("T2")
    assert satellites.ids[satellites.parent[t2]] == "K0"
    extras = satellites.extra_to[satellites.extra_ptr[t2]:satellites.extra_ptr[t2 + 1]]
    assert [satellites.ids[j] for j in extras] == ["T1"]


def test_a_split_plan_anneals_alone_and_others_beside_the_greedy_placement():
    """The construction gives both cores to the annealing for a plan the satellites split
    (construct._anneal_order "alone"), and not for one without a large block."""
    assert construct._anneal_order(ring_block_spec()) == "alone"
    assert construct._anneal_order(ladder_spec()) == "first"


def test_a_plan_without_a_large_block_is_not_split():
    assert Satellites.of(cycle_spec()) is None  # a ring of five rooms
    assert Satellites.of(tree_spec()) is None
    assert Satellites.of(_school()) is None  # a ring of four corridors


@pytest.mark.parametrize("seed", range(3))
def test_a_run_that_meets_every_door_is_rooms_a_wall_apart_with_every_door_met(seed):
    """A ring of twelve rooms (the core) with a triangle, a chain, a room on the boundary
    and one without a door beside it (the satellites)."""
    spec = ring_block_spec()
    geometry, violation = _run(spec, seed)
    assert violation <= 1e-9
    assert set(geometry) == {room.id for room in spec.rooms}
    wall = spec.settings.walldim
    for a, b in itertools.combinations(geometry.values(), 2):
        assert max(_gaps(a, b)) >= wall - TOL
    boundary = spec.boundary
    for room in spec.rooms:
        x, y, w, h = geometry[room.id]
        assert x >= -TOL and y >= -TOL and x + w <= boundary.w + TOL and y + h <= boundary.h + TOL
        if room.on_boundary:
            assert min(x, y, boundary.w - x - w, boundary.h - y - h) <= TOL
    for adj in spec.adjacencies:
        a, b = geometry[adj.a], geometry[adj.b]
        gap_x, gap_y = _gaps(a, b)
        along_y, along_x = _shared(a, b)[1], _shared(a, b)[0]
        need = adj.door / spec.settings.door_utilization
        assert (abs(gap_x - wall) <= TOL and along_y >= need - TOL) or \
            (abs(gap_y - wall) <= TOL and along_x >= need - TOL), (adj.a, adj.b)


def test_the_same_seed_gives_the_same_geometry_and_another_seed_another():
    spec = ring_block_spec()
    first, _ = _run(spec, 5)
    again, _ = _run(spec, 5)
    other, _ = _run(spec, 6)
    assert first == again
    assert first != other


def test_a_cancelled_run_stops_at_once():
    satellites = Satellites.of(ring_block_spec())
    geometry, violation = satellites.geometry(satellites.chain(0, np.ones(1, dtype=np.int64)))
    assert len(geometry) == len(satellites.ids) and violation > 0.0  # a random start, unmoved


def test_a_satellites_geometry_repairs_into_a_verified_layout():
    spec = ring_block_spec()
    geometry, violation = _run(spec, 1)
    assert violation <= 1e-9
    problem = construct._Problem.of(spec)
    rects = construct._repair(problem, geometry, time.monotonic() + 30, seed=0)
    assert rects is not None
    assert verify(spec, construct.rects_to_layout(spec, rects)) == []


def test_a_plan_with_a_large_block_runs_satellites_on_every_worker_with_runs_asked_for_first():
    """Its runs from scratch are the satellites', as many at a time as there are workers;
    runs asked for go first and are the sequence pair's. A plan without a large block starts
    sequence-pair runs only, one at a time."""
    runs = AnnealingRuns(ring_block_spec(), seed=0, deadline=None, workers=0)
    try:
        runs.at_once = 2  # as with two workers, whose threads this test does without
        with runs.condition:
            first, second = runs._next_job(), runs._next_job()
            assert [first[1:], second[1:]] == [(None, "satellites")] * 2
            assert first[0] != second[0]
            runs.random_busy -= 1  # one of them is done
            runs.asked.append((7, {"K0": (0.0, 0.0, 1.0, 1.0)}))  # the lock is held
            assert runs._next_job() == (7, {"K0": (0.0, 0.0, 1.0, 1.0)}, "sequence pair")
            assert runs._next_job()[1:] == (None, "satellites")
    finally:
        runs.close()
    runs = AnnealingRuns(_school(), seed=0, deadline=None, workers=0)
    try:
        assert runs.kind == "sequence pair" and runs.at_once == 1
    finally:
        runs.close()


def _crowded():
    """ring_block_spec's rooms (at least 120 m², at their least sizes) in a 9 m x 9 m
    boundary: no run comes near a layout."""
    return dataclasses.replace(ring_block_spec(), boundary=Boundary(9.0, 9.0))


@pytest.fixture
def short_runs(monkeypatch):
    """Runs of 20k moves on the core alone, then 20k with the satellites (a fraction of a
    second each)."""
    monkeypatch.setattr(satellites_module, "CORE_MAX_MOVES", 20_000)
    monkeypatch.setattr(satellites_module, "SATELLITE_MOVES", 20_000)


def test_a_run_still_beyond_reach_at_the_checkpoint_stops_there(short_runs, monkeypatch):
    """REACH_M at CHECKPOINT_SHARE of the moves with the satellites: a run farther from a
    layout stops there, one within reach goes on to SETTLED_SHARE of them (or, with that
    share 1, to its last move)."""
    satellites = Satellites.of(_crowded())
    checkpoint = 20_000 + int(satellites_module.CHECKPOINT_SHARE * 20_000)
    violation, *_, made = satellites.chain(3, np.zeros(1, dtype=np.int64))
    assert violation > satellites_module.REACH_M
    assert made == checkpoint
    assert not satellites.repairable(violation)
    monkeypatch.setattr(satellites_module, "REACH_M", 1e9)  # every run within reach
    violation, *_, made = satellites.chain(3, np.zeros(1, dtype=np.int64))
    assert violation > 0.0 and made == 20_000 + int(satellites_module.SETTLED_SHARE * 20_000) < 40_000
    assert satellites.repairable(violation)
    monkeypatch.setattr(satellites_module, "SETTLED_SHARE", 1.0)
    settled_later, *_, made = satellites.chain(3, np.zeros(1, dtype=np.int64))
    assert made == satellites.moves() == 40_000
    assert settled_later <= violation  # the same run, longer: its best can only be as good


def test_a_run_records_its_best_so_far_at_every_mark(short_runs, monkeypatch):
    """progress holds the best state's distance from a layout at every 5 % of the moves
    with the satellites the run made (NaN beyond), never rising, and the run's result is
    the last of them or better."""
    monkeypatch.setattr(satellites_module, "REACH_M", 1e9)  # no checkpoint stops it
    satellites = Satellites.of(_crowded())
    progress = np.zeros(satellites_module.PROGRESS_MARKS)
    violation, *_, made = satellites.chain(3, np.zeros(1, dtype=np.int64), progress)
    marks = (made - 20_000) // 1_000  # one every 1000 moves with the satellites
    assert marks == 16  # the run settles at 80 %
    assert not np.isnan(progress[:marks]).any() and np.isnan(progress[marks:]).all()
    # never rising (a best of equal violation within 1e-9 and a lower cost may replace it)
    assert all(later <= earlier + 1e-6 for earlier, later in zip(progress[:marks], progress[1:marks]))
    assert violation <= progress[marks - 1] + 1e-6
    # the record changes nothing in the run
    unrecorded = satellites.chain(3, np.zeros(1, dtype=np.int64))
    assert unrecorded[0] == violation and unrecorded[5] == made


def test_runs_beyond_reach_give_the_construction_nothing_to_repair(short_runs, monkeypatch):
    """AnnealingRuns drops a satellites run that ended beyond REACH_M: the construction
    waits for the next run instead of repairing it."""
    logged: list[str] = []
    runs = AnnealingRuns(_crowded(), seed=0, deadline=None, workers=1, log=logged.append)
    try:
        waited = time.monotonic() + 30.0
        while len(logged) < 2 and time.monotonic() < waited:
            time.sleep(0.05)
        assert len(logged) >= 2
        assert all(line.endswith("stopped after 80% of its moves; dropped, beyond satellites.REACH_M")
                   for line in logged)
        assert runs.pop_done() is None
        monkeypatch.setattr(satellites_module, "REACH_M", 1e9)
        found = runs.wait(lambda violation: True, time.monotonic() + 30.0)
    finally:
        runs.close()
    assert found is not None
    geometry, violation, from_geometry = found
    assert set(geometry) == {room.id for room in _crowded().rooms} and violation > 4.0  # beyond the default reach


def _busy():
    """ring_block_spec with three more rooms hung off each ring room (42 satellites) in a
    boundary they barely fit: satellites in one another's way all run long."""
    from _specs import adjacent, room

    spec = ring_block_spec()
    hung = [room(f"S{i}_{j}", 3.0, 2.5) for i in range(12) for j in range(3)]
    doors = [adjacent(f"K{i}", f"S{i}_{j}") for i in range(12) for j in range(3)]
    return dataclasses.replace(spec, rooms=spec.rooms + tuple(hung), adjacencies=spec.adjacencies + tuple(doors),
                               boundary=Boundary(24.0, 24.0))


@pytest.mark.parametrize("make_spec", [ring_block_spec, _crowded, _busy])
def test_keeping_undisturbed_satellites_in_place_changes_no_run(short_runs, monkeypatch, make_spec):
    """INCREMENTAL_PLACEMENT only saves work: each run, move for move, ends in the same
    state as when every satellite is placed again after every move."""
    satellites = Satellites.of(make_spec())
    results = {}
    for incremental in (True, False):
        monkeypatch.setattr(satellites_module, "INCREMENTAL_PLACEMENT", incremental)
        results[incremental] = [satellites.chain(seed, np.zeros(1, dtype=np.int64)) for seed in range(3)]
    for kept, placed_again in zip(results[True], results[False]):
        assert kept[0] == placed_again[0] and kept[5] == placed_again[5]
        for a, b in zip(kept[1:5], placed_again[1:5]):
            assert np.array_equal(a, b)


def test_a_split_plans_runs_start_before_the_model_is_built_and_the_construction_takes_them_over(
        short_runs, monkeypatch):
    """compile starts the construction's annealing (construct.start_annealing) before it
    builds and probes the thesis' model; the construction then uses that annealing, and
    starts none of its own."""
    from layoutdsl.compile import pipeline
    from layoutdsl.solve import SolveOptions

    made: list[construct.Annealing] = []
    init = construct.Annealing.__init__

    def counted(self, *args, **kwargs):
        made.append(self)
        init(self, *args, **kwargs)

    monkeypatch.setattr(construct.Annealing, "__init__", counted)
    build = pipeline.build_model
    running_at_build: list[bool] = []

    def build_model(*args, **kwargs):
        running_at_build.append(len(made) == 1 and made[0].order == "alone" and not made[0].closed)
        return build(*args, **kwargs)

    monkeypatch.setattr(pipeline, "build_model", build_model)
    spec = ring_block_spec()
    result = pipeline.compile_from_start(spec, SolveOptions(time_limit=20, seed=0, quiet=True))
    assert running_at_build == [True]
    assert len(made) == 1 and made[0].closed
    assert result.layout is not None and verify(spec, result.layout) == []


def test_an_infeasible_split_plan_closes_the_runs_started_for_it(monkeypatch):
    """A spec whose probe proves it infeasible (rooms wider than the boundary) has the
    annealing started for it closed before the infeasibility is explained, its threads gone."""
    from layoutdsl.compile import pipeline
    from layoutdsl.solve import SolveOptions

    started: list = []
    start = pipeline.start_annealing

    def recorded(*args, **kwargs):
        started.append(start(*args, **kwargs))
        return started[-1]

    monkeypatch.setattr(pipeline, "start_annealing", recorded)
    explain = pipeline._no_layout
    closed_before_explaining: list[bool] = []

    def no_layout(*args, **kwargs):
        closed_before_explaining.append(started[0].closed)
        return explain(*args, **kwargs)

    monkeypatch.setattr(pipeline, "_no_layout", no_layout)
    spec = dataclasses.replace(ring_block_spec(), boundary=Boundary(2.0, 200.0))
    result = pipeline.compile_from_start(spec, SolveOptions(time_limit=20, seed=0, quiet=True),
                                         explain_infeasible=False)
    assert result.status == "infeasible" and closed_before_explaining == [True]
    assert len(started) == 1 and started[0] is not None and started[0].closed
    runs = started[0].runs
    assert runs is None or not any(thread.is_alive() for thread in runs.threads)
