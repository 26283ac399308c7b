"""The census: every triangulation of the sphere with n vertices, classified in parts on Dask.

plantri enumerates the triangulations with n vertices; its ``res/mod`` arguments split one
enumeration into disjoint parts. Each part is one Dask task that streams plantri's output
through the counting path of ``summarize`` (planar_code bytes, no per-grain rows) into a
partial tally. A finished part is written to ``DIR/parts`` at once (whole or not at all), so a
rerun skips it: an interrupted census resumes, and a lost worker costs only the part it held,
which Dask runs again elsewhere. plantri's own counts are the cross-checks: all
triangulations (``-u``), the 4-connected ones (``-c4``, the census's flag class) and those of
minimum degree 4 (``-m4``: flag plus sc, the fundamental ones).
"""

from __future__ import annotations

import json
import os
import threading
import time
import uuid
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from grainclass import interrupts
from grainclass.errors import CensusError, OutputError
from grainclass.options import DEFAULT_CHUNK_SIZE
from grainclass.plantri import CHECKS, plantri_count, plantri_version, run_plantri
from grainclass.vocabulary import TABLES

if TYPE_CHECKING:
    import pandas as pd
    from distributed import Client

    from grainclass.summary import Summary

PROGRESS_TOPIC = "grainclass-census-progress"


@dataclass(frozen=True, order=True)
class Part:
    """Part ``index`` of ``parts`` of the triangulations with ``n`` vertices."""

    n: int
    index: int
    parts: int

    @property
    def name(self) -> str:
        return f"n{self.n:02d}-part{self.index:04d}of{self.parts:04d}"

    def plantri_args(self) -> list[str]:
        """plantri's arguments: no header, n, and ``res/mod`` when there is more than one part."""
        return ["-h", str(self.n)] + ([f"{self.index}/{self.parts}"] if self.parts > 1 else [])


@dataclass(frozen=True)
class PartResult:
    """A part's tally (``summary.tally`` groups and sums) and what plantri said of it."""

    part: Part
    counts: pd.DataFrame
    grains: int
    plantri_count: int
    seconds: float


def count_part(part: Part, chunk_size: int, plantri: str | None = None) -> PartResult:
    """Enumerate one part with plantri and tally it (runs on a Dask worker).

    Raises
    ------
    PlantriError
        When plantri fails, or reports no number of triangulations.
    CensusError
        When plantri reports another number of triangulations than were read.
    """
    from grainclass.parallel import set_jobs
    from grainclass.pipeline import prefetch
    from grainclass.readers.planar_code import read_planar_code
    from grainclass.summary import merge_tallies, tally_batch

    set_jobs(1)  # parallel over parts: one thread per worker process
    start = time.perf_counter()
    frames: list[pd.DataFrame] = []
    grains = 0
    publish, published = _progress_publisher(), time.monotonic()
    with run_plantri(part.plantri_args(), plantri) as run:
        # Read in a thread of its own: read in turn with the counting, plantri would wait on
        # a full pipe while a chunk is counted (the task would take plantri's time plus ours).
        for records in prefetch(
            read_planar_code(run.stdout, f"plantri {part.name}", chunk_size, raw=True)
        ):
            tallied = tally_batch(records)
            grains += len(tallied)
            frames.append(tallied.counts)
            if len(frames) >= 64:  # keep a long part's tallies small
                frames = [merge_tallies(frames)]
            if publish is not None and time.monotonic() - published >= 1.0:
                publish({"part": part.name, "grains": grains})
                published = time.monotonic()
    reported = run.written
    if reported != grains:
        raise CensusError(
            f"{' '.join(run.command)}: plantri reported {reported} triangulations, "
            f"{grains} were read"
        )
    return PartResult(part, merge_tallies(frames), grains, reported, time.perf_counter() - start)


def _progress_publisher() -> Callable[[dict], None] | None:
    """On a Dask worker, a function that sends a progress event to the client; else None."""
    try:
        from distributed import get_worker

        worker = get_worker()
    except (ImportError, ValueError):
        return None
    return lambda message: worker.log_event(PROGRESS_TOPIC, message)


