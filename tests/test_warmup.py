"""The helper that fills a cold kernel cache from the other end must compile exactly what
``classify`` then asks for: a signature that differed would be compiled twice. It starts when a
kernel compiles, as the command line's notice is printed then, and only then."""

from __future__ import annotations

import io
import json
import os
import subprocess
import sys

import pytest

from conftest import EVOLVER_FIXTURES, EXAMPLES
from grainclass import compilation

needs_jit = pytest.mark.skipif(
    os.environ.get("NUMBA_DISABLE_JIT") == "1", reason="nothing is compiled without the JIT"
)

# Classify adjacency text read from a file, as the command line does, recording what numba
# compiles in this process (whatever is not in the cache).
RECORD = """
import json, sys
from numba.core import event
recorder = event.RecordingListener()
event.register("numba:compile", recorder)
from grainclass.classification import classify
from grainclass.readers import read_dataset
for batch in read_dataset([sys.argv[1]]):
    classify(batch)
names = {e.data["dispatcher"].py_func.__name__ for _, e in recorder.buffer if e.is_start}
print(json.dumps(sorted(names)))
"""
FIRST = ["_weinberg_batch", "_code_strings", "_p_vectors", "_compact", "_strings_from_codes"]
LAST_FIRST = """
from grainclass.batch import GrainBatch
from grainclass.warmup import CUBE, _last_kernels_first
_last_kernels_first(GrainBatch.from_lists([CUBE]), types=True)
"""


@needs_jit
def test_helper_compiles_the_kernels_classify_calls_last_with_its_signatures(tmp_path):
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "cache"))
    text = tmp_path / "grains.txt"
    # A truncated cube (a truncation tree) and the cube (a 4-belt), both with their types.
    text.write_text(
        "t 1 2 3 4;0 4 5 2 6;0 1 5 3;0 2 5 4;0 3 5 1;1 4 3 2 6;1 5 4\n"
        "cube 1 2 3 4;0 4 5 2;0 1 5 3;0 2 5 4;0 3 5 1;1 4 3 2\n"
    )
    subprocess.run([sys.executable, "-c", LAST_FIRST], env=env, check=True)
    done = subprocess.run(
        [sys.executable, "-c", RECORD, str(text)], env=env, check=True, capture_output=True
    )
    compiled = json.loads(done.stdout)
    assert not set(FIRST) & set(compiled), compiled
    assert "_classify_batch" in compiled  # what the helper leaves to the end is compiled here


GENERAL_TOO = """
from grainclass.batch import GrainBatch
from grainclass.warmup import CUBE, GENERAL, _last_kernels_first
_last_kernels_first(GrainBatch.from_lists([CUBE]), types=True, plan=lambda: GENERAL)
"""
# The run compiles the general validation before its first batch, the helper the fast path.
VALIDATION_FIRST = """
from grainclass.batch import GrainBatch
from grainclass.warmup import CUBE, VALIDATION, _last_kernels_first, _validation_first
_validation_first()
_last_kernels_first(GrainBatch.from_lists([CUBE]), types=True, plan=lambda: VALIDATION)
"""


def _prism(k: int) -> str:
    """The k-gonal prism, a line of adjacency text: k + 2 faces."""
    faces = [[k, (i - 1) % k, k + 1, (i + 1) % k] for i in range(k)]
    faces += [list(range(k)), list(reversed(range(k)))]
    return f"prism{k}\t" + ";".join(" ".join(map(str, face)) for face in faces) + "\n"


@needs_jit
def test_helper_told_of_a_large_grain_compiles_the_general_classification_with_its_signature(
    tmp_path,
):
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "cache"))
    text = tmp_path / "prism.txt"
    text.write_text(_prism(66))
    subprocess.run([sys.executable, "-c", GENERAL_TOO], env=env, check=True)
    done = subprocess.run(
        [sys.executable, "-c", RECORD, str(text)], env=env, check=True, capture_output=True
    )
    compiled = json.loads(done.stdout)
    assert not {"_classify_general_batch", *FIRST} & set(compiled), compiled
    assert "_validate_pending_batch" in compiled  # left to the run, which needs it first


