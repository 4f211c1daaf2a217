"""The time loop of the spring foundation (:class:`~contactlab.foundation.Winkler`): the load
path's steps through its tangential and torsional Jenkins elements.

The normal problem (non-adhesive) is path independent: it is solved for every step before the
loop (:func:`contactlab.foundation.base.path_normal_series`). Then one loop over the time steps
advances the spring families, every operation vectorised over the springs. Displacement/twist
controlled steps are explicit; force/torque controlled steps are solved exactly (the element sum
is piecewise linear and monotone in the increment); a target at or beyond full sliding gives
gross sliding (flagged, not an error). Runs of steps at a held normal load and a monotone control
are advanced in closed form (:func:`monotone_block`); with the numba backend, runs of steps with a
new depth each go through one compiled call (:mod:`contactlab.foundation._compiled`).
"""
from __future__ import annotations

import itertools
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from . import _compiled

__all__ = ["time_loop", "monotone_block", "snapshot", "snapshot_shear", "abel_traction",
           "memory", "FAMILY_SERIES", "run_writes"]

#: float64 values held per step and per spring at the peak of a run (tracemalloc, rounded up:
#: 42 per step for a sinusoid, 35 per spring, 8 per spring and stored snapshot)
_PER_STEP, _PER_SPRING, _PER_SNAPSHOT_SPRING = 48, 48, 8


def memory(n_steps: int, n_springs: int, n_snapshots: int = 0) -> float:
    """Estimated peak memory of a spring-foundation run, bytes (checked against the memory
    budget before anything is allocated; see :func:`contactlab.set_memory_budget`)."""
    return 8.0 * (_PER_STEP * float(n_steps) + _PER_SPRING * float(n_springs)
                  + _PER_SNAPSHOT_SPRING * float(n_springs) * n_snapshots)


#: steps converted to plain floats at a time by the step-by-step loop (bounded temporaries)
_CHUNK = 4096
#: steps per window of the fused compiled runs (edge data a window at a time; larger than
#: ``_CHUNK``: each window costs ~60 numpy calls, ~25 ns per step at 4096 steps)
_FUSED_WINDOW = 1 << 15
#: steps per window of the direction-reversal search (bounded temporaries)
_TURN_WINDOW = 1 << 16
#: shortest run of steps advanced in closed form (shorter runs: step by step, which is cheaper)
_MIN_BLOCK = 8

#: the series of each spring family, written at every step by the time loop
FAMILY_SERIES = {"tangential": ("displacement", "tangential_force"),
                 "torsion": ("twist", "torque")}


def run_writes(needs: tuple, outputs: tuple) -> tuple:
    """The series :func:`time_loop` writes at every step (each step's fused, closed-form or
    step-by-step route): those need no zero fill. The others (a family the path does not
    load, ``gross_sliding`` which steps OR into) start from zeros."""
    out = ["dissipated_energy"]
    if "stick_radius" in outputs:      # the loop skips the stick search otherwise
        out.append("stick_radius")
    for fam in needs:
        out += FAMILY_SERIES[fam]
    return tuple(out)


@dataclass(eq=False)
class _Channel:
    """One spring family in the time loop: its elements, stiffness, slip limit (the name of the
    state's array), its position and force series, and what the loop carries between steps."""

    m: np.ndarray              # element forces (N) or torques (N·m): the run's state
    K: np.ndarray              # full stiffness per cell
    invK: np.ndarray
    L: str                     # "L_tan" or "L_tor": the slip-limit array of the spring state
    pos: str                   # the position series: "displacement" or "twist"
    frc: str                   # the force series: "tangential_force" or "torque"
    res: dict = field(repr=False)
    Keff: np.ndarray = field(init=False)    # stiffness of this step (times the contact weight)
    iKeff: np.ndarray = field(init=False)
    ctrl: str = field(init=False)           # the controlled quantity (pos or frc)
    x: float = 0.0                          # position now
    dir: float = 1.0                        # sign of the last non-zero increment
    release: bool = False                   # the depth fell: clip to the new limits
    out_pos: np.ndarray = field(init=False)
    out_frc: np.ndarray = field(init=False)
    fused: Any = None                       # the compiled fused step's per-family arguments

    def __post_init__(self) -> None:
        n = self.m.size
        self.Keff, self.iKeff = np.zeros(n), np.zeros(n)
        self.ctrl = self.pos
        self.out_pos, self.out_frc = self.res[self.pos], self.res[self.frc]


