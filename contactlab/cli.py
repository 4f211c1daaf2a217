"""The ``contactlab`` command line.

Subcommands: ``demo`` (an embedded default scene) and ``--version``; later issues add ``run``,
``validate``, ``plan`` and ``formulas``. Exit codes: 0 ok, 2 invalid input, 1 numerical failure.
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


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``contactlab`` console script; returns the exit code."""
    from . import __version__
    from .errors import ContactlabError, ConvergenceError

    parser = argparse.ArgumentParser(prog="contactlab", description=__doc__.splitlines()[0])
    parser.add_argument("--version", action="version", version=f"contactlab {__version__}")
    sub = parser.add_subparsers(dest="command")
    p_demo = sub.add_parser("demo", help="run the embedded default scene")
    p_demo.set_defaults(func=_demo)
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
