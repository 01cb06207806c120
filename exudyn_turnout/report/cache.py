"""On-disk cache of expensive results (FE receptances, FE passages), keyed by their inputs.

A result is stored as ``<key>.npz`` (its arrays) and ``<key>.json`` (everything else)
under the cache directory. The key is the SHA-256 of everything the result depends on:
the turnout file's content, the options and settings, the frequencies, and the files of
the package's stage folders that compute it, with the report's own modules that run the
computation or store its result (:data:`REPORT_RESULT_MODULES`) (:func:`code_fingerprint`:
a code change invalidates the entry). No pickle: a cache file cannot run code.

The default directory is ``$XDG_CACHE_HOME/exudyn_turnout`` (``~/.cache/exudyn_turnout``).
"""

from __future__ import annotations

import contextlib
import dataclasses
import hashlib
import json
import os
import warnings
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

__all__ = [
    "ResultCache",
    "default_cache_dir",
    "input_key",
    "file_fingerprint",
    "code_files",
    "code_fingerprint",
    "RESULT_STAGES",
    "REPORT_RESULT_MODULES",
]

#: Stage folders of the package whose code a cached result (FE receptance, FE static
#: stiffness, FE passage) can execute. One set for all: importing the package runs
#: ``corunning/`` code even for an FE receptance, and an FE receptance or stiffness profile is
#: recomputed in seconds, so a narrower set would save little and could go stale.
RESULT_STAGES = ("inputs", "wheel_rail", "corunning", "fe", "passage")

#: Modules of ``report/`` whose code is on the path of a cached value, part of every key:
#: ``passage_api`` picks the vehicle and makes the FE passage's options, ``passages`` runs the
#: report's passage (:func:`~exudyn_turnout.report.passages.run_passage`) and rebuilds a
#: cached one, and this module stores and reads every cached array. A change in them can
#: change what the cache returns; the rest of ``report/`` only reads results (text, figures,
#: criteria), so editing it keeps the cache (an FE passage of the full vehicle costs minutes:
#: 146 s stepping for the through route in validation/report/report.md).
REPORT_RESULT_MODULES = ("report/cache.py", "report/passage_api.py", "report/passages.py")

#: Top-level modules of the package that every stage may execute.
_TOP_LEVEL = ("__init__.py", "compiled_cache.py", "provenance.py", "receptance.py")

#: Package data that change results: turnout and vehicle files, wheel and rail profiles.
_DATA = ("data/**/*.toml", "data/wheel_rail/profiles/**/*")


def default_cache_dir() -> Path:
    """``$XDG_CACHE_HOME/exudyn_turnout``, or ``~/.cache/exudyn_turnout``.

    Returns
    -------
    Path
        The directory (it may not exist yet).
    """
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "exudyn_turnout"


def _jsonable(value: Any) -> Any:
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return {type(value).__name__: _jsonable(dataclasses.asdict(value))}
    if isinstance(value, np.ndarray):
        return hashlib.sha256(np.ascontiguousarray(value, dtype=float).tobytes()).hexdigest()
    if isinstance(value, Mapping):
        return {str(k): _jsonable(v) for k, v in sorted(value.items(), key=lambda kv: str(kv[0]))}
    if isinstance(value, (list, tuple)):
        return [_jsonable(v) for v in value]
    return value if isinstance(value, (str, int, float, bool, type(None))) else repr(value)


def input_key(*parts: Any) -> str:
    """SHA-256 (hex) of the parts: dataclasses, arrays (by their bytes), mappings, numbers, text.

    Parameters
    ----------
    *parts : Any
        Everything the result depends on.

    Returns
    -------
    str
        64 hex digits.
    """
    text = json.dumps(_jsonable(list(parts)), sort_keys=True, allow_nan=True)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def file_fingerprint(path: str | Path) -> str:
    """SHA-256 (hex) of a file's bytes.

    Parameters
    ----------
    path : str or Path

    Returns
    -------
    str
        64 hex digits.
    """
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


def _package_root() -> Path:
    """The folder of the ``exudyn_turnout`` package (the parent of ``report/``)."""
    return Path(__file__).resolve().parents[1]


