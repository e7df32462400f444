"""The schedule: how the generator searches the states, with work limits only.

Simulated annealing over sequence-pair states (representation.py), from a state read off
the room graph (initial.py), through random moves (moves.py), scored by one cost (cost.py):

- a *chain* makes MOVES_PER_ROOM x rooms moves (at most MAX_MOVES), the temperature falling
  geometrically from START_TEMPERATURE to END_TEMPERATURE (x the outline's half perimeter,
  in metres of cost); it stops early once it has reached a violation of 0 and made ZERO_STOP of
  its moves, or at GIVE_UP_AT of them when it is still more than GIVE_UP_M from a layout;
- a *round* runs CHAINS chains side by side (numba releases the GIL), each seeded from the
  spec's seed, the round and the chain index; the round's result is its best FINISHED chain
  by (score: violation plus guide, cost, chain index), so which thread ends first never matters;
- rounds follow one another (`rounds`), each with ROUND_GROWTH times the moves of the one
  before, until the caller has what it needs; the caller's `starts` gives each chain its
  initial state (the generator: the best state so far for chain 0, a new embedding else).

The number of moves decides every result; the wall clock only cuts a compile off at its
time limit (`cancel`), and then there is no result, never another one.
"""

from __future__ import annotations

import math
import random
import threading
import time
from collections.abc import Callable, Iterator
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numpy as np
from numba import njit

from layoutdsl.compile.budgets import WORK
from layoutdsl.compile.cost import COMPACT_WEIGHT, RESIZE_WEIGHT
from layoutdsl.compile.cost import violation as cost_violation
from layoutdsl.compile.moves import drift, propose
from layoutdsl.compile.representation import Rooms, State, new_work, pack_state

MOVES_PER_ROOM = WORK["moves_per_room"]
MAX_MOVES = WORK["max_moves"]
CHAINS = WORK["chains"]
ROUND_GROWTH = WORK["round_growth"]
START_TEMPERATURE = WORK["start_temperature"]
END_TEMPERATURE = WORK["end_temperature"]
ZERO_STOP = WORK["zero_stop"]
GIVE_UP_AT = WORK["give_up_at"]
GIVE_UP_M = WORK["give_up_m"]

CANCEL_CHECK = 2048
"""Moves between two looks at the cancel flag (a few milliseconds)."""


@dataclass(frozen=True)
class Found:
    """A round's best chain: its state, violation (metres; 0 = a layout) and cost."""

    state: State
    violation: float
    cost: float
    round: int
    chain: int
    moves: int
    """Moves made by all the round's chains."""
    score: float
    """What the search minimised (cost.violation): the violation plus the cost of the
    packing's extent beyond a guide outline, which is not violation (the boundary is drawn
    round the packing). Chains and rounds rank their states by it."""

    @property
    def rank(self) -> tuple[float, float]:
        return (self.score, self.cost)


def chain_seeds(seed: int, round_index: int) -> list[int]:
    """The numba seeds of a round's chains, drawn through Python's generator from the spec's
    seed and the round, so that nearby seeds start far apart."""
    draw = random.Random(f"{seed}:{round_index}")
    return [draw.randrange(2**31) for _ in range(CHAINS)]


def run_chain(rooms: Rooms, start: State, kernel_seed: int, moves: int, cancel: np.ndarray,
              start_temperature: float = START_TEMPERATURE, zero_stop: float = ZERO_STOP,
              met: float = 1e-9):
    """One chain from `start` (the kernel releases the GIL)."""
    scale = rooms.width + rooms.height
    give_up_step = int(GIVE_UP_AT * moves)
    return _chain(rooms.target_long, rooms.target_short, rooms.bounds, rooms.edge_a, rooms.edge_b,
                  rooms.need, rooms.join, rooms.group_end, rooms.door_ptr, rooms.door_to, rooms.on_boundary, rooms.width,
                  rooms.height, rooms.wall, rooms.outline_given, rooms.partner, kernel_seed, moves,
                  start_temperature * scale, END_TEMPERATURE * scale, give_up_step, GIVE_UP_M,
                  zero_stop, met, cancel, *start)


