"""C99 templates of ``toda{N}.h`` and of the transfer-matrix form of ``toda{N}.c``.

Markers: ``@@N@@`` (the size), ``@@name@@`` / ``@@name[i]@@`` (a kernel of
:mod:`symbt.codegen.kernels`, or item ``i`` of a tuple kernel, printed in C) and
``@@name{A:M1[0],D:M1[3]}@@`` (the same with symbols bound to other C expressions);
``@@coef:name[i]@@`` is the coefficient-wise form of an update kernel on polynomials in
lambda (see :mod:`symbt.codegen.emit_c`).  Only ``<math.h>`` is used.

>>> "int toda@@N@@_bt_step(" in HEADER
True
"""
from __future__ import annotations

__all__ = ["HEADER", "COMMON", "LOOP"]

HEADER = '''/* C99 code for the N=@@N@@ periodic Toda lattice, emitted by symbt codegen (@@FORM@@ form).
 *
 * Conventions: {p_i, q_j} = delta_ij, xdot = {H, x}; L = l_N ... l_1, tr L = sum_k H_k lambda^k,
 * H_N = 1; lambda_1 = lam0 + mu, lambda_2 = lam0 - mu; branch b = +1 or -1 means
 * gamma_i = b sqrt(tr L(lambda_i)^2 - 4) (positive root).  Arrays have length @@N@@ (p, q, c, outputs).
 * No dependency beyond libm.  Outputs are written only when the return value is SYMBT_TODA_OK.
 *
 * Return values:
 *   SYMBT_TODA_OK                      0  success
 *   SYMBT_TODA_NO_REAL_MAP_TRACE       1  |tr L(lambda_i)| <= 2: a spectral parameter in a band
 *   SYMBT_TODA_NO_REAL_MAP_POSITIVITY  2  some Etilde_j = E_j - x_j <= 0 (lambda_1, lambda_2 in
 *                                         different spectral gaps): no real map
 *   SYMBT_TODA_RANGE                   3  a value leaves the float64 range (overflow, |q_{j+1} - q_j| > 700,
 *                                         or a degenerate eigenvector)
 *   SYMBT_TODA_INVALID_INPUT           4  NULL pointer, non-finite input, or branch not +1/-1
 *   SYMBT_TODA_ILL_CONDITIONED         5  bt_step: the condition estimate exceeds KAPPA_MAX = @@KAPPA@@,
 *                                         float64 cannot decide or compute the step here (symbt.numeric
 *                                         recomputes such states at higher precision)
 */
#ifndef SYMBT_TODA@@N@@_H
#define SYMBT_TODA@@N@@_H

#ifndef SYMBT_TODA_STATUS_CODES
#define SYMBT_TODA_STATUS_CODES
#define SYMBT_TODA_OK 0
#define SYMBT_TODA_NO_REAL_MAP_TRACE 1
#define SYMBT_TODA_NO_REAL_MAP_POSITIVITY 2
#define SYMBT_TODA_RANGE 3
#define SYMBT_TODA_INVALID_INPUT 4
#define SYMBT_TODA_ILL_CONDITIONED 5
#endif

#define TODA@@N@@_N @@N@@

#ifdef __cplusplus
extern "C" {
#endif

/* One Backlund step (p, q) -> (pt, qt) (paper eqs. D, xy, lam0mu, xyqqt, imptransf). */
int toda@@N@@_bt_step(const double *p, const double *q, double lam0, double mu, int branch,
                      double *pt, double *qt);

/* H[k] = H_k, k = 0 .. N-1: the coefficients of tr L(lambda) (eq. tra). */
int toda@@N@@_invariants(const double *p, const double *q, double *H);

/* tr L(lam) (eq. tra). */
int toda@@N@@_spectral_trace(double lam, const double *p, const double *q, double *tr);

/* Vector field of sum_k c_k H_k (eq. eqdisc): qdot = dG/dp, pdot = -dG/dq. */
int toda@@N@@_flow_field(const double *c, const double *p, const double *q, double *qdot, double *pdot);

#ifdef __cplusplus
}
#endif

#endif
'''

COMMON = '''#include <math.h>
#include "toda@@N@@.h"

#define NS @@N@@

static int toda@@N@@_finite(const double *x, int n)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(x[i]))
            return 0;
    return 1;
}
'''

