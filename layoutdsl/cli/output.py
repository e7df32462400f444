"""One output convention for every subcommand (issue 42: "one CLI convention").

Every command registers its parser with `add_command` and its output flags with
`add_output_arguments`, then reports through an `Output`:

- `-q/--quiet`: only what the command exists to produce (a formatted spec, diagnostics,
  errors); no progress, no summary.  `-v/--verbose`: also each step, the files read and
  written, and timings.  Neither: progress and a summary.
- `--format text|json` (commands that print diagnostics also take `concise`): with `json`,
  stdout holds exactly one JSON object when the command ends, successful or not:

      {"command": "compile", "status": "ok", "exit_code": 0, "written": [...],
       "diagnostics": [...], "errors": [...], "timings": {"total_s": 1.2, ...}, ...}

  (plus fields of the command); progress still goes to stderr unless -q.
- An I/O problem is always `layoutdsl CMD: error: cannot read `PATH`: REASON` on stderr and
  exit 2 (exitcodes.USAGE), never a diagnostic with an invented location.
- Colour: diagnostics and error lines are coloured only when the stream is a terminal and
  `NO_COLOR` is unset or empty (https://no-color.org); never when piped.
- Help: descriptions are wrapped to the terminal (at most 88 columns), followed by an
  `examples:` section and the exit codes the command can return (exitcodes.BY_COMMAND).
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import re
import shutil
import sys
import textwrap
import time
from collections.abc import Iterable, Iterator, Mapping
from pathlib import Path
from typing import Any, TextIO

from layoutdsl.diagnostics import exitcodes

QUIET, NORMAL, VERBOSE = -1, 0, 1
"""Verbosity levels (`Output.level`)."""

HELP_WIDTH = 88
"""Help lines are wrapped to the terminal's width, but never wider than this."""

DEPRECATED_FORMATS = {"full": "text"}
"""`--format` values still accepted with a warning: old name -> new name."""


# --------------------------------------------------------------------------- help


class HelpFormatter(argparse.RawDescriptionHelpFormatter):
    """Wraps prose paragraphs of descriptions and epilogs to the terminal; keeps indented
    lines (examples, exit codes, lists) as written, so commands can be copied."""

    def __init__(self, prog: str, **kwargs: Any) -> None:
        width = min(HELP_WIDTH, shutil.get_terminal_size((HELP_WIDTH, 24)).columns - 2)
        kwargs.setdefault("width", max(width, 40))
        kwargs.setdefault("max_help_position", 30)
        super().__init__(prog, **kwargs)

    def _fill_text(self, text: str, width: int, indent: str) -> str:
        out: list[str] = []
        for paragraph in re.split(r"\n\s*\n", text.strip("\n")):
            lines = paragraph.split("\n")
            if any(line.startswith(" ") for line in lines) or lines[0].rstrip().endswith(":"):
                out.append("\n".join(indent + line for line in lines))
            else:
                words = " ".join(line.strip() for line in lines)
                out.append(textwrap.fill(words, width, initial_indent=indent, subsequent_indent=indent))
        return "\n\n".join(out) + "\n"


def examples_block(examples: Iterable[tuple[str, str]]) -> str:
    """`examples:` then, per example, `  # what it does` and `  $ command`."""
    lines = ["examples:"]
    for what, command in examples:
        if what:  # an empty description continues the example above
            lines.append(f"  # {what}")
        lines.append(f"  $ {command}")
    return "\n".join(lines) + "\n"


def add_command(
    subparsers,
    name: str,
    *,
    help: str,
    description: str,
    examples: Iterable[tuple[str, str]] = (),
    exit_codes: tuple[int, ...] | None = None,
) -> argparse.ArgumentParser:
    """A subcommand's parser with the common help layout: wrapped description, then
    examples, then only the exit codes it can return (default exitcodes.BY_COMMAND[name])."""
    codes = exit_codes if exit_codes is not None else exitcodes.BY_COMMAND.get(name)
    parts = []
    examples = list(examples)
    if examples:
        parts.append(examples_block(examples))
    parts.append(exitcodes.epilog(codes, name))
    parser = subparsers.add_parser(
        name, help=help, description=description, epilog="\n".join(parts), formatter_class=HelpFormatter
    )
    parser.exit_codes = tuple(codes) if codes is not None else tuple(exitcodes.MEANINGS)
    return parser


def _format_value(choices: tuple[str, ...]):
    def convert(text: str) -> str:
        if text in DEPRECATED_FORMATS:
            new = DEPRECATED_FORMATS[text]
            print(f"layoutdsl: warning: `--format {text}` is deprecated and will be removed in 0.3; "
                  f"use `--format {new}` (the same output)", file=sys.stderr)
            return new
        return text

    return convert


