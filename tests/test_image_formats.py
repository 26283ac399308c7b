"""The readers of 3D label images: every format read slab by slab gives the image written by
hand in that format's documented layout (tests/image_writers.py), or another program's own
output (DAMASK's grid, a SPPARKS run); bad files end in an InputError naming the file."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

from grainclass.errors import InputError, MissingDependencyError, OptionError
from grainclass.readers.dream3d import looks_like_dream3d, open_dream3d
from grainclass.readers.sniffing import points_kind
from grainclass.readers.spparks import looks_like_spparks, open_spparks
from grainclass.readers.tesr import looks_like_tesr, open_tesr
from grainclass.readers.tiff_image import looks_like_tiff, open_tiff
from grainclass.readers.vti import looks_like_vti, open_vti
from image_writers import LABELS, SPACING, spparks_snapshot, write_dream3d, write_tesr, write_vti

DATA = Path(__file__).parent / "data" / "images"
DEPTHS = (1, 2, 3, 5, 7)


def read_all(image, depth: int) -> np.ndarray:
    """The image's slabs of at most ``depth`` slices, each checked, stacked."""
    slabs = list(image.slabs(depth))
    _, ny, nx = image.shape
    assert all(1 <= len(s) <= depth and s.shape[1:] == (ny, nx) for s in slabs)
    assert all(s.dtype == image.dtype for s in slabs)
    return np.concatenate(slabs)


def assert_reads_labels(image, expected=LABELS) -> None:
    assert image.shape == expected.shape
    for depth in DEPTHS:
        np.testing.assert_array_equal(read_all(image, depth), expected)


def assert_refused(opener, path, *words: str) -> InputError:
    """``opener(path)``, or reading all its slabs, raises an InputError naming the file."""
    with pytest.raises(InputError) as caught:
        read_all(opener(str(path)), 2)
    assert str(path) in str(caught.value)
    for word in words:
        assert word in str(caught.value)
    return caught.value


# TIFF


tifffile = pytest.importorskip("tifffile")


@pytest.mark.parametrize(
    ("dtype", "options"),
    [
        ("uint16", {}),
        ("uint8", {"compression": "zlib"}),
        ("int32", {"bigtiff": True}),
        ("uint16", {"imagej": True, "metadata": {"axes": "ZYX"}}),
        ("uint16", {"volumetric": True, "tile": (8, 16, 16)}),
    ],
)
def test_tiff_stack_reads_pages_as_z(tmp_path, dtype, options):
    path = tmp_path / "labels.tif"
    tifffile.imwrite(path, LABELS.astype(dtype), **options)
    image = open_tiff(str(path))
    assert image.dtype == np.dtype(dtype)
    assert image.spacing is None
    assert_reads_labels(image)
    assert looks_like_tiff(path.read_bytes()[:4096])


@pytest.mark.parametrize(
    ("array", "words"),
    [
        (LABELS.astype(np.float32), ("float32",)),
        (LABELS[0].astype(np.uint16), ("2D",)),
        (np.stack([LABELS.astype(np.uint8)] * 3, axis=-1), ("axes",)),
        (-LABELS.astype(np.int16) - 1, ("negative label",)),
    ],
)
def test_tiff_refused(tmp_path, array, words):
    path = tmp_path / "bad.tif"
    tifffile.imwrite(path, array)
    assert_refused(open_tiff, path, *words)


def test_tiff_damaged_is_an_input_error(tmp_path):
    path = tmp_path / "bad.tif"
    tifffile.imwrite(path, LABELS.astype(np.uint16))
    path.write_bytes(path.read_bytes()[:12] + bytes(100))
    assert_refused(open_tiff, path)


def test_missing_tifffile_names_the_extra(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "tifffile", None)
    with pytest.raises(MissingDependencyError, match=r"grainclass\[images\]"):
        open_tiff(str(tmp_path / "any.tif"))


# DREAM.3D


h5py = pytest.importorskip("h5py")


def test_dream3d_reads_feature_ids_and_spacing(tmp_path):
    path = tmp_path / "labels.dream3d"
    write_dream3d(path)
    image = open_dream3d(str(path))
    assert image.spacing == SPACING
    assert image.dtype == np.int32
    assert_reads_labels(image)
    assert looks_like_dream3d(path.read_bytes()[:4096])


