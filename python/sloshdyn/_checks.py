"""Conversion and checks of the values a caller passes to the public functions, done once here
before anything reaches f2py, which would otherwise coerce silently (an array where a scalar
belongs gives its first element, complex loses its imaginary part, a bool is a number) or fail
with its own ValueError, OverflowError or MemoryError. Only the type, the shape, finiteness,
the range of a C int and the memory an output asks for are checked here; every rule of the
model and of the methods is the Fortran core's (one source of truth, its messages).

Every failure is an InputError naming the argument, its value and what is allowed."""

from __future__ import annotations

import math
import numbers
import os

import numpy as np

from ._errors import InputError

C_INT_MIN, C_INT_MAX = -2**31, 2**31 - 1
#: the largest result a single call may ask f2py to allocate: half the machine's memory
MAX_OUTPUT_BYTES = (os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")) // 2


def show(value):
    """A value as messages show it: reals as the Fortran core writes them (NaN, +Infinity),
    anything else by its repr, cut to 60 characters."""
    if isinstance(value, (float, np.floating)):
        x = float(value)
        if math.isnan(x):
            return "NaN"
        if math.isinf(x):
            return "+Infinity" if x > 0 else "-Infinity"
        return repr(x)
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def _is_bool(value):
    return isinstance(value, (bool, np.bool_))


def real(name, value):
    """A finite real scalar as a float (int, float and numpy reals; not bool, complex, str,
    arrays)."""
    if _is_bool(value) or not isinstance(value, numbers.Real):
        if isinstance(value, np.ndarray) and value.ndim == 0:
            return real(name, value[()])
        raise InputError(f"{name} = {show(value)} is not valid: {name} must be a real number")
    try:
        x = float(value)
    except OverflowError:
        x = math.inf if value > 0 else -math.inf
    if not math.isfinite(x):
        raise InputError(f"{name} = {show(x)} is not valid: {name} must be a finite real number")
    return x


def optional_real(name, value, default):
    """real(name, value), or default when value is None."""
    return default if value is None else real(name, value)


def integer(name, value, lower=C_INT_MIN, upper=C_INT_MAX):
    """An integer in [lower, upper] (by default the range of a C int) as an int: int and numpy
    integers, not bool or float."""
    if _is_bool(value) or not isinstance(value, numbers.Integral):
        if isinstance(value, np.ndarray) and value.ndim == 0:
            return integer(name, value[()], lower, upper)
        raise InputError(f"{name} = {show(value)} is not valid: {name} must be an integer")
    n = int(value)
    if not lower <= n <= upper:
        raise InputError(f"{name} = {n} is out of range: {name} must be an integer in "
                         f"[{lower}, {upper}]")
    return n


def flag(name, value):
    """True or False (bool, numpy bool)."""
    if not _is_bool(value):
        raise InputError(f"{name} = {show(value)} is not valid: {name} must be True or False")
    return bool(value)


def reals(name, value, shape=None, *, ndim=None, min_size=0, finite=True):
    """A C-contiguous float64 array of finite reals (finite=False: where the core or the caller
    checks finiteness with its own message), of the given shape (or number of dimensions), with
    at least min_size elements. Integer arrays convert; bool, complex, text and ragged
    sequences are refused."""
    try:
        a = np.asarray(value)
    except (TypeError, ValueError):
        a = None
    if a is None or a.dtype.kind not in "iuf":
        raise InputError(f"{name} = {show(value)} is not valid: {name} must be an array of "
                         "real numbers")
    if a.dtype.kind in "iu" and a.size and (a.max() > 2**53 or a.min() < -2**53):
        raise InputError(f"{name} holds integers beyond 2^53: they are not exact as reals")
    a = np.asarray(a, dtype=np.float64, order="C")   # keeps a 0-d array 0-d
    if shape is not None and a.shape != tuple(shape):
        raise InputError(f"{name} has shape {a.shape}: it must have shape {tuple(shape)}")
    if ndim is not None and a.ndim != ndim:
        raise InputError(f"{name} has shape {a.shape}: it must be {ndim}-dimensional")
    if a.size < min_size:
        raise InputError(f"{name} has {a.size} values: it needs at least {min_size}")
    bad = np.flatnonzero(~np.isfinite(a)) if finite else ()
    if len(bad):
        index = np.unravel_index(bad[0], a.shape) if a.ndim > 1 else (int(bad[0]),)
        where = ", ".join(str(int(i)) for i in index) if a.ndim else ""
        label = f"{name}[{where}]" if a.ndim else name
        raise InputError(f"{label} = {show(a.flat[bad[0]])} is not valid: every value of "
                         f"{name} must be a finite real number")
    return a


def interval(name, value):
    """(low, high): two finite reals (their order is the core's rule)."""
    a = reals(name, value) if not isinstance(value, (str, bytes)) else None
    if a is None or a.shape != (2,):
        raise InputError(f"{name} = {show(value)} is not valid: give two numbers (low, high)")
    return float(a[0]), float(a[1])


def choice(name, value, choices):
    """One of the allowed strings."""
    if not isinstance(value, str) or value not in choices:
        raise InputError(f"{name} = {show(value)} is not valid: it must be one of "
                         f"{', '.join(repr(c) for c in choices)}")
    return value


def text(name, value):
    """A string for the core: ASCII (what f2py passes to Fortran), no NUL (it ends a C
    string)."""
    if not isinstance(value, str) or "\0" in value or not value.isascii():
        raise InputError(f"{name} = {show(value)} is not valid: {name} must be a string of "
                         "ASCII characters")
    return value


def path(name, value):
    """A file path (str or path-like) as a string; give the core os.fsencode(path) (f2py
    takes only ASCII str, but any bytes)."""
    try:
        p = os.fspath(value)
    except TypeError:
        raise InputError(f"{name} = {show(value)} is not valid: {name} must be a path") from None
    if isinstance(p, bytes):
        p = os.fsdecode(p)
    if not p or "\0" in p:
        raise InputError(f"{name} = {show(value)} is not valid: {name} must be a non-empty path")
    return p


def instance(name, value, cls):
    """value itself if it is a cls."""
    if not isinstance(value, cls):
        raise InputError(f"{name} = {show(value)} is not valid: give a sloshdyn.{cls.__name__}")
    return value


def output_size(name, count, values_per_item=1):
    """Refuse a result of count items of values_per_item float64s that would take more than
    MAX_OUTPUT_BYTES (count is the caller's argument `name`, already an int)."""
    size = 8 * max(count, 0) * max(values_per_item, 1)
    if size > MAX_OUTPUT_BYTES or max(count, 0) * max(values_per_item, 1) > C_INT_MAX:
        raise InputError(f"{name} = {count} is out of range: its results would take "
                         f"{size / 2**30:.3g} GiB (at most {MAX_OUTPUT_BYTES / 2**30:.3g} GiB, "
                         f"half this machine's memory, and {C_INT_MAX} values)")
    return count
