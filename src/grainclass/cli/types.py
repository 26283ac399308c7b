"""``grainclass types``: grains counted by combinatorial type, most frequent first."""

from __future__ import annotations

from contextlib import nullcontext

import click

from grainclass.cli import errors, exit_codes, options, startup
from grainclass.options import OutputOptions, ReadOptions
from grainclass.vocabulary import CLASSES


@click.command("types", cls=errors.Command, epilog=exit_codes.SUMMARY)
@click.argument("grains", nargs=-1, required=True, metavar="GRAINS...")
@click.option(
    "--top", type=click.IntRange(1, 2**63 - 1), metavar="K", help="Only the K most frequent types."
)
@options.faces("Only grains with N faces.", multiple=False, name="n_faces")
@click.option(
    "--class", "class_name", type=click.Choice(CLASSES), help="Only grains of this class."
)
@click.option(
    "--vorotop",
    metavar="FILE",
    callback=options.nonempty_path,
    help="Also write what VoroTop's -d writes (its .distribution file) for these grains.",
)
@options.table_output()
@options.reading(
    types_default=None,
    belts=options.belt_length(
        "The split column of L-belts (k:L:m) instead of 4-belts; Parquet inputs need the belts "
        "of classify --belt-length L."
    ),
)
def types_cmd(
    grains: tuple[str, ...],
    top: int | None,
    n_faces: int | None,
    class_name: str | None,
    vorotop: str | None,
    output: OutputOptions,
    reading: ReadOptions,
    quiet: bool,
) -> None:
    """Count grains by combinatorial type (Weinberg vector), most frequent first.

    Each type comes with its faces, p-vector, class, split type (of 4-belts, or of L-belts with
    --belt-length L) and penalty (flag grains), symmetry, count and fraction. GRAINS are
    per-grain Parquet tables or any input classify reads. Grains cut by a sample boundary are
    left out, as summarize leaves them.
    """
    startup.begin(grains, reading, [output.path, vorotop])
    from grainclass.atomic import atomic_output
    from grainclass.cli.output import refuse_parquet_on_terminal, write_all
    from grainclass.datasets import type_counts
    from grainclass.frequencies import vorotop_distribution
    from grainclass.render import render_frame

    fmt = output.table_format
    if fmt == "parquet":
        refuse_parquet_on_terminal(output.path)
    with (
        atomic_output(output.path) as sink,
        atomic_output(vorotop) if vorotop else nullcontext() as distribution,
    ):
        watch = startup.watcher(quiet)
        table = type_counts(list(grains), reading, watch, n_faces, class_name)
        if distribution is not None:
            write_all(distribution, vorotop_distribution(table, grains))
        shown = table.head(top) if top else table
        shown = shown.drop(columns=["left", "achiral", "right"])
        title = f"{len(table)} types, most frequent first"
        left_out = table.attrs["boundary_excluded"]
        if left_out:
            title += f"; {left_out} grains cut by the sample boundary left out"
            if not quiet:
                click.echo(
                    f"grainclass: {left_out} grains cut by the sample boundary left out "
                    "(--include-boundary counts them)",
                    err=True,
                )
        write_all(sink, render_frame(shown, fmt, title))
