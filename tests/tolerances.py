"""Named test tolerances, each with its reason."""

#: closed form against closed form / the exact transform: only rounding differs
CLOSED_FORM = 1e-10
#: tanh-sinh quadrature at the default rtol 1e-10 against a closed form: the quadrature's own
#: estimate is 1e-10; rounding in singular integrands (flat-punch edges, slope jumps) costs ~10x
QUADRATURE = 1e-9

# ---- noisy measured tables (issue 12): smoothing="auto" against the noise-free closed form
#: force at a = half the table, noise up to 2 % of the largest height, 200-2000 points
#: (measured worst 6.1e-2 on 200-point n = 4 tables at 2 % noise; the smoothing's own
#: error estimate is the sharper statement and is tested for coverage)
NOISY_TABLE_FORCE = 0.1
#: contact radius, same tables (measured worst 2.5e-2)
NOISY_TABLE_RADIUS = 0.05
#: our banded Reinsch smoother against scipy's make_smoothing_spline, relative to max |f|: two
#: solvers of the same banded system; rounding grows with λ times the condition number
#: (measured 1.7e-12 at λ = 1e-4)
SMOOTHER_SECOND_METHOD = 1e-10
#: slopes of a table integrated from non-decreasing slopes (cumsum, then differences): rounding
#: of heights ~100 times larger than one step's rise (measured 5e-15 relative)
INTEGRATED_SLOPES = 1e-13
#: hip-cup study (examples/hip_cup.toml): contact radius of the smoothed noisy table under the
#: gait load against Hertz; the r^4 wear term (< 1e-3), the smoothing (~1e-4) and the foundation
#: with 400 springs (~1e-4) (measured 8.7e-4)
HIP_CUP_RADIUS = 3e-3
#: |torque| <= (3/4) mu F a (full slip) up to rounding of the spring sums
SLIP_BOUND = 1e-9


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
#: foundation torsion against the MDR torsion closed form (theory §6.4) at the default N,
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
#: the normal series of a partial run (a load path whose normal solve failed at step k) against
#: contact.normal on the loads of steps 0..k-1: the same solver on another batch of steps (the
#: path solves per segment), whose iterations stop when the whole batch has converged
PARTIAL_PREFIX_NORMAL = 1e-12
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
#: docs/theory table values are printed with 6 significant digits
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
#: torsional stick-ratio boundary (one direct evaluation of φ(c = threshold a), a quadrature at
#: rtol 1e-10) against the closed form φ(c) of the Lubkin problem
TORSION_BOUNDARY = 1e-8
#: criterion at the torsional energy/torque-ratio boundary (issue 26): the boundary is certified
#: to 1e-10 relative in the twist on the loop's own route, so the loop there misses the threshold
#: by |dv/d ln φ| x 1e-10 (|dv/d ln φ| <= 1) plus the quadrature tolerance 1e-10 of W, M*, φ*;
#: measured <= 1e-10. (It was 1e-5 while the boundary was three regula-falsi steps.)
TORSION_BOUNDARY_ROOT = 1e-8
#: torsional energy/torque-ratio boundary against the Hertz root of the Lubkin / Jäger closed
#: forms in 20-digit arithmetic (issue 26): bracket 1e-10 relative in the twist plus the
#: quadrature tolerance of the criterion divided by |d v/d ln φ| (>= 0.1 for thresholds <= 0.9);
#: measured <= 6e-11 (benchmarks/fretting_boundary.py)
TORSION_BOUNDARY_CONVERGED = 1e-9
#: a torsional boundary against brentq on fretting_loop's own criterion (the twist-given route,
#: a second method): both roots to 1e-12 / 1e-10 in the twist, each criterion evaluated with
#: quadrature tolerance 1e-10
TORSION_BOUNDARY_LOOP_ROUTE = 1e-9

# ---- adversarial review (issue 11)
#: surface displacement within 1000 rounding steps outside the contact edge against a 40-digit
#: reference: closed-form route (atan2 angle, hypergeometric connection formula near z = 1),
#: only a few roundings remain (measured 4.4e-16); the issue's target
EDGE_DISPLACEMENT = 1e-12
#: Masing dissipation along sampled histories, relative to the total: small loops integrate
#: their definition over [c, a] directly (Gauss-Legendre) instead of differencing integrals from
#: 0, so only a few ε·a/(a-c) remain (closed form before: 3e-10 at u = 0.01 u*; now ~1e-15 there)
DISSIPATION_CANCELLATION = 1e-12
#: energy per cycle of small Hertz loops against Mindlin-Deresiewicz in 50 digits: the rounding
#: of d - g(x) at the nodes leaves ~ε·a/(a-c) with a - c ≈ a·u/(2u*): measured 2.6e-15 at
#: u = 0.01 u*, 9e-14 at 1e-3, 3.3e-12 at 1e-4; the bound is this factor times u*/u, and
#: SMALL_LOOP_FLOOR for large loops (closed form, 1.3e-14 measured at u = 0.5 u*)
SMALL_LOOP_ENERGY = 1e-15
SMALL_LOOP_FLOOR = 1e-13

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

#: Cattaneo–Mindlin force at small displacement (down to u/u* = 1e-19) against a 40-digit
#: evaluation of the MDR force from the same radius and depth: the slip term integrated on
#: [c, a] (error ε d (a - c), a few ε of the force) and the stick radius entering only to second
#: order (dF/dc = 0 at the exact c); measured <= 1e-13: at u/u* = 1e-19 the stick radius is
#: within ulps of a, and the normal state's d = g(a) holds only to rounding, which the force
#: then sees at ~2e-13
SMALL_SLIP_FORCE = 1e-12

#: normal solves at the edges of the float range (powers and roots in logarithms where the
#: power alone leaves it: relative error ~eps |ln(result)| <= 2e-13; roots of 1e-200 against a
#: bracket tightened from 1e-3: a few ulps) and the torsion field integrated by QUADPACK against
#: the torque: measured <= 2e-13
EXTREME_SCALE = 1e-12

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
#: the law's generated standalone source (ContactLaw.to_source) against ContactLaw: the same
#: kernels and embedded coefficients (repr round-trips), so they agree to rounding; 1e-12 is the
#: issue's bar
LAW_SOURCE = 1e-12
#: ContactLaw's per-contact MDR springs against Contact.simulate at equal spring counts and cell
#: layout: the same element arithmetic, cell integrals by the same closed forms evaluated in
#: another order (measured ~1e-14 of the largest value); 1e-12 is the issue's bar
LAW_SPRINGS = 1e-12
#: ContactLaw after a regrid (the radius left the springs' cover and the cells were re-laid,
#: element forces carried over by their cumulative line load) against Contact.simulate at equal
#: spring counts, whose cells cover the path's largest radius from the start: the two layouts
#: differ by about the 16-spring discretisation error itself (measured 1.3e-2 of the peak)
LAW_REGRID = 3e-2
#: ContactLaw's compiled step against its numpy path under force control: the compiled radius
#: (a power) may differ by an ulp from numpy's; responses then differ by ulps of their largest
#: value, the per-step dissipation (a difference of branch dissipations, conditioned as 1/x at
#: small slip) by ~1.5e-13 of the cumulative dissipation (measured); under depth control the two
#: are bit-identical
COMPILED_VS_NUMPY = 1e-12
# ---- shared levels of agreement (named so each assertion states which kind it expects)
#: one or two floating-point operations apart (a unit conversion, a compliance sum, a value written
#: with repr() and read back, a constant): a few ulps
ULPS = 1e-15
#: the same closed form evaluated along two short arithmetic paths (a lambdified sympy formula
#: against the hand-written formula, sampled load values against their formula)
SHORT_ARITHMETIC = 1e-14
#: the same closed form through a longer chain (sympy substitution into a solver state, an elliptic
#: kernel against scipy's Carlson integral whose own error is ~5e-14)
LONG_ARITHMETIC = 1e-13
#: the same exact state reached by two exact routes (spring sums of the foundation against a closed
#: form, a held or repeated load path against its first pass, loop closure): rounding of O(N) terms
EXACT_ROUTES = 1e-12
#: absolute floor for quantities that are exactly zero at some samples (unloaded steps, the axis),
#: in the quantity's own unit or as a factor of its scale: far below any value of interest
ABS_FLOOR = 1e-12
#: absolute floor (N) for the forces of a viscoelastic history that start at exactly zero
ABS_FLOOR_TINY = 1e-14
#: absolute floor (rad) for twists that are exactly zero in a sampled scene history
ABS_ZERO_TWIST = 1e-18
#: an absolute floor that only keeps exact zeros from failing a relative comparison
ABS_ZERO = 1e-300
#: elliptic kernel (K-E)/k² against scipy's elliprd(0, p, 1)/3: both good to a few ulps
ELLIPTIC_KERNEL = 5e-15
#: absolute floor of the h(v) kernel against its series near v = 1 (h -> 0 there)
H_SERIES_ABS = 1e-16
#: exact torsion at c/a = 1 - 1e-12 against the no-slip Reissner-Sagoci torque: the slip annulus
#: left contributes O((1 - c/a)^(3/2)); the root and quadrature tolerances add ~1e-12
NO_SLIP_LIMIT = 1e-11
#: an error estimate at the default rtol 1e-10 must stay below that rtol
DEFAULT_RTOL_BOUND = 1e-10

