"""MMD of graph statistics (GraphRNN's form) and the WL similarity, against hand-computed values."""

from __future__ import annotations

import math

import networkx as nx
import numpy as np
import pytest

from layoutdsl.sample import stats
from layoutdsl.sample.novelty import NoveltyCheck, wl_features, wl_similarity


def typed(graph: nx.Graph, types: str) -> nx.Graph:
    for node, rtype in zip(sorted(graph), types):
        graph.nodes[node]["rtype"] = rtype
        graph.nodes[node]["label"] = {"R": "OFFICE", "C": "CORRIDOR", "E": "ENTRANCE"}[rtype]
    return graph


def test_mmd_of_a_set_with_itself_is_zero_and_it_is_symmetric():
    a = [np.array([1.0, 2.0, 0.0]), np.array([0.0, 1.0, 1.0])]
    b = [np.array([3.0, 0.0]), np.array([1.0, 1.0, 1.0, 1.0])]
    assert stats.mmd2(a, a) == pytest.approx(0.0, abs=1e-12)
    assert stats.mmd2(a, b) == pytest.approx(stats.mmd2(b, a))
    assert stats.mmd2(a, b) > 0


def test_mmd_of_two_disjoint_point_masses():
    # TV = 1 between the two one-hot histograms: MMD² = 1 + 1 - 2 exp(-1 / 2σ²)
    a, b = [np.array([1.0, 0.0])], [np.array([0.0, 1.0])]
    assert stats.mmd2(a, b, sigma=1.0) == pytest.approx(2 - 2 * math.exp(-0.5))
    assert stats.mmd2(a, b, sigma=0.1) == pytest.approx(2 - 2 * math.exp(-50))


def test_mmd_by_hand_on_half_overlapping_histograms():
    # x = (1, 0), y = (0.5, 0.5): TV = 0.5, k = exp(-0.125); sets {x} and {x, y}
    x, y = np.array([1.0, 0.0]), np.array([1.0, 1.0])  # y is normalized to (0.5, 0.5)
    k = math.exp(-0.125)
    expected = 1 + (1 + 1 + 2 * k) / 4 - 2 * (1 + k) / 2
    assert stats.mmd2([x], [x, y]) == pytest.approx(expected)


def test_statistics_of_a_small_building():
    # corridor 0 - corridor 1, rooms 2, 3 on corridor 0 with a door between them (a triangle),
    # entrance 4 on corridor 1
    graph = typed(nx.Graph([(0, 1), (0, 2), (0, 3), (2, 3), (1, 4)]), "CCRRE")
    assert list(stats.rooms(graph)).index(1.0) == 0  # 5 rooms: bin 0-9
    assert list(stats.corridor_share(graph)).index(1.0) == 8  # 2/5 = 0.40
    assert list(stats.entrances(graph)).index(1.0) == 1
    assert list(stats.degrees(graph)) == [0, 1, 3, 1]  # one leaf, three of degree 2, corridor 0
    assert stats.cycle_rank(graph) == 1 and list(stats.cycles(graph)).index(1.0) == 1
    clustering = stats.clustering(graph)
    assert clustering.sum() == 5 and clustering[0] == 2 and clustering[99] == 2 and clustering[33] == 1
    (labels,) = stats.label_histograms([graph])
    assert list(labels[0]) == [2.0, 1.0, 2.0]  # C:CORRIDOR, E:ENTRANCE, R:OFFICE


def test_room_areas_fall_in_octaves():
    graph = typed(nx.Graph([(0, 1), (1, 2)]), "CRR")
    for node, area in zip(graph, (1.5, 3.0, 700.0)):
        graph.nodes[node]["area"] = area
    histogram = stats.room_areas(graph)
    assert histogram[0] == 1 and histogram[1] == 1 and histogram[9] == 1 and histogram.sum() == 3


def test_novelty_check_finds_a_relabelled_copy_and_passes_a_new_graph():
    known = typed(nx.Graph([(0, 1), (0, 2), (0, 3), (1, 4), (1, 5)]), "CCRRER")
    check = NoveltyCheck([known])
    copy = nx.relabel_nodes(known, {0: "a", 1: "b", 2: "c", 3: "d", 4: "e", 5: "f"})
    assert check.copy_of(copy) == 0
    other = typed(nx.path_graph(6), "CCRRER")  # same counts, another shape
    assert not check.is_copy(other)


def test_wl_similarity_is_one_for_isomorphic_graphs_and_lower_otherwise():
    star = typed(nx.star_graph(4), "CRRRR")
    same = nx.relabel_nodes(star, {i: 10 + i for i in range(5)})
    path = typed(nx.path_graph(5), "CRRRR")
    assert wl_similarity(wl_features(star), wl_features(same)) == pytest.approx(1.0)
    assert 0 < wl_similarity(wl_features(star), wl_features(path)) < 1
