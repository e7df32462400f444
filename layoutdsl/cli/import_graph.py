"""`layoutdsl import graph.csv|.json|.graphml -o spec.lay`: a room graph without geometry -> a spec.

`import` dispatches here when its input is a room graph (named with `--from`, or detected
from the file's extension or text). The graph is read and validated by
`importer.graphs.read_graph`; each room gets sizes from the room-size model of the building
kind `--like` (typical sizes, or drawn ones with `--seed`), the boundary is chosen by
`sizes.boundary.choose_boundary`, and entrances must open to the outside (`onB`). The spec
is linted before it is written, and written atomically.
"""

from __future__ import annotations

import argparse
import random
import sys
from pathlib import Path

from layoutdsl.diagnostics import exitcodes, has_errors
from layoutdsl.diagnostics.source import Source
from layoutdsl.importer.graphs import FORMATS, GRAPH_UNREADABLE, detect_format, read_graph

GRAPH_FORMATS = FORMATS
"""The `--from` values that name a room graph (`xml` names a building plan)."""


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """The options only graph inputs use (registered by `import`)."""
    parser.add_argument(
        "--from", dest="input_format", choices=("xml", *GRAPH_FORMATS), default=None, metavar="FORMAT",
        help="what the input is: xml (a building plan), or a room graph: csv (adjacency matrix), "
        "json (networkx node-link), graphml. Default: from the file's extension, else its text",
    )  # fmt: skip
    parser.add_argument(
        "--like", default="school", metavar="KIND",
        help="room graphs: the building kind whose room sizes to use (default school; the shipped "
        "model knows school and office)",
    )  # fmt: skip
    parser.add_argument(
        "--seed", type=int, default=None, metavar="N",
        help="room graphs: draw each room's sizes from the model with this seed (default: typical sizes)",
    )  # fmt: skip
    parser.add_argument(
        "--size-model", default=None, metavar="FILE",
        help="room graphs: a size model from `layoutdsl sizes fit` (default: the shipped one)",
    )  # fmt: skip
    parser.add_argument(
        "--fixed-boundary", action="store_true",
        help="room graphs: write the chosen boundary as a `boundary` section, which compile must "
        "keep (default: leave it out, so compile chooses the same one and may grow it)",
    )  # fmt: skip


def graph_format(args: argparse.Namespace, text: str | None) -> str | None:
    """The graph format of the input, or None when it is a building plan (or unknown)."""
    chosen = getattr(args, "input_format", None)
    if chosen is not None:
        return None if chosen == "xml" else chosen
    if args.input == "-":
        name = args.stdin_filename or ""
        found = detect_format(name, text) if name else detect_format("-", text)
        if found == "graphml" and Path(name).suffix.lower() == ".xml" and "<graphml" not in (text or "")[:4096]:
            found = None  # as for a file: an .xml name is a building plan unless its text says GraphML
    else:
        found = detect_format(args.input)
        if found == "graphml" and Path(args.input).suffix.lower() == ".xml":
            found = None  # an .xml file is a building plan unless its text says GraphML
            try:
                head = Path(args.input).read_text(encoding="utf-8", errors="replace")[:4096]
            except OSError:
                head = ""
            if "<graphml" in head:
                found = "graphml"
    return found


def run(args: argparse.Namespace, fmt: str, text: str | None, print_diagnostics) -> int:
    """Import one room graph; exit codes as `import` (0, 1 errors, 2 usage or I/O)."""
    from layoutdsl.api import lint_source
    from layoutdsl.emit.atomic import write_text_atomic
    from layoutdsl.sizes import ModelError, load_model, spec_from_graph
    from layoutdsl.syntax.format import format_spec

    style = getattr(args, "format", "full")
    try:
        model = load_model(args.size_model)
        model.kind(args.like)
    except (OSError, ModelError) as error:
        reason = error.strerror if isinstance(error, OSError) and error.strerror else str(error)
        where = f"`{args.size_model}`: " if args.size_model and isinstance(error, OSError) else ""
        print(f"layoutdsl import: error: {where}{reason}", file=sys.stderr)
        return exitcodes.USAGE
    source_name = (args.stdin_filename or "<stdin>") if args.input == "-" else args.input
    graph, diagnostics = read_graph(source_name, fmt, text=text)
    if text is None:
        try:
            text = Path(source_name).read_text(encoding="utf-8", errors="replace")
        except OSError:
            text = None
    sources = {source_name: Source(source_name, text)} if text is not None else {}
    print_diagnostics(diagnostics, sources, style)
    if graph is None or has_errors(diagnostics):
        unreadable = any(d.code == GRAPH_UNREADABLE and d.message.startswith("cannot read") for d in diagnostics)
        return exitcodes.USAGE if unreadable else exitcodes.SPEC_ERRORS
    to_stdout = args.output == "-"
    name = Path(args.output).stem if not to_stdout else Path(source_name if args.input != "-" else "stdin").stem
    rng = random.Random(args.seed) if args.seed is not None else None
    spec = spec_from_graph(graph, kind=args.like, model=model, rng=rng, name=name)
    from dataclasses import replace

    spec = replace(spec, path=f"{name}.lay" if to_stdout else args.output)
    chosen = spec.boundary
    if args.fixed_boundary:
        output = format_spec(spec)
    else:
        # No boundary section: lint and compile choose the same boundary from the same rooms
        # (sizes.resolve), and compile may grow it, as it does for a graph given in memory.
        output = _header(args, fmt, source_name, chosen) + format_spec(replace(spec, boundary=None))
    lint_errors = [d for d in lint_source(Source(spec.path, output))[1] if d.is_error]
    if lint_errors:
        print_diagnostics(lint_errors, {spec.path: Source(spec.path, output)}, style)
        print("layoutdsl import: error: the imported spec does not lint clean (an importer bug); nothing written",
              file=sys.stderr)  # fmt: skip
        return exitcodes.SPEC_ERRORS
    if to_stdout:
        sys.stdout.write(output)
        sys.stdout.flush()
    else:
        try:
            write_text_atomic(args.output, output)
        except OSError as error:
            print(f"layoutdsl import: error: cannot write `{args.output}`: {error.strerror or error}", file=sys.stderr)
            return exitcodes.USAGE
    if not getattr(args, "quiet", False) and style != "json":
        where = "standard output" if to_stdout else f"`{args.output}`"
        sizes = f"drawn with seed {args.seed}" if args.seed is not None else "typical"
        print(
            f"imported {len(spec.rooms)} rooms and {len(spec.adjacencies)} adjacencies into {where} "
            f"({sizes} {args.like} sizes, boundary {chosen.w:g} x {chosen.h:g} m chosen"
            f"{'' if args.fixed_boundary else ' at compile time'})",
            file=sys.stderr,
        )
    return exitcodes.OK


def _header(args: argparse.Namespace, fmt: str, source_name: str, boundary) -> str:
    """The comment that opens an imported graph's spec: where it came from, and its boundary."""
    sizes = f"drawn with seed {args.seed}" if args.seed is not None else "typical"
    return (
        f"# room graph {Path(source_name).name} ({fmt}), rooms with {sizes} {args.like} sizes from the size model.\n"
        f"# No boundary section: the tool chooses {boundary.w:g} x {boundary.h:g} m for these rooms and compile\n"
        "# may grow it; `layoutdsl fmt --fill-sizes` writes it in (docs/graph-formats.md).\n\n"
    )