@needs_jit
def test_the_validation_first_plan_compiles_what_a_run_with_bad_grains_calls(tmp_path):
    """The run's general validation and the helper's fast path, with their signatures: a run on
    a degenerate grain (a 2-gon) and a cube then compiles none of the batch kernels."""
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "cache"))
    text = tmp_path / "grains.txt"
    text.write_text("theta\t1 2;0 2;0 1\ncube\t1 2 3 4;0 4 5 2;0 1 5 3;0 2 5 4;0 3 5 1;1 4 3 2\n")
    subprocess.run([sys.executable, "-c", VALIDATION_FIRST], env=env, check=True)
    done = subprocess.run(
        [sys.executable, "-c", RECORD, str(text)], env=env, check=True, capture_output=True
    )
    compiled = json.loads(done.stdout)
    assert not {"_classify_batch", "_validate_pending_batch", *FIRST} & set(compiled), compiled


THE_RUNS_SHARE = """
from grainclass.warmup import _runs_share
_runs_share(types=True)
"""


@needs_jit
def test_the_evolver_stage_and_the_runs_share_compile_what_a_run_on_evolver_files_calls(tmp_path):
    """The helper told the Surface Evolver assembly is ahead compiles it, and says so, while
    the run compiles its share (the fast path, the walk, the general validation), both at once
    as in a first run: a run reading Evolver files with degenerate grains then compiles the
    tokenizer but none of those."""
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "cache"))
    helper = subprocess.Popen(
        [sys.executable, "-m", "grainclass.warmup", "--counting", "--ahead=evolver"],
        env=env,
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
    )
    subprocess.run([sys.executable, "-c", THE_RUNS_SHARE], env=env, check=True)
    said, _ = helper.communicate(b"")  # no plan: counting, it stops after its stages
    assert (said, helper.returncode) == (b"evolver\n", 0)
    done = subprocess.run(
        [sys.executable, "-c", RECORD, str(EVOLVER_FIXTURES / "21000-00000025.fe")],
        env=env,
        check=True,
        capture_output=True,
    )
    compiled = json.loads(done.stdout)
    assert "_tokenize" in compiled  # the run's own first stage
    assert not {
        "_assemble", "_classify_batch", "_weinberg_batch", "_validate_pending_batch"
    } & set(compiled), compiled  # fmt: skip


# summarize's counting, recorded as RECORD records classify.
RECORD_COUNTING = RECORD.replace(
    "from grainclass.classification import classify", "from grainclass.summary import tally_batch"
).replace("classify(batch)", "tally_batch(batch)")
COUNTING_HELPER = """
import sys
from numba.core import event
recorder = event.RecordingListener()
event.register("numba:compile", recorder)
from grainclass.warmup import fill_cache
fill_cache(types=False, plan=lambda: sys.argv[1].encode(), counting=True)
print(sum(e.is_start for _, e in recorder.buffer))
"""


@needs_jit
def test_counting_plans_compile_what_summarize_calls(tmp_path):
    """summarize counts grains and writes no table: with bad grains, the run's general
    validation and the helper's fast path and counting kernels leave it nothing to compile;
    told nothing, the helper compiles nothing (the run starts with the fast path)."""
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "cache"))
    text = tmp_path / "grains.txt"
    text.write_text("theta\t1 2;0 2;0 1\ncube\t1 2 3 4;0 4 5 2;0 1 5 3;0 2 5 4;0 3 5 1;1 4 3 2\n")
    idle = subprocess.run(
        [sys.executable, "-c", COUNTING_HELPER, ""], env=env, check=True, capture_output=True
    )
    assert idle.stdout.split() == [b"0"]
    subprocess.run([sys.executable, "-c", COUNTING_HELPER, "validation\n"], env=env, check=True)
    subprocess.run(
        [sys.executable, "-c", "from grainclass.warmup import _validation_first as v; v()"],
        env=env,
        check=True,
    )
    done = subprocess.run(
        [sys.executable, "-c", RECORD_COUNTING, str(text)], env=env, check=True, capture_output=True
    )
    compiled = json.loads(done.stdout)
    counting = {"_classify_batch", "_validate_pending_batch", "_group_keys", "_triangle_counts"}
    assert not counting & set(compiled), compiled


