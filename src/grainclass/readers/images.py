"""The formats of 3D label images: how each is opened into a
:class:`~grainclass.readers.label_image.LabelImage`, and how an image is told from its first
bytes.

Images are read by file (memory-mapped or by slab), never from standard input.
"""

from __future__ import annotations

from collections.abc import Callable

from grainclass.readers.label_image import LabelImage
from grainclass.readers.npy_image import NPY_MAGIC, ZIP_MAGIC, header_says_points, open_npy

# The opener of each image format: path -> LabelImage. Every name is one of
# vocabulary.INPUT_FORMATS.
IMAGE_OPENERS: dict[str, Callable[[str], LabelImage]] = {
    "npy": open_npy,
}


def sniff_image(path: str, head: bytes) -> str | None:
    """The image format of a file from its name and first bytes, or None when it is no image.

    A ``.npy`` file is an image unless its array is points (``grainclass voronoi --points``:
    (n, 3) or (n, 4) floats, or fields); one that is neither is refused as an image, for what
    it is (a 2D array, float labels). A ``.npz`` archive is read as an image (it must hold one
    3D integer array).

    >>> import numpy as np, io
    >>> buffer = io.BytesIO(); np.save(buffer, np.zeros((2, 2, 2), np.uint16))
    >>> sniff_image("a.npy", buffer.getvalue()[:128])
    'npy'
    >>> buffer = io.BytesIO(); np.save(buffer, np.zeros((5, 3)))
    >>> sniff_image("p.npy", buffer.getvalue()[:128]) is None
    True
    """
    if head.startswith(NPY_MAGIC):
        # A damaged header of integers is refused as an image, saying what is wrong with it.
        return None if header_says_points(head) else "npy"
    if head.startswith(ZIP_MAGIC) and path.lower().endswith(".npz"):
        return "npy"
    return None
