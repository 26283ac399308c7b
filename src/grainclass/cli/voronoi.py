"""``grainclass voronoi``: the Voronoi (or Laguerre) cells of random seeds or of given points."""

from __future__ import annotations

import click

from grainclass.cli import exit_codes, options, startup


class BoxType(click.ParamType):
    """``L`` (the cube [0, L]) or ``XLO,XHI,YLO,YHI,ZLO,ZHI``."""

    name = "box"
    # Volumes are computed in a box of volume about 1000^3 and scaled back, and summed: far
    # beyond these bounds the factor or the sum leaves the range of a float.
    SMALLEST, LARGEST = 1e-30, 1e30

    def convert(self, value, param, ctx):
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
        sides = [numbers[1] - numbers[0], numbers[3] - numbers[2], numbers[5] - numbers[4]]
        if not all(self.SMALLEST <= side <= self.LARGEST for side in sides):
            self.fail(
                f"each side must be from {self.SMALLEST:g} to {self.LARGEST:g}, got {value!r}",
                param,
                ctx,
            )
        return (tuple(numbers[0::2]), tuple(numbers[1::2]))


def periodic_axes(ctx: click.Context, param: click.Parameter, value: str | None):
    """``xyz``, ``xy``, ..., or ``none``: the periodic axes, as three booleans."""
    if value is None:
        return None
    axes = "" if value.lower() == "none" else value.lower()
    if set(axes) - set("xyz") or len(set(axes)) != len(axes):
        raise click.BadParameter(f"expected axes among x, y, z (or none), got {value!r}")
    return tuple(axis in axes for axis in "xyz")


@click.command("voronoi", epilog=exit_codes.VORONOI)
@click.argument("n_seeds", type=click.IntRange(min=1), metavar="[N]", required=False)
@click.option(
    "--points",
    "points_path",
    metavar="FILE",
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
@click.option(
    "--seed",
    type=click.IntRange(min=0),
    help="Random seed: the same seed gives the same grains.",
)
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
@options.jobs
@options.quiet("No report on stderr.")
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
    from grainclass.cli.output import quiet_broken_pipe, write_all
    from grainclass.cli.progress import Progress
    from grainclass.errors import GrainclassError
    from grainclass.voronoi import Box, VoronoiReport, check_points, poisson_voronoi, tessellate

    if (n_seeds is None) == (points_path is None):
        raise click.UsageError("give either N (random seeds) or --points FILE, not both")
    if points_path is None and (radius_column or points_format != "auto"):
        raise click.UsageError("--radius-column and --points-format go with --points")
    if jobs is not None:
        from grainclass.parallel import set_jobs

        set_jobs(jobs)
    startup.resume_collection()
    report = VoronoiReport()
    progress = Progress.on_terminal(quiet)
    if points_path is None:
        if periodic is not None and not all(periodic):
            raise click.UsageError(
                "random seeds fill a periodic box: --periodic goes with --points"
            )
        if box is not None and (set(box[0]) != {0.0} or len(set(box[1])) != 1):
            raise click.UsageError("random seeds fill a cube: --box L")
        side = 1.0 if box is None else box[1][0]
        the_box = Box.cube(side)
        if progress.enabled:
            click.echo(f"tessellating {n_seeds:,} seeds with Voro++ ...", err=True)
        batches = poisson_voronoi(n_seeds, seed, side, report=report)
    else:
        from grainclass.readers.points import read_points

        if seed is not None:
            raise click.UsageError("--seed goes with N random seeds, not with --points")
        try:
            points = read_points(
                points_path, None if points_format == "auto" else points_format, radius_column
            )
            low, high, tilt = (*box, None) if box is not None else (None, None, None)
            if low is None and points.box is not None:
                low, high, tilt = points.box.low, points.box.high, points.box.tilt
            if low is None:
                low, high = (0.0, 0.0, 0.0), (1.0, 1.0, 1.0)
            if periodic is None:
                periodic = points.box.periodic if points.box is not None else (True,) * 3
            the_box = Box(tuple(low), tuple(high), tuple(periodic), tilt)
            check_points(points, the_box)
        except GrainclassError as exc:
            raise click.ClickException(str(exc)) from None
        if progress.enabled:
            kind = "Laguerre" if points.radii is not None else "Voronoi"
            click.echo(
                f"{kind} cells of {len(points.xyz):,} points in {the_box.describe()} ...", err=True
            )
        batches = tessellate(points, the_box, report=report, checked=True)
    batches = progress.wrap(batches)
    try:
        if output.lower().endswith(".parquet"):
            from grainclass.classification import classify
            from grainclass.parquet import GrainTableWriter

            with GrainTableWriter(output) as writer:
                for batch in batches:
                    writer.write(classify(batch))
        else:
            from grainclass.atomic import atomic_output
            from grainclass.writers import adjacency_text

            with atomic_output(output) as sink:
                for batch in batches:
                    write_all(sink, adjacency_text(batch))
    except GrainclassError as exc:
        raise click.ClickException(str(exc)) from None
    except BrokenPipeError:
        quiet_broken_pipe()
    if not quiet:
        click.echo(
            f"grainclass: {report.cells} cells, volume {report.volume:.12g} "
            f"(box {the_box.volume:.12g}); boundary cells: {report.boundary}; cells with a "
            f"corner not of three faces: {report.bad_corners}; cells with a face seen from one "
            f"side: {report.one_sided_faces}",
            err=True,
        )
    weighted = points_path is not None and points.radii is not None
    if report.no_cell and (weighted or not quiet):
        shown = ", ".join(report.no_cell[:10]) + (" ..." if len(report.no_cell) > 10 else "")
        why = " (hidden by their neighbours' radii)" if weighted else ""
        click.echo(
            f"grainclass: {len(report.no_cell)} point(s) without a cell{why}, so without a "
            f"grain: {shown}",
            err=True,
        )
    problems = report.problems(the_box.volume, simple=points_path is None, weighted=weighted)
    if problems:
        raise click.ClickException(
            f"the tessellation failed its checks ({'; '.join(problems)}); {output} is written, "
            "but its grains are not those of the points' Voronoi tessellation"
        )
