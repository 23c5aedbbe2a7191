# ---
# jupyter:
#   jupytext:
#     formats: py:percent
#   kernelspec:
#     display_name: Python 3
#     language: python
#     name: python3
# ---

# %% [markdown]
# # Falling with quadratic drag, checked
#
# This notebook walks through `note.tex` -- a short derivation of our own, with two displays
# printed wrong on purpose -- and shows what symbt says about each labelled display.  Run it from
# this directory (`jupytext --to ipynb --execute walkthrough.py`, or open it in Jupyter with
# jupytext); as a plain script (`python walkthrough.py`) it prints the same results as text.
#
# The model (eq. `model`) is $\dot v = g - k v^2$ with $g, k > 0$; it lives in `drag_model.py`,
# which every claim imports.

# %%
import symbt
import sympy as sp

from drag_model import RATE, V_T, dimensionless, drag_rhs, model_ode, t, v0, w

try:
    from IPython.display import display
    in_notebook = get_ipython() is not None  # noqa: F821 -- defined in IPython only
except (ImportError, NameError):
    in_notebook = False


def show(*objs):
    """Rich cards in Jupyter, text in a terminal."""
    for obj in objs:
        display(obj) if in_notebook else print(obj)


show(sp.Eq(sp.Symbol("vdot"), drag_rhs(sp.Symbol("v"))), sp.Eq(sp.Symbol("v_T"), V_T))

# %% [markdown]
# ## Every claim of the note
#
# `symbt.verify()` reads `[tool.symbt]` in `pyproject.toml` (the claims module, the note, the
# reasons) and returns one result per claim; in Jupyter each renders as a card with its status,
# its evidence (`proof` or `sampled`) and, for an erratum, the printed and corrected statements and
# the scope generated from the domain cells.

# %%
results = {r.claim.id: r for r in symbt.verify()}
for r in results.values():
    show(r)

# %% [markdown]
# ## Eq. `v`: exact, in the dimensionless time
#
# $v = \sqrt{g/k}\tanh(\sqrt{gk}\,t)$ solves the model.  `symbt.solves_ode` takes the ODE and the
# closed form; in $s = \sqrt{gk}\,t$ (with $g = k w^2$, $w = v_T$) the residual is a rational
# function of $e^{s}$, so it is *proved* rather than sampled.  In the original variables the square
# roots of $g$ and $k$ stop the exact layer, and the same check is sampled -- and says so:

# %%
v = V_T * sp.tanh(RATE * t)
proof = symbt.solves_ode(model_ode(in_s=True), dimensionless(v))
sampled = symbt.solves_ode(model_ode(), v)
show(model_ode(), proof.verdict + " by " + proof.method, sampled.verdict + " by " + sampled.method)
assert proof.verdict == "proved" and sampled.evidence == "sampled"

# %% [markdown]
# ## Eq. `t99`: a dropped factor 1/2
#
# The note prints $t_{99} = \ln 199/\sqrt{gk}$.  But $\tanh(\ln 199) = 39600/39602 \ne 0.99$: the
# claim `drag.t99` is an **erratum**, and its correction
# $t_{99} = \operatorname{artanh}(0.99)/\sqrt{gk} = \ln(199)/(2\sqrt{gk})$ is proved.

# %%
show(sp.tanh(sp.log(199)), sp.tanh(sp.log(199) / 2))
show(results["drag.t99"])

# %% [markdown]
# ## Eq. `v0`: a formula that holds in some cells only
#
# With an initial velocity $v_0$ the note prints
# $v = v_T\tanh\bigl(\sqrt{gk}\,t + \tfrac12\ln\lvert (v_T+v_0)/(v_T-v_0)\rvert\bigr)$.  The claim
# samples four cells of a `symbt.Domain` -- $\lvert v_0\rvert$ below or above $v_T$, times the
# sign of $v_0$ -- at seeded points; the scope sentence below is generated from that table, not
# written by hand:

# %%
out = results["drag.v0"].outcome
print(out.scope)
for c in out.cells:
    print(c["cell"], f"{c['printed_holds']}/{c['n']} printed, {c['corrected_holds']}/{c['n']} corrected")
assert out.status == "erratum"

# %% [markdown]
# Above $v_T$ the absolute value hides a change of branch: the printed formula starts at
# $v_T^2/v_0$, not at $v_0$.  (Written with $\operatorname{artanh}(v_0/v_T)$ instead, the formula
# would hold for every $v_0$ under the principal complex branch -- artanh picks up $\pm i\pi/2$ and
# $\tanh(u + i\pi/2) = \coth u$ -- which is why the corrected statement spells out its branches.)

# %%
a = sp.Symbol("a", positive=True)                       # v0 = (1 + a) v_T
start = V_T * sp.tanh(sp.log(sp.Abs((V_T + v0) / (V_T - v0))) / 2)
show(symbt.check_identity(dimensionless(start.subs(v0, (1 + a) * V_T)), w / (1 + a)))   # w = v_T
