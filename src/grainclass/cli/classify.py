"""``grainclass classify``: every grain of the inputs, a row of a per-grain Parquet table."""

from __future__ import annotations

import dataclasses
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


@click.command("classify", cls=errors.Command, epilog=exit_codes.CLASSIFY)
@click.argument("inputs", nargs=-1, required=True, metavar="INPUT...")
@click.option(
    "-o",
    "--output",
    metavar="FILE|DIR/",
    callback=options.nonempty_path,
    help="Parquet file to write, one row per grain; '-' writes to standard output. Default: "
    "the input's name with .parquet in the current directory (out.parquet for standard input "
    "or several inputs). A folder (DIR/, with its /): a data set in parts on Dask, one "
    "part per input; the same command again redoes only the parts not done.",
)
@options.cluster("the parts")
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
    scheduler: str | None,
    workers: int | None,
    reading: ReadOptions,
    quiet: bool,
) -> None:
    """Classify every grain of INPUT... into a per-grain Parquet table.

    INPUT is adjacency text (one grain per line), plantri's planar_code, Surface Evolver
    datafiles (a folder stands for its *.fe files), Voro++ face loops or a Neper .tess file,
    sniffed from the content; face-vertex loops must be named (--input-format loops). '-'
    reads standard input, e.g. `plantri 12 | grainclass classify -` (writes out.parquet).

    With -o DIR/ each INPUT (a file, or a folder of *.fe files: one time step) is classified by
    a Dask task (a local cluster, or --scheduler) into DIR/part-00000.parquet, ..., in input
    order. Needs the census extra: pip install 'grainclass[census]'.
    """
    if with_belts and reading.belt_length is None:
        reading = dataclasses.replace(reading, belt_length=6)
    if output is not None and options.is_folder(output):
        _in_parts(inputs, output, strict, scheduler, workers, reading, quiet)
        return
    if scheduler is not None or workers is not None:
        raise click.UsageError("--scheduler and --workers write a folder: give -o DIR/")
    named = output is not None
    output = output if named else default_output(inputs)
    startup.begin(inputs, reading, [output])
    from grainclass.cli.output import refuse_parquet_on_terminal
    from grainclass.datasets import write_grains

    refuse_parquet_on_terminal(output)
    written = write_grains(list(inputs), output, reading, startup.watcher(quiet))
    if written.dropped:
        click.echo(
            f"grainclass: warning: {output}: attributes that no grain of the first chunk had "
            f"are not written: {', '.join(sorted(written.dropped))}",
            err=True,
        )
    _report(
        written.rows, written.statuses, "" if named else f", written to {output}", strict, quiet
    )


def _report(rows: int, counts: dict[str, int], where: str, strict: bool, quiet: bool) -> None:
    """The grains by status on standard error (with -q, only if a grain is not ok); with
    --strict, a grain that is not ok exits 1."""
    bad = sum(count for status, count in counts.items() if status != "ok")
    if not quiet or bad:
        detail = ", ".join(f"{counts[s]} {s}" for s in STATUSES if s in counts)
        grains = plural(rows, "grain")
        click.echo(f"grainclass: {grains} classified ({detail or 'none'}){where}", err=True)
    if strict and bad:
        verb = "is" if bad == 1 else "are"
        raise click.ClickException(f"--strict: {plural(bad, 'grain')} {verb} not ok")


def _in_parts(
    inputs: tuple[str, ...],
    output: str,
    strict: bool,
    scheduler: str | None,
    workers: int | None,
    reading: ReadOptions,
    quiet: bool,
) -> None:
    """Each input a part of the data set in the folder ``output``, on Dask."""
    if reading.jobs is not None:
        raise click.UsageError("-j/--jobs goes with one output file: in parts, --workers")
    if "-" in inputs:
        raise click.UsageError("standard input cannot be classified in parts: give files")
    from grainclass.classify_parts import check_inputs, classify_in_parts
    from grainclass.cli.progress import PartsPrinter, parts_line
    from grainclass.cluster import dask_client, require_dask
    from grainclass.parts import check_output_folder, remove_part_temporaries

    check_output_folder(output)
    check_inputs(inputs, output)  # before a cluster starts
    require_dask()
    startup.resume_collection()
    printer = None if quiet else PartsPrinter(line=parts_line("classify", "grains"))
    try:
        with dask_client(scheduler, workers) as client:
            result = classify_in_parts(inputs, output, client, reading, printer)
    finally:  # the temporary files of parts that stopped with the workers
        remove_part_temporaries(output)
    if result.dropped:
        click.echo(
            f"grainclass: warning: {output}: attributes that no grain of a part's first chunk "
            f"had are not written there: {', '.join(sorted(result.dropped))}",
            err=True,
        )
    for failure in result.failures:
        click.echo(f"grainclass: failed: {failure}", err=True)
    parts = f" in {plural(result.parts, 'part')} ({result.computed} computed now, "
    where = parts + f"{result.skipped} from earlier runs), written to {output}"
    _report(result.rows, result.statuses, where, strict and result.ok, quiet)
    if result.failures:
        raise click.ClickException(
            f"{plural(len(result.failures), 'part')} failed; finished parts are kept in "
            f"{output}: run the same command again to classify the rest"
        )
