"""The census path: planar_code classified straight from its bytes, counted without per-grain rows.

It must agree, grain for grain, with the CSR path that ``classify`` takes (itself checked
against the reference implementation and the paper), on plantri's triangulations, on planar
graphs that are not triangulations, and on damaged records.
"""

from __future__ import annotations

import io
import os
import random
import struct
import sys

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from grainclass.options import ReadOptions
from grainclass.pipeline import tallies
from grainclass.readers.planar_code import PlanarCodeRecords, read_planar_code
from grainclass.summary import group_rows, merge_tallies, summarize, tally_batch
from strategies import bipyramid, planar_code_record, rotation_lists


def _tallies(data: bytes, raw: bool, chunk_size: int) -> list[pd.DataFrame]:
    batches = read_planar_code(io.BytesIO(data), "x", chunk_size, raw=raw)
    return [tally_batch(b).counts for b in batches]


def _assert_same(data: bytes) -> int:
    """Records counted from their bytes (``summary._tally_records``) and from CSR lists (the
    per-grain codes grouped with numpy) agree in batches and one record at a time, where each
    tally is the group of its one grain; returns the number of records."""
    _assert_same_tallies(data)
    raw, csr = _tallies(data, True, 1), _tallies(data, False, 1)
    assert len(raw) == len(csr)
    for a, b in zip(raw, csr, strict=True):
        pd.testing.assert_frame_equal(a, b)
    return len(raw)


def _assert_same_tallies(data: bytes, chunk_size: int = 1000) -> pd.DataFrame:
    """The counts of :func:`_assert_same`, batch by batch, merged; returns them."""
    counted = merge_tallies(_tallies(data, True, chunk_size))
    pd.testing.assert_frame_equal(counted, merge_tallies(_tallies(data, False, chunk_size)))
    return counted


def _record_ends(data: bytes) -> list[int]:
    """Where each complete 1-byte record ends: after its n-th zero (plain Python)."""
    ends, pos = [], 0
    while pos < len(data):
        n, end, zeros = data[pos], pos + 1, 0
        while zeros < n and end < len(data):
            zeros += data[end] == 0
            end += 1
        if zeros < n:
            break
        ends.append(end)
        pos = end
    return ends


@st.composite
def _near_triangulation_records(draw) -> bytes:
    """A 1-byte record that is, or nearly is, as long as a triangulation's: n lists whose
    lengths add up to 6n - 12 give or take one, empty lists and zeros where a triangulation's
    last list would end included."""
    n = draw(st.integers(1, 20))
    total = max(0, 6 * n - 12 + draw(st.sampled_from([-1, 0, 0, 1])))
    cuts = sorted(draw(st.lists(st.integers(0, total), min_size=n - 1, max_size=n - 1)))
    sizes = [b - a for a, b in zip([0, *cuts], [*cuts, total], strict=True)]
    entry = st.integers(1, 255)
    lists = [draw(st.lists(entry, min_size=size, max_size=size)) for size in sizes]
    return bytes([n] + [x for nbrs in lists for x in [*nbrs, 0]])


@settings(max_examples=300, deadline=None)
@given(
    st.lists(_near_triangulation_records(), min_size=1, max_size=12),
    st.integers(0, 5),
    st.integers(0, 15),
)
def test_records_are_cut_where_their_nth_zero_is(records, cut, offset):
    """From any offset into a buffer (the bytes before it 0 or not), whatever its alignment."""
    from grainclass._kernels.planar_code import _scan

    data = b"".join(records)[: -cut or None]
    whole = np.full(offset + len(data), offset % 2, np.uint8)
    whole[offset:] = np.frombuffer(data, np.uint8)
    starts = np.empty(len(records) + 1, np.int64)
    found, _, _, consumed = _scan(whole[offset:], False, len(records), starts)
    ends = _record_ends(data)
    assert starts[1 : found + 1].tolist() == ends
    assert consumed == (ends[-1] if ends else 0)


@pytest.mark.parametrize("n", range(4, 12))
def test_bytes_and_csr_paths_agree_on_every_triangulation(plantri_output, n):
    data = plantri_output(n).read_bytes()
    assert _assert_same(data) > 0


@pytest.mark.parametrize(("n", "flags"), [(8, "-p"), (9, "-pc2"), (7, "-pc1m1")])
def test_bytes_and_csr_paths_agree_on_planar_graphs_that_are_not_triangulations(
    plantri_output, n, flags
):
    data = plantri_output(n, flags).read_bytes()
    counted = _assert_same_tallies(data)
    assert set(counted["status"]) > {"ok"}  # most are not simple grains


