"""The ``contactlab`` command line.

Subcommands: ``run SCENE``, ``validate SCENE``, ``plan SCENE``, ``demo``, ``list`` (registered
profiles, materials and effects with their parameters and units), ``formulas`` (closed-form
formulas of a registered profile as text, LaTeX or Python), ``sweep SCENE --grid ...`` (a
parameter study, see :func:`contactlab.sweep`), ``cost SCENE`` (what accuracy costs: error
against wall time over a ladder of each numeric knob); ``--version``.
Exit codes: 0 ok, 2 invalid scene (or usage), 1 numerical failure. ``--json`` prints one JSON
document on stdout for machines; messages for humans otherwise (errors on stderr).
"""
from __future__ import annotations

import argparse
import json
import sys
import warnings
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from .fit_commands import _cmd_fit, _formulas

__all__ = ["main", "DEMO_SCENE"]

#: The scene ``contactlab demo`` runs: steel ball on a steel flat, preload then oscillating twist.
DEMO_SCENE = """\
[scene]
title = "demo: steel ball on steel flat, preload then oscillating twist"

[profile]
type = "paraboloid"
R = "10 mm"

[materials]
body1 = { type = "elastic", E = "210 GPa", nu = 0.3 }
body2 = { type = "elastic", E = "210 GPa", nu = 0.3 }

[interface]
friction = 0.2

[[load_path]]
ramp = { force = "100 N", steps = 20 }

[[load_path]]
sinusoid = { twist = "2 mrad", cycles = 2, steps_per_cycle = 100 }

[outputs]
method = "exact"
series = ["time", "depth", "force", "radius", "peak_pressure", "twist", "torque", "stick_radius",
          "dissipated_energy"]
"""


def _emit(args: argparse.Namespace, payload: dict[str, Any], text: str) -> None:
    if getattr(args, "json", False):
        print(json.dumps(payload, indent=1))
    elif text:
        print(text)


def _load(args: argparse.Namespace) -> Any:
    from ..scene import Scene
    return Scene.from_toml(args.scene, allow_outside=getattr(args, "allow_outside", False))


def _output_dir(value: str | None, overwrite: bool) -> Path | None:
    """The output folder of ``-o DIR``, created if missing, checked before any work is done.

    Raises
    ------
    ParameterError
        DIR is a file, cannot be created or written, or is not empty and ``--overwrite`` was
        not given (exit 2).
    """
    import os

    from ..errors import ParameterError
    if value is None:
        return None
    d = Path(value)
    if d.exists() and not d.is_dir():
        raise ParameterError(f"-o {value!r} is invalid: it is a file, not a folder; give a folder "
                             "name (created if missing).")
    if d.is_dir() and any(d.iterdir()) and not overwrite:
        raise ParameterError(f"-o {value!r} is invalid: the folder is not empty; choose a new "
                             "folder or pass --overwrite to replace an earlier run's files.")
    try:
        d.mkdir(parents=True, exist_ok=True)
    except OSError as err:
        raise ParameterError(f"-o {value!r} is invalid: the folder cannot be created "
                             f"({err.strerror or type(err).__name__}).") from None
    if not os.access(d, os.W_OK | os.X_OK):
        raise ParameterError(f"-o {value!r} is invalid: the folder is not writable.")
    return d


def _scene_inputs(args: argparse.Namespace, scene: Any) -> list[Path]:
    """Every file a scene reads: the scene file itself and each ``file = ...`` it names (tabulated
    profiles, CSV load histories), resolved against the scene's folder."""
    from ..scene.validate import resolve_file
    found = [Path(args.scene)] if getattr(args, "scene", None) else []

    def walk(node: Any) -> None:
        if isinstance(node, dict):
            for key, value in node.items():
                if key == "file" and isinstance(value, (str, Path)):
                    found.append(resolve_file(value, scene.base_dir))
                else:
                    walk(value)
        elif isinstance(node, (list, tuple)):
            for value in node:
                walk(value)
    walk(scene.to_dict())
    return found


