"""Lazy public names of a package (PEP 562): a name loads its submodule on first use.

This keeps ``import symbt`` cheap and lets a fully cached ``symbt verify`` run without importing
SymPy, NumPy or mpmath: a package's ``__init__`` lists where each public name lives and binds the
two module hooks returned here.

>>> getattr_, dir_ = lazy_attributes("json", {"dumps": "json"}, ["dumps"])
>>> getattr_("dumps")([1])
'[1]'
>>> dir_()
['dumps']
"""
from __future__ import annotations

import importlib
from collections.abc import Callable, Iterable
from typing import Any

__all__ = ["lazy_attributes"]


def lazy_attributes(package: str, where: dict[str, str], public: Iterable[str]
                    ) -> tuple[Callable[[str], Any], Callable[[], list[str]]]:
    """``(__getattr__, __dir__)`` for ``package``: ``where[name]`` is the (relative) module of ``name``."""
    names = sorted(public)

    def __getattr__(name: str) -> Any:
        if name in where:
            return getattr(importlib.import_module(where[name], package), name)
        raise AttributeError(f"module {package!r} has no attribute {name!r}")

    def __dir__() -> list[str]:
        return names

    return __getattr__, __dir__
