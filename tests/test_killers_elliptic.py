"""The claims of ``symbt/claims/library_elliptic_file.py`` observe whole functions of ``symbt.reference.elliptic``,
``taylor`` and ``inverse``: each planted single-point bug of ``symbt mutate --source``'s kind (the mutant's own text,
with :func:`planting.planted`) makes the claim fail; unpatched, every claim verifies (issue 21, item 4;
docs/mutation.md, "Fresh samples of symbt/reference/elliptic.py, taylor.py, inverse.py").

The mutants planted are those of the fresh samples (seeds 51 and 52) and their neighbours in the same functions:
the claims were written for the functions, not for the lines.
"""
from __future__ import annotations

import pytest
from planting import planted

from symbt.claims import library_elliptic_file as L
from symbt.claims import library_elliptic_flows as LF
from symbt.reference import elliptic as E
from symbt.reference import inverse, taylor

CLAIMS = [L.abel_cell, L.F_forms, L.shift_fields, LF.flow_angles, LF.flow_field, LF.inverse_fields, LF.flow_steps,
          L.addition_third, LF.newton_rule]


def status(check) -> str:
    return check.run().status


@pytest.mark.parametrize("check", CLAIMS, ids=lambda c: c.id)
def test_unpatched_verified(check):
    assert status(check) == "verified"


# ------------------------------------------------------------------------------------------ library.abel_cell

@pytest.mark.parametrize("old, new", [
    ("u0 = mp.sign(s) * v", "u0 = -mp.sign(s) * v"),                                             # elliptic:232
    ("W = mp.sqrt((1 - s * s) * (1 - m * s * s))", "W = mp.sqrt((1 - s * s) * (0 - m * s * s))"),  # elliptic:224
    ("_F_m(1 / (mp.sqrt(m) * a), m), -W", "_F_m(1 / (mp.sqrt(m) * a), m), W"),                   # elliptic:231
    ("v, cd = K + 1j * _F_m(t, 1 - m), -W", "v, cd = K - 1j * _F_m(t, 1 - m), -W"),
    ("elif m * a * a < 1:", "elif m * a * a > 1:"),
    ("return u0 if abs(cd - w) <= abs(cd + w) else 2 * K - u0",
     "return u0 if abs(cd - w) <= abs(cd + w) else 2 * K + u0"),
    ("        if a <= 1:\n", "        if a < 1:\n"),                                              # elliptic:225 (26)
])
def test_abel_killed(monkeypatch, old, new):
    monkeypatch.setattr(E, "abel", planted(E.abel, old, new))
    assert status(L.abel_cell) == "failed"


@pytest.mark.parametrize("old, new", [
    ("d = d - 2j * Kp * mp.nint(mp.im(d) / (2 * Kp))", "d = d - 2j * Kp * mp.nint(mp.im(d) / (Kp))"),
    ("return abs(d - 4 * K * mp.nint(mp.re(d) / (4 * K)))", "return abs(d + 4 * K * mp.nint(mp.re(d) / (4 * K)))"),
])
def test_lattice_residual_killed(monkeypatch, old, new):
    monkeypatch.setattr(E, "lattice_residual", planted(E.lattice_residual, old, new))
    assert status(L.abel_cell) == "failed"


# ------------------------------------------------------------------------------------------ library.F_forms

@pytest.mark.parametrize("func, old, new", [
    ("_F_m", "return -_F_memo(-z, m, mp.mp.prec)", "return -_F_memo(z, m, mp.mp.prec)"),           # elliptic:146
    ("F", "if abs(z) > 1:", "if abs(z) >= 1:"),
    ("F_real", "return -_F_m(1 / (k * s), k ** 2)", "return _F_m(1 / (k * s), k ** 2)"),
    ("F_real", "if abs(k * s) >= 1:", "if abs(k * s) <= 1:"),
    ("F_real", "if abs(k * s) >= 1:", "if abs(k * s) > 1:"),                                        # seed 8, :171
    ("F_real", "if abs(s) <= 1:", "if abs(s) >= 1:"),
    ("theta2_printed", "mm = (I2 - 2) / (I2 + 2) if m is None else m",
     "mm = (I2 - 2) / (I2 + 2) if not (m is None) else m"),
    ("angles", "return q[0] + q[1], u / mp.sqrt(I2 + 2)", "return q[0] - q[1], u / mp.sqrt(I2 + 2)"),
    ("F_principal", "return mp.ellipf(mp.asin(z), k ** 2)", "return mp.ellipf(mp.asin(z), k ** 1)"),
])
def test_F_forms_killed(monkeypatch, func, old, new):
    monkeypatch.setattr(E, func, planted(getattr(E, func), old, new))
    assert status(L.F_forms) == "failed"


