"""Named test tolerances, each with its reason."""

#: closed form against closed form / the exact transform: only rounding differs
CLOSED_FORM = 1e-10
#: tanh-sinh quadrature at the default rtol 1e-10 against a closed form: the quadrature's own
#: estimate is 1e-10; rounding in singular integrands (flat-punch edges, slope jumps) costs ~10x
QUADRATURE = 1e-9
#: Tabulated profile with 1000 linear-interpolation points sampled from an analytic profile:
#: interpolation error ~ (Δr)² f''/8 relative to f, i.e. ~1e-7 for smooth profiles
TABULATED_1000 = 1e-6
#: scene example with a tabulated profile (1001 linear-interpolation nodes, Δr = 1 µm, contact
#: radii 47-100 µm) against Hertz: the interpolant overestimates r² by at most Δr²/4, a relative
#: gap error up to (Δr/a)²/4 = 1.2e-4 at the smallest loaded step (measured: 1.9e-4 in the radius)
TABULATED_SCENE = 5e-4
#: CSV/JSON outputs are written with repr(float) (exact); re-solving from a re-read output
#: (e.g. the force, which is recomputed from the radius) moves results by a few ulps
OUTPUT_ROUNDTRIP = 1e-13
#: viscoelastic creep example (SLS, tau = 4.5 s) against the Lee-Radok step solution: the force
#: is ramped in 1 ms instead of stepped (relative error ~ 1e-3 s / tau = 2e-4 right after the
#: step, decaying) plus the foundation's radius discretisation (measured max 6e-5)
VISCO_SCENE = 3e-4
