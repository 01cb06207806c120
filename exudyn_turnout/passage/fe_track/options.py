"""Options of the FE track under a passage: the FE mesh and the time integrator's settings."""

from __future__ import annotations

import math
from dataclasses import dataclass

from exudyn_turnout.fe.mesh import FEOptions

__all__ = ["FEPassageOptions"]


@dataclass(frozen=True)
class FEPassageOptions:
    """Discretisation and solver options of the FE passage."""

    mesh: FEOptions = FEOptions()  #: FE mesh (element order and length, model-end extensions)
    loss_reference_hz: float = 1000.0  #: Hz, f_ref of the viscous equivalent G / (2 pi f_ref)
    contact_tolerance: float = (
        1e-2  #: N, Newton residual of the contact forces (2e-7 of a wheel load)
    )
    max_contact_iterations: int = 50  #: Newton iterations per step before giving up

    def __post_init__(self):
        if not (math.isfinite(self.loss_reference_hz) and self.loss_reference_hz > 0):
            raise ValueError(
                f"FEPassageOptions.loss_reference_hz must be > 0, got {self.loss_reference_hz!r}"
            )
        if not self.contact_tolerance > 0 or self.max_contact_iterations < 1:
            raise ValueError(
                "FEPassageOptions.contact_tolerance must be > 0 and max_contact_iterations >= 1"
            )
