"""The package's import graph, and the check that it runs one way only.

    python -m layoutdsl.devtools.imports            # module -> modules, then the verdict
    python -m layoutdsl.devtools.imports --packages # the same, folded to packages

Every `import` counts, also the ones inside functions and under `TYPE_CHECKING`: a cycle
hidden in a function body is still a cycle a reader has to untangle. The graph is read from
the source text (nothing is imported), so it works on a broken tree too.

Exit status: 0 when there is no cycle and every edge between packages points down the
`LAYERS` order, 1 otherwise (each offending edge or cycle is printed).
"""

from __future__ import annotations

import argparse
import ast
import sys
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from pathlib import Path

ROOT_PACKAGE = "layoutdsl"

# Lowest first. A module may import from its own package or from any package listed before
# it, never from one after it (docs/architecture.md explains the order).
LAYERS: tuple[str, ...] = (
    "private_api",
    "diagnostics",
    "syntax",
    "check",
    "layout",
    "importer",
    "sizes",
    "sample",
    "model",
    "solve",
    "emit",
    "compile",
    "evaluate",
    "api",
    "lsp",
    "editor",
    "batch",
    "cli",
    "__main__",
    ROOT_PACKAGE,
    "devtools",
)


@dataclass(frozen=True, slots=True)
class Violation:
    """One thing that breaks the layering: an upward edge, or a cycle of modules."""

    kind: str  # "upward" or "cycle"
    modules: tuple[str, ...]

    def __str__(self) -> str:
        if self.kind == "upward":
            source, target = self.modules
            return f"upward import: {source} -> {target} ({layer_of(source)} is below {layer_of(target)})"
        return "cycle among: " + ", ".join(self.modules)


def package_dir() -> Path:
    """The folder of the layoutdsl package this module belongs to."""
    return Path(__file__).resolve().parents[1]


def module_names(root: Path) -> dict[str, Path]:
    """Dotted module name -> file, for every .py file of the package."""
    modules = {}
    for path in sorted(root.rglob("*.py")):
        parts = path.relative_to(root.parent).with_suffix("").parts
        if parts[-1] == "__init__":
            parts = parts[:-1]
        modules[".".join(parts)] = path
    return modules


def _imported_names(tree: ast.AST, module: str, is_package: bool) -> Iterator[str]:
    """Every dotted name the module imports (a module, or a module's attribute)."""
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            yield from (alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = module.split(".")
                anchor = anchor[: len(anchor) - node.level + (1 if is_package else 0)]
                base = ".".join([*anchor, base] if base else anchor)
            # `from a.b import c` depends on a.b.c if that is a module, else on a.b (resolved
            # by the caller, which strips names until one is a module).
            yield from (f"{base}.{alias.name}" for alias in node.names)


def import_graph(root: Path | None = None) -> dict[str, set[str]]:
    """Module -> the package's modules it imports (submodules resolved, self-edges dropped)."""
    root = root or package_dir()
    modules = module_names(root)
    graph: dict[str, set[str]] = {}
    for module, path in modules.items():
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        targets = set()
        for name in _imported_names(tree, module, path.name == "__init__.py"):
            # `from layoutdsl.emit import png` names a module; `from layoutdsl.layout import
            # Layout` names an attribute of the package module `layoutdsl.layout`.
            while name and name not in modules:
                name = name.rpartition(".")[0]
            if name and name != module and not (name == ROOT_PACKAGE and module != ROOT_PACKAGE):
                targets.add(name)
        graph[module] = targets
    return graph


def layer_of(module: str) -> str:
    """The layer a module belongs to: its first package below layoutdsl."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else ROOT_PACKAGE


def _rank(module: str) -> int:
    return _layer_rank(layer_of(module), module)


def _layer_rank(layer: str, module: str | None = None) -> int:
    if layer not in LAYERS:
        module = module or f"{ROOT_PACKAGE}.{layer}"
        raise SystemExit(f"{module}: package `{layer}` has no place in LAYERS; add it where it belongs")
    return LAYERS.index(layer)


def cycles(graph: dict[str, set[str]]) -> list[tuple[str, ...]]:
    """The strongly connected components with more than one module (Tarjan), sorted."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found = []

    def visit(node: str) -> None:
        index[node] = low[node] = len(index)
        stack.append(node)
        on_stack.add(node)
        for target in sorted(graph.get(node, ())):
            if target not in index:
                visit(target)
                low[node] = min(low[node], low[target])
            elif target in on_stack:
                low[node] = min(low[node], index[target])
        if low[node] == index[node]:
            component = []
            while True:
                member = stack.pop()
                on_stack.discard(member)
                component.append(member)
                if member == node:
                    break
            if len(component) > 1:
                found.append(tuple(sorted(component)))

    for node in sorted(graph):
        if node not in index:
            visit(node)
    return sorted(found)


def violations(graph: dict[str, set[str]]) -> list[Violation]:
    """Upward edges between packages, then cycles between modules."""
    upward = [
        Violation("upward", (source, target))
        for source in sorted(graph)
        for target in sorted(graph[source])
        if layer_of(source) != layer_of(target) and _rank(target) > _rank(source)
    ]
    return upward + [Violation("cycle", component) for component in cycles(graph)]


def fold_to_packages(graph: dict[str, set[str]]) -> dict[str, set[str]]:
    """The same graph between layers (packages) instead of modules."""
    folded: dict[str, set[str]] = {}
    for source, targets in graph.items():
        edges = folded.setdefault(layer_of(source), set())
        edges.update(layer_of(t) for t in targets if layer_of(t) != layer_of(source))
    return folded


def format_graph(graph: dict[str, set[str]], order: Iterable[str]) -> str:
    """One `module -> a, b` line per module, in the given order."""
    return "\n".join(f"{node} -> {', '.join(sorted(graph[node])) or '(nothing)'}" for node in order)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m layoutdsl.devtools.imports", description=__doc__.split("\n")[0])
    parser.add_argument("--packages", action="store_true", help="fold the graph to packages (layers)")
    args = parser.parse_args(argv)
    graph = import_graph()
    if args.packages:
        folded = fold_to_packages(graph)
        print(format_graph(folded, sorted(folded, key=_layer_rank)))
    else:
        print(format_graph(graph, sorted(graph, key=lambda m: (_rank(m), m))))
    problems = violations(graph)
    for problem in problems:
        print(problem, file=sys.stderr)
    print(
        f"{len(graph)} modules, {sum(map(len, graph.values()))} edges: "
        + ("no cycle, every edge points down the layers" if not problems else f"{len(problems)} problem(s)"),
        file=sys.stderr,
    )
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
