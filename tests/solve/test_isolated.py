"""solve/isolated.py: the long search in a child process survives a native crash of SCIP.

Each case runs in a fresh interpreter: forking needs a process without other threads, and
earlier tests in this one (the Dask cluster's) may leave some behind.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

pytestmark = pytest.mark.skipif(not hasattr(os, "fork"), reason="no fork on this platform")

TESTS = Path(__file__).resolve().parents[1]

PRELUDE = """
import faulthandler, json, os
import pyomo.environ as pyo
from layoutdsl.compile import compile_spec
from layoutdsl.layout.verify import verify
from layoutdsl.model import build_model
from layoutdsl.solve import SolveOptions, solve
from layoutdsl.solve import isolated
from layoutdsl.solve.isolated import can_isolate, solve_isolated
from planted import planted

OPTIONS = SolveOptions(time_limit=20, node_limit=200, quiet=True)

def values(model):
    return [v.value for v in model.component_data_objects(pyo.Var, descend_into=True)]

def abort(*args, **kwargs):
    # what a native SCIP abort does to the child: SIGABRT, nothing sent back
    faulthandler.disable()
    os.abort()

assert can_isolate()
"""


def run_case(body: str) -> dict:
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(TESTS), os.environ.get("PYTHONPATH", "")])}
    done = subprocess.run([sys.executable, "-c", PRELUDE + textwrap.dedent(body)], capture_output=True,
                          text=True, env=env, timeout=120)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout.strip().splitlines()[-1])


def test_a_search_in_a_child_loads_what_the_same_search_in_process_finds():
    result = run_case("""
        spec, _ = planted(2, 1)
        here, there = build_model(spec), build_model(spec)
        a, b = solve(here, OPTIONS), solve_isolated(there, OPTIONS)
        print(json.dumps({"status": [a.status, b.status], "objective": [a.objective, b.objective],
                          "has": b.has_solution, "values": [values(here), values(there)]}))
    """)
    assert result["has"] and result["status"][0] == result["status"][1]
    assert result["objective"][1] == pytest.approx(result["objective"][0])
    # the child's solution is on the parent's model, variable for variable
    assert result["values"][1] == pytest.approx(result["values"][0])


def test_a_child_that_aborts_gives_a_crashed_outcome_and_leaves_the_model_as_it_was():
    result = run_case("""
        spec, _ = planted(2, 1)
        model = build_model(spec)
        before = values(model)
        isolated.solve = abort
        outcome = solve_isolated(model, OPTIONS)
        print(json.dumps({"status": outcome.status, "has": outcome.has_solution,
                          "unchanged": values(model) == before, "detail": outcome.crash_detail}))
    """)
    assert result == {"status": "solver_crashed", "has": False, "unchanged": True, "detail": "killed by SIGABRT"}


def test_an_error_in_the_child_is_raised_in_the_parent_as_it_was():
    result = run_case("""
        def refuse(*args, **kwargs):
            raise ValueError("unknown emphasis 'fast'")
        isolated.solve = refuse
        try:
            solve_isolated(build_model(planted(2, 1)[0]), OPTIONS)
        except ValueError as error:
            print(json.dumps({"raised": type(error).__name__, "message": str(error)}))
    """)
    assert result == {"raised": "ValueError", "message": "unknown emphasis 'fast'"}


def test_a_compile_whose_search_aborts_writes_its_verified_start_and_says_so():
    result = run_case("""
        spec, _ = planted(3, 1)
        isolated.solve = abort
        result = compile_spec(spec, SolveOptions(time_limit=20, quiet=True))
        print(json.dumps({"verified": result.layout is not None and verify(spec, result.layout) == [],
                          "status": result.layout.solve.status if result.layout else None}))
    """)
    assert result == {"verified": True, "status": "solver_crashed"}


def test_a_child_that_hangs_is_killed_after_its_time_limit_and_reported_crashed():
    # what a glibc abort deadlocked between SCIP's thread and the progress ticker does
    result = run_case("""
        import time
        def hang(*args, **kwargs):
            time.sleep(600)
        isolated.solve = hang
        isolated.CHILD_GRACE_SECONDS = 0.5
        began = time.monotonic()
        outcome = solve_isolated(build_model(planted(2, 1)[0]), SolveOptions(time_limit=1, quiet=True))
        print(json.dumps({"status": outcome.status, "has": outcome.has_solution,
                          "seconds": time.monotonic() - began}))
    """)
    assert result["status"] == "solver_crashed" and not result["has"]
    assert result["seconds"] < 10


def test_a_slow_child_is_given_time_in_proportion_to_its_search_and_model():
    # a flat 5 s grace called children hung that were only slow on a loaded machine
    from layoutdsl.solve.isolated import CHILD_GRACE_SECONDS, child_grace

    assert child_grace(0.5, 100) == pytest.approx(CHILD_GRACE_SECONDS + 0.125 + 0.02)
    assert child_grace(40, 12_000) > child_grace(0.5, 12_000) > child_grace(0.5, 100) >= CHILD_GRACE_SECONDS
