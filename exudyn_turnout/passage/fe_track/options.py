"""Options of the FE track under a passage: the FE mesh and the time integrator's settings."""

from __future__ import annotations

import math
from dataclasses import dataclass

from exudyn_turnout.fe.mesh import FEOptions

__all__ = ["FEPassageOptions"]


@dataclass(frozen=True)
class FEPassageOptions:
    """Discretisation and damping options of the FE track under a passage (the coupling's
    Newton tolerances are :data:`~exudyn_turnout.passage.fe_track.coupling.COUPLING_TOLERANCE`
    and its neighbours)."""

    mesh: FEOptions = FEOptions()  #: FE mesh (element order and length, model-end extensions)
    loss_reference_hz: float = 1000.0  #: Hz, f_ref of the viscous equivalent G / (2 pi f_ref)

    def __post_init__(self):
        if not (math.isfinite(self.loss_reference_hz) and self.loss_reference_hz > 0):
            raise ValueError(
                f"FEPassageOptions.loss_reference_hz must be > 0, got {self.loss_reference_hz!r}"
            )