def one_chain(rooms: Rooms, start: State, kernel_seed: int, moves: int, deadline: float | None,
              start_temperature: float, zero_stop: float = ZERO_STOP, met: float = 1e-9) -> Found | None:
    """A single chain from `start` at its own start temperature (x the outline's half
    perimeter), in this thread: a derived arrangement's (generator.derive), which runs
    beside other variants and needs no second core. None when `deadline` cut it off."""
    cancel = np.zeros(1, dtype=np.int64)
    timer = _cancel_at(deadline, cancel)
    try:
        p, q, turned, long_side, short_side, score, violation, cost, done = run_chain(
            rooms, start, kernel_seed, moves, cancel, start_temperature, zero_stop, met)
    finally:
        if timer is not None:
            timer.cancel()
    if cancel[0]:
        return None
    return Found((p, q, turned, long_side, short_side), float(violation), float(cost), 0, 0, int(done), float(score))


def grown(rooms: Rooms, targets: dict[str, tuple[float, float]], start: State, kernel_seed: int,
          deadline: float | None) -> State:
    """`start` (a state of `rooms` within a layout) with its rooms grown towards `targets` in
    WORK["grow_steps"] steps: each step draws them that much larger (Rooms.grown_towards),
    raises the state's sides to that size and runs one cool chain to meet the doors again.
    The state of the last step that ended within WORK["grow_tolerance_m"] of a layout is
    returned (`start` if none did); a cut-off step ends the growth like a failed one."""
    steps = WORK["grow_steps"]
    moves = WORK["grow_moves_per_room"] * len(rooms.ids)
    draw = random.Random(kernel_seed)
    state = start
    for step in range(1, steps + 1):
        larger = rooms.grown_towards(targets, step / steps, WORK["grow_floor"])
        # a step only has to meet the doors again: it stops at the first state that does
        found = one_chain(larger, larger.fitted(state), draw.randrange(2**31), moves, deadline,
                          WORK["grow_temperature"], zero_stop=0.0, met=WORK["grow_tolerance_m"])
        if found is None or found.violation > WORK["grow_tolerance_m"]:
            break
        state = found.state
    return state


def moves_of_round(rooms: Rooms, round_index: int) -> int:
    return int(min(MAX_MOVES, MOVES_PER_ROOM * len(rooms.ids) * ROUND_GROWTH ** round_index))


def rounds(rooms_of: Callable[[int], Rooms], starts, seed: int, deadline: float | None,
           max_rounds: int, first_round: int = 0) -> Iterator[Found | None]:
    """The best chain of each round in turn, from `first_round` (a schedule resumed where
    it stopped) up to `max_rounds`; None when `deadline` (time.monotonic()) cut the round
    off. `rooms_of(round_index)` gives the rooms a round searches (the generator may reshape
    them between rounds), `starts(round_index, chain_index)` each chain's initial state.
    A round's moves and seeds depend only on its index, so rounds 0..k-1 then k..n-1 are
    rounds 0..n-1."""
    with ThreadPoolExecutor(max_workers=CHAINS) as pool:
        for round_index in range(first_round, max_rounds):
            this = rooms_of(round_index)
            moves = moves_of_round(this, round_index)
            cancel = np.zeros(1, dtype=np.int64)
            timer = _cancel_at(deadline, cancel)
            states = [starts(round_index, c) for c in range(CHAINS)]
            try:
                results = list(pool.map(lambda job: run_chain(this, job[0], job[1], moves, cancel),
                                        zip(states, chain_seeds(seed, round_index))))
            finally:
                if timer is not None:
                    timer.cancel()
            if cancel[0]:
                yield None
                return
            best = min(range(CHAINS), key=lambda c: (results[c][5], results[c][7], c))
            p, q, turned, long_side, short_side, score, violation, cost, _done = results[best]
            yield Found((p, q, turned, long_side, short_side), float(violation), float(cost), round_index,
                        best, int(sum(r[8] for r in results)), float(score))


def _cancel_at(deadline: float | None, cancel: np.ndarray) -> threading.Timer | None:
    """A timer that sets cancel[0] at `deadline`: the kernel cannot read the clock, the
    chains look at the flag every CANCEL_CHECK moves and stop."""
    if deadline is None:
        return None
    timer = threading.Timer(max(0.0, deadline - time.monotonic()), cancel.fill, (1,))
    timer.daemon = True
    timer.start()
    return timer


