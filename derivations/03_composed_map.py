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
# # 03 · The composed two-parameter map (Section 3)
#
# Eqs. `D`, `new`, `l1l2`, `v1v2`, `xy`, `lam0mu`: the Darboux matrix $\mathcal D$ of the
# composed BT, its kernels at $\lambda_1,\lambda_2$, the explicit $x, y$ and the limit
# $\mu\to0$.  One erratum: the eigenvalue of $L(\lambda_2)$ on $|\Omega_2\rangle$ (eq. `v1v2`).
#
# *Branch convention* (not in the paper, fixed by the claims): $\gamma(\lambda_i) =
# b\sqrt{\operatorname{tr}L(\lambda_i)^2-4}$ with the same sign $b=\pm1$ at both points.

# %%
import sys
from pathlib import Path

try:
    import symbt
except ImportError:  # running from a checkout without installing
    sys.path.insert(0, str(Path(globals().get("__file__", "derivations/x")).resolve().parents[1]))

import mpmath as mp
import sympy as sp

from symbt.engine import Walkthrough
from symbt.proof.identity import check_identity
from symbt.reference.literal import lax_matrix, literal_step
from symbt.reference.samples import admissible_states
from symbt.symbolic.darboux import composed_darboux, lam1, lam2
from symbt.symbolic.toda import lam

wt = Walkthrough()            # loads every claim module
show, display = wt.show, wt.display

# %% [markdown]
# ## The Darboux matrix, eq. (`D`), and its kernels
#
# $$\mathcal D(\lambda,\lambda_1,\lambda_2)=\begin{pmatrix}\lambda-\lambda_1-xy&-x\\
#   y(\lambda_1-\lambda_2+xy)&\lambda-\lambda_2+xy\end{pmatrix}$$
# is degenerate at $\lambda_1,\lambda_2$ with kernels $|\Omega_1\rangle=(1,-y)^T$ and
# $|\Omega_2\rangle=(x,\lambda_2-\lambda_1-xy)^T$.

# %%
x, y = sp.symbols("x y")
Dm = composed_darboux(x, y)
display(Dm)
display(sp.factor(Dm.det()))
Om1, Om2 = sp.Matrix([1, -y]), sp.Matrix([x, lam2 - lam1 - x * y])
display(check_identity(Dm.subs(lam, lam1) * Om1, sp.zeros(2, 1)))
display(check_identity(Dm.subs(lam, lam2) * Om2, sp.zeros(2, 1)))
show("D.n2", "D.n3")

# %% [markdown]
# ## Eigenvectors and $x$, $y$: eqs. (`l1l2`), (`v1v2`), (`xy`)
#
# $\tilde L\mathcal D=\mathcal D L$ (eq. `new`) forces $|\Omega_i\rangle$ to be eigenvectors of
# $L(\lambda_i)$.  For a unimodular $L=\begin{pmatrix}A&B\\C&D\end{pmatrix}$ ($C = (AD-1)/B$),
# $(1,-y)^T$ is an eigenvector iff $By^2-(A-D)y-C=0$, i.e.
# $$y=\frac{A(\lambda_1)-D(\lambda_1)+\gamma(\lambda_1)}{2B(\lambda_1)},\qquad
#   \gamma^2=(A+D)^2-4,$$
# with eigenvalue $A-yB = \frac{A+D-\gamma}{2} = v(\lambda_1)$ as printed.  We check both modulo
# $\gamma^2 = \operatorname{tr}^2-4$ (so for either sign of $\gamma$):

# %%
A, B, D, g = sp.symbols("A B D gamma")
L = sp.Matrix([[A, B], [(A * D - 1) / B, D]])
y1 = (A - D + g) / (2 * B)
rel = {g: g ** 2 - ((A + D) ** 2 - 4)}
display(check_identity(L * sp.Matrix([1, -y1]), (A + D - g) / 2 * sp.Matrix([1, -y1]), relations=rel))

# %% [markdown]
# At $\lambda_2$ the paper states $L(\lambda_2)|\Omega_2\rangle = v(\lambda_2)^{-1}|\Omega_2\rangle$ with
# $v(\lambda_2)=\frac{A+D+\gamma}{2}$.  But the eigenvalue that goes with $x$ of eq. (`xy`) is
# $\frac{A+D+\gamma}{2}$ itself — which is $v(\lambda_2)^{-1}$ only if $v(\lambda_2)=\frac{A+D-\gamma}{2}$,
# the convention Appendix B (eq. `spec`) actually uses.  On the $N=2$ lattice, numerically:

