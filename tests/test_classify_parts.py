"""`grainclass classify IN... -o DIR/`: one part per input on Dask, each part the rows one
process gives for its input, a rerun that redoes only the parts not done, and the summaries,
types and penalties of the data set those of its parts together.

The truth each test holds to is the classification of the same inputs in this process
(``read_grains``, ``summary_tables``, ``type_counts`` on the inputs themselves).
"""

from __future__ import annotations

import json
import os
import shutil

import dask
import pandas as pd
import pyarrow.parquet as pq
import pytest
from click.testing import CliRunner

from conftest import die_once
from grainclass import read_grains, summary_tables, type_counts
from grainclass.classify_parts import classify_in_parts, input_fingerprint
from grainclass.cli import cli
from grainclass.cluster import dask_client
from grainclass.datasets import penalty_table
from grainclass.errors import InputError
from grainclass.options import ReadOptions
from grainclass.parts import DATASET_FILE, PART_METADATA

EXAMPLES = ["examples/polytopes.txt", "examples/plantri-10.pc", "examples/bad-grains.txt"]


@pytest.fixture(scope="module")
def client():
    with dask_client(workers=2) as dask:
        yield dask


@pytest.fixture
def inputs(tmp_path, plantri_output):
    """Four inputs: the bundled examples and every triangulation with 11 vertices."""
    paths = []
    for example in EXAMPLES:
        paths.append(str(tmp_path / os.path.basename(example)))
        shutil.copy(example, paths[-1])
    paths.append(str(plantri_output(11)))
    return paths


def _invoke(*args: str):
    return CliRunner().invoke(cli, ["classify", *args, "--workers", "2", "-q"])


def test_each_part_is_its_input_classified(tmp_path, inputs):
    out = tmp_path / "out"
    result = _invoke(*inputs, "-o", f"{out}/")
    assert result.exit_code == 0, result.output
    parts = sorted(out.glob("part-*.parquet"))
    assert [p.name for p in parts] == [f"part-{k:05d}.parquet" for k in range(4)]
    for part, path in zip(parts, inputs, strict=True):
        pd.testing.assert_frame_equal(read_grains(str(part)), read_grains(path))
        identity = json.loads(pq.read_schema(part).metadata[PART_METADATA.encode()])
        assert identity["input"] == os.path.realpath(path)
    held = json.loads((out / DATASET_FILE).read_text())
    assert held["complete"]
    assert held["identity"]["inputs"] == [os.path.realpath(p) for p in inputs]
    assert held["rows"] == sum(len(read_grains(p)) for p in inputs)
    # The bad grains of examples/bad-grains.txt are rows, counted in the report.
    assert held["statuses"]["invalid"] == 6
    # The data set reads as its parts in order.
    pd.testing.assert_frame_equal(read_grains(str(out)), read_grains(inputs))


def test_a_rerun_redoes_the_missing_part_and_the_changed_input(client, tmp_path, inputs):
    out = str(tmp_path / "out")
    first = classify_in_parts(inputs, out, client)
    assert (first.computed, first.skipped) == (4, 0)
    mtimes = {p.name: p.stat().st_mtime_ns for p in (tmp_path / "out").glob("part-*")}
    os.unlink(os.path.join(out, "part-00001.parquet"))
    with open(inputs[0], "a") as handle:
        handle.write("extra\t1,2,3;0,3,2;0,1,3;0,2,1\n")  # a tetrahedron more
    second = classify_in_parts(inputs, out, client)
    assert (second.computed, second.skipped) == (2, 2)
    redone = {
        p.name
        for p in (tmp_path / "out").glob("part-*")
        if p.stat().st_mtime_ns != mtimes.get(p.name)
    }
    assert redone == {"part-00000.parquet", "part-00001.parquet"}
    assert second.rows == first.rows + 1
    pd.testing.assert_frame_equal(read_grains(out), read_grains(inputs))


def test_the_tables_of_a_data_set_are_those_of_its_inputs_together(client, tmp_path, inputs):
    out = str(tmp_path / "out")
    assert classify_in_parts(inputs, out, client, ReadOptions(belt_length=6)).ok
    whole = summary_tables(inputs, n_values=[10, 11])
    parted = summary_tables(out, n_values=[10, 11])
    assert parted.headline == whole.headline
    for table in ("classes", "round", "split", "geometry"):
        pd.testing.assert_frame_equal(getattr(parted, table), getattr(whole, table))
    pd.testing.assert_frame_equal(type_counts(out), type_counts(inputs))
    pd.testing.assert_frame_equal(
        penalty_table(out, belt_length=6), penalty_table(inputs, belt_length=6)
    )


