"""Every command documents itself, and the README opens with the two commands that set up."""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner

from grainclass.cli import cli
from grainclass.schema import GRAIN_SCHEMA

ROOT = Path(__file__).resolve().parent.parent
README = (ROOT / "README.md").read_text()


@pytest.mark.parametrize("command", sorted(cli.commands))
def test_every_command_has_help(command):
    result = CliRunner().invoke(cli, [command, "--help"])
    assert result.exit_code == 0
    assert cli.commands[command].help
    assert "Exit codes" in result.output


def test_readme_opens_with_make_demo_and_make_test():
    first_block = README.split("```sh\n", 1)[1].split("```", 1)[0].splitlines()
    assert [line.split("#")[0].strip() for line in first_block] == ["make demo", "make test"]


@pytest.mark.parametrize("column", GRAIN_SCHEMA.names)
def test_readme_documents_every_output_column(column):
    assert f"`{column}`" in README


@pytest.mark.parametrize("command", sorted(cli.commands))
def test_readme_documents_every_command(command):
    assert f"grainclass {command}" in README


def test_make_test_lowest_pins_the_lower_bounds_of_pyproject():
    """``make test-lowest`` installs lowest-dependencies.txt: each runtime dependency at the
    lowest version pyproject.toml allows, and no other."""
    import tomllib

    from packaging.requirements import Requirement
    from packaging.version import Version

    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    lowest = {}
    for line in project["dependencies"]:
        requirement = Requirement(line)
        (bound,) = [s.version for s in requirement.specifier if s.operator in (">=", "==")]
        lowest[requirement.name] = Version(bound)
    pinned = {}
    for line in (ROOT / "lowest-dependencies.txt").read_text().splitlines():
        if line and not line.startswith("#"):
            name, version = line.split("==")
            pinned[name] = Version(version)
    assert pinned == lowest
