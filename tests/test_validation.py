"""Bad input: every grain keeps its row, with a status and a message that names where it is."""

from __future__ import annotations

import gzip
import io
import random
import struct
from pathlib import Path

import pyarrow as pa
import pytest

from conftest import EXAMPLES
from grainclass import GrainBatch, classify, read_dataset
from grainclass._kernels.small import CORNERS, STAMP_STEP, STAMPS
from grainclass.errors import InputError
from grainclass.readers import sniff
from strategies import planar_code_record, rotation_lists

CUBE = [[1, 2, 3, 4], [0, 4, 5, 2], [0, 1, 5, 3], [0, 2, 5, 4], [0, 3, 5, 1], [1, 4, 3, 2]]


def _table(path, **kwargs) -> pa.Table:
    return pa.concat_tables(classify(b) for b in read_dataset(str(path), **kwargs))


def _row(lists):
    return classify(GrainBatch.from_lists([lists])).to_pylist()[0]


# grain id -> (status, line, words the message must contain); lines counted by hand in the file.
BAD_GRAINS = {
    "cube": ("ok", 3, None),
    "bad_token": ("invalid", 5, "'x' is not a face index"),
    "out_of_range": ("invalid", 7, "face 5 lists face 7"),
    "asymmetric": ("invalid", 9, "face 0 lists face 1 once, but face 1 does not list face 0"),
    "dodecahedron": ("ok", 11, None),
    "trihedron": ("degenerate", 13, "2-gon"),
    "shared_edges": ("degenerate", 15, "faces 0 and 1 share more than one edge"),
    "square_pyramid": ("non_simple", 17, "corner where 4 faces meet"),
    "two_tetrahedra": ("invalid", 19, "not connected"),
    "torus": ("invalid", 21, "not a sphere"),
    "no_tab": ("invalid", 23, "expected a grain id, a TAB and the faces"),
    "pentagonal_prism_unordered": ("ok", 25, None),
}


def test_bad_grains_file_keeps_every_grain_with_status_and_line():
    table = _table(EXAMPLES / "bad-grains.txt")
    rows = table.to_pylist()
    assert [r["grain_id"] for r in rows] == list(BAD_GRAINS)
    for row in rows:
        status, line, words = BAD_GRAINS[row["grain_id"]]
        assert row["status"] == status, row
        if words is None:
            assert row["error"] is None
            assert row["class"] == "flag"
        else:
            assert row["error"].startswith(f"{EXAMPLES / 'bad-grains.txt'}:{line}: ")
            assert words in row["error"]
            assert row["class"] is None
            assert row["family"] is None


def test_an_asymmetric_adjacency_says_which_list_has_the_extra_entry():
    # The tetrahedron, with face 0 a second time in the list of face 3.
    row = _row([[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1, 0]])
    assert row["status"] == "invalid"
    assert row["error"].endswith("face 0 lists face 3 once, but face 3 lists face 0 twice")


def test_unordered_pentagonal_prism_classifies_like_the_ordered_one():
    row = next(
        r
        for r in _table(EXAMPLES / "bad-grains.txt").to_pylist()
        if r["grain_id"] == "pentagonal_prism_unordered"
    )
    # Hand-derived (tests/hand_derived.py): split 1:2, five 4-belts, penalty 70.
    assert (row["split_k"], row["split_m"], row["belts4"], row["penalty"]) == (1, 2, 5, 70)


def test_planar_code_cut_off_mid_record_keeps_the_complete_records(plantri_output, tmp_path):
    data = plantri_output(8).read_bytes()
    path = tmp_path / "cut.pc"
    path.write_bytes(data[:-7])
    rows = _table(path).to_pylist()
    assert len(rows) == 14
    assert [r["status"] for r in rows] == ["ok"] * 13 + ["invalid"]
    assert rows[-1]["grain_id"] == "14"
    assert rows[-1][
        "error"
    ] == f"{path}: record 14: the input ends in the middle of this record (" + (
        f"{len(data) - 7 - _offset_of_record(data, 13)} bytes left)"
    )


