"""The passage's output files: which files, the CSV and NPZ formats, their writers.

Pure numpy and the compiled CSV formatter (:mod:`~exudyn_turnout.passage.csv_format`):
:func:`~exudyn_turnout.passage.results.write_passage` writes a
:class:`~exudyn_turnout.passage.results.PassageResult` with these.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

__all__ = [
    "OUTPUT_FILES",
    "OUTPUT_DTYPES",
    "CSV_DIGITS",
    "without_empty_columns",
    "keeps_float64",
    "csv_text",
    "write_csv",
    "NPZ_LEVEL",
    "save_npz",
]


#: Files a passage command writes into its output directory (cleared before a run).
OUTPUT_FILES = (
    "timeseries.csv",
    "timeseries.npz",
    "summary.json",
    "forces.png",
    "contact_band.png",
    "safety.png",
    "wheelsets.png",
    "bodies.png",
)


#: Types of the NPZ arrays (:func:`write_passage`); "float32" halves the file again.
OUTPUT_DTYPES = ("float64", "float32")

#: Significant digits of the CSV's numbers: a double to ~1e-9 relative (time steps of
#: 1e-5 s in 10 s, x in mm over 1 km, forces to 0.1 mN at 100 kN).
CSV_DIGITS = 9


def without_empty_columns(columns: Mapping[str, np.ndarray]) -> dict[str, np.ndarray]:
    """The columns that hold at least one finite value, in their order.

    A contact-point or rail column of a body the run never met (e.g. the crossing nose in
    a run that ends before the crossing) is left out, so that no column of a result, its CSV
    or its NPZ is empty from top to bottom.

    Parameters
    ----------
    columns : mapping
        Name -> array.

    Returns
    -------
    dict
        The same arrays (not copied), all-NaN ones left out.
    """
    out = {}
    for name, values in columns.items():
        array = np.asarray(values)
        if array.dtype.kind not in "fc" or array.size == 0 or np.isfinite(array).any():
            out[name] = values
    return out


def keeps_float64(name: str) -> bool:
    """Whether a column stays float64 in a float32 NPZ: time and longitudinal positions.

    float32 resolves 2.4e-7 s at t = 2 s and 3.8e-6 m at x = 60 m: enough for a value, not
    for differences of neighbouring samples (a time step of 1e-5 s would carry 2 % error),
    so ``t_s``, ``x_m`` and ``x_<wheelset>_m`` keep their 16 digits.

    Parameters
    ----------
    name : str
        Column name.

    Returns
    -------
    bool
    """
    return name == "t_s" or (name.startswith("x_") and name.endswith("_m"))


def csv_text(columns: Mapping[str, np.ndarray], digits: int = CSV_DIGITS) -> str:
    """The columns as CSV text: a header line of names, then one line per sample.

    Numbers with ``digits`` significant digits (``%g``, the text of Python's formatting);
    a NaN or infinite value is an empty cell. Formatted in compiled code
    (:func:`~exudyn_turnout.passage.csv_format.format_rows`: ~11x faster than Python's
    formatting value by value).

    Parameters
    ----------
    columns : mapping
        Name -> 1-D array, all of one length.
    digits : int
        Significant digits.

    Returns
    -------
    str
        Ends with a newline.
    """
    from exudyn_turnout.passage.csv_format import format_rows

    names = list(columns)
    return ",".join(names) + "\n" + format_rows(_table(columns, names), digits)


def _table(columns: Mapping[str, np.ndarray], names: list[str]) -> np.ndarray:
    """(samples, columns) float64 table of the named columns."""
    return np.column_stack([np.asarray(columns[n], dtype=float) for n in names])


def write_csv(
    path, columns: Mapping[str, np.ndarray], digits: int = CSV_DIGITS, block: int = 1 << 16
) -> None:
    """Write :func:`csv_text` of the columns into a file, in blocks of rows.

    The same bytes as ``Path(path).write_text(csv_text(columns, digits), encoding="utf-8")``
    (the text is ASCII), formatted block by block of about ``block`` values into one small
    buffer (:func:`~exudyn_turnout.passage.csv_format.format_into`) and written from it:
    neither the whole table (45 MB for the full vehicle's main job) nor its text (58 MB)
    is ever held, nor copied into a ``str``.

    Parameters
    ----------
    path : str or Path
        The file, replaced.
    columns : mapping
        Name -> 1-D array, all of one length.
    digits : int
        Significant digits, 1 to 10.
    block : int
        Values per block (rows of at least one).
    """
    from exudyn_turnout.passage.csv_format import (
        COMPILED_FROM,
        buffer_size,
        format_into,
        format_rows_bytes,
    )

    names = list(columns)
    arrays = [np.asarray(columns[n]) for n in names]
    rows = arrays[0].shape[0] if arrays else 0
    with open(path, "wb") as handle:
        handle.write((",".join(names) + "\n").encode("utf-8"))
        if rows * len(names) < COMPILED_FROM:  # small: Python's formatting, as csv_text
            handle.write(format_rows_bytes(_table(columns, names), digits))
            return
        if not 1 <= digits <= 10:
            raise ValueError(f"digits must be 1 to 10, got {digits}")
        step = max(1, block // len(names))
        table = np.empty((step, len(names)))
        text = np.empty(buffer_size(step, len(names), digits), np.uint8)
        for start in range(0, rows, step):
            part = table[: min(step, rows - start)]
            for j, values in enumerate(arrays):
                part[:, j] = values[start : start + step]
            handle.write(text[: format_into(part, digits, text)].data)


#: zlib level of the NPZ: 1 compresses a passage's doubles as well as numpy's default 6
#: (7.06 against 7.07 MB for the main job) in ~0.8 of the time.
NPZ_LEVEL = 1


def save_npz(path, arrays: Mapping[str, np.ndarray], level: int = NPZ_LEVEL) -> None:
    """An NPZ file (``np.load`` reads it): one ``.npy`` entry per array, deflated.

    ``np.savez_compressed`` with a choice of the compression level.

    Parameters
    ----------
    path : str or Path
        The file.
    arrays : mapping
        Name -> array (no object arrays).
    level : int
        zlib level, 1 (fastest) to 9.
    """
    import zipfile

    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED, compresslevel=level) as archive:
        for name, array in arrays.items():
            with archive.open(f"{name}.npy", "w", force_zip64=True) as fh:
                np.lib.format.write_array(fh, np.asanyarray(array), allow_pickle=False)
