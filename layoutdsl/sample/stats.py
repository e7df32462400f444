"""Graph statistics and their MMD, as graph generative models are evaluated (GraphRNN).

Each statistic turns one room graph into a histogram; two sets of graphs are compared by the
maximum mean discrepancy of their histograms under a Gaussian kernel on the total-variation
distance, k(x, y) = exp(-TV(x, y)² / 2σ²) with TV(x, y) = ½ Σ|x - y| between normalized
histograms (You et al. 2018, GraphRNN; the form of GRAN's evaluation code, Liao et al. 2019).
The figure is the biased estimate of MMD², the number GraphRNN's tables print:

    MMD²(X, Y) = mean k(X, X) + mean k(Y, Y) - 2 mean k(X, Y)   (all pairs, diagonal included)

Statistics whose value per graph is one number (rooms, corridor share, entrances, cycle rank)
are one-hot histograms over fixed bins; MMD² is then proportional to the squared L2 distance
between the two sets' binned distributions. Bins and σ are module constants, so figures stay
comparable between runs.

Graphs carry `rtype` and `label` per node, and `area` (m²) where it is known.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import networkx as nx
import numpy as np

ROOM_BINS = tuple(range(0, 160, 10))
"""Rooms: 0-9, 10-19, ..., 150+."""
SHARE_BINS = tuple(i / 20 for i in range(20))
"""Share of corridor-like spaces: 0-0.05, ..., 0.95-1."""
ENTRANCE_BINS = tuple(range(0, 16))
"""Entrances: 0, 1, ..., 15+."""
CYCLE_BINS = (0, 1, 3, 6, 11, 21)
"""Cycle rank: 0, 1-2, 3-5, 6-10, 11-20, 21+ (real plans have 0 to 26)."""
AREA_BINS = tuple(2.0**k for k in range(0, 11))
"""Room area (m²): under 2, 2-4, 4-8, ..., 512-1024, 1024+ (an octave per bin)."""
CLUSTERING_BINS = 100
"""Local clustering coefficient: 100 bins over [0, 1], as GraphRNN's evaluation."""

SIGMA = 1.0
CLUSTERING_SIGMA = 0.1
"""Kernel widths: GraphRNN's (degree and the rest 1.0; clustering 0.1)."""


def _bin(value: float, edges: Sequence[float]) -> int:
    """The bin of `value`: the last edge at or below it (values below edges[0] in bin 0)."""
    index = 0
    for i, edge in enumerate(edges):
        if value >= edge:
            index = i
    return index


def _one_hot(value: float, edges: Sequence[float]) -> np.ndarray:
    histogram = np.zeros(len(edges))
    histogram[_bin(value, edges)] = 1.0
    return histogram


def _counts(values, edges: Sequence[float]) -> np.ndarray:
    histogram = np.zeros(len(edges))
    for value in values:
        histogram[_bin(value, edges)] += 1.0
    return histogram


def cycle_rank(graph: nx.Graph) -> int:
    """Independent cycles: edges - nodes + connected components."""
    return graph.number_of_edges() - graph.number_of_nodes() + nx.number_connected_components(graph)


def rooms(graph: nx.Graph) -> np.ndarray:
    return _one_hot(graph.number_of_nodes(), ROOM_BINS)


def corridor_share(graph: nx.Graph) -> np.ndarray:
    share = sum(1 for n in graph if graph.nodes[n].get("rtype") == "C") / max(1, graph.number_of_nodes())
    return _one_hot(share, SHARE_BINS)


def entrances(graph: nx.Graph) -> np.ndarray:
    return _one_hot(sum(1 for n in graph if graph.nodes[n].get("rtype") == "E"), ENTRANCE_BINS)


def degrees(graph: nx.Graph) -> np.ndarray:
    return np.array(nx.degree_histogram(graph), dtype=float)


def clustering(graph: nx.Graph) -> np.ndarray:
    values = list(nx.clustering(graph).values())
    histogram, _ = np.histogram(values, bins=CLUSTERING_BINS, range=(0.0, 1.0))
    return histogram.astype(float)


def cycles(graph: nx.Graph) -> np.ndarray:
    return _one_hot(cycle_rank(graph), CYCLE_BINS)


