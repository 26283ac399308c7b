"""NumPy label images (readers/npy_image.py, readers/images.py): .npy read slab by slab, .npz,
sniffing images apart from points, and every bad input refused with the file named, exit 1."""

from __future__ import annotations

import io

import numpy as np
import pyarrow.parquet as pq
import pytest
from click.testing import CliRunner

from grainclass.cli import cli
from grainclass.readers.images import IMAGE_OPENERS, sniff_image
from grainclass.readers.npy_image import open_npy
from grainclass.readers.sniffing import points_kind


def _classify(path, *flags):
    out = path.with_suffix(".parquet")
    result = CliRunner().invoke(cli, ["classify", str(path), "-o", str(out), "-q", *flags])
    return result, out


def _two_grains() -> np.ndarray:
    labels = np.ones((4, 5, 6), np.int32)
    labels[:, :, 3:] = 2
    return labels


def test_npy_image_slabs_are_the_array_in_order(tmp_path):
    labels = np.arange(5 * 3 * 4, dtype=np.uint32).reshape(5, 3, 4)
    np.save(tmp_path / "a.npy", labels)
    image = open_npy(str(tmp_path / "a.npy"))
    assert image.shape == (5, 3, 4)
    assert image.dtype == np.uint32
    slabs = list(image.slabs(2))
    assert [len(s) for s in slabs] == [2, 2, 1]
    np.testing.assert_array_equal(np.concatenate(slabs), labels)


def test_npy_image_fortran_order_is_read_as_indexed(tmp_path):
    labels = np.asfortranarray(np.arange(24, dtype=np.int16).reshape(2, 3, 4))
    np.save(tmp_path / "f.npy", labels)
    np.testing.assert_array_equal(
        np.concatenate(list(open_npy(str(tmp_path / "f.npy")).slabs(1))), labels
    )


def test_npy_image_npz_with_one_image(tmp_path):
    np.savez_compressed(tmp_path / "a.npz", labels=_two_grains(), spacing=np.ones(3))
    result, out = _classify(tmp_path / "a.npz")
    assert result.exit_code == 0, result.output
    assert pq.read_table(out)["grain_id"].to_pylist() == ["1", "2"]


def test_npy_image_classify_writes_a_row_per_label(tmp_path):
    np.save(tmp_path / "two.npy", _two_grains())
    result, out = _classify(tmp_path / "two.npy", "--spacing", "2,2,2")
    assert result.exit_code == 0, result.output
    table = pq.read_table(out)
    assert table["grain_id"].to_pylist() == ["1", "2"]
    assert table["volume"].to_pylist() == [60 * 8.0, 60 * 8.0]
    assert table["boundary"].to_pylist() == [True, True]


@pytest.mark.parametrize(
    ("make", "says"),
    [
        (lambda p: np.save(p, np.ones((4, 4), np.int32)), "a 2D array"),
        (lambda p: np.save(p, np.ones((2, 2, 2, 2), np.int32)), "a 4D array"),
        (lambda p: np.save(p, np.ones((3, 3, 3), np.float32)), "float32"),
        (
            lambda p: np.save(p, -np.ones((3, 3, 3), np.int64)),
            "negative label -1 at voxel x=0, y=0, z=0",
        ),
        (lambda p: np.save(p, np.ones((0, 3, 3), np.int32)), "an empty image"),
        (lambda p: p.write_bytes(_npy_bytes(np.ones((8, 8, 8), np.int32))[:-100]), "cut short"),
        (lambda p: p.write_bytes(b"\x93NUMPY\x01\x00garbage"), "not a NumPy .npy file"),
    ],
)
def test_npy_image_bad_input_exits_1_naming_the_file(tmp_path, make, says):
    path = tmp_path / "bad.npy"
    make(path)
    result, out = _classify(path)
    assert result.exit_code == 1, result.output
    assert str(path) in result.stderr
    assert says in result.stderr
    assert not out.exists()


def test_npy_image_npz_without_one_image_names_its_arrays(tmp_path):
    path = tmp_path / "two.npz"
    np.savez(path, a=_two_grains(), b=_two_grains())
    result, _ = _classify(path)
    assert result.exit_code == 1
    assert "several 3D integer arrays" in result.stderr
    assert "a (4x5x6 int32)" in result.stderr
    assert "b (4x5x6 int32)" in result.stderr
    np.savez(path, points=np.zeros((5, 3)))
    result, _ = _classify(path)
    assert result.exit_code == 1
    assert "no 3D integer array" in result.stderr
    assert "points (5x3 float64)" in result.stderr


def test_npy_image_from_standard_input_is_refused(tmp_path):
    data = _npy_bytes(_two_grains())
    result = CliRunner().invoke(
        cli, ["classify", "-", "-o", str(tmp_path / "o.parquet")], input=data
    )
    assert result.exit_code == 1
    assert "not a pipe" in result.stderr


def test_npy_image_named_as_another_format_is_refused_for_what_it_is(tmp_path):
    path = tmp_path / "grains.npy"
    np.save(path, _two_grains())
    result, out = _classify(path, "--input-format", "adjacency")
    assert result.exit_code == 1
    assert f"{path}: a label image (npy), not adjacency input" in result.stderr
    assert not out.exists()


def _npy_bytes(array: np.ndarray) -> bytes:
    buffer = io.BytesIO()
    np.save(buffer, array)
    return buffer.getvalue()


def test_npy_image_sniffed_apart_from_points():
    image = _npy_bytes(np.zeros((2, 2, 2), np.uint8))[:128]
    points = _npy_bytes(np.zeros((10, 3)))[:128]
    assert sniff_image("x.npy", image) == "npy"
    assert sniff_image("x.npy", points) is None
    assert points_kind(points) == "a NumPy array of points"
    assert points_kind(image) is None
    assert sniff_image("x.txt", b"1\t2 3 4;") is None


def test_npy_image_opener_is_registered():
    assert IMAGE_OPENERS["npy"] is open_npy