LOOP = '''
/* ---- transfer-matrix form: loops over the sites; every formula is a kernel derived in symbt.codegen.kernels ---- */

/* r_j = E_{j+1}/E_j = exp(q_{j+1} - q_j) (cyclic); 0 if a difference is beyond the float64 range */
static int toda@@N@@_ratios(const double *q, double *rv)
{
    for (int j = 0; j < NS; j++) {
        const double dq = q[(j + 1) % NS] - q[j];
        if (!(fabs(dq) <= 700.0))
            return 0;
        rv[j] = exp(dq);
    }
    return 1;
}

/* M = m_N ... m_1, m_j = [[a_j, -1], [r_j, 0]] (kernels site, update) as M = 2^e (M[0], M[1]; M[2], M[3]);
   returns e.  The plain product first; if an entry leaves [2^-500, 2^500] (tr^2 - 4 or a later product
   could overflow), the product again with the largest entry scaled into [1/2, 1) after every site by a
   power of two (exact, as symbt.numeric) */
static int toda@@N@@_monodromy(const double *av, const double *rv, double *M)
{
    int e = 0;
    for (int pass = 0; pass < 2; pass++) {
        double A, B, C, D;
        {
            const double a = av[0], r = rv[0];
            A = @@site[0]@@;
            B = @@site[1]@@;
            C = @@site[2]@@;
            D = @@site[3]@@;
        }
        for (int j = 0; j < NS; j++) {
            if (j > 0) {
                const double a = av[j], r = rv[j];
                const double nA = @@update[0]@@, nB = @@update[1]@@, nC = @@update[2]@@, nD = @@update[3]@@;
                A = nA;
                B = nB;
                C = nC;
                D = nD;
            }
            if (pass == 1) {
                const double mx = fmax(fmax(fabs(A), fabs(B)), fmax(fabs(C), fabs(D)));
                if (isfinite(mx) && mx > 0.0) {
                    int k;
                    (void)frexp(mx, &k);
                    A = ldexp(A, -k);
                    B = ldexp(B, -k);
                    C = ldexp(C, -k);
                    D = ldexp(D, -k);
                    e += k;
                }
            }
        }
        M[0] = A;
        M[1] = B;
        M[2] = C;
        M[3] = D;
        const double mx = fmax(fmax(fabs(A), fabs(B)), fmax(fabs(C), fabs(D)));   /* fmax drops a NaN: */
        if (pass == 1 || (toda@@N@@_finite(M, 4) && mx <= 0x1p500 && mx >= 0x1p-500))
            break;
    }
    return e;
}

/* 4^-e (tr^2 - 4) of the rescaled M = 2^e (A, B; C, D), t = A + D, two = 2^(1 - e): near a closed gap (M close
   to +-I) (A - D)^2 + 4BC, whose terms round at the scale of A - D, B, C, else (t - two)(t + two)
   (kernels near_closed, disc_entries, disc_scaled; symbt.codegen.closed_gap) */
static double toda@@N@@_disc(double A, double B, double C, double D, double t, double two)
{
    return (@@near_closed@@) ? @@disc_entries@@ : @@disc_scaled@@;
}

/* scaled slopes of the eigenvector (1, -u) with eigenvalue (t - s g)/2 (M, t rescaled by 2^-e: the roots are
   homogeneous of degree 0, kernels disc_scaled, root_k, root_c), transport in the contracting direction
   (forward iff s t < 0); 0 if a slope or a transport denominator a_j + u_j is not finite (an infinite
   slope would read out as 2 mu/d = 0: a finite wrong state) */
static int toda@@N@@_slopes(const double *av, const double *rv, const double *M, double t, int e, double s, double *us)
{
    const double A = M[0], B = M[1], C = M[2], D = M[3], two = ldexp(2.0, -e);
    const double g = sqrt(toda@@N@@_disc(A, B, C, D, t, two));
    const double sd = (A - D >= 0.0) ? 1.0 : -1.0;
    us[0] = (sd * s > 0.0) ? @@root_k@@ : @@root_c@@;
    /* pass 0 is one turn that refines the root (the loop template's _turn_forward, _turn_backward: the root
       carries the rounding of |m_N| ... |m_1|, the turn contracts it by the ratio of the eigenvalues) */
    for (int pass = 0; pass < 2; pass++) {
        if (s * t < 0.0) {
            for (int j = 0; j < NS - 1; j++) {
                const double a = av[j], r = rv[j], u = us[j];
                us[j + 1] = @@forward@@;
            }
            if (pass == 0) {
                const double a = av[NS - 1], r = rv[NS - 1], u = us[NS - 1];
                us[0] = @@forward@@;
            }
        } else {
            double un = us[0];
            for (int j = NS - 1; j > 0; j--) {
                const double a = av[j], r = rv[j];
                un = @@backward@@;
                us[j] = un;
            }
            if (pass == 0) {
                const double a = av[0], r = rv[0];
                us[0] = @@backward@@;
            }
        }
    }
    for (int j = 0; j < NS; j++)
        if (!isfinite(av[j] + us[j]))
            return 0;
    return 1;
}

/* symbt.numeric's float64 condition estimate of the trace decision, T (|t| + 2) / |t^2 - 4| (T the trace of
   |m_N| ... |m_1|: the monodromy of |a_j| and -r_j, no cancellation, rescaled to M's power of two) */
static double toda@@N@@_trace_kappa(const double *av, const double *rv, int e, double t, double disc)
{
    double aa[NS], rr[NS], Ma[4];
    for (int j = 0; j < NS; j++) {
        aa[j] = fabs(av[j]);
        rr[j] = -rv[j];
    }
    const int ea = toda@@N@@_monodromy(aa, rr, Ma);
    return ldexp(Ma[0] + Ma[3], ea - e) * ((fabs(t) + ldexp(2.0, -e)) / fabs(disc));   /* T / ||t| - 2| */
}

/* max_j (|lam| + |p_j|) / |lam + p_j|: the cancellation in a_j */
static double toda@@N@@_cancellation(double lam, const double *p, const double *av)
{
    double k = 0.0;
    for (int j = 0; j < NS; j++) {
        const double c = (fabs(lam) + fabs(p[j])) / fabs(av[j]);
        if (!(c <= k))
            k = c;
    }
    return k;
}

#define TODA@@N@@_KAPPA_MAX @@KAPPA@@.0   /* symbt.numeric.core.limits.KAPPA_MAX */

int toda@@N@@_bt_step(const double *p, const double *q, double lam0, double mu, int branch,
                      double *pt, double *qt)
{
    double rv[NS], a1[NS], a2[NS], M1[4], M2[4], u[NS], w[NS], pn[NS], qn[NS];
    if (!p || !q || !pt || !qt || (branch != 1 && branch != -1))
        return SYMBT_TODA_INVALID_INPUT;
    if (!toda@@N@@_finite(p, NS) || !toda@@N@@_finite(q, NS) || !isfinite(lam0) || !isfinite(mu))
        return SYMBT_TODA_INVALID_INPUT;
    if (!toda@@N@@_ratios(q, rv) || !isfinite(lam0 + mu) || !isfinite(lam0 - mu))
        return SYMBT_TODA_RANGE;
    for (int j = 0; j < NS; j++) {
        a1[j] = lam0 + mu + p[j];
        a2[j] = lam0 - mu + p[j];
    }
    const int e1 = toda@@N@@_monodromy(a1, rv, M1), e2 = toda@@N@@_monodromy(a2, rv, M2);
    /* rescaled traces t_i = tr L(lambda_i) / 2^e_i */
    const double t1 = @@trace{A:M1[0],D:M1[3]}@@, t2 = @@trace{A:M2[0],D:M2[3]}@@;
    const double two1 = ldexp(2.0, -e1), two2 = ldexp(2.0, -e2);
    const double d1 = @@disc_scaled{t:t1,two:two1}@@, d2 = @@disc_scaled{t:t2,two:two2}@@;
    if (!(isfinite(d1) && isfinite(d2)))
        return SYMBT_TODA_RANGE;
    /* float64 decides only where the condition estimate is at most KAPPA_MAX (as symbt.numeric) */
    const double k1 = toda@@N@@_trace_kappa(a1, rv, e1, t1, d1), k2 = toda@@N@@_trace_kappa(a2, rv, e2, t2, d2);
    if (!(k1 <= TODA@@N@@_KAPPA_MAX) || !(k2 <= TODA@@N@@_KAPPA_MAX))   /* NaN too: a trace underflowed */
        return SYMBT_TODA_ILL_CONDITIONED;
    if (!(toda@@N@@_disc(M1[0], M1[1], M1[2], M1[3], t1, two1) > 0.0)
        || !(toda@@N@@_disc(M2[0], M2[1], M2[2], M2[3], t2, two2) > 0.0))
        return SYMBT_TODA_NO_REAL_MAP_TRACE;
    if ((t1 > 0.0) != (t2 > 0.0))           /* lambda_1, lambda_2 in different gaps: some Etilde_j <= 0 */
        return SYMBT_TODA_NO_REAL_MAP_POSITIVITY;
    if (!toda@@N@@_slopes(a1, rv, M1, t1, e1, (double)branch, u)
        || !toda@@N@@_slopes(a2, rv, M2, t2, e2, -(double)branch, w))
        return SYMBT_TODA_RANGE;
    for (int j = 0; j < NS; j++)
        if (!isfinite(w[j] - u[j]))
            return SYMBT_TODA_RANGE;
    const double c1 = k1 * toda@@N@@_cancellation(lam0 + mu, p, a1), c2 = k2 * toda@@N@@_cancellation(lam0 - mu, p, a2);
    const double kt = c1 > c2 ? c1 : c2;
    for (int j = 0; j < NS; j++) {       /* the slopes' conditioning: the margin of the numpy module */
        const double dj = w[j] - u[j], x = -2.0 * mu / dj;
        const double margin = TODA@@N@@_KAPPA_MAX * fabs(dj) * fabs(1.0 + x)
                              - kt * (fabs(u[j]) + fabs(w[j])) * (fabs(1.0 + x) + fabs(x));
        if (!isfinite(margin))
            return SYMBT_TODA_RANGE;
        if (!(margin > 0.0))
            return SYMBT_TODA_ILL_CONDITIONED;
    }
    for (int j = 0; j < NS; j++) {
        const int k = (j + 1) % NS;
        const double uj = u[j], dj = w[j] - u[j], un1 = u[k], dn1 = w[k] - u[k], wj = w[j], wn1 = w[k];
        if (!(@@positivity@@ > 0.0))
            return isfinite(dj) ? SYMBT_TODA_NO_REAL_MAP_POSITIVITY : SYMBT_TODA_RANGE;
        pn[j] = p[j] + @@eta_diff@@;
        qn[j] = q[j] + @@dq@@;
    }
    if (!toda@@N@@_finite(pn, NS) || !toda@@N@@_finite(qn, NS))
        return SYMBT_TODA_RANGE;
    for (int j = 0; j < NS; j++) {
        pt[j] = pn[j];
        qt[j] = qn[j];
    }
    return SYMBT_TODA_OK;
}

int toda@@N@@_spectral_trace(double lam, const double *p, const double *q, double *tr)
{
    double rv[NS], av[NS], M[4];
    if (!p || !q || !tr || !toda@@N@@_finite(p, NS) || !toda@@N@@_finite(q, NS) || !isfinite(lam))
        return SYMBT_TODA_INVALID_INPUT;
    if (!toda@@N@@_ratios(q, rv))
        return SYMBT_TODA_RANGE;
    for (int j = 0; j < NS; j++)
        av[j] = lam + p[j];
    const int e = toda@@N@@_monodromy(av, rv, M);
    const double t = ldexp(@@trace{A:M[0],D:M[3]}@@, e);
    if (!isfinite(t))
        return SYMBT_TODA_RANGE;
    *tr = t;
    return SYMBT_TODA_OK;
}

/* Polynomials in lambda: coefficient k of X at X[k + 1], X[0] = 0 (so X[k] is coefficient k - 1). */
#define NP (NS + 2)

/* M <- m_j M (kernel update, coefficient-wise with a = lambda + p_j) */
static void toda@@N@@_poly_left(double pj, double r, double *A, double *B, double *C, double *D)
{
    double nA[NP], nB[NP], nC[NP], nD[NP];
    nA[0] = nB[0] = nC[0] = nD[0] = 0.0;
    for (int k = 0; k <= NS; k++) {
        nA[k + 1] = @@coef:update[0]@@;
        nB[k + 1] = @@coef:update[1]@@;
        nC[k + 1] = @@coef:update[2]@@;
        nD[k + 1] = @@coef:update[3]@@;
    }
    for (int k = 0; k < NP; k++) {
        A[k] = nA[k];
        B[k] = nB[k];
        C[k] = nC[k];
        D[k] = nD[k];
    }
}

/* M <- M m_j (kernel update_right, coefficient-wise with a = lambda + p_j) */
static void toda@@N@@_poly_right(double pj, double r, double *A, double *B, double *C, double *D)
{
    double nA[NP], nB[NP], nC[NP], nD[NP];
    nA[0] = nB[0] = nC[0] = nD[0] = 0.0;
    for (int k = 0; k <= NS; k++) {
        nA[k + 1] = @@coef:update_right[0]@@;
        nB[k + 1] = @@coef:update_right[1]@@;
        nC[k + 1] = @@coef:update_right[2]@@;
        nD[k + 1] = @@coef:update_right[3]@@;
    }
    for (int k = 0; k < NP; k++) {
        A[k] = nA[k];
        B[k] = nB[k];
        C[k] = nC[k];
        D[k] = nD[k];
    }
}

static void toda@@N@@_identity(double *A, double *B, double *C, double *D)
{
    for (int k = 0; k < NP; k++)
        A[k] = B[k] = C[k] = D[k] = 0.0;
    A[1] = D[1] = 1.0;
}

int toda@@N@@_invariants(const double *p, const double *q, double *H)
{
    double rv[NS], A[NP], B[NP], C[NP], D[NP], out[NS];
    if (!p || !q || !H || !toda@@N@@_finite(p, NS) || !toda@@N@@_finite(q, NS))
        return SYMBT_TODA_INVALID_INPUT;
    if (!toda@@N@@_ratios(q, rv))
        return SYMBT_TODA_RANGE;
    toda@@N@@_identity(A, B, C, D);
    for (int j = 0; j < NS; j++)
        toda@@N@@_poly_left(p[j], rv[j], A, B, C, D);
    for (int k = 0; k < NS; k++)
        out[k] = @@trace{A:A[k + 1],D:D[k + 1]}@@;
    if (!toda@@N@@_finite(out, NS))
        return SYMBT_TODA_RANGE;
    for (int k = 0; k < NS; k++)
        H[k] = out[k];
    return SYMBT_TODA_OK;
}

/* sum_k c_k [lambda^k] (X(lambda) Y(lambda)) */
static double toda@@N@@_cdot(const double *c, const double *X, const double *Y)
{
    double s = 0.0;
    for (int i = 0; i < NS; i++)
        for (int l = 0; i + l < NS; l++)
            s += c[i + l] * X[i + 1] * Y[l + 1];
    return s;
}

int toda@@N@@_flow_field(const double *c, const double *p, const double *q, double *qdot, double *pdot)
{
    /* prefix P_j = m_{j-1} ... m_1 and suffix S_j = m_N ... m_{j+1}; d tr/dx_j = tr(dm_j/dx_j P_j S_j)
       (kernels dtr_dp, dtr_dr), contracted with c; d/dq_j by the chain rule (kernel dtr_dq) */
    static const int e00 = 0, e01 = 1, e10 = 2, e11 = 3;
    double rv[NS], pre[NS][4][NP], suf[NS][4][NP], A[NP], B[NP], C[NP], D[NP], cdp[NS], cdr[NS], qo[NS], po[NS];
    if (!c || !p || !q || !qdot || !pdot)
        return SYMBT_TODA_INVALID_INPUT;
    if (!toda@@N@@_finite(c, NS) || !toda@@N@@_finite(p, NS) || !toda@@N@@_finite(q, NS))
        return SYMBT_TODA_INVALID_INPUT;
    if (!toda@@N@@_ratios(q, rv))
        return SYMBT_TODA_RANGE;
    toda@@N@@_identity(A, B, C, D);
    for (int j = 0; j < NS; j++) {
        for (int k = 0; k < NP; k++) {
            pre[j][e00][k] = A[k];
            pre[j][e01][k] = B[k];
            pre[j][e10][k] = C[k];
            pre[j][e11][k] = D[k];
        }
        toda@@N@@_poly_left(p[j], rv[j], A, B, C, D);
    }
    toda@@N@@_identity(A, B, C, D);
    for (int j = NS - 1; j >= 0; j--) {
        for (int k = 0; k < NP; k++) {
            suf[j][e00][k] = A[k];
            suf[j][e01][k] = B[k];
            suf[j][e10][k] = C[k];
            suf[j][e11][k] = D[k];
        }
        toda@@N@@_poly_right(p[j], rv[j], A, B, C, D);
    }
    for (int j = 0; j < NS; j++) {
        cdp[j] = @@cdot:dtr_dp@@;
        cdr[j] = @@cdot:dtr_dr@@;
    }
    for (int j = 0; j < NS; j++) {
        const double r_prev = rv[(j + NS - 1) % NS], dr_prev = cdr[(j + NS - 1) % NS], r = rv[j], dr = cdr[j];
        qo[j] = cdp[j];
        po[j] = -(@@dtr_dq@@);
    }
    if (!toda@@N@@_finite(qo, NS) || !toda@@N@@_finite(po, NS))
        return SYMBT_TODA_RANGE;
    for (int j = 0; j < NS; j++) {
        qdot[j] = qo[j];
        pdot[j] = po[j];
    }
    return SYMBT_TODA_OK;
}
'''
