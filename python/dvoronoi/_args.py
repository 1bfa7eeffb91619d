"""Checks of the scalar arguments of the public functions, made before anything reaches the compiled
core: a pybind11 conversion error would list every accepted signature and print the whole call, arrays
included. Each message names the argument and says what it accepts.

Conventions (docs/spec.md, "API conventions"): ``workers: int | None = None`` everywhere, None or -1 = all
cores, k >= 1 = k threads, anything else a ValueError naming ``workers``; ``threads`` stays as a
deprecated alias (0 = all cores, as it always meant; None = not given, so ``threads=None`` does not
warn). Numbers are Python or numpy numbers (or 0-d arrays of them); a string such as ``"0.2"`` or a
bool is a TypeError, not converted.
"""
from __future__ import annotations

import math
import numbers
import warnings
from typing import Any, Optional

import numpy as np

#: The largest count the core takes (a C int).
MAX_COUNT = 2**31 - 1
#: Seeds are unsigned 64-bit integers.
MAX_SEED = 2**64 - 1


def _scalar(value: Any) -> Any:
    """A 0-d numpy array as its scalar; anything else as it is."""
    if isinstance(value, np.ndarray) and value.ndim == 0:
        return value[()]
    return value


def _show(value: Any) -> str:
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def _kind(value: Any) -> str:
    return f"{type(value).__name__} {_show(value)}"


def real(value: Any, name: str) -> float:
    """`value` as a float, or TypeError naming `name` unless it is a real number (not a bool, not a
    string)."""
    v = _scalar(value)
    if isinstance(v, bool) or isinstance(v, np.bool_) or not isinstance(v, numbers.Real):
        raise TypeError(f"{name} must be a real number, got {_kind(value)}")
    return float(v)


def text(value: Any, name: str) -> str:
    """`value` if it is a string; TypeError naming `name` otherwise."""
    if not isinstance(value, str):
        raise TypeError(f"{name} must be a string, got {_kind(value)}")
    return value


def positive(value: Any, name: str) -> float:
    """A finite number > 0; ValueError naming `name` otherwise (TypeError for a non-number)."""
    v = real(value, name)
    if not (math.isfinite(v) and v > 0.0):
        raise ValueError(f"{name} must be a positive finite number, got {_show(value)}")
    return v


def integer(value: Any, name: str, minimum: Optional[int] = None, maximum: Optional[int] = None) -> int:
    """`value` as an int within [minimum, maximum]; TypeError naming `name` unless it is an integer
    (2.0 and "2" are not), ValueError outside the range."""
    v = _scalar(value)
    if isinstance(v, (bool, np.bool_)) or not isinstance(v, numbers.Integral):
        raise TypeError(f"{name} must be an integer, got {_kind(value)}")
    v = int(v)
    if (minimum is not None and v < minimum) or (maximum is not None and v > maximum):
        if maximum is None:
            raise ValueError(f"{name} must be >= {minimum}, got {v}")
        lo = "" if minimum is None else f"from {minimum} "
        raise ValueError(f"{name} must be an integer {lo}to {maximum}, got {_show(v)}")
    return v


def seed(value: Any, name: str = "seed") -> int:
    """A seed: an integer from 0 to 2**64 - 1."""
    return integer(value, name, 0, MAX_SEED)


def workers(workers: Any = None, threads: Any = None, *, stacklevel: int = 3) -> int:
    """The thread count for the core (0 = all cores) from ``workers`` (None or -1 = all cores,
    k >= 1 = k threads; anything else is a ValueError naming ``workers``) or from the deprecated
    alias ``threads`` (0 = all cores, k >= 1 = k threads; None = not given), which warns."""
    if threads is not None:
        if workers is not None:
            raise ValueError("give workers or its deprecated alias threads, not both")
        warnings.warn("threads= is deprecated; use workers= (None or -1 = all cores, k >= 1 = k threads)",
                      DeprecationWarning, stacklevel=stacklevel)
        t = _scalar(threads)
        if isinstance(t, (bool, np.bool_)) or not isinstance(t, numbers.Integral) or not 0 <= int(t) <= MAX_COUNT:
            raise ValueError(f"threads must be 0 (all cores) or an integer from 1 to {MAX_COUNT}, got "
                             f"{_kind(threads)} (threads= is deprecated: use workers=)")
        return int(t)
    if workers is None:
        return 0
    w = _scalar(workers)
    if not isinstance(w, (bool, np.bool_)) and isinstance(w, numbers.Integral):
        if int(w) == -1:
            return 0
        if 1 <= int(w) <= MAX_COUNT:
            return int(w)
    zero = isinstance(w, numbers.Number) and not isinstance(w, bool) and w == 0
    hint = " (0 is not a count; all cores is None or -1)" if zero else ""
    raise ValueError(f"workers must be None or -1 (all cores) or an integer from 1 to {MAX_COUNT}, got "
                     f"{_kind(workers)}{hint}")
