"""The contact law's constant-load step as fused GPU kernels (``ContactLaw(backend="cupy")``).

The array-module step (:mod:`contactlab.physics.law_xp`) runs every array operation as a
kernel of its own, each reading its operands from device memory and writing its result back:
about 680 launches and 5.6–5.8 kB of memory traffic per contact and step, most of it in
Masing's rule (the reversal test, the rounds of loop closure, the loading curves). This module
holds that work as CUDA kernels with one thread per contact:

* ``law_normal``: the normal contact of every contact from a force or a depth, and flags that
  say whether the step is the plain constant-load case (every input finite, every contact in
  contact, no depth beyond ``load_rtol`` of its reference); no state written;
* ``law_step``: that case's whole step after it: the reference depths, both channels' Masing
  steps, the outputs, the overflow and finiteness tests, each contact's state read and
  written once;
* ``law_channel``: one channel's Masing step, for the steps that are not the plain case
  (separations, contacts switching onto their springs), whose bookkeeping stays array
  operations.

Contacts already on their MDR springs (stepped on the host) do not leave the plain case:
both kernels take a mask of them (``spring``), the normal kernel lets their loads change, and
the step kernel gives them placeholder outputs and leaves their stacks alone.

The kernels are :data:`SOURCE`, plain C with a few macros, so that the same text builds
    * on a GPU through CuPy's runtime compiler (:func:`cupy_kernels`, ``--fmad=false``: no
      contraction of a multiply and an add into one rounding, the arithmetic as written), and
    * on the host with a C compiler (:func:`host_kernels`), which runs the text contact by
      contact against the numpy reference on any machine with ``cc``.
They perform, per contact, the floating-point operations of :func:`contactlab.physics.law_xp.normal`
and :func:`~contactlab.physics.law_xp.masing_step` with the loading curves of
:func:`~contactlab.physics.law_xp.tangential_curve` and
:func:`~contactlab.physics.master.evaluate`, in the same order; the transcendental functions
(``sqrt``, ``cbrt``, ``pow``, ``expm1``, ``log1p``) come from the device's (or the host's)
math library, so results agree with the numpy law to rounding (not to the bit).

Pure kernels: arrays in, arrays out, the stacks updated in place; no object state.
"""
from __future__ import annotations

import ctypes
import os
import subprocess
import tempfile
from collections.abc import Callable
from typing import Any

import numpy as np

from ..errors import NotSupportedError

__all__ = ["SOURCE", "TANGENTIAL", "TORSION", "ORDER", "Kernels", "channel_args",
           "normal_args", "step_args", "cupy_kernels", "host_kernels", "curve_kind",
           "FLAG_BAD", "FLAG_SEPARATED", "FLAG_OFF", "FLAG_BOTH", "FLAG_NONFINITE",
           "COUNT_OVERFLOW"]

TANGENTIAL = 0
TORSION = 1

