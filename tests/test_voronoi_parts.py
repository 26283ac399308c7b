"""`grainclass voronoi ... -o DIR/`: a tessellation in parts on Dask gives the cells of one
process, row by row.

The truth each test holds to is computed apart from the parts: the same seeds or points
tessellated by one process (``voronoi.poisson_voronoi`` and ``voronoi.tessellate``, which
tests/test_voronoi.py checks against the voro++ program), and the parts' checks are seen to
fail on cells computed with a margin too small.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys

import numpy as np
import pandas as pd
import pytest
from click.testing import CliRunner

from conftest import ctrl_c_at_a_terminal, die_once
from grainclass import voronoi
from grainclass.box import Box
from grainclass.cli import cli
from grainclass.cluster import dask_client
from grainclass.errors import OptionError, OutputError
from grainclass.parts import DATASET_FILE
from grainclass.readers.points import read_points
from grainclass.voronoi_parts import PartJob, _merged, tessellate_in_parts, tessellation_part
from grainclass.voronoi_slabs import Slabs, seed_points

pytest.importorskip("grainclass._voro")

COLUMNS = ["grain_id", "source", "n_faces", "p_vector", "class", "weinberg", "boundary"]


@pytest.fixture(scope="module")
def client():
    with dask_client(workers=2) as dask:
        yield dask


@pytest.fixture(scope="module")
def one_process(tmp_path_factory):
    """The cells of 6,000 seeds (seed 11) as one process writes them."""
    path = tmp_path_factory.mktemp("one") / "pv.parquet"
    voronoi.write_cells(voronoi.poisson_voronoi(6000, 11), str(path))
    return pd.read_parquet(path)


def _same_cells(parts: pd.DataFrame, whole: pd.DataFrame) -> None:
    """Row by row, in order: the same grain ids, faces, types and volumes (to 1e-9)."""
    assert len(parts) == len(whole)
    parts, whole = parts.reset_index(drop=True), whole.reset_index(drop=True)
    pd.testing.assert_frame_equal(parts[COLUMNS], whole[COLUMNS])
    np.testing.assert_allclose(parts["volume"], whole["volume"], rtol=1e-9, atol=0)
    np.testing.assert_allclose(parts["area"], whole["area"], rtol=1e-9, atol=0)


def test_six_parts_give_the_cells_of_one_part_and_of_one_process(client, tmp_path, one_process):
    one = tessellate_in_parts(str(tmp_path / "one"), client, 1, n_seeds=6000, seed=11)
    six = tessellate_in_parts(str(tmp_path / "six"), client, 6, n_seeds=6000, seed=11)
    assert one.ok
    assert six.ok
    assert six.report.problems(1.0) == [] == one.report.problems(1.0)
    assert six.report.cells == 6000
    assert sorted(os.listdir(tmp_path / "six")) == [
        DATASET_FILE,
        *(f"part-{k:05d}.parquet" for k in range(6)),
    ]
    by_one = pd.read_parquet(tmp_path / "one")
    by_six = pd.read_parquet(tmp_path / "six")
    _same_cells(by_six, by_one)
    _same_cells(by_six, one_process)
    # Each part holds one slab: its grains' points lie between its bounds.
    slabs = Slabs(Box.cube(1.0), 6000, 6)
    held = json.loads((tmp_path / "six" / DATASET_FILE).read_text())
    assert held["complete"]
    assert held["checks_passed"]
    assert sum(p["report"]["cells"] for p in held["parts"].values()) == 6000
    assert [slabs.bounds(k)[1] for k in range(5)] == [slabs.bounds(k + 1)[0] for k in range(5)]


def test_margins_too_small_are_widened(client, tmp_path, one_process):
    narrow = tessellate_in_parts(str(tmp_path), client, 4, n_seeds=6000, seed=11, margin=0.1)
    assert narrow.ok
    assert sorted(narrow.widened) == [0, 1, 2, 3]  # every part reached past 0.1 spacings
    assert all(m > 0.1 for margins in narrow.widened.values() for m in margins)
    _same_cells(pd.read_parquet(tmp_path), one_process)
    assert narrow.report.problems(1.0) == []


def test_cells_cut_short_by_a_margin_fail_the_checks_across_parts(tmp_path, monkeypatch):
    """With the reach of cells not looked at, a margin of a tenth of a spacing truncates cells
    at the slabs' sides: faces across parts no longer pair up, and the volumes do not add up."""
    monkeypatch.setattr("grainclass.voronoi_parts._check_reach", lambda *args: None)
    slabs = Slabs(Box.cube(1.0), 3000, 3)
    records = []
    for k in range(3):
        job = PartJob(
            index=k,
            slabs=slabs,
            margin=0.1 * slabs.spacing,
            path=str(tmp_path / f"part-{k}.parquet"),
            identity={},
            scale=voronoi.cell_scale(slabs.box, 3000),
            seed=5,
            source="voronoi:3000:5",
        )
        records.append(tessellation_part(job, None))
    merged = _merged(records)
    problems = merged.problems(1.0)
    assert sorted(merged.unmatched_parts) == [(0, 1), (0, 2), (1, 2)]
    assert any("the cells' volume is" in p for p in problems)