@pytest.mark.parametrize(
    ("options", "words"),
    [
        ({"containers": ("A", "B")}, ("2 data containers", "A, B")),
        ({"containers": ()}, ("no FeatureIds",)),
        ({"dimensions": [5, 6, 7]}, ("DIMENSIONS",)),
        ({"nx_layout": True}, ("DREAM3D-NX",)),
        ({"components": 3}, ("3 components",)),
        ({"labels": LABELS.astype(np.float32)}, ("float32",)),
        ({"labels": LABELS[:1]}, ("2D",)),
        ({"labels": LABELS - 1}, ("negative label -1",)),
    ],
)
def test_dream3d_refused(tmp_path, options, words):
    path = tmp_path / "bad.dream3d"
    write_dream3d(path, **options)
    assert_refused(open_dream3d, path, *words)


def test_dream3d_spacing_named_resolution_before_6_5(tmp_path):
    path = tmp_path / "old.dream3d"
    write_dream3d(path)
    with h5py.File(path, "r+") as file:
        geometry = file["DataContainers/ImageDataContainer/_SIMPL_GEOMETRY"]
        geometry.move("SPACING", "RESOLUTION")
    assert open_dream3d(str(path)).spacing == SPACING


def test_dream3d_not_hdf5(tmp_path):
    path = tmp_path / "bad.dream3d"
    path.write_bytes(b"\x89HDF\r\n\x1a\n" + bytes(200))
    assert_refused(open_dream3d, path, "HDF5")


# VTK image data


VTI_CASES = {
    "ascii": {"encoding": "ascii"},
    "binary": {"encoding": "binary"},
    "binary header apart": {"encoding": "binary", "joint_base64": False},
    "binary zlib": {"encoding": "binary", "compressor": "zlib"},
    "binary zlib UInt64": {"encoding": "binary", "compressor": "zlib", "header": "UInt64"},
    "appended raw": {"encoding": "appended-raw"},
    "appended raw UInt64 big-endian":
        {"encoding": "appended-raw", "header": "UInt64", "order": ">"},
    "appended raw zlib": {"encoding": "appended-raw", "compressor": "zlib"},
    "appended raw lzma": {"encoding": "appended-raw", "compressor": "lzma"},
    "appended base64": {"encoding": "appended-base64"},
    "appended base64 zlib": {"encoding": "appended-base64", "compressor": "zlib"},
}  # fmt: skip


@pytest.mark.parametrize("case", VTI_CASES)
@pytest.mark.parametrize("dtype", ["int32", "uint8", "int64"])
def test_vti_every_encoding(tmp_path, case, dtype):
    path = tmp_path / "labels.vti"
    write_vti(path, LABELS.astype(dtype), **VTI_CASES[case])
    image = open_vti(str(path))
    assert image.dtype == np.dtype(dtype)
    assert image.spacing == SPACING
    assert_reads_labels(image)
    assert looks_like_vti(path.read_bytes()[:4096])


def test_vti_point_data_is_a_voxel_per_point(tmp_path):
    path = tmp_path / "points.vti"
    write_vti(path, LABELS, "appended-raw", kind="PointData", name="labels")
    assert_reads_labels(open_vti(str(path)))


def test_vti_takes_the_one_integer_array(tmp_path):
    path = tmp_path / "one.vti"
    other = '<DataArray type="Float32" Name="phase" format="ascii">' + " 0.5" * 210 + "</DataArray>"
    write_vti(path, LABELS, "ascii", name="grains", extra_arrays=other)
    assert_reads_labels(open_vti(str(path)))


def test_vti_appended_arrays_each_at_its_offset(tmp_path):
    # A float cell array first, the labels after it: the offsets count from the "_".
    path = tmp_path / "two.vti"
    write_vti(path, LABELS.astype(np.uint16), "appended-raw", header="UInt64")
    data = path.read_bytes()
    phase = np.full(LABELS.size, 0.5, dtype="<f4").tobytes()
    head = np.array([len(phase)], dtype="<u8").tobytes()
    first = '<DataArray type="Float32" Name="phase" format="appended" offset="0"/>\n'
    data = data.replace(
        b'format="appended" offset="0"', f'format="appended" offset="{8 + len(phase)}"'.encode()
    )
    data = data.replace(b"<DataArray", first.encode() + b"      <DataArray", 1)
    data = data.replace(b"\n   _", b"\n   _" + head + phase, 1)
    path.write_bytes(data)
    assert_reads_labels(open_vti(str(path)))


