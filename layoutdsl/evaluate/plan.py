"""Everything measured on one plan on its own: areas, sizes, graph, entrance paths, exploration.

The report (report.py) then compares the generated plans' measures with the original's.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import networkx as nx
import numpy as np
from scipy import ndimage

from layoutdsl.importer.building import Building, realism_of_building
from layoutdsl.evaluate.explore import ExploreSettings, ExplorationResult, explore
from layoutdsl.evaluate.grid import coarsen, inflate, nearest_cell, room_cells
from layoutdsl.evaluate.metrics import PlanAreas, plan_areas, room_shapes, room_sizes
from layoutdsl.evaluate.difference import building_centres
from layoutdsl.evaluate.paths import DistanceGrid, shortest_path
from layoutdsl.evaluate.portals import MapCheck, realise_portal_graph
from layoutdsl.evaluate.topology import room_graph, room_ids, sorted_rooms
from layoutdsl.emit.raster import rasterize_building
from layoutdsl.layout.realism import Realism


@dataclass(frozen=True, slots=True)
class EvaluateOptions:
    """How plans are measured; every field ends up in the report."""

    robot_radius_m: float = 0.2
    resolution_m: float = 0.05
    """Cell size of the occupancy grid (the Stage/ROS map) and of the entrance paths."""
    explore_resolution_m: float = 0.1
    """Cell size of the exploration grid: the map coarsened (a cell is a wall when any of
    its fine cells is) by a whole factor; never finer than `resolution_m`."""
    seed: int = 0
    start_room: str | None = None
    """Room the exploration starts in (the same in every variant); default the first entrance."""
    explore: ExploreSettings = field(default_factory=ExploreSettings)

    @property
    def coarsening(self) -> int:
        return max(1, round(self.explore_resolution_m / self.resolution_m))


@dataclass(frozen=True, slots=True)
class RoomAnchor:
    """Where a path or exploration starts in a room: its centre, or the nearest free cell."""

    room: str
    cell: tuple[int, int]
    offset_m: float
    """Distance from the room's centroid to the cell used (0 when the centroid is free)."""
    inside_room: bool


@dataclass(frozen=True, slots=True)
class PlanMeasures:
    """The measures of one plan."""

    name: str
    rooms: int
    graph: nx.Graph
    areas: PlanAreas
    sizes: dict[str, tuple[float, float]]
    entrances: tuple[str, ...]
    anchors: dict[str, RoomAnchor]
    path_lengths: dict[tuple[str, str], float | None]
    """Entrance pair (a, b), a before b -> any-angle path length in metres; None if unreachable."""
    grid_path_lengths: dict[tuple[str, str], float | None]
    """The same on the 16-connected grid (an upper bound, <= +2.75 %)."""
    exploration: ExplorationResult | None
    explore_start: RoomAnchor | None
    explore_note: str = ""
    grid_shape: tuple[int, int] = (0, 0)
    free_area_m2: float = 0.0
    occupied_preview: np.ndarray | None = None
    """The exploration grid (for plots), row 0 at the top."""
    map_check: MapCheck | None = None
    """Whether the rasterized map joins exactly the rooms the portals join (and what was opened)."""
    centres: dict[str, tuple[float, float]] = field(default_factory=dict)
    """Room centres under report ids, for the arrangement difference (evaluate.difference)."""
    shapes: dict[str, tuple[float, float]] = field(default_factory=dict)
    """Room -> (polygon area m², polygon / bounding-box area): the rooms' real shapes."""
    unreachable: dict[str, str] = field(default_factory=dict)
    """Every room the robot cannot reach from the exploration's start room -> why, in words."""
    path_notes: dict[tuple[str, str], str] = field(default_factory=dict)
    """Entrance pair without a path -> why."""
    realism: Realism | None = None
    """Entrances open to the outside, enclosed voids, rooms with an outside wall (layout.realism)."""


class Reach:
    """Which rooms the robot can reach from which, on the map inflated by its radius, and why not.

    A room is out of reach either because no spot in it is a robot's radius from every wall
    (the room, or its narrowest part, is smaller than the robot), or because on every way to
    it through the plan's doors one opening is too narrow for the robot to pass; the reason
    names the first such opening on the shortest way through the room graph.
    """

    def __init__(self, traversable: np.ndarray, labels: np.ndarray, ids: tuple[str, ...],
                 graph: nx.Graph, robot_radius_m: float):
        self.components, _ = ndimage.label(traversable, structure=np.ones((3, 3), dtype=bool))
        self.graph = graph
        self.diameter = 2 * robot_radius_m
        self.parts: dict[str, set[int]] = {}
        for index, room in enumerate(ids):
            cells = self.components[(labels == index) & traversable]
            self.parts[room] = set(np.unique(cells[cells > 0]).tolist())

    def why_not(self, start: str, room: str) -> str | None:
        """None when the robot in `start` can reach `room`; else the reason."""
        if room == start:
            return None
        if not self.parts.get(room):
            return self._too_small(room)
        if not self.parts.get(start):
            return f"the start `{start}` has no spot for the robot"
        reachable = self._reachable_parts(start)
        if self.parts[room] & reachable:
            return None
        if start not in self.graph or room not in self.graph or not nx.has_path(self.graph, start, room):
            return f"no door leads to it from `{start}`"
        way = nx.shortest_path(self.graph, start, room)
        for u, v in zip(way, way[1:]):
            if self.parts.get(v, set()) & reachable:
                continue
            if not self.parts.get(v):
                return f"the way passes `{v}`, " + self._too_small(v)
            return (f"the opening between `{u}` and `{v}` is narrower than the robot "
                    f"({self.diameter:g} m across)")
        return f"every way to it from `{start}` is narrower than the robot ({self.diameter:g} m across)"

    def _reachable_parts(self, start: str) -> set[int]:
        return set(self.parts.get(start, set()))

    def _too_small(self, room: str) -> str:
        return (f"`{room}` is smaller than the robot: no spot in it is {self.diameter / 2:g} m "
                f"(the robot's radius) from every wall")