@dataclass
class Checkpoints:
    """Finished parts and plantri counts kept in a census directory."""

    directory: Path

    def __post_init__(self) -> None:
        try:
            for sub in ("parts", "checks"):
                (self.directory / sub).mkdir(parents=True, exist_ok=True)
            # Tables left by an earlier run are not this run's until it writes them again.
            self.provenance_path.unlink(missing_ok=True)
        except OSError as exc:
            raise OutputError(f"{self.directory}: {exc.strerror or exc}") from None

    def part_path(self, part: Part) -> Path:
        return self.directory / "parts" / f"{part.name}.parquet"

    def check_path(self, n: int, check: str) -> Path:
        return self.directory / "checks" / f"n{n:02d}-{check}.json"

    def save_part(self, result: PartResult) -> None:
        import pyarrow as pa
        import pyarrow.parquet as pq

        from grainclass import __version__
        from grainclass.atomic import atomic_output

        table = pa.Table.from_pandas(result.counts, preserve_index=False)
        about = {
            "grainclass": __version__,
            "n": result.part.n,
            "index": result.part.index,
            "parts": result.part.parts,
            "grains": result.grains,
            "plantri_count": result.plantri_count,
            "seconds": result.seconds,
        }
        metadata = {**(table.schema.metadata or {}), b"grainclass.census": json.dumps(about)}
        with atomic_output(str(self.part_path(result.part))) as sink:
            pq.write_table(table.replace_schema_metadata(metadata), sink)

    def load_part(self, part: Part) -> PartResult | None:
        """The part's result if it finished in an earlier run of this version of grainclass,
        else None (also for a file that cannot be read: the part is then computed again and the
        file replaced)."""
        import pyarrow as pa
        import pyarrow.parquet as pq

        from grainclass import __version__

        path = self.part_path(part)
        if not path.exists():
            return None
        try:
            table = pq.read_table(path)
            about = json.loads(table.schema.metadata[b"grainclass.census"])
        except (OSError, pa.ArrowException, KeyError, TypeError, ValueError):
            return None
        if about.get("grainclass") != __version__:  # counted by other code: count again
            return None
        counts = table.replace_schema_metadata(None).to_pandas()
        return PartResult(part, counts, about["grains"], about["plantri_count"], about["seconds"])

    def save_check(self, n: int, check: str, count: int) -> None:
        from grainclass.atomic import atomic_output

        record = {"n": n, "check": check, "plantri": list(CHECKS[check]), "count": count}
        with atomic_output(str(self.check_path(n, check))) as sink:
            sink.write(json.dumps(record).encode())

    def load_check(self, n: int, check: str) -> int | None:
        """plantri's count from an earlier run, else None (also for an unreadable file)."""
        try:
            return int(json.loads(self.check_path(n, check).read_text())["count"])
        except (OSError, KeyError, TypeError, ValueError):
            return None

    def forget_check(self, n: int, check: str) -> None:
        """Drop plantri's count, so that the next run asks plantri again."""
        self.check_path(n, check).unlink(missing_ok=True)

    @property
    def provenance_path(self) -> Path:
        """Written last, when the tables are complete and current: its absence says they are
        not."""
        return self.directory / "provenance.json"


@dataclass(frozen=True)
class CrossCheck:
    """One comparison of the census with plantri's own count (``check``, a key of CHECKS)."""

    n: int
    check: str
    what: str
    census: int
    plantri: int

    @property
    def ok(self) -> bool:
        return self.census == self.plantri


@dataclass
class CensusResult:
    """What :func:`run_census` computed: the tables, the cross-checks, and what failed."""

    summary: Summary | None
    counts: pd.DataFrame | None
    checks: list[CrossCheck]
    failures: list[str]
    parts: list[PartResult]
    computed: int
    skipped: int
    seconds: float
    provenance: dict = field(default_factory=dict)

    @property
    def ok(self) -> bool:
        return not self.failures and all(check.ok for check in self.checks)


@dataclass
class CensusProgress:
    """Parts done, triangulations per second and time left, handed to a report callback."""

    done: int
    total: int
    grains: int
    rate: float
    seconds_left: float | None


class ProgressTracker:
    """What the progress line needs: triangulations read by finished parts and, from the
    workers' events, by running ones; and an estimate of how many the census will read."""

    def __init__(
        self,
        ns: list[int],
        parts: int,
        results: dict[Part, PartResult],
        plantri_counts: dict[tuple[int, str], int],
        start: float,
    ) -> None:
        self.ns, self.parts, self.start = ns, parts, start
        self.results, self.plantri_counts = results, plantri_counts  # updated by run_census
        self.skipped_grains = sum(r.grains for r in results.values())
        self._reading: dict[str, int] = {}  # written from the Dask client's event thread
        self._lock = threading.Lock()

    def running(self, event: tuple[float, dict]) -> None:
        """A worker's event: a running part's triangulations read so far."""
        message = event[1]
        with self._lock:
            self._reading[message["part"]] = message["grains"]

    def finished(self, part: Part) -> None:
        with self._lock:
            self._reading.pop(part.name, None)

    def reading(self) -> int:
        """Triangulations read so far by the running parts."""
        with self._lock:
            return sum(self._reading.values())

    def expected(self) -> float | None:
        """Triangulations in the whole census: plantri's count where known, else the mean part
        so far times the parts, else extrapolated from another n at 7.5 per vertex (their
        ratio for n = 14..18)."""
        per_n: dict[int, float] = {}
        for n in self.ns:
            sizes = [r.grains for p, r in self.results.items() if p.n == n]
            if (n, "all") in self.plantri_counts:
                per_n[n] = self.plantri_counts[n, "all"]
            elif sizes:
                per_n[n] = sum(sizes) / len(sizes) * self.parts
        if not per_n:
            return None
        for n in self.ns:
            if n not in per_n:
                known = min(per_n, key=lambda m: abs(m - n))
                per_n[n] = per_n[known] * 7.5 ** (n - known)
        return sum(per_n.values())

    def progress(self, total_parts: int) -> CensusProgress:
        elapsed = max(time.perf_counter() - self.start, 1e-9)
        done = sum(r.grains for r in self.results.values()) + self.reading()
        this_run = done - self.skipped_grains
        rate = this_run / elapsed
        expected = self.expected()
        left = None
        if expected is not None and rate > 0:
            left = max(expected - done, 0.0) / rate
        return CensusProgress(len(self.results), total_parts, this_run, rate, left)


