"""Data sets written in parts: a folder of per-grain Parquet files, ``part-00000.parquet``,
``part-00001.parquet``, ..., each written whole or not at all by one task, and ``_dataset.json``,
which says what the data set is (the command and its inputs), which parts are done and what
each part's run found.

A part is done when ``_dataset.json`` lists it, with the identity it was asked for (its input,
the options) and the size its file has: a rerun of the same command skips it and redoes the
rest. ``_dataset.json`` is written (whole, by renaming) before the first part starts and again as
each part finishes, so that every part file in the folder belongs to the data set it describes;
``complete`` is true once every part is in. A reader of the folder
(:func:`grainclass.readers.expand_paths`) refuses one that is not complete.

A worker that dies while it writes a part leaves its temporary file (``.part-00003.parquet.*.tmp``,
:mod:`grainclass.atomic`), which no process of its own is left to remove: the run removes such
files once its tasks are over (:meth:`DatasetFolder.remove_temporaries`).
"""

from __future__ import annotations

import contextlib
import json
import os
import time
from dataclasses import dataclass
from pathlib import Path

from grainclass.errors import InputError, OutputError

DATASET_FILE = "_dataset.json"  # "_": pyarrow, pandas and Dask skip it when they read the folder
PART_METADATA = "grainclass.part"  # key of a part file's identity in its Parquet metadata


def part_name(index: int) -> str:
    """``part-00003.parquet``: the file of part ``index`` (0-based)."""
    return f"part-{index:05d}.parquet"


def _is_part_temporary(name: str) -> bool:
    return name.startswith(".part-") and name.endswith(".tmp")


def check_output_folder(directory: str) -> None:
    """Refuse a folder output that cannot be one: ``-`` (standard output), an empty name, or a
    path that names something other than a folder.

    Raises
    ------
    OutputError
    """
    if directory in ("", "-"):
        raise OutputError("a data set in parts is written into a folder, not to standard output")
    bare = directory.rstrip("/" + os.sep) or directory  # "file/" exists for no system call
    if os.path.lexists(bare) and not os.path.isdir(bare):
        raise OutputError(f"{directory}: is not a folder")


@dataclass(frozen=True)
class PartsProgress:
    """Parts done, grains in them, grains per second and time left, for a progress line."""

    done: int
    total: int
    grains: int
    rate: float
    seconds_left: float | None


