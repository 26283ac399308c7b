"""Arrow arrays straight from numpy buffers (no Python object per row).

Every column of a classification is built here with ``pa.Array.from_buffers``: besides
skipping a checked conversion per row, this keeps pandas unimported, since ``pa.array`` imports
it, a noticeable part of start-up, to ask whether its input is a pandas object, and ``classify``
never needs it.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import pyarrow as pa

from grainclass._kernels.columns import _decimal_strings, _strings_from_codes
from grainclass.batch import offsets_from_counts
from grainclass.errors import DataError, Remedy


def string_array(
    offsets: np.ndarray, data: np.ndarray, valid: np.ndarray | None = None
) -> pa.Array:
    """A string array from int32 offsets and UTF-8 bytes; ``valid`` (bool) marks non-nulls."""
    return pa.Array.from_buffers(
        pa.string(), len(offsets) - 1, [_bitmap(valid), pa.py_buffer(offsets), pa.py_buffer(data)]
    )


def _bitmap(valid: np.ndarray | None) -> pa.Buffer | None:
    """Arrow's validity bitmap, or None when every row is valid."""
    if valid is None or valid.all():
        return None
    return pa.py_buffer(np.packbits(valid, bitorder="little"))


def numbers(values: np.ndarray, type_: pa.DataType, valid: np.ndarray | None = None) -> pa.Array:
    """An integer or float column of ``type_``, null where not ``valid``; values must fit
    ``type_`` (they are cast as numpy casts, unchecked)."""
    data = np.ascontiguousarray(values, _numpy_dtype(type_))
    return pa.Array.from_buffers(type_, len(data), [_bitmap(valid), pa.py_buffer(data)])


def _numpy_dtype(type_: pa.DataType) -> np.dtype:
    """The numpy dtype of a fixed-width integer or float type: ``type_.to_pandas_dtype()``
    imports pandas to answer in older pyarrow (15 to 18 at least)."""
    signed = "i" if pa.types.is_signed_integer(type_) else "u"
    kind = "f" if pa.types.is_floating(type_) else signed
    return np.dtype(f"{kind}{type_.bit_width // 8}")


def floats(values: np.ndarray) -> pa.Array:
    """A float64 column, null where the value is NaN."""
    return numbers(values, pa.float64(), ~np.isnan(values))


def booleans(values: np.ndarray, valid: np.ndarray | None = None) -> pa.Array:
    """A boolean column, null where not ``valid``."""
    data = pa.py_buffer(np.packbits(values, bitorder="little"))
    return pa.Array.from_buffers(pa.bool_(), len(values), [_bitmap(valid), data])


def strings(values: Sequence[str | None]) -> pa.Array:
    """A string column from Python strings, None as null."""
    values = list(values)
    valid = None
    if None in values:
        valid = np.fromiter((value is not None for value in values), bool, len(values))
        values = ["" if value is None else value for value in values]
    text = "".join(values)
    if text.isascii():  # one encode for all: a character is a byte
        data = text.encode("ascii")
        lengths = np.fromiter(map(len, values), np.int64, len(values))
    else:
        encoded = [_utf8(value) for value in values]
        data = b"".join(encoded)
        lengths = np.fromiter(map(len, encoded), np.int64, len(values))
    offsets = offsets_from_counts(lengths)
    if offsets[-1] > np.iinfo(np.int32).max:
        raise DataError("the strings of one batch exceed 2 GB", Remedy("chunk_size"))
    return string_array(offsets.astype(np.int32), np.frombuffer(data, np.uint8), valid)


def _utf8(text: str) -> bytes:
    """``text`` as UTF-8. A file name that is not UTF-8 comes from the system with its bytes
    escaped (surrogates), which UTF-8 cannot hold: they become U+FFFD, as a terminal shows them.
    """
    try:
        return text.encode()
    except UnicodeEncodeError:
        return text.encode("utf-8", "surrogateescape").decode("utf-8", "replace").encode()


def strings_from_codes(codes: np.ndarray, names: tuple[str, ...]) -> pa.Array:
    """``names[code]`` per row, null where the code is negative."""
    encoded = [_utf8(name) for name in names]
    table = np.frombuffer(b"".join(encoded), np.uint8)
    name_offsets = offsets_from_counts([len(e) for e in encoded])
    offsets, data = _strings_from_codes(np.asarray(codes, np.int64), table, name_offsets)
    return string_array(offsets, data, codes >= 0)


def repeated_string(value: str, length: int) -> pa.Array:
    """The same string ``length`` times."""
    return strings_from_codes(np.zeros(length, np.int64), (value,))


def decimal_strings(values: np.ndarray) -> pa.Array:
    """Non-negative integers written as decimal strings ("1", "2", ...)."""
    offsets, data = _decimal_strings(np.asarray(values, np.int64))
    return string_array(offsets, data)
