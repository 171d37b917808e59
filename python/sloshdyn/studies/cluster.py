"""Where a study runs: the Dask client (given, connected to a scheduler address, or an
embedded local cluster), the bounds on its workers, and the workers it may use -- each asked,
before it gets a task, which sloshdyn it imports (a worker that cannot import it, or imports
another version, is refused by name) -- with the grace time after which a study without a
usable worker fails instead of waiting for ever."""

from __future__ import annotations

import contextlib
import math
import os
import socket
import struct
import sys
import time
import warnings

from .. import _checks, _tables
from .._errors import ClusterError, InputError
from .._version import __version__

_STUDY_DEFAULTS = _tables.defaults("study")
#: the default worker kind of an embedded cluster, the core's (&study worker_kind): threads,
#: by measurement (docs/studies.md, "Worker kind and task size")
WORKER_KIND = _tables.codes("worker_kinds")[int(_STUDY_DEFAULTS["worker_kind"])]
#: how long a study waits for its workers: for min_workers at its start, and whenever no
#: usable worker is alive (the core's &study grace_time default, seconds)
GRACE_TIME = float(_STUDY_DEFAULTS["grace_time"])
#: how long a scheduler address may take to answer
CONNECT_TIMEOUT = 5.0
#: how often the workers are looked at while a study waits (seconds)
TICK = 0.5
#: the memory a worker process takes, for the bound on their number (measured: ~150 MiB)
WORKER_PROCESS_BYTES = 512 * 2**20
#: Dask settings of an embedded cluster: its servers' periodic work (the event-loop tick, the
#: workers' sampling profiler, the system and memory monitors), made for dashboards, which
#: the embedded cluster does not start, took ~4 % of a core in the study's process and ~3 %
#: in each worker even while idle, CPU that two workers on two cores take from the tasks
#: (measured: docs/studies.md, "Worker kind and task size")
CLUSTER_CONFIG = {
    "distributed.admin.tick.interval": "1s",
    "distributed.worker.profile.enabled": False,
    "distributed.admin.system-monitor.interval": "2s",
    "distributed.worker.memory.monitor-interval": "500ms",
}
#: what a worker is asked before it gets a task, evaluated by the builtin eval: a worker
#: without sloshdyn cannot unpickle a task (it closes, or the task errs), but it answers these
#: with its own error
_ASK_INTERPRETER = "__import__('sys').executable"
_ASK_VERSION = "__import__('sloshdyn').__version__"


def version():
    return __version__


def check_scheduler(scheduler):
    """The scheduler address: [scheme://]host:port, with a scheme Dask can connect by (tcp
    when none is given) and a port in 1..65535. Returns (address, scheme, host, port)."""
    from urllib.parse import urlsplit
    from distributed.comm import registry
    schemes = sorted(k for k in registry.backends if k != "inproc")
    if not isinstance(scheduler, str) or not scheduler.strip():
        raise InputError(f"scheduler = {scheduler!r:.80} is not valid: give the address of a "
                         "Dask scheduler, such as tcp://host:8786")
    address = scheduler.strip()
    scheme = address.split("://", 1)[0] if "://" in address else "tcp"
    if scheme not in schemes:
        raise InputError(f"scheduler = {scheduler!r:.80} is not valid: its scheme {scheme!r} "
                         f"is not one of {', '.join(schemes)}")
    try:
        parts = urlsplit(address if "://" in address else f"tcp://{address}")
        host, port = parts.hostname, parts.port
    except ValueError:
        host = port = None
    if not host or port is None or not 0 < port < 65536 or parts.path or parts.query:
        raise InputError(f"scheduler = {scheduler!r:.80} is not valid: give "
                         f"{scheme}://host:port with a port in 1..65535")
    return f"{scheme}://{parts.netloc}", scheme, host, port


#: the largest first message a Dask scheduler sends (its handshake is well under 1 kB)
MAX_HANDSHAKE = 1 << 20


def probe_scheduler(scheduler, host, port):
    """A scheduler at tcp://host:port answers at once with its handshake, a Dask message whose
    8-byte header is its length: wait for that header at most CONNECT_TIMEOUT, and check that
    it is a Dask message (an HTTP or other service answers other bytes, which Dask would take
    for a length of exabytes). Says what happened: refused at once, no answer, closed."""
    deadline = time.monotonic() + CONNECT_TIMEOUT
    header = b""
    try:
        with socket.create_connection((host, port), timeout=CONNECT_TIMEOUT) as s:
            while len(header) < 8:
                s.settimeout(max(0.01, deadline - time.monotonic()))
                part = s.recv(8 - len(header))
                if not part:
                    raise ConnectionError("it closed the connection without a word")
                header += part
    except ConnectionRefusedError:
        raise InputError(f"scheduler = {scheduler!r} refused the connection: nothing listens "
                         f"at {host}:{port} (is the scheduler started, and is this its "
                         "address?)") from None
    except TimeoutError:
        raise InputError(f"scheduler = {scheduler!r} did not answer within "
                         f"{CONNECT_TIMEOUT:g} s") from None
    except OSError as exc:
        raise InputError(f"scheduler = {scheduler!r} cannot be reached "
                         f"({type(exc).__name__}: {exc})") from None
    (length,) = struct.unpack("Q", header)
    if not 0 < length <= MAX_HANDSHAKE:
        raise InputError(f"scheduler = {scheduler!r} is not a Dask scheduler: it answered "
                         f"{header!r} (a Dask scheduler answers with a message of at most "
                         f"{MAX_HANDSHAKE} bytes)")