def add_output_arguments(parser: argparse.ArgumentParser, *, diagnostics: bool = False) -> None:
    """-q/-v and --format, the same on every command. `diagnostics=True` also offers
    `--format concise` (one line per diagnostic) to commands that print diagnostics."""
    group = parser.add_argument_group("output")
    level = group.add_mutually_exclusive_group()
    level.add_argument("-q", "--quiet", action="store_true",
                       help="print only the command's product, diagnostics and errors: "
                       "no progress, no summary")
    level.add_argument("-v", "--verbose", action="store_true",
                       help="also print each step, the files read and written, and timings")
    choices = ("text", "concise", "json") if diagnostics else ("text", "json")
    group.add_argument("--format", type=_format_value(choices), choices=choices, default="text",
                       help="text: for people (default)"
                       + ("; concise: one line per diagnostic" if diagnostics else "")
                       + "; json: one JSON result object on stdout, for scripts")


# --------------------------------------------------------------------------- colour

_STYLES = {
    "error": "\x1b[1;31m",
    "warning": "\x1b[1;33m",
    "note": "\x1b[1;34m",
    "help": "\x1b[1;36m",
    "bold": "\x1b[1m",
}
_RESET = "\x1b[0m"


def use_colour(stream: TextIO) -> bool:
    """Colour only on a terminal, and never when NO_COLOR is set to a non-empty value."""
    if os.environ.get("NO_COLOR"):
        return False
    if os.environ.get("TERM") == "dumb":
        return False
    isatty = getattr(stream, "isatty", None)
    try:
        return bool(isatty and isatty())
    except ValueError:  # a closed stream
        return False


def paint(text: str, style: str, enabled: bool) -> str:
    return f"{_STYLES[style]}{text}{_RESET}" if enabled and text else text


# --------------------------------------------------------------------------- files


def describe_os_error(error: BaseException) -> str:
    """The reason a file could not be read or written, in words, the same for every command."""
    if isinstance(error, UnicodeDecodeError):
        return f"not UTF-8 text (byte {error.start})"
    if isinstance(error, IsADirectoryError):
        return "is a directory"
    if isinstance(error, FileNotFoundError):
        return "no such file or directory"
    if isinstance(error, OSError) and error.strerror:
        return error.strerror[0].lower() + error.strerror[1:]
    return str(error)


def expand_specs(paths: Iterable[str], suffix: str = ".lay") -> tuple[list[str], list[str]]:
    """FILE arguments with folders replaced by the `*.lay` files under them, recursively and
    sorted (as ruff and black do); hidden folders are skipped. Returns (files, empty folders)."""
    files: list[str] = []
    empty: list[str] = []
    for path in paths:
        if path != "-" and os.path.isdir(path):
            found = sorted(
                str(p) for p in Path(path).rglob(f"*{suffix}")
                if p.is_file() and not any(part.startswith(".") for part in p.relative_to(path).parts[:-1])
            )
            if found:
                files.extend(found)
            else:
                empty.append(path)
        else:
            files.append(path)
    return files, empty


def plural(count: int, noun: str) -> str:
    """`1 file`, `2 files`: summaries count things in words."""
    return f"{count} {noun}{'' if count == 1 else 's'}"


def ensure_parent(path: str | Path) -> None:
    """Create the folder a file is written into (`-o out/x.lay` creates `out/`)."""
    Path(path).parent.mkdir(parents=True, exist_ok=True)


# --------------------------------------------------------------------------- reporting


