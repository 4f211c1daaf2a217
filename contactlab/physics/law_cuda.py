"""The contact law's Masing channels as one fused GPU kernel (``ContactLaw(backend="cupy")``).

The array-module step (:mod:`contactlab.physics.law_xp`) runs every array operation as a
kernel of its own, each reading its operands from device memory and writing its result back:
about 800 launches and 7.4–7.6 kB of memory traffic per contact and step, most of it in
Masing's rule (the reversal test, the rounds of loop closure, the loading curves). This module
holds that work for one channel (tangential or torsion) as one CUDA kernel, one thread per
contact: the thread reads its contact's stack (the top turning points only), evaluates the
loading curve where it is needed, and writes the stack and the channel's three outputs once.

The kernel is :data:`SOURCE`, plain C with a few macros, so that the same text builds
    * on a GPU through CuPy's runtime compiler (:func:`cupy_launcher`, ``--fmad=false``: no
      contraction of a multiply and an add into one rounding, the arithmetic as written), and
    * on the host with a C compiler (:func:`host_launcher`), which runs the kernel's text
      contact by contact against the numpy reference on any machine with ``cc``.
It performs, per contact, the floating-point operations of
:func:`contactlab.physics.law_xp.masing_step` with the loading curves of
:func:`~contactlab.physics.law_xp.tangential_curve` and
:func:`~contactlab.physics.master.evaluate` in the same order; the transcendental functions
(``sqrt``, ``pow``, ``expm1``, ``log1p``) come from the device's (or the host's) math library,
so results agree with the numpy law to rounding (not to the bit).

Pure kernels: arrays in, arrays out, the channel's stack updated in place; no object state.
"""
from __future__ import annotations

import ctypes
import os
import subprocess
import tempfile
from collections.abc import Callable
from typing import Any

import numpy as np

__all__ = ["SOURCE", "TANGENTIAL", "TORSION", "channel_args", "cupy_launcher",
           "host_launcher", "curve_kind"]

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

#define CHANNEL_ARGS \
    int kind, long long n_contacts, int K, \
    const double* x, const double* a, const double* d, const double* FN, \
    const double* mu, const double* E, const double* G, \
    double n, int ncase, double cM, \
    const double* coef, int N, double y_scale, double y0, double m0, int scaled, int power, \
    double* sx, double* sy, double* sw, signed char* last, long long* depth, \
    double* X, double* Y, unsigned char* over, \
    double* y_out, double* aux_out, double* w_out

#define CHANNEL_PASS \
    kind, n_contacts, K, x, a, d, FN, mu, E, G, n, ncase, cM, coef, N, y_scale, y0, m0, \
    scaled, power, sx, sy, sw, last, depth, X, Y, over, y_out, aux_out, w_out