def _anchor(room: str, index: int, rooms, traversable: np.ndarray, resolution: float) -> RoomAnchor | None:
    centre = rooms.centres[index]
    in_room = rooms.labels == index
    cell = nearest_cell(traversable, centre, within=in_room)
    if cell is None:
        return None
    offset = math.hypot(cell[0] - centre[0], cell[1] - centre[1]) * resolution
    return RoomAnchor(room, cell, offset, bool(in_room[cell]))


def measure_plan(building: Building, options: EvaluateOptions = EvaluateOptions(), name: str | None = None) -> PlanMeasures:
    """Measure one plan (see module doc)."""
    ids = room_ids(building)
    res = options.resolution_m
    grid = rasterize_building(building, res)
    rooms = room_cells(building, grid, ids)
    graph = room_graph(building)
    # every measure below runs on a map whose free space joins exactly the portal graph, as
    # far as it can be repaired; what cannot is reported (evaluate.portals)
    occupied, map_check = realise_portal_graph(
        grid.occupied, rooms.labels, rooms.ids, {tuple(sorted(e)) for e in graph.edges}, res,
        building.real_distance_m)
    grid = replace(grid, occupied=occupied)
    traversable = ~inflate(grid.occupied, options.robot_radius_m, res)
    entrances = tuple(sorted_rooms(room for room in rooms.ids if graph.nodes[room]["rtype"] == "E"))
    anchors: dict[str, RoomAnchor] = {}
    for room in entrances:
        anchor = _anchor(room, rooms.ids.index(room), rooms, traversable, res)
        if anchor is not None:
            anchors[room] = anchor
    reach = Reach(traversable, rooms.labels, rooms.ids, graph, options.robot_radius_m)
    lengths: dict[tuple[str, str], float | None] = {}
    grid_lengths: dict[tuple[str, str], float | None] = {}
    path_notes: dict[tuple[str, str], str] = {}
    dg = DistanceGrid(traversable) if len(entrances) > 1 else None
    for i, a in enumerate(entrances):
        later = entrances[i + 1 :]
        if not later:
            break
        dist = dg.distances([anchors[a].cell]) if a in anchors else None
        for b in later:
            result = None
            if dist is not None and b in anchors:
                result = shortest_path(dg, anchors[a].cell, anchors[b].cell, dist)
            lengths[(a, b)] = None if result is None else result.length * res
            grid_lengths[(a, b)] = None if result is None else result.grid_length * res
            if result is None:
                path_notes[(a, b)] = (reach.why_not(a, b) or reach.why_not(b, a)
                                      or "no path between the two rooms' anchor points")

    # exploration on the coarser grid
    factor = options.coarsening
    coarse_res = res * factor
    occupied = coarsen(grid.occupied, factor)
    coarse_trav = ~inflate(occupied, options.robot_radius_m, coarse_res)
    coarse_rooms = room_cells(building, grid, ids, factor) if factor > 1 else rooms
    start_room = options.start_room or (entrances[0] if entrances else sorted_rooms(rooms.ids)[0])
    unreachable = {}
    if start_room in rooms.ids:
        for room in sorted_rooms(rooms.ids):
            reason = reach.why_not(start_room, room)
            if reason is not None:
                unreachable[room] = reason
    exploration = None
    start_anchor = None
    note = ""
    if start_room not in coarse_rooms.ids:
        note = f"start room `{start_room}` is not in this plan"
    else:
        start_anchor = _anchor(start_room, coarse_rooms.ids.index(start_room), coarse_rooms, coarse_trav, coarse_res)
        if start_anchor is None:
            note = f"no free cell for the robot in `{start_room}`"
        else:
            exploration = explore(
                occupied, coarse_res, start_anchor.cell, options.robot_radius_m, options.seed,
                options.explore, traversable=coarse_trav,
            )
    return PlanMeasures(
        name=name or building.name,
        rooms=len(building.spaces),
        graph=graph,
        areas=plan_areas(building),
        sizes=room_sizes(building),
        entrances=entrances,
        anchors=anchors,
        path_lengths=lengths,
        grid_path_lengths=grid_lengths,
        exploration=exploration,
        explore_start=start_anchor,
        explore_note=note,
        grid_shape=grid.shape,
        free_area_m2=float((~grid.occupied).sum()) * res * res,
        occupied_preview=occupied,
        map_check=map_check,
        centres=building_centres(building),
        shapes=room_shapes(building),
        unreachable=unreachable,
        path_notes=path_notes,
        realism=realism_of_building(building, ids),
    )
