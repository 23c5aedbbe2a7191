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
# # 01 · The periodic Toda lattice (Section 3, first part)
#
# The model of Section 3: the Lax matrix (eq. `eq:lax`), the Hamiltonians as coefficients
# of its trace (eq. `tra`), their involutivity (eq. `Hj`), the $N=2$ trace (eq. `tn2`)
# and the action variables (eq. `th1th2`), and the three $N=3$ Hamiltonians printed in the
# Numerics subsection (an erratum).
#
# Everything is built in the rational variables $E_j = e^{q_j}$ (positive symbols), so
# that identities of the model are identities of rational functions and are *proved*
# by exact cancellation (`symbt.proof`).

# %%
import sys
from pathlib import Path

try:
    import symbt
except ImportError:  # running from a checkout without installing
    sys.path.insert(0, str(Path(globals().get("__file__", "derivations/x")).resolve().parents[1]))

import itertools

import sympy as sp

from symbt.engine import Walkthrough
from symbt.proof.identity import check_identity
from symbt.symbolic.toda import local_lax, toda_model

wt = Walkthrough()            # loads every claim module
show, display = wt.show, wt.display

# %% [markdown]
# ## The Lax matrix, eq. (`eq:lax`)
#
# $$L(\lambda) = \begin{pmatrix}A(\lambda)&B(\lambda)\\C(\lambda)&D(\lambda)\end{pmatrix}
#   = l_N(\lambda)\cdots l_1(\lambda),\qquad
#   l_j(\lambda)=\begin{pmatrix}\lambda+p_j&-e^{q_j}\\ e^{-q_j}&0\end{pmatrix}.$$
#
# Each $\det l_j = 1$, hence $\det L = 1$.  For $N = 2$:

# %%
m = toda_model(2)
lam = m.lam
display(local_lax(lam, m.p[0], m.E[0]))
display(m.L)
display(check_identity(m.L.det(), 1))
show("lax.n2", "lax.n3", "lax.n4")

# %% [markdown]
# ## Hamiltonians from the trace, eq. (`tra`)
#
# $$\operatorname{tr}L(\lambda) = A(\lambda)+D(\lambda) = \sum_{k=0}^N H_k\lambda^k,\qquad H_N = 1.$$

# %%
m3 = toda_model(3)
display(sp.Poly(m3.trace, lam).as_expr())
for k, H in enumerate(m3.hamiltonians):
    display(f"H_{k} = {sp.sstr(sp.powsimp(m3.to_q(H)))}")
show("tra.n2", "tra.n3", "tra.n4")

# %% [markdown]
# ## Involution, eq. (`Hj`)
#
# With $\{p_i, q_j\} = \delta_{ij}$: $\{H_i, H_j\} = 0$ for all $i, j$.  We compute every
# bracket for $N=3$; the bracket is not trivially zero ($\{H_{N-1}, e^{q_1}\} = e^{q_1}$).

# %%
for i, j in itertools.combinations(range(3), 2):
    r = check_identity(m3.poisson(m3.hamiltonians[i], m3.hamiltonians[j]), 0)
    display(f"{{H_{i}, H_{j}}} = 0: {r.status}")
display(check_identity(m3.poisson(m3.hamiltonians[2], m3.E[0]), m3.E[0]))
show("Hj.n2", "Hj.n3", "Hj.n4")

# %% [markdown]
# ## The case $N=2$, eqs. (`tn2`) and (`th1th2`)
#
# $$A(\lambda)+D(\lambda)=\lambda^2+(p_1+p_2)\lambda+p_1p_2-2\cosh(q_1-q_2)$$
# and with $I_1=\frac{p_1+p_2}{2}$, $I_2 = 2\cosh(q_1-q_2)+\left(\frac{p_1-p_2}{2}\right)^2$
# the trace becomes $(\lambda+I_1)^2-I_2$.

# %%
(p1, p2), (q1, q2) = m.p, m.q
tn2 = lam ** 2 + (p1 + p2) * lam + p1 * p2 - 2 * sp.cosh(q1 - q2)
display(check_identity(m.to_E(tn2), m.trace))
I1 = (p1 + p2) / 2
I2 = 2 * sp.cosh(q1 - q2) + ((p1 - p2) / 2) ** 2
display(check_identity((lam + I1) ** 2 - I2, m.to_q(m.trace)))
show("tn2", "th1th2.trace")

# %% [markdown]
# The angle $\theta_2$ of eq. (`th1th2`) involves an elliptic integral; it is treated in
# `06_n2_elliptic.py`.
#
# ## The $N=3$ Hamiltonians of the Numerics subsection — an erratum
#
# The paper prints
# $$\begin{aligned}
# H_1 &= p_1+p_2+p_3,\\
# H_2 &= p_1p_2+p_2p_2+p_3p_1-e^{q_1-q_3}-e^{q_2-q_1}-e^{q_3-q_2},\\
# H_3 &= p_1p_2p_3-p_2e^{q_1-q_3}-p_3e^{q_2-q_1}-p_1e^{q_3-q_2}.
# \end{aligned}$$
# Two things go wrong.  The labels are reversed with respect to eq. (`tra`) (the printed
# $H_k$ is the coefficient of $\lambda^{3-k}$, and eq. (`tra`) has $H_3=1$), and $p_2p_2$
# is a typo for $p_2p_3$ — as printed, $H_2$ is not even in involution with $H_3$:

# %%
(P1, P2, P3), (Q1, Q2, Q3) = m3.p, m3.q
e = sp.exp
H2_printed = P1 * P2 + P2 * P2 + P3 * P1 - e(Q1 - Q3) - e(Q2 - Q1) - e(Q3 - Q2)
H2_fixed = P1 * P2 + P2 * P3 + P3 * P1 - e(Q1 - Q3) - e(Q2 - Q1) - e(Q3 - Q2)
H3 = P1 * P2 * P3 - P2 * e(Q1 - Q3) - P3 * e(Q2 - Q1) - P1 * e(Q3 - Q2)
bracket_printed = check_identity(m3.poisson(m3.to_E(H2_printed), m3.to_E(H3)), 0)
display(bracket_printed)
display(check_identity(m3.poisson(m3.to_E(H2_fixed), m3.to_E(H3)), 0))
display(check_identity(m3.to_E(H2_fixed), m3.hamiltonians[1]))
show("n3-hamiltonians.tra", "n3-hamiltonians.involution")

# %% [markdown]
# **Corrected statement:** the printed $H_k$ is the coefficient of $\lambda^{3-k}$ in
# $\operatorname{tr}L(\lambda)$, with $H_2 = p_1p_2+p_2p_3+p_3p_1-e^{q_1-q_3}-e^{q_2-q_1}-e^{q_3-q_2}$.
#
# ## Outcomes

# %%
wt.expect({
    "lax.n2": "verified", "lax.n3": "verified", "lax.n4": "verified",
    "tra.n2": "verified", "tra.n3": "verified", "tra.n4": "verified",
    "Hj.n2": "verified", "Hj.n3": "verified", "Hj.n4": "verified",
    "tn2": "verified", "th1th2.trace": "verified",
    "n3-hamiltonians.tra": "erratum", "n3-hamiltonians.involution": "erratum",
})
assert bracket_printed.status == "false"
print("01_toda_model: all claim outcomes as expected")