/* Masing's rule for contact i (law_xp.masing_step, one contact) */
DEV void channel_one(long long i, CHANNEL_ARGS)
{
    const long long nc = n_contacts;
    double xi = x[i], ai = a[i], di = d[i];
    struct Scales S;
    S.kind = kind;
    S.ai = ai;
    S.n = n;
    S.ncase = ncase;
    S.coef = coef;
    S.N = N;
    S.y_scale = y_scale;
    S.y0 = y0;
    S.m0 = m0;
    S.scaled = scaled;
    S.power = power;
    double mEd = (mu[i] * E[i]) * di;
    if (kind == 0) {            /* G / (mu E d), mu F, 2 a (mu E d)^2 / G */
        S.xs = G[i] / mEd;
        S.ys = mu[i] * FN[i];
        S.Ds = ((2.0 * ai) * (mEd * mEd)) / G[i];
    } else {                    /* 2 G_t a / (mu E d), M_full */
        S.xs = ((2.0 * G[i]) * ai) / mEd;
        S.ys = ((((cM * mu[i]) * E[i]) * di) * ai) * ai;
        S.Ds = S.ys;
    }
    double xprev = sx[i];
    double delta = xi - xprev;
    int moved = delta != 0.0;
    int s = (delta > 0.0) - (delta < 0.0);
    int lst = last[i];
    long long dep = depth[i];
    double w = sw[i];
    double e = 0.0;
    double yl, ax, D;
    if (moved && lst != 0 && s != lst) {        /* a reversal: push the turning point */
        if (dep >= K) {                         /* full: forget the innermost open loop */
            over[i] = 1;
            dep -= (K >= 2 ? 2 : 1);
        }
        X[dep * nc + i] = xprev;
        Y[dep * nc + i] = sy[i];
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
    sw[i] = max_np(w, wn);
    sx[i] = xi;
    sy[i] = yv;
    last[i] = (signed char)lst;
    depth[i] = dep;
    y_out[i] = yv;
    aux_out[i] = ax;
    w_out[i] = e;
}

#ifdef CONTACTLAB_DEVICE
extern "C" __global__ void law_channel(CHANNEL_ARGS)
{
    long long i = (long long)blockIdx.x * blockDim.x + threadIdx.x;
    if (i < n_contacts)
        channel_one(i, CHANNEL_PASS);
}
#else
void law_channel(CHANNEL_ARGS)
{
    for (long long i = 0; i < n_contacts; i++)
        channel_one(i, CHANNEL_PASS);
}
#endif
"""

#: threads per block of the device kernel
THREADS = 256

# the kernel's scalar arguments in order, with their C types (the arrays are pointers)
_SCALARS = {"kind": np.int32, "n_contacts": np.int64, "K": np.int32, "n": np.float64,
            "ncase": np.int32, "cM": np.float64, "N": np.int32, "y_scale": np.float64,
            "y0": np.float64, "m0": np.float64, "scaled": np.int32, "power": np.int32}
_ORDER = ("kind", "n_contacts", "K", "x", "a", "d", "FN", "mu", "E", "G", "n", "ncase", "cM",
          "coef", "N", "y_scale", "y0", "m0", "scaled", "power", "sx", "sy", "sw", "last",
          "depth", "X", "Y", "over", "y_out", "aux_out", "w_out")


def curve_kind(n: float) -> int:
    """The tangential curve's case of the exponent ``n``: 1 and 2 (closed forms), 3 (flat
    punch, ``n = inf``), 0 otherwise."""
    return {1.0: 1, 2.0: 2, float("inf"): 3}.get(float(n), 0)


def channel_args(kind: int, x: Any, a: Any, d: Any, FN: Any, mu: Any, E: Any, G: Any,
                 n: float, master: Any, coef: Any, chan: dict, c: int, out: tuple) -> tuple:
    """The kernel's arguments, in order: channel ``kind`` (:data:`TANGENTIAL` with ``G`` the
    shear modulus, :data:`TORSION` with ``G`` the torsional one), control ``x``, radius ``a``
    and depth ``d`` (>0 in every lane: the law's safe values), normal force ``FN``, friction
    ``mu``, ``E*``, exponent ``n``, the torsion :class:`~contactlab.physics.master.MasterCurve`
    ``master`` with its table ``coef`` in the arrays' module, the law's stacked channel state
    ``chan`` (fields (2, n), turning points level-major (2, K, n)) of channel ``c``, and the
    outputs ``(y, aux, w)``."""
    if kind == TORSION and master.coef.shape[2] != 8:
        raise ValueError("the fused kernel evaluates master curves of degree 7")
    inf = float(n) == float("inf")
    cM = 0.5 * np.pi if inf else np.pi * float(n) / (2.0 * (float(n) + 2.0))
    vals = {"kind": kind, "n_contacts": x.size, "K": chan["X_levels"].shape[1], "x": x, "a": a,
            "d": d, "FN": FN, "mu": mu, "E": E, "G": G, "n": float(n),
            "ncase": curve_kind(n), "cM": cM, "coef": coef, "N": master.coef.shape[1],
            "y_scale": float(master.y_scale), "y0": float(master.y0), "m0": float(master.m0),
            "scaled": int(bool(master.scaled)), "power": int(master.power),
            "sx": chan["x"][c], "sy": chan["y"][c], "sw": chan["w"][c], "last": chan["last"][c],
            "depth": chan["depth"][c], "X": chan["X_levels"][c], "Y": chan["Y_levels"][c],
            "over": chan["overflow"][c], "y_out": out[0], "aux_out": out[1], "w_out": out[2]}
    return tuple(_SCALARS[k](vals[k]) if k in _SCALARS else vals[k] for k in _ORDER)


def cupy_launcher(cupy: Any) -> Callable[[tuple], None]:
    """A function that runs the kernel on CuPy arrays (compiled once per process and
    device by CuPy's runtime compiler, cached by CuPy on disk)."""
    kernel = cupy.RawKernel(SOURCE, "law_channel",
                            options=("-DCONTACTLAB_DEVICE", "--fmad=false"))

    def launch(args: tuple) -> None:
        size = int(args[1])
        if size:
            kernel(((size + THREADS - 1) // THREADS,), (THREADS,), args)
    return launch


def host_launcher(compiler: str = "cc") -> Callable[[tuple], None]:
    """A function that runs the kernel's text on numpy arrays, compiled for the host with
    ``compiler`` (no contraction, no fast math): the kernel tested on any machine.

    Raises
    ------
    OSError
        The compiler failed or is missing.
    """
    with tempfile.TemporaryDirectory(prefix="contactlab-law-cuda-") as folder:
        src = os.path.join(folder, "law_channel.c")
        lib = os.path.join(folder, "law_channel.so")
        with open(src, "w", encoding="utf-8") as fh:
            fh.write(SOURCE)
        done = subprocess.run([compiler, "-O2", "-fPIC", "-shared", "-ffp-contract=off",
                               "-fno-fast-math", "-o", lib, src, "-lm"],
                              capture_output=True, text=True, check=False)
        if done.returncode:
            raise OSError(f"{compiler} failed on the law's kernel: {done.stderr.strip()}")
        fn = ctypes.CDLL(lib).law_channel       # loaded: the files can go
    ctype: dict[type, Any] = {np.int32: ctypes.c_int, np.int64: ctypes.c_longlong,
                              np.float64: ctypes.c_double}
    fn.argtypes = [ctype[_SCALARS[k]] if k in _SCALARS else ctypes.c_void_p for k in _ORDER]
    fn.restype = None

    def launch(args: tuple) -> None:
        conv = []
        for k, v in zip(_ORDER, args):
            if k in _SCALARS:
                conv.append(v.item())
            else:
                if not v.flags.c_contiguous:
                    raise ValueError(f"{k} is not C-contiguous")
                conv.append(v.ctypes.data)
        fn(*conv)
    return launch