# Every input kind and path of classify and summarize, in a fresh process: the kernels of
# grainclass._kernels called with more than one set of argument types (each set is compiled
# on its own at a first run).
SIGNATURES = """
import importlib, json, pkgutil, sys
from numba.extending import is_jitted
import grainclass._kernels as kernels
from grainclass.classification import classify
from grainclass.options import ReadOptions
from grainclass.pipeline import tallies
from grainclass.readers import read_dataset
for path in sys.argv[1:]:
    for batch in read_dataset([path]):
        classify(batch)
    for types in (False, True):
        for _ in tallies([path], ReadOptions(types=types)):
            pass
several = {}
for module in pkgutil.iter_modules(kernels.__path__):
    found = importlib.import_module(f"grainclass._kernels.{module.name}")
    for name, value in vars(found).items():
        if is_jitted(value) and len(value.signatures) > 1:
            several[name] = [str(s) for s in value.signatures]
print(json.dumps(several))
"""


@needs_jit
def test_every_kernel_is_called_with_one_set_of_argument_types(tmp_path, plantri_output):
    """A literal 0 or 64 where an int64 is passed elsewhere, or int32 indices where int64 are,
    compiled a kernel again: 1-1.5 s of a first run, over the general path's kernels."""
    from conftest import EVOLVER_FIXTURES, EXAMPLES

    prism = tmp_path / "prism.txt"
    prism.write_text(_prism(66))
    inputs = [
        EXAMPLES / "bad-grains.txt",
        EXAMPLES / "polytopes.txt",
        prism,
        plantri_output(9),
        EVOLVER_FIXTURES,
    ]
    done = subprocess.run(
        [sys.executable, "-c", SIGNATURES, *map(str, inputs)],
        check=True,
        capture_output=True,
    )
    assert json.loads(done.stdout) == {}


TWO_GON = [[1, 2], [0, 2, 3], [0, 3, 1], [1, 2]]  # face 0 has two neighbours
EXTRA = [[1, 2, 3, 4, 5], [0, 4, 5, 2], [0, 1, 5, 3], [0, 2, 5, 4], [0, 3, 5, 1], [1, 4, 3, 2]]


def _helper_that_listens(monkeypatch, warmup) -> list[bytes]:
    """The helper process replaced by one that keeps what it is told (each plan, in order)."""
    heard: list[bytes] = []

    class Pipe(io.BytesIO):
        def close(self) -> None:
            if not self.closed:
                heard.append(self.getvalue())
            super().close()

    class Helper:
        def __init__(self, *args, **kwargs) -> None:
            self.stdin = Pipe()
            self.stdout = io.BytesIO()  # it says nothing

        def wait(self, timeout=None) -> int:
            return 0

    monkeypatch.setattr(warmup.subprocess, "Popen", Helper)
    return heard


@pytest.mark.parametrize(
    ("grains", "told"),
    [
        ([], b""),
        (["cube"], b""),
        (["cube", "prism"], b""),
        (["prism"], b"general\n"),
        (["prism", "cube"], b"general\n"),
        (["two-gon"], b"validation\n"),
        (["extra", "cube"], b"validation\n"),
        (["cube", "two-gon"], b""),
    ],
)
def test_the_first_batch_tells_the_helper_the_plan(monkeypatch, grains, told):
    """Batches of one grain each: a large grain (a 65-gonal prism) in the first batch sends the
    helper to the general classification; a grain whose lists the fast path surely leaves (a
    2-gon, a cube with 6n - 11 entries) makes the run compile the general validation first."""
    import grainclass.warmup as warmup
    from grainclass.batch import GrainBatch

    heard = _helper_that_listens(monkeypatch, warmup)
    validated_first: list[bool] = []
    monkeypatch.setattr(warmup, "_validation_first", lambda: validated_first.append(True))
    lists = {"cube": warmup.CUBE, "prism": warmup.PRISM, "two-gon": TWO_GON, "extra": EXTRA}
    batches = [GrainBatch.from_lists([lists[name]]) for name in grains]
    with warmup.compiling_from_both_ends(jobs=2, types=True) as watch:
        compilation.kernel_compiling()  # a cold cache: the reader's kernel, say
        assert list(watch(batches)) == batches
    assert heard == [told]
    assert validated_first == ([True] if told == warmup.VALIDATION else [])


