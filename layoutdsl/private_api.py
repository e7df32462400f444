"""Every use of a dependency's private API, in one place.

layoutdsl needs a few things its dependencies do not publish. Each is wrapped here, named
for what it does, with the versions it was written against; no other module reaches into
a dependency's internals. When a release moves one of them, the wrapper raises
`PrivateApiMoved` naming the attribute and the versions that work, instead of an
AttributeError deep in a solve, and `tests/test_private_api.py` fails the same way before
any user meets it.

- Pyomo (pyomo>=6.10.1,<6.11), `pyomo.contrib.solver`'s `ScipDirect`: the translation to a
  PySCIPOpt model without solving it (`_create_solver_model`), the map from Pyomo variables
  to SCIP variables (`_pyomo_var_to_solver_var_map`) and the variable Pyomo moves the
  objective into (`_obj_var`). The public `solve()` would run SCIP itself, without our
  event handler, emphasis settings and complete warm start.
- Lark (lark>=1.3,<2): `lark.utils.TextSlice`, the text a custom lexer is handed since
  lark 1.3, and the parser's lexer object (`Lark.parser.lexer`), to tokenise a line alone
  when naming a syntax error.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from lark.utils import TextSlice

PYOMO_VERSIONS = "pyomo>=6.10.1,<6.11"
LARK_VERSIONS = "lark>=1.3,<2"


class PrivateApiMoved(RuntimeError):
    """A dependency release moved an internal layoutdsl relies on."""

    def __init__(self, package: str, what: str, versions: str) -> None:
        installed = _installed_version(package)
        super().__init__(
            f"{package} {installed} has no {what}, which layoutdsl uses (see layoutdsl/private_api.py); "
            f"install {versions}, the versions it was written against"
        )


def _installed_version(package: str) -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version(package)
    except PackageNotFoundError:
        return "(not installed)"


def _attribute(obj: Any, name: str, package: str, owner: str, versions: str) -> Any:
    try:
        return getattr(obj, name)
    except AttributeError:
        raise PrivateApiMoved(package, f"`{owner}.{name}`", versions) from None


# ===== Pyomo: pyomo.contrib.solver's ScipDirect =====


def scip_model_of(interface: Any, model: Any, config: Any) -> tuple[Any, Any]:
    """(PySCIPOpt model, solution loader): Pyomo's translation of `model`, not yet solved."""
    create = _attribute(interface, "_create_solver_model", "pyomo", "ScipDirect", PYOMO_VERSIONS)
    scip_model, loader, _ = create(model, config)
    return scip_model, loader


def scip_variables(interface: Any) -> Mapping[Any, Any]:
    """Pyomo variable -> SCIP variable, for a model `scip_model_of` translated."""
    return _attribute(interface, "_pyomo_var_to_solver_var_map", "pyomo", "ScipDirect", PYOMO_VERSIONS)


def scip_objective_variable(interface: Any) -> Any | None:
    """The SCIP variable t >= objective Pyomo adds for a nonlinear objective (None if none)."""
    return _attribute(interface, "_obj_var", "pyomo", "ScipDirect", PYOMO_VERSIONS)


# ===== Lark =====


def lexer_text(text: Any) -> str:
    """The text a custom lexer's lex() is handed: a TextSlice since lark 1.3, else a str."""
    if isinstance(text, TextSlice):
        return text.text[text.start : text.end]
    return text


def parser_lexer(parser: Any) -> Any:
    """The lexer instance a Lark parser built (for tokenising one line alone)."""
    frontend = _attribute(parser, "parser", "lark", "Lark", LARK_VERSIONS)
    return _attribute(frontend, "lexer", "lark", "Lark.parser", LARK_VERSIONS)
