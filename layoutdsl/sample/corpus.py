"""Training data of the sampler: the room graphs of real plans (building XML, the thesis, §5.2).

A plan's room graph has one node per space, with its type (`rtype`: R, C or E), its label as
a spec writes it, and its area in m² (the polygon's: what the benchmark compares sampled room
sizes with); one edge per pair of spaces joined by at least one portal, with `kind` "e" for a
door and "i" for an opening (EXPLICIT / IMPLICIT portals). The plans are read by the project's
one building-XML reader (`layoutdsl.importer`), so a plan the importer refuses is refused here
too, with its diagnostics.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import networkx as nx

from layoutdsl.diagnostics import Diagnostic, has_errors
from layoutdsl.importer import read_building
from layoutdsl.importer.convert import spec_label

KINDS = ("school", "office")
"""Building kinds the corpus names in its file names (`school_X.xml`, `office_Y.xml`)."""

OTHER_KIND = "other"
"""The kind of a plan whose file name does not start with a known kind."""

DEFAULT_LABELS = {"R": "ROOM", "C": "CORRIDOR", "E": "ENTRANCE"}
"""A space without a label gets its type's word, as the importer names it."""

SHARED_CORPUS = Path(__file__).resolve().parents[3] / "shared" / "floorplans"
"""The 24-plan development corpus, where CI and the project's machines keep it: beside the
repository, in `../shared/floorplans`."""

BUNDLED_CORPUS = Path(__file__).resolve().parents[2] / "examples" / "floorplans"
"""The four plans that ship with the repository (examples/floorplans)."""


class CorpusError(ValueError):
    """A training folder that holds no usable plan (a usage error)."""


@dataclass(frozen=True, slots=True)
class PlanGraph:
    """One training plan: its name, its kind and its room graph."""

    name: str
    kind: str
    graph: nx.Graph


def plan_kind(name: str) -> str:
    """`school` for `school_Ursy1`, `office` for `office_Milano-1`, else `other`."""
    prefix = name.split("_", 1)[0].lower()
    return prefix if prefix in KINDS else OTHER_KIND


def default_corpus() -> Path:
    """The shared 24-plan corpus when this machine has it, else the bundled plans."""
    return SHARED_CORPUS if SHARED_CORPUS.is_dir() and any(SHARED_CORPUS.glob("*.xml")) else BUNDLED_CORPUS


def plan_files(folder: str | Path) -> list[Path]:
    """The building XML files of a folder, sorted by name (not recursive)."""
    folder = Path(folder)
    if not folder.is_dir():
        raise CorpusError(f"`{folder}` is not a folder of building XML plans")
    files = sorted(p for p in folder.iterdir() if p.suffix.lower() == ".xml" and p.is_file())
    if not files:
        raise CorpusError(f"`{folder}` holds no building XML plan (*.xml)")
    return files


def read_plan_graph(path: str | Path) -> tuple[PlanGraph | None, list[Diagnostic]]:
    """A plan's room graph, or (None, diagnostics) when the reader refuses the file."""
    path = Path(path)
    building, diagnostics = read_building(path)
    if building is None or has_errors(diagnostics):
        return None, diagnostics
    area_scale = building.metres_per_unit**2
    graph = nx.Graph(name=path.stem)
    for space in building.spaces:
        rtype = space.spec_type
        label = spec_label(space.label) or DEFAULT_LABELS[rtype]
        graph.add_node(space.id, rtype=rtype, label=label, area=round(space.area * area_scale, 3))
    for pair, portal_type in sorted(building.portal_edges().items(), key=lambda item: sorted(item[0])):
        a, b = sorted(pair)
        graph.add_edge(a, b, kind="i" if portal_type == "IMPLICIT" else "e")
    return PlanGraph(path.stem, plan_kind(path.stem), graph), diagnostics


def read_corpus(paths) -> list[PlanGraph]:
    """The room graphs of the given plan files (or of every plan in one folder), in order.

    Raises CorpusError naming the first plan the reader refuses: a model fitted on part of a
    corpus without saying so would be a different model.
    """
    if isinstance(paths, (str, Path)):
        paths = plan_files(paths)
    plans = []
    for path in paths:
        plan, diagnostics = read_plan_graph(path)
        if plan is None:
            first = next((d for d in diagnostics if d.is_error), None)
            reason = f"{first.code} {first.message}" if first else "unreadable"
            raise CorpusError(f"cannot use `{path}` for training: {reason}")
        plans.append(plan)
    if not plans:
        raise CorpusError("no training plan given")
    return plans
