"""``grainclass summarize``: the paper's tables (classes, round, split, geometry) of grains."""

from __future__ import annotations

import click

from grainclass.cli import errors, exit_codes, options, startup
from grainclass.options import OutputOptions, ReadOptions
from grainclass.vocabulary import ALL_TABLES, TABLES


@click.command("summarize", cls=errors.Command, epilog=exit_codes.SUMMARY)
@click.argument("grains", nargs=-1, required=True, metavar="GRAINS...")
@click.option(
    "--table",
    "table_name",
    type=click.Choice(ALL_TABLES),
    help="Print only this table (default: classes, round and split).",
)
@options.faces("Add a round-table row for grains with N faces (repeatable).")
@options.table_output()
@options.reading(
    types_default=False,
    belts=options.belt_length(
        "The split table by the split type k:L:m of L-belts instead of 4-belts; Parquet inputs "
        "need the belts of classify --belt-length L."
    ),
)
def summarize_cmd(
    grains: tuple[str, ...],
    table_name: str | None,
    n_values: tuple[int, ...],
    output: OutputOptions,
    reading: ReadOptions,
    quiet: bool,
) -> None:
    """Summarize grains into the paper's tables: classes, round, split.

    GRAINS are per-grain Parquet tables from `grainclass classify` (or folders of them), or any
    input classify reads, classified on the fly without keeping per-grain rows:
    `plantri 14 | grainclass summarize -`. Above the tables, one line gives the grains by
    status, the mean number of faces, the percentage of faces that are triangles and the number
    of distinct types (from Parquet files that have them, or from raw inputs with --types).
    """
    tables = (table_name,) if table_name else TABLES
    fmt = output.table_format
    if fmt == "parquet" and len(tables) != 1:
        raise click.UsageError("parquet output holds one table: choose one with --table")
    if n_values and "round" not in tables:
        raise click.UsageError(
            f"--n adds rows to the round table, which --table {table_name} leaves out"
        )
    if reading.belt_length is not None and tables != ("split",):
        raise click.UsageError("--belt-length changes the split table: use it with --table split")
    startup.begin(grains, reading, [output.path])
    from grainclass.atomic import atomic_output
    from grainclass.cli.output import refuse_parquet_on_terminal, write_all
    from grainclass.datasets import summary_tables
    from grainclass.render import render

    if fmt == "parquet":
        refuse_parquet_on_terminal(output.path)
    with atomic_output(output.path) as sink:
        summary = summary_tables(list(grains), reading, startup.watcher(quiet), n_values)
        write_all(sink, render(summary, tables, fmt))