def test_vti_without_spacing(tmp_path):
    path = tmp_path / "nospacing.vti"
    write_vti(path, spacing=None)
    assert open_vti(str(path)).spacing is None


def test_vti_base64_in_lines(tmp_path):
    path = tmp_path / "lines.vti"
    write_vti(path, LABELS, "binary", compressor="zlib")
    text = path.read_text()
    start = text.index('format="binary">') + len('format="binary">')
    end = text.index("</DataArray>")
    payload = "".join(text[start:end].split())
    wrapped = "\n".join(payload[i : i + 76] for i in range(0, len(payload), 76))
    path.write_text(text[:start] + "\n" + wrapped + "\n" + text[end:])
    assert_reads_labels(open_vti(str(path)))


def test_damask_grid_reads_as_damask_loads_it():
    # DAMASK's material array is indexed [x, y, z]; a LabelImage is [z, y, x].
    material = np.load(DATA / "damask-voronoi.material.npy")
    image = open_vti(str(DATA / "damask-voronoi.vti"))
    assert image.shape == material.shape[::-1] == (8, 10, 12)
    assert image.dtype == np.int64
    np.testing.assert_allclose(image.spacing, (0.1, 0.1, 0.1))
    for depth in DEPTHS:
        np.testing.assert_array_equal(read_all(image, depth), material.transpose(2, 1, 0))


def _vti_with(tmp_path, old: bytes, new: bytes, **options) -> Path:
    path = tmp_path / "bad.vti"
    write_vti(path, **options)
    data = path.read_bytes()
    assert old in data
    path.write_bytes(data.replace(old, new))
    return path


@pytest.mark.parametrize(
    ("old", "new", "options", "words"),
    [
        (b'type="Int32"', b'type="Float64"', {"encoding": "ascii"}, ("float64",)),
        (b'Name="material"', b'Name="a"', {"extra_arrays": '<DataArray type="Int8" Name="b"/>'},
         ("'a'", "'b'")),
        (b"0 7 0 6 0 5", b"0 7 0 6 0 1", {"encoding": "ascii"}, ("2D",)),
        (b'<Piece Extent="0 7 0 6 0 5">', b'<Piece Extent="0 7 0 6 0 4">', {}, ("piece",)),
        (b"</Piece>", b'</Piece><Piece Extent="0 7 0 6 0 5"></Piece>', {}, ("2 pieces",)),
        (b"vtkZLibDataCompressor", b"vtkLZ4DataCompressor", {"compressor": "zlib"}, ("LZ4",)),
        (b'type="ImageData"', b'type="UnstructuredGrid"', {}, ("ImageData",)),
        (b'Name="material"', b'Name="material" NumberOfComponents="3"', {}, ("3 components",)),
        (b"</AppendedData>", b"", {"encoding": "appended-base64"}, ()),
        (b' Spacing="0.5', b' Spacing="-0.5', {}, ("Spacing",)),
        (b"format=\"ascii\">", b"format=\"ascii\"> 1.5", {"encoding": "ascii"}, ("'1.5'",)),
        (b"format=\"ascii\">", b"format=\"ascii\"> -3", {"encoding": "ascii"}, ("negative",)),
    ],
)  # fmt: skip
def test_vti_refused(tmp_path, old, new, options, words):
    path = _vti_with(tmp_path, old, new, **options)
    if not words:  # cut off: the data are read up to the end of the file
        path.write_bytes(path.read_bytes()[:-60])
    assert_refused(open_vti, path, *words)


def test_vti_length_header_that_disagrees(tmp_path):
    path = tmp_path / "bad.vti"
    write_vti(path)
    data = bytearray(path.read_bytes())
    at = data.index(b"\n   _") + 5
    data[at : at + 4] = np.array([LABELS.size * 4 - 4], dtype="<u4").tobytes()
    path.write_bytes(bytes(data))
    assert_refused(open_vti, path, "holds 836 bytes, the extent needs 840")


