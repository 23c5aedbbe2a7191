"""Invariant drift of long float64 Bäcklund orbits: windowed RMS drift, its growth exponent, heyoka alongside.

* :func:`invariant_drift_curve` -- 1e5 steps of the batched ``bt_step`` (used by ``tests/test_stress.py``
  and ``symbt/benchmarks/drift_figure.py``).
* :func:`windowed_rms` -- the measure of issue 26: at log-spaced ``n_k`` the RMS of the relative drift
  ``(H(x_m) - H(x_0)) / |H(x_0)|`` over the stored states with ``n_k / 2 < m <= n_k``, over members and
  invariants, and the fitted log-log exponent (random walk 0.5, systematic drift 1).
* :func:`kernel_drift` -- orbits of the fused kernel (``bt_orbit``'s single-state route) of the paper's
  example (N = 3) or the ``n64-chain`` / ``n256-chain`` states, stored two ways: ``store="absolute"``, the
  float64 positions ``bt_orbit`` returns, and ``store="modular"``, the same orbit with each stored position
  taken relative to a common multiple of 64 (:func:`modular_orbit`, a measuring device: only the
  read-out of the stored rows differs, the orbit is the kernel's bit for bit).  The invariants see only
  ``q_{j+1} - q_j``: the absolute rows round them to ``ulp(|q|)`` and ``|q|`` grows linearly with the
  centre of mass, which by itself gives drift ~ n; the modular rows show the drift of the orbit.
* :func:`heyoka_drift` -- the same measure for heyoka's ``taylor_adaptive`` on the flow the map
  interpolates (N = 3, explicit polynomials) at a given tolerance.

Invariants are evaluated at 50 digits (N <= 8: ``H_0..H_{N-1}``; larger N: ``tr L`` at ``lam0`` and
``lam0 +- mu``).  ``python -m symbt.benchmarks.drift --help`` runs the measurement and draws the figure
(BENCHMARKS.md, "Drift at the round-off limit").

>>> import numpy as np
>>> n = np.arange(1, 10**4 + 1)
>>> rel = 1e-16 * n[:, None, None].astype(float)          # a drift growing exactly like n
>>> edges, rms, slope = windowed_rms(n, rel, nwin=6)
>>> abs(slope - 1.0) < 0.02                              # whole-step windows: 0.99
True
"""
from __future__ import annotations

import argparse
import json
import time
from collections.abc import Callable
from typing import Any

import mpmath
import numpy as np

from ..numeric import bt_step, invariants, spectral_trace
from ..numeric.float64.kernels import _dd_add, _logf
from ..paper import P_EXAMPLE, Q_EXAMPLE

__all__ = ["invariant_drift_curve", "windowed_rms", "drift_case", "modular_orbit", "unguarded_orbit", "kernel_drift",
           "heyoka_drift", "plot_drift"]

P_PAPER, Q_PAPER = P_EXAMPLE, Q_EXAMPLE
#: stored positions of :func:`modular_orbit` are taken modulo this power of two (exact)
MODULUS = 64.0


def invariant_drift_curve(n=10**5, members=16, npoints=40, lam0=10.0, mu=5.0, seed=0, spread=1e-9,
                          keep_first=False):
    """Relative invariant drift of float64 BT orbits of the paper's example, for a growth fit.

    ``members`` orbits start at the paper's state perturbed by ``spread``
    (independent round-off, same torus to ~1e-9); they are advanced together
    with the batched :func:`~symbt.numeric.bt_step` (centre of mass removed each
    step -- the invariants only see ``q`` differences).  At ``npoints``
    log-spaced steps the invariants of the float64 states are evaluated at 40
    digits (so evaluation round-off does not mask the drift).  Returns
    ``(steps, drift)`` with ``drift[i, m, k] = |H_k(x_n) - H_k(x_0)| / |H_k(x_0)|``
    and the RMS over members and k, and the fitted log-log slope of the RMS
    drift versus n (over n >= 100).  Member 0 is the paper's state itself;
    ``keep_first=True`` also returns its whole centred trajectory ``(P, Q)``.
    """
    rng = np.random.default_rng(seed)
    p = np.array(P_PAPER) + spread * rng.normal(size=(members, 3))
    q = np.array(Q_PAPER) + spread * rng.normal(size=(members, 3))
    p[0], q[0] = P_PAPER, Q_PAPER                 # member 0: the paper's state itself
    q = q - q.mean(-1, keepdims=True)
    traj = (np.empty((n + 1, 3)), np.empty((n + 1, 3))) if keep_first else None
    if keep_first:
        traj[0][0], traj[1][0] = p[0], q[0]
    steps = np.unique(np.round(np.logspace(0, np.log10(n), npoints)).astype(int))

    def inv_mp(p, q):
        with mpmath.workdps(40):
            return [invariants([mpmath.mpf(float(a)) for a in pp], [mpmath.mpf(float(b)) for b in qq])
                    for pp, qq in zip(p, q)]
    H0 = inv_mp(p, q)
    drift = np.empty((len(steps), members, 3))
    k = 0
    for i in range(1, n + 1):
        p, q = bt_step(p, q, lam0, mu)
        q = q - q.mean(-1, keepdims=True)
        if keep_first:
            traj[0][i], traj[1][i] = p[0], q[0]
        if i == steps[k]:
            H = inv_mp(p, q)
            with mpmath.workdps(40):
                for m in range(members):
                    for j in range(3):
                        drift[k, m, j] = float(abs(H[m][j] - H0[m][j]) / abs(H0[m][j]))
            k += 1
    rms = np.sqrt(np.mean(drift**2, axis=(1, 2)))
    sel = steps >= 100
    slope = float(np.polyfit(np.log(steps[sel]), np.log(rms[sel]), 1)[0])
    if keep_first:
        return steps, drift, rms, slope, traj
    return steps, drift, rms, slope


