"""``grainclass penalties``: how well candidate penalties rank the flag types' frequencies."""

from __future__ import annotations

import click

from grainclass.cli import exit_codes, options, startup


@click.command("penalties", epilog=exit_codes.SUMMARY)
@click.argument("grains", nargs=-1, required=True, metavar="GRAINS...")
@click.option(
    "--belt-lengths",
    type=click.IntRange(4, 10),
    default=6,
    show_default=True,
    metavar="L",
    help="Sum the belt penalties over l = 4..L (Parquet inputs need classify --belts "
    "--belt-lengths L or more).",
)
@click.option(
    "--n",
    "n_values",
    type=click.IntRange(min=4),
    multiple=True,
    help="Only grains with N faces (repeatable; default: every n with three flag types).",
)
@options.table_format
@options.stdout_or_file
@options.include_boundary
@options.reading_grains("--input-format", types_default=None)
def penalties_cmd(
    grains: tuple[str, ...],
    belt_lengths: int,
    n_values: tuple[int, ...],
    output_format: str | None,
    output: str,
    include_boundary: bool,
    input_format: str,
    triple_edges: tuple[str, str],
    chunk_size: int,
    jobs: int | None,
    quiet: bool,
) -> None:
    """Rank correlations between flag types' frequencies and candidate penalties, per n.

    For the flag grains of GRAINS, grouped by type (Weinberg vector), Spearman's rho between
    each type's count and each candidate: P4, the paper's penalty; P4..L, the belt penalties
    summed over l = 4..L; each divided by the symmetry order (/sym), or plus one times it
    (*sym); sym alone. A penalty that ranks the types well has rho near -1. GRAINS are per-grain
    Parquet tables classified with --belts, or any input classify reads (classified now).
    """
    startup.read_ahead(grains, input_format)
    from grainclass.cli.output import opened, refuse_parquet_on_terminal, table_format, write_all
    from grainclass.cli.progress import Progress
    from grainclass.errors import GrainclassError
    from grainclass.parallel import set_jobs
    from grainclass.penalties import COLUMNS, penalty_correlations
    from grainclass.pipeline import grain_tables
    from grainclass.render import render_frame

    fmt = table_format(output_format, output)
    if fmt == "parquet":
        refuse_parquet_on_terminal(output)
    if jobs is not None:
        set_jobs(jobs)
    in_fmt = None if input_format == "auto" else input_format
    with opened(output) as sink:
        try:
            stream = grain_tables(
                list(grains), COLUMNS, in_fmt, chunk_size, triple_edges, belts=belt_lengths
            )
            table = penalty_correlations(
                Progress.on_terminal(quiet).wrap(startup.after_start_up(stream)),
                n_values,
                include_boundary,
                belt_lengths,
            )
        except GrainclassError as exc:
            raise click.ClickException(str(exc)) from None
        except ValueError as exc:
            raise click.ClickException(str(exc)) from None
        shown = table.copy()
        if fmt in ("text", "markdown", "latex"):
            for name in shown.columns[3:]:
                shown[name] = shown[name].map(lambda rho: "" if rho != rho else f"{rho:+.3f}")
        title = (
            f"Spearman's rho between flag types' counts and penalties, per n "
            f"(belts of l = 4..{belt_lengths}; -1: larger penalty, rarer type)"
        )
        write_all(sink, render_frame(shown, fmt, title))
