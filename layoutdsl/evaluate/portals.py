"""Does a plan's occupancy map realise its portal graph? Check it, and open missed doors.

The realism measures (entrance paths, exploration) are only meaningful on a map whose free
space joins exactly the rooms the plan's portals join. Real plans break this in two ways the
rasterization of the thesis (§6.3.6) cannot always avoid: a door drawn a little off the wall
the two rooms share stays closed (the room behind it is walled off, and exploring the
original then "covers 100 %" of a building that is missing rooms), and overlapping room
polygons or missing wall segments join rooms that have no portal.

`realise_portal_graph` finds both from the map itself: two rooms *meet* when their interior
cells touch, or when both touch the same connected piece of free space that lies in no room
(a door opening, a gap between walls). A portal whose rooms do not meet gets an opening of
the plan's door width cut through the wall zone between them; an opening that would join a
third room is not cut. What cannot be fixed (rooms too far apart for a door, joins without a
portal) is returned for the report to name.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import ndimage

REACH_M = 0.6
"""How far apart (metres of wall and gap) two rooms' interiors may be for a door between them."""


@dataclass(frozen=True, slots=True)
class MapCheck:
    """How a plan's map relates to its portal graph, before and after the repair."""

    missing_before: tuple[tuple[str, str], ...]
    """Portal pairs whose rooms did not meet in the map as rasterized."""
    opened: tuple[tuple[str, str], ...]
    """Of those, the pairs an opening was cut for."""
    still_missing: tuple[tuple[str, str], ...]
    """Portal pairs that still do not meet: no wall zone between them, or the cut would join a third room."""
    extra: tuple[tuple[str, str], ...]
    """Room pairs that still meet without a portal: sealing them would part rooms a portal joins."""
    extra_before: tuple[tuple[str, str], ...] = ()
    """Room pairs that met without a portal as rasterized (overlapping polygons, missing walls,
    PORTAL segments no portal references)."""
    closed: tuple[tuple[str, str], ...] = ()
    """Of those, the pairs a one-cell wall now parts."""

    @property
    def realised_before(self) -> bool:
        return not self.missing_before and not self.extra_before

    @property
    def realised(self) -> bool:
        return not self.still_missing and not self.extra

    def warnings(self) -> list[str]:
        """One line per problem left, naming the rooms."""
        lines = [f"rooms `{a}` and `{b}` share a portal but are not joined in the map" for a, b in self.still_missing]
        lines += [f"rooms `{a}` and `{b}` are joined in the map without a portal" for a, b in self.extra]
        return lines


def meetings(free: np.ndarray, labels: np.ndarray, ids: tuple[str, ...]) -> set[tuple[str, str]]:
    """Room pairs (sorted) whose free regions meet directly or through free space in no room."""
    in_room = free & (labels >= 0)
    gaps, count = ndimage.label(free & (labels < 0))
    # one node per room (its index) and per gap component (len(ids) + component - 1)
    node = np.where(in_room, labels, np.where(gaps > 0, len(ids) + gaps - 1, -1))
    pairs: set[tuple[int, int]] = set()
    for a, b in ((node[:, :-1], node[:, 1:]), (node[:-1, :], node[1:, :])):
        touching = (a >= 0) & (b >= 0) & (a != b)
        both = np.stack([np.minimum(a[touching], b[touching]), np.maximum(a[touching], b[touching])], axis=1)
        pairs.update(map(tuple, np.unique(both, axis=0).tolist()) if both.size else ())
    rooms_at_gap: dict[int, set[int]] = {}
    met: set[tuple[int, int]] = set()
    for a, b in pairs:
        if b < len(ids):
            met.add((a, b))
        elif a < len(ids):
            rooms_at_gap.setdefault(b, set()).add(a)
    for rooms in rooms_at_gap.values():
        ordered = sorted(rooms)
        met.update((x, y) for i, x in enumerate(ordered) for y in ordered[i + 1:])
    return {tuple(sorted((ids[a], ids[b]))) for a, b in met if ids[a] != ids[b]}


