r"""Paths the claims did not reach (issue 21, seed 18).

* ``paths.many_rows.n3`` -- past ``SIDE_BY_SIDE_ROWS`` rows ``step_core(FLOAT)`` and ``float_status`` work site
  by site (lists over the sites, not stacked arrays): ``paths.threshold``'s scans (both sides of ``KAPPA_MAX``)
  repeated to 2304 rows give the bits and statuses of the same rows in batches of one scan (a consistency check
  of the two forms of one computation).  And ``bt_orbit``'s block ensemble (the python backend: the kernel numba
  compiles, in plain Python) over one block - 1, one block and one block + 1 states gives each state's bits in a
  batch of the distinct states alone: a last block that is partial, full, or one state long (seed 18: a block
  count rounded up once too often added a block of negative length past the batch, which both kernels happened to
  tolerate; the count is a ceiling division now).
* ``library.qd_marker`` -- the compiled quad-double kernel's cache marker, which decides whether
  ``backend="auto"`` takes it: in a temporary ``NUMBA_CACHE_DIR`` and ``HOME``, the digest recomputed from the six
  sources and numba's version, a stale marker not ready, a loaded kernel ready, the marker written into a
  directory made for it and over a stale one.
* ``paths.lohner_reorth.n{3,13}`` -- Lohner frames re-orthogonalised (``MAX_FRAME_COND`` lowered to 1): every
  hull still contains the literal orbit at 80 digits, and the counter counts the condition checks.
* ``library.importable`` -- ``importable`` on an importable, a missing and a broken module (one that raises on
  import).
* ``shipped.loop_xy.n5`` -- the loop form's Dapp x and y against eq. xy as printed, through
  :func:`symbt.codegen.verify.xy_vs_printed` (as ``codegen.xy`` for the closed forms; seed 20: a sign error in
  the loop form's ``dapp_y`` passed every default claim).
"""
from __future__ import annotations

import mpmath as mp
import numpy as np

from ._shipped import scale_parts, scaled, without_numba
from .base import Outcome, Parts, claim, failed, skipped


@claim("paths.many_rows", equation="bt_step", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       where="symbt/numeric/core/step.py: step_core past SIDE_BY_SIDE_ROWS rows (_over_sites site by site, "
             "float_status's condition test per site); core/condition.py: monodromy_and_abs's two calls",
       statement="step_core(FLOAT) and float_status on paths.threshold's scans (N={N}; per branch, repeated past "
                 "SIDE_BY_SIDE_ROWS rows) give the bits and statuses of the same rows in batches of one scan "
                 "(the stacked form), the statuses both OK and ILLCOND; bt_orbit's block ensemble (python) over one "
                 "block - 1, one block and one block + 1 states gives each state's bits in a batch of the distinct "
                 "states")
