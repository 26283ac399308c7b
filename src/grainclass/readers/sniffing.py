"""Naming the format of an input from its first bytes (:func:`sniff`), and refusing inputs that
hold no grains for what they are (:func:`not_grains`): UTF-16 text, compressed files, Parquet
tables.

planar_code always holds 0 bytes (its terminators), and text has none but by accident
(:func:`_looks_like_planar_code` tells the two apart).
"""

from __future__ import annotations

import re

from grainclass.readers.neper import looks_like_neper
from grainclass.readers.spparks import looks_like_spparks
from grainclass.readers.voro import looks_like_voro

SNIFF_BYTES = 4096  # the first bytes of an input that name its format
_BOM = b"\xef\xbb\xbf"  # what some Windows editors put before UTF-8 text
_EVOLVER = re.compile(rb"(?im)^\s*(vertices|torus_filled|torus|periods):?\s*(//.*)?$")

# Files that hold no grains a reader could take, by their first bytes (whole magic numbers: a
# grain id may start with "BZh"): named, not misread (their 0 bytes would make them planar_code).
# Compressed files, by their magic bytes: (compression, the command that decompresses to
# standard output).
_COMPRESSED = {
    re.compile(rb"\x1f\x8b\x08"): ("gzip", "zcat"),
    re.compile(rb"BZh[1-9]1AY&SY", re.DOTALL): ("bzip2", "bzcat"),
    re.compile(rb"\xfd7zXZ\x00"): ("xz", "xzcat"),
    re.compile(rb"\x28\xb5\x2f\xfd"): ("zstd", "zstdcat"),
}


def sniff(head: bytes) -> str:
    """Name the format of an input from its first bytes.

    Examples
    --------
    >>> sniff(b">>planar_code<<" + bytes([4, 2, 3, 4, 0]))
    'planar_code'
    >>> sniff(b"cube\\t1 2 3 4;0 4 5 2")
    'adjacency'
    >>> sniff(b"// a foam\\nvertices\\n1 0 0 0\\n")
    'evolver'
    >>> sniff(b"7 0.0351 (1,3,2) (1,5,4,3)\\n")
    'voro'

    Face-vertex-loop text looks like adjacency text: it is read only with ``--format loops``.
    A Parquet table or a compressed file is ``not grains``: :func:`read_dataset` says why.
    """
    if not_grains(head):
        return "not grains"
    head = head.removeprefix(_BOM)
    if _returns_alone(head):
        head = head.replace(b"\r", b"\n")
    if _looks_like_planar_code(head):
        return "planar_code"
    if _EVOLVER.search(head):
        return "evolver"
    if looks_like_voro(head):
        return "voro"
    if looks_like_neper(head):
        return "neper"
    return "adjacency"


def _returns_alone(head: bytes) -> bool:
    """Text whose lines end in a carriage return alone, as classic Mac OS saved it."""
    return b"\r" in head and b"\n" not in head