@pytest.mark.parametrize("options", [{}, {"compressor": "zlib"}])
def test_vti_cut_short_reads_the_slabs_it_has(tmp_path, options):
    path = tmp_path / "cut.vti"
    write_vti(path, **options)
    data = path.read_bytes()
    cut = data.index(b"\n   _") + 5 + 4 * (7 if options else 1) + 170
    path.write_bytes(data[:cut])
    image = open_vti(str(path)) if not options else None
    if image is None:  # the compressed blocks' sizes say more than the file holds
        assert_refused(open_vti, path, "cut short")
        return
    slabs = image.slabs(1)
    np.testing.assert_array_equal(next(slabs), LABELS[:1])
    with pytest.raises(InputError, match="cut short"):
        next(slabs)


def test_vti_corrupt_block_is_an_input_error(tmp_path):
    path = tmp_path / "bad.vti"
    write_vti(path, compressor="zlib")
    data = bytearray(path.read_bytes())
    data[-40] ^= 0xFF
    path.write_bytes(bytes(data))
    assert_refused(open_vti, path)


# Neper raster tessellations


@pytest.mark.parametrize(
    ("data_format", "dtype"),
    [("ascii", "int32"), ("binary8", "uint8"), ("binary16", "int16"),
     ("binary16_big", "int16"), ("binary32", "int32"), ("binary32_big", "int32")],
)  # fmt: skip
def test_tesr_formats(tmp_path, data_format, dtype):
    path = tmp_path / "labels.tesr"
    write_tesr(path, data_format=data_format)
    image = open_tesr(str(path))
    assert image.dtype == np.dtype(dtype)
    assert image.spacing == SPACING
    assert_reads_labels(image)
    assert looks_like_tesr(path.read_bytes()[:4096])


@pytest.mark.parametrize("data_format", ["ascii", "binary16"])
def test_tesr_data_in_a_file_beside_it(tmp_path, data_format):
    path = tmp_path / "labels.tesr"
    write_tesr(path, data_format=data_format, external="labels.raw")
    assert_reads_labels(open_tesr(str(path)))


def test_tesr_format_2_0(tmp_path):
    path = tmp_path / "old.tesr"
    write_tesr(path, data_format="binary8", version="2.0")
    assert_reads_labels(open_tesr(str(path)))


def test_tesr_cells_by_their_ids(tmp_path):
    path = tmp_path / "ids.tesr"
    ids = [11, 22, 33, 44, 55]  # cell k of the data is ids[k - 1]; void 0 stays 0
    write_tesr(path, data_format="binary8", ids=ids)
    lookup = np.array([0, *ids])
    image = open_tesr(str(path))
    assert image.dtype == np.int32
    assert_reads_labels(image, lookup[LABELS])


@pytest.mark.parametrize(
    ("options", "words"),
    [
        ({"dimension": 2}, ("2D",)),
        ({"data_format": "binary64"}, ("binary64",)),
        ({"data_format": "binary8", "ids": [1, 2, 3]}, ("cell 5", "3 of **cell *id")),
        ({"labels": LABELS[:, :, :1]}, ("2D",)),
        ({"labels": LABELS - 1}, ("negative label -1",)),
    ],
)
def test_tesr_refused(tmp_path, options, words):
    path = tmp_path / "bad.tesr"
    write_tesr(path, **options)
    assert_refused(open_tesr, path, *words)


@pytest.mark.parametrize("data_format", ["ascii", "binary32"])
def test_tesr_cut_short(tmp_path, data_format):
    path = tmp_path / "cut.tesr"
    write_tesr(path, data_format=data_format)
    data = path.read_bytes()
    path.write_bytes(data[: data.index(b"**data") + 100])
    assert_refused(open_tesr, path, "cut short")


def test_tesr_without_data(tmp_path):
    path = tmp_path / "orientations.tesr"
    path.write_text("***tesr\n **format\n   2.1\n **general\n   2\n   4 3\n   1 1\n***end\n")
    assert_refused(open_tesr, path, "no **data")


# SPPARKS site dumps


def _dump(tmp_path, text: str) -> Path:
    path = tmp_path / "dump.potts"
    path.write_text(text)
    return path


