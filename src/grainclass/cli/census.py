"""``grainclass census``: every triangulation of the sphere with N vertices, on Dask."""

from __future__ import annotations

import sys

import click

from grainclass.cli import errors, exit_codes, options, startup
from grainclass.options import DEFAULT_CHUNK_SIZE, MAX_CHUNK_SIZE


@click.command("census", cls=errors.Command, epilog=exit_codes.CENSUS)
@click.argument("n_values", nargs=-1, required=True, metavar="N...", callback=options.vertex_counts)
@click.option(
    "-o",
    "--output",
    required=True,
    metavar="DIR",
    callback=options.output_folder,
    help="Census directory: checkpoints, then the tables (Parquet and CSV) and provenance.json.",
)
@click.option(
    "--parts",
    type=click.IntRange(1, 1_000_000),
    default=8,
    show_default=True,
    help="Tasks per N (plantri's res/mod); a rerun must give the same number to resume.",
)
@options.cluster("the parts")
@click.option(
    "--chunk-size",
    type=click.IntRange(min=1, max=MAX_CHUNK_SIZE),
    default=DEFAULT_CHUNK_SIZE,
    show_default=True,
    help="Triangulations per batch inside a task.",
)
@click.option(
    "--plantri",
    metavar="PATH",
    callback=options.nonempty_path,
    help="plantri binary (default: passagemath-plantri's).",
)
@click.option("-q", "--quiet", is_flag=True, help="Only the tables, the cross-checks and failures.")
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
    from grainclass.census import run_census
    from grainclass.cli.progress import PartsPrinter
    from grainclass.cluster import dask_client, require_dask

    startup.resume_collection()
    require_dask()
    if scheduler is None:  # a remote cluster's workers may see another plantri at that path
        from grainclass.plantri import check_plantri

        check_plantri(plantri)
    with dask_client(scheduler, workers) as client:
        result = run_census(
            n_values,
            parts,
            output,
            client,
            chunk_size,
            plantri,
            report=None if quiet else PartsPrinter(),
        )
    _report(result, output, quiet)


def _report(result, output: str, quiet: bool) -> None:
    """The census's tables and cross-checks on standard output; what it did on standard error
    unless ``quiet``, and its failures."""
    from grainclass.cli.output import write_all
    from grainclass.render import render
    from grainclass.vocabulary import plural

    if not quiet:
        click.echo(
            f"census: {plural(len(result.parts), 'part')} ({result.computed} computed now, "
            f"{result.skipped} from earlier runs) in {result.seconds:.1f} s",
            err=True,
        )
    for failure in result.failures:
        click.echo(f"census: failed: {failure}", err=True)
    if result.summary is None:
        raise click.ClickException(
            f"{plural(len(result.failures), 'task')} failed; finished parts are kept in "
            f"{output}: run the same command again to retry the rest"
        )
    write_all(sys.stdout.buffer, render(result.summary, ("classes", "split"), "text"))
    click.echo("Cross-checks against plantri's own counts")
    for check in result.checks:
        verdict = "ok" if check.ok else "MISMATCH"
        click.echo(
            f"  n={check.n:<3} {check.what:<28} {check.census:>12} {check.plantri:>12}  {verdict}"
        )
    if not result.ok:
        raise click.ClickException("the census disagrees with plantri (see the cross-checks)")
    if not quiet:
        click.echo(f"tables and provenance written to {output}", err=True)
