r"""What the numeric screen measures a difference against (scene ``checker``; issue 21, item 3).

The screen judged every point relative to :math:`\max(|l|, |r|, 1)`.  The floor 1 kept rounding noise where both
sides vanish from counting as a residual of 1, but made the test absolute for statements far below 1:
:math:`10^{-50} \sin x = 2 \cdot 10^{-50} \sin x` was *verified*.  The scale is now
:math:`\max(|l|, |r|, \min(1, m))`, :math:`m` the size of the sides' terms
(:func:`symbt.proof.magnitude.magnitude`), and the re-evaluation compares the two differences :math:`l - r`
absolutely, over that scale.

* ``checker.screen_scale`` -- the residual of a false statement recomputed at its counterexample (by SymPy at 50
  digits, ``checker.screen_arithmetic``'s definition) where the floor used to matter: sides near
  :math:`10^{-50}` (relative residual 1/2) and a sum that is :math:`10^{-20}` off 0 (judged against its terms of
  size 1); :math:`\sin^2 x + \cos^2 x - 1 = 0` holds (its rounding is no residual); a 14-digit cancellation
  :math:`(x + 10^7)^2 - 10^{14} - 2 \cdot 10^7 x = x^2` is verified after the re-evaluation, its error the two
  evaluations' drift relative to the sides, alike at size 1 and times :math:`10^{50}`.
"""
from __future__ import annotations

from typing import Any

import mpmath as mp
import sympy as sp

from ._facts import Facts
from ._facts import facts_failed as _bad
from ._facts import facts_verified as _ok
from .base import Outcome, claim


def _exact(value: sp.Expr) -> sp.Expr:
    """A printed number with its decimals as exact rationals."""
    return value.xreplace({f: sp.Rational(str(f)) for f in value.atoms(sp.Float)})


def _residual_at(lhs: sp.Expr, rhs: sp.Expr, point: dict[str, str]) -> Any:
    """``|l - r| / max(|l|, |r|, min(1, size))`` at a printed point, at 50 digits (the definition, evaluated by
    SymPy); the terms' size is their largest modulus, the sides' summands (no cell has a sum inside a product)."""
    with mp.workdps(50):
        # the printed decimals taken exactly (a Float's own 20 digits would cap evalf where the sides cancel)
        sub = {s: _exact(sp.sympify(point[str(s)].replace(" ", ""))) for s in (lhs - rhs).free_symbols}
        lv, rv = (mp.mpmathify(side.xreplace(sub).evalf(50)) for side in (lhs, rhs))
        size = max(abs(mp.mpmathify(t.xreplace(sub).evalf(50)))
                   for side in (lhs, rhs) for t in sp.Add.make_args(side))
        return abs(lv - rv) / max(abs(lv), abs(rv), min(mp.mpf(1), size))


def residual_cells(cells: Any) -> Facts:
    """For each ``(what, lhs, rhs)`` of a false statement, screened at 30 digits with and without the re-evaluation:
    false, its residual within ``1e-12`` of :func:`_residual_at` at its counterexample, re-evaluated or not."""
    from ..proof.screen import screen

    got: Facts = []
    for what, lhs, rhs in cells:
        for recheck in (True, False):
            r = screen(lhs, rhs, {}, 30, 3, 5, {}, recheck=recheck)
            want = _residual_at(lhs, rhs, r.point or {}) if r.point else mp.inf
            got.append((f"{what} ({'re-evaluated' if recheck else 'first evaluation'}): false, residual",
                        (r.status, bool(abs(r.residual - want) <= 1e-12 * want), r.rechecked == int(recheck)),
                        ("false", True, True)))
    return got


@claim("checker.screen_scale", equation="checker", scene="checker",
       where="symbt.proof.screen: _scale and the re-evaluation's error (symbt.proof.magnitude for the terms' size)",
       statement="the residual is |l - r| / max(|l|, |r|, min(1, size of the terms)) with no absolute floor: "
                 "1e-50 sin x = 2e-50 sin x is false at residual 1/2 and sin^2 x + cos^2 x - 1 - 1e-20 = 0 at 1e-20 "
                 "(first evaluation and re-evaluation, 1e-12); sin^2 x + cos^2 x - 1 = 0 holds; a 14-digit "
                 "cancellation is verified after two re-evaluations with error < 1e-22, at size 1 and times 1e50; a "
                 "verified statement reports the largest residual of its points")
def screen_scale() -> Outcome:
    from ..proof.screen import screen

    got: Facts = []
    pos = sp.Symbol("x", positive=True)
    tiny = sp.Integer(10) ** -50
    cells = (("both near 1e-50", tiny * sp.sin(pos), 2 * tiny * sp.sin(pos)),
             # e = 0 is judged against e's terms (size about 1), not against 0: off by 1e-20 is false at 1e-20
             ("a sum off by 1e-20 against 0", sp.sin(pos) ** 2 + sp.cos(pos) ** 2 - 1 - sp.Integer(10) ** -20,
              sp.Integer(0)))
    got += residual_cells(cells)
    # a sum that is 0 is measured against its terms: the rounding of sin^2 + cos^2 - 1 is not a residual of size 1
    r = screen(sp.sin(pos) ** 2 + sp.cos(pos) ** 2 - 1, sp.Integer(0), {}, 30, 4, 1, {})
    got.append(("sin^2 x + cos^2 x - 1 = 0 (the sides 0 up to rounding)", r.status, "verified"))
    # a 14-digit cancellation: the first evaluation is good to about 1e-26, short of every digit asked, and the two
    # evaluations' drift (about 1e-26 of the sides) is the error -- alike times 1e50, where it is 1e24 absolutely
    for k in (0, 50):
        big = sp.Integer(10) ** k
        r = screen(big * ((pos + 10 ** 7) ** 2 - 10 ** 14 - 2 * 10 ** 7 * pos), big * pos ** 2, {}, 30, 2, 1, {})
        got.append((f"14-digit cancellation times 1e{k}: status, re-evaluated, error < 1e-22",
                    (r.status, r.rechecked, r.error < 1e-22), ("verified", 2, True)))
    # a verified statement reports its largest residual over the points (off by 1e-28 x: a different residual at
    # each point, every one above 1e-30, so each is re-evaluated at 70 digits and known to many digits)
    lhs, rhs = (1 + sp.Integer(10) ** -28 * pos) * sp.sin(pos), sp.sin(pos)
    r = screen(lhs, rhs, {}, 30, 4, 3, {})
    each = [_residual_at(lhs, rhs, pt) for pt in r.points]
    got.append(("verified: the largest residual of its points",
                (r.status, bool(abs(r.residual - max(each)) <= 1e-9 * max(each))), ("verified", True)))
    bad = _bad("the screen's scale", got)
    return bad or _ok("screen's residuals recomputed at the counterexample where the floor used to matter",
                      f"{len(got)} facts: 2 residual cells x 2 evaluations, a sum that is 0, a 14-digit "
                      "cancellation at two sizes, the largest residual", "sampled")
