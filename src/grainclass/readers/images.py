"""The formats of 3D label images: how each is opened into a
:class:`~grainclass.readers.label_image.LabelImage`, and how an image is told from its first
bytes.

Images are read by file (memory-mapped or by slab), never from standard input.
"""

from __future__ import annotations

from collections.abc import Callable

from grainclass.readers.dream3d import looks_like_dream3d, open_dream3d
from grainclass.readers.label_image import LabelImage
from grainclass.readers.npy_image import NPY_MAGIC, ZIP_MAGIC, header_says_points, open_npy
from grainclass.readers.spparks import looks_like_spparks, open_spparks
from grainclass.readers.tesr import looks_like_tesr, open_tesr
from grainclass.readers.tiff_image import looks_like_tiff, open_tiff
from grainclass.readers.vti import looks_like_vti, open_vti

# The opener of each image format: path -> LabelImage. Every name is one of
# vocabulary.INPUT_FORMATS.
IMAGE_OPENERS: dict[str, Callable[[str], LabelImage]] = {
    "npy": open_npy,
    "tiff": open_tiff,
    "dream3d": open_dream3d,
    "vti": open_vti,
    "spparks": open_spparks,
    "tesr": open_tesr,
}

# The formats told by their first bytes alone, in the order they are tried.
_LOOKS_LIKE: tuple[tuple[str, Callable[[bytes], bool]], ...] = (
    ("tiff", looks_like_tiff),
    ("dream3d", looks_like_dream3d),
    ("vti", looks_like_vti),
    ("spparks", looks_like_spparks),
    ("tesr", looks_like_tesr),
)


def sniff_image(path: str, head: bytes) -> str | None:
    """The image format of a file from its name and first bytes, or None when it is no image.

    A ``.npy`` file is an image unless its array is points (``grainclass voronoi --points``:
    (n, 3) or (n, 4) floats, or fields); one that is neither is refused as an image, for what
    it is (a 2D array, float labels). A ``.npz`` archive is read as an image (it must hold one
    3D integer array). TIFF, HDF5 (DREAM.3D), VTK image data, SPPARKS dumps and Neper raster
    tessellations are told by their first bytes, whatever the file's name.

    >>> import numpy as np, io
    >>> buffer = io.BytesIO(); np.save(buffer, np.zeros((2, 2, 2), np.uint16))
    >>> sniff_image("a.npy", buffer.getvalue()[:128])
    'npy'
    >>> buffer = io.BytesIO(); np.save(buffer, np.zeros((5, 3)))
    >>> sniff_image("p.npy", buffer.getvalue()[:128]) is None
    True
    >>> sniff_image("grains", b"***tesr\\n **format\\n   2.1\\n")
    'tesr'
    """
    if head.startswith(NPY_MAGIC):
        # A damaged header of integers is refused as an image, saying what is wrong with it.
        return None if header_says_points(head) else "npy"
    if head.startswith(ZIP_MAGIC) and path.lower().endswith(".npz"):
        return "npy"
    for format, looks_like in _LOOKS_LIKE:
        if looks_like(head):
            return format
    return None
