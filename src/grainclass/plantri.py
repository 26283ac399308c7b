"""plantri (Brinkmann and McKay), which enumerates triangulations of the sphere: finding it,
running it, and reading its report of how many triangulations it wrote.

The ``passagemath-plantri`` wheel ships the binary inside the package as
``sage_wheels/bin/plantri``; it is found there, never downloaded.
"""

from __future__ import annotations

import importlib.util
import os
import re
import shutil
import stat
import subprocess
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import BinaryIO

from grainclass.errors import GrainclassError, PlantriError

# plantri's own counts, by the flags that select them: all triangulations (-u), the
# 4-connected ones (-c4) and those of minimum degree 4 (-m4).
CHECKS = {"all": ("-u",), "flag": ("-u", "-c4"), "min_degree_4": ("-u", "-m4")}
_COUNT_LINE = re.compile(rb"(\d+) triangulations (?:written|generated)")


def find_plantri() -> str:
    """Path of an executable plantri: from passagemath-plantri, else from ``PATH``.

    Raises
    ------
    GrainclassError
        When neither is installed (``pip install passagemath-plantri``).
    """
    spec = importlib.util.find_spec("sage_wheels")
    locations = list(spec.submodule_search_locations or []) if spec else []
    for base in locations:
        binary = Path(base) / "bin" / "plantri"
        if binary.is_file():
            if not os.access(binary, os.X_OK):  # some installers drop the run bit
                binary.chmod(binary.stat().st_mode | stat.S_IXUSR | stat.S_IXGRP | stat.S_IXOTH)
            return str(binary)
    found = shutil.which("plantri")
    if found:
        return found
    raise GrainclassError("plantri not found: pip install passagemath-plantri")


def plantri_command(plantri: str | None) -> str:
    """The plantri to run: ``plantri`` if given, else the one ``find_plantri`` finds."""
    return plantri or find_plantri()


def _reported_count(stderr: bytes, command: list[str], returncode: int = 0) -> int:
    """The number of triangulations plantri says it wrote or generated.

    Raises
    ------
    PlantriError
        When plantri failed, or said no such number.
    """
    if returncode:
        message = stderr.decode(errors="replace").strip()
        said = f": {message}" if message else ""
        raise PlantriError(f"{' '.join(command)} failed (exit {returncode}){said}")
    found = _COUNT_LINE.search(stderr)
    if not found:
        message = stderr.decode(errors="replace").strip()
        raise PlantriError(f"{' '.join(command)}: no count in plantri's report: {message!r}")
    return int(found.group(1))


@dataclass
class PlantriRun:
    """A running plantri: its ``command``, its standard output, and once it has ended the number
    of triangulations it reports having ``written`` (0 until then)."""

    command: list[str]
    stdout: BinaryIO
    written: int = 0


@contextmanager
def run_plantri(args: Sequence[str], plantri: str | None = None) -> Iterator[PlantriRun]:
    """Run plantri with ``args``; the body reads its standard output (``run.stdout``). On the
    way out plantri has ended and ``run.written`` holds its count.

    Raises
    ------
    PlantriError
        On the way out, when plantri failed or reported no count.
    """
    from grainclass.pipes import enlarge_pipe

    command = [plantri_command(plantri), *args]
    with subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE) as process:
        enlarge_pipe(process.stdout)
        run = PlantriRun(command, process.stdout)
        yield run
        stderr = process.stderr.read()
    run.written = _reported_count(stderr, command, process.returncode)


def plantri_count(n: int, check: str, plantri: str | None = None) -> int:
    """plantri's own count of the triangulations with ``n`` vertices of a :data:`CHECKS` kind."""
    flags = CHECKS[check]
    if check != "all" and n < 6:
        # plantri takes -c4 and -m4 only from n = 6; there are none below: a vertex degree sum
        # of 6n - 12 >= 4n needs n >= 6.
        return 0
    command = [plantri_command(plantri), *flags, str(n)]
    done = subprocess.run(command, capture_output=True, check=False)
    return _reported_count(done.stderr, command, done.returncode)


def check_plantri(plantri: str | None = None) -> None:
    """Run plantri on the triangulations with 4 vertices: a binary that cannot be run, or fails,
    fails here, once, rather than in every task of a census.

    Raises
    ------
    PlantriError
        When it cannot be run, or fails.
    """
    command = [plantri_command(plantri), "-u", "4"]
    try:
        done = subprocess.run(command, capture_output=True, check=False)
    except OSError as exc:
        raise PlantriError(f"{command[0]}: cannot be run ({exc.strerror or exc})") from None
    if done.returncode:
        _reported_count(done.stderr, command, done.returncode)


def plantri_version(plantri: str | None = None) -> str:
    """plantri's version line, e.g. ``5.8 - March 4, 2026`` (from its usage message)."""
    done = subprocess.run(
        [plantri_command(plantri), "-help"], capture_output=True, check=False, text=True
    )
    found = re.search(r"[Pp]lantri version (.+)", done.stdout + done.stderr)
    return found.group(1).strip() if found else "unknown"
