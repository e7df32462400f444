"""Benchmark: how soon `layoutdsl lsp` publishes diagnostics after an edit of a 2,000-room spec.

Issue 42 asks that diagnostics come back within 1 s of an edit on a 2,000-room spec. This
starts the real server (`python -m layoutdsl lsp`) over stdio with pygls' client, opens the
generated spec of bench/lint_bench.py (a grid of rooms on corridor spines: planar,
connected, many cycles), and times, from the moment the client sends the change to the
moment the diagnostics for that version arrive:

- open: the first diagnostics (no debounce); the first open builds the parser, later
  ones (after a close) find the lines parsed already;
- typo: an adjacency's room id misspelled (an E102 error, found by the checks);
- fix: the typo undone (a clean spec: every check runs);
- half line: a line cut halfway (a syntax error: the parser stops before the checks);
- insert: a room line added at the top of `rooms`, which moves every line below it (the
  worst case for the remembered lines, which are keyed by line number);
- burst: five keystrokes 50 ms apart, timed from the last one (what a typist sees).

Every figure includes the server's debounce (layoutdsl.lsp.server.DEBOUNCE_SECONDS), which
is waited on purpose. The lint-only row is `layoutdsl.lsp.features.lint` called in this
process without remembered lines (`parser.keep_parsed_lines`), as `layoutdsl lint` runs it. It also times hover, definition, references and completion on the
same document. Run: `.venv/bin/python bench/lsp.py [--rooms 2000] [--repeat 5] [--out FILE]`.
"""

from __future__ import annotations

import argparse
import asyncio
import os
import platform
import statistics
import sys
import time
from pathlib import Path

from lsprotocol import types as lsp
from pygls.lsp.client import LanguageClient

sys.path.insert(0, str(Path(__file__).resolve().parent))
from lint_bench import generate  # noqa: E402  (the same 2,000-room spec the lint bench uses)

from layoutdsl.lsp import features  # noqa: E402
from layoutdsl.lsp.server import DEBOUNCE_SECONDS  # noqa: E402

URI = "file:///bench/generated.lay"
TARGET_SECONDS = 1.0


class Timer:
    """Records when the diagnostics of each document version arrive."""

    def __init__(self) -> None:
        self.arrived: dict[int, tuple[float, int]] = {}
        self.event = asyncio.Event()

    def publish(self, params: lsp.PublishDiagnosticsParams) -> None:
        self.arrived[params.version] = (time.perf_counter(), len(params.diagnostics))
        self.event.set()

    async def wait(self, version: int, timeout: float = 30.0) -> tuple[float, int]:
        deadline = time.perf_counter() + timeout
        while version not in self.arrived:
            self.event.clear()
            await asyncio.wait_for(self.event.wait(), max(0.01, deadline - time.perf_counter()))
        return self.arrived[version]


def _whole(text: str) -> list[lsp.TextDocumentContentChangeWholeDocument]:
    return [lsp.TextDocumentContentChangeWholeDocument(text=text)]


def _edit(line: int, start: int, end: int, new: str) -> list[lsp.TextDocumentContentChangePartial]:
    rng = lsp.Range(lsp.Position(line, start), lsp.Position(line, end))
    return [lsp.TextDocumentContentChangePartial(range=rng, text=new)]