def code_files(
    stages: Iterable[str] = RESULT_STAGES, root: str | Path | None = None
) -> tuple[Path, ...]:
    """Every file of the package whose content a result of ``stages`` depends on.

    All ``*.py`` files of the stage folders, recursively (a stage reorganised into
    sub-folders stays covered, no module is named), the package's top-level modules
    (``__init__.py``, ``compiled_cache.py``, ``provenance.py``, ``receptance.py``), the
    report modules that run or store a cached computation (:data:`REPORT_RESULT_MODULES`)
    and the package's data files that change results (``data/**/*.toml``, the wheel and
    rail profiles). Files of these that ``root`` does not have are left out.

    Parameters
    ----------
    stages : iterable of str
        Stage folders of the package, e.g. :data:`RESULT_STAGES`.
    root : str or Path, optional
        The package folder (default: the installed ``exudyn_turnout``).

    Returns
    -------
    tuple of Path
        Paths under ``root``, sorted, no duplicates.
    """
    root = _package_root() if root is None else Path(root)
    named = _TOP_LEVEL + REPORT_RESULT_MODULES
    files = {root / name for name in named if (root / name).is_file()}
    for stage in stages:
        files.update(f for f in (root / stage).rglob("*.py") if "__pycache__" not in f.parts)
    for pattern in _DATA:
        files.update(f for f in root.glob(pattern) if f.is_file())
    return tuple(sorted(files))


def code_fingerprint(stages: Iterable[str] = RESULT_STAGES, root: str | Path | None = None) -> str:
    """SHA-256 (hex) of the files of :func:`code_files` (their paths and bytes).

    Parameters
    ----------
    stages : iterable of str
        Stage folders of the package, e.g. :data:`RESULT_STAGES`.
    root : str or Path, optional
        The package folder (default: the installed ``exudyn_turnout``).

    Returns
    -------
    str
        64 hex digits; any change of a file's content, a new file or a removed one changes it.
    """
    root = _package_root() if root is None else Path(root)
    h = hashlib.sha256()
    for f in code_files(stages, root):
        name = f.relative_to(root).as_posix().encode()
        data = f.read_bytes()
        # lengths first: no two file sets can give the same byte stream
        h.update(f"{len(name)}:{len(data)}:".encode())
        h.update(name)
        h.update(data)
    return h.hexdigest()


@dataclass(frozen=True)
class ResultCache:
    """Arrays + JSON metadata per key in ``directory``; ``directory=None`` disables the cache."""

    directory: Path | None

    def _paths(self, key: str) -> tuple[Path, Path]:
        assert self.directory is not None
        return self.directory / f"{key}.npz", self.directory / f"{key}.json"

    def load(self, key: str) -> tuple[dict[str, np.ndarray], dict[str, Any]] | None:
        """The stored (arrays, metadata), or None if absent, disabled or unreadable.

        Parameters
        ----------
        key : str
            From :func:`input_key`.

        Returns
        -------
        (dict, dict) or None
            Arrays by name and the JSON metadata.
        """
        if self.directory is None:
            return None
        npz, meta = self._paths(key)
        try:
            if not (npz.is_file() and meta.is_file()):
                return None
            with np.load(npz, allow_pickle=False) as data:
                arrays = {k: data[k] for k in data.files}
            return arrays, json.loads(meta.read_text(encoding="utf-8"))
        except (OSError, ValueError):
            return None

    def save(self, key: str, arrays: Mapping[str, np.ndarray], metadata: Mapping[str, Any]) -> None:
        """Store arrays and JSON-serialisable metadata under key (no-op when disabled).

        A location that cannot be written (under a file, no permission, disk full) gives a
        warning and stores nothing: the run goes on without the cache.

        Parameters
        ----------
        key : str
            From :func:`input_key`.
        arrays : mapping
            name -> array (stored as ``<key>.npz``, no pickle).
        metadata : mapping
            JSON-serialisable values (stored as ``<key>.json``).
        """
        if self.directory is None:
            return
        npz, meta = self._paths(key)
        tmp = npz.with_suffix(".tmp.npz")
        named = {name: np.asarray(value) for name, value in arrays.items()}
        text = json.dumps(metadata, default=_jsonable, allow_nan=True)
        try:
            self.directory.mkdir(parents=True, exist_ok=True)
            # mypy cannot rule out an array named like the keyword allow_pickle: bool
            np.savez_compressed(tmp, **named)  # type: ignore[arg-type]
            tmp.replace(npz)
            meta.write_text(text, encoding="utf-8")
        except OSError as err:
            # an unusable cache location (under a file, not writable, disk full) costs the
            # cache, not the run: the result is kept in memory and the run goes on
            for path in (tmp, npz, meta):
                with contextlib.suppress(OSError):
                    path.unlink(missing_ok=True)
            warnings.warn(
                f"FE result cache {self.directory} is not usable "
                f"({err.strerror or err}): running without it",
                stacklevel=2,
            )
