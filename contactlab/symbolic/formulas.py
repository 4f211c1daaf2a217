"""Named sympy formulas of a profile and of a contact (physics.md §2-4, §6).

Every formula is derived on a route that always terminates: power terms through
``κ_n = √π Γ(n/2+1)/Γ(n/2+1/2)`` [H1], the pressure through the hypergeometric form of
physics.md §3 simplified with :func:`sympy.hyperexpand` (elementary for integer ``n``; a Gauss
``₂F₁`` remains for other ``n``), the other profiles through the closed forms of physics.md §2.
No open-ended ``integrate``/``solve`` runs. A formula that is not known in closed form is *absent*
and asking for it raises :class:`~contactlab.errors.NotSupportedError` with the reason.

Symbols (all ``positive=True``; :data:`SYMBOLS` documents each): variables ``x r a d F phi
c_stick``; contact parameters ``E_star G_t G_star mu Delta_gamma``; profile parameters named by
their :class:`~contactlab.params.Param` ``symbol`` (``R``, ``c``, ``s``, ``b``...; the exponent
``n`` is always a number because it fixes the form of every formula).

References
----------
V. L. Popov, M. Heß, Facta Univ. Mech. Eng. 12 (2014) 1-14 [H1]; physics.md (this project).
"""
from __future__ import annotations

import difflib
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field
from functools import lru_cache
from typing import Any

from ..errors import MissingParameterError, NotSupportedError, UnknownNameError

__all__ = ["FormulaSet", "SYMBOLS", "VARIABLES", "symbol", "profile_formulas", "contact_formulas"]

#: name -> (description, SI unit) of every documented symbol
SYMBOLS: dict[str, tuple[str, str]] = {
    "x": ("1D (MDR) coordinate", "m"),
    "r": ("radial coordinate", "m"),
    "a": ("contact radius", "m"),
    "d": ("indentation depth", "m"),
    "F": ("normal force", "N"),
    "phi": ("twist angle", "rad"),
    "c_stick": ("stick radius (torsion)", "m"),
    "E_star": ("effective normal modulus E*", "Pa"),
    "G_t": ("effective torsional modulus G_t = (1/G1 + 1/G2)^-1", "Pa"),
    "G_star": ("effective tangential modulus G*", "Pa"),
    "mu": ("Coulomb friction coefficient", "1"),
    "Delta_gamma": ("work of adhesion Delta gamma", "J/m^2"),
    "R": ("radius of curvature", "m"),
    "c": ("power-law coefficient", "m^(1-n)"),
    "n": ("power-law exponent (always substituted)", "1"),
    "s": ("cone slope tan(beta)", "1"),
    "b": ("flat (punch) radius", "m"),
    "k": ("scale factor", "1"),
}

#: variables of the formulas, in the order they become arguments of exported functions
VARIABLES = ("x", "r", "a", "d", "F", "phi", "c_stick")

#: LaTeX spelling of symbols whose sympy name is not already LaTeX
LATEX_NAMES = {"E_star": "E^{*}", "G_t": "G_{t}", "G_star": "G^{*}", "mu": r"\mu",
               "phi": r"\varphi", "c_stick": r"c_{\mathrm{s}}", "Delta_gamma": r"\Delta\gamma"}

