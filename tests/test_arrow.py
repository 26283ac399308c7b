"""Columns built from numpy buffers equal what pyarrow's own conversion makes of the values."""

from __future__ import annotations

import numpy as np
import pyarrow as pa

from grainclass.arrow import booleans, floats, numbers, strings


def test_strings_with_nulls_empty_and_non_ascii():
    values = ["a", None, "", "grain é ü 粒", None]
    assert strings(values).equals(pa.array(values, pa.string()))
    assert strings([]).equals(pa.array([], pa.string()))


def test_numbers_null_where_not_valid():
    values = np.array([1, -2, 3, 2**31 - 1], np.int64)
    valid = np.array([True, False, True, True])
    expected = pa.array([1, None, 3, 2**31 - 1], pa.int32())
    assert numbers(values, pa.int32(), valid).equals(expected)
    assert numbers(values, pa.int64()).equals(pa.array(values.tolist(), pa.int64()))


def test_floats_null_where_nan():
    values = np.array([1.5, np.nan, -0.0, np.inf])
    assert floats(values).equals(pa.array([1.5, None, -0.0, np.inf], pa.float64()))


def test_booleans_null_where_not_valid_over_more_than_one_byte():
    rng = np.random.default_rng(7)
    values, valid = rng.random(21) < 0.5, rng.random(21) < 0.7
    expected = pa.array([bool(v) if ok else None for v, ok in zip(values, valid, strict=True)])
    assert booleans(values, valid).equals(expected)
    assert booleans(values).equals(pa.array(values.tolist(), pa.bool_()))
