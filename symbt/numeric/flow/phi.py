r"""The real Φ of the map (the flow coefficients ``c_k`` live in :mod:`symbt.numeric.flow.coefficients`).

Φ (paper eqs. ``vqqtmu``, ``newkmu``, App. B).  On the map,
``Φ = sum_k ln|(eta_k + mu)/(eta_k - mu)|`` equals ``ln|v(lam1)| - ln|v_z(lam2)|``
where ``v(lam1) = (tr1 - g1)/2`` and ``v_z(lam2) = (tr2 + g2)/2`` are the eigenvalues
of the two kernel vectors.  Written with traces this is

    Φ = branch * ( -sgn(tr1) arccosh(|tr1|/2) - sgn(tr2) arccosh(|tr2|/2) ).

The paper's eq. ``newkmu``, ``-arccosh(tr1/2) - arccosh(tr2/2)``, is the case
``tr > 2``, ``branch = +1`` only (for ``tr < -2`` it is not even real).

Examples
--------
>>> from symbt.numeric import phi
>>> round(float(phi([-20.0, 10.0, 1.0], [1.0, 0.0, 0.9], 10.0, 5.0)), 10)
14.8058092993
"""

from __future__ import annotations

import mpmath
import numpy as np
import numpy.typing as npt

from ..core.context import FLOAT, IV, MPValue
from ..core.errors import InvalidInputError, NoRealMapError
from ..core.inputs import ParamLike, StateLike, as_state_pair, check_branch, prepare_spectral_pair
from ..core.monodromy import neighbour_ratios
from ..core.step import eigen_slopes

__all__ = ["phi"]


def phi(p: StateLike, q: StateLike, lam0: ParamLike, mu: ParamLike, *,
        branch: int = 1) -> npt.NDArray[np.float64] | MPValue:
    """The real Φ of the map (see module docstring); O(N) per state.

    Only the trace condition ``|tr L(lam_i)| > 2`` is checked (Φ is a spectral
    quantity); :class:`NoRealMapError` otherwise.  float64: array of the batch
    shape (0-d for one state); mpmath: mpf.
    """
    branch = check_branch(branch)
    ctx, P, Q, shape = as_state_pair(p, q, lam0, mu)
    if ctx is IV:
        raise InvalidInputError("phi takes float64 or mpf inputs (interval arithmetic covers bt_step only)")
    lam0, mu = prepare_spectral_pair(ctx, lam0, mu, shape)
    if ctx is FLOAT and 0 in shape:
        return np.zeros(shape)  # an empty batch has an empty Φ
    r = neighbour_ratios(ctx, Q)
    out = 0
    with np.errstate(all="ignore"):
        for lam, name in ((lam0 + mu, "lam1"), (lam0 - mu, "lam2")):
            S = eigen_slopes(ctx, [lam + pj for pj in P], r, 1, need_slopes=False)
            if not ctx.all_positive(S.trace_ok):
                raise NoRealMapError("no real Φ: |tr L(%s)| <= 2" % name, condition="trace")
            L = ctx.acosh_half_abs(S.t, S.g, S.e)
            sgn = np.sign(S.t) if ctx is FLOAT else mpmath.sign(S.t)
            out = out - sgn * L
    out = branch * out
    if ctx is FLOAT:
        return np.asarray(out, dtype=float).reshape(shape)
    return +out
