"""The one atomic writer: reports, cache entries and generated code are never seen half-written.

The text goes to a temporary file in the target directory, is flushed and
``fsync``-ed, gets the permissions a plain ``open(path, "w")`` would give
(``0o666`` less the umask), and replaces the target with ``os.replace``
(atomic on POSIX and Windows).  On any error the temporary file is removed and
the target is left as it was.

Reports go through :func:`write_report`, which writes a regular file with
:func:`atomic_write` but writes *through* a symlink, a device or a pipe (never
replacing it), and :func:`output_problem` says before any work why a report
path cannot be written.

>>> import tempfile, pathlib
>>> d = pathlib.Path(tempfile.mkdtemp())
>>> atomic_write(d / "sub" / "x.txt", "hello\\n").read_text()
'hello\\n'
"""
from __future__ import annotations

import os
import stat
import sys
import tempfile
from pathlib import Path
from typing import Any

__all__ = ["atomic_write", "write_report", "output_problem", "directory_problem", "is_stdout", "toml_loads"]


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


def _written_through(path: str | os.PathLike[str]) -> bool:
    """True if ``path`` must be opened and written, not replaced: a symlink, or anything but a regular file."""
    p = Path(path)
    if p.is_symlink():
        return True
    try:
        mode = p.stat().st_mode
    except FileNotFoundError:
        return False
    return not stat.S_ISREG(mode) and not stat.S_ISDIR(mode)


def write_report(path: str | os.PathLike[str], text: str) -> None:
    """Deliver a report to what the user named: ``-`` (or a path that is stdout, :func:`is_stdout`)
    is stdout, anything else a path.

    A regular file (or a new path; one missing parent directory is created) is
    written atomically (:func:`atomic_write`).  A symlink, a character device
    (``/dev/stdout``, ``/dev/null``), a FIFO or a socket is opened for writing
    and written *through*: the link stays a link and its target gets the text,
    the device stays a device.  Raises ``OSError`` on failure.

    >>> import tempfile, pathlib
    >>> d = pathlib.Path(tempfile.mkdtemp())
    >>> (d / "target.json").write_text("old")
    3
    >>> (d / "link.json").symlink_to(d / "target.json")
    >>> write_report(d / "link.json", "new")
    >>> (d / "link.json").is_symlink(), (d / "target.json").read_text()
    (True, 'new')
    """
    if is_stdout(path):
        # through our own stdout, not a second open of /proc/self/fd/1 (that would truncate a redirected file)
        sys.stdout.write(text)
        sys.stdout.flush()
        return
    if _written_through(path):
        # never os.replace a device, pipe or link: that would swap it for a regular file
        with open(path, "w", encoding="utf-8") as fh:
            fh.write(text)
        return
    parent = Path(path).parent
    if not parent.exists():
        parent.mkdir()
    atomic_write(path, text, mkdir=False)


def is_stdout(path: str | os.PathLike[str]) -> bool:
    """True for ``-`` and for a path that is this process's stdout when that is a pipe or a file.

    ``--json /dev/stdout > out.json`` then behaves like ``--json -``: the report alone on stdout,
    the text report moved to stderr.  A terminal or ``/dev/null`` (character devices) is not
    counted: nothing parses them.

    >>> is_stdout("-"), is_stdout("/")
    (True, False)
    """
    if str(path) == "-":
        return True
    try:
        st, out = os.stat(path), os.fstat(sys.stdout.fileno())
    except (OSError, ValueError, AttributeError):       # no such path, or a replaced sys.stdout
        return False
    return (st.st_dev, st.st_ino) == (out.st_dev, out.st_ino) and not stat.S_ISCHR(out.st_mode)


def _probe_directory(directory: Path) -> str | None:
    """Why a file cannot be created in ``directory`` (tried for real: root ignores modes, /proc refuses)."""
    try:
        fd, tmp = tempfile.mkstemp(dir=directory, prefix=".symbt-probe.", suffix=".tmp")
    except OSError as exc:
        return f"directory {directory} is not writable ({exc.strerror or exc})"
    os.close(fd)
    os.unlink(tmp)
    return None


def directory_problem(directory: str | os.PathLike[str]) -> str | None:
    """Why files cannot be created in ``directory`` (None if they can; missing levels may be created).

    The nearest existing ancestor must be a directory in which a file can really be
    created (tried: root ignores permission bits, a read-only mount or ``/proc`` does not).

    >>> directory_problem("/proc/symbt-out")
    '/proc is not writable'
    """
    d = Path(os.path.abspath(directory))
    while not d.exists() and d != d.parent:
        d = d.parent
    if not d.is_dir():
        return f"{d} is not a directory"
    if not os.access(d, os.W_OK) or _probe_directory(d):
        return f"{d} is not writable"
    return None


def output_problem(path: str | os.PathLike[str]) -> str | None:
    """Why a report cannot be written to ``path`` (None if it can; ``"-"`` is stdout).

    Checked before any work starts, with the rules of :func:`write_report`: a
    symlink, device or pipe must be writable as it is; a regular file or a new
    path needs a directory in which a file can really be created (a missing
    parent directory may be created, one level deep).

    >>> output_problem("-") is None, output_problem("/")
    (True, '/: is a directory')
    >>> output_problem("/no/such/dir/report.json")
    '/no/such/dir/report.json: directory /no/such does not exist'
    """
    if str(path) == "-":
        return None
    p = Path(path)
    if p.is_dir():
        return f"{path}: is a directory"
    if _written_through(p):
        if p.exists():
            if not os.access(p, os.W_OK):
                return f"{path}: not writable"
            return None
        p = Path(os.path.realpath(p))          # a dangling link: its target will be created
    parent = p.parent
    if parent.exists():
        if not parent.is_dir():
            return f"{path}: {parent} is not a directory"
        if not os.access(parent, os.W_OK):
            return f"{path}: directory {parent} is not writable"
        problem = _probe_directory(parent)
        return f"{path}: {problem}" if problem else None
    if not parent.parent.is_dir():
        return f"{path}: directory {parent.parent} does not exist"
    if not os.access(parent.parent, os.W_OK) or _probe_directory(parent.parent):
        return f"{path}: directory {parent.parent} is not writable"
    return None


def toml_loads(text: str) -> dict[str, Any]:
    """``text`` parsed as TOML -- the one TOML reader (the ``[tool.symbt]`` table, the equivalents file, a
    checkout's ``pyproject.toml``): ``tomllib`` from Python 3.11, else ``tomli`` (a dependency on 3.10).  A
    ``ValueError`` (``TOMLDecodeError``) if it is not TOML.

    >>> toml_loads('[project]\\nname = "symbt"')["project"]["name"]
    'symbt'
    >>> try:
    ...     toml_loads("name = ")
    ... except ValueError as exc:          # tomllib.TOMLDecodeError is a ValueError
    ...     print(type(exc).__name__)
    TOMLDecodeError
    """
    try:
        import tomllib
    except ModuleNotFoundError:  # Python 3.10
        import tomli as tomllib
    return tomllib.loads(text)
