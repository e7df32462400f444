"""The sampler's model: a graph grammar whose pieces and rates are read off real plans.

A real plan's room graph (layoutdsl.sample.corpus) is cut at its corridor-like spaces (type C:
corridors, halls, lobbies, and what the plans type C such as washrooms). What remains falls
apart into clusters of rooms and entrances: a classroom alone, a classroom with its closet, a
row of labs with doors between them. A cluster joined to one corridor is that corridor's
*pendant*; a cluster joined to two corridors or more is a *bridge* (a room with a door on two
corridors, a suite between two wings).

Fitting keeps, per plan:
- each corridor-like space as a `CorridorProfile`: its label, how many corridor-like
  neighbours it has (its degree in the backbone) and its pendants, exactly as drawn;
- its bridges, each with the corridors it touches numbered as ports;
- how many corridor-to-corridor edges close cycles among corridors (cycle rank of the
  corridor subgraph), and which corridor-to-corridor edges are openings ("i") rather than
  doors;
- its whole room graph, so that samples can be checked against it (novelty).

Sampling (layoutdsl.sample.generate) draws a plan as a template, a number of corridors near
its own, a profile per corridor from the template or from every plan of the kind, joins the
corridors into a random tree with the profiles' degrees, and adds bridges and corridor cycles
at the template's rates. This is the constructive idea of Luperto & Amigoni's graph sampling
for indoor environments (new buildings from fitted pieces of real ones) in the explicit,
measurable form of ProcTHOR's room-spec sampling (Deitke et al. 2022): counts and pieces are
drawn from fitted distributions, structure is assembled by rules, and every output is checked.

The fitted model is plain JSON: `layoutdsl/sample/data/grammar.json` ships, fitted on the
24 real plans of the development corpus; `layoutdsl sample --train DIR --save-model FILE`
refits it.
"""

from __future__ import annotations

import hashlib
import json
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path

import networkx as nx

from layoutdsl.sample.corpus import PlanGraph

FORMAT_VERSION = 1
"""Bumped when the JSON layout of a fitted grammar changes."""

SHIPPED_MODEL = "grammar.json"
"""The fitted grammar in the package's data folder."""

CORRIDOR_LIKE = "C"


@dataclass(frozen=True, slots=True)
class Cluster:
    """Rooms and entrances that hang together off the corridors.

    `nodes` are (rtype, label); `edges` (i, j, kind) join two of them; `attach` (i, port,
    kind) joins node i to the cluster's port-th corridor (a pendant has the one port 0).
    """

    nodes: tuple[tuple[str, str], ...]
    edges: tuple[tuple[int, int, str], ...]
    attach: tuple[tuple[int, int, str], ...]
    spans: tuple[int, ...] = ()
    """A bridge's ports 1, 2, ...: how far (in doors) their corridor was from port 0's in the
    plan without the bridge, 0 when only the bridge joined them. Real bridges rarely join
    neighbouring corridors (that would close a triangle); a sample places them as far apart."""

    @property
    def ports(self) -> int:
        return 1 + max(port for _, port, _ in self.attach)

    def to_json(self) -> dict:
        data = {"nodes": [list(n) for n in self.nodes], "edges": [list(e) for e in self.edges],
                "attach": [list(a) for a in self.attach]}
        if self.spans:
            data["spans"] = list(self.spans)
        return data

    @classmethod
    def from_json(cls, data: dict) -> Cluster:
        return cls(tuple((str(t), str(l)) for t, l in data["nodes"]),
                   tuple((int(a), int(b), str(k)) for a, b, k in data["edges"]),
                   tuple((int(i), int(p), str(k)) for i, p, k in data["attach"]),
                   tuple(int(d) for d in data.get("spans", ())))


@dataclass(frozen=True, slots=True)
class CorridorProfile:
    """One corridor-like space of a real plan: label, backbone degree and its pendants."""

    label: str
    degree: int
    """How many corridor-like neighbours it has in its plan."""
    pendants: tuple[Cluster, ...]

    def to_json(self) -> dict:
        return {"label": self.label, "degree": self.degree, "pendants": [c.to_json() for c in self.pendants]}

    @classmethod
    def from_json(cls, data: dict) -> CorridorProfile:
        return cls(str(data["label"]), int(data["degree"]), tuple(Cluster.from_json(c) for c in data["pendants"]))


