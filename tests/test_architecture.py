"""The package's layout shows its architecture: groups by the paper's concepts,
each importing only the groups below it, and no import cycles."""

from __future__ import annotations

import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PACKAGE = ROOT / "ethasp"

# Lowest first: a group may import itself and the groups before it.
LAYERS = ["core", "planning", "principles", "reasons", "questions", "batch", "interfaces"]
CORE = {
    "ethasp",
    "ethasp.errors",
    "ethasp.execution",
    "ethasp.memo",
    "ethasp.resources",
    "ethasp.vocabulary",
}


def _module(path: Path) -> str:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def _group(module: str) -> str:
    if module in CORE or module.startswith(("ethasp.vocabulary.", "ethasp.execution.")):
        return "core"
    return module.split(".")[1]


# Imports made only for annotations (under ``if TYPE_CHECKING:``) that point
# upwards: the layer below names a type of the layer above.  Known debt, kept
# short on purpose: Judgement.explanation is filled in by ethasp.reasons.
TYPE_ONLY_UPWARDS = {("ethasp.principles.judgement", "ethasp.reasons.explanation")}


def _type_checking_nodes(tree: ast.AST) -> set[ast.AST]:
    """The nodes inside ``if TYPE_CHECKING:`` blocks."""
    inside: set[ast.AST] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and ast.unparse(node.test).endswith("TYPE_CHECKING"):
            for child in node.body:
                inside |= set(ast.walk(child))
    return inside


def _imports(type_only: bool = False) -> dict[str, set[str]]:
    """Every ethasp module and the ethasp modules it imports (anywhere in it);
    with ``type_only``, only those it imports for annotations alone."""
    modules = {_module(path): path for path in PACKAGE.rglob("*.py")}
    graph: dict[str, set[str]] = {}
    for name, path in modules.items():
        found: set[str] = set()
        tree = ast.parse(path.read_text())
        typing_only = _type_checking_nodes(tree)
        for node in ast.walk(tree):
            if (node in typing_only) != type_only:
                continue
            if isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
                targets = [node.module] + [f"{node.module}.{a.name}" for a in node.names]
            elif isinstance(node, ast.Import):
                targets = [alias.name for alias in node.names]
            else:
                continue
            found |= {t for t in targets if t in modules and t != name}
        graph[name] = found
    return graph


def test_every_module_is_in_a_group():
    for module in _imports():
        assert _group(module) in LAYERS, module


def test_groups_import_only_groups_below():
    graph = _imports()
    for module, targets in graph.items():
        if module == "ethasp":
            continue  # the package's lazy exports name every group
        for target in targets:
            assert LAYERS.index(_group(target)) <= LAYERS.index(_group(module)), (module, target)


def test_type_only_imports_upwards_are_the_known_ones():
    upwards = {
        (module, target)
        for module, targets in _imports(type_only=True).items()
        if module != "ethasp"  # the package names its exports for type checkers
        for target in targets
        if LAYERS.index(_group(target)) > LAYERS.index(_group(module))
    }
    assert upwards == TYPE_ONLY_UPWARDS


def test_no_import_cycles():
    graph = _imports()
    graph["ethasp"] = set()  # lazy exports, not imports at load time
    state: dict[str, int] = {}

    def visit(module: str, path: list[str]) -> None:
        state[module] = 1
        for target in sorted(graph[module]):
            assert state.get(target) != 1, " -> ".join([*path, target])
            if target not in state:
                visit(target, [*path, target])
        state[module] = 2

    for module in sorted(graph):
        if module not in state:
            visit(module, [module])


def test_each_command_has_its_own_module():
    """The command line is a package: a module per command holds its parser and
    what it runs, and main() with how a command runs is one module of its own."""
    import argparse

    from ethasp.interfaces import cli
    from ethasp.interfaces.cli import execution

    parser = cli.build_parser()
    commands = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    for name, sub in commands.choices.items():
        module = sub.get_default("run").__module__
        assert module == f"ethasp.interfaces.cli.{name}", (name, module)
    assert cli.main is execution.main
    assert not (PACKAGE / "interfaces" / "cli.py").exists()
    assert (PACKAGE / "interfaces" / "cli" / "__main__.py").is_file()  # python -m ...cli
