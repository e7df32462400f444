"""Fit the room-size model on a folder of real plans (building XML).

    python -m layoutdsl.sizes.fit DIR [-o model.json]
    layoutdsl sizes fit DIR -o model.json          # the same, as a subcommand

A plan's building kind is its file name's prefix before the first `_` (`school_Ursy1.xml`
is a school), as in the corpus of real plans. Each plan is read with the project's XML
importer, every room rectangularized as the thesis does (§5.3.1: a rectangle of the
polygon's area with the bounding box's proportions), and its measured sides are the
samples. Plans that do not import are skipped with a message. The shipped model
(`layoutdsl/sizes/model.json`) is `python -m layoutdsl.sizes.fit ../shared/floorplans`,
the 24 plans of the development corpus; tests/sizes checks that refitting gives it byte
for byte.
"""

from __future__ import annotations

import argparse
import math
import statistics
import sys
from collections import Counter, defaultdict
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path

from layoutdsl.diagnostics import has_errors
from layoutdsl.importer import ImportOptions, import_building
from layoutdsl.sizes.model import (
    CORRIDOR_LABEL,
    QUANTILES,
    CorridorLaw,
    KindModel,
    SizeLaw,
    SizeModel,
)

_TYPE_ORDER = {"R": 0, "C": 1, "E": 2}


@dataclass(frozen=True, slots=True)
class RoomSample:
    """One measured room of a real plan."""

    kind: str
    rtype: str
    label: str
    long: float
    short: float
    doors: int


@dataclass(frozen=True, slots=True)
class PlanSample:
    """What one plan contributes: its rooms, its adjacencies, its outline."""

    name: str
    kind: str
    rooms: tuple[RoomSample, ...]
    adjacencies: tuple[tuple[str, str, str, float], ...]
    """(type a, type b, `e`/`i`, door width) per adjacency."""
    boundary: tuple[float, float]


def plan_kind(path: str | Path) -> str:
    """A plan's building kind: its file name's prefix (`school_Ursy1.xml` -> school)."""
    stem = Path(path).stem
    return stem.split("_", 1)[0].lower() if "_" in stem else "other"


def measure_plan(path: str | Path) -> tuple[PlanSample | None, list[str]]:
    """Import one plan and measure its rooms; (None, problems) when it does not import."""
    spec, diagnostics = import_building(path, ImportOptions(rectangular_only=True))
    if spec is None or has_errors(diagnostics):
        errors = [d.message for d in diagnostics if d.is_error]
        return None, errors or ["does not import"]
    kind = plan_kind(path)
    doors: Counter[str] = Counter()
    types = {room.id: room.rtype for room in spec.rooms}
    adjacencies = []
    for adjacency in spec.adjacencies:
        doors[adjacency.a] += 1
        doors[adjacency.b] += 1
        adjacencies.append((types[adjacency.a], types[adjacency.b], adjacency.kind, adjacency.door))
    rooms = tuple(
        RoomSample(kind, room.rtype, room.label.strip().upper(), max(room.target_w, room.target_h),
                   min(room.target_w, room.target_h), doors[room.id])
        for room in spec.rooms
    )  # fmt: skip
    boundary = (spec.boundary.w, spec.boundary.h) if spec.boundary else (0.0, 0.0)
    return PlanSample(Path(path).name, kind, rooms, tuple(adjacencies), boundary), []


def fit_model(
    plans: Iterable[str | Path], corpus: str = "", skipped: list[tuple[str, str]] | None = None
) -> SizeModel:
    """Fit the model on these plan files (see the module doc). A plan that does not import
    is left out, and (file name, first problem) appended to `skipped` when it is given.
    Raises ValueError when no plan imports."""
    samples: list[PlanSample] = []
    for path in sorted(Path(p) for p in plans):
        sample, problems = measure_plan(path)
        if sample is None:
            if skipped is not None:
                skipped.append((path.name, problems[0]))
            continue
        samples.append(sample)
    if not samples:
        raise ValueError("no plan imported: nothing to fit")
    by_kind: dict[str, list[PlanSample]] = defaultdict(list)
    for sample in samples:
        by_kind[sample.kind].append(sample)
    return SizeModel({kind: fit_kind(kind, found) for kind, found in sorted(by_kind.items())}, corpus)


def fit_folder(folder: str | Path, skipped: list[tuple[str, str]] | None = None) -> SizeModel:
    """Fit on every `*.xml` plan in a folder (see fit_model for `skipped`)."""
    folder = Path(folder)
    plans = sorted(folder.glob("*.xml"))
    if not plans:
        raise ValueError(f"no *.xml plan in {folder}")
    return fit_model(plans, corpus=folder.name, skipped=skipped)


