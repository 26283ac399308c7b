"""The options that several commands share, defined once, and the objects they build: every
command that reads grains gets one ``reading`` (:class:`grainclass.options.ReadOptions`), every
command that writes a table one ``output`` (:class:`grainclass.options.OutputOptions`).

One vocabulary: ``--input-format`` names the format of inputs, ``--format`` that of outputs,
``--belt-length L`` the longest belts taken into account, in every command.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import Any, TypeVar

import click

from grainclass.cli import startup
from grainclass.options import (
    DEFAULT_CHUNK_SIZE,
    DEFAULT_TRIPLE_EDGES,
    LONGEST_BELT,
    MAX_CHUNK_SIZE,
    SHORTEST_BELT,
)
from grainclass.vocabulary import INPUT_FORMATS, OUTPUT_FORMATS

F = TypeVar("F", bound=Callable[..., Any])

# The command-line flag of each library parameter, for messages about them.
FLAGS = {
    "input_format": "--input-format",
    "chunk_size": "--chunk-size",
    "triple_edges": "--triple-edges",
    "types": "--types",
    "belt_length": "--belt-length",
    "include_boundary": "--include-boundary",
    "jobs": "--jobs",
    "format": "--format",
    "output": "--output",
    "n_values": "--n",
    "n_faces": "--n",
    "class_name": "--class",
    "labels": "--label",
    "steps": "--times",
    "series": "--series",
    "penalty": "--penalty",
    "min_frequency": "--min-frequency",
    "seed": "--seed",
    "flips": "--flips",
    "kind": "KIND",
    "periodic": "--periodic",
    "box": "--box",
    "radius_column": "--radius-column",
    "workers": "--workers",
    "scheduler": "--scheduler",
    "ids": "--id",
    "weinberg": "--weinberg",
    "named": "--named",
    "top": "--top",
    "outer_face": "--outer-face",
    "face_label": "--labels",
    "belt": "--belt",
    "columns": "--columns",
    "solid": "--3d",
    "spacing": "--spacing",
    "background": "--background",
    "components": "--components",
}


def key_value(ctx: click.Context, param: click.Parameter, value: str) -> tuple[str, str]:
    """``KEY=VALUE`` as a pair of stripped strings."""
    key, sep, val = value.partition("=")
    if not sep or not key.strip() or not val.strip():
        raise click.BadParameter(f"expected KEY=VALUE, got {value!r}")
    return key.strip(), val.strip()


def nonempty_path(ctx: click.Context, param: click.Parameter, value: str | None) -> str | None:
    """A path given as an empty string names nothing (a shell variable unset, say), and one
    with a NUL byte nothing the system can open."""
    if value == "":
        raise click.BadParameter("an empty path names no file")
    if value is not None and "\x00" in value:
        raise click.BadParameter("a path holds no NUL byte")
    return value


def figure_path(ctx: click.Context, param: click.Parameter, value: str) -> str:
    """A figure's path: a .png, .svg or .pdf file."""
    from grainclass.errors import OptionError
    from grainclass.plots import figure_format

    nonempty_path(ctx, param, value)
    try:
        figure_format(value)
    except OptionError as exc:
        raise click.BadParameter(exc.message) from None
    return value


def figure_output() -> Callable[[F], F]:
    """``-o/--output FIGURE``: the figure a command draws."""
    return click.option(
        "-o",
        "--output",
        required=True,
        metavar="FIGURE",
        callback=figure_path,
        help="The figure: .png, .svg or .pdf.",
    )


def output_folder(ctx: click.Context, param: click.Parameter, value: str | None) -> str | None:
    """A folder to write into (a census, a data set in parts): neither ``-`` nor a file."""
    import os

    nonempty_path(ctx, param, value)
    if value == "-":
        raise click.BadParameter("this is written into a folder, not to standard output")
    bare = value.rstrip("/" + os.sep) or value if value is not None else None
    if bare is not None and os.path.lexists(bare) and not os.path.isdir(bare):
        raise click.BadParameter(f"{value!r} is not a folder")
    return value


def is_folder(path: str) -> bool:
    """Whether an output names a folder to write a data set in parts into: a path that ends with
    ``/`` (a folder named without it stays an output file that cannot be written, as before)."""
    import os

    return path.endswith(("/", os.sep))


def _address(ctx: click.Context, param: click.Parameter, value: str | None) -> str | None:
    if value is not None and not value.strip():
        raise click.BadParameter("an empty address names no scheduler")
    return value


def cluster(what: str) -> Callable[[F], F]:
    """``--scheduler ADDRESS`` and ``--workers N``: where the Dask tasks of ``what`` run."""
    return _stack(
        [
            click.option(
                "--scheduler",
                metavar="ADDRESS",
                callback=_address,
                help=f"Run {what} on an existing Dask cluster (tcp://host:port) instead of a "
                "local one.",
            ),
            click.option(
                "--workers",
                type=click.IntRange(1, 4096),
                help="Worker processes of the local cluster, up to four per CPU this process "
                "may use (default: one per CPU).",
            ),
        ]
    )


