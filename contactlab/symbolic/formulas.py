"""Named sympy formulas of a profile and of a contact (theory §2-4, §6).

Every formula is derived on a route that always terminates: power terms through
``κ_n = √π Γ(n/2+1)/Γ(n/2+1/2)`` [H1], the pressure through the hypergeometric form of
theory §3 simplified with :func:`sympy.hyperexpand` (elementary for integer ``n``; a Gauss
``₂F₁`` remains for other ``n``), the other profiles through the closed forms of theory §2.
No open-ended ``integrate``/``solve`` runs. A formula that is not known in closed form is *absent*
and asking for it raises :class:`~contactlab.errors.NotSupportedError` with the reason.

Every profile, built-in or plugin, hands over its closed forms through one hook,
``Profile._sympy_form()``, as a :class:`~contactlab.symbolic.form.SympyForm`; this module knows
no profile class (``symbolic/`` sits below ``profiles/`` and never imports it).

Symbols (all ``positive=True``; :data:`SYMBOLS` documents each): variables ``x r a d F phi
c_stick``; contact parameters ``E_star G_t G_star mu Delta_gamma``; profile parameters named by
their :class:`~contactlab.params.Param` ``symbol`` (``R``, ``c``, ``s``, ``b``...; the exponent
``n`` is always a number because it fixes the form of every formula).

References
----------
V. L. Popov, M. Heß, Facta Univ. Mech. Eng. 12 (2014) 1-14 [H1]; docs/theory (this project).
"""
from __future__ import annotations

from collections.abc import Callable, Iterator, Mapping
from functools import lru_cache
from typing import Any

from ..errors import MissingParameterError, NotSupportedError, UnknownNameError
from .form import SympyForm, symbol
from .transform import kappa_sympy

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
        import difflib      # error path only: ~2 ms of import
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


# ====================================================================== the profile's form
def _form_of(profile: Any) -> SympyForm:
    """The closed forms ``profile`` declares through its one hook, ``_sympy_form()``.

    Built-in and plugin profiles alike: the default ``Profile._sympy_form`` turns the plugin
    shorthands (``_height_sympy``, ``_g_sympy``, ``_g_integral_sympy``, ``power_terms()``) into a
    :class:`~contactlab.symbolic.form.SympyForm`; the built-ins override it.
    """
    hook = getattr(profile, "_sympy_form", None)
    if hook is None:
        return SympyForm(reason=f"{type(profile).__name__} has no symbolic form: define "
                                "power_terms() or _g_sympy(x, **symbols) (see docs/plugins.md)")
    return hook()


# ====================================================================== profile formulas
def _profile_exprs(form: SympyForm) -> tuple[dict, dict]:
    """Profile-only formulas (no moduli) and the reasons for those missing."""
    x, r, a, d = (symbol(v) for v in "xrad")
    out: dict = {}
    missing: dict = {}
    why = form.reason or "not known in closed form"
    height = form.height_piecewise or form.height
    if height:
        out["height"] = height(r)
    else:
        missing["height"] = why
    if form.wall_radius is not None:
        out["g"] = 0 * x
        missing["depth_of_radius"] = missing["radius_of_depth"] = form.reason
        return out, missing
    if form.g:
        out["g"] = (form.g_piecewise or form.g)(x)
        out["depth_of_radius"] = form.g(a)
    else:
        missing["g"] = missing["depth_of_radius"] = why
    if form.g_integral:
        out["g_integral"] = form.g_integral(a)
    else:
        missing["g_integral"] = why
    if form.radius_of_depth:
        out["radius_of_depth"] = form.radius_of_depth(d)
    else:
        missing["radius_of_depth"] = why
    return out, missing


