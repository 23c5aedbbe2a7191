"""A user's claims about their note on the open Toda lattice: ~20 cheap claims of the usual kinds.

Polynomial identities decided by ``decide``, a matrix (Lax pair) identity, a family over N, a sampled
claim over sign cells with a ``CellTable`` (an erratum with a branch), numeric constants -- and three
claims that give mutation testing nothing to work with (a zero right-hand side, a matrix of bare
symbols, no parts at all).
"""
from __future__ import annotations

import mpmath as mp
import sympy as sp
from note_model import R_OF_T, c, coordinates, equations_of_motion, hamiltonian, t, time_derivative

from symbt import CellTable, Outcome, Parts, Verdict, claim, decide, from_decision, judge, scene

scene("note", "the open Toda lattice, as in my note")

x, y = sp.symbols("x y", real=True)
a1, a2, b1, b2 = sp.symbols("a1 a2 b1 b2", real=True)
m11, m12, m21, m22 = sp.symbols("m11 m12 m21 m22")
p1, p2, q1, q2 = sp.symbols("p1 p2 q1 q2", real=True)
E = sp.exp(q1 - q2)


def _two(lhs: sp.Expr, rhs: sp.Expr) -> Parts:
    return Parts(printed={"lhs": lhs, "rhs": rhs})


def _decide_sides(parts: Parts) -> Outcome:
    return from_decision(decide(parts.printed["lhs"], parts.printed["rhs"]))


# --------------------------------------------------------------------------- polynomial identities

@claim("note.binomial4", equation="binom", scene="note", statement="(x+y)^4 expanded",
       parts=lambda: _two((x + y) ** 4, x ** 4 + 4 * x ** 3 * y + 6 * x ** 2 * y ** 2 + 4 * x * y ** 3 + y ** 4))
def binomial4(parts: Parts) -> Outcome:
    return _decide_sides(parts)


@claim("note.cubes", equation="cubes", scene="note", statement="x^3 + y^3 = (x+y)(x^2 - xy + y^2)",
       parts=lambda: _two(x ** 3 + y ** 3, (x + y) * (x ** 2 - x * y + y ** 2)))
def cubes(parts: Parts) -> Outcome:
    return _decide_sides(parts)


@claim("note.lagrange", equation="lagrange", scene="note",
       statement="(a1^2 + a2^2)(b1^2 + b2^2) = (a1 b1 + a2 b2)^2 + (a1 b2 - a2 b1)^2",
       parts=lambda: _two((a1 ** 2 + a2 ** 2) * (b1 ** 2 + b2 ** 2),
                          (a1 * b1 + a2 * b2) ** 2 + (a1 * b2 - a2 * b1) ** 2))
def lagrange(parts: Parts) -> Outcome:
    return _decide_sides(parts)


@claim("note.geometric", equation="geom", scene="note", statement="(1 - x^5)/(1 - x) = 1 + x + x^2 + x^3 + x^4",
       parts=lambda: _two((1 - x ** 5) / (1 - x), 1 + x + x ** 2 + x ** 3 + x ** 4))
def geometric(parts: Parts) -> Outcome:
    return _decide_sides(parts)


@claim("note.squares", equation="squares", scene="note", statement="sum_{k=1}^n k^2 = n(n+1)(2n+1)/6",
       parts=lambda: Parts(printed={"rhs": sp.Symbol("n") * (sp.Symbol("n") + 1) * (2 * sp.Symbol("n") + 1) / 6}))
def squares(parts: Parts) -> Outcome:
    n, k = sp.symbols("n k", integer=True, positive=True)
    rhs = parts.printed["rhs"].subs(sp.Symbol("n"), n)
    return from_decision(decide(sp.summation(k ** 2, (k, 1, n)), rhs))


@claim("note.chebyshev", equation="cheb", scene="note", statement="cos 3x = 4 cos^3 x - 3 cos x",
       parts=lambda: Parts(printed={"rhs": 4 * sp.cos(x) ** 3 - 3 * sp.cos(x)}))
def chebyshev(parts: Parts) -> Outcome:
    return from_decision(decide(sp.cos(3 * x), parts.printed["rhs"], exact=False))


@claim("note.cube.erratum", equation="cube", scene="note", statement="(x+y)^3 = x^3 + 3x^2y + 3xy^2 + y^3 + xy",
       parts=lambda: Parts(printed={"rhs": x ** 3 + 3 * x ** 2 * y + 3 * x * y ** 2 + y ** 3 + x * y},
                           corrected={"rhs": x ** 3 + 3 * x ** 2 * y + 3 * x * y ** 2 + y ** 3}))
