"""Architecture of the package: layers, import graph, public names, size.

Every module of ``tefcore`` (the solver's layers and the ``tefcore.paper``
layer) is parsed with :mod:`ast`; imports anywhere in a module (top level,
functions, ``TYPE_CHECKING`` blocks) are edges of the import graph.

* (a) the layers of :data:`LAYERS`, bottom up: a module imports only modules
  of its own folder and of layers below its own (folders on one layer are
  peers and do not import each other); the solver never imports the paper;
* (b) the graph has no cycles: imports flow one way;
* (c) every module has ``__all__`` and every name in it exists;
* (d) no private name (``_x``) of one module is imported or read by another,
  nor a shared name imported under a private alias (``import X as _x``);
  private *modules* (``tefcore.floquet._analysis``) are the implementation
  of their package's public face and may be imported whole or by their
  public names;
* (e) size: no module has more than :data:`MAX_CODE_LINES` lines of code
  (docstrings, comments and blank lines aside) and no function more than
  :data:`MAX_FUNCTION_LINES` lines of code or a cyclomatic complexity above
  :data:`MAX_COMPLEXITY`, unless :data:`LONG_FUNCTIONS` gives its reason.

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

#: The solver's layers, bottom up: folders (subpackages) and root modules of
#: ``tefcore``.  A module may import its own folder (or, for a root module,
#: itself only) and any layer below; the names on one layer are peers that do
#: not import each other.  The package's face (``tefcore/__init__.py``) lazily
#: exports names from every layer (PEP 562) and is exempt.
LAYERS = (
    ("_version", "units", "errors", "runtime", "fourier", "faces"),  # no imports
    ("provenance", "safe_io"),            # files, fingerprints
    ("config",),                          # the configuration: data, no physics
    ("structure", "aero", "floquet"),     # blade and hub; section airloads; Floquet theory
    ("model",),                           # the coupled blade/flap/actuator equations
    ("trimming", "modes"),                # the trim; mode identity
    ("linear",),                          # stability of the trimmed rotor, mechanism
    ("sweeps", "timedomain"),             # sweeps, boundaries, maps; the marched response
    ("paper",),                           # the paper's figures, claims, notebooks
    ("cli",),                             # the command (text: what it prints; watch)
    ("__main__",),                        # python -m tefcore
)

#: The paper layer's rooms and single-module homes, bottom up (``tefcore.paper.<home>``):
#: the same rule one level down -- a module imports its own room and the homes
#: below, never a peer or a home above.
PAPER_LAYERS = (
    ("calibration", "figures"),          # the stated frequencies; the figures as analyses
    ("claims",),                         # the paper's statements and their checks
    ("attribution", "fig6_calibration", "explorer", "summaries"),
    ("inference",),                      # the unknown properties inferred from the claims
    ("explorer_app", "notebook_tools"),  # the web page; the notebooks' vocabulary
    ("run",),                            # reproduce, report, batches, the subcommands
)

#: Most lines of code in one module (documentation aside): a page of screens.
MAX_CODE_LINES = 400

#: Most lines of code in one function (its docstring aside): about a page.
MAX_FUNCTION_LINES = 60

#: Highest cyclomatic complexity of a function (decision points + 1).
MAX_COMPLEXITY = 25

#: function -> why it is longer or more branched than the limits allow.
LONG_FUNCTIONS: dict[str, str] = {
    "tefcore.aero.c81.reader.numbers":
        "one pass over a line's fields: each branch is one way a number can be wrong, "
        "with the error docs/c81_format.md specifies for it",
    "tefcore.model.jacobian.jacobian_blocks":
        "the dispatch between the exact Jacobian and the difference schemes with the "
        "shed-wake and inflow states; one screen",
    "tefcore.model.jacobian.exact_jacobian":
        "the station derivatives (fused kernel or complex step) projected on the shapes "
        "by derivative order, the thrust's, the linear terms' and the controls' and "
        "inflow's chain rule: one sequence over a dozen shared arrays (theory 6.3)",
    "tefcore.model.station_kernel._kernel":
        "the compiled kernel: one station's section loads, airloads and flap equation "
        "per complex step, written out in one body because numba compiles it as one "
        "function (no Python helpers inside a cached kernel)",
    "tefcore.modes.tracking._lock_steps":
        "the plane rule of a Floquet lock: entering, within and leaving a k/2 lock are "
        "three cases of one decision on the same cost and shape matrices",
    "tefcore.paper.run.batch_state.changes":
        "one comparison per recorded input of a run (parameters, configuration file, "
        "version, code, notebook cells, reference data), each worded for the user",
    "tefcore.structure.blade.multiple_load_path_model":
        "declarative: the hub's components, joints and couplings listed in the order of "
        "docs/theory.md 2.5a",
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


def layer_of(module: str) -> tuple[int, str] | None:
    """``(rank in LAYERS, folder or root module)`` of a module; None for the face."""
    parts = module.split(".")
    if len(parts) == 1:
        return None                      # tefcore/__init__.py: the curated face
    home = parts[1]
    for rank, homes in enumerate(LAYERS):
        if home in homes:
            return rank, home
    raise AssertionError(f"{module}: {home!r} is on no layer of LAYERS")


def layer_violations(graph=None) -> list[str]:
    """Imports that do not run down the layers (or stay in the module's own folder)."""
    out = []
    for m in MODULES:
        here = layer_of(m)
        if here is None:
            for target in _lazy_targets(m):
                if _is_paper(target):
                    out.append(f"{m}: lazily exports {target}")
            continue
        for target, _, line in _imports(m):
            there = layer_of(target) if target in MODULES else None
            if there is None or there[1] == here[1]:
                continue
            if there[0] >= here[0]:
                kind = "a peer" if there[0] == here[0] else "a layer above"
                out.append(f"{m}: imports {target}, {kind} ({there[1]!r} on layer "
                           f"{there[0]}, {here[1]!r} on layer {here[0]}) (line {line})")
    return out


def paper_home(module: str) -> tuple[int, str] | None:
    """``(rank in PAPER_LAYERS, room or module)`` of a paper module; None for the face."""
    parts = module.split(".")
    if parts[:2] != ["tefcore", "paper"] or len(parts) == 2:
        return None
    for rank, homes in enumerate(PAPER_LAYERS):
        if parts[2] in homes:
            return rank, parts[2]
    raise AssertionError(f"{module}: {parts[2]!r} is on no layer of PAPER_LAYERS")


def paper_layer_violations() -> list[str]:
    """Imports inside the paper layer that do not run down its rooms."""
    out = []
    for m in MODULES:
        here = paper_home(m)
        if here is None:
            continue
        for target, _, line in _imports(m):
            there = paper_home(target) if target in MODULES else None
            if there is None or there[1] == here[1]:
                continue
            if there[0] >= here[0]:
                kind = "a peer" if there[0] == here[0] else "a room above"
                out.append(f"{m}: imports {target}, {kind} ({there[1]!r} on paper layer "
                           f"{there[0]}, {here[1]!r} on paper layer {here[0]}) (line {line})")
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


def _docstring_lines(node) -> set[int]:
    first = node.body[0] if node.body else None
    if (isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant)
            and isinstance(first.value.value, str)):
        return set(range(first.lineno, first.end_lineno + 1))
    return set()