#: the kernel text (C; CUDA when compiled with -DCONTACTLAB_DEVICE)
SOURCE = r"""
#ifdef CONTACTLAB_DEVICE
#define DEV __device__ static
#else
#include <math.h>
#define DEV static
#endif

/* numpy's maximum and minimum: a NaN operand gives NaN */
DEV double max_np(double a, double b) { return (a >= b || a != a) ? a : b; }
DEV double min_np(double a, double b) { return (a <= b || a != a) ? a : b; }

/* Cattaneo-Mindlin virgin curve (t, f, w) at x >= 0; ncase 0: general n, 1: n = 1, 2: n = 2,
   3: n = inf (flat punch) */
DEV void tangential_curve(double x, double n, int ncase, double* t, double* f, double* w)
{
    double xc = min_np(x, 1.0);
    double r = 1.0 - xc;
    double tt, one_t;
    if (ncase == 2) {
        tt = sqrt(r);
        one_t = xc / (1.0 + tt);
    } else if (ncase == 1) {
        tt = r;
        one_t = xc;
    } else if (ncase == 3) {
        one_t = xc >= 1.0 ? 1.0 : 0.0;
        tt = 1.0 - one_t;
    } else {
        one_t = -expm1(log1p(-xc) / n);
        tt = 1.0 - one_t;
    }
    double ff = xc + r * one_t;
    double f2 = xc + r * ff;
    double a1 = 1.0 / (n + 1.0);
    double a2 = 1.0 / (2.0 * n + 1.0);
    double J1 = one_t - ff * a1;
    double J2 = one_t - 2.0 * ff * a1 + f2 * a2;
    *t = tt;
    *f = ff;
    *w = max_np(x * J1 - J2, 0.0);
}

/* the torsion master curves (t, m, q) at y >= 0: panel polynomials of degree 7 (Estrin) */
DEV void torsion_curves(double y, const double* coef, int N, double y_scale, double y0,
                        double m0, int scaled, int power, double* t, double* m, double* q)
{
    double yy = y;
    int pw = power;
    if (y0 > 0.0) {             /* flat punch: stuck up to y0, the table beyond */
        yy = max_np(y - y0, 0.0);
        pw = 1;
    }
    double s;
    if (pw == 1) {
        s = yy / (yy + y_scale);
    } else {
        double r = pow(yy / y_scale, 1.0 / pw);
        s = r / (1.0 + r);
    }
    double z = s * N;
    long long j = (z >= 0.0) ? ((z < (double)N) ? (long long)z : N - 1) : 0;   /* NaN: 0 */
    double u = 2.0 * (z - (double)j) - 1.0;
    double u2 = u * u;
    double u4 = u2 * u2;
    double out[3];
    for (int k = 0; k < 3; k++) {
        const double* c = coef + ((long long)k * N + j) * 8;
        out[k] = ((c[0] + c[1] * u) + (c[2] + c[3] * u) * u2)
                 + ((c[4] + c[5] * u) + (c[6] + c[7] * u) * u2) * u4;
    }
    double tt = min_np(max_np(out[0], 0.0), 1.0);
    double mm = out[1], qq = out[2];
    if (scaled) {
        double sp = pw != 1 ? pow(s, (double)pw) : s;
        mm = mm * sp;
        qq = qq * (sp * sp);
    }
    if (y0 > 0.0 && y <= y0) {
        tt = 1.0;
        mm = m0 * y;
        qq = 0.0;
    }
    *t = tt;
    *m = mm;
    *q = qq;
}

struct Scales {
    int kind;           /* 0 tangential, 1 torsion */
    double xs, ys, ai, Ds;
    double n;
    int ncase;
    const double* coef;
    int N;
    double y_scale, y0, m0;
    int scaled, power;
};

/* the loading curve of one contact at argument arg >= 0: (y_load, aux, D_load) */
DEV void load(const struct Scales* S, double arg, double* yl, double* aux, double* D)
{
    double t, f, w;
    if (S->kind == 0) {
        tangential_curve(arg * S->xs, S->n, S->ncase, &t, &f, &w);
        *yl = S->ys * f;
        *aux = S->ai * t;
        *D = S->Ds * w;
    } else {
        torsion_curves(arg * S->xs, S->coef, S->N, S->y_scale, S->y0, S->m0, S->scaled,
                       S->power, &t, &f, &w);
        *yl = S->ys * f;
        *aux = S->ai * t;
        *D = (S->ys * arg) * w;
    }
}

/* one channel's stack: fields of nc contacts, turning points level-major (K, nc) */
struct Stack {
    long long nc;
    int K;
    double *sx, *sy, *sw;
    signed char* last;
    long long* depth;
    double *X, *Y;
    unsigned char* over;
};

/* Masing's rule for contact i of one channel (law_xp.masing_step, one contact): control xi,
   radius ai, depth di, normal force FNi, friction mui, modulus Ei, shear (or torsional)
   modulus Gi; the response, the auxiliary radius and the dissipation of the step out */
DEV void masing_one(long long i, int kind, const struct Scales* C, const struct Stack* T,
                    double xi, double ai, double di, double FNi, double mui, double Ei,
                    double Gi, double cM, double* y_res, double* aux_res, double* w_res)
{
    const long long nc = T->nc;
    double* X = T->X;
    double* Y = T->Y;
    struct Scales S = *C;
    S.kind = kind;
    S.ai = ai;
    double mEd = (mui * Ei) * di;
    if (kind == 0) {            /* G / (mu E d), mu F, 2 a (mu E d)^2 / G */
        S.xs = Gi / mEd;
        S.ys = mui * FNi;
        S.Ds = ((2.0 * ai) * (mEd * mEd)) / Gi;
    } else {                    /* 2 G_t a / (mu E d), M_full */
        S.xs = ((2.0 * Gi) * ai) / mEd;
        S.ys = ((((cM * mui) * Ei) * di) * ai) * ai;
        S.Ds = S.ys;
    }
    double xprev = T->sx[i];
    double delta = xi - xprev;
    int moved = delta != 0.0;
    int s = (delta > 0.0) - (delta < 0.0);
    int lst = T->last[i];
    long long dep = T->depth[i];
    double w = T->sw[i];
    double e = 0.0;
    double yl, ax, D;
    if (moved && lst != 0 && s != lst) {        /* a reversal: push the turning point */
        if (dep >= T->K) {                      /* full: forget the innermost open loop */
            T->over[i] = 1;
            dep -= (T->K >= 2 ? 2 : 1);
        }
        X[dep * nc + i] = xprev;
        Y[dep * nc + i] = T->sy[i];
        dep += 1;
        w = 0.0;
    }
    if (moved) {
        lst = s;
        while (dep > 0) {                       /* loop closure (Iwan erasure) */
            double lim = dep >= 2 ? X[(dep - 2) * nc + i] : -X[i];
            if (!((xi - lim) * (double)lst > 0.0))
                break;
            double xo = X[(dep - 1) * nc + i];
            double f = 2.0;
            load(&S, fabs(lim - xo) / f, &yl, &ax, &D);
            e += max_np(f * D - w, 0.0);
            dep = dep >= 2 ? dep - 2 : 0;
            if (dep > 0) {
                xo = X[(dep - 1) * nc + i];
                f = 2.0;
            } else {
                xo = 0.0;
                f = 1.0;
            }
            load(&S, fabs(lim - xo) / f, &yl, &ax, &D);
            w = f * D;
        }
    }
    double xo = 0.0, yo = 0.0, f = 1.0;
    if (dep > 0) {
        xo = X[(dep - 1) * nc + i];
        yo = Y[(dep - 1) * nc + i];
        f = 2.0;
    }
    load(&S, fabs(xi - xo) / f, &yl, &ax, &D);
    double sg = (double)((xi > xo) - (xi < xo));
    double yv = yo + sg * f * yl;
    double wn = f * D;
    e += max_np(wn - w, 0.0);
    T->sw[i] = max_np(w, wn);
    T->sx[i] = xi;
    T->sy[i] = yv;
    T->last[i] = (signed char)lst;
    T->depth[i] = dep;
    *y_res = yv;
    *aux_res = ax;
    *w_res = e;
}

#define CURVE_ARGS \
    double n, int ncase, double cM, \
    const double* coef, int N, double y_scale, double y0, double m0, int scaled, int power

DEV void curve_of(struct Scales* C, CURVE_ARGS)
{
    C->n = n;
    C->ncase = ncase;
    C->coef = coef;
    C->N = N;
    C->y_scale = y_scale;
    C->y0 = y0;
    C->m0 = m0;
    C->scaled = scaled;
    C->power = power;
    (void)cM;
}

#define STATE_ARGS \
    double* sx, double* sy, double* sw, signed char* last, long long* depth, \
    double* X, double* Y, unsigned char* over

/* the stack of channel c in the law's stacked state ((2, nc) fields, (2, K, nc) points) */
DEV void stack_of(struct Stack* T, int c, long long nc, int K, STATE_ARGS)
{
    T->nc = nc;
    T->K = K;
    T->sx = sx + c * nc;
    T->sy = sy + c * nc;
    T->sw = sw + c * nc;
    T->last = last + c * nc;
    T->depth = depth + c * nc;
    T->X = X + (long long)c * K * nc;
    T->Y = Y + (long long)c * K * nc;
    T->over = over + c * nc;
}

#define CHANNEL_ARGS \
    int kind, long long n_contacts, int K, \
    const double* x, const double* a, const double* d, const double* FN, \
    const double* mu, const double* E, const double* G, CURVE_ARGS, STATE_ARGS, \
    double* y_out, double* aux_out, double* w_out

#define CHANNEL_PASS \
    kind, n_contacts, K, x, a, d, FN, mu, E, G, n, ncase, cM, coef, N, y_scale, y0, m0, \
    scaled, power, sx, sy, sw, last, depth, X, Y, over, y_out, aux_out, w_out

/* one channel of contact i (the stack fields of that channel only: c = 0 in stack_of) */
DEV void channel_one(long long i, CHANNEL_ARGS)
{
    struct Scales C;
    struct Stack T;
    curve_of(&C, n, ncase, cM, coef, N, y_scale, y0, m0, scaled, power);
    stack_of(&T, 0, n_contacts, K, sx, sy, sw, last, depth, X, Y, over);
    masing_one(i, kind, &C, &T, x[i], a[i], d[i], FN[i], mu[i], E[i], G[i], cM,
               y_out + i, aux_out + i, w_out + i);
}

/* flags of a step: 0 an input not finite (or a force < 0) or a normal result not finite,
   1 a contact separated, 2 a depth left load_rtol of its reference, 3 a contact with both a
   displacement and a twist, 4 an output not finite, 5 the count of first overflows */
#ifdef CONTACTLAB_DEVICE
#define COUNT(p) atomicAdd((p), 1ULL)
#else
#define COUNT(p) (*(p) += 1ULL)
#endif
#define FINITE(v) ((v) - (v) == 0.0)

#define NORMAL_ARGS \
    int by_force, long long n_contacts, const double* val, int has_u, const double* u, \
    int has_phi, const double* phi, const double* kc, const double* E, const double* flat, \
    double n, int flat_punch, double c2, double rtol, const double* ref, int has_spring, \
    const unsigned char* spring, double* d, double* a, double* F, unsigned long long* flags

#define NORMAL_PASS \
    by_force, n_contacts, val, has_u, u, has_phi, phi, kc, E, flat, n, flat_punch, c2, rtol, \
    ref, has_spring, spring, d, a, F, flags

/* normal contact of contact i (law_xp.normal) and the flags that send a step to the
   array path (a contact on its springs, spring[i] != 0, may change its load); no state
   written */
DEV void normal_one(long long i, NORMAL_ARGS)
{
    double v = val[i];
    if (!FINITE(v) || (by_force && v < 0.0) || (has_u && !FINITE(u[i]))
            || (has_phi && !FINITE(phi[i])))
        flags[0] = 1ULL;
    double di, ai, Fi;
    if (flat_punch) {
        if (by_force) {
            Fi = v;
            di = Fi / ((2.0 * E[i]) * flat[i]);
            ai = Fi > 0.0 ? flat[i] : 0.0;
        } else {
            double dp = max_np(v, 0.0);
            di = v;
            ai = dp > 0.0 ? flat[i] : 0.0;
            Fi = ((2.0 * E[i]) * dp) * flat[i];
        }
    } else if (by_force) {
        Fi = v;
        double c = (n + 1.0) / (((2.0 * n) * E[i]) * kc[i]);
        if (n == 2.0) {
            ai = cbrt(Fi) * cbrt(c);
            di = (kc[i] * ai) * ai;
        } else {
            ai = pow(Fi * c, 1.0 / (n + 1.0));
            di = kc[i] * pow(ai, n);
        }
    } else {
        double dp = max_np(v, 0.0);
        ai = n == 2.0 ? sqrt(dp / kc[i]) : pow(dp / kc[i], 1.0 / n);
        Fi = ((c2 * E[i]) * dp) * ai;
        di = v;
    }
    d[i] = di;
    a[i] = ai;
    F[i] = Fi;
    if (!(FINITE(di) && FINITE(ai) && FINITE(Fi)))
        flags[0] = 1ULL;
    if (!(ai > 0.0)) {
        flags[1] = 1ULL;
    } else {
        double r = ref[i];
        if (r != 0.0 && fabs(di - r) > rtol * r && !(has_spring && spring[i]))
            flags[2] = 1ULL;
        if (has_u && has_phi && u[i] != 0.0 && phi[i] != 0.0)
            flags[3] = 1ULL;
    }
}

#define STEP_ARGS \
    long long n_contacts, int K, int has_u, const double* u, int has_phi, const double* phi, \
    const double* d, const double* a, const double* F, \
    const double* mu, const double* E, const double* G, const double* Gt, CURVE_ARGS, \
    double* ref, int has_spring, const unsigned char* spring, STATE_ARGS, \
    double* Ft, double* ct, double* M, double* cm, double* dW, unsigned char* exact, \
    unsigned long long* flags

#define STEP_PASS \
    n_contacts, K, has_u, u, has_phi, phi, d, a, F, mu, E, G, Gt, n, ncase, cM, coef, N, \
    y_scale, y0, m0, scaled, power, ref, has_spring, spring, sx, sy, sw, last, depth, X, Y, \
    over, Ft, ct, M, cm, dW, exact, flags

/* the constant-load step of contact i, every contact in contact (the array step's
   bookkeeping for that case): reference depth, both channels, outputs, overflow and
   finiteness. A contact on its springs (spring[i] != 0; the host steps them and writes their
   outputs): the array step's initial outputs, not exact, its stacks left as they are (unused
   while it is on springs, reset when it leaves them), its normal results tested */
DEV void step_one(long long i, STEP_ARGS)
{
    double di = d[i], ai = a[i], Fi = F[i];
    if (has_spring && spring[i]) {
        Ft[i] = 0.0;
        ct[i] = ai;
        M[i] = 0.0;
        cm[i] = ai;
        dW[i] = 0.0;
        exact[i] = 0;
        double sum = di + ai;
        sum += Fi;
        if (!FINITE(sum))
            flags[4] = 1ULL;
        return;
    }
    struct Scales C;
    struct Stack T0, T1;
    curve_of(&C, n, ncase, cM, coef, N, y_scale, y0, m0, scaled, power);
    stack_of(&T0, 0, n_contacts, K, sx, sy, sw, last, depth, X, Y, over);
    stack_of(&T1, 1, n_contacts, K, sx, sy, sw, last, depth, X, Y, over);
    if (ref[i] == 0.0)
        ref[i] = di;
    int was = T0.over[i] | T1.over[i];
    double ft = 0.0, cti = ai, mi = 0.0, cmi = ai, e = 0.0, w;
    if (has_u) {
        masing_one(i, 0, &C, &T0, u[i], ai, di, Fi, mu[i], E[i], G[i], cM, &ft, &cti, &w);
        e = e + w;
    }
    if (has_phi) {
        masing_one(i, 1, &C, &T1, phi[i], ai, di, 0.0, mu[i], E[i], Gt[i], cM, &mi, &cmi,
                   &w);
        e = e + w;
    }
    int now = T0.over[i] | T1.over[i];
    Ft[i] = ft;
    ct[i] = cti;
    M[i] = mi;
    cm[i] = cmi;
    dW[i] = e;
    exact[i] = (unsigned char)!now;
    if (now && !was)
        COUNT(flags + 5);
    double tot = di + ai;       /* the array step's test: the sum, in its order */
    tot += Fi;
    tot += ft;
    tot += mi;
    tot += cti;
    tot += cmi;
    tot += e;
    if (!FINITE(tot))
        flags[4] = 1ULL;
}

#ifdef CONTACTLAB_DEVICE
#define KERNEL(name, ARGS, one, PASS) \
    extern "C" __global__ void name(ARGS) \
    { \
        long long i = (long long)blockIdx.x * blockDim.x + threadIdx.x; \
        if (i < n_contacts) \
            one(i, PASS); \
    }
#else
#define KERNEL(name, ARGS, one, PASS) \
    void name(ARGS) \
    { \
        for (long long i = 0; i < n_contacts; i++) \
            one(i, PASS); \
    }
#endif

KERNEL(law_channel, CHANNEL_ARGS, channel_one, CHANNEL_PASS)
KERNEL(law_normal, NORMAL_ARGS, normal_one, NORMAL_PASS)
KERNEL(law_step, STEP_ARGS, step_one, STEP_PASS)
"""

