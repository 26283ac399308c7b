"""``grainclass classify``: every grain of the inputs, a row of a per-grain Parquet table."""

from __future__ import annotations

import os
import stat

import click

from grainclass.cli import exit_codes, options, startup
from grainclass.vocabulary import STATUSES


def default_output(inputs: tuple[str, ...]) -> str:
    """Where ``classify`` writes without ``-o``: the one input's name with ``.parquet``, in the
    current directory (``dataset.txt`` -> ``dataset.parquet``, ``dump/21000/`` ->
    ``21000.parquet``); ``out.parquet`` for standard input, a FIFO or several inputs.

    Examples
    --------
    >>> default_output(("runs/dataset.txt",)), default_output(("-",))
    ('dataset.parquet', 'out.parquet')
    """
    if len(inputs) == 1 and inputs[0] != "-" and _is_file_or_folder(inputs[0]):
        name = os.path.basename(os.path.normpath(inputs[0]))
        stem = name if os.path.isdir(inputs[0]) else os.path.splitext(name)[0]
        if stem and stem not in (".", ".."):
            return stem + ".parquet"
    return "out.parquet"


def _is_file_or_folder(path: str) -> bool:
    try:
        mode = os.stat(path).st_mode
    except (OSError, ValueError):
        return True  # the reader says what is wrong with it
    return stat.S_ISREG(mode) or stat.S_ISDIR(mode)


@click.command("classify", epilog=exit_codes.GRAINS)
@click.argument("inputs", nargs=-1, required=True, metavar="INPUT...")
@click.option(
    "-o",
    "--output",
    metavar="FILE",
    callback=options.nonempty_path,
    help="Parquet file to write, one row per grain; '-' writes to standard output. Default: "
    "the input's name with .parquet in the current directory (out.parquet for standard input "
    "or several inputs).",
)
@options.reading_grains("--format", "--input-format")
@click.option("--strict", is_flag=True, help="Exit 1 if any grain is not a simple polytope.")
@click.option(
    "--belts",
    "with_belts",
    is_flag=True,
    help="Count the belts of every length 3..6 of each ok grain (columns belts, splits, "
    "belt_penalties); they cost more than the rest of the classification.",
)
@click.option(
    "--belt-lengths",
    type=click.IntRange(3, 10),
    metavar="L",
    help="Belts of lengths 3..L (3 to 10; implies --belts).",
)
def classify_cmd(
    inputs: tuple[str, ...],
    output: str | None,
    input_format: str,
    triple_edges: tuple[str, str],
    chunk_size: int,
    jobs: int | None,
    quiet: bool,
    types: bool,
    strict: bool,
    with_belts: bool,
    belt_lengths: int | None,
) -> None:
    """Classify every grain of INPUT... into a per-grain Parquet table.

    INPUT is adjacency text (one grain per line), plantri's planar_code, Surface Evolver
    datafiles (a folder stands for its *.fe files), Voro++ face loops or a Neper .tess file,
    sniffed from the content; face-vertex loops must be named (--format loops). '-' reads
    standard input, e.g. `plantri 12 | grainclass classify -` (writes out.parquet).
    """
    startup.read_ahead(inputs, input_format)
    from grainclass.cli.output import quiet_broken_pipe, refuse_parquet_on_terminal
    from grainclass.cli.progress import Progress
    from grainclass.errors import GrainclassError
    from grainclass.parallel import set_jobs
    from grainclass.parquet import GrainTableWriter
    from grainclass.pipeline import classified_tables

    named = output is not None
    output = output if named else default_output(inputs)
    refuse_parquet_on_terminal(output)
    if jobs is not None:
        set_jobs(jobs)
    fmt = None if input_format == "auto" else input_format
    counts: dict[str, int] = {}
    try:
        with GrainTableWriter(output) as writer:
            longest = belt_lengths or (6 if with_belts else 0)
            tables = classified_tables(
                list(inputs), fmt, chunk_size, triple_edges, types, belts=longest
            )
            for table in Progress.on_terminal(quiet).wrap(startup.after_start_up(tables)):
                for item in table.column("status").value_counts().to_pylist():
                    counts[item["values"]] = counts.get(item["values"], 0) + item["counts"]
                writer.write(table)
    except GrainclassError as exc:
        raise click.ClickException(str(exc)) from None
    except BrokenPipeError:
        quiet_broken_pipe()
    if writer.dropped:
        click.echo(
            f"grainclass: warning: {output}: attributes that no grain of the first chunk had "
            f"are not written: {', '.join(sorted(writer.dropped))}",
            err=True,
        )
    bad = sum(count for status, count in counts.items() if status != "ok")
    if not quiet or bad:
        detail = ", ".join(f"{counts[s]} {s}" for s in STATUSES if s in counts)
        written = "" if named else f", written to {output}"
        click.echo(
            f"grainclass: {writer.rows} grains classified ({detail or 'none'}){written}", err=True
        )
    if strict and bad:
        raise click.ClickException(f"{bad} grain(s) are not simple polytopes (--strict)")
