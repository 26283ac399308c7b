"""DREAM.3D files (``.dream3d``: HDF5 in the layout of DREAM.3D 6, SIMPL), read with h5py (the
``images`` extra).

What is read: the cell array ``FeatureIds`` of an image geometry::

    /DataContainers/<container>/CellData/FeatureIds        integers, shape (z, y, x, 1)
    /DataContainers/<container>/_SIMPL_GEOMETRY/DIMENSIONS  voxels along x, y, z
    /DataContainers/<container>/_SIMPL_GEOMETRY/SPACING     voxel size along x, y, z

(``RESOLUTION``, the name DREAM.3D gave the spacing before version 6.5, is read too.) The
array may sit in a cell attribute matrix of another name than ``CellData``; among several of
one container ``CellData`` is taken. The dataset is indexed ``[z, y, x, component]``, so z is
its slowest axis: a slab is one slice of the dataset, read by h5py alone.

Refused: an HDF5 file without ``/DataContainers`` (DREAM3D-NX's ``/DataStructure`` layout is
named as such), no ``FeatureIds`` in any container, ``FeatureIds`` in several containers (they
are named: one image is read), a geometry other than an image (``GeometryTypeName``), a
``DIMENSIONS`` that disagrees with the array's shape, more than one component, float labels,
a spacing that is not three positive numbers.
"""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np

from grainclass.errors import InputError
from grainclass.readers.label_image import (
    LabelImage,
    check_shape,
    checked_slab,
    label_dtype,
    require,
    slabs_of,
)

_HDF5 = b"\x89HDF\r\n\x1a\n"
_USER_BLOCKS = (0, 512, 1024, 2048)  # where HDF5 may put its signature, within 4096 bytes
_ARRAY = "FeatureIds"
_GEOMETRY = "_SIMPL_GEOMETRY"


def looks_like_dream3d(head: bytes) -> bool:
    """True for the first bytes of an HDF5 file (its signature at byte 0, or after a user
    block of 512, 1024 or 2048 bytes); whether it is in DREAM.3D's layout, the opener says.

    >>> looks_like_dream3d(b"\\x89HDF\\r\\n\\x1a\\n" + bytes(8)), looks_like_dream3d(b"II*\\x00")
    (True, False)
    """
    return any(head[at : at + 8] == _HDF5 for at in _USER_BLOCKS)


def _text(value) -> str:
    """An HDF5 string attribute as str, however h5py hands it over."""
    if isinstance(value, np.ndarray):
        value = value.ravel()[0] if value.size else b""
    if isinstance(value, bytes | np.bytes_):
        return bytes(value).decode("utf-8", "replace").rstrip("\x00")
    return str(value)


def _feature_ids(path: str, h5py, file) -> tuple[str, object]:
    """The path of the one ``FeatureIds`` array, and its container."""
    containers = file.get("DataContainers")
    if not isinstance(containers, h5py.Group):
        if "DataStructure" in file:
            raise InputError(
                path,
                "a DREAM3D-NX file (/DataStructure): only the DREAM.3D 6 layout "
                "(/DataContainers) is read",
            )
        raise InputError(path, "an HDF5 file without /DataContainers: not a DREAM.3D file")
    found: dict[str, list[str]] = {}
    for name, container in containers.items():
        if not isinstance(container, h5py.Group):
            continue
        for matrix_name, matrix in container.items():
            if isinstance(matrix, h5py.Group) and isinstance(matrix.get(_ARRAY), h5py.Dataset):
                found.setdefault(name, []).append(matrix_name)
    if not found:
        names = ", ".join(sorted(containers)) or "none"
        raise InputError(path, f"no {_ARRAY} array in any data container (containers: {names})")
    if len(found) > 1:
        raise InputError(
            path,
            f"{_ARRAY} in {len(found)} data containers ({', '.join(sorted(found))}): "
            "one image is read",
        )
    ((name, matrices),) = found.items()
    matrix = "CellData" if "CellData" in matrices else sorted(matrices)[0]
    return f"DataContainers/{name}/{matrix}/{_ARRAY}", containers[name]