#: threads per block of the device kernels
THREADS = 256

#: the flags a step's kernels raise (:data:`SOURCE`): indices into the flag array
FLAG_BAD, FLAG_SEPARATED, FLAG_OFF, FLAG_BOTH, FLAG_NONFINITE, COUNT_OVERFLOW = range(6)

# the kernels' scalar arguments with their C types (every other argument is a pointer)
_SCALARS = {"kind": np.int32, "n_contacts": np.int64, "K": np.int32, "n": np.float64,
            "ncase": np.int32, "cM": np.float64, "N": np.int32, "y_scale": np.float64,
            "y0": np.float64, "m0": np.float64, "scaled": np.int32, "power": np.int32,
            "by_force": np.int32, "has_u": np.int32, "has_phi": np.int32,
            "flat_punch": np.int32, "c2": np.float64, "rtol": np.float64,
            "has_spring": np.int32}
_CURVE = ("n", "ncase", "cM", "coef", "N", "y_scale", "y0", "m0", "scaled", "power")
_STATE = ("sx", "sy", "sw", "last", "depth", "X", "Y", "over")
#: each kernel's arguments, in order
ORDER = {
    "law_channel": ("kind", "n_contacts", "K", "x", "a", "d", "FN", "mu", "E", "G", *_CURVE,
                    *_STATE, "y_out", "aux_out", "w_out"),
    "law_normal": ("by_force", "n_contacts", "val", "has_u", "u", "has_phi", "phi", "kc", "E",
                   "flat", "n", "flat_punch", "c2", "rtol", "ref", "has_spring", "spring", "d",
                   "a", "F", "flags"),
    "law_step": ("n_contacts", "K", "has_u", "u", "has_phi", "phi", "d", "a", "F", "mu", "E",
                 "G", "Gt", *_CURVE, "ref", "has_spring", "spring", *_STATE, "Ft", "ct", "M",
                 "cm", "dW", "exact", "flags"),
}


