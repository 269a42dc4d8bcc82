"""Architecture of the package: import graph, public names, module size.

Every module of ``tefcore`` (the flat solver and the ``tefcore.paper``
layer) is parsed with :mod:`ast`; imports anywhere in a module (top level,
functions, ``TYPE_CHECKING`` blocks) are edges of the import graph.

* (a) the graph has no cycles: imports flow one way;
* (b) solver modules (``tefcore/*.py``) never import ``tefcore.paper``,
  except :mod:`tefcore.cli`, which dispatches ``tefcore reproduce`` to it;
* (c) every module has ``__all__`` and every name in it exists;
* (d) no private name (``_x``) of one module is imported or read by another,
  nor a shared name imported under a private alias (``import X as _x``);
  private *modules*, ``tefcore._floquet_*``, are the implementation of a
  public facade and may be imported whole or by their public names;
* (e) a module over :data:`MAX_LINES` lines has its reason in
  :data:`LARGE_MODULES`: one job that a split would scatter, or
  :data:`DOCUMENTED` -- its code (without docstrings, comments and blank
  lines) is within the limit, which the test checks.

``PAPER_PENDING`` lists the violations of the paper layer that are known and
being fixed there; it must shrink, never grow: a violation not in it fails, and
so does an entry that is no longer a violation (delete it).
"""

from __future__ import annotations

import ast
import importlib
import re
import subprocess
import sys
from pathlib import Path

import pytest

import tefcore

PACKAGE_DIR = Path(tefcore.__file__).resolve().parent

#: Beyond this many lines a module needs a reason in LARGE_MODULES.
MAX_LINES = 400

#: The reason of a module whose *code* is within MAX_LINES and whose length is
#: its numpydoc documentation (checked: :func:`code_lines`).
DOCUMENTED = "code within the limit; the rest is its documentation"

#: module -> why it stays over MAX_LINES (one job, split would scatter it).
LARGE_MODULES = {
    "tefcore.config": "one job: the typed, validated configuration sections and their "
                      "cross-field checks; each section is a dataclass of Param fields and "
                      "splitting them would separate a field from the checks that use it",
    "tefcore.sweep": "one job: the sweep driver (serial/joblib/dask evaluation, resumable "
                     "store, refinement near close passes, tracking); the file format is "
                     "already in sweep_store, boundaries in boundary and matching in "
                     "mode_matching",
    "tefcore.paper.reference": "one job: the reference-data format of "
                               "reference_data/README.md (claims of eight kinds, curve "
                               "sidecars, WebPlotDigitizer CSV) read and every field checked "
                               "with an error naming it; the checks are the specification",
    "tefcore.blade": DOCUMENTED,
    "tefcore._floquet_modes": DOCUMENTED,
    "tefcore.stability": DOCUMENTED,
    "tefcore.c81_reader": DOCUMENTED,
    "tefcore.paper.batch_report": DOCUMENTED,
    "tefcore.paper.batch_spec": DOCUMENTED,
    "tefcore.paper.claim_checks": DOCUMENTED,
    "tefcore.paper.plotting": DOCUMENTED,
    "tefcore.paper.report": DOCUMENTED,
    "tefcore.paper.reproduce": DOCUMENTED,
    "tefcore.paper.sensitivity": DOCUMENTED,
    "tefcore.paper.summaries": DOCUMENTED,
    "tefcore.cli": DOCUMENTED,
    "tefcore.config_io": DOCUMENTED,
    "tefcore.coupled": DOCUMENTED,
    "tefcore.flap_dynamics": DOCUMENTED,
    "tefcore.mechanism": DOCUMENTED,
    "tefcore.mode_matching": DOCUMENTED,
    "tefcore.section_inertia": DOCUMENTED,
    "tefcore.settings": DOCUMENTED,
    "tefcore.structure": DOCUMENTED,
    "tefcore.sweep_store": DOCUMENTED,
    "tefcore.theodorsen": DOCUMENTED,
    "tefcore.tracking": DOCUMENTED,
    "tefcore.trim": DOCUMENTED,
    "tefcore.flap_aero": DOCUMENTED,
    "tefcore.residual_jacobian": DOCUMENTED,
    "tefcore._floquet_propagators": DOCUMENTED,
    "tefcore.units": DOCUMENTED,
    "tefcore.unsteady_aero": DOCUMENTED,
}

#: Known violations in tefcore.paper, being fixed there (remove entries as they are fixed).
PAPER_PENDING: set[str] = set()


# ------------------------------------------------------------------ the graph


def _module_name(path: Path) -> str:
    rel = path.relative_to(PACKAGE_DIR.parent).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


#: The notebooks' jupytext sources are notebooks, not modules.
NOTEBOOK_SOURCES = PACKAGE_DIR / "paper" / "notebooks"
MODULES = {_module_name(p): p for p in sorted(PACKAGE_DIR.rglob("*.py"))
           if NOTEBOOK_SOURCES not in p.parents}
TREES = {m: ast.parse(p.read_text(encoding="utf-8"), filename=str(p)) for m, p in MODULES.items()}


def _is_package(module: str) -> bool:
    return MODULES[module].name == "__init__.py"


