"""`layoutdsl import plan.xml -o plan.lay`: a real floor plan (building XML) -> a spec.

The spec is written in the thesis' intermediate-model format (the thesis, §5.4): the room
graph, size bounds and boundary, from which `compile` generates a new arrangement. With
`--keep-arrangement` it also gets a `hints` section (each room's place in the original
plan), which compile then starts from, so the layout keeps the original arrangement.
Diagnostics go to stderr; the output file is written atomically and only when the import
succeeded. Output follows layoutdsl.cli.output (-q/-v, --format, one I/O error style).
"""

from __future__ import annotations

import argparse
import sys
from dataclasses import replace
from pathlib import Path

from layoutdsl.cli import import_graph
from layoutdsl.cli.output import Output, add_command, add_output_arguments, ensure_parent
from layoutdsl.diagnostics import exitcodes, has_errors
from layoutdsl.diagnostics.filekind import wrong_kind_for_import
from layoutdsl.diagnostics.source import Source
from layoutdsl.importer import ImportOptions, import_building

_DEFAULTS = ImportOptions()


def add_parser(subparsers) -> None:
    """Register the `import` subcommand."""
    parser = add_command(
        subparsers, "import",
        help="convert a building XML floor plan or a room graph into a spec (the thesis, §5.3)",
        description=(
            "Convert a real floor plan in the building XML format into a layout spec: one "
            "rectangular room per space (sizes from its polygon, the thesis, §5.3), one "
            "adjacency per pair of spaces joined by a portal, the plan's bounding box as "
            "boundary. compile then generates a NEW arrangement of that room graph; "
            "--keep-arrangement also writes each room's original place as a hint, and compile "
            "then starts from (and mostly keeps) the original arrangement.\n\n"
            "A room graph (.csv adjacency matrix, .json node-link, .graphml) becomes a spec "
            "with room sizes from the size model of --like. The folder of -o is created if needed."
        ),
        examples=[
            ("a plan into a spec, then a new arrangement of it", "layoutdsl import plan.xml -o specs/plan.lay"),
            ("keep the plan's arrangement as hints", "layoutdsl import plan.xml -o plan.lay --keep-arrangement"),
            ("a room graph with office room sizes", "layoutdsl import graph.csv -o graph.lay --like office"),
            ("the result (rooms, the file written) as JSON; out/ is created", "layoutdsl import plan.xml -o out/plan.lay --format json"),
        ],
    )  # fmt: skip
    parser.add_argument("input", help="building XML file or room graph (.csv, .json, .graphml), or - for standard input")
    parser.add_argument(
        "-o", "--output", default="-", help="spec file to write, or - for standard output (default)"
    )
    parser.add_argument(
        "--var-plus", type=float, default=_DEFAULTS.var_plus, metavar="F",
        help=f"variance+ of rooms: max side = bbox side x (ratio + F) (default {_DEFAULTS.var_plus})",
    )  # fmt: skip
    parser.add_argument(
        "--var-minus", type=float, default=_DEFAULTS.var_minus, metavar="F",
        help=f"variance- of rooms: min side = bbox side x (ratio - F) (default {_DEFAULTS.var_minus})",
    )  # fmt: skip
    parser.add_argument(
        "--var-corridor", type=float, default=_DEFAULTS.var_corridor, metavar="F",
        help=f"+/- variance of corridors (default {_DEFAULTS.var_corridor})",
    )  # fmt: skip
    parser.add_argument(
        "--mindim", type=float, default=_DEFAULTS.mindim, metavar="M",
        help=f"minimum side of every room in metres (default {_DEFAULTS.mindim})",
    )  # fmt: skip
    parser.add_argument(
        "--alpha", type=float, default=_DEFAULTS.alpha, metavar="F",
        help=f"linear weight of the aspect-ratio margin (default {_DEFAULTS.alpha})",
    )  # fmt: skip
    parser.add_argument(
        "--beta", type=float, default=_DEFAULTS.beta, metavar="F",
        help=f"quadratic weight of the aspect-ratio margin (default {_DEFAULTS.beta})",
    )  # fmt: skip
    parser.add_argument(
        "--l-threshold", type=float, default=_DEFAULTS.l_threshold, metavar="F",
        help="a space whose polygon covers less than F of its bounding box becomes an "
        f"L-shaped room fitted to the polygon (default {_DEFAULTS.l_threshold}; 0: none)",
    )  # fmt: skip
    parser.add_argument(
        "--rectangular-only", action="store_true",
        help="every room a rectangle of its polygon's area, as the thesis imports (§5.3.1)",
    )  # fmt: skip
    parser.add_argument(
        "--keep-arrangement", dest="hints", action="store_true", default=False,
        help="write the rooms' places in the original plan as hints: compile starts from "
        "the original arrangement instead of generating a new one",
    )  # fmt: skip
    parser.add_argument(
        "--no-hints", dest="no_hints", action="store_true",
        help="deprecated, does nothing: no hints is the default since 0.1.0; removed in 0.3",
    )  # fmt: skip
    parser.add_argument(
        "--stdin-filename", metavar="NAME", help="the name messages use for standard input"
    )
    add_output_arguments(parser, diagnostics=True)
    import_graph.add_arguments(parser)
    parser.set_defaults(run=run)


