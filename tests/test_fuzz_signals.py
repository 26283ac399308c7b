"""The CLI mode of ``make fuzz`` once per command: a stop signal half a second into a run (while
the command reads, computes or starts its workers) ends it with 128 + the signal, no traceback,
nothing left behind and no process of its group alive."""

from __future__ import annotations

import signal

import pytest

from fuzz_signals import COMMANDS, prepare, run_case


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    folder = tmp_path_factory.mktemp("signals")
    prepare(folder)
    return folder


@pytest.mark.parametrize("command", COMMANDS, ids=[c.name for c in COMMANDS])
def test_a_stop_signal_ends_each_command_as_documented(data, command):
    signum = signal.SIGINT if COMMANDS.index(command) % 2 else signal.SIGTERM
    outcome, finding = run_case(command, data, signum, delay=0.5)
    assert finding is None, finding
    assert outcome == "stopped"
