"""The layers of ``symbt.LAYERS`` hold: every import (function-level ones included) goes down or
sideways within a layer, the module graph has no cycle, and the sympy-free layers stay sympy-free."""
from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import pytest

import symbt

PKG = Path(symbt.__file__).resolve().parent
LAYER_OF = {name: i for i, names in enumerate(symbt.LAYERS) for name in names}
MAX_TOP_LEVEL_MODULES = 8
MAX_LINES = 500


def _module_name(path: Path) -> str:
    rel = path.relative_to(PKG.parent).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def _sources():
    return sorted(p for p in PKG.rglob("*.py") if "__pycache__" not in p.parts)


def _imports(path: Path):
    """(line, imported module name) for every import in the file, at any depth."""
    yield from _imports_of(_module_name(path), path.name == "__init__.py", path.read_text(encoding="utf-8"))


def _imports_of(mod: str, is_package: bool, source: str):
    package = mod if is_package else mod.rsplit(".", 1)[0]
    tree = ast.parse(source)
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for a in node.names:
                yield node.lineno, a.name
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[: len(base) - (node.level - 1)]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            # "from .pkg import x" imports the submodule pkg.x when there is one, else the name x
            # defined in pkg: the graph resolves "pkg.x" to the longest existing module, so no
            # separate edge to pkg is added (it would make "from . import kernels" an edge to the
            # package's __init__, which re-exports everything, and hide the cycles behind it)
            for a in node.names:
                yield node.lineno, f"{target}.{a.name}" if a.name != "*" else target
        elif (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
              and node.func.attr == "import_module" and node.args and isinstance(node.args[0], ast.Constant)
              and isinstance(node.args[0].value, str)):
            yield node.lineno, node.args[0].value


def _component(name: str) -> str | None:
    parts = name.split(".")
    if parts[0] != "symbt" or len(parts) < 2:
        return None
    return parts[1]


def _layer(component: str) -> int:
    assert component in LAYER_OF, f"symbt.{component} is in no layer of symbt.LAYERS"
    return LAYER_OF[component]


def test_every_top_level_entry_has_a_layer():
    for p in PKG.iterdir():
        if p.name.startswith("__pycache__") or p.name in ("__init__.py", "py.typed"):
            continue
        name = p.stem if p.suffix == ".py" else p.name
        if p.is_dir() and not (p / "__init__.py").exists():
            continue
        assert name in LAYER_OF, f"symbt/{p.name} is in no layer"


def test_at_most_eight_modules_directly_in_the_package():
    mods = [p.name for p in PKG.glob("*.py")]
    assert len(mods) <= MAX_TOP_LEVEL_MODULES, mods


def test_no_upward_import():
    bad = []
    for path in _sources():
        own = _component(_module_name(path)) if path.parent != PKG or path.name != "__init__.py" else None
        if own is None:
            continue  # symbt/__init__.py itself only loads layers lazily by name
        for line, target in _imports(path):
            comp = _component(target)
            if comp is None or comp == own:
                continue
            if comp not in LAYER_OF:
                continue  # an attribute imported from a module, e.g. "symbt.paper.EXAMPLE"
            if _layer(comp) > _layer(own):
                bad.append(f"{path.relative_to(PKG.parent)}:{line} imports {target} "
                           f"(layer {_layer(comp)} > {_layer(own)})")
    assert not bad, "upward imports:\n" + "\n".join(bad)


def _module_graph() -> dict[str, set[str]]:
    modules = {_module_name(p): p for p in _sources()}
    graph: dict[str, set[str]] = {}
    for name, path in modules.items():
        deps = set()
        for _, target in _imports(path):
            target = _resolve(target, modules)
            if target.startswith("symbt.") and target != name:
                deps.add(target)
        graph[name] = deps
    return graph


def _resolve(target: str, modules) -> str:
    """The longest module prefix of an imported name (``pkg.mod.attr`` -> ``pkg.mod``)."""
    while target and target not in modules:
        target = target.rpartition(".")[0]
    return target


def _pkg_of(name: str) -> str:
    return ".".join(name.split(".")[:2])


def _is_package_of(package: str, module: str) -> bool:
    return module.startswith(package + ".")