#: name -> (left-hand side in LaTeX, description) of every formula a set may hold
FORMULA_DOCS: dict[str, tuple[str, str]] = {
    "height": (r"f(r)", "profile (gap) f(r), m"),
    "g": (r"g(x)", "MDR-transformed profile g(x), m"),
    "g_integral": (r"\int_0^a g\,dx", "integral of g from 0 to a, m^2"),
    "depth_of_radius": (r"d(a)", "depth at contact radius a (non-adhesive), m"),
    "radius_of_depth": (r"a(d)", "contact radius at depth d, m"),
    "force_of_radius": (r"F(a)", "normal force at contact radius a, N"),
    "force_of_depth": (r"F(d)", "normal force at depth d, N"),
    "radius_of_force": (r"a(F)", "contact radius at normal force F, m"),
    "depth_of_force": (r"d(F)", "depth at normal force F, m"),
    "stiffness_of_radius": (r"k(a)", "incremental normal stiffness dF/dd = 2E*a, N/m"),
    "stiffness_of_depth": (r"k(d)", "incremental normal stiffness at depth d, N/m"),
    "stiffness_of_force": (r"k(F)", "incremental normal stiffness at force F, N/m"),
    "pressure": (r"p(r)", "contact pressure p(r) for 0 <= r < a (or < b for a flat punch), Pa"),
    "torque_no_slip": (r"M_{\mathrm{no\,slip}}", "no-slip torque (16/3) G_t a^3 phi, N m"),
    "torque_full_slip_exact": (r"M_{\mathrm{slide}}",
                               "full-sliding torque, exact: (pi/2) mu E* int_0^a x^2 g' dx, N m"),
    "torque_full_slip_mdr": (r"M_{\mathrm{slide}}^{\mathrm{MDR}}",
                             "full-sliding torque, MDR: 2 mu E* int_0^a x^2 g' dx, N m"),
    "twist_of_stick_radius_mdr": (r"\varphi(c_{\mathrm{s}})",
                                  "MDR twist at stick radius c: 8 G_t phi c = 2 mu E* (d - g(c)), rad"),
    "torque_of_stick_radius_mdr": (r"M(c_{\mathrm{s}})", "MDR torque at stick radius c, N m"),
    "jkr_depth_of_radius": (r"d_{\mathrm{JKR}}(a)", "JKR depth at contact radius a, m"),
    "jkr_force_of_radius": (r"F_{\mathrm{JKR}}(a)", "JKR force at contact radius a, N"),
    "jkr_pull_off_radius": (r"a_{c}", "JKR contact radius at pull-off under force control, m"),
    "jkr_pull_off_force": (r"F_{c}", "JKR pull-off force under force control, N"),
    "jkr_pull_off_depth": (r"d_{c}", "JKR depth at pull-off (flat punch), m"),
}


def symbol(name: str):
    """The positive sympy symbol ``name`` (the same object on every call)."""
    return _symbol(name)


@lru_cache(maxsize=None)
def _symbol(name: str):
    import sympy as sp
    return sp.Symbol(name, positive=True)


def _float(v: float):
    """sympy Float holding exactly the double ``v`` (53 bits; prints as its shortest repr)."""
    import sympy as sp
    return sp.Float(float(v), precision=53)