def _resolve(module: str, node: ast.ImportFrom) -> str:
    """Absolute name of the module a ``from ... import`` reads from."""
    if node.level == 0:
        return node.module or ""
    parts = module.split(".")
    if not _is_package(module):
        parts.pop()
    parts = parts[: len(parts) - (node.level - 1)]
    return ".".join(parts + ([node.module] if node.module else []))


def _imports(module: str):
    """``(target, name or None, lineno)`` for every import of a tefcore module.

    ``name`` is the imported attribute for ``from target import name`` when
    ``target.name`` is not itself a module, else None.
    """
    for node in ast.walk(TREES[module]):
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.split(".")[0] == "tefcore":
                    yield alias.name, None, node.lineno
        elif isinstance(node, ast.ImportFrom):
            base = _resolve(module, node)
            if base.split(".")[0] != "tefcore":
                continue
            for alias in node.names:
                sub = f"{base}.{alias.name}"
                if sub in MODULES:
                    yield sub, None, node.lineno
                else:
                    yield base, alias.name, node.lineno


def _lazy_targets(module: str) -> set[str]:
    """Modules a package loads on first attribute access (PEP 562 table ``API``)."""
    targets = set()
    for node in TREES[module].body:
        if isinstance(node, ast.Assign | ast.AnnAssign):
            names = [t.id for t in (node.targets if isinstance(node, ast.Assign)
                                    else [node.target]) if isinstance(t, ast.Name)]
            if "API" in names and isinstance(node.value, ast.Dict):
                for v in node.value.values:
                    if isinstance(v, ast.Constant) and isinstance(v.value, str):
                        targets.add(v.value)
    return targets


def import_graph() -> dict[str, set[str]]:
    graph = {m: set() for m in MODULES}
    for m in MODULES:
        for target, _, _ in _imports(m):
            if target in MODULES and target != m:
                graph[m].add(target)
        graph[m] |= {t for t in _lazy_targets(m) if t in MODULES}
    return graph


