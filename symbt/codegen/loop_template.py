"""Source template of the transfer-matrix (O(N)) form of the emitted Python modules.

The control flow (loops over the sites, the choice of root and transport direction,
the guards) is written here once; every formula inside is a kernel derived in
:mod:`symbt.codegen.kernels` and printed in place of a ``@@name@@`` marker by
:mod:`symbt.codegen.emit_loop`.  The core functions take an arithmetic namespace
``_X`` (``_NP``: float64 numpy batch arrays, both sides of a selection evaluated;
``_MP``: mpmath scalars, lazy selection, guards raise at once) and are shared by
the numpy and mpmath flavours; ``_ArrayPoly`` (numpy) and ``_ListPoly`` (mpmath) carry the
polynomials in lambda for the invariants and the fields.

>>> "@@update@@" in CORE
True
"""
from __future__ import annotations

__all__ = ["CORE"]

CORE = '''

class _NumpyOps:
    """float64 arithmetic on batch arrays; guards are collected and checked by the caller."""

    exp = staticmethod(np.exp)
    log1p = staticmethod(np.log1p)
    sqrt = staticmethod(np.sqrt)
    acosh = staticmethod(np.arccosh)
    sign = staticmethod(np.sign)
    one, zero = 1.0, 0.0

    @staticmethod
    def ratio(dq):
        # exp(dq) under/overflows for |dq| > ~700: not representable (NaN -> NumericRangeError / mask)
        return np.where(np.abs(dq) <= 700.0, np.exp(np.clip(dq, -700.0, 700.0)), np.nan)

    @staticmethod
    def sgn(x):
        return np.where(x >= 0, 1.0, -1.0)

    ldexp = staticmethod(np.ldexp)

    @staticmethod
    def out_of_range(A, B, C, D):
        # entries beyond [2**-500, 2**500] (or not finite): tr**2 - 4 or a later product could overflow
        mx = np.maximum(np.maximum(np.abs(A), np.abs(B)), np.maximum(np.abs(C), np.abs(D)))
        return ~((mx <= 2.0 ** 500) & (mx >= 2.0 ** -500))

    @staticmethod
    def renorm(A, B, C, D, e):
        # divide by 2**k (exact) so that the largest entry lies in [1/2, 1); k carried in e
        mx = np.maximum(np.maximum(np.abs(A), np.abs(B)), np.maximum(np.abs(C), np.abs(D)))
        k = np.where(np.isfinite(mx) & (mx > 0), np.frexp(mx)[1], 0)
        # float64 first: numpy would take an integer entry (the site's -1, 0) to float16
        A, B, C, D = (np.ldexp(np.asarray(x, dtype=np.float64), -k) for x in (A, B, C, D))
        return A, B, C, D, e + k

    @staticmethod
    def select(cond, f, g):
        cond = np.asarray(cond)
        if cond.all():
            return f()
        if not cond.any():
            return g()
        return np.where(cond, f(), g())

    @staticmethod
    def every(c):
        return bool(np.all(c))

    @staticmethod
    def none(c):
        return not bool(np.any(c))

    @staticmethod
    def merge(c, xs, ys):
        return [np.where(c, x, y) for x, y in zip(xs, ys)]

    @staticmethod
    def guard(guards, condition, label, value):
        guards.append((condition, label, value))

    conditioned = True      # float64 decides only where its condition estimate is at most _KAPPA_MAX


class _MpOps:
    """mpmath arithmetic on one state at the current precision; a failed guard raises at once."""

    exp = staticmethod(mpmath.exp)
    log1p = staticmethod(mpmath.log1p)
    sqrt = staticmethod(mpmath.sqrt)
    acosh = staticmethod(mpmath.acosh)
    sign = staticmethod(mpmath.sign)
    one, zero = 1, 0
    ratio = staticmethod(mpmath.exp)

    @staticmethod
    def sgn(x):
        return 1 if x >= 0 else -1

    @staticmethod
    def ldexp(x, e):
        return x          # e = 0: mpmath's exponent range needs no rescaling

    @staticmethod
    def out_of_range(A, B, C, D):
        return False

    @staticmethod
    def select(cond, f, g):
        return f() if cond else g()

    @staticmethod
    def every(c):
        return bool(c)

    @staticmethod
    def none(c):
        return not c

    @staticmethod
    def merge(c, xs, ys):
        return xs if c else ys

    @staticmethod
    def guard(guards, condition, label, value):
        _mp_guard(condition, label, value)

    conditioned = False     # the recomputation route: no float64 conditioning guard


# symbt.numeric's limit of the float64 condition estimate (symbt.numeric.core.limits.KAPPA_MAX)
_KAPPA_MAX = @@KAPPA_MAX@@
_NP, _MP = _NumpyOps(), _MpOps()


class _ListPoly:
    """Polynomial in lambda as a list of mpf coefficients (index = power); +, -, * only."""

    __slots__ = ("c",)

    def __init__(self, c):
        self.c = list(c)

    def coeff(self, k):
        return self.c[k] if k < len(self.c) else 0

    def __add__(self, o):
        if not isinstance(o, _ListPoly):
            o = _ListPoly([o])
        n = max(len(self.c), len(o.c))
        return _ListPoly([self.coeff(k) + o.coeff(k) for k in range(n)])

    __radd__ = __add__

    def __neg__(self):
        return _ListPoly([-x for x in self.c])

    def __sub__(self, o):
        return self + (-o)

    def __rsub__(self, o):
        return (-self) + o

    def __mul__(self, o):
        if not isinstance(o, _ListPoly):
            return _ListPoly([x * o for x in self.c])
        out = [0] * (len(self.c) + len(o.c) - 1)
        for i, x in enumerate(self.c):
            for k, y in enumerate(o.c):
                out[i + k] = out[i + k] + x * y
        return _ListPoly(out)

    __rmul__ = __mul__


class _ArrayPoly:
    """Polynomial in lambda over a float64 batch: array of shape (degree + 1,) + batch."""

    __slots__ = ("c",)

    def __init__(self, c):
        self.c = c

    @staticmethod
    def of(coeffs):
        return _ArrayPoly(np.array(np.broadcast_arrays(*[np.asarray(x, dtype=np.float64) for x in coeffs])))

    def coeff(self, k):
        return self.c[k] if k < len(self.c) else 0.0

    def __add__(self, o):
        if not isinstance(o, _ArrayPoly):
            o = _ArrayPoly.of([o])
        a, b = (self.c, o.c) if len(self.c) >= len(o.c) else (o.c, self.c)
        out = a + np.zeros(b.shape[1:])
        out[:len(b)] += b
        return _ArrayPoly(out)

    __radd__ = __add__

    def __neg__(self):
        return _ArrayPoly(-self.c)

    def __sub__(self, o):
        return self + (-o)

    def __rsub__(self, o):
        return (-self) + o

    def __mul__(self, o):
        if not isinstance(o, _ArrayPoly):
            return _ArrayPoly(self.c * o)
        a, b = (self.c, o.c) if len(self.c) <= len(o.c) else (o.c, self.c)
        out = np.zeros((len(a) + len(b) - 1,) + np.broadcast_shapes(a.shape[1:], b.shape[1:]))
        for i in range(len(a)):
            out[i:i + len(b)] += a[i] * b
        return _ArrayPoly(out)

    __rmul__ = __mul__


_NumpyOps.poly = staticmethod(_ArrayPoly.of)
_MpOps.poly = _ListPoly


def _cols(a):
    """Per-site columns of a batch + (N,) array."""
    return [a[..., j] for j in range(N)]


def _ratios(_X, Q):
    """r_j = E_{j+1}/E_j = exp(q_{j+1} - q_j) (cyclic): the only way q enters the scaled transfer matrices."""
    return [_X.ratio(Q[(j + 1) % N] - Q[j]) for j in range(N)]


def _monodromy(av, R):
    """M = m_N ... m_1 with m_j = [[a_j, -1], [r_j, 0]] (kernels 'site', 'update')."""
    a, r = av[0], R[0]
    A, B, C, D = @@site@@
    for a, r in zip(av[1:], R[1:]):
        A, B, C, D = @@update@@
    return A, B, C, D


def _scaled_monodromy(_X, av, R):
    """M = 2**e (A, B; C, D) = m_N ... m_1 at numbers a_j: the plain product; float64 elements whose entries
    leave [2**-500, 2**500] are computed again with the product rescaled by a power of two after every site
    (exact; as symbt.numeric), so that tr**2 - 4 never overflows.  Returns (A, B, C, D, e)."""
    plain = _monodromy(av, R)
    bad = _X.out_of_range(*plain)
    if _X.none(bad):
        return plain + (0,)
    a, r = av[0], R[0]
    A, B, C, D, e = _X.renorm(@@site@@, 0)
    for a, r in zip(av[1:], R[1:]):
        A, B, C, D, e = _X.renorm(@@update@@, e)
    return tuple(_X.merge(bad, (A, B, C, D, e), plain + (0,)))


def _forward(av, R, u1):
    """Slopes at sites 2 to N by the Moebius action of m_j (kernel 'forward')."""
    us = [u1]
    for j in range(N - 1):
        a, r, u = av[j], R[j], us[j]
        us.append(@@forward@@)
    return us


def _backward(av, R, u1):
    """Slopes at sites N down to 2 by the inverse action, from u_{N+1} = u_1 (kernel 'backward')."""
    us = [u1] + [None] * (N - 1)
    un = u1
    for j in range(N - 1, 0, -1):
        a, r = av[j], R[j]
        un = us[j] = @@backward@@
    return us


def _slopes(_X, av, R, mono, t, s):
    """Scaled slopes u_j = E_j * (slope at site j) of the eigenvector (1, -u) of M with eigenvalue
    (t - s g)/2, g = sqrt(t^2 - 4): root without cancellation at site 1 (kernels 'root_k', 'root_c';
    read off the rescaled M = 2**e (A, B; C, D), t = A + D: the roots are homogeneous of degree 0), then
    transport in the contracting direction (forward iff |(t - s g)/2| >= 1 iff s t < 0)."""
    A, B, C, D, e = mono
    two = _X.ldexp(2 * _X.one, -e)
    g = _X.sqrt(_disc(_X, A, B, C, D, t, two))
    sd = _X.sgn(A - D)
    u1 = _X.select(sd * s > 0, lambda: @@root_k@@, lambda: @@root_c@@)
    fwd = s * t < 0
    if _X.every(fwd):
        return _forward(av, R, _turn_forward(av, R, u1))
    if _X.none(fwd):
        return _backward(av, R, _turn_backward(av, R, u1))
    return _X.merge(fwd, _forward(av, R, _turn_forward(av, R, u1)), _backward(av, R, _turn_backward(av, R, u1)))


# The root read off M carries M's rounding errors, eps times the entries of |m_N| ... |m_1|, which can exceed
# those of M by many orders (cancellation in the product: N = 8, a root 10**5 eps off while the step's output is
# well-conditioned).  One turn of the transport in the contracting direction multiplies the root's error by
# the ratio of the eigenvalues, 1/|(t - s g)/2|**2 (there 10**-12), and adds only the transport's own rounding,
# which the slopes at sites 2 to N carry anyway: the refined root is as accurate as the transport.
def _turn_forward(av, R, u1):
    """The slope at site N + 1 = site 1 after one forward turn from ``u1``."""
    a, r, u = av[N - 1], R[N - 1], _forward(av, R, u1)[N - 1]
    return @@forward@@


def _turn_backward(av, R, u1):
    """The slope at site 1 after one backward turn from ``u_{N+1} = u1``."""
    a, r, un = av[0], R[0], _backward(av, R, u1)[1]
    return @@backward@@


def _traces(_X, P, R, lam0, mu, guards, kappa=None):
    """Rescaled monodromies M_i = 2**e_i (A, B; C, D) at lambda_1 = lambda_0 + mu, lambda_2 = lambda_0 - mu,
    their rescaled traces t_i = tr L(lambda_i) / 2**e_i, and the trace guards (kernel 'disc_scaled'); with
    a list ``kappa`` (float64 step), each trace guard after its conditioning guard (:func:`_trace_kappa`),
    and ``kappa`` receives the two traces' condition estimates."""
    a1 = [lam0 + mu + p for p in P]
    a2 = [lam0 - mu + p for p in P]
    M1, M2 = _scaled_monodromy(_X, a1, R), _scaled_monodromy(_X, a2, R)
    A, B, C, D = M1[:4]
    t1 = @@trace@@
    A, B, C, D = M2[:4]
    t2 = @@trace@@
    for i, (lam, av, M, t, label) in enumerate(((lam0 + mu, a1, M1, t1, "lam1 = lam0 + mu"),
                                                (lam0 - mu, a2, M2, t2, "lam2 = lam0 - mu"))):
        two = _X.ldexp(2 * _X.one, -M[4])
        disc = @@disc_scaled@@
        if kappa is not None and _X.conditioned:
            k = _trace_kappa(_X, av, R, M, t, disc, two)
            # +-1; a NaN estimate refuses too: the rescaled trace can underflow to 0 (2**-e below the float64
            # range, |lambda| ~ 10**103 at N = 6: tr = 0, t**2 - 4 = 0, kappa = 0/0), and the trace guard after
            # it would read "no real map" where the map exists (the deep fuzz, docs/fuzz.md)
            _X.guard(guards, "illcond", f"tr L(lam{i + 1})", np.where(k <= _KAPPA_MAX, 1, -1))
            kappa.append(k * _cancellation(lam, P, av))
        _X.guard(guards, "trace", label, _disc(_X, *M[:4], t, two))
    return a1, a2, M1, M2, t1, t2


def _disc(_X, A, B, C, D, t, two):
    """4**-e (tr**2 - 4) of M = 2**e (A, B; C, D), t = A + D, two = 2**(1 - e): near a closed gap (M close to +-I)
    (A - D)**2 + 4BC, else (t - two)(t + two) (kernels near_closed, disc_entries, disc_scaled; closed_gap.py)."""
    return _X.select(@@near_closed@@, lambda: @@disc_entries@@, lambda: @@disc_scaled@@)


def _trace_kappa(_X, av, R, M, t, disc, two):
    """float64 condition estimate of the trace decision T (|t| + 2) / |t**2 - 4| (as symbt.numeric's
    trace_kappa): T the trace of |m_N| ... |m_1| (the monodromy of |a_j| and -r_j, no cancellation), the
    rounding scale of t, rescaled to M's power of two."""
    A, B, C, D, e = _scaled_monodromy(_X, [np.abs(a) for a in av], [-r for r in R])
    return np.ldexp(A + D, e - M[4]) * ((np.abs(t) + np.abs(two)) / np.abs(disc))


def _cancellation(lam, P, av):
    """max_j (|lam| + |p_j|) / |lam + p_j|: the cancellation in a_j (symbt.numeric's kernels)."""
    k = (np.abs(lam) + np.abs(P[0])) / np.abs(av[0])
    for p, a in zip(P[1:], av[1:]):
        k = np.maximum(k, (np.abs(lam) + np.abs(p)) / np.abs(a))
    return k


def _traces_unscaled(_X, P, R, lam0, mu, guards):
    """tr L(lambda_1), tr L(lambda_2) (non-finite beyond the float64 range), with the trace guards."""
    M1, M2, t1, t2 = _traces(_X, P, R, lam0, mu, guards)[2:]
    return _X.ldexp(t1, M1[4]), _X.ldexp(t2, M2[4])


_GAP = "Etilde_j for some j (tr L(lam1), tr L(lam2) of opposite signs)"


def _step_slopes(_X, P, Q, lam0, mu, b, guards):
    """Slopes u (at lambda_1), w (at lambda_2) and d = w - u at every site, with the guards of the step:
    traces of opposite signs (lambda_1, lambda_2 in different gaps; decided on the signs), and every
    slope finite with its transport denominator a_j + u_j (an infinite slope, or one whose transport
    overflowed, would read out as 2 mu/d = 0: a finite wrong state; here a range error)."""
    R = _ratios(_X, Q)
    kappa = []
    a1, a2, M1, M2, t1, t2 = _traces(_X, P, R, lam0, mu, guards, kappa)
    _X.guard(guards, "positivity", _GAP, _X.sign(t1) * _X.sign(t2))
    u = _slopes(_X, a1, R, M1, t1, b)           # y: eigenvalue (t1 - b g1)/2 at lambda_1
    w = _slopes(_X, a2, R, M2, t2, -b)          # z: eigenvalue (t2 + b g2)/2 at lambda_2
    d = [w[j] - u[j] for j in range(N)]
    for name, vs in (("u", [a + x for a, x in zip(a1, u)]), ("w", [a + x for a, x in zip(a2, w)]), ("d", d)):
        for j, v in enumerate(vs):
            _X.guard(guards, "range", f"{name}_{j + 1}", v)
    if kappa:   # the slopes' conditioning, as symbt.numeric's kernels: the margin KAPPA_MAX |d| |1 + x| - kappa ...
        kt = np.maximum(kappa[0], kappa[1])
        for j in range(N):
            x = -2 * mu / d[j]
            _X.guard(guards, "illcond", f"the slopes at site {j + 1}", _KAPPA_MAX * np.abs(d[j]) * np.abs(1 + x)
                     - kt * (np.abs(u[j]) + np.abs(w[j])) * (np.abs(1 + x) + np.abs(x)))
    return u, w, d


def _step(_X, P, Q, lam0, mu, b, guards):
    """One step (kernels 'positivity', 'eta_diff', 'dq'): q~ = q + log1p(-2 mu/d), p~ = p + eta_j - eta_{j+1}."""
    u, w, dd = _step_slopes(_X, P, Q, lam0, mu, b, guards)
    Pn, Qn = [], []
    for j in range(N):
        uj, dj, un1, dn1, wj, wn1 = u[j], dd[j], u[(j + 1) % N], dd[(j + 1) % N], w[j], w[(j + 1) % N]
        _X.guard(guards, "positivity", f"Etilde_{j + 1}", @@positivity@@)
        Pn.append(P[j] + @@eta_diff@@)
        Qn.append(Q[j] + @@dq@@)
    return Pn, Qn


def _dapp(_X, P, Q, lam0, mu, b, guards):
    u, w, dd = _step_slopes(_X, P, Q, lam0, mu, b, guards)
    q, uj, dj = Q[0], u[0], dd[0]
    return @@dapp_x@@, @@dapp_y@@


def _phi_tr(_X, tr1, tr2, branch, guards):
    t = tr1
    _X.guard(guards, "trace", "tr1", @@disc@@)
    t = tr2
    _X.guard(guards, "trace", "tr2", @@disc@@)
    return @@phi@@


def _phi(_X, P, Q, lam0, mu, branch, guards):
    R = _ratios(_X, Q)
    tr1, tr2 = _traces_unscaled(_X, P, R, lam0, mu, guards)
    return @@phi@@


def _trace_derivatives(av, R, one, zero):
    """d tr/dp_j and d tr/dq_j for every j from the prefix products P_j = m_{j-1} ... m_1 and the
    suffix products S_j = m_N ... m_{j+1} (kernels 'update', 'update_right', 'dtr_dp', 'dtr_dr',
    'dtr_dq'); numbers or polynomial entries alike."""
    pre, suf = [None] * N, [None] * N
    A, B, C, D = one, zero, zero, one
    for j in range(N):
        pre[j] = (A, B, C, D)
        a, r = av[j], R[j]
        A, B, C, D = @@update@@
    A, B, C, D = one, zero, zero, one
    for j in range(N - 1, -1, -1):
        suf[j] = (A, B, C, D)
        a, r = av[j], R[j]
        A, B, C, D = @@update_right@@
    dp, drs = [], []
    for j in range(N):
        P00, P01, P10, P11 = pre[j]
        S00, S01, S10, S11 = suf[j]
        dp.append(@@dtr_dp@@)
        drs.append(@@dtr_dr@@)
    dq = []
    for j in range(N):
        r_prev, dr_prev, r, dr = R[j - 1], drs[j - 1], R[j], drs[j]
        dq.append(@@dtr_dq@@)
    return dp, dq


def _phi_grad(_X, P, Q, lam0, mu, branch, guards):
    R = _ratios(_X, Q)
    tr1, tr2 = _traces_unscaled(_X, P, R, lam0, mu, guards)
    a1 = [lam0 + mu + p for p in P]
    a2 = [lam0 - mu + p for p in P]
    dp1, dq1 = _trace_derivatives(a1, R, _X.one, _X.zero)
    dp2, dq2 = _trace_derivatives(a2, R, _X.one, _X.zero)
    gp, gq = [], []
    for x1, x2 in zip(dp1, dp2):
        gp.append(@@grad@@)
    for x1, x2 in zip(dq1, dq2):
        gq.append(@@grad@@)
    return gp, gq


def _poly_sites(_X, P):
    """a_j = lambda + p_j as polynomials."""
    return [_X.poly([p, _X.one]) for p in P]


def _fields(_X, P, Q):
    """Coefficient polynomials of d tr/dp_j, d tr/dq_j: [lambda^k] = dH_k/dp_j, dH_k/dq_j."""
    R = _ratios(_X, Q)
    return _trace_derivatives(_poly_sites(_X, P), R, _X.poly([_X.one]), _X.poly([_X.zero]))


def _invariants(_X, P, Q):
    R = _ratios(_X, Q)
    A, B, C, D = _monodromy(_poly_sites(_X, P), R)
    tr = @@trace@@
    return [tr.coeff(k) for k in range(N)]


def _spectral_trace(_X, lam, P, Q):
    R = _ratios(_X, Q)
    A, B, C, D, e = _scaled_monodromy(_X, [lam + p for p in P], R)
    return _X.ldexp(@@trace@@, e)


def _ck_integrand(_X, lam, P, Q, guards):
    t = _spectral_trace(_X, lam, P, Q)
    _X.guard(guards, "trace", "lam", @@disc@@)
    w = @@inv_sqrt_disc@@
    return [lam ** k * w for k in range(N)]
'''