def test_bytes_and_csr_paths_agree_on_damaged_records(plantri_output):
    data = plantri_output(11).read_bytes()
    header = b">>planar_code<<"
    body = data[len(header) :]
    ends = _record_ends(body)
    assert ends[-1] == len(body)
    records = [bytearray(body[a:b]) for a, b in zip([0, *ends[:-1]], ends, strict=True)]
    rng = random.Random(20261122)
    damaged = []
    for record in rng.sample(records, 400):
        entries = [i for i in range(1, len(record)) if record[i]]
        at = rng.choice(entries)
        record[at] = rng.choice([record[at] % 10 + 1, 11, 12, 70, 255])  # other, or out of range
        damaged.append(bytes(record))
    assert _assert_same(header + b"".join(damaged)) == 400


def test_large_and_wide_records_take_the_general_way():
    prism_dual = bipyramid(68)  # 70 faces: beyond the 64-face bitsets
    wide = b"\x00" + struct.pack("<H", 6)
    for nbrs in bipyramid(4):
        wide += b"".join(struct.pack("<H", x + 1) for x in nbrs) + struct.pack("<H", 0)
    data = b">>planar_code<<" + planar_code_record(prism_dual) + planar_code_record(bipyramid(5))
    # The 68- and 5-gonal prisms: ok, flag and fundamental, no triangular faces, split types
    # (k - 2) // 2 (see the test above).
    columns = ["n_faces", "status", "family", "round_k", "split_k", "triangles", "count"]
    counted = _assert_same_tallies(data)
    assert counted[columns].values.tolist() == [
        [7, "ok", "flag", 0, 1, 0, 1],
        [70, "ok", "flag", 0, 33, 0, 1],
    ]
    assert _assert_same(data) == 2
    (cube,) = _tallies(wide, True, 10)
    assert cube[columns].values.tolist() == [[6, "ok", "flag", 0, 1, 0, 1]]  # split type 1:1


def _truncated_prism(k: int, t: int) -> list[list[int]]:
    """The dual of the k-gonal prism truncated t times in a chain (each new triangle cut at one
    of its corners), as rotation lists: a flag grain with k + 2 + t faces and one truncation
    tree of depth t."""
    lists = bipyramid(k)
    faces = {(v, nbrs[i - 1], nbrs[i]) for v, nbrs in enumerate(lists) for i in range(len(nbrs))}
    faces = {f for f in faces if f[0] == min(f)}  # each triangle once
    a, b, c = min(faces)
    for w in range(k + 2, k + 2 + t):
        faces -= {(a, b, c)}
        faces |= {(a, b, w), (b, c, w), (c, a, w)}
        c = w  # the next cut is at a corner of the triangle just made
    return rotation_lists(faces, k + 2 + t)


