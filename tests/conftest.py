"""Options shared by every test folder."""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import settings

# Property tests draw the same examples on every run (CI included): a failure is then the
# code's, reproducible from the test name alone, not a new draw's. A hypothesis run that
# explores afresh: pytest --hypothesis-profile=explore
settings.register_profile("deterministic", derandomize=True, database=None)
settings.register_profile("explore", derandomize=False)
settings.load_profile("deterministic")


def pytest_addoption(parser) -> None:
    parser.addoption(
        "--update-goldens",
        action="store_true",
        default=False,
        help="rewrite golden/snapshot files from the current output instead of comparing",
    )


@pytest.fixture
def golden(request):
    """golden(path, actual): `actual` must equal the golden file at `path`.

    Under `pytest --update-goldens` the file is (re)written instead. A missing golden file
    fails: a snapshot is only ever created on purpose.
    """
    update = request.config.getoption("--update-goldens")

    def compare(path: Path, actual: str) -> None:
        if update:
            path.write_text(actual, encoding="utf-8")
            return
        assert path.exists(), f"missing golden file {path}; run pytest --update-goldens to create it"
        assert actual == path.read_text(encoding="utf-8"), f"{path} differs (pytest --update-goldens accepts it)"

    return compare


SPECS_DIR = Path(__file__).resolve().parents[1] / "specs"
COMPILE_SECONDS = 8.0
"""Per spec. The construction gets half of it; its first layout takes 0.1-3 s on an idle
machine, so 8 s leaves room for a loaded CI box. The tests that use these layouts check the
outputs' correctness, not their quality, so the time-limited (non-deterministic) polish is
harmless."""


@pytest.fixture(scope="session")
def compiled_spec_layouts() -> dict[str, tuple]:
    """Every spec in specs/ compiled once per test run: stem -> (spec, verified Layout)."""
    from layoutdsl.api import load_spec
    from layoutdsl.compile import compile_spec
    from layoutdsl.compile.generator import generate
    from layoutdsl.solve import SolveOptions

    # the generator's numba kernels compile on first use, 8-9 s with an empty cache (a fresh
    # checkout running tests/compile alone): that would count against the first timed compile
    # that anneals, so the annealer runs once here without a deadline
    generate(load_spec(str(SPECS_DIR / "l_corridor.lay"))[0], seed=0)
    compiled = {}
    for path in sorted(SPECS_DIR.glob("*.lay")):
        spec, diagnostics = load_spec(str(path))
        assert spec is not None, [d.message for d in diagnostics]
        options = SolveOptions.from_settings(spec.settings, time_limit=COMPILE_SECONDS, quiet=True)
        result = compile_spec(spec, options)
        assert result.layout is not None, [d.message for d in result.diagnostics]
        compiled[path.stem] = (spec, result.layout)
    return compiled


def pytest_report_header(config) -> str:
    from real_plans import CORPUS, CORPUS_MISSING, corpus_plans

    found = corpus_plans()
    if found:
        return f"real plans: examples/floorplans and the {len(found)}-plan corpus at {CORPUS}"
    return f"real plans: examples/floorplans only; {CORPUS_MISSING}"
