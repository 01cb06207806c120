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
    #: m, the FE window: the track is stepped from window_length / 2 behind each wheelset to
    #: window_length / 2 ahead of it (None: the whole model). The default is the shortest
    #: length whose peaks at switch and crossing are within 1 % of the whole model's
    #: (validation/fe_window_convergence.md).
    window_length: float | None = 20.0
    window_shift: float = 1.0  #: m, the window is cut anew each time the vehicle moves this far
    window_absorbing_length: float = 4.0  #: m, absorbing zone inside each cut end
    window_eta_max: float = 0.5  #: loss factor added at a cut end (-), grown quadratically
    #: sample every step of the windows run at the check rail's finer step (the output is
    #: then denser there than the run's grid; the full vehicle's body columns stay at the
    #: nearest grid sample), not only the grid's: the FE check-rail force has a spike of
    #: ~50 us at the end of the check rail's entry flare that a 1e-4 s grid misses
    #: (:mod:`~exudyn_turnout.passage.fe_track.common`)
    check_rail_every_step: bool = False

    def __post_init__(self):
        if self.window_length is not None and not (
            math.isfinite(self.window_length)
            and self.window_length >= 2.0 * self.window_absorbing_length + 2.0
        ):
            raise ValueError(
                "FEPassageOptions.window_length must be None or >= 2 window_absorbing_length "
                f"+ 2 m, got {self.window_length!r}"
            )
        for name in ("window_shift", "window_absorbing_length"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value > 0):
                raise ValueError(f"FEPassageOptions.{name} must be > 0, got {value!r}")
        if not (math.isfinite(self.window_eta_max) and self.window_eta_max >= 0):
            raise ValueError(
                f"FEPassageOptions.window_eta_max must be >= 0, got {self.window_eta_max!r}"
            )
        if not (math.isfinite(self.loss_reference_hz) and self.loss_reference_hz > 0):
            raise ValueError(
                f"FEPassageOptions.loss_reference_hz must be > 0, got {self.loss_reference_hz!r}"
            )
