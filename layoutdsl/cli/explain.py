"""`layoutdsl explain CODE`: print a diagnostic code's page, as `ruff rule` does.

The pages are package data (`layoutdsl/diagnostics/pages/CODE.md`), the same Markdown the
docs site renders as its per-code reference, so the command works without the docs and the
two cannot disagree.
"""

from __future__ import annotations

import argparse
import difflib
import re
from importlib import resources

from layoutdsl.cli.output import Output, add_command, add_output_arguments
from layoutdsl.diagnostics import exitcodes

_CODE = re.compile(r"[EWI]\d{3}")  # I: info notes (layoutdsl.sizes.resolve)


def pages() -> dict[str, str]:
    """Every code's page: code -> Markdown text, in code order."""
    folder = resources.files("layoutdsl.diagnostics") / "pages"
    found = {}
    for entry in folder.iterdir():
        name = entry.name
        if name.endswith(".md") and _CODE.fullmatch(name[:-3]):
            found[name[:-3]] = entry.read_text(encoding="utf-8")
    return dict(sorted(found.items()))


def title(page: str) -> str:
    """`E201: minimum larger than maximum` -> `minimum larger than maximum`."""
    first = page.split("\n", 1)[0].lstrip("# ")
    return first.split(": ", 1)[1] if ": " in first else first


def severity(page: str) -> str:
    """The page's `Severity: error.` line."""
    found = re.search(r"^Severity: (\w+)\.", page, re.M)
    return found.group(1) if found else "error"


def suggestion(wrong: str, codes: list[str]) -> str | None:
    """The nearest existing code: letters typed for digits (`E2O1`), the other severity letter
    (`W102` for `E102`), then the closest by edit distance."""
    normal = wrong.strip().upper()
    normal = normal[:1] + normal[1:].translate(str.maketrans("OIL", "011"))
    for letter in "EWI":
        if len(normal) == 4 and letter + normal[1:] in codes:
            return letter + normal[1:]
    close = difflib.get_close_matches(normal, codes, n=1, cutoff=0.5)
    return close[0] if close else None


def add_parser(subparsers) -> argparse.ArgumentParser:
    """Register the `explain` subcommand."""
    parser = add_command(
        subparsers, "explain",
        help="print what a diagnostic code means and how to fix it",
        description="Print the documentation page of a diagnostic code (E201, W301, I441, ...): "
        "what it reports, why that is a problem, and an example; the same page the docs site "
        "shows. Without CODE, list every code with its severity and title.",
        examples=[("what E102 means", "layoutdsl explain E102"),
                  ("every code and its title", "layoutdsl explain"),
                  ("the page as a JSON object, for tools", "layoutdsl explain W906 --format json")],
    )  # fmt: skip
    parser.add_argument("code", nargs="?", metavar="CODE", help="a code such as E102 (case does not matter)")
    add_output_arguments(parser)
    parser.set_defaults(run=run)
    return parser


def run(args: argparse.Namespace) -> int:
    """Print one page (exit 0), the list of codes (exit 0), or a suggestion (exit 2)."""
    out = Output("explain", args)
    known = pages()
    if args.code is None:
        rows = [{"code": c, "severity": severity(p), "title": title(p)} for c, p in known.items()]
        if not out.json:
            out.product("".join(f"{r['code']}  {r['severity']:<7}  {r['title']}\n" for r in rows))
        return out.finish(exitcodes.OK, codes=rows)
    code = args.code.strip().upper()
    if code not in known:
        near = suggestion(code, list(known))
        hint = f"; did you mean `{near}`?" if near else "; `layoutdsl explain` lists every code"
        status = out.error(f"no diagnostic code `{args.code}`{hint}")
        return out.finish(status, code=args.code, suggestion=near)
    page = known[code]
    if not out.json:
        out.product(page if page.endswith("\n") else page + "\n")
    return out.finish(exitcodes.OK, code=code, severity=severity(page), title=title(page), page=page)
