"""`layoutdsl fmt FILE...`: print (or --check, or --write) the canonical form of specs."""

from __future__ import annotations

import argparse
import sys

from layoutdsl.diagnostics import exitcodes
from layoutdsl.emit.atomic import write_text_atomic
from layoutdsl.cli.lint import read_input
from layoutdsl.diagnostics import has_errors
from layoutdsl.syntax.format import format_source
from layoutdsl.syntax.parser import parse_source
from layoutdsl.diagnostics.render import render_full


def add_parser(subparsers) -> argparse.ArgumentParser:
    """Register the `fmt` subcommand."""
    parser = subparsers.add_parser(
        "fmt",
        help="print specs in canonical form",
        description=(
            "Print the canonical form of layout specs (thesis section order, single spaces, "
            "shortest exact numbers). Comments are kept: a comment line stays above the line "
            "after it, a comment after values stays at the end of its line."
        ),
        epilog=exitcodes.EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument("files", nargs="+", metavar="FILE", help="spec files; `-` reads standard input")
    mode = parser.add_mutually_exclusive_group()
    mode.add_argument("--check", action="store_true", help="exit 1 if a file is not in canonical form")
    mode.add_argument("--write", action="store_true", help="rewrite files in place (atomically)")
    parser.add_argument("--stdin-filename", metavar="NAME", default=None, help="name for standard input")
    parser.set_defaults(run=run)
    return parser


def run(args: argparse.Namespace) -> int:
    """Format every file; errors in a spec are printed to stderr and the file is left alone."""
    status = exitcodes.OK
    for path in args.files:
        try:
            source = read_input(path, args.stdin_filename)
        except (OSError, ValueError) as error:
            reason = error.strerror if isinstance(error, OSError) and error.strerror else str(error)
            print(f"layoutdsl fmt: cannot read {path}: {reason}", file=sys.stderr)
            status = exitcodes.USAGE
            continue
        spec, diagnostics = parse_source(source)
        if spec is None or has_errors(diagnostics):
            sys.stderr.write(render_full(diagnostics, {source.path: source}))
            status = max(status, exitcodes.SPEC_ERRORS)
            continue
        text = format_source(source)
        if args.check:
            if text != source.text:
                print(f"would reformat {source.path}", file=sys.stderr)
                status = max(status, exitcodes.SPEC_ERRORS)
        elif args.write:
            if text == source.text:
                continue
            if path == "-":
                sys.stdout.write(text)
                continue
            try:
                write_text_atomic(path, text)
            except OSError as error:
                print(f"layoutdsl fmt: cannot write {path}: {error.strerror or error}", file=sys.stderr)
                status = exitcodes.USAGE
                continue
            print(f"reformatted {path}", file=sys.stderr)
        else:
            sys.stdout.write(text)
    return status
