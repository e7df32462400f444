"""Room sizes learned from real plans, and specs for room graphs that have none.

    from layoutdsl.sizes import load_model, spec_from_graph
    model = load_model()                                  # the shipped, fitted model
    model.room_sizes("school", "R", "CLASSROOM")          # typical sizes (RoomSize)
    model.sample_room_sizes("school", "R", "CLASSROOM", random.Random(7))   # drawn sizes
    spec = spec_from_graph(graph, kind="school")          # a networkx graph -> a Spec

`model` holds the parametric form and `fit` how it is fitted (docs/sizes.md explains both);
`boundary.choose_boundary` is the boundary the tool chooses when a spec gives none;
`resolve` fills in the sizes of sizeless room lines (`R1 R CLASSROOM`).
"""

from __future__ import annotations

from layoutdsl.sizes.model import ModelError, RoomSize, SizeModel, load_model

__all__ = ["ModelError", "RoomSize", "SizeModel", "load_model", "spec_from_graph"]


def __getattr__(name: str):
    # spec_from_graph needs networkx, which `lint` (through sizes.resolve) never uses:
    # import it on first use, so linting a spec does not pay for it
    if name == "spec_from_graph":
        from layoutdsl.sizes.graph import spec_from_graph

        return spec_from_graph
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
