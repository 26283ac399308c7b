"""``grainclass summarize``: the paper's tables (classes, round, split, geometry) of grains."""

from __future__ import annotations

import click

from grainclass.cli import exit_codes, options, startup
from grainclass.vocabulary import ALL_TABLES, TABLES


@click.command("summarize", epilog=exit_codes.SUMMARY)
@click.argument("grains", nargs=-1, required=True, metavar="GRAINS...")
@click.option(
    "--table",
    "table_name",
    type=click.Choice(ALL_TABLES),
    help="Print only this table (default: classes, round and split).",
)
@options.table_format
@click.option(
    "--n",
    "n_values",
    type=click.IntRange(min=4),
    multiple=True,
    help="Add a round-table row for grains with N faces (repeatable).",
)
@options.stdout_or_file
@options.include_boundary
@options.belt_length
@options.reading_grains("--input-format", types_default=False)
def summarize_cmd(
    grains: tuple[str, ...],
    table_name: str | None,
    output_format: str | None,
    n_values: tuple[int, ...],
    output: str,
    include_boundary: bool,
    belt_length: int,
    input_format: str,
    triple_edges: tuple[str, str],
    chunk_size: int,
    jobs: int | None,
    quiet: bool,
    types: bool,
) -> None:
    """Summarize grains into the paper's tables: classes, round, split.

    GRAINS are per-grain Parquet tables from `grainclass classify`, or any input classify reads,
    classified on the fly without keeping per-grain rows: `plantri 14 | grainclass summarize -`.
    Above the tables, one line gives the grains by status, the mean number of faces, the
    percentage of faces that are triangles and the number of distinct types (from Parquet
    files that have them, or from raw inputs with --types).
    """
    startup.read_ahead(grains, input_format)
    from grainclass.cli.output import opened, refuse_parquet_on_terminal, table_format, write_all
    from grainclass.cli.progress import Progress
    from grainclass.errors import GrainclassError
    from grainclass.parallel import set_jobs
    from grainclass.pipeline import tallies
    from grainclass.render import render
    from grainclass.summary import summarize

    fmt = table_format(output_format, output)
    tables = (table_name,) if table_name else TABLES
    if fmt == "parquet" and len(tables) != 1:
        raise click.UsageError("parquet output holds one table: choose one with --table")
    if n_values and "round" not in tables:
        raise click.UsageError(
            f"--n adds rows to the round table, which --table {table_name} leaves out"
        )
    if belt_length != 4 and tables != ("split",):
        raise click.UsageError("--belt-length changes the split table: use it with --table split")
    if fmt == "parquet":
        refuse_parquet_on_terminal(output)
    if jobs is not None:
        set_jobs(jobs)
    in_fmt = None if input_format == "auto" else input_format
    with opened(output) as sink:
        try:
            stream = tallies(
                list(grains), in_fmt, chunk_size, triple_edges, types, include_boundary,
                belt_length,
            )  # fmt: skip
            progress = Progress.on_terminal(quiet)
            summary = summarize(
                progress.wrap(startup.after_start_up(stream)),
                n_values,
                include_boundary,
                belt_length,
            )
        except GrainclassError as exc:
            raise click.ClickException(str(exc)) from None
        write_all(sink, render(summary, tables, fmt))