def _offset_of_record(data: bytes, index: int) -> int:
    """Byte offset of the 0-based record ``index`` of a 1-byte planar_code stream with header."""
    pos = len(b">>planar_code<<")
    for _ in range(index):
        n = data[pos]
        pos += 1
        zeros = 0
        while zeros < n:
            zeros += data[pos] == 0
            pos += 1
    return pos


def _planar_code_wide(lists, big_endian: bool) -> bytes:
    fmt = ">H" if big_endian else "<H"
    out = bytearray(b"\x00" + struct.pack(fmt, len(lists)))
    for nbrs in lists:
        for x in nbrs:
            out += struct.pack(fmt, x + 1)
        out += struct.pack(fmt, 0)
    return bytes(out)


@pytest.mark.parametrize(
    ("header", "big_endian"), [(b">>planar_code le<<", False), (b">>planar_code be<<", True)]
)
def test_planar_code_two_byte_entries_in_both_byte_orders(tmp_path, header, big_endian):
    path = tmp_path / "wide.pc"
    path.write_bytes(header + _planar_code_wide(CUBE, big_endian) * 2)
    rows = _table(path).to_pylist()
    assert [(r["grain_id"], r["class"], r["penalty"]) for r in rows] == [
        ("1", "flag", 18),
        ("2", "flag", 18),
    ]


@pytest.mark.parametrize("chunk_size", [1, 5, 100_000])
def test_planar_code_streams_one_after_another_read_as_one(plantri_output, tmp_path, chunk_size):
    """`cat a.pc b.pc`, `(plantri 7; plantri 8) | ...`: the second header is read as a header,
    also one that changes the byte order, and the records are numbered on across it."""
    sevens, eights = plantri_output(7).read_bytes(), plantri_output(8).read_bytes()
    wide = b">>planar_code be<<" + _planar_code_wide(CUBE, big_endian=True)
    path = tmp_path / "both.pc"
    path.write_bytes(sevens + eights + wide + b">>planar_code<<")
    rows = _table(path, chunk_size=chunk_size).to_pylist()
    assert [r["n_faces"] for r in rows] == [7] * 5 + [8] * 14 + [6]
    assert all(r["status"] == "ok" for r in rows)
    assert [r["grain_id"] for r in rows] == [str(k) for k in range(1, 21)]
    assert rows[-1]["penalty"] == 18


def test_text_with_a_stray_0_byte_or_in_utf16_is_not_sniffed_as_planar_code():
    """Any 0 byte made planar_code of it: every line an invalid 'record', none named text."""
    line = "cube\t1 2 3 4;0 4 5 2;0 1 5 3;0 2 5 4;0 3 5 1;1 4 3 2\n"
    assert sniff(line.encode() + b"\x00\n") == "adjacency"
    assert sniff(b"a\t1 2 3;0 3 2;0 1 3;0 2 1\x00\n") == "adjacency"
    assert sniff(line.encode("utf-16")) == "not grains"
    assert sniff(b"BZh" + line.encode()) == "adjacency"  # bzip2's magic is longer


@pytest.mark.parametrize("encoding", ["utf-16-le", "utf-16-be"])
def test_utf16_without_a_byte_order_mark_is_named(tmp_path, encoding):
    """Without the mark it was read as adjacency text: every line an invalid grain, exit 0."""
    path = tmp_path / "grains.txt"
    path.write_bytes((EXAMPLES / "polytopes.txt").read_text().encode(encoding))
    name = {"utf-16-le": "UTF-16LE", "utf-16-be": "UTF-16BE"}[encoding]
    with pytest.raises(InputError, match=f"{name} text without a byte order mark"):
        list(read_dataset(str(path)))


