"""The moves: small random changes of a sequence-pair state (representation.py).

Each move writes its trial state into spare arrays (copies of the state on entry), so the
schedule can take or reject it without allocating. The share of each kind (MOVES, in
order; the shares add up to 1):

- resize: one side of one room longer or shorter, within its bounds and aspect ratio;
- beside: a room whose door is unmet put right beside its neighbour, on a random side
  (sometimes turned): the move that closes doors;
- swap in P, swap in Q: two rooms trade places in one sequence (changes one relation);
- trade: two rooms trade places in both sequences (they swap places in the plan);
- turn: one room turned by a quarter.

Adding a move is adding a kind here: a share in MOVES and a branch in `propose`.

`traded` is not one of them: it is the kick that starts a derived arrangement
(generator.derive), a few trades made at once on a state that is already a layout.
"""

from __future__ import annotations

import math
import random

import numpy as np
from numba import njit

MOVES = (("resize", 0.15), ("beside", 0.30), ("swap_p", 0.10), ("swap_q", 0.10), ("trade", 0.20),
         ("turn", 0.15))
"""(kind, share of the moves)."""

_EDGES = np.cumsum(np.array([share for _kind, share in MOVES]))
RESIZE_UP_TO, BESIDE_UP_TO, SWAP_P_UP_TO, SWAP_Q_UP_TO, TRADE_UP_TO = (float(v) for v in _EDGES[:5])

RESIZE_STEP = 0.15
"""Spread of a resize: the side is multiplied by exp(this x a standard normal draw)."""

TURN_BESIDE = 0.3
"""Chance that the room a `beside` move places is also turned."""


@njit(cache=True)
def _move_beside(seq, room, anchor, after, out):
    """Into `out`: the permutation `seq` with `room` taken out and put just after (or
    before) `anchor`."""
    n = seq.shape[0]
    k = 0
    for i in range(n):
        r = seq[i]
        if r == room:
            continue
        if r == anchor and not after:
            out[k] = room
            k += 1
        out[k] = r
        k += 1
        if r == anchor and after:
            out[k] = room
            k += 1


@njit(cache=True)
def _resize_into(i, long_side, short_side, bounds, new_long, new_short):
    """One side of room i longer or shorter (into new_long or new_short, copies of the
    sides), within its bounds and aspect ratio."""
    factor = math.exp(RESIZE_STEP * np.random.standard_normal())
    lo_long, hi_long, lo_short, hi_short, min_ar, max_ar = bounds[i]
    if np.random.random() < 0.5:
        lo = max(lo_long, min_ar * short_side[i], short_side[i])
        hi = min(hi_long, max_ar * short_side[i])
        new_long[i] = min(hi, max(lo, long_side[i] * factor))
    else:
        lo = max(lo_short, long_side[i] / max_ar)
        hi = min(hi_short, long_side[i] / min_ar, long_side[i])
        new_short[i] = min(hi, max(lo, short_side[i] * factor))


@njit(cache=True, inline="always")
def drift(i, long_side, short_side, drawn_long, drawn_short):
    """How far room i's sides are from their targets (cost.RESIZE_WEIGHT), in metres."""
    return abs(long_side[i] - drawn_long[i]) + abs(short_side[i] - drawn_short[i])


@njit(cache=True)
def propose(p, q, turned, long_side, short_side, new_p, new_q, new_turned, spare_long, spare_short,
            bounds, edge_a, edge_b, per_edge, partner):
    """One random move (numba's generator, seeded by the schedule) into new_p, new_q,
    new_turned (copies of p, q, turned on entry) or, for a resize, into spare_long and
    spare_short: returns the resized room, or -1 for any other move. per_edge (each door's
    violation, cost.violation) steers `beside` towards unmet doors. A room turned turns its
    partner too (representation.Rooms.partner: the two rectangles of an L turn together)."""
    n = p.shape[0]
    m = edge_a.shape[0]
    kind = np.random.random()
    if kind < RESIZE_UP_TO:
        i = np.random.randint(n)
        spare_long[:] = long_side
        spare_short[:] = short_side
        _resize_into(i, long_side, short_side, bounds, spare_long, spare_short)
        return i
    if kind < BESIDE_UP_TO and m > 0:
        k = np.random.randint(m)
        for _ in range(8):
            if per_edge[k] > 0.0:
                break
            k = np.random.randint(m)
        a = edge_a[k]
        b = edge_b[k]
        if np.random.random() < 0.5:
            a, b = b, a
        side = np.random.randint(4)
        # b right of a: after in both; left: before in both;
        # above: before in P, after in Q; below: after in P, before in Q
        _move_beside(p, b, a, side == 0 or side == 3, new_p)
        _move_beside(q, b, a, side == 0 or side == 2, new_q)
        if np.random.random() < TURN_BESIDE:
            _turn(b, new_turned, partner)
    elif kind < SWAP_P_UP_TO:
        i = np.random.randint(n)
        j = np.random.randint(n)
        new_p[i], new_p[j] = new_p[j], new_p[i]
    elif kind < SWAP_Q_UP_TO:
        i = np.random.randint(n)
        j = np.random.randint(n)
        new_q[i], new_q[j] = new_q[j], new_q[i]
    elif kind < TRADE_UP_TO:
        a = np.random.randint(n)
        b = np.random.randint(n)
        for k in range(n):
            if new_p[k] == a:
                new_p[k] = b
            elif new_p[k] == b:
                new_p[k] = a
            if new_q[k] == a:
                new_q[k] = b
            elif new_q[k] == b:
                new_q[k] = a
    else:
        _turn(np.random.randint(n), new_turned, partner)
    return -1


@njit(cache=True, inline="always")
def _turn(i, turned, partner):
    """Room i turned a quarter, with the other rectangle of its L if it has one."""
    turned[i] = not turned[i]
    if partner[i] >= 0:
        turned[partner[i]] = not turned[partner[i]]


def traded(state, trades: int, rng: random.Random):
    """A copy of the state with `trades` random pairs of rooms traded (each swaps places in
    both sequences, the `trade` move): the kick from which generator.derive anneals a new
    arrangement near a found one."""
    p, q, turned, long_side, short_side = (part.copy() for part in state)
    n = p.shape[0]
    for _ in range(trades):
        a, b = rng.randrange(n), rng.randrange(n)
        for seq in (p, q):
            at_a, at_b = int(np.flatnonzero(seq == a)[0]), int(np.flatnonzero(seq == b)[0])
            seq[at_a], seq[at_b] = b, a
    return p, q, turned, long_side, short_side
