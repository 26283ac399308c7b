"""Voro++ custom output with face-vertex loops, one cell per line.

Accepted format strings (``voro++ -c FORMAT``): ``"%i %t"``, ``"%i %v %t"`` and
``"%i %v %F %t"``: the particle id, optionally the cell volume and its total face area, then
``%t``, each face as the parenthesised, comma-separated loop of its vertex indices, e.g.
``7 0.0351 0.6219 (1,3,2) (1,5,4,3) ...``.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Iterator

import numpy as np

from grainclass.batch import GrainBatch
from grainclass.readers.loops import batch_from_loops

LINE = re.compile(rb"^\s*\d+(\s+[-+0-9.eE]+){0,2}\s+\(\d+(,\d+)*\)")
_LOOP = re.compile(r"\(([0-9,\s]*)\)")


def looks_like_voro(head: bytes) -> bool:
    """True when the first line of ``head`` is a cell written by ``%i [%v [%F]] %t``."""
    first = head.split(b"\n", 1)[0]
    return bool(LINE.match(first))


def read_voro(lines: Iterable[bytes], source: str, chunk_size: int) -> Iterator[GrainBatch]:
    """Parse Voro++ ``%t`` output into batches of at most ``chunk_size`` cells."""
    pending = []
    for line_no, raw in enumerate(lines, 1):
        line = raw.decode("utf-8", "replace").strip()
        if not line or line.startswith("#"):
            continue
        head, paren, _ = line.partition("(")
        tokens = head.split()
        grain_id = tokens[0] if tokens else f"line{line_no}"
        try:
            if not paren or not 1 <= len(tokens) <= 3:
                raise ValueError("expected: id [volume [area]] (loop) (loop) ...")
            int(tokens[0])
            numbers = [float(t) for t in tokens[1:]] + [np.nan, np.nan]
            loops = [[int(v) for v in loop.split(",")] for loop in _LOOP.findall(line[len(head) :])]
            pending.append((grain_id, line_no, loops, numbers[0], numbers[1], None))
        except ValueError as exc:
            pending.append(
                (grain_id, line_no, None, np.nan, np.nan, f"cannot read this cell: {exc}")
            )
        if len(pending) >= chunk_size:
            yield batch_from_loops(pending, source)
            pending = []
    if pending:
        yield batch_from_loops(pending, source)
