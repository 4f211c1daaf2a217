"""Export of a :class:`~contactlab.symbolic.formulas.FormulaSet`: LaTeX, Python source, callables.

* :func:`to_latex` — one formula, an ``align*`` block of all, or a complete LaTeX document;
* :func:`to_python` — source of standalone functions (imports only ``math``/``numpy``) a user can
  paste into their own code; parameters become keyword arguments defaulting to their numbers;
* :func:`to_callable` — a fast numeric function (``sympy.lambdify(..., cse=True)``);
* :func:`formulas_command` — the text the ``contactlab formulas`` command prints.
"""
from __future__ import annotations

import keyword
from typing import Any
from collections.abc import Callable

import numpy as np

from ..errors import NotSupportedError, ParameterError
from ..params import as_float_array
from .formulas import FORMULA_DOCS, LATEX_NAMES, SYMBOLS, FormulaSet

__all__ = ["to_latex", "to_python", "to_callable", "formulas_command", "FORMATS", "UNLOADED_AT_ZERO"]

#: formula -> its load variable: at a load <= 0 the bodies are apart and the callable returns 0,
#: as :meth:`contactlab.Contact.normal` does (the closed forms hold for a positive load only)
UNLOADED_AT_ZERO = {"force_of_depth": "d", "radius_of_depth": "d", "stiffness_of_depth": "d",
                    "radius_of_force": "F", "depth_of_force": "F", "stiffness_of_force": "F"}

#: output formats of :func:`formulas_command`
FORMATS = ("text", "latex", "python")


# ====================================================================== LaTeX
def _latex_names(expr: Any) -> dict:
    names = {}
    for s in expr.free_symbols:
        n = str(s)
        if n in LATEX_NAMES:
            names[s] = LATEX_NAMES[n]
        elif "_" in n and n.rsplit("_", 1)[0] in LATEX_NAMES:
            head, tail = n.rsplit("_", 1)
            names[s] = f"{LATEX_NAMES[head]}_{{{tail}}}"
    return names


def expr_latex(expr: Any, *, parseable: bool = False) -> str:
    """LaTeX of one sympy expression.

    ``parseable=True`` writes what :func:`sympy.parsing.latex.parse_latex` reads back: sympy's own
    symbol names, and ``atanh``/``acosh`` in their logarithmic forms (the parser knows no
    ``\\operatorname``).
    """
    import sympy as sp
    from sympy.codegen.cfunctions import log1p
    expr = expr.replace(log1p, lambda z: sp.log(1 + z, evaluate=False))
    if parseable:
        expr = expr.replace(sp.atanh, lambda z: sp.log((1 + z) / (1 - z)) / 2)
        expr = expr.replace(sp.acosh, lambda z: sp.log(z + sp.sqrt(z**2 - 1)))
    # parseable: explicit \\cdot, else the parser reads "v (..)" as a function call
    return sp.latex(expr, symbol_names={} if parseable else _latex_names(expr),
                    ln_notation=False, inv_trig_style="full",
                    mul_symbol="dot" if parseable else None)


def to_latex(fs: FormulaSet, name: str | None = None, *, document: bool = False) -> str:
    """LaTeX of formula ``name`` (``lhs = rhs``), or of all formulas.

    Parameters
    ----------
    fs : FormulaSet
    name : str, optional
        One formula; default all (an ``align*`` environment, one line each).
    document : bool
        Wrap in a complete, compilable LaTeX document with a symbol table.
    """
    names = [name] if name is not None else list(fs)
    lines = []
    for n in names:
        lhs = FORMULA_DOCS.get(n, (n, ""))[0]
        lines.append(f"{lhs} &= {expr_latex(fs[n])}")
    if name is not None and not document:
        return lines[0].replace(" &= ", " = ")
    body = "\\begin{align*}\n" + " \\\\\n".join(lines) + "\n\\end{align*}"
    if not document:
        return body
    rows = []
    for s, (desc, unit) in fs.symbols.items():
        tex = LATEX_NAMES.get(s, s)
        val = next((v for k, v in fs.numbers.items() if str(k) == s), None)
        val_s = "" if val is None else f"{val:.10g}"
        rows.append(f"${tex}$ & {_tex_escape(desc)} & {_tex_escape(unit)} & {val_s} \\\\")
    table = ("\\begin{tabular}{llll}\nsymbol & meaning & unit & value \\\\ \\hline\n"
             + "\n".join(rows) + "\n\\end{tabular}")
    return ("\\documentclass{article}\n\\usepackage{amsmath}\n\\begin{document}\n"
            f"\\section*{{Formulas for {_tex_escape(fs.owner)}}}\n{body}\n\n{table}\n"
            "\\end{document}\n")


