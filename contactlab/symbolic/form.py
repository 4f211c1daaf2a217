"""A profile's sympy form: the closed forms every named formula is derived from.

Every profile hands the formula engine (:mod:`contactlab.symbolic.formulas`) one
:class:`SympyForm` through the same hook, ``Profile._sympy_form()``: the built-ins override it,
and the default implementation builds it from the plugin shorthands (``_height_sympy``,
``_g_sympy``, ``_g_integral_sympy``, ``power_terms()``). This module holds the form and the
builders shared by all of them (power sums through ``κ_n``, sums, scaled forms); it knows no
profile class.

Symbols are positive (:func:`contactlab.symbolic.formulas.symbol`); the exponents of power terms
are rational numbers, never symbols, because they fix the form of every formula.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field, replace
from functools import cache
from typing import Any, cast

from .transform import kappa_sympy

__all__ = ["SympyForm", "symbol", "power_form", "sum_form", "scaled_form", "form_from_hooks",
           "as_power_terms", "coefficient_symbols", "rational"]

#: fields of :class:`SympyForm` holding callables of sympy symbols
CALLABLE_FIELDS = ("height", "g", "g_piecewise", "height_piecewise", "g_integral", "xg_integral",
                   "radius_of_depth", "pressure_shape")


@dataclass
class SympyForm:
    """What is known in closed form about a profile, as callables of sympy symbols.

    Every field is optional; a formula whose ingredients are missing is reported unavailable
    with :attr:`reason`.

    Attributes
    ----------
    values : dict
        ``sympy.Symbol -> float``: the number each parameter symbol stands for.
    height : callable, optional
        ``f(r)`` (for truncated profiles the branch outside the flat centre).
    g : callable, optional
        ``g(x)`` (for truncated profiles the branch outside the flat centre).
    g_piecewise, height_piecewise : callable, optional
        ``g(x)`` and ``f(r)`` for every argument ``>= 0``, when they differ from ``g``/``height``.
    g_integral : callable, optional
        ``∫_0^a g dx`` as a function of ``a``.
    xg_integral : callable, optional
        ``∫_0^a x g dx`` as a function of ``a`` (torsion).
    radius_of_depth : callable, optional
        The contact radius ``a`` with ``g(a) = d`` as a function of ``d``.
    pressure_shape : callable, optional
        ``∫_r^a g'(x)/sqrt(x²-r²) dx`` as a function of ``(r, a)``.
    power_terms : list, optional
        ``[(coefficient, rational n)]`` when ``f = Σ c r**n`` exactly (enables the force inverse
        and the JKR pull-off point for one term).
    wall_radius : sympy.Symbol, optional
        Radius of a vertical wall (flat punch): the contact radius equals it at every depth.
    flat_radius : sympy.Symbol, optional
        Radius of a flat centre (``g = 0`` inside).
    reason : str
        Why the missing formulas are missing.
    """

    values: dict = field(default_factory=dict)
    height: Callable | None = None
    g: Callable | None = None
    g_piecewise: Callable | None = None
    height_piecewise: Callable | None = None
    g_integral: Callable | None = None
    xg_integral: Callable | None = None
    radius_of_depth: Callable | None = None
    pressure_shape: Callable | None = None
    power_terms: list | None = None
    wall_radius: Any = None
    flat_radius: Any = None
    reason: str = ""

    def renamed(self, suffix: str, clash: set) -> "SympyForm":
        """This form with the symbols in ``clash`` renamed ``<name>_<suffix>``."""
        sub = {s: symbol(f"{s}_{suffix}") for s in self.values if s in clash}
        if not sub:
            return self

        def wrap(fn: Callable | None) -> Callable | None:
            if fn is None:
                return None
            return lambda *args: fn(*args).xreplace(sub)

        return replace(
            self, values={sub.get(k, k): v for k, v in self.values.items()},
            wall_radius=(sub.get(self.wall_radius, self.wall_radius)
                         if self.wall_radius is not None else None),
            flat_radius=(sub.get(self.flat_radius, self.flat_radius)
                         if self.flat_radius is not None else None),
            power_terms=(None if self.power_terms is None
                         else [(c.xreplace(sub), n) for c, n in self.power_terms]),
            **cast("dict[str, Any]", {name: wrap(getattr(self, name)) for name in CALLABLE_FIELDS}))


def symbol(name: str):
    """The positive sympy symbol ``name`` (the same object on every call)."""
    return _symbol(name)


@cache
def _symbol(name: str):
    import sympy as sp
    return sp.Symbol(name, positive=True)


def rational(n: float):
    """The exponent ``n`` as an exact sympy rational."""
    import sympy as sp
    return sp.nsimplify(n, rational=True)


def coefficient_symbols(n_terms: int) -> list:
    """``[c]`` for one term, ``[c_1, c_2, ...]`` for more."""
    return [symbol("c")] if n_terms == 1 else [symbol(f"c_{i + 1}") for i in range(n_terms)]


def power_form(terms: list, values: dict) -> SympyForm:
    """Form of ``f = Σ c_i r**n_i`` with sympy coefficients ``c_i`` and rational ``n_i``.

    ``g``, ``∫g``, ``∫xg`` by ``κ_n`` per term [H1]; the pressure through
    ``n κ_n c a^(n-1) sqrt(z) ₂F₁(1-n/2, 1; 3/2; z)``, ``z = 1 - r²/a²``, simplified with
    :func:`sympy.hyperexpand`; the inverse ``a(d)`` for one term.
    """
    import sympy as sp

    def g(x):
        return sp.Add(*[kappa_sympy(n) * c * x**n for c, n in terms])

    def pressure_shape(r, a):
        z = sp.Dummy("z", positive=True)
        out = []
        for c, n in terms:
            hyp = sp.hyperexpand(sp.sqrt(z) * sp.hyper([1 - n / 2, 1], [sp.Rational(3, 2)], z))
            hyp = hyp.xreplace({z: (a**2 - r**2) / a**2})
            if not hyp.has(sp.hyper):
                hyp = sp.simplify(hyp)
            out.append(n * kappa_sympy(n) * c * a ** (n - 1) * hyp)
        return sp.Add(*out)

    form = SympyForm(
        values=values, power_terms=terms, g=g,
        height=lambda r: sp.Add(*[c * r**n for c, n in terms]),
        g_integral=lambda a: sp.Add(*[kappa_sympy(n) * c * a ** (n + 1) / (n + 1) for c, n in terms]),
        xg_integral=lambda a: sp.Add(*[kappa_sympy(n) * c * a ** (n + 2) / (n + 2)
                                       for c, n in terms]),
        pressure_shape=pressure_shape)
    if len(terms) == 1:
        c, n = terms[0]
        form.radius_of_depth = lambda d: (d / (kappa_sympy(n) * c)) ** (1 / n)
    else:
        form.reason = "a sum of power terms has no closed-form inverse g(a) = d in general"
    return form


def sum_form(forms: list[SympyForm]) -> SympyForm:
    """Form of a sum of profiles (the MDR is linear): every quantity is the sum of the terms'.

    Parameter symbols shared by several terms are renamed ``<name>_<term number>``.
    """
    import sympy as sp
    seen: dict = {}
    for f in forms:
        for k in f.values:
            seen[k] = seen.get(k, 0) + 1
    clash = {k for k, n in seen.items() if n > 1}
    forms = [f.renamed(str(i + 1), clash) for i, f in enumerate(forms)]
    values = {k: v for f in forms for k, v in f.values.items()}
    if any(f.wall_radius is not None for f in forms):
        return SympyForm(values=values, reason="sums containing a flat punch have no formulas here")

    def total(attr: str, fallback: str | None = None):
        fns = [getattr(f, attr) or (getattr(f, fallback) if fallback else None) for f in forms]
        if any(fn is None for fn in fns):
            return None
        found = cast("list[Callable]", fns)   # none is None past the test above
        return lambda *args: sp.Add(*[fn(*args) for fn in found])

    if all(f.power_terms is not None for f in forms):
        return power_form([t for f in forms for t in cast(list, f.power_terms)], values)
    has_flat = any(f.flat_radius is not None for f in forms)
    # the reasons in term order (a set would order them by string hash, differently per process)
    reasons = list(dict.fromkeys(f.reason for f in forms if f.reason))
    return SympyForm(values=values, height=total("height"), g=total("g"),
                     g_piecewise=total("g_piecewise", "g"),
                     height_piecewise=total("height_piecewise", "height"),
                     g_integral=total("g_integral"),
                     xg_integral=None if has_flat else total("xg_integral"),
                     pressure_shape=total("pressure_shape"),
                     reason="; ".join(reasons)
                     or "a sum of profiles has no closed-form inverse g(a) = d in general")


def scaled_form(base: SympyForm, factor: float) -> SympyForm:
    """Form of ``k * base`` with the scale factor as the symbol ``k``."""
    k = symbol("k")
    if base.power_terms is not None:
        return power_form([(k * c, n) for c, n in base.power_terms], {**base.values, k: factor})

    def wrap(fn: Callable | None) -> Callable | None:
        return None if fn is None else (lambda *args: k * fn(*args))

    callables: dict[str, Any] = {name: wrap(getattr(base, name)) for name in CALLABLE_FIELDS}
    callables["radius_of_depth"] = None
    return SympyForm(values={**base.values, k: factor},
                     reason=base.reason or "the inverse of a scaled profile is not derived",
                     wall_radius=base.wall_radius, flat_radius=base.flat_radius, **callables)


def form_from_hooks(params: tuple, values: dict, *, height_sympy: Callable | None = None,
                     g_sympy: Callable | None = None, g_integral_sympy: Callable | None = None,
                     power_terms: Callable[[], list | None] | None = None,
                     owner: str = "the profile") -> SympyForm:
    """Form from the plugin shorthands (what ``Profile._sympy_form`` does by default).

    Parameters
    ----------
    params : tuple of Param
        The profile's parameters; each hook gets one positive symbol per parameter, named by
        ``Param.symbol`` and passed by keyword ``Param.name``.
    values : dict
        ``Param.name -> float`` of the parameters that have a number.
    height_sympy, g_sympy, g_integral_sympy : callable, optional
        ``f(r, **symbols)``, ``g(x, **symbols)``, ``∫_0^a g dx (a, **symbols)``. A height that is
        a sum of power terms ``c r**n`` (and no ``g_sympy``) gives every power-law formula.
    power_terms : callable, optional
        Returns ``[(c, n)]`` numbers or None (``Profile.power_terms``); asked only when no hook is
        given, its terms get the symbols ``c`` (one term) or ``c_1, c_2, ...``.
    owner : str
        Class name used in the reasons.
    """
    import sympy as sp

    syms = {p.name: symbol(p.symbol) for p in params}
    numbers = {syms[name]: v for name, v in values.items() if name in syms}
    if height_sympy is not None and g_sympy is None:
        r = symbol("r")
        terms = as_power_terms(sp.expand(height_sympy(r, **syms)), r)
        if terms is not None:
            return power_form(terms, numbers)
    hooks = {"_g_sympy": g_sympy, "_height_sympy": height_sympy,
             "_g_integral_sympy": g_integral_sympy}
    if g_sympy is not None or height_sympy is not None:
        def bind(fn: Callable | None) -> Callable | None:
            return None if fn is None else (lambda v: fn(v, **syms))
        return SympyForm(values=numbers, g=bind(g_sympy), height=bind(height_sympy),
                         g_integral=bind(g_integral_sympy),
                         reason=f"{owner} supplies only "
                                f"{', '.join(h for h, f in hooks.items() if f is not None)}")
    terms = power_terms() if power_terms is not None else None
    if terms is not None:
        cs = coefficient_symbols(len(terms))
        return power_form([(ci, rational(n)) for ci, (_, n) in zip(cs, terms)],
                          {ci: float(cv) for ci, (cv, _) in zip(cs, terms)})
    return SympyForm(reason=f"{owner} has no symbolic form: define power_terms() "
                            "or _g_sympy(x, **symbols) (see docs/plugins.md)")


def as_power_terms(expr: Any, r: Any) -> list | None:
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
