"""How grains are read, what a figure draws and where results go: small frozen objects, built
once per command (or per library call) and passed whole through readers, pipeline, summaries
and figures.

Each field is checked once, here, when the object is made: a value the library cannot take is an
:class:`~grainclass.errors.OptionError` that names the field, which the command line words with
its flag.
"""

from __future__ import annotations

import dataclasses
import os
from dataclasses import dataclass
from typing import Any

from grainclass.errors import OptionError
from grainclass.vocabulary import (
    CLASSES,
    FACE_LABELS,
    INPUT_FORMATS,
    NAMED_SERIES,
    OUTPUT_FORMATS,
    PENALTIES,
    PLOT_KINDS,
)

DEFAULT_CHUNK_SIZE = 50_000
"""Grains per batch: per compiled call, per thread and per Parquet row group."""

MAX_CHUNK_SIZE = 10_000_000
"""Readers size their arrays for a whole chunk at once: a typo's 10**11 would ask for 745 GB."""

DEFAULT_TRIPLE_EDGES = ("color", "red")
"""The Surface Evolver edge attribute that marks triple lines, as the grain-growth files have it."""

SHORTEST_BELT, LONGEST_BELT = 4, 10
"""The belt lengths a reading may ask for: 4-belts are the paper's; beyond 10 the counts grow
past what a per-grain list is for."""

SHORTEST_DRAWN_BELT = 3
"""A drawing shows 3-belts too: the non-trivial one of a severely constricted grain is what
the paper draws it for (fig. smallest_nonflag)."""

TABLE_EXTENSIONS = {
    ".txt": "text",
    ".csv": "csv",
    ".md": "markdown",
    ".markdown": "markdown",
    ".tex": "latex",
    ".latex": "latex",
    ".json": "json",
    ".parquet": "parquet",
}
"""The format of a table output named by its file's extension."""


@dataclass(frozen=True)
class ReadOptions:
    """How the grains of inputs are read and classified.

    Parameters
    ----------
    input_format : str or None
        One of :data:`grainclass.vocabulary.INPUT_FORMATS`; None sniffs each input.
    chunk_size : int
        Grains per batch (and per Parquet row group), 1 to :data:`MAX_CHUNK_SIZE`.
    triple_edges : (str, str)
        Surface Evolver: the edge attribute and value that mark triple lines.
    types : bool
        Compute the Weinberg vectors (weinberg, symmetry, chirality) of raw inputs.
    belt_length : int or None
        Take belts up to this length (4 to 10) into account: per-grain lists of belts of
        lengths 3..L, the split type of L-belts in summaries and type counts, belt penalties
        summed over 4..L. None: the paper's 4-belts only.
    include_boundary : bool
        Count grains cut by a sample boundary too (summaries, types and penalties leave them
        out by default: their faces there are cuts, not grain boundaries).
    jobs : int or None
        Threads for the compiled kernels; None: every CPU this process may use.
    geometry : bool
        Keep each grain's corner positions and surface polygons (``GrainBatch.shapes``) where
        the input has them (Surface Evolver, Neper), to draw the grain in space.
    periodic : str or None
        Label images: the axes that wrap (``"xyz"``, ``"xy"``, ..., ``""`` for none); None: as
        the image's file says, else none.
    spacing : (float, float, float) or None
        Label images: the size of a voxel along x, y and z; None: as the file says, else 1.
    background : tuple of int
        Label images: labels that are no grain (a grain touching one is a boundary grain).
    components : bool
        Label images: each connected piece of a label (voxels joined through faces, across
        the axes that wrap) is a grain of its own (needs ``grainclass[images]``).

    Examples
    --------
    >>> ReadOptions(input_format="planar_code").chunk_size
    50000
    >>> ReadOptions(belt_length=12)
    Traceback (most recent call last):
    ...
    grainclass.errors.OptionError: belt lengths go from 4 to 10, not 12
    """

    input_format: str | None = None
    chunk_size: int = DEFAULT_CHUNK_SIZE
    triple_edges: tuple[str, str] = DEFAULT_TRIPLE_EDGES
    types: bool = True
    belt_length: int | None = None
    include_boundary: bool = False
    jobs: int | None = None
    geometry: bool = False
    periodic: str | None = None
    spacing: tuple[float, float, float] | None = None
    background: tuple[int, ...] = ()
    components: bool = False

    def __post_init__(self) -> None:
        if self.input_format is not None:
            require_choice("input_format", self.input_format, INPUT_FORMATS, "input format")
        _require_int("chunk_size", self.chunk_size, 1, MAX_CHUNK_SIZE, "grains per batch")
        if self.belt_length is not None:
            _require_int(
                "belt_length", self.belt_length, SHORTEST_BELT, LONGEST_BELT, "belt lengths"
            )
        if self.jobs is not None:
            _require_int("jobs", self.jobs, 1, 1 << 16, "jobs")
        key_value = tuple(self.triple_edges)
        if len(key_value) != 2 or not all(isinstance(s, str) and s for s in key_value):
            raise OptionError(
                "triple_edges", f"the triple-edge mark is a (key, value) pair, not {key_value!r}"
            )
        object.__setattr__(self, "triple_edges", key_value)
        _check_image_options(self)

    @classmethod
    def of(cls, options: ReadOptions | None = None, **settings: Any) -> ReadOptions:
        """``options`` (default: the defaults) with ``settings`` in place of its fields.

        Raises
        ------
        OptionError
            For a setting that is no field, or a value a field cannot take.
        """
        base = options if options is not None else cls()
        unknown = set(settings) - {field.name for field in dataclasses.fields(cls)}
        if unknown:
            raise OptionError(
                sorted(unknown)[0], f"no such reading option: {', '.join(sorted(unknown))}"
            )
        return dataclasses.replace(base, **settings) if settings else base

    @property
    def longest_belt(self) -> int:
        """The longest belts the classification counts beyond its 4-belts (0: none)."""
        return self.belt_length or 0

    @property
    def split_length(self) -> int:
        """The length of the belts whose split type summaries and type counts give."""
        return self.belt_length or SHORTEST_BELT


