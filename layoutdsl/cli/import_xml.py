"""`layoutdsl import plan.xml -o plan.lay`: a real floor plan (building XML) -> a spec.

The spec is written in the thesis' intermediate-model format (the thesis, §5.4): the room
graph, size bounds and boundary, from which `compile` generates a new arrangement. With
`--keep-arrangement` it also gets a `hints` section (each room's place in the original
plan), which compile then starts from, so the layout keeps the original arrangement.
Diagnostics go to stderr; the output file is written atomically and only when the import succeeded.
"""

from __future__ import annotations

import argparse
import sys
from dataclasses import replace
from pathlib import Path

from layoutdsl.cli import import_graph
from layoutdsl.diagnostics import exitcodes
from layoutdsl.diagnostics import Diagnostic, has_errors
from layoutdsl.importer import ImportOptions, import_building
from layoutdsl.importer import codes as import_codes
from layoutdsl.diagnostics.source import Source

_DEFAULTS = ImportOptions()


def add_parser(subparsers) -> None:
    """Register the `import` subcommand."""
    parser = subparsers.add_parser(
        "import",
        help="convert a building XML floor plan into a spec (the thesis, §5.3)",
        description=(
            "Convert a real floor plan in the building XML format into a layout spec:\n"
            "one rectangular room per space (sizes from its polygon, the thesis, §5.3), one\n"
            "adjacency per pair of spaces joined by a portal, the plan's bounding box as\n"
            "boundary. compile then generates a NEW arrangement of that room graph;\n"
            "--keep-arrangement also writes each room's original place as a hint, and\n"
            "compile then starts from (and mostly keeps) the original arrangement."
        ),
        epilog=exitcodes.EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
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
        "--no-hints", dest="hints", action="store_false",
        help="no hints section (the default; kept for compatibility)",
    )  # fmt: skip
    parser.add_argument(
        "--stdin-filename", metavar="NAME", help="the name messages use for standard input"
    )
    parser.add_argument(
        "--format", choices=("full", "concise", "json"), default="full",
        help="how diagnostics are printed (default full)",
    )  # fmt: skip
    parser.add_argument("-q", "--quiet", action="store_true", help="print no summary line")
    import_graph.add_arguments(parser)
    parser.set_defaults(run=run)


def _print_diagnostics(diagnostics: list[Diagnostic], sources: dict[str, Source], style: str) -> None:
    from layoutdsl.diagnostics import render

    if not diagnostics and style != "json":
        return
    if style == "json":
        text = render.render_json(diagnostics)
    elif style == "concise":
        text = render.render_concise(diagnostics)
    else:
        text = render.render_full(diagnostics, sources)
    sys.stderr.write(text)


def run(args: argparse.Namespace) -> int:
    """Import one plan; 0 on success (warnings allowed), 1 on errors, 2 on usage/I/O errors."""
    from layoutdsl.api import lint_source
    from layoutdsl.emit.atomic import write_text_atomic
    from layoutdsl.syntax.format import format_spec

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
        print(f"layoutdsl import: error: {error}", file=sys.stderr)
        return exitcodes.USAGE

    text: str | None = None
    if args.input == "-":
        source_name = args.stdin_filename or "<stdin>"
        text = sys.stdin.read()
    else:
        source_name = args.input
    graph_format = import_graph.graph_format(args, text)
    if graph_format is not None:  # a room graph without geometry, not a building plan
        return import_graph.run(args, graph_format, text, _print_diagnostics)
    to_stdout = args.output == "-"
    # The spec's name is the output's stem, which is also what reading the file back gives,
    # so the formatter needs no `name` setting and the output stays a plain thesis file.
    if to_stdout:
        name = Path(args.stdin_filename or "stdin").stem if args.input == "-" else Path(args.input).stem
    else:
        name = Path(args.output).stem
    spec, diagnostics = import_building(source_name, options, text=text, name=name)

    sources = {}
    xml_text = text if text is not None else _read_quietly(Path(source_name))
    if xml_text is not None:
        sources[source_name] = Source(source_name, xml_text)
    _print_diagnostics(diagnostics, sources, args.format)
    if spec is None or has_errors(diagnostics):
        if any(d.code == import_codes.UNREADABLE_FILE for d in diagnostics):
            return exitcodes.USAGE
        return exitcodes.SPEC_ERRORS

    spec = replace(spec, path=f"{name}.lay" if to_stdout else args.output)
    output = format_spec(spec)
    # The importer promises specs that lint clean; check before writing, so a bug shows up
    # as diagnostics here rather than as a broken file for the next command.
    lint_errors = [d for d in lint_source(Source(spec.path, output))[1] if d.is_error]
    if lint_errors:
        _print_diagnostics(lint_errors, {spec.path: Source(spec.path, output)}, args.format)
        print("layoutdsl import: error: the imported spec does not lint clean (an importer bug); nothing written", file=sys.stderr)
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
    if not args.quiet and args.format != "json":
        where = "standard output" if to_stdout else f"`{args.output}`"
        print(
            f"imported {len(spec.rooms)} rooms{_l_rooms(spec)} and {len(spec.adjacencies)} adjacencies into {where}",
            file=sys.stderr,
        )
    return exitcodes.OK


def _l_rooms(spec) -> str:
    return f" ({len(spec.arms)} L-shaped)" if spec.arms else ""


def _read_quietly(path: Path) -> str | None:
    try:
        return path.read_text(encoding="utf-8", errors="replace")
    except OSError:
        return None
