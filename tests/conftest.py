"""Shared fixtures: the plantri binary shipped by passagemath-plantri, and example paths."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path

import pytest

from grainclass.plantri import find_plantri

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"
EVOLVER_DATA = ROOT / "tests" / "data" / "evolver"  # hand-made Surface Evolver foams
EVOLVER_FIXTURES = EVOLVER_DATA / "grain3d"  # grains of a grain-growth simulation


@pytest.fixture(scope="session")
def plantri() -> str:
    return find_plantri()


@pytest.fixture(scope="session")
def plantri_output(plantri, tmp_path_factory):
    """``plantri_output(n)``: path of a file holding every triangulation with n vertices."""
    directory = tmp_path_factory.mktemp("plantri")

    def make(n: int, *flags: str) -> Path:
        path = directory / f"plantri{''.join(flags)}-{n}.pc"
        if not path.exists():
            subprocess.run([plantri, *flags, str(n), str(path)], check=True, capture_output=True)
        return path

    return make


def pytest_configure(config):
    # Tests run the real console script in subprocesses; make sure numba's cache is writable.
    os.environ.setdefault("NUMBA_CACHE_DIR", str(ROOT / "build" / "numba-cache"))
    # A suite started in the background (`make test &`, nohup) inherits SIGINT and SIGHUP
    # ignored, and so would every command it starts, which keeps them ignored as a command
    # does: the tests that stop a command with them need them as a terminal gives them.
    if signal.getsignal(signal.SIGINT) == signal.SIG_IGN:
        signal.signal(signal.SIGINT, signal.default_int_handler)
    if signal.getsignal(signal.SIGHUP) == signal.SIG_IGN:
        signal.signal(signal.SIGHUP, signal.SIG_DFL)


def has_children(pid: int) -> bool:
    """Whether process ``pid`` has started a child process (from any of its threads)."""
    tasks = Path(f"/proc/{pid}/task")
    return any((task / "children").read_text().strip() for task in tasks.iterdir())


def ctrl_c_at_a_terminal(*args: str, when: Callable[[int], bool] = has_children) -> tuple[int, str]:
    """Run ``grainclass ARGS`` in a process group of its own, as a terminal runs a command, and
    send the group SIGINT (a terminal's Ctrl-C) once ``when(pid)`` holds, 0.05 s later (by
    default: its workers are starting up, importing, where Ctrl-C hurt them): (exit code,
    standard error)."""
    run = subprocess.Popen(
        [sys.executable, "-m", "grainclass", *args],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        start_new_session=True,
    )
    deadline = time.monotonic() + 60
    while not when(run.pid):
        assert time.monotonic() < deadline
        assert run.poll() is None
        time.sleep(0.02)
    time.sleep(0.05)
    os.killpg(run.pid, signal.SIGINT)
    _, err = run.communicate(timeout=60)
    return run.returncode, err.decode()