def curve_kind(n: float) -> int:
    """The tangential curve's case of the exponent ``n``: 1 and 2 (closed forms), 3 (flat
    punch, ``n = inf``), 0 otherwise."""
    return {1.0: 1, 2.0: 2, float("inf"): 3}.get(float(n), 0)


def _pack(name: str, vals: dict) -> tuple:
    return tuple(_SCALARS[k](vals[k]) if k in _SCALARS else vals[k] for k in ORDER[name])


def _curve(n: float, master: Any, coef: Any) -> dict:
    """The loading curves' arguments: exponent, cases, the torsion master curve's table."""
    if master.coef.shape[2] != 8:
        raise NotSupportedError(
            f"the fused GPU kernels evaluate master curves of degree 7 (Estrin's scheme), got "
            f"degree {master.coef.shape[2] - 1}: build the curve with the default degree "
            "(contactlab.physics.master.MASTER_DEGREE).")
    inf = float(n) == float("inf")
    cM = 0.5 * np.pi if inf else np.pi * float(n) / (2.0 * (float(n) + 2.0))
    return {"n": float(n), "ncase": curve_kind(n), "cM": cM, "coef": coef,
            "N": master.coef.shape[1], "y_scale": float(master.y_scale),
            "y0": float(master.y0), "m0": float(master.m0),
            "scaled": int(bool(master.scaled)), "power": int(master.power)}