# ------------------------------------------------------------------------------------------ library.shift_fields

@pytest.mark.parametrize("func, old, new", [
    ("shift", "v1, v2 = (T1 - g1) / 2, (T2 + g2) / 2", "v1, v2 = (T1 + g1) / 2, (T2 + g2) / 2"),
    ("shift", "du = abel(s1, w1, m) - abel(s2, w2, m)", "du = abel(s1, w1, m) + abel(s2, w2, m)"),
    ("shift", "dtheta2=du / mp.sqrt(I2 + 2)", "dtheta2=du / mp.sqrt(I2 - 2)"),
    ("shift", "s1, w1, T1, g1 = spectral_point(lam0 + mu, I1, I2, branch)",
     "s1, w1, T1, g1 = spectral_point(lam0 - mu, I1, I2, branch)"),
    ("spectral_point", "T = (lam + I1) ** 2 - I2", "T = (lam - I1) ** 2 - I2"),
    ("spectral_point", "return (lam + I1) / mp.sqrt(I2 - 2), gam / mp.sqrt(I2 ** 2 - 4), T, gam",
     "return (lam + I1) / mp.sqrt(I2 - 2), gam / mp.sqrt(I2 ** 2 + 4), T, gam"),
    ("curve_point", "return P, (r - 1 / r) / mp.sqrt(I2 ** 2 - 4)", "return P, (r + 1 / r) / mp.sqrt(I2 ** 2 - 4)"),
])
def test_shift_fields_killed(monkeypatch, func, old, new):
    monkeypatch.setattr(E, func, planted(getattr(E, func), old, new))
    assert status(L.shift_fields) == "failed"


# ------------------------------------------------------------------------------------------ library.flow_angles

@pytest.mark.parametrize("func, old, new", [
    ("_poly_G", "G[e] = G.get(e, 0) + c[k] * v", "G[e] = G.get(e, 0) + c[k - 1] * v"),                  # taylor:42
    ("hamiltonian_flow", "with mp.workdps(dps + 15):", "with mp.workdps(dps - 15):"),                   # taylor:150
    ("hamiltonian_flow", "sign = 1 if t >= 0 else -1", "sign = 1 if t <= 0 else -1"),
    ("hamiltonian_flow", "while done < T:", "while done > T:"),                                          # taylor:158
    ("hamiltonian_flow", "h = min(h, T - done)", "h = max(h, T - done)"),
])
def test_flow_angles_killed(monkeypatch, func, old, new):
    monkeypatch.setattr(taylor, func, planted(getattr(taylor, func), old, new))
    monkeypatch.setattr(LF, "hamiltonian_flow", taylor.hamiltonian_flow)
    assert status(LF.flow_angles) == "failed"


@pytest.mark.parametrize("old, new", [
    ("J[key].append(mp.fsum(pj[m] * leaf[n - m] for m in range(n + 1)))",
     "J[key].append(mp.fsum(pj[m] * leaf[n - m] for m in range(n + 0)))"),
    ("X[i].append(s / (n + 1))", "X[i].append(s / (n - 1))"),
])
def test_flow_angles_jets_killed(monkeypatch, old, new):
    monkeypatch.setattr(taylor._TaylorSystem, "jets", planted(taylor._TaylorSystem.jets, old, new))
    assert status(LF.flow_angles) == "failed"


# ------------------------------------------------------------------------------------------ library.flow_field

@pytest.mark.parametrize("func, old, new", [
    ("hamilton_equations", "ad = [_mul_var(_sub(qd[(j + 1) % N], qd[j]), N + j) for j in range(N)]",
     "ad = [_mul_var(qd[(j + 1) % N], N + j) for j in range(N)]"),        # taylor:83 (qdot_j dropped from a_j's rate)
    ("hamilton_equations", "_mul_var(_d(G, N + (j - 1) % N), N + (j - 1) % N)",
     "_mul_var(_d(G, N + (j + 1) % N), N + (j - 1) % N)"),
    ("_poly_G", "k, e = key[0], key[1:]", "k, e = key[1], key[1:]"),
])
def test_flow_field_killed(monkeypatch, func, old, new):
    monkeypatch.setattr(taylor, func, planted(getattr(taylor, func), old, new))
    monkeypatch.setattr(LF, "hamilton_equations", taylor.hamilton_equations)
    assert status(LF.flow_field) == "failed"


# ------------------------------------------------------------------------------------------ library.inverse_fields

