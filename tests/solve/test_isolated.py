"""solve/isolated.py: the long search in a child process survives a native crash of SCIP."""

from __future__ import annotations

import faulthandler
import os

import pyomo.environ as pyo
import pytest

from layoutdsl.compile import compile_spec
from layoutdsl.layout.verify import verify
from layoutdsl.model import build_model
from layoutdsl.solve import SolveOptions, solve
from layoutdsl.solve import isolated
from layoutdsl.solve.isolated import SOLVER_CRASHED, can_isolate, solve_isolated

from planted import planted

pytestmark = pytest.mark.skipif(not can_isolate(), reason="no fork here, or other threads run")

OPTIONS = SolveOptions(time_limit=20, node_limit=200, quiet=True)


def _abort(*args, **kwargs):
    """What a native SCIP abort does to the child (without the test runner's traceback dump)."""
    faulthandler.disable()
    os.abort()


def _values(model) -> list:
    return [v.value for v in model.component_data_objects(pyo.Var, descend_into=True)]


def test_a_search_in_a_child_loads_what_the_same_search_in_process_finds():
    spec, _ = planted(2, 1)
    here, there = build_model(spec), build_model(spec)
    outcome_here = solve(here, OPTIONS)
    outcome_there = solve_isolated(there, OPTIONS)
    assert outcome_there.has_solution and outcome_there.status == outcome_here.status
    assert outcome_there.objective == pytest.approx(outcome_here.objective)
    # the child's solution is on the parent's model, variable for variable
    assert _values(there) == pytest.approx(_values(here))


def test_a_child_that_aborts_gives_a_crashed_outcome_and_leaves_the_model_as_it_was(monkeypatch):
    spec, _ = planted(2, 1)
    model = build_model(spec)
    before = _values(model)
    # the child dies as SCIP does when it aborts natively: SIGABRT, nothing sent back
    monkeypatch.setattr(isolated, "solve", _abort)
    outcome = solve_isolated(model, OPTIONS)
    assert outcome.status == SOLVER_CRASHED and not outcome.has_solution
    assert _values(model) == before


def test_a_compile_whose_search_aborts_writes_its_verified_start_and_says_so(monkeypatch):
    spec, _ = planted(3, 1)
    monkeypatch.setattr(isolated, "solve", _abort)
    result = compile_spec(spec, SolveOptions(time_limit=20, quiet=True))
    assert result.layout is not None and verify(spec, result.layout) == []
    assert result.layout.solve.status == SOLVER_CRASHED
