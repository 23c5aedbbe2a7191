r"""The project a front end works on: which claims, which paper, which reasons, budget and cache.

Every front end (``symbt verify | scenes | mutate | coverage``, the pytest plugin) asks
:func:`discover` for its :class:`Project` and :func:`load` for its claims, so they all agree.

Where the settings come from, the first that applies:

1. command-line options (``--claims MODULE_OR_PATH``, repeatable; ``--paper``; ``--budget``);
2. a ``[tool.symbt]`` table in the first ``pyproject.toml`` found from the working directory
   upwards (as pytest finds its configuration)::

       [tool.symbt]
       claims = ["note_claims.py"]          # modules or paths (relative to this file)
       paper = "note.tex"                   # the paper's LaTeX source (symbt coverage)
       budget = 60                          # seconds per claim
       cache-dir = ".symbt-cache"           # else $SYMBT_CACHE_DIR or ~/.cache/symbt
       codegen = ["model_emit.py"]          # modules or paths declaring `symbt.emit` functions
       codegen-out = "generated"            # where `symbt codegen` writes them (the default)
       [tool.symbt.reasons]                 # labels that carry no claim, and why
       def-H = "a definition"

3. neither: Zullo's paper, the package's own claims module :data:`PACKAGE_CLAIMS`.

With a user's configuration or ``--claims`` only the user's claims run; list
``"symbt.claims"`` among them to run Zullo's too.

A *claims source* is a module name (``note_claims``, ``mypaper.claims``) or a path to a ``.py``
file or package directory.  Importing it registers its claims (``@symbt.claim``); a package may
list submodules to import in ``CLAIM_MODULES`` (the package's own :mod:`symbt.claims` does).
The source *owns* the claims defined in it and in its submodules; only those are selected.

A path is imported under its own name with its directory first on ``sys.path`` (so helper modules
beside it import as they would in a script); a file inside a package is imported as part of its
package.

>>> p = discover(start=Path("/"))
>>> p.claims, p.is_package
(('symbt.claims',), True)
"""
from __future__ import annotations

import hashlib
import importlib
import os
import sys
import sysconfig
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from .._files import toml_loads

if TYPE_CHECKING:
    from ..claims.base import Claim

__all__ = ["Project", "ConfigError", "PACKAGE_CLAIMS", "discover", "find_config", "read_config", "load",
           "owned", "claim_module", "project_digest", "emitted_digest", "active", "CONFIG_KEYS", "DEFAULT_CODEGEN_OUT"]

#: the package's own claims (Zullo's paper), a claims source like any other
PACKAGE_CLAIMS = "symbt.claims"
#: the keys of ``[tool.symbt]``
CONFIG_KEYS = ("claims", "paper", "reasons", "budget", "cache-dir", "codegen", "codegen-out")
#: where ``symbt codegen`` writes a user's emitted modules, relative to the configuration file
DEFAULT_CODEGEN_OUT = "generated"


class ConfigError(ValueError):
    """A bad ``[tool.symbt]`` table, or a claims source that does not exist or does not import (one line)."""


@dataclass(frozen=True)
class Project:
    """What the front ends work on (see the module docstring).

    ``root`` is the directory of the configuration file (or the working directory);
    ``claims`` the claims sources (module names, or absolute paths); ``paper`` the LaTeX
    source (``None``: Zullo's paper as shipped, or none given); ``reasons`` label -> why it
    carries no claim; ``budget`` seconds per claim (``None``: the engine's default);
    ``cache_dir`` the claim cache (``None``: ``$SYMBT_CACHE_DIR`` or ``~/.cache/symbt``);
    ``codegen`` the sources declaring ``symbt.emit`` functions (each gets claims comparing the
    emitted file in ``codegen_out`` with its SymPy source).
    """

    root: Path
    claims: tuple[str, ...] = (PACKAGE_CLAIMS,)
    config: Path | None = None
    paper: Path | None = None
    reasons: Mapping[str, str] = field(default_factory=dict)
    budget: float | None = None
    cache_dir: Path | None = None
    codegen: tuple[str, ...] = ()
    codegen_out: Path | None = None

    @property
    def is_package(self) -> bool:
        """Only Zullo's paper (the package's own claims)."""
        return self.claims == (PACKAGE_CLAIMS,)

    @property
    def includes_package(self) -> bool:
        return PACKAGE_CLAIMS in self.claims

    def label(self) -> str:
        """A stable name of the claim set (keys the warm path's manifest)."""
        if self.is_package:
            return ""
        text = "\0".join((str(self.root), *self.claims, *self.codegen))
        return hashlib.sha256(text.encode()).hexdigest()[:16]


# --------------------------------------------------------------------------- configuration

