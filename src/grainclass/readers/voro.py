"""Voro++ custom output with face-vertex loops, one cell per line.

Accepted format strings (``voro++ -c FORMAT``): ``"%i [%v [%F]] [%n] %t"``: the particle id,
optionally the cell volume and its total face area, optionally the neighbour behind each face
(``%n``), then ``%t``, each face as the parenthesised, comma-separated loop of its vertex
indices, e.g. ``7 0.0351 0.6219 (1,3,2) (1,5,4,3) ...``.

With ``%n``, a cell with a face on a wall of the container (a negative neighbour id: Voro++
numbers the walls -1 to -6) is a boundary grain, and the others are not; without it, the file
does not tell.

Voro++'s loops turn clockwise seen from outside; they are read turned round, so that the
neighbour lists turn counter-clockwise, as those of every reader with geometry do.
"""

from __future__ import annotations

import itertools
import re
from collections.abc import Iterable, Iterator

import numpy as np

from grainclass.batch import GrainBatch, no_body_has
from grainclass.readers.loops import LoopText

LINE = re.compile(rb"^\s*-?\d+(\s+[-+0-9.eE]+)*\s+\(\s*\d+(\s*,\s*\d+)*\s*\)")
SNIFFED_LINES = 5


def looks_like_voro(head: bytes) -> bool:
    """True when one of the first lines of ``head`` that are not blank or comments is a cell
    written by ``%i [%v [%F]] %t``: no other format has a parenthesised loop, and one odd cell
    at the top should not make the whole file unreadable."""
    lines = (
        line for line in head.splitlines() if line.strip() and not line.lstrip().startswith(b"#")
    )
    return any(LINE.match(line) for line in itertools.islice(lines, SNIFFED_LINES))


# A loop "(1,3,2)" read as the loop text of loops.py, "1 3 2;" (byte for byte, in C).
_AS_LOOP_TEXT = bytes.maketrans(b"(,)", b"  ;")


def read_voro(lines: Iterable[bytes], source: str, chunk_size: int) -> Iterator[GrainBatch]:
    """Parse Voro++ ``%t`` output into batches of at most ``chunk_size`` cells."""
    unreadable = "cannot read this cell: expected id [volume [area]] [neighbours] (loop) ..."
    rows = LoopText(source, unreadable, clockwise=True)
    for line_no, raw in enumerate(lines, 1):
        line = raw.strip()
        if not line or line.startswith(b"#"):
            continue
        head, paren, loops = line.partition(b"(")
        tokens = head.decode("utf-8", "replace").split()
        grain_id = tokens[0] if tokens else f"line{line_no}"
        boundary = None
        try:
            n_loops = loops.count(b"(") + 1
            if paren and len(tokens) > 3:  # %n: a neighbour per face, after the numbers
                if len(tokens) - 1 < n_loops or len(tokens) - 1 - n_loops > 2:
                    raise ValueError(
                        f"{len(tokens) - 1} numbers before {n_loops} loops: expected "
                        "[volume [area]] and a neighbour (%n) per face"
                    )
                boundary = any(int(t) < 0 for t in tokens[-n_loops:])
                tokens = tokens[:-n_loops]
            if not paren or not 1 <= len(tokens) <= 3:
                raise ValueError("expected: id [volume [area]] [neighbours] (loop) (loop) ...")
            if n_loops != loops.count(b")") or not loops.endswith(b")"):
                raise ValueError("a face loop is not closed by ')' (a cut-off line?)")
            int(tokens[0])
            numbers = [float(t) for t in tokens[1:]] + [np.nan, np.nan]
            if any(number < 0 for number in numbers[:2]):  # NaN, an absent one, is not < 0
                raise ValueError(f"a negative volume or area ({' '.join(tokens[1:])})")
        except ValueError as exc:
            rows.add_unreadable(grain_id, line_no, f"cannot read this cell: {exc}")
        else:
            # No body has 36 pi V^2 > S^3: the two numbers are not %v then %F (a "%i %F %v %t"
            # file would otherwise give every grain the other's volume and area).
            volume, area = numbers[0], numbers[1]
            if no_body_has(volume, area):
                message = (
                    f"volume {volume:g} and area {area:g} cannot both be right "
                    '(36 pi V^2 > S^3): expected a cell as voro++ -c "%i %v %F %t" writes it'
                )
                rows.add_unreadable(grain_id, line_no, f"cannot read this cell: {message}")
            else:
                text = (paren + loops).translate(_AS_LOOP_TEXT)
                rows.add(grain_id, line_no, text, volume, area, boundary)
        if len(rows) >= chunk_size:
            yield rows.batch()
            rows = LoopText(source, unreadable, clockwise=True)
    if len(rows):
        yield rows.batch()