def max_workers(worker_kind):
    """The most workers an embedded cluster may have on this machine: 4 per core; worker
    processes also at most one per WORKER_PROCESS_BYTES of its memory."""
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    bound = 4 * (cores or 1)
    if worker_kind == "processes":
        bound = min(bound, max(1, 2 * _checks.MAX_OUTPUT_BYTES // WORKER_PROCESS_BYTES))
    return bound


def check_workers(workers, worker_kind):
    _checks.choice("worker_kind", worker_kind, _tables.names("worker_kinds")[0])
    if workers is None:
        return None
    n = _checks.integer("workers", workers, 1)
    bound = max_workers(worker_kind)
    if n > bound:
        raise InputError(f"workers = {n} is out of range: this machine runs at most {bound} "
                         f"{'worker processes' if worker_kind == 'processes' else 'threads'} "
                         "(4 per core" + (", one per 512 MiB of memory" if worker_kind ==
                                          "processes" else "") + ")")
    return n


def embedded_size(workers, worker_kind):
    """The workers of an embedded cluster: `workers`, or one per core within max_workers."""
    return workers or min(os.cpu_count() or 1, max_workers(worker_kind))


def check_waiting(min_workers, grace_time, embedded=None):
    """min_workers (>= 1; at most the `embedded` cluster's workers) and grace_time (finite,
    > 0 seconds, at most a day), checked before anything runs."""
    minimum = _checks.integer("min_workers", 1 if min_workers is None else min_workers, 1)
    grace = _checks.real("grace_time", GRACE_TIME if grace_time is None else grace_time)
    if not 0 < grace <= 86400:
        raise InputError(f"grace_time = {grace:g} is out of range: it must lie in (0, 86400] "
                         "seconds")
    if embedded is not None and minimum > embedded:
        raise InputError(f"min_workers = {minimum} is out of range: the embedded cluster has "
                         f"{embedded} workers (workers)")
    return minimum, grace


def _guarded(filename, lineno):
    """Line `lineno` of the file is inside a top-level `if __name__ == "__main__":` block."""
    import ast
    try:
        with open(filename, encoding="utf-8") as f:
            tree = ast.parse(f.read())
    except (OSError, SyntaxError, ValueError):
        return False

    def is_main(test):
        if not (isinstance(test, ast.Compare) and len(test.ops) == 1
                and isinstance(test.ops[0], ast.Eq)):
            return False
        sides = [test.left, test.comparators[0]]
        return (any(isinstance(x, ast.Name) and x.id == "__name__" for x in sides)
                and any(isinstance(x, ast.Constant) and x.value == "__main__" for x in sides))
    return any(isinstance(node, ast.If) and is_main(node.test)
               and node.body[0].lineno <= lineno <= node.body[-1].end_lineno
               for node in tree.body)


def _why_no_processes():
    """Why worker processes cannot start from this program, or None. Python starts them by
    spawning: each imports the program's main module again (as __mp_main__), so a main module
    read from standard input cannot be imported, and a study called outside the
    `if __name__ == "__main__":` block would start again in every worker."""
    main = sys.modules.get("__main__")
    path = getattr(main, "__file__", None)
    if getattr(getattr(main, "__spec__", None), "name", None) is None:
        if path is None:
            return None                 # python -c, interactive: nothing is imported again
        if not os.path.isfile(path):
            return f"its main program ({path}) is not a file that they can import"
    frame = sys._getframe(1)
    while frame is not None:
        if frame.f_code.co_name == "<module>" and frame.f_globals is vars(main) and \
                not _guarded(frame.f_code.co_filename, frame.f_lineno):
            return (f"the study is started at line {frame.f_lineno} of "
                    f"{frame.f_code.co_filename}, outside an `if __name__ == \"__main__\":` "
                    "block, so every worker process would start it again")
        frame = frame.f_back
    return None


@contextlib.contextmanager
def connect(client, scheduler, workers, worker_kind):
    """The Dask client of a study: the one given, one connected to `scheduler`, or an embedded
    local cluster sized to the machine (closed afterwards)."""
    import dask
    from dask.distributed import Client, LocalCluster
    if client is not None:
        yield client
        return
    if scheduler:
        address, scheme, host, port = check_scheduler(scheduler)
        if scheme == "tcp":
            probe_scheduler(scheduler, host, port)
        try:
            c = Client(address, timeout=CONNECT_TIMEOUT)
        except (OSError, TimeoutError, ValueError) as exc:
            raise InputError(f"scheduler = {scheduler!r} did not complete Dask's handshake "
                             f"within {CONNECT_TIMEOUT:g} s ({type(exc).__name__}: "
                             f"{exc})") from None
        try:
            yield c
        finally:
            c.close()
        return
    n = embedded_size(workers, worker_kind)
    processes = worker_kind == "processes"
    why = _why_no_processes() if processes else None
    if why:
        warnings.warn(f"the study runs on {n} threads, not worker processes: {why}",
                      RuntimeWarning, stacklevel=4)
        processes = False
    options = {"preload": ["sloshdyn.studies.worker"]} if processes else {}
    with contextlib.ExitStack() as stack:
        with dask.config.set(CLUSTER_CONFIG):    # read as the servers start
            cluster = stack.enter_context(LocalCluster(
                n_workers=n if processes else 1, threads_per_worker=1 if processes else n,
                processes=processes, dashboard_address=None, silence_logs=50, **options))
        # results come straight from the workers (not through the scheduler: one copy and
        # one (de)serialisation less in the study's process per task)
        c = stack.enter_context(Client(cluster, direct_to_workers=True))
        yield c


class Workers:
    """The workers a study may use: each new worker of the cluster is asked which interpreter
    it runs and which sloshdyn it imports before it gets a task (restrictions keep the tasks
    off the others); a worker that cannot import sloshdyn, or imports another version, is
    refused by name. While no usable worker is alive the study waits at most `grace` seconds,
    then fails (ClusterError) naming the cause: the workers that left, those refused and why,
    or that none joined."""

    def __init__(self, client, grace, minimum):
        self.client, self.grace, self.minimum = client, grace, minimum
        self.usable = {}            #: address -> threads
        self.refused = {}           #: address -> why
        self.lost = []              #: usable workers that left the cluster, in order
        self.without = None         #: since when no usable worker is alive (monotonic)
        self.checked = -math.inf

    def threads(self):
        return sum(self.usable.values())

    def refresh(self, every=TICK):
        """Look at the cluster's workers (at most every `every` seconds): ask the new ones."""
        now = time.monotonic()
        if now - self.checked < every:
            return
        self.checked = now
        alive = self.client.nthreads()
        for address in [a for a in self.usable if a not in alive]:
            del self.usable[address]
            self.lost.append(address)
        new = [a for a in alive if a not in self.usable and a not in self.refused]
        if new:
            self._ask(new, alive)
        self.without = None if self.usable else (self.without or now)

    def _ask(self, new, alive):
        expected = version()
        where = self.client.run(eval, _ASK_INTERPRETER, workers=new, on_error="return")
        found = self.client.run(eval, _ASK_VERSION, workers=new, on_error="return")
        for address in new:
            python = where.get(address)
            python = python if isinstance(python, str) else "an unknown interpreter"
            answer = found.get(address, KeyError("it gave no answer"))
            if isinstance(answer, BaseException):
                why = (f"it cannot import sloshdyn ({type(answer).__name__}: {answer}) with "
                       f"{python}")
            elif answer != expected:
                why = (f"it imports sloshdyn {answer} with {python}, this client "
                       f"{expected}: its results would not be this version's")
            else:
                self.usable[address] = alive[address]
                continue
            self.refused[address] = why
            warnings.warn(f"worker {address} is refused: {why}", RuntimeWarning, stacklevel=2)

    def _refusals(self):
        return "; ".join(f"{a} is refused: {why}" for a, why in self.refused.items())

    def wait_for_minimum(self):
        """Wait for min_workers usable workers, at most the grace time."""
        start = time.monotonic()
        while True:
            self.refresh(every=0)
            if len(self.usable) >= self.minimum:
                return
            waited = time.monotonic() - start
            if waited > self.grace:
                refused = f"; {self._refusals()}" if self.refused else ""
                raise ClusterError(
                    f"only {len(self.usable)} of the {self.minimum} workers asked for "
                    f"(min_workers) can run the study after {self.grace:g} s (grace_time): "
                    f"{len(self.client.nthreads())} joined the scheduler{refused}")
            time.sleep(min(TICK, max(0.0, self.grace - waited) + 0.01))

    def check_alive(self):
        """Raise ClusterError once no usable worker has been alive for the grace time."""
        self.refresh()
        if self.without is None or time.monotonic() - self.without <= self.grace:
            return
        causes = []
        if self.lost:
            causes.append(f"the workers {', '.join(self.lost[-4:])} left the cluster "
                          "(killed, or lost)")
        if self.refused:
            causes.append(self._refusals())
        if not causes:
            causes.append("no worker joined the scheduler")
        raise ClusterError(f"no worker able to run the study has been alive for "
                           f"{self.grace:g} s (grace_time): {'; '.join(causes)}")

