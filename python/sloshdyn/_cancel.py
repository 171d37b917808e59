"""Ctrl-C during a long Fortran call.

Python delivers KeyboardInterrupt only to the main thread, and only between bytecodes: while a
Fortran routine runs in the main thread, Ctrl-C waits until it returns. So the call runs in a
worker thread (the bridge routines that compute release the GIL), the main thread waits for it
and stays responsive; on KeyboardInterrupt it sets the core's cancellation flag
(``request_cancel``), which every integrator and continuation step polls: the call returns
status 10 (cancelled) within one step, the flag is cleared and KeyboardInterrupt goes on.

A request cancels every sloshdyn computation running in the process at that moment (the flag
is the core's one piece of global state, docs/architecture.md "Cancellation").
"""

from __future__ import annotations

import threading

from . import _core

_bridge = _core.sloshdyn_bridge_input


def cancellable(function, *args):
    """function(*args), a bridge routine that releases the GIL, run so that Ctrl-C stops it."""
    if threading.current_thread() is not threading.main_thread():
        return function(*args)          # KeyboardInterrupt never reaches other threads
    outcome = {}
    finished = threading.Event()

    def run():
        try:
            outcome["value"] = function(*args)
        except BaseException as exc:    # handed to the caller below
            outcome["error"] = exc
        finally:
            finished.set()

    # An Event, not Thread.join: a join interrupted by KeyboardInterrupt (CPython 3.11) marks the
    # thread stopped, so a second join returns at once while the Fortran still runs.
    threading.Thread(target=run, name="sloshdyn-core", daemon=True).start()
    try:
        while not finished.wait(0.1):
            pass
    except KeyboardInterrupt:
        _bridge.request_cancel()
        finished.wait()
        _bridge.clear_cancel()
        raise
    if "error" in outcome:
        raise outcome["error"]
    return outcome["value"]


#: The app layer's routines (the reader, the driver: read_input, input_record, run_input)
#: release the GIL so that Ctrl-C and SIGTERM can cancel them, but their modules keep static
#: string lengths (docs/architecture.md, "Studies on Dask"): one such call at a time.
_ONE_APP_CALL_AT_A_TIME = threading.Lock()


def app_call(function, *args):
    """function(*args), a routine of the app layer, cancellable and one at a time."""
    with _ONE_APP_CALL_AT_A_TIME:
        return cancellable(function, *args)