def windowed_rms(steps: Any, rel: Any, nwin: int = 12, first: int | None = None) -> tuple[Any, Any, float]:
    """Windowed RMS drift and its fitted log-log exponent.

    ``steps`` (S,): step numbers of stored states; ``rel`` (S, members, K): relative drift of invariant
    k of member m at each stored state.  Windows end at ``nwin`` log-spaced ``n_k`` from ``first``
    (default ``steps[-1] / 1000``, at least the second stored step) to ``steps[-1]``; window k holds the
    states with ``n_k / 2 < step <= n_k``.  Returns ``(n_k, rms_k, exponent)``.

    >>> import numpy as np
    >>> rng = np.random.default_rng(1)
    >>> walk = np.cumsum(rng.normal(size=(10**5, 200)), axis=0)[:, :, None]     # 200 random walks
    >>> e, r, s = windowed_rms(np.arange(1, 10**5 + 1), walk, nwin=8)
    >>> 0.45 < s < 0.55
    True
    """
    steps = np.asarray(steps)
    rel = np.asarray(rel, dtype=float)
    lo = max(float(first) if first else steps[-1] / 1000.0, float(steps[1]))
    edges = np.unique(np.round(np.logspace(np.log10(lo), np.log10(steps[-1]), nwin)).astype(np.int64))
    rms = []
    keep = []
    for e in edges:
        sel = (steps > e / 2) & (steps <= e)
        if sel.any():
            rms.append(float(np.sqrt(np.mean(rel[sel] ** 2))))
            keep.append(e)
    edges = np.array(keep)
    rms_a = np.array(rms)
    slope = float(np.polyfit(np.log(edges), np.log(rms_a), 1)[0])
    return edges, rms_a, slope


def drift_case(N: int) -> tuple[Any, Any, float, float]:
    """``(p, q, lam0, mu)`` of the drift runs: N = 3 the paper's example (mu = 5), N = 64 / 256 the
    benchmark chains ``n64-chain`` / ``n256-chain`` (:mod:`symbt.benchmarks.cases`), the latter at
    ``lam0 = 8.3`` (the kernel refuses its ``lam0 = 3.4`` as ill-conditioned).

    >>> drift_case(3)[2:]
    (10.0, 5.0)
    """
    from .cases import cases

    if N == 3:
        return np.array(P_PAPER), np.array(Q_PAPER), 10.0, 5.0
    c = {64: cases()[3], 256: cases()[4]}[N]
    if N == 256:
        # n256-chain's own lam0 = 3.4 is refused by the kernel's conditioning guard (trace decision, KAPPA_MAX);
        # at 8.3 it is decided, and fl(lam0 + mu) - fl(lam0 - mu) != 2 mu as at 3.4 (the inconsistent case)
        return np.array(c.p), np.array(c.q), 8.3, c.mu
    return np.array(c.p), np.array(c.q), c.lam0, c.mu


def _modular_position(qh: float, ql: float, fh: float, fl: float) -> float:
    """``qh + ql + log F`` minus the multiple of :data:`MODULUS` nearest ``qh`` (exact), rounded once."""
    c = MODULUS * np.floor(qh / MODULUS + 0.5)
    h, lo = _dd_add(qh - c, ql, _logf(fh, fl))
    return h + lo


_MODULAR: dict[str, Any] = {}


