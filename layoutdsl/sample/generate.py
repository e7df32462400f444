"""Sample new room graphs from a fitted grammar (layoutdsl.sample.grammar explains the model).

One sample, given a seeded `random.Random`:

1. Template: a training plan of the kind, uniformly.
2. Corridors: their number is the template's times exp(N(0, CORRIDOR_SPREAD)), at least one.
   Each corridor takes a profile (label, backbone degree, pendant rooms): with probability
   OWN_SHARE the template's next one (its profiles in a shuffled order, each used once),
   else one of any plan of the kind.
3. Backbone: a uniformly random tree with the profiles' degrees (a shuffled Prüfer sequence;
   degrees are nudged so that they sum to 2(n - 1), the missing ones going to labels that
   join corridors in real plans). Corridor-to-corridor edges are
   openings at the template's rate.
4. Bridges (clusters on two corridors or more) at the template's rate per corridor, on
   corridors as far apart in the backbone as in their plan; cycles among corridors at the
   template's rate, each as long as one of its cycles. A bridge or an edge that would make
   the graph undrawable (`drawable`: non-planar, or no drawing with rectangles that keeps
   every entrance open to the outside) is not added.
5. A building without an entrance gets one, on a random corridor.

A sample must then have MIN_ROOMS..MAX_ROOMS rooms, be drawable, and be no training graph
(isomorphism on the bare topology, layoutdsl.sample.novelty); otherwise the same rng draws
another. Every sample is connected (a tree of corridors with clusters attached) and planar
(pendants are pieces of planar plans glued at one corridor; added edges are checked), and
passes layoutdsl.check.rectangles with every room a rectangle, as the 24 real plans of the
development corpus do: before that test, 3 of the first 40 samples of seed 0 (any-0010,
any-0012, any-0033) had entrances that no drawing could keep on the outside, and compile
could only fail on them.
"""

from __future__ import annotations

import hashlib
import math
import random

import networkx as nx

from layoutdsl.check.rectangles import drawable as drawable_with_rectangles
from layoutdsl.sample.grammar import Cluster, CorridorProfile, Grammar
from layoutdsl.sample.novelty import NoveltyCheck
from layoutdsl.sizes.graph import opens_outside

MIN_ROOMS = 10
MAX_ROOMS = 150
"""Samples have this many rooms (spaces of any type), bounds included."""

CORRIDOR_SPREAD = 0.25
"""Standard deviation of the log-ratio between a sample's corridor count and its template's."""

OWN_SHARE = 0.6
"""Chance that a corridor profile (or a bridge) comes from the template rather than from any
plan of the kind: high keeps a sample's style (a school of classroom rows stays one), low
mixes plans more."""

MAX_ATTEMPTS = 1000
"""Draws per sample before giving up (in practice a handful at most)."""

CONNECTOR_FLOOR = 0.02
"""Added to every label's share of corridor-joining spaces (connector_shares)."""

PLACEMENT_TRIES = 4
"""Places tried for a bridge or a corridor cycle before dropping it."""

ENTRANCE_LABEL = "ENTRANCE"


class SampleError(RuntimeError):
    """The grammar cannot produce a valid sample (e.g. it has no plan of the kind)."""


def sample_seed(seed: int, index: int, like: str) -> int:
    """The seed of the `index`-th sample of a run: it depends on nothing else, so sample 7 is
    the same whether 10 or 1,000 are drawn, and on any machine (sha256, not hash())."""
    digest = hashlib.sha256(f"layoutdsl-sample\0{like}\0{seed}\0{index}".encode()).digest()
    return int.from_bytes(digest[:8], "big")