@pytest.mark.parametrize("fmt", ["adjacency", "voro", "neper", "loops"])
@pytest.mark.parametrize("packing", ["utf-16", "utf-16-le", "gzip"])
def test_text_format_named_on_utf16_or_compressed_input_says_what_it_is(tmp_path, fmt, packing):
    """Named, a text format read such input as text: every line an invalid grain, exit 0."""
    text = (EXAMPLES / "polytopes.txt").read_text()
    path = tmp_path / "grains.txt"
    path.write_bytes(gzip.compress(text.encode()) if packing == "gzip" else text.encode(packing))
    why = {"utf-16": "UTF-16 text", "utf-16-le": "UTF-16LE text", "gzip": "gzip-compressed"}
    with pytest.raises(InputError, match=why[packing]):
        list(read_dataset(str(path), input_format=fmt))


def test_planar_code_named_reads_what_it_is_given(tmp_path):
    """planar_code is bytes: a record may start as a byte order mark does (n = 255, then 254)
    or as gzip's magic, so named it reads them as records (invalid ones here)."""
    path = tmp_path / "grains.pc"
    path.write_bytes(gzip.compress((EXAMPLES / "polytopes.txt").read_bytes()))
    table = _table(path, input_format="planar_code")
    assert set(table.column("status").to_pylist()) == {"invalid"}


def test_utf16_or_compressed_evolver_file_is_a_row_that_says_so(tmp_path):
    """An Evolver file is one grain's row among the others' (a dump of many): 'no bodies'
    said nothing of why. A compressed one must become a file again: Evolver input is no pipe."""
    text = (Path(__file__).parent / "data" / "evolver" / "two_cubes.fe").read_text()
    (tmp_path / "a.fe").write_bytes(text.encode("utf-16"))
    (tmp_path / "b.fe").write_bytes(gzip.compress(text.encode()))
    (tmp_path / "c.fe").write_text(text)
    rows = _table(tmp_path).to_pylist()
    assert [(r["grain_id"], r["status"]) for r in rows] == [
        ("a", "invalid"),
        ("b", "invalid"),
        ("1", "ok"),
        ("2", "ok"),
    ]
    assert rows[0]["error"] == f"{tmp_path / 'a.fe'}:1: UTF-16 text: save it as UTF-8 " + (
        "(iconv -f UTF-16 -t UTF-8 FILE)"
    )
    assert rows[1]["error"] == f"{tmp_path / 'b.fe'}:1: gzip-compressed: decompress it " + (
        "first (zcat FILE > NEW.fe)"
    )


def test_planar_code_with_two_byte_entries_is_no_utf16(tmp_path):
    """Written with 2-byte entries, a small grain has every other byte 0, as UTF-16 text
    has, but entries no text holds (the tetrahedron: 4, 2, 3)."""
    lists = [[2, 3, 4], [1, 4, 3], [1, 2, 4], [1, 3, 2]]
    record = b"\x00" + struct.pack("<H", 4) + b"".join(struct.pack("<4H", *f, 0) for f in lists)
    path = tmp_path / "wide.pc"
    path.write_bytes(record * 4)
    assert sniff(record * 4) == "planar_code"
    assert _table(path).column("class").to_pylist() == ["stacked"] * 4


def test_planar_code_without_header_is_sniffed(plantri_output, tmp_path):
    data = plantri_output(7).read_bytes()[len(b">>planar_code<<") :]
    assert sniff(data[:64]) == "planar_code"
    path = tmp_path / "headerless"
    path.write_bytes(data)
    assert _table(path).column("class").to_pylist().count("flag+1") == 1


@pytest.mark.parametrize("chunk_size", [1, 3, 100_000])
def test_chunk_size_does_not_change_rows(chunk_size):
    base = _table(EXAMPLES / "bad-grains.txt").to_pylist()
    assert _table(EXAMPLES / "bad-grains.txt", chunk_size=chunk_size).to_pylist() == base