# ---- torsion fields and limits
#: full-sliding torque 3π/16 μFa: ∫x g by tanh-sinh to rtol 1e-10 plus the limit c -> 0 of the root
SLIDING_TORQUE = 1e-8
#: a field (pressure, traction) integrated again with scipy quad over the contact (nested
#: quadratures, square-root edge weight) against the integral quantity (force, sliding torque)
FIELD_INTEGRAL = 1e-8
#: 2π∫τ r² dr over the stick zone (nested quadrature of a nested quadrature) against the torque
SHEAR_INTEGRAL = 1e-7
#: dM/dφ by central differences with h = 1e-6 φ at rtol 1e-13: truncation ~h², noise ~1e-13/h
FD_STIFFNESS_FINE = 1e-7
#: stiffness at the smallest twist of a ladder against the no-slip (16/3) G_t a³: c/a = 1 - O(φ)
SMALL_TWIST_STIFFNESS = 1e-6
#: circumferential displacement at r = 2a against the far field M/(4πG_t r²): O((a/r)²)·small
#: coefficient at the chosen radius
FAR_FIELD_NEAR = 1e-6
#: the same far field at r = 100 a, where the neglected terms are O((a/r)²) = 1e-4
FAR_FIELD = 1e-4
#: continuity of u_φ across r = a: both sides are nested quadratures converging as the edge is
#: approached
CONTINUITY_EDGE = 1e-6
#: continuity of τ at the stick edge r = c approached to eps = 1e-10: the slip side approaches as
#: O(sqrt(eps/c))
CONTINUITY_SQRT = 1e-3
#: stick radius -> twist -> stick radius round trip (MDR): the root in c at rtol 1e-10 has slope
#: ~1/(1 - c/a) near the edge
STICK_ROUND_TRIP = 1e-7
#: stick radius of a history step from the exact twist root at rtol 1e-10 (slope ~1/(1 - c/a))
STICK_RADIUS = 1e-8
#: values printed to 3 significant digits in the reference table
TABLE_3_DIGITS = 6e-4
#: energy per cycle from the Iwan dissipation integral (tanh-sinh to rtol 1e-10 of a difference of
#: two O(W) terms) against the closed-form loop energy
MASING_ENERGY = 1e-8
#: trapezoid area of a loop sampled with 4000 steps per cycle against its energy
LOOP_AREA_HISTORY = 1e-6
#: trapezoid area of a loop sampled with 200 points against its energy: ~W''δ²/(12 n²)
LOOP_TRAPEZOID_200 = 5e-3
#: cumulative dissipation of a brute-force 4000-Jenkins-element model against the exact history:
#: the element slip thresholds resolve the stick edge to ~1/N, the energy converges as ~1/N
JENKINS_DISSIPATION = 1e-3
#: Simpson's rule for the cycle work across the kink of M(φ) at the reversal
SIMPSON_KINK = 1e-5
#: energy per cycle of a periodic foundation path after the first cycle (1e6 steps accumulate
#: ~sqrt(steps) ulps of the cumulative sum)
ENERGY_PER_CYCLE = 1e-9

# ---- foundation
#: force-controlled displacement of the foundation against Cattaneo–Mindlin: the one lumped cell at
#: the stick edge, 1/N² at N = 2000
FOUNDATION_DISPLACEMENT = 2e-6
#: MDR foundation torque against the exact torque at a very narrow slip annulus (c/a ≈ 0.999):
#: the model error ~(1 - c/a)² plus the 1/N² spring error
NARROW_SLIP_FOUNDATION = 1e-4
#: the "segments" (closed-form blocks) and "steps" routes of the time loop: same algebra, sums
#: accumulated in a different order over 1e3 steps
STRATEGY_AGREEMENT = 1e-9
#: tractions of a snapshot from the spring line loads (the MDR inverse piecewise linear between
#: cells) against the closed-form traction, relative to μ p0
SNAPSHOT_TRACTION = 1e-3
#: contact radius of a viscoelastic scene interpolated inside the outermost element's cell
FOUNDATION_RADIUS = 1e-3

# ---- tangential, adhesion, viscoelastic, scenes
#: Cattaneo–Mindlin through the MDR against the Hertz closed forms: displacement root solved to
#: rtol 1e-14, depth from the normal solve; a few 1e-10 at the stick edge
CM_CLOSED = 1e-9
#: location of a flat minimum by scipy's minimiser (xatol ~1e-8 of the position): ~sqrt(eps)
MINIMISER_LOCATION = 1e-6
#: the same with scipy's default tolerance
MINIMISER_LOCATION_DEFAULT = 1e-5
#: dF/dd at the force-controlled pull-off is zero analytically: 2E*a·(φ - 3/2) with φ from a root
#: at rtol 1e-14 and g' from differences
JKR_STIFFNESS_ZERO = 1e-6
#: ratio of errors at two step sizes against the asymptotic order's ratio
CONVERGENCE_ORDER = 1e-3
#: the creep/relaxation identity ∫G(t-s) dJ(s) = 1 by scipy quad on stiff exponentials
VISCO_IDENTITY = 1e-6
#: force-controlled viscoelastic history against the depth-controlled one it reproduces: each step's
#: depth is a root to rtol 1e-13 of a force that varies steeply at the contact edge
VISCO_FORCE_CONTROL = 1e-8
#: scene outputs (exact torsion, loops) against mpmath references evaluated with findroot and quad
#: at mpmath's default precision (15 digits) through elliptic integrals near c/a -> 0
SCENE_VS_MPMATH = 1e-6
#: pressure at r = a in a scene output: the square-root edge turns the last-ulp difference of r
#: into ~1e-8 p0
EDGE_PRESSURE = 1e-7
#: expected values quoted with 6 significant digits (scene comments, docs)
PRINTED_6_DIGITS = 1e-5
#: expected values printed with 5 significant digits (the demo's table)
PRINTED_5_DIGITS = 1e-4
#: a 200-point cubic spline of a parabola against the parabola: the spline is exact inside but its
#: not-a-knot ends deviate at ~1e-9
CUBIC_PARABOLA = 1e-8
#: root of 3x at 1e-310 by regula falsi down to subnormal numbers (few significant bits left)
SUBNORMAL_ROOT = 1e-6
#: slack of the per-step work bracket of the foundation energy balance, relative to the work
WORK_SLACK = 1e-2

