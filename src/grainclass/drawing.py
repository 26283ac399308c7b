"""The grains ``grainclass draw`` draws, and what it draws on them.

Grains come by id from the inputs (a raw input's grain as read; a per-grain Parquet row from its
Weinberg vector, the table holding no faces), by Weinberg vector, by name
(:data:`grainclass.weinberg_grains.NAMED_GRAINS`), or as a data set's most frequent types
(:func:`grainclass.datasets.type_counts`), each drawn from its Weinberg vector. Only ok grains
have a Schlegel diagram: any other is refused, with what is wrong with it.

On each grain: its belts of a length (:func:`grainclass.schlegel.belts`); what each edge's flip
gives, by the Weinberg vector of every grain one flip makes (:func:`grainclass.perturb.all_flips`)
against the grain's own; and its reverse truncations, as the classification makes them (the
kernels ``_reduce`` and ``_parents_from_links``).
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from grainclass import interrupts, schema
from grainclass.batch import GrainBatch, Shape, offsets_from_counts, run_indices
from grainclass.errors import DataError, OptionError, Remedy
from grainclass.options import DrawingOptions, ReadOptions
from grainclass.schlegel import Belt, GrainDrawing, Truncations, belts, diagram
from grainclass.weinberg_grains import NAMED_GRAINS, grain_from_weinberg, parse_weinberg

if TYPE_CHECKING:
    import pyarrow as pa

Lists = list[list[int]]
Watch = Callable[[Iterable[Any]], Iterable[Any]]

MAX_PANELS = 100
"""Panels one figure may hold: past this, a figure is no longer read panel by panel."""


def _unwatched(items: Iterable[Any]) -> Iterable[Any]:
    return items


@dataclass
class _Subject:
    """A grain to draw: its lists (turning one way), its classification row, the names of its
    faces, its panels' title and what the data says of it besides."""

    grain_id: str
    title: str
    lists: Lists
    row: dict
    face_ids: tuple[str, ...]
    fields: dict = field(default_factory=dict)
    caption: str = ""
    shape: Shape | None = None


def grain_drawings(
    paths: Sequence[str],
    request: DrawingOptions,
    options: ReadOptions | None = None,
    watch: Watch = _unwatched,
) -> list[GrainDrawing]:
    """The drawings of the grains ``request`` asks for, in the order ids, Weinberg vectors,
    names, most frequent types.

    Parameters
    ----------
    paths : sequence of str
        Inputs of any format grainclass reads, or per-grain Parquet files: where ids are looked
        for and types counted. Needed by ``request.ids`` and a gallery, refused otherwise.
    request : DrawingOptions
        Which grains, and what is drawn on them.
    options : ReadOptions, optional
        How the inputs are read.

    Raises
    ------
    OptionError
        For inputs given with nothing to draw from them, or ids or a gallery without inputs;
        an unknown name; a vector that is no grain's Weinberg vector.
    DataError
        For an id not in the inputs, a grain that is not ok, an outer face or belt the grain
        does not have, a data set with no types to draw, or more than :data:`MAX_PANELS`
        panels.
    InputError
        For an input that cannot be read.

    Examples
    --------
    >>> cube = grain_drawings([], DrawingOptions(named=("cube",), flips=True))[0]
    >>> cube.caption, sorted(set(cube.flips))
    ('6 faces (0,6) flag 1:1', ['other'])
    """
    options = ReadOptions.of(options, geometry=request.solid)
    needs_inputs = bool(request.ids) or request.gallery
    if paths and not needs_inputs:
        raise OptionError("ids", "inputs given, but no grain of them chosen (by id or top)")
    if needs_inputs and not paths:
        raise OptionError("ids", "grains by id and the most frequent types need inputs")
    for name in request.named:
        if name not in NAMED_GRAINS:
            raise OptionError("named", f"no grain named {name!r}: one of {', '.join(NAMED_GRAINS)}")
    codes = [parse_weinberg(code) for code in request.weinberg]
    subjects = _by_id(paths, request.ids, options, watch) if request.ids else []
    if request.solid:
        for subject in subjects:
            if subject.shape is None:
                raise DataError(
                    f"grain {subject.grain_id}: {subject.fields['source']} has no corner "
                    "positions to draw it in space (Surface Evolver and Neper inputs have them)"
                )
    built = [
        *[(_shortened(code), grain_from_weinberg(code), {}) for code in codes],
        *[
            (name, grain_from_weinberg(NAMED_GRAINS[name].weinberg), {"name": name})
            for name in request.named
        ],
    ]
    if request.gallery:
        built += _most_frequent(paths, request, options, watch)
    subjects += _classified(built)
    drawings = []
    for subject, flips in _with_flips(subjects, request):
        interrupts.checkpoint()  # a stop asked for is taken between grains
        drawings.append(_drawing(subject, request, flips))
    return drawings