def find_config(start: Path | None = None) -> Path | None:
    """The first ``pyproject.toml`` with a ``[tool.symbt]`` table in ``start`` (default: cwd) or above."""
    here = (start or Path.cwd()).resolve()
    for d in (here, *here.parents):
        f = d / "pyproject.toml"
        if f.is_file():
            try:
                text = f.read_text(encoding="utf-8")
            except OSError:
                continue
            if "[tool.symbt" in text and _has_table(text):
                return f
    return None


def _has_table(text: str) -> bool:
    """Whether the TOML ``text`` has a ``[tool.symbt]`` table (a file that does not parse: yes, so its
    reader reports the error instead of silently skipping the file)."""
    try:
        return toml_loads(text).get("tool", {}).get("symbt") is not None
    except ValueError:
        return True




def read_config(path: Path) -> dict[str, Any]:
    """The validated ``[tool.symbt]`` table of ``path`` (paths made absolute); :class:`ConfigError` if malformed."""
    try:
        data = toml_loads(path.read_text(encoding="utf-8"))
    except OSError as exc:
        raise ConfigError(f"cannot read {path}: {exc.strerror or exc}") from None
    except ValueError as exc:  # tomllib.TOMLDecodeError
        raise ConfigError(f"{path}: not valid TOML: {exc}") from None
    table = data.get("tool", {}).get("symbt")
    if table is None:
        return {}
    where = f"{path} [tool.symbt]"
    if not isinstance(table, dict):
        raise ConfigError(f"{where}: must be a table")
    unknown = sorted(set(table) - set(CONFIG_KEYS))
    if unknown:
        raise ConfigError(f"{where}: unknown key(s) {', '.join(unknown)}; known: {', '.join(CONFIG_KEYS)}")
    base = path.parent
    out: dict[str, Any] = {}
    for key, attr in (("claims", "claims"), ("codegen", "codegen")):
        if key in table:
            out[attr] = _sources(table[key], f"{where}: '{key}'", base)
    for key, attr in (("paper", "paper"), ("cache-dir", "cache_dir"), ("codegen-out", "codegen_out")):
        if key in table:
            if not isinstance(table[key], str) or not table[key]:
                raise ConfigError(f"{where}: '{key}' must be a path")
            out[attr] = (base / table[key]).resolve()
    if "reasons" in table:
        r = table["reasons"]
        if not isinstance(r, dict) or not all(isinstance(k, str) and isinstance(v, str) and v for k, v in r.items()):
            raise ConfigError(f"{where}: 'reasons' must be a table of label = \"reason\"")
        out["reasons"] = dict(r)
    if "budget" in table:
        out["budget"] = _budget(table["budget"], f"{where}: 'budget'")
    return out


def _sources(value: Any, what: str, base: Path) -> tuple[str, ...]:
    """A list of module names or paths (a single string is a list of one); paths made absolute."""
    if isinstance(value, str):
        value = [value]
    if not isinstance(value, list) or not value or not all(isinstance(c, str) and c for c in value):
        raise ConfigError(f"{what} must be a non-empty list of module names or paths")
    return tuple(_source_spec(c, base) for c in value)