def cube_erratum(parts: Parts) -> Outcome:
    lhs = (x + y) ** 3
    return judge(decide(lhs, parts.printed["rhs"]), printed=str(parts.printed["rhs"]),
                 corrected=str(parts.corrected.get("rhs")),
                 corrected_check=lambda: decide(lhs, parts.corrected["rhs"]))


# --------------------------------------------------------------------------- the model: H, flow, Lax pair

def _flow2() -> dict:
    return equations_of_motion(2)


@claim("note.eom", equation="eom", scene="note", statement="qdot_j = p_j, pdot_1 = -e^{q1-q2}, pdot_2 = e^{q1-q2}",
       parts=lambda: Parts(printed={"pdot1": -E, "pdot2": E, "qdot1": p1, "qdot2": p2}))
def eom(parts: Parts) -> Outcome:
    H = hamiltonian(2)
    P = parts.printed
    return from_decision(decide(sp.Matrix([P["qdot1"], P["qdot2"], P["pdot1"], P["pdot2"]]),
                                sp.Matrix([sp.diff(H, p1), sp.diff(H, p2), -sp.diff(H, q1), -sp.diff(H, q2)])))


@claim("note.energy", equation="energy", scene="note", statement="dH/dt = 0 along the printed flow",
       parts=lambda: Parts(printed={"H": p1 ** 2 / 2 + p2 ** 2 / 2 + E}))
def energy(parts: Parts) -> Outcome:
    return from_decision(decide(time_derivative(parts.printed["H"], _flow2()), 0))


@claim("note.lax", equation="lax", scene="note",
       statement="dL/dt = [B, L], L = [[p1, 1], [E, p2]], B = [[0, 0], [E, 0]]",
       parts=lambda: Parts(printed={"L": sp.Matrix([[p1, 1], [E, p2]]), "B": sp.Matrix([[0, 0], [E, 0]])}))
def lax(parts: Parts) -> Outcome:
    L, B = parts.printed["L"], parts.printed["B"]
    flow = _flow2()
    Ldot = L.applyfunc(lambda e: time_derivative(e, flow))
    return from_decision(decide(Ldot, B * L - L * B))


@claim("note.trace", equation="trL2", scene="note", statement="tr L^2 = 2H",
       parts=lambda: Parts(printed={"rhs": p1 ** 2 + p2 ** 2 + 2 * E}))
def trace(parts: Parts) -> Outcome:
    L = sp.Matrix([[p1, 1], [E, p2]])
    return from_decision(decide((L * L).trace(), parts.printed["rhs"]))


@claim("note.det", equation="detL", scene="note", statement="det L = p1 p2 - e^{q1-q2}",
       parts=lambda: Parts(printed={"rhs": p1 * p2 - E}))
def det(parts: Parts) -> Outcome:
    return from_decision(decide(sp.Matrix([[p1, 1], [E, p2]]).det(), parts.printed["rhs"]))


@claim("note.eigen", equation="eig", scene="note",
       statement="lambda_pm = (p1+p2)/2 +- s, s^2 = (p1-p2)^2/4 + w, are the roots of det(lambda - L)",
       parts=lambda: Parts(printed={"plus": (p1 + p2) / 2 + sp.Symbol("s"), "minus": (p1 + p2) / 2 - sp.Symbol("s")}))
def eigen(parts: Parts) -> Outcome:
    s, lam = sp.Symbol("s"), sp.Symbol("lambda")
    w = sp.Symbol("w", positive=True)            # w = e^{q1-q2}: the relation is polynomial in it
    char = (lam - p1) * (lam - p2) - w
    rel = {s: s ** 2 - (p1 - p2) ** 2 / 4 - w}
    roots = sp.Matrix([char.subs(lam, parts.printed["plus"]), char.subs(lam, parts.printed["minus"])])
    return from_decision(decide(roots, sp.zeros(2, 1), relations=rel))


@claim("note.momentum", equation="mom", scene="note", sizes=(2, 3, 4), statement="P = sum p_j is conserved (N = {N})",
       parts=lambda N: Parts(printed={"P": sum(coordinates(N)[0])}))
def momentum(N: int, parts: Parts) -> Outcome:
    return from_decision(decide(time_derivative(parts.printed["P"], equations_of_motion(N)), 0))


