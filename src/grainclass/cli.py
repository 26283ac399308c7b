"""The ``grainclass`` command line: parses arguments, calls the library, maps errors to exit codes.

Heavy imports (numba, pyarrow, pandas) happen inside the commands, so ``--help`` stays fast.
"""

from __future__ import annotations

import _thread
import gc
import os
import signal
import sys
import warnings
from collections.abc import Iterable, Iterator, Sequence
from contextlib import contextmanager, nullcontext, suppress
from typing import BinaryIO, TypeVar

import click

from grainclass import DEFAULT_CHUNK_SIZE, __version__
from grainclass.vocabulary import (
    ALL_TABLES,
    CLASSES,
    INPUT_FORMATS,
    OUTPUT_FORMATS,
    STATUSES,
    TABLES,
)

T = TypeVar("T")

# Readers size their arrays for a whole chunk at once: a typo's 10**11 asked for 745 GB.
MAX_CHUNK_SIZE = 10_000_000

INTERRUPTED = "  130  interrupted: Ctrl-C (129, 143: SIGHUP, SIGTERM); "

EXIT_CODES = f"""\b
Exit codes:
  0    success (bad grains are data: they get a row with their status)
  1    an input or output could not be read or written; with --strict, bad grains
  2    usage error
{INTERRUPTED}no partial output
       file is left behind
"""

SUMMARY_EXIT_CODES = f"""\b
Exit codes:
  0    success (bad grains are data, not errors)
  1    an input or output could not be read or written
  2    usage error
{INTERRUPTED}no partial output
       file is left behind
"""

VORONOI_EXIT_CODES = f"""\b
Exit codes:
  0    success
  1    the tessellation failed (seeds Voro++ cannot separate) or its checks (then the
       output is written, for a look), or the output could not be written
  2    usage error
{INTERRUPTED}no partial output
       file is left behind
"""

CENSUS_EXIT_CODES = f"""\b
Exit codes:
  0    every part done, every cross-check passed
  1    a part failed (the others are kept), the census disagrees with plantri,
       or an output could not be written
  2    usage error
{INTERRUPTED}finished parts are
       kept: the same command resumes
"""


def _key_value(ctx: click.Context, param: click.Parameter, value: str) -> tuple[str, str]:
    key, sep, val = value.partition("=")
    if not sep or not key.strip() or not val.strip():
        raise click.BadParameter(f"expected KEY=VALUE, got {value!r}")
    return key.strip(), val.strip()


@click.group(epilog=EXIT_CODES, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="grainclass")
def cli() -> None:
    """Classify the grains of 3D cellular microstructures by combinatorial type.

    Each grain is a simple 3-polytope given by its face adjacency; grainclass reduces it to its
    fundamental polytope and reports its class (stacked, flag, sc and their truncations),
    roundness, 4-belts, split type and penalty, as in Lutz, Mason, Lazar and MacPherson,
    "Roundness of grains in cellular microstructures".
    """


def _input_options(*format_flags: str, types: bool | None = True):
    """Options shared by every command that reads grains; the input format goes by
    ``format_flags`` (``--format`` is the output format of summarize and types), ``types`` is
    the default of ``--types/--no-types`` (None: no such option, the command always needs
    them)."""
    options = [
        click.option(
            *format_flags,
            "input_format",
            type=click.Choice(["auto", *INPUT_FORMATS]),
            default="auto",
            show_default=True,
            help="Input format; 'auto' sniffs each input.",
        ),
        click.option(
            "--triple-edges",
            default="color=red",
            show_default=True,
            metavar="KEY=VALUE",
            callback=_key_value,
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
            type=click.IntRange(min=1),
            help="Threads for the compiled kernels (default: all cores).",
        ),
        click.option(
            "-q",
            "--quiet",
            is_flag=True,
            help="No progress on stderr, and classify's counts only if a grain is not ok.",
        ),
    ]
    if types is not None:
        options.append(
            click.option(
                "--types/--no-types",
                default=types,
                show_default=True,
                help="Compute the Weinberg vectors (weinberg, symmetry, chirality) of raw "
                "inputs; they cost several times the rest of the classification.",
            )
        )

    def decorate(command):
        for option in reversed(options):
            command = option(command)
        return command

    return decorate