# ====================================================================== the formula set
class FormulaSet(Mapping):
    """Named sympy expressions with the numbers their parameters stand for.

    A read-only mapping ``name -> sympy expression``; see :data:`FORMULA_DOCS` for the names and
    :data:`SYMBOLS` for the symbols. Formulas not known in closed form are absent; asking for one
    raises :class:`~contactlab.errors.NotSupportedError` with the reason.

    Attributes
    ----------
    numbers : dict
        ``sympy.Symbol -> float`` for the parameters a number is known for.
    unavailable : dict
        ``name -> reason`` of the formulas that are not available.
    owner : str
        ``repr`` of the profile/contact the formulas belong to.

    Examples
    --------
    >>> from contactlab.profiles import Paraboloid
    >>> fs = Paraboloid(R=0.01).formulas()
    >>> fs["g"]
    x**2/R
    >>> float(fs.callable("g")(1e-4))
    1e-06
    """

    def __init__(self, exprs: Mapping[str, Any], values: Mapping[Any, float],
                 unavailable: Mapping[str, str] | None = None, owner: str = "") -> None:
        self._exprs = dict(exprs)
        self.numbers = dict(values)
        self.unavailable = dict(unavailable or {})
        self.owner = owner

    # ---------------------------------------------------------------- mapping protocol
    def __getitem__(self, name: str):
        if name in self._exprs:
            return self._exprs[name]
        if name in self.unavailable:
            raise NotSupportedError(f"formula {name!r} is not available for {self.owner}: "
                                    f"{self.unavailable[name]}")
        known = sorted(set(self._exprs) | set(self.unavailable))
        close = difflib.get_close_matches(name, known, n=3)
        hint = f" Did you mean {', '.join(map(repr, close))}?" if close else ""
        raise UnknownNameError(f"formula {name!r} is unknown.{hint} Available: "
                               f"{', '.join(self._exprs) or 'none'}.")

    def __contains__(self, name: object) -> bool:
        return name in self._exprs

    def get(self, name: str, default: Any = None) -> Any:
        return self._exprs.get(name, default)

    def __iter__(self) -> Iterator[str]:
        return iter(self._exprs)

    def __len__(self) -> int:
        return len(self._exprs)

    def __repr__(self) -> str:
        lines = [f"FormulaSet for {self.owner}:"]
        lines += [f"  {k} = {v}" for k, v in self._exprs.items()]
        if self.numbers:
            lines.append("  where " + ", ".join(f"{s} = {v!r}" for s, v in self.numbers.items()))
        return "\n".join(lines)

    # ---------------------------------------------------------------- symbols
    def variables(self, name: str) -> tuple:
        """The variable symbols of formula ``name`` (in :data:`VARIABLES` order)."""
        free = self[name].free_symbols
        return tuple(symbol(v) for v in VARIABLES if symbol(v) in free)

    def parameters(self, name: str) -> tuple:
        """The parameter (non-variable) symbols of formula ``name``, sorted by name."""
        var = set(self.variables(name))
        return tuple(sorted((s for s in self[name].free_symbols if s not in var), key=str))

    @property
    def symbols(self) -> dict[str, tuple[str, str]]:
        """``name -> (description, unit)`` of every symbol the formulas use."""
        names = sorted({str(s) for e in self._exprs.values() for s in e.free_symbols})
        return {n: SYMBOLS.get(n.rsplit("_", 1)[0] if n not in SYMBOLS else n, ("", "")) for n in names}

    # ---------------------------------------------------------------- substitution
    def _bind(self, overrides: Mapping[str, float]) -> dict:
        vals = dict(self.numbers)
        by_name = {str(s): s for e in self._exprs.values() for s in e.free_symbols}
        for k, v in overrides.items():
            vals[by_name.get(k, symbol(k))] = float(v)
        return vals

    def substitute(self, **values: float) -> "FormulaSet":
        """A new set with every known parameter (plus ``values``, by symbol name) substituted."""
        vals = self._bind(values)
        subs = {s: _float(v) for s, v in vals.items()}
        exprs = {k: e.xreplace(subs) for k, e in self._exprs.items()}
        return FormulaSet(exprs, {}, self.unavailable, self.owner)

    def bound(self, name: str, **values: float):
        """Formula ``name`` with every parameter substituted.

        Raises
        ------
        MissingParameterError
            If a parameter has no number (name it in ``values``).
        """
        vals = self._bind(values)
        expr = self[name]
        var = set(self.variables(name))
        missing = sorted(str(s) for s in expr.free_symbols if s not in var and s not in vals)
        if missing:
            raise MissingParameterError(
                f"formula {name!r} of {self.owner} has unbound parameters {', '.join(missing)}; "
                f"give them as keywords, e.g. callable({name!r}, {missing[0]}=...).")
        return expr.xreplace({s: _float(v) for s, v in vals.items() if s in expr.free_symbols})

    # ---------------------------------------------------------------- export
    def callable(self, name: str, **values: float) -> Callable[..., Any]:
        """Fast numeric function of the variables of ``name`` (``lambdify`` with ``cse``).

        Arguments are the variables in :data:`VARIABLES` order (see :meth:`variables`); the
        parameters are bound to their values (override or supply them as keywords).
        """
        from .export import to_callable
        return to_callable(self, name, **values)

    def latex(self, name: str | None = None, *, document: bool = False) -> str:
        """LaTeX of one formula (``name``), of all (one ``align`` block) or a whole document."""
        from .export import to_latex
        return to_latex(self, name, document=document)

    def python(self, names: Any = None) -> str:
        """Source of standalone Python functions (imports only ``math``/``numpy``)."""
        from .export import to_python
        return to_python(self, names)


# ====================================================================== profile specs
@dataclass
class _Spec:
    """What is known in closed form about a profile (sympy callables of one symbol)."""

    values: dict = field(default_factory=dict)
    height: Callable | None = None
    g: Callable | None = None              # g(x) (outer branch for truncated profiles)
    g_piecewise: Callable | None = None    # g(x) for all x >= 0, if it differs from g
    height_piecewise: Callable | None = None
    g_int: Callable | None = None          # ∫_0^a g dx
    xg_int: Callable | None = None         # ∫_0^a x g dx
    radius_of_depth: Callable | None = None
    pressure_shape: Callable | None = None  # ∫_r^a g'(x)/sqrt(x²-r²) dx
    power: list | None = None               # [(coefficient expr, rational n)]
    wall: Any = None                        # flat punch radius symbol
    flat: Any = None                        # radius of a flat centre (g = 0 inside), symbol
    reason: str = ""                        # why something is missing


def _kappa(n):
    from .transform import kappa_sympy
    return kappa_sympy(n)


def _rational(n: float):
    import sympy as sp
    return sp.nsimplify(n, rational=True)


