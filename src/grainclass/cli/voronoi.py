"""``grainclass voronoi``: the Voronoi (or Laguerre) cells of random seeds or of given points."""

from __future__ import annotations

import click

from grainclass.cli import errors, exit_codes, options, startup
from grainclass.cli.progress import Progress
from grainclass.vocabulary import plural


class BoxType(click.ParamType):
    """``L`` (the cube [0, L]) or ``XLO,XHI,YLO,YHI,ZLO,ZHI``."""

    name = "box"

    def convert(self, value, param, ctx):
        from grainclass.box import Box

        if not isinstance(value, str):
            return value
        try:
            numbers = [float(v) for v in value.split(",")]
        except ValueError:
            self.fail(f"expected L or XLO,XHI,YLO,YHI,ZLO,ZHI, got {value!r}", param, ctx)
        if len(numbers) == 1:
            numbers = [0.0, numbers[0]] * 3
        if len(numbers) != 6:
            self.fail(f"expected 1 or 6 numbers, got {len(numbers)}", param, ctx)
        box = Box(tuple(numbers[0::2]), tuple(numbers[1::2]))
        if box.problem():
            self.fail(f"{value!r} is no box: {box.problem()}", param, ctx)
        return box


def periodic_axes(ctx: click.Context, param: click.Parameter, value: str | None):
    """``xyz``, ``xy``, ..., or ``none``: the periodic axes, as three booleans."""
    if value is None:
        return None
    axes = "" if value.lower() == "none" else value.lower()
    if not value or set(axes) - set("xyz") or len(set(axes)) != len(axes):
        raise click.BadParameter(f"expected axes among x, y, z (or none), got {value!r}")
    return tuple(axis in axes for axis in "xyz")


@click.command("voronoi", cls=errors.Command, epilog=exit_codes.VORONOI)
@click.argument("n_seeds", type=click.IntRange(1, 2**31 - 1), metavar="[N]", required=False)
@click.option(
    "--points",
    "points_path",
    metavar="FILE",
    callback=options.nonempty_path,
    help="Tessellate these points instead of N random seeds (formats: docs/formats.md).",
)
@click.option(
    "--points-format",
    type=click.Choice(["auto", "voro", "xyz", "lammps", "csv", "npy"]),
    default="auto",
    show_default=True,
    help="Format of --points; 'auto' goes by the file's suffix, else its first lines.",
)
@click.option(
    "--radius-column",
    metavar="NAME",
    help="The column (CSV, LAMMPS, extended XYZ, .npy fields) of the points' radii, which make "
    "the cells Laguerre cells (default: a column r or radius, if any).",
)
@options.seed("Random seed, 0 to 2^64-1: the same seed gives the same grains.")
@click.option(
    "--box",
    type=BoxType(),
    help="The box: L (the cube from 0 to L) or XLO,XHI,YLO,YHI,ZLO,ZHI. Default: the box of "
    "the points file (LAMMPS, extended XYZ), else the unit cube.",
)
@click.option(
    "--periodic",
    metavar="AXES",
    callback=periodic_axes,
    help="The periodic axes: xyz, xy, ..., or none (walls on every side). Default: as the "
    "points file says (LAMMPS pp, extended XYZ pbc), else xyz.",
)
@click.option(
    "-o",
    "--output",
    required=True,
    metavar="FILE|DIR/",
    callback=options.nonempty_path,
    help="Adjacency text with volume= and area= per grain; *.parquet: classified grains; a "
    "folder (DIR/, with its /): classified grains in parts, on Dask.",
)
@click.option(
    "--parts",
    type=click.IntRange(1, 1_000_000),
    help="Slabs along z, each a Dask task and a file of the folder -o DIR/ (default: one per "
    "million cells, at least one per worker). Any number gives the same cells.",
)
@options.cluster("the parts")
@click.option(
    "-j",
    "--jobs",
    type=click.IntRange(min=1, max=1 << 16),
    help="Threads that compute the cells (default: the CPUs this process may use); in parts, "
    "each task has one.",
)
@click.option(
    "-q", "--quiet", is_flag=True, help="No report on stderr.", callback=startup.note_quiet
)
def voronoi_cmd(
    n_seeds: int | None,
    points_path: str | None,
    points_format: str,
    radius_column: str | None,
    seed: int | None,
    box,
    periodic,
    output: str,
    parts: int | None,
    scheduler: str | None,
    workers: int | None,
    jobs: int | None,
    quiet: bool,
) -> None:
    """Voronoi cells as grains: of N uniform random seeds in a periodic cube, or of the points
    of a file (--points), with Voro++.

    The paper's V-268402 data set is `grainclass voronoi 268402 -o pv.txt`. With --points, each
    grain's grain_id is its point's id; points with radii give Laguerre (power) cells; cells
    with a face on a side of the box that is not periodic are boundary grains. Every cell is
    checked (every face seen from both sides, the cells filling the box; for random seeds, also
    three faces at each corner); a failed check exits 1.

    With -o DIR/ the box is cut into slabs along z, each computed by a Dask task (a local
    cluster, or --scheduler) with a margin of its neighbours' points, widened where a cell
    reaches past it, into DIR/part-00000.parquet, ...; running the same command again keeps
    the parts already done. Needs the census extra: pip install 'grainclass[census]'.
    """
    if (n_seeds is None) == (points_path is None):
        raise click.UsageError("give either N (random seeds) or --points FILE, not both")
    if points_path is None and (radius_column or points_format != "auto"):
        raise click.UsageError("--radius-column and --points-format go with --points")
    if points_path is not None and seed is not None:
        raise click.UsageError("--seed goes with N random seeds, not with --points")
    folder = options.is_folder(output)
    if not folder and (parts is not None or scheduler is not None or workers is not None):
        raise click.UsageError("--parts, --scheduler and --workers write a folder: give -o DIR/")
    if folder and jobs is not None:
        raise click.UsageError("-j/--jobs goes with one output file: in parts, --workers")
    from grainclass import voronoi
    from grainclass.atomic import refuse_inputs

    refuse_inputs([output], [points_path] if points_path else [])
    if folder:
        from grainclass.cluster import require_dask
        from grainclass.parts import check_output_folder

        check_output_folder(output)
        require_dask()
    voronoi.voro_engine()  # installed without Voro++: say so before reading the points
    if jobs is not None:
        from grainclass.parallel import set_jobs

        set_jobs(jobs)
    startup.resume_collection()
    report = voronoi.VoronoiReport()
    progress = Progress.on_terminal(quiet)
    weighted = False
    if points_path is None:
        the_box = voronoi.random_seeds_box(box, periodic)
        side = float(the_box.high[0])
        if folder:
            _in_parts(
                output, parts, scheduler, workers, quiet, n_seeds=n_seeds, seed=seed, side=side
            )
            return
        if progress.enabled:
            click.echo(f"tessellating {n_seeds:,} seeds with Voro++ ...", err=True)
        batches = voronoi.poisson_voronoi(n_seeds, seed, side, report=report)
    else:
        from grainclass.readers.points import read_points

        fmt = None if points_format == "auto" else points_format
        points = read_points(points_path, fmt, radius_column)
        the_box = voronoi.points_box(points, box, periodic)
        voronoi.check_points(points, the_box)
        weighted = points.radii is not None
        if folder:
            _in_parts(
                output, parts, scheduler, workers, quiet, points=points, box=the_box, checked=True
            )
            return
        if progress.enabled:
            kind = "Laguerre" if weighted else "Voronoi"
            click.echo(
                f"{kind} cells of {len(points.xyz):,} points in {the_box.describe()} ...", err=True
            )
        batches = voronoi.tessellate(points, the_box, report=report, checked=True)
    voronoi.write_cells(progress.wrap(batches), output)
    if not quiet:
        click.echo(
            f"grainclass: {plural(report.cells, 'cell')}, volume {report.volume:.12g} "
            f"(box {the_box.volume:.12g}); boundary cells: {report.boundary}; cells with a "
            f"corner not of three faces: {report.bad_corners}; cells with a face seen from one "
            f"side: {report.one_sided_faces}",
            err=True,
        )
    _report_problems(report, the_box.volume, output, points_path is None, weighted, quiet)