def _set_jobs(jobs: int | None) -> None:
    if jobs is not None:
        from grainclass.parallel import set_jobs

        set_jobs(jobs)


def _path(ctx: click.Context, param: click.Parameter, value: str | None) -> str | None:
    """An output path given as an empty string names nothing (a shell variable unset, say)."""
    if value == "":
        raise click.BadParameter("an empty path names no file")
    return value


# The options summarize and types share (each use makes its own click.Option).
_STDOUT_OR_FILE = click.option(
    "-o",
    "--output",
    default="-",
    metavar="FILE",
    callback=_path,
    help="Write here instead of stdout.",
)
_INCLUDE_BOUNDARY = click.option(
    "--include-boundary", is_flag=True, help="Count grains cut by a sample boundary too."
)


def _after_start_up(items: Iterable[T]) -> Iterator[T]:
    """``items``, with the cyclic garbage collector (off since :func:`main`) back on once the
    first has come through, or once there are none."""
    try:
        for item in items:
            _resume_collection()
            yield item
    finally:
        _resume_collection()


def _resume_collection() -> None:
    """Collect cyclic garbage from now on, except among the objects made so far (the imported
    libraries, the kernels loaded from numba's cache), which live as long as the process."""
    if not gc.isenabled():
        gc.freeze()
        gc.enable()


def _read_ahead(inputs: Sequence[str], input_format: str) -> None:
    """Standard input, if it is an input and a pipe, and the first input, if it is a FIFO (a
    process substitution, ``<(plantri 16)``), are read from now on, while the libraries load
    (:class:`grainclass.pipes.ReadAhead`). Later FIFOs are opened in their turn; Surface
    Evolver files are read whole by their own reader."""
    from grainclass.pipes import read_ahead, read_ahead_path

    if "-" in inputs:
        read_ahead(sys.stdin.buffer)
    first = inputs[0]
    if first != "-" and input_format != "evolver" and not first.lower().endswith(".fe"):
        read_ahead_path(first)


def _progress(quiet: bool):
    from grainclass.pipeline import Progress

    return Progress(enabled=not quiet and sys.stderr.isatty())


@cli.command("classify", epilog=EXIT_CODES)
@click.argument("inputs", nargs=-1, required=True, metavar="INPUT...")
@click.option(
    "-o",
    "--output",
    required=True,
    metavar="FILE",
    callback=_path,
    help="Parquet file to write, one row per grain; '-' writes to standard output.",
)
@_input_options("--format", "--input-format")
@click.option("--strict", is_flag=True, help="Exit 1 if any grain is not a simple polytope.")
def classify_cmd(
    inputs: tuple[str, ...],
    output: str,
    input_format: str,
    triple_edges: tuple[str, str],
    chunk_size: int,
    jobs: int | None,
    quiet: bool,
    types: bool,
    strict: bool,
) -> None:
    """Classify every grain of INPUT... into a per-grain Parquet table.

    INPUT is adjacency text (one grain per line), plantri's planar_code, Surface Evolver
    datafiles (a folder stands for its *.fe files), Voro++ face loops or a Neper .tess file,
    sniffed from the content; face-vertex loops must be named (--format loops). '-' reads
    standard input, e.g. `plantri 12 | grainclass classify - -o all12.parquet`.
    """
    _read_ahead(inputs, input_format)
    from grainclass.errors import GrainclassError
    from grainclass.parquet import GrainTableWriter
    from grainclass.pipeline import classified_tables

    if output == "-" and sys.stdout.isatty():
        raise click.UsageError("refusing to write Parquet to a terminal; use -o FILE")
    _set_jobs(jobs)
    fmt = None if input_format == "auto" else input_format
    counts: dict[str, int] = {}
    progress = _progress(quiet)
    try:
        with GrainTableWriter(output) as writer:
            tables = classified_tables(list(inputs), fmt, chunk_size, triple_edges, types)
            for table in progress.wrap(_after_start_up(tables)):
                for item in table.column("status").value_counts().to_pylist():
                    counts[item["values"]] = counts.get(item["values"], 0) + item["counts"]
                writer.write(table)
    except GrainclassError as exc:
        raise click.ClickException(str(exc)) from None
    except BrokenPipeError:
        _quiet_broken_pipe()
    if writer.dropped:
        click.echo(
            f"grainclass: warning: {output}: attributes that no grain of the first chunk had "
            f"are not written: {', '.join(sorted(writer.dropped))}",
            err=True,
        )
    bad = sum(count for status, count in counts.items() if status != "ok")
    if not quiet or bad:
        detail = ", ".join(f"{counts[s]} {s}" for s in STATUSES if s in counts)
        click.echo(f"grainclass: {writer.rows} grains classified ({detail or 'none'})", err=True)
    if strict and bad:
        raise click.ClickException(f"{bad} grain(s) are not simple polytopes (--strict)")