def _power_spec(terms: list, values: dict) -> _Spec:
    """Spec of ``f = Σ c_i r**n_i`` with sympy coefficients ``c_i`` and rational ``n_i``."""
    import sympy as sp

    def g(x):
        return sp.Add(*[_kappa(n) * c * x**n for c, n in terms])

    def pressure_shape(r, a):
        # n κ_n c a^(n-1) sqrt(z) ₂F₁(1-n/2, 1; 3/2; z), z = 1 - r²/a² (physics.md §3)
        z = sp.Dummy("z", positive=True)
        out = []
        for c, n in terms:
            hyp = sp.hyperexpand(sp.sqrt(z) * sp.hyper([1 - n / 2, 1], [sp.Rational(3, 2)], z))
            hyp = hyp.xreplace({z: (a**2 - r**2) / a**2})
            if not hyp.has(sp.hyper):
                hyp = sp.simplify(hyp)
            out.append(n * _kappa(n) * c * a ** (n - 1) * hyp)
        return sp.Add(*out)

    spec = _Spec(
        values=values, power=terms, g=g,
        height=lambda r: sp.Add(*[c * r**n for c, n in terms]),
        g_int=lambda a: sp.Add(*[_kappa(n) * c * a ** (n + 1) / (n + 1) for c, n in terms]),
        xg_int=lambda a: sp.Add(*[_kappa(n) * c * a ** (n + 2) / (n + 2) for c, n in terms]),
        pressure_shape=pressure_shape)
    if len(terms) == 1:
        c, n = terms[0]
        spec.radius_of_depth = lambda d: (d / (_kappa(n) * c)) ** (1 / n)
    else:
        spec.reason = "a sum of power terms has no closed-form inverse g(a) = d in general"
    return spec


def _coefficient_symbols(n_terms: int) -> list:
    return [symbol("c")] if n_terms == 1 else [symbol(f"c_{i + 1}") for i in range(n_terms)]


def _spec_of(profile: Any) -> _Spec:
    """Closed forms known for ``profile`` (built-ins by class, plugins through their hooks)."""
    import sympy as sp

    from ..profiles import (Cone, FlatPunch, Paraboloid, Polynomial, PowerLaw, Scaled, Sphere,
                            Sum, Tabulated, TruncatedCone, TruncatedParaboloid)
    R, s, b, c = symbol("R"), symbol("s"), symbol("b"), symbol("c")
    t = type(profile)
    if t is Paraboloid:
        return _power_spec([(1 / (2 * R), sp.Integer(2))], {R: profile.R})
    if t is Cone:
        return _power_spec([(s, sp.Integer(1))], {s: profile.slope})
    if t is PowerLaw:
        return _power_spec([(c, _rational(profile.n))], {c: profile.c})
    if t is Polynomial:
        cs = _coefficient_symbols(len(profile.terms))
        return _power_spec([(ci, _rational(n)) for ci, (_, n) in zip(cs, profile.terms)],
                           {ci: cv for ci, (cv, _) in zip(cs, profile.terms)})
    if t is Sphere:
        from sympy.codegen.cfunctions import log1p   # accurate for a << R (numpy.log1p)

        def xg_int(a):
            return (a**3 / 3 * sp.atanh(a / R) + R * a**2 / 6
                    + R**3 / 6 * log1p(-a**2 / R**2))
        return _Spec(values={R: profile.R}, height=lambda r: R - sp.sqrt(R**2 - r**2),
                     g=lambda x: x * sp.atanh(x / R),
                     g_int=lambda a: (a**2 - R**2) / 2 * sp.atanh(a / R) + R * a / 2,
                     xg_int=xg_int,
                     reason="the exact sphere has no closed-form inverse of d = a artanh(a/R) and "
                            "no closed-form pressure (physics.md §3: quadrature)")
    if t is FlatPunch:
        return _Spec(values={b: profile.radius}, wall=b,
                     height=lambda r: sp.Piecewise((0, r <= b), (sp.oo, True)),
                     reason="the contact radius of a flat punch is its radius b at every depth")
    if t is TruncatedParaboloid:
        def xg_int(a):
            root = sp.sqrt(a**2 - b**2)
            return (a * (2 * a**2 - b**2) * root / 8 - b**4 / 8 * sp.acosh(a / b)) / R
        return _Spec(
            values={b: profile.radius, R: profile.R}, flat=b,
            height=lambda r: (r**2 - b**2) / (2 * R),
            height_piecewise=lambda r: sp.Max(r**2 - b**2, 0) / (2 * R),
            g=lambda x: x * sp.sqrt(x**2 - b**2) / R,
            g_piecewise=lambda x: x * sp.sqrt(sp.Max(x**2 - b**2, 0)) / R,
            g_int=lambda a: (a**2 - b**2) ** sp.Rational(3, 2) / (3 * R), xg_int=xg_int,
            radius_of_depth=lambda d: sp.sqrt((b**2 + sp.sqrt(b**4 + 4 * R**2 * d**2)) / 2),
            reason="the pressure of a truncated paraboloid has no closed form here "
                   "(elliptic integrals; physics.md §3: quadrature)")
    if t is TruncatedCone:
        def xg_int(a):
            return s * (a**3 / 3 * sp.acos(b / a)
                        - b / 6 * (a * sp.sqrt(a**2 - b**2) + b**2 * sp.acosh(a / b)))
        return _Spec(
            values={b: profile.radius, s: profile.slope}, flat=b,
            height=lambda r: s * (r - b),
            height_piecewise=lambda r: s * sp.Max(r - b, 0),
            g=lambda x: s * x * sp.acos(b / x),
            g_piecewise=lambda x: s * x * sp.acos(sp.Min(b / x, 1)),
            g_int=lambda a: s * (a**2 / 2 * sp.acos(b / a) - b / 2 * sp.sqrt(a**2 - b**2)),
            xg_int=xg_int,
            reason="a truncated cone has no closed-form inverse of d = s a arccos(b/a) and no "
                   "closed-form pressure (physics.md §3: quadrature)")
    if t is Tabulated:
        return _Spec(reason="a tabulated (measured) profile has no symbolic form; use the numeric "
                            "routes (contact.normal(...))")
    if t is Sum:
        return _sum_spec([_spec_of(term) for term in profile.terms])
    if t is Scaled:
        base = _spec_of(profile.base)
        return _scaled_spec(base, profile.factor)
    return _plugin_spec(profile)