def realise_portal_graph(
    occupied: np.ndarray,
    labels: np.ndarray,
    ids: tuple[str, ...],
    portal_pairs: set[tuple[str, str]],
    resolution: float,
    door_m: float,
) -> tuple[np.ndarray, MapCheck]:
    """The map with missed portals opened, and what was found; `occupied` is not modified."""
    wanted = {tuple(sorted(pair)) for pair in portal_pairs}
    met_as_rasterized = met = meetings(~occupied, labels, ids)
    missing = sorted(wanted - met)
    repaired = occupied.copy()
    opened: list[tuple[str, str]] = []
    reach = max(1, int(round(REACH_M / resolution)))
    disc = _disc(reach)
    door_disc = _disc(max(1, int(round(door_m / 2 / resolution))))
    index = {room: k for k, room in enumerate(ids)}
    for a, b in missing:
        if a not in index or b not in index:
            continue
        window = _window(labels, (index[a], index[b]), reach)
        if window is None:
            continue
        lab, occ = labels[window], occupied[window]
        in_a = (lab == index[a]) & ~occ
        in_b = (lab == index[b]) & ~occ
        near_both = ndimage.binary_dilation(in_a, structure=disc) & ndimage.binary_dilation(in_b, structure=disc)
        # the wall zone between the two rooms: close to both, in no third room
        zone = near_both & ((lab < 0) | (lab == index[a]) | (lab == index[b]))
        if not zone.any():
            continue
        rows, cols = np.nonzero(zone)
        centre = (rows.mean(), cols.mean())
        pick = int(np.argmin((rows - centre[0]) ** 2 + (cols - centre[1]) ** 2))
        mark = np.zeros_like(zone)
        mark[rows[pick], cols[pick]] = True
        cut = np.zeros_like(occupied)
        cut[window] = ndimage.binary_dilation(mark, structure=door_disc) & zone
        trial = repaired.copy()
        trial[cut] = False
        after = meetings(~trial, labels, ids)
        if (a, b) in after and not (after - met - wanted):
            repaired = trial
            met = after
            opened.append((a, b))
    closed: list[tuple[str, str]] = []
    for a, b in sorted(met - wanted):
        if a not in index or b not in index:
            continue
        for sealed in (_seal(repaired, labels, index[a], index[b]), _seal(repaired, labels, index[b], index[a])):
            after = meetings(~sealed, labels, ids)
            # accepted only when it parts these two rooms and nothing the portals join
            if (a, b) not in after and wanted & met <= after:
                repaired, met = sealed, after
                closed.append((a, b))
                break
    # `met` follows every accepted change, so it is the repaired map's meetings
    final = met
    check = MapCheck(
        missing_before=tuple(missing),
        opened=tuple(opened),
        still_missing=tuple(sorted(wanted - final)),
        extra=tuple(sorted(final - wanted)),
        extra_before=tuple(sorted(met_as_rasterized - wanted)),
        closed=tuple(closed),
    )
    return repaired, check


def _disc(radius: int) -> np.ndarray:
    span = np.arange(-radius, radius + 1)
    return (span[:, None] ** 2 + span[None, :] ** 2) <= radius * radius


def _seal(occupied: np.ndarray, labels: np.ndarray, room: int, other: int) -> np.ndarray:
    """The map with a one-cell wall on `room`'s side of wherever it touches `other`.

    It touches `other` directly (overlapping polygons without a wall between them) or through
    free space in no room (a gap, an opening no portal accounts for) that `other` touches too.
    """
    free = ~occupied
    in_room = free & (labels == room)
    in_other = free & (labels == other)
    gaps, _ = ndimage.label(free & (labels < 0))
    shared = np.intersect1d(np.unique(gaps[ndimage.binary_dilation(in_room) & (gaps > 0)]),
                            np.unique(gaps[ndimage.binary_dilation(in_other) & (gaps > 0)]))
    towards = in_other | np.isin(gaps, shared[shared > 0])
    sealed = occupied.copy()
    sealed[in_room & ndimage.binary_dilation(towards)] = True
    return sealed


def _window(labels: np.ndarray, rooms: tuple[int, int], margin: int) -> tuple[slice, slice] | None:
    """The part of the grid around two rooms (plus `margin` cells): where a door can go."""
    rows, cols = np.nonzero(np.isin(labels, rooms))
    if rows.size == 0:
        return None
    r0, r1 = max(0, rows.min() - margin), min(labels.shape[0], rows.max() + margin + 1)
    c0, c1 = max(0, cols.min() - margin), min(labels.shape[1], cols.max() + margin + 1)
    return slice(r0, r1), slice(c0, c1)