def snapshot(fnd: Any, st: Any, res: dict, i: int) -> dict:
    """The spring state at step ``i``: ``depth``, ``radius`` and, with a foundation, the cell
    midpoints ``x``, the normal spring forces (N) and, with a state, the tangential/torsional
    element forces (N, N·m) and the 3D tractions of :func:`snapshot_shear` (Pa). The 3D pressure
    is the normal solution's: the caller adds it (``"pressure"``)."""
    d, a = float(res["depth"][i]), float(res["radius"][i])
    snap: dict[str, Any] = {"depth": d, "radius": a}
    if fnd is not None:
        x = fnd.positions
        snap["x"] = x.copy()
        S = np.maximum(d * fnd.w - fnd.dG, 0.0)
        S[fnd.bl >= a] = 0.0
        if st is not None:
            S = st.S.copy()
            snap["tangential"] = None if st.tangential is None else st.tangential.copy()
            snap["torsion"] = None if st.torsion is None else st.torsion.copy()
            snap.update(snapshot_shear(fnd, st, x))
        snap["normal"] = 2.0 * fnd.moduli.normal * S
    return snap


def _turns(v0: float, v: np.ndarray) -> np.ndarray:
    """Indices j where the increment v[j] - v[j-1] reverses the direction of the last non-zero
    increment (v[-1] := v0): the starts of new monotone runs (a window of steps at a time:
    bounded temporaries)."""
    out = [np.zeros(0, np.int64)]
    last, prev = 0.0, v0
    for c0 in range(0, v.size, _TURN_WINDOW):
        w = v[c0:c0 + _TURN_WINDOW]
        sg = np.sign(np.diff(w, prepend=prev))
        prev = w[-1]
        nnz = np.count_nonzero(sg)
        if nnz == 0:
            continue
        if nnz == sg.size:  # every step moves (a gait): no index gather
            s = sg
            flips = np.flatnonzero(s[1:] != s[:-1]) + 1
            first = 0
        else:
            nz = np.flatnonzero(sg)
            s = sg[nz]
            flips = nz[1:][s[1:] != s[:-1]]
            first = int(nz[0])
        if last != 0.0 and s[0] != last:
            flips = np.concatenate(([first], flips))
        out.append(flips + c0)
        last = s[-1]
    return np.concatenate(out)


def _run_edges(flags: np.ndarray) -> np.ndarray:
    """Starts and ends (one past) of the runs of True in ``flags``."""
    f = flags.view(np.int8)
    return np.flatnonzero(np.diff(f, prepend=np.int8(0), append=np.int8(0)))


def _next(sorted_idx: np.ndarray, j: int, default: int) -> int:
    k = int(np.searchsorted(sorted_idx, j, side="right"))
    return int(sorted_idx[k]) if k < sorted_idx.size else default


def _set_keff(ch: "_Channel", weight: np.ndarray) -> None:
    """Stiffness of the elements for this step: full stiffness times the contact weight."""
    np.multiply(ch.K, weight, out=ch.Keff)
    # 1/K_eff where in contact; elsewhere the slip is 0 and any finite value will do
    np.divide(ch.invK, weight, out=ch.iKeff, where=weight > 0)


def _fused_step(fnd: Any, chans: list) -> Any:
    """The compiled fused step (numba backend) for one spring family with friction, else None;
    its arguments per family: the limit's cell integrals and friction factor."""
    if len(chans) != 1 or fnd.friction is None:
        return None
    kernel = _compiled.fused_step()
    if kernel is None:
        return None
    tor = chans[0].L == "L_tor"
    chans[0].fused = ((fnd.X1, fnd.dH, fnd._c_tor) if tor else (fnd.w, fnd.dG, fnd._c_tan))
    return kernel


