"""Adjacency text: runs of plain lines (``id<TAB>faces``, ASCII) are split by a compiled kernel,
every other run line by line. Both ways must read the same grains from the same text."""

from __future__ import annotations

import io

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import grainclass.readers.adjacency as adjacency
from conftest import EXAMPLES

CUBE = "1 2 3 4;0 4 5 2;0 1 5 3;0 2 5 4;0 3 5 1;1 4 3 2"


def _grains(data: bytes, chunk_size: int) -> list[tuple]:
    """Every grain read from ``data``, batch boundaries aside."""
    grains = []
    for batch in adjacency.read_adjacency(io.BytesIO(data), "x", chunk_size):
        ids = batch.grain_id
        ids = ids.to_pylist() if hasattr(ids, "to_pylist") else list(ids)
        boundary = [None] * len(batch) if batch.boundary is None else batch.boundary.tolist()
        for g in range(len(batch)):
            f0, f1 = batch.face_offsets[g], batch.face_offsets[g + 1]
            offsets = batch.nbr_offsets[f0 : f1 + 1]
            grains.append(
                (
                    ids[g],
                    int(batch.location[g]),
                    batch.neighbors[offsets[0] : offsets[-1]].tolist(),
                    np.diff(offsets).tolist(),
                    batch.parse_errors.get(g),
                    repr(batch.volume[g]),
                    repr(batch.area[g]),
                    boundary[g],
                    # An attribute a batch lacks is None, as when its grain lacks it.
                    {k: v[g] for k, v in batch.attributes.items() if v[g] is not None},
                )
            )
    return grains


def _both_ways(data: bytes, chunk_size: int, monkeypatch) -> tuple[list, list]:
    fast = _grains(data, chunk_size)
    with monkeypatch.context() as patch:
        patch.setattr(adjacency, "_plain_batch", lambda *args: None)
        slow = _grains(data, chunk_size)
    return fast, slow


def test_plain_runs_take_the_kernel(monkeypatch):
    data = "".join(f"g{i}\t{CUBE}\n" for i in range(10)).encode()
    runs = []
    real = adjacency._plain_batch
    monkeypatch.setattr(adjacency, "_plain_batch", lambda *a: runs.append(real(*a)) or runs[-1])
    assert len(_grains(data, 4)) == 10
    assert [run is not None for run in runs] == [True, True, True]


@pytest.mark.parametrize("chunk_size", [1, 3, 1000])
def test_examples_read_alike_both_ways(chunk_size, monkeypatch):
    for name in ("polytopes.txt", "bad-grains.txt"):
        fast, slow = _both_ways((EXAMPLES / name).read_bytes(), chunk_size, monkeypatch)
        assert fast == slow


# Pieces of lines that one way or the other might read differently.
IDS = ["g", " g ", "\x1cg\x1f", "#g", "", " ", "grain é", "a b"]
FACES = [CUBE, f" {CUBE} ", "1 2 3;0 2;x", "", f"{CUBE};", f"{CUBE}\tvolume=2.5", "0 1;;2"]
ENDS = ["\n", "\r\n", "\r\r\n", " \n"]


@settings(max_examples=200, deadline=None)
@given(
    st.lists(
        st.one_of(
            st.tuples(st.sampled_from(IDS), st.sampled_from(FACES), st.sampled_from(ENDS)),
            st.sampled_from(["\n", "# a comment\n", "   \n", "no tab at all\n", "a\tb\tc=d\n"]),
        ),
        min_size=1,
        max_size=12,
    ),
    st.integers(1, 5),
    st.booleans(),
)
def test_any_lines_read_alike_both_ways(lines, chunk_size, last_newline):
    text = "".join(
        line if isinstance(line, str) else f"{line[0]}\t{line[1]}{line[2]}" for line in lines
    )
    if not last_newline:
        text = text.rstrip("\n")
    with pytest.MonkeyPatch.context() as monkeypatch:
        fast, slow = _both_ways(text.encode(), chunk_size, monkeypatch)
    assert fast == slow


@pytest.mark.parametrize(
    "text",
    [
        f"cube\t{CUBE}\t\n".encode(),
        f"cube\t{CUBE} \t \n".encode(),
        f"cube\t{CUBE}\tvolume=1\t\n".encode(),
        f"# gr\xe4ins, in Latin-1\ncube\t{CUBE}\n".encode("latin-1"),
    ],
    ids=["trailing tab", "trailing blanks", "tab after a field", "Latin-1 comment"],
)
def test_what_an_editor_leaves_around_a_grain_is_not_an_error(text):
    (batch,) = adjacency.read_adjacency(io.BytesIO(text), "x", 10)
    assert list(batch.grain_id) == ["cube"]
    assert batch.parse_errors == {}
