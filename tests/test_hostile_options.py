"""Every option of every command, given a hostile value (huge, negative, NaN, infinite, empty,
any text): no traceback, an exit code the command's help lists, and nothing left behind by a
run that fails."""

from __future__ import annotations

import shutil
import warnings
from pathlib import Path

import click
import pytest
from click.testing import CliRunner
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from grainclass.cli import cli

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"

HOSTILE = [
    "",
    "0",
    "-1",
    "-0",
    "1e309",
    "nan",
    "NaN",
    "inf",
    "-inf",
    "9" * 30,
    "-" + "9" * 30,
    "0.5",
    "1,2,3",
    " ",
    "\u00e9",
    "--",
    "a=b=c",
    "/dev/null",
    "-",
]

# A run of each command on small inputs, into the folder it runs in, with the options it
# needs; "{out}" is an output of the command's own kind.
BASES = {
    "classify": ["classify", "grains.txt", "-o", "out.parquet", "-q"],
    "summarize": ["summarize", "grains.txt", "-o", "out.txt", "-q"],
    "types": ["types", "grains.txt", "-o", "out.txt", "-q"],
    "penalties": ["penalties", "grains.txt", "-o", "out.txt", "-q"],
    "perturb": ["perturb", "grains.txt", "--flips", "1", "-o", "out.txt", "-q"],
    "plot": ["plot", "round", "grains.txt", "-o", "out.png", "-q"],
    "voronoi": ["voronoi", "30", "-o", "out.txt", "-q"],
}


def _options(command: str) -> list[str]:
    """The long flags of ``command`` that take a value."""
    return sorted(
        flag
        for param in cli.commands[command].params
        if isinstance(param, click.Option) and not param.is_flag and not param.hidden
        for flag in param.opts
        if flag.startswith("--")
    )


CASES = [(command, flag) for command in BASES for flag in _options(command)]


def _documented_codes(command: str) -> set[int]:
    help_text = CliRunner().invoke(cli, [command, "--help"]).output
    section = help_text.split("Exit codes:", 1)[1]
    return {int(line.split()[0]) for line in section.splitlines() if line[:6].strip().isdigit()}


CODES = {command: _documented_codes(command) for command in BASES}


def test_the_cases_cover_every_option_that_takes_a_value():
    assert ("classify", "--chunk-size") in CASES
    assert ("plot", "--times") in CASES
    assert ("voronoi", "--box") in CASES
    assert len(CASES) >= 50


@settings(
    max_examples=250,
    deadline=None,
    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow],
)
@given(
    case=st.sampled_from(CASES),
    value=st.sampled_from(HOSTILE) | st.text(max_size=12),
)
def test_a_hostile_option_value_ends_in_a_documented_way(tmp_path_factory, case, value):
    command, flag = case
    folder = tmp_path_factory.mktemp("run")
    shutil.copy(EXAMPLES / "polytopes.txt", folder / "grains.txt")
    args = [*BASES[command], flag, value]
    before = {p.name for p in folder.iterdir()}
    with warnings.catch_warnings(record=True), pytest.MonkeyPatch.context() as patch:
        warnings.simplefilter("always")
        patch.chdir(folder)
        result = CliRunner().invoke(cli, args)
    where = f"{' '.join(args)!r}: {result.stderr}"
    assert result.exception is None or isinstance(result.exception, SystemExit), (
        f"{where} {result.exception!r}"
    )
    assert result.exit_code in CODES[command], where
    assert "Traceback" not in result.stderr, where
    if result.exit_code:
        assert sum(line.startswith("Error: ") for line in result.stderr.splitlines()) == 1, where
        assert {p.name for p in folder.iterdir()} == before, where


# Values the census can use start a cluster of worker processes and run it: an output folder
# is given only values it must refuse, the other options all of HOSTILE (which they refuse,
# or which name nothing the census can run or reach).
CENSUS = {
    flag: ["", "-", "/dev/null", "\x00"] if flag == "--output" else HOSTILE
    for flag in _options("census")
}


@pytest.mark.parametrize("flag", sorted(CENSUS))
def test_hostile_census_options_end_in_a_documented_way(tmp_path, monkeypatch, flag):
    monkeypatch.chdir(tmp_path)
    codes = _documented_codes("census")
    for value in CENSUS[flag]:
        args = ["census", "4", "-o", "census", "--workers", "1", "-q", flag, value]
        result = CliRunner().invoke(cli, args)
        where = f"{' '.join(args)!r}: {result.stderr}"
        assert result.exception is None or isinstance(result.exception, SystemExit), where
        assert result.exit_code in codes, where
        assert "Traceback" not in result.stderr, where
        assert result.exit_code != 0, where