def _renamed(spec: _Spec, suffix: str, clash: set) -> _Spec:
    """``spec`` with the symbols in ``clash`` renamed ``<name>_<suffix>``."""
    sub = {s: symbol(f"{s}_{suffix}") for s in spec.values if s in clash}
    if not sub:
        return spec

    def wrap(fn):
        if fn is None:
            return None
        return lambda *args: fn(*args).xreplace(sub)

    out = _Spec(values={sub.get(k, k): v for k, v in spec.values.items()}, reason=spec.reason,
                wall=sub.get(spec.wall, spec.wall) if spec.wall is not None else None,
                flat=sub.get(spec.flat, spec.flat) if spec.flat is not None else None,
                power=None if spec.power is None else [(c.xreplace(sub), n) for c, n in spec.power])
    for name in ("height", "g", "g_piecewise", "height_piecewise", "g_int", "xg_int",
                 "radius_of_depth", "pressure_shape"):
        setattr(out, name, wrap(getattr(spec, name)))
    return out


def _sum_spec(specs: list[_Spec]) -> _Spec:
    import sympy as sp
    seen: dict = {}
    for sp_ in specs:
        for k in sp_.values:
            seen[k] = seen.get(k, 0) + 1
    clash = {k for k, n in seen.items() if n > 1}
    specs = [_renamed(s_, str(i + 1), clash) for i, s_ in enumerate(specs)]
    values = {k: v for s_ in specs for k, v in s_.values.items()}
    if any(s_.wall is not None for s_ in specs):
        return _Spec(values=values, reason="sums containing a flat punch have no formulas here")

    def total(attr: str, fallback: str | None = None):
        fns = [getattr(s_, attr) or (getattr(s_, fallback) if fallback else None) for s_ in specs]
        if any(f is None for f in fns):
            return None
        return lambda *args: sp.Add(*[f(*args) for f in fns])

    power = None
    if all(s_.power is not None for s_ in specs):
        power = [t for s_ in specs for t in s_.power]
        out = _power_spec(power, values)
        return out
    has_flat = any(s_.flat is not None for s_ in specs)
    return _Spec(values=values, height=total("height"), g=total("g"),
                 g_piecewise=total("g_piecewise", "g"),
                 height_piecewise=total("height_piecewise", "height"),
                 g_int=total("g_int"), xg_int=None if has_flat else total("xg_int"),
                 pressure_shape=total("pressure_shape"),
                 reason="; ".join(filter(None, {s_.reason for s_ in specs}))
                 or "a sum of profiles has no closed-form inverse g(a) = d in general")


def _scaled_spec(base: _Spec, factor: float) -> _Spec:
    k = symbol("k")
    if base.power is not None:
        return _power_spec([(k * c, n) for c, n in base.power], {**base.values, k: factor})

    def wrap(fn):
        return None if fn is None else (lambda *args: k * fn(*args))

    out = _Spec(values={**base.values, k: factor}, reason=base.reason or
                "the inverse of a scaled profile is not derived", wall=base.wall, flat=base.flat)
    for name in ("height", "g", "g_piecewise", "height_piecewise", "g_int", "xg_int",
                 "pressure_shape"):
        setattr(out, name, wrap(getattr(base, name)))
    return out


