"""Inputs that ``make fuzz`` found, kept in tests/data/fuzz/findings: each passes the fuzz's own
checks now (no exception but a typed error, no lost row, not slow)."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
FINDINGS = ROOT / "tests" / "data" / "fuzz" / "findings"
FORMATS = {".txt": "adjacency", ".loops": "loops", ".pc": "planar_code", ".voro": "voro",
           ".tess": "neper", ".fe": "evolver", ".tif": "tiff", ".dream3d": "dream3d",
           ".vti": "vti", ".dump": "spparks", ".tesr": "tesr", ".npy": "npy"}  # fmt: skip


def _fuzz():
    spec = importlib.util.spec_from_file_location("fuzz", ROOT / "scripts" / "fuzz.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize("path", sorted(FINDINGS.iterdir()), ids=lambda p: p.name)
def test_a_fuzz_finding_passes_the_fuzz_checks(path):
    finding, _ = _fuzz().run_case(path, FORMATS[path.suffix], path.read_bytes())
    assert finding is None


def test_a_comment_after_blanks_is_no_grain():
    # Found by make fuzz (the checker counted it as a line of a grain): the reader takes "#"
    # after tabs as a comment, and so does the checker now.
    fuzz = _fuzz()
    data = (FINDINGS / "comment-after-blanks.txt").read_bytes()
    assert data.startswith(b"\t\t\t#")
    assert fuzz.data_lines(data) == 4


def test_the_seeds_are_read_without_findings():
    fuzz = _fuzz()
    for path, fmt, _ in fuzz.SEEDS:
        assert fuzz.run_case(path, fmt, path.read_bytes())[0] is None, path