def vertex_counts(ctx: click.Context, param: click.Parameter, values: tuple[str, ...]) -> list[int]:
    """N arguments: numbers of vertices, or ranges ``A..B`` (both ends included)."""
    ns: list[int] = []
    for value in values:
        low, dots, high = value.partition("..")
        try:
            ns += list(range(int(low), int(high) + 1)) if dots else [int(value)]
        except ValueError:
            raise click.BadParameter(f"expected N or A..B, got {value!r}") from None
    if not ns or min(ns) < 4 or max(ns) > 64:
        raise click.BadParameter("numbers of vertices go from 4 to 64")
    return sorted(set(ns))


def _stack(options: list[Callable[[F], F]]) -> Callable[[F], F]:
    def decorate(command: F) -> F:
        for option in reversed(options):
            command = option(command)
        return command

    return decorate


def _deprecated(old: str, new: str) -> Callable[[click.Context, click.Parameter, Any], Any]:
    def warn(ctx: click.Context, param: click.Parameter, value: Any) -> Any:
        if value is not None:
            click.echo(f"grainclass: warning: {old} is deprecated: use {new}", err=True)
        return value

    return warn


MAX_FACES = 2**31 - 1  # the n_faces column is int32
MAX_SEED = 2**64 - 1


def faces(help: str, multiple: bool = True, name: str = "n_values") -> Callable[[F], F]:
    """``--n N``: grains with N faces (4 to 2^31 - 1), repeatable unless not ``multiple``."""
    return click.option(
        "--n",
        name,
        type=click.IntRange(4, MAX_FACES),
        multiple=multiple,
        metavar="N",
        help=help,
    )


def seed(help: str) -> Callable[[F], F]:
    """``--seed S``: a random seed, 0 to 2^64 - 1."""
    return click.option("--seed", type=click.IntRange(0, MAX_SEED), metavar="S", help=help)


def belt_length(
    help: str, default: int | None = None, deprecated_alias: bool = False
) -> Callable[[F], F]:
    """``--belt-length L``, L from 4 to 10; ``--belt-lengths`` is kept, hidden, for a release."""
    options = [
        click.option(
            "--belt-length",
            type=click.IntRange(SHORTEST_BELT, LONGEST_BELT),
            default=default,
            show_default=default is not None,
            metavar="L",
            help=help,
        )
    ]
    if deprecated_alias:
        options.append(
            click.option(
                "--belt-lengths",
                "deprecated_belt_lengths",
                type=click.IntRange(SHORTEST_BELT, LONGEST_BELT),
                hidden=True,
                callback=_deprecated("--belt-lengths", "--belt-length"),
            )
        )
    return _stack(options)


def reading(
    types_default: bool | None = True,
    boundary: bool = True,
    belts: Callable[[F], F] | None = None,
    deprecated_format: bool = False,
    quiet_help: str = "No progress on stderr.",
) -> Callable[[F], F]:
    """The options of a command that reads grains, passed to it as one ``reading``
    (:class:`~grainclass.options.ReadOptions`) and ``quiet``: --input-format, --triple-edges,
    --chunk-size, --jobs, --quiet; --types/--no-types unless ``types_default`` is None (the
    command always computes them, or never needs them); --include-boundary if ``boundary``;
    the ``belts`` option (:func:`belt_length`) if given; classify's old --format if
    ``deprecated_format``."""
    options: list[Callable[[F], F]] = [
        click.option(
            "--input-format",
            type=click.Choice(["auto", *INPUT_FORMATS]),
            default="auto",
            show_default=True,
            help="Input format; 'auto' sniffs each input.",
        ),
        click.option(
            "--triple-edges",
            default="=".join(DEFAULT_TRIPLE_EDGES),
            show_default=True,
            metavar="KEY=VALUE",
            callback=key_value,
            help="Surface Evolver: the edge attribute that marks triple lines.",
        ),
        click.option(
            "--chunk-size",
            type=click.IntRange(min=1, max=MAX_CHUNK_SIZE),
            default=DEFAULT_CHUNK_SIZE,
            show_default=True,
            help="Grains per batch (and per Parquet row group).",
        ),
        click.option(
            "-j",
            "--jobs",
            type=click.IntRange(min=1, max=1 << 16),
            help="Threads for the compiled kernels (default: the CPUs this process may use).",
        ),
        click.option("-q", "--quiet", is_flag=True, help=quiet_help, callback=startup.note_quiet),
        *image_options(),
    ]
    if types_default is not None:
        options.append(
            click.option(
                "--types/--no-types",
                default=types_default,
                show_default=True,
                help="Compute the Weinberg vectors (weinberg, symmetry, chirality) of raw "
                "inputs; they cost several times the rest of the classification.",
            )
        )
    if boundary:
        options.append(
            click.option(
                "--include-boundary",
                is_flag=True,
                help="Count grains cut by a sample boundary too.",
            )
        )
    if belts is not None:
        options.append(belts)
    if deprecated_format:
        options.append(
            click.option(
                "--format",
                "deprecated_format",
                type=click.Choice(INPUT_FORMATS),
                hidden=True,
                callback=_deprecated("classify --format", "--input-format"),
            )
        )

    def decorate(command: F) -> F:
        @functools.wraps(command)
        def with_reading(*args: Any, **kwargs: Any) -> Any:
            from grainclass.options import ReadOptions

            input_format = kwargs.pop("input_format")
            input_format = kwargs.pop("deprecated_format", None) or input_format
            length = kwargs.pop("belt_length", None)
            length = kwargs.pop("deprecated_belt_lengths", None) or length
            kwargs["reading"] = ReadOptions(
                input_format=None if input_format == "auto" else input_format,
                chunk_size=kwargs.pop("chunk_size"),
                triple_edges=kwargs.pop("triple_edges"),
                types=kwargs.pop("types", True if types_default is None else types_default),
                belt_length=length,
                include_boundary=kwargs.pop("include_boundary", False),
                jobs=kwargs.pop("jobs"),
                periodic=kwargs.pop("periodic"),
                spacing=kwargs.pop("spacing"),
                background=kwargs.pop("background"),
                components=kwargs.pop("components"),
            )
            return command(*args, **kwargs)

        return _stack(options)(with_reading)  # type: ignore[return-value]

    return decorate


