"""`layoutdsl fmt PATH...`: print (or --check, or --write) the canonical form of specs."""

from __future__ import annotations

import argparse

from layoutdsl.cli.lint import read_input
from layoutdsl.cli.output import Output, add_command, add_output_arguments, expand_specs, plural
from layoutdsl.diagnostics import exitcodes, has_errors
from layoutdsl.diagnostics.filekind import wrong_kind_for_spec
from layoutdsl.emit.atomic import write_text_atomic
from layoutdsl.sizes.resolve import resolve_spec
from layoutdsl.syntax.format import format_source
from layoutdsl.syntax.parser import parse_source


def add_parser(subparsers) -> argparse.ArgumentParser:
    """Register the `fmt` subcommand."""
    parser = add_command(
        subparsers, "fmt",
        help="print specs in canonical form",
        description=(
            "Print the canonical form of layout specs (thesis section order, single spaces, "
            "shortest exact numbers). Comments are kept: a comment line stays above the line "
            "after it, a comment after values stays at the end of its line. A folder means "
            "every `*.lay` file under it, recursively. A spec with errors is left alone and "
            "its diagnostics are printed."
        ),
        examples=[
            ("print the canonical form", "layoutdsl fmt specs/office_small.lay"),
            ("fail (exit 1) if any spec under a folder is not canonical, as CI does", "layoutdsl fmt --check specs/"),
            ("rewrite every spec under a folder in place", "layoutdsl fmt --write specs/"),
        ],
    )  # fmt: skip
    parser.add_argument("files", nargs="+", metavar="PATH",
                        help="spec files or folders of them; `-` reads standard input")
    mode = parser.add_mutually_exclusive_group()
    mode.add_argument("--check", action="store_true", help="exit 1 if a file is not in canonical form")
    mode.add_argument("--write", action="store_true", help="rewrite files in place (atomically)")
    parser.add_argument("--stdin-filename", metavar="NAME", default=None, help="name for standard input")
    parser.add_argument(
        "--fill-sizes", action="store_true",
        help="write the sizes the size model gives sizeless rooms (`R1 R CLASSROOM`) and the "
        "boundary the tool chooses when there is none (docs/sizes.md)",
    )  # fmt: skip
    add_output_arguments(parser, diagnostics=True)
    parser.set_defaults(run=run)
    return parser


def run(args: argparse.Namespace) -> int:
    """Format every file; errors in a spec are printed to stderr and the file is left alone."""
    out = Output("fmt", args)
    status = exitcodes.OK
    paths, empty = expand_specs(args.files)
    for folder in empty:
        status = out.error(f"no `.lay` files under `{folder}`", kind="io", path=folder)
    unchanged: list[str] = []
    changed: list[str] = []
    formatted: dict[str, str] = {}
    for path in paths:
        out.reading(path)
        try:
            source = read_input(path, args.stdin_filename)
        except (OSError, ValueError) as error:
            status = max(status, out.cannot_read(path, error))
            continue
        wrong = wrong_kind_for_spec(source.path, source.text)
        spec, diagnostics = (None, [wrong]) if wrong is not None else parse_source(source)
        out.diagnostics(diagnostics, {source.path: source})
        if spec is None or has_errors(diagnostics):
            status = max(status, exitcodes.SPEC_ERRORS)
            continue
        text = format_source(source, resolve=resolve_spec if args.fill_sizes else None)
        (unchanged if text == source.text else changed).append(source.path)
        if args.check:
            if text != source.text:
                if not out.json:
                    print(f"would reformat {source.path}", file=out.stderr)
                status = max(status, exitcodes.SPEC_ERRORS)
        elif args.write:
            if text == source.text:
                continue
            if path == "-":
                out.product(text)
                continue
            try:
                write_text_atomic(path, text)
            except OSError as error:
                status = max(status, out.cannot_write(path, error))
                continue
            out.wrote(path)
            out.progress(f"reformatted {path}")
        elif out.json:
            formatted[source.path] = text
        else:
            out.product(text)
    if (args.check or args.write) and "-" not in paths:  # stdout may hold a formatted spec
        verb = "would reformat" if args.check else "reformatted"
        out.summary(f"{plural(len(changed), 'file')} {verb}, {len(unchanged)} already canonical")
    fields = {"changed": changed, "unchanged": unchanged}
    if formatted:
        fields["formatted"] = formatted
    return out.finish(status, **fields)