def _fused_run(kernel, fnd, st, ch, i0, d, a, k, S_edge, T_edge, target, state, out_W,
               out_stick):
    """Steps ``i0 ...`` (each with a new depth, a prescribed displacement/twist) in one compiled
    call (the same element arithmetic as ``set_normal`` + stiffness weighting + ``jenkins`` + sum
    + stick radius per step), then the normal state and slip limits of the last step."""
    X1, dH, c = ch.fused
    n = d.size
    sl = slice(i0, i0 + n)
    stick = out_stick[sl] if out_stick is not None else np.empty(n)
    W = out_W[sl]
    sgn, lo = kernel(d, a, k, S_edge, T_edge, target, st.depth, st.k, ch.x, ch.release, c,
                     fnd.w, fnd.dG, X1, dH, ch.K, ch.invK, ch.iKeff, st.S, ch.m,
                     fnd.bl, state["W"], ch.out_frc[sl], W, stick, out_stick is not None,
                     _compiled.FUSED_BLOCK, _compiled.FUSED_BLOCK_FROM)
    ch.iKeff[:lo] = ch.invK[:lo]   # the bulk of the last step (weight 1)
    # the normal state and slip limits of the last step (what set_normal computes), written
    # into the run's arrays: no full-length temporaries (10^6 springs: 4 fresh 8 MB arrays)
    dl, kl = float(d[-1]), int(k[-1])
    S = st.S   # read by the kernel at the first step only
    np.multiply(fnd.w, dl, out=S)
    S -= fnd.dG
    S[kl + 1:] = 0.0
    S[kl] = S_edge[-1]
    name = ch.L
    L, nL = getattr(st, name), getattr(st, "n" + name)
    if name == "L_tor":
        np.multiply(X1, dl, out=L)
        L -= dH
        L[kl + 1:] = 0.0
        L[kl] = T_edge[-1]
        L *= c
    else:
        np.multiply(S, c, out=L)
    np.negative(L, out=nL)
    st.depth, st.radius, st.k = dl, float(a[-1]), kl
    state.update(first=False, keff_is_frac=False, W=float(W[-1]))
    if sgn != 0.0:
        ch.dir = sgn
    ch.release = False
    ch.x = float(target[-1])
    dst = ch.out_pos[sl]
    if dst.ctypes.data != target.ctypes.data or dst.strides != target.strides:
        dst[...] = target      # (the time loop passes the series' own view: nothing to copy)


