"""The spring passes' pieces written as LLVM vectors (numba intrinsics, extra ``fast``): both
channels' Jenkins elements of a cell in two lanes (:func:`slip2`), and the cells of a row
inside the edge cell four at a time (:func:`cells4`), for
:mod:`contactlab.physics.law_kernel_springs`. IEEE lane by lane, no fused multiply-adds, the
comparisons and selects numba emits for the scalar source's ``min``, ``max``, ``abs`` and
``!=``: the bits of the scalar source (which the plain-Python run of the kernels and the
tests use). Built by :func:`contactlab.physics.law_kernel._kernels`; importing this module
imports numba.
"""
from __future__ import annotations

from llvmlite import ir  # type: ignore[import-untyped]  # (numba's dependency)
from numba import types
from numba.core import cgutils
from numba.extending import intrinsic

__all__ = ["slip2", "cells4"]


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


def cells4(W: int):
    """:func:`~contactlab.physics.law_kernel_springs._cells` for ``W`` (four) cells as a numba
    intrinsic: the cells' boundaries, limits,
    stiffnesses and elements of each channel in the lanes of one 4-lane vector (unaligned
    loads of the unit boundaries, their ``∫g`` and ``∫xg`` tables and the row's elements;
    the lanes past ``cnt`` stored back as loaded), then the sums, dissipation and stick
    radii in the cells' order, lane by lane (LLVM IR written here: numba's optimiser does
    not vectorise the loop of a handful of cells). No fused multiply-adds; the comparisons
    and selects of numba's ``min``, ``max``, ``abs`` and ``!=``: each lane rounds and
    selects as the scalar code, so the same bits. The caller keeps ``i0 + 4 <= N`` (the
    loads stay in the row)."""

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
            v = [context.cast(builder, x, t, types.intp if 5 <= k <= 7 else
                              b1 if t == types.boolean else f8)
                 if k >= 5 else x for k, (x, t) in enumerate(zip(args, tys))]
            (_, _, _, _, _, r_, i0_, cnt_, cov_, cp1_, cp2_, d_, K2_, K16_, L2_,
             L4_, it_, ir__, hu, hp, a_, e_, F_, M_, ft, fm, ct_, cm_) = v
            vty = ir.VectorType(ir.DoubleType(), W)
            i32 = ir.IntType(32)
            intp = context.get_value_type(types.intp)
            fa, fs, fm_, fd = builder.fadd, builder.fsub, builder.fmul, builder.fdiv

            def ptr(k, inds):
                t = tys[k]
                ary = context.make_array(t)(context, builder, v[k])
                p = cgutils.get_item_pointer2(context, builder, ary.data,
                                              cgutils.unpack_tuple(builder, ary.shape, t.ndim),
                                              cgutils.unpack_tuple(builder, ary.strides, t.ndim),
                                              t.layout, inds)
                return builder.bitcast(p, vty.as_pointer())

            def splat(x):
                u = builder.insert_element(ir.Constant(vty, ir.Undefined), x,
                                           ir.Constant(i32, 0))
                return builder.shuffle_vector(u, u, ir.Constant(ir.VectorType(i32, W), [0] * W))

            def lanes(c):
                return ir.Constant(vty, [c] * W)

            i1 = builder.add(i0_, ir.Constant(intp, 1))

            def load(k, inds):
                return builder.load(ptr(k, inds), align=8)

            COV = splat(cov_)
            bl = fm_(COV, load(0, [i0_]))
            br = fm_(COV, load(0, [i1]))
            bl2 = fm_(bl, bl)
            bl3 = fm_(bl2, bl)
            br2 = fm_(br, br)
            br3 = fm_(br2, br)
            w = fs(br, bl)
            C1, C2, D = splat(cp1_), splat(cp2_), splat(d_)
            dg = fs(fm_(C1, load(1, [i1])), fm_(C1, load(1, [i0_])))
            dh = fs(fm_(C2, load(2, [i1])), fm_(C2, load(2, [i0_])))
            Lt = fm_(splat(L2_), fs(fm_(D, w), dg))
            Lr = fm_(splat(L4_), fs(fd(fm_(D, fs(br2, bl2)), lanes(2.0)), dh))
            Kt = fm_(splat(K2_), w)
            Kr = fm_(splat(K16_), fd(fs(br3, bl3), lanes(3.0)))
            zero = lanes(0.0)

            def slip(m, K, L, inc):
                trial = fa(m, fm_(K, inc))
                nL = fs(lanes(-0.0), L)
                lo = builder.select(builder.fcmp_ordered(">", nL, trial), nL, trial)
                mn = builder.select(builder.fcmp_ordered("<", L, lo), L, lo)
                slips = builder.and_(builder.fcmp_ordered(">", K, zero),
                                     builder.fcmp_unordered("!=", trial, mn))
                return mn, builder.select(slips, fd(fm_(fs(trial, mn), mn), K), zero)

            pt, pr = ptr(3, [r_, i0_]), ptr(4, [r_, i0_])
            mt0 = builder.load(pt, align=8)
            mr0 = builder.load(pr, align=8)
            mt, et = slip(mt0, Kt, Lt, splat(it_))
            mr, er = slip(mr0, Kr, Lr, splat(ir__))
            ity = ir.VectorType(intp, W)
            n_ = builder.insert_element(ir.Constant(ity, ir.Undefined), cnt_,
                                        ir.Constant(i32, 0))
            n_ = builder.shuffle_vector(n_, n_, ir.Constant(ir.VectorType(i32, W), [0] * W))
            act = builder.icmp_signed("<", ir.Constant(ity, list(range(W))), n_)
            bW = ir.VectorType(ir.IntType(1), W)

            def bsplat(x):
                u = builder.insert_element(ir.Constant(bW, ir.Undefined), x,
                                           ir.Constant(i32, 0))
                return builder.shuffle_vector(u, u, ir.Constant(ir.VectorType(i32, W), [0] * W))

            on_t = builder.and_(act, bsplat(hu))
            on_r = builder.and_(act, bsplat(hp))
            builder.store(builder.select(on_t, mt, mt0), pt, align=8)
            builder.store(builder.select(on_r, mr, mr0), pr, align=8)
            # the lanes not stepped summed as +0 (a sum from +0 is never -0: the same bits)
            zt, et = builder.select(on_t, mt, zero), builder.select(on_t, et, zero)
            zr, er = builder.select(on_r, mr, zero), builder.select(on_r, er, zero)
            F, Mo = F_, M_
            for lane in range(W):
                L_ = ir.Constant(i32, lane)
                F = fa(F, builder.extract_element(zt, L_))
                Mo = fa(Mo, builder.extract_element(zr, L_))
            # the dissipation summed on only where a lane's is not zero (adding a zero leaves
            # the sum's bits): the chain of additions off the common path of sticking cells
            iW = ir.IntType(W)
            nz = builder.or_(builder.fcmp_unordered("!=", et, zero),
                             builder.fcmp_unordered("!=", er, zero))
            slipping = builder.icmp_unsigned("!=", builder.bitcast(nz, iW), ir.Constant(iW, 0))
            before = builder.basic_block
            with builder.if_then(slipping, likely=False):
                e = e_
                for lane in range(W):
                    L_ = ir.Constant(i32, lane)
                    e = fa(e, builder.extract_element(et, L_))
                    e = fa(e, builder.extract_element(er, L_))
                summed = builder.basic_block
            e_phi = builder.phi(e_.type)
            e_phi.add_incoming(e, summed)
            e_phi.add_incoming(e_, before)
            e = e_phi
            # the first cell at its limit: its left boundary, at most the radius
            i32t = ir.IntType(32)
            cttz = cgutils.get_or_insert_function(
                builder.module, ir.FunctionType(i32t, [i32t, ir.IntType(1)]), "llvm.cttz.i32")
            vi64 = ir.VectorType(ir.IntType(64), W)
            sign = ir.Constant(vi64, [0x7FFFFFFFFFFFFFFF] * W)

            def fabs(x):
                return builder.bitcast(builder.and_(builder.bitcast(x, vi64), sign), vty)

            def stick(m, L, on, free, cs):
                hit = builder.and_(on, builder.fcmp_ordered(">=", fabs(m), L))
                bits = builder.zext(builder.bitcast(hit, iW), i32t)
                anyhit = builder.icmp_unsigned("!=", bits, ir.Constant(i32t, 0))
                first = builder.call(cttz, [bits, ir.Constant(ir.IntType(1), 0)])
                first = builder.select(anyhit, first, ir.Constant(i32t, 0))
                b_ = builder.extract_element(bl, first)
                new = builder.select(builder.fcmp_ordered("<", a_, b_), a_, b_)  # min(b, a)
                take = builder.and_(free, anyhit)
                return builder.and_(free, builder.not_(anyhit)), builder.select(take, new, cs)

            ft, ct = stick(mt, Lt, on_t, ft, ct_)
            fm, cm = stick(mr, Lr, on_r, fm, cm_)
            return context.make_tuple(builder, signature.return_type, [e, F, Mo, ft, fm, ct, cm])

        return sig, codegen

    return cells4
