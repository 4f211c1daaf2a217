"""Compiled (numba, extra ``fast``) contact-law step: normal contact, both Masing channels.

The same arithmetic as the numpy path (:func:`contactlab.physics.masing_stack.masing_step` with
the loading curves of :mod:`contactlab.physics.master`), as loops over contacts instead of array
passes; the numpy path stays the reference and the tests compare the two. A step of the law is
three passes over the contacts: :func:`normal_pass` (inputs checked, depth/radius/force, which
contacts separate or leave the constant-load regime; no state written) and :func:`fused_pass`
(scale factors, tangential and torsional Masing steps and the outputs of every contact, in
two loops, one per channel, no temporary arrays). Contacts whose load changes go onto their
MDR springs through :func:`switch_pass` (once per contact, in the arrays the law allocated) and
then :func:`spring_pass` every step. The paraboloid's cube root by force is
:func:`contactlab.numeric.cube_root.cbrt_one` in a loop of its own (:func:`_cbrt_pass`: arithmetic
and bit operations, vectorised, no call; the numpy law takes its numpy twin), the other fractional
powers of the normal contact (``n != 2``) come from numpy's vectorised ``power``, so that the
compiled step matches the numpy law to the bit. The torsion
master curve's three polynomials are evaluated side by side in the lanes of one vector
(:func:`_poly3_lanes`, a numba intrinsic; the table from :func:`lane_table`).
:data:`AVAILABLE` is False when numba is not installed.
"""
from __future__ import annotations

import math

import threading
import weakref

import numpy as np

from ..errors import NotSupportedError
from ..numeric import jit as _jit
from ..numeric.cube_root import cbrt as _cbrt
from ..numeric.cube_root import cbrt_one as _cbrt_one
from . import law_kernel_springs as _springs
from .law_kernel_springs import (_first_pass, _spring_pass, _switch_pass, _switch_step_pass,
                                 spring_pass, switch_pass, switch_step_pass)

__all__ = ["AVAILABLE", "normal_pass", "fused_pass", "force_factor", "spring_pass", "switch_pass",
           "switch_step_pass", "TORSION", "TANGENTIAL"]

TORSION = 0
TANGENTIAL = 1


# ``prange`` in the loops over contacts: ``range`` in plain Python and in the serial build, numba's
# parallel range in the threaded build (numba's ``prange`` is ``range`` outside compiled code)
_prange = range


def _poly3(tab, j, u, u2, u4):
    """The three degree-7 polynomials of panel ``j`` of a lane table (:func:`lane_table`) at
    ``u`` (``u2 = u²``, ``u4 = u2²``) by Estrin's scheme in the order of
    :func:`contactlab.physics.master.evaluate`. Compiled, :func:`_poly3_lanes` replaces it: the
    same operations on 4-lane vectors (t, m, q and a zero lane), IEEE lane by lane, so the
    same bits in a third of the instructions."""
    c = tab[j]
    out = [((c[0, k] + c[1, k] * u) + (c[2, k] + c[3, k] * u) * u2)
           + ((c[4, k] + c[5, k] * u) + (c[6, k] + c[7, k] * u) * u2) * u4 for k in range(3)]
    return out[0], out[1], out[2]


_POLY3_PY = _poly3      # the plain source (the tests run the kernels uncompiled against it)


