"""Ordinary pytest tests of the note's formulas with the ``symbt_identity`` fixture (the plugin provides it).

They complement the claims (``drag_claims.py``, run by ``pytest --symbt``): each test derives something
a second way, so that a slip in one route shows up against the other.
"""
from __future__ import annotations

import mpmath as mp
import sympy as sp

from drag_model import RATE, V_T, dimensionless, drag_rhs, g, k, t, v0, w

x, u = sp.symbols("x u", real=True)


def test_speed_of_distance_solves_its_own_ode(symbt_identity):
    # v dv/dx = f(v), i.e. (1/2) dV/dx = f(sqrt(V)) for V = v^2, with V(0) = 0; in u = k x it is a
    # polynomial identity in e^{-u}, so it is proved, not sampled
    V = (g / k) * (1 - sp.exp(-2 * k * x))
    in_u = {x: u / k}
    symbt_identity((sp.diff(V, x) / 2).subs(in_u), drag_rhs(sp.sqrt(V)).subs(in_u), require="proved")
    symbt_identity(V.subs(x, 0), 0, require="proved")


def test_tanh_addition_gives_the_rational_form(symbt_identity):
    # for |v0| < v_T the solution is v_T (v0 + v_T T)/(v_T + v0 T), T = tanh(sqrt(g k) t): a rational form
    # valid on both sides of v_T, which the piecewise tanh/coth correction of eq. v0 agrees with
    T = sp.tanh(RATE * t)
    rational = V_T * (v0 + V_T * T) / (V_T + v0 * T)
    residual = sp.diff(rational, t) - drag_rhs(rational)
    symbt_identity(dimensionless(residual), 0, require="proved")
    symbt_identity(rational.subs(t, 0), v0)


def test_printed_v0_form_starts_at_the_wrong_velocity_above_v_T(symbt_identity):
    # the printed eq. v0 at t = 0 is v_T tanh(arcoth(v0/v_T)) = v_T^2/v0 when v0 > v_T
    a = sp.Symbol("a", positive=True)          # v0 = (1 + a) v_T > v_T
    start = V_T * sp.tanh(sp.log(sp.Abs((V_T + v0) / (V_T - v0))) / 2)
    symbt_identity(dimensionless(start.subs(v0, (1 + a) * V_T)), w / (1 + a))


def test_time_to_99_percent_by_integrating_the_model():
    # an independent route to t_99: integrate v' = g - k v^2 numerically (skydiver: v_T = 55 m/s) and
    # find where v = 0.99 v_T; the corrected formula agrees, the printed one is twice too long
    gv, vT = mp.mpf("9.81"), mp.mpf(55)
    kv = gv / vT**2
    with mp.workdps(20):
        v = mp.odefun(lambda _t, y: gv - kv * y**2, 0, 0)
        t99 = mp.findroot(lambda s: v(s) - mp.mpf("0.99") * vT, 14)
    corrected, printed = mp.log(199) / (2 * mp.sqrt(gv * kv)), mp.log(199) / mp.sqrt(gv * kv)
    assert abs(t99 - corrected) < 1e-10
    assert abs(t99 - printed) > 10
