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
#: radius ~100 µm) against Hertz: the interpolant overestimates r² by at most Δr²/4, i.e. a relative
#: gap error ~ (Δr/a)²/4 = 2.5e-5, which moves force-controlled radius and depth by less than 1e-4
TABULATED_SCENE = 1e-4
#: CSV/JSON outputs are written with repr(float): the round trip is exact up to rounding
OUTPUT_ROUNDTRIP = 1e-15
