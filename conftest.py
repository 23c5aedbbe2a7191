"""Collection for ``pytest`` from the checkout, so that the doctests pass on a core install too.

A module that imports an optional extra at module level is not collected without it; a doctest
whose example needs an extra is skipped, with the reason, without it.  (The code itself says which
extra to install when it is used; ``tests/`` skips such tests in the same way.)
"""
from __future__ import annotations

import importlib.util

import pytest

#: module file -> the optional dependency it imports at module level
_IMPORTS = {"symbt/numeric/arb.py": "flint"}

#: doctest (module or object, dotted) -> the optional dependency its examples need
_NEEDS = {
    "symbt.numeric.certified": "flint",
    "symbt.numeric.mpfast.arb_step": "flint",
    "symbt.numeric.qd": "numba",
    "symbt.proof.flint_exact": "flint",
    "symbt.numeric.dask_orbit": "dask",
}


def _missing(dep: str) -> bool:
    return importlib.util.find_spec(dep) is None


collect_ignore = [path for path, dep in _IMPORTS.items() if _missing(dep)]


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    for item in items:
        if not isinstance(item, pytest.DoctestItem):
            continue
        for name, dep in _NEEDS.items():
            if (item.name == name or item.name.startswith(name + ".")) and _missing(dep):
                item.add_marker(pytest.mark.skip(reason=f"needs the optional dependency {dep!r}"))
