"""Label images written by hand in each format's documented layout, for tests/test_image_formats.py:
VTK XML image data in every encoding (VTK's file-format page: the length header, compressed
blocks, base64), Neper raster tessellations (Neper's doc/fileformat.rst), SPPARKS site dumps
(SPPARKS's dump_text.cpp) and DREAM.3D's HDF5 layout (SIMPL's ImageGeom::writeGeometryToHDF5).
Nothing here comes from grainclass: the readers are checked against these writers."""

from __future__ import annotations

import base64
import lzma
import zlib

import numpy as np

# The image every format holds, indexed [z, y, x]: 5 slices of 6 rows of 7 columns, no two axes
# alike, so that a reader that swaps or flips axes gives another array.
LABELS = np.ones((5, 6, 7), dtype=np.int32)
LABELS[:, :, 3:] = 2
LABELS[:2, :4, 3:] = 3
LABELS[3:, :2, :2] = 5
LABELS[4, 5, 6] = 4
LABELS[0, 5, 0] = 0
SPACING = (0.5, 0.25, 2.0)  # x, y, z

VTK_TYPES = {"i1": "Int8", "u1": "UInt8", "i2": "Int16", "u2": "UInt16", "i4": "Int32",
             "u4": "UInt32", "i8": "Int64", "u8": "UInt64", "f4": "Float32",
             "f8": "Float64"}  # fmt: skip


def _vtk_type(dtype: np.dtype) -> str:
    return VTK_TYPES[f"{dtype.kind}{dtype.itemsize}"]


def vti_payload(
    values: np.ndarray, header: str = "UInt32", order: str = "<", compressor=None, block=64
) -> tuple[bytes, bytes]:
    """(length header, data) of an array as VTK's binary encodings store it: uncompressed,
    the header is the data's byte count; compressed, the data are cut into blocks of ``block``
    bytes, each compressed, and the header lists their number, the block size, the size of the
    last block (0 if whole) and each block's compressed size."""
    word = np.dtype(f"{order}u{4 if header == 'UInt32' else 8}")
    raw = np.ascontiguousarray(values.astype(values.dtype.newbyteorder(order))).tobytes()
    if compressor is None:
        return np.array([len(raw)], dtype=word).tobytes(), raw
    pieces = [raw[i : i + block] for i in range(0, len(raw), block)]
    compress = zlib.compress if compressor == "zlib" else lzma.compress
    packed = [compress(piece) for piece in pieces]
    last = len(raw) % block
    words = [len(pieces), block, last, *(len(p) for p in packed)]
    return np.array(words, dtype=word).tobytes(), b"".join(packed)


def write_vti(
    path,
    labels: np.ndarray = LABELS,
    encoding: str = "appended-raw",
    *,
    header: str = "UInt32",
    order: str = "<",
    compressor: str | None = None,
    name: str = "material",
    kind: str = "CellData",
    extra_arrays: str = "",
    joint_base64: bool = True,
    spacing=SPACING,
    block: int = 64,
) -> None:
    """A .vti file of ``labels`` ([z, y, x]) in one encoding: ``ascii``, ``binary`` (base64
    inline), ``appended-raw`` or ``appended-base64``."""
    nz, ny, nx = labels.shape
    less = 1 if kind == "PointData" else 0
    extent = f"0 {nx - less} 0 {ny - less} 0 {nz - less}"
    values = labels.ravel()  # x fastest, then y, then z
    compressors = {"zlib": "vtkZLibDataCompressor", "lzma": "vtkLZMADataCompressor"}
    byte_order = "LittleEndian" if order == "<" else "BigEndian"
    attributes = [
        f'type="ImageData" version="1.0" byte_order="{byte_order}" header_type="{header}"'
    ]
    if compressor:
        attributes.append(f'compressor="{compressors.get(compressor, compressor)}"')
    head, data = vti_payload(values, header, order, compressor, block)
    appended = b""
    if encoding == "ascii":
        fmt, text = "ascii", " ".join(str(v) for v in values)
    elif encoding == "binary":
        if compressor or not joint_base64:  # VTK encodes a compressed array's header apart
            text = (base64.b64encode(head) + base64.b64encode(data)).decode()
        else:
            text = base64.b64encode(head + data).decode()
        fmt = "binary"
    elif encoding == "appended-raw":
        fmt, text, appended = 'appended" offset="0', "", b'<AppendedData encoding="raw">\n   _'
        appended += head + data + b"\n  </AppendedData>\n"
    else:
        encoded = base64.b64encode(head) + base64.b64encode(data)
        fmt, text = 'appended" offset="0', ""
        appended = b'<AppendedData encoding="base64">\n   _' + encoded + b"\n  </AppendedData>\n"
    spacing_text = "" if spacing is None else f' Spacing="{spacing[0]} {spacing[1]} {spacing[2]}"'
    xml = (
        '<?xml version="1.0"?>\n'
        f"<VTKFile {' '.join(attributes)}>\n"
        f'  <ImageData WholeExtent="{extent}" Origin="0 0 0"{spacing_text}>\n'
        f'  <Piece Extent="{extent}">\n'
        f"    <{kind}>\n"
        f"      {extra_arrays}\n"
        f'      <DataArray type="{_vtk_type(values.dtype)}" Name="{name}" format="{fmt}">\n'
        f"        {text}\n"
        "      </DataArray>\n"
        f"    </{kind}>\n"
        "  </Piece>\n"
        "  </ImageData>\n"
    ).encode()
    with open(path, "wb") as out:
        out.write(xml + appended + b"</VTKFile>\n")


