"""The example domains and scenes that ship inside the package, found by name.

An installed btplan has no checkout beside it: `btplan plan pick_place` must work from
any folder, so the examples are package data (`btplan.domains`, from the top-level
domains/ folder) and a bare name that is not a file is looked up among them.
"""

from __future__ import annotations

import os
from pathlib import Path


def folder() -> Path:
    """Where the shipped domains are (the checkout's domains/ in an editable install)."""
    from importlib import resources  # here: `btplan plan FILE` starts without it

    return Path(str(resources.files("btplan.domains")))


def scenes() -> Path:
    """The shipped scene files (TOML, named after the domain they set up), package data
    beside the domains."""
    return folder() / "scenes"


def names() -> list[str]:
    """The shipped domains as bare names (file stems without `.bt`, sorted): what `resolve`
    accepts in place of a path."""
    return sorted(p.stem for p in folder().glob("*.bt"))


def resolve(path: str) -> str:
    """`path` itself if it is a file (or '-', or has a folder part); else a shipped domain.

    `pick_place` and `pick_place.bt` name the shipped domains/pick_place.bt when there
    is no such file in the current folder. Anything else is returned unchanged, so a
    missing file is still reported as missing.
    """
    if path == "-" or os.sep in path or Path(path).exists():
        return path
    shipped = folder() / (path if path.endswith(".bt") else f"{path}.bt")
    return str(shipped) if shipped.is_file() else path