class Output:
    """What a command prints, in the common convention; see the module doc.

    Typical use::

        out = Output("lint", args)
        ...
        out.diagnostics(found, sources)
        return out.finish(exitcodes.OK, checked=3)
    """

    def __init__(self, command: str, args: argparse.Namespace | None = None, *,
                 stdout: TextIO | None = None, stderr: TextIO | None = None) -> None:
        self.command = command
        self.format = getattr(args, "format", "text") or "text"
        if getattr(args, "quiet", False):
            self.level = QUIET
        elif getattr(args, "verbose", False):
            self.level = VERBOSE
        else:
            self.level = NORMAL
        self._stdout = stdout
        self._stderr = stderr
        self.started = time.monotonic()
        self.timings: dict[str, float] = {}
        self.written: list[str] = []
        self.read: list[str] = []
        self.errors: list[dict[str, Any]] = []
        self.collected: list = []  # diagnostics, for the JSON result

    # streams are looked up late so pytest's capsys and redirections see them
    @property
    def stdout(self) -> TextIO:
        return self._stdout or sys.stdout

    @property
    def stderr(self) -> TextIO:
        return self._stderr or sys.stderr

    @property
    def json(self) -> bool:
        return self.format == "json"

    @property
    def quiet(self) -> bool:
        return self.level == QUIET

    @property
    def verbose(self) -> bool:
        return self.level == VERBOSE

    # -- lines for people
    def progress(self, line: str) -> None:
        """A progress line on stderr (not with -q)."""
        if self.level >= NORMAL:
            print(line, file=self.stderr, flush=True)

    def detail(self, line: str) -> None:
        """A line only -v prints (stderr)."""
        if self.level >= VERBOSE:
            print(line, file=self.stderr, flush=True)

    def summary(self, text: str) -> None:
        """The closing summary on stdout: text format only, not with -q."""
        if not self.json and self.level >= NORMAL and text:
            print(text, file=self.stdout, flush=True)

    def product(self, text: str) -> None:
        """What the command exists to print (a formatted spec) on stdout, whatever the level."""
        self.stdout.write(text)
        self.stdout.flush()

    def warning(self, message: str) -> None:
        """`layoutdsl CMD: warning: ...` on stderr (also with -q: a warning may matter)."""
        colour = use_colour(self.stderr)
        print(f"layoutdsl {self.command}: {paint('warning', 'warning', colour)}: {message}", file=self.stderr)

    def error(self, message: str, code: int = exitcodes.USAGE, *, kind: str = "usage", path: str | None = None) -> int:
        """`layoutdsl CMD: error: ...` on stderr; returns `code` (default 2) for `return`."""
        colour = use_colour(self.stderr)
        print(f"layoutdsl {self.command}: {paint('error', 'error', colour)}: {message}", file=self.stderr, flush=True)
        entry: dict[str, Any] = {"kind": kind, "message": message}
        if path is not None:
            entry["path"] = path
        self.errors.append(entry)
        return code

    def cannot_read(self, path: str, error: BaseException) -> int:
        """The one I/O error style for reading: exit 2."""
        return self.error(f"cannot read `{path}`: {describe_os_error(error)}", kind="io", path=str(path))

    def cannot_write(self, path: str | Path, error: BaseException) -> int:
        """The one I/O error style for writing: exit 2."""
        return self.error(f"cannot write `{path}`: {describe_os_error(error)}", kind="io", path=str(path))

    # -- diagnostics
    def diagnostics(self, diagnostics, sources: Mapping | None = None, *, stream: str = "stderr") -> None:
        """Print diagnostics in the chosen format (text: ruff's full format, coloured on a
        terminal; concise: one line each); with json they go into the result instead."""
        from layoutdsl.diagnostics import render

        items = list(diagnostics)
        self.collected.extend(items)
        if self.json or not items:
            return
        target = self.stdout if stream == "stdout" else self.stderr
        if self.format == "concise":
            target.write(render.render_concise(items))
        else:
            target.write(render.render_full(items, sources or {}, colour=use_colour(target)))
        target.flush()

    # -- the result
    @contextlib.contextmanager
    def timed(self, name: str) -> Iterator[None]:
        """Record how long a step took, as timings[`NAME_s`] (shown by -v and in JSON)."""
        started = time.monotonic()
        try:
            yield
        finally:
            self.timings[f"{name}_s"] = round(time.monotonic() - started, 3)
            self.detail(f"  {name}: {self.timings[f'{name}_s']:.2f} s")

    def wrote(self, *paths: str | Path) -> None:
        for path in paths:
            self.written.append(str(path))
            self.detail(f"wrote {path}")

    def reading(self, path: str) -> None:
        self.read.append(str(path))
        self.detail(f"reading {path}")

    def result(self, exit_code: int, **fields: Any) -> dict[str, Any]:
        """The JSON result object (without printing it)."""
        from layoutdsl.diagnostics.render import to_json_object
        from layoutdsl.diagnostics import Diagnostic

        self.timings["total_s"] = round(time.monotonic() - self.started, 3)
        ordered = sorted(self.collected, key=Diagnostic.sort_key)
        result: dict[str, Any] = {
            "command": self.command,
            "status": exitcodes.STATUS.get(exit_code, "error"),
            "exit_code": exit_code,
            "read": self.read,
            "written": self.written,
            "diagnostics": [to_json_object(d) for d in ordered],
            "errors": self.errors,
            "timings": self.timings,
        }
        result.update(fields)
        return result

    def finish(self, exit_code: int, **fields: Any) -> int:
        """End the command: with --format json print the result object; return exit_code."""
        if self.json:
            self.stdout.write(json.dumps(self.result(exit_code, **fields), indent=2, ensure_ascii=False,
                                         default=str) + "\n")
            self.stdout.flush()
        elif self.verbose:
            self.timings["total_s"] = round(time.monotonic() - self.started, 3)
            self.detail(f"done in {self.timings['total_s']:.2f} s (exit {exit_code})")
        return exit_code
