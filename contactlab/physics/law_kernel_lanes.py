"""The spring passes' pieces written as LLVM vectors (numba intrinsics, extra ``fast``): both
channels' Jenkins elements of a cell in two lanes (:func:`slip2`), and the cells of a row
inside the edge cell four at a time (:func:`cells4`), for
:mod:`contactlab.physics.law_kernel_springs`. IEEE lane by lane, no fused multiply-adds, the
comparisons and selects numba emits for the scalar source's ``min``, ``max``, ``abs`` and
``!=``: the bits of the scalar source (which the plain-Python run of the kernels and the
tests use). Built by :func:`contactlab.physics.law_kernel._kernels`; importing this module
imports numba. numba's disk cache keys a compiled pass by its own source file only: a change
here reaches a cached pass once :mod:`~contactlab.physics.law_kernel_springs` changes too (or
the cache is cleared).
"""
from __future__ import annotations

from llvmlite import ir  # type: ignore[import-untyped]  # (numba's dependency)
from numba import types
from numba.core import cgutils
from numba.extending import intrinsic

__all__ = ["slip2", "cells4", "first4"]


def slip2():
    """:func:`~contactlab.physics.law_kernel_springs._slip2` as a numba intrinsic: the two
    channels' elements side by side in the lanes of one 2-lane vector (LLVM IR written here:
    numba's optimiser does not pair the two channels itself), one vector division for both
    dissipations; no fused multiply-adds, the comparisons and selects of numba's
    ``min``/``max`` and ``!=`` lane by lane: each lane rounds and selects as the scalar
    code."""

    @intrinsic
    def slip2(typingctx, mt, mr, Kt, Kr, Lt, Lr, it, ir_):
        f8 = types.float64
        sig = types.UniTuple(f8, 4)(f8, f8, f8, f8, f8, f8, f8, f8)

        def codegen(context, builder, signature, args):
            vty = ir.VectorType(ir.DoubleType(), 2)
            i32 = ir.IntType(32)

            def pair(x, y):
                v = builder.insert_element(ir.Constant(vty, ir.Undefined), x,
                                           ir.Constant(i32, 0))
                return builder.insert_element(v, y, ir.Constant(i32, 1))

            m, K, L, inc = (pair(args[p], args[p + 1]) for p in range(0, 8, 2))
            trial = builder.fadd(m, builder.fmul(K, inc))
            nL = builder.fsub(ir.Constant(vty, [-0.0, -0.0]), L)
            # numba's max(x, y): y where y > x (ordered), else x; min: y where y < x
            lo = builder.select(builder.fcmp_ordered(">", nL, trial), nL, trial)
            mn = builder.select(builder.fcmp_ordered("<", L, lo), L, lo)
            zero = ir.Constant(vty, [0.0, 0.0])
            slips = builder.and_(builder.fcmp_ordered(">", K, zero),
                                 builder.fcmp_unordered("!=", trial, mn))
            de = builder.fdiv(builder.fmul(builder.fsub(trial, mn), mn), K)
            de = builder.select(slips, de, zero)
            return context.make_tuple(builder, signature.return_type,
                                      [builder.extract_element(v, ir.Constant(i32, k))
                                       for v in (mn, de) for k in range(2)])

        return sig, codegen

    return slip2


