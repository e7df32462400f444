"""Editor support files shipped with the package (docs/editor.md says how to install them).

- `lay.tmLanguage.json`: a TextMate grammar for `.lay` specs (scope `source.lay`): section
  names, room ids where defined and where referenced, numbers, room types, labels, the `onB`
  flag, `cover=`/`error=` weights, portal types, obstacle and cluster ids, setting keys and
  values, comments, and values that cannot be right where they stand.
- `language-configuration.json`: what VS Code needs beside it (`#` line comments, words).
- `package.json` and `extension.js`: this folder is also a VS Code extension that declares the
  language and the grammar and starts `layoutdsl lsp` (copy it to `~/.vscode/extensions/`
  and run `npm install` there; docs/editor.md).

tests/lsp/test_textmate_grammar.py tokenizes the bundled specs with vscode-textmate, the engine VS Code
uses, and compares them with committed snapshots.
"""

from __future__ import annotations

from pathlib import Path

GRAMMAR = Path(__file__).with_name("lay.tmLanguage.json")
LANGUAGE_CONFIGURATION = Path(__file__).with_name("language-configuration.json")
VSCODE_EXTENSION = Path(__file__).parent
"""The folder to copy into VS Code's extensions folder."""
