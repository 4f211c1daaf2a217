"""Every Python snippet in README.md and docs/*.md runs as written.

The blocks of one page run in order in one namespace (a later block may use names of an earlier
one), in a temporary folder that holds copies of the repository's examples/ (snippets may read
example data or write result files). A block whose first line is ``# not run: <reason>`` is
skipped: that marker says in the page itself why it cannot run here (e.g. it needs a cluster).
A block whose first line is ``# needs: pandas, xarray`` skips the rest of its page when one of
those optional packages is missing.
Plots are drawn with the non-interactive Agg backend when matplotlib is installed.
"""
from __future__ import annotations

import re
import shutil
import warnings
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]
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
