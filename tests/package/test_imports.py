"""The package's import graph: no cycles, no private names across modules.

Read from the source with :mod:`ast`, so imports inside functions (lazy imports)
count as much as the ones at the top of a module. Imports under
``if TYPE_CHECKING:`` are not edges: they never run, they only name a type for
the reader (a result module naming the film state that made it). A module is a file of
``bearingfe/`` (a package is its ``__init__.py``); ``from .x import name`` is an
edge to ``x`` (or to ``x.name`` when that is a module). Dunder names such as
``__version__`` are not private.
"""

from __future__ import annotations

import ast
from pathlib import Path

from tests.helpers import ROOT

PACKAGE = ROOT / "bearingfe"

def _modules() -> dict[str, Path]:
    out = {}
    for path in PACKAGE.rglob("*.py"):
        parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out[".".join(parts)] = path
    return out


def _imports(modules: dict[str, Path]):
    """Edges ``module -> imported module`` and the names each import takes, lazy imports included."""
    edges: dict[str, set[str]] = {m: set() for m in modules}
    names: list[tuple[str, str, str]] = []
    for module, path in modules.items():
        package = module if path.name == "__init__.py" else module.rpartition(".")[0]
        for node in _runtime_nodes(ast.parse(path.read_text(), str(path))):
            if isinstance(node, ast.ImportFrom):
                if node.level:
                    base = package.split(".")[: len(package.split(".")) - node.level + 1]
                    target = ".".join(base + ([node.module] if node.module else []))
                else:
                    target = node.module or ""
                if target not in modules:
                    continue
                for alias in node.names:
                    sub = f"{target}.{alias.name}"
                    edges[module].add(sub if sub in modules else target)
                    if sub not in modules:
                        names.append((module, target, alias.name))
            elif isinstance(node, ast.Import):
                edges[module].update(a.name for a in node.names if a.name in modules)
    return edges, names


def _type_checking(node: ast.AST) -> bool:
    test = node.test if isinstance(node, ast.If) else None
    return isinstance(test, ast.Name) and test.id == "TYPE_CHECKING" or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING")


def _runtime_nodes(tree: ast.AST):
    """Every node of ``tree`` except those under ``if TYPE_CHECKING:``."""
    stack = [tree]
    while stack:
        node = stack.pop()
        yield node
        stack.extend(child for child in ast.iter_child_nodes(node) if not _type_checking(child))


def _cycles(edges: dict[str, set[str]]) -> list[frozenset[str]]:
    """Strongly connected components with more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    out = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in edges[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = set()
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.add(w)
                if w == v:
                    break
            if len(component) > 1 or v in edges[v]:
                out.append(frozenset(component))

    for v in sorted(edges):
        if v not in index:
            visit(v)
    return out


def _private(name: str) -> bool:
    return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))


def test_no_private_name_is_imported_across_modules():
    modules = _modules()
    _, names = _imports(modules)
    private = {(m, t, n) for m, t, n in names if _private(n) and m != t}
    assert private == set(), "import the public name, or move the helper to the module that owns it"


def test_there_is_no_import_cycle():
    assert _cycles(_imports(_modules())[0]) == []


def test_the_checks_see_cycles_and_private_names():
    # the checks themselves on a small made-up graph: a -> b -> c -> a is one cycle, d is alone
    assert _cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [frozenset("abc")]
    assert _private("_flows") and not _private("__version__") and not _private("flows")
    # an import under `if TYPE_CHECKING:` is no edge, one beside it is
    tree = ast.parse("from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    import a\nimport b\n")
    assert [n.names[0].name for n in _runtime_nodes(tree) if isinstance(n, ast.Import)] == ["b"]
    # and on the package: the reynolds front door reaches the cavitation models, which must not import it back
    edges, _ = _imports(_modules())
    assert "bearingfe.cavitation" in edges["bearingfe.reynolds"]
    assert not any("bearingfe.reynolds" in targets for module, targets in edges.items()
                   if module.startswith("bearingfe.cavitation"))
