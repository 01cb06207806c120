"""On-disk cache of expensive results (FE receptances, FE passages), keyed by their inputs.

A result is stored as ``<key>.npz`` (its arrays) and ``<key>.json`` (everything else)
under the cache directory. The key is the SHA-256 of everything the result depends on:
the turnout file's content, the options and settings, the frequencies, and the source
code of the modules that compute it (so that a code change invalidates the entry). No
pickle: a cache file cannot run code.

The default directory is ``$XDG_CACHE_HOME/exudyn_turnout`` (``~/.cache/exudyn_turnout``).
"""

from __future__ import annotations

import dataclasses
import hashlib
import importlib.util
import json
import os
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

__all__ = [
    "ResultCache",
    "default_cache_dir",
    "input_key",
    "source_fingerprint",
    "file_fingerprint",
]


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


def source_fingerprint(modules: Iterable[str]) -> str:
    """SHA-256 (hex) of the source files of modules (a package contributes all its ``.py`` files).

    Modules that cannot be found contribute their name only.

    Parameters
    ----------
    modules : iterable of str
        Dotted module or package names.

    Returns
    -------
    str
        64 hex digits.
    """
    h = hashlib.sha256()
    for name in sorted(modules):
        h.update(name.encode())
        spec = importlib.util.find_spec(name)
        if spec is None or spec.origin is None:
            continue
        origin = Path(spec.origin)
        files = sorted(origin.parent.glob("*.py")) if origin.name == "__init__.py" else [origin]
        for f in files:
            h.update(f.name.encode())
            h.update(f.read_bytes())
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
        if not (npz.exists() and meta.exists()):
            return None
        try:
            with np.load(npz, allow_pickle=False) as data:
                arrays = {k: data[k] for k in data.files}
            return arrays, json.loads(meta.read_text(encoding="utf-8"))
        except (OSError, ValueError):
            return None

    def save(self, key: str, arrays: Mapping[str, np.ndarray], metadata: Mapping[str, Any]) -> None:
        """Store arrays and JSON-serialisable metadata under key (no-op when disabled).

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
        self.directory.mkdir(parents=True, exist_ok=True)
        npz, meta = self._paths(key)
        tmp = npz.with_suffix(".tmp.npz")
        named = {name: np.asarray(value) for name, value in arrays.items()}
        # mypy cannot rule out an array named like the keyword allow_pickle: bool
        np.savez_compressed(tmp, **named)  # type: ignore[arg-type]
        tmp.replace(npz)
        meta.write_text(json.dumps(metadata, default=_jsonable, allow_nan=True), encoding="utf-8")