def _check_image_options(options: ReadOptions) -> None:
    """The label-image fields of ``options``, checked and put in one form."""
    import math

    if options.periodic is not None:
        axes = options.periodic.lower() if isinstance(options.periodic, str) else "?"
        axes = "" if axes == "none" else axes
        if set(axes) - set("xyz") or len(set(axes)) != len(axes):
            raise OptionError(
                "periodic", f"periodic axes are some of x, y and z (or none), not {axes!r}"
            )
        object.__setattr__(options, "periodic", "".join(a for a in "xyz" if a in axes))
    if options.spacing is not None:
        try:
            spacing = tuple(float(d) for d in options.spacing)
        except (TypeError, ValueError):
            spacing = ()
        if len(spacing) != 3 or not all(math.isfinite(d) and d > 0 for d in spacing):
            raise OptionError(
                "spacing",
                f"the voxel size is three positive numbers DX,DY,DZ, not {options.spacing!r}",
            )
        object.__setattr__(options, "spacing", spacing)
    background = tuple(options.background)
    if not all(isinstance(b, int) and not isinstance(b, bool) and b >= 0 for b in background):
        raise OptionError("background", f"background labels are integers >= 0, not {background!r}")
    object.__setattr__(options, "background", tuple(sorted(set(background))))


@dataclass(frozen=True)
class OutputOptions:
    """Where a table goes and in which format.

    ``path`` is a file, or ``-`` for standard output; ``format`` one of
    :data:`grainclass.vocabulary.OUTPUT_FORMATS`, or None to go by the path's extension
    (:data:`TABLE_EXTENSIONS`), else text.
    """

    path: str = "-"
    format: str | None = None

    def __post_init__(self) -> None:
        if self.format is not None:
            require_choice("format", self.format, OUTPUT_FORMATS, "output format")
        if not self.path:
            raise OptionError("output", "an empty path names no file")

    @property
    def table_format(self) -> str:
        """The format tables are written in."""
        extension = os.path.splitext(self.path)[1].lower()
        return self.format or TABLE_EXTENSIONS.get(extension, "text")


@dataclass(frozen=True)
class FigureOptions:
    """What a figure draws: its ``kind`` (:data:`grainclass.vocabulary.PLOT_KINDS`) and what
    that kind takes: ``n_values`` (round: grains with these numbers of faces),
    ``min_frequency`` and ``penalty`` (penalty: the least frequency drawn, the candidate of
    :data:`grainclass.vocabulary.PENALTIES`), ``series`` and ``steps`` (evolution: classes or
    named kinds to follow, the time of each input), ``seed`` (edge-errors: of the flips,
    default 0)."""

    kind: str
    n_values: tuple[int, ...] = ()
    min_frequency: float = 1e-5
    penalty: str = "P4"
    series: tuple[str, ...] = ("flag",)
    steps: tuple[float, ...] | None = None
    seed: int | None = None

    def __post_init__(self) -> None:
        require_choice("kind", self.kind, PLOT_KINDS, "figure")
        if self.n_values and self.kind != "round":
            raise OptionError("n_values", "numbers of faces choose the grains of the round figure")
        if self.seed is not None and self.kind != "edge-errors":
            raise OptionError("seed", "a seed is that of the edge flips of the edge-errors figure")
        require_choice("penalty", self.penalty, PENALTIES, "penalty")
        if self.penalty != "P4" and self.kind != "penalty":
            raise OptionError("penalty", "a penalty is the candidate of the penalty figure")
        if not 0 <= self.min_frequency <= 1:
            raise OptionError("min_frequency", "a frequency goes from 0 to 1")
        for series in self.series:
            require_choice("series", series, (*CLASSES, *NAMED_SERIES), "series")
        if self.steps is not None and not all(map(_finite, self.steps)):
            raise OptionError("steps", "a time step is a finite number")