@pytest.mark.parametrize("compiled_before_the_first_batch", [True, False])
def test_the_plan_reaches_the_helper_once_whenever_it_starts(
    monkeypatch, compiled_before_the_first_batch
):
    """The first kernel compiled may come before the first batch (a reader's) or after it (the
    classification's): the helper hears the plan either way, once."""
    import grainclass.warmup as warmup
    from grainclass.batch import GrainBatch

    heard = _helper_that_listens(monkeypatch, warmup)
    with warmup.compiling_from_both_ends(jobs=2, types=True) as watch:
        if compiled_before_the_first_batch:
            compilation.kernel_compiling()
        list(watch([GrainBatch.from_lists([warmup.PRISM])]))
        compilation.kernel_compiling()
        compilation.kernel_compiling()
    assert heard == [warmup.GENERAL]


@needs_jit
def test_the_first_compiled_kernel_is_heard_once_and_a_cached_one_not_at_all(tmp_path):
    """numba's compile event: a process with an empty cache hears its first kernel compile
    once (the callback is not called again for the kernels that follow); the next process
    loads them from the cache and hears nothing."""
    probe = (
        "from grainclass import compilation; heard = []; "
        "compilation.on_first_compile(lambda: heard.append(True)); "
        "from grainclass._kernels.groups import _group_keys; import numpy as np; "
        "_group_keys(np.zeros(3, np.int64)); _group_keys(np.zeros(3, np.int8)); print(len(heard))"
    )
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "cache"))
    runs = [
        subprocess.run([sys.executable, "-c", probe], env=env, check=True, capture_output=True)
        for _ in range(2)
    ]
    assert [run.stdout.split() for run in runs] == [[b"1"], [b"0"]]


USER_KERNELS = """
import numba
from grainclass import _numba, compilation
heard = []
compilation.on_first_compile(lambda: heard.append(True))
made = {}
exec("def plus_one(x):\\n    return x + 1", made)
made["plus_one"].__module__ = None  # as a function made by exec may have it
assert numba.njit(made["plus_one"])(1) == 2
assert numba.njit(lambda x: 2 * x)(2) == 4
print(len(heard))
"""


@needs_jit
def test_other_code_compiling_in_the_process_is_not_heard_and_not_disturbed(tmp_path):
    """The listener is numba's, for the whole process: a library user's own kernels, one of
    them without a module, compile as ever and are no kernels of grainclass's."""
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "cache"))
    done = subprocess.run(
        [sys.executable, "-c", USER_KERNELS], env=env, check=True, capture_output=True
    )
    assert done.stdout.split() == [b"0"]


@needs_jit
def test_a_command_says_once_that_kernels_compile_and_not_when_they_are_cached(tmp_path):
    """The first run with an empty cache compiles (stderr is a pipe here, and -q is not
    given): one line says so. The second loads every kernel from the cache and says nothing."""
    from grainclass.cli.startup import COMPILING

    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "cache"))
    command = [sys.executable, "-m", "grainclass", "summarize", str(EXAMPLES / "plantri-10.pc")]
    first, second = (
        subprocess.run(command, env=env, check=True, capture_output=True, text=True)
        for _ in range(2)
    )
    assert first.stderr.splitlines().count(COMPILING) == 1, first.stderr
    assert COMPILING not in second.stderr, second.stderr
    assert first.stdout == second.stdout


@pytest.mark.parametrize(
    ("terminal", "quiet", "said"),
    [(True, False, True), (True, True, True), (False, False, True), (False, True, False)],
)
def test_the_compiling_notice_is_said_on_a_terminal_and_elsewhere_unless_quiet(
    monkeypatch, terminal, quiet, said
):
    """A person at a terminal is told even with -q; a log or a pipe only without -q."""
    from grainclass.cli import startup

    class Stderr(io.StringIO):
        def isatty(self) -> bool:
            return terminal

    stderr = Stderr()
    monkeypatch.setattr(sys, "stderr", stderr)
    monkeypatch.setattr(startup, "_quiet", False)
    startup.note_quiet(None, None, quiet)
    startup.announce_compilation()
    assert (startup.COMPILING + "\n" in stderr.getvalue()) == said