def room_areas(graph: nx.Graph) -> np.ndarray:
    return _counts((graph.nodes[n]["area"] for n in graph if "area" in graph.nodes[n]), AREA_BINS)


def node_label(graph: nx.Graph, node) -> str:
    return f"{graph.nodes[node].get('rtype', '?')}:{graph.nodes[node].get('label', '')}"


@dataclass(frozen=True, slots=True)
class Statistic:
    name: str
    histogram: Callable[[nx.Graph], np.ndarray] | None
    """One graph's histogram; None for labels, whose bins depend on the sets compared."""
    sigma: float = SIGMA


STATISTICS = (
    Statistic("rooms", rooms),
    Statistic("corridor share", corridor_share),
    Statistic("entrances", entrances),
    Statistic("degree", degrees),
    Statistic("clustering", clustering, CLUSTERING_SIGMA),
    Statistic("cycle rank", cycles),
    Statistic("labels", None),  # over the vocabulary of the sets compared: label_histograms
    Statistic("room area", room_areas),
)
"""The statistics bench/sample.py compares, in its table's order."""


def label_histograms(*sets: Sequence[nx.Graph]) -> list[list[np.ndarray]]:
    """Label histograms of several sets of graphs over their common vocabulary (rtype:label)."""
    vocabulary = sorted({node_label(g, n) for graphs in sets for g in graphs for n in g})
    position = {label: i for i, label in enumerate(vocabulary)}
    result = []
    for graphs in sets:
        histograms = []
        for graph in graphs:
            histogram = np.zeros(len(vocabulary))
            for node in graph:
                histogram[position[node_label(graph, node)]] += 1.0
            histograms.append(histogram)
        result.append(histograms)
    return result


def histograms(statistic: Statistic, *sets: Sequence[nx.Graph]) -> list[list[np.ndarray]]:
    """Each set's histograms for a statistic (labels share one vocabulary across the sets)."""
    if statistic.histogram is None:
        return label_histograms(*sets)
    return [[statistic.histogram(graph) for graph in graphs] for graphs in sets]


def _normalized(histograms: Sequence[np.ndarray], width: int) -> np.ndarray:
    matrix = np.zeros((len(histograms), width))
    for row, histogram in enumerate(histograms):
        total = histogram.sum()
        if total > 0:
            matrix[row, : len(histogram)] = histogram / total
    return matrix


def _mean_kernel(a: np.ndarray, b: np.ndarray, sigma: float) -> float:
    """Mean of exp(-TV² / 2σ²) over all pairs of rows of a and b."""
    total = 0.0
    for row in a:  # one row against all of b at once: 1,000 x 12 pairs in a few milliseconds
        tv = 0.5 * np.abs(b - row).sum(axis=1)
        total += float(np.exp(-(tv * tv) / (2.0 * sigma * sigma)).sum())
    return total / (len(a) * len(b))


def mmd2(first: Sequence[np.ndarray], second: Sequence[np.ndarray], sigma: float = SIGMA) -> float:
    """The biased MMD² estimate between two sets of histograms (padded to one length and
    normalized to sum 1; an empty histogram stays all zeros)."""
    if not first or not second:
        raise ValueError("MMD needs two non-empty sets")
    width = max(len(h) for h in (*first, *second))
    a, b = _normalized(first, width), _normalized(second, width)
    value = _mean_kernel(a, a, sigma) + _mean_kernel(b, b, sigma) - 2.0 * _mean_kernel(a, b, sigma)
    return max(0.0, value)  # rounding may leave -1e-17


def statistic_mmd2(statistic: Statistic, first: Sequence[nx.Graph], second: Sequence[nx.Graph]) -> float:
    a, b = histograms(statistic, first, second)
    return mmd2(a, b, statistic.sigma)


def summary(graph: nx.Graph) -> dict:
    """A graph's headline numbers (for manifests and tables)."""
    types = [graph.nodes[n].get("rtype") for n in graph]
    return {
        "rooms": graph.number_of_nodes(),
        "corridors": types.count("C"),
        "entrances": types.count("E"),
        "doors": graph.number_of_edges(),
        "cycle_rank": cycle_rank(graph),
    }
