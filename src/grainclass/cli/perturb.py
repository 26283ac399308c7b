"""``grainclass perturb``: edge flips put into grains, the paper's topological edge errors."""

from __future__ import annotations

import click

from grainclass.cli import errors, exit_codes, options, startup
from grainclass.options import ReadOptions
from grainclass.vocabulary import STATUSES, plural

EPILOG = exit_codes.epilog(
    "success (grains that are not ok, or have no admissible edge left, are written as they "
    "are, and counted on standard error)",
    "an input or output could not be read or written",
)


@click.command("perturb", cls=errors.Command, epilog=EPILOG)
@click.argument("inputs", nargs=-1, required=True, metavar="INPUT...")
@click.option(
    "--flips",
    type=click.IntRange(0, 2**63 - 1),
    metavar="K",
    help="Edge flips per ok grain, one after another, each drawn uniformly among the edges "
    "admissible then (the paper's edge errors per grain, EEPG).",
)
@click.option(
    "--all-flips",
    is_flag=True,
    help="Instead: every grain one admissible flip makes of each ok grain, with the fields "
    "from_grain, flipped_edge and new_edge (always adjacency text).",
)
@options.seed(
    "Random seed, 0 to 2^64-1: the same seed gives the same grains, whatever --jobs and "
    "--chunk-size (default: a new one, reported on stderr)."
)
@click.option(
    "-o",
    "--output",
    default="-",
    metavar="FILE",
    callback=options.nonempty_path,
    help="Write here instead of stdout.",
)
@options.reading(types_default=None, boundary=False, quiet_help="No report on stderr.")
def perturb_cmd(
    inputs: tuple[str, ...],
    flips: int | None,
    all_flips: bool,
    seed: int | None,
    output: str,
    reading: ReadOptions,
    quiet: bool,
) -> None:
    """Flip edges of every ok grain of INPUT...: the paper's topological edge errors.

    A flip replaces the edge where faces A and B meet, between the corners where faces C and D
    meet them, by an edge where C and D meet: A and B lose a side, C and D gain one. It is
    admissible when A and B keep at least three sides and C and D do not meet already. The
    grains are written as adjacency text (planar_code when every input is planar_code) with
    their ids and fields; grains that are not ok are written unchanged. INPUT is anything
    classify reads ('-': standard input), e.g.
    `grainclass perturb evolved.txt --flips 1 --seed 7 | grainclass summarize -`.
    """
    if (flips is None) == (not all_flips):
        raise click.UsageError("give either --flips K or --all-flips")
    if all_flips and seed is not None:
        raise click.UsageError(
            "--all-flips makes every flip: it draws nothing, and needs no --seed"
        )
    startup.begin(inputs, reading, [output])
    from grainclass.atomic import atomic_output
    from grainclass.cli.output import write_all
    from grainclass.perturb import Counts, new_seed, output_format, perturbed_batches
    from grainclass.writers import PLANAR_CODE_HEADER

    given = seed is not None
    seed = seed if given else new_seed()
    counts = Counts()
    with atomic_output(output) as sink:
        out_fmt = "adjacency" if all_flips else output_format(inputs, reading.input_format)
        if out_fmt == "planar_code":
            if output == "-" and sink.isatty():
                raise click.UsageError("refusing to write planar_code to a terminal; use -o FILE")
            write_all(sink, PLANAR_CODE_HEADER)
        results = perturbed_batches(
            list(inputs), None if all_flips else flips, seed, reading, write=out_fmt
        )
        for item in startup.watcher(quiet)(results):
            write_all(sink, item.data)
            counts.add(item)
    if not quiet or (counts.stuck and not all_flips) or counts.left_out:
        click.echo(f"grainclass: {_report(counts, flips, None if given else seed)}", err=True)


def _report(counts, flips: int | None, seed: int | None) -> str:
    """The run's counts in words; ``flips`` None for all flips, ``seed`` if it was drawn."""
    bad = sum(counts.not_ok.values())
    detail = ", ".join(f"{counts.not_ok[s]} {s}" for s in STATUSES if s in counts.not_ok)
    if flips is None:
        written, ok = plural(counts.written, "grain"), plural(counts.ok, "ok grain")
        what = f"{written} written, one per admissible flip of {ok}"
        if counts.stuck:
            what += f" ({counts.stuck} with no admissible edge gave none)"
        rest = f"; {bad} not ok ({detail}) gave none" if bad else ""
    else:
        what = f"{plural(counts.grains, 'grain')}: {counts.ok} ok, {plural(flips, 'flip')} each"
        if counts.stuck:
            what += (
                f", but {counts.stuck} had no admissible edge left before the last "
                "(kept as they were then)"
            )
        rest = f"; {bad} not ok ({detail}), written unchanged" if bad else ""
        rest += f"; seed {seed}" if seed is not None else ""
    if counts.left_out:
        records = plural(counts.left_out, "record")
        rest += f"; {records} that could not be read left out of the planar_code"
    return what + rest
