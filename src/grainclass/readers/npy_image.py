"""Label images stored by NumPy: a ``.npy`` file of one 3D integer array indexed ``[z, y, x]``,
or a ``.npz`` archive holding exactly one such array.

A ``.npy`` file is read slab by slab (memory-mapped where it is in Fortran order), so an image
larger than memory is never held whole; an array in a ``.npz`` archive cannot be mapped (it may
be compressed) and is read whole. The header is checked before a voxel is read: three axes,
integer labels, and as many bytes as the header promises (a file cut short is named as such,
not read as garbage).
"""

from __future__ import annotations

import io
import re
import zipfile
from collections.abc import Iterator

import numpy as np

from grainclass.errors import InputError
from grainclass.readers.label_image import LabelImage, check_shape, in_memory

NPY_MAGIC = b"\x93NUMPY"
ZIP_MAGIC = b"PK\x03\x04"


def npy_header(handle) -> tuple[tuple[int, ...], bool, np.dtype, int]:
    """``(shape, fortran_order, dtype, data_offset)`` of the ``.npy`` stream at its start.

    Raises ValueError for anything that is not a ``.npy`` header."""
    from tokenize import TokenError

    major, _ = np.lib.format.read_magic(handle)
    try:
        if major == 1:
            shape, fortran, dtype = np.lib.format.read_array_header_1_0(handle)
        elif major in (2, 3):
            shape, fortran, dtype = np.lib.format.read_array_header_2_0(handle)
        else:
            raise ValueError(f"NumPy format version {major} is not known")
    # numpy reads the header's dictionary with Python's tokenizer and literal_eval: a damaged
    # one raises what they raise.
    except (SyntaxError, TokenError, TypeError, OverflowError, EOFError, KeyError) as exc:
        raise ValueError(f"a damaged header: {exc}") from None
    return tuple(int(n) for n in shape), bool(fortran), np.dtype(dtype), handle.tell()


def is_label_array(shape: tuple[int, ...], dtype: np.dtype) -> bool:
    """A 3D array of integers: a label image."""
    return len(shape) == 3 and dtype.kind in "iu"


_DESCR = re.compile(rb"""['"]descr['"]\s*:\s*['"][<>|=]?([a-zA-Z])""")


def header_says_points(head: bytes) -> bool:
    """Whether the first bytes of a ``.npy`` file are points: by its header, or, for a header
    cut short or damaged, by the kind of number its ``descr`` names (floats are points)."""
    try:
        shape, _, dtype, _ = npy_header(io.BytesIO(head))
    except ValueError:
        kind = _DESCR.search(head)
        return kind is not None and kind.group(1) == b"f"
    return looks_like_points(shape, dtype)


def looks_like_points(shape: tuple[int, ...], dtype: np.dtype) -> bool:
    """An array of points (``grainclass voronoi --points``): (n, 3) or (n, 4) floats, or a
    structured array. Any other array is taken for an image, to be refused as one if it is
    not."""
    if dtype.names:
        return True
    return len(shape) == 2 and shape[1] in (3, 4) and dtype.kind == "f"


def _why_not(shape: tuple[int, ...], dtype: np.dtype) -> str | None:
    """What keeps an array from being a label image, or None."""
    if len(shape) != 3:
        return (
            f"a {len(shape)}D array (shape {shape}): a label image has three axes, "
            "indexed [z, y, x]"
        )
    if dtype.kind not in "iu":
        return f"its voxels are {dtype}: a label image holds integer grain ids"
    return None


def open_npy(path: str) -> LabelImage:
    """Open a ``.npy`` or ``.npz`` label image (see the module's docstring).

    Raises
    ------
    InputError
        A file that cannot be opened, is no NumPy file, is not one 3D integer array, or is cut
        short; an archive with no such array, or several.
    """
    try:
        with open(path, "rb") as handle:
            head = handle.read(len(ZIP_MAGIC))
    except OSError as exc:
        raise InputError(path, exc.strerror or str(exc)) from None
    if head.startswith(ZIP_MAGIC):
        return _open_npz(path)
    return _open_npy(path)


def _open_npy(path: str) -> LabelImage:
    import os

    try:
        with open(path, "rb") as handle:
            shape, fortran, dtype, offset = npy_header(handle)
        size = os.path.getsize(path)
    except OSError as exc:
        raise InputError(path, exc.strerror or str(exc)) from None
    except ValueError as exc:
        raise InputError(path, f"not a NumPy .npy file ({exc})") from None
    why = _why_not(shape, dtype)
    if why:
        raise InputError(path, why)
    expected = offset + int(np.prod(shape)) * dtype.itemsize
    if size < expected:
        raise InputError(
            path, f"cut short: {size} bytes, but its header promises {expected} ({shape} {dtype})"
        )
    nz, ny, nx = check_shape(path, shape)
    if fortran:  # z varies fastest on disk: a slab is strided, read through a memory map
        voxels = np.memmap(path, dtype=dtype, mode="r", offset=offset, shape=shape, order="F")

        def slabs(depth: int) -> Iterator[np.ndarray]:
            for z in range(0, nz, depth):
                yield np.ascontiguousarray(voxels[z : z + depth])

        return LabelImage(path, (nz, ny, nx), dtype, None, slabs)

    def slabs(depth: int) -> Iterator[np.ndarray]:
        # Read, not mapped: pages of a map that were read count as the process's memory until
        # the system takes them back, a whole 4 GB image by the end of a pass.
        plane = ny * nx
        with open(path, "rb") as handle:
            handle.seek(offset)
            for z in range(0, nz, depth):
                k = min(depth, nz - z)
                slab = np.fromfile(handle, dtype=dtype, count=k * plane)
                if slab.size != k * plane:
                    raise InputError(path, f"cut short at plane {z} of {nz}")
                yield slab.reshape(k, ny, nx)

    return LabelImage(path, (nz, ny, nx), dtype, None, slabs)


def _open_npz(path: str) -> LabelImage:
    try:
        with zipfile.ZipFile(path) as archive:
            found: list[tuple[str, tuple[int, ...], np.dtype]] = []
            for name in archive.namelist():
                if not name.endswith(".npy"):
                    continue
                with archive.open(name) as member:
                    head = io.BytesIO(member.read(1 << 16))
                try:
                    shape, _, dtype, _ = npy_header(head)
                except ValueError:
                    continue
                found.append((name[: -len(".npy")], shape, dtype))
            images = [item for item in found if is_label_array(item[1], item[2])]
            if len(images) != 1:
                listed = ", ".join(
                    f"{n} ({'x'.join(map(str, s)) or 'scalar'} {d})" for n, s, d in found
                )
                what = "no 3D integer array" if not images else "several 3D integer arrays"
                raise InputError(
                    path,
                    f"{what}: a .npz label image holds one (it holds {listed or 'no arrays'}); "
                    "save the one to read with numpy.save as a .npy file",
                )
            with archive.open(images[0][0] + ".npy") as member:
                labels = np.lib.format.read_array(member)
    except (OSError, zipfile.BadZipFile, EOFError) as exc:
        raise InputError(path, f"cannot read this .npz archive: {exc}") from None
    except ValueError as exc:
        raise InputError(path, f"cannot read this .npz archive: {exc}") from None
    check_shape(path, labels.shape)
    return in_memory(path, labels)
