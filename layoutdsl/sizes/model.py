"""The room-size model: per building kind, room type and label, how big rooms are.

Fitted from real plans (`layoutdsl.sizes.fit`), shipped as JSON (`model.json` beside this
module), and used wherever a room has no sizes of its own: a sizeless room line
(`R1 R CLASSROOM`), a room graph imported without geometry, a sampled building.

The parametric form, per group of rooms (a label, a room type, or a whole kind):

- area: log-normal, `log A ~ N(mu, sigma)`. Room areas in the corpus are skewed (a few
  large halls, many small closets) and positive; a log-normal is the simplest law with
  both properties, and its median exp(mu) is the typical area;
- aspect ratio (long side / short side, >= 1): the empirical quantiles at QUANTILES,
  sampled by inverse transform with linear interpolation between them. Aspect ratios are
  bounded below by 1 and bimodal for some labels, which no simple law fits;
- corridors (label CORRIDOR): the width (short side) is log-normal; the length grows with
  the number of doors on the corridor, `L = a + b * doors` (least squares over the corpus),
  with a log-normal spread around that line. A corridor exists to reach its doors, and in
  the corpus its length follows its door count (Pearson r 0.59 in schools, 0.85 in
  offices), which area alone does not say.

Area and aspect are treated as independent. A label with fewer than MIN_SAMPLES rooms in
the corpus falls back to its room type (R, C, E), and a type with too few to its kind.

A room's eight numbers (`RoomSize`) come from a target rectangle exactly as the importer
makes them from a measured room (the thesis, §5.3.2): the sides may shrink by 30 % and grow
by 20 % (corridors ± 40 %), never below 1 m, and the aspect-ratio bounds widen with the
target's elongation. A room sized by the model is thus what importing a plan whose room
has the model's size would give.
"""

from __future__ import annotations

import json
import math
import random
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path

QUANTILES = (0.0, 0.1, 0.25, 0.5, 0.75, 0.9, 1.0)
"""Probabilities at which a group's aspect-ratio quantiles are stored."""

MIN_SAMPLES = 5
"""A label (or type) with fewer rooms than this borrows its type's (or kind's) law."""

CORRIDOR_LABEL = "CORRIDOR"
"""The label whose length is tied to its door count (see the module doc)."""

Z_CLIP = 2.0
"""Drawn areas and corridor lengths stay within this many standard deviations (log scale):
the tails of a fitted log-normal reach sizes no plan in the corpus has."""

FORMAT = "layoutdsl-size-model"
VERSION = 1

# The importer's variance rule (the thesis, §5.3.2), with its default parameters.
VAR_PLUS = 0.2
VAR_MINUS = 0.3
VAR_CORRIDOR = 0.4
MINDIM = 1.0
ALPHA = 1.5
BETA = 0.2
WALL = 0.2
"""The default wall thickness (`walldim`): a room must hold its door between two walls."""

SHIPPED_MODEL = Path(__file__).resolve().parent / "model.json"


class ModelError(ValueError):
    """A size model file that cannot be used (wrong format, unknown kind)."""


@dataclass(frozen=True, slots=True)
class RoomSize:
    """The eight numbers of a room line (metres), and where they came from."""

    min_w: float
    max_w: float
    target_w: float
    min_h: float
    max_h: float
    target_h: float
    min_ar: float
    max_ar: float
    source: str = field(default="", compare=False)
    """Which group of the model gave them, e.g. `school, label CLASSROOM (142 rooms)`."""

    def as_tuple(self) -> tuple[float, ...]:
        """The eight numbers in room-line order."""
        return (self.min_w, self.max_w, self.target_w, self.min_h, self.max_h, self.target_h,
                self.min_ar, self.max_ar)  # fmt: skip