def not_grains(head: bytes, file_only: bool = False) -> str | None:
    """What an input that holds no grains is, from its first bytes; None for anything else.
    ``file_only``: the input must be a file (Surface Evolver), so a compressed one is to be
    decompressed into another file, not into a pipe."""
    if head[:2] in (b"\xff\xfe", b"\xfe\xff"):  # a byte order mark, as Windows writes UTF-16
        try:
            head[: len(head) // 2 * 2].decode("utf-16")
        except UnicodeDecodeError:
            return None
        return "UTF-16 text: save it as UTF-8 (iconv -f UTF-16 -t UTF-8 FILE)"
    encoding = _utf16_without_mark(head)
    if encoding:
        return (
            f"{encoding} text without a byte order mark: save it as UTF-8 "
            f"(iconv -f {encoding} -t UTF-8 FILE)"
        )
    if head.startswith(b"PAR1"):
        return "a Parquet table, not grains: summarize and types read it, classify reads grains"
    points = points_kind(head)
    if points:
        return f"{points}, not grains: grainclass voronoi --points FILE tessellates them"
    for magic, (compression, cat) in _COMPRESSED.items():
        if magic.match(head):
            how = f"{cat} FILE > NEW.fe" if file_only else f"{cat} FILE | grainclass ... -"
            return f"{compression}-compressed: decompress it first ({how})"
    return None


_NUMBER = rb"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"
_XYZ_ATOM = re.compile(rb"\S+(?:\s+" + _NUMBER + rb"){3}(?:\s.*)?")
_VORO_POINT = re.compile(rb"\d+(?:\s+" + _NUMBER + rb"){3,4}")


def points_kind(head: bytes) -> str | None:
    """What kind of points file an input is, from its first bytes (the files
    ``grainclass voronoi --points`` reads), or None: a LAMMPS dump, a NumPy array, (extended)
    XYZ, a CSV table with x, y and z columns, or Voro++'s input of ``id x y z [r]`` lines.
    Grains never look so: adjacency text has a ``;`` between faces, Voro++ output parentheses.

    >>> points_kind(b"ITEM: TIMESTEP\\n0\\n"), points_kind(b"cube\\t1 2 3 4;0 4 5 2\\n")
    ('a LAMMPS dump of points', None)

    A SPPARKS site dump looks like a LAMMPS dump, but holds a label image, not points: it is
    left alone (:func:`grainclass.readers.spparks.looks_like_spparks`).

    >>> points_kind(b"ITEM: TIMESTEP\\n0    3.03846\\nITEM: NUMBER OF ATOMS\\n8\\n") is None
    True
    >>> points_kind(b"1 0.5 0.25 0.125\\n2 0.1 0.2 0.3\\n")
    "Voro++'s input of points"
    """
    if head.startswith(b"\x93NUMPY"):
        # A 3D integer array is a label image, which readers.images names; an (n, 3) float
        # array is points.
        return "a NumPy array of points" if _npy_points(head) else None
    lines = [line.strip() for line in head.splitlines() if line.strip()]
    if len(head) == SNIFF_BYTES and lines and not head.endswith(b"\n"):
        lines.pop()  # cut short by the head
    if not lines:
        return None
    if lines[0].startswith(b"ITEM:"):
        return None if looks_like_spparks(head) else "a LAMMPS dump of points"
    if re.fullmatch(rb"\d+", lines[0]) and len(lines) >= 3:
        extended = re.search(rb"\b(Lattice|Properties)=", lines[1])
        if extended or all(_XYZ_ATOM.fullmatch(line) for line in lines[2:]):
            return "an XYZ file of points"
    header = [field.strip().strip(b'"').lower() for field in lines[0].split(b",")]
    if len(header) >= 3 and {b"x", b"y", b"z"} <= set(header):
        return "a CSV table of points"
    if all(_VORO_POINT.fullmatch(line) for line in lines) and any(b"." in x for x in lines):
        return "Voro++'s input of points"
    return None


def _npy_points(head: bytes) -> bool:
    from grainclass.readers.npy_image import header_says_points

    return header_says_points(head)


_TEXT = frozenset(b"\t\n\r" + bytes(range(32, 127)))


def _utf16_without_mark(head: bytes) -> str | None:
    """``UTF-16LE`` or ``UTF-16BE`` for ASCII text so encoded without a byte order mark (every
    other byte 0, the others printable), else None. planar_code has no such rhythm: a 0 ends a
    list of three neighbours or more, and 2-byte entries are used for numbers past 255."""
    sample = head[:256]
    if len(sample) < 16:
        return None
    sample = sample[: len(sample) // 2 * 2]
    for encoding, zeros, text in (
        ("UTF-16LE", sample[1::2], sample[0::2]),
        ("UTF-16BE", sample[0::2], sample[1::2]),
    ):
        if not any(zeros) and set(text) <= _TEXT:
            return encoding
    return None


def _looks_like_planar_code(head: bytes) -> bool:
    """planar_code: a header, or a first record that holds together: n, then n lists ended by
    0 bytes, every entry at most n, the first list without a repeat (or n in 2-byte entries,
    after a 0). Text, repeating its blanks and digits, would have to start with a control
    character: a stray 0 byte in text does not make it planar_code."""
    if head.startswith(b">>planar_code"):
        return True
    if b"\x00" not in head:
        return False
    n = head[0]
    if n == 0:
        return True
    first_list = head[1:].split(b"\x00", 1)[0]
    if len(set(first_list)) != len(first_list):
        return False
    zeros = 0
    for byte in head[1:]:
        if byte > n:
            return False
        zeros += byte == 0
        if zeros == n:
            return True
    return True  # a record longer than the head: nothing against it