def test_mixed_orientation_is_normalized():
    flipped = [list(reversed(nbrs)) if f % 2 else nbrs for f, nbrs in enumerate(CUBE)]
    assert _row(flipped)["penalty"] == 18


def test_scrambled_lists_are_embedded_from_the_graph():
    rng = random.Random(7)
    scrambled = [rng.sample(nbrs, len(nbrs)) for nbrs in CUBE]
    row = _row(scrambled)
    assert (row["status"], row["class"], row["belts4"]) == ("ok", "flag", 3)


def test_octahedron_graph_is_not_a_grain_of_its_own_dual():
    # K_{2,2,2} plus one extra edge: 13 > 3n - 6 = 12 adjacencies.
    lists = [
        [2, 3, 4, 5, 1],
        [2, 5, 3, 4, 0],
        [0, 4, 1, 5],
        [0, 5, 1, 4],
        [0, 3, 1, 2],
        [0, 2, 1, 3],
    ]
    row = _row(lists)
    assert row["status"] == "invalid"
    assert "at most 3n-6 = 12" in row["error"]


def test_graph_with_3n_minus_6_edges_that_is_not_planar_is_invalid():
    # K_{3,3} plus three edges (on one side): 12 = 3n - 6 edges, but K_{3,3} is not planar.
    lists = [[3, 4, 5, 1, 2], [3, 4, 5, 0, 2], [3, 4, 5, 0, 1], [0, 1, 2], [0, 1, 2], [0, 1, 2]]
    row = _row(lists)
    assert row["status"] == "invalid"
    assert "do not close up into a sphere" in row["error"]


def test_self_reference_and_lonely_face_are_invalid():
    assert "lists itself" in _row([[0, 1, 2], [0, 2, 3], [0, 1, 3], [1, 2, 0]])["error"]
    assert "has 1 neighbour" in _row([[1], [0]])["error"]


def test_non_simple_grain_is_non_simple_whichever_way_its_lists_turn():
    # A sphere map found by a fuzzer: seven faces, 13 adjacencies, eight corners (7 - 13 + 8 =
    # 2), two of them of four faces (2, 6, 4, 3 and 2, 4, 5, 6). Faces adjacent across one
    # corner are side by side in lists at the other, which looked like triangles there.
    lists = [
        [4, 5, 6],
        [2, 4, 3],
        [1, 3, 6, 4],
        [1, 4, 2],
        [0, 6, 3, 1, 2, 5],
        [0, 4, 6],
        [0, 5, 2, 4],
    ]
    for turned in (lists, [nbrs[::-1] for nbrs in lists]):
        for fast in (64, 0):
            row = classify(GrainBatch.from_lists([turned]), max_bitset_faces=fast).to_pylist()[0]
            assert row["status"] == "non_simple", row["error"]
            assert "a corner where 4 faces meet" in row["error"]


def test_non_simple_grain_with_scrambled_lists_is_invalid_and_says_why():
    # The square pyramid (non_simple when ordered), its lists in no cyclic order: with fewer than
    # 3n - 6 adjacencies the corners cannot be recovered from the graph.
    row = _row([[1, 3, 2, 4], [2, 0, 4], [3, 0, 1], [4, 0, 2], [1, 0, 3]])
    assert row["status"] == "invalid"
    assert "Euler characteristic" in row["error"] or "not in cyclic order" in row["error"]


def test_grain_of_a_disconnected_surface_with_no_cyclic_order_is_invalid():
    # Octahedron with two lists scrambled so that no orientation is consistent, one edge removed.
    lists = [[1, 2, 3, 4], [0, 4, 5, 2], [0, 1, 5, 3], [0, 2, 5, 4], [0, 3, 5, 1], [1, 4, 3, 2]]
    lists[0], lists[1] = [1, 3, 2, 4], [0, 5, 4, 2]
    lists = [[x for x in nbrs if {f, x} != {2, 3}] for f, nbrs in enumerate(lists)]
    row = _row(lists)
    assert row["status"] == "invalid"


