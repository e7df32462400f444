"""solve.relations.compacted: the rooms around an enclosed void are pulled together (and grown
into it) with every relation kept, no room gets smaller, and the layout still verifies.

The void is checked here with its own arithmetic, not with layout.realism's raster."""

from __future__ import annotations

import pytest

from layoutdsl.layout.geometry import layout_from_rects
from layoutdsl.layout.verify import verify
from layoutdsl.solve.relations import compacted
from layoutdsl.syntax.ast import Adjacency

from spec_cases import FIVE, FIVE_RECTS, room, spec

USABLE = 0.6

# four rooms in a ring, each with a door to the next: A and C stand left and right, B and D
# lie between them at the top and the bottom, 4 m apart, so a 6 x 4 m hole is enclosed
RING = spec(
    "ring",
    [room("A", (2, 4, 3), (8, 12, 10), ar=(1, 6)), room("B", (5, 8, 6), (2, 6, 3), ar=(1, 4)),
     room("C", (2, 4, 3), (8, 12, 10), ar=(1, 6)), room("D", (5, 8, 6), (2, 6, 3), ar=(1, 4))],
    20, 20,
    adjacencies=[Adjacency("A", "B", 0.9, "e"), Adjacency("B", "C", 0.9, "e"), Adjacency("C", "D", 0.9, "e"),
                 Adjacency("D", "A", 0.9, "e")],
)
RING_RECTS = {
    "A": (0.0, 0.0, 3.0, 10.0),
    "D": (3.2, 0.0, 6.0, 3.0),
    "B": (3.2, 7.0, 6.0, 3.0),
    "C": (9.4, 0.0, 3.0, 10.0),
}


def _hole(rects) -> float:
    """Metres between B's bottom and D's top, where both lie between A and C."""
    return rects["B"][1] - (rects["D"][1] + rects["D"][3])


def test_the_planted_ring_is_a_layout_around_a_hole():
    assert not verify(RING, layout_from_rects(RING, RING_RECTS))
    assert _hole(RING_RECTS) == pytest.approx(4.0)


def test_the_rooms_around_a_void_close_it_without_shrinking():
    walldim = RING.settings.walldim
    pulled = compacted(RING, RING_RECTS, usable_width=USABLE, deadline=1e12, nodes=2000, seed=0)
    assert pulled is not None
    # B and D meet across a wall: nothing is left between A, B, C and D
    assert _hole(pulled) == pytest.approx(walldim, abs=1e-4)
    for room_id, (_x, _y, w, h) in RING_RECTS.items():
        assert pulled[room_id][2] >= w - 1e-4 and pulled[room_id][3] >= h - 1e-4, room_id
    assert not verify(RING, layout_from_rects(RING, pulled))


def test_a_layout_without_voids_is_left_as_it_is():
    assert compacted(FIVE, FIVE_RECTS, usable_width=USABLE, deadline=1e12, nodes=2000, seed=0) is None
