"""Arrow string arrays straight from kernel buffers (no Python object per row)."""

from __future__ import annotations

import numpy as np
import pyarrow as pa

from grainclass._kernels.columns import _decimal_strings, _strings_from_codes


def string_array(
    offsets: np.ndarray, data: np.ndarray, valid: np.ndarray | None = None
) -> pa.Array:
    """A string array from int32 offsets and UTF-8 bytes; ``valid`` (bool) marks non-nulls."""
    bitmap = None if valid is None else pa.py_buffer(np.packbits(valid, bitorder="little"))
    return pa.Array.from_buffers(
        pa.string(), len(offsets) - 1, [bitmap, pa.py_buffer(offsets), pa.py_buffer(data)]
    )


def strings_from_codes(codes: np.ndarray, names: tuple[str, ...]) -> pa.Array:
    """``names[code]`` per row, null where the code is negative."""
    encoded = [name.encode() for name in names]
    table = np.frombuffer(b"".join(encoded), np.uint8)
    name_offsets = np.concatenate([[0], np.cumsum([len(e) for e in encoded])]).astype(np.int64)
    offsets, data = _strings_from_codes(np.asarray(codes, np.int64), table, name_offsets)
    return string_array(offsets, data, None if (codes >= 0).all() else codes >= 0)


def repeated_string(value: str, length: int) -> pa.Array:
    """The same string ``length`` times."""
    return strings_from_codes(np.zeros(length, np.int64), (value,))


def decimal_strings(values: np.ndarray) -> pa.Array:
    """Non-negative integers written as decimal strings ("1", "2", ...)."""
    offsets, data = _decimal_strings(np.asarray(values, np.int64))
    return string_array(offsets, data)
