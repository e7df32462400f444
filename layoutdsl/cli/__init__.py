"""The `layoutdsl` command: a thin dispatcher over one module per subcommand.

Each subcommand module defines `add_parser(subparsers)` and `run(args) -> int`; modules are
imported only when their command runs, so `lint` never pays for importing Pyomo.
"""

from __future__ import annotations

import argparse
import importlib
import os
import sys

from layoutdsl import __version__
from layoutdsl.cli.output import HelpFormatter, examples_block
from layoutdsl.diagnostics import exitcodes

# command name -> (module under layoutdsl.cli, one-line help), in the order --help lists them.
# The one-line help lives here so `layoutdsl --help` need not import every command.
COMMANDS = {
    "compile": ("compile", "solve a spec into a verified layout and write its files"),
    "lint": ("lint", "report every problem in spec files"),
    "fmt": ("fmt", "print or rewrite a spec in canonical form"),
    "import": ("import_xml", "convert a building XML plan into a spec"),
    "evaluate": ("evaluate", "compare generated plans with their original"),
    "batch": ("batch", "make many verified buildings from specs and plans, resumably"),
    "sample": ("sample", "write specs of new buildings learned from real plans"),
    "explain": ("explain", "print what a diagnostic code means"),
    "sizes": ("sizes", "fit or show the room-size model learned from real plans"),
    "lsp": ("lsp", "run the language server for editors (stdio)"),
}


def build_parser(command: str | None = None) -> argparse.ArgumentParser:
    """The argument parser; only `command`'s module is imported (all of them when None)."""
    parser = argparse.ArgumentParser(
        prog="layoutdsl",
        description=(
            "Compile building-layout specs into verified floor plans for robot simulation.\n"
            "Follows Carideo, Procedural generation of realistic building layouts from graphs\n"
            "(Politecnico di Milano, 2019); \"the thesis, §5.4\" in messages means its sections."
        ),
        epilog=examples_block([
            ("check a spec, then compile it into out/", "layoutdsl lint specs/office_small.lay"),
            ("", "layoutdsl compile specs/office_small.lay -o out"),
            ("what a diagnostic code means", "layoutdsl explain E102"),
            ("a command's options and examples", "layoutdsl compile --help"),
        ]) + "\n" + exitcodes.EPILOG + "\nEvery command takes -q/--quiet, -v/--verbose and --format text|json.\n",
        formatter_class=HelpFormatter,
    )
    parser.add_argument("--version", action="version", version=f"layoutdsl {__version__}")
    subparsers = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name, (module_name, summary) in COMMANDS.items():
        if command is None or name == command:
            module = importlib.import_module(f"layoutdsl.cli.{module_name}")
            module.add_parser(subparsers)
        else:
            subparsers.add_parser(name, help=summary)
    return parser


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    # The first plain word names the command; top-level options take no values.
    command = next((word for word in argv if not word.startswith("-")), None)
    parser = build_parser(command if command in COMMANDS else None)
    args = _parse(parser, argv, command)
    if not getattr(args, "run", None):
        parser.print_help(sys.stderr)
        return exitcodes.USAGE
    try:
        return args.run(args)
    except KeyboardInterrupt:
        print("layoutdsl: interrupted", file=sys.stderr)
        return exitcodes.USAGE
    except BrokenPipeError:
        return exitcodes.USAGE
    except Exception as error:  # a bug in layoutdsl, not a problem of the input
        if os.environ.get("LAYOUTDSL_TRACEBACK"):
            raise
        print(
            f"layoutdsl: internal error: {type(error).__name__}: {error}\n"
            "  this is a bug in layoutdsl, not in your input; nothing was written.\n"
            "  set LAYOUTDSL_TRACEBACK=1 to see where it happened, and please report it",
            file=sys.stderr,
        )
        if getattr(args, "format", None) == "json":  # a script still gets its one result object
            from layoutdsl.cli.output import Output

            out = Output(args.command, args)
            out.errors.append({"kind": "internal", "message": f"{type(error).__name__}: {error}"})
            out.finish(exitcodes.USAGE)
        return exitcodes.USAGE


def _wants_json(argv: list[str]) -> bool:
    return any(word == "--format=json" or (word == "--format" and following == "json")
               for word, following in zip(argv, [*argv[1:], ""]))


def _parse(parser: argparse.ArgumentParser, argv: list[str], command: str | None) -> argparse.Namespace:
    """parser.parse_args; a usage error under --format json also prints the one JSON result
    object (status usage_or_io_error, argparse's message), so a script never parses text."""
    if not _wants_json(argv):
        return parser.parse_args(argv)
    import contextlib
    import io

    messages = io.StringIO()
    try:
        with contextlib.redirect_stderr(messages):
            return parser.parse_args(argv)
    except SystemExit as stop:
        if stop.code == exitcodes.USAGE:
            import json

            last = messages.getvalue().strip().splitlines()[-1:] or ["usage error"]
            print(json.dumps({"command": command, "status": exitcodes.STATUS[exitcodes.USAGE],
                              "exit_code": exitcodes.USAGE, "read": [], "written": [], "diagnostics": [],
                              "errors": [{"kind": "usage", "message": last[0]}], "timings": {}}, indent=2))
        raise
    finally:
        sys.stderr.write(messages.getvalue())  # usage and warnings still reach the terminal


if __name__ == "__main__":
    sys.exit(main())
