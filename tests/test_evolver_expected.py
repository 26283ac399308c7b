"""The table of evolver_expected.py against its derivation from the datafiles (no grainclass)."""

from __future__ import annotations

import pytest

from conftest import EVOLVER_DATA, EVOLVER_FIXTURES
from evolver_derivation import foam_file_values, grain_file_values
from evolver_expected import FIXTURES, FOAMS


def _to_table_digits(value):
    """``value`` with its floats rounded to the table's 9 significant digits."""
    if isinstance(value, float):
        return float(f"{value:.9g}")
    if isinstance(value, dict):
        return {key: _to_table_digits(item) for key, item in value.items()}
    if isinstance(value, tuple):
        return tuple(_to_table_digits(item) for item in value)
    return value


def _assert_agrees(derived: dict, table: dict) -> None:
    assert sorted(derived) == sorted(table)
    for key, value in table.items():
        assert (key, _to_table_digits(derived[key])) == (key, value)


def test_the_table_has_an_entry_for_every_datafile():
    assert sorted(p.name for p in EVOLVER_FIXTURES.glob("*.fe")) == sorted(FIXTURES)
    assert sorted(p.name for p in EVOLVER_DATA.glob("*.fe")) == sorted(FOAMS)


@pytest.mark.parametrize("name", sorted(FIXTURES))
def test_grain_file_entry_is_what_the_derivation_finds(name):
    _assert_agrees(grain_file_values(EVOLVER_FIXTURES / name), FIXTURES[name])


@pytest.mark.parametrize("name", sorted(FOAMS))
def test_foam_file_entry_is_what_the_derivation_finds(name):
    _assert_agrees(foam_file_values(EVOLVER_DATA / name), FOAMS[name])
