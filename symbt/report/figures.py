r"""Figures 1 and 2 of the paper (Sec. 3.3, Numerics), regenerated: ``symbt figures --out DIR``.

Both figures use the paper's example p = (-20, 10, 1), q = (1, 0, 0.9), lam0 = 10, branch
gamma = +sqrt(tr^2 - 4) (the branch of eq. ``eqdisc`` and of the negative caption constants):

* Fig. 1 (``fig1.png``): left, the continuous flow of sum_k c_k H_k (mu = 5) for t in [0, 3500];
  right, the first 3500 BT iterates; axes (p3, q2 - Q, q3 - Q), Q = (q1 + q2 + q3)/3.
* Fig. 2 (``fig2.png``): continuous trajectories (grey) and BT iterates (black dots, at t = n)
  of p1 (left) and q1 - Q (right), mu = 5 (top) and mu = 2 (bottom).

The c_k come from eq. ``eqdisc`` at 30 digits (:func:`symbt.numeric.flow_coefficients`);
the flow is integrated by ``scipy.integrate.solve_ivp`` (DOP853, rtol = atol = 1e-12) on
Hamilton's equations of sum_k c_k H_k (:class:`symbt.numeric.flow.field.FlowField`); the iterates are
:func:`symbt.numeric.bt_orbit` (float64), or a float loop over :func:`symbt.reference.literal.literal_step`
if that is unavailable.  matplotlib and scipy are imported only here, inside :func:`main`.
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from collections.abc import Sequence

    import numpy as np
    import numpy.typing as npt

from ..paper import CAPTIONS, EXAMPLE, LAM0_EXAMPLE, P_EXAMPLE, Q_EXAMPLE

__all__ = ["main", "paper_example_data"]

P0, Q0, LAM0 = P_EXAMPLE, Q_EXAMPLE, LAM0_EXAMPLE
PRINTED = {float(mu): consts for mu, consts in CAPTIONS["fig:2"].items()}


def _constants(mu: float) -> list[float]:
    import mpmath as mp

    from ..numeric import flow_coefficients

    with mp.workdps(30):
        c = flow_coefficients([mp.mpf(v) for v in EXAMPLE["p"]], [mp.mpf(v) for v in EXAMPLE["q"]],
                              mp.mpf(EXAMPLE["lam0"]), mp.mpf(mu), branch=1, ks=range(4))
    return [float(v) for v in c]


def _iterates(mu: float, n: int) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    import numpy as np

    try:
        from ..numeric import bt_orbit
    except ImportError:  # pragma: no cover - fallback while symbt.numeric is incomplete
        bt_orbit = None  # type: ignore[assignment]
    if bt_orbit is not None:
        P, Q = bt_orbit(list(P0), list(Q0), LAM0, mu, n, branch=1)
        return np.asarray(P, float), np.asarray(Q, float)
    import mpmath as mp  # pragma: no cover

    from ..reference.literal import literal_step
    P, Q = [list(P0)], [list(Q0)]
    with mp.workdps(20):
        for _ in range(n):
            pt, qt, _ = literal_step(P[-1], Q[-1], LAM0, mu, 1)
            P.append([float(v) for v in pt])
            Q.append([float(v) for v in qt])
    return np.array(P), np.array(Q)


def _flow(mu: float, T: float,
          per_unit: int) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    import numpy as np
    from scipy.integrate import solve_ivp

    from ..numeric.flow.field import FlowField

    f = FlowField(list(P0), list(Q0), LAM0, mu, branch=1).rhs
    t_eval = np.linspace(0.0, T, int(round(T * per_unit)) + 1)
    sol = solve_ivp(f, (0.0, T), list(Q0) + list(P0), method="DOP853", rtol=1e-12, atol=1e-12, t_eval=t_eval)
    if not sol.success:
        raise RuntimeError(f"solve_ivp failed: {sol.message}")
    return sol.t, sol.y[3:].T, sol.y[:3].T  # t, P, Q


def paper_example_data(mu: float, n: int, T: float | None = None, per_unit: int = 20) -> dict[str, Any]:
    """Constants, iterates and flow for the paper's example; also the max |flow(n) - BT^n(x)|."""
    import numpy as np

    c = _constants(mu)
    P, Q = _iterates(mu, n)
    T = n if T is None else T
    t, Pf, Qf = _flow(mu, T, per_unit)
    idx = np.arange(0, min(n, int(T)) + 1) * per_unit
    dev = float(max(np.abs(Pf[idx] - P[: len(idx)]).max(), np.abs(Qf[idx] - Q[: len(idx)]).max()))
    return dict(c=c, P=P, Q=Q, t=t, Pf=Pf, Qf=Qf, deviation=dev)


def _cstr(c: Sequence[float], k: int = 3, tex: bool = True) -> str:
    if tex:
        return ", ".join(f"$c_{i}={v:.4g}$" for i, v in enumerate(c[:k]))
    return ", ".join(f"c_{i} = {v:.12g}" for i, v in enumerate(c[:k]))


