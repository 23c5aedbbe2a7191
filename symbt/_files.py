"""The one atomic writer: reports, cache entries and generated code are never seen half-written.

The text goes to a temporary file in the target directory, is flushed and
``fsync``-ed, gets the permissions a plain ``open(path, "w")`` would give
(``0o666`` less the umask), and replaces the target with ``os.replace``
(atomic on POSIX and Windows).  On any error the temporary file is removed and
the target is left as it was.

>>> import tempfile, pathlib
>>> d = pathlib.Path(tempfile.mkdtemp())
>>> atomic_write(d / "sub" / "x.txt", "hello\\n").read_text()
'hello\\n'
"""
from __future__ import annotations

import os
import tempfile
from pathlib import Path

__all__ = ["atomic_write"]


def atomic_write(path: str | os.PathLike[str], data: str | bytes, *, mkdir: bool = True) -> Path:
    """Write ``data`` (text is UTF-8 encoded) to ``path`` atomically; return the path.

    ``mkdir`` creates missing parent directories.  Raises ``OSError`` (e.g.
    ``IsADirectoryError`` when ``path`` is a directory) without touching ``path``.
    """
    target = Path(path)
    if target.is_dir():
        raise IsADirectoryError(f"{target} is a directory")
    if mkdir:
        target.parent.mkdir(parents=True, exist_ok=True)
    raw = data.encode("utf-8") if isinstance(data, str) else bytes(data)
    fd, tmp = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(raw)
            fh.flush()
            os.fsync(fh.fileno())
        mask = os.umask(0)
        os.umask(mask)
        os.chmod(tmp, 0o666 & ~mask)
        os.replace(tmp, target)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    return target


def output_problem(path: str | os.PathLike[str]) -> str | None:
    """Why a report cannot be written to ``path`` (None if it can; ``"-"`` is stdout).

    Checked before any work starts.  A missing parent directory may be created, one level deep.

    >>> output_problem("-") is None, output_problem("/")
    (True, '/: is a directory')
    """
    if str(path) == "-":
        return None
    p = Path(path)
    if p.is_dir():
        return f"{path}: is a directory"
    parent = p.parent
    if parent.exists():
        if not parent.is_dir():
            return f"{path}: {parent} is not a directory"
        if not os.access(parent, os.W_OK):
            return f"{path}: directory {parent} is not writable"
    elif not parent.parent.is_dir():
        return f"{path}: directory {parent.parent} does not exist"
    return None