#: the numba and the numpy foundation kernels on the same path: element updates are bit-identical,
#: the dissipated energy is summed in another order (sequential vs pairwise, ~N ulps of the sum)
BACKENDS_AGREE = 1e-12
#: worn volume from the final wear-depth table against (k/μ) × dissipated energy: both are sums of
#: the same Heun increments, so only rounding over ~10³ steps remains (measured <= 2e-15)
WEAR_ENERGY_IDENTITY = 1e-8
#: fresh-profile energy per cycle on the wear grid (n = 200 intervals over ~2a) against the loop's
#: closed form: the grid resolves the stick-slip boundary to O(Δ^1.5); measured 6.7e-3 (shift,
#: partial slip), 6e-4 (gross slip), 2.3e-3 (twist, c/a = 0.4), see docs/fretting.md
WEAR_GRID_ENERGY = 1e-2
#: limiting state at n = 200 against the closed form for the run's final stick radius: depth and
#: scar radius measured <= 0.3 %, volume <= 5 % (0.2 % at n = 400; the stick edge carries a
#: flat-punch singularity the grid resolves slowly)
WEAR_LIMIT_DEPTH = 5e-3
WEAR_LIMIT_VOLUME = 6e-2
#: tangential gross-slip scar radius against the asymptote (16kRFδN/π)^(1/4) after 10⁶ cycles at
#: δ = 50 µm (Hertz): measured 5e-4; the transient decays as the elastic slip share does
WEAR_SCAR_ASYMPTOTE = 1e-2
#: torsional gross-slip scar radius against (6kRFφN/π)^(1/3) inside the bracket of its two
#: leading corrections (docs/fretting.md section 6): the elastic excess of the contact over the
#: worn cap, at most (a0/a)³ (measured factor 0.8-1.1 of it in the tangential run), and the
#: unworn pillar's load share ψ, which slows the cap by (1 - ψ)^(1/3); the slack is the grid
#: (scar radius at 3e5 cycles: 1.0118, 1.0121, 1.0183 for grid cells of 6, 3, 1.5 µm)
WEAR_TORSION_SCAR_GRID = 1e-2
#: Hertz torsional loop energy of the reference (adaptive quadrature of Lubkin's closed forms
#: M(c/a) and φ'(c/a) = -C E(1 - (c/a)²)/(c/a)) against the exact solver: measured <= 1.2e-12 in
#: the energy ratio (amplified by 1/A ~ 150 at c/a = 0.99 from the cancelling 8∫M dφ - 4φM)
LUBKIN_ENERGY_REFERENCE = 1e-9
#: shift and twist wear runs (Hertz, n = 200) tuned to the same final stick radius: the secant on
#: the twist amplitude stops within this relative difference of the stick radii
WEAR_SAME_STICK = 2e-4
#: their limiting states against each other (the same shape, Dmitriev et al. 2016): depth, scar
#: radius and largest wear depth measured <= 2.8e-3 (the stick edge falls at different places in a
#: grid cell of 2 µm); volume 5e-3 and the profile away from the 3 cells at the stick edge 4.6e-3
#: of the largest wear depth
WEAR_MODES_SAME_LIMIT = 5e-3
WEAR_MODES_SAME_LIMIT_VOLUME = 1e-2

# ---- exact ring solver for torsion along load paths (issue 18)
#: one step from rest of the punch-density (single slip annulus) kernel at 200 rings against
#: Lubkin's closed form (Hertz): torque measured <= 3e-7 of the sliding torque (the full-sliding
#: density's collocation error); the stick radius is a root inside its ring
RINGS_ANNULUS_STEP = 1e-6
#: 200 rings (default) against the exact Jäger/Masing twist_history at constant load (monotone,
#: oscillating, irregular Hertz histories): measured max 3.9e-7 of the sliding torque with the
#: stick radius solved inside its ring (punch-density steps; 4.1e-5 with the ring solver alone,
#: whose boundary switched whole rings); what remains is the collocation error of the
#: full-sliding density
RINGS_CONSTANT_LOAD = 1e-6
#: 400 rings on the same histories: measured max 5.6e-8
RINGS_CONSTANT_LOAD_FINE = 2e-7
#: full sliding, torque weights against 2π∫μp r² dr (Hertz closed form): error falls as N^-2.5,
#: measured 3.3e-7 at 200 rings
RINGS_FULL_SLIDING = 1e-6
#: no slip with a growing contact, incremental stiffness against (16/3) G_t a³ (and with a
#: shrinking one, M against (16/3) G_t a³ φ), the ring solver alone: each increment is a rigid
#: punch of the current radius, whose singular edge traction r/sqrt(a² − r²) the continuous
#: densities miss where the radius is an inner node (first order: 7.5e-3, 4.2e-3, 2.2e-3,
#: 9.6e-4 at 100, 200, 400, 800 rings, the same for growing and shrinking and already at the
#: first step, a single punch);
#: measured 4.2e-3 at 200 rings, both
RINGS_NO_SLIP_GROWING = 6e-3
#: the same with the exact solver (rigid punches at the contact radii, no friction limit): only
#: rounding remains (measured 3e-15); also its dissipation, of the work (no slip: none)
RINGS_NO_SLIP = 1e-12
#: full sliding at every step of a changing load (Hertz), torque against (3π/16) μ F a: the
#: contact edge is an inner node, where the density jumps; measured 6.7e-7 at 200 rings (3.7e-4
#: without the jump, the density's jump at the edge smeared over the next ring)
RINGS_FULL_SLIDING_VARYING = 5e-6
#: stick radius at constant load against twist_history, in ring widths of the default 200 rings
#: (the boundary is placed inside its ring by the square-root approach of τ to μp): measured 0.54
RINGS_STICK_RADIUS = 1.0
#: flat punch (singular edge pressure), 200 rings with the edge punch against the exact
#: twist_history (monotone, oscillating, irregular): measured 2.0e-6 of the sliding torque on a
#: 120-step history (5e-2 without the edge punch)
RINGS_FLAT_PUNCH = 1e-5
#: discrete energy identity (midpoint traction): only rounding of the per-step sums remains
RINGS_WORK_BALANCE = 1e-10
#: per-step dissipation from the returned fields (τ, slip increments at the collocation points)
#: by scipy quad on a PCHIP interpolant, against the solver's, of the path's total dissipation:
#: the interpolant's error (measured 1.3e-5 per step, 2.0e-5 in total at 100 rings; 4.2e-6,
#: 4.2e-5 at 200; 4.4e-6, 1.1e-5 at 400: the point data, not the solver, limit it)
RINGS_DISSIPATION_QUADRATURE = 2e-4
#: Coulomb's law on the returned fields, of the largest μp: rounding of the tractions
RINGS_COMPLEMENTARITY = 1e-9
#: the full-sliding density held to Ψ >= 0 (physics.torsion_annulus.nonnegative_psi): the band of
#: the edge ring it removes slides below μp, and the points inside the edge ring see its
#: traction; of the largest μp beyond the edge ring (measured 2.7e-7 on the 100-ring varying-load
#: path, 1.8e-5 at 200 rings, 3.7e-3 at 24)
RINGS_SLIDING_PROJECTION = 1e-6
#: torque control inverted by twist control on a cone with a changing force (steps with two slip
#: zones on the ring solver): the torque of the twist-controlled run against the prescribed one,
#: of the largest torque; root solves and rounding (measured 3e-13; 4.5e-3 when the ring solver's
#: step aimed at the target in its own torque measure g·z instead of the density's torque)
RINGS_TORQUE_INVERSION = 1e-9
#: dissipated energy against twist_history's exact integral, an oscillation in 50 and in 800 steps
#: at 100 rings: each step's work is ∫ M dφ along the step (exact in time at constant force), the
#: rings remain: measured 6.9e-8 for both (the trapezoid booking before issue 26: 1.6e-2 and
#: 6.3e-5, second order in the step)
RINGS_DISSIPATION_800_STEPS = 1e-6
#: 120 rings against the independent brute-force (piecewise-constant punch density, BVLS,
#: 300 rings) on a 16-step path with the force changing every step: the brute force carries the
#: edge error of a contact radius between ring nodes (order ~1.2); measured 3.1e-4 of the sliding
#: torque with the density jumps at the contact radii (6.1e-4 without, 6.8e-4 before the nodes)
RINGS_VS_BRUTE_FORCE = 3e-3
#: simulate() with its long-path windows (normal solve, edge data, fused runs, turn search)
#: shrunk to a few steps against the default windows: the same arithmetic per step, only the
#: grouping of vectorised calls differs (rounding)
WINDOWED_PATH = 1e-12