def _state(chan: dict, c: int | None) -> dict:
    """The stack arrays: channel ``c``'s, or both channels' (None; the kernel offsets)."""
    def pick(v: Any) -> Any:
        return v if c is None else v[c]
    return {"sx": pick(chan["x"]), "sy": pick(chan["y"]), "sw": pick(chan["w"]),
            "last": pick(chan["last"]), "depth": pick(chan["depth"]),
            "X": pick(chan["X_levels"]), "Y": pick(chan["Y_levels"]),
            "over": pick(chan["overflow"]), "K": chan["X_levels"].shape[1]}


def channel_args(kind: int, x: Any, a: Any, d: Any, FN: Any, mu: Any, E: Any, G: Any,
                 n: float, master: Any, coef: Any, chan: dict, c: int, out: tuple) -> tuple:
    """The arguments of ``law_channel``, in order: channel ``kind`` (:data:`TANGENTIAL` with
    ``G`` the shear modulus, :data:`TORSION` with ``G`` the torsional one), control ``x``,
    radius ``a`` and depth ``d`` (>0 in every lane: the law's safe values), normal force
    ``FN``, friction ``mu``, ``E*``, exponent ``n``, the torsion
    :class:`~contactlab.physics.master.MasterCurve` ``master`` with its table ``coef`` in the
    arrays' module, the law's stacked channel state ``chan`` (fields (2, n), turning points
    level-major (2, K, n)) of channel ``c``, and the outputs ``(y, aux, w)``."""
    vals = {"kind": kind, "n_contacts": x.size, "x": x, "a": a, "d": d, "FN": FN, "mu": mu,
            "E": E, "G": G, **_curve(n, master, coef), **_state(chan, c),
            "y_out": out[0], "aux_out": out[1], "w_out": out[2]}
    return _pack("law_channel", vals)