@pytest.mark.parametrize(
    ("faces", "status", "words"),
    [
        ("1 2 3 4;0 4 5 2;0 1 5 3;0 2 5 4;0 3 5 1;1 4 3 2;", "ok", None),  # trailing ;
        (" 1 2 3 4 ; 0 4 5 2;0 1 5 3;0 2 5 4;0 3 5 1;1 4 3 2 ", "ok", None),  # blanks
        (
            "1 2 3 4;;0 4 5 2;0 1 5 3;0 2 5 4;0 3 5 1;1 4 3 2",
            "invalid",
            "face 1 lists no neighbours",
        ),
        ("1 2 3 4;0 4 5 2;0 1 5 3;0 2 5 4;0 3 5 1;-1 4 3 2", "invalid", "'-1' is not a face index"),
        ("", "invalid", "face 0 lists no neighbours"),
        (
            "1 2 3 99999999999;0 4 5 2;0 1 5 3;0 2 5 4;0 3 5 1;1 4 3 2",
            "invalid",
            "face 0: 99999999999 is too large for a face index",
        ),
        (
            "1 2 3 4;0 4 5 2;0 1 5 3;0 2 5 4;0 3 5 1;1 4 3 \u00b2",
            "invalid",
            "'\u00b2' is not a face",
        ),
        (  # the largest int32 is read, and out of range
            "1 2 3 2147483647;0 4 5 2;0 1 5 3;0 2 5 4;0 3 5 1;1 4 3 2",
            "invalid",
            "face 0 lists face 2147483647, but the faces are numbered 0..5",
        ),
    ],
)
def test_faces_field_edge_cases(tmp_path, faces, status, words):
    path = tmp_path / "one.txt"
    path.write_text(f"g\t{faces}\n")
    (row,) = _table(path).to_pylist()
    assert row["status"] == status
    if words is None:
        assert row["penalty"] == 18
    else:
        assert words in row["error"]


def _grain_lists(batch: GrainBatch, g: int) -> list[list[int]]:
    offsets = batch.nbr_offsets
    faces = range(batch.face_offsets[g], batch.face_offsets[g + 1])
    return [batch.neighbors[offsets[f] : offsets[f + 1]].tolist() for f in faces]


def _planar_code(grains: list[list[list[int]]]) -> bytes:
    return b">>planar_code<<" + b"".join(planar_code_record(lists) for lists in grains)


def _damaged(lists: list[list[int]], rng: random.Random) -> list[list[int]]:
    """A copy of ``lists`` with one or two entries changed, and maybe one list shuffled."""
    damaged = [list(nbrs) for nbrs in lists]
    for _ in range(rng.randint(1, 2)):
        face = rng.randrange(len(damaged))
        damaged[face][rng.randrange(len(damaged[face]))] = rng.randrange(len(damaged))
    if rng.random() < 0.5:
        rng.shuffle(damaged[rng.randrange(len(damaged))])
    return damaged


def test_fast_check_agrees_with_the_full_diagnosis_on_damaged_grains(plantri_output):
    """The fast check (bitsets and a corner table) passes only grains that the full diagnosis
    finds ok; each damaged copy comes right after its original."""
    batch = next(read_dataset(str(plantri_output(11)), chunk_size=10**6))
    rng = random.Random(20261122)
    grains = []
    for g in rng.sample(range(len(batch)), 300):
        lists = _grain_lists(batch, g)
        grains += [lists, _damaged(lists, rng)]
    damaged = GrainBatch.from_lists(grains)
    fast, full = classify(damaged), classify(damaged, max_bitset_faces=0)
    assert fast.equals(full)
    assert 0 < fast.column("status").to_pylist().count("ok") < len(grains)


