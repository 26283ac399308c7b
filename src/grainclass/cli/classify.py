"""``grainclass classify``: every grain of the inputs, a row of a per-grain Parquet table."""

from __future__ import annotations

import os
import stat

import click

from grainclass.cli import errors, exit_codes, options, startup
from grainclass.options import ReadOptions
from grainclass.vocabulary import STATUSES, plural


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


@click.command("classify", cls=errors.Command, epilog=exit_codes.GRAINS)
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
@click.option("--strict", is_flag=True, help="Exit 1 if any grain is not a simple polytope.")
@click.option(
    "--belts",
    "with_belts",
    is_flag=True,
    help="Count the belts of every length 3..6 of each ok grain (columns belts, splits, "
    "belt_penalties); they cost more than the rest of the classification.",
)
@options.reading(
    types_default=True,
    boundary=False,
    belts=options.belt_length("Belts of lengths 3..L (4 to 10; implies --belts).", None, True),
    deprecated_format=True,
    quiet_help="No progress on stderr, and the counts only if a grain is not ok.",
)
def classify_cmd(
    inputs: tuple[str, ...],
    output: str | None,
    strict: bool,
    with_belts: bool,
    reading: ReadOptions,
    quiet: bool,
) -> None:
    """Classify every grain of INPUT... into a per-grain Parquet table.

    INPUT is adjacency text (one grain per line), plantri's planar_code, Surface Evolver
    datafiles (a folder stands for its *.fe files), Voro++ face loops or a Neper .tess file,
    sniffed from the content; face-vertex loops must be named (--input-format loops). '-'
    reads standard input, e.g. `plantri 12 | grainclass classify -` (writes out.parquet).
    """
    named = output is not None
    output = output if named else default_output(inputs)
    startup.begin(inputs, reading, [output])
    import dataclasses

    from grainclass.cli.output import refuse_parquet_on_terminal
    from grainclass.datasets import write_grains

    refuse_parquet_on_terminal(output)
    if with_belts and reading.belt_length is None:
        reading = dataclasses.replace(reading, belt_length=6)
    written = write_grains(list(inputs), output, reading, startup.watcher(quiet))
    if written.dropped:
        click.echo(
            f"grainclass: warning: {output}: attributes that no grain of the first chunk had "
            f"are not written: {', '.join(sorted(written.dropped))}",
            err=True,
        )
    counts = written.statuses
    bad = sum(count for status, count in counts.items() if status != "ok")
    if not quiet or bad:
        detail = ", ".join(f"{counts[s]} {s}" for s in STATUSES if s in counts)
        where = "" if named else f", written to {output}"
        grains = plural(written.rows, "grain")
        click.echo(f"grainclass: {grains} classified ({detail or 'none'}){where}", err=True)
    if strict and bad:
        verb = "is" if bad == 1 else "are"
        raise click.ClickException(f"--strict: {plural(bad, 'grain')} {verb} not ok")