def _poly3_lanes():
    """:func:`_poly3` as a numba intrinsic: eight 4-lane loads of the panel's coefficients and
    Estrin's scheme on the vectors (LLVM IR written here: numba's optimiser does not pack the
    three scalar polynomials itself). Measured at 10^6 Hertz contacts: the master curve alone
    12.0 -> 8.1 ms (and the torsion pass, see the CHANGELOG), results bit-identical (no fused
    multiply-adds: each lane rounds as the scalar code)."""
    from llvmlite import ir  # type: ignore[import-untyped]  # (numba's dependency)
    from numba import types
    from numba.extending import intrinsic

    @intrinsic
    def poly3(typingctx, tab, j, u, u2, u4):
        f8 = types.float64
        sig = types.UniTuple(f8, 3)(tab, types.intp, f8, f8, f8)

        def codegen(context, builder, signature, args):
            tabv, jv, uv, u2v, u4v = args
            data = context.make_array(signature.args[0])(context, builder, tabv).data
            vty = ir.VectorType(ir.DoubleType(), 4)
            i32 = ir.IntType(32)
            base = builder.mul(jv, ir.Constant(jv.type, 32))

            def load(p):
                ptr = builder.gep(data, [builder.add(base, ir.Constant(base.type, 4 * p))])
                return builder.load(builder.bitcast(ptr, vty.as_pointer()), align=8)

            def splat(x):
                v = builder.insert_element(ir.Constant(vty, ir.Undefined), x, ir.Constant(i32, 0))
                return builder.shuffle_vector(v, v, ir.Constant(ir.VectorType(i32, 4),
                                                                [0, 0, 0, 0]))

            U, U2, U4 = splat(uv), splat(u2v), splat(u4v)
            c = [load(p) for p in range(8)]
            fa, fm = builder.fadd, builder.fmul
            lo = fa(fa(c[0], fm(c[1], U)), fm(fa(c[2], fm(c[3], U)), U2))
            hi = fa(fa(c[4], fm(c[5], U)), fm(fa(c[6], fm(c[7], U)), U2))
            r = fa(lo, fm(hi, U4))
            return context.make_tuple(builder, signature.return_type,
                                      [builder.extract_element(r, ir.Constant(i32, k))
                                       for k in range(3)])

        return sig, codegen

    return poly3


_LANES: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()     # curve -> its table


def lane_table(master) -> np.ndarray:
    """The coefficients of a :class:`~contactlab.physics.master.MasterCurve` of degree 7 as
    ``(panels, 8, 4)``: panel, power of ``u``, curve (t, m, q, then a zero lane), so that one
    panel's coefficient of one power for the three curves are adjacent (a vector load); built
    once per curve (the curves are cached per exponent)."""
    tab = _LANES.get(master)
    if tab is None:
        tab = np.zeros((master.coef.shape[1], 8, 4))
        tab[:, :, :3] = master.coef.transpose(1, 2, 0)
        _LANES[master] = tab
    return tab


def _load(kind, arg, xs, ys, aux, Ds, coef, y_scale, n, y0, m0, kp):
    """(y_load, aux, D_load) of one contact at argument arg >= 0 (``xs``: the inverse of the
    argument's scale, ``arg * xs`` is the curve's argument; scales ys, aux, Ds;
    ``coef``: the torsion curve's :func:`lane_table`);
    ``y0 > 0``: flat punch (no slip up to y0, unscaled table beyond); ``kp``: power of the
    panel map (:func:`contactlab.physics.master.evaluate`), None for 1 (numba compiles a
    separate specialisation for None and prunes the branches: the n >= 1 loop is unchanged)."""
    if kind == TORSION:
        y = arg * xs
        if y0 > 0.0:
            if y <= y0:
                return ys * (m0 * y), aux, 0.0
            y = y - y0
        N = coef.shape[0]
        if kp is None:
            s = y / (y + y_scale)
        else:
            r = (y / y_scale) ** (1.0 / kp)
            s = r / (1.0 + r)
        z = s * N
        # a NaN z (an input overflowing y to inf) takes panel 0 instead of casting NaN to an
        # index: the curves stay NaN and the law refuses the step; finite z >= 0 is unchanged
        j = min(int(z if z >= 0.0 else 0.0), N - 1)
        u = 2.0 * (z - j) - 1.0
        # degree 7 (the law's master curves, checked by fused_pass): Estrin's scheme in the
        # order of master.evaluate (same bits), the three curves side by side in the lanes of
        # one vector (:func:`_poly3`); a fallback loop for other degrees in this kernel was
        # measured 20 % slower over the whole pass (code layout), so there is none
        u2 = u * u
        u4 = u2 * u2
        t, m, q = _poly3(coef, j, u, u2, u4)
        t = min(max(t, 0.0), 1.0)
        if y0 == 0.0:
            if kp is not None:
                s = s ** kp
            m = m * s
            q = q * (s * s)
        return ys * m, aux * t, ys * arg * q
    x = arg * xs
    xc = min(x, 1.0)
    r = 1.0 - xc
    if n == 2.0:
        t = math.sqrt(r)
        one_t = xc / (1.0 + t)
    elif n == 1.0:
        t = r
        one_t = xc
    elif n == math.inf:
        one_t = 0.0 if xc < 1.0 else 1.0
        t = 1.0 - one_t
    else:
        one_t = -math.expm1(math.log1p(-xc) / n) if xc < 1.0 else 1.0
        t = 1.0 - one_t
    f = xc + r * one_t
    f2 = xc + r * f
    a1 = 1.0 / (n + 1.0)
    a2 = 1.0 / (2.0 * n + 1.0)
    J1 = one_t - f * a1
    J2 = one_t - 2.0 * f * a1 + f2 * a2
    w = max(x * J1 - J2, 0.0)
    return ys * f, aux * t, Ds * w


