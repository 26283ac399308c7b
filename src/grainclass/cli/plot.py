"""``grainclass plot``: the paper's figures from the user's own grains."""

from __future__ import annotations

import os

import click

from grainclass.cli import exit_codes, options, startup
from grainclass.vocabulary import CLASSES, NAMED_SERIES, PLOT_KINDS

EPILOG = exit_codes.epilog(
    "success",
    "an input could not be read or cannot give the figure (no ok grains, no volumes for Q, no "
    "time step in its name), or an output could not be written",
)


def _figure_path(ctx: click.Context, param: click.Parameter, value: str) -> str:
    options.nonempty_path(ctx, param, value)
    if os.path.splitext(value)[1].lower() not in (".png", ".svg", ".pdf"):
        raise click.BadParameter(f"{value!r}: a figure is a .png, .svg or .pdf file")
    return value


def _times(ctx: click.Context, param: click.Parameter, value: str | None) -> list[float] | None:
    if value is None:
        return None
    try:
        return [float(t) for t in value.split(",")]
    except ValueError:
        raise click.BadParameter(f"expected numbers separated by commas, got {value!r}") from None


@click.command("plot", epilog=EPILOG)
@click.argument("kind", type=click.Choice(PLOT_KINDS), metavar="KIND")
@click.argument("inputs", nargs=-1, required=True, metavar="INPUT...")
@click.option(
    "-o",
    "--output",
    required=True,
    metavar="FIGURE",
    callback=_figure_path,
    help="The figure: .png, .svg or .pdf.",
)
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
@click.option(
    "--n",
    "n_values",
    type=click.IntRange(min=4),
    multiple=True,
    help="round: grains with N faces instead of all grains (repeatable).",
)
@click.option(
    "--min-frequency",
    type=click.FloatRange(min=0, max=1),
    default=1e-5,
    show_default=True,
    help="penalty: the least frequency of a flag type drawn.",
)
@click.option(
    "--penalty",
    type=click.Choice(["P4", "P4..L", "P4/sym", "P4..L/sym", "sym", "(1+P4)*sym", "(1+P4..L)*sym"]),
    default="P4",
    show_default=True,
    help="penalty: the candidate drawn (see grainclass penalties; P4 is the paper's, the "
    "others need the belts of classify --belts, L = 6).",
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
@click.option(
    "--seed",
    type=click.IntRange(min=0, max=2**64 - 1),
    help="edge-errors: the seed of the random edge flips, as grainclass perturb --seed "
    "(default 0).",
)
@options.include_boundary
@options.input_format("--input-format")
@options.triple_edges
@options.chunk_size()
@options.jobs
@options.quiet("No progress on stderr.")
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
    include_boundary: bool,
    input_format: str,
    triple_edges: tuple[str, str],
    chunk_size: int,
    jobs: int | None,
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
    if kind == "evolution":
        if len(labels) > 1:
            raise click.UsageError("evolution draws one data set: give at most one --label")
        if times is not None and len(times) != len(inputs):
            raise click.UsageError(f"--times gives {len(times)} times for {len(inputs)} inputs")
    elif labels and len(labels) != len(inputs):
        raise click.UsageError(f"{len(labels)} --label for {len(inputs)} inputs: give one each")
    if n_values and kind != "round":
        raise click.UsageError("--n chooses the grains of the round figure")
    if seed is not None and kind != "edge-errors":
        raise click.UsageError("--seed is the seed of the edge flips of the edge-errors figure")
    if penalty != "P4" and kind != "penalty":
        raise click.UsageError("--penalty chooses the candidate of the penalty figure")
    startup.read_ahead(inputs, input_format)
    from grainclass.cli.output import opened, write_all
    from grainclass.cli.progress import Progress
    from grainclass.errors import GrainclassError
    from grainclass.figures import figure_data, read_datasets
    from grainclass.parallel import set_jobs
    from grainclass.plots import draw, require_matplotlib

    try:
        require_matplotlib()
    except GrainclassError as exc:
        raise click.ClickException(str(exc)) from None
    if jobs is not None:
        set_jobs(jobs)
    names = list(inputs) if kind == "evolution" else list(labels) or [_name(p) for p in inputs]
    fmt = None if input_format == "auto" else input_format
    progress = Progress.on_terminal(quiet)
    try:
        datasets = read_datasets(
            inputs,
            names,
            kind,
            fmt,
            chunk_size,
            triple_edges,
            include_boundary,
            n_values,
            wrap=lambda items: progress.wrap(startup.after_start_up(items)),
            seed=seed or 0,
            penalty=penalty,
        )
        table = figure_data(
            kind,
            datasets,
            n_values=n_values,
            min_frequency=min_frequency,
            series=series or ("flag",),
            steps=times,
            label=labels[0] if labels else "steps",
        )
        table.attrs["penalty"] = penalty
        draw(kind, table, output)
    except GrainclassError as exc:
        raise click.ClickException(str(exc)) from None
    if data is not None:
        with opened(data) as sink:
            write_all(sink, table.to_csv(index=False))
    if not quiet:
        click.echo(
            f"grainclass: {kind} figure of {len(table)} points written to {output}", err=True
        )


def _name(path: str) -> str:
    """A data set's default label: its file or folder name; ``stdin`` for standard input."""
    return "stdin" if path == "-" else os.path.basename(os.path.normpath(path))
