"""Named test tolerances, each with its reason."""

#: closed form against closed form / the exact transform: only rounding differs
CLOSED_FORM = 1e-10
#: tanh-sinh quadrature at the default rtol 1e-10 against a closed form: the quadrature's own
#: estimate is 1e-10; rounding in singular integrands (flat-punch edges, slope jumps) costs ~10x
QUADRATURE = 1e-9
#: Tabulated profile with 1000 linear-interpolation points sampled from an analytic profile:
#: interpolation error ~ (Δr)² f''/8 relative to f, i.e. ~1e-7 for smooth profiles
TABULATED_1000 = 1e-6

# ---- hard cases (issue 7)
#: closed form against an independent closed form at extreme parameters (n up to 50, scales
#: 1e-9..10 m, moduli 1e3..1e12 Pa): a few hundred ulps of rounding in powers and gamma ratios
HARD_CLOSED = 1e-12
#: closed-form pressure of a power law against a 30-digit mpmath quadrature: scipy's hyp2f1 and
#: the tanh-sinh fallback near the axis are good to ~1e-13 up to n = 50
HARD_PRESSURE = 2e-12
#: the exact transform of a piecewise-linear table against an independent re-implementation
#: (different summation order; tables up to 10^6 points accumulate ~N·eps·|terms| of rounding)
TABLE_EXACT = 1e-11
#: tabulated profile against scipy.integrate.quad of the definition (quad's own epsrel 1e-12)
TABLE_QUAD = 1e-9
#: rounded-edge punch converging to the flat punch: the relative difference is O(eps) for a
#: rounding zone b..b(1+eps) (force: eps/3, pressure away from the edge: ~eps); allow 2 eps
ROUNDED_PUNCH_FACTOR = 2.0
