"""How well a voxelized tessellation's types are recovered: a periodic centroidal Voronoi
tessellation of 200 seeds at about 25 voxels across a grain, against the exact cells of the same
seeds from Voro++ (``grainclass voronoi --points``), and against the columns alone: the triple
lines that 2x2 columns of three labels show, on the pass's own faces (the naive rule's edges;
docs/voxels.md's naive rule takes its faces from voxel faces too)."""

from __future__ import annotations

import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq
import pytest
from click.testing import CliRunner

import grainclass.voxels as voxels
from grainclass import classify
from grainclass.cli import cli
from grainclass.readers.label_image import in_memory
from voxel_images import lloyd, nearest_seed

SEEDS, RESOLUTION = 200, 146  # 146 / 200^(1/3) = 25.0 voxels across a grain


@pytest.fixture(scope="module")
def cvt(tmp_path_factory):
    """The seeds after 20 Lloyd iterations, the image, and the exact cells' types by id."""
    work = tmp_path_factory.mktemp("cvt")
    seeds = lloyd(np.random.default_rng(40).random((SEEDS, 3)), 20, 40)
    points = work / "seeds.txt"
    ids = np.arange(1, SEEDS + 1)
    np.savetxt(points, np.column_stack([ids, seeds]), fmt="%d %.17g %.17g %.17g")
    cells = work / "cells.parquet"
    result = CliRunner().invoke(
        cli, ["voronoi", "--points", str(points), "--box", "1", "-o", str(cells), "-q"]
    )
    assert result.exit_code == 0, result.output
    exact = pq.read_table(cells).to_pandas().set_index("grain_id")
    assert (exact["status"] == "ok").all()
    labels = nearest_seed(seeds, RESOLUTION).astype(np.uint16)
    return labels, exact


def _share_right(table: pa.Table, exact) -> float:
    ours = table.to_pandas().set_index("grain_id").reindex(exact.index)
    return float(((ours["status"] == "ok") & (ours["weinberg"] == exact["weinberg"])).mean())


def test_voxel_accuracy_cvt_types_against_voro(cvt):
    labels, exact = cvt
    topology = voxels.image_topology(in_memory("cvt", labels), "xyz")
    ours = pa.concat_tables(classify(b) for b in voxels.image_batches(topology, 1000))
    columns = pa.concat_tables(
        classify(b) for b in voxels.image_batches(topology, 1000, triples=topology.columns)
    )
    assert ours["grain_id"].to_pylist() == [str(i) for i in range(1, SEEDS + 1)]
    ours_right, columns_right = _share_right(ours, exact), _share_right(columns, exact)
    print(f"exact types: ours {ours_right:.1%}, columns alone {columns_right:.1%}")
    assert ours_right >= 0.62
    assert ours_right >= columns_right + 0.05
    # Every grain is a simple polytope: the junctions agree between neighbours.
    assert ours["status"].to_pylist().count("ok") >= 0.97 * SEEDS
    np.testing.assert_array_equal(ours["voxels"].to_numpy(), np.bincount(labels.ravel())[1:])
