"""New room graphs learned from real plans, as specs ready to compile (issue 41).

    from layoutdsl.sample import SpecSampler, load_grammar
    sampler = SpecSampler(load_grammar(), like="school", seed=0)   # the shipped model
    sample = sampler.sample(1)             # sample.graph (networkx), sample.spec, sample.text

`corpus` reads real plans' room graphs, `grammar` fits the model (and ships it as data),
`generate` draws graphs, `novelty` checks them against the training plans, `specs` gives
them sizes and a boundary (layoutdsl.sizes), `stats` measures graphs as GraphRNN does.
docs/sampling.md explains the method and the measurements.
"""

from __future__ import annotations

from layoutdsl.sample.corpus import CorpusError, default_corpus, read_corpus
from layoutdsl.sample.generate import MAX_ROOMS, MIN_ROOMS, SampleError, Sampler, sample_graphs, sample_seed
from layoutdsl.sample.grammar import Grammar, ModelError, fit_grammar, load_grammar
from layoutdsl.sample.specs import Sample, SpecSampler, sample_name

__all__ = [
    "MAX_ROOMS", "MIN_ROOMS", "CorpusError", "Grammar", "ModelError", "Sample", "SampleError",
    "Sampler", "SpecSampler", "default_corpus", "fit_grammar", "load_grammar", "read_corpus",
    "sample_graphs", "sample_name", "sample_seed",
]
