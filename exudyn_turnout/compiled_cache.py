"""Numba's cache of compiled functions, discarded when any compiled source changes.

The contact kernel, the creep table's interpolation, the track springs and the CSV writer
are numba functions compiled once and cached next to their modules (``__pycache__/*.nbi``,
``*.nbc``).  Numba checks a cached function against the time stamp of *its own* file only:
a function that calls a compiled function of another module (the kernel calls the creep
table's ``table_creep_scalar``) keeps the machine code of the callee it was compiled with.
Measured: after the creep table's interpolation changed in ``creep_table.py``, the
kernel's cached code went on applying the old interpolation to the new table, silently,
until its cache files were deleted (tests/test_compiled_cache.py reproduces it).

:func:`refresh_compiled_cache` closes that hole: it hashes the source of every module of
the package that uses numba, keeps the digest in ``__pycache__/numba-sources.sha256`` at
the package's top, and when the digest differs deletes the package's numba cache files,
so every function is compiled afresh against its current callees.  ``import
exudyn_turnout`` calls it once (a few milliseconds: the sources are read and hashed).
Where the package directory is not writable (numba then caches elsewhere, or not at all)
nothing is done.
"""

from __future__ import annotations

import hashlib
from pathlib import Path

__all__ = ["STAMP_NAME", "compiled_sources_digest", "refresh_compiled_cache"]

#: File name of the digest, in the package's top ``__pycache__`` directory.
STAMP_NAME = "numba-sources.sha256"

_PACKAGE = Path(__file__).resolve().parent
_CACHE_SUFFIXES = (".nbi", ".nbc")


def compiled_sources_digest(package_dir: Path | str | None = None) -> str:
    """SHA-256 over the sources of the package's modules that use numba.

    Parameters
    ----------
    package_dir : pathlib.Path or str, optional
        The package's directory (default: this package).

    Returns
    -------
    str
        Hex digest over (relative path, content) of every ``*.py`` file that mentions
        ``numba``, in sorted order.
    """
    root = Path(package_dir) if package_dir is not None else _PACKAGE
    digest = hashlib.sha256()
    for path in sorted(root.rglob("*.py")):
        content = path.read_bytes()
        if b"numba" in content:
            digest.update(str(path.relative_to(root)).encode())
            digest.update(b"\0")
            digest.update(content)
            digest.update(b"\0")
    return digest.hexdigest()


def refresh_compiled_cache(package_dir: Path | str | None = None) -> bool:
    """Delete the package's numba cache files if any compiled source changed since.

    Parameters
    ----------
    package_dir : pathlib.Path or str, optional
        The package's directory (default: this package).

    Returns
    -------
    bool
        True if cache files were found stale and deleted (or the stamp was missing and
        written), False if the stamp matched or the directory is not writable.
    """
    root = Path(package_dir) if package_dir is not None else _PACKAGE
    stamp = root / "__pycache__" / STAMP_NAME
    digest = compiled_sources_digest(root)
    try:
        if stamp.read_text().strip() == digest:
            return False
    except OSError:
        pass
    try:
        for cache_dir in root.rglob("__pycache__"):
            for path in cache_dir.iterdir():
                if path.suffix in _CACHE_SUFFIXES:
                    path.unlink(missing_ok=True)
        stamp.parent.mkdir(exist_ok=True)
        temporary = stamp.with_name(f"{STAMP_NAME}.{digest[:8]}.tmp")
        temporary.write_text(digest + "\n")
        temporary.replace(stamp)
    except OSError:
        return False
    return True
