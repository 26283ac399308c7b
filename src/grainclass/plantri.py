"""Locating plantri (Brinkmann and McKay), which enumerates triangulations of the sphere.

The ``passagemath-plantri`` wheel ships the binary inside the package as
``sage_wheels/bin/plantri``; it is found there, never downloaded.
"""

from __future__ import annotations

import importlib.util
import os
import shutil
import stat
from pathlib import Path

from grainclass.errors import GrainclassError


def find_plantri() -> str:
    """Path of an executable plantri: from passagemath-plantri, else from ``PATH``.

    Raises
    ------
    GrainclassError
        When neither is installed (``pip install passagemath-plantri``).
    """
    spec = importlib.util.find_spec("sage_wheels")
    locations = list(spec.submodule_search_locations or []) if spec else []
    for base in locations:
        binary = Path(base) / "bin" / "plantri"
        if binary.is_file():
            if not os.access(binary, os.X_OK):  # some installers drop the run bit
                binary.chmod(binary.stat().st_mode | stat.S_IXUSR | stat.S_IXGRP | stat.S_IXOTH)
            return str(binary)
    found = shutil.which("plantri")
    if found:
        return found
    raise GrainclassError("plantri not found: pip install passagemath-plantri")
