"""The ``contactlab fit`` and ``contactlab formulas`` subcommands (registered by
:func:`contactlab.cli.main`'s parser): fit an indentation curve from a file; print a registered
profile's closed-form formulas as text, LaTeX or Python.
"""
from __future__ import annotations

import argparse
import json
from collections.abc import Sequence
from pathlib import Path
from typing import Any

__all__: list[str] = []


def _parse_assignments(items: Sequence[str], what: str) -> dict[str, float]:
    from ..errors import ParameterError
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


def _cmd_fit(args: argparse.Namespace) -> int:
    """``contactlab fit CURVE``: fit an indentation curve (depth, force; with the sample times
    for a viscoelastic sample) and report the parameters with their standard errors and 95 %
    intervals. CSV files, or AFM instrument files through ``afmformats`` (the extra ``afm``)."""
    import numpy as np

    from .. import fit
    from ..errors import ParameterError
    from ..fit.io import AFM_EXTENSIONS, _read_csv
    from . import _check_targets
    from ..registry import registry
    # every output is checked before any work: none is written when another would be refused
    for option, target in (("-o", args.output), ("--plot", args.plot)):
        if target:
            _check_targets(f"{option} {target!r}", [Path(target)], [Path(args.curve)],
                           args.overwrite)
    profile = registry.create("profile", args.profile, **_parse_assignments(args.param, "--param"))

    def material(spec: str) -> Any:
        name, _, rest = spec.partition(":")
        return registry.create("material", name.strip(),
                               **_parse_assignments([rest] if rest else [], "--material"))

    sample = material(args.sample)
    tip = material(args.tip) if args.tip else None
    visco = bool(getattr(sample, "is_viscoelastic", False))
    time = None
    if str(args.curve).lower().endswith(AFM_EXTENSIONS):
        if args.time is not None:
            raise ParameterError(f"--time {args.time!r} is invalid for an instrument file: its "
                                 "own time channel is used; drop --time.")
        # a viscoelastic fit needs the approach and the retract
        segment = args.segment or ("both" if visco else "approach")
        curve = fit.read_curve(args.curve, segment=segment, index=args.index)
        depth, force = curve.depth, curve.force
        if visco:
            if curve.time is None:
                raise ParameterError(f"{args.curve!r} has no time channel: a viscoelastic "
                                     f"sample ({args.sample!r}) needs the sample times.")
            time = curve.time
    else:
        if args.segment is not None or args.index != 0:
            raise ParameterError("--segment and --index apply to AFM instrument files "
                                 f"({', '.join(AFM_EXTENSIONS)}); a CSV file is read whole.")
        # the columns by name, as read_curve reads them (any order, other columns ignored)
        col = args.time or "time"
        curve = _read_csv(str(args.curve), time=col)
        depth, force = curve.depth, curve.force
        if visco or args.time is not None:
            if curve.time is None:
                raise ParameterError(
                    f"{args.curve!r} has no column {col!r} (columns {curve.meta['columns']}): "
                    + ("a viscoelastic sample needs the sample times, e.g. a column "
                       "'time [ms]' (or name it with --time)." if visco else
                       "--time names the column of sample times."))
            if not visco:
                raise ParameterError(f"--time {col!r} is given but sample={args.sample!r} is "
                                     "elastic: times are used by viscoelastic samples only "
                                     "(e.g. standard_linear_solid:G_inf=...,G_1=...,eta_1=...).")
            time = curve.time
    if args.work_of_adhesion is not None and args.adhesion is None:
        raise ParameterError(f"--work-of-adhesion {args.work_of_adhesion!r} is given without "
                             "--adhesion: it is used by an adhesive fit only; add --adhesion "
                             "jkr (or dmt), or drop it.")
    free = (None if args.free is None
            else tuple(n.strip() for n in args.free.split(",") if n.strip()))
    res = fit.indentation(depth, force, profile, sample=sample, tip=tip, free=free,
                          adhesion=args.adhesion, work_of_adhesion=args.work_of_adhesion,
                          time=time)
    if args.output:
        res.to_csv(args.output, overwrite=args.overwrite)
    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        res.plot().savefig(Path(args.plot))
    ci = res.confidence(0.95)
    if args.json:
        print(json.dumps({"ok": True, "params": res.params, "stderr": res.stderr,
                          "confidence_95": {k: list(v) for k, v in ci.items()},
                          "free": list(res.free), "dof": res.dof, "notes": list(res.notes),
                          "model_error": float(res.model_error)}, indent=1))
        return 0
    units = {"E": "Pa", "contact_point": "m", "force_offset": "N", "work_of_adhesion": "J/m^2"}

    def unit(k: str) -> str:            # viscoelastic names: moduli, viscosities, times
        base = k.split("[")[0]
        return units.get(k) or ("Pa" if base.startswith("G") or base == "moduli" else
                                "Pa s" if base.startswith("eta") else
                                "s" if base in ("relaxation_times", "tau") else "")
    for k in res.free:
        lo, hi = ci[k]
        print(f"{k} = {res.params[k]:.10g} {unit(k)}  (stderr {res.stderr[k]:.3g}; "
              f"95 %: {lo:.8g} .. {hi:.8g})")
    print(f"residual rms = {float(np.sqrt(np.mean(res.residuals ** 2))):.3g} N "
          f"({res.x.size} points, {res.dof} degrees of freedom)")
    return 0


def _formulas(args: argparse.Namespace) -> int:
    from ..errors import ParameterError
    from ..registry import registry
    from ..symbolic.export import formulas_command

    given = _parse_assignments(args.param, "--param")
    cls = registry.get("profile", args.profile)
    specs = tuple(getattr(cls, "params", ()))
    missing = [p for p in specs if p.name not in given]
    # parameters not given stay symbols: placeholders (never shown) stand in for their numbers
    params = {**{p.name: p.typical[0] for p in missing}, **given}
    substitute = not missing and bool(given) and not args.symbolic
    try:
        profile = registry.create("profile", args.profile, **params)
    except (TypeError, ValueError) as err:
        if not missing or set(given) - {p.name for p in specs}:
            raise                     # the user's own values: the message names them
        kinds = ", ".join(f"{p.name} ({p.description})" for p in specs)
        hint = (" It is a measured table: run it in a scene (contactlab run) or load it with "
                "contactlab.profiles.Tabulated.from_csv in Python."
                if args.profile == "tabulated" else
                " Build it in Python, e.g. contact = contactlab.Contact("
                "contactlab.profiles.Polynomial({2: 50.0, 4: 1e6}), materials=...), then "
                "contact.formulas(); one power term is --profile power_law --param n=2."
                if args.profile == "polynomial" else "")
        raise ParameterError(f"profile {args.profile!r} cannot be built from --param NAME=NUMBER "
                             f"values (its parameters: {kinds}).{hint}") from err
    if missing:
        from ..symbolic.formulas import profile_formulas
        bound = {str(s) for s in profile_formulas(profile).numbers}
        fixed = [p.name for p in missing if p.symbol not in bound]
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
    substitute = substitute or bool(materials and not missing and not args.symbolic)
    given_txt = ", ".join(f"{k}={v:g}" for k, v in given.items())
    title = (None if substitute else
             f"{cls.__name__}({given_txt}) (symbolic)" if given else f"{cls.__name__} (symbolic)")
    print(formulas_command(profile, materials, fmt, substitute=substitute,
                           friction=args.friction, work_of_adhesion=args.work_of_adhesion,
                           title=title), end="")
    return 0
