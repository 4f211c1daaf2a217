"""Measured (tabulated) profiles.

``interpolation="linear"`` (default) is the piecewise-linear interpolant of the table. Its MDR
transform is exact, a sum of truncated-cone transforms (theory §2):

    g(x) = x [ s_k π/2 - Σ_{j=1..k} (s_j - s_{j-1}) asin(r_j/x) ],   r_k <= x < r_{k+1}

(the node r_k = x itself is included, so g is continuous at the nodes)

and ``∫_0^a g = Σ_i s_i ∫_{r_i}^{min(r_{i+1},a)} sqrt(a²-r²) dr`` in closed form. Summed node by
node, each evaluation costs O(N) for N table points; tables of at least 4096
slope-jump nodes (``_far.FAR_FIELD_FROM``) sum the far nodes by Taylor series over a dyadic
tree of node blocks set up once (``_far``: O(log N) per point, agreeing with the node-by-node
sums to rounding), so tables of 10^6 points work and batches of loads on them are cheap.

``interpolation="cubic"`` uses a C² cubic spline (scipy ``CubicSpline``, not-a-knot ends). Its
transform is set up once as node sums: the spline's slope written as jumps at the nodes, each
node contributing elementary terms (``Tabulated._cubic_sums``), O(nodes below x) per point (on
the tree of ``_far_cols`` for tables of at least 4096 jump nodes: O(log N)).
Pieces between nearly coincident nodes (random spacing: 1e-15 of the radius apart at 10^6
points), whose cubic coefficient is data rounding divided by h³, are kept local: integrated over
the piece only instead of extrapolated over the table, where their huge jumps would cancel
(``Tabulated._setup_cubic_jumps``). Points whose sums still carry a rounding estimate above
:data:`CUBIC_SUM_RTOL` fall back to a Gauss-Legendre rule per table interval in θ (12 nodes,
error estimate from 8). Every sum over the nodes is grouped in fixed blocks
(:mod:`contactlab.numeric.fixed_sums`), so a point's value does not depend on the other points
of its call.

The two interpolants of the same table differ at the level of the linear interpolation error:
for a table sampled from a smooth profile the linear one is off by ~0.35 (Δr/a)² in force and
~2.4 (Δr/a)² in contact radius, the cubic one by ~1e-12 at 1000 points
(tests/unit/profiles/test_transform.py).

Heights are taken relative to the table's first value (the datum of a measurement is arbitrary),
and a table starting at ``r0 > 0`` is extended flat to the axis. Contact radii must stay inside the
table (``max_radius`` = last radius).

Layout (one module per job, all private; the public class is :class:`Tabulated`):
``_table`` reads and checks the table and implements the Profile hooks by dispatching to
``_linear`` (the linear interpolant's transform), ``_cubic`` (the spline's transform) and
``_solve`` (contact-radius solves); ``_base`` holds the shared attributes and node integrals;
``_far`` the tree of a large linear table's node sums, ``_far_cols`` the same tree for the
cubic spline's coefficient columns.
"""
from ._cubic import CUBIC_LOCAL_RATIO, CUBIC_SUM_RTOL
from ._table import BREAKPOINT_LIMIT, Tabulated

__all__ = ["Tabulated", "BREAKPOINT_LIMIT", "CUBIC_SUM_RTOL", "CUBIC_LOCAL_RATIO"]
