"""The pygls language server: `layoutdsl.lsp.features` spoken over the protocol.

Linting is debounced: every edit restarts a short timer (DEBOUNCE_SECONDS), and the text is
linted once the user pauses, in a worker thread so hover and completion stay answered
meanwhile. A result is published only if the document has not changed since, so a slow
lint of an old text never overwrites a newer one. Opening or saving a file lints at once.
"""

from __future__ import annotations

import asyncio
import logging
from dataclasses import dataclass
from urllib.parse import unquote, urlparse

from lsprotocol import types as lsp
from pygls.exceptions import JsonRpcInvalidParams
from pygls.lsp.server import LanguageServer

from layoutdsl import __version__
from layoutdsl.lsp import features
from layoutdsl.lsp.document import SpecDocument, split_lines
from layoutdsl.syntax.ast import Spec
from layoutdsl.syntax import parser

DEBOUNCE_SECONDS = 0.2
"""Pause after the last keystroke before linting: long enough to skip the intermediate
texts of a burst of typing, short enough to feel immediate (editors use 0.1-0.5 s)."""

SOURCE = "layoutdsl"

log = logging.getLogger(__name__)

_COMPLETION_KINDS = {
    "section": lsp.CompletionItemKind.Module,
    "room": lsp.CompletionItemKind.Variable,
    "label": lsp.CompletionItemKind.Text,
    "setting": lsp.CompletionItemKind.Property,
    "value": lsp.CompletionItemKind.EnumMember,
    "flag": lsp.CompletionItemKind.Keyword,
}


_SEVERITIES = {
    "error": lsp.DiagnosticSeverity.Error,
    "warning": lsp.DiagnosticSeverity.Warning,
    "info": lsp.DiagnosticSeverity.Information,  # what the tool decided (sizes, boundary): not a problem
}


@dataclass
class _OpenSpec:
    """What the server keeps per open document: its lint task and its latest index."""

    pending: asyncio.Task | None = None
    index: SpecDocument | None = None
    index_text: str | None = None
    spec: Spec | None = None
    """The last spec that parsed: the sizes the size model gave its sizeless rooms."""


class SpecLanguageServer(LanguageServer):
    """A LanguageServer that remembers, per document, its pending lint and lexical index."""

    def __init__(self) -> None:
        super().__init__("layoutdsl", __version__, text_document_sync_kind=lsp.TextDocumentSyncKind.Incremental)
        self.open_specs: dict[str, _OpenSpec] = {}

    def state(self, uri: str) -> _OpenSpec:
        return self.open_specs.setdefault(uri, _OpenSpec())

    def index(self, uri: str) -> tuple[SpecDocument, list[str]]:
        """The document's lexical index (rebuilt when its text changed) and its lines."""
        text = self.workspace.get_text_document(uri).source
        state = self.state(uri)
        if state.index is None or state.index_text is not text:
            state.index, state.index_text = SpecDocument(text), text
        return state.index, split_lines(text)

    # ------------------------------------------------------------ position encoding

    def _units(self, text: str) -> int:
        """How many of the client's position units `text` takes."""
        encoding = self.workspace.position_encoding or lsp.PositionEncodingKind.Utf16
        if encoding == lsp.PositionEncodingKind.Utf8:
            return len(text.encode("utf-8"))
        if encoding == lsp.PositionEncodingKind.Utf32:
            return len(text)
        return len(text.encode("utf-16-le")) // 2

    def to_client(self, lines: list[str], line: int, column: int) -> lsp.Position:
        text = lines[line] if 0 <= line < len(lines) else ""
        return lsp.Position(line, self._units(text[:column]))

    def from_client(self, lines: list[str], position: lsp.Position) -> tuple[int, int]:
        """(line, code-point column) of a client position."""
        text = lines[position.line] if 0 <= position.line < len(lines) else ""
        units = 0
        for column, char in enumerate(text):
            if units >= position.character:
                return position.line, column
            units += self._units(char)
        return position.line, len(text)

    def range_to_client(self, lines: list[str], rng: features.Range) -> lsp.Range:
        return lsp.Range(self.to_client(lines, rng.start_line, rng.start_col), self.to_client(lines, rng.end_line, rng.end_col))

    # ------------------------------------------------------------ diagnostics

    def schedule_lint(self, uri: str, delay: float) -> None:
        """(Re)start the document's lint timer; the previous pending lint is dropped."""
        state = self.state(uri)
        if state.pending is not None:
            state.pending.cancel()
        state.pending = asyncio.get_running_loop().create_task(self._lint_later(uri, delay))

    async def _lint_later(self, uri: str, delay: float) -> None:
        if delay:
            await asyncio.sleep(delay)
        document = self.workspace.get_text_document(uri)
        text, version = document.source, document.version
        try:
            linted = await asyncio.to_thread(features.lint, text, _path_of(uri))
        except Exception as error:  # a bug in a check: say so in the editor's log, keep serving
            log.exception("linting %s failed", uri)
            self.window_log_message(lsp.LogMessageParams(
                lsp.MessageType.Error, f"layoutdsl: linting failed (a bug in layoutdsl): {type(error).__name__}: {error}"))
            return
        current = self.workspace.text_documents.get(uri)
        if current is None or current.version != version:
            return  # edited (or closed) while linting: the newer text's lint will publish
        state = self.state(uri)
        if linted.spec is not None:
            state.spec = linted.spec
        lines = split_lines(text)
        diagnostics = [self._lsp_diagnostic(lines, item) for item in linted.diagnostics]
        self.text_document_publish_diagnostics(lsp.PublishDiagnosticsParams(uri, diagnostics, version))
        # then index the text, so the next hover or completion need not wait for it
        index = await asyncio.to_thread(SpecDocument, text)
        if state.index_text is not text:
            state.index, state.index_text = index, text

    def _lsp_diagnostic(self, lines: list[str], item: features.EditorDiagnostic) -> lsp.Diagnostic:
        d = item.diagnostic
        return lsp.Diagnostic(
            range=self.range_to_client(lines, item.range),
            message=item.message,
            severity=_SEVERITIES.get(d.severity.value, lsp.DiagnosticSeverity.Warning),
            code=d.code,
            source=SOURCE,
            data=self._fix_data(lines, item.fix) if item.fix else None,
        )

    def _fix_data(self, lines: list[str], fix: features.Fix) -> dict:
        """The quick fix, carried in the diagnostic's `data` (clients send it back with the
        code-action request): its title, its text and the range it replaces, which is not
        always the diagnostic's own (a fix may remove the whole line)."""
        rng = self.range_to_client(lines, fix.range)
        return {"title": fix.title, "replacement": fix.new_text,
                "range": [rng.start.line, rng.start.character, rng.end.line, rng.end.character]}  # fmt: skip


