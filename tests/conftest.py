"""Shared fixtures: the plantri binary shipped by passagemath-plantri, and example paths."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import threading
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


class DieOnce:
    """A Dask worker plugin, the tests' hook: the worker that starts the task of part ``name``
    dies (os._exit) once, at once or, given ``writing``, as soon as the part's temporary file
    is in that folder. The file ``marker`` says it has died."""

    def __init__(self, name: str, marker: str, writing: str | None) -> None:
        self.name, self.marker, self.writing = name, marker, writing

    def transition(self, key, start, finish, **kwargs):
        if finish != "executing" or self.name not in str(key) or os.path.exists(self.marker):
            return
        Path(self.marker).touch()
        if self.writing is None:
            os._exit(1)

        def die_while_writing() -> None:
            while not [f for f in os.listdir(self.writing) if f.startswith(f".{self.name}")]:
                time.sleep(0.001)
            os._exit(1)

        threading.Thread(target=die_while_writing, daemon=True).start()


def die_once(name: str, marker: Path, writing: Path | None = None):
    """A :class:`DieOnce` worker plugin to register with a Dask client."""
    from distributed.diagnostics.plugin import WorkerPlugin

    plugin = type("DieOncePlugin", (DieOnce, WorkerPlugin), {})
    return plugin(name, str(marker), None if writing is None else str(writing))