# Two triangulations, each with an invalid copy (some lists changed) that the fast check passes
# if the original's corners, left in its corner table, count as the copy's: right after it
# (each grain has a stamp of its own), or STAMPS - 1 tetrahedra later, where the stamps start
# over (the table is cleared then). The tetrahedra overwrite only the corners of faces 0..3.
ORIGINAL = [[1, 2, 3, 4, 5, 6, 7, 8], [0, 8, 2], [0, 1, 8, 3], [0, 2, 8, 6, 5, 4], [0, 3, 5],
            [0, 4, 3, 6], [0, 5, 3, 8, 7], [0, 6, 8], [0, 7, 6, 3, 2, 1]]  # fmt: skip
COPY = [[7, 4, 1, 6, 3, 8, 2, 5], [0, 8, 2], [0, 5, 8, 3], [0, 2, 8, 6, 5, 1], [0, 3, 5],
        [0, 4, 3, 6], [0, 5, 3, 8, 7], [0, 6, 8], [0, 7, 6, 3, 2, 1]]  # fmt: skip
STAMPED = [[1, 2, 3, 4, 5, 6, 7, 8], [0, 8, 4, 3, 2], [0, 1, 3], [0, 2, 1, 4], [0, 3, 1, 8, 5],
           [0, 4, 8, 7, 6], [0, 5, 7], [0, 6, 5, 8], [0, 7, 5, 4, 1]]  # fmt: skip
STALE = [[1, 7, 5, 2, 6, 3, 8, 4], [0, 8, 4, 3, 2], [0, 1, 3], [0, 2, 1, 4], [0, 3, 1, 8, 5],
         [0, 2, 8, 7, 6], [0, 5, 7], [0, 6, 5, 8], [0, 7, 5, 4, 1]]  # fmt: skip
TETRAHEDRON = [[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]]


def _fast_check(lists, following, stamp) -> bool:
    import numpy as np

    from grainclass._kernels.small import _validate_small

    csr = GrainBatch.from_lists([lists])
    adj = np.empty(64, np.uint64)
    ok, _ = _validate_small(len(lists), csr.nbr_offsets, csr.neighbors, 0, adj, following, stamp)
    return ok


def _statuses(grains: list[list[list[int]]]) -> tuple[list[str], list[str]]:
    """Statuses from one kernel call (one corner table) over ``grains``: as CSR lists, and as
    planar_code records counted from their bytes (sorted: counts keep no order)."""
    from grainclass.parallel import get_jobs, set_jobs
    from grainclass.readers.planar_code import read_planar_code
    from grainclass.summary import tally_batch

    jobs = get_jobs()
    try:
        set_jobs(1)
        rows = classify(GrainBatch.from_lists(grains)).column("status").to_pylist()
        (records,) = read_planar_code(io.BytesIO(_planar_code(grains)), "x", 10**6, raw=True)
        counts = tally_batch(records).counts.groupby("status")["count"].sum()
    finally:
        set_jobs(jobs)
    return rows, sorted(counts.index.repeat(counts.to_numpy()))


def test_a_sphere_beside_a_torus_is_invalid_though_as_long_as_a_triangulation():
    # The tetrahedron and K7 on the torus (faces i, i+1, i+3 and i, i+3, i+2 mod 7): 11 faces,
    # 12 + 42 = 6 * 11 - 12 entries, and every triangle closes, 4 + 14 = 2 * 11 - 4 of them, as
    # a triangulation's would. Only connectivity tells the two surfaces from one sphere.
    torus = {(4 + i, 4 + (i + 1) % 7, 4 + (i + 3) % 7) for i in range(7)}
    torus |= {(4 + i, 4 + (i + 3) % 7, 4 + (i + 2) % 7) for i in range(7)}
    lists = rotation_lists({(0, 1, 2), (0, 2, 3), (0, 3, 1), (1, 3, 2)} | torus, 11)
    assert sum(map(len, lists)) == 6 * 11 - 12
    assert _statuses([lists]) == (["invalid"], ["invalid"])
    assert "not connected" in _row(lists)["error"]


