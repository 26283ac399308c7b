"""Every error grainclass raises on purpose, and its warnings: the one place they are defined.

An error a user can cause (an input that cannot be read, a value the library cannot take, a
missing optional dependency, data that cannot give what was asked) is a :class:`GrainclassError`;
any other exception is a bug. Messages speak of the data and of the library's own parameters,
never of command-line flags: an error that a parameter would mend carries a :class:`Remedy`, and
the command line words it with its flag (``grainclass.cli.exit_codes``), as a library user reads
it with the parameter's name. A bad *grain* is not an error: it is a row with its status.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Remedy:
    """What would mend an error: the library parameter ``parameter`` set to ``value`` (None:
    a smaller or different value, as the message says), or, for ``"reclassify"``, the input
    classified again with it."""

    parameter: str
    value: object = None
    reclassify: bool = False

    def __str__(self) -> str:
        setting = self.parameter if self.value is None else f"{self.parameter}={self.value!r}"
        return f"classify the input again with {setting}" if self.reclassify else setting


class GrainclassError(Exception):
    """Base class of every error grainclass raises on purpose."""

    def __init__(self, message: str, remedy: Remedy | None = None) -> None:
        super().__init__(message)
        self.message = message
        self.remedy = remedy

    def __str__(self) -> str:
        return self.message if self.remedy is None else f"{self.message} ({self.remedy})"


class InputError(GrainclassError):
    """An input that cannot be read at all: missing, unreadable, in no format grainclass reads,
    cut off. ``source`` is its path (``-`` for standard input), ``line`` the line or record."""

    def __init__(
        self, source: str, message: str, line: int | None = None, remedy: Remedy | None = None
    ) -> None:
        self.source = source
        self.line = line
        where = f"{source}:{line}" if line is not None else source
        super().__init__(f"{where}: {message}", remedy)


class DataError(GrainclassError):
    """Data that was read but cannot give what was asked of it: a per-grain table without the
    columns a summary needs, a figure with nothing to draw, a batch larger than a table holds."""


class OptionError(GrainclassError, ValueError):
    """A value that a library parameter cannot take (``parameter`` names it). The command line
    checks its options before calling the library, so there this is a usage error."""

    def __init__(self, parameter: str, message: str) -> None:
        self.parameter = parameter
        super().__init__(message)


class OutputError(GrainclassError):
    """An output that cannot be written where it was asked for."""


class MissingDependencyError(GrainclassError):
    """An optional part of grainclass that is not installed (matplotlib for figures, Dask for
    the census, Voro++ for tessellations); the message says how to install it."""


class TessellationError(GrainclassError):
    """A tessellation that failed its checks (a face seen from one side, cells that do not fill
    the box): its grains are not those of the points' tessellation."""


class PlantriError(GrainclassError):
    """plantri failed, or its report says no number of triangulations."""


class ClusterError(GrainclassError):
    """A Dask cluster that cannot be reached or started."""


class CensusError(GrainclassError):
    """A census part whose count disagrees with plantri's, failed tasks, or a census directory
    that holds another census."""


class EmptyInputWarning(UserWarning):
    """An input that holds no grains (an empty file, comments only, a bare header): among
    several, it would otherwise go unnoticed."""