def _budget(value: Any, what: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not (0 < value < float("inf")):
        raise ConfigError(f"{what} must be a positive number of seconds, not {value!r}")
    return float(value)


def _looks_like_path(spec: str) -> bool:
    return spec.endswith(".py") or "/" in spec or os.sep in spec or spec.startswith(".")


def _source_spec(spec: str, base: Path) -> str:
    """A module name as given; a path made absolute against ``base``."""
    if _looks_like_path(spec) or (base / spec).exists() and not spec.isidentifier():
        return str((base / spec).resolve())
    return spec


def discover(*, claims: Sequence[str] = (), paper: str | os.PathLike[str] | None = None,
             budget: float | None = None, start: Path | None = None, config: Path | None = None,
             codegen: Sequence[str] = ()) -> Project:
    """The project for the given options and the ``[tool.symbt]`` found from ``start`` (default: cwd).

    Options given here win over the configuration.  Raises :class:`ConfigError`.
    """
    cwd = (start or Path.cwd()).resolve()
    cfg_path = config if config is not None else find_config(cwd)
    cfg = read_config(cfg_path) if cfg_path is not None else {}
    root = cfg_path.parent.resolve() if cfg_path is not None else cwd
    emitters = tuple(_source_spec(c, cwd) for c in codegen) or cfg.get("codegen") or ()
    # a project that only emits code has no claims of its own besides those of its emitted functions
    if cfg_path is not None and not claims and not emitters and "claims" not in cfg:
        raise ConfigError(f"{cfg_path} [tool.symbt]: no 'claims' (your claims modules or paths; "
                          "\"symbt.claims\" for Zullo's paper), or give --claims")
    sources = tuple(_source_spec(c, cwd) for c in claims) or cfg.get("claims") or \
        (() if emitters else (PACKAGE_CLAIMS,))
    return Project(root=root, claims=tuple(dict.fromkeys(sources)), config=cfg_path,
                   codegen=tuple(dict.fromkeys(emitters)),
                   codegen_out=cfg.get("codegen_out") or (root / DEFAULT_CODEGEN_OUT if emitters else None),
                   paper=Path(paper).resolve() if paper else cfg.get("paper"),
                   reasons=cfg.get("reasons", {}),
                   budget=_budget(budget, "--budget") if budget is not None else cfg.get("budget"),
                   cache_dir=cfg.get("cache_dir"))


# --------------------------------------------------------------------------- loading claims

_ACTIVE: list[Project] = []


def active() -> Project | None:
    """The project whose claims were loaded last (the warm path's manifest records its claims)."""
    return _ACTIVE[-1] if _ACTIVE else None


def _import_path(path: Path) -> str:
    """Put the directory above ``path``'s package (or beside the file) on ``sys.path``; the module name."""
    if not path.exists():
        raise ConfigError(f"claims path {path} does not exist")
    if path.is_dir():
        if not (path / "__init__.py").is_file():
            raise ConfigError(f"claims path {path} is a directory without __init__.py")
        parts, above = [path.name], path.parent
    elif path.suffix == ".py":
        parts, above = ([path.parent.name], path.parent.parent) if path.name == "__init__.py" else \
            ([path.stem], path.parent)
    else:
        raise ConfigError(f"claims path {path} is neither a .py file nor a package directory")
    while (above / "__init__.py").is_file():  # a file inside a package is imported as part of it
        parts.insert(0, above.name)
        above = above.parent
    name = ".".join(parts)
    if not all(p.isidentifier() for p in parts):
        raise ConfigError(f"claims path {path}: {name!r} is not an importable module name")
    if str(above) not in sys.path:
        sys.path.insert(0, str(above))
    existing = sys.modules.get(name)
    f = getattr(existing, "__file__", None)
    want = path / "__init__.py" if path.is_dir() else path
    if f is not None and Path(f).resolve() != want.resolve():
        raise ConfigError(f"claims path {path}: a different module named {name!r} is already imported ({f})")
    return name


def _import(spec: str, what: str = "claims") -> str:
    """Import one claims (or codegen) source; the module name that owns its claims."""
    name = _import_path(Path(spec)) if os.path.isabs(spec) or _looks_like_path(spec) else spec
    try:
        mod = importlib.import_module(name)
    except ConfigError:
        raise
    except ModuleNotFoundError as exc:
        if exc.name and (name == exc.name or name.startswith(exc.name + ".")):
            raise ConfigError(f"{what} module {spec!r} not found (not importable from {Path.cwd()}; "
                              "give a path, or install it)") from None
        raise ConfigError(f"{what} module {spec!r} does not import: {type(exc).__name__}: {exc}") from None
    except Exception as exc:  # the user's module raised: say so in one line
        raise ConfigError(f"{what} module {spec!r} does not import: {type(exc).__name__}: {exc}") from None
    from ..claims import import_listed

    import_listed(name, tuple(getattr(mod, "CLAIM_MODULES", ())))
    return name


def claim_module(c: Any) -> str:
    """The module that declared a claim (else the module its check is defined in)."""
    if getattr(c, "module", ""):
        return str(c.module)
    fn = c.func or getattr(c.check, "func", c.check)
    return getattr(fn, "__module__", None) or ""


def owned(module: str, owners: Sequence[str]) -> bool:
    """Is a claim defined in ``module`` owned by one of the sources ``owners`` (module names)?

    >>> owned("symbt.claims.toy", ["symbt.claims"]), owned("note", ["symbt.claims"])
    (True, False)
    """
    return any(module == o or module.startswith(o + ".") for o in owners)


_OWNERS: dict[tuple[str, ...], tuple[str, ...]] = {}


def load(project: Project | None = None) -> list[Claim]:
    """Import the project's claims sources; its claims, in registration order.

    A source that registers no claim is a :class:`ConfigError` (a typo, or a module that is
    not a claims module).
    """
    from ..claims.base import REGISTRY

    project = project or discover()
    if project.cache_dir is not None and not os.environ.get("SYMBT_CACHE_DIR"):
        os.environ["SYMBT_CACHE_DIR"] = str(project.cache_dir)
    owners = _OWNERS.get(project.claims + project.codegen)
    if owners is None:
        names = []
        for spec in project.claims:
            name = _import(spec)
            if not any(owned(claim_module(c), [name]) for c in REGISTRY.values()):
                raise ConfigError(f"claims source {spec!r} registers no claim (declare them with @symbt.claim)")
            names.append(name)
        if project.codegen:   # the claims of the emitted functions, owned by their declaring modules
            from ..codegen.user.declare import emissions_of
            from .emitted_claims import register_emitted

            for spec in project.codegen:
                name = _import(spec, "codegen")
                if not emissions_of([name]):
                    raise ConfigError(f"codegen source {spec!r} declares nothing to emit (call symbt.emit)")
                names.append(name)
                register_emitted(emissions_of([name]), project.root,
                                 project.codegen_out or project.root / DEFAULT_CODEGEN_OUT)
        owners = _OWNERS[project.claims + project.codegen] = tuple(names)
    if not _ACTIVE or _ACTIVE[-1] != project:
        _ACTIVE.append(project)
    return [c for c in REGISTRY.values() if owned(claim_module(c), owners)]


# --------------------------------------------------------------------------- what a user's claim depends on

_SKIP_DIRS = {"__pycache__", "node_modules", "build", "dist", "site-packages", "dist-packages"}


def _library_dirs() -> set[Path]:
    dirs = set()
    for key in ("stdlib", "platstdlib", "purelib", "platlib"):
        try:
            dirs.add(Path(sysconfig.get_paths()[key]).resolve())
        except (KeyError, OSError):
            pass
    return dirs


def _python_files(root: Path) -> list[Path]:
    if root.is_file():
        return [root]
    out = []
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames[:] = sorted(d for d in dirnames if not d.startswith(".") and d not in _SKIP_DIRS
                             and not d.endswith(".egg-info")
                             and not (Path(dirpath) / d / "pyvenv.cfg").exists())
        out += [Path(dirpath) / f for f in sorted(filenames) if f.endswith(".py")]
    return out


_DIGESTS: dict[tuple[Any, ...], str] = {}


def _digest_of(root: Path) -> str:
    """SHA-256 of the paths and bytes of the Python files under ``root``; rehashed only when a stat changed."""
    files = _python_files(root)
    stats = []
    for f in files:
        try:
            st = f.stat()
        except OSError:
            continue
        stats.append((str(f), st.st_mtime_ns, st.st_size))
    sig = (str(root), *stats)
    hit = _DIGESTS.get(sig)
    if hit is not None:
        return hit
    h = hashlib.sha256()
    for name, _, _ in stats:
        f = Path(name)
        try:
            data = f.read_bytes()
        except OSError:
            continue
        h.update(str(f.relative_to(root) if root.is_dir() else f.name).encode() + b"\0")
        h.update(data)
    _DIGESTS[sig] = h.hexdigest()
    return _DIGESTS[sig]


def source_root(module_file: Path, project_root: Path) -> Path:
    """The files a claim defined in ``module_file`` may depend on (a directory or the file itself).

    The project root when the module lies under it; else its top-level package's directory;
    else the module's directory, unless that is a library directory (site-packages, the
    standard library), where only the file itself counts.
    """
    f = module_file.resolve()
    if project_root in f.parents:
        return project_root
    top = f.parent
    if (top / "__init__.py").is_file():
        while (top.parent / "__init__.py").is_file():
            top = top.parent
        return top
    return f if top in _library_dirs() or top.name in _SKIP_DIRS else top


def project_digest(modules: Sequence[str], project_root: Path) -> str:
    """SHA-256 of every Python file the claims of ``modules`` may depend on (see :func:`source_root`),
    and of the files in the active project's ``codegen_out`` (the emitted files its claims read).

    Bytes only -- nothing is imported -- and memoised per process.
    """
    roots = set()
    for name in modules:
        mod = sys.modules.get(name)
        f = getattr(mod, "__file__", None)
        if f:
            roots.add(source_root(Path(f), project_root.resolve()))
    h = hashlib.sha256()
    for r in sorted(roots):
        h.update(str(r).encode() + b"\0" + _digest_of(r).encode())
    h.update(emitted_digest(active()).encode())
    return h.hexdigest()


def emitted_digest(project: Project | None) -> str:
    """SHA-256 of the files in ``project``'s ``codegen_out`` (the emitted files the claims of its emitted
    functions read: C sources too, and wherever the directory lies); ``""`` without one."""
    out = None if project is None else project.codegen_out
    if out is None or not out.is_dir():
        return ""
    h = hashlib.sha256()
    for f in sorted(p for p in out.iterdir() if p.is_file()):
        h.update(f.name.encode() + b"\0" + hashlib.sha256(f.read_bytes()).hexdigest().encode())
    return h.hexdigest()