def test_helper_runs_only_once_a_kernel_compiles_with_jobs_and_stops_when_the_run_fails(
    monkeypatch,
):
    import grainclass.warmup as warmup

    started: list[subprocess.Popen] = []
    popen = subprocess.Popen

    def recording_popen(*args, **kwargs):
        started.append(popen(*args, **kwargs))
        return started[-1]

    monkeypatch.setattr(warmup.subprocess, "Popen", recording_popen)
    with warmup.compiling_from_both_ends(jobs=2, types=True):
        pass
    assert started == []  # nothing compiled: a warm cache
    with warmup.compiling_from_both_ends(jobs=1, types=True):
        compilation.kernel_compiling()
    assert started == []  # one job: no second process

    def failing_run() -> None:
        with warmup.compiling_from_both_ends(jobs=2, types=True):
            compilation.kernel_compiling()
            compilation.kernel_compiling()
            raise KeyError("bad input")

    with pytest.raises(KeyError):
        failing_run()
    assert len(started) == 1  # one helper, however many kernels compile
    assert started[0].returncode == -9  # killed at once, and reaped
    compilation.kernel_compiling()  # after the run: no helper
    assert len(started) == 1


def test_a_helper_that_cannot_start_leaves_the_run_to_itself(monkeypatch):
    """It only saves time: starting it failed (an interpreter this user may not run) and the
    run failed with it, the error blamed on the output file."""
    import grainclass.warmup as warmup

    def no_process(*args, **kwargs):
        raise PermissionError(13, "Permission denied")

    monkeypatch.setattr(warmup.subprocess, "Popen", no_process)
    ran = []
    with warmup.compiling_from_both_ends(jobs=2, types=True):
        compilation.kernel_compiling()
        ran.append(True)
    assert ran == [True]


class _SayingHelper:
    """A helper process that says what the test writes to its standard output, and keeps the
    command it was started with."""

    def __init__(self, monkeypatch, warmup) -> None:
        self.commands: list[list[str]] = []
        read, self.write = os.pipe()
        stdout = os.fdopen(read, "rb")
        outer = self

        class Process:
            def __init__(self, command, **kwargs) -> None:
                outer.commands.append(command)
                self.stdin = io.BytesIO()
                self.stdout = stdout

            def wait(self, timeout=None) -> int:
                return 0

            def kill(self) -> None:
                pass

        monkeypatch.setattr(warmup.subprocess, "Popen", Process)

    def say(self, line: bytes) -> None:
        os.write(self.write, line)

    def end(self) -> None:
        os.close(self.write)

    def says_after(self, order: list, step: str, stage: str):
        """A stand-in for the run's ``step`` that notes its call (with its arguments) in
        ``order``; once it has run, the helper notes ``stage`` and says it."""
        import threading

        ran = threading.Event()

        def helper_done() -> None:
            ran.wait(10)
            order.append(stage)
            self.say(stage.encode() + b"\n")

        threading.Thread(target=helper_done).start()

        def stand_in(*args) -> None:
            order.append((step, *args))
            ran.set()

        return stand_in


def test_a_stage_said_ahead_is_the_helpers_and_the_run_waits_for_it_after_its_share(
    monkeypatch,
):
    """A reader says its second stage is ahead before its first kernel compiles: the helper is
    started with it, and when the reader reaches it the run compiles its own share once, then
    waits until the helper says the stage is in the cache."""
    import grainclass.warmup as warmup

    helper = _SayingHelper(monkeypatch, warmup)
    order: list = []
    share = helper.says_after(order, "share", compilation.EVOLVER)
    monkeypatch.setattr(warmup, "_runs_share", share)
    with warmup.compiling_from_both_ends(jobs=2, types=True):
        compilation.ahead(compilation.EVOLVER)
        compilation.kernel_compiling()  # the tokenizer compiles: a cold cache
        compilation.before(compilation.EVOLVER)
        order.append("assembled")
        compilation.before(compilation.EVOLVER)  # another group of files: no share, no wait
        helper.end()
    assert helper.commands[0][-1] == "--ahead=evolver"
    assert order == [("share", True), "evolver", "assembled"]