@cli.command("summarize", epilog=SUMMARY_EXIT_CODES)
@click.argument("grains", nargs=-1, required=True, metavar="GRAINS...")
@click.option(
    "--table",
    "table_name",
    type=click.Choice(ALL_TABLES),
    help="Print only this table (default: classes, round and split).",
)
@click.option(
    "--format",
    "output_format",
    type=click.Choice(OUTPUT_FORMATS),
    help="Output format (default: from the -o extension, else text).",
)
@click.option(
    "--n",
    "n_values",
    type=click.IntRange(min=4),
    multiple=True,
    help="Add a round-table row for grains with N faces (repeatable).",
)
@_STDOUT_OR_FILE
@_INCLUDE_BOUNDARY
@_input_options("--input-format", types=False)
def summarize_cmd(
    grains: tuple[str, ...],
    table_name: str | None,
    output_format: str | None,
    n_values: tuple[int, ...],
    output: str,
    include_boundary: bool,
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
    _read_ahead(grains, input_format)
    from grainclass.errors import GrainclassError
    from grainclass.pipeline import tallies
    from grainclass.render import EXTENSIONS, render
    from grainclass.summary import summarize

    fmt = output_format or EXTENSIONS.get(os.path.splitext(output)[1].lower(), "text")
    tables = (table_name,) if table_name else TABLES
    if fmt == "parquet" and len(tables) != 1:
        raise click.UsageError("parquet output holds one table: choose one with --table")
    if n_values and "round" not in tables:
        raise click.UsageError(
            f"--n adds rows to the round table, which --table {table_name} leaves out"
        )
    if fmt == "parquet" and output == "-" and sys.stdout.isatty():
        raise click.UsageError("refusing to write Parquet to a terminal; use -o FILE")
    _set_jobs(jobs)
    in_fmt = None if input_format == "auto" else input_format
    with _output(output) as sink:
        try:
            stream = tallies(
                list(grains), in_fmt, chunk_size, triple_edges, types, include_boundary
            )
            summary = summarize(
                _progress(quiet).wrap(_after_start_up(stream)), n_values, include_boundary
            )
        except GrainclassError as exc:
            raise click.ClickException(str(exc)) from None
        _write_all(sink, render(summary, tables, fmt))


@cli.command("types", epilog=SUMMARY_EXIT_CODES)
@click.argument("grains", nargs=-1, required=True, metavar="GRAINS...")
@click.option("--top", type=click.IntRange(min=1), help="Only the K most frequent types.")
@click.option("--n", "n_faces", type=click.IntRange(min=4), help="Only grains with N faces.")
@click.option(
    "--class", "class_name", type=click.Choice(CLASSES), help="Only grains of this class."
)
@click.option(
    "--format",
    "output_format",
    type=click.Choice(OUTPUT_FORMATS),
    help="Output format (default: from the -o extension, else text).",
)
@_STDOUT_OR_FILE
@click.option(
    "--vorotop",
    metavar="FILE",
    callback=_path,
    help="Also write VoroTop's .distribution file: (code) total left achiral right.",
)
@_INCLUDE_BOUNDARY
@_input_options("--input-format", types=None)
def types_cmd(
    grains: tuple[str, ...],
    top: int | None,
    n_faces: int | None,
    class_name: str | None,
    output_format: str | None,
    output: str,
    vorotop: str | None,
    include_boundary: bool,
    input_format: str,
    triple_edges: tuple[str, str],
    chunk_size: int,
    jobs: int | None,
    quiet: bool,
) -> None:
    """Count grains by combinatorial type (Weinberg vector), most frequent first.

    Each type comes with its faces, p-vector, class, split type and penalty (flag grains),
    symmetry, count and fraction. GRAINS are per-grain Parquet tables or any input classify reads.
    Grains cut by a sample boundary are left out, as summarize leaves them.
    """
    _read_ahead(grains, input_format)
    from grainclass.errors import GrainclassError
    from grainclass.frequencies import COLUMNS, type_frequencies, vorotop_distribution
    from grainclass.pipeline import grain_tables
    from grainclass.render import EXTENSIONS, render_frame

    fmt = output_format or EXTENSIONS.get(os.path.splitext(output)[1].lower(), "text")
    if fmt == "parquet" and output == "-" and sys.stdout.isatty():
        raise click.UsageError("refusing to write Parquet to a terminal; use -o FILE")
    _set_jobs(jobs)
    in_fmt = None if input_format == "auto" else input_format
    with _output(output) as sink, _output(vorotop) if vorotop else nullcontext() as distribution:
        try:
            stream = grain_tables(list(grains), COLUMNS, in_fmt, chunk_size, triple_edges)
            table = type_frequencies(
                _progress(quiet).wrap(_after_start_up(stream)),
                n_faces,
                class_name,
                include_boundary,
            )
        except GrainclassError as exc:
            raise click.ClickException(str(exc)) from None
        if distribution is not None:
            _write_all(distribution, vorotop_distribution(table))
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
        _write_all(sink, render_frame(shown, fmt, title))


@cli.command("voronoi", epilog=VORONOI_EXIT_CODES)
@click.argument("n_seeds", type=click.IntRange(min=1), metavar="N")
@click.option(
    "--seed",
    type=click.IntRange(min=0),
    help="Random seed: the same seed gives the same grains.",
)
@click.option(
    "--box",
    # Volumes are computed in a box of side about 1000 and scaled back by (L / 1000)^3, and
    # summed: far beyond these bounds the factor or the sum leaves the range of a float.
    type=click.FloatRange(min=1e-30, max=1e30),
    default=1.0,
    show_default=True,
    help="Side of the periodic cube.",
)
@click.option(
    "-o",
    "--output",
    required=True,
    metavar="FILE",
    callback=_path,
    help="Adjacency text with volume= and area= per grain; *.parquet: classified grains.",
)
@click.option("-q", "--quiet", is_flag=True, help="No report on stderr.")
def voronoi_cmd(n_seeds: int, seed: int | None, box: float, output: str, quiet: bool) -> None:
    """A periodic Poisson-Voronoi tessellation of N uniform random seeds (Voro++), as grains.

    The paper's V-268402 data set is `grainclass voronoi 268402 -o pv.txt`. Every cell is checked
    (three faces at each corner, every face seen from both sides, the cells filling the box);
    a failed check exits 1.
    """
    from grainclass.errors import GrainclassError
    from grainclass.pipeline import Progress
    from grainclass.voronoi import VoronoiReport, poisson_voronoi

    _resume_collection()
    report = VoronoiReport()
    progress = Progress(enabled=not quiet and sys.stderr.isatty())
    if progress.enabled:
        click.echo(f"tessellating {n_seeds:,} seeds with Voro++ ...", err=True)
    batches = progress.wrap(poisson_voronoi(n_seeds, seed, box, report=report))
    try:
        if output.lower().endswith(".parquet"):
            from grainclass.classification import classify
            from grainclass.parquet import GrainTableWriter

            with GrainTableWriter(output) as writer:
                for batch in batches:
                    writer.write(classify(batch))
        else:
            from grainclass.atomic import atomic_output
            from grainclass.readers.adjacency import adjacency_lines

            with atomic_output(output) as sink:
                for batch in batches:
                    _write_all(sink, "".join(adjacency_lines(batch)))
    except GrainclassError as exc:
        raise click.ClickException(str(exc)) from None
    except BrokenPipeError:
        _quiet_broken_pipe()
    if not quiet:
        click.echo(
            f"grainclass: {report.cells} cells, volume {report.volume:.12g} "
            f"(box {box**3:.12g}); cells with a corner not of three faces: "
            f"{report.bad_corners}; faces seen from one side: {report.one_sided_faces}",
            err=True,
        )
    problems = report.problems(box)
    if problems:
        raise click.ClickException(
            f"the tessellation failed its checks ({'; '.join(problems)}); {output} is written, "
            "but its grains are not those of the seeds' Voronoi tessellation"
        )


def _vertex_counts(
    ctx: click.Context, param: click.Parameter, values: tuple[str, ...]
) -> list[int]:
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


@cli.command("census", epilog=CENSUS_EXIT_CODES)
@click.argument("n_values", nargs=-1, required=True, metavar="N...", callback=_vertex_counts)
@click.option(
    "-o",
    "--output",
    required=True,
    metavar="DIR",
    callback=_path,
    type=click.Path(file_okay=False),
    help="Census directory: checkpoints, then the tables (Parquet and CSV) and provenance.json.",
)
@click.option(
    "--parts",
    type=click.IntRange(min=1),
    default=8,
    show_default=True,
    help="Tasks per N (plantri's res/mod); a rerun must give the same number to resume.",
)
@click.option(
    "--scheduler",
    metavar="ADDRESS",
    help="Run on an existing Dask cluster (tcp://host:port) instead of a local one.",
)
@click.option(
    "--workers",
    type=click.IntRange(min=1),
    help="Worker processes of the local cluster (default: one per core).",
)
@click.option(
    "--chunk-size",
    type=click.IntRange(min=1, max=MAX_CHUNK_SIZE),
    default=DEFAULT_CHUNK_SIZE,
    show_default=True,
    help="Triangulations per batch inside a task.",
)
@click.option("--plantri", metavar="PATH", help="plantri binary (default: passagemath-plantri's).")
@click.option("-q", "--quiet", is_flag=True, help="No progress on stderr.")
def census_cmd(
    n_values: list[int],
    output: str,
    parts: int,
    scheduler: str | None,
    workers: int | None,
    chunk_size: int,
    plantri: str | None,
    quiet: bool,
) -> None:
    """Classify every triangulation of the sphere with N vertices, in parts on Dask.

    N is a number of vertices or a range A..B: `grainclass census 4..16 -o census/`. Each part
    streams plantri's output through the classification into counts, saved in DIR as soon as
    it finishes; running the same command again skips finished parts. At the end the counts are
    checked against plantri's own (-u, -c4, -m4) and the tables are printed and written to DIR.
    Needs the census extra: pip install 'grainclass[census]'.
    """
    from grainclass.census import ProgressPrinter, dask_client, run_census
    from grainclass.errors import GrainclassError

    _resume_collection()
    try:
        import distributed  # noqa: F401 (the census extra)
    except ImportError as exc:
        raise click.ClickException(
            f"census needs Dask ({exc.name} is missing): pip install 'grainclass[census]'"
        ) from None
    try:
        with dask_client(scheduler, workers) as client:
            result = run_census(
                n_values,
                parts,
                output,
                client,
                chunk_size,
                plantri,
                report=None if quiet else ProgressPrinter(),
            )
    except (GrainclassError, OSError) as exc:
        raise click.ClickException(str(exc)) from None
    _report_census(result, output)


def _report_census(result, output: str) -> None:
    from grainclass.render import render

    click.echo(
        f"census: {len(result.parts)} parts ({result.computed} computed now, "
        f"{result.skipped} from earlier runs) in {result.seconds:.1f} s",
        err=True,
    )
    for failure in result.failures:
        click.echo(f"census: failed: {failure}", err=True)
    if result.summary is None:
        raise click.ClickException(
            f"{len(result.failures)} task(s) failed; finished parts are kept in {output}: "
            "run the same command again to retry the rest"
        )
    with _output("-") as sink:
        _write_all(sink, render(result.summary, ("classes", "split"), "text"))
    click.echo("Cross-checks against plantri's own counts")
    for check in result.checks:
        verdict = "ok" if check.ok else "MISMATCH"
        click.echo(
            f"  n={check.n:<3} {check.what:<28} {check.census:>12} {check.plantri:>12}  {verdict}"
        )
    if not result.ok:
        raise click.ClickException("the census disagrees with plantri (see the cross-checks)")
    click.echo(f"tables and provenance written to {output}", err=True)


def _write_all(sink: BinaryIO, data: str | bytes) -> None:
    """Write all of ``data``: a pipe whose reader goes away mid-write takes part of it and
    says so only in the count, and the next write raises BrokenPipeError."""
    view = memoryview(data.encode() if isinstance(data, str) else data)
    while view:
        view = view[sink.write(view) :]


@contextmanager
def _output(path: str) -> Iterator[BinaryIO]:
    """The output ``path`` (``-``: standard output), opened now, so that a path that cannot
    be written fails before the work, not after it; written whole or not at all (see
    :func:`grainclass.atomic.atomic_output`). A closed pipe ends quietly."""
    from grainclass.atomic import atomic_output
    from grainclass.errors import OutputError

    try:
        with atomic_output(path) as sink:
            yield sink
    except BrokenPipeError:
        _quiet_broken_pipe()
    except OutputError as exc:
        raise click.ClickException(str(exc)) from None


def _quiet_broken_pipe() -> None:
    # The reader of our output went away (`| head`): stop quietly, as Unix tools do.
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, sys.stdout.fileno())
    sys.exit(1)


