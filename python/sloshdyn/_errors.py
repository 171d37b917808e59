"""Exceptions raised when the Fortran core returns a nonzero status.

The status codes are those of ``fortran/sloshdyn_status.f90``.
"""


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


def check_status(status, message, context=None):
    """Raise the exception matching a nonzero Fortran status, with the Fortran message."""
    status = int(status)
    if status == 0:
        return
    if isinstance(message, (bytes, bytearray)):
        message = message.decode("utf-8", "replace")
    message = str(message).strip()
    if context:
        message = f"{context}: {message}"
    if status == CANCELLED:
        raise KeyboardInterrupt(message)
    raise _BY_STATUS.get(status, SloshdynError)(message, status)