def _same_file(a: Path, b: Path) -> bool:
    import os
    try:
        return os.path.samefile(a, b)
    except OSError:                      # one of them missing: compare where they would be
        return a.resolve() == b.resolve()


def _check_targets(option: str, targets: Sequence[Path], inputs: Sequence[Path],
                   overwrite: bool) -> None:
    """Refuse, before any work, to write over a scene's input (always) or over an existing file
    (without ``--overwrite``).

    Raises
    ------
    ParameterError
        A target is one of ``inputs``, or exists and ``overwrite`` is False (exit 2).
    """
    from ..errors import ParameterError
    for t in targets:
        for i in inputs:
            if _same_file(t, i):
                raise ParameterError(
                    f"{option} is invalid: it would replace or remove {str(t)!r}, which the scene "
                    f"reads ({str(i)!r}); write the outputs to another folder or file (--overwrite "
                    "never replaces a scene's own input).")
        if not overwrite and (t.exists() or t.is_symlink()):
            raise ParameterError(f"{option} is invalid: {str(t)!r} exists; choose another name "
                                 "or pass --overwrite to replace it.")


def _cmd_validate(args: argparse.Namespace) -> int:
    scene = _load(args)
    _emit(args, {"ok": True, "scene": str(args.scene), "steps": scene.history().n_steps},
          f"{args.scene}: valid ({scene.history().n_steps} load steps)")
    return 0


def _cmd_plan(args: argparse.Namespace) -> int:
    plan = _load(args).plan()
    _emit(args, {"ok": True, "plan": plan.to_dict()}, str(plan))
    return 0


def _write_outputs(args: argparse.Namespace, result: Any, outdir: Path | None) -> tuple[list, str]:
    from ..scene.run import record_outputs
    files: list[Path] = []
    notes = ""
    if outdir is not None:
        # the command checked its targets before the run (-o DIR, --overwrite)
        files += result.write(outdir, args.format, overwrite=True)
    if args.plot:
        try:
            files.append(result.plot((outdir or Path(".")) / "plot.png"))
            if outdir is not None:
                record_outputs(outdir, files[-1:])
        except ImportError as err:
            notes = f"note: no plot written ({err})"
    return files, notes


def _run_targets(args: argparse.Namespace, scene: Any) -> Path | None:
    """The output folder of ``run`` (checked), after refusing any output that would replace a
    scene input, or an existing ``plot.png`` in the current folder without ``--overwrite``."""
    from ..scene.run import MANIFEST, OUTPUT_FILES
    inputs = _scene_inputs(args, scene)
    if args.output is not None:
        d = Path(args.output)
        if d.is_dir():
            _check_targets(f"-o {args.output!r}", [d / n for n in (*OUTPUT_FILES, MANIFEST)],
                           inputs, True)
        return _output_dir(args.output, args.overwrite)
    if args.plot:
        _check_targets("--plot", [Path("plot.png")], inputs, args.overwrite)
    return None


def _cmd_run(args: argparse.Namespace) -> int:
    from ..errors import ContactlabError
    scene = _load(args)
    plan = scene.plan()
    if args.plan:
        return _cmd_plan(args)
    outdir = _run_targets(args, scene)    # before the (maybe long) run
    try:
        result = scene.run()
    except ContactlabError as err:
        if getattr(err, "partial", None) is None:
            raise
        return _partial_run(args, err, outdir)
    files, plot_note = _write_outputs(args, result, outdir)
    # the run's warnings (validity, model errors) as text, then the note of a missing plot
    notes = "\n".join([*result.meta.get("notes", ()), *([plot_note] if plot_note else [])])
    if args.json:
        payload = {"ok": True, "files": [str(f) for f in files], "notes": notes}
        payload.update(result.to_dict() if outdir is None else
                       {"plan": plan.to_dict(), "meta": result.meta,
                        "final": {k: float(v[-1]) for k, v in result.series.items()}})
        print(json.dumps(payload, indent=1))
        return 0
    print(f"{scene.title}: {plan.route.replace('_', ' ')} route, computed "
          f"{', '.join(result.meta['computed'])}")
    print(result.table())
    for f in files:
        print(f"wrote {f}")
    if plot_note:               # the warnings were shown as they were raised
        print(plot_note, file=sys.stderr)
    return 0


