"""Simulated frontier exploration (the thesis, §6.5), standing in for Stage + GMapping + explore.

The robot knows nothing at first. It scans with a 270°, 30 m laser (ray casting on the
occupancy grid), then repeatedly drives to the nearest frontier goal by path distance
(like the ROS explorer's nearest-frontier strategy) until no reachable frontier is left.

Model, stated because the numbers depend on it:
- Perfect localisation and mapping: a beam marks the free cells it crosses and the first
  occupied cell it hits (1081 beams over 270°, as stage_ros' laser; sampled every half cell).
- The robot plans only through cells it has seen free and that its body fits in (the walls
  inflated by the robot radius; the inflation uses the true walls, as a local costmap
  would see them), on 16-connected distances with string-pulled paths (see paths.py).
- A frontier is a known free cell with an unknown 4-neighbour. A goal is a cell the robot
  fits in, at most robot radius + 2 cells from a frontier cell. On arrival the robot turns
  towards the unknown cells near the goal and scans; a goal whose frontier survives that is
  blacklisted (the explorer's blacklist), so the run always ends.
- While driving it scans every `scan_every_m` metres and replans as soon as its goal's
  frontier has been seen.
- Time = distance / linear speed + total turning / turning speed + a stop per goal.

Coverage is measured on the reachable free space: the free cells the robot can reach with
its centre, grown through free cells by the robot radius + 1 cell (the strip along the
walls and the room corners its laser sees but its centre never enters).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from layoutdsl.evaluate.grid import dilate, disc_offsets, inflate
from layoutdsl.evaluate.paths import DistanceGrid, backtrack, string_pull

UNKNOWN, FREE, OCCUPIED = -1, 0, 1

_FOUR = [(1, 0), (-1, 0), (0, 1), (0, -1)]
_EIGHT = [(dr, dc) for dr in (-1, 0, 1) for dc in (-1, 0, 1) if dr or dc]


@dataclass(frozen=True, slots=True)
class ExploreSettings:
    """The simulated robot and its speed model."""

    laser_range_m: float = 30.0
    laser_fov_deg: float = 270.0
    laser_beams: int = 1081
    linear_speed_m_s: float = 0.5
    turn_speed_deg_s: float = 90.0
    stop_per_goal_s: float = 1.0
    """Time to stop, accept the goal and plan the next one."""
    scan_every_m: float = 1.0
    coverage_target: float = 0.99
    max_goals: int = 5000
    """A safety net; a run that hits it is reported as such."""
    first_window_m: float = 8.0
    """Half-size of the first search window for the nearest goal (doubled until exact)."""


@dataclass(frozen=True, slots=True)
class ExplorationResult:
    """What one exploration run cost. Distances in metres, times in seconds."""

    reached_target: bool
    distance_to_target_m: float | None
    """Travelled distance when the coverage target (99 %) was first met."""
    time_to_target_s: float | None
    total_distance_m: float
    total_time_s: float
    final_coverage: float
    goals: int
    blacklisted: int
    reachable_free_m2: float
    hit_goal_limit: bool
    trajectory: tuple[tuple[float, float], ...] = field(default=())
    """Robot positions (row, col) in cells of the exploration grid, in driving order."""


class _Run:
    def __init__(self, occupied: np.ndarray, traversable: np.ndarray, resolution: float, settings: ExploreSettings, robot_radius_m: float) -> None:
        self.occupied = occupied
        self.traversable = traversable
        self.resolution = resolution
        self.settings = settings
        self.known = np.full(occupied.shape, UNKNOWN, dtype=np.int8)
        self.blacklist = np.zeros(occupied.shape, dtype=bool)
        self.reach_cells = robot_radius_m / resolution + 2
        self.reach_offsets = disc_offsets(self.reach_cells)
        self.distance = 0.0
        self.turning = 0.0  # radians
        self.goals = 0
        self.blacklisted = 0
        self.trajectory: list[tuple[float, float]] = []
        self.target_distance: float | None = None
        self.target_time: float | None = None

    # ------------------------------------------------------------------ sensing

    def scan(self, pos: tuple[float, float], heading: float) -> None:
        """Cast the laser from `pos` (row, col) facing `heading` (radians, x right, y up)."""
        s = self.settings
        h, w = self.occupied.shape
        half = math.radians(s.laser_fov_deg) / 2
        angles = heading + np.linspace(-half, half, s.laser_beams)
        d_row, d_col = -np.sin(angles), np.cos(angles)
        max_t = min(s.laser_range_m / self.resolution, math.hypot(h, w) + 1)
        step = 0.5
        active = np.arange(s.laser_beams)
        t0 = 0.0
        chunk = 64
        r0, c0 = pos
        # march all beams together, a chunk of samples at a time, dropping beams that hit
        while active.size and t0 <= max_t:
            t = t0 + step * np.arange(chunk)
            t = t[t <= max_t]
            if t.size == 0:
                break
            rows = np.floor(r0 + d_row[active, None] * t[None, :] + 0.5).astype(np.int64)
            cols = np.floor(c0 + d_col[active, None] * t[None, :] + 0.5).astype(np.int64)
            inside = (rows >= 0) & (rows < h) & (cols >= 0) & (cols < w)
            rows_c, cols_c = np.clip(rows, 0, h - 1), np.clip(cols, 0, w - 1)
            blocked = ~inside | self.occupied[rows_c, cols_c]
            hit = blocked.any(axis=1)
            first = np.where(hit, blocked.argmax(axis=1), t.size)
            seen = np.arange(t.size)[None, :] < first[:, None]
            self.known[rows_c[seen], cols_c[seen]] = FREE
            beam = np.nonzero(hit)[0]
            at = first[beam]
            ok = inside[beam, at]
            self.known[rows_c[beam, at][ok], cols_c[beam, at][ok]] = OCCUPIED
            active = active[~hit]
            t0 += step * chunk

    # ------------------------------------------------------------------ goals

    def frontier(self) -> np.ndarray:
        unknown = self.known == UNKNOWN
        near_unknown = np.zeros_like(unknown)
        h, w = unknown.shape
        for dr, dc in _FOUR:
            near_unknown[max(0, -dr) : h - max(0, dr), max(0, -dc) : w - max(0, dc)] |= unknown[
                max(0, dr) : h - max(0, -dr), max(0, dc) : w - max(0, -dc)
            ]
        return (self.known == FREE) & near_unknown

    def goal_alive(self, goal: tuple[int, int]) -> bool:
        """Is a frontier cell still within reach of the goal?"""
        r, c = goal
        k = int(math.ceil(self.reach_cells)) + 1
        r0, r1 = max(0, r - k), min(self.known.shape[0], r + k + 1)
        c0, c1 = max(0, c - k), min(self.known.shape[1], c + k + 1)
        window = self.known[r0:r1, c0:c1]
        unknown = window == UNKNOWN
        rr, cc = np.nonzero(window == FREE)
        for dr, dc in _FOUR:
            nr, nc = rr + dr, cc + dc
            ok = (nr >= 0) & (nr < window.shape[0]) & (nc >= 0) & (nc < window.shape[1])
            hits = np.zeros(rr.shape, dtype=bool)
            hits[ok] = unknown[nr[ok], nc[ok]]
            near = (rr + r0 - r) ** 2 + (cc + c0 - c) ** 2 <= self.reach_cells**2
            if (hits & near).any():
                return True
        return False

    def nearest_goal(self, cell: tuple[int, int], navigable: np.ndarray, goals: np.ndarray):
        """(goal, distance field) of the goal nearest by path, or None; exact by windowing.

        A window of half-size R around the robot is searched first. Any path that leaves it
        is at least as long as the way to its edge, so a goal found no farther than that
        margin is the global nearest; otherwise the window doubles.
        """
        h, w = navigable.shape
        r, c = cell
        half = max(4, int(self.settings.first_window_m / self.resolution))
        while True:
            r0, r1 = max(0, r - half), min(h, r + half + 1)
            c0, c1 = max(0, c - half), min(w, c + half + 1)
            whole = r0 == 0 and c0 == 0 and r1 == h and c1 == w
            dist = DistanceGrid(navigable[r0:r1, c0:c1]).distances([(r - r0, c - c0)])
            candidates = goals[r0:r1, c0:c1] & np.isfinite(dist)
            if candidates.any():
                values = np.where(candidates, dist, np.inf)
                best = np.unravel_index(int(np.argmin(values)), values.shape)
                margins = [
                    r - r0 if r0 > 0 else math.inf,
                    r1 - 1 - r if r1 < h else math.inf,
                    c - c0 if c0 > 0 else math.inf,
                    c1 - 1 - c if c1 < w else math.inf,
                ]
                if values[best] <= min(margins) or whole:
                    full = np.full((h, w), np.inf)
                    full[r0:r1, c0:c1] = dist
                    return (int(best[0]) + r0, int(best[1]) + c0), full
            elif whole:
                return None
            half *= 2

    # ------------------------------------------------------------------ bookkeeping

    def time(self) -> float:
        s = self.settings
        return (
            self.distance / s.linear_speed_m_s
            + math.degrees(self.turning) / s.turn_speed_deg_s
            + self.goals * s.stop_per_goal_s
        )

    def turn_to(self, heading: float, new_heading: float) -> float:
        delta = (new_heading - heading + math.pi) % (2 * math.pi) - math.pi
        self.turning += abs(delta)
        return new_heading


def reachable_free(free: np.ndarray, traversable: np.ndarray, start: tuple[int, int], grow_cells: int) -> np.ndarray:
    """Free cells the robot can reach with its centre from `start`, grown through free cells."""
    dist = DistanceGrid(traversable).distances([start])
    region = np.isfinite(dist)
    for _ in range(grow_cells):
        region = dilate(region, _EIGHT) & free
    return region


def explore(
    occupied: np.ndarray,
    resolution: float,
    start: tuple[int, int],
    robot_radius_m: float = 0.2,
    seed: int = 0,
    settings: ExploreSettings = ExploreSettings(),
    traversable: np.ndarray | None = None,
) -> ExplorationResult:
    """Explore the grid from the `start` cell until no reachable frontier is left.

    `occupied` is the true map (row 0 at the top); `traversable` the cells the robot's
    centre may occupy (the walls inflated by its radius), computed here when omitted. The
    seed picks the initial heading; everything else is deterministic.
    """
    if traversable is None:
        traversable = ~inflate(occupied, robot_radius_m, resolution)
    if not traversable[start]:
        raise ValueError(f"start cell {start} is not free for a robot of radius {robot_radius_m} m")
    run = _Run(occupied, traversable, resolution, settings, robot_radius_m)
    target_region = reachable_free(~occupied, traversable, start, int(math.ceil(robot_radius_m / resolution)) + 1)
    target_cells = int(target_region.sum())
    rng = np.random.default_rng(seed)
    heading = float(rng.uniform(-math.pi, math.pi))
    pos = (float(start[0]), float(start[1]))
    cell = start
    run.trajectory.append(pos)

    def sense(at: tuple[float, float], facing: float) -> None:
        run.scan(at, facing)
        if run.target_distance is None:
            seen = int(((run.known == FREE) & target_region).sum())
            if seen >= settings.coverage_target * target_cells:
                run.target_distance = run.distance
                run.target_time = run.time()

    sense(pos, heading)
    hit_limit = False
    while True:
        if run.goals >= settings.max_goals:
            hit_limit = True
            break
        navigable = (run.known == FREE) & traversable
        goals = navigable & dilate(run.frontier(), run.reach_offsets) & ~run.blacklist
        found = run.nearest_goal(cell, navigable, goals)
        if found is None:
            break
        goal, dist = found
        run.goals += 1
        polyline = string_pull(navigable, backtrack(dist, navigable, goal), passes=2)
        pos, heading, aborted = _drive(run, polyline, goal, pos, heading, sense)
        cell = (int(math.floor(pos[0] + 0.5)), int(math.floor(pos[1] + 0.5)))
        if not navigable[cell]:  # rounding off a segment end: fall back to the goal's path
            cell = goal if not aborted else _nearest_true(navigable, pos)
        if aborted:
            continue
        heading = _look_at_goal(run, goal, pos, heading, sense)
    return _result(run, target_region, target_cells, hit_limit)


def _result(run: _Run, target_region: np.ndarray, target_cells: int, hit_limit: bool) -> ExplorationResult:
    """What the run cost, and how much of the reachable free space it saw."""
    coverage = int(((run.known == FREE) & target_region).sum()) / max(1, target_cells)
    return ExplorationResult(
        reached_target=run.target_distance is not None,
        distance_to_target_m=run.target_distance,
        time_to_target_s=run.target_time,
        total_distance_m=run.distance,
        total_time_s=run.time(),
        final_coverage=coverage,
        goals=run.goals,
        blacklisted=run.blacklisted,
        reachable_free_m2=target_cells * run.resolution * run.resolution,
        hit_goal_limit=hit_limit,
        trajectory=tuple(run.trajectory),
    )


def _drive(run: _Run, polyline, goal: tuple[int, int], pos: tuple[float, float], heading: float,
           sense: Callable[[tuple[float, float], float], None]) -> tuple[tuple[float, float], float, bool]:
    """Drive along the polyline, scanning every `scan_every_m` metres.

    Returns (position, heading, aborted): aborted when a scan on the way saw the goal's
    frontier, so the robot stops there and replans.
    """
    settings = run.settings
    aborted = False
    since_scan = 0.0
    for a, b in zip(polyline, polyline[1:]):
        seg = math.hypot(b[0] - a[0], b[1] - a[1]) * run.resolution
        if seg == 0:
            continue
        heading = run.turn_to(heading, math.atan2(-(b[0] - a[0]), b[1] - a[1]))
        done = 0.0
        while done < seg:
            step = min(seg - done, settings.scan_every_m - since_scan)
            done += step
            since_scan += step
            run.distance += step
            f = done / seg
            pos = (a[0] + (b[0] - a[0]) * f, a[1] + (b[1] - a[1]) * f)
            if since_scan >= settings.scan_every_m - 1e-9:
                since_scan = 0.0
                sense(pos, heading)
                if not run.goal_alive(goal):
                    aborted = True
                    break
        run.trajectory.append(pos)
        if aborted:
            break
    return pos, heading, aborted


def _look_at_goal(run: _Run, goal: tuple[int, int], pos: tuple[float, float], heading: float,
                  sense: Callable[[tuple[float, float], float], None]) -> float:
    """At the goal: face the unknown cells it was chosen for and scan; blacklist the goal if
    its frontier survives that. Returns the new heading."""
    facing = _towards_unknown(run.known, goal, run.reach_cells + 2)
    if facing is not None:
        heading = run.turn_to(heading, facing)
    sense(pos, heading)
    if run.goal_alive(goal):
        k = int(math.ceil(run.reach_cells))
        r0, c0 = max(0, goal[0] - k), max(0, goal[1] - k)
        run.blacklist[r0 : goal[0] + k + 1, c0 : goal[1] + k + 1] = True
        run.blacklisted += 1
    return heading


def _nearest_true(mask: np.ndarray, pos: tuple[float, float]) -> tuple[int, int]:
    rr, cc = np.nonzero(mask)
    best = int(np.argmin((rr - pos[0]) ** 2 + (cc - pos[1]) ** 2))
    return (int(rr[best]), int(cc[best]))


def _towards_unknown(known: np.ndarray, cell: tuple[int, int], radius: float) -> float | None:
    """Heading (radians, x right, y up) from a cell towards the unknown cells around it."""
    k = int(math.ceil(radius))
    r, c = cell
    r0, c0 = max(0, r - k), max(0, c - k)
    window = known[r0 : r + k + 1, c0 : c + k + 1] == UNKNOWN
    rr, cc = np.nonzero(window)
    if rr.size == 0:
        return None
    d_row = float((rr + r0 - r).mean())
    d_col = float((cc + c0 - c).mean())
    if abs(d_row) < 1e-9 and abs(d_col) < 1e-9:
        return None
    return math.atan2(-d_row, d_col)


__all__ = ["ExploreSettings", "ExplorationResult", "explore", "reachable_free"]