class Sampler:
    """Draws room graphs `like` a kind from a grammar; holds the novelty check's cache."""

    def __init__(self, grammar: Grammar, like: str = "school", rooms: tuple[int, int] = (MIN_ROOMS, MAX_ROOMS)) -> None:
        self.grammar = grammar
        self.like = like
        if not MIN_ROOMS <= rooms[0] <= rooms[1] <= MAX_ROOMS:
            raise SampleError(f"rooms {rooms[0]}-{rooms[1]}: samples have {MIN_ROOMS}-{MAX_ROOMS} rooms")
        self.rooms = rooms
        """Samples outside this range of rooms are drawn again (a narrower range costs draws)."""
        self.templates = grammar.plans_of(like)
        if not self.templates:
            kinds = ", ".join(grammar.kinds) or "none"
            raise SampleError(f"the model has no plan of kind `{like}` (it has: {kinds}, or `any`)")
        self._pools: dict[str, tuple[list[CorridorProfile], list[Cluster], float]] = {}
        self._connectors: dict[str, dict[str, float]] = {}
        self.novelty = NoveltyCheck(grammar.training_graphs())

    def _pool(self, kind: str) -> tuple[list[CorridorProfile], list[Cluster], float]:
        """Every profile and bridge of the kind's plans, and their share of openings."""
        if kind not in self._pools:
            plans = [p for p in self.grammar.plans if p.kind == kind] or list(self.grammar.plans)
            profiles = [c for p in plans for c in p.corridors]
            bridges = [b for p in plans for b in p.bridges]
            edges = sum(p.corridor_edges for p in plans)
            openings = sum(p.corridor_openings for p in plans) / edges if edges else 0.0
            self._pools[kind] = (profiles, bridges, openings)
        return self._pools[kind]

    def _connects(self, kind: str) -> dict[str, float]:
        if kind not in self._connectors:
            self._connectors[kind] = connector_shares(self._pool(kind)[0])
        return self._connectors[kind]

    def sample(self, rng: random.Random) -> nx.Graph:
        """One new room graph (see the module doc); raises SampleError after MAX_ATTEMPTS."""
        for _ in range(MAX_ATTEMPTS):
            graph = self.draw(rng)
            if (self.rooms[0] <= graph.number_of_nodes() <= self.rooms[1] and drawable(graph)
                    and not self.novelty.is_copy(graph)):
                return graph
        raise SampleError(f"no new graph of {self.rooms[0]}-{self.rooms[1]} rooms in {MAX_ATTEMPTS} draws "
                          f"(the model's {self.like} plans may not come near that size)")

    def draw(self, rng: random.Random) -> nx.Graph:
        """One draw of the grammar, before the size and novelty checks."""
        template = self.templates[rng.randrange(len(self.templates))]
        profiles_pool, bridges_pool, openings = self._pool(template.kind)
        own = list(template.corridors)
        rng.shuffle(own)
        count = max(1, round(len(template.corridors) * math.exp(rng.gauss(0.0, CORRIDOR_SPREAD))))
        profiles = []
        for _ in range(count):
            if own and rng.random() < OWN_SHARE:
                profiles.append(own.pop())
            else:
                profiles.append(profiles_pool[rng.randrange(len(profiles_pool))])

        graph = nx.Graph(kind=template.kind, template=template.name)
        for index, profile in enumerate(profiles):
            graph.add_node(index, rtype="C", label=profile.label)
        if template.corridor_edges:
            openings = template.corridor_openings / template.corridor_edges
        connects = self._connects(template.kind)
        for a, b in _backbone(rng, [p.degree for p in profiles], [connects[p.label] for p in profiles]):
            graph.add_edge(a, b, kind="i" if rng.random() < openings else "e")
        backbone = graph.copy()
        for index, profile in enumerate(profiles):
            for cluster in profile.pendants:
                _add_cluster(graph, cluster, [index])

        scale = count / len(template.corridors)
        for _ in range(_stochastic_round(rng, len(template.bridges) * scale)):
            if template.bridges and rng.random() < OWN_SHARE:
                bridge = template.bridges[rng.randrange(len(template.bridges))]
            elif bridges_pool:
                bridge = bridges_pool[rng.randrange(len(bridges_pool))]
            else:
                break
            _place_bridge(rng, graph, backbone, bridge)
        cycles = template.corridor_cycles
        for _ in range(_stochastic_round(rng, len(cycles) * scale)):
            _close_corridor_cycle(rng, graph, backbone, cycles[rng.randrange(len(cycles))], openings)

        if not any(graph.nodes[n]["rtype"] == "E" for n in graph):
            node = graph.number_of_nodes()
            graph.add_node(node, rtype="E", label=_entrance_label(rng, profiles_pool))
            graph.add_edge(node, rng.randrange(count), kind="e")
        return graph


def _stochastic_round(rng: random.Random, value: float) -> int:
    """floor(value) plus one with probability frac(value): right on average."""
    whole = math.floor(value)
    return whole + (1 if rng.random() < value - whole else 0)


def _backbone(rng: random.Random, wanted: list[int], connects: list[float]) -> list[tuple[int, int]]:
    """A uniformly random tree on len(wanted) corridors whose degrees are `wanted`, nudged to
    a valid tree degree sequence (each at least 1, summing to 2(n - 1)).

    Real plans' corridors often form several groups joined through rooms, so their degrees
    sum to less than a tree needs. The missing degree goes to corridors in proportion to
    `connects`, how often their label joins two corridors or more in real plans: halls and
    corridors take it, washrooms (typed C in real plans, and leaves there) rarely do."""
    count = len(wanted)
    if count < 2:
        return []
    degrees = [max(1, d) for d in wanted]
    target = 2 * (count - 1)
    while sum(degrees) > target:
        over = [i for i, d in enumerate(degrees) if d > 1]
        degrees[over[rng.randrange(len(over))]] -= 1
    while sum(degrees) < target:
        degrees[_weighted_index(rng, connects)] += 1
    sequence = [i for i, d in enumerate(degrees) for _ in range(d - 1)]
    rng.shuffle(sequence)
    tree = nx.from_prufer_sequence(sequence) if count > 2 else nx.path_graph(2)
    return sorted((min(a, b), max(a, b)) for a, b in tree.edges)


def _weighted_index(rng: random.Random, weights: list[float]) -> int:
    """An index drawn with probability proportional to its weight (rng.random() only, so the
    draw is the same on every Python version)."""
    point = rng.random() * sum(weights)
    for index, weight in enumerate(weights):
        point -= weight
        if point < 0:
            return index
    return len(weights) - 1


