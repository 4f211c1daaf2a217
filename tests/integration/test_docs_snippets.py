"""Every Python snippet and every documented ``contactlab`` command in README.md and docs/ runs.

The blocks of one page run in order in one namespace (a later block may use names of an earlier
one), in a temporary folder that holds copies of the repository's examples/ (snippets may read
example data or write result files). A block whose first line is ``# not run: <reason>`` is
skipped: that marker says in the page itself why it cannot run here (e.g. it needs a cluster).
A block whose first line is ``# needs: pandas, xarray`` skips the rest of its page when one of
those optional packages is missing.
Plots are drawn with the non-interactive Agg backend when matplotlib is installed.

Shell blocks (```bash, ```console, ```sh or unlabelled): every line that starts with
``contactlab`` (after an optional ``$``/``pip install ... &&``) runs through
:func:`contactlab.cli.main` in the same kind of folder, with the page's usage notation read the
usual way: ``[--opt]`` is optional (left out), ``a|b`` takes the first choice, ``\\`` continues a
line, ``#`` starts a comment. A generic ``scene.toml`` is a copy of examples/hertz_steel_ball.toml.
It must exit 0.
"""
from __future__ import annotations

import contextlib
import io
import re
import shlex
import shutil
import warnings
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PAGES = [ROOT / "README.md", *sorted(p for p in (ROOT / "docs").rglob("*.md")
                                     if "_build" not in p.parts)]
BLOCK = re.compile(r"^```python\n(.*?)^```", re.S | re.M)


def _blocks(page: Path) -> list[str]:
    return [b for b in BLOCK.findall(page.read_text(encoding="utf-8"))
            if not b.lstrip().startswith("# not run:")]


@pytest.mark.parametrize("page", [p for p in PAGES if _blocks(p)],
                         ids=lambda p: str(p.relative_to(ROOT)))
def test_snippets_run(page, tmp_path, monkeypatch):
    try:
        import matplotlib
        matplotlib.use("Agg")
    except ImportError:
        pass
    shutil.copytree(ROOT / "examples", tmp_path / "examples")
    monkeypatch.chdir(tmp_path)
    from contactlab.registry import registry
    before = {k: set(v) for k, v in registry._session.items()}
    env: dict = {"__name__": "__snippet__"}
    try:
        for i, block in enumerate(_blocks(page)):
            first = block.lstrip().partition("\n")[0]
            if first.startswith("# needs:"):        # optional extras the page's snippets use
                for module in first[len("# needs:"):].split(","):
                    pytest.importorskip(module.strip())
            with warnings.catch_warnings():
                # snippets may show a model's validity warning on purpose
                warnings.simplefilter("ignore")
                exec(compile(block, f"{page.name} block {i + 1}", "exec"), env)
    finally:        # a snippet may register a type for the session: leave the registry as found
        for kind, names in registry._session.items():
            for name in set(names) - before.get(kind, set()):
                registry.unregister(kind, name)


SHELL_LANGUAGES = {"bash", "console", "sh", "shell", ""}


def _fenced(text: str) -> list[tuple[str, str]]:
    """(language, body) of every fenced block, fences paired in order."""
    blocks, lang, body = [], None, []
    for line in text.splitlines():
        if line.startswith("```"):
            if lang is None:
                lang, body = line[3:].strip(), []
            else:
                blocks.append((lang, "\n".join(body)))
                lang = None
        elif lang is not None:
            body.append(line)
    return blocks


def _commands(page: Path) -> list[str]:
    """The documented ``contactlab ...`` command lines of a page, usage notation resolved."""
    out = []
    for lang, block in _fenced(page.read_text(encoding="utf-8")):
        if lang not in SHELL_LANGUAGES or block.lstrip().startswith("# not run:"):
            continue
        for line in block.replace("\\\n", " ").splitlines():
            line = line.split(" #", 1)[0].strip().removeprefix("$ ")
            line = re.sub(r"^pip install .*?&&\s*", "", line)
            if not line.startswith("contactlab"):
                continue
            line = re.sub(r"\s+\[[^\]]*\]", "", line)           # optional parts: left out
            line = re.sub(r"(\S+)\|\S+", r"\1", line)              # a|b: the first choice
            out.append(line)
    return out


_CMD_CASES = [(p, c) for p in PAGES for c in _commands(p)]


@pytest.mark.parametrize("page, command", _CMD_CASES,
                         ids=[f"{p.relative_to(ROOT)}: {c}" for p, c in _CMD_CASES])
def test_documented_commands_run(page, command, tmp_path, monkeypatch):
    try:
        import matplotlib
        matplotlib.use("Agg")
    except ImportError:
        pass
    from contactlab.cli import main
    shutil.copytree(ROOT / "examples", tmp_path / "examples")
    shutil.copy(ROOT / "examples" / "hertz_steel_ball.toml", tmp_path / "scene.toml")
    monkeypatch.chdir(tmp_path)
    argv = shlex.split(command)[1:]
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err), \
            warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            code = main(argv)
        except SystemExit as exc:           # --help / --version
            code = exc.code or 0
    if code == 1 and "pip install 'contactlab[" in err.getvalue() + out.getvalue():
        pytest.skip(f"{command!r} needs an optional extra that is not installed")
    assert code == 0, f"{command!r} exited {code}: {err.getvalue()[-2000:]}"


def test_the_scan_finds_the_documented_commands():
    found = {c for _, c in _CMD_CASES}
    assert "contactlab demo" in found
    assert "contactlab formulas --profile power_law --param n=3 --latex" in found
