"""Process exit codes: the one place they are defined and explained.

Every command returns one of these; `BY_COMMAND` says which ones each command can return, so
its `--help` lists only those, and the docs' exit-code page renders this module.
"""

OK = 0
"""Success; warnings allowed."""
SPEC_ERRORS = 1
"""The input has errors (diagnostics printed), or `fmt --check` found a file to reformat."""
USAGE = 2
"""Usage, I/O or internal error: a bad flag, a file that cannot be read or written, a bug."""
NO_LAYOUT = 3
"""No layout: the spec is infeasible, the time limit passed with no layout, or a solved
layout failed independent verification (nothing is written)."""

MEANINGS: dict[int, str] = {
    OK: "OK (warnings allowed)",
    SPEC_ERRORS: "the input has errors (diagnostics printed)",
    USAGE: "usage, I/O or internal error (nothing was written)",
    NO_LAYOUT: "no layout: infeasible spec, time limit with no layout, or failed verification",
}
"""One line per code, as `--help` prints it."""

STATUS: dict[int, str] = {OK: "ok", SPEC_ERRORS: "errors", USAGE: "usage_or_io_error", NO_LAYOUT: "no_layout"}
"""The `status` word of a `--format json` result for each exit code."""

BY_COMMAND: dict[str, tuple[int, ...]] = {
    "compile": (OK, SPEC_ERRORS, USAGE, NO_LAYOUT),
    "lint": (OK, SPEC_ERRORS, USAGE),
    "fmt": (OK, SPEC_ERRORS, USAGE),
    "import": (OK, SPEC_ERRORS, USAGE),
    "evaluate": (OK, SPEC_ERRORS, USAGE),
    "batch": (OK, USAGE, NO_LAYOUT),
    "sample": (OK, SPEC_ERRORS, USAGE),
    "explain": (OK, USAGE),
    "sizes": (OK, USAGE),
    "lsp": (OK, USAGE),
}
"""The codes each command can return (its `--help` lists exactly these)."""

COMMAND_NOTES: dict[str, dict[int, str]] = {
    "fmt": {SPEC_ERRORS: "a spec has errors, or --check found a file to reformat"},
    "batch": {NO_LAYOUT: "at least one building failed, say a spec with errors (see the manifest)"},
    "evaluate": {SPEC_ERRORS: "a plan has errors (diagnostics printed)"},
}
"""Where a command gives a code a more precise meaning than MEANINGS."""


def epilog(codes: tuple[int, ...] | None = None, command: str | None = None) -> str:
    """The `exit codes:` block of a help text: only `codes` (all when None)."""
    notes = COMMAND_NOTES.get(command or "", {})
    chosen = tuple(MEANINGS) if codes is None else codes
    lines = ["exit codes:"]
    lines += [f"  {code}  {notes.get(code, MEANINGS[code])}" for code in chosen]
    return "\n".join(lines) + "\n"


EPILOG = epilog()
"""Every code, for `layoutdsl --help`."""
