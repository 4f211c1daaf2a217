"""Nothing in the repository refers to files outside it.

The documentation must stand alone: no pointer to notes that are not in the repository, no path
of a developer's machine, in code, docstrings, comments, docs, examples or benchmark logs.
"""
from __future__ import annotations

import re
from pathlib import Path

from tests.repo_files import repository_files

ROOT = Path(__file__).resolve().parents[2]
SUFFIXES = {".py", ".md", ".toml", ".txt", ".cfg", ".log", ".csv", ".rst", ".json", ".yml"}
SKIP = {".git", "_build", "auto_examples", "generated", "build", "dist", "__pycache__",
        ".pytest_cache", ".hypothesis"}
# written in pieces so this file does not match itself
OUTSIDE = re.compile("|".join([r"physics" + r"\.md", r"/" + r"work/", r"/" + r"home/\w",
                               r"/" + r"Users/\w", r"[A-Z]:\\" + r"\\Users"]))


def test_no_reference_to_files_outside_the_repository():
    hits = []
    for path in repository_files():      # the virtualenv CI makes inside the tree is not ours
        if path.suffix not in SUFFIXES or SKIP & set(path.relative_to(ROOT).parts):
            continue
        for i, line in enumerate(path.read_text(encoding="utf-8", errors="replace").splitlines()):
            if OUTSIDE.search(line):
                hits.append(f"{path.relative_to(ROOT)}:{i + 1}: {line.strip()[:100]}")
    assert not hits, "references to files outside the repository:\n" + "\n".join(hits)
