r"""A user's emitted files: which, with what provenance, written atomically, and ``--check``.

``symbt codegen`` in a project whose ``[tool.symbt]`` lists ``codegen`` sources imports them
(each ``symbt.emit`` call declares a function) and writes, per emitted module,
``<out>/<module>.py`` (and with ``--target c`` ``<module>.c`` and ``<module>.h``).  ``out`` is
``codegen-out`` of ``[tool.symbt]`` (relative to that file), by default ``generated/`` beside it.

The provenance header is Zullo's (:mod:`symbt.codegen.provenance`); its *derivation hash*
covers, in this order: the generator version, symbt's user-codegen sources
(``symbt/codegen/user/*.py``, the printer and the typed runtime), and the **derivation sources** of the module --
the files of the modules that declared its functions and of every module of the user's
project they import, directly or not (a static scan of their ``import`` statements, so the
hash does not depend on what else the process imported).  A derivation change anywhere in that
chain makes the file *stale*; an edit of the file itself makes it *edited by hand*.

>>> file_names(["m"], "c")
['m.c', 'm.h']
"""
from __future__ import annotations

import ast
import hashlib
import importlib.util
import sys
from collections.abc import Iterable
from pathlib import Path

from ..._files import atomic_write
from ..forms import LANGUAGES, Language
from ..provenance import GENERATOR_VERSION, PACKAGE, file_problem, with_header
from .declare import Emission

__all__ = ["LANGUAGES", "file_names", "derivation_sources", "derivation_hash", "render", "generate", "check",
           "by_module"]

_GENERATOR = sorted((PACKAGE / "codegen" / "user").glob("*.py")) + [PACKAGE / "codegen" / "printer.py",
                                                                  PACKAGE / "codegen" / "runtime.py"]


def file_names(modules: Iterable[str], target: Language = "python") -> list[str]:
    if target not in LANGUAGES:
        raise ValueError(f"unknown target {target!r} (choose from {', '.join(LANGUAGES)})")
    mods = sorted(set(modules))
    return [f"{m}.py" for m in mods] if target == "python" else [f"{m}.{x}" for m in mods for x in ("c", "h")]


def by_module(emissions: Iterable[Emission]) -> dict[str, list[Emission]]:
    """Emitted module name -> its declarations (declaration order), modules sorted."""
    out: dict[str, list[Emission]] = {}
    for e in emissions:
        out.setdefault(e.module, []).append(e)
    return dict(sorted(out.items()))


def _module_file(name: str) -> Path | None:
    mod = sys.modules.get(name)
    f = getattr(mod, "__file__", None)
    if f is None:
        try:
            spec = importlib.util.find_spec(name)
        except (ImportError, ValueError):
            return None
        f = getattr(spec, "origin", None) if spec is not None else None
    return Path(f).resolve() if f and f.endswith(".py") else None


def _imports(path: Path, modname: str) -> set[str]:
    try:
        tree = ast.parse(path.read_bytes(), filename=str(path))
    except (OSError, SyntaxError, ValueError):
        return set()
    pkg = modname if path.name == "__init__.py" else modname.rpartition(".")[0]
    out: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            out |= {a.name for a in node.names}
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                parts = pkg.split(".") if pkg else []
                parts = parts[:len(parts) - (node.level - 1)]      # level 1: the package itself
                base = ".".join([*parts, base] if base else parts)
            if base:
                out.add(base)
                out |= {f"{base}.{a.name}" for a in node.names if a.name != "*"}
    return out


def derivation_sources(modules: Iterable[str], root: Path, exclude: Path | None = None) -> list[Path]:
    """The files of ``modules`` and of every module under ``root`` they import (sorted; ``exclude`` left out)."""
    root = root.resolve()
    seen: dict[str, Path] = {}
    todo = list(modules)
    while todo:
        name = todo.pop()
        if name in seen:
            continue
        f = _module_file(name)
        if f is None or root not in f.parents or (exclude is not None and exclude.resolve() in f.parents):
            continue
        seen[name] = f
        todo += sorted(_imports(f, name) - set(seen))
    return sorted(set(seen.values()))


def derivation_hash(sources: Iterable[Path], root: Path) -> str:
    h = hashlib.sha256()
    h.update(f"user generator {GENERATOR_VERSION}\0".encode())
    for f in _GENERATOR:
        h.update(f.relative_to(PACKAGE).as_posix().encode() + b"\0" + f.read_bytes() + b"\0")
    for f in sources:
        rel = f.relative_to(root.resolve()).as_posix() if root.resolve() in f.parents else f.name
        h.update(rel.encode() + b"\0" + f.read_bytes() + b"\0")
    return h.hexdigest()


def module_hash(module: str, emissions: list[Emission], root: Path, out: Path) -> str:
    """The derivation hash of the emitted module ``module``."""
    declaring = sorted({e.declared_in for e in emissions if e.module == module})
    return derivation_hash(derivation_sources(declaring, root, exclude=out), root)


def render(emissions: Iterable[Emission], root: Path, out: Path, target: Language = "python") -> dict[str, str]:
    """File name -> full text (provenance header + body) for every emitted module."""
    import sympy

    from .render import c_header, c_source, python_module
    from .typed import TEMPLATES

    files: dict[str, str] = {}
    for module, ems in by_module(emissions).items():
        dh = module_hash(module, ems, root, out)
        srcs = ", ".join(sorted({e.declared_in for e in ems}))
        desc = f"{module} (declared in {srcs})"
        if target == "python":
            body = python_module(module, ems, srcs, TEMPLATES.get(module))
            files[f"{module}.py"] = with_header(body, desc, dh, sympy.__version__, "#")
        elif target == "c":
            files[f"{module}.c"] = with_header(c_source(module, ems), desc + ", C99", dh, sympy.__version__, "//")
            files[f"{module}.h"] = with_header(c_header(module, ems), desc + ", C99", dh, sympy.__version__, "//")
        else:
            raise ValueError(f"unknown target {target!r} (choose from {', '.join(LANGUAGES)})")
    return files


def generate(emissions: Iterable[Emission], root: Path, out: Path, target: Language = "python") -> list[Path]:
    """Render and write (atomically; files already right are not touched) into ``out``."""
    written = []
    for name, text in render(list(emissions), root, out, target).items():
        path = out / name
        if not (path.is_file() and path.read_bytes() == text.encode("utf-8")):
            atomic_write(path, text)
        written.append(path)
    return written


def check(emissions: Iterable[Emission], root: Path, out: Path, target: Language = "python") -> list[str]:
    """One line per missing, stale or hand-edited file in ``out`` (empty: up to date)."""
    problems = []
    for module, ems in by_module(emissions).items():
        dh = module_hash(module, ems, root, out)
        for name in file_names([module], target):
            p = file_problem(out / name, dh)
            if p:
                problems.append(p)
    return problems
