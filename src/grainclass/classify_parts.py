"""Classification in parts, on Dask: every input (a file, or a folder of Surface Evolver grain
files such as one time step) classified by one task into one part of a data set
(:mod:`grainclass.parts`), in input order.

A part is kept when it is done. Its identity is its input as it was read (its real path, and
the size and time of change of each of its files) and the options that shape the rows, so a
rerun of the same command skips every part whose input has not changed since and redoes the
rest: those a stop, a crash or a lost worker left undone, and those whose input changed.
"""

from __future__ import annotations

import dataclasses
import hashlib
import os
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from grainclass.errors import InputError, OptionError, OutputError
from grainclass.options import ReadOptions
from grainclass.parts import PART_METADATA, DatasetFolder, PartsProgress

if TYPE_CHECKING:
    from distributed import Client


@dataclass(frozen=True)
class ClassifiedPart:
    """What the task of part ``index`` wrote: rows, their count by status, the attribute
    columns not written (:class:`grainclass.datasets.Written`), its seconds."""

    index: int
    rows: int
    statuses: dict[str, int]
    dropped: list[str]
    seconds: float


@dataclass
class ClassifyPartsResult:
    """What :func:`classify_in_parts` did: the parts' rows by status (those kept from an
    earlier run included), the parts computed now and kept, and the parts that failed."""

    parts: int
    rows: int = 0
    statuses: dict[str, int] = field(default_factory=dict)
    dropped: set[str] = field(default_factory=set)
    computed: int = 0
    skipped: int = 0
    failures: list[str] = field(default_factory=list)
    seconds: float = 0.0

    @property
    def ok(self) -> bool:
        return not self.failures


def _rows_options(options: ReadOptions) -> dict:
    """The reading options that shape the rows (not the batch size, not the threads)."""
    return {
        "input_format": options.input_format,
        "triple_edges": list(options.triple_edges),
        "types": options.types,
        "belt_length": options.belt_length,
    }


def input_fingerprint(path: str) -> str:
    """What changes when an input changes: a digest of the size and time of change of the file,
    or of each file a folder stands for.

    Raises
    ------
    InputError
        For an input that is not there, or not a file or folder.
    """
    from grainclass.readers import expand_paths

    if not os.path.isfile(path) and not os.path.isdir(path):
        why = "no such file or folder" if not os.path.lexists(path) else "not a file or folder"
        raise InputError(path, f"{why}: a part is classified from a file or a folder")
    digest = hashlib.sha256()
    for name in expand_paths([path]):
        info = os.stat(name)
        digest.update(f"{name}\0{info.st_size}\0{info.st_mtime_ns}\n".encode())
    return digest.hexdigest()[:32]


def check_inputs(inputs: Sequence[str], directory: str) -> list[str]:
    """Refuse inputs that cannot be parts, before any task starts: none, standard input, one
    that is not a file or folder, or one that is the output folder. Their fingerprints
    (:func:`input_fingerprint`).

    Raises
    ------
    InputError, OptionError, OutputError
    """
    if not inputs:
        raise OptionError("inputs", "give the inputs to classify")
    if "-" in inputs:
        raise OptionError("inputs", "standard input cannot be classified in parts: give files")
    fingerprints = [input_fingerprint(path) for path in inputs]
    real = {os.path.realpath(path) for path in inputs}
    if os.path.realpath(directory.rstrip("/" + os.sep) or directory) in real:
        raise OutputError(f"{directory}: is also an input; write elsewhere")
    return fingerprints


def classify_in_parts(
    inputs: Sequence[str],
    directory: str,
    client: Client,
    options: ReadOptions | None = None,
    report: Callable[[PartsProgress], None] | None = None,
) -> ClassifyPartsResult:
    """Classify each input into a part of the data set in ``directory`` (``part-00000.parquet``
    for the first input, ...), each a task on ``client``; parts an earlier run of the same
    inputs finished, whose inputs have not changed since, are kept.

    Parameters
    ----------
    inputs : sequence of str
        Files or folders (a folder: its ``*.fe`` files, one time step), one part each; not
        standard input.
    directory : str
        The data set's folder. The workers must see it, and the inputs, at those paths.
    client : distributed.Client
        Where the tasks run.
    options : ReadOptions
        How the inputs are read (its ``jobs`` is not used: each task has one thread).
    report : callable, optional
        Called with a :class:`~grainclass.parts.PartsProgress` as parts finish.

    Raises
    ------
    InputError
        For an input that is not a file or folder.
    OptionError
        For standard input, or no inputs.
    OutputError
        For a folder that is one of the inputs, or holds something else.
    """
    from grainclass.cluster import Tasks, task_failure

    start = time.perf_counter()
    options = options if options is not None else ReadOptions()
    fingerprints = check_inputs(inputs, directory)
    real = [os.path.realpath(path) for path in inputs]
    identity = {"command": "classify", "inputs": real, "options": _rows_options(options)}
    folder = DatasetFolder(directory, identity, len(inputs))
    result = ClassifyPartsResult(len(inputs))
    tasks = Tasks(client, "classify")
    identities = [
        {"part": k, "input": real[k], "files": fingerprints[k], "options": identity["options"]}
        for k in range(len(inputs))
    ]
    names = {f"part-{k:05d}": k for k in range(len(inputs))}
    for k, path in enumerate(inputs):
        found = folder.done(k, identities[k])
        if found is not None:
            _count(result, found)
            result.skipped += 1
            continue
        part = (k, path, options, folder.path(k), identities[k])
        tasks.submit(f"part-{k:05d}", classification_part, *part, priority=-k)

    def progress() -> None:
        if report is None:
            return
        done = result.computed + result.skipped
        elapsed = max(time.perf_counter() - start, 1e-9)
        rate = (result.rows - skipped_rows) / elapsed
        left = (len(inputs) - done) * elapsed / result.computed if result.computed else None
        report(PartsProgress(done, len(inputs), result.rows, rate, left))

    skipped_rows = result.rows
    for name, outcome in tasks.finished(progress):
        if isinstance(outcome, ClassifiedPart):
            record = {"identity": identities[outcome.index], **dataclasses.asdict(outcome)}
            folder.add(outcome.index, record)
            _count(result, record)
            result.computed += 1
        else:
            result.failures.append(task_failure(f"{name} ({inputs[names[name]]})", outcome))
    progress()
    folder.remove_temporaries()
    result.seconds = time.perf_counter() - start
    folder.finish(
        {
            "rows": result.rows,
            "statuses": dict(sorted(result.statuses.items())),
            "failures": result.failures,
        }
    )
    return result


def _count(result: ClassifyPartsResult, record: dict) -> None:
    result.rows += record["rows"]
    for status, count in record["statuses"].items():
        result.statuses[status] = result.statuses.get(status, 0) + count
    result.dropped.update(record["dropped"])


def classification_part(
    index: int, path: str, options: ReadOptions, output: str, identity: dict
) -> ClassifiedPart:
    """Classify one input into one part file (runs on a Dask worker)."""
    import json

    from grainclass.datasets import write_grains

    start = time.perf_counter()
    written = write_grains(
        [path],
        output,
        dataclasses.replace(options, jobs=1),  # parallel over parts: one thread per task
        metadata={PART_METADATA: json.dumps(identity)},
    )
    return ClassifiedPart(
        index,
        written.rows,
        written.statuses,
        sorted(written.dropped),
        time.perf_counter() - start,
    )
