"""`layoutdsl lint PATH...`: report every problem in specs (diagnostics go to stdout)."""

from __future__ import annotations

import argparse
import sys

from layoutdsl.api import lint_source, read_source
from layoutdsl.cli.output import Output, add_command, add_output_arguments, expand_specs, plural
from layoutdsl.diagnostics import exitcodes
from layoutdsl.diagnostics.filekind import wrong_kind_for_spec
from layoutdsl.diagnostics.render import summary
from layoutdsl.diagnostics.source import Source


def add_parser(subparsers) -> argparse.ArgumentParser:
    """Register the `lint` subcommand."""
    parser = add_command(
        subparsers, "lint",
        help="check specs and report every problem",
        description="Check layout specs and report every problem with its location, code and a "
        "hint. A folder means every `*.lay` file under it, recursively. Diagnostics go to "
        "standard output; `layoutdsl explain CODE` tells more about a code.",
        examples=[
            ("check one spec", "layoutdsl lint specs/office_small.lay"),
            ("check every spec under a folder, one line per problem", "layoutdsl lint --format concise specs/"),
            ("the result as JSON for a script", "layoutdsl lint --format json specs/office_small.lay"),
            ("check an editor buffer", "layoutdsl lint --stdin-filename mine.lay - < mine.lay"),
        ],
    )  # fmt: skip
    parser.add_argument("files", nargs="+", metavar="PATH",
                        help="spec files or folders of them; `-` reads standard input")
    parser.add_argument(
        "--stdin-filename", metavar="NAME", default=None,
        help="the name messages use for standard input (default `<stdin>`)",
    )  # fmt: skip
    parser.add_argument(
        "--warnings-as-errors", action="store_true", help="exit with 1 when there are only warnings"
    )
    add_output_arguments(parser, diagnostics=True)
    parser.set_defaults(run=run)
    return parser


def read_input(path: str, stdin_filename: str | None) -> Source:
    """The source for a FILE argument (`-` = standard input); raises OSError/ValueError."""
    if path == "-":
        data = getattr(sys.stdin, "buffer", sys.stdin).read()  # a StringIO stdin has no buffer
        return Source(stdin_filename or "<stdin>", data.decode("utf-8") if isinstance(data, bytes) else data)
    return read_source(path)


def run(args: argparse.Namespace) -> int:
    """Lint every file; exit 0 clean, 1 errors, 2 when a file cannot be read."""
    out = Output("lint", args)
    sources: dict[str, Source] = {}
    diagnostics = []
    paths, empty = expand_specs(args.files)
    unreadable = 0
    for folder in empty:
        out.error(f"no `.lay` files under `{folder}`", kind="io", path=folder)
        unreadable += 1
    for path in paths:
        out.reading(path)
        try:
            source = read_input(path, args.stdin_filename)
        except (OSError, ValueError) as error:
            out.cannot_read(path, error)
            unreadable += 1
            continue
        sources[source.path] = source
        wrong = wrong_kind_for_spec(source.path, source.text)
        if wrong is not None:  # a plan or a graph: one E019 instead of a page of syntax errors
            diagnostics.append(wrong)
            continue
        _, found = lint_source(source)
        diagnostics.extend(found)
    out.diagnostics(diagnostics, sources, stream="stdout")
    if out.format == "text" and diagnostics:
        out.stdout.write("\n")  # a blank line between the last excerpt and the summary
    # never "no problems found" about files that were not read
    line = summary(diagnostics)
    if unreadable:
        line = (f"{line} in the {plural(len(sources), 'file')} read" if diagnostics
                else f"checked {plural(len(sources), 'file')}")
        line += f"; {unreadable} could not be read"
    elif out.verbose:
        line += f" in {plural(len(sources), 'file')}"
    out.summary(line)
    if unreadable:
        code = exitcodes.USAGE
    else:
        failing = [d for d in diagnostics if d.is_error or (args.warnings_as_errors and d.severity.value == "warning")]
        code = exitcodes.SPEC_ERRORS if failing else exitcodes.OK
    return out.finish(code, files=list(sources))
