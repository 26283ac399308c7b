"""``grainclass penalties``: how well candidate penalties rank the flag types' frequencies."""

from __future__ import annotations

import click

from grainclass.cli import errors, exit_codes, options, startup
from grainclass.options import OutputOptions, ReadOptions


@click.command("penalties", cls=errors.Command, epilog=exit_codes.SUMMARY)
@click.argument("grains", nargs=-1, required=True, metavar="GRAINS...")
@options.faces("Only grains with N faces (repeatable; default: every n with three flag types).")
@options.table_output()
@options.reading(
    types_default=None,
    belts=options.belt_length(
        "Sum the belt penalties over l = 4..L (Parquet inputs need classify --belt-length L or "
        "more).",
        default=6,
        deprecated_alias=True,
    ),
)
def penalties_cmd(
    grains: tuple[str, ...],
    n_values: tuple[int, ...],
    output: OutputOptions,
    reading: ReadOptions,
    quiet: bool,
) -> None:
    """Rank correlations between flag types' frequencies and candidate penalties, per n.

    For the flag grains of GRAINS, grouped by type (Weinberg vector), Spearman's rho between
    each type's count and each candidate: P4, the paper's penalty; P4..L, the belt penalties
    summed over l = 4..L; each divided by the symmetry order (/sym), or plus one times it
    (*sym); sym alone. A penalty that ranks the types well has rho near -1. GRAINS are per-grain
    Parquet tables classified with --belt-length L, or any input classify reads (classified
    now).
    """
    startup.begin(grains, reading, [output.path])
    from grainclass.atomic import atomic_output
    from grainclass.cli.output import refuse_parquet_on_terminal, write_all
    from grainclass.datasets import penalty_table
    from grainclass.render import render_frame

    fmt = output.table_format
    if fmt == "parquet":
        refuse_parquet_on_terminal(output.path)
    with atomic_output(output.path) as sink:
        table = penalty_table(list(grains), reading, startup.watcher(quiet), n_values)
        shown = table.copy()
        if fmt in ("text", "markdown", "latex"):
            for name in shown.columns[3:]:
                shown[name] = shown[name].map(lambda rho: "" if rho != rho else f"{rho:+.3f}")
        title = (
            f"Spearman's rho between flag types' counts and penalties, per n "
            f"(belts of l = 4..{reading.belt_length}; -1: larger penalty, rarer type)"
        )
        write_all(sink, render_frame(shown, fmt, title))