def find_cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components with more than one module (Tarjan)."""
    index, low, stack, on_stack, out = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


# ------------------------------------------------------------------ the rules


def _is_paper(module: str) -> bool:
    return module == "tefcore.paper" or module.startswith("tefcore.paper.")


def _private(name: str) -> bool:
    return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))


def cycle_violations(graph) -> list[str]:
    return [f"cycle: {' <-> '.join(c)}" for c in find_cycles(graph)]


def layer_violations() -> list[str]:
    out = []
    for m in MODULES:
        if _is_paper(m) or m == "tefcore.cli":
            continue
        for target, _, line in _imports(m):
            if _is_paper(target):
                out.append(f"{m}: solver module imports {target} (line {line})")
        for target in _lazy_targets(m):
            if _is_paper(target):
                out.append(f"{m}: lazily exports {target}")
    return out


def all_violations() -> list[str]:
    out = []
    for m in MODULES:
        if m == "tefcore.__main__":   # a script: importing it runs the command
            has_all = any(
                isinstance(t, ast.Name) and t.id == "__all__"
                for n in TREES[m].body if isinstance(n, ast.Assign | ast.AnnAssign)
                for t in (n.targets if isinstance(n, ast.Assign) else [n.target]))
            if not has_all:
                out.append(f"{m}: no __all__")
            continue
        mod = importlib.import_module(m)
        names = getattr(mod, "__all__", None)
        if names is None:
            out.append(f"{m}: no __all__")
            continue
        out += [f"{m}: __all__ names missing {n!r}" for n in names if not hasattr(mod, n)]
        if len(set(names)) != len(names):
            out.append(f"{m}: __all__ has duplicates")
    return out


def private_violations() -> list[str]:
    out = []
    for m in MODULES:
        module_aliases = {}
        for node in ast.walk(TREES[m]):
            if isinstance(node, ast.ImportFrom):
                base = _resolve(m, node)
                if base.split(".")[0] != "tefcore":
                    continue
                for alias in node.names:
                    if f"{base}.{alias.name}" in MODULES:
                        module_aliases[alias.asname or alias.name] = f"{base}.{alias.name}"
                    elif _private(alias.name) and base != m:
                        out.append(f"{m}: imports private {base}.{alias.name} "
                                   f"(line {node.lineno})")
                    if alias.asname and _private(alias.asname) and base != m:
                        # a shared name hidden under a private alias: the
                        # reader cannot tell where it lives or that it is shared
                        out.append(f"{m}: imports {base}.{alias.name} as private "
                                   f"{alias.asname} (line {node.lineno})")
            elif isinstance(node, ast.Import):
                for alias in node.names:
                    if alias.name.split(".")[0] == "tefcore" and alias.asname:
                        module_aliases[alias.asname] = alias.name
        for node in ast.walk(TREES[m]):
            if (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name)
                    and node.value.id in module_aliases and _private(node.attr)):
                out.append(f"{m}: reads private {module_aliases[node.value.id]}.{node.attr} "
                           f"(line {node.lineno})")
    return out


def code_lines(module: str) -> int:
    """Lines of a module that are neither blank, comments nor docstrings."""
    lines = MODULES[module].read_text(encoding="utf-8").splitlines()
    docs = set()
    for node in ast.walk(TREES[module]):
        if isinstance(node, ast.Module | ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef):
            first = node.body[0] if node.body else None
            if (isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant)
                    and isinstance(first.value.value, str)):
                docs.update(range(first.lineno, first.end_lineno + 1))
    return sum(1 for i, text in enumerate(lines, 1)
               if i not in docs and text.strip() and not text.lstrip().startswith("#"))


def size_violations() -> list[str]:
    out = []
    for m, p in MODULES.items():
        n = len(p.read_text(encoding="utf-8").splitlines())
        if n > MAX_LINES and m not in LARGE_MODULES:
            out.append(f"{m}: {n} lines > {MAX_LINES} without a reason")
        elif LARGE_MODULES.get(m) == DOCUMENTED and code_lines(m) > MAX_LINES:
            out.append(f"{m}: {code_lines(m)} lines of code > {MAX_LINES}: the reason "
                       "'documentation' does not hold")
    return out


def _key(violation: str) -> str:
    """A violation without its line number (PAPER_PENDING survives edits above it)."""
    return re.sub(r" \(line \d+\)$", "", violation)


def _check(violations: list[str]) -> None:
    solver = [v for v in violations if not _is_paper(v.split(":")[0].split(" ")[-1])
              and not v.startswith("cycle: tefcore.paper")]
    paper = sorted({_key(v) for v in violations} - {_key(v) for v in solver})
    assert not solver, "\n".join(solver)
    new = [v for v in paper if v not in PAPER_PENDING]
    assert not new, "new violations in tefcore.paper:\n" + "\n".join(new)


# ------------------------------------------------------------------ tests


def test_the_graph_sees_function_level_and_relative_imports():
    # the checks below are only as good as the graph: tefcore.cli imports
    # tefcore.paper.commands inside a function, relatively (.paper)
    graph = import_graph()
    assert "tefcore.paper.commands" in graph["tefcore.cli"]
    assert "tefcore.config" in graph["tefcore.config_io"]


def test_cycle_finder_finds_a_planted_cycle():
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}
    assert find_cycles(graph) == [["a", "b", "c"]]
    assert find_cycles({"a": {"b"}, "b": set()}) == []


def test_the_checks_find_planted_violations(monkeypatch):
    # a module importing a private name, reading one through a module alias,
    # and a solver module importing the paper layer: each must be reported
    fake = "tefcore.planted"
    monkeypatch.setitem(MODULES, fake, PACKAGE_DIR / "planted.py")
    monkeypatch.setitem(TREES, fake, ast.parse(
        "from .sweep import _evaluate\n"
        "from .units import to_si as _to_si\n"
        "from . import floquet as fq\n"
        "def f():\n"
        "    from .paper import reproduce\n"
        "    return fq._private\n"))
    found = private_violations() + layer_violations()
    assert any("planted: imports private tefcore.sweep._evaluate" in v for v in found)
    assert any("planted: reads private tefcore.floquet._private" in v for v in found)
    assert any("planted: imports tefcore.units.to_si as private _to_si" in v for v in found)
    assert any("planted: solver module imports tefcore.paper.reproduce" in v for v in found)


def test_no_import_cycles():
    _check(cycle_violations(import_graph()))


def test_solver_does_not_import_the_paper_layer():
    _check(layer_violations())


def test_every_module_has_a_valid_all():
    _check(all_violations())


def test_no_private_names_across_modules():
    _check(private_violations())


def test_module_size_has_a_reason():
    _check(size_violations())
    stale = [m for m in LARGE_MODULES
             if m not in MODULES
             or len(MODULES[m].read_text(encoding="utf-8").splitlines()) <= MAX_LINES]
    assert not stale, f"LARGE_MODULES entries no longer needed: {stale}"


def test_code_lines_leave_out_documentation():
    # tefcore.floquet is a facade: a long docstring over a few imports
    assert code_lines("tefcore.floquet") < 50
    assert len(MODULES["tefcore.floquet"].read_text().splitlines()) > code_lines("tefcore.floquet")


def test_paper_pending_is_not_stale():
    # an entry that is fixed must be removed, so the list only shrinks
    everything = {_key(v) for v in cycle_violations(import_graph()) + layer_violations()
                  + all_violations() + private_violations() + size_violations()}
    stale = sorted(PAPER_PENDING - everything)
    assert not stale, "fixed: delete from PAPER_PENDING:\n" + "\n".join(stale)


def test_import_tefcore_is_light():
    # the curated API is loaded on first use: importing the package loads none
    # of the solver (nor numpy/scipy, nor any process setting)
    code = ("import sys, tefcore; print(sorted(m for m in sys.modules "
            "if m.startswith(('tefcore', 'numpy', 'scipy', 'threadpoolctl'))))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True)
    assert out.stdout.strip() == "['tefcore', 'tefcore._version']"


@pytest.mark.parametrize("name", sorted(getattr(tefcore, "__all__", [])))
def test_top_level_api_resolves(name):
    assert getattr(tefcore, name) is not None
