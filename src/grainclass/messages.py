"""The ``error`` column: why a grain is not ok, in words, from the kernels' integer codes
(:mod:`grainclass._kernels.codes`) or the reader's own message, naming the grain's faces as the
input names them."""

from __future__ import annotations

import numpy as np

from grainclass._kernels import codes
from grainclass.batch import GrainBatch

MESSAGES = {
    codes.E_TOO_FEW_FACES: "{a} faces; a grain needs at least 4",
    codes.E_INDEX_RANGE: "face {a} lists face {b}, but the faces are numbered 0..{last}",
    codes.E_SELF: "face {a} lists itself as a neighbour",
    codes.E_ASYMMETRIC: "asymmetric adjacency: face {a} lists face {b}{ab}, but face {b} {ba}",
    codes.E_FEW_NEIGHBOURS: "face {a} has {b} neighbour(s); a face needs at least 2",
    codes.E_TWO_GON: "degenerate: face {a} is a 2-gon",
    codes.E_SHARED_EDGES: "degenerate: faces {a} and {b} share more than one edge",
    codes.E_DISCONNECTED: "not connected: face {a} cannot be reached from face {first}",
    codes.E_TOO_MANY_EDGES: "not a sphere: {a} adjacencies, but a grain with {n} faces "
    "has at most 3n-6 = {b}",
    codes.E_EULER: "not a sphere: the neighbour lists, read as cyclic orders, "
    "describe a surface of Euler characteristic {a} (or they are in no cyclic order)",
    codes.E_UNORDERED: "not a simple grain ({a} adjacencies, 3n-6 = {b}) and the neighbour "
    "lists are not in cyclic order, so the corners cannot be recovered",
    codes.E_NOT_SPHERE: "not a sphere: {edges} adjacencies, but the triangles around "
    "faces {a} and {b} do not close up into a sphere",
    codes.E_NON_SIMPLE: "non-simple: a corner where {a} faces meet (face {b} is one of them)",
    codes.E_TOO_LARGE: "too large: {n} faces and {darts} neighbour entries could need {a_mb} "
    "of memory, more than the {b_mb} a grain may take (GRAINCLASS_GRAIN_MEMORY, in MB)",
    codes.E_FOREST_TOO_LARGE: "too large: the strings of its truncation forest would take "
    "{a_mb}, more than the {b_mb} a grain may take (GRAINCLASS_GRAIN_MEMORY, in MB)",
    codes.E_MEMORY: "out of memory: the system refused the memory that classifying "
    "this grain of {n} faces needed",
}


def _mb(size: int) -> str:
    return f"{size / 2**20:,.1f} MB"


def _where(batch: GrainBatch, g: int) -> str:
    source = batch.source if isinstance(batch.source, str) else batch.source[g]
    if batch.location_kind == "line":
        return f"{source}:{batch.location[g]}"
    if batch.location_kind == "label":  # a label image's grain, named by its label
        return f"{source}: grain {batch.location[g]}"
    return f"{source}: record {batch.location[g]}"


# The parameters of a message that are faces of the grain, named by the input's face ids
# where it has them (GrainBatch.face_labels).
_FACE_PARAMETERS = {
    codes.E_SELF: "a",
    codes.E_ASYMMETRIC: "ab",
    codes.E_FEW_NEIGHBOURS: "a",
    codes.E_TWO_GON: "a",
    codes.E_SHARED_EDGES: "ab",
    codes.E_DISCONNECTED: "a",
    codes.E_NOT_SPHERE: "ab",
    codes.E_NON_SIMPLE: "b",
}


def _face_name(batch: GrainBatch, g: int, face: int) -> int:
    """Face ``face`` of grain ``g`` as the input names it."""
    labels, start = batch.face_labels, int(batch.face_offsets[g])
    if labels is None or not 0 <= face < int(batch.face_offsets[g + 1]) - start:
        return face
    return int(labels[start + face])


def _asymmetry(batch: GrainBatch, g: int, a: int, b: int) -> tuple[str, str]:
    """How often face a lists face b, and what face b's list does about face a, in words."""

    def listed(v: int, x: int) -> int:
        face = batch.face_offsets[g] + v
        lst = batch.neighbors[batch.nbr_offsets[face] : batch.nbr_offsets[face + 1]]
        return int((lst == x).sum())

    def times(k: int) -> str:
        return {1: "once", 2: "twice"}.get(k, f"{k} times")

    back = listed(b, a)
    return (
        f" {times(listed(a, b))}",
        f"lists face {_face_name(batch, g, a)} {times(back)}"
        if back
        else f"does not list face {_face_name(batch, g, a)}",
    )


def error_messages(batch: GrainBatch, status: np.ndarray, err: np.ndarray) -> list[str | None]:
    """The ``error`` column: for each grain that is not ok, where it is and what is wrong with it
    in words, from the kernels' codes (``err``: int64[G, 3], code, a, b) or the reader's message;
    None for an ok grain."""
    messages: list[str | None] = [None] * len(batch)
    n_faces = batch.n_faces
    for g in np.flatnonzero(status != codes.OK):
        code, a, b = (int(x) for x in err[g])
        if code == codes.E_PARSE:
            what = batch.parse_errors.get(int(g), "unreadable record")
        else:
            n = int(n_faces[g])
            ab, ba = _asymmetry(batch, int(g), a, b) if code == codes.E_ASYMMETRIC else ("", "")
            darts = int(batch.nbr_offsets[batch.face_offsets[g + 1]])
            darts -= int(batch.nbr_offsets[batch.face_offsets[g]])
            faces = _FACE_PARAMETERS.get(code, "")
            what = MESSAGES[code].format(
                a=_face_name(batch, int(g), a) if "a" in faces else a,
                b=_face_name(batch, int(g), b) if "b" in faces else b,
                first=_face_name(batch, int(g), 0), n=n, last=n - 1, edges=3 * n - 6,
                ab=ab, ba=ba, darts=darts, a_mb=_mb(a), b_mb=_mb(b),
            )  # fmt: skip
        messages[g] = f"{_where(batch, g)}: {what}"
    return messages