# Cubic tables, closed-form transform (issue 12): the node-term sums for g and ∫g against the
# per-interval Gauss-Legendre rule (a different evaluation of the same spline). Measured worst
# 1.6e-15 up to 1000 random nodes, 3e-15 on uniform 10^4 tables; 1e-11 leaves a margin.
CUBIC_CLOSED_FORM = 1e-11
# ... on 10^4 random nodes (some 2.5e-12 m apart): the spline's third-derivative jumps there are
# ~1e15 m^-2 from data rounding alone and cancel in the node sums; measured 2.1e-8.
CUBIC_CLOSED_FORM_CLUSTERED = 1e-7
#: node sums of a randomly spaced cubic table (10^5-10^6 points, nearest nodes ~1e-15 of the
#: radius apart, clustered pieces kept local) against the sampled profile's closed form: the
#: remaining jumps' rounding, measured 4.6e-10 at 10^6 points (uniform tables: 4e-13)
CUBIC_RANDOM_FINE = 2e-9
# g' of the closed form against a central difference of g (step 1e-9 of a 1e-3 m table):
# difference error ~h² g''' and rounding eps g / h ~ 1e-7; measured 3.5e-10 (uniform tables).
CUBIC_SLOPE_FD = 1e-8
# ---- fretting maps in blocks (issue 16)
#: the vectorised torsion solvers iterate on a whole array until every entry has converged, so an
#: entry's last bits depend on the other entries: a map computed in small blocks against the map
#: in one block (observed 1.1e-14 relative on the exact model's energy)
MAP_BLOCKS = 1e-12
# Table audit (issue 12, tests/hard/test_table_audit.py): every route on tables of 10..10^6
# points. normal(depth=normal(force=F).depth).force against F: both radius solves converge to a
# relative bracket of 1e-15; the force is smooth in the radius (contactlab.testing ROUND_TRIP).
TABLE_ROUND_TRIP = 1e-9
# inverse transform (2/π)∫g(r sinθ)dθ of a table against its interpolated height: a quadrature
# (rtol 1e-10, summed over the θ segments of a linear table) of the exact transform.
TABLE_INVERSE = 1e-8
# dissipated energy of a shift loop, 1000-point linear table of a paraboloid against the
# paraboloid: a difference of ∫g and ∫g² terms over the slip annulus, which amplifies the table's
# own error ((Δr/a)² ~ 1.1e-4 at a = 0.19 mm); measured 2.6e-4.
TABLE_1000_DISSIPATION = 1e-3
# MDR springs on a twisted path whose normal force changes, within the validity limit of
# effects.path.warn_mdr_path (no warning): torque error against the exact ring solver, of the
# path's largest sliding torque. The MDR model's own threshold is 1 % (MDR_ERROR_THRESHOLD);
# measured up to 0.8 % at the limit (benchmarks/torsion_rings.py --map), 0.1 % in the test.
MDR_PATH_WITHIN_VALIDITY = 1e-2
# effects.path.warn_mdr_path, dissipated energy: the criterion's own threshold (1 % of the energy
# per twist cycle, physics.fretting.MDR_VALID_STICK_RATIOS["energy"] at constant load). Measured
# at constant force (Hertz, MDR default springs vs Jäger/Masing's closed form) 0.2 % at c/a = 0.99
# and 2.5 % at 0.93; under a changing force 13-30 % (tests' paths, against the ring solver)
MDR_PATH_ENERGY_THRESHOLD = 1e-2
# Torque weights of the ring solver with the edge punch against 2π∫ r² p dr of a flat punch's
# singular pressure 1/sqrt(a² − r²) (closed form π²a²/2): N^-2.5, measured 8.7e-8 at 200 rings.
QUADRATURE_EDGE_PUNCH = 1e-6

# shift loop energy, 200-point linear table of a sphere (R = 10 mm, 5 µm spacing) against the
# sphere, contact radius 87 µm: the table's error is O((Δr/a)²) ~ 3e-3 at most in the slip
# annulus terms; measured 8.4e-6 (the loop's ∫g² differences average the chord error out)
TABLE_200_SHIFT_LOOP = 1e-4

# ---- pressure of a table at fixed ring radii (physics.ring_pressure, issue 12)
#: against a closed form (linear table of a cone, cubic spline of a cubic polynomial: the
#: interpolants are the profiles): Gauss rules of 30 points in u per table segment, rounding of
#: the running sums over up to a few hundred segments; measured 2e-13, relative to |S| + g(a)/a
RING_PRESSURE_CLOSED = 1e-11
#: against the profile's per-(ring, node) tanh-sinh route (rtol 1e-10 each, summed over the
#: nodes) on linear and cubic tables, uniform, random and clustered nodes; measured 4e-12
RING_PRESSURE_SECOND = 1e-10
#: exact ring solver on a table with the running-sum pressure against the per-step route: the
#: pressures differ by < 1e-10 relative, the solver's active sets stay the same; measured 8e-13
#: of the largest torque/energy
RING_PRESSURE_PATH = 1e-9

# physics.torsion_validity: Jäger's slip function at c/a = 0.83 and 0.97 by the fixed 16-point
# rule over [c, a] against the exact composite table rule (2500-point sphere tables, linear and
# cubic, uniform and random spacing). The rule samples g at 16 points only, so the square-root
# cusps of a linear table's g at its nodes limit it; measured up to 1.5e-5 (linear, random
# spacing), 2.4e-6 (linear, uniform), 1e-10 (cubic); a validity limit needs two digits (c/a = 0.83
# is known to them).
TABLE_BOUNDED_SLIP = 1e-4
# the same rule's validity twists on a 10^5-point table of a paraboloid against Jäger's closed
# form for Hertz contact: the table's own error (Δr/a)² < 5e-6 at a = 30 µm plus the rule's;
# measured 3.5e-8 (linear), 2.4e-13 (cubic)
TABLE_BOUNDED_SLIP_HERTZ = 1e-6

#: κ_n = √π Γ(n/2+1)/Γ(n/2+1/2) in double precision against the 30-digit mpmath reference:
#: whole-number n exact rationals (times π for odd n), other n a math.gamma ratio (worst
#: measured 22.5 ulp near n = 31) or, for n >= 300, an asymptotic series (< 1e-18 truncation)
KAPPA_DOUBLE = 1e-14

