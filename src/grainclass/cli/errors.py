"""How an error of the library reaches the user: one line in the command line's words, and its
exit code. The one place where an error class meets an exit code."""

from __future__ import annotations

import click

from grainclass import interrupts
from grainclass.cli.exit_codes import ExitCode
from grainclass.cli.options import FLAGS
from grainclass.cli.output import quiet_broken_pipe
from grainclass.errors import GrainclassError, OptionError, Remedy

# Every other GrainclassError is a failure of the run (1): an input, an output or the machine.
EXIT_CODES: dict[type[GrainclassError], ExitCode] = {OptionError: ExitCode.USAGE}


def exit_code(error: GrainclassError) -> ExitCode:
    """The exit code of a run that ``error`` ended."""
    for kind, code in EXIT_CODES.items():
        if isinstance(error, kind):
            return code
    return ExitCode.FAILURE


def message(error: GrainclassError) -> str:
    """``error`` in one line, its parameter and remedy named by their flags.

    >>> from grainclass.errors import DataError
    >>> message(DataError("x.parquet: ok grains without belts", Remedy("belt_length", 8, True)))
    'x.parquet: ok grains without belts: classify the input again with --belt-length 8'
    """
    text = error.message
    if isinstance(error, OptionError):
        text = f"{FLAGS.get(error.parameter, error.parameter)}: {text}"
    if error.remedy is not None:
        text = f"{text}: {remedy(error.remedy)}"
    return " ".join(text.split())


def remedy(fix: Remedy) -> str:
    """What would mend an error, said with the command line's flags."""
    flag = FLAGS.get(fix.parameter, fix.parameter)
    if fix.parameter == "types" and fix.value is True:
        setting = "without --no-types"
    elif fix.value is None:
        setting = f"another {flag}"
    else:
        setting = f"with {flag} {fix.value}"
    if fix.reclassify:
        return f"classify the input again {setting}"
    if fix.parameter == "chunk_size":
        return "a smaller --chunk-size may do"
    return f"try {setting}"


class Command(click.Command):
    """A command of ``grainclass``: an error of the library that it lets through ends it as a
    click error, one line with its exit code (:func:`exit_code`); a usage error shows the
    command's usage too. A reader of standard output that goes away ends it quietly with 141
    (click would end it with 1, as a failure)."""

    def invoke(self, ctx: click.Context) -> object:
        try:
            return super().invoke(ctx)
        except Exception as exc:
            # A failure while a stop is pending is most likely the stop's doing (a child process
            # it ended, a worker that died starting): the run ends as stopped.
            interrupts.checkpoint()
            if isinstance(exc, BrokenPipeError):
                raise click.exceptions.Exit(quiet_broken_pipe()) from None
            if not isinstance(exc, GrainclassError):
                raise
            if exit_code(exc) == ExitCode.USAGE:
                raise click.UsageError(message(exc), ctx) from None
            failure = click.ClickException(message(exc))
            failure.exit_code = exit_code(exc)
            raise failure from None