def _partial_run(args: argparse.Namespace, err: Any, outdir: Path | None) -> int:
    """A run that failed part-way: write what it computed (atomically, with status.json), then
    one line naming the step and the files (or one JSON object), exit 1."""
    from ..errors import ConvergenceError
    part = err.partial
    files = part.write(outdir, args.format, overwrite=True) if outdir is not None else []
    msg = _one_line(err).rstrip(".")
    if files:
        msg += f"; wrote what was computed to {', '.join(str(f) for f in files)}"
    if args.json:
        payload = {"ok": False, "exit": 1, "error": msg, "kind": type(err).__name__,
                   "failed_at": err.failed_at, "files": [str(f) for f in files]}
        if outdir is None:
            payload["partial"] = part.to_dict()
        print(json.dumps(payload, indent=1))
    else:
        what = "numerical failure" if isinstance(err, ConvergenceError) else "run failed"
        print(f"contactlab: {what} ({type(err).__name__}): {msg}", file=sys.stderr)
    return 1


#: the folder ``contactlab demo`` writes its picture into when no ``-o`` is given: a new folder
#: under the current one (``contactlab-demo``, else ``contactlab-demo-2``, ...), never an
#: existing one
DEMO_FOLDER = "contactlab-demo"


def _new_folder(stem: str, tries: int = 1000) -> Path:
    """A folder created now under the current one: ``stem``, else ``stem-2``, ``stem-3``, ..."""
    from ..errors import ParameterError
    for k in range(1, tries + 1):
        d = Path(stem if k == 1 else f"{stem}-{k}")
        try:
            d.mkdir()
            return d
        except FileExistsError:
            continue
        except OSError as err:
            raise ParameterError(f"the demo's output folder {str(d)!r} cannot be created "
                                 f"({err.strerror or type(err).__name__}); give -o DIR.") from None
    raise ParameterError(f"{stem}, {stem}-2, ... {stem}-{tries} all exist: give -o DIR.")


def _cmd_demo(args: argparse.Namespace) -> int:
    from ..errors import NotSupportedError
    from ..scene import Scene
    outdir = _output_dir(args.output, args.overwrite)
    scene = Scene.loads(DEMO_SCENE)
    note = ""
    try:
        result = scene.run()
    except NotSupportedError as err:  # torsion history not in this build: run the preload only
        note = f"note: {err} Showing the preload only."
        data = scene.to_dict()
        data["load_path"] = data["load_path"][:1]
        data["outputs"] = {"series": ["time", "depth", "force", "radius", "peak_pressure"]}
        data.pop("interface", None)
        scene = Scene.from_dict(data)
        result = scene.run()
    files: list[Path] = []
    made = outdir is None
    folder = _new_folder(DEMO_FOLDER) if outdir is None else outdir
    try:
        files.append(result.plot(folder / "contactlab_demo.png"))
    except ImportError as err:
        note = (note + "\n" if note else "") + f"note: no plot written ({err})"
        if made:
            folder.rmdir()                 # the folder made for the plot: empty, not kept
    if args.json:
        payload = result.to_dict()
        payload.update({"ok": True, "files": [str(f) for f in files], "notes": note})
        print(json.dumps(payload, indent=1))
        return 0
    moduli = scene.contact().moduli
    print(scene.title)
    print(f"E* = {moduli.normal / 1e9:.3f} GPa, G_t = {moduli.torsional / 1e9:.3f} GPa")
    print(str(scene.plan()))
    print(_demo_tables(scene, result))
    for f in files:
        print(f"wrote {f}")
    if note:
        print(note)
    return 0


