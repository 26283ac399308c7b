"""``make fuzz`` (its CLI mode): every command stopped by SIGINT or SIGTERM at random moments.

Each command runs as the console script, in a process group of its own as a terminal runs it,
on inputs big enough for a run of a second or more; a signal comes at a random moment of a
clean run's time (half of them in its first 0.3 s, while Python imports): SIGINT to the group
(Ctrl-C at a terminal), SIGTERM to the process alone (``kill``, ``timeout``). A finding is a run
that ends otherwise than the exit codes say: a code that is neither 128 + the signal nor 0 (the
run ended before the signal took effect, its outputs whole), a traceback on standard error, a
file left in the run's folder by a stopped run (a census keeps what it finished, never a
temporary), or a process of the group still alive 10 s after the run ended.

A signal that comes while the Python interpreter itself starts, before any of grainclass runs,
ends the process as Python ends it: by the signal (a shell reports 128 + N all the same), after
Ctrl-C with Python's KeyboardInterrupt traceback, or while the interpreter initializes (its
standard streams, ``site``) with a fatal error and exit 1. Such runs are counted apart; one is
a finding if its traceback shows a frame of grainclass past the loading of its entry point, or
it left a file.
"""

from __future__ import annotations

import argparse
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

# The console script, as users run it, beside this interpreter.
GRAINCLASS = [str(Path(sys.executable).with_name("grainclass"))]

# A frame of grainclass's code past the entry point (which takes the signals as it loads).
RUNNING = re.compile(r'File ".*/grainclass/(?!__init__\.py|__main__\.py)')


@dataclass(frozen=True)
class Command:
    """A run of one command: its arguments (inputs from ``{data}``, outputs into the run's
    folder, the current directory) and the outputs a whole run leaves."""

    name: str
    args: list[str]
    outputs: list[str]


COMMANDS = [
    Command("classify", ["classify", "{data}/cells.txt", "-o", "out.parquet"], ["out.parquet"]),
    Command("summarize", ["summarize", "{data}/cells.txt", "-o", "out.txt"], ["out.txt"]),
    Command("types", ["types", "{data}/cells.txt", "-o", "out.txt"], ["out.txt"]),
    Command("penalties", ["penalties", "{data}/cells.txt", "-o", "out.txt"], ["out.txt"]),
    Command(
        "perturb",
        ["perturb", "{data}/cells.txt", "--flips", "1", "--seed", "1", "-o", "out.txt"],
        ["out.txt"],
    ),
    Command(
        "plot",
        ["plot", "round", "{data}/cells.parquet", "-o", "out.png", "--data", "out.csv"],
        ["out.png", "out.csv"],
    ),
    Command(
        "draw",
        ["draw", "{data}/cells.txt", "--top", "12", "--flips", "-o", "out.svg", "--data", "o.json"],
        ["out.svg", "o.json"],
    ),
    Command("voronoi", ["voronoi", "20000", "--seed", "2", "-o", "out.txt"], ["out.txt"]),
    Command(
        "census",
        ["census", "11", "--parts", "4", "--workers", "2", "-o", "census"],
        ["census/classes.csv"],
    ),
]


def _default_sigint() -> None:
    # A run started from a background job inherits SIGINT ignored, and Python then leaves it
    # so: the child gets Ctrl-C as a terminal gives it.
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def start(command: Command, data: Path, folder: Path) -> subprocess.Popen:
    args = [arg.replace("{data}", str(data)) for arg in command.args]
    return subprocess.Popen(
        [*GRAINCLASS, *args, "-q"],
        cwd=folder,
        stdin=subprocess.DEVNULL,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        start_new_session=True,
        preexec_fn=_default_sigint,
    )


def _group_alive(pgid: int) -> bool:
    try:
        os.killpg(pgid, 0)
    except ProcessLookupError:
        return False
    return True


def _python_starting(code: int, signum: int, stderr: str) -> bool:
    """Whether a run ended as Python ends one stopped while it starts: by the signal, or (Ctrl-C
    while the interpreter initializes: its standard streams, ``site``) exit 1 with a fatal
    error; no frame of grainclass in its traceback."""
    by_python = code == -signum or (code == 1 and "Fatal Python error: init_" in stderr)
    return by_python and not RUNNING.search(stderr)


def _left_behind(command: Command, folder: Path) -> list[str]:
    """Files a stopped run must not leave: any, except what a census finished (its directory is
    the state a rerun resumes from), never a temporary."""
    left = []
    for path in folder.rglob("*"):
        if path.is_file() and (command.name != "census" or path.name.endswith(".tmp")):
            left.append(str(path.relative_to(folder)))
    return left