def _normal_of(hertz: bool = False):
    """:func:`_normal_pass` as a function for numba to compile, ``hertz``: with the
    paraboloid's exponent 2 a constant (the argument ``n`` ignored: the branches on ``n``
    fold away, the same bits; measured at 2 x 10^4 Hertz contacts by force, in cache, three
    rounds alternating: the loop 0.09-0.10 -> 0.08 ms)."""

    def _normal_pass(by_force, val, u, phi, has_u, has_phi, kc, E, n, flat, ref, rtol, pre,
                     fac, d_out, a_out, F_out, flag):
        """Depth, radius and force of every contact; flag: 0 constant load, 1 separated (a <= 0),
        2 depth left rtol of the reference depth. Returns counts (bad inputs, separated, off,
        contacts moved in both channels, non-finite results). ``pre``: the powers of the power-law
        family (``n != 2``) are given (numpy's vectorised ``power``, the reference's arithmetic
        to the bit): ``a_out`` holds the radius and, by force, ``d_out`` the depth ``kc a^n``.
        By force with ``n = 2``, ``a_out`` holds the force's cube root (:func:`_cbrt_pass`)
        and the radius is its product with ``fac``, the cube root of ``(n + 1)/(2 n E kc)``
        (:func:`force_factor`)."""
        if hertz:
            n = 2.0
        bad = 0
        dead = 0
        off = 0
        both = 0
        nonfinite = 0
        c2 = 2.0 * n / (n + 1.0) if n != math.inf else 2.0
        for i in _prange(val.size):
            v = val[i]
            ok = math.isfinite(v) and (v >= 0.0 or not by_force)
            if has_u and not math.isfinite(u[i]):
                ok = False
            if has_phi and not math.isfinite(phi[i]):
                ok = False
            if not ok:
                bad += 1
                v = 0.0
            if n == math.inf:                       # flat punch of radius flat[i]
                if by_force:
                    ai = flat[i] if v > 0.0 else 0.0
                    di = v / (2.0 * E[i] * flat[i])
                    Fi = v
                else:
                    dp = max(v, 0.0)
                    ai = flat[i] if dp > 0.0 else 0.0
                    di = v
                    Fi = 2.0 * E[i] * dp * flat[i]
            elif by_force:
                if n == 2.0:        # a = cbrt(F) cbrt(3/(4 E kc)), cbrt(F) given
                    ai = a_out[i] * fac[i]
                    di = kc[i] * ai * ai
                elif pre:
                    ai = a_out[i]
                    di = d_out[i]
                else:
                    ai = (v * ((n + 1.0) / (2.0 * n * E[i] * kc[i]))) ** (1.0 / (n + 1.0))
                    di = kc[i] * ai ** n
                Fi = v
            else:
                dp = max(v, 0.0)
                if n == 2.0:
                    ai = math.sqrt(dp / kc[i])
                elif pre:
                    ai = a_out[i]
                else:
                    ai = (dp / kc[i]) ** (1.0 / n)
                di = v
                Fi = c2 * E[i] * dp * ai
            d_out[i] = di
            a_out[i] = ai
            F_out[i] = Fi
            if not (math.isfinite(di) and math.isfinite(ai) and math.isfinite(Fi)):
                nonfinite += 1
            fl = 0
            if not ai > 0.0:
                fl = 1
                dead += 1
            else:
                r = ref[i]
                if r != 0.0 and abs(di - r) > rtol * r:
                    fl = 2
                    off += 1
                if has_u and has_phi and u[i] != 0.0 and phi[i] != 0.0:
                    both += 1
            flag[i] = fl
        return bad, dead, off, both, nonfinite

    _normal_pass.__name__ = _normal_pass.__qualname__ = "_normal_pass" + ("_hertz" if hertz
                                                                          else "")
    return _normal_pass