def _demo_tables(scene: Any, result: Any) -> str:
    """Preload table (Hertz numbers) and, when computed, the twist cycle at its quarter points."""
    import numpy as np
    seg = scene.history().segment
    s = result.series
    pre = np.flatnonzero(seg == 0)
    lines = ["preload (exact Hertz through the MDR):",
             f"{'depth [um]':>12} {'force [N]':>12} {'radius [um]':>12} {'p_max [MPa]':>12}"]
    for i in pre[np.linspace(0, pre.size - 1, 5).round().astype(int)]:
        lines.append(f"{s['depth'][i] * 1e6:12.4f} {s['force'][i]:12.4f} "
                     f"{s['radius'][i] * 1e6:12.4f} {s['peak_pressure'][i] / 1e6:12.2f}")
    if "torque" in s:
        tw = np.flatnonzero(seg == 1)
        quarter = max(1, int(scene.to_dict()["load_path"][1]["sinusoid"]["steps_per_cycle"]) // 4)
        lines += ["oscillating twist (exact Masing history):",
                  f"{'step':>6} {'twist [mrad]':>13} {'torque [N mm]':>14} "
                  f"{'stick radius [um]':>18} {'dissipated [uJ]':>16}"]
        for i in tw[quarter - 1::quarter]:
            lines.append(f"{'#' + str(i):>6} {s['twist'][i] * 1e3:13.4f} {s['torque'][i] * 1e3:14.5f} "
                         f"{s['stick_radius'][i] * 1e6:18.3f} {s['dissipated_energy'][i] * 1e6:16.5f}")
    return "\n".join(lines)


def _cmd_cost(args: argparse.Namespace) -> int:
    from ..scene.cost import scene_cost
    scene = _load(args)
    if args.plot:                          # before the (long) ladders
        _check_targets(f"--plot {args.plot!r}", [Path(args.plot)], _scene_inputs(args, scene),
                       args.overwrite)
    report = scene_cost(scene, target=args.target)
    notes = ""
    if args.plot:
        try:
            report.plot(args.plot)
        except ImportError as err:
            notes = f"note: no plot written ({err})"
    _emit(args, {"ok": True, **report.to_dict(), "plot": args.plot if args.plot and not notes
                 else None, "notes": notes}, str(report) + (f"\nwrote {args.plot}" if args.plot
                                                             and not notes else ""))
    if notes and not args.json:
        print(notes, file=sys.stderr)
    return 0


def _cmd_list(args: argparse.Namespace) -> int:
    from ..scene.catalog import catalog, catalog_text
    data = catalog()
    if args.what != "all":
        data = {args.what: data[args.what]}
    _emit(args, {"ok": True, **data}, catalog_text(args.what).rstrip("\n"))
    return 0


def _cmd_sweep(args: argparse.Namespace) -> int:
    from ..sweeps.command import sweep_command
    if args.output is not None:          # the scene's own files are never an output
        from ..scene.validate import resolve_file
        from ..sweeps.grid import parse_axis
        d = Path(args.output)
        scene = _load(args)
        inputs = _scene_inputs(args, scene)
        for spec in args.grid:           # files a grid axis swaps in are read too
            key, values = parse_axis(spec)
            if key.rsplit(".", 1)[-1] == "file":
                inputs += [resolve_file(str(v), scene.base_dir) for v in values]
        _check_targets(f"-o {args.output!r}", [d / "sweep.csv", d / "sweep.parquet"], inputs,
                       True)
    try:
        payload, text = sweep_command(args.scene, args.grid, args.output, scheduler=args.scheduler,
                                      workers=args.workers, progress=not args.json,
                                      on_error=args.on_error,
                                      allow_outside=args.allow_outside,
                                      overwrite=args.overwrite)
    except ImportError as err:           # a missing optional extra (pandas, pyarrow, dask)
        _emit(args, {"ok": False, "exit": 1, "error": str(err), "kind": "ImportError"}, "")
        if not args.json:
            print(f"contactlab: {err}", file=sys.stderr)
        return 1
    _emit(args, payload, text)
    return 0


class _Parser(argparse.ArgumentParser):
    """argparse with the CLI's error contract: one line on stderr (or a JSON object), exit 2."""

    def error(self, message: str) -> Any:
        if "--json" in sys.argv[1:] or getattr(self, "_as_json", False):
            print(json.dumps({"ok": False, "exit": 2, "error": message, "kind": "UsageError"},
                             indent=1))
        else:
            print(f"{self.prog}: {message} (see {self.prog.split()[0]} --help)", file=sys.stderr)
        raise SystemExit(2)


def _parser() -> argparse.ArgumentParser:
    from .._version import __version__
    p = _Parser(prog="contactlab", description=__doc__.splitlines()[0])
    p.add_argument("--version", action="version", version=f"contactlab {__version__}")
    sub = p.add_subparsers(dest="command")

    def add(name: str, func: Any, help_: str, scene: bool = True) -> argparse.ArgumentParser:
        sp = sub.add_parser(name, help=help_)
        sp._as_json = False  # type: ignore[attr-defined]
        if scene:
            sp.add_argument("scene", help="scene file (TOML)")
            sp.add_argument("--allow-outside", action="store_true",
                            help="let relative file names in the scene leave its folder")
        sp.add_argument("--json", action="store_true", help="machine-readable JSON on stdout")
        sp.set_defaults(func=func)
        return sp

    r = add("run", _cmd_run, "run a scene")
    r.add_argument("-o", "--output", metavar="DIR", help="write outputs into DIR")
    r.add_argument("--format", choices=("csv", "json"), default="csv", help="output format")
    r.add_argument("--plot", action="store_true", help="write plot.png (needs matplotlib)")
    r.add_argument("--plan", action="store_true", help="show the plan, do not run")
    r.add_argument("--overwrite", action="store_true",
                   help="write into a non-empty output folder, replacing the files this run "
                   "writes (never a scene's input); without -o, replace ./plot.png")
    add("validate", _cmd_validate, "check a scene, report every problem")
    add("plan", _cmd_plan, "show which effects a scene computes, how and why")
    d = add("demo", _cmd_demo, "run the embedded demo scene", scene=False)
    d.add_argument("-o", "--output", metavar="DIR", help="directory for the demo plot "
                   f"(default: a new folder {DEMO_FOLDER}[-N] in the current one)")
    d.add_argument("--overwrite", action="store_true", help="write into a non-empty DIR")
    co = add("cost", _cmd_cost, "what accuracy costs: each numeric knob over a ladder, error "
             "against wall time, the cheapest setting meeting --target")
    co.add_argument("--target", type=float, default=1e-6, help="relative error to meet "
                    "(default 1e-6)")
    co.add_argument("--plot", metavar="FILE", help="write error against time to FILE "
                    "(needs matplotlib)")
    co.add_argument("--overwrite", action="store_true", help="replace FILE if it exists")
    ls = add("list", _cmd_list, "registered profiles and materials, the effects; with units",
             scene=False)
    ls.add_argument("what", nargs="?", default="all",
                    choices=("all", "profiles", "materials", "effects"), help="what to list")
    sw = add("sweep", _cmd_sweep, "run a scene over a grid of values (serial, all cores or Dask)")
    sw.add_argument("--grid", action="append", default=[], metavar="KEY=A:B:N[:log]",
                    help="an axis (repeatable): scene key path = range or comma list, e.g. "
                    "interface.friction=0.1:0.5:9 or load_path[1].sinusoid.twist=1e-4:1e-2:50:log")
    sw.add_argument("-o", "--output", metavar="DIR",
                    help="write DIR/sweep.csv; DIR/sweep.parquet checkpoints (a rerun resumes)")
    where = sw.add_mutually_exclusive_group()
    where.add_argument("--scheduler", metavar="URL", help="Dask scheduler, e.g. tcp://host:8786")
    where.add_argument("--workers", type=int, metavar="N", help="local processes (1: serial)")
    sw.add_argument("--on-error", choices=("record", "raise"), default="record",
                    help="record failed points (default) or stop at the first")
    sw.add_argument("--overwrite", action="store_true",
                    help="replace an existing DIR/sweep.csv (never a scene's input)")
    ft = add("fit", _cmd_fit, "fit an indentation curve (depth, force): modulus, contact point, "
             "offset, work of adhesion, with standard errors", scene=False)
    ft.add_argument("curve", help="CSV file: depth and force columns (units in the header, e.g. "
                    "'depth [nm], force [nN]'; SI without) and, for a viscoelastic sample, a "
                    "'time' column; or an AFM instrument file (.jpk-force, .ibw, .tab, ...) "
                    "read through afmformats (pip install 'contactlab[afm]')")
    ft.add_argument("--profile", required=True, help="registered profile name, e.g. sphere")
    ft.add_argument("--param", action="append", default=[], metavar="NAME=VALUE",
                    help="profile parameter (repeatable), e.g. R=5e-6")
    ft.add_argument("--sample", required=True, metavar="NAME:K=V,...",
                    help="sample material template, e.g. elastic:E=1e6,nu=0.5 (E: the start)")
    ft.add_argument("--tip", metavar="NAME:K=V,...", help="tip material (default rigid)")
    ft.add_argument("--free", default=None,
                    help="comma-separated names to fit (default E,contact_point; for a "
                    "viscoelastic sample its parameters and contact_point)")
    ft.add_argument("--time", metavar="COLUMN", default=None,
                    help="CSV column of the sample times for a viscoelastic sample (default "
                    "'time'; units in the header, e.g. 'time [ms]')")
    ft.add_argument("--segment", choices=("approach", "retract", "both"), default=None,
                    help="part of an instrument curve (default approach; both for a "
                    "viscoelastic sample)")
    ft.add_argument("--index", type=int, default=0,
                    help="curve of an instrument file holding several (a force map), from 0")
    ft.add_argument("--adhesion", choices=("jkr", "dmt"), default=None, help="adhesive model")
    ft.add_argument("--work-of-adhesion", type=float, default=None,
                    help="fixed work of adhesion, J/m^2 (with --adhesion jkr or dmt)")
    ft.add_argument("-o", "--output", metavar="FILE", help="write data, fit and residuals (CSV)")
    ft.add_argument("--plot", metavar="FILE", help="write data, fit and residuals as a picture")
    ft.add_argument("--overwrite", action="store_true", help="replace existing output files")
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
    return p


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``contactlab`` console script; returns the exit code."""
    try:
        return _main(argv)
    except KeyboardInterrupt:    # a second Ctrl-C while the first was handled
        print("contactlab: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:      # `contactlab ... | head`: the reader left; no traceback
        import os
        try:
            os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        except (OSError, ValueError, AttributeError):
            pass
        return 1


def _main(argv: Sequence[str] | None) -> int:
    from ..errors import (ContactlabError, ConvergenceError, ParameterError, SceneError,
                         UnknownNameError)

    parser = _parser()
    if argv is not None and "--json" in argv:      # usage errors as JSON too
        for action in parser._subparsers._group_actions if parser._subparsers else ():
            for sp in getattr(action, "choices", {}).values():
                sp._as_json = True
        parser._as_json = True  # type: ignore[attr-defined]
    args = parser.parse_args(argv)   # --help/--version exit 0, usage errors exit 2 (SystemExit)
    if not getattr(args, "func", None):
        parser.print_help()
        return 2
    as_json = getattr(args, "json", False)
    try:
        with warnings.catch_warnings():
            warnings.showwarning = _show_warning      # one line per warning, no source echo
            return int(args.func(args))
    except (ParameterError, UnknownNameError) as err:     # invalid command-line input
        if as_json:
            print(json.dumps({"ok": False, "exit": 2, "error": str(err),
                              "kind": type(err).__name__}, indent=1))
        else:
            print(f"contactlab: {_one_line(err)}", file=sys.stderr)
        return 2
    except SceneError as err:
        if as_json:
            print(json.dumps({"ok": False, "exit": 2,
                              "error": _scene_line(err, getattr(args, "scene", None)),
                              "kind": type(err).__name__,
                              "issues": [{"path": p, "value": _plain(v), "allowed": a}
                                         for p, v, a in err.issues]}, indent=1))
        else:
            print(f"contactlab: {_scene_line(err, getattr(args, 'scene', None))}",
                  file=sys.stderr)
        return 2
    except ContactlabError as err:
        if as_json:
            print(json.dumps({"ok": False, "exit": 1, "error": str(err),
                              "kind": type(err).__name__}, indent=1))
        else:
            what = "numerical failure" if isinstance(err, ConvergenceError) else "run failed"
            print(f"contactlab: {what} ({type(err).__name__}): {_one_line(err)}", file=sys.stderr)
        return 1
    except OSError as err:      # a file that cannot be read or written: the user's input
        where = f" {err.filename!r}" if getattr(err, "filename", None) else ""
        msg = f"cannot access{where}: {err.strerror or type(err).__name__}"
        if as_json:
            print(json.dumps({"ok": False, "exit": 2, "error": msg, "kind": type(err).__name__},
                             indent=1))
        else:
            print(f"contactlab: {msg}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:   # Ctrl-C: one line, exit 130 (128 + SIGINT), as shells do
        return _interrupted(args, as_json)
    except Exception as err:    # noqa: BLE001 - a bug: still one line, never a traceback
        msg = (f"internal error ({type(err).__name__}): {_one_line(err)}; please report it with "
               "the command line that caused it")
        if as_json:
            print(json.dumps({"ok": False, "exit": 1, "error": msg, "kind": type(err).__name__},
                             indent=1))
        else:
            print(f"contactlab: {msg}", file=sys.stderr)
        return 1


def _interrupted(args: Any, as_json: bool) -> int:
    """Ctrl-C: one line on stderr (or a JSON object) saying what was kept; exit 130."""
    msg = "interrupted"
    if getattr(args, "command", None) == "sweep" and getattr(args, "output", None):
        store = Path(args.output) / "sweep.parquet"
        if store.is_dir():
            msg += (f"; the points finished so far are kept in {store}: run the same command "
                    "again to resume")
    if as_json:
        try:
            print(json.dumps({"ok": False, "exit": 130, "error": msg,
                              "kind": "KeyboardInterrupt"}, indent=1))
        except (OSError, ValueError):
            pass
    else:
        print(f"contactlab: {msg}", file=sys.stderr)
    return 130


def _show_warning(message: Any, category: type, filename: str, lineno: int, file: Any = None,
                  line: Any = None) -> None:
    print(f"contactlab: {category.__name__}: {_one_line(message)}", file=sys.stderr)


def _scene_line(err: Any, scene: Any) -> str:
    """A scene's problems on one line: ``s.toml: 2 problems: a = 1: expected > 0; b = ...``
    (the full list is in the ``--json`` error object)."""
    issues = getattr(err, "issues", None)
    if not issues:
        return _one_line(err)
    from ..scene.validate import _short
    where = f"{Path(str(scene)).name}: " if scene else ""
    parts = [f"{p or '<scene>'} = {_short(v)}: expected {str(a).rstrip('.')}"
             for p, v, a in issues]
    n = len(parts)
    return " ".join(f"{where}{n} problem{'s' if n > 1 else ''}: {'; '.join(parts)}".split())


def _one_line(err: BaseException) -> str:
    text = " ".join(str(err).split())
    return text or type(err).__name__


def _plain(v: Any) -> Any:
    try:
        json.dumps(v)
        return v
    except (TypeError, ValueError):
        return repr(v)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
