"""`layoutdsl lsp` end to end: a real LSP client (pytest-lsp) talks to the server over stdio.

One server process serves the whole module (starting Python and pygls is most of the cost);
each test opens its own document URI so the tests do not see each other's state.
"""

from __future__ import annotations

import asyncio
import re
import subprocess
import sys

import pytest
import pytest_lsp
from lsprotocol import types as lsp
from pytest_lsp import ClientServerConfig, LanguageClient, client_capabilities

pytestmark = pytest.mark.asyncio(loop_scope="module")

SPEC = """\
# a small clinic
rooms
hall 10 20 15 2 3 2.5 4 10 C HALL
kitchen 3 5 4 3 5 4 1 1.67 R KITCHEN
office 3 5 4 3 5 4 1 1.67 R OFFICE onB
door 2 4 3 2 4 3 1 2 E ENTRANCE onB

boundary
20 12

adjacencies
kitchen hall 0.9 e
office hall 0.9 e
door hall 1.2 i

settings
seed 3
"""
"""Room ids are words, so that a misspelling gets a did-you-mean suggestion today."""

WAIT = 10.0
"""Seconds to wait for a notification; generous for a loaded CI machine."""


@pytest_lsp.fixture(
    scope="module",
    config=ClientServerConfig(server_command=[sys.executable, "-m", "layoutdsl", "lsp"]),
)
async def client(lsp_client: LanguageClient):
    params = lsp.InitializeParams(capabilities=client_capabilities("visual-studio-code"))
    await lsp_client.initialize_session(params)
    yield
    await lsp_client.shutdown_session()


async def open_doc(client: LanguageClient, name: str, text: str) -> str:
    """Open a document and wait for its first diagnostics; returns its URI."""
    uri = f"file:///clinic/{name}.lay"
    client.diagnostics.pop(uri, None)
    client.text_document_did_open(lsp.DidOpenTextDocumentParams(lsp.TextDocumentItem(uri, "lay", 1, text)))
    await diagnostics_of(client, uri)
    return uri