def _shortened(code: Sequence[int]) -> str:
    text = "(" + ",".join(map(str, code)) + ")"
    return text if len(text) <= 24 else text[:21] + "...)"


def _classified(built: list[tuple[str, Lists, dict]]) -> list[_Subject]:
    """Grains made from Weinberg vectors, classified; their faces named by position."""
    from grainclass.classification import classify

    if not built:
        return []
    rows = classify(GrainBatch.from_lists([lists for _, lists, _ in built])).to_pylist()
    subjects = []
    for (title, lists, fields), row in zip(built, rows, strict=True):
        fields = {"weinberg": row[schema.WEINBERG], **fields}
        grain_id = fields.get("name") or row[schema.WEINBERG]
        subjects.append(_Subject(grain_id, title, lists, row, _positions(len(lists)), fields))
    return subjects


def _positions(n: int) -> tuple[str, ...]:
    return tuple(str(f) for f in range(n))


def _ids(batch: GrainBatch) -> list[str]:
    ids = batch.grain_id
    return [str(i) for i in (ids.to_pylist() if hasattr(ids, "to_pylist") else ids)]


def _by_id(
    paths: Sequence[str], wanted: Sequence[str], options: ReadOptions, watch: Watch
) -> list[_Subject]:
    """The first grain with each id in the inputs, in the order of ``wanted``."""
    from grainclass.parquet import iter_grain_tables
    from grainclass.pipeline import input_runs
    from grainclass.readers import read_dataset

    found: dict[str, _Subject] = {}
    pending = set(wanted)
    for parquet, group in input_runs(list(paths)):
        if not pending:
            break
        if parquet:
            tables = iter_grain_tables(group[0], schema.GRAIN_SCHEMA.names)
            with contextlib.closing(tables):
                for table in watch(tables):
                    found |= _rows_with_ids(table, pending, group[0])
                    pending -= set(found)
                    if not pending:
                        break
        else:
            batches = read_dataset(group, options)
            with contextlib.closing(batches):
                for batch in watch(batches):
                    ids = _ids(batch)
                    positions = [g for g, i in enumerate(ids) if i in pending]
                    # The first grain of each id only.
                    positions = list({ids[g]: g for g in reversed(positions)}.values())
                    if positions:
                        found |= _grains_at(batch, sorted(positions))
                        pending -= set(found)
                    if not pending:
                        break
    missing = [i for i in wanted if i not in found]
    if missing:
        shown = ", ".join(missing[:5]) + (", ..." if len(missing) > 5 else "")
        where = ", ".join(paths) if len(paths) <= 3 else f"{len(paths)} inputs"
        raise DataError(f"no grain with id {shown} in {where}")
    return [found[i] for i in dict.fromkeys(wanted)]


def _grains_at(batch: GrainBatch, positions: list[int]) -> dict[str, _Subject]:
    """The grains at ``positions`` of a batch, classified and their lists turned one way."""
    from grainclass.classification import classify
    from grainclass.perturb import check

    picked = _pick(batch, positions)
    rows = classify(picked).to_pylist()
    for row in rows:
        _require_ok(row)
    checked = check(picked)
    subjects = {}
    for g, row in enumerate(rows):
        first, last = picked.face_offsets[g], picked.face_offsets[g + 1]
        lists = [
            checked.lists[picked.nbr_offsets[f] : picked.nbr_offsets[f + 1]].tolist()
            for f in range(first, last)
        ]
        if picked.face_labels is not None:
            face_ids = tuple(str(label) for label in picked.face_labels[first:last].tolist())
        else:
            face_ids = _positions(len(lists))
        grain_id = row[schema.GRAIN_ID]
        fields = {"source": row[schema.SOURCE], "weinberg": row[schema.WEINBERG]}
        shape = None if picked.shapes is None else picked.shapes[g]
        subjects[grain_id] = _Subject(grain_id, grain_id, lists, row, face_ids, fields, "", shape)
    return subjects