#: a path of the exact ring solver (no friction limit: rigid punches) opening with a step out of
#: contact against the same path without it: the empty punch at radius 0 changes only the order of
#: the sums of the twist and the released energy (measured 1.7e-16 and 5.9e-16 relative)
ZERO_LOAD_START = 1e-14
# Energy of the exact torsion solver (physics.torsion_energy; issue 26 item 1).
#: a step's dissipation is a sum of products over Gauss points that vanish (Φ = 0 in the stick
#: zone, a released density of zero): rounding of those sums, of the running total of the path
#: (measured down to -1.4e-16, hip-cup scene)
ENERGY_STEP_ROUNDING = 1e-12
#: work in = elastic energy + dissipation, each its own sum of exact Gauss integrals, of the
#: largest work or elastic energy of the path: rounding (measured 1.6e-15)
ENERGY_BALANCE = 1e-12
#: a step after a force rise at held twist whose stick radius stays outside the old contact
#: dissipates what a fresh contact does (superposition), per step of the post-rise running
#: total: rounding of the two runs' sums (measured 1.0e-12 of one step's own dissipation, 6.9e-14
#: of the running total)
ENERGY_SUPERPOSITION = 1e-10
#: work and dissipation of a held-force twist path in coarse steps against the same path in
#: finer steps (the booked work is ∫ M dφ along each step, additive): rounding of the root solves
#: (measured 3.2e-14 of the largest work)
ENERGY_REFINEMENT = 1e-10
#: booked work of a twist from rest at constant force against ∫ M dφ of the closed-form exact
#: torque (Jäger, contact.torsion) by scipy quad: the collocated full-sliding density of the
#: rings (measured 4.0e-8 at 200 rings, for 1, 3 and 10 steps; the trapezoid rule of the old
#: booking was off by 18 %, 2 %, 0.2 %)
ENERGY_WORK_CLOSED_FORM = 1e-6
#: pressure of a 300-point cubic table of a paraboloid against Hertz: the spline's interpolation
#: error (~(h/a)^4 ~ 1e-9 at h/a = 6e-3; measured 1.8e-14 of p0 on a uniform table, f'' exact
#: on parabolas away from the ends) plus the per-segment rules (~1e-12)
TABLE_PRESSURE_CUBIC = 1e-8
#: linear table of a paraboloid against Hertz, in units of (h/a) p0: the interpolant's slope
#: jumps give log singularities at the nodes of strength ~ (h/R) E*, first order in h/a
#: (measured 0.35 between the nodes on uniform 300-point tables)
TABLE_PRESSURE_LINEAR = 2.0
#: per-segment rules of physics.table_pressure against the profile's own per-node quadratures
#: (both at rtol 1e-10; measured 1e-12 of the largest shape on uniform and random tables)
TABLE_PRESSURE_SECOND = 1e-9
# ---- model errors of approximate routes (issue 26)
#: the map's model error against the actual MDR error: a stick ratio that lands on a ladder
#: point of the map is bracketed by rounding on either side (the error there is the actual one)
MODEL_ERROR_ROUNDING = 1e-3
#: how far the map overstates the actual error for a mapped family (paraboloid, cone) at
#: 0.35 <= c/a <= 0.98: the conservative bracket takes the next ladder point (measured 1.34x)
MODEL_ERROR_MAP_SHARPNESS = 1.4
#: coarse exact check of a varying-load MDR path (64 rings) against the exact ring solver at 400
#: rings: the check's own ring discretisation (energy ~0.3 %, torque ~0.2 % measured)
MODEL_ERROR_PATH_CHECK = 5e-3
# ---- subsurface stresses (issue 31)
#: Huber's closed Hertz field (the library's route) against Johnson's axis and surface forms and
#: Huber's field written independently in tests/reference/stress.py: both are closed forms in
#: double precision, evaluated with different algebra; measured <= 1.1e-15 relative to p0
STRESS_CLOSED_FORM = 1e-10
#: the flat-punch kernel against Boussinesq's point load integrated numerically (240 x 240
#: Gauss points, ρ = a sin t at the rim) at depths >= 0.1a: the 2D quadrature limits it;
#: measured <= 5e-13 relative to the mean pressure
STRESS_BOUSSINESQ_PUNCH = 1e-10
#: Hertz field by the numerical Boussinesq integration at depths >= 0.1a: the split 240 x 240 rule
#: on the smooth Hertz pressure; measured <= 6e-9 relative to p0
STRESS_BOUSSINESQ_HERTZ = 1e-7
#: the punch superposition (Gauss-Kronrod 15 per segment) for smooth g' against a closed form,
#: measured on 801 radii over [0, 2a]: <= 2.1e-7 of p0 at depths 1e-6 a .. 2a (<= 7.5e-9 at
#: z >= 0.1a), 2.3e-6 on the surface and 4.5e-6 at z = 1e-9 a (the kernel's peak at x = r is
#: then narrower than the rule resolves); every point within its own error estimate (tested)
STRESS_SUPERPOSITION = 1e-5
#: equilibrium ∫σ_zz dA = -F at a depth, by a 2 x 400-point Gauss rule in the polar angle
#: (r = z tan θ): the rule's own error; measured 7e-14 (Hertz), 9e-10 (cone, superposition, whose
#: axis log-singular pressure gives the slowest convergence at z = 0.1a)
STRESS_EQUILIBRIUM = 1e-8
#: location of the maximum shear below Hertz contact: the maximum is flat (quadratic), so its
#: depth is fixed only to ~ sqrt(rounding) by any maximiser; measured 1.7e-8 of a between our
#: Nelder-Mead and the reference's bounded scalar minimiser
STRESS_MAX_LOCATION = 1e-6
#: the twisted-punch kernel against Reissner-Sagoci's Hankel integral (scipy quad, epsrel 1e-12)
#: at depths >= 0.1a; measured 1.6e-14 of 4Gφ/π
STRESS_TWIST_HANKEL = 1e-10
#: surface σ_θz of a partial-slip torsion field (Jäger's twist density, Chebyshev-differentiated
#: in ln x, superposed by the Gauss-Kronrod rule) against the library's own surface traction
#: TorsionState.shear (a different algorithm: the stick-zone integral of theory §6.2 item 5);
#: measured 2.4e-13 (exact) and 1.6e-8 (MDR, whose lag is not smooth at the slip boundary) of
#: the peak traction
STRESS_TORSION_SURFACE = 1e-7

# ---- fitting (issue 30)
#: parameters recovered from noise-free curves made from independent closed forms: the solver
#: converges to rounding (measured <= 2e-15 for E and the contact point)
FIT_RECOVERY = 1e-8
#: analytic slope dΦ/dδ = 2a of the fit's tip models against a central finite difference with
#: step 1e-6 δ (truncation ~1e-12, rounding ~1e-10 relative)
FIT_JACOBIAN_FD = 1e-7
#: compiled ContactLaw against its numpy reference where their arithmetic is not the same to the
#: bit (issue 29): contacts on MDR springs (the cell integrals S = d w - dG are formed as
#: d w - kc cover^(n+1) (beta^(n+1) differences) in the kernel and as differences of
#: kc b^(n+1) in numpy; near the contact edge they cancel, and an edge element at its slip
#: limit then differed by 2.1e-12 of the largest element force, measured over 60 contacts x 30
#: steps), and the per-step dissipation of a general exponent (n = 1.5: one ulp of numpy's
#: vectorised expm1/log1p against libm's in the Cattaneo-Mindlin curve, amplified as 1/x at
#: small slip: 1.8e-12 of the cumulative dissipation measured over 120 contacts x 60 steps)
COMPILED_VS_NUMPY_SPRINGS = 1e-11
#: exact-sphere contact radius by Newton from above (issue 29) against a 30-digit mpmath
#: reference: rounding of q artanh q (depth) and of the reduced force, whose closed form cancels
#: by ~75x at q = a/R = 0.1 where the series takes over (measured 4.4e-15 radius, 2.6e-14 force)
SPHERE_NEWTON_RADIUS = 1e-13

# ---- exact ring solver speed (issue 28)
#: the punch-density traction and slip lag summed with a NodeTable (antiderivatives at fixed
#: points and ring ends, times the density's jumps of offset and slope per node) against the
#: piece-by-piece differences they replace: the same terms added in another order; measured
#: 9.6e-13 of the largest |traction| over the 185 checks of the 180-step benchmark path (the
#: arccosh terms of neighbouring nodes cancel) and 3e-14 on the test densities. Only the
#: annulus step's checks use them (slack CHECK_RTOL = 1e-9), so the series stay bit-identical
RINGS_NODE_TABLE = 1e-11
#: the exact Hertz torque-twist curve from its closed forms (physics.torsion_hertz: Newton in
#: ln(c/a) on K - E, a 32-point Gauss rule for the torque integral) against the 30-digit mpmath
#: Lubkin reference: measured 3.5e-15 of the torque (twists given; the stick ratio round trip
#: 4e-16); a few hundred ulps allowed for scipy's elliptic integrals
HERTZ_TORSION_CLOSED = 1e-13
#: the same curve against the quadrature route it replaces (root solve of the slip function and
#: tanh-sinh torque integral at rtol 1e-10, whose own error is that tolerance)
HERTZ_TORSION_VS_QUADRATURE = 1e-9
#: the wear rate's analytic Jacobian (physics.wear_rosenbrock) against central differences of the
#: rate kernels at a step of 1e-5 of the wear depth: measured <= 9e-10 of the largest entry (the
#: differences' rounding); far below any kink of the positive parts
WEAR_JACOBIAN_FD = 1e-6
#: fitted order of the ROS34PW2 step and of its embedded estimate over 16..128 steps on an ODE with
#: a closed-form solution: measured 3.02-3.10 (the asymptotic constant still settling)
WEAR_STEP_ORDER = 0.2
#: implicit (Rosenbrock-W) against explicit (Heun) wear runs, both at jump_rtol = 1e-5, Hertz,
#: n_grid = 120, 300 cycles at k = 1e-13: scar radius and worn volume measured <= 4.7e-4 apart
#: (partial slip to 20x full sliding, shift and twist)
WEAR_INTEGRATORS_AGREE = 1e-3
#: the viscoelastic (Lee-Radok/Ting) fit model against Ting's solution by mpmath quadrature,
#: relative to the largest force: Gauss-Legendre on each time step (the step where contact
#: begins in u with s = t_c + L u²) measured 3e-15; the rest is the reference's 25 digits
FIT_TING_MODEL = 1e-12
#: the monotone dissipation of a shift or twist history (exact, MDR) at amplitudes of 1e-15..1e-6
#: of the scale against its definition evaluated at 40 digits in annulus coordinates: the thin
#: slip annulus integrated in its own coordinate is exact to rounding (measured 4.4e-16; at the
#: stick radius the old forms erred by ~ε a/(a − c): D = 0 at one ulp, 1.4e-3 at 1e-12)
TINY_LOOP_DISSIPATION = 1e-12