@lru_cache(maxsize=128)
def _profile_formulas_cached(profile: Any) -> FormulaSet:
    form = _form_of(profile)
    exprs, missing = _profile_exprs(form)
    return FormulaSet(exprs, form.values, missing, owner=repr(profile))


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
    """Named sympy formulas of a contact (theory §3, §4, §6).

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
    form = _form_of(profile)
    exprs, missing = _profile_exprs(form)
    _x, r, a, d, F, phi, cs = (symbol(v) for v in VARIABLES)
    E, Gt, mu, dg = symbol("E_star"), symbol("G_t"), symbol("mu"), symbol("Delta_gamma")
    values = dict(form.values)
    if moduli is not None:
        values[E] = float(moduli.normal)
        values[Gt] = float(moduli.torsional)
    if friction is not None:
        values[mu] = float(friction)
    if work_of_adhesion is not None:
        values[dg] = float(work_of_adhesion)
    why = form.reason or "not known in closed form"
    pi = sp.pi

    exprs["torque_no_slip"] = sp.Rational(16, 3) * Gt * a**3 * phi
    exprs["stiffness_of_radius"] = 2 * E * a
    if form.wall_radius is not None:                       # flat punch: a = b at every depth
        b = form.wall_radius
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
            missing[k] = form.reason
        return FormulaSet(exprs, values, missing, owner=repr(profile))

    # ---- normal contact (theory §3)
    if form.g and form.g_integral:
        F_a = 2 * E * (a * form.g(a) - form.g_integral(a))
        if form.power_terms is not None:
            F_a = sp.Add(*[2 * E * kappa_sympy(n) * c * n / (n + 1) * a ** (n + 1)
                           for c, n in form.power_terms])
        exprs["force_of_radius"] = F_a
        if form.radius_of_depth:
            a_d = form.radius_of_depth(d)
            exprs["force_of_depth"] = sp.powsimp(sp.expand_power_base(F_a.subs(a, a_d), force=True),
                                                 force=True)
            exprs["stiffness_of_depth"] = 2 * E * a_d
        else:
            missing["force_of_depth"] = missing["stiffness_of_depth"] = why
        if form.power_terms is not None and len(form.power_terms) == 1:
            c, n = form.power_terms[0]
            a_F = (F * (n + 1) / (2 * E * kappa_sympy(n) * c * n)) ** (1 / (n + 1))
            exprs["radius_of_force"] = a_F
            exprs["depth_of_force"] = form.g(a_F)
            exprs["stiffness_of_force"] = 2 * E * a_F
        else:
            missing["radius_of_force"] = missing["depth_of_force"] = missing["stiffness_of_force"] = (
                "F(a) has no closed-form inverse for this profile")
    else:
        for k in ("force_of_radius", "force_of_depth", "radius_of_force"):
            missing[k] = why
    if form.pressure_shape:
        exprs["pressure"] = E / pi * form.pressure_shape(r, a)
    else:
        missing["pressure"] = why

    # ---- torsion (theory §6): ∫_0^a x² g' dx = a² g(a) - 2 ∫_0^a x g dx
    if form.g and form.xg_integral:
        if form.power_terms is not None:
            x2gp = sp.Add(*[kappa_sympy(n) * c * n / (n + 2) * a ** (n + 2) for c, n in form.power_terms])
        else:
            x2gp = a**2 * form.g(a) - 2 * form.xg_integral(a)
        exprs["torque_full_slip_exact"] = pi / 2 * mu * E * x2gp
        exprs["torque_full_slip_mdr"] = 2 * mu * E * x2gp
        # a stick radius inside a flat centre: g = 0 and ∫_0^c x g = 0 there
        ce = sp.Max(cs, form.flat_radius) if form.flat_radius is not None else cs
        tw = mu * E * (form.g(a) - form.g(ce)) / (4 * Gt * cs)
        exprs["twist_of_stick_radius_mdr"] = tw
        exprs["torque_of_stick_radius_mdr"] = (
            sp.Rational(16, 3) * Gt * tw * cs**3
            + 4 * mu * E * (form.g(a) * (a**2 - cs**2) / 2 - (form.xg_integral(a) - form.xg_integral(ce))))
        if form.power_terms is not None:
            for k in ("twist_of_stick_radius_mdr", "torque_of_stick_radius_mdr"):
                exprs[k] = sp.factor(sp.expand(exprs[k]))
    else:
        for k in ("torque_full_slip_exact", "torque_full_slip_mdr", "twist_of_stick_radius_mdr",
                  "torque_of_stick_radius_mdr"):
            missing[k] = why

    # ---- JKR through the MDR (theory §4)
    if "force_of_radius" in exprs:
        assert form.g is not None   # force_of_radius is derived from g (normal contact above)
        exprs["jkr_depth_of_radius"] = form.g(a) - sp.sqrt(2 * pi * a * dg / E)
        exprs["jkr_force_of_radius"] = exprs["force_of_radius"] - sp.sqrt(8 * pi * a**3 * E * dg)
        one = form.power_terms if form.power_terms is not None and len(form.power_terms) == 1 else None
        if one is not None and one[0][1] > sp.Rational(1, 2):
            c, n = one[0]
            A = 2 * E * kappa_sympy(n) * c * n / (n + 1)
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