@pytest.mark.parametrize(
    ("original", "copy", "between"),
    [(ORIGINAL, COPY, 0), (STAMPED, STALE, STAMPS - 1)],
    ids=["next grain", "stamps start over"],
)
def test_corners_of_an_earlier_grain_never_count(original, copy, between):
    import numpy as np

    grains = [original] + [TETRAHEDRON] * between + [copy]
    # The premise: given the original's stamp, the copy would pass.
    following = np.zeros(CORNERS, np.uint16)
    for g, lists in enumerate(grains[:-1]):
        assert _fast_check(lists, following, (g + 1) * STAMP_STEP)
    assert _fast_check(copy, following, STAMP_STEP)
    assert _row(copy)["status"] == "invalid"

    expected = ["ok"] * (1 + between) + ["invalid"]
    assert _statuses(grains) == (expected, sorted(expected))


OCTAHEDRON = [[1, 2, 3, 4], [0, 4, 5, 2], [0, 1, 5, 3], [0, 2, 5, 4], [0, 3, 5, 1], [1, 4, 3, 2]]


def test_a_record_with_an_empty_list_is_invalid_on_both_paths():
    # The octahedron with face 0's list emptied and its four entries moved to face 5's: the
    # record keeps a triangulation's length (7n - 11 bytes), so only the empty list tells.
    emptied = [[], *OCTAHEDRON[1:5], OCTAHEDRON[5] + [1, 2, 3, 4]]
    assert len(planar_code_record(emptied)) == 7 * 6 - 11
    assert _statuses([OCTAHEDRON, emptied]) == (["ok", "invalid"], ["invalid", "ok"])


# Found by a search over the triangulations with n <= 6, one list doubled and as many entries
# taken from others: face 5 lists its three neighbours twice, and each of its triangles, closed
# by the other lists, would count twice, making up for the triangles the removed entries open.
# Without its repeat check the fast path counts 2n - 4 closed triangles and passes it.
TWICE_AROUND = [[1, 4, 5], [0, 5, 4, 2], [1, 4, 3], [0, 2, 4], [0, 3, 2, 1, 5], [0, 4, 1, 0, 4, 1]]


@pytest.mark.parametrize(
    "lists",
    [
        TWICE_AROUND,
        # Face 0's neighbour 2 written as 66: the same face once the index is taken modulo 64,
        # as the fast path's bitsets take it.
        [[1, 66, 3, 4], *OCTAHEDRON[1:]],
        # And as 130: modulo 128 too, as the corner table of planar_code records takes it.
        [[1, 130, 3, 4], *OCTAHEDRON[1:]],
    ],
    ids=["a list twice around", "an index 64 too large", "an index 128 too large"],
)
def test_what_only_the_repeat_and_range_checks_reject_is_invalid(lists):
    assert len(planar_code_record(lists)) == 7 * len(lists) - 11
    assert _statuses([OCTAHEDRON, lists]) == (["ok", "invalid"], ["invalid", "ok"])


def test_evolver_text_with_carriage_returns_alone_is_sniffed():
    from conftest import ROOT

    text = (ROOT / "tests" / "data" / "evolver" / "two_cubes.fe").read_bytes()
    assert sniff(text[:4096].replace(b"\n", b"\r")) == "evolver"


def test_the_quotient_of_one_grain_is_the_quotient_of_the_arrays():
    import numpy as np

    from grainclass.batch import isoperimetric_quotient

    pairs = [(1.0, 6.0), (1e160, 1e107), (0.0, 0.0), (1.0, 0.0), (0.0, 2.0), (float("nan"), 1.0)]
    arrays = isoperimetric_quotient(
        np.array([v for v, _ in pairs]), np.array([s for _, s in pairs])
    )
    single = [isoperimetric_quotient(v, s) for v, s in pairs]
    np.testing.assert_allclose(single, arrays, rtol=1e-15)