@dataclass(frozen=True, slots=True)
class SizeLaw:
    """The fitted law of one group of rooms (see the module doc)."""

    rooms: int
    log_area_mean: float
    log_area_sd: float
    area_min: float
    area_max: float
    aspect_quantiles: tuple[float, ...]
    """Aspect ratios (>= 1) at QUANTILES."""
    long_quantiles: tuple[float, ...] = ()
    """The rooms' long sides (metres) at QUANTILES: what the corpus' widths look like, for
    reports (`sizes show --format json`) and comparisons; sizes come from area and aspect."""
    short_quantiles: tuple[float, ...] = ()
    """The rooms' short sides (metres) at QUANTILES."""

    @property
    def typical_area(self) -> float:
        return math.exp(self.log_area_mean)

    @property
    def typical_aspect(self) -> float:
        return _interpolate(QUANTILES, self.aspect_quantiles, 0.5)

    def draw_area(self, rng: random.Random) -> float:
        z = max(-Z_CLIP, min(Z_CLIP, rng.gauss(0.0, 1.0)))
        area = math.exp(self.log_area_mean + self.log_area_sd * z)
        return min(max(area, self.area_min), self.area_max)

    def draw_aspect(self, rng: random.Random) -> float:
        return _interpolate(QUANTILES, self.aspect_quantiles, rng.random())

    def to_json(self) -> dict:
        return {
            "rooms": self.rooms,
            "log_area_mean": self.log_area_mean,
            "log_area_sd": self.log_area_sd,
            "area_min": self.area_min,
            "area_max": self.area_max,
            "aspect_quantiles": list(self.aspect_quantiles),
            "long_quantiles": list(self.long_quantiles),
            "short_quantiles": list(self.short_quantiles),
        }

    @classmethod
    def from_json(cls, data: dict) -> SizeLaw:
        return cls(
            int(data["rooms"]), float(data["log_area_mean"]), float(data["log_area_sd"]),
            float(data["area_min"]), float(data["area_max"]),
            tuple(float(q) for q in data["aspect_quantiles"]),
            tuple(float(q) for q in data.get("long_quantiles", ())),
            tuple(float(q) for q in data.get("short_quantiles", ())),
        )  # fmt: skip


@dataclass(frozen=True, slots=True)
class CorridorLaw:
    """Corridor width (log-normal) and length `a + b * doors` (log-normal spread)."""

    rooms: int
    log_width_mean: float
    log_width_sd: float
    length_intercept: float
    length_per_door: float
    log_length_sd: float
    """Standard deviation of log(measured length / the line's length)."""

    def typical(self, doors: int) -> tuple[float, float]:
        """(length, width) of a corridor with this many doors."""
        width = math.exp(self.log_width_mean)
        return max(width, self.length_intercept + self.length_per_door * doors), width

    def draw(self, doors: int, rng: random.Random) -> tuple[float, float]:
        length, _ = self.typical(doors)
        zw = max(-Z_CLIP, min(Z_CLIP, rng.gauss(0.0, 1.0)))
        zl = max(-Z_CLIP, min(Z_CLIP, rng.gauss(0.0, 1.0)))
        width = math.exp(self.log_width_mean + self.log_width_sd * zw)
        return max(width, length * math.exp(self.log_length_sd * zl)), width

    def to_json(self) -> dict:
        return {
            "rooms": self.rooms,
            "log_width_mean": self.log_width_mean,
            "log_width_sd": self.log_width_sd,
            "length_intercept": self.length_intercept,
            "length_per_door": self.length_per_door,
            "log_length_sd": self.log_length_sd,
        }

    @classmethod
    def from_json(cls, data: dict) -> CorridorLaw:
        return cls(
            int(data["rooms"]), float(data["log_width_mean"]), float(data["log_width_sd"]),
            float(data["length_intercept"]), float(data["length_per_door"]), float(data["log_length_sd"]),
        )  # fmt: skip