# ---- small gaps of issue 26 (tiny scales, model error, budgets)
#: a truncated cone's depth and force at tiny forces against the θ closed form (mpmath, 40
#: digits): the Newton root in t = tan θ stops at rounding (measured <= 2e-16 down to 1e-290 N);
#: at 1e-300 N the reduced force F/(2E*) ~ 4e-312 m² is subnormal and keeps ~12 digits
#: (measured 4e-13)
TRUNCATED_CONE_TINY = 1e-15
TRUNCATED_CONE_SUBNORMAL = 1e-11
#: an exact ring-solver torque path scaled by s (force s F, torque s^(4/3) M) against the same path
#: at s = 1 through the Hertz scaling laws (a ~ s^(1/3), twist ~ s^(1/3)): the
#: ring solver keeps every digit where a⁵ is a normal float; measured <= 7e-15 down to a = 3e-58 m
RINGS_SCALE_INVARIANCE = 1e-13
#: MDR annulus integral, twist and torque of a flat punch with c/a = 1 - 1e-3 .. 1 - 1e-12 against
#: their closed forms (mpmath): integrated in the offset x - c, measured <= 2.4e-16 (integral)
#: and <= 1e-15 (twist, torque); the error estimate of the integral ~3.7e-14
MDR_NEAR_ANNULUS = 1e-12
#: the MDR loop energy 32 G_t φ0² c (a - c)² of a flat punch next to the punch radius, relative,
#: in units of eps a/(a - c): the stick radius of the amplitude enters squared through a - c,
#: which carries the rounding of c (measured 1.1-1.9 units at gaps 1e-6 .. 1e-12)
MDR_NEAR_LOOP_ENERGY = 8.0
#: the MDR torsion kernels of a single power term in closed form (stick radius from
#: β s + s^n = δ, annulus integral (1 - s²)/2 - (1 - s^(n+2))/(n+2) or its offset rule) against
#: the generic quadrature route: torque measured <= 1.1e-14 (twist and stick-radius control);
#: the generic route's stick radius is a bracketed root to its tolerance (ln c to 1e-10 of
#: rtol, measured 3.3e-11), so it is compared at that tolerance
MDR_POWER_CLOSED_TORQUE = 1e-13
MDR_POWER_CLOSED_STICK = 1e-9
#: the MDR Hertz torque-twist relation against its closed form written with mpmath (30 digits):
#: measured <= 4e-16 (stick radius) and 1e-15 (torque)
MDR_HERTZ_CLOSED = 1e-14
#: MDR torsion given the force, scalar call against the same state in an array call: the scalar
#: and array normal solves of a non-whole power may differ in the last bits of the depth
#: (docs/robustness.md, <= 2.1e-15), which the torsion state carries (measured <= 1e-15)
MDR_SCALAR_ARRAY_FORCE = 1e-14

