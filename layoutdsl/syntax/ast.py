"""The spec's abstract syntax tree: frozen dataclasses, each carrying its source span.

Lengths are metres. Coordinates are in the boundary's frame: origin at the boundary's
bottom-left corner, x to the right, y upwards, and a rectangle's (x, y) is its bottom-left
corner (the thesis, §5.4). Spans never take part in equality, so `parse(format(spec)) == spec`
compares content only.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from types import MappingProxyType

from layoutdsl.diagnostics.source import Span

_NO_SPANS: Mapping[str, Span] = MappingProxyType({})

ROOM_TYPE_NAMES = {"R": "room", "C": "corridor", "E": "entrance"}
"""Room type letter -> what it is: R generic room, C corridor, E entrance (the thesis, §5.2)."""

ROOM_TYPES = tuple(ROOM_TYPE_NAMES)

EMPHASES = ("default", "heuristics", "feasibility", "optimality", "easycip")
"""Values of the `emphasis` setting (and `--emphasis`): SCIP's emphasis meta settings."""

SIZES_PENDING = ""
"""`Room.sizes_from` of a sizeless room line before the size model has sized it."""

NO_SIZE = math.nan
"""The eight numbers of a sizeless room before it is sized (one object, so two parses of the
same sizeless line compare equal: tuple comparison tries identity first)."""

ADJACENCY_TYPES = ("e", "i")
"""e explicit portal (a door), i implicit portal (an opening with no barrier)."""


@dataclass(frozen=True, slots=True)
class Room:
    """A rectangular room to place (one line of the `rooms` section)."""

    id: str
    min_w: float
    max_w: float
    target_w: float
    min_h: float
    max_h: float
    target_h: float
    min_ar: float
    max_ar: float
    rtype: str
    """One of ROOM_TYPES."""
    label: str
    """Free text; may contain spaces (`MEDIUM SERVICE`)."""
    on_boundary: bool = False
    """`onB`: the room must touch a side of the boundary (5.12)."""
    rho_cover: float = 1.0
    """Weight of this room's area in E_cover (5.2)."""
    rho_error: float = 1.0
    """Weight of this room's size error in E_error (5.3)."""
    span: Span | None = field(default=None, compare=False)
    spans: Mapping[str, Span] = field(default_factory=lambda: _NO_SPANS, compare=False)
    """Span of each field by name (`min_w`, `label`, ...), for pointed diagnostics."""
    sizes_from: str | None = field(default=None, compare=False)
    """None: the spec gives the eight numbers. Otherwise the line is sizeless (`R1 R
    CLASSROOM`): SIZES_PENDING until the size model sizes it (layoutdsl.sizes.resolve),
    then which group of the model the sizes came from. `rtype` is "" while pending if the
    line gave no type."""

    @property
    def is_corridor(self) -> bool:
        return self.rtype == "C"

    @property
    def sizeless(self) -> bool:
        """Does the spec leave this room's sizes to the size model?"""
        return self.sizes_from is not None

    @property
    def has_sizes(self) -> bool:
        """Are the eight numbers known (given, or filled in by the size model)?"""
        return not math.isnan(self.min_w)


@dataclass(frozen=True, slots=True)
class Arm:
    """The second rectangle of an L-shaped room (one line of the `arms` section).

    The room's line in `rooms` gives its first rectangle; this one is joined to it flush
    along one full edge, at a corner of the shared side, so the union is an L with no wall
    inside (the thesis' first item of future work, §7: rooms made of several rectangles).
    The bounds read like the room line's columns and apply to this rectangle alone; as
    written, wide or tall, the two lines also say whether the arm runs across the first
    rectangle or along it (`crosses`).
    """

    room: str
    min_w: float
    max_w: float
    target_w: float
    min_h: float
    max_h: float
    target_h: float
    min_ar: float
    max_ar: float
    span: Span | None = field(default=None, compare=False)
    spans: Mapping[str, Span] = field(default_factory=lambda: _NO_SPANS, compare=False)

    def crosses(self, room: Room) -> bool | None:
        """Does the L's arm run across its room's first rectangle (True: one line is wide,
        the other tall) or along it (False)? None when a line's targets are square, and so
        say nothing. The L keeps this shape however it is turned."""
        room_wide, arm_wide = room.target_w - room.target_h, self.target_w - self.target_h
        if room_wide == 0 or arm_wide == 0:
            return None
        return (room_wide > 0) != (arm_wide > 0)

    def as_room(self, room: Room) -> Room:
        """This rectangle as a Room of its own (id `arm_id(room.id)`), with the room's type,
        label and weights: how the checks and the construction size it."""
        return Room(
            arm_id(room.id), self.min_w, self.max_w, self.target_w, self.min_h, self.max_h,
            self.target_h, self.min_ar, self.max_ar, room.rtype, room.label, False,
            room.rho_cover, room.rho_error, span=self.span, spans=self.spans,
        )  # fmt: skip