@dataclass(frozen=True, slots=True)
class KindModel:
    """Everything the model knows about one building kind (school, office)."""

    kind: str
    plans: tuple[str, ...]
    """The plan files it was fitted on (names only)."""
    overall: SizeLaw
    by_type: dict[str, SizeLaw]
    by_label: dict[str, SizeLaw]
    label_types: dict[str, str]
    """Label -> the room type it has most often in the corpus (ties: R, then C, then E)."""
    corridor: CorridorLaw | None
    door: float
    """The median door width in metres."""
    implicit_share: dict[str, float]
    """Room-type pair (`CC`, `CR`, ... sorted) -> share of its adjacencies that are openings (i)."""
    fill: float
    """Median share of the plans' bounding box that their rooms' target areas cover."""
    aspect: float
    """Median aspect ratio (long / short) of the plans' bounding boxes."""

    def law(self, rtype: str, label: str) -> tuple[SizeLaw, str]:
        """The law for a room and a description of the group it comes from."""
        key = label.strip().upper()
        found = self.by_label.get(key)
        if found is not None and found.rooms >= MIN_SAMPLES:
            return found, f"{self.kind}, label {key} ({found.rooms} rooms)"
        found = self.by_type.get(rtype)
        if found is not None and found.rooms >= MIN_SAMPLES:
            why = "" if key not in self.by_label else f"; {key} has only {self.by_label[key].rooms}"
            return found, f"{self.kind}, type {rtype} ({found.rooms} rooms{why})"
        return self.overall, f"{self.kind}, all rooms ({self.overall.rooms} rooms)"

    def uses_corridor_law(self, rtype: str, label: str, doors: int | None) -> bool:
        return (
            doors is not None and self.corridor is not None and self.corridor.rooms >= MIN_SAMPLES
            and label.strip().upper() == CORRIDOR_LABEL
        )  # fmt: skip

    def to_json(self) -> dict:
        return {
            "plans": list(self.plans),
            "door": self.door,
            "fill": self.fill,
            "aspect": self.aspect,
            "implicit_share": dict(sorted(self.implicit_share.items())),
            "label_types": dict(sorted(self.label_types.items())),
            "overall": self.overall.to_json(),
            "by_type": {k: v.to_json() for k, v in sorted(self.by_type.items())},
            "by_label": {k: v.to_json() for k, v in sorted(self.by_label.items())},
            "corridor": self.corridor.to_json() if self.corridor else None,
        }

    @classmethod
    def from_json(cls, kind: str, data: dict) -> KindModel:
        return cls(
            kind=kind,
            plans=tuple(data["plans"]),
            overall=SizeLaw.from_json(data["overall"]),
            by_type={k: SizeLaw.from_json(v) for k, v in data["by_type"].items()},
            by_label={k: SizeLaw.from_json(v) for k, v in data["by_label"].items()},
            label_types=dict(data["label_types"]),
            corridor=CorridorLaw.from_json(data["corridor"]) if data.get("corridor") else None,
            door=float(data["door"]),
            implicit_share={k: float(v) for k, v in data["implicit_share"].items()},
            fill=float(data["fill"]),
            aspect=float(data["aspect"]),
        )


@dataclass(frozen=True, slots=True)
class SizeModel:
    """Room sizes per building kind: typical (deterministic) and drawn (seeded)."""

    kinds: dict[str, KindModel]
    corpus: str = ""
    """What it was fitted on, in words (the folder's name)."""

    def kind(self, kind: str) -> KindModel:
        """The model of one building kind; raises ModelError naming the known ones."""
        found = self.kinds.get(kind)
        if found is None:
            raise ModelError(f"unknown building kind `{kind}`; the model knows " + ", ".join(sorted(self.kinds)))
        return found

    def label_type(self, kind: str, label: str) -> str:
        """The room type a label usually has (R when the corpus never saw it)."""
        return self.kind(kind).label_types.get(label.strip().upper(), "R")

    def room_sizes(self, kind: str, rtype: str, label: str, *, doors: int | None = None) -> RoomSize:
        """Typical sizes: the law's median area at its median aspect ratio.

        `doors` (the room's adjacency count) sizes a CORRIDOR by its length law."""
        model = self.kind(kind)
        if model.uses_corridor_law(rtype, label, doors):
            length, width = model.corridor.typical(doors)
            source = f"{kind}, corridor with {doors} doors ({model.corridor.rooms} corridors)"
            return room_size_from_target(length, width, rtype, model.door, source)
        law, source = model.law(rtype, label)
        return _from_area(law.typical_area, law.typical_aspect, rtype, model.door, source)

    def sample_room_sizes(
        self, kind: str, rtype: str, label: str, rng: random.Random, *, doors: int | None = None
    ) -> RoomSize:
        """Drawn sizes: area and aspect ratio drawn from the law with `rng` (the same seed
        gives the same sizes on any machine: only `random.Random` is used)."""
        model = self.kind(kind)
        if model.uses_corridor_law(rtype, label, doors):
            length, width = model.corridor.draw(doors, rng)
            source = f"{kind}, corridor with {doors} doors, drawn"
            return room_size_from_target(length, width, rtype, model.door, source)
        law, source = model.law(rtype, label)
        area = law.draw_area(rng)
        aspect = law.draw_aspect(rng)
        return _from_area(area, aspect, rtype, model.door, source + ", drawn")

    def door(self, kind: str) -> float:
        return self.kind(kind).door

    def adjacency_kind(self, kind: str, type_a: str, type_b: str) -> str:
        """`i` (an opening) when most adjacencies between these room types are, else `e`."""
        share = self.kind(kind).implicit_share.get("".join(sorted(type_a + type_b)), 0.0)
        return "i" if share > 0.5 else "e"

    def to_json(self) -> dict:
        return {
            "format": FORMAT,
            "version": VERSION,
            "corpus": self.corpus,
            "parameters": {"quantiles": list(QUANTILES), "min_samples": MIN_SAMPLES, "z_clip": Z_CLIP},
            "kinds": {k: v.to_json() for k, v in sorted(self.kinds.items())},
        }

    def dumps(self) -> str:
        """The model as JSON text (stable: sorted keys, rounded numbers, one trailing newline)."""
        return json.dumps(_rounded(self.to_json()), indent=1, sort_keys=True) + "\n"

    @classmethod
    def from_json(cls, data: dict) -> SizeModel:
        if not isinstance(data, dict) or data.get("format") != FORMAT:
            raise ModelError(f"not a size model (expected \"format\": \"{FORMAT}\")")
        if data.get("version") != VERSION:
            raise ModelError(f"size model version {data.get('version')!r}, this layoutdsl reads {VERSION}")
        try:
            kinds = {k: KindModel.from_json(k, v) for k, v in data["kinds"].items()}
        except (KeyError, TypeError, ValueError) as error:
            raise ModelError(f"malformed size model: {type(error).__name__}: {error}") from None
        if not kinds:
            raise ModelError("the size model knows no building kind")
        return cls(kinds, str(data.get("corpus", "")))


