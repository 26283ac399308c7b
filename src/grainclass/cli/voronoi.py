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
    metavar="FILE",
    callback=options.nonempty_path,
    help="Adjacency text with volume= and area= per grain; *.parquet: classified grains.",
)
@click.option(
    "-j",
    "--jobs",
    type=click.IntRange(min=1, max=1 << 16),
    help="Threads that compute the cells (default: the CPUs this process may use).",
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
    """
    if (n_seeds is None) == (points_path is None):
        raise click.UsageError("give either N (random seeds) or --points FILE, not both")
    if points_path is None and (radius_column or points_format != "auto"):
        raise click.UsageError("--radius-column and --points-format go with --points")
    if points_path is not None and seed is not None:
        raise click.UsageError("--seed goes with N random seeds, not with --points")
    from grainclass import voronoi
    from grainclass.atomic import refuse_inputs

    refuse_inputs([output], [points_path] if points_path else [])
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
        if progress.enabled:
            click.echo(f"tessellating {n_seeds:,} seeds with Voro++ ...", err=True)
        side = float(the_box.high[0])
        batches = voronoi.poisson_voronoi(n_seeds, seed, side, report=report)
    else:
        from grainclass.readers.points import read_points

        fmt = None if points_format == "auto" else points_format
        points = read_points(points_path, fmt, radius_column)
        the_box = voronoi.points_box(points, box, periodic)
        voronoi.check_points(points, the_box)
        weighted = points.radii is not None
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
    if report.no_cell and (weighted or not quiet):
        shown = ", ".join(report.no_cell[:10]) + (" ..." if len(report.no_cell) > 10 else "")
        why = " (hidden by their neighbours' radii)" if weighted else ""
        click.echo(
            f"grainclass: {plural(len(report.no_cell), 'point')} without a cell{why}, so "
            f"without a grain: {shown}",
            err=True,
        )
    problems = report.problems(the_box.volume, simple=points_path is None, weighted=weighted)
    if problems:
        raise click.ClickException(
            f"the tessellation failed its checks ({'; '.join(problems)}); {output} is written, "
            "but its grains are not those of the points' Voronoi tessellation"
        )
