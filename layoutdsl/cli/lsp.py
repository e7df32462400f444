"""`layoutdsl lsp`: the language server for `.lay` specs, over standard input and output."""

from __future__ import annotations

import argparse
import logging

from layoutdsl.cli.output import Output, add_command, add_output_arguments
from layoutdsl.diagnostics import exitcodes

INSTALL_HINT = "install the `lsp` extra: pip install 'layoutdsl[lsp]'"


def add_parser(subparsers) -> argparse.ArgumentParser:
    """Register the `lsp` subcommand."""
    parser = add_command(
        subparsers, "lsp",
        help="run the language server for editors (stdio)",
        description="Run the layoutdsl language server on standard input and output, for an "
        "editor to start: lint diagnostics as you type, hover on a room id, go to definition "
        "and references, completion, formatting through `fmt` and quick fixes. Standard "
        "output carries the protocol, so messages go to standard error; with `--format json` "
        "the result object is written after the client has said exit. docs/editor.md shows "
        "how to configure VS Code, Neovim and Helix.",
        examples=[
            ("what an editor runs", "layoutdsl lsp"),
            ("the same, logging each request to standard error", "layoutdsl lsp -v"),
        ],
    )  # fmt: skip
    parser.add_argument(
        "--stdio", action="store_true",
        help="accepted for editors that pass it (vscode-languageclient does); stdio is the only transport",
    )  # fmt: skip
    add_output_arguments(parser)
    parser.set_defaults(run=run)
    return parser


def run(args: argparse.Namespace) -> int:
    """Serve until the client exits; exit 2 when pygls is not installed."""
    out = Output("lsp", args)
    try:
        from layoutdsl.lsp.server import build_server
    except ImportError as error:
        out.error(f"the language server needs pygls ({error.name or error}): {INSTALL_HINT}", kind="usage")
        return out.finish(exitcodes.USAGE)
    level = logging.DEBUG if out.verbose else logging.ERROR if out.quiet else logging.WARNING
    logging.basicConfig(level=level, format="layoutdsl lsp: %(levelname)s: %(message)s")
    out.detail("serving the language server on standard input and output")
    with out.timed("serve"):
        build_server().start_io()
    return out.finish(exitcodes.OK)