def figure1(out: Path, n: int = 3500) -> dict[str, Any]:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    d = paper_example_data(5.0, n, per_unit=10)
    fig = plt.figure(figsize=(12, 6))
    for i, (title, P, Q, style) in enumerate((
            (f"continuous flow of $\\sum_k c_k H_k$, $t\\in[0,{n}]$", d["Pf"], d["Qf"], dict(lw=0.15, color="0.25")),
            (f"first {n} BT iterates ($\\lambda_0=10$, $\\mu=5$)", d["P"], d["Q"], dict(s=0.6, color="k")))):
        ax = fig.add_subplot(1, 2, i + 1, projection="3d")
        Qc = Q.mean(axis=1)
        x, y, z = P[:, 2], Q[:, 1] - Qc, Q[:, 2] - Qc
        if "s" in style:
            ax.scatter(x, y, z, depthshade=False, **style)
        else:
            ax.plot(x, y, z, **style)
        ax.set_xlabel("$p_3$")
        ax.set_ylabel("$q_2 - Q$")
        ax.set_zlabel("$q_3 - Q$")
        ax.set_title(title, fontsize=10)
        ax.view_init(elev=25, azim=-60)
    fig.suptitle("Fig. 1: $p=(-20,10,1)$, $q=(1,0,0.9)$, $Q=(q_1+q_2+q_3)/3$; "
                 f"{_cstr(d['c'])} (paper: $c_0=-0.005$, $c_1=-0.048$, $c_2=-0.512$)", fontsize=10)
    fig.text(0.5, 0.02, f"max |flow(t=n) - BT$^n$| over n $\\leq$ {n}: {d['deviation']:.1e} "
             "(float64 iterates vs DOP853 at rtol 1e-12)", ha="center", fontsize=9)
    fig.savefig(out / "fig1.png", dpi=110)
    plt.close(fig)
    return d


def figure2(out: Path, n: int = 40) -> dict[float, dict[str, Any]]:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, 2, figsize=(12, 7), sharex=True)
    devs = {}
    for row, mu in enumerate((5.0, 2.0)):
        d = paper_example_data(mu, n, per_unit=50)
        devs[mu] = d
        nn = range(n + 1)
        Qc, Qcf = d["Q"].mean(axis=1), d["Qf"].mean(axis=1)
        for col, (lab, yf, yd) in enumerate((("$p_1$", d["Pf"][:, 0], d["P"][:, 0]),
                                             ("$q_1 - Q$", d["Qf"][:, 0] - Qcf, d["Q"][:, 0] - Qc))):
            ax = axes[row, col]
            ax.plot(d["t"], yf, color="0.6", lw=1.2, label="continuous flow")
            ax.plot(list(nn), yd, "k.", ms=5, label="BT iterates")
            ax.set_ylabel(lab)
            ax.set_title(f"$\\mu={mu:g}$: " + (f"ours {_cstr(d['c'])}" if col == 0 else
                                                f"printed in the caption: ({', '.join(PRINTED[mu])})"), fontsize=9)
            if row == 1:
                ax.set_xlabel("$t$ (= iteration $n$ at the dots)")
    axes[0, 0].legend(loc="lower right", fontsize=8)
    fig.suptitle("Fig. 2: $p=(-20,10,1)$, $q=(1,0,0.9)$, $\\lambda_0=10$; the smaller $\\mu$ is the smaller time step",
                 fontsize=10)
    fig.tight_layout(rect=(0, 0, 1, 0.96))
    fig.savefig(out / "fig2.png", dpi=110)
    plt.close(fig)
    return devs


def main(argv: Sequence[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="symbt figures", description="Regenerate Figs. 1-2 of the paper (PNG).")
    ap.add_argument("--out", default="docs/figures", help="output directory (default docs/figures)")
    ap.add_argument("--iterates", type=int, default=3500, help="BT iterates in Fig. 1 (default 3500)")
    ap.add_argument("--window", type=int, default=40, help="iterates shown in Fig. 2 (default 40)")
    args = ap.parse_args(list(argv or []))
    try:
        import matplotlib  # noqa: F401
        import scipy  # noqa: F401
    except ImportError as exc:
        print(f"symbt figures: needs matplotlib and scipy (pip install 'symbt[plot,scipy]'): {exc}",
              file=sys.stderr)
        return 2
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    d1 = figure1(out, args.iterates)
    d2 = figure2(out, args.window)
    print(f"wrote {out / 'fig1.png'} (max |flow - BT| over {args.iterates} steps: {d1['deviation']:.1e})")
    print(f"wrote {out / 'fig2.png'} (max |flow - BT|: mu=5 {d2[5.0]['deviation']:.1e}, "
          f"mu=2 {d2[2.0]['deviation']:.1e})")
    print(f"c_k (mu=5): {_cstr(d1['c'], tex=False)}; (mu=2): {_cstr(d2[2.0]['c'], tex=False)}; "
          f"{time.perf_counter() - t0:.1f}s")
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main(sys.argv[1:]))
