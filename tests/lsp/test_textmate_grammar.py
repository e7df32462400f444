"""The TextMate grammar (layoutdsl/editor/lay.tmLanguage.json), tokenized by vscode-textmate.

vscode-textmate with vscode-oniguruma is the engine VS Code highlights with, so the
snapshots show what an editor shows. Its two npm packages are pinned by
tests/lsp/textmate/package-lock.json and installed here (`npm ci`) the first time; the
snapshots are tests/lsp/textmate/snapshots/*.snap (`pytest --update-goldens` rewrites them).
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from layoutdsl.editor import GRAMMAR, LANGUAGE_CONFIGURATION, VSCODE_EXTENSION
from layoutdsl.syntax.ast import EMPHASES, ROOM_TYPES
from layoutdsl.syntax.parser import SECTIONS

HERE = Path(__file__).parent / "textmate"
ROOT = Path(__file__).resolve().parents[2]
SPECS = sorted((ROOT / "specs").glob("*.lay")) + [HERE / "edge_cases.lay"]


@pytest.fixture(scope="module")
def tokenized() -> dict[str, str]:
    """Snapshot text per spec file name, from one run of tokenize.js over all of them."""
    node, npm = shutil.which("node"), shutil.which("npm")
    if node is None or npm is None:
        pytest.skip("node and npm are needed to run vscode-textmate (Node 18 or later)")
    if not (HERE / "node_modules" / "vscode-textmate").is_dir():
        install = subprocess.run([npm, "ci", "--no-audit", "--no-fund", "--loglevel=error"], cwd=HERE,
                                 capture_output=True, text=True, timeout=600)  # fmt: skip
        if install.returncode != 0:
            message = f"npm ci in {HERE} failed:\n{install.stderr[-2000:]}"
            if os.environ.get("CI"):  # CI reaches the npm registry: a failure there is real
                pytest.fail(message)
            pytest.skip(message + "\n(offline? the grammar's snapshot test needs the npm registry once)")
    result = subprocess.run(
        [node, str(HERE / "tokenize.js"), str(GRAMMAR), *map(str, SPECS)],
        capture_output=True, text=True, check=True, timeout=120,
    )  # fmt: skip
    return {Path(path).name: text for path, text in json.loads(result.stdout).items()}


@pytest.mark.parametrize("spec", SPECS, ids=[s.name for s in SPECS])
def test_tokens_match_snapshot(spec: Path, tokenized: dict[str, str], golden) -> None:
    golden(HERE / "snapshots" / f"{spec.name}.snap", tokenized[spec.name])


def _tokens(snapshot: str) -> list[tuple[int, str, str]]:
    """(line, token text, scopes) of a snapshot."""
    out, line = [], 0
    for row in snapshot.splitlines():
        if match := re.match(r"(\d+)\| ", row):
            line = int(match.group(1))
        else:
            text, _, scopes = row.strip().rpartition('" ')
            out.append((line, json.loads(text + '"'), scopes))
    return out


def test_every_token_of_the_bundled_specs_is_highlighted_as_what_it_is(tokenized: dict[str, str]) -> None:
    # independent of the snapshots: every bundled spec is valid, so nothing is flagged, and
    # each value's kind is the one the parser gives it (ids, numbers, types, labels)
    from layoutdsl.api import load_spec

    for spec_path in SPECS[:-1]:
        tokens = _tokens(tokenized[spec_path.name])
        assert not [t for t in tokens if "invalid" in t[2]], spec_path.name
        spec, _ = load_spec(str(spec_path))
        lines = spec_path.read_text(encoding="utf-8").splitlines()
        for room in spec.rooms:
            line = room.span.line
            kinds = [(text, scopes) for number, text, scopes in tokens if number == line and "comment" not in scopes]
            assert kinds[0] == (room.id, "entity.name.type.room.lay"), lines[line - 1]
            if "rtype" in room.spans:  # a sizeless line may leave the type out
                assert (room.rtype, "storage.type.room-type.lay") in kinds
            label = [text for text, scopes in kinds if scopes == "string.unquoted.label.lay"]
            assert " ".join(label) == room.label
            assert ("onB", "constant.language.flag.on-boundary.lay") in kinds if room.on_boundary else True
        for adjacency in spec.adjacencies:
            refs = [t for n, t, s in tokens if n == adjacency.span.line and s == "variable.other.room.lay"]
            assert refs == [adjacency.a, adjacency.b]
        sections = [t for _, t, s in tokens if s == "keyword.control.section.lay"]
        opened = [line.strip() for line in lines if line.strip() in SECTIONS]
        assert sections == opened


def test_the_grammar_knows_the_languages_words() -> None:
    grammar = GRAMMAR.read_text(encoding="utf-8")
    rules = json.loads(grammar)["repository"]
    assert {name.removeprefix("section-") for name in rules if name.startswith("section-")} == set(SECTIONS)
    room_type = rules["section-rooms"]["patterns"][1]["patterns"][2]["begin"]
    assert room_type == r"(?<=\s)([" + "".join(ROOM_TYPES) + r"])(?=\s|$)"
    emphasis = next(p["match"] for p in rules["section-settings"]["patterns"][1]["patterns"] if "constant.language" in p.get("name", ""))
    assert all(value in emphasis for value in EMPHASES)
    assert json.loads(LANGUAGE_CONFIGURATION.read_text(encoding="utf-8"))["comments"]["lineComment"] == "#"


def test_the_folder_is_a_vs_code_extension_for_the_grammar_and_the_server() -> None:
    manifest = json.loads((VSCODE_EXTENSION / "package.json").read_text(encoding="utf-8"))
    (language,) = manifest["contributes"]["languages"]
    (grammar,) = manifest["contributes"]["grammars"]
    assert language["extensions"] == [".lay"] and grammar["language"] == language["id"] == "lay"
    assert grammar["scopeName"] == json.loads(GRAMMAR.read_text(encoding="utf-8"))["scopeName"] == "source.lay"
    for path in (grammar["path"], language["configuration"], manifest["main"]):
        assert (VSCODE_EXTENSION / path).is_file(), path
    assert manifest["activationEvents"] == ["onLanguage:lay"]
    assert manifest["contributes"]["configuration"]["properties"]["layoutdsl.command"]["default"] == ["layoutdsl", "lsp"]
    node = shutil.which("node")
    if node is not None:  # the script at least parses (it runs only inside VS Code)
        subprocess.run([node, "--check", str(VSCODE_EXTENSION / manifest["main"])], check=True, timeout=60)
