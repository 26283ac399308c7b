"""Output files that appear whole or not at all."""

from __future__ import annotations

import os
import sys
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from typing import BinaryIO

from grainclass.errors import OutputError


@contextmanager
def atomic_output(path: str, binary_stdout_ok: bool = True) -> Iterator[BinaryIO]:
    """A binary stream for ``path``: written to a temporary file beside it and renamed when the
    block ends without an error, removed otherwise. ``-`` is standard output (written as it
    goes; ``binary_stdout_ok=False`` refuses it when that is a terminal).
    """
    if path == "-":
        if not binary_stdout_ok and sys.stdout.isatty():
            raise OutputError("refusing to write binary output to a terminal; use -o FILE")
        yield sys.stdout.buffer
        sys.stdout.buffer.flush()
        return
    directory = os.path.dirname(os.path.abspath(path))
    try:
        fd, tmp = tempfile.mkstemp(
            prefix=f".{os.path.basename(path)}.", suffix=".tmp", dir=directory
        )
    except OSError as exc:
        raise OutputError(f"{path}: cannot write here ({exc.strerror})") from None
    try:
        with os.fdopen(fd, "wb") as sink:
            yield sink
        # mkstemp makes the file private; give it the permissions open() would.
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)
        os.replace(tmp, path)
    except BaseException as exc:
        os.unlink(tmp)
        # The readers report their own system errors as InputError: one here is the output's
        # (a full disk, or a path that names a folder).
        if isinstance(exc, OSError):
            raise OutputError(f"{path}: cannot write here ({exc.strerror or exc})") from None
        raise
