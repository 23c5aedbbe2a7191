"""The one TOML reader: ``tomllib`` (standard library from Python 3.11), else ``tomli`` (a dependency on 3.10).

>>> loads('[project]\\nname = "symbt"')["project"]["name"]
'symbt'
>>> try:
...     loads("name = ")
... except ValueError as exc:          # tomllib.TOMLDecodeError is a ValueError
...     print(type(exc).__name__)
TOMLDecodeError
"""
from __future__ import annotations

from typing import Any

try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10
    import tomli as tomllib

__all__ = ["loads"]


def loads(text: str) -> dict[str, Any]:
    """``text`` parsed as TOML; a ``ValueError`` (``TOMLDecodeError``) if it is not."""
    return tomllib.loads(text)
