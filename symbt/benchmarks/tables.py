"""Markdown for ``bench.md``: the summary against heyoka, the per-case tables and the other experiments.

The summary ratio is ``heyoka time / symbt time`` measured in the same run (> 1: symbt is faster),
heyoka at its cheapest setting that reaches symbt's final error, or -- marked "not reached" --
its most accurate setting.  heyoka's JIT build time is listed apart and not in the ratio.
"""
from __future__ import annotations

__all__ = ["summary_rows", "format_summary", "format_tables"]


def _fmt(t: float | None, e: float | None) -> str:
    if t is None:
        return "n/a"
    return "%.3g s, err %.1e" % (t, e) if e is not None else "%.3g s" % t


def _case(results: dict, name: str) -> dict | None:
    return next((c for c in results.get("cases", []) if c["case"] == name), None)


def _from_headline(cr: dict, key: str, what: str) -> dict | None:
    h = cr.get("headline", {}).get(key + "_vs_heyoka")
    if not h:
        return None
    jit = next((r.get("jit_s") for r in cr["runs"]
                if r["method"].startswith("heyoka") and r.get("param") == h["param"]), None)
    return {"what": what, "symbt": "%s: %s" % (h["bt"], _fmt(h["bt_time_s"], h["bt_final_err"])),
            "heyoka": "tol %g: %s%s%s" % (h["param"], _fmt(h["contender_time_s"], h["contender_final_err"]),
                                         "" if h["reached"] else " (does not reach symbt's error)",
                                         "" if jit is None else "; JIT %.2g s" % jit),
            "ratio": h["ratio"]}


def summary_rows(results: dict) -> list[dict]:
    """Rows ``{what, symbt, heyoka, ratio}`` of the summary table (those that ran)."""
    rows: list = []
    cr = _case(results, "paper-mu5")
    if cr:
        rows.append(_from_headline(cr, "bt_orbit", "float64, paper N=3 mu=5, %d steps: documented call bt_orbit"
                                   % cr["steps"]))
        rows.append(_from_headline(cr, "kernel", "float64, paper N=3 mu=5, %d steps: fused kernel fast_orbit"
                                   % cr["steps"]))
    for d in ("50", "100"):
        row = results.get("precision", {}).get(d)
        if row and "time_s" in row.get("heyoka", {}):
            h = row["heyoka"]
            rows.append({"what": "%s digits, %d steps (paper N=3 mu=5)" % (d, results["precision"]["steps"]),
                         "symbt": "bt_orbit on mpf (%s): %s" % (row["bt"].get("backend", "auto"),
                                                                 _fmt(row["bt"]["time_s"], row["bt"]["err"])),
                         "heyoka": "heyoka.real %d bits, tol 1e-%s: %s; JIT %.2g s" % (
                             h["prec_bits"], d, _fmt(h["time_s"], h["err"]), h["jit_s"]),
                         "ratio": h["ratio"]})
    ens = results.get("ensemble")
    if ens and "heyoka" in ens:
        h = ens["heyoka"]
        best = min((h["loop"], h.get("ensemble_api", h["loop"])), key=lambda r: r["time_s"])
        rows.append({"what": "ensemble M=%d, N=3, %d steps" % (ens["M"], ens["steps"]),
                     "symbt": "bt_orbit on (M, N): %s" % _fmt(ens["bt"]["time_s"], ens["bt"]["max_err"]),
                     "heyoka": "batch (SIMD %d), tol %g, %s threads: %s%s; JIT %.2g s" % (
                         h["simd"], h["tol"], best["threads"], _fmt(best["time_s"], h["max_err"]),
                         "" if h["max_err"] <= ens["bt"]["max_err"] else " (does not reach symbt's error)",
                         h["jit_s"]),
                     "ratio": ens["ratio"]})
    for name in ("n64-chain", "n256-chain"):
        cr = _case(results, name)
        if cr:
            for key, label in (("kernel", "fast_orbit"), ("bt_orbit", "bt_orbit")):
                rows.append(_from_headline(cr, key, "float64, N=%d, %d steps: %s" % (cr["N"], cr["steps"], label)))
    return [r for r in rows if r]


def format_summary(results: dict) -> str:
    rows = summary_rows(results)
    if not rows:
        return "(no heyoka rows: heyoka not installed, --no-heyoka, or no case ran)\n"
    lines = ["| what | symbt | heyoka | heyoka time / symbt time |", "|---|---|---|---|"]
    for r in rows:
        lines.append("| %s | %s | %s | %.3g |" % (r["what"], r["symbt"], r["heyoka"], r["ratio"]))
    return "\n".join(lines) + "\n"


def _case_table(cr: dict) -> list[str]:
    lines = ["### %s -- %s" % (cr["case"], cr["note"]), ""]
    lines.append("N=%d, lam0=%g, mu=%g, branch=%+d, %d steps (T=%d); field: %s; heyoka: %s; c_k = %s" % (
        cr["N"], cr["lam0"], cr["mu"], cr["branch"], cr["steps"], cr["T"], cr.get("field", "-"),
        cr.get("heyoka_system", cr.get("heyoka_skipped", "-")),
        ", ".join("%.6g" % v for v in cr["c"]) if cr["N"] <= 8 else "(%d values)" % cr["N"]))
    lines += ["", "| method | tol / h | final err | max err | invariant drift | time [s] | repeats | nfev / steps |",
              "|---|---|---|---|---|---|---|---|"]
    for r in cr["runs"]:
        par = "" if r.get("param") is None else "%g" % r["param"]
        if "failed" in r:
            lines.append("| %s | %s | failed: %s | | | | | |" % (r["method"], par, r["failed"]))
            continue
        lines.append("| %s | %s | %.2e | %.2e | %.1e | %.3e | %d | %s |" % (
            r["method"], par, r["final_err"], r["max_err"], r["inv_drift"], r["time_s"], r["repeats"], r["nfev"]))
    setup = []
    for k, v in cr["setup"].items():
        if isinstance(v, dict):
            setup.append("%s {%s}" % (k, ", ".join("%s: %.2g s" % kv for kv in v.items())))
        else:
            setup.append("%s %.3g s" % (k, v))
    lines += ["", "Set-up (not in the times above): " + "; ".join(setup), "",
              "**Headline:** " + cr["headline"]["text"], ""]
    return lines