class DatasetFolder:
    """The folder of a data set in parts being written: its ``_dataset.json`` and part files.

    Parameters
    ----------
    directory : str
        The folder; made if it does not exist.
    identity : dict
        What the data set is (JSON values): the command, its inputs and options. A folder that
        holds another data set, or Parquet files of none, is refused.
    parts : int
        How many parts the data set has.

    Raises
    ------
    OutputError
        For a folder that cannot be made or written, or that holds something else.
    """

    def __init__(self, directory: str, identity: dict, parts: int) -> None:
        check_output_folder(directory)
        # Absolute: the workers write the parts, and on another machine from another folder.
        self.directory = Path(os.path.abspath(directory))
        self.identity = json.loads(json.dumps(identity))  # as read back: lists, not tuples
        self.parts = parts
        try:
            self.directory.mkdir(parents=True, exist_ok=True)
            names = sorted(os.listdir(self.directory))
        except OSError as exc:
            raise OutputError(f"{directory}: {exc.strerror or exc}") from None
        held = read_dataset_file(self.directory)
        if held is not None and held.get("identity") != self.identity:
            raise OutputError(
                f"{directory}: holds another data set ({describe(held.get('identity'))}): write "
                "elsewhere, or remove it"
            )
        if held is None:
            strangers = [n for n in names if n.lower().endswith(".parquet")]
            if strangers:
                raise OutputError(
                    f"{directory}: holds {strangers[0]}, which belongs to no data set written "
                    "in parts: write elsewhere"
                )
        self.records: dict[str, dict] = {}
        if held is not None:
            for name, record in held.get("parts", {}).items():
                if self._whole(name, record):
                    self.records[name] = record
        self._save(complete=False)

    def _whole(self, name: str, record: dict) -> bool:
        try:
            return (self.directory / name).stat().st_size == record.get("bytes")
        except OSError:
            return False

    def done(self, index: int, identity: dict) -> dict | None:
        """The record of part ``index`` if an earlier run wrote it for ``identity``, else None."""
        record = self.records.get(part_name(index))
        if record is None or record.get("identity") != json.loads(json.dumps(identity)):
            return None
        return record

    def path(self, index: int) -> str:
        return str(self.directory / part_name(index))

    def add(self, index: int, record: dict) -> None:
        """Part ``index`` is done: ``record`` (JSON values; its ``identity``) is kept, with the
        size of its file."""
        name = part_name(index)
        try:
            size = (self.directory / name).stat().st_size
        except OSError as exc:
            raise OutputError(f"{self.directory / name}: {exc.strerror or exc}") from None
        self.records[name] = {**json.loads(json.dumps(record)), "bytes": size}
        self._save(complete=False)

    def finish(self, about: dict) -> None:
        """Every part is in: ``_dataset.json`` says so, with ``about`` (what the run found)."""
        self._save(complete=len(self.records) == self.parts, about=about)

    def _save(self, complete: bool, about: dict | None = None) -> None:
        from grainclass import __version__
        from grainclass.atomic import atomic_output

        content = {
            "grainclass": __version__,
            "identity": self.identity,
            "parts_total": self.parts,
            "complete": complete,
            **(about or {}),
            "written": time.strftime("%Y-%m-%dT%H:%M:%S%z"),
            "parts": dict(sorted(self.records.items())),
        }
        with atomic_output(str(self.directory / DATASET_FILE)) as sink:
            sink.write((json.dumps(content, indent=1) + "\n").encode())

    def remove_temporaries(self) -> None:
        """Remove the temporary part files that workers which died left behind."""
        remove_part_temporaries(str(self.directory))


def remove_part_temporaries(directory: str) -> None:
    """Remove the temporary files of parts in ``directory``: to be called when no task of the
    run that writes it is running any more (its workers died, or were stopped with it)."""
    with contextlib.suppress(OSError):
        for name in os.listdir(directory):
            if _is_part_temporary(name):
                with contextlib.suppress(OSError):
                    os.unlink(os.path.join(directory, name))


def read_dataset_file(directory: str | os.PathLike) -> dict | None:
    """The content of a folder's ``_dataset.json``, or None where it has none (or one that is
    not a JSON object)."""
    try:
        content = json.loads((Path(directory) / DATASET_FILE).read_text())
    except (OSError, ValueError):
        return None
    return content if isinstance(content, dict) else None


def require_complete(directory: str) -> None:
    """Refuse a data-set folder that a run has not finished writing (its ``_dataset.json`` says
    so, or a part it lists is gone): read, it would give the numbers of some of its parts.

    Raises
    ------
    InputError
    """
    held = read_dataset_file(directory)
    if held is None:
        return
    listed = held.get("parts", {})
    total = held.get("parts_total", len(listed))
    if not held.get("complete"):
        raise InputError(
            directory,
            f"an unfinished data set ({len(listed)} of {total} parts written): run the command "
            f"that writes it again to finish it ({describe(held.get('identity'))})",
        )
    missing = [name for name in sorted(listed) if not (Path(directory) / name).is_file()]
    if missing:
        raise InputError(directory, f"{missing[0]}, a part of this data set, is missing")


def describe(identity: object) -> str:
    """A data set's identity in a few words: ``grainclass voronoi 1000 --seed 2, 6 parts``."""
    if not isinstance(identity, dict):
        return "of unknown make"
    words = [f"grainclass {identity.get('command', '?')}"]
    for key, value in identity.items():
        if key in ("command", "parts") or isinstance(value, dict | list):
            continue
        words.append(f"{key} {value}")
    parts = identity.get("parts")
    return ", ".join(words) + (f"; {parts} parts" if parts is not None else "")