def _tex_escape(s: str) -> str:
    for a, b in (("_", r"\_"), ("{", r"\{"), ("}", r"\}"),
                 ("&", r"\&"), ("%", r"\%"), ("#", r"\#"), ("$", r"\$"), ("^", r"\^{}")):
        s = s.replace(a, b)
    return s


# ====================================================================== Python source
def _printer():
    from sympy.printing.numpy import NumPyPrinter

    class _Printer(NumPyPrinter):
        """numpy printer writing Max/Min as nested numpy.maximum/minimum (no functools)."""

        def _nested(self, fn: str, args: Any) -> str:
            out = self._print(args[0])
            for arg in args[1:]:
                out = f"numpy.{fn}({out}, {self._print(arg)})"
            return out

        def _print_Max(self, expr: Any) -> str:
            return self._nested("maximum", expr.args)

        def _print_Min(self, expr: Any) -> str:
            return self._nested("minimum", expr.args)

    return _Printer({"fully_qualified_modules": True, "inline": True,
                     "allow_unknown_functions": False})


def _identifier(name: str) -> str:
    return name + "_" if keyword.iskeyword(name) else name


def _function_source(fs: FormulaSet, name: str) -> str:
    import sympy as sp
    expr = fs[name]
    if expr.has(sp.hyper):
        raise NotSupportedError(
            f"formula {name!r} contains a Gauss hypergeometric function ₂F₁, which math/numpy "
            "lack; use FormulaSet.callable() (scipy) instead.")
    var = fs.variables(name)
    params = fs.parameters(name)
    values = {str(k): v for k, v in fs.numbers.items()}
    args = ", ".join(_identifier(str(v)) for v in var)
    kw = []
    for p in params:
        v = values.get(str(p))
        kw.append(f"{_identifier(str(p))}={v!r}" if v is not None else _identifier(str(p)))
    sig = args + (", *, " + ", ".join(kw) if kw else "")
    if not args and kw:
        sig = "*, " + ", ".join(kw)
    printer = _printer()
    reps, (reduced,) = sp.cse(expr, symbols=sp.numbered_symbols("t_"), optimizations="basic")
    body = [f"    {s} = {printer.doprint(e)}" for s, e in reps]
    body.append(f"    return {printer.doprint(reduced)}")
    desc = FORMULA_DOCS.get(name, ("", name))[1]
    units = "; ".join(f"{s}: {SYMBOLS.get(s, ('', ''))[0]} [{SYMBOLS.get(s, ('', ''))[1]}]"
                      for s in [str(v) for v in var] + [str(p) for p in params] if s in SYMBOLS)
    doc = f'    """{desc}.\n\n    {expr}\n\n    {units}\n    """' if units else f'    """{desc}."""'
    text = "\n".join([f"def {name}({sig}):", doc, *body])
    if "math." in text:
        raise NotSupportedError(f"formula {name!r} needs a function numpy lacks")  # pragma: no cover
    return text


def to_python(fs: FormulaSet, names: Any = None) -> str:
    """Source of standalone Python functions, one per formula (imports only ``numpy``).

    Each function takes the formula's variables (``a``, ``d``, ``r``...) positionally and the
    parameters as keywords defaulting to their known numbers (required keywords when unknown).
    Formulas numpy cannot express (a ₂F₁ pressure for non-integer ``n``) are left out with a
    comment when exporting all, and raise :class:`~contactlab.errors.NotSupportedError` when
    asked for by name.
    """
    explicit = names is not None
    names = [names] if isinstance(names, str) else list(names if explicit else fs)
    parts = [f'"""Formulas for {fs.owner}, exported by contactlab (SI units)."""',
             "import numpy", ""]
    for n in names:
        try:
            parts.append(_function_source(fs, n))
        except NotSupportedError as err:
            if explicit:
                raise
            parts.append(f"# {n}: not exported ({err})")
        parts.append("")
    return "\n\n".join(p for p in parts if p != "") + "\n"


# ====================================================================== callables
def _hyper_numpy(ap: Any, bq: Any, z: Any) -> np.ndarray:
    from scipy.special import hyp2f1
    if len(ap) != 2 or len(bq) != 1:
        raise NotSupportedError(f"hypergeometric function with {len(ap)}, {len(bq)} parameters")
    return hyp2f1(float(ap[0]), float(ap[1]), float(bq[0]), z)