@pytest.mark.parametrize("func, old, new", [
    ("_newton", "return x, it + 1", "return x, it - 1"),                                               # inverse:68
    ("_newton", "return x, it + 1", "return x, it + 0"),                                               # inverse:68
    ("solve_parameters", "m = -c_target[0] * mp.sqrt(abs(t0 ** 2 - 4)) / 2",
     "m = -c_target[0] * mp.sqrt(abs(t0 ** 2 - 4))"),                                                 # inverse:160
    ("solve_parameters", "l0 = c_target[1] / c_target[0]", "l0 = c_target[0] / c_target[0]"),
    ("solve_parameters", "branch=1 if m > 0 else -1", "branch=1 if m < 0 else -1"),                    # inverse:182
    ("solve_parameters", "res = max(abs(c[k] - c_target[k]) for k in range(N))",
     "res = min(abs(c[k] - c_target[k]) for k in range(N))"),
    ("solve_parameters", "res = max(abs(c[k] - c_target[k]) for k in range(N))",
     "res = max(abs(c[k] + c_target[k]) for k in range(N))"),
    ("solve_parameters", "res = max(abs(c[k] - c_target[k]) for k in range(N))",
     "res = max(c[k] - c_target[k] for k in range(N))"),                                               # inverse:187
    ("solve_parameters", "kappa = num / mp.fsum(b ** 2 for b in c_target[:N])",
     "kappa = num / mp.fsum(b ** 1 for b in c_target[:N])"),
    ("solve_parameters", "c = flow_coefficients_mp(p, q, l0, m, 1, check=False)",
     "c = flow_coefficients_mp(p, q, l0, m, 0, check=False)"),
])
def test_inverse_fields_killed(monkeypatch, func, old, new):
    monkeypatch.setattr(inverse, func, planted(getattr(inverse, func), old, new))
    assert status(LF.inverse_fields) == "failed"


# ------------------------------------------------------------------------------------------ library.flow_steps

@pytest.mark.parametrize("func, old, new", [
    ("hamiltonian_flow", "scale = max(1, max(abs(v) for v in x))", "scale = min(1, max(abs(v) for v in x))"),
    ("hamiltonian_flow", "if steps >= max_steps:", "if steps > max_steps:"),
    ("hamiltonian_flow", 'h = min(hs) * mp.mpf("0.7") if hs else T - done',
     'h = min(hs) * mp.mpf("0.7") if not hs else T - done'),
    ("hamiltonian_flow", "out.steps, out.order = steps, K", "out.steps, out.order = steps + 1, K"),
    ("_poly_G", "if k < len(c) and c[k]:", "if k <= len(c) and c[k]:"),
    ("hamilton_equations", "sign: int = 1) -> list[Polynomial]:", "sign: int = 0) -> list[Polynomial]:"),  # seed 9
])
def test_flow_steps_killed(monkeypatch, func, old, new):
    monkeypatch.setattr(taylor, func, planted(getattr(taylor, func), old, new))
    monkeypatch.setattr(LF, "hamiltonian_flow", taylor.hamiltonian_flow)
    monkeypatch.setattr(LF, "hamilton_equations", taylor.hamilton_equations)
    assert status(LF.flow_steps) == "failed"


# ------------------------------------------------------------------------------------------ library.addition_third

@pytest.mark.parametrize("old, new", [
    ("abs(Et[0] * Et[1] - E1E2) / max(1, abs(E1E2)))", "abs(Et[0] * Et[1] - E1E2) / min(1, abs(E1E2)))"),
    ("abs(Et[0] * Et[1] - E1E2) / max(1, abs(E1E2)))", "abs(Et[0] * Et[1] + E1E2) / max(1, abs(E1E2)))"),
    ('E1E2 = mp.exp(q[0] + q[1]) * sh["v1"] * sh["v2"]', 'E1E2 = mp.exp(q[0] - q[1]) * sh["v1"] * sh["v2"]'),
    ('u + (sh["du"] if du is None else du)', 'u + (sh["du"] if not (du is None) else du)'),
])
def test_addition_third_killed(monkeypatch, old, new):
    monkeypatch.setattr(E, "addition_residual", planted(E.addition_residual, old, new))
    assert status(L.addition_third) == "failed"


# ------------------------------------------------------------------------------------------ library.newton_rule