class _Lanes:
    """IR builders on ``W``-lane vectors of doubles for one intrinsic's code generation."""

    def __init__(self, context, builder, W: int):
        self.c, self.b, self.W = context, builder, W
        self.vty = ir.VectorType(ir.DoubleType(), W)
        self.i32 = ir.IntType(32)
        self.intp = context.get_value_type(types.intp)
        self.zero = self.const(0.0)

    def const(self, x):
        return ir.Constant(self.vty, [x] * self.W)

    def splat(self, x, vty=None):
        b, vty = self.b, vty or self.vty
        u = b.insert_element(ir.Constant(vty, ir.Undefined), x, ir.Constant(self.i32, 0))
        return b.shuffle_vector(u, u, ir.Constant(ir.VectorType(self.i32, self.W), [0] * self.W))

    def bsplat(self, x):
        return self.splat(x, ir.VectorType(ir.IntType(1), self.W))

    def ptr(self, ty, val, inds, vector=True):
        """Pointer to ``val[inds]`` (``W`` elements on from there where ``vector``)."""
        ary = self.c.make_array(ty)(self.c, self.b, val)
        p = cgutils.get_item_pointer2(self.c, self.b, ary.data,
                                      cgutils.unpack_tuple(self.b, ary.shape, ty.ndim),
                                      cgutils.unpack_tuple(self.b, ary.strides, ty.ndim),
                                      ty.layout, inds)
        return self.b.bitcast(p, self.vty.as_pointer()) if vector else p

    def clip(self, x, L):
        """numba's ``min(max(x, -L), L)``: ``max(x, y)`` is y where y > x (ordered), else x;
        ``min``: y where y < x; ``-L`` is ``-0.0 - L``."""
        b = self.b
        nL = b.fsub(self.const(-0.0), L)
        lo = b.select(b.fcmp_ordered(">", nL, x), nL, x)
        return b.select(b.fcmp_ordered("<", L, lo), L, lo)

    def slip(self, m, K, L, inc):
        """Elements after the increment ``inc`` and their dissipation ``(trial - m) m / K``
        where they slip (``K > 0``, ``trial != m``), else +0."""
        b = self.b
        trial = b.fadd(m, b.fmul(K, inc))
        mn = self.clip(trial, L)
        slips = b.and_(b.fcmp_ordered(">", K, self.zero), b.fcmp_unordered("!=", trial, mn))
        return mn, b.select(slips, b.fdiv(b.fmul(b.fsub(trial, mn), mn), K), self.zero)

    def geometry(self, tys, vals, i0, cov, cp1, cp2):
        """Boundaries ``bl, br`` of the cells ``i0 ..``, their squares and cubes, widths
        and the ``∫g``, ``∫xg`` differences (``tys``, ``vals``: beta, bG, bH)."""
        b = self.b
        i1 = b.add(i0, ir.Constant(self.intp, 1))

        def load(k, i):
            return b.load(self.ptr(tys[k], vals[k], [i]), align=8)

        C, C1, C2 = self.splat(cov), self.splat(cp1), self.splat(cp2)
        bl, br = b.fmul(C, load(0, i0)), b.fmul(C, load(0, i1))
        g = {"bl": bl, "br": br, "bl2": b.fmul(bl, bl), "br2": b.fmul(br, br)}
        g["bl3"], g["br3"] = b.fmul(g["bl2"], bl), b.fmul(g["br2"], br)
        g["w"] = b.fsub(br, bl)
        g["x1"] = b.fsub(g["br2"], g["bl2"])
        g["dg"] = b.fsub(b.fmul(C1, load(1, i1)), b.fmul(C1, load(1, i0)))
        g["dh"] = b.fsub(b.fmul(C2, load(2, i1)), b.fmul(C2, load(2, i0)))
        return g

    def limits(self, g, d, L2, L4):
        """``(2 mu E (d w - dg), 4 mu E (d x1 / 2 - dh))`` at depth ``d``."""
        b, D = self.b, self.splat(d)
        return (b.fmul(self.splat(L2), b.fsub(b.fmul(D, g["w"]), g["dg"])),
                b.fmul(self.splat(L4), b.fsub(b.fdiv(b.fmul(D, g["x1"]), self.const(2.0)),
                                              g["dh"])))

    def active(self, cnt):
        ity = ir.VectorType(self.intp, self.W)
        return self.b.icmp_signed("<", ir.Constant(ity, list(range(self.W))),
                                  self.splat(cnt, ity))

    def sums(self, g, mt, mr, et, er, Lt, Lr, on_t, on_r, a, e_, F_, M_, ft, fm, ct, cm):
        """The stepped lanes ``on_t``, ``on_r`` summed on in the cells' order: ``(e, F, M,
        free_t, free_m, ct, cm)``."""
        b, W, i32, zero = self.b, self.W, self.i32, self.zero
        # the lanes not stepped summed as +0 (a sum from +0 is never -0: the same bits)
        zt, et = b.select(on_t, mt, zero), b.select(on_t, et, zero)
        zr, er = b.select(on_r, mr, zero), b.select(on_r, er, zero)
        F, Mo = F_, M_
        for lane in range(W):
            L_ = ir.Constant(i32, lane)
            F = b.fadd(F, b.extract_element(zt, L_))
            Mo = b.fadd(Mo, b.extract_element(zr, L_))
        # the dissipation summed on only where a lane's is not zero (adding a zero leaves
        # the sum's bits): the chain of additions off the common path of sticking cells
        iW = ir.IntType(W)
        nz = b.or_(b.fcmp_unordered("!=", et, zero), b.fcmp_unordered("!=", er, zero))
        slipping = b.icmp_unsigned("!=", b.bitcast(nz, iW), ir.Constant(iW, 0))
        before = b.basic_block
        with b.if_then(slipping, likely=False):
            e = e_
            for lane in range(W):
                L_ = ir.Constant(i32, lane)
                e = b.fadd(e, b.extract_element(et, L_))
                e = b.fadd(e, b.extract_element(er, L_))
            summed = b.basic_block
        e_phi = b.phi(e_.type)
        e_phi.add_incoming(e, summed)
        e_phi.add_incoming(e_, before)
        # the first cell at its limit: its left boundary, at most the radius
        cttz = cgutils.get_or_insert_function(
            b.module, ir.FunctionType(i32, [i32, ir.IntType(1)]), "llvm.cttz.i32")
        vi64 = ir.VectorType(ir.IntType(64), W)
        sign = ir.Constant(vi64, [0x7FFFFFFFFFFFFFFF] * W)

        def stick(m, L, on, free, cs):
            absm = b.bitcast(b.and_(b.bitcast(m, vi64), sign), self.vty)
            hit = b.and_(on, b.fcmp_ordered(">=", absm, L))
            bits = b.zext(b.bitcast(hit, iW), i32)
            anyhit = b.icmp_unsigned("!=", bits, ir.Constant(i32, 0))
            first = b.call(cttz, [bits, ir.Constant(ir.IntType(1), 0)])
            first = b.select(anyhit, first, ir.Constant(i32, 0))
            bk = b.extract_element(g["bl"], first)
            new = b.select(b.fcmp_ordered("<", a, bk), a, bk)          # min(b, a)
            return b.and_(free, b.not_(anyhit)), b.select(b.and_(free, anyhit), new, cs)

        ft, ct = stick(mt, Lt, on_t, ft, ct)
        fm, cm = stick(mr, Lr, on_r, fm, cm)
        return [e_phi, F, Mo, ft, fm, ct, cm]


