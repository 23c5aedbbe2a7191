"""Ranges of a domain's variables: how each one is drawn (see :mod:`symbt.proof.domain`).

Every draw is a double (or an ``int``) turned exactly into an mpmath number, so a point is the
same at every working precision.
"""
from __future__ import annotations

import math
import random
from dataclasses import dataclass
from typing import Any

import mpmath as mp

__all__ = ["Range", "uniform", "log_uniform", "integers", "complex_box", "as_range"]


@dataclass(frozen=True)
class Range:
    """How one variable of a :class:`Domain` is drawn (made by :func:`uniform` and its siblings).

    >>> r = uniform(-1, 1)
    >>> str(r), -1 <= r.draw(random.Random(0)) <= 1
    ('uniform(-1, 1)', True)
    """

    kind: str
    lo: Any
    hi: Any

    def draw(self, rng: random.Random) -> Any:
        """One value: an mpmath number (exactly the double drawn) or, for :func:`integers`, an ``int``."""
        if self.kind == "uniform":
            return mp.mpf(rng.uniform(self.lo, self.hi))
        if self.kind == "log_uniform":
            return mp.mpf(math.exp(rng.uniform(math.log(self.lo), math.log(self.hi))))
        if self.kind == "integers":
            return rng.randint(self.lo, self.hi)
        return mp.mpc(rng.uniform(self.lo.real, self.hi.real), rng.uniform(self.lo.imag, self.hi.imag))

    def __str__(self) -> str:
        lo, hi = self.lo, self.hi
        return (f"{self.kind}({lo:g}, {hi:g})" if self.kind != "complex_box"
                else f"complex_box(re=({lo.real:g}, {hi.real:g}), im=({lo.imag:g}, {hi.imag:g}))")


def _interval(name: str, lo: Any, hi: Any) -> tuple[float, float]:
    try:
        a, b = float(lo), float(hi)
    except (TypeError, ValueError):
        a = b = math.nan
    if not (math.isfinite(a) and math.isfinite(b) and a < b):
        raise ValueError(f"{name}(lo, hi) needs real numbers lo < hi, got {lo!r}, {hi!r}")
    return a, b


def uniform(lo: float, hi: float) -> Range:
    """A real variable, uniform on ``[lo, hi]``.

    >>> uniform(0, 2)
    Range(kind='uniform', lo=0.0, hi=2.0)
    """
    return Range("uniform", *_interval("uniform", lo, hi))


def log_uniform(lo: float, hi: float) -> Range:
    """A positive variable whose logarithm is uniform on ``[log lo, log hi]`` (scales over decades).

    >>> log_uniform(1e-3, 1e3).kind
    'log_uniform'
    """
    a, b = _interval("log_uniform", lo, hi)
    if a <= 0:
        raise ValueError(f"log_uniform(lo, hi) needs 0 < lo, got {lo!r}")
    return Range("log_uniform", a, b)


def integers(lo: int, hi: int) -> Range:
    """An integer variable, uniform on ``lo, lo + 1, ..., hi`` (both included).

    >>> integers(1, 5).draw(random.Random(0)) in range(1, 6)
    True
    """
    if not all(isinstance(v, int) and not isinstance(v, bool) for v in (lo, hi)) or lo > hi:
        raise ValueError(f"integers(lo, hi) needs integers lo <= hi, got {lo!r}, {hi!r}")
    return Range("integers", lo, hi)


def complex_box(re: tuple[float, float], im: tuple[float, float]) -> Range:
    """A complex variable, uniform on the box ``re[0] <= Re z <= re[1]``, ``im[0] <= Im z <= im[1]``.

    >>> str(complex_box(re=(-1, 1), im=(0, 2)))
    'complex_box(re=(-1, 1), im=(0, 2))'
    """
    (a, b), (c, d) = _interval("complex_box re", *re), _interval("complex_box im", *im)
    return Range("complex_box", complex(a, c), complex(b, d))


def as_range(name: str, spec: Any) -> Range:
    """The :class:`Range` a :class:`~symbt.proof.domain.Domain` makes of ``spec`` for variable ``name``.

    >>> as_range("t", (0, 1)), as_range("n", range(1, 4)).hi, as_range("z", (-1j, 1 + 1j)).kind
    (Range(kind='uniform', lo=0.0, hi=1.0), 3, 'complex_box')
    """
    if isinstance(spec, Range):
        return spec
    if isinstance(spec, range):
        if spec.step != 1 or len(spec) == 0:
            raise ValueError(f"variable {name!r}: a range must be non-empty with step 1, got {spec!r}")
        return integers(spec.start, spec.stop - 1)
    if isinstance(spec, (tuple, list)) and len(spec) == 2:
        lo, hi = spec
        if isinstance(lo, complex) or isinstance(hi, complex):
            lo, hi = complex(lo), complex(hi)
            return complex_box(re=(lo.real, hi.real), im=(lo.imag, hi.imag))
        return uniform(lo, hi)
    raise TypeError(f"variable {name!r}: give a range as (lo, hi), range(a, b), uniform(...), log_uniform(...), "
                    f"integers(...) or complex_box(...), got {spec!r}")