def run_case(command: Command, data: Path, signum: int, delay: float) -> tuple[str, str | None]:
    """One run stopped by ``signum`` ``delay`` seconds after it starts: (outcome, finding)."""
    folder = Path(tempfile.mkdtemp(prefix=f"fuzz-{command.name}-"))
    try:
        run = start(command, data, folder)
        time.sleep(delay)
        if run.poll() is not None:
            outcome = "finished first"
        else:
            outcome = "stopped"
            if signum == signal.SIGINT:
                os.killpg(run.pid, signum)
            else:
                os.kill(run.pid, signum)
        try:
            _, err = run.communicate(timeout=120)
        except subprocess.TimeoutExpired:
            os.killpg(run.pid, signal.SIGKILL)
            run.communicate()
            return outcome, "still running 120 s after the signal"
        stderr = err.decode(errors="replace")
        deadline = time.monotonic() + 10
        while _group_alive(run.pid) and time.monotonic() < deadline:
            time.sleep(0.05)
        problems = []
        if _group_alive(run.pid):
            os.killpg(run.pid, signal.SIGKILL)
            problems.append("processes of its group outlived it by 10 s")
        if "Traceback" in stderr:
            problems.append("a traceback on standard error")
        if run.returncode == 0:
            missing = [name for name in command.outputs if not (folder / name).is_file()]
            temporaries = [p.name for p in folder.rglob("*.tmp")]
            if missing or temporaries:
                problems.append(f"exit 0, outputs missing {missing}, temporaries {temporaries}")
            if outcome == "stopped":
                outcome = "finished before the signal took effect"
        elif outcome == "stopped" and _python_starting(run.returncode, signum, stderr):
            outcome = "stopped while Python started"
            problems = [p for p in problems if "traceback" not in p]
        if outcome.startswith("stopped") and run.returncode != 0:
            left = _left_behind(command, folder)
            if left:
                problems.append(f"left behind: {left}")
        if run.returncode not in (0, 128 + signum) and outcome != "stopped while Python started":
            problems.append(f"exit {run.returncode} ({outcome})")
        if problems:
            return outcome, "; ".join(problems) + f"\nstandard error:\n{stderr}"
        return outcome, None
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def prepare(data: Path) -> None:
    """The inputs: 20,000 Poisson-Voronoi cells as adjacency text, and classified."""
    for args in (
        ["voronoi", "20000", "--seed", "1", "-o", str(data / "cells.txt")],
        ["classify", str(data / "cells.txt"), "-o", str(data / "cells.parquet")],
    ):
        subprocess.run([*GRAINCLASS, *args, "-q"], check=True)


def clean_time(command: Command, data: Path) -> float:
    """Seconds of a whole run (the second of two: the first may compile kernels)."""
    seconds = 0.0
    for _ in range(2):
        folder = Path(tempfile.mkdtemp(prefix=f"fuzz-{command.name}-"))
        try:
            started = time.perf_counter()
            run = start(command, data, folder)
            _, err = run.communicate()
            seconds = time.perf_counter() - started
            if run.returncode != 0:
                raise SystemExit(f"{command.name} fails unstopped:\n{err.decode()}")
        finally:
            shutil.rmtree(folder, ignore_errors=True)
    return seconds


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--trials", type=int, default=50, help="runs per command and signal")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--command", action="append", help="only these commands (repeatable)")
    args = parser.parse_args()
    rng = random.Random(args.seed)
    commands = [c for c in COMMANDS if not args.command or c.name in args.command]
    findings = 0
    started = time.perf_counter()
    with tempfile.TemporaryDirectory() as tmp:
        data = Path(tmp)
        prepare(data)
        for command in commands:
            whole = clean_time(command, data)
            outcomes: dict[str, int] = {}
            for signum in (signal.SIGINT, signal.SIGTERM):
                for trial in range(args.trials):
                    span = 0.3 if trial % 2 == 0 else 1.1 * whole
                    delay = rng.uniform(0.0, span)
                    outcome, finding = run_case(command, data, signum, delay)
                    outcomes[outcome] = outcomes.get(outcome, 0) + 1
                    if finding is not None:
                        findings += 1
                        name = signal.Signals(signum).name
                        print(f"{command.name} {name} at {delay:.3f} s: {finding}", flush=True)
            tally = ", ".join(f"{count} {outcome}" for outcome, count in sorted(outcomes.items()))
            print(f"{command.name} (a whole run {whole:.2f} s): {tally}", flush=True)
    elapsed = time.perf_counter() - started
    print(
        f"{len(commands)} commands x 2 signals x {args.trials} runs, {findings} findings; "
        f"{elapsed:.0f} s in all"
    )
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
