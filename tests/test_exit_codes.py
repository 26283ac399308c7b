"""Exit codes are one enum, and every command's help lists them as the enum says."""

from __future__ import annotations

import signal

import pytest
from click.testing import CliRunner

from grainclass.cli import cli
from grainclass.cli.exit_codes import ExitCode


def test_exit_codes_follow_unix_habits():
    assert [int(code) for code in ExitCode] == [0, 1, 2, 129, 130, 141, 143]
    assert ExitCode.stopped_by(signal.SIGINT) is ExitCode.INTERRUPTED
    assert ExitCode.stopped_by(signal.SIGTERM) == 143
    assert ExitCode.stopped_by(signal.SIGHUP) == 129


@pytest.mark.parametrize("command", sorted(cli.commands))
def test_every_epilog_lists_the_codes(command):
    result = CliRunner().invoke(cli, [command, "--help"])
    assert result.exit_code == ExitCode.OK
    section = result.output.split("Exit codes:", 1)[1]
    codes = [line.split()[0] for line in section.splitlines() if line[:6].strip().isdigit()]
    assert codes == ["0", "1", "2", "130", "141"]
    assert "129, 143: SIGHUP, SIGTERM" in " ".join(section.split())


def test_a_usage_error_exits_2():
    result = CliRunner().invoke(cli, ["classify", "--chunk-size", "0", "-"])
    assert result.exit_code == ExitCode.USAGE
