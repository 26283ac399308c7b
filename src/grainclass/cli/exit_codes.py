"""Exit codes, the contract every command keeps, and the help text that lists them."""

from __future__ import annotations

import signal
from enum import IntEnum


class ExitCode(IntEnum):
    """What a ``grainclass`` process returns: Unix habits, and 128 + N for a stop by signal N."""

    OK = 0
    FAILURE = 1
    USAGE = 2
    HANGUP = 128 + signal.SIGHUP
    INTERRUPTED = 128 + signal.SIGINT
    BROKEN_PIPE = 128 + signal.SIGPIPE
    TERMINATED = 128 + signal.SIGTERM

    @classmethod
    def stopped_by(cls, signum: int) -> ExitCode:
        """The code of a run stopped by signal ``signum`` (SIGINT, SIGTERM or SIGHUP)."""
        return cls(128 + signum)


def epilog(
    ok: str, failure: str, interrupted: str = "no partial output file is left behind"
) -> str:
    """A command's ``Exit codes`` help section: what 0, 1 and an interruption mean for it."""
    rows = [
        (ExitCode.OK, ok),
        (ExitCode.FAILURE, failure),
        (ExitCode.USAGE, "usage error"),
        (
            ExitCode.INTERRUPTED,
            f"interrupted: Ctrl-C ({ExitCode.HANGUP:d}, {ExitCode.TERMINATED:d}: SIGHUP, "
            f"SIGTERM); {interrupted}",
        ),
        (
            ExitCode.BROKEN_PIPE,
            "the reader of standard output went away (`| head`): the command stops quietly, as "
            "cat does",
        ),
    ]
    return "\b\nExit codes:\n" + "".join(_row(code, meaning) for code, meaning in rows)


def _row(code: int, meaning: str, width: int = 76) -> str:
    """``  CODE MEANING``, the meaning wrapped under itself (click keeps a ``\\b`` block as is)."""
    import textwrap

    lead = f"  {code:<5d}"
    return (
        "\n".join(
            textwrap.wrap(meaning, width, initial_indent=lead, subsequent_indent=" " * len(lead))
        )
        + "\n"
    )


GRAINS = epilog(
    "success (bad grains are data: they get a row with their status)",
    "an input or output could not be read or written; with --strict, bad grains",
)
SUMMARY = epilog(
    "success (bad grains are data, not errors)",
    "an input or output could not be read or written",
)
CLASSIFY = epilog(
    "success (bad grains are data: they get a row with their status)",
    "an input or output could not be read or written; with --strict, bad grains; in parts "
    "(-o DIR/), a part failed (the others are kept)",
    interrupted="no partial output file is left behind; in parts, the finished parts are kept",
)
VORONOI = epilog(
    "success",
    "points that cannot be read or tessellated (nothing is written), a tessellation that failed "
    "its checks (then the output is written, for a look), or an output that could not be "
    "written; in parts (-o DIR/), a part failed (the others are kept)",
    interrupted="no partial output file is left behind; in parts, the finished parts are kept",
)
CENSUS = epilog(
    "every part done, every cross-check passed",
    "a part failed (the others are kept), the census disagrees with plantri, or an output "
    "could not be written",
    interrupted="finished parts are kept: the same command resumes",
)