def _path_of(uri: str) -> str:
    """The file path messages name (the URI's path for `file:` URIs)."""
    parsed = urlparse(uri)
    return unquote(parsed.path) if parsed.scheme == "file" else uri



def build_server() -> SpecLanguageServer:
    """A server with every feature registered."""
    # Every edit re-lints the whole text, of which it changes a line or two: reuse the
    # parsed lines (on a 2,000-room spec this takes a lint from 0.7 s to 0.1 s, bench/lsp.py).
    parser.keep_parsed_lines()
    ls = SpecLanguageServer()

    @ls.feature(lsp.TEXT_DOCUMENT_DID_OPEN)
    async def did_open(ls: SpecLanguageServer, params: lsp.DidOpenTextDocumentParams) -> None:
        ls.schedule_lint(params.text_document.uri, 0.0)

    @ls.feature(lsp.TEXT_DOCUMENT_DID_CHANGE)
    async def did_change(ls: SpecLanguageServer, params: lsp.DidChangeTextDocumentParams) -> None:
        ls.schedule_lint(params.text_document.uri, DEBOUNCE_SECONDS)

    @ls.feature(lsp.TEXT_DOCUMENT_DID_SAVE)
    async def did_save(ls: SpecLanguageServer, params: lsp.DidSaveTextDocumentParams) -> None:
        ls.schedule_lint(params.text_document.uri, 0.0)

    @ls.feature(lsp.TEXT_DOCUMENT_DID_CLOSE)
    async def did_close(ls: SpecLanguageServer, params: lsp.DidCloseTextDocumentParams) -> None:
        state = ls.open_specs.pop(params.text_document.uri, None)
        if state is not None and state.pending is not None:
            state.pending.cancel()
        ls.text_document_publish_diagnostics(lsp.PublishDiagnosticsParams(params.text_document.uri, []))

    @ls.feature(lsp.TEXT_DOCUMENT_HOVER)
    def hover(ls: SpecLanguageServer, params: lsp.HoverParams) -> lsp.Hover | None:
        index, lines = ls.index(params.text_document.uri)
        spec = ls.state(params.text_document.uri).spec
        found = features.hover(index, *ls.from_client(lines, params.position), spec)
        if found is None:
            return None
        markdown, rng = found
        return lsp.Hover(lsp.MarkupContent(lsp.MarkupKind.Markdown, markdown), ls.range_to_client(lines, rng))

    @ls.feature(lsp.TEXT_DOCUMENT_DEFINITION)
    def definition(ls: SpecLanguageServer, params: lsp.DefinitionParams) -> lsp.Location | None:
        index, lines = ls.index(params.text_document.uri)
        rng = features.definition(index, *ls.from_client(lines, params.position))
        if rng is None:
            return None
        return lsp.Location(params.text_document.uri, ls.range_to_client(lines, rng))

    @ls.feature(lsp.TEXT_DOCUMENT_REFERENCES)
    def references(ls: SpecLanguageServer, params: lsp.ReferenceParams) -> list[lsp.Location]:
        index, lines = ls.index(params.text_document.uri)
        found = features.references(index, *ls.from_client(lines, params.position), params.context.include_declaration)
        return [lsp.Location(params.text_document.uri, ls.range_to_client(lines, rng)) for rng in found]

    @ls.feature(lsp.TEXT_DOCUMENT_PREPARE_RENAME)
    def prepare_rename(ls: SpecLanguageServer, params: lsp.PrepareRenameParams) -> lsp.Range | None:
        index, lines = ls.index(params.text_document.uri)
        use = index.room_use_at(*ls.from_client(lines, params.position))
        return ls.range_to_client(lines, features.Range.of_word(use.word)) if use else None

    @ls.feature(lsp.TEXT_DOCUMENT_RENAME)
    def rename(ls: SpecLanguageServer, params: lsp.RenameParams) -> lsp.WorkspaceEdit:
        index, lines = ls.index(params.text_document.uri)
        try:
            found = features.rename(index, *ls.from_client(lines, params.position), params.new_name)
        except features.RenameError as error:
            raise JsonRpcInvalidParams(str(error)) from None
        edits = [lsp.TextEdit(ls.range_to_client(lines, rng), params.new_name) for rng in found]
        return lsp.WorkspaceEdit(changes={params.text_document.uri: edits})

    @ls.feature(lsp.TEXT_DOCUMENT_DOCUMENT_SYMBOL)
    def document_symbol(ls: SpecLanguageServer, params: lsp.DocumentSymbolParams) -> list[lsp.DocumentSymbol]:
        index, lines = ls.index(params.text_document.uri)

        def convert(symbol: features.Symbol) -> lsp.DocumentSymbol:
            rng = ls.range_to_client(lines, symbol.range)
            kind = lsp.SymbolKind.Namespace if symbol.kind == "section" else lsp.SymbolKind.Variable
            return lsp.DocumentSymbol(name=symbol.name, kind=kind, range=rng, selection_range=rng,
                                      detail=symbol.detail or None, children=[convert(c) for c in symbol.children])  # fmt: skip

        return [convert(symbol) for symbol in features.outline(index)]

    @ls.feature(lsp.TEXT_DOCUMENT_COMPLETION, lsp.CompletionOptions(trigger_characters=[" "]))
    def completion(ls: SpecLanguageServer, params: lsp.CompletionParams) -> lsp.CompletionList:
        index, lines = ls.index(params.text_document.uri)
        items = [
            lsp.CompletionItem(item.label, kind=_COMPLETION_KINDS[item.kind], detail=item.detail or None)
            for item in features.completions(index, *ls.from_client(lines, params.position))
        ]
        return lsp.CompletionList(is_incomplete=False, items=items)

    @ls.feature(lsp.TEXT_DOCUMENT_FORMATTING)
    def formatting(ls: SpecLanguageServer, params: lsp.DocumentFormattingParams) -> list[lsp.TextEdit] | None:
        document = ls.workspace.get_text_document(params.text_document.uri)
        text = document.source
        new_text = features.formatted(text, _path_of(params.text_document.uri))
        if new_text is None or new_text == text:
            return None  # errors (fmt formats only a spec that parses) or already canonical
        lines = split_lines(text)
        end = lsp.Position(len(lines) - 1, ls._units(lines[-1]))
        return [lsp.TextEdit(lsp.Range(lsp.Position(0, 0), end), new_text)]

    @ls.feature(
        lsp.TEXT_DOCUMENT_CODE_ACTION,
        lsp.CodeActionOptions(code_action_kinds=[lsp.CodeActionKind.QuickFix]),
    )
    def code_action(ls: SpecLanguageServer, params: lsp.CodeActionParams) -> list[lsp.CodeAction]:
        uri = params.text_document.uri
        actions = []
        for diagnostic in params.context.diagnostics:
            data = diagnostic.data if isinstance(diagnostic.data, dict) else None
            if diagnostic.source != SOURCE or not data or "replacement" not in data:
                continue
            where = data.get("range")
            rng = lsp.Range(lsp.Position(*where[:2]), lsp.Position(*where[2:])) if where else diagnostic.range
            edit = lsp.TextEdit(rng, data["replacement"])
            actions.append(lsp.CodeAction(
                title=data.get("title") or f"Replace with `{data['replacement']}`",
                kind=lsp.CodeActionKind.QuickFix,
                diagnostics=[diagnostic],
                edit=lsp.WorkspaceEdit(changes={uri: [edit]}),
                is_preferred=True,
            ))  # fmt: skip
        return actions

    return ls


def serve_stdio() -> None:
    """Run the server on standard input and output until the client says exit."""
    build_server().start_io()
