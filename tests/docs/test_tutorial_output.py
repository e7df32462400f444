"""The output the tutorial shows is what layoutdsl prints today (the rest of its commands run in
test_shell_examples.py; this checks the one `console` block, so it cannot go stale either)."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
TUTORIAL = ROOT / "docs" / "tutorial.md"


def test_the_typo_output_is_what_lint_prints(tmp_path: Path) -> None:
    text = TUTORIAL.read_text(encoding="utf-8")
    blocks = re.findall(r"^```(sh|console)\n(.*?)^```", text, re.M | re.S)
    write_spec = next(body for tag, body in blocks if tag == "sh" and "cat > clinic.lay" in body)
    make_typo = next(body for tag, body in blocks if tag == "sh" and "typo.lay" in body)
    shown = next(body for tag, body in blocks if tag == "console")
    env = {**os.environ, "PATH": str(Path(sys.executable).parent) + os.pathsep + os.environ["PATH"],
           "NO_COLOR": "1"}  # fmt: skip
    subprocess.run(["bash", "-euo", "pipefail", "-c", write_spec], cwd=tmp_path, env=env, check=True)
    subprocess.run(["bash", "-euo", "pipefail", "-c", make_typo], cwd=tmp_path, env=env, check=True,
                   capture_output=True)  # fmt: skip
    lint = subprocess.run([sys.executable, "-m", "layoutdsl", "lint", "typo.lay"], cwd=tmp_path, env=env,
                          capture_output=True, text=True)  # fmt: skip
    assert lint.returncode == 1
    assert (lint.stdout + lint.stderr).strip() == shown.strip()