def time_loop(fnd: Any, leaves: Any, normal: list, res: dict, snaps: set, snapshot_data: dict,
              want_stick: bool, progress: Any = None, strategy: str = "segments",
              track: dict | None = None) -> None:
    """The time loop of the spring foundation ``fnd`` (a :class:`~contactlab.foundation.Winkler`)
    over the leaf segments ``leaves`` with their normal states ``normal`` (per leaf: views of the
    ``depth`` and ``radius`` series), writing the series ``res`` in place.

    ``strategy="segments"``: runs of steps with a held normal load and a monotone control are
    advanced in closed form (:func:`monotone_block`), other steps one by one; ``"steps"``: every
    step one by one (same results up to rounding). ``progress(n)`` is called with the steps of
    each leaf when done; ``track["done"]`` counts the steps complete (the partial result of a
    failure)."""
    st = fnd.new_state()
    n = fnd.n_springs
    chans = []
    if st.tangential is not None:
        chans.append(_Channel(st.tangential, fnd.K_tan, fnd.invK_tan, "L_tan", "displacement",
                              "tangential_force", res))
    if st.torsion is not None:
        chans.append(_Channel(st.torsion, fnd.K_tor, fnd.invK_tor, "L_tor", "twist", "torque",
                              res))
    stick_ch = chans[0] if chans else None
    loop_controls = tuple(q for ch in chans for q in (ch.pos, ch.frc))
    tmp = np.empty(n)
    cur = dict.fromkeys(("depth", "force", "displacement", "tangential_force", "twist",
                         "torque"), 0.0)
    out_W, out_stick, out_gross = res["dissipated_energy"], res["stick_radius"], res["gross_sliding"]
    snap_idx = np.array(sorted(snaps), int)
    state = track if track is not None else {}      # "done": steps complete (partial results)
    state.update(W=0.0, first=True, keff_is_frac=False, done=0)
    fused = _fused_step(fnd, chans)

    def step(i, d, a, k_edge, S_edge, T_edge, targets):
        W = state["W"]
        if state["first"] or d != st.depth or a != st.radius:
            state["first"] = False
            release = d < st.depth  # slip limits only shrink when the depth decreases
            weight = fnd.set_normal(st, d, a, k_edge, S_edge, T_edge)
            state["keff_is_frac"] = weight is None
            if weight is None:
                weight = fnd.fraction(a)
            for ch in chans:
                _set_keff(ch, weight)
                # springs beyond their new limit slide back to it (a prescribed displacement
                # step does this in the same clip as its increment)
                if release and ch.ctrl != ch.pos:
                    W += fnd.jenkins(ch.m, ch.Keff, ch.iKeff, getattr(st, ch.L),
                                     getattr(st, "n" + ch.L), 0.0, tmp)
                elif release:
                    ch.release = True
        elif not state["keff_is_frac"]:
            frac = fnd.fraction(a)
            for ch in chans:
                _set_keff(ch, frac)
            state["keff_is_frac"] = True
        for ch, target in zip(chans, targets):
            m = ch.m
            L = getattr(st, ch.L)
            if ch.ctrl == ch.pos:
                inc = target - ch.x
            else:
                inc, gross = fnd.solve(m, ch.Keff, L, target)
                out_gross[i] |= gross
            if inc != 0.0 or ch.release:
                if inc != 0.0:
                    ch.dir = 1.0 if inc > 0 else -1.0
                W += fnd.jenkins(m, ch.Keff, ch.iKeff, L, getattr(st, "n" + ch.L), inc,
                                 tmp)
                ch.x += inc
                ch.release = False
            if ch.ctrl == ch.pos:
                ch.x = float(target)  # no round-off drift of a prescribed position
            ch.out_pos[i] = ch.x
            ch.out_frc[i] = m.sum()
        out_W[i] = W
        state["W"] = W
        if want_stick:
            out_stick[i] = (fnd.stick_radius(stick_ch.m, getattr(st, stick_ch.L), fnd.bl, a)
                            if stick_ch is not None else a)
        state["done"] = i + 1

    def block(i0, i1, values):
        if not state["keff_is_frac"]:
            frac = fnd.fraction(st.radius)
            for ch in chans:
                _set_keff(ch, frac)
            state["keff_is_frac"] = True
        sl = slice(i0, i1)
        Wblock = np.zeros(i1 - i0)
        for ch, v in zip(chans, values):
            m = ch.m
            L = getattr(st, ch.L)
            ref = ch.x if ch.ctrl == ch.pos else float(m.sum())
            nzv = v[v != ref]
            sgn = ch.dir if nzv.size == 0 else (1.0 if nzv[0] > ref else -1.0)
            ch.dir = sgn
            want = want_stick and ch is stick_ch
            if ch.ctrl == ch.pos:
                out = monotone_block(m, ch.Keff, L, fnd.bl, st.radius, sgn, du=sgn * (v - ref),
                                     want_stick=want)
                ch.out_pos[sl] = v
                ch.x = float(v[-1])
            else:
                out = monotone_block(m, ch.Keff, L, fnd.bl, st.radius, sgn, target=v,
                                     want_stick=want)
                ch.out_pos[sl] = ch.x + sgn * out["x"]
                ch.x = float(ch.out_pos[i1 - 1])
                out_gross[sl] |= out["gross"]
            ch.out_frc[sl] = out["force"]
            Wblock += out["dissipation"]
            if want:
                out_stick[sl] = out["stick"]
        out_W[sl] = state["W"] + Wblock
        state["W"] += float(Wblock[-1])
        if want_stick and stick_ch is None:
            out_stick[sl] = st.radius
        state["done"] = i1

    base = 0
    for leaf, nrm in zip(leaves, normal):
        if base:
            cur["depth"], cur["force"] = float(res["depth"][base - 1]), float(res["force"][base - 1])
        # the spring families' controls only (the normal solve read the others)
        _, vals = leaf.values_of(cur, loop_controls, time=False)
        nsteps = leaf.n_steps
        d_arr, a_arr = nrm["depth"], nrm["radius"]
        d0, a0 = st.depth, st.radius
        changed = np.empty(nsteps, bool)
        changed[0] = d_arr[0] != d0 or a_arr[0] != a0 or state["first"]
        np.not_equal(d_arr[1:], d_arr[:-1], out=changed[1:])
        changed[1:] |= a_arr[1:] != a_arr[:-1]
        breaks = [np.array([0, nsteps])]
        vs = []
        for ch in chans:
            pos, frc = ch.pos, ch.frc
            if pos in vals or frc in vals:
                ch.ctrl = pos if pos in vals else frc
                v = vals[ch.ctrl]
                if ch.ctrl == pos:   # a prescribed position is its own series: the loop
                    # reads the targets from it (writeable, unlike a table's own columns,
                    # which the compiled run would take as another argument type)
                    out = ch.out_pos[base:base + nsteps]
                    out[:] = v
                    v = out
            else:
                v = np.full(nsteps, cur[ch.ctrl])
            vs.append(v)
            breaks.append(_turns(cur[ch.ctrl], v))
        del vals
        # runs of steps whose normal state changes are run step by step: their ends are breaks
        all_changed = bool(changed.all())   # e.g. a gait: no run edges, no gather
        breaks += [np.array([0, nsteps]) if all_changed else _run_edges(changed),
                   snap_idx - base + 1]
        brk = np.unique(np.concatenate(breaks))
        del breaks
        brk = brk[(brk >= 0) & (brk <= nsteps)].tolist()
        fusing = fused is not None and chans[0].ctrl == chans[0].pos
        tor_edge = bool(chans) and chans[0].L == "L_tor"

        # the helpers below run only within this iteration: the loop's values are bound as
        # keyword defaults (the same objects the closures would read) so that no helper can
        # see a later iteration's values
        def edges(c0, c1, *, all_changed=all_changed, changed=changed, d_arr=d_arr, a_arr=a_arr):
            """Edge cell data of steps c0..c1-1, computed where the normal state changes
            (zeros elsewhere: step() does not read them there)."""
            if all_changed or changed[c0:c1].all():    # no gather and scatter
                edc = fnd.edge_data(d_arr[c0:c1], a_arr[c0:c1])
                return edc["k"], edc["S"], edc.get("T")
            ci = np.flatnonzero(changed[c0:c1])
            ek, eS = np.zeros(c1 - c0, np.int64), np.zeros(c1 - c0)
            eT = np.zeros(c1 - c0) if "torsion" in fnd.needs else None
            if ci.size:
                edc = fnd.edge_data(d_arr[c0:c1][ci], a_arr[c0:c1][ci])
                ek[ci], eS[ci] = edc["k"], edc["S"]
                if eT is not None:
                    eT[ci] = edc["T"]
            return ek, eS, eT

        def one_by_one(j0, j1, *, d_arr=d_arr, a_arr=a_arr, vs=vs, base=base, edges=edges):
            for c0 in range(j0, j1, _CHUNK):   # plain floats, converted a chunk at a time
                c1 = min(c0 + _CHUNK, j1)
                dl, al = d_arr[c0:c1].tolist(), a_arr[c0:c1].tolist()
                ek, eS, eT = edges(c0, c1)
                ek, eS = ek.tolist(), eS.tolist()
                eT = eT.tolist() if eT is not None else [None] * (c1 - c0)
                vl = [v[c0:c1].tolist() for v in vs]
                for o in range(c1 - c0):
                    step(base + c0 + o, dl[o], al[o], ek[o], eS[o], eT[o], [v[o] for v in vl])

        def steps(j0, j1, *, fusing=fusing, d_arr=d_arr, a_arr=a_arr, d0=d0, tor_edge=tor_edge,
                  base=base, vs=vs, edges=edges, one_by_one=one_by_one):
            if not fusing:
                one_by_one(j0, j1)
                return
            for c0 in range(j0, j1, _FUSED_WINDOW):   # edge data a window at a time
                c1 = min(c0 + _FUSED_WINDOW, j1)
                prev = d_arr[c0 - 1] if c0 > 0 else d0
                # steps whose depth equals the one before (run step by step)
                same = np.flatnonzero(d_arr[c0 + 1:c1] == d_arr[c0:c1 - 1])
                same += 1
                if d_arr[c0] == prev:
                    same = np.concatenate(([0], same))
                ek, eS, eT = edges(c0, c1)
                eT = eT if tor_edge else eS
                j = 0
                while j < c1 - c0:   # runs of steps with a new depth each: one compiled call
                    r = _next(same, j - 1, c1 - c0)
                    if r > j:
                        _fused_run(fused, fnd, st, chans[0], base + c0 + j, d_arr[c0 + j:c0 + r],
                                   a_arr[c0 + j:c0 + r], ek[j:r], eS[j:r], eT[j:r],
                                   vs[0][c0 + j:c0 + r], state, out_W,
                                   out_stick if want_stick else None)
                        state["done"] = base + c0 + r
                        j = r
                    else:
                        one_by_one(c0 + j, c0 + j + 1)
                        j += 1

        pending = None   # first step of a stretch of step-by-step intervals not yet run
        for j0, j1 in itertools.pairwise(brk):
            if strategy == "segments" and j1 - j0 >= _MIN_BLOCK and not changed[j0]:
                if pending is not None:
                    steps(pending, j0)
                    pending = None
                block(base + j0, base + j1, [v[j0:j1] for v in vs])
            elif pending is None:
                pending = j0
            if base + j1 - 1 in snaps:
                if pending is not None:
                    steps(pending, j1)
                    pending = None
                snapshot_data[base + j1 - 1] = snapshot(fnd, st, res, base + j1 - 1)
        if pending is not None:
            steps(pending, nsteps)
        base += nsteps
        for ch in chans:
            cur[ch.pos], cur[ch.frc] = ch.out_pos[base - 1], ch.out_frc[base - 1]
        if progress is not None:
            progress(nsteps)