def load_model(path: str | Path | None = None) -> SizeModel:
    """The size model in `path` (None: the shipped model). Raises OSError, ModelError."""
    if path is None:
        return _shipped()
    return _load(Path(path))


@lru_cache(maxsize=1)
def _shipped() -> SizeModel:
    return _load(SHIPPED_MODEL)


def _load(path: Path) -> SizeModel:
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except json.JSONDecodeError as error:
        raise ModelError(f"{path}: not JSON ({error.msg} at line {error.lineno})") from None
    return SizeModel.from_json(data)


# ===== From a target rectangle to a room line's eight numbers =====


def _from_area(area: float, aspect: float, rtype: str, door: float, source: str) -> RoomSize:
    aspect = max(1.0, aspect)
    return room_size_from_target(math.sqrt(area * aspect), math.sqrt(area / aspect), rtype, door, source)


def _floor3(value: float) -> float:
    return math.floor(value * 1000 + 1e-6) / 1000


def _ceil3(value: float) -> float:
    return math.ceil(value * 1000 - 1e-6) / 1000


def room_size_from_target(
    width: float, height: float, rtype: str, door: float = 0.9, source: str = ""
) -> RoomSize:
    """The eight numbers of a room whose target is `width` x `height` (the importer's rule,
    the thesis §5.3.2; see the module doc). Targets are rounded to centimetres, bounds to
    millimetres outwards, and the target is always a feasible witness of its own bounds."""
    plus, minus = (VAR_CORRIDOR, VAR_CORRIDOR) if rtype == "C" else (VAR_PLUS, VAR_MINUS)
    target_w = max(round(width, 2), MINDIM)
    target_h = max(round(height, 2), MINDIM)
    min_w = max(MINDIM, _floor3(target_w * (1 - minus)))
    min_h = max(MINDIM, _floor3(target_h * (1 - minus)))
    max_w = _ceil3(target_w * (1 + plus))
    max_h = _ceil3(target_h * (1 + plus))
    door_side = door + 2 * WALL
    widened = max(max_w, max_h) < door_side
    if widened:  # the room must hold its door between two walls (5.9)
        if max_w >= max_h:
            max_w = _ceil3(door_side)
        else:
            max_h = _ceil3(door_side)
    ar_target = max(target_w, target_h) / min(target_w, target_h)
    var_avg = (plus + minus) / 2
    margin = ALPHA * var_avg + BETA * var_avg * (ar_target - 1) ** 2
    min_ar = max(1.0, _floor3(ar_target - margin))
    max_ar = _ceil3(ar_target + margin)
    if widened:
        max_ar = max(max_ar, _ceil3(door_side / min(max_w, max_h)))
    return RoomSize(min_w, max_w, target_w, min_h, max_h, target_h, min_ar, max_ar, source)


# ===== Helpers =====


def _interpolate(xs: tuple[float, ...], ys: tuple[float, ...], x: float) -> float:
    """Piecewise-linear y(x) through the points (xs increasing)."""
    if x <= xs[0]:
        return ys[0]
    for (x0, y0), (x1, y1) in zip(zip(xs, ys), zip(xs[1:], ys[1:])):
        if x <= x1:
            return y0 if x1 == x0 else y0 + (y1 - y0) * (x - x0) / (x1 - x0)
    return ys[-1]


def _rounded(value):
    """Numbers to 6 decimals, so a refit on another machine writes the same bytes."""
    if isinstance(value, float):
        return round(value, 6) + 0.0  # + 0.0 turns -0.0 into 0.0
    if isinstance(value, dict):
        return {k: _rounded(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_rounded(v) for v in value]
    return value