def _decided_unguarded(aux: Any, t: float, disc: float, tt: Any, i: int, p: Any, r: Any, lam: float,
                       lo: float) -> bool:
    """The float64 hook ``decided`` recording the condition but never refusing (a measuring device)."""
    tt[i + 2] = (aux[0] + aux[3]) * abs(t) / abs(disc) * (aux[4] / aux[5])
    return True


def _trusted_unguarded(kt: float, u: float, w: float, dn: float, x: float) -> bool:
    return True


def unguarded_orbit(store: str = "absolute") -> Any:
    """:func:`symbt.numeric.float64.kernels.orbit` (numba) with its two conditioning refusals (status 5,
    ``KAPPA_MAX``) switched off; ``store="modular"`` also reads out as :func:`modular_orbit`.

    A measuring device: since the conditioning guard, the shipped kernel refuses the drift cases' long
    orbits somewhere (``n64-chain`` within 10 steps, one perturbed orbit of the paper's example between
    1e4 and 1e5 steps) and ``bt_orbit`` recomputes them on the general path; this runs the kernel's
    arithmetic through those states (every other operation unchanged).
    """
    key = "unguarded-" + store
    if key not in _MODULAR:
        from ..numeric.float64.jit import orbit_with

        hooks: dict[str, Callable[..., Any]] = {"decided": _decided_unguarded, "trusted": _trusted_unguarded}
        extra = {"_dd_position": _modular_position} if store == "modular" else {}
        _MODULAR[key] = orbit_with(hooks, **extra)
    return _MODULAR[key]


def modular_orbit() -> Any:
    """The single-state kernel :func:`symbt.numeric.float64.kernels.orbit` (numba), storing positions modulo 64.

    Same arguments; the orbit is the kernel's operation for operation, only the stored ``q`` rows are
    ``q - 64 k`` (``k`` per stored position; :func:`unwrap` recovers the differences ``q_{j+1} - q_j``,
    which are below 32 in modulus here), each rounded once at a magnitude below 64 instead of ``|q|``.
    """
    if "orbit" not in _MODULAR:
        from ..numeric.float64.jit import orbit_with

        _MODULAR["orbit"] = orbit_with(_dd_position=_modular_position)
    return _MODULAR["orbit"]


def unwrap(Q: Any) -> Any:
    """Positions with consecutive differences brought into ``(-MODULUS/2, MODULUS/2]`` (exact).

    >>> unwrap(np.array([[63.5, 0.25, 1.0]])).tolist()          # differences 0.75, 0.75
    [[63.5, 64.25, 65.0]]
    """
    Q = np.array(Q, dtype=float)
    d = np.diff(Q, axis=-1)
    d -= MODULUS * np.round(d / MODULUS)
    return np.concatenate([Q[..., :1], Q[..., :1] + np.cumsum(d, axis=-1)], axis=-1)


def _invariants_50(p: Any, q: Any, lams: tuple, qlo: Any = None) -> list:
    with mpmath.workdps(50):
        P = [mpmath.mpf(float(a)) for a in p]
        Q = [mpmath.mpf(float(b)) for b in q]
        if qlo is not None:                 # the low parts of q_low rows, added exactly
            Q = [b + mpmath.mpf(float(c)) for b, c in zip(Q, qlo)]
        if len(P) <= 8:
            return list(invariants(P, Q))
        return [spectral_trace(mpmath.mpf(lam), P, Q) for lam in lams]


def _relative_drift(P: Any, Q: Any, rows: Any, H0: list, lams: tuple, Qlo: Any = None) -> Any:
    out = np.empty((len(rows), len(H0)))
    with mpmath.workdps(50):
        for i, r in enumerate(rows):
            H = _invariants_50(P[r], Q[r], lams, None if Qlo is None else Qlo[r])
            out[i] = [float((a - b) / abs(b)) for a, b in zip(H, H0)]
    return out


def _sample_rows(steps: Any, n: int, nwin: int, per_window: int) -> Any:
    lo = max(n / 1000.0, float(steps[1]))
    edges = np.logspace(np.log10(lo), np.log10(n), nwin)
    rows = set()
    for e in edges:
        sel = np.flatnonzero((steps > e / 2) & (steps <= e))
        if sel.size:
            rows.update(sel[np.linspace(0, sel.size - 1, min(per_window, sel.size)).astype(int)].tolist())
    return np.array(sorted(rows))


