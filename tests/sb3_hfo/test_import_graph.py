"""sb3_hfo's modules import one another without circles.

The graph is built with :mod:`ast` from every ``import`` statement in the package, those inside functions
included (an import inside a function still ties the two modules together; it only hides the circle from the
interpreter until the function runs). Imports under ``if TYPE_CHECKING:`` are left out: they never run. ``python tests/sb3_hfo/test_import_graph.py`` prints the circles.
"""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

PACKAGE = "sb3_hfo"
PACKAGE_DIR = Path(__file__).resolve().parents[2] / PACKAGE


def module_name(path: Path, root: Path) -> str:
    """``root/sb3_hfo/cli/train.py`` -> ``sb3_hfo.cli.train``; a package's ``__init__.py`` -> the package."""
    parts = list(path.relative_to(root).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _is_type_checking(node: ast.AST) -> bool:
    test = node.test if isinstance(node, ast.If) else None
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"
    )


def _runtime_nodes(tree: ast.AST) -> list[ast.AST]:
    """Every node of ``tree`` except the bodies of ``if TYPE_CHECKING:`` blocks (their ``else`` runs)."""
    nodes: list[ast.AST] = []
    pending = [tree]
    while pending:
        node = pending.pop()
        nodes.append(node)
        if _is_type_checking(node):
            pending.extend(node.orelse)  # type: ignore[attr-defined]
            continue
        pending.extend(ast.iter_child_nodes(node))
    return nodes


def imported_modules(tree: ast.AST, module: str, is_package: bool, known: set[str]) -> set[str]:
    """The modules of ``known`` that the statements of ``tree`` (module ``module``) import, anywhere in it.

    ``from pkg import name`` counts as importing ``pkg.name`` when that is a module, else ``pkg``.
    """
    found: set[str] = set()
    base_parts = module.split(".") if is_package else module.split(".")[:-1]
    for node in _runtime_nodes(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                found.add(alias.name)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                anchor = base_parts[: len(base_parts) - node.level + 1]
                source = ".".join([*anchor, node.module] if node.module else anchor)
            else:
                source = node.module or ""
            for alias in node.names:
                candidate = f"{source}.{alias.name}"
                found.add(candidate if candidate in known else source)
    edges: set[str] = set()
    for name in found:
        # `import sb3_hfo.cli.train` also runs sb3_hfo/__init__ and sb3_hfo/cli/__init__; the leaf is the edge
        # that matters, so take the longest known prefix.
        parts = name.split(".")
        for end in range(len(parts), 0, -1):
            prefix = ".".join(parts[:end])
            if prefix in known:
                if prefix != module:
                    edges.add(prefix)
                break
    return edges


def import_graph(root: Path = PACKAGE_DIR.parent) -> dict[str, set[str]]:
    """Module -> the package modules it imports (by any ``import`` statement in it)."""
    paths = sorted((root / PACKAGE).rglob("*.py"))
    known = {module_name(path, root) for path in paths}
    graph: dict[str, set[str]] = {}
    for path in paths:
        name = module_name(path, root)
        tree = ast.parse(path.read_text(), filename=str(path))
        graph[name] = imported_modules(tree, name, path.name == "__init__.py", known)
    return graph


def circles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components with more than one module (Tarjan's algorithm), each sorted."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    components: list[list[str]] = []

    def visit(node: str) -> None:
        index[node] = low[node] = len(index)
        stack.append(node)
        on_stack.add(node)
        for successor in sorted(graph.get(node, ())):
            if successor not in index:
                visit(successor)
                low[node] = min(low[node], low[successor])
            elif successor in on_stack:
                low[node] = min(low[node], index[successor])
        if low[node] == index[node]:
            component = []
            while True:
                member = stack.pop()
                on_stack.discard(member)
                component.append(member)
                if member == node:
                    break
            if len(component) > 1:
                components.append(sorted(component))

    for node in sorted(graph):
        if node not in index:
            visit(node)
    return sorted(components)


def test_circles_are_found() -> None:
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}, "e": set()}
    assert circles(graph) == [["a", "b", "c"]]


def test_function_level_and_relative_imports_are_edges() -> None:
    source = (
        "def f():\n    from sb3_hfo.b import x\nfrom . import c\n"
        "if TYPE_CHECKING:\n    import sb3_hfo.d\nelse:\n    import sb3_hfo.e\n"
    )
    known = {"sb3_hfo", "sb3_hfo.a", "sb3_hfo.b", "sb3_hfo.c", "sb3_hfo.d", "sb3_hfo.e"}
    found = imported_modules(ast.parse(source), "sb3_hfo.a", False, known)
    assert found == {"sb3_hfo.b", "sb3_hfo.c", "sb3_hfo.e"}


def test_the_graph_covers_the_package() -> None:
    graph = import_graph()
    assert "sb3_hfo.skill_ddpg.skill_ddpg" in graph
    assert "sb3_hfo.skill_ddpg.policies" in graph["sb3_hfo.skill_ddpg.skill_ddpg"]


def test_sb3_hfo_has_no_import_circles() -> None:
    found = circles(import_graph())
    assert found == [], f"import circles among sb3_hfo's modules: {found}"


#: The library's public modules: none of them may reach the command line (argparse tools, rl-zoo3, Optuna).
LIBRARY_MODULES = (
    "sb3_hfo",
    "sb3_hfo.evaluation",
    "sb3_hfo.models",
    "sb3_hfo.callbacks",
    "sb3_hfo.demonstrations",
)


def reachable(graph: dict[str, set[str]], roots: tuple[str, ...]) -> set[str]:
    """The modules that importing ``roots`` can import, by any path through ``graph`` (roots included)."""
    seen: set[str] = set()
    pending = list(roots)
    while pending:
        module = pending.pop()
        if module not in seen:
            seen.add(module)
            pending.extend(graph.get(module, ()))
    return seen


def test_the_library_does_not_reach_the_command_line() -> None:
    graph = import_graph()
    assert set(LIBRARY_MODULES) <= set(graph)
    assert sorted(m for m in reachable(graph, LIBRARY_MODULES) if m.startswith("sb3_hfo.cli")) == []


def test_importing_the_library_imports_neither_rl_zoo3_nor_the_cli() -> None:
    code = (
        f"import sys\nimport {', '.join(LIBRARY_MODULES)}\n"
        "print(sorted(m for m in sys.modules if m.split('.')[0] in ('rl_zoo3', 'optuna', 'huggingface_sb3')"
        " or m.startswith('sb3_hfo.cli')))\n"
    )
    completed = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert completed.returncode == 0, completed.stderr[-2000:]
    assert completed.stdout.strip() == "[]"


if __name__ == "__main__":
    for component in circles(import_graph()):
        print(" <-> ".join(component))
    sys.exit(0)
