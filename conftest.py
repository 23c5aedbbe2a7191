"""Collection for ``pytest`` from the checkout, so that the doctests pass on a core install too.

A module that imports an optional extra at module level is not collected without it; a doctest
whose example needs an extra is skipped, with the reason, without it.  (The code itself says which
extra to install when it is used; ``tests/`` skips such tests in the same way.)
"""
from __future__ import annotations

import importlib.util

import pytest

#: module file -> the optional dependency it imports at module level
_IMPORTS = {"symbt/numeric/multiprec/arb.py": "flint", "symbt/numeric/multiprec/lohner.py": "flint",
            "symbt/numeric/multiprec/lohner_checks.py": "flint"}

#: doctest (module or object, dotted) -> the optional dependency its examples need
_NEEDS = {
    "symbt.numeric.multiprec.certified": "flint",
    "symbt.benchmarks.certified": "flint",
    "symbt.numeric.multiprec.runners.arb_step": "flint",
    "symbt.numeric.multiprec.runners.flint_orbit": "flint",
    "symbt.numeric.multiprec.qd": "numba",
    "symbt.proof.flint_exact": "flint",
    "symbt.numeric.float64.dask_orbit": "dask",
    "symbt.numeric.float64.orbit.kernel_batch_step": "numba",
    "symbt.engine.coverage.scan_labels": "pylatexenc",
    "symbt.engine.labels": "pylatexenc",
    "symbt.engine.latex": "pylatexenc",
    "symbt.engine.site": "pylatexenc",
    "symbt.report.site.mathml": "latex2mathml",
}
#: the same, for one doctest exactly (not the objects below it): a package's own docstring
_NEEDS_EXACT = {"symbt.report.site": "latex2mathml"}


def _missing(dep: str) -> bool:
    return importlib.util.find_spec(dep) is None


collect_ignore = [path for path, dep in _IMPORTS.items() if _missing(dep)]


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    for item in items:
        if not isinstance(item, pytest.DoctestItem):
            continue
        needs = [dep for name, dep in _NEEDS.items() if item.name == name or item.name.startswith(name + ".")]
        needs += [dep for name, dep in _NEEDS_EXACT.items() if item.name == name]
        for dep in needs:
            if _missing(dep):
                item.add_marker(pytest.mark.skip(reason=f"needs the optional dependency {dep!r}"))
