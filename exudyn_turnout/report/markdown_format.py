"""Formatting of the report's Markdown and JSON: numbers, tables, figures, verdicts.

The pieces every section of ``report.md`` uses (:mod:`exudyn_turnout.report.markdown`):
:func:`fmt` (a number or "n/a"), :func:`table` (a GitHub table), :func:`figure` (an
embedded PNG), :func:`fe_source` (where an FE result came from), :func:`span` (min-max),
:func:`verdict_text` and :func:`claims_table`; and :func:`to_json` for ``metrics.json``.
"""

from __future__ import annotations

import json
import math
from collections.abc import Iterable, Mapping, Sequence
from typing import Any

import numpy as np

from exudyn_turnout.report.criteria import FAILS, HOLDS, NOT_CHECKED, Claim
from exudyn_turnout.report.metrics_types import FEInfo

__all__ = [
    "fmt",
    "to_json",
    "table",
    "figure",
    "fe_source",
    "span",
    "verdict_text",
    "claims_table",
    "EXCL",
]

#: Suffix of a frequency range without the pinned-pinned bands.
EXCL = " excl. pinned-pinned"


def fmt(value: Any, spec: str = ".3g", scale: float = 1.0, unit: str = "") -> str:
    """``value * scale`` formatted with ``spec`` (and `` unit``); "n/a" for None or NaN.

    Parameters
    ----------
    value : float or None
    spec : str
        Format specification, e.g. ``".3g"``.
    scale : float
        Factor applied before formatting (e.g. 1e-3 for kN).
    unit : str
        Appended after a space when not empty.

    Returns
    -------
    str
    """
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "n/a"
    return f"{value * scale:{spec}}" + (f" {unit}" if unit else "")


def _plain(value: Any) -> Any:
    if isinstance(value, Mapping):
        return {str(k): _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, (np.floating, float)):
        return float(value) if math.isfinite(value) else None
    if isinstance(value, (np.integer, np.bool_)):
        return value.item()
    return value


def to_json(metrics: Mapping[str, Any]) -> str:
    """metrics as strict JSON (NaN and infinities as null, numpy scalars as numbers).

    Parameters
    ----------
    metrics : mapping
        Nested dicts, lists, numbers and text.

    Returns
    -------
    str
        Indented JSON.
    """
    return json.dumps(_plain(metrics), indent=1, allow_nan=False)


def _row(cells: Sequence[str]) -> str:
    """One Markdown table row; a "|" inside a cell (e.g. |H|) is escaped to stay in its cell."""
    return "| " + " | ".join(str(c).replace("|", "\\|") for c in cells) + " |"


def table(header: Sequence[str], rows: Sequence[Sequence[str]]) -> list[str]:
    """A GitHub-flavoured Markdown table and the empty line after it.

    Parameters
    ----------
    header : sequence of str
        Column titles.
    rows : sequence of sequence of str
        Cells ("|" in a cell is escaped).

    Returns
    -------
    list of str
        Lines.
    """
    return [_row(header), "|" + "---|" * len(header)] + [_row(r) for r in rows] + [""]


def verdict_text(verdict: str) -> str:
    """A claim's verdict as the report prints it (bold for holds / does not hold).

    Parameters
    ----------
    verdict : str
        HOLDS, FAILS or NOT_CHECKED.

    Returns
    -------
    str
    """
    return {
        HOLDS: "**holds**",
        FAILS: "**does not hold here**",
        NOT_CHECKED: "not checked",
    }.get(verdict, verdict)


def claims_table(claims: Iterable[Claim], topic: str | None = None) -> list[str]:
    """The table of the claims of ``topic`` (all if None): claim, criterion, FE reference,
    verdict, numbers.

    Parameters
    ----------
    claims : iterable of Claim
    topic : str, optional
        E.g. "receptance".

    Returns
    -------
    list of str
        Lines.
    """
    rows = [
        [c.id, c.statement, c.criterion, c.fe_reference or "-", verdict_text(c.verdict), c.evidence]
        for c in claims
        if topic is None or c.topic == topic
    ]
    return table(["id", "paper's claim", "criterion", "FE reference", "verdict", "numbers"], rows)


def figure(figures: Mapping[str, str], name: str, alt: str) -> list[str]:
    """An embedded figure, or a note that it was not drawn.

    Parameters
    ----------
    figures : mapping
        Figure name -> file name relative to report.md.
    name : str
        The figure's name.
    alt : str
        Its alternative text.

    Returns
    -------
    list of str
        Lines.
    """
    if name not in figures:
        return [f"*(figure {name} not drawn: no data)*", ""]
    return [f"![{alt}]({figures[name]})", ""]


def fe_source(info: FEInfo) -> str:
    """Where an FE result came from: this run or the cache (or why it is missing).

    Parameters
    ----------
    info : FEInfo

    Returns
    -------
    str
    """
    if info.error is not None:
        return f"failed ({info.error})"
    if info.note is not None:
        return f"not available ({info.note})"
    return (
        f"read from the cache (computed {info.computed})" if info.cached else "computed in this run"
    )


def span(values: Iterable[float | None], spec: str = ".1f") -> str:
    """``min-max`` of the finite values, or "n/a" without one.

    Parameters
    ----------
    values : iterable of float or None
    spec : str
        Format of both ends.

    Returns
    -------
    str
    """
    v = [x for x in values if x is not None and math.isfinite(x)]
    return f"{min(v):{spec}}-{max(v):{spec}}" if v else "n/a"
