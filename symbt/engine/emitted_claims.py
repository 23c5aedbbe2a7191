r"""The claims of a project's emitted functions: each ``symbt.emit`` declaration, three claims.

:func:`register_emitted` (called by :func:`symbt.engine.project.load` for a project with
``codegen`` sources) gives every declared function three claims in the scene ``codegen``,
owned by the module that declared it: ``emit.<module>.<name>.numpy``, ``.mpmath`` and ``.c``
(``skipped`` with the reason when the C file was not emitted or no compiler is present; ``todo``
when the declaration has no ``domain``).  Each checks the file's provenance (missing, stale or
hand-edited: ``failed``), then compares the emitted function, imported from disk, with its SymPy
source (:mod:`symbt.codegen.user.check`).
"""
from __future__ import annotations

import functools
from dataclasses import replace
from pathlib import Path

from ..claims.base import REGISTRY, SCENES, Claim, Outcome, failed, judge_cells, skipped, todo
from ..codegen.provenance import file_problem
from ..codegen.user.declare import EMISSIONS, Emission
from ..codegen.user.files import by_module, module_hash

__all__ = ["register_emitted", "FLAVOURS", "SCENE"]

FLAVOURS = ("numpy", "mpmath", "c")
SCENE = "codegen"


def _statement(e: Emission, flavour: str) -> str:
    what = {"numpy": "numpy float64", "mpmath": "mpmath", "c": "C99"}[flavour]
    return f"the emitted {e.module}.{e.name} ({what}) equals its SymPy source on the declared domain"


def _check(key: tuple[str, str], flavour: str, root: Path, out: Path, *, deep: bool = False) -> Outcome:
    from ..codegen.user.check import Comparison, compare, compiler, method_text

    e = EMISSIONS.get(key)
    if e is None:
        return failed("declaration", detail=f"{key[0]}.{key[1]} is no longer declared")
    if e.domain is None:
        return todo(f"emit({e.name!r}, ..., domain=symbt.Domain(...)) declares no domain to verify on")
    names = [f"{e.module}.c", f"{e.module}.h"] if flavour == "c" else [f"{e.module}.py"]
    if flavour == "c":
        if not (out / names[0]).is_file():
            return skipped(f"C target not emitted ({out / names[0]} missing; run `symbt codegen --target c`)")
        if compiler() is None:
            return skipped("no C compiler (cc, gcc or clang) on PATH")
    ems = by_module(EMISSIONS.values())[e.module]
    dh = module_hash(e.module, ems, root, out)
    problems = [p for p in (file_problem(out / n, dh) for n in names) if p]
    if problems:
        return failed("provenance", detail="; ".join(problems))
    seen = Comparison()
    table = compare(e, out / names[0], flavour, deep=deep, seen=seen)
    detail = "residual: the worst |emitted - reference| in units of the error bound (a point holds at <= 1)"
    if e.guards:        # points a guard refused on both sides are counted, not compared
        why = ", ".join(f"{c} {n}" for c, n in sorted(seen.conditions.items()))
        detail += f"; {seen.compared} points compared, {seen.refused} refused by a guard on both sides" + (
            f" ({why})" if why else "")
        if seen.compared == 0:
            return failed("domain", detail=f"every sampled point was refused by a guard: nothing compared; {detail}")
    res = judge_cells(table, printed=_statement(e, flavour), method=method_text(flavour), detail=detail)
    res = replace(res, digits=None)   # the residual is in units of the bound, not a relative error: no digits to count
    return res


def register_emitted(emissions: list[Emission], root: Path, out: Path) -> list[str]:
    """Register the claims of ``emissions`` (files in ``out``, derivation sources under ``root``); their ids."""
    ids = []
    for e in emissions:
        for fl in FLAVOURS:
            cid = f"emit.{e.module}.{e.name}.{fl}"
            check = functools.partial(_check, (e.module, e.name), fl, root, out)
            REGISTRY[cid] = Claim(id=cid, equation=f"{e.module}.{e.name}", statement=_statement(e, fl),
                                  check=check, scene=SCENE, func=_check, source_equation=e.equation,
                                  deep_check=functools.partial(check, deep=True), module=e.declared_in)
            ids.append(cid)
    SCENES.setdefault(SCENE, {"description": "emitted code vs its SymPy source", "deep": False})
    return ids
