"""Typing holds beyond ``symbt.numeric`` (issue 22, item 5), checked without running mypy.

``mypy symbt`` (CI) is the real check; these tests keep its configuration honest and fast to
see: the strict packages are listed in ``pyproject.toml``, every function there is annotated (the
rule ``disallow_untyped_defs`` enforces, read off the syntax tree), and the numeric files of the
typing pass keep their ``Any`` count down (the aliases that are ``Any`` on purpose are named, once,
in ``symbt.numeric.core``)."""
from __future__ import annotations

import ast
import fnmatch
from pathlib import Path

import pytest

import symbt

PKG = Path(symbt.__file__).resolve().parent
STRICT = ("symbt.numeric.*", "symbt.symbolic.*", "symbt.proof.*", "symbt.reference.*", "symbt.engine.*",
          "symbt.report.*", "symbt.codegen.*")


def _overrides() -> list[dict]:
    try:
        import tomllib
    except ModuleNotFoundError:  # Python 3.10
        tomllib = pytest.importorskip("tomli")
    config = tomllib.loads((PKG.parent / "pyproject.toml").read_text(encoding="utf-8"))
    return config["tool"]["mypy"]["overrides"]


def _strict_setting(module: str, key: str = "disallow_untyped_defs") -> bool:
    """``key`` (a mypy flag) for ``module`` as mypy resolves it: an exact name beats a pattern, and
    of two patterns the longer (more specific) one wins."""
    best: tuple[int, bool] | None = None
    for o in _overrides():
        if key not in o:
            continue
        for m in o["module"]:
            if m == module:
                rank = 10_000
            elif m.endswith(".*") and (module == m[:-2] or fnmatch.fnmatchcase(module, m)):
                rank = len(m)
            else:
                continue
            if best is None or rank >= best[0]:
                best = (rank, bool(o[key]))
    return bool(best and best[1])


def _matches(module: str, patterns: list[str]) -> bool:
    return any(m == module or (m.endswith(".*") and (module == m[:-2] or fnmatch.fnmatchcase(module, m)))
               for m in patterns)


def _module(path: Path) -> str:
    parts = list(path.relative_to(PKG.parent).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _untyped(tree: ast.AST) -> list[tuple[int, str]]:
    """``(line, name)`` of every def that ``disallow_untyped_defs`` refuses."""
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.ClassDef):
            for item in node.body:
                if isinstance(item, (ast.FunctionDef, ast.AsyncFunctionDef)):
                    item.is_method = True
        if not isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            continue
        a = node.args
        params = a.posonlyargs + a.args + a.kwonlyargs + [x for x in (a.vararg, a.kwarg) if x]
        if getattr(node, "is_method", False) and (a.posonlyargs + a.args) and not any(
                isinstance(d, ast.Name) and d.id == "staticmethod" for d in node.decorator_list):
            params = params[1:]                      # self / cls
        missing_param = any(p.annotation is None for p in params)
        # mypy lets ``__init__`` omit ``-> None`` when some argument is annotated
        init_ok = node.name == "__init__" and params and not missing_param
        if missing_param or (node.returns is None and not init_ok):
            out.append((node.lineno, node.name))
    return out


@pytest.mark.parametrize("key", ["disallow_untyped_defs", "disallow_any_generics"])
def test_strict_packages_are_configured(key):
    for pattern in STRICT:
        probe = pattern.replace("*", "anything")
        assert _strict_setting(probe, key), f"{pattern} is not under {key} in pyproject.toml"


def test_no_module_of_a_strict_package_is_exempted():
    # the codegen rewrite has landed: no override may switch ``disallow_untyped_defs`` off again
    exempt = [m for o in _overrides() if o.get("disallow_untyped_defs") is False for m in o["module"]
              if any(_matches(m.replace("*", "anything"), [p]) for p in STRICT)]
    assert not exempt, f"strict modules excepted from disallow_untyped_defs: {exempt}"


def test_a_function_without_annotations_is_found():
    tree = ast.parse("def f(x):\n    return x\nclass C:\n    def m(self, y: int) -> int:\n        return y\n"
                     "    def n(self, z):\n        pass\n")
    assert _untyped(tree) == [(1, "f"), (6, "n")]


@pytest.mark.parametrize("pattern", STRICT)
def test_every_function_of_a_strict_package_is_annotated(pattern):
    top = PKG / pattern.split(".")[1]
    found = []
    for path in sorted(top.rglob("*.py")):
        mod = _module(path)
        exempt = any(o.get("disallow_untyped_defs") is False and _matches(mod, o["module"]) for o in _overrides())
        if "__pycache__" in path.parts or exempt:   # the modules pyproject.toml names as not yet strict
            continue
        found += [f"{path.relative_to(PKG.parent)}:{line} {name}"
                  for line, name in _untyped(ast.parse(path.read_text(encoding="utf-8")))]
    assert not found, "functions without annotations under disallow_untyped_defs:\n" + "\n".join(found)


#: (a bare ``type`` is ``type[object]`` to mypy, not refused)
_GENERICS = {"dict", "list", "tuple", "set", "frozenset", "Callable", "OrderedDict", "Sequence", "Mapping", "Iterable",
             "Iterator"}


