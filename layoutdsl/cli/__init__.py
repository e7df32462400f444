"""The `layoutdsl` command: a thin dispatcher over one module per subcommand.

Each subcommand module defines `add_parser(subparsers)` and `run(args) -> int`; modules are
imported only when their command runs, so `lint` never pays for importing Pyomo.
"""

from __future__ import annotations

import argparse
import importlib
import sys

from layoutdsl import __version__, exitcodes

# command name -> module under layoutdsl.cli, in the order --help lists them
COMMANDS = {
    "compile": "compile",
    "lint": "lint",
    "fmt": "fmt",
    "import": "import_xml",
    "evaluate": "evaluate",
}


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="layoutdsl",
        description="Compile building-layout specs into verified floor plans for robot simulation.",
        epilog=exitcodes.EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument("--version", action="version", version=f"layoutdsl {__version__}")
    subparsers = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name, module_name in COMMANDS.items():
        try:
            module = importlib.import_module(f"layoutdsl.cli.{module_name}")
        except ModuleNotFoundError as error:
            if error.name != f"layoutdsl.cli.{module_name}":
                raise
            continue  # a command still being built is simply not offered
        module.add_parser(subparsers)
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
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


if __name__ == "__main__":
    sys.exit(main())
