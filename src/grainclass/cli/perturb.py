"""``grainclass perturb``: edge flips put into grains, the paper's topological edge errors."""

from __future__ import annotations

import click

from grainclass.cli import exit_codes, options, startup

EPILOG = exit_codes.epilog(
    "success (grains that are not ok, or have no admissible edge left, are written as they "
    "are, and counted on standard error)",
    "an input or output could not be read or written",
)


@click.command("perturb", epilog=EPILOG)
@click.argument("inputs", nargs=-1, required=True, metavar="INPUT...")
@click.option(
    "--flips",
    type=click.IntRange(min=0),
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
@click.option(
    "--seed",
    type=click.IntRange(min=0, max=2**64 - 1),
    help="Random seed, 0 to 2^64-1: the same seed gives the same grains, whatever --jobs and "
    "--chunk-size (default: a new one, reported on stderr).",
)
@options.stdout_or_file
@options.reading_grains("--input-format", types_default=None)
def perturb_cmd(
    inputs: tuple[str, ...],
    flips: int | None,
    all_flips: bool,
    seed: int | None,
    output: str,
    input_format: str,
    triple_edges: tuple[str, str],
    chunk_size: int,
    jobs: int | None,
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
    startup.read_ahead(inputs, input_format)
    from grainclass.cli.output import opened, write_all
    from grainclass.cli.progress import Progress
    from grainclass.errors import GrainclassError
    from grainclass.parallel import set_jobs
    from grainclass.perturb import new_seed, output_format, perturbed_batches
    from grainclass.vocabulary import STATUSES
    from grainclass.writers import PLANAR_CODE_HEADER, unwritable

    if jobs is not None:
        set_jobs(jobs)
    fmt = None if input_format == "auto" else input_format
    given = seed is not None
    seed = seed if given else new_seed()
    grains = written = ok = stuck = dropped = 0
    not_ok: dict[int, int] = {}
    with opened(output) as sink:
        try:
            out_fmt = "adjacency" if all_flips else output_format(inputs, fmt)
            if out_fmt == "planar_code":
                if output == "-" and sink.isatty():
                    raise click.UsageError(
                        "refusing to write planar_code to a terminal; use -o FILE"
                    )
                write_all(sink, PLANAR_CODE_HEADER)
            results = perturbed_batches(
                list(inputs),
                None if all_flips else flips,
                seed,
                fmt,
                chunk_size,
                triple_edges,
                write=out_fmt,
            )
            for item in Progress.on_terminal(quiet).wrap(startup.after_start_up(results)):
                write_all(sink, item.data)
                result = item.result
                status = result.status
                grains += len(status)
                written += len(result.batch) - unwritable(result.batch, out_fmt)
                dropped += unwritable(result.batch, out_fmt)
                for code, count in zip(*_counts(status), strict=True):
                    if code:
                        not_ok[code] = not_ok.get(code, 0) + count
                ok += int((status == 0).sum())
                stuck += result.stuck
        except GrainclassError as exc:
            raise click.ClickException(str(exc)) from None
    bad = sum(not_ok.values())
    if not quiet or (stuck and not all_flips) or dropped:
        detail = ", ".join(f"{count} {STATUSES[code]}" for code, count in sorted(not_ok.items()))
        if all_flips:
            what = f"{written} grains written, one per admissible flip of {ok} ok grains"
            if stuck:
                what += f" ({stuck} with no admissible edge gave none)"
            rest = f"; {bad} not ok ({detail}) gave none" if bad else ""
        else:
            what = f"{grains} grains: {ok} ok, {flips} flip(s) each"
            if stuck:
                what += (
                    f", but {stuck} had no admissible edge left before the last "
                    "(kept as they were then)"
                )
            rest = f"; {bad} not ok ({detail}), written unchanged" if bad else ""
            rest += f"; seed {seed}" if not given else ""
        if dropped:
            rest += f"; {dropped} record(s) that could not be read left out of the planar_code"
        click.echo(f"grainclass: {what}{rest}", err=True)


def _counts(status):
    import numpy as np

    codes, counts = np.unique(status, return_counts=True)
    return codes.tolist(), counts.tolist()
