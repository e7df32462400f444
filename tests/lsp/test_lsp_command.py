"""`layoutdsl lsp` as a command: its exit codes, and what it says without pygls."""

from __future__ import annotations

import json
import subprocess
import sys

BLOCK_PYGLS = """
import sys
from importlib.abc import MetaPathFinder

class NoPygls(MetaPathFinder):
    def find_spec(self, name, path=None, target=None):
        if name == "pygls" or name.startswith("pygls."):
            raise ModuleNotFoundError(f"No module named {name!r}", name=name)
        return None

sys.meta_path.insert(0, NoPygls())
from layoutdsl.cli import main
sys.exit(main(sys.argv[1:]))
"""


def test_without_pygls_it_says_which_extra_to_install() -> None:
    result = subprocess.run([sys.executable, "-c", BLOCK_PYGLS, "lsp"], capture_output=True, text=True,
                            stdin=subprocess.DEVNULL, timeout=60)  # fmt: skip
    assert result.returncode == 2
    assert "pip install 'layoutdsl[lsp]'" in result.stderr and "pygls" in result.stderr
    assert "Traceback" not in result.stderr


def test_it_serves_until_standard_input_ends_and_reports_in_json() -> None:
    result = subprocess.run([sys.executable, "-m", "layoutdsl", "lsp", "--stdio", "--format", "json"],
                            capture_output=True, text=True, stdin=subprocess.DEVNULL, timeout=60)  # fmt: skip
    assert result.returncode == 0, result.stderr
    report = json.loads(result.stdout)
    assert (report["command"], report["status"], report["exit_code"]) == ("lsp", "ok", 0)