_normal_pass = _normal_of()
_normal_pass_hertz = _normal_of(True)


def _cbrt_pass(x, out):
    """``out = cbrt(x)`` (:func:`~contactlab.numeric.cube_root.cbrt_one`, glibc's algorithm in
    arithmetic and bit operations): the paraboloid's cube root of the force, ahead of the normal
    pass. A loop of its own with no call and no branch, compiled with numpy's error model (no
    zero-divisor test: its divisor ``2 t^3 + x`` is positive), which numba vectorises: measured
    at 10^6 contacts, AVX2, the normal pass 22 ms with numpy's (libm's) ``cbrt``, 9.4-9.8 ms
    with this loop (3.3-3.4 of it) and 20-21 ms with the cube root inside the normal pass's
    loop (whose branches keep it scalar)."""
    for i in _prange(x.size):
        out[i] = _cbrt_one(x[i])


def _channel_pass(c: int, hertz: bool = False):
    """The fused pass over the contacts for channel ``c`` (0: tangential, the first of the two
    passes; 1: torsion, the second): scales, the Masing step (the same bookkeeping as
    :func:`~contactlab.physics.masing_stack.masing_step`) and outputs of every contact, as a
    function that numba compiles with ``c`` a constant (a closure variable: the other channel's
    code and loading curve are left out). ``hertz``: the exponent is the paraboloid's 2 in the
    compiled code (the arguments ``n`` and ``y0`` are ignored: the paraboloid's torsion curve
    has no flat start): the tangential loading curve's branches on ``n`` and its constants
    ``1/(n+1)``, ``1/(2n+1)`` fold away, and the torsion curve's flat-punch branches (the
    same IEEE operations on the same values, so the same bits; measured at 2 x 10^4 Hertz
    contacts, in cache, three rounds alternating: tangential pass 0.31-0.32 -> 0.29-0.30 ms,
    torsion pass 0.44 -> 0.42 ms).

    Two passes, tangential then torsion, instead of both channels in one loop: the loop body
    of one channel is small enough for the processor to overlap the long dependency chains of
    neighbouring contacts (measured 14 % less CPU time of the fused work at 10^6 Hertz contacts,
    results bit-identical; the inputs the two passes share are read twice; the tangential
    pass first measured 3 % faster than the torsion pass first). The first pass handles
    separated contacts and those on springs, sets ``ref`` where it is 0 and leaves in ``dW``
    the tangential dissipation and in ``exact`` whether the contact's stack had not overflowed
    before the step; the second pass completes ``dW`` (tangential + torsion, in that order),
    ``exact`` and the counts.

    Channel state with a leading channel axis (0 tangential, 1 torsion): ``sx, sy, sw, last,
    depth, over`` (2, n), turning points ``X, Y`` (2, K, n), level-major: a step reads the
    top levels of each stack, and most contacts hold one or two, so the deeper levels' rows
    stay out of the memory traffic (a contact-major block of K levels is read whole)."""
    first = c == 0
    kind = TANGENTIAL if first else TORSION

    def _pass(u, phi, has_u, has_phi, d, a, F, flag, ref, mu, E, G, Gt, muE, n, coef, y_scale,
              y0, m0, kp, sx, sy, sw, last, depth, X, Y, over, Ft, ct, M, cm, dW, exact):
        if hertz:
            n = 2.0
            y0 = 0.0
        cM = math.pi * n / (2.0 * (n + 2.0)) if n != math.inf else 0.5 * math.pi
        K = X.shape[1]
        nonfinite = 0
        n_over = 0
        on = has_u if first else has_phi
        for i in _prange(a.size):
            ai = a[i]
            if first:
                if flag[i] == 3:                # on springs: the spring pass writes
                    exact[i] = False
                    continue
                if flag[i] == 1:                # separated: nothing carried, memory cleared
                    Ft[i] = 0.0
                    M[i] = 0.0
                    dW[i] = 0.0
                    ct[i] = ai
                    cm[i] = ai
                    exact[i] = False
                    continue
            elif flag[i] == 3 or flag[i] == 1:  # done by the first pass
                continue
            di = d[i]
            if first:
                if ref[i] == 0.0:
                    ref[i] = di
                exact[i] = not (over[0, i] | over[1, i])    # before the step: for the second
            mEd = muE[i] * di                   # (mu E) d: mu[i] * E[i] * di to the bit
            e = 0.0
            if on:
                if first:
                    xi = u[i]
                    xs = G[i] / mEd                 # inverse scales: arguments by multiplies
                    ys = mu[i] * F[i]
                    Ds = 2.0 * ai * (mEd * mEd) / G[i]
                else:
                    xi = phi[i]
                    xs = (2.0 * Gt[i] * ai) / mEd
                    ys = cM * mu[i] * E[i] * di * ai * ai
                    Ds = ys
                xp = sx[c, i]
                if xi != xp:
                    s = 2 * int(xi > xp) - 1            # (no branch: directions differ)
                    if last[c, i] != 0 and s != last[c, i]:
                        if depth[c, i] >= K:            # full: forget the innermost open loop
                            over[c, i] = True
                            depth[c, i] -= 2
                        k = depth[c, i]
                        X[c, k, i] = xp
                        Y[c, k, i] = sy[c, i]
                        depth[c, i] = k + 1
                        sw[c, i] = 0.0
                    last[c, i] = s
                    while depth[c, i] > 0:              # loop closure (Iwan erasure)
                        k = depth[c, i]
                        lim = X[c, k - 2, i] if k >= 2 else -X[c, 0, i]
                        if (xi - lim) * last[c, i] <= 0:
                            break
                        xo = X[c, k - 1, i]
                        D = _load(kind, abs(lim - xo) * 0.5, xs, ys, ai, Ds, coef, y_scale, n,
                                  y0, m0, kp)[2]
                        e += max(2.0 * D - sw[c, i], 0.0)
                        k = k - 2 if k >= 2 else 0
                        depth[c, i] = k
                        if k > 0:
                            xo2, f2, h2 = X[c, k - 1, i], 2.0, 0.5
                        else:
                            xo2, f2, h2 = 0.0, 1.0, 1.0
                        D = _load(kind, abs(lim - xo2) * h2, xs, ys, ai, Ds, coef, y_scale, n,
                                  y0, m0, kp)[2]
                        sw[c, i] = f2 * D
                k = depth[c, i]
                if k > 0:       # (x / f by a multiply: f is 1 or 2, the same bits)
                    xo, yo, f, h = X[c, k - 1, i], Y[c, k - 1, i], 2.0, 0.5
                else:
                    xo, yo, f, h = 0.0, 0.0, 1.0, 1.0
                yl, ax, D = _load(kind, abs(xi - xo) * h, xs, ys, ai, Ds, coef, y_scale, n, y0,
                                  m0, kp)
                sg = float(int(xi > xo) - int(xi < xo))     # 1, -1 or 0, without a branch
                yv = yo + sg * f * yl
                wn = f * D
                e += max(wn - sw[c, i], 0.0)
                sw[c, i] = max(sw[c, i], wn)
                sx[c, i] = xi
                sy[c, i] = yv
            else:
                yv = 0.0
                ax = ai
            if first:
                Ft[i] = yv
                ct[i] = ax
                dW[i] = e                       # the tangential share, completed by the second
                continue
            M[i] = yv
            cm[i] = ax
            wsum = 0.0                          # tangential + torsion, in that order
            if has_u:
                wsum += dW[i]
            if has_phi:
                wsum += e
            dW[i] = wsum
            was = not exact[i]
            now = over[0, i] | over[1, i]
            exact[i] = not now                  # an overflowed stack is approximate
            n_over += int(now > was)            # no branch: first overflow
            # one test of the sum: non-finite when an output is (a sum of finite outputs that
            # overflows only sends the step to the law's exact check of every array, which
            # finds none); measured 2-3 ms less per 10^6 contacts than five tests
            if not math.isfinite(wsum + Ft[i] + yv + ct[i] + ax):
                nonfinite += 1
        return nonfinite, n_over

    _pass.__name__ = _pass.__qualname__ = (("_fused_tangential" if first else "_fused_torsion")
                                           + ("_hertz" if hertz else ""))
    return _pass