def _pick(batch: GrainBatch, positions: list[int]) -> GrainBatch:
    """The grains at ``positions`` of a batch as a batch of their own, with their sources and
    places in the input, so that what is said of them says where they are."""
    at = np.asarray(positions, np.int64)
    counts = np.diff(batch.face_offsets)[at]
    faces = run_indices(batch.face_offsets[at], counts)
    degrees = np.diff(batch.nbr_offsets)[faces]
    ids = _ids(batch)
    where = {p: i for i, p in enumerate(positions)}
    return GrainBatch(
        source=batch.source if isinstance(batch.source, str) else [batch.source[p] for p in at],
        grain_id=[ids[p] for p in positions],
        location=batch.location[at],
        location_kind=batch.location_kind,
        face_offsets=offsets_from_counts(counts),
        nbr_offsets=offsets_from_counts(degrees),
        neighbors=batch.neighbors[run_indices(batch.nbr_offsets[faces], degrees)],
        parse_errors={where[p]: m for p, m in batch.parse_errors.items() if p in where},
        face_labels=None if batch.face_labels is None else batch.face_labels[faces],
        shapes=None if batch.shapes is None else [batch.shapes[p] for p in positions],
    )


def _require_ok(row: dict) -> None:
    if row[schema.STATUS] != "ok":
        raise DataError(
            f"grain {row[schema.GRAIN_ID]} is {row[schema.STATUS]} ({row[schema.ERROR]}): "
            "only an ok grain, a simple polytope, has a Schlegel diagram"
        )


def _rows_with_ids(table: pa.Table, pending: set[str], path: str) -> dict[str, _Subject]:
    """The first row of each pending id in a per-grain table, drawn from its Weinberg vector."""
    found: dict[str, _Subject] = {}
    ids = table.column(schema.GRAIN_ID).to_pylist()
    for i, grain_id in enumerate(ids):
        if grain_id not in pending or grain_id in found:
            continue
        row = table.slice(i, 1).to_pylist()[0]
        _require_ok(row)
        code = row[schema.WEINBERG]
        if code is None:
            raise DataError(
                f"{path}: grain {grain_id} has no Weinberg vector, from which a table's grain is "
                "drawn",
                Remedy("types", True, reclassify=True),
            )
        lists = grain_from_weinberg(code)
        fields = {"source": row[schema.SOURCE], "weinberg": code}
        found[grain_id] = _Subject(grain_id, grain_id, lists, row, _positions(len(lists)), fields)
    return found


def _most_frequent(
    paths: Sequence[str], request: DrawingOptions, options: ReadOptions, watch: Watch
) -> list[tuple[str, Lists, dict]]:
    """The data set's most frequent types (as ``grainclass types`` counts them), each with
    its rank, count and frequency."""
    from grainclass.datasets import type_counts

    types = type_counts(list(paths), options, watch, request.n_faces, request.class_name)
    chosen = types.head(request.top) if request.top is not None else types
    if not len(chosen):
        raise DataError(f"{', '.join(paths)}: no ok grains of the types asked for, none to draw")
    if len(chosen) > MAX_PANELS:
        raise DataError(
            f"{len(chosen)} types to draw, more than the {MAX_PANELS} panels a figure holds",
            Remedy("top", MAX_PANELS),
        )
    built = []
    for rank, (code, count, fraction) in enumerate(
        zip(chosen[schema.WEINBERG], chosen["count"], chosen["fraction"], strict=True), 1
    ):
        title = f"{rank}. {int(count)} grains, {100 * float(fraction):.2f}%"
        fields = {"rank": rank, "count": int(count), "fraction": float(fraction)}
        built.append((title, grain_from_weinberg(code), fields))
    return built


def _with_flips(
    subjects: list[_Subject], request: DrawingOptions
) -> list[tuple[_Subject, dict[tuple[int, int], str] | None]]:
    """Each grain with what each admissible flip gives it: ``{(a, b): "same" | "other"}`` for
    the flip of the edge between faces a < b (when ``request.flips``)."""
    if not request.flips or not subjects:
        return [(subject, None) for subject in subjects]
    from grainclass.classification import classify
    from grainclass.perturb import FLIPPED_EDGE, FROM_GRAIN, all_flips

    batch = GrainBatch.from_lists([s.lists for s in subjects])
    flipped = all_flips(batch)
    codes = classify(flipped.batch).column(schema.WEINBERG).to_pylist()
    sources = flipped.batch.attributes[FROM_GRAIN]
    edges = flipped.batch.attributes[FLIPPED_EDGE]
    results: list[dict[tuple[int, int], str]] = [{} for _ in subjects]
    for source, edge, code in zip(sources, edges, codes, strict=True):
        g = int(source) - 1  # GrainBatch.from_lists numbers grains from 1
        a, b = (int(face) for face in edge.split("-"))
        results[g][(a, b)] = "same" if code == subjects[g].row[schema.WEINBERG] else "other"
    return list(zip(subjects, results, strict=True))