def monotone_block(m: np.ndarray, K: np.ndarray, L: np.ndarray, bl: np.ndarray, radius: float,
                   s: float, du: np.ndarray | None = None, target: np.ndarray | None = None,
                   want_stick: bool = True) -> dict[str, np.ndarray]:
    """Advance Jenkins elements over a run of steps with fixed ``K``, ``L`` and monotone input.

    Exact closed form of ``T`` successive updates ``m ← clip(m + K Δ, -L, L)`` when every
    increment has the sign ``s``: element ``i`` sticks until the accumulated displacement
    ``x`` reaches its room ``r_i = (L_i - s m_i)/K_i`` and slides after that. With the rooms
    sorted, the force ``Σ clip(m + s K x, -L, L)``, the dissipation ``Σ_{r_i < x} L_i (x - r_i)``
    and the stick radius (first element, from the centre, whose room is reached) follow from
    cumulative sums and a binary search per step: ``O(N log N + T log N)`` instead of ``O(N T)``.

    Parameters
    ----------
    m : ndarray
        Element forces, updated in place to the state after the last step.
    K, L : ndarray
        Stiffness and slip limit of each element (``K = 0``: out of contact).
    bl : ndarray
        Left cell boundaries (for the stick radius); ``radius`` is the contact radius.
    s : {+1, -1}
        Direction of the run.
    du : ndarray, optional
        Accumulated displacement ``x_t >= 0`` (``s``-directed) at each step of the run, or
    target : ndarray, optional
        Total force at each step (force control); ``x_t`` is solved exactly.

    Returns
    -------
    dict
        ``force`` (total per step), ``dissipation`` (cumulative within the run), ``x``
        (accumulated displacement), ``gross`` (target at/over full sliding) and, if asked,
        ``stick``.
    """
    act = K > 0
    sm = s * m
    F0 = float(m.sum())
    Ka = K[act]
    room = (L[act] - sm[act]) / Ka
    order = np.argsort(room, kind="stable")
    r = room[order]
    k = Ka[order]
    lim = L[act][order]
    fin = np.isfinite(r)
    kr = np.where(fin, k * r, 0.0)
    ckr = np.concatenate(([0.0], np.cumsum(kr)))
    ck = np.concatenate(([0.0], np.cumsum(k)))
    Ktot = ck[-1]
    gross = None
    if target is not None:
        G = s * (np.asarray(target, float) - F0)
        gb = ckr[:-1] + np.where(fin, r, np.inf) * (Ktot - ck[:-1])
        j = np.searchsorted(gb, G, side="left")
        over = j >= r.size
        jj = np.minimum(j, max(r.size - 1, 0))
        slope = Ktot - ck[jj]
        with np.errstate(divide="ignore", invalid="ignore"):
            x = np.where(over, r[-1] if r.size else 0.0, (G - ckr[jj]) / slope)
        x = np.maximum(x, 0.0)
        gross = over
    else:
        x = np.asarray(du, float)
    idx = np.searchsorted(r, x, side="right")  # elements whose room is used up
    gain = ckr[idx] + x * (Ktot - ck[idx])
    force = F0 + s * gain
    if gross is not None:
        force = np.where(gross, s * float(L[act].sum()), force)
    lr = np.where(fin, lim * r, 0.0)
    cl = np.concatenate(([0.0], np.cumsum(np.where(fin, lim, 0.0))))
    clr = np.concatenate(([0.0], np.cumsum(lr)))
    diss = x * cl[idx] - clr[idx]
    out = {"force": force, "dissipation": np.maximum(diss, 0.0), "x": x,
           "gross": np.zeros(x.size, bool) if gross is None else gross}
    if want_stick:
        rs = np.zeros(m.size)
        rs[act] = room
        pm = np.minimum.accumulate(rs)
        first = np.searchsorted(-pm, -x, side="left")
        out["stick"] = np.where(first < m.size, bl[np.minimum(first, m.size - 1)], radius)
    xe = float(x[-1])
    np.minimum(sm + K * xe, L, out=sm)
    np.multiply(sm, s, out=m)
    return out