# --------------------------------------------------------------------------- sampled, in cells

RDOT = sp.diff(R_OF_T, t)


@claim("note.rdot", equation="rdot", scene="note",
       statement="r'(t) = -2c sqrt(1 - 2 e^r / c^2) on the solution e^r = c^2/2 sech^2(ct)",
       parts=lambda: Parts(printed={"rdot": -2 * c * sp.sqrt(1 - 2 * sp.exp(R_OF_T) / c ** 2)},
                           corrected={"rdot": -2 * c * sp.sign(t) * sp.sqrt(1 - 2 * sp.exp(R_OF_T) / c ** 2)}))
def rdot(parts: Parts) -> Outcome:
    exact = sp.lambdify((t, c), RDOT, "mpmath")
    printed = sp.lambdify((t, c), parts.printed["rdot"], "mpmath")
    corrected = sp.lambdify((t, c), parts.corrected["rdot"], "mpmath")
    table = CellTable(tol=1e-20)
    rng = mp.mpf(0)
    with mp.workdps(30):
        for sign_t in (1, -1):
            for regime, (lo, hi) in {"slow": (0.2, 1), "fast": (1, 3)}.items():
                for i in range(4):
                    rng = (rng * 7 + mp.mpf(i + 1) / 3) % 1
                    tt, cc = sign_t * (0.1 + 2 * rng), lo + (hi - lo) * rng
                    ref = exact(tt, cc)
                    table.add({"sign_t": sign_t, "regime": regime},
                              printed=abs(printed(tt, cc) - ref) / abs(ref),
                              corrected=abs(corrected(tt, cc) - ref) / abs(ref), point={"t": str(tt), "c": str(cc)})
    ok_p, ok_c = table.printed_holds_everywhere(), table.corrected_holds_everywhere()
    status = "verified" if ok_p else ("erratum" if ok_c else "failed")
    res, where = table.worst("printed")
    return Outcome(status, "mpmath 30 digits in 4 cells", residual=res, evidence="sampled", cells=table.cells(),
                   scope=table.scope(), counterexample=None if ok_p else where)


# --------------------------------------------------------------------------- numeric constants

@claim("note.K", equation="Kval", scene="note", statement="K(k = 1/sqrt 2) = 1.8540746773013719",
       parts=lambda: Parts(printed={"value": 1.8540746773013719}))
def complete_K(parts: Parts) -> Outcome:
    ref = mp.ellipk(mp.mpf(1) / 2)          # mpmath's parameter m = k^2
    r = abs(parts.printed["value"] - ref) / ref
    return from_decision(Verdict.sampled(r, tol=1e-15, method="mpmath ellipk at 30 digits"))


@claim("note.zeta2", equation="basel", scene="note", statement="sum 1/n^2 = pi^2/6",
       parts=lambda: Parts(printed={"rhs": sp.pi ** 2 / 6}))
def zeta2(parts: Parts) -> Outcome:
    with mp.workdps(30):
        r = abs(mp.zeta(2) - sp.N(parts.printed["rhs"], 30)) / mp.zeta(2)
    return from_decision(Verdict.sampled(r, tol=1e-25, method="mpmath zeta at 30 digits"))


# --------------------------------------------------------------------------- nothing to mutate

@claim("note.isospectral", equation="iso", scene="note", statement="d/dt tr L^2 = 0",
       parts=lambda: Parts(printed={"rhs": sp.S(0)}))
def isospectral(parts: Parts) -> Outcome:
    L = sp.Matrix([[p1, 1], [E, p2]])
    return from_decision(decide(time_derivative((L * L).trace(), _flow2()), parts.printed["rhs"]))


@claim("note.cayley", equation="cayley", scene="note", statement="M^2 - tr(M) M + det(M) I = 0 for 2x2 M",
       parts=lambda: Parts(printed={"M": sp.Matrix([[m11, m12], [m21, m22]])}))
def cayley(parts: Parts) -> Outcome:
    M = parts.printed["M"]
    return from_decision(decide(M * M - M.trace() * M + M.det() * sp.eye(2), sp.zeros(2, 2)))


@claim("note.hessian", equation="hess", scene="note", statement="the Hessian of H in p is the identity")
def hessian() -> Outcome:
    H = hamiltonian(2)
    return from_decision(decide(sp.hessian(H, (p1, p2)), sp.eye(2)))