def fit_kind(kind: str, plans: list[PlanSample]) -> KindModel:
    """The model of one building kind from its plans."""
    rooms = [room for plan in plans for room in plan.rooms]
    by_type: dict[str, list[RoomSample]] = defaultdict(list)
    by_label: dict[str, list[RoomSample]] = defaultdict(list)
    for room in rooms:
        by_type[room.rtype].append(room)
        by_label[room.label].append(room)
    label_types = {
        label: min(Counter(r.rtype for r in found).items(), key=lambda item: (-item[1], _TYPE_ORDER.get(item[0], 9)))[0]
        for label, found in by_label.items()
    }  # fmt: skip
    corridors = by_label.get(CORRIDOR_LABEL, [])
    adjacencies = [adjacency for plan in plans for adjacency in plan.adjacencies]
    pairs: dict[str, list[str]] = defaultdict(list)
    for type_a, type_b, kind_of_portal, _door in adjacencies:
        pairs["".join(sorted(type_a + type_b))].append(kind_of_portal)
    fills, aspects = [], []
    for plan in plans:
        w, h = plan.boundary
        if w > 0 and h > 0:
            fills.append(sum(room.long * room.short for room in plan.rooms) / (w * h))
            aspects.append(max(w, h) / min(w, h))
    return KindModel(
        kind=kind,
        plans=tuple(plan.name for plan in plans),
        overall=fit_law(rooms),
        by_type={rtype: fit_law(found) for rtype, found in sorted(by_type.items())},
        by_label={label: fit_law(found) for label, found in sorted(by_label.items())},
        label_types=dict(sorted(label_types.items())),
        corridor=fit_corridor(corridors) if len(corridors) >= 2 else None,
        door=statistics.median(door for *_, door in adjacencies) if adjacencies else 0.9,
        implicit_share={pair: kinds.count("i") / len(kinds) for pair, kinds in sorted(pairs.items())},
        fill=statistics.median(fills) if fills else 0.6,
        aspect=statistics.median(aspects) if aspects else 1.6,
    )


def fit_law(rooms: list[RoomSample]) -> SizeLaw:
    """Log-normal area and aspect-ratio quantiles of a group of rooms."""
    areas = [room.long * room.short for room in rooms]
    logs = [math.log(area) for area in areas]
    aspects = sorted(room.long / room.short for room in rooms)
    return SizeLaw(
        rooms=len(rooms),
        log_area_mean=statistics.fmean(logs),
        log_area_sd=statistics.stdev(logs) if len(logs) > 1 else 0.0,
        area_min=min(areas),
        area_max=max(areas),
        aspect_quantiles=tuple(_quantile(aspects, p) for p in QUANTILES),
        long_quantiles=tuple(_quantile(sorted(room.long for room in rooms), p) for p in QUANTILES),
        short_quantiles=tuple(_quantile(sorted(room.short for room in rooms), p) for p in QUANTILES),
    )


def fit_corridor(corridors: list[RoomSample]) -> CorridorLaw:
    """Width log-normal; length = a + b * doors by least squares; log spread around it."""
    widths = [math.log(room.short) for room in corridors]
    xs = [float(room.doors) for room in corridors]
    ys = [room.long for room in corridors]
    mean_x, mean_y = statistics.fmean(xs), statistics.fmean(ys)
    sxx = sum((x - mean_x) ** 2 for x in xs)
    slope = sum((x - mean_x) * (y - mean_y) for x, y in zip(xs, ys)) / sxx if sxx > 0 else 0.0
    slope = max(slope, 0.0)  # more doors never make a corridor shorter
    intercept = mean_y - slope * mean_x
    residuals = [math.log(y / max(intercept + slope * x, 1e-3)) for x, y in zip(xs, ys)]
    return CorridorLaw(
        rooms=len(corridors),
        log_width_mean=statistics.fmean(widths),
        log_width_sd=statistics.stdev(widths),
        length_intercept=intercept,
        length_per_door=slope,
        log_length_sd=statistics.stdev(residuals),
    )


def _quantile(ordered: list[float], p: float) -> float:
    """The p-quantile by linear interpolation between order statistics (numpy's default)."""
    position = p * (len(ordered) - 1)
    low = math.floor(position)
    high = min(low + 1, len(ordered) - 1)
    return ordered[low] + (ordered[high] - ordered[low]) * (position - low)


# ===== Command line =====


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("folder", metavar="DIR", help="folder of building XML plans named KIND_NAME.xml")
    parser.add_argument("-o", "--output", default="-", help="model JSON to write, or - for standard output (default)")


def run(args: argparse.Namespace) -> int:
    """Fit and write; 0 on success, 2 when the folder has no plan or the file cannot be written."""
    skipped: list[tuple[str, str]] = []
    try:
        model = fit_folder(args.folder, skipped)
    except ValueError as error:
        print(f"layoutdsl sizes fit: error: {error}", file=sys.stderr)
        return 2
    for name, problem in skipped:
        print(f"layoutdsl sizes fit: warning: skipped {name}: {problem}", file=sys.stderr)
    text = model.dumps()
    if args.output == "-":
        sys.stdout.write(text)
        return 0
    try:
        Path(args.output).write_text(text, encoding="utf-8")
    except OSError as error:
        print(f"layoutdsl sizes fit: error: cannot write `{args.output}`: {error.strerror or error}", file=sys.stderr)
        return 2
    summary = ", ".join(f"{kind}: {len(m.plans)} plans, {m.overall.rooms} rooms" for kind, m in model.kinds.items())
    print(f"fitted {summary} into `{args.output}`", file=sys.stderr)
    return 0


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m layoutdsl.sizes.fit", description=__doc__.split("\n\n")[0])
    add_arguments(parser)
    return run(parser.parse_args(argv))


if __name__ == "__main__":
    sys.exit(main())