def test_a_stage_said_once_the_helper_runs_is_the_runs_own(monkeypatch):
    import grainclass.warmup as warmup

    helper = _SayingHelper(monkeypatch, warmup)
    monkeypatch.setattr(warmup, "_runs_share", lambda types: pytest.fail("no share"))
    with warmup.compiling_from_both_ends(jobs=2, types=False):
        compilation.kernel_compiling()  # another reader's kernel started the helper
        compilation.ahead(compilation.EVOLVER)
        compilation.before(compilation.EVOLVER)  # returns at once: the helper never heard
        helper.end()
    assert not any(arg.startswith("--ahead") for arg in helper.commands[0])
    compilation.before(compilation.EVOLVER)  # after the run: no one listens


def test_a_helper_that_ends_without_saying_is_not_waited_for(monkeypatch):
    """It only saves time: killed, or failed, it says nothing more, and the run goes on."""
    import grainclass.warmup as warmup

    helper = _SayingHelper(monkeypatch, warmup)
    shares: list[bool] = []
    monkeypatch.setattr(warmup, "_runs_share", shares.append)
    with warmup.compiling_from_both_ends(jobs=2, types=False, counting=True):
        compilation.ahead(compilation.EVOLVER)
        compilation.kernel_compiling()
        helper.end()
        compilation.before(compilation.EVOLVER)
    assert shares == [False]


def test_a_helper_that_hangs_is_waited_for_a_while_only(monkeypatch):
    """Neither saying nor ending (stopped, say): the run goes on after a while and compiles
    the stage itself."""
    import threading

    import grainclass.warmup as warmup

    helper = _SayingHelper(monkeypatch, warmup)
    monkeypatch.setattr(warmup, "_runs_share", lambda types: None)
    monkeypatch.setattr(warmup, "_STAGE_WAIT", 0.2)
    with warmup.compiling_from_both_ends(jobs=2, types=True):
        compilation.ahead(compilation.EVOLVER)
        compilation.kernel_compiling()
        reader = threading.Thread(target=compilation.before, args=(compilation.EVOLVER,))
        reader.start()
        reader.join(30)
        waiting = reader.is_alive()
        helper.end()
    assert not waiting


def test_after_the_general_validation_the_run_waits_for_the_helpers_fast_path(monkeypatch):
    """With grains the fast path leaves, the run compiles their validation and the helper the
    fast path; the run then waits for it rather than compile it too."""
    import grainclass.warmup as warmup
    from grainclass.batch import GrainBatch

    helper = _SayingHelper(monkeypatch, warmup)
    order: list = []
    validation_first = helper.says_after(order, "validation", warmup.FAST)
    monkeypatch.setattr(warmup, "_validation_first", validation_first)
    with warmup.compiling_from_both_ends(jobs=2, types=True) as watch:
        compilation.kernel_compiling()
        for _ in watch([GrainBatch.from_lists([TWO_GON])]):
            order.append("batch")
        helper.end()
    assert order == [("validation",), "fast", "batch"]


# A run that starts the helper and is gone while it compiles, as one killed or stopped by a
# signal then: it ends without waiting for its helper (whose standard output is the test's).
GONE_RUN = """
import os, subprocess, sys, time
subprocess.Popen(
    [sys.executable, "-m", "grainclass.warmup", f"--run={os.getpid()}", "--ahead=evolver"],
    stdin=subprocess.PIPE,
)
time.sleep(3)  # the helper compiles by now
os._exit(0)
"""


@needs_jit
def test_the_helper_ends_when_the_run_is_gone(tmp_path):
    """Its work (the Evolver assembly first, the longest kernel to compile) would keep a core
    busy for no one: it ends before it has compiled the assembly, whose line it never says."""
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "cache"))
    gone = subprocess.run(
        [sys.executable, "-c", GONE_RUN], env=env, stdout=subprocess.PIPE, timeout=120
    )  # its standard output reaches its end once the helper, which holds it too, has ended
    assert (gone.returncode, gone.stdout) == (0, b"")