NO_HINTS_WARNING = (
    "`--no-hints` is deprecated and does nothing: a spec gets no hints unless "
    "--keep-arrangement is given (the default since 0.1.0); the flag will be removed in 0.3"
)
"""Warned, not yet removed: scripts written for 0.0.x pass it, and it asks for what is now the
default, so it can keep working for a release while they are told to drop it."""


def run(args: argparse.Namespace) -> int:
    """Import one plan or graph; 0 on success (warnings allowed), 1 on errors, 2 on usage/I/O errors."""
    from layoutdsl.api import lint_source
    from layoutdsl.emit.atomic import write_text_atomic
    from layoutdsl.syntax.format import format_spec

    out = Output("import", args)
    if args.no_hints:
        out.warning(NO_HINTS_WARNING)
    try:
        options = ImportOptions(
            var_plus=args.var_plus,
            var_minus=args.var_minus,
            var_corridor=args.var_corridor,
            mindim=args.mindim,
            alpha=args.alpha,
            beta=args.beta,
            l_threshold=args.l_threshold,
            rectangular_only=args.rectangular_only,
            hints=args.hints,
        )
    except ValueError as error:
        return out.finish(out.error(str(error)))

    text: str | None = None
    out.reading(args.input)
    if args.input == "-":
        source_name = args.stdin_filename or "<stdin>"
        text = sys.stdin.read()
        head = text
    else:
        source_name = args.input
        try:  # one I/O error style (exit 2) for a missing or unreadable input, whatever its format
            head = Path(args.input).read_bytes().decode("utf-8", errors="replace")
        except OSError as error:
            return out.finish(out.cannot_read(args.input, error))
    wrong = wrong_kind_for_import(source_name, head)
    if wrong is not None:  # `import spec.lay`: say it is already a spec, not "malformed XML"
        out.diagnostics([wrong], {source_name: Source(source_name, head)})
        return out.finish(exitcodes.SPEC_ERRORS)
    to_stdout = args.output == "-"
    if not to_stdout:
        try:
            ensure_parent(args.output)  # `-o out/plan.lay` creates out/
        except OSError as error:
            return out.finish(out.cannot_write(args.output, error))
    graph_format = import_graph.graph_format(args, text)
    if graph_format is not None:  # a room graph without geometry, not a building plan
        def show(diagnostics, sources, _style) -> None:
            out.diagnostics(diagnostics, sources)

        code = import_graph.run(args, graph_format, text, show)
        if code == exitcodes.OK and not to_stdout:
            out.wrote(args.output)
        return out.finish(code, input_format=graph_format)
    # The spec's name is the output's stem, which is also what reading the file back gives,
    # so the formatter needs no `name` setting and the output stays a plain thesis file.
    if to_stdout:
        name = Path(args.stdin_filename or "stdin").stem if args.input == "-" else Path(args.input).stem
    else:
        name = Path(args.output).stem
    with out.timed("import"):
        spec, diagnostics = import_building(source_name, options, text=text, name=name)

    sources = {source_name: Source(source_name, head)}
    out.diagnostics(diagnostics, sources)
    if spec is None or has_errors(diagnostics):
        return out.finish(exitcodes.SPEC_ERRORS)

    spec = replace(spec, path=f"{name}.lay" if to_stdout else args.output)
    output = format_spec(spec)
    # The importer promises specs that lint clean; check before writing, so a bug shows up
    # as diagnostics here rather than as a broken file for the next command.
    lint_errors = [d for d in lint_source(Source(spec.path, output))[1] if d.is_error]
    if lint_errors:
        out.diagnostics(lint_errors, {spec.path: Source(spec.path, output)})
        return out.finish(out.error("the imported spec does not lint clean (an importer bug); nothing written",
                                    exitcodes.SPEC_ERRORS, kind="bug"))
    if to_stdout:
        out.product(output)
    else:
        try:
            write_text_atomic(args.output, output)
        except OSError as error:
            return out.finish(out.cannot_write(args.output, error))
        out.wrote(args.output)
    where = "standard output" if to_stdout else f"`{args.output}`"
    # on stderr: stdout may hold the spec itself
    out.progress(f"imported {len(spec.rooms)} rooms{_l_rooms(spec)} and {len(spec.adjacencies)} adjacencies into {where}")
    return out.finish(exitcodes.OK, input_format="xml", spec=spec.name, rooms=len(spec.rooms),
                      adjacencies=len(spec.adjacencies), l_rooms=len(spec.arms))


def _l_rooms(spec) -> str:
    return f" ({len(spec.arms)} L-shaped)" if spec.arms else ""
