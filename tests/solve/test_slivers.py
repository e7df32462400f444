"""solve.relations.without_slivers: every gap between two rooms' facing walls ends up a wall
exactly or at least a usable width (issue 40), and the layout still verifies.

The gaps are checked here with their own arithmetic, not with layout.realism's detector."""

from __future__ import annotations

from itertools import combinations
from pathlib import Path

import pytest

from layoutdsl.api import lint_source, read_source
from layoutdsl.compile import compile_spec
from layoutdsl.layout.geometry import layout_from_rects
from layoutdsl.layout.verify import verify
from layoutdsl.solve import SolveOptions
from layoutdsl.solve.relations import without_slivers

from spec_cases import FIVE, FIVE_RECTS

ROOT = Path(__file__).resolve().parents[2]
USABLE = 0.6

def _facing_gaps(rects, walldim):
    """(a, b, gap) for every two rectangles whose walls face each other along more than a
    wall's thickness."""
    found = []
    for (a, ra), (b, rb) in combinations(sorted(rects.items()), 2):
        along_y = min(ra[1] + ra[3], rb[1] + rb[3]) - max(ra[1], rb[1])
        along_x = min(ra[0] + ra[2], rb[0] + rb[2]) - max(ra[0], rb[0])
        if along_y > walldim:
            gap = max(rb[0] - ra[0] - ra[2], ra[0] - rb[0] - rb[2])
            if gap >= 0:
                found.append((a, b, gap))
        if along_x > walldim:
            gap = max(rb[1] - ra[1] - ra[3], ra[1] - rb[1] - rb[3])
            if gap >= 0:
                found.append((a, b, gap))
    return found


def _slivers(rects, walldim):
    return [(a, b, round(gap, 4)) for a, b, gap in _facing_gaps(rects, walldim)
            if walldim + 1e-4 < gap < USABLE - 1e-4]


# FIVE_RECTS with E moved 0.2 m right: 0.4 m between D and E, neither wall nor space
SLIVERED = dict(FIVE_RECTS, E=(4.4, 0.8, 3.0, 3.0))


def test_the_planted_geometry_is_a_layout_with_one_sliver():
    walldim = FIVE.settings.walldim
    assert not verify(FIVE, layout_from_rects(FIVE, SLIVERED))
    assert _slivers(SLIVERED, walldim) == [("D", "E", 0.4)]


def test_a_sliver_is_shut_to_a_wall_or_opened_to_usable_width():
    walldim = FIVE.settings.walldim
    cleared = without_slivers(FIVE, SLIVERED, usable_width=USABLE, deadline=1e12, nodes=2000, seed=0)
    assert cleared is not None
    assert _slivers(cleared, walldim) == []
    gap = next(g for a, b, g in _facing_gaps(cleared, walldim) if (a, b) == ("D", "E"))
    assert gap == pytest.approx(walldim, abs=1e-4) or gap >= USABLE - 1e-4
    assert not verify(FIVE, layout_from_rects(FIVE, cleared))


def test_rectangles_without_slivers_are_left_as_they_are():
    assert _slivers(FIVE_RECTS, FIVE.settings.walldim) == []
    assert without_slivers(FIVE, FIVE_RECTS, usable_width=USABLE, deadline=1e12, nodes=2000, seed=0) is None


def test_compile_returns_the_bundled_school_without_slivers():
    # its best layout before this pass has three (measured): the pass must remove them
    spec, diagnostics = lint_source(read_source(ROOT / "specs" / "school_fig42.lay"))
    assert spec is not None
    result = compile_spec(spec, SolveOptions(time_limit=30, seed=0, quiet=True, search=False))
    assert result.layout is not None
    rects = {room.id: (room.x, room.y, room.w, room.h) for room in result.layout.rooms}
    assert _slivers(rects, spec.settings.walldim) == []
    assert not verify(spec, result.layout)
