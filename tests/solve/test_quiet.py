"""solve.quiet: what C code writes to fds 1 and 2 around SCIP never reaches the terminal."""

from __future__ import annotations

import ctypes
import os
import subprocess
import sys
import threading
from pathlib import Path

from layoutdsl.model import build_model
from layoutdsl.solve import SolveOptions, solve
from layoutdsl.solve.quiet import native_output_silenced

from planted import planted

LIBC = ctypes.CDLL(None)


def _c_printf(text: str) -> None:
    """Write through C's buffered stdio, as SCIP and SoPlex do (no flush: the buffer is the trap)."""
    LIBC.printf(text.encode())


def test_c_writes_inside_are_discarded_and_python_prints_still_show(capfd):
    with native_output_silenced():
        os.write(1, b"raw fd 1 chatter\n")
        os.write(2, b"raw fd 2 chatter\n")
        _c_printf("buffered C chatter\n")
        print("our own line", file=sys.stderr)
        print("our own stdout line")
    os.write(2, b"after\n")
    out, err = capfd.readouterr()
    assert "chatter" not in out + err
    assert "our own line" in err and "our own stdout line" in out
    assert err.endswith("after\n")


def test_nested_and_threaded_silencing_restores_the_descriptors_once(capfd):
    before = (os.fstat(1).st_ino, os.fstat(2).st_ino)

    def worker():
        with native_output_silenced():
            os.write(2, b"thread chatter\n")

    with native_output_silenced():
        with native_output_silenced():
            thread = threading.Thread(target=worker)
            thread.start()
            thread.join()
        os.write(1, b"still silenced\n")
    assert (os.fstat(1).st_ino, os.fstat(2).st_ino) == before
    os.write(1, b"visible\n")
    out, err = capfd.readouterr()
    assert "chatter" not in err and "still silenced" not in out
    assert out == "visible\n"


def test_scip_messages_from_c_during_a_solve_do_not_reach_the_descriptors(capfd):
    spec, _ = planted(2, 1)
    model = build_model(spec)
    outcome = solve(model, SolveOptions(time_limit=20, quiet=True, node_limit=50))
    assert outcome.has_solution
    # SCIP itself printing an error message from C (wrong stage) while silenced
    from pyscipopt import Model

    scip = Model()
    with native_output_silenced():
        try:
            scip.getNLPIterations()
        except Exception:  # noqa: BLE001  (SCIP refuses in the problem stage, after printing)
            pass
    out, err = capfd.readouterr()
    assert out == "" and err == ""


def test_a_compile_prints_only_its_own_lines(tmp_path):
    """The CLI end to end, in a fresh process whose fds are real pipes: every line on stdout
    and stderr is one layoutdsl wrote (summary, progress), none from SCIP, SoPlex or Pyomo."""
    spec = Path(__file__).resolve().parents[2] / "specs" / "office_small.lay"
    run = subprocess.run(
        [sys.executable, "-m", "layoutdsl", "compile", str(spec), "-o", str(tmp_path / "out"),
         "--time-limit", "30", "--emit", "xml"],
        capture_output=True, text=True, timeout=120,
    )
    assert run.returncode == 0, run.stderr
    for line in (run.stdout + run.stderr).splitlines():
        assert "GMP" not in line and "feasibility tolerance" not in line, line
        assert not line.startswith("[") and "ERROR" not in line, line  # SCIP: "[file.c:12] ERROR: ..."
        assert line.startswith(("compil", "  ")), line  # ours: "compiling"/"compiled" and indented lines


def test_a_stream_kept_from_inside_the_silence_still_writes_afterwards(capfd):
    with native_output_silenced():
        kept = sys.stderr  # a logging handler made now would hold this object
    os.write(2, b"")  # the descriptor is back
    print("after the silence", file=kept)
    assert "after the silence" in capfd.readouterr().err


class _ChattyModel:
    """A SCIP model whose solve first writes from C to fds 1 and 2, as SoPlex's warnings do."""

    def __init__(self, model):
        self._model = model

    def optimizeNogil(self):  # noqa: N802  (pyscipopt's name)
        os.write(2, b"chatter from the LP solver\n")
        _c_printf("buffered chatter from the LP solver\n")
        return self._model.optimizeNogil()

    def __getattr__(self, name):
        return getattr(self._model, name)


def test_the_generator_called_directly_keeps_the_solver_off_the_terminal(capfd, monkeypatch):
    """A library user calling compile.generator.generate (no compile around it) sees none of
    what the sizing stage's SCIP writes from C."""
    from layoutdsl.compile.generator import generate
    from layoutdsl.solve import relations
    from tests.compile._specs import tree_spec

    real = relations._scip_model
    monkeypatch.setattr(relations, "_scip_model", lambda *args: _ChattyModel(real(*args)))
    generated = generate(tree_spec(), seed=0)
    assert generated.rects is not None
    out, err = capfd.readouterr()
    assert "chatter" not in out + err
