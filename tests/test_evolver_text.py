"""How the compiled tokenizer reads a datafile's text: numbers as Python reads them, line ends,
comments, joined lines and the numbers it leaves to Python."""

from __future__ import annotations

import math

import numpy as np
import pyarrow as pa
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from conftest import EVOLVER_DATA
from grainclass import classify, read_dataset
from grainclass._kernels.evolver.codes import ENTRY_BAD, ENTRY_OK
from grainclass._kernels.evolver.numbers import _parse_float
from grainclass.readers.sniffing import sniff

TWO_CUBES = (EVOLVER_DATA / "two_cubes.fe").read_text()


def _rows(*paths) -> list[dict]:
    batches = read_dataset([str(p) for p in paths])
    return pa.concat_tables(classify(b) for b in batches).to_pylist()


def _parse(text: str) -> tuple[int, float]:
    data = np.frombuffer(text.encode(), np.uint8)
    return _parse_float(data, 0, len(data))


def _agrees_with_python(text: str) -> None:
    """A number the kernel reads is float()'s to the bit; one it refuses, float() refuses."""
    code, value = _parse(text)
    if code == ENTRY_OK:
        expected = float(text)
        assert math.isnan(value) if math.isnan(expected) else value == expected, text
        assert math.copysign(1, value) == math.copysign(1, expected), text
    elif code == ENTRY_BAD:
        with pytest.raises(ValueError, match="could not convert"):
            float(text)


@settings(max_examples=500, deadline=None)
@given(
    st.floats(allow_nan=False),
    st.sampled_from(["{!r}", "{:.6g}", "{:.3e}", "{:+.10f}", "{:.17g}", "{:.1f}", "{:E}"]),
)
def test_numbers_are_read_as_python_reads_them(value, form):
    _agrees_with_python(form.format(value))


@settings(max_examples=500, deadline=None)
@given(st.text(alphabet="0123456789.eE+-_ inafINFAtyTY", min_size=1, max_size=12))
def test_what_python_refuses_is_refused(text):
    _agrees_with_python(text.strip() or "0")


@pytest.mark.parametrize(
    "text",
    ["1", "-0", "+.5", "5.", "1e5", "1E-05", "007.5", "inf", "-Infinity", "nan", "NaN", "1e22"],
)
def test_plain_numbers(text):
    assert _parse(text)[0] == ENTRY_OK
    _agrees_with_python(text)


@pytest.mark.parametrize("text", ["+", ".", "e5", "1e", "1.2.3", "0x10", "in", "--1", "1e+"])
def test_not_numbers(text):
    assert _parse(text)[0] == ENTRY_BAD
    _agrees_with_python(text)


def _same_rows(tmp_path, text: str) -> None:
    path = tmp_path / "variant.fe"
    path.write_bytes(text.encode() if isinstance(text, str) else text)
    plain = tmp_path / "plain.fe"
    plain.write_text(TWO_CUBES)
    keys = ("grain_id", "status", "n_faces", "p_vector", "volume", "area", "error")
    got = [tuple(r[k] for k in keys) for r in _rows(path)]
    want = [tuple(r[k] for k in keys) for r in _rows(plain)]
    assert got == want


@pytest.mark.parametrize(
    "line_end",
    ["\r\n", "\r", "\n\n", " \t\n"],
    ids=["CRLF", "CR", "blank lines", "trailing blanks"],
)
def test_line_ends(tmp_path, line_end):
    _same_rows(tmp_path, TWO_CUBES.replace("\n", line_end))


def test_comments_directives_and_joined_lines(tmp_path):
    text = TWO_CUBES.replace(
        "\nvertices\n", "\n#define SIDE 1\n/* the\ncorners */ vertices // all\n"
    )
    text = text.replace("\nbodies\n1\t1 2 3 4 5 6\n", "\nbodies\n1\t1 2 3 \\\n4 5 6 // the first\n")
    _same_rows(tmp_path, "\ufeff" + text)


def test_section_keywords_with_a_colon(tmp_path):
    """Surface Evolver reads `vertices:` as `vertices` (its own sphere.fe is written so)."""
    text = TWO_CUBES
    for word in ("vertices", "edges", "faces", "bodies"):
        text = text.replace(f"\n{word}\n", f"\n{word}:\n")
    assert text.count(":\n") == 4
    assert sniff(text.encode()) == "evolver"
    _same_rows(tmp_path, text)


def test_a_volume_given_as_an_expression_is_computed_from_the_geometry(tmp_path):
    """Surface Evolver evaluates `volume 2*pi/3`; grainclass does not, and measures the body:
    the two cubes are unit cubes."""
    text = TWO_CUBES.replace("\n1\t1 2 3 4 5 6\n", "\n1\t1 2 3 4 5 6 volume 2*pi/3\n")
    assert text != TWO_CUBES
    path = tmp_path / "expression.fe"
    path.write_text(text)
    rows = _rows(path)
    assert [(r["status"], r["n_faces"]) for r in rows] == [("ok", 6), ("ok", 6)]
    assert [r["volume"] for r in rows] == pytest.approx([1.0, 1.0], rel=1e-12)


def test_numbers_left_to_python(tmp_path):
    """Many digits and underscores: float() reads them, in place."""
    text = TWO_CUBES.replace("\n3\t0\t1\t0\n", "\n3\t0.000000000000000000000000\t1_0e-1\t0\n")
    assert text != TWO_CUBES
    _same_rows(tmp_path, text)


def test_line_numbers_count_every_physical_line(tmp_path):
    """A comment over lines, a joined line and CR LF line ends: the unreadable vertex line is
    named by its line in the file."""
    text = TWO_CUBES.replace("\nvertices\n", "\n/* two\nlines */\nvertices\n")
    text = text.replace("\n3\t1\t1\t0\n", "\n3\t1\t1\t0\t\\\n\tfixed\n")
    text = text.replace("\n12\t2\t0\t1\n", "\n12\t2\tzero\t1\n").replace("\n", "\r\n")
    path = tmp_path / "lines.fe"
    path.write_bytes(text.encode())
    number = text.split("\r\n").index("12\t2\tzero\t1") + 1
    rows = _rows(path)
    assert rows[1]["error"].endswith(
        f"body 2: cannot read the line of its vertex 12 (line {number})"
    )