def _cast(context, builder, args, tys, ints, first):
    """The scalars from ``first`` on cast to intp (positions ``ints``), boolean or float64."""
    f8, b1 = types.float64, types.boolean
    return [x if k < first else
            context.cast(builder, x, t, types.intp if k in ints else b1 if t == b1 else f8)
            for k, (x, t) in enumerate(zip(args, tys))]


def cells4(W: int):
    """:func:`~contactlab.physics.law_kernel_springs._cells` for ``W`` (four) cells as a numba
    intrinsic: the cells' boundaries, limits, stiffnesses and elements of each channel in
    the lanes of one vector (unaligned loads of the unit boundaries, their ``∫g`` and
    ``∫xg`` tables and the row's elements; the lanes past ``cnt`` stored back as loaded),
    then the sums, dissipation and stick radii in the cells' order, lane by lane (LLVM IR
    written here: numba's optimiser does not vectorise the loop of a handful of cells). No
    fused multiply-adds; the comparisons and selects of numba's ``min``, ``max``, ``abs``
    and ``!=``: each lane rounds and selects as the scalar code, so the same bits. The
    caller keeps ``i0 + W <= N`` (the loads stay in the row)."""

    @intrinsic
    def cells4(typingctx, beta, bG, bH, m_tan, m_tor, r, i0, cnt, cov, cp1, cp2, d, K2, K16,
               L2, L4, it, ir_, has_u, has_phi, a, e, Ft, M, free_t, free_m, ct, cm):
        f8, b1 = types.float64, types.boolean
        if any(getattr(t, "layout", "") != "C" for t in (beta, bG, bH, m_tan, m_tor)):
            return None             # vector loads: contiguous tables and rows only
        argtys = (beta, bG, bH, m_tan, m_tor, r, i0, cnt, cov, cp1, cp2, d, K2, K16, L2, L4,
                  it, ir_, has_u, has_phi, a, e, Ft, M, free_t, free_m, ct, cm)
        sig = types.Tuple((f8, f8, f8, b1, b1, f8, f8))(*argtys)

        def codegen(context, builder, signature, args):
            tys = signature.args
            v = _cast(context, builder, args, tys, (5, 6, 7), 5)
            (_, _, _, _, _, r_, i0_, cnt_, cov_, cp1_, cp2_, d_, K2_, K16_, L2_,
             L4_, it_, ir__, hu, hp, a_, e_, F_, M_, ft, fm, ct_, cm_) = v
            V = _Lanes(context, builder, W)
            b = builder
            g = V.geometry(tys, v, i0_, cov_, cp1_, cp2_)
            Lt, Lr = V.limits(g, d_, L2_, L4_)
            Kt = b.fmul(V.splat(K2_), g["w"])
            Kr = b.fmul(V.splat(K16_), b.fdiv(b.fsub(g["br3"], g["bl3"]), V.const(3.0)))
            pt, pr = V.ptr(tys[3], v[3], [r_, i0_]), V.ptr(tys[4], v[4], [r_, i0_])
            mt0 = b.load(pt, align=8)
            mr0 = b.load(pr, align=8)
            mt, et = V.slip(mt0, Kt, Lt, V.splat(it_))
            mr, er = V.slip(mr0, Kr, Lr, V.splat(ir__))
            act = V.active(cnt_)
            on_t = b.and_(act, V.bsplat(hu))
            on_r = b.and_(act, V.bsplat(hp))
            b.store(b.select(on_t, mt, mt0), pt, align=8)
            b.store(b.select(on_r, mr, mr0), pr, align=8)
            out = V.sums(g, mt, mr, et, er, Lt, Lr, on_t, on_r, a_, e_, F_, M_, ft, fm, ct_,
                         cm_)
            return context.make_tuple(b, signature.return_type, out)

        return sig, codegen

    return cells4