def normal_args(by_force: bool, val: Any, u: Any, phi: Any, kc: Any, E: Any, flat: Any,
                n: float, rtol: float, ref: Any, out: tuple, flags: Any,
                spring: Any = None) -> tuple:
    """The arguments of ``law_normal``: the normal contact of every contact from a force
    (``by_force``) or a depth ``val``, the controls ``u`` and ``phi`` (None: absent; only
    checked), per-contact ``kc``, ``E*`` and punch radii ``flat``, exponent ``n``, the law's
    ``load_rtol`` and reference depths ``ref``; outputs ``(d, a, F)`` and the step's
    ``flags`` (uint64, :data:`FLAG_BAD` ...); ``spring``: one byte per contact (bool or
    uint8), nonzero for a contact on its springs (its load may change), or None (none is)."""
    n = float(n)
    vals = {"by_force": bool(by_force), "n_contacts": val.size, "val": val,
            "has_u": u is not None, "u": val if u is None else u, "has_phi": phi is not None,
            "phi": val if phi is None else phi, "kc": kc, "E": E, "flat": flat, "n": n,
            "flat_punch": n == float("inf"),
            "c2": 2.0 * n / (n + 1.0) if n != float("inf") else 2.0, "rtol": float(rtol),
            "ref": ref, "has_spring": spring is not None,
            "spring": flags if spring is None else spring, "d": out[0], "a": out[1],
            "F": out[2], "flags": flags}
    return _pack("law_normal", vals)