def to_callable(fs: FormulaSet, name: str, **values: float) -> Callable[..., Any]:
    """Numeric function of the variables of formula ``name`` (``lambdify`` with ``cse=True``).

    Raises
    ------
    MissingParameterError
        If a parameter of the formula has no number (supply it as a keyword).
    """
    import sympy as sp
    expr = fs.bound(name, **values)
    var = fs.variables(name)
    fn = sp.lambdify(var, expr, modules=[{"hyper": _hyper_numpy}, "numpy", "scipy"], cse=True)

    names = [str(v) for v in var]
    load = names.index(UNLOADED_AT_ZERO[name]) if UNLOADED_AT_ZERO.get(name) in names else None

    def f(*args: Any) -> Any:
        if len(args) != len(var):
            raise ParameterError(f"formula {name!r} takes {len(var)} argument(s) "
                                 f"({', '.join(names)}); got {len(args)}.")
        arr = [as_float_array(n, v) for n, v in zip(names, args)]
        shape = np.broadcast_shapes(*(v.shape for v in arr)) if arr else ()
        unloaded = np.zeros(shape, bool)
        if load is not None:
            unloaded = np.broadcast_to(arr[load] <= 0, shape)
            arr[load] = np.where(arr[load] > 0, arr[load], 1.0)   # any point of the domain
        for n, v in zip(names, arr):
            if np.any(v < 0):
                raise ParameterError(f"{n} contains {float(v[v < 0].ravel()[0])!r}: the "
                                     f"variables of formula {name!r} are >= 0.")
        with np.errstate(all="ignore"):
            out = np.broadcast_to(np.asarray(fn(*arr), dtype=float), shape)
        out = np.where(unloaded, 0.0, out)
        if np.any(np.isnan(out)):
            i = np.unravel_index(int(np.argmax(np.isnan(out))), shape) if shape else ()
            at = ", ".join(f"{n}={float(np.broadcast_to(v, shape)[i])!r}" for n, v in zip(names, arr))
            raise ParameterError(f"formula {name!r} is not defined at {at}: "
                                 f"{FORMULA_DOCS.get(name, ('', name))[1]}.")
        return out.copy() if shape else float(out)

    f.__name__ = name
    f.__doc__ = f"{FORMULA_DOCS.get(name, ('', name))[1]}: {expr}. Arguments: {', '.join(map(str, var))}."
    f.variables = var  # type: ignore[attr-defined]
    return f


# ====================================================================== CLI helper
def formulas_command(profile: Any, materials: Any = None, fmt: str = "text", *,
                     substitute: bool = True, friction: float | None = None,
                     work_of_adhesion: float | None = None, title: str | None = None) -> str:
    """Text printed by ``contactlab formulas``: all formulas of a profile (and contact).

    Parameters
    ----------
    profile : Profile
    materials : (Material, Material), optional
        With materials the contact formulas get numbers for ``E_star`` and ``G_t``; without, the
        moduli stay symbols.
    fmt : {"text", "latex", "python"}
        ``"latex"`` gives a complete document, ``"python"`` standalone functions.
    substitute : bool
        Insert the known numbers (default) or keep every parameter symbolic.
    friction, work_of_adhesion : float, optional
        Numbers for ``mu`` and ``Delta_gamma``.
    title : str, optional
        What the formulas are "for" in the header (default: the profile's ``repr``).
    """
    from .formulas import contact_formulas
    if fmt not in FORMATS:
        raise ParameterError(f"fmt={fmt!r} is invalid: choose one of {', '.join(FORMATS)}.")
    moduli = None
    if materials is not None:
        first, second = materials
        if not callable(getattr(first, "pair", None)):     # Material.pair: the effective moduli
            raise ParameterError(f"materials[0]={first!r} is invalid: expected a Material "
                                 "(e.g. contactlab.Elastic(E=..., nu=...) or Rigid()).")
        moduli = first.pair(second)
    fs = contact_formulas(profile, moduli, friction=friction, work_of_adhesion=work_of_adhesion)
    if title is not None:
        fs = FormulaSet(dict(fs), fs.numbers, fs.unavailable, title)
    if fmt == "latex":
        return to_latex(fs.substitute() if substitute else fs, document=True)
    if fmt == "python":
        # defaults carry the numbers; the formulas keep their symbols as keyword arguments
        return to_python(fs if substitute else FormulaSet(dict(fs), {}, fs.unavailable, fs.owner))
    shown = fs.substitute() if substitute else fs
    width = max(len(k) for k in shown)
    lines = [f"Formulas for {fs.owner}"]
    lines += [f"  {k:<{width}} = {v}" for k, v in shown.items()]
    if not substitute and fs.numbers:
        lines.append("where")
        lines += [f"  {s} = {v!r}" for s, v in fs.numbers.items()]
    if fs.unavailable:
        lines.append("not available:")
        lines += [f"  {k}: {v}" for k, v in fs.unavailable.items()]
    return "\n".join(lines) + "\n"