_fused_torsion = _channel_pass(1)
_fused_tangential = _channel_pass(0)
_fused_tangential_hertz = _channel_pass(0, True)
_fused_torsion_hertz = _channel_pass(1, True)


# (the springs module indexes the spring passes by position: 2, 3, 4 and 6)
_PASSES = (_normal_pass, _fused_tangential, _spring_pass, _switch_pass, _switch_step_pass,
           _fused_torsion, _first_pass, _fused_tangential_hertz,
           _fused_torsion_hertz, _normal_pass_hertz, _cbrt_pass)
# the spring pass divides without numba's test of each divisor for zero (Python's
# ZeroDivisionError; a zero divisor gives the IEEE result, as in the numpy reference): measured
# 3-6 % faster with the split loop over cells, results bit-identical; the same for the n = 2
# channel passes (no difference in cache at 2 x 10^4 contacts, but at 10^6 Hertz contacts,
# four rounds alternating, one thread: tangential 16.1-16.7 -> 15.2-15.7 ms, torsion
# 21.7-22.2 -> 21.1-21.4 ms; fewer instructions per contact in flight beside the divisions);
# and the cube-root loop, which numba vectorises only without that test
_OPTIONS: dict[object, dict] = {_spring_pass: {"error_model": "numpy"},
                                _cbrt_pass: {"error_model": "numpy"},
                                _first_pass: {"error_model": "numpy"},
                                _fused_tangential_hertz: {"error_model": "numpy"},
                                _fused_torsion_hertz: {"error_model": "numpy"}}

