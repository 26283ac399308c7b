"""``grainclass plot``: the paper's figures from the user's own grains."""

from __future__ import annotations

import click

from grainclass.cli import errors, exit_codes, options, startup
from grainclass.options import ReadOptions
from grainclass.vocabulary import CLASSES, NAMED_SERIES, PENALTIES, PLOT_KINDS

EPILOG = exit_codes.epilog(
    "success",
    "an input could not be read or cannot give the figure (no ok grains, no volumes for Q, no "
    "time step in its name), matplotlib is not installed, or an output could not be written",
)


def _times(ctx: click.Context, param: click.Parameter, value: str | None) -> list[float] | None:
    if value is None:
        return None
    try:
        return [float(t) for t in value.split(",")]
    except ValueError:
        raise click.BadParameter(f"expected numbers separated by commas, got {value!r}") from None


@click.command("plot", cls=errors.Command, epilog=EPILOG)
@click.argument("kind", type=click.Choice(PLOT_KINDS), metavar="KIND")
@click.argument("inputs", nargs=-1, required=True, metavar="INPUT...")
@options.figure_output()
@click.option(
    "--label",
    "labels",
    multiple=True,
    metavar="NAME",
    help="Name of each data set in the legend, in input order (default: the file's name); "
    "evolution: one name for the series of steps.",
)
@click.option(
    "--data",
    metavar="CSV",
    callback=options.nonempty_path,
    help="Also write the numbers drawn, one row per point: dataset, series, x, y (and yerr).",
)
@options.faces("round: grains with N faces instead of all grains (repeatable).")
@click.option(
    "--min-frequency",
    type=click.FloatRange(min=0, max=1),
    default=1e-5,
    show_default=True,
    help="penalty: the least frequency of a flag type drawn.",
)
@click.option(
    "--penalty",
    type=click.Choice(PENALTIES),
    default="P4",
    show_default=True,
    help="penalty: the candidate drawn (see grainclass penalties; P4 is the paper's, the "
    "others need the belts of classify --belt-length L, L = 6 unless --belt-length).",
)
@click.option(
    "--series",
    multiple=True,
    type=click.Choice([*CLASSES, *NAMED_SERIES]),
    help="evolution: a class or named kind to follow (repeatable; default: flag).",
)
@click.option(
    "--times",
    callback=_times,
    metavar="T1,T2,...",
    help="evolution: the time of each input, in input order (default: the number in its name).",
)
@options.seed(
    "edge-errors: the seed of the random edge flips, as grainclass perturb --seed (default 0)."
)
@options.reading(
    types_default=None,
    belts=options.belt_length("penalty: the candidates' belts of l = 4..L (default 6)."),
)
def plot_cmd(
    kind: str,
    inputs: tuple[str, ...],
    output: str,
    labels: tuple[str, ...],
    data: str | None,
    n_values: tuple[int, ...],
    min_frequency: float,
    penalty: str,
    series: tuple[str, ...],
    times: list[float] | None,
    seed: int | None,
    reading: ReadOptions,
    quiet: bool,
) -> None:
    """Draw one of the paper's figures for the grains of INPUT...

    \b
    KIND is one of
      round      percent of grains in round<=k against k (--n N: grains with N faces)
      classes    frequency of each class against the number of faces n
      faces-q    mean isoperimetric quotient Q against n, with standard errors
      round-q    mean Q against round_k
      penalty    flag types' frequency against their penalty, coloured by n (--penalty)
      ranks      type frequency against rank
      evolution  one input per time step: percent of flag grains (or --series) over time
      edge-errors  percent of grains in round_k against k, and sc, for the first input
                 after 0, 1, 2 and 3 random edge flips per grain (EEPG, as grainclass
                 perturb --flips K --seed SEED), beside the other inputs as they are

    Each INPUT is a data set (V, R and E in the paper): a per-grain Parquet file or anything
    summarize reads, classified on the fly ('-' reads standard input). Needs the plot extra:
    pip install 'grainclass[plot]'.
    """
    from grainclass.options import FigureOptions

    request = FigureOptions(
        kind,
        n_values=n_values,
        min_frequency=min_frequency,
        penalty=penalty,
        series=series or ("flag",),
        steps=None if times is None else tuple(times),
        seed=seed,
    )
    startup.begin(inputs, reading, [output, data])
    from contextlib import nullcontext

    from grainclass.atomic import atomic_output
    from grainclass.cli.output import write_all
    from grainclass.datasets import figure_table
    from grainclass.plots import draw, figure_format, require_matplotlib

    require_matplotlib()
    # Both outputs are opened before the work and appear together, or neither does.
    with (
        atomic_output(output) as figure,
        atomic_output(data) if data is not None else nullcontext() as numbers,
    ):
        table = figure_table(list(inputs), request, labels, reading, startup.watcher(quiet))
        table.attrs["penalty"] = penalty
        draw(kind, table, figure, figure_format(output))
        if numbers is not None:
            write_all(numbers, table.to_csv(index=False))
    if not quiet:
        click.echo(
            f"grainclass: {kind} figure of {len(table)} points written to {output}", err=True
        )