def abel_traction(x: np.ndarray, q: np.ndarray, a: float, q_edge: float,
                  r: np.ndarray) -> np.ndarray:
    """``-(1/π) ∫_r^a q'(x)/sqrt(x² - r²) dx + q_edge/(π sqrt(a² - r²))`` for ``r < a``.

    ``q`` is the piecewise-linear interpolant through ``(x_i, q_i)``, constant on ``[0, x_0]`` and
    linear from the last node to ``(a, q_edge)``; ``q_edge`` is the value at ``a⁻`` (a jump to 0
    at ``a`` gives the edge term). MDR inverse of a line load [H1; theory §3]. Returns 0 for
    ``r >= a``.
    """
    r = np.asarray(r, float)
    xn = np.concatenate((x, [a]))
    qn = np.concatenate((q, [q_edge]))
    x0, x1 = xn[:-1], xn[1:]
    slope = np.diff(qn) / np.diff(xn)
    rr = np.maximum(r, 1e-300)[..., None]
    lo = np.maximum(x0, rr)
    hi = np.maximum(x1, rr)
    with np.errstate(divide="ignore", invalid="ignore"):
        seg = np.arccosh(hi / rr) - np.arccosh(lo / rr)
        tau = -(slope * seg).sum(axis=-1) / np.pi
        tau = tau + np.where(r < a, q_edge / (np.pi * np.sqrt(np.maximum(a * a - r * r, 0))), 0.0)
    return np.where(r < a, tau, 0.0)