AVAILABLE: bool   # declared for checkers only: the value comes from __getattr__ on first access
_KERNELS: dict = {}
_build_lock = threading.Lock()


def __getattr__(name: str):
    """``AVAILABLE``: numba is installed and imports (extra "fast"), answered on first access
    (numba takes ~0.2 s to import: not with contactlab, at the first law that may use it)."""
    if name == "AVAILABLE":
        return _jit.available()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def _kernels(parallel: bool) -> tuple:
    """The compiled ``(normal, fused tangential, spring, switch, switch-and-step in blocks,
    fused torsion, switch-and-step per contact, fused tangential, fused torsion and normal for
    n = 2, cube root)`` passes, serial or threaded (built on first use, compiled on their first call,
    machine code cached on disk: :func:`contactlab.numeric.jit.njit`; the plain Python
    functions without numba). The
    switch-and-step of both builds calls the serial switch and spring passes per block.
    Contacts are independent, so the threaded build gives bit-identical results. The two
    builds are cached under two names (numba keys its cache by function and argument types,
    not by the ``parallel`` option)."""
    kernels = _KERNELS.get(parallel)
    if kernels is None:
        if parallel:        # its switch-and-step runs the serial switch and spring per block
            _kernels(False)
        with _build_lock:
            if parallel not in _KERNELS:
                if _jit.available():
                    global _load, _poly3, _prange, _cbrt_one
                    import numba
                    if "load" not in _KERNELS:      # the callee, shared by both builds
                        _poly3 = _poly3_lanes()
                        # inlined into each pass at numba's IR level (measured 8-12 % faster
                        # fused pass than a call, results bit-identical)
                        _KERNELS["load"] = _load = _jit.njit(_load, nogil=True, inline="always")
                        _cbrt_one = _jit.njit(_cbrt_one, nogil=True, inline="always")
                        _prange = _springs._prange = numba.prange
                        for h in _springs._INLINE:      # the spring passes' shared pieces
                            setattr(_springs, h, _jit.njit(getattr(_springs, h), nogil=True,
                                                           inline="always"))
                        for h, lanes in _springs._intrinsics().items():
                            setattr(_springs, h, lanes)
                    _KERNELS[parallel] = tuple(
                        _jit.njit(f, name=f.__name__ + ("_parallel" if parallel else ""),
                                  nogil=True, parallel=parallel, **_OPTIONS.get(f, {}))
                        for f in _PASSES)
                    if not parallel:
                        _springs._switch_one = _KERNELS[False][3]
                        _springs._spring_one = _KERNELS[False][2]
                else:                       # pragma: no cover - without numba
                    _KERNELS[parallel] = _PASSES
            kernels = _KERNELS[parallel]
    return kernels


