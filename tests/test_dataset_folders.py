"""A folder of per-grain Parquet parts reads as one data set: `summarize`, `types`, `penalties`
and `plot` give the numbers of the same rows in one file, when the parts are tallied on several
threads and the tallies and type counts merged as they go.

The truth is the one file: the same inputs classified into a single table.
"""

from __future__ import annotations

import pandas as pd
import pytest

from grainclass import summary, summary_tables, type_counts
from grainclass.datasets import figure_table, penalty_table, write_grains
from grainclass.options import FigureOptions

EXAMPLES = ["examples/polytopes.txt", "examples/bad-grains.txt"]


@pytest.fixture(scope="module")
def folder_and_file(tmp_path_factory, plantri_output):
    """The same grains as a folder of three parts of many row groups, and as one file."""
    root = tmp_path_factory.mktemp("dataset")
    inputs = [EXAMPLES, [str(plantri_output(10))], [str(plantri_output(11))]]
    (root / "parts").mkdir()
    for k, paths in enumerate(inputs):
        write_grains(
            paths, str(root / "parts" / f"part-{k:05d}.parquet"), chunk_size=97, belt_length=6
        )
    everything = [path for paths in inputs for path in paths]
    write_grains(everything, str(root / "one.parquet"), belt_length=6)
    return str(root / "parts"), str(root / "one.parquet")


@pytest.mark.parametrize("jobs", [1, 2])
def test_summaries_of_the_folder_are_those_of_one_file(folder_and_file, monkeypatch, jobs):
    folder, one = folder_and_file
    monkeypatch.setattr(summary, "MERGE_EVERY", 3)  # 250 row groups: merged as they come
    parted = summary_tables(folder, n_values=[10, 11], jobs=jobs)
    whole = summary_tables(one, n_values=[10, 11])
    assert parted.headline == whole.headline
    assert parted.headline["grains"] == 12 + 13 + 233 + 1249
    for table in ("classes", "round", "split", "geometry"):
        pd.testing.assert_frame_equal(getattr(parted, table), getattr(whole, table))
    by_belts = summary_tables(folder, belt_length=6, jobs=jobs)
    pd.testing.assert_frame_equal(by_belts.split, summary_tables(one, belt_length=6).split)


def test_types_penalties_and_figures_of_the_folder_are_those_of_one_file(folder_and_file):
    folder, one = folder_and_file
    pd.testing.assert_frame_equal(type_counts(folder), type_counts(one))
    pd.testing.assert_frame_equal(type_counts(folder, n_faces=11), type_counts(one, n_faces=11))
    pd.testing.assert_frame_equal(
        penalty_table(folder, belt_length=6), penalty_table(one, belt_length=6)
    )
    for request in (FigureOptions("round", n_values=(11,)), FigureOptions("ranks")):
        pd.testing.assert_frame_equal(
            figure_table([folder], request, labels=["data"]),
            figure_table([one], request, labels=["data"]),
        )
