"""The ``grainclass`` command line: a thin layer over the library, one module per command.

A command parses its arguments, resolves its streams, calls the library and turns its typed
errors into messages and exit codes (:mod:`.exit_codes`). Heavy imports (numba, pyarrow,
pandas) happen inside the commands, so that ``grainclass --help`` stays fast.
"""

from __future__ import annotations

import gc
import os
import signal
import sys
import warnings
from contextlib import suppress

import click

from grainclass import __version__, compilation, interrupts
from grainclass.cli import output, signals, startup
from grainclass.cli.census import census_cmd
from grainclass.cli.classify import classify_cmd
from grainclass.cli.draw import draw_cmd
from grainclass.cli.exit_codes import GRAINS, ExitCode
from grainclass.cli.penalties import penalties_cmd
from grainclass.cli.perturb import perturb_cmd
from grainclass.cli.plot import plot_cmd
from grainclass.cli.summarize import summarize_cmd
from grainclass.cli.types import types_cmd
from grainclass.cli.voronoi import voronoi_cmd
from grainclass.pipes import open_closed_standard_streams

__all__ = ["cli", "main"]


@click.group(epilog=GRAINS, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="grainclass")
def cli() -> None:
    """Classify the grains of 3D cellular microstructures by combinatorial type.

    Each grain is a simple 3-polytope given by its face adjacency; grainclass reduces it to its
    fundamental polytope and reports its class (stacked, flag, sc and their truncations),
    roundness, 4-belts, split type and penalty, as in Lutz, Mason, Lazar and MacPherson,
    "Roundness of grains in cellular microstructures".
    """


for _command in (
    classify_cmd,
    summarize_cmd,
    types_cmd,
    plot_cmd,
    draw_cmd,
    penalties_cmd,
    perturb_cmd,
    voronoi_cmd,
    census_cmd,
):
    cli.add_command(_command)


def _show_warning(message, category, filename, lineno, file=None, line=None) -> None:
    """A warning as a line of its own on standard error, without Python's source location."""
    click.echo(f"grainclass: warning: {message}", err=True)


def main() -> None:
    """Entry point: click's handling, except that Ctrl-C exits 130 as shells expect, and
    SIGTERM and SIGHUP (``timeout``, a batch scheduler, a closed terminal) 143 and 129."""
    # Readers build millions of short-lived lists, freed by reference counting, and start-up
    # makes some 230,000 objects that live as long as the process: the cyclic collector stays
    # off while the libraries load and runs less often afterwards (the commands turn it on
    # when their first batch is through; docs/performance.md).
    gc.set_threshold(100_000, 50, 1000)
    gc.disable()
    # numpy's OpenBLAS would start a spinning thread per core, taking CPU from a producer such
    # as plantri in the same pipe; grainclass multiplies no matrices.
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    open_closed_standard_streams()
    warnings.showwarning = _show_warning
    compilation.on_first_compile(startup.announce_compilation)
    signals.catch_stops()
    stopped = False
    try:
        code = cli.main(standalone_mode=False)
    except click.ClickException as exc:
        exc.show()
        code = exc.exit_code
    except BrokenPipeError:
        code = output.quiet_broken_pipe()
    except MemoryError:
        # A grain's own needs are refused grain by grain (its row says so); this is the run's.
        click.echo("grainclass: error: out of memory (a smaller --chunk-size may do)", err=True)
        code = ExitCode.FAILURE
    except (click.Abort, KeyboardInterrupt):
        click.echo("grainclass: interrupted", err=True)
        code = ExitCode.INTERRUPTED
        stopped = True
    except interrupts.Stopped as stop:
        click.echo(f"grainclass: stopped by {signal.Signals(stop.signum).name}", err=True)
        code = ExitCode.stopped_by(stop.signum)
        stopped = True
    signals.all_done()
    if stopped and signals.threads_busy():
        # A thread still runs a kernel, or numba compiles one at a first run: the interpreter's
        # exit would wait for it, seconds after Ctrl-C. What the run began is undone already
        # (its output file removed, its worker processes stopped), and nothing that thread
        # does is needed.
        with suppress(OSError, ValueError):
            sys.stdout.flush()
            sys.stderr.flush()
        os._exit(code)
    sys.exit(int(code) if isinstance(code, int) else ExitCode.OK)
