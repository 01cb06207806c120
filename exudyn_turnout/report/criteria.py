"""The criteria the paper's claims are judged by, and a claim with its verdict.

:class:`Criteria` (thresholds fixed before any result is computed, printed in the report),
:class:`Claim` (one claim of the paper, our verdict and the numbers behind it), the
verdicts :data:`HOLDS`, :data:`FAILS`, :data:`NOT_CHECKED`, and the frequency ranges of the
receptance comparison :data:`RANGES`. The claims themselves are evaluated by
:mod:`exudyn_turnout.report.claims`.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from exudyn_turnout.report.record import Record, optional

__all__ = ["Criteria", "Claim", "HOLDS", "FAILS", "NOT_CHECKED", "RANGES"]

HOLDS, FAILS, NOT_CHECKED = "holds", "does not hold here", "not checked"

#: Hz, the frequency ranges of the receptance comparison (nominal one-third-octave centres).
RANGES: tuple[tuple[float, float], ...] = ((1.0, 125.0), (125.0, 500.0), (500.0, 2000.0))


@dataclass(frozen=True)
class Criteria:
    """Thresholds that turn metrics into verdicts (stated in the report before the results)."""

    agree_db: float = (
        3.0  #: dB; a model "agrees" with FE in a range if its band RMS is at most this
    )
    pinned_pinned_neighbours: int = 1  #: bands either side of the pinned-pinned band also left out
    peak_prominence_db: float = 1.0  #: dB; minimum prominence of a receptance "main peak"
    peak_agree: float = (
        0.10  #: -; peak forces "agree" if they differ from FE by at most this fraction
    )
    overestimate: float = 0.05  #: -; a peak "overestimates" FE if it exceeds it by more than this
    #: -; the lateral crossing peak "overestimates" FE if its magnitude exceeds FE's by more
    #: than this: the same 5 % as the vertical one, because the paper makes one statement for
    #: both figures ("overestimates the peak impact forces at the crossing panel despite a lower
    #: vehicle speed", Sec. 4.2: the lower speed is the diverging route of Fig. 8, lateral)
    overestimate_lateral: float = 0.05
    trend_window: float = 1.0  #: m; running-mean window that defines a force's "overall trend"
    trend_agree: float = 0.10  #: -; trends agree if they differ by at most this x static wheel load
    cost_ratio: tuple[float, float] = (
        1.0,
        1.2,
    )  #: -; "about 10 % more": 3-layer / 2-layer in this range
    fe_slower: float = 10.0  #: -; "far more expensive": FE / 3-layer wall time at least this
    converged: float = 0.01  #: -; peak change when the time step is halved at most this
    static_tolerance: float = 0.005  #: -; static wheel load within this of (m_w + m_s) g / 2
    stock_uniform: float = (
        0.10  #: -; "remains the same": stock-rail K_z within this of its plain-track value
    )
    much_higher: float = 1.2  #: -; "much higher" stiffness: ratio at least this
    lateral_increase: tuple[float, float] = (
        1.15,
        1.35,
    )  #: -; "around 25 %": K_y end / start in this range


@dataclass(frozen=True)
class Claim(Record):
    """One claim of the paper with our verdict (a record: ``metrics.json``'s ``claims``)."""

    id: str  #: short id, e.g. "R1"
    topic: str  #: "track stiffness", "receptance", "contact forces" or "computing cost"
    statement: str  #: the paper's claim, paraphrased, with its section
    criterion: str  #: how we judge it
    verdict: str  #: HOLDS, FAILS or NOT_CHECKED
    evidence: str  #: the numbers behind the verdict, one line
    values: Mapping[str, Any] = field(default_factory=dict)  #: those numbers, for metrics.json
    #: which FE reference the verdict is formed against (``claims.FE_REFERENCES``); absent
    #: in reports written before it was stated
    fe_reference: str | None = optional()