def test_spparks_reads_the_last_snapshot(tmp_path):
    rng = np.random.default_rng(1)
    first = spparks_snapshot(LABELS[::-1].copy(), 0, 0.0, range(LABELS.size))
    last = spparks_snapshot(LABELS, 10, 10.0, rng.permutation(LABELS.size))
    image = open_spparks(str(_dump(tmp_path, first + last)))
    assert image.dtype == np.int32
    assert image.spacing is None
    assert_reads_labels(image)
    assert looks_like_spparks((first + last).encode()[:4096])


def test_spparks_default_columns_name_the_spin_type(tmp_path):
    text = spparks_snapshot(LABELS, 0, 0.0, range(LABELS.size), spin="type")
    assert_reads_labels(open_spparks(str(_dump(tmp_path, text))))


@pytest.mark.parametrize(
    ("edit", "words"),
    [
        (lambda t: t[: t.rindex("\n", 0, len(t) - 1)], ("cut short: 209 of the snapshot's 210",)),
        (lambda t: t[:-8] + "\n", ("columns expected",)),
        (lambda t: t.replace("id i1 x y z", "id d1 x y z"), ("no spin",)),
        (lambda t: t.replace("id i1 x y z", "id i1 x y q"), ("no z",)),
        (lambda t: t.replace("\n1 1 0 0 0", "\n1 1.5 0 0 0"), ("not an integer",)),
        (lambda t: t.replace("\n1 1 0 0 0", "\n1 -1 0 0 0"), ("negative label -1",)),
        (lambda t: t.replace("\n1 1 0 0 0", "\n1 1 0.5 0 0"), ("not equally spaced",)),
        (lambda t: t.replace("\n1 1 0 0 0", "\n1 1 1 0 0"), ("same point",)),
        (lambda t: t + "ITEM: TIMESTEP\n", ("cut short in the snapshot's header",)),
        (lambda t: t.replace("NUMBER OF ATOMS", "NUMBER OF SITES"), ("NUMBER OF ATOMS expected",)),
        (lambda t: t + "1 2 3 4 5\n", ("a line after the snapshot's last site",)),
    ],
)
def test_spparks_refused(tmp_path, edit, words):
    text = spparks_snapshot(LABELS, 0, 0.0, range(LABELS.size))
    assert_refused(open_spparks, _dump(tmp_path, edit(text)), *words)


@pytest.mark.parametrize("block", [7, 100, 4096])
def test_spparks_lines_parsed_a_block_at_a_time(tmp_path, monkeypatch, block):
    from grainclass.readers import spparks

    monkeypatch.setattr(spparks, "_BLOCK", block)
    text = spparks_snapshot(LABELS, 0, 0.0, np.random.default_rng(2).permutation(LABELS.size))
    assert_reads_labels(open_spparks(str(_dump(tmp_path, text))))
    error = assert_refused(open_spparks, _dump(tmp_path, text[: text.rindex("\n", 0, -1)]))
    assert error.line == 9 + 209
    error = assert_refused(open_spparks, _dump(tmp_path, text + "\n\n7 1 0 0 0\n"))
    assert error.line == 222  # 9 header lines, 210 sites, 2 blank lines


def test_spparks_cut_short_names_the_line(tmp_path):
    text = spparks_snapshot(LABELS, 0, 0.0, range(LABELS.size))
    error = assert_refused(open_spparks, _dump(tmp_path, text[: text.rindex("\n", 0, -1)]))
    assert error.line == 9 + 209  # the 209th site's line: the last there is


def test_spparks_sites_that_do_not_fill_a_grid(tmp_path):
    text = spparks_snapshot(LABELS, 0, 0.0, range(LABELS.size))
    lines = text.splitlines()
    lines[3] = str(LABELS.size - 1)
    del lines[20]
    assert_refused(open_spparks, _dump(tmp_path, "\n".join(lines) + "\n"), "do not fill")


