"""The work-precision figure: final error against wall time, one panel per case (matplotlib, lazily)."""
from __future__ import annotations

import os

__all__ = ["plot_work_precision"]

_LINES = {"scipy DOP853": ("o-", "C0"), "scipy RK45": ("s-", "C1"), "scipy LSODA": ("^-", "C2"),
          "Gauss-Legendre s=3 (order 6)": ("d-", "C3"), "heyoka taylor_adaptive (float64)": ("h-", "C4")}
_POINTS = {"BT fast_orbit (numba)": ("*", "k", 14), "BT fast_orbit (python)": ("P", "k", 9),
           "BT bt_orbit (auto)": ("X", "0.4", 9)}


def plot_work_precision(results: dict, path: str) -> None:
    """Write the figure to ``path`` (PNG); ODE/heyoka sweeps as lines, BT contenders as points."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    cases = results["cases"]
    ncol = min(len(cases), 3)
    nrow = -(-len(cases) // ncol)
    fig, axes = plt.subplots(nrow, ncol, figsize=(4.4 * ncol, 4.0 * nrow + 0.6), squeeze=False)
    for ax in axes.ravel()[len(cases):]:
        ax.set_visible(False)
    floor = 1e-17
    for ax, cr in zip(axes.ravel(), cases):
        runs = [r for r in cr["runs"] if "final_err" in r]
        for name, (mk, col) in _LINES.items():
            rr = sorted([r for r in runs if r["method"] == name], key=lambda r: r["time_s"])
            if rr:
                ax.loglog([r["time_s"] for r in rr], [max(r["final_err"], floor) for r in rr], mk, color=col, ms=4,
                          label=name.replace("scipy ", "").replace(" taylor_adaptive (float64)", " (float64)"))
        for r in runs:
            key = r["method"].split(" [")[0]
            if key in _POINTS:
                mk, col, ms = _POINTS[key]
                ax.loglog([r["time_s"]], [max(r["final_err"], floor)], mk, color=col, ms=ms, ls="none",
                          label=key.replace("BT ", "BT: "))
            elif r["method"].startswith("BT generated"):
                ax.loglog([r["time_s"]], [max(r["final_err"], floor)], "v", color="m", ms=8, ls="none",
                          label="BT: generated step")
        ax.set_title("%s (N=%d, %d steps)" % (cr["case"], cr["N"], cr["steps"]), fontsize=9)
        ax.set_xlabel("wall time [s]")
        ax.grid(True, which="major", alpha=0.3)
    for row in axes:
        row[0].set_ylabel("final relative error")
    handles: dict = {}
    for ax in axes.ravel():
        for h, lab in zip(*ax.get_legend_handles_labels()):
            handles.setdefault(lab, h)
    fig.legend(list(handles.values()), list(handles.keys()), fontsize=8, loc="lower center",
               ncol=min(len(handles), 5), frameon=False)
    label = " (--quick, provisional)" if results.get("quick") else ""
    fig.suptitle("Work-precision: Bäcklund map vs ODE solvers on the flow of sum c_k H_k%s" % label, fontsize=10)
    fig.tight_layout(rect=(0, 0.1, 1, 0.97))
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    fig.savefig(path, dpi=100)
    plt.close(fig)