def _drawing(
    subject: _Subject, request: DrawingOptions, flips: dict[tuple[int, int], str] | None
) -> GrainDrawing:
    lists = subject.lists
    if request.outer_face is not None and request.outer_face >= len(lists):
        raise DataError(
            f"grain {subject.grain_id} has {len(lists)} faces, 0 to {len(lists) - 1}: "
            f"no face {request.outer_face} to put outside"
        )
    d = diagram(lists, request.outer_face)
    flip_styles = None
    if flips is not None:
        flip_styles = tuple(flips.get((int(f), int(g)), "none") for f, g in d.edges[:, 2:])
    chosen: tuple[Belt, ...] = ()
    numbers: tuple[int, ...] = ()
    count = 0
    if request.belt_length is not None:
        found = belts(lists, request.belt_length)
        count = len(found)
        numbers = tuple(range(1, count + 1))
        if request.belt is not None:
            if request.belt > count:
                raise DataError(
                    f"grain {subject.grain_id} has {count} belts of {request.belt_length} faces, "
                    f"no belt {request.belt}"
                )
            numbers = (request.belt,)
        chosen = tuple(found[k - 1] for k in numbers)
    truncations = _truncations(lists, subject.row[schema.TREES]) if request.trees else None
    return GrainDrawing(
        grain_id=subject.grain_id,
        title=subject.title,
        caption=subject.caption or caption(subject.row),
        diagram=d,
        face_ids=subject.face_ids,
        labels=request.face_label_kind,
        dual=request.dual,
        flips=flip_styles,
        belt_length=request.belt_length,
        belts=chosen,
        belt_numbers=numbers,
        belt_count=count,
        truncations=truncations,
        shape=subject.shape if request.solid else None,
        fields=subject.fields | _classification_fields(subject.row),
    )


def caption(row: dict) -> str:
    """A grain in a line: its faces, p-vector, class and, for a flag grain, split type.

    >>> caption({"n_faces": 6, "p_vector": [0, 6], "class": "flag", "split_k": 1, "split_m": 1})
    '6 faces (0,6) flag 1:1'
    """
    words = [
        f"{row[schema.N_FACES]} faces",
        "(" + ",".join(map(str, row[schema.P_VECTOR])) + ")",
        row[schema.CLASS],
    ]
    if row.get(schema.SPLIT_K) is not None:
        words.append(f"{row[schema.SPLIT_K]}:{row[schema.SPLIT_M]}")
    return " ".join(words)


def _classification_fields(row: dict) -> dict:
    """What the drawing's data repeats of the grain's classification."""
    return {
        schema.N_FACES: row[schema.N_FACES],
        schema.P_VECTOR: row[schema.P_VECTOR],
        schema.CLASS: row[schema.CLASS],
        schema.SPLIT_K: row[schema.SPLIT_K],
        schema.SPLIT_M: row[schema.SPLIT_M],
        schema.SYMMETRY: row[schema.SYMMETRY],
    }


def _truncations(lists: Lists, forest: str | None) -> Truncations:
    """The reverse truncations of a grain, as the general classification kernel removes its
    triangles, round by round."""
    from grainclass._kernels.reduce import _reduce
    from grainclass._kernels.trees import _parents_from_links

    n = len(lists)
    off = offsets_from_counts([len(nbrs) for nbrs in lists])
    nb = np.array([x for nbrs in lists for x in nbrs], np.int32)
    alive = np.empty(n, np.bool_)
    removed_round = np.empty(n, np.int32)
    link = np.empty((n, 3), np.int32)
    _reduce(n, off, nb, alive, removed_round, link)
    parent = np.empty(n, np.int32)
    _parents_from_links(n, alive, removed_round, link, parent)
    depth = [0] * n
    # A parent goes in a later round than its children: deepest first is latest round last.
    for v in sorted(range(n), key=lambda v: -removed_round[v]):
        if not alive[v]:
            depth[v] = 1 if parent[v] < 0 else depth[parent[v]] + 1
    return Truncations(tuple(depth), tuple(int(p) for p in parent), forest)
