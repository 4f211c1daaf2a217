"""The repository's own files, for tests that read every file (no virtualenv, build output or cache).

``git ls-files`` (tracked files plus new files git does not ignore) when the tree is a git
checkout; otherwise a walk that skips hidden folders (``.venv``, ``.git``) and build output.
"""
from __future__ import annotations

import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
_BUILD = {"_build", "auto_examples", "generated", "build", "dist", "__pycache__"}


def repository_files() -> list[Path]:
    """Every file of the repository (absolute paths), ignored and hidden ones excluded."""
    try:
        out = subprocess.run(["git", "ls-files", "--cached", "--others", "--exclude-standard"],
                             cwd=ROOT, capture_output=True, text=True, check=True, timeout=60)
        files = [ROOT / p for p in out.stdout.splitlines() if p]
    except (OSError, subprocess.SubprocessError):
        files = [p for p in ROOT.rglob("*")
                 if not any(part.startswith(".") for part in p.relative_to(ROOT).parts)]
    return [p for p in files if p.is_file() and not (_BUILD & set(p.relative_to(ROOT).parts))
            and ".egg-info" not in str(p)]
