"""Exceptions raised when the Fortran core returns a nonzero status, and the exit codes of both
front doors.

The status codes are those of ``fortran/base/sloshdyn_status.f90``; so is the rule that turns a
status into an exit code (its exit_code, which the executable applies): `exit_code` below asks
the core, so sloshdyn-py and the executable exit alike by construction.
"""

from . import _core


class SloshdynError(Exception):
    """Base class of every sloshdyn error; ``status`` is the Fortran status code."""

    status = None

    def __init__(self, message, status=None):
        super().__init__(message)
        if status is not None:
            self.status = status


class InputError(SloshdynError, ValueError):
    """An input value is missing, malformed or out of its allowed range."""

    status = 1


class ConvergenceError(SloshdynError):
    """An iterative solver did not converge."""

    status = 2


class SingularMatrixError(SloshdynError):
    """A linear system or Jacobian is singular."""

    status = 3


class LapackError(SloshdynError):
    """LAPACK returned a nonzero info."""

    status = 4


class IntegrationError(SloshdynError):
    """The time integration failed (step too small, too many steps, non-finite state)."""


class CapacityError(SloshdynError):
    """A result did not fit the space reserved for it."""

    status = 9


class FileError(SloshdynError, OSError):
    """A file could not be read or written."""

    status = 8


class ClusterError(SloshdynError):
    """A study's cluster cannot run it: no worker that can run sloshdyn of this version has
    been alive for the study's grace time (all gone, none joined, or all refused), or fewer
    than its min_workers joined. The points stored are kept (rerun to resume)."""

    exit_status = 7


CANCELLED = 10    #: the core stopped on request (python/sloshdyn/_cancel.py): KeyboardInterrupt

_BY_STATUS = {
    1: InputError,
    2: ConvergenceError,
    3: SingularMatrixError,
    4: LapackError,
    5: IntegrationError,
    6: IntegrationError,
    7: IntegrationError,
    8: FileError,
    9: CapacityError,
}


#: the exit codes of both front doors and what each says (docs/failure.md)
EXIT_MEANINGS = {
    0: "success: every result file of the run is complete",
    1: "check: a quantity is outside its tolerance",
    2: "usage: the command line is wrong",
    3: "input: a namelist value, a rule, an input file that cannot be read or is malformed "
       "(check: a corrupted values.json or reference table); nothing was written",
    4: "the computation failed (no convergence, integration failure, singular matrix, "
       "LAPACK); nothing was written",
    5: "the results could not be written (a full disk, a read-only directory, an output "
       "directory that holds a file no run wrote); nothing of "
       "the run is left under a final name",
    130: "interrupted (Ctrl-C); no file was left half-written",
    6: "study: some points failed, each stored with its status and message (the others are "
       "complete)",
    7: "study: no worker could run it (none alive, none with this sloshdyn) within its grace "
       "time, or fewer than min_workers joined; the points stored are kept",
    130: "interrupted (Ctrl-C); no file was left half-written",
    143: "terminated (SIGTERM); no file was left half-written",
}
EXIT_FAILURE, EXIT_INTERRUPTED, EXIT_TERMINATED = 4, 130, 143
EXIT_POINTS_FAILED = 6


def exit_code(error, reading=False):
    """The exit code of a SloshdynError: the core's rule for its status (any status while the
    input is read is an input error); a study's own errors have their own code."""
    if getattr(error, "exit_status", None) is not None:
        return error.exit_status
    return int(_core.sloshdyn_bridge_input.exit_code(int(error.status or 1), bool(reading)))


def message_text(message):
    """A message from the bridge (bytes of a Fortran character) as text."""
    if isinstance(message, (bytes, bytearray)):
        message = message.decode("utf-8", "replace")
    return str(message).strip()


def with_partial(result, status, message, what):
    """result, or (status nonzero) the status's exception with result as its ``partial``."""
    if status:
        try:
            check_status(status, message, what)
        except Exception as exc:
            exc.partial = result
            raise
    return result


def check_status(status, message, context=None):
    """Raise the exception matching a nonzero Fortran status, with the Fortran message."""
    status = int(status)
    if status == 0:
        return
    message = message_text(message)
    if context:
        message = f"{context}: {message}"
    if status == CANCELLED:
        raise KeyboardInterrupt(message)
    raise _BY_STATUS.get(status, SloshdynError)(message, status)