_EMPTY = np.zeros(1)


def normal_pass(by_force: bool, val, u, phi, kc, E, n: float, flat, ref, rtol: float,
                parallel: bool = False, out=None, factor=None):
    """Normal contact of every contact from a force (``by_force``) or a depth ``val``; ``u``,
    ``phi`` (or None) are only checked. ``flat``: punch radii (flat punch family, ``n = inf``).
    Returns ``(d, a, F, flag, counts)`` with ``flag`` 0 (constant load), 1 (separated), 2 (depth
    beyond ``rtol`` of ``ref``) and ``counts = (bad inputs, separated, off, both channels)``.
    ``out``: the four arrays to write into (default: new arrays). ``factor``:
    :func:`force_factor` per contact (the law's, computed once) or None (computed here)."""
    m = val.size
    d, a, F, flag = ((np.empty(m), np.empty(m), np.empty(m), np.empty(m, np.int8))
                     if out is None else out)
    if by_force and float(n) == 2.0 and factor is None:
        factor = force_factor(E, kc, 2.0)
    pre = _powers(by_force, val, kc, E, float(n), d, a, factor)
    kernels = _kernels(parallel)
    if by_force and float(n) == 2.0:    # a = cbrt(F) cbrt(3/(4 E kc)): cbrt(F) here
        kernels[10](val, a)
    fac = factor if by_force and float(n) == 2.0 else _EMPTY
    counts = kernels[9 if float(n) == 2.0 else 0](
        bool(by_force), val, _EMPTY if u is None else u, _EMPTY if phi is None else phi,
        u is not None, phi is not None, kc, E, float(n), flat, ref, float(rtol), pre, fac, d, a,
        F, flag)
    return d, a, F, flag, counts


def force_factor(E, kc, n: float):
    """``(n + 1)/(2 n E kc)`` per contact, the factor of the force in the radius
    ``a = (F (n + 1)/(2 n E kc))^(1/(n+1))`` (in the numpy reference's order,
    ``(n + 1)/(((2 n) E) kc)``: the same bits), for ``n = 2`` its cube root
    (:func:`contactlab.numeric.cube_root.cbrt`),
    the factor of the force's cube root in the paraboloid's radius
    ``a = cbrt(F) cbrt(3/(4 E kc))`` (:func:`contactlab.physics.law_xp.normal`), None for the
    flat punch: a law computes it once (these are per-contact constants), saving the step
    three passes (for ``n = 2``: four)."""
    if n == np.inf:
        return None
    c = (n + 1.0) / (2.0 * n * E * kc)
    return _cbrt(c) if n == 2.0 else c


