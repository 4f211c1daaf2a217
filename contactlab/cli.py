"""The ``contactlab`` command line.

Subcommands: ``demo`` (an embedded default scene), ``formulas`` (closed-form formulas of a
profile, as text, LaTeX or Python) and ``--version``; later issues add ``run``, ``validate``,
``plan``. Exit codes: 0 ok, 2 invalid input, 1 numerical failure.
"""
from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

__all__ = ["main"]


def _demo(args: argparse.Namespace) -> int:
    import numpy as np

    from . import Contact, Elastic
    from .profiles import Paraboloid

    steel = Elastic(E=210e9, nu=0.3)
    ball = Paraboloid(R=0.01)
    contact = Contact(ball, materials=(steel, steel))
    depths = np.array([0.25, 0.5, 1.0, 2.0, 4.0]) * 1e-6
    s = contact.normal(depth=depths)
    print("contactlab demo: steel sphere (R = 10 mm) on a steel flat, E = 210 GPa, nu = 0.3")
    print(f"effective modulus E* = {contact.moduli.normal / 1e9:.3f} GPa (exact Hertz via the MDR)")
    print(f"{'depth [um]':>12} {'force [N]':>12} {'radius [um]':>12} {'p_max [MPa]':>12}")
    for d, f, a, p in zip(s.depth, s.force, s.radius, s.peak_pressure):
        print(f"{d * 1e6:12.3f} {f:12.4f} {a * 1e6:12.3f} {p / 1e6:12.2f}")
    return 0


def _parse_assignments(items: Sequence[str], what: str) -> dict[str, float]:
    from .errors import ParameterError
    out: dict[str, float] = {}
    for item in items:
        for part in filter(None, item.split(",")):
            key, sep, value = part.partition("=")
            if not sep or not key.strip():
                raise ParameterError(f"{what} {part!r} is invalid: expected NAME=VALUE, e.g. R=0.01.")
            try:
                out[key.strip()] = float(value)
            except ValueError as err:
                raise ParameterError(f"{what} {part!r} is invalid: {value!r} is not a number.") from err
    return out


def _formulas(args: argparse.Namespace) -> int:
    from .errors import ParameterError
    from .registry import registry
    from .symbolic.export import formulas_command

    params = _parse_assignments(args.param, "--param")
    cls = registry.get("profile", args.profile)
    substitute = bool(params) and not args.symbolic
    if not params:
        # fully symbolic: placeholders (never shown) for every parameter that becomes a symbol
        params = {p.name: p.typical[0] for p in getattr(cls, "params", ())}
    profile = registry.create("profile", args.profile, **params)
    if not args.param:
        from .symbolic.formulas import profile_formulas
        bound = {str(s) for s in profile_formulas(profile).numbers}
        fixed = [p.name for p in cls.params if p.symbol not in bound]
        if fixed:
            raise ParameterError(f"profile {args.profile!r}: give --param for {', '.join(fixed)} "
                                 "(they fix the form of the formulas), e.g. --param n=3.")
    materials = None
    if args.material:
        if len(args.material) != 2:
            raise ParameterError(f"--material was given {len(args.material)} time(s): give it "
                                 "twice (both bodies), e.g. --material elastic:E=210e9,nu=0.3 "
                                 "--material rigid.")
        materials = []
        for spec in args.material:
            name, _, rest = spec.partition(":")
            materials.append(registry.create("material", name.strip(),
                                             **_parse_assignments([rest], "--material")))
    fmt = "latex" if args.latex else "python" if args.python else "text"
    substitute = substitute or bool(materials and not args.symbolic)
    print(formulas_command(profile, materials, fmt, substitute=substitute,
                           friction=args.friction, work_of_adhesion=args.work_of_adhesion,
                           title=None if args.param else f"{cls.__name__} (symbolic)"), end="")
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``contactlab`` console script; returns the exit code."""
    from . import __version__
    from .errors import ContactlabError, ConvergenceError

    parser = argparse.ArgumentParser(prog="contactlab", description=__doc__.splitlines()[0])
    parser.add_argument("--version", action="version", version=f"contactlab {__version__}")
    sub = parser.add_subparsers(dest="command")
    p_demo = sub.add_parser("demo", help="run the embedded default scene")
    p_demo.set_defaults(func=_demo)
    p_form = sub.add_parser("formulas", help="print the closed-form formulas of a profile/contact",
                            description="Closed-form MDR formulas (normal, torsion, JKR) of a "
                            "registered profile, as text, a LaTeX document or Python source.")
    p_form.add_argument("--profile", required=True, help="registered profile name, e.g. paraboloid")
    p_form.add_argument("--param", action="append", default=[], metavar="NAME=VALUE",
                        help="profile parameter (repeatable; comma-separated allowed); without "
                        "any, the formulas stay symbolic")
    p_form.add_argument("--material", action="append", default=[], metavar="NAME[:K=V,...]",
                        help="body material, give twice, e.g. elastic:E=210e9,nu=0.3 and rigid")
    p_form.add_argument("--friction", type=float, default=None, help="friction coefficient mu")
    p_form.add_argument("--work-of-adhesion", type=float, default=None,
                        help="work of adhesion Delta_gamma, J/m^2")
    p_form.add_argument("--symbolic", action="store_true",
                        help="keep every parameter symbolic (numbers only as Python defaults)")
    fmt = p_form.add_mutually_exclusive_group()
    fmt.add_argument("--latex", action="store_true", help="a complete LaTeX document")
    fmt.add_argument("--python", action="store_true", help="standalone Python functions")
    p_form.set_defaults(func=_formulas)
    args = parser.parse_args(argv)
    if not getattr(args, "func", None):
        parser.print_help()
        return 2
    try:
        return int(args.func(args))
    except ConvergenceError as err:
        print(f"contactlab: numerical failure: {err}", file=sys.stderr)
        return 1
    except ContactlabError as err:
        print(f"contactlab: {err}", file=sys.stderr)
        return 2


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
