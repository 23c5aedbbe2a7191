"""Which files ``symbt codegen`` writes and checks, rendered with their provenance headers.

* Python (default): ``__init__.py`` and ``toda{N}.py`` for every N asked (default
  :data:`TARGETS` = (2, 3)) into ``symbt/generated`` or ``--out DIR``;
* C (``--target c``): ``toda{N}.c`` and ``toda{N}.h`` into ``--out DIR``.

Rendering is deterministic (fixed CSE names, canonical CSE order, no unordered
iteration); writing is atomic (:func:`symbt._files.atomic_write`) and skips files
whose bytes are already right.

>>> file_names((2, 3))
['__init__.py', 'toda2.py', 'toda3.py']
>>> file_names((5,), "c")
['toda5.c', 'toda5.h']
"""
from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path

from .._files import atomic_write, directory_problem
from .forms import LANGUAGES, LOOP_FROM, Language, form_of
from .provenance import PACKAGE, derivation_hash, file_problem, with_header

__all__ = ["TARGETS", "LANGUAGES", "DEFAULT_OUT", "LOOP_FROM", "form_of", "file_names", "render", "generate",
           "check"]

#: the lattice sizes emitted by default (the committed ``symbt/generated/toda{2,3}.py``)
TARGETS = (2, 3)

DEFAULT_OUT = PACKAGE / "generated"


def _check_args(ns: Iterable[int], target: Language) -> tuple[int, ...]:
    ns = tuple(ns)
    if target not in LANGUAGES:
        raise ValueError(f"unknown target {target!r} (choose from {', '.join(LANGUAGES)})")
    if not ns or any(isinstance(n, bool) or not isinstance(n, int) or n < 2 for n in ns):
        raise ValueError(f"lattice sizes must be integers >= 2, got {ns!r}")
    return tuple(sorted(set(ns)))


def file_names(ns: Iterable[int] = TARGETS, target: Language = "python") -> list[str]:
    ns = _check_args(ns, target)
    if target == "c":
        return [f"toda{N}.{ext}" for N in ns for ext in ("c", "h")]
    return ["__init__.py"] + [f"toda{N}.py" for N in ns]


def render(ns: Iterable[int] = TARGETS, target: Language = "python") -> dict[str, str]:
    """File name -> full text of every generated file (runs the derivations)."""
    import sympy

    from .emit import module_body, package_init_body

    ns = _check_args(ns, target)
    dhash = derivation_hash()
    files = {}
    if target == "c":
        from .emit_c import c_files

        for N in ns:
            src, hdr = c_files(N)
            desc = f"toda{N} (N={N}, C99, {form_of(N)} form)"
            files[f"toda{N}.c"] = with_header(src, desc, dhash, sympy.__version__, "//")
            files[f"toda{N}.h"] = with_header(hdr, desc, dhash, sympy.__version__, "//")
        return files
    files["__init__.py"] = with_header(package_init_body(), "package", dhash, sympy.__version__, "#")
    for N in ns:
        files[f"toda{N}.py"] = with_header(module_body(N), f"toda{N} (N={N}, {form_of(N)} form)", dhash,
                                           sympy.__version__, "#")
    return files


def generate(out: str | Path | None = None, ns: Iterable[int] = TARGETS, target: Language = "python") -> list[Path]:
    """Render the files and write those that differ into ``out`` (default ``symbt/generated``; required for C).

    Returns the paths actually written (files whose bytes are already right are left alone and
    not listed).  If anything must be written and ``out`` cannot take it, ``PermissionError``
    is raised before any file is touched.
    """
    if out is None and target == "c":
        raise ValueError("the C target needs an output directory (--out DIR)")
    out = Path(out) if out is not None else DEFAULT_OUT
    texts = render(ns, target)
    todo = {out / name: text for name, text in texts.items()
            if not ((out / name).is_file() and (out / name).read_bytes() == text.encode("utf-8"))}
    problem = directory_problem(out) if todo else None
    if problem:
        raise PermissionError(problem)      # all or nothing: no half-regenerated package
    for path, text in todo.items():
        atomic_write(path, text)
    return list(todo)


def check(out: str | Path | None = None, ns: Iterable[int] = TARGETS, target: Language = "python",
          dhash: str | None = None) -> list[str]:
    """Problems with the generated files in ``out`` (empty list = up to date).  SymPy-free."""
    if out is None and target == "c":
        raise ValueError("the C target needs an output directory (--out DIR)")
    out = Path(out) if out is not None else DEFAULT_OUT
    dhash = derivation_hash() if dhash is None else dhash
    problems = [file_problem(out / name, dhash) for name in file_names(ns, target)]
    return [p for p in problems if p]
