"""Atomic file output: a file is either written completely or left untouched (temp file + os.replace).
A link is followed (the file it names is replaced, the link stays); a device or a pipe (/dev/null, a
FIFO) is written in place, as renaming over it would replace the device itself."""
from __future__ import annotations

import os
import stat
import tempfile
from typing import IO, Callable, Union

PathLike = Union[str, "os.PathLike[str]"]


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


_MODE = 0o666 & ~_umask()


def atomic_write(path: PathLike, write: Callable[[IO[bytes]], object]) -> None:
    """Call ``write(f)`` on a temporary file next to `path`, then move it over `path`.

    On any error the temporary file is removed and `path` is not touched.
    """
    path = os.fspath(path)
    target = os.path.realpath(path)  # links followed as far as they lead
    try:
        mode = os.stat(target).st_mode
    except FileNotFoundError:
        mode = None
    if mode is not None and not stat.S_ISREG(mode) and not stat.S_ISDIR(mode):  # a device or a pipe
        with open(target, "wb") as f:
            write(f)
        return
    folder = os.path.dirname(target)
    if not os.path.isdir(folder):  # else the error would name the temporary file
        raise FileNotFoundError(f"{path}: the folder {folder} does not exist")
    fd, tmp = tempfile.mkstemp(prefix="." + os.path.basename(target) + ".", suffix=".tmp", dir=folder)
    try:
        with os.fdopen(fd, "wb") as f:
            write(f)
            f.flush()
            os.fsync(f.fileno())
        os.chmod(tmp, stat.S_IMODE(mode) if mode is not None else _MODE)  # a replaced file keeps its mode
        os.replace(tmp, target)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise


def atomic_write_text(path: PathLike, text: str) -> None:
    """Write `text` (UTF-8) to `path` atomically."""
    data = text.encode("utf-8")
    atomic_write(path, lambda f: f.write(data))