def step_args(u: Any, phi: Any, d: Any, a: Any, F: Any, mu: Any, E: Any, G: Any, Gt: Any,
              n: float, master: Any, coef: Any, ref: Any, chan: dict, out: tuple,
              flags: Any, spring: Any = None) -> tuple:
    """The arguments of ``law_step``: the constant-load step of every contact (all in
    contact) from the controls ``u`` and ``phi`` (None: absent), the normal
    results ``d``, ``a``, ``F``, the per-contact parameters, the curves, the reference depths
    ``ref`` and both channels' state ``chan``; outputs ``(Ft, ct, M, cm, dW, exact)`` and
    ``flags``; ``spring``: one byte per contact (bool or uint8), nonzero for a contact on its
    springs (left to the host: placeholder outputs, not exact, its stacks untouched), or
    None."""
    vals = {"n_contacts": d.size, "has_u": u is not None, "u": d if u is None else u,
            "has_phi": phi is not None, "phi": d if phi is None else phi, "d": d, "a": a,
            "F": F, "mu": mu, "E": E, "G": G, "Gt": Gt, **_curve(n, master, coef),
            "ref": ref, "has_spring": spring is not None,
            "spring": flags if spring is None else spring, **_state(chan, None),
            "Ft": out[0], "ct": out[1], "M": out[2], "cm": out[3], "dW": out[4],
            "exact": out[5], "flags": flags}
    return _pack("law_step", vals)