def test_each_part_draws_the_seeds_of_one_process():
    """Drawn a million at a time, the seeds are those one process draws at once, in the same
    order: the parts' own points, together, are every seed once."""
    slabs = Slabs(Box.cube(1.0), 3000, 4)
    whole = np.random.default_rng(9).random((3000, 3))
    drawn = {}
    for k in range(4):
        part = seed_points(slabs, k, 9, "s", slabs.container(k, 0.05))
        drawn.update(zip(part.own.ids.tolist(), map(tuple, part.own.xyz), strict=True))
        assert (whole[part.own_keys] == part.own.xyz).all()
        assert (whole[part.margin_keys, :2] == part.margin_xyz[:, :2]).all()
    order = voronoi.block_order(whole, Box.cube(1.0))
    assert [drawn[i] for i in range(3000)] == list(map(tuple, whole[order]))


def test_points_with_radii_in_a_walled_box(tmp_path):
    """Laguerre cells of a CSV's points, walled along z and periodic in x and y: the parts
    give the rows of one process, boundary flags and hidden points included."""
    rng = np.random.default_rng(5)
    xyz = rng.random((4000, 3)) * [2.0, 3.0, 4.0]
    radii = rng.random(4000) * 0.15
    path = tmp_path / "points.csv"
    lines = [
        ",".join(map(repr, [i, *map(float, row)]))
        for i, row in enumerate(np.column_stack([xyz, radii]))
    ]
    path.write_text("id,x,y,z,r\n" + "\n".join(lines) + "\n")
    box = ["--box", "0,2,0,3,0,4", "--periodic", "xy"]
    parted = CliRunner().invoke(
        cli,
        [
            "voronoi",
            "--points",
            str(path),
            *box,
            "--parts",
            "5",
            "--workers",
            "2",
            "-o",
            f"{tmp_path}/parts/",
        ],
    )
    assert parted.exit_code == 0, parted.output
    assert "in 5 parts (5 computed now, 0 from earlier runs)" in parted.stderr
    points = read_points(str(path))
    assert (points.xyz == xyz).all()
    assert (points.radii == radii).all()
    the_box = Box((0.0, 0.0, 0.0), (2.0, 3.0, 4.0), (True, True, False))
    single = tmp_path / "single.parquet"
    report = voronoi.VoronoiReport()
    voronoi.write_cells(voronoi.tessellate(points, the_box, report=report), str(single))
    whole = pd.read_parquet(single)
    assert whole["boundary"].any()
    assert report.no_cells
    assert f"{report.no_cells} point" in parted.stderr
    _same_cells(pd.read_parquet(tmp_path / "parts"), whole)


def test_a_rerun_rewrites_only_the_missing_part(client, tmp_path):
    first = tessellate_in_parts(str(tmp_path), client, 4, n_seeds=3000, seed=2)
    assert (first.computed, first.skipped) == (4, 0)
    files = sorted(tmp_path.glob("part-*.parquet"))
    before = {f.name: f.stat().st_mtime_ns for f in files}
    files[2].unlink()
    second = tessellate_in_parts(str(tmp_path), client, 4, n_seeds=3000, seed=2)
    assert (second.computed, second.skipped) == (1, 3)
    after = {f.name: f.stat().st_mtime_ns for f in sorted(tmp_path.glob("part-*.parquet"))}
    assert {name for name in after if after[name] != before.get(name)} == {files[2].name}
    assert second.report.cells == 3000
    assert second.report.problems(1.0) == []
    # Without --seed, an unfinished run of the same seeds is resumed with the seed it drew.
    drawn = tessellate_in_parts(str(tmp_path / "drawn"), client, 3, n_seeds=3000)
    seed = json.loads((tmp_path / "drawn" / DATASET_FILE).read_text())["identity"]["seed"]
    (tmp_path / "drawn" / "part-00001.parquet").unlink()
    held = json.loads((tmp_path / "drawn" / DATASET_FILE).read_text())
    held["complete"] = False
    (tmp_path / "drawn" / DATASET_FILE).write_text(json.dumps(held))
    again = tessellate_in_parts(str(tmp_path / "drawn"), client, 3, n_seeds=3000)
    assert (drawn.computed, again.computed, again.skipped) == (3, 1, 2)
    assert json.loads((tmp_path / "drawn" / DATASET_FILE).read_text())["identity"]["seed"] == seed