@pytest.mark.parametrize("func, old, new", [
    ("_newton", "return (x, maxit) if rf is not None and max(abs(v) for v in rf) < tol else None",
     "return (x, maxit) if rf is not None and max(v for v in rf) < tol else None"),                  # inverse:80
    ("_newton", "lambda rn, lam: _norm(rn) < r0 * (1 - lam / 4) + tol",
     "lambda rn, lam: _norm(rn) < r0 * (1 - lam) + tol"),                                              # inverse:75
    ("_newton", "return x, it + 1", "return x, it + 0"),                                               # inverse:68
    ("_solve", "return mp.qr_solve(Jm, -mp.matrix(r))[0]", "return mp.qr_solve(Jm, mp.matrix(r))[0]"),  # inverse:70
    ("_newton", "if rn is not None and _norm(rn) <= _norm(r):", "if rn is not None and _norm(rn) >= _norm(r):"),
    ("_gauss_newton", "if step is None:", "if not (step is None):"),
    ("_gauss_newton", "if max(abs(d) for d in dx) * lam < tol:", "if max(abs(d) for d in dx) * lam > tol:"),
    ("_line_search", "while lam > mp.mpf(2) ** -30:", "while lam >= mp.mpf(2) ** -30:"),               # seed 8, :36
    ("_newton", "rf is not None and max(abs(v) for v in rf) < tol else None",
     "rf is not None and min(abs(v) for v in rf) < tol else None"),                                   # seed 9, :80
    ("_line_search", "lam /= 2", "lam /= 3"),
])
def test_newton_rule_killed(monkeypatch, func, old, new):
    monkeypatch.setattr(inverse, func, planted(getattr(inverse, func), old, new))
    assert status(LF.newton_rule) == "failed"


# ------------------------------------------------------------------------------------------ equivalent mutants

def test_taylor_empty_rule_step_is_equivalent():
    # taylor:170 (seed 51): `h = min(hs) * 0.7 if hs else T - done` -> `... else T + done`.  The next statement is
    # `h = min(h, T - done)`, `done` starts at 0 and only grows by `done += h` with h > 0 (the loop runs while
    # done < T), so T + done >= T - done and the min is T - done either way -- checked on the syntax tree, and bit
    # for bit on the flow of G = H_2 (every Taylor coefficient 0: the branch taken) and of G = H_0 (not taken)
    import ast
    import inspect
    import textwrap

    import mpmath as mp

    tree = ast.parse(textwrap.dedent(inspect.getsource(taylor.hamiltonian_flow)))
    loop = next(n for n in ast.walk(tree) if isinstance(n, ast.While))
    texts = [ast.unparse(s) for s in loop.body]
    i = texts.index("h = min(hs) * mp.mpf('0.7') if hs else T - done")
    assert texts[i + 1] == "h = min(h, T - done)"
    assert ast.unparse(loop.test) == "done < T"
    writes = [ast.unparse(n) for n in ast.walk(tree) if isinstance(n, (ast.Assign, ast.AugAssign))
              and "done" in {t.id for t in ast.walk(n.targets[0] if isinstance(n, ast.Assign) else n.target)
                             if isinstance(t, ast.Name)}]
    assert writes == ["T, done, steps = (abs(t), mp.mpf(0), 0)", "done += h"]
    bad = planted(taylor.hamiltonian_flow, "if hs else T - done", "if hs else T + done")
    p, q = [mp.mpf("0.3"), mp.mpf("-0.2")], [mp.mpf("0.1"), mp.mpf("0.4")]
    with mp.workdps(20):
        for c, t in (([0, 0, 1], mp.mpf(2)), ([0, 0, 1], mp.mpf(-3)), ([1, 0, 0], mp.mpf("0.3"))):
            got, want = bad(p, q, c, t), taylor.hamiltonian_flow(p, q, c, t)
            assert (got, got.steps) == (want, want.steps)


def test_F_m_other_half_is_equivalent():
    # elliptic:145 (seed 9), `if not (isinstance(z, mp.mpf) and z < 0)`: F is evaluated at -z and negated for the
    # other half of the line (and for complex z).  z R_F(1 - z^2, 1 - m z^2, 1) is odd in z exactly: (-z)(-z) = z z
    # and (-z) R = -(z R) in binary floating point (real and complex), so every value is the same, bit for bit
    import mpmath as mp

    bad = planted(E._F_m, "    if isinstance(z, mp.mpf) and z < 0:", "    if not (isinstance(z, mp.mpf) and z < 0):")
    with mp.workdps(30):
        for m in (mp.mpf("0.36"), mp.mpf("0.9")):
            for z in ("-1", "-0.7", "-0.2", "0", "0.3", "0.9", "1"):
                assert bad(mp.mpf(z), m) == E._F_m(mp.mpf(z), m)
            for a, b in (("0.4", "0.3"), ("-2", "0.5"), ("0.1", "-1.7")):
                assert bad(mp.mpc(a, b), m) == E._F_m(mp.mpc(a, b), m)