async def diagnostics_of(client: LanguageClient, uri: str) -> list[lsp.Diagnostic]:
    """The next diagnostics published for `uri` (the caller pops the old ones first)."""
    async def published() -> list[lsp.Diagnostic]:
        while uri not in client.diagnostics:
            await client.wait_for_notification(lsp.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
        return list(client.diagnostics[uri])

    return await asyncio.wait_for(published(), WAIT)


def position_of(text: str, needle: str, occurrence: int = 0, offset: int = 0) -> lsp.Position:
    """The position of the `occurrence`-th `needle` in text (plus `offset` characters)."""
    index = -1
    for _ in range(occurrence + 1):
        index = text.index(needle, index + 1)
    line = text.count("\n", 0, index)
    column = index - (text.rfind("\n", 0, index) + 1)
    return lsp.Position(line, column + offset)


def doc(uri: str) -> lsp.TextDocumentIdentifier:
    return lsp.TextDocumentIdentifier(uri)


def apply_edits(text: str, edits: list[lsp.TextEdit]) -> str:
    """Apply text edits (ASCII text: columns are characters) from the last to the first."""
    lines = text.split("\n")
    offsets = [0]
    for line in lines:
        offsets.append(offsets[-1] + len(line) + 1)

    def offset(position: lsp.Position) -> int:
        return offsets[position.line] + position.character

    for edit in sorted(edits, key=lambda e: offset(e.range.start), reverse=True):
        text = text[: offset(edit.range.start)] + edit.new_text + text[offset(edit.range.end):]
    return text


# ----------------------------------------------------------------------------- diagnostics


async def test_a_clean_spec_has_no_diagnostics(client: LanguageClient) -> None:
    uri = await open_doc(client, "clean", SPEC)
    assert list(client.diagnostics[uri]) == []


async def test_diagnostics_are_lints_and_follow_edits(client: LanguageClient) -> None:
    text = SPEC.replace("office hall 0.9 e", "offce hall 0.9 e")
    uri = await open_doc(client, "typo", text)
    # (W301, "office is cut off", may follow until follow-on warnings are suppressed)
    (found,) = [d for d in client.diagnostics[uri] if d.severity == lsp.DiagnosticSeverity.Error]
    start = position_of(text, "offce hall")
    assert found.range == lsp.Range(start, lsp.Position(start.line, start.character + len("offce")))
    assert found.code == "E102" and found.severity == lsp.DiagnosticSeverity.Error
    assert found.source == "layoutdsl"
    assert "unknown room `offce`" in found.message and "did you mean `office`?" in found.message
    # the same diagnostic `layoutdsl lint` gives for the same text
    lint = subprocess.run(
        [sys.executable, "-m", "layoutdsl", "lint", "--format", "concise", "--stdin-filename", "typo.lay", "-"],
        input=text, capture_output=True, text=True, check=False,
    )  # fmt: skip
    assert f"typo.lay:{start.line + 1}:{start.character + 1}: E102" in lint.stdout + lint.stderr

    # an edit that fixes the typo clears it, once the debounce has passed
    client.diagnostics.pop(uri)
    client.text_document_did_change(lsp.DidChangeTextDocumentParams(
        lsp.VersionedTextDocumentIdentifier(uri=uri, version=2),
        [lsp.TextDocumentContentChangePartial(
            range=lsp.Range(start, lsp.Position(start.line, start.character + 5)), text="office")],
    ))  # fmt: skip
    assert await diagnostics_of(client, uri) == []


async def test_a_half_typed_line_is_a_located_syntax_error(client: LanguageClient) -> None:
    text = SPEC.replace("door hall 1.2 i", "door hall 1.2")
    uri = await open_doc(client, "halfway", text)
    (found,) = client.diagnostics[uri]
    assert found.code == "E003" and found.range.start.line == position_of(text, "door hall").line


# ----------------------------------------------------------------------------- navigation


async def test_hover_on_a_room_id_shows_its_sizes_type_label_and_adjacencies(client: LanguageClient) -> None:
    uri = await open_doc(client, "hover", SPEC)
    where = position_of(SPEC, "office hall", offset=2)  # on a reference, not the definition
    result = await client.text_document_hover_async(lsp.HoverParams(doc(uri), where))
    assert result is not None and result.contents.kind == lsp.MarkupKind.Markdown
    text = result.contents.value
    assert "**office**" in text and "room `OFFICE`" in text
    assert "| width (m) | 3 | 5 | 4 |" in text and "| height (m) | 3 | 5 | 4 |" in text
    assert "aspect ratio 1 to 1.67" in text and "`onB`" in text
    assert "- `hall` (door, 0.9 m)" in text
    start = position_of(SPEC, "office hall")
    assert result.range == lsp.Range(start, lsp.Position(start.line, start.character + 6))
    # a number is not a room id
    assert await client.text_document_hover_async(lsp.HoverParams(doc(uri), position_of(SPEC, "20 12"))) is None


async def test_definition_of_a_room_id_is_its_rooms_line(client: LanguageClient) -> None:
    uri = await open_doc(client, "definition", SPEC)
    result = await client.text_document_definition_async(
        lsp.DefinitionParams(doc(uri), position_of(SPEC, "kitchen hall", offset=3))
    )
    start = position_of(SPEC, "kitchen 3 5")
    assert result == lsp.Location(uri, lsp.Range(start, lsp.Position(start.line, start.character + 7)))


async def test_references_of_a_room_id(client: LanguageClient) -> None:
    uri = await open_doc(client, "references", SPEC)
    params = lsp.ReferenceParams(
        text_document=doc(uri), position=position_of(SPEC, "hall 10"),
        context=lsp.ReferenceContext(include_declaration=True),
    )  # fmt: skip
    result = await client.text_document_references_async(params)
    expected = [position_of(SPEC, "hall 10")] + [position_of(SPEC, "hall 0.9", n) for n in (0, 1)]
    expected.append(position_of(SPEC, "hall 1.2"))
    assert [loc.range.start for loc in result] == expected
    assert all(loc.range.end.character - loc.range.start.character == 4 for loc in result)
    # without the declaration: the three adjacencies
    params.context.include_declaration = False
    assert len(await client.text_document_references_async(params)) == 3


# ----------------------------------------------------------------------------- completion


async def _labels(client: LanguageClient, uri: str, position: lsp.Position) -> list[str]:
    result = await client.text_document_completion_async(lsp.CompletionParams(doc(uri), position))
    items = result.items if isinstance(result, lsp.CompletionList) else result
    return [item.label for item in items]


async def test_completion_of_room_ids_sections_settings_and_labels(client: LanguageClient) -> None:
    text = SPEC.replace("door hall 1.2 i\n", "door hall 1.2 i\nkitchen \n").replace("seed 3\n", "seed 3\n\n")
    uri = await open_doc(client, "complete", text)
    # the second id of an adjacency: every room but the first
    after_kitchen = position_of(text, "kitchen \n", offset=len("kitchen "))
    assert await _labels(client, uri, after_kitchen) == ["hall", "office", "door"]
    # a new line in settings: the sections not opened yet, then the keys not set yet
    blank = lsp.Position(position_of(text, "seed 3").line + 1, 0)
    offered = await _labels(client, uri, blank)
    assert {"arms", "positions", "connections", "clusters", "hints"} <= set(offered)
    assert "rooms" not in offered and "seed" not in offered
    assert {"walldim", "time_limit", "emphasis"} <= set(offered)
    # the value of `emphasis`
    text2 = SPEC.replace("seed 3", "emphasis ")
    uri2 = await open_doc(client, "complete2", text2)
    assert "feasibility" in await _labels(client, uri2, position_of(text2, "emphasis ", offset=9))
    # a label: the labels the file already uses
    text3 = SPEC.replace("door 2 4 3 2 4 3 1 2 E ENTRANCE onB", "door 2 4 3 2 4 3 1 2 E ")
    uri3 = await open_doc(client, "complete3", text3)
    labels = await _labels(client, uri3, position_of(text3, "1 2 E ", offset=6))
    assert labels[:3] == ["HALL", "KITCHEN", "OFFICE"]


# ----------------------------------------------------------------------------- formatting


async def test_formatting_gives_what_fmt_writes(client: LanguageClient) -> None:
    messy = SPEC.replace("kitchen hall 0.9 e", "kitchen    hall\t0.9 e   ").replace("20 12", "20.0 12")
    uri = await open_doc(client, "format", messy)
    edits = await client.text_document_formatting_async(
        lsp.DocumentFormattingParams(doc(uri), lsp.FormattingOptions(tab_size=4, insert_spaces=True))
    )
    fmt = subprocess.run(
        [sys.executable, "-m", "layoutdsl", "fmt", "-"], input=messy, capture_output=True, text=True, check=True
    )
    assert fmt.stdout != messy
    assert apply_edits(messy, edits) == fmt.stdout
    # an already formatted document needs no edit
    uri2 = await open_doc(client, "formatted", fmt.stdout)
    assert not await client.text_document_formatting_async(
        lsp.DocumentFormattingParams(doc(uri2), lsp.FormattingOptions(tab_size=4, insert_spaces=True))
    )


# ----------------------------------------------------------------------------- code actions


@pytest.mark.parametrize(
    ("typo", "fixed", "code"),
    [("offce hall 0.9 e", "office hall 0.9 e", "E102"), ("sede 3", "seed 3", "E010"), ("adjacency\n", "adjacencies\n", "E001")],
)  # fmt: skip
async def test_a_quick_fix_applies_the_suggestion(client: LanguageClient, typo: str, fixed: str, code: str) -> None:
    original = {"E102": "office hall 0.9 e", "E010": "seed 3", "E001": "adjacencies\n"}[code]
    text = SPEC.replace(original, typo)
    uri = await open_doc(client, f"fix-{code}", text)
    (found,) = [d for d in client.diagnostics[uri] if d.code == code]
    actions = await client.text_document_code_action_async(lsp.CodeActionParams(
        doc(uri), found.range, lsp.CodeActionContext(diagnostics=[found], only=[lsp.CodeActionKind.QuickFix]),
    ))  # fmt: skip
    (action,) = actions
    assert action.kind == lsp.CodeActionKind.QuickFix and list(action.diagnostics) == [found]
    assert SPEC.replace(original, fixed) == apply_edits(text, action.edit.changes[uri]) == SPEC
    # and the fixed text lints clean
    client.diagnostics.pop(uri)
    client.text_document_did_change(lsp.DidChangeTextDocumentParams(
        lsp.VersionedTextDocumentIdentifier(uri=uri, version=2), [lsp.TextDocumentContentChangeWholeDocument(text=SPEC)]
    ))  # fmt: skip
    assert await diagnostics_of(client, uri) == []


@pytest.mark.parametrize(
    ("original", "repeated", "code"),
    [("door hall 1.2 i\n", "door hall 1.2 i\nkitchen hall 0.9 e\n", "E111"), ("seed 3\n", "seed 3\nseed 4\n", "E014")],
)  # fmt: skip
async def test_a_quick_fix_removes_a_repeated_line(client: LanguageClient, original: str, repeated: str, code: str) -> None:
    text = SPEC.replace(original, repeated)
    uri = await open_doc(client, f"repeat-{code}", text)
    (found,) = [d for d in client.diagnostics[uri] if d.severity == lsp.DiagnosticSeverity.Error]
    assert found.code == code
    actions = await client.text_document_code_action_async(
        lsp.CodeActionParams(doc(uri), found.range, lsp.CodeActionContext(diagnostics=[found]))
    )
    (action,) = actions
    assert action.title.startswith(f"Remove line {found.range.start.line + 1}")
    assert apply_edits(text, action.edit.changes[uri]) == SPEC


async def test_no_quick_fix_without_a_suggestion(client: LanguageClient) -> None:
    text = SPEC.replace("office hall 0.9 e", "zzzzzzzz hall 0.9 e")
    uri = await open_doc(client, "nofix", text)
    (found,) = [d for d in client.diagnostics[uri] if d.code == "E102"]
    assert found.code == "E102"
    actions = await client.text_document_code_action_async(
        lsp.CodeActionParams(doc(uri), found.range, lsp.CodeActionContext(diagnostics=[found]))
    )
    assert not actions



async def test_columns_are_counted_in_the_clients_utf16_units(client: LanguageClient) -> None:
    # the label holds a character outside the BMP: two UTF-16 units, one code point
    text = SPEC.replace("R KITCHEN", "R CAFÉ 😀 covr=0.5")
    uri = await open_doc(client, "utf16", text)
    (found,) = [d for d in client.diagnostics[uri] if d.code == "E009"]
    index = text.index("covr=0.5")
    column = index - (text.rfind("\n", 0, index) + 1)
    assert found.range.start.character == column + 1  # the emoji counts twice
    assert found.range.end.character == column + 1 + len("covr=0.5")
    assert "did you mean `cover`?" in found.message
    actions = await client.text_document_code_action_async(
        lsp.CodeActionParams(doc(uri), found.range, lsp.CodeActionContext(diagnostics=[found]))
    )
    assert [action.edit.changes[uri][0].new_text for action in actions] == ["cover"]


async def test_navigation_works_while_the_spec_does_not_parse(client: LanguageClient) -> None:
    text = SPEC.replace("door hall 1.2 i", "door hall 1.")  # half typed: no spec from the parser
    uri = await open_doc(client, "broken", text)
    assert any(d.severity == lsp.DiagnosticSeverity.Error for d in client.diagnostics[uri])
    where = position_of(text, "kitchen hall")
    hover = await client.text_document_hover_async(lsp.HoverParams(doc(uri), where))
    assert hover is not None and "room `KITCHEN`" in hover.contents.value
    result = await client.text_document_definition_async(lsp.DefinitionParams(doc(uri), where))
    assert result.range.start == position_of(text, "kitchen 3 5")


async def test_a_sizeless_room_hovers_with_the_size_models_sizes(client: LanguageClient) -> None:
    # `id [rtype] label`: the size model gives the sizes; lint notes where they came from
    text = SPEC.replace("kitchen 3 5 4 3 5 4 1 1.67 R KITCHEN", "kitchen R KITCHEN")
    uri = await open_doc(client, "sizeless", text)
    infos = [d for d in client.diagnostics[uri] if d.severity == lsp.DiagnosticSeverity.Information]
    assert infos and not [d for d in client.diagnostics[uri] if d.severity == lsp.DiagnosticSeverity.Error]
    result = await client.text_document_hover_async(lsp.HoverParams(doc(uri), position_of(text, "kitchen hall")))
    hover = result.contents.value
    assert "**kitchen**: room `KITCHEN`" in hover and "sizes from the size model" in hover
    widths = re.search(r"\| width \(m\) \| ([\d.]+) \| ([\d.]+) \| ([\d.]+) \|", hover)
    low, high, target = map(float, widths.groups())
    assert 0 < low <= target <= high


async def test_rename_a_room_everywhere(client: LanguageClient) -> None:
    uri = await open_doc(client, "rename", SPEC)
    where = position_of(SPEC, "hall 1.2")
    ready = await client.text_document_prepare_rename_async(lsp.PrepareRenameParams(doc(uri), where))
    assert ready == lsp.Range(where, lsp.Position(where.line, where.character + 4))
    edit = await client.text_document_rename_async(lsp.RenameParams(doc(uri), where, "corridor"))
    renamed = apply_edits(SPEC, edit.changes[uri])
    assert renamed == re.sub(r"\bhall\b", "corridor", SPEC)  # the label HALL is not an id
    # a name that is taken, or not an id, is refused with the reason
    for taken, reason in (("kitchen", "already defined on line 4"), ("4.5", "not an id")):
        with pytest.raises(Exception, match=reason):
            await client.text_document_rename_async(lsp.RenameParams(doc(uri), where, taken))


async def test_the_outline_lists_sections_and_rooms(client: LanguageClient) -> None:
    uri = await open_doc(client, "outline", SPEC)
    symbols = await client.text_document_document_symbol_async(lsp.DocumentSymbolParams(doc(uri)))
    assert [s.name for s in symbols] == ["rooms", "boundary", "adjacencies", "settings"]
    rooms = symbols[0]
    assert [(c.name, c.detail) for c in rooms.children] == [
        ("hall", "C HALL"), ("kitchen", "R KITCHEN"), ("office", "R OFFICE"), ("door", "E ENTRANCE")]
    assert (rooms.range.start.line, rooms.range.end.line) == (1, 5)  # the header to the last room
    assert [c.range.start.line for c in rooms.children] == [2, 3, 4, 5]
