"""The language server for `.lay` specs (`layoutdsl lsp`).

Two layers, so the editor features can be tested without an editor:

- `layoutdsl.lsp.document`: a lexical index of a spec's text (sections, words, where each
  room id is defined and used). It is built from the text alone, so hover, go to
  definition, references and completion keep working while a line is half typed and the
  spec does not parse.
- `layoutdsl.lsp.features`: what each request answers (diagnostics from the same parser and
  checks as `layoutdsl lint`, hover, completion, formatting through `fmt`, quick fixes),
  in code-point columns and 0-based lines, with no protocol I/O.
- `layoutdsl.lsp.server`: the pygls server that speaks the protocol over stdio, converts
  columns to the client's encoding and debounces linting while the user types.

pygls is an optional dependency (the `lsp` extra); only `server` imports it.
"""