def test_a_folder_that_holds_another_data_set_is_refused(client, tmp_path):
    tessellate_in_parts(str(tmp_path), client, 2, n_seeds=500, seed=1)
    with pytest.raises(OutputError, match="holds another data set"):
        tessellate_in_parts(str(tmp_path), client, 2, n_seeds=500, seed=2)
    stranger = tmp_path / "other"
    stranger.mkdir()
    (stranger / "mine.parquet").write_bytes(b"PAR1")
    with pytest.raises(OutputError, match=r"mine\.parquet, which belongs to no data set"):
        tessellate_in_parts(str(stranger), client, 2, n_seeds=500, seed=1)


def test_slabs_refuse_more_parts_than_layers_of_blocks_and_tilted_boxes():
    with pytest.raises(OptionError, match="at most 8 parts, not 9"):
        Slabs(Box.cube(1.0), 3000, 9)
    with pytest.raises(OptionError, match="tilted box"):
        Slabs(Box((0, 0, 0), (1, 1, 1), tilt=(0.1, 0, 0)), 3000, 2)
    slabs = Slabs(Box.cube(2.0, (True, True, False)), 3000, 3)
    assert slabs.cuts.tolist() == [0, 3, 5, 8]
    whole = slabs.container(1, 10.0)
    assert whole.whole
    inside, shift = slabs.container(0, 0.1).images(np.array([0.2, 1.99, 1.0, 0.8]))
    assert inside.tolist() == [True, False, False, True]  # walled: no image wraps round
    assert shift.tolist() == [0, 0, 0, 0]


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--parts", "2", "-o", "pv.parquet"], "give -o DIR/"),
        (["--workers", "2", "-o", "pv.txt"], "give -o DIR/"),
        (["-j", "2", "-o", "out/"], "in parts, --workers"),
        (["--parts", "99", "-o", "out/"], "at most 8 parts, not 99"),
    ],
)
def test_usage_errors_of_parts(tmp_path, monkeypatch, args, message):
    monkeypatch.chdir(tmp_path)
    result = CliRunner().invoke(cli, ["voronoi", "3000", "--seed", "1", "--workers", "1", *args])
    assert result.exit_code == 2, result.output
    assert message in result.stderr


def test_a_folder_output_that_is_a_file_is_refused(tmp_path):
    (tmp_path / "taken").write_text("x")
    result = CliRunner().invoke(cli, ["voronoi", "100", "-o", f"{tmp_path}/taken/"])
    assert result.exit_code == 1
    assert "is not a folder" in result.stderr


def test_a_worker_that_dies_costs_only_its_part(tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    with dask_client(workers=2) as dask:
        dask.register_plugin(die_once("part-00002", tmp_path / "died", writing=out))
        before = set(dask.run(os.getpid).values())
        result = tessellate_in_parts(str(out), dask, 4, n_seeds=20000, seed=4)
        after = set(dask.run(os.getpid).values())
    assert (tmp_path / "died").exists()
    assert len(before - after) == 1  # one worker died, and was replaced
    assert result.ok
    assert result.computed == 4
    assert result.report.problems(1.0) == []
    assert not [f for f in os.listdir(out) if f.endswith(".tmp")]
    whole = tmp_path / "whole.parquet"
    voronoi.write_cells(voronoi.poisson_voronoi(20000, 4), str(whole))
    _same_cells(pd.read_parquet(out), pd.read_parquet(whole))


def test_ctrl_c_keeps_finished_parts_and_leaves_no_temporary(tmp_path):
    out = tmp_path / "out"
    args = ["voronoi", "400000", "--seed", "1", "--parts", "12", "--workers", "2", "-o", f"{out}/"]
    code, err = ctrl_c_at_a_terminal(
        *args, when=lambda pid: len(list(out.glob("part-*.parquet"))) >= 1
    )
    assert code == 130, err
    assert "Traceback" not in err
    finished = {f.name: f.stat().st_mtime_ns for f in out.glob("part-*.parquet")}
    assert 1 <= len(finished) < 12
    assert not [f for f in os.listdir(out) if f.endswith(".tmp")], (os.listdir(out), err)
    summarized = subprocess.run(
        [sys.executable, "-m", "grainclass", "summarize", str(out)], capture_output=True, text=True
    )
    assert summarized.returncode == 1
    assert "an unfinished data set" in summarized.stderr


def test_bad_points_fail_before_a_cluster_starts_and_write_nothing(tmp_path):
    points = tmp_path / "points.txt"  # Voro++'s input: id x y z
    points.write_text("1 0.1 0.2 0.3\n2 0.6 0.7 0.8\n3 0.1 0.2 0.3\n")
    result = CliRunner().invoke(
        cli, ["voronoi", "--points", str(points), "--parts", "1", "-o", f"{tmp_path}/out/"]
    )
    assert result.exit_code == 1
    assert "point 3 is at the same place as point 1" in result.stderr
    assert not (tmp_path / "out").exists()