def test_a_part_that_fails_is_named_and_the_others_kept(tmp_path, inputs):
    broken = tmp_path / "broken.pc"
    broken.write_bytes(b"\x1f\x8b\x08\x00")  # gzip: refused by the reader
    out = tmp_path / "out"
    result = _invoke(inputs[0], str(broken), inputs[1], "-o", f"{out}/")
    assert result.exit_code == 1
    assert f"part-00001 ({broken})" in result.stderr
    assert "1 part failed; finished parts are kept" in result.stderr
    assert sorted(p.name for p in out.glob("part-*")) == [
        "part-00000.parquet",
        "part-00002.parquet",
    ]
    summarized = CliRunner().invoke(cli, ["summarize", str(out)])
    assert summarized.exit_code == 1
    assert "an unfinished data set (2 of 3 parts written)" in summarized.stderr
    shutil.copy(inputs[3], broken)  # mended: the rerun classifies it alone
    again = CliRunner().invoke(
        cli, ["classify", inputs[0], str(broken), inputs[1], "-o", f"{out}/", "--workers", "2"]
    )
    assert again.exit_code == 0, again.output
    assert "(1 computed now, 2 from earlier runs)" in again.stderr


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["-", "-o", "out/"], "standard input cannot be classified in parts"),
        (["x.txt", "-o", "x.parquet", "--workers", "2"], "give -o DIR/"),
        (["x.txt", "-o", "out/", "-j", "2"], "in parts, --workers"),
    ],
)
def test_usage_errors_of_parts(tmp_path, monkeypatch, args, message):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "x.txt").write_text("a\t1,2,3;0,3,2;0,1,3;0,2,1\n")
    result = CliRunner().invoke(cli, ["classify", *args])
    assert result.exit_code == 2, result.output
    assert message in result.stderr


def test_an_output_folder_that_is_an_input_or_a_file_is_refused(tmp_path):
    (tmp_path / "steps").mkdir()
    (tmp_path / "steps" / "a.fe").write_text("vertices\n")
    result = _invoke(str(tmp_path / "steps"), "-o", f"{tmp_path}/steps/")
    assert result.exit_code == 1
    assert "is also an input" in result.stderr
    missing = _invoke(str(tmp_path / "nothing.txt"), "-o", f"{tmp_path}/out/")
    assert missing.exit_code == 1
    assert "nothing.txt: no such file or folder" in missing.stderr


def test_a_folder_input_changes_when_one_of_its_files_does(tmp_path):
    step = tmp_path / "21000"
    step.mkdir()
    for name in ("21000-1.fe", "21000-2.fe"):
        (step / name).write_text("vertices\n")
    before = input_fingerprint(str(step))
    assert input_fingerprint(str(step)) == before
    (step / "21000-2.fe").write_text("vertices\n1 0 0 0\n")
    assert input_fingerprint(str(step)) != before
    with pytest.raises(InputError, match="no such file or folder"):
        input_fingerprint(str(tmp_path / "gone"))


def test_a_part_whose_workers_all_die_is_named_and_the_rerun_finishes(tmp_path, inputs):
    """With no second try allowed, a worker that dies fails its part (and any other part Dask
    had handed it, which waited its turn there), named; the finished parts are kept, and the
    next run (with the worker's stand-in) classifies the failed parts alone."""
    out = str(tmp_path / "out")
    with (
        dask.config.set({"distributed.scheduler.allowed-failures": 0}),
        dask_client(workers=2) as dask_cluster,
    ):
        dask_cluster.register_plugin(die_once("part-00001", tmp_path / "died"))
        failed = classify_in_parts(inputs, out, dask_cluster)
        assert (tmp_path / "died").exists()
        named = {failure.split(" ")[0] for failure in failed.failures}
        assert "part-00001" in named
        died = f"part-00001 ({inputs[1]}): every worker that ran it died"
        assert any(failure.startswith(died) for failure in failed.failures)
        assert failed.computed == 4 - len(named)
        assert not json.loads((tmp_path / "out" / DATASET_FILE).read_text())["complete"]
        kept = {p.name: p.stat().st_mtime_ns for p in (tmp_path / "out").glob("part-*")}
        assert {f"{name}.parquet" for name in named}.isdisjoint(kept)
        again = classify_in_parts(inputs, out, dask_cluster)
    assert (again.computed, again.skipped, again.failures) == (len(named), len(kept), [])
    for name, mtime in kept.items():
        assert (tmp_path / "out" / name).stat().st_mtime_ns == mtime
    pd.testing.assert_frame_equal(read_grains(out), read_grains(inputs))
