"""MkDocs hook: the reference pages generated from the package at build time, so they cannot drift.

- `reference/cli.md`: every subcommand's `--help`, from the argparse parser `layoutdsl` runs;
- `reference/codes/CODE.md`: one page per diagnostic code, from `layoutdsl/diagnostics/pages/`
  (the pages `layoutdsl explain` prints), with the rendered snapshot from `tests/diagnostics/`
  when there is one, and `reference/codes/index.md` listing them;
- `reference/exit-codes.md`: `layoutdsl.diagnostics.exitcodes`, the module every command uses.
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path

from mkdocs.structure.files import File, Files

ROOT = Path(__file__).resolve().parents[2]
SNAPSHOTS = ROOT / "tests" / "diagnostics"
FAMILIES = (
    ("E0", "Syntax"), ("E1", "Names and references"), ("E2", "Geometry"), ("W3", "Spec warnings"),
    ("E4", "Import (building XML, room graphs) and size model: errors"), ("W4", "Building XML import: warnings"),
    ("E9", "Solving: errors"), ("W9", "Solving: warnings"),
    ("I4", "Notes: sizes and boundary the tool chose"),
)  # fmt: skip


def cli_page() -> str:
    """Every subcommand's help text, as argparse prints it at a fixed 88-column width."""
    os.environ["COLUMNS"] = "88"  # argparse wraps to the terminal; the page must not depend on it
    from layoutdsl.cli import build_parser

    parser = build_parser(None)
    subparsers = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    parts = [
        "# Command line",
        "",
        "Generated from the argparse parsers of `layoutdsl` when this site is built, so every flag",
        "below is one the installed command accepts. `layoutdsl COMMAND --help` prints the same.",
        "",
        "```text",
        parser.format_help().rstrip(),
        "```",
    ]
    for name, sub in subparsers.choices.items():
        parts += ["", f"## `layoutdsl {name}`", "", "```text", sub.format_help().rstrip(), "```"]
        parts += nested_help(sub, f"layoutdsl {name}")
    return "\n".join(parts) + "\n"


def nested_help(parser: argparse.ArgumentParser, prefix: str) -> list[str]:
    """Sections for a command's own subcommands (`layoutdsl X Y`), should one grow them."""
    parts: list[str] = []
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for name, sub in action.choices.items():
                parts += ["", f"### `{prefix} {name}`", "", "```text", sub.format_help().rstrip(), "```"]
                parts += nested_help(sub, f"{prefix} {name}")
    return parts


INPUT_SUFFIXES = (".lay", ".xml", ".csv", ".json", ".graphml")
"""What a snapshot's input can be: a spec, a building XML plan or a room graph."""
LANGUAGES = {".xml": "xml", ".json": "json", ".graphml": "xml"}


def snapshot(code: str) -> str | None:
    """The first golden rendering of `code` under tests/diagnostics/ (any folder), with the
    input it comes from, as the test suite checks it."""
    for rendered in sorted(SNAPSHOTS.rglob(f"{code}_*.txt")):
        inputs = [rendered.with_suffix(suffix) for suffix in INPUT_SUFFIXES]
        source = next((path for path in inputs if path.is_file()), None)
        if source is None:
            continue
        text = source.read_text(encoding="utf-8", errors="replace").rstrip()
        if len(text.splitlines()) > 60:
            continue  # a long input would bury the page; the snapshot's own file has it
        relative = rendered.relative_to(ROOT).as_posix()
        return (
            "## What it looks like\n\n"
            f"For the input `{source.name}`\n\n```{LANGUAGES.get(source.suffix, 'text')}\n{text}\n```\n\n"
            f"layoutdsl prints (the test suite's snapshot `{relative}`)\n\n"
            f"```text\n{rendered.read_text(encoding='utf-8').rstrip()}\n```\n"
        )
    return None


def code_pages() -> dict[str, str]:
    """reference/codes/*.md: the package's pages, each with its snapshot, and an index."""
    from layoutdsl.cli.explain import pages, severity, title

    found = pages()
    out: dict[str, str] = {}
    index = [
        "# Diagnostic codes",
        "",
        "Every code layoutdsl can report, one page each (as ruff has per rule). A code is never",
        "reused. `layoutdsl explain CODE` prints the same page in a terminal.",
    ]
    named = {prefix for prefix, _ in FAMILIES}
    for prefix, heading in FAMILIES + (("", "Other codes"),):
        if prefix:
            codes = [code for code in found if code.startswith(prefix)]
        else:  # a family added to the code base before it is named above is still listed
            codes = [code for code in found if code[:2] not in named]
        if not codes:
            continue
        title_line = f"## {heading} ({prefix}xx)" if prefix else f"## {heading}"
        index += ["", title_line, "", "| code | severity | title |", "|---|---|---|"]
        index += [f"| [{c}]({c}.md) | {severity(found[c])} | {title(found[c])} |" for c in codes]
    for code, page in found.items():
        extra = snapshot(code)
        out[f"reference/codes/{code}.md"] = page.rstrip() + "\n" + (f"\n{extra}" if extra else "")
    out["reference/codes/index.md"] = "\n".join(index) + "\n"
    return out


def exit_codes_page() -> str:
    from layoutdsl.diagnostics import exitcodes

    lines = [
        "# Exit codes",
        "",
        "Generated from `layoutdsl/diagnostics/exitcodes.py`, the one module every command takes",
        "its exit codes from. A script can rely on them; with `--format json` the result's",
        "`status` word says the same.",
        "",
        "| code | status | meaning |",
        "|---|---|---|",
    ]
    status = getattr(exitcodes, "STATUS", {})
    lines += [f"| {c} | `{status.get(c, '')}` | {m} |" for c, m in exitcodes.MEANINGS.items()]
    by_command = getattr(exitcodes, "BY_COMMAND", {})
    if by_command:
        notes = getattr(exitcodes, "COMMAND_NOTES", {})
        lines += ["", "## By command", "", "| command | can return | where the meaning is narrower |", "|---|---|---|"]
        for command, codes in by_command.items():
            narrower = "; ".join(f"{c}: {t}" for c, t in notes.get(command, {}).items())
            lines.append(f"| `{command}` | {', '.join(map(str, codes))} | {narrower} |")
    return "\n".join(lines) + "\n"


def on_files(files: Files, config) -> Files:
    generated = {"reference/cli.md": cli_page(), "reference/exit-codes.md": exit_codes_page(), **code_pages()}
    for uri, content in generated.items():
        files.append(File.generated(config, uri, content=content))
    return files
