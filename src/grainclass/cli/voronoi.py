"""``grainclass voronoi``: a periodic Poisson-Voronoi tessellation, as grains."""

from __future__ import annotations

import click

from grainclass.cli import exit_codes, options, startup


@click.command("voronoi", epilog=exit_codes.VORONOI)
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
    callback=options.nonempty_path,
    help="Adjacency text with volume= and area= per grain; *.parquet: classified grains.",
)
@options.quiet("No report on stderr.")
def voronoi_cmd(n_seeds: int, seed: int | None, box: float, output: str, quiet: bool) -> None:
    """A periodic Poisson-Voronoi tessellation of N uniform random seeds (Voro++), as grains.

    The paper's V-268402 data set is `grainclass voronoi 268402 -o pv.txt`. Every cell is checked
    (three faces at each corner, every face seen from both sides, the cells filling the box);
    a failed check exits 1.
    """
    from grainclass.cli.output import quiet_broken_pipe, write_all
    from grainclass.cli.progress import Progress
    from grainclass.errors import GrainclassError
    from grainclass.voronoi import VoronoiReport, poisson_voronoi

    startup.resume_collection()
    report = VoronoiReport()
    progress = Progress.on_terminal(quiet)
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
                    write_all(sink, "".join(adjacency_lines(batch)))
    except GrainclassError as exc:
        raise click.ClickException(str(exc)) from None
    except BrokenPipeError:
        quiet_broken_pipe()
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