def many_rows(N: int) -> Outcome:
    from ..numeric.core.condition import SIDE_BY_SIDE_ROWS
    from ..numeric.core.context import FLOAT
    from ..numeric.core.limits import ILLCOND, OK
    from ..numeric.core.step import float_status, step_core
    from .shipped_routes import threshold_states

    def run(rows: list, b: int) -> tuple[np.ndarray, np.ndarray]:
        pa, qa = np.array([st[0] for st in rows]), np.array([st[1] for st in rows])
        l0, m = np.array([st[2] for st in rows]), np.array([st[3] for st in rows])
        with np.errstate(all="ignore"):
            Pn, Qn, aux = step_core(FLOAT, list(pa.T.copy()), list(qa.T.copy()), l0, m, b, check_real=False)
            status = float_status(aux, Pn, Qn)
        return np.concatenate([np.array(Pn), np.array(Qn)]).T, np.asarray(status)

    bad: list[str] = []
    counts = []
    for b in (1, -1):
        scans = [list(sts) for _, bb, sts in threshold_states() if bb == b]
        one = [st for sts in scans for st in sts]
        rows = one * (SIDE_BY_SIDE_ROWS // len(one) + 1)
        X, st = run(rows, b)
        parts = [run(sts, b) for sts in scans]
        Xs = np.concatenate([x for x, _ in parts] * (len(rows) // len(one)))
        sts = np.concatenate([s for _, s in parts] * (len(rows) // len(one)))
        if not (np.array_equal(X, Xs, equal_nan=True) and np.array_equal(st, sts)):
            rows_off = np.flatnonzero(np.any((X != Xs) & ~(np.isnan(X) & np.isnan(Xs)), axis=1) | (st != sts))
            bad.append(f"branch {b}: {rows_off.size} of {len(rows)} rows differ (first {rows_off[:3].tolist()})")
        counts.append((len(rows), int(np.sum(st == OK)), int(np.sum(st == ILLCOND))))
        if not (np.any(st == OK) and np.any(st == ILLCOND)):
            bad.append(f"branch {b}: the statuses are not both OK and ILLCOND (the test would not see the estimate)")
    # the block ensemble (python backend) over M = one block - 1, one block, one block + 1 states: each row the
    # bits of the same state in a batch of the distinct states alone (a last block that is partial, full or one
    # state long)
    from ..codegen.verify import map_states
    from ..numeric import bt_orbit
    from ..numeric.float64.orbit import _block_rows

    states = map_states(N)
    block = _block_rows(N)

    def batch(idx: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        with without_numba(), np.errstate(all="ignore"):
            return bt_orbit(np.array([states[i][0] for i in idx]), np.array([states[i][1] for i in idx]),
                            np.array([states[i][2] for i in idx]), np.array([states[i][3] for i in idx]), 2,
                            backend="python")
    Pd, Qd = batch(np.arange(len(states)))
    for M in (block - 1, block, block + 1):
        idx = np.arange(M) % len(states)
        Pm, Qm = batch(idx)
        if not (np.array_equal(Pm, Pd[:, idx]) and np.array_equal(Qm, Qd[:, idx])):
            bad.append(f"the block ensemble over {M} states (blocks of {block}) differs from the distinct states' "
                       "batch")
    detail = "; ".join(f"{n} rows ({ok} OK, {ill} ILLCOND)" for n, ok, ill in counts) + \
        f" (SIDE_BY_SIDE_ROWS = {SIDE_BY_SIDE_ROWS}); block ensembles of {block - 1}, {block}, {block + 1} " \
        "states."
    if bad:
        return failed("numeric: step_core past SIDE_BY_SIDE_ROWS rows vs batches of one scan",
                      detail="; ".join(bad) + ". " + detail)
    return Outcome("verified", "numeric: step_core past SIDE_BY_SIDE_ROWS rows vs batches of one scan, bit for bit "
                   "(consistency)", evidence="sampled", n_scope=[N], detail=detail,
                   printed="the same bits and statuses")


@claim("library.qd_marker", equation="bt_step", source_equation="imptransf", scene="library", requires=("numba",),
       where="symbt/numeric/multiprec/qd.py: _marker_dirs, _digest, qd_ready, _mark_ready (the compiled quad-double "
             "kernel's cache marker, which decides whether backend='auto' takes it)",
       statement="with NUMBA_CACHE_DIR and HOME in a temporary directory and no kernel loaded in the process: the "
                 "marker is looked for in NUMBA_CACHE_DIR, the package's __pycache__ and ~/.cache/symbt, in that "
                 "order; the digest is the SHA-256 of qd.py, qd_arith.py, qd_step.py, core/limits.py, core/fused.py, "
                 "core/compile.py and numba's version; qd_ready is true exactly when one of them holds the digest "
                 "(a stale marker is not), or when a kernel with signatures is loaded; _mark_ready writes the "
                 "digest into the first, made if missing, over a stale marker if there")
def qd_marker() -> Outcome:
    import hashlib
    import importlib.util
    import os
    import tempfile
    from importlib.metadata import version
    from pathlib import Path

    from ..numeric.multiprec import qd

    if importlib.util.find_spec("numba") is None:
        return skipped("numba is not installed (.[fast]): the marker digests its version")
    here = Path(qd.__file__).parent
    core = here.parent / "core"
    h = hashlib.sha256()
    for path in (here / "qd.py", here / "qd_arith.py", here / "qd_step.py", core / "limits.py", core / "fused.py",
                 core / "compile.py"):
        h.update(path.read_bytes())
    h.update(version("numba").encode())
    digest = h.hexdigest()
    bad: list[str] = []
    saved_env = {k: os.environ.get(k) for k in ("NUMBA_CACHE_DIR", "HOME")}
    loaded = qd._compiled.pop("qd_orbit", None)
    with tempfile.TemporaryDirectory(prefix="symbt-qd-marker-") as tmp:
        cache, home = Path(tmp) / "numba", Path(tmp) / "home"
        os.environ["NUMBA_CACHE_DIR"], os.environ["HOME"] = str(cache), str(home)
        try:
            dirs = qd._marker_dirs()
            want_dirs = [cache, here / "__pycache__", home / ".cache" / "symbt"]
            if dirs != want_dirs:
                bad.append(f"marker dirs {dirs}, documented {want_dirs}")
            if qd._digest() != digest:
                bad.append("the digest is not the SHA-256 of the six sources and numba's version")
            # the package's own __pycache__ is outside the claim's control: read, not written
            pkg = here / "__pycache__" / qd._MARKER
            pkg_ready = pkg.is_file() and pkg.read_text(encoding="utf-8").strip() == digest
            if qd.qd_ready() != pkg_ready:
                bad.append(f"no marker in the temporary dirs: qd_ready {qd.qd_ready()}, the package's marker "
                           f"says {pkg_ready}")
            cache.mkdir(parents=True)
            (cache / qd._MARKER).write_text("0" * 64 + "\n", encoding="utf-8")
            if qd.qd_ready() != pkg_ready:
                bad.append("a stale marker in NUMBA_CACHE_DIR made qd_ready true")
            # a kernel loaded in the process (a dispatcher with signatures) is ready whatever the markers say
            for sigs, want in (([("float64[:]",)], True), ([], pkg_ready)):
                qd._compiled["qd_orbit"] = type("Loaded", (), {"signatures": sigs})()
                if qd.qd_ready() != want:
                    bad.append(f"a loaded kernel with {len(sigs)} signatures: qd_ready {not want}")
                del qd._compiled["qd_orbit"]
            # _mark_ready into a NUMBA_CACHE_DIR that does not exist yet, two levels down: made, then written
            fresh = Path(tmp) / "a" / "b"
            os.environ["NUMBA_CACHE_DIR"] = str(fresh)
            qd._mark_ready()
            marker = fresh / qd._MARKER
            if not (marker.is_file() and marker.read_text(encoding="utf-8") == digest + "\n"):
                bad.append("_mark_ready did not write the digest into a new NUMBA_CACHE_DIR")
            if not qd.qd_ready():
                bad.append("qd_ready is false after _mark_ready")
            if marker.is_file():
                marker.write_text("0" * 64 + "\n", encoding="utf-8")      # stale again, the directory there
                qd._mark_ready()
            if not (marker.is_file() and marker.read_text(encoding="utf-8") == digest + "\n"):
                bad.append("_mark_ready did not rewrite a stale marker in an existing NUMBA_CACHE_DIR")
            if list(fresh.glob("*.tmp")):
                bad.append("_mark_ready left its temporary file")
        finally:
            for k, v in saved_env.items():
                if v is None:
                    os.environ.pop(k, None)
                else:
                    os.environ[k] = v
            if loaded is not None:
                qd._compiled["qd_orbit"] = loaded
    if bad:
        return failed("the quad-double cache marker", detail="; ".join(bad))
    return Outcome("verified", "exact: the quad-double cache marker vs its documented rule (digest recomputed)",
                   evidence="proof", n_scope="all",
                   detail=f"digest {digest[:12]}...; the package's own marker {'current' if pkg_ready else 'absent'}")


#: paths.lohner_reorth: steps per size (the small frame checks its condition every _COND_EVERY = 32 steps, a frame
#: past _SMALL = 24 coordinates at every step), the balls' precision, the reference's digits
REORTH_STEPS, REORTH_PREC, REORTH_DPS = {3: 40, 13: 3}, 160, 80


@claim("paths.lohner_reorth", equation="bt_orbit", source_equation="imptransf", scene="numeric-paths",
       sizes=(3, 13), requires=("flint",),
       where="symbt/numeric/multiprec/lohner.py: LohnerSet's frames re-orthogonalised (_small_frame at 2N <= 24, "
             "_frame_of beyond) past MAX_FRAME_COND",
       statement="LohnerSet on an admissible state (N={N}, exact input, 160 bits; 40 steps at N = 3, 3 at N = 13) "
                 "with MAX_FRAME_COND lowered to 1 (restored after) re-orthogonalises at every condition check -- "
                 "every 32nd step of the small frame, every step beyond 24 coordinates -- and at its own threshold "
                 "never on these runs; either way every hull contains the literal orbit (80 digits)")
def lohner_reorth(N: int) -> Outcome:
    from flint import arb

    from ..numeric.multiprec import lohner
    from ..numeric.multiprec.arb import flint_prec
    from ..reference.literal import reference_step
    from ..reference.samples import admissible_states

    n = REORTH_STEPS[N]
    with mp.workdps(30):
        st = admissible_states(N, 1, 1)[0]
    p, q, l0, m = [float(v) for v in st[0]], [float(v) for v in st[1]], float(st[2]), float(st[3])
    ref = []
    with mp.workdps(REORTH_DPS):
        a, b = [mp.mpf(v) for v in p], [mp.mpf(v) for v in q]
        for _ in range(n):
            a, b = reference_step(a, b, mp.mpf(l0), mp.mpf(m))
            ref.append(a + b)
    bad: list[str] = []
    counts = {}
    saved = lohner.MAX_FRAME_COND
    for threshold in (1.0, saved):
        lohner.MAX_FRAME_COND = threshold
        try:
            with flint_prec(REORTH_PREC):
                S = lohner.LohnerSet([arb(v) for v in p + q])
                for i in range(n):
                    S.step(arb(l0), arb(m), 1)
                    with flint_prec(REORTH_DPS * 4):
                        if not all(h.contains(arb(mp.nstr(x, REORTH_DPS))) for h, x in zip(S.hull, ref[i])):
                            bad.append(f"threshold {threshold:g}: the hull at step {i + 1} misses the literal orbit")
                            break
        finally:
            lohner.MAX_FRAME_COND = saved
        counts[threshold] = S.reorthogonalised
    want = n if 2 * N > lohner._SMALL else n // lohner._COND_EVERY
    if counts[1.0] != want or counts[saved] != 0:
        bad.append(f"re-orthogonalised {counts[1.0]} times at threshold 1 (every check: {want}), {counts[saved]} "
                   f"at {saved:g} (none expected)")
    detail = f"{n} steps; re-orthogonalised {counts[1.0]} times at threshold 1, {counts[saved]} at {saved:g}."
    if bad:
        return failed("numeric: Lohner frames re-orthogonalised", detail="; ".join(bad[:3]) + " " + detail)
    return Outcome("verified", "numeric: Lohner sets with re-orthogonalised frames vs the literal orbit (80 digits)",
                   evidence="sampled", n_scope=[N], detail=detail)


@claim("library.importable", equation="bt_step", source_equation="imptransf", scene="library",
       where="symbt/numeric/core/errors.py: importable (what the optional features ask before they run)",
       statement="importable is true for an importable module, false for a missing one and for one whose import "
                 "raises (a broken installation: a temporary package that raises on import), and keeps its answer")
def importable_modules() -> Outcome:
    import sys
    import tempfile
    from pathlib import Path

    from ..numeric.core import errors

    bad: list[str] = []
    with tempfile.TemporaryDirectory(prefix="symbt-importable-") as tmp:
        name = "symbt_broken_probe_" + Path(tmp).name.replace("-", "_")
        (Path(tmp) / f"{name}.py").write_text("raise RuntimeError('a broken installation')\n", encoding="utf-8")
        sys.path.insert(0, tmp)
        try:
            got = {"math": errors.importable("math"), "missing": errors.importable(name + "_missing"),
                   "broken": errors.importable(name)}
            again = errors.importable(name)
        finally:
            sys.path.remove(tmp)
            sys.modules.pop(name, None)
            for key in (name, name + "_missing"):
                errors._IMPORTABLE.pop(key, None)
    if got != {"math": True, "missing": False, "broken": False} or again is not False:
        bad.append(f"importable: {got}, asked again for the broken one: {again}")
    if bad:
        return failed("importable", detail="; ".join(bad))
    return Outcome("verified", "exact: importable on an importable, a missing and a broken module", evidence="proof",
                   n_scope="all", detail=f"{got}")


@claim("shipped.loop_xy", equation="toda{N}.dapp_xy", source_equation="xy", scene="shipped", sizes=(5,),
       parts=scale_parts,
       where="symbt codegen --n {N}: toda{N}.py (loop form): dapp_xy_mp",
       statement="the loop form's Dapp x and y (N={N}, mpmath at 50 digits) = eq. xy as printed (literal_step's "
                 "x and y_1 at 70 digits) within a relative 1e-45, both branches, on codegen.verify's states (as "
                 "codegen.xy checks the closed forms)")
def loop_xy(N: int, parts: Parts) -> Outcome:
    from types import SimpleNamespace

    from ..codegen import verify
    from .shipped_emitted import emitted_module

    mod = emitted_module(N)
    s = parts.printed["scale"]
    # codegen.verify's own comparison (as codegen.xy), on the loop form's x and y times the printed scale
    probe = SimpleNamespace(dapp_xy_mp=lambda *args: scaled(list(mod.dapp_xy_mp(*args)), s))
    worst = verify.xy_vs_printed(probe, N)  # type: ignore[arg-type]
    detail = (f"{2 * len(verify.map_states(N))} (state, branch) pairs; worst relative difference "
              f"{mp.nstr(worst, 3)}.")
    if not worst <= verify.MP_TOL:
        return failed("numeric: the loop form's dapp_xy vs eq. xy as printed", residual=float(worst), detail=detail)
    return Outcome("verified", "numeric: the loop form's dapp_xy vs eq. xy as printed (literal_step, 70 digits)",
                   evidence="sampled", n_scope=[N], residual=float(worst), detail=detail)
