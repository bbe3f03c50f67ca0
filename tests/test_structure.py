"""The package's structure (issue 19): layers, import cycles, kernel signatures, module sizes.

Layers, from the bottom: the *domain* modules (every module of ``moorlife`` outside ``io`` and
``stages``; ``plots`` included: the figures are built in memory and saved by the stages
through :func:`moorlife.io.save_figure`), then ``moorlife.io`` (formats and stores), then
``moorlife.stages`` (one module per Snakemake stage). A module may import only from its own
layer or below. The import graph is read statically from the source (module-level and
function-level imports both count), so a lazy import cannot hide a cycle.
"""

from __future__ import annotations

import ast
import itertools
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src"
PKG = SRC / "moorlife"

MAX_KERNEL_PARAMS = 12
MAX_MODULE_LINES = 800


def module_name(path: Path) -> str:
    rel = path.relative_to(SRC).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def modules() -> dict[str, Path]:
    return {module_name(p): p for p in sorted(PKG.rglob("*.py"))}


def _is_package(name: str, mods: dict[str, Path]) -> bool:
    return mods[name].name == "__init__.py"


def imports_of(name: str, mods: dict[str, Path]) -> dict[str, int]:
    """The moorlife modules that ``name`` imports, anywhere in its source, with a line number."""
    tree = ast.parse(mods[name].read_text(), filename=str(mods[name]))
    package = name if _is_package(name, mods) else name.rpartition(".")[0]
    found: dict[str, int] = {}

    def add(target: str, line: int) -> None:
        while target and target not in mods:  # an attribute of a module: the module
            target = target.rpartition(".")[0]
        if target and target != name:
            found.setdefault(target, line)

    def typing_only(node: ast.AST) -> bool:  # ``if TYPE_CHECKING:``: annotations only, never run
        t = node.test if isinstance(node, ast.If) else None
        return isinstance(t, ast.Name | ast.Attribute) and getattr(t, "id", getattr(t, "attr", "")) == "TYPE_CHECKING"

    skipped = {id(n) for block in ast.walk(tree) if typing_only(block) for stmt in block.body for n in ast.walk(stmt)}
    for node in ast.walk(tree):
        if id(node) in skipped:
            continue
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.split(".")[0] == "moorlife":
                    add(alias.name, node.lineno)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[: len(base) - node.level + 1]
                origin = ".".join(base + ([node.module] if node.module else []))
            else:
                origin = node.module or ""
            if origin.split(".")[0] != "moorlife":
                continue
            for alias in node.names:
                sub = f"{origin}.{alias.name}"
                add(sub if sub in mods else origin, node.lineno)
    return found


def import_graph() -> dict[str, dict[str, int]]:
    mods = modules()
    return {m: imports_of(m, mods) for m in mods}


def find_cycle(graph: dict[str, dict[str, int]]) -> list[str] | None:
    """One import cycle as a list of modules (first == last), or None."""
    state: dict[str, int] = {}  # 1: on the stack, 2: done
    stack: list[str] = []

    def visit(m: str) -> list[str] | None:
        state[m] = 1
        stack.append(m)
        for t in sorted(graph.get(m, {})):
            if state.get(t) == 1:
                return stack[stack.index(t) :] + [t]
            if t not in state:
                found = visit(t)
                if found:
                    return found
        stack.pop()
        state[m] = 2
        return None

    for m in sorted(graph):
        if m not in state:
            found = visit(m)
            if found:
                return found
    return None


def layer(name: str) -> int:
    if name == "moorlife.stages" or name.startswith("moorlife.stages."):
        return 2
    if name == "moorlife.io" or name.startswith("moorlife.io."):
        return 1
    return 0


def test_the_graph_sees_function_level_imports():
    graph = import_graph()
    assert "moorlife.hydro" in graph["moorlife.simulate.prepare"], "function-level imports must count"
    # imports under ``if TYPE_CHECKING:`` (annotations only) do not count
    assert "moorlife.hydro.model" not in graph["moorlife.hydro.loads"]
    assert "moorlife.simulate" in graph["moorlife.stages.simulate"]
    assert "moorlife.io.partial" in graph["moorlife.stages.fanout"]


def test_find_cycle_reports_the_cycle():
    assert find_cycle({"a": {"b": 1}, "b": {"c": 1}, "c": {"a": 1}}) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b": 1}, "b": {}}) is None


def test_no_import_cycles():
    graph = import_graph()
    cycle = find_cycle(graph)
    if cycle:
        where = [f"{a} -> {b} (line {graph[a][b]})" for a, b in itertools.pairwise(cycle)]
        pytest.fail("import cycle: " + "; ".join(where))


def test_lower_layers_never_import_higher_ones():
    """Domain modules never import moorlife.io or moorlife.stages; moorlife.io never imports stages."""
    graph = import_graph()
    names = {0: "domain", 1: "io", 2: "stages"}
    bad = [
        f"{m} ({names[layer(m)]}) imports {t} ({names[layer(t)]}) at line {ln}"
        for m, deps in graph.items()
        for t, ln in deps.items()
        if layer(t) > layer(m)
    ]
    assert bad == [], "\n".join(bad)


def _is_numba_decorator(dec: ast.expr) -> bool:
    target = dec.func if isinstance(dec, ast.Call) else dec
    name = target.attr if isinstance(target, ast.Attribute) else getattr(target, "id", "")
    return name in {"njit", "jit"}


def kernel_signatures() -> list[tuple[str, str, int]]:
    """(module, function, parameter count) of every njit/jit-decorated function."""
    out = []
    for name, path in modules().items():
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.FunctionDef) and any(_is_numba_decorator(d) for d in node.decorator_list):
                a = node.args
                n = len(a.posonlyargs) + len(a.args) + len(a.kwonlyargs) + bool(a.vararg) + bool(a.kwarg)
                out.append((name, node.name, n))
    return out


def test_kernel_scan_finds_the_kernels():
    sigs = kernel_signatures()
    assert len(sigs) > 10 and all(n >= 0 for *_, n in sigs)
    assert any(m.startswith("moorlife.fatigue.") for m, *_ in sigs)
    assert any(m.startswith("moorlife.simulate.") for m, *_ in sigs)


def test_no_kernel_takes_more_than_12_parameters():
    long = [f"{m}.{f}: {n} parameters" for m, f, n in kernel_signatures() if n > MAX_KERNEL_PARAMS]
    assert long == [], "\n".join(long)


def test_no_module_over_800_lines():
    big = [f"{m}: {n} lines" for m, p in modules().items() if (n := len(p.read_text().splitlines())) > MAX_MODULE_LINES]
    assert big == [], "\n".join(big)
