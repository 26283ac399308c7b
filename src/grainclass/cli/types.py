"""``grainclass types``: grains counted by combinatorial type, most frequent first."""

from __future__ import annotations

from contextlib import nullcontext

import click

from grainclass.cli import exit_codes, options, startup
from grainclass.vocabulary import CLASSES


@click.command("types", epilog=exit_codes.SUMMARY)
@click.argument("grains", nargs=-1, required=True, metavar="GRAINS...")
@click.option("--top", type=click.IntRange(min=1), help="Only the K most frequent types.")
@click.option("--n", "n_faces", type=click.IntRange(min=4), help="Only grains with N faces.")
@click.option(
    "--class", "class_name", type=click.Choice(CLASSES), help="Only grains of this class."
)
@options.table_format
@options.stdout_or_file
@click.option(
    "--vorotop",
    metavar="FILE",
    callback=options.nonempty_path,
    help="Also write what VoroTop's -d writes (its .distribution file) for these grains.",
)
@options.include_boundary
@options.belt_length
@options.reading_grains("--input-format", types_default=None)
def types_cmd(
    grains: tuple[str, ...],
    top: int | None,
    n_faces: int | None,
    class_name: str | None,
    output_format: str | None,
    output: str,
    vorotop: str | None,
    include_boundary: bool,
    belt_length: int,
    input_format: str,
    triple_edges: tuple[str, str],
    chunk_size: int,
    jobs: int | None,
    quiet: bool,
) -> None:
    """Count grains by combinatorial type (Weinberg vector), most frequent first.

    Each type comes with its faces, p-vector, class, split type (of 4-belts, or of l-belts with
    --belt-length l) and penalty (flag grains),
    symmetry, count and fraction. GRAINS are per-grain Parquet tables or any input classify reads.
    Grains cut by a sample boundary are left out, as summarize leaves them.
    """
    startup.read_ahead(grains, input_format)
    from grainclass.cli.output import opened, refuse_parquet_on_terminal, table_format, write_all
    from grainclass.cli.progress import Progress
    from grainclass.errors import GrainclassError
    from grainclass.frequencies import COLUMNS, type_frequencies, vorotop_distribution
    from grainclass.parallel import set_jobs
    from grainclass.pipeline import grain_tables
    from grainclass.render import render_frame
    from grainclass.schema import SPLITS

    fmt = table_format(output_format, output)
    if fmt == "parquet":
        refuse_parquet_on_terminal(output)
    if jobs is not None:
        set_jobs(jobs)
    in_fmt = None if input_format == "auto" else input_format
    with opened(output) as sink, opened(vorotop) if vorotop else nullcontext() as distribution:
        try:
            by_length = belt_length != 4
            columns = [*COLUMNS, SPLITS] if by_length else COLUMNS
            stream = grain_tables(
                list(grains), columns, in_fmt, chunk_size, triple_edges,
                belts=max(belt_length, 6) if by_length else 0,
            )  # fmt: skip
            table = type_frequencies(
                Progress.on_terminal(quiet).wrap(startup.after_start_up(stream)),
                n_faces,
                class_name,
                include_boundary,
                belt_length,
            )
        except GrainclassError as exc:
            raise click.ClickException(str(exc)) from None
        if distribution is not None:
            write_all(distribution, vorotop_distribution(table, grains))
        shown = table.head(top) if top else table
        shown = shown.drop(columns=["left", "achiral", "right"])
        title = f"{len(table)} types, most frequent first"
        if table.attrs["boundary_excluded"]:
            left_out = table.attrs["boundary_excluded"]
            title += f"; {left_out} grains cut by the sample boundary left out"
            if not quiet:
                click.echo(
                    f"grainclass: {left_out} grains cut by the sample boundary left out "
                    "(--include-boundary counts them)",
                    err=True,
                )
        write_all(sink, render_frame(shown, fmt, title))