def _plugin_spec(profile: Any) -> _Spec:
    """Spec of a third-party profile from ``power_terms()`` or its ``_*_sympy`` hooks.

    Hooks (all optional), each receiving the profile's parameters as positive sympy symbols named
    by ``Param.symbol`` (keywords = ``Param.name``): ``_g_sympy(x, **s)``,
    ``_height_sympy(r, **s)``, ``_g_integral_sympy(a, **s)``. A ``_height_sympy`` that is a sum of
    power terms ``c r**n`` gives every power-law formula.
    """
    import sympy as sp
    syms = {p.name: symbol(p.symbol) for p in getattr(profile, "params", ())}
    values = {}
    for p in getattr(profile, "params", ()):
        try:
            values[syms[p.name]] = float(getattr(profile, p.name))
        except (TypeError, ValueError, AttributeError):
            pass
    hooks = {h: getattr(profile, h, None) for h in ("_g_sympy", "_height_sympy", "_g_integral_sympy")}
    if hooks["_height_sympy"] is not None and hooks["_g_sympy"] is None:
        r = symbol("r")
        terms = _as_power_terms(sp.expand(hooks["_height_sympy"](r, **syms)), r)
        if terms is not None:
            return _power_spec(terms, values)
    if hooks["_g_sympy"] is not None or hooks["_height_sympy"] is not None:
        def bind(h):
            fn = hooks[h]
            return None if fn is None else (lambda v: fn(v, **syms))
        return _Spec(values=values, g=bind("_g_sympy"), height=bind("_height_sympy"),
                     g_int=bind("_g_integral_sympy"),
                     reason=f"{type(profile).__name__} supplies only "
                            f"{', '.join(h for h, f in hooks.items() if f is not None)}")
    terms = profile.power_terms() if hasattr(profile, "power_terms") else None
    if terms is not None:
        cs = _coefficient_symbols(len(terms))
        return _power_spec([(ci, _rational(n)) for ci, (_, n) in zip(cs, terms)],
                           {ci: float(cv) for ci, (cv, _) in zip(cs, terms)})
    return _Spec(reason=f"{type(profile).__name__} has no symbolic form: define power_terms() "
                        "or _g_sympy(x, **symbols) (see docs/plugins.md)")


def _as_power_terms(expr: Any, r: Any) -> list | None:
    """``[(c, n)]`` if ``expr`` is ``Σ c r**n`` with ``c`` free of ``r`` and numeric ``n > 0``."""
    import sympy as sp
    terms = []
    for term in sp.Add.make_args(expr):
        coeff, rest = term.as_independent(r, as_Add=False)
        if rest == 1:
            return None
        base, expo = rest.as_base_exp()
        if base != r or not expo.is_number or not expo.is_positive:
            return None
        terms.append((coeff, sp.nsimplify(expo)))
    return terms


# ====================================================================== profile formulas
def _profile_exprs(spec: _Spec) -> tuple[dict, dict]:
    """Profile-only formulas (no moduli) and the reasons for those missing."""
    x, r, a, d = (symbol(v) for v in "xrad")
    out: dict = {}
    missing: dict = {}
    why = spec.reason or "not known in closed form"
    if spec.height_piecewise or spec.height:
        out["height"] = (spec.height_piecewise or spec.height)(r)
    else:
        missing["height"] = why
    if spec.wall is not None:
        out["g"] = 0 * x
        missing["depth_of_radius"] = missing["radius_of_depth"] = spec.reason
        return out, missing
    if spec.g:
        out["g"] = (spec.g_piecewise or spec.g)(x)
        out["depth_of_radius"] = spec.g(a)
    else:
        missing["g"] = missing["depth_of_radius"] = why
    if spec.g_int:
        out["g_integral"] = spec.g_int(a)
    else:
        missing["g_integral"] = why
    if spec.radius_of_depth:
        out["radius_of_depth"] = spec.radius_of_depth(d)
    else:
        missing["radius_of_depth"] = why
    return out, missing


@lru_cache(maxsize=128)
def _profile_formulas_cached(profile: Any) -> FormulaSet:
    spec = _spec_of(profile)
    exprs, missing = _profile_exprs(spec)
    return FormulaSet(exprs, spec.values, missing, owner=repr(profile))