def test_records_tally_grows_its_table_past_its_first_size():
    # One batch with 777 groups (the kernel's table starts at 1,024 slots and doubles at half
    # full): a k-prism truncated t times, k = 4..40, t = 0..20, is flag with round t and
    # k + 2 + t faces. Its split type (t = 0 only) is (k - 2) // 2: a 4-belt runs over both
    # k-gons and two quadrilaterals, which leaves the others in two runs, of k - 2 in all.
    records = [planar_code_record(_truncated_prism(k, t)) for k in range(4, 41) for t in range(21)]
    counted = _assert_same_tallies(b">>planar_code<<" + b"".join(records), chunk_size=10_000)
    assert len(counted) == 37 * 21
    assert (counted["count"] == 1).all()
    assert set(counted["family"]) == {"flag"}
    expected = {(k + 2 + t, t) for k in range(4, 41) for t in range(21)}
    pairs = zip(counted["n_faces"].astype(int), counted["round_k"].astype(int), strict=True)
    assert set(pairs) == expected
    classes = dict(zip(counted["round_k"], counted["class"], strict=False))
    assert [classes[t] for t in range(4)] == ["flag", "flag+1", "flag+2", "flag>=3"]
    prisms = counted[counted["round_k"] == 0]
    assert (prisms["split_k"] == (prisms["n_faces"] - 4) // 2).all()  # (k - 2) // 2
    assert counted.loc[counted["round_k"] > 0, "split_k"].isna().all()


def test_summary_from_bytes_equals_summary_from_classified_rows(plantri_output):
    from grainclass.pipeline import classified_tables

    path = str(plantri_output(10))
    counted = summarize(tallies([path], ReadOptions(types=False)))
    from_rows = summarize(classified_tables([path], ReadOptions(types=False)))
    for name in ("classes", "round", "split"):
        assert counted.table(name).equals(from_rows.table(name)), name
    assert counted.headline == from_rows.headline


def test_cut_off_record_is_counted_as_invalid(plantri_output):
    data = plantri_output(8).read_bytes()
    parts = list(read_planar_code(io.BytesIO(data[:-3]), "x", 1000, raw=True))
    assert isinstance(parts[0], PlanarCodeRecords)
    tally = tally_batch(parts[-1])
    assert tally.counts["status"].tolist() == ["invalid"]


def test_batches_keep_their_bytes_while_buffers_are_reused(plantri_output, monkeypatch):
    # Blocks of 256 bytes: the stream goes through many buffers. Batches still held must keep
    # their bytes (a buffer is reused only once nothing refers to it), and batches dropped as
    # they come must classify as one batch of everything does.
    import grainclass.readers.planar_code as reader

    data = plantri_output(10).read_bytes()  # 233 triangulations of 59 bytes
    (whole,) = _tallies(data, True, 10**6)
    assert whole["count"].sum() == 233
    monkeypatch.setattr(reader, "BLOCK_BYTES", 256)
    held = list(read_planar_code(io.BytesIO(data), "x", 3, raw=True))
    assert len(held) > 50
    assert b"".join(b.buf.tobytes() for b in held) == data[len(b">>planar_code<<") :]
    batches = read_planar_code(io.BytesIO(data), "x", 3, raw=True)
    streamed = merge_tallies([tally_batch(b).counts for b in batches])
    pd.testing.assert_frame_equal(streamed, merge_tallies([whole]))


def test_a_pipe_written_in_small_pieces_reads_as_the_whole_stream(plantri_output, monkeypatch):
    # From a pipe, reads that find it nearly empty wait for more to gather (pipes.py).
    # A writer that sends 1 to 4,000 bytes at a time, pausing now and then, across records and
    # across the reader's blocks, must give the records a file gives, and the last record, cut
    # off, must still come out as an unreadable grain.
    import threading
    import time

    import grainclass.readers.planar_code as reader
    from grainclass.pipes import gathers_reads

    data = plantri_output(10).read_bytes()[:-5]
    monkeypatch.setattr(reader, "BLOCK_BYTES", 3000)
    read_end, write_end = os.pipe()
    pieces = random.Random(3)

    def write() -> None:
        with os.fdopen(write_end, "wb", buffering=0) as sink:
            at = 0
            while at < len(data):
                size = pieces.choice([1, 7, 59, 700, 4000])
                sink.write(data[at : at + size])
                at += size
                if pieces.random() < 0.1:
                    time.sleep(0.005)

    writer = threading.Thread(target=write)
    writer.start()
    with os.fdopen(read_end, "rb") as stream:
        assert gathers_reads(stream) == sys.platform.startswith("linux")
        piped = list(read_planar_code(stream, "x", 7, raw=True))
    writer.join()
    whole = list(read_planar_code(io.BytesIO(data), "x", 7, raw=True))
    assert [type(b) for b in piped] == [type(b) for b in whole]
    assert [len(b) for b in piped] == [len(b) for b in whole]
    for a, b in zip(piped[:-1], whole[:-1], strict=True):
        assert a.buf.tobytes() == b.buf.tobytes()
        assert a.first_record == b.first_record
    assert tally_batch(piped[-1]).counts["status"].tolist() == ["invalid"]
    assert not gathers_reads(io.BytesIO(data))


def test_group_rows_packs_or_compares_whole_rows():
    rows = np.array([[1, 2], [0, 5], [1, 2], [0, 5], [3, 3]])
    for scale in (1, 2**40):  # 2**40: too wide to pack two columns into one int64
        first, group = group_rows(list((rows * scale).T))
        assert first.tolist() == [0, 1, 4]  # in order of first appearance
        assert group.tolist() == [0, 1, 0, 1, 2]


def test_group_rows_hash_table_grows_past_its_first_size():
    # 5,000 distinct keys (the table starts at 1,024 slots), each repeated, checked against a
    # grouping by Python dict.
    rng = np.random.default_rng(7)
    a, b = rng.integers(0, 100, 20_000), rng.integers(0, 50, 20_000)
    first, group = group_rows([a, b])
    seen: dict[tuple[int, int], int] = {}
    expected = [
        seen.setdefault((x, y), len(seen)) for x, y in zip(a.tolist(), b.tolist(), strict=True)
    ]
    assert group.tolist() == expected
    assert [(a[i], b[i]) for i in first] == list(seen)


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="F_SETPIPE_SZ is Linux's")
def test_pipes_are_read_with_a_larger_buffer(tmp_path):
    import fcntl

    from grainclass.pipes import PIPE_BYTES, enlarge_pipe, gathers_reads

    read_end, write_end = os.pipe()
    with os.fdopen(read_end, "rb") as reader, os.fdopen(write_end, "wb"):
        before = fcntl.fcntl(reader.fileno(), fcntl.F_GETPIPE_SZ)
        assert enlarge_pipe(reader) == PIPE_BYTES
        assert before < PIPE_BYTES
        assert fcntl.fcntl(reader.fileno(), fcntl.F_GETPIPE_SZ) == PIPE_BYTES
    path = tmp_path / "file"
    path.write_bytes(b"")
    with path.open("rb") as regular:
        assert enlarge_pipe(regular) == 0  # not a pipe: left alone, no error
        assert not gathers_reads(regular)


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="F_SETPIPE_SZ is Linux's")
def test_a_larger_pipe_is_never_shrunk(monkeypatch):
    # Only a privileged user can give a pipe more than 1 MB: such a pipe is seen through a
    # stand-in for fcntl that reports 4 MB and records every change asked of it.
    import fcntl

    from grainclass.pipes import PIPE_BYTES, enlarge_pipe

    changes = []

    def four_megabytes(fd, command, *args):
        if command == fcntl.F_SETPIPE_SZ:
            changes.append(args)
        return 4 * PIPE_BYTES

    read_end, write_end = os.pipe()
    with os.fdopen(read_end, "rb") as reader, os.fdopen(write_end, "wb"):
        monkeypatch.setattr(fcntl, "fcntl", four_megabytes)
        assert enlarge_pipe(reader) == 4 * PIPE_BYTES
    assert changes == []


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="F_SETPIPE_SZ is Linux's")
def test_reads_wait_to_gather_only_from_a_pipe_that_holds_enough(monkeypatch):
    # A 64 kB pipe fills long before a 2 ms wait ends: waiting would hold the writer up.
    import fcntl

    import grainclass.pipes as pipes

    real_fcntl = fcntl.fcntl

    def refuse_to_enlarge(fd, command, *args):
        if command == fcntl.F_SETPIPE_SZ:
            raise PermissionError(1, "Operation not permitted")
        return real_fcntl(fd, command, *args)

    read_end, write_end = os.pipe()
    with os.fdopen(read_end, "rb") as reader, os.fdopen(write_end, "wb"):
        default = real_fcntl(reader.fileno(), fcntl.F_GETPIPE_SZ)
        assert default < pipes.PIPE_BYTES
        with monkeypatch.context() as refused:
            refused.setattr(fcntl, "fcntl", refuse_to_enlarge)
            assert pipes.enlarge_pipe(reader) == default
            assert not pipes.gathers_reads(reader)
        assert pipes.gathers_reads(reader)
        assert real_fcntl(reader.fileno(), fcntl.F_GETPIPE_SZ) == pipes.PIPE_BYTES


def test_records_read_again_as_lists_keep_their_place_in_the_stream(plantri_output):
    """The census hands the records its fast path leaves to the general path as lists: they
    keep their ids and record numbers (those of the same records read as lists directly)."""
    data = plantri_output(9).read_bytes()
    chunks = list(read_planar_code(io.BytesIO(data), "x", 20, raw=True))
    (direct,) = read_planar_code(io.BytesIO(data), "x", 1000)
    chunk = chunks[1]  # records 21..40 of 50
    picked = np.array([0, 5, 19])
    again = chunk.as_csr(picked)
    expected = chunk.first_record - 1 + picked
    assert list(again.grain_id) == [direct.grain_id[int(r)] for r in expected]
    assert again.location.tolist() == direct.location[expected].tolist()
    assert again.n_faces.tolist() == direct.n_faces[expected].tolist()
