"""The dependency internals layoutdsl uses (layoutdsl/private_api.py) are where it expects.

A failure here means a Pyomo or Lark release moved something: the message names it and the
versions layoutdsl was written against.
"""

from __future__ import annotations

import tomllib
from pathlib import Path

import pyomo.environ as pyo
import pytest
from pyomo.common.timing import HierarchicalTimer
from pyomo.contrib.solver.solvers.scip.scip_direct import ScipDirect

from layoutdsl import private_api
from layoutdsl.syntax.parser import get_parser

ROOT = Path(__file__).resolve().parents[1]


def _translated():
    model = pyo.ConcreteModel()
    model.x = pyo.Var(bounds=(0, 4))
    model.b = pyo.Var(domain=pyo.Binary)
    model.limit = pyo.Constraint(expr=model.x <= 3 + model.b)
    model.objective = pyo.Objective(expr=(model.x - 1) ** 2 + model.b)  # nonlinear: Pyomo adds t
    interface = ScipDirect()
    config = interface.config(value={}, preserve_implicit=True)
    config.timer = HierarchicalTimer()
    return model, interface, config


def test_pyomo_scip_direct_internals_are_where_layoutdsl_expects() -> None:
    model, interface, config = _translated()
    scip_model, _loader = private_api.scip_model_of(interface, model, config)
    variables = private_api.scip_variables(interface)
    assert sorted(v.name for v in variables) == ["b", "x"]
    assert {v.name for v in variables.values()} <= {v.name for v in scip_model.getVars()}
    objective = private_api.scip_objective_variable(interface)
    assert objective is not None and objective.name in {v.name for v in scip_model.getVars()}
    scip_model.freeProb()


def test_lark_internals_are_where_layoutdsl_expects() -> None:
    tokens = list(private_api.parser_lexer(get_parser()).tokens("R0 4 6"))
    assert [t.type for t in tokens] == ["NAME", "NUMBER", "NUMBER"]
    assert private_api.lexer_text(private_api.TextSlice("xx R0 4", 3, 7)) == "R0 4"
    assert private_api.lexer_text("R0 4") == "R0 4"


def test_a_moved_internal_names_itself_and_the_versions_that_work() -> None:
    class ReleaseWithoutIt:
        pass

    with pytest.raises(private_api.PrivateApiMoved) as caught:
        private_api.scip_objective_variable(ReleaseWithoutIt())
    message = str(caught.value)
    assert "`ScipDirect._obj_var`" in message
    assert private_api.PYOMO_VERSIONS in message
    assert "layoutdsl/private_api.py" in message


def test_the_version_pins_are_the_ones_the_adapter_was_written_against() -> None:
    dependencies = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["dependencies"]
    assert private_api.PYOMO_VERSIONS in dependencies
    assert private_api.LARK_VERSIONS in dependencies