ARM_SUFFIX = "/arm"
"""What `arm_id` appends to a room id: the name of an L-room's second rectangle wherever
rectangles are keyed by id (the construction's geometry, messages about the arm's sizes)."""


def arm_id(room_id: str) -> str:
    """The key of an L-room's second rectangle."""
    return room_id + ARM_SUFFIX


@dataclass(frozen=True, slots=True)
class Obstacle:
    """A fixed rectangle inside the boundary that no room may overlap."""

    id: str
    x: float
    y: float
    w: float
    h: float
    span: Span | None = field(default=None, compare=False)
    spans: Mapping[str, Span] = field(default_factory=lambda: _NO_SPANS, compare=False)


@dataclass(frozen=True, slots=True)
class Boundary:
    """The rectangle every room must lie in, with its obstacles."""

    w: float
    h: float
    obstacles: tuple[Obstacle, ...] = ()
    span: Span | None = field(default=None, compare=False)
    spans: Mapping[str, Span] = field(default_factory=lambda: _NO_SPANS, compare=False)
    chosen: bool = field(default=False, compare=False)
    """True when the spec gave no boundary and the tool chose this one
    (layoutdsl.sizes.boundary.choose_boundary): compile may then grow it."""


@dataclass(frozen=True, slots=True)
class Adjacency:
    """Two rooms that share a wall with a portal of at least `door` metres."""

    a: str
    b: str
    door: float
    """`mina`: the door length; the shared wall must be at least door / door_utilization."""
    kind: str
    """One of ADJACENCY_TYPES."""
    span: Span | None = field(default=None, compare=False)
    spans: Mapping[str, Span] = field(default_factory=lambda: _NO_SPANS, compare=False)


@dataclass(frozen=True, slots=True)
class Position:
    """The room must cover the point (x, y) (5.10). At most one per room."""

    room: str
    x: float
    y: float
    span: Span | None = field(default=None, compare=False)
    spans: Mapping[str, Span] = field(default_factory=lambda: _NO_SPANS, compare=False)


@dataclass(frozen=True, slots=True)
class Connection:
    """The room must cover both points (5.11). A room may have several."""

    room: str
    x1: float
    y1: float
    x2: float
    y2: float
    span: Span | None = field(default=None, compare=False)
    spans: Mapping[str, Span] = field(default_factory=lambda: _NO_SPANS, compare=False)


@dataclass(frozen=True, slots=True)
class ClusterMember:
    """A room of a cluster and its point in the cluster's own frame (5.13)."""

    room: str
    x: float
    y: float
    span: Span | None = field(default=None, compare=False)
    spans: Mapping[str, Span] = field(default_factory=lambda: _NO_SPANS, compare=False)


@dataclass(frozen=True, slots=True)
class Cluster:
    """Rooms whose relative positions are kept, the cluster itself free to move (5.13)."""

    id: str
    members: tuple[ClusterMember, ...]
    span: Span | None = field(default=None, compare=False)
    spans: Mapping[str, Span] = field(default_factory=lambda: _NO_SPANS, compare=False)


@dataclass(frozen=True, slots=True)
class Hint:
    """An optional starting rectangle for a room (e.g. its place in the original plan).

    Not a constraint: the solver may move and resize the room freely. Hints only guide the
    construction of the first feasible layout.
    """

    room: str
    x: float
    y: float
    w: float
    h: float
    span: Span | None = field(default=None, compare=False)
    spans: Mapping[str, Span] = field(default_factory=lambda: _NO_SPANS, compare=False)


