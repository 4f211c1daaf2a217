"""``contactlab formulas`` end to end (in-process main() and one real subprocess)."""
from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

import contactlab as cl
from contactlab.cli import main
from tests import tolerances as TOL


def run(capsys, *args):
    code = main(["formulas", *args])
    out, err = capsys.readouterr()
    return code, out, err


def test_symbolic_text(capsys):
    code, out, _ = run(capsys, "--profile", "paraboloid")
    assert code == 0
    assert out.startswith("Formulas for Paraboloid (symbolic)")
    assert "force_of_depth" in out and "4*E_star*sqrt(R)*d**(3/2)/3" in out


def test_substituted_python_is_executable(capsys):
    code, out, _ = run(capsys, "--profile", "paraboloid", "--param", "R=0.01", "--material",
                       "elastic:E=210e9,nu=0.3", "--material", "rigid", "--python")
    assert code == 0
    ns: dict = {}
    exec(out, ns)   # noqa: S102 - the exported source
    c = cl.Contact(cl.profiles.Paraboloid(R=0.01), materials=(cl.Elastic(210e9, 0.3), cl.Rigid()))
    assert ns["force_of_depth"](1e-6) == pytest.approx(float(c.normal(depth=1e-6).force), rel=TOL.LONG_ARITHMETIC)


def test_latex_document(capsys):
    code, out, _ = run(capsys, "--profile", "cone", "--param", "slope=0.2", "--latex")
    assert code == 0 and out.startswith(r"\documentclass") and "0.2" in out


def test_structural_parameter_required(capsys):
    code, _, err = run(capsys, "--profile", "power_law")
    assert code == 2 and "--param for n" in err
    code, out, _ = run(capsys, "--profile", "power_law", "--param", "n=3,c=2")
    assert code == 0 and "c*r**3" not in out and "2.0*r**3" in out


@pytest.mark.parametrize("args, match", [
    (["--profile", "parabolid"], "Did you mean 'paraboloid'"),
    (["--profile", "paraboloid", "--param", "R"], "NAME=VALUE"),
    (["--profile", "paraboloid", "--param", "R=abc"], "not a number"),
    (["--profile", "paraboloid", "--param", "Q=1"], "not a parameter"),
    (["--profile", "paraboloid", "--param", "R=1", "--material", "rigid"], "give it twice"),
])
def test_bad_input_exit_2(capsys, args, match):
    code, _, err = run(capsys, *args)
    assert code == 2 and match in err


def test_console_entry_subprocess():
    root = Path(cl.__file__).parents[1]
    out = subprocess.run([sys.executable, "-m", "contactlab", "formulas", "--profile", "sphere",
                          "--param", "R=0.01"], capture_output=True, text=True, cwd=root, check=False)
    assert out.returncode == 0, out.stderr
    assert "atanh" in out.stdout and "not available:" in out.stdout


def test_documented_power_law_latex_command(capsys):
    """docs/formulas.md: ``--profile power_law --param n=3 --latex`` keeps c symbolic."""
    code, out, err = run(capsys, "--profile", "power_law", "--param", "n=3", "--latex")
    assert code == 0 and err == ""
    assert r"\documentclass" in out and "c r^{3}" in out and "PowerLaw(n=3) (symbolic)" in out


@pytest.mark.parametrize("profile, match", [
    ("polynomial", "Polynomial\\({2: 50.0"),     # was a TypeError traceback
    ("tabulated", "measured table"),             # was "interpolation=0.001 is invalid"
])
def test_profiles_not_built_from_numbers_exit_2(capsys, profile, match):
    code, out, err = run(capsys, "--profile", profile)
    assert code == 2 and out == "" and "Traceback" not in err
    assert re.search(match, err), err
