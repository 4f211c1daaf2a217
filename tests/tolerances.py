"""Named test tolerances, each with its reason."""

#: closed form against closed form / the exact transform: only rounding differs
CLOSED_FORM = 1e-10
#: tanh-sinh quadrature at the default rtol 1e-10 against a closed form: the quadrature's own
#: estimate is 1e-10; rounding in singular integrands (flat-punch edges, slope jumps) costs ~10x
QUADRATURE = 1e-9
#: Tabulated profile with 1000 linear-interpolation points sampled from an analytic profile:
#: interpolation error ~ (Δr)² f''/8 relative to f, i.e. ~1e-7 for smooth profiles
TABULATED_1000 = 1e-6

# ---- load paths and the MDR foundation (issue 4)
#: foundation (edge spacing, default N = 2000) against the Cattaneo–Mindlin / Mindlin–Deresiewicz
#: closed forms, relative to the loop amplitude: only the one cell holding the stick–slip boundary
#: is lumped, error ~ 1/N² of the local force; measured 2.0e-7 (Hertz), 3.4e-7 (cone), see
#: benchmarks/foundation_accuracy.py. This is the issue's target rtol.
FOUNDATION_CM = 1e-6
#: foundation torsion against the MDR torsion closed form (physics.md §6.4) at the default N,
#: relative to the loop amplitude; measured 6.2e-7 (Hertz). Same target as the tangential loop.
FOUNDATION_TORSION = 1e-6
#: normal force through the foundation: the cells integrate (d - g)_+ exactly, so only rounding
FOUNDATION_NORMAL = 1e-12
#: energy per cycle of a periodic twist after the first cycle: Jenkins states repeat; only the
#: rounding of the elastic increments differs between cycles
ENERGY_DRIFT = 1e-10