@dataclass(frozen=True, slots=True)
class Settings:
    """Program parameters the thesis kept outside its file (the `settings` section).

    Every field has a default; `explicit` names the ones the spec set, so the formatter
    writes back only those and CLI flags can tell a default from a choice.
    """

    lambda_cover: float = 0.1
    """λ_cover (5.1). The default formulation counts a room's area only up to its target
    (model.Formulation.cover_up_to_target); with the thesis' term as written, the thesis
    found 0.1-0.2 keeps the generated area near the original (§6.1.1)."""
    lambda_error: float = 1.0
    """λ_error (5.1)."""
    walldim: float = 0.2
    """Wall thickness in metres: the gap between two rooms (5.8, 5.9)."""
    door_utilization: float = 1.0
    """A shared wall must be at least door / door_utilization long (5.9); in (0, 1]."""
    cluster_margin: float = 0.5
    """How far (metres) a cluster member may deviate from its cluster point (5.13)."""
    time_limit: float = 60.0
    """Wall-clock seconds for the whole solve."""
    gap: float = 0.01
    """Relative optimality gap at which the solve stops."""
    seed: int = 0
    """Random seed for SCIP and for the construction of the first layout."""
    emphasis: str = "default"
    """SCIP emphasis: default, heuristics, feasibility, optimality, easycip. SCIP's defaults:
    the whole-model search starts from the generator's layout, and with heuristics emphasis
    it took twice the time to reach the same optimum (office_small 21.6 s against 5.3 s,
    school_cycle 20.7 s against 10.3 s) and ran into the wall clock on school_Sabadell3
    where the defaults stopped at their work limit with the same layout."""
    node_limit: int | None = None
    """Stop after this many branch-and-bound nodes: a deterministic stopping rule."""
    kind: str = "school"
    """The building kind whose room sizes a sizeless room line gets (layoutdsl.sizes)."""
    explicit: frozenset[str] = field(default=frozenset(), compare=False)
    span: Span | None = field(default=None, compare=False)
    spans: Mapping[str, Span] = field(default_factory=lambda: _NO_SPANS, compare=False)


SETTING_KEYS = (
    "name", "lambda_cover", "lambda_error", "walldim", "door_utilization", "cluster_margin",
    "time_limit", "gap", "seed", "emphasis", "node_limit", "kind",
)  # fmt: skip
"""Keys of the `settings` section, in the order the formatter writes them: `name` (the
Spec's name), then the Settings fields."""


@dataclass(frozen=True, slots=True)
class Spec:
    """A whole layout spec, as written (names not yet resolved: see check.py)."""

    name: str
    """The building's name: the file's stem unless a `name` setting says otherwise."""
    rooms: tuple[Room, ...]
    boundary: Boundary | None
    adjacencies: tuple[Adjacency, ...] = ()
    positions: tuple[Position, ...] = ()
    connections: tuple[Connection, ...] = ()
    clusters: tuple[Cluster, ...] = ()
    hints: tuple[Hint, ...] = ()
    settings: Settings = Settings()
    path: str = field(default="<spec>", compare=False)
    arms: tuple[Arm, ...] = ()
    """The second rectangles of the L-shaped rooms (at most one per room)."""

    def room(self, room_id: str) -> Room | None:
        """The room with this id, or None."""
        for room in self.rooms:
            if room.id == room_id:
                return room
        return None

    def arm(self, room_id: str) -> Arm | None:
        """The second rectangle of an L-shaped room, or None for a rectangular one."""
        for arm in self.arms:
            if arm.room == room_id:
                return arm
        return None

    @property
    def room_ids(self) -> tuple[str, ...]:
        return tuple(room.id for room in self.rooms)

    def door_neighbours(self) -> dict[str, set[str]]:
        """Room id -> the rooms it shares a door with (rooms without a door left out)."""
        neighbours: dict[str, set[str]] = {}
        for adj in self.adjacencies:
            neighbours.setdefault(adj.a, set()).add(adj.b)
            neighbours.setdefault(adj.b, set()).add(adj.a)
        return neighbours

    def restricted_to(self, keep, name: str) -> Spec:
        """The spec of some rooms alone: those rooms, in the same boundary, with every
        constraint among them only (the sub-problems of cycle decomposition and generation)."""
        keep = set(keep)
        return replace(
            self,
            name=name,
            rooms=tuple(room for room in self.rooms if room.id in keep),
            adjacencies=tuple(a for a in self.adjacencies if a.a in keep and a.b in keep),
            positions=tuple(p for p in self.positions if p.room in keep),
            connections=tuple(c for c in self.connections if c.room in keep),
            clusters=tuple(c for c in self.clusters if all(member.room in keep for member in c.members)),
            hints=tuple(h for h in self.hints if h.room in keep),
            arms=tuple(a for a in self.arms if a.room in keep),
        )
