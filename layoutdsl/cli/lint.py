"""`layoutdsl lint FILE...`: report every problem in specs (diagnostics go to stdout)."""

from __future__ import annotations

import argparse
import sys

from layoutdsl.diagnostics import exitcodes
from layoutdsl.api import lint_source, read_source
from layoutdsl.diagnostics.render import render_concise, render_full, render_json, summary
from layoutdsl.diagnostics.source import Source


def add_parser(subparsers) -> argparse.ArgumentParser:
    """Register the `lint` subcommand."""
    parser = subparsers.add_parser(
        "lint",
        help="check specs and report every problem",
        description="Check layout specs and report every problem with its location, code and a hint.",
        epilog=exitcodes.EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument("files", nargs="+", metavar="FILE", help="spec files; `-` reads standard input")
    parser.add_argument(
        "--format", choices=("full", "concise", "json"), default="full",
        help="full: code excerpts and hints (default); concise: one line each; json: for tools",
    )  # fmt: skip
    parser.add_argument(
        "--stdin-filename", metavar="NAME", default=None,
        help="the name messages use for standard input (default `<stdin>`)",
    )  # fmt: skip
    parser.add_argument(
        "--warnings-as-errors", action="store_true", help="exit with 1 when there are only warnings"
    )
    parser.set_defaults(run=run)
    return parser


def read_input(path: str, stdin_filename: str | None) -> Source:
    """The source for a FILE argument (`-` = standard input); raises OSError/ValueError."""
    if path == "-":
        data = sys.stdin.buffer.read()
        return Source(stdin_filename or "<stdin>", data.decode("utf-8"))
    return read_source(path)


def run(args: argparse.Namespace) -> int:
    """Lint every file; exit 0 clean, 1 errors, 2 when a file cannot be read."""
    sources: dict[str, Source] = {}
    diagnostics = []
    io_failed = False
    for path in args.files:
        try:
            source = read_input(path, args.stdin_filename)
        except (OSError, ValueError) as error:
            reason = error.strerror if isinstance(error, OSError) and error.strerror else str(error)
            if isinstance(error, UnicodeDecodeError):
                reason = f"not UTF-8 text (byte {error.start})"
            print(f"layoutdsl lint: cannot read {path}: {reason}", file=sys.stderr)
            io_failed = True
            continue
        sources[source.path] = source
        _, found = lint_source(source)
        diagnostics.extend(found)
    if args.format == "json":
        sys.stdout.write(render_json(diagnostics))
    else:
        text = render_full(diagnostics, sources) if args.format == "full" else render_concise(diagnostics)
        if text:
            sys.stdout.write(text + ("\n" if args.format == "full" else ""))
        print(summary(diagnostics))
    if io_failed:
        return exitcodes.USAGE
    failing = [d for d in diagnostics if d.is_error or args.warnings_as_errors]
    return exitcodes.SPEC_ERRORS if failing else exitcodes.OK