def first4(W: int):
    """:func:`~contactlab.physics.law_kernel_springs._first_cells` for ``W`` (four) cells as a
    numba intrinsic (:func:`cells4`'s lanes): the switch's elements (each channel's turning
    points ``X[ch, c, :depth]`` then its control replayed through the cells' elements at
    the held depth ``d0``, the increments per contact), the step's (depth ``d``) where a
    channel is driven, both stored (the lanes past ``cnt`` as +0: see below) and
    summed on in the cells' order. The caller keeps ``i0 + W <= N``."""

    @intrinsic
    def first4(typingctx, beta, bG, bH, X, m_tan, m_tor, r, c, i0, cnt, dt, dr, cov, cp1, cp2,
               d0, d, K2, K16, L2, L4, incs, it, ir_, st_u, st_p, a, acc):
        f8, b1 = types.float64, types.boolean
        if any(getattr(t, "layout", "") != "C" for t in (beta, bG, bH, m_tan, m_tor)):
            return None             # vector loads: contiguous tables and rows only
        accty = types.Tuple((f8, f8, f8, b1, b1, f8, f8))
        if incs != types.UniTuple(f8, 4) or acc != accty:
            return None
        argtys = (beta, bG, bH, X, m_tan, m_tor, r, c, i0, cnt, dt, dr, cov, cp1, cp2, d0, d,
                  K2, K16, L2, L4, incs, it, ir_, st_u, st_p, a, acc)
        sig = accty(*argtys)

        def codegen(context, builder, signature, args):
            tys = signature.args
            flat = list(args[:21]) + cgutils.unpack_tuple(builder, args[21], 4) + list(
                args[22:27]) + cgutils.unpack_tuple(builder, args[27], 7)
            ftys = list(tys[:21]) + [f8] * 4 + list(tys[22:27]) + list(accty.types)
            v = _cast(context, builder, flat, ftys, (6, 7, 8, 9, 10, 11), 6)
            (_, _, _, _, _, _, r_, c_, i0_, cnt_, dt_, dr_, cov_, cp1_, cp2_, d0_, d_, K2_,
             K16_, L2_, L4_, it0_, ir0_, itl_, irl_, it_, ir__, su, sp, a_, e_, F_, M_, ft,
             fm, ct_, cm_) = v
            V = _Lanes(context, builder, W)
            b = builder
            intp = V.intp
            one = ir.Constant(intp, 1)
            g = V.geometry(tys, v, i0_, cov_, cp1_, cp2_)
            Kt = b.fmul(V.splat(K2_), g["w"])
            Kr = b.fmul(V.splat(K16_), b.fdiv(b.fsub(g["br3"], g["bl3"]), V.const(3.0)))
            L0t, L0r = V.limits(g, d0_, L2_, L4_)

            def replay(ch, K, L, depth, first, last):
                """0 -> X[ch, c, 0] -> ... -> X[ch, c, depth - 1] -> the control."""
                m = cgutils.alloca_once_value(b, V.zero)
                with b.if_then(b.icmp_signed(">", depth, ir.Constant(intp, 0))):
                    b.store(V.clip(b.fadd(V.zero, b.fmul(K, V.splat(first))), L), m)
                    with cgutils.for_range(b, b.sub(depth, one)) as loop:
                        q = b.add(loop.index, one)
                        chv = ir.Constant(intp, ch)
                        xq = b.load(V.ptr(tys[3], v[3], [chv, c_, q], vector=False))
                        xp = b.load(V.ptr(tys[3], v[3], [chv, c_, b.sub(q, one)],
                                          vector=False))
                        inc = V.splat(b.fsub(xq, xp))
                        b.store(V.clip(b.fadd(b.load(m), b.fmul(K, inc)), L), m)
                return V.clip(b.fadd(b.load(m), b.fmul(K, V.splat(last))), L)

            m0t = replay(0, Kt, L0t, dt_, it0_, itl_)
            m0r = replay(1, Kr, L0r, dr_, ir0_, irl_)
            Lt, Lr = V.limits(g, d_, L2_, L4_)
            mt, et = V.slip(m0t, Kt, Lt, V.splat(it_))
            mr, er = V.slip(m0r, Kr, Lr, V.splat(ir__))
            act = V.active(cnt_)
            pt, pr = V.ptr(tys[4], v[4], [r_, i0_]), V.ptr(tys[5], v[5], [r_, i0_])
            # the lanes past ``cnt`` stored +0, not loaded and stored back: the row is fresh,
            # its cells past the four's are the edge cells' (written after) or +0 (a load of
            # the row's line measured ~5 % of the pass at 10^5 contacts)
            b.store(b.select(act, b.select(V.bsplat(su), mt, m0t), V.zero), pt, align=8)
            b.store(b.select(act, b.select(V.bsplat(sp), mr, m0r), V.zero), pr, align=8)
            out = V.sums(g, mt, mr, et, er, Lt, Lr, b.and_(act, V.bsplat(su)),
                         b.and_(act, V.bsplat(sp)), a_, e_, F_, M_, ft, fm, ct_, cm_)
            return context.make_tuple(b, signature.return_type, out)

        return sig, codegen

    return first4