#: tangential field of the sliding sphere against Hamilton's closed form (1983), relative to p0:
#: the superposition's quadrature reaches ~1e-9 p0 (measured 7e-10 at worst over points inside
#: and outside the contact down to z = 0.01a, away from the edge)
STRESS_HAMILTON = 1e-8
#: the same within 0.05a of the edge and 0.02a of the surface, where the elementary shear field
#: varies on the scale of the depth: measured 8.4e-8 p0 at (x, y, z) = (1.05, 0.1, 0.02)a (the
#: field's own error estimate there is 7e-5 p0, so the estimate holds)
STRESS_HAMILTON_EDGE = 2e-7
#: surface sxz of a Cattaneo-Mindlin state against the library's own surface traction
#: state.shear(r), relative to its peak (measured 8e-14 for Hertz; a cone's pressure shape
#: difference near the axis is summed differently by the two routes)
STRESS_TANGENTIAL_SURFACE = 1e-8
#: contact radius of a table by the Newton iteration of issue 29 (start from the left node's
#: cusp, stop on quadratic convergence) against the previous iteration (plain start, stop on a
#: small step), in units of the solve's relative tolerance root_rtol(rtol): each stops within
#: 0.5 root_rtol of the root, so they differ by at most 1 (measured <= 0.1 at rtol 1e-6; at
#: rtol 1e-10 both sit at rounding, a few ulps against the floor of 1e-15)
TABLE_NEWTON_ROUTES = 2.0
#: contact radius and force of a uniformly sampled paraboloid's linear table against the
#: paraboloid's closed form at radii drawn at random between the nodes, as C (Δr/a)²: measured
#: C = 4.9 for the radius over 50 random radii on a 2000-point table (tabulated_linear's C = 3
#: was measured at one radius and does not cover every position of a between two nodes);
#: the test allows 2C for the other quantity
TABLE_LINEAR_RANDOM_RADII = 6.0
#: gross sliding on the exact torsion route (torque beyond the sliding torque, the force falling
#: at held twist): the dissipation of the fall against the closed-form elastic energy of the
#: Hertz-shaped sliding traction (independent quadrature), and the torque against 3πμFa/16: the
#: sliding density collocated on 200 rings (measured 9.5e-7 and 5.1e-7; 3e-5 at 50 rings)
GROSS_SLIDING_ENERGY = 1e-5
#: gross sliding with the force rising (the twist turns with the full-sliding density): booked
#: work against the trapezoid of the closed-form sliding torque over the reported twist: first
#: order in the force step (each step's family takes the end pressure; measured 1.2e-2 in 20
#: steps from 12 N to 20 N, 3.2e-3 in 80)
GROSS_SLIDING_WORK_STEP = 1e-2
#: the exact sphere's ∫g closed form ((a² - R²)/2 artanh(a/R) + R a/2, q = a/R >= 0.1) against a
#: 30-digit reference: the cancellation of its two terms near q = 0.1 costs digits (measured
#: up to 2.7e-14 relative over q in [0.1, 0.999] at R = 0.01; 1e-13 leaves room for other libms'
#: artanh)
SPHERE_G_INTEGRAL = 1e-13
#: PathResult.stress (issue 31): the normal part of a path snapshot is the normal state's own
#: field (same code: rounding); the force through a plane (trapezoid to 10⁴ a on 6800 radii) to
#: the quadrature of the plane integral (measured 2.2e-7)
PATH_STRESS_NORMAL = 1e-12
PATH_STRESS_PLANE = 1e-6
#: the torsional part at depth against the torque of the snapshot traction and that torque
#: against the ring solver's step torque (200 rings; measured 1.5e-3 and 7.3e-4 on the varying
#: load path of tests/unit/effects/test_stress_path.py), and the field against TwistHistory's
#: at a constant force step (measured 1.4e-3 of the largest σ_θz)
PATH_STRESS_TORQUE = 5e-3
#: the part of the difference of PathResult.stress's torsional field from the snapshot traction
#: (surface) and from TwistHistory's field (constant force step) that its own error estimate does
#: not cover, of the largest traction: measured 1.4e-3 (surface, step 20 of the varying load
#: path, where the traction turns sharply at earlier stick radii) and 3.1e-4 (TwistHistory)
PATH_STRESS_EXCESS = 3e-3
#: the fit's models against closed forms written in the tests, where both are closed forms in
#: double precision (Kendall's pull-off, the effective radius a/f'(a), the punch's stiffness):
#: a few ulps times the cancellation (measured <= 2e-14)
FIT_CLOSED_FORM_ROUNDING = 1e-12
#: the fit's models against closed forms where the model finds the contact radius by iteration
#: or a table (the JKR branch of a flat-centred tip, a JKR table ending at a wall): the solve's
#: tolerance and the table's differenced slopes (measured <= 4e-11)
FIT_MODEL_SOLVE = 1e-10
#: PathResult.stress along a shifted path (issue 31): the field of the step's sampled traction
#: (2000 springs, linear between the samples, which spread the stick radius's kink over a few
#: samples) against Cattaneo–Mindlin from Hamilton's closed form and against ShiftHistory at a
#: constant-force step: measured up to 4.5e-5 p0 (PATH_SHIFT_FIELD); the part of it the field's
#: own estimate does not cover (PATH_SHIFT_EXCESS, of p0 or of the largest traction); the
#: estimate itself relative to the largest stress (measured 1.0e-3); the tangential force through
#: planes at depth 0.1-1.5 a against the step's Q (measured 4.8e-5: the sampled traction's Q)
PATH_SHIFT_FIELD = 2e-4
PATH_SHIFT_EXCESS = 1e-4
PATH_SHIFT_ESTIMATE = 3e-3
PATH_SHIFT_PLANE = 3e-4
#: PathResult.stress without friction (issue 31): the ring solver's punches are summed exactly
#: (torque through planes measured 3e-12); the springs' entry history (depth and control linear
#: within a step, pointwise) against the springs' own torque/force (cell-averaged contact
#: weights): measured 8e-8 / 6e-11 while the contact grows, up to 5.9e-4 of M and 6.2e-4 of Q
#: after unloading and reloading (the same at every depth: the field carries its traction's
#: load to 1e-9); the twisted or shifted punch at a constant force against Reissner–Sagoci's
#: Hankel integral and the closed-form surface traction beyond the field's estimate, of 4Gφ/π or
#: Q/a² (measured 1.6e-14 and 4.5e-17)
PATH_NOSLIP_RINGS = 1e-9
PATH_NOSLIP_SPRINGS = 2e-3
PATH_NOSLIP_CLOSED = 1e-8
#: Findley's parameter on the 2.5° grids of plane normals and in-plane shear directions against
#: the maximum over all planes in closed form: a smooth maximum missed by at most 1.25° on each
#: grid (measured 8.4e-6 uniaxial, 4.4e-4 for the fully reversed shear)
FINDLEY_GRID = 1e-3
#: TorsionState.stress at full sliding (the slip annulus reaching the axis, the punches
#: narrower than 1e-6 a left out): the surface σ_θz against the state's traction (μp on the exact
#: model), measured up to 7.1e-7 of its peak (paraboloid, flat punch; exact and MDR); the torque
#: through a plane to 7e-9
STRESS_TORSION_SLIDING = 1e-5
#: fit.torsion_loop's exact route (issue 30): the test's nested scipy quadrature of Jäger's
#: equations (epsrel 1e-12 per level) against Lubkin's closed form for Hertz; and the exact
#: route's fitted values and model on a paraboloid against the certified master curve (both at
#: rounding of ~1e-13, the fits' stopping tolerance ~1e-12)
FIT_TORSION_VIRGIN = 1e-10
#: the two routes' fitted friction and modulus on the same loop: the fit amplifies a change of
#: the master curve at the rounding level (each coefficient moved by one ulp: the routes then
#: differ by up to 7.7e-10; the curve evaluated by Estrin's scheme instead of Horner's rule,
#: within 3.3e-16 of it: 2.9e-10), so the agreement is stated at 1e-9
FIT_TORSION_ROUTES = 1e-9
#: the exact ring solver's reference in the torque_rtol ladder (400 rings): its own error on the
#: 180-step varying-load Hertz path, against 800 rings, measured 6.2e-6 of the sliding torque
RINGS_RTOL_REFERENCE = 1e-5

# ---- tiny shifts and twists on any profile (edge annulus from g')
#: torque (exact, MDR) and force at amplitudes 1e-30..1e-18 against the no-slip limit, beyond
#: the slip-correction bound (1.5 σ_c/a, σ_c/(2a)): rounding of the no-slip closed form and of
#: the correction (measured <= 2.3e-16 at 1e-30..1e-21)
EDGE_ANNULUS_NO_SLIP = 8 * 2.220446049250313e-16
#: dissipation at 1e-30..1e-18 against the leading order of a thin annulus, g'(a) from closed
#: forms (mpmath) or a fourth-order difference of g at a step of 1e-3 a: the O(σ_c/a) <= 1e-12
#: correction plus the difference's error (measured <= 3.3e-11, truncated cone; <= 9e-13 else)
EDGE_ANNULUS_LEADING = 1e-9
#: shift dissipation (sphere, paraboloid + cone, linear table) at 1e-28, 1e-20, 1e-12 against
#: its definition at 90 digits: measured <= 6.7e-16
EDGE_ANNULUS_ANY = 1e-14

