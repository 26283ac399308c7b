"""`grainclass census`: parts on Dask add up to the paper's tables and to plantri's own counts.

Expected values are the paper's tables (transcribed in scripts/paper_tables.py), plantri's counts
and the single-stream census of ``summarize``; fake plantri programs (shell scripts around the
real one) make parts slow, lie about counts or fail, so that the checks are seen to fail.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pandas as pd
import pytest

from conftest import ctrl_c_at_a_terminal, has_children
from grainclass.census import (
    CHECKS,
    CensusProgress,
    Part,
    PartResult,
    ProgressTracker,
    run_census,
)
from grainclass.cli.progress import PartsPrinter
from grainclass.cluster import dask_client
from grainclass.options import ReadOptions
from grainclass.pipeline import tallies
from grainclass.summary import summarize
from paper_tables import CLASS_COLUMNS, SPLIT, TABLE_II


@pytest.fixture(scope="module")
def client():
    with dask_client(workers=2) as dask:
        yield dask


def _fake_plantri(directory: Path, name: str, plantri: str, body: str) -> str:
    """A shell script that runs ``body`` and otherwise hands its arguments to the real plantri."""
    path = directory / name
    path.write_text(f'#!/bin/sh\n{body}\nexec "{plantri}" "$@"\n')
    path.chmod(0o755)
    return str(path)


def _classes_row(summary, n: int) -> tuple[int, ...]:
    row = summary.classes[summary.classes["n"] == str(n)].iloc[0]
    return tuple(int(row[c]) for c in CLASS_COLUMNS)


def _split(summary, n: int) -> dict[int, int]:
    row = summary.split[summary.split["n"] == n].iloc[0]
    return {int(k): int(v) for k, v in row.items() if k != "n" and v}


def _census(*args: str, **kwargs) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "grainclass", "census", *args],
        capture_output=True,
        text=True,
        check=False,
        **kwargs,
    )


def test_parts_add_up_to_table_ii_and_the_single_stream(client, tmp_path, plantri_output):
    result = run_census(range(4, 13), 3, tmp_path, client)
    assert result.ok
    assert (result.computed, result.skipped) == (27, 0)
    for n in range(4, 13):
        assert _classes_row(result.summary, n) == TABLE_II[n]
        if n >= 6:
            assert _split(result.summary, n) == SPLIT[n]
    # Three checks per n, all passed, against plantri's counts (Table I for -c4 and -m4).
    assert len(result.checks) == 3 * 9
    assert all(check.ok for check in result.checks)
    flag_checks = {c.n: c.plantri for c in result.checks if "-c4" in c.what}
    assert flag_checks[12] == 87
    assert flag_checks[4] == 0
    # The same tables as one stream of each n through summarize.
    paths = [str(plantri_output(n)) for n in range(4, 13)]
    single = summarize(tallies(paths, ReadOptions(types=False)), range(4, 13))
    pd.testing.assert_frame_equal(result.summary.classes, single.classes)
    pd.testing.assert_frame_equal(result.summary.split, single.split)
    pd.testing.assert_frame_equal(result.summary.round, single.round)
    # What was written: the tables in both formats, one checkpoint per part, provenance.
    written = pd.read_csv(tmp_path / "classes.csv", dtype={"n": str})
    pd.testing.assert_frame_equal(written, result.summary.classes)
    assert pd.read_parquet(tmp_path / "split.parquet").equals(result.summary.split)
    assert len(list((tmp_path / "parts").glob("*.parquet"))) == 27
    provenance = (tmp_path / "provenance.json").read_text()
    assert '"parts": 3' in provenance
    assert "n12-part0002of0003" in provenance
    assert '"cross_checks_passed": true' in provenance


def test_rerun_skips_finished_parts_and_redoes_a_missing_one(client, tmp_path):
    first = run_census([10, 11], 4, tmp_path, client)
    assert first.ok
    assert first.computed == 8
    files = sorted((tmp_path / "parts").glob("*.parquet"))
    before = {f.name: (f.stat().st_ino, f.stat().st_mtime_ns) for f in files}
    files[3].unlink()  # as if the run had stopped before this part finished

    second = run_census([10, 11], 4, tmp_path, client)
    assert (second.computed, second.skipped) == (1, 7)
    for f in sorted((tmp_path / "parts").glob("*.parquet")):
        if f.name != files[3].name:
            assert (f.stat().st_ino, f.stat().st_mtime_ns) == before[f.name]
    pd.testing.assert_frame_equal(second.summary.classes, first.summary.classes)
    assert _classes_row(second.summary, 11) == TABLE_II[11]


def test_a_lost_worker_costs_only_its_part(tmp_path, plantri):
    # Every part takes at least half a second, so that a worker is killed while it holds one.
    slow = _fake_plantri(tmp_path, "slow-plantri", plantri, "sleep 0.5")
    killed = []
    with dask_client(workers=2) as dask:

        def kill_a_busy_worker(progress):
            if killed:
                return
            busy = [address for address, keys in dask.processing().items() if keys]
            pid = dask.run(os.getpid, workers=busy[:1])[busy[0]]
            os.kill(pid, signal.SIGKILL)
            killed.append(pid)

        result = run_census(
            [13], 12, tmp_path / "census", dask, plantri=slow, report=kill_a_busy_worker
        )
        pids_after = set(dask.run(os.getpid).values())
    assert killed
    assert killed[0] not in pids_after
    assert result.ok
    assert result.computed == 12
    assert _classes_row(result.summary, 13) == TABLE_II[13]


def test_interrupted_census_resumes_where_it_stopped(tmp_path, plantri):
    slow = _fake_plantri(tmp_path, "slow-plantri", plantri, 'case "$*" in */8) sleep 0.5;; esac')
    out = tmp_path / "census"
    args = ["12", "--parts", "8", "--workers", "1", "-o", str(out), "--plantri", slow, "-q"]
    # Python's Ctrl-C handler set explicitly: a test run in the background inherits SIGINT
    # ignored, and Python then leaves it so.
    start = "import signal; signal.signal(signal.SIGINT, signal.default_int_handler); "
    start += "from grainclass.cli import main; main()"
    run = subprocess.Popen(
        [sys.executable, "-c", start, "census", *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
    )
    deadline = time.monotonic() + 60
    while not list(out.glob("parts/*.parquet")) and time.monotonic() < deadline:
        time.sleep(0.05)
    run.send_signal(signal.SIGINT)
    _, stderr = run.communicate(timeout=60)
    assert run.returncode == 130, stderr
    finished = {f.name: f.stat().st_mtime_ns for f in out.glob("parts/*.parquet")}
    assert 1 <= len(finished) < 8
    assert not [f for f in out.rglob("*") if f.name.endswith(".tmp")]
    assert not (out / "classes.csv").exists()

    again = _census(*args[:-1])
    assert again.returncode == 0, again.stderr
    assert f"{8 - len(finished)} computed now, {len(finished)} from earlier runs" in again.stderr
    for name, mtime in finished.items():
        assert (out / "parts" / name).stat().st_mtime_ns == mtime
    quiet = _census(*args)
    assert quiet.returncode == 0, quiet.stderr
    assert quiet.stderr == ""  # -q: the tables and cross-checks on stdout, nothing else
    assert "n=12" in quiet.stdout
    row = pd.read_csv(out / "classes.csv", dtype={"n": str}).set_index("n").loc["12"]
    assert tuple(int(row[c]) for c in CLASS_COLUMNS) == TABLE_II[12]


@pytest.mark.parametrize("moment", ["workers starting", "parts running"])
def test_ctrl_c_at_a_terminal_ends_the_census_and_its_workers_quietly(tmp_path, plantri, moment):
    """Ctrl-C reaches the Dask workers too, starting up or each at its part: they end quietly
    (each printed a page of traceback), the census exits 130 and its plantri runs end with it."""
    slow = _fake_plantri(tmp_path, "slow-plantri", plantri, 'case "$*" in *7/8*) sleep 30;; esac')
    out = tmp_path / "census"
    args = ["12", "--parts", "8", "--workers", "2", "-o", str(out), "--plantri", slow]
    when = {
        "workers starting": has_children,
        "parts running": lambda pid: len(list(out.glob("parts/*.parquet"))) >= 2,
    }[moment]
    code, err = ctrl_c_at_a_terminal("census", *args, when=when)
    assert code == 130, err
    assert "Traceback" not in err
    assert "grainclass: interrupted" in err
    assert not [f for f in out.rglob("*") if f.name.endswith(".tmp")]


def test_a_cross_check_that_fails_exits_1(tmp_path, plantri):
    # This plantri miscounts the 4-connected triangulations.
    lying = _fake_plantri(
        tmp_path,
        "lying-plantri",
        plantri,
        'case "$*" in *-c4*) echo "999 triangulations generated" >&2; exit 0;; esac',
    )
    done = _census(
        "8",
        "9",
        "--parts",
        "2",
        "--workers",
        "1",
        "-o",
        str(tmp_path / "c"),
        "--plantri",
        lying,
        "-q",
    )
    assert done.returncode == 1
    assert "n=8   flag = plantri -u -c4                   2          999  MISMATCH" in done.stdout
    assert "n=9   flag + sc = plantri -u -m4              5            5  ok" in done.stdout
    assert "disagrees with plantri" in done.stderr
    assert not json.loads((tmp_path / "c" / "provenance.json").read_text())["cross_checks_passed"]
    # The wrong count is not kept: the same census with a plantri that counts right passes.
    again = _census("8", "9", "--parts", "2", "--workers", "1", "-o", str(tmp_path / "c"), "-q")
    assert again.returncode == 0, again.stderr
    assert "n=8   flag = plantri -u -c4                   2            2  ok" in again.stdout
    provenance = json.loads((tmp_path / "c" / "provenance.json").read_text())
    assert provenance["cross_checks_passed"]


def test_a_failed_part_is_reported_and_retried_on_the_next_run(tmp_path, plantri):
    failing = _fake_plantri(
        tmp_path,
        "failing-plantri",
        plantri,
        'case "$*" in *" 1/3"*) echo "out of luck" >&2; exit 3;; esac',
    )
    out = tmp_path / "c"
    args = ["11", "--parts", "3", "--workers", "1", "-o", str(out), "-q"]
    done = _census(*args, "--plantri", failing)
    assert done.returncode == 1
    assert "part n11-part0001of0003 (plantri -h 11 1/3)" in done.stderr
    assert "failed (exit 3): out of luck" in done.stderr
    assert sorted(f.name for f in out.glob("parts/*")) == [
        "n11-part0000of0003.parquet",
        "n11-part0002of0003.parquet",
    ]
    again = _census(*args[:-1])
    assert again.returncode == 0, again.stderr
    assert "1 computed now, 2 from earlier runs" in again.stderr
    assert (out / "provenance.json").exists()
    # A later run that fails leaves the tables, but not the mark that they are its own.
    (out / "parts" / "n11-part0001of0003.parquet").unlink()
    assert _census(*args, "--plantri", failing).returncode == 1
    assert (out / "classes.csv").exists()
    assert not (out / "provenance.json").exists()


def test_a_part_with_fewer_triangulations_than_plantri_reports_fails(tmp_path, plantri):
    # The real plantri's output of the part, then a report that claims one more.
    short = tmp_path / "short-plantri"
    short.write_text(
        f'#!/bin/sh\n"{plantri}" "$@" 2>/dev/null\n'
        'case "$*" in *-u*) ;; *) echo "1250 triangulations written to stdout" >&2;; esac\n'
    )
    short.chmod(0o755)
    done = _census(
        "11",
        "--parts",
        "1",
        "--workers",
        "1",
        "-o",
        str(tmp_path / "c"),
        "--plantri",
        str(short),
        "-q",
    )
    assert done.returncode == 1
    assert "plantri reported 1250 triangulations, 1249 were read" in done.stderr


def test_vertex_ranges_and_bad_arguments(tmp_path):
    assert Part(16, 3, 8).plantri_args() == ["-h", "16", "3/8"]
    assert Part(9, 0, 1).plantri_args() == ["-h", "9"]
    assert set(CHECKS) == {"all", "flag", "min_degree_4"}
    bad = _census("3..5", "-o", str(tmp_path / "c"))
    assert bad.returncode == 2
    assert "numbers of vertices go from 4 to 64" in bad.stderr
    bad = _census("a..5", "-o", str(tmp_path / "c"))
    assert bad.returncode == 2
    assert "expected N or A..B, got 'a..5'" in bad.stderr
    done = _census("4..6", "9", "--parts", "1", "--workers", "1", "-o", str(tmp_path / "c"), "-q")
    assert done.returncode == 0, done.stderr
    written = pd.read_csv(tmp_path / "c" / "classes.csv", dtype={"n": str})
    assert list(written["n"]) == ["4", "5", "6", "9", "total"]


def _result(n: int, index: int, parts: int, grains: int) -> PartResult:
    return PartResult(Part(n, index, parts), pd.DataFrame(), grains, grains, 1.0)


def test_time_left_comes_from_plantri_counts_then_parts_then_growth():
    results: dict = {}
    counts: dict = {}
    tracker = ProgressTracker([16, 17], 4, results, counts, time.perf_counter())
    assert tracker.expected() is None  # nothing known yet: the time left is shown as '?'
    results[Part(17, 0, 4)] = _result(17, 0, 4, 30_000_000)
    # One part of n = 17 known: 4 such parts, and n = 16 at 1/7.5 of that.
    assert tracker.expected() == pytest.approx(120_000_000 * (1 + 1 / 7.5))
    counts[16, "all"] = 17_490_241
    assert tracker.expected() == pytest.approx(120_000_000 + 17_490_241)
    tracker.running((0.0, {"part": "n17-part0001of0004", "grains": 5_000_000}))
    progress = tracker.progress(8)
    assert (progress.done, progress.total, progress.grains) == (1, 8, 35_000_000)
    assert progress.seconds_left == pytest.approx(
        (137_490_241 - 35_000_000) / progress.rate, rel=1e-3
    )
    tracker.finished(Part(17, 1, 4))
    assert tracker.reading() == 0


def test_progress_lines_in_a_log_are_spaced_out(capsys):
    printer = PartsPrinter(every=3600)
    for done in (1, 2, 3, 4, 4):
        printer(CensusProgress(done, 4, 1000 * done, 2500.0, 60.0 * (4 - done)))
    lines = capsys.readouterr().err.splitlines()
    assert lines == [
        "census: 1/4 parts, 1,000 triangulations (2,500/s), about 0:03:00 left",
        "census: 4/4 parts, 4,000 triangulations (2,500/s), about 0:00:00 left",
    ]


def test_the_same_census_runs_on_an_existing_cluster(client, tmp_path):
    done = _census(
        "9",
        "10",
        "--parts",
        "2",
        "--scheduler",
        client.scheduler.address,
        "-o",
        str(tmp_path),
        "-q",
    )
    assert done.returncode == 0, done.stderr
    written = pd.read_csv(tmp_path / "classes.csv", dtype={"n": str}).set_index("n")
    for n in (9, 10):
        assert tuple(int(written.loc[str(n), c]) for c in CLASS_COLUMNS) == TABLE_II[n]


def test_a_part_counted_by_another_version_is_counted_again(client, tmp_path):
    import pyarrow.parquet as pq

    first = run_census([9], 2, tmp_path, client)
    path = tmp_path / "parts" / "n09-part0001of0002.parquet"
    table = pq.read_table(path)
    about = json.loads(table.schema.metadata[b"grainclass.census"])
    about["grainclass"] = "0.0.1"
    pq.write_table(table.replace_schema_metadata({b"grainclass.census": json.dumps(about)}), path)
    again = run_census([9], 2, tmp_path, client)
    assert (again.computed, again.skipped) == (1, 1)
    pd.testing.assert_frame_equal(again.summary.classes, first.summary.classes)


def test_an_unreadable_checkpoint_is_computed_again(client, tmp_path):
    first = run_census([9], 2, tmp_path, client)
    (tmp_path / "parts" / "n09-part0001of0002.parquet").write_bytes(b"not parquet")
    (tmp_path / "checks" / "n09-flag.json").write_text("{")
    again = run_census([9], 2, tmp_path, client)
    assert (again.computed, again.skipped) == (1, 1)
    assert again.ok
    pd.testing.assert_frame_equal(again.summary.classes, first.summary.classes)
    assert _classes_row(again.summary, 9) == TABLE_II[9]