def profile_formulas(profile: Any) -> FormulaSet:
    """Named sympy formulas of a profile: ``height``, ``g``, ``g_integral``, ``depth_of_radius``,
    ``radius_of_depth`` (those known in closed form).

    Parameters
    ----------
    profile : Profile

    Returns
    -------
    FormulaSet
        Symbolic parameters, with their numbers in ``.numbers`` (``.substitute()`` inserts them).
    """
    try:
        return _profile_formulas_cached(profile)
    except TypeError:       # unhashable plugin profile
        return _profile_formulas_cached.__wrapped__(profile)


# ====================================================================== contact formulas
def contact_formulas(profile: Any, moduli: Any = None, *, friction: float | None = None,
                     work_of_adhesion: float | None = None, substitute: bool = False
                     ) -> FormulaSet:
    """Named sympy formulas of a contact (physics.md §3, §4, §6).

    Parameters
    ----------
    profile : Profile
    moduli : EffectiveModuli, optional
        Numbers for ``E_star``, ``G_star``, ``G_t`` (symbolic without them).
    friction, work_of_adhesion : float, optional
        Numbers for ``mu`` and ``Delta_gamma``.
    substitute : bool
        Insert every known number (the variables stay symbols).

    Returns
    -------
    FormulaSet
        Normal contact (``force_of_radius``, ``force_of_depth``, ``radius_of_force``,
        ``stiffness_*``, ``pressure``), torsion (``torque_no_slip``, ``torque_full_slip_exact``,
        ``torque_full_slip_mdr``, ``twist_of_stick_radius_mdr``, ``torque_of_stick_radius_mdr``)
        and JKR (``jkr_depth_of_radius``, ``jkr_force_of_radius``, ``jkr_pull_off_*``) formulas,
        plus the profile's.
    """
    key = (profile, moduli, friction, work_of_adhesion)
    try:
        fs = _contact_formulas_cached(*key)
    except TypeError:
        fs = _contact_formulas_cached.__wrapped__(*key)
    return fs.substitute() if substitute else fs