class Kernels:
    """The law's fused kernels, each a function of its argument tuple: ``channel`` (one
    channel's Masing step), ``normal`` and ``step`` (the whole constant-load step; None: only
    the channels are fused)."""

    def __init__(self, channel: Callable[[tuple], None],
                 normal: Callable[[tuple], None] | None = None,
                 step: Callable[[tuple], None] | None = None) -> None:
        self.channel = channel
        self.normal = normal
        self.step = step


def cupy_kernels(cupy: Any) -> Kernels:
    """The kernels on CuPy arrays (compiled once per process and device by CuPy's runtime
    compiler, cached by CuPy on disk)."""
    module = cupy.RawModule(code=SOURCE, options=("-DCONTACTLAB_DEVICE", "--fmad=false"))

    def launcher(name: str) -> Callable[[tuple], None]:
        kernel = module.get_function(name)
        at = ORDER[name].index("n_contacts")

        def launch(args: tuple) -> None:
            size = int(args[at])
            if size:
                kernel(((size + THREADS - 1) // THREADS,), (THREADS,), args)
        return launch
    return Kernels(launcher("law_channel"), launcher("law_normal"), launcher("law_step"))


def host_kernels(compiler: str = "cc") -> Kernels:
    """The kernels' text compiled for the host with ``compiler`` (no contraction, no fast
    math) and run contact by contact on numpy arrays: the kernels tested on any machine.

    Raises
    ------
    OSError
        The compiler failed or is missing.
    """
    with tempfile.TemporaryDirectory(prefix="contactlab-law-cuda-") as folder:
        src = os.path.join(folder, "law_kernels.c")
        lib = os.path.join(folder, "law_kernels.so")
        with open(src, "w", encoding="utf-8") as fh:
            fh.write(SOURCE)
        done = subprocess.run([compiler, "-O2", "-fPIC", "-shared", "-ffp-contract=off",
                               "-fno-fast-math", "-o", lib, src, "-lm"],
                              capture_output=True, text=True, check=False)
        if done.returncode:
            raise OSError(f"{compiler} failed on the law's kernels: {done.stderr.strip()}")
        dll = ctypes.CDLL(lib)                  # loaded: the files can go
    ctype: dict[type, Any] = {np.int32: ctypes.c_int, np.int64: ctypes.c_longlong,
                              np.float64: ctypes.c_double}

    def launcher(name: str) -> Callable[[tuple], None]:
        fn = getattr(dll, name)
        order = ORDER[name]
        fn.argtypes = [ctype[_SCALARS[k]] if k in _SCALARS else ctypes.c_void_p
                       for k in order]
        fn.restype = None

        def launch(args: tuple) -> None:
            conv = []
            for k, v in zip(order, args):
                if k in _SCALARS:
                    conv.append(v.item())
                else:
                    if not v.flags.c_contiguous:
                        raise ValueError(f"{k} is not C-contiguous")
                    conv.append(v.ctypes.data)
            fn(*conv)
        return launch
    return Kernels(launcher("law_channel"), launcher("law_normal"), launcher("law_step"))
