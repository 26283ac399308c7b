"""The ``grainclass`` command and ``python -m grainclass``: stop signals are caught before the
command line loads.

Loading the command line imports click and every command's module, some tens of milliseconds
in which Ctrl-C would end the process in a KeyboardInterrupt traceback. Until
:func:`grainclass.cli.main` takes the signals over, a stop signal ends the process at once with
its exit code: nothing has been begun that would need undoing.
"""

import os
import signal

_STOPS = ("SIGINT", "SIGTERM", "SIGHUP")  # SIGTERM and SIGHUP are not on Windows


def _stop_while_loading(signum: int, frame: object) -> None:
    said = "interrupted" if signum == signal.SIGINT else f"stopped by {signal.Signals(signum).name}"
    try:
        os.write(2, f"grainclass: {said}\n".encode())
    finally:
        os._exit(128 + signum)


def catch_stops_while_loading() -> None:
    """Until the command line takes them over, stop signals end the process at once."""
    for name in _STOPS:
        # One ignored already stays so (nohup, a shell's background job).
        stop = getattr(signal, name, None)
        if stop is not None and signal.getsignal(stop) != signal.SIG_IGN:
            signal.signal(stop, _stop_while_loading)


def main() -> None:
    """Catch the stop signals, load the command line and run it."""
    catch_stops_while_loading()
    from grainclass.cli import main as run

    run()


if __name__ == "__main__":
    main()