def _report_problems(
    report, box_volume: float, output: str, simple: bool, weighted: bool, quiet: bool
) -> None:
    """Points without a cell on standard error; a failed check exits 1."""
    if report.no_cells and (weighted or not quiet):
        shown = ", ".join(report.no_cell[:10]) + (" ..." if report.no_cells > 10 else "")
        why = " (hidden by their neighbours' radii)" if weighted else ""
        click.echo(
            f"grainclass: {plural(report.no_cells, 'point')} without a cell{why}, so "
            f"without a grain: {shown}",
            err=True,
        )
    problems = report.problems(box_volume, simple=simple, weighted=weighted)
    if problems:
        raise click.ClickException(
            f"the tessellation failed its checks ({'; '.join(problems)}); {output} is written, "
            "but its grains are not those of the points' Voronoi tessellation"
        )


def _in_parts(
    output: str,
    parts: int | None,
    scheduler: str | None,
    workers: int | None,
    quiet: bool,
    **what,
) -> None:
    """The tessellation as a data set in parts on Dask (``what``: the seeds or the points)."""
    from grainclass.box import Box
    from grainclass.cli.progress import PartsPrinter, parts_line
    from grainclass.cluster import dask_client
    from grainclass.parts import remove_part_temporaries
    from grainclass.voronoi_parts import default_parts, tessellate_in_parts
    from grainclass.voronoi_slabs import Slabs

    points = what.get("points")
    n = len(points.xyz) if points is not None else what["n_seeds"]
    if parts is not None:  # before a cluster starts
        Slabs(what.get("box") or Box.cube(what.get("side", 1.0)), n, parts)
    try:
        with dask_client(scheduler, workers) as client:
            if parts is None:
                parts = default_parts(n, sum(client.nthreads().values()))
            if not quiet:
                click.echo(f"tessellating {n:,} points in {parts} parts on Dask ...", err=True)
            printer = None if quiet else PartsPrinter(line=parts_line("voronoi", "cells"))
            result = tessellate_in_parts(output, client, parts, report=printer, **what)
    finally:  # the temporary files of parts that stopped with the workers
        remove_part_temporaries(output)
    report = result.report
    if not quiet:
        widened = f"; margins widened in {len(result.widened)}" if result.widened else ""
        click.echo(
            f"grainclass: {plural(report.cells, 'cell')} in {plural(result.parts, 'part')} "
            f"({result.computed} computed now, {result.skipped} from earlier runs{widened}) in "
            f"{result.seconds:.1f} s, volume {report.volume:.12g} (box {result.box.volume:.12g}); "
            f"boundary cells: {report.boundary}; cells with a corner not of three faces: "
            f"{report.bad_corners}; cells with a face seen from one side: "
            f"{report.one_sided_faces}",
            err=True,
        )
    for failure in result.failures:
        click.echo(f"grainclass: failed: {failure}", err=True)
    if result.failures:
        raise click.ClickException(
            f"{plural(len(result.failures), 'part')} failed; finished parts are kept in "
            f"{output}: run the same command again to compute the rest"
        )
    weighted = points is not None and points.radii is not None
    _report_problems(report, result.box.volume, output, points is None, weighted, quiet)