def format_tables(results: dict) -> str:
    """The whole ``bench.md``."""
    m = results["machine"]
    lines = ["# symbt bench%s -- %s" % (" --quick (provisional numbers)" if results.get("quick") else "",
                                        results["date"]), "",
             "Command: `%s`; machine: %s, %s cores, %s; python %s, numpy %s, scipy %s, numba %s, heyoka %s; "
             "load average at start %s; total %.0f s." % (
                 results.get("command", "symbt bench"), m.get("cpu"), m.get("cores"), m.get("platform"),
                 m.get("python"), m.get("numpy"), m.get("scipy"), m.get("numba"), m.get("heyoka"),
                 m.get("loadavg"), results.get("total_s", 0.0)), "",
             "## Summary against heyoka (same run)", "", format_summary(results)]
    for cr in results["cases"]:
        lines += _case_table(cr)
    prec = results.get("precision")
    if prec:
        lines += ["## High precision (paper N=3, mu=5, %d steps)" % prec["steps"], "",
                  "| digits | method | time [s] | error | note |", "|---|---|---|---|---|"]
        for d in ("50", "100"):
            row = prec.get(d)
            if not row:
                continue
            lines.append("| %s | BT bt_orbit (mpmath) | %.3e | %.1e | |" % (d, row["bt"]["time_s"], row["bt"]["err"]))
            h = row.get("heyoka", {})
            if "time_s" in h:
                lines.append("| %s | heyoka.real (%d bits, order %d) | %.3e | %.1e | JIT %.2f s; %.3gx the BT |" % (
                    d, h["prec_bits"], h["order"], h["time_s"], h["err"], h["jit_s"], h["ratio"]))
            t = row.get("symbt_taylor")
            if t:
                lines.append("| %s | symbt Taylor (hamiltonian_flow) | %.3e | %.1e | %d steps of order %d; %.3gx the "
                             "BT |" % (d, t["time_s"], t["err"], t["steps"], t["order"], t["ratio"]))
        lines.append("")
    ens = results.get("ensemble")
    if ens:
        lines += ["## Ensemble (M=%d, N=3, %d steps, %d scored members)" % (ens["M"], ens["steps"],
                                                                          ens["scored_members"]), ""]
        lines.append("* symbt `bt_orbit` on (M, N) arrays: %.3g s, max error %.1e" % (ens["bt"]["time_s"],
                                                                                    ens["bt"]["max_err"]))
        h = ens.get("heyoka")
        if h:
            lines.append("* heyoka tolerances tried (max error on the scored members): " + ", ".join(
                "%g: %.1e" % (t["tol"], t["max_err"]) for t in ens["heyoka_tolerances_tried"]))
            lines.append("* heyoka tol %g, batch of %d, one thread (integrator re-used): %.3g s; "
                         "`ensemble_propagate_until_batch` (all cores): %s; max error %.1e; JIT %.2g s" % (
                             h["tol"], h["simd"], h["loop"]["time_s"],
                             "%.3g s" % h["ensemble_api"]["time_s"] if "ensemble_api" in h else "n/a",
                             h["max_err"], h["jit_s"]))
        lines.append("")
    thr = results.get("throughput")
    if thr:
        def numpy_cols(r: dict, key: str, own: str, fmt: str) -> str:   # runs recorded before the column existed
            return (fmt + " | %.2f") % (r[key], r[key] / r[own]) if key in r else "- | -"

        lines += ["## Throughput of the batched float64 step", "",
                  "| batch (N=3) | s per call | system-steps/s | numpy route [s per call] | numpy / default |",
                  "|---|---|---|---|---|"]
        lines += ["| %d | %.3e | %.3e | %s |" % (r["batch"], r["time_s"], r["steps_per_s"],
                                                 numpy_cols(r, "numpy_time_s", "time_s", "%.3e"))
                  for r in thr["batch"]]
        lines += ["", "| N (batch 256) | system-steps/s | ns per site-step | numpy route [ns per site-step] | "
                  "numpy / default |", "|---|---|---|---|---|"]
        lines += ["| %d | %.3e | %.1f | %s |" % (r["N"], r["steps_per_s"], r["ns_per_site_step"],
                                                numpy_cols(r, "numpy_ns_per_site_step", "ns_per_site_step", "%.1f"))
                  for r in thr["vsN"]]
        if "slope_time_vs_N" in thr:
            lines.append("\nlog-log slope of time per system-step vs N (N >= 128): %.3f" % thr["slope_time_vs_N"])
        lines.append("")
    be = results.get("band_edge")
    if be:
        lines += ["## Band edge", "", "| side | \\|tr\\|-2 | err | cond | eps cond | err / (eps cond) |",
                  "|---|---|---|---|---|---|"]
        lines += ["| %+d | %.1e | %.2e | %.2e | %.2e | %.3f |" % (r["side"], r["delta"], r["err"], r["cond"],
                                                                 r["eps_cond"], r["ratio"]) for r in be]
        lines.append("")
    return "\n".join(lines)
