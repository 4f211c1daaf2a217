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
#: JKR pull-off radii: bracketed solve of φ(a) = 3/2 or 1/2 to rtol 1e-14 on closed-form g'; the
#: radius enters through a root of a smooth function, so only rounding (~1e-13) remains
JKR_ROOT = 1e-10
#: JKR pull-off with g' from 4th-order finite differences (profiles without closed-form g'):
#: the force is stationary at the minimum, the radius carries the ~1e-9 derivative error
JKR_FINITE_DIFFERENCE = 1e-7
#: Δγ → 0: JKR differs from Hertz by O(sqrt(Δγ)); at Δγ = 1e-20 J/m² the relative gap is ~1e-9
JKR_SMALL_ADHESION = 1e-7
#: Gauss-Legendre (96 nodes in θ, r = a sinθ) integral of the JKR pressure against F
PRESSURE_INTEGRAL = 1e-9
#: MDR viscoelastic foundation, closed forms that are exact in time (Maxwell relaxation, elastic
#: limits): only the midpoint sum over 2000 elements remains, O((Δx/a)²) ≈ 1e-6
VISCO_SPATIAL = 1e-5
#: SLS creep with 400 steps: second-order time integration, measured 1.5e-5; bound with margin
VISCO_TIME = 5e-4
#: Ting unloading (800 steps, 2000 elements): measured 4e-6 of the peak force
VISCO_TING = 2e-5
#: contact edge interpolated inside one element cell (linear interpolation of a smooth
#: function over Δx): measured ≤ 6e-4 Δx; bound in units of the element spacing
VISCO_EDGE = 1e-2
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
# ---- hard cases of torsion and load paths (issue 7, accuracy2)
#: torque increments of steps of 1e-13..1e-15 of the amplitude: M is a sum over 2000 spring
#: moments (foundation) or a difference M_max - 2M_load (Masing) of O(M) terms, so each value
#: carries rounding of a few to ~sqrt(N) ulps of |M|; measured <= 14 eps |M| (foundation)
TORSION_TINY_STEP = 64 * 2.220446049250313e-16
#: dM/dφ by central differences (h = 1e-4 φ) at rtol 1e-13 against (16/3)G_t c³: truncation
#: ~h² M'''/M' ~ 1e-8, quadrature noise 1e-13·M/(h M') <= 1e-8 for c/a >= 0.3 (M/(φM') < 40)
FD_STIFFNESS = 1e-6
#: Masing branches of a twist history against the monotonic solver at another argument (both
#: converged to rtol 1e-10 on M), cycle work by Simpson's rule with 4000 steps per cycle
MASING_HISTORY = 1e-7
#: energy balance of the foundation: work bracketed per step (trapezoid + slack) and the stored
#: energy Σ m²/(2K) summed over 400 cells: only rounding of O(steps + N) terms remains
WORK_TRAPEZOID = 1e-10

# ---- torsion error estimates (issue 7)
#: Share of (estimate, actual) pairs where the estimate bounds the actual error (issue 7 target).
TORSION_ERR_HONEST_FRACTION = 0.95
#: Estimates should exceed the actual error by at most this factor (over this floor) in at least
#: TORSION_ERR_HONEST_FRACTION of the pairs, and by at most TORSION_ERR_MAX_OVER_ALL in every pair:
#: tanh-sinh's "change between the last two levels" is conservative by design (the error squares
#: per level; measured worst 6e4 where a 1e-10 estimate meets an actual error of 1e-15).
TORSION_ERR_MAX_OVER = 1e3
TORSION_ERR_MAX_OVER_ALL = 1e5
TORSION_ERR_FLOOR = 1e-15
#: sin(2πk/n) evaluated directly against a sampled sinusoid (one period computed, then tiled;
#: exact zeros at half periods): the argument 2πk/n carries a rounding error ~k ulp, so beyond
#: the first period the two differ by a few ulp of the amplitude; 8 ulp leaves margin
SINE_TILING = 8 * 2.220446049250313e-16

# ---- fretting loops, maps and wear (issue 15)
#: loop energy W = 4 D_load (Iwan form, closed-form ∫g and ∫g² of power laws) against the Masing
#: integral of the closed-form virgin curve: both closed forms; only rounding in the cancelling
#: difference 8∫Q - 4δQ* (a factor ~10 at A ~ 0.05)
FRETTING_CLOSED = 1e-9
#: trapezoid area of the returned loop (n points per branch) against W: error ~ W'' δ²/(12 n²);
#: measured 2e-6 at n = 2000
LOOP_TRAPEZOID = 1e-5
#: torsional boundary (regula falsi in c/a, 3 refinements after a 48-point grid) against the
#: closed form φ(c) of the Lubkin problem: stick_ratio is one direct evaluation (quadrature)
TORSION_BOUNDARY = 1e-8
#: torsional energy/torque-ratio boundary: root of the criterion in c/a after 3 regula-falsi steps;
#: measured criterion residual <= 1e-6
TORSION_BOUNDARY_ROOT = 1e-5

# ---- adversarial review (issue 11)
#: surface displacement within 1000 rounding steps outside the contact edge against a 40-digit
#: reference: closed-form route (atan2 angle, hypergeometric connection formula near z = 1),
#: only a few roundings remain (measured 4.4e-16); the issue's target
EDGE_DISPLACEMENT = 1e-12

# ---- speed (issue 13)
#: a history whose amplitudes differ by rounding only (A sin(2πk/n) over 10^4 steps, ~1e-12 of A)
#: against the same history with every distinct argument solved: merged arguments (closer than
#: 1e-11 of the largest) move along the loading curve with its tangent stiffness, so only the
#: second-order term and rounding remain; relative to the torque amplitude
MERGED_ARGUMENTS = 1e-12
#: the scalar fast path of normal() against the array route on the same input: the same
#: formulas in plain floats (libm) and in numpy (SIMD), and root solves to the same bracket
#: tolerance 1e-15: a few ulps apart
SCALAR_VS_ARRAY = 1e-14

# ---- contact law (issue 14)
#: ContactLaw (master curves + vectorised Masing) against Contact.twist_history/shift_history:
#: the histories' own stick-radius root and quadratures are good to ~1e-12; margin for the
#: Masing recursion adding branch values over many reversals
LAW_HISTORY = 1e-9
#: torsion master curves (certified piecewise polynomials) against the exact solvers at points
#: that are not interpolation nodes: certified to 1e-13 absolute at construction
MASTER_CURVE = 1e-12
#: loop area by the trapezoid rule over 4000 steps per cycle against the law's dissipation:
#: O(h²) with the curvature of the branches, measured ~1e-7
LOOP_AREA = 1e-5