def census_parts(ns: Iterable[int], parts: int) -> list[Part]:
    """Every part of every n, largest n first (the longest tasks start first)."""
    return [Part(n, index, parts) for n in sorted(set(ns), reverse=True) for index in range(parts)]


def run_census(
    ns: Sequence[int],
    parts: int,
    directory: str | os.PathLike,
    client: Client,
    chunk_size: int = DEFAULT_CHUNK_SIZE,
    plantri: str | None = None,
    report: Callable[[CensusProgress], None] | None = None,
) -> CensusResult:
    """Classify every triangulation with n vertices for each n in ``ns``, ``parts`` Dask tasks per
    n, on ``client``; finished parts in ``directory`` are reused. Writes the tables (Parquet and
    CSV), the summed tally and ``provenance.json`` there when every part and count is in.

    Parameters
    ----------
    ns : sequence of int
        Numbers of vertices (faces of the grains), each at least 4.
    parts : int
        plantri ``res/mod`` parts per n.
    directory : path
        Census directory: ``parts/`` and ``checks/`` hold the checkpoints.
    client : distributed.Client
        Where the tasks run (a local cluster, or one reached by its scheduler's address).
    chunk_size : int
        Triangulations per batch inside a task.
    plantri : str, optional
        The plantri binary as the workers see it (default: found on each worker).
    report : callable, optional
        Called with a :class:`CensusProgress` when tasks finish, and every two seconds.
    """
    from distributed import wait

    start = time.perf_counter()
    store = Checkpoints(Path(directory))
    all_parts = census_parts(ns, parts)
    results: dict[Part, PartResult] = {}
    for part in all_parts:
        found = store.load_part(part)
        if found is not None:
            results[part] = found
    skipped = len(results)
    counts: dict[tuple[int, str], int] = {}
    for n in set(ns):
        for check in CHECKS:
            found_count = store.load_check(n, check)
            if found_count is not None:
                counts[n, check] = found_count

    # Keys of this run only: on a shared scheduler, another census (another directory, another
    # plantri) must not be handed this one's results.
    run = uuid.uuid4().hex[:12]
    futures = {}
    for part in all_parts:
        if part not in results:
            future = client.submit(
                count_part,
                part,
                chunk_size,
                plantri,
                key=f"census-{run}-{part.name}",
                pure=False,
                priority=part.n,
            )
            futures[future] = part
    for n in sorted(set(ns), reverse=True):
        for check in CHECKS:
            if (n, check) not in counts:
                # Before the parts of n: a long -u runs beside them, not alone at the end,
                # and its count sharpens the time left.
                future = client.submit(
                    plantri_count,
                    n,
                    check,
                    plantri,
                    key=f"census-{run}-n{n:02d}-{check}",
                    pure=False,
                    priority=n + 1,
                )
                futures[future] = (n, check)

    failures: list[str] = []
    computed = 0
    tracker = ProgressTracker(sorted(set(ns)), parts, results, counts, start)
    client.subscribe_topic(PROGRESS_TOPIC, tracker.running)
    pending = set(futures)
    while pending:
        try:
            interrupts.checkpoint()
            done, pending = wait(pending, timeout=0.5, return_when="FIRST_COMPLETED")
        except TimeoutError:  # nothing finished: report the running parts' progress
            done = set()
        for future in done:
            what = futures.pop(future)
            try:
                value = future.result()
            except Exception as exc:  # a failed part is reported; the others go on
                failures.append(f"{_task_name(what)}: {exc}")
                if isinstance(what, Part):
                    tracker.finished(what)
                continue
            finally:
                future.release()
            if isinstance(what, Part):
                store.save_part(value)
                results[what] = value
                tracker.finished(what)
                computed += 1
            else:
                store.save_check(*what, value)
                counts[what] = value
        if report is not None:
            report(tracker.progress(len(all_parts)))
    client.unsubscribe_topic(PROGRESS_TOPIC)

    result = CensusResult(
        summary=None,
        counts=None,
        checks=[],
        failures=failures,
        parts=[results[p] for p in sorted(results)],
        computed=computed,
        skipped=skipped,
        seconds=time.perf_counter() - start,
    )
    if failures:
        return result
    _finish(result, ns, parts, counts, store, plantri, client)
    return result


