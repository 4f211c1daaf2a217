"""Named test tolerances, each with its reason."""

#: closed form against closed form / the exact transform: only rounding differs
CLOSED_FORM = 1e-10
#: tanh-sinh quadrature at the default rtol 1e-10 against a closed form: the quadrature's own
#: estimate is 1e-10; rounding in singular integrands (flat-punch edges, slope jumps) costs ~10x
QUADRATURE = 1e-9
#: Tabulated profile with 1000 linear-interpolation points sampled from an analytic profile:
#: interpolation error ~ (Δr)² f''/8 relative to f, i.e. ~1e-7 for smooth profiles
TABULATED_1000 = 1e-6

# ---- torsion (issue 3)
#: mpmath reference (30 digits) against contactlab at its default rtol 1e-10: tanh-sinh estimate
#: plus root-finding residual (1e-10) and rounding of g(t) - g(x) near t = x
TORSION_EXACT = 1e-9
#: c/a = 1 - 1e-6: the slip function is ~1e-6 of its scale, so the rounding of g(t) - g(x) (1e-16
#: of g) costs ~1e-10 relative; the twist inverts a function of slope ~1e6
TORSION_NEAR_STICK = 1e-8
#: physics.md table values are printed with 6 significant digits
TABLE_6_DIGITS = 5e-6
#: brute-force Jenkins-element simulation of a hysteresis with N elements (midpoint rule, slip
#: thresholds resolved to ~1/N): discretisation error ~1/N² relative for N = 4000 plus the
#: partially slipped element at the stick-zone edge (~1/N^1.5)
JENKINS_4000 = 2e-5
#: 1000-point linear table of a paraboloid against the paraboloid: the transform g of the linear
#: interpolant differs from x²/R by up to 5e-5 relative (first order in Δr/x near the axis)
TORSION_TABLE_1000 = 1e-4