def _periodic_axes(ctx: click.Context, param: click.Parameter, value: str | None) -> str | None:
    if value is None:
        return None
    axes = value.strip().lower()
    axes = "" if axes == "none" else axes
    if set(axes) - set("xyz") or len(set(axes)) != len(axes):
        raise click.BadParameter(f"expected some of x, y, z (xyz, xy, ...) or none, got {value!r}")
    return axes


def _spacing(
    ctx: click.Context, param: click.Parameter, value: str | None
) -> tuple[float, float, float] | None:
    import math

    if value is None:
        return None
    try:
        sizes = tuple(float(part) for part in value.split(","))
    except ValueError:
        sizes = ()
    if len(sizes) == 1:
        sizes = sizes * 3
    if len(sizes) != 3 or not all(math.isfinite(d) and d > 0 for d in sizes):
        raise click.BadParameter(f"expected DX,DY,DZ (or D), positive numbers, got {value!r}")
    return sizes  # type: ignore[return-value]


def image_options() -> list[Callable[[F], F]]:
    """--periodic, --spacing, --background, --components: how a label image is read."""
    return [
        click.option(
            "--periodic",
            metavar="AXES",
            callback=_periodic_axes,
            help="Label images: the axes that wrap (xyz, xy, ..., none). Default: as the file "
            "says, else none (a grain on a side of the image is a boundary grain).",
        ),
        click.option(
            "--spacing",
            metavar="DX,DY,DZ",
            callback=_spacing,
            help="Label images: the size of a voxel (volume = voxels x DX DY DZ). Default: as "
            "the file says, else 1.",
        ),
        click.option(
            "--background",
            type=click.IntRange(min=0),
            multiple=True,
            metavar="ID",
            help="Label images: a label that is no grain (repeatable); grains touching it are "
            "boundary grains.",
        ),
        click.option(
            "--components",
            is_flag=True,
            help="Label images: each connected piece of a label is a grain of its own "
            "(needs grainclass[images]).",
        ),
    ]


def table_output(help: str = "Write here instead of stdout.") -> Callable[[F], F]:
    """``-o/--output`` and ``--format`` of a command that writes a table, passed to it as one
    ``output`` (:class:`~grainclass.options.OutputOptions`)."""
    options: list[Callable[[F], F]] = [
        click.option(
            "-o", "--output", default="-", metavar="FILE", callback=nonempty_path, help=help
        ),
        click.option(
            "--format",
            "output_format",
            type=click.Choice(OUTPUT_FORMATS),
            help="Output format (default: from the -o extension, else text).",
        ),
    ]

    def decorate(command: F) -> F:
        @functools.wraps(command)
        def with_output(*args: Any, **kwargs: Any) -> Any:
            from grainclass.options import OutputOptions

            kwargs["output"] = OutputOptions(kwargs.pop("output"), kwargs.pop("output_format"))
            return command(*args, **kwargs)

        return _stack(options)(with_output)  # type: ignore[return-value]

    return decorate