@dataclass(frozen=True, slots=True)
class PlanModel:
    """What the grammar keeps of one training plan."""

    name: str
    kind: str
    rooms: int
    corridors: tuple[CorridorProfile, ...]
    bridges: tuple[Cluster, ...]
    corridor_cycles: tuple[int, ...]
    """Lengths of the cycles among corridor-like spaces (a minimum cycle basis of their
    subgraph): its cycle rank is how many there are."""
    corridor_edges: int
    corridor_openings: int
    """Corridor-to-corridor edges that are openings ("i"), of `corridor_edges`."""
    nodes: tuple[tuple[str, str], ...]
    """The plan's whole room graph: (rtype, label) per node..."""
    edges: tuple[tuple[int, int], ...]
    """...and its edges, for the novelty check."""

    def graph(self) -> nx.Graph:
        """The plan's room graph as the grammar keeps it (nodes 0..n-1, rtype and label)."""
        graph = nx.Graph(name=self.name, kind=self.kind)
        for index, (rtype, label) in enumerate(self.nodes):
            graph.add_node(index, rtype=rtype, label=label)
        graph.add_edges_from(self.edges)
        return graph

    def to_json(self) -> dict:
        return {
            "name": self.name, "kind": self.kind, "rooms": self.rooms,
            "corridors": [c.to_json() for c in self.corridors],
            "bridges": [b.to_json() for b in self.bridges],
            "corridor_cycles": list(self.corridor_cycles), "corridor_edges": self.corridor_edges,
            "corridor_openings": self.corridor_openings,
            "nodes": [list(n) for n in self.nodes], "edges": [list(e) for e in self.edges],
        }  # fmt: skip

    @classmethod
    def from_json(cls, data: dict) -> PlanModel:
        return cls(
            str(data["name"]), str(data["kind"]), int(data["rooms"]),
            tuple(CorridorProfile.from_json(c) for c in data["corridors"]),
            tuple(Cluster.from_json(b) for b in data["bridges"]),
            tuple(int(n) for n in data["corridor_cycles"]), int(data["corridor_edges"]), int(data["corridor_openings"]),
            tuple((str(t), str(l)) for t, l in data["nodes"]), tuple((int(a), int(b)) for a, b in data["edges"]),
        )  # fmt: skip


@dataclass(frozen=True, slots=True)
class Grammar:
    """The fitted grammar: one PlanModel per training plan."""

    plans: tuple[PlanModel, ...]
    source: str = ""
    """Where it was fitted from (a folder, or the names of the plans)."""
    _graphs: list = field(default_factory=list, compare=False, repr=False)

    @property
    def kinds(self) -> tuple[str, ...]:
        """The building kinds the grammar has plans of, sorted."""
        return tuple(sorted({plan.kind for plan in self.plans}))

    def plans_of(self, like: str) -> tuple[PlanModel, ...]:
        """The plans a sample `--like` this kind is built from (`any`: all of them)."""
        return self.plans if like == "any" else tuple(p for p in self.plans if p.kind == like)

    def training_graphs(self) -> list[nx.Graph]:
        """Every training plan's room graph (built once)."""
        if not self._graphs:
            self._graphs.extend(plan.graph() for plan in self.plans)
        return self._graphs

    def to_json(self) -> str:
        data = {"format": FORMAT_VERSION, "source": self.source, "plans": [p.to_json() for p in self.plans]}
        return json.dumps(data, separators=(",", ":"), sort_keys=False) + "\n"

    @property
    def digest(self) -> str:
        """A short hash of the fitted content: samples depend on it, so batch fingerprints do."""
        return hashlib.sha256(self.to_json().encode("utf-8")).hexdigest()[:16]

    @classmethod
    def from_json(cls, text: str) -> Grammar:
        data = json.loads(text)
        if not isinstance(data, dict) or data.get("format") != FORMAT_VERSION:
            raise ValueError(f"not a layoutdsl sampler model (format {FORMAT_VERSION})")
        return cls(tuple(PlanModel.from_json(p) for p in data["plans"]), str(data.get("source", "")))