def test_spparks_run_agrees_with_its_own_cluster_count():
    # SPPARKS's run (tests/data/README.md): 20^3 sites; its cluster diagnostic, written by the
    # same run, lists each cluster's spin (ivalue) and size, so the sites of each spin add up.
    image = open_spparks(str(DATA / "spparks" / "dump.potts20"))
    assert image.shape == (20, 20, 20)
    labels = read_all(image, 3)
    assert labels.min() >= 1
    assert labels.max() <= 8000
    sizes: dict[int, int] = {}
    text = (DATA / "spparks" / "clusters.potts20").read_text()
    rows = text.split("id ivalue")[1].splitlines()[1:]
    assert len([row for row in rows if row.strip()]) == 42  # its ncluster
    for row in filter(str.strip, rows):
        _, spin, _, size, *_ = row.split()
        sizes[int(spin)] = sizes.get(int(spin), 0) + int(size)
    spins, counts = np.unique(labels, return_counts=True)
    assert dict(zip(spins.tolist(), counts.tolist(), strict=True)) == sizes
    # The sc lattice numbers its sites x fastest from 1, independently of the coordinates.
    table = np.loadtxt(DATA / "spparks" / "dump.potts20", skiprows=9, dtype=np.int64)
    np.testing.assert_array_equal(labels.ravel()[table[:, 0] - 1], table[:, 1])


def test_points_kind_leaves_spparks_dumps_alone():
    head = (DATA / "spparks" / "dump.potts20").read_bytes()[:4096]
    assert points_kind(head) is None
    lammps = b"ITEM: TIMESTEP\n100\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS pp pp pp\n"
    assert points_kind(lammps) == "a LAMMPS dump of points"
    assert not looks_like_spparks(lammps)


# All formats


def test_each_sniffer_knows_only_its_own_format(tmp_path):
    files = {
        "tiff": tmp_path / "a.tif", "dream3d": tmp_path / "a.dream3d", "vti": tmp_path / "a.vti",
        "spparks": DATA / "spparks" / "dump.potts20", "tesr": tmp_path / "a.tesr",
    }  # fmt: skip
    tifffile.imwrite(files["tiff"], LABELS.astype(np.uint8))
    write_dream3d(files["dream3d"])
    write_vti(files["vti"])
    write_tesr(files["tesr"])
    sniffers = {"tiff": looks_like_tiff, "dream3d": looks_like_dream3d, "vti": looks_like_vti,
                "spparks": looks_like_spparks, "tesr": looks_like_tesr}  # fmt: skip
    found = {
        name: [fmt for fmt, sniff in sniffers.items() if sniff(path.read_bytes()[:4096])]
        for name, path in files.items()
    }
    assert found == {name: [name] for name in files}
    assert looks_like_dream3d(bytes(512) + b"\x89HDF\r\n\x1a\n")  # after a user block


@pytest.mark.parametrize("opener", [open_tiff, open_dream3d, open_vti, open_spparks, open_tesr])
def test_an_empty_or_foreign_file_is_an_input_error(tmp_path, opener):
    empty = tmp_path / "empty"
    empty.write_bytes(b"")
    assert_refused(opener, empty)
    foreign = tmp_path / "grains.txt"
    foreign.write_text("cube\t1 2 3 4;0 4 5 2;0 1 5 3;0 2 5 4;0 3 5 1;1 4 3 2\n")
    assert_refused(opener, foreign)


@pytest.mark.parametrize("depth", [0, -1, 1.5])
def test_a_depth_below_one_is_an_option_error(tmp_path, depth):
    path = tmp_path / "labels.vti"
    write_vti(path)
    with pytest.raises(OptionError):
        next(open_vti(str(path)).slabs(depth))


@pytest.mark.parametrize(
    "path", sorted((DATA.parent / "fuzz" / "images").iterdir()), ids=lambda p: p.name
)
def test_the_fuzz_seeds_are_whole_images(path):
    # make fuzz mutates these: a seed that did not read would leave its reader unfuzzed.
    opener = {".tif": open_tiff, ".dream3d": open_dream3d, ".vti": open_vti,
              ".dump": open_spparks, ".tesr": open_tesr}[path.suffix]  # fmt: skip
    image = opener(str(path))
    assert image.shape == (3, 4, 5)
    expected = LABELS[:3, :4, :5]
    if path.name == "ascii.tesr":  # written with *id 7 .. 11 for cells 1 .. 5
        expected = np.array([0, 7, 8, 9, 10, 11])[expected]
    np.testing.assert_array_equal(read_all(image, 2), expected)


# Every format through classify