def write_tesr(
    path, labels: np.ndarray = LABELS, data_format: str = "ascii", *, ids=None, version="2.1",
    external: str | None = None, dimension: int = 3,
) -> None:  # fmt: skip
    """A Neper .tesr of ``labels`` ([z, y, x]; cells x fastest), with ``*id`` if ``ids``;
    ``external``: the data in that file beside it (``*file``)."""
    nz, ny, nx = labels.shape
    values = labels.ravel()
    lines = [
        "***tesr",
        " **format",
        f"   {version}" + (f" {data_format}" if version == "2.0" else ""),
    ]
    lines += [" **general", f"   {dimension}", f"   {nx} {ny} {nz}",
              f"   {SPACING[0]:.12f} {SPACING[1]:.12f} {SPACING[2]:.12f}",
              "  *origin", "   0 0 0"]  # fmt: skip
    if ids is not None:
        lines += [" **cell", f"   {len(ids)}", "  *id", "   " + " ".join(map(str, ids))]
        lines += ["  *seed"] + [f"   {i + 1} 0.5 0.5 0.5 0" for i in range(len(ids))]
    lines += [" **data"] + ([f"   {data_format}"] if version != "2.0" else [])
    if data_format == "ascii" or not data_format.startswith("binary"):
        body = (" ".join(str(v) for v in values) + "\n").encode()
    else:
        dtype = {"binary8": "u1", "binary16": "<i2", "binary16_big": ">i2", "binary32": "<i4",
                 "binary32_big": ">i4"}.get(data_format, "<i8")  # fmt: skip
        body = values.astype(dtype).tobytes() + b"\n"
    text = ("\n".join(lines) + "\n").encode()
    if external is not None:
        with open(path.parent / external, "wb") as out:
            out.write(body)
        body = f"  *file {external}\n".encode()
    with open(path, "wb") as out:
        out.write(text + body + b"***end\n")


def spparks_snapshot(labels: np.ndarray, step: int, time: float, order, spin="i1") -> str:
    """One snapshot of ``dump 1 text DELTA FILE id i1 x y z`` on a simple cubic lattice of
    spacing 1, sites listed in ``order`` (site ids are 1 + x + nx (y + ny z))."""
    nz, ny, nx = labels.shape
    lines = [
        "ITEM: TIMESTEP", f"{step} {time:10g}", "ITEM: NUMBER OF ATOMS", str(labels.size),
        "ITEM: BOX BOUNDS", f"0 {nx}", f"0 {ny}", f"0 {nz}", f"ITEM: ATOMS id {spin} x y z",
    ]  # fmt: skip
    for site in order:
        z, rest = divmod(int(site), nx * ny)
        y, x = divmod(rest, nx)
        lines.append(f"{site + 1} {labels[z, y, x]} {x} {y} {z} ")
    return "\n".join(lines) + "\n"


def write_dream3d(path, labels: np.ndarray = LABELS, *, containers=("ImageDataContainer",),
                  dimensions=None, nx_layout=False, components=1) -> None:  # fmt: skip
    """A DREAM.3D 6 file: each container with an image geometry and CellData/FeatureIds of
    shape (z, y, x, components)."""
    import h5py

    nz, ny, nx = labels.shape
    with h5py.File(path, "w") as file:
        file.attrs["FileVersion"] = np.bytes_(b"7.0")
        if nx_layout:
            file.create_group("DataStructure").create_group("Image")
            return
        root = file.create_group("DataContainers")
        for name in containers:
            container = root.create_group(name)
            geometry = container.create_group("_SIMPL_GEOMETRY")
            geometry.attrs["GeometryTypeName"] = np.bytes_(b"ImageGeometry")
            geometry.attrs["GeometryType"] = np.uint32(0)
            dims = [nx, ny, nz] if dimensions is None else dimensions
            geometry.create_dataset("DIMENSIONS", data=np.array(dims, dtype=np.int64))
            geometry.create_dataset("ORIGIN", data=np.zeros(3, dtype=np.float32))
            geometry.create_dataset("SPACING", data=np.array(SPACING, dtype=np.float32))
            cells = container.create_group("CellData")
            cells.attrs["AttributeMatrixType"] = np.uint32(3)
            cells.attrs["TupleDimensions"] = np.array([nx, ny, nz], dtype=np.uint64)
            stacked = np.repeat(labels[..., None], components, axis=3)
            ids = cells.create_dataset("FeatureIds", data=stacked, chunks=(1, ny, nx, components))
            ids.attrs["ComponentDimensions"] = np.array([components], dtype=np.uint64)
            ids.attrs["ObjectType"] = np.bytes_(b"DataArray<int32_t>")
