r"""Certified orbits that stay sharp: a Lohner-type method (moving frame) in Arb ball arithmetic.

Plain ball arithmetic (:mod:`.certified`, ``method="ball"``) loses the correlations between the
coordinates (the wrapping effect): on the paper's example its radius grows about 2 bits per step,
although the true error propagation of this integrable map is a linear shear along the tori.  This
module keeps the set of states as (CAPD's "doubleton")

    x_k  in  xh_k + C_k r0 + B_k r_k

with an exact centre ``xh_k``, exact matrices ``C_k``, ``B_k``, the fixed ball vector ``r0`` of the
input (zero for exact binary input) and a ball vector ``r_k``.  One step, with ``K`` a box that
contains the set and ``xh_k`` (its hull):

1. the plain ball image ``f(K)`` and a rigorous enclosure ``J`` of the Jacobian of the step over the
   whole box ``K`` (:func:`step_jacobian`): :func:`~symbt.numeric.core.step.step_core` on ``K`` -- its
   existence decisions (``|tr L| > 2``, ``Etilde_j > 0``) hold on the whole box or raise, exactly as on
   the plain path -- gives the image and the eigenvector slopes on ``K``; the slopes' gradients follow
   from their implicit cyclic relations and the read-out is differentiated by the chain rule, in ball
   arithmetic (forward-mode dual numbers through ``step_core``,
   :func:`~symbt.numeric.lohner_checks.jacobian_dual`, are the independent check of this derivation);
2. ``y = f(xh_k)`` on the exact centre (:func:`~symbt.numeric.multiprec.runners.arb_step`, a ball);
3. mean-value form: ``f(x) in y + J (C r0) + J (B r)``; ``C <- mid(J) C`` and ``B <- mid(J) B``
   (both rounded to exact midpoints, in Arb at ``jac_prec`` for ``2N <= 24``, in float64 above:
   ``C`` and ``B`` only have to be exact, and ``B`` invertible -- its inverse
   is enclosed rigorously, :func:`frame_inverse`); ``xh <- mid(y)`` and
       r <- (B^-1 J B) r + B^-1 ((J C - C_new) r0 + (y - mid y)),

   so the rounding errors of the step and the width of ``J`` go into ``r`` (above ``2N = 24``, where ``B^-1``
   is enclosed from a float64 inverse, as ``r <- r + B^-1 ((J B - B_new) r + ...)``: that enclosure never
   multiplies ``r``; docs/certified.md, "The N = 64 radius jump").  ``J`` and the frame algebra run at
   ``jac_prec = 96`` bits: they only multiply the tiny offsets ``r`` (``xh``, ``y`` carry the working precision);
4. the stored enclosure is the hull ``xh + C r0 + B r`` intersected with ``f(K)``.

The frame.  With ``B <- mid(J) B`` (the parallelepiped frame) ``B^-1 J B`` is the identity up to the
width of ``J``, so ``r`` only collects the mapped rounding errors; the price is the condition number of
``B``, which for this integrable map grows only like ``n**2`` (a shear).  Past :data:`MAX_FRAME_COND` the
frame is re-orthogonalised by a plain QR factorisation of ``mid(J) B`` (no column reordering: the issue
reports that reordering by raw column norm blew up); ``frame="qr"`` does that every step (Lohner's QR
method, CAPD's default), measurably worse here (``n**6.2`` against ``n**3.6`` on the paper's example,
docs/certified.md).

A Jacobian that is not finite (a box that contains a degenerate eigenvector, i.e. a slope at
infinity, or a pole of the formulation) raises :class:`JacobianBlowup`: :func:`certified_orbit`
then falls back to the plain ball path.

Example
-------
>>> import mpmath
>>> from symbt.numeric import certified_orbit
>>> info = {}
>>> with mpmath.workdps(30):
...     P, Q, Pr, Qr = certified_orbit([-20, 10, 1], [1, 0, 0.9], 10, 5, 1000, every=1000, info=info)
>>> info["method"], info["prec"] < 200, float(max(Pr[-1] + Qr[-1])) < 1e-29
('lohner', True, True)
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any, NamedTuple

import flint
import numpy as np
from flint import arb, arb_mat

from ..core.errors import NumericRangeError
from ..core.step import step_core
from .arb import ARB_CERTAIN, Uncertain, flint_prec
from .runners import arb_step

__all__ = ["JacobianBlowup", "LohnerSet", "LohnerPass", "lohner_certified", "step_jacobian", "frame_inverse",
           "lohner_pass", "growth_law"]


class JacobianBlowup(ArithmeticError):
    """The interval Jacobian of the step over the current box is not finite (the Lohner step is undefined).

    >>> issubclass(JacobianBlowup, ArithmeticError)
    True
    """


def _check_finite(img: Sequence[Any], J: Any) -> None:
    # a row sum is finite iff every entry of the row is (inf and nan radii propagate): n checks, not n**2
    sums = J * arb_mat(J.ncols(), 1, [1] * J.ncols())
    if not (all(x.is_finite() for x in img) and all(sums[i, 0].is_finite() for i in range(J.nrows()))):
        raise JacobianBlowup("the Jacobian of the step is not finite on the current box")


_UNITS: dict[tuple[int, int], list[Any]] = {}


def _unit_rows(n: int) -> list[Any]:
    """The unit rows ``e_1 .. e_n`` (``1 x n``), made once per size and precision."""
    key = (n, flint.ctx.prec)
    if key not in _UNITS:
        _UNITS[key] = [arb_mat(1, n, [1 if k == i else 0 for k in range(n)]) for i in range(n)]
    return _UNITS[key]


def _slope_rows(u: list[Any], r: list[Any], eP: list[Any], eQ: list[Any], zero: Any, fwd: bool) -> list[Any]:
    """Gradients (``1 x 2N`` rows) of the eigenvector slopes ``u_j`` of one spectral parameter.

    The slopes satisfy the cyclic relations ``u_{j+1} (a_j + u_j) = -r_j`` (``u_{N+1} = u_1``, the
    eigenvector transported once around), so ``du_{j+1} = alpha_j du_j + b_j`` with
    ``alpha_j = u_{j+1}**2 / r_j``, ``b_j = alpha_j e_{p_j} + u_{j+1} (e_{q_{j+1}} - e_{q_j})``, closed by
    ``du_1 = c / (1 - prod alpha)``; run in the direction the step transports the slope (contracting).
    """
    N = len(u)
    nx = [u[(j + 1) % N] for j in range(N)]
    alpha = [nx[j] * nx[j] / r[j] for j in range(N)]
    b = [eP[j] * alpha[j] + (eQ[(j + 1) % N] - eQ[j]) * nx[j] for j in range(N)]
    c, prod = zero, arb(1)
    if fwd:
        for j in range(N):
            c, prod = c * alpha[j] + b[j], prod * alpha[j]
        du = [c * (1 / (1 - prod))]
        for j in range(N - 1):
            du.append(du[j] * alpha[j] + b[j])
        return du
    inv = [1 / a for a in alpha]
    for j in range(N - 1, -1, -1):
        c, prod = (c - b[j]) * inv[j], prod * inv[j]
    out = [c * (1 / (1 - prod))] * N
    nxt = out[0]
    for j in range(N - 1, 0, -1):
        nxt = out[j] = (nxt - b[j]) * inv[j]
    return out


def step_jacobian(box: Sequence[Any], lam0: Any, mu: Any, branch: int,
                  jac_prec: int | None = None) -> tuple[list[Any], Any]:
    """Plain ball image ``f(box)`` and an enclosure of the step's Jacobian over the whole ``box``.

    ``step_core`` on the box at the current precision (its existence decisions hold on the whole box or
    raise, as on the plain certified path) gives the image and the slopes; the Jacobian follows from the
    implicit cyclic relations of the slopes (module docstring) and the read-out of the step, at ``jac_prec``
    bits (default: the current precision; the Jacobian only multiplies the tiny offsets ``r``, so 64-96
    bits suffice).  Encloses the same Jacobian as :func:`~symbt.numeric.lohner_checks.jacobian_dual` (forward-mode
    dual numbers through ``step_core``), several times faster.

    >>> img, J = step_jacobian([arb(-20), arb(10), arb(1), arb(1), arb(0), arb(0.9)], arb(10), arb(5), 1)
    >>> J[0, 0].str(5, radius=False), sum(J[0, k] for k in range(3, 6)).contains(0)   # q-shift invariance
    ('1.0067', True)
    """
    n = len(box)
    N = n // 2
    Pn, Qn, aux = step_core(ARB_CERTAIN, list(box[:N]), list(box[N:]), lam0, mu, branch)
    img = Pn + Qn
    if not all(x.is_finite() for x in img):
        raise JacobianBlowup("the step is not finite on the current box")
    with flint_prec(jac_prec or flint.ctx.prec):
        E = _unit_rows(n)
        eP, eQ, zero = E[:N], E[N:], arb_mat(1, n)
        Q = box[N:]
        r = [(Q[(j + 1) % N] - Q[j]).exp() for j in range(N)]
        u, w, xr, gq = aux["u"], aux["w"], aux["xr"], aux["gq"]
        du = _slope_rows(u, r, eP, eQ, zero, bool(aux["S1"].forward))
        dw = _slope_rows(w, r, eP, eQ, zero, bool(aux["S2"].forward))
        two_mu = 2 * mu
        dP, dQ, dg = [], [], []
        for j in range(N):
            dn = u[j] - w[j]
            ddn = du[j] - dw[j]
            dxr = ddn * (-xr[j] / dn)
            dQ.append(eQ[j] + dxr * (1 / (1 + xr[j])))
            dg.append((du[j] - ddn * gq[j]) * (1 / dn))
        for j in range(N):
            dP.append(eP[j] + (dg[(j + 1) % N] - dg[j]) * two_mu)
        J = arb_mat([x.entries() for x in dP + dQ])
    _check_finite(img, J)
    return img, J


def _col(xs: Sequence[Any]) -> Any:
    return arb_mat([[x] for x in xs])


def _floats(M: Any) -> Any:
    return np.array([[float(x) for x in row] for row in M.tolist()], dtype=float)


def _frame(F: Any) -> tuple[Any, Any]:
    """``(Bf, B)``: the orthogonal factor of a plain QR of the float matrix ``F`` (float64 and exact arb_mat)."""
    if not np.all(np.isfinite(F)):
        raise JacobianBlowup("the frame matrix is not finite")
    Qf, R = np.linalg.qr(F)
    if not np.all(np.abs(np.diag(R)) > 1e-300):
        raise JacobianBlowup("the frame matrix is singular")
    return Qf, arb_mat(Qf.tolist())


_SMALL = 24       # below this size Arb's inv is faster than the Python loops of the bound
#: the product frame is re-orthogonalised (QR) past this 1-norm condition (paper's example: ~n**2, 6e4 at 1000 steps)
MAX_FRAME_COND = 1e12
_COND_EVERY = 32       # small frames: check the condition every so many steps (rigour does not depend on it)


def _inv(B: Any) -> Any:
    try:
        return B.inv()
    except ZeroDivisionError as exc:           # Arb cannot certify that B is invertible
        raise JacobianBlowup("the frame matrix is not certainly invertible") from exc


def frame_inverse(B: Any, X: Any = None) -> Any:
    """A rigorous enclosure of ``B**-1`` for an exact ``B``, given an approximate inverse ``X`` (float64 array;
    default ``B^T``, for a nearly orthogonal ``B``): one product, no elimination.

    With ``X B = I + D`` and ``|D|_inf <= d < 1/2``: ``B^-1 = (I + D)^-1 X = X + E X`` with
    ``|E|_inf <= d / (1 - d)``, so every entry of ``B^-1 - X`` is at most ``max|X_ij| d / (1 - d)``.  Falls
    back to Arb's ``inv`` (Gaussian elimination) when ``X`` is not good enough, and for small matrices
    (faster there).

    >>> import numpy as np
    >>> B = arb_mat(np.linalg.qr(np.arange(1.0, 1601.0).reshape(40, 40) ** 0.5)[0].tolist())
    >>> (frame_inverse(B) * B).contains(arb_mat(40, 40, [1 if i == j else 0 for i in range(40) for j in range(40)]))
    True
    """
    n = B.nrows()
    if n <= _SMALL:
        return _inv(B)
    Xa = B.transpose() if X is None else arb_mat(np.asarray(X).tolist())
    ents = (Xa * B - _identity(n)).entries()
    d = arb(0)
    for i in range(n):
        d = d.max(arb(sum(abs(x) for x in ents[i * n:(i + 1) * n]).abs_upper()))
    if not d < 0.5:
        return _inv(B)
    beta = arb(float(np.abs(X).max())) if X is not None else max(abs(x) for x in Xa.entries())
    rad = arb((beta * d / (1 - d)).abs_upper())
    return Xa + arb_mat(n, n, [arb(0, rad)] * (n * n))


def _identity(n: int) -> Any:
    return arb_mat(n, n, [1 if i == j else 0 for i in range(n) for j in range(n)])


class LohnerSet:
    """The set ``xh + C r0 + B r`` of one step (see the module docstring) and its hull.

    ``hull`` is the stored enclosure (a list of balls, ``p`` then ``q``).  ``jac_prec``: bits of the
    Jacobian and the frame algebra; ``frame``: ``"product"`` (default) or ``"qr"`` (module docstring);
    ``reorthogonalised`` counts the QR steps of the product frame.  ``unsound=True`` drops the rounding
    errors and the Jacobian's radius (a deliberately wrong variant: the tests show that the containment
    check catches it).

    >>> S = LohnerSet([arb(-20), arb(10), arb(1), arb(1), arb(0), arb(0.9)])
    >>> S.step(arb(10), arb(5), 1); S.hull[0].str(8, radius=False)
    '-19.996568'
    """

    def __init__(self, balls: Sequence[Any], jac_prec: int = 96, unsound: bool = False,
                 frame: str = "product") -> None:
        n = len(balls)
        self.frame = frame
        self.reorthogonalised = self.steps = 0
        self.n = n
        self.jac_prec = jac_prec
        self.xh = [b.mid() for b in balls]
        self.r0 = _col([b - b.mid() for b in balls])
        self.has_r0 = not all(b.rad() == 0 for b in balls)
        self.Cf = self.Bf = np.eye(n)
        self.C = self.B = arb_mat(self.Bf.tolist())
        self.r = arb_mat(n, 1)
        self.hull = list(balls)
        self.unsound = unsound

    def _box(self) -> list[Any]:
        """A box containing the set and ``xh`` (the mean-value form needs the segment ``[xh, x]``)."""
        return [h.union(c) for h, c in zip(self.hull, self.xh)]

    def _frame_of(self, F: Any) -> tuple[Any, Any, Any, bool]:
        """``(Bf, B, enclosure of B^-1, near)``: ``near`` if ``B`` is ``F`` itself (``B^-1 J B_old ~ I``)."""
        if not np.all(np.isfinite(F)):
            raise JacobianBlowup("the frame matrix is not finite")
        if self.frame == "product":       # past _SMALL coordinates (smaller product frames: _small_frame)
            X = None
            try:                           # every step: the inverse is needed anyway (frame_inverse)
                X = np.linalg.inv(F)
                cond = np.linalg.norm(F, 1) * np.linalg.norm(X, 1)
            except np.linalg.LinAlgError:
                cond = math.inf
            if cond < MAX_FRAME_COND:
                B = arb_mat(F.tolist())
                return F, B, frame_inverse(B, X), True
            self.reorthogonalised += 1
        Bf, B = _frame(F)
        return Bf, B, frame_inverse(B), False

    def _small_frame(self, Jm: Any) -> tuple[Any, Any]:
        """``(B, enclosure of B^-1)``: the product frame ``mid(mid(J) B)`` of a small set, all in Arb (any exact
        invertible ``B`` is rigorous; no numpy round trips per step, which dominated at N = 3); the condition
        is checked in float64 every ``_COND_EVERY`` steps, past :data:`MAX_FRAME_COND` a plain QR."""
        B = (Jm * self.B).mid()
        self.steps += 1
        if self.steps % _COND_EVERY == 0:
            F = _floats(B)
            with np.errstate(all="ignore"):
                try:
                    cond = np.linalg.cond(F, 1) if np.all(np.isfinite(F)) else math.inf
                except np.linalg.LinAlgError:
                    cond = math.inf
                if not cond < MAX_FRAME_COND:
                    self.reorthogonalised += 1
                    B = _frame(F)[1]
        return B, _inv(B)

    def step(self, lam0: Any, mu: Any, branch: int) -> None:
        """One step: the set and its hull are replaced by enclosures of their image."""
        N = self.n // 2
        img, J = step_jacobian(self._box(), lam0, mu, branch, self.jac_prec)
        try:
            Pc, Qc = arb_step(self.xh[:N], self.xh[N:], lam0, mu, branch)
        except ArithmeticError as exc:         # a division by an exact zero at the centre
            raise JacobianBlowup("the step at the centre is not finite") from exc
        y = Pc + Qc
        if not all(v.is_finite() for v in y):
            raise JacobianBlowup("the step at the centre is not finite")
        xh = [v.mid() for v in y]
        err = _col([v - c for v, c in zip(y, xh)])           # the rounding of f(xh): into r
        with flint_prec(self.jac_prec):
            if self.unsound:
                J, err = J.mid(), arb_mat(self.n, 1)
            Jm = J.mid()
            small = self.n <= _SMALL and self.frame == "product"
            near = False
            if small:
                Bn, Binv = self._small_frame(Jm)
            else:
                Jf = _floats(Jm)
                with np.errstate(all="ignore"):      # overflow or a singular frame is decided, not warned
                    Bf, Bn, Binv, near = self._frame_of(Jf @ self.Bf)
            rhs = err
            if self.has_r0:
                if not small:
                    with np.errstate(all="ignore"):
                        self.Cf = Jf @ self.Cf
                Cn = (Jm * self.C).mid() if small else arb_mat(self.Cf.tolist())
                if not all(x.is_finite() for x in Cn.entries()):
                    raise JacobianBlowup("the matrix C is not finite")
                rhs = rhs + (J * self.C - Cn) * self.r0
                self.C = Cn
            if near:          # B^-1 multiplies the small J B - B_new, never r (module docstring, step 3)
                self.r = self.r + Binv * ((J * self.B - Bn) * self.r + rhs)
            else:
                self.r = (Binv * (J * self.B)) * self.r + Binv * rhs
            self.B, self.Bf = Bn, (self.Bf if small else Bf)
            lin = Bn * self.r
            if self.has_r0:
                lin = lin + self.C * self.r0
        self.xh = xh
        hull = [c + lin[i, 0] for i, c in enumerate(xh)]
        if not self.unsound:
            hull = [h.intersection(v) for h, v in zip(hull, img)]
        self.hull = hull


class LohnerPass(NamedTuple):
    """What one pass at a fixed precision gives (:func:`lohner_pass`)."""

    ok: bool                                       #: every radius met the target
    stored: list[tuple[list[Any], list[Any]]]      #: the ``(P, Q)`` balls at the kept steps
    hist: list[float]                              #: ``excess`` after each step
    lograd: list[float]                            #: ``log2`` of the largest radius after each step
    done: int                                      #: steps done


def _lograd(xs: Sequence[Any]) -> float:
    r = max(float(x.rad()) for x in xs)
    return math.log2(r) if r > 0 else -math.inf


def lohner_pass(P: list[Any], Q: list[Any], lam0: Any, mu: Any, n: int, branch: int, keep: set[int],
                excess: Callable[[list[Any]], float], *, jac_prec: int = 96, unsound: bool = False,
                stop: float = 8.0, frame: str = "product") -> LohnerPass:
    """``n`` Lohner steps from the balls ``P, Q`` at the current flint precision.

    The stored ``(P, Q)`` balls at the steps in ``keep`` (and the initial state), ``hist[i] =
    excess(state after i steps)`` (``max log2(radius / target)``), stopping early once the excess passes
    ``stop``.  Raises :class:`JacobianBlowup`, :class:`~symbt.numeric.multiprec.arb.Uncertain`,
    :class:`NoRealMapError`.

    >>> run = lohner_pass([arb(-20), arb(10), arb(1)], [arb(1), arb(0), arb(0.9)], arb(10), arb(5), 3, 1, {3},
    ...                   lambda xs: -100.0)
    >>> run.ok, len(run.stored), run.done
    (True, 2, 3)
    """
    N = len(P)
    S = LohnerSet(list(P) + list(Q), jac_prec=jac_prec, unsound=unsound, frame=frame)
    stored = [(list(P), list(Q))]
    hist, lograd = [excess(S.hull)], [_lograd(S.hull)]
    for i in range(1, n + 1):
        S.step(lam0, mu, branch)
        if not all(h.is_finite() for h in S.hull):
            raise JacobianBlowup("the enclosure is no longer finite")
        e = excess(S.hull)
        hist.append(e)
        lograd.append(_lograd(S.hull))
        if i in keep:
            stored.append((S.hull[:N], S.hull[N:]))
        if e > stop:
            return LohnerPass(False, stored, hist, lograd, i)
    return LohnerPass(max(hist) <= 0, stored, hist, lograd, n)


def growth_law(lograd: Sequence[float], first: int = 100) -> dict[str, Any]:
    """The radius growth ``rad(n) ~ c n**degree`` fitted (least squares in log-log) over ``first .. len - 1``.

    ``lograd[i]`` is ``log2`` of the largest radius after ``i`` steps; the fit uses log-spaced steps (ten
    per decade) from ``first`` (lowered to a tenth of the run for short runs) to the last step.  Returns
    ``{"degree", "steps": (first, last), "log2_radius": (at first, at last)}``; ``degree`` is ``None``
    without two usable points.

    >>> law = growth_law([math.log2(1e-50 * max(i, 1) ** 2) for i in range(10001)])
    >>> round(law["degree"], 6), law["steps"]
    (2.0, (100, 10000))
    """
    last = len(lograd) - 1
    first = max(1, min(first, last // 10))
    pts = sorted({int(round(first * 10 ** (k / 10))) for k in range(0, 200)} & set(range(first, last + 1)) | {last})
    xy = [(math.log2(i), lograd[i]) for i in pts if i >= 1 and math.isfinite(lograd[i])]
    out: dict[str, Any] = {"degree": None, "steps": (first, last),
                           "log2_radius": (lograd[first] if last >= first else None, lograd[last])}
    if len(xy) >= 2:                 # distinct steps: their logarithms differ
        x = np.array([a for a, _ in xy])
        y = np.array([b for _, b in xy])
        x -= x.mean()
        out["degree"] = float(np.dot(x, y - y.mean()) / np.dot(x, x))     # least-squares slope
    return out


def _next_prec(prec: int, run: LohnerPass, n: int) -> int:
    """Working precision for the next pass: the measured excess, extrapolated polynomially to step ``n``."""
    hist, done = run.hist, run.done
    finite = [i for i in range(1, done + 1) if math.isfinite(hist[i])]
    if not finite:
        return 2 * prec
    i1 = finite[-1]
    e1 = max(hist[i] for i in finite)
    extra = e1
    if i1 < n:
        law = growth_law(run.lograd[:i1 + 1], first=max(1, i1 // 10))
        degree = max(law["degree"] or 2.0, 1.0)
        extra = e1 + 1.5 * degree * math.log2(n / i1)
    return max(int(prec + extra + _MARGIN) + 1, prec + 32)


_MARGIN = 16           # bits beyond the extrapolated excess
_ATTEMPTS = 6
#: initial working precision beyond the output precision, per bit of the number of steps (measured: the
#: paper's example loses ~5 bits per doubling of n)
_BITS_PER_OCTAVE = 5


def lohner_certified(state: Callable[[], tuple[list[Any], list[Any], Any, Any]], n: int, branch: int,
                     keep: set[int], excess: Callable[[list[Any]], float], target_bits: int, prec: int | None,
                     max_prec: int, passes: list[int]) -> tuple[list[tuple[list[Any], list[Any]]], int, dict[str, Any]]:
    """The precision loop of the Lohner orbit: ``(stored balls, working precision, growth law)``.

    ``state()`` makes the input balls at the current flint precision; the first pass runs at ``prec`` (default
    ``target_bits + 24 + 5 bitlen(n)``, ``target_bits = log2(1 / target radius)``), each later one at the
    precision the measured growth requires (the excess so far plus 1.5 times the degree fitted from step ``done // 10``
    on, at least 1: a transient left out, times ``log2(n / done)``, plus 16 bits; ``done``: the last step with a finite
    excess); ``passes`` receives the precisions tried.  Raises :class:`JacobianBlowup` (the caller falls back to the
    plain ball path), :class:`NumericRangeError` (not certified below ``max_prec``), :class:`NoRealMapError`.

    >>> def state():
    ...     return [arb(-20), arb(10), arb(1)], [arb(1), arb(0), arb(0.9)], arb(10), arb(5)
    >>> def excess(xs):                       # log2(radius / 1e-40), the worst coordinate
    ...     return max(math.log2(float(x.rad()) / 1e-40) if x.rad() > 0 else -math.inf for x in xs)
    >>> passes = []
    >>> stored, prec, law = lohner_certified(state, 100, 1, {100}, excess, 133, None, 4096, passes)
    >>> len(stored), prec == passes[-1], float(stored[1][0][0].rad()) < 1e-40
    (2, True, True)
    """
    work = int(prec) if prec is not None else target_bits + 24 + _BITS_PER_OCTAVE * int(n).bit_length()
    for _ in range(_ATTEMPTS):
        if work > max_prec:
            break
        passes.append(work)
        with flint_prec(work):
            P, Q, l0, m = state()
            try:
                run = lohner_pass(P, Q, l0, m, n, branch, keep, excess)
            except Uncertain:
                work = max(2 * work, work + 64)      # an existence decision on the boundary: more bits
                continue
        if run.ok:
            return run.stored, work, growth_law(run.lograd)
        work = _next_prec(work, run, n)
    raise NumericRangeError("certified orbit (Lohner): the enclosure could not be certified below max_prec = "
                            "%d bits" % max_prec)