def _geometry(path: str, h5py, container, shape) -> tuple[float, float, float] | None:
    """The spacing along x, y, z, after checking the geometry against the array's shape."""
    geometry = container.get(_GEOMETRY)
    if not isinstance(geometry, h5py.Group):
        return None
    kind = geometry.attrs.get("GeometryTypeName")
    if kind is not None and _text(kind) != "ImageGeometry":
        raise InputError(path, f"a {_text(kind)}, not an ImageGeometry: a label image is read")
    nz, ny, nx = shape
    dims = geometry.get("DIMENSIONS")
    if isinstance(dims, h5py.Dataset):
        got = np.asarray(dims[()]).ravel()
        if got.shape != (3,) or tuple(int(n) for n in got) != (nx, ny, nz):
            raise InputError(
                path,
                f"{_GEOMETRY}/DIMENSIONS is {got.tolist()}, but {_ARRAY} holds "
                f"{nx} x {ny} x {nz} voxels (x, y, z)",
            )
    for name in ("SPACING", "RESOLUTION"):
        spacing = geometry.get(name)
        if isinstance(spacing, h5py.Dataset):
            values = np.asarray(spacing[()], dtype=np.float64).ravel()
            if values.shape != (3,) or not (np.isfinite(values).all() and (values > 0).all()):
                raise InputError(
                    path, f"{_GEOMETRY}/{name} is {values.tolist()}: three positive numbers"
                )
            return (float(values[0]), float(values[1]), float(values[2]))
    return None


def _open(path: str, h5py):
    try:
        return h5py.File(path, "r")
    except Exception as exc:  # h5py raises many kinds on a damaged file
        raise InputError(path, f"not an HDF5 file h5py can read ({exc})") from None


def open_dream3d(path: str) -> LabelImage:
    """Open the ``FeatureIds`` of a DREAM.3D file as a :class:`LabelImage` (see the module's
    docstring).

    Parameters
    ----------
    path : str
        The ``.dream3d`` file.

    Returns
    -------
    LabelImage
        Shape ``(z, y, x)`` of ``FeatureIds``, its integer type, the geometry's spacing.

    Raises
    ------
    InputError
        For what the module's docstring says is refused.
    MissingDependencyError
        Without h5py.
    """
    h5py = require("h5py", "DREAM.3D files")
    with _open(path, h5py) as file:
        try:
            name, container = _feature_ids(path, h5py, file)
            dataset = file[name]
            raw_shape = tuple(int(n) for n in dataset.shape)
            if len(raw_shape) == 4 and raw_shape[3] != 1:
                raise InputError(
                    path, f"{name} has {raw_shape[3]} components per voxel: labels have one"
                )
            if len(raw_shape) not in (3, 4):
                raise InputError(
                    path, f"{name} has shape {raw_shape}: expected (z, y, x, 1) or (z, y, x)"
                )
            dtype = label_dtype(path, dataset.dtype, name)
            shape = check_shape(path, raw_shape[:3])
            spacing = _geometry(path, h5py, container, shape)
        except InputError:
            raise
        except Exception as exc:  # h5py raises many kinds (RuntimeError too) on a damaged file
            raise InputError(path, f"cannot be read as a DREAM.3D file ({exc})") from None

    def slabs(depth: int) -> Iterator[np.ndarray]:
        with _open(path, h5py) as file:
            try:
                dataset = file.get(name)
            except Exception as exc:  # h5py raises many kinds on a damaged file
                raise InputError(path, f"{name} cannot be read ({exc})") from None
            if not isinstance(dataset, h5py.Dataset) or dataset.shape != raw_shape:
                raise InputError(path, "the file changed since it was opened")
            for z0, z1 in slabs_of(shape[0], depth):
                try:
                    slab = dataset[z0:z1, :, :, 0] if len(raw_shape) == 4 else dataset[z0:z1]
                except Exception as exc:  # h5py raises many kinds on a damaged chunk
                    raise InputError(
                        path, f"{name}: z = {z0} to {z1 - 1} cannot be read ({exc})"
                    ) from None
                yield checked_slab(path, np.ascontiguousarray(slab, dtype=dtype), z0)

    return LabelImage(path, shape, dtype, spacing, slabs)