def kernel_drift(N: int = 3, n: int = 10**6, members: int = 4, store: str = "absolute", seed: int = 0,
                 spread: float = 1e-9, nwin: int = 12, per_window: int = 8, guarded: bool = True) -> dict:
    """Windowed RMS drift of ``members`` kernel orbits (member 0 the case's state, the others perturbed).

    ``store``: ``"absolute"`` (the positions ``bt_orbit`` returns), ``"low"`` (the same with their low
    parts, ``bt_orbit(..., q_low=True)``) or ``"modular"`` (:func:`modular_orbit`); ``guarded=False``
    runs :func:`unguarded_orbit` (the kernel's arithmetic without its conditioning refusals).

    Returns a dict with ``n_k``, ``rms``, ``exponent``, ``final`` (relative drift of each member and
    invariant at step n), ``seconds_per_step`` (the kernel alone) and the settings.
    """
    from ..numeric.float64.jit import kernel
    from ..numeric.float64.kernels import ANCHOR, orbit_rows, stored_steps

    p0, q0, lam0, mu = drift_case(N)
    lams = (lam0 - mu, lam0, lam0 + mu)
    if guarded:
        fn = modular_orbit() if store == "modular" else kernel("orbit", "numba")[0]
    else:
        fn = unguarded_orbit(store)
    every = max(1, n // 20000)
    steps = np.array(stored_steps(n, every))
    rows = _sample_rows(steps, n, nwin, per_window)
    rng = np.random.default_rng(seed)
    rel = np.empty((rows.size, members, 3))        # N <= 8: H_0..H_2 (N = 3); else tr L at 3 lams
    t_kernel = 0.0
    for m in range(members):
        p = p0 + (spread * rng.normal(size=N) if m else 0.0)
        q = q0 + (spread * rng.normal(size=N) if m else 0.0)
        P = np.empty((orbit_rows(n, every), N))
        Q = np.empty((orbit_rows(n, every), 2 * N if store == "low" else N))
        t0 = time.perf_counter()
        st = fn(p, q, lam0 + mu, lam0 - mu, 2.0 * mu, 1, n, every, ANCHOR, P, Q)
        t_kernel += time.perf_counter() - t0
        if st != 0:
            raise RuntimeError("kernel status %d" % st)
        Qlo = None
        if store == "modular":
            Q = unwrap(Q)
        elif store == "low":
            Q, Qlo = Q[:, :N], Q[:, N:]
        rel[:, m] = _relative_drift(P, Q, rows, _invariants_50(p, q, lams), lams, Qlo)
    edges, rms, slope = windowed_rms(steps[rows], rel, nwin)
    return {"N": N, "n": n, "members": members, "store": store, "guarded": guarded,
            "n_k": edges.tolist(), "rms": rms.tolist(),
            "exponent": slope, "final": rel[-1].tolist(), "seconds_per_step": t_kernel / (members * n)}


def heyoka_drift(n: int = 10**6, tol: float = 1e-16, members: int = 4, seed: int = 0, spread: float = 1e-9,
                 nwin: int = 12, per_window: int = 8) -> dict:
    """The same measure for heyoka's float64 ``taylor_adaptive`` on the flow the map interpolates (N = 3).

    The map is the time-1 map of ``sum c_k H_k``; heyoka integrates Hamilton's equations to ``t = n``
    (explicit polynomials, exact ``c_k`` from :func:`~symbt.numeric.flow_coefficients`).
    """
    from ..numeric import flow_coefficients
    from .heyoka_system import load, polynomial_system

    hy, msg = load()
    if hy is None:
        return {"skipped": msg}
    p0, q0, lam0, mu = drift_case(3)
    lams = (lam0 - mu, lam0, lam0 + mu)
    steps = np.arange(0, n + 1)
    rows = _sample_rows(steps, n, nwin, per_window)
    grid = steps[rows].astype(float)
    rng = np.random.default_rng(seed)
    rel = np.empty((rows.size, members, 3))
    secs = 0.0
    for m in range(members):
        p = p0 + (spread * rng.normal(size=3) if m else 0.0)
        q = q0 + (spread * rng.normal(size=3) if m else 0.0)
        c = flow_coefficients(p, q, lam0, mu)
        ta = hy.taylor_adaptive(polynomial_system(hy, 3, [float(v) for v in c]), list(np.concatenate([q, p])),
                                tol=tol)
        t0 = time.perf_counter()
        out = ta.propagate_grid(np.concatenate([[0.0], grid]))
        secs += time.perf_counter() - t0
        Y = out[-1][1:]
        rel[:, m] = _relative_drift(Y[:, 3:], Y[:, :3], range(rows.size), _invariants_50(p, q, lams), lams)
    edges, rms, slope = windowed_rms(steps[rows], rel, nwin)
    return {"N": 3, "n": n, "members": members, "tol": tol, "n_k": edges.tolist(), "rms": rms.tolist(),
            "exponent": slope, "final": rel[-1].tolist(), "seconds": secs, "heyoka": msg}


def plot_drift(results: dict, path: str) -> None:
    """Log-log figure: windowed RMS drift vs n of every run in ``results["runs"]``, with sqrt(n) and n guides."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    runs = [r for r in results["runs"] if "rms" in r]
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.3), sharey=True)
    for ax, pick in zip(axes, (lambda r: "tol" not in r, lambda r: r.get("N") == 3)):
        for r in runs:
            if not pick(r):
                continue
            if "tol" in r:
                label, style = "heyoka tol %g, N=3 (exp. %.2f)" % (r["tol"], r["exponent"]), "s-"
            else:
                label = "BT kernel N=%d, %s rows (exp. %.2f)" % (r["N"], r["store"], r["exponent"])
                style = {"modular": "o-", "low": "^-"}.get(r["store"], "o--")
            ax.loglog(r["n_k"], r["rms"], style, ms=3, label=label)
        n = np.array([1e3, 1e7])
        ax.loglog(n, 1e-14 * np.sqrt(n / n[0]), "k:", lw=0.8, label="sqrt(n) guide")
        ax.loglog(n, 1e-14 * (n / n[0]), "k-.", lw=0.8, label="n guide")
        ax.set_xlabel("steps n (heyoka: t = n)")
        ax.grid(True, which="major", alpha=0.3)
        ax.legend(fontsize=7)
    axes[0].set_title("Bäcklund map, fused float64 kernel", fontsize=10)
    axes[1].set_title("N = 3, paper's example: BT kernel and heyoka", fontsize=10)
    axes[0].set_ylabel("windowed RMS relative drift of the invariants")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def main(argv: list | None = None) -> int:
    """Command line: the drift runs, a JSON record and the figure."""
    ap = argparse.ArgumentParser(prog="python -m symbt.benchmarks.drift", description=__doc__.split("\n")[0])
    ap.add_argument("--n", type=float, default=1e7, help="steps for N = 3 (default 1e7)")
    ap.add_argument("--n64", type=float, default=1e7, help="steps for N = 64 (default 1e7)")
    ap.add_argument("--n256", type=float, default=1e6, help="steps for N = 256 (default 1e6)")
    ap.add_argument("--members", type=int, default=4, help="orbits per N = 3 run (default 4)")
    ap.add_argument("--members-large", type=int, default=2, help="orbits per N = 64 / 256 run (default 2)")
    ap.add_argument("--heyoka-tol", type=float, default=1e-16)
    ap.add_argument("--no-heyoka", action="store_true")
    ap.add_argument("--reuse-heyoka", action="store_true",
                    help="copy the heyoka run from the existing --json record (its inputs unchanged) instead of "
                    "rerunning it (~840 s)")
    ap.add_argument("--stores", default="absolute,low,modular", help="row read-outs to measure")
    ap.add_argument("--guarded", action="store_true",
                    help="the shipped kernel with its conditioning refusals (default: unguarded_orbit, which "
                    "runs through the states the guard refuses)")
    ap.add_argument("--json", default="benchmarks/results/drift.json")
    ap.add_argument("--figure", default="docs/figures/drift_roundoff.png")
    a = ap.parse_args(argv)
    runs = []
    old_runs = []
    if a.reuse_heyoka:
        with open(a.json) as fh:
            old_runs = [r for r in json.load(fh)["runs"] if "tol" in r]
    for N, n in ((3, a.n), (64, a.n64), (256, a.n256)):
        for store in a.stores.split(","):
            r = kernel_drift(N, int(n), a.members if N == 3 else a.members_large, store, guarded=a.guarded)
            print("kernel N=%d n=%.0e %-8s exponent %.2f, rms at n %.2e, %.3g us/step" % (
                N, n, store, r["exponent"], r["rms"][-1], 1e6 * r["seconds_per_step"]), flush=True)
            runs.append(r)
    if old_runs:
        runs += [dict(r, reused=True) for r in old_runs]
    elif not a.no_heyoka:
        r = heyoka_drift(int(a.n), a.heyoka_tol, a.members)
        if "rms" in r:
            print("heyoka tol %g n=%.0e exponent %.2f, rms at n %.2e, %.1f s" % (
                a.heyoka_tol, a.n, r["exponent"], r["rms"][-1], r["seconds"]), flush=True)
        runs.append(r)
    res = {"date": time.strftime("%Y-%m-%d %H:%M"), "runs": runs}
    with open(a.json, "w") as fh:
        json.dump(res, fh, indent=1)
    plot_drift(res, a.figure)
    print("wrote", a.json, a.figure)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