class ModelError(ValueError):
    """A model file that cannot be read or is not a fitted grammar."""


def load_grammar(path: str | Path | None = None) -> Grammar:
    """A fitted grammar: the one in `path`, else the one that ships with layoutdsl."""
    try:
        if path is None:
            text = resources.files("layoutdsl.sample").joinpath("data", SHIPPED_MODEL).read_text(encoding="utf-8")
        else:
            text = Path(path).read_text(encoding="utf-8")
        return Grammar.from_json(text)
    except (OSError, UnicodeDecodeError) as error:
        raise ModelError(f"cannot read the sampler model `{path}`: {error}") from None
    except (ValueError, KeyError, TypeError, IndexError) as error:
        raise ModelError(f"`{path}` is not a layoutdsl sampler model: {error}") from None


def fit_grammar(plans: list[PlanGraph], source: str = "") -> Grammar:
    """Cut each plan into corridor profiles and bridges (see the module doc)."""
    return Grammar(tuple(fit_plan(plan) for plan in plans), source)


def fit_plan(plan: PlanGraph) -> PlanModel:
    graph = plan.graph
    order = sorted(graph.nodes, key=str)
    index = {node: i for i, node in enumerate(order)}
    corridors = [n for n in order if graph.nodes[n]["rtype"] == CORRIDOR_LIKE]
    is_corridor = set(corridors)
    backbone = graph.subgraph(corridors)
    rest = graph.subgraph([n for n in order if n not in is_corridor])
    pendants: dict[str, list[Cluster]] = {c: [] for c in corridors}
    bridges: list[Cluster] = []
    components = sorted((sorted(c, key=index.get) for c in nx.connected_components(rest)), key=lambda c: index[c[0]])
    for component in components:
        touched = sorted({m for n in component for m in graph[n] if m in is_corridor}, key=index.get)
        if not touched:
            continue  # a wing with no corridor: nothing to attach it to (its plan is disconnected)
        if len(touched) == 1:
            pendants[touched[0]].append(_cluster(graph, component, touched))
        else:
            bridges.append(_cluster(graph, component, touched, _spans(graph, component, touched)))
    profiles = tuple(
        CorridorProfile(graph.nodes[c]["label"], backbone.degree(c), tuple(pendants[c])) for c in corridors
    )
    corridor_cycles = tuple(sorted(len(cycle) for cycle in nx.minimum_cycle_basis(backbone)))
    openings = sum(1 for a, b in backbone.edges if graph.edges[a, b].get("kind") == "i")
    return PlanModel(
        plan.name, plan.kind, graph.number_of_nodes(), profiles, tuple(bridges), corridor_cycles,
        backbone.number_of_edges(), openings,
        tuple((graph.nodes[n]["rtype"], graph.nodes[n]["label"]) for n in order),
        tuple(sorted((min(index[a], index[b]), max(index[a], index[b])) for a, b in graph.edges)),
    )  # fmt: skip


def _spans(graph: nx.Graph, component: list, touched: list) -> tuple[int, ...]:
    """How far each touched corridor is from the first one without the bridge (0: unjoined)."""
    rest = graph.subgraph(set(graph) - set(component))
    distances = nx.single_source_shortest_path_length(rest, touched[0])
    return tuple(distances.get(corridor, 0) for corridor in touched[1:])


def _cluster(graph: nx.Graph, component: list, touched: list, spans: tuple[int, ...] = ()) -> Cluster:
    local = {node: i for i, node in enumerate(component)}
    port = {corridor: p for p, corridor in enumerate(touched)}
    nodes = tuple((graph.nodes[n]["rtype"], graph.nodes[n]["label"]) for n in component)
    edges = []
    attach = []
    for n in component:
        for m in sorted(graph[n], key=str):
            kind = graph.edges[n, m].get("kind", "e")
            if m in local and local[n] < local[m]:
                edges.append((local[n], local[m], kind))
            elif m in port:
                attach.append((local[n], port[m], kind))
    return Cluster(nodes, tuple(edges), tuple(sorted(attach)), spans)
