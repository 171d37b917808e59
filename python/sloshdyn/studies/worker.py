"""Preloaded by the worker processes of a study's embedded cluster (engine._client): they
ignore SIGINT. Ctrl-C reaches every process of the terminal's process group; the study's own
process stops the study and closes the cluster, so the workers need not print their
KeyboardInterrupt tracebacks."""

import signal


def dask_setup(worker):
    signal.signal(signal.SIGINT, signal.SIG_IGN)