@lru_cache(maxsize=128)
def _contact_formulas_cached(profile: Any, moduli: Any, friction: float | None,
                             work_of_adhesion: float | None) -> FormulaSet:
    import sympy as sp
    spec = _spec_of(profile)
    exprs, missing = _profile_exprs(spec)
    x, r, a, d, F, phi, cs = (symbol(v) for v in VARIABLES)
    E, Gt, mu, dg = symbol("E_star"), symbol("G_t"), symbol("mu"), symbol("Delta_gamma")
    values = dict(spec.values)
    if moduli is not None:
        values[E] = float(moduli.normal)
        values[Gt] = float(moduli.torsional)
    if friction is not None:
        values[mu] = float(friction)
    if work_of_adhesion is not None:
        values[dg] = float(work_of_adhesion)
    why = spec.reason or "not known in closed form"
    pi = sp.pi

    exprs["torque_no_slip"] = sp.Rational(16, 3) * Gt * a**3 * phi
    exprs["stiffness_of_radius"] = 2 * E * a
    if spec.wall is not None:                       # flat punch: a = b at every depth
        b = spec.wall
        exprs["force_of_depth"] = 2 * E * b * d
        exprs["depth_of_force"] = F / (2 * E * b)
        exprs["stiffness_of_depth"] = 2 * E * b
        exprs["pressure"] = E * d / (pi * sp.sqrt(b**2 - r**2))
        exprs["torque_no_slip"] = sp.Rational(16, 3) * Gt * b**3 * phi
        exprs.pop("stiffness_of_radius")
        exprs["torque_full_slip_exact"] = pi / 2 * mu * E * b**2 * d
        exprs["torque_full_slip_mdr"] = 2 * mu * E * b**2 * d
        exprs["twist_of_stick_radius_mdr"] = mu * E * d / (4 * Gt * cs)
        exprs["torque_of_stick_radius_mdr"] = (sp.Rational(16, 3) * Gt * cs**3
                                               * exprs["twist_of_stick_radius_mdr"]
                                               + 2 * mu * E * d * (b**2 - cs**2))
        exprs["jkr_pull_off_force"] = -sp.sqrt(8 * pi * b**3 * E * dg)
        exprs["jkr_pull_off_depth"] = -sp.sqrt(2 * pi * b * dg / E)
        for k in ("force_of_radius", "radius_of_force", "stiffness_of_force",
                  "jkr_depth_of_radius", "jkr_force_of_radius"):
            missing[k] = spec.reason
        return FormulaSet(exprs, values, missing, owner=repr(profile))

    # ---- normal contact (physics.md §3)
    if spec.g and spec.g_int:
        F_a = 2 * E * (a * spec.g(a) - spec.g_int(a))
        if spec.power is not None:
            F_a = sp.Add(*[2 * E * _kappa(n) * c * n / (n + 1) * a ** (n + 1) for c, n in spec.power])
        exprs["force_of_radius"] = F_a
        if spec.radius_of_depth:
            a_d = spec.radius_of_depth(d)
            exprs["force_of_depth"] = sp.powsimp(sp.expand_power_base(F_a.subs(a, a_d), force=True),
                                                 force=True)
            exprs["stiffness_of_depth"] = 2 * E * a_d
        else:
            missing["force_of_depth"] = missing["stiffness_of_depth"] = why
        if spec.power is not None and len(spec.power) == 1:
            c, n = spec.power[0]
            a_F = (F * (n + 1) / (2 * E * _kappa(n) * c * n)) ** (1 / (n + 1))
            exprs["radius_of_force"] = a_F
            exprs["depth_of_force"] = spec.g(a_F)
            exprs["stiffness_of_force"] = 2 * E * a_F
        else:
            missing["radius_of_force"] = missing["depth_of_force"] = missing["stiffness_of_force"] = (
                "F(a) has no closed-form inverse for this profile")
    else:
        for k in ("force_of_radius", "force_of_depth", "radius_of_force"):
            missing[k] = why
    if spec.pressure_shape:
        exprs["pressure"] = E / pi * spec.pressure_shape(r, a)
    else:
        missing["pressure"] = why

    # ---- torsion (physics.md §6): ∫_0^a x² g' dx = a² g(a) - 2 ∫_0^a x g dx
    if spec.g and spec.xg_int:
        if spec.power is not None:
            x2gp = sp.Add(*[_kappa(n) * c * n / (n + 2) * a ** (n + 2) for c, n in spec.power])
        else:
            x2gp = a**2 * spec.g(a) - 2 * spec.xg_int(a)
        exprs["torque_full_slip_exact"] = pi / 2 * mu * E * x2gp
        exprs["torque_full_slip_mdr"] = 2 * mu * E * x2gp
        # a stick radius inside a flat centre: g = 0 and ∫_0^c x g = 0 there
        ce = sp.Max(cs, spec.flat) if spec.flat is not None else cs
        tw = mu * E * (spec.g(a) - spec.g(ce)) / (4 * Gt * cs)
        exprs["twist_of_stick_radius_mdr"] = tw
        exprs["torque_of_stick_radius_mdr"] = (
            sp.Rational(16, 3) * Gt * tw * cs**3
            + 4 * mu * E * (spec.g(a) * (a**2 - cs**2) / 2 - (spec.xg_int(a) - spec.xg_int(ce))))
        if spec.power is not None:
            for k in ("twist_of_stick_radius_mdr", "torque_of_stick_radius_mdr"):
                exprs[k] = sp.factor(sp.expand(exprs[k]))
    else:
        for k in ("torque_full_slip_exact", "torque_full_slip_mdr", "twist_of_stick_radius_mdr",
                  "torque_of_stick_radius_mdr"):
            missing[k] = why

    # ---- JKR through the MDR (physics.md §4)
    if "force_of_radius" in exprs:
        exprs["jkr_depth_of_radius"] = spec.g(a) - sp.sqrt(2 * pi * a * dg / E)
        exprs["jkr_force_of_radius"] = exprs["force_of_radius"] - sp.sqrt(8 * pi * a**3 * E * dg)
        if spec.power is not None and len(spec.power) == 1 and spec.power[0][1] > sp.Rational(1, 2):
            c, n = spec.power[0]
            A = 2 * E * _kappa(n) * c * n / (n + 1)
            B = sp.sqrt(8 * pi * E * dg)
            a_c = (3 * B / (2 * (n + 1) * A)) ** (1 / (n - sp.Rational(1, 2)))
            exprs["jkr_pull_off_radius"] = sp.powsimp(sp.expand_power_base(a_c, force=True), force=True)
            exprs["jkr_pull_off_force"] = sp.simplify(-B * a_c ** sp.Rational(3, 2) * (2 * n - 1)
                                                      / (2 * (n + 1)))
        else:
            missing["jkr_pull_off_radius"] = missing["jkr_pull_off_force"] = (
                "the pull-off point is closed form only for one power term with n > 1/2; use "
                "contact.pull_off()")
    else:
        missing["jkr_depth_of_radius"] = missing["jkr_force_of_radius"] = why
    return FormulaSet(exprs, values, missing, owner=repr(profile))