def snapshot_shear(fnd: Any, st: Any, r: np.ndarray) -> dict[str, np.ndarray]:
    """3D tractions from the spring states at radii ``r`` (MDR inverse of the line loads).

    Tangential: line load ``q_x = f_i/(2 w_i)`` (both sides lumped in ``f_i``),
    ``τ_x = -(1/π)∫ q_x'/sqrt(x²-r²)``. Torsion: cell rotation ``ψ_i = m_i/K_i`` (``u_y = xψ``),
    ``τ = (4G_t r/π)[-∫ ψ'/sqrt(x²-r²) + ψ(a)/sqrt(a²-r²)]`` (theory §8, item 1).
    A cell at its slip limit next to the edge means ``u(a) = 0``; otherwise the edge cell's value
    holds up to ``a`` (no slip).
    """
    a = st.radius
    inside = fnd.bl < a
    x = fnd.positions[inside]
    out: dict[str, np.ndarray] = {}
    if x.size == 0:
        return out
    last = int(np.flatnonzero(inside)[-1])
    if st.tangential is not None:
        q = st.tangential[inside] / (2.0 * fnd.w[inside])
        slipping = np.abs(st.tangential[last]) >= st.L_tan[last]
        out["shear_tangential"] = abel_traction(x, q, a, 0.0 if slipping else q[-1], r)
    if st.torsion is not None:
        psi = st.torsion[inside] / fnd.K_tor[inside]
        slipping = np.abs(st.torsion[last]) >= st.L_tor[last]
        out["shear_torsion"] = 4.0 * fnd.moduli.torsional * np.asarray(r, float) * abel_traction(
            x, psi, a, 0.0 if slipping else psi[-1], r)
    return out