#: The nodes that add a path through a function (cyclomatic complexity).
_BRANCHES = (ast.If, ast.For, ast.While, ast.IfExp, ast.Try, ast.ExceptHandler, ast.BoolOp,
             ast.comprehension, ast.Assert, ast.match_case, ast.With)


def function_sizes(module: str):
    """``(qualified name, lines of code, complexity)`` of every function of a module."""
    lines = MODULES[module].read_text(encoding="utf-8").splitlines()
    for node in ast.walk(TREES[module]):
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
            docs = _docstring_lines(node)
            n = sum(1 for i in range(node.lineno, node.end_lineno + 1)
                    if i not in docs and lines[i - 1].strip()
                    and not lines[i - 1].lstrip().startswith("#"))
            cc = 1 + sum(isinstance(x, _BRANCHES) for x in ast.walk(node))
            yield f"{module}.{node.name}", n, cc


def size_violations() -> list[str]:
    out = []
    for m in MODULES:
        if code_lines(m) > MAX_CODE_LINES:
            out.append(f"{m}: {code_lines(m)} lines of code > {MAX_CODE_LINES}")
        for name, n, cc in function_sizes(m):
            if name in LONG_FUNCTIONS:
                continue
            if n > MAX_FUNCTION_LINES:
                out.append(f"{name}: {n} lines of code > {MAX_FUNCTION_LINES}")
            if cc > MAX_COMPLEXITY:
                out.append(f"{name}: complexity {cc} > {MAX_COMPLEXITY}")
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
    # tefcore.paper.run.commands inside a function, relatively (.paper)
    graph = import_graph()
    assert "tefcore.paper.run.commands" in graph["tefcore.cli"]
    assert "tefcore.config.configuration" in graph["tefcore.config.io"]


def test_cycle_finder_finds_a_planted_cycle():
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}
    assert find_cycles(graph) == [["a", "b", "c"]]
    assert find_cycles({"a": {"b"}, "b": set()}) == []


def test_the_checks_find_planted_violations(monkeypatch):
    # a module importing a private name, reading one through a module alias,
    # and importing the paper layer: each must be reported
    fake = "tefcore.model.planted"
    monkeypatch.setitem(MODULES, fake, PACKAGE_DIR / "model" / "planted.py")
    monkeypatch.setitem(TREES, fake, ast.parse(
        "from ..sweeps.sweep import _evaluate\n"
        "from ..units import to_si as _to_si\n"
        "from .. import floquet as fq\n"
        "def f():\n"
        "    from ..paper.run import reproduce\n"
        "    return fq._private\n"))
    found = private_violations() + layer_violations()
    assert any("planted: imports private tefcore.sweeps.sweep._evaluate" in v for v in found)
    assert any("planted: reads private tefcore.floquet._private" in v for v in found)
    assert any("planted: imports tefcore.units.to_si as private _to_si" in v for v in found)
    assert any("planted: imports tefcore.paper.run.reproduce, a layer above" in v for v in found)


