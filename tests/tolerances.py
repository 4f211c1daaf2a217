"""Named test tolerances, each with its reason."""

#: closed form against closed form / the exact transform: only rounding differs
CLOSED_FORM = 1e-10
#: tanh-sinh quadrature at the default rtol 1e-10 against a closed form: the quadrature's own
#: estimate is 1e-10; rounding in singular integrands (flat-punch edges, slope jumps) costs ~10x
QUADRATURE = 1e-9


def tabulated_linear(spacing_over_radius: float) -> float:
    """Piecewise-linear table of a smooth profile: the interpolant differs from the profile at
    second order, so force and radius errors are <= C (Δr/a)²; measured C = 0.35 (force) and
    2.4 (radius) for paraboloid and n = 4 at 1000 points; 3 leaves margin."""
    return 3.0 * spacing_over_radius**2


#: Cubic-spline table (1000 points) of a smooth profile: interpolation error ~ (Δr/a)^4 ~ 1e-11,
#: transform converged to rounding (per-interval Gauss rule); measured <= 2.2e-12.
TABULATED_CUBIC_1000 = 1e-10

#: an exported sympy formula (lambdified, double precision) against the package's numeric solver
#: at the same point: both are closed forms or converged quadratures in double precision; the
#: budget covers rounding in cancelling forms such as the exact sphere's (a²-R²)/2·artanh(a/R)
SYMBOLIC_VS_SOLVER = 1e-12
#: a plugin profile given only by f(r): slope by Richardson-extrapolated 4th-order finite
#: differences (truncation ~ h⁶ f⁽⁷⁾ with h = 1e-3 of the length scale) then tanh-sinh quadrature
HEIGHT_ONLY_PROFILE = 1e-9
#: the exact sphere's closed forms cancel: ∫_0^a g = (a²-R²)/2·artanh(a/R) + Ra/2 loses a factor
#: ~(R/a)² to rounding (400 at a/R = 0.05), so formula and solver differ by ~1e-13..1e-12
SYMBOLIC_SPHERE = 1e-10
