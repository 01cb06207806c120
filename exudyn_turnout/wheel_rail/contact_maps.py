"""Contact, adhesion and slip maps printed by CONTACT ("FORM OF THE CONTACT ...").

CONTACT (E.A.H. Vollebregt, github.com/eve70a/CONTACT, Apache-2.0) prints, per contact
patch, a map of its potential contact grid: one character per element, ``*`` adhesion,
``S`` slip, ``.`` exterior, ``o`` the grid's corners; rows are the lateral (s) element
index printed from the largest down, columns the longitudinal (x) index.  Wide maps put a
blank between the characters.  This module reads the maps element by element, so that
the exact rolling solver (``wheel_rail.exact_rolling``) can be run on CONTACT's own
contact area.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

__all__ = ["ContactMap", "read_contact_maps"]

_MAP_ROW = re.compile(r"^\s+(\d+)\s+([.oS*|PE -]+)$")


@dataclass(frozen=True, eq=False)
class ContactMap:
    """One printed map; arrays indexed (x element, s element), s increasing with j."""

    contact: np.ndarray  #: bool, elements in contact (adhesion or slip)
    adhesion: np.ndarray  #: bool, elements in adhesion
    first_row: int  #: -, CONTACT's s index of row j = 0


def read_contact_maps(path: str | Path) -> list[ContactMap]:
    """Every "FORM OF THE CONTACT" map of a CONTACT output, in the file's order.

    Parameters
    ----------
    path : str or Path
        A CONTACT ``.out`` / ``.ref_out`` file.

    Returns
    -------
    list of ContactMap
        One per printed map (per case and patch).
    """
    lines = Path(path).read_text(encoding="utf-8", errors="replace").splitlines()
    maps: list[ContactMap] = []
    for i, line in enumerate(lines):
        if not line.strip().startswith("FORM OF THE CONTACT"):
            continue
        rows: list[str] = []
        numbers: list[int] = []
        j = i + 1
        while j < len(lines) and (match := _MAP_ROW.match(lines[j])):
            body = lines[j].split(None, 1)[1]
            if " . " in body or " * " in body or " S " in body:  # one blank between cells
                body = body[0::2]
            rows.append(body)
            numbers.append(int(match.group(1)))
            j += 1
        if not rows:
            continue
        width = max(len(r) for r in rows)
        cells = np.array([list(r.ljust(width, ".")) for r in rows[::-1]]).T
        maps.append(
            ContactMap(
                contact=np.isin(cells, ["*", "S"]),
                adhesion=cells == "*",
                first_row=min(numbers),
            )
        )
    return maps
