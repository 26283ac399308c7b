"""The options that several commands share, defined once (each use makes its own click.Option)."""

from __future__ import annotations

from collections.abc import Callable
from typing import TypeVar

import click

from grainclass import DEFAULT_CHUNK_SIZE
from grainclass.cli import startup
from grainclass.vocabulary import INPUT_FORMATS, OUTPUT_FORMATS

F = TypeVar("F", bound=Callable)

# Readers size their arrays for a whole chunk at once: a typo's 10**11 would ask for 745 GB.
MAX_CHUNK_SIZE = 10_000_000


def key_value(ctx: click.Context, param: click.Parameter, value: str) -> tuple[str, str]:
    """``KEY=VALUE`` as a pair of stripped strings."""
    key, sep, val = value.partition("=")
    if not sep or not key.strip() or not val.strip():
        raise click.BadParameter(f"expected KEY=VALUE, got {value!r}")
    return key.strip(), val.strip()


def nonempty_path(ctx: click.Context, param: click.Parameter, value: str | None) -> str | None:
    """An output path given as an empty string names nothing (a shell variable unset, say)."""
    if value == "":
        raise click.BadParameter("an empty path names no file")
    return value


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


def input_format(*flags: str) -> Callable[[F], F]:
    """The input format, under ``flags`` (``--format`` is the output format of summarize and
    types, the input format of classify)."""
    return click.option(
        *flags,
        "input_format",
        type=click.Choice(["auto", *INPUT_FORMATS]),
        default="auto",
        show_default=True,
        help="Input format; 'auto' sniffs each input.",
    )


triple_edges = click.option(
    "--triple-edges",
    default="color=red",
    show_default=True,
    metavar="KEY=VALUE",
    callback=key_value,
    help="Surface Evolver: the edge attribute that marks triple lines.",
)


def chunk_size(help: str = "Grains per batch (and per Parquet row group).") -> Callable[[F], F]:
    return click.option(
        "--chunk-size",
        type=click.IntRange(min=1, max=MAX_CHUNK_SIZE),
        default=DEFAULT_CHUNK_SIZE,
        show_default=True,
        help=help,
    )


jobs = click.option(
    "-j",
    "--jobs",
    type=click.IntRange(min=1),
    help="Threads for the compiled kernels (default: the CPUs this process may use).",
)


def quiet(
    help: str = "No progress on stderr, and classify's counts only if a grain is not ok.",
) -> Callable[[F], F]:
    return click.option("-q", "--quiet", is_flag=True, help=help, callback=startup.note_quiet)


def types(default: bool) -> Callable[[F], F]:
    return click.option(
        "--types/--no-types",
        default=default,
        show_default=True,
        help="Compute the Weinberg vectors (weinberg, symmetry, chirality) of raw inputs; they "
        "cost several times the rest of the classification.",
    )


def reading_grains(*format_flags: str, types_default: bool | None = True) -> Callable[[F], F]:
    """The options of every command that reads grains: the input format under
    ``format_flags``, --triple-edges, --chunk-size, --jobs, --quiet and, unless
    ``types_default`` is None (the command always computes them), --types/--no-types."""
    options = [input_format(*format_flags), triple_edges, chunk_size(), jobs, quiet()]
    if types_default is not None:
        options.append(types(types_default))

    def decorate(command: F) -> F:
        for option in reversed(options):
            command = option(command)
        return command

    return decorate


stdout_or_file = click.option(
    "-o",
    "--output",
    default="-",
    metavar="FILE",
    callback=nonempty_path,
    help="Write here instead of stdout.",
)

table_format = click.option(
    "--format",
    "output_format",
    type=click.Choice(OUTPUT_FORMATS),
    help="Output format (default: from the -o extension, else text).",
)

belt_length = click.option(
    "--belt-length",
    type=click.IntRange(3, 10),
    default=4,
    show_default=True,
    metavar="L",
    help="The split type of L-belts (k:L:m) instead of 4-belts; Parquet inputs need the "
    "belts of classify --belts (--belt-lengths L for L > 6).",
)

include_boundary = click.option(
    "--include-boundary", is_flag=True, help="Count grains cut by a sample boundary too."
)
