"""The strategy table: how `compile --strategy NAME` finds its layout.

Kept free of heavy imports: the CLI reads the names when it builds its parser.
"""

from __future__ import annotations

STRATEGIES = {
    "auto": "the generator's first layout (layoutdsl.compile.generator), polished and "
            "improved by SCIP",
    "thesis": "the thesis' formulation as written (§5.5.1) solved by SCIP from scratch: the "
              "reference",
}
"""Strategy name -> what it does; compile_spec dispatches on the name."""