def connector_shares(profiles: list[CorridorProfile]) -> dict[str, float]:
    """Label -> share of its corridor-like spaces with two corridor-like neighbours or more,
    plus CONNECTOR_FLOOR so that no label is ruled out."""
    seen: dict[str, list[int]] = {}
    for profile in profiles:
        counts = seen.setdefault(profile.label, [0, 0])
        counts[0] += 1
        counts[1] += profile.degree >= 2
    return {label: joined / total + CONNECTOR_FLOOR for label, (total, joined) in seen.items()}


def _add_cluster(graph: nx.Graph, cluster: Cluster, corridors: list[int]) -> list[int]:
    """Copy a cluster into the graph, port p joined to corridors[p]; returns its new nodes."""
    first = graph.number_of_nodes()
    nodes = [first + i for i in range(len(cluster.nodes))]
    for node, (rtype, label) in zip(nodes, cluster.nodes):
        graph.add_node(node, rtype=rtype, label=label)
    for a, b, kind in cluster.edges:
        graph.add_edge(nodes[a], nodes[b], kind=kind)
    for i, port, kind in cluster.attach:
        graph.add_edge(nodes[i], corridors[port], kind=kind)
    return nodes


def _place_bridge(rng: random.Random, graph: nx.Graph, backbone: nx.Graph, bridge: Cluster) -> bool:
    """Attach a bridge to corridors as far apart in the backbone as its ports were in its
    plan (the farthest ones for ports only the bridge joined), if the graph stays planar."""
    ports = bridge.ports
    if backbone.number_of_nodes() < ports:
        return False
    spans = list(bridge.spans) + [1] * (ports - 1 - len(bridge.spans))
    for _ in range(PLACEMENT_TRIES):
        first = rng.randrange(backbone.number_of_nodes())
        distance = nx.single_source_shortest_path_length(backbone, first)
        chosen = [first]
        for span in spans:
            free = [c for c in sorted(distance) if c not in chosen]
            if not free:
                break
            want = span if span > 0 else max(distance[c] for c in free)
            best = min(abs(distance[c] - want) for c in free)
            closest = [c for c in free if abs(distance[c] - want) == best]
            chosen.append(closest[rng.randrange(len(closest))])
        if len(chosen) < ports:
            return False
        nodes = _add_cluster(graph, bridge, chosen)
        if drawable(graph):
            return True
        graph.remove_nodes_from(nodes)
    return False


def _close_corridor_cycle(rng: random.Random, graph: nx.Graph, backbone: nx.Graph, length: int,
                          openings: float) -> bool:
    """Join two corridors not yet joined whose backbone path has `length` corridors (the
    nearest length the backbone has), so the new cycle is as long as one of the plan's, if
    the graph stays planar."""
    corridors = sorted(backbone)
    if len(corridors) < 3:
        return False
    for _ in range(PLACEMENT_TRIES):
        first = corridors[rng.randrange(len(corridors))]
        distance = nx.single_source_shortest_path_length(backbone, first)
        free = [c for c in sorted(distance) if distance[c] >= 2 and not graph.has_edge(first, c)]
        if not free:
            continue
        best = min(abs(distance[c] - (length - 1)) for c in free)
        closest = [c for c in free if abs(distance[c] - (length - 1)) == best]
        other = closest[rng.randrange(len(closest))]
        graph.add_edge(first, other, kind="i" if rng.random() < openings else "e")
        if drawable(graph):
            return True
        graph.remove_edge(first, other)
    return False


def drawable(graph: nx.Graph) -> bool:
    """Planar, and drawable with every room a rectangle and every entrance open to the
    outside as far as layoutdsl.check.rectangles can tell (it never refuses a drawable graph).
    One planarity test: the rectangle test's graph holds a subdivision of this one, so a
    non-planar graph fails it too."""
    outside = [node for node in graph if opens_outside(graph, node)]
    return drawable_with_rectangles(graph, graph.nodes, outside)


def _entrance_label(rng: random.Random, profiles: list[CorridorProfile]) -> str:
    """The label of an entrance alone on a corridor, drawn from the plans' entrances."""
    labels = sorted(
        cluster.nodes[0][1] for profile in profiles for cluster in profile.pendants
        if len(cluster.nodes) == 1 and cluster.nodes[0][0] == "E"
    )
    return labels[rng.randrange(len(labels))] if labels else ENTRANCE_LABEL


def sample_graphs(grammar: Grammar, like: str, count: int, seed: int, start: int = 0) -> list[nx.Graph]:
    """Samples start..start+count-1 of the run with this seed (each from its own seed)."""
    sampler = Sampler(grammar, like)
    return [sampler.sample(random.Random(sample_seed(seed, index, like))) for index in range(start, start + count)]


__all__ = ["MAX_ROOMS", "MIN_ROOMS", "SampleError", "Sampler", "sample_graphs", "sample_seed"]