@dataclass(frozen=True)
class DrawingOptions:
    """Which grains ``grainclass draw`` draws and what it draws on them.

    Grains: ``ids`` (grains of the inputs, by id), ``weinberg`` (Weinberg vectors),
    ``named`` (names of :data:`grainclass.weinberg_grains.NAMED_GRAINS`), and a data set's
    most frequent types: ``top`` of them, among those with ``n_faces`` faces and of class
    ``class_name`` where given (either alone chooses every such type).

    On each: ``outer_face``, the face that bounds the diagram (0-based; None: the largest);
    ``face_label``, what each face shows (:data:`grainclass.vocabulary.FACE_LABELS`; None:
    ``ids`` with ``trees``, else ``sides``); ``dual``, the dual graph; ``belt_length``, every
    belt of that length (3 to 10; for 3 the non-trivial ones), one panel each, or only the
    ``belt``-th of them (from 1); ``flips``, each edge styled by what its flip gives;
    ``trees``, the faces reverse truncations remove, by depth, and the truncation forest;
    ``solid``, the grain in space beside its diagram, from its input's corner positions (grains
    by id only). ``columns``: panels in a row.
    """

    ids: tuple[str, ...] = ()
    weinberg: tuple[str, ...] = ()
    named: tuple[str, ...] = ()
    top: int | None = None
    n_faces: int | None = None
    class_name: str | None = None
    outer_face: int | None = None
    face_label: str | None = None
    dual: bool = False
    belt_length: int | None = None
    belt: int | None = None
    flips: bool = False
    trees: bool = False
    solid: bool = False
    columns: int | None = None

    def __post_init__(self) -> None:
        if not (self.ids or self.weinberg or self.named or self.gallery):
            raise OptionError(
                "ids",
                "nothing to draw: choose grains by id, Weinberg vector or name, or the most "
                "frequent types",
            )
        if self.top is not None:
            _require_int("top", self.top, 1, 2**63 - 1, "numbers of types")
        if self.n_faces is not None:
            _require_int("n_faces", self.n_faces, 4, 2**31 - 1, "numbers of faces")
        if self.class_name is not None:
            require_choice("class_name", self.class_name, CLASSES, "class")
        if self.outer_face is not None:
            _require_int("outer_face", self.outer_face, 0, 2**31 - 1, "face numbers")
        if self.face_label is not None:
            require_choice("face_label", self.face_label, FACE_LABELS, "face label")
        if self.belt_length is not None:
            _require_int(
                "belt_length", self.belt_length, SHORTEST_DRAWN_BELT, LONGEST_BELT, "belt lengths"
            )
        if self.belt is not None:
            if self.belt_length is None:
                raise OptionError("belt", "a belt is one of the belts of a length: give it")
            _require_int("belt", self.belt, 1, 2**31 - 1, "belt numbers")
        if self.columns is not None:
            _require_int("columns", self.columns, 1, 1000, "columns")
        if self.solid and (self.weinberg or self.named or self.gallery):
            raise OptionError(
                "solid",
                "a grain is drawn in space from its input's corner positions: only grains "
                "chosen by id have them",
            )

    @property
    def gallery(self) -> bool:
        """Whether a data set's most frequent types are drawn."""
        return self.top is not None or self.n_faces is not None or self.class_name is not None

    @property
    def face_label_kind(self) -> str:
        """What each face shows: ``face_label``, or its default."""
        return self.face_label or ("ids" if self.trees else "sides")


def require_choice(name: str, value: object, choices: tuple[str, ...], what: str) -> None:
    """Raise :class:`OptionError` unless ``value`` is one of ``choices``."""
    if value not in choices:
        raise OptionError(name, f"no {what} {value!r}: one of {', '.join(choices)}")


def _require_int(name: str, value: object, low: int, high: int, what: str) -> None:
    if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
        raise OptionError(name, f"{what} go from {low} to {high}, not {value!r}")


def _finite(value: float) -> bool:
    return value == value and abs(value) != float("inf")