def _powers(by_force: bool, val, kc, E, n: float, d, a, factor=None) -> bool:
    """The fractional powers of the normal contact for ``n != 2`` (the radius from a force or
    a depth; the depth ``kc a^n`` from a force) by numpy's vectorised ``power`` into ``a`` and
    ``d``, in the numpy reference's order of operations (:meth:`ContactLaw.normal`), so the
    compiled step matches it to the bit (a scalar ``pow`` in the kernel may differ from numpy's
    SIMD one by an ulp, and is slower); ``d`` is the only scratch; ``factor``:
    :func:`force_factor` (None: computed here). Returns whether they were computed (not for
    ``n = 2``: a square root from a depth, correctly rounded everywhere, and from a force
    the kernel's own cube root; not for the flat punch). Entries of bad inputs are garbage
    here; the kernel counts them and the step is refused."""
    if n == np.inf or n == 2.0:
        return False
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        if by_force:        # a = (F ((n+1) / (2 n E kc)))^(1/(n+1)), d = kc a^n
            if factor is None:
                factor = np.multiply(E, 2.0 * n, out=d)
                factor *= kc
                np.divide(n + 1.0, factor, out=factor)
            np.multiply(val, factor, out=a)
            a **= 1.0 / (n + 1.0)       # ``**=``: numpy's scalar fast paths, as ``**``
            d[...] = a
            d **= n
            d *= kc
        else:               # a = (max(d, 0) / kc)^(1/n)
            np.maximum(val, 0.0, out=a)
            a /= kc
            a **= 1.0 / n
    return True


def fused_pass(u, phi, d, a, F, flag, ref, mu, E, G, Gt, n: float, master, chan: dict,
               parallel: bool = False, out=None, muE=None):
    """Both channels of every contact in one pass (``master``: the torsion
    :class:`~contactlab.physics.master.MasterCurve`; ``chan``: the fields of
    :func:`~contactlab.physics.masing_stack.new_stack` stacked over a leading channel axis, 0
    tangential and 1 torsion, updated in place, the turning points also as level-major
    arrays ``X_levels``, ``Y_levels`` (2, K, n), which the kernel reads; ``ref`` set where it
    is 0). Returns
    ``(Ft, ct, M, cm, dW, exact, nonfinite, n_over)``: the outputs (written into ``out`` when
    given), a count that is not 0 when some output is not finite (the sum of a contact's
    outputs is tested: a sum of finite outputs that overflows counts too) and the number of
    contacts whose turning-point stack overflowed for the first time in this step (``exact``
    is False for every overflowed contact). ``muE``: ``mu E`` per contact (the law's, computed
    once: the passes form ``mu E d`` from it with one multiply, the same bits) or None (computed
    here)."""
    if master.coef.shape[2] != 8:
        raise NotSupportedError(
            f"the compiled contact law evaluates master curves of degree 7 (Estrin's scheme), "
            f"got degree {master.coef.shape[2] - 1}: build the curve with the default degree "
            "(contactlab.physics.master.MASTER_DEGREE).")
    m = a.size
    if out is None:
        out = (np.empty(m), np.empty(m), np.empty(m), np.empty(m), np.empty(m),
               np.empty(m, bool))
    kernels = _kernels(parallel)
    args = (_EMPTY if u is None else u, _EMPTY if phi is None else phi, u is not None,
            phi is not None, d, a, F, flag, ref, mu, E, G, Gt, mu * E if muE is None else muE,
            float(n), lane_table(master),
            float(master.y_scale), float(master.y0), float(master.m0),
            None if master.power == 1 else int(master.power), chan["x"], chan["y"], chan["w"],
            chan["last"], chan["depth"], chan["X_levels"], chan["Y_levels"], chan["overflow"],
            *out)
    hertz = float(n) == 2.0             # (the n = 2 builds: indices 7, 8)
    kernels[7 if hertz else 1](*args)                   # tangential (and flagged contacts)
    nf, n_over = kernels[8 if hertz else 5](*args)      # torsion, dW, exact, counts
    return (*out, nf, n_over)