# %%
mp.mp.dps = 30
p, q, l0, mu = admissible_states(2, 1, 1)[0]
pt, qt, info = literal_step(p, q, l0, mu)
l2v = l0 - mu
M2 = lax_matrix(l2v, p, q)
tr2, g2 = info["tr2"], info["gamma2"]
Omega2 = mp.matrix([info["x_formula"], l2v - (l0 + mu) - info["x_formula"] * info["y"][0]])
eigenvalue = (M2 * Omega2)[0] / Omega2[0]
display(f"L(l2) Omega2 / Omega2      = {mp.nstr(eigenvalue, 20)}")
display(f"(tr2 + gamma2)/2           = {mp.nstr((tr2 + g2) / 2, 20)}")
display(f"printed v(l2)^-1 = 2/(tr2 + gamma2) = {mp.nstr(2 / (tr2 + g2), 20)}")
show("xy.n2", "v1v2.n2", "l1l2.n2", "l1l2.n3")

# %% [markdown]
# **Corrected statement (eq. `v1v2`):** $L(\lambda_2)|\Omega_2\rangle=\frac{A(\lambda_2)+D(\lambda_2)+\gamma(\lambda_2)}{2}|\Omega_2\rangle$,
# i.e. $v(\lambda_2)=\frac{A(\lambda_2)+D(\lambda_2)-\gamma(\lambda_2)}{2}$ (same form as $v(\lambda_1)$).
# The statements are proved for generic unimodular matrices, hence for every $N$; the
# $N=3$ claims also screen them on the $N=3$ Lax matrix:

# %%
show("xy.n3", "v1v2.n3")

# %% [markdown]
# ## The explicit map and eq. (`new`)
#
# With $x, y$ from eq. (`xy`), $\tilde L = \mathcal D L\mathcal D^{-1}$ is again a Toda Lax matrix;
# in particular $\operatorname{tr}\tilde L(\lambda) = \operatorname{tr}L(\lambda)$ for every $\lambda$:

# %%
for lv in (mp.mpf("0.3"), mp.mpf(-1), mp.mpf(7)):
    t, tt = [(M[0, 0] + M[1, 1]) for M in (lax_matrix(lv, p, q), lax_matrix(lv, pt, qt))]
    display(f"lambda = {mp.nstr(lv, 3):>4}: tr L = {mp.nstr(t, 20)}, tr L~ = {mp.nstr(tt, 20)}")
show("new.n2", "new.n3")

# %% [markdown]
# ## Connected to the identity, eq. (`lam0mu`)
#
# With $\lambda_{1,2}=\lambda_0\pm\mu$ the map tends to the identity as $\mu\to0$
# (for $b=+1$ and for $b=-1$; mixed signs do not), and $b=-1$ at $\mu$ is the inverse of $b=+1$:

# %%
for m_ in ("1e-3", "1e-6", "1e-9"):
    pt_, qt_, _ = literal_step(p, q, l0, mp.mpf(m_))
    display(f"mu = {m_}: max |step - id| = {mp.nstr(max(abs(a - b) for a, b in zip(pt_ + qt_, p + q)), 5)}")
back_p, back_q, _ = literal_step(pt, qt, l0, mu, branch=-1)
display(f"T_-(T_+(p, q)) - (p, q): {mp.nstr(max(abs(a - b) for a, b in zip(back_p + back_q, p + q)), 5)}")
show("lam0mu.n2", "lam0mu.n3", "xy.branches.n2", "xy.branches.n3")

# %% [markdown]
# ## Outcomes

# %%
wt.expect({"D.n2": "verified", "D.n3": "verified", "xy.n2": "verified", "v1v2.n2": "erratum",
           "xy.n3": "verified", "v1v2.n3": "erratum",
           "l1l2.n2": "verified", "l1l2.n3": "verified", "new.n2": "verified", "new.n3": "verified",
           "lam0mu.n2": "verified", "lam0mu.n3": "verified",
           "xy.branches.n2": "verified", "xy.branches.n3": "verified"})
print("03_composed_map: all claim outcomes as expected")
