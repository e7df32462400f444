"""Test modules in folders without __init__.py are imported by their file name alone
(pytest's default rootdir import mode), so two with one name stop the whole suite from
being collected ("import file mismatch"). Found once the suite grew per-feature folders."""

from pathlib import Path

TESTS = Path(__file__).resolve().parents[1]


def test_test_module_names_are_unique_outside_packages():
    seen: dict[str, Path] = {}
    clashes = []
    for path in sorted(TESTS.rglob("test_*.py")):
        if (path.parent / "__init__.py").exists():
            continue  # imported under its package's name
        if path.name in seen:
            clashes.append(f"{seen[path.name].relative_to(TESTS)} and {path.relative_to(TESTS)}")
        seen.setdefault(path.name, path)
    assert not clashes, "test modules sharing a name: " + "; ".join(clashes)