def _bcc_in_every_format(tmp_path) -> dict[str, Path]:
    """The voxelized BCC lattice (54 grains, 36^3 voxels) written as each format, named so that
    nothing but the file's first bytes tells its format."""
    from voxel_images import bcc_seeds, nearest_seed

    labels = nearest_seed(bcc_seeds(3), 36).astype(np.int32)
    paths = {fmt: tmp_path / f"bcc-{fmt}" for fmt in ("npy", "tiff", "dream3d", "vti", "tesr")}
    with open(paths["npy"], "wb") as out:
        np.save(out, labels)
    tifffile.imwrite(paths["tiff"], labels)
    write_dream3d(paths["dream3d"], labels)
    write_vti(paths["vti"], labels, "appended-base64", compressor="zlib")
    write_tesr(paths["tesr"], labels, "binary16")
    paths["spparks"] = _dump(tmp_path, spparks_snapshot(labels, 0, 0.0, range(labels.size)))
    return paths


def test_every_format_classifies_to_the_same_truncated_octahedra(tmp_path):
    """``classify --periodic xyz`` of one image in each format, its format sniffed: every grain
    a truncated octahedron (6 squares, 8 hexagons: the BCC lattice's Voronoi cell), 864 voxels,
    the same rows in every format, and each volume the voxels times the file's voxel size."""
    import pyarrow.parquet as pq
    from click.testing import CliRunner

    from grainclass.cli import cli

    spacings = {"dream3d": SPACING, "vti": SPACING, "tesr": SPACING}
    tables = {}
    for fmt, path in _bcc_in_every_format(tmp_path).items():
        out = tmp_path / f"{fmt}.parquet"
        result = CliRunner().invoke(
            cli, ["classify", str(path), "--periodic", "xyz", "-o", str(out), "-q"]
        )
        assert result.exit_code == 0, (fmt, result.output)
        tables[fmt] = pq.read_table(out).to_pylist()
    for fmt, rows in tables.items():
        assert [row["grain_id"] for row in rows] == [str(i) for i in range(1, 55)], fmt
        assert {(row["status"], row["n_faces"], tuple(row["p_vector"])) for row in rows} == {
            ("ok", 14, (0, 6, 0, 8))
        }, fmt
        assert {row["voxels"] for row in rows} == {864}, fmt
        voxel = np.prod(spacings.get(fmt, (1.0, 1.0, 1.0)))
        assert [row["volume"] for row in rows] == pytest.approx([864 * voxel] * 54), fmt
    shared = ("grain_id", "status", "n_faces", "weinberg", "chirality", "shortest_triple_line")
    first = [{k: row[k] for k in shared} for row in tables["npy"]]
    for fmt, rows in tables.items():
        assert [{k: row[k] for k in shared} for row in rows] == first, fmt


def test_damask_grid_classifies_as_damask_reads_it(tmp_path):
    """The .vti DAMASK wrote gives, grain by grain, the rows of DAMASK's own reading of it
    saved as .npy: voxels as numpy counts them, volumes at DAMASK's 0.1 cell size."""
    import pyarrow.parquet as pq
    from click.testing import CliRunner

    from grainclass.cli import cli

    material = np.load(DATA / "damask-voronoi.material.npy").transpose(2, 1, 0)
    npy = tmp_path / "damask.npy"
    np.save(npy, np.ascontiguousarray(material))
    tables = {}
    for name, path in (("vti", DATA / "damask-voronoi.vti"), ("npy", npy)):
        out = tmp_path / f"{name}.parquet"
        result = CliRunner().invoke(
            cli, ["classify", str(path), "--periodic", "xyz", "-o", str(out), "-q"]
        )
        assert result.exit_code == 0, result.output
        tables[name] = pq.read_table(out).to_pylist()
    labels, counts = np.unique(material, return_counts=True)
    assert [row["grain_id"] for row in tables["vti"]] == [str(i) for i in labels]
    assert [row["voxels"] for row in tables["vti"]] == counts.tolist()
    assert [row["volume"] for row in tables["vti"]] == pytest.approx((counts * 1e-3).tolist())
    shared = ("grain_id", "status", "error", "n_faces", "weinberg", "class", "boundary")

    def rows(name, path):
        return [
            {k: r[k] if k != "error" else (r[k] or "").replace(str(path), "FILE") for k in shared}
            for r in tables[name]
        ]

    assert rows("vti", DATA / "damask-voronoi.vti") == rows("npy", npy)
