"""Is a sampled room graph new? Isomorphism against the training graphs, and WL similarity.

Novelty is judged on the bare topology (rooms and doors, labels and types ignored): a sample
that rewires a real plan's rooms but keeps its graph counts as a copy. That is stricter than
comparing labelled graphs.
"""

from __future__ import annotations

import math
import warnings
from collections import Counter
from dataclasses import dataclass

import networkx as nx

WL_ITERATIONS = 3
"""Weisfeiler-Lehman refinement rounds: subtrees up to three doors deep, enough to tell a room
hanging off a corridor from one inside a suite (Shervashidze et al. 2011 use 2-5)."""


@dataclass(frozen=True, slots=True)
class _Invariants:
    nodes: int
    edges: int
    degrees: tuple[int, ...]
    wl: str


def _invariants(graph: nx.Graph) -> _Invariants:
    with warnings.catch_warnings():
        # networkx 3.5 changed the hashes of unlabelled graphs and says so on every call; the
        # hashes here are only compared with others computed by the same process
        warnings.simplefilter("ignore", UserWarning)
        wl = nx.weisfeiler_lehman_graph_hash(graph, iterations=WL_ITERATIONS)
    return _Invariants(graph.number_of_nodes(), graph.number_of_edges(), tuple(sorted(d for _, d in graph.degree)), wl)


class NoveltyCheck:
    """Answers `is_copy(graph)` against a fixed set of graphs, cheaply: node and edge counts,
    then the degree sequence, then the WL hash, then an exact isomorphism test (VF2++) for
    the few graphs that pass every invariant."""

    def __init__(self, graphs: list[nx.Graph]) -> None:
        self._known = [(graph, _invariants(graph)) for graph in graphs]

    def copy_of(self, graph: nx.Graph) -> int | None:
        """The index of a graph isomorphic to `graph`, or None when it is new."""
        mine: _Invariants | None = None
        for index, (known, invariants) in enumerate(self._known):
            if (invariants.nodes, invariants.edges) != (graph.number_of_nodes(), graph.number_of_edges()):
                continue
            mine = mine or _invariants(graph)
            if invariants.degrees != mine.degrees or invariants.wl != mine.wl:
                continue
            if nx.vf2pp_is_isomorphic(known, graph):
                return index
        return None

    def is_copy(self, graph: nx.Graph) -> bool:
        return self.copy_of(graph) is not None


def wl_features(graph: nx.Graph, node_attr: str | None = "rtype", iterations: int = WL_ITERATIONS) -> Counter:
    """The graph's Weisfeiler-Lehman subtree features: how many nodes have each rooted
    subtree pattern, at every depth 0..iterations (depth 0 = the node's type)."""
    features: Counter = Counter()
    for node in graph.nodes:
        label = str(graph.nodes[node].get(node_attr, "")) if node_attr else ""
        features[("0", label)] += 1
    hashes = nx.weisfeiler_lehman_subgraph_hashes(graph, node_attr=node_attr, iterations=iterations)
    for node_hashes in hashes.values():
        for depth, value in enumerate(node_hashes, start=1):
            features[(str(depth), value)] += 1
    return features


def wl_similarity(a: Counter, b: Counter) -> float:
    """The normalized WL subtree kernel k(a, b) / sqrt(k(a, a) k(b, b)), in [0, 1]: 1 for
    graphs WL cannot tell apart, near 0 for graphs that share few rooted patterns."""
    dot = sum(count * b.get(key, 0) for key, count in a.items())
    norm = math.sqrt(sum(c * c for c in a.values()) * sum(c * c for c in b.values()))
    return dot / norm if norm else 0.0
