"""The literal route's fast Lax product is the mpmath matrix product, bit for bit (real and complex states)."""
import random

import mpmath as mp
import pytest

from symbt.reference.literal import lax_matrix, literal_step


def _product(lam, p, q):
    M = mp.eye(2)
    for pj, qj in zip(p, q):
        M = mp.matrix([[lam + pj, -mp.exp(qj)], [mp.exp(-qj), 0]]) * M
    return M


def _step_by_matrices(p, q, lam0, mu, b):
    """literal_step's first stage written with mp.matrix products (the traces and the slope y)."""
    L1, L2 = _product(lam0 + mu, p, q), _product(lam0 - mu, p, q)
    tr1 = L1[0, 0] + L1[1, 1]
    g1 = b * mp.sqrt(tr1 ** 2 - 4)
    return tr1, L2[0, 0] + L2[1, 1], (L1[0, 0] - L1[1, 1] + g1) / (2 * L1[0, 1])


@pytest.mark.parametrize("dps", [30, 60])
def test_lax_product_bit_identical(dps):
    rng = random.Random(dps)
    with mp.workdps(dps):
        for k in range(60):
            N = 2 + k % 4
            p = [mp.mpf(rng.uniform(-5, 5)) for _ in range(N)]
            q = [mp.mpf(rng.uniform(-2, 2)) for _ in range(N)]
            if k % 3 == 0:
                q[0] = mp.mpc(q[0], rng.uniform(-1, 1))   # complex states take mp.fdot's own path
            lam, lam0, mu = (mp.mpf(rng.uniform(-10, 10)) for _ in range(3))
            assert lax_matrix(lam, p, q) == _product(lam, p, q)
            _, _, info = literal_step(p, q, lam0, mu, 1)
            tr1, tr2, y = _step_by_matrices(p, q, lam0, mu, 1)
            assert (info["tr1"], info["tr2"], info["y"][0]) == (tr1, tr2, y)


def _as_tuple(res):
    pt, qt, info = res
    return list(pt), list(qt), {k: (list(v) if isinstance(v, list) else v) for k, v in info.items()}


@pytest.mark.parametrize("dps", [30, 60])
def test_real_route_bit_identical_to_generic(dps):
    # literal_step on real mpf takes the libmp-tuple route; it must give the generic route's bits exactly,
    # on both branches, mixed gamma signs, either sign of tr, and states whose image is complex (fallback)
    from symbt.reference.literal import _literal_step_generic

    rng = random.Random(100 + dps)
    real = fallback = 0
    with mp.workdps(dps):
        for k in range(200):
            N = 2 + k % 4
            p = [mp.mpf(rng.uniform(-6, 6)) for _ in range(N)]
            q = [mp.mpf(rng.uniform(-2, 2)) for _ in range(N)]
            lam0, mu = mp.mpf(rng.uniform(-12, 12)), mp.mpf(rng.uniform(-4, 4))
            signs = [(1, 1), (-1, -1), (1, -1), (-1, 1)][k % 4]
            got = literal_step(p, q, lam0, mu, gamma_signs=signs)
            want = _literal_step_generic(p, q, lam0, mu, *signs)
            assert _as_tuple(got) == _as_tuple(want)
            if all(type(v) is mp.mpf for v in got[1]):
                real += 1
            else:
                fallback += 1
    assert real > 20 and fallback > 20   # both routes exercised
