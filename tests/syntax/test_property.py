"""Mutated specs never crash the front end: every input ends in a Spec or in diagnostics."""

from __future__ import annotations

from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from layoutdsl.sizes.resolve import resolve_spec
from layoutdsl.api import lint_source
from layoutdsl.diagnostics import Diagnostic
from layoutdsl.syntax.format import format_source, format_spec
from layoutdsl.syntax.parser import parse_source
from layoutdsl.diagnostics.render import render_concise, render_full, render_json
from layoutdsl.diagnostics.source import Source

ROOT = Path(__file__).resolve().parents[2]
SEEDS = [p.read_text(encoding="utf-8") for p in sorted((ROOT / "specs").glob("*.lay"))]
SEEDS.append(
    "rooms\nR0 4 6 5 3 5 4 1 2 R OFFICE onB cover=0.5\nR1 4 6 5 3 5 4 1 2 R A B\n\nboundary\n12 14\n"
    "O1 0 0 1 1\n\nadjacencies\nR0 R1 0.9 e\n\npositions\nR0 3 3\n\nconnections\nR1 5 5 6 6\n\n"
    "clusters\nK0\nR0 0 0\nR1 5 0\n\nhints\nR0 0 2 5 4\n\nsettings\nseed 3\nnode_limit none\n"
)
ODD_TOKENS = [
    "nan", "inf", "-inf", "1e999", "-1e999", "1e308", "0", "-0", "-1", "1e-320", "99999999999999999999",
    "x", "=", "cover=", "cover=nan", "error=1e999", "onB", "#", "# c", "rooms", "boundary", "clusters",
    "settings", "hints", "\t", "\r", "\x00", "\x0c", "\u00a0", "\u2028", "\ufeff", "é", "房间", "🙂",
    "R", "C", "E", "e", "i", "K0", "R0", "R0 R0 1 e", "\n", "\n\n",
]  # fmt: skip


def _mutate(text: str, data) -> str:
    lines = text.split("\n")
    for _ in range(data.draw(st.integers(1, 4), label="mutations")):
        kind = data.draw(st.sampled_from(
            ["del_line", "dup_line", "swap_lines", "del_token", "dup_token", "swap_tokens",
             "odd_token", "bytes", "huge"]), label="kind")  # fmt: skip
        if not lines:
            lines = [""]
        i = data.draw(st.integers(0, len(lines) - 1), label="line")
        if kind == "del_line":
            del lines[i]
        elif kind == "dup_line":
            lines.insert(i, lines[i])
        elif kind == "swap_lines":
            j = data.draw(st.integers(0, len(lines) - 1), label="other")
            lines[i], lines[j] = lines[j], lines[i]
        else:
            tokens = lines[i].split(" ")
            k = data.draw(st.integers(0, max(0, len(tokens) - 1)), label="token")
            if kind == "del_token" and tokens:
                del tokens[k]
            elif kind == "dup_token" and tokens:
                tokens.insert(k, tokens[k])
            elif kind == "swap_tokens" and len(tokens) > 1:
                m = data.draw(st.integers(0, len(tokens) - 1), label="other token")
                tokens[k], tokens[m] = tokens[m], tokens[k]
            elif kind == "odd_token":
                tokens.insert(k, data.draw(st.sampled_from(ODD_TOKENS), label="odd"))
            elif kind == "bytes":
                raw = data.draw(st.binary(max_size=8), label="bytes")
                tokens.insert(k, raw.decode("utf-8", errors="replace") + data.draw(st.text(max_size=4)))
            elif kind == "huge":
                tokens.insert(k, data.draw(st.sampled_from(["1e300", "1" * 400, "-" + "9" * 30, "0.000"]), label="n"))
            lines[i] = " ".join(tokens)
    return "\n".join(lines)


@settings(max_examples=2000, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])  # fmt: skip
@given(seed=st.sampled_from(range(len(SEEDS))), data=st.data())
def test_mutated_specs_end_in_a_spec_or_diagnostics(seed: int, data) -> None:
    text = _mutate(SEEDS[seed], data)
    source = Source("mutant.lay", text)
    spec, diagnostics = lint_source(source)
    assert all(isinstance(d, Diagnostic) for d in diagnostics)
    assert spec is not None or any(d.is_error for d in diagnostics)
    for d in diagnostics:
        assert d.span.line >= 1 and d.span.col >= 1 and d.code and d.message
    # every renderer copes with whatever was found
    render_full(diagnostics, {source.path: source})
    render_concise(diagnostics)
    render_json(diagnostics)
    if spec is not None and not any(d.is_error for d in diagnostics):
        again, problems = parse_source(Source(source.path, format_spec(spec)))
        # lint_source's spec is resolved (sizes and boundary the spec leaves to the tool);
        # the text keeps them left out, and resolving its parse gives them back
        again, _ = resolve_spec(again)
        assert problems == [] and again == spec
        assert format_source(source) is not None