# ---- the contact law on a GPU (backend="cupy") against the numpy law
#: responses per step against the largest value of that field, the per-step dissipation against
#: each contact's slip-energy scale (mu F u* + M_full phi_s: the dissipation is a difference of
#: loading-curve energies of that size, computed with cancellation at small slip, so two
#: roundings of it differ by ulps of the scale, up to 4e-8 of the dissipation itself). The
#: device's math library (pow, sqrt, cbrt, expm1, log1p) may differ from numpy's by an ulp,
#: amplified in the turning points and torques. Measured on an NVIDIA H200 (CuPy 14.2), channel
#: kernels and array path alike, every family by force and by depth over 60 steps: responses
#: <= 1.4e-13, dissipation <= 5.6e-16 of the energy scale, turning points <= 4.1e-12 (the
#: fused step kernel passed this bound there too)
GPU_VS_NUMPY = 1e-11
#: the fused kernels' text (contactlab.physics.law_cuda) built for the host against the
#: numpy law, responses against each field's largest value, the per-step dissipation against
#: each contact's slip-energy scale, the float state against each entry's largest value:
#: measured 0 for the paraboloid, cone and flat punch (the same operations, sqrt correctly
#: rounded); for the power law <= 1.8e-16 with the channel kernel alone and <= 7.9e-16 with the
#: whole step fused (the host's pow, expm1 and log1p against numpy's vectorised ones), the
#: dissipation <= 6e-17, the turning points <= 3.6e-15
FUSED_HOST_VS_NUMPY = 1e-14
#: the same for the contacts on their MDR springs while the fused kernels step the others, and
#: for the spring state: their springs take the depth and radius of the normal kernel (the
#: host's pow for the power law, an ulp from numpy's), which the edge cell's weights amplify
#: (as the compiled law's other order of the cell integrals, COMPILED_VS_NUMPY_SPRINGS);
#: measured 0 for the paraboloid, cone and flat punch, for the power law <= 7.8e-14 of each
#: field's largest value (the dissipation <= 6.4e-18 of the energy scale), the spring elements
#: <= 5.9e-13 of their largest value, 60 steps by force and by depth
FUSED_HOST_SPRINGS_VS_NUMPY = 1e-11
#: a large linear table's node sums (g, g', ∫g) over the dyadic tree (20-term Taylor series of
#: the far blocks, near nodes exact) against the node-by-node sums and against 30-digit sums of
#: the same nodes, relative to the sum of the terms' magnitudes: measured <= 3.3e-16 on even,
#: random and wavy 10^4-point tables (the rounding of the sums; 16 terms would leave 1.3e-14
#: in g', 14 terms 4e-13: caught); the solved radius, depth and force of the two routes
#: likewise (measured <= 2e-15)
TABLE_FAR_FIELD_SUMS = 4e-15
#: TABLE_LINEAR_RANDOM_RADII's C (Δr/a)² on a 10^4-point table (rtol 1e-10): measured C = 11.4
#: for the radius (and 0.13 for the other quantity) over 50 random radii, the same on the
#: node-by-node route and on the tree (it is the interpolant's error, not the sums'); the
#: 2000-point constant does not cover it
TABLE_LINEAR_RANDOM_RADII_10K = 15.0
#: a large cubic table's column sums over the tree against the dense node sums, as a fraction of
#: the rounding estimate the dense route reports (8 eps times the parts' magnitudes): measured
#: <= 0.68 (wavy 10^4-point table, at points where g nearly cancels), 0.03 on a sampled sphere
TABLE_FAR_FIELD_CUBIC = 1.0
# ---- exact torque-twist curve on large tables: product-integration panels (issue 28)
#: the slip function P and torque integral T with panels against the composite rule, relative to
#: their largest value over the curve: the panel interpolation (rho^-18 = 1.6e-14 of the kernel's
#: scale at ratio 2) and the 8-point rule's integration of g times the Lagrange basis; measured
#: 1e-15 (P) and 2e-15 (T) of the largest value on a 667-node linear table, 60x below this
TABLE_PANELS = 1e-13
#: the analytic continuations the panels evaluate below a lower limit (kme_over_m at p > 1,
#: h_kernel at 1 < v <= 2) against mpmath: rounding of scipy's ellipk/ellipe and of a 16-point
#: Gauss rule of an analytic integrand (measured <= 1.7e-15)
PANEL_CONTINUATION = 1e-14
#: g of a linear table from per-segment cached far sums against the direct sum over all nodes,
#: relative to the largest |g|: rounding of two orderings of one sum (measured 8e-16 on a
#: smooth sampled table, 5e-13 on one with 20 % noise whose slope jumps of both signs cancel
#: in the sum to 1e-4 of their magnitudes)
FAST_G = 2e-12
#: the lower bounds of g and of F/2E* from f (radius_bounds: left Riemann-Stieltjes sums of
#: non-negative terms) against the closed forms of random polynomial gaps: a bound may exceed
#: the value only by the rounding of the two sums (16 terms each; measured: never above it)
RADIUS_BOUND_ROUNDING = 1e-13
#: the exact sphere's force-solve start (the series inverting its Hertz radius, seven terms)
#: against 30-digit roots up to q = a/R = 0.85: the truncated series errs by 1e-6 there (2.4e-10
#: at q = 0.45, the cbrt and the reduced force's rounding below ~1e-15); the bound leaves 3x
SPHERE_FORCE_START = 3e-6
#: the panel sums with the kernels interpolated in the lower limit x as well (24 Chebyshev
#: points per x-range of ratio 2, rho^-24 ~ 4e-19 of the kernel's scale) against the same panel
#: sums with the kernels evaluated at every point, relative to the largest value over the
#: points: measured <= 2.6e-16 (P) and 1.4e-15 (T) on the three test tables (rounding of the
#: contracted prefix rows), 7x below this
TABLE_PANELS_X = 1e-14
#: a ContactLaw state saved before the spring rows kept their radius (``spr_S`` instead of
#: ``spr_a``, issue 29) restored into a force-driven PowerLaw run: the radius recomputed from the
#: stored depth differs from the one the force gave by an ulp, which moves the edge cell's
#: integral and so the contact weight of the first step after the restore (measured 1.2e-14 of
#: the largest tangential force, torque and dissipation, numpy and compiled)
OLD_SPRING_STATE = 1e-12
# ---- exact ring solver on long paths: the inside-traction allowance (issue 28)
#: ring-solver steps per step on the first 600 steps of a 10^4-step varying-load Hertz path
#: (the twist ramped in) at 200 rings: measured 42/600 = 0.07 with the
#: allowance, 489/600 = 0.82 without; the bound leaves ~2x
RINGS_LONG_PATH_FALLBACK = 0.15
#: that path's torque at 200 rings with the allowance against the strict solver (no allowance)
#: at 400 rings, relative to its largest sliding torque: measured 1.0e-4 (strict at 200 rings:
#: 1.4e-4); the bound is the ring count's error law at 200 rings, RTOL_LAW = 20/200² = 5e-4
RINGS_LONG_PATH_TORQUE = 5e-4
# ---- exact ring solver: torque-controlled steps from full sliding (issue 28)
#: a torque-controlled box step's torque g·z against its target, relative to the sliding torque
#: g·μp: rounding of the free-set solve and of g·z (measured <= 1e-15); the old all-at-bound
#: acceptance missed it by 0.1..1.6 of the sliding torque
RINGS_TORQUE_TARGET = 1e-12
#: the unloading step from full sliding against the superposition of a loading step from zero
#: (twice its traction and twist), relative to the largest limit (tractions) and to the twist:
#: two solves of the same linear system by different pivot sequences, 40 rings (measured ~1e-14)
RINGS_SUPERPOSITION = 1e-10
#: twist increments of stored path 64's unloading after gross sliding (steps 99-102) at 61 rings
#: against 240 rings, relative: measured <= 2.2e-3 (the ring count's error); before the fix
#: both were wrong the same way (no increment), which the spring model's bound below catches
RINGS_RELEASE_FINE = 5e-3
#: the twist turned from step 97 to 102 of that path (gross sliding at 98, then the unloading)
#: against the spring model (2000 springs), relative: the spring model's error for torsion
#: under a varying normal load, measured 13 % (0.00222 against 0.00196 rad); the old solver's
#: 0.0267 rad (a gross slide the wrong way at step 102) missed it 13x
RINGS_RELEASE_MDR = 0.25
# ---- a requested torque_rtol on long paths (issue 28)
#: the torque of a torque_rtol run on the benchmark's varying-load path against 400 rings with
#: every contact radius on a node, in units of the requested torque_rtol times the sliding
#: torque: the request itself (measured 0.026 at 10^2 steps, 0.039 at 10^3 with the node cap at
#: 3x the rings; 2.9 at 10^3 with the old cap of 1.5x)
RINGS_RTOL_LONG_PATH = 1.0
#: where a torque_rtol run warns (edges off their nodes), its torque error against that
#: reference relative to error_estimate=True's torque estimate (both relative to the largest
#: torque): the estimate must cover the error; the half-ring run's difference is an upper
#: bound for an error falling at least as N^-1
RINGS_RTOL_ESTIMATE_COVERS = 1.0
#: the slip increments of a density change that the running-integral test of
#: physics.torsion_slip_sign accepts may point against the traction by no more than the rounding
#: of their closed-form sums (relative to their largest magnitude): in exact arithmetic they never
#: do (the kernel is non-negative and falls with the punch radius)
SLIP_SIGN_ROUNDING = 1e-12
# ---- a paraboloid under force control in one constant per contact (issue 29)
#: radius, depth and force of a paraboloid's force-controlled solve (a = cbrt(F/K), d = a²/R,
#: F = (a·d)·4E*/3) against the 30-digit Hertz closed form, relative: the sum of their
#: roundings (K's two, the quotient, cbrt's 0.53 ulp tripled by the cube, a·a, /R, a·d, ·c and
#: c's own) stays below 12 ulp; the numpy passes rest their request check on this bound
HERTZ_FORCE_ROUNDING = 12 * 2.220446049250313e-16

#: a ContactLaw paraboloid's radius from a force, cbrt(F)·cbrt(3/(4 E* kc)), against the
#: 40-digit cube root of the same F·3/(4 E* kc) in the law's own kc and E*: each cube root is
#: glibc's algorithm (contactlab.numeric.cube_root, on every machine: within 3 ulp, 2.86
#: measured), the factor's quotient rounds twice (a third of it through the root) and the
#: product once: at most ~6.9 ulp; measured <= 3.6 ulp on 2 x 10^4 contacts (the same on the
#: C library's cbrt before), 7 ulp the bound
LAW_HERTZ_RADIUS = 7 * 2.220446049250313e-16
