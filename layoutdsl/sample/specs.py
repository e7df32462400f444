"""Sampled room graphs -> specs ready to compile: sizes and boundary from the size model.

Sample `index` of a run is a function of (grammar, size model, like, seed, index) alone: its
graph and its room sizes are drawn from one `random.Random` seeded by `sample_seed`, so the
same command gives the same bytes on any machine, and `-n 10` gives the first ten of
`-n 1000`.
"""

from __future__ import annotations

import random
from dataclasses import dataclass, replace

import networkx as nx

from layoutdsl.sample.generate import Sampler, sample_seed
from layoutdsl.sample.grammar import Grammar
from layoutdsl.sample.stats import summary
from layoutdsl.sizes import SizeModel, load_model, spec_from_graph
from layoutdsl.syntax.ast import Spec
from layoutdsl.syntax.format import format_spec


@dataclass(frozen=True, slots=True)
class Sample:
    """One sampled building: its name, graph, spec and the spec's text."""

    name: str
    index: int
    graph: nx.Graph
    spec: Spec
    text: str

    def record(self) -> dict:
        """What a manifest says about it."""
        return {"name": self.name, "index": self.index, "kind": self.graph.graph["kind"],
                "template": self.graph.graph["template"], **summary(self.graph)}


def sample_name(like: str, index: int) -> str:
    """`school-0007` for the 7th sample like a school (numbered from 1)."""
    return f"{like}-{index:04d}"


class SpecSampler:
    """Draws sampled specs; holds the grammar, the size model and the novelty cache."""

    def __init__(self, grammar: Grammar, like: str = "school", sizes: SizeModel | None = None, seed: int = 0,
                 *, drawn_sizes: bool = True, rooms: tuple[int, int] | None = None) -> None:
        self.sampler = Sampler(grammar, like) if rooms is None else Sampler(grammar, like, rooms)
        self.rooms = rooms
        self.drawn_sizes = drawn_sizes
        """Room sizes drawn from the size model's laws (default), else each label's typical
        sizes: fewer outliers such as a corridor three times its typical length."""
        self.sizes = sizes if sizes is not None else load_model()
        self.like = like
        self.seed = seed
        self.grammar = grammar
        for kind in {plan.kind for plan in self.sampler.templates}:
            self.sizes.kind(kind)  # a kind the size model lacks fails now, not at sample 500

    def header(self, index: int, graph: nx.Graph) -> str:
        """Comment lines saying where a spec came from (a spec's `#` starts a comment)."""
        return (
            f"# sampled by `layoutdsl sample --like {self.like} --seed {self.seed}"
            f"{'' if self.drawn_sizes else ' --typical-sizes'}"
            f"{'' if self.rooms is None else f' --rooms {self.rooms[0]}-{self.rooms[1]}'}`, sample {index}\n"
            f"# template plan {graph.graph['template']}; sampler model {self.grammar.digest}; "
            f"{graph.number_of_nodes()} rooms, {graph.number_of_edges()} adjacencies\n"
        )

    def sample(self, index: int) -> Sample:
        """Sample `index` (from 1) of this run."""
        rng = random.Random(sample_seed(self.seed, index, self.like))
        graph = self.sampler.sample(rng)
        name = sample_name(self.like, index)
        spec = spec_from_graph(graph, kind=graph.graph["kind"], model=self.sizes,
                               rng=rng if self.drawn_sizes else None, name=name)
        # No boundary section, as `layoutdsl import` writes a room graph: compile chooses the
        # same boundary from the same rooms (sizes.resolve) and may fit it to the building it
        # draws; written in, it would be a limit as if the user had set it.
        boundary = spec.boundary
        text = (self.header(index, graph)
                + f"# No boundary section: the tool chooses {boundary.w:g} x {boundary.h:g} m for these rooms "
                f"and compile may grow it.\n" + format_spec(replace(spec, boundary=None)))
        return Sample(name, index, graph, spec, text)