def _bad_cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components of the module graph (import cycles), sorted.

    The only edge left out is a submodule's import of a package that contains it (say
    ``symbt.codegen.cli`` importing a name from ``symbt.codegen``): the package ``__init__``
    runs before any of its submodules and re-exports them, so that edge closes no cycle a
    reader must untangle.  Every other cycle -- between layers, or between two submodules of
    one package -- is reported.
    """
    graph = {v: {w for w in ws if not _is_package_of(w, v)} for v, ws in graph.items()}
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    on: set[str] = set()
    stack: list[str] = []
    out: list[list[str]] = []
    counter = [0]

    def strong(v: str) -> None:
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(graph.get(v, ())):
            if w not in index:
                strong(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            strong(v)
    return sorted(out)


def test_cycle_detector_catches_a_cycle_between_layers():
    g = {"symbt.claims": {"symbt.claims.base"}, "symbt.claims.base": {"symbt.report.html"},
         "symbt.report.html": {"symbt.claims"}}
    assert _bad_cycles(g) == [["symbt.claims", "symbt.claims.base", "symbt.report.html"]]
    assert _bad_cycles({"symbt.codegen": {"symbt.codegen.cli"}, "symbt.codegen.cli": {"symbt.codegen"}}) == []


def test_cycle_detector_sees_a_cycle_between_submodules_behind_their_package():
    # numeric/__init__ re-exports a and b, which import each other and the package:
    # the package edge is excused, the a <-> b circle is not
    g = {"symbt.numeric": {"symbt.numeric.a", "symbt.numeric.b"},
         "symbt.numeric.a": {"symbt.numeric", "symbt.numeric.b"},
         "symbt.numeric.b": {"symbt.numeric", "symbt.numeric.a"},
         "symbt.numeric.c": {"symbt.numeric"}}
    assert _bad_cycles(g) == [["symbt.numeric.a", "symbt.numeric.b"]]
    # a chain a -> b -> c -> a through three submodules is one component
    g = {"symbt.numeric.a": {"symbt.numeric.b"}, "symbt.numeric.b": {"symbt.numeric.c"},
         "symbt.numeric.c": {"symbt.numeric.a"}}
    assert _bad_cycles(g) == [["symbt.numeric.a", "symbt.numeric.b", "symbt.numeric.c"]]


def test_from_package_import_submodule_is_an_edge_to_the_submodule():
    modules = {"symbt.numeric", "symbt.numeric.kernels", "symbt.numeric.errors", "symbt.numeric.jit"}
    src = "from . import kernels\nfrom .errors import InvalidInputError\nfrom . import bt_step\n"
    edges = {_resolve(t, modules) for _, t in _imports_of("symbt.numeric.jit", False, src)}
    # the first two name submodules; only the third imports a name defined by the package's __init__
    assert edges == {"symbt.numeric.kernels", "symbt.numeric.errors", "symbt.numeric"}
    src = "from . import kernels\nfrom .errors import InvalidInputError\n"
    edges = {_resolve(t, modules) for _, t in _imports_of("symbt.numeric.jit", False, src)}
    assert edges == {"symbt.numeric.kernels", "symbt.numeric.errors"}


def test_no_import_cycle():
    cycles = _bad_cycles(_module_graph())
    assert not cycles, "import cycles: " + "; ".join(" <-> ".join(c) for c in cycles)


# the layers inside symbt.numeric (docs/architecture.md): the step written once, in core, depends on no backend
NUMERIC_LAYERS = (("core",), ("float64",), ("multiprec",), ("backends", "dispatch"), ("flow",))
NUMERIC_LAYER_OF = {name: i for i, names in enumerate(NUMERIC_LAYERS) for name in names}


def _numeric_part(module: str) -> str | None:
    parts = module.split(".")
    return parts[2] if len(parts) > 2 and parts[:2] == ["symbt", "numeric"] else None


def test_numeric_sub_packages_import_downwards():
    bad = []
    for name, deps in _module_graph().items():
        own = _numeric_part(name)
        if own is None:
            continue
        assert own in NUMERIC_LAYER_OF, f"{name} is in no layer of NUMERIC_LAYERS"
        for dep in deps:
            other = _numeric_part(dep)
            if other is not None and NUMERIC_LAYER_OF[other] > NUMERIC_LAYER_OF[own]:
                bad.append(f"{name} imports {dep}")
    assert not bad, "upward imports inside symbt.numeric:\n" + "\n".join(sorted(bad))


def test_no_handwritten_module_over_500_lines():
    long = []
    for p in _sources():
        if "generated" in p.parts:
            continue
        n = len(p.read_text(encoding="utf-8").splitlines())
        if n > MAX_LINES:
            long.append(f"{p.relative_to(PKG.parent)}: {n} lines")
    assert not long, "\n".join(long)


@pytest.mark.parametrize("module", ["symbt.numeric", "symbt.reference", "symbt.generated.toda3"])
def test_sympy_free_layers(module):
    code = f"import sys, {module}; print('sympy' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False", f"{module} imports sympy"