def _task_name(what: Part | tuple[int, str]) -> str:
    if isinstance(what, Part):
        return f"part {what.name} (plantri {' '.join(what.plantri_args())})"
    n, check = what
    return f"plantri {' '.join(CHECKS[check])} {n}"


def cross_checks(
    counts: pd.DataFrame, plantri_counts: dict[tuple[int, str], int]
) -> list[CrossCheck]:
    """The census against plantri, for every n: ok grains against all triangulations, the flag
    class against the 4-connected ones, flag plus sc against those of minimum degree 4."""
    from grainclass import schema
    from grainclass.summary import COUNT

    ok = counts[counts[schema.STATUS] == "ok"]
    checks = []
    for n in sorted({n for n, _ in plantri_counts}):
        of_n = ok[ok[schema.N_FACES] == n]
        by_class = of_n.groupby(schema.CLASS)[COUNT].sum()
        flag, sc = int(by_class.get("flag", 0)), int(by_class.get("sc", 0))
        ours = {"all": int(of_n[COUNT].sum()), "flag": flag, "min_degree_4": flag + sc}
        for check, what in (
            ("all", "ok grains = plantri -u"),
            ("flag", "flag = plantri -u -c4"),
            ("min_degree_4", "flag + sc = plantri -u -m4"),
        ):
            checks.append(CrossCheck(n, check, what, ours[check], plantri_counts[n, check]))
    return checks


def _finish(
    result: CensusResult,
    ns: Sequence[int],
    parts: int,
    plantri_counts: dict[tuple[int, str], int],
    store: Checkpoints,
    plantri: str | None,
    client: Client,
) -> None:
    """Sum the parts, check against plantri, write the tables and the provenance."""
    from grainclass import __version__
    from grainclass.summary import Tally, merge_tallies, summarize

    counts = merge_tallies([r.counts for r in result.parts])
    result.counts = counts
    result.summary = summarize(
        [Tally(counts, sum(r.grains for r in result.parts))], n_values=tuple(sorted(set(ns)))
    )
    result.checks = cross_checks(counts, plantri_counts)
    for check in result.checks:
        if not check.ok:  # a wrong count must not outlive this run: plantri is asked again
            store.forget_check(check.n, check.check)
    result.provenance = {
        "grainclass": __version__,
        "plantri": client.submit(plantri_version, plantri, pure=False).result(),
        "n": sorted(set(ns)),
        "parts": parts,
        "plantri_counts": {
            f"n{n:02d}-{check}": count for (n, check), count in sorted(plantri_counts.items())
        },
        "cross_checks_passed": all(check.ok for check in result.checks),
        "part_seconds": {r.part.name: round(r.seconds, 3) for r in result.parts},
        "part_grains": {r.part.name: r.grains for r in result.parts},
        "written": time.strftime("%Y-%m-%dT%H:%M:%S%z"),
    }
    write_tables(store.directory, result)


def write_tables(directory: Path, result: CensusResult) -> None:
    """The census tables as Parquet and CSV, the summed tally, and ``provenance.json``."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    from grainclass import schema
    from grainclass.atomic import atomic_output
    from grainclass.summary import Q_COUNT, Q_SQUARES, Q_SUM

    frames = {name: result.summary.table(name) for name in TABLES}
    # The summed tally, without the isoperimetric sums (triangulations have no geometry).
    frames["counts"] = result.counts.drop(columns=[Q_COUNT, Q_SUM, Q_SQUARES]).astype(
        {schema.N_FACES: "Int64", schema.ROUND_K: "Int64", schema.SPLIT_K: "Int64"}
    )
    for name, frame in frames.items():
        with atomic_output(str(directory / f"{name}.parquet")) as sink:
            pq.write_table(pa.Table.from_pandas(frame, preserve_index=False), sink)
        with atomic_output(str(directory / f"{name}.csv")) as sink:
            sink.write(frame.to_csv(index=False).encode())
    with atomic_output(str(directory / "provenance.json")) as sink:
        sink.write((json.dumps(result.provenance, indent=2) + "\n").encode())