def _bare_generics(tree: ast.AST) -> list[tuple[int, str]]:
    """``(line, name)`` of every generic named without parameters in an annotation or a base class (what
    ``disallow_any_generics`` refuses; ``np.ndarray`` has default parameters in numpy 2 and is not one)."""
    roots: list[ast.AST] = []
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            a = node.args
            params = a.posonlyargs + a.args + a.kwonlyargs + [x for x in (a.vararg, a.kwarg) if x]
            roots += [p.annotation for p in params if p.annotation is not None]
            roots += [node.returns] if node.returns is not None else []
        elif isinstance(node, ast.AnnAssign):
            roots.append(node.annotation)
        elif isinstance(node, ast.ClassDef):
            roots += node.bases
    out = []
    for root in roots:
        subscripted = {id(n.value) for n in ast.walk(root) if isinstance(n, ast.Subscript)}
        for n in ast.walk(root):
            name = n.id if isinstance(n, ast.Name) else n.attr if isinstance(n, ast.Attribute) else None
            if name in _GENERICS and id(n) not in subscripted:
                out.append((n.lineno, name))
    return out


def test_a_bare_generic_is_found():
    tree = ast.parse("def f(x: dict, y: list[int]) -> tuple:\n    z: Callable[..., int]\n    w: OrderedDict = 0\n"
                     "class C(tuple):\n    pass\nclass D(tuple[int, ...]):\n    pass\n")
    assert sorted(_bare_generics(tree)) == [(1, "dict"), (1, "tuple"), (3, "OrderedDict"), (4, "tuple")]


@pytest.mark.parametrize("pattern", STRICT)
def test_no_bare_generic_in_a_strict_package(pattern):
    top = PKG / pattern.split(".")[1]
    found = [f"{path.relative_to(PKG.parent)}:{line} {name}" for path in sorted(top.rglob("*.py"))
             if "__pycache__" not in path.parts
             for line, name in _bare_generics(ast.parse(path.read_text(encoding="utf-8")))]
    assert not found, "generics without parameters under disallow_any_generics:\n" + "\n".join(found)


#: the numeric files of the typing pass and their literal ``Any`` (names in the syntax tree); 555 before
TYPED_NUMERIC = (
    "core/inputs.py", "core/step.py", "core/context.py", "core/monodromy.py", "core/problem.py",
    "core/errors.py", "core/limits.py", "dispatch.py", "backends.py", "__init__.py", "flow/coefficients.py",
    "flow/field.py", "flow/invariants.py", "flow/phi.py", "float64/orbit.py", "float64/rows.py",
    "float64/step.py", "float64/dask_orbit.py", "multiprec/runners.py", "multiprec/certified.py",
    "multiprec/arb.py")
ANY_BUDGET = 20


def _any_count(path: Path) -> int:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    return sum(1 for n in ast.walk(tree)
               if (isinstance(n, ast.Name) and n.id == "Any") or (isinstance(n, ast.Attribute) and n.attr == "Any"))


def test_numeric_signatures_say_what_they_take():
    counts = {f: _any_count(PKG / "numeric" / f) for f in TYPED_NUMERIC if (PKG / "numeric" / f).is_file()}
    assert sum(counts.values()) <= ANY_BUDGET, {f: c for f, c in counts.items() if c}


# --- vocabularies: one Literal each, the runtime tuple read off it, a bad value refused once with a typed error ---

def test_vocabulary_literals_are_the_checked_tuples():
    import inspect
    from typing import get_args

    from symbt.codegen import LANGUAGES, Language, generate
    from symbt.numeric import BackendName, CertifiedMethod, Float64Backend, certified_orbit, dask_orbit
    from symbt.numeric.backends import check_name
    from symbt.numeric.float64.orbit import ORBIT_BACKENDS
    from symbt.numeric.multiprec.certified import CERTIFIED_METHODS

    assert ORBIT_BACKENDS == get_args(Float64Backend) == ("auto", "numba", "python", "numpy")
    # BackendName is built from Float64Backend: the float64 names are not written twice
    assert get_args(BackendName) == ORBIT_BACKENDS + ("qd", "flint", "mpmath")
    assert CERTIFIED_METHODS == get_args(CertifiedMethod) == ("auto", "lohner", "ball")
    assert LANGUAGES == get_args(Language) == ("python", "c")
    for fn, param, alias in ((certified_orbit, "method", "CertifiedMethod"), (dask_orbit, "backend", "Float64Backend"),
                             (generate, "target", "Language")):
        assert inspect.signature(fn).parameters[param].annotation == alias, (fn.__name__, param)
    for name in get_args(BackendName):
        check_name(name, "float64" if name in ORBIT_BACKENDS else "mpmath")


def test_dask_orbit_refuses_an_unknown_backend_at_the_call():
    # checked when the graph is built (before: only when a chunk was computed), and before dask is imported
    from symbt.numeric import InvalidInputError, dask_orbit

    with pytest.raises(InvalidInputError, match="backend must be one of"):
        dask_orbit([[-20.0, 10.0, 1.0]], [[1.0, 0.0, 0.9]], 10.0, 5.0, 2, backend="qd")


def test_certified_orbit_refuses_an_unknown_method():
    pytest.importorskip("flint")
    from symbt.numeric import InvalidInputError, certified_orbit

    with pytest.raises(InvalidInputError, match="method must be one of"):
        certified_orbit([-20, 10, 1], [1, 0, 0.9], 10, 5, 1, method="taylor")


def test_codegen_refuses_an_unknown_target():
    from symbt.codegen import file_names
    from symbt.codegen.user.files import file_names as user_file_names

    with pytest.raises(ValueError, match="unknown target 'java'"):
        file_names((2,), target="java")
    with pytest.raises(ValueError, match="unknown target 'java'"):
        user_file_names(["m"], target="java")