def _show_warning(message, category, filename, lineno, file=None, line=None) -> None:
    """A warning as a line of its own on standard error, without Python's source location."""
    click.echo(f"grainclass: warning: {message}", err=True)


class _Stopped(BaseException):
    """SIGTERM or SIGHUP, raised like Ctrl-C's KeyboardInterrupt, so that what a command has
    begun (a temporary output file) is undone on the way out."""

    def __init__(self, signum: int) -> None:
        super().__init__(signum)
        self.signum = signum


_STOPS = ("SIGINT", "SIGTERM", "SIGHUP")  # SIGTERM and SIGHUP are not on Windows


_stopping = False  # set by the first stop signal, and once all is done


def _stop(signum: int, frame: object) -> None:
    # Stopping, the run undoes what it began (a temporary output file) and waits for its
    # threads: a second signal (timeout sends one to the process, then one to its group; a
    # second Ctrl-C) cut that short, or, once all was done, ended the interpreter's shutdown
    # in a traceback. Later signals are let go here, not set to be ignored: processes started
    # from here on (a test's, say) would inherit that.
    global _stopping
    if _stopping:
        return
    _stopping = True
    raise KeyboardInterrupt if signum == signal.SIGINT else _Stopped(signum)


def _lost_stop(unraisable: sys.UnraisableHookArgs) -> None:
    """``sys.unraisablehook``: a stop that :func:`_stop` raised where Python ignores exceptions
    (a weakref's callback, a ``__del__`` run by the garbage collector) was lost, and with it
    every later stop signal, which :func:`_stop` lets go: a census went on to its end after
    Ctrl-C. The signal is sent again, from a thread of its own, to be raised in the code that
    runs next (sent from here, it was raised here again; a ``threading.Thread`` waits for its
    start, and it was raised in that wait)."""
    global _stopping
    stop = unraisable.exc_value
    if not isinstance(stop, KeyboardInterrupt | _Stopped):
        sys.__unraisablehook__(unraisable)
        return
    _stopping = False
    signum = stop.signum if isinstance(stop, _Stopped) else signal.SIGINT
    _thread.start_new_thread(signal.raise_signal, (signum,))