def test_the_layer_check_finds_a_backward_import(monkeypatch):
    # the configuration importing the coupled model (up), the Floquet theory
    # importing the structure (a peer), and a structure module importing its
    # own folder and the configuration (allowed)
    planted = {
        "tefcore.config.planted": "from ..model.coupled import coupled_model\n",
        "tefcore.floquet.planted": "from ..structure.fem import classify\n",
        "tefcore.structure.planted": "from .fem import classify\nfrom ..config import io\n",
    }
    for name, code in planted.items():
        monkeypatch.setitem(MODULES, name, PACKAGE_DIR / "planted.py")
        monkeypatch.setitem(TREES, name, ast.parse(code))
    found = [v for v in layer_violations() if "planted" in v]
    assert found == [
        "tefcore.config.planted: imports tefcore.model.coupled, a layer above ('model' on "
        "layer 4, 'config' on layer 2) (line 1)",
        "tefcore.floquet.planted: imports tefcore.structure.fem, a peer ('structure' on "
        "layer 3, 'floquet' on layer 3) (line 1)",
    ]


def test_the_paper_layer_is_in_rooms():
    assert not paper_layer_violations(), "\n".join(paper_layer_violations())


def test_the_room_check_finds_a_backward_import(monkeypatch):
    # a figure module reading the claims (a room above) and a claims module
    # reading the figures (below: allowed)
    planted = {
        "tefcore.paper.figures.planted": "from ..claims.reference import load_claims\n",
        "tefcore.paper.claims.planted": "from ..figures.catalogue import FIGURES\n",
    }
    for name, code in planted.items():
        monkeypatch.setitem(MODULES, name, PACKAGE_DIR / "planted.py")
        monkeypatch.setitem(TREES, name, ast.parse(code))
    found = [v for v in paper_layer_violations() if "planted" in v]
    assert found == [
        "tefcore.paper.figures.planted: imports tefcore.paper.claims.reference, a room above "
        "('claims' on paper layer 1, 'figures' on paper layer 0) (line 1)"]


def test_every_paper_module_is_in_a_room():
    homes = {m.split(".")[2] for m in MODULES if m.startswith("tefcore.paper.")}
    assert homes == {h for layer in PAPER_LAYERS for h in layer}
    flat = [p for p in (PACKAGE_DIR / "paper").glob("*.py") if p.name != "__init__.py"]
    assert len(flat) <= 12, sorted(p.name for p in flat)


def test_no_face_name_is_also_a_module_of_its_package():
    # importing a submodule binds its name in the package: a face name equal to
    # a module's name would be the function or the module depending on what
    # was imported first
    for m in MODULES:
        if _is_package(m):
            clash = _lazy_targets_names(m) & {s.rsplit(".", 1)[1] for s in MODULES
                                              if "." in s and s.rsplit(".", 1)[0] == m}
            assert not clash, f"{m}: face names that are modules: {sorted(clash)}"


def _lazy_targets_names(module: str) -> set[str]:
    for node in TREES[module].body:
        if isinstance(node, ast.Assign) and any(
                isinstance(t, ast.Name) and t.id == "API" for t in node.targets):
            return {k.value for k in node.value.keys if isinstance(k, ast.Constant)}
    return set()


def test_every_folder_and_root_module_is_on_a_layer():
    homes = {m.split(".")[1] for m in MODULES if m.count(".") >= 1}
    placed = {h for layer in LAYERS for h in layer}
    assert homes == placed


def test_the_solver_is_in_layers():
    _check(layer_violations())


def test_no_import_cycles():
    _check(cycle_violations(import_graph()))


def test_every_module_has_a_valid_all():
    _check(all_violations())


def test_no_private_names_across_modules():
    _check(private_violations())


def test_modules_and_functions_are_within_size():
    _check(size_violations())
    known = {name for m in MODULES for name, _, _ in function_sizes(m)}
    stale = [name for name in LONG_FUNCTIONS if name not in known or all(
        n <= MAX_FUNCTION_LINES and cc <= MAX_COMPLEXITY
        for m in MODULES for f, n, cc in function_sizes(m) if f == name)]
    assert not stale, f"LONG_FUNCTIONS entries no longer needed: {stale}"


def test_code_lines_leave_out_documentation():
    # tefcore.floquet is a facade: a long docstring over a few imports
    assert code_lines("tefcore.floquet") < 50
    assert len(MODULES["tefcore.floquet"].read_text().splitlines()) > code_lines("tefcore.floquet")


def test_size_check_counts_code_and_branches(monkeypatch):
    name = "tefcore.model.planted"
    body = "".join(f"    if x == {i}:\n        x += 1\n" for i in range(40))
    monkeypatch.setitem(MODULES, name, PACKAGE_DIR / "model" / "planted.py")
    monkeypatch.setattr(Path, "read_text", lambda self, **kw: f"def f(x):\n{body}")
    monkeypatch.setitem(TREES, name, ast.parse(f"def f(x):\n{body}"))
    assert ("tefcore.model.planted.f", 81, 41) in set(function_sizes(name))


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