async def measure(rooms: int, repeat: int) -> tuple[dict[str, list[float]], dict[str, int], str]:
    text = generate(rooms)
    lines = text.split("\n")
    adjacency = next(i for i, line in enumerate(lines) if line.startswith("R0_5 C0"))
    last_room = max(i for i, line in enumerate(lines) if line.startswith("R") and " OFFICE " in line)
    client = LanguageClient("layoutdsl-bench", "1")
    timer = Timer()
    client.feature(lsp.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)(lambda params: timer.publish(params))
    await client.start_io(sys.executable, "-m", "layoutdsl", "lsp")
    await client.initialize_async(lsp.InitializeParams(capabilities=lsp.ClientCapabilities()))
    client.initialized(lsp.InitializedParams())
    times: dict[str, list[float]] = {}
    counts: dict[str, int] = {}
    version = 0

    async def change(name: str, edits) -> None:
        nonlocal version
        version += 1
        sent = time.perf_counter()
        client.text_document_did_change(lsp.DidChangeTextDocumentParams(
            lsp.VersionedTextDocumentIdentifier(uri=URI, version=version), edits))  # fmt: skip
        arrived, count = await timer.wait(version)
        times.setdefault(name, []).append(arrived - sent)
        counts[name] = count

    for round_ in range(repeat):
        version += 1
        sent = time.perf_counter()
        if round_:
            client.text_document_did_close(lsp.DidCloseTextDocumentParams(lsp.TextDocumentIdentifier(URI)))
        client.text_document_did_open(lsp.DidOpenTextDocumentParams(lsp.TextDocumentItem(URI, "lay", version, text)))
        name = "reopen (parsed lines kept)" if round_ else "first open (cold parser)"
        arrived, counts[name] = await timer.wait(version)
        times.setdefault(name, []).append(arrived - sent)
        await change("typo (E102)", _edit(adjacency, 0, 4, "R0_X"))
        await change("fix (clean spec)", _edit(adjacency, 0, 4, "R0_5"))
        # a new line near the top: every line below it moves, so none of them is remembered
        rooms_header = lines.index("rooms")
        await change("insert a line at the top", _edit(rooms_header + 1, 0, 0, "R_new 3 4.5 3.6 3 5 4 1 1.6 R NEW\n"))
        await change("restore", _whole(text))
        cut = len(lines[last_room]) // 2
        await change("half line (E005/E003)", _edit(last_room, cut, len(lines[last_room]), ""))
        await change("restore", _whole(text))
        # a burst of keystrokes: only the last one's text is linted (the debounce restarts)
        for index in range(5):  # `x` typed five times after an id: R0_5x ... R0_5xxxxx
            version += 1
            sent = time.perf_counter()
            client.text_document_did_change(lsp.DidChangeTextDocumentParams(
                lsp.VersionedTextDocumentIdentifier(uri=URI, version=version),
                _edit(adjacency, 4 + index, 4 + index, "x")))  # fmt: skip
            if index < 4:
                await asyncio.sleep(0.05)
        arrived, counts["burst (5 keys, 50 ms apart)"] = await timer.wait(version)
        times.setdefault("burst (5 keys, 50 ms apart)", []).append(arrived - sent)
        await change("restore", _whole(text))

    doc = lsp.TextDocumentIdentifier(URI)
    on_id = lsp.Position(adjacency, 1)
    for _ in range(repeat):
        for name, request in (
            ("hover", lambda: client.text_document_hover_async(lsp.HoverParams(doc, on_id))),
            ("definition", lambda: client.text_document_definition_async(lsp.DefinitionParams(doc, on_id))),
            ("references", lambda: client.text_document_references_async(lsp.ReferenceParams(
                context=lsp.ReferenceContext(include_declaration=True), text_document=doc,
                position=lsp.Position(adjacency, 6)))),
            ("completion", lambda: client.text_document_completion_async(
                lsp.CompletionParams(doc, lsp.Position(adjacency, 5)))),
            ("formatting", lambda: client.text_document_formatting_async(lsp.DocumentFormattingParams(
                doc, lsp.FormattingOptions(tab_size=4, insert_spaces=True)))),
        ):  # fmt: skip
            started = time.perf_counter()
            await request()
            times.setdefault(name, []).append(time.perf_counter() - started)
    await client.shutdown_async(None)
    client.exit(None)
    await client.stop()

    started_lint = []
    for _ in range(repeat):
        started = time.perf_counter()
        features.lint(text, "generated.lay")
        started_lint.append(time.perf_counter() - started)
    times["lint alone, no lines kept"] = started_lint
    times.pop("restore", None)
    about = f"{rooms} rooms, {len(lines)} lines, {len(text) // 1024} KiB"
    return times, counts, about


def table(times: dict[str, list[float]], counts: dict[str, int], about: str, repeat: int) -> str:
    out = [
        f"# bench/lsp.py: `layoutdsl lsp` over stdio, generated spec of bench/lint_bench.py ({about})",
        f"# {repeat} rounds; seconds from sending the change to receiving its diagnostics,",
        f"# debounce of {DEBOUNCE_SECONDS:g} s included; target {TARGET_SECONDS:g} s.",
        f"# python {platform.python_version()}, {os.cpu_count()} cores, load average "
        + " ".join(f"{x:.2f}" for x in os.getloadavg()),
        "",
        f"{'what':34} {'median s':>9} {'max s':>7} {'diagnostics':>11}",
    ]
    for name, values in times.items():
        count = counts.get(name)
        out.append(f"{name:34} {statistics.median(values):9.3f} {max(values):7.3f} "
                   f"{'' if count is None else count:>11}")  # fmt: skip
    # the target is about edits: opening a file is not one (the first open also builds the
    # parser and imports the checks)
    edits = [name for name in times if name not in ("hover", "definition", "references", "completion", "formatting",
                                                     "lint alone, no lines kept", "first open (cold parser)",
                                                     "reopen (parsed lines kept)")]  # fmt: skip
    worst = max(max(times[name]) for name in edits)
    verdict = "PASS" if worst <= TARGET_SECONDS else "FAIL"
    out += ["", f"{verdict}: slowest diagnostics after an edit {worst:.3f} s (target {TARGET_SECONDS:g} s)"]
    return "\n".join(out) + "\n"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rooms", type=int, default=2000)
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--out", type=Path, default=None, help="also write the table to this file")
    args = parser.parse_args()
    times, counts, about = asyncio.run(measure(args.rooms, args.repeat))
    text = table(times, counts, about, args.repeat)
    sys.stdout.write(text)
    if args.out:
        args.out.write_text(text, encoding="utf-8")


if __name__ == "__main__":
    main()