@njit(cache=True, nogil=True)
def _chain(drawn_long, drawn_short, bounds, edge_a, edge_b, need, join, group_end, door_ptr, door_to, on_boundary,
           width, height, wall, outline_given, partner, seed, moves, t_start, t_end, give_up_step, give_up_m,
           zero_stop, met, cancel, start_p, start_q, start_turned, start_long, start_short):
    np.random.seed(seed)
    n = drawn_long.shape[0]
    m = edge_a.shape[0]
    p, q, turned = start_p.copy(), start_q.copy(), start_turned.copy()
    long_side, short_side = start_long.copy(), start_short.copy()
    per_edge = np.zeros(m)
    # every array a move needs is made here, once: a move's trial state is written over the
    # spare arrays, which trade places with the state's when the move is taken
    work = new_work(n)
    pack_state(p, q, turned, long_side, short_side, bounds, wall, door_ptr, door_to, work)
    score, violation, box = cost_violation(work, edge_a, edge_b, need, join, group_end, on_boundary, width, height,
                                           wall, outline_given, per_edge)
    boundary_area = width * height
    cost = score + COMPACT_WEIGHT * box / boundary_area
    resized = 0.0
    for i in range(n):
        resized += drift(i, long_side, short_side, drawn_long, drawn_short)
    cost += RESIZE_WEIGHT * resized
    best_p, best_q, best_turned = p.copy(), q.copy(), turned.copy()
    best_long, best_short = long_side.copy(), short_side.copy()
    best_violation = violation
    best_score = score
    best_cost = cost
    ratio = t_end / t_start
    trial_edge = np.zeros(m)
    new_p, new_q, new_turned = p.copy(), q.copy(), turned.copy()
    spare_long, spare_short = long_side.copy(), short_side.copy()
    done = 0
    for step in range(moves):
        done = step
        if step % CANCEL_CHECK == 0 and cancel[0]:
            break
        if step == give_up_step and best_score > give_up_m:
            break  # GIVE_UP_AT: too far from a layout to get there
        temperature = t_start * ratio ** (step / moves)
        new_p[:] = p
        new_q[:] = q
        new_turned[:] = turned
        new_long = long_side
        new_short = short_side
        new_resized = resized
        resized_room = propose(p, q, turned, long_side, short_side, new_p, new_q, new_turned, spare_long,
                                spare_short, bounds, edge_a, edge_b, per_edge, partner)
        resizing = resized_room >= 0
        if resizing:
            new_long = spare_long
            new_short = spare_short
            new_resized = resized - drift(resized_room, long_side, short_side, drawn_long, drawn_short) \
                + drift(resized_room, new_long, new_short, drawn_long, drawn_short)
        pack_state(new_p, new_q, new_turned, new_long, new_short, bounds, wall, door_ptr, door_to, work)
        new_score, new_violation, box = cost_violation(work, edge_a, edge_b, need, join, group_end, on_boundary,
                                                       width, height, wall, outline_given, trial_edge)
        new_cost = new_score + COMPACT_WEIGHT * box / boundary_area + RESIZE_WEIGHT * new_resized
        delta = new_cost - cost
        if delta <= 0.0 or np.random.random() < math.exp(-delta / temperature):
            p, new_p = new_p, p
            q, new_q = new_q, q
            turned, new_turned = new_turned, turned
            if resizing:
                long_side, spare_long = spare_long, long_side
                short_side, spare_short = spare_short, short_side
            cost, resized = new_cost, new_resized
            per_edge[:] = trial_edge
            if new_score < best_score - 1e-9 or (abs(new_score - best_score) <= 1e-9 and new_cost < best_cost):
                best_p[:] = p
                best_q[:] = q
                best_turned[:] = turned
                best_long[:] = long_side
                best_short[:] = short_side
                best_violation = new_violation
                best_score = new_score
                best_cost = new_cost
        if best_score <= met and step >= zero_stop * moves:
            # a packing with every door met, within its guide outline if it has one: the rest
            # would only make it more compact
            break
    return best_p, best_q, best_turned, best_long, best_short, best_score, best_violation, best_cost, done + 1
