"""Shared fixtures: the plantri binary shipped by passagemath-plantri, and example paths."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

import pytest

from grainclass.plantri import find_plantri

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"


@pytest.fixture(scope="session")
def plantri() -> str:
    return find_plantri()


@pytest.fixture(scope="session")
def plantri_output(plantri, tmp_path_factory):
    """``plantri_output(n)``: path of a file holding every triangulation with n vertices."""
    directory = tmp_path_factory.mktemp("plantri")

    def make(n: int, *flags: str) -> Path:
        path = directory / f"plantri{''.join(flags)}-{n}.pc"
        if not path.exists():
            subprocess.run([plantri, *flags, str(n), str(path)], check=True, capture_output=True)
        return path

    return make


def pytest_configure(config):
    # Tests run the real console script in subprocesses; make sure numba's cache is writable.
    os.environ.setdefault("NUMBA_CACHE_DIR", str(ROOT / "build" / "numba-cache"))