def _catch_stops() -> None:
    """Stop signals raise (:func:`_stop`), and are sent again if raised where Python ignores
    exceptions (:func:`_lost_stop`)."""
    for name in _STOPS:
        # One ignored already stays so: nohup ignores SIGHUP for a run to outlive its terminal,
        # and a shell, SIGINT for a job it starts in the background.
        if hasattr(signal, name) and signal.getsignal(getattr(signal, name)) != signal.SIG_IGN:
            signal.signal(getattr(signal, name), _stop)
    sys.unraisablehook = _lost_stop


def _stop_worker_pools() -> None:
    """Worker processes of an interrupted run, if it started any, stopped before exit."""
    if "grainclass.parallel" in sys.modules:  # else none was started
        from grainclass.parallel import stop_worker_pools

        stop_worker_pools()


def main() -> None:
    """Entry point: click's handling, except that Ctrl-C exits 130 as shells expect, and
    SIGTERM and SIGHUP (``timeout``, a batch scheduler, a closed terminal) 143 and 129."""
    # Readers build millions of short-lived lists (freed by reference counting, not in
    # cycles); at the default thresholds the cyclic collector's passes over them and over the
    # imported libraries took half of the time of reading face-loop text. It still runs, less
    # often, but not during start-up: importing numba, pandas and pyarrow and loading the
    # kernels makes some 230,000 objects for good, and passes over them took a third of a
    # warm run (0.3 of 1.0 s). The commands turn it on when their first batch is through.
    gc.set_threshold(100_000, 50, 1000)
    gc.disable()
    # numpy's OpenBLAS starts a thread per core when it is imported, which spin a while waiting
    # for matrices (0.1 s of CPU, taken from a producer such as plantri in the same pipe);
    # grainclass multiplies none large enough to use them.
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    warnings.showwarning = _show_warning
    _catch_stops()
    stopped = False
    try:
        code = cli.main(standalone_mode=False)
    except click.ClickException as exc:
        exc.show()
        code = exc.exit_code
    except (click.Abort, KeyboardInterrupt):
        click.echo("grainclass: interrupted", err=True)
        code = 130
        stopped = True
        _stop_worker_pools()
    except _Stopped as stop:
        click.echo(f"grainclass: stopped by {signal.Signals(stop.signum).name}", err=True)
        code = 128 + stop.signum
        stopped = True
        _stop_worker_pools()
    global _stopping
    _stopping = True  # all is done: a signal now would only end the shutdown in a traceback
    if stopped and _threads_busy():
        # Stopped while a thread still runs a kernel, or numba compiles one at a first run:
        # the interpreter's exit would wait for it, seconds after Ctrl-C. What the run began is
        # undone already (its output file removed, its worker processes stopped), and nothing
        # that thread does is needed.
        with suppress(OSError, ValueError):
            sys.stdout.flush()
            sys.stderr.flush()
        os._exit(code)
    sys.exit(code if isinstance(code, int) else 0)


def _threads_busy() -> bool:
    return (
        "grainclass.parallel" in sys.modules and sys.modules["grainclass.parallel"].threads_busy()
    )
