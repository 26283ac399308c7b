"""Typed errors of the library; the CLI turns them into messages and exit codes."""


class GrainclassError(Exception):
    """Base class of all errors grainclass raises on purpose."""


class InputError(GrainclassError):
    """An input that cannot be read at all (a bad grain is data, not an InputError)."""

    def __init__(self, source: str, message: str, line: int | None = None) -> None:
        self.source = source
        self.line = line
        self.message = message
        where = f"{source}:{line}" if line is not None else source
        super().__init__(f"{where}: {message}")


class OutputError(GrainclassError):
    """An output that cannot be written where it was asked for."""


class EmptyInputWarning(UserWarning):
    """An input that holds no grains (an empty file, comments only, a bare header): among
    several, it would otherwise go unnoticed."""
